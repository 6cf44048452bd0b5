/* rotor_unbalance2.c: stability of the balanced motion of TWO balancer planes (two balls each,
 * isotropic supports, the paper's inertia) for every relative phase of the two unbalances, and over a
 * grid of their magnitudes (docs/rotor.md "Every unbalance", "Two planes").
 *
 * In the rotating frame (docs/rotor.md (3.16)) with sigma_j eliminated (L_j = lambda^2 + kappa_j lambda,
 * rows multiplied by L_1 L_2) the closed system in (W, Theta, W~, Theta~) (W~ the conjugate variable) is
 *     [ G   H ]       G = L1 L2 K - P^4 sum_j Lo_j (m_bj / 2) e_j e_j^T,   e_j = (1, d_j),
 *     [ H~  G*]       H = (lambda^2 + w^2)^2 sum_j Lo_j (Q_j / 2) e_j e_j^T  (Lo_j = L of the other plane),
 * H~ the same with conj(Q_j), G* with conjugated coefficients; its determinant is (L1 L2)^2 Delta16.
 * Q_j enters only the rows of W, Theta through H, conj(Q_j) only those of W~, Theta~ through H~; the
 * determinant is a polynomial in (Q_1, Q_2, conj Q_1, conj Q_2) taken as independent, and the common
 * rotation Q_j -> Q_j e^{2 i phi} leaves it invariant, so only the monomials 1, |Q1|^2, |Q2|^2,
 * |Q1|^2 |Q2|^2, Q1 conj(Q2), conj(Q1) Q2 remain (a sum of rank-one updates: each q_j at most once
 * per block...): each is read off from the determinant at a few values of the four (independent)
 * scalars (det_at).  With p = e^{i arg(Q1 conj Q2)} = a + i b:
 *     Delta16 = E + p Yp + conj(p) Ys,   U = Yp + Ys, V = i (Yp - Ys) real polynomials,
 * and lambda = i y is a root iff E(iy) + a U(iy) + b V(iy) = 0: with p(i y) = p_e(y^2) + i y p_o(y^2)
 * two real linear equations (y > 0) [U_e V_e; U_o V_o] (a, b) = -(E_e, E_o), whose solution lies on
 * a^2 + b^2 = 1 iff R(z) = (E_e V_o - V_e E_o)^2 + (U_e E_o - U_o E_e)^2 - (U_e V_o - V_e U_o)^2 = 0,
 * z = y^2 > 0; y = 0 is the line E_0 + a U_0 + b V_0 = 0 against the unit circle.  Those p give the
 * critical phases; the verdict between them is taken from the closed 16x16 matrix (method CLOSED), which
 * does not use these polynomials, at each arc's midpoint and near both ends (a disagreement is bisected).
 *
 * May use: the handle (rotor_stab_handle.h), rotor_closed.h, the numerics (autobal/stability.h). */
#include "autobal/rotor_stability.h"
#include "autobal/stability.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/rotor_box2.h"
#include "analysis/rotor_closed.h"
#include "analysis/rotor_stab_handle.h"
#include "analysis/rotor_stability.h"
#include "internal.h"

#define NCAP 32 /* coefficients of the 4x4 determinant: degree 24 */

typedef long double complex lcx;
typedef struct lp {
  size_t n; /* coefficients */
  lcx c[NCAP];
} lp;

static void lp_zero(lp *p) {
  memset(p, 0, sizeof *p);
  p->n = 1;
}
static void lp_mul(const lp *a, const lp *b, lp *o) {
  lp r;
  size_t i, j;
  memset(&r, 0, sizeof r);
  r.n = a->n + b->n - 1;
  for (i = 0; i < a->n; i++)
    for (j = 0; j < b->n; j++) r.c[i + j] += a->c[i] * b->c[j];
  *o = r;
}
/* o = x a + y b */
static void lp_axpy(lcx x, const lp *a, lcx y, const lp *b, lp *o) {
  lp r;
  size_t i;
  memset(&r, 0, sizeof r);
  r.n = a->n > b->n ? a->n : b->n;
  for (i = 0; i < r.n; i++) r.c[i] = (i < a->n ? x * a->c[i] : 0.0L) + (i < b->n ? y * b->c[i] : 0.0L);
  *o = r;
}
static void lp_conj(const lp *a, lp *o) {
  size_t i;
  *o = *a;
  for (i = 0; i < a->n; i++) o->c[i] = conjl(a->c[i]);
}
/* a / (lambda + k) (the remainder, zero in exact arithmetic, is dropped) */
static void lp_div_lin(lp *a, long double k) {
  lcx carry = 0.0L;
  size_t i;
  lcx q[NCAP];
  if (a->n < 2) return;
  for (i = a->n - 1; i >= 1; i--) {
    q[i - 1] = a->c[i] + carry;
    carry = -k * q[i - 1];
  }
  for (i = 0; i + 1 < a->n; i++) a->c[i] = q[i];
  a->n--;
}

/* The data of det_at: the blocks without the Q's. */
typedef struct sys2 {
  lp G[2][2], Gs[2][2]; /* G and G* */
  lp B[2][2][2];        /* B[j] = (lambda^2 + w^2)^2 Lo_j / 2 e_j e_j^T (H = sum_j Q_j B[j]) */
  long double k1, k2;   /* kappa_1, kappa_2 */
} sys2;

/* with_w2 = 0: B without the factor (lambda^2 + w^2)^2 (the reduced parts of box_check) */
static void build_sys(const autobal_rotor_closed *c, sys2 *S, int with_w2) {
  const autobal_rotor_lumped *L = &c->L;
  const long double w = c->omega;
  lp P, P2, P4, one, K11, K12, K22, Lj[2], L12, t1, t2, W2;
  size_t j, a, b;
  lp_zero(&P);
  P.n = 2;
  P.c[0] = I * w;
  P.c[1] = 1.0L;
  lp_zero(&one);
  one.c[0] = 1.0L;
  lp_mul(&P, &P, &P2);
  lp_mul(&P2, &P2, &P4);
  lp_axpy((long double)L->M, &P2, (long double)L->h_x, &P, &t1);
  lp_axpy(1.0L, &t1, (long double)L->c_x, &one, &K11);
  lp_axpy((long double)L->A, &P2, (long double)L->h_alpha - I * (long double)L->C * w, &P, &t1);
  lp_axpy(1.0L, &t1, (long double)L->c_alpha, &one, &K22);
  lp_axpy(-(long double)L->h_xbeta, &P, -(long double)L->c_xbeta, &one, &K12);
  for (j = 0; j < 2; j++) {
    lp_zero(&Lj[j]);
    Lj[j].n = 3;
    Lj[j].c[1] = c->plane[j].kappa;
    Lj[j].c[2] = 1.0L;
  }
  lp_mul(&Lj[0], &Lj[1], &L12);
  lp_zero(&W2); /* (lambda^2 + w^2)^2 */
  W2.n = 3;
  W2.c[0] = w * w;
  W2.c[2] = 1.0L;
  lp_mul(&W2, &W2, &W2);
  if (!with_w2) {
    lp_zero(&W2);
    W2.c[0] = 1.0L;
  }
  {
    lp *K[2][2] = {{&K11, &K12}, {&K12, &K22}};
    for (a = 0; a < 2; a++)
      for (b = 0; b < 2; b++) lp_mul(K[a][b], &L12, &S->G[a][b]);
  }
  for (j = 0; j < 2; j++) {
    const lp *Lo = &Lj[1 - j];
    const long double d = c->plane[j].d, e[2] = {1.0L, d};
    lp_mul(&P4, Lo, &t1); /* P^4 Lo_j */
    lp_mul(&W2, Lo, &t2); /* (lambda^2 + w^2)^2 Lo_j */
    for (a = 0; a < 2; a++)
      for (b = 0; b < 2; b++) {
        lp_axpy(1.0L, &S->G[a][b], -0.5L * (long double)c->plane[j].mass * e[a] * e[b], &t1, &S->G[a][b]);
        lp_axpy(0.5L * e[a] * e[b], &t2, 0.0L, &t2, &S->B[j][a][b]);
      }
  }
  for (a = 0; a < 2; a++)
    for (b = 0; b < 2; b++) lp_conj(&S->G[a][b], &S->Gs[a][b]);
  S->k1 = c->plane[0].kappa;
  S->k2 = c->plane[1].kappa;
}

/* out / (L1 L2)^2 = out / (lambda^4 (lambda + k1)^2 (lambda + k2)^2) (exact in exact arithmetic): drop
 * the four lowest coefficients, then divide by the linear factors. */
static void div_L(const sys2 *S, lp *out) {
  size_t a, b;
  for (a = 0; a < 4; a++) {
    for (b = 0; b + 1 < out->n; b++) out->c[b] = out->c[b + 1];
    out->n--;
  }
  lp_div_lin(out, S->k1);
  lp_div_lin(out, S->k1);
  lp_div_lin(out, S->k2);
  lp_div_lin(out, S->k2);
}

