/* test_rotor_unbalance_aniso_margin.c: every unbalance with a margin delta on ANISOTROPIC supports (one plane,
 * two balls; autobal_rotor_stab_every_unbalance_margin: Hill's method on the line Re lambda = -delta,
 * docs/rotor.md "Anisotropic supports: Hill's method", "Margin"), against analyses that do not use the
 * Hill matrix:
 *  - data/rotor_anisotropic.ini at four (speed, range) cases: the decay rate rho_s sampled by 120 Floquet
 *    analyses across the range (rho_s = -max log|mu| / T); delta = 0.5 rho_s must be proven (and every
 *    sample has |mu| < exp(-delta T)), delta = 1.15 rho_s must be refused by a member whose Floquet margin
 *    is >= -delta (an ordinary analysis of that member checks it).  The cases are stable at delta = 0, so
 *    the margin decides the second verdict;
 *  - isotropic supports through the Hill route with delta against the closed (Routh-Hurwitz) set of
 *    autobal_rotor_stab_margin_ratio_set with the same delta (identical balls): the same verdict at 0.6 and
 *    1.1 times the closed decay rate of the range (bisection on the closed verdict);
 *  - delta = 0 gives the verdict of autobal_rotor_stab_every_unbalance; m0 restored; bad input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define R0 0.1 /* m, the default plane1.r0 */
#define NS 120 /* Floquet samples per range */

static autobal_rotor_stab *make(int aniso) {
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
  o.hill_boxes = 100000;
  s = autobal_rotor_stab_alloc(&p, &o, &err);
  if (s == NULL) printf("alloc: %s\n", err.message);
  return s;
}

/* Floquet margin log(max |mu|) / T at unbalance sv (kg m). */
static double floquet_margin(autobal_rotor_stab *s, double sv) {
  double mg = NAN;
  int v;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv / R0);
  if (autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_FLOQUET, &mg, &v) != AUTOBAL_SUCCESS) return NAN;
  return mg;
}

/* The largest Floquet margin over NS unbalances spread evenly over [lo, hi]. */
static double sampled_worst(autobal_rotor_stab *s, double lo, double hi) {
  double worst = -INFINITY;
  size_t k;
  for (k = 0; k < NS; k++) {
    const double mg = floquet_margin(s, lo + (hi - lo) * (double)k / (double)(NS - 1));
    if (!(mg <= worst)) worst = mg; /* NaN propagates as "worst" */
  }
  return worst;
}

static void aniso_case(autobal_rotor_stab *s, double w, double lo, double hi) {
  const double m0 = autobal_rotor_stab_params(s)->plane[0].m0;
  autobal_rotor_unbalance_range ur;
  double worst, rho, d_in, d_out;
  int v0, v1, v2, st;
  char what[160];
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  worst = sampled_worst(s, lo, hi);
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  rho = -worst;
  snprintf(what, sizeof what, "omega %g, [%g, %g] g mm", w, lo * 1e6, hi * 1e6);
  printf("     %s: sampled decay rate rho_s = %.6g 1/s\n", what, rho);
  CHECK("the case is stable at every sample (rho_s > 0)", rho > 0.0);
  d_in = 0.5 * rho, d_out = 1.15 * rho;
  st = autobal_rotor_stab_every_unbalance_margin(s, lo, hi, 0.0, &v0, &ur);
  CHECK_STATUS("delta = 0", st, AUTOBAL_SUCCESS);
  CHECK("delta = 0: proven stable (the margin decides the verdicts below)", v0 == 1 && ur.all_stable == 1);
  CHECK("m0 restored bitwise", autobal_rotor_stab_params(s)->plane[0].m0 == m0);
  st = autobal_rotor_stab_every_unbalance_margin(s, lo, hi, d_in, &v1, &ur);
  CHECK_STATUS("delta = 0.5 rho_s", st, AUTOBAL_SUCCESS);
  printf("     delta = %.5g: verdict %d (%ld boxes, %zu open, N %zu)\n", d_in, v1, ur.hill_boxes, ur.hill_open,
         ur.hill_order);
  CHECK("delta = 0.5 rho_s: proven (every sample has |mu| < exp(-delta T) too: rho_s > delta)",
        v1 == 1 && ur.all_stable == 1 && ur.hill_open == 0);
  st = autobal_rotor_stab_every_unbalance_margin(s, lo, hi, d_out, &v2, &ur);
  CHECK_STATUS("delta = 1.15 rho_s", st, AUTOBAL_SUCCESS);
  printf("     delta = %.5g: verdict %d (%ld boxes, %zu open), member %.6g g mm\n", d_out, v2, ur.hill_boxes,
         ur.hill_open, ur.s_unstable * 1e6);
  CHECK("delta = 1.15 rho_s: refused by a member of the range", v2 == 0 && ur.all_stable == 0 &&
                                                                   ur.s_unstable >= lo && ur.s_unstable <= hi);
  if (v2 == 0) {
    const double mg = floquet_margin(s, ur.s_unstable);
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
    printf("     that member's Floquet margin %.6g 1/s (-delta = %.6g)\n", mg, -d_out);
    CHECK("that member decays slower than delta by an ordinary Floquet analysis", mg >= -d_out);
  }
}

