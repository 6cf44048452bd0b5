/* bench_friction.c: time the rotor with stiction (docs/device.md section 3, EXACT law: stick-slip
 * switching at events of the transient engine, reset by autobal_rotor_friction_settle) against
 * the same rotor without friction (issue 16, "Speed").  Companion of bench/friction_scipy.py.
 * Only public functions: the event wiring of src/studies/rotor_friction.c is replicated here
 * (one event per ball, autobal_rotor_friction_switch; a reset that calls
 * autobal_rotor_friction_settle).
 *
 * Problem: the default rotor (docs/rotor.md, two balls of 0.05 kg, the unbalance 0.02 kg at
 * 0.1 m), the prescribed RAMP drive Omega = OMEGA_A + (OMEGA_B - OMEGA_A) t / T_B on [0, T_B]
 * (OMEGA_B after), the rotor at rest at the origin, the balls at rest relative to the rotor at
 * psi = 1.0, 2.5 (SEED 0) or at psi uniform in [-pi, pi) (SEED > 0, a 64-bit LCG); fixed frame;
 * final state only.  LAW: none (frictionless, autobal_rotor_rhs of 0.2.0) or exact (F, MU per
 * ball).
 *
 *   bench_friction run LAW F MU RTOL ATOL T1 REPEATS OMEGA_A OMEGA_B T_B SEED [EVENT_TOL [H_INIT]]
 *       One member, REPEATS times (EVENT_TOL: the driver's event_tol in s, 0 or absent: the
 *       driver's default 1e-10; the tight references use a smaller one.  H_INIT: the first
 *       trial step in s, 0 or absent: automatic; with friction and rtol >= 1e-8 the automatic
 *       first step of this problem reaches a stage state with N < 0 and the run fails, 1e-4 s
 *       avoids it); JSON: best process CPU time, best wall time, the driver's
 *       statistics (steps, rhs evaluations, events, resets), the switches (sticks, slips,
 *       reversals; the initial settling not counted), the final modes and state.
 *   bench_friction ensemble LAW F MU RTOL ATOL T1 MEMBERS THREADS OMEGA_A OMEGA_B T_B
 *       MEMBERS members (SEED = 1 .. MEMBERS) on THREADS POSIX threads (members dealt out by
 *       an atomic counter; each member allocates its own rotor and driver); JSON: wall time,
 *       process CPU time, members per second, switches summed, members that failed.
 *   bench_friction check F MU OMEGA_A OMEGA_B T_B
 *       States for friction_scipy.py to check its independent right-hand side: t, y, the modes
 *       (-1, 0, 1), autobal_rotor_rhs (EXACT law) and the normal and holding forces.
 *
 * Options before the mode (bench/run.sh contact, friction_scipy.py --contact):
 *   --contact D E   ball contact (docs/device.md section 4, "Stiction and contact"): both balls of
 *       diameter D (m), restitution E, v_rest the default 1e-3 rad/s; one event per pair
 *       (autobal_rotor_contact_switch, direction -1) after the ball events, and the reset calls
 *       autobal_rotor_hybrid_settle for every event (hybrid_reset of src/studies/rotor_friction.c);
 *       the start: autobal_rotor_friction_settle (initial), autobal_rotor_contact_order,
 *       autobal_rotor_hybrid_settle (initial).  JSON gains impacts, joins, releases, contacts_final
 *       (pairs in resting contact at the end); the ensemble also members_with_impacts,
 *       members_with_joins, min_impacts, max_impacts.  Random angles (SEED > 0): the second angle
 *       is redrawn from the same LCG stream until the two balls are at least the gap angle
 *       2 asin(D / (2 r)) + 1e-3 rad apart (no overlap, not touching).  check gains the event reset
 *       at 6 states where the balls touch and close (every mode pattern, both pairs): y, modes
 *       before, y, modes and counts after autobal_rotor_hybrid_settle.
 *   --psi-gap D     only the redrawing of the random angles (no contact): the frictionless ensemble
 *       starts from the same angles as the contact ensemble.
 * run also prints y0 (the initial state, before any settle).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "autobal/rotor.h"
#include "autobal/transient.h"

#define PI 3.14159265358979323846

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double urand(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return 2.0 * ((double)(*s >> 11) * (1.0 / 9007199254740992.0)) - 1.0;
}

typedef struct problem {
  int law;
  double f, mu, rtol, atol, t1, omega_a, omega_b, t_b;
  double event_tol; /* 0: the driver's default */
  double h_init;    /* 0: automatic */
  double psi_gap_d; /* m, > 0: random angles redrawn until the balls of this diameter do not touch */
  double diameter;  /* m, > 0: ball contact on (both balls this diameter) */
  double restitution;
} problem;