/* The parts of det([G H; H~ G*]) with H = q1 B1 + q2 B2, H~ = r1 B1 + r2 B2 (q, r independent), by the
 * Laplace expansion along the first two rows, term by term (no differences of large determinants):
 * det = det G det G* + sum_{j,k} q_j r_k M[j][k] + q1 q2 r1 r2 beta^2, beta = the mixed determinant of
 * B1, B2 (det B_j = 0: rank one).  Each part divided by (L1 L2)^2. */
static void det_parts(const sys2 *S, lp *D0, lp M[2][2], lp *T12) {
  lp t1, t2, dG, dGs, beta;
  size_t j, k, a, b;
  lp_mul(&S->G[0][0], &S->G[1][1], &t1);
  lp_mul(&S->G[0][1], &S->G[1][0], &t2);
  lp_axpy(1.0L, &t1, -1.0L, &t2, &dG);
  lp_conj(&dG, &dGs);
  lp_mul(&dG, &dGs, D0);
  div_L(S, D0);
  for (j = 0; j < 2; j++)
    for (k = 0; k < 2; k++) {
      lp acc;
      lp_zero(&acc);
      for (a = 0; a < 2; a++)
        for (b = 2; b < 4; b++) {
          /* top: columns a (G) and b (B_j); bottom: the complement c = 1 - a (B_k), d (G*) */
          const size_t c = 1 - a, d = 5 - b, bb = b - 2, dd = d - 2;
          const long double sg = ((a + b + 1) % 2 == 0) ? 1.0L : -1.0L;
          lp top, bot;
          lp_mul(&S->G[0][a], &S->B[j][1][bb], &t1);
          lp_mul(&S->B[j][0][bb], &S->G[1][a], &t2);
          lp_axpy(1.0L, &t1, -1.0L, &t2, &top);
          lp_mul(&S->B[k][0][c], &S->Gs[1][dd], &t1);
          lp_mul(&S->Gs[0][dd], &S->B[k][1][c], &t2);
          lp_axpy(1.0L, &t1, -1.0L, &t2, &bot);
          lp_mul(&top, &bot, &t1);
          lp_axpy(1.0L, &acc, sg, &t1, &acc);
        }
      div_L(S, &acc);
      M[j][k] = acc;
    }
  /* beta = B1[0][0] B2[1][1] + B2[0][0] B1[1][1] - B1[0][1] B2[1][0] - B2[0][1] B1[1][0] */
  lp_mul(&S->B[0][0][0], &S->B[1][1][1], &t1);
  lp_mul(&S->B[1][0][0], &S->B[0][1][1], &t2);
  lp_axpy(1.0L, &t1, 1.0L, &t2, &beta);
  lp_mul(&S->B[0][0][1], &S->B[1][1][0], &t1);
  lp_axpy(1.0L, &beta, -1.0L, &t1, &beta);
  lp_mul(&S->B[1][0][1], &S->B[0][1][0], &t1);
  lp_axpy(1.0L, &beta, -1.0L, &t1, &beta);
  lp_mul(&beta, &beta, T12);
  div_L(S, T12);
}

/* Real parts (ascending) and the largest |imaginary part| relative to the largest coefficient. */
static long double real_of(const lp *p, long double *r, size_t n) {
  long double big = 0.0L, im = 0.0L;
  size_t i;
  for (i = 0; i < n; i++) {
    r[i] = i < p->n ? creall(p->c[i]) : 0.0L;
    if (i < p->n) {
      big = fmaxl(big, cabsl(p->c[i]));
      im = fmaxl(im, fabsl(cimagl(p->c[i])));
    }
  }
  return big > 0.0L ? im / big : 0.0L;
}

/* p(i y) = pe(z) + i y po(z), z = y^2, for real ascending p of length n (<= 17). */
static void split(const long double *p, size_t n, long double *pe, long double *po) {
  size_t j;
  for (j = 0; 2 * j < n; j++) pe[j] = ((j % 2) ? -1.0L : 1.0L) * p[2 * j];
  for (j = 0; 2 * j + 1 < n; j++) po[j] = ((j % 2) ? -1.0L : 1.0L) * p[2 * j + 1];
}

static long double lpv(const long double *c, size_t n, long double z) {
  long double v = 0.0L;
  while (n-- > 0) v = v * z + c[n];
  return v;
}

/* The polynomial parts of Delta16 at the handle's unbalances: E, U, V (real, ascending, 17 each). */
typedef struct parts2 {
  long double E[17], U[17], V[17];
  long double Ee[9], Eo[8], Ue[9], Uo[8], Ve[9], Vo[8];
  long double p_ref_arg; /* arg(Q1 conj Q2) at the handle's psi0 */
  long double imag_rel;  /* the largest relative imaginary part met (a check of the construction) */
  long double v_rel;     /* max |V| / max |U| */
  int v_zero;            /* V negligible: Delta16 = E + cos(arg p) U */
  /* the raw parts (real, ascending): Delta16 = D0 + x M11 + y M22 + x y T12 + t U0, x = |Q1|^2,
     y = |Q2|^2, t = |Q1||Q2| cos(arg p) (when v_zero) */
  long double D0[17], M11[17], M22[17], T12[17], U0[17];
} parts2;

static int build_parts(const autobal_rotor_closed *c, parts2 *o, autobal_error *err) {
  sys2 S;
  lp D0, M[2][2], T12, Ec, Uc, Vc;
  const long double a1 = hypotl(c->plane[0].Q_re, c->plane[0].Q_im), a2 = hypotl(c->plane[1].Q_re, c->plane[1].Q_im);
  long double im = 0.0L;
  build_sys(c, &S, 1);
  det_parts(&S, &D0, M, &T12);
  /* E = D0 + |Q1|^2 M11 + |Q2|^2 M22 + |Q1|^2 |Q2|^2 beta^2; p = e^{i arg(Q1 conj Q2)}: |Q1||Q2| (p M12 + conj(p) M21) */
  lp_axpy(1.0L, &D0, a1 * a1, &M[0][0], &Ec);
  lp_axpy(1.0L, &Ec, a2 * a2, &M[1][1], &Ec);
  lp_axpy(1.0L, &Ec, a1 * a1 * a2 * a2, &T12, &Ec);
  lp_axpy(a1 * a2, &M[0][1], a1 * a2, &M[1][0], &Uc);
  lp_axpy(I * a1 * a2, &M[0][1], -I * a1 * a2, &M[1][0], &Vc);
  {
    lp u0;
    lp_axpy(1.0L, &M[0][1], 1.0L, &M[1][0], &u0);
    if (D0.n > 17 || M[0][0].n > 17 || M[1][1].n > 17 || T12.n > 17 || u0.n > 17)
      return autobal_error_set(err, AUTOBAL_ENUMERIC, "every phase: Delta16 has more than 17 coefficients");
    real_of(&D0, o->D0, 17);
    real_of(&M[0][0], o->M11, 17);
    real_of(&M[1][1], o->M22, 17);
    real_of(&T12, o->T12, 17);
    real_of(&u0, o->U0, 17);
  }
  if (Ec.n > 17 || Uc.n > 17 || Vc.n > 17)
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "every phase: Delta16 has more than 17 coefficients");
  im = fmaxl(im, real_of(&Ec, o->E, 17));
  im = fmaxl(im, real_of(&Uc, o->U, 17));
  {
    /* V = i |Q1||Q2| (M12 - M21): zero in exact arithmetic for this model (then Delta16 depends on the
     * phase through cos(arg p) only: X = X*), here rounding; kept when it is not negligible */
    long double ub = 0.0L, vb = 0.0L;
    size_t k;
    for (k = 0; k < Uc.n; k++) ub = fmaxl(ub, cabsl(Uc.c[k]));
    for (k = 0; k < Vc.n; k++) vb = fmaxl(vb, cabsl(Vc.c[k]));
    o->v_rel = ub > 0.0L ? vb / ub : 0.0L;
    o->v_zero = o->v_rel <= 1e-9L;
    if (o->v_zero) memset(o->V, 0, sizeof o->V);
    else im = fmaxl(im, real_of(&Vc, o->V, 17));
  }
  o->imag_rel = im;
  if (!(im <= 1e-9L))
    return autobal_error_set(err, AUTOBAL_ENUMERIC,
                             "every phase: the parts of Delta16 are not real (relative imaginary part %.3Lg)", im);
  split(o->E, 17, o->Ee, o->Eo);
  split(o->U, 17, o->Ue, o->Uo);
  split(o->V, 17, o->Ve, o->Vo);
  o->p_ref_arg = atan2l((long double)c->plane[0].Q_im * c->plane[1].Q_re - (long double)c->plane[0].Q_re * c->plane[1].Q_im,
                        (long double)c->plane[0].Q_re * c->plane[1].Q_re + (long double)c->plane[0].Q_im * c->plane[1].Q_im);
  return AUTOBAL_SUCCESS;
}

