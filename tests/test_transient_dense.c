/* test_transient_dense.c: the DOP853 stepper and its continuous extension
 * (src/transient/dop853.c, dop853_coeffs.inc) and the driver's dense output
 * (src/transient/transient.c, stepper "dop853", exact_output = 0).
 *
 * The coefficients (generated from SciPy's transcription of Hairer's dop853.f) are
 * checked, not trusted: row sums of A against c, the quadrature conditions
 * sum b_i c_i^(k-1) = 1/k up to k = 8 (and that k = 9 fails: the order is 8, not more),
 * the embedded differences summing to 0; then the orders of convergence of one step, of the
 * error estimate and of the continuous extension on a closed-form, nonlinear, non-autonomous
 * system (a limit cycle with a time-dependent angular speed):
 *     x' = -w(t) y + x (1 - r^2),  y' = w(t) x + y (1 - r^2),  w = 1 + cos t,
 *     r(t) = (1 + (1/r0^2 - 1) e^(-2t))^(-1/2),  angle(t) = angle0 + t + sin t.
 * Then the driver: the error at output points on the extension against the closed form
 * across tolerances, beside the error of the same run's integrated states (exact hits);
 * rhs evaluations with and without output; events (the crossings x = 0 at closed-form
 * times), a terminal event, a dwell event, the observer stopping a run, a bad option. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "autobal/transient.h"
#include "check.h"
#include "transient/dop853.h"
#include "transient/dop853_coeffs.inc"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const double R0 = 0.4, ANG0 = 0.3;

static void exact(double t, double *out) {
  const double r = 1.0 / sqrt(1.0 + (1.0 / (R0 * R0) - 1.0) * exp(-2.0 * t));
  const double a = ANG0 + t + sin(t);
  out[0] = r * cos(a);
  out[1] = r * sin(a);
}

typedef struct cnt_ctx {
  unsigned long calls;
} cnt_ctx;

static int cyc_rhs(double t, const double y[], double f[], void *p) {
  const double w = 1.0 + cos(t), g = 1.0 - (y[0] * y[0] + y[1] * y[1]);
  if (p) ((cnt_ctx *)p)->calls++;
  f[0] = -w * y[1] + y[0] * g;
  f[1] = w * y[0] + y[1] * g;
  return 0;
}

static double err2(const double *a, const double *b) { return fmax(fabs(a[0] - b[0]), fabs(a[1] - b[1])); }

/* ---- the coefficients ----------------------------------------------------------------------- */

static void test_coefficients(void) {
  double worst = 0.0, s5 = 0.0, s3 = 0.0, q9 = 0.0;
  int i, j, k;
  char what[96];
  for (i = 1; i < 16; i++) {
    double s = 0.0;
    for (j = 0; j < i; j++) s += DOP853_A[i][j];
    worst = fmax(worst, fabs(s - DOP853_C[i]));
  }
  CHECK_CLOSE("dop853: max_i |sum_j a_ij - c_i| (16 rows, stage 12 = weights b, c = 1)", worst, 0.0, 0.0, 1e-13);
  for (k = 1; k <= 9; k++) {
    double s = 0.0;
    for (j = 0; j < 12; j++) s += DOP853_A[12][j] * pow(DOP853_C[j], k - 1);
    if (k <= 8) {
      snprintf(what, sizeof what, "dop853: quadrature condition sum b_i c_i^%d = 1/%d", k - 1, k);
      CHECK_CLOSE(what, s, 1.0 / k, 0.0, 1e-13);
    } else {
      q9 = fabs(s - 1.0 / k);
    }
  }
  CHECK("dop853: sum b_i c_i^8 != 1/9 (the order is 8, not 9): defect > 1e-8", q9 > 1e-8);
  for (j = 0; j < 13; j++) {
    s5 += DOP853_E5[j];
    s3 += DOP853_E3[j];
  }
  CHECK_CLOSE("dop853: sum of E5 (b - bhat, 5th order) = 0", s5, 0.0, 0.0, 1e-13);
  CHECK_CLOSE("dop853: sum of E3 (b - bhh, 3rd order) = 0", s3, 0.0, 0.0, 1e-13);
}

/* ---- orders of one step --------------------------------------------------------------------- */

