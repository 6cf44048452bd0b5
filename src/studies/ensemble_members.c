/* ensemble_members.c: the ready-made ensemble members (include/autobal/ensemble.h): the rotor
 * with ball autobalancers and the two-pendulum model, as autobal_ensemble_member callback
 * tables.  What a member's parameter values change, its initial state, its residual unbalance,
 * amplitude, final angles and series columns. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/attractor.h"
#include "autobal/ensemble.h"
#include "autobal/rotor_stability.h"
#include "autobal/study.h"
#include "internal.h"
#include "studies/rotor_friction.h"

#define TWO_PI 6.283185307179586476925286766559
#define PEND_NCOLS 15

void autobal_ensemble_member_release(autobal_ensemble_member *member) {
  if (!member) return;
  if (member->destroy && member->model) member->destroy(member->model);
  memset(member, 0, sizeof *member);
}

static uint64_t hash_doubles(uint64_t h, const double *v, size_t n) {
  size_t i;
  int b;
  for (i = 0; i < n; i++) {
    uint64_t u;
    double x = v[i];
    memcpy(&u, &x, sizeof u);
    for (b = 0; b < 8; b++) {
      h ^= (unsigned char)(u >> (8 * b));
      h *= UINT64_C(0x100000001B3);
    }
  }
  return h;
}

/* ================================ rotor ================================================ */
enum { R_PSI, R_RATE, R_OMEGA, R_DAMPING, R_M0, R_X, R_Y, R_RAMP_RATE, R_RAMP_TIME, R_OMEGA_B, R_PSI0, R_BALL_F, R_BALL_MU };

#define ROTOR_MAX_QUANTITIES 7

typedef struct rotor_model {
  autobal_rotor_params p; /* ball arrays point into storage, a table drive's points into table */
  double *storage, *table;
  int frame;
  char frame_name[32];
  size_t n_balls, dim, nout;
  autobal_rotor *rot; /* the base handle: output names */
  /* the quantities of this model: the two of every rotor, the exact law's three, contact's two */
  autobal_ensemble_quantity quantity[ROTOR_MAX_QUANTITIES];
  size_t n_quantities, q_friction, q_contact; /* index of the first friction / contact quantity (0: none) */
} rotor_model;

typedef struct rotor_worker {
  const rotor_model *M;
  size_t np;
  int kind[AUTOBAL_ENSEMBLE_MAX_PARAMS];
  size_t index[AUTOBAL_ENSEMBLE_MAX_PARAMS];
  double *bpsi, *brate, *bdamp, *bf, *bmu, *out;
  autobal_rotor *rot; /* the current member's handle */
  double omega;
  /* the exact friction law: the member's stick-slip switching (events and reset on the worker's
   * driver, user data here) and what it found at the end */
  study_friction *fric;
  double balls_stuck_final, time_stuck_max, switches;
  /* contact: the member's impact events and the combined reset (the pairs ordered from its own
   * initial angles), and what it found at the end */
  study_contact *cont;
  double contact_impacts, contacts_final;
  /* the attractor classification: the member's parameters (pointers into this worker's arrays),
   * each ball's plane and first moment m r, and the final window's angles, residuals, amplitudes */
  autobal_rotor_params pm;
  size_t *cplane;
  double *cmom, *cpsi, *cres, *camp;
  size_t ccap;
} rotor_worker;

static int rotor_parse(const rotor_model *M, const char *name, int *kind, size_t *index, autobal_ensemble_param_info *info,
                       autobal_error *err) {
  autobal_ensemble_param_info dummy;
  if (!info) info = &dummy;
  memset(info, 0, sizeof *info);
  *index = 0;
  if (!strncmp(name, "psi_", 4) || !strncmp(name, "rate_", 5)) {
    const char *num = name + (name[0] == 'p' ? 4 : 5);
    char *end;
    unsigned long k;
    if (!(*num >= '1' && *num <= '9')) goto unknown;
    errno = 0;
    k = strtoul(num, &end, 10);
    if (*end || errno) goto unknown;
    if (k < 1 || k > M->n_balls)
      return autobal_error_set(err, AUTOBAL_EINVAL, "%s: ball %lu does not exist (the model has %zu balls: 1..%zu, plane 1 first)",
                               name, k, M->n_balls, M->n_balls);
    *index = k - 1;
    if (name[0] == 'p') {
      *kind = R_PSI, info->periodic = 1, info->units = "rad", info->long_name = "initial angle of the ball relative to the rotor";
    } else {
      *kind = R_RATE, info->units = "rad/s", info->long_name = "initial angular rate of the ball relative to the rotor";
    }
    return AUTOBAL_SUCCESS;
  }
  if (!strcmp(name, "omega")) *kind = R_OMEGA, info->units = "rad/s", info->long_name = "spin speed omega";
  else if (!strcmp(name, "ball_damping")) *kind = R_DAMPING, info->units = "kg/s", info->long_name = "damping h of every ball";
  else if (!strcmp(name, "m0")) *kind = R_M0, info->units = "kg", info->long_name = "unbalance mass m0 of plane 1";
  else if (!strcmp(name, "psi0"))
    *kind = R_PSI0, info->units = "rad", info->periodic = 1, info->long_name = "angle psi0 of the unbalance of plane 1 on the rotor";
  else if (!strcmp(name, "x")) *kind = R_X, info->units = "m", info->long_name = "initial displacement x of the centre of mass";
  else if (!strcmp(name, "y")) *kind = R_Y, info->units = "m", info->long_name = "initial displacement y of the centre of mass";
  else if (!strcmp(name, "ramp_rate"))
    *kind = R_RAMP_RATE, info->units = "rad/s^2", info->positive = 1,
    info->long_name = "rate |omega_b - omega_a| / (t_b - t_a) of the speed ramp (t_b follows from it)";
  else if (!strcmp(name, "ramp_time"))
    *kind = R_RAMP_TIME, info->units = "s", info->positive = 1, info->long_name = "duration t_b - t_a of the speed ramp";
  else if (!strcmp(name, "omega_b")) *kind = R_OMEGA_B, info->units = "rad/s", info->long_name = "final speed omega_b of the ramp";
  else if (!strcmp(name, "ball_f"))
    *kind = R_BALL_F, info->units = "1", info->long_name = "rolling-resistance coefficient f of every ball (friction)";
  else if (!strcmp(name, "ball_mu"))
    *kind = R_BALL_MU, info->units = "1", info->long_name = "static friction coefficient mu of every ball (friction)";
  else goto unknown;
  return AUTOBAL_SUCCESS;
unknown:
  return autobal_error_set(err, AUTOBAL_EINVAL,
                           "'%s' is not a rotor ensemble parameter: psi_K, rate_K (ball K = 1..%zu), omega, ball_damping, m0, psi0, x, y; "
                           "with a ramp drive also ramp_rate, ramp_time, omega_b; with a friction law also ball_f, ball_mu",
                           name, M->n_balls);
}

/* The drive parameters need a ramp drive; omega (the constant speed) needs the constant drive;
 * ramp_rate and ramp_time both set t_b. */
