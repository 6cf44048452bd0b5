/* test_transient_dense_events.c: events on dop853's continuous extension (output dense, dense6)
 * where the step's ends and uniform probes cannot see them (issue 20, problems 1 and 2), and (a)
 * also with exact output (the search on the integrated state).
 * The state is y = t (y' = 1: steps limited only by h_max = 0.1), so every event time is known in
 * closed form from g alone:
 *  (a) a narrow crossing between probes: g = w^2 - (y - 0.531)^2 (w = 1e-3) is >= 0 only on
 *      [0.530, 0.532], inside a step of 0.1 whose 7 probes are 0.0125 apart: found by the search of
 *      the sampled maximum (probe_extremum), the hit just past the root 0.530; with exact output
 *      (output every 0.1, so the steps stay 0.1 long) the same search on the integrated state,
 *      which dop853 and rk8pd missed before (0 events; dop853 took another stick-slip branch of
 *      tests/app/tight_tolerance.sh at rtol 1e-12 for it);
 *  (b) a crossing visible at an output time only: g = v^2 - (y - 0.6)^2 (v = 1e-4) with output
 *      every 0.05 (0.6 is one) and no probes: found with autobal_transient_set_event_output_probes,
 *      missed without it (0 events: the reason for the option);
 *  (c) where the hit lies: past the root by at most 1e-3 event_tol plus a few ulps (as locate()
 *      puts its far point), not anywhere in a bracket of event_tol. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "autobal/transient.h"
#include "check.h"

static int one(double t, const double y[], double f[], void *p) {
  (void)t, (void)y, (void)p;
  f[0] = 1.0;
  return 0;
}

static double g_narrow(double t, const double y[], void *p) {
  (void)t, (void)p;
  return 1e-6 - (y[0] - 0.531) * (y[0] - 0.531);
}

static double g_output(double t, const double y[], void *p) {
  (void)t, (void)p;
  return 1e-8 - (y[0] - 0.6) * (y[0] - 0.6);
}

static int count_obs(double t, const double y[], void *p) {
  (void)t, (void)y;
  (*(unsigned long *)p)++;
  return 0;
}

/* a run of y' = 1 on [0, 1] with one event (rising only); probes, output probes; the count and hit;
 * exact output: output every 0.1 (the steps' length), else every 0.05 on the extension */
static int run_with(int order, const char *stepper, int exact, double (*g)(double, const double *, void *),
                    unsigned probes, int at_outputs, unsigned long *count, double *t_hit) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys = {one, NULL, 1, NULL};
  autobal_transient_event_hit first;
  autobal_transient *tr;
  double y[1] = {0.0}, te = 0.0;
  unsigned long nobs = 0;
  int rc, idx;
  o.stepper = stepper;
  o.dense_order = order;
  o.exact_output = exact;
  o.rtol = 1e-10;
  o.atol = 1e-10;
  o.h_max = 0.1;
  o.dt_out = exact ? 0.1 : 0.05;
  o.event_tol = 1e-9;
  tr = autobal_transient_alloc(1, &o, NULL);
  if (!tr) return -1;
  autobal_transient_set_observer(tr, count_obs, &nobs);
  idx = autobal_transient_add_event(tr, g, NULL, 1, 0);
  if (probes) autobal_transient_set_event_probes(tr, idx, probes);
  if (at_outputs) autobal_transient_set_event_output_probes(tr, idx, 1);
  rc = autobal_transient_run(tr, &sys, 0.0, 1.0, y, &te);
  memset(&first, 0, sizeof first);
  autobal_transient_event_result(tr, (size_t)idx, count, &first);
  *t_hit = first.t;
  autobal_transient_free(tr);
  return rc == AUTOBAL_SUCCESS && nobs == (exact ? 11u : 21u) ? 0 : -2;
}

static int run(int order, double (*g)(double, const double *, void *), unsigned probes, int at_outputs,
               unsigned long *count, double *t_hit) {
  return run_with(order, "dop853", 0, g, probes, at_outputs, count, t_hit);
}

int main(void) {
  int order;
  for (order = 6; order <= 7; order++) {
    const char *name = order == 6 ? "dense6" : "dense";
    unsigned long n = 0;
    double th = 0.0;
    char what[256];
    int rc = run(order, g_narrow, 7, 0, &n, &th);
    printf("%s narrow: rc %d, %lu event(s), hit %.17g (root 0.530, hit - root %.3g)\n", name, rc, n, th, th - 0.530);
    snprintf(what, sizeof what, "%s: a crossing 2e-3 wide between probes 0.0125 apart found once", name);
    CHECK(what, rc == 0 && n == 1);
    snprintf(what, sizeof what, "%s: its hit past the root 0.530 by at most 1e-3 event_tol + 1e-15", name);
    CHECK(what, th >= 0.530 && th - 0.530 <= 1e-12 + 1e-15);
    rc = run(order, g_output, 0, 1, &n, &th);
    printf("%s at outputs: rc %d, %lu event(s), hit %.17g (root 0.5999, hit - root %.3g)\n", name, rc, n, th, th - 0.5999);
    snprintf(what, sizeof what, "%s: a crossing 2e-4 wide around the output time 0.6 found with output probes", name);
    CHECK(what, rc == 0 && n == 1 && th >= 0.5999 && th - 0.5999 <= 1e-12 + 1e-15);
    rc = run(order, g_output, 0, 0, &n, &th);
    snprintf(what, sizeof what, "%s: ... and missed without them (the steps' ends do not see it)", name);
    CHECK(what, rc == 0 && n == 0);
  }
  {
    static const char *const steppers[2] = {"dop853", "rk8pd"};
    int k;
    for (k = 0; k < 2; k++) {
      unsigned long n = 0;
      double th = 0.0;
      char what[256];
      const int rc = run_with(7, steppers[k], 1, g_narrow, 7, 0, &n, &th);
      printf("%s exact narrow: rc %d, %lu event(s), hit %.17g (hit - root %.3g)\n", steppers[k], rc, n, th, th - 0.530);
      snprintf(what, sizeof what, "%s, exact output: a crossing 2e-3 wide between probes 0.0125 apart found once", steppers[k]);
      CHECK(what, rc == 0 && n == 1);
      snprintf(what, sizeof what, "%s, exact output: its hit past the root 0.530 by at most event_tol", steppers[k]);
      CHECK(what, th >= 0.530 && th - 0.530 <= 1e-9);
    }
  }
  return check_summary();
}