/* One step of length h from the exact state at t0: the errors of the result, of the estimate
 * yerr (against the true error), of the continuous extension at theta = 0.37 and 0.81. */
static void one_step(gsl_odeiv2_step *s, double t0, double h, double *e_end, double *e_est,
                     double *e_dense) {
  gsl_odeiv2_system sys = {cyc_rhs, NULL, 2, NULL};
  double y[2], yerr[2], f0[2], f1[2], ye[2], u[2];
  const double th[2] = {0.37, 0.81};
  int q;
  exact(t0, y);
  cyc_rhs(t0, y, f0, NULL);
  gsl_odeiv2_step_reset(s);
  gsl_odeiv2_step_apply(s, t0, h, y, yerr, f0, f1, &sys);
  exact(t0 + h, ye);
  *e_end = err2(y, ye);
  *e_est = fmax(fabs(yerr[0]), fabs(yerr[1]));
  autobal_transient_dop853_dense_prepare_(s->state, &sys);
  *e_dense = 0.0;
  for (q = 0; q < 2; q++) {
    autobal_transient_dop853_dense_eval_(s->state, th[q], u);
    exact(t0 + th[q] * h, ye);
    *e_dense = fmax(*e_dense, err2(u, ye));
  }
  {
    double u0[2], u1[2], y0[2];
    exact(t0, y0);
    autobal_transient_dop853_dense_eval_(s->state, 0.0, u0);
    autobal_transient_dop853_dense_eval_(s->state, 1.0, u1);
    if (h == 0.8) {
      CHECK_CLOSE("dense: u(theta = 0) = y0", err2(u0, y0), 0.0, 0.0, 1e-15);
      CHECK_CLOSE("dense: u(theta = 1) = the step's result", err2(u1, y), 0.0, 0.0, 1e-15);
    }
  }
}

static void test_orders(void) {
  gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(&autobal_transient_dop853_type_, 2);
  const double t0 = 0.7;
  double h = 0.8, pe = 0, pest = 0, pd = 0, e1, es1, ed1, ratio = 0.0;
  int k;
  char what[128];
  CHECK("dop853: gsl_odeiv2_step_alloc with autobal's step type", s != NULL);
  if (!s) return;
  CHECK("dop853: name", strcmp(gsl_odeiv2_step_name(s), "dop853") == 0);
  one_step(s, t0, h, &e1, &es1, &ed1);
  ratio = ed1 / es1;
  for (k = 0; k < 3; k++) { /* 0.8 -> 0.1 (at 0.05 the step's error reaches rounding) */
    double e2, es2, ed2;
    one_step(s, t0, 0.5 * h, &e2, &es2, &ed2);
    pe = log2(e1 / e2) - 1.0;   /* local error O(h^(p+1)) */
    pest = log2(es1 / es2) - 1.0;
    pd = log2(ed1 / ed2) - 1.0;
    printf("     h = %-6g -> %-6g: step error %.3e -> %.3e (order %.2f), estimate %.3e -> %.3e (%.2f), "
           "extension %.3e -> %.3e (order %.2f)\n",
           h, 0.5 * h, e1, e2, pe, es1, es2, pest, ed1, ed2, pd);
    h *= 0.5;
    e1 = e2, es1 = es2, ed1 = ed2;
    ratio = fmax(ratio, ed1 / es1);
  }
  snprintf(what, sizeof what, "dop853: observed order of the step (last halving) %.2f, want 8 +- 0.6", pe);
  CHECK(what, fabs(pe - 8.0) <= 0.6);
  snprintf(what, sizeof what, "dop853: observed order of the error estimate %.2f, want 7 +- 0.6 (O(h^8))", pest);
  CHECK(what, fabs(pest - 7.0) <= 0.6);
  snprintf(what, sizeof what, "dop853: observed order of the continuous extension %.2f, want 7 +- 0.6", pd);
  CHECK(what, fabs(pd - 7.0) <= 0.6);
  /* the extension's local error is of the order of the error estimate (both O(h^8)), which the
   * control keeps below atol + rtol |y|: the interpolation error is bounded by the step's error
   * control, within this factor */
  snprintf(what, sizeof what,
           "dop853: local error of the extension / the step's error estimate <= 3 at h = 0.8 .. 0.1 (max %.2f)",
           ratio);
  CHECK(what, ratio <= 3.0);
  gsl_odeiv2_step_free(s);
}