/* The positive roots z of the real polynomial r (n <= 64 coefficients), generous: near-real pairs
 * (|Im| <= 1e-2 Re) count with their real part, polished by Newton in long double while close;
 * scaled z = z2 x (src/numerics/poly_positive.c). */
static int pos_roots(const long double *r, size_t n, long double z2, long double *z, size_t *nz, autobal_error *err) {
  return autobal_poly_positive_roots_tol_(r, n, z2, 1e-15, 1e-2, z, nz, err);
}

static int opposite(int a, int b) {
  return (a == AUTOBAL_VERDICT_STABLE && b == AUTOBAL_VERDICT_UNSTABLE) ||
         (a == AUTOBAL_VERDICT_UNSTABLE && b == AUTOBAL_VERDICT_STABLE);
}

/* The checks of the model's domain for two planes. */
static int check_domain2(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2]) {
  const autobal_rotor_params *p = &s->cur;
  size_t j, off = 0;
  if (p->n_planes != 2 || p->plane[0].n_balls != 2 || p->plane[1].n_balls != 2)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance (two planes): built for two planes with two balls each (here %zu "
                             "plane(s), %zu + %zu ball(s))",
                             p->n_planes, p->plane[0].n_balls, p->n_planes > 1 ? p->plane[1].n_balls : (size_t)0);
  if (p->inertia != AUTOBAL_ROTOR_INERTIA_PAPER)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance: needs the paper's inertia model (inertia = paper): with "
                             "inertia = full the unbalance mass also enters the mass matrix");
  if (!autobal_rotor_lumped_isotropic_(&s->L))
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance: needs isotropic supports (the closed system in the rotating frame)");
  for (j = 0; j < 2; j++) {
    const autobal_rotor_plane *pl = &p->plane[j];
    const double a1 = pl->ball_mass[0] * pl->ball_radius[0], a2 = pl->ball_mass[1] * pl->ball_radius[1];
    const double smin = fabs(a1 - a2), smax = a1 + a2;
    if (!autobal_rotor_close_rel_(s->h[off] / pl->ball_mass[0], s->h[off + 1] / pl->ball_mass[1], 1e-12))
      return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                               "every unbalance: the two balls of plane %zu need a common h/m (the closure)", j + 1);
    if (!(pl->r0 > 0.0))
      return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                               "every unbalance: plane%zu.r0 = %g m must be > 0 (the unbalance m0 r0 is varied "
                               "through m0)",
                               j + 1, pl->r0);
    if (!(isfinite(s_lo[j]) && isfinite(s_hi[j]) && s_lo[j] > smin && s_hi[j] < smax && s_lo[j] <= s_hi[j]))
      return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                               "every unbalance: the range of plane %zu's m0 r0 [%.9g, %.9g] kg m must lie in (%.9g, "
                               "%.9g) kg m, where its two balls (m r = %.9g, %.9g kg m) balance it off a line through "
                               "the axis, with min <= max",
                               j + 1, s_lo[j], s_hi[j], smin, smax, a1, a2);
    off += pl->n_balls;
  }
  if (!(p->omega != 0.0 && isfinite(p->omega)))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance: omega must be finite and non-zero");
  return AUTOBAL_SUCCESS;
}

#define PSI2 AUTOBAL_ROTOR_PARAM_PLANE(1, AUTOBAL_ROTOR_PLANE_PSI0)

/* Verdict at the relative phase phi (plane2.psi0 = plane1.psi0 + phi). */
static int verdict_phase(autobal_rotor_stab *s, double phi, double *mg, int *v) {
  int st = autobal_rotor_stab_set(s, PSI2, s->cur.plane[0].psi0 + phi);
  if (st != AUTOBAL_SUCCESS) return st;
  return autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_CLOSED, mg, v);
}

static double wrap_pi(double x) {
  x = fmod(x, M_PI);
  if (x < 0.0) x += M_PI;
  if (x >= M_PI) x -= M_PI;
  return x;
}

