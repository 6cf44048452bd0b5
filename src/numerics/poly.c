/* poly.c: model-agnostic polynomial arithmetic, roots, eigenvalues, root
 * matching.  The sign tests (Routh-Hurwitz, Sturm) are in sign_tests.c, bracketed root
 * finding in root_bracket.c.  See include/autobal/stability.h for the contracts.
 *
 * May use: core (internal.h), GSL, libm.  No model, no I/O. */
#include "autobal/stability.h"
#include "internal.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_poly.h>
#include <gsl/gsl_vector.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

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
  gsl_poly_complex_workspace *w; /* last fall-back solver */
  double *z;                     /* 2*degree packed complex roots (GSL) */
  double *h;                     /* degree x degree companion matrix */
  double *ab;                    /* Aberth: nrm[n], ca[n+1], starting-point tables */
  unsigned char *flag;           /* Aberth: done[n], used[n] */
  double *cs;                    /* degree + 1 scaled coefficients */
};

/* ---- eigenvalues of a small upper Hessenberg matrix ------------------------
 * The Francis double-shift QR iteration of LAPACK's DLAHQR (version 3.x, with
 * the Ahues-Tisseur deflation test and DLANV2 for the final 2 x 2 blocks),
 * eigenvalues only: the reflectors are applied to the active block
 * h[l..i][l..i] alone.  h is row-major with leading dimension ld and is
 * overwritten.  Returns 0, or -1 when an eigenvalue did not converge in
 * 30 max(10, n) iterations (the caller falls back to GSL). */
#define HH(r, c) h[(size_t)(r) * ld + (size_t)(c)]

/* Fortran SIGN(a, b) */
static double sign_of(double a, double b) { return (b >= 0.0) ? fabs(a) : -fabs(a); }

/* eigenvalues of the real 2 x 2 [[a, b], [c, d]] (DLANV2, Schur factor not formed) */
static void eig2_standard(double a, double b, double c, double d, double *rt1r, double *rt1i,
                          double *rt2r, double *rt2i) {
  const double eps = DBL_EPSILON;
  if (c == 0.0) {
    /* already upper triangular */
  } else if (b == 0.0) {
    double t = d; /* swap rows and columns */
    d = a;
    a = t;
    b = -c;
    c = 0.0;
  } else if ((a - d) == 0.0 && (b >= 0.0) != (c >= 0.0)) {
    /* standard complex block */
  } else {
    const double temp = a - d;
    double p = 0.5 * temp;
    const double bcmax = fmax(fabs(b), fabs(c));
    const double bcmis = fmin(fabs(b), fabs(c)) * sign_of(1.0, b) * sign_of(1.0, c);
    const double scale = fmax(fabs(p), bcmax);
    double z = (p / scale) * p + (bcmax / scale) * bcmis;
    if (z >= 4.0 * eps) {
      /* real eigenvalues */
      z = p + sign_of(sqrt(scale) * sqrt(z), p);
      a = d + z;
      d = d - (bcmax / z) * bcmis;
      b = b - c;
      c = 0.0;
    } else {
      /* complex or nearly equal real eigenvalues: make the diagonal equal */
      const double sigma = b + c;
      const double tau = hypot(sigma, temp);
      const double cs = sqrt(0.5 * (1.0 + fabs(sigma) / tau));
      const double sn = -(p / (tau * cs)) * sign_of(1.0, sigma);
      const double aa = a * cs + b * sn, bb = -a * sn + b * cs;
      const double cc = c * cs + d * sn, dd = -c * sn + d * cs;
      double mid;
      a = aa * cs + cc * sn;
      b = bb * cs + dd * sn;
      c = -aa * sn + cc * cs;
      d = -bb * sn + dd * cs;
      mid = 0.5 * (a + d);
      a = mid;
      d = mid;
      if (c != 0.0) {
        if (b != 0.0) {
          if ((b >= 0.0) == (c >= 0.0)) {
            /* real eigenvalues */
            const double sab = sqrt(fabs(b)), sac = sqrt(fabs(c));
            p = sign_of(sab * sac, c);
            a = mid + p;
            d = mid - p;
            b = b - c;
            c = 0.0;
          }
        } else {
          b = -c;
          c = 0.0;
        }
      }
    }
  }
  *rt1r = a;
  *rt2r = d;
  if (c == 0.0) {
    *rt1i = 0.0;
    *rt2i = 0.0;
  } else {
    *rt1i = sqrt(fabs(b)) * sqrt(fabs(c));
    *rt2i = -*rt1i;
  }
}

