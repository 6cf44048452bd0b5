/* pendulum_verdict.h: the pendulum analysis' workspace layout, its Routh kernel on lanes of
 * polynomials (static inline, shared with the maps for bitwise equal verdicts) and the
 * internal functions of pendulum_verdict.c (not installed).  Included by pendulum_verdict.c,
 * pendulum_critical.c and pendulum_map.c; includes the model's pendulum_internal.h only. */
#ifndef AUTOBAL_PENDULUM_VERDICT_H
#define AUTOBAL_PENDULUM_VERDICT_H

#include "autobal/pendulum.h"
#include "autobal/stability.h"
#include "internal.h"
#include "models/pendulum/pendulum_internal.h"


#define PEND_MAXDEG 12

struct autobal_pendulum_workspace {
  autobal_poly_workspace *pw[PEND_MAXDEG + 1]; /* roots of degree d = 1..12 */
  autobal_eigen_workspace *ew;
  autobal_error err;
  autobal_pendulum_cancel_fn cancel; /* autobal_pendulum_workspace_set_cancel (NULL: none) */
  void *cancel_user;
};

/* Non-zero (status AUTOBAL_ECANCELLED and "cancelled by the caller" in ws->err) when the
 * workspace's cancel hook asks to stop. */
int autobal_pendulum_cancelled_(autobal_pendulum_workspace *ws);

#define MAP_MAXW 5 /* width of the Routh array for degree <= 8 */
/* full unrolling of the short fixed loops of the Routh kernel (GCC >= 8) */
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 8
#define MAP_UNROLL _Pragma("GCC unroll 16")
#else
#define MAP_UNROLL
#endif

/* ---- the Routh test on MAP_LANES polynomials at once -------------------- */

/* The map decides with exactly the verdicts of autobal_poly_hurwitz_err (the
 * Routh array with a running error bound per entry), in two stages:
 *
 * 1. autobal_pendulum_routh_lanes_: the Routh array of MAP_LANES polynomials of degree n (7 or
 *    8, positive leading coefficient) side by side, with the values of
 *    autobal_poly_hurwitz_err operation for operation (so the first-column
 *    entries are bitwise the same), but instead of one error bound per entry
 *    two per row: with weights s2^-j on column j (s2 = max(1, W), the scale
 *    of lambda^2, which makes the entries of a row comparable), G_t >= the
 *    weighted sum of the bounds of the entries j >= 1 of row t, and F_t >=
 *    the bound of its first entry; N_t = the weighted sum of |entries j >= 1|
 *    (sums, no comparisons: they vectorize); from the test's recurrence
 *      F_{t+1} = G_{t+1} = s2 (G_{t-1} + |q| G_t + N_t eq + u (N_{t-1} + 2|q| N_t)),
 *    eq = (F_{t-1} + |q| F_t)/|a| + u|q|.  About a third of the work.
 * 2. a lane whose first-column entries all clear twice their row bound
 *    (|a| > 2 F_t, up to the first negative one) has the verdict of the full
 *    test, since there |a| > e_t too (the factor 2 covers the rounding of the
 *    bounds themselves); any other lane (an entry within 2 F_t of zero: near
 *    a stability boundary, rare) is decided by the full scalar test
 *    autobal_poly_hurwitz_err.
 * Rows of the generic test beyond len(t) = (n - t)/2 + 1 entries are
 * structural zeros, which never reach the first column of rows <= n (entry
 * j of row t+1 depends on entries j+1 of rows t and t-1): not computed.
 * The lanes give the processor independent work (the divisions are the
 * critical path of one array) and vectorize. */
