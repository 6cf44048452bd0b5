/* bench_sundials.c: autobal's transient driver against SUNDIALS (CVODE Adams
 * and ARKODE explicit Runge-Kutta, called from C) on the same right-hand
 * side, compared at matched error.  Built by bench/perf/CMakeLists.txt when
 * SUNDIALS (Debian libsundials-dev, 6.x) is found; run by perf.py.
 *
 *   bench_sundials all
 *
 * Problem: the pendulum transient of bench/bench_pendulum.c (R_w = 3,
 * R_m = 0.1, H = 0.05, h = 0.1, psi0 = 0.5, from rest, tau in [0, 100],
 * final state only), right-hand side autobal_pendulum_motion_rhs for all
 * solvers (SUNDIALS through a two-line N_Vector wrapper).  Reference: autobal
 * rk8pd at rtol = atol = 1e-14.  Error = max over the 8 components of
 * |y - y_ref| at tau = 100.  Solvers (rtol = atol = tol on a grid of
 * tolerances; SUNDIALS' error norm is a weighted RMS, GSL's a maximum, so
 * errors, not tolerances, are matched):
 *   autobal rk8pd      autobal_transient_run (GSL rk8pd, the driver's own loop)
 *   CVODE Adams        CV_ADAMS with the fixed-point nonlinear solver
 *                      (non-stiff problem: no Jacobian, no linear solver)
 *   ARKODE ERK o8      ERKStep, method order 8 (ERKStepSetOrder(8))
 *   ARKODE ERK o4      ERKStep, default order 4
 * For each autobal tolerance the cheapest run of each SUNDIALS solver whose
 * error is at most autobal's is found; the ratio of their times is printed
 * ("ratios": time of SUNDIALS / time of autobal, > 1: autobal faster).
 * Times: best of REPS runs (3 for runs longer than 20 ms; wall time,
 * CLOCK_MONOTONIC), solver set-up included for neither (SUNDIALS is re-initialised with *ReInit between runs, outside
 * the timed part).  One JSON object on stdout. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <gsl/gsl_errno.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "autobal/pendulum.h"
#include "autobal/transient.h"

#define REPS 21
#define T1 100.0

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int f_sun(realtype t, N_Vector y, N_Vector ydot, void *user) {
  return autobal_pendulum_motion_rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), user);
}

typedef struct {
  const char *solver;
  double tol, seconds, err;
  long rhs_evals;
} run_t;

static double maxerr(const double *y, const double *ref) {
  double e = 0.0;
  int i;
  for (i = 0; i < 8; i++)
    if (fabs(y[i] - ref[i]) > e) e = fabs(y[i] - ref[i]);
  return e;
}

static int run_autobal(autobal_pendulum_motion *m, double tol, int reps, double *y, run_t *r) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys = {autobal_pendulum_motion_rhs, autobal_pendulum_motion_jac, 8, m};
  autobal_transient_stats st;
  autobal_error err;
  autobal_transient *tr;
  int k;
  o.stepper = "rk8pd";
  o.rtol = o.atol = tol;
  tr = autobal_transient_alloc(8, &o, &err);
  if (!tr) return -1;
  r->seconds = INFINITY;
  for (k = 0; k < reps; k++) {
    double t;
    memset(y, 0, 8 * sizeof(double));
    t = now();
    if (autobal_transient_run(tr, &sys, 0.0, T1, y, NULL) != AUTOBAL_SUCCESS) {
      autobal_transient_free(tr);
      return -1;
    }
    t = now() - t;
    if (t < r->seconds) r->seconds = t;
  }
  autobal_transient_get_stats(tr, &st);
  r->rhs_evals = (long)st.rhs_evals;
  r->solver = "autobal rk8pd";
  r->tol = tol;
  autobal_transient_free(tr);
  return 0;
}

/* kind 0: CVODE Adams; 8 or 4: ARKODE ERK of that order */
static int run_sundials(SUNContext ctx, autobal_pendulum_motion *m, int kind, double tol, int reps,
                        double *yout, run_t *r) {
  N_Vector y = N_VNew_Serial(8, ctx);
  SUNNonlinearSolver nls = NULL;
  void *mem = NULL;
  long nfe = 0;
  int k, ok = 1;
  double t;
  if (!y) return -1;
  N_VConst(0.0, y);
  if (kind == 0) {
    mem = CVodeCreate(CV_ADAMS, ctx);
    ok = mem && CVodeInit(mem, f_sun, 0.0, y) == CV_SUCCESS &&
         CVodeSStolerances(mem, tol, tol) == CV_SUCCESS && CVodeSetUserData(mem, m) == CV_SUCCESS &&
         CVodeSetMaxNumSteps(mem, 100000000L) == CV_SUCCESS;
    nls = SUNNonlinSol_FixedPoint(y, 0, ctx);
    ok = ok && nls && CVodeSetNonlinearSolver(mem, nls) == CV_SUCCESS;
  } else {
    mem = ERKStepCreate(f_sun, 0.0, y, ctx);
    ok = mem && ERKStepSStolerances(mem, tol, tol) == ARK_SUCCESS &&
         ERKStepSetUserData(mem, m) == ARK_SUCCESS && ERKStepSetOrder(mem, kind) == ARK_SUCCESS &&
         ERKStepSetMaxNumSteps(mem, 100000000L) == ARK_SUCCESS;
  }
  r->seconds = INFINITY;
  for (k = 0; k < reps && ok; k++) {
    double tt;
    if (k == 1 && r->seconds > 0.02) reps = 3; /* long runs: best of 3 */
    N_VConst(0.0, y);
    if (kind == 0) ok = CVodeReInit(mem, 0.0, y) == CV_SUCCESS;
    else ok = ERKStepReInit(mem, f_sun, 0.0, y) == ARK_SUCCESS;
    if (!ok) break;
    tt = now();
    if (kind == 0) ok = CVode(mem, T1, y, &t, CV_NORMAL) >= 0;
    else ok = ERKStepEvolve(mem, T1, y, &t, ARK_NORMAL) >= 0;
    tt = now() - tt;
    if (tt < r->seconds) r->seconds = tt;
  }
  if (ok) {
    if (kind == 0) CVodeGetNumRhsEvals(mem, &nfe);
    else ERKStepGetNumRhsEvals(mem, &nfe);
    memcpy(yout, N_VGetArrayPointer(y), 8 * sizeof(double));
  }
  r->rhs_evals = nfe;
  r->tol = tol;
  r->solver = kind == 0 ? "CVODE Adams" : kind == 8 ? "ARKODE ERK order 8" : "ARKODE ERK order 4";
  if (kind == 0) CVodeFree(&mem);
  else ERKStepFree(&mem);
  if (nls) SUNNonlinSolFree(nls);
  N_VDestroy(y);
  return ok ? 0 : -1;
}

