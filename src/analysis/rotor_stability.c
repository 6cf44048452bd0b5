/* rotor_stability.c: stability of the balanced motions of the rotor with ball
 * autobalancers (docs/rotor.md, (3.14)-(3.16)): members of the family of balanced
 * configurations, the closed linear system of the isotropic rotor, its degree-12
 * characteristic polynomial Delta and its real first-order matrix, the analysis
 * handle, margins and verdicts by four methods, sweeps, critical values and maps.
 * The Floquet analysis and the full-model linearization are in rotor_floquet.c,
 * the rotor-housing modes in rotor_campbell.c. */
#include "autobal/rotor_stability.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#ifdef AUTOBAL_HAVE_OPENMP
#include <omp.h>
#endif

#include "internal.h"
#include "rotor_stab_internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Largest number of balls for which the full linearization and Floquet analysis
 * workspaces are allocated ((8 + 2N)^2 ODE states). */
#define MAX_FULL_BALLS 64

/* ---- small helpers ---------------------------------------------------------- */

static double wrap_pi(double a) {
  double w = a - 2.0 * M_PI * ceil((a - M_PI) / (2.0 * M_PI));
  if (w <= -M_PI) w += 2.0 * M_PI;
  if (w > M_PI) w -= 2.0 * M_PI;
  return w;
}

static int close_rel(double a, double b, double rtol) {
  return fabs(a - b) <= rtol * fmax(fabs(a), fabs(b));
}

