/* pendulum_motion.c: the explicit first-order form of the equations of
 * motion (1) of the two-pendulum autobalancer, its Jacobian and derived
 * quantities (docs/pendulum.md).  Dimensionless throughout
 * (time tau = omega0 t, lengths in units of l).  No allocation, O(1).
 *
 * Derivation of the explicit form.  Write the absolute acceleration of the
 * shaft centre in the rotating axes as
 *     A = xi'' - 2R_w eta' - R_w^2 xi,   B = eta'' + 2R_w xi' - R_w^2 eta.
 * The pendulum equations of (1) give the pendulum accelerations in terms of
 * (A, B):
 *     psi'' = -h psi' + A cos psi + B sin psi,
 *     phi'' = -h phi' + A cos phi - B sin phi.                    eq. (1c,d)
 * Substituted into the shaft equations (1a,b) they leave a symmetric 2x2
 * system for (A, B):
 *     [1 - R_m (c1^2 + c2^2)]  A - R_m (s1 c1 - s2 c2) B = r1,
 *     -R_m (s1 c1 - s2 c2) A + [1 - R_m (s1^2 + s2^2)]  B = r2,
 * (c1, s1 = cos, sin psi; c2, s2 = cos, sin phi) with
 *     r1 = -H (xi' - R_w eta) - xi + R_m [ -h (psi' c1 + phi' c2)
 *          - 2R_w (psi' s1 - phi' s2) - psi'^2 s1 - phi'^2 s2 + R_w^2 (2 s0 - s1 - s2) ],
 *     r2 = -H (eta' + R_w xi) - eta + R_m [ -h (psi' s1 - phi' s2)
 *          + 2R_w (psi' c1 + phi' c2) + psi'^2 c1 - phi'^2 c2 + R_w^2 (c1 - c2) ].
 * Its determinant is 1 - 2R_m + R_m^2 (|u|^2 |v|^2 - (u.v)^2) with
 * u = (c1, c2), v = (s1, -s2), hence >= 1 - 2R_m > 0 for R_m < 1/2
 * (Cauchy-Schwarz): the system is solved in closed form (Cramer), then
 *     xi'' = A + 2R_w eta' + R_w^2 xi,  eta'' = B - 2R_w xi' + R_w^2 eta.
 */
#include "autobal/pendulum.h"

#include <math.h>
#include <string.h>

#include "internal.h"
#include "numerics/fastmath.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The 2x2 system for (A, B) at state y. */
typedef struct motion_parts {
  double s1, c1, s2, c2;     /* sin, cos of psi and phi */
  double m11, m12, m22, det; /* the symmetric matrix and its determinant */
  double r1, r2;             /* right-hand sides */
  double A, B;               /* absolute acceleration of the shaft centre (rotating axes) */
} motion_parts;

#if defined(__GNUC__)
#define MOTION_INLINE static inline __attribute__((always_inline))
#else
#define MOTION_INLINE static inline
#endif

/* s0 = sin(psi0), passed in so that a prepared autobal_pendulum_motion does
 * not recompute it at every call. */
MOTION_INLINE void motion_solve(const autobal_pendulum_params *p, double s0, const double *y,
                                motion_parts *q) {
  const double Rw = p->R_w, Rm = p->R_m, H = p->H, h = p->h;
  const double Rw2 = Rw * Rw;
  const double xi = y[0], eta = y[1], dxi = y[4], deta = y[5], dpsi = y[6], dphi = y[7];
  const double s1 = sin(y[2]), c1 = cos(y[2]), s2 = sin(y[3]), c2 = cos(y[3]);
  q->s1 = s1;
  q->c1 = c1;
  q->s2 = s2;
  q->c2 = c2;
  q->m11 = 1.0 - Rm * (c1 * c1 + c2 * c2);
  q->m22 = 1.0 - Rm * (s1 * s1 + s2 * s2);
  q->m12 = -Rm * (s1 * c1 - s2 * c2);
  q->det = q->m11 * q->m22 - q->m12 * q->m12;
  q->r1 = -H * (dxi - Rw * eta) - xi +
          Rm * (-h * (dpsi * c1 + dphi * c2) - 2.0 * Rw * (dpsi * s1 - dphi * s2) -
                dpsi * dpsi * s1 - dphi * dphi * s2 + Rw2 * (2.0 * s0 - s1 - s2));
  q->r2 = -H * (deta + Rw * xi) - eta +
          Rm * (-h * (dpsi * s1 - dphi * s2) + 2.0 * Rw * (dpsi * c1 + dphi * c2) +
                dpsi * dpsi * c1 - dphi * dphi * c2 + Rw2 * (c1 - c2));
  {
    const double inv = 1.0 / q->det; /* Cramer's rule */
    q->A = (q->m22 * q->r1 - q->m12 * q->r2) * inv;
    q->B = (q->m11 * q->r2 - q->m12 * q->r1) * inv;
  }
}