/* Leading options (before the mode), shared by every mode; argv shifted past them. */
static double opt_diameter = 0.0, opt_restitution = 0.0, opt_psi_gap = 0.0;

/* The rotor of member `seed` (0: the default angles). */
static autobal_rotor *make_rotor(const problem *pb, unsigned long long seed, char *msg, size_t nmsg) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_error err;
  autobal_rotor *r;
  double psi[2], fs[2] = {pb->f, pb->f}, mus[2] = {pb->mu, pb->mu}, dia[2] = {pb->diameter, pb->diameter};
  memset(&p.drive, 0, sizeof p.drive);
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
  p.drive.omega_a = pb->omega_a;
  p.drive.omega_b = pb->omega_b;
  p.drive.t_a = 0.0;
  p.drive.t_b = pb->t_b;
  if (seed != 0) {
    unsigned long long s = seed * 0x9E3779B97F4A7C15ULL;
    (void)urand(&s);
    psi[0] = PI * urand(&s);
    psi[1] = PI * urand(&s);
    if (pb->psi_gap_d > 0.0) {
      /* with contact the balls must not overlap: the second angle is redrawn (same LCG stream)
       * until the angular distance exceeds the gap angle 2 asin(d / (2 r)) by 1e-3 rad */
      const double gam = autobal_rotor_gap_angle(pb->psi_gap_d, pb->psi_gap_d, p.plane[0].ball_radius[0]);
      for (;;) {
        double dd = fmod(fabs(psi[1] - psi[0]), 2.0 * PI);
        if (dd > PI) dd = 2.0 * PI - dd;
        if (dd >= gam + 1e-3) break;
        psi[1] = PI * urand(&s);
      }
    }
    p.plane[0].ball_psi = psi;
  }
  if (pb->diameter > 0.0) {
    p.contact.on = 1;
    p.contact.restitution = pb->restitution;
    p.contact.ball_diameter[0] = dia;
  }
  if (pb->law == AUTOBAL_ROTOR_FRICTION_EXACT) {
    p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
    p.friction.ball_f[0] = fs;
    p.friction.ball_mu[0] = mus;
  }
  r = autobal_rotor_alloc(&p, &err);
  if (r == NULL) snprintf(msg, nmsg, "%s", err.message);
  return r;
}

/* The event wiring of src/studies/rotor_friction.c with public functions. */
typedef struct member {
  autobal_rotor *rot;
  int contact;
  unsigned long sticks, slips, reversals, impacts, joins, releases;
  int failed;
} member;

typedef struct ball_ev {
  member *m;
  size_t k;
} ball_ev;

static double ball_switch(double t, const double y[], void *user) {
  const ball_ev *e = (const ball_ev *)user;
  return autobal_rotor_friction_switch(e->m->rot, AUTOBAL_ROTOR_FIXED, e->k, t, y);
}

static double pair_switch(double t, const double y[], void *user) {
  const ball_ev *e = (const ball_ev *)user;
  return autobal_rotor_contact_switch(e->m->rot, AUTOBAL_ROTOR_FIXED, e->k, t, y);
}

/* Stiction alone: autobal_rotor_friction_settle; with contact (hybrid_reset of
 * src/studies/rotor_friction.c): autobal_rotor_hybrid_settle for every event. */
