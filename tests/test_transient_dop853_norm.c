/* test_transient_dop853_norm.c: DOP853's normwise error estimate does not overflow (issue 20,
 * problem 3).  Hairer's factor |e5|^2 / sqrt(|e5|^2 + 0.01 |e3|^2) sums the squares of
 * e / (atol + rtol |y|); with atol = 1e-300 from rest those squares overflowed (inf / inf = NaN)
 * and `rotor transient --set transient.atol=1e-300` stopped at t = 0 with exit 5.
 *  (a) one step, the same step with rtol = 0 at atol = 1e-100 (plain sums, no overflow) and at
 *      atol = 1e-300 (sums overflow): the scale atol is common to every component, so the factor
 *      and yerr must agree to rounding (not NaN); a component that is identically 0 with atol = 0
 *      (0 / 0 in the plain sums) leaves the other components' yerr as without it;
 *  (b) the driver from rest with atol = 1e-300, rtol = 1e-10, output exact, dense and dense6: the
 *      forced oscillator x'' + x = cos t (x = t sin t / 2, closed form) reaches t = 20 with the
 *      error at the output points within 100 rtol max|x|, as with atol = 1e-12;
 *  (c) the step's own step-size control (autobal_transient_dop853_hadjust_, its ratio max computed
 *      inside the step) against GSL's standard control (a_y = 1, a_dydt = 0) on the same step:
 *      systems of 1 to 31 components (the unrolled sizes and the general one, with and without
 *      padding), components identically 0 (0 / 0 with atol = 0), three tolerance pairs, four step
 *      sizes: the same decision, the same new step bit for bit when it shrinks or stays (GSL's
 *      formulas), within 1e-15 when it grows (rmax^(1/8) as three square roots, not pow). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "autobal/transient.h"
#include "check.h"
#include "transient/dop853.h"

/* a pendulum (nonlinear: e5, e3 not 0) with an optional third component that stays 0 */
static int pend(double t, const double y[], double f[], void *p) {
  const size_t dim = *(const size_t *)p;
  (void)t;
  f[0] = y[1];
  f[1] = -sin(y[0]);
  if (dim > 2) f[2] = 0.0;
  return GSL_SUCCESS;
}

/* one step of h from y0 with the given tolerances: yerr into out, the status returned */
static int one_step(size_t dim, double atol, double rtol, const double y0[], double h, double yerr[]) {
  size_t d = dim;
  gsl_odeiv2_system sys = {pend, NULL, dim, &d};
  gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(&autobal_transient_dop853_type_, dim);
  double y[3], dydt[3];
  int st;
  memcpy(y, y0, dim * sizeof(double));
  autobal_transient_dop853_set_tol_(s->state, atol, rtol);
  st = gsl_odeiv2_step_apply(s, 0.0, h, y, yerr, NULL, dydt, &sys);
  gsl_odeiv2_step_free(s);
  return st;
}

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(a), fabs(b)); }

typedef struct {
  unsigned long n;
  double max_err, max_x;
} obs_ctx;

static int forced(double t, const double y[], double f[], void *p) {
  (void)p;
  f[0] = y[1];
  f[1] = -y[0] + cos(t);
  return 0;
}

static int obs(double t, const double y[], void *p) {
  obs_ctx *o = (obs_ctx *)p;
  const double x = 0.5 * t * sin(t), e = fabs(y[0] - x);
  o->n++;
  if (e > o->max_err) o->max_err = e;
  if (fabs(x) > o->max_x) o->max_x = fabs(x);
  return 0;
}

