/* test_transient_reset.c: event resets of the transient engine (hybrid systems), checked
 * against closed forms:
 *  - a ball bouncing on a floor with restitution e: impact times
 *    t_1 = sqrt(2 h / g), t_{k+1} = t_k + 2 e^k v_1 / g, v_1 = g t_1; with e = 1 the
 *    height is restored after every bounce (energy conserved by the reset);
 *  - a mass on a spring with Coulomb friction (kinetic F, static F_s >= F per unit mass):
 *    each half-cycle lasts pi / w and shrinks the amplitude by 2 F / w^2, the mass sticks at
 *    the first turning point x_n with w^2 |x_n| <= F_s and stays there (the output grid
 *    goes on); a stuck mass pulled by a force a t breaks free at t = (F_s + w^2 x) / a;
 *  - a reset that re-arms its own event at once (chattering) stops the run with ESTEP. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "autobal/transient.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- bouncing ball ------------------------------------------------------- */
typedef struct {
  double g, e;
  int bounces, max_bounces;
  double t_hit[64], v_before[64];
} ball_ctx;

static int ball_rhs(double t, const double y[], double f[], void *p) {
  const ball_ctx *b = (const ball_ctx *)p;
  (void)t;
  f[0] = y[1];
  f[1] = -b->g;
  return 0;
}
static double ball_floor(double t, const double y[], void *p) {
  (void)t;
  (void)p;
  return y[0];
}
static int ball_reset(const autobal_transient_event_hit *h, double y[], void *p) {
  ball_ctx *b = (ball_ctx *)p;
  if (b->bounces < 64) {
    b->t_hit[b->bounces] = h->t;
    b->v_before[b->bounces] = y[1];
  }
  b->bounces++;
  if (b->bounces >= b->max_bounces) return 7; /* stop */
  y[0] = 0.0;
  y[1] = -b->e * y[1];
  return AUTOBAL_TRANSIENT_RESET;
}

static void test_bouncing_ball(double e) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  ball_ctx b;
  autobal_transient_system sys;
  autobal_transient_stats st;
  double y[2] = {1.0, 0.0}, tr_end = 0.0, t1, v1, tk;
  int rc, k;
  char what[96];
  memset(&b, 0, sizeof b);
  b.g = 9.80665;
  b.e = e;
  b.max_bounces = 10;
  o.rtol = 1e-12;
  o.atol = 1e-14;
  o.event_tol = 1e-13;
  tr = autobal_transient_alloc(2, &o, NULL);
  sys.rhs = ball_rhs;
  sys.jac = NULL;
  sys.dim = 2;
  sys.params = &b;
  autobal_transient_add_event(tr, ball_floor, NULL, -1, 0);
  autobal_transient_set_event_reset(tr, ball_reset, &b);
  rc = autobal_transient_run(tr, &sys, 0.0, 100.0, y, &tr_end);
  autobal_transient_get_stats(tr, &st);
  snprintf(what, sizeof what, "bouncing ball e = %g: stopped by the reset after 10 bounces", e);
  CHECK_STATUS(what, rc, AUTOBAL_EVENT);
  CHECK("stop reason event, user code 7", st.stop_reason == AUTOBAL_TRANSIENT_STOP_EVENT && st.user_code == 7);
  CHECK("9 resets counted", st.resets == 9);
  t1 = sqrt(2.0 * 1.0 / b.g);
  v1 = b.g * t1;
  tk = t1;
  for (k = 0; k < 10; k++) {
    snprintf(what, sizeof what, "e = %g: impact %d time (closed form)", e, k + 1);
    CHECK_CLOSE(what, b.t_hit[k], tk, 0.0, 1e-10);
    snprintf(what, sizeof what, "e = %g: impact %d speed e^k v_1", e, k + 1);
    CHECK_CLOSE(what, -b.v_before[k], pow(e, k) * v1, 1e-10, 0.0);
    tk += 2.0 * pow(e, k + 1) * v1 / b.g;
  }
  autobal_transient_free(tr);
}

/* ---- spring-mass with Coulomb friction and stiction ---------------------- */
typedef struct {
  double w2, F, Fs, pull; /* per unit mass: spring w^2, kinetic F, static Fs, pulling force rate */
  int stuck, dir;         /* dir: sense of the slip (+1 / -1) */
  int n_stick, n_slip;
  double t_stick, x_stick, t_slip;
  double t_turn[64];
  int n_turn;
} fric_ctx;

