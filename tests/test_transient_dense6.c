/* test_transient_dense6.c: DOP853's continuous extension of order 6 with no extra stage
 * (src/transient/dop853.c, dop853_dense6.inc from tools/derive/derive_dense6.py; the driver's
 * option dense_order = 6).
 *
 * Independent expected values: closed-form solutions (a harmonic oscillator y'' = -y, and the
 * nonlinear non-autonomous limit cycle of test_transient_dense.c), the theory's convergence
 * orders (local error O(h^7) for order 6, O(h^8) for contd8), event times from the closed form
 * (bisection on the closed-form angle), and the count of right-hand sides: a step costs 12 (the
 * first stage is the previous step's FSAL derivative), so a run with an output grid must cost
 * exactly what the run without one costs when no event cuts a step. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "autobal/transient.h"
#include "check.h"
#include "transient/dop853.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const double R0 = 0.4, ANG0 = 0.3;

static double cyc_angle(double t) { return ANG0 + t + sin(t); }

static void cyc_exact(double t, double *out) {
  const double r = 1.0 / sqrt(1.0 + (1.0 / (R0 * R0) - 1.0) * exp(-2.0 * t));
  const double a = cyc_angle(t);
  out[0] = r * cos(a);
  out[1] = r * sin(a);
}

static int cyc_rhs(double t, const double y[], double f[], void *p) {
  const double w = 1.0 + cos(t), g = 1.0 - (y[0] * y[0] + y[1] * y[1]);
  if (p) (*(unsigned long *)p)++;
  f[0] = -w * y[1] + y[0] * g;
  f[1] = w * y[0] + y[1] * g;
  return 0;
}

/* y'' = -y: y = (cos t, -sin t) */
static void osc_exact(double t, double *out) {
  out[0] = cos(t);
  out[1] = -sin(t);
}

static int osc_rhs(double t, const double y[], double f[], void *p) {
  (void)t;
  if (p) (*(unsigned long *)p)++;
  f[0] = y[1];
  f[1] = -y[0];
  return 0;
}

static double err2(const double *a, const double *b) { return fmax(fabs(a[0] - b[0]), fabs(a[1] - b[1])); }

/* One step of length h from the exact state at t0, then the largest error of the extension of
 * the given order over theta = 0.05, 0.10, ..., 0.95 against the closed form; *nfev: the
 * right-hand sides the extension needed. */
static double one_step(gsl_odeiv2_step *s, int order, int (*rhs)(double, const double *, double *, void *),
                       void (*ex)(double, double *), double t0, double h, unsigned long *nfev) {
  unsigned long calls = 0;
  gsl_odeiv2_system sys = {rhs, NULL, 2, &calls};
  double y[2], yerr[2], f0[2], f1[2], ye[2], u[2], e = 0.0;
  int q;
  ex(t0, y);
  rhs(t0, y, f0, NULL);
  gsl_odeiv2_step_reset(s);
  autobal_transient_dop853_set_dense_order_(s->state, order);
  gsl_odeiv2_step_apply(s, t0, h, y, yerr, f0, f1, &sys);
  calls = 0;
  autobal_transient_dop853_dense_prepare_(s->state, &sys);
  *nfev = calls;
  for (q = 1; q < 20; q++) {
    const double th = 0.05 * q;
    autobal_transient_dop853_dense_eval_(s->state, th, u);
    ex(t0 + th * h, ye);
    e = fmax(e, err2(u, ye));
  }
  return e;
}