static int ball_reset(const autobal_transient_event_hit *hit, double y[], void *user) {
  member *m = (member *)user;
  int rc;
  if (m->contact) {
    size_t n[6] = {0, 0, 0, 0, 0, 0};
    rc = autobal_rotor_hybrid_settle(m->rot, AUTOBAL_ROTOR_FIXED, hit->t, y, 0, n);
    if (rc < 0) {
      m->failed = rc;
      return 2;
    }
    m->sticks += n[0];
    m->slips += n[1];
    m->reversals += n[2];
    m->impacts += n[3];
    m->joins += n[4];
    m->releases += n[5];
  } else {
    size_t ns, nl, nr;
    rc = autobal_rotor_friction_settle(m->rot, AUTOBAL_ROTOR_FIXED, hit->t, y, 0, &ns, &nl, &nr);
    if (rc < 0) {
      m->failed = rc;
      return 2;
    }
    m->sticks += ns;
    m->slips += nl;
    m->reversals += nr;
  }
  return rc == 1 ? AUTOBAL_TRANSIENT_RESET : 0;
}

typedef struct result {
  double cpu, wall;
  autobal_transient_stats st;
  unsigned long sticks, slips, reversals, impacts, joins, releases, contacts_final;
  int modes[2];
  double y[16], y0[16];
  size_t dim;
} result;

/* One member from t = 0 to t1; 0 on success (msg on failure).  The driver tr is allocated
 * here (one per member, as an ensemble member would). */
static int run_member(const problem *pb, unsigned long long seed, result *res, char *msg, size_t nmsg) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient *tr;
  autobal_error err;
  member m;
  ball_ev ev[2], pev[4];
  double y[16], c0, w0;
  size_t dim, k, np = 0;
  int rc;
  memset(&m, 0, sizeof m);
  memset(res, 0, sizeof *res);
  o.rtol = pb->rtol;
  o.atol = pb->atol;
  o.stepper = "rk8pd";
  if (pb->event_tol > 0.0) o.event_tol = pb->event_tol;
  if (pb->h_init > 0.0) o.h_init = pb->h_init;
  c0 = cpu_seconds();
  w0 = now_seconds();
  m.rot = make_rotor(pb, seed, msg, nmsg);
  if (m.rot == NULL) return 1;
  m.contact = autobal_rotor_contact_on(m.rot);
  dim = autobal_rotor_dim(m.rot);
  if (dim > 16) return 1;
  tr = autobal_transient_alloc(dim, &o, &err);
  if (tr == NULL) {
    snprintf(msg, nmsg, "%s", err.message);
    autobal_rotor_free(m.rot);
    return 1;
  }
  sys.rhs = autobal_rotor_rhs;
  sys.jac = NULL;
  sys.dim = dim;
  sys.params = m.rot;
  if (autobal_rotor_initial_state(m.rot, AUTOBAL_ROTOR_FIXED, 0.0, y, dim) != AUTOBAL_SUCCESS) return 1;
  memcpy(res->y0, y, dim * sizeof(double));
  if (pb->law == AUTOBAL_ROTOR_FRICTION_EXACT) {
    if (autobal_rotor_friction_settle(m.rot, AUTOBAL_ROTOR_FIXED, 0.0, y, 1, NULL, NULL, NULL) < 0) {
      snprintf(msg, nmsg, "member %llu: initial settle: %s", seed, autobal_rotor_errmsg(m.rot));
      return 1;
    }
    for (k = 0; k < 2; k++) {
      ev[k].m = &m;
      ev[k].k = k;
      if (autobal_transient_add_event(tr, ball_switch, &ev[k], 0, 0) < 0) return 1;
    }
  }
  if (m.contact) { /* study_contact_begin: the pairs from the state, the start settled with them */
    size_t n[6] = {0, 0, 0, 0, 0, 0};
    if (autobal_rotor_contact_order(m.rot, AUTOBAL_ROTOR_FIXED, 0.0, y) != AUTOBAL_SUCCESS ||
        autobal_rotor_hybrid_settle(m.rot, AUTOBAL_ROTOR_FIXED, 0.0, y, 1, n) < 0) {
      snprintf(msg, nmsg, "member %llu: initial contact settle: %s", seed, autobal_rotor_errmsg(m.rot));
      return 1;
    }
    m.impacts += n[3];
    m.joins += n[4];
    m.releases += n[5];
    np = autobal_rotor_contact_n_pairs(m.rot);
    if (np > 4) return 1;
    for (k = 0; k < np; k++) {
      pev[k].m = &m;
      pev[k].k = k;
      if (autobal_transient_add_event(tr, pair_switch, &pev[k], -1, 0) < 0) return 1;
    }
  }
  if (pb->law == AUTOBAL_ROTOR_FRICTION_EXACT || m.contact) autobal_transient_set_event_reset(tr, ball_reset, &m);
  rc = autobal_transient_run(tr, &sys, 0.0, pb->t1, y, NULL);
  autobal_transient_get_stats(tr, &res->st);
  res->cpu = cpu_seconds() - c0;
  res->wall = now_seconds() - w0;
  if (rc != AUTOBAL_SUCCESS || m.failed) {
    snprintf(msg, nmsg, "member %llu: %s / %s", seed, autobal_transient_errmsg(tr),
             autobal_rotor_errmsg(m.rot));
    autobal_transient_free(tr);
    autobal_rotor_free(m.rot);
    return 1;
  }
  res->sticks = m.sticks;
  res->slips = m.slips;
  res->reversals = m.reversals;
  res->impacts = m.impacts;
  res->joins = m.joins;
  res->releases = m.releases;
  res->contacts_final = m.contact ? (unsigned long)autobal_rotor_contact_n_active(m.rot) : 0;
  for (k = 0; k < 2; k++) res->modes[k] = autobal_rotor_ball_mode_get(m.rot, k);
  if (pb->law != AUTOBAL_ROTOR_FRICTION_EXACT) res->modes[0] = res->modes[1] = 9;
  memcpy(res->y, y, dim * sizeof(double));
  res->dim = dim;
  autobal_transient_free(tr);
  autobal_rotor_free(m.rot);
  return 0;
}

