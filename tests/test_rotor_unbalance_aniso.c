/* test_rotor_unbalance_aniso.c: every unbalance with ANISOTROPIC supports (one plane, two balls; Hill's
 * method with a guaranteed exclusion, docs/rotor.md "Anisotropic supports: Hill's method"), against
 * analyses that do not use the Hill matrix:
 *  - the phase of the unbalance (plane1.psi0) does not change the Floquet multipliers (a time shift);
 *  - the rotating-frame Hill matrix is (nearly) singular at the Floquet exponents of the monodromy
 *    matrix (time integration of the mixed-frame linearization), and not a little away from them;
 *  - isotropic supports through the Hill route give the verdicts of the closed-polynomial route
 *    (autobal_rotor_stab_every_unbalance, isotropic) on ranges stable for all, unstable throughout and
 *    straddling a critical unbalance;
 *  - anisotropic supports (data/rotor_anisotropic.ini): at three speeds the verdict agrees with 200
 *    Floquet analyses across the range (stable for all exactly when all are stable), a reported unstable
 *    unbalance is unstable by an ordinary analysis, and a range whose ends and middle are stable but with
 *    an unstable window inside is reported not stable (found in the boxes left open);
 *  - m0 restored bitwise, the refusals (three balls anisotropic), the budget option's range. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/rotor_stab_handle.h"
#include "analysis/rotor_unbalance_aniso.h"
#include "autobal.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define R0 0.1 /* m, the default plane1.r0 */

static autobal_rotor_stab *make(int aniso, long hill_boxes) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_error err;
  autobal_rotor_stab *s;
  if (aniso) { /* data/rotor_anisotropic.ini */
    p.hw.c_Ly = 0.7e5;
    p.hw.c_Ry = 1.1e5;
    p.hw.h_Ly = 80;
    p.hw.h_Ry = 120;
  }
  o.hill_boxes = hill_boxes;
  s = autobal_rotor_stab_alloc(&p, &o, &err);
  if (s == NULL) printf("alloc: %s\n", err.message);
  return s;
}

/* Floquet margin at unbalance sv (kg m). */
static double floquet_margin(autobal_rotor_stab *s, double sv, int *verdict) {
  double mg = NAN;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv / R0);
  if (autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_FLOQUET, &mg, verdict) != AUTOBAL_SUCCESS) return NAN;
  return mg;
}

static void phase_invariance(autobal_rotor_stab *s) {
  const double phases[3] = {0.0, 1.3, -2.2};
  double mg[3];
  int v, k;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, 500.0);
  for (k = 0; k < 3; k++) {
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_PSI0), phases[k]);
    mg[k] = floquet_margin(s, 0.003, &v);
  }
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_PSI0), 0.0);
  printf("     Floquet margins at psi0 = 0, 1.3, -2.2: %.12g %.12g %.12g\n", mg[0], mg[1], mg[2]);
  /* the monodromy's tolerance (rtol 1e-10 by default): 1e-6 of the margin */
  CHECK("the unbalance's phase leaves the Floquet margin unchanged (a time shift)",
        fabs(mg[1] - mg[0]) <= 1e-6 * fabs(mg[0]) && fabs(mg[2] - mg[0]) <= 1e-6 * fabs(mg[0]));
}

