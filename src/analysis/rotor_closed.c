/* rotor_closed.c: members of the family of balanced configurations of the rotor with ball
 * autobalancers (docs/rotor.md, (3.14)) and the closed linear system of the isotropic rotor
 * ((3.15), (3.16)): its degree-12 characteristic polynomial Delta and its real first-order
 * matrix.  Functions of plain data (a plane, an autobal_rotor_closed), no analysis handle.
 *
 * May use: the rotor model (autobal/rotor.h), the numerics (autobal/stability.h: polynomial
 * arithmetic), GSL (LU), core (internal.h).  Used by rotor_stab_handle.c and
 * rotor_stability.c through rotor_closed.h; it uses no other file of src/analysis/. */
#include "autobal/rotor_stability.h"
#include "autobal/stability.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include "analysis/rotor_closed.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- small helpers ---------------------------------------------------------- */

static double wrap_pi(double a) {
  double w = a - 2.0 * M_PI * ceil((a - M_PI) / (2.0 * M_PI));
  if (w <= -M_PI) w += 2.0 * M_PI;
  if (w > M_PI) w -= 2.0 * M_PI;
  return w;
}

int autobal_rotor_close_rel_(double a, double b, double rtol) {
  return fabs(a - b) <= rtol * fmax(fabs(a), fabs(b));
}

int autobal_rotor_lumped_isotropic_(const autobal_rotor_lumped *L) {
  const double t = 1e-12;
  return autobal_rotor_close_rel_(L->c_x, L->c_y, t) && autobal_rotor_close_rel_(L->c_alpha, L->c_beta, t) &&
         autobal_rotor_close_rel_(L->c_xbeta, L->c_yalpha, t) && autobal_rotor_close_rel_(L->h_x, L->h_y, t) &&
         autobal_rotor_close_rel_(L->h_alpha, L->h_beta, t) && autobal_rotor_close_rel_(L->h_xbeta, L->h_yalpha, t);
}

/* ---- members of the family of balanced configurations (3.14) ----------------- */

/* Existence (same rule as autobal_rotor_plane_can_balance, without an array of a). */
static int plane_can_balance(const autobal_rotor_plane *pl) {
  double sum = 0.0, amax = 0.0, lo, s0 = pl->m0 * pl->r0;
  size_t i;
  if (pl->n_balls == 0) return s0 == 0.0;
  for (i = 0; i < pl->n_balls; i++) {
    double a = pl->ball_mass[i] * pl->ball_radius[i];
    sum += a;
    if (a > amax) amax = a;
  }
  lo = 2.0 * amax - sum;
  if (lo < 0.0) lo = 0.0;
  return s0 <= sum * (1.0 + 1e-12) && s0 >= lo - 1e-12 * sum;
}

/* The last two balls (indices n-2, n-1) so that they reach the remaining target
 * (Tx, Ty): a1 e^{i psi1} + a2 e^{i psi2} = T = -|T| e^{i arg(-T)}. */
static int place_last_two(const autobal_rotor_plane *pl, size_t n, double Tx, double Ty,
                          double *psi, autobal_error *err) {
  double a1 = pl->ball_mass[n - 2] * pl->ball_radius[n - 2];
  double a2 = pl->ball_mass[n - 1] * pl->ball_radius[n - 1];
  double tau = hypot(Tx, Ty);
  double ang = tau > 0.0 ? atan2(-Ty, -Tx) : 0.0;
  double slack = 1e-12 * (a1 + a2 + tau);
  if (tau > a1 + a2 + slack || tau < fabs(a1 - a2) - slack)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "member: the last two balls (m r = %.6g, %.6g kg m) cannot reach the "
                             "remaining unbalance %.6g kg m left by the given angles",
                             a1, a2, tau);
  if (tau > a1 + a2) tau = a1 + a2;
  if (tau < fabs(a1 - a2)) tau = fabs(a1 - a2);
  if (tau == 0.0 && a1 != a2) tau = fabs(a1 - a2);
  return autobal_rotor_balanced_angles_two(tau, a1, a2, ang, psi + n - 2, err);
}