/* ---- the driver ------------------------------------------------------------------------------ */

typedef struct obs_ctx {
  double max_err;
  double max_err_steps; /* at the ends of the accepted steps */
  unsigned long n;
  double t_last;
  int monotone;
  unsigned long stop_at; /* the observer returns 5 at call number stop_at (0: never) */
} obs_ctx;

static int obs_err(double t, const double y[], void *user) {
  obs_ctx *o = (obs_ctx *)user;
  double ye[2];
  exact(t, ye);
  o->max_err = fmax(o->max_err, err2(y, ye));
  if (o->n > 0 && !(t > o->t_last)) o->monotone = 0;
  o->t_last = t;
  o->n++;
  if (o->stop_at && o->n == o->stop_at) return 5;
  return 0;
}

/* An event function that never changes sign: evaluated by the driver at t0 and at the end of
 * every accepted step (no crossing, so nowhere else); records the error of the integrated state. */
static double g_step_err(double t, const double y[], void *user) {
  double ye[2], *worst = (double *)user;
  exact(t, ye);
  *worst = fmax(*worst, err2(y, ye));
  return 1.0;
}

static int run_cyc(const char *stepper, int exact_output, double tol, double dt_out, double t1, obs_ctx *o,
                   autobal_transient_stats *st) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_system sys = {cyc_rhs, NULL, 2, NULL};
  double y[2];
  int rc;
  opt.stepper = stepper;
  opt.exact_output = exact_output;
  opt.rtol = tol;
  opt.atol = tol;
  opt.dt_out = dt_out;
  tr = autobal_transient_alloc(2, &opt, NULL);
  if (!tr) return -100;
  memset(o, 0, sizeof *o);
  o->monotone = 1;
  autobal_transient_set_observer(tr, obs_err, o);
  o->max_err_steps = 0.0;
  autobal_transient_add_event(tr, g_step_err, &o->max_err_steps, 0, 0);
  exact(0.0, y);
  rc = autobal_transient_run(tr, &sys, 0.0, t1, y, NULL);
  autobal_transient_get_stats(tr, st);
  autobal_transient_free(tr);
  return rc;
}