/* The core at the handle's omega and unbalances (psi0 of plane 2 changed; the caller restores it). */
static int every_phase(autobal_rotor_stab *s, autobal_rotor_phase_range *out) {
  autobal_rotor_closed c;
  parts2 q;
  double cand[2 * AUTOBAL_ROTOR_MAX_PCRIT], cy[2 * AUTOBAL_ROTOR_MAX_PCRIT], phi_ref;
  size_t nc = 0, i, k;
  int st;
  const long double w2 = (long double)s->cur.omega * s->cur.omega;
  memset(out, 0, sizeof *out);
  out->omega = s->cur.omega;
  out->s[0] = s->cur.plane[0].m0 * s->cur.plane[0].r0;
  out->s[1] = s->cur.plane[1].m0 * s->cur.plane[1].r0;
  if ((st = autobal_rotor_stab_closed(s, &c)) != AUTOBAL_SUCCESS) return st;
  if ((st = build_parts(&c, &q, &s->err)) != AUTOBAL_SUCCESS) return st;
  phi_ref = s->cur.plane[1].psi0 - s->cur.plane[0].psi0;
  if (q.v_zero) {
    /* Delta16(i y) = E(i y) + a U(i y), a = cos(arg p) real: y = 0 gives a = -E0 / U0; y > 0 needs
     * E_e + a U_e = E_o + a U_o = 0, i.e. h(z) = E_e U_o - E_o U_e = 0 (z = y^2) and |a| <= 1 */
    long double hz[16], zr[32];
    size_t nz, a, b;
    double acand[33], ycand[33];
    size_t na = 0;
    if (q.U[0] != 0.0L) {
      acand[na] = (double)(-q.E[0] / q.U[0]);
      ycand[na++] = 0.0;
    }
    memset(hz, 0, sizeof hz);
    for (a = 0; a < 9; a++)
      for (b = 0; b < 8; b++) hz[a + b] += q.Ee[a] * q.Uo[b] - q.Eo[b] * q.Ue[a];
    if ((st = pos_roots(hz, 16, w2, zr, &nz, &s->err)) != AUTOBAL_SUCCESS) return st;
    for (k = 0; k < nz; k++) {
      const long double z = zr[k], ee = lpv(q.Ee, 9, z), eo = lpv(q.Eo, 8, z), ue = lpv(q.Ue, 9, z),
                        uo = lpv(q.Uo, 8, z);
      /* the better conditioned of the two equations */
      const long double av = fabsl(ue) * sqrtl(z) >= fabsl(uo) * z ? -ee / ue : -eo / uo;
      if (!isfinite((double)av)) continue;
      acand[na] = (double)av;
      ycand[na++] = (double)sqrtl(z);
    }
    for (k = 0; k < na && nc + 2 <= 2 * AUTOBAL_ROTOR_MAX_PCRIT; k++) {
      if (!(fabs(acand[k]) <= 1.0 + 1e-12)) continue;
      {
        const double th = acos(fmax(-1.0, fmin(1.0, acand[k])));
        cand[nc] = th;
        cy[nc++] = ycand[k];
        if (th > 0.0 && th < M_PI) {
          cand[nc] = -th;
          cy[nc++] = ycand[k];
        }
      }
    }
  } else {
  /* y = 0: E0 + a U0 + b V0 = 0 on a^2 + b^2 = 1 */
  /* y > 0: R(z) */
  {
    long double n1[17], n2[17], dd[17], R[33], zr[32];
    size_t nz, a, b;
    memset(n1, 0, sizeof n1);
    memset(n2, 0, sizeof n2);
    memset(dd, 0, sizeof dd);
    memset(R, 0, sizeof R);
    for (a = 0; a < 9; a++)
      for (b = 0; b < 8; b++) {
        n1[a + b] += q.Ee[a] * q.Vo[b] - q.Ve[a] * q.Eo[b];
        n2[a + b] += q.Ue[a] * q.Eo[b] - q.Ee[a] * q.Uo[b];
        dd[a + b] += q.Ue[a] * q.Vo[b] - q.Ve[a] * q.Uo[b];
      }
    for (a = 0; a < 16; a++)
      for (b = 0; b < 16; b++) R[a + b] += n1[a] * n1[b] + n2[a] * n2[b] - dd[a] * dd[b];
    if ((st = pos_roots(R, 31, w2, zr, &nz, &s->err)) != AUTOBAL_SUCCESS) return st;
    for (k = 0; k < nz && nc < 2 * AUTOBAL_ROTOR_MAX_PCRIT; k++) {
      const long double z = zr[k], ee = lpv(q.Ee, 9, z), eo = lpv(q.Eo, 8, z), ue = lpv(q.Ue, 9, z),
                        uo = lpv(q.Uo, 8, z), ve = lpv(q.Ve, 9, z), vo = lpv(q.Vo, 8, z);
      const long double det = ue * vo - ve * uo;
      long double aa, bb;
      if (det == 0.0L) continue;
      aa = -(ee * vo - ve * eo) / det;
      bb = -(ue * eo - uo * ee) / det;
      if (!(fabsl(hypotl(aa, bb) - 1.0L) <= 1e-3L)) continue; /* a near-real pair of R that is no crossing */
      cand[nc] = (double)atan2l(bb, aa);
      cy[nc++] = (double)sqrtl(z);
    }
  }
  }
  /* phases: p(phi) = p_ref e^{-2 i (phi - phi_ref)} -> phi = phi_ref - (arg p - arg p_ref) / 2 (mod pi) */
  for (i = 0; i < nc; i++) cand[i] = wrap_pi(phi_ref - 0.5 * (cand[i] - (double)q.p_ref_arg));
  {
    /* sort (phase, y) pairs by phase */
    size_t a, b;
    for (a = 1; a < nc; a++)
      for (b = a; b > 0 && cand[b - 1] > cand[b]; b--) {
        double t = cand[b]; cand[b] = cand[b - 1]; cand[b - 1] = t;
        t = cy[b]; cy[b] = cy[b - 1]; cy[b - 1] = t;
      }
  }
  for (i = 0; i < nc; i++) {
    if (out->n_crit > 0 && cand[i] - out->phase_crit[out->n_crit - 1] <= 1e-12) continue;
    if (out->n_crit >= AUTOBAL_ROTOR_MAX_PCRIT) break;
    out->y_crit[out->n_crit] = cy[i];
    out->phase_crit[out->n_crit++] = cand[i];
  }
  if (out->n_crit > 1 && out->phase_crit[out->n_crit - 1] - out->phase_crit[0] >= M_PI - 1e-12) out->n_crit--;
  /* the arcs between them (cyclic); no critical phase: one arc [0, pi) checked at 0, pi/3, 2 pi/3 */
  {
    double edges[AUTOBAL_ROTOR_MAX_PCRIT + 2];
    size_t ne = 0;
    if (out->n_crit == 0) {
      edges[ne++] = 0.0;
      edges[ne++] = M_PI;
    } else {
      for (k = 0; k < out->n_crit; k++) edges[ne++] = out->phase_crit[k];
      edges[ne++] = out->phase_crit[0] + M_PI;
    }
    out->all_stable = out->n_crit == 0;
    out->margin_worst = -INFINITY;
    for (k = 0; k + 1 < ne; k++) {
      const double lo = edges[k], hi = edges[k + 1], wdt = hi - lo;
      const double pts[3] = {out->n_crit ? lo + 1e-7 * wdt : lo, lo + 0.5 * wdt,
                             out->n_crit ? hi - 1e-7 * wdt : lo + wdt / 6.0};
      int vv[3], qq;
      double mg[3];
      if (autobal_rotor_stab_cancelled_(s))
        return autobal_error_set(&s->err, AUTOBAL_ECANCELLED, "every phase: cancelled by the caller");
      for (qq = 0; qq < 3; qq++) {
        if ((st = verdict_phase(s, pts[qq], &mg[qq], &vv[qq])) != AUTOBAL_SUCCESS) return st;
        out->evaluations++;
        if (mg[qq] > out->margin_worst) {
          out->margin_worst = mg[qq];
          out->phase_worst = wrap_pi(pts[qq]);
        }
        if (vv[qq] != AUTOBAL_VERDICT_STABLE) out->all_stable = 0;
      }
      {
        /* pts are not in ascending order when there is no critical phase: compare each with the midpoint */
        int pair = -1;
        if (opposite(vv[0], vv[1])) pair = 0;
        else if (opposite(vv[1], vv[2])) pair = 2;
        if (pair >= 0) {
          double x0 = pts[1], x1 = pts[pair];
          const int v0 = vv[1];
          int it;
          for (it = 0; it < 60 && fabs(x1 - x0) > 1e-12; it++) {
            const double xm = 0.5 * (x0 + x1);
            double mm;
            int vm;
            if ((st = verdict_phase(s, xm, &mm, &vm)) != AUTOBAL_SUCCESS) return st;
            out->evaluations++;
            if (vm == v0) x0 = xm;
            else x1 = xm;
          }
          out->n_missed++;
          out->all_stable = 0;
          if (out->n_crit < AUTOBAL_ROTOR_MAX_PCRIT) { /* recorded in order, its frequency unknown (NaN) */
            const double ph = wrap_pi(0.5 * (x0 + x1));
            size_t at = out->n_crit++;
            for (; at > 0 && out->phase_crit[at - 1] > ph; at--) {
              out->phase_crit[at] = out->phase_crit[at - 1];
              out->y_crit[at] = out->y_crit[at - 1];
            }
            out->phase_crit[at] = ph;
            out->y_crit[at] = NAN;
          }
        }
      }
      if (out->n_sub < AUTOBAL_ROTOR_MAX_PCRIT + 1) {
        out->sub_lo[out->n_sub] = lo;
        out->sub_hi[out->n_sub] = hi;
        out->sub_verdict[out->n_sub] = vv[1];
        out->sub_margin[out->n_sub] = mg[1];
        out->n_sub++;
      }
    }
  }
  return AUTOBAL_SUCCESS;
}

/* The interval of |Q|^2 of two balls (m_i, a_i = m_i r_i) over the unbalances s in [lo, hi] (the
 * balanced angles: c = cos(psi_1 - psi_2) = (s^2 - a1^2 - a2^2) / (2 a1 a2) increases with s,
 * |Q|^2 = m1^2 + m2^2 + 2 m1 m2 (2 c^2 - 1)). */
static void q2_range(const autobal_rotor_plane *pl, double lo, double hi, long double *x_lo, long double *x_hi) {
  const long double m1 = pl->ball_mass[0], m2 = pl->ball_mass[1], a1 = m1 * pl->ball_radius[0],
                    a2 = m2 * pl->ball_radius[1];
  const long double c0 = ((long double)lo * lo - a1 * a1 - a2 * a2) / (2.0L * a1 * a2),
                    c1 = ((long double)hi * hi - a1 * a1 - a2 * a2) / (2.0L * a1 * a2);
  const long double q0 = c0 * c0, q1 = c1 * c1, qmin = (c0 <= 0.0L && c1 >= 0.0L) ? 0.0L : fminl(q0, q1),
                    qmax = fmaxl(q0, q1);
  *x_lo = m1 * m1 + m2 * m2 + 2.0L * m1 * m2 * (2.0L * qmin - 1.0L);
  *x_hi = m1 * m1 + m2 * m2 + 2.0L * m1 * m2 * (2.0L * qmax - 1.0L);
}

/* Is the crossing point (x(z), t(z)) at z = y^2 inside the region x in [x_lo, x_hi], t^2 <= x yq? */
static int in_region(const long double *A0e, const long double *A0o, const long double *A1e, const long double *A1o,
                     const long double *A2e, const long double *A2o, long double z, long double x_lo, long double x_hi,
                     long double yq) {
  const long double e0 = lpv(A0e, 9, z), o0 = lpv(A0o, 8, z), e1 = lpv(A1e, 9, z), o1 = lpv(A1o, 8, z),
                    e2 = lpv(A2e, 9, z), o2 = lpv(A2o, 8, z);
  const long double det = e1 * o2 - e2 * o1;
  long double x, tt;
  if (det == 0.0L) return 0;
  x = (e2 * o0 - e0 * o2) / det;
  tt = (e0 * o1 - e1 * o0) / det;
  return x >= x_lo * (1.0L - 1e-12L) && x <= x_hi * (1.0L + 1e-12L) && tt * tt <= x * yq * (1.0L + 1e-12L);
}

/* At the handle's plane-2 unbalance (and omega): is there a crossing for SOME s1 in [lo, hi] and some
 * phase?  Exact in s1 and the phase (docs/rotor.md "Every unbalance"): with y = |Q2|^2 fixed,
 * Delta16(i w) = A0 + x A1 + t A2 = 0 is two real linear equations for (x, t), solved as rational
 * functions of z = w^2; the region is x in X (the |Q1|^2 of [lo, hi]), t^2 <= x y (every phase).  Its
 * boundary crossings are the positive roots of Nx - x_lo det, Nx - x_hi det, Nt^2 - y Nx det and det;
 * membership is tested at each root and between consecutive ones.  w = 0: a quadratic in x.
 * *crossing = 1 if found; *ok = 0 if the parts are not of the cos form (use the grid instead). */