int autobal_rotor_member_angles(const autobal_rotor_plane *pl, const autobal_rotor_member *mem,
                                double *psi, size_t n, autobal_error *err) {
  int kind = mem ? mem->kind : AUTOBAL_ROTOR_MEMBER_DEFAULT;
  double s0, Tx, Ty;
  size_t i;
  int identical = 1;
  if (pl == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "member: plane is NULL");
  if (n != pl->n_balls || (n > 0 && psi == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "member: n = %zu must equal the plane's ball count %zu", n, pl->n_balls);
  if (n > 0 && (pl->ball_mass == NULL || pl->ball_radius == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL, "member: NULL ball arrays");
  if (kind < AUTOBAL_ROTOR_MEMBER_DEFAULT || kind > AUTOBAL_ROTOR_MEMBER_GIVEN)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "member: kind = %d is not valid (0 default, 1 symmetric, 2 free, 3 given)",
                             kind);
  s0 = pl->m0 * pl->r0;
  if (!plane_can_balance(pl))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "no balanced configuration (3.14) exists: the balls cannot cancel m0 r0 "
                             "= %.6g kg m",
                             s0);
  if (n == 0) return AUTOBAL_SUCCESS;
  for (i = 1; i < n; i++)
    if (!autobal_rotor_close_rel_(pl->ball_mass[i] * pl->ball_radius[i], pl->ball_mass[0] * pl->ball_radius[0],
                                  1e-12))
      identical = 0;
  if (kind == AUTOBAL_ROTOR_MEMBER_GIVEN) {
    double sx = s0 * cos(pl->psi0), sy = s0 * sin(pl->psi0), asum = s0;
    if (mem->n_angles != n || mem->angles == NULL)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "member 'given': %zu angles for %zu balls (need all of them)",
                               mem->n_angles, n);
    for (i = 0; i < n; i++) {
      double a = pl->ball_mass[i] * pl->ball_radius[i];
      if (!isfinite(mem->angles[i]))
        return autobal_error_set(err, AUTOBAL_EINVAL, "member angle %zu = %g is not finite", i,
                                 mem->angles[i]);
      sx += a * cos(mem->angles[i]);
      sy += a * sin(mem->angles[i]);
      asum += a;
      psi[i] = wrap_pi(mem->angles[i]);
    }
    if (hypot(sx, sy) > 1e-9 * asum)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "member 'given': the angles do not balance the plane: residual "
                               "unbalance %.3g kg m (allowed 1e-9 of %.6g kg m)",
                               hypot(sx, sy), asum);
    return AUTOBAL_SUCCESS;
  }
  if (n == 1) {
    psi[0] = wrap_pi(pl->psi0 + M_PI);
    return AUTOBAL_SUCCESS;
  }
  if (n == 2) {
    return autobal_rotor_balanced_angles_two(s0, pl->ball_mass[0] * pl->ball_radius[0],
                                             pl->ball_mass[1] * pl->ball_radius[1], pl->psi0, psi,
                                             err);
  }
  if (kind == AUTOBAL_ROTOR_MEMBER_SYMMETRIC ||
      (kind == AUTOBAL_ROTOR_MEMBER_DEFAULT && identical)) {
    /* symmetric fan: sum_i e^{i (i-(n-1)/2) 2x} = sin(n x)/sin(x) = s0/a, x in (0, pi/n] */
    const double a = pl->ball_mass[0] * pl->ball_radius[0], nn = (double)n, target = s0 / a;
    double lo = 0.0, hi = M_PI / nn, x;
    int it;
    if (!identical)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "member 'symmetric' needs identical m_i r_i in the plane");
    for (it = 0; it < 200; it++) {
      const double mid = 0.5 * (lo + hi);
      if (sin(nn * mid) / sin(mid) > target) lo = mid;
      else hi = mid;
    }
    x = target >= nn ? 0.0 : 0.5 * (lo + hi);
    for (i = 0; i < n; i++) psi[i] = wrap_pi(pl->psi0 + M_PI + ((double)i - 0.5 * (nn - 1.0)) * 2.0 * x);
    return AUTOBAL_SUCCESS;
  }
  Tx = -s0 * cos(pl->psi0);
  Ty = -s0 * sin(pl->psi0);
  if (kind == AUTOBAL_ROTOR_MEMBER_FREE) {
    if (mem->n_angles != n - 2 || mem->angles == NULL)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "member 'free': %zu angles given, need n - 2 = %zu (balls 1..n-2)",
                               mem->n_angles, n - 2);
    for (i = 0; i + 2 < n; i++) {
      double a = pl->ball_mass[i] * pl->ball_radius[i];
      if (!isfinite(mem->angles[i]))
        return autobal_error_set(err, AUTOBAL_EINVAL, "member angle %zu = %g is not finite", i,
                                 mem->angles[i]);
      psi[i] = wrap_pi(mem->angles[i]);
      Tx -= a * cos(psi[i]);
      Ty -= a * sin(psi[i]);
    }
    return place_last_two(pl, n, Tx, Ty, psi, err);
  }
  /* DEFAULT with unequal m_i r_i: ball by ball, each remaining sub-chain keeping the
   * remaining target inside its reachable annulus (the rule of autobal_rotor_balanced_angles) */
  for (i = 0; i + 2 < n; i++) {
    double rest = 0.0, amax = 0.0, lrest, tau, lo, hi, rho, ang, cg;
    double ai = pl->ball_mass[i] * pl->ball_radius[i];
    size_t k;
    for (k = i + 1; k < n; k++) {
      double a = pl->ball_mass[k] * pl->ball_radius[k];
      rest += a;
      if (a > amax) amax = a;
    }
    lrest = 2.0 * amax - rest;
    if (lrest < 0.0) lrest = 0.0;
    tau = hypot(Tx, Ty);
    lo = fmax(lrest, fabs(tau - ai));
    hi = fmin(rest, tau + ai);
    rho = 0.5 * (lo + hi);
    if (tau > 0.0) {
      cg = (tau * tau + ai * ai - rho * rho) / (2.0 * tau * ai);
      cg = cg > 1.0 ? 1.0 : (cg < -1.0 ? -1.0 : cg);
      ang = atan2(Ty, Tx) + ((i % 2) ? -acos(cg) : acos(cg));
    } else {
      ang = 0.0;
    }
    psi[i] = wrap_pi(ang);
    Tx -= ai * cos(ang);
    Ty -= ai * sin(ang);
  }
  return place_last_two(pl, n, Tx, Ty, psi, err);
}