/* At every Floquet exponent lambda = log(mu) / T (mod i w) the Hill matrix (N = 8) is nearly singular. */
static void hill_vs_floquet(autobal_rotor_stab *s, double w, double sv) {
  double mre[12], mim[12], psi[2];
  const double T = 2.0 * M_PI / w;
  size_t j, bad = 0;
  double worst = 0.0;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv / R0);
  CHECK_STATUS("floquet", autobal_rotor_stab_floquet(s, mre, mim, 12, NULL), AUTOBAL_SUCCESS);
  CHECK_STATUS("balanced angles", autobal_rotor_stab_balanced_angles(s, psi, 2), AUTOBAL_SUCCESS);
  for (j = 0; j < 12; j++) {
    const double complex lam = clog(mre[j] + I * mim[j]) / T;
    double sg = INFINITY, ref = INFINITY;
    int q;
    for (q = 0; q < 2; q++) { /* lambda or lambda + i w: the multipliers over T fix lambda mod i w */
      const double li = cimag(lam) + (double)q * w;
      const double a = autobal_rotor_hill_sigma_min_(s, 0.5 * (psi[0] - psi[1]), 8, creal(lam), li);
      /* a point 0.02 w away along the real axis: no exponent is that far from the axis nearby */
      const double b = autobal_rotor_hill_sigma_min_(s, 0.5 * (psi[0] - psi[1]), 8, creal(lam) + 0.02 * w, li);
      if (a < sg) sg = a, ref = b;
    }
    if (!(sg <= 1e-3 * ref)) bad++;
    if (sg / ref > worst) worst = sg / ref;
  }
  printf("     omega %g, m0 r0 %g: sigma_min(Hill) at the 12 Floquet exponents / away: worst %.3g\n", w, sv, worst);
  CHECK("the Hill matrix is singular at every Floquet exponent (ratio <= 1e-3)", bad == 0);
}

/* The isotropic handle: the Hill route against the closed-polynomial route. */
static void isotropic_route(autobal_rotor_stab *s, double w, double lo, double hi) {
  autobal_rotor_unbalance_range a, b;
  const double m0 = autobal_rotor_stab_params(s)->plane[0].m0;
  char what[160];
  int st;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  CHECK_STATUS("isotropic route", autobal_rotor_stab_every_unbalance(s, lo, hi, &a), AUTOBAL_SUCCESS);
  memset(&b, 0, sizeof b);
  b.s_lo = lo, b.s_hi = hi;
  st = autobal_rotor_every_unbalance_aniso_(s, lo, hi, &b);
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  snprintf(what, sizeof what, "omega %g, [%g, %g] g mm: the Hill route", w, lo * 1e6, hi * 1e6);
  CHECK_STATUS(what, st, AUTOBAL_SUCCESS);
  printf("     %s: closed %d (%zu critical), Hill %d verdict %d (%ld boxes, %zu open, N %zu)\n", what, a.all_stable,
         a.n_crit, b.all_stable, b.sub_verdict[0], b.hill_boxes, b.hill_open, b.hill_order);
  CHECK("the Hill route agrees with the closed polynomial (stable for all or not)", a.all_stable == b.all_stable);
  if (a.all_stable) CHECK("stable for all proven (no box left open)", b.hill_open == 0);
  else CHECK("not stable: shown by an unstable member", b.sub_verdict[0] == AUTOBAL_VERDICT_UNSTABLE && !isnan(b.s_unstable));
}

/* Anisotropic: the verdict against 200 Floquet analyses across the range. */
static void dense(autobal_rotor_stab *s, double w, double lo, double hi, int expect_all) {
  autobal_rotor_unbalance_range ur;
  const double m0 = autobal_rotor_stab_params(s)->plane[0].m0;
  size_t k, n_unst = 0;
  int all = 1, v, st;
  char what[160];
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  st = autobal_rotor_stab_every_unbalance(s, lo, hi, &ur);
  snprintf(what, sizeof what, "anisotropic, omega %g, [%g, %g] g mm", w, lo * 1e6, hi * 1e6);
  CHECK_STATUS(what, st, AUTOBAL_SUCCESS);
  if (st != AUTOBAL_SUCCESS) {
    printf("     %s\n", autobal_rotor_stab_errmsg(s));
    return;
  }
  CHECK("m0 restored bitwise", autobal_rotor_stab_params(s)->plane[0].m0 == m0);
  CHECK("the Hill route was taken", ur.hill == 1 && ur.n_sub == 1 && ur.n_crit == 0);
  for (k = 0; k < 200; k++) {
    const double sv = lo + (hi - lo) * (double)k / 199.0;
    floquet_margin(s, sv, &v);
    if (v != AUTOBAL_VERDICT_STABLE) all = 0, n_unst++;
  }
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  printf("     %s: all stable %d, verdict %d, %ld boxes, %zu open, N %zu, s_unstable %g; sampled: %zu of 200 not "
         "stable\n",
         what, ur.all_stable, ur.sub_verdict[0], ur.hill_boxes, ur.hill_open, ur.hill_order, ur.s_unstable, n_unst);
  CHECK("stable for all exactly when all 200 samples are stable", ur.all_stable == all);
  CHECK("the expected verdict", ur.all_stable == expect_all);
  if (!ur.all_stable) {
    CHECK("not stable: an unstable member is reported", ur.sub_verdict[0] == AUTOBAL_VERDICT_UNSTABLE &&
                                                             ur.s_unstable >= lo && ur.s_unstable <= hi);
    floquet_margin(s, ur.s_unstable, &v);
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
    CHECK("the reported member is unstable by an ordinary analysis", v == AUTOBAL_VERDICT_UNSTABLE);
  } else
    CHECK("stable for all: proven, no box open", ur.hill_open == 0);
}

