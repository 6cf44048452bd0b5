/* test_pendulum_exact.c: the exact integer machinery behind the undamped critical speeds
 * (src/numerics/exact_poly.c, src/analysis/pendulum_exact.c, autobal_pendulum_critical_speeds)
 * against known answers that do not come from it:
 *  1. root isolation of integer polynomials with chosen rational roots (products of linear
 *     factors): every root inside its bracket, checked in exact integers; roots 2^-40 apart,
 *     roots closer than a double can show (the unresolved flag), integer roots (exact
 *     brackets), and the gcd with the derivative of a polynomial with a chosen double root;
 *  2. critical speeds against the closed forms: k = 0: R_w1 = 1 (13) exactly, R_w2, R_w3 near
 *     R_m = 1/4 against the series (14) (relative error below 60 q^5: its next term is about
 *     30 q^5 by 50-digit computations) and near R_m = 0 (below 60 R_m^3 and 10 eps^4); k = 1:
 *     R_w1 against (16), the touch against (18) -- here the touch comes from the discriminant's
 *     double root, so the comparison is not circular -- right up to R_m = 1/4 and beyond it;
 *  3. item 2 of issue 18 in structure: at k = 0.9999, R_m = 0.04482 a stable island
 *     (R_w1, R_w2) of relative width ~1e-7 below the window is reported (gained, lost, gained),
 *     and the exact verdicts on both sides and inside agree with it;
 *  4. the error path: R_m out of range named.
 * The dense comparisons with SymPy's exact root isolation are in tests/app/pendulum_exact.sh. */
#include <float.h>
#include <gmp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/pendulum.h"
#include "check.h"
#include "exact_poly.h"
#include "pendulum_exact.h"

/* p := prod_j (den_j x - num_j) (integers num_j, den_j > 0) */
static void poly_from_roots(autobal_xpoly *p, const long *num, const long *den, int n) {
  autobal_xpoly f;
  int j;
  autobal_xpoly_init(&f);
  autobal_xpoly_zero(p);
  mpz_set_ui(p->c[0], 1);
  p->len = 1;
  for (j = 0; j < n; j++) {
    autobal_xpoly_zero(&f);
    mpz_set_si(f.c[0], -num[j]);
    mpz_set_si(f.c[1], den[j]);
    f.len = 2;
    autobal_xpoly_mul(p, p, &f);
  }
  autobal_xpoly_clear(&f);
}

/* lo <= num/den <= hi, exactly (den > 0) */
static int in_bracket(double lo, double hi, const mpz_t num, const mpz_t den) {
  mpq_t r, a, b;
  int ok;
  mpq_inits(r, a, b, NULL);
  mpz_set(mpq_numref(r), num);
  mpz_set(mpq_denref(r), den);
  mpq_canonicalize(r);
  mpq_set_d(a, lo);
  mpq_set_d(b, hi);
  ok = mpq_cmp(a, r) <= 0 && mpq_cmp(r, b) <= 0;
  mpq_clears(r, a, b, NULL);
  return ok;
}

static int tight(double lo, double hi) { return lo == hi || nextafter(lo, INFINITY) == hi; }