int main(int argc, char **argv) {
  static const double atols[] = {1e-6, 1e-8, 1e-10};
  static const double stols[] = {1e-4, 3e-5, 1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9,
                                 1e-9, 3e-10, 1e-10, 3e-11, 1e-11, 3e-12, 1e-12, 3e-13, 1e-13};
  static const int kinds[] = {0, 8, 4};
  enum { NA = sizeof atols / sizeof atols[0], NS = sizeof stols / sizeof stols[0], NK = 3 };
  autobal_pendulum_params p = {3.0, 0.1, 0.05, 0.1, 0.5};
  autobal_pendulum_motion m;
  autobal_error err;
  SUNContext ctx;
  run_t ra[NA], rs[NK][NS];
  double ref[8], y[8];
  int i, j, kk, first = 1;
  (void)argv;
  if (argc != 2) {
    fprintf(stderr, "usage: bench_sundials all\n");
    return 2;
  }
  gsl_set_error_handler_off();
  if (autobal_pendulum_motion_init(&m, &p, &err)) return 1;
  if (SUNContext_Create(NULL, &ctx)) return 1;
  {
    run_t rr;
    if (run_autobal(&m, 1e-14, 1, ref, &rr)) return 1;
  }
  for (i = 0; i < NA; i++) {
    if (run_autobal(&m, atols[i], REPS, y, &ra[i])) return 1;
    ra[i].err = maxerr(y, ref);
  }
  for (kk = 0; kk < NK; kk++)
    for (j = 0; j < NS; j++) {
      if (run_sundials(ctx, &m, kinds[kk], stols[j], REPS, y, &rs[kk][j])) {
        rs[kk][j].seconds = INFINITY;
        rs[kk][j].err = INFINITY;
      } else {
        rs[kk][j].err = maxerr(y, ref);
      }
    }
  printf("{\"runs\": [");
  for (i = 0; i < NA; i++) {
    printf("%s{\"solver\": \"%s\", \"tol\": %g, \"seconds\": %.6g, \"rhs_evals\": %ld, \"err\": %.4g}",
           first ? "" : ", ", ra[i].solver, ra[i].tol, ra[i].seconds, ra[i].rhs_evals, ra[i].err);
    first = 0;
    for (kk = 0; kk < NK; kk++) {
      /* the cheapest run of this solver with error <= autobal's */
      int best = -1;
      for (j = 0; j < NS; j++)
        if (rs[kk][j].err <= ra[i].err && (best < 0 || rs[kk][j].seconds < rs[kk][best].seconds))
          best = j;
      if (best >= 0)
        printf(", {\"solver\": \"%s\", \"tol\": %g, \"seconds\": %.6g, \"rhs_evals\": %ld, "
               "\"err\": %.4g, \"vs_autobal_tol\": %g}",
               rs[kk][best].solver, rs[kk][best].tol, rs[kk][best].seconds, rs[kk][best].rhs_evals,
               rs[kk][best].err, ra[i].tol);
    }
  }
  printf("], \"ratios\": [");
  first = 1;
  for (kk = 0; kk < NK; kk++) {
    /* smallest ratio over the autobal tolerances (the least favourable) */
    double worst = INFINITY;
    for (i = 0; i < NA; i++) {
      int best = -1;
      for (j = 0; j < NS; j++)
        if (rs[kk][j].err <= ra[i].err && (best < 0 || rs[kk][j].seconds < rs[kk][best].seconds))
          best = j;
      if (best >= 0 && rs[kk][best].seconds / ra[i].seconds < worst)
        worst = rs[kk][best].seconds / ra[i].seconds;
    }
    printf("%s[\"%s\", %.4g]", first ? "" : ", ",
           kinds[kk] == 0 ? "CVODE Adams" : kinds[kk] == 8 ? "ARKODE ERK order 8" : "ARKODE ERK order 4",
           worst);
    first = 0;
  }
  printf("]}\n");
  SUNContext_Free(&ctx);
  return 0;
}