static double dmax(double a, double b) { return a > b ? a : b; }
static double dmin(double a, double b) { return a < b ? a : b; }

static int hessenberg_eigvals(int n, double *h, size_t ld, double *wr, double *wi) {
  const double ulp = DBL_EPSILON, safmin = DBL_MIN;
  const double smlnum = safmin * ((double)n / ulp);
  const int itmax = 30 * (n > 10 ? n : 10), kexsh = 10;
  const double dat1 = 0.75, dat2 = -0.4375;
  int i = n - 1, kdefl = 0;
  int j;
  /* clear out the trash below the subdiagonal */
  for (j = 0; j < n - 3; j++) {
    HH(j + 2, j) = 0.0;
    HH(j + 3, j) = 0.0;
  }
  if (n >= 3) HH(n - 1, n - 3) = 0.0;
  while (i >= 0) {
    int l = 0, its, converged = 0;
    for (its = 0; its <= itmax; its++) {
      int k, m;
      double h11, h12, h21, h22, s, rt1r, rt1i, rt2r, rt2i, v[3] = {0.0, 0.0, 0.0};
      /* look for a single small subdiagonal element */
      for (k = i; k > l; k--) {
        double tst, hkk1 = fabs(HH(k, k - 1));
        if (hkk1 <= smlnum) break;
        tst = fabs(HH(k - 1, k - 1)) + fabs(HH(k, k));
        if (tst == 0.0) {
          if (k - 2 >= 0) tst += fabs(HH(k - 1, k - 2));
          if (k + 1 <= n - 1) tst += fabs(HH(k + 1, k));
        }
        if (hkk1 <= ulp * tst) {
          const double hk1k = fabs(HH(k - 1, k));
          const double ab = dmax(hkk1, hk1k), ba = dmin(hkk1, hk1k);
          const double dk = fabs(HH(k - 1, k - 1) - HH(k, k));
          const double aa = dmax(fabs(HH(k, k)), dk), bb = dmin(fabs(HH(k, k)), dk);
          s = aa + ab;
          if (ba * (ab / s) <= dmax(smlnum, ulp * (bb * (aa / s)))) break;
        }
      }
      l = k;
      if (l > 0) HH(l, l - 1) = 0.0;
      if (l >= i - 1) {
        converged = 1;
        break;
      }
      kdefl++;
      /* shifts */
      if (kdefl % (2 * kexsh) == 0) { /* exceptional shift */
        s = fabs(HH(i, i - 1)) + fabs(HH(i - 1, i - 2));
        h11 = dat1 * s + HH(i, i);
        h12 = dat2 * s;
        h21 = s;
        h22 = h11;
      } else if (kdefl % kexsh == 0) {
        s = fabs(HH(l + 1, l)) + fabs(HH(l + 2, l + 1));
        h11 = dat1 * s + HH(l, l);
        h12 = dat2 * s;
        h21 = s;
        h22 = h11;
      } else {
        h11 = HH(i - 1, i - 1);
        h21 = HH(i, i - 1);
        h12 = HH(i - 1, i);
        h22 = HH(i, i);
      }
      s = fabs(h11) + fabs(h12) + fabs(h21) + fabs(h22);
      if (s == 0.0) {
        rt1r = rt1i = rt2r = rt2i = 0.0;
      } else {
        double tr, det, rtdisc;
        h11 /= s;
        h21 /= s;
        h12 /= s;
        h22 /= s;
        tr = (h11 + h22) / 2.0;
        det = (h11 - tr) * (h22 - tr) - h12 * h21;
        rtdisc = sqrt(fabs(det));
        if (det >= 0.0) { /* complex conjugate shifts */
          rt1r = tr * s;
          rt2r = rt1r;
          rt1i = rtdisc * s;
          rt2i = -rt1i;
        } else { /* real shifts: use only one of them, twice */
          rt1r = tr + rtdisc;
          rt2r = tr - rtdisc;
          if (fabs(rt1r - h22) <= fabs(rt2r - h22)) {
            rt1r *= s;
            rt2r = rt1r;
          } else {
            rt2r *= s;
            rt1r = rt2r;
          }
          rt1i = rt2i = 0.0;
        }
      }
      /* look for two consecutive small subdiagonal elements */
      for (m = i - 2; m >= l; m--) {
        double h21s = HH(m + 1, m), h00, h01;
        s = fabs(HH(m, m) - rt2r) + fabs(rt2i) + fabs(h21s);
        h21s = HH(m + 1, m) / s;
        v[0] = h21s * HH(m, m + 1) + (HH(m, m) - rt1r) * ((HH(m, m) - rt2r) / s) - rt1i * (rt2i / s);
        v[1] = h21s * (HH(m, m) + HH(m + 1, m + 1) - rt1r - rt2r);
        v[2] = h21s * HH(m + 2, m + 1);
        s = fabs(v[0]) + fabs(v[1]) + fabs(v[2]);
        v[0] /= s;
        v[1] /= s;
        v[2] /= s;
        if (m == l) break;
        h00 = fabs(HH(m, m - 1)) * (fabs(v[1]) + fabs(v[2]));
        h01 = fabs(v[0]) * (fabs(HH(m - 1, m - 1)) + fabs(HH(m, m)) + fabs(HH(m + 1, m + 1)));
        if (h00 <= ulp * h01) break;
      }
      /* double-shift QR sweep on rows/columns l..i */
      for (k = m; k <= i - 1; k++) {
        const int nr = (i - k + 1 < 3) ? i - k + 1 : 3;
        double alpha, xnorm, t1, v2, t2;
        int jj;
        if (k > m) {
          v[0] = HH(k, k - 1);
          v[1] = HH(k + 1, k - 1);
          if (nr == 3) v[2] = HH(k + 2, k - 1);
        }
        /* DLARFG: reflector I - t1 (1, v2, v3)(1, v2, v3)^T mapping v to (beta, 0, 0) */
        alpha = v[0];
        xnorm = (nr == 3) ? v[1] * v[1] + v[2] * v[2] : v[1] * v[1]; /* squared */
        if (xnorm == 0.0) {
          t1 = 0.0;
        } else {
          /* plain sums of squares (hypot is ~10x slower); v was scaled to
           * |v| ~ 1 above or holds entries of the balanced matrix */
          double nrm = sqrt(alpha * alpha + xnorm);
          double beta;
          if (!(nrm > 1e-150 && nrm < 1e150)) nrm = hypot(alpha, hypot(v[1], nr == 3 ? v[2] : 0.0));
          beta = -sign_of(nrm, alpha);
          const double sc = 1.0 / (alpha - beta);
          t1 = (beta - alpha) / beta;
          v[1] *= sc;
          if (nr == 3) v[2] *= sc;
          v[0] = beta;
        }
        if (k > m) {
          HH(k, k - 1) = v[0];
          HH(k + 1, k - 1) = 0.0;
          if (k < i - 1) HH(k + 2, k - 1) = 0.0;
        } else if (m > l) {
          HH(k, k - 1) *= (1.0 - t1);
        }
        v2 = v[1];
        t2 = t1 * v2;
        if (nr == 3) {
          const double v3 = v[2], t3 = t1 * v3;
          const int jmax = (k + 3 < i) ? k + 3 : i;
          double *r0 = &HH(k, 0), *r1 = &HH(k + 1, 0), *r2 = &HH(k + 2, 0);
          for (jj = k; jj <= i; jj++) {
            const double sum = r0[jj] + v2 * r1[jj] + v3 * r2[jj];
            r0[jj] -= sum * t1;
            r1[jj] -= sum * t2;
            r2[jj] -= sum * t3;
          }
          for (jj = l; jj <= jmax; jj++) {
            double *rj = &HH(jj, k);
            const double sum = rj[0] + v2 * rj[1] + v3 * rj[2];
            rj[0] -= sum * t1;
            rj[1] -= sum * t2;
            rj[2] -= sum * t3;
          }
        } else {
          double *r0 = &HH(k, 0), *r1 = &HH(k + 1, 0);
          for (jj = k; jj <= i; jj++) {
            const double sum = r0[jj] + v2 * r1[jj];
            r0[jj] -= sum * t1;
            r1[jj] -= sum * t2;
          }
          for (jj = l; jj <= i; jj++) {
            double *rj = &HH(jj, k);
            const double sum = rj[0] + v2 * rj[1];
            rj[0] -= sum * t1;
            rj[1] -= sum * t2;
          }
        }
      }
    }
    if (!converged) return -1;
    if (l == i) {
      wr[i] = HH(i, i);
      wi[i] = 0.0;
    } else { /* l == i - 1 */
      eig2_standard(HH(i - 1, i - 1), HH(i - 1, i), HH(i, i - 1), HH(i, i), &wr[i - 1], &wi[i - 1],
                    &wr[i], &wi[i]);
    }
    kdefl = 0;
    i = l - 1;
  }
  return 0;
}
#undef HH