static int parse_problem(char **a, problem *pb) {
  if (strcmp(a[0], "none") == 0) pb->law = AUTOBAL_ROTOR_FRICTION_NONE;
  else if (strcmp(a[0], "exact") == 0) pb->law = AUTOBAL_ROTOR_FRICTION_EXACT;
  else return 2;
  pb->f = atof(a[1]);
  pb->mu = atof(a[2]);
  pb->rtol = atof(a[3]);
  pb->atol = atof(a[4]);
  pb->t1 = atof(a[5]);
  pb->diameter = opt_diameter;
  pb->restitution = opt_restitution;
  pb->psi_gap_d = opt_diameter > 0.0 ? opt_diameter : opt_psi_gap;
  return 0;
}

static int mode_run(int argc, char **argv) {
  problem pb;
  result res, best;
  char msg[512];
  int repeats, r;
  unsigned long long seed;
  size_t i;
  if (argc < 13 || argc > 15 || parse_problem(argv + 2, &pb) != 0) return 2;
  pb.event_tol = argc >= 14 ? atof(argv[13]) : 0.0;
  pb.h_init = argc == 15 ? atof(argv[14]) : 0.0;
  repeats = atoi(argv[8]);
  pb.omega_a = atof(argv[9]);
  pb.omega_b = atof(argv[10]);
  pb.t_b = atof(argv[11]);
  seed = strtoull(argv[12], NULL, 10);
  if (repeats < 1) repeats = 1;
  memset(&best, 0, sizeof best);
  for (r = 0; r < repeats; r++) {
    if (run_member(&pb, seed, &res, msg, sizeof msg) != 0) {
      fprintf(stderr, "bench_friction: %s\n", msg);
      return 1;
    }
    if (r == 0 || res.cpu < best.cpu) {
      const double w = r == 0 ? res.wall : (res.wall < best.wall ? res.wall : best.wall);
      best = res;
      best.wall = w;
    } else if (res.wall < best.wall) {
      best.wall = res.wall;
    }
  }
  printf("{\"law\": \"%s\", \"f\": %.6g, \"mu\": %.6g, \"rtol\": %.3g, \"atol\": %.3g, \"t1\": %.17g, "
         "\"seed\": %llu, \"event_tol\": %.3g, \"h_init\": %.3g, \"repeats\": %d, \"cpu_seconds_min\": %.9g, \"seconds_min\": %.9g, "
         "\"steps\": %lu, \"rejected\": %lu, \"rhs_evals\": %lu, \"events\": %lu, \"event_steps\": %lu, "
         "\"resets\": %lu, \"sticks\": %lu, \"slips\": %lu, \"reversals\": %lu, \"modes\": [%d, %d], "
         "\"diameter\": %.6g, \"restitution\": %.6g, \"impacts\": %lu, \"joins\": %lu, \"releases\": %lu, "
         "\"contacts_final\": %lu, \"y\": [",
         argv[2], pb.f, pb.mu, pb.rtol, pb.atol, pb.t1, seed, pb.event_tol, pb.h_init, repeats, best.cpu, best.wall,
         best.st.steps, best.st.rejected, best.st.rhs_evals, best.st.events, best.st.event_steps,
         best.st.resets, best.sticks, best.slips, best.reversals, best.modes[0], best.modes[1],
         pb.diameter, pb.restitution, best.impacts, best.joins, best.releases, best.contacts_final);
  for (i = 0; i < best.dim; i++) printf("%.17g%s", best.y[i], i + 1 < best.dim ? ", " : "], \"y0\": [");
  for (i = 0; i < best.dim; i++) printf("%.17g%s", best.y0[i], i + 1 < best.dim ? ", " : "]}\n");
  return 0;
}

