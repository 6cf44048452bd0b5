/* test_transient.c: the model-agnostic gsl_odeiv2 driver (src/transient/transient.c).
 *
 * Known answers: the harmonic oscillator y'' = -y (y = cos t), exponential
 * decay y' = -y, a stiff linear equation y' = -L (y - cos t) - sin t with
 * y = cos t + (y0 - 1) e^{-L t}; event times pi/2 + k pi, 2pi/3 (+ dwell),
 * ln 2; rhs-evaluation counts against the test's own counter.  Every error
 * path is provoked: bad options, bad arguments, failing or non-finite rhs,
 * failing Jacobian, NaN event, max steps, h_min, step-size underflow,
 * cancellation by the progress callback, stop by the observer. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/transient.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- test systems ---------------------------------------------------------- */

typedef struct osc_ctx {
  unsigned long calls; /* our own count of rhs calls */
  unsigned long jac_calls;
  double fail_after; /* rhs returns -7 for t > fail_after */
  double nan_after;  /* rhs returns NaN for t > nan_after */
  double jac_fail_after;
} osc_ctx;

static int osc_rhs(double t, const double y[], double f[], void *p) {
  osc_ctx *c = (osc_ctx *)p;
  c->calls++;
  if (t > c->fail_after) return -7;
  f[0] = y[1];
  f[1] = -y[0];
  if (t > c->nan_after) f[1] = NAN;
  return 0;
}

static int osc_jac(double t, const double y[], double *J, double dfdt[], void *p) {
  osc_ctx *c = (osc_ctx *)p;
  (void)y;
  c->jac_calls++;
  if (t > c->jac_fail_after) return 3;
  J[0] = 0.0;
  J[1] = 1.0;
  J[2] = -1.0;
  J[3] = 0.0;
  dfdt[0] = dfdt[1] = 0.0;
  return 0;
}

static void osc_init(osc_ctx *c) {
  c->calls = 0;
  c->jac_calls = 0;
  c->fail_after = INFINITY;
  c->nan_after = INFINITY;
  c->jac_fail_after = INFINITY;
}

/* stiff: y' = -L (y - cos t) - sin t, exact y = cos t + (y0 - 1) exp(-L t) */
static const double STIFF_L = 1e4;
static int stiff_rhs(double t, const double y[], double f[], void *p) {
  unsigned long *calls = (unsigned long *)p;
  (*calls)++;
  f[0] = -STIFF_L * (y[0] - cos(t)) - sin(t);
  return 0;
}
static int stiff_jac(double t, const double y[], double *J, double dfdt[], void *p) {
  (void)y;
  (void)p;
  J[0] = -STIFF_L;
  dfdt[0] = -STIFF_L * sin(t) - cos(t);
  return 0;
}

static int decay_rhs(double t, const double y[], double f[], void *p) {
  (void)t;
  (void)p;
  f[0] = -y[0];
  return 0;
}

static int zero_rhs(double t, const double y[], double f[], void *p) {
  (void)t;
  (void)y;
  (void)p;
  f[0] = 0.0;
  return 0;
}

/* derivative that flips sign on every call: no step size meets a tolerance */
static int flip_rhs(double t, const double y[], double f[], void *p) {
  unsigned long *calls = (unsigned long *)p;
  (void)t;
  (void)y;
  (*calls)++;
  f[0] = (*calls % 2) ? 1e10 : -1e10;
  return 0;
}

/* ---- callbacks ------------------------------------------------------------------ */

typedef struct obs_rec {
  int n;
  double t[64];
  double y0[64];
  double stop_at; /* return 5 when t >= stop_at */
} obs_rec;

static int observer(double t, const double y[], void *user) {
  obs_rec *r = (obs_rec *)user;
  if (r->n < 64) {
    r->t[r->n] = t;
    r->y0[r->n] = y[0];
  }
  r->n++;
  return t >= r->stop_at ? 5 : 0;
}

typedef struct prog_rec {
  int n;
  double first, last, min_inc;
  int monotone;
  double cancel_at;
} prog_rec;

static int progress(double f, void *user) {
  prog_rec *r = (prog_rec *)user;
  if (r->n == 0) {
    r->first = f;
    r->min_inc = INFINITY;
    r->monotone = 1;
  } else {
    if (f < r->last) r->monotone = 0;
    if (f < 1.0 && f - r->last < r->min_inc) r->min_inc = f - r->last;
  }
  r->last = f;
  r->n++;
  return f >= r->cancel_at ? 1 : 0;
}

typedef struct hit_rec {
  int n;
  autobal_transient_event_hit hit[16];
  double y0[16], y1[16];
  int stop_on; /* handler returns 9 on hit number stop_on (0-based), -1 never */
} hit_rec;

static int handler(const autobal_transient_event_hit *h, const double y[], void *user) {
  hit_rec *r = (hit_rec *)user;
  int k = r->n;
  if (k < 16) {
    r->hit[k] = *h;
    r->y0[k] = y[0];
    r->y1[k] = y[1];
  }
  r->n++;
  return k == r->stop_on ? 9 : 0;
}

static double g_y0(double t, const double y[], void *user) {
  (void)t;
  (void)user;
  return y[0];
}
static double g_y0_dim1(double t, const double y[], void *user) {
  (void)t;
  (void)user;
  return y[0];
}
static double g_time_minus(double t, const double y[], void *user) {
  (void)y;
  return t - *(const double *)user;
}
static double g_nan(double t, const double y[], void *user) {
  (void)y;
  (void)user;
  return t > 1.0 ? NAN : 1.0;
}