static int slice_crossing(autobal_rotor_stab *s, double lo, double hi, int *crossing, int *ok) {
  autobal_rotor_closed c;
  parts2 q;
  long double A0[17], A1[17], A0e[9], A0o[8], A1e[9], A1o[8], A2e[9], A2o[8], x_lo, x_hi, yq;
  long double det[16], nx[16], nt[16], P1[16], P2[16], P3[31], dP[4][30], zr[9][32], zs[300];
  size_t nz[9], k, a, b, n = 0;
  int st;
  const long double w2 = (long double)s->cur.omega * s->cur.omega;
  *crossing = 0;
  *ok = 0;
  if ((st = autobal_rotor_stab_closed(s, &c)) != AUTOBAL_SUCCESS) return st;
  if ((st = build_parts(&c, &q, &s->err)) != AUTOBAL_SUCCESS) return st;
  if (!q.v_zero) return AUTOBAL_SUCCESS;
  *ok = 1;
  yq = (long double)c.plane[1].Q_re * c.plane[1].Q_re + (long double)c.plane[1].Q_im * c.plane[1].Q_im;
  q2_range(&s->cur.plane[0], lo, hi, &x_lo, &x_hi);
  for (k = 0; k < 17; k++) {
    A0[k] = q.D0[k] + yq * q.M22[k];
    A1[k] = q.M11[k] + yq * q.T12[k];
  }
  split(A0, 17, A0e, A0o);
  split(A1, 17, A1e, A1o);
  split(q.U0, 17, A2e, A2o);
  /* w = 0: A0(0) + x A1(0) + t A2(0) = 0 with t^2 <= x y, x in X */
  {
    const long double a0 = A0[0], a1 = A1[0], a2 = q.U0[0];
    if (a2 != 0.0L) {
      /* f(x) = (a0 + a1 x)^2 - a2^2 y x <= 0 for some x in X: f convex; its minimum over X */
      const long double A = a1 * a1, B = 2.0L * a0 * a1 - a2 * a2 * yq, C0 = a0 * a0;
      long double xm = A > 0.0L ? -B / (2.0L * A) : x_lo, fmin;
      if (xm < x_lo) xm = x_lo;
      if (xm > x_hi) xm = x_hi;
      fmin = fminl(fminl(A * xm * xm + B * xm + C0, A * x_lo * x_lo + B * x_lo + C0), A * x_hi * x_hi + B * x_hi + C0);
      if (fmin <= 0.0L) *crossing = 1;
    } else if (a1 != 0.0L) {
      const long double xx = -a0 / a1;
      if (xx >= x_lo && xx <= x_hi) *crossing = 1;
    }
  }
  memset(det, 0, sizeof det);
  memset(nx, 0, sizeof nx);
  memset(nt, 0, sizeof nt);
  memset(P3, 0, sizeof P3);
  for (a = 0; a < 9; a++)
    for (b = 0; b < 8; b++) {
      det[a + b] += A1e[a] * A2o[b] - A2e[a] * A1o[b];
      nx[a + b] += A2e[a] * A0o[b] - A0e[a] * A2o[b];
      nt[a + b] += A0e[a] * A1o[b] - A1e[a] * A0o[b];
    }
  for (k = 0; k < 16; k++) {
    P1[k] = nx[k] - x_lo * det[k];
    P2[k] = nx[k] - x_hi * det[k];
  }
  for (a = 0; a < 16; a++)
    for (b = 0; b < 16; b++) P3[a + b] += nt[a] * nt[b] - yq * nx[a] * det[b];
  if ((st = pos_roots(P1, 16, w2, zr[0], &nz[0], &s->err)) != AUTOBAL_SUCCESS) return st;
  if ((st = pos_roots(P2, 16, w2, zr[1], &nz[1], &s->err)) != AUTOBAL_SUCCESS) return st;
  if ((st = pos_roots(P3, 31, w2, zr[2], &nz[2], &s->err)) != AUTOBAL_SUCCESS) return st;
  if ((st = pos_roots(det, 16, w2, zr[3], &nz[3], &s->err)) != AUTOBAL_SUCCESS) return st;
  /* more points to test, never fewer: with y = |Q2|^2 small the region t^2 <= x y is a sliver about
   * N_t = 0 and P3 = N_t^2 - y N_x det has a close pair of roots there, which the root finder can
   * return as a complex pair (lost).  The roots of N_t (the sliver's middle) and of the derivatives
   * of the four boundary polynomials (the extremum between a close pair) are tested as well. */
  for (k = 0; k + 1 < 31; k++) dP[0][k] = (long double)(k + 1) * P3[k + 1];
  for (k = 0; k + 1 < 16; k++) {
    dP[1][k] = (long double)(k + 1) * P1[k + 1];
    dP[2][k] = (long double)(k + 1) * P2[k + 1];
    dP[3][k] = (long double)(k + 1) * det[k + 1];
  }
  if ((st = pos_roots(nt, 16, w2, zr[4], &nz[4], &s->err)) != AUTOBAL_SUCCESS) return st;
  if ((st = pos_roots(dP[0], 30, w2, zr[5], &nz[5], &s->err)) != AUTOBAL_SUCCESS) return st;
  for (a = 1; a < 4; a++)
    if ((st = pos_roots(dP[a], 15, w2, zr[5 + a], &nz[5 + a], &s->err)) != AUTOBAL_SUCCESS) return st;
  for (a = 0; a < 9; a++)
    for (b = 0; b < nz[a]; b++) zs[n++] = zr[a][b];
  /* sort */
  for (a = 1; a < n; a++)
    for (b = a; b > 0 && zs[b - 1] > zs[b]; b--) {
      const long double tmp = zs[b];
      zs[b] = zs[b - 1];
      zs[b - 1] = tmp;
    }
  if (in_region(A0e, A0o, A1e, A1o, A2e, A2o, n ? 0.5L * zs[0] : w2, x_lo, x_hi, yq)) *crossing = 1;
  if (n && in_region(A0e, A0o, A1e, A1o, A2e, A2o, 2.0L * zs[n - 1], x_lo, x_hi, yq)) *crossing = 1;
  for (k = 0; k < n && !*crossing; k++) {
    if (in_region(A0e, A0o, A1e, A1o, A2e, A2o, zs[k], x_lo, x_hi, yq)) *crossing = 1;
    if (k + 1 < n && in_region(A0e, A0o, A1e, A1o, A2e, A2o, 0.5L * (zs[k] + zs[k + 1]), x_lo, x_hi, yq))
      *crossing = 1;
  }
  return AUTOBAL_SUCCESS;
}

/* Set plane j's unbalance m0 r0 = sv. */
static int set_unb(autobal_rotor_stab *s, size_t j, double sv) {
  return autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(j, AUTOBAL_ROTOR_PLANE_M0), sv / s->cur.plane[j].r0);
}

/* The box budgets (per side of the search, rotor_box2.c): about 8 us a box.  A slice (y fixed) is
 * decided in a few hundred boxes where it is decided at all; the whole plane-2 range took 30000 to
 * 70000 at the stable cases of the tests. */
#define BOX_BUDGET_SLICE 5000
#define BOX_BUDGET_RANGE 100000

/* The unbalance s in [lo, hi] of two balls with |Q|^2 = q (the inverse of q2_range; NaN if none). */
static double s_of_q2(const autobal_rotor_plane *pl, long double q, double lo, double hi) {
  const long double m1 = pl->ball_mass[0], m2 = pl->ball_mass[1], a1 = m1 * pl->ball_radius[0],
                    a2 = m2 * pl->ball_radius[1];
  const long double cc = 0.5L * ((q - m1 * m1 - m2 * m2) / (2.0L * m1 * m2) + 1.0L);
  const long double c = sqrtl(fmaxl(0.0L, cc));
  int k;
  for (k = 0; k < 2; k++) {
    const long double s2 = a1 * a1 + a2 * a2 + 2.0L * a1 * a2 * (k ? -c : c);
    const double sv = (double)sqrtl(fmaxl(0.0L, s2));
    if (sv >= lo * (1.0 - 1e-9) && sv <= hi * (1.0 + 1e-9)) return fmin(hi, fmax(lo, sv));
  }
  return NAN;
}

/* Over both planes' whole ranges at once (rotor_box2.c): *verdict 0 no root on the imaginary axis
 * anywhere in the region, 1 one found (out->found_*), -1 undecided (or the parts are not of the cos
 * form).  The handle's unbalances are those of the caller (the parts do not depend on them). */
/* p(mu - delta) in place (ascending, n coefficients): the Taylor shift, in long double */
static void shift_poly(long double *p, size_t n, long double delta) {
  size_t k, i;
  for (k = 0; k + 1 < n; k++)
    for (i = n - 1; i > k; i--) p[i - 1] -= delta * p[i];
}