/* ---- the closed linear system -------------------------------------------------- */

/* Rank (0..2) of dpsi -> dsigma = sum_i i a_i e^{i psi_i} dpsi_i (Gram determinant test). */
size_t autobal_rotor_plane_rank_(const double *m, const double *r, const double *psi, size_t n) {
  double g11 = 0.0, g12 = 0.0, g22 = 0.0, tr;
  size_t i;
  for (i = 0; i < n; i++) {
    double a = m[i] * r[i], vx = -a * sin(psi[i]), vy = a * cos(psi[i]);
    g11 += vx * vx;
    g12 += vx * vy;
    g22 += vy * vy;
  }
  tr = g11 + g22;
  if (!(tr > 0.0)) return 0;
  return (g11 * g22 - g12 * g12) > 1e-10 * tr * tr ? 2 : 1;
}

/* Interleaved complex polynomial of at most 13 coefficients. */
typedef struct cpoly {
  double c[2 * AUTOBAL_ROTOR_POLY_LEN];
  size_t len;
} cpoly;

static void cp_set(cpoly *p, size_t len, const double *v) {
  memset(p, 0, sizeof *p);
  p->len = len;
  memcpy(p->c, v, 2 * len * sizeof(double));
}
/* out = a * b (complex) */
static void cp_mul(const cpoly *a, const cpoly *b, cpoly *out) {
  cpoly t;
  memset(&t, 0, sizeof t);
  t.len = a->len + b->len - 1;
  (void)autobal_cpoly_mul(a->c, a->len, b->c, b->len, t.c, t.len, NULL);
  *out = t;
}
/* out = (xr + i xi) a + (yr + i yi) b */
static void cp_axpby(double xr, double xi, const cpoly *a, double yr, double yi, const cpoly *b,
                     cpoly *out) {
  cpoly t;
  memset(&t, 0, sizeof t);
  t.len = a->len > b->len ? a->len : b->len;
  (void)autobal_cpoly_axpby(xr, xi, a->c, a->len, yr, yi, b->c, b->len, t.c, t.len, NULL);
  *out = t;
}
/* Real magnitude polynomials for the error bound. */
typedef struct rpoly {
  double c[AUTOBAL_ROTOR_POLY_LEN];
  size_t len;
} rpoly;
static void rp_mul(const rpoly *a, const rpoly *b, rpoly *out) {
  rpoly t;
  memset(&t, 0, sizeof t);
  t.len = a->len + b->len - 1;
  (void)autobal_poly_mul(a->c, a->len, b->c, b->len, t.c, t.len, NULL);
  *out = t;
}
static void rp_axpby(double x, const rpoly *a, double y, const rpoly *b, rpoly *out) {
  rpoly t;
  memset(&t, 0, sizeof t);
  t.len = a->len > b->len ? a->len : b->len;
  (void)autobal_poly_axpby(x, a->c, a->len, y, b->c, b->len, t.c, t.len, NULL);
  *out = t;
}