static void test_isolation(void) {
  autobal_xpoly p, d, g;
  double lo[32], hi[32];
  size_t n, i;
  int unres, ok;
  mpz_t num, den;
  printf("-- exact root isolation\n");
  autobal_xpoly_init(&p);
  autobal_xpoly_init(&d);
  autobal_xpoly_init(&g);
  mpz_inits(num, den, NULL);
  {
    /* roots 1/3, 2/7, 5, 1e6/3, 7/1 and a negative one */
    long nu[] = {1, 2, 5, 1000000, 7, -4}, de[] = {3, 7, 1, 3, 1, 9};
    double want[] = {2.0 / 7.0, 1.0 / 3.0, 5.0, 7.0, 1e6 / 3.0};
    long wn[] = {2, 1, 5, 7, 1000000}, wd[] = {7, 3, 1, 1, 3};
    poly_from_roots(&p, nu, de, 6);
    unres = 0;
    CHECK("six rational roots: isolation returns 0", autobal_xpoly_positive_roots(&p, lo, hi, 32, &n, &unres) == 0);
    CHECK("... five positive roots", n == 5);
    ok = n == 5;
    for (i = 0; ok && i < 5; i++) {
      mpz_set_si(num, wn[i]);
      mpz_set_si(den, wd[i]);
      if (!in_bracket(lo[i], hi[i], num, den) || !tight(lo[i], hi[i])) ok = 0;
      if (fabs(lo[i] - want[i]) > 2 * DBL_EPSILON * want[i]) ok = 0;
    }
    CHECK("... each root inside its bracket of adjacent doubles (exact rational test)", ok);
    CHECK("... integer roots 5, 7 are exact brackets", n == 5 && lo[2] == 5.0 && hi[2] == 5.0 && lo[3] == 7.0 && hi[3] == 7.0);
    CHECK("... unresolved = 0", unres == 0);
  }
  {
    /* roots 1 and 1 + 2^-40: two brackets, apart */
    long nu[] = {1L << 40, (1L << 40) + 1}, de[] = {1L << 40, 1L << 40};
    poly_from_roots(&p, nu, de, 2);
    unres = 0;
    autobal_xpoly_positive_roots(&p, lo, hi, 32, &n, &unres);
    CHECK("roots 1 and 1 + 2^-40: two exact brackets", n == 2 && lo[0] == 1.0 && hi[0] == 1.0 &&
                                                         lo[1] == 1.0 + ldexp(1.0, -40) && hi[1] == lo[1]);
  }
  {
    /* roots (3 2^52 + 1)/(3 2^52) and (3 2^52 + 2)/(3 2^52): both in (1, 1 + 2^-52) */
    long t = 3L << 52;
    long nu[] = {t + 1, t + 2}, de[] = {t, t};
    poly_from_roots(&p, nu, de, 2);
    unres = 0;
    autobal_xpoly_positive_roots(&p, lo, hi, 32, &n, &unres);
    CHECK("two roots inside one ulp of 1: both reported, in the same bracket, flagged unresolved",
          n == 2 && lo[0] == 1.0 && hi[0] == nextafter(1.0, 2.0) && lo[1] == lo[0] && hi[1] == hi[0] && unres == 1);
  }
  {
    /* a root pair 1e-9 apart near 1e4 (relative 1e-13) and a double root at 3/11 */
    long nu[] = {10000000000000L, 10000000000001L, 3, 3, 17}, de[] = {1000000000L, 1000000000L, 11, 11, 2};
    poly_from_roots(&p, nu, de, 5);
    unres = 0;
    autobal_xpoly_positive_roots(&p, lo, hi, 32, &n, &unres);
    ok = n == 3;
    mpz_set_si(num, 17), mpz_set_si(den, 2);
    if (ok && !in_bracket(lo[0], hi[0], num, den)) ok = 0;
    mpz_set_si(num, 10000000000000L), mpz_set_si(den, 1000000000L);
    if (ok && !(in_bracket(lo[1], hi[1], num, den) && tight(lo[1], hi[1]))) ok = 0;
    mpz_set_si(num, 10000000000001L);
    if (ok && !(in_bracket(lo[2], hi[2], num, den) && tight(lo[2], hi[2]))) ok = 0;
    CHECK("pair 1e-13 apart (relative) resolved; the double root 3/11 is not a sign change", ok && unres == 0);
    autobal_xpoly_deriv(&d, &p);
    autobal_xpoly_gcd(&g, &p, &d);
    CHECK("gcd(p, p') = 11 x - 3 (the double root)", g.len == 2 && mpz_cmp_si(g.c[1], 11) == 0 && mpz_cmp_si(g.c[0], -3) == 0);
  }
  autobal_xpoly_clear(&p);
  autobal_xpoly_clear(&d);
  autobal_xpoly_clear(&g);
  mpz_clears(num, den, NULL);
}