static int box_check_shift(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2], size_t budget,
                           double delta, int *verdict, autobal_rotor_unbalance_range2 *out);
static int box_check(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2], size_t budget, int *verdict,
                     autobal_rotor_unbalance_range2 *out) {
  return box_check_shift(s, s_lo, s_hi, budget, 0.0, verdict, out);
}

/* box_check for the roots right of -delta (delta > 0): the search on Delta16(mu - delta), whose parts
 * (D0, and M11, M22, U0, T12 with their factors F) are each Taylor-shifted; a root mu = i w found is
 * a root lambda = -delta + i w.  delta = 0: box_check as it was. */
static int box_check_shift(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2], size_t budget,
                           double delta, int *verdict, autobal_rotor_unbalance_range2 *out) {
  autobal_rotor_closed c;
  parts2 q;
  autobal_rotor_box2_in in;
  autobal_rotor_box2_out bo;
  int st;
  *verdict = -1;
  if ((st = autobal_rotor_stab_closed(s, &c)) != AUTOBAL_SUCCESS) return st;
  if ((st = build_parts(&c, &q, &s->err)) != AUTOBAL_SUCCESS) return st;
  if (!q.v_zero) return AUTOBAL_SUCCESS;
  memset(&in, 0, sizeof in);
  {
    /* the parts without their common factors: M_jk = F m_jk, T12 = F^2 t12, F = (lambda^2 + w^2)^4
     * (each B_j carries (lambda^2 + w^2)^2), built so (no division) */
    sys2 S;
    lp D0, M[2][2], T12, u0;
    build_sys(&c, &S, 0);
    det_parts(&S, &D0, M, &T12);
    lp_axpy(1.0L, &M[0][1], 1.0L, &M[1][0], &u0);
    if (D0.n > 17 || M[0][0].n > 17 || M[1][1].n > 17 || T12.n > 17 || u0.n > 17) return AUTOBAL_SUCCESS;
    memcpy(in.D0, q.D0, sizeof in.D0);
    real_of(&M[0][0], in.M11, 17);
    real_of(&M[1][1], in.M22, 17);
    real_of(&T12, in.T12, 17);
    real_of(&u0, in.U0, 17);
  }
  if (delta != 0.0) {
    /* the full parts (with F), shifted: Delta16(mu - delta) = D0s + x M11s + y M22s + t U0s + x y T12s */
    const long double dl = (long double)delta;
    memcpy(in.D0, q.D0, sizeof in.D0);
    memcpy(in.M11, q.M11, sizeof in.M11);
    memcpy(in.M22, q.M22, sizeof in.M22);
    memcpy(in.T12, q.T12, sizeof in.T12);
    memcpy(in.U0, q.U0, sizeof in.U0);
    shift_poly(in.D0, 17, dl);
    shift_poly(in.M11, 17, dl);
    shift_poly(in.M22, 17, dl);
    shift_poly(in.T12, 17, dl);
    shift_poly(in.U0, 17, dl);
    in.full = 1;
  }
  q2_range(&s->cur.plane[0], s_lo[0], s_hi[0], &in.x_lo, &in.x_hi);
  q2_range(&s->cur.plane[1], s_lo[1], s_hi[1], &in.y_lo, &in.y_hi);
  in.w2 = (long double)s->cur.omega * s->cur.omega;
  in.max_boxes = budget;
  if (autobal_rotor_box2_(&in, &bo) != 0) return AUTOBAL_SUCCESS;
  out->boxes += bo.boxes;
  *verdict = bo.verdict;
  if (bo.verdict == 1 && !bo.at_zero) {
    out->found_s[0] = s_of_q2(&s->cur.plane[0], bo.x, s_lo[0], s_hi[0]);
    out->found_s[1] = s_of_q2(&s->cur.plane[1], bo.y, s_lo[1], s_hi[1]);
    /* t = |Q1||Q2| cos(arg p), p = e^{i arg(Q1 conj Q2)}; the relative phase phi of the unbalances
     * from p as in every_phase, at the point's own unbalances (arg p also depends on them) */
    if (isfinite(out->found_s[0]) && isfinite(out->found_s[1]) && bo.x > 0.0L && bo.y > 0.0L) {
      const long double ap = acosl(fmaxl(-1.0L, fminl(1.0L, bo.t / sqrtl(bo.x * bo.y))));
      if ((st = set_unb(s, 0, out->found_s[0])) != AUTOBAL_SUCCESS) return st;
      if ((st = set_unb(s, 1, out->found_s[1])) != AUTOBAL_SUCCESS) return st;
      if ((st = autobal_rotor_stab_closed(s, &c)) != AUTOBAL_SUCCESS) return st;
      if ((st = build_parts(&c, &q, &s->err)) != AUTOBAL_SUCCESS) return st;
      out->found_phase =
          wrap_pi(s->cur.plane[1].psi0 - s->cur.plane[0].psi0 - 0.5 * (double)(ap - q.p_ref_arg));
    }
  }
  return AUTOBAL_SUCCESS;
}

typedef struct saved2 {
  double m0[2], psi2;
} saved2;
static void save2(autobal_rotor_stab *s, saved2 *v) {
  v->m0[0] = s->cur.plane[0].m0;
  v->m0[1] = s->cur.plane[1].m0;
  v->psi2 = s->cur.plane[1].psi0;
}
static int restore2(autobal_rotor_stab *s, const saved2 *v, int st) {
  const int a = autobal_rotor_stab_set(s, PSI2, v->psi2);
  const int b = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_M0), v->m0[0]);
  const int c = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(1, AUTOBAL_ROTOR_PLANE_M0), v->m0[1]);
  if (st != AUTOBAL_SUCCESS) return st;
  return a != AUTOBAL_SUCCESS ? a : b != AUTOBAL_SUCCESS ? b : c;
}

int autobal_rotor_stab_every_unbalance2_shift(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2],
                                              double delta, int *verdict, autobal_rotor_unbalance_range2 *out) {
  saved2 sv;
  int st, bv = -1, a;
  const size_t budget = s && s->opt.unbalance2_boxes > 0 ? (size_t)s->opt.unbalance2_boxes : BOX_BUDGET_RANGE;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL || verdict == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance (shift): out or verdict is NULL");
  if (!(delta >= 0.0 && isfinite(delta)))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance (shift): delta = %g: allowed [0, inf)", delta);
  memset(out, 0, sizeof *out);
  out->found_s[0] = out->found_s[1] = out->found_phase = NAN;
  out->omega = s->cur.omega;
  out->margin_worst = -INFINITY;
  *verdict = -1;
  if ((st = check_domain2(s, s_lo, s_hi)) != AUTOBAL_SUCCESS) return st;
  save2(s, &sv);
  st = set_unb(s, 0, s_lo[0]);
  if (st == AUTOBAL_SUCCESS) st = set_unb(s, 1, s_lo[1]);
  if (st == AUTOBAL_SUCCESS) st = box_check_shift(s, s_lo, s_hi, budget, delta, &bv, out);
  if (st == AUTOBAL_SUCCESS && bv == 1) *verdict = 0;
  if (st == AUTOBAL_SUCCESS && bv == 0) {
    /* no root on Re lambda = -delta in the connected region: the count of roots right of it is the
     * same everywhere; the corners (closed matrix) say whether it is 0 */
    *verdict = 1;
    for (a = 0; a < 8 && st == AUTOBAL_SUCCESS; a++) {
      double mg;
      int v;
      st = set_unb(s, 0, (a & 1) ? s_hi[0] : s_lo[0]);
      if (st == AUTOBAL_SUCCESS) st = set_unb(s, 1, (a & 2) ? s_hi[1] : s_lo[1]);
      if (st == AUTOBAL_SUCCESS) st = verdict_phase(s, (a & 4) ? 0.5 * M_PI : 0.0, &mg, &v);
      out->evaluations++;
      if (st == AUTOBAL_SUCCESS && mg > out->margin_worst) out->margin_worst = mg;
      if (st == AUTOBAL_SUCCESS && !(mg < -delta)) {
        *verdict = 0;
        out->found_s[0] = (a & 1) ? s_hi[0] : s_lo[0];
        out->found_s[1] = (a & 2) ? s_hi[1] : s_lo[1];
        out->found_phase = (a & 4) ? 0.5 * M_PI : 0.0;
        break;
      }
    }
  }
  out->all_stable = *verdict == 1;
  out->exact_in_s2 = out->exact_in_s1 = *verdict != -1;
  return restore2(s, &sv, st);
}