int autobal_rotor_lumped_isotropic_(const autobal_rotor_lumped *L) {
  const double t = 1e-12;
  return close_rel(L->c_x, L->c_y, t) && close_rel(L->c_alpha, L->c_beta, t) &&
         close_rel(L->c_xbeta, L->c_yalpha, t) && close_rel(L->h_x, L->h_y, t) &&
         close_rel(L->h_alpha, L->h_beta, t) && close_rel(L->h_xbeta, L->h_yalpha, t);
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
    if (!close_rel(pl->ball_mass[i] * pl->ball_radius[i], pl->ball_mass[0] * pl->ball_radius[0],
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
static size_t plane_rank(const double *m, const double *r, const double *psi, size_t n) {
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

/* Fill the closed system from the handle's current data and member angles. */
static void closed_from_handle(const autobal_rotor_stab *s, autobal_rotor_closed *c) {
  size_t j, i;
  memset(c, 0, sizeof *c);
  c->L = s->L;
  c->omega = s->cur.omega;
  c->n_planes = s->n_planes;
  c->isotropic = autobal_rotor_lumped_isotropic_(&s->L);
  c->closure_ok = 1;
  for (j = 0; j < s->n_planes; j++) {
    autobal_rotor_closed_plane *cp = &c->plane[j];
    const size_t o = s->off[j], n = s->cnt[j];
    double k0 = n > 0 ? s->h[o] / s->m[o] : 0.0;
    cp->d = s->cur.plane[j].d;
    cp->n_balls = n;
    for (i = 0; i < n; i++) {
      const double m = s->m[o + i], ph = 2.0 * s->psi[o + i];
      cp->mass += m;
      cp->Q_re += m * cos(ph);
      cp->Q_im += m * sin(ph);
      if (!close_rel(s->h[o + i] / m, k0, 1e-12) && !(s->h[o + i] == 0.0 && k0 == 0.0))
        c->closure_ok = 0;
    }
    cp->kappa = k0;
    cp->m_add = s->cur.inertia == AUTOBAL_ROTOR_INERTIA_FULL ? cp->mass + s->cur.plane[j].m0 : 0.0;
    cp->rank = plane_rank(s->m + o, s->r + o, s->psi + o, n);
    cp->family = n - cp->rank;
    if (cp->rank < 2) c->closure_ok = 0;
  }
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

int autobal_rotor_char_poly(const autobal_rotor_closed *c, double coef[13], double cerr[13],
                            autobal_error *err) {
  const autobal_rotor_lumped *L;
  const autobal_rotor_closed_plane *pl;
  double w, d, ma, qabs, max_imag = 0.0;
  cpoly P, P2, P4, Pb4, one, K11, K12, K22, D, N, L2, F, Fs, FF, Ns, NN, PP, G, Del, t1, t2;
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
  cp_axpby(1.0, 0.0, &FF, -0.25 * qabs * qabs, 0.0, &G, &Del);
  if (Del.len != AUTOBAL_ROTOR_POLY_LEN)
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "char_poly: internal degree error");
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
static int closed_matrix_ws(const autobal_rotor_closed *c, double *a, size_t dim, gsl_matrix *lu,
                            gsl_permutation *perm, autobal_error *err) {
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
  st = closed_matrix_ws(c, a, dim, lu, perm, err);
  gsl_matrix_free(lu);
  gsl_permutation_free(perm);
  return st;
}

/* ---- the handle ---------------------------------------------------------------------- */

const char *autobal_rotor_stab_method_name(int method) {
  switch (method) {
    case AUTOBAL_ROTOR_STAB_AUTO: return "auto";
    case AUTOBAL_ROTOR_STAB_POLY: return "poly";
    case AUTOBAL_ROTOR_STAB_CLOSED: return "closed";
    case AUTOBAL_ROTOR_STAB_FULL: return "full";
    case AUTOBAL_ROTOR_STAB_FLOQUET: return "floquet";
    default: return "unknown";
  }
}

static const char *const param_names[] = {"omega", "ball_damping", "ball_mass",
                                          "stiffness_scale", "damping_scale", "unbalance_mass"};
static const char *const param_units[] = {"rad/s", "kg/s", "kg", "1", "1", "kg"};
#define N_PARAMS 6

const char *autobal_rotor_stab_param_name(int param) {
  return param >= 0 && param < N_PARAMS ? param_names[param] : NULL;
}
const char *autobal_rotor_stab_param_unit(int param) {
  return param >= 0 && param < N_PARAMS ? param_units[param] : NULL;
}
int autobal_rotor_stab_param_from_name(const char *name) {
  int i;
  if (name == NULL) return -1;
  for (i = 0; i < N_PARAMS; i++)
    if (!strcmp(name, param_names[i])) return i;
  return -1;
}

autobal_rotor_stab_options autobal_rotor_stab_options_default(void) {
  autobal_rotor_stab_options o;
  memset(&o, 0, sizeof o);
  o.method = AUTOBAL_ROTOR_STAB_AUTO;
  o.tol = 1e-9;
  o.floquet_rtol = 1e-11;
  o.floquet_atol = 1e-13;
  return o;
}

void autobal_rotor_stab_free(autobal_rotor_stab *s) {
  if (s == NULL) return;
  autobal_poly_workspace_free(s->pw);
  autobal_eigen_workspace_free(s->ew_closed);
  autobal_eigen_workspace_free(s->ew_full);
  if (s->lu_closed) gsl_matrix_free(s->lu_closed);
  if (s->perm_closed) gsl_permutation_free(s->perm_closed);
  if (s->lu_full) gsl_matrix_free(s->lu_full);
  if (s->perm_full) gsl_permutation_free(s->perm_full);
  if (s->vec_full) gsl_vector_free(s->vec_full);
  autobal_transient_free(s->tr);
  free(s->store);
  free(s);
}

const char *autobal_rotor_stab_errmsg(const autobal_rotor_stab *s) {
  return s ? s->err.message : "rotor stability handle is NULL";
}

static int check_options(const autobal_rotor_stab_options *o, const autobal_rotor_params *p,
                         autobal_error *err) {
  int st;
  size_t j;
  if (o->method < AUTOBAL_ROTOR_STAB_AUTO || o->method > AUTOBAL_ROTOR_STAB_FLOQUET)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option method = %d is not valid: 0 auto, 1 poly, 2 closed, 3 full, 4 floquet",
                             o->method);
  if ((st = autobal_check_param(err, "tol", o->tol, 0.0, 1, 1e-2, 0, "")) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_check_param(err, "floquet_rtol", o->floquet_rtol, 0.0, 1, 1e-3, 0, "")) !=
      AUTOBAL_SUCCESS)
    return st;
  if ((st = autobal_check_param(err, "floquet_atol", o->floquet_atol, 0.0, 1, 1e-3, 0, "")) !=
      AUTOBAL_SUCCESS)
    return st;
  for (j = 0; j < p->n_planes; j++) {
    const autobal_rotor_member *m = &o->member[j];
    if (m->kind < AUTOBAL_ROTOR_MEMBER_DEFAULT || m->kind > AUTOBAL_ROTOR_MEMBER_GIVEN)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "option member[%zu].kind = %d is not valid (0 default, 1 symmetric, 2 "
                               "free, 3 given)",
                               j, m->kind);
    if ((m->kind == AUTOBAL_ROTOR_MEMBER_FREE || m->kind == AUTOBAL_ROTOR_MEMBER_GIVEN)) {
      size_t need = m->kind == AUTOBAL_ROTOR_MEMBER_GIVEN
                        ? p->plane[j].n_balls
                        : (p->plane[j].n_balls >= 2 ? p->plane[j].n_balls - 2 : 0);
      if (m->n_angles != need || (need > 0 && m->angles == NULL))
        return autobal_error_set(err, AUTOBAL_EINVAL,
                                 "option member[%zu]: %zu angles given, the %s member of a plane "
                                 "with %zu balls needs %zu",
                                 j, m->n_angles,
                                 m->kind == AUTOBAL_ROTOR_MEMBER_GIVEN ? "'given'" : "'free'",
                                 p->plane[j].n_balls, need);
    }
  }
  return AUTOBAL_SUCCESS;
}

autobal_rotor_stab *autobal_rotor_stab_alloc(const autobal_rotor_params *p,
                                             const autobal_rotor_stab_options *opt,
                                             autobal_error *err) {
  autobal_rotor_stab *s;
  autobal_rotor_stab_options o = opt ? *opt : autobal_rotor_stab_options_default();
  size_t j, i, N = 0, nmem = 0, nstore;
  int st;
  autobal_error e;
  autobal_error_clear(&e);
  st = autobal_rotor_params_check(p, &e);
  if (st < 0) {
    if (err) *err = e;
    return NULL;
  }
  if ((st = check_options(&o, p, err)) != AUTOBAL_SUCCESS) return NULL;
  for (j = 0; j < p->n_planes; j++) {
    N += p->plane[j].n_balls;
    nmem += p->plane[j].n_balls;
  }
  s = (autobal_rotor_stab *)calloc(1, sizeof *s);
  if (s == NULL) {
    autobal_error_set(err, AUTOBAL_ENOMEM, "rotor stability: out of memory");
    return NULL;
  }
  s->N = N;
  s->n_planes = p->n_planes;
  s->ns = 8 + 2 * N;
  s->nm = 4 + N;
  s->opt = o;
  s->cur = *p;
  s->cur.axial = 0;
  s->c_scale = 1.0;
  s->h_scale = 1.0;
  if (p->input == AUTOBAL_ROTOR_HARDWARE)
    (void)autobal_rotor_lumped_from_hardware(&p->hw, &s->Lbase, NULL);
  else
    s->Lbase = p->lumped;
  s->L = s->Lbase;
  nstore = 8 * N + nmem + 1;
  if (N <= MAX_FULL_BALLS) nstore += 7 * s->ns * s->ns + 9 * s->ns + 2 * s->nm * s->nm;
  s->store = (double *)calloc(nstore, sizeof(double));
  if (s->store == NULL) goto nomem;
  s->m = s->store;
  s->r = s->m + N;
  s->h = s->r + N;
  s->psi_init = s->h + N;
  s->rate_init = s->psi_init + N;
  s->psi = s->rate_init + N;
  s->member_store = s->psi + N;
  s->m_save = s->member_store + nmem;
  s->h_save = s->m_save + N;
  {
    double *q = s->h_save + N;
    size_t o2 = 0;
    for (j = 0; j < p->n_planes; j++) {
      const autobal_rotor_plane *pl = &p->plane[j];
      s->off[j] = o2;
      s->cnt[j] = pl->n_balls;
      for (i = 0; i < pl->n_balls; i++) {
        s->m[o2 + i] = pl->ball_mass[i];
        s->r[o2 + i] = pl->ball_radius[i];
        s->h[o2 + i] = pl->ball_damping[i];
        s->psi_init[o2 + i] = pl->ball_psi ? pl->ball_psi[i] : 0.0;
        s->rate_init[o2 + i] = pl->ball_rate ? pl->ball_rate[i] : 0.0;
      }
      s->cur.plane[j].ball_mass = s->m + o2;
      s->cur.plane[j].ball_radius = s->r + o2;
      s->cur.plane[j].ball_damping = s->h + o2;
      s->cur.plane[j].ball_psi = s->psi_init + o2;
      s->cur.plane[j].ball_rate = s->rate_init + o2;
      /* member angles: copied; DEFAULT with n >= 3 unequal balls becomes FREE with the first
       * n - 2 angles of the default member at these parameters */
      {
        autobal_rotor_member *mb = &s->opt.member[j];
        double *dst = s->member_store + o2;
        if (mb->kind == AUTOBAL_ROTOR_MEMBER_FREE || mb->kind == AUTOBAL_ROTOR_MEMBER_GIVEN) {
          for (i = 0; i < mb->n_angles; i++) dst[i] = mb->angles[i];
          mb->angles = dst;
        } else if (mb->kind == AUTOBAL_ROTOR_MEMBER_DEFAULT && pl->n_balls >= 3) {
          int identical = 1;
          for (i = 1; i < pl->n_balls; i++)
            if (!close_rel(pl->ball_mass[i] * pl->ball_radius[i],
                           pl->ball_mass[0] * pl->ball_radius[0], 1e-12))
              identical = 0;
          if (!identical &&
              autobal_rotor_member_angles(&s->cur.plane[j], NULL, dst, pl->n_balls, NULL) ==
                  AUTOBAL_SUCCESS) {
            mb->kind = AUTOBAL_ROTOR_MEMBER_FREE;
            mb->n_angles = pl->n_balls - 2;
            mb->angles = dst;
          } else {
            mb->angles = NULL;
            mb->n_angles = 0;
          }
        } else {
          mb->angles = NULL;
          mb->n_angles = 0;
        }
      }
      o2 += pl->n_balls;
    }
    for (; j < AUTOBAL_ROTOR_MAX_PLANES; j++) memset(&s->opt.member[j], 0, sizeof s->opt.member[j]);
    if (N <= MAX_FULL_BALLS) {
      const size_t ns = s->ns, nm = s->nm;
      s->Afull = q;
      q += ns * ns;
      s->Ascaled = q;
      q += ns * ns;
      s->phi = q;
      q += 5 * ns * ns; /* phi and scratch for products */
      s->sc = q;
      q += ns;
      s->full_re = q;
      q += ns;
      s->full_im = q;
      q += ns;
      s->mu_re = q;
      q += ns;
      s->mu_im = q;
      q += ns;
      s->tmp_re = q;
      q += ns;
      s->tmp_im = q;
      q += ns;
      q += 2 * ns;
      s->Kt = q;
      q += nm * nm;
      s->Ct = q;
    }
  }
  s->pw = autobal_poly_workspace_alloc(AUTOBAL_ROTOR_POLY_LEN - 1);
  s->ew_closed = autobal_eigen_workspace_alloc(8 + 4 * s->n_planes);
  s->lu_closed = gsl_matrix_alloc(4 + 2 * s->n_planes, 4 + 2 * s->n_planes);
  s->perm_closed = gsl_permutation_alloc(4 + 2 * s->n_planes);
  if (!s->pw || !s->ew_closed || !s->lu_closed || !s->perm_closed) goto nomem;
  if (N <= MAX_FULL_BALLS) {
    autobal_transient_options to = autobal_transient_options_default();
    to.rtol = o.floquet_rtol;
    to.atol = o.floquet_atol;
    to.max_steps = 10000000UL;
    s->ew_full = autobal_eigen_workspace_alloc(s->ns);
    s->lu_full = gsl_matrix_alloc(s->nm, s->nm);
    s->perm_full = gsl_permutation_alloc(s->nm);
    s->vec_full = gsl_vector_alloc(s->nm);
    s->tr = autobal_transient_alloc(s->ns * s->ns, &to, NULL);
    if (!s->ew_full || !s->lu_full || !s->perm_full || !s->vec_full || !s->tr) goto nomem;
  }
  s->psi_status = AUTOBAL_EINVAL;
  autobal_error_clear(&s->err);
  if (err) *err = e; /* success or the warning of autobal_rotor_params_check */
  return s;
nomem:
  autobal_rotor_stab_free(s);
  autobal_error_set(err, AUTOBAL_ENOMEM, "rotor stability: out of memory");
  return NULL;
}

const autobal_rotor_params *autobal_rotor_stab_params(const autobal_rotor_stab *s) {
  return s ? &s->cur : NULL;
}
size_t autobal_rotor_stab_n_balls(const autobal_rotor_stab *s) { return s ? s->N : 0; }

static void scale_lumped(autobal_rotor_stab *s) {
  const autobal_rotor_lumped *B = &s->Lbase;
  autobal_rotor_lumped *L = &s->L;
  const double f = s->c_scale, g = s->h_scale;
  L->c_x = f * B->c_x;
  L->c_y = f * B->c_y;
  L->c_z = f * B->c_z;
  L->c_alpha = f * B->c_alpha;
  L->c_beta = f * B->c_beta;
  L->c_xbeta = f * B->c_xbeta;
  L->c_yalpha = f * B->c_yalpha;
  L->h_x = g * B->h_x;
  L->h_y = g * B->h_y;
  L->h_z = g * B->h_z;
  L->h_alpha = g * B->h_alpha;
  L->h_beta = g * B->h_beta;
  L->h_xbeta = g * B->h_xbeta;
  L->h_yalpha = g * B->h_yalpha;
  /* keep the working parameters consistent (lumped input with the scaled set) */
  s->cur.input = AUTOBAL_ROTOR_LUMPED;
  s->cur.lumped = *L;
}

int autobal_rotor_stab_set(autobal_rotor_stab *s, int param, double value) {
  int st;
  size_t i, j;
  if (s == NULL) return AUTOBAL_EINVAL;
  switch (param) {
    case AUTOBAL_ROTOR_PARAM_OMEGA:
      if ((st = autobal_check_param(&s->err, "omega", value, -INFINITY, 1, INFINITY, 1, "rad/s")))
        return st;
      s->cur.omega = value;
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_BALL_DAMPING:
      if ((st = autobal_check_param(&s->err, "ball_damping", value, 0.0, 0, INFINITY, 1, "kg/s")))
        return st;
      for (i = 0; i < s->N; i++) s->h[i] = value;
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_BALL_MASS:
      if ((st = autobal_check_param(&s->err, "ball_mass", value, 0.0, 1, INFINITY, 1, "kg")))
        return st;
      for (i = 0; i < s->N; i++) s->m[i] = value;
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_STIFFNESS_SCALE:
      if ((st = autobal_check_param(&s->err, "stiffness_scale", value, 0.0, 1, INFINITY, 1, "")))
        return st;
      s->c_scale = value;
      scale_lumped(s);
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_DAMPING_SCALE:
      if ((st = autobal_check_param(&s->err, "damping_scale", value, 0.0, 0, INFINITY, 1, "")))
        return st;
      s->h_scale = value;
      scale_lumped(s);
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS:
      if ((st = autobal_check_param(&s->err, "unbalance_mass", value, 0.0, 0, INFINITY, 1, "kg")))
        return st;
      for (j = 0; j < s->n_planes; j++) s->cur.plane[j].m0 = value;
      return AUTOBAL_SUCCESS;
    default:
      return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                               "parameter id %d is not valid (0 omega .. 5 unbalance_mass)", param);
  }
}

double autobal_rotor_stab_get(const autobal_rotor_stab *s, int param) {
  if (s == NULL) return NAN;
  switch (param) {
    case AUTOBAL_ROTOR_PARAM_OMEGA: return s->cur.omega;
    case AUTOBAL_ROTOR_PARAM_BALL_DAMPING: return s->N ? s->h[0] : NAN;
    case AUTOBAL_ROTOR_PARAM_BALL_MASS: return s->N ? s->m[0] : NAN;
    case AUTOBAL_ROTOR_PARAM_STIFFNESS_SCALE: return s->c_scale;
    case AUTOBAL_ROTOR_PARAM_DAMPING_SCALE: return s->h_scale;
    case AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS: return s->cur.plane[0].m0;
    default: return NAN;
  }
}

int autobal_rotor_stab_update_member_(autobal_rotor_stab *s) {
  size_t j;
  int st = AUTOBAL_SUCCESS;
  for (j = 0; j < s->n_planes && st == AUTOBAL_SUCCESS; j++) {
    st = autobal_rotor_member_angles(&s->cur.plane[j], &s->opt.member[j], s->psi + s->off[j],
                                     s->cnt[j], &s->err);
    if (st != AUTOBAL_SUCCESS) {
      char tmp[AUTOBAL_ERRMSG_SIZE];
      snprintf(tmp, sizeof tmp, "%s", s->err.message);
      autobal_error_set(&s->err, st, "plane %zu: %.480s", j + 1, tmp);
    }
  }
  s->psi_status = st;
  return st;
}

size_t autobal_rotor_stab_family_(const autobal_rotor_stab *s) {
  size_t j, f = 0;
  for (j = 0; j < s->n_planes; j++)
    f += s->cnt[j] - plane_rank(s->m + s->off[j], s->r + s->off[j], s->psi + s->off[j], s->cnt[j]);
  return f;
}

int autobal_rotor_stab_balanced_angles(autobal_rotor_stab *s, double *psi, size_t n) {
  int st;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (n != s->N || (n > 0 && psi == NULL))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "balanced angles: n = %zu, need N = %zu", n,
                             s->N);
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) return st;
  if (n) memcpy(psi, s->psi, n * sizeof *psi);
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_stab_closed(autobal_rotor_stab *s, autobal_rotor_closed *c) {
  int st;
  if (s == NULL || c == NULL) return AUTOBAL_EINVAL;
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) return st;
  closed_from_handle(s, c);
  return AUTOBAL_SUCCESS;
}