MOTION_INLINE void motion_rhs(const autobal_pendulum_params *p, double s0, const double y[],
                              double dydt[], motion_parts *q) {
  const double Rw = p->R_w, h = p->h;
  motion_solve(p, s0, y, q);
  dydt[0] = y[4];
  dydt[1] = y[5];
  dydt[2] = y[6];
  dydt[3] = y[7];
  dydt[4] = q->A + 2.0 * Rw * y[5] + Rw * Rw * y[0];   /* eq. (1a) */
  dydt[5] = q->B - 2.0 * Rw * y[4] + Rw * Rw * y[1];   /* eq. (1b) */
  dydt[6] = -h * y[6] + q->A * q->c1 + q->B * q->s1;   /* eq. (1c) */
  dydt[7] = -h * y[7] + q->A * q->c2 - q->B * q->s2;   /* eq. (1d) */
}

int autobal_pendulum_rhs(double tau, const double y[], double dydt[], void *params) {
  const autobal_pendulum_params *p = (const autobal_pendulum_params *)params;
  motion_parts q;
  (void)tau;
  if (p == NULL || y == NULL || dydt == NULL) return AUTOBAL_EINVAL;
  motion_rhs(p, sin(p->psi0), y, dydt, &q);
  if (!(q.det > 0.0)) return AUTOBAL_ENUMERIC; /* only for R_m >= 1/2 or NaN input */
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_motion_rhs(double tau, const double y[], double dydt[], void *motion) {
  const autobal_pendulum_motion *m = (const autobal_pendulum_motion *)motion;
  motion_parts q;
  (void)tau;
  if (m == NULL || y == NULL || dydt == NULL) return AUTOBAL_EINVAL;
  motion_rhs(&m->p, m->sin_psi0, y, dydt, &q);
  if (!(q.det > 0.0)) return AUTOBAL_ENUMERIC;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_motion_init(autobal_pendulum_motion *m, const autobal_pendulum_params *p,
                                 autobal_error *err) {
  int rc;
  if (m == NULL || p == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum motion: NULL argument");
  if ((rc = autobal_pendulum_params_validate(p, err)) != AUTOBAL_SUCCESS) return rc;
  m->p = *p;
  m->sin_psi0 = sin(p->psi0);
  return AUTOBAL_SUCCESS;
}

/* Analytic Jacobian: differentiate M (A, B)^T = r,
 *   M d(A, B)/dz = dr/dz - (dM/dz) (A, B),
 * then the four acceleration formulas above. */
static int motion_jac(const autobal_pendulum_params *p, double s0, const double y[], double *dfdy,
                      double dfdt[]) {
  motion_parts q;
  double Rw, Rm, H, h, Rw2, dpsi, dphi;
  double dr1[8], dr2[8], dm11[8], dm12[8], dm22[8];
  size_t z;
  Rw = p->R_w;
  Rm = p->R_m;
  H = p->H;
  h = p->h;
  Rw2 = Rw * Rw;
  dpsi = y[6];
  dphi = y[7];
  motion_solve(p, s0, y, &q);
  if (!(q.det > 0.0)) return AUTOBAL_ENUMERIC;
  {
    const double s1 = q.s1, c1 = q.c1, s2 = q.s2, c2 = q.c2;
    memset(dm11, 0, sizeof dm11);
    memset(dm12, 0, sizeof dm12);
    memset(dm22, 0, sizeof dm22);
    dm11[2] = 2.0 * Rm * c1 * s1;
    dm11[3] = 2.0 * Rm * c2 * s2;
    dm12[2] = -Rm * (c1 * c1 - s1 * s1);
    dm12[3] = Rm * (c2 * c2 - s2 * s2);
    dm22[2] = -2.0 * Rm * s1 * c1;
    dm22[3] = -2.0 * Rm * s2 * c2;

    dr1[0] = -1.0;
    dr1[1] = H * Rw;
    dr1[2] = Rm * (h * dpsi * s1 - 2.0 * Rw * dpsi * c1 - dpsi * dpsi * c1 - Rw2 * c1);
    dr1[3] = Rm * (h * dphi * s2 + 2.0 * Rw * dphi * c2 - dphi * dphi * c2 - Rw2 * c2);
    dr1[4] = -H;
    dr1[5] = 0.0;
    dr1[6] = Rm * (-h * c1 - 2.0 * Rw * s1 - 2.0 * dpsi * s1);
    dr1[7] = Rm * (-h * c2 + 2.0 * Rw * s2 - 2.0 * dphi * s2);

    dr2[0] = -H * Rw;
    dr2[1] = -1.0;
    dr2[2] = Rm * (-h * dpsi * c1 - 2.0 * Rw * dpsi * s1 - dpsi * dpsi * s1 - Rw2 * s1);
    dr2[3] = Rm * (h * dphi * c2 - 2.0 * Rw * dphi * s2 + dphi * dphi * s2 + Rw2 * s2);
    dr2[4] = 0.0;
    dr2[5] = -H;
    dr2[6] = Rm * (-h * s1 + 2.0 * Rw * c1 + 2.0 * dpsi * c1);
    dr2[7] = Rm * (h * s2 + 2.0 * Rw * c2 - 2.0 * dphi * c2);

    memset(dfdy, 0, 64 * sizeof(double));
    dfdy[0 * 8 + 4] = 1.0;
    dfdy[1 * 8 + 5] = 1.0;
    dfdy[2 * 8 + 6] = 1.0;
    dfdy[3 * 8 + 7] = 1.0;
    for (z = 0; z < 8; z++) {
      const double b1 = dr1[z] - dm11[z] * q.A - dm12[z] * q.B;
      const double b2 = dr2[z] - dm12[z] * q.A - dm22[z] * q.B;
      const double dA = (q.m22 * b1 - q.m12 * b2) / q.det;
      const double dB = (q.m11 * b2 - q.m12 * b1) / q.det;
      dfdy[4 * 8 + z] = dA;
      dfdy[5 * 8 + z] = dB;
      dfdy[6 * 8 + z] = dA * c1 + dB * s1;
      dfdy[7 * 8 + z] = dA * c2 - dB * s2;
    }
    dfdy[4 * 8 + 5] += 2.0 * Rw;
    dfdy[4 * 8 + 0] += Rw2;
    dfdy[5 * 8 + 4] += -2.0 * Rw;
    dfdy[5 * 8 + 1] += Rw2;
    dfdy[6 * 8 + 6] += -h;
    dfdy[6 * 8 + 2] += -q.A * s1 + q.B * c1;
    dfdy[7 * 8 + 7] += -h;
    dfdy[7 * 8 + 3] += -q.A * s2 - q.B * c2;
  }
  for (z = 0; z < 8; z++) dfdt[z] = 0.0; /* autonomous */
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_jac(double tau, const double y[], double *dfdy, double dfdt[],
                         void *params) {
  const autobal_pendulum_params *p = (const autobal_pendulum_params *)params;
  (void)tau;
  if (p == NULL || y == NULL || dfdy == NULL || dfdt == NULL) return AUTOBAL_EINVAL;
  return motion_jac(p, sin(p->psi0), y, dfdy, dfdt);
}

int autobal_pendulum_motion_jac(double tau, const double y[], double *dfdy, double dfdt[],
                                void *motion) {
  const autobal_pendulum_motion *m = (const autobal_pendulum_motion *)motion;
  (void)tau;
  if (m == NULL || y == NULL || dfdy == NULL || dfdt == NULL) return AUTOBAL_EINVAL;
  return motion_jac(&m->p, m->sin_psi0, y, dfdy, dfdt);
}

void autobal_pendulum_main_motion(const autobal_pendulum_params *p, double y[]) {
  size_t i;
  for (i = 0; i < 8; i++) y[i] = 0.0;
  y[2] = y[3] = p->psi0; /* eq. (4) */
}

/* remainder(a, 2 pi) is exact and is a itself when |a| <= pi (the nearest multiple of 2 pi is 0;
 * at |a| = pi a tie, rounded to the even multiple 0): then no call, the same number bit for bit. */
static inline double wrap_angle(double a) {
  double w = fabs(a) <= M_PI ? a : remainder(a, 2.0 * M_PI); /* in [-pi, pi] */
  if (w <= -M_PI) w += 2.0 * M_PI;
  return w;
}

double autobal_pendulum_wrap_angle(double a) { return wrap_angle(a); }

double autobal_pendulum_shaft_amplitude(const double y[]) { return hypot(y[0], y[1]); }

double autobal_pendulum_residual_unbalance(const autobal_pendulum_params *p, const double y[],
                                           double *d_u, double *d_v) {
  const double du = sin(p->psi0) - 0.5 * (sin(y[2]) + sin(y[3]));
  const double dv = 0.5 * (cos(y[2]) - cos(y[3]));
  if (d_u) *d_u = du;
  if (d_v) *d_v = dv;
  return hypot(du, dv);
}

double autobal_pendulum_unbalance_scalar(double tau, const double y[], void *params) {
  (void)tau;
  return autobal_pendulum_residual_unbalance((const autobal_pendulum_params *)params, y, NULL,
                                             NULL);
}

double autobal_pendulum_jacobi_integral(const autobal_pendulum_params *p, const double y[]) {
  const double Rw2 = p->R_w * p->R_w, Rm = p->R_m, s0 = sin(p->psi0);
  const double xi = y[0], eta = y[1], dxi = y[4], deta = y[5], dpsi = y[6], dphi = y[7];
  const double s1 = sin(y[2]), c1 = cos(y[2]), s2 = sin(y[3]), c2 = cos(y[3]);
  const double T2 = 0.5 * (dxi * dxi + deta * deta + Rm * (dpsi * dpsi + dphi * dphi)) -
                    Rm * dxi * (c1 * dpsi + c2 * dphi) - Rm * deta * (s1 * dpsi - s2 * dphi);
  const double T0 =
      0.5 * Rw2 * (xi * xi + eta * eta + 2.0 * Rm * (xi * (2.0 * s0 - s1 - s2) + eta * (c1 - c2)));
  const double V = 0.5 * (xi * xi + eta * eta);
  return T2 - T0 + V;
}

double autobal_pendulum_jacobi_power(const autobal_pendulum_params *p, const double y[]) {
  const double Rw = p->R_w;
  const double vx = y[4] - Rw * y[1], vy = y[5] + Rw * y[0]; /* absolute shaft velocity */
  return -p->H * (vx * y[4] + vy * y[5]) - p->R_m * p->h * (y[6] * y[6] + y[7] * y[7]);
}

/* The same expressions as shaft_amplitude, residual_unbalance, wrap_angle and jacobi_integral
 * (the same numbers, bit for bit: no contraction in ISO C mode), with sin(psi0) and the sines and
 * cosines of the two angles computed once instead of twice (called at every output point);
 * s0 = sin(p->psi0), computed by the caller (once per run: autobal_pendulum_motion_derive_m).
 * fast = 1 (a constant at every call: the function is inlined and specialized): the sines and
 * cosines by fastmath.h's autobal_sincos2 and the two hypot by autobal_hypot_fast instead of
 * libm (autobal_pendulum_motion_derive_fast); the rest is the same expressions. */
static AUTOBAL_FM_INLINE void derive(const autobal_pendulum_params *p, double s0, const double y[],
                                     autobal_pendulum_motion_derived *out, int fast) {
  double s1, c1, s2, c2;
  if (fast) {
    /* both angles in one pass (the two lanes of one vector) */
    const double a[2] = {y[2], y[3]};
    double sn[2], cs[2];
    autobal_sincos2(a, sn, cs);
    s1 = sn[0], c1 = cs[0], s2 = sn[1], c2 = cs[1];
  } else {
    s1 = sin(y[2]), c1 = cos(y[2]), s2 = sin(y[3]), c2 = cos(y[3]);
  }
  const double du = s0 - 0.5 * (s1 + s2), dv = 0.5 * (c1 - c2);
  const double Rw2 = p->R_w * p->R_w, Rm = p->R_m;
  const double xi = y[0], eta = y[1], dxi = y[4], deta = y[5], dpsi = y[6], dphi = y[7];
  const double T2 = 0.5 * (dxi * dxi + deta * deta + Rm * (dpsi * dpsi + dphi * dphi)) -
                    Rm * dxi * (c1 * dpsi + c2 * dphi) - Rm * deta * (s1 * dpsi - s2 * dphi);
  const double T0 =
      0.5 * Rw2 * (xi * xi + eta * eta + 2.0 * Rm * (xi * (2.0 * s0 - s1 - s2) + eta * (c1 - c2)));
  const double V = 0.5 * (xi * xi + eta * eta);
  out->amplitude = fast ? autobal_hypot_fast(y[0], y[1]) : hypot(y[0], y[1]);
  out->unbalance_u = du;
  out->unbalance_v = dv;
  out->unbalance = fast ? autobal_hypot_fast(du, dv) : hypot(du, dv);
  out->alpha = wrap_angle(y[2] - p->psi0);
  out->beta = wrap_angle(y[3] - p->psi0);
  out->jacobi = T2 - T0 + V;
}

void autobal_pendulum_motion_derive(const autobal_pendulum_params *p, const double y[],
                                    autobal_pendulum_motion_derived *out) {
  derive(p, sin(p->psi0), y, out, 0);
}

void autobal_pendulum_motion_derive_m(const autobal_pendulum_motion *m, const double y[],
                                      autobal_pendulum_motion_derived *out) {
  derive(&m->p, m->sin_psi0, y, out, 0); /* m->sin_psi0 = sin(m->p.psi0) (motion_init) */
}

/* compiled for AVX2 and the baseline (GCC function multiversioning, as rotor.c's ball_sincos):
 * the constants of the two-lane sine and cosine are broadcast by one instruction each there; no
 * FMA in either clone, so both give the same bits */
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 8 && defined(__x86_64__) && \
    defined(__linux__) && !defined(AUTOBAL_NO_CLONES)
__attribute__((target_clones("avx2", "default")))
#endif
void autobal_pendulum_motion_derive_fast(const autobal_pendulum_motion *m, const double y[],
                                         autobal_pendulum_motion_derived *out) {
  derive(&m->p, m->sin_psi0, y, out, 1);
}

/* derive_fast over columns: in chunks of DCOLS states, (1) the sines and cosines of psi and phi in
 * one vectorizable pass (autobal_sincos_array: the bits of autobal_sincos2's lanes, libm out of
 * range), (2) derive's expressions in the same order over the chunk (no FMA: the bits of derive),
 * hypot as sqrt(a^2 + b^2) (the square roots in a pass of their own) and the wrap as the
 * identity, with the states where either is not valid (outside hypot_fast's sqrt range, |a| >= pi,
 * NaN) marked on the bits as in autobal_sincos_array, (3) those few states again by derive's
 * scalar functions. */
enum { DCOLS = 64 };
/* one chunk of nc <= DCOLS states (a function of its own: inside the loop over the chunks GCC
 * does not vectorize the loops) */
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 8 && defined(__x86_64__) && \
    defined(__linux__) && !defined(AUTOBAL_NO_CLONES)
__attribute__((target_clones("avx2", "default")))
#endif
static void derive_chunk(const autobal_pendulum_motion *m, size_t nc, const double *restrict xi_,
                         const double *restrict eta_, const double *restrict psi_, const double *restrict phi_,
                         const double *restrict dxi_, const double *restrict deta_,
                         const double *restrict dpsi_, const double *restrict dphi_, double *restrict amp,
                         double *restrict unb, double *restrict uu, double *restrict uv, double *restrict al,
                         double *restrict be, double *restrict jac) {
  const autobal_pendulum_params *p = &m->p;
  const double s0 = m->sin_psi0, psi0 = p->psi0, Rw2 = p->R_w * p->R_w, Rm = p->R_m;
  const double lo = 0x1p-968, hi = 0x1p1000, pi = M_PI;
  const uint64_t absmask = ~((uint64_t)1 << 63);
  uint64_t blo, bhi, bpi1, bad = 0;
  double sn1[DCOLS], cs1[DCOLS], sn2[DCOLS], cs2[DCOLS];
  size_t k;
  memcpy(&blo, &lo, sizeof blo);
  memcpy(&bhi, &hi, sizeof bhi);
  memcpy(&bpi1, &pi, sizeof bpi1);
  bpi1 -= 1; /* the double below pi */
  (void)autobal_sincos_array(psi_, sn1, cs1, nc);
  (void)autobal_sincos_array(phi_, sn2, cs2, nc);
  for (k = 0; k < nc; k++) {
    const double s1 = sn1[k], c1 = cs1[k], s2 = sn2[k], c2 = cs2[k];
    const double xi = xi_[k], eta = eta_[k], dxi = dxi_[k], deta = deta_[k], dpsi = dpsi_[k],
                 dphi = dphi_[k];
    const double du = s0 - 0.5 * (s1 + s2), dv = 0.5 * (c1 - c2);
    const double T2 = 0.5 * (dxi * dxi + deta * deta + Rm * (dpsi * dpsi + dphi * dphi)) -
                      Rm * dxi * (c1 * dpsi + c2 * dphi) - Rm * deta * (s1 * dpsi - s2 * dphi);
    const double T0 =
        0.5 * Rw2 * (xi * xi + eta * eta + 2.0 * Rm * (xi * (2.0 * s0 - s1 - s2) + eta * (c1 - c2)));
    const double V = 0.5 * (xi * xi + eta * eta);
    const double qa = xi * xi + eta * eta, qu = du * du + dv * dv; /* hypot_fast's sums */
    const double a1 = psi_[k] - psi0, a2 = phi_[k] - psi0;
    uint64_t b1, b2, b3, b4;
    memcpy(&b1, &qa, sizeof b1);
    memcpy(&b2, &qu, sizeof b2);
    memcpy(&b3, &a1, sizeof b3);
    memcpy(&b4, &a2, sizeof b4);
    /* out of range: the difference wraps around and sets the top bit (qa, qu >= 0 or NaN) */
    bad |= (bhi - b1) | (b1 - blo) | (bhi - b2) | (b2 - blo) | (bpi1 - (b3 & absmask)) |
           (bpi1 - (b4 & absmask));
    amp[k] = qa; /* the square roots in the next pass (libm's sqrt sets errno: not vectorized) */
    uu[k] = du;
    uv[k] = dv;
    unb[k] = qu;
    /* wrap_angle for |a| < pi: a itself (|a| >= pi, with -pi -> pi, in the last pass) */
    al[k] = a1;
    be[k] = a2;
    jac[k] = T2 - T0 + V;
  }
  for (k = 0; k < nc; k++) {
    amp[k] = sqrt(amp[k]);
    unb[k] = sqrt(unb[k]);
  }
  if ((bad >> 63) != 0) {
    for (k = 0; k < nc; k++) {
      amp[k] = autobal_hypot_fast(xi_[k], eta_[k]);
      unb[k] = autobal_hypot_fast(uu[k], uv[k]);
      al[k] = wrap_angle(psi_[k] - psi0);
      be[k] = wrap_angle(phi_[k] - psi0);
    }
  }
}

void autobal_pendulum_motion_derive_fast_cols(const autobal_pendulum_motion *m, size_t n,
                                              const double *const y[8], double *const d[7]) {
  size_t k0;
  for (k0 = 0; k0 < n; k0 += DCOLS) {
    const size_t nc = n - k0 < DCOLS ? n - k0 : DCOLS;
    derive_chunk(m, nc, y[0] + k0, y[1] + k0, y[2] + k0, y[3] + k0, y[4] + k0, y[5] + k0, y[6] + k0,
                 y[7] + k0, d[0] + k0, d[1] + k0, d[2] + k0, d[3] + k0, d[4] + k0, d[5] + k0, d[6] + k0);
  }
}