/* Balance the companion matrix m (nc x nc, row-major: ones on the subdiagonal,
 * -c_i/c_n in the last column) by powers of 2, exploiting its sparsity: the
 * algorithm of GSL's balance_companion_matrix (poly/balance.c), which is the
 * Parlett-Reinsch balancing restricted to the non-zero entries.  Exact: only
 * exponents change. */
static void balance_companion(double *m, size_t nc) {
  int not_converged = 1, pass = 0;
  /* bounded: every entry is finite (checked by the caller), so each inner loop runs at most
   * about 1100 times (the exponent range of a double); the passes are capped too (balancing
   * only improves accuracy: an unfinished one still leaves a similar matrix) */
  while (not_converged && pass++ < 1000) {
    size_t i, j;
    not_converged = 0;
    for (i = 0; i < nc; i++) {
      double col_norm, row_norm, g, f, s;
      /* column norm, excluding the diagonal */
      if (i != nc - 1) {
        col_norm = fabs(m[(i + 1) * nc + i]);
      } else {
        col_norm = 0.0;
        for (j = 0; j < nc - 1; j++) col_norm += fabs(m[j * nc + nc - 1]);
      }
      /* row norm, excluding the diagonal */
      if (i == 0)
        row_norm = fabs(m[nc - 1]);
      else if (i == nc - 1)
        row_norm = fabs(m[i * nc + i - 1]);
      else
        row_norm = fabs(m[i * nc + i - 1]) + fabs(m[i * nc + nc - 1]);
      if (col_norm == 0.0 || row_norm == 0.0) continue;
      g = row_norm / 2.0;
      f = 1.0;
      s = col_norm + row_norm;
      while (col_norm < g && f < 0x1p500) {
        f *= 2.0;
        col_norm *= 4.0;
      }
      g = row_norm * 2.0;
      while (col_norm > g && f > 0x1p-500) {
        f /= 2.0;
        col_norm /= 4.0;
      }
      if ((row_norm + col_norm) < 0.95 * s * f) {
        not_converged = 1;
        g = 1.0 / f;
        if (i == 0) {
          m[nc - 1] *= g;
        } else {
          m[i * nc + i - 1] *= g;
          m[i * nc + nc - 1] *= g;
        }
        if (i == nc - 1)
          for (j = 0; j < nc; j++) m[j * nc + i] *= f;
        else
          m[(i + 1) * nc + i] *= f;
      }
    }
  }
}

