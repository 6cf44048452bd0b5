/* test_attractor.c: the attractor classification (include/autobal/attractor.h) on constructed
 * windows whose class follows from their construction, one or more per class and at the
 * thresholds; its error paths; and the ensemble engine's final window (autobal_ensemble_member
 * .classify) on a model written here, psi' = rate (a "ball" turning at a known rate relative to a
 * rotor at 10 rad/s), whose window, class and circulation frequency are known in closed form.
 * The rotor's own cases (balanced, heavy side, circulating at 500 rad/s against the natural
 * frequencies from an independent linearization) are tests/app/attractors.sh. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

#define TWO_PI 6.283185307179586476925286766559
#define PI_ 3.1415926535897932384626433832795
#define NS 201 /* samples over [0, 1] s */
/* GCC 12.2 at -O2 and above dropped every call of balls_at and circulate below (functions that only
 * store into the caller's cwin, read later through the window's pointers by the library), as if
 * those stores were dead; without SLP vectorization it keeps them.  No interprocedural analysis of
 * the helpers that write the samples: */
#if defined(__GNUC__) && !defined(__clang__)
#define FILLER __attribute__((noipa))
#else
#define FILLER
#endif
#define NB 2

/* A constructed window: NS samples on [0, 1] s, two balls in one plane (m r = 0.005 kg m each),
 * unbalance 0.002 kg m at psi0 = 0.3 rad, balance_tol 0.01, speed 500 rad/s, no modes. */
typedef struct win {
  double t[NS], psi[NS * NB], res[NS], amp[NS];
  size_t plane[NB];
  double mom[NB], umom[2], uang[2];
  autobal_attractor_window w;
} cwin;

static void win_init(cwin *x) {
  size_t k;
  memset(x, 0, sizeof *x);
  for (k = 0; k < NS; k++) x->t[k] = (double)k / (NS - 1), x->res[k] = 4.0, x->amp[k] = 1e-3;
  x->mom[0] = x->mom[1] = 0.005;
  x->umom[0] = 0.002, x->uang[0] = 0.3;
  x->w.n = NS, x->w.t = x->t, x->w.n_balls = NB, x->w.psi = x->psi, x->w.residual = x->res, x->w.amplitude = x->amp;
  x->w.balance_tol = 0.01, x->w.speed = 500.0;
  x->w.n_planes = 1, x->w.plane_of_ball = x->plane, x->w.ball_moment = x->mom;
  x->w.unbalance_moment = x->umom, x->w.unbalance_angle = x->uang;
}

/* balls at fixed angles a, b (plus a libration of amplitude lib at 40 rad/s) */
FILLER static void balls_at(cwin *x, double a, double b, double lib) {
  size_t k;
  for (k = 0; k < NS; k++) {
    x->psi[k * NB] = a + lib * sin(40.0 * x->t[k]);
    x->psi[k * NB + 1] = b - lib * sin(40.0 * x->t[k]);
  }
}

static int classify(cwin *x, const autobal_attractor_options *o, autobal_attractor_result *r) {
  autobal_error err;
  x->w.t = x->t, x->w.psi = x->psi, x->w.residual = x->res;
  if (x->w.amplitude) x->w.amplitude = x->amp;
  x->w.plane_of_ball = x->plane, x->w.ball_moment = x->mom, x->w.unbalance_moment = x->umom, x->w.unbalance_angle = x->uang;
  autobal_error_clear(&err);
  return autobal_attractor_classify(o, &x->w, r, &err);
}

static void expect(const char *what, cwin *x, const autobal_attractor_options *o, int cls) {
  autobal_attractor_result r;
  int st;
  char msg[256];
  st = classify(x, o, &r);
  snprintf(msg, sizeof msg, "%s: %s (want %s; %zu at rest, %zu circulating)", what, autobal_attractor_class_name(r.cls),
           autobal_attractor_class_name(cls), r.n_at_rest, r.n_circulating);
  CHECK(msg, st == AUTOBAL_SUCCESS && r.cls == cls);
}

static void test_names(void) {
  int c;
  const char *legend = autobal_attractor_legend();
  printf("# names, symbols, legend\n");
  for (c = 0; c < AUTOBAL_ATTRACTOR_N_CLASSES; c++) {
    char item[64];
    snprintf(item, sizeof item, "%d %s", c, autobal_attractor_class_name(c));
    CHECK_MSG("legend lists the class with its value", legend, item);
    CHECK("one symbol each", autobal_attractor_class_symbol(c) && strlen(autobal_attractor_class_symbol(c)) == 1);
  }
  CHECK("no 8th class", !autobal_attractor_class_name(AUTOBAL_ATTRACTOR_N_CLASSES) && !autobal_attractor_class_name(-1) &&
                            !autobal_attractor_class_symbol(7));
}

