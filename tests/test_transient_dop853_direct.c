/* test_transient_dop853_direct.c: dop853 takes its steps on the user's right-hand side
 * directly (no counting adapter) with its own step-size control (src/transient/dop853.c,
 * take_step in transient.c).  What the adapter did must still hold: every evaluation counted
 * (against the right-hand side's own count), a failure code, a NaN and a rejected state
 * reported as with rk8pd, and the state at the last good step kept (closed form cos t). */
#include <math.h>
#include <stdio.h>

#include "autobal/transient.h"
#include "check.h"

typedef struct {
  unsigned long calls; /* the right-hand side's own count */
  double fail_after;   /* returns -7 for t > fail_after */
  double nan_after;    /* f[1] = NaN for t > nan_after */
  double reject_x;     /* AUTOBAL_TRANSIENT_RHS_REJECT for |x| > reject_x */
  double reject_t;     /* ... and for t > reject_t */
  unsigned long rejects;
} osc_ctx;

static int osc_rhs(double t, const double y[], double f[], void *p) {
  osc_ctx *c = (osc_ctx *)p;
  c->calls++;
  if (t > c->fail_after) return -7;
  if (fabs(y[0]) > c->reject_x || t > c->reject_t) {
    c->rejects++;
    return AUTOBAL_TRANSIENT_RHS_REJECT;
  }
  f[0] = y[1];
  f[1] = t > c->nan_after ? NAN : -y[0];
  return 0;
}

static void osc_init(osc_ctx *c) {
  c->calls = 0;
  c->fail_after = c->nan_after = c->reject_t = INFINITY;
  c->reject_x = INFINITY;
  c->rejects = 0;
}

typedef struct {
  unsigned long n;
  double max_err; /* largest |x - cos t| at the output times */
} obs_ctx;

static int obs(double t, const double y[], void *p) {
  obs_ctx *o = (obs_ctx *)p;
  const double e = fabs(y[0] - cos(t));
  o->n++;
  if (e > o->max_err) o->max_err = e;
  return 0;
}

static autobal_transient *make(double tol, double dt_out, double h_init) {
  autobal_transient_options o = autobal_transient_options_default();
  o.stepper = "dop853";
  o.rtol = tol;
  o.atol = tol;
  o.dt_out = dt_out;
  o.h_init = h_init;
  return autobal_transient_alloc(2, &o, NULL);
}

