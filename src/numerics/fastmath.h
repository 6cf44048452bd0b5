/* fastmath.h (library-private): a branch-free sin/cos pair for the rotor's
 * per-ball loops, written so that GCC vectorizes it over arrays (and, at the
 * end, a hypot by sqrt where that is safe: autobal_hypot_fast).  Both serve
 * the derived quantities of the transients with output = dense6 too
 * (pendulum_motion.c, rotor.c).
 *
 * Method (fdlibm/FreeBSD msun, made branch-free):
 *  - Cody-Waite reduction x = k pi/2 + r, k = nearest integer to x 2/pi
 *    (rounded by adding and subtracting 1.5 * 2^52, so k's low bits are read
 *    from the sum's mantissa: no float-to-int conversion), with pi/2 split in
 *    P1 + P2 + P3 + P3t (fdlibm's pio2_1, pio2_2, pio2_3, pio2_3t: 31, 32 and
 *    28 significant bits and a 53-bit tail; pi/2 - (P1 + P2 + P3 + P3t) is
 *    7.4e-49).  For |k| < 2^21 the products k P1, k P2, k P3 are exact and
 *    x - k P1 is exact; the two remaining subtractions are error-free
 *    (Knuth's TwoSum), so r comes out as a double-double y0 + y1 with an
 *    error below about 2^-135 + 2^-105 |r| (k P3t rounded, the tail of pi/2,
 *    the rounding of the sum of the low-order parts).  The smallest |r| over
 *    all doubles |x| < 2^22 is 6.2e-19 = 2^-60.5 (at x near 29 pi/2;
 *    continued fractions of 2^(52-e) pi/2 per binade e), so the relative
 *    error of r is below 2^-74 even next to multiples of pi/2.
 *  - Kernels on |r| <= pi/4 (+ a rounding margin): FreeBSD's __kernel_sin
 *    and __kernel_cos (minimax polynomials of degree 13 and 14 with the tail
 *    y1 of r; error < 1 ulp in both), used unconditionally (no |x| < 2^-27
 *    shortcut, no branch on the tail).
 *  - Quadrant: sin x = (s, c, -s, -c)[k mod 4], cos x = (c, -s, -c, s)[k mod 4],
 *    selected with integer masks and sign-bit XORs (no branches).
 * The kernels' coefficients and the split of pi/2 are fdlibm's, which carries
 * this notice:
 *   Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved.
 *   Developed at SunPro, a Sun Microsystems, Inc. business.
 *   Permission to use, copy, modify, and distribute this software is freely
 *   granted, provided that this notice is preserved.
 * Only IEEE double additions, subtractions and multiplications in a fixed
 * order (no FMA contraction: the library is compiled as ISO C11, so GCC's
 * -ffp-contract=off applies): the vector and scalar forms of the loop, and
 * GCC's AVX2 and baseline clones, give the same bits.
 *
 * Range: |x| <= AUTOBAL_SINCOS_MAX = 2^21 rad (about 2.1e6 rad: 70 minutes at
 * 500 rad/s).  Above it, and for NaN and +-inf, autobal_sincos_array falls
 * back to libm's sin and cos for that element (so NaN in gives NaN out, +-inf
 * gives NaN).  Measured (bench/README.md: 1e7 random arguments in 7 ranges up
 * to 2^21, and the 3 doubles each side of every k pi/2 up to 2^21): at most
 * 0.79 ulp (sin) and 0.77 ulp (cos) from the true values (64-bit long double
 * sinl, cosl), 0.5 ulp next to multiples of pi/2, at most 1 ulp from glibc's
 * sin and cos; tests/test_rotor.c checks 5e5 such arguments.  Signed zeros:
 * sin(+-0) = +-0, cos(+-0) = 1.
 */
#ifndef AUTOBAL_FASTMATH_H
#define AUTOBAL_FASTMATH_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#if defined(__GNUC__)
#define AUTOBAL_FM_INLINE __attribute__((always_inline)) inline
#else
#define AUTOBAL_FM_INLINE inline
#endif

/* Largest |x| (rad) handled by the fast path; larger, NaN and inf go to libm. */
#define AUTOBAL_SINCOS_MAX 0x1p21

/* The fast path for one argument, |x| <= AUTOBAL_SINCOS_MAX (not checked:
 * outside it the results are meaningless but the call is harmless). */