static void test_balanced_and_fixed(const autobal_attractor_options *o) {
  cwin x;
  size_t k;
  autobal_attractor_result r;
  printf("# balanced, heavy side, fixed\n");
  win_init(&x);
  balls_at(&x, 2.0, -1.5, 0.0);
  x.w.stopped_balanced = 1;
  expect("stopped at balance (the dwell rule), whatever the window", &x, o, AUTOBAL_ATTRACTOR_BALANCED);
  x.w.stopped_balanced = 0;
  for (k = 0; k < NS; k++) x.res[k] = 0.01 * (1.0 - 0.5 * x.t[k]);
  expect("residual <= balance_tol at every sample (equal at the first)", &x, o, AUTOBAL_ATTRACTOR_BALANCED);
  x.res[NS / 2] = 0.0100001;
  expect("one sample above balance_tol: balls at rest, balls' moment away from the unbalance", &x, o, AUTOBAL_ATTRACTOR_FIXED);
  /* heavy side: both balls within 90 degrees of psi0 = 0.3 */
  win_init(&x);
  balls_at(&x, 0.3 + 0.2, 0.3 - 1.2, 0.0);
  expect("both balls on the unbalance's side", &x, o, AUTOBAL_ATTRACTOR_HEAVY_SIDE);
  CHECK("... both at rest, none circulating", classify(&x, o, &r) == 0 && r.n_at_rest == 2 && r.n_circulating == 0 &&
                                                  isnan(r.frequency) && isnan(r.natural_frequency) && r.mode == -1);
  /* the projection sum m r cos(psi - psi0): 0.005 (cos 1.5 + cos(-1.75)) > 0 vs < 0 */
  balls_at(&x, 0.3 + 1.5, 0.3 - 1.75, 0.0);
  CHECK("(cos 1.5 + cos 1.75 < 0)", cos(1.5) + cos(1.75) < 0);
  expect("balls 1.5 and -1.75 rad from the unbalance: moment on the far side", &x, o, AUTOBAL_ATTRACTOR_FIXED);
  balls_at(&x, 0.3 + 1.5, 0.3 - 1.6, 0.0);
  CHECK("(cos 1.5 + cos 1.6 > 0)", cos(1.5) + cos(1.6) > 0);
  expect("balls 1.5 and -1.6 rad from it: on its side", &x, o, AUTOBAL_ATTRACTOR_HEAVY_SIDE);
  /* at rest up to rest_tol: a libration of amplitude a has range 2a (samples hit sin = +-1 within 1e-3) */
  balls_at(&x, 0.4, 0.2, 0.024);
  expect("libration of range 0.048 rad <= rest_tol 0.05: at rest", &x, o, AUTOBAL_ATTRACTOR_HEAVY_SIDE);
  balls_at(&x, 0.4, 0.2, 0.026);
  expect("libration of range 0.052 rad > rest_tol, steady: periodic", &x, o, AUTOBAL_ATTRACTOR_PERIODIC);
  /* a second plane without unbalance: never "heavy side" */
  win_init(&x);
  balls_at(&x, 0.3, 0.3, 0.0);
  x.plane[1] = 1, x.w.n_planes = 2, x.umom[1] = 0.0, x.uang[1] = 0.0;
  expect("plane 2 has balls but no unbalance", &x, o, AUTOBAL_ATTRACTOR_FIXED);
  x.umom[1] = 0.001, x.uang[1] = 0.3 + PI_;
  expect("plane 2's ball opposite its unbalance", &x, o, AUTOBAL_ATTRACTOR_FIXED);
  x.uang[1] = 0.2;
  expect("both planes' balls on their unbalance's side", &x, o, AUTOBAL_ATTRACTOR_HEAVY_SIDE);
}

/* ball 1 turns at rate r (rad/s) relative to the rotor with a ripple of the circulation's own
 * frequency, ball 2 rests: the mean rate over [0, 1] is r + q sin(|r|)/1 exactly */