static int hit_record_y1_dim1(const autobal_transient_event_hit *h, const double y[], void *user) {
  hit_rec *r = (hit_rec *)user;
  if (r->n < 16) {
    r->hit[r->n] = *h;
    r->y0[r->n] = y[0];
  }
  r->n++;
  return 0;
}

/* ---- tests -------------------------------------------------------------------------- */

static void test_options(void) {
  autobal_error err;
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  CHECK_STATUS("defaults validate", autobal_transient_options_validate(&o, &err), AUTOBAL_SUCCESS);
  CHECK("default stepper rk8pd", strcmp(o.stepper, "rk8pd") == 0);

  o.stepper = "rk9";
  CHECK_STATUS("unknown stepper", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  CHECK_MSG("unknown stepper named", err.message, "rk9");
  CHECK_MSG("unknown stepper: valid names listed", err.message, "msbdf");
  tr = autobal_transient_alloc(2, &o, &err);
  CHECK("alloc with unknown stepper fails", tr == NULL);
  CHECK_STATUS("alloc with unknown stepper status", err.status, AUTOBAL_EINVAL);

  o = autobal_transient_options_default();
  o.rtol = 0.0;
  CHECK_STATUS("rtol = 0", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  CHECK_MSG("rtol = 0 message", err.message, "rtol");
  o.rtol = 1e-300;
  o.atol = 1e-300;
  CHECK_STATUS("rtol = atol = 1e-300 (below double rounding)", autobal_transient_options_validate(&o, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("rtol = 1e-300 message names rtol", err.message, "rtol");
  CHECK_MSG("rtol = 1e-300 message gives the bound", err.message, "8.88");
  o.rtol = 4.0 * DBL_EPSILON;
  CHECK_STATUS("rtol = 4 DBL_EPSILON is accepted", autobal_transient_options_validate(&o, &err), AUTOBAL_SUCCESS);
  o = autobal_transient_options_default();
  o.rtol = NAN;
  CHECK_STATUS("rtol = NaN", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  o = autobal_transient_options_default();
  o.atol = INFINITY;
  CHECK_STATUS("atol = inf", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  CHECK_MSG("atol = inf message", err.message, "atol");
  o.atol = -1e-9;
  CHECK_STATUS("atol < 0", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  o = autobal_transient_options_default();
  o.h_max = -1.0;
  CHECK_STATUS("h_max < 0", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  CHECK_MSG("h_max message", err.message, "h_max");
  o = autobal_transient_options_default();
  o.h_max = 0.1;
  o.h_min = 0.2;
  CHECK_STATUS("h_min > h_max", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  CHECK_MSG("h_min > h_max message", err.message, "h_min");
  o = autobal_transient_options_default();
  o.h_max = 0.1;
  o.h_init = 0.2;
  CHECK_STATUS("h_init > h_max", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  o = autobal_transient_options_default();
  o.dt_out = -0.5;
  CHECK_STATUS("dt_out < 0", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  CHECK_MSG("dt_out message", err.message, "dt_out");
  o = autobal_transient_options_default();
  o.event_tol = 0.0;
  CHECK_STATUS("event_tol = 0", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  o = autobal_transient_options_default();
  o.progress_step = 0.0;
  CHECK_STATUS("progress_step = 0", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);
  o.progress_step = 1.5;
  CHECK_STATUS("progress_step = 1.5", autobal_transient_options_validate(&o, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("progress_step message", err.message, "progress_step");
  o = autobal_transient_options_default();
  o.progress_wall = -1.0;
  CHECK_STATUS("progress_wall < 0", autobal_transient_options_validate(&o, &err), AUTOBAL_EINVAL);

  tr = autobal_transient_alloc(0, NULL, &err);
  CHECK("alloc dim 0 fails", tr == NULL);
  CHECK_MSG("alloc dim 0 message", err.message, "dim");

  tr = autobal_transient_alloc(2, NULL, &err);
  CHECK("alloc with defaults", tr != NULL);
  o = autobal_transient_options_default();
  o.stepper = "nope";
  CHECK_STATUS("set_options rejects a bad stepper", autobal_transient_set_options(tr, &o),
               AUTOBAL_EINVAL);
  CHECK_MSG("set_options message", autobal_transient_errmsg(tr), "nope");
  CHECK("old options kept", strcmp(autobal_transient_get_options(tr).stepper, "rk8pd") == 0);
  o.stepper = "msbdf";
  CHECK_STATUS("set_options msbdf", autobal_transient_set_options(tr, &o), AUTOBAL_SUCCESS);
  CHECK("new stepper", strcmp(autobal_transient_get_options(tr).stepper, "msbdf") == 0);
  CHECK_STATUS("add_event NULL g", autobal_transient_add_event(tr, NULL, NULL, 0, 0),
               AUTOBAL_EINVAL);
  CHECK_STATUS("add_event direction 2", autobal_transient_add_event(tr, g_y0, NULL, 2, 0),
               AUTOBAL_EINVAL);
  CHECK_STATUS("dwell duration < 0",
               autobal_transient_add_dwell_event(tr, g_y0, NULL, 0.0, -1.0, 0), AUTOBAL_EINVAL);
  CHECK_MSG("dwell duration message", autobal_transient_errmsg(tr), "duration");
  CHECK_STATUS("dwell threshold NaN",
               autobal_transient_add_dwell_event(tr, g_y0, NULL, NAN, 1.0, 0), AUTOBAL_EINVAL);
  CHECK_STATUS("event_result bad index", autobal_transient_event_result(tr, 3, NULL, NULL),
               AUTOBAL_EINVAL);
  autobal_transient_free(tr);
  autobal_transient_free(NULL);
  CHECK("errmsg(NULL) is a string", autobal_transient_errmsg(NULL)[0] == '\0');
}

static void test_bad_run_args(void) {
  autobal_transient *tr = autobal_transient_alloc(2, NULL, NULL);
  osc_ctx c;
  autobal_transient_system sys = {osc_rhs, NULL, 2, &c};
  autobal_transient_system sys3 = {osc_rhs, NULL, 3, &c};
  autobal_transient_system sys0 = {NULL, NULL, 2, &c};
  double y[2] = {1.0, 0.0}, tr_t = -1.0;
  osc_init(&c);
  CHECK_STATUS("run NULL system", autobal_transient_run(tr, NULL, 0, 1, y, NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("run NULL rhs", autobal_transient_run(tr, &sys0, 0, 1, y, NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("run dim mismatch", autobal_transient_run(tr, &sys3, 0, 1, y, NULL),
               AUTOBAL_EINVAL);
  CHECK_MSG("dim mismatch message", autobal_transient_errmsg(tr), "dimension");
  CHECK_STATUS("run t1 < t0", autobal_transient_run(tr, &sys, 1, 0, y, &tr_t), AUTOBAL_EINVAL);
  CHECK_MSG("t1 < t0 message", autobal_transient_errmsg(tr), "t1");
  CHECK_STATUS("run t1 = NaN", autobal_transient_run(tr, &sys, 0, NAN, y, NULL), AUTOBAL_EINVAL);
  y[1] = NAN;
  CHECK_STATUS("run NaN state", autobal_transient_run(tr, &sys, 0, 1, y, NULL), AUTOBAL_EINVAL);
  CHECK_MSG("NaN state message", autobal_transient_errmsg(tr), "y[1]");
  CHECK("y untouched after EINVAL", y[0] == 1.0 && isnan(y[1]));
  CHECK("rhs never called on EINVAL", c.calls == 0);
  CHECK_STATUS("run NULL handle", autobal_transient_run(NULL, &sys, 0, 1, y, NULL),
               AUTOBAL_EINVAL);
  /* t0 == t1: observer once, success, state unchanged */
  {
    obs_rec r;
    memset(&r, 0, sizeof r);
    r.stop_at = INFINITY;
    y[0] = 1.0;
    y[1] = 0.0;
    autobal_transient_set_observer(tr, observer, &r);
    CHECK_STATUS("t0 == t1", autobal_transient_run(tr, &sys, 2.0, 2.0, y, &tr_t), AUTOBAL_SUCCESS);
    CHECK("t0 == t1: observer once at t0", r.n == 1 && r.t[0] == 2.0);
    CHECK("t0 == t1: state unchanged", y[0] == 1.0 && y[1] == 0.0 && tr_t == 2.0);
  }
  autobal_transient_free(tr);
}

/* every stepper on the oscillator: accuracy vs cos t, rhs-call bookkeeping */
static void test_all_steppers(void) {
  static const struct {
    const char *name;
    double tol, t1, factor;
    int implicit;
  } cases[] = {
      {"rk2", 1e-7, 3.0, 1e3, 0},    {"rk4", 1e-9, 3.0, 1e3, 0},
      {"rkf45", 1e-9, 3.0, 1e3, 0},  {"rkck", 1e-10, 3.0, 1e3, 0},
      {"rk8pd", 1e-12, 3.0, 1e3, 0}, {"rk1imp", 1e-6, 1.0, 1e3, 1},
      {"rk2imp", 1e-8, 3.0, 1e3, 1}, {"rk4imp", 1e-10, 3.0, 1e3, 1},
      {"bsimp", 1e-10, 3.0, 1e3, 1}, {"msadams", 1e-10, 3.0, 1e3, 0},
      {"msbdf", 1e-9, 3.0, 1e3, 1},
  };
  size_t k;
  for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    int with_jac;
    for (with_jac = 0; with_jac <= cases[k].implicit; with_jac++) {
      autobal_transient_options o = autobal_transient_options_default();
      autobal_transient *tr;
      autobal_transient_stats st;
      osc_ctx c;
      autobal_transient_system sys = {osc_rhs, with_jac ? osc_jac : NULL, 2, &c};
      double y[2] = {1.0, 0.0}, t_end = 0.0;
      char what[160];
      int rc;
      o.stepper = cases[k].name;
      o.rtol = cases[k].tol;
      o.atol = cases[k].tol;
      tr = autobal_transient_alloc(2, &o, NULL);
      osc_init(&c);
      rc = autobal_transient_run(tr, &sys, 0.0, cases[k].t1, y, &t_end);
      autobal_transient_get_stats(tr, &st);
      snprintf(what, sizeof what, "%s%s: status", cases[k].name, with_jac ? " (analytic jac)" : "");
      CHECK_STATUS(what, rc, AUTOBAL_SUCCESS);
      snprintf(what, sizeof what, "%s%s: y(t1) = cos t1 (tol %g x %g)", cases[k].name,
               with_jac ? " (jac)" : "", cases[k].tol, cases[k].factor);
      CHECK_CLOSE(what, y[0], cos(cases[k].t1), 0.0, cases[k].tol * cases[k].factor);
      snprintf(what, sizeof what, "%s: y'(t1) = -sin t1", cases[k].name);
      CHECK_CLOSE(what, y[1], -sin(cases[k].t1), 0.0, cases[k].tol * cases[k].factor);
      snprintf(what, sizeof what, "%s: t reached = t1 exactly", cases[k].name);
      CHECK(what, t_end == cases[k].t1 && st.t_end == cases[k].t1);
      snprintf(what, sizeof what, "%s: stats.rhs_evals (%lu) == our own count (%lu)",
               cases[k].name, st.rhs_evals, c.calls);
      CHECK(what, st.rhs_evals == c.calls);
      snprintf(what, sizeof what, "%s: steps > 0, stop reason end", cases[k].name);
      CHECK(what, st.steps > 0 && st.stop_reason == AUTOBAL_TRANSIENT_STOP_END);
      if (cases[k].implicit) {
        snprintf(what, sizeof what, "%s%s: jacobian used (jac %lu, fd %lu, analytic calls %lu)",
                 cases[k].name, with_jac ? " analytic" : " fd", st.jac_evals, st.fd_jac_evals,
                 c.jac_calls);
        if (with_jac)
          CHECK(what, st.jac_evals > 0 && st.fd_jac_evals == 0 && c.jac_calls == st.jac_evals);
        else
          CHECK(what, st.jac_evals > 0 && st.fd_jac_evals == st.jac_evals && c.jac_calls == 0);
      } else {
        snprintf(what, sizeof what, "%s: explicit stepper makes no Jacobian call", cases[k].name);
        CHECK(what, st.jac_evals == 0);
      }
      autobal_transient_free(tr);
    }
  }
}

/* stiff equation: implicit steppers with analytic and FD Jacobians */
static void test_stiff(void) {
  static const char *names[] = {"msbdf", "bsimp", "rk4imp", "rk2imp"};
  const double t1 = 2.0, y0 = 3.0;
  const double exact = cos(t1) + (y0 - 1.0) * exp(-STIFF_L * t1);
  unsigned long steps_imp = 0, steps_rk8 = 0;
  size_t k;
  for (k = 0; k < 4; k++) {
    int with_jac;
    for (with_jac = 0; with_jac <= 1; with_jac++) {
      autobal_transient_options o = autobal_transient_options_default();
      autobal_transient *tr;
      autobal_transient_stats st;
      unsigned long calls = 0;
      autobal_transient_system sys = {stiff_rhs, with_jac ? stiff_jac : NULL, 1, &calls};
      double y[1] = {y0};
      char what[160];
      o.stepper = names[k];
      o.rtol = 1e-8;
      o.atol = 1e-8;
      tr = autobal_transient_alloc(1, &o, NULL);
      snprintf(what, sizeof what, "stiff %s (%s jac): status", names[k], with_jac ? "analytic" : "fd");
      CHECK_STATUS(what, autobal_transient_run(tr, &sys, 0.0, t1, y, NULL), AUTOBAL_SUCCESS);
      autobal_transient_get_stats(tr, &st);
      snprintf(what, sizeof what, "stiff %s (%s jac): y(2) = cos 2 + 2e^{-2e4}", names[k],
               with_jac ? "analytic" : "fd");
      CHECK_CLOSE(what, y[0], exact, 0.0, 1e-5);
      snprintf(what, sizeof what, "stiff %s: fd jacobian used iff no analytic one", names[k]);
      CHECK(what, with_jac ? st.fd_jac_evals == 0 : st.fd_jac_evals > 0);
      if (k == 0 && with_jac) steps_imp = st.steps;
      autobal_transient_free(tr);
    }
  }
  {
    autobal_transient_options o = autobal_transient_options_default();
    autobal_transient *tr;
    autobal_transient_stats st;
    unsigned long calls = 0;
    autobal_transient_system sys = {stiff_rhs, NULL, 1, &calls};
    double y[1] = {y0};
    o.rtol = o.atol = 1e-8;
    tr = autobal_transient_alloc(1, &o, NULL);
    CHECK_STATUS("stiff rk8pd: status", autobal_transient_run(tr, &sys, 0.0, t1, y, NULL),
                 AUTOBAL_SUCCESS);
    autobal_transient_get_stats(tr, &st);
    steps_rk8 = st.steps;
    CHECK_CLOSE("stiff rk8pd: y(2)", y[0], exact, 0.0, 1e-5);
    printf("     stiff problem: msbdf %lu steps, rk8pd %lu steps\n", steps_imp, steps_rk8);
    CHECK("explicit rk8pd needs many more steps than msbdf on the stiff problem (stability limit)",
          steps_rk8 > 10 * steps_imp);
    autobal_transient_free(tr);
  }
}

static void test_output_grid(void) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_stats st;
  osc_ctx c;
  autobal_transient_system sys = {osc_rhs, NULL, 2, &c};
  obs_rec r;
  double y[2], t_end;
  int k, ok_t = 1;
  double max_err = 0.0;
  o.rtol = o.atol = 1e-12;
  o.dt_out = 0.25;
  tr = autobal_transient_alloc(2, &o, NULL);
  memset(&r, 0, sizeof r);
  r.stop_at = INFINITY;
  autobal_transient_set_observer(tr, observer, &r);
  osc_init(&c);
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("grid run", autobal_transient_run(tr, &sys, 0.0, 2.0, y, &t_end), AUTOBAL_SUCCESS);
  CHECK("grid [0,2] step 0.25: 9 observer calls", r.n == 9);
  for (k = 0; k < r.n && k < 64; k++) {
    if (r.t[k] != (k == 8 ? 2.0 : 0.25 * k)) ok_t = 0;
    max_err = fmax(max_err, fabs(r.y0[k] - cos(r.t[k])));
  }
  CHECK("observer times are t0 + k dt_out exactly", ok_t);
  CHECK_CLOSE("observer states = cos t on the grid (max error)", max_err, 0.0, 0.0, 1e-10);
  autobal_transient_get_stats(tr, &st);
  CHECK("stats.observer_calls", st.observer_calls == 9);

  /* t1 off the grid: grid points plus t1 */
  memset(&r, 0, sizeof r);
  r.stop_at = INFINITY;
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("grid run to 2.1", autobal_transient_run(tr, &sys, 0.0, 2.1, y, NULL),
               AUTOBAL_SUCCESS);
  CHECK("grid [0,2.1]: 9 grid points + t1", r.n == 10 && r.t[9] == 2.1 && r.t[8] == 2.0);

  /* t1 a rounding error beyond the last grid point: no tiny extra output */
  memset(&r, 0, sizeof r);
  r.stop_at = INFINITY;
  y[0] = 1.0;
  y[1] = 0.0;
  {
    autobal_transient_options o2 = o;
    o2.dt_out = 0.1;
    autobal_transient_set_options(tr, &o2);
    CHECK_STATUS("grid 0.1 run to 1.0", autobal_transient_run(tr, &sys, 0.0, 1.0, y, NULL),
                 AUTOBAL_SUCCESS);
    CHECK("grid 0.1 on [0,1]: 11 outputs, last exactly 1", r.n == 11 && r.t[10] == 1.0);
  }

  /* the observer stops the run */
  memset(&r, 0, sizeof r);
  r.stop_at = 1.0;
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("observer stop", autobal_transient_run(tr, &sys, 0.0, 2.0, y, &t_end),
               AUTOBAL_EVENT);
  autobal_transient_get_stats(tr, &st);
  CHECK("observer stop: reason and code", st.stop_reason == AUTOBAL_TRANSIENT_STOP_OBSERVER &&
                                              st.user_code == 5);
  CHECK("observer stop: t reached = 1.0", t_end == 1.0);
  CHECK_CLOSE("observer stop: y = cos(1)", y[0], cos(1.0), 0.0, 1e-10);

  /* dt_out = 0: only t0 and t1 */
  {
    autobal_transient_options o3 = autobal_transient_options_default();
    autobal_transient_set_options(tr, &o3);
    memset(&r, 0, sizeof r);
    r.stop_at = INFINITY;
    y[0] = 1.0;
    y[1] = 0.0;
    autobal_transient_run(tr, &sys, 0.0, 5.0, y, NULL);
    CHECK("dt_out = 0: observer at t0 and t1 only", r.n == 2 && r.t[0] == 0.0 && r.t[1] == 5.0);
  }
  autobal_transient_free(tr);
}

static void test_steps_and_limits(void) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_stats st;
  osc_ctx c;
  autobal_transient_system sys = {osc_rhs, NULL, 2, &c};
  double y[2], y2[2], t_end;

  /* h_max respected */
  o.h_max = 0.01;
  tr = autobal_transient_alloc(2, &o, NULL);
  osc_init(&c);
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("h_max run", autobal_transient_run(tr, &sys, 0.0, 1.0, y, NULL), AUTOBAL_SUCCESS);
  autobal_transient_get_stats(tr, &st);
  printf("     h_max = 0.01: %lu steps, largest %.17g\n", st.steps, st.h_max_used);
  CHECK("h_max: largest step <= 0.01", st.h_max_used <= 0.01);
  CHECK("h_max: at least 100 steps", st.steps >= 100);
  autobal_transient_free(tr);

  /* a far too large first step is rejected (and counted) */
  o = autobal_transient_options_default();
  o.h_init = 2.0;
  o.rtol = o.atol = 1e-12;
  tr = autobal_transient_alloc(2, &o, NULL);
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("h_init = 2 run", autobal_transient_run(tr, &sys, 0.0, 3.0, y, NULL),
               AUTOBAL_SUCCESS);
  autobal_transient_get_stats(tr, &st);
  CHECK("h_init = 2 at tol 1e-12: rejected steps counted", st.rejected >= 1);
  CHECK_CLOSE("h_init = 2: still accurate", y[0], cos(3.0), 0.0, 1e-10);
  /* determinism: a second run gives the same bits */
  y2[0] = 1.0;
  y2[1] = 0.0;
  autobal_transient_run(tr, &sys, 0.0, 3.0, y2, NULL);
  CHECK("two runs are bitwise identical", y2[0] == y[0] && y2[1] == y[1]);
  autobal_transient_free(tr);

  /* max steps */
  o = autobal_transient_options_default();
  o.max_steps = 10;
  tr = autobal_transient_alloc(2, &o, NULL);
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("max_steps = 10", autobal_transient_run(tr, &sys, 0.0, 100.0, y, &t_end),
               AUTOBAL_EMAXSTEPS);
  autobal_transient_get_stats(tr, &st);
  CHECK_MSG("max_steps message", autobal_transient_errmsg(tr), "maximum number of steps");
  CHECK("max_steps: exactly 10 steps, t reached in (0, 100)",
        st.steps == 10 && t_end > 0.0 && t_end < 100.0 && st.t_end == t_end);
  CHECK_CLOSE("max_steps: y = cos(t reached)", y[0], cos(t_end), 0.0, 1e-9);
  CHECK("max_steps: stop reason error", st.stop_reason == AUTOBAL_TRANSIENT_STOP_ERROR);
  autobal_transient_free(tr);

  /* h_min: rk2 cannot meet 1e-10 with steps >= 0.01 */
  o = autobal_transient_options_default();
  o.stepper = "rk2";
  o.h_min = 0.01;
  tr = autobal_transient_alloc(2, &o, NULL);
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("h_min = 0.01 with rk2 at 1e-10", autobal_transient_run(tr, &sys, 0.0, 1.0, y, &t_end),
               AUTOBAL_ESTEP);
  CHECK_MSG("h_min message", autobal_transient_errmsg(tr), "h_min");
  CHECK_CLOSE("h_min: y = cos(t reached)", y[0], cos(t_end), 0.0, 1e-6);
  autobal_transient_free(tr);

  /* step-size underflow: a derivative that flips sign on every call */
  {
    unsigned long calls = 0;
    autobal_transient_system fs = {flip_rhs, NULL, 1, &calls};
    double z[1] = {0.0};
    o = autobal_transient_options_default();
    o.stepper = "rkck";
    tr = autobal_transient_alloc(1, &o, NULL);
    CHECK_STATUS("flipping derivative: step underflow", autobal_transient_run(tr, &fs, 1.0, 2.0, z, &t_end),
                 AUTOBAL_ESTEP);
    CHECK_MSG("underflow message", autobal_transient_errmsg(tr), "underflow");
    CHECK("underflow: state and time of the start kept", z[0] == 0.0 && t_end == 1.0);
    autobal_transient_free(tr);
  }
}

static void test_rhs_failures(void) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr = autobal_transient_alloc(2, &o, NULL);
  autobal_transient_stats st;
  osc_ctx c;
  autobal_transient_system sys = {osc_rhs, NULL, 2, &c};
  double y[2] = {1.0, 0.0}, t_end;
  int rc;

  osc_init(&c);
  c.fail_after = 1.2345;
  rc = autobal_transient_run(tr, &sys, 0.0, 3.0, y, &t_end);
  autobal_transient_get_stats(tr, &st);
  CHECK_STATUS("failing rhs: ERHS", rc, AUTOBAL_ERHS);
  CHECK_MSG("failing rhs: message", autobal_transient_errmsg(tr), "right-hand side returned -7");
  CHECK("failing rhs: user code -7 recorded", st.user_code == -7);
  CHECK("failing rhs: t reached in (0.5, 1.2345]", t_end > 0.5 && t_end <= 1.2345);
  CHECK_CLOSE("failing rhs: state at the last good step = cos(t reached)", y[0], cos(t_end), 0.0,
              1e-9);
  CHECK_CLOSE("failing rhs: y' = -sin(t reached)", y[1], -sin(t_end), 0.0, 1e-9);

  osc_init(&c);
  c.nan_after = 2.0;
  y[0] = 1.0;
  y[1] = 0.0;
  rc = autobal_transient_run(tr, &sys, 0.0, 3.0, y, &t_end);
  CHECK_STATUS("NaN rhs: ERHS", rc, AUTOBAL_ERHS);
  CHECK_MSG("NaN rhs: message", autobal_transient_errmsg(tr), "non-finite");
  CHECK("NaN rhs: t reached in (1, 2]", t_end > 1.0 && t_end <= 2.0);
  CHECK_CLOSE("NaN rhs: state kept = cos(t reached)", y[0], cos(t_end), 0.0, 1e-9);

  /* failure of the very first evaluation */
  osc_init(&c);
  c.fail_after = -1.0;
  y[0] = 1.0;
  y[1] = 0.0;
  rc = autobal_transient_run(tr, &sys, 0.0, 3.0, y, &t_end);
  CHECK_STATUS("rhs failing at t0: ERHS", rc, AUTOBAL_ERHS);
  CHECK("rhs failing at t0: y and t untouched", y[0] == 1.0 && y[1] == 0.0 && t_end == 0.0);
  autobal_transient_free(tr);

  /* failing analytic Jacobian with an implicit stepper */
  o.stepper = "rk4imp";
  tr = autobal_transient_alloc(2, &o, NULL);
  {
    autobal_transient_system sj = {osc_rhs, osc_jac, 2, &c};
    osc_init(&c);
    c.jac_fail_after = 0.5;
    y[0] = 1.0;
    y[1] = 0.0;
    rc = autobal_transient_run(tr, &sj, 0.0, 3.0, y, &t_end);
    CHECK_STATUS("failing Jacobian: ERHS", rc, AUTOBAL_ERHS);
    CHECK_MSG("failing Jacobian: message", autobal_transient_errmsg(tr), "Jacobian returned 3");
    CHECK("failing Jacobian: t reached <= 0.5 + step", t_end <= 0.5 + 1.0 && t_end < 3.0);
    CHECK_CLOSE("failing Jacobian: state kept = cos(t reached)", y[0], cos(t_end), 0.0, 1e-8);
  }
  autobal_transient_free(tr);
}

static void test_progress(void) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_stats st;
  osc_ctx c;
  autobal_transient_system sys = {osc_rhs, NULL, 2, &c};
  prog_rec r;
  double y[2] = {1.0, 0.0}, t_end;
  o.progress_step = 0.01;
  o.h_max = 0.01; /* many small steps */
  tr = autobal_transient_alloc(2, &o, NULL);
  osc_init(&c);
  memset(&r, 0, sizeof r);
  r.cancel_at = INFINITY;
  autobal_transient_set_progress(tr, progress, &r);
  CHECK_STATUS("progress run", autobal_transient_run(tr, &sys, 0.0, 10.0, y, NULL),
               AUTOBAL_SUCCESS);
  printf("     progress: %d calls, smallest increment %.4g\n", r.n, r.min_inc);
  CHECK("progress: first 0, last 1, non-decreasing", r.first == 0.0 && r.last == 1.0 && r.monotone);
  CHECK("progress: at most 1/step + 2 calls", r.n >= 3 && r.n <= 102);
  CHECK("progress: increments >= progress_step", r.min_inc >= 0.01 - 1e-12);

  memset(&r, 0, sizeof r);
  r.cancel_at = 0.3;
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("cancel at 30%", autobal_transient_run(tr, &sys, 0.0, 10.0, y, &t_end),
               AUTOBAL_ECANCELLED);
  autobal_transient_get_stats(tr, &st);
  CHECK("cancel: stop reason cancelled", st.stop_reason == AUTOBAL_TRANSIENT_STOP_CANCELLED);
  CHECK("cancel: t reached in [3, 3.2]", t_end >= 3.0 && t_end <= 3.2);
  CHECK_CLOSE("cancel: y = cos(t reached)", y[0], cos(t_end), 0.0, 1e-9);
  CHECK_MSG("cancel: message", autobal_transient_errmsg(tr), "cancelled");

  /* cancel before the first step */
  memset(&r, 0, sizeof r);
  r.cancel_at = 0.0;
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("cancel at 0", autobal_transient_run(tr, &sys, 0.0, 10.0, y, &t_end),
               AUTOBAL_ECANCELLED);
  CHECK("cancel at 0: nothing integrated", t_end == 0.0 && y[0] == 1.0);
  autobal_transient_free(tr);
}

static void test_events(void) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_stats st;
  osc_ctx c;
  autobal_transient_system sys = {osc_rhs, NULL, 2, &c};
  hit_rec r;
  autobal_transient_event_hit first;
  unsigned long count;
  double y[2], t_end;
  int i, idx;
  o.rtol = o.atol = 1e-12;
  o.event_tol = 1e-12;
  tr = autobal_transient_alloc(2, &o, NULL);
  autobal_transient_set_event_handler(tr, handler, &r);
  osc_init(&c);

  /* both directions, not terminal: y = cos t crosses 0 at pi/2 + k pi */
  idx = autobal_transient_add_event(tr, g_y0, NULL, 0, 0);
  CHECK("add_event returns index 0", idx == 0);
  memset(&r, 0, sizeof r);
  r.stop_on = -1;
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("events run", autobal_transient_run(tr, &sys, 0.0, 10.0, y, NULL),
               AUTOBAL_SUCCESS);
  CHECK("three zero crossings of cos t in [0, 10]", r.n == 3);
  for (i = 0; i < 3 && i < r.n; i++) {
    char what[128];
    const double want = M_PI / 2 + i * M_PI;
    snprintf(what, sizeof what, "crossing %d at pi/2 + %d pi", i, i);
    CHECK_CLOSE(what, r.hit[i].t, want, 0.0, 1e-10);
    snprintf(what, sizeof what, "crossing %d: direction %+d", i, i % 2 ? 1 : -1);
    CHECK(what, r.hit[i].direction == (i % 2 ? 1 : -1) && r.hit[i].terminal == 0);
    snprintf(what, sizeof what, "crossing %d: y0 = 0 there", i);
    CHECK_CLOSE(what, r.y0[i], 0.0, 0.0, 1e-10);
    snprintf(what, sizeof what, "crossing %d: y1 = -sin t there", i);
    CHECK_CLOSE(what, r.y1[i], -sin(want), 0.0, 1e-10);
  }
  CHECK_CLOSE("run continued to t1 unaffected: y(10) = cos 10", y[0], cos(10.0), 0.0, 1e-9);
  CHECK("event_result: 3 hits, first at pi/2",
        autobal_transient_event_result(tr, 0, &count, &first) == 1 && count == 3 &&
            fabs(first.t - M_PI / 2) < 1e-10);
  autobal_transient_get_stats(tr, &st);
  CHECK("stats.events == 3, event_steps > 0", st.events == 3 && st.event_steps > 0);

  /* terminal, rising only: stops at 3 pi / 2 with y = (0, 1) */
  autobal_transient_clear_events(tr);
  autobal_transient_add_event(tr, g_y0, NULL, +1, 1);
  memset(&r, 0, sizeof r);
  r.stop_on = -1;
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("terminal rising event", autobal_transient_run(tr, &sys, 0.0, 10.0, y, &t_end),
               AUTOBAL_EVENT);
  autobal_transient_get_stats(tr, &st);
  CHECK_CLOSE("terminal event at 3 pi/2", t_end, 1.5 * M_PI, 0.0, 1e-10);
  CHECK("terminal: stop reason event, index 0, one hit",
        st.stop_reason == AUTOBAL_TRANSIENT_STOP_EVENT && st.event_index == 0 && r.n == 1);
  CHECK_CLOSE("terminal: y0 = 0", y[0], 0.0, 0.0, 1e-10);
  CHECK_CLOSE("terminal: y1 = 1", y[1], 1.0, 0.0, 1e-10);
  CHECK("terminal: located on the far side (g >= 0)", y[0] >= 0.0);
  /* restarting from the event state does not re-trigger at once */
  CHECK_STATUS("restart after terminal event", autobal_transient_run(tr, &sys, t_end, 12.0, y, &t_end),
               AUTOBAL_EVENT);
  CHECK_CLOSE("restart: next rising crossing at 3 pi/2 + 2 pi", t_end, 3.5 * M_PI, 0.0, 1e-9);

  /* the handler stops the run on a non-terminal event */
  autobal_transient_clear_events(tr);
  autobal_transient_add_event(tr, g_y0, NULL, 0, 0);
  memset(&r, 0, sizeof r);
  r.stop_on = 1;
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("handler stop", autobal_transient_run(tr, &sys, 0.0, 10.0, y, &t_end),
               AUTOBAL_EVENT);
  autobal_transient_get_stats(tr, &st);
  CHECK_CLOSE("handler stop at the second crossing 3 pi/2", t_end, 1.5 * M_PI, 0.0, 1e-10);
  CHECK("handler stop: user code 9", st.user_code == 9);

  /* NaN from an event function */
  autobal_transient_clear_events(tr);
  autobal_transient_add_event(tr, g_nan, NULL, 0, 0);
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("NaN event function", autobal_transient_run(tr, &sys, 0.0, 10.0, y, &t_end),
               AUTOBAL_ENUMERIC);
  CHECK_MSG("NaN event message", autobal_transient_errmsg(tr), "NaN");
  CHECK_CLOSE("NaN event: state at the end of the step = cos(t reached)", y[0], cos(t_end), 0.0,
              1e-9);

  /* dwell: cos t < -0.5 on (2pi/3, 4pi/3), 2.094 long */
  autobal_transient_clear_events(tr);
  autobal_transient_add_dwell_event(tr, g_y0, NULL, -0.5, 1.0, 0);  /* fires */
  autobal_transient_add_dwell_event(tr, g_y0, NULL, -0.5, 2.5, 0);  /* never: interval too short */
  autobal_transient_add_dwell_event(tr, g_y0, NULL, 2.0, 0.75, 0);  /* below from t0 */
  memset(&r, 0, sizeof r);
  r.stop_on = -1;
  y[0] = 1.0;
  y[1] = 0.0;
  CHECK_STATUS("dwell run", autobal_transient_run(tr, &sys, 0.0, 6.0, y, NULL), AUTOBAL_SUCCESS);
  CHECK("dwell 1.0 fired once", autobal_transient_event_result(tr, 0, &count, &first) == 1 &&
                                     count == 1);
  CHECK_CLOSE("dwell: t_start = 2 pi / 3 (cos t = -1/2)", first.t_start, 2 * M_PI / 3, 0.0, 1e-10);
  CHECK_CLOSE("dwell: fires at 2 pi/3 + 1", first.t, 2 * M_PI / 3 + 1.0, 0.0, 1e-10);
  CHECK("dwell 2.5 never fired", autobal_transient_event_result(tr, 1, &count, NULL) == 0 &&
                                     count == 0);
  CHECK("dwell below from t0 fired", autobal_transient_event_result(tr, 2, &count, &first) == 1);
  CHECK("dwell below from t0: t_start = 0, t = 0.75", first.t_start == 0.0 && first.t == 0.75);
  CHECK("dwell hits reported in time order", r.n == 2 && r.hit[0].index == 2 && r.hit[1].index == 0);
  CHECK_CLOSE("dwell hit state: y0 = cos(2pi/3 + 1)", r.y0[1], cos(2 * M_PI / 3 + 1.0), 0.0, 1e-10);
  autobal_transient_free(tr);

  /* terminal dwell on exponential decay: y = e^-t < 0.5 from ln 2 */
  {
    autobal_transient_system ds = {decay_rhs, NULL, 1, NULL};
    double z[1] = {1.0};
    hit_rec r2;
    tr = autobal_transient_alloc(1, &o, NULL);
    memset(&r2, 0, sizeof r2);
    autobal_transient_set_event_handler(tr, hit_record_y1_dim1, &r2);
    autobal_transient_add_dwell_event(tr, g_y0_dim1, NULL, 0.5, 1.0, 1);
    CHECK_STATUS("terminal dwell", autobal_transient_run(tr, &ds, 0.0, 10.0, z, &t_end),
                 AUTOBAL_EVENT);
    CHECK_CLOSE("terminal dwell: t_start = ln 2", r2.hit[0].t_start, log(2.0), 0.0, 1e-10);
    CHECK_CLOSE("terminal dwell: stops at ln 2 + 1", t_end, log(2.0) + 1.0, 0.0, 1e-10);
    CHECK_CLOSE("terminal dwell: y = 0.5/e", z[0], 0.5 / exp(1.0), 0.0, 1e-11);
    autobal_transient_free(tr);
  }

  /* two events inside one (huge) step are reported in time order */
  {
    autobal_transient_system zs = {zero_rhs, NULL, 1, NULL};
    double z[1] = {0.0};
    double a1 = 1.0, a2 = 0.9;
    hit_rec r3;
    autobal_transient_options o2 = autobal_transient_options_default();
    o2.h_init = 5.0;
    tr = autobal_transient_alloc(1, &o2, NULL);
    memset(&r3, 0, sizeof r3);
    autobal_transient_set_event_handler(tr, hit_record_y1_dim1, &r3);
    autobal_transient_add_event(tr, g_time_minus, &a1, 0, 0);
    autobal_transient_add_event(tr, g_time_minus, &a2, 0, 0);
    CHECK_STATUS("two events in one step", autobal_transient_run(tr, &zs, 0.0, 5.0, z, NULL),
                 AUTOBAL_SUCCESS);
    autobal_transient_get_stats(tr, &st);
    CHECK("one step only", st.steps == 1);
    CHECK("both reported, earlier first", r3.n == 2 && r3.hit[0].index == 1 && r3.hit[1].index == 0);
    /* located on the far side of each crossing, within event_tol (default 1e-10); g = t - a is
     * exactly 0 at a secant point for a = 1 (the bracket [0, 5] gives 1 at once): not reported
     * there but strictly past it (a value exactly 0 counts as not yet crossed) */
    CHECK("first at 0.9 (far side, event_tol)", r3.hit[0].t >= 0.9 && r3.hit[0].t - 0.9 <= o2.event_tol);
    CHECK("second at 1.0 (far side, event_tol)", r3.hit[1].t > 1.0 && r3.hit[1].t - 1.0 <= o2.event_tol);
    autobal_transient_free(tr);
  }
}

int main(void) {
  gsl_set_error_handler_off();
  test_options();
  test_bad_run_args();
  test_all_steppers();
  test_stiff();
  test_output_grid();
  test_steps_and_limits();
  test_rhs_failures();
  test_progress();
  test_events();
  return check_summary();
}
