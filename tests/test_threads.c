/* test_threads.c: two threads using separate handles at the same time get the same results as
 * one thread (CONVENTIONS "State": no mutable globals, no static scratch buffers, one handle per
 * thread).
 *
 * Three workloads, each computed first serially (the reference), then by two POSIX threads at
 * the same time (released together by a barrier, repeated for several rounds, the second thread
 * running the workloads in the opposite order so that different modules overlap too):
 *   A  pendulum analysis: autobal_pendulum_analyze() over a grid of (R_m, R_w, k, damping) with
 *      one workspace per thread, the undamped critical speeds (autobal_pendulum_critical_speeds,
 *      same workspace) and a small serial stability map (autobal_pendulum_map, n_threads = 1);
 *   B  pendulum transient: the equations of motion (1) (autobal_pendulum_motion_rhs/jac) with
 *      one transient driver per thread, once with rk8pd and a dwell event ("time to balance"),
 *      once with the implicit rk4imp (analytic Jacobian) and once with bsimp driven by the
 *      driver's finite-difference Jacobian workspace; the state at every output time is recorded;
 *   C  rotor transient: the default rotor (autobal_rotor_params_default) with one rotor handle
 *      and one driver per thread, fixed frame (autobal_rotor_rhs) and rotating frame
 *      (autobal_rotor_rhs_rotating), the derived outputs (autobal_rotor_outputs) recorded at every
 *      output time.
 * Every double is compared BITWISE with the serial result (memcmp of the representation), every
 * status, verdict and counter exactly.  Why this can fail: a static scratch buffer, a shared
 * workspace or any other hidden shared state written by one thread while the other reads it
 * changes results (or crashes); under ThreadSanitizer it is reported as a race.
 *
 * The reference is also checked for sanity (so that "equal" does not mean "equally empty"):
 * the analysis gives both verdicts somewhere on the grid, the transients ran to t1 with steps.
 *
 * ThreadSanitizer (not part of CTest; the library built without OpenMP, whose runtime TSan does
 * not understand, and without the map's target_clones, whose ifunc resolvers run before TSan is
 * initialised and crash):
 *   gcc -std=c11 -fsanitize=thread -O1 -g -DAUTOBAL_BUILDING -DH5_USE_110_API -DAUTOBAL_NO_CLONES \
 *       -DAUTOBAL_GIT_REVISION='"tsan"' -Iinclude -I<build>/include -Isrc -Itests \
 *       -I/usr/include/hdf5/serial $(find src -name '*.c') tests/test_threads.c -o test_threads_tsan \
 *       -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5_hl -lhdf5 -lgsl -lgslcblas -lm -lpthread
 * reported no race (2026-11-21).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "autobal.h"
#include "check.h"

#define ROUNDS 4

/* ---- A: pendulum analysis ------------------------------------------------------------- */
#define A_NRM 3
#define A_NRW 12
#define A_NK 3
#define A_NPTS (A_NRM * A_NRW * A_NK * 2)
#define A_NCRIT 4
#define A_MAP_NRM 6
#define A_MAP_NRW 8

typedef struct pend_out {
  autobal_pendulum_result res[A_NPTS];
  int status[A_NPTS];
  autobal_pendulum_crit_set crit[A_NCRIT];
  int crit_status[A_NCRIT];
  signed char map_verdict[A_MAP_NRM * A_MAP_NRW];
  double map_max_real[A_MAP_NRM * A_MAP_NRW];
  int map_status;
} pend_out;