/* The two parts of Delta = F F* - (|Q| / 2)^2 P^4 Pb^4 N N* of a one-plane isotropic closed system:
 * FF = F F* and G = P^4 Pb^4 N N* (complex arithmetic; both are real polynomials).  Neither depends
 * on Q: with the paper's inertia (m_add = 0) they do not depend on the unbalance at all. */
static void delta_parts(const autobal_rotor_closed *c, cpoly *FFo, cpoly *Go, cpoly *NNo) {
  const autobal_rotor_lumped *L = &c->L;
  const autobal_rotor_closed_plane *pl = &c->plane[0];
  const double w = c->omega, d = pl->d, ma = pl->m_add;
  cpoly P, P2, P4, Pb4, one, K11, K12, K22, D, N, L2, F, Fs, FF, Ns, NN, PP, G, t1, t2;
  {
    const double vP[4] = {0.0, w, 1.0, 0.0}; /* P = lambda + i w */
    const double v1[2] = {1.0, 0.0};
    cp_set(&P, 2, vP);
    cp_set(&one, 1, v1);
  }
  cp_mul(&P, &P, &P2);
  cp_mul(&P2, &P2, &P4);
  Pb4 = P4;
  autobal_cpoly_conj(P4.c, P4.len, Pb4.c); /* Pb^4 = (P^4)*, since P* = lambda - i w = Pb */
  /* K11 = (M + m_a) P^2 + h P + c */
  cp_axpby(L->M + ma, 0.0, &P2, L->h_x, 0.0, &P, &t1);
  cp_axpby(1.0, 0.0, &t1, L->c_x, 0.0, &one, &K11);
  /* K22 = (A + m_a d^2) P^2 + (h_t - i C w) P + c_t */
  cp_axpby(L->A + ma * d * d, 0.0, &P2, L->h_alpha, -L->C * w, &P, &t1);
  cp_axpby(1.0, 0.0, &t1, L->c_alpha, 0.0, &one, &K22);
  /* K12 = -(h_c P + c_c) + m_a d P^2 */
  cp_axpby(-L->h_xbeta, 0.0, &P, -L->c_xbeta, 0.0, &one, &t1);
  cp_axpby(1.0, 0.0, &t1, ma * d, 0.0, &P2, &K12);
  /* D = K11 K22 - K12^2 */
  cp_mul(&K11, &K22, &t1);
  cp_mul(&K12, &K12, &t2);
  cp_axpby(1.0, 0.0, &t1, -1.0, 0.0, &t2, &D);
  /* N = K22 - 2 d K12 + d^2 K11 (N of docs/rotor.md; independent of m_a) */
  cp_axpby(1.0, 0.0, &K22, -2.0 * d, 0.0, &K12, &t1);
  cp_axpby(1.0, 0.0, &t1, d * d, 0.0, &K11, &N);
  /* F = (lambda^2 + kappa lambda) D - (m_b / 2) P^4 N */
  {
    const double vL2[6] = {0.0, 0.0, pl->kappa, 0.0, 1.0, 0.0};
    cp_set(&L2, 3, vL2);
  }
  cp_mul(&L2, &D, &t1);
  cp_mul(&P4, &N, &t2);
  cp_axpby(1.0, 0.0, &t1, -0.5 * pl->mass, 0.0, &t2, &F);
  /* Delta = F F* - (|Q| / 2)^2 P^4 Pb^4 N N* */
  Fs = F;
  autobal_cpoly_conj(F.c, F.len, Fs.c);
  cp_mul(&F, &Fs, &FF);
  Ns = N;
  autobal_cpoly_conj(N.c, N.len, Ns.c);
  cp_mul(&N, &Ns, &NN);
  cp_mul(&P4, &Pb4, &PP);
  cp_mul(&PP, &NN, &G);
  *FFo = FF;
  *Go = G;
  if (NNo) *NNo = NN;
}