static void test_closed_forms(autobal_pendulum_workspace *ws) {
  static const double rm_near[] = {0.24, 0.245, 0.249, 0.2495, 0.2497, 0.2499, 0.24995, 0.24999, 0.249999, 0.2499999};
  static const double rm_small[] = {1e-2, 3e-3, 1e-3, 1e-4, 1e-5};
  static const double rm_k1[] = {0.041, 0.05, 0.1, 0.2, 0.249, 0.2499, 0.24999, 0.249999, 0.2499999, 0.25000001,
                                 0.251, 0.3, 0.45};
  autobal_pendulum_crit_set s;
  size_t i;
  double rm1;
  char what[160];
  printf("-- critical speeds against (13), (14), (16), (18)\n");
  for (i = 0; i < sizeof rm_near / sizeof rm_near[0]; i++) {
    double rm = rm_near[i], q = sqrt((0.25 - rm) / 2.0), s2, s3, tol = 60.0 * pow(q, 5) + 4 * DBL_EPSILON;
    int st = autobal_pendulum_critical_speeds(ws, rm, 0.0, &s);
    autobal_pendulum_rw23_k0_series_large(rm, &s2, &s3, NULL);
    snprintf(what, sizeof what, "k = 0, R_m = %.9g: status, three critical speeds gained/lost/gained", rm);
    CHECK(what, st == 0 && s.n == 3 && s.kind[0] == 1 && s.kind[1] == -1 && s.kind[2] == 1 && !s.unresolved);
    snprintf(what, sizeof what, "k = 0, R_m = %.9g: R_w1 = 1 (13)", rm);
    CHECK_CLOSE(what, autobal_pendulum_crit_get(&s, 0), 1.0, 0.0, 0.0);
    snprintf(what, sizeof what, "k = 0, R_m = %.9g: R_w2 vs (14), rel tol 60 q^5", rm);
    CHECK_CLOSE(what, autobal_pendulum_crit_get(&s, 1), s2, tol, 0.0);
    snprintf(what, sizeof what, "k = 0, R_m = %.9g: R_w3 vs (14), rel tol 60 q^5", rm);
    CHECK_CLOSE(what, autobal_pendulum_crit_get(&s, 2), s3, tol, 0.0);
    snprintf(what, sizeof what, "k = 0, R_m = %.9g: stable (1, R_w2) and (R_w3, inf)", rm);
    CHECK(what, s.n_stable == 2 && s.stable_lo[0] == 1.0 && s.stable_hi[0] == s.R_w[1] && s.stable_lo[1] == s.R_w[2] &&
                    isinf(s.stable_hi[1]));
  }
  for (i = 0; i < sizeof rm_small / sizeof rm_small[0]; i++) {
    double rm = rm_small[i], eps = cbrt(rm / 2.0), s2, s3;
    int st = autobal_pendulum_critical_speeds(ws, rm, 0.0, &s);
    autobal_pendulum_rw23_k0_series_small(rm, &s2, &s3, NULL);
    snprintf(what, sizeof what, "k = 0, R_m = %.3g: R_w2 vs (14), rel tol 60 R_m^3", rm);
    CHECK_CLOSE(what, st == 0 ? autobal_pendulum_crit_get(&s, 1) : NAN, s2, 60.0 * rm * rm * rm + 4 * DBL_EPSILON, 0.0);
    snprintf(what, sizeof what, "k = 0, R_m = %.3g: R_w3 vs (14), rel tol 10 eps^4", rm);
    CHECK_CLOSE(what, autobal_pendulum_crit_get(&s, 2), s3, 10.0 * pow(eps, 4), 0.0);
  }
  autobal_pendulum_rm1(&rm1, NULL, NULL);
  for (i = 0; i < sizeof rm_k1 / sizeof rm_k1[0]; i++) {
    double rm = rm_k1[i], r16, r18, touch = NAN;
    size_t j, nt = 0;
    int st = autobal_pendulum_critical_speeds(ws, rm, 1.0, &s);
    autobal_pendulum_rw1_k1(rm, &r16, NULL, NULL);
    r18 = sqrt(2.0 * (1.0 - 2.0 * rm)) / fabs(1.0 - 4.0 * rm); /* (18) (its modulus above 1/4) */
    for (j = 0; j < s.n; j++)
      if (s.kind[j] == AUTOBAL_CRIT_TOUCH) touch = s.R_w[j], nt++;
    snprintf(what, sizeof what, "k = 1, R_m = %.10g: R_w1 (gained) vs (16)", rm);
    /* (16) evaluated in double through u loses a few ulp as 1 - 2u^2 shrinks (R_m = 0.45: 2e-15
     * against 40 digits), hence 1e-14 */
    CHECK_CLOSE(what, st == 0 && s.n >= 1 && s.kind[0] == 1 ? s.R_w[0] : NAN, r16, 1e-14, 0.0);
    if (r18 > r16) {
      snprintf(what, sizeof what, "k = 1, R_m = %.10g: one touch (double root of the discriminant) vs (18)", rm);
      CHECK_CLOSE(what, nt == 1 ? touch : NAN, r18, 4 * DBL_EPSILON, 0.0);
    } else {
      snprintf(what, sizeof what, "k = 1, R_m = %.10g: (18) below R_w1, no touch reported", rm);
      CHECK(what, nt == 0);
    }
    snprintf(what, sizeof what, "k = 1, R_m = %.10g: one crossing only, stable above it", rm);
    CHECK(what, s.n == 1 + nt && s.n_stable == 1 && s.stable_lo[0] == s.R_w[0] && isinf(s.stable_hi[0]) && !s.unresolved);
  }
  CHECK("R_m^(1) in (0.040, 0.041)", rm1 > 0.040 && rm1 < 0.041);
}