static int run_forced(double atol, int exact, int order, obs_ctx *o, double *t_end, char *msg, size_t msz) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient_system sys = {forced, NULL, 2, NULL};
  autobal_transient *tr;
  double y[2] = {0.0, 0.0};
  int rc;
  opt.stepper = "dop853";
  opt.rtol = 1e-10;
  opt.atol = atol;
  opt.dt_out = 0.25;
  opt.exact_output = exact;
  opt.dense_order = order;
  tr = autobal_transient_alloc(2, &opt, NULL);
  if (tr == NULL) return -1;
  memset(o, 0, sizeof *o);
  autobal_transient_set_observer(tr, obs, o);
  rc = autobal_transient_run(tr, &sys, 0.0, 20.0, y, t_end);
  snprintf(msg, msz, "%s", rc == AUTOBAL_SUCCESS ? "" : autobal_transient_errmsg(tr));
  autobal_transient_free(tr);
  return rc;
}

/* n components; every fifth from the fourth is identically 0 (and starts at 0) */
static int coupled(double t, const double y[], double f[], void *p) {
  const size_t dim = *(const size_t *)p;
  size_t i;
  (void)t;
  for (i = 0; i < dim; i++) f[i] = i % 5 == 3 ? 0.0 : y[(i + 1) % dim] - (1.0 + 0.1 * (double)i) * sin(y[i]);
  return GSL_SUCCESS;
}

/* (c): returns the number of failed comparisons; counts the decisions in n_dec, n_nil, n_inc */
static int control_cases(int *n_dec, int *n_nil, int *n_inc) {
  static const size_t dims[] = {1, 2, 3, 4, 5, 8, 11, 12, 13, 17, 20, 24, 25, 31};
  static const double tols[3][2] = {{1e-8, 1e-8}, {0.0, 1e-6}, {1e-9, 0.0}}; /* atol, rtol */
  static const double hs[4] = {0.003, 0.05, 0.3, 1.5};
  size_t di, ti, hi, i;
  int bad = 0;
  for (di = 0; di < sizeof dims / sizeof dims[0]; di++) {
    size_t dim = dims[di];
    gsl_odeiv2_system sys = {coupled, NULL, dim, &dim};
    for (ti = 0; ti < 3; ti++) {
      gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(&autobal_transient_dop853_type_, dim);
      gsl_odeiv2_control *c = gsl_odeiv2_control_standard_new(tols[ti][0], tols[ti][1], 1.0, 0.0);
      for (hi = 0; hi < 4; hi++) {
        double y[31], yerr[31], dydt[31], h1 = hs[hi], h2 = hs[hi];
        int a1, a2, st;
        for (i = 0; i < dim; i++) y[i] = i % 5 == 3 ? 0.0 : 0.3 + 0.7 * sin(1.3 * (double)i + 0.5);
        autobal_transient_dop853_set_tol_(s->state, tols[ti][0], tols[ti][1]);
        gsl_odeiv2_step_reset(s);
        st = gsl_odeiv2_step_apply(s, 0.0, hs[hi], y, yerr, NULL, dydt, &sys);
        a1 = autobal_transient_dop853_hadjust_(s->state, &h1);
        a2 = gsl_odeiv2_control_hadjust(c, s, y, yerr, dydt, &h2);
        if (st != GSL_SUCCESS || a1 != a2 || (a1 != GSL_ODEIV_HADJ_INC && h1 != h2) ||
            (a1 == GSL_ODEIV_HADJ_INC && !(fabs(h1 - h2) <= 1e-15 * h2))) {
          printf("  dim %zu atol %g rtol %g h %g: step %d, own %d %.17g, GSL %d %.17g\n", dim, tols[ti][0],
                 tols[ti][1], hs[hi], st, a1, h1, a2, h2);
          bad++;
        }
        *(a2 == GSL_ODEIV_HADJ_DEC ? n_dec : a2 == GSL_ODEIV_HADJ_INC ? n_inc : n_nil) += 1;
      }
      gsl_odeiv2_control_free(c);
      gsl_odeiv2_step_free(s);
    }
  }
  return bad;
}