int autobal_rotor_char_poly(const autobal_rotor_closed *c, double coef[13], double cerr[13],
                            autobal_error *err) {
  const autobal_rotor_lumped *L;
  const autobal_rotor_closed_plane *pl;
  double w, d, ma, qabs, max_imag = 0.0;
  cpoly FF, G, Del;
  rpoly aP, aP2, aP4, aone, aK11, aK12, aK22, aD, aN, aL2, aF, aPP, aNN, aDel, r1, r2;
  size_t k;
  if (c == NULL || coef == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "char_poly: NULL argument");
  if (c->n_planes != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "char_poly: Delta is built for one plane (n_planes = %zu); use the closed "
                             "matrix for two planes",
                             c->n_planes);
  if (!c->isotropic)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "char_poly: the supports are not isotropic (c_x = c_y, c_alpha = "
                             "c_beta, c_xbeta = c_yalpha and the same for h are required)");
  L = &c->L;
  pl = &c->plane[0];
  w = c->omega;
  d = pl->d;
  ma = pl->m_add;
  qabs = hypot(pl->Q_re, pl->Q_im);
  delta_parts(c, &FF, &G, NULL);
  cp_axpby(1.0, 0.0, &FF, -0.25 * qabs * qabs, 0.0, &G, &Del);
  autobal_cpoly_real_part(Del.c, Del.len, coef, &max_imag);
  if (!(max_imag <= 1e-10))
    return autobal_error_set(err, AUTOBAL_ENUMERIC,
                             "char_poly: Delta is not real (relative imaginary part %.3g)", max_imag);
  for (k = 0; k < AUTOBAL_ROTOR_POLY_LEN; k++)
    if (!isfinite(coef[k]))
      return autobal_error_set(err, AUTOBAL_ENUMERIC, "char_poly: coefficient %zu is not finite", k);
  if (cerr) {
    /* the same construction with the moduli of every coefficient: a bound of the
     * sizes of the terms summed, hence of the rounding error (a few dozen
     * operations per coefficient: 64 eps per unit of that size) */
    aP.len = 2;
    aP.c[0] = fabs(w);
    aP.c[1] = 1.0;
    aone.len = 1;
    aone.c[0] = 1.0;
    rp_mul(&aP, &aP, &aP2);
    rp_mul(&aP2, &aP2, &aP4);
    rp_axpby(L->M + ma, &aP2, fabs(L->h_x), &aP, &r1);
    rp_axpby(1.0, &r1, fabs(L->c_x), &aone, &aK11);
    rp_axpby(L->A + ma * d * d, &aP2, hypot(L->h_alpha, L->C * w), &aP, &r1);
    rp_axpby(1.0, &r1, fabs(L->c_alpha), &aone, &aK22);
    rp_axpby(fabs(L->h_xbeta), &aP, fabs(L->c_xbeta), &aone, &r1);
    rp_axpby(1.0, &r1, fabs(ma * d), &aP2, &aK12);
    rp_mul(&aK11, &aK22, &r1);
    rp_mul(&aK12, &aK12, &r2);
    rp_axpby(1.0, &r1, 1.0, &r2, &aD);
    rp_axpby(1.0, &aK22, 2.0 * fabs(d), &aK12, &r1);
    rp_axpby(1.0, &r1, d * d, &aK11, &aN);
    aL2.len = 3;
    aL2.c[0] = 0.0;
    aL2.c[1] = fabs(pl->kappa);
    aL2.c[2] = 1.0;
    rp_mul(&aL2, &aD, &r1);
    rp_mul(&aP4, &aN, &r2);
    rp_axpby(1.0, &r1, 0.5 * pl->mass, &r2, &aF);
    rp_mul(&aF, &aF, &r1);
    rp_mul(&aP4, &aP4, &aPP);
    rp_mul(&aN, &aN, &aNN);
    rp_mul(&aPP, &aNN, &r2);
    rp_axpby(1.0, &r1, 0.25 * qabs * qabs, &r2, &aDel);
    for (k = 0; k < AUTOBAL_ROTOR_POLY_LEN; k++) cerr[k] = 64.0 * DBL_EPSILON * aDel.c[k];
  }
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_char_parts_(const autobal_rotor_closed *c, double A[13], double Bt[13], autobal_error *err) {
  cpoly FF, G, NN;
  double mi1 = 0.0, mi2 = 0.0;
  if (c == NULL || A == NULL || Bt == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "char_parts: NULL argument");
  if (c->n_planes != 1 || !c->isotropic)
    return autobal_error_set(err, AUTOBAL_EINVAL, "char_parts: one plane and isotropic supports are required");
  delta_parts(c, &FF, &G, &NN);
  if (FF.len != AUTOBAL_ROTOR_POLY_LEN || NN.len > AUTOBAL_ROTOR_POLY_LEN)
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "char_parts: internal degree error");
  memset(Bt, 0, AUTOBAL_ROTOR_POLY_LEN * sizeof(double));
  autobal_cpoly_real_part(FF.c, FF.len, A, &mi1);
  autobal_cpoly_real_part(NN.c, NN.len, Bt, &mi2);
  if (!(mi1 <= 1e-10) || !(mi2 <= 1e-10))
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "char_parts: F F* or N N* is not real (relative %.3g, %.3g)",
                             mi1, mi2);
  return AUTOBAL_SUCCESS;
}

