/* poly.c: model-agnostic polynomial arithmetic, roots, eigenvalues, root
 * matching, Routh-Hurwitz and Sturm sign tests, bracketed root finding.
 * See include/autobal/stability.h for the contracts. */
#include "autobal/stability.h"
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_poly.h>
#include <gsl/gsl_vector.h>

const char *autobal_verdict_name(int verdict) {
  switch (verdict) {
    case AUTOBAL_VERDICT_STABLE:
      return "stable";
    case AUTOBAL_VERDICT_UNSTABLE:
      return "unstable";
    case AUTOBAL_VERDICT_MARGINAL:
      return "marginal";
    default:
      return "unknown";
  }
}

/* ------------------------------------------------------------------------ */
/* Real polynomials                                                         */
/* ------------------------------------------------------------------------ */

double autobal_poly_eval(const double *c, size_t len, double x) {
  double s = 0.0;
  size_t j = len;
  while (j-- > 0) s = s * x + c[j];
  return s;
}

void autobal_poly_eval_complex(const double *c, size_t len, double zre, double zim, double *re,
                               double *im) {
  double sr = 0.0, si = 0.0;
  size_t j = len;
  while (j-- > 0) {
    double tr = sr * zre - si * zim + c[j];
    double ti = sr * zim + si * zre;
    sr = tr;
    si = ti;
  }
  if (re) *re = sr;
  if (im) *im = si;
}

size_t autobal_poly_degree(const double *c, size_t len) {
  size_t j = len;
  while (j-- > 0)
    if (c[j] != 0.0) return j;
  return 0;
}

int autobal_poly_mul(const double *a, size_t alen, const double *b, size_t blen, double *out,
                     size_t outlen, autobal_error *err) {
  size_t i, j;
  if (a == NULL || b == NULL || out == NULL || alen == 0 || blen == 0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_poly_mul: empty or NULL polynomial");
  if (outlen < alen + blen - 1)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_mul: outlen = %zu is too small: need >= %zu", outlen,
                             alen + blen - 1);
  for (i = 0; i < outlen; i++) out[i] = 0.0;
  for (i = 0; i < alen; i++)
    for (j = 0; j < blen; j++) out[i + j] += a[i] * b[j];
  return AUTOBAL_SUCCESS;
}