int autobal_rotor_stab_every_phase(autobal_rotor_stab *s, double s1, double s2, autobal_rotor_phase_range *out) {
  saved2 sv;
  int st;
  const double lo[2] = {s1, s2};
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every phase: out is NULL");
  memset(out, 0, sizeof *out);
  if ((st = check_domain2(s, lo, lo)) != AUTOBAL_SUCCESS) return st;
  save2(s, &sv);
  st = set_unb(s, 0, s1);
  if (st == AUTOBAL_SUCCESS) st = set_unb(s, 1, s2);
  if (st == AUTOBAL_SUCCESS) st = every_phase(s, out);
  return restore2(s, &sv, st);
}

static int every2(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2], size_t n_grid,
                  autobal_rotor_unbalance_range2 *out) {
  size_t i, k, n[2];
  int st, any_crossing = 0;
  autobal_rotor_phase_range ph;
  memset(out, 0, sizeof *out);
  out->omega = s->cur.omega;
  for (k = 0; k < 2; k++) {
    out->s_lo[k] = s_lo[k];
    out->s_hi[k] = s_hi[k];
    out->first_bad_s[k] = NAN;
    out->worst_s[k] = NAN;
  }
  out->worst_phase = NAN;
  if ((st = check_domain2(s, s_lo, s_hi)) != AUTOBAL_SUCCESS) return st;
  if (n_grid < 2 || n_grid > 100000)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance (two planes): n_grid = %zu must be in [2, 1e5]",
                             n_grid);
  for (k = 0; k < 2; k++) out->n_s[k] = n[k] = s_lo[k] == s_hi[k] ? 1 : n_grid;
  out->all_stable = 1;
  out->margin_worst = -INFINITY;
  out->exact_in_s1 = 1;
  out->found_s[0] = out->found_s[1] = out->found_phase = NAN;
  /* one slice per plane-2 unbalance: exact over plane 1's range and every phase (slice_crossing), and
   * every_phase at the grid points of plane 1 (the margins, and a cross-check) */
  for (k = 0; k < n[1]; k++) {
    const double s2 = n[1] == 1 ? s_lo[1] : s_lo[1] + (s_hi[1] - s_lo[1]) * (double)k / (double)(n[1] - 1);
    int crossing = 0, ok = 0, grid_ok = 1, slice_ok;
    if ((st = set_unb(s, 1, s2)) != AUTOBAL_SUCCESS) return st;
    if ((st = set_unb(s, 0, s_lo[0])) != AUTOBAL_SUCCESS) return st;
    if ((st = slice_crossing(s, s_lo[0], s_hi[0], &crossing, &ok)) != AUTOBAL_SUCCESS) return st;
    if (!ok) out->exact_in_s1 = 0;
    for (i = 0; i < n[0]; i++) {
      const double s1 = n[0] == 1 ? s_lo[0] : s_lo[0] + (s_hi[0] - s_lo[0]) * (double)i / (double)(n[0] - 1);
      if ((st = set_unb(s, 0, s1)) != AUTOBAL_SUCCESS) return st;
      if ((st = every_phase(s, &ph)) != AUTOBAL_SUCCESS) return st;
      out->n_points++;
      out->evaluations += ph.evaluations;
      out->n_missed += ph.n_missed;
      if (ph.n_crit) out->n_with_crit++;
      if (ph.margin_worst > out->margin_worst) {
        out->margin_worst = ph.margin_worst;
        out->worst_s[0] = s1;
        out->worst_s[1] = s2;
        out->worst_phase = ph.phase_worst;
      }
      if (!ph.all_stable) {
        if (out->all_stable) {
          out->first_bad_s[0] = s1;
          out->first_bad_s[1] = s2;
        }
        out->all_stable = 0;
        grid_ok = 0;
        out->n_not_stable++;
      }
    }
    /* the slice: no crossing in the region and stable at one point of it (the grid's), else not */
    slice_ok = ok ? (!crossing && grid_ok) : grid_ok;
    if (ok && !crossing && !grid_ok) out->n_missed++; /* a grid point unstable without a crossing: should not happen */
    if (!slice_ok) {
      out->n_slices_not_stable++;
      if (out->all_stable) {
        out->first_bad_s[0] = NAN;
        out->first_bad_s[1] = s2;
      }
      out->all_stable = 0;
    }
    if (crossing) any_crossing = 1;
  }
  /* plane 2's whole range (or its one value): the box search, where the grid and slices say stable */
  if (!out->all_stable)
    out->exact_in_s2 = 1; /* not stable for all: decided by a grid point or an exact slice already */
  else if (out->exact_in_s1 && s->opt.unbalance2_boxes != -1) {
    const size_t budget = s->opt.unbalance2_boxes > 0 ? (size_t)s->opt.unbalance2_boxes : BOX_BUDGET_RANGE;
    const size_t budget_slice = budget < BOX_BUDGET_SLICE ? budget : BOX_BUDGET_SLICE;
    int bv;
    if ((st = box_check(s, s_lo, s_hi, budget, &bv, out)) != AUTOBAL_SUCCESS) return st;
    out->exact_in_s2 = bv != -1;
    if (bv == -1) {
      /* undecided over the range: each grid slice by the box search with y fixed (where the slice said
       * stable): a second, independent look at each slice (it found the roots the slice lost before
       * slice_crossing tested the roots of N_t and of the derivatives) */
      for (k = 0; k < n[1] && bv != 1; k++) {
        const double s2 = n[1] == 1 ? s_lo[1] : s_lo[1] + (s_hi[1] - s_lo[1]) * (double)k / (double)(n[1] - 1);
        const double l1[2] = {s_lo[0], s2}, h1[2] = {s_hi[0], s2};
        int sv;
        if ((st = box_check(s, l1, h1, budget_slice, &sv, out)) != AUTOBAL_SUCCESS) return st;
        if (sv == 1) {
          bv = 1;
          out->exact_in_s2 = 1; /* a point found: not stable for all, certainly */
          out->n_slices_not_stable++;
        }
      }
    }
    if (bv == 1) {
      if (!any_crossing && out->all_stable) {
        /* a crossing between the s2 grid values (or one a grid slice missed) */
        out->first_bad_s[0] = out->found_s[0];
        out->first_bad_s[1] = out->found_s[1];
      }
      out->all_stable = 0;
    } else if (bv == 0 && any_crossing)
      out->n_missed++; /* a grid slice met a crossing the box search excluded: should not happen */
  }
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_stab_every_unbalance2(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2],
                                        size_t n_grid, autobal_rotor_unbalance_range2 *out) {
  saved2 sv;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL || s_lo == NULL || s_hi == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance (two planes): NULL argument");
  save2(s, &sv);
  return restore2(s, &sv, every2(s, s_lo, s_hi, n_grid, out));
}

/* The speeds evaluated by the scan, in order (speed, verdict, plane 2 decided exactly, boxes). */
typedef struct speed_rec {
  double w;
  int stable, exact;
  size_t boxes;
} speed_rec;

typedef struct {
  const double *s_lo, *s_hi;
  size_t n_grid;
  speed_rec *rec; /* NULL: no record kept */
  size_t n_rec, cap;
  int keep;
} speeds2_ctx;

/* The speed set's verdict by the box search first (the same certificate every2 ends with, without the
 * grid before it): a root found in the region is "not stable for all"; none, and the four corners of
 * both ranges at the phases 0 and pi/2 stable (the closed matrix), is "stable for all" (the region is
 * connected: no root crosses the axis inside it).  *decided 0 when the search was undecided or a
 * corner was not stable (then every2 decides, as before).  ur gets all_stable, exact_in_s2, boxes,
 * evaluations. */
static int box_first(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2],
                     autobal_rotor_unbalance_range2 *ur, int *decided) {
  int st, bv, a;
  const size_t budget = s->opt.unbalance2_boxes > 0 ? (size_t)s->opt.unbalance2_boxes : BOX_BUDGET_RANGE;
  memset(ur, 0, sizeof *ur);
  ur->found_s[0] = ur->found_s[1] = ur->found_phase = NAN;
  *decided = 0;
  if ((st = check_domain2(s, s_lo, s_hi)) != AUTOBAL_SUCCESS) return st;
  if ((st = set_unb(s, 0, s_lo[0])) != AUTOBAL_SUCCESS) return st;
  if ((st = set_unb(s, 1, s_lo[1])) != AUTOBAL_SUCCESS) return st;
  if ((st = box_check(s, s_lo, s_hi, budget, &bv, ur)) != AUTOBAL_SUCCESS) return st;
  if (bv == 1) {
    ur->all_stable = 0;
    ur->exact_in_s2 = 1;
    *decided = 1;
    return AUTOBAL_SUCCESS;
  }
  if (bv != 0) return AUTOBAL_SUCCESS;
  for (a = 0; a < 8; a++) {
    double mg;
    int v;
    if ((st = set_unb(s, 0, (a & 1) ? s_hi[0] : s_lo[0])) != AUTOBAL_SUCCESS) return st;
    if ((st = set_unb(s, 1, (a & 2) ? s_hi[1] : s_lo[1])) != AUTOBAL_SUCCESS) return st;
    if ((st = verdict_phase(s, (a & 4) ? 0.5 * M_PI : 0.0, &mg, &v)) != AUTOBAL_SUCCESS) return st;
    ur->evaluations++;
    if (v != AUTOBAL_VERDICT_STABLE) return AUTOBAL_SUCCESS; /* not what the search says: every2 decides */
  }
  ur->all_stable = 1;
  ur->exact_in_s2 = 1;
  *decided = 1;
  return AUTOBAL_SUCCESS;
}