static int fric_rhs(double t, const double y[], double f[], void *p) {
  const fric_ctx *c = (const fric_ctx *)p;
  if (c->stuck) {
    f[0] = 0.0;
    f[1] = 0.0;
  } else {
    f[0] = y[1];
    f[1] = -c->w2 * y[0] + c->pull * t - c->F * c->dir;
  }
  return 0;
}
/* event 0: the slip velocity reaches 0 (only while slipping) */
static double fric_g_stop(double t, const double y[], void *p) {
  const fric_ctx *c = (const fric_ctx *)p;
  (void)t;
  return c->stuck ? 1.0 : y[1] * c->dir;
}
/* event 1: the holding force exceeds the static limit (only while stuck) */
static double fric_g_break(double t, const double y[], void *p) {
  const fric_ctx *c = (const fric_ctx *)p;
  return c->stuck ? fabs(-c->w2 * y[0] + c->pull * t) - c->Fs : -1.0;
}
static int fric_reset(const autobal_transient_event_hit *h, double y[], void *p) {
  fric_ctx *c = (fric_ctx *)p;
  const double hold = -c->w2 * y[0] + c->pull * h->t; /* force needed to hold the mass */
  y[1] = 0.0;
  if (h->index == 0 && c->n_turn < 64) c->t_turn[c->n_turn++] = h->t;
  /* the velocity reached 0: the mass sticks if the holding force is within the static limit;
   * the holding force reached the limit (event 1): it slips */
  if (h->index == 0 && fabs(hold) <= c->Fs) {
    if (!c->stuck) {
      c->n_stick++;
      c->t_stick = h->t;
      c->x_stick = y[0];
    }
    c->stuck = 1;
  } else {
    if (c->stuck) {
      c->n_slip++;
      c->t_slip = h->t;
    }
    c->stuck = 0;
    c->dir = hold > 0 ? 1 : -1;
  }
  return AUTOBAL_TRANSIENT_RESET;
}

static double grid_x[1000];
static size_t grid_n;
static double grid_t[1000];
static int grid_obs(double t, const double y[], void *u) {
  (void)u;
  if (grid_n < 1000) {
    grid_t[grid_n] = t;
    grid_x[grid_n] = y[0];
  }
  grid_n++;
  return 0;
}

static void test_stick_slip(void) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  fric_ctx c;
  autobal_transient_system sys;
  autobal_transient_stats st;
  const double w = 2.0, A = 1.0;
  double y[2] = {A, 0.0}, te = 0.0, xn = A;
  int rc, n = 0, k, grid_ok = 1, still = 1;
  size_t i;
  memset(&c, 0, sizeof c);
  c.w2 = w * w;
  c.F = 0.3;
  c.Fs = 0.5;
  c.dir = -1; /* the spring pulls towards -x */
  o.rtol = 1e-12;
  o.atol = 1e-14;
  o.event_tol = 1e-13;
  o.dt_out = 0.1;
  tr = autobal_transient_alloc(2, &o, NULL);
  sys.rhs = fric_rhs;
  sys.jac = NULL;
  sys.dim = 2;
  sys.params = &c;
  autobal_transient_add_event(tr, fric_g_stop, &c, -1, 0);
  autobal_transient_add_event(tr, fric_g_break, &c, 1, 0);
  autobal_transient_set_event_reset(tr, fric_reset, &c);
  grid_n = 0;
  autobal_transient_set_observer(tr, grid_obs, NULL);
  rc = autobal_transient_run(tr, &sys, 0.0, 10.0, y, &te);
  autobal_transient_get_stats(tr, &st);
  CHECK_STATUS("stick-slip oscillator runs to t1", rc, AUTOBAL_SUCCESS);
  /* closed form: turning points x_k = (-1)^k (A - 2 k F / w^2) until w^2 |x_k| <= F_s */
  while (c.w2 * fabs(xn) > c.Fs) {
    n++;
    xn = (n % 2 ? -1.0 : 1.0) * (A - 2.0 * n * c.F / c.w2);
  }
  printf("closed form: %d half-cycles, sticks at x = %.15g, t = %.15g\n", n, xn, n * M_PI / w);
  CHECK("the mass sticks once and never slips again", c.n_stick == 1 && c.n_slip == 0);
  CHECK("one turning point per half-cycle", c.n_turn == n);
  for (k = 0; k < c.n_turn && k < n; k++) {
    char what[64];
    snprintf(what, sizeof what, "turning point %d at k pi / w", k + 1);
    CHECK_CLOSE(what, c.t_turn[k], (k + 1) * M_PI / w, 0.0, 1e-10);
  }
  CHECK_CLOSE("stick time n pi / w", c.t_stick, n * M_PI / w, 0.0, 1e-10);
  CHECK_CLOSE("stick position", c.x_stick, xn, 0.0, 1e-10);
  CHECK_CLOSE("final position = stick position", y[0], xn, 0.0, 1e-10);
  CHECK("resets = turning points", st.resets == (unsigned long)n);
  /* the output grid is kept through the resets: 101 samples at k dt_out, and after the stick
   * the samples do not move */
  for (i = 0; i < grid_n && i < 1000; i++) {
    if (fabs(grid_t[i] - 0.1 * (double)i) > 1e-12 * (1.0 + (double)i)) grid_ok = 0;
    if (grid_t[i] > c.t_stick && grid_x[i] != c.x_stick) still = 0;
  }
  CHECK("observer grid: 101 samples at k * 0.1", grid_n == 101 && grid_ok);
  CHECK("samples after the stick stay at the stick position", still);
  autobal_transient_free(tr);

  /* a stuck mass pulled by a t breaks free at (F_s + w^2 x) / a */
  memset(&c, 0, sizeof c);
  c.w2 = 4.0;
  c.F = 0.3;
  c.Fs = 0.5;
  c.pull = 0.25;
  c.stuck = 1;
  c.dir = 1;
  y[0] = 0.05;
  y[1] = 0.0;
  tr = autobal_transient_alloc(2, &o, NULL);
  sys.params = &c;
  autobal_transient_add_event(tr, fric_g_stop, &c, -1, 0);
  autobal_transient_add_event(tr, fric_g_break, &c, 1, 0);
  autobal_transient_set_event_reset(tr, fric_reset, &c);
  rc = autobal_transient_run(tr, &sys, 0.0, 3.0, y, &te);
  CHECK_STATUS("pulled mass runs", rc, AUTOBAL_SUCCESS);
  CHECK("it breaks free once", c.n_slip == 1);
  CHECK_CLOSE("break-free time (F_s + w^2 x) / a", c.t_slip, (c.Fs + c.w2 * 0.05) / c.pull, 0.0, 1e-10);
  autobal_transient_free(tr);
}