/* ---- Aberth-Ehrlich iteration --------------------------------------------
 * All roots of a real polynomial at once (O. Aberth, Math. Comp. 27 (1973);
 * L. W. Ehrlich, Comm. ACM 10 (1967)) with the starting points and the
 * stopping rule of D. A. Bini, Numer. Algorithms 13 (1996) (MPSolve):
 *  - start: the moduli from the upper convex hull ("Newton polygon") of
 *    (j, log|c_j|); the m roots of a hull segment of slope -log r are put on
 *    the circle |z| = r at angles 2 pi t/m + 2 pi s/n + 0.7 (s = segment);
 *  - update (Gauss-Seidel): N = p(z_i)/p'(z_i),
 *    z_i <- z_i - N / (1 - N sum_{j != i} 1/(z_i - z_j));
 *  - a root is accepted when |p(z_i)| <= 4 n eps sum_j |c_j| |z_i|^j (it is
 *    then an exact root of a polynomial whose coefficients differ from c by
 *    a relative 4 n eps: componentwise backward stable), after one more
 *    update (which brings well-conditioned roots to rounding level).
 * The result is accepted only when the Newton inclusion disks (a disk of
 * radius n |p(z)/p'(z)| about z holds a root; (n + 1) |N| about the updated
 * point) are pairwise disjoint, so that each holds exactly one root.  The
 * real structure is then restored (real_structure): roots whose disk meets
 * the real axis become real (Im = 0 exactly), the others are paired with
 * their mirror images and replaced by exact conjugate pairs.  Anything that
 * does not fit (no convergence in AB_MAXIT sweeps, overlapping disks, i.e.
 * clustered or multiple roots, an odd number of non-real roots, a
 * non-finite value) returns -1 and the caller uses the companion matrix QR
 * instead. */