/* ---- margins ------------------------------------------------------------------------ */

/* Roots of Delta in 1/s: the polynomial is solved in s = lambda / ws (see the header). */
static int poly_roots(autobal_rotor_stab *s, const double *coef, double *re, double *im,
                      double *ws_out) {
  double cs[AUTOBAL_ROTOR_POLY_LEN], ws, big = 0.0, pw = 1.0;
  size_t k;
  int st;
  if (coef[0] != 0.0 && coef[12] != 0.0) ws = pow(fabs(coef[0] / coef[12]), 1.0 / 12.0);
  else ws = fmax(1.0, fabs(s->cur.omega));
  for (k = 0; k < AUTOBAL_ROTOR_POLY_LEN; k++) {
    cs[k] = coef[k] * pw;
    pw *= ws;
    big = fmax(big, fabs(cs[k]));
  }
  for (k = 0; k < AUTOBAL_ROTOR_POLY_LEN; k++) cs[k] /= big;
  st = autobal_poly_roots(s->pw, cs, AUTOBAL_ROTOR_POLY_LEN, re, im, &s->err);
  if (st != AUTOBAL_SUCCESS) return st;
  for (k = 0; k < AUTOBAL_ROTOR_POLY_LEN - 1; k++) {
    re[k] *= ws;
    im[k] *= ws;
  }
  if (ws_out) *ws_out = ws;
  return AUTOBAL_SUCCESS;
}