size_t autobal_rotor_closed_dim(const autobal_rotor_closed *c) {
  return c ? 8 + 4 * c->n_planes : 0;
}

/* Complex coefficient matrices of the closed second-order system (see the header of
 * rotor_stability.h): sum_k al[o][r][k] z_k^(o) + be[o][r][k] conj(z_k)^(o), o = 0, 1, 2. */
typedef struct cmat {
  double al[3][4][4][2];
  double be[3][4][4][2];
} cmat;

static void cm_add(double (*m)[4][4][2], int o, int r, int k, double re, double im) {
  m[o][r][k][0] += re;
  m[o][r][k][1] += im;
}
/* coef * p(z_k) into row r, p(f) = f'' + 2 i w f' - w^2 f */
static void cm_p(cmat *m, double w, int r, int k, double re, double im) {
  cm_add(m->al, 2, r, k, re, im);
  cm_add(m->al, 1, r, k, -2.0 * w * im, 2.0 * w * re);
  cm_add(m->al, 0, r, k, -w * w * re, -w * w * im);
}
/* coef * q(z_k), q(f) = f' + i w f */
static void cm_q(cmat *m, double w, int r, int k, double re, double im) {
  cm_add(m->al, 1, r, k, re, im);
  cm_add(m->al, 0, r, k, -w * im, w * re);
}
/* coef * conj(p(z_k)) = coef * (f̄'' - 2 i w f̄' - w^2 f̄) */
static void cm_pc(cmat *m, double w, int r, int k, double re, double im) {
  cm_add(m->be, 2, r, k, re, im);
  cm_add(m->be, 1, r, k, 2.0 * w * im, -2.0 * w * re);
  cm_add(m->be, 0, r, k, -w * w * re, -w * w * im);
}