#define AB_MAXIT 60

/* approximate log2|x| for x != 0 (error < 0.09: enough for the hull) */
static double log2_rough(double x) {
  int e;
  double m = frexp(fabs(x), &e); /* |x| = m 2^e, m in [0.5, 1) */
  return (double)e - 2.0 + 2.0 * m;
}

static int aberth_roots(size_t n, const double *c, double *zr, double *zi, double *nrm,
                        double *ca, unsigned char *done, const double *tab_re,
                        const double *tab_im) {
  const double tol = 4.0 * (double)n * DBL_EPSILON;
  size_t i, j, nconv = 0, it;
  /* Newton polygon: upper convex hull of (j, log2|c_j|), j = 0..n (c_0, c_n != 0) */
  {
    size_t hull[AUTOBAL_POLY_MAXLEN + 1], nh = 0, s;
    double lg[AUTOBAL_POLY_MAXLEN + 1];
    if (n + 1 > AUTOBAL_POLY_MAXLEN) return -1;
    for (j = 0; j <= n; j++) {
      ca[j] = fabs(c[j]);
      lg[j] = (c[j] != 0.0) ? log2_rough(c[j]) : -HUGE_VAL;
    }
    for (j = 0; j <= n; j++) {
      if (c[j] == 0.0) continue;
      while (nh >= 2) { /* pop while the last point is not strictly above the chord */
        const size_t a = hull[nh - 2], b = hull[nh - 1];
        if ((lg[b] - lg[a]) * (double)(j - a) <= (lg[j] - lg[a]) * (double)(b - a)) nh--;
        else break;
      }
      hull[nh++] = j;
    }
    i = 0;
    for (s = 0; s + 1 < nh; s++) {
      const size_t a = hull[s], b = hull[s + 1], m = b - a;
      const double r = exp2((lg[a] - lg[b]) / (double)m);
      const double rot_re = tab_re[n * (n + 1) / 2 + s], rot_im = tab_im[n * (n + 1) / 2 + s];
      size_t t;
      for (t = 0; t < m; t++, i++) {
        const double ur = tab_re[m * (m - 1) / 2 + t], ui = tab_im[m * (m - 1) / 2 + t];
        zr[i] = r * (ur * rot_re - ui * rot_im);
        zi[i] = r * (ur * rot_im + ui * rot_re);
        done[i] = 0;
      }
    }
    if (i != n) return -1;
  }
  for (it = 0; it < AB_MAXIT && nconv < n; it++) {
    for (i = 0; i < n; i++) {
      double x, y, pr, pi, dr, di, b, ax, den, Nr, Ni, sr = 0.0, si = 0.0, tr, ti, q;
      if (done[i] == 2) continue;
      x = zr[i];
      y = zi[i];
      ax = sqrt(x * x + y * y);
      pr = c[n];
      pi = 0.0;
      dr = 0.0;
      di = 0.0;
      b = ca[n];
      for (j = n; j-- > 0;) {
        const double t1 = dr * x - di * y + pr, t2 = pr * x - pi * y + c[j];
        di = dr * y + di * x + pi;
        dr = t1;
        pi = pr * y + pi * x;
        pr = t2;
        b = b * ax + ca[j];
      }
      if (done[i] == 0 && pr * pr + pi * pi <= (tol * b) * (tol * b)) done[i] = 1;
      den = dr * dr + di * di;
      if (!(den > 0.0) || !isfinite(den)) {
        if (done[i] == 1 || (pr == 0.0 && pi == 0.0)) { /* exact root or p' = 0 at an accepted point */
          nrm[i] = 0.0;
          done[i] = 2;
          nconv++;
          continue;
        }
        return -1;
      }
      den = 1.0 / den;
      Nr = (pr * dr + pi * di) * den;
      Ni = (pi * dr - pr * di) * den;
      nrm[i] = (double)(n + 1) * sqrt(Nr * Nr + Ni * Ni); /* inclusion radius about the update */
      for (j = 0; j < n; j++) {
        double ur, ui;
        if (j == i) continue;
        ur = x - zr[j];
        ui = y - zi[j];
        q = ur * ur + ui * ui;
        if (q > 0.0) {
          q = 1.0 / q;
          sr += ur * q;
          si -= ui * q;
        }
      }
      tr = 1.0 - (Nr * sr - Ni * si);
      ti = -(Nr * si + Ni * sr);
      q = tr * tr + ti * ti;
      if (q > 0.0 && isfinite(q)) {
        q = 1.0 / q;
        zr[i] = x - (Nr * tr + Ni * ti) * q;
        zi[i] = y - (Ni * tr - Nr * ti) * q;
      }
      if (done[i] == 1) { /* accepted: this was the final update */
        done[i] = 2;
        nconv++;
      }
    }
  }
  if (nconv < n) return -1;
  for (i = 0; i < n; i++)
    if (!isfinite(zr[i]) || !isfinite(zi[i])) return -1;
  return 0;
}