/* Margin over n roots excluding `family` roots closest to `center` (0 for roots); the
 * verdict with the handle's tolerance. */
static void roots_margin(const autobal_rotor_stab *s, size_t n, const double *re, const double *im,
                         size_t family, double *margin, int *verdict) {
  double mx = -INFINITY, scale = 1.0;
  size_t i, k;
  unsigned char excl[AUTOBAL_ROTOR_CLOSED_MAX + 2 * MAX_FULL_BALLS + 8];
  memset(excl, 0, sizeof excl);
  for (k = 0; k < family && k < n; k++) {
    size_t best = n;
    double bd = INFINITY;
    for (i = 0; i < n; i++)
      if (!excl[i] && hypot(re[i], im[i]) < bd) {
        bd = hypot(re[i], im[i]);
        best = i;
      }
    if (best < n) excl[best] = 1;
  }
  for (i = 0; i < n; i++) {
    scale = fmax(scale, hypot(re[i], im[i]));
    if (!excl[i] && re[i] > mx) mx = re[i];
  }
  *margin = mx;
  if (mx > s->opt.tol * scale) *verdict = AUTOBAL_VERDICT_UNSTABLE;
  else if (mx < -s->opt.tol * scale) *verdict = AUTOBAL_VERDICT_STABLE;
  else *verdict = AUTOBAL_VERDICT_MARGINAL;
}

static int resolve_method(const autobal_rotor_stab *s, const autobal_rotor_closed *c, int method) {
  if (method == AUTOBAL_ROTOR_STAB_AUTO) method = s->opt.method;
  if (method != AUTOBAL_ROTOR_STAB_AUTO) return method;
  if (c->isotropic && c->closure_ok)
    return c->n_planes == 1 ? AUTOBAL_ROTOR_STAB_POLY : AUTOBAL_ROTOR_STAB_CLOSED;
  if (c->isotropic) return AUTOBAL_ROTOR_STAB_FULL;
  return AUTOBAL_ROTOR_STAB_FLOQUET;
}

