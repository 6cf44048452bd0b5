/* test_transient_locate.c: event location of the transient engine against closed forms, on
 * trajectories that no stepper integrates exactly and no cubic interpolates exactly.
 *  - The oscillator x'' = -w^2 x, x(0) = 1, x'(0) = 0 (x = cos w t), event g = x - 0.3 in both
 *    directions: the crossings are at w t = +-acos(0.3) + 2 pi k.  Every hit lies on the far side of
 *    its crossing, within event_tol (plus the integration's own time error: its state error at the
 *    hits over |x'|, 1e-13 s for rk8pd, 2e-11 s for rk4imp), and the
 *    state handed to the handler is the integrated one (|x - cos w t_hit| to the tolerance) - the
 *    later trial points of the location are short RK4 hops from the earlier ones, and this checks
 *    them.  For rk8pd (first stage handed over, derivative at the trial point from the step),
 *    rkf45 (no exact derivative at the step's end: one more evaluation) and rk4imp (implicit).
 *  - The same oscillator with a wall at x = -1/2 and restitution e = 0.8 (a falling crossing, reset
 *    x' -> -e x'): from each post-impact state (x_k, v_k) at t_k the next impact is at
 *    t_k + (acos(-1/2 / R) + d) / w, R = hypot(x_k, v_k / w), d = atan2(v_k / w, x_k); every impact
 *    is checked against that closed form from the integrator's own previous impact, so the check
 *    is as sharp as event_tol, not blurred by the accumulated error.
 *  - The cost of the location (a regression guard, counts not times): rk8pd needs at most 4
 *    auxiliary steps or hops per crossing here. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "autobal/transient.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define W (2.0 * M_PI)
#define MAXHIT 64

static int rhs(double t, const double y[], double f[], void *p) {
  (void)t;
  (void)p;
  f[0] = y[1];
  f[1] = -W * W * y[0];
  return 0;
}

static double g_level(double t, const double y[], void *p) {
  (void)t;
  (void)p;
  return y[0] - 0.3;
}

static double g_wall(double t, const double y[], void *p) {
  (void)t;
  (void)p;
  return y[0] + 0.5;
}

typedef struct {
  int n;
  double t[MAXHIT], x[MAXHIT], v[MAXHIT]; /* at the hit (before a reset) */
  double xa[MAXHIT], va[MAXHIT];          /* after the reset */
} hits;

static int on_hit(const autobal_transient_event_hit *h, const double y[], void *u) {
  hits *H = (hits *)u;
  if (H->n < MAXHIT) {
    H->t[H->n] = h->t;
    H->x[H->n] = y[0];
    H->v[H->n] = y[1];
  }
  H->n++;
  return 0;
}

static int on_reset(const autobal_transient_event_hit *h, double y[], void *u) {
  hits *H = (hits *)u;
  (void)h;
  y[1] = -0.8 * y[1];
  if (H->n >= 1 && H->n <= MAXHIT) {
    H->xa[H->n - 1] = y[0];
    H->va[H->n - 1] = y[1];
  }
  return AUTOBAL_TRANSIENT_RESET;
}

/* A driver with `stepper` at rtol = atol = 1e-12 (into *o), event g in `direction`, the handler
 * recording into *H (zeroed); NULL (a failed check) if it cannot be allocated. */
static autobal_transient *make(const char *stepper, autobal_transient_options *o, hits *H,
                               double (*g)(double, const double *, void *), int direction) {
  autobal_transient *tr;
  memset(H, 0, sizeof *H);
  o->stepper = stepper;
  o->rtol = 1e-12;
  o->atol = 1e-12;
  tr = autobal_transient_alloc(2, o, NULL);
  if (!tr) {
    CHECK("alloc", 0);
    return NULL;
  }
  autobal_transient_add_event(tr, g, NULL, direction, 0);
  autobal_transient_set_event_handler(tr, on_hit, H);
  return tr;
}