static void test_dense_accuracy(void) {
  const double tols[4] = {1e-6, 1e-8, 1e-10, 1e-12};
  const double t1 = 30.0, dt_out = 0.05; /* several output times per step */
  double prev = INFINITY;
  int k;
  char what[200];
  printf("     tol      dense: err at outputs, at step ends  rhs  steps | exact hits: err  rhs  steps | no output: rhs\n");
  for (k = 0; k < 4; k++) {
    obs_ctx od, ox, on;
    autobal_transient_stats sd, sx, sn;
    int rd = run_cyc("dop853", 0, tols[k], dt_out, t1, &od, &sd);
    int rx = run_cyc("dop853", 1, tols[k], dt_out, t1, &ox, &sx);
    int rn = run_cyc("dop853", 0, tols[k], 0.0, t1, &on, &sn);
    printf("     %-8g %.3e %.3e %8lu %6lu | %.3e %8lu %6lu | %8lu\n", tols[k], od.max_err, od.max_err_steps,
           sd.rhs_evals, sd.steps, ox.max_err, sx.rhs_evals, sx.steps, sn.rhs_evals);
    CHECK_STATUS("dense run", rd, AUTOBAL_SUCCESS);
    CHECK_STATUS("exact-hits run", rx, AUTOBAL_SUCCESS);
    CHECK_STATUS("no-output run", rn, AUTOBAL_SUCCESS);
    CHECK("dense: one observer call per output time (601), in increasing time", od.n == 601 && od.monotone);
    CHECK("exact hits: one observer call per output time (601)", ox.n == 601);
    /* the extension's error at the output points: the error of the integrated states of the same
     * run (at the ends of its accepted steps) plus the extension's local error, which the control
     * bounds through the estimate (above; the estimate is kept below atol + rtol |y| <= 2 tol
     * here, |y| <= 1): measured (err_out - err_steps) / (2 tol) = 1.6, 4.9, 4.6, 5.7 at tol 1e-6,
     * 1e-8, 1e-10, 1e-12; checked <= 10 */
    snprintf(what, sizeof what,
             "tol %g: error at the output points on the extension %.3e <= the error at the step "
             "ends %.3e + 10 x 2 tol (ratio %.2f)",
             tols[k], od.max_err, od.max_err_steps, (od.max_err - od.max_err_steps) / (2.0 * tols[k]));
    CHECK(what, od.max_err <= od.max_err_steps + 20.0 * tols[k]);
    snprintf(what, sizeof what, "tol %g: error at the output points %.3e below 100 tol", tols[k], od.max_err);
    CHECK(what, od.max_err <= 100.0 * tols[k]);
    CHECK("the error at the output points decreases with the tolerance", od.max_err < prev);
    prev = od.max_err;
    snprintf(what, sizeof what,
             "tol %g: dense output takes the steps of the run without output (%lu vs %lu) and fewer "
             "rhs than exact hits (%lu vs %lu)",
             tols[k], sd.steps, sn.steps, sd.rhs_evals, sx.rhs_evals);
    CHECK(what, sd.steps == sn.steps && sd.rhs_evals < sx.rhs_evals);
    snprintf(what, sizeof what, "tol %g: dense output costs 12 + 3 rhs per step at most (%lu <= 15 x %lu + 2)",
             tols[k], sd.rhs_evals, sd.steps);
    CHECK(what, sd.rhs_evals <= 15 * sd.steps + 2 + sd.rejected * 12);
  }
  {
    /* rk8pd has no continuous extension: exact_output = 0 leaves it hitting the grid */
    obs_ctx o8;
    autobal_transient_stats s8;
    int r8 = run_cyc("rk8pd", 0, 1e-10, dt_out, t1, &o8, &s8);
    CHECK_STATUS("rk8pd with exact_output = 0", r8, AUTOBAL_SUCCESS);
    snprintf(what, sizeof what, "rk8pd (no extension): exact hits, error %.3e <= 1e-8, steps %lu >= 600", o8.max_err, s8.steps);
    CHECK(what, o8.max_err <= 1e-8 && o8.n == 601 && s8.steps >= 600);
  }
}

/* ---- events on the extension ----------------------------------------------------------------- */

typedef struct ev_ctx {
  double t[64];
  double y0[64];
  int dir[64];
  int n;
  double t_start;
} ev_ctx;

static double g_x(double t, const double y[], void *u) {
  (void)t, (void)u;
  return y[0];
}
static double s_gap(double t, const double y[], void *u) {
  (void)t, (void)u;
  return fabs(1.0 - sqrt(y[0] * y[0] + y[1] * y[1]));
}
static int ev_handler(const autobal_transient_event_hit *h, const double y[], void *user) {
  ev_ctx *c = (ev_ctx *)user;
  if (h->index == 0 && c->n < 64) {
    c->t[c->n] = h->t;
    c->y0[c->n] = y[0];
    c->dir[c->n] = h->direction;
    c->n++;
  }
  if (h->index == 1) c->t_start = h->t_start;
  return 0;
}

/* angle(t) = ANG0 + t + sin t = pi/2 + k pi: x crosses 0 (bisection on the closed form, which
 * increases with t) */
static double crossing(int k) {
  double a = 0.0, b = 30.0;
  int i;
  for (i = 0; i < 200 && b - a > 1e-15 * b; i++) {
    const double c = 0.5 * (a + b);
    if (ANG0 + c + sin(c) - (M_PI / 2 + k * M_PI) < 0.0) a = c;
    else b = c;
  }
  return 0.5 * (a + b);
}

