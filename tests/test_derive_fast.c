/* test_derive_fast.c: the derived quantities of output = dense6 (issue 20): fastmath.h's
 * autobal_hypot_fast and autobal_sincos2, autobal_pendulum_motion_derive_fast and
 * autobal_rotor_outputs_fast against independent references.
 *
 * - autobal_hypot_fast against hypotl (64-bit long double: its own error is 2^-11 of a double
 *   ulp) on 10^6 pairs over magnitudes 2^-600 .. 2^600 and ratios down to 2^-60, edges of its
 *   sqrt range: at most 1.5 ulp (the bound derived in fastmath.h: 1 ulp from the rounded sum,
 *   1/2 from sqrt); the special cases of hypot (inf with NaN is inf, NaN, 0, no overflow).
 * - autobal_sincos2: the same bits as the scalar autobal_sincos_fast on every lane (it is
 *   documented as the same operations), within 1 ulp of sinl/cosl, libm out of range.
 * - derive_fast vs derive_m on 2000 states: the columns without trigonometry (alpha, beta) equal
 *   bit for bit; the others within a few ulp of the magnitude of their terms (the only
 *   difference: sin, cos within 1 ulp of libm, hypot within 1.5 ulp).
 * - rotor outputs_fast vs outputs: the default rotor (2 balls), 8 balls, 70 balls (the scalar
 *   path), both frames: angle and rate columns bit for bit, the others within 1e-13 of their
 *   scale; the same argument checks (EINVAL).
 * - the ball columns again at edge angles (next to 0, pi, 3, odd multiples of pi, 2^52 2 pi, inf,
 *   NaN), 1 to 63 balls: bit for bit (outputs_fast wraps them without branches).
 * - outputs_fast_block (the rotor study's buffered output points) against outputs_fast point by
 *   point: every column bit for bit (two NaNs count as equal), 1 to 70 balls, 1 and 2 planes, 0 to
 *   19 points; its refusals. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"
#include "fastmath.h"
#include "models/rotor/rotor_internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static uint64_t rng_state = 0x9e3779b97f4a7c15ULL;
static double urand(void) { /* xorshift64*, uniform in [0, 1) */
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return (double)((rng_state * 0x2545F4914F6CDD1DULL) >> 11) * 0x1p-53;
}

/* |got - ref| in units of the double ulp at ref (ref a long double) */
static double ulps(double got, long double ref) {
  const double r = (double)ref;
  int e;
  if (r == 0.0) return got == 0.0 ? 0.0 : INFINITY;
  if (isinf(r)) return got == r ? 0.0 : INFINITY; /* the exact value overflows: inf is right */
  frexp(r, &e);
  if (e - 53 < -1074) e = -1074 + 53; /* subnormal results: the ulp is 2^-1074 */
  return (double)(fabsl((long double)got - ref) / ldexpl(1.0L, e - 53));
}