static int rotor_check(const void *model, const char *const *names, size_t n, autobal_error *err) {
  const rotor_model *M = model;
  const int mode = M->p.drive.mode;
  static const char *const mode_name[3] = {"constant", "ramp", "table"};
  const char *mname = mode >= 0 && mode <= 2 ? mode_name[mode] : "unknown";
  int has_rate = 0, has_time = 0, has_wb = 0;
  size_t j;
  for (j = 0; j < n; j++) {
    int kind = -1;
    size_t index = 0;
    if (rotor_parse(M, names[j], &kind, &index, NULL, err) != AUTOBAL_SUCCESS) return AUTOBAL_EINVAL;
    if ((kind == R_RAMP_RATE || kind == R_RAMP_TIME || kind == R_OMEGA_B) && mode != AUTOBAL_ROTOR_DRIVE_RAMP)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "%s varies the speed ramp, but the drive is %s: it needs drive mode = ramp", names[j], mname);
    if (kind == R_OMEGA && mode != AUTOBAL_ROTOR_DRIVE_CONSTANT)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "omega is the constant speed, which a %s drive does not use: with a ramp vary omega_b, ramp_rate "
                               "or ramp_time",
                               mname);
    if ((kind == R_BALL_F || kind == R_BALL_MU) && M->p.friction.law == AUTOBAL_ROTOR_FRICTION_NONE)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "%s varies the friction of the balls, but there is no friction law: it needs friction law = exact or "
                               "regularized",
                               names[j]);
    has_rate |= kind == R_RAMP_RATE, has_time |= kind == R_RAMP_TIME, has_wb |= kind == R_OMEGA_B;
  }
  if (has_rate && has_time)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ramp_rate and ramp_time both set the end t_b of the ramp; vary one of them");
  if (has_rate && !has_wb && !(M->p.drive.omega_b != M->p.drive.omega_a))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "ramp_rate needs a ramp that changes the speed: omega_a = omega_b = %g rad/s", M->p.drive.omega_a);
  return AUTOBAL_SUCCESS;
}

static int rotor_describe(const void *model, const char *name, autobal_ensemble_param_info *info, autobal_error *err) {
  int kind;
  size_t index;
  if (!name) return autobal_error_set(err, AUTOBAL_EINVAL, "rotor ensemble parameter: NULL name");
  return rotor_parse(model, name, &kind, &index, info, err);
}

static void rotor_worker_free(void *wp) {
  rotor_worker *w = wp;
  if (!w) return;
  study_contact_free(w->cont);
  study_friction_free(w->fric);
  autobal_rotor_free(w->rot);
  free(w->bpsi), free(w->brate), free(w->bdamp), free(w->bf), free(w->bmu), free(w->out);
  free(w->cplane), free(w->cmom), free(w->cpsi), free(w->cres), free(w->camp);
  free(w);
}

static void *rotor_worker_alloc(const void *model, const char *const *names, size_t n, autobal_error *err) {
  const rotor_model *M = model;
  size_t nb = M->n_balls ? M->n_balls : 1, j;
  rotor_worker *w;
  if (n > AUTOBAL_ENSEMBLE_MAX_PARAMS) {
    autobal_error_set(err, AUTOBAL_EINVAL, "rotor ensemble: %zu parameters (at most %d)", n, AUTOBAL_ENSEMBLE_MAX_PARAMS);
    return NULL;
  }
  w = calloc(1, sizeof *w);
  if (!w) goto nomem;
  w->M = M;
  w->np = n;
  for (j = 0; j < n; j++)
    if (rotor_parse(M, names[j], &w->kind[j], &w->index[j], NULL, err) != AUTOBAL_SUCCESS) {
      rotor_worker_free(w);
      return NULL;
    }
  w->bpsi = calloc(nb, sizeof *w->bpsi);
  w->brate = calloc(nb, sizeof *w->brate);
  w->bdamp = calloc(nb, sizeof *w->bdamp);
  w->bf = calloc(nb, sizeof *w->bf);
  w->bmu = calloc(nb, sizeof *w->bmu);
  w->out = calloc(M->nout ? M->nout : 1, sizeof *w->out);
  w->cplane = calloc(nb, sizeof *w->cplane);
  w->cmom = calloc(nb, sizeof *w->cmom);
  if (!w->bpsi || !w->brate || !w->bdamp || !w->bf || !w->bmu || !w->out || !w->cplane || !w->cmom) goto nomem;
  {
    size_t pl, i, k = 0;
    for (pl = 0; pl < M->p.n_planes; pl++)
      for (i = 0; i < M->p.plane[pl].n_balls; i++, k++) {
        w->cplane[k] = pl;
        w->cmom[k] = M->p.plane[pl].ball_mass[i] * M->p.plane[pl].ball_radius[i];
      }
  }
  return w;
nomem:
  rotor_worker_free(w);
  autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (rotor ensemble worker)");
  return NULL;
}

static double rotor_monitor(double t, const double y[], void *user) {
  const rotor_worker *w = user;
  return autobal_rotor_balance_monitor(w->rot, w->M->frame, t, y);
}

