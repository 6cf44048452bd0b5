/* test_transient_probes.c: grazing crossings and exact zeros in the transient engine's event
 * location, against closed forms.
 *  - A bump: y' = (1, 2 t) (y_0 = t, y_1 = t^2: the stepper is exact, so one step of length 1 is
 *    accepted), g = w^2 - (y_0 - c)^2 > 0 only for |t - c| < w.  Both step ends have g < 0: without
 *    probes the crossing is missed; with n probes at t = k/(n + 1) it is found when a probe lies in
 *    the bump, and located at t = c - w (to event_tol); a bump between two probes is found too when
 *    the samples show it as a maximum whose parabola reaches 0 (the search between the probes, on
 *    the integrated state with exact output): 3 probes at 0.25, 0.5, 0.75 around the bump
 *    (0.32, 0.42).  The Hermite interpolant of t^2 from its values and slopes is exact.
 *  - A spike that leaves no trace at the samples (g = -1 + 2 exp(-((t - c)/w)^2), w = 1e-3: -1 to
 *    the last bit at every probe): missed with 15 probes, the documented limit.
 *  - An exact zero: g = y_0 - 1/2 on [0, 1] reaches 0.0 exactly at a secant point of the location
 *    (the first secant of the bracket [0, 1] is 1/2): the hit is reported strictly past the
 *    crossing (g > 0 there), within event_tol of 1/2, so a reset sees the new sign. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "autobal/transient.h"
#include "check.h"

static int rhs(double t, const double y[], double f[], void *p) {
  (void)y;
  (void)p;
  f[0] = 1.0;
  f[1] = 2.0 * t;
  return 0;
}

typedef struct {
  double c, w;
} bump;

static double g_bump(double t, const double y[], void *p) {
  const bump *b = (const bump *)p;
  (void)t;
  return b->w * b->w - (y[0] - b->c) * (y[0] - b->c);
}

static double g_spike(double t, const double y[], void *p) {
  const bump *b = (const bump *)p;
  const double z = (y[0] - b->c) / b->w;
  (void)t;
  return -1.0 + 2.0 * exp(-z * z);
}

static double g_half(double t, const double y[], void *p) {
  (void)t;
  (void)p;
  return y[0] - 0.5;
}

typedef struct {
  int n;
  double t, g;
} hits;

static double (*g_cur)(double, const double *, void *);
static void *g_user;

static int on_hit(const autobal_transient_event_hit *h, const double y[], void *u) {
  hits *H = (hits *)u;
  H->n++;
  H->t = h->t;
  H->g = g_cur(h->t, y, g_user);
  return 0;
}

/* One run over [0, 1] with one event, n probes; returns the hits. */
static hits run(double (*g)(double, const double *, void *), void *user, unsigned n, int direction) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys = {rhs, NULL, 2, NULL};
  autobal_transient *tr;
  hits H;
  double y[2] = {0.0, 0.0};
  int idx;
  memset(&H, 0, sizeof H);
  o.h_init = 1.0; /* one step: the stepper is exact for t and t^2 */
  o.rtol = 1e-6;
  o.atol = 1e-9;
  o.event_tol = 1e-12;
  tr = autobal_transient_alloc(2, &o, NULL);
  if (!tr) return H;
  g_cur = g;
  g_user = user;
  idx = autobal_transient_add_event(tr, g, user, direction, 0);
  CHECK_STATUS("probes set", autobal_transient_set_event_probes(tr, idx, n), AUTOBAL_SUCCESS);
  autobal_transient_set_event_handler(tr, on_hit, &H);
  CHECK_STATUS("run to t = 1", autobal_transient_run(tr, &sys, 0.0, 1.0, y, NULL), AUTOBAL_SUCCESS);
  {
    autobal_transient_stats st;
    autobal_transient_get_stats(tr, &st);
    printf("     %u probes: %lu step(s), %d hit(s)%s, probe hits %lu\n", n, st.steps, H.n, H.n ? "" : " (missed)",
           autobal_transient_probe_hits(tr));
  }
  autobal_transient_free(tr);
  return H;
}

int main(void) {
  bump b = {0.37, 0.05};
  hits H;
  char what[200];
  autobal_transient *tr;
  printf("-- a bump of width 0.1 at t = 0.37 inside one step\n");
  H = run(g_bump, &b, 0, 0);
  CHECK("no probes: the bump is missed (both step ends have g < 0)", H.n == 0);
  H = run(g_bump, &b, 15, 0);
  CHECK("15 probes (spacing 1/16 < 0.1): found once", H.n == 1);
  snprintf(what, sizeof what, "located at c - w = 0.32 (t = %.15f)", H.t);
  CHECK_CLOSE(what, H.t, 0.32, 0.0, 1e-11);
  CHECK("the hit is past the crossing (g >= 0)", H.g >= 0.0);
  H = run(g_bump, &b, 15, -1);
  CHECK("15 probes, direction -1 (falling only): not reported", H.n == 0);
  H = run(g_bump, &b, 3, 0);
  CHECK("3 probes (at 0.25, 0.5, 0.75; none in (0.32, 0.42)): found by the search between the probes", H.n == 1);
  snprintf(what, sizeof what, "... located at c - w = 0.32 (t = %.15f)", H.t);
  CHECK_CLOSE(what, H.t, 0.32, 0.0, 1e-11);
  {
    bump sp = {0.37, 1e-3};
    H = run(g_spike, &sp, 15, 0);
    CHECK("a spike 2e-3 wide between probes 1/16 apart, -1 at every probe: missed, the documented limit", H.n == 0);
  }
  b.c = 0.5;
  H = run(g_bump, &b, 1, 1);
  CHECK("1 probe at 0.5 inside a bump at 0.5: found, rising", H.n == 1);
  CHECK_CLOSE("located at 0.45", H.t, 0.45, 0.0, 1e-11);

  printf("-- an exact zero at a secant point\n");
  H = run(g_half, NULL, 0, 1);
  CHECK("one hit", H.n == 1);
  snprintf(what, sizeof what, "g at the hit > 0 (strictly past the crossing: %.3e)", H.g);
  CHECK(what, H.g > 0.0);
  CHECK_CLOSE("within event_tol of 1/2", H.t, 0.5, 0.0, 1e-12);

  printf("-- argument checks\n");
  tr = autobal_transient_alloc(2, NULL, NULL);
  CHECK_STATUS("probes of an event that does not exist", autobal_transient_set_event_probes(tr, 0, 3), AUTOBAL_EINVAL);
  autobal_transient_add_event(tr, g_half, NULL, 0, 0);
  CHECK_STATUS("65 probes refused", autobal_transient_set_event_probes(tr, 0, 65), AUTOBAL_EINVAL);
  CHECK_STATUS("64 probes", autobal_transient_set_event_probes(tr, 0, 64), AUTOBAL_SUCCESS);
  CHECK_STATUS("NULL handle", autobal_transient_set_event_probes(NULL, 0, 3), AUTOBAL_EINVAL);
  autobal_transient_free(tr);
  return check_summary();
}