FILLER static void circulate(cwin *x, double r, double q) {
  size_t k;
  for (k = 0; k < NS; k++) {
    x->psi[k * NB] = 1.0 + r * x->t[k] + q * sin(fabs(r) * x->t[k]);
    x->psi[k * NB + 1] = -2.0 + 0.01 * sin(30.0 * x->t[k]);
  }
}

static void test_circulating(const autobal_attractor_options *o) {
  cwin x;
  autobal_attractor_result r;
  /* natural frequencies at 500 rad/s of the default rotor as autobal_rotor_campbell gives them
   * (only their order and whirl matter here: which one is nearest is decided by construction) */
  double f[4] = {155.87, 157.28, 173.32, 265.66};
  int wh[4] = {-1, 1, -1, 1};
  double want;
  printf("# circulating\n");
  win_init(&x);
  x.w.n_modes = 4, x.w.mode_frequency = f, x.w.mode_whirl = wh;
  circulate(&x, -262.8, 0.2);
  CHECK_STATUS("classify", classify(&x, o, &r), AUTOBAL_SUCCESS);
  CHECK("a ball lagging 262.8 rad/s behind the rotor: circulating", r.cls == AUTOBAL_ATTRACTOR_CIRCULATING);
  want = 500.0 + (x.psi[(NS - 1) * NB] - x.psi[0]) / 1.0;
  CHECK_CLOSE("nu = Omega + (psi(1) - psi(0)) / 1 s", r.frequency, 500.0 - 262.8 + 0.2 * sin(262.8), 1e-13, 0);
  CHECK_CLOSE("... = the samples' mean rate", r.frequency, want, 1e-13, 0);
  CHECK("nearest forward mode: 265.66 (index 3), not the backward 173.32", r.mode == 3 && r.natural_frequency == 265.66);
  CHECK("1 circulating, 1 at rest", r.n_circulating == 1 && r.n_at_rest == 1);
  /* a backward mode nearer than any forward one is not the one a forward circulation excites */
  f[2] = 240.0;
  CHECK("backward 240 nearer: still the forward 265.66", classify(&x, o, &r) == 0 && r.mode == 3);
  wh[2] = 0;
  CHECK("an undecided whirl at 240 counts for either sense", classify(&x, o, &r) == 0 && r.mode == 2 && r.natural_frequency == 240.0);
  wh[2] = -1;
  /* a ball faster than the rotor the other way round: nu = 500 - 700 = -200, backward whirl */
  circulate(&x, -700.0, 0.0);
  CHECK("nu = -200: backward whirl, nearest backward mode 173.32 (index 0..2: 2? no, 240 is nearer)",
        classify(&x, o, &r) == 0 && r.cls == AUTOBAL_ATTRACTOR_CIRCULATING && r.mode == 2 && fabs(r.frequency + 200.0) < 1e-9);
  /* the spin the other way: everything mirrored */
  x.w.speed = -500.0;
  circulate(&x, 262.8, 0.0);
  CHECK("Omega = -500, rate +262.8: nu = -237.2, forward, 265.66",
        classify(&x, o, &r) == 0 && r.cls == AUTOBAL_ATTRACTOR_CIRCULATING && r.mode == 3 && fabs(r.frequency + 237.2) < 1e-9);
  x.w.speed = 500.0;
  /* min_turns: 2 relative turns over the window; a slow drift of 1.9 turns with the rest at rest */
  circulate(&x, -1.9 * TWO_PI, 0.0);
  expect("1.9 relative turns < min_turns 2, steady: periodic", &x, o, AUTOBAL_ATTRACTOR_PERIODIC);
  circulate(&x, -2.1 * TWO_PI, 0.0);
  expect("2.1 turns: circulating", &x, o, AUTOBAL_ATTRACTOR_CIRCULATING);
  x.w.n_modes = 0;
  CHECK("no modes given: frequency, no natural frequency",
        classify(&x, o, &r) == 0 && r.cls == AUTOBAL_ATTRACTOR_CIRCULATING && isnan(r.natural_frequency) && r.mode == -1 &&
            fabs(r.frequency - (500.0 - 2.1 * TWO_PI)) < 1e-9);
}