static void test_events(void) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient_system sys = {cyc_rhs, NULL, 2, NULL};
  autobal_transient *tr;
  ev_ctx c;
  double y[2], tr_end = 0.0, worst_t = 0.0, worst_y = 0.0;
  int rc, k, dir_ok = 1;
  char what[200];
  autobal_transient_stats st;
  /* the crossings: angle from 0.3 to 0.3 + 20 + sin 20 = 21.21: k = 0 .. 6 */
  opt.stepper = "dop853";
  opt.rtol = opt.atol = 1e-11;
  opt.event_tol = 1e-12;
  tr = autobal_transient_alloc(2, &opt, NULL);
  memset(&c, 0, sizeof c);
  autobal_transient_add_event(tr, g_x, NULL, 0, 0);
  /* |1 - r| < 1e-3 for 2 time units: r = 0.999 at the closed-form time t_b below */
  autobal_transient_add_dwell_event(tr, s_gap, NULL, 1e-3, 2.0, 0);
  autobal_transient_set_event_handler(tr, ev_handler, &c);
  exact(0.0, y);
  rc = autobal_transient_run(tr, &sys, 0.0, 20.0, y, &tr_end);
  autobal_transient_get_stats(tr, &st);
  CHECK_STATUS("dense events run", rc, AUTOBAL_SUCCESS);
  snprintf(what, sizeof what, "dense events: %d crossings of x = 0 in [0, 20], want 7", c.n);
  CHECK(what, c.n == 7);
  for (k = 0; k < c.n && k < 7; k++) {
    const double te = crossing(k);
    worst_t = fmax(worst_t, fabs(c.t[k] - te));
    worst_y = fmax(worst_y, fabs(c.y0[k]));
    if (c.dir[k] != ((k % 2 == 0) ? -1 : 1)) dir_ok = 0;
  }
  CHECK_CLOSE("dense events: max |t_event - closed form| (event_tol 1e-12, tol 1e-11)", worst_t, 0.0, 0.0, 1e-9);
  CHECK_CLOSE("dense events: max |x| at the located events (the interpolated state)", worst_y, 0.0, 0.0, 1e-9);
  CHECK("dense events: directions alternate, falling first", dir_ok);
  {
    /* r(t) = 0.999: (1/r0^2 - 1) e^(-2t) = 1/0.999^2 - 1 */
    const double tb = -0.5 * log((1.0 / (0.999 * 0.999) - 1.0) / (1.0 / (R0 * R0) - 1.0));
    autobal_transient_event_hit h1;
    int fired = autobal_transient_event_result(tr, 1, NULL, &h1);
    CHECK("dense dwell event fired", fired == 1);
    CHECK_CLOSE("dense dwell: t_start = closed-form time of r = 0.999", h1.t_start, tb, 0.0, 1e-8);
    CHECK_CLOSE("dense dwell: fires at t_start + 2 (no step landed there)", h1.t, h1.t_start + 2.0, 0.0, 1e-12);
  }
  /* a terminal event stops at the crossing with the interpolated state there */
  autobal_transient_clear_events(tr);
  autobal_transient_set_event_handler(tr, NULL, NULL);
  autobal_transient_add_event(tr, g_x, NULL, 1, 1);
  exact(0.0, y);
  rc = autobal_transient_run(tr, &sys, 0.0, 20.0, y, &tr_end);
  CHECK_STATUS("dense terminal event", rc, AUTOBAL_EVENT);
  CHECK_CLOSE("dense terminal event: stops at the first rising crossing", tr_end, crossing(1), 0.0, 1e-9);
  {
    double ye[2];
    exact(tr_end, ye);
    CHECK_CLOSE("dense terminal event: the state left in y is the closed form there", err2(y, ye), 0.0, 0.0, 1e-9);
  }
  autobal_transient_free(tr);
}

static void test_observer_stop_and_options(void) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient_system sys = {cyc_rhs, NULL, 2, NULL};
  autobal_transient *tr;
  autobal_error err;
  obs_ctx o;
  double y[2], t_end = 0.0, ye[2];
  int rc;
  opt.stepper = "dop853";
  opt.dt_out = 0.05;
  tr = autobal_transient_alloc(2, &opt, NULL);
  memset(&o, 0, sizeof o);
  o.monotone = 1;
  o.stop_at = 38; /* t = 37 x 0.05 = 1.85 */
  autobal_transient_set_observer(tr, obs_err, &o);
  exact(0.0, y);
  rc = autobal_transient_run(tr, &sys, 0.0, 10.0, y, &t_end);
  CHECK_STATUS("dense: the observer stops the run", rc, AUTOBAL_EVENT);
  CHECK_CLOSE("dense: stopped at the output time of the stopping call", t_end, 1.85, 0.0, 1e-12);
  exact(t_end, ye);
  CHECK_CLOSE("dense: y is the output state there", err2(y, ye), 0.0, 0.0, 1e-8);
  autobal_transient_free(tr);
  opt.exact_output = 2;
  rc = autobal_transient_options_validate(&opt, &err);
  CHECK_STATUS("exact_output = 2 rejected", rc, AUTOBAL_EINVAL);
  CHECK_MSG("exact_output = 2 rejected", err.message, "exact_output");
}