static int rotor_setup(void *wp, const double *values, double y0[], autobal_ensemble_setup *su, autobal_error *err) {
  rotor_worker *w = wp;
  const rotor_model *M = w->M;
  autobal_rotor_params p = M->p;
  size_t pl, off = 0, j;
  int st;
  double rate = NAN;
  for (pl = 0; pl < p.n_planes; pl++) {
    const autobal_rotor_plane *b = &M->p.plane[pl];
    size_t i;
    for (i = 0; i < b->n_balls; i++) {
      w->bpsi[off + i] = b->ball_psi ? b->ball_psi[i] : 0.0;
      w->brate[off + i] = b->ball_rate ? b->ball_rate[i] : 0.0;
      w->bdamp[off + i] = b->ball_damping[i];
      if (p.friction.law != AUTOBAL_ROTOR_FRICTION_NONE) {
        w->bf[off + i] = M->p.friction.ball_f[pl][i];
        w->bmu[off + i] = M->p.friction.ball_mu[pl][i];
      }
    }
    p.plane[pl].ball_psi = w->bpsi + off;
    p.plane[pl].ball_rate = w->brate + off;
    p.plane[pl].ball_damping = w->bdamp + off;
    if (p.friction.law != AUTOBAL_ROTOR_FRICTION_NONE && b->n_balls) {
      p.friction.ball_f[pl] = w->bf + off;
      p.friction.ball_mu[pl] = w->bmu + off;
    }
    off += b->n_balls;
  }
  for (j = 0; j < w->np; j++) {
    double v = values[j];
    size_t i;
    switch (w->kind[j]) {
      case R_RAMP_RATE: rate = v; break;
      case R_RAMP_TIME: p.drive.t_b = p.drive.t_a + v; break;
      case R_OMEGA_B: p.drive.omega_b = v; break;
      case R_PSI: w->bpsi[w->index[j]] = v; break;
      case R_RATE: w->brate[w->index[j]] = v; break;
      case R_OMEGA: p.omega = v; break;
      case R_DAMPING:
        for (i = 0; i < M->n_balls; i++) w->bdamp[i] = v;
        break;
      case R_BALL_F:
        for (i = 0; i < M->n_balls; i++) w->bf[i] = v;
        break;
      case R_BALL_MU:
        for (i = 0; i < M->n_balls; i++) w->bmu[i] = v;
        break;
      case R_M0: p.plane[0].m0 = v; break;
      case R_PSI0: p.plane[0].psi0 = v; break;
      case R_X: p.q0[0] = v; break;
      case R_Y: p.q0[1] = v; break;
      default: break;
    }
  }
  /* a ramp of the given rate: from the member's omega_b (its parameter or the drive's) */
  if (!isnan(rate)) p.drive.t_b = p.drive.t_a + fabs(p.drive.omega_b - p.drive.omega_a) / rate;
  study_contact_free(w->cont); /* they point to the previous member's handle */
  w->cont = NULL;
  study_friction_free(w->fric);
  w->fric = NULL;
  w->balls_stuck_final = w->time_stuck_max = w->switches = NAN;
  w->contact_impacts = w->contacts_final = NAN;
  autobal_rotor_free(w->rot);
  /* a new handle per member: with contact it orders the pairs from this member's initial angles,
   * and overlapping balls fail this member (EINVAL naming the balls), not the ensemble */
  w->rot = autobal_rotor_alloc(&p, err);
  if (!w->rot) return err && err->status < 0 ? err->status : AUTOBAL_EINVAL;
  w->omega = p.omega;
  w->pm = p;
  st = autobal_rotor_initial_state(w->rot, M->frame, 0.0, y0, M->dim);
  if (st != AUTOBAL_SUCCESS) return st;
  su->sys.rhs = M->frame == AUTOBAL_ROTOR_FIXED ? autobal_rotor_rhs : autobal_rotor_rhs_rotating;
  su->sys.jac = NULL;
  su->sys.dim = M->dim;
  su->sys.params = w->rot;
  /* revolutions at the largest |speed| (|omega| for the constant drive), as `rotor transient` */
  su->speed = p.drive.mode == AUTOBAL_ROTOR_DRIVE_CONSTANT ? p.omega : autobal_rotor_drive_speed_max(w->rot);
  su->settle_time = 0.0;
  if (p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP) su->settle_time = fmax(0.0, p.drive.t_b);
  else if (p.drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE) su->settle_time = fmax(0.0, p.drive.table_t[p.drive.n_points - 1]);
  su->monitor = rotor_monitor;
  su->monitor_user = w;
  su->residual_initial = autobal_rotor_balance_monitor(w->rot, M->frame, 0.0, y0);
  return AUTOBAL_SUCCESS;
}

/* The exact friction law: the stick-slip events and the reset of `rotor transient`
 * (src/studies/rotor_friction.c) on this worker's driver, settled at t = 0 as there; then contact:
 * one impact event per neighbour pair (ordered from this member's initial angles) and the reset
 * that serves both, as `rotor transient` installs them. */
static int rotor_prepare(void *wp, autobal_transient *tr, double y0[], autobal_error *err) {
  rotor_worker *w = wp;
  int st = study_friction_begin(w->rot, w->M->frame, tr, 0.0, y0, &w->fric, err);
  if (st != AUTOBAL_SUCCESS) return st;
  return study_contact_begin(w->rot, w->M->frame, tr, 0.0, y0, w->fric, &w->cont, err);
}

/* After the run: the friction results (final stuck flags, time stuck, switches) and the contact
 * results (impacts, touching pairs at the end); a ball that left its track during the switching
 * or a contact that could not be settled (the reset stopped the run) fails the member. */
static int rotor_complete(void *wp, double t_reached, int run_status, autobal_error *err) {
  rotor_worker *w = wp;
  autobal_study_rotor_transient_summary *s;
  size_t j, i;
  int st, stc;
  if (!w->fric && !w->cont) return run_status;
  s = calloc(1, sizeof *s);
  if (!s) return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (rotor ensemble friction, contact)");
  s->n_planes = w->M->p.n_planes;
  st = study_friction_finish(w->fric, t_reached, s, err);
  /* contact (after friction: a friction failure keeps its message) */
  stc = w->cont ? study_contact_finish(w->cont, w->rot, s, st == AUTOBAL_SUCCESS ? err : NULL) : AUTOBAL_SUCCESS;
  if (s->have_contact) w->contact_impacts = (double)s->contact_impacts, w->contacts_final = (double)s->contacts_final;
  if (st == AUTOBAL_SUCCESS) st = stc;
  if (s->have_friction) {
    w->balls_stuck_final = 0.0, w->time_stuck_max = 0.0;
    for (j = 0; j < s->n_planes; j++)
      for (i = 0; i < w->M->p.plane[j].n_balls && s->ball_stuck_final[j] && s->ball_time_stuck[j]; i++) {
        w->balls_stuck_final += s->ball_stuck_final[j][i] ? 1.0 : 0.0;
        w->time_stuck_max = fmax(w->time_stuck_max, s->ball_time_stuck[j][i]);
      }
    w->switches = (double)(s->friction_sticks + s->friction_slips + s->friction_reversals);
  }
  study_friction_summary_free(s);
  free(s);
  if (st != AUTOBAL_SUCCESS) return st;
  return run_status;
}

static int rotor_observe(void *wp, double t, const double y[], double *amplitude, double *row) {
  rotor_worker *w = wp;
  const rotor_model *M = w->M;
  if (autobal_rotor_outputs(w->rot, M->frame, t, y, w->out, M->nout) != AUTOBAL_SUCCESS) return 1;
  *amplitude = w->out[0];
  if (row) {
    memcpy(row, y, M->dim * sizeof *y);
    memcpy(row + M->dim, w->out, M->nout * sizeof *w->out);
  }
  return 0;
}

static void rotor_finish(void *wp, double t, const double y[], double *residual, double *amplitude, double *angles) {
  rotor_worker *w = wp;
  const rotor_model *M = w->M;
  size_t i;
  double phi0 = w->omega * t, dv[3];
  *residual = autobal_rotor_balance_monitor(w->rot, M->frame, t, y);
  *amplitude = autobal_rotor_outputs(w->rot, M->frame, t, y, w->out, M->nout) == AUTOBAL_SUCCESS ? w->out[0] : NAN;
  /* the rotor angle phi_0(t) of a ramp or table drive */
  if (M->p.drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT)
    phi0 = autobal_rotor_drive_eval(w->rot, t, dv) == AUTOBAL_SUCCESS ? dv[2] : NAN;
  for (i = 0; i < M->n_balls; i++) {
    double a = M->frame == AUTOBAL_ROTOR_FIXED ? y[8 + i] - phi0 : y[8 + i];
    angles[i] = remainder(a, TWO_PI);
  }
}

/* The residual unbalance in engineering units, as `rotor transient` reports it
 * (src/studies/rotor_transient.c, engineering_compute): the worst plane's |s_j| and the ISO
 * 21940-11 grade of n_planes times it with the rotor mass, at the speed at the end. */