static void orders_on(const char *name, int (*rhs)(double, const double *, double *, void *),
                      void (*ex)(double, double *), double t0, double h_first, int halvings) {
  gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(&autobal_transient_dop853_type_, 2);
  char what[200];
  int order;
  CHECK("dop853 step allocated", s != NULL);
  if (!s) return;
  for (order = 6; order <= 7; order++) {
    double h = h_first, p = 0.0, e1, e2;
    unsigned long nf = 0, nf_all = 0;
    int k;
    e1 = one_step(s, order, rhs, ex, t0, h, &nf);
    nf_all = nf;
    for (k = 0; k < halvings; k++) {
      e2 = one_step(s, order, rhs, ex, t0, 0.5 * h, &nf);
      nf_all = nf > nf_all ? nf : nf_all;
      p = log2(e1 / e2);
      printf("     %s, extension of order %d: h = %-6g -> %-6g: %.3e -> %.3e (slope %.2f)\n", name, order, h,
             0.5 * h, e1, e2, p);
      h *= 0.5;
      e1 = e2;
    }
    /* local interpolation error O(h^(order + 1)) */
    snprintf(what, sizeof what, "%s: slope of the local error of the order-%d extension %.2f, want %d +- 0.6",
             name, order, p, order + 1);
    CHECK(what, fabs(p - (order + 1)) <= 0.6);
    snprintf(what, sizeof what, "%s: the order-%d extension needs %lu right-hand sides per step, want %d", name,
             order, nf_all, order == 6 ? 0 : 3);
    CHECK(what, nf_all == (order == 6 ? 0UL : 3UL));
  }
  /* the ends: u(0) = y0 and u(1) = the step's result to rounding; u'(0) = f0, u'(1) = f1 by
   * central differences of the extension (O(d^2) with d = 1e-4: 1e-8 relative to h |f|) */
  {
    unsigned long calls = 0;
    gsl_odeiv2_system sys = {rhs, NULL, 2, &calls};
    const double h = 0.4, d = 1e-4;
    double y[2], y0[2], yerr[2], f0[2], f1[2], u0[2], u1[2], a[2], b[2], du[2];
    ex(t0, y0);
    memcpy(y, y0, sizeof y);
    rhs(t0, y, f0, NULL);
    gsl_odeiv2_step_reset(s);
    autobal_transient_dop853_set_dense_order_(s->state, 6);
    gsl_odeiv2_step_apply(s, t0, h, y, yerr, f0, f1, &sys);
    autobal_transient_dop853_dense_prepare_(s->state, &sys);
    autobal_transient_dop853_dense_eval_(s->state, 0.0, u0);
    autobal_transient_dop853_dense_eval_(s->state, 1.0, u1);
    snprintf(what, sizeof what, "%s, order 6: u(0) = y0 (%.1e), u(1) = y1 (%.1e)", name, err2(u0, y0), err2(u1, y));
    CHECK(what, err2(u0, y0) <= 4e-16 && err2(u1, y) <= 4e-16);
    autobal_transient_dop853_dense_eval_(s->state, d, a);
    autobal_transient_dop853_dense_eval_(s->state, -d, b); /* the polynomial continued past 0 */
    du[0] = (a[0] - b[0]) / (2 * d * h), du[1] = (a[1] - b[1]) / (2 * d * h);
    snprintf(what, sizeof what, "%s, order 6: u'(0) = f0 (%.1e)", name, err2(du, f0));
    CHECK(what, err2(du, f0) <= 1e-7);
    autobal_transient_dop853_dense_eval_(s->state, 1.0 + d, a);
    autobal_transient_dop853_dense_eval_(s->state, 1.0 - d, b);
    du[0] = (a[0] - b[0]) / (2 * d * h), du[1] = (a[1] - b[1]) / (2 * d * h);
    snprintf(what, sizeof what, "%s, order 6: u'(1) = f1 (%.1e)", name, err2(du, f1));
    CHECK(what, err2(du, f1) <= 1e-7);
  }
  gsl_odeiv2_step_free(s);
}

/* ---- the driver ------------------------------------------------------------------------------ */

typedef struct obs_ctx {
  double max_err;
  unsigned long n;
} obs_ctx;

static int obs_err(double t, const double y[], void *user) {
  obs_ctx *o = (obs_ctx *)user;
  double ye[2];
  cyc_exact(t, ye);
  o->max_err = fmax(o->max_err, err2(y, ye));
  o->n++;
  return 0;
}

typedef struct ev_ctx {
  double t[64];
  int n;
} ev_ctx;

static double g_x(double t, const double y[], void *u) {
  (void)t, (void)u;
  return y[0];
}

static int ev_handler(const autobal_transient_event_hit *h, const double y[], void *user) {
  ev_ctx *c = (ev_ctx *)user;
  (void)y;
  if (c->n < 64) c->t[c->n++] = h->t;
  return 0;
}