static void level_crossings(const char *stepper) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys = {rhs, NULL, 2, NULL};
  autobal_transient *tr;
  autobal_transient_stats st;
  hits H;
  double y[2] = {1.0, 0.0}, worst_early = 0.0, worst_late = 0.0, worst_x = 0.0, terr;
  const double a = acos(0.3);
  int k, far = 1;
  char what[160];
  if (!(tr = make(stepper, &o, &H, g_level, 0))) return;
  CHECK_STATUS("run", autobal_transient_run(tr, &sys, 0.0, 10.0, y, NULL), AUTOBAL_SUCCESS);
  autobal_transient_get_stats(tr, &st);
  snprintf(what, sizeof what, "%s: 20 crossings of x = 0.3 in [0, 10]", stepper);
  CHECK(what, H.n == 20);
  for (k = 0; k < H.n && k < MAXHIT; k++) {
    /* crossing k: w t = acos(0.3) + 2 pi (k / 2) (falling, k even), 2 pi (k + 1) / 2 - acos(0.3) */
    const double ts = ((k % 2 == 0) ? a + M_PI * k : M_PI * (k + 1) - a) / W;
    const double d = H.t[k] - ts;
    if (d < 0.0) worst_early = fmax(worst_early, -d);
    worst_late = fmax(worst_late, d);
    worst_x = fmax(worst_x, fabs(H.x[k] - cos(W * H.t[k])));
    far &= (k % 2 == 0) ? H.x[k] <= 0.3 : H.x[k] >= 0.3;
  }
  /* (worst_x first: the allowance for the integration's own time error uses it) */
  /* the integration's own time error at a crossing: its state error over |x'| = w sqrt(1 - 0.09) */
  terr = 1e-13 + worst_x / (W * sqrt(1.0 - 0.09));
  snprintf(what, sizeof what, "%s: no hit before its crossing by more than the integration error (%.2g s)",
           stepper, terr);
  CHECK_CLOSE(what, worst_early, 0.0, 0.0, terr);
  snprintf(what, sizeof what, "%s: every hit within event_tol (1e-10 s) past its crossing (+ %.2g s)", stepper,
           terr);
  CHECK(what, worst_late <= o.event_tol + terr);
  snprintf(what, sizeof what, "%s: the state at the hits is the integrated one (|x - cos w t|)", stepper);
  CHECK_CLOSE(what, worst_x, 0.0, 0.0, 1e-9);
  snprintf(what, sizeof what, "%s: every hit on the far side (g of the hit state)", stepper);
  CHECK(what, far);
  if (strcmp(stepper, "rk8pd") == 0) {
    printf("     %s: %lu auxiliary steps and hops for %lu events, %lu evaluations in all\n", stepper,
           st.event_steps, st.events, st.rhs_evals);
    CHECK("rk8pd: at most 4 auxiliary steps or hops per crossing", st.event_steps <= 4 * st.events);
  }
  autobal_transient_free(tr);
}

static void wall_impacts(const char *stepper) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys = {rhs, NULL, 2, NULL};
  autobal_transient *tr;
  hits H;
  double y[2] = {1.0, 0.0}, worst = 0.0, worst_x = 0.0;
  int k, far = 1;
  char what[160];
  if (!(tr = make(stepper, &o, &H, g_wall, -1))) return;
  autobal_transient_set_event_reset(tr, on_reset, &H);
  CHECK_STATUS("run with the wall", autobal_transient_run(tr, &sys, 0.0, 5.0, y, NULL), AUTOBAL_SUCCESS);
  /* the impacts of the exact motion in [0, 5] (the closed form above from x = -1/2 exactly) */
  {
    double t = 1.0 / 3.0, v = 0.8 * W * sqrt(3.0) / 2.0;
    int n = 0;
    while (t <= 5.0) {
      const double R = hypot(-0.5, v / W), d = atan2(v / W, -0.5);
      n++;
      t += (acos(-0.5 / R) + d) / W;
      v *= 0.8;
    }
    snprintf(what, sizeof what, "%s: %d impacts on the wall in [0, 5] as the closed form (got %d)", stepper, n, H.n);
    CHECK(what, H.n == n && n >= 5);
  }
  CHECK_CLOSE("first impact at w t = 2 pi / 3", H.n > 0 ? H.t[0] : NAN, 1.0 / 3.0, 0.0, o.event_tol + 1e-12);
  for (k = 1; k < H.n && k < MAXHIT; k++) {
    const double xk = H.xa[k - 1], vk = H.va[k - 1];
    const double R = hypot(xk, vk / W), d = atan2(vk / W, xk);
    const double ts = H.t[k - 1] + (acos(-0.5 / R) + d) / W;
    worst = fmax(worst, fabs(H.t[k] - ts - 0.5 * o.event_tol));
    worst_x = fmax(worst_x, fabs(H.x[k] - (xk * cos(W * (H.t[k] - H.t[k - 1])) +
                                           vk / W * sin(W * (H.t[k] - H.t[k - 1])))));
    far &= H.x[k] <= -0.5;
  }
  snprintf(what, sizeof what,
           "%s: every impact within event_tol past the closed form from the previous one (|dt - tol/2| <= tol/2 + 1e-12)",
           stepper);
  CHECK(what, worst <= 0.5 * o.event_tol + 1e-12);
  snprintf(what, sizeof what, "%s: the state at each impact is the integrated one", stepper);
  CHECK_CLOSE(what, worst_x, 0.0, 0.0, 1e-9);
  snprintf(what, sizeof what, "%s: every impact state on the far side (x <= -1/2)", stepper);
  CHECK(what, far);
  autobal_transient_free(tr);
}

int main(void) {
  level_crossings("rk8pd");
  level_crossings("rkf45");
  level_crossings("rk4imp");
  wall_impacts("rk8pd");
  wall_impacts("rkf45");
  return check_summary();
}