static const autobal_ensemble_quantity rotor_quantities[ROTOR_MAX_QUANTITIES] = {
    {"residual_unbalance_abs_final", "kg m",
     "residual unbalance |s_j| at the end of the run, the largest over the balancer planes (one plane: |s|)"},
    {"balance_grade_final", "mm/s",
     "ISO 21940-11 balance quality grade at the end: G = e Omega, e = n_planes max_j |s_j| / m with m the rotor mass "
     "(m_p; M with lumped input) and Omega the speed at the end of the run"},
    /* the exact friction law only */
    {"balls_stuck_final", "1", "number of balls stuck on their track at the end of the run (exact friction law)"},
    {"time_stuck_max", "s", "the longest total time one ball spent stuck during the run (exact friction law)"},
    {"friction_switches", "1", "stick-slip switches during the run: sticks, slips from stuck and reversals at psi' = 0 (exact friction law)"},
    /* contact only (ball_diameter given): after the friction quantities when both are on */
    {"contact_impacts", "1", "impacts of neighbouring balls during the run (contact; the plastic ones that join a pair included)"},
    {"contacts_final", "1", "pairs of neighbouring balls touching (held in resting contact) at the end of the run (contact)"}};

static void rotor_finish_quantities(void *wp, double t, const double y[], double *q) {
  rotor_worker *w = wp;
  const rotor_model *M = w->M;
  const size_t np = M->p.n_planes;
  size_t j;
  double worst = 0.0, omega = fabs(w->omega), dv[3], m;
  for (j = 0; j < np; j++) {
    double s4[4], u = autobal_rotor_plane_unbalance(w->rot, j, M->frame, t, y, s4) == AUTOBAL_SUCCESS ? hypot(s4[0], s4[1]) : NAN;
    if (isnan(u)) {
      worst = NAN;
      break;
    }
    if (u > worst) worst = u;
  }
  if (M->p.drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT) { /* the speed at the end (the largest if that is 0) */
    omega = autobal_rotor_spin(w->rot, t, y, dv) == AUTOBAL_SUCCESS ? fabs(dv[0]) : NAN;
    if (!(omega > 0)) omega = autobal_rotor_drive_speed_max(w->rot);
  }
  m = M->p.input == AUTOBAL_ROTOR_HARDWARE ? M->p.hw.m_p : M->p.lumped.M;
  q[0] = worst;
  q[1] = autobal_balance_grade(worst * (double)np, m, omega);
  if (M->q_friction) q[M->q_friction] = w->balls_stuck_final, q[M->q_friction + 1] = w->time_stuck_max, q[M->q_friction + 2] = w->switches;
  if (M->q_contact) q[M->q_contact] = w->contact_impacts, q[M->q_contact + 1] = w->contacts_final;
}

/* The arrays of a final window of n samples with nb balls (angles n x nb, residual, amplitude),
 * grown between members, never during a run; *cap the samples they hold. */
static int window_reserve(double **psi, double **res, double **amp, size_t *cap, size_t n, size_t nb,
                          autobal_error *err) {
  double *a, *b, *c;
  if (n <= *cap) return AUTOBAL_SUCCESS;
  a = realloc(*psi, n * (nb ? nb : 1) * sizeof *a);
  if (a) *psi = a;
  b = a ? realloc(*res, n * sizeof *b) : NULL;
  if (b) *res = b;
  c = b ? realloc(*amp, n * sizeof *c) : NULL;
  if (c) *amp = c;
  if (!c) return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (ensemble attractor window)");
  *cap = n;
  return AUTOBAL_SUCCESS;
}

/* The attractor of a member (autobal/attractor.h) from its final window: each sample's ball angles
 * relative to the rotor (psi = phi - phi_0(t) in the fixed frame), residual unbalance
 * (autobal_rotor_balance_monitor) and amplitude (output 0); the planes' unbalances; the spin
 * speed at the end and the natural frequencies of the rotor-housing there (autobal_rotor_modes:
 * the Campbell diagram's column at that speed, damped frequencies Im lambda, with their whirl). */
static int rotor_classify(void *wp, const autobal_attractor_options *opt, double balance_tol, int stopped_balanced, size_t n,
                          const double *t, const double *y, autobal_attractor_result *res, autobal_error *err) {
  rotor_worker *w = wp;
  const rotor_model *M = w->M;
  const size_t nb = M->n_balls, np = M->p.n_planes;
  autobal_attractor_window win;
  double umom[AUTOBAL_ROTOR_MAX_PLANES], uang[AUTOBAL_ROTOR_MAX_PLANES], freq[AUTOBAL_ROTOR_N_MODES], spin[2];
  int whirl[AUTOBAL_ROTOR_N_MODES], st;
  size_t k, i, j;
  if ((st = window_reserve(&w->cpsi, &w->cres, &w->camp, &w->ccap, n, nb, err)) != AUTOBAL_SUCCESS) return st;
  for (k = 0; k < n; k++) {
    const double *yk = y + k * M->dim;
    double phi0 = 0.0;
    if (M->frame == AUTOBAL_ROTOR_FIXED) phi0 = autobal_rotor_spin(w->rot, t[k], yk, spin) == AUTOBAL_SUCCESS ? spin[1] : NAN;
    for (i = 0; i < nb; i++) w->cpsi[k * nb + i] = yk[8 + i] - phi0;
    w->cres[k] = autobal_rotor_balance_monitor(w->rot, M->frame, t[k], yk);
    w->camp[k] = autobal_rotor_outputs(w->rot, M->frame, t[k], yk, w->out, M->nout) == AUTOBAL_SUCCESS ? w->out[0] : NAN;
  }
  for (j = 0; j < np; j++) /* the member's own m0, psi0 (parameters of the ensemble) */
    umom[j] = w->pm.plane[j].m0 * w->pm.plane[j].r0, uang[j] = w->pm.plane[j].psi0;
  memset(&win, 0, sizeof win);
  win.n = n, win.t = t, win.n_balls = nb, win.psi = w->cpsi, win.residual = w->cres, win.amplitude = w->camp;
  win.balance_tol = balance_tol, win.stopped_balanced = stopped_balanced;
  win.speed = w->omega;
  if (n && M->p.drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT)
    win.speed = autobal_rotor_spin(w->rot, t[n - 1], y + (n - 1) * M->dim, spin) == AUTOBAL_SUCCESS ? spin[0] : NAN;
  win.n_planes = np, win.plane_of_ball = w->cplane, win.ball_moment = w->cmom;
  win.unbalance_moment = umom, win.unbalance_angle = uang;
  /* the natural frequencies only when a ball may circulate (the modes cost an eigenproblem) */
  win.n_modes = 0;
  if (isfinite(win.speed)) {
    autobal_attractor_result probe;
    st = autobal_attractor_classify(opt, &win, &probe, err);
    if (st != AUTOBAL_SUCCESS) return st;
    if (probe.cls != AUTOBAL_ATTRACTOR_CIRCULATING) {
      *res = probe;
      return AUTOBAL_SUCCESS;
    }
    st = autobal_rotor_modes(&w->pm, win.speed, 0, freq, NULL, NULL, whirl, err);
    if (st != AUTOBAL_SUCCESS) return st;
    win.n_modes = AUTOBAL_ROTOR_N_MODES, win.mode_frequency = freq, win.mode_whirl = whirl;
  }
  return autobal_attractor_classify(opt, &win, res, err);
}