/* Restore the structure of the roots of a real polynomial (see above):
 * real roots get Im = 0, the others exact conjugate pairs.  -1 when the
 * non-real roots do not pair up. */
static int real_structure(size_t n, double *zr, double *zi, const double *nrm,
                          unsigned char *used) {
  size_t i, j, nup = 0, nlo = 0;
  /* every root alone in its inclusion disk (else: a cluster, left to the QR,
   * whose eigenvalues of one perturbed matrix keep e.g. the cluster's mean) */
  for (i = 0; i < n; i++)
    for (j = i + 1; j < n; j++) {
      const double dr = zr[i] - zr[j], di = zi[i] - zi[j], rad = nrm[i] + nrm[j];
      if (dr * dr + di * di <= rad * rad) return -1;
    }
  for (i = 0; i < n; i++) {
    used[i] = 0;
    if (fabs(zi[i]) <= nrm[i] + 4.0 * DBL_EPSILON * fabs(zr[i])) zi[i] = 0.0;
    else if (zi[i] > 0.0) nup++;
    else nlo++;
  }
  if (nup != nlo) return -1;
  for (i = 0; i < n; i++) {
    size_t best = n;
    double bd = HUGE_VAL;
    if (!(zi[i] > 0.0)) continue;
    for (j = 0; j < n; j++) {
      double d;
      if (used[j] || !(zi[j] < 0.0)) continue;
      d = fabs(zr[j] - zr[i]) + fabs(zi[j] + zi[i]);
      if (d < bd) {
        bd = d;
        best = j;
      }
    }
    /* the mirror image must lie within the two inclusion radii */
    if (best == n || bd > 2.0 * (nrm[i] + nrm[best]) + 16.0 * DBL_EPSILON * (fabs(zr[i]) + zi[i]))
      return -1;
    used[best] = 1;
    {
      const double mr = 0.5 * (zr[i] + zr[best]), mi = 0.5 * (zi[i] - zi[best]);
      zr[i] = zr[best] = mr;
      zi[i] = mi;
      zi[best] = -mi;
    }
  }
  return 0;
}

/* Roots by the balanced companion matrix and hessenberg_eigvals; -1 when the
 * iteration did not converge or produced a non-finite value. */