/* ---- chattering ---------------------------------------------------------- */
static int fall_rhs(double t, const double y[], double f[], void *p) {
  (void)t;
  (void)y;
  (void)p;
  f[0] = -1.0;
  return 0;
}
static double fall_g(double t, const double y[], void *p) {
  (void)t;
  (void)p;
  return y[0];
}
static int rearm_reset(const autobal_transient_event_hit *h, double y[], void *p) {
  (void)h;
  (void)p;
  y[0] = 1e-14;
  return AUTOBAL_TRANSIENT_RESET;
}
static int nan_reset(const autobal_transient_event_hit *h, double y[], void *p) {
  (void)h;
  (void)p;
  y[0] = NAN;
  return AUTOBAL_TRANSIENT_RESET;
}

static void test_chatter(void) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr = autobal_transient_alloc(1, &o, NULL);
  autobal_transient_system sys = {fall_rhs, NULL, 1, NULL};
  autobal_transient_stats st;
  double y[1] = {0.5}, te = 0.0;
  int rc;
  autobal_transient_add_event(tr, fall_g, NULL, -1, 0);
  autobal_transient_set_event_reset(tr, rearm_reset, NULL);
  rc = autobal_transient_run(tr, &sys, 0.0, 2.0, y, &te);
  autobal_transient_get_stats(tr, &st);
  CHECK_STATUS("a reset that re-arms its event at once: ESTEP", rc, AUTOBAL_ESTEP);
  CHECK_MSG("the message says chattering", autobal_transient_errmsg(tr), "chattering");
  printf("chattering: %lu resets, stopped at t = %.17g\n", st.resets, te);
  CHECK_CLOSE("it stopped near the accumulation point t = 0.5", te, 0.5, 0.0, 1e-6);
  CHECK("more than 1000 resets", st.resets > 1000);
  autobal_transient_set_event_reset(tr, nan_reset, NULL);
  y[0] = 0.5;
  rc = autobal_transient_run(tr, &sys, 0.0, 2.0, y, &te);
  CHECK_STATUS("a reset that writes NaN: ENUMERIC", rc, AUTOBAL_ENUMERIC);
  CHECK_MSG("the message names the reset", autobal_transient_errmsg(tr), "event reset");
  autobal_transient_set_event_reset(tr, NULL, NULL);
  y[0] = 0.5;
  rc = autobal_transient_run(tr, &sys, 0.0, 2.0, y, &te);
  CHECK_STATUS("reset removed: the event is only reported", rc, AUTOBAL_SUCCESS);
  CHECK_CLOSE("and the run ends at y = -1.5", y[0], -1.5, 1e-12, 1e-12);
  autobal_transient_free(tr);
}