/* Isotropic supports, two identical balls: is [lo, hi] inside one interval of the closed set with delta? */
static int closed_verdict(autobal_rotor_stab *s, double lo, double hi, double delta) {
  const autobal_rotor_plane *pl = &autobal_rotor_stab_params(s)->plane[0];
  const double a = pl->ball_mass[0] * pl->ball_radius[0];
  autobal_rotor_ratio_set rs;
  size_t i;
  if (autobal_rotor_stab_margin_ratio_set(s, delta, &rs) != AUTOBAL_SUCCESS) return -1;
  for (i = 0; i < rs.n; i++)
    if (rs.lo[i] < lo / a && hi / a < rs.hi[i]) return 1;
  return 0;
}

/* The Hill route with delta against the closed set (Routh-Hurwitz on the shifted polynomial, exact in the
 * unbalance): the closed decay rate rho_c of the range by bisection over the closed verdict, then the Hill
 * verdict at 0.6 rho_c (the closed set says yes) and at 1.1 rho_c (no). */
static void iso_case(autobal_rotor_stab *s, double w, double lo, double hi) {
  autobal_rotor_unbalance_range ur;
  double a = 0.0, b = 100.0, d[2];
  int v, k, st;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  CHECK("the closed set: stable at delta = 0, not at 100 1/s",
        closed_verdict(s, lo, hi, a) == 1 && closed_verdict(s, lo, hi, b) == 0);
  for (k = 0; k < 40; k++) {
    const double c = 0.5 * (a + b);
    if (closed_verdict(s, lo, hi, c) == 1) a = c;
    else b = c;
  }
  d[0] = 0.6 * a, d[1] = 1.1 * a;
  for (k = 0; k < 2; k++) {
    const int closed = closed_verdict(s, lo, hi, d[k]);
    st = autobal_rotor_stab_every_unbalance_margin(s, lo, hi, d[k], &v, &ur);
    CHECK_STATUS("isotropic, the Hill route with delta", st, AUTOBAL_SUCCESS);
    printf("     omega %g, [%g, %g] g mm, rho_c %.6g, delta %.6g: closed %d, Hill %d (%ld boxes, %zu open)\n", w,
           lo * 1e6, hi * 1e6, a, d[k], closed, v, ur.hill_boxes, ur.hill_open);
    CHECK("the closed verdict: yes at 0.6 rho_c, no at 1.1 rho_c", closed == (k == 0));
    CHECK("the Hill route with delta gives the closed verdict with delta", v == closed);
  }
}

static void bad_input(autobal_rotor_stab *s) {
  autobal_rotor_unbalance_range ur;
  int v;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, 500.0);
  CHECK_STATUS("delta < 0 refused", autobal_rotor_stab_every_unbalance_margin(s, 0.002, 0.003, -1.0, &v, &ur),
               AUTOBAL_EINVAL);
  CHECK("the message names delta and its range", strstr(autobal_rotor_stab_errmsg(s), "delta") != NULL &&
                                                     strstr(autobal_rotor_stab_errmsg(s), "[0, inf)") != NULL);
  CHECK_STATUS("delta NaN refused", autobal_rotor_stab_every_unbalance_margin(s, 0.002, 0.003, NAN, &v, &ur),
               AUTOBAL_EINVAL);
  CHECK_STATUS("a range the balls cannot balance refused",
               autobal_rotor_stab_every_unbalance_margin(s, 0.002, 0.02, 1.0, &v, &ur), AUTOBAL_EINVAL);
  CHECK_STATUS("NULL verdict refused", autobal_rotor_stab_every_unbalance_margin(s, 0.002, 0.003, 1.0, NULL, &ur),
               AUTOBAL_EINVAL);
}

int main(void) {
  autobal_rotor_stab *an = make(1), *iso = make(0);
  if (an == NULL || iso == NULL) return 1;
  printf("anisotropic supports: the margin against dense Floquet sampling\n");
#ifndef AUTOBAL_TEST_SANITIZE
  /* the sanitizer build (AUTOBAL_TEST_SANITIZE) runs the two cheaper cases below, the same library paths
   * (36180 and 19109 of the 74069 boxes are these two's); the Release pass runs all four */
  aniso_case(an, 500.0, 0.0015, 0.003);
#endif
  aniso_case(an, 1000.0, 0.0015, 0.003);
  aniso_case(an, 700.0, 0.002, 0.004);
#ifndef AUTOBAL_TEST_SANITIZE
  aniso_case(an, 1500.0, 0.001, 0.0025);
#endif
  printf("isotropic supports: the Hill route with delta against the closed set\n");
  iso_case(iso, 500.0, 0.0015, 0.003);
  iso_case(iso, 1000.0, 0.002, 0.004);
  printf("bad input\n");
  bad_input(an);
  autobal_rotor_stab_free(an);
  autobal_rotor_stab_free(iso);
  return check_summary();
}