static AUTOBAL_FM_INLINE void autobal_sincos_fast(double x, double *sn, double *cs) {
  /* fdlibm e_rem_pio2.c: invpio2, pio2_1, pio2_2, pio2_3, pio2_3t */
  const double inv_pio2 = 0x1.45f306dc9c883p-1;
  const double P1 = 0x1.921fb544p+0, P2 = 0x1.0b4611a6p-34, P3 = 0x1.3198a2ep-69;
  const double P3t = 0x1.b839a252049c1p-104;
  const double shift = 0x1.8p52;
  /* FreeBSD k_sin.c / k_cos.c */
  const double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
               S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
               S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  const double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
               C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
               C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  double kb, kd, t1, w2, w3, s, bb, e1, s2, bb2, e2, nlo, y0, y1;
  double z, w, v, rs, rc, hz, wc, ks, kc;
  uint64_t q, ub, cb, swap, sgn_s, sgn_c, bs, bc;

  /* k = nearest integer to x 2/pi; its low bits are the low mantissa bits of kb */
  kb = x * inv_pio2 + shift;
  kd = kb - shift;
  memcpy(&q, &kb, sizeof q);
  /* r = x - k pi/2 as y0 + y1 */
  t1 = x - kd * P1; /* exact */
  w2 = kd * P2;     /* exact */
  s = t1 - w2;      /* TwoSum(t1, -w2): s + e1 = t1 - w2 exactly */
  bb = s - t1;
  e1 = (t1 - (s - bb)) - (w2 + bb);
  w3 = kd * P3; /* exact */
  s2 = s - w3;  /* TwoSum(s, -w3) */
  bb2 = s2 - s;
  e2 = (s - (s2 - bb2)) - (w3 + bb2);
  nlo = kd * P3t - (e1 + e2); /* r = s2 - nlo (written so that r = -0 stays -0) */
  y0 = s2 - nlo;
  y1 = (s2 - y0) - nlo; /* Fast2Sum: |s2| >> |nlo| */

  /* __kernel_sin(y0, y1, 1) */
  z = y0 * y0;
  w = z * z;
  rs = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
  v = z * y0;
  ks = y0 - ((z * (0.5 * y1 - v * rs) - y1) - v * S1);
  /* __kernel_cos(y0, y1) */
  rc = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
  hz = 0.5 * z;
  wc = 1.0 - hz;
  kc = wc + (((1.0 - wc) - hz) + (z * rc - y0 * y1));

  /* quadrant */
  memcpy(&ub, &ks, sizeof ub);
  memcpy(&cb, &kc, sizeof cb);
  swap = (uint64_t)0 - (q & 1u);            /* all ones for odd k */
  sgn_s = (q & 2u) << 62;                   /* sin negated for k mod 4 = 2, 3 */
  sgn_c = ((q + 1u) & 2u) << 62;            /* cos negated for k mod 4 = 1, 2 */
  bs = ((ub & ~swap) | (cb & swap)) ^ sgn_s;
  bc = ((cb & ~swap) | (ub & swap)) ^ sgn_c;
  memcpy(sn, &bs, sizeof bs);
  memcpy(cs, &bc, sizeof bc);
}

/* 1 if x is in the fast path's range (|x| <= AUTOBAL_SINCOS_MAX, so not NaN or inf). */
static AUTOBAL_FM_INLINE int autobal_sincos_in_range(double x) {
  return fabs(x) <= AUTOBAL_SINCOS_MAX;
}

/* sin and cos of one argument: the fast path, or libm outside its range. */
static AUTOBAL_FM_INLINE void autobal_sincos1(double x, double *sn, double *cs) {
  if (autobal_sincos_in_range(x)) {
    autobal_sincos_fast(x, sn, cs);
  } else {
    *sn = sin(x);
    *cs = cos(x);
  }
}

/* sn[k] = sin(x[k]), cs[k] = cos(x[k]) for k < n.  One branch-free pass over
 * all elements (vectorizable: x, sn, cs must not overlap), then libm for the
 * elements out of range, if any.  Returns the number of such elements. */
static AUTOBAL_FM_INLINE size_t autobal_sincos_array(const double *restrict x, double *restrict sn,
                                                     double *restrict cs, size_t n) {
  /* Out of range: the bits of |x| (a non-negative double, NaN and inf
   * included, orders like its bit pattern) exceed those of the bound, so
   * maxbits - bits wraps around and sets the top bit.  An OR reduction of
   * integer differences (no comparisons: SSE2 has no 64-bit compare, so GCC
   * would not vectorize the loop on the baseline target). */
  const double bound = AUTOBAL_SINCOS_MAX;
  const uint64_t absmask = ~((uint64_t)1 << 63);
  uint64_t maxbits, bad = 0;
  size_t k, nbad = 0;
  memcpy(&maxbits, &bound, sizeof maxbits);
  for (k = 0; k < n; k++) {
    uint64_t b;
    memcpy(&b, &x[k], sizeof b);
    bad |= maxbits - (b & absmask);
    autobal_sincos_fast(x[k], &sn[k], &cs[k]);
  }
  if ((bad >> 63) != 0) {
    for (k = 0; k < n; k++) {
      if (!autobal_sincos_in_range(x[k])) {
        sn[k] = sin(x[k]);
        cs[k] = cos(x[k]);
        nbad++;
      }
    }
  }
  return nbad;
}