int main(void) {
  osc_ctx c;
  obs_ctx ob = {0, 0.0};
  autobal_transient_system sys = {osc_rhs, NULL, 2, &c};
  autobal_transient_stats st;
  double y[2], te = 0.0;
  int rc, k;
  autobal_transient *tr;

  /* counts: with dense output (the extension's stages through the adapter, the steps' directly)
   * and without an output grid, at three tolerances */
  for (k = 0; k < 3; k++) {
    const double tol = k == 0 ? 1e-6 : k == 1 ? 1e-9 : 1e-12;
    int grid;
    for (grid = 0; grid < 2; grid++) {
      char what[160];
      tr = make(tol, grid ? 0.37 : 0.0, 0.0);
      osc_init(&c);
      ob.n = 0, ob.max_err = 0.0;
      y[0] = 1.0, y[1] = 0.0;
      autobal_transient_set_observer(tr, obs, &ob);
      rc = autobal_transient_run(tr, &sys, 0.0, 20.0, y, &te);
      autobal_transient_get_stats(tr, &st);
      snprintf(what, sizeof what, "tol %g, %s: run succeeds", tol, grid ? "output every 0.37" : "no grid");
      CHECK_STATUS(what, rc, AUTOBAL_SUCCESS);
      printf("tol %g grid %d: %lu steps, %lu rejected, %lu rhs (own count %lu), max |x - cos t| %.2e\n", tol, grid,
             st.steps, st.rejected, st.rhs_evals, c.calls, ob.max_err);
      snprintf(what, sizeof what, "tol %g, %s: rhs_evals = the right-hand side's own count", tol,
               grid ? "output every 0.37" : "no grid");
      CHECK(what, st.rhs_evals == c.calls && c.calls > 0);
      /* 12 per trial step (f at the end reused as the next first stage), 2 for the automatic
       * first step (f(t0), the Euler probe), 3 more per step holding an output time */
      snprintf(what, sizeof what, "tol %g: 12 per trial step + the first stage (+ 3 per extension)", tol);
      CHECK(what, grid ? (c.calls > 12 * (st.steps + st.rejected) + 2 &&
                          c.calls <= 15 * (st.steps + st.rejected) + 2)
                       : c.calls == 12 * (st.steps + st.rejected) + 2);
      /* the control keeps the error near the tolerance (a closed form: x = cos t; the global
       * error over 3 periods, a few hundred times the tolerance at most) */
      snprintf(what, sizeof what, "tol %g: x(20) = cos 20 within 1000 tol", tol);
      CHECK_CLOSE(what, y[0], cos(20.0), 0.0, 1000.0 * tol);
      autobal_transient_free(tr);
    }
  }

  /* a failing right-hand side: ERHS naming the code, the state of the last good step kept */
  tr = make(1e-9, 0.0, 0.0);
  osc_init(&c);
  c.fail_after = 1.2345;
  y[0] = 1.0, y[1] = 0.0;
  rc = autobal_transient_run(tr, &sys, 0.0, 3.0, y, &te);
  autobal_transient_get_stats(tr, &st);
  CHECK_STATUS("failing rhs: ERHS", rc, AUTOBAL_ERHS);
  CHECK_MSG("failing rhs: message", autobal_transient_errmsg(tr), "right-hand side returned -7 at t = ");
  CHECK("failing rhs: user code -7 recorded", st.user_code == -7);
  CHECK("failing rhs: rhs_evals = own count", st.rhs_evals == c.calls);
  CHECK("failing rhs: t reached in (0.5, 1.2345]", te > 0.5 && te <= 1.2345);
  CHECK_CLOSE("failing rhs: state at the last good step = cos(t reached)", y[0], cos(te), 0.0, 1e-8);

  /* a NaN in a stage: ERHS "non-finite", state kept */
  osc_init(&c);
  c.nan_after = 2.0;
  y[0] = 1.0, y[1] = 0.0;
  rc = autobal_transient_run(tr, &sys, 0.0, 3.0, y, &te);
  CHECK_STATUS("NaN rhs: ERHS", rc, AUTOBAL_ERHS);
  CHECK_MSG("NaN rhs: message", autobal_transient_errmsg(tr), "non-finite");
  CHECK("NaN rhs: t reached in (1, 2]", te > 1.0 && te <= 2.0);
  CHECK_CLOSE("NaN rhs: state kept = cos(t reached)", y[0], cos(te), 0.0, 1e-8);
  autobal_transient_free(tr);

  /* rejected trial states (x = cos(t - 0.3) rises to 1 at t = 0.3; a first step of 6 overshoots):
   * the step is shortened and the run succeeds */
  tr = make(1e-9, 0.0, 6.0);
  osc_init(&c);
  c.reject_x = 1.0 + 1e-9;
  y[0] = cos(0.3), y[1] = sin(0.3);
  rc = autobal_transient_run(tr, &sys, 0.0, 10.0, y, &te);
  autobal_transient_get_stats(tr, &st);
  printf("domain |x| <= 1: %lu rejected trial states\n", c.rejects);
  CHECK_STATUS("rejected trial states: the run shortens its steps and succeeds", rc, AUTOBAL_SUCCESS);
  CHECK("... some trial state was rejected", c.rejects > 0);
  CHECK("... rhs_evals = own count", st.rhs_evals == c.calls);
  CHECK_CLOSE("... x(10) = cos(10 - 0.3)", y[0], cos(9.7), 0.0, 1e-7);
  /* a domain ending at t = 0.5: no step passes it */
  osc_init(&c);
  c.reject_t = 0.5;
  y[0] = 1.0, y[1] = 0.0;
  rc = autobal_transient_run(tr, &sys, 0.0, 10.0, y, &te);
  CHECK_STATUS("a domain ending at t = 0.5: ERHS", rc, AUTOBAL_ERHS);
  CHECK_MSG("... saying the right-hand side rejected the state", autobal_transient_errmsg(tr), "rejected");
  CHECK("... stopped at t in (0.49, 0.5]", te <= 0.5 && te > 0.49);
  autobal_transient_free(tr);
  return check_summary();
}
