/* test_stability.c: the model-agnostic stability tools (stability.h, src/numerics/).
 * Known answers: products and roots of polynomials built from known factors,
 * eigenvalues of block-triangular matrices, a brute-force assignment, the
 * Routh-Hurwitz count against roots, Sturm counts against roots, Brent on
 * functions with known zeros (cbrt 2, the Dottie number). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/stability.h"
#include "check.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* deterministic uniform [0, 1) (xorshift64*) */
static unsigned long long rng_state = 0x9E3779B97F4A7C15ULL;
static double urand(void) {
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return (double)((rng_state * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

/* build a real polynomial from real roots r[] and complex pairs (pr +- i pi) */
static size_t poly_from_roots(const double *r, size_t nr, const double *pr, const double *pim,
                              size_t np, double lead, double *out) {
  double a[AUTOBAL_POLY_MAXLEN], t[AUTOBAL_POLY_MAXLEN];
  size_t len = 1, i;
  a[0] = lead;
  for (i = 0; i < nr; i++) {
    double f[2] = {-r[i], 1.0};
    autobal_poly_mul(a, len, f, 2, t, len + 1, NULL);
    len++;
    memcpy(a, t, len * sizeof(double));
  }
  for (i = 0; i < np; i++) {
    double f[3] = {pr[i] * pr[i] + pim[i] * pim[i], -2.0 * pr[i], 1.0};
    autobal_poly_mul(a, len, f, 3, t, len + 2, NULL);
    len += 2;
    memcpy(a, t, len * sizeof(double));
  }
  memcpy(out, a, len * sizeof(double));
  return len;
}

static int f_cubic(double x, void *ctx, double *fx) {
  (void)ctx;
  *fx = x * x * x - 2.0;
  return AUTOBAL_SUCCESS;
}
static int f_dottie(double x, void *ctx, double *fx) {
  (void)ctx;
  *fx = cos(x) - x;
  return AUTOBAL_SUCCESS;
}
static int f_fail(double x, void *ctx, double *fx) {
  (void)ctx;
  *fx = x;
  return x > 0.5 ? AUTOBAL_ERHS : AUTOBAL_SUCCESS;
}
static int p_above_sqrt2(double x, void *ctx, int *v) {
  (void)ctx;
  *v = x * x > 2.0;
  return AUTOBAL_SUCCESS;
}

static void test_arithmetic(void) {
  autobal_error err;
  double a[2] = {1, 1}, b[2] = {1, -1}, out[4], d[3];
  double ca[4] = {0, 1, 1, 0}; /* i + x */
  double cb[4], cc[6], re, im, mi, rp[3];
  printf("-- real and complex arithmetic\n");
  CHECK_STATUS("mul (1+x)(1-x)", autobal_poly_mul(a, 2, b, 2, out, 4, NULL), AUTOBAL_SUCCESS);
  CHECK("(1+x)(1-x) = 1 - x^2 (extra entry zeroed)",
        out[0] == 1 && out[1] == 0 && out[2] == -1 && out[3] == 0);
  CHECK_CLOSE("eval 1 - x^2 at 3", autobal_poly_eval(out, 3, 3.0), -8.0, 0, 0);
  autobal_poly_eval_complex(out, 3, 0.0, 2.0, &re, &im); /* 1 - (2i)^2 = 5 */
  CHECK("eval 1 - x^2 at 2i = 5", re == 5.0 && im == 0.0);
  CHECK("degree of 1 - x^2 + 0 x^3 is 2", autobal_poly_degree(out, 4) == 2);
  CHECK_STATUS("deriv", autobal_poly_deriv(out, 3, d, 2, NULL), AUTOBAL_SUCCESS);
  CHECK("d/dx (1 - x^2) = -2x", d[0] == 0 && d[1] == -2);
  CHECK_STATUS("axpby", autobal_poly_axpby(2.0, a, 2, 3.0, out, 3, d, 3, NULL), AUTOBAL_SUCCESS);
  CHECK("2(1+x) + 3(1-x^2) = 5 + 2x - 3x^2", d[0] == 5 && d[1] == 2 && d[2] == -3);
  autobal_error_clear(&err);
  CHECK_STATUS("mul: outlen too small", autobal_poly_mul(a, 2, b, 2, out, 2, &err), AUTOBAL_EINVAL);
  CHECK_MSG("mul: message names outlen", err.message, "outlen");
  CHECK_STATUS("axpby: outlen too small", autobal_poly_axpby(1, a, 2, 1, out, 3, d, 2, &err),
               AUTOBAL_EINVAL);
  CHECK_STATUS("deriv: outlen too small", autobal_poly_deriv(out, 3, d, 1, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("mul: empty", autobal_poly_mul(a, 0, b, 2, out, 4, &err), AUTOBAL_EINVAL);
  /* (x + i)(x - i) = x^2 + 1 */
  autobal_cpoly_conj(ca, 2, cb);
  CHECK("conj(x + i) = x - i", cb[0] == 0 && cb[1] == -1 && cb[2] == 1 && cb[3] == 0);
  CHECK_STATUS("cmul", autobal_cpoly_mul(ca, 2, cb, 2, cc, 3, NULL), AUTOBAL_SUCCESS);
  autobal_cpoly_real_part(cc, 3, rp, &mi);
  CHECK("(x+i)(x-i) = 1 + x^2, imaginary part 0",
        rp[0] == 1 && rp[1] == 0 && rp[2] == 1 && mi == 0.0);
  autobal_cpoly_eval(ca, 2, 1.0, 2.0, &re, &im); /* (1+2i) + i */
  CHECK("eval x + i at 1 + 2i = 1 + 3i", re == 1.0 && im == 3.0);
  /* (1+i)(x+i) + 2 (x - i) */
  CHECK_STATUS("caxpby", autobal_cpoly_axpby(1, 1, ca, 2, 2, 0, cb, 2, cc, 2, NULL),
               AUTOBAL_SUCCESS);
  CHECK("(1+i)(x+i) + 2(x-i) = (-1-i) + (3+i) x",
        cc[0] == -1 && cc[1] == -1 && cc[2] == 3 && cc[3] == 1);
  CHECK_STATUS("cmul: outlen too small", autobal_cpoly_mul(ca, 2, cb, 2, cc, 2, &err),
               AUTOBAL_EINVAL);
  CHECK_STATUS("caxpby: outlen too small", autobal_cpoly_axpby(1, 0, ca, 2, 1, 0, cb, 2, cc, 1, &err),
               AUTOBAL_EINVAL);
}

static void test_roots_eigen(void) {
  double r[3] = {1, 2, 3}, pr[1] = {-0.5}, pim[1] = {2.0}, c[AUTOBAL_POLY_MAXLEN];
  double re[8], im[8], wre[8], wim[8], md, A[64];
  size_t len, i, j, perm[8];
  autobal_poly_workspace *w;
  autobal_eigen_workspace *ew;
  autobal_error err;
  printf("-- roots (GSL) and eigenvalues (GSL)\n");
  len = poly_from_roots(r, 3, pr, pim, 1, 2.5, c); /* degree 5 */
  w = autobal_poly_workspace_alloc(5);
  CHECK("poly workspace allocated", w != NULL && autobal_poly_workspace_degree(w) == 5);
  CHECK_STATUS("roots of 2.5 (x-1)(x-2)(x-3)(x^2+x+4.25)", autobal_poly_roots(w, c, len, re, im, NULL),
               AUTOBAL_SUCCESS);
  wre[0] = -0.5, wim[0] = -2.0, wre[1] = -0.5, wim[1] = 2.0;
  wre[2] = 1, wre[3] = 2, wre[4] = 3, wim[2] = wim[3] = wim[4] = 0;
  for (i = 0; i < 5; i++) {
    CHECK_CLOSE("root re (sorted by Re then Im)", re[i], wre[i], 1e-12, 1e-12);
    CHECK_CLOSE("root im", im[i], wim[i], 1e-12, 1e-12);
  }
  autobal_error_clear(&err);
  CHECK_STATUS("roots: wrong length", autobal_poly_roots(w, c, 5, re, im, &err), AUTOBAL_EINVAL);
  CHECK_MSG("roots: message names len", err.message, "len");
  c[5] = 0.0;
  CHECK_STATUS("roots: zero leading coefficient", autobal_poly_roots(w, c, 6, re, im, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("roots: message says leading", err.message, "leading");
  c[5] = 2.5;
  c[2] = NAN;
  CHECK_STATUS("roots: NaN coefficient", autobal_poly_roots(w, c, 6, re, im, &err), AUTOBAL_EINVAL);
  CHECK_MSG("roots: message names c[2]", err.message, "c[2]");
  autobal_poly_workspace_free(w);
  autobal_poly_workspace_free(NULL);
  CHECK("degree-0 workspace refused", autobal_poly_workspace_alloc(0) == NULL);

  /* eigenvalues of an upper block-triangular 5x5: blocks [[a, b], [-b, a]]
   * (eigenvalues a +- ib), then diag 4, -7, 0.5; random upper part */
  ew = autobal_eigen_workspace_alloc(5);
  CHECK("eigen workspace allocated", ew != NULL && autobal_eigen_workspace_size(ew) == 5);
  for (i = 0; i < 25; i++) A[i] = 0.0;
  for (i = 0; i < 5; i++)
    for (j = i + 1; j < 5; j++) A[5 * i + j] = urand() - 0.5;
  A[0] = -0.3, A[1] = 1.7, A[5] = -1.7, A[6] = -0.3;
  A[12] = 4.0, A[18] = -7.0, A[24] = 0.5;
  CHECK_STATUS("eigenvalues of block-triangular matrix", autobal_eigen_nonsymm(ew, A, re, im, NULL),
               AUTOBAL_SUCCESS);
  wre[0] = -7, wim[0] = 0, wre[1] = -0.3, wim[1] = -1.7, wre[2] = -0.3, wim[2] = 1.7;
  wre[3] = 0.5, wim[3] = 0, wre[4] = 4, wim[4] = 0;
  CHECK_STATUS("match", autobal_match_roots(5, re, im, wre, wim, perm, &md, NULL), AUTOBAL_SUCCESS);
  CHECK_CLOSE("eigenvalues vs diagonal blocks: max distance", md, 0.0, 0, 1e-12);
  A[7] = INFINITY;
  autobal_error_clear(&err);
  CHECK_STATUS("eigen: inf entry", autobal_eigen_nonsymm(ew, A, re, im, &err), AUTOBAL_EINVAL);
  CHECK_MSG("eigen: message names the entry", err.message, "(1, 2)");
  autobal_eigen_workspace_free(ew);
  autobal_eigen_workspace_free(NULL);

  /* companion matrix eigenvalues == polynomial roots (two GSL paths) */
  {
    double worst = 0.0;
    int t;
    autobal_poly_workspace *w8 = autobal_poly_workspace_alloc(8);
    autobal_eigen_workspace *e8 = autobal_eigen_workspace_alloc(8);
    for (t = 0; t < 50; t++) {
      double cc[9], er[8], ei[8];
      for (i = 0; i < 9; i++) cc[i] = urand() * 2 - 1;
      cc[8] = 1.0 + urand();
      for (i = 0; i < 64; i++) A[i] = 0.0;
      for (i = 0; i < 7; i++) A[8 * (i + 1) + i] = 1.0;
      for (i = 0; i < 8; i++) A[8 * i + 7] = -cc[i] / cc[8];
      autobal_poly_roots(w8, cc, 9, re, im, NULL);
      autobal_eigen_nonsymm(e8, A, er, ei, NULL);
      autobal_match_roots(8, re, im, er, ei, NULL, &md, NULL);
      if (md > worst) worst = md;
    }
    CHECK_CLOSE("50 random degree-8: roots vs companion eigenvalues, max distance", worst, 0, 0,
                1e-6);
    autobal_poly_workspace_free(w8);
    autobal_eigen_workspace_free(e8);
  }
}

/* brute force: min over permutations of max |a_i - b_p(i)| */
static double brute_bottleneck(size_t n, const double *ar, const double *ai, const double *br,
                               const double *bi, size_t *p, size_t k, int *used, double cur) {
  size_t j;
  double best = INFINITY;
  if (k == n) return cur;
  for (j = 0; j < n; j++) {
    double d, v;
    if (used[j]) continue;
    d = hypot(ar[k] - br[j], ai[k] - bi[j]);
    used[j] = 1;
    p[k] = j;
    v = brute_bottleneck(n, ar, ai, br, bi, p, k + 1, used, d > cur ? d : cur);
    used[j] = 0;
    if (v < best) best = v;
  }
  return best;
}

/* first-order error bounds for a simple root r of c (len coefficients):
 * componentwise condition sum |c_j| |r|^j / |r p'(r)| (Aberth: backward
 * error ~ n eps in every coefficient) and normwise condition
 * ||c||_1 sum |r|^j / |r p'(r)| (companion QR: backward error ~ eps ||c||) */
static void root_conditions(const double *c, size_t len, double rr, double ri, double *kc,
                            double *kn) {
  double dr, di, ar = hypot(rr, ri), sa = 0.0, sp = 0.0, cn = 0.0, d[AUTOBAL_POLY_MAXLEN];
  size_t j;
  for (j = 0; j < len; j++) {
    sa += fabs(c[j]) * pow(ar, (double)j);
    sp += pow(ar, (double)j);
    cn += fabs(c[j]);
  }
  autobal_poly_deriv(c, len, d, len - 1, NULL);
  autobal_poly_eval_complex(d, len - 1, rr, ri, &dr, &di);
  *kc = sa / (ar * hypot(dr, di));
  *kn = cn * sp / (ar * hypot(dr, di));
}

/* every root with Im != 0 has its exact mirror image; count real roots */
static int exact_pairs(size_t n, const double *re, const double *im, size_t *nreal) {
  size_t i, j;
  *nreal = 0;
  for (i = 0; i < n; i++) {
    int found = 0;
    if (im[i] == 0.0) {
      (*nreal)++;
      continue;
    }
    for (j = 0; j < n; j++)
      if (j != i && re[j] == re[i] && im[j] == -im[i]) found = 1;
    if (!found) return 0;
  }
  return 1;
}

typedef int (*roots_fn)(autobal_poly_workspace *, const double *, double *, double *);

static void test_roots_methods(void) {
  static const char *const name[3] = {"Aberth", "companion QR", "autobal_poly_roots"};
  int m;
  printf("-- root finders: Aberth-Ehrlich, companion QR (DLAHQR), the public entry\n");
  for (m = 0; m < 3; m++) {
    int t, bad_acc = 0, bad_struct = 0, bad_count = 0, unsettled = 0;
    double worst = 0.0;
    for (t = 0; t < 400; t++) {
      /* known roots: a random mix of real roots and pairs, moduli in [0.1, 10],
       * kept apart (pairwise distance >= 0.05 |r|) so every root is simple */
      double r[12], pr[6], pim[6], c[AUTOBAL_POLY_MAXLEN], re[12], im[12], wr[12], wi[12];
      size_t nr = (size_t)(urand() * 5.0), np = 1 + (size_t)(urand() * 4.0), n, i, j, k, nreal;
      size_t perm[12];
      double md;
      int st;
      autobal_poly_workspace *w;
      for (i = 0, k = 0; i < nr + np; i++) {
        int again;
        do {
          double mod = pow(10.0, 2.0 * urand() - 1.0), ang = M_PI * urand();
          double zr = (i < nr) ? mod * (urand() < 0.5 ? -1.0 : 1.0) : mod * cos(ang);
          double zi = (i < nr) ? 0.0 : mod * sin(ang) + 0.05 * mod;
          again = 0;
          for (j = 0; j < k; j++)
            if (hypot(wr[j] - zr, wi[j] - zi) < 0.05 * mod || hypot(wr[j] - zr, wi[j] + zi) < 0.05 * mod)
              again = 1;
          if (!again) {
            wr[k] = zr;
            wi[k++] = zi;
            if (zi != 0.0) {
              wr[k] = zr;
              wi[k++] = -zi;
            }
          }
        } while (again);
      }
      for (i = 0, j = 0; i < k; i++) {
        if (wi[i] == 0.0) r[j++] = wr[i];
      }
      for (i = 0, j = 0; i < k; i++)
        if (wi[i] > 0.0) {
          pr[j] = wr[i];
          pim[j++] = wi[i];
        }
      n = poly_from_roots(r, nr, pr, pim, np, 0.5 + urand(), c) - 1;
      w = autobal_poly_workspace_alloc(n);
      if (m == 2) {
        st = autobal_poly_roots(w, c, n + 1, re, im, NULL);
      } else {
        roots_fn f = (m == 0) ? autobal_poly_roots_aberth : autobal_poly_roots_qr;
        st = f(w, c, re, im);
      }
      autobal_poly_workspace_free(w);
      if (st != 0) {
        unsettled++;
        continue;
      }
      if (!exact_pairs(n, re, im, &nreal)) bad_struct++;
      if (nreal != nr) bad_count++;
      autobal_match_roots(n, wr, wi, re, im, perm, &md, NULL);
      for (i = 0; i < n; i++) {
        double kc, kn, err = hypot(re[perm[i]] - wr[i], im[perm[i]] - wi[i]);
        double bound;
        root_conditions(c, n + 1, wr[i], wi[i], &kc, &kn);
        /* the polynomial itself carries rounding from poly_from_roots (~n eps
         * componentwise), plus the method's own backward error */
        bound = 64.0 * (double)n * DBL_EPSILON * (m == 1 ? kn : kc) * hypot(wr[i], wi[i]);
        if (err > bound) bad_acc++;
        if (err / bound > worst) worst = err / bound;
      }
    }
    printf("   %s: worst error / first-order bound %.3g\n", name[m], worst);
    CHECK(m == 1 ? "companion QR settles on 400 random polynomials with simple roots"
                 : (m == 0 ? "Aberth settles on 400 random polynomials with simple roots"
                           : "autobal_poly_roots succeeds on 400 random polynomials"),
          unsettled == 0);
    CHECK("errors within 64 n eps x condition x |r| (componentwise condition; normwise for QR)",
          bad_acc == 0);
    CHECK("real roots have Im = 0 exactly, the others come in exact conjugate pairs",
          bad_struct == 0);
    CHECK("number of real roots == number of known real roots", bad_count == 0);
  }
  /* roots of very different size: the componentwise backward stability of the
   * Aberth stopping rule gives every root to a few ulps */
  {
    double r[5] = {1e-8, -1e-3, 1.0, 1e3, -1e8}, c[8], re[7], im[7], pr[1] = {2e4}, pim[1] = {3e4};
    size_t len = poly_from_roots(r, 5, pr, pim, 1, 1.0, c), i, j;
    autobal_poly_workspace *w = autobal_poly_workspace_alloc(len - 1);
    double worst = 0.0;
    CHECK_STATUS("roots spread over 16 decades", autobal_poly_roots(w, c, len, re, im, NULL), 0);
    for (i = 0; i < 5; i++) {
      double best = INFINITY;
      for (j = 0; j < 7; j++) best = fmin(best, hypot(re[j] - r[i], im[j]) / fabs(r[i]));
      worst = fmax(worst, best);
    }
    CHECK_CLOSE("roots 1e-8 .. 1e8: worst relative error of the real roots", worst, 0, 0, 1e-13);
    autobal_poly_workspace_free(w);
  }
  /* exact zero roots are split off */
  {
    double c[7] = {0.0, 0.0, 0.0, -2.0, 1.0, -2.0, 1.0}, re[6], im[6]; /* x^3 (x - 2)(x^2 + 1) */
    autobal_poly_workspace *w = autobal_poly_workspace_alloc(6);
    size_t i, nz = 0;
    CHECK_STATUS("x^3 (x - 2)(x^2 + 1)", autobal_poly_roots(w, c, 7, re, im, NULL), 0);
    for (i = 0; i < 6; i++) nz += (re[i] == 0.0 && im[i] == 0.0);
    CHECK("three roots exactly 0", nz == 3);
    CHECK_CLOSE("root 2", re[5], 2.0, 1e-15, 0);
    /* sorted by Re then Im: the pair (Re ~ 0) sits among the zeros */
    {
      size_t a = 6, b = 6;
      for (i = 0; i < 6; i++) {
        if (im[i] < 0.0) a = i;
        if (im[i] > 0.0) b = i;
      }
      CHECK("+-i: exact pair", a < 6 && b < 6 && re[a] == re[b] && im[a] == -im[b]);
      if (b < 6) CHECK_CLOSE("Im of the pair", im[b], 1.0, 1e-15, 0);
    }
    autobal_poly_workspace_free(w);
  }
  /* a 4-fold root: any backward-stable method gives it to ~eps^(1/4) */
  {
    double r[5] = {1.0, 1.0, 1.0, 1.0, -2.0}, c[6], re[5], im[5];
    size_t len = poly_from_roots(r, 5, NULL, NULL, 0, 1.0, c), i;
    autobal_poly_workspace *w = autobal_poly_workspace_alloc(5);
    double d1 = 0.0, sum_r = 0.0, sum_i = 0.0;
    CHECK_STATUS("(x - 1)^4 (x + 2)", autobal_poly_roots(w, c, len, re, im, NULL), 0);
    CHECK_CLOSE("simple root -2", re[0], -2.0, 1e-14, 0);
    for (i = 1; i < 5; i++) {
      d1 = fmax(d1, hypot(re[i] - 1.0, im[i]));
      sum_r += re[i];
      sum_i += im[i];
    }
    CHECK_CLOSE("4-fold root 1: worst distance (~eps^(1/4))", d1, 0, 0, 1e-3);
    /* the mean of a cluster is well conditioned */
    CHECK_CLOSE("mean of the cluster", sum_r / 4.0, 1.0, 1e-12, 0);
    CHECK_CLOSE("imaginary parts cancel", sum_i, 0.0, 0, 1e-15);
    autobal_poly_workspace_free(w);
  }
  /* degrees 1 and 2, closed forms */
  {
    double c1[2] = {3.0, -2.0}, c2[3] = {5.0, 2.0, 1.0}, re[2], im[2]; /* x = 1.5; -1 +- 2i */
    autobal_poly_workspace *w1 = autobal_poly_workspace_alloc(1), *w2 = autobal_poly_workspace_alloc(2);
    CHECK_STATUS("degree 1", autobal_poly_roots(w1, c1, 2, re, im, NULL), 0);
    CHECK("3 - 2x: root 1.5 exactly", re[0] == 1.5 && im[0] == 0.0);
    CHECK_STATUS("degree 2", autobal_poly_roots(w2, c2, 3, re, im, NULL), 0);
    CHECK_CLOSE("x^2 + 2x + 5: Re", re[0], -1.0, 1e-15, 0);
    CHECK_CLOSE("x^2 + 2x + 5: Im", im[1], 2.0, 1e-15, 0);
    CHECK("exact pair", re[0] == re[1] && im[0] == -im[1]);
    autobal_poly_workspace_free(w1);
    autobal_poly_workspace_free(w2);
  }
  /* Wilkinson's polynomial of degree 10 (roots 1..10, conditions up to ~1e7) */
  {
    double r[10], c[11], re[10], im[10], worst = 0.0;
    size_t i, len;
    autobal_poly_workspace *w = autobal_poly_workspace_alloc(10);
    for (i = 0; i < 10; i++) r[i] = (double)(i + 1);
    len = poly_from_roots(r, 10, NULL, NULL, 0, 1.0, c);
    CHECK_STATUS("Wilkinson 10", autobal_poly_roots(w, c, len, re, im, NULL), 0);
    for (i = 0; i < 10; i++) worst = fmax(worst, hypot(re[i] - r[i], im[i]));
    CHECK_CLOSE("Wilkinson 10: worst error (conditions ~1e7 x eps)", worst, 0, 0, 1e-7);
    autobal_poly_workspace_free(w);
  }
}

static void test_matching(void) {
  double ar[2] = {0.0, 0.5}, ai[2] = {0, 0}, br[2] = {0.4, 1.2}, bi[2] = {0, 0}, md;
  size_t perm[AUTOBAL_MATCH_MAXN];
  int t, bad = 0;
  autobal_error err;
  printf("-- bottleneck matching\n");
  /* greedy by smallest distance pairs 0.5-0.4 then 0-1.2 (max 1.2); optimum 0.7 */
  autobal_match_roots(2, ar, ai, br, bi, perm, &md, NULL);
  CHECK_CLOSE("bottleneck beats greedy: max distance", md, 0.7, 1e-15, 0);
  CHECK("bottleneck pairing 0->0.4, 0.5->1.2", perm[0] == 0 && perm[1] == 1);
  for (t = 0; t < 40; t++) {
    double xr[6], xi[6], yr[6], yi[6], bf;
    size_t pp[6], i;
    int used[6] = {0};
    for (i = 0; i < 6; i++) {
      xr[i] = urand(), xi[i] = urand(), yr[i] = urand(), yi[i] = urand();
    }
    bf = brute_bottleneck(6, xr, xi, yr, yi, pp, 0, used, 0.0);
    autobal_match_roots(6, xr, xi, yr, yi, perm, &md, NULL);
    if (md != bf) bad++;
    for (i = 0; i < 6; i++)
      if (hypot(xr[i] - yr[perm[i]], xi[i] - yi[perm[i]]) > md) bad++;
  }
  CHECK("40 random 6-sets: bottleneck == brute force over 720 permutations", bad == 0);
  CHECK_STATUS("n = 0", autobal_match_roots(0, NULL, NULL, NULL, NULL, NULL, &md, NULL),
               AUTOBAL_SUCCESS);
  autobal_error_clear(&err);
  CHECK_STATUS("n too large", autobal_match_roots(AUTOBAL_MATCH_MAXN + 1, ar, ai, br, bi, NULL, &md, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("n too large: message names n", err.message, "n = ");
}

static void test_hurwitz(void) {
  double c[AUTOBAL_POLY_MAXLEN], re[32], im[32];
  int v, nr, t, disagree = 0, decided = 0;
  size_t len;
  autobal_error err;
  printf("-- Routh-Hurwitz sign test\n");
  {
    double r[3] = {-1, -2, -3};
    len = poly_from_roots(r, 3, NULL, NULL, 0, 1.0, c);
    autobal_poly_hurwitz(c, len, 0.0, &v, &nr, NULL);
    CHECK("(x+1)(x+2)(x+3) stable", v == AUTOBAL_VERDICT_STABLE && nr == 0);
    len = poly_from_roots(r, 3, NULL, NULL, 0, -2.0, c);
    autobal_poly_hurwitz(c, len, 0.0, &v, &nr, NULL);
    CHECK("negative leading coefficient: still stable", v == AUTOBAL_VERDICT_STABLE);
  }
  {
    double r[2] = {1, -2};
    len = poly_from_roots(r, 2, NULL, NULL, 0, 1.0, c);
    autobal_poly_hurwitz(c, len, 0.0, &v, &nr, NULL);
    CHECK("(x-1)(x+2): unstable, one root in RHP", v == AUTOBAL_VERDICT_UNSTABLE && nr == 1);
  }
  {
    double r[1] = {-1}, pr[2] = {1, -0.1}, pim[2] = {2, 3};
    len = poly_from_roots(r, 1, pr, pim, 2, 1.0, c);
    autobal_poly_hurwitz(c, len, 0.0, &v, &nr, NULL);
    CHECK("(x+1)(pair 1 +- 2i)(pair -0.1 +- 3i): two RHP roots", v == AUTOBAL_VERDICT_UNSTABLE && nr == 2);
  }
  {
    double r[1] = {-1}, pr[1] = {0}, pim[1] = {1};
    len = poly_from_roots(r, 1, pr, pim, 1, 1.0, c);
    autobal_poly_hurwitz(c, len, 0.0, &v, &nr, NULL);
    CHECK("(x+1)(x^2+1): marginal", v == AUTOBAL_VERDICT_MARGINAL);
    len = poly_from_roots(r, 1, NULL, NULL, 0, 1.0, c);
    c[2] = c[1], c[1] = c[0], c[0] = 0.0; /* x (x + 1) */
    autobal_poly_hurwitz(c, 3, 0.0, &v, &nr, NULL);
    CHECK("x (x+1): marginal (root 0)", v == AUTOBAL_VERDICT_MARGINAL);
  }
  {
    /* near-axis pair -eps +- i: decided with rtol 0, marginal with rtol >> eps */
    double r[1] = {-2}, pr[1] = {-1e-9}, pim[1] = {1};
    len = poly_from_roots(r, 1, pr, pim, 1, 1.0, c);
    autobal_poly_hurwitz(c, len, 0.0, &v, &nr, NULL);
    CHECK("pair -1e-9 +- i, rtol 0: stable", v == AUTOBAL_VERDICT_STABLE);
    autobal_poly_hurwitz(c, len, 1e-6, &v, &nr, NULL);
    CHECK("pair -1e-9 +- i, rtol 1e-6: marginal", v == AUTOBAL_VERDICT_MARGINAL);
    pr[0] = +1e-9;
    len = poly_from_roots(r, 1, pr, pim, 1, 1.0, c);
    autobal_poly_hurwitz(c, len, 0.0, &v, &nr, NULL);
    CHECK("pair +1e-9 +- i, rtol 0: unstable", v == AUTOBAL_VERDICT_UNSTABLE && nr == 2);
  }
  /* random polynomials of degree 1..12 built from random roots: the count of
   * RHP roots equals the number of sign changes, whenever the margin is clear */
  for (t = 0; t < 400; t++) {
    size_t nrr = (size_t)(urand() * 5), np = (size_t)(urand() * 4), i, nrhp = 0;
    double rr[6], ppr[6], ppi[6];
    double mre;
    int vr;
    if (nrr + np == 0) nrr = 1;
    for (i = 0; i < nrr; i++) {
      rr[i] = (urand() - 0.7) * 4.0;
      if (rr[i] > 0) nrhp++;
    }
    for (i = 0; i < np; i++) {
      ppr[i] = (urand() - 0.7) * 2.0;
      ppi[i] = urand() * 3.0 + 0.1;
      if (ppr[i] > 0) nrhp += 2;
    }
    len = poly_from_roots(rr, nrr, ppr, ppi, np, urand() + 0.5, c);
    autobal_poly_hurwitz(c, len, 1e-12, &v, &nr, NULL);
    /* the same through GSL roots */
    {
      autobal_poly_workspace *w = autobal_poly_workspace_alloc(len - 1);
      autobal_poly_roots(w, c, len, re, im, NULL);
      autobal_poly_workspace_free(w);
    }
    vr = autobal_roots_verdict(len - 1, re, im, 1e-9, &mre);
    if (fabs(mre) > 1e-3) {
      decided++;
      if (v != vr || (v == AUTOBAL_VERDICT_UNSTABLE && (size_t)nr != nrhp)) disagree++;
    }
  }
  printf("   (random sets decided: %d)\n", decided);
  CHECK("400 random polynomials: Routh verdict and RHP count == from the roots", disagree == 0);
  CHECK("most random sets were decided", decided > 300);
  autobal_error_clear(&err);
  CHECK_STATUS("hurwitz: rtol < 0", autobal_poly_hurwitz(c, 3, -1.0, &v, NULL, &err), AUTOBAL_EINVAL);
  CHECK_MSG("hurwitz: message names rtol", err.message, "rtol");
  c[0] = NAN;
  CHECK_STATUS("hurwitz: NaN", autobal_poly_hurwitz(c, 3, 0.0, &v, NULL, &err), AUTOBAL_EINVAL);
  CHECK_MSG("hurwitz: message names c[0]", err.message, "c[0]");
  c[0] = 1.0, c[2] = 0.0;
  CHECK_STATUS("hurwitz: zero leading", autobal_poly_hurwitz(c, 3, 0.0, &v, NULL, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("hurwitz: len too large",
               autobal_poly_hurwitz(c, AUTOBAL_POLY_MAXLEN + 1, 0.0, &v, NULL, &err), AUTOBAL_EINVAL);
  {
    double ce[3] = {0, -1, 0};
    c[2] = 1.0;
    CHECK_STATUS("hurwitz_err: negative bound", autobal_poly_hurwitz_err(c, ce, 3, &v, NULL, &err),
                 AUTOBAL_EINVAL);
    CHECK_MSG("hurwitz_err: message names cerr[1]", err.message, "cerr[1]");
  }
  {
    double r1[2] = {1.0, -2.0}, r2[2] = {-2.0, -3.0}, i2[2] = {0.5, 4.0};
    double m;
    CHECK("roots_verdict: Re 1 > 0 -> unstable",
          autobal_roots_verdict(2, r1, i2, 1e-9, &m) == AUTOBAL_VERDICT_UNSTABLE && m == 1.0);
    CHECK("roots_verdict: all Re < 0 -> stable",
          autobal_roots_verdict(2, r2, i2, 1e-9, &m) == AUTOBAL_VERDICT_STABLE && m == -2.0);
    r2[0] = -1e-12;
    CHECK("roots_verdict: Re -1e-12 -> marginal",
          autobal_roots_verdict(2, r2, i2, 1e-9, NULL) == AUTOBAL_VERDICT_MARGINAL);
  }
}

/* ---- the quick stage of the Routh test against the full test ------------ */
/* The generated quick stage itself (src/routh_quick.inc), to count how often
 * it decides and to check every decision directly. */
#include <stdint.h>
#define AUTOBAL_RQ_INLINE inline
#include "routh_quick.inc"

static int quick_n(size_t n, const double *c, const double *ce, double rtol, double eps0, int rel,
                   int *ch) {
  switch (n) {
    case 3: return autobal_routh_quick_3(c, ce, NULL, rtol, eps0, rel, ch);
    case 4: return autobal_routh_quick_4(c, ce, NULL, rtol, eps0, rel, ch);
    case 5: return autobal_routh_quick_5(c, ce, NULL, rtol, eps0, rel, ch);
    case 6: return autobal_routh_quick_6(c, ce, NULL, rtol, eps0, rel, ch);
    case 7: return autobal_routh_quick_7(c, ce, NULL, rtol, eps0, rel, ch);
    case 8: return autobal_routh_quick_8(c, ce, NULL, rtol, eps0, rel, ch);
    case 9: return autobal_routh_quick_9(c, ce, NULL, rtol, eps0, rel, ch);
    case 10: return autobal_routh_quick_10(c, ce, NULL, rtol, eps0, rel, ch);
    case 11: return autobal_routh_quick_11(c, ce, NULL, rtol, eps0, rel, ch);
    case 12: return autobal_routh_quick_12(c, ce, NULL, rtol, eps0, rel, ch);
    default: return 0;
  }
}

static double logrand(double lo, double hi) { return pow(10.0, lo + (hi - lo) * urand()); }

/* A random test polynomial of degree n (1..12) in c[0..n], of one of seven
 * kinds: 0 random roots (real parts in [-2, 1] s, so some unstable), 1 the
 * same with one root or pair within 1e-17..1e-6 s of the imaginary axis, on
 * either side, 2 random coefficients of mixed sizes with some zeros, 3 kind
 * 0 scaled by 10^(-300..300) (overflow/underflow of the bounds), 4 a pair
 * exactly on the axis or c[0] = 0 (marginal), 5 roots of very different
 * sizes (10^-4..10^4), 6 every pair near the axis.  Root scale s =
 * 10^(-3..3); leading coefficient of either sign.  Returns 0 when the
 * coefficients overflowed (skip). */
static int random_poly(size_t n, int kind, double *c) {
  double rr[12], pr[6], pim[6], s = logrand(-3, 3), lead = (0.5 + urand()) * (urand() < 0.3 ? -1 : 1);
  size_t np = (size_t)(urand() * (double)(n / 2 + 1)), nr, i, len;
  if (np > n / 2) np = n / 2;
  nr = n - 2 * np;
  if (kind == 2) {
    for (i = 0; i <= n; i++) c[i] = (urand() < 0.1 && i < n) ? 0.0 : (2 * urand() - 1) * logrand(-2, 2);
    if (c[n] == 0.0) c[n] = lead;
    return 1;
  }
  for (i = 0; i < nr; i++) rr[i] = (urand() * 3.0 - 2.0) * s * (kind == 5 ? logrand(-4, 4) : 1.0);
  for (i = 0; i < np; i++) {
    double sc = kind == 5 ? logrand(-4, 4) : 1.0;
    pr[i] = (urand() * 3.0 - 2.0) * s * sc;
    pim[i] = (urand() * 3.0 + 0.1) * s * sc;
  }
  if (kind == 1) {
    double d = logrand(-17, -6) * (urand() < 0.5 ? -1 : 1);
    if (np > 0) pr[0] = d * pim[0];
    else rr[0] = d * s;
  }
  if (kind == 6) /* every pair near the axis: near-zero entries in early rows too */
    for (i = 0; i < np; i++) pr[i] = logrand(-17, -6) * (urand() < 0.5 ? -1 : 1) * pim[i];
  if (kind == 4) {
    if (np > 0) pr[0] = 0.0;
    else rr[0] = 0.0;
  }
  len = poly_from_roots(rr, nr, pr, pim, np, lead, c);
  if (len != n + 1) return 0;
  if (kind == 3) {
    double f = logrand(-300, 300);
    for (i = 0; i <= n; i++) c[i] *= f;
  }
  for (i = 0; i <= n; i++)
    if (!isfinite(c[i])) return 0;
  return 1;
}

static void test_hurwitz_quick(void) {
  const int ntrial = 140000;
  int t, mism_err = 0, mism_rtol = 0, wrong_quick = 0, wrong_rel = 0, n_quick = 0, n_decl = 0;
  int n_marg = 0, n_cases = 0, n_near_quick = 0, n_near = 0, bad_input_pass = 0, n_elig = 0;
  printf("-- Routh test: quick stage + full test == full test alone\n");
  for (t = 0; t < ntrial; t++) {
    size_t n = (size_t)(t % 12) + 1, i;
    int kind = (t / 12) % 7, mode = (t / 84) % 4;
    double c[13], ce[13], rtol = logrand(-16, -6), sc = 0.0, se = 0.0, eps0;
    const double *cep = ce;
    int v1, v2, r1 = -7, r2 = -7, s1, s2, ch, q;
    autobal_error e1, e2;
    if (!random_poly(n, kind, c)) continue;
    n_cases++;
    /* the bounds: none, relative, per-coefficient relative + absolute, zero */
    for (i = 0; i <= n; i++) {
      if (mode == 1) ce[i] = rtol * fabs(c[i]);
      else if (mode == 2)
        ce[i] = fabs(c[i]) * logrand(-16, -8) + (urand() < 0.2 ? logrand(-20, -5) : 0.0);
      else ce[i] = 0.0;
      if (!isfinite(ce[i])) ce[i] = 0.0;
    }
    if (mode == 0) cep = NULL;
    /* public test (quick stage + full) vs the full test alone */
    s1 = autobal_poly_hurwitz_err(c, cep, n + 1, &v1, &r1, &e1);
    s2 = autobal_poly_hurwitz_err_full(c, cep, n + 1, &v2, &r2, &e2);
    if (s1 != s2 || v1 != v2 || r1 != r2) mism_err++;
    if (s2 == AUTOBAL_SUCCESS && v2 == AUTOBAL_VERDICT_MARGINAL) n_marg++;
    if (mode == 1) { /* autobal_poly_hurwitz with rtol: the same as its bounds made explicit */
      s1 = autobal_poly_hurwitz(c, n + 1, rtol, &v1, &r1, &e1);
      if (s1 != s2 || v1 != v2 || r1 != r2) mism_rtol++;
    }
    if (n < 3 || s2 != AUTOBAL_SUCCESS) continue;
    /* the quick stage directly: a pass must be the full test's decision; any
     * eps0 > 0 is valid (the one of autobal_poly_hurwitz_err, and random) */
    n_elig++;
    for (i = 0; i <= n; i++) sc += fabs(c[i]), se += ce[i];
    eps0 = DBL_EPSILON + se / sc;
    q = quick_n(n, c, ce, 0.0, urand() < 0.8 ? eps0 : logrand(-16, -2), 0, &ch);
    if (kind == 1 || kind == 6) n_near++;
    if (q) {
      int vq = ch == 0 ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
      n_quick++;
      if (kind == 1 || kind == 6) n_near_quick++;
      if (vq != v2 || ch != r2) wrong_quick++;
    } else n_decl++;
    if (mode == 1 && quick_n(n, c, NULL, rtol, DBL_EPSILON + rtol, 1, &ch)) { /* rel mode */
      int vq = ch == 0 ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
      if (vq != v2 || ch != r2) wrong_rel++;
    }
  }
  printf("   (%d polynomials; full test marginal on %d; quick stage decided %d, declined %d; "
         "near the axis: %d of %d decided by it)\n",
         n_cases, n_marg, n_quick, n_decl, n_near_quick, n_near);
  CHECK("quick + full == full: status, verdict, n_rhp (hurwitz_err, bounds none/rel/mixed/0)",
        mism_err == 0);
  CHECK("autobal_poly_hurwitz (rtol, rel mode) == full test with cerr = rtol |c|", mism_rtol == 0);
  CHECK("every quick decision (gen mode, any eps0) == the full test's verdict and count",
        wrong_quick == 0);
  CHECK("every quick decision (rel mode) == the full test's verdict and count", wrong_rel == 0);
  CHECK("coverage: >= 1e5 polynomials", n_cases >= 100000);
  CHECK("coverage: the quick stage decides > 40% of degrees 3..12, declines some",
        n_quick > n_elig / 5 * 2 && n_decl > 1000);
  CHECK("coverage: marginal cases occur", n_marg > 1000);
  CHECK("coverage: near-axis cases both decided and declined",
        n_near_quick > n_near / 10 && n_near_quick < n_near);
  /* the quick stage declines bad input (the full test then reports it) */
  {
    double c[9] = {1, 8, 28, 56, 70, 56, 28, 8, 1}, ce[9] = {0}; /* (x+1)^8: stable */
    int ch;
    CHECK("quick: (x+1)^8 decided stable", quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch) && ch == 0);
    c[3] = NAN;
    bad_input_pass += quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch);
    c[3] = INFINITY;
    bad_input_pass += quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch);
    c[3] = 56, ce[5] = -1e-300;
    bad_input_pass += quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch);
    ce[5] = NAN;
    bad_input_pass += quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch);
    ce[5] = INFINITY;
    bad_input_pass += quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch);
    ce[5] = 0.0, c[8] = 0.0;
    bad_input_pass += quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch);
    c[8] = 1.0, c[0] = 0.0;
    bad_input_pass += quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch);
    CHECK("quick: declines NaN, inf, negative/NaN/inf bound, zero c[n], zero c[0]",
          bad_input_pass == 0);
    {
      int vf, rf;
      c[0] = 1e-320; /* subnormal: the copies of c[0] carry the full test's own bound */
      autobal_poly_hurwitz_err_full(c, ce, 9, &vf, &rf, NULL);
      CHECK("quick: subnormal c[0]: decided as the full test",
            quick_n(8, c, ce, 0.0, DBL_EPSILON, 0, &ch) && vf == AUTOBAL_VERDICT_STABLE && ch == rf);
    }
  }
}

static void test_sturm(void) {
  double c[AUTOBAL_POLY_MAXLEN], re[32], im[32];
  double r[3] = {1, 2, 3}, pr[1] = {0.5}, pim[1] = {1};
  size_t len;
  int n, t, bad = 0;
  autobal_error err;
  printf("-- Sturm sequences\n");
  len = poly_from_roots(r, 3, pr, pim, 1, 1.0, c);
  autobal_poly_sturm_count(c, len, -INFINITY, INFINITY, 0, &n, NULL);
  CHECK("(x-1)(x-2)(x-3)(x^2-x+1.25): 3 real roots", n == 3);
  autobal_poly_sturm_count(c, len, 1.5, 2.5, 0, &n, NULL);
  CHECK("... one in (1.5, 2.5]", n == 1);
  autobal_poly_sturm_count(c, len, 0.0, 1.0, 0, &n, NULL);
  CHECK("... one in (0, 1] (root at the right end counts)", n == 1);
  autobal_poly_sturm_count(c, len, 1.0, 1.5, 0, &n, NULL);
  CHECK("... none in (1, 1.5] (root at the left end does not)", n == 0);
  {
    double r2[3] = {1, 1, -1};
    len = poly_from_roots(r2, 3, NULL, NULL, 0, 1.0, c);
    autobal_poly_sturm_count(c, len, -INFINITY, INFINITY, 0, &n, NULL);
    CHECK("(x-1)^2 (x+1): 2 distinct real roots", n == 2);
  }
  for (t = 0; t < 200; t++) {
    double rr[5], ppr[3], ppi[3], a = urand() * 4 - 2, b = a + urand() * 3;
    size_t nrr = 1 + (size_t)(urand() * 4), np = (size_t)(urand() * 3), i;
    int want = 0;
    for (i = 0; i < nrr; i++) {
      rr[i] = urand() * 6 - 3;
      if (rr[i] > a && rr[i] <= b) want++;
      if (fabs(rr[i] - a) < 1e-3 || fabs(rr[i] - b) < 1e-3) want = -100; /* too close to call */
    }
    for (i = 0; i < np; i++) ppr[i] = urand() * 4 - 2, ppi[i] = 0.05 + urand();
    len = poly_from_roots(rr, nrr, ppr, ppi, np, 1.0, c);
    if (want < 0) continue;
    {
      int close = 0;
      size_t x, y;
      for (x = 0; x < nrr; x++)
        for (y = x + 1; y < nrr; y++)
          if (fabs(rr[x] - rr[y]) < 1e-3) close = 1;
      if (close) continue;
    }
    autobal_poly_sturm_count(c, len, a, b, 0, &n, NULL);
    if (n != want) bad++;
  }
  CHECK("200 random polynomials: Sturm count == count of the known real roots", bad == 0);
  (void)re, (void)im;
  autobal_error_clear(&err);
  CHECK_STATUS("sturm: a > b", autobal_poly_sturm_count(c, len, 2.0, 1.0, 0, &n, &err), AUTOBAL_EINVAL);
  c[0] = NAN;
  CHECK_STATUS("sturm: NaN", autobal_poly_sturm_count(c, len, 0.0, 1.0, 0, &n, &err), AUTOBAL_EINVAL);
  CHECK_MSG("sturm: message names c[0]", err.message, "c[0]");
  c[0] = 0.0;
  CHECK_STATUS("sturm: zero polynomial", autobal_poly_sturm_count(c, 1, 0.0, 1.0, 0, &n, &err),
               AUTOBAL_EINVAL);
}

static void test_brent(void) {
  double x, lo, hi;
  autobal_error err;
  printf("-- Brent and bisection\n");
  CHECK_STATUS("brent x^3 - 2", autobal_root_brent(f_cubic, NULL, 0.0, 3.0, 0.0, 1e-15, 100, &x, NULL),
               AUTOBAL_SUCCESS);
  CHECK_CLOSE("root of x^3 - 2 = cbrt(2)", x, cbrt(2.0), 4e-15, 0);
  autobal_root_brent(f_dottie, NULL, 0.0, 1.0, 0.0, 1e-15, 100, &x, NULL);
  CHECK_CLOSE("root of cos x - x (Dottie number)", x, 0.739085133215160641655312087673873, 4e-15, 0);
  autobal_error_clear(&err);
  CHECK_STATUS("brent: no sign change", autobal_root_brent(f_cubic, NULL, 2.0, 3.0, 0, 1e-12, 100, &x, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("brent: message says bracket", err.message, "bracket");
  CHECK_STATUS("brent: status of f propagated", autobal_root_brent(f_fail, NULL, -1.0, 1.0, 0, 1e-12, 100, &x, &err),
               AUTOBAL_ERHS);
  CHECK_STATUS("brent: max_iter reached", autobal_root_brent(f_dottie, NULL, 0.0, 1.0, 0, 1e-15, 2, &x, &err),
               AUTOBAL_ENUMERIC);
  CHECK_STATUS("brent: bad tolerance", autobal_root_brent(f_dottie, NULL, 0.0, 1.0, 0, 0, 100, &x, &err),
               AUTOBAL_EINVAL);
  CHECK_STATUS("bisect x^2 > 2", autobal_bisect_change(p_above_sqrt2, NULL, 0.0, 2.0, 0, 1e-14, &lo, &hi, NULL),
               AUTOBAL_SUCCESS);
  CHECK("bracket contains sqrt 2", lo * lo <= 2.0 && hi * hi > 2.0 && hi - lo <= 3e-14);
  CHECK_STATUS("bisect: same value at both ends",
               autobal_bisect_change(p_above_sqrt2, NULL, 0.0, 1.0, 0, 1e-14, &lo, &hi, &err), AUTOBAL_EINVAL);
  CHECK_MSG("bisect: message says same value", err.message, "same value");
  CHECK_STATUS("bisect: a >= b", autobal_bisect_change(p_above_sqrt2, NULL, 2.0, 0.0, 0, 1e-14, &lo, &hi, &err),
               AUTOBAL_EINVAL);
  CHECK("verdict names", strcmp(autobal_verdict_name(1), "stable") == 0 &&
                             strcmp(autobal_verdict_name(-1), "unstable") == 0 &&
                             strcmp(autobal_verdict_name(0), "marginal") == 0 &&
                             strcmp(autobal_verdict_name(7), "unknown") == 0);
}

int main(void) {
  gsl_set_error_handler_off();
  test_arithmetic();
  test_roots_eigen();
  test_roots_methods();
  test_matching();
  test_hurwitz();
  test_hurwitz_quick();
  test_sturm();
  test_brent();
  return check_summary();
}