static void work_pendulum(pend_out *o) {
  static const double Rm[A_NRM] = {0.02, 0.1, 0.2};
  static const double ks[A_NK] = {0.0, 0.5, 1.0};
  static const double crit_rm[A_NCRIT] = {0.05, 0.1, 0.2, 0.24};
  static const double crit_k[A_NCRIT] = {0.0, 0.3, 1.0, 0.9};
  double map_rm[A_MAP_NRM], map_rw[A_MAP_NRW];
  autobal_pendulum_map_spec spec;
  autobal_error err;
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  size_t i, j, l, d, n = 0;
  memset(o, 0, sizeof *o);
  for (i = 0; i < A_NRM; i++)
    for (j = 0; j < A_NRW; j++)
      for (l = 0; l < A_NK; l++)
        for (d = 0; d < 2; d++, n++) {
          autobal_pendulum_params p;
          int st = autobal_pendulum_params_from_k(0.4 + 0.35 * (double)j, Rm[i], d ? 0.2 : 0.0, d ? 0.7 : 0.05,
                                                  ks[l], &p, NULL);
          o->status[n] = st ? st : (ws ? autobal_pendulum_analyze(ws, &p, &o->res[n]) : AUTOBAL_ENOMEM);
        }
  for (i = 0; i < A_NCRIT; i++)
    o->crit_status[i] = ws ? autobal_pendulum_critical_speeds(ws, crit_rm[i], crit_k[i], &o->crit[i]) : AUTOBAL_ENOMEM;
  autobal_pendulum_workspace_free(ws);
  for (i = 0; i < A_MAP_NRM; i++) map_rm[i] = 0.03 + 0.07 * (double)i;
  for (j = 0; j < A_MAP_NRW; j++) map_rw[j] = 0.5 + 0.6 * (double)j;
  memset(&spec, 0, sizeof spec);
  spec.R_m = map_rm;
  spec.n_Rm = A_MAP_NRM;
  spec.R_w = map_rw;
  spec.n_Rw = A_MAP_NRW;
  spec.H = 0.1;
  spec.h = 0.5;
  spec.k = NULL; /* the default k set: 65 values per point */
  spec.n_k = 0;
  spec.n_threads = 1;
  o->map_status = autobal_pendulum_map(&spec, o->map_verdict, o->map_max_real, &err);
}

/* ---- B: pendulum transient ------------------------------------------------------------- */
#define B_RUNS 3
#define B_NOUT 128
#define B_DIM AUTOBAL_PENDULUM_STATE_DIM

typedef struct series {
  size_t n, cap, dim;
  double *t;
  double *y; /* n x dim */
  int overflow;
} series;

static int record(double t, const double y[], void *user) {
  series *s = user;
  if (s->n >= s->cap) {
    s->overflow = 1;
    return 0;
  }
  s->t[s->n] = t;
  memcpy(s->y + s->n * s->dim, y, s->dim * sizeof *y);
  s->n++;
  return 0;
}

typedef struct run_out {
  int status;
  double t_reached;
  double y_final[64];
  autobal_transient_stats stats;
  int fired;
  autobal_transient_event_hit hit;
  double tt[B_NOUT];
  double yy[B_NOUT * 64];
  size_t n_out;
  int overflow;
} run_out;

typedef struct ptr_out {
  run_out run[B_RUNS];
} ptr_out;

static void work_pendulum_transient(ptr_out *o) {
  static const char *const steppers[B_RUNS] = {"rk8pd", "rk4imp", "bsimp"};
  autobal_pendulum_params p;
  autobal_pendulum_motion motion;
  size_t r;
  memset(o, 0, sizeof *o);
  if (autobal_pendulum_params_from_k(3.0, 0.1, 0.1, 0.5, 0.5, &p, NULL) != AUTOBAL_SUCCESS ||
      autobal_pendulum_motion_init(&motion, &p, NULL) != AUTOBAL_SUCCESS) {
    o->run[0].status = -1000;
    return;
  }
  for (r = 0; r < B_RUNS; r++) {
    run_out *ro = &o->run[r];
    autobal_transient_options opt = autobal_transient_options_default();
    autobal_transient_system sys;
    autobal_transient *tr;
    series s;
    double t1 = r == 0 ? 300.0 : 40.0;
    opt.stepper = steppers[r];
    opt.rtol = 1e-9;
    opt.atol = 1e-11;
    opt.dt_out = t1 / (B_NOUT - 2);
    tr = autobal_transient_alloc(B_DIM, &opt, NULL);
    if (!tr) {
      ro->status = AUTOBAL_ENOMEM;
      continue;
    }
    sys.rhs = autobal_pendulum_motion_rhs;
    sys.jac = r == 2 ? NULL : autobal_pendulum_motion_jac; /* bsimp: the driver's FD Jacobian */
    sys.dim = B_DIM;
    sys.params = &motion;
    s.n = 0;
    s.cap = B_NOUT;
    s.dim = B_DIM;
    s.t = ro->tt;
    s.y = ro->yy;
    s.overflow = 0;
    autobal_transient_set_observer(tr, record, &s);
    if (r == 0) autobal_transient_add_dwell_event(tr, autobal_pendulum_unbalance_scalar, &p, 0.05, 5.0, 0);
    /* start from rest with the pendulums opposite each other (psi = phi = 0) */
    memset(ro->y_final, 0, sizeof ro->y_final);
    ro->y_final[AUTOBAL_PENDULUM_Y_PSI] = 0.3;
    ro->status = autobal_transient_run(tr, &sys, 0.0, t1, ro->y_final, &ro->t_reached);
    autobal_transient_get_stats(tr, &ro->stats);
    if (r == 0) ro->fired = autobal_transient_event_result(tr, 0, NULL, &ro->hit);
    ro->n_out = s.n;
    ro->overflow = s.overflow;
    autobal_transient_free(tr);
  }
}