static void test_periodic_irregular(const autobal_attractor_options *o) {
  cwin x;
  size_t k;
  printf("# periodic, irregular\n");
  win_init(&x);
  /* a steady libration of both balls with the residual oscillating at twice its frequency */
  balls_at(&x, 2.0, -2.0, 0.5);
  for (k = 0; k < NS; k++) x.res[k] = 1.0 + 0.5 * sin(80.0 * x.t[k]), x.amp[k] = 1e-3 * (1.0 + 0.3 * cos(80.0 * x.t[k]));
  expect("libration of 0.5 rad, stationary envelope", &x, o, AUTOBAL_ATTRACTOR_PERIODIC);
  /* the same with a growing residual oscillation: halves differ */
  for (k = 0; k < NS; k++) x.res[k] = 1.0 + 0.5 * x.t[k] * sin(80.0 * x.t[k]);
  expect("libration with a growing residual oscillation", &x, o, AUTOBAL_ATTRACTOR_IRREGULAR);
  for (k = 0; k < NS; k++) x.res[k] = 1.0 + 0.5 * sin(80.0 * x.t[k]), x.amp[k] = 1e-3 * (1.0 + x.t[k] * cos(80.0 * x.t[k]));
  expect("... a growing amplitude oscillation", &x, o, AUTOBAL_ATTRACTOR_IRREGULAR);
  x.w.amplitude = NULL;
  expect("... not looked at without amplitudes", &x, o, AUTOBAL_ATTRACTOR_PERIODIC);
  x.w.amplitude = x.amp;
  for (k = 0; k < NS; k++) x.amp[k] = 1e-3;
  /* two balls circulating at different steady rates: quasi-periodic */
  for (k = 0; k < NS; k++) x.psi[k * NB] = -263.0 * x.t[k], x.psi[k * NB + 1] = -150.0 * x.t[k];
  for (k = 0; k < NS; k++) x.res[k] = 2.0;
  expect("two balls circulating at -263 and -150 rad/s", &x, o, AUTOBAL_ATTRACTOR_PERIODIC);
  /* a rate that swings by +-60 rad/s with a period of half the window: the two halves' mean rates
   * agree (-263 both), the quarters' do not (-263 +- 38.2): not a steady circulation (the case of a
   * member of the default rotor's 32 x 32 map whose wandering balls passed a halves-only test) */
  for (k = 0; k < NS; k++)
    x.psi[k * NB] = -263.0 * x.t[k] - 60.0 / (4 * PI_) * (cos(4 * PI_ * x.t[k]) - 1.0), x.psi[k * NB + 1] = 0.1;
  expect("rate -263 +- 60 sin(4 pi t): halves equal, quarters 14.5 % apart", &x, o, AUTOBAL_ATTRACTOR_PERIODIC);
  for (k = 0; k < NS; k++)
    x.psi[k * NB] = -263.0 * x.t[k] - 3.0 / (4 * PI_) * (cos(4 * PI_ * x.t[k]) - 1.0);
  expect("... +- 3 sin(4 pi t): quarters 0.73 % apart, steady", &x, o, AUTOBAL_ATTRACTOR_CIRCULATING);
  /* a circulation slowing down: psi = -263 t + 31.5 t^2, halves' rates -247.25 and -215.75 */
  for (k = 0; k < NS; k++) x.psi[k * NB] = -263.0 * x.t[k] + 31.5 * x.t[k] * x.t[k], x.psi[k * NB + 1] = 0.1;
  expect("a ball slowing from 263 to 200 rad/s", &x, o, AUTOBAL_ATTRACTOR_IRREGULAR);
  for (k = 0; k < NS; k++) x.psi[k * NB] = -263.0 * x.t[k] + 2.0 * x.t[k] * x.t[k];
  expect("... from 263 to 259 rad/s (quarters within 0.6 % of the mean rate, rate_tol 2 %)", &x, o, AUTOBAL_ATTRACTOR_CIRCULATING);
  for (k = 0; k < NS; k++) x.psi[k * NB] = -263.0 * x.t[k] + 5.0 * x.t[k] * x.t[k];
  expect("... from 263 to 253 rad/s (first quarter -261.75 vs mean -258, 1.45 %; last -254.25, 1.45 %)", &x, o,
         AUTOBAL_ATTRACTOR_CIRCULATING);
  for (k = 0; k < NS; k++) x.psi[k * NB] = -263.0 * x.t[k] + 7.0 * x.t[k] * x.t[k];
  expect("... from 263 to 249 rad/s (first quarter 2.05 % from the mean -256; halves 7 rad/s apart > 2 pi / window)", &x, o,
         AUTOBAL_ATTRACTOR_IRREGULAR);
  /* non-finite samples, too few samples */
  x.res[7] = NAN;
  expect("a NaN residual", &x, o, AUTOBAL_ATTRACTOR_IRREGULAR);
  x.res[7] = 2.0;
  x.psi[9 * NB + 1] = INFINITY;
  expect("an infinite angle", &x, o, AUTOBAL_ATTRACTOR_IRREGULAR);
  x.psi[9 * NB + 1] = 0.1;
  x.w.n = 1;
  expect("one sample, not balanced", &x, o, AUTOBAL_ATTRACTOR_IRREGULAR);
  x.res[0] = 0.001;
  expect("one sample, balanced", &x, o, AUTOBAL_ATTRACTOR_BALANCED);
  x.w.n = 2, x.res[1] = 2.0;
  balls_at(&x, 2.0, -1.5, 0.0);
  expect("two samples, balls at rest away from the unbalance", &x, o, AUTOBAL_ATTRACTOR_FIXED);
  x.psi[3] = -1.5 - 2.1 * TWO_PI;
  expect("two samples, ball 2 turned 2.1 times: one rate for both halves, steady", &x, o, AUTOBAL_ATTRACTOR_CIRCULATING);
}