typedef struct pool {
  const problem *pb;
  unsigned long members;
  unsigned long next;
  pthread_mutex_t lock;
  unsigned long done, failed, sticks, slips, reversals, steps, rhs_evals, resets, stuck_final;
  unsigned long impacts, joins, releases, contacts_final, with_impacts, with_joins, min_impacts, max_impacts;
  char msg[512];
} pool;

static void *worker(void *arg) {
  pool *p = (pool *)arg;
  for (;;) {
    result res;
    char msg[512];
    unsigned long i;
    int rc;
    pthread_mutex_lock(&p->lock);
    i = p->next++;
    pthread_mutex_unlock(&p->lock);
    if (i >= p->members) break;
    rc = run_member(p->pb, (unsigned long long)i + 1u, &res, msg, sizeof msg);
    pthread_mutex_lock(&p->lock);
    if (rc != 0) {
      p->failed++;
      snprintf(p->msg, sizeof p->msg, "%s", msg);
    } else {
      p->done++;
      p->sticks += res.sticks;
      p->slips += res.slips;
      p->reversals += res.reversals;
      p->steps += res.st.steps;
      p->rhs_evals += res.st.rhs_evals;
      p->resets += res.st.resets;
      p->stuck_final += (unsigned long)(res.modes[0] == 0) + (unsigned long)(res.modes[1] == 0);
      p->impacts += res.impacts;
      p->joins += res.joins;
      p->releases += res.releases;
      p->contacts_final += res.contacts_final;
      p->with_impacts += (unsigned long)(res.impacts > 0);
      p->with_joins += (unsigned long)(res.joins > 0);
      if (p->done == 1 || res.impacts < p->min_impacts) p->min_impacts = res.impacts;
      if (res.impacts > p->max_impacts) p->max_impacts = res.impacts;
    }
    pthread_mutex_unlock(&p->lock);
  }
  return NULL;
}