int autobal_poly_axpby(double alpha, const double *a, size_t alen, double beta, const double *b,
                       size_t blen, double *out, size_t outlen, autobal_error *err) {
  size_t i;
  size_t n = alen > blen ? alen : blen;
  if (out == NULL || (alen > 0 && a == NULL) || (blen > 0 && b == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_poly_axpby: NULL polynomial");
  if (outlen < n)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_axpby: outlen = %zu is too small: need >= %zu", outlen, n);
  for (i = 0; i < outlen; i++) {
    double s = 0.0;
    if (i < alen) s += alpha * a[i];
    if (i < blen) s += beta * b[i];
    out[i] = s;
  }
  return AUTOBAL_SUCCESS;
}

int autobal_poly_deriv(const double *c, size_t len, double *out, size_t outlen,
                       autobal_error *err) {
  size_t i;
  size_t need = len > 1 ? len - 1 : 1;
  if (c == NULL || out == NULL || len == 0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_poly_deriv: empty or NULL polynomial");
  if (outlen < need)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_deriv: outlen = %zu is too small: need >= %zu", outlen,
                             need);
  for (i = 0; i + 1 < len; i++) out[i] = (double)(i + 1) * c[i + 1];
  for (i = len > 1 ? len - 1 : 0; i < outlen; i++) out[i] = 0.0;
  return AUTOBAL_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Complex polynomials                                                      */
/* ------------------------------------------------------------------------ */

int autobal_cpoly_mul(const double *a, size_t alen, const double *b, size_t blen, double *out,
                      size_t outlen, autobal_error *err) {
  size_t i, j;
  if (a == NULL || b == NULL || out == NULL || alen == 0 || blen == 0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_cpoly_mul: empty or NULL polynomial");
  if (outlen < alen + blen - 1)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_cpoly_mul: outlen = %zu is too small: need >= %zu", outlen,
                             alen + blen - 1);
  for (i = 0; i < 2 * outlen; i++) out[i] = 0.0;
  for (i = 0; i < alen; i++)
    for (j = 0; j < blen; j++) {
      double ar = a[2 * i], ai = a[2 * i + 1], br = b[2 * j], bi = b[2 * j + 1];
      out[2 * (i + j)] += ar * br - ai * bi;
      out[2 * (i + j) + 1] += ar * bi + ai * br;
    }
  return AUTOBAL_SUCCESS;
}

int autobal_cpoly_axpby(double ar, double ai, const double *a, size_t alen, double br, double bi,
                        const double *b, size_t blen, double *out, size_t outlen,
                        autobal_error *err) {
  size_t i;
  size_t n = alen > blen ? alen : blen;
  if (out == NULL || (alen > 0 && a == NULL) || (blen > 0 && b == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_cpoly_axpby: NULL polynomial");
  if (outlen < n)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_cpoly_axpby: outlen = %zu is too small: need >= %zu", outlen,
                             n);
  for (i = 0; i < outlen; i++) {
    double sr = 0.0, si = 0.0;
    if (i < alen) {
      sr += ar * a[2 * i] - ai * a[2 * i + 1];
      si += ar * a[2 * i + 1] + ai * a[2 * i];
    }
    if (i < blen) {
      sr += br * b[2 * i] - bi * b[2 * i + 1];
      si += br * b[2 * i + 1] + bi * b[2 * i];
    }
    out[2 * i] = sr;
    out[2 * i + 1] = si;
  }
  return AUTOBAL_SUCCESS;
}

void autobal_cpoly_conj(const double *a, size_t len, double *out) {
  size_t i;
  for (i = 0; i < len; i++) {
    out[2 * i] = a[2 * i];
    out[2 * i + 1] = -a[2 * i + 1];
  }
}

void autobal_cpoly_eval(const double *a, size_t len, double zre, double zim, double *re,
                        double *im) {
  double sr = 0.0, si = 0.0;
  size_t j = len;
  while (j-- > 0) {
    double tr = sr * zre - si * zim + a[2 * j];
    double ti = sr * zim + si * zre + a[2 * j + 1];
    sr = tr;
    si = ti;
  }
  if (re) *re = sr;
  if (im) *im = si;
}

void autobal_cpoly_real_part(const double *a, size_t len, double *out, double *max_imag) {
  size_t i;
  double mi = 0.0, ma = 0.0;
  for (i = 0; i < len; i++) {
    double m = hypot(a[2 * i], a[2 * i + 1]);
    if (m > ma) ma = m;
    if (fabs(a[2 * i + 1]) > mi) mi = fabs(a[2 * i + 1]);
    out[i] = a[2 * i];
  }
  if (max_imag) *max_imag = mi / (ma > 1e-300 ? ma : 1e-300);
}

/* ------------------------------------------------------------------------ */
/* Roots and eigenvalues                                                    */
/* ------------------------------------------------------------------------ */

struct autobal_poly_workspace {
  size_t degree;
  gsl_poly_complex_workspace *w;
  double *z; /* 2*degree packed complex roots */
};

autobal_poly_workspace *autobal_poly_workspace_alloc(size_t degree) {
  autobal_poly_workspace *w;
  if (degree < 1) return NULL;
  w = (autobal_poly_workspace *)calloc(1, sizeof *w);
  if (w == NULL) return NULL;
  w->degree = degree;
  {
    /* gsl_poly_complex_workspace_alloc reports n < 2 through the error
     * handler; degree >= 1 means n = degree + 1 >= 2. */
    w->w = gsl_poly_complex_workspace_alloc(degree + 1);
  }
  w->z = (double *)calloc(2 * degree, sizeof(double));
  if (w->w == NULL || w->z == NULL) {
    autobal_poly_workspace_free(w);
    return NULL;
  }
  return w;
}

void autobal_poly_workspace_free(autobal_poly_workspace *w) {
  if (w == NULL) return;
  if (w->w) gsl_poly_complex_workspace_free(w->w);
  free(w->z);
  free(w);
}

size_t autobal_poly_workspace_degree(const autobal_poly_workspace *w) { return w ? w->degree : 0; }

/* Sort (re, im) pairs by increasing re, then im (insertion sort; n small). */
static void sort_pairs(size_t n, double *re, double *im) {
  size_t i, j;
  for (i = 1; i < n; i++) {
    double r = re[i], m = im[i];
    j = i;
    while (j > 0 && (re[j - 1] > r || (re[j - 1] == r && im[j - 1] > m))) {
      re[j] = re[j - 1];
      im[j] = im[j - 1];
      j--;
    }
    re[j] = r;
    im[j] = m;
  }
}

int autobal_poly_roots(autobal_poly_workspace *w, const double *c, size_t len, double *re,
                       double *im, autobal_error *err) {
  size_t i;
  int gs;
  if (w == NULL || c == NULL || re == NULL || im == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_poly_roots: NULL argument");
  if (len != w->degree + 1)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_roots: len = %zu does not match the workspace (degree "
                             "%zu needs len = %zu)",
                             len, w->degree, w->degree + 1);
  for (i = 0; i < len; i++)
    if (!isfinite(c[i]))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "autobal_poly_roots: coefficient c[%zu] = %g is not finite", i, c[i]);
  if (c[len - 1] == 0.0)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_roots: leading coefficient c[%zu] is zero", len - 1);
  gs = gsl_poly_complex_solve(c, len, w->w, w->z);
  if (gs != GSL_SUCCESS) {
    for (i = 0; i < w->degree; i++) re[i] = im[i] = NAN;
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "autobal_poly_roots: gsl_poly_complex_solve: %s",
                             gsl_strerror(gs));
  }
  for (i = 0; i < w->degree; i++) {
    re[i] = w->z[2 * i];
    im[i] = w->z[2 * i + 1];
  }
  sort_pairs(w->degree, re, im);
  return AUTOBAL_SUCCESS;
}

struct autobal_eigen_workspace {
  size_t n;
  gsl_eigen_nonsymm_workspace *w;
  gsl_matrix *a;
  gsl_vector_complex *eval;
};

autobal_eigen_workspace *autobal_eigen_workspace_alloc(size_t n) {
  autobal_eigen_workspace *w;
  if (n < 1) return NULL;
  w = (autobal_eigen_workspace *)calloc(1, sizeof *w);
  if (w == NULL) return NULL;
  w->n = n;
  w->w = gsl_eigen_nonsymm_alloc(n);
  w->a = gsl_matrix_alloc(n, n);
  w->eval = gsl_vector_complex_alloc(n);
  if (w->w == NULL || w->a == NULL || w->eval == NULL) {
    autobal_eigen_workspace_free(w);
    return NULL;
  }
  /* no Schur form needed; balance the matrix first (better accuracy) */
  gsl_eigen_nonsymm_params(0, 1, w->w);
  return w;
}

void autobal_eigen_workspace_free(autobal_eigen_workspace *w) {
  if (w == NULL) return;
  if (w->w) gsl_eigen_nonsymm_free(w->w);
  if (w->a) gsl_matrix_free(w->a);
  if (w->eval) gsl_vector_complex_free(w->eval);
  free(w);
}

size_t autobal_eigen_workspace_size(const autobal_eigen_workspace *w) { return w ? w->n : 0; }

int autobal_eigen_nonsymm(autobal_eigen_workspace *w, const double *a, double *re, double *im,
                          autobal_error *err) {
  size_t i, j, n;
  int gs;
  if (w == NULL || a == NULL || re == NULL || im == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_eigen_nonsymm: NULL argument");
  n = w->n;
  for (i = 0; i < n; i++)
    for (j = 0; j < n; j++) {
      double v = a[i * n + j];
      if (!isfinite(v))
        return autobal_error_set(err, AUTOBAL_EINVAL,
                                 "autobal_eigen_nonsymm: matrix entry (%zu, %zu) = %g is not finite",
                                 i, j, v);
      gsl_matrix_set(w->a, i, j, v);
    }
  gs = gsl_eigen_nonsymm(w->a, w->eval, w->w);
  if (gs != GSL_SUCCESS) {
    for (i = 0; i < n; i++) re[i] = im[i] = NAN;
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "autobal_eigen_nonsymm: gsl_eigen_nonsymm: %s",
                             gsl_strerror(gs));
  }
  for (i = 0; i < n; i++) {
    gsl_complex z = gsl_vector_complex_get(w->eval, i);
    re[i] = GSL_REAL(z);
    im[i] = GSL_IMAG(z);
  }
  sort_pairs(n, re, im);
  return AUTOBAL_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Matching                                                                 */
/* ------------------------------------------------------------------------ */

/* Kuhn's augmenting path for the bipartite graph "dist(i, j) <= thr". */
static int match_try(size_t i, size_t n, const double *dist, double thr, int *seen, int *owner) {
  size_t j;
  for (j = 0; j < n; j++) {
    if (seen[j] || dist[i * n + j] > thr) continue;
    seen[j] = 1;
    if (owner[j] < 0 || match_try((size_t)owner[j], n, dist, thr, seen, owner)) {
      owner[j] = (int)i;
      return 1;
    }
  }
  return 0;
}

static int match_perfect(size_t n, const double *dist, double thr, int *owner) {
  size_t i, j;
  int seen[AUTOBAL_MATCH_MAXN];
  for (j = 0; j < n; j++) owner[j] = -1;
  for (i = 0; i < n; i++) {
    for (j = 0; j < n; j++) seen[j] = 0;
    if (!match_try(i, n, dist, thr, seen, owner)) return 0;
  }
  return 1;
}

static int cmp_double(const void *pa, const void *pb) {
  double a = *(const double *)pa, b = *(const double *)pb;
  return (a > b) - (a < b);
}

int autobal_match_roots(size_t n, const double *a_re, const double *a_im, const double *b_re,
                        const double *b_im, size_t *perm, double *max_dist, autobal_error *err) {
  double dist[AUTOBAL_MATCH_MAXN * AUTOBAL_MATCH_MAXN];
  double sorted[AUTOBAL_MATCH_MAXN * AUTOBAL_MATCH_MAXN];
  int owner[AUTOBAL_MATCH_MAXN];
  size_t i, j, lo, hi, nn;
  if (n > AUTOBAL_MATCH_MAXN)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_match_roots: n = %zu is out of range: allowed [0, %d]", n,
                             AUTOBAL_MATCH_MAXN);
  if (n == 0) {
    if (max_dist) *max_dist = 0.0;
    return AUTOBAL_SUCCESS;
  }
  if (a_re == NULL || a_im == NULL || b_re == NULL || b_im == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_match_roots: NULL argument");
  nn = n * n;
  for (i = 0; i < n; i++)
    for (j = 0; j < n; j++) {
      double d = hypot(a_re[i] - b_re[j], a_im[i] - b_im[j]);
      if (!(d == d)) d = INFINITY; /* NaN: never preferred */
      dist[i * n + j] = d;
      sorted[i * n + j] = d;
    }
  qsort(sorted, nn, sizeof(double), cmp_double);
  /* smallest threshold (among the n^2 distances) admitting a perfect matching */
  lo = 0;
  hi = nn - 1; /* the largest distance always admits one */
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (match_perfect(n, dist, sorted[mid], owner)) hi = mid;
    else lo = mid + 1;
  }
  match_perfect(n, dist, sorted[lo], owner);
  if (perm)
    for (j = 0; j < n; j++) perm[owner[j]] = j;
  if (max_dist) *max_dist = sorted[lo];
  return AUTOBAL_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Routh-Hurwitz with running error bounds                                  */
/* ------------------------------------------------------------------------ */

int autobal_poly_hurwitz_err(const double *c, const double *cerr, size_t len, int *verdict,
                             int *n_rhp, autobal_error *err) {
  /* Routh array: three rotating rows of width n/2 + 1 (values and bounds).
   * Row t has len(t) = (n - t)/2 + 1 entries; the rest of the fixed width
   * is structural zeros (value and bound 0), which never reach the first
   * column of rows <= n (entry j of row t+1 depends on entries j+1 of rows
   * t and t-1), so only the len(t+1) entries of each new row are computed,
   * reading the structural zero y = 0 at the end of row t where needed. */
  double rb[3][AUTOBAL_POLY_MAXLEN / 2 + 1], eb[3][AUTOBAL_POLY_MAXLEN / 2 + 1];
  const double u = DBL_EPSILON;
  size_t n, width, i, j, row, i0 = 0, i1 = 1, i2 = 2;
  double sgn;
  int changes = 0, prev_sign, decided = 1;
  if (c == NULL || verdict == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_poly_hurwitz: NULL argument");
  if (len < 2 || len > AUTOBAL_POLY_MAXLEN)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_hurwitz: len = %zu is out of range: allowed [2, %d]", len,
                             AUTOBAL_POLY_MAXLEN);
  for (i = 0; i < len; i++) {
    if (!isfinite(c[i]))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "autobal_poly_hurwitz: coefficient c[%zu] = %g is not finite", i,
                               c[i]);
    if (cerr && !(cerr[i] >= 0.0 && isfinite(cerr[i])))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "autobal_poly_hurwitz: error bound cerr[%zu] = %g is out of range: "
                               "allowed [0, inf)",
                               i, cerr[i]);
  }
  n = len - 1;
  if (c[n] == 0.0)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_hurwitz: leading coefficient c[%zu] is zero", n);
  sgn = c[n] > 0 ? 1.0 : -1.0;
  width = n / 2 + 1;
  for (j = 0; j < width; j++) {
    /* row 0: c[n], c[n-2], ...; row 1: c[n-1], c[n-3], ... */
    size_t k0 = 2 * j, k1 = 2 * j + 1;
    rb[0][j] = k0 <= n ? sgn * c[n - k0] : 0.0;
    eb[0][j] = k0 <= n ? (cerr ? cerr[n - k0] : 0.0) + u * fabs(c[n - k0]) : 0.0;
    rb[1][j] = k1 <= n ? sgn * c[n - k1] : 0.0;
    eb[1][j] = k1 <= n ? (cerr ? cerr[n - k1] : 0.0) + u * fabs(c[n - k1]) : 0.0;
  }
  prev_sign = 1; /* rb[0][0] > 0 after normalisation */
  for (row = 1; row <= n; row++) {
    /* first-column entry of this row: rb[i1][0] with bound eb[i1][0] */
    double a = rb[i1][0], ea = eb[i1][0];
    int s;
    if (!(fabs(a) > ea)) {
      decided = 0;
      break;
    }
    s = a > 0 ? 1 : -1;
    if (s != prev_sign) changes++;
    prev_sign = s;
    if (row == n) break;
    /* next row: rn[j] = r0[j+1] - q r1[j+1], q = r0[0]/r1[0] */
    {
      double q = rb[i0][0] / a;
      double eq = (eb[i0][0] + fabs(q) * ea) / fabs(a) + u * fabs(q);
      size_t len1 = (n - row) / 2 + 1, len2 = (n - row - 1) / 2 + 1, t;
      for (j = 0; j < len2; j++) {
        /* j + 1 < len(row - 1) = len2 + 1: x is always an entry */
        double x = rb[i0][j + 1], ex = eb[i0][j + 1];
        double y = j + 1 < len1 ? rb[i1][j + 1] : 0.0, ey = j + 1 < len1 ? eb[i1][j + 1] : 0.0;
        rb[i2][j] = x - q * y;
        eb[i2][j] = ex + fabs(q) * ey + fabs(y) * eq + u * (fabs(x) + 2.0 * fabs(q * y));
      }
      t = i0, i0 = i1, i1 = i2, i2 = t;
    }
  }
  if (n_rhp) *n_rhp = changes;
  if (decided) *verdict = changes == 0 ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
  else *verdict = changes > 0 ? AUTOBAL_VERDICT_UNSTABLE : AUTOBAL_VERDICT_MARGINAL;
  return AUTOBAL_SUCCESS;
}

int autobal_poly_hurwitz(const double *c, size_t len, double rtol, int *verdict, int *n_rhp,
                         autobal_error *err) {
  double cerr[AUTOBAL_POLY_MAXLEN];
  size_t i;
  if (!(rtol >= 0.0) || !isfinite(rtol))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter rtol = %g is out of range: allowed [0, inf)", rtol);
  if (c == NULL || len > AUTOBAL_POLY_MAXLEN)
    return autobal_poly_hurwitz_err(c, NULL, len, verdict, n_rhp, err);
  for (i = 0; i < len; i++) cerr[i] = rtol * fabs(c[i]);
  for (i = 0; i < len; i++)
    if (!isfinite(cerr[i])) cerr[i] = 0.0; /* reported as a bad coefficient below */
  return autobal_poly_hurwitz_err(c, cerr, len, verdict, n_rhp, err);
}

int autobal_roots_verdict(size_t n, const double *re, const double *im, double tol,
                          double *max_re) {
  size_t i;
  double m = -INFINITY, scale = 1.0;
  for (i = 0; i < n; i++) {
    double a = hypot(re[i], im[i]);
    if (re[i] > m || re[i] != re[i]) m = re[i];
    if (a > scale) scale = a;
  }
  if (max_re) *max_re = m;
  if (n == 0) return AUTOBAL_VERDICT_STABLE;
  if (m != m) return AUTOBAL_VERDICT_MARGINAL;
  if (m < -tol * scale) return AUTOBAL_VERDICT_STABLE;
  if (m > tol * scale) return AUTOBAL_VERDICT_UNSTABLE;
  return AUTOBAL_VERDICT_MARGINAL;
}

/* ------------------------------------------------------------------------ */
/* Sturm sequences                                                          */
/* ------------------------------------------------------------------------ */

/* sign of p at x (x may be +-inf); p has degree deg, p[deg] != 0 */
static int sturm_sign_at(const double *p, size_t deg, double x) {
  double v;
  if (isinf(x)) {
    int s = p[deg] > 0 ? 1 : -1;
    if (x < 0 && (deg % 2) == 1) s = -s;
    return s;
  }
  v = autobal_poly_eval(p, deg + 1, x);
  return (v > 0) - (v < 0);
}

static size_t sturm_variations(double seq[][AUTOBAL_POLY_MAXLEN], const size_t *deg, size_t m,
                               double x) {
  size_t i, v = 0;
  int last = 0;
  for (i = 0; i < m; i++) {
    int s = sturm_sign_at(seq[i], deg[i], x);
    if (s == 0) continue;
    if (last != 0 && s != last) v++;
    last = s;
  }
  return v;
}

int autobal_poly_sturm_count(const double *c, size_t len, double a, double b, double rtol,
                             int *count, autobal_error *err) {
  double seq[AUTOBAL_POLY_MAXLEN][AUTOBAL_POLY_MAXLEN];
  size_t deg[AUTOBAL_POLY_MAXLEN];
  size_t m, i, j, d;
  double tol;
  if (c == NULL || count == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_poly_sturm_count: NULL argument");
  if (len < 1 || len > AUTOBAL_POLY_MAXLEN)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_sturm_count: len = %zu is out of range: allowed [1, %d]",
                             len, AUTOBAL_POLY_MAXLEN);
  if (!(rtol >= 0.0) || !isfinite(rtol))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter rtol = %g is out of range: allowed [0, inf)", rtol);
  if (isnan(a) || isnan(b) || a > b)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_poly_sturm_count: interval (%g, %g] is empty or NaN", a, b);
  for (i = 0; i < len; i++)
    if (!isfinite(c[i]))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "autobal_poly_sturm_count: coefficient c[%zu] = %g is not finite", i,
                               c[i]);
  tol = rtol > 0 ? rtol : 1e3 * DBL_EPSILON;
  d = autobal_poly_degree(c, len);
  if (d == 0 && c[0] == 0.0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_poly_sturm_count: zero polynomial");
  if (d == 0) {
    *count = 0;
    return AUTOBAL_SUCCESS;
  }
  /* p0 = c, p1 = c', each scaled to max |coef| = 1 (positive scaling keeps signs) */
  for (i = 0; i <= d; i++) seq[0][i] = c[i];
  deg[0] = d;
  for (i = 0; i < d; i++) seq[1][i] = (double)(i + 1) * c[i + 1];
  deg[1] = d - 1;
  m = 2;
  for (j = 0; j < 2; j++) {
    double s = 0.0;
    for (i = 0; i <= deg[j]; i++)
      if (fabs(seq[j][i]) > s) s = fabs(seq[j][i]);
    for (i = 0; i <= deg[j]; i++) seq[j][i] /= s;
  }
  while (deg[m - 1] > 0) {
    const double *p = seq[m - 2], *q = seq[m - 1];
    size_t dp = deg[m - 2], dq = deg[m - 1];
    double r[AUTOBAL_POLY_MAXLEN];
    double s = 0.0, scale = 0.0;
    size_t dr;
    for (i = 0; i <= dp; i++) r[i] = p[i];
    for (i = dp + 1; i-- > dq;) {
      double f = r[i] / q[dq];
      for (j = 0; j <= dq; j++) r[i - dq + j] -= f * q[j];
      r[i] = 0.0;
    }
    for (i = 0; i <= dp; i++)
      if (fabs(p[i]) > scale) scale = fabs(p[i]);
    /* remainder has degree < dq; entries below tol*scale are rounding noise */
    for (i = 0; i < dq; i++) {
      if (fabs(r[i]) <= tol * scale) r[i] = 0.0;
      if (fabs(r[i]) > s) s = fabs(r[i]);
    }
    if (s == 0.0) break; /* p_{m-1} is the gcd: sequence complete */
    dr = autobal_poly_degree(r, dq);
    for (i = 0; i <= dr; i++) seq[m][i] = -r[i] / s;
    deg[m] = dr;
    m++;
    if (m >= AUTOBAL_POLY_MAXLEN) break;
  }
  {
    size_t va = sturm_variations(seq, deg, m, a);
    size_t vb = sturm_variations(seq, deg, m, b);
    *count = (int)va - (int)vb;
  }
  return AUTOBAL_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Brent's method and bisection of a predicate                              */
/* ------------------------------------------------------------------------ */

int autobal_root_brent(autobal_scalar_fn f, void *ctx, double a, double b, double xtol_abs,
                       double xtol_rel, int max_iter, double *root, autobal_error *err) {
  double fa, fb, c, fc, d, e;
  int st, it;
  if (f == NULL || root == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_root_brent: NULL argument");
  if (!(xtol_abs >= 0.0) || !(xtol_rel >= 0.0) || !isfinite(xtol_abs) || !isfinite(xtol_rel) ||
      (xtol_abs == 0.0 && xtol_rel == 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_root_brent: tolerances xtol_abs = %g, xtol_rel = %g: need "
                             ">= 0, finite, not both 0",
                             xtol_abs, xtol_rel);
  if (max_iter < 1)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter max_iter = %d is out of range: allowed [1, inf)", max_iter);
  if (!isfinite(a) || !isfinite(b))
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_root_brent: bracket [%g, %g] not finite",
                             a, b);
  if ((st = f(a, ctx, &fa)) != AUTOBAL_SUCCESS) return st;
  if ((st = f(b, ctx, &fb)) != AUTOBAL_SUCCESS) return st;
  if (fa == 0.0) {
    *root = a;
    return AUTOBAL_SUCCESS;
  }
  if (fb == 0.0) {
    *root = b;
    return AUTOBAL_SUCCESS;
  }
  if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0)))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_root_brent: f(a) = %g and f(b) = %g at a = %.17g, b = %.17g "
                             "do not bracket a root",
                             fa, fb, a, b);
  c = a;
  fc = fa;
  d = e = b - a;
  for (it = 0; it < max_iter; it++) {
    double tol, m, p, q, r, s;
    if ((fb > 0 && fc > 0) || (fb < 0 && fc < 0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (fabs(fc) < fabs(fb)) {
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    tol = 2.0 * DBL_EPSILON * fabs(b) + 0.5 * (xtol_abs + xtol_rel * fabs(b));
    m = 0.5 * (c - b);
    if (fabs(m) <= tol || fb == 0.0) {
      *root = b;
      return AUTOBAL_SUCCESS;
    }
    if (fabs(e) >= tol && fabs(fa) > fabs(fb)) {
      s = fb / fa;
      if (a == c) {
        p = 2.0 * m * s;
        q = 1.0 - s;
      } else {
        q = fa / fc;
        r = fb / fc;
        p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0));
        q = (q - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0) q = -q;
      else p = -p;
      if (2.0 * p < 3.0 * m * q - fabs(tol * q) && p < fabs(0.5 * e * q)) {
        e = d;
        d = p / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    if (fabs(d) > tol) b += d;
    else b += m > 0 ? tol : -tol;
    if ((st = f(b, ctx, &fb)) != AUTOBAL_SUCCESS) return st;
  }
  *root = b;
  return autobal_error_set(err, AUTOBAL_ENUMERIC,
                           "autobal_root_brent: no convergence in max_iter = %d iterations (best "
                           "estimate %.17g)",
                           max_iter, b);
}

int autobal_bisect_change(autobal_predicate_fn p, void *ctx, double a, double b, double xtol_abs,
                          double xtol_rel, double *lo, double *hi, autobal_error *err) {
  int pa, pb, st;
  if (p == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_bisect_change: NULL predicate");
  if (!isfinite(a) || !isfinite(b) || !(a < b))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_bisect_change: bracket [%g, %g] must be finite with a < b", a,
                             b);
  if (!(xtol_abs >= 0.0) || !(xtol_rel >= 0.0) || !isfinite(xtol_abs) || !isfinite(xtol_rel) ||
      (xtol_abs == 0.0 && xtol_rel == 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_bisect_change: tolerances xtol_abs = %g, xtol_rel = %g: need "
                             ">= 0, finite, not both 0",
                             xtol_abs, xtol_rel);
  if ((st = p(a, ctx, &pa)) != AUTOBAL_SUCCESS) return st;
  if ((st = p(b, ctx, &pb)) != AUTOBAL_SUCCESS) return st;
  if (pa == pb)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_bisect_change: the predicate has the same value %d at both "
                             "ends %.17g and %.17g",
                             pa, a, b);
  while (b - a > xtol_abs + xtol_rel * fabs(b)) {
    double mid = a + 0.5 * (b - a);
    int pm;
    if (mid <= a || mid >= b) break; /* adjacent doubles */
    if ((st = p(mid, ctx, &pm)) != AUTOBAL_SUCCESS) return st;
    if (pm == pa) a = mid;
    else b = mid;
  }
  if (lo) *lo = a;
  if (hi) *hi = b;
  return AUTOBAL_SUCCESS;
}