static int rotor_column_name(const void *model, size_t k, char *name, size_t size, const char **units) {
  static const char *const q[8] = {"x", "y", "alpha", "beta", "x_rate", "y_rate", "alpha_rate", "beta_rate"};
  static const char *const qu[8] = {"m", "m", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s"};
  const rotor_model *M = model;
  const int fixed = M->frame == AUTOBAL_ROTOR_FIXED;
  size_t nb = M->n_balls;
  if (k >= M->dim) return k < M->dim + M->nout ? autobal_rotor_output_name(M->rot, k - M->dim, name, size, units) : AUTOBAL_EINVAL;
  if (k < 8) snprintf(name, size, "%s", q[k]), *units = qu[k];
  else if (k < 8 + nb) snprintf(name, size, fixed ? "state_phi_%zu" : "state_psi_%zu", k - 8 + 1), *units = "rad";
  else if (k < 8 + 2 * nb) snprintf(name, size, fixed ? "state_phi_rate_%zu" : "state_psi_rate_%zu", k - 8 - nb + 1), *units = "rad/s";
  else if (k == 8 + 2 * nb) snprintf(name, size, "z"), *units = "m";
  else snprintf(name, size, "z_rate"), *units = "m/s";
  return AUTOBAL_SUCCESS;
}

static int rotor_write_attrs(const void *model, autobal_archive *a, const char *group) {
  const rotor_model *M = model;
  const autobal_rotor_drive *d = &M->p.drive;
  int st = autobal_archive_attr_string(a, group, "frame", M->frame_name);
  /* the drive (the layout of /rotor/transient; none for the constant drive, as there) */
  if (!st && d->mode == AUTOBAL_ROTOR_DRIVE_RAMP) {
    st = autobal_archive_attr_string(a, group, "drive_mode", "ramp");
    if (!st) st = autobal_archive_attr_double(a, group, "drive_omega_a", d->omega_a, "rad/s");
    if (!st) st = autobal_archive_attr_double(a, group, "drive_omega_b", d->omega_b, "rad/s");
    if (!st) st = autobal_archive_attr_double(a, group, "drive_t_a", d->t_a, "s");
    if (!st) st = autobal_archive_attr_double(a, group, "drive_t_b", d->t_b, "s");
  } else if (!st && d->mode == AUTOBAL_ROTOR_DRIVE_TABLE) {
    st = autobal_archive_attr_string(a, group, "drive_mode", "table");
    if (!st) st = autobal_archive_attr_double_array(a, group, "drive_table_t", d->n_points, d->table_t, "s");
    if (!st) st = autobal_archive_attr_double_array(a, group, "drive_table_omega", d->n_points, d->table_omega, "rad/s");
  }
  /* the friction law (the layout of /rotor/transient: the law on the group, ball_f and ball_mu on
   * /rotor/plane<j>; nothing without friction) */
  if (!st) st = study_friction_write_inputs(a, M->rot, group);
  return st;
}

static uint64_t rotor_hash(const void *model) {
  const rotor_model *M = model;
  const autobal_rotor_params *p = &M->p;
  uint64_t h = UINT64_C(0xCBF29CE484222325);
  double v[6];
  size_t pl;
  v[0] = p->input, v[1] = p->inertia, v[2] = p->omega, v[3] = p->axial, v[4] = (double)p->n_planes, v[5] = M->frame;
  h = hash_doubles(h, v, 6);
  h = hash_doubles(h, (const double *)&p->hw, sizeof p->hw / sizeof(double));
  h = hash_doubles(h, (const double *)&p->lumped, sizeof p->lumped / sizeof(double));
  h = hash_doubles(h, p->q0, 4);
  h = hash_doubles(h, p->qd0, 4);
  v[0] = p->z0, v[1] = p->zd0;
  h = hash_doubles(h, v, 2);
  for (pl = 0; pl < p->n_planes; pl++) {
    const autobal_rotor_plane *b = &p->plane[pl];
    size_t i;
    v[0] = b->d, v[1] = b->m0, v[2] = b->r0, v[3] = b->psi0, v[4] = (double)b->n_balls;
    h = hash_doubles(h, v, 5);
    for (i = 0; i < b->n_balls; i++) {
      v[0] = b->ball_mass[i], v[1] = b->ball_radius[i], v[2] = b->ball_damping[i];
      v[3] = b->ball_psi ? b->ball_psi[i] : 0.0, v[4] = b->ball_rate ? b->ball_rate[i] : 0.0;
      h = hash_doubles(h, v, 5);
    }
  }
  if (p->drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT) { /* the constant drive: the hash of 0.1.0 */
    const autobal_rotor_drive *d = &p->drive;
    v[0] = d->mode, v[1] = d->omega_a, v[2] = d->omega_b, v[3] = d->t_a, v[4] = d->t_b, v[5] = (double)d->n_points;
    h = hash_doubles(h, v, 6);
    if (d->mode == AUTOBAL_ROTOR_DRIVE_TABLE) {
      h = hash_doubles(h, d->table_t, d->n_points);
      h = hash_doubles(h, d->table_omega, d->n_points);
    }
  }
  if (p->gravity) { /* absent when off: the hashes before gravity */
    v[0] = 1.0, v[1] = p->shaft_angle, v[2] = p->g;
    h = hash_doubles(h, v, 3);
  }
  if (p->friction.law != AUTOBAL_ROTOR_FRICTION_NONE) { /* absent when off: the hashes before friction */
    v[0] = (double)p->friction.law, v[1] = p->friction.u_eps;
    h = hash_doubles(h, v, 2);
    for (pl = 0; pl < p->n_planes; pl++) {
      h = hash_doubles(h, p->friction.ball_f[pl], p->plane[pl].n_balls);
      h = hash_doubles(h, p->friction.ball_mu[pl], p->plane[pl].n_balls);
    }
  }
  if (p->rolling.on) { /* absent when off: the hashes before rolling inertia */
    v[0] = 2.0;
    h = hash_doubles(h, v, 1);
    for (pl = 0; pl < p->n_planes; pl++)
      if (p->rolling.ball_rho[pl]) h = hash_doubles(h, p->rolling.ball_rho[pl], p->plane[pl].n_balls);
  }
  if (p->contact.on) { /* absent when off: the hashes before contact */
    v[0] = 1.0, v[1] = p->contact.restitution, v[2] = p->contact.v_rest;
    h = hash_doubles(h, v, 3);
    for (pl = 0; pl < p->n_planes; pl++)
      if (p->contact.ball_diameter[pl]) h = hash_doubles(h, p->contact.ball_diameter[pl], p->plane[pl].n_balls);
  }
  return h;
}

static void rotor_destroy(void *model) {
  rotor_model *M = model;
  if (!M) return;
  autobal_rotor_free(M->rot);
  free(M->storage);
  free(M->table);
  free(M);
}

int autobal_ensemble_rotor_member(const autobal_rotor_params *p, int frame, const char *frame_name, autobal_ensemble_member *out,
                                  autobal_error *err) {
  rotor_model *M;
  size_t pl, nb = 0, off = 0;
  autobal_error_clear(err);
  if (out) memset(out, 0, sizeof *out);
  if (!p || !out) return autobal_error_set(err, AUTOBAL_EINVAL, "rotor ensemble member: NULL argument");
  if (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING)
    return autobal_error_set(err, AUTOBAL_EINVAL, "rotor ensemble member: frame = %d is not AUTOBAL_ROTOR_FIXED or AUTOBAL_ROTOR_ROTATING", frame);
  /* the prescribed speeds only: the settle time, the sampling speed and the rotor angle of the
   * final ball angles are those of a kinematic drive */
  if (p->drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT && p->drive.mode != AUTOBAL_ROTOR_DRIVE_RAMP &&
      p->drive.mode != AUTOBAL_ROTOR_DRIVE_TABLE)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "rotor ensemble member: drive mode %d is not one the ensemble supports (constant, ramp, table)",
                             p->drive.mode);
  if (p->n_planes < 1 || p->n_planes > AUTOBAL_ROTOR_MAX_PLANES)
    return autobal_error_set(err, AUTOBAL_EINVAL, "rotor ensemble member: n_planes = %zu is out of range: allowed [1, %d]", p->n_planes,
                             AUTOBAL_ROTOR_MAX_PLANES);
  for (pl = 0; pl < p->n_planes; pl++) {
    const autobal_rotor_plane *b = &p->plane[pl];
    if (b->n_balls > 4096)
      return autobal_error_set(err, AUTOBAL_EINVAL, "rotor ensemble member: plane[%zu].n_balls = %zu is out of range: allowed [0, 4096]", pl,
                               b->n_balls);
    if (b->n_balls && (!b->ball_mass || !b->ball_radius || !b->ball_damping))
      return autobal_error_set(err, AUTOBAL_EINVAL, "rotor ensemble member: plane[%zu] has balls but no mass, radius or damping array", pl);
    nb += b->n_balls;
  }
  if (p->friction.law != AUTOBAL_ROTOR_FRICTION_NONE)
    for (pl = 0; pl < p->n_planes; pl++)
      if (p->plane[pl].n_balls && (!p->friction.ball_f[pl] || !p->friction.ball_mu[pl]))
        return autobal_error_set(err, AUTOBAL_EINVAL, "rotor ensemble member: plane[%zu] has a friction law but no ball_f or ball_mu array", pl);
  M = calloc(1, sizeof *M);
  if (!M || !(M->storage = calloc(9 * (nb ? nb : 1), sizeof *M->storage))) {
    free(M);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (rotor ensemble member)");
  }
  M->p = *p;
  for (pl = 0; pl < p->n_planes; pl++) {
    const autobal_rotor_plane *b = &p->plane[pl];
    autobal_rotor_plane *c = &M->p.plane[pl];
    size_t i, n = b->n_balls;
    double *s = M->storage + 9 * off;
    for (i = 0; i < n; i++) {
      s[i] = b->ball_mass[i];
      s[n + i] = b->ball_radius[i];
      s[2 * n + i] = b->ball_damping[i];
      s[3 * n + i] = b->ball_psi ? b->ball_psi[i] : 0.0;
      s[4 * n + i] = b->ball_rate ? b->ball_rate[i] : 0.0;
      if (p->friction.law != AUTOBAL_ROTOR_FRICTION_NONE) s[5 * n + i] = p->friction.ball_f[pl][i], s[6 * n + i] = p->friction.ball_mu[pl][i];
      s[7 * n + i] = p->contact.on && p->contact.ball_diameter[pl] ? p->contact.ball_diameter[pl][i] : 0.0;
      s[8 * n + i] = p->rolling.on && p->rolling.ball_rho[pl] ? p->rolling.ball_rho[pl][i] : 0.0;
    }
    M->p.contact.ball_diameter[pl] = p->contact.on && n ? s + 7 * n : NULL; /* the diameters, copied (NULL: all 0) */
    M->p.rolling.ball_rho[pl] = p->rolling.on && n ? s + 8 * n : NULL;      /* the balls' radii, copied (rolling) */
    if (p->friction.law != AUTOBAL_ROTOR_FRICTION_NONE) {
      M->p.friction.ball_f[pl] = n ? s + 5 * n : NULL;
      M->p.friction.ball_mu[pl] = n ? s + 6 * n : NULL;
    }
    c->ball_mass = n ? s : NULL;
    c->ball_radius = n ? s + n : NULL;
    c->ball_damping = n ? s + 2 * n : NULL;
    c->ball_psi = n ? s + 3 * n : NULL;
    c->ball_rate = n ? s + 4 * n : NULL;
    off += n;
  }
  if (p->drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE && p->drive.table_t && p->drive.table_omega && p->drive.n_points > 0 &&
      p->drive.n_points <= AUTOBAL_ROTOR_DRIVE_MAX_POINTS) {
    size_t k, np = p->drive.n_points;
    if (!(M->table = malloc(2 * np * sizeof *M->table))) {
      rotor_destroy(M);
      return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (rotor ensemble member)");
    }
    for (k = 0; k < np; k++) M->table[k] = p->drive.table_t[k], M->table[np + k] = p->drive.table_omega[k];
    M->p.drive.table_t = M->table;
    M->p.drive.table_omega = M->table + np;
  }
  M->frame = frame;
  snprintf(M->frame_name, sizeof M->frame_name, "%s", frame_name ? frame_name : (frame == AUTOBAL_ROTOR_FIXED ? "fixed" : "rotating"));
  M->rot = autobal_rotor_alloc(&M->p, err);
  if (!M->rot) {
    int st = err && err->status < 0 ? err->status : AUTOBAL_EINVAL;
    rotor_destroy(M);
    return st;
  }
  M->n_balls = autobal_rotor_n_balls_total(M->rot);
  M->dim = autobal_rotor_dim(M->rot);
  M->nout = autobal_rotor_output_count(M->rot);
  autobal_error_clear(err);
  out->model_name = "rotor";
  out->model = M;
  out->dim = M->dim;
  out->n_angles = M->n_balls;
  out->n_columns = M->dim + M->nout;
  out->time_units = "s";
  out->time_name = "time";
  out->time_long_name = "time";
  out->length_units = "m";
  out->angle_dim = "ball";
  out->angle_dim_long_name = "ball (plane 1 first)";
  out->angle_long_name = "ball angle relative to the rotor at the end, wrapped to (-pi, pi]";
  out->describe = rotor_describe;
  out->check = rotor_check;
  out->worker_alloc = rotor_worker_alloc;
  out->worker_free = rotor_worker_free;
  out->setup = rotor_setup;
  out->observe = rotor_observe;
  out->finish = rotor_finish;
  out->column_name = rotor_column_name;
  out->write_attrs = rotor_write_attrs;
  out->hash = rotor_hash;
  out->destroy = rotor_destroy;
  /* the quantities: 2, the exact law's 3, contact's 2 (the layout of 0.2.0 without contact) */
  M->n_quantities = 0;
  memcpy(M->quantity, rotor_quantities, 2 * sizeof *M->quantity), M->n_quantities = 2;
  if (M->p.friction.law == AUTOBAL_ROTOR_FRICTION_EXACT) {
    M->q_friction = M->n_quantities;
    memcpy(M->quantity + M->n_quantities, rotor_quantities + 2, 3 * sizeof *M->quantity), M->n_quantities += 3;
  }
  if (M->p.contact.on) {
    M->q_contact = M->n_quantities;
    memcpy(M->quantity + M->n_quantities, rotor_quantities + 5, 2 * sizeof *M->quantity), M->n_quantities += 2;
  }
  out->n_quantities = M->n_quantities;
  out->quantity = M->quantity;
  out->finish_quantities = rotor_finish_quantities;
  out->prepare = rotor_prepare;
  out->complete = rotor_complete;
  out->classify = rotor_classify;
  return AUTOBAL_SUCCESS;
}