/* autobal_rotor_speed_verdict_fn_ of the two-plane speed set. */
static int speeds2_verdict(autobal_rotor_stab *s, void *user, int *all_stable, size_t *evaluations) {
  speeds2_ctx *c = (speeds2_ctx *)user;
  autobal_rotor_unbalance_range2 ur;
  int st, decided = 0;
  size_t boxes = 0;
  memset(&ur, 0, sizeof ur);
  if (s->opt.unbalance2_boxes != -1) {
    if ((st = box_first(s, c->s_lo, c->s_hi, &ur, &decided)) != AUTOBAL_SUCCESS) return st;
    boxes = ur.boxes;
  }
  if (!decided) {
    const size_t ev = ur.evaluations;
    if ((st = every2(s, c->s_lo, c->s_hi, c->n_grid, &ur)) != AUTOBAL_SUCCESS) return st;
    ur.boxes += boxes;
    ur.evaluations += ev;
  }
  *evaluations = ur.evaluations;
  *all_stable = ur.all_stable;
  if (c->keep) {
    if (c->n_rec == c->cap) {
      const size_t cap = c->cap ? 2 * c->cap : 256;
      speed_rec *r = realloc(c->rec, cap * sizeof *r);
      if (r == NULL) return autobal_error_set(&s->err, AUTOBAL_ENOMEM, "every unbalance (two planes): out of memory");
      c->rec = r;
      c->cap = cap;
    }
    c->rec[c->n_rec].w = s->cur.omega;
    c->rec[c->n_rec].stable = ur.all_stable;
    c->rec[c->n_rec].exact = ur.exact_in_s2;
    c->rec[c->n_rec].boxes = ur.boxes;
    c->n_rec++;
  }
  return st;
}

/* The detail from the record of the speeds evaluated. */
static void fill_detail(const speeds2_ctx *c, const autobal_rotor_crit *out, double w_lo, double w_hi, size_t n_omega,
                        autobal_rotor_speeds2_detail *d) {
  size_t k, j;
  d->n_evaluated = c->n_rec;
  for (j = 0; j < c->n_rec; j++) {
    if (!c->rec[j].exact) d->n_undecided++;
    d->boxes += c->rec[j].boxes;
  }
  for (k = 0; k < n_omega; k++) {
    /* the scan's grid speed, bit for bit (rotor_speed_scan.c) */
    const double w = w_lo + (w_hi - w_lo) * (double)k / (double)(n_omega - 1);
    if (d->grid_omega) d->grid_omega[k] = w;
    if (d->grid_stable) d->grid_stable[k] = -1;
    if (d->grid_exact) d->grid_exact[k] = 0;
    if (d->grid_boxes) d->grid_boxes[k] = 0;
    for (j = 0; j < c->n_rec; j++)
      if (c->rec[j].w == w) {
        if (d->grid_stable) d->grid_stable[k] = c->rec[j].stable;
        if (d->grid_exact) d->grid_exact[k] = c->rec[j].exact;
        if (d->grid_boxes) d->grid_boxes[k] = c->rec[j].boxes;
        break;
      }
  }
  for (k = 0; k < out->n_stable && k < AUTOBAL_ROTOR_MAX_CRIT; k++) {
    const double lo = fmin(out->stable_lo[k], out->stable_hi[k]), hi = fmax(out->stable_lo[k], out->stable_hi[k]);
    d->interval_exact[k] = 1;
    for (j = 0; j < c->n_rec; j++)
      if (c->rec[j].w >= lo && c->rec[j].w <= hi && !c->rec[j].exact) {
        d->interval_exact[k] = 0;
        d->interval_undecided[k]++;
      }
  }
  for (k = 0; k < out->n && k < AUTOBAL_ROTOR_MAX_CRIT; k++) {
    /* the final bracket: the nearest speeds evaluated on either side */
    const double v = out->value[k];
    size_t below = c->n_rec, above = c->n_rec;
    for (j = 0; j < c->n_rec; j++) {
      if (c->rec[j].w <= v && (below == c->n_rec || c->rec[j].w > c->rec[below].w)) below = j;
      if (c->rec[j].w >= v && (above == c->n_rec || c->rec[j].w < c->rec[above].w)) above = j;
    }
    d->critical_exact[k] = below < c->n_rec && above < c->n_rec && c->rec[below].exact && c->rec[above].exact;
  }
}

int autobal_rotor_stab_every_unbalance2_speeds_detail(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2],
                                                      size_t n_grid, double w_lo, double w_hi, size_t n_omega,
                                                      double xtol_rel, autobal_rotor_crit *out,
                                                      autobal_rotor_speeds2_detail *detail) {
  speeds2_ctx c;
  saved2 sv;
  int st;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL || s_lo == NULL || s_hi == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance (two planes): NULL argument");
  memset(&c, 0, sizeof c);
  c.s_lo = s_lo;
  c.s_hi = s_hi;
  c.n_grid = n_grid;
  c.keep = detail != NULL;
  if (detail) {
    /* the caller's arrays kept, the rest cleared */
    double *gw = detail->grid_omega;
    int *gs = detail->grid_stable, *ge = detail->grid_exact;
    size_t *gb = detail->grid_boxes;
    memset(detail, 0, sizeof *detail);
    detail->grid_omega = gw;
    detail->grid_stable = gs;
    detail->grid_exact = ge;
    detail->grid_boxes = gb;
  }
  save2(s, &sv);
  st = restore2(s, &sv, autobal_rotor_scan_speeds_(s, w_lo, w_hi, n_omega, xtol_rel, speeds2_verdict, &c, out));
  if (detail && (st == AUTOBAL_SUCCESS || st == AUTOBAL_WARNING) && n_omega >= 2) fill_detail(&c, out, w_lo, w_hi, n_omega, detail);
  free(c.rec);
  return st;
}

int autobal_rotor_stab_every_unbalance2_speeds(autobal_rotor_stab *s, const double s_lo[2], const double s_hi[2],
                                               size_t n_grid, double w_lo, double w_hi, size_t n_omega,
                                               double xtol_rel, autobal_rotor_crit *out) {
  return autobal_rotor_stab_every_unbalance2_speeds_detail(s, s_lo, s_hi, n_grid, w_lo, w_hi, n_omega, xtol_rel, out,
                                                           NULL);
}

/* For the one-plane entry points (rotor_unbalance.c) with two planes: both planes over [s_lo, s_hi],
 * every phase, AUTOBAL_ROTOR_EVERY2_GRID points per plane; the one-plane record gets the verdict
 * (one sub-interval holding the worst verdict met, no critical unbalances). */
int autobal_rotor_every_unbalance_two_planes_(autobal_rotor_stab *s, double s_lo, double s_hi,
                                              autobal_rotor_unbalance_range *out) {
  autobal_rotor_unbalance_range2 u;
  const double lo[2] = {s_lo, s_lo}, hi[2] = {s_hi, s_hi};
  int st = autobal_rotor_stab_every_unbalance2(s, lo, hi, AUTOBAL_ROTOR_EVERY2_GRID, &u);
  memset(out, 0, sizeof *out);
  out->omega = s->cur.omega;
  out->s_lo = s_lo;
  out->s_hi = s_hi;
  if (st != AUTOBAL_SUCCESS) return st;
  out->all_stable = u.all_stable;
  out->margin_worst = u.margin_worst;
  out->n_missed = u.n_missed;
  out->evaluations = u.evaluations;
  out->n_sub = 1;
  out->sub_lo[0] = s_lo;
  out->sub_hi[0] = s_hi;
  out->sub_verdict[0] = u.all_stable ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
  out->sub_margin[0] = u.margin_worst;
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_every_unbalance_speeds_two_planes_(autobal_rotor_stab *s, double s_lo, double s_hi, double w_lo,
                                                     double w_hi, size_t n_grid, double xtol_rel,
                                                     autobal_rotor_crit *out) {
  const double lo[2] = {s_lo, s_lo}, hi[2] = {s_hi, s_hi};
  return autobal_rotor_stab_every_unbalance2_speeds(s, lo, hi, AUTOBAL_ROTOR_EVERY2_GRID, w_lo, w_hi, n_grid,
                                                    xtol_rel, out);
}