static int mode_ensemble(int argc, char **argv) {
  problem pb;
  pool p;
  pthread_t th[64];
  int nth, i;
  double w0, c0, wall, cpu;
  if (argc != 13 || parse_problem(argv + 2, &pb) != 0) return 2;
  pb.event_tol = 0.0;
  pb.h_init = 0.0;
  memset(&p, 0, sizeof p);
  p.members = strtoul(argv[8], NULL, 10);
  nth = atoi(argv[9]);
  pb.omega_a = atof(argv[10]);
  pb.omega_b = atof(argv[11]);
  pb.t_b = atof(argv[12]);
  if (nth < 1 || nth > 64 || p.members < 1) return 2;
  p.pb = &pb;
  pthread_mutex_init(&p.lock, NULL);
  w0 = now_seconds();
  c0 = cpu_seconds();
  for (i = 0; i < nth; i++)
    if (pthread_create(&th[i], NULL, worker, &p) != 0) return 1;
  for (i = 0; i < nth; i++) pthread_join(th[i], NULL);
  wall = now_seconds() - w0;
  cpu = cpu_seconds() - c0;
  pthread_mutex_destroy(&p.lock);
  printf("{\"law\": \"%s\", \"f\": %.6g, \"mu\": %.6g, \"rtol\": %.3g, \"atol\": %.3g, \"t1\": %.17g, "
         "\"members\": %lu, \"threads\": %d, \"done\": %lu, \"failed\": %lu, \"wall_seconds\": %.6g, "
         "\"cpu_seconds\": %.6g, \"members_per_second\": %.6g, \"members_per_cpu_second\": %.6g, "
         "\"steps\": %lu, \"rhs_evals\": %lu, \"resets\": %lu, \"sticks\": %lu, \"slips\": %lu, "
         "\"reversals\": %lu, \"balls_stuck_final\": %lu, \"diameter\": %.6g, \"restitution\": %.6g, "
         "\"impacts\": %lu, \"joins\": %lu, \"releases\": %lu, \"contacts_final\": %lu, "
         "\"members_with_impacts\": %lu, \"members_with_joins\": %lu, \"min_impacts\": %lu, "
         "\"max_impacts\": %lu, \"message\": \"%s\"}\n",
         argv[2], pb.f, pb.mu, pb.rtol, pb.atol, pb.t1, p.members, nth, p.done, p.failed, wall, cpu,
         (double)p.done / wall, (double)p.done / cpu, p.steps, p.rhs_evals, p.resets, p.sticks, p.slips,
         p.reversals, p.stuck_final, pb.diameter, pb.restitution, p.impacts, p.joins, p.releases,
         p.contacts_final, p.with_impacts, p.with_joins, p.min_impacts, p.max_impacts, p.failed ? p.msg : "");
  return p.failed ? 1 : 0;
}

/* With contact: the event reset at states where the two balls touch (gap 0) and close, for
 * friction_scipy.py's impact law: t, the modes and y before, autobal_rotor_hybrid_settle's y, modes
 * and counts after.  ahead: 1 (ball 1 ahead of ball 0 by the gap angle) or 0 (ball 0 ahead). */