/* ---- C: rotor transient ------------------------------------------------------------------ */
#define C_RUNS 2
#define C_NOUT 96
#define C_MAXOUT 64

typedef struct rot_run {
  int status, alloc_status;
  double t_reached;
  double y_final[64];
  autobal_transient_stats stats;
  double tt[C_NOUT];
  double out[C_NOUT * C_MAXOUT];
  size_t n_out, nvals;
  int overflow;
} rot_run;

typedef struct rot_out {
  rot_run run[C_RUNS];
} rot_out;

typedef struct rot_obs {
  autobal_rotor *rotor;
  int frame;
  rot_run *ro;
} rot_obs;

static int rotor_observer(double t, const double y[], void *user) {
  rot_obs *ob = user;
  rot_run *ro = ob->ro;
  if (ro->n_out >= C_NOUT) {
    ro->overflow = 1;
    return 0;
  }
  ro->tt[ro->n_out] = t;
  if (autobal_rotor_outputs(ob->rotor, ob->frame, t, y, ro->out + ro->n_out * C_MAXOUT, ro->nvals) != AUTOBAL_SUCCESS)
    return 1;
  ro->n_out++;
  return 0;
}

static void work_rotor_transient(rot_out *o) {
  size_t r;
  memset(o, 0, sizeof *o);
  for (r = 0; r < C_RUNS; r++) {
    rot_run *ro = &o->run[r];
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_transient_options opt = autobal_transient_options_default();
    autobal_transient_system sys;
    autobal_transient *tr;
    autobal_error err;
    autobal_rotor *rot;
    rot_obs ob;
    size_t dim;
    int frame = r == 0 ? AUTOBAL_ROTOR_FIXED : AUTOBAL_ROTOR_ROTATING;
    double t1 = 1.0;
    rot = autobal_rotor_alloc(&p, &err);
    ro->alloc_status = err.status;
    if (!rot) continue;
    dim = autobal_rotor_dim(rot);
    ro->nvals = autobal_rotor_output_count(rot);
    if (dim > 64 || ro->nvals > C_MAXOUT) {
      ro->status = -1000;
      autobal_rotor_free(rot);
      continue;
    }
    opt.rtol = 1e-8;
    opt.atol = 1e-10;
    opt.dt_out = t1 / (C_NOUT - 2);
    tr = autobal_transient_alloc(dim, &opt, NULL);
    if (!tr) {
      ro->status = AUTOBAL_ENOMEM;
      autobal_rotor_free(rot);
      continue;
    }
    sys.rhs = frame == AUTOBAL_ROTOR_FIXED ? autobal_rotor_rhs : autobal_rotor_rhs_rotating;
    sys.jac = NULL;
    sys.dim = dim;
    sys.params = rot;
    ob.rotor = rot;
    ob.frame = frame;
    ob.ro = ro;
    autobal_transient_set_observer(tr, rotor_observer, &ob);
    ro->status = autobal_rotor_initial_state(rot, frame, 0.0, ro->y_final, dim);
    if (ro->status == AUTOBAL_SUCCESS) ro->status = autobal_transient_run(tr, &sys, 0.0, t1, ro->y_final, &ro->t_reached);
    autobal_transient_get_stats(tr, &ro->stats);
    autobal_transient_free(tr);
    autobal_rotor_free(rot);
  }
}

/* ---- comparison ----------------------------------------------------------------------- */
static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int same_bits(const double *a, const double *b, size_t n) { return memcmp(a, b, n * sizeof *a) == 0; }

/* Counters and times of the statistics (wall time excluded: it is the only field allowed to
 * differ). */