int main(void) {
  /* (a) one step */
  {
    const double y0[3] = {2.5, 0.3, 0.0};
    double ea[3], eb[3], ec[3], e2[2];
    int sa = one_step(2, 1e-100, 0.0, y0, 0.5, ea);
    int sb = one_step(2, 1e-300, 0.0, y0, 0.5, eb);
    printf("yerr at atol 1e-100: %.17g %.17g; at 1e-300: %.17g %.17g\n", ea[0], ea[1], eb[0], eb[1]);
    CHECK("rtol = 0, atol = 1e-100 and 1e-300: both steps computed", sa == GSL_SUCCESS && sb == GSL_SUCCESS);
    CHECK("the errors are not 0 (the case tests something)", ea[0] != 0.0 && ea[1] != 0.0);
    CHECK("atol = 1e-300 (the squares overflow): yerr finite, equal to atol = 1e-100's to 1e-14",
          isfinite(eb[0]) && isfinite(eb[1]) && rel(ea[0], eb[0]) < 1e-14 && rel(ea[1], eb[1]) < 1e-14);
    sa = one_step(3, 0.0, 1e-8, y0, 0.5, ec);
    sb = one_step(2, 0.0, 1e-8, y0, 0.5, e2);
    printf("atol = 0, a zero component: %.17g %.17g %.17g; without it: %.17g %.17g\n", ec[0], ec[1], ec[2], e2[0],
           e2[1]);
    CHECK("atol = 0 with a component identically 0 (0 / 0): yerr finite, as without that component (1e-14)",
          sa == GSL_SUCCESS && sb == GSL_SUCCESS && isfinite(ec[0]) && isfinite(ec[1]) && ec[2] == 0.0 &&
              rel(ec[0], e2[0]) < 1e-14 && rel(ec[1], e2[1]) < 1e-14);
  }
  /* (b) the driver from rest */
  {
    static const struct {
      int exact, order;
      const char *name;
    } cases[3] = {{1, 7, "exact"}, {0, 7, "dense"}, {0, 6, "dense6"}};
    int k;
    for (k = 0; k < 3; k++) {
      obs_ctx o, r;
      double te = 0.0, tr = 0.0;
      char msg[512], msg2[512], what[256];
      int rc = run_forced(1e-300, cases[k].exact, cases[k].order, &o, &te, msg, sizeof msg);
      int rc2 = run_forced(1e-12, cases[k].exact, cases[k].order, &r, &tr, msg2, sizeof msg2);
      printf("%-6s atol 1e-300: rc %d t %.6g, %lu outputs, max error %.3e (max |x| %.3g) %s; atol 1e-12: %.3e\n",
             cases[k].name, rc, te, o.n, o.max_err, o.max_x, msg, r.max_err);
      snprintf(what, sizeof what, "output %s, atol = 1e-300 from rest: reaches t = 20, 81 outputs", cases[k].name);
      CHECK(what, rc == AUTOBAL_SUCCESS && te == 20.0 && o.n == 81);
      snprintf(what, sizeof what, "output %s, atol = 1e-300: error at the outputs <= 100 rtol max|x| (and atol = 1e-12's)",
               cases[k].name);
      CHECK(what, rc2 == AUTOBAL_SUCCESS && o.max_err <= 100.0 * 1e-10 * o.max_x && r.max_err <= 100.0 * 1e-10 * r.max_x);
    }
  }
  /* (c) the step's own control against GSL's */
  {
    int n_dec = 0, n_nil = 0, n_inc = 0;
    const int bad = control_cases(&n_dec, &n_nil, &n_inc);
    printf("own control vs GSL's standard control: %d differ; decisions: %d shrink, %d keep, %d grow\n", bad, n_dec,
           n_nil, n_inc);
    CHECK("the step's own control: GSL's decision and step in every case (shrink, keep: bit for bit; grow: 1e-15)",
          bad == 0);
    CHECK("every decision occurs (the cases test shrinking, keeping and growing)", n_dec > 0 && n_nil > 0 && n_inc > 0);
  }
  return check_summary();
}