static void test_errors(void) {
  autobal_attractor_options o = autobal_attractor_options_default(), b;
  autobal_attractor_result r;
  autobal_error err;
  cwin x;
  size_t k;
  printf("# errors\n");
  CHECK_CLOSE("default window_revs", o.window_revs, 100, 0, 0);
  CHECK_CLOSE("default rest_tol", o.rest_tol, 0.05, 0, 0);
  CHECK_CLOSE("default min_turns", o.min_turns, 2, 0, 0);
  CHECK_CLOSE("default rate_tol", o.rate_tol, 0.02, 0, 0);
  CHECK_CLOSE("default envelope_tol", o.envelope_tol, 0.05, 0, 0);
  CHECK_STATUS("defaults valid", autobal_attractor_options_check(&o, NULL), AUTOBAL_SUCCESS);
#define BAD(field, value, name)                                                                \
  do {                                                                                         \
    b = o, b.field = (value);                                                                  \
    autobal_error_clear(&err);                                                                 \
    CHECK_STATUS(name " = " #value, autobal_attractor_options_check(&b, &err), AUTOBAL_EINVAL); \
    CHECK_MSG(name " named", err.message, name);                                               \
  } while (0)
  BAD(window_revs, 0.0, "attractor_window_revs");
  BAD(window_revs, NAN, "attractor_window_revs");
  BAD(window_revs, 2e6, "attractor_window_revs");
  BAD(rest_tol, 0.0, "attractor_rest_tol");
  BAD(rest_tol, 4.0, "attractor_rest_tol");
  BAD(min_turns, 0.5, "attractor_min_turns");
  BAD(min_turns, INFINITY, "attractor_min_turns");
  BAD(rate_tol, 1.0, "attractor_rate_tol");
  BAD(rate_tol, -0.1, "attractor_rate_tol");
  BAD(envelope_tol, 0.0, "attractor_envelope_tol");
  BAD(envelope_tol, NAN, "attractor_envelope_tol");
  b = o, b.rest_tol = 0.0, autobal_error_clear(&err);
  CHECK_MSG("the range is stated", err.message[0] ? err.message : (autobal_attractor_options_check(&b, &err), err.message), "(0, 3.14159");
  CHECK_STATUS("NULL options", autobal_attractor_options_check(NULL, NULL), AUTOBAL_EINVAL);
  win_init(&x);
  balls_at(&x, 0.3, 0.3, 0.0);
  CHECK_STATUS("NULL window", autobal_attractor_classify(&o, NULL, &r, NULL), AUTOBAL_EINVAL);
  CHECK("... result says unclassified", r.cls == AUTOBAL_ATTRACTOR_UNCLASSIFIED && isnan(r.frequency));
  CHECK_STATUS("NULL result", autobal_attractor_classify(&o, &x.w, NULL, NULL), AUTOBAL_EINVAL);
  b = o, b.rate_tol = 2.0;
  CHECK_STATUS("bad options", autobal_attractor_classify(&b, &x.w, &r, NULL), AUTOBAL_EINVAL);
  x.t[5] = x.t[4];
  autobal_error_clear(&err);
  CHECK_STATUS("times not increasing", autobal_attractor_classify(&o, &x.w, &r, &err), AUTOBAL_EINVAL);
  CHECK_MSG("... the sample named", err.message, "sample 5");
  x.t[5] = 5.0 / (NS - 1);
  x.plane[1] = 1;
  CHECK_STATUS("ball in plane 1 of 1", autobal_attractor_classify(&o, &x.w, &r, NULL), AUTOBAL_EINVAL);
  x.plane[1] = 0;
  x.w.n_balls = 65;
  CHECK_STATUS("65 balls", autobal_attractor_classify(&o, &x.w, &r, NULL), AUTOBAL_EINVAL);
  x.w.n_balls = NB, x.w.psi = NULL;
  CHECK_STATUS("no angles", autobal_attractor_classify(&o, &x.w, &r, NULL), AUTOBAL_EINVAL);
  x.w.psi = x.psi, x.w.n_modes = 2;
  CHECK_STATUS("modes without frequencies", autobal_attractor_classify(&o, &x.w, &r, NULL), AUTOBAL_EINVAL);
  x.w.n_modes = 0;
  for (k = 0; k < NS; k++) x.res[k] = 1.0;
  CHECK_STATUS("and valid again", autobal_attractor_classify(&o, &x.w, &r, NULL), AUTOBAL_SUCCESS);
}

/* ---- the engine's window: psi' = rate on a "rotor" at 10 rad/s --------------------------------------
 * Member (rate, psi_init): y(t) = psi_init + rate t.  The residual (monitor) is 1 + |y| / 100, never
 * below balance_tol, except for rate = 0 where it is 0 (balanced at once, the run stops after the
 * dwell).  Its classify checks the window the engine hands over against the closed form (the output
 * times k dt_out in [t_end - window, t_end], window = window_revs 2 pi / 10 s; y = psi_init + rate t
 * at each) and fails the member (UNCLASSIFIED) when it differs; then autobal_attractor_classify with
 * one plane (unbalance at angle 0) and one forward mode at 7 rad/s. */
typedef struct spin_expect {
  size_t n;               /* samples of the window */
  double t_first, t_last; /* its first and last time */
} spin_expect;

typedef struct spin_worker {
  const spin_expect *E;
  double rate, y0;
} spin_worker;

static int spin_describe(const void *model, const char *name, autobal_ensemble_param_info *info, autobal_error *err) {
  (void)model;
  if (strcmp(name, "rate") && strcmp(name, "psi_init")) {
    if (err) err->status = AUTOBAL_EINVAL, snprintf(err->message, sizeof err->message, "'%s' is not rate or psi_init", name);
    return AUTOBAL_EINVAL;
  }
  info->units = name[0] == 'r' ? "rad/s" : "rad", info->long_name = name, info->periodic = 0;
  return AUTOBAL_SUCCESS;
}
static void *spin_alloc(const void *model, const char *const *names, size_t n, autobal_error *err) {
  spin_worker *w = calloc(1, sizeof(spin_worker));
  (void)names, (void)n, (void)err;
  if (w) w->E = model;
  return w;
}
static void spin_free(void *w) { free(w); }
static int spin_rhs(double t, const double y[], double dydt[], void *params) {
  const spin_worker *w = params;
  (void)t, (void)y;
  dydt[0] = w->rate;
  return 0;
}
static double spin_monitor(double t, const double y[], void *user) {
  const spin_worker *w = user;
  (void)t;
  return w->rate == 0 ? 0.0 : 1.0 + fabs(y[0]) / 100.0;
}
static int spin_setup(void *wp, const double *values, double y0[], autobal_ensemble_setup *su, autobal_error *err) {
  spin_worker *w = wp;
  (void)err;
  w->rate = values[0], w->y0 = values[1];
  y0[0] = w->y0;
  su->sys.rhs = spin_rhs, su->sys.jac = NULL, su->sys.dim = 1, su->sys.params = w;
  su->speed = 10.0;
  su->monitor = spin_monitor, su->monitor_user = w;
  su->residual_initial = spin_monitor(0, y0, w);
  su->settle_time = 0;
  return AUTOBAL_SUCCESS;
}
static int spin_observe(void *wp, double t, const double y[], double *amplitude, double *row) {
  (void)wp, (void)t;
  *amplitude = 1e-3;
  if (row) row[0] = y[0];
  return 0;
}
static void spin_finish(void *wp, double t, const double y[], double *residual, double *amplitude, double *angles) {
  spin_worker *w = wp;
  (void)angles;
  *residual = spin_monitor(t, y, w), *amplitude = 1e-3;
}
static int spin_column(const void *model, size_t k, char *name, size_t size, const char **units) {
  (void)model, (void)k;
  snprintf(name, size, "psi");
  *units = "rad";
  return AUTOBAL_SUCCESS;
}
static int spin_classify(void *wp, const autobal_attractor_options *opt, double balance_tol, int stopped_balanced, size_t n,
                         const double *t, const double *y, autobal_attractor_result *res, autobal_error *err) {
  spin_worker *w = wp;
  autobal_attractor_window win;
  double res_k[1000], amp[1000], mom = 0.01, umom = 0.005, uang = 0.0, f = 7.0;
  size_t k, plane = 0;
  int whirl = 1;
  if (n > 1000) return AUTOBAL_EINVAL;
  if (!stopped_balanced) { /* the window against the closed form */
    if (n != w->E->n || fabs(t[0] - w->E->t_first) > 1e-9 || fabs(t[n - 1] - w->E->t_last) > 1e-9) {
      printf("  window: %zu samples %g..%g, want %zu samples %g..%g\n", n, n ? t[0] : NAN, n ? t[n - 1] : NAN, w->E->n,
             w->E->t_first, w->E->t_last);
      return AUTOBAL_EINVAL;
    }
    for (k = 0; k < n; k++)
      if (fabs(y[k] - (w->y0 + w->rate * t[k])) > 1e-9 * (1 + fabs(y[k]))) return AUTOBAL_EINVAL;
  }
  for (k = 0; k < n; k++) res_k[k] = spin_monitor(t[k], y + k, w), amp[k] = 1e-3;
  memset(&win, 0, sizeof win);
  win.n = n, win.t = t, win.n_balls = 1, win.psi = y, win.residual = res_k, win.amplitude = amp;
  win.balance_tol = balance_tol, win.stopped_balanced = stopped_balanced, win.speed = 10.0;
  win.n_planes = 1, win.plane_of_ball = &plane, win.ball_moment = &mom, win.unbalance_moment = &umom, win.unbalance_angle = &uang;
  win.n_modes = 1, win.mode_frequency = &f, win.mode_whirl = &whirl;
  return autobal_attractor_classify(opt, &win, res, err);
}

static void test_engine(void) {
  autobal_ensemble_member mb;
  autobal_ensemble_settings s = autobal_ensemble_settings_default();
  autobal_ensemble_attractors at;
  autobal_ensemble *e;
  autobal_error err;
  size_t aix, m;
  /* rate in {-3, 0, 0.0005} x psi_init in {0.2, 3.0}, t_end 100 s, dt_out 0.5 s, window 100 revs of
   * 10 rad/s = 62.83 s: the samples 37.5, 38.0, ..., 100 (126).  rate -3: 3 x 62.8 / 2 pi = 30 turns,
   * steady: circulating at nu = 10 - 3 = 7; rate 0: balanced at once; rate 0.0005: range 0.031 rad
   * (at rest), the ball at 0.2 rad from the unbalance (heavy side) or at 3.0 rad (fixed). */
  const double rates[3] = {-3.0, 0.0, 0.0005}, psis[2] = {0.2, 3.0};
  const int want[3][2] = {{AUTOBAL_ATTRACTOR_CIRCULATING, AUTOBAL_ATTRACTOR_CIRCULATING},
                          {AUTOBAL_ATTRACTOR_BALANCED, AUTOBAL_ATTRACTOR_BALANCED},
                          {AUTOBAL_ATTRACTOR_HEAVY_SIDE, AUTOBAL_ATTRACTOR_FIXED}};
  const double window = 100.0 * TWO_PI / 10.0;
  spin_expect E;
  E.t_last = 100.0, E.t_first = ceil((100.0 - window) / 0.5) * 0.5, E.n = (size_t)((E.t_last - E.t_first) / 0.5) + 1;
  printf("# the engine's final window: psi' = rate on a rotor at 10 rad/s\n");
  CHECK("(window: 126 samples from 37.5 s)", E.n == 126 && E.t_first == 37.5);
  memset(&mb, 0, sizeof mb);
  mb.model_name = "spin";
  mb.model = &E;
  mb.dim = 1, mb.n_angles = 0, mb.n_columns = 1;
  mb.time_units = "s", mb.time_name = "time", mb.time_long_name = "time", mb.length_units = "1";
  mb.describe = spin_describe, mb.worker_alloc = spin_alloc, mb.worker_free = spin_free, mb.setup = spin_setup;
  mb.observe = spin_observe, mb.finish = spin_finish, mb.column_name = spin_column, mb.classify = spin_classify;
  s.n_params = 2;
  s.param[0].name = "rate", s.param[0].min = 0, s.param[0].max = 0, s.param[0].n = 1;
  s.param[1].name = "psi_init", s.param[1].min = 0.2, s.param[1].max = 3.0, s.param[1].n = 2;
  s.endpoint = 1;
  s.t_end = 100, s.use_revs_out = 0, s.dt_out = 0.5, s.balance_tol = 0.01, s.balance_revs = 1;
  s.transient.rtol = 1e-12, s.transient.atol = 1e-12;
  s.threads = 1;
  /* bad thresholds are refused by alloc, the option named */
  s.attractor.rest_tol = -1;
  autobal_error_clear(&err);
  e = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK("alloc refuses rest_tol = -1", e == NULL && err.status == AUTOBAL_EINVAL);
  CHECK_MSG("... naming it", err.message, "attractor_rest_tol");
  autobal_ensemble_free(e);
  s.attractor = autobal_attractor_options_default();
  for (m = 0; m < 3; m++) {
    size_t j;
    s.param[0].min = s.param[0].max = rates[m];
    e = autobal_ensemble_alloc(&mb, &s, &err);
    CHECK("alloc", e != NULL);
    if (!e) {
      printf("  %s\n", err.message);
      return;
    }
    aix = autobal_ensemble_attractor_index(e);
    CHECK("attractor block after the summary", aix == AUTOBAL_ENSEMBLE_ANGLES && autobal_ensemble_summary_length(e) == aix + 3);
    CHECK_STATUS("run", autobal_ensemble_run(e), AUTOBAL_SUCCESS);
    CHECK_STATUS("counts", autobal_ensemble_get_attractors(e, &at), AUTOBAL_SUCCESS);
    for (j = 0; j < 2; j++) {
      const double *r = autobal_ensemble_summary(e, j);
      char what[160];
      snprintf(what, sizeof what, "rate %g, psi_init %g: %s (want %s)", rates[m], psis[j],
               r ? autobal_attractor_class_name((int)r[aix]) : "not done", autobal_attractor_class_name(want[m][j]));
      CHECK(what, r && (int)r[aix] == want[m][j]);
      if (r && want[m][j] == AUTOBAL_ATTRACTOR_CIRCULATING) {
        CHECK_CLOSE("  nu = speed + rate = 7 rad/s", r[aix + 1], 10.0 + rates[m], 1e-9, 0);
        CHECK_CLOSE("  natural frequency: the forward mode at 7", r[aix + 2], 7.0, 0, 0);
      } else if (r) {
        CHECK("  no frequency", isnan(r[aix + 1]) && isnan(r[aix + 2]));
      }
    }
    CHECK("  counts: the two members' classes", want[m][0] == want[m][1] ? at.count[want[m][0]] == 2
                                                                          : at.count[want[m][0]] == 1 && at.count[want[m][1]] == 1);
    if (want[m][0] == AUTOBAL_ATTRACTOR_CIRCULATING)
      CHECK("  circulation range 7..7, ratio 1", fabs(at.frequency_min - 7.0) < 1e-9 && fabs(at.frequency_max - 7.0) < 1e-9 &&
                                                     fabs(at.ratio_min - 1.0) < 1e-9 && fabs(at.ratio_max - 1.0) < 1e-9);
    else
      CHECK("  no circulation range", isnan(at.frequency_min) && isnan(at.ratio_max));
    autobal_ensemble_free(e);
  }
  /* a member without classify: no attractor block */
  mb.classify = NULL;
  e = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK("no classify: no block, no counts", e && autobal_ensemble_attractor_index(e) == (size_t)-1 &&
                                               autobal_ensemble_summary_length(e) == AUTOBAL_ENSEMBLE_ANGLES &&
                                               autobal_ensemble_get_attractors(e, &at) == AUTOBAL_EINVAL);
  autobal_ensemble_free(e);
}

int main(void) {
  autobal_attractor_options o = autobal_attractor_options_default();
  test_names();
  test_balanced_and_fixed(&o);
  test_circulating(&o);
  test_periodic_irregular(&o);
  test_errors();
  test_engine();
  return check_summary();
}