/* ================================ pendulum ============================================== */
enum { P_STATE, P_RW, P_RM, P_H, P_HS, P_PSI0, P_K };

typedef struct pend_model {
  autobal_pendulum_params p;
  double y0[8];
} pend_model;

typedef struct pend_worker {
  const pend_model *M;
  size_t np;
  int kind[AUTOBAL_ENSEMBLE_MAX_PARAMS];
  size_t index[AUTOBAL_ENSEMBLE_MAX_PARAMS];
  autobal_pendulum_motion motion;
  /* the attractor classification's final window (pend_classify): angles, residual, amplitude */
  double *cpsi, *cres, *camp;
  size_t ccap;
} pend_worker;

static int pend_parse(const char *name, int *kind, size_t *index, autobal_ensemble_param_info *info, autobal_error *err) {
  static const char *const pstate[8] = {"xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate"};
  static const char *const pstate_u[8] = {"1", "1", "rad", "rad", "1", "1", "1", "1"};
  static const char *const pstate_l[8] = {
      "initial shaft displacement xi (units of l)", "initial shaft displacement eta (units of l)",
      "initial angle psi of pendulum 1", "initial angle phi of pendulum 2", "initial d xi/d tau",
      "initial d eta/d tau", "initial d psi/d tau", "initial d phi/d tau"};
  autobal_ensemble_param_info dummy;
  size_t i;
  if (!info) info = &dummy;
  memset(info, 0, sizeof *info);
  *index = 0;
  for (i = 0; i < 8; i++)
    if (!strcmp(name, pstate[i])) {
      *kind = P_STATE, *index = i, info->units = pstate_u[i], info->long_name = pstate_l[i];
      info->periodic = (i == 2 || i == 3);
      return AUTOBAL_SUCCESS;
    }
  if (!strcmp(name, "R_w")) *kind = P_RW, info->units = "1", info->long_name = "rotor speed omega/omega0";
  else if (!strcmp(name, "R_m")) *kind = P_RM, info->units = "1", info->long_name = "mass ratio m/(M + 2m)";
  else if (!strcmp(name, "H")) *kind = P_H, info->units = "1", info->long_name = "external damping H";
  else if (!strcmp(name, "h")) *kind = P_HS, info->units = "1", info->long_name = "pendulum damping h";
  else if (!strcmp(name, "psi0")) *kind = P_PSI0, info->units = "rad", info->long_name = "main-motion angle psi0", info->periodic = 1;
  else if (!strcmp(name, "k")) *kind = P_K, info->units = "1", info->long_name = "unbalance parameter k = sin^2(2 psi0)";
  else
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "'%s' is not a pendulum ensemble parameter: xi, eta, psi, phi, xi_rate, eta_rate, psi_rate, phi_rate, R_w, R_m, H, h, psi0, k",
                             name);
  return AUTOBAL_SUCCESS;
}