static void test_hypot(void) {
  double worst = 0.0, wa = 0.0, wb = 0.0;
  long n;
  int ok_special;
  for (n = 0; n < 1000000; n++) {
    const double ea = -600.0 + 1200.0 * urand(), ratio = -60.0 * urand() * urand();
    const double a = (urand() < 0.5 ? -1 : 1) * ldexp(1.0 + urand(), (int)ea);
    const double b = (urand() < 0.5 ? -1 : 1) * a * ldexp(1.0 + urand(), (int)ratio);
    const double u = ulps(autobal_hypot_fast(a, b), hypotl((long double)a, (long double)b));
    if (u > worst) worst = u, wa = a, wb = b;
  }
  {
    char what[200];
    snprintf(what, sizeof what, "hypot_fast: 1e6 pairs, largest error %.3f ulp (at %.17g, %.17g) <= 1.5", worst, wa, wb);
    CHECK(what, worst <= 1.5);
  }
  /* at the edges of the sqrt range and outside it (libm there) */
  {
    const double e[] = {0x1p-484, 0x1p-485, 0x1p-483, 0x1p500, 0x1p499, 0x1p501, 1e-310, 1e300, 1.7e308};
    double w2 = 0.0;
    size_t i, j;
    for (i = 0; i < sizeof e / sizeof e[0]; i++)
      for (j = 0; j < sizeof e / sizeof e[0]; j++) {
        const double u = ulps(autobal_hypot_fast(e[i], e[j]), hypotl((long double)e[i], (long double)e[j]));
        if (u > w2) w2 = u;
      }
    CHECK("hypot_fast at the edges of the sqrt range, tiny (subnormal result) and huge (inf only where the exact value overflows) arguments: <= 1.5 ulp", w2 <= 1.5);
  }
  ok_special = autobal_hypot_fast(INFINITY, NAN) == INFINITY && autobal_hypot_fast(NAN, -INFINITY) == INFINITY &&
               isnan(autobal_hypot_fast(NAN, 1.0)) && autobal_hypot_fast(0.0, -0.0) == 0.0 &&
               autobal_hypot_fast(-3.0, 4.0) == 5.0 && autobal_hypot_fast(1e308, 1e308) == hypot(1e308, 1e308);
  CHECK("hypot_fast special cases: inf with NaN = inf, NaN, 0, 3-4-5 exact, 1e308 without overflow", ok_special);
}