/* ---- AUTOBAL_TRANSIENT_RHS_REJECT: a trial state outside the domain shortens the step ------ */
typedef struct {
  int code;       /* what to return outside the domain */
  double t_limit; /* the domain also ends at t > t_limit */
  unsigned long rejects;
} dom_ctx;
static int dom_rhs(double t, const double y[], double f[], void *p) {
  dom_ctx *d = (dom_ctx *)p;
  if (fabs(y[0]) > 1.0 + 1e-9 || t > d->t_limit) {
    d->rejects++;
    return d->code;
  }
  f[0] = y[1];
  f[1] = -y[0];
  return 0;
}

static void test_reject(void) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  dom_ctx d = {AUTOBAL_TRANSIENT_RHS_REJECT, 1e300, 0};
  autobal_transient_system sys = {dom_rhs, NULL, 2, &d};
  /* x = cos(t - 0.3): it rises to 1 at t = 0.3, so a long trial step's stages overshoot */
  const double x0 = cos(0.3), v0 = sin(0.3);
  double y[2] = {x0, v0}, te = 0.0;
  int rc;
  o.h_init = 2.0; /* a first step long enough for the stages to leave |x| <= 1 */
  tr = autobal_transient_alloc(2, &o, NULL);
  rc = autobal_transient_run(tr, &sys, 0.0, 10.0, y, &te);
  printf("domain |x| <= 1: %lu rejected trial states\n", d.rejects);
  CHECK_STATUS("rejected trial states: the run shortens its steps and succeeds", rc, AUTOBAL_SUCCESS);
  CHECK("... and some trial state was rejected", d.rejects > 0);
  CHECK_CLOSE("x(10) = cos(10 - 0.3)", y[0], cos(9.7), 0.0, 1e-8);
  /* the same with an ordinary failure code: fatal, as before */
  d.code = 1, d.rejects = 0;
  y[0] = x0, y[1] = v0;
  rc = autobal_transient_run(tr, &sys, 0.0, 10.0, y, &te);
  CHECK_STATUS("an ordinary failure code at a trial state stops the run", rc, AUTOBAL_ERHS);
  /* a domain that ends in time: no step can pass it */
  d.code = AUTOBAL_TRANSIENT_RHS_REJECT, d.t_limit = 0.5, d.rejects = 0;
  y[0] = 1.0, y[1] = 0.0;
  rc = autobal_transient_run(tr, &sys, 0.0, 10.0, y, &te);
  CHECK_STATUS("a domain ending at t = 0.5: ERHS", rc, AUTOBAL_ERHS);
  CHECK_MSG("... saying the right-hand side rejected the state", autobal_transient_errmsg(tr), "rejected");
  CHECK("... stopped at t <= 0.5", te <= 0.5 && te > 0.49);
  /* a rejected initial state */
  d.t_limit = -1.0;
  y[0] = 1.0, y[1] = 0.0;
  rc = autobal_transient_run(tr, &sys, 0.0, 10.0, y, &te);
  CHECK_STATUS("a rejected initial state: ERHS", rc, AUTOBAL_ERHS);
  autobal_transient_free(tr);
  /* the automatic first step probes a state outside the domain: it is shortened */
  o.h_init = 0.0;
  o.rtol = 1e-3, o.atol = 1e-3;
  tr = autobal_transient_alloc(2, &o, NULL);
  d.t_limit = 1e300, d.rejects = 0;
  y[0] = x0, y[1] = v0;
  rc = autobal_transient_run(tr, &sys, 0.0, 3.0, y, &te);
  printf("loose tolerances: %lu rejected trial states\n", d.rejects);
  CHECK_STATUS("loose tolerances, automatic first step: succeeds", rc, AUTOBAL_SUCCESS);
  CHECK_CLOSE("x(3) = cos(2.7) to the tolerance", y[0], cos(2.7), 0.0, 1e-2);
  autobal_transient_free(tr);
}

int main(void) {
  test_bouncing_ball(0.8);
  test_bouncing_ball(1.0);
  test_stick_slip();
  test_chatter();
  test_reject();
  return check_summary();
}