static int check_impacts(autobal_rotor *rot, const problem *pb, unsigned long long *seed) {
  static const int pat[6][2] = {{1, -1}, {0, -1}, {1, 0}, {-1, -1}, {-1, 1}, {0, 1}};
  static const double rate[6][2] = {{3, -2}, {0, -5}, {4, 0}, {-1, -6}, {-2, 3}, {0, 4}};
  static const int ahead[6] = {1, 1, 1, 1, 0, 0};
  const double gam = autobal_rotor_gap_angle(pb->diameter, pb->diameter, 0.1);
  double y[12], y0[12], w[3];
  size_t i, k, n[6];
  int s, rc;
  printf(", \"gap_angle\": %.17g, \"restitution\": %.17g, \"impacts\": [", gam, pb->restitution);
  for (s = 0; s < 6; s++) {
    const double t = 0.14 * pb->t_b * (double)(s + 1) + 0.0077;
    if (autobal_rotor_drive_eval(rot, t, w) != AUTOBAL_SUCCESS) return 1;
    y[0] = 2e-4 * urand(seed);
    y[1] = 2e-4 * urand(seed);
    y[2] = 1e-3 * urand(seed);
    y[3] = 1e-3 * urand(seed);
    y[4] = 0.1 * urand(seed);
    y[5] = 0.1 * urand(seed);
    y[6] = 0.5 * urand(seed);
    y[7] = 0.5 * urand(seed);
    y[8 + (size_t)(1 - ahead[s])] = w[2] + PI * urand(seed);
    y[8 + (size_t)ahead[s]] = y[8 + (size_t)(1 - ahead[s])] + gam;
    for (k = 0; k < 2; k++) y[10 + k] = w[0] + rate[s][k];
    memcpy(y0, y, sizeof y);
    if (autobal_rotor_contact_order(rot, AUTOBAL_ROTOR_FIXED, t, y) != AUTOBAL_SUCCESS) {
      fprintf(stderr, "bench_friction: %s\n", autobal_rotor_errmsg(rot));
      return 1;
    }
    for (k = 0; k < 2; k++)
      if (autobal_rotor_ball_mode_set(rot, k, pat[s][k]) != AUTOBAL_SUCCESS) return 1;
    memset(n, 0, sizeof n);
    rc = autobal_rotor_hybrid_settle(rot, AUTOBAL_ROTOR_FIXED, t, y, 0, n);
    if (rc < 0) {
      fprintf(stderr, "bench_friction: %s\n", autobal_rotor_errmsg(rot));
      return 1;
    }
    printf("%s{\"t\": %.17g, \"ahead\": %d, \"modes\": [%d, %d], \"y\": [", s ? ", " : "", t, ahead[s],
           pat[s][0], pat[s][1]);
    for (i = 0; i < 12; i++) printf("%.17g%s", y0[i], i + 1 < 12 ? ", " : "], \"y_after\": [");
    for (i = 0; i < 12; i++) printf("%.17g%s", y[i], i + 1 < 12 ? ", " : "], ");
    printf("\"modes_after\": [%d, %d], \"counts\": [%zu, %zu, %zu, %zu, %zu, %zu]}",
           autobal_rotor_ball_mode_get(rot, 0), autobal_rotor_ball_mode_get(rot, 1), n[0], n[1], n[2], n[3],
           n[4], n[5]);
  }
  printf("]");
  return 0;
}