static int same_stats(const autobal_transient_stats *a, const autobal_transient_stats *b) {
  return a->steps == b->steps && a->rejected == b->rejected && a->rhs_evals == b->rhs_evals &&
         a->jac_evals == b->jac_evals && a->fd_jac_evals == b->fd_jac_evals && a->events == b->events &&
         a->event_steps == b->event_steps && a->observer_calls == b->observer_calls &&
         same_bits(&a->t_start, &b->t_start, 1) && same_bits(&a->t_end, &b->t_end, 1) &&
         same_bits(&a->h_last, &b->h_last, 1) && same_bits(&a->h_min_used, &b->h_min_used, 1) &&
         same_bits(&a->h_max_used, &b->h_max_used, 1) && a->status == b->status &&
         a->stop_reason == b->stop_reason && a->user_code == b->user_code && a->event_index == b->event_index;
}

static int same_result(const autobal_pendulum_result *a, const autobal_pendulum_result *b) {
  return same_bits(a->coef, b->coef, AUTOBAL_PENDULUM_NCOEF) &&
         same_bits(a->root_re, b->root_re, AUTOBAL_PENDULUM_ORDER) &&
         same_bits(a->root_im, b->root_im, AUTOBAL_PENDULUM_ORDER) &&
         same_bits(a->eig_re, b->eig_re, AUTOBAL_PENDULUM_ORDER) &&
         same_bits(a->eig_im, b->eig_im, AUTOBAL_PENDULUM_ORDER) && same_bits(&a->max_real, &b->max_real, 1) &&
         same_bits(&a->max_real_eig, &b->max_real_eig, 1) && same_bits(&a->mismatch, &b->mismatch, 1) &&
         same_bits(&a->mismatch_rel, &b->mismatch_rel, 1) && a->verdict == b->verdict &&
         a->verdict_roots == b->verdict_roots && a->verdicts_agree == b->verdicts_agree && a->n_rhp == b->n_rhp &&
         a->zero_root_deflated == b->zero_root_deflated && a->undamped == b->undamped &&
         a->undamped_verdict == b->undamped_verdict && a->cond7.applicable == b->cond7.applicable &&
         a->cond7.predicts_stable == b->cond7.predicts_stable && same_bits(&a->cond7.small, &b->cond7.small, 1) &&
         a->cond8.predicts_stable == b->cond8.predicts_stable && same_bits(&a->cond8.small, &b->cond8.small, 1) &&
         a->cond9.predicts_stable == b->cond9.predicts_stable && same_bits(&a->cond9.small, &b->cond9.small, 1);
}

static int same_crit(const autobal_pendulum_crit_set *a, const autobal_pendulum_crit_set *b) {
  size_t i;
  if (a->n != b->n || a->n_stable != b->n_stable || a->n > AUTOBAL_PENDULUM_MAX_CRIT ||
      a->n_stable > AUTOBAL_PENDULUM_MAX_CRIT + 1)
    return 0;
  for (i = 0; i < a->n; i++)
    if (a->kind[i] != b->kind[i]) return 0;
  return same_bits(a->R_w, b->R_w, a->n) && same_bits(a->stable_lo, b->stable_lo, a->n_stable) &&
         same_bits(a->stable_hi, b->stable_hi, a->n_stable);
}

static int same_pend(const pend_out *a, const pend_out *b) {
  size_t i;
  for (i = 0; i < A_NPTS; i++)
    if (a->status[i] != b->status[i] || (a->status[i] == AUTOBAL_SUCCESS && !same_result(&a->res[i], &b->res[i])))
      return 0;
  for (i = 0; i < A_NCRIT; i++)
    if (a->crit_status[i] != b->crit_status[i] || !same_crit(&a->crit[i], &b->crit[i])) return 0;
  return a->map_status == b->map_status && memcmp(a->map_verdict, b->map_verdict, sizeof a->map_verdict) == 0 &&
         same_bits(a->map_max_real, b->map_max_real, A_MAP_NRM * A_MAP_NRW);
}

