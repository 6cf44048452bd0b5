/* pendulum.c: the planar two-pendulum autobalancer, stability of the main
 * motion (docs/pendulum.md, equations (2)-(18)).
 * Everything here is dimensionless (see include/autobal/pendulum.h). */
#include "autobal/pendulum.h"
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef AUTOBAL_HAVE_OPENMP
#include <omp.h>
#endif

#define PEND_PI 3.14159265358979323846
#define U_D DBL_EPSILON
#define U_LD LDBL_EPSILON
/* Safety factor on first-order rounding-error bounds (number of operations
 * per coefficient is far below this). */
#define PEND_GAMMA 64.0

/* ======================================================================== */
/* Parameters (2), (3)                                                      */
/* ======================================================================== */

int autobal_pendulum_params_validate(const autobal_pendulum_params *p, autobal_error *err) {
  int st;
  if (p == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum parameters: NULL pointer");
  /* fast path: exactly the conditions checked below */
  if (isfinite(p->R_w) && p->R_w >= 0.0 && isfinite(p->R_m) && p->R_m > 0.0 && p->R_m < 0.5 &&
      isfinite(p->H) && p->H >= 0.0 && isfinite(p->h) && p->h >= 0.0 && isfinite(p->psi0) &&
      p->psi0 >= 0.0 && p->psi0 < PEND_PI / 2)
    return AUTOBAL_SUCCESS;
  if ((st = autobal_check_param(err, "R_w", p->R_w, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "R_m", p->R_m, 0.0, 1, 0.5, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "H", p->H, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "h", p->h, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "psi0", p->psi0, 0.0, 0, PEND_PI / 2, 1, "rad")) != 0)
    return st;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_params_from_k(double R_w, double R_m, double H, double h, double k,
                                   autobal_pendulum_params *out, autobal_error *err) {
  autobal_pendulum_params p;
  int st;
  if (out == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum parameters: NULL output");
  if ((st = autobal_check_param(err, "k", k, 0.0, 0, 1.0, 0, "")) != 0) return st;
  p.R_w = R_w;
  p.R_m = R_m;
  p.H = H;
  p.h = h;
  p.psi0 = 0.5 * asin(sqrt(k)); /* in [0, pi/4]; k = sin^2(2 psi0) */
  if ((st = autobal_pendulum_params_validate(&p, err)) != 0) return st;
  *out = p;
  return AUTOBAL_SUCCESS;
}

double autobal_pendulum_k(const autobal_pendulum_params *p) {
  double s = sin(2.0 * p->psi0);
  return s * s;
}

int autobal_pendulum_params_from_physical(const autobal_pendulum_physical *q,
                                          autobal_pendulum_params *out, autobal_error *err) {
  autobal_pendulum_params p;
  double Ms, w0;
  int st;
  if (q == NULL || out == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum physical parameters: NULL pointer");
  if ((st = autobal_check_param(err, "M", q->M, 0.0, 1, INFINITY, 1, "kg")) != 0) return st;
  if ((st = autobal_check_param(err, "e", q->e, 0.0, 0, INFINITY, 1, "m")) != 0) return st;
  if ((st = autobal_check_param(err, "m", q->m, 0.0, 1, INFINITY, 1, "kg")) != 0) return st;
  if ((st = autobal_check_param(err, "l", q->l, 0.0, 1, INFINITY, 1, "m")) != 0) return st;
  if ((st = autobal_check_param(err, "c", q->c, 0.0, 1, INFINITY, 1, "N/m")) != 0) return st;
  if ((st = autobal_check_param(err, "H1", q->H1, 0.0, 0, INFINITY, 1, "N m s")) != 0) return st;
  if ((st = autobal_check_param(err, "H2", q->H2, 0.0, 0, INFINITY, 1, "N s/m")) != 0) return st;
  if ((st = autobal_check_param(err, "omega", q->omega, 0.0, 0, INFINITY, 1, "rad/s")) != 0)
    return st;
  /* sin psi0 = M e / (2 m l) < 1: the pendulums must be able to balance */
  if ((st = autobal_check_param(err, "M*e", q->M * q->e, 0.0, 0, 2.0 * q->m * q->l, 1,
                                "kg m (limit 2*m*l)")) != 0)
    return st;
  Ms = q->M + 2.0 * q->m;    /* (2) M_sigma */
  w0 = sqrt(q->c / Ms);      /* (2) omega0  */
  p.R_w = q->omega / w0;     /* (3) */
  p.R_m = q->m / Ms;         /* (3) */
  p.H = q->H2 / (w0 * Ms);   /* (3) */
  p.h = q->H1 / (q->m * q->l * q->l * w0); /* (3) */
  p.psi0 = asin(q->M * q->e / (2.0 * q->m * q->l)); /* (3) */
  if ((st = autobal_pendulum_params_validate(&p, err)) != 0) return st;
  *out = p;
  return AUTOBAL_SUCCESS;
}

/* ======================================================================== */
/* Characteristic polynomial (6)                                            */
/* ======================================================================== */

/* a11, a31, a33 of (6) as complex quadratics in lambda (interleaved). */
static void blocks(double R_w, double H, double h, double a11[6], double a31[6], double a33[6]) {
  /* (lambda + i R_w)^2 = lambda^2 + 2 i R_w lambda - R_w^2 */
  a31[0] = -R_w * R_w;
  a31[1] = 0.0;
  a31[2] = 0.0;
  a31[3] = 2.0 * R_w;
  a31[4] = 1.0;
  a31[5] = 0.0;
  /* a11 = a31 + H (lambda + i R_w) + 1 */
  a11[0] = 1.0 - R_w * R_w;
  a11[1] = H * R_w;
  a11[2] = H;
  a11[3] = 2.0 * R_w;
  a11[4] = 1.0;
  a11[5] = 0.0;
  /* a33 = lambda^2 + h lambda */
  a33[0] = 0.0;
  a33[1] = 0.0;
  a33[2] = h;
  a33[3] = 0.0;
  a33[4] = 1.0;
  a33[5] = 0.0;
}

/* ---- lanes ---------------------------------------------------------------
 * The maps evaluate MAP_LANES grid points or k values side by side: with GCC
 * or Clang a vector extension type (plain element-wise IEEE arithmetic, so
 * every lane gives bitwise the result of the same expression in scalar
 * code; no fused multiply-add: C11 mode has FP contraction off), else (or
 * with -DAUTOBAL_NO_VECTOR_EXT) MAP_LANES = 1 and plain doubles.  The scalar entry points below run the
 * same code on broadcast values, so the map and the one-point functions
 * share one implementation of (6) and agree bitwise. */
#if defined(__GNUC__) && !defined(AUTOBAL_NO_VECTOR_EXT)
#define MAP_LANES 4
typedef double mvec __attribute__((vector_size(MAP_LANES * sizeof(double))));
typedef int64_t mmask __attribute__((vector_size(MAP_LANES * sizeof(int64_t))));
#define MV_L(v, l) ((v)[l])
#define MV_BCAST(x) ((mvec){(x), (x), (x), (x)})
#define MV_ABS(a) ((mvec)((mmask)(a) & (mmask){INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX}))
#define MV_CMP(x) ((mmask)(x)) /* lane masks: -1 true, 0 false */
#define MV_MASK0 ((mmask){0, 0, 0, 0})
#else
#define MAP_LANES 1
typedef double mvec;
typedef long long mmask;
#define MV_CMP(x) ((mmask)(x))
#define MV_MASK0 ((mmask)0)
#define MV_L(v, l) (*((void)(l), &(v)))
#define MV_BCAST(x) (x)
#define MV_ABS(a) fabs(a)
#endif

/* The map's hot functions are compiled twice, for AVX2 and for the baseline
 * x86-64, and the best is picked when the library is loaded (GCC function
 * multiversioning, glibc ifunc).  The lanes give the same bits either way
 * (element-wise IEEE arithmetic; AVX2 without FMA). */
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 8 && defined(__x86_64__) && \
    defined(__linux__) && !defined(AUTOBAL_NO_CLONES)
#define MAP_CLONES __attribute__((target_clones("avx2", "default")))
#define MAP_INLINE __attribute__((always_inline)) inline
#else
#define MAP_CLONES
#define MAP_INLINE inline
#endif

/* The two parts of (6): A = P1 conj(P1) with P1 = a11 a33 - R_m a31^2 (15),
 * B = a31^2 conj(a31)^2 = (lambda^2 + W)^4 (W = R_w^2), so that
 * (6) = A - R_m^2 cos^2(2 psi0) B; plus coefficient-wise bounds Aabs of the
 * magnitudes that enter each coefficient of A (for the rounding-error bound;
 * the coefficients of B are positive, they are their own bound).
 * Optionally P1 itself (5 complex coefficients, interleaved).  One lane per
 * entry of R_w (lanes of one vector).
 *
 * Real arithmetic (no complex products): expanding a11 a33 - R_m a31^2 with
 * a31 = (lambda + i R_w)^2 = lambda^2 + 2i R_w lambda - W gives P1 = sum p_j lambda^j,
 *   p4 = 1 - R_m,                  p3 = (H + h) + 2i R_w (1 - 2R_m),
 *   p2 = 1 - W + hH + 6R_m W + i R_w (H + 2h),
 *   p1 = h (1 - W) + i R_w (hH + 4R_m W),   p0 = -R_m W^2,
 * and A_m = sum_{j+l=m} (x_j x_l + y_j y_l) with p_j = x_j + i y_j (the tests
 * check this against the complex products of the blocks and against
 * det(M lambda^2 + C lambda + K)).  Aabs is the same sum over the magnitudes
 * of the terms of x_j, y_j (W - 1 counted as W + 1). */
/* GCC 12 reports the broadcasts below as "may be used uninitialized" in the
 * AVX2 clone of the map (a false positive: every output is assigned). */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
static MAP_INLINE void char_parts_v(const mvec *Rw, double R_m, double H, double h, mvec A[9], mvec Aabs[9],
                         mvec B[9], mvec p1_out[10]) {
  mvec R_w = *Rw, W = R_w * R_w;
  mvec y3 = 2.0 * R_w * (1.0 - 2.0 * R_m);
  mvec x2 = 1.0 - W + h * H + 6.0 * R_m * W, y2 = R_w * (H + 2.0 * h);
  mvec x1 = h * (1.0 - W), y1 = R_w * (h * H + 4.0 * R_m * W);
  mvec x0 = -R_m * W * W;
  mvec xa2 = 1.0 + W + h * H + 6.0 * R_m * W, xa1 = h * (1.0 + W), xa0 = R_m * W * W;
  double x4 = 1.0 - R_m, x3 = H + h, a8 = x4 * x4, a7 = 2.0 * (x4 * x3);
  A[8] = MV_BCAST(a8);
  A[7] = MV_BCAST(a7);
  A[6] = 2.0 * (x4 * x2) + (x3 * x3 + y3 * y3);
  A[5] = 2.0 * (x4 * x1 + x3 * x2 + y3 * y2);
  A[4] = 2.0 * (x4 * x0 + x3 * x1 + y3 * y1) + (x2 * x2 + y2 * y2);
  A[3] = 2.0 * (x3 * x0 + x2 * x1 + y2 * y1);
  A[2] = 2.0 * (x2 * x0) + (x1 * x1 + y1 * y1);
  A[1] = 2.0 * (x1 * x0);
  A[0] = x0 * x0;
  Aabs[8] = MV_BCAST(a8);
  Aabs[7] = MV_BCAST(a7);
  Aabs[6] = 2.0 * (x4 * xa2) + (x3 * x3 + y3 * y3);
  Aabs[5] = 2.0 * (x4 * xa1 + x3 * xa2 + y3 * y2);
  Aabs[4] = 2.0 * (x4 * xa0 + x3 * xa1 + y3 * y1) + (xa2 * xa2 + y2 * y2);
  Aabs[3] = 2.0 * (x3 * xa0 + xa2 * xa1 + y2 * y1);
  Aabs[2] = 2.0 * (xa2 * xa0) + (xa1 * xa1 + y1 * y1);
  Aabs[1] = 2.0 * (xa1 * xa0);
  Aabs[0] = x0 * x0;
  /* B = (lambda^2 + W)^4 */
  B[8] = MV_BCAST(1.0);
  B[6] = 4.0 * W;
  B[4] = 6.0 * W * W;
  B[2] = 4.0 * W * W * W;
  B[0] = W * W * W * W;
  B[7] = B[5] = B[3] = B[1] = MV_BCAST(0.0);
  if (p1_out) {
    p1_out[0] = x0, p1_out[1] = MV_BCAST(0.0);
    p1_out[2] = x1, p1_out[3] = y1;
    p1_out[4] = x2, p1_out[5] = y2;
    p1_out[6] = MV_BCAST(x3), p1_out[7] = y3;
    p1_out[8] = MV_BCAST(x4), p1_out[9] = MV_BCAST(0.0);
  }
}

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

/* (6) from its parts (char_parts_v) for given k (kc = cos^2(2 psi0) = 1 - k),
 * with absolute error bounds cerr (may be NULL):
 * AUTOBAL_PENDULUM_HURWITZ_RTOL relative plus rounding.  Lane-wise. */
static MAP_INLINE void char_poly_from_parts_v(const mvec *Rw, double R_m, const mvec A[9], const mvec Aa[9],
                                   const mvec B[9], const mvec *kp, const mvec *kcp,
                                   mvec coef[9], mvec cerr[9]) {
  size_t j;
  mvec W = *Rw * *Rw, k = *kp, kc = *kcp;
  for (j = 0; j < 9; j++) {
    coef[j] = A[j] - R_m * R_m * kc * B[j]; /* eq. (6) */
    if (cerr)
      cerr[j] = PEND_GAMMA * U_D * (Aa[j] + R_m * R_m * kc * B[j]) +
                AUTOBAL_PENDULUM_HURWITZ_RTOL * MV_ABS(coef[j]);
  }
  /* The constant term is the difference of two terms of size R_m^2 W^4 and
   * cancels catastrophically for small k; its exact value k R_m^2 W^4 (the
   * closed form in docs/pendulum.md, checked in the tests against the arithmetic above)
   * is used instead, so that the structural root lambda = 0 at k = 0 is
   * exact and small k keep the right sign. */
  coef[0] = k * R_m * R_m * W * W * W * W;
  if (cerr) cerr[0] = (4.0 * U_D + AUTOBAL_PENDULUM_HURWITZ_RTOL) * coef[0];
}

/* Scalar forms (lane 0 of broadcast values). */
typedef struct {
  mvec A[9], Aa[9], B[9];
} char_parts_t;

static MAP_INLINE void char_parts(double R_w, double R_m, double H, double h, char_parts_t *P,
                                  double p1_out[10]) {
  mvec Rw = MV_BCAST(R_w), p1[10];
  size_t j;
  char_parts_v(&Rw, R_m, H, h, P->A, P->Aa, P->B, p1_out ? p1 : NULL);
  if (p1_out)
    for (j = 0; j < 10; j++) p1_out[j] = MV_L(p1[j], 0);
}

static MAP_INLINE void char_poly_from_parts(double R_w, double R_m, const char_parts_t *P,
                                            double k, double kc, double coef[9],
                                            double cerr[9]) {
  mvec Rw = MV_BCAST(R_w), kv = MV_BCAST(k), kcv = MV_BCAST(kc), c[9], ce[9];
  size_t j;
  char_poly_from_parts_v(&Rw, R_m, P->A, P->Aa, P->B, &kv, &kcv, c, cerr ? ce : NULL);
  for (j = 0; j < 9; j++) {
    coef[j] = MV_L(c[j], 0);
    if (cerr) cerr[j] = MV_L(ce[j], 0);
  }
}

/* (6) for given k, see char_poly_from_parts */
static MAP_INLINE void char_poly_k(double R_w, double R_m, double H, double h, double k,
                                   double kc, double coef[9], double cerr[9]) {
  char_parts_t P;
  char_parts(R_w, R_m, H, h, &P, NULL);
  char_poly_from_parts(R_w, R_m, &P, k, kc, coef, cerr);
}

static void k_and_kc(const autobal_pendulum_params *p, double *k, double *kc) {
  double s = sin(2.0 * p->psi0), c = cos(2.0 * p->psi0);
  *k = s * s;
  *kc = c * c;
}

int autobal_pendulum_char_blocks(const autobal_pendulum_params *p, double a11[6], double a31[6],
                                 double a33[6], autobal_error *err) {
  double b11[6], b31[6], b33[6];
  int st = autobal_pendulum_params_validate(p, err);
  if (st) return st;
  blocks(p->R_w, p->H, p->h, b11, b31, b33);
  if (a11) memcpy(a11, b11, sizeof b11);
  if (a31) memcpy(a31, b31, sizeof b31);
  if (a33) memcpy(a33, b33, sizeof b33);
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_char_poly(const autobal_pendulum_params *p, double coef[9],
                               autobal_error *err) {
  double k, kc;
  int st = autobal_pendulum_params_validate(p, err);
  if (st) return st;
  if (coef == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "char_poly: NULL output");
  k_and_kc(p, &k, &kc);
  char_poly_k(p->R_w, p->R_m, p->H, p->h, k, kc, coef, NULL);
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_char_p1(const autobal_pendulum_params *p, double p1[10], autobal_error *err) {
  char_parts_t P;
  int st = autobal_pendulum_params_validate(p, err);
  if (st) return st;
  if (p1 == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "char_p1: NULL output");
  char_parts(p->R_w, p->R_m, p->H, p->h, &P, p1);
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_linear_matrices(const autobal_pendulum_params *p, double Mm[16], double C[16],
                                     double K[16], autobal_error *err) {
  double s, c, R, Rm, R2;
  int st = autobal_pendulum_params_validate(p, err);
  if (st) return st;
  s = sin(p->psi0);
  c = cos(p->psi0);
  R = p->R_w;
  R2 = R * R;
  Rm = p->R_m;
  /* eq. (5), q = (xi, eta, alpha, beta); rows are the four equations of (5) */
  if (Mm) {
    const double m[16] = {1, 0, -Rm * c, -Rm * c, 0, 1, -Rm * s, Rm * s,
                          -c, -s, 1, 0, -c, s, 0, 1};
    memcpy(Mm, m, sizeof m);
  }
  if (C) {
    const double d[16] = {p->H, -2 * R, 2 * Rm * R * s, -2 * Rm * R * s,
                          2 * R, p->H, -2 * Rm * R * c, -2 * Rm * R * c,
                          -2 * R * s, 2 * R * c, p->h, 0,
                          2 * R * s, 2 * R * c, 0, p->h};
    memcpy(C, d, sizeof d);
  }
  if (K) {
    const double kk[16] = {1 - R2, -p->H * R, Rm * R2 * c, Rm * R2 * c,
                           p->H * R, 1 - R2, Rm * R2 * s, -Rm * R2 * s,
                           R2 * c, R2 * s, 0, 0,
                           R2 * c, -R2 * s, 0, 0};
    memcpy(K, kk, sizeof kk);
  }
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_first_order_matrix(const autobal_pendulum_params *p, double A[64],
                                        autobal_error *err) {
  double Mm[16], C[16], K[16], aug[4][8];
  size_t i, j, r;
  int st = autobal_pendulum_linear_matrices(p, Mm, C, K, err);
  if (st) return st;
  if (A == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "first_order_matrix: NULL output");
  /* solve M X = [K C] by Gaussian elimination with partial pivoting */
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) {
      aug[i][j] = K[4 * i + j];
      aug[i][4 + j] = C[4 * i + j];
    }
  for (r = 0; r < 4; r++) {
    size_t piv = r;
    double best = fabs(Mm[4 * r + r]);
    for (i = r + 1; i < 4; i++)
      if (fabs(Mm[4 * i + r]) > best) {
        best = fabs(Mm[4 * i + r]);
        piv = i;
      }
    if (!(best > 1e-14))
      return autobal_error_set(err, AUTOBAL_ENUMERIC,
                               "first_order_matrix: mass matrix of (5) is singular (pivot %g)",
                               best);
    if (piv != r) {
      for (j = 0; j < 4; j++) {
        double t = Mm[4 * r + j];
        Mm[4 * r + j] = Mm[4 * piv + j];
        Mm[4 * piv + j] = t;
      }
      for (j = 0; j < 8; j++) {
        double t = aug[r][j];
        aug[r][j] = aug[piv][j];
        aug[piv][j] = t;
      }
    }
    for (i = r + 1; i < 4; i++) {
      double f = Mm[4 * i + r] / Mm[4 * r + r];
      for (j = r; j < 4; j++) Mm[4 * i + j] -= f * Mm[4 * r + j];
      for (j = 0; j < 8; j++) aug[i][j] -= f * aug[r][j];
    }
  }
  for (r = 4; r-- > 0;) {
    for (j = 0; j < 8; j++) {
      double s = aug[r][j];
      for (i = r + 1; i < 4; i++) s -= Mm[4 * r + i] * aug[i][j];
      aug[r][j] = s / Mm[4 * r + r];
    }
  }
  for (i = 0; i < 64; i++) A[i] = 0.0;
  for (i = 0; i < 4; i++) {
    A[8 * i + 4 + i] = 1.0;
    for (j = 0; j < 4; j++) {
      A[8 * (4 + i) + j] = -aug[i][j];         /* -M^{-1} K */
      A[8 * (4 + i) + 4 + j] = -aug[i][4 + j]; /* -M^{-1} C */
    }
  }
  return AUTOBAL_SUCCESS;
}

/* ======================================================================== */
/* Workspace                                                                */
/* ======================================================================== */

#define PEND_MAXDEG 12

struct autobal_pendulum_workspace {
  autobal_poly_workspace *pw[PEND_MAXDEG + 1]; /* roots of degree d = 1..12 */
  autobal_eigen_workspace *ew;
  autobal_error err;
};

autobal_pendulum_workspace *autobal_pendulum_workspace_alloc(void) {
  size_t d;
  autobal_pendulum_workspace *ws = (autobal_pendulum_workspace *)calloc(1, sizeof *ws);
  if (ws == NULL) return NULL;
  for (d = 1; d <= PEND_MAXDEG; d++) {
    ws->pw[d] = autobal_poly_workspace_alloc(d);
    if (ws->pw[d] == NULL) {
      autobal_pendulum_workspace_free(ws);
      return NULL;
    }
  }
  ws->ew = autobal_eigen_workspace_alloc(AUTOBAL_PENDULUM_ORDER);
  if (ws->ew == NULL) {
    autobal_pendulum_workspace_free(ws);
    return NULL;
  }
  autobal_error_clear(&ws->err);
  return ws;
}

void autobal_pendulum_workspace_free(autobal_pendulum_workspace *ws) {
  size_t d;
  if (ws == NULL) return;
  for (d = 0; d <= PEND_MAXDEG; d++) autobal_poly_workspace_free(ws->pw[d]);
  autobal_eigen_workspace_free(ws->ew);
  free(ws);
}

const char *autobal_pendulum_errmsg(const autobal_pendulum_workspace *ws) {
  return ws ? ws->err.message : "";
}

int autobal_pendulum_status(const autobal_pendulum_workspace *ws) {
  return ws ? ws->err.status : AUTOBAL_SUCCESS;
}

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
 * 1. routh_quick: the Routh array of MAP_LANES polynomials of degree n (7 or
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
static MAP_INLINE void routh_quick(size_t n, const mvec *c, const mvec *ce, const mvec *s2p,
                               mvec *col, mvec *colU) {
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
static MAP_INLINE void routh_quick7(const mvec *c, const mvec *ce, const mvec *s2, mvec *col,
                                    mvec *colU) {
  routh_quick(7, c, ce, s2, col, colU);
}
static MAP_INLINE void routh_quick8(const mvec *c, const mvec *ce, const mvec *s2, mvec *col,
                                    mvec *colU) {
  routh_quick(8, c, ce, s2, col, colU);
}


/* Sign test of (6) (coef, cerr from char_poly_from_parts; deflate: k == 0,
 * lambda = 0 divided out) with the maps' two-stage Routh kernel: the
 * verdict and count of autobal_poly_hurwitz_err bitwise (all first-column
 * entries clear twice their row bound, so the full test decides them the
 * same way; else the full test runs, which also reports bad input). */
static MAP_INLINE int sign_test_poly_i(const double coef[9], const double cerr[9], double W,
                                       int deflate, int *verdict, int *n_rhp,
                                       autobal_error *err) {
  mvec c[9], ce[9], col[9], colU[9], s2 = MV_BCAST(W > 1.0 ? W : 1.0);
  double chk = 0.0;
  size_t j, row, n = deflate ? 7 : 8, off = deflate ? 1 : 0;
  int changes = 0, prev = 1, ok;
  for (j = 0; j < 9; j++) {
    c[j] = MV_BCAST(coef[j]);
    ce[j] = MV_BCAST(cerr[j]);
    chk += cerr[j];
  }
  ok = isfinite(chk) && coef[8] > 0 && verdict != NULL;
  if (deflate) routh_quick7(c + 1, ce + 1, &s2, col, colU);
  else routh_quick8(c, ce, &s2, col, colU);
  if (ok) {
    for (row = 1; row <= n && ok; row++) {
      double a = MV_L(col[row], 0);
      int sg = a > 0 ? 1 : -1;
      if (!(fabs(a) > 2.0 * MV_L(colU[row], 0))) ok = 0;
      if (sg != prev) changes++;
      prev = sg;
    }
  }
  if (!ok) return autobal_poly_hurwitz_err(coef + off, cerr + off, n + 1, verdict, n_rhp, err);
  *verdict = changes == 0 ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
  if (n_rhp) *n_rhp = changes;
  return AUTOBAL_SUCCESS;
}

MAP_CLONES static int sign_test_poly(const double coef[9], const double cerr[9], double W,
                                     int deflate, int *verdict, int *n_rhp, autobal_error *err) {
  return sign_test_poly_i(coef, cerr, W, deflate, verdict, n_rhp, err);
}

/* ======================================================================== */
/* Verdicts                                                                 */
/* ======================================================================== */

/* The quick stage of the Routh test (src/numerics/routh_quick.inc, generated by
 * tools/gen_routh_quick.py; see "Quick stage" in src/numerics/poly.c): straight-line
 * scalar code that gives the verdict and count of the full test
 * autobal_poly_hurwitz_err or declines (then the full test runs). */
#define AUTOBAL_RQ_INLINE MAP_INLINE
#include "numerics/routh_quick.inc"

/* (6) with its bounds as char_poly_k, in scalar arithmetic, for the
 * single-verdict path: the same expressions as char_parts_v and
 * char_poly_from_parts_v operation for operation, so the same bits
 * (element-wise IEEE arithmetic, no fused multiply-add), without the lanes.
 * Checked against char_poly_k by tests/test_pendulum_fast.c
 * (autobal_pendulum_verdict against autobal_pendulum_analyze and the map:
 * verdicts and counts, also within 3 ulps of stability boundaries).  During
 * development coef and cerr were also compared bit for bit on 4e6 random
 * points, with default, AVX2 and AVX-512 + FMA code generation.  Also mu0,
 * the magnitudes for the quick stage of the Routh test. */
typedef struct {
  double A[9], Aa[9], B[9];
} char_parts_s;

/* |x(lambda)|^2 + |y(lambda)|^2 coefficients for x = x4 l^4 + x3 l^3 + x2 l^2 +
 * x1 l + x0, y = y3 l^3 + y2 l^2 + y1 l (the products of char_parts_v, in
 * its order) */
static MAP_INLINE void abs2_coefs(double x4, double x3, double x2, double x1, double x0, double y3,
                                  double y2, double y1, double *A) {
  A[8] = x4 * x4;
  A[7] = 2.0 * (x4 * x3);
  A[6] = 2.0 * (x4 * x2) + (x3 * x3 + y3 * y3);
  A[5] = 2.0 * (x4 * x1 + x3 * x2 + y3 * y2);
  A[4] = 2.0 * (x4 * x0 + x3 * x1 + y3 * y1) + (x2 * x2 + y2 * y2);
  A[3] = 2.0 * (x3 * x0 + x2 * x1 + y2 * y1);
  A[2] = 2.0 * (x2 * x0) + (x1 * x1 + y1 * y1);
  A[1] = 2.0 * (x1 * x0);
  A[0] = x0 * x0;
}

/* the parts that do not depend on k */
static MAP_INLINE void char_parts_scalar(double R_w, double R_m, double H, double h,
                                         char_parts_s *P) {
  const double W = R_w * R_w;
  const double y3 = 2.0 * R_w * (1.0 - 2.0 * R_m);
  const double x2 = 1.0 - W + h * H + 6.0 * R_m * W, y2 = R_w * (H + 2.0 * h);
  const double x1 = h * (1.0 - W), y1 = R_w * (h * H + 4.0 * R_m * W);
  const double x0 = -R_m * W * W;
  const double xa2 = 1.0 + W + h * H + 6.0 * R_m * W, xa1 = h * (1.0 + W), xa0 = R_m * W * W;
  const double x4 = 1.0 - R_m, x3 = H + h;
  double *B = P->B;
  /* Aa[0] = xa0^2 = x0^2 bitwise (xa0 = -x0 exactly) */
  abs2_coefs(x4, x3, x2, x1, x0, y3, y2, y1, P->A);
  abs2_coefs(x4, x3, xa2, xa1, xa0, y3, y2, y1, P->Aa);
  B[8] = 1.0;
  B[6] = 4.0 * W;
  B[4] = 6.0 * W * W;
  B[2] = 4.0 * W * W * W;
  B[0] = W * W * W * W;
  B[7] = B[5] = B[3] = B[1] = 0.0;
}

/* eps0 of the quick stage for the bounds of (6): their relative part
 * AUTOBAL_PENDULUM_HURWITZ_RTOL plus the rounding of the coefficient; then
 * (cerr + u |coef|) / eps0 = |coef| + K s with s the magnitude sum of the
 * coefficient's terms (cerr = PEND_GAMMA u s + RTOL |coef|) and K below
 * (rounded up by 2^-20, far more than the rounding of these few operations) */
#define PEND_RQ_EPS0 (U_D + AUTOBAL_PENDULUM_HURWITZ_RTOL)
#define PEND_RQ_K (PEND_GAMMA * U_D / PEND_RQ_EPS0 * (1.0 + 0x1p-20))

/* (6) for given k = sin^2(2 psi0), kc = cos^2(2 psi0) from the parts */
static MAP_INLINE void char_poly_from_parts_scalar(const char_parts_s *P, double R_w, double R_m,
                                                   double k, double kc, double coef[9],
                                                   double cerr[9], double mu0[9]) {
  const double W = R_w * R_w, t = R_m * R_m * kc;
  int j;
  /* eq. (6); B[j] = 0 for odd j, where A[j] - t * 0 is A[j] (t is finite) */
  for (j = 8; j >= 0; j--) {
    double s = j % 2 ? P->Aa[j] : P->Aa[j] + t * P->B[j];
    coef[j] = j % 2 ? P->A[j] : P->A[j] - t * P->B[j];
    cerr[j] = PEND_GAMMA * U_D * s + AUTOBAL_PENDULUM_HURWITZ_RTOL * fabs(coef[j]);
    /* magnitude for the quick stage: >= (cerr + u |coef|) / PEND_RQ_EPS0 */
    mu0[j] = fabs(coef[j]) + PEND_RQ_K * s;
  }
  coef[0] = k * R_m * R_m * W * W * W * W; /* the exact constant term, see char_poly_from_parts_v */
  cerr[0] = (4.0 * U_D + AUTOBAL_PENDULUM_HURWITZ_RTOL) * coef[0];
  {
    double b0 = (cerr[0] + U_D * coef[0]) * (1.0 / PEND_RQ_EPS0); /* NaN stays NaN */
    mu0[0] = coef[0] > b0 ? coef[0] : b0;
  }
}

static MAP_INLINE void char_poly_scalar(double R_w, double R_m, double H, double h, double k,
                                        double kc, double coef[9], double cerr[9],
                                        double mu0[9]) {
  char_parts_s P;
  char_parts_scalar(R_w, R_m, H, h, &P);
  char_poly_from_parts_scalar(&P, R_w, R_m, k, kc, coef, cerr, mu0);
}

#if defined(__GNUC__) || defined(__clang__)
#define PEND_UNLIKELY(x) __builtin_expect(!!(x), 0) /* code layout only */
#else
#define PEND_UNLIKELY(x) (x)
#endif

/* The full test on (6) (the fall-back of damped_verdict_k). */
static int damped_full_k(double R_w, double R_m, double H, double h, double k, double kc,
                         int *verdict, int *n_rhp, autobal_error *err) {
  double coef[9], cerr[9], mu0[9];
  size_t off = k == 0.0; /* k == 0: lambda = 0 divided out */
  char_poly_scalar(R_w, R_m, H, h, k, kc, coef, cerr, mu0);
  return autobal_poly_hurwitz_err_full(coef + off, cerr + off, 9 - off, verdict, n_rhp, err);
}

/* Sign-test verdict of (6) from raw values (no validation): the quick
 * stage, else the full test (which also reports bad input: coefficients
 * that overflowed).  The verdict and count of autobal_poly_hurwitz_err on
 * (coef, cerr) either way. */
static MAP_INLINE int damped_verdict_parts(const char_parts_s *P, double R_w, double R_m, double H,
                                           double h, double k, double kc, int *verdict,
                                           int *n_rhp, autobal_error *err) {
  double coef[9], cerr[9], mu0[9];
  int changes, ok;
  char_poly_from_parts_scalar(P, R_w, R_m, k, kc, coef, cerr, mu0);
  /* k == 0: deflate the structural root lambda = 0 */
  if (PEND_UNLIKELY(k == 0.0))
    ok = autobal_routh_quick_7(coef + 1, cerr + 1, mu0 + 1, 0.0, PEND_RQ_EPS0, 0, &changes);
  else
    ok = autobal_routh_quick_8(coef, cerr, mu0, 0.0, PEND_RQ_EPS0, 0, &changes);
  if (ok && verdict != NULL) {
    *verdict = changes == 0 ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
    if (n_rhp) *n_rhp = changes;
    return AUTOBAL_SUCCESS;
  }
  /* the full test, on the same values formed again (so that the arrays
   * above stay in registers: only a few of their entries are used) */
  return damped_full_k(R_w, R_m, H, h, k, kc, verdict, n_rhp, err);
}

MAP_CLONES static int damped_verdict_k(double R_w, double R_m, double H, double h, double k,
                                       double kc, int *verdict, int *n_rhp, autobal_error *err) {
  char_parts_s P;
  char_parts_scalar(R_w, R_m, H, h, &P);
  return damped_verdict_parts(&P, R_w, R_m, H, h, k, kc, verdict, n_rhp, err);
}

/* autobal_pendulum_verdict after validation: the parts of (6) that do not
 * depend on psi0 first, then sin and cos of 2 psi0, (6) and the sign test.
 * Compiled also for AVX-512 (more registers; about 1.5 ns less per call than
 * AVX2, 57 instead of 79 ns on the baseline x86-64);
 * the values are the same bits on every clone (scalar IEEE operations, no
 * fused multiply-add: C11 mode has -ffp-contract=off). */
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 8 && defined(__x86_64__) && \
    defined(__linux__) && !defined(AUTOBAL_NO_CLONES)
#define PEND_VERDICT_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PEND_VERDICT_CLONES
#endif
PEND_VERDICT_CLONES static int damped_verdict_psi(const autobal_pendulum_params *p,
                                                  int *verdict, int *n_rhp, autobal_error *err) {
  char_parts_s P;
  double k, kc;
  char_parts_scalar(p->R_w, p->R_m, p->H, p->h, &P);
  k_and_kc(p, &k, &kc);
  return damped_verdict_parts(&P, p->R_w, p->R_m, p->H, p->h, k, kc, verdict, n_rhp, err);
}

int autobal_pendulum_verdict(const autobal_pendulum_params *p, int *verdict, int *n_rhp,
                             autobal_error *err) {
  /* the conditions of autobal_pendulum_params_validate in one expression
   * (NaN fails every comparison); it names the bad field when they fail */
  if (p == NULL || !(p->R_w >= 0.0 && p->R_w < INFINITY && p->R_m > 0.0 && p->R_m < 0.5 &&
                     p->H >= 0.0 && p->H < INFINITY && p->h >= 0.0 && p->h < INFINITY &&
                     p->psi0 >= 0.0 && p->psi0 < PEND_PI / 2)) {
    int st = autobal_pendulum_params_validate(p, err);
    if (st) return st;
  }
  if (verdict == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "verdict: NULL output");
  return damped_verdict_psi(p, verdict, n_rhp, err);
}

/* ---- (10) in long double -------------------------------------------------- */

/* Coefficients c_j(W) of P(x) of (10) at a given W, long double. */
static void undamped_coefs_ld(long double Rm, long double W, long double k, long double c[5]) {
  long double r2 = k * Rm * Rm;
  long double a0 = 2.0L * Rm * W * W * (W - 1.0L);                    /* (10) */
  long double a2 = (W - 1.0L) * (W - 1.0L) + 2.0L * Rm * W * (W + 6.0L); /* (10) */
  long double a4 = 2.0L * (1.0L - Rm) * (W + 1.0L);                   /* (10) */
  long double a6 = 1.0L - 2.0L * Rm;                                  /* (10) */
  c[0] = r2 * W * W * W * W;
  c[1] = a0 + 4.0L * r2 * W * W * W;
  c[2] = a2 + 6.0L * r2 * W * W;
  c[3] = a4 + 4.0L * r2 * W;
  c[4] = a6 + r2;
}

/* The 16 terms of the discriminant of a x^4 + b x^3 + c x^2 + d x + e:
 * coefficient and exponents of (a, b, c, d, e). */
static const struct {
  int coef;
  int ex[5];
} QUARTIC_DISC[16] = {
    {256, {3, 0, 0, 0, 3}}, {-192, {2, 1, 0, 1, 2}}, {-128, {2, 0, 2, 0, 2}},
    {144, {2, 0, 1, 2, 1}}, {-27, {2, 0, 0, 4, 0}},  {144, {1, 2, 1, 0, 2}},
    {-6, {1, 2, 0, 2, 1}},  {-80, {1, 1, 2, 1, 1}},  {18, {1, 1, 1, 3, 0}},
    {16, {1, 0, 4, 0, 1}},  {-4, {1, 0, 3, 2, 0}},   {-27, {0, 4, 0, 0, 2}},
    {18, {0, 3, 1, 1, 1}},  {-4, {0, 3, 0, 3, 0}},   {-4, {0, 2, 3, 0, 1}},
    {1, {0, 2, 2, 2, 0}}};

static long double ipow_ld(long double x, int n) {
  long double r = 1.0L;
  while (n-- > 0) r *= x;
  return r;
}

/* Discriminant of the quartic c[0] + ... + c[4] x^4 and the sum of the
 * magnitudes of its terms (for the error bound). */
static void quartic_disc_ld(const long double c[5], long double *disc, long double *mag) {
  long double s = 0.0L, m = 0.0L;
  long double v[5];
  int t, j;
  v[0] = c[4]; /* a */
  v[1] = c[3]; /* b */
  v[2] = c[2]; /* c */
  v[3] = c[1]; /* d */
  v[4] = c[0]; /* e */
  for (t = 0; t < 16; t++) {
    long double p = (long double)QUARTIC_DISC[t].coef;
    for (j = 0; j < 5; j++) p *= ipow_ld(v[j], QUARTIC_DISC[t].ex[j]);
    s += p;
    m += fabsl(p);
  }
  *disc = s;
  *mag = m;
}

/* 8ac - 3b^2 and 64a^3e - 16a^2c^2 + 16ab^2c - 16a^2bd - 3b^4 of the quartic
 * c[0] + ... + c[4] x^4 (a = c[4], ..., e = c[0]); *sure is cleared when
 * either is within its rounding bound of 0. */
static void quartic_aux_ld(const long double c[5], long double *P8, long double *D4, int *sure) {
  long double a = c[4], b = c[3], cc = c[2], d = c[1], e = c[0];
  long double t[5], m8, m4 = 0.0L, s4 = 0.0L;
  int i;
  *P8 = 8.0L * a * cc - 3.0L * b * b;
  m8 = fabsl(8.0L * a * cc) + fabsl(3.0L * b * b);
  t[0] = 64.0L * a * a * a * e;
  t[1] = -16.0L * a * a * cc * cc;
  t[2] = 16.0L * a * b * b * cc;
  t[3] = -16.0L * a * a * b * d;
  t[4] = -3.0L * b * b * b * b;
  for (i = 0; i < 5; i++) {
    s4 += t[i];
    m4 += fabsl(t[i]);
  }
  *D4 = s4;
  if (fabsl(*P8) <= PEND_GAMMA * U_LD * m8 || fabsl(*D4) <= PEND_GAMMA * U_LD * m4) *sure = 0;
}

/* Verdict of the undamped system at W = R_w^2 (see the header).  Exact sign
 * criteria, evaluated in long double with first-order error bounds:
 *  k = 0: x = 0 plus the cubic a6 x^3 + a4 x^2 + a2 x + a0, all roots real and
 *         <= 0 iff a_j >= 0 and its discriminant >= 0 (i.e. (12) lhs <= 0);
 *  k > 0: c0 > 0, so all roots real and <= 0 iff all c_j > 0 (Descartes) and
 *         the quartic has four real roots: discriminant > 0 with
 *         8ac - 3b^2 < 0 and 64a^3e - 16a^2c^2 + 16ab^2c - 16a^2bd - 3b^4 < 0
 *         (distinct roots), or discriminant = 0 on the boundary (MARGINAL). */
static int undamped_verdict_ld(long double Rm, long double W, long double k, int *sure) {
  long double c[5];
  int sure_dummy;
  if (sure == NULL) sure = &sure_dummy;
  *sure = 1;
  if (k == 1.0L) {
    /* (15): stable iff f(nu) = (1-R_m) nu^4 - 2R nu^3 + (R^2-1) nu^2 + 2R nu - R^2
     * (P1 at lambda = i(nu - R)) has four real roots (the roots of conj(P1)
     * are their mirror images); exact quartic criterion on f, whose
     * discriminant stays away from 0 at the double roots of (10) on (18). */
    long double R = sqrtl(W), f[5], disc, mag, P8, D4;
    f[0] = -W;
    f[1] = 2.0L * R;
    f[2] = W - 1.0L;
    f[3] = -2.0L * R;
    f[4] = 1.0L - Rm;
    quartic_disc_ld(f, &disc, &mag);
    if (disc < -PEND_GAMMA * U_LD * mag) return AUTOBAL_VERDICT_UNSTABLE;
    quartic_aux_ld(f, &P8, &D4, sure);
    if (P8 >= 0.0L || D4 >= 0.0L) return AUTOBAL_VERDICT_UNSTABLE;
    if (disc <= PEND_GAMMA * U_LD * mag) {
      *sure = 0;
      return AUTOBAL_VERDICT_MARGINAL;
    }
    return AUTOBAL_VERDICT_STABLE;
  }
  undamped_coefs_ld(Rm, W, k, c);
  if (k == 0.0L) {
    long double a0 = c[1], a2 = c[2], a4 = c[3], a6 = c[4];
    long double t[5], d = 0.0L, m = 0.0L;
    int i;
    long double ba0 = PEND_GAMMA * U_LD * 2.0L * Rm * W * W * (W + 1.0L);
    if (a2 <= 0.0L || a4 <= 0.0L || a6 <= 0.0L) return AUTOBAL_VERDICT_UNSTABLE;
    if (a0 < -ba0) return AUTOBAL_VERDICT_UNSTABLE;
    t[0] = 18.0L * a6 * a4 * a2 * a0; /* discriminant of the cubic = -(12) lhs */
    t[1] = -4.0L * a4 * a4 * a4 * a0;
    t[2] = a4 * a4 * a2 * a2;
    t[3] = -4.0L * a6 * a2 * a2 * a2;
    t[4] = -27.0L * a6 * a6 * a0 * a0;
    for (i = 0; i < 5; i++) {
      d += t[i];
      m += fabsl(t[i]);
    }
    if (d < -PEND_GAMMA * U_LD * m) return AUTOBAL_VERDICT_UNSTABLE;
    if (a0 <= ba0 || d <= PEND_GAMMA * U_LD * m) {
      *sure = 0;
      return AUTOBAL_VERDICT_MARGINAL;
    }
    return AUTOBAL_VERDICT_STABLE;
  }
  {
    long double a = c[4], b = c[3], cc = c[2], d = c[1], e = c[0];
    long double disc, mag, P8, D4;
    long double bnd;
    if (b <= 0.0L || cc <= 0.0L || d <= 0.0L) return AUTOBAL_VERDICT_UNSTABLE;
    (void)a, (void)e;
    quartic_disc_ld(c, &disc, &mag);
    bnd = PEND_GAMMA * U_LD * mag;
    if (disc < -bnd) return AUTOBAL_VERDICT_UNSTABLE;
    quartic_aux_ld(c, &P8, &D4, sure);
    if (P8 >= 0.0L || D4 >= 0.0L) {
      /* two complex pairs unless on the boundary disc = 0 */
      return AUTOBAL_VERDICT_UNSTABLE;
    }
    if (disc <= bnd) {
      *sure = 0;
      return AUTOBAL_VERDICT_MARGINAL;
    }
    return AUTOBAL_VERDICT_STABLE;
  }
}

static int check_rm_k(double R_m, double k, autobal_error *err) {
  int st;
  if ((st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "k", k, 0.0, 0, 1.0, 0, "")) != 0) return st;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_undamped_poly(double R_m, double R_w, double k, double coef[5],
                                   autobal_error *err) {
  double W, r2, a0, a2, a4, a6;
  int st;
  if ((st = check_rm_k(R_m, k, err)) != 0) return st;
  if ((st = autobal_check_param(err, "R_w", R_w, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if (coef == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "undamped_poly: NULL output");
  W = R_w * R_w;
  r2 = k * R_m * R_m;
  a0 = 2.0 * R_m * W * W * (W - 1.0);                       /* (10) */
  a2 = (W - 1.0) * (W - 1.0) + 2.0 * R_m * W * (W + 6.0);   /* (10) */
  a4 = 2.0 * (1.0 - R_m) * (W + 1.0);                       /* (10) */
  a6 = 1.0 - 2.0 * R_m;                                     /* (10) */
  /* P = x (a6 x^3 + a4 x^2 + a2 x + a0) + k R_m^2 (x + W)^4 */
  coef[0] = r2 * W * W * W * W;
  coef[1] = a0 + 4.0 * r2 * W * W * W;
  coef[2] = a2 + 6.0 * r2 * W * W;
  coef[3] = a4 + 4.0 * r2 * W;
  coef[4] = a6 + r2;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_undamped_verdict(double R_m, double R_w, double k, int *verdict,
                                      autobal_error *err) {
  int st;
  if ((st = check_rm_k(R_m, k, err)) != 0) return st;
  if ((st = autobal_check_param(err, "R_w", R_w, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if (verdict == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "undamped_verdict: NULL output");
  *verdict = undamped_verdict_ld(R_m, (long double)R_w * (long double)R_w, k, NULL);
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_cond12(double R_m, double R_w, double *lhs, int *stable, autobal_error *err) {
  double W, a0, a2, a4, a6, L;
  int st;
  if ((st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "R_w", R_w, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  W = R_w * R_w;
  a0 = 2.0 * R_m * W * W * (W - 1.0);
  a2 = (W - 1.0) * (W - 1.0) + 2.0 * R_m * W * (W + 6.0);
  a4 = 2.0 * (1.0 - R_m) * (W + 1.0);
  a6 = 1.0 - 2.0 * R_m;
  /* (12), with the corrected 4 a2^3 a6 */
  L = -a2 * a2 * a4 * a4 + 4.0 * a2 * a2 * a2 * a6 + 27.0 * a0 * a0 * a6 * a6 -
      18.0 * a0 * a2 * a4 * a6 + 4.0 * a0 * a4 * a4 * a4;
  if (lhs) *lhs = L;
  if (stable) *stable = (a0 > 0 && a2 > 0 && a4 > 0 && a6 > 0 && L <= 0) ? 1 : 0;
  return AUTOBAL_SUCCESS;
}

/* ---- discriminant in W, long double polynomial arithmetic ---------------- */

#define LDP_LEN 16

static void ldp_zero(long double *a) {
  int i;
  for (i = 0; i < LDP_LEN; i++) a[i] = 0.0L;
}

/* out = a * b truncated to LDP_LEN (degrees here never exceed 12) */
static void ldp_mul(const long double *a, const long double *b, long double *out) {
  long double t[LDP_LEN];
  int i, j;
  ldp_zero(t);
  for (i = 0; i < LDP_LEN; i++) {
    if (a[i] == 0.0L) continue;
    for (j = 0; i + j < LDP_LEN; j++) t[i + j] += a[i] * b[j];
  }
  memcpy(out, t, sizeof t);
}

static long double ldp_eval(const long double *a, int len, long double x) {
  long double s = 0.0L;
  int j = len;
  while (j-- > 0) s = s * x + a[j];
  return s;
}

/* c_j(W) of (10) as polynomials in W (long double), and |.| versions. */
static void undamped_coef_polys(long double Rm, long double k, long double c[5][LDP_LEN]) {
  long double r2 = k * Rm * Rm;
  int j;
  for (j = 0; j < 5; j++) ldp_zero(c[j]);
  /* c0 = k R_m^2 W^4 */
  c[0][4] = r2;
  /* c1 = a0 + 4 r2 W^3, a0 = 2 R_m W^2 (W - 1) */
  c[1][2] = -2.0L * Rm;
  c[1][3] = 2.0L * Rm + 4.0L * r2;
  /* c2 = a2 + 6 r2 W^2, a2 = (W - 1)^2 + 2 R_m W (W + 6) */
  c[2][0] = 1.0L;
  c[2][1] = -2.0L + 12.0L * Rm;
  c[2][2] = 1.0L + 2.0L * Rm + 6.0L * r2;
  /* c3 = a4 + 4 r2 W, a4 = 2 (1 - R_m)(W + 1) */
  c[3][0] = 2.0L * (1.0L - Rm);
  c[3][1] = 2.0L * (1.0L - Rm) + 4.0L * r2;
  /* c4 = a6 + r2, a6 = 1 - 2 R_m */
  c[4][0] = 1.0L - 2.0L * Rm + r2;
}

/* Discriminant of the quartic sum_j c[j] x^j whose coefficients c[j] are
 * polynomials (in W or R), by polynomial arithmetic on the 16 terms; ca are
 * the coefficient-wise magnitudes; Dm receives the magnitude polynomial
 * (same products on |.|) for rounding-error bounds. */
static void quartic_disc_poly(long double c[5][LDP_LEN], long double ca[5][LDP_LEN],
                              long double D[LDP_LEN], long double Dm[LDP_LEN]) {
  long double pw[5][5][LDP_LEN], pa[5][5][LDP_LEN];
  int i, j, t;
  /* powers 0..4 of each coefficient polynomial; index v: 0=a=c4 ... 4=e=c0 */
  for (i = 0; i < 5; i++) {
    const long double *base = c[4 - i], *basea = ca[4 - i];
    ldp_zero(pw[i][0]);
    ldp_zero(pa[i][0]);
    pw[i][0][0] = 1.0L;
    pa[i][0][0] = 1.0L;
    for (j = 1; j < 5; j++) {
      ldp_mul(pw[i][j - 1], base, pw[i][j]);
      ldp_mul(pa[i][j - 1], basea, pa[i][j]);
    }
  }
  ldp_zero(D);
  ldp_zero(Dm);
  for (t = 0; t < 16; t++) {
    long double term[LDP_LEN], terma[LDP_LEN];
    ldp_zero(term);
    ldp_zero(terma);
    term[0] = (long double)QUARTIC_DISC[t].coef;
    terma[0] = fabsl(term[0]);
    for (i = 0; i < 5; i++) {
      ldp_mul(term, pw[i][QUARTIC_DISC[t].ex[i]], term);
      ldp_mul(terma, pa[i][QUARTIC_DISC[t].ex[i]], terma);
    }
    for (j = 0; j < LDP_LEN; j++) {
      D[j] += term[j];
      Dm[j] += terma[j];
    }
  }
}

/* The discriminant of (10) in x as a polynomial in W (13 coefficients) and
 * the magnitude polynomial. */
static void undamped_disc_poly(long double Rm, long double k, long double D[LDP_LEN],
                               long double Dm[LDP_LEN]) {
  long double c[5][LDP_LEN], ca[5][LDP_LEN];
  int i, j;
  undamped_coef_polys(Rm, k, c);
  for (i = 0; i < 5; i++)
    for (j = 0; j < LDP_LEN; j++) ca[i][j] = fabsl(c[i][j]);
  quartic_disc_poly(c, ca, D, Dm);
  /* Degree <= 11: the W^12 coefficient is the discriminant of the top-degree
   * parts T(y) = sum_j c_j^top y^j, which has the double root y = -1
   * (T = (y+1)^2 [y((1-2R_m) y + 2R_m) + k R_m^2 (y+1)^2]), so it vanishes
   * identically; drop its rounding noise. */
  for (j = 12; j < LDP_LEN; j++) D[j] = 0.0L;
}

int autobal_pendulum_undamped_discriminant(double R_m, double k, double disc[13],
                                           autobal_error *err) {
  long double D[LDP_LEN], Dm[LDP_LEN];
  int st, j;
  if ((st = check_rm_k(R_m, k, err)) != 0) return st;
  if (disc == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "undamped_discriminant: NULL output");
  undamped_disc_poly(R_m, k, D, Dm);
  for (j = 0; j < 13; j++) disc[j] = (double)D[j];
  return AUTOBAL_SUCCESS;
}

/* ======================================================================== */
/* Analysis                                                                 */
/* ======================================================================== */

static void sufficient_conditions(const autobal_pendulum_params *p, double k,
                                  autobal_pendulum_result *r) {
  double W = p->R_w * p->R_w;
  double s7 = p->R_m;
  if (p->h > 0 && 1.0 / p->h < s7) s7 = 1.0 / p->h;
  /* (7): R_m << 1 or h >> 1: stable if R_w > 1 */
  r->cond7.small = s7;
  r->cond7.applicable = s7 <= AUTOBAL_PENDULUM_ASYMPTOTIC_SMALL;
  r->cond7.predicts_stable = p->R_w > 1.0;
  /* (8): R_w >> 1: stable if h > H sqrt(R_m) */
  r->cond8.small = p->R_w > 0 ? 1.0 / p->R_w : INFINITY;
  r->cond8.applicable = r->cond8.small <= AUTOBAL_PENDULUM_ASYMPTOTIC_SMALL;
  r->cond8.predicts_stable = p->h > p->H * sqrt(p->R_m);
  /* (9), corrected: H >> 1: stable iff R_m k W^2 / h^2 < W - 1 */
  r->cond9.small = p->H > 0 ? 1.0 / p->H : INFINITY;
  r->cond9.applicable = r->cond9.small <= AUTOBAL_PENDULUM_ASYMPTOTIC_SMALL;
  if (p->h > 0) r->cond9.predicts_stable = p->R_m * k * W * W < (W - 1.0) * p->h * p->h;
  else r->cond9.predicts_stable = (k == 0.0 && W > 1.0);
}

int autobal_pendulum_analyze(autobal_pendulum_workspace *ws, const autobal_pendulum_params *p,
                             autobal_pendulum_result *r) {
  double cerr[9], A[64], k, kc, scale;
  size_t perm[AUTOBAL_PENDULUM_ORDER], i;
  double er[AUTOBAL_PENDULUM_ORDER], ei[AUTOBAL_PENDULUM_ORDER];
  int st;
  if (ws == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&ws->err);
  if ((st = autobal_pendulum_params_validate(p, &ws->err)) != 0) return st;
  if (r == NULL) return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "analyze: NULL result");
  memset(r, 0, sizeof *r);
  k_and_kc(p, &k, &kc);
  char_poly_k(p->R_w, p->R_m, p->H, p->h, k, kc, r->coef, cerr);
  if ((st = autobal_poly_roots(ws->pw[8], r->coef, 9, r->root_re, r->root_im, &ws->err)) != 0)
    return st;
  if ((st = autobal_pendulum_first_order_matrix(p, A, &ws->err)) != 0) return st;
  if ((st = autobal_eigen_nonsymm(ws->ew, A, er, ei, &ws->err)) != 0) return st;
  if ((st = autobal_match_roots(8, r->root_re, r->root_im, er, ei, perm, &r->mismatch,
                                &ws->err)) != 0)
    return st;
  scale = 1.0;
  for (i = 0; i < 8; i++) {
    double m = hypot(r->root_re[i], r->root_im[i]);
    if (m > scale) scale = m;
    r->eig_re[i] = er[perm[i]];
    r->eig_im[i] = ei[perm[i]];
  }
  r->mismatch_rel = r->mismatch / scale;
  r->zero_root_deflated = (k == 0.0);
  /* sign test on the coefficients */
  st = sign_test_poly(r->coef, cerr, p->R_w * p->R_w, k == 0.0, &r->verdict, &r->n_rhp,
                      &ws->err);
  if (st) return st;
  /* verdict from the roots (drop the root nearest 0 when deflated) */
  {
    double rr[8], ri[8], emax = -INFINITY;
    size_t n = 0, skip = 8, esk = 8;
    if (k == 0.0) {
      double best = INFINITY;
      for (i = 0; i < 8; i++)
        if (hypot(r->root_re[i], r->root_im[i]) < best) {
          best = hypot(r->root_re[i], r->root_im[i]);
          skip = i;
        }
      esk = skip; /* eig[i] is matched to root[i] */
    }
    for (i = 0; i < 8; i++) {
      if (i == skip) continue;
      rr[n] = r->root_re[i];
      ri[n] = r->root_im[i];
      n++;
    }
    r->verdict_roots = autobal_roots_verdict(n, rr, ri, AUTOBAL_PENDULUM_ROOTS_TOL, &r->max_real);
    for (i = 0; i < 8; i++)
      if (i != esk && r->eig_re[i] > emax) emax = r->eig_re[i];
    r->max_real_eig = emax;
  }
  r->verdicts_agree = r->verdict == r->verdict_roots;
  r->undamped = (p->H == 0.0 && p->h == 0.0);
  if (r->undamped)
    r->undamped_verdict = undamped_verdict_ld(p->R_m, (long double)p->R_w * p->R_w, k, NULL);
  sufficient_conditions(p, k, r);
  return AUTOBAL_SUCCESS;
}

/* ======================================================================== */
/* Critical speeds of the undamped system                                   */
/* ======================================================================== */

typedef struct {
  const long double *q;
  int len;
} ldpoly_ctx;

static int ldpoly_fn(double x, void *ctx, double *fx) {
  const ldpoly_ctx *c = (const ldpoly_ctx *)ctx;
  long double v = ldp_eval(c->q, c->len, x);
  /* keep the sign even if the magnitude is outside double's range */
  if (v > 0) *fx = v > (long double)DBL_MAX ? DBL_MAX : (v < (long double)DBL_MIN ? DBL_MIN : (double)v);
  else if (v < 0)
    *fx = -v > (long double)DBL_MAX ? -DBL_MAX : (-v < (long double)DBL_MIN ? -DBL_MIN : (double)v);
  else *fx = 0.0;
  return AUTOBAL_SUCCESS;
}

/* sign of q at x, 0 if |q(x)| is within the rounding bound */
static int ld_sign(const long double *q, const long double *qa, int len, long double x) {
  long double v = ldp_eval(q, len, x);
  long double b = PEND_GAMMA * U_LD * ldp_eval(qa, len, fabsl(x));
  if (v > b) return 1;
  if (v < -b) return -1;
  return 0;
}

static int cmp_dbl(const void *pa, const void *pb) {
  double a = *(const double *)pa, b = *(const double *)pb;
  return (a > b) - (a < b);
}

/* Positive real roots of q (long double, len <= LDP_LEN) with magnitude
 * polynomial qa: isolation between the critical points of q (roots of q',
 * by GSL, polished by Newton in long double), sign changes refined by Brent,
 * critical points where |q| is within its rounding bound reported as
 * (double) roots.  Writes up to maxout sorted roots. */
static int positive_roots(autobal_pendulum_workspace *ws, const long double *q0,
                          const long double *qa, int len0, double *out, size_t maxout,
                          size_t *nout) {
  long double q[LDP_LEN], dq[LDP_LEN], ddq[LDP_LEN];
  double dqd[LDP_LEN], rre[LDP_LEN], rim[LDP_LEN];
  double brk[LDP_LEN + 2];
  size_t nb = 0, n = 0, i;
  int len = len0, deg, j, st;
  ldpoly_ctx ctx;
  while (len > 0 && q0[len - 1] == 0.0L) len--;
  *nout = 0;
  if (len < 2) return AUTOBAL_SUCCESS;
  for (j = 0; j < LDP_LEN; j++) q[j] = j < len ? q0[j] : 0.0L;
  deg = len - 1;
  for (j = 0; j < LDP_LEN; j++) {
    dq[j] = j + 1 < len ? (long double)(j + 1) * q[j + 1] : 0.0L;
    ddq[j] = j + 2 < len ? (long double)((j + 2) * (j + 1)) * q[j + 2] : 0.0L;
  }
  brk[nb++] = 0.0;
  if (deg >= 2) {
    /* critical points: roots of q' (degree deg-1) */
    for (j = 0; j < deg; j++) dqd[j] = (double)dq[j];
    st = autobal_poly_roots(ws->pw[deg - 1], dqd, (size_t)deg, rre, rim, &ws->err);
    if (st) return st;
    for (j = 0; j < deg - 1; j++) {
      long double x;
      int it;
      if (!(rre[j] > 0.0) || fabs(rim[j]) > 1e-3 * fabs(rre[j])) continue;
      x = rre[j];
      for (it = 0; it < 6; it++) { /* Newton on q' */
        long double f = ldp_eval(dq, len, x), fp = ldp_eval(ddq, len, x);
        long double nx;
        if (fp == 0.0L) break;
        nx = x - f / fp;
        if (!(nx > 0.0L) || fabsl(nx - x) > 1e-2L * x) break;
        x = nx;
      }
      brk[nb++] = (double)x;
    }
  }
  {
    /* upper bound of the positive roots (Cauchy) */
    long double m = 0.0L;
    for (j = 0; j < deg; j++)
      if (fabsl(q[j] / q[deg]) > m) m = fabsl(q[j] / q[deg]);
    m = 2.0L * (1.0L + m);
    if (m > 1e150L) m = 1e150L;
    brk[nb++] = (double)m;
  }
  qsort(brk + 1, nb - 2, sizeof(double), cmp_dbl);
  ctx.q = q;
  ctx.len = len;
  for (i = 0; i + 1 < nb; i++) {
    double a = brk[i], b = brk[i + 1];
    int sa, sb;
    if (!(b > a)) continue;
    sa = ld_sign(q, qa, len, a);
    sb = ld_sign(q, qa, len, b);
    if (i > 0 && sa == 0) {
      /* (near-)double root at a critical point */
      if (n == 0 || out[n - 1] < a * (1 - 1e-14)) {
        if (n < maxout) out[n++] = a;
      }
    }
    if (sa != 0 && sb != 0 && sa != sb) {
      double root;
      st = autobal_root_brent(ldpoly_fn, &ctx, a, b, 0.0, 1e-15, 400, &root, &ws->err);
      if (st) return st;
      if (n == 0 || out[n - 1] < root * (1 - 1e-14)) {
        if (n < maxout) out[n++] = root;
      }
    }
  }
  *nout = n;
  return AUTOBAL_SUCCESS;
}

/* ---- the colliding pair of roots of (10): a well-conditioned local test ---- */

/* Quadratic factor x^2 + u x + v of the quartic a[0..4] (ascending) near the
 * initial (u, v), by Bairstow's method in long double; b[2..4] receive the
 * quotient b4 x^2 + b3 x + b2.  Returns 0 on convergence. */
static int bairstow(const long double a[5], long double *u, long double *v, long double q[3]) {
  long double b[5], c[5], prev = INFINITY, best = INFINITY, bu = *u, bv = *v;
  int it, i, conv = 0;
  for (it = 0; it < 100; it++) {
    long double det, du, dv;
    b[4] = a[4];
    b[3] = a[3] - *u * b[4];
    for (i = 2; i >= 0; i--) b[i] = a[i] - *u * b[i + 1] - *v * b[i + 2];
    c[4] = b[4];
    c[3] = b[3] - *u * c[4];
    for (i = 2; i >= 1; i--) c[i] = b[i] - *u * c[i + 1] - *v * c[i + 2];
    det = c[2] * c[2] - c[1] * c[3];
    if (det == 0.0L) return -1;
    du = (b[1] * c[2] - b[0] * c[3]) / det;
    dv = (c[2] * b[0] - c[1] * b[1]) / det;
    *u += du;
    *v += dv;
    {
      /* converged when the step is at rounding level, or stops shrinking
       * once small (quadratic convergence has ended in rounding noise);
       * the iterate after the smallest step is kept */
      long double step = fabsl(du) / (1 + fabsl(*u)) + fabsl(dv) / (1 + fabsl(*v));
      if (step < best) {
        best = step;
        bu = *u;
        bv = *v;
      }
      if (step <= 16 * U_LD || (step < 1e-14L && step >= 0.5L * prev)) {
        conv = 1;
        break;
      }
      prev = step;
    }
  }
  if (!conv && best < 1e-13L) conv = 1;
  *u = bu;
  *v = bv;
  b[4] = a[4];
  b[3] = a[3] - *u * b[4];
  b[2] = a[2] - *u * b[3] - *v * b[4];
  q[0] = b[2];
  q[1] = b[3];
  q[2] = b[4];
  return conv ? 0 : -1;
}

/* The closest pair of roots of (10) at W as a quadratic factor: *g = u^2 - 4v
 * (> 0: the pair is real and distinct, < 0: complex), *rest_ok = 1 when both
 * quadratics have real roots <= 0 apart from the sign of g. */
static int undamped_cluster(autobal_pendulum_workspace *ws, long double Rm, long double W,
                            long double k, long double *g, int *rest_ok) {
  long double c[5], u, v, q[3];
  double cd[5], re[4], im[4], best = INFINITY;
  int i, j, bi = 0, bj = 1, st;
  undamped_coefs_ld(Rm, W, k, c);
  for (i = 0; i < 5; i++) cd[i] = (double)c[i];
  if ((st = autobal_poly_roots(ws->pw[4], cd, 5, re, im, &ws->err)) != 0) return st;
  for (i = 0; i < 4; i++)
    for (j = i + 1; j < 4; j++) {
      double d;
      int conj = im[i] != 0.0 && im[i] == -im[j] && re[i] == re[j];
      int reals = im[i] == 0.0 && im[j] == 0.0;
      if (!conj && !reals) continue;
      d = hypot(re[i] - re[j], im[i] - im[j]);
      if (d < best) {
        best = d;
        bi = i;
        bj = j;
      }
    }
  u = -((long double)re[bi] + re[bj]);
  v = (long double)re[bi] * re[bj] - (long double)im[bi] * im[bj];
  if (bairstow(c, &u, &v, q) != 0) {
    /* no convergence (e.g. a third root close by): fall back on the double
     * precision roots themselves */
    long double dr = (long double)re[bi] - re[bj], di = (long double)im[bi] - im[bj];
    int m, okr = 1;
    *g = dr * dr - di * di;
    for (m = 0; m < 4; m++)
      if (m != bi && m != bj && (im[m] != 0.0 || re[m] > 0.0)) okr = 0;
    *rest_ok = okr && re[bi] + re[bj] <= 0.0;
    return AUTOBAL_SUCCESS;
  }
  *g = u * u - 4.0L * v;
  *rest_ok = (q[1] * q[1] - 4.0L * q[2] * q[0] >= 0.0L) && q[1] * q[2] >= 0.0L &&
             q[0] * q[2] >= 0.0L && u >= 0.0L && v >= 0.0L;
  return AUTOBAL_SUCCESS;
}

typedef struct {
  autobal_pendulum_workspace *ws;
  long double Rm, k;
} cluster_ctx;

static int cluster_fn(double W, void *vctx, double *fx) {
  const cluster_ctx *c = (const cluster_ctx *)vctx;
  long double g;
  int ok, st = undamped_cluster(c->ws, c->Rm, W, c->k, &g, &ok);
  *fx = (double)g;
  return st;
}

/* Verdict with the cluster test as fallback where the quartic criterion is
 * undecided (very narrow windows, double roots). */
static int undamped_verdict_robust(autobal_pendulum_workspace *ws, long double Rm, long double W,
                                   long double k, int *verdict) {
  long double g;
  int ok, st, sure;
  *verdict = undamped_verdict_ld(Rm, W, k, &sure);
  if (sure || k == 0.0L || k == 1.0L) return AUTOBAL_SUCCESS;
  if ((st = undamped_cluster(ws, Rm, W, k, &g, &ok)) != 0) return st;
  if (g < 0.0L || !ok) *verdict = AUTOBAL_VERDICT_UNSTABLE;
  else if (g > 0.0L) *verdict = AUTOBAL_VERDICT_STABLE;
  return AUTOBAL_SUCCESS;
}

/* Refine a root W0 of the discriminant on the pair discriminant g: find a
 * sign change of g within W0 (1 -+ h), h = 1e-12 ... 1e-3, then Brent. */
static int refine_on_cluster(cluster_ctx *cc, double W0, double *W) {
  double h, fa, fb, f0;
  int st;
  *W = W0;
  if ((st = cluster_fn(W0, cc, &f0)) != 0) return st;
  for (h = 1e-12; h <= 1e-3; h *= 4) {
    double a = W0 * (1 - h), b = W0 * (1 + h);
    if ((st = cluster_fn(a, cc, &fa)) != 0) return st;
    if ((st = cluster_fn(b, cc, &fb)) != 0) return st;
    if ((fa < 0) != (f0 < 0) || (fb < 0) != (f0 < 0)) {
      double lo = (fa < 0) != (f0 < 0) ? a : W0, hi = (fa < 0) != (f0 < 0) ? W0 : b;
      if (lo == W0 && (fb < 0) == (f0 < 0)) return AUTOBAL_SUCCESS;
      return autobal_root_brent(cluster_fn, cc, lo, hi, 0.0, 1e-15, 200, W, &cc->ws->err);
    }
  }
  return AUTOBAL_SUCCESS; /* no sign change of g nearby (touch): keep W0 */
}

/* The degenerate points of the limits k -> 1 and k -> 0 open into windows
 * where a pair of roots of (10) is complex, of width ~ sqrt(1-k) resp.
 * sqrt(k), too narrow for the discriminant in W when k is close to 1 or 0:
 *  - k -> 1: the double root of (10) at k = 1, W18 = 2(1-2R_m)/(1-4R_m)^2
 *    ((18) squared), an unstable window when R_m^(1) < R_m < 1/4;
 *  - k -> 0: W = 1, where x = 0 meets the cubic (13).
 * Look for a window at such a point W18 directly: if the pair is complex
 * there, walk outwards until it is real and refine both ends on g. */
static int window_at(cluster_ctx *cc, double W18, double *lo, double *hi, int *found) {
  double g0, h, ga, gb, a = 0, b = 0;
  int st, fa = 0, fb = 0;
  *found = 0;
  if (!isfinite(W18) || !(W18 > 0)) return AUTOBAL_SUCCESS;
  if ((st = cluster_fn(W18, cc, &g0)) != 0) return st;
  if (!(g0 < 0)) return AUTOBAL_SUCCESS;
  for (h = 1e-15; h < 0.5 && !(fa && fb); h *= 2) {
    if (!fa) {
      if ((st = cluster_fn(W18 * (1 - h), cc, &ga)) != 0) return st;
      if (ga > 0) fa = 1, a = W18 * (1 - h);
    }
    if (!fb) {
      if ((st = cluster_fn(W18 * (1 + h), cc, &gb)) != 0) return st;
      if (gb > 0) fb = 1, b = W18 * (1 + h);
    }
  }
  if (!(fa && fb)) return AUTOBAL_SUCCESS;
  if ((st = autobal_root_brent(cluster_fn, cc, a, W18, 0.0, 1e-15, 300, lo, &cc->ws->err)) != 0) return st;
  if ((st = autobal_root_brent(cluster_fn, cc, W18, b, 0.0, 1e-15, 300, hi, &cc->ws->err)) != 0) return st;
  *found = 1;
  return AUTOBAL_SUCCESS;
}

static int crit_set_fill(autobal_pendulum_crit_set *out, const double *rw, const int *vint,
                         size_t nc, int keep_touch_stable_only, double lo_end, double hi_end) {
  /* vint[i] = verdict (1 stable) on interval i: (rw[i-1], rw[i]), i = 0..nc */
  size_t i;
  out->n = 0;
  out->n_stable = 0;
  for (i = 0; i < nc; i++) {
    int l = vint[i] == AUTOBAL_VERDICT_STABLE, r = vint[i + 1] == AUTOBAL_VERDICT_STABLE;
    int kind = l == r ? AUTOBAL_CRIT_TOUCH : (r ? AUTOBAL_CRIT_GAINED : AUTOBAL_CRIT_LOST);
    if (kind == AUTOBAL_CRIT_TOUCH && keep_touch_stable_only && !l) continue;
    if (out->n < AUTOBAL_PENDULUM_MAX_CRIT) {
      out->R_w[out->n] = rw[i];
      out->kind[out->n] = kind;
      out->n++;
    }
  }
  for (i = 0; i <= nc; i++) {
    double a = i == 0 ? lo_end : rw[i - 1];
    double b = i == nc ? hi_end : rw[i];
    if (vint[i] != AUTOBAL_VERDICT_STABLE) continue;
    if (out->n_stable > 0 && out->stable_hi[out->n_stable - 1] == a) {
      out->stable_hi[out->n_stable - 1] = b; /* merge across a touch */
    } else if (out->n_stable < AUTOBAL_PENDULUM_MAX_CRIT + 1) {
      out->stable_lo[out->n_stable] = a;
      out->stable_hi[out->n_stable] = b;
      out->n_stable++;
    }
  }
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_critical_speeds(autobal_pendulum_workspace *ws, double R_m, double k,
                                     autobal_pendulum_crit_set *out) {
  long double D[LDP_LEN], Dm[LDP_LEN];
  double Wr[AUTOBAL_PENDULUM_MAX_CRIT], rw[AUTOBAL_PENDULUM_MAX_CRIT];
  int vint[AUTOBAL_PENDULUM_MAX_CRIT + 1];
  size_t nW = 0, i;
  int st, len;
  if (ws == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&ws->err);
  if ((st = check_rm_k(R_m, k, &ws->err)) != 0) return st;
  if (out == NULL) return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_speeds: NULL output");
  memset(out, 0, sizeof *out);
  if (k == 0.0) {
    /* x = 0 plus the cubic: its discriminant in W (degree 6), and W = 1
     * where a0 = 2 R_m W^2 (W - 1) changes sign (13) */
    long double c[5][LDP_LEN], ca[5][LDP_LEN], t[LDP_LEN], ta[LDP_LEN];
    long double *a0, *a2, *a4, *a6;
    static const int TERMS[5][5] = {/* coef, exps of a6, a4, a2, a0 */
                                    {18, 1, 1, 1, 1},
                                    {-4, 0, 3, 0, 1},
                                    {1, 0, 2, 2, 0},
                                    {-4, 1, 0, 3, 0},
                                    {-27, 2, 0, 0, 2}};
    int tt, v, e, j;
    undamped_coef_polys(R_m, 0.0L, c);
    for (v = 0; v < 5; v++)
      for (j = 0; j < LDP_LEN; j++) ca[v][j] = fabsl(c[v][j]);
    a0 = c[1];
    a2 = c[2];
    a4 = c[3];
    a6 = c[4];
    ldp_zero(D);
    ldp_zero(Dm);
    for (tt = 0; tt < 5; tt++) {
      long double *base[4], *basea[4];
      base[0] = a6;
      base[1] = a4;
      base[2] = a2;
      base[3] = a0;
      basea[0] = ca[4];
      basea[1] = ca[3];
      basea[2] = ca[2];
      basea[3] = ca[1];
      ldp_zero(t);
      ldp_zero(ta);
      t[0] = TERMS[tt][0];
      ta[0] = fabsl(t[0]);
      for (v = 0; v < 4; v++)
        for (e = 0; e < TERMS[tt][v + 1]; e++) {
          ldp_mul(t, base[v], t);
          ldp_mul(ta, basea[v], ta);
        }
      for (j = 0; j < LDP_LEN; j++) {
        D[j] += t[j];
        Dm[j] += ta[j];
      }
    }
    /* Degree <= 5: the W^6 coefficient is the discriminant of the top-degree
     * parts (1-2R_m) y^3 + 2(1-R_m) y^2 + (1+2R_m) y + 2R_m = (y+1)^2 ((1-2R_m) y
     * + 2R_m), which has a double root, so it vanishes identically. */
    for (j = 6; j < LDP_LEN; j++) D[j] = 0.0L;
    len = 6;
    if ((st = positive_roots(ws, D, Dm, len, Wr, AUTOBAL_PENDULUM_MAX_CRIT - 1, &nW)) != 0)
      return st;
    /* add W = 1 */
    {
      int have = 0;
      for (i = 0; i < nW; i++)
        if (fabs(Wr[i] - 1.0) <= 1e-14) {
          Wr[i] = 1.0;
          have = 1;
        }
      if (!have) Wr[nW++] = 1.0;
      qsort(Wr, nW, sizeof(double), cmp_dbl);
    }
  } else {
    size_t nT = 0;
    double T[AUTOBAL_PENDULUM_MAX_CRIT];
    if (k == 1.0) {
      /* (15): at k = 1, with lambda = i mu and nu = mu + R_w, P1 becomes the
       * real quartic f(nu) = (nu - R_w)^2 (nu^2 - 1) - R_m nu^4 and (6) is
       * stable in the first approximation iff f has four real roots; the
       * verdict changes only where disc_nu(f) = 0.  Its roots are located on
       * their own (the double root of (6) at (18) is not one of them, so no
       * near-triple root arises near R_m^(1)). */
      long double F[5][LDP_LEN], Fa[5][LDP_LEN], E[LDP_LEN], Ea[LDP_LEN];
      long double Q1[LDP_LEN], Q1a[LDP_LEN];
      int j;
      for (j = 0; j < 5; j++) ldp_zero(F[j]);
      F[0][2] = -1.0L;             /* -R^2          */
      F[1][1] = 2.0L;              /* 2R nu         */
      F[2][0] = -1.0L;             /* (R^2 - 1) nu^2 */
      F[2][2] = 1.0L;
      F[3][1] = -2.0L;             /* -2R nu^3      */
      F[4][0] = 1.0L - (long double)R_m; /* (1 - R_m) nu^4 */
      for (j = 0; j < 5; j++) {
        int m;
        for (m = 0; m < LDP_LEN; m++) Fa[j][m] = fabsl(F[j][m]);
      }
      quartic_disc_poly(F, Fa, E, Ea);
      /* disc is even in R (each term has an even number of odd factors b, d),
       * so it is a polynomial in W = R^2 */
      ldp_zero(Q1);
      ldp_zero(Q1a);
      for (j = 0; 2 * j < LDP_LEN; j++) {
        Q1[j] = E[2 * j];
        Q1a[j] = Ea[2 * j];
      }
      if ((st = positive_roots(ws, Q1, Q1a, 8, T, AUTOBAL_PENDULUM_MAX_CRIT / 2, &nT)) != 0)
        return st;
    }
    undamped_disc_poly(R_m, k, D, Dm);
    /* D = W^4 Q(W): the coefficients of W^0..W^3 vanish exactly (every term
     * of the discriminant holds e = c0 ~ W^4 or d^2 = c1^2 ~ W^4) */
    if ((st = positive_roots(ws, D + 4, Dm + 4, 8, Wr, AUTOBAL_PENDULUM_MAX_CRIT / 2, &nW)) != 0)
      return st;
    if (k == 1.0) {
      /* keep the exact transitions T, plus the candidates of D that are not
       * one of them (touches such as the double root at (18)) */
      size_t n2 = 0, a, b;
      for (a = 0; a < nW; a++) {
        int dup = 0;
        for (b = 0; b < nT; b++)
          if (fabs(Wr[a] - T[b]) <= 1e-6 * T[b]) dup = 1;
        if (!dup) Wr[n2++] = Wr[a];
      }
      for (b = 0; b < nT; b++) Wr[n2++] = T[b];
      nW = n2;
      qsort(Wr, nW, sizeof(double), cmp_dbl);
    }
  }
  if (k < 1.0) {
    /* refine every candidate on the pair discriminant (well conditioned,
     * from the coefficients of (10) at W rather than the expanded
     * discriminant in W), then look for a window at (18) too narrow for the
     * discriminant in W */
    cluster_ctx cc;
    double wlo, whi;
    int found, pt;
    cc.ws = ws;
    cc.Rm = R_m;
    cc.k = k;
    for (i = 0; i < nW; i++) {
      double Wn;
      if (k == 0.0 && Wr[i] == 1.0) continue; /* exact (13) */
      if ((st = refine_on_cluster(&cc, Wr[i], &Wn)) != 0) return st;
      Wr[i] = Wn;
    }
    for (pt = 0; pt < 2 && k > 0.0; pt++) {
      double Wc = pt == 0 ? 2.0 * (1.0 - 2.0 * R_m) / ((1.0 - 4.0 * R_m) * (1.0 - 4.0 * R_m)) : 1.0;
      if ((st = window_at(&cc, Wc, &wlo, &whi, &found)) != 0) return st;
      if (!found) continue;
      /* candidates that approximated the ends were refined onto them above
       * (merged below); inside a window too narrow for the discriminant in W
       * any candidate is an artefact */
      size_t n2 = 0;
      int narrow = whi - wlo < 1e-6 * whi;
      for (i = 0; i < nW; i++)
        if (!(narrow && Wr[i] > wlo && Wr[i] < whi)) Wr[n2++] = Wr[i];
      if (n2 + 2 <= AUTOBAL_PENDULUM_MAX_CRIT) {
        Wr[n2++] = wlo;
        Wr[n2++] = whi;
      }
      nW = n2;
      qsort(Wr, nW, sizeof(double), cmp_dbl);
    }
    qsort(Wr, nW, sizeof(double), cmp_dbl);
    {
      /* merge duplicates produced by the refinement */
      size_t n2 = 0;
      for (i = 0; i < nW; i++)
        if (n2 == 0 || Wr[i] > Wr[n2 - 1] * (1 + 1e-13)) Wr[n2++] = Wr[i];
      nW = n2;
    }
  }
  /* verdict on every interval between consecutive candidates */
  for (i = 0; i <= nW; i++) {
    long double a = i == 0 ? 0.0L : Wr[i - 1];
    long double b = i == nW ? 2.0L * a + 1.0L : Wr[i];
    if ((st = undamped_verdict_robust(ws, R_m, 0.5L * (a + b), k, &vint[i])) != 0) return st;

  }
  for (i = 0; i < nW; i++) rw[i] = sqrt(Wr[i]);
  st = crit_set_fill(out, rw, vint, nW, 1, 0.0, INFINITY);
  {
    /* a touch within 1e-8 of a transition is an artefact of the rounding of
     * the pair discriminant (large W): drop it */
    size_t n2 = 0;
    for (i = 0; i < out->n; i++) {
      int drop = 0;
      if (out->kind[i] == AUTOBAL_CRIT_TOUCH) {
        if (i > 0 && out->kind[i - 1] != AUTOBAL_CRIT_TOUCH && out->R_w[i] - out->R_w[i - 1] < 1e-8 * out->R_w[i])
          drop = 1;
        if (i + 1 < out->n && out->kind[i + 1] != AUTOBAL_CRIT_TOUCH &&
            out->R_w[i + 1] - out->R_w[i] < 1e-8 * out->R_w[i])
          drop = 1;
      }
      if (!drop) {
        out->R_w[n2] = out->R_w[i];
        out->kind[n2] = out->kind[i];
        n2++;
      }
    }
    out->n = n2;
  }
  return st;
}

size_t autobal_pendulum_crit_count(const autobal_pendulum_crit_set *s) {
  size_t i, n = 0;
  if (s == NULL) return 0;
  for (i = 0; i < s->n; i++)
    if (s->kind[i] != AUTOBAL_CRIT_TOUCH) n++;
  return n;
}

double autobal_pendulum_crit_get(const autobal_pendulum_crit_set *s, size_t j) {
  size_t i, n = 0;
  if (s == NULL) return NAN;
  for (i = 0; i < s->n; i++)
    if (s->kind[i] != AUTOBAL_CRIT_TOUCH) {
      if (n == j) return s->R_w[i];
      n++;
    }
  return NAN;
}

int autobal_pendulum_critical_curves(autobal_pendulum_workspace *ws, double k, const double *R_m,
                                     size_t n_Rm, size_t n_curve, double *rw) {
  size_t i, j;
  int st;
  if (ws == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&ws->err);
  if ((st = autobal_check_param(&ws->err, "k", k, 0.0, 0, 1.0, 0, "")) != 0) return st;
  if ((n_Rm > 0 && R_m == NULL) || (n_Rm * n_curve > 0 && rw == NULL))
    return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_curves: NULL array");
  for (i = 0; i < n_Rm; i++) {
    char name[32];
    snprintf(name, sizeof name, "R_m[%zu]", i);
    if ((st = autobal_check_param(&ws->err, name, R_m[i], 0.0, 1, 0.5, 1, "")) != 0) return st;
  }
  for (i = 0; i < n_Rm; i++) {
    autobal_pendulum_crit_set s;
    if ((st = autobal_pendulum_critical_speeds(ws, R_m[i], k, &s)) != 0) return st;
    for (j = 0; j < n_curve; j++) rw[i * n_curve + j] = autobal_pendulum_crit_get(&s, j);
  }
  return AUTOBAL_SUCCESS;
}

/* ======================================================================== */
/* Critical speeds of the damped system                                     */
/* ======================================================================== */

typedef struct {
  autobal_pendulum_workspace *ws;
  double R_m, H, h, k, kc;
} damped_ctx;

static int damped_stable_pred(double R_w, void *vctx, int *value) {
  const damped_ctx *c = (const damped_ctx *)vctx;
  int v, st;
  st = damped_verdict_k(R_w, c->R_m, c->H, c->h, c->k, c->kc, &v, NULL, &c->ws->err);
  *value = v == AUTOBAL_VERDICT_STABLE;
  return st;
}

/* max Re of the roots of (6) (deflated at k = 0) */
static int damped_maxre_fn(double R_w, void *vctx, double *fx) {
  const damped_ctx *c = (const damped_ctx *)vctx;
  double coef[9], re[8], im[8];
  int st;
  char_poly_k(R_w, c->R_m, c->H, c->h, c->k, c->kc, coef, NULL);
  if (c->k == 0.0) st = autobal_poly_roots(c->ws->pw[7], coef + 1, 8, re, im, &c->ws->err);
  else st = autobal_poly_roots(c->ws->pw[8], coef, 9, re, im, &c->ws->err);
  if (st) return st;
  autobal_roots_verdict(c->k == 0.0 ? 7 : 8, re, im, 0.0, fx);
  return AUTOBAL_SUCCESS;
}

/* The damped search with at most cap recorded changes (1 <= cap <= AUTOBAL_PENDULUM_MAX_CRIT;
 * the public function uses AUTOBAL_PENDULUM_MAX_CRIT).  A test hook for the truncation path
 * (the damped system has far fewer changes than the capacity, see the header); declared here
 * and in tests/test_pendulum.c, not part of the API.  AUTOBAL_EINVAL for cap out of range. */
int autobal_pendulum_critical_speeds_damped_cap_(autobal_pendulum_workspace *ws,
                                                 const autobal_pendulum_params *p, double rw_min,
                                                 double rw_max, size_t n_sweep, size_t cap,
                                                 autobal_pendulum_crit_set *out);

int autobal_pendulum_critical_speeds_damped_cap_(autobal_pendulum_workspace *ws,
                                                 const autobal_pendulum_params *p, double rw_min,
                                                 double rw_max, size_t n_sweep, size_t cap,
                                                 autobal_pendulum_crit_set *out) {
  damped_ctx ctx;
  double rw[AUTOBAL_PENDULUM_MAX_CRIT];
  int vint[AUTOBAL_PENDULUM_MAX_CRIT + 1];
  size_t nc = 0, i;
  int st, prev, truncated = 0;
  autobal_pendulum_params q;
  if (ws == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&ws->err);
  if (p == NULL) return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_speeds_damped: NULL parameters");
  q = *p;
  q.R_w = 0.0;
  if ((st = autobal_pendulum_params_validate(&q, &ws->err)) != 0) return st;
  if ((st = autobal_check_param(&ws->err, "rw_min", rw_min, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if ((st = autobal_check_param(&ws->err, "rw_max", rw_max, rw_min, 1, INFINITY, 1, "")) != 0)
    return st;
  if (n_sweep < 2)
    return autobal_error_set(&ws->err, AUTOBAL_EINVAL,
                             "parameter n_sweep = %zu is out of range: allowed [2, inf)", n_sweep);
  if (cap < 1 || cap > AUTOBAL_PENDULUM_MAX_CRIT)
    return autobal_error_set(&ws->err, AUTOBAL_EINVAL,
                             "critical_speeds_damped: capacity %zu out of range [1, %d]", cap,
                             AUTOBAL_PENDULUM_MAX_CRIT);
  if (out == NULL) return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_speeds_damped: NULL output");
  memset(out, 0, sizeof *out);
  ctx.ws = ws;
  ctx.R_m = p->R_m;
  ctx.H = p->H;
  ctx.h = p->h;
  k_and_kc(p, &ctx.k, &ctx.kc);
  if ((st = damped_stable_pred(rw_min, &ctx, &prev)) != 0) return st;
  vint[0] = prev ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
  for (i = 1; i < n_sweep; i++) {
    double a = rw_min + (rw_max - rw_min) * (double)(i - 1) / (double)(n_sweep - 1);
    double b = i + 1 == n_sweep ? rw_max : rw_min + (rw_max - rw_min) * (double)i / (double)(n_sweep - 1);
    int cur;
    if ((st = damped_stable_pred(b, &ctx, &cur)) != 0) return st;
    if (cur != prev && nc >= cap) {
      /* one change more than the list holds: stop before refining it */
      truncated = 1;
      break;
    }
    if (cur != prev) {
      double lo, hi, x, fa, fb;
      if ((st = autobal_bisect_change(damped_stable_pred, &ctx, a, b, 0.0, 1e-13, &lo, &hi,
                                      &ws->err)) != 0)
        return st;
      x = 0.5 * (lo + hi);
      /* polish on max Re (continuous, crosses 0 transversally) */
      {
        double wa = lo - 1e-9 * (1 + lo), wb = hi + 1e-9 * (1 + hi);
        if (wa < a) wa = a;
        if (wb > b) wb = b;
        if ((st = damped_maxre_fn(wa, &ctx, &fa)) != 0) return st;
        if ((st = damped_maxre_fn(wb, &ctx, &fb)) != 0) return st;
        if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
          double root;
          if (autobal_root_brent(damped_maxre_fn, &ctx, wa, wb, 0.0, 1e-14, 200, &root, &ws->err) ==
              AUTOBAL_SUCCESS)
            x = root;
        }
      }
      autobal_error_clear(&ws->err);
      rw[nc] = x;
      vint[nc + 1] = cur ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
      nc++;
    }
    prev = cur;
  }
  if (!truncated) return crit_set_fill(out, rw, vint, nc, 0, rw_min, rw_max);
  /* truncated (nc = cap >= 1): the results cover [rw_min, rw[nc-1]] only.  The interval
   * after the last recorded change becomes (rw[nc-1], rw[nc-1]) and is dropped when stable:
   * no stable interval extends past the last recorded change. */
  (void)crit_set_fill(out, rw, vint, nc, 0, rw_min, rw[nc - 1]);
  if (out->n_stable > 0 && out->stable_lo[out->n_stable - 1] == rw[nc - 1] &&
      out->stable_hi[out->n_stable - 1] == rw[nc - 1]) {
    out->n_stable--;
    out->stable_lo[out->n_stable] = 0.0;
    out->stable_hi[out->n_stable] = 0.0;
  }
  out->truncated = 1;
  return autobal_error_set(&ws->err, AUTOBAL_WARNING,
                           "critical_speeds_damped: more than %zu stability changes for R_w in "
                           "[%.9g, %.9g] (the capacity of the list): the first %zu are kept and "
                           "the search stopped at the next one; the results cover R_w in [%.9g, "
                           "%.12g] only (up to the last kept change). Narrow the range (e.g. "
                           "rw_max <= %.12g) or split it",
                           cap, rw_min, rw_max, nc, rw_min, rw[nc - 1], rw[nc - 1]);
}

int autobal_pendulum_critical_speeds_damped(autobal_pendulum_workspace *ws,
                                            const autobal_pendulum_params *p, double rw_min,
                                            double rw_max, size_t n_sweep,
                                            autobal_pendulum_crit_set *out) {
  return autobal_pendulum_critical_speeds_damped_cap_(ws, p, rw_min, rw_max, n_sweep,
                                                      AUTOBAL_PENDULUM_MAX_CRIT, out);
}

/* ======================================================================== */
/* Closed forms and series (13)-(18), R_m^(1)                               */
/* ======================================================================== */

int autobal_pendulum_rw1_k0(double R_m, double *rw1, autobal_error *err) {
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "");
  if (st) return st;
  if (rw1) *rw1 = 1.0; /* (13) */
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw23_k0_series_small(double R_m, double *rw2, double *rw3,
                                          autobal_error *err) {
  double eps;
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "");
  if (st) return st;
  eps = cbrt(R_m / 2.0);
  /* (14), 0 < R_m < 0.05 */
  if (rw2) *rw2 = 1.0 + (49.0 / 16.0) * R_m + (12397.0 / 1024.0) * R_m * R_m;
  if (rw3) *rw3 = 1.0 + 2.0 * eps + (7.0 / 3.0) * eps * eps + (29.0 / 8.0) * eps * eps * eps;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw23_k0_series_large(double R_m, double *rw2, double *rw3,
                                          autobal_error *err) {
  double q, q2, pre, even, odd;
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.25, 1, "");
  if (st) return st;
  q = sqrt((0.25 - R_m) / 2.0); /* (14), corrected q */
  q2 = q * q;
  pre = 1.0 / (8.0 * q2);
  even = 1.0 + 5.5 * q2 - (155.0 / 8.0) * q2 * q2;
  odd = 2.0 * q - (37.0 / 4.0) * q2 * q;
  /* upper signs R_w3, lower signs R_w2 */
  if (rw3) *rw3 = pre * (even + odd);
  if (rw2) *rw2 = pre * (even - odd);
  return AUTOBAL_SUCCESS;
}

typedef struct {
  double s;
} u_ctx;

/* R_m = (u^3/(1-2u^2))^2  <=>  u^3 + 2 sqrt(R_m) u^2 - sqrt(R_m) = 0 on (0, 1/sqrt 2) */
static int u_fn(double u, void *vctx, double *fx) {
  const u_ctx *c = (const u_ctx *)vctx;
  *fx = u * u * u + 2.0 * c->s * u * u - c->s;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw1_k1(double R_m, double *rw1, double *u_out, autobal_error *err) {
  u_ctx c;
  double u;
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "");
  if (st) return st;
  c.s = sqrt(R_m);
  /* f(0) = -s < 0, f(1/sqrt 2) = 2^{-3/2} > 0, f increasing on u > 0 */
  st = autobal_root_brent(u_fn, &c, 0.0, sqrt(0.5), 1e-300, 4 * DBL_EPSILON, 400, &u, err);
  if (st) return st;
  if (u_out) *u_out = u;
  if (rw1) *rw1 = sqrt(1.0 - u * u) / (1.0 - 2.0 * u * u); /* (16) */
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw1_k1_series(double R_m, double *rw1, autobal_error *err) {
  double s;
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "");
  if (st) return st;
  s = cbrt(R_m);
  if (rw1) *rw1 = 1.0 + 1.5 * s + 0.875 * s * s + (1.0 / 48.0) * s * s * s; /* (17) */
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw23_k1(double R_m, double *rw23, autobal_error *err) {
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.25, 1, "");
  if (st) return st;
  if (rw23) *rw23 = sqrt(2.0 * (1.0 - 2.0 * R_m)) / (1.0 - 4.0 * R_m); /* (18) */
  return AUTOBAL_SUCCESS;
}

/* g'(u) for g(u) = R_w1(u) of (16) - R_w2/3(R_m(u)) of (18) */
static int g_prime_fn(double u, void *vctx, double *fx) {
  double A = sqrt(1.0 - u * u), B = 1.0 - 2.0 * u * u;
  double t = u * u * u / B, tp = (3.0 * u * u * B + 4.0 * u * u * u * u) / (B * B);
  double Rm = t * t, Rmp = 2.0 * t * tp;
  double C = sqrt(2.0 * (1.0 - 2.0 * Rm)), E = 1.0 - 4.0 * Rm;
  double d16 = (-u * B / A + 4.0 * u * A) / (B * B);
  double d18 = (-2.0 * E / C + 4.0 * C) / (E * E);
  (void)vctx;
  *fx = d16 - d18 * Rmp;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rm1(double *rm1, double *rw, autobal_error *err) {
  /* The curves touch where g has a double zero: g <= 0 near it with a
   * maximum 0, so g'(u) = 0 there.  Bracket the sign change of g' from + to -
   * by a scan over u (R_m(u) < 1/4 needs u < 0.5615), then Brent. */
  double a = 0.30, fa, u = 0.0, g;
  int i, st, found = 0;
  g_prime_fn(a, NULL, &fa);
  for (i = 1; i <= 200 && !found; i++) {
    double b = 0.30 + (0.56 - 0.30) * i / 200.0, fb;
    g_prime_fn(b, NULL, &fb);
    if (fa > 0 && fb <= 0) {
      st = autobal_root_brent(g_prime_fn, NULL, a, b, 1e-300, 4 * DBL_EPSILON, 400, &u, err);
      if (st) return st;
      found = 1;
    }
    a = b;
    fa = fb;
  }
  if (!found)
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "rm1: no maximum of (16) - (18) found");
  {
    double B = 1.0 - 2.0 * u * u, t = u * u * u / B, Rm = t * t;
    double r16 = sqrt(1.0 - u * u) / B;
    double r18 = sqrt(2.0 * (1.0 - 2.0 * Rm)) / (1.0 - 4.0 * Rm);
    g = r16 - r18;
    if (fabs(g) > 1e-8 * r16)
      return autobal_error_set(err, AUTOBAL_ENUMERIC,
                               "rm1: curves (16) and (18) do not touch at u = %.17g (gap %g)", u, g);
    if (rm1) *rm1 = Rm;
    if (rw) *rw = r16;
  }
  return AUTOBAL_SUCCESS;
}

/* ======================================================================== */
/* Maps                                                                     */
/* ======================================================================== */

#define MAP_DEFAULT_NK 65
/* Grid points per OpenMP work item (one row segment; a multiple of MAP_LANES,
 * so that the grouping of points into lanes does not depend on the schedule) */
#define MAP_TILE 64
/* Damped verdicts of MAP_LANES polynomials (6) with coefficients c[j] and
 * bounds ce[j], j = 0..8 (deflate: lambda = 0 divided out, degree 7, for
 * k == 0), s2 = max(1, W) per lane.  A lane with a non-finite coefficient
 * or bound (overflow at huge R_w) or a leading coefficient <= 0 goes to the
 * scalar test, which reports it (AUTOBAL_EINVAL) like autobal_pendulum_verdict. */
static MAP_INLINE int damped_lanes(const mvec *c, const mvec *ce, const mvec *s2, int deflate,
                                   int *v) {
  mvec col[9], colU[9], chk = ce[0];
  mmask alive, neg = MV_MASK0;
  size_t l, j, row, n = deflate ? 7 : 8, off = deflate ? 1 : 0;
  for (j = 1; j < 9; j++) chk = chk + ce[j];
  /* lanes stage 1 may decide: finite coefficients and bounds (chk - chk is
   * NaN for inf and NaN) and a positive leading coefficient; the kernel
   * runs on all lanes, the others' results are not used */
  alive = MV_CMP(chk - chk == 0.0) & MV_CMP(c[8] > 0.0);
  if (deflate) routh_quick7(c + 1, ce + 1, s2, col, colU);
  else routh_quick8(c, ce, s2, col, colU);
  /* the verdict rule, on all lanes at once: alive = every row so far
   * clears its bound, neg = a decided negative entry was met while alive */
  for (row = 1; row <= n; row++) {
    alive = alive & MV_CMP(MV_ABS(col[row]) > 2.0 * colU[row]);
    neg = neg | (alive & MV_CMP(col[row] < 0.0));
  }
  for (l = 0; l < MAP_LANES; l++) {
    v[l] = MV_L(neg, l) ? AUTOBAL_VERDICT_UNSTABLE : MV_L(alive, l) ? AUTOBAL_VERDICT_STABLE : 2;
    if (v[l] == 2) { /* near the boundary (or a bad lane): the full test */
      double cl[9], cel[9];
      int st;
      for (j = 0; j < 9; j++) cl[j] = MV_L(c[j], l), cel[j] = MV_L(ce[j], l);
      st = autobal_poly_hurwitz_err(cl + off, cel + off, n + 1, &v[l], NULL, NULL);
      if (st) return st;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* ---- undamped verdicts with a double-precision filter ------------------- */

/* The map's undamped verdict (MARGINAL, a point on a boundary, counts as
 * STABLE) is that of undamped_verdict_ld.  Its deciding quantities are
 * evaluated first in double together with the magnitude sums of their terms
 * (built from magnitudes of the coefficients, W - 1 counted as W + 1); a
 * quantity whose value exceeds MAP_FILTER times its magnitude sum has the
 * same sign in long double, far beyond the long-double rounding bound
 * PEND_GAMMA * LDBL_EPSILON (the double evaluation and the difference
 * between W in double and in long double perturb it by < 1e3 DBL_EPSILON of
 * the same sum).  Only when a needed quantity is below that threshold (near
 * a critical speed) is the long-double test run: the verdicts are those of
 * autobal_pendulum_undamped_verdict. */
#define MAP_FILTER 1e-10

/* The deciding quantities of the quartic c (ascending, lane-wise) and the
 * sums of the magnitudes of their terms evaluated on m (>= |c|): the
 * discriminant (the 16 terms of quartic_disc_ld), P8 = 8ac - 3b^2 and
 * D4 = 64a^3e - 16a^2c^2 + 16ab^2c - 16a^2bd - 3b^4 (quartic_aux_ld). */
typedef struct {
  mvec disc, mag, P8, m8, D4, m4;
} quartic_q;

static MAP_INLINE void quartic_quantities(const mvec *c, const mvec *m, quartic_q *r) {
  mvec a = c[4], b = c[3], cc = c[2], d = c[1], e = c[0];
  mvec a2 = a * a, b2 = b * b, c2 = cc * cc, d2 = d * d, e2 = e * e;
  mvec ma = m[4], mb = m[3], mc = m[2], md = m[1], me = m[0];
  mvec ma2 = ma * ma, mb2 = mb * mb, mc2 = mc * mc, md2 = md * md, me2 = me * me;
  r->disc = 256.0 * a2 * a * e2 * e - 192.0 * a2 * b * d * e2 - 128.0 * a2 * c2 * e2 +
            144.0 * a2 * cc * d2 * e - 27.0 * a2 * d2 * d2 + 144.0 * a * b2 * cc * e2 -
            6.0 * a * b2 * d2 * e - 80.0 * a * b * c2 * d * e + 18.0 * a * b * cc * d2 * d +
            16.0 * a * c2 * c2 * e - 4.0 * a * c2 * cc * d2 - 27.0 * b2 * b2 * e2 +
            18.0 * b2 * b * cc * d * e - 4.0 * b2 * b * d2 * d - 4.0 * b2 * c2 * cc * e +
            b2 * c2 * d2;
  r->mag = 256.0 * ma2 * ma * me2 * me + 192.0 * ma2 * mb * md * me2 + 128.0 * ma2 * mc2 * me2 +
           144.0 * ma2 * mc * md2 * me + 27.0 * ma2 * md2 * md2 + 144.0 * ma * mb2 * mc * me2 +
           6.0 * ma * mb2 * md2 * me + 80.0 * ma * mb * mc2 * md * me +
           18.0 * ma * mb * mc * md2 * md + 16.0 * ma * mc2 * mc2 * me +
           4.0 * ma * mc2 * mc * md2 + 27.0 * mb2 * mb2 * me2 + 18.0 * mb2 * mb * mc * md * me +
           4.0 * mb2 * mb * md2 * md + 4.0 * mb2 * mc2 * mc * me + mb2 * mc2 * md2;
  r->P8 = 8.0 * a * cc - 3.0 * b2;
  r->m8 = 8.0 * ma * mc + 3.0 * mb2;
  r->D4 = 64.0 * a2 * a * e - 16.0 * a2 * c2 + 16.0 * a * b2 * cc - 16.0 * a2 * b * d -
          3.0 * b2 * b2;
  r->m4 = 64.0 * ma2 * ma * me + 16.0 * ma2 * mc2 + 16.0 * ma * mb2 * mc + 16.0 * ma2 * mb * md +
          3.0 * mb2 * mb2;
}

/* sign of x if |x| > MAP_FILTER * mag, else 0 (undecided) */
static MAP_INLINE int filt_sign(double x, double mag) {
  if (x > MAP_FILTER * mag) return 1;
  if (x < -MAP_FILTER * mag) return -1;
  return 0;
}

/* The quartic part of the undamped test (k > 0) for lane l: UNSTABLE iff
 * disc < 0 or P8 >= 0 or D4 >= 0; 0 when undecided. */
static MAP_INLINE int quartic_decide(const quartic_q *q, size_t l) {
  int sd = filt_sign(MV_L(q->disc, l), MV_L(q->mag, l)), s8, s4;
  if (sd < 0) return AUTOBAL_VERDICT_UNSTABLE;
  if (sd == 0) return 0;
  s8 = filt_sign(MV_L(q->P8, l), MV_L(q->m8, l));
  if (s8 > 0) return AUTOBAL_VERDICT_UNSTABLE;
  s4 = filt_sign(MV_L(q->D4, l), MV_L(q->m4, l));
  if (s4 > 0) return AUTOBAL_VERDICT_UNSTABLE;
  if (s8 < 0 && s4 < 0) return AUTOBAL_VERDICT_STABLE;
  return 0;
}

/* the exact long-double test, with the map's convention MARGINAL -> STABLE */
static int undamped_map_exact(double Rm, double Rw, double k) {
  int v = undamped_verdict_ld(Rm, (long double)Rw * Rw, k, NULL);
  return v == AUTOBAL_VERDICT_MARGINAL ? AUTOBAL_VERDICT_STABLE : v; /* on a boundary */
}

/* The map's undamped verdicts for 0 < k < 1 of MAP_LANES lanes (R_w[l], k[l]):
 * P(x) of (10), c_j with magnitudes m_j; unstable iff c_1 < 0 or the quartic
 * test says so (c_0, c_2, c_3, c_4 > 0 always). */
static MAP_INLINE void undamped_lanes(const mvec *Rwp, double Rm, const mvec *kp, int *v) {
  mvec Rw = *Rwp, k = *kp, W = Rw * Rw, r2 = k * Rm * Rm, W2 = W * W, W3 = W2 * W;
  mvec a0 = 2.0 * Rm * W2 * (W - 1.0), m0 = 2.0 * Rm * W2 * (W + 1.0);
  mvec a2 = (W - 1.0) * (W - 1.0) + 2.0 * Rm * W * (W + 6.0);
  mvec m2 = (W + 1.0) * (W + 1.0) + 2.0 * Rm * W * (W + 6.0);
  mvec a4 = 2.0 * (1.0 - Rm) * (W + 1.0);
  mvec c[5], m[5];
  quartic_q q;
  size_t l;
  c[0] = r2 * W2 * W2, m[0] = c[0];
  c[1] = a0 + 4.0 * r2 * W3, m[1] = m0 + 4.0 * r2 * W3;
  c[2] = a2 + 6.0 * r2 * W2, m[2] = m2 + 6.0 * r2 * W2;
  c[3] = a4 + 4.0 * r2 * W, m[3] = c[3];
  c[4] = (1.0 - 2.0 * Rm) + r2, m[4] = c[4];
  quartic_quantities(c, m, &q);
  for (l = 0; l < MAP_LANES; l++) {
    int sd = filt_sign(MV_L(c[1], l), MV_L(m[1], l));
    v[l] = sd < 0 ? AUTOBAL_VERDICT_UNSTABLE : sd > 0 ? quartic_decide(&q, l) : 0;
    if (v[l] == 0) v[l] = undamped_map_exact(Rm, MV_L(Rw, l), MV_L(k, l));
  }
}

/* The map's undamped verdict at one point and one k: STABLE or UNSTABLE. */
static int undamped_map_verdict(double Rm, double Rw, double k) {
  double W = Rw * Rw;
  int v = 0;
  if (k == 1.0) {
    mvec c[5], m[5];
    quartic_q q;
    c[0] = MV_BCAST(-W), m[0] = MV_BCAST(W);
    c[1] = MV_BCAST(2.0 * Rw), m[1] = c[1];
    c[2] = MV_BCAST(W - 1.0), m[2] = MV_BCAST(W + 1.0);
    c[3] = MV_BCAST(-2.0 * Rw), m[3] = c[1];
    c[4] = MV_BCAST(1.0 - Rm), m[4] = c[4];
    quartic_quantities(c, m, &q);
    v = quartic_decide(&q, 0);
  } else if (k == 0.0) {
    /* x times the cubic a6 x^3 + a4 x^2 + a2 x + a0: unstable iff a0 < 0 or
     * its discriminant < 0 */
    double a0 = 2.0 * Rm * W * W * (W - 1.0), m0 = 2.0 * Rm * W * W * (W + 1.0);
    double a2 = (W - 1.0) * (W - 1.0) + 2.0 * Rm * W * (W + 6.0);
    double m2 = (W + 1.0) * (W + 1.0) + 2.0 * Rm * W * (W + 6.0);
    double a4 = 2.0 * (1.0 - Rm) * (W + 1.0), a6 = 1.0 - 2.0 * Rm;
    int s0 = filt_sign(a0, m0);
    if (s0 < 0) v = AUTOBAL_VERDICT_UNSTABLE;
    else if (s0 > 0) {
      double d = 18.0 * a6 * a4 * a2 * a0 - 4.0 * a4 * a4 * a4 * a0 + a4 * a4 * a2 * a2 -
                 4.0 * a6 * a2 * a2 * a2 - 27.0 * a6 * a6 * a0 * a0;
      double md = 18.0 * a6 * a4 * m2 * m0 + 4.0 * a4 * a4 * a4 * m0 + a4 * a4 * m2 * m2 +
                  4.0 * a6 * m2 * m2 * m2 + 27.0 * a6 * a6 * m0 * m0;
      int sd = filt_sign(d, md);
      v = sd < 0 ? AUTOBAL_VERDICT_UNSTABLE : sd > 0 ? AUTOBAL_VERDICT_STABLE : 0;
    }
  } else {
    mvec Rwv = MV_BCAST(Rw), kv = MV_BCAST(k);
    int vl[MAP_LANES];
    undamped_lanes(&Rwv, Rm, &kv, vl);
    return vl[0];
  }
  if (v == 0) v = undamped_map_exact(Rm, Rw, k); /* undecided in double */
  return v;
}

/* ---- grid points --------------------------------------------------------- */

typedef struct {
  const autobal_pendulum_map_spec *s;
  const double *ks;
  size_t nk;
  int undamped;
  int has_zero; /* some k == 0 (the damped test deflates lambda = 0 there) */
  int has_one;  /* some k == 1 (the undamped test uses the factor P1 there) */
} map_ctx;

/* Point (Rm, Rw) with a root solve per k for max_real (the slow path). */
static int map_point(const map_ctx *mc, double Rm, double Rw, autobal_pendulum_workspace *ws,
                     signed char *v, double *mr) {
  const autobal_pendulum_map_spec *s = mc->s;
  size_t i;
  int worst = AUTOBAL_VERDICT_STABLE;
  double mre = -INFINITY;
  char_parts_t P;
  memset(&P, 0, sizeof P);
  if (!mc->undamped) char_parts(Rw, Rm, s->H, s->h, &P, NULL); /* independent of k */
  for (i = 0; i < mc->nk; i++) {
    double k = mc->ks[i], kc = 1.0 - k, m;
    int vv, st;
    damped_ctx c;
    if (mc->undamped) {
      vv = undamped_map_verdict(Rm, Rw, k);
    } else {
      double coef[9], cerr[9];
      char_poly_from_parts(Rw, Rm, &P, k, kc, coef, cerr);
      st = sign_test_poly(coef, cerr, Rw * Rw, k == 0.0, &vv, NULL, NULL);
      if (st) return st;
    }
    if (vv < worst) worst = vv;
    c.ws = ws;
    c.R_m = Rm;
    c.H = s->H;
    c.h = s->h;
    c.k = k;
    c.kc = kc;
    st = damped_maxre_fn(Rw, &c, &m);
    if (st) return st;
    if (m > mre) mre = m;
  }
  *v = (signed char)worst;
  *mr = mre;
  return AUTOBAL_SUCCESS;
}

/* Verdict at one point over the whole k set (no max_real): the k set is
 * taken MAP_LANES at a time and the scan stops at the first UNSTABLE group.
 * *hint (per thread) is the group that was unstable last time, tried first:
 * the verdict (a minimum over all k) does not depend on the order. */
MAP_CLONES static int map_point_all_k(const map_ctx *mc, double Rm, double Rw, size_t *hint,
                                      signed char *v) {
  const autobal_pendulum_map_spec *s = mc->s;
  size_t ng = (mc->nk + MAP_LANES - 1) / MAP_LANES, t, l;
  int worst = AUTOBAL_VERDICT_STABLE, st, und = mc->undamped;
  char_parts_t P;
  mvec c[9], ce[9], s2 = MV_BCAST(Rw * Rw > 1.0 ? Rw * Rw : 1.0), Rwv = MV_BCAST(Rw);
  /* the special values, once each: k == 0 (damped: lambda = 0 deflated;
   * undamped: the cubic) and, undamped, k == 1 (the factor P1) */
  char_parts_v(&Rwv, Rm, s->H, s->h, P.A, P.Aa, P.B, NULL); /* (unused when undamped) */
  if (und) {
    if (mc->has_zero) worst = undamped_map_verdict(Rm, Rw, 0.0);
    if (mc->has_one && worst != AUTOBAL_VERDICT_UNSTABLE) {
      int v1 = undamped_map_verdict(Rm, Rw, 1.0);
      if (v1 < worst) worst = v1;
    }
  } else if (mc->has_zero) {
    mvec kz = MV_BCAST(0.0), kcz = MV_BCAST(1.0);
    int vz[MAP_LANES];
    char_poly_from_parts_v(&Rwv, Rm, P.A, P.Aa, P.B, &kz, &kcz, c, ce);
    if ((st = damped_lanes(c, ce, &s2, 1, vz)) != 0) return st;
    worst = vz[0];
  }
  for (t = 0; t < ng && worst != AUTOBAL_VERDICT_UNSTABLE; t++) {
    size_t g = (*hint + t) % ng, i0 = g * MAP_LANES, n = 0;
    double fill = 0.0;
    mvec kv;
    int vl[MAP_LANES];
    for (l = 0; l < MAP_LANES && i0 + l < mc->nk; l++) {
      double k = mc->ks[i0 + l];
      if (k != 0.0 && !(und && k == 1.0)) fill = k, n++;
    }
    if (n == 0) continue; /* only special values here, done above */
    kv = MV_BCAST(fill);
    for (l = 0; l < MAP_LANES && i0 + l < mc->nk; l++) {
      double k = mc->ks[i0 + l];
      if (k != 0.0 && !(und && k == 1.0)) MV_L(kv, l) = k;
    }
    if (und) {
      undamped_lanes(&Rwv, Rm, &kv, vl);
    } else {
      mvec kcv = 1.0 - kv;
      char_poly_from_parts_v(&Rwv, Rm, P.A, P.Aa, P.B, &kv, &kcv, c, ce);
      if ((st = damped_lanes(c, ce, &s2, 0, vl)) != 0) return st;
    }
    for (l = 0; l < MAP_LANES; l++)
      if (vl[l] < worst) worst = vl[l];
    if (worst == AUTOBAL_VERDICT_UNSTABLE) *hint = g;
  }
  *v = (signed char)worst;
  return AUTOBAL_SUCCESS;
}

/* One work item: row i, columns [j0, j1). */
MAP_CLONES static int map_tile(const map_ctx *mc, size_t i, size_t j0, size_t j1,
                    autobal_pendulum_workspace *ws, size_t *hint, signed char *verdict,
                    double *max_real) {
  const autobal_pendulum_map_spec *s = mc->s;
  double Rm = s->R_m[i];
  size_t j, l, base = i * s->n_Rw;
  int st;
  if (max_real) {
    for (j = j0; j < j1; j++)
      if ((st = map_point(mc, Rm, s->R_w[j], ws, &verdict[base + j], &max_real[base + j])) != 0)
        return st;
    return AUTOBAL_SUCCESS;
  }
  if (mc->nk > 1 || (mc->undamped && (mc->ks[0] == 0.0 || mc->ks[0] == 1.0))) {
    for (j = j0; j < j1; j++)
      if ((st = map_point_all_k(mc, Rm, s->R_w[j], hint, &verdict[base + j])) != 0) return st;
    return AUTOBAL_SUCCESS;
  }
  if (mc->undamped) { /* one k in (0, 1): MAP_LANES neighbouring R_w at once */
    for (j = j0; j < j1; j += MAP_LANES) {
      mvec Rwv, kv = MV_BCAST(mc->ks[0]);
      int vl[MAP_LANES];
      for (l = 0; l < MAP_LANES; l++) MV_L(Rwv, l) = s->R_w[j + l < j1 ? j + l : j1 - 1];
      undamped_lanes(&Rwv, Rm, &kv, vl);
      for (l = 0; l < MAP_LANES && j + l < j1; l++) verdict[base + j + l] = (signed char)vl[l];
    }
    return AUTOBAL_SUCCESS;
  }
  /* damped, one k: MAP_LANES neighbouring R_w at once (the last group is
   * padded with copies of its last point) */
  for (j = j0; j < j1; j += MAP_LANES) {
    mvec c[9], ce[9], s2, Rwv, kv = MV_BCAST(mc->ks[0]), kcv = 1.0 - kv;
    char_parts_t P;
    int vl[MAP_LANES];
    for (l = 0; l < MAP_LANES; l++) {
      double Rw = s->R_w[j + l < j1 ? j + l : j1 - 1];
      MV_L(Rwv, l) = Rw;
      MV_L(s2, l) = Rw * Rw > 1.0 ? Rw * Rw : 1.0;
    }
    char_parts_v(&Rwv, Rm, s->H, s->h, P.A, P.Aa, P.B, NULL);
    char_poly_from_parts_v(&Rwv, Rm, P.A, P.Aa, P.B, &kv, &kcv, c, ce);
    if ((st = damped_lanes(c, ce, &s2, mc->ks[0] == 0.0, vl)) != 0) return st;
    for (l = 0; l < MAP_LANES && j + l < j1; l++) verdict[base + j + l] = (signed char)vl[l];
  }
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_map(const autobal_pendulum_map_spec *s, signed char *verdict,
                         double *max_real, autobal_error *err) {
  double kdef[MAP_DEFAULT_NK];
  const double *ks;
  size_t nk, i, ntot, tpr, ntiles;
  int st, fail = AUTOBAL_SUCCESS;
  char name[40];
  map_ctx mc;
  if (s == NULL || verdict == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: NULL spec or output");
  if ((s->n_Rm > 0 && s->R_m == NULL) || (s->n_Rw > 0 && s->R_w == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: NULL grid array");
  if ((st = autobal_check_param(err, "H", s->H, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "h", s->h, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if (s->n_threads < 0)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter n_threads = %d is out of range: allowed [0, inf)",
                             s->n_threads);
  for (i = 0; i < s->n_Rm; i++) {
    snprintf(name, sizeof name, "R_m[%zu]", i);
    if ((st = autobal_check_param(err, name, s->R_m[i], 0.0, 1, 0.5, 1, "")) != 0) return st;
  }
  for (i = 0; i < s->n_Rw; i++) {
    snprintf(name, sizeof name, "R_w[%zu]", i);
    if ((st = autobal_check_param(err, name, s->R_w[i], 0.0, 0, INFINITY, 1, "")) != 0) return st;
  }
  if (s->k == NULL || s->n_k == 0) {
    if (s->k == NULL && s->n_k != 0)
      return autobal_error_set(err, AUTOBAL_EINVAL, "map: k is NULL but n_k = %zu", s->n_k);
    for (i = 0; i < MAP_DEFAULT_NK; i++) kdef[i] = (double)i / (double)(MAP_DEFAULT_NK - 1);
    ks = kdef;
    nk = MAP_DEFAULT_NK;
  } else {
    for (i = 0; i < s->n_k; i++) {
      snprintf(name, sizeof name, "k[%zu]", i);
      if ((st = autobal_check_param(err, name, s->k[i], 0.0, 0, 1.0, 0, "")) != 0) return st;
    }
    ks = s->k;
    nk = s->n_k;
  }
  ntot = s->n_Rm * s->n_Rw;
  if (ntot == 0) return AUTOBAL_SUCCESS;
  mc.s = s;
  mc.ks = ks;
  mc.nk = nk;
  mc.undamped = s->H == 0.0 && s->h == 0.0;
  mc.has_zero = mc.has_one = 0;
  for (i = 0; i < nk; i++) {
    if (ks[i] == 0.0) mc.has_zero = 1;
    if (ks[i] == 1.0) mc.has_one = 1;
  }
  tpr = (s->n_Rw + MAP_TILE - 1) / MAP_TILE;
  ntiles = s->n_Rm * tpr;
#ifdef AUTOBAL_HAVE_OPENMP
  {
    int nth = s->n_threads > 0 ? s->n_threads : omp_get_max_threads();
#pragma omp parallel num_threads(nth)
    {
      autobal_pendulum_workspace *ws = NULL;
      int local = AUTOBAL_SUCCESS;
      size_t hint = 0;
      long long t;
      if (max_real) {
        ws = autobal_pendulum_workspace_alloc();
        if (ws == NULL) local = AUTOBAL_ENOMEM;
      }
#pragma omp for schedule(dynamic, 1)
      for (t = 0; t < (long long)ntiles; t++) {
        size_t ii = (size_t)t / tpr, j0 = ((size_t)t % tpr) * MAP_TILE;
        size_t j1 = j0 + MAP_TILE < s->n_Rw ? j0 + MAP_TILE : s->n_Rw;
        if (local != AUTOBAL_SUCCESS) continue;
        local = map_tile(&mc, ii, j0, j1, ws, &hint, verdict, max_real);
      }
      if (local != AUTOBAL_SUCCESS) {
#pragma omp critical(autobal_pendulum_map_fail)
        {
          if (fail == AUTOBAL_SUCCESS) fail = local;
        }
      }
      autobal_pendulum_workspace_free(ws);
    }
  }
#else
  {
    autobal_pendulum_workspace *ws = NULL;
    size_t t, hint = 0;
    if (max_real) {
      ws = autobal_pendulum_workspace_alloc();
      if (ws == NULL) fail = AUTOBAL_ENOMEM;
    }
    for (t = 0; t < ntiles && fail == AUTOBAL_SUCCESS; t++) {
      size_t ii = t / tpr, j0 = (t % tpr) * MAP_TILE;
      size_t j1 = j0 + MAP_TILE < s->n_Rw ? j0 + MAP_TILE : s->n_Rw;
      fail = map_tile(&mc, ii, j0, j1, ws, &hint, verdict, max_real);
    }
    autobal_pendulum_workspace_free(ws);
  }
#endif
  if (fail == AUTOBAL_ENOMEM)
    return autobal_error_set(err, AUTOBAL_ENOMEM, "map: cannot allocate a per-thread workspace");
  if (fail != AUTOBAL_SUCCESS)
    return autobal_error_set(err, fail, "map: evaluation failed at a grid point (%s)",
                             autobal_strerror(fail));
  return AUTOBAL_SUCCESS;
}