static MAP_INLINE void autobal_pendulum_routh_lanes_(size_t n, const mvec *c, const mvec *ce,
                                                     const mvec *s2p, mvec *col, mvec *colU) {
  /* per row t: b[.][j] the entries, F the bound of entry 0, G >= the
   * weighted sum of the bounds of entries j >= 1, N = the weighted sum of
   * |entries j >= 1| (entries j >= 1 are the ones that enter the next rows
   * as x and y; entry 0 enters only through q) */
  mvec b[3][MAP_MAXW], F[3], G[3], N[3], w[MAP_MAXW];
  const double u = DBL_EPSILON;
  mvec s2 = *s2p, is2 = 1.0 / s2, zero = MV_BCAST(0.0), ez;
  size_t j, row, i0 = 0, i1 = 1, i2 = 2;
  w[0] = MV_BCAST(1.0);
  for (j = 1; j < MAP_MAXW; j++) w[j] = w[j - 1] * is2;
  G[0] = N[0] = G[1] = N[1] = zero;
  MAP_UNROLL
  for (j = 0; 2 * j <= n; j++) {
    mvec v = c[n - 2 * j], av = MV_ABS(v), ev = ce[n - 2 * j] + u * av;
    b[0][j] = v;
    if (j == 0) F[0] = ev;
    else G[0] = G[0] + ev * w[j], N[0] = N[0] + av * w[j];
  }
  MAP_UNROLL
  for (j = 0; 2 * j + 1 <= n; j++) {
    mvec v = c[n - 2 * j - 1], av = MV_ABS(v), ev = ce[n - 2 * j - 1] + u * av;
    b[1][j] = v;
    if (j == 0) F[1] = ev;
    else G[1] = G[1] + ev * w[j], N[1] = N[1] + av * w[j];
  }
  /* The single entry of row n is the lowest coefficient c[0], copied down
   * from row n mod 2 two rows at a time (as x - q*0 = x); the full test's
   * bound of it grows only by u|c[0]| per copy.  That bound, bitwise the
   * full test's, replaces the row bound there (which would be far too wide
   * when c[0] is small, e.g. for small k). */
  ez = ce[0] + u * MV_ABS(c[0]);
  for (row = n % 2 + 2; row <= n; row += 2) ez = ez + u * MV_ABS(c[0]);
  MAP_UNROLL
  for (row = 1; row <= n; row++) {
    /* rows row-1 (i0) and row (i1) give row+1 (i2): entry j from entries
     * j+1 (weight s2 w_{j+1} = w_j), so the weighted sum of the new bounds
     * is at most s2 (G0 + |q| G1 + N1 eq + u (N0 + 2|q| N1)) */
    size_t len1 = (n - row) / 2 + 1, len2 = row < n ? (n - row - 1) / 2 + 1 : 0;
    mvec a = b[i1][0], q, fq, eq, t;
    col[row] = a;
    colU[row] = row < n ? F[i1] : ez;
    if (row == n) break;
    q = b[i0][0] / a;
    fq = MV_ABS(q);
    eq = (F[i0] + fq * F[i1]) / MV_ABS(a) + u * fq;
    t = s2 * (G[i0] + fq * G[i1] + N[i1] * eq + u * (N[i0] + 2.0 * fq * N[i1]));
    F[i2] = t;
    G[i2] = t;
    N[i2] = zero;
    MAP_UNROLL
    for (j = 0; j < len2; j++) { /* j + 1 < len(row - 1) = len2 + 1 always */
      mvec x = b[i0][j + 1], y = j + 1 < len1 ? b[i1][j + 1] : zero;
      mvec v = x - q * y;
      b[i2][j] = v;
      if (j > 0) N[i2] = N[i2] + MV_ABS(v) * w[j];
    }
    {
      size_t tmp = i0;
      i0 = i1, i1 = i2, i2 = tmp;
    }
  }
}

/* the two degrees used, with n a compile-time constant (full unrolling) */
static MAP_INLINE void autobal_pendulum_routh_lanes7_(const mvec *c, const mvec *ce, const mvec *s2,
                                                      mvec *col, mvec *colU) {
  autobal_pendulum_routh_lanes_(7, c, ce, s2, col, colU);
}
static MAP_INLINE void autobal_pendulum_routh_lanes8_(const mvec *c, const mvec *ce, const mvec *s2,
                                                      mvec *col, mvec *colU) {
  autobal_pendulum_routh_lanes_(8, c, ce, s2, col, colU);
}

/* Sign test of (6) (coef, cerr from the kernel; deflate: k == 0, lambda = 0 divided out)
 * with the two-stage Routh kernel: the verdict and count of autobal_poly_hurwitz_err. */
int autobal_pendulum_sign_test_poly_(const double coef[9], const double cerr[9], double W,
                                     int deflate, int *verdict, int *n_rhp, autobal_error *err);
/* Sign-test verdict of (6) from raw values (no validation) for given k, kc. */
int autobal_pendulum_damped_verdict_k_(double R_w, double R_m, double H, double h, double k,
                                       double kc, int *verdict, int *n_rhp, autobal_error *err);
/* The 16 terms of the discriminant of a x^4 + b x^3 + c x^2 + d x + e: coefficient and
 * exponents of (a, b, c, d, e) (defined in pendulum_verdict.c). */
typedef struct {
  int coef;
  int ex[5];
} autobal_pendulum_disc_term_;
extern const autobal_pendulum_disc_term_ autobal_pendulum_quartic_disc_[16];
/* Coefficients c_j(W) of P(x) of (10) at a given W, long double. */
void autobal_pendulum_undamped_coefs_ld_(long double Rm, long double W, long double k,
                                         long double c[5]);
/* Discriminant of the quartic c (and the magnitude of its terms). */
void autobal_pendulum_quartic_disc_ld_(const long double c[5], long double *disc, long double *mag);
/* The auxiliary quantities P8, D4 of the quartic c (sure: their signs are certain). */
void autobal_pendulum_quartic_aux_ld_(const long double c[5], long double *P8, long double *D4,
                                      int *sure);
/* Verdict of the undamped system (10) at (Rm, W = R_w^2, k) in long double (sure may be NULL). */
int autobal_pendulum_undamped_verdict_ld_(long double Rm, long double W, long double k, int *sure);
/* The undamped verdict at (R_m, R_w, k) decided: the long double test where its bounds decide,
 * else exact (integers, GMP); MARGINAL only exactly on a boundary. */
int autobal_pendulum_undamped_verdict_exact_(double R_m, double R_w, double k);
/* Verdict of autobal_pendulum_verdict / autobal_pendulum_analyze when H = h = 0: that of
 * autobal_pendulum_undamped_verdict_exact_ with R_w = 0 and (k = 0) R_w = 1, where lambda = 0
 * is not semisimple, UNSTABLE; if n_rhp != NULL, the number of roots of (6) with Re > 0 (no
 * validation). */
int autobal_pendulum_undamped_semisimple_(double R_m, double R_w, double k, int *n_rhp);
/* Range checks of R_m in (0, 0.5) and k in [0, 1]. */
int autobal_pendulum_check_rm_k_(double R_m, double k, autobal_error *err);

#endif