static void test_island(autobal_pendulum_workspace *ws) {
  autobal_pendulum_crit_set s;
  autobal_pendulum_exact ex;
  double rm = 0.04482, k = 0.9999;
  int st;
  printf("-- a stable island of relative width ~1e-7 (issue 18 item 2)\n");
  st = autobal_pendulum_critical_speeds(ws, rm, k, &s);
  CHECK("R_m = 0.04482, k = 0.9999: gained, lost, gained", st == 0 && s.n == 3 && s.kind[0] == 1 && s.kind[1] == -1 && s.kind[2] == 1);
  if (s.n == 3) {
    double w = s.R_w[1] / s.R_w[0] - 1;
    CHECK("... island relative width between 1e-8 and 1e-6", w > 1e-8 && w < 1e-6);
    autobal_pendulum_exact_init(&ex, rm, k);
    /* exact verdicts at speeds just outside and inside the island and the window (independent
     * of the root isolation: the quartic criterion at these R_w) */
    CHECK("... unstable just below R_w1", autobal_pendulum_exact_verdict_Rw(&ex, s.R_w[0] * (1 - 1e-12)) == AUTOBAL_VERDICT_UNSTABLE);
    CHECK("... stable inside the island", autobal_pendulum_exact_verdict_Rw(&ex, 0.5 * (s.R_w[0] + s.R_w[1])) == AUTOBAL_VERDICT_STABLE);
    CHECK("... unstable inside the window", autobal_pendulum_exact_verdict_Rw(&ex, 0.5 * (s.R_w[1] + s.R_w[2])) == AUTOBAL_VERDICT_UNSTABLE);
    CHECK("... stable above R_w3", autobal_pendulum_exact_verdict_Rw(&ex, s.R_w[2] * (1 + 1e-12)) == AUTOBAL_VERDICT_STABLE);
    autobal_pendulum_exact_clear(&ex);
  }
  {
    int v;
    /* the public one-point verdict decides inside the island too (exact fall-back) */
    autobal_pendulum_undamped_verdict(rm, s.n == 3 ? 0.5 * (s.R_w[0] + s.R_w[1]) : 1.0, k, &v, NULL);
    CHECK("autobal_pendulum_undamped_verdict: stable inside the island", v == AUTOBAL_VERDICT_STABLE);
  }
}

static void test_errors(autobal_pendulum_workspace *ws) {
  autobal_pendulum_crit_set s;
  printf("-- errors\n");
  CHECK_STATUS("R_m = 0.5 rejected", autobal_pendulum_critical_speeds(ws, 0.5, 0.3, &s), AUTOBAL_EINVAL);
  CHECK_MSG("... names R_m", autobal_pendulum_errmsg(ws), "R_m");
  CHECK_STATUS("k = -0.1 rejected", autobal_pendulum_critical_speeds(ws, 0.2, -0.1, &s), AUTOBAL_EINVAL);
  CHECK_MSG("... names k", autobal_pendulum_errmsg(ws), "k");
}

int main(void) {
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  test_isolation();
  test_closed_forms(ws);
  test_island(ws);
  test_errors(ws);
  autobal_pendulum_workspace_free(ws);
  return check_summary();
}
