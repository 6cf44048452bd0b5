/* test_transient_dense_events.c: events on dop853's continuous extension (output dense, dense6)
 * where the step's ends and uniform probes cannot see them (issue 20, problems 1 and 2).
 * The state is y = t (y' = 1: steps limited only by h_max = 0.1), so every event time is known in
 * closed form from g alone:
 *  (a) a narrow crossing between probes: g = w^2 - (y - 0.531)^2 (w = 1e-3) is >= 0 only on
 *      [0.530, 0.532], inside a step of 0.1 whose 7 probes are 0.0125 apart: found by the search of
 *      the sampled maximum (probe_extremum), the hit just past the root 0.530;
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

/* a run of y' = 1 on [0, 1] with one event (rising only); probes, output probes; the count and hit */
static int run(int order, double (*g)(double, const double *, void *), unsigned probes, int at_outputs,
               unsigned long *count, double *t_hit) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys = {one, NULL, 1, NULL};
  autobal_transient_event_hit first;
  autobal_transient *tr;
  double y[1] = {0.0}, te = 0.0;
  unsigned long nobs = 0;
  int rc, idx;
  o.stepper = "dop853";
  o.dense_order = order;
  o.rtol = 1e-10;
  o.atol = 1e-10;
  o.h_max = 0.1;
  o.dt_out = 0.05;
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
  return rc == AUTOBAL_SUCCESS && nobs == 21 ? 0 : -2;
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
  return check_summary();
}