/* Closed matrix into a (dim x dim), using the LU workspace lu/perm (nr x nr, nr = dim/2). */
int autobal_rotor_closed_matrix_ws_(const autobal_rotor_closed *c, double *a, size_t dim,
                                    gsl_matrix *lu, gsl_permutation *perm, autobal_error *err) {
  cmat m;
  const autobal_rotor_lumped *L;
  const double w = c->omega;
  const int nc = 2 + (int)c->n_planes, nr = 2 * nc;
  double Mr[8][8], Cr[8][8], Kr[8][8];
  int r, k, o, j, signum, gs;
  size_t i;
  if (dim != (size_t)(2 * nr) || lu->size1 != (size_t)nr)
    return autobal_error_set(err, AUTOBAL_EINVAL, "closed matrix: dim = %zu, need %d", dim, 2 * nr);
  if (!c->isotropic)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "closed matrix: the supports are not isotropic; use FULL or FLOQUET");
  L = &c->L;
  memset(&m, 0, sizeof m);
  /* W row: M p(W) + h q(W) + c W - h_c q(Theta) - c_c Theta + sum_j [p(sigma_j) + m_a p(W + d Theta)] */
  cm_p(&m, w, 0, 0, L->M, 0.0);
  cm_q(&m, w, 0, 0, L->h_x, 0.0);
  cm_add(m.al, 0, 0, 0, L->c_x, 0.0);
  cm_q(&m, w, 0, 1, -L->h_xbeta, 0.0);
  cm_add(m.al, 0, 0, 1, -L->c_xbeta, 0.0);
  /* Theta row: A p(Theta) + (h_t - i C w) q(Theta) + c_t Theta - h_c q(W) - c_c W + sum_j d_j [...] */
  cm_p(&m, w, 1, 1, L->A, 0.0);
  cm_q(&m, w, 1, 1, L->h_alpha, -L->C * w);
  cm_add(m.al, 0, 1, 1, L->c_alpha, 0.0);
  cm_q(&m, w, 1, 0, -L->h_xbeta, 0.0);
  cm_add(m.al, 0, 1, 0, -L->c_xbeta, 0.0);
  for (j = 0; j < (int)c->n_planes; j++) {
    const autobal_rotor_closed_plane *pl = &c->plane[j];
    const double d = pl->d, ma = pl->m_add;
    const int sg = 2 + j;
    cm_p(&m, w, 0, sg, 1.0, 0.0);
    cm_p(&m, w, 0, 0, ma, 0.0);
    cm_p(&m, w, 0, 1, ma * d, 0.0);
    cm_p(&m, w, 1, sg, d, 0.0);
    cm_p(&m, w, 1, 0, ma * d, 0.0);
    cm_p(&m, w, 1, 1, ma * d * d, 0.0);
    /* sigma row, (3.16): sigma'' + kappa sigma' + (m_b/2) a - (Q/2) conj(a) = 0, a = p(W + d Theta) */
    cm_add(m.al, 2, sg, sg, 1.0, 0.0);
    cm_add(m.al, 1, sg, sg, pl->kappa, 0.0);
    cm_p(&m, w, sg, 0, 0.5 * pl->mass, 0.0);
    cm_p(&m, w, sg, 1, 0.5 * pl->mass * d, 0.0);
    cm_pc(&m, w, sg, 0, -0.5 * pl->Q_re, -0.5 * pl->Q_im);
    cm_pc(&m, w, sg, 1, -0.5 * pl->Q_re * d, -0.5 * pl->Q_im * d);
  }
  /* real form: alpha z + beta conj(z) -> [[ar + br, -ai + bi], [ai + bi, ar - br]] */
  for (o = 0; o < 3; o++) {
    double(*R)[8] = o == 2 ? Mr : (o == 1 ? Cr : Kr);
    for (r = 0; r < nc; r++)
      for (k = 0; k < nc; k++) {
        const double ar = m.al[o][r][k][0], ai = m.al[o][r][k][1];
        const double br = m.be[o][r][k][0], bi = m.be[o][r][k][1];
        R[2 * r][2 * k] = ar + br;
        R[2 * r][2 * k + 1] = -ai + bi;
        R[2 * r + 1][2 * k] = ai + bi;
        R[2 * r + 1][2 * k + 1] = ar - br;
      }
  }
  for (r = 0; r < nr; r++)
    for (k = 0; k < nr; k++) gsl_matrix_set(lu, (size_t)r, (size_t)k, Mr[r][k]);
  gs = gsl_linalg_LU_decomp(lu, perm, &signum);
  if (gs != GSL_SUCCESS)
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "closed matrix: LU failed: %s", gsl_strerror(gs));
  {
    double dmax = 0.0;
    for (r = 0; r < nr; r++) dmax = fmax(dmax, fabs(gsl_matrix_get(lu, (size_t)r, (size_t)r)));
    for (r = 0; r < nr; r++)
      if (!(fabs(gsl_matrix_get(lu, (size_t)r, (size_t)r)) > 1e-14 * dmax))
        return autobal_error_set(err, AUTOBAL_ENUMERIC, "closed matrix: singular mass matrix");
  }
  for (i = 0; i < dim * dim; i++) a[i] = 0.0;
  for (r = 0; r < nr; r++) a[(size_t)r * dim + (size_t)(nr + r)] = 1.0;
  for (o = 0; o < 2; o++) {
    double(*R)[8] = o == 0 ? Kr : Cr;
    for (k = 0; k < nr; k++) {
      double col[8];
      gsl_vector_view v = gsl_vector_view_array(col, (size_t)nr);
      for (r = 0; r < nr; r++) col[r] = R[r][k];
      gs = gsl_linalg_LU_svx(lu, perm, &v.vector);
      if (gs != GSL_SUCCESS)
        return autobal_error_set(err, AUTOBAL_ENUMERIC, "closed matrix: solve failed: %s",
                                 gsl_strerror(gs));
      for (r = 0; r < nr; r++) a[(size_t)(nr + r) * dim + (size_t)(o * nr + k)] = -col[r];
    }
  }
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_closed_matrix(const autobal_rotor_closed *c, double *a, size_t dim,
                                autobal_error *err) {
  gsl_matrix *lu;
  gsl_permutation *perm;
  size_t nr;
  int st;
  if (c == NULL || a == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "closed matrix: NULL argument");
  if (c->n_planes < 1 || c->n_planes > AUTOBAL_ROTOR_MAX_PLANES)
    return autobal_error_set(err, AUTOBAL_EINVAL, "closed matrix: n_planes = %zu", c->n_planes);
  nr = 2 * (2 + c->n_planes);
  lu = gsl_matrix_alloc(nr, nr);
  perm = gsl_permutation_alloc(nr);
  if (!lu || !perm) {
    if (lu) gsl_matrix_free(lu);
    if (perm) gsl_permutation_free(perm);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "closed matrix: out of memory");
  }
  st = autobal_rotor_closed_matrix_ws_(c, a, dim, lu, perm, err);
  gsl_matrix_free(lu);
  gsl_permutation_free(perm);
  return st;
}