static void test_sincos2(void) {
  const double ranges[] = {1e-300, 1e-8, 0.1, 1.0, 4.0, 100.0, 1e4, 0x1p21};
  double worst = 0.0;
  long n, same = 0, total = 0;
  size_t r;
  for (r = 0; r < sizeof ranges / sizeof ranges[0]; r++)
    for (n = 0; n < 50000; n++) {
      const double x[2] = {(2.0 * urand() - 1.0) * ranges[r], (2.0 * urand() - 1.0) * ranges[r]};
      double sn[2], cs[2];
      int k;
      autobal_sincos2(x, sn, cs);
      for (k = 0; k < 2; k++) {
        double s1, c1;
        autobal_sincos_fast(x[k], &s1, &c1);
        same += memcmp(&s1, &sn[k], sizeof s1) == 0 && memcmp(&c1, &cs[k], sizeof c1) == 0;
        total++;
        worst = fmax(worst, fmax(ulps(sn[k], sinl((long double)x[k])), ulps(cs[k], cosl((long double)x[k]))));
      }
    }
  {
    char what[200];
    snprintf(what, sizeof what, "sincos2: %ld of %ld lanes the bits of autobal_sincos_fast", same, total);
    CHECK(what, same == total);
    snprintf(what, sizeof what, "sincos2: largest error %.3f ulp against sinl, cosl (<= 1)", worst);
    CHECK(what, worst <= 1.0);
  }
  {
    const double x[2] = {3e6, NAN};
    double sn[2], cs[2];
    autobal_sincos2(x, sn, cs);
    CHECK("sincos2 out of range: libm's sin, cos (3e6 rad), NaN gives NaN",
          sn[0] == sin(3e6) && cs[0] == cos(3e6) && isnan(sn[1]) && isnan(cs[1]));
  }
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static void test_pendulum(void) {
  autobal_pendulum_params p = {3.0, 0.1, 0.05, 0.1, 0.5};
  autobal_pendulum_motion m;
  autobal_error err;
  double wa = 0.0, wu = 0.0, wj = 0.0;
  int bits = 1, k;
  CHECK_STATUS("pendulum motion init", autobal_pendulum_motion_init(&m, &p, &err), AUTOBAL_SUCCESS);
  for (k = 0; k < 2000; k++) {
    double y[8];
    autobal_pendulum_motion_derived d1, d2;
    int i;
    double sc;
    for (i = 0; i < 8; i++) y[i] = (2.0 * urand() - 1.0) * (i < 2 ? 0.5 : i < 4 ? 8.0 : 3.0);
    if (k % 4 == 0) y[0] *= 1e-9, y[1] *= 1e-9; /* small amplitudes */
    autobal_pendulum_motion_derive_m(&m, y, &d1);
    autobal_pendulum_motion_derive_fast(&m, y, &d2);
    bits = bits && same_bits(d1.alpha, d2.alpha) && same_bits(d1.beta, d2.beta);
    /* amplitude: both within their bounds of the exact value (1 and 1.5 ulp): at most 2.5 ulp apart */
    wa = fmax(wa, fabs(d2.amplitude - d1.amplitude) / (DBL_EPSILON * d1.amplitude));
    /* u, v: sums of sines and cosines (each within 1 ulp of libm's, |.| <= 1) with s0: a few eps */
    wu = fmax(wu, fmax(fabs(d2.unbalance_u - d1.unbalance_u), fabs(d2.unbalance_v - d1.unbalance_v)) / DBL_EPSILON);
    wu = fmax(wu, fabs(d2.unbalance - d1.unbalance) / DBL_EPSILON);
    /* Jacobi: sines and cosines times terms of the size sc */
    sc = 1.0 + y[4] * y[4] + y[5] * y[5] + y[6] * y[6] + y[7] * y[7] + p.R_w * p.R_w * (y[0] * y[0] + y[1] * y[1]) +
         fabs(y[4]) * (fabs(y[6]) + fabs(y[7])) + fabs(y[5]) * (fabs(y[6]) + fabs(y[7])) +
         p.R_w * p.R_w * (fabs(y[0]) + fabs(y[1]));
    wj = fmax(wj, fabs(d2.jacobi - d1.jacobi) / (DBL_EPSILON * sc));
  }
  {
    char what[200];
    CHECK("derive_fast: alpha, beta (no trigonometry) bit for bit as derive_m on 2000 states", bits);
    snprintf(what, sizeof what, "derive_fast: amplitude within %.2f eps (relative) of derive_m's (<= 3)", wa);
    CHECK(what, wa <= 3.0);
    snprintf(what, sizeof what, "derive_fast: unbalance u, v, |d| within %.2f eps of derive_m's (<= 4)", wu);
    CHECK(what, wu <= 4.0);
    snprintf(what, sizeof what, "derive_fast: Jacobi integral within %.2f eps of its terms' size (<= 8)", wj);
    CHECK(what, wj <= 8.0);
  }
}

/* derive_fast_cols: the bytes of derive_fast at every state, for block lengths around the chunk
 * size, with the states of the slow paths among them (angles out of the wrap's identity range and
 * out of the sine's range, -pi, NaN, amplitudes outside hypot_fast's sqrt range, -0) */
static void test_pendulum_cols(void) {
  autobal_pendulum_params p = {3.0, 0.1, 0.05, 0.1, 0.5};
  autobal_pendulum_motion m;
  autobal_error err;
  enum { NMAX = 131 };
  static double cols[8][NMAX], dc[7][NMAX];
  const double *const yc[8] = {cols[0], cols[1], cols[2], cols[3], cols[4], cols[5], cols[6], cols[7]};
  double *const dd[7] = {dc[0], dc[1], dc[2], dc[3], dc[4], dc[5], dc[6]};
  const size_t lens[] = {1, 5, 63, 64, 65, 131};
  size_t li;
  int bad = 0, edges = 0;
  CHECK_STATUS("pendulum motion init (cols)", autobal_pendulum_motion_init(&m, &p, &err), AUTOBAL_SUCCESS);
  for (li = 0; li < sizeof lens / sizeof lens[0]; li++) {
    const size_t n = lens[li];
    size_t k;
    for (k = 0; k < n; k++) {
      int i;
      for (i = 0; i < 8; i++) cols[i][k] = (2.0 * urand() - 1.0) * (i < 2 ? 0.5 : i < 4 ? 3.0 : 3.0);
      if (k % 9 == 3) cols[2][k] = p.psi0 - 3.14159265358979323846;              /* alpha: -pi -> pi */
      if (k % 11 == 4) cols[3][k] = 7.5 + 20.0 * urand();       /* beta: remainder */
      if (k % 13 == 5) cols[0][k] = 1e-300, cols[1][k] = -0.0;  /* amplitude: libm's hypot */
      if (k % 17 == 6) cols[1][k] = 1e200;                      /* amplitude: libm's hypot */
      if (k % 19 == 7) cols[2][k] = 3e6;                        /* sine out of range: libm */
      if (k % 23 == 8) cols[3][k] = NAN;
      if (li == 0 && n == 1) cols[2][k] = cols[3][k] = p.psi0; /* alpha = beta = 0, unbalance 0 */
    }
    autobal_pendulum_motion_derive_fast_cols(&m, n, yc, dd);
    for (k = 0; k < n; k++) {
      autobal_pendulum_motion_derived d;
      double y[8];
      const double *want;
      int i;
      for (i = 0; i < 8; i++) y[i] = cols[i][k];
      autobal_pendulum_motion_derive_fast(&m, y, &d);
      want = &d.amplitude;
      for (i = 0; i < 7; i++) {
        if (!same_bits(dc[i][k], want[i])) {
          if (bad++ < 5) printf("     n %zu state %zu column %d: %.17g, derive_fast %.17g\n", n, k, i, dc[i][k], want[i]);
        }
      }
      edges += k % 9 == 3 || k % 11 == 4 || k % 13 == 5 || k % 17 == 6 || k % 19 == 7 || k % 23 == 8;
    }
  }
  CHECK("derive_fast_cols: the bytes of derive_fast in every column, blocks of 1, 5, 63, 64, 65, 131 states "
        "with the slow paths among them", bad == 0 && edges > 20);
}

static autobal_rotor *rotor_n(size_t n) {
  autobal_rotor_params rp = autobal_rotor_params_default();
  static double mass[70], rad[70], damp[70], psi[70], rate[70];
  autobal_error err;
  size_t i;
  if (n != 2) {
    for (i = 0; i < n; i++) {
      mass[i] = 0.1 / (double)n;
      rad[i] = 0.1;
      damp[i] = 0.1;
      psi[i] = 1.0 + 0.4 * (double)i;
      rate[i] = 0.0;
    }
    rp.plane[0].n_balls = n;
    rp.plane[0].ball_mass = mass;
    rp.plane[0].ball_radius = rad;
    rp.plane[0].ball_damping = damp;
    rp.plane[0].ball_psi = psi;
    rp.plane[0].ball_rate = rate;
  }
  return autobal_rotor_alloc(&rp, &err);
}

static void test_rotor(void) {
  const size_t ns[3] = {2, 8, 70};
  size_t c;
  for (c = 0; c < 3; c++) {
    autobal_rotor *R = rotor_n(ns[c]);
    char what[200];
    double worst = 0.0;
    int bits = 1, frame, k;
    size_t dim, nout, i;
    double *y, *o1, *o2;
    snprintf(what, sizeof what, "rotor with %zu balls allocated", ns[c]);
    CHECK(what, R != NULL);
    if (!R) continue;
    dim = autobal_rotor_dim(R);
    nout = autobal_rotor_output_count(R);
    y = malloc(dim * sizeof *y);
    o1 = malloc(nout * sizeof *o1);
    o2 = malloc(nout * sizeof *o2);
    for (frame = 0; frame < 2; frame++) {
      const int fr = frame ? AUTOBAL_ROTOR_ROTATING : AUTOBAL_ROTOR_FIXED;
      for (k = 0; k < 200; k++) {
        const double t = 3.0 * urand();
        int r1, r2;
        for (i = 0; i < dim; i++) y[i] = (2.0 * urand() - 1.0) * (i < 4 ? 1e-4 : i < 8 ? 0.05 : 600.0);
        r1 = autobal_rotor_outputs(R, fr, t, y, o1, nout);
        r2 = autobal_rotor_outputs_fast(R, fr, t, y, o2, nout);
        bits = bits && r1 == AUTOBAL_SUCCESS && r2 == AUTOBAL_SUCCESS;
        for (i = 0; i < nout; i++) {
          char name[64];
          const char *unit;
          autobal_rotor_output_name(R, i, name, sizeof name, &unit);
          if (strstr(name, "_b") != NULL) { /* ball angles and rates: no trigonometry */
            bits = bits && same_bits(o1[i], o2[i]);
          } else {
            /* amplitudes (m), unbalances (kg m, about the unbalance plus the balls' capacity) */
            const double scale = strcmp(unit, "m") == 0 ? fabs(o1[i]) : strcmp(unit, "1") == 0 ? 1.0 : 0.01;
            if (scale > 0) worst = fmax(worst, fabs(o2[i] - o1[i]) / scale);
          }
        }
      }
    }
    snprintf(what, sizeof what, "rotor, %zu balls, both frames, 400 states: ball columns bit for bit, status", ns[c]);
    CHECK(what, bits);
    snprintf(what, sizeof what, "rotor, %zu balls: amplitudes and unbalances within %.2e of their scale (<= 1e-13)", ns[c],
             worst);
    CHECK(what, worst <= 1e-13);
    CHECK_STATUS("outputs_fast: wrong n_out rejected", autobal_rotor_outputs_fast(R, AUTOBAL_ROTOR_FIXED, 0.0, y, o2, nout - 1),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("outputs_fast: NULL state rejected", autobal_rotor_outputs_fast(R, AUTOBAL_ROTOR_FIXED, 0.0, NULL, o2, nout),
                 AUTOBAL_EINVAL);
    free(y);
    free(o1);
    free(o2);
    autobal_rotor_free(R);
  }
}

/* The ball columns of outputs_fast (the wraps without branches, wrap_pi4 in rotor.c: ceil by
 * rounding with 2^52 and masks) against autobal_rotor_outputs' (libm's ceil, branches) bit for
 * bit, at the angles where the two ways could part: +-0, next to +-pi, +-3 and the odd multiples
 * of pi (where the quotient (a - pi) / (2 pi) is an integer or next to one, and the corrections
 * by 2 pi apply), next to 2^52 2 pi (the quotient's last fractional bit), beyond it, +-inf, NaN,
 * subnormals; 1 to 62 balls (the vector loop's remainders) and 63 (the scalar path), both
 * frames, phi_0 = 0 (t = 0: psi is the angle itself) and phi_0 != 0. */
static void test_rotor_wrap_edges(void) {
  const size_t ns[8] = {1, 3, 4, 5, 8, 13, 62, 63};
  double edge[80];
  size_t ne = 0, c, i;
  int bits = 1, inrange = 1;
  long compared = 0;
  {
    const double base[] = {0.0, M_PI, 3.0, 3.0 * M_PI, 5.0 * M_PI, 101.0 * M_PI, 2.0 * M_PI, 0x1p52 * 2.0 * M_PI,
                           0x1p53 * 2.0 * M_PI, 1e300, 4.9e-324, 2.2e-308};
    size_t b;
    for (b = 0; b < sizeof base / sizeof base[0]; b++) {
      const double v[3] = {nextafter(base[b], -INFINITY), base[b], nextafter(base[b], INFINITY)};
      int m;
      for (m = 0; m < 3; m++) {
        edge[ne++] = v[m];
        edge[ne++] = -v[m];
      }
    }
    edge[ne++] = INFINITY;
    edge[ne++] = -INFINITY;
    edge[ne++] = NAN;
    edge[ne++] = -0.0;
  }
  for (c = 0; c < 8; c++) {
    autobal_rotor *R = rotor_n(ns[c]);
    size_t dim, nout, nb = ns[c];
    double *y, *o1, *o2;
    int frame, k;
    if (!R) {
      bits = 0;
      continue;
    }
    dim = autobal_rotor_dim(R);
    nout = autobal_rotor_output_count(R);
    y = calloc(dim, sizeof *y);
    o1 = malloc(nout * sizeof *o1);
    o2 = malloc(nout * sizeof *o2);
    for (frame = 0; frame < 2; frame++) {
      const int fr = frame ? AUTOBAL_ROTOR_ROTATING : AUTOBAL_ROTOR_FIXED;
      for (k = 0; k < 40; k++) {
        const double t = k % 2 ? 0.0 : 3.0 * urand();
        for (i = 0; i < nb; i++) { /* the edges in every lane position over the 40 states */
          y[8 + i] = edge[(i + (size_t)k * 7) % ne];
          y[8 + nb + i] = (2.0 * urand() - 1.0) * 600.0;
        }
        bits = bits && autobal_rotor_outputs(R, fr, t, y, o1, nout) == AUTOBAL_SUCCESS &&
               autobal_rotor_outputs_fast(R, fr, t, y, o2, nout) == AUTOBAL_SUCCESS;
        for (i = 0; i < nout; i++) {
          char name[64];
          autobal_rotor_output_name(R, i, name, sizeof name, NULL);
          if (strstr(name, "_b") == NULL) continue;
          bits = bits && same_bits(o1[i], o2[i]);
          compared++;
          if (strstr(name, "_w") != NULL && isfinite(o2[i]))
            inrange = inrange && o2[i] > -M_PI && o2[i] <= M_PI; /* (-pi, pi] */
        }
      }
    }
    free(y);
    free(o1);
    free(o2);
    autobal_rotor_free(R);
  }
  {
    char what[240];
    snprintf(what, sizeof what,
             "rotor outputs_fast: ball columns at %zu edge angles (next to 0, pi, 3, odd multiples of pi, "
             "2^52 2 pi, inf, NaN), 1..63 balls, both frames: %ld values bit for bit with outputs", ne, compared);
    CHECK(what, bits && compared > 10000);
    CHECK("rotor outputs_fast: the finite wrapped angles in (-pi, pi]", inrange);
  }
}

/* equal bits, or both NaN (C leaves a NaN's sign and payload open: two NaN inputs of one sum may
 * give either) */
static int same_or_nan(double a, double b) { return same_bits(a, b) || (isnan(a) && isnan(b)); }

/* autobal_rotor_outputs_fast_block (the rotor study's buffered output points, rotor_internal.h)
 * against autobal_rotor_outputs_fast one point at a time: every column, 1 to 70 balls (the vector
 * path's lane counts and the scalar path above 62), one and two planes (the second with gravity:
 * the amplitudes about the static offset), both frames, 0 to 19 points (the stages' chunks of 8
 * and their remainders), states with angles out of the fast sine's range, inf and NaN among
 * them; the refusals (EINVAL, nothing written). */
static void test_rotor_block(void) {
  const size_t ns[12] = {1, 2, 3, 4, 5, 6, 7, 8, 13, 62, 63, 70};
  const double edge[6] = {0x1p21 * 1.5, -1e300, INFINITY, -INFINITY, NAN, 3.0 * M_PI};
  static double mass[2][70], rad[2][70], damp[2][70], psi[2][70], rate[2][70];
  long compared = 0;
  int bits = 1, refused = 1, untouched = 1;
  size_t c, j, i;
  for (c = 0; c < 24; c++) {
    autobal_rotor_params rp = autobal_rotor_params_default();
    const size_t nb = ns[c % 12], np = c < 12 ? 1 : 2;
    autobal_error err;
    autobal_rotor *R;
    size_t dim, nout, n;
    double *t, *y, *o1, *o2;
    int frame;
    rp.n_planes = np;
    for (j = 0; j < np; j++) {
      const size_t m = np == 1 ? nb : (j == 0 ? nb - nb / 2 : (nb / 2 > 0 ? nb / 2 : 1));
      for (i = 0; i < m; i++) {
        mass[j][i] = 0.1 / (double)m;
        rad[j][i] = 0.1;
        damp[j][i] = 0.1;
        psi[j][i] = 1.0 + 0.4 * (double)i;
        rate[j][i] = 0.0;
      }
      rp.plane[j].n_balls = m;
      rp.plane[j].ball_mass = mass[j];
      rp.plane[j].ball_radius = rad[j];
      rp.plane[j].ball_damping = damp[j];
      rp.plane[j].ball_psi = psi[j];
      rp.plane[j].ball_rate = rate[j];
    }
    if (np == 2) {
      rp.plane[1].d = 0.05;
      rp.plane[1].m0 = 0.5 * rp.plane[0].m0;
      rp.plane[1].r0 = rp.plane[0].r0;
      rp.plane[1].psi0 = 0.3;
      rp.gravity = 1;
      rp.shaft_angle = 0.5 * M_PI;
      rp.g = 9.80665;
    }
    R = autobal_rotor_alloc(&rp, &err);
    if (!R) {
      printf("  rotor with %zu balls, %zu planes: %s\n", nb, np, err.message);
      bits = 0;
      continue;
    }
    dim = autobal_rotor_dim(R);
    nout = autobal_rotor_output_count(R);
    t = malloc(20 * sizeof *t);
    y = malloc(20 * (dim + 1) * sizeof *y); /* stride dim + 1: the stride is honoured */
    o1 = malloc(20 * (nout + 2) * sizeof *o1);
    o2 = malloc(nout * sizeof *o2);
    for (frame = 0; frame < 2; frame++) {
      const int fr = frame ? AUTOBAL_ROTOR_ROTATING : AUTOBAL_ROTOR_FIXED;
      for (n = 0; n < 20; n++) {
        size_t k, q;
        for (k = 0; k < n; k++) {
          double *yk = y + k * (dim + 1);
          t[k] = k % 5 == 4 ? 2e4 * urand() : 3.0 * urand(); /* phi_0 beyond 2^21 rad too */
          for (q = 0; q < dim + 1; q++) yk[q] = (2.0 * urand() - 1.0) * (q < 4 ? 1e-4 : q < 8 ? 0.05 : 600.0);
          if (k % 3 == 1) yk[8 + (size_t)(urand() * (double)nb)] = edge[(size_t)(urand() * 6.0)];
        }
        if (autobal_rotor_outputs_fast_block(R, fr, n, t, y, dim + 1, o1, nout + 2) != AUTOBAL_SUCCESS) {
          bits = 0;
          continue;
        }
        for (k = 0; k < n; k++) {
          bits = bits && autobal_rotor_outputs_fast(R, fr, t[k], y + k * (dim + 1), o2, nout) == AUTOBAL_SUCCESS;
          for (q = 0; q < nout; q++, compared++) bits = bits && same_or_nan(o1[k * (nout + 2) + q], o2[q]);
        }
        if (n == 19) { /* refused: a non-finite time, a short stride; nothing written */
          for (k = 0; k < n * (nout + 2); k++) o1[k] = -7.0;
          t[n - 1] = NAN;
          refused = refused && autobal_rotor_outputs_fast_block(R, fr, n, t, y, dim + 1, o1, nout + 2) == AUTOBAL_EINVAL;
          t[n - 1] = 1.0;
          refused = refused && autobal_rotor_outputs_fast_block(R, fr, n, t, y, dim - 1, o1, nout + 2) == AUTOBAL_EINVAL &&
                    autobal_rotor_outputs_fast_block(R, fr, n, t, y, dim + 1, o1, nout - 1) == AUTOBAL_EINVAL &&
                    autobal_rotor_outputs_fast_block(R, 7, n, t, y, dim + 1, o1, nout + 2) == AUTOBAL_EINVAL;
          for (k = 0; k < n * (nout + 2); k++) untouched = untouched && o1[k] == -7.0;
        }
      }
    }
    free(t);
    free(y);
    free(o1);
    free(o2);
    autobal_rotor_free(R);
  }
  {
    char what[200];
    snprintf(what, sizeof what, "rotor outputs_fast_block = outputs_fast point by point: %ld values, 1..70 balls, 1 and 2 planes, both frames, 0..19 points", compared);
    CHECK(what, bits && compared > 1000000);
    CHECK("rotor outputs_fast_block: a non-finite time, short strides, a bad frame refused (EINVAL)", refused);
    CHECK("rotor outputs_fast_block: nothing written when refused", untouched);
  }
}

int main(void) {
  test_hypot();
  test_sincos2();
  test_pendulum();
  test_pendulum_cols();
  test_rotor();
  test_rotor_wrap_edges();
  test_rotor_block();
  return check_summary();
}