static int same_ptr(const ptr_out *a, const ptr_out *b) {
  size_t r;
  for (r = 0; r < B_RUNS; r++) {
    const run_out *x = &a->run[r], *y = &b->run[r];
    if (x->status != y->status || x->n_out != y->n_out || x->overflow != y->overflow || x->fired != y->fired ||
        !same_bits(&x->t_reached, &y->t_reached, 1) || !same_bits(x->y_final, y->y_final, B_DIM) ||
        !same_stats(&x->stats, &y->stats) || !same_bits(x->tt, y->tt, x->n_out) ||
        !same_bits(x->yy, y->yy, x->n_out * B_DIM))
      return 0;
    if (x->fired == 1 && (x->hit.index != y->hit.index || !same_bits(&x->hit.t, &y->hit.t, 1) ||
                          !same_bits(&x->hit.t_start, &y->hit.t_start, 1) || x->hit.direction != y->hit.direction))
      return 0;
  }
  return 1;
}

static int same_rot(const rot_out *a, const rot_out *b) {
  size_t r;
  for (r = 0; r < C_RUNS; r++) {
    const rot_run *x = &a->run[r], *y = &b->run[r];
    if (x->status != y->status || x->alloc_status != y->alloc_status || x->n_out != y->n_out ||
        x->nvals != y->nvals || x->overflow != y->overflow || !same_bits(&x->t_reached, &y->t_reached, 1) ||
        !same_bits(x->y_final, y->y_final, 64) || !same_stats(&x->stats, &y->stats) ||
        !same_bits(x->tt, y->tt, x->n_out) || !same_bits(x->out, y->out, x->n_out * C_MAXOUT))
      return 0;
  }
  return 1;
}

/* ---- threads -------------------------------------------------------------------------- */
typedef struct thread_job {
  int reverse; /* run C, B, A instead of A, B, C */
  pthread_barrier_t *barrier;
  pend_out *pend;
  ptr_out *ptr;
  rot_out *rot;
} thread_job;

static void *thread_main(void *arg) {
  thread_job *j = arg;
  pthread_barrier_wait(j->barrier);
  if (!j->reverse) {
    work_pendulum(j->pend);
    work_pendulum_transient(j->ptr);
    work_rotor_transient(j->rot);
  } else {
    work_rotor_transient(j->rot);
    work_pendulum_transient(j->ptr);
    work_pendulum(j->pend);
  }
  return NULL;
}