/* the k-th zero of x(t) = r cos(angle(t)) for t > 0: angle(t) = pi/2 + k pi (angle increasing) */
static double crossing(int k) {
  const double target = M_PI / 2 + k * M_PI;
  double lo = 0.0, hi = 200.0;
  int i;
  for (i = 0; i < 200; i++) {
    const double mid = 0.5 * (lo + hi);
    if (cyc_angle(mid) < target) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

static int run_cyc(int order, double tol, double dt_out, double t1, obs_ctx *o, ev_ctx *ev,
                   autobal_transient_stats *st) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_system sys = {cyc_rhs, NULL, 2, NULL};
  double y[2];
  int rc;
  opt.stepper = "dop853";
  opt.dense_order = order;
  opt.rtol = tol;
  opt.atol = tol;
  opt.dt_out = dt_out;
  opt.event_tol = 1e-13;
  tr = autobal_transient_alloc(2, &opt, NULL);
  if (!tr) return -100;
  memset(o, 0, sizeof *o);
  autobal_transient_set_observer(tr, obs_err, o);
  if (ev) {
    memset(ev, 0, sizeof *ev);
    autobal_transient_add_event(tr, g_x, NULL, 0, 0);
    autobal_transient_set_event_handler(tr, ev_handler, ev);
  }
  cyc_exact(0.0, y);
  rc = autobal_transient_run(tr, &sys, 0.0, t1, y, NULL);
  autobal_transient_get_stats(tr, st);
  autobal_transient_free(tr);
  return rc;
}

static void test_driver(void) {
  const double tols[4] = {1e-6, 1e-8, 1e-10, 1e-12};
  const double t1 = 30.0, dt_out = 0.05; /* several output times per step */
  double prev = INFINITY;
  int k, i;
  char what[220];
  printf("     tol      order 6: err at outputs  rhs steps | no output: rhs steps | order 7: err  rhs | events (6): max |dt|\n");
  for (k = 0; k < 4; k++) {
    obs_ctx o6, on, o7, oe;
    ev_ctx ev;
    autobal_transient_stats s6, sn, s7, se;
    int r6 = run_cyc(6, tols[k], dt_out, t1, &o6, NULL, &s6);
    int rn = run_cyc(6, tols[k], 0.0, t1, &on, NULL, &sn);
    int r7 = run_cyc(7, tols[k], dt_out, t1, &o7, NULL, &s7);
    int re = run_cyc(6, tols[k], dt_out, t1, &oe, &ev, &se);
    double dtmax = 0.0;
    for (i = 0; i < ev.n; i++) dtmax = fmax(dtmax, fabs(ev.t[i] - crossing(i)));
    printf("     %-8g %.3e %8lu %6lu | %8lu %6lu | %.3e %8lu | %d events, %.2e\n", tols[k], o6.max_err, s6.rhs_evals,
           s6.steps, sn.rhs_evals, sn.steps, o7.max_err, s7.rhs_evals, ev.n, dtmax);
    CHECK_STATUS("order 6 run", r6, AUTOBAL_SUCCESS);
    CHECK_STATUS("order 6 run without output", rn, AUTOBAL_SUCCESS);
    CHECK_STATUS("order 7 run", r7, AUTOBAL_SUCCESS);
    CHECK_STATUS("order 6 run with events", re, AUTOBAL_SUCCESS);
    CHECK("order 6: one observer call per output time (601)", o6.n == 601);
    snprintf(what, sizeof what,
             "tol %g: output for free: rhs with output %lu = without %lu (steps %lu = %lu); contd8 %lu more",
             tols[k], s6.rhs_evals, sn.rhs_evals, s6.steps, sn.steps, s7.rhs_evals - s6.rhs_evals);
    CHECK(what, s6.rhs_evals == sn.rhs_evals && s6.steps == sn.steps && s7.rhs_evals > s6.rhs_evals);
    /* here every theta of every step holds output times (20 per step at 1e-6), and the order-6
     * extension's own error (one order below contd8's) shows: measured 1.9, 2.2, 3.9, 5.1 times
     * contd8's at 1e-6 .. 1e-12; checked <= 8 (on the bench's cases, output every quarter
     * revolution, the ratio is 0.99-1.08: tests/app/dense6.sh checks <= 1.5 there) */
    snprintf(what, sizeof what, "tol %g: error at the output points, order 6 %.3e <= 8 x order 7's %.3e (%.2f)", tols[k],
             o6.max_err, o7.max_err, o6.max_err / o7.max_err);
    CHECK(what, o6.max_err <= 8.0 * o7.max_err);
    snprintf(what, sizeof what, "tol %g: error at the output points %.3e below 100 tol and decreasing", tols[k],
             o6.max_err);
    CHECK(what, o6.max_err <= 100.0 * tols[k] && o6.max_err < prev);
    prev = o6.max_err;
    /* events located on the order-6 extension: x = 0 at the closed-form times (every one of
     * them in (0, 30): angle(30) - angle(0) = 30 + sin 30 -> 9 crossings); |dt| ~ |x error| /
     * |x'| with |x'| >= r w, here within 1000 tol; no more rhs than the run without events */
    snprintf(what, sizeof what, "tol %g: order 6: %d crossings x = 0, max |t - closed form| %.2e <= 1000 tol, rhs %lu = %lu",
             tols[k], ev.n, dtmax, se.rhs_evals, sn.rhs_evals);
    CHECK(what, ev.n == 9 && dtmax <= 1000.0 * tols[k] && se.rhs_evals == sn.rhs_evals);
  }
}

static void test_option(void) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_error err;
  int rc;
  CHECK("default dense_order is 7 (contd8)", opt.dense_order == 7);
  opt.dense_order = 5;
  memset(&err, 0, sizeof err);
  rc = autobal_transient_options_validate(&opt, &err);
  CHECK_STATUS("dense_order = 5 rejected", rc, AUTOBAL_EINVAL);
  CHECK_MSG("dense_order = 5 rejected, naming the option", err.message, "dense_order");
  CHECK_MSG("dense_order = 5 rejected, naming the allowed values", err.message, "7 or 6");
  opt.dense_order = 0;
  CHECK_STATUS("dense_order = 0 (taken as 7) accepted", autobal_transient_options_validate(&opt, &err), AUTOBAL_SUCCESS);
}

int main(void) {
  gsl_set_error_handler_off();
  orders_on("harmonic oscillator", osc_rhs, osc_exact, 0.7, 1.6, 3);
  orders_on("limit cycle", cyc_rhs, cyc_exact, 0.7, 0.8, 3);
  test_driver();
  test_option();
  return check_summary();
}
