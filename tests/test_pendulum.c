/* test_pendulum.c: the two-pendulum autobalancer's stability analysis
 * (pendulum.h, src/models/pendulum/, src/analysis/pendulum_*.c).  Independent reasons for every expected
 * value: the closed facts of docs/pendulum.md, the determinant of the (5) pencil computed
 * here by complex elimination, eigenvalues vs roots, GSL polynomial roots of
 * (10) for the verdicts on both sides of each critical speed, the symbolic
 * factorisation 4v^3 - 8v^2 + 6v - 1 = 0 (v = u^2) for R_m^(1), the next term
 * -407/3456 s^4 of (17) (sympy), asymptotic orders of the series. */
#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>

#include "autobal/pendulum.h"
#include "check.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static unsigned long long rng_state = 0x2545F4914F6CDD1DULL;
static double urand(void) {
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return (double)((rng_state * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

static autobal_pendulum_params random_params(void) {
  autobal_pendulum_params p;
  double u = urand(), k;
  if (u < 0.1) k = 0.0;
  else if (u < 0.2) k = 1.0;
  else k = urand();
  autobal_pendulum_params_from_k(4.0 * urand(), 0.001 + 0.488 * urand(), 2.0 * urand(),
                                 2.0 * urand(), k, &p, NULL);
  return p;
}

/* all roots x of the real quartic c real and <= 0 (GSL roots, loose
 * tolerance); when c[0] == 0 (k = 0) the root x = 0 is divided out first,
 * since the sign of its computed value is rounding noise */
static int quartic_all_real_nonpos(const double c[5], double *worst_im) {
  double re[4], im[4];
  int ok = 1, i, n = c[0] == 0.0 ? 3 : 4;
  autobal_poly_workspace *w = autobal_poly_workspace_alloc((size_t)n);
  autobal_poly_roots(w, c + (4 - n), (size_t)n + 1, re, im, NULL);
  autobal_poly_workspace_free(w);
  *worst_im = 0.0;
  for (i = 0; i < n; i++) {
    double s = 1.0 + hypot(re[i], im[i]);
    if (fabs(im[i]) / s > *worst_im) *worst_im = fabs(im[i]) / s;
    if (fabs(im[i]) > 1e-6 * s || re[i] > 1e-12 * s) ok = 0;
  }
  return ok;
}

static int roots_stable_undamped(double Rm, double Rw, double k) {
  double c[5], wi;
  autobal_pendulum_undamped_poly(Rm, Rw, k, c, NULL);
  return quartic_all_real_nonpos(c, &wi);
}

/* ------------------------------------------------------------------------ */

static void test_params(void) {
  autobal_error err;
  autobal_pendulum_params p, good;
  autobal_pendulum_physical q = {10.0, 0.01, 1.0, 0.1, 1200.0, 0.05, 24.0, 15.0};
  printf("-- parameters (2), (3) and validation\n");
  /* M_sigma = 12, omega0 = 10, R_w = 1.5, R_m = 1/12, H = 24/120, h = 0.05/(0.01*10),
   * sin psi0 = 10*0.01/(2*1*0.1) = 1/2 -> psi0 = pi/6, k = sin^2(pi/3) = 3/4 */
  CHECK_STATUS("from_physical", autobal_pendulum_params_from_physical(&q, &p, NULL), AUTOBAL_SUCCESS);
  CHECK_CLOSE("R_w = omega/omega0", p.R_w, 1.5, 1e-15, 0);
  CHECK_CLOSE("R_m = m/(M+2m)", p.R_m, 1.0 / 12.0, 1e-15, 0);
  CHECK_CLOSE("H = H2/(omega0 M_sigma)", p.H, 0.2, 1e-15, 0);
  CHECK_CLOSE("h = H1/(m l^2 omega0)", p.h, 0.5, 1e-15, 0);
  CHECK_CLOSE("psi0 = asin(Me/2ml)", p.psi0, M_PI / 6.0, 1e-15, 0);
  CHECK_CLOSE("k = sin^2(2 psi0)", autobal_pendulum_k(&p), 0.75, 1e-15, 0);
  good = p;
  CHECK_STATUS("from_k(k = 3/4)", autobal_pendulum_params_from_k(1.5, 1.0 / 12, 0.2, 0.5, 0.75, &p, NULL),
               AUTOBAL_SUCCESS);
  CHECK_CLOSE("from_k: psi0 in [0, pi/4] with sin^2(2 psi0) = k", p.psi0, M_PI / 6.0, 1e-15, 0);
  CHECK_STATUS("valid parameters pass", autobal_pendulum_params_validate(&good, NULL), AUTOBAL_SUCCESS);

#define BAD(field, value, needle)                                                          \
  do {                                                                                     \
    p = good;                                                                              \
    p.field = (value);                                                                     \
    autobal_error_clear(&err);                                                             \
    CHECK_STATUS("reject " #field " = " #value, autobal_pendulum_params_validate(&p, &err), \
                 AUTOBAL_EINVAL);                                                          \
    CHECK_MSG("message names " #field, err.message, needle);                               \
  } while (0)
  BAD(R_m, 0.5, "R_m = 0.5");
  BAD(R_m, -1.0, "R_m = -1");
  BAD(R_m, 0.0, "R_m = 0");
  BAD(R_w, NAN, "R_w = nan");
  BAD(R_w, -0.1, "R_w");
  BAD(H, -1e-3, "parameter H");
  BAD(h, -2.0, "parameter h");
  BAD(h, INFINITY, "parameter h");
  BAD(psi0, M_PI / 2, "psi0");
  BAD(psi0, -0.1, "psi0");
#undef BAD
  CHECK_MSG("message gives the allowed range", err.message, "is too small: must be >= 0 rad (allowed range [0, 1.5707963267948966))");
  autobal_error_clear(&err);
  CHECK_STATUS("from_k rejects k = 1.1", autobal_pendulum_params_from_k(1, 0.1, 0, 0, 1.1, &p, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("... naming k", err.message, "parameter k = 1.1");
  CHECK_STATUS("from_k rejects k = -0.5", autobal_pendulum_params_from_k(1, 0.1, 0, 0, -0.5, &p, &err),
               AUTOBAL_EINVAL);
  CHECK_STATUS("from_k rejects R_m = 0.5", autobal_pendulum_params_from_k(1, 0.5, 0, 0, 0.5, &p, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("... naming R_m", err.message, "R_m");
  {
    autobal_pendulum_physical b;
#define BADP(field, value, needle)                                                                 \
  do {                                                                                             \
    b = q;                                                                                         \
    b.field = (value);                                                                             \
    autobal_error_clear(&err);                                                                     \
    CHECK_STATUS("physical: reject " #field " = " #value,                                          \
                 autobal_pendulum_params_from_physical(&b, &p, &err), AUTOBAL_EINVAL);             \
    CHECK_MSG("physical: message names " #field, err.message, needle);                             \
  } while (0)
    BADP(M, 0.0, "parameter M = 0");
    BADP(m, -1.0, "parameter m = -1");
    BADP(l, NAN, "parameter l");
    BADP(c, -5.0, "parameter c");
    BADP(H1, -0.1, "parameter H1");
    BADP(H2, -0.1, "parameter H2");
    BADP(omega, -1.0, "parameter omega");
    BADP(e, -0.01, "parameter e");
    BADP(e, 0.02, "M*e"); /* M e = 0.2 = 2 m l */
    BADP(e, 0.05, "M*e");
#undef BADP
    CHECK_MSG("M e >= 2 m l: message gives the limit", err.message, "0.2");
  }
}

/* determinant of a 4x4 complex matrix by Gaussian elimination with pivoting */
static double complex det4(double complex a[4][4]) {
  double complex d = 1.0;
  int i, j, r;
  for (r = 0; r < 4; r++) {
    int piv = r;
    for (i = r + 1; i < 4; i++)
      if (cabs(a[i][r]) > cabs(a[piv][r])) piv = i;
    if (piv != r) {
      for (j = 0; j < 4; j++) {
        double complex t = a[r][j];
        a[r][j] = a[piv][j];
        a[piv][j] = t;
      }
      d = -d;
    }
    d *= a[r][r];
    if (a[r][r] == 0) return 0;
    for (i = r + 1; i < 4; i++) {
      double complex f = a[i][r] / a[r][r];
      for (j = r; j < 4; j++) a[i][j] -= f * a[r][j];
    }
  }
  return d;
}

static void test_char_poly(void) {
  int t, i, j;
  double worst_det = 0.0, worst_fact = 0.0, worst_raw = 0.0, worst_c1 = 0.0, worst_c8 = 0.0;
  double worst_c0 = 0.0;
  printf("-- characteristic polynomial (6) vs the pencil of (5)\n");
  for (t = 0; t < 60; t++) {
    autobal_pendulum_params p = random_params();
    double c[9], Mm[16], C[16], K[16], W = p.R_w * p.R_w, k = autobal_pendulum_k(&p);
    double a11[6], a31[6], a33[6], t1[10], t2[10], p1[10], p1c[10], q[18], raw[9];
    double scale = 0.0;
    autobal_pendulum_char_poly(&p, c, NULL);
    autobal_pendulum_linear_matrices(&p, Mm, C, K, NULL);
    for (j = 0; j < 9; j++)
      if (fabs(c[j]) > scale) scale = fabs(c[j]);
    /* useful facts */
    if (fabs(c[1] - 2 * p.h * p.R_m * W * W * (W - 1)) / scale > worst_c1)
      worst_c1 = fabs(c[1] - 2 * p.h * p.R_m * W * W * (W - 1)) / scale;
    if (fabs(c[8] - (1 - 2 * p.R_m + k * p.R_m * p.R_m)) > worst_c8)
      worst_c8 = fabs(c[8] - (1 - 2 * p.R_m + k * p.R_m * p.R_m));
    /* (6) from the blocks, by this test's own complex arithmetic */
    autobal_pendulum_char_blocks(&p, a11, a31, a33, NULL);
    autobal_cpoly_mul(a11, 3, a33, 3, t1, 5, NULL);
    autobal_cpoly_mul(a31, 3, a31, 3, t2, 5, NULL);
    autobal_cpoly_axpby(1, 0, t1, 5, -p.R_m, 0, t2, 5, p1, 5, NULL);
    autobal_cpoly_conj(p1, 5, p1c);
    autobal_cpoly_mul(p1, 5, p1c, 5, q, 9, NULL);
    autobal_cpoly_real_part(q, 9, raw, NULL);
    {
      double cc = cos(2 * p.psi0), b2[10], b2c[10], bq[18], braw[9];
      autobal_cpoly_conj(t2, 5, b2c);
      memcpy(b2, t2, sizeof b2);
      autobal_cpoly_mul(b2, 5, b2c, 5, bq, 9, NULL);
      autobal_cpoly_real_part(bq, 9, braw, NULL);
      for (j = 0; j < 9; j++) raw[j] -= p.R_m * p.R_m * cc * cc * braw[j];
    }
    /* the constant term: raw arithmetic agrees with k R_m^2 W^4 up to rounding of R_m^2 W^4 */
    if (fabs(raw[0] - k * p.R_m * p.R_m * W * W * W * W) / (1e-300 + p.R_m * p.R_m * W * W * W * W) >
        worst_c0)
      worst_c0 = fabs(raw[0] - k * p.R_m * p.R_m * W * W * W * W) / (p.R_m * p.R_m * W * W * W * W);
    for (j = 1; j < 9; j++)
      if (fabs(raw[j] - c[j]) / scale > worst_raw) worst_raw = fabs(raw[j] - c[j]) / scale;
    /* (6) == det(M l^2 + C l + K) at random complex lambda */
    for (i = 0; i < 3; i++) {
      double complex lam = (urand() * 4 - 2) + I * (urand() * 4 - 2), a[4][4], d;
      double pr, pi, mag = 0.0;
      int r, s;
      for (r = 0; r < 4; r++)
        for (s = 0; s < 4; s++) a[r][s] = Mm[4 * r + s] * lam * lam + C[4 * r + s] * lam + K[4 * r + s];
      d = det4(a);
      autobal_poly_eval_complex(c, 9, creal(lam), cimag(lam), &pr, &pi);
      for (j = 0; j < 9; j++) mag += fabs(c[j]) * pow(cabs(lam), j);
      if (cabs(d - (pr + I * pi)) / mag > worst_det) worst_det = cabs(d - (pr + I * pi)) / mag;
    }
    /* (15): at k = 1, (6) = P1 conj(P1) */
    {
      autobal_pendulum_params p1p = p;
      double pp[10], ppc[10], prod[18], rp[9], c1[9], sc = 0.0;
      p1p.psi0 = M_PI / 4;
      autobal_pendulum_char_poly(&p1p, c1, NULL);
      autobal_pendulum_char_p1(&p1p, pp, NULL);
      autobal_cpoly_conj(pp, 5, ppc);
      autobal_cpoly_mul(pp, 5, ppc, 5, prod, 9, NULL);
      autobal_cpoly_real_part(prod, 9, rp, NULL);
      for (j = 0; j < 9; j++)
        if (fabs(c1[j]) > sc) sc = fabs(c1[j]);
      for (j = 0; j < 9; j++)
        if (fabs(rp[j] - c1[j]) / sc > worst_fact) worst_fact = fabs(rp[j] - c1[j]) / sc;
    }
  }
  CHECK_CLOSE("60 sets: coefficient of lambda = 2 h R_m W^2 (W-1), rel. to max |coef|", worst_c1, 0, 0, 1e-14);
  CHECK_CLOSE("60 sets: leading coefficient = 1 - 2R_m + k R_m^2", worst_c8, 0, 0, 1e-15);
  CHECK_CLOSE("60 sets: constant term of the arithmetic = k R_m^2 W^4 (rel. to R_m^2 W^4)", worst_c0, 0, 0, 1e-14);
  CHECK_CLOSE("60 sets: char_poly == products of a11, a31, a33 (rel.)", worst_raw, 0, 0, 1e-14);
  CHECK_CLOSE("180 lambdas: (6) == det(M l^2 + C l + K) (rel. to sum |c_j| |l|^j)", worst_det, 0, 0, 1e-13);
  CHECK_CLOSE("60 sets at k = 1: (6) == P1 conj(P1) (15)", worst_fact, 0, 0, 1e-14);
  {
    autobal_pendulum_params p;
    double c[9];
    autobal_pendulum_params_from_k(1.3, 0.2, 0.1, 0.2, 0.0, &p, NULL);
    autobal_pendulum_char_poly(&p, c, NULL);
    CHECK("k = 0: constant term exactly 0 (structural root lambda = 0)", c[0] == 0.0);
  }
  /* (10) == (6) at H = h = 0 */
  {
    double worst = 0.0, odd = 0.0;
    for (t = 0; t < 40; t++) {
      autobal_pendulum_params p = random_params();
      double c[9], u[5], sc = 0.0;
      p.H = p.h = 0.0;
      autobal_pendulum_char_poly(&p, c, NULL);
      autobal_pendulum_undamped_poly(p.R_m, p.R_w, autobal_pendulum_k(&p), u, NULL);
      for (j = 0; j < 9; j++)
        if (fabs(c[j]) > sc) sc = fabs(c[j]);
      for (j = 0; j < 5; j++)
        if (fabs(c[2 * j] - u[j]) / sc > worst) worst = fabs(c[2 * j] - u[j]) / sc;
      for (j = 0; j < 4; j++)
        if (fabs(c[2 * j + 1]) / sc > odd) odd = fabs(c[2 * j + 1]) / sc;
    }
    CHECK_CLOSE("40 sets: (10) in x = lambda^2 == even coefficients of (6) at H = h = 0", worst, 0, 0, 1e-14);
    CHECK_CLOSE("40 sets: odd coefficients of (6) vanish at H = h = 0", odd, 0, 0, 1e-15);
  }
}

static void test_analyze(void) {
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  autobal_pendulum_result r;
  double worst = 0.0, worst_abs = 0.0;
  int t, disagree = 0, decided = 0, hurwitz_vs_roots = 0, st;
  printf("-- one-call analysis: roots of (6) vs eigenvalues of (5), sign test vs roots\n");
  CHECK("workspace allocated", ws != NULL);
  for (t = 0; t < 300; t++) {
    autobal_pendulum_params p = random_params();
    st = autobal_pendulum_analyze(ws, &p, &r);
    if (st != AUTOBAL_SUCCESS) {
      disagree += 1000;
      continue;
    }
    if (r.mismatch_rel > worst) worst = r.mismatch_rel;
    if (r.mismatch > worst_abs) worst_abs = r.mismatch;
    /* verdicts: decided when the margin is clear */
    if (fabs(r.max_real) > 1e-6) {
      decided++;
      if (r.verdict != r.verdict_roots) disagree++;
      if ((r.verdict == AUTOBAL_VERDICT_STABLE) != (r.max_real < 0)) hurwitz_vs_roots++;
      if ((r.max_real_eig < 0) != (r.max_real < 0)) hurwitz_vs_roots++;
    }
  }
  printf("   max |root - eigenvalue| over 300 sets: %.3g absolute, %.3g relative; %d decided\n",
         worst_abs, worst, decided);
  CHECK_CLOSE("300 random sets: max |root - eigenvalue| / max(1, |root|)", worst, 0, 0, 1e-8);
  CHECK("300 random sets: sign-test verdict == root verdict when |max Re| > 1e-6", disagree == 0);
  CHECK("... and max Re of roots and of eigenvalues have the same sign", hurwitz_vs_roots == 0);
  CHECK("most sets decided", decided > 200);
  /* k = 0: structural zero root deflated */
  {
    autobal_pendulum_params p;
    /* R_w = 3.5 > R_w3(0.1, 0) = 2.735: stable region of the undamped k = 0 case */
    autobal_pendulum_params_from_k(3.5, 0.1, 0.2, 0.3, 0.0, &p, NULL);
    autobal_pendulum_analyze(ws, &p, &r);
    CHECK("k = 0: zero root deflated", r.zero_root_deflated == 1);
    {
      int i, has0 = 0;
      for (i = 0; i < 8; i++)
        if (hypot(r.root_re[i], r.root_im[i]) < 1e-10) has0 = 1;
      CHECK("k = 0: (6) has the root lambda = 0", has0);
    }
    CHECK("k = 0, R_w = 3.5, damped: verdict stable from both tests",
          r.verdict == AUTOBAL_VERDICT_STABLE && r.verdict_roots == AUTOBAL_VERDICT_STABLE);
    autobal_pendulum_params_from_k(3.0, 0.1, 0.0, 0.0, 0.5, &p, NULL);
    autobal_pendulum_analyze(ws, &p, &r);
    CHECK("H = h = 0: undamped, the verdict from (10) (stable), n_rhp = 0",
          r.undamped == 1 && r.verdict == AUTOBAL_VERDICT_STABLE && r.n_rhp == 0);
    CHECK("H = h = 0, R_m = 0.1, k = 0.5, R_w = 3: stable in the first approximation",
          r.undamped_verdict == AUTOBAL_VERDICT_STABLE && roots_stable_undamped(0.1, 3.0, 0.5));
    p.R_w = 2.0; /* inside the window (1.657, 2.557) of R_m = 0.1, k = 0.5 */
    autobal_pendulum_analyze(ws, &p, &r);
    CHECK("H = h = 0, R_m = 0.1, k = 0.5, R_w = 2: unstable",
          r.undamped_verdict == AUTOBAL_VERDICT_UNSTABLE && !roots_stable_undamped(0.1, 2.0, 0.5));
    CHECK("... the verdict too, from (10) (a complex pair of x: n_rhp = 2), roots agree",
          r.verdict == AUTOBAL_VERDICT_UNSTABLE && r.n_rhp == 2 && r.verdict_roots == AUTOBAL_VERDICT_UNSTABLE);
  }
  /* error paths */
  {
    autobal_pendulum_params p;
    autobal_pendulum_params_from_k(2.0, 0.1, 0.2, 0.3, 0.5, &p, NULL);
    p.R_m = 0.75;
    CHECK_STATUS("analyze: R_m = 0.75 rejected", autobal_pendulum_analyze(ws, &p, &r), AUTOBAL_EINVAL);
    CHECK_MSG("analyze: errmsg names R_m", autobal_pendulum_errmsg(ws), "R_m = 0.75");
    CHECK_STATUS("analyze: status kept in workspace", autobal_pendulum_status(ws), AUTOBAL_EINVAL);
    p.R_m = 0.1;
    CHECK_STATUS("analyze: NULL result", autobal_pendulum_analyze(ws, &p, NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("analyze: NULL workspace", autobal_pendulum_analyze(NULL, &p, &r), AUTOBAL_EINVAL);
    CHECK_STATUS("analyze: success clears the message", autobal_pendulum_analyze(ws, &p, &r), AUTOBAL_SUCCESS);
    CHECK("... errmsg empty", autobal_pendulum_errmsg(ws)[0] == '\0');
    CHECK("errmsg(NULL) is \"\"", autobal_pendulum_errmsg(NULL)[0] == '\0');
    autobal_pendulum_workspace_free(NULL);
  }
  autobal_pendulum_workspace_free(ws);
}

static void test_undamped(void) {
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  int t, bad = 0, bad12 = 0, n = 0;
  autobal_error err;
  printf("-- undamped verdict (10) vs roots, (12)\n");
  for (t = 0; t < 2000; t++) {
    double Rm = 0.001 + 0.49 * urand(), Rw = 0.05 + 4.0 * urand(), k = t % 5 == 0 ? 0.0 : (t % 5 == 1 ? 1.0 : urand());
    double c[5], wi;
    int v, rs;
    autobal_pendulum_undamped_verdict(Rm, Rw, k, &v, NULL);
    autobal_pendulum_undamped_poly(Rm, Rw, k, c, NULL);
    rs = quartic_all_real_nonpos(c, &wi);
    /* skip points too close to a boundary for the loose root test */
    if (wi > 1e-9 && wi < 1e-3) continue;
    n++;
    if ((v == AUTOBAL_VERDICT_STABLE) != rs) bad++;
    if (k == 0.0) {
      int s12;
      autobal_pendulum_cond12(Rm, Rw, NULL, &s12, NULL);
      if (s12 != (v == AUTOBAL_VERDICT_STABLE)) bad12++;
    }
  }
  printf("   (%d points compared)\n", n);
  CHECK("2000 random points: exact sign criterion == GSL roots of (10) all real <= 0", bad == 0);
  CHECK("k = 0 points: (12) == verdict", bad12 == 0);
  CHECK("most points compared", n > 1800);
  {
    /* the verdict of autobal_pendulum_verdict / analyze at H = h = 0 (issue 18 item 4) against
     * the eigenvalues of the 8x8 matrix of (5) (GSL, no use of (10)): unstable iff some
     * eigenvalue has Re > 0, the count of those = n_rhp; at k = 0 the two eigenvalues nearest 0
     * (the family and its rate) are left out.  Points whose largest |Re| lies between 1e-9 and
     * 1e-4 (near a critical speed, where a double root splits by ~sqrt(eps)) are skipped. */
    autobal_eigen_workspace *ew = autobal_eigen_workspace_alloc(8);
    int nv = 0, badv = 0, badn = 0, nst = 0, nun = 0;
    for (t = 0; t < 3000; t++) {
      double Rm = 0.001 + 0.49 * urand(), Rw = 0.05 + 4.0 * urand();
      double k = t % 5 == 0 ? 0.0 : (t % 5 == 1 ? 1.0 : urand());
      double A[64], er[8], ei[8], mre = -INFINITY;
      int v = -9, nr = -9, cnt = 0, i, j, skip[8] = {0, 0, 0, 0, 0, 0, 0, 0};
      autobal_pendulum_params p;
      autobal_pendulum_result r;
      autobal_pendulum_params_from_k(Rw, Rm, 0.0, 0.0, k, &p, NULL);
      k = autobal_pendulum_k(&p);
      autobal_pendulum_first_order_matrix(&p, A, NULL);
      autobal_eigen_nonsymm(ew, A, er, ei, NULL);
      for (j = 0; j < (k == 0.0 ? 2 : 0); j++) {
        int b = -1;
        for (i = 0; i < 8; i++)
          if (!skip[i] && (b < 0 || hypot(er[i], ei[i]) < hypot(er[b], ei[b]))) b = i;
        skip[b] = 1;
      }
      for (i = 0; i < 8; i++) {
        if (skip[i]) continue;
        if (fabs(er[i]) > mre) mre = fabs(er[i]);
        cnt += er[i] > 1e-9 * (1.0 + hypot(er[i], ei[i]));
      }
      if (mre > 1e-9 && mre < 1e-4) continue;
      nv++;
      autobal_pendulum_verdict(&p, &v, &nr, NULL);
      autobal_pendulum_analyze(ws, &p, &r);
      if (v != (cnt ? AUTOBAL_VERDICT_UNSTABLE : AUTOBAL_VERDICT_STABLE) || r.verdict != v) badv++;
      if (nr != cnt || r.n_rhp != cnt) badn++;
      nst += v == AUTOBAL_VERDICT_STABLE, nun += v == AUTOBAL_VERDICT_UNSTABLE;
    }
    autobal_eigen_workspace_free(ew);
    printf("   (%d undamped points vs eigenvalues of (5): %d stable, %d unstable)\n", nv, nst, nun);
    CHECK("3000 random points, H = h = 0: verdict (verdict and analyze) == eigenvalues of (5)", badv == 0);
    CHECK("... n_rhp == eigenvalues with Re > 0", badn == 0);
    CHECK("... most points compared, both verdicts", nv > 2500 && nst > 300 && nun > 300);
  }
  autobal_error_clear(&err);
  CHECK_STATUS("undamped_verdict: k = 1.5", autobal_pendulum_undamped_verdict(0.1, 1, 1.5, &t, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("... names k", err.message, "parameter k");
  CHECK_STATUS("undamped_poly: R_w < 0", autobal_pendulum_undamped_poly(0.1, -1, 0.5, NULL, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("... names R_w", err.message, "parameter R_w");
  CHECK_STATUS("cond12: R_m = 0.5", autobal_pendulum_cond12(0.5, 1, NULL, NULL, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("discriminant: k = NaN", autobal_pendulum_undamped_discriminant(0.1, NAN, NULL, &err),
               AUTOBAL_EINVAL);
  /* the discriminant polynomial == prod (x_i - x_j)^2 a^6 at random W */
  {
    double disc[13], worst = 0.0;
    for (t = 0; t < 30; t++) {
      double Rm = 0.01 + 0.45 * urand(), k = urand(), Rw = 0.3 + 3 * urand(), c[5], re[4], im[4];
      double complex prod = 1.0;
      int i, j;
      autobal_poly_workspace *w = autobal_poly_workspace_alloc(4);
      autobal_pendulum_undamped_discriminant(Rm, k, disc, NULL);
      autobal_pendulum_undamped_poly(Rm, Rw, k, c, NULL);
      autobal_poly_roots(w, c, 5, re, im, NULL);
      autobal_poly_workspace_free(w);
      for (i = 0; i < 4; i++)
        for (j = i + 1; j < 4; j++) {
          double complex d = (re[i] - re[j]) + I * (im[i] - im[j]);
          prod *= d * d;
        }
      prod *= pow(c[4], 6);
      {
        double dv = autobal_poly_eval(disc, 13, Rw * Rw), mag = 0.0;
        for (i = 0; i < 13; i++) mag += fabs(disc[i]) * pow(Rw * Rw, i);
        if (fabs(dv - creal(prod)) / mag > worst) worst = fabs(dv - creal(prod)) / mag;
      }
    }
    CHECK_CLOSE("30 points: discriminant in W == a^6 prod (x_i - x_j)^2 from roots (rel.)", worst, 0, 0, 1e-9);
  }
  autobal_pendulum_workspace_free(ws);
}

static void test_critical(void) {
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  autobal_pendulum_crit_set s;
  const double rms[] = {0.001, 0.01, 0.03, 0.05, 0.1, 0.2, 0.24, 0.26, 0.3, 0.45};
  const double ks[] = {0.0, 0.3, 0.7, 0.99, 1.0};
  size_t i, j, c;
  int bad_side = 0, n_checked = 0, bad16 = 0, bad13 = 0, count0 = 0;
  double worst16 = 0.0, worst18 = 0.0;
  printf("-- critical speeds of the undamped system\n");
  for (i = 0; i < sizeof rms / sizeof *rms; i++)
    for (j = 0; j < sizeof ks / sizeof *ks; j++) {
      if (autobal_pendulum_critical_speeds(ws, rms[i], ks[j], &s) != AUTOBAL_SUCCESS) {
        bad_side += 100;
        continue;
      }
      for (c = 0; c < s.n; c++) {
        double rc = s.R_w[c], lo = rc * (1 - 1e-7), hi = rc * (1 + 1e-7);
        int sl = roots_stable_undamped(rms[i], lo, ks[j]), sh = roots_stable_undamped(rms[i], hi, ks[j]);
        if (c + 1 < s.n && s.R_w[c + 1] < hi * (1 + 1e-7)) continue; /* too narrow for this check */
        if (c > 0 && s.R_w[c - 1] > lo * (1 - 1e-7)) continue;
        n_checked++;
        if (s.kind[c] == AUTOBAL_CRIT_GAINED && !(sh && !sl)) bad_side++;
        if (s.kind[c] == AUTOBAL_CRIT_LOST && !(sl && !sh)) bad_side++;
        if (s.kind[c] == AUTOBAL_CRIT_TOUCH && !(sl && sh)) bad_side++;
      }
      if (ks[j] == 0.0) {
        /* (13): R_w1(R_m, 0) = 1, gained; three critical speeds below 1/4, one above */
        if (!(s.n >= 1 && s.R_w[0] == 1.0 && s.kind[0] == AUTOBAL_CRIT_GAINED)) bad13++;
        if (autobal_pendulum_crit_count(&s) != (rms[i] < 0.25 ? 3u : 1u)) count0++;
      }
      if (ks[j] == 1.0) {
        double r16, r18;
        autobal_pendulum_rw1_k1(rms[i], &r16, NULL, NULL);
        if (fabs(autobal_pendulum_crit_get(&s, 0) - r16) / r16 > worst16)
          worst16 = fabs(autobal_pendulum_crit_get(&s, 0) - r16) / r16;
        if (autobal_pendulum_crit_count(&s) != 1) bad16++;
        if (rms[i] < 0.25) {
          autobal_pendulum_rw23_k1(rms[i], &r18, NULL);
          for (c = 0; c < s.n; c++)
            if (s.kind[c] == AUTOBAL_CRIT_TOUCH && fabs(s.R_w[c] - r18) / r18 > worst18)
              worst18 = fabs(s.R_w[c] - r18) / r18;
        }
      }
    }
  printf("   (%d critical speeds checked with roots on both sides)\n", n_checked);
  CHECK("every critical speed: roots of (10) at R_w (1 -+ 1e-7) agree with its kind", bad_side == 0);
  CHECK("... many checked", n_checked > 60);
  CHECK("(13): R_w1(R_m, 0) = 1 exactly, stability gained", bad13 == 0);
  CHECK("k = 0: three critical speeds for R_m < 1/4, one above", count0 == 0);
  CHECK("k = 1: one critical speed (the rest are touches)", bad16 == 0);
  CHECK_CLOSE("(16) vs numerical R_w1(R_m, 1), worst relative over 10 R_m", worst16, 0, 0, 1e-12);
  CHECK_CLOSE("(18) vs the touch (double root of (10)) at k = 1, worst relative", worst18, 0, 0, 1e-9);
  /* k -> 1: the unstable window (R_w2, R_w3) shrinks onto (18), width ~ sqrt(1 - k) */
  {
    double Rm = 0.1, r18, w_prev = 0.0;
    const double dk[] = {1e-4, 1e-6, 1e-8, 1e-10};
    autobal_pendulum_rw23_k1(Rm, &r18, NULL);
    for (j = 0; j < 4; j++) {
      double a, b;
      char what[160];
      autobal_pendulum_critical_speeds(ws, Rm, 1.0 - dk[j], &s);
      CHECK("k = 1 - dk, R_m = 0.1: three critical speeds", autobal_pendulum_crit_count(&s) == 3);
      a = autobal_pendulum_crit_get(&s, 1);
      b = autobal_pendulum_crit_get(&s, 2);
      snprintf(what, sizeof what, "dk = %g: window (%.12g, %.12g) contains (18) = %.12g", dk[j], a, b, r18);
      CHECK(what, a < r18 && r18 < b);
      snprintf(what, sizeof what, "dk = %g: roots unstable inside the window, stable outside", dk[j]);
      CHECK(what, !roots_stable_undamped(Rm, 0.5 * (a + b), 1.0 - dk[j]) &&
                      roots_stable_undamped(Rm, a - (b - a), 1.0 - dk[j]) &&
                      roots_stable_undamped(Rm, b + (b - a), 1.0 - dk[j]));
      if (j > 0) CHECK_CLOSE("window width ratio for dk / 100 (width ~ sqrt(dk))", w_prev / (b - a), 10.0, 0.02, 0);
      w_prev = b - a;
    }
  }
  /* windows far narrower than the discriminant in W can resolve (1 - k down
   * to 1e-16): still found, centred on (18), width ~ sqrt(1 - k) */
  {
    double r18, a, b, w10;
    autobal_pendulum_rw23_k1(0.2, &r18, NULL);
    autobal_pendulum_critical_speeds(ws, 0.2, 1.0 - 1e-10, &s);
    w10 = autobal_pendulum_crit_get(&s, 2) - autobal_pendulum_crit_get(&s, 1);
    autobal_pendulum_critical_speeds(ws, 0.2, 1.0 - 1e-14, &s);
    a = autobal_pendulum_crit_get(&s, 1);
    b = autobal_pendulum_crit_get(&s, 2);
    CHECK("R_m = 0.2, k = 1 - 1e-14: window found around (18)",
          autobal_pendulum_crit_count(&s) == 3 && a < r18 && r18 < b);
    CHECK_CLOSE("... width(1 - 1e-10) / width(1 - 1e-14) = sqrt(1e4)", w10 / (b - a), 100.0, 0.01, 0);
  }
  /* k -> 0: R_w1(R_m, k) - 1 ~ sqrt(k) (the pair at x = 0, W = 1 of (13)) */
  {
    double d12, d16;
    autobal_pendulum_critical_speeds(ws, 0.1, 1e-12, &s);
    d12 = autobal_pendulum_crit_get(&s, 0) - 1.0;
    autobal_pendulum_critical_speeds(ws, 0.1, 1e-16, &s);
    d16 = autobal_pendulum_crit_get(&s, 0) - 1.0;
    CHECK("k = 1e-16: R_w1 above 1, stability gained", d16 > 0 && s.kind[0] == AUTOBAL_CRIT_GAINED);
    CHECK_CLOSE("R_w1 - 1 at k = 1e-12 over k = 1e-16: sqrt(1e4) = 100", d12 / d16, 100.0, 1e-4, 0);
  }
  /* near R_m = 1/4 (R_w ~ 250): reference roots of the cubic discriminant in W
   * computed independently with mpmath (50 digits, findroot on (12)'s lhs) */
  {
    autobal_pendulum_critical_speeds(ws, 0.249, 0.0, &s);
    CHECK_CLOSE("R_m = 0.249: R_w2(R_m, 0) vs 50-digit reference", autobal_pendulum_crit_get(&s, 1),
                239.53175855327261, 1e-10, 0);
    CHECK_CLOSE("R_m = 0.249: R_w3(R_m, 0) vs 50-digit reference", autobal_pendulum_crit_get(&s, 2),
                261.8408115730119, 1e-10, 0);
  }
  /* R_m^(1): the symbolic factorisation of (16)^2 - (18)^2 in u gives
   * (3u^2 - 1)(4u^6 - 8u^4 + 6u^2 - 1)^2, so the touch is at the root v of
   * 4v^3 - 8v^2 + 6v - 1 = 0, v = u^2 */
  {
    double rm1, rw, v0, v1, v2, u, ref;
    int nr = gsl_poly_solve_cubic(-2.0, 1.5, -0.25, &v0, &v1, &v2);
    CHECK("cubic 4v^3 - 8v^2 + 6v - 1 has one real root", nr == 1);
    u = sqrt(v0);
    ref = pow(u * u * u / (1 - 2 * u * u), 2);
    CHECK_STATUS("rm1", autobal_pendulum_rm1(&rm1, &rw, NULL), AUTOBAL_SUCCESS);
    printf("   R_m^(1) = %.15g, R_w there = %.15g\n", rm1, rw);
    CHECK_CLOSE("R_m^(1) vs the root of the factor", rm1, ref, 1e-11, 0);
    CHECK_CLOSE("R_w at R_m^(1) = (16) there", rw, sqrt(1 - u * u) / (1 - 2 * u * u), 1e-11, 0);
    /* windows exist just above R_m^(1) and not just below */
    autobal_pendulum_critical_speeds(ws, rm1 * 1.05, 1.0 - 1e-6, &s);
    CHECK("R_m = 1.05 R_m^(1), k = 1 - 1e-6: a window (3 critical speeds)", autobal_pendulum_crit_count(&s) == 3);
    autobal_pendulum_critical_speeds(ws, rm1 * 0.95, 1.0 - 1e-6, &s);
    CHECK("R_m = 0.95 R_m^(1), k = 1 - 1e-6: no window (1 critical speed)", autobal_pendulum_crit_count(&s) == 1);
  }
  /* stable intervals */
  {
    double r2, r3;
    autobal_pendulum_critical_speeds(ws, 0.1, 0.0, &s);
    r2 = autobal_pendulum_crit_get(&s, 1);
    r3 = autobal_pendulum_crit_get(&s, 2);
    CHECK("k = 0, R_m = 0.1: stable on (1, R_w2) and (R_w3, inf)",
          s.n_stable == 2 && s.stable_lo[0] == 1.0 && s.stable_hi[0] == r2 && s.stable_lo[1] == r3 &&
              isinf(s.stable_hi[1]));
  }
  /* curves */
  {
    double R_m[3] = {0.05, 0.2, 0.3}, rw[9];
    CHECK_STATUS("curves k = 0", autobal_pendulum_critical_curves(ws, 0.0, R_m, 3, 3, rw), AUTOBAL_SUCCESS);
    autobal_pendulum_critical_speeds(ws, 0.2, 0.0, &s);
    CHECK("curves: R_m = 0.2 row == critical speeds", rw[3] == 1.0 && rw[4] == autobal_pendulum_crit_get(&s, 1) &&
                                                          rw[5] == autobal_pendulum_crit_get(&s, 2));
    CHECK("curves: R_m = 0.3: R_w2, R_w3 are NaN", rw[6] == 1.0 && isnan(rw[7]) && isnan(rw[8]));
    CHECK_STATUS("curves: bad R_m entry", autobal_pendulum_critical_curves(ws, 0.0, (double[]){0.1, 0.6}, 2, 3, rw),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... named with its index", autobal_pendulum_errmsg(ws), "R_m[1]");
  }
  CHECK_STATUS("critical_speeds: k = 2", autobal_pendulum_critical_speeds(ws, 0.1, 2.0, &s), AUTOBAL_EINVAL);
  CHECK_MSG("... names k", autobal_pendulum_errmsg(ws), "parameter k = 2");
  CHECK_STATUS("critical_speeds: R_m = 0.5", autobal_pendulum_critical_speeds(ws, 0.5, 0.5, &s), AUTOBAL_EINVAL);
  autobal_pendulum_workspace_free(ws);
}

/* relative error of a series against the numerical value */
static void test_series(void) {
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  autobal_pendulum_crit_set s0, s1;
  double Rm, prev2 = 0, prev3 = 0, prev17 = 0;
  int i;
  autobal_error err;
  printf("-- series (14), (17) and closed forms (16), (18)\n");
  for (i = 0, Rm = 0.004; i < 4; i++, Rm /= 2) {
    double r2, r3, r17, e2, e3, e17, s = cbrt(Rm);
    char what[160];
    autobal_pendulum_critical_speeds(ws, Rm, 0.0, &s0);
    autobal_pendulum_critical_speeds(ws, Rm, 1.0, &s1);
    autobal_pendulum_rw23_k0_series_small(Rm, &r2, &r3, NULL);
    autobal_pendulum_rw1_k1_series(Rm, &r17, NULL);
    e2 = r2 - autobal_pendulum_crit_get(&s0, 1);
    e3 = r3 - autobal_pendulum_crit_get(&s0, 2);
    e17 = r17 - autobal_pendulum_crit_get(&s1, 0);
    printf("   R_m = %-10g err (14) R_w2 %.3e, R_w3 %.3e, (17) %.3e\n", Rm, e2, e3, e17);
    snprintf(what, sizeof what, "(17) error / s^4 -> -407/3456 (next term, sympy), R_m = %g", Rm);
    CHECK_CLOSE(what, e17 / (s * s * s * s), 407.0 / 3456.0, 0.12, 0);
    if (i > 0) {
      CHECK_CLOSE("(14) R_w2 error ratio when R_m halves: O(R_m^3) -> 8", prev2 / e2, 8.0, 0.03, 0);
      /* next-order terms still matter here: the ratio falls 2.68, 2.64, 2.61 towards 2.52 */
      CHECK_CLOSE("(14) R_w3 error ratio when R_m halves: O(eps^4) -> 2^(4/3)", prev3 / e3, pow(2, 4.0 / 3), 0.08, 0);
      CHECK_CLOSE("(17) error ratio when R_m halves: O(s^4) -> 2^(4/3)", prev17 / e17, pow(2, 4.0 / 3), 0.06, 0);
    }
    prev2 = e2, prev3 = e3, prev17 = e17;
  }
  {
    double prev2l = 0, prev3l = 0, dq;
    for (i = 0, dq = 0.01; i < 4; i++, dq /= 2) {
      double r2, r3, e2, e3;
      Rm = 0.25 - dq; /* q = sqrt(dq/2) */
      autobal_pendulum_critical_speeds(ws, Rm, 0.0, &s0);
      autobal_pendulum_rw23_k0_series_large(Rm, &r2, &r3, NULL);
      e2 = fabs(r2 / autobal_pendulum_crit_get(&s0, 1) - 1);
      e3 = fabs(r3 / autobal_pendulum_crit_get(&s0, 2) - 1);
      printf("   R_m = %-10g rel err (14, large) R_w2 %.3e, R_w3 %.3e\n", Rm, e2, e3);
      if (i > 0) {
        /* relative error O(q^5), q^2 halves: ratio 2^(5/2) = 5.66 */
        CHECK("(14, large) R_w2 relative error ratio in [4.5, 7] (O(q^5): 5.66)", prev2l / e2 > 4.5 && prev2l / e2 < 7);
        CHECK("(14, large) R_w3 relative error ratio in [4.5, 7] (O(q^5): 5.66)", prev3l / e3 > 4.5 && prev3l / e3 < 7);
      }
      prev2l = e2, prev3l = e3;
    }
  }
  {
    double r1, u;
    autobal_pendulum_rw1_k0(0.3, &r1, NULL);
    CHECK("(13) returns 1", r1 == 1.0);
    autobal_pendulum_rw1_k1(0.1, &r1, &u, NULL);
    CHECK_CLOSE("(16): u solves R_m = (u^3/(1-2u^2))^2", pow(u * u * u / (1 - 2 * u * u), 2), 0.1, 1e-14, 0);
  }
  autobal_error_clear(&err);
  CHECK_STATUS("(18) R_m = 0.25 rejected", autobal_pendulum_rw23_k1(0.25, &Rm, &err), AUTOBAL_EINVAL);
  CHECK_MSG("... naming R_m", err.message, "R_m");
  CHECK_STATUS("(14 large) R_m = 0.3 rejected", autobal_pendulum_rw23_k0_series_large(0.3, &Rm, NULL, &err),
               AUTOBAL_EINVAL);
  CHECK_STATUS("(16) R_m = 0 rejected", autobal_pendulum_rw1_k1(0.0, &Rm, NULL, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("(17) R_m = NaN rejected", autobal_pendulum_rw1_k1_series(NAN, &Rm, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("(14 small) R_m = -1 rejected", autobal_pendulum_rw23_k0_series_small(-1, &Rm, NULL, &err),
               AUTOBAL_EINVAL);
  CHECK_STATUS("(13) R_m = 1 rejected", autobal_pendulum_rw1_k0(1, &Rm, &err), AUTOBAL_EINVAL);
  autobal_pendulum_workspace_free(ws);
}

static void test_damped(void) {
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  autobal_pendulum_params p;
  autobal_pendulum_crit_set s;
  autobal_pendulum_result r;
  size_t c;
  int bad = 0, i;
  printf("-- damped critical speeds, (8), (9)\n");
  /* (9): H >> 1, k = 1, h = 1, R_m = 0.1: stable iff 0.1 W^2 < W - 1 */
  {
    const double Hs[2] = {100.0, 1000.0};
    double lo9 = sqrt((1 - sqrt(0.6)) / 0.2), hi9 = sqrt((1 + sqrt(0.6)) / 0.2), e_prev = 0;
    for (i = 0; i < 2; i++) {
      double e;
      autobal_pendulum_params_from_k(0, 0.1, Hs[i], 1.0, 1.0, &p, NULL);
      CHECK_STATUS("damped critical speeds (H large)",
                   autobal_pendulum_critical_speeds_damped(ws, &p, 0.05, 5.0, 200, &s), AUTOBAL_SUCCESS);
      CHECK("two critical speeds: gained, lost",
            s.n == 2 && s.kind[0] == AUTOBAL_CRIT_GAINED && s.kind[1] == AUTOBAL_CRIT_LOST);
      e = fabs(s.R_w[0] - lo9) + fabs(s.R_w[1] - hi9);
      printf("   H = %g: (%.10g, %.10g) vs (9) (%.10g, %.10g)\n", Hs[i], s.R_w[0], s.R_w[1], lo9, hi9);
      if (i == 1) CHECK_CLOSE("(9): error shrinks like 1/H (ratio for H x10)", e_prev / e, 10.0, 0.1, 0);
      e_prev = e;
      for (c = 0; c < s.n; c++) {
        /* the root-based margin changes sign across each critical speed */
        autobal_pendulum_params q = p;
        double m_lo, m_hi;
        q.R_w = s.R_w[c] * (1 - 1e-8);
        autobal_pendulum_analyze(ws, &q, &r);
        m_lo = r.max_real;
        q.R_w = s.R_w[c] * (1 + 1e-8);
        autobal_pendulum_analyze(ws, &q, &r);
        m_hi = r.max_real;
        if (!((m_lo < 0) != (m_hi < 0))) bad++;
        if (s.kind[c] == AUTOBAL_CRIT_GAINED && !(m_hi < 0)) bad++;
      }
    }
    CHECK("max Re of roots changes sign across every damped critical speed (+-1e-8)", bad == 0);
    autobal_pendulum_params_from_k(1.3, 0.1, 1000, 1.0, 1.0, &p, NULL);
    autobal_pendulum_analyze(ws, &p, &r);
    CHECK("(9) applicable and agrees with the exact verdict inside (stable)",
          r.cond9.applicable && r.cond9.predicts_stable && r.verdict == AUTOBAL_VERDICT_STABLE);
    p.R_w = 3.2;
    autobal_pendulum_analyze(ws, &p, &r);
    CHECK("(9) agrees outside (unstable)", !r.cond9.predicts_stable && r.verdict == AUTOBAL_VERDICT_UNSTABLE);
  }
  /* (8): R_w >> 1: stable if h > H sqrt(R_m) (sharp at k = 1, sufficient for k < 1) */
  {
    double H = 1.0, Rm = 0.1, hs = H * sqrt(Rm);
    autobal_pendulum_params_from_k(1000, Rm, H, 1.05 * hs, 1.0, &p, NULL);
    autobal_pendulum_analyze(ws, &p, &r);
    CHECK("(8), R_w = 1000, k = 1, h = 1.05 H sqrt(R_m): stable, predicted",
          r.cond8.applicable && r.cond8.predicts_stable && r.verdict == AUTOBAL_VERDICT_STABLE);
    p.h = 0.95 * hs;
    autobal_pendulum_analyze(ws, &p, &r);
    CHECK("(8), k = 1, h = 0.95 H sqrt(R_m): unstable, predicted not stable",
          !r.cond8.predicts_stable && r.verdict == AUTOBAL_VERDICT_UNSTABLE);
    for (i = 0; i < 5; i++) {
      autobal_pendulum_params_from_k(1000, Rm, H, 1.05 * hs, 0.2 * i, &p, NULL);
      autobal_pendulum_analyze(ws, &p, &r);
      if (r.verdict != AUTOBAL_VERDICT_STABLE) bad++;
    }
    CHECK("(8) sufficient for k = 0, 0.2, ..., 0.8", bad == 0);
  }
  CHECK_STATUS("damped: rw_max <= rw_min", autobal_pendulum_critical_speeds_damped(ws, &p, 2.0, 1.0, 10, &s),
               AUTOBAL_EINVAL);
  CHECK_MSG("... names rw_max", autobal_pendulum_errmsg(ws), "rw_max");
  CHECK_STATUS("damped: n_sweep = 1", autobal_pendulum_critical_speeds_damped(ws, &p, 0.0, 1.0, 1, &s),
               AUTOBAL_EINVAL);
  CHECK_MSG("... names n_sweep", autobal_pendulum_errmsg(ws), "n_sweep");
  p.h = -1;
  CHECK_STATUS("damped: h < 0", autobal_pendulum_critical_speeds_damped(ws, &p, 0.0, 1.0, 10, &s), AUTOBAL_EINVAL);
  CHECK_MSG("... names h", autobal_pendulum_errmsg(ws), "parameter h");
  autobal_pendulum_workspace_free(ws);
}

static void test_map(void) {
  enum { NM = 40, NW = 60 };
  double R_m[NM], R_w[NW], mr1[NM * NW], mr2[NM * NW];
  signed char v1[NM * NW], v2[NM * NW];
  autobal_pendulum_map_spec sp;
  autobal_error err;
  size_t i, j;
  int bad = 0;
  printf("-- stability maps\n");
  for (i = 0; i < NM; i++) R_m[i] = 0.01 + 0.47 * (double)i / (NM - 1);
  for (j = 0; j < NW; j++) R_w[j] = 0.2 + 5.0 * (double)j / (NW - 1);
  memset(&sp, 0, sizeof sp);
  sp.R_m = R_m, sp.n_Rm = NM, sp.R_w = R_w, sp.n_Rw = NW, sp.H = 0.05, sp.h = 0.1;
  sp.k = (double[]){0.0, 0.5, 1.0};
  sp.n_k = 3;
  sp.n_threads = 1;
  CHECK_STATUS("damped map, serial", autobal_pendulum_map(&sp, v1, mr1, NULL), AUTOBAL_SUCCESS);
  sp.n_threads = 2;
  CHECK_STATUS("damped map, 2 threads", autobal_pendulum_map(&sp, v2, mr2, NULL), AUTOBAL_SUCCESS);
  CHECK("serial == OpenMP (verdicts, bitwise)", memcmp(v1, v2, sizeof v1) == 0);
  CHECK("serial == OpenMP (max Re, bitwise)", memcmp(mr1, mr2, sizeof mr1) == 0);
  for (i = 0; i < NM; i += 7)
    for (j = 0; j < NW; j += 5) {
      int worst = 1, t;
      for (t = 0; t < 3; t++) {
        autobal_pendulum_params p;
        int v;
        autobal_pendulum_params_from_k(R_w[j], R_m[i], 0.05, 0.1, sp.k[t], &p, NULL);
        autobal_pendulum_verdict(&p, &v, NULL, NULL);
        if (v < worst) worst = v;
      }
      if (worst != v1[i * NW + j]) bad++;
      if (v1[i * NW + j] == AUTOBAL_VERDICT_STABLE && !(mr1[i * NW + j] < 0)) bad++;
    }
  CHECK("map entries == worst verdict over k, stable entries have max Re < 0", bad == 0);
  /* undamped, every unbalance (default 65 k): regions A and B */
  {
    autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
    autobal_pendulum_crit_set s;
    double rm3[3] = {0.02, 0.1, 0.2}, rwA[3], rwB[3], rwU[3], r2, r3, g1;
    signed char va[9];
    for (i = 0; i < 3; i++) {
      autobal_pendulum_critical_speeds(ws, rm3[i], 0.0, &s);
      r2 = autobal_pendulum_crit_get(&s, 1);
      r3 = autobal_pendulum_crit_get(&s, 2);
      autobal_pendulum_rw1_k1(rm3[i], &g1, NULL, NULL);
      rwA[i] = 1.05 * r3;
      rwB[i] = g1 < r2 ? 0.5 * (g1 + r2) : NAN;
      rwU[i] = 0.5 * (r2 + r3);
    }
    memset(&sp, 0, sizeof sp);
    sp.n_threads = 2;
    sp.n_Rm = 1, sp.n_Rw = 3;
    for (i = 0; i < 3; i++) {
      double rw3[3];
      rw3[0] = rwA[i], rw3[1] = isnan(rwB[i]) ? rwA[i] : rwB[i], rw3[2] = rwU[i];
      sp.R_m = &rm3[i];
      sp.R_w = rw3;
      autobal_pendulum_map(&sp, va + 3 * i, NULL, NULL);
    }
    CHECK("region A: 1.05 R_w3(R_m, 0) stable for every k (R_m = 0.02, 0.1, 0.2)",
          va[0] == 1 && va[3] == 1 && va[6] == 1);
    CHECK("region B: between R_w1(R_m, 1) and R_w2(R_m, 0) stable for every k (R_m = 0.2)",
          !isnan(rwB[2]) && va[7] == 1);
    CHECK("between R_w2(R_m, 0) and R_w3(R_m, 0): unstable (k = 0 is)", va[2] == -1 && va[5] == -1 && va[8] == -1);
    autobal_pendulum_workspace_free(ws);
  }
  autobal_error_clear(&err);
  memset(&sp, 0, sizeof sp);
  sp.R_m = R_m, sp.n_Rm = NM, sp.R_w = R_w, sp.n_Rw = NW;
  sp.k = (double[]){0.5, 1.5};
  sp.n_k = 2;
  CHECK_STATUS("map: k = 1.5 rejected", autobal_pendulum_map(&sp, v1, NULL, &err), AUTOBAL_EINVAL);
  CHECK_MSG("... named k[1]", err.message, "k[1]");
  sp.k = NULL, sp.n_k = 0;
  R_m[3] = 0.5;
  CHECK_STATUS("map: R_m[3] = 0.5 rejected", autobal_pendulum_map(&sp, v1, NULL, &err), AUTOBAL_EINVAL);
  CHECK_MSG("... named R_m[3]", err.message, "R_m[3]");
  R_m[3] = 0.1;
  sp.h = -1;
  CHECK_STATUS("map: h < 0 rejected", autobal_pendulum_map(&sp, v1, NULL, &err), AUTOBAL_EINVAL);
  sp.h = 0;
  sp.n_threads = -2;
  CHECK_STATUS("map: n_threads < 0 rejected", autobal_pendulum_map(&sp, v1, NULL, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("map: NULL output", autobal_pendulum_map(&sp, NULL, NULL, &err), AUTOBAL_EINVAL);
}

/* Test hook in src/analysis/pendulum_critical.c (not in the API): the damped search with the capacity of its
 * list lowered to cap, to reach the truncation path with the few changes the model has. */
int autobal_pendulum_critical_speeds_damped_cap_(autobal_pendulum_workspace *ws,
                                                 const autobal_pendulum_params *p, double rw_min,
                                                 double rw_max, size_t n_sweep, size_t cap,
                                                 autobal_pendulum_crit_set *out);

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static void test_damped_truncation(void) {
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  autobal_pendulum_params p;
  autobal_pendulum_crit_set full, s;
  int st;
  printf("-- damped critical speeds: a full list is reported (capacity lowered for the test)\n");
  /* (9) regime: H = 100, k = 1, h = 1, R_m = 0.1: gained at the lower end of the window of (9),
   * lost at the upper end (two changes) */
  autobal_pendulum_params_from_k(0, 0.1, 100.0, 1.0, 1.0, &p, NULL);
  st = autobal_pendulum_critical_speeds_damped(ws, &p, 0.05, 5.0, 200, &full);
  CHECK_STATUS("full capacity: success", st, AUTOBAL_SUCCESS);
  CHECK("not truncated (flag 0), two changes gained/lost, one stable interval",
        full.truncated == 0 && full.n == 2 && full.kind[0] == AUTOBAL_CRIT_GAINED &&
            full.kind[1] == AUTOBAL_CRIT_LOST && full.n_stable == 1);
  CHECK("message empty after success", autobal_pendulum_errmsg(ws)[0] == '\0');
  st = autobal_pendulum_critical_speeds_damped_cap_(ws, &p, 0.05, 5.0, 200, 2, &s);
  CHECK("capacity = number of changes: success, not truncated, identical",
        st == AUTOBAL_SUCCESS && s.truncated == 0 && s.n == 2 && same_bits(s.R_w[0], full.R_w[0]) &&
            same_bits(s.R_w[1], full.R_w[1]) && s.n_stable == 1 && same_bits(s.stable_hi[0], full.stable_hi[0]));
  st = autobal_pendulum_critical_speeds_damped_cap_(ws, &p, 0.05, 5.0, 200, 1, &s);
  CHECK_STATUS("capacity 1 < 2 changes: AUTOBAL_WARNING", st, AUTOBAL_WARNING);
  CHECK_STATUS("... recorded in the workspace", autobal_pendulum_status(ws), AUTOBAL_WARNING);
  CHECK("truncated = 1, the first change kept (bitwise)", s.truncated == 1 && s.n == 1 &&
        s.kind[0] == AUTOBAL_CRIT_GAINED && same_bits(s.R_w[0], full.R_w[0]));
  CHECK("the stable interval beginning at the last kept change is not extended (not listed)", s.n_stable == 0);
  CHECK_MSG("message names the capacity", autobal_pendulum_errmsg(ws), "more than 1 stability changes");
  CHECK_MSG("message says what to do", autobal_pendulum_errmsg(ws), "Narrow the range");
  /* k = 0, R_m = 0.2, light damping: gained near R_w1 = 1 (13), lost near R_w2, gained near R_w3 */
  autobal_pendulum_params_from_k(0, 0.2, 1e-3, 1e-3, 0.0, &p, NULL);
  st = autobal_pendulum_critical_speeds_damped(ws, &p, 0.0, 10.0, 2000, &full);
  CHECK("k = 0, R_m = 0.2: success, three changes gained/lost/gained, not truncated",
        st == AUTOBAL_SUCCESS && full.truncated == 0 && full.n == 3 && full.kind[0] == AUTOBAL_CRIT_GAINED &&
            full.kind[1] == AUTOBAL_CRIT_LOST && full.kind[2] == AUTOBAL_CRIT_GAINED && full.n_stable == 2 &&
            full.stable_hi[1] == 10.0);
  if (full.n == 3) CHECK_CLOSE("first change near R_w1 = 1 of (13) (light damping)", full.R_w[0], 1.0, 1e-2, 0);
  st = autobal_pendulum_critical_speeds_damped_cap_(ws, &p, 0.0, 10.0, 2000, 2, &s);
  CHECK_STATUS("capacity 2 < 3 changes: AUTOBAL_WARNING", st, AUTOBAL_WARNING);
  CHECK("the closed stable interval [R_w(0), R_w(1)] is kept, nothing beyond R_w(1)",
        s.truncated == 1 && s.n == 2 && s.n_stable == 1 && same_bits(s.stable_lo[0], full.R_w[0]) &&
            same_bits(s.stable_hi[0], full.R_w[1]));
  CHECK_STATUS("capacity 0 rejected", autobal_pendulum_critical_speeds_damped_cap_(ws, &p, 0.0, 10.0, 20, 0, &s), AUTOBAL_EINVAL);
  CHECK_STATUS("capacity above AUTOBAL_PENDULUM_MAX_CRIT rejected",
               autobal_pendulum_critical_speeds_damped_cap_(ws, &p, 0.0, 10.0, 20, AUTOBAL_PENDULUM_MAX_CRIT + 1, &s),
               AUTOBAL_EINVAL);
  /* the undamped search never truncates: its flag is 0 */
  CHECK("undamped critical speeds: flag 0",
        autobal_pendulum_critical_speeds(ws, 0.2, 1.0, &s) == AUTOBAL_SUCCESS && s.truncated == 0);
  autobal_pendulum_workspace_free(ws);
}

int main(void) {
  gsl_set_error_handler_off();
  test_params();
  test_char_poly();
  test_analyze();
  test_undamped();
  test_critical();
  test_series();
  test_damped();
  test_damped_truncation();
  test_map();
  return check_summary();
}
