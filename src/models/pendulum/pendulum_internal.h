/* pendulum_internal.h: the kernel of the characteristic polynomial (6) of the two-pendulum
 * model shared by the model (pendulum.c) and its analysis (src/analysis/pendulum_*.c), not
 * installed.  The kernel is static inline (always inlined with GCC), so that the one-point
 * functions, the sign tests and the maps evaluate (6) with the same operations, bit for bit,
 * in every translation unit and in every clone (MAP_CLONES).  Includes no other private
 * header but internal.h. */
#ifndef AUTOBAL_PENDULUM_INTERNAL_H
#define AUTOBAL_PENDULUM_INTERNAL_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "autobal/pendulum.h"
#include "internal.h"

#define PEND_PI 3.14159265358979323846
#define U_D DBL_EPSILON
#define U_LD LDBL_EPSILON
/* Safety factor on first-order rounding-error bounds (number of operations
 * per coefficient is far below this). */
#define PEND_GAMMA 64.0

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
static MAP_INLINE void autobal_pendulum_char_parts_v_(const mvec *Rw, double R_m, double H,
                                                      double h, mvec A[9], mvec Aabs[9], mvec B[9],
                                                      mvec p1_out[10]) {
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

/* (6) from its parts (autobal_pendulum_char_parts_v_) for given k (kc = cos^2(2 psi0) = 1 - k),
 * with absolute error bounds cerr (may be NULL):
 * AUTOBAL_PENDULUM_HURWITZ_RTOL relative plus rounding.  Lane-wise. */
static MAP_INLINE void autobal_pendulum_char_poly_from_parts_v_(const mvec *Rw, double R_m,
                                                                const mvec A[9], const mvec Aa[9],
                                                                const mvec B[9], const mvec *kp,
                                                                const mvec *kcp, mvec coef[9],
                                                                mvec cerr[9]) {
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
} autobal_pendulum_char_parts_t_;

static MAP_INLINE void autobal_pendulum_char_parts_(double R_w, double R_m, double H, double h,
                                                    autobal_pendulum_char_parts_t_ *P,
                                                    double p1_out[10]) {
  mvec Rw = MV_BCAST(R_w), p1[10];
  size_t j;
  autobal_pendulum_char_parts_v_(&Rw, R_m, H, h, P->A, P->Aa, P->B, p1_out ? p1 : NULL);
  if (p1_out)
    for (j = 0; j < 10; j++) p1_out[j] = MV_L(p1[j], 0);
}

static MAP_INLINE void autobal_pendulum_char_poly_from_parts_(double R_w, double R_m,
                                                              const autobal_pendulum_char_parts_t_ *P,
                                                              double k, double kc, double coef[9],
                                                              double cerr[9]) {
  mvec Rw = MV_BCAST(R_w), kv = MV_BCAST(k), kcv = MV_BCAST(kc), c[9], ce[9];
  size_t j;
  autobal_pendulum_char_poly_from_parts_v_(&Rw, R_m, P->A, P->Aa, P->B, &kv, &kcv, c, cerr ? ce : NULL);
  for (j = 0; j < 9; j++) {
    coef[j] = MV_L(c[j], 0);
    if (cerr) cerr[j] = MV_L(ce[j], 0);
  }
}

/* (6) for given k, see autobal_pendulum_char_poly_from_parts_ */
static MAP_INLINE void autobal_pendulum_char_poly_k_(double R_w, double R_m, double H, double h,
                                                     double k, double kc, double coef[9],
                                                     double cerr[9]) {
  autobal_pendulum_char_parts_t_ P;
  autobal_pendulum_char_parts_(R_w, R_m, H, h, &P, NULL);
  autobal_pendulum_char_poly_from_parts_(R_w, R_m, &P, k, kc, coef, cerr);
}

/* k = sin^2(2 psi0), kc = cos^2(2 psi0) of the parameters. */
void autobal_pendulum_k_and_kc_(const autobal_pendulum_params *p, double *k, double *kc);

#endif