/* autobal_sincos_fast's kernel on every lane of a GCC/Clang vector (VT: doubles, UT: uint64_t of
 * the same size; x, sn, cs: VT lvalues, x not among sn, cs): the same operations in the same order,
 * the constants broadcast from the same scalars, so each lane gets the bits of autobal_sincos_fast
 * (no range check: the callers below do it).  Written once for the 2- and the 4-lane forms. */
#define AUTOBAL_FM_SINCOS_LANES(VT, UT, x, sn, cs)                                                     \
  do {                                                                                                 \
    const VT kb_ = (x) * 0x1.45f306dc9c883p-1 + 0x1.8p52; /* inv_pio2, shift */                        \
    const VT kd_ = kb_ - 0x1.8p52;                                                                     \
    const UT q_ = (UT)kb_;                                                                             \
    const VT t1_ = (x) - kd_ * 0x1.921fb544p+0; /* P1 */                                               \
    const VT w2_ = kd_ * 0x1.0b4611a6p-34;      /* P2 */                                               \
    const VT s_ = t1_ - w2_;                                                                           \
    const VT bb_ = s_ - t1_;                                                                           \
    const VT e1_ = (t1_ - (s_ - bb_)) - (w2_ + bb_);                                                   \
    const VT w3_ = kd_ * 0x1.3198a2ep-69; /* P3 */                                                     \
    const VT s2_ = s_ - w3_;                                                                           \
    const VT bb2_ = s2_ - s_;                                                                          \
    const VT e2_ = (s_ - (s2_ - bb2_)) - (w3_ + bb2_);                                                 \
    const VT nlo_ = kd_ * 0x1.b839a252049c1p-104 - (e1_ + e2_); /* P3t */                              \
    const VT y0_ = s2_ - nlo_;                                                                         \
    const VT y1_ = (s2_ - y0_) - nlo_;                                                                 \
    const VT z_ = y0_ * y0_;                                                                           \
    const VT w_ = z_ * z_;                                                                             \
    const VT rs_ = 8.33333333332248946124e-03 +                                                        \
                   z_ * (-1.98412698298579493134e-04 + z_ * 2.75573137070700676789e-06) +              \
                   z_ * w_ * (-2.50507602534068634195e-08 + z_ * 1.58969099521155010221e-10);          \
    const VT v_ = z_ * y0_;                                                                            \
    const VT ks_ = y0_ - ((z_ * (0.5 * y1_ - v_ * rs_) - y1_) - v_ * -1.66666666666666324348e-01);     \
    const VT rc_ = z_ * (4.16666666666666019037e-02 +                                                  \
                         z_ * (-1.38888888888741095749e-03 + z_ * 2.48015872894767294178e-05)) +       \
                   w_ * w_ *                                                                           \
                       (-2.75573143513906633035e-07 +                                                  \
                        z_ * (2.08757232129817482790e-09 + z_ * -1.13596475577881948265e-11));         \
    const VT hz_ = 0.5 * z_;                                                                           \
    const VT wc_ = 1.0 - hz_;                                                                          \
    const VT kc_ = wc_ + (((1.0 - wc_) - hz_) + (z_ * rc_ - y0_ * y1_));                               \
    const UT ub_ = (UT)ks_, cb_ = (UT)kc_;                                                             \
    const UT swap_ = 0u - (q_ & 1u);                                                                   \
    const UT sgn_s_ = (q_ & 2u) << 62;                                                                 \
    const UT sgn_c_ = ((q_ + 1u) & 2u) << 62;                                                          \
    (sn) = (VT)(((ub_ & ~swap_) | (cb_ & swap_)) ^ sgn_s_);                                            \
    (cs) = (VT)(((cb_ & ~swap_) | (ub_ & swap_)) ^ sgn_c_);                                            \
  } while (0)

/* sin and cos of two arguments x[0], x[1] at once: autobal_sincos_fast's operations, in the same
 * order, on the two lanes of one vector (GCC/Clang vector extensions; elsewhere two scalar calls),
 * so the same bits as autobal_sincos_fast for each; libm's sin and cos for an argument out of
 * range (as autobal_sincos1).  For two angles at a time (the pendulum's derived quantities) the
 * loop of autobal_sincos_array leaves GCC shuffling lanes; written out, it is one pass. */