int main(void) {
  pend_out *pend_ref, *pend[2];
  ptr_out *ptr_ref, *ptr[2];
  rot_out *rot_ref, *rot[2];
  int round, t, n_stable = 0, n_unstable = 0;
  double t0, t1, t2, t3;
  size_t i;
  char what[160];

  gsl_set_error_handler_off(); /* once, before any thread: the host's job (status.h) */
  pend_ref = malloc(sizeof *pend_ref);
  ptr_ref = malloc(sizeof *ptr_ref);
  rot_ref = malloc(sizeof *rot_ref);
  for (t = 0; t < 2; t++) {
    pend[t] = malloc(sizeof *pend[t]);
    ptr[t] = malloc(sizeof *ptr[t]);
    rot[t] = malloc(sizeof *rot[t]);
  }
  if (!pend_ref || !ptr_ref || !rot_ref || !pend[0] || !pend[1] || !ptr[0] || !ptr[1] || !rot[0] || !rot[1]) {
    printf("FAIL out of memory\n");
    return 1;
  }

  /* serial reference */
  t0 = now();
  work_pendulum(pend_ref);
  t1 = now();
  work_pendulum_transient(ptr_ref);
  t2 = now();
  work_rotor_transient(rot_ref);
  t3 = now();
  printf("serial reference: pendulum analysis %.3f s, pendulum transients %.3f s, rotor transients %.3f s\n", t1 - t0,
         t2 - t1, t3 - t2);

  /* the reference is a real result, not an empty one */
  for (i = 0; i < A_NPTS; i++) {
    if (pend_ref->status[i] != AUTOBAL_SUCCESS) continue;
    n_stable += pend_ref->res[i].verdict == AUTOBAL_VERDICT_STABLE;
    n_unstable += pend_ref->res[i].verdict == AUTOBAL_VERDICT_UNSTABLE;
  }
  for (i = 0; i < A_NPTS; i++)
    if (pend_ref->status[i] != AUTOBAL_SUCCESS) break;
  CHECK("reference: every analysis point succeeded", i == A_NPTS);
  CHECK("reference: the grid has stable and unstable points", n_stable > 0 && n_unstable > 0);
  for (i = 0; i < A_NCRIT; i++) {
    snprintf(what, sizeof what, "reference: critical speeds %zu found", i);
    CHECK(what, pend_ref->crit_status[i] == AUTOBAL_SUCCESS && autobal_pendulum_crit_count(&pend_ref->crit[i]) >= 1);
  }
  CHECK_STATUS("reference: map", pend_ref->map_status, AUTOBAL_SUCCESS);
  for (i = 0; i < B_RUNS; i++) {
    const run_out *ro = &ptr_ref->run[i];
    snprintf(what, sizeof what, "reference: pendulum transient %zu reached t1 with %lu steps, %zu outputs", i,
             ro->stats.steps, ro->n_out);
    CHECK(what, ro->status == AUTOBAL_SUCCESS && ro->stats.steps > 10 && ro->n_out == B_NOUT - 1 && !ro->overflow);
  }
  CHECK("reference: pendulum transient fd Jacobian used by bsimp", ptr_ref->run[2].stats.fd_jac_evals > 0);
  CHECK("reference: dwell event fired (the balancer balanced)", ptr_ref->run[0].fired == 1);
  for (i = 0; i < C_RUNS; i++) {
    const rot_run *ro = &rot_ref->run[i];
    snprintf(what, sizeof what, "reference: rotor transient %zu reached t1 with %lu steps, %zu outputs", i,
             ro->stats.steps, ro->n_out);
    CHECK(what, ro->status == AUTOBAL_SUCCESS && ro->stats.steps > 10 && ro->n_out == C_NOUT - 1 && !ro->overflow);
  }
  /* the two frames are two implementations of the same motion: close, not identical */
  CHECK_CLOSE("reference: rotor amp_G at t1, fixed vs rotating frame", rot_ref->run[0].out[(C_NOUT - 2) * C_MAXOUT],
              rot_ref->run[1].out[(C_NOUT - 2) * C_MAXOUT], 1e-4, 1e-12);

  /* two threads at once, several rounds */
  for (round = 0; round < ROUNDS; round++) {
    pthread_t th[2];
    pthread_barrier_t barrier;
    thread_job job[2];
    int created[2] = {0, 0};
    pthread_barrier_init(&barrier, NULL, 2);
    for (t = 0; t < 2; t++) {
      memset(pend[t], 0xA5, sizeof *pend[t]); /* poison: stale results cannot pass */
      memset(ptr[t], 0xA5, sizeof *ptr[t]);
      memset(rot[t], 0xA5, sizeof *rot[t]);
      job[t].reverse = t;
      job[t].barrier = &barrier;
      job[t].pend = pend[t];
      job[t].ptr = ptr[t];
      job[t].rot = rot[t];
    }
    t0 = now();
    for (t = 0; t < 2; t++) created[t] = pthread_create(&th[t], NULL, thread_main, &job[t]) == 0;
    if (!created[0] || !created[1]) {
      printf("FAIL pthread_create\n");
      return 1;
    }
    for (t = 0; t < 2; t++) pthread_join(th[t], NULL);
    printf("round %d: two threads, %.3f s wall\n", round, now() - t0);
    pthread_barrier_destroy(&barrier);
    for (t = 0; t < 2; t++) {
      snprintf(what, sizeof what, "round %d thread %d: pendulum analysis, critical speeds, map bitwise = serial", round, t);
      CHECK(what, same_pend(pend[t], pend_ref));
      snprintf(what, sizeof what, "round %d thread %d: pendulum transients (rk8pd+dwell, rk4imp, bsimp) bitwise = serial",
               round, t);
      CHECK(what, same_ptr(ptr[t], ptr_ref));
      snprintf(what, sizeof what, "round %d thread %d: rotor transients (fixed, rotating) bitwise = serial", round, t);
      CHECK(what, same_rot(rot[t], rot_ref));
    }
  }
  /* the comparison itself can fail: a one-ulp change is detected */
  {
    double x = ptr_ref->run[0].yy[B_DIM * 5 + 1];
    ptr[0]->run[0] = ptr_ref->run[0];
    ptr[0]->run[0].yy[B_DIM * 5 + 1] = nextafter(x, INFINITY);
    CHECK("comparison detects a one-ulp difference", !same_ptr(ptr[0], ptr_ref));
  }

  free(pend_ref);
  free(ptr_ref);
  free(rot_ref);
  for (t = 0; t < 2; t++) {
    free(pend[t]);
    free(ptr[t]);
    free(rot[t]);
  }
  return check_summary();
}