static int method_applies(autobal_rotor_stab *s, const autobal_rotor_closed *c, int method) {
  switch (method) {
    case AUTOBAL_ROTOR_STAB_POLY:
      if (c->n_planes != 1 || !c->isotropic || !c->closure_ok)
        return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                                 "method 'poly' needs one plane, isotropic supports, a common h_i/m_i "
                                 "and balls not all on one line (closure of (3.16))");
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_STAB_CLOSED:
      if (!c->isotropic || !c->closure_ok)
        return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                                 "method 'closed' needs isotropic supports, a common h_i/m_i per "
                                 "plane and balls not all on one line");
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_STAB_FULL:
      if (!c->isotropic)
        return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                                 "method 'full' needs isotropic supports (use 'floquet')");
      /* fall through */
    case AUTOBAL_ROTOR_STAB_FLOQUET:
      if (s->tr == NULL)
        return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                                 "methods 'full' and 'floquet' are limited to %d balls (N = %zu)",
                                 MAX_FULL_BALLS, s->N);
      return AUTOBAL_SUCCESS;
    default:
      return autobal_error_set(&s->err, AUTOBAL_EINVAL, "method %d is not valid", method);
  }
}

int autobal_rotor_stab_margin(autobal_rotor_stab *s, int method, double *margin, int *verdict) {
  autobal_rotor_closed c;
  double re[AUTOBAL_ROTOR_CLOSED_MAX], im[AUTOBAL_ROTOR_CLOSED_MAX];
  int st, m;
  if (s == NULL || margin == NULL || verdict == NULL) return AUTOBAL_EINVAL;
  *margin = NAN;
  *verdict = AUTOBAL_ROTOR_VERDICT_NONE;
  if (!(s->cur.omega != 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "the stability of a balanced motion needs omega != 0");
  if (autobal_rotor_stab_update_member_(s) != AUTOBAL_SUCCESS) return AUTOBAL_SUCCESS;
  closed_from_handle(s, &c);
  m = resolve_method(s, &c, method);
  if ((st = method_applies(s, &c, m)) != AUTOBAL_SUCCESS) return st;
  switch (m) {
    case AUTOBAL_ROTOR_STAB_POLY: {
      double coef[AUTOBAL_ROTOR_POLY_LEN];
      if ((st = autobal_rotor_char_poly(&c, coef, NULL, &s->err)) != AUTOBAL_SUCCESS) return st;
      if ((st = poly_roots(s, coef, re, im, NULL)) != AUTOBAL_SUCCESS) return st;
      roots_margin(s, AUTOBAL_ROTOR_POLY_LEN - 1, re, im, 0, margin, verdict);
      return AUTOBAL_SUCCESS;
    }
    case AUTOBAL_ROTOR_STAB_CLOSED: {
      const size_t dim = autobal_rotor_closed_dim(&c);
      if ((st = closed_matrix_ws(&c, s->closed_mat, dim, s->lu_closed, s->perm_closed, &s->err)))
        return st;
      if ((st = autobal_eigen_nonsymm(s->ew_closed, s->closed_mat, re, im, &s->err))) return st;
      roots_margin(s, dim, re, im, 0, margin, verdict);
      return AUTOBAL_SUCCESS;
    }
    case AUTOBAL_ROTOR_STAB_FULL:
      if ((st = autobal_rotor_stab_lin_(s, 0.0, 1)) != AUTOBAL_SUCCESS) return st;
      if ((st = autobal_eigen_nonsymm(s->ew_full, s->Afull, s->full_re, s->full_im, &s->err)))
        return st;
      roots_margin(s, s->ns, s->full_re, s->full_im, autobal_rotor_stab_family_(s), margin,
                   verdict);
      return AUTOBAL_SUCCESS;
    default: { /* FLOQUET */
      const double T = 2.0 * M_PI / fabs(s->cur.omega);
      const double band = fmax(s->opt.tol, 10.0 * s->opt.floquet_rtol) / T;
      if ((st = autobal_rotor_stab_floquet_(s, NULL)) != AUTOBAL_SUCCESS) return st;
      *margin = autobal_rotor_stab_floquet_margin_(s, autobal_rotor_stab_family_(s));
      *verdict = *margin > band ? AUTOBAL_VERDICT_UNSTABLE
                                : (*margin < -band ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_MARGINAL);
      return AUTOBAL_SUCCESS;
    }
  }
}

/* ---- one point, every method ------------------------------------------------------------ */

int autobal_rotor_stab_analyze(autobal_rotor_stab *s, autobal_rotor_stab_result *res) {
  autobal_rotor_closed c;
  int st, m;
  size_t i, fam;
  double scale = 1.0;
  if (s == NULL || res == NULL) return AUTOBAL_EINVAL;
  memset(res, 0, sizeof *res);
  res->verdict = AUTOBAL_ROTOR_VERDICT_NONE;
  res->margin = res->closed_margin = res->full_margin = res->floquet_margin = NAN;
  res->full_mismatch = res->floquet_mismatch = NAN;
  res->hurwitz_verdict = AUTOBAL_VERDICT_MARGINAL;
  res->n_balls = s->N;
  res->psi = s->psi;
  if (!(s->cur.omega != 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "the stability of a balanced motion needs omega != 0");
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) return st;
  closed_from_handle(s, &c);
  fam = autobal_rotor_stab_family_(s);
  res->n_family = fam;
  res->isotropic = c.isotropic;
  res->closure_ok = c.closure_ok;
  res->period = 2.0 * M_PI / fabs(s->cur.omega);
  m = resolve_method(s, &c, AUTOBAL_ROTOR_STAB_AUTO);
  if ((st = method_applies(s, &c, m)) != AUTOBAL_SUCCESS) return st;
  res->method = m;
  /* closed system */
  if (c.isotropic && c.closure_ok) {
    const size_t dim = autobal_rotor_closed_dim(&c);
    double ere[AUTOBAL_ROTOR_CLOSED_MAX], eim[AUTOBAL_ROTOR_CLOSED_MAX];
    size_t perm[AUTOBAL_ROTOR_CLOSED_MAX];
    int v;
    res->n_closed = dim;
    if ((st = closed_matrix_ws(&c, s->closed_mat, dim, s->lu_closed, s->perm_closed, &s->err)))
      return st;
    if ((st = autobal_eigen_nonsymm(s->ew_closed, s->closed_mat, ere, eim, &s->err))) return st;
    if (c.n_planes == 1) {
      double cerr[AUTOBAL_ROTOR_POLY_LEN], cs[AUTOBAL_ROTOR_POLY_LEN], es[AUTOBAL_ROTOR_POLY_LEN];
      double ws = 1.0, pw = 1.0, dist = 0.0;
      if ((st = autobal_rotor_char_poly(&c, res->poly, cerr, &s->err))) return st;
      res->n_poly = AUTOBAL_ROTOR_POLY_LEN;
      if ((st = poly_roots(s, res->poly, res->root_re, res->root_im, &ws))) return st;
      for (i = 0; i < AUTOBAL_ROTOR_POLY_LEN; i++) {
        cs[i] = res->poly[i] * pw;
        es[i] = cerr[i] * pw;
        pw *= ws;
      }
      if ((st = autobal_poly_hurwitz_err(cs, es, AUTOBAL_ROTOR_POLY_LEN, &res->hurwitz_verdict,
                                         &res->hurwitz_n_rhp, &s->err)))
        return st;
      if ((st = autobal_match_roots(dim, res->root_re, res->root_im, ere, eim, perm, &dist,
                                    &s->err)))
        return st;
      for (i = 0; i < dim; i++) {
        res->closed_eig_re[i] = ere[perm[i]];
        res->closed_eig_im[i] = eim[perm[i]];
        scale = fmax(scale, hypot(res->root_re[i], res->root_im[i]));
      }
      res->root_eig_mismatch = dist / scale;
    } else {
      for (i = 0; i < dim; i++) {
        res->root_re[i] = res->closed_eig_re[i] = ere[i];
        res->root_im[i] = res->closed_eig_im[i] = eim[i];
      }
      res->root_eig_mismatch = 0.0;
    }
    roots_margin(s, dim, res->root_re, res->root_im, 0, &res->closed_margin, &v);
    if (m == AUTOBAL_ROTOR_STAB_POLY || m == AUTOBAL_ROTOR_STAB_CLOSED) {
      res->margin = res->closed_margin;
      res->verdict = v;
    }
  }
  if (s->tr == NULL) return AUTOBAL_SUCCESS; /* too many balls for the full model */
  /* full model in rotating coordinates (isotropic) */
  if (c.isotropic) {
    int v;
    if ((st = autobal_rotor_stab_lin_(s, 0.0, 1)) != AUTOBAL_SUCCESS) return st;
    if ((st = autobal_eigen_nonsymm(s->ew_full, s->Afull, s->full_re, s->full_im, &s->err)))
      return st;
    res->n_full = s->ns;
    res->full_re = s->full_re;
    res->full_im = s->full_im;
    roots_margin(s, s->ns, s->full_re, s->full_im, fam, &res->full_margin, &v);
    if (m == AUTOBAL_ROTOR_STAB_FULL) {
      res->margin = res->full_margin;
      res->verdict = v;
    }
    if (res->n_closed > 0 && s->ns <= AUTOBAL_MATCH_MAXN) {
      /* expected: closed roots + per plane (n-2) zeros and (n-2) roots -kappa */
      size_t k = 0, j, q;
      double dist = 0.0, sc2 = 1.0;
      for (i = 0; i < res->n_closed; i++, k++) {
        s->tmp_re[k] = res->root_re[i];
        s->tmp_im[k] = res->root_im[i];
      }
      for (j = 0; j < c.n_planes; j++)
        for (q = 0; q + 2 < c.plane[j].n_balls; q++) {
          s->tmp_re[k] = 0.0;
          s->tmp_im[k++] = 0.0;
          s->tmp_re[k] = -c.plane[j].kappa;
          s->tmp_im[k++] = 0.0;
        }
      if (k == s->ns &&
          autobal_match_roots(k, s->full_re, s->full_im, s->tmp_re, s->tmp_im, NULL, &dist, NULL) ==
              AUTOBAL_SUCCESS) {
        for (i = 0; i < k; i++) sc2 = fmax(sc2, hypot(s->tmp_re[i], s->tmp_im[i]));
        res->full_mismatch = dist / sc2;
      }
    }
  }
  /* Floquet */
  {
    const double T = res->period;
    const double band = fmax(s->opt.tol, 10.0 * s->opt.floquet_rtol) / T;
    if ((st = autobal_rotor_stab_floquet_(s, NULL)) != AUTOBAL_SUCCESS) return st;
    res->n_floquet = s->ns;
    res->mu_re = s->mu_re;
    res->mu_im = s->mu_im;
    res->floquet_margin = autobal_rotor_stab_floquet_margin_(s, fam);
    if (m == AUTOBAL_ROTOR_STAB_FLOQUET) {
      res->margin = res->floquet_margin;
      res->verdict = res->margin > band ? AUTOBAL_VERDICT_UNSTABLE
                                        : (res->margin < -band ? AUTOBAL_VERDICT_STABLE
                                                               : AUTOBAL_VERDICT_MARGINAL);
    }
    if (res->n_full > 0 && s->ns <= AUTOBAL_MATCH_MAXN) {
      double dist = 0.0;
      for (i = 0; i < s->ns; i++) {
        const double mag = exp(s->full_re[i] * T);
        s->tmp_re[i] = mag * cos(s->full_im[i] * T);
        s->tmp_im[i] = mag * sin(s->full_im[i] * T);
      }
      if (autobal_match_roots(s->ns, s->mu_re, s->mu_im, s->tmp_re, s->tmp_im, NULL, &dist, NULL) ==
          AUTOBAL_SUCCESS)
        res->floquet_mismatch = dist;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* ---- sweeps and critical values ------------------------------------------------------- */

/* Everything autobal_rotor_stab_set can change (any parameter id): the working parameters
 * (omega, input and lumped set, every plane's m0; the ball arrays hold the same pointers),
 * the current lumped set and scale factors, and every ball's mass and damping (into the
 * handle's m_save / h_save, sized at alloc).  A sweep or critical search saves them first
 * and puts them back bitwise afterwards, also after a failure. */
typedef struct stab_saved {
  autobal_rotor_params cur;
  autobal_rotor_lumped L;
  double c_scale, h_scale;
} stab_saved;

static void stab_save(autobal_rotor_stab *s, stab_saved *sv) {
  sv->cur = s->cur;
  sv->L = s->L;
  sv->c_scale = s->c_scale;
  sv->h_scale = s->h_scale;
  if (s->N > 0) {
    memcpy(s->m_save, s->m, s->N * sizeof *s->m);
    memcpy(s->h_save, s->h, s->N * sizeof *s->h);
  }
}

static void stab_restore(autobal_rotor_stab *s, const stab_saved *sv) {
  s->cur = sv->cur;
  s->L = sv->L;
  s->c_scale = sv->c_scale;
  s->h_scale = sv->h_scale;
  if (s->N > 0) {
    memcpy(s->m, s->m_save, s->N * sizeof *s->m);
    memcpy(s->h, s->h_save, s->N * sizeof *s->h);
  }
}

int autobal_rotor_stab_sweep(autobal_rotor_stab *s, int param, const double *values, size_t n,
                             double *margin, int *verdict) {
  stab_saved sv;
  size_t k;
  int st = AUTOBAL_SUCCESS;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (values == NULL || margin == NULL || verdict == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "sweep: NULL array");
  if (autobal_rotor_stab_param_name(param) == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "sweep: parameter id %d is not valid", param);
  stab_save(s, &sv);
  for (k = 0; k < n; k++) {
    if ((st = autobal_rotor_stab_set(s, param, values[k])) != AUTOBAL_SUCCESS) break;
    if ((st = autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_AUTO, &margin[k], &verdict[k])) !=
        AUTOBAL_SUCCESS)
      break;
  }
  stab_restore(s, &sv);
  return st;
}

typedef struct crit_ctx {
  autobal_rotor_stab *s;
  int param;
  size_t evals;
  int status;
} crit_ctx;

static int crit_margin(double x, void *ctx, double *fx) {
  crit_ctx *c = (crit_ctx *)ctx;
  int v, st;
  c->evals++;
  if ((st = autobal_rotor_stab_set(c->s, c->param, x)) != AUTOBAL_SUCCESS) return st;
  st = autobal_rotor_stab_margin(c->s, AUTOBAL_ROTOR_STAB_AUTO, fx, &v);
  if (st == AUTOBAL_SUCCESS && v == AUTOBAL_ROTOR_VERDICT_NONE) return AUTOBAL_EINVAL;
  return st;
}

static int crit_exists(double x, void *ctx, int *value) {
  crit_ctx *c = (crit_ctx *)ctx;
  double mg;
  int v, st;
  c->evals++;
  if ((st = autobal_rotor_stab_set(c->s, c->param, x)) != AUTOBAL_SUCCESS) return st;
  st = autobal_rotor_stab_margin(c->s, AUTOBAL_ROTOR_STAB_AUTO, &mg, &v);
  *value = v != AUTOBAL_ROTOR_VERDICT_NONE;
  return st;
}

/* sign class of a margin: +1 stable side (< 0), -1 unstable side (>= 0), 0 none */
static int side_of(double margin) { return isnan(margin) ? 0 : (margin < 0.0 ? 1 : -1); }

/* The scan of autobal_rotor_stab_critical with at most `cap` critical values (arguments
 * checked by the caller, *out zeroed, the parameters saved and restored by the caller). */
static int critical_scan(autobal_rotor_stab *s, int param, double lo, double hi, size_t n_grid,
                         double xtol_rel, size_t cap, autobal_rotor_crit *out) {
  crit_ctx cc;
  double prev_x = lo, start = NAN;
  size_t k;
  int st = AUTOBAL_SUCCESS, prev_side = 0, in_stable = 0;
  cc.s = s;
  cc.param = param;
  cc.evals = 0;
  cc.status = 0;
  for (k = 0; k < n_grid; k++) {
    const double x = k + 1 == n_grid ? hi : lo + (hi - lo) * (double)k / (double)(n_grid - 1);
    double mg;
    int v, side;
    cc.evals++;
    if ((st = autobal_rotor_stab_set(s, param, x)) != AUTOBAL_SUCCESS) break;
    if ((st = autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_AUTO, &mg, &v)) != AUTOBAL_SUCCESS)
      break;
    side = side_of(mg);
    if (k == 0) {
      if (side == 1) {
        in_stable = 1;
        start = lo;
      }
    } else if (side != prev_side) {
      double xc = NAN;
      int kind;
      if (out->n >= cap) {
        /* one change more than the list holds: stop here, before refining it.  The
         * results cover [lo, value[n-1]]: an open stable interval (it began at the last
         * recorded change) is not reported, nothing beyond it is claimed. */
        out->truncated = 1;
        break;
      }
      if (side != 0 && prev_side != 0) {
        /* margin changes sign: Brent on the margin */
        st = autobal_root_brent(crit_margin, &cc, prev_x, x, 0.0, xtol_rel, 200, &xc, &s->err);
        if (st == AUTOBAL_EINVAL && !isfinite(xc)) xc = 0.5 * (prev_x + x);
        if (st == AUTOBAL_ENUMERIC || st == AUTOBAL_EINVAL) st = AUTOBAL_SUCCESS; /* best estimate */
        kind = side == 1 ? 1 : -1;
      } else {
        double blo = prev_x, bhi = x;
        st = autobal_bisect_change(crit_exists, &cc, prev_x, x, 0.0, xtol_rel, &blo, &bhi, &s->err);
        xc = 0.5 * (blo + bhi);
        kind = 0;
      }
      if (st != AUTOBAL_SUCCESS) break;
      out->value[out->n] = xc;
      out->kind[out->n] = kind;
      out->n++;
      if (in_stable && side != 1) {
        /* at most n/2 + 1 <= AUTOBAL_ROTOR_MAX_CRIT closed intervals: never full */
        if (out->n_stable < AUTOBAL_ROTOR_MAX_CRIT) {
          out->stable_lo[out->n_stable] = start;
          out->stable_hi[out->n_stable] = xc;
          out->n_stable++;
        }
        in_stable = 0;
      } else if (!in_stable && side == 1) {
        in_stable = 1;
        start = xc;
      }
    }
    prev_side = side;
    prev_x = x;
  }
  if (st == AUTOBAL_SUCCESS && in_stable && !out->truncated &&
      out->n_stable < AUTOBAL_ROTOR_MAX_CRIT) {
    out->stable_lo[out->n_stable] = start;
    out->stable_hi[out->n_stable] = hi;
    out->n_stable++;
  }
  out->evaluations = cc.evals;
  if (st == AUTOBAL_SUCCESS && out->truncated)
    st = autobal_error_set(&s->err, AUTOBAL_WARNING,
                           "critical: more than %zu verdict changes of %s in [%.9g, %.9g] (the "
                           "capacity of the list): the first %zu are kept and the search stopped "
                           "at the next one; the results cover [%.9g, %.12g] only (up to the last "
                           "kept change). Narrow the range (e.g. an upper end <= %.12g) or split it",
                           cap, autobal_rotor_stab_param_name(param), lo, hi, out->n, lo,
                           out->value[out->n - 1], out->value[out->n - 1]);
  return st;
}

static int critical_checked(autobal_rotor_stab *s, int param, double lo, double hi, size_t n_grid,
                            double xtol_rel, size_t cap, autobal_rotor_crit *out) {
  stab_saved sv;
  int st;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: NULL output");
  memset(out, 0, sizeof *out);
  out->param = param;
  if (autobal_rotor_stab_param_name(param) == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: parameter id %d is not valid", param);
  if (!(isfinite(lo) && isfinite(hi) && lo < hi))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "critical: need finite lo < hi, got [%g, %g]", lo, hi);
  if (param == AUTOBAL_ROTOR_PARAM_OMEGA && !(lo > 0.0 || hi < 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "critical: the omega range [%g, %g] must not contain 0", lo, hi);
  if (n_grid < 2 || n_grid > 100000000)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: n_grid = %zu out of range [2, 1e8]",
                             n_grid);
  if (!(xtol_rel > 0.0 && xtol_rel < 0.1))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: xtol_rel = %g out of range (0, 0.1)",
                             xtol_rel);
  if (cap < 1 || cap > AUTOBAL_ROTOR_MAX_CRIT)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: capacity %zu out of range [1, %d]",
                             cap, AUTOBAL_ROTOR_MAX_CRIT);
  stab_save(s, &sv);
  st = critical_scan(s, param, lo, hi, n_grid, xtol_rel, cap, out);
  stab_restore(s, &sv);
  return st;
}