/* A range whose ends and middle are stable with an unstable window inside (found by sampling). */
static void window_inside(autobal_rotor_stab *s) {
  /* the analysis evaluates the ends and the middle in theta, half the angle between the balls: two balls
   * of a = m r = 0.005 kg m, s = 2 a cos theta */
  const double w = 500.0, lo = 0.001, hi = 0.0086, a = 0.005;
  const double smid = 2.0 * a * cos(0.5 * (acos(lo / (2.0 * a)) + acos(hi / (2.0 * a))));
  autobal_rotor_unbalance_range ur;
  int v0, v1, vm, v, any = 0;
  size_t k;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  floquet_margin(s, lo, &v0);
  floquet_margin(s, hi, &v1);
  floquet_margin(s, smid, &vm);
  for (k = 0; k < 100; k++) {
    floquet_margin(s, lo + (hi - lo) * (double)k / 99.0, &v);
    if (v == AUTOBAL_VERDICT_UNSTABLE) any = 1;
  }
  CHECK("the constructed range: ends and middle stable, an unstable window inside (sampled)",
        v0 == AUTOBAL_VERDICT_STABLE && v1 == AUTOBAL_VERDICT_STABLE && vm == AUTOBAL_VERDICT_STABLE && any);
  CHECK_STATUS("every unbalance over the window", autobal_rotor_stab_every_unbalance(s, lo, hi, &ur), AUTOBAL_SUCCESS);
  printf("     window inside [1000, 8600] g mm at 500 rad/s (middle in theta %g g mm): verdict %d, %ld boxes, %zu open, s_unstable %g\n",
         smid * 1e6, ur.sub_verdict[0], ur.hill_boxes, ur.hill_open, ur.s_unstable);
  CHECK("reported not stable, by an unstable member found in the open boxes",
        !ur.all_stable && ur.hill_open > 0 && ur.sub_verdict[0] == AUTOBAL_VERDICT_UNSTABLE);
  floquet_margin(s, ur.s_unstable, &v);
  CHECK("that member is unstable by an ordinary analysis", v == AUTOBAL_VERDICT_UNSTABLE);
}

/* Low speeds, where no truncation of at most 40 harmonics is bounded: an answer, never "stable for all"
 * and never an error (a speed scan passes through them); a member reported unstable is unstable. */