static int pend_describe(const void *model, const char *name, autobal_ensemble_param_info *info, autobal_error *err) {
  int kind;
  size_t index;
  (void)model;
  if (!name) return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum ensemble parameter: NULL name");
  return pend_parse(name, &kind, &index, info, err);
}

static int pend_check(const void *model, const char *const *names, size_t n, autobal_error *err) {
  size_t i;
  int k = 0, psi0 = 0;
  (void)model;
  for (i = 0; i < n; i++) {
    if (!strcmp(names[i], "k")) k = 1;
    if (!strcmp(names[i], "psi0")) psi0 = 1;
  }
  if (k && psi0) return autobal_error_set(err, AUTOBAL_EINVAL, "k and psi0 describe the same unbalance; vary one of them");
  return AUTOBAL_SUCCESS;
}

static void pend_worker_free(void *wp) {
  pend_worker *w = wp;
  if (!w) return;
  free(w->cpsi);
  free(w->cres);
  free(w->camp);
  free(w);
}

static void *pend_worker_alloc(const void *model, const char *const *names, size_t n, autobal_error *err) {
  pend_worker *w;
  size_t j;
  if (n > AUTOBAL_ENSEMBLE_MAX_PARAMS) {
    autobal_error_set(err, AUTOBAL_EINVAL, "pendulum ensemble: %zu parameters (at most %d)", n, AUTOBAL_ENSEMBLE_MAX_PARAMS);
    return NULL;
  }
  w = calloc(1, sizeof *w);
  if (!w) {
    autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (pendulum ensemble worker)");
    return NULL;
  }
  w->M = model;
  w->np = n;
  for (j = 0; j < n; j++)
    if (pend_parse(names[j], &w->kind[j], &w->index[j], NULL, err) != AUTOBAL_SUCCESS) {
      free(w);
      return NULL;
    }
  return w;
}

static int pend_setup(void *wp, const double *values, double y0[], autobal_ensemble_setup *su, autobal_error *err) {
  pend_worker *w = wp;
  autobal_pendulum_params p = w->M->p;
  int k_given = 0, st;
  double k = 0;
  size_t j;
  memcpy(y0, w->M->y0, sizeof w->M->y0);
  for (j = 0; j < w->np; j++) {
    double v = values[j];
    switch (w->kind[j]) {
      case P_STATE: y0[w->index[j]] = v; break;
      case P_RW: p.R_w = v; break;
      case P_RM: p.R_m = v; break;
      case P_H: p.H = v; break;
      case P_HS: p.h = v; break;
      case P_PSI0: p.psi0 = v; break;
      case P_K: k_given = 1, k = v; break;
      default: break;
    }
  }
  if (k_given && (st = autobal_pendulum_params_from_k(p.R_w, p.R_m, p.H, p.h, k, &p, err)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_pendulum_motion_init(&w->motion, &p, err)) != AUTOBAL_SUCCESS) return st;
  su->sys.rhs = autobal_pendulum_motion_rhs;
  su->sys.jac = autobal_pendulum_motion_jac;
  su->sys.dim = AUTOBAL_PENDULUM_STATE_DIM;
  su->sys.params = &w->motion;
  su->speed = p.R_w;
  su->monitor = autobal_pendulum_unbalance_scalar;
  su->monitor_user = &w->motion.p;
  su->residual_initial = autobal_pendulum_residual_unbalance(&w->motion.p, y0, NULL, NULL);
  return AUTOBAL_SUCCESS;
}

static int pend_observe(void *wp, double t, const double y[], double *amplitude, double *row) {
  pend_worker *w = wp;
  autobal_pendulum_motion_derived d;
  (void)t;
  autobal_pendulum_motion_derive_m(&w->motion, y, &d);
  *amplitude = d.amplitude;
  if (row) {
    memcpy(row, y, 8 * sizeof *y);
    row[8] = d.amplitude, row[9] = d.unbalance, row[10] = d.unbalance_u, row[11] = d.unbalance_v;
    row[12] = d.alpha, row[13] = d.beta, row[14] = d.jacobi;
  }
  return 0;
}