/* States for the SciPy check: random states at t = 0.2 k T_B (k = 1..4), every mode pattern. */
static int mode_check(int argc, char **argv) {
  problem pb;
  autobal_rotor *rot;
  char msg[512];
  unsigned long long seed = 4242u;
  double y[12], dydt[12], N[2], H[2], w[3];
  size_t i, k;
  int s, first = 1;
  static const int pat[6][2] = {{1, 1}, {-1, 1}, {1, -1}, {0, 1}, {-1, 0}, {0, 0}};
  if (argc != 7) return 2;
  memset(&pb, 0, sizeof pb);
  pb.law = AUTOBAL_ROTOR_FRICTION_EXACT;
  pb.f = atof(argv[2]);
  pb.mu = atof(argv[3]);
  pb.omega_a = atof(argv[4]);
  pb.omega_b = atof(argv[5]);
  pb.t_b = atof(argv[6]);
  pb.diameter = opt_diameter;
  pb.restitution = opt_restitution;
  rot = make_rotor(&pb, 0, msg, sizeof msg);
  if (rot == NULL || autobal_rotor_dim(rot) != 12) return 1;
  printf("{\"states\": [");
  for (s = 0; s < 6; s++) {
    const double t = 0.15 * pb.t_b * (double)(s + 1) - 0.0123;
    if (autobal_rotor_drive_eval(rot, t, w) != AUTOBAL_SUCCESS) return 1;
    y[0] = 2e-4 * urand(&seed);
    y[1] = 2e-4 * urand(&seed);
    y[2] = 1e-3 * urand(&seed);
    y[3] = 1e-3 * urand(&seed);
    y[4] = 0.1 * urand(&seed);
    y[5] = 0.1 * urand(&seed);
    y[6] = 0.5 * urand(&seed);
    y[7] = 0.5 * urand(&seed);
    for (k = 0; k < 2; k++) {
      y[8 + k] = w[2] + PI * urand(&seed);
      y[10 + k] = pat[s][k] == 0 ? w[0] : w[0] + (double)pat[s][k] * (1.0 + 20.0 * fabs(urand(&seed)));
      if (autobal_rotor_ball_mode_set(rot, k, pat[s][k]) != AUTOBAL_SUCCESS) return 1;
    }
    if (autobal_rotor_rhs(t, y, dydt, rot) != 0 ||
        autobal_rotor_normal_forces(rot, AUTOBAL_ROTOR_FIXED, t, y, N, 2) != AUTOBAL_SUCCESS ||
        autobal_rotor_holding_forces(rot, AUTOBAL_ROTOR_FIXED, t, y, H, 2) != AUTOBAL_SUCCESS) {
      fprintf(stderr, "bench_friction: %s\n", autobal_rotor_errmsg(rot));
      return 1;
    }
    printf("%s{\"t\": %.17g, \"modes\": [%d, %d], \"y\": [", first ? "" : ", ", t, pat[s][0], pat[s][1]);
    first = 0;
    for (i = 0; i < 12; i++) printf("%.17g%s", y[i], i + 1 < 12 ? ", " : "], \"dydt\": [");
    for (i = 0; i < 12; i++) printf("%.17g%s", dydt[i], i + 1 < 12 ? ", " : "], \"N\": [");
    printf("%.17g, %.17g], \"H\": [", N[0], N[1]);
    for (k = 0; k < 2; k++) {
      if (isnan(H[k])) printf("null");
      else printf("%.17g", H[k]);
      printf("%s", k ? "]}" : ", ");
    }
  }
  printf("]");
  if (opt_diameter > 0.0 && check_impacts(rot, &pb, &seed) != 0) return 1;
  printf("}\n");
  autobal_rotor_free(rot);
  return 0;
}

int main(int argc, char **argv) {
  int rc = 2;
  gsl_set_error_handler_off();
  while (argc >= 2 && argv[1][0] == '-' && argv[1][1] == '-') {
    if (strcmp(argv[1], "--contact") == 0 && argc >= 4) {
      opt_diameter = atof(argv[2]);
      opt_restitution = atof(argv[3]);
      argv[3] = argv[0];
      argv += 3;
      argc -= 3;
    } else if (strcmp(argv[1], "--psi-gap") == 0 && argc >= 3) {
      opt_psi_gap = atof(argv[2]);
      argv[2] = argv[0];
      argv += 2;
      argc -= 2;
    } else {
      argc = 0;
      break;
    }
  }
  if (argc >= 2 && strcmp(argv[1], "run") == 0) rc = mode_run(argc, argv);
  else if (argc >= 2 && strcmp(argv[1], "ensemble") == 0) rc = mode_ensemble(argc, argv);
  else if (argc >= 2 && strcmp(argv[1], "check") == 0) rc = mode_check(argc, argv);
  if (rc == 2)
    fprintf(stderr,
            "usage: %s run none|exact F MU RTOL ATOL T1 REPEATS OMEGA_A OMEGA_B T_B SEED [EVENT_TOL [H_INIT]]\n"
            "       %s ensemble none|exact F MU RTOL ATOL T1 MEMBERS THREADS OMEGA_A OMEGA_B T_B\n"
            "       %s check F MU OMEGA_A OMEGA_B T_B\n"
            "options before the mode: --contact DIAMETER RESTITUTION (ball contact, both balls; random angles\n"
            "       respect the gap angle), --psi-gap DIAMETER (only the random angles of contact)\n",
            argv[0], argv[0], argv[0]);
  return rc;
}