static void low_speed(autobal_rotor_stab *s) {
  const double ws[3] = {5.0, 15.0, 30.0};
  size_t i;
  for (i = 0; i < 3; i++) {
    autobal_rotor_unbalance_range ur;
    char what[120];
    int st, v;
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, ws[i]);
    st = autobal_rotor_stab_every_unbalance(s, 0.0015, 0.003, &ur);
    snprintf(what, sizeof what, "omega %g rad/s: a verdict, not an error", ws[i]);
    CHECK_STATUS(what, st, AUTOBAL_SUCCESS);
    if (st != AUTOBAL_SUCCESS) continue;
    if (ur.hill_order == 0)
      CHECK("no bounded truncation: not stable for all, undecided or an unstable member",
            !ur.all_stable && (ur.sub_verdict[0] == AUTOBAL_ROTOR_VERDICT_NONE ||
                               (ur.sub_verdict[0] == AUTOBAL_VERDICT_UNSTABLE && !isnan(ur.s_unstable))));
    if (!isnan(ur.s_unstable)) {
      floquet_margin(s, ur.s_unstable, &v);
      CHECK("the unstable member is unstable by an ordinary analysis", v == AUTOBAL_VERDICT_UNSTABLE);
    }
  }
  {
    autobal_rotor_unbalance_range ur;
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, 5.0);
    autobal_rotor_stab_every_unbalance(s, 0.0015, 0.003, &ur);
    CHECK("at 5 rad/s the truncation is not bounded (the case above is met)", ur.hill_order == 0);
  }
}

static void refusals(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_error err;
  autobal_rotor_unbalance_range ur;
  autobal_rotor_stab *s;
  static double bm[3] = {0.05, 0.05, 0.05}, br[3] = {0.1, 0.1, 0.1}, bh[3] = {0.1, 0.1, 0.1}, bp[3] = {0, 2, 4},
                brt[3] = {0, 0, 0};
  p.hw.c_Ly = 0.7e5;
  p.plane[0].n_balls = 3;
  p.plane[0].ball_mass = bm, p.plane[0].ball_radius = br, p.plane[0].ball_damping = bh;
  p.plane[0].ball_psi = bp, p.plane[0].ball_rate = brt;
  s = autobal_rotor_stab_alloc(&p, NULL, &err);
  CHECK("three balls, anisotropic: a handle", s != NULL);
  if (s != NULL) {
    CHECK_STATUS("three balls, anisotropic: refused", autobal_rotor_stab_every_unbalance(s, 0.002, 0.003, &ur),
                 AUTOBAL_EUNSUPPORTED);
    CHECK("the message names what is supported", strstr(autobal_rotor_stab_errmsg(s), "two balls") != NULL);
    autobal_rotor_stab_free(s);
  }
  o.hill_boxes = 50;
  p = autobal_rotor_params_default();
  s = autobal_rotor_stab_alloc(&p, &o, &err);
  CHECK("hill_boxes = 50 refused", s == NULL && strstr(err.message, "hill_boxes") != NULL);
  autobal_rotor_stab_free(s);
}

int main(void) {
  autobal_rotor_stab *an = make(1, 0), *iso = make(0, 0), *small = make(1, 3000);
  if (an == NULL || iso == NULL || small == NULL) return 1;
  printf("phase invariance\n");
  phase_invariance(an);
  printf("Hill against Floquet\n");
  hill_vs_floquet(an, 500.0, 0.002);
  hill_vs_floquet(an, 500.0, 0.007);
  hill_vs_floquet(an, 1200.0, 0.004);
  hill_vs_floquet(iso, 500.0, 0.003);
  printf("isotropic supports through the Hill route\n");
  isotropic_route(iso, 500.0, 0.0015, 0.003);  /* stable for all */
  isotropic_route(iso, 500.0, 0.006, 0.008);   /* between the critical unbalances: unstable throughout */
  isotropic_route(iso, 500.0, 0.005, 0.0062);  /* straddles 5596.2 g mm */
  printf("anisotropic supports against dense Floquet sampling\n");
  dense(an, 500.0, 0.0015, 0.003, 1);
  dense(an, 1000.0, 0.0015, 0.003, 1);
  dense(an, 700.0, 0.005, 0.0065, 0);
  dense(an, 500.0, 0.0065, 0.008, 0);
  printf("an unstable window strictly inside\n");
  window_inside(small);
  printf("low speeds\n");
  low_speed(an);
  printf("refusals\n");
  refusals();
  autobal_rotor_stab_free(an);
  autobal_rotor_stab_free(iso);
  autobal_rotor_stab_free(small);
  return check_summary();
}