int autobal_rotor_stab_critical(autobal_rotor_stab *s, int param, double lo, double hi,
                                size_t n_grid, double xtol_rel, autobal_rotor_crit *out) {
  return critical_checked(s, param, lo, hi, n_grid, xtol_rel, AUTOBAL_ROTOR_MAX_CRIT, out);
}

int autobal_rotor_stab_critical_cap_(autobal_rotor_stab *s, int param, double lo, double hi,
                                     size_t n_grid, double xtol_rel, size_t cap,
                                     autobal_rotor_crit *out) {
  return critical_checked(s, param, lo, hi, n_grid, xtol_rel, cap, out);
}

/* ---- maps ---------------------------------------------------------------------------- */

static int map_point(autobal_rotor_stab *s, int p1, double x1, int p2, double x2, double *mg,
                     int *v) {
  int st;
  *mg = NAN;
  *v = AUTOBAL_ROTOR_VERDICT_NONE;
  if ((st = autobal_rotor_stab_set(s, p1, x1)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_set(s, p2, x2)) != AUTOBAL_SUCCESS) return st;
  return autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_AUTO, mg, v);
}

int autobal_rotor_stab_map(const autobal_rotor_params *p, const autobal_rotor_stab_options *opt,
                           int param1, const double *v1, size_t n1, int param2, const double *v2,
                           size_t n2, int n_threads, double *margin, int *verdict,
                           autobal_error *err) {
  size_t ntot;
  int fail = AUTOBAL_SUCCESS;
  char failmsg[AUTOBAL_ERRMSG_SIZE];
  autobal_rotor_stab *probe;
  failmsg[0] = '\0';
  if (autobal_rotor_stab_param_name(param1) == NULL || autobal_rotor_stab_param_name(param2) == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: parameter ids %d, %d: not valid", param1,
                             param2);
  if (param1 == param2)
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: the two parameters must differ (both %s)",
                             autobal_rotor_stab_param_name(param1));
  if ((n1 > 0 && v1 == NULL) || (n2 > 0 && v2 == NULL) || margin == NULL || verdict == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: NULL array");
  if (n_threads < 0) n_threads = 0;
  /* validate once (and report parameter/option errors before going parallel) */
  probe = autobal_rotor_stab_alloc(p, opt, err);
  if (probe == NULL) return err ? err->status : AUTOBAL_EINVAL;
  autobal_rotor_stab_free(probe);
  ntot = n1 * n2;
  if (ntot == 0) return AUTOBAL_SUCCESS;
#ifdef AUTOBAL_HAVE_OPENMP
  {
    int nth = n_threads > 0 ? n_threads : omp_get_max_threads();
#pragma omp parallel num_threads(nth)
    {
      autobal_rotor_stab *s = autobal_rotor_stab_alloc(p, opt, NULL);
      int local = s ? AUTOBAL_SUCCESS : AUTOBAL_ENOMEM;
      char msg[AUTOBAL_ERRMSG_SIZE];
      long long idx;
      msg[0] = '\0';
#pragma omp for schedule(dynamic, 8)
      for (idx = 0; idx < (long long)ntot; idx++) {
        const size_t i = (size_t)idx / n2, j = (size_t)idx % n2;
        if (local != AUTOBAL_SUCCESS) continue;
        local = map_point(s, param1, v1[i], param2, v2[j], &margin[idx], &verdict[idx]);
        if (local != AUTOBAL_SUCCESS)
          snprintf(msg, sizeof msg, "map point (%s = %.9g, %s = %.9g): %.400s",
                   autobal_rotor_stab_param_name(param1), v1[i],
                   autobal_rotor_stab_param_name(param2), v2[j], s->err.message);
      }
      if (local != AUTOBAL_SUCCESS) {
#pragma omp critical(autobal_rotor_stab_map_fail)
        {
          if (fail == AUTOBAL_SUCCESS) {
            fail = local;
            snprintf(failmsg, sizeof failmsg, "%s", msg[0] ? msg : "out of memory");
          }
        }
      }
      autobal_rotor_stab_free(s);
    }
  }
#else
  {
    autobal_rotor_stab *s = autobal_rotor_stab_alloc(p, opt, NULL);
    size_t idx;
    (void)n_threads;
    if (s == NULL) fail = AUTOBAL_ENOMEM;
    for (idx = 0; idx < ntot && fail == AUTOBAL_SUCCESS; idx++) {
      const size_t i = idx / n2, j = idx % n2;
      fail = map_point(s, param1, v1[i], param2, v2[j], &margin[idx], &verdict[idx]);
      if (fail != AUTOBAL_SUCCESS)
        snprintf(failmsg, sizeof failmsg, "map point (%s = %.9g, %s = %.9g): %.400s",
                 autobal_rotor_stab_param_name(param1), v1[i],
                 autobal_rotor_stab_param_name(param2), v2[j], s->err.message);
    }
    autobal_rotor_stab_free(s);
  }
#endif
  if (fail != AUTOBAL_SUCCESS) return autobal_error_set(err, fail, "%s", failmsg);
  return AUTOBAL_SUCCESS;
}