int autobal_poly_roots_qr(autobal_poly_workspace *w, const double *c, double *re, double *im) {
  const size_t n = w->degree;
  double *h = w->h;
  size_t i;
  if (n == 1) {
    re[0] = -c[0] / c[1];
    im[0] = 0.0;
    return isfinite(re[0]) ? 0 : -1;
  }
  memset(h, 0, n * n * sizeof *h);
  for (i = 1; i < n; i++) h[i * n + i - 1] = 1.0;
  for (i = 0; i < n; i++) {
    h[i * n + n - 1] = -c[i] / c[n];
    if (!isfinite(h[i * n + n - 1])) return -1; /* c[i] / c[n] overflows: scale first */
  }
  balance_companion(h, n);
  if (hessenberg_eigvals((int)n, h, n, re, im) != 0) return -1;
  for (i = 0; i < n; i++)
    if (!isfinite(re[i]) || !isfinite(im[i])) return -1;
  return 0;
}

autobal_poly_workspace *autobal_poly_workspace_alloc(size_t degree) {
  autobal_poly_workspace *w;
  /* the size check comes first: the counts below must not overflow */
  if (degree < 1 || degree > AUTOBAL_POLY_MAX_DEGREE) return NULL;
  w = (autobal_poly_workspace *)calloc(1, sizeof *w);
  if (w == NULL) return NULL;
  w->degree = degree;
  {
    /* gsl_poly_complex_workspace_alloc reports n < 2 through the error
     * handler; degree >= 1 means n = degree + 1 >= 2. */
    w->w = gsl_poly_complex_workspace_alloc(degree + 1);
  }
  w->z = (double *)calloc(2 * degree, sizeof(double));
  w->h = (double *)malloc(degree * degree * sizeof(double));
  w->ab = (double *)malloc((2 * degree + 1 + 2 * (degree * (degree + 1) / 2 + degree)) * sizeof(double));
  w->flag = (unsigned char *)malloc(2 * degree);
  w->cs = (double *)malloc((degree + 1) * sizeof(double));
  if (w->w == NULL || w->z == NULL || w->h == NULL || w->ab == NULL || w->flag == NULL ||
      w->cs == NULL) {
    autobal_poly_workspace_free(w);
    return NULL;
  }
  {
    /* starting-point tables: e^{i (2 pi t/m + 0.7)} at m(m-1)/2 + t (m = 1..n),
     * e^{i 2 pi s/n} at n(n+1)/2 + s */
    const size_t nt = degree * (degree + 1) / 2 + degree;
    double *tre = w->ab + 2 * degree + 1, *tim = tre + nt;
    size_t m, t;
    for (m = 1; m <= degree; m++)
      for (t = 0; t < m; t++) {
        const double a = 2.0 * M_PI * (double)t / (double)m + 0.7;
        tre[m * (m - 1) / 2 + t] = cos(a);
        tim[m * (m - 1) / 2 + t] = sin(a);
      }
    for (t = 0; t < degree; t++) {
      tre[degree * (degree + 1) / 2 + t] = cos(2.0 * M_PI * (double)t / (double)degree);
      tim[degree * (degree + 1) / 2 + t] = sin(2.0 * M_PI * (double)t / (double)degree);
    }
  }
  return w;
}