/* ---- every system size: the padded, unrolled and generic kernels ---------------------------- */

/* n identical copies of y' = cos(t) y, y(0) = 1: y = exp(sin t).  dop853 pads its stage arrays to
 * a multiple of 4 components and has a step unrolled for each padded size up to 24 and a generic
 * one above; every size must give every component exactly the same numbers (the components do not
 * interact, and the padding must not leak into them), the closed form within the tolerance, and
 * the step sequence of n = 1 (Hairer's normwise factor |e5|/sqrt(|e5|^2 + 0.01 |e3|^2) does not
 * depend on the number of identical components). */
static int copies_rhs(double t, const double y[], double f[], void *p) {
  const size_t n = *(const size_t *)p;
  size_t i;
  for (i = 0; i < n; i++) f[i] = cos(t) * y[i];
  return 0;
}

typedef struct copies_obs {
  size_t n;
  unsigned long calls;
  int same;
  double max_err;
} copies_obs;

static int copies_observe(double t, const double y[], void *user) {
  copies_obs *o = (copies_obs *)user;
  size_t i;
  for (i = 1; i < o->n; i++)
    if (memcmp(&y[i], &y[0], sizeof y[0]) != 0) o->same = 0;
  o->max_err = fmax(o->max_err, fabs(y[0] - exp(sin(t))));
  o->calls++;
  return 0;
}

static void test_sizes(void) {
  static const size_t sizes[] = {1, 2, 3, 4, 5, 7, 8, 9, 12, 13, 16, 17, 20, 21, 24, 25, 28, 33};
  unsigned long steps1 = 0;
  size_t q;
  for (q = 0; q < sizeof sizes / sizeof sizes[0]; q++) {
    size_t n = sizes[q];
    autobal_transient_options opt = autobal_transient_options_default();
    autobal_transient_system sys = {copies_rhs, NULL, n, &n};
    autobal_transient *tr;
    autobal_transient_stats st;
    copies_obs o = {n, 0, 1, 0.0};
    double y[33];
    char what[160];
    size_t i;
    int rc;
    opt.stepper = "dop853";
    opt.rtol = opt.atol = 1e-9;
    opt.dt_out = 0.37;
    tr = autobal_transient_alloc(n, &opt, NULL);
    for (i = 0; i < n; i++) y[i] = 1.0;
    autobal_transient_set_observer(tr, copies_observe, &o);
    rc = autobal_transient_run(tr, &sys, 0.0, 20.0, y, NULL);
    autobal_transient_get_stats(tr, &st);
    autobal_transient_free(tr);
    if (n == 1) steps1 = st.steps;
    snprintf(what, sizeof what, "dop853 dense, %zu identical components: run succeeds, 56 output times (0, 0.37, .., 19.98, 20)", n);
    CHECK(what, rc == AUTOBAL_SUCCESS && o.calls == 56);
    snprintf(what, sizeof what, "dop853 dense, %zu components: all components bit for bit equal", n);
    CHECK(what, o.same);
    snprintf(what, sizeof what, "dop853 dense, %zu components: |y - exp(sin t)| <= 100 tol", n);
    CHECK(what, o.max_err <= 1e-7);
    snprintf(what, sizeof what, "dop853 dense, %zu components: the steps of n = 1 (%lu, here %lu)", n,
             steps1, st.steps);
    CHECK(what, st.steps == steps1);
  }
}

int main(void) {
  gsl_set_error_handler_off();
  test_coefficients();
  test_orders();
  test_dense_accuracy();
  test_events();
  test_observer_stop_and_options();
  test_sizes();
  return check_summary();
}