static void pend_finish(void *wp, double t, const double y[], double *residual, double *amplitude, double *angles) {
  pend_worker *w = wp;
  autobal_pendulum_motion_derived d;
  (void)t;
  autobal_pendulum_motion_derive_m(&w->motion, y, &d);
  *residual = d.unbalance;
  *amplitude = d.amplitude;
  angles[0] = d.alpha;
  angles[1] = d.beta;
}

/* The attractor of a pendulum member (autobal/attractor.h) from its final window.  The rule's ball
 * angles are the directions of the two pendulum masses from O relative to the rotor, measured from
 * +U (the side of the unbalance Me) towards +V: pendulum 1's mass sits at l(-sin psi, cos psi), at
 * angle psi + pi/2; pendulum 2's at l(-sin phi, -cos phi), at -phi - pi/2 (docs/pendulum.md,
 * "Axes"); both continuous in time.  Each pendulum has the first moment m l (1 in units of m l),
 * the unbalance M e = 2 m l sin psi0 lies at angle 0.  The residual unbalance and the amplitude
 * are those of the ensemble (autobal_pendulum_motion_derive).  Time is tau = omega0 t, so rates
 * and frequencies are in units of omega0 = sqrt(c / (M + 2m)), the natural frequency of the shaft
 * carrying rotor and pendulums as one mass (the model's scale, the first critical speed without
 * unbalance, (13)); damped by H: sqrt(1 - H^2/4), for both whirl directions (no gyroscopic effect
 * in the plane); none when H >= 2. */
static int pend_classify(void *wp, const autobal_attractor_options *opt, double balance_tol, int stopped_balanced, size_t n,
                         const double *t, const double *y, autobal_attractor_result *res, autobal_error *err) {
  pend_worker *w = wp;
  const autobal_pendulum_params *p = &w->motion.p;
  autobal_attractor_window win;
  autobal_pendulum_motion_derived d;
  static const size_t plane_of[2] = {0, 0};
  static const double moment[2] = {1.0, 1.0};
  const double zh = 0.5 * p->H;
  double umom = 2.0 * sin(p->psi0), uang = 0.0, freq[2];
  int whirl[2] = {+1, -1};
  size_t k;
  int st;
  if ((st = window_reserve(&w->cpsi, &w->cres, &w->camp, &w->ccap, n, 2, err)) != AUTOBAL_SUCCESS) return st;
  for (k = 0; k < n; k++) {
    const double *yk = y + k * AUTOBAL_PENDULUM_STATE_DIM;
    w->cpsi[2 * k] = yk[2] + 0.25 * TWO_PI;
    w->cpsi[2 * k + 1] = -yk[3] - 0.25 * TWO_PI;
    autobal_pendulum_motion_derive_m(&w->motion, yk, &d);
    w->cres[k] = d.unbalance;
    w->camp[k] = d.amplitude;
  }
  memset(&win, 0, sizeof win);
  win.n = n, win.t = t, win.n_balls = 2, win.psi = w->cpsi, win.residual = w->cres, win.amplitude = w->camp;
  win.balance_tol = balance_tol, win.stopped_balanced = stopped_balanced;
  win.speed = p->R_w;
  win.n_planes = 1, win.plane_of_ball = plane_of, win.ball_moment = moment;
  win.unbalance_moment = &umom, win.unbalance_angle = &uang;
  win.n_modes = 0;
  if (zh < 1.0) {
    freq[0] = freq[1] = sqrt(1.0 - zh * zh);
    win.n_modes = 2, win.mode_frequency = freq, win.mode_whirl = whirl;
  }
  return autobal_attractor_classify(opt, &win, res, err);
}

static int pend_column_name(const void *model, size_t k, char *name, size_t size, const char **units) {
  static const char *const n[PEND_NCOLS] = {"xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate",
                                            "amplitude", "unbalance", "unbalance_u", "unbalance_v", "alpha", "beta", "jacobi"};
  static const char *const u[PEND_NCOLS] = {"1", "1", "rad", "rad", "1", "1", "rad", "rad", "1", "1", "1", "1", "rad", "rad", "1"};
  (void)model;
  if (k >= PEND_NCOLS) return AUTOBAL_EINVAL;
  snprintf(name, size, "%s", n[k]);
  *units = u[k];
  return AUTOBAL_SUCCESS;
}

static int pend_write_attrs(const void *model, autobal_archive *a, const char *group) {
  const pend_model *M = model;
  return autobal_archive_attr_double_array(a, group, "initial_state", 8, M->y0, "1");
}

static uint64_t pend_hash(const void *model) {
  const pend_model *M = model;
  double v[5];
  uint64_t h = UINT64_C(0xCBF29CE484222325);
  v[0] = M->p.R_w, v[1] = M->p.R_m, v[2] = M->p.H, v[3] = M->p.h, v[4] = M->p.psi0;
  h = hash_doubles(h, v, 5);
  return hash_doubles(h, M->y0, 8);
}

static void pend_destroy(void *model) { free(model); }

int autobal_ensemble_pendulum_member(const autobal_pendulum_params *p, const double y0[8], autobal_ensemble_member *out,
                                     autobal_error *err) {
  pend_model *M;
  autobal_pendulum_motion mo;
  int i, st;
  autobal_error_clear(err);
  if (out) memset(out, 0, sizeof *out);
  if (!p || !y0 || !out) return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum ensemble member: NULL argument");
  if ((st = autobal_pendulum_motion_init(&mo, p, err)) != AUTOBAL_SUCCESS) return st;
  for (i = 0; i < 8; i++)
    if (!isfinite(y0[i])) return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum ensemble member: initial state y0[%d] = %g is not finite", i, y0[i]);
  M = calloc(1, sizeof *M);
  if (!M) return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (pendulum ensemble member)");
  M->p = *p;
  memcpy(M->y0, y0, sizeof M->y0);
  out->model_name = "pendulum";
  out->model = M;
  out->dim = AUTOBAL_PENDULUM_STATE_DIM;
  out->n_angles = 2;
  out->n_columns = PEND_NCOLS;
  out->time_units = "1";
  out->time_name = "tau";
  out->time_long_name = "dimensionless time tau";
  out->length_units = "1";
  out->angle_dim = "pendulum";
  out->angle_dim_long_name = "pendulum (1: psi, 2: phi)";
  out->angle_long_name = "pendulum angle minus psi0 at the end (alpha, beta), wrapped to (-pi, pi]";
  out->describe = pend_describe;
  out->check = pend_check;
  out->worker_alloc = pend_worker_alloc;
  out->worker_free = pend_worker_free;
  out->setup = pend_setup;
  out->observe = pend_observe;
  out->finish = pend_finish;
  out->column_name = pend_column_name;
  out->write_attrs = pend_write_attrs;
  out->hash = pend_hash;
  out->destroy = pend_destroy;
  out->classify = pend_classify;
  return AUTOBAL_SUCCESS;
}