#if defined(__GNUC__) && !defined(AUTOBAL_NO_VECTOR_EXT)
#define AUTOBAL_FM_VECTORS 1
typedef double autobal_fm_v2 __attribute__((vector_size(16)));
typedef uint64_t autobal_fm_u2 __attribute__((vector_size(16)));
typedef double autobal_fm_v4 __attribute__((vector_size(32)));
typedef uint64_t autobal_fm_u4 __attribute__((vector_size(32)));
static AUTOBAL_FM_INLINE void autobal_sincos2(const double x_in[2], double sn_out[2], double cs_out[2]) {
  autobal_fm_v2 x, sn, cs;
  int k;
  memcpy(&x, x_in, sizeof x);
  AUTOBAL_FM_SINCOS_LANES(autobal_fm_v2, autobal_fm_u2, x, sn, cs);
  memcpy(sn_out, &sn, sizeof sn);
  memcpy(cs_out, &cs, sizeof cs);
  for (k = 0; k < 2; k++) {
    if (!autobal_sincos_in_range(x_in[k])) {
      sn_out[k] = sin(x_in[k]);
      cs_out[k] = cos(x_in[k]);
    }
  }
}

/* The 4-lane form for callers that keep their angles in vectors (the rotor's output columns):
 * *sn, *cs get autobal_sincos_fast's bits on every lane; no range check and no libm fallback (the
 * caller tests autobal_sincos_out_of_range4 and redoes those lanes with libm, as autobal_sincos1). */
static AUTOBAL_FM_INLINE void autobal_sincos_fast4(const autobal_fm_v4 *x, autobal_fm_v4 *sn, autobal_fm_v4 *cs) {
  const autobal_fm_v4 a = *x;
  autobal_fm_v4 s, c;
  AUTOBAL_FM_SINCOS_LANES(autobal_fm_v4, autobal_fm_u4, a, s, c);
  *sn = s;
  *cs = c;
}

/* *bad |= a lane with the top bit set where x is out of the fast path's range (|x| >
 * AUTOBAL_SINCOS_MAX, inf, NaN), as in autobal_sincos_array (integer differences of the bits of
 * |x|: no comparisons).  (Vectors by pointer: 32-byte vectors by value change the ABI without AVX.) */
static AUTOBAL_FM_INLINE void autobal_sincos_out_of_range4(const autobal_fm_v4 *x, autobal_fm_u4 *bad) {
  const double bound = AUTOBAL_SINCOS_MAX;
  uint64_t maxbits;
  memcpy(&maxbits, &bound, sizeof maxbits);
  *bad |= maxbits - ((autobal_fm_u4)*x & ~((uint64_t)1 << 63));
}
#else
static AUTOBAL_FM_INLINE void autobal_sincos2(const double x_in[2], double sn_out[2], double cs_out[2]) {
  autobal_sincos1(x_in[0], &sn_out[0], &cs_out[0]);
  autobal_sincos1(x_in[1], &sn_out[1], &cs_out[1]);
}
#endif

/* hypot(a, b) as sqrt(a a + b b) where that is safe, else libm's hypot.  For a a + b b in
 * [2^-968, 2^1000] the larger square is a normal number and nothing overflows: the two products
 * and the sum are rounded once each, so the computed sum is (a^2 + b^2)(1 + e) with |e| <= 2u + u^2
 * (u = 2^-53; a square that underflows adds at most 2^-1075, below 2^-107 of the sum); its square
 * root is within (1 + e)^(1/2) - 1 <= u (relative), less than 1 ulp of the result, and sqrt rounds
 * once more (1/2 ulp): below 1.5 ulp of the exact value (glibc's hypot: below 1 ulp).  Outside that
 * range (tiny or huge arguments, inf, NaN: the comparison is false) libm's hypot gives the result,
 * so hypot's special cases (inf with NaN gives inf) hold.  IEEE multiplications, one addition and
 * sqrt (correctly rounded): the same bits in every clone.  tests/test_pendulum_motion.c checks it
 * against hypotl. */
static AUTOBAL_FM_INLINE double autobal_hypot_fast(double a, double b) {
  const double s = a * a + b * b;
  if (s >= 0x1p-968 && s <= 0x1p1000) {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__SSE2__)
    /* SSE2's sqrtsd: libm's sqrt's bits, without the errno branch around it (s is in range) */
    typedef double autobal_fm_sd __attribute__((vector_size(16)));
    return __builtin_ia32_sqrtsd((autobal_fm_sd){s, 0.0})[0];
#else
    return sqrt(s);
#endif
  }
  return hypot(a, b);
}

#endif