void autobal_poly_workspace_free(autobal_poly_workspace *w) {
  if (w == NULL) return;
  if (w->w) gsl_poly_complex_workspace_free(w->w);
  free(w->z);
  free(w->cs);
  free(w->h);
  free(w->ab);
  free(w->flag);
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

int autobal_poly_roots_aberth(autobal_poly_workspace *w, const double *c, double *re, double *im) {
  /* exact zero roots first, then Aberth on the rest */
  const size_t n = w->degree, nt = n * (n + 1) / 2 + n;
  size_t i, nz = 0, deg;
  while (nz < n && c[nz] == 0.0) nz++;
  deg = n - nz;
  for (i = 0; i < nz; i++) re[deg + i] = im[deg + i] = 0.0;
  if (deg == 0) return 0;
  if (deg == 1) {
    re[0] = -c[nz] / c[nz + 1];
    im[0] = 0.0;
    return isfinite(re[0]) ? 0 : -1;
  }
  if (aberth_roots(deg, c + nz, re, im, w->ab, w->ab + n, w->flag, w->ab + 2 * n + 1,
                   w->ab + 2 * n + 1 + nt) != 0)
    return -1;
  return real_structure(deg, re, im, w->ab, w->flag + n);
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
  {
    /* 2^k about the geometric mean of the roots' moduli (|c_nz / c_n|^(1/(n - nz)), nz =
     * number of zero roots) and the exponent range of the coefficients; with |k| n or the
     * range near the double's exponent range the powers of the roots and the ratios c_i / c_n
     * over- or underflow, and the scaled problem below is solved directly */
    const size_t n = w->degree;
    size_t nz = 0;
    int k, emax = INT_MIN, emin = INT_MAX, r1, r2;
    while (nz < n && c[nz] == 0.0) nz++;
    k = nz < n ? (int)lround((double)(ilogb(c[nz]) - ilogb(c[n])) / (double)(n - nz)) : 0;
    for (i = 0; i < len; i++)
      if (c[i] != 0.0) {
        if (ilogb(c[i]) < emin) emin = ilogb(c[i]);
        if (ilogb(c[i]) > emax) emax = ilogb(c[i]);
      }
    if (abs(k) * (int)(n < 64 ? n : 64) < 900 && emax - emin < 1800 &&
        (autobal_poly_roots_aberth(w, c, re, im) == 0 || autobal_poly_roots_qr(w, c, re, im) == 0)) {
      sort_pairs(w->degree, re, im);
      return AUTOBAL_SUCCESS;
    }
    /* Extreme scaling, or neither method settled: solve for z = x / 2^k with the
     * coefficients c_j 2^(j k) normalised by a power of 2 (exact unless a negligible one
     * underflows), then x = 2^k z. */
    emax = INT_MIN;
    for (i = 0; i < len; i++)
      if (c[i] != 0.0 && ilogb(c[i]) + (int)i * k > emax) emax = ilogb(c[i]) + (int)i * k;
    for (i = 0; i < len; i++) w->cs[i] = c[i] == 0.0 ? 0.0 : ldexp(c[i], (int)i * k - emax);
    r1 = autobal_poly_roots_aberth(w, w->cs, re, im);
    r2 = r1 == 0 ? 0 : autobal_poly_roots_qr(w, w->cs, re, im);
    if (r2 != 0) {
      /* last resort (not seen in practice): GSL's companion QR (EISPACK hqr) on the scaled
       * coefficients, when their companion matrix is finite (GSL's balancing does not stop
       * on infinite entries) */
      for (i = 0; i < n; i++)
        if (!isfinite(w->cs[i] / w->cs[n])) {
          for (i = 0; i < n; i++) re[i] = im[i] = NAN;
          return autobal_error_set(err, AUTOBAL_ENUMERIC,
                                   "autobal_poly_roots: the roots of this degree-%zu polynomial "
                                   "span more than the double range (coefficient ratio "
                                   "c[%zu]/c[%zu] overflows even after scaling)",
                                   n, i, n);
        }
      gs = gsl_poly_complex_solve(w->cs, len, w->w, w->z);
      if (gs != GSL_SUCCESS) {
        for (i = 0; i < n; i++) re[i] = im[i] = NAN;
        return autobal_error_set(err, AUTOBAL_ENUMERIC,
                                 "autobal_poly_roots: gsl_poly_complex_solve: %s",
                                 gsl_strerror(gs));
      }
      for (i = 0; i < n; i++) {
        re[i] = w->z[2 * i];
        im[i] = w->z[2 * i + 1];
      }
    }
    for (i = 0; i < n; i++) {
      re[i] = ldexp(re[i], k);
      im[i] = ldexp(im[i], k);
      if (!isfinite(re[i]) || !isfinite(im[i])) {
        size_t j;
        for (j = 0; j < n; j++) re[j] = im[j] = NAN;
        return autobal_error_set(err, AUTOBAL_ENUMERIC,
                                 "autobal_poly_roots: a root of this degree-%zu polynomial has a "
                                 "modulus beyond the double range (about 1.8e308)",
                                 n);
      }
    }
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

int autobal_poly_roots_once_(const double *c, size_t len, double *re, double *im, autobal_error *err) {
  autobal_poly_workspace *w = autobal_poly_workspace_alloc(len > 1 ? len - 1 : 1);
  int st;
  if (!w) return autobal_error_set(err, AUTOBAL_ENOMEM, "polynomial roots: out of memory");
  st = autobal_poly_roots(w, c, len, re, im, err);
  autobal_poly_workspace_free(w);
  return st;
}
