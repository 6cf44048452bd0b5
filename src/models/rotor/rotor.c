/* rotor.c: the rotor - massive housing - ball autobalancer model (docs/rotor.md):
 * parameters and lumped coefficients (2.7)-(2.11), the right-hand sides in the
 * fixed frame (3.2)-(3.8) and with the balls in the rotating frame (3.9)-(3.13),
 * derived outputs, balanced configurations (3.14). */
#include "autobal/rotor.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "numerics/fastmath.h"
#include "internal.h"
#include "models/rotor/rotor_internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

struct autobal_rotor {
  autobal_rotor_params p;  /* copy; plane arrays point into `store` */
  autobal_rotor_lumped L;  /* lumped coefficients in use */
  size_t n_planes, N, dim;
  size_t off[AUTOBAL_ROTOR_MAX_PLANES], cnt[AUTOBAL_ROTOR_MAX_PLANES];
  double s0[AUTOBAL_ROTOR_MAX_PLANES];    /* m0 r0, kg m */
  double sref[AUTOBAL_ROTOR_MAX_PLANES];  /* reference of the monitor, kg m */
  double mtot[AUTOBAL_ROTOR_MAX_PLANES];  /* m0 + sum m_i (FULL inertia), kg */
  double l_L, l_R;                        /* support positions for outputs (may be NAN) */
  double inv_M, inv_A;                    /* 1/M (1/kg), 1/A (1/(kg m^2)) */
  double g[AUTOBAL_ROTOR_MAX_PLANES];     /* 1/M + d_j^2/A (1/kg), one-plane closed form */
  double cpsi0[AUTOBAL_ROTOR_MAX_PLANES]; /* cos psi_j0, sin psi_j0 of the unbalance */
  double spsi0[AUTOBAL_ROTOR_MAX_PLANES];
  /* per ball (length N each, state order) */
  double *m, *r, *mr, *hr, *kappa, *psi_init, *rate_init, *h;
  /* workspace of the right-hand sides */
  double *sn, *cs;
  /* the drive as a table (RAMP: its two corners; CONSTANT: dn = 0): times dT, speeds dV,
   * slopes dS (rad/s^2, dn - 1 of them), antiderivative dP = F(dT[k]) with F(t) = dV[0] t
   * for t <= dT[0]; phi_0(t) = F(t) - dF0, dF0 = F(0) */
  size_t dn;
  double *dT, *dV, *dS, *dP, dF0;
  /* a MOTOR drive: phi_0 at y[im], Omega at y[im + 1]; the torque table (mn points: speeds mW,
   * torques mL; mn = 0: linear characteristic); Jeff = J + sum_j m_j0 r_j0^2 (kg m^2) */
  int motor;
  size_t im, mn;
  double *mW, *mL, Jeff;
  /* friction (docs/device.md section 3): the law, per ball f, mu, the workspace fs (f times the
   * sign or tanh of the current call) and the EXACT law's modes (mode0: a copy at the entry of
   * autobal_rotor_friction_settle); gravity inputs gu, gv (m/s^2: the in-plane gravity enters
   * every ball equation as the acceleration (gu, gv) of D, fixed axes; (0, g sin theta) with gravity on, else 0),
   * Wtot = M + all small masses, Dm = sum_j d_j m_j (for the weights' rows);
   * the cache of autobal_rotor_friction_switch: (t, frame, y copy) -> N, H */
  int law;
  double inv_ueps, gu, gv, Wtot, Dm;
  double *f, *mu, *fws, *cN, *cH, *pd0, *ycache, cache_t;
  int *mode, *mode0, cache_ok, cache_frame;
  double *store;
  /* gravity (docs/device.md section 2): g_s = g sin(theta) (m/s^2), the weights g_s W on y (N)
   * and g_s sum_j d_j m_j on alpha (N m), W = M + all small masses; all 0 when off */
  double gs, gW, gD;
  /* rolling inertia (docs/device.md section 3): on, per ball rho (m), rk = 5/7 (the inverse relative
   * inertia) and re = 2/5 (1 + rho/r) (the Omega' coefficient of the ball equation over m r^2);
   * rk = 1, re = 0 when off */
  int rolling;
  double *rho, *rk, *re;
  /* contact (docs/device.md section 4): on, restitution e, resting speed v_rest (rad/s); per ball
   * delta (m); the pairs of neighbours on a track (np of them: pb behind, pa ahead, gap angle pg,
   * offset pc: a multiple of 2 pi fixed by the order, see pair_gap), their cluster flags pact and
   * contact forces plam (N m, of the last evaluation); workspaces: cQ (N), cW ((CMAX + 1) dim),
   * cG (CMAX^2), the event cache (t, frame, y copy in cy) */
  int contact, *pact, ccache_ok, ccache_frame;
  /* with the EXACT law: cfree[k] = 1 for a ball set free by an impact's impulse (stuck balls outside the
   * impact's clusters stay fixed to the rotor), cleared by the friction settle; modein, reach: the
   * modes at the entry of autobal_rotor_hybrid_settle and which slipping balls had reached psi' = 0
   * (for its counts); nsplit: stuck chains split by the friction settle (counted as releases) */
  int *cfree, *modein, *reach;
  size_t np, *pb, *pa, nsplit;
  double e_rest, v_rest, *delta, *pg, *pc, *plam, *cQ, *cW, *cG, *cy, ccache_t;
  double *cstore;
  double qs[4]; /* the static offset (autobal_rotor_static_offset; 0 without gravity): amplitudes about it */
  size_t nout;  /* autobal_rotor_output_count, fixed at allocation (checked by every outputs call) */
  autobal_error err;
};

/* ---- helpers ------------------------------------------------------------ */

/* The balls' sines and cosines are computed by one vectorizable loop
 * (fastmath.h), compiled twice, for AVX2 and for the baseline x86-64, and the
 * best is picked when the library is loaded (GCC function multiversioning, as
 * in src/analysis/pendulum_map.c).  No FMA in either: both clones give the same bits. */
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 8 && defined(__x86_64__) && \
    defined(__linux__) && !defined(AUTOBAL_NO_CLONES)
#define ROTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define ROTOR_CLONES
#endif

/* sn[k] = sin x[k], cs[k] = cos x[k], k < n (x must not overlap sn, cs); libm
 * for |x[k]| > AUTOBAL_SINCOS_MAX or non-finite x[k]. */
ROTOR_CLONES static void ball_sincos(const double *restrict x, double *restrict sn,
                                     double *restrict cs, size_t n) {
  (void)autobal_sincos_array(x, sn, cs, n);
}

/* Antiderivative F(t) of the drive table and Omega, Omega' at t (dn >= 1): constant dV[0]
 * before dT[0], linear between the points (the interval [dT[k], dT[k+1]) found by binary
 * search), constant dV[dn-1] after the last. */
static double drive_F(const autobal_rotor *R, double t, double *W, double *Wd) {
  const size_t n = R->dn;
  const double *T = R->dT, *V = R->dV;
  size_t lo, hi;
  double tau;
  if (t < T[0]) {
    *W = V[0];
    *Wd = 0.0;
    return V[0] * t;
  }
  if (t >= T[n - 1]) {
    *W = V[n - 1];
    *Wd = 0.0;
    return R->dP[n - 1] + V[n - 1] * (t - T[n - 1]);
  }
  lo = 0; /* T[lo] <= t < T[hi] */
  hi = n - 1;
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (T[mid] <= t) lo = mid;
    else hi = mid;
  }
  tau = t - T[lo];
  *Wd = R->dS[lo];
  *W = V[lo] + R->dS[lo] * tau;
  return R->dP[lo] + tau * (V[lo] + 0.5 * R->dS[lo] * tau);
}

/* The prescribed spin at t: Omega, Omega' and phi_0 = integral_0^t Omega.  The constant drive
 * is (omega, 0, omega t), computed exactly as the constant-speed model always did. */
static void drive_eval(const autobal_rotor *R, double t, double *W, double *Wd, double *ph0) {
  if (R->dn == 0) {
    *W = R->p.omega;
    *Wd = 0.0;
    *ph0 = R->p.omega * t;
    return;
  }
  *ph0 = drive_F(R, t, W, Wd) - R->dF0;
}

/* Omega and phi_0 of the state: the prescribed drive at t, or a MOTOR's state entries. */
static void spin_state(const autobal_rotor *R, double t, const double *y, double *W, double *ph0) {
  double Wd;
  if (R->motor) {
    *ph0 = y[R->im];
    *W = y[R->im + 1];
    return;
  }
  drive_eval(R, t, W, &Wd, ph0);
}

/* The motor characteristic L(Omega) (N m): linear L_0 (1 - Omega/omega_0), or the table, linear
 * between its points (binary search) and constant outside. */
static double motor_L(const autobal_rotor *R, double W) {
  const size_t n = R->mn;
  const double *X = R->mW, *Y = R->mL;
  size_t lo, hi;
  if (n == 0) return R->p.drive.L_0 * (1.0 - W / R->p.drive.omega_0);
  if (!(W > X[0])) return Y[0];
  if (W >= X[n - 1]) return Y[n - 1];
  lo = 0; /* X[lo] < W < X[hi] (or W == X[lo]) */
  hi = n - 1;
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (X[mid] <= W) lo = mid;
    else hi = mid;
  }
  return Y[lo] + (Y[hi] - Y[lo]) * ((W - X[lo]) / (X[hi] - X[lo]));
}

/* Wrap an angle to (-pi, pi].  For |a| <= 3 the formula gives a + 0 (ceil of a value in (-1, 0)
 * is -0): taken directly, the same number bit for bit (-0 becomes +0 as in the formula). */
static inline double wrap_pi_formula(double a) {
  double w = a - 2.0 * M_PI * ceil((a - M_PI) / (2.0 * M_PI));
  if (w <= -M_PI) w += 2.0 * M_PI;
  if (w > M_PI) w -= 2.0 * M_PI;
  return w;
}
static double wrap_pi(double a) {
  if (fabs(a) <= 3.0) return a + 0.0;
  return wrap_pi_formula(a);
}

/* Solve a symmetric positive definite 4x4 system by the root-free Cholesky
 * factorization a = L D L^T (L unit lower triangular; the lower triangle of a
 * is used and overwritten with L); b is overwritten with the solution.  The
 * pivots D_jj are those of the Cholesky factorization squared; returns 0, or -1
 * when a pivot is not positive relative to the diagonal entry a_jj (or NaN).
 * No square roots and one division per pivot (the solve multiplies by 1/D_jj). */
static int ldl4_factor(double a[4][4], double dinv[4]) {
  double dg[4], v[4];
  int i, j, k;
  for (j = 0; j < 4; j++) {
    double s = a[j][j];
    for (k = 0; k < j; k++) {
      v[k] = a[j][k] * dg[k]; /* L_jk D_kk */
      s -= a[j][k] * v[k];
    }
    if (!(s > 1e-13 * fabs(a[j][j]))) return -1;
    dg[j] = s;
    dinv[j] = 1.0 / s;
    for (i = j + 1; i < 4; i++) {
      double t = a[i][j];
      for (k = 0; k < j; k++) t -= a[i][k] * v[k];
      a[i][j] = t * dinv[j];
    }
  }
  return 0;
}

/* The substitutions of ldl4_factor's factorization for one right-hand side b (overwritten). */
static void ldl4_subst(double a[4][4], const double dinv[4], double b[4]) {
  int i, k;
  for (i = 0; i < 4; i++) { /* L z = b */
    double s = b[i];
    for (k = 0; k < i; k++) s -= a[i][k] * b[k];
    b[i] = s;
  }
  for (i = 3; i >= 0; i--) { /* L^T x = D^-1 z */
    double s = b[i] * dinv[i];
    for (k = i + 1; k < 4; k++) s -= a[k][i] * b[k];
    b[i] = s;
  }
}

/* Rotor part of (3.2) / (3.5)-(3.8) with everything but the mass terms moved
 * to the right: b = -(damping + gyroscopic + stiffness forces). */
static void rotor_forces(const autobal_rotor_lumped *L, double omega, double omega_rate,
                         const double *q, const double *qd, double b[4]) {
  const double x = q[0], yy = q[1], al = q[2], be = q[3];
  const double xd = qd[0], yd = qd[1], ald = qd[2], bed = qd[3];
  b[0] = -(L->h_x * xd + L->c_x * x - L->h_xbeta * bed - L->c_xbeta * be);
  b[1] = -(L->h_y * yd + L->c_y * yy + L->h_yalpha * ald + L->c_yalpha * al);
  b[2] = -(L->h_alpha * ald + L->c_alpha * al + L->C * omega * bed + L->h_yalpha * yd +
           L->c_yalpha * yy);
  b[3] = -(L->h_beta * bed + L->c_beta * be - L->C * omega * ald - L->h_xbeta * xd -
           L->c_xbeta * x);
  /* a varying spin: d/dt (C Omega beta) = C Omega beta' + C Omega' beta in the alpha equation
   * (the spin kinetic energy 1/2 C (Omega + alpha' beta)^2 of the Resal angles); skipped when
   * Omega' = 0, so that a constant speed gives the constant-speed model's bits */
  if (omega_rate != 0.0) b[2] -= L->C * omega_rate * be;
}

/* How the unbalance of one plane (fixed axes u, v) depends on the accelerations:
 *   s_u'' = Suu u_D'' + Suv v_D'' + Fu,   s_v'' = Suv u_D'' + Svv v_D'' + Fv,
 * with u_D'' = eu . q'', v_D'' = ev . q'' (3.3), eu = (1, 0, 0, d), ev = (0, 1, -d, 0).
 * In (3.2)/(3.5)-(3.8) s_u'' enters the rows along eu and s_v'' along ev, so the
 * plane adds U C U^T to the mass matrix diag(M, M, A, A) and -U (Fu, Fv) to the
 * right-hand side, U = [eu ev], C = [[Suu, Suv], [Suv, Svv]].  In the FULL inertia
 * model Suu and Svv include mfull (the term mfull (eu eu^T + ev ev^T)). */
typedef struct plane_coupling {
  double Suu, Suv, Svv; /* kg */
  double Fu, Fv;        /* N */
} plane_coupling;

/* Lower triangle of a += U C U^T for one plane (see plane_coupling). */
static void add_plane_mass(double a[4][4], double d, const plane_coupling *c) {
  a[0][0] += c->Suu;
  a[1][0] += c->Suv;
  a[1][1] += c->Svv;
  a[2][0] -= c->Suv * d;
  a[2][1] -= c->Svv * d;
  a[2][2] += c->Svv * d * d;
  a[3][0] += c->Suu * d;
  a[3][1] += c->Suv * d;
  a[3][2] -= c->Suv * (d * d);
  a[3][3] += c->Suu * d * d;
}

/* One plane, closed form (see solve_accelerations): q'' and (u_D'', v_D'') for the right-hand
 * side b, given S = I + g C through s11, s12, s22 and 1/det S. */
static void one_plane_apply(const autobal_rotor *R, const plane_coupling *c, double s11, double s12,
                            double s22, double idet, const double b[4], double qdd[4], double uv[2]) {
  const double d = R->p.plane[0].d, iM = R->inv_M, iA = R->inv_A;
  const double ru = b[0] * iM + d * b[3] * iA; /* U^T D^-1 b */
  const double rv = b[1] * iM - d * b[2] * iA;
  const double wu = (s22 * ru - s12 * rv) * idet;
  const double wv = (s11 * rv - s12 * ru) * idet;
  const double cu = c->Suu * wu + c->Suv * wv; /* (cu, cv) = C w; U C w = (cu, cv, -d cv, d cu) */
  const double cv = c->Suv * wu + c->Svv * wv;
  qdd[0] = (b[0] - cu) * iM;
  qdd[1] = (b[1] - cv) * iM;
  qdd[2] = (b[2] + d * cv) * iA;
  qdd[3] = (b[3] - d * cu) * iA;
  uv[0] = wu;
  uv[1] = wv;
}

/* Solve the rotor equations (3.2) (one plane) or (3.5)-(3.8) (two planes) with
 * the planes' couplings substituted,
 *   a q'' = b - sum_j U_j (Fu_j, Fv_j),   a = D + sum_j U_j C_j U_j^T,  D = diag(M, M, A, A),
 * for q'' = (x'', y'', alpha'', beta''), and the accelerations of the planes'
 * centres uvdd[j] = (u_jD'', v_jD'') = U_j^T q'' (3.3).  b is overwritten.
 * With b1 != NULL (a MOTOR drive) also a q1'' = b1 with the same matrix (b1 overwritten; its
 * results in qdd1, uvdd1).
 * Returns 0, or -1 when a is not positive definite (one plane: see below; two
 * planes: a Cholesky pivot not positive relative to the diagonal entry) or a
 * result is not finite. */
static int solve_accelerations(const autobal_rotor *R, const plane_coupling *cp, double b[4],
                               double qdd[4], double uvdd[][2], double *b1, double *qdd1,
                               double uvdd1[][2]) {
  size_t j;
  for (j = 0; j < R->n_planes; j++) { /* b -= Fu eu + Fv ev */
    const double d = R->p.plane[j].d;
    b[0] -= cp[j].Fu;
    b[1] -= cp[j].Fv;
    b[2] += d * cp[j].Fv;
    b[3] -= d * cp[j].Fu;
  }
  if (R->n_planes == 1) {
    /* One plane, in closed form.  With w = U^T q'' = (u_D'', v_D''), a q'' = b reads
     * D q'' + U C w = b, so q'' = D^-1 (b - U C w); applying U^T gives
     *   (I + G C) w = U^T D^-1 b,   G = U^T D^-1 U = g I,   g = 1/M + d^2/A
     * (eu and ev have disjoint supports, so G is diagonal).  D^-1/2 a D^-1/2 has the
     * eigenvalues 1, 1 and those of I + g C: a is positive definite iff the 2x2
     * S = I + g C is.  S counts as positive definite when tr S > 0 and
     * det S > 1e-13 (tr S)^2, i.e. lambda_min / lambda_max > about 1e-13: a test
     * invariant under rotations of the (u, v) axes, so both frames agree on it. */
    const plane_coupling *c = &cp[0];
    const double g = R->g[0];
    const double s11 = 1.0 + g * c->Suu, s12 = g * c->Suv, s22 = 1.0 + g * c->Svv;
    const double det = s11 * s22 - s12 * s12, tr = s11 + s22;
    double idet;
    if (!(tr > 0.0) || !(det > 1e-13 * tr * tr)) return -1; /* also catches NaN */
    idet = 1.0 / det;
    one_plane_apply(R, c, s11, s12, s22, idet, b, qdd, uvdd[0]);
    if (b1) one_plane_apply(R, c, s11, s12, s22, idet, b1, qdd1, uvdd1[0]);
  } else {
    /* Two planes: the 4x4 system by a root-free Cholesky (L D L^T) solve. */
    double a[4][4], dinv[4];
    memset(a, 0, sizeof a);
    a[0][0] = R->L.M;
    a[1][1] = R->L.M;
    a[2][2] = R->L.A;
    a[3][3] = R->L.A;
    for (j = 0; j < R->n_planes; j++) add_plane_mass(a, R->p.plane[j].d, &cp[j]);
    if (ldl4_factor(a, dinv) != 0) return -1;
    ldl4_subst(a, dinv, b);
    for (j = 0; j < 4; j++) qdd[j] = b[j];
    if (b1) {
      ldl4_subst(a, dinv, b1);
      for (j = 0; j < 4; j++) qdd1[j] = b1[j];
    }
    for (j = 0; j < R->n_planes; j++) {
      const double d = R->p.plane[j].d;
      uvdd[j][0] = qdd[0] + d * qdd[3]; /* eq. (3.3) */
      uvdd[j][1] = qdd[1] - d * qdd[2];
      if (b1) {
        uvdd1[j][0] = qdd1[0] + d * qdd1[3];
        uvdd1[j][1] = qdd1[1] - d * qdd1[2];
      }
    }
  }
  if (!isfinite(qdd[0] + qdd[1] + qdd[2] + qdd[3])) return -1;
  for (j = 0; j < R->n_planes; j++)
    if (!isfinite(uvdd[j][0] + uvdd[j][1])) return -1;
  return 0;
}

/* MOTOR: the rotor right-hand side per unit Omega', b1 = -g with g the coupling of the phi_0
 * equation, g . q'' = C beta alpha'' + sum_j m_j0 r_j0 (-u_jD'' sin th_j + v_jD'' cos th_j)
 * (th_j = phi_0 + psi_j0; (sw, cw) = sin, cos phi_0): the term C Omega' beta of the alpha
 * equation and the unbalance's tangential acceleration m_j0 r_j0 Omega' (-sin th, cos th) in
 * s'' (docs/device.md, "Fixed-frame equations"); the same in both frames. */
static void motor_b1(const autobal_rotor *R, double sw, double cw, double beta, double b1[4]) {
  size_t j;
  b1[0] = 0.0;
  b1[1] = 0.0;
  b1[2] = -R->L.C * beta;
  b1[3] = 0.0;
  for (j = 0; j < R->n_planes; j++) {
    const double d = R->p.plane[j].d;
    const double sth = R->s0[j] * (sw * R->cpsi0[j] + cw * R->spsi0[j]); /* m0 r0 sin th */
    const double cth = R->s0[j] * (cw * R->cpsi0[j] - sw * R->spsi0[j]); /* m0 r0 cos th */
    b1[0] += sth;
    b1[1] -= cth;
    b1[2] += d * cth;
    b1[3] += d * sth;
  }
}

/* MOTOR: Omega' from the phi_0 equation with q'' = q0'' + Omega' q1'' (q0'': the solve without
 * the Omega' terms, q1'': per unit Omega'):
 *   Jeff Omega' - b1 . q'' + C alpha' beta' = L(Omega) - k_r Omega + tb,
 * tb = sum h r^2 (phi' - Omega) the balls' resistance torque on the rotor; then q'' and the
 * planes' (u_D'', v_D'') completed.  Returns 0, or -1 when the Schur complement
 * Jeff - b1 . q1'' is not positive (relative 1e-13) or a result is not finite. */
static int motor_complete(const autobal_rotor *R, const double y[], double omega, double tb,
                          const double b1[4], double qdd[4], const double qdd1[4], double uvdd[][2],
                          double uvdd1[][2], double *omega_rate) {
  const autobal_rotor_drive *dr = &R->p.drive;
  const double den = R->Jeff - (b1[0] * qdd1[0] + b1[1] * qdd1[1] + b1[2] * qdd1[2] + b1[3] * qdd1[3]);
  double rhs = motor_L(R, omega) - dr->k_r * omega + tb - R->L.C * y[6] * y[7] +
               (b1[0] * qdd[0] + b1[1] * qdd[1] + b1[2] * qdd[2] + b1[3] * qdd[3]);
  double wd;
  size_t j;
  /* gravity (docs/device.md section 2): the unbalance's weight torque g_s sum_j m_j0 r_j0 cos th_j
   * on the left of the phi_0 equation; b1[1] = -sum_j m_j0 r_j0 cos th_j (motor_b1) */
  if (R->gs != 0.0) rhs += R->gs * b1[1];
  if (!(den > 1e-13 * R->Jeff)) return -1;
  wd = rhs / den;
  if (!isfinite(wd)) return -1;
  for (j = 0; j < 4; j++) qdd[j] += wd * qdd1[j];
  for (j = 0; j < R->n_planes; j++) {
    uvdd[j][0] += wd * uvdd1[j][0];
    uvdd[j][1] += wd * uvdd1[j][1];
  }
  for (j = 0; j < R->n_planes; j++)
    if (!isfinite(uvdd[j][0] + uvdd[j][1])) return -1;
  *omega_rate = wd;
  return isfinite(qdd[0] + qdd[1] + qdd[2] + qdd[3]) ? 0 : -1;
}

/* The balls' accelerations of a right-hand side finite?  They are written after the rotor's
 * (which the solves check): a huge but finite state (|phi'| near 1e304) can still overflow
 * h/m (phi' - Omega).  Branch-free (vectorizable). */
static int ball_rows_finite(const double *dydt, size_t N) {
  int ok = 1;
  size_t k;
  for (k = 0; k < N; k++) ok &= fabs(dydt[8 + N + k]) <= DBL_MAX;
  return ok;
}

static int rhs_fail(autobal_rotor *R, double t, const char *which) {
  autobal_error_set(&R->err, AUTOBAL_ENUMERIC,
                    "%s right-hand side failed at t = %.17g s: the effective mass matrix is not "
                    "positive definite or the state is not finite",
                    which, t);
  return GSL_EBADFUNC;
}

/* The rows both right-hand sides share: q' = qd, q'' from the solve, the
 * balls' angle rates (y[8 + N + k]) and the axial equation (2.12). */
static void rhs_common_rows(const autobal_rotor *R, const double y[], const double qdd[4],
                            double dydt[]) {
  const size_t N = R->N;
  size_t k;
  for (k = 0; k < 4; k++) {
    dydt[k] = y[4 + k];
    dydt[4 + k] = qdd[k];
  }
  for (k = 0; k < N; k++) dydt[8 + k] = y[8 + N + k];
  if (R->p.axial) { /* eq. (2.12) */
    const double z = y[8 + 2 * N], zd = y[9 + 2 * N];
    dydt[8 + 2 * N] = zd;
    dydt[9 + 2 * N] = -(R->L.h_z * zd + R->L.c_z * z) / R->L.M;
  }
}

/* ---- right-hand sides ------------------------------------------------------ */

/* Both right-hand sides make three passes over the balls: (1) sin and cos of
 * every ball angle into the workspace (one vectorizable loop over all N balls,
 * fastmath.h; libm above |angle| = 2^21 rad), (2) per plane, the sums of
 * "Solving for the accelerations" (in ball order, so the result does not
 * depend on the vector width), (3) after the 4x4 (or 2x2) solve, the ball
 * accelerations from the stored sines and cosines (elementwise). */

static int fric_eval_full(const autobal_rotor *R, double *ws, autobal_error *errp, int frame, double t,
                          const double y[], double dydt[], double *Nout, double *Hout, int check_N, const double *Q,
                          int nofric, const size_t *plist, size_t nw, double *Wr);
static int fric_eval(const autobal_rotor *R, double *ws, autobal_error *errp, int frame, double t, const double y[],
                     double dydt[], double *Nout, double *Hout, int check_N, const double *Q, int nofric) {
  return fric_eval_full(R, ws, errp, frame, t, y, dydt, Nout, Hout, check_N, Q, nofric, NULL, 0, NULL);
}
static int contact_rhs(autobal_rotor *R, int frame, double t, const double y[], double dydt[]);
static int contact_solve(autobal_rotor *R, int frame, double t, const double *y, double *dydt);
static size_t active_list(const autobal_rotor *R, size_t *list, int impulse);
static int pair_rigid(const autobal_rotor *R, size_t p, int impulse);

int autobal_rotor_rhs(double t, const double y[], double dydt[], void *rotor) {
  autobal_rotor *R = (autobal_rotor *)rotor;
  if (R->contact) return contact_rhs(R, AUTOBAL_ROTOR_FIXED, t, y, dydt);
  if (R->law != AUTOBAL_ROTOR_FRICTION_NONE || R->rolling)
    return fric_eval(R, R->fws, &R->err, AUTOBAL_ROTOR_FIXED, t, y, dydt, NULL, NULL,
                     R->law != AUTOBAL_ROTOR_FRICTION_NONE, NULL, 0);
  const size_t N = R->N;
  const double *q = y, *qd = y + 4, *phi = y + 8, *phid = y + 8 + N;
  const double *sn = R->sn, *cs = R->cs;
  plane_coupling cp[AUTOBAL_ROTOR_MAX_PLANES] = {{0.0, 0.0, 0.0, 0.0, 0.0}};
  double b[4], qdd[4], uvdd[AUTOBAL_ROTOR_MAX_PLANES][2], sw, cw, omega, omega_rate, phi0, w2;
  double b1[4], b1s[4], qdd1[4], uvdd1[AUTOBAL_ROTOR_MAX_PLANES][2], tb = 0.0;
  size_t j, k;

  if (R->motor) { /* phi_0 and Omega from the state; the Omega' terms are solved for below */
    phi0 = y[R->im];
    omega = y[R->im + 1];
    omega_rate = 0.0;
  } else {
    drive_eval(R, t, &omega, &omega_rate, &phi0); /* Omega(t), Omega'(t), phi_0(t) */
  }
  w2 = omega * omega;
  autobal_sincos1(phi0, &sw, &cw);
  ball_sincos(phi, R->sn, R->cs, N);
  rotor_forces(&R->L, omega, omega_rate, q, qd, b);
  if (R->gs != 0.0) b[1] -= R->gW, b[2] += R->gD; /* the weights (docs/device.md section 2) */
  for (j = 0; j < R->n_planes; j++) {
    double Sss = 0.0, Ssc = 0.0, Scc = 0.0, Fu = 0.0, Fv = 0.0;
    const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
    for (k = k0; k < k1; k++) {
      const double s = sn[k], c = cs[k], m = R->m[k], pd = phid[k];
      const double ms = m * s, mc = m * c;
      const double a = R->hr[k] * (pd - omega), bc = R->mr[k] * pd * pd;
      Sss += ms * s;
      Ssc += ms * c;
      Scc += mc * c;
      /* F_u, F_v of "Solving for the accelerations" */
      Fu += a * s - bc * c;
      Fv -= a * c + bc * s;
    }
    {
      /* the unbalance at phi_0(t) + psi_j0: phi_0' = Omega, phi_0'' = Omega' (added last:
       * the sums over the balls do not wait for sin, cos of phi_0):
       * s_u'' = -m0 r0 (Omega^2 cos + Omega' sin), s_v'' = -m0 r0 (Omega^2 sin - Omega' cos) */
      const double c0 = cw * R->cpsi0[j] - sw * R->spsi0[j];
      const double s0 = sw * R->cpsi0[j] + cw * R->spsi0[j];
      const double w2s0 = w2 * R->s0[j];
      Fu -= w2s0 * c0;
      Fv -= w2s0 * s0;
      if (omega_rate != 0.0) {
        const double wds0 = omega_rate * R->s0[j];
        Fu -= wds0 * s0;
        Fv += wds0 * c0;
      }
    }
    /* gravity: the balls' phi'' gain -g_s cos(phi)/r (v_D'' -> v_D'' + g_s in (3.4)) */
    if (R->gs != 0.0) Fu += R->gs * Ssc, Fv -= R->gs * Scc;
    /* s_u'' = -S_ss u_D'' + S_sc v_D'' + F_u, s_v'' = S_sc u_D'' - S_cc v_D'' + F_v */
    cp[j].Suu = -Sss + R->mtot[j];
    cp[j].Suv = Ssc;
    cp[j].Svv = -Scc + R->mtot[j];
    cp[j].Fu = Fu;
    cp[j].Fv = Fv;
  }
  if (R->motor) {
    motor_b1(R, sw, cw, q[3], b1);
    memcpy(b1s, b1, sizeof b1);
    for (k = 0; k < N; k++) tb += R->hr[k] * R->r[k] * (phid[k] - omega);
  }
  if (solve_accelerations(R, cp, b, qdd, uvdd, R->motor ? b1s : NULL, qdd1, uvdd1) != 0 ||
      (R->motor && motor_complete(R, y, omega, tb, b1, qdd, qdd1, uvdd, uvdd1, &omega_rate) != 0))
    return rhs_fail(R, t, "fixed-frame");

  rhs_common_rows(R, y, qdd, dydt);
  for (j = 0; j < R->n_planes; j++) {
    /* eq. (3.3); gravity acts on the balls as an upward acceleration g_s of D */
    const double uDdd = uvdd[j][0], vDdd = R->gs != 0.0 ? uvdd[j][1] + R->gs : uvdd[j][1];
    const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
    for (k = k0; k < k1; k++) /* eq. (3.4) solved for phi_i'' */
      dydt[8 + N + k] = (uDdd * sn[k] - vDdd * cs[k]) / R->r[k] - R->kappa[k] * (phid[k] - omega);
  }
  if (!ball_rows_finite(dydt, N)) return rhs_fail(R, t, "fixed-frame");
  if (R->motor) {
    dydt[R->im] = omega;
    dydt[R->im + 1] = omega_rate;
  }
  return GSL_SUCCESS;
}

int autobal_rotor_rhs_rotating(double t, const double y[], double dydt[], void *rotor) {
  autobal_rotor *R = (autobal_rotor *)rotor;
  if (R->contact) return contact_rhs(R, AUTOBAL_ROTOR_ROTATING, t, y, dydt);
  if (R->law != AUTOBAL_ROTOR_FRICTION_NONE || R->rolling)
    return fric_eval(R, R->fws, &R->err, AUTOBAL_ROTOR_ROTATING, t, y, dydt, NULL, NULL,
                     R->law != AUTOBAL_ROTOR_FRICTION_NONE, NULL, 0);
  const size_t N = R->N;
  const double *q = y, *qd = y + 4, *psi = y + 8, *psid = y + 8 + N;
  const double *sn = R->sn, *cs = R->cs;
  plane_coupling cp[AUTOBAL_ROTOR_MAX_PLANES] = {{0.0, 0.0, 0.0, 0.0, 0.0}};
  double b[4], qdd[4], uvdd[AUTOBAL_ROTOR_MAX_PLANES][2], sw, cw, omega, omega_rate, phi0, w2;
  double b1[4], b1s[4], qdd1[4], uvdd1[AUTOBAL_ROTOR_MAX_PLANES][2], tb = 0.0;
  size_t j, k;

  if (R->motor) { /* phi_0 and Omega from the state; the Omega' terms are solved for below */
    phi0 = y[R->im];
    omega = y[R->im + 1];
    omega_rate = 0.0;
  } else {
    drive_eval(R, t, &omega, &omega_rate, &phi0); /* Omega(t), Omega'(t), phi_0(t) */
  }
  w2 = omega * omega;
  autobal_sincos1(phi0, &sw, &cw);
  ball_sincos(psi, R->sn, R->cs, N);
  rotor_forces(&R->L, omega, omega_rate, q, qd, b);
  if (R->gs != 0.0) b[1] -= R->gW, b[2] += R->gD; /* the weights (docs/device.md section 2) */
  for (j = 0; j < R->n_planes; j++) {
    /* rotor-axes quantities (3.10): s_xi, s_eta and their rates */
    double sxi = R->s0[j] * R->cpsi0[j], seta = R->s0[j] * R->spsi0[j];
    double sxid = 0.0, setad = 0.0;
    /* s_xi'' = Txx a_xi + Txe a_eta + Gxi, s_eta'' = Txe a_xi + Tee a_eta + Geta,
     * from s_xi'' = -sum m r (psi'' sin + psi'^2 cos), s_eta'' = sum m r (psi'' cos - psi'^2 sin)
     * and (3.13): psi'' = (a_xi sin psi - a_eta cos psi) / r - (h/m) psi' */
    double Txx = 0.0, Txe = 0.0, Tee = 0.0, Gxi = 0.0, Geta = 0.0;
    const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
    for (k = k0; k < k1; k++) {
      const double s = sn[k], c = cs[k], m = R->m[k], mr = R->mr[k], pd = psid[k];
      const double ms = m * s, mc = m * c, mrs = mr * s, mrc = mr * c;
      const double a = R->hr[k] * pd, bp = mr * pd * pd;
      sxi += mrc;
      seta += mrs;
      sxid -= mrs * pd;
      setad += mrc * pd;
      Txx -= ms * s;
      Txe += ms * c;
      Tee -= mc * c;
      Gxi += a * s - bp * c;
      Geta -= a * c + bp * s;
    }
    if (R->gs != 0.0) {
      /* gravity: (a_xi, a_eta) -> (a_xi - g_xi, a_eta - g_eta) in (3.13), g on the rotor axes
       * (g_xi, g_eta) = -g_s (sin phi_0, cos phi_0) */
      Gxi += R->gs * (Txx * sw + Txe * cw);
      Geta += R->gs * (Txe * sw + Tee * cw);
    }
    {
      /* (3.11) differentiated twice:
       * s_u'' = (s_xi'' - 2w s_eta' - w^2 s_xi) cos wt - (s_eta'' + 2w s_xi' - w^2 s_eta) sin wt
       * s_v'' = (s_xi'' - 2w s_eta' - w^2 s_xi) sin wt + (s_eta'' + 2w s_xi' - w^2 s_eta) cos wt */
      double cxi = Gxi - 2.0 * omega * setad - w2 * sxi;
      double ceta = Geta + 2.0 * omega * sxid - w2 * seta;
      if (omega_rate != 0.0) {
        /* with phi_0'' = Omega' the rotation adds Omega' J (s_xi, s_eta) = Omega' (-s_eta, s_xi)
         * to the bracket, and (3.13) adds -Omega' to every psi_i'', i.e. Omega' times the balls'
         * sum m r (sin psi, -cos psi) to (s_xi'', s_eta''): together only the unbalance's
         * tangential acceleration remains, Omega' m0 r0 (-sin psi0, cos psi0) */
        cxi -= omega_rate * R->s0[j] * R->spsi0[j];
        ceta += omega_rate * R->s0[j] * R->cpsi0[j];
      }
      /* (a_xi, a_eta) = Rot^T (u_D'', v_D''): the fixed-axes coupling is Rot T Rot^T */
      const double t00 = cw * Txx - sw * Txe, t01 = cw * Txe - sw * Tee; /* Rot T, row 0 */
      const double t10 = sw * Txx + cw * Txe, t11 = sw * Txe + cw * Tee; /* Rot T, row 1 */
      cp[j].Suu = t00 * cw - t01 * sw + R->mtot[j];
      cp[j].Suv = t00 * sw + t01 * cw;
      cp[j].Svv = t10 * sw + t11 * cw + R->mtot[j];
      cp[j].Fu = cxi * cw - ceta * sw;
      cp[j].Fv = cxi * sw + ceta * cw;
    }
  }
  if (R->motor) {
    /* the coupling per unit Omega' in fixed axes is the fixed frame's (see the Omega' terms
     * above: only the unbalance's tangential acceleration and C Omega' beta remain) */
    motor_b1(R, sw, cw, q[3], b1);
    memcpy(b1s, b1, sizeof b1);
    for (k = 0; k < N; k++) tb += R->hr[k] * R->r[k] * psid[k];
  }
  if (solve_accelerations(R, cp, b, qdd, uvdd, R->motor ? b1s : NULL, qdd1, uvdd1) != 0 ||
      (R->motor && motor_complete(R, y, omega, tb, b1, qdd, qdd1, uvdd, uvdd1, &omega_rate) != 0))
    return rhs_fail(R, t, "rotating-frame");

  rhs_common_rows(R, y, qdd, dydt);
  for (j = 0; j < R->n_planes; j++) {
    /* eq. (3.3); gravity acts on the balls as an upward acceleration g_s of D */
    const double uDdd = uvdd[j][0], vDdd = R->gs != 0.0 ? uvdd[j][1] + R->gs : uvdd[j][1];
    /* acceleration of D on the rotor axes (docs/rotor.md, after (3.13)) */
    const double axi = uDdd * cw + vDdd * sw, aeta = -uDdd * sw + vDdd * cw;
    const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
    for (k = k0; k < k1; k++) /* eq. (3.13) divided by m r^2; psi'' = phi'' - Omega' */
      dydt[8 + N + k] = (axi * sn[k] - aeta * cs[k]) / R->r[k] - R->kappa[k] * psid[k];
    if (omega_rate != 0.0)
      for (k = k0; k < k1; k++) dydt[8 + N + k] -= omega_rate;
  }
  if (!ball_rows_finite(dydt, N)) return rhs_fail(R, t, "rotating-frame");
  if (R->motor) {
    dydt[R->im] = omega;
    dydt[R->im + 1] = omega_rate;
  }
  return GSL_SUCCESS;
}

/* ---- friction (docs/device.md section 3) ----------------------------------------------------- */

/* The friction path of both right-hand sides (and of the force functions): the balls' equations
 * written in the fixed axes for both frames (rotating frame: the ball's absolute sin, cos from
 * those of psi and phi_0; phi' = psi' + Omega).  A slipping ball, fs = f sgn(psi') (EXACT: the
 * sign of its mode; REGULARIZED: f tanh(psi'/u_eps)), with (au, av) = (u_D'' + gu, v_D'' + gv):
 *   m r [r phi'' - au sin + av cos] + h r^2 psi' + r fs N = 0,  N = m [r phi'^2 - au cos - av sin],
 *   phi'' = (Au au + Av av) / r - kappa psi' - fs phi'^2,  Au = sin + fs cos,  Av = fs sin - cos,
 * so its s'' depends on (u_D'', v_D'') through the NON-symmetric 2x2 C = [[-m s Au, -m s Av],
 * [m c Au, m c Av]] (f = 0: the matrix of plane_coupling).  A stuck ball (EXACT) is an unbalance:
 * phi' = Omega, phi'' = Omega'.  The rotor rows a q'' = b - U F, a = D + sum U C U^T, are solved
 * exactly (one plane: the 2x2 closed form with the non-symmetric S = I + g C; two planes: 4x4 LU
 * with partial pivoting); a MOTOR adds the Omega' column b1 and the phi_0 row G . q'' + Jeff' Omega'
 * = RHS with G != -b1 (the reaction torques r fs N contain D's accelerations). */
typedef struct fric_plane {
  double Cuu, Cuv, Cvu, Cvv; /* kg */
  double Fu, Fv;             /* N */
  double Pu, Pv;             /* motor row: coefficients of u_D'', v_D'' (kg m) */
} fric_plane;

/* 4x4 LU with partial pivoting of a (overwritten), solving for nb right-hand sides x[0..nb-1]
 * (overwritten).  -1 when a pivot is below 1e-13 times the largest diagonal entry of a. */
static int lu4_solve(double a[4][4], double x[][4], int nb) {
  double scale = 0.0;
  int i, j, k, c;
  for (i = 0; i < 4; i++)
    if (fabs(a[i][i]) > scale) scale = fabs(a[i][i]);
  for (k = 0; k < 4; k++) {
    int piv = k;
    for (i = k + 1; i < 4; i++)
      if (fabs(a[i][k]) > fabs(a[piv][k])) piv = i;
    if (!(fabs(a[piv][k]) > 1e-13 * scale)) return -1;
    if (piv != k) {
      for (j = 0; j < 4; j++) {
        double t = a[k][j];
        a[k][j] = a[piv][j];
        a[piv][j] = t;
      }
      for (c = 0; c < nb; c++) {
        double t = x[c][k];
        x[c][k] = x[c][piv];
        x[c][piv] = t;
      }
    }
    for (i = k + 1; i < 4; i++) {
      const double l = a[i][k] / a[k][k];
      for (j = k + 1; j < 4; j++) a[i][j] -= l * a[k][j];
      for (c = 0; c < nb; c++) x[c][i] -= l * x[c][k];
    }
  }
  for (c = 0; c < nb; c++)
    for (i = 3; i >= 0; i--) {
      double sum = x[c][i];
      for (j = i + 1; j < 4; j++) sum -= a[i][j] * x[c][j];
      x[c][i] = sum / a[i][i];
    }
  return 0;
}

static int fric_fail(autobal_error *errp, double t, const char *which) {
  autobal_error_set(errp, AUTOBAL_ENUMERIC,
                    "%s right-hand side failed at t = %.17g s: the effective mass matrix is singular or the "
                    "state is not finite",
                    which, t);
  return GSL_EBADFUNC;
}

/* One plane: q'' for the right-hand side b through the 2x2 S = I + g C (see solve_accelerations). */
static void fric_one_plane_apply(const autobal_rotor *R, const fric_plane *c, const double S[4], double idet,
                                 const double b[4], double qdd[4]) {
  const double d = R->p.plane[0].d, iM = R->inv_M, iA = R->inv_A;
  const double ru = b[0] * iM + d * b[3] * iA, rv = b[1] * iM - d * b[2] * iA;
  const double wu = (S[3] * ru - S[1] * rv) * idet, wv = (S[0] * rv - S[2] * ru) * idet;
  const double cu = c->Cuu * wu + c->Cuv * wv, cv = c->Cvu * wu + c->Cvv * wv;
  qdd[0] = (b[0] - cu) * iM;
  qdd[1] = (b[1] - cv) * iM;
  qdd[2] = (b[2] + d * cv) * iA;
  qdd[3] = (b[3] - d * cu) * iA;
}

/* The whole friction evaluation at (t, y) in `frame`, with the workspace ws (3 N doubles: sin, cos,
 * f sgn; the handle's R->fws) and the error record errp:
 * accelerations into dydt (may be NULL), the
 * normal forces into Nout and the holding forces of the stuck balls into Hout (NAN for slipping
 * balls; both may be NULL).  check_N: fail when a ball has N <= 0.  Returns 0, or GSL_EBADFUNC
 * with the message on the handle.
 * Responses (nw > 0, with Q = NULL and dydt given): besides a0 = dydt, the change of the whole
 * right-hand side under a unit force pair on each pair plist[i] (Q = +1 on its ball ahead, -1 on the
 * ball behind) into Wr + i dim: the accelerations are linear in Q, so each response is one more
 * right-hand side of the same solve (contact_responses; docs/device.md "Resting contact"). */
static int fric_eval_full(const autobal_rotor *R, double *ws, autobal_error *errp, int frame, double t,
                          const double y[], double dydt[], double *Nout, double *Hout, int check_N, const double *Q,
                          int nofric, const size_t *plist, size_t nw, double *Wr) {
  const size_t N = R->N;
  const double *q = y, *qd = y + 4, *ang = y + 8, *rate = y + 8 + N;
  double *sn = ws, *cs = ws + N, *fs = ws + 2 * N;
  /* nofric: every ball free and f = 0 (the impulsive response of an impact, docs/device.md section 4);
   * Q (may be NULL): generalized forces on the balls' angles (N m), the contact forces */
  const int exact = R->law == AUTOBAL_ROTOR_FRICTION_EXACT && !nofric;
  const int reg = R->law == AUTOBAL_ROTOR_FRICTION_REGULARIZED && !nofric;
  /* a stuck ball is a mass fixed to the rotor; in an impact's impulse (nofric) too, unless the
   * impact set it free (cfree: the balls of the impacting pairs and their clusters) */
  const int held = R->law == AUTOBAL_ROTOR_FRICTION_EXACT;
  const int *cfree = nofric && R->contact ? R->cfree : NULL;
#define FRIC_STUCK(k) (held && R->mode[k] == AUTOBAL_ROTOR_BALL_STUCK && !(cfree && cfree[k]))
  const double gu = R->gu, gv = R->gv;
  fric_plane cp[AUTOBAL_ROTOR_MAX_PLANES];
  double b[4], b1[4], qdd[4], qdd1[4], uv[AUTOBAL_ROTOR_MAX_PLANES][2], sw, cw, W, Wd = 0.0, phi0;
  double Jeff = R->Jeff, rhsm = 0.0;
  /* the responses: their right-hand sides of the solve and of the phi_0 row, then their q'' */
  double rb[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE][4], rm[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE],
      rq[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE][4], rW[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE];
  size_t j, k, i;
  const char *which = frame == AUTOBAL_ROTOR_FIXED ? "fixed-frame (friction)" : "rotating-frame (friction)";

  if (R->motor) {
    phi0 = y[R->im];
    W = y[R->im + 1];
  } else {
    drive_eval(R, t, &W, &Wd, &phi0);
  }
  autobal_sincos1(phi0, &sw, &cw);
  ball_sincos(ang, sn, cs, N);
  if (frame == AUTOBAL_ROTOR_ROTATING)
    for (k = 0; k < N; k++) { /* phi = psi + phi_0 */
      const double s = sn[k], c = cs[k];
      sn[k] = s * cw + c * sw;
      cs[k] = c * cw - s * sw;
    }
  rotor_forces(&R->L, W, R->motor ? 0.0 : Wd, q, qd, b);
  if (gu != 0.0 || gv != 0.0) { /* the weights (docs/device.md section 2, for a field (-gu, -gv)) */
    b[0] -= gu * R->Wtot;
    b[1] -= gv * R->Wtot;
    b[2] += gv * R->Dm;
    b[3] -= gu * R->Dm;
  }
  for (j = 0; j < R->n_planes; j++) {
    fric_plane *c = &cp[j];
    const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
    const double cth = cw * R->cpsi0[j] - sw * R->spsi0[j], sth = sw * R->cpsi0[j] + cw * R->spsi0[j];
    c->Cuu = R->mtot[j];
    c->Cuv = 0.0;
    c->Cvu = 0.0;
    c->Cvv = R->mtot[j];
    /* the unbalance (as in the frictionless right-hand sides) */
    c->Fu = -W * W * R->s0[j] * cth;
    c->Fv = -W * W * R->s0[j] * sth;
    if (!R->motor) {
      c->Fu -= Wd * R->s0[j] * sth;
      c->Fv += Wd * R->s0[j] * cth;
    }
    c->Pu = -R->s0[j] * sth;
    c->Pv = R->s0[j] * cth;
    rhsm -= R->s0[j] * (-gu * sth + gv * cth);
    for (k = k0; k < k1; k++) {
      const double s = sn[k], cc = cs[k], mr = R->mr[k], r = R->r[k];
      double m = R->m[k];
      if (FRIC_STUCK(k)) { /* a mass fixed to the rotor */
        fs[k] = 0.0;
        if (Q && R->motor) rhsm += Q[k]; /* a contact force on it acts on the rotor's spin */
        c->Fu -= W * W * mr * cc;
        c->Fv -= W * W * mr * s;
        if (!R->motor) {
          c->Fu -= Wd * mr * s;
          c->Fv += Wd * mr * cc;
        }
        c->Pu -= mr * s;
        c->Pv += mr * cc;
        Jeff += mr * r;
        if (R->rolling) Jeff += 0.4 * m * R->rho[k] * R->rho[k]; /* the rolling ball's own spin */
        rhsm -= mr * (-gu * s + gv * cc);
      } else {
        const double pd = frame == AUTOBAL_ROTOR_FIXED ? rate[k] : rate[k] + W; /* phi' */
        const double psid = frame == AUTOBAL_ROTOR_FIXED ? rate[k] - W : rate[k];
        double fk = 0.0, Au, Av, e;
        if (exact) fk = R->f[k] * (double)R->mode[k];
        else if (reg) fk = R->f[k] * tanh(psid * R->inv_ueps);
        fs[k] = fk;
        Au = s + fk * cc;
        Av = fk * s - cc;
        e = (Au * gu + Av * gv) / r - R->kappa[k] * psid - fk * pd * pd;
        if (Q) e += Q[k] / (mr * r); /* a generalized force Q on phi: + Q/(m r^2) */
        if (R->rolling) {
          /* rolling inertia: phi'' = rk (... + re Omega'), the prescribed Omega' known here, a
           * MOTOR's through b1 and the phi_0 row below (docs/device.md "Rolling inertia") */
          const double rk = R->rk[k], ke = rk * R->re[k];
          if (R->motor) {
            /* phi_0 row: + 2/5 m (r + rho) ((r + rho) Omega' - r phi''), 2/5 m (r + rho) r = re m r^2 */
            const double rr = r + R->rho[k];
            Jeff += 0.4 * m * rr * rr - ke * R->re[k] * mr * r;
            rhsm += ke * mr * r * e;
            c->Pu -= ke * mr * Au;
            c->Pv -= ke * mr * Av;
          }
          e = rk * (R->motor ? e : e + R->re[k] * Wd);
          m *= rk; /* the coupling of D's accelerations: rk m */
        }
        c->Cuu -= m * s * Au;
        c->Cuv -= m * s * Av;
        c->Cvu += m * cc * Au;
        c->Cvv += m * cc * Av;
        c->Fu -= mr * (s * e + pd * pd * cc);
        c->Fv += mr * (cc * e - pd * pd * s);
        if (R->motor) {
          m = R->m[k];
          rhsm += R->hr[k] * r * psid + r * fk * m * (r * pd * pd - gu * cc - gv * s);
          c->Pu += r * fk * m * cc;
          c->Pv += r * fk * m * s;
        }
      }
    }
    {
      const double d = R->p.plane[j].d;
      b[0] -= c->Fu;
      b[1] -= c->Fv;
      b[2] += d * c->Fv;
      b[3] -= d * c->Fu;
    }
  }
  if (R->motor) {
    /* the rows per unit Omega' (motor_b1): -C beta e_alpha and the tangential accelerations
     * m r Omega' (-sin, cos) of the unbalance and the stuck balls (the slipping balls' reaction
     * terms Pu, Pv belong to the phi_0 row only) */
    b1[0] = 0.0;
    b1[1] = 0.0;
    b1[2] = -R->L.C * q[3];
    b1[3] = 0.0;
    for (j = 0; j < R->n_planes; j++) {
      const double d = R->p.plane[j].d;
      const double cth = cw * R->cpsi0[j] - sw * R->spsi0[j], sth = sw * R->cpsi0[j] + cw * R->spsi0[j];
      double Su = R->s0[j] * sth, Sv = R->s0[j] * cth; /* sum m r sin, sum m r cos */
      const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
      if (held)
        for (k = k0; k < k1; k++)
          if (FRIC_STUCK(k)) {
            Su += R->mr[k] * sn[k];
            Sv += R->mr[k] * cs[k];
          }
      if (R->rolling) /* a slipping rolling ball's phi'' has rk re Omega' */
        for (k = k0; k < k1; k++)
          if (!FRIC_STUCK(k)) {
            const double kem = R->rk[k] * R->re[k] * R->mr[k];
            Su += kem * sn[k];
            Sv += kem * cs[k];
          }
      b1[0] += Su;
      b1[1] -= Sv;
      b1[2] += d * Sv;
      b1[3] += d * Su;
    }
  }
  if (nw > AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE || (nw > 0 && (Q || !dydt))) return fric_fail(errp, t, which);
  for (i = 0; i < nw; i++) { /* the Q terms of the loop above, for Q[pa] = +1, Q[pb] = -1 */
    const size_t kk[2] = {R->pa[plist[i]], R->pb[plist[i]]};
    int side;
    rb[i][0] = rb[i][1] = rb[i][2] = rb[i][3] = 0.0;
    rm[i] = 0.0;
    for (side = 0; side < 2; side++) {
      const double Qk = side == 0 ? 1.0 : -1.0;
      double d = 0.0, de, mr;
      k = kk[side];
      for (j = 0; j < R->n_planes; j++)
        if (k >= R->off[j] && k < R->off[j] + R->cnt[j]) d = R->p.plane[j].d;
      if (FRIC_STUCK(k)) {
        if (R->motor) rm[i] += Qk;
        continue;
      }
      mr = R->mr[k];
      de = Qk / (mr * R->r[k]);
      if (R->rolling) {
        if (R->motor) rm[i] += R->rk[k] * R->re[k] * mr * R->r[k] * de;
        de *= R->rk[k];
      }
      /* b -= F with F_u -= mr s e, F_v += mr c e */
      rb[i][0] += mr * sn[k] * de;
      rb[i][1] -= mr * cs[k] * de;
      rb[i][2] += d * mr * cs[k] * de;
      rb[i][3] += d * mr * sn[k] * de;
    }
  }
  if (R->n_planes == 1) {
    const fric_plane *c = &cp[0];
    const double g = R->g[0];
    double S[4], det, nrm, idet;
    S[0] = 1.0 + g * c->Cuu;
    S[1] = g * c->Cuv;
    S[2] = g * c->Cvu;
    S[3] = 1.0 + g * c->Cvv;
    det = S[0] * S[3] - S[1] * S[2];
    nrm = fabs(S[0]) + fabs(S[1]) + fabs(S[2]) + fabs(S[3]);
    if (!(det > 1e-13 * nrm * nrm)) return fric_fail(errp, t, which);
    idet = 1.0 / det;
    fric_one_plane_apply(R, c, S, idet, b, qdd);
    if (R->motor) fric_one_plane_apply(R, c, S, idet, b1, qdd1);
    for (i = 0; i < nw; i++) fric_one_plane_apply(R, c, S, idet, rb[i], rq[i]);
  } else {
    double a[4][4], x[2 + AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE][4];
    memset(a, 0, sizeof a);
    a[0][0] = R->L.M;
    a[1][1] = R->L.M;
    a[2][2] = R->L.A;
    a[3][3] = R->L.A;
    for (j = 0; j < R->n_planes; j++) {
      const double d = R->p.plane[j].d;
      const double eu[4] = {1.0, 0.0, 0.0, d}, ev[4] = {0.0, 1.0, -d, 0.0};
      const fric_plane *c = &cp[j];
      int m, n;
      for (m = 0; m < 4; m++)
        for (n = 0; n < 4; n++)
          a[m][n] += eu[m] * (c->Cuu * eu[n] + c->Cuv * ev[n]) + ev[m] * (c->Cvu * eu[n] + c->Cvv * ev[n]);
    }
    memcpy(x[0], b, sizeof b);
    if (R->motor) memcpy(x[1], b1, sizeof b1);
    else memset(x[1], 0, sizeof x[1]);
    for (i = 0; i < nw; i++) memcpy(x[2 + i], rb[i], sizeof rb[i]);
    if (lu4_solve(a, x, nw > 0 ? 2 + (int)nw : R->motor ? 2 : 1) != 0) return fric_fail(errp, t, which);
    memcpy(qdd, x[0], sizeof qdd);
    if (R->motor) memcpy(qdd1, x[1], sizeof qdd1);
    for (i = 0; i < nw; i++) memcpy(rq[i], x[2 + i], sizeof rq[i]);
  }
  if (R->motor) { /* the phi_0 row: Jeff' Omega' + G . q'' = rhsm + L - k_r Omega - C alpha' beta' */
    double G[4] = {0.0, 0.0, R->L.C * q[3], 0.0}, den, num;
    for (j = 0; j < R->n_planes; j++) {
      const double d = R->p.plane[j].d;
      G[0] += cp[j].Pu;
      G[1] += cp[j].Pv;
      G[2] -= d * cp[j].Pv;
      G[3] += d * cp[j].Pu;
    }
    den = Jeff + G[0] * qdd1[0] + G[1] * qdd1[1] + G[2] * qdd1[2] + G[3] * qdd1[3];
    num = rhsm + motor_L(R, W) - R->p.drive.k_r * W - R->L.C * qd[2] * qd[3] -
          (G[0] * qdd[0] + G[1] * qdd[1] + G[2] * qdd[2] + G[3] * qdd[3]);
    if (!(den > 1e-13 * Jeff)) return fric_fail(errp, t, which);
    Wd = num / den;
    for (j = 0; j < 4; j++) qdd[j] += Wd * qdd1[j];
    for (i = 0; i < nw; i++) {
      rW[i] = (rm[i] - (G[0] * rq[i][0] + G[1] * rq[i][1] + G[2] * rq[i][2] + G[3] * rq[i][3])) / den;
      for (j = 0; j < 4; j++) rq[i][j] += rW[i] * qdd1[j];
    }
  } else {
    for (i = 0; i < nw; i++) rW[i] = 0.0;
  }
  if (!isfinite(qdd[0] + qdd[1] + qdd[2] + qdd[3] + Wd)) return fric_fail(errp, t, which);
  for (j = 0; j < R->n_planes; j++) {
    const double d = R->p.plane[j].d;
    uv[j][0] = qdd[0] + d * qdd[3]; /* eq. (3.3) */
    uv[j][1] = qdd[1] - d * qdd[2];
  }
  /* the normal and holding forces (and the check N > 0) before anything is written to dydt */
  if (check_N || Nout || Hout)
    for (j = 0; j < R->n_planes; j++) {
      const double au = uv[j][0] + gu, av = uv[j][1] + gv;
      const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
      for (k = k0; k < k1; k++) {
        const double s = sn[k], cc = cs[k], m = R->m[k], r = R->r[k];
        const int stuck = FRIC_STUCK(k);
        const double pd = stuck ? W : (frame == AUTOBAL_ROTOR_FIXED ? rate[k] : rate[k] + W);
        const double Nk = m * (r * pd * pd - au * cc - av * s);
        if (Nout) Nout[k] = Nk;
        /* the holding force: with a contact force Q on the stuck ball (N m on phi, Q / r along the
         * track) the track holds H - Q / r */
        if (Hout)
          Hout[k] = stuck ? m * (r * Wd - au * s + av * cc) - (R->rolling ? 0.4 * m * R->rho[k] * Wd : 0.0) -
                                (Q ? Q[k] / r : 0.0)
                          : NAN;
        if (check_N && !(Nk > 0.0)) {
          const size_t ii = k - k0;
          autobal_error_set(errp, AUTOBAL_ENUMERIC,
                            "%s right-hand side failed at t = %.17g s: ball %zu of plane %zu (p%zu_b%zu) would "
                            "leave its track: normal force N = %.17g N (must be > 0)",
                            which, t, ii + 1, j + 1, j + 1, ii + 1, Nk);
          /* outside the model's domain: at a trial stage the driver retries a shorter step */
          return AUTOBAL_ROTOR_RHS_LEAVES_TRACK;
        }
      }
    }
  if (!dydt) return GSL_SUCCESS;
  rhs_common_rows(R, y, qdd, dydt);
  for (j = 0; j < R->n_planes; j++) {
    const double au = uv[j][0] + gu, av = uv[j][1] + gv;
    const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
    for (k = k0; k < k1; k++) {
      const double s = sn[k], cc = cs[k], r = R->r[k];
      double acc;
      if (FRIC_STUCK(k)) {
        dydt[8 + k] = frame == AUTOBAL_ROTOR_FIXED ? W : 0.0;
        acc = frame == AUTOBAL_ROTOR_FIXED ? Wd : 0.0;
      } else {
        const double pd = frame == AUTOBAL_ROTOR_FIXED ? rate[k] : rate[k] + W;
        const double psid = frame == AUTOBAL_ROTOR_FIXED ? rate[k] - W : rate[k];
        const double fk = fs[k];
        acc = ((s + fk * cc) * au + (fk * s - cc) * av) / r - R->kappa[k] * psid - fk * pd * pd;
        if (Q) acc += Q[k] / (R->mr[k] * r);
        if (R->rolling) acc = R->rk[k] * (acc + R->re[k] * Wd);
        if (frame == AUTOBAL_ROTOR_ROTATING) acc -= Wd;
      }
      dydt[8 + N + k] = acc;
    }
  }
  if (!ball_rows_finite(dydt, N)) return fric_fail(errp, t, which);
  if (R->motor) {
    dydt[R->im] = W;
    dydt[R->im + 1] = Wd;
  }
  for (i = 0; i < nw; i++) { /* the responses' rows, as the rows above without the Q-free terms */
    double *w = Wr + i * R->dim;
    memset(w, 0, R->dim * sizeof(double));
    for (k = 0; k < 4; k++) w[4 + k] = rq[i][k];
    for (j = 0; j < R->n_planes; j++) {
      const double d = R->p.plane[j].d, au = rq[i][0] + d * rq[i][3], av = rq[i][1] - d * rq[i][2];
      const size_t k0 = R->off[j], k1 = R->off[j] + R->cnt[j];
      for (k = k0; k < k1; k++) {
        double acc;
        if (FRIC_STUCK(k)) {
          acc = frame == AUTOBAL_ROTOR_FIXED ? rW[i] : 0.0;
        } else {
          const double s = sn[k], cc = cs[k], fk = fs[k], r = R->r[k];
          acc = ((s + fk * cc) * au + (fk * s - cc) * av) / r;
          if (k == R->pa[plist[i]]) acc += 1.0 / (R->mr[k] * r);
          if (k == R->pb[plist[i]]) acc -= 1.0 / (R->mr[k] * r);
          if (R->rolling) acc = R->rk[k] * (acc + R->re[k] * rW[i]);
          if (frame == AUTOBAL_ROTOR_ROTATING) acc -= rW[i];
        }
        w[8 + N + k] = acc;
      }
    }
    if (!ball_rows_finite(w, N) || !isfinite(rW[i])) return fric_fail(errp, t, which);
    if (R->motor) w[R->im + 1] = rW[i];
  }
  return GSL_SUCCESS;
#undef FRIC_STUCK
}

int autobal_rotor_friction_gravity_hook(autobal_rotor *r, double gu, double gv) {
  if (r == NULL || !isfinite(gu) || !isfinite(gv)) return AUTOBAL_EINVAL;
  r->gu = gu;
  r->gv = gv;
  r->cache_ok = 0;
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_friction_on(const autobal_rotor *r) {
  return r != NULL && r->law != AUTOBAL_ROTOR_FRICTION_NONE;
}

int autobal_rotor_ball_mode_get(const autobal_rotor *r, size_t k) {
  if (r == NULL || k >= r->N) return -2;
  return r->law == AUTOBAL_ROTOR_FRICTION_EXACT ? r->mode[k] : AUTOBAL_ROTOR_BALL_SLIP_POSITIVE;
}

int autobal_rotor_ball_mode_set(autobal_rotor *r, size_t k, int mode) {
  if (r == NULL || k >= r->N || r->law != AUTOBAL_ROTOR_FRICTION_EXACT ||
      (mode != AUTOBAL_ROTOR_BALL_STUCK && mode != AUTOBAL_ROTOR_BALL_SLIP_POSITIVE &&
       mode != AUTOBAL_ROTOR_BALL_SLIP_NEGATIVE))
    return AUTOBAL_EINVAL;
  r->mode[k] = mode;
  r->cache_ok = 0;
  return AUTOBAL_SUCCESS;
}

/* N and H of every ball with the accelerations of the current modes and clusters: with clusters that
 * are not rigid, their contact forces from the constraint solve act on the balls (Q = lambda on the ball
 * ahead, -lambda on the ball behind). */
static int full_forces(autobal_rotor *r, int frame, double t, const double *y, double *N, double *H) {
  size_t list[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE], na = 0, i;
  if (r->contact) na = active_list(r, list, 0);
  if (na == 0) return fric_eval(r, r->fws, &r->err, frame, t, y, NULL, N, H, 0, NULL, 0);
  if (contact_solve(r, frame, t, y, NULL) != 0) return GSL_EBADFUNC;
  memset(r->cQ, 0, r->N * sizeof(double));
  for (i = 0; i < na; i++) {
    r->cQ[r->pa[list[i]]] += r->plam[list[i]];
    r->cQ[r->pb[list[i]]] -= r->plam[list[i]];
  }
  return fric_eval(r, r->fws, &r->err, frame, t, y, NULL, N, H, 0, r->cQ, 0);
}

static int forces_common(autobal_rotor *r, int frame, double t, const double *y, double *N, double *H, size_t n) {
  if (r == NULL || y == NULL || (N == NULL && H == NULL) || n != r->N || !isfinite(t) ||
      (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING))
    return AUTOBAL_EINVAL;
  return full_forces(r, frame, t, y, N, H) == GSL_SUCCESS ? AUTOBAL_SUCCESS : AUTOBAL_ENUMERIC;
}

int autobal_rotor_normal_forces(autobal_rotor *r, int frame, double t, const double *y, double *N, size_t n) {
  return forces_common(r, frame, t, y, N, NULL, n);
}

int autobal_rotor_holding_forces(autobal_rotor *r, int frame, double t, const double *y, double *H, size_t n) {
  return forces_common(r, frame, t, y, NULL, H, n);
}

/* N and H of every ball into the cache, unless it holds them for (t, frame, y) already. */
static int fric_cache(autobal_rotor *r, int frame, double t, const double *y) {
  if (r->cache_ok && r->cache_t == t && r->cache_frame == frame &&
      memcmp(r->ycache, y, r->dim * sizeof(double)) == 0)
    return 0;
  r->cache_ok = 0;
  if (full_forces(r, frame, t, y, r->cN, r->cH) != GSL_SUCCESS) return -1;
  memcpy(r->ycache, y, r->dim * sizeof(double));
  r->cache_t = t;
  r->cache_frame = frame;
  r->cache_ok = 1;
  return 0;
}

/* psi' of ball k of the state (stuck: 0). */
static double ball_psid(const autobal_rotor *r, int frame, double t, const double *y, size_t k) {
  double W, ph;
  if (frame == AUTOBAL_ROTOR_ROTATING) return y[8 + r->N + k];
  spin_state(r, t, y, &W, &ph);
  return y[8 + r->N + k] - W;
}

/* ---- stuck chains (EXACT law with contact) -------------------------------------------------------
 * Balls in resting contact that are all stuck form a chain b_0 .. b_n along their track (b_0 behind),
 * held by stiction as one body.  Its contact forces Lambda_i >= 0 (N, between b_(i-1) and b_i; Lambda_0 =
 * Lambda_(n+1) = 0) are not fixed by the accelerations: the chain holds when some choice of them lets
 * every ball's track force stay within its stiction, |H_i - (Lambda_i - Lambda_(i+1))| <= mu_i N_i, H_i
 * the holding force of b_i without contact forces.  With l_i = H_i - mu_i N_i, u_i = H_i + mu_i N_i that
 * is (docs/device.md, "Stiction and contact"): sum l <= 0 <= sum u (the chain as a whole), every prefix
 * sum of l <= 0 (the balls behind do not pull away backwards) and every suffix sum of u >= 0 (the balls
 * ahead do not pull away forwards).  A single ball: |H| <= mu N. */

/* The rigid cluster behind (dir = -1) or ahead (dir = +1) of ball k: the other ball, or N when none. */
static size_t chain_next(const autobal_rotor *R, size_t k, int dir) {
  size_t p;
  for (p = 0; p < R->np; p++)
    if (R->pact[p] && (dir > 0 ? R->pb[p] : R->pa[p]) == k && pair_rigid(R, p, 0)) return dir > 0 ? R->pa[p] : R->pb[p];
  return R->N;
}

/* The stuck chain of stuck ball k into chain (behind to ahead); returns its length (>= 1).  A closed
 * ring (every ball of a track stuck and touching) starts at its lowest state index. */
static size_t chain_of(const autobal_rotor *R, size_t k, size_t *chain) {
  size_t head = k, n = 0, c, steps = 0, lo = k;
  if (!R->contact) {
    chain[0] = k;
    return 1;
  }
  for (c = chain_next(R, k, -1); c != R->N && steps < R->N; c = chain_next(R, c, -1), steps++) {
    if (c == k) { /* a ring */
      head = lo;
      break;
    }
    head = c;
    if (c < lo) lo = c;
  }
  chain[n++] = head;
  for (c = chain_next(R, head, 1); c != R->N && c != head && n < R->N; c = chain_next(R, c, 1)) chain[n++] = c;
  return n;
}

/* The smallest margin (N) of the chain's conditions with the forces N, H; *kind: 0 the whole chain
 * slips backwards (sum l > 0), 1 forwards (sum u < 0), 2 the balls up to chain[*pos] pull away
 * backwards, 3 the balls after chain[*pos] forwards (split between chain[*pos] and chain[*pos + 1]). */
static double chain_margin(const autobal_rotor *R, const size_t *chain, size_t n, const double *N, const double *H,
                           int *kind, size_t *pos) {
  double sl = 0.0, su = 0.0, m, best;
  size_t i;
  for (i = 0; i < n; i++) {
    const size_t k = chain[i];
    sl += H[k] - R->mu[k] * N[k];
    su += H[k] + R->mu[k] * N[k];
  }
  best = -sl, *kind = 0, *pos = 0;
  if (su < best) best = su, *kind = 1;
  m = 0.0;
  for (i = 0; i + 1 < n; i++) { /* prefixes b_0..b_i */
    m += H[chain[i]] - R->mu[chain[i]] * N[chain[i]];
    if (-m < best) best = -m, *kind = 2, *pos = i;
  }
  m = 0.0;
  for (i = n - 1; i > 0; i--) { /* suffixes b_i..b_n, split after chain[i - 1] */
    m += H[chain[i]] + R->mu[chain[i]] * N[chain[i]];
    if (m < best) best = m, *kind = 3, *pos = i - 1;
  }
  return best;
}

/* The pair joining balls b (behind) and a (ahead), or np. */
static size_t pair_of(const autobal_rotor *R, size_t b, size_t a) {
  size_t p;
  for (p = 0; p < R->np; p++)
    if (R->pb[p] == b && R->pa[p] == a) return p;
  return R->np;
}

double autobal_rotor_friction_switch(autobal_rotor *r, int frame, size_t k, double t, const double *y) {
  size_t n, pos;
  int kind;
  if (r == NULL || y == NULL || k >= r->N || r->law != AUTOBAL_ROTOR_FRICTION_EXACT || !isfinite(t) ||
      (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING))
    return NAN;
  if (r->mode[k] != AUTOBAL_ROTOR_BALL_STUCK) return (double)r->mode[k] * ball_psid(r, frame, t, y, k);
  n = r->contact ? chain_of(r, k, r->pb + r->N) : 1; /* the scratch after the pairs' arrays */
  if (n > 1 && r->pb[r->N] != k) return -1.0; /* a chain is watched by its first ball */
  if (fric_cache(r, frame, t, y) != 0) return NAN;
  if (n == 1) return fabs(r->cH[k]) - r->mu[k] * r->cN[k];
  return -chain_margin(r, r->pb + r->N, n, r->cN, r->cH, &kind, &pos);
}

int autobal_rotor_friction_settle(autobal_rotor *r, int frame, double t, double *y, int initial, size_t *n_stick,
                                  size_t *n_slip, size_t *n_reverse) {
  size_t k, it, ns = 0, nl = 0, nr = 0, nsplit0;
  int changed = 0;
  double W, ph;
  if (n_stick) *n_stick = 0;
  if (n_slip) *n_slip = 0;
  if (n_reverse) *n_reverse = 0;
  if (r == NULL || y == NULL || r->law != AUTOBAL_ROTOR_FRICTION_EXACT || !isfinite(t) ||
      (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING))
    return AUTOBAL_EINVAL;
  r->cache_ok = 0;
  spin_state(r, t, y, &W, &ph);
  memcpy(r->mode0, r->mode, r->N * sizeof(int));
  nsplit0 = r->contact ? r->nsplit : 0;
  for (k = 0; k < r->N; k++) {
    const double pd = ball_psid(r, frame, t, y, k);
    r->pd0[k] = y[8 + r->N + k]; /* restored for a ball that reaches 0 but slips on */
    if (initial) r->mode[k] = pd > 0.0 ? 1 : pd < 0.0 ? -1 : AUTOBAL_ROTOR_BALL_STUCK;
    else if (r->contact && r->cfree[k]) /* an impact's impulse set the ball free: its new direction; at rest
                                          * relative to the rotor (to rounding: 1e-12 (1 + |Omega|) rad/s) it sticks */
      r->mode[k] = pd > 1e-12 * (1.0 + fabs(W)) ? 1 : pd < -1e-12 * (1.0 + fabs(W)) ? -1 : AUTOBAL_ROTOR_BALL_STUCK;
    else if (r->mode[k] != AUTOBAL_ROTOR_BALL_STUCK && (double)r->mode[k] * pd <= 0.0)
      r->mode[k] = AUTOBAL_ROTOR_BALL_STUCK; /* psi' has reached 0 */
    if (r->contact) r->cfree[k] = 0;
    if (r->mode[k] == AUTOBAL_ROTOR_BALL_STUCK && pd != 0.0) {
      y[8 + r->N + k] = frame == AUTOBAL_ROTOR_FIXED ? W : 0.0;
      changed = 1;
    }
  }
  if (r->contact) { /* balls in resting contact move as one: a cluster with a stuck ball sticks */
    int more = 1;
    while (more) {
      size_t p;
      more = 0;
      for (p = 0; p < r->np; p++) {
        const size_t b = r->pb[p], a = r->pa[p];
        if (!r->pact[p] || (r->mode[b] == AUTOBAL_ROTOR_BALL_STUCK) == (r->mode[a] == AUTOBAL_ROTOR_BALL_STUCK)) continue;
        k = r->mode[b] == AUTOBAL_ROTOR_BALL_STUCK ? a : b;
        r->mode[k] = AUTOBAL_ROTOR_BALL_STUCK;
        y[8 + r->N + k] = frame == AUTOBAL_ROTOR_FIXED ? W : 0.0;
        more = changed = 1;
      }
    }
  }
  for (it = 0; it <= 2 * r->N + 2; it++) {
    size_t worst = r->N;
    double excess = 0.0;
    if (r->contact) { /* stuck chains (a single stuck ball is a chain of one) */
      size_t *chain = r->pb + r->N, n, i, pos, wpos = 0;
      int kind, wkind = 0;
      if (full_forces(r, frame, t, y, r->cN, r->cH) != GSL_SUCCESS) return AUTOBAL_ENUMERIC;
      for (k = 0; k < r->N; k++) {
        if (!(r->cN[k] > 0.0)) break;
        if (r->mode[k] != AUTOBAL_ROTOR_BALL_STUCK) continue;
        n = chain_of(r, k, chain);
        if (chain[0] == k) {
          double nsum = 0.0, ex;
          for (i = 0; i < n; i++) nsum += r->cN[chain[i]];
          ex = -chain_margin(r, chain, n, r->cN, r->cH, &kind, &pos) / nsum;
          if (ex > excess) excess = ex, worst = k, wkind = kind, wpos = pos;
        }
      }
      if (k == r->N) {
        if (worst == r->N) break;
        n = chain_of(r, worst, chain);
        if (wkind <= 1) /* the whole chain slips */
          for (i = 0; i < n; i++) {
            r->mode[chain[i]] = wkind == 0 ? AUTOBAL_ROTOR_BALL_SLIP_NEGATIVE : AUTOBAL_ROTOR_BALL_SLIP_POSITIVE;
            y[8 + r->N + chain[i]] = r->pd0[chain[i]];
          }
        else { /* the chain comes apart: the balls on either side are checked on their own */
          r->pact[pair_of(r, chain[wpos], chain[wpos + 1])] = 0;
          r->nsplit++;
        }
        r->ccache_ok = 0;
        continue;
      }
    } else if (fric_eval(r, r->fws, &r->err, frame, t, y, NULL, r->cN, r->cH, 0, NULL, 0) != GSL_SUCCESS)
      return AUTOBAL_ENUMERIC;
    for (k = 0; k < r->N; k++) {
      if (!(r->cN[k] > 0.0)) {
        size_t j = 0;
        while (j + 1 < r->n_planes && k >= r->off[j + 1]) j++;
        return autobal_error_set(&r->err, AUTOBAL_ENUMERIC,
                                 "friction: ball %zu of plane %zu (p%zu_b%zu) would leave its track at t = %.17g "
                                 "s: normal force N = %.17g N (must be > 0)",
                                 k - r->off[j] + 1, j + 1, j + 1, k - r->off[j] + 1, t, r->cN[k]);
      }
      if (r->mode[k] == AUTOBAL_ROTOR_BALL_STUCK) {
        const double ex = (fabs(r->cH[k]) - r->mu[k] * r->cN[k]) / r->cN[k];
        if (ex > excess) {
          excess = ex;
          worst = k;
        }
      }
    }
    if (worst == r->N) break;
    r->mode[worst] = r->cH[worst] > 0.0 ? AUTOBAL_ROTOR_BALL_SLIP_NEGATIVE : AUTOBAL_ROTOR_BALL_SLIP_POSITIVE;
    y[8 + r->N + worst] = r->pd0[worst]; /* its rate as it was (psi' = 0 if it was stuck at entry) */
  }
  if (it > 2 * r->N + 2)
    return autobal_error_set(&r->err, AUTOBAL_ENUMERIC, "friction: the switching rules did not settle at t = %.17g s", t);
  /* changed: a mode, a rate or a cluster differs from the entry (a ball stuck and set slipping again
   * with its rate restored in the same call is no change) */
  if (r->contact) { /* (without contact the rule of 0.2.0: any stick set at entry counts) */
    changed = r->nsplit != nsplit0;
    for (k = 0; k < r->N; k++)
      if (y[8 + r->N + k] != r->pd0[k]) changed = 1;
  }
  for (k = 0; k < r->N; k++) {
    const int was = r->mode0[k] == AUTOBAL_ROTOR_BALL_STUCK, is = r->mode[k] == AUTOBAL_ROTOR_BALL_STUCK;
    if (r->mode[k] != r->mode0[k]) changed = 1;
    if (!was && is) ns++;
    else if (was && !is) nl++;
    else if (!was && !is && !initial && (double)r->mode0[k] * ball_psid(r, frame, t, y, k) <= 0.0) nr++;
  }
  r->cache_ok = 0;
  if (n_stick) *n_stick = ns;
  if (n_slip) *n_slip = nl;
  if (n_reverse) *n_reverse = nr;
  return changed;
}

/* ---- contact (docs/device.md section 4) ------------------------------------------------------------ */

double autobal_rotor_gap_angle(double delta_i, double delta_j, double r) {
  const double x = (delta_i + delta_j) / (4.0 * r);
  if (!(delta_i >= 0.0) || !(delta_j >= 0.0) || !(r > 0.0) || !(x <= 1.0)) return NAN;
  return 2.0 * asin(x);
}

int autobal_rotor_contact_on(const autobal_rotor *r) { return r ? r->contact : 0; }
size_t autobal_rotor_contact_n_pairs(const autobal_rotor *r) { return r ? r->np : 0; }
int autobal_rotor_contact_pair(const autobal_rotor *r, size_t p, size_t *behind, size_t *ahead) {
  if (!r || p >= r->np) return AUTOBAL_EINVAL;
  if (behind) *behind = r->pb[p];
  if (ahead) *ahead = r->pa[p];
  return AUTOBAL_SUCCESS;
}
int autobal_rotor_contact_active(const autobal_rotor *r, size_t p) { return (r && p < r->np) ? r->pact[p] : 0; }
int autobal_rotor_contact_set_active(autobal_rotor *r, size_t p, int active) {
  if (!r || p >= r->np) return AUTOBAL_EINVAL;
  r->pact[p] = active != 0;
  r->ccache_ok = 0;
  r->cache_ok = 0; /* the friction switches depend on the clusters too */
  return AUTOBAL_SUCCESS;
}
size_t autobal_rotor_contact_n_active(const autobal_rotor *r) {
  size_t p, n = 0;
  for (p = 0; r && p < r->np; p++) n += (size_t)r->pact[p];
  return n;
}

/* The gap of pair p: the unwrapped angle difference minus the gap angle plus the multiple of 2 pi
 * (pc) fixed when the pairs were set, so that it is continuous along a run (the state's angles are
 * unwrapped) and an overlap of any depth is negative. */
static double pair_gap(const autobal_rotor *R, size_t p, const double *y) {
  return y[8 + R->pa[p]] - y[8 + R->pb[p]] - R->pg[p] + R->pc[p];
}
double autobal_rotor_contact_gap(const autobal_rotor *r, size_t p, const double *y) {
  return (r && y && p < r->np) ? pair_gap(r, p, y) : NAN;
}

/* Balls of state index k0..k1-1 sorted by their angle wrapped to [0, 2 pi) (insertion sort of the
 * indices into idx; tracks are small). */
static void sort_by_angle(const double *ang, size_t *idx, size_t n) {
  size_t i, j;
  for (i = 1; i < n; i++) {
    const size_t v = idx[i];
    const double a = ang[v] - 2.0 * M_PI * floor(ang[v] / (2.0 * M_PI));
    for (j = i; j > 0; j--) {
      const double b = ang[idx[j - 1]] - 2.0 * M_PI * floor(ang[idx[j - 1]] / (2.0 * M_PI));
      if (b <= a) break;
      idx[j] = idx[j - 1];
    }
    idx[j] = v;
  }
}

/* The pairs from angles ang[k] (any frame: only differences matter); with check, overlap -> EINVAL. */
static int contact_pairs(autobal_rotor *R, const double *ang, autobal_error *err) {
  size_t j, k, np = 0;
  size_t *idx = R->pb + R->N; /* scratch of N entries after the pairs' arrays (see alloc) */
  for (j = 0; j < R->n_planes; j++) {
    const size_t k0 = R->off[j], k1 = k0 + R->cnt[j];
    for (k = k0; k < k1; k++) {
      size_t n = 0, i, q;
      double gsum = 0.0, dmax = 0.0;
      int first = 1;
      for (q = k0; q < k; q++)
        if (R->r[q] == R->r[k]) first = 0;
      if (!first) continue; /* the track of ball k was done */
      for (q = k; q < k1; q++)
        if (R->r[q] == R->r[k]) idx[n++] = q, dmax = fmax(dmax, R->delta[q]);
      if (n < 2 || dmax == 0.0) continue;
      sort_by_angle(ang, idx, n);
      for (i = 0; i < n; i++) gsum += autobal_rotor_gap_angle(R->delta[idx[i]], R->delta[idx[(i + 1) % n]], R->r[k]);
      for (i = 0; i < n; i++) {
        const size_t b = idx[i], a = idx[(i + 1) % n];
        double g;
        R->pb[np] = b;
        R->pa[np] = a;
        R->pg[np] = autobal_rotor_gap_angle(R->delta[b], R->delta[a], R->r[k]);
        R->pact[np] = 0;
        R->plam[np] = 0.0;
        g = ang[a] - ang[b] - R->pg[np];
        R->pc[np] = -2.0 * M_PI * floor(g / (2.0 * M_PI)); /* the forward distance minus gamma, in [0, 2 pi) */
        g += R->pc[np];
        if (g > 2.0 * M_PI - 1e-12) g -= 2.0 * M_PI, R->pc[np] -= 2.0 * M_PI;
        if (g > 2.0 * M_PI - gsum + 1e-12 || g < -1e-12) {
          const size_t jb = b - k0 + 1, ja = a - k0 + 1;
          return autobal_error_set(err, AUTOBAL_EINVAL,
                                   "balls %zu and %zu of plane %zu (p%zu_b%zu, p%zu_b%zu) overlap at the initial "
                                   "position: they must be at least the gap angle %.9g rad apart",
                                   jb, ja, j + 1, j + 1, jb, j + 1, ja, R->pg[np]);
        }
        np++;
      }
    }
  }
  R->np = np;
  R->ccache_ok = 0;
  memset(R->cfree, 0, R->N * sizeof(int));
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_contact_order(autobal_rotor *r, int frame, double t, const double *y) {
  (void)frame, (void)t;
  if (!r || !y) return AUTOBAL_EINVAL;
  if (!r->contact) return AUTOBAL_SUCCESS;
  return contact_pairs(r, y + 8, &r->err);
}

/* The responses w_p = a(Q = J_p^T) - a0 of the accelerations to a unit force pair on pair p
 * (rows: all of the state; positions give 0), for the nw pairs list[] into R->cW + (1 + i) dim,
 * with a0 (Q = 0) in R->cW.  nofric: the impulsive response (friction off, every ball free).
 * One evaluation: the accelerations are linear in Q, so the responses are further right-hand sides
 * of the same solve (fric_eval_full), not differences of evaluations. */
static int contact_responses(autobal_rotor *R, int frame, double t, const double *y, const size_t *list, size_t nw,
                             int nofric) {
  const int chk = R->law != AUTOBAL_ROTOR_FRICTION_NONE && !nofric;
  return fric_eval_full(R, R->fws, &R->err, frame, t, y, R->cW, NULL, NULL, chk, NULL, nofric, list, nw,
                        R->cW + R->dim) == GSL_SUCCESS
             ? 0
             : -1;
}

/* Solve the n x n system a x = b (a row-major, overwritten; b overwritten by x) by Gaussian
 * elimination with partial pivoting; -1 when a pivot is below 1e-13 times the largest entry. */
static int small_solve(double *a, double *b, size_t n) {
  double scale = 0.0;
  size_t i, j, k;
  for (i = 0; i < n * n; i++) scale = fmax(scale, fabs(a[i]));
  for (k = 0; k < n; k++) {
    size_t piv = k;
    for (i = k + 1; i < n; i++)
      if (fabs(a[i * n + k]) > fabs(a[piv * n + k])) piv = i;
    if (!(fabs(a[piv * n + k]) > 1e-13 * scale)) return -1;
    if (piv != k) {
      for (j = 0; j < n; j++) {
        const double tt = a[k * n + j];
        a[k * n + j] = a[piv * n + j];
        a[piv * n + j] = tt;
      }
      {
        const double tt = b[k];
        b[k] = b[piv];
        b[piv] = tt;
      }
    }
    for (i = k + 1; i < n; i++) {
      const double l = a[i * n + k] / a[k * n + k];
      for (j = k + 1; j < n; j++) a[i * n + j] -= l * a[k * n + j];
      b[i] -= l * b[k];
    }
  }
  for (k = n; k-- > 0;) {
    double sum = b[k];
    for (j = k + 1; j < n; j++) sum -= a[k * n + j] * b[j];
    b[k] = sum / a[k * n + k];
  }
  return 0;
}

/* Ball k fixed to the rotor (EXACT law, stuck; in an impulse (impulse = 1) also not set free by it). */
static int ball_fixed(const autobal_rotor *R, size_t k, int impulse) {
  return R->law == AUTOBAL_ROTOR_FRICTION_EXACT && R->mode[k] == AUTOBAL_ROTOR_BALL_STUCK &&
         !(impulse && R->cfree[k]);
}

/* A cluster whose two balls are both fixed to the rotor: a rigid part of it, left out of the constraint
 * solve (its contact force is not determined by the accelerations; stiction of the chain decides,
 * see stuck_chains). */
static int pair_rigid(const autobal_rotor *R, size_t p, int impulse) {
  return ball_fixed(R, R->pb[p], impulse) && ball_fixed(R, R->pa[p], impulse);
}

/* The clusters' list (at most AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE) into list, without the rigid ones;
 * returns the count. */
static size_t active_list(const autobal_rotor *R, size_t *list, int impulse) {
  size_t p, n = 0;
  for (p = 0; p < R->np && n < AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE; p++)
    if (R->pact[p] && !pair_rigid(R, p, impulse)) list[n++] = p;
  return n;
}

/* The accelerations with the clusters' constraints J_p a = 0: a = a0 + sum lambda_p w_p with
 * G lambda = -J a0 (G_pq = J_p w_q); into dydt (may be NULL), lambda into R->plam. */
static int contact_solve(autobal_rotor *R, int frame, double t, const double *y, double *dydt) {
  size_t list[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE] = {0}, na = active_list(R, list, 0), i, q, n;
  const size_t dim = R->dim, N = R->N;
  double lam[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE];
  if (contact_responses(R, frame, t, y, list, na, 0) != 0) return -1;
  for (i = 0; i < na; i++) {
    const size_t a = 8 + N + R->pa[list[i]], b = 8 + N + R->pb[list[i]];
    lam[i] = -(R->cW[a] - R->cW[b]);
    for (q = 0; q < na; q++) {
      const double *w = R->cW + (1 + q) * dim;
      R->cG[i * na + q] = w[a] - w[b];
    }
  }
  if (na > 0 && small_solve(R->cG, lam, na) != 0) return -1;
  for (q = 0; q < R->np; q++)
    if (R->pact[q] && pair_rigid(R, q, 0)) R->plam[q] = HUGE_VAL; /* never released by its force */
  for (i = 0; i < na; i++) R->plam[list[i]] = lam[i];
  if (dydt) {
    memcpy(dydt, R->cW, dim * sizeof(double));
    for (i = 0; i < na; i++) {
      const double *w = R->cW + (1 + i) * dim;
      for (n = 0; n < dim; n++) dydt[n] += lam[i] * w[n];
    }
    if (!ball_rows_finite(dydt, N)) return -1;
  }
  return 0;
}

static int contact_rhs(autobal_rotor *R, int frame, double t, const double y[], double dydt[]) {
  const int chk = R->law != AUTOBAL_ROTOR_FRICTION_NONE;
  size_t p;
  int any = 0;
  for (p = 0; p < R->np; p++) any |= R->pact[p] && !pair_rigid(R, p, 0);
  if (!any) return fric_eval(R, R->fws, &R->err, frame, t, y, dydt, NULL, NULL, chk, NULL, 0);
  autobal_error_clear(&R->err);
  if (contact_solve(R, frame, t, y, dydt) != 0) {
    if (R->err.status == AUTOBAL_SUCCESS)
      autobal_error_set(&R->err, AUTOBAL_ENUMERIC,
                        "%s right-hand side failed at t = %.17g s: the accelerations with the touching balls held "
                        "together (contact) could not be solved",
                        frame == AUTOBAL_ROTOR_FIXED ? "fixed-frame" : "rotating-frame", t);
    return GSL_EBADFUNC;
  }
  return GSL_SUCCESS;
}

double autobal_rotor_contact_switch(autobal_rotor *r, int frame, size_t p, double t, const double *y) {
  if (!r || !y || p >= r->np) return NAN;
  /* a free pair: its gap plus a skin of 1e-12 rad, so that a pair just set to gap 0 by a reset
   * starts positive (the engine reports a falling crossing only from g > 0) */
  if (!r->pact[p]) return pair_gap(r, p, y) + 1e-12;
  if (pair_rigid(r, p, 0)) return 1.0; /* both balls stuck: held while they are */
  if (!(r->ccache_ok && r->ccache_t == t && r->ccache_frame == frame &&
        memcmp(r->cy, y, r->dim * sizeof(double)) == 0)) {
    r->ccache_ok = 0;
    if (contact_solve(r, frame, t, y, NULL) != 0) return NAN;
    memcpy(r->cy, y, r->dim * sizeof(double));
    r->ccache_t = t;
    r->ccache_frame = frame;
    r->ccache_ok = 1;
  }
  return r->plam[p];
}

/* One impact step: the free pairs imp[0..ni-1] with the restitutions ei[], the clusters held
 * (J v+ = 0): G Lambda = target - J v-, v += W Lambda.  Outputs of the first impact pair. */
static int impact_apply(autobal_rotor *R, int frame, double t, double *y, const size_t *imp, const double *ei, size_t ni,
                        double *Gout, double *Lout, double *uout) {
  size_t list[2 * AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE] = {0}, n = 0, i, q, k;
  double rhs[2 * AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE], G[4 * AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE * AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE];
  const size_t dim = R->dim, N = R->N;
  for (i = 0; i < ni; i++) list[n++] = imp[i];
  if (R->law == AUTOBAL_ROTOR_FRICTION_EXACT) { /* set free: the impacting balls and their clusters */
    int more = 1;
    double W, ph;
    spin_state(R, t, y, &W, &ph);
    for (k = 0; k < N; k++) /* a stuck ball moves with the rotor exactly (its integrated rate drifts by rounding) */
      if (R->mode[k] == AUTOBAL_ROTOR_BALL_STUCK) y[8 + N + k] = frame == AUTOBAL_ROTOR_FIXED ? W : 0.0;
    for (i = 0; i < ni; i++) R->cfree[R->pb[imp[i]]] = R->cfree[R->pa[imp[i]]] = 1;
    while (more) {
      more = 0;
      for (q = 0; q < R->np; q++)
        if (R->pact[q] && R->cfree[R->pb[q]] != R->cfree[R->pa[q]]) R->cfree[R->pb[q]] = R->cfree[R->pa[q]] = 1, more = 1;
    }
  }
  n += active_list(R, list + n, 1);
  if (contact_responses(R, frame, t, y, list, n, 1) != 0) return AUTOBAL_ENUMERIC;
  for (i = 0; i < n; i++) {
    const size_t a = 8 + N + R->pa[list[i]], b = 8 + N + R->pb[list[i]];
    const double u = y[a] - y[b];
    rhs[i] = (i < ni ? -ei[i] * u : 0.0) - u;
    for (q = 0; q < n; q++) {
      const double *w = R->cW + (1 + q) * dim;
      G[i * n + q] = w[a] - w[b];
    }
    if (i == 0) {
      if (uout) *uout = u;
      if (Gout) *Gout = G[0];
    }
  }
  if (!(G[0] > 0.0)) return AUTOBAL_ENUMERIC;
  if (small_solve(G, rhs, n) != 0) return AUTOBAL_ENUMERIC;
  if (Lout) *Lout = rhs[0];
  for (i = 0; i < n; i++) {
    const double *w = R->cW + (1 + i) * dim;
    for (k = 0; k < dim; k++) y[k] += rhs[i] * w[k];
  }
  R->ccache_ok = 0;
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_contact_impact(autobal_rotor *r, int frame, size_t p, double e, double t, double *y, double *G,
                                 double *Lambda, double *u) {
  if (!r || !y || p >= r->np || !(e >= 0.0 && e <= 1.0)) return AUTOBAL_EINVAL;
  return impact_apply(r, frame, t, y, &p, &e, 1, G, Lambda, u);
}

/* Move the ball ahead of pair p so that its gap is exactly 0. */
static void close_gap(autobal_rotor *R, size_t p, double *y) { y[8 + R->pa[p]] -= pair_gap(R, p, y); }

int autobal_rotor_contact_settle(autobal_rotor *r, int frame, double t, double *y, size_t *n_impacts, size_t *n_joins,
                                 size_t *n_releases) {
  const size_t N = r ? r->N : 0;
  size_t p, rounds, ni = 0, nj = 0, nr = 0;
  int changed = 0;
  if (!r || !y) return AUTOBAL_EINVAL;
  if (!r->contact || r->np == 0) return 0;
  /* releases: clusters pulling (lambda <= 0) */
  if (autobal_rotor_contact_n_active(r) > 0) {
    if (contact_solve(r, frame, t, y, NULL) != 0) return AUTOBAL_ENUMERIC;
    for (p = 0; p < r->np; p++)
      if (r->pact[p] && !(r->plam[p] > 0.0)) {
        r->pact[p] = 0;
        close_gap(r, p, y);
        nr++;
        changed = 1;
      }
  }
  /* impacts, until no touching free pair closes (chains); each round all such pairs at once */
  for (rounds = 0; rounds < 1000; rounds++) {
    size_t imp[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE], cnt = 0;
    double ei[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE];
    int join[AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE];
    for (p = 0; p < r->np && cnt < AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE; p++) {
      const double u = y[8 + N + r->pa[p]] - y[8 + N + r->pb[p]];
      /* closing; with the exact law's repeated settles not by a rounding error (|u| <= 1e-12 rad/s) */
      if (r->pact[p] || !(pair_gap(r, p, y) <= 1e-9) || !(u < (r->law == AUTOBAL_ROTOR_FRICTION_EXACT ? -1e-12 : 0.0))) continue;
      join[cnt] = r->e_rest * -u < r->v_rest &&
                  autobal_rotor_contact_n_active(r) + (size_t)cnt < AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE;
      ei[cnt] = join[cnt] ? 0.0 : r->e_rest;
      imp[cnt++] = p;
    }
    if (cnt == 0) break;
    for (p = 0; p < cnt; p++) close_gap(r, imp[p], y);
    if (impact_apply(r, frame, t, y, imp, ei, cnt, NULL, NULL, NULL) != AUTOBAL_SUCCESS) return AUTOBAL_ENUMERIC;
    for (p = 0; p < cnt; p++)
      if (join[p]) r->pact[imp[p]] = 1, nj++;
    ni += cnt;
    changed = 1;
  }
  /* a pair joined by a plastic impact that is not pressed (lambda <= 0) separates at once: else its
   * event (lambda falling through 0) would start at or below 0 and never fire */
  if (nj > 0) {
    if (contact_solve(r, frame, t, y, NULL) != 0) return AUTOBAL_ENUMERIC;
    for (p = 0; p < r->np; p++)
      if (r->pact[p] && !(r->plam[p] > 0.0)) {
        r->pact[p] = 0;
        close_gap(r, p, y);
        nr++;
      }
  }
  r->ccache_ok = 0;
  r->cache_ok = 0;
  if (n_impacts) *n_impacts += ni;
  if (n_joins) *n_joins += nj;
  if (n_releases) *n_releases += nr;
  return changed;
}

int autobal_rotor_hybrid_settle(autobal_rotor *r, int frame, double t, double *y, int initial, size_t counts[6]) {
  size_t k, p, it, ni = 0, nj = 0, nr = 0, ns = 0, nl = 0, nv = 0, max_it;
  int changed = 0, rc;
  if (!r || !y || !counts || !isfinite(t) || (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING))
    return AUTOBAL_EINVAL;
  if (r->law != AUTOBAL_ROTOR_FRICTION_EXACT) {
    if (!r->contact) return 0;
    rc = autobal_rotor_contact_settle(r, frame, t, y, &counts[3], &counts[4], &counts[5]);
    return rc;
  }
  if (!r->contact) {
    rc = autobal_rotor_friction_settle(r, frame, t, y, initial, &ns, &nl, &nv);
    if (rc >= 0) counts[0] += ns, counts[1] += nl, counts[2] += nv;
    return rc;
  }
  for (k = 0; k < r->N; k++) { /* the modes at entry, and which slipping balls have reached psi' = 0 */
    r->modein[k] = r->mode[k];
    r->reach[k] = r->mode[k] != AUTOBAL_ROTOR_BALL_STUCK && (double)r->mode[k] * ball_psid(r, frame, t, y, k) <= 0.0;
  }
  if (initial) /* balls placed touching, at rest relative to each other, start in resting contact */
    for (p = 0; p < r->np; p++) {
      const double u = y[8 + r->N + r->pa[p]] - y[8 + r->N + r->pb[p]];
      if (!r->pact[p] && fabs(pair_gap(r, p, y)) <= 1e-12 && fabs(u) <= 1e-12 && autobal_rotor_contact_n_active(r) < AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE) {
        r->pact[p] = 1;
        close_gap(r, p, y);
        changed = 1;
      }
    }
  r->nsplit = 0;
  max_it = 4 * r->N + 8;
  if (initial) { /* the modes first (the touching pairs' forces depend on them) */
    rc = autobal_rotor_friction_settle(r, frame, t, y, 1, NULL, NULL, NULL);
    if (rc < 0) return rc;
    changed |= rc;
  }
  for (it = 0; it < max_it; it++) {
    const int c1 = autobal_rotor_contact_settle(r, frame, t, y, &ni, &nj, &nr);
    int f1;
    if (c1 < 0) return c1;
    f1 = autobal_rotor_friction_settle(r, frame, t, y, 0, NULL, NULL, NULL);
    if (f1 < 0) return f1;
    if (c1 == 0 && f1 == 0) break;
    changed = 1;
  }
  if (it == max_it)
    return autobal_error_set(&r->err, AUTOBAL_ENUMERIC,
                             "contact and friction: the impacts and switching rules did not settle at t = %.17g s", t);
  for (k = 0; k < r->N; k++) {
    const int was = r->modein[k] == AUTOBAL_ROTOR_BALL_STUCK, is = r->mode[k] == AUTOBAL_ROTOR_BALL_STUCK;
    if (initial) continue;
    if (!was && is) ns++;
    else if (was && !is) nl++;
    else if (!was && !is && (r->reach[k] || r->mode[k] != r->modein[k])) nv++;
  }
  counts[0] += ns, counts[1] += nl, counts[2] += nv;
  counts[3] += ni, counts[4] += nj, counts[5] += nr + r->nsplit;
  r->nsplit = 0;
  r->cache_ok = 0;
  r->ccache_ok = 0;
  return changed;
}

double autobal_rotor_contact_capacity(const autobal_rotor *r, size_t plane) {
  size_t k, q, k0, k1;
  double cap = 0.0;
  if (!r || plane >= r->n_planes) return NAN;
  k0 = r->off[plane], k1 = k0 + r->cnt[plane];
  for (k = k0; k < k1; k++) {
    int first = 1;
    double su = 0.0, sv = 0.0, ang = 0.0;
    size_t prev = k;
    for (q = k0; q < k; q++)
      if (r->r[q] == r->r[k]) first = 0;
    if (!first) continue;
    for (q = k; q < k1; q++) /* the balls of this track packed in index order */
      if (r->r[q] == r->r[k]) {
        if (q != k) ang += r->contact ? autobal_rotor_gap_angle(r->delta[prev], r->delta[q], r->r[k]) : 0.0;
        su += r->mr[q] * cos(ang);
        sv += r->mr[q] * sin(ang);
        prev = q;
      }
    cap += hypot(su, sv);
  }
  return cap;
}

int autobal_rotor_contact_reachable(const autobal_rotor *r, size_t plane) {
  const double cap = autobal_rotor_contact_capacity(r, plane);
  if (!(cap >= 0.0)) return 0;
  return r->s0[plane] <= cap * (1.0 + 1e-12);
}

/* ---- parameters ----------------------------------------------------------- */

static const double default_ball_mass[2] = {0.05, 0.05};
static const double default_ball_radius[2] = {0.1, 0.1};
static const double default_ball_damping[2] = {0.1, 0.1};
static const double default_ball_psi[2] = {1.0, 2.5};
static const double default_ball_rate[2] = {0.0, 0.0};

autobal_rotor_params autobal_rotor_params_default(void) {
  autobal_rotor_params p;
  memset(&p, 0, sizeof p);
  p.input = AUTOBAL_ROTOR_HARDWARE;
  p.hw.M_k = 6.0;
  p.hw.A_k = 0.12;
  p.hw.m_p = 4.0;
  p.hw.A_p = 0.04;
  p.hw.C_p = 0.03;
  p.hw.l_L = 0.20;
  p.hw.l_R = 0.15;
  p.hw.c_Lx = 1.0e5;
  p.hw.c_Ly = 1.0e5;
  p.hw.c_Lz = 2.0e5;
  p.hw.c_Rx = 1.5e5;
  p.hw.c_Ry = 1.5e5;
  p.hw.h_Lx = 100.0;
  p.hw.h_Ly = 100.0;
  p.hw.h_Lz = 200.0;
  p.hw.h_Rx = 150.0;
  p.hw.h_Ry = 150.0;
  (void)autobal_rotor_lumped_from_hardware(&p.hw, &p.lumped, NULL);
  p.inertia = AUTOBAL_ROTOR_INERTIA_PAPER;
  p.omega = 500.0;
  p.g = 9.80665; /* gravity off (p.gravity = 0) */
  p.axial = 0;
  p.n_planes = 1;
  p.plane[0].d = 0.10;
  p.plane[0].m0 = 0.02;
  p.plane[0].r0 = 0.1;
  p.plane[0].psi0 = 0.0;
  p.plane[0].n_balls = 2;
  p.plane[0].ball_mass = default_ball_mass;
  p.plane[0].ball_radius = default_ball_radius;
  p.plane[0].ball_damping = default_ball_damping;
  p.plane[0].ball_psi = default_ball_psi;
  p.plane[0].ball_rate = default_ball_rate;
  return p;
}

static int check_hw(const autobal_rotor_hardware *hw, autobal_error *err) {
  int st;
  if (hw == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "hardware parameters are NULL");
#define CHK(field, lo, lo_open, unit)                                                          \
  if ((st = autobal_check_param(err, "hw." #field, hw->field, lo, lo_open, INFINITY, 1, unit)) != \
      AUTOBAL_SUCCESS)                                                                         \
    return st;
  CHK(M_k, 0.0, 1, "kg")
  CHK(A_k, 0.0, 1, "kg m^2")
  CHK(m_p, 0.0, 1, "kg")
  CHK(A_p, 0.0, 1, "kg m^2")
  CHK(C_p, 0.0, 0, "kg m^2")
  CHK(l_L, -INFINITY, 1, "m")
  CHK(l_R, -INFINITY, 1, "m")
  CHK(c_Lx, 0.0, 0, "N/m")
  CHK(c_Ly, 0.0, 0, "N/m")
  CHK(c_Lz, 0.0, 0, "N/m")
  CHK(c_Rx, 0.0, 0, "N/m")
  CHK(c_Ry, 0.0, 0, "N/m")
  CHK(h_Lx, 0.0, 0, "N s/m")
  CHK(h_Ly, 0.0, 0, "N s/m")
  CHK(h_Lz, 0.0, 0, "N s/m")
  CHK(h_Rx, 0.0, 0, "N s/m")
  CHK(h_Ry, 0.0, 0, "N s/m")
#undef CHK
  if (!(hw->l_L + hw->l_R > 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "support positions: the left support (z = -l_L = %.17g m) must lie left "
                             "of the right one (z = l_R = %.17g m): need l_L + l_R > 0",
                             -hw->l_L, hw->l_R);
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_lumped_from_hardware(const autobal_rotor_hardware *hw, autobal_rotor_lumped *out,
                                       autobal_error *err) {
  int st = check_hw(hw, err);
  autobal_rotor_lumped L;
  if (st != AUTOBAL_SUCCESS) return st;
  if (out == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "output lumped struct is NULL");
  /* eq. (2.7) */
  L.M = hw->M_k + hw->m_p;
  L.A = hw->A_k + hw->A_p;
  L.C = hw->C_p;
  /* eq. (2.9), with the corrected c_z = c_Lz */
  L.c_x = hw->c_Lx + hw->c_Rx;
  L.c_y = hw->c_Ly + hw->c_Ry;
  L.c_z = hw->c_Lz;
  L.c_alpha = hw->c_Ly * hw->l_L * hw->l_L + hw->c_Ry * hw->l_R * hw->l_R;
  L.c_beta = hw->c_Lx * hw->l_L * hw->l_L + hw->c_Rx * hw->l_R * hw->l_R;
  L.c_xbeta = hw->c_Lx * hw->l_L - hw->c_Rx * hw->l_R;
  L.c_yalpha = hw->c_Ly * hw->l_L - hw->c_Ry * hw->l_R;
  /* eq. (2.11) */
  L.h_x = hw->h_Lx + hw->h_Rx;
  L.h_y = hw->h_Ly + hw->h_Ry;
  L.h_z = hw->h_Lz;
  L.h_alpha = hw->h_Ly * hw->l_L * hw->l_L + hw->h_Ry * hw->l_R * hw->l_R;
  L.h_beta = hw->h_Lx * hw->l_L * hw->l_L + hw->h_Rx * hw->l_R * hw->l_R;
  L.h_xbeta = hw->h_Lx * hw->l_L - hw->h_Rx * hw->l_R;
  L.h_yalpha = hw->h_Ly * hw->l_L - hw->h_Ry * hw->l_R;
  *out = L;
  return AUTOBAL_SUCCESS;
}

/* 2x2 block [[d1, o], [o, d2]] positive semidefinite (relative slack). */
static int check_psd(autobal_error *err, const char *what, const char *n1, double d1,
                     const char *n2, double d2, const char *no, double o, const char *unit) {
  if (o * o > d1 * d2 * (1.0 + 1e-12))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "lumped %s block is not positive semidefinite: %s^2 = %.17g exceeds "
                             "%s*%s = %.17g (%s = %.17g %s)",
                             what, no, o * o, n1, n2, d1 * d2, no, o, unit);
  return AUTOBAL_SUCCESS;
}

static int check_lumped(const autobal_rotor_lumped *L, autobal_error *err) {
  int st;
#define CHK(field, lo, lo_open, unit)                                                              \
  if ((st = autobal_check_param(err, "lumped." #field, L->field, lo, lo_open, INFINITY, 1, unit)) != \
      AUTOBAL_SUCCESS)                                                                             \
    return st;
  CHK(M, 0.0, 1, "kg")
  CHK(A, 0.0, 1, "kg m^2")
  CHK(C, 0.0, 0, "kg m^2")
  CHK(c_x, 0.0, 0, "N/m")
  CHK(c_y, 0.0, 0, "N/m")
  CHK(c_z, 0.0, 0, "N/m")
  CHK(c_alpha, 0.0, 0, "N m")
  CHK(c_beta, 0.0, 0, "N m")
  CHK(c_xbeta, -INFINITY, 1, "N")
  CHK(c_yalpha, -INFINITY, 1, "N")
  CHK(h_x, 0.0, 0, "N s/m")
  CHK(h_y, 0.0, 0, "N s/m")
  CHK(h_z, 0.0, 0, "N s/m")
  CHK(h_alpha, 0.0, 0, "N m s")
  CHK(h_beta, 0.0, 0, "N m s")
  CHK(h_xbeta, -INFINITY, 1, "N s")
  CHK(h_yalpha, -INFINITY, 1, "N s")
#undef CHK
  if ((st = check_psd(err, "stiffness x-beta", "c_x", L->c_x, "c_beta", L->c_beta, "c_xbeta",
                      L->c_xbeta, "N")) != AUTOBAL_SUCCESS)
    return st;
  if ((st = check_psd(err, "stiffness y-alpha", "c_y", L->c_y, "c_alpha", L->c_alpha, "c_yalpha",
                      L->c_yalpha, "N")) != AUTOBAL_SUCCESS)
    return st;
  if ((st = check_psd(err, "damping x-beta", "h_x", L->h_x, "h_beta", L->h_beta, "h_xbeta",
                      L->h_xbeta, "N s")) != AUTOBAL_SUCCESS)
    return st;
  return check_psd(err, "damping y-alpha", "h_y", L->h_y, "h_alpha", L->h_alpha, "h_yalpha",
                   L->h_yalpha, "N s");
}

int autobal_rotor_plane_can_balance(double s0, const double *a, size_t n) {
  double sum = 0.0, amax = 0.0, lo;
  size_t i;
  if (!(s0 >= 0.0)) return 0;
  if (n == 0) return s0 == 0.0;
  if (a == NULL) return 0;
  for (i = 0; i < n; i++) {
    if (!(a[i] >= 0.0) || !isfinite(a[i])) return 0;
    sum += a[i];
    if (a[i] > amax) amax = a[i];
  }
  lo = 2.0 * amax - sum;
  if (lo < 0.0) lo = 0.0;
  return s0 <= sum * (1.0 + 1e-12) && s0 >= lo - 1e-12 * sum;
}

static int check_plane(const autobal_rotor_plane *pl, size_t j, autobal_error *err, int *warn,
                       char *warnmsg, size_t warnlen, double *msum) {
  char name[96];
  int st;
  size_t i;
  double s0, asum = 0.0;
#define CHKP(field, lo, lo_open, hi, hi_open, unit)                                        \
  snprintf(name, sizeof name, "plane[%zu]." #field, j);                                   \
  if ((st = autobal_check_param(err, name, pl->field, lo, lo_open, hi, hi_open, unit)) != \
      AUTOBAL_SUCCESS)                                                                    \
    return st;
  CHKP(d, -INFINITY, 1, INFINITY, 1, "m")
  CHKP(m0, 0.0, 0, INFINITY, 1, "kg")
  CHKP(r0, 0.0, 0, INFINITY, 1, "m")
  CHKP(psi0, -INFINITY, 1, INFINITY, 1, "rad")
#undef CHKP
  if (pl->n_balls > AUTOBAL_ROTOR_MAX_BALLS)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter plane[%zu].n_balls = %zu is out of range: allowed [0, %d]", j,
                             pl->n_balls, AUTOBAL_ROTOR_MAX_BALLS);
  if (pl->n_balls > 0 &&
      (pl->ball_mass == NULL || pl->ball_radius == NULL || pl->ball_damping == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "plane[%zu]: n_balls = %zu but ball_mass, ball_radius or ball_damping "
                             "is NULL",
                             j, pl->n_balls);
  for (i = 0; i < pl->n_balls; i++) {
#define CHKB(arr, lo, lo_open, unit)                                                          \
  snprintf(name, sizeof name, "plane[%zu]." #arr "[%zu]", j, i);                              \
  if ((st = autobal_check_param(err, name, pl->arr[i], lo, lo_open, INFINITY, 1, unit)) !=    \
      AUTOBAL_SUCCESS)                                                                        \
    return st;
    CHKB(ball_mass, 0.0, 1, "kg")
    CHKB(ball_radius, 0.0, 1, "m")
    CHKB(ball_damping, 0.0, 0, "kg/s")
    if (pl->ball_psi) {
      CHKB(ball_psi, -INFINITY, 1, "rad")
    }
    if (pl->ball_rate) {
      CHKB(ball_rate, -INFINITY, 1, "rad/s")
    }
#undef CHKB
    asum += pl->ball_mass[i] * pl->ball_radius[i];
    *msum += pl->ball_mass[i];
  }
  /* existence of a balanced configuration (3.14): a warning, not an error */
  s0 = pl->m0 * pl->r0;
  {
    double amax = 0.0, lo;
    for (i = 0; i < pl->n_balls; i++)
      if (pl->ball_mass[i] * pl->ball_radius[i] > amax) amax = pl->ball_mass[i] * pl->ball_radius[i];
    lo = 2.0 * amax - asum;
    if (lo < 0.0) lo = 0.0;
    if (!(s0 <= asum * (1.0 + 1e-12))) {
      if (!*warn)
        snprintf(warnmsg, warnlen,
                 "plane[%zu]: the balls cannot cancel the unbalance: sum m_i r_i = %.6g kg m < "
                 "m0 r0 = %.6g kg m (no balanced motion exists)",
                 j, asum, s0);
      *warn = 1;
    } else if (!(s0 >= lo - 1e-12 * asum)) {
      if (!*warn)
        snprintf(warnmsg, warnlen,
                 "plane[%zu]: the balls cannot cancel the unbalance: m0 r0 = %.6g kg m is below "
                 "2 max m_i r_i - sum m_i r_i = %.6g kg m (the heaviest ball dominates; no "
                 "balanced motion exists)",
                 j, s0, lo);
      *warn = 1;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* A MOTOR drive (C: the lumped polar moment C_p). */
static int check_motor(const autobal_rotor_drive *d, double C, int inertia, autobal_error *err) {
  int st;
  size_t k;
  if (inertia != AUTOBAL_ROTOR_INERTIA_PAPER)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "drive.mode = MOTOR needs the PAPER inertia model (inertia = 0): the motor "
                             "equations are derived with the paper's truncation (2.2) only (docs/device.md)");
  if (!isfinite(d->J) || !(d->J >= C))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter drive.J = %.17g kg m^2 is out of range: allowed [C_p, inf) = "
                             "[%.17g, inf) kg m^2 (the rotor's polar moment C_p plus the motor's rotor)",
                             d->J, C);
  if ((st = autobal_check_param(err, "drive.k_r", d->k_r, 0.0, 0, INFINITY, 1, "N m s")) ||
      (st = autobal_check_param(err, "drive.omega_start", d->omega_start, -INFINITY, 1, INFINITY, 1, "rad/s")))
    return st;
  if (d->n_torque == 0) {
    if (!(d->L_0 > 0.0) || !isfinite(d->L_0))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "parameter drive.L_0 = %.17g N m is out of range: allowed (0, inf) (the "
                               "starting torque; L_0 <= 0: the motor cannot start)",
                               d->L_0);
    return autobal_check_param(err, "drive.omega_0", d->omega_0, 0.0, 1, INFINITY, 1, "rad/s");
  }
  if (d->n_torque > AUTOBAL_ROTOR_DRIVE_MAX_POINTS)
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter drive.n_torque = %zu is out of range: allowed [0, %d]",
                             d->n_torque, AUTOBAL_ROTOR_DRIVE_MAX_POINTS);
  if (d->torque_omega == NULL || d->torque_L == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "drive: n_torque = %zu but torque_omega or torque_L is NULL",
                             d->n_torque);
  for (k = 0; k < d->n_torque; k++) {
    char name[64];
    snprintf(name, sizeof name, "drive.torque_L[%zu]", k);
    if ((st = autobal_check_param(err, name, d->torque_L[k], -INFINITY, 1, INFINITY, 1, "N m"))) return st;
    snprintf(name, sizeof name, "drive.torque_omega[%zu]", k);
    if ((st = autobal_check_param(err, name, d->torque_omega[k], k ? d->torque_omega[k - 1] : -INFINITY, 1,
                                  INFINITY, 1, "rad/s")))
      return st; /* finite and strictly increasing */
  }
  {
    /* L(0) of the table (linear between the points, constant outside) */
    const double *X = d->torque_omega, *Y = d->torque_L;
    const size_t n = d->n_torque;
    double L0 = Y[0];
    if (0.0 >= X[n - 1]) L0 = Y[n - 1];
    else if (0.0 > X[0])
      for (k = 0; k + 1 < n; k++)
        if (X[k] <= 0.0 && 0.0 < X[k + 1]) L0 = Y[k] + (Y[k + 1] - Y[k]) * ((0.0 - X[k]) / (X[k + 1] - X[k]));
    if (!(L0 > 0.0))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "drive: the torque table gives L(0) = %.17g N m: allowed (0, inf) (the "
                               "starting torque; L(0) <= 0: the motor cannot start)",
                               L0);
  }
  return AUTOBAL_SUCCESS;
}

static int check_drive(const autobal_rotor_drive *d, double C, int inertia, autobal_error *err) {
  int st;
  size_t k;
  if (d->mode == AUTOBAL_ROTOR_DRIVE_CONSTANT) return AUTOBAL_SUCCESS;
  if (d->mode == AUTOBAL_ROTOR_DRIVE_MOTOR) return check_motor(d, C, inertia, err);
  if (d->mode == AUTOBAL_ROTOR_DRIVE_RAMP) {
    if ((st = autobal_check_param(err, "drive.omega_a", d->omega_a, -INFINITY, 1, INFINITY, 1, "rad/s")) ||
        (st = autobal_check_param(err, "drive.omega_b", d->omega_b, -INFINITY, 1, INFINITY, 1, "rad/s")) ||
        (st = autobal_check_param(err, "drive.t_a", d->t_a, -INFINITY, 1, INFINITY, 1, "s")) ||
        (st = autobal_check_param(err, "drive.t_b", d->t_b, d->t_a, 1, INFINITY, 1, "s")))
      return st;
    return AUTOBAL_SUCCESS;
  }
  if (d->mode != AUTOBAL_ROTOR_DRIVE_TABLE)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter drive.mode = %d is not valid: use AUTOBAL_ROTOR_DRIVE_CONSTANT (0), "
                             "AUTOBAL_ROTOR_DRIVE_RAMP (1), AUTOBAL_ROTOR_DRIVE_TABLE (2) or "
                             "AUTOBAL_ROTOR_DRIVE_MOTOR (3)",
                             d->mode);
  if (d->n_points < 1 || d->n_points > AUTOBAL_ROTOR_DRIVE_MAX_POINTS)
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter drive.n_points = %zu is out of range: allowed [1, %d]",
                             d->n_points, AUTOBAL_ROTOR_DRIVE_MAX_POINTS);
  if (d->table_t == NULL || d->table_omega == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "drive: n_points = %zu but table_t or table_omega is NULL",
                             d->n_points);
  for (k = 0; k < d->n_points; k++) {
    char name[64];
    snprintf(name, sizeof name, "drive.table_omega[%zu]", k);
    if ((st = autobal_check_param(err, name, d->table_omega[k], -INFINITY, 1, INFINITY, 1, "rad/s"))) return st;
    snprintf(name, sizeof name, "drive.table_t[%zu]", k);
    if ((st = autobal_check_param(err, name, d->table_t[k], k ? d->table_t[k - 1] : -INFINITY, 1, INFINITY, 1,
                                  "s")))
      return st; /* finite and strictly increasing */
  }
  return AUTOBAL_SUCCESS;
}

/* The friction block for plane j (the law and u_eps with j == 0). */
static int check_friction(const autobal_rotor_params *p, size_t j, autobal_error *err) {
  const autobal_rotor_friction *fr = &p->friction;
  const autobal_rotor_plane *pl = &p->plane[j];
  char name[64];
  size_t i;
  int st;
  if (j == 0) {
    if (fr->law != AUTOBAL_ROTOR_FRICTION_NONE && fr->law != AUTOBAL_ROTOR_FRICTION_EXACT &&
        fr->law != AUTOBAL_ROTOR_FRICTION_REGULARIZED)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "parameter friction.law = %d is not valid: use AUTOBAL_ROTOR_FRICTION_NONE (0), "
                               "AUTOBAL_ROTOR_FRICTION_EXACT (1) or AUTOBAL_ROTOR_FRICTION_REGULARIZED (2)",
                               fr->law);
    if (fr->law == AUTOBAL_ROTOR_FRICTION_REGULARIZED &&
        (st = autobal_check_param(err, "friction.u_eps", fr->u_eps, 0.0, 1, INFINITY, 1, "rad/s")))
      return st;
  }
  for (i = 0; i < pl->n_balls; i++) {
    const double f = fr->ball_f[j] ? fr->ball_f[j][i] : 0.0;
    if (fr->ball_f[j]) {
      snprintf(name, sizeof name, "plane[%zu].ball_f[%zu]", j, i);
      if ((st = autobal_check_param(err, name, f, 0.0, 0, INFINITY, 1, ""))) return st;
    }
    if (fr->ball_mu[j]) {
      const double mu = fr->ball_mu[j][i];
      snprintf(name, sizeof name, "plane[%zu].ball_mu[%zu]", j, i);
      if (isfinite(mu) && mu < f) {
        char fb[40];
        snprintf(fb, sizeof fb, "%.15g", f); /* the shortest of %.15g / %.17g that reads back */
        if (strtod(fb, NULL) != f) snprintf(fb, sizeof fb, "%.17g", f);
        return autobal_error_set(err, AUTOBAL_EINVAL,
                                 "parameter %s = %.15g is too small: the static coefficient must be >= the "
                                 "rolling-resistance coefficient plane[%zu].ball_f[%zu] = %s (allowed range "
                                 "[%s, inf))",
                                 name, mu, j, i, fb, fb);
      }
      if ((st = autobal_check_param(err, name, mu, f, 0, INFINITY, 1, ""))) return st;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* The rolling block for plane j (the switch with j == 0). */
static int check_rolling(const autobal_rotor_params *p, size_t j, autobal_error *err) {
  const autobal_rotor_rolling *ro = &p->rolling;
  char name[64];
  size_t i;
  int st;
  if (j == 0 && ro->on != 0 && ro->on != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter rolling.on = %d is not valid: use 0 (off) or 1 (on)",
                             ro->on);
  if (!ro->on || !ro->ball_rho[j]) return AUTOBAL_SUCCESS;
  for (i = 0; i < p->plane[j].n_balls; i++) {
    snprintf(name, sizeof name, "plane[%zu].ball_rho[%zu]", j, i);
    if ((st = autobal_check_param(err, name, ro->ball_rho[j][i], 0.0, 0, INFINITY, 1, "m"))) return st;
  }
  return AUTOBAL_SUCCESS;
}

/* The contact block for plane j (the switch, e, v_rest with j == 0): diameters >= 0, the balls of
 * every track fit (the gap angles of neighbours sum to at most 2 pi). */
static int check_contact(const autobal_rotor_params *p, size_t j, autobal_error *err) {
  const autobal_rotor_contact *c = &p->contact;
  const autobal_rotor_plane *pl = &p->plane[j];
  char name[64];
  size_t i, q;
  int st;
  if (j == 0) {
    if (c->on != 0 && c->on != 1)
      return autobal_error_set(err, AUTOBAL_EINVAL, "parameter contact.on = %d is not valid: use 0 (off) or 1 (on)", c->on);
    if (!c->on) return AUTOBAL_SUCCESS;
    if ((st = autobal_check_param(err, "contact.restitution", c->restitution, 0.0, 0, 1.0, 0, ""))) return st;
    if ((st = autobal_check_param(err, "contact.v_rest", c->v_rest, 0.0, 0, INFINITY, 1, "rad/s"))) return st;
  }
  if (!c->on || !c->ball_diameter[j]) return AUTOBAL_SUCCESS;
  for (i = 0; i < pl->n_balls; i++) {
    snprintf(name, sizeof name, "plane[%zu].ball_diameter[%zu]", j, i);
    if ((st = autobal_check_param(err, name, c->ball_diameter[j][i], 0.0, 0, INFINITY, 1, "m"))) return st;
  }
  for (i = 0; i < pl->n_balls; i++) { /* per track (first ball of each radius) */
    double gsum = 0.0, dsum = 0.0, d1 = -1.0, dprev = 0.0, r = pl->ball_radius[i];
    size_t n = 0;
    int first = 1;
    for (q = 0; q < i; q++)
      if (pl->ball_radius[q] == r) first = 0;
    if (!first) continue;
    for (q = i; q < pl->n_balls; q++)
      if (pl->ball_radius[q] == r) {
        const double d = c->ball_diameter[j][q];
        if (d1 < 0.0) d1 = d;
        else gsum += autobal_rotor_gap_angle(dprev, d, r);
        dsum += d;
        dprev = d;
        n++;
      }
    if (n >= 2) gsum += autobal_rotor_gap_angle(dprev, d1, r);
    if (n >= 2 && !(gsum <= 2.0 * M_PI))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "the balls of plane %zu on the track of radius %.9g m do not fit: sum of the diameters %.9g m "
                               "against the circumference %.9g m; neighbours need the gap angles 2 asin((delta_i + "
                               "delta_j)/(4 r)), whose sum must be <= 2 pi (plane[%zu].ball_diameter)",
                               j + 1, r, dsum, 2.0 * M_PI * r, j);
  }
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_params_check(const autobal_rotor_params *p, autobal_error *err) {
  autobal_rotor_lumped L;
  int st, warn = 0;
  char warnmsg[AUTOBAL_ERRMSG_SIZE];
  size_t j, ntot = 0;
  double heavy = 0.0;
  warnmsg[0] = '\0';
  if (p == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "rotor parameters are NULL");
  if (p->input == AUTOBAL_ROTOR_HARDWARE) {
    if ((st = autobal_rotor_lumped_from_hardware(&p->hw, &L, err)) != AUTOBAL_SUCCESS) return st;
  } else if (p->input == AUTOBAL_ROTOR_LUMPED) {
    L = p->lumped;
    if ((st = check_lumped(&L, err)) != AUTOBAL_SUCCESS) return st;
    if (!isnan(p->hw.l_L) && !isfinite(p->hw.l_L))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "parameter hw.l_L = %g m must be finite or NAN (unknown)", p->hw.l_L);
    if (!isnan(p->hw.l_R) && !isfinite(p->hw.l_R))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "parameter hw.l_R = %g m must be finite or NAN (unknown)", p->hw.l_R);
  } else {
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter input = %d is not valid: use AUTOBAL_ROTOR_HARDWARE (0) or "
                             "AUTOBAL_ROTOR_LUMPED (1)",
                             p->input);
  }
  if (p->inertia != AUTOBAL_ROTOR_INERTIA_PAPER && p->inertia != AUTOBAL_ROTOR_INERTIA_FULL)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter inertia = %d is not valid: use AUTOBAL_ROTOR_INERTIA_PAPER "
                             "(0) or AUTOBAL_ROTOR_INERTIA_FULL (1)",
                             p->inertia);
  if (p->axial != 0 && p->axial != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter axial = %d is not valid: use 0 or 1",
                             p->axial);
  if ((st = autobal_check_param(err, "omega", p->omega, -INFINITY, 1, INFINITY, 1, "rad/s")) !=
      AUTOBAL_SUCCESS)
    return st;
  if ((st = check_drive(&p->drive, L.C, p->inertia, err)) != AUTOBAL_SUCCESS) return st;
  if (p->gravity != 0 && p->gravity != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter gravity = %d is not valid: use 0 or 1",
                             p->gravity);
  if (p->gravity &&
      ((st = autobal_check_param(err, "shaft_angle", p->shaft_angle, 0.0, 0, M_PI, 0, "rad")) != AUTOBAL_SUCCESS ||
       (st = autobal_check_param(err, "g", p->g, 0.0, 1, INFINITY, 1, "m/s^2")) != AUTOBAL_SUCCESS))
    return st;
  if (p->gravity && sin(p->shaft_angle) != 0.0 && !(L.c_y * L.c_alpha - L.c_yalpha * L.c_yalpha > 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "gravity = 1 needs supports that carry the weight: c_y c_alpha - c_yalpha^2 = %g "
                             "N^2 must be > 0 (else there is no static equilibrium)",
                             L.c_y * L.c_alpha - L.c_yalpha * L.c_yalpha);
  if (p->n_planes < 1 || p->n_planes > AUTOBAL_ROTOR_MAX_PLANES)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter n_planes = %zu is out of range: allowed [1, %d]", p->n_planes,
                             AUTOBAL_ROTOR_MAX_PLANES);
  {
    static const char *const qn[4] = {"q0[0] (x)", "q0[1] (y)", "q0[2] (alpha)", "q0[3] (beta)"};
    static const char *const qdn[4] = {"qd0[0] (x')", "qd0[1] (y')", "qd0[2] (alpha')",
                                       "qd0[3] (beta')"};
    for (j = 0; j < 4; j++) {
      if ((st = autobal_check_param(err, qn[j], p->q0[j], -INFINITY, 1, INFINITY, 1,
                                    j < 2 ? "m" : "rad")) != AUTOBAL_SUCCESS)
        return st;
      if ((st = autobal_check_param(err, qdn[j], p->qd0[j], -INFINITY, 1, INFINITY, 1,
                                    j < 2 ? "m/s" : "rad/s")) != AUTOBAL_SUCCESS)
        return st;
    }
    if ((st = autobal_check_param(err, "z0", p->z0, -INFINITY, 1, INFINITY, 1, "m")) != AUTOBAL_SUCCESS)
      return st;
    if ((st = autobal_check_param(err, "zd0", p->zd0, -INFINITY, 1, INFINITY, 1, "m/s")) !=
        AUTOBAL_SUCCESS)
      return st;
  }
  for (j = 0; j < p->n_planes; j++) {
    double msum = 0.0;
    if ((st = check_plane(&p->plane[j], j, err, &warn, warnmsg, sizeof warnmsg, &msum)) !=
        AUTOBAL_SUCCESS)
      return st;
    if ((st = check_friction(p, j, err)) != AUTOBAL_SUCCESS) return st;
    if ((st = check_rolling(p, j, err)) != AUTOBAL_SUCCESS) return st;
    if ((st = check_contact(p, j, err)) != AUTOBAL_SUCCESS) return st;
    ntot += p->plane[j].n_balls;
    heavy += msum * (1.0 / L.M + p->plane[j].d * p->plane[j].d / L.A);
  }
  if (ntot > AUTOBAL_ROTOR_MAX_BALLS)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "total number of balls %zu is out of range: allowed [0, %d]", ntot,
                             AUTOBAL_ROTOR_MAX_BALLS);
  if (p->inertia == AUTOBAL_ROTOR_INERTIA_PAPER && !(heavy < 1.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "balls too heavy for the paper's inertia simplification: "
                             "sum_j sum_i m_ji (1/M + d_j^2/A) = %.6g must be < 1 (the effective mass "
                             "matrix could become singular; use the FULL inertia model or lighter balls)",
                             heavy);
  if (warn) return autobal_error_set(err, AUTOBAL_WARNING, "%s", warnmsg);
  autobal_error_clear(err);
  return AUTOBAL_SUCCESS;
}

/* ---- the handle ------------------------------------------------------------ */

static size_t output_count_base(const autobal_rotor *r);

autobal_rotor *autobal_rotor_alloc(const autobal_rotor_params *p, autobal_error *err) {
  autobal_rotor *R;
  autobal_error e;
  int st = autobal_rotor_params_check(p, &e);
  size_t j, k, N = 0, dn, mn;
  if (err != NULL) *err = e;
  if (st < 0) return NULL;
  for (j = 0; j < p->n_planes; j++) N += p->plane[j].n_balls;
  dn = p->drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE ? p->drive.n_points
       : p->drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP ? 2u : 0u;
  mn = p->drive.mode == AUTOBAL_ROTOR_DRIVE_MOTOR ? p->drive.n_torque : 0u;
  R = (autobal_rotor *)calloc(1, sizeof *R);
  if (R == NULL) {
    autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory allocating the rotor handle");
    return NULL;
  }
  /* 21 arrays of N doubles, 4 of dn, 2 of mn and the cache of a state (N may be 0: allocate at
   * least one element) */
  R->store = (double *)calloc(21 * N + 4 * dn + 2 * mn + (8 + 2 * N + 4) + 1, sizeof(double));
  R->mode = (int *)calloc(2 * N + 1, sizeof(int));
  if (R->store == NULL || R->mode == NULL) {
    free(R->store);
    free(R->mode);
    free(R);
    autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory allocating arrays for %zu balls", N);
    return NULL;
  }
  R->m = R->store;
  R->r = R->m + N;
  R->h = R->r + N;
  R->mr = R->h + N;
  R->hr = R->mr + N;
  R->kappa = R->hr + N;
  R->psi_init = R->kappa + N;
  R->rate_init = R->psi_init + N;
  R->sn = R->rate_init + N;
  R->cs = R->sn + N;
  R->dn = dn;
  R->dT = R->cs + N;
  R->dV = R->dT + dn;
  R->dS = R->dV + dn;
  R->dP = R->dS + dn;
  R->mn = mn;
  R->mW = R->dP + dn;
  R->mL = R->mW + mn;
  R->f = R->mL + mn;
  R->mu = R->f + N;
  R->cN = R->mu + N;
  R->cH = R->cN + N;
  R->fws = R->cH + N; /* 3 N: the friction path's sin, cos, f sgn */
  R->pd0 = R->fws + 3 * N;
  R->ycache = R->pd0 + N;
  R->rho = R->ycache + (8 + 2 * N + 4);
  R->rk = R->rho + N;
  R->re = R->rk + N;
  R->mode0 = R->mode + N;
  R->p = *p;
  R->motor = p->drive.mode == AUTOBAL_ROTOR_DRIVE_MOTOR;
  if (mn > 0) {
    memcpy(R->mW, p->drive.torque_omega, mn * sizeof(double));
    memcpy(R->mL, p->drive.torque_L, mn * sizeof(double));
    R->p.drive.torque_omega = R->mW;
    R->p.drive.torque_L = R->mL;
  } else {
    R->p.drive.torque_omega = NULL;
    R->p.drive.torque_L = NULL;
  }
  if (dn > 0) {
    double W, Wd;
    if (p->drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP) {
      R->dT[0] = p->drive.t_a;
      R->dT[1] = p->drive.t_b;
      R->dV[0] = p->drive.omega_a;
      R->dV[1] = p->drive.omega_b;
    } else {
      memcpy(R->dT, p->drive.table_t, dn * sizeof(double));
      memcpy(R->dV, p->drive.table_omega, dn * sizeof(double));
    }
    R->dP[0] = R->dV[0] * R->dT[0]; /* F(t) = dV[0] t before the first point */
    for (k = 0; k + 1 < dn; k++) {
      R->dS[k] = (R->dV[k + 1] - R->dV[k]) / (R->dT[k + 1] - R->dT[k]);
      R->dP[k + 1] = R->dP[k] + 0.5 * (R->dV[k] + R->dV[k + 1]) * (R->dT[k + 1] - R->dT[k]);
    }
    R->dS[dn - 1] = 0.0;
    R->dF0 = 0.0;
    R->dF0 = drive_F(R, 0.0, &W, &Wd);
    /* the handle's copy of the drive points into the handle (a RAMP keeps its four numbers) */
    if (p->drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE) {
      R->p.drive.table_t = R->dT;
      R->p.drive.table_omega = R->dV;
    }
  }
  if (p->input == AUTOBAL_ROTOR_HARDWARE) {
    (void)autobal_rotor_lumped_from_hardware(&p->hw, &R->L, NULL);
    R->l_L = p->hw.l_L;
    R->l_R = p->hw.l_R;
  } else {
    R->L = p->lumped;
    R->l_L = isfinite(p->hw.l_L) ? p->hw.l_L : NAN;
    R->l_R = isfinite(p->hw.l_R) ? p->hw.l_R : NAN;
  }
  R->p.lumped = R->L;
  R->inv_M = 1.0 / R->L.M;
  R->inv_A = 1.0 / R->L.A;
  for (j = 0; j < p->n_planes; j++) R->g[j] = R->inv_M + p->plane[j].d * p->plane[j].d * R->inv_A;
  R->n_planes = p->n_planes;
  R->N = N;
  R->dim = 8 + 2 * N + (p->axial ? 2u : 0u) + (R->motor ? 2u : 0u);
  R->im = R->motor ? R->dim - 2 : 0;
  R->Jeff = p->drive.J;
  for (j = 0; j < p->n_planes; j++) R->Jeff += p->plane[j].m0 * p->plane[j].r0 * p->plane[j].r0;
  k = 0;
  for (j = 0; j < p->n_planes; j++) {
    const autobal_rotor_plane *pl = &p->plane[j];
    size_t i;
    double asum = 0.0;
    R->off[j] = k;
    R->cnt[j] = pl->n_balls;
    R->s0[j] = pl->m0 * pl->r0;
    R->cpsi0[j] = cos(pl->psi0);
    R->spsi0[j] = sin(pl->psi0);
    R->mtot[j] = 0.0;
    for (i = 0; i < pl->n_balls; i++, k++) {
      R->m[k] = pl->ball_mass[i];
      R->r[k] = pl->ball_radius[i];
      R->h[k] = pl->ball_damping[i];
      R->mr[k] = R->m[k] * R->r[k];
      R->hr[k] = R->h[k] * R->r[k];
      R->kappa[k] = R->h[k] / R->m[k];
      R->psi_init[k] = pl->ball_psi ? pl->ball_psi[i] : 0.0;
      R->rate_init[k] = pl->ball_rate ? pl->ball_rate[i] : 0.0;
      asum += R->mr[k];
      R->mtot[j] += R->m[k];
    }
    R->mtot[j] = p->inertia == AUTOBAL_ROTOR_INERTIA_FULL ? R->mtot[j] + pl->m0 : 0.0;
    R->sref[j] = R->s0[j] > 0.0 ? R->s0[j] : (asum > 0.0 ? asum : 1.0);
    /* the handle's copy of the plane points into the handle's own arrays */
    R->p.plane[j].ball_mass = R->m + R->off[j];
    R->p.plane[j].ball_radius = R->r + R->off[j];
    R->p.plane[j].ball_damping = R->h + R->off[j];
    R->p.plane[j].ball_psi = R->psi_init + R->off[j];
    R->p.plane[j].ball_rate = R->rate_init + R->off[j];
  }
  for (j = p->n_planes; j < AUTOBAL_ROTOR_MAX_PLANES; j++) memset(&R->p.plane[j], 0, sizeof R->p.plane[j]);
  R->gs = R->gW = R->gD = 0.0;
  if (p->gravity) { /* docs/device.md section 2: g_s (M + sum m) on y, -g_s sum d m on alpha */
    double W = R->L.M, D = 0.0;
    R->gs = p->g * sin(p->shaft_angle);
    for (j = 0; j < p->n_planes; j++) {
      double mj = p->plane[j].m0;
      for (k = R->off[j]; k < R->off[j] + R->cnt[j]; k++) mj += R->m[k];
      W += mj;
      D += p->plane[j].d * mj;
    }
    R->gW = R->gs * W;
    R->gD = R->gs * D;
    if (R->gs != 0.0) { /* the static offset K q_s = -(0, gW, -gD, 0) (as autobal_rotor_static_offset;
                           calloc: 0 without weight in the plane; det > 0 checked by the parameters) */
      const double det = R->L.c_y * R->L.c_alpha - R->L.c_yalpha * R->L.c_yalpha;
      R->qs[1] = -(R->gW * R->L.c_alpha + R->L.c_yalpha * R->gD) / det;
      R->qs[2] = (R->L.c_y * R->gD + R->L.c_yalpha * R->gW) / det;
    }
  }
  /* friction: per-ball coefficients (mu defaults to f), initial modes from the initial rates */
  R->law = p->friction.law;
  R->inv_ueps = R->law == AUTOBAL_ROTOR_FRICTION_REGULARIZED ? 1.0 / p->friction.u_eps : 0.0;
  R->gu = 0.0;
  R->gv = 0.0;
  R->Wtot = R->L.M;
  R->Dm = 0.0;
  for (j = 0; j < p->n_planes; j++) {
    const autobal_rotor_plane *pl = &p->plane[j];
    double mj = pl->m0;
    size_t i;
    for (i = 0; i < pl->n_balls; i++) {
      k = R->off[j] + i;
      R->f[k] = p->friction.ball_f[j] ? p->friction.ball_f[j][i] : 0.0;
      R->mu[k] = p->friction.ball_mu[j] ? p->friction.ball_mu[j][i] : R->f[k];
      R->mode[k] = R->rate_init[k] < 0.0 ? AUTOBAL_ROTOR_BALL_SLIP_NEGATIVE : AUTOBAL_ROTOR_BALL_SLIP_POSITIVE;
      mj += pl->ball_mass[i];
    }
    R->Wtot += mj;
    R->Dm += pl->d * mj;
    R->p.friction.ball_f[j] = R->f + R->off[j];
    R->p.friction.ball_mu[j] = R->mu + R->off[j];
  }
  for (j = p->n_planes; j < AUTOBAL_ROTOR_MAX_PLANES; j++) {
    R->p.friction.ball_f[j] = NULL;
    R->p.friction.ball_mu[j] = NULL;
  }
  R->gv = R->gs; /* the friction right-hand sides take gravity as the acceleration (0, g_s) of D */
  /* rolling inertia: rho copied, rk = 5/7, re = 2/5 (1 + rho/r) */
  R->rolling = p->rolling.on != 0;
  for (j = 0; j < p->n_planes; j++) {
    size_t i;
    for (i = 0; i < p->plane[j].n_balls; i++) {
      k = R->off[j] + i;
      R->rho[k] = (R->rolling && p->rolling.ball_rho[j]) ? p->rolling.ball_rho[j][i] : 0.0;
      R->rk[k] = R->rolling ? 5.0 / 7.0 : 1.0;
      R->re[k] = R->rolling ? 0.4 * (1.0 + R->rho[k] / R->r[k]) : 0.0;
    }
    R->p.rolling.ball_rho[j] = R->rolling ? R->rho + R->off[j] : NULL;
  }
  for (j = p->n_planes; j < AUTOBAL_ROTOR_MAX_PLANES; j++) R->p.rolling.ball_rho[j] = NULL;
  /* contact: diameters copied, the pairs from the initial angles */
  R->contact = p->contact.on != 0;
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++) R->p.contact.ball_diameter[j] = NULL;
  if (R->contact) {
    const size_t dim = R->dim, CM = AUTOBAL_ROTOR_CONTACT_MAX_ACTIVE;
    const size_t nd = 5 * N + (2 * CM + 1) * dim + CM * CM + dim + 1;
    R->cstore = (double *)calloc(nd, sizeof(double));
    R->pb = (size_t *)calloc(3 * N + 1, sizeof(size_t));
    R->pact = (int *)calloc(4 * N + 4, sizeof(int));
    if (!R->cstore || !R->pb || !R->pact) {
      autobal_rotor_free(R);
      autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory allocating the contact arrays");
      return NULL;
    }
    R->pa = R->pb + 2 * N;
    R->cfree = R->pact + N + 1;
    R->modein = R->cfree + N + 1;
    R->reach = R->modein + N + 1;
    R->delta = R->cstore;
    R->pg = R->delta + N;
    R->pc = R->pg + N;
    R->plam = R->pc + N;
    R->cQ = R->plam + N;
    R->cW = R->cQ + N;
    R->cG = R->cW + (2 * CM + 1) * dim;
    R->cy = R->cG + CM * CM;
    R->e_rest = p->contact.restitution;
    R->v_rest = p->contact.v_rest > 0.0 ? p->contact.v_rest : 1e-3;
    for (j = 0; j < p->n_planes; j++) {
      size_t i;
      for (i = 0; i < p->plane[j].n_balls; i++)
        R->delta[R->off[j] + i] = p->contact.ball_diameter[j] ? p->contact.ball_diameter[j][i] : 0.0;
      R->p.contact.ball_diameter[j] = R->delta + R->off[j];
    }
    if (contact_pairs(R, R->psi_init, &e) != AUTOBAL_SUCCESS) {
      if (err) *err = e;
      autobal_rotor_free(R);
      return NULL;
    }
  }
  R->nout = output_count_base(R) + (R->law != AUTOBAL_ROTOR_FRICTION_NONE ? 2u * R->N : 0u);
  R->err = e;
  return R;
}

void autobal_rotor_free(autobal_rotor *r) {
  if (r == NULL) return;
  free(r->store);
  free(r->mode);
  free(r->cstore);
  free(r->pb);
  free(r->pact);
  free(r);
}

const char *autobal_rotor_errmsg(const autobal_rotor *r) {
  if (r == NULL) return "rotor handle is NULL";
  return r->err.message;
}

const autobal_rotor_params *autobal_rotor_get_params(const autobal_rotor *r) {
  return r ? &r->p : NULL;
}
const autobal_rotor_lumped *autobal_rotor_get_lumped(const autobal_rotor *r) {
  return r ? &r->L : NULL;
}
size_t autobal_rotor_dim(const autobal_rotor *r) { return r ? r->dim : 0; }
size_t autobal_rotor_n_planes(const autobal_rotor *r) { return r ? r->n_planes : 0; }
size_t autobal_rotor_n_balls(const autobal_rotor *r, size_t plane) {
  return (r && plane < r->n_planes) ? r->cnt[plane] : 0;
}
size_t autobal_rotor_n_balls_total(const autobal_rotor *r) { return r ? r->N : 0; }
size_t autobal_rotor_ball_index(const autobal_rotor *r, size_t plane, size_t i) {
  if (r == NULL || plane >= r->n_planes || i >= r->cnt[plane]) return (size_t)-1;
  return r->off[plane] + i;
}
double autobal_rotor_omega(const autobal_rotor *r) { return r ? r->p.omega : NAN; }

int autobal_rotor_drive_eval(const autobal_rotor *r, double t, double out[3]) {
  double W, Wd, ph;
  if (r == NULL || out == NULL || !isfinite(t) || r->motor) return AUTOBAL_EINVAL;
  drive_eval(r, t, &W, &Wd, &ph);
  out[0] = W;
  out[1] = Wd;
  out[2] = ph;
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_spin(const autobal_rotor *r, double t, const double *y, double out[2]) {
  double W, ph;
  if (r == NULL || out == NULL || !isfinite(t) || (r->motor && y == NULL)) return AUTOBAL_EINVAL;
  spin_state(r, t, y, &W, &ph);
  out[0] = W;
  out[1] = ph;
  return AUTOBAL_SUCCESS;
}

double autobal_rotor_motor_torque(const autobal_rotor *r, double Omega) {
  if (r == NULL || !r->motor || !isfinite(Omega)) return NAN;
  return motor_L(r, Omega);
}

double autobal_rotor_drive_speed_max(const autobal_rotor *r) {
  double m;
  size_t k;
  if (r == NULL) return NAN;
  if (r->motor) {
    m = r->mn == 0 ? r->p.drive.omega_0 : 0.0;
    for (k = 0; k < r->mn; k++)
      if (fabs(r->mW[k]) > m) m = fabs(r->mW[k]);
    return fmax(m, fabs(r->p.drive.omega_start));
  }
  if (r->dn == 0) return fabs(r->p.omega);
  m = 0.0;
  for (k = 0; k < r->dn; k++)
    if (fabs(r->dV[k]) > m) m = fabs(r->dV[k]);
  return m;
}

int autobal_rotor_set_omega(autobal_rotor *r, double omega) {
  int st;
  if (r == NULL) return AUTOBAL_EINVAL;
  st = autobal_check_param(&r->err, "omega", omega, -INFINITY, 1, INFINITY, 1, "rad/s");
  if (st == AUTOBAL_SUCCESS) {
    r->p.omega = omega;
    r->cache_ok = 0; /* the friction forces cached for autobal_rotor_friction_switch */
    r->ccache_ok = 0; /* the contact forces cached for autobal_rotor_contact_switch */
  }
  return st;
}

static int check_frame_dim(const autobal_rotor *r, int frame, size_t dim, autobal_error *err) {
  if (r == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "rotor handle is NULL");
  if (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "frame = %d is not valid: use AUTOBAL_ROTOR_FIXED (0) or "
                             "AUTOBAL_ROTOR_ROTATING (1)",
                             frame);
  if (dim != r->dim)
    return autobal_error_set(err, AUTOBAL_EINVAL, "state dimension %zu does not match the model's %zu",
                             dim, r->dim);
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_initial_state(const autobal_rotor *r, int frame, double t0, double *y, size_t dim) {
  size_t k;
  double W, Wd, ph0;
  int st = check_frame_dim(r, frame, dim, NULL);
  if (st != AUTOBAL_SUCCESS || y == NULL || !isfinite(t0)) return AUTOBAL_EINVAL;
  for (k = 0; k < 4; k++) {
    y[k] = r->p.q0[k];
    y[4 + k] = r->p.qd0[k];
  }
  if (r->motor) { /* phi_0(t0) = 0, Omega(t0) = omega_start */
    W = r->p.drive.omega_start;
    ph0 = 0.0;
    y[r->im] = ph0;
    y[r->im + 1] = W;
  } else {
    drive_eval(r, t0, &W, &Wd, &ph0);
  }
  for (k = 0; k < r->N; k++) {
    if (frame == AUTOBAL_ROTOR_FIXED) {
      y[8 + k] = ph0 + r->psi_init[k];
      y[8 + r->N + k] = W + r->rate_init[k];
    } else {
      y[8 + k] = r->psi_init[k];
      y[8 + r->N + k] = r->rate_init[k];
    }
  }
  if (r->p.axial) {
    y[8 + 2 * r->N] = r->p.z0;
    y[9 + 2 * r->N] = r->p.zd0;
  }
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_convert_state(const autobal_rotor *r, int from_frame, int to_frame, double t,
                                const double *in, double *out, size_t dim) {
  size_t k;
  double sgn, W, ph0;
  if (check_frame_dim(r, from_frame, dim, NULL) != AUTOBAL_SUCCESS ||
      check_frame_dim(r, to_frame, dim, NULL) != AUTOBAL_SUCCESS || in == NULL || out == NULL ||
      !isfinite(t))
    return AUTOBAL_EINVAL;
  if (in != out) memmove(out, in, dim * sizeof(double));
  if (from_frame == to_frame) return AUTOBAL_SUCCESS;
  sgn = to_frame == AUTOBAL_ROTOR_ROTATING ? -1.0 : 1.0;
  spin_state(r, t, out, &W, &ph0); /* a motor's phi_0, Omega: copied unchanged to out */
  for (k = 0; k < r->N; k++) {
    out[8 + k] += sgn * ph0;
    out[8 + r->N + k] += sgn * W;
  }
  return AUTOBAL_SUCCESS;
}

/* ---- derived quantities ------------------------------------------------------ */

/* s_xi, s_eta of plane j (eq. (3.10)), fixed to the rotor; wt = phi_0(t).  The state's ball angle
 * + offset = absolute angle phi.  cpsi0, spsi0 hold cos and sin of the plane's psi0 (computed once
 * at allocation, the same numbers as computing them here). */
static void plane_sxe(const autobal_rotor *r, size_t j, int frame, double wt, const double *y,
                      double *sxi_out, double *seta_out) {
  double sxi = r->s0[j] * r->cpsi0[j], seta = r->s0[j] * r->spsi0[j];
  /* relative angle = state angle - shift; absolute = state angle + (wt - shift) */
  const double shift = frame == AUTOBAL_ROTOR_FIXED ? wt : 0.0;
  size_t k;
  for (k = r->off[j]; k < r->off[j] + r->cnt[j]; k++) {
    const double psi = y[8 + k] - shift;
    sxi += r->mr[k] * cos(psi);
    seta += r->mr[k] * sin(psi);
  }
  *sxi_out = sxi;
  *seta_out = seta;
}

/* plane_sxe with fastmath.h's sine and cosine (autobal_rotor_outputs_fast without the vector path:
 * more than 62 balls, or not GCC): the balls' relative angles in chunks of 32, their sines and
 * cosines by one vectorized pass (ball_sincos), then the same sums in the same order. */
static void plane_sxe_fast(const autobal_rotor *r, size_t j, int frame, double wt, const double *y,
                           double *sxi_out, double *seta_out) {
  enum { CHUNK = 32 };
  double sxi = r->s0[j] * r->cpsi0[j], seta = r->s0[j] * r->spsi0[j];
  double a[CHUNK], sn[CHUNK], cs[CHUNK];
  const double shift = frame == AUTOBAL_ROTOR_FIXED ? wt : 0.0;
  const size_t k1 = r->off[j] + r->cnt[j];
  size_t k0, i, m;
  for (k0 = r->off[j]; k0 < k1; k0 += m) {
    m = k1 - k0 < CHUNK ? k1 - k0 : CHUNK;
    for (i = 0; i < m; i++) a[i] = y[8 + k0 + i] - shift;
    ball_sincos(a, sn, cs, m);
    for (i = 0; i < m; i++) {
      sxi += r->mr[k0 + i] * cs[i];
      seta += r->mr[k0 + i] * sn[i];
    }
  }
  *sxi_out = sxi;
  *seta_out = seta;
}

/* s_u, s_v, s_xi, s_eta of plane j from its s_xi, s_eta and cos, sin of phi_0(t) (eq. (3.11)). */
static void plane_turn(double sxi, double seta, double cw, double sw, double s[4]) {
  s[2] = sxi;
  s[3] = seta;
  s[0] = sxi * cw - seta * sw; /* eq. (3.11) */
  s[1] = sxi * sw + seta * cw;
}

/* s_u, s_v, s_xi, s_eta of plane j; the state's ball angle + offset = absolute angle phi. */
static void plane_unbalance(const autobal_rotor *r, size_t j, int frame, double t, const double *y,
                            double s[4]) {
  double W, wt, sxi, seta;
  spin_state(r, t, y, &W, &wt); /* wt = phi_0(t) */
  plane_sxe(r, j, frame, wt, y, &sxi, &seta);
  plane_turn(sxi, seta, cos(wt), sin(wt), s);
}

int autobal_rotor_plane_unbalance(const autobal_rotor *r, size_t plane, int frame, double t,
                                  const double *y, double s[4]) {
  if (r == NULL || plane >= r->n_planes || y == NULL || s == NULL || !isfinite(t) ||
      (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING))
    return AUTOBAL_EINVAL;
  plane_unbalance(r, plane, frame, t, y, s);
  return AUTOBAL_SUCCESS;
}

double autobal_rotor_balance_monitor(const autobal_rotor *r, int frame, double t, const double *y) {
  double worst = 0.0, W, wt;
  size_t j;
  if (r == NULL || y == NULL || !isfinite(t) ||
      (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING))
    return NAN;
  /* only |(s_xi, s_eta)| of each plane: phi_0(t) once, its cosine and sine not needed */
  spin_state(r, t, y, &W, &wt);
  for (j = 0; j < r->n_planes; j++) {
    double rel, sxi, seta;
    plane_sxe(r, j, frame, wt, y, &sxi, &seta);
    rel = hypot(sxi, seta) / r->sref[j];
    if (rel > worst) worst = rel;
  }
  return worst;
}

#define N_GLOBAL_OUT 3u
#define N_PLANE_OUT 7u
#define N_BALL_OUT 6u

/* The outputs without the friction columns (the layout of 0.2.0). */
static size_t output_count_base(const autobal_rotor *r) {
  return N_GLOBAL_OUT + N_PLANE_OUT * r->n_planes + N_BALL_OUT * r->N + (r->dn > 0 ? 1u : 0u) +
         (r->motor ? 3u : 0u);
}

size_t autobal_rotor_output_count(const autobal_rotor *r) { return r ? r->nout : 0; }

/* The output columns' fast path for up to 62 balls (GCC's vector extensions): every ball column,
 * the balls' sines and cosines and the hypots in vectors of 4 doubles, with the same operations as
 * the scalar path, so the same bits (tests/test_derive_fast.c checks the ball columns bit for bit
 * at edge angles, the rest against autobal_rotor_outputs):
 *  - the relative angles psi and phi_0 in blocks of 4 lanes held in registers (no scalar stores
 *    read back as vectors: such a load waits until the stores are written), their sines and
 *    cosines by fastmath.h's 4-lane kernel (the bits of autobal_sincos_fast; libm for a lane out
 *    of its range, as autobal_sincos1);
 *  - the wraps (wrap_pi4) and the ball columns (ball_columns4: a 6 x 4 transpose by shuffles)
 *    straight from those vectors;
 *  - the four hypots that do not depend on the balls (amp_G, amp_L, amp_R, the first plane's
 *    amp_D) in one vector, sqrt by SSE2's instruction on x86-64 (correctly rounded as libm's sqrt,
 *    without the errno branch around it). */
#if defined(__GNUC__) && !defined(__clang__) && defined(AUTOBAL_FM_VECTORS)
#define ROTOR_VEC 1
typedef autobal_fm_v4 rotor_v4;
typedef autobal_fm_u4 rotor_u4;
typedef long long rotor_i4 __attribute__((vector_size(32)));

/* wrap_pi_formula on every lane, the same bits, without branches.  Under the default
 * -ftrapping-math GCC vectorizes neither ceil nor a conditional addition, so both are written
 * with masks:
 *  - ceil(q): r = (q + M) - M with M = 2^52 carrying the sign of q rounds |q| < 2^52 to the
 *    nearest integer (q + M lies where the spacing of doubles is 1, and the subtraction is
 *    exact); r < q means the nearest is below q: r + 1 (exact).  ceil(q) has the sign of q
 *    (-0 for q in (-1, 0]), and so has r after the sign bit of q is ORed in (r >= 0 for
 *    q >= 0, r <= 0 for q < 0).  |q| >= 2^52, inf and NaN are their own ceil: q is taken.
 *  - the corrections add 2 pi or +0.0 and subtract 2 pi or +0.0: w is never -0 before the
 *    first (a - c with c = 2 pi ceil(q) is -0 only for a = -0 and c = +0, but a = +-0 gives
 *    ceil(-0.5) = -0, c = -0), so adding +0.0 keeps its bits (NaN stays NaN), and subtracting
 *    +0.0 keeps any value's bits. */
static AUTOBAL_FM_INLINE void wrap_pi4(const rotor_v4 *xp, rotor_v4 *w) {
  const rotor_v4 x = *xp;
  const uint64_t sgn = (uint64_t)1 << 63;
  const double two52 = 0x1p52, one = 1.0, twopi = 2.0 * M_PI;
  uint64_t b52, bone, btp;
  rotor_v4 q, r, v;
  rotor_u4 bq, br, big;
  memcpy(&b52, &two52, sizeof b52);
  memcpy(&bone, &one, sizeof bone);
  memcpy(&btp, &twopi, sizeof btp);
  q = (x - M_PI) / (2.0 * M_PI);
  bq = (rotor_u4)q;
  r = (q + (rotor_v4)(b52 | (bq & sgn))) - (rotor_v4)(b52 | (bq & sgn));
  r += (rotor_v4)(bone & (rotor_u4)(r < q));
  br = (rotor_u4)r | (bq & sgn);
  big = 0u - (((b52 - 1u) - (bq & ~sgn)) >> 63); /* |q| >= 2^52 (inf, NaN too) */
  br = (bq & big) | (br & ~big);
  v = x - 2.0 * M_PI * (rotor_v4)br;
  v += (rotor_v4)(btp & (rotor_u4)(v <= -M_PI));
  *w = v - (rotor_v4)(btp & (rotor_u4)(v > M_PI));
}

/* p[0 .. m-1] (m < 4: zeros after; m >= 4: p[0 .. 3]), reading nothing beyond p[m - 1]. */
static AUTOBAL_FM_INLINE void load4(const double *p, size_t m, rotor_v4 *v) {
  if (m >= 4) memcpy(v, p, sizeof *v);
  else if (m == 3) *v = (rotor_v4){p[0], p[1], p[2], 0.0};
  else if (m == 2) *v = (rotor_v4){p[0], p[1], 0.0, 0.0};
  else if (m == 1) *v = (rotor_v4){p[0], 0.0, 0.0, 0.0};
  else *v = (rotor_v4){0.0, 0.0, 0.0, 0.0};
}

/* o[6 k + c] = lane k of column c (A .. F), k < m: the ball columns of m <= 4 balls in the layout
 * of the outputs, as a 6 x 4 transpose by two-input shuffles (12 shuffles, 6 stores of 4 doubles;
 * for 2 or 3 balls the first 3 stores hold balls 0 and 1); writes nothing beyond ball m - 1.
 * Moves only. */
static AUTOBAL_FM_INLINE void ball_columns4(double *restrict o, const rotor_v4 col[N_BALL_OUT], size_t m) {
  const rotor_v4 A = col[0], B = col[1], C = col[2], D = col[3], E = col[4], F = col[5];
  const rotor_i4 even = {0, 4, 2, 6}, odd = {1, 5, 3, 7}, lo = {0, 1, 4, 5}, hi = {2, 3, 6, 7};
  const rotor_v4 t0 = __builtin_shuffle(A, B, even); /* A0 B0 A2 B2 */
  const rotor_v4 t1 = __builtin_shuffle(A, B, odd);  /* A1 B1 A3 B3 */
  const rotor_v4 t2 = __builtin_shuffle(C, D, even); /* C0 D0 C2 D2 */
  const rotor_v4 t3 = __builtin_shuffle(C, D, odd);  /* C1 D1 C3 D3 */
  const rotor_v4 t4 = __builtin_shuffle(E, F, even); /* E0 F0 E2 F2 */
  const rotor_v4 t5 = __builtin_shuffle(E, F, odd);  /* E1 F1 E3 F3 */
  rotor_v4 v;
  if (m >= 2) {
    v = __builtin_shuffle(t0, t2, lo); /* ball 0: A0 B0 C0 D0 */
    memcpy(o, &v, sizeof v);
    v = __builtin_shuffle(t4, t1, lo); /* E0 F0, ball 1: A1 B1 */
    memcpy(o + 4, &v, sizeof v);
    v = __builtin_shuffle(t3, t5, lo); /* C1 D1 E1 F1 */
    memcpy(o + 8, &v, sizeof v);
  }
  if (m >= 4) {
    v = __builtin_shuffle(t0, t2, hi); /* ball 2: A2 B2 C2 D2 */
    memcpy(o + 12, &v, sizeof v);
    v = __builtin_shuffle(t4, t1, hi); /* E2 F2, ball 3: A3 B3 */
    memcpy(o + 16, &v, sizeof v);
    v = __builtin_shuffle(t3, t5, hi); /* C3 D3 E3 F3 */
    memcpy(o + 20, &v, sizeof v);
  } else if (m == 3 || m == 1) { /* the last ball alone */
    const size_t k = m - 1;
    double *ok = o + N_BALL_OUT * k;
    ok[0] = A[k];
    ok[1] = B[k];
    ok[2] = C[k];
    ok[3] = D[k];
    ok[4] = E[k];
    ok[5] = F[k];
  }
}

/* sqrt of every lane (IEEE, correctly rounded: libm's sqrt's bits); on x86-64 by SSE2's sqrtpd,
 * which has no errno branch around it (the lanes are >= 0 or NaN here: no exception to raise). */
static AUTOBAL_FM_INLINE void sqrt4(const rotor_v4 *s, rotor_v4 *h) {
#if defined(__x86_64__) && defined(__SSE2__)
  typedef double v2 __attribute__((vector_size(16)));
  const v2 a = __builtin_ia32_sqrtpd((v2){(*s)[0], (*s)[1]}), b = __builtin_ia32_sqrtpd((v2){(*s)[2], (*s)[3]});
  *h = (rotor_v4){a[0], a[1], b[0], b[1]};
#else
  *h = (rotor_v4){sqrt((*s)[0]), sqrt((*s)[1]), sqrt((*s)[2]), sqrt((*s)[3])};
#endif
}

/* autobal_hypot_fast on every lane, the same bits: sqrt(a a + b b) where the sum lies in
 * [2^-968, 2^1000], libm's hypot for the other lanes. */
static AUTOBAL_FM_INLINE void hypot_fast4(const rotor_v4 *a, const rotor_v4 *b, rotor_v4 *h) {
  const rotor_v4 s = *a * *a + *b * *b;
  const rotor_i4 ok = (s >= 0x1p-968) & (s <= 0x1p1000);
  sqrt4(&s, h);
  if ((ok[0] & ok[1] & ok[2] & ok[3]) == 0) {
    int k;
    for (k = 0; k < 4; k++)
      if (!ok[k]) (*h)[k] = hypot((*a)[k], (*b)[k]);
  }
}
#endif

/* The friction columns of out (the stuck flags of all balls, then their normal forces, after the
 * ball columns; the solve's workspace is the ball columns, written after this). */
static void friction_columns(const autobal_rotor *r, int frame, double t, const double *y, double *out) {
  double *fo = out + output_count_base(r);
  size_t k;
  if (fric_eval(r, out + N_GLOBAL_OUT + N_PLANE_OUT * r->n_planes, NULL, frame, t, y, NULL, fo + r->N, NULL, 0, NULL, 0) !=
      GSL_SUCCESS)
    for (k = 0; k < r->N; k++) fo[r->N + k] = NAN;
  for (k = 0; k < r->N; k++)
    fo[k] = (r->law == AUTOBAL_ROTOR_FRICTION_EXACT && r->mode[k] == AUTOBAL_ROTOR_BALL_STUCK) ? 1.0 : 0.0;
}

/* The drive's columns after the ball columns (o): Omega with a ramp or table; Omega, the motor's
 * torque and power with a motor. */
static AUTOBAL_FM_INLINE void spin_columns(const autobal_rotor *r, double W, double *o) {
  if (r->dn > 0) o[0] = W;
  if (r->motor) {
    o[0] = W;
    o[1] = motor_L(r, W);
    o[2] = o[1] * W;
  }
}

enum { FAST_TRIG = 63 }; /* the vector path: up to 62 balls (with phi_0, 63 lanes: 16 vectors) */

/* a plane's columns from its unbalance sum s (plane_turn) and |s|'s amplitude amp: the same
 * operations for the vector and the scalar paths */
static AUTOBAL_FM_INLINE void plane_columns(double *o, const double s[4], double amp, double sref) {
  o[0] = s[0];
  o[1] = s[1];
  o[2] = s[2];
  o[3] = s[3];
  o[4] = amp;
  o[5] = amp / sref;
}

#ifdef ROTOR_VEC
enum { FAST_VEC = FAST_TRIG / 4 + 1 };

/* The vector path's first stage for the point (t, y): Omega (*W), phi_0 (*wt), every ball's
 * relative angle psi (lane k of ta: ang - phi_0 in the fixed frame, ang - 0.0 = ang in the
 * rotating one) and phi_0 (lane N), zeros after it, in N / 4 + 1 vectors, and their sines sn[k]
 * and cosines cs[k] (libm for a lane out of the fast path's range, as autobal_sincos1). */
static AUTOBAL_FM_INLINE void vec_trig(const autobal_rotor *r, int frame, double t, const double *y, double *W,
                                       double *wt, rotor_v4 *ta, double *sn, double *cs) {
  const size_t N = r->N, nt = N / 4 + 1, m = N % 4;
  const rotor_i4 lane = {0, 1, 2, 3};
  const rotor_u4 ball = (rotor_u4)(lane < (long long)m), last = (rotor_u4)(lane == (long long)m);
  rotor_u4 bad = {0, 0, 0, 0};
  rotor_v4 a = {0.0, 0.0, 0.0, 0.0}, wtv, sv;
  double shift;
  size_t k;
  spin_state(r, t, y, W, wt);
  shift = frame == AUTOBAL_ROTOR_FIXED ? *wt : 0.0;
  wtv = (rotor_v4){*wt, *wt, *wt, *wt};
  sv = (rotor_v4){shift, shift, shift, shift};
  for (k = 0; k + 1 < nt; k++) {
    load4(y + 8 + 4 * k, 4, &a);
    ta[k] = a - shift;
  }
  /* the last: its m balls, phi_0, zeros (a lane without a ball subtracts +0.0 from +0.0) */
  load4(y + 8 + 4 * k, m, &a);
  ta[k] = (rotor_v4)((rotor_u4)(a - (rotor_v4)((rotor_u4)sv & ball)) | ((rotor_u4)wtv & last));
  for (k = 0; k < nt; k++) {
    rotor_v4 vs, vc;
    autobal_sincos_fast4(&ta[k], &vs, &vc);
    memcpy(sn + 4 * k, &vs, sizeof vs);
    memcpy(cs + 4 * k, &vc, sizeof vc);
    autobal_sincos_out_of_range4(&ta[k], &bad);
  }
  if (((bad[0] | bad[1] | bad[2] | bad[3]) >> 63) != 0) {
    for (k = 0; k <= N; k++) { /* libm out of the fast path's range (as autobal_sincos1) */
      const double ak = ta[k / 4][k % 4];
      if (!autobal_sincos_in_range(ak)) {
        sn[k] = sin(ak);
        cs[k] = cos(ak);
      }
    }
  }
}

/* The vector path's second stage: the planes' columns of the point (t, y) but amp_D of the first
 * (s_u, s_v, s_xi, s_eta, s_abs, s_rel; amp_D of the second) from vec_trig's sn, cs, the
 * expressions of the scalar path below: the rest of the chain from the ball angles to s_rel. */
static AUTOBAL_FM_INLINE void vec_planes(const autobal_rotor *r, const double *y, const double *sn,
                                         const double *cs, double *out) {
  const double sw = sn[r->N], cw = cs[r->N];
  double *o = out + N_GLOBAL_OUT;
  size_t j, k;
  for (j = 0; j < r->n_planes; j++, o += N_PLANE_OUT) {
    double s[4], sxi = r->s0[j] * r->cpsi0[j], seta = r->s0[j] * r->spsi0[j];
    for (k = r->off[j]; k < r->off[j] + r->cnt[j]; k++) { /* plane_sxe's sums */
      sxi += r->mr[k] * cs[k];
      seta += r->mr[k] * sn[k];
    }
    plane_turn(sxi, seta, cw, sw, s);
    plane_columns(o, s, autobal_hypot_fast(s[2], s[3]), r->sref[j]);
    if (j > 0) {
      const double x = y[0] - r->qs[0], yy = y[1] - r->qs[1], al = y[2] - r->qs[2], be = y[3] - r->qs[3];
      o[6] = autobal_hypot_fast(x + r->p.plane[j].d * be, yy - r->p.plane[j].d * al);
    }
  }
}

/* The vector path's third stage: the other columns of the point (t, y) (amplitudes, friction,
 * balls, drive) from vec_trig's W, wt, ta, the expressions of the scalar path below. */
static AUTOBAL_FM_INLINE void vec_columns(const autobal_rotor *r, int frame, double t, const double *y, double W,
                                          double wt, const rotor_v4 *ta, double *out) {
  const size_t N = r->N;
  const double x = y[0] - r->qs[0], yy = y[1] - r->qs[1], al = y[2] - r->qs[2], be = y[3] - r->qs[3];
  const double *ang = y + 8, *rate = y + 8 + N;
  double *o = out + N_GLOBAL_OUT + N_PLANE_OUT * r->n_planes;
  size_t k;
  {
    /* amp_G, amp_L, amp_R and the first plane's amp_D in one vector */
    const double d = r->p.plane[0].d;
    const rotor_v4 a = {x, x - r->l_L * be, x + r->l_R * be, x + d * be},
                   b = {yy, yy + r->l_L * al, yy - r->l_R * al, yy - d * al};
    rotor_v4 h;
    hypot_fast4(&a, &b, &h);
    out[0] = h[0];
    out[1] = h[1];
    out[2] = h[2];
    out[N_GLOBAL_OUT + 6] = h[3];
  }
  if (r->law != AUTOBAL_ROTOR_FRICTION_NONE) friction_columns(r, frame, t, y, out);
  /* the six ball columns 4 balls at a time: phi, its wrap, psi, its wrap (wrap_pi4: the formula
   * of wrap_pi without its |a| <= 3 shortcut and without branches, the same numbers; the branches
   * cost mispredictions where ball angles move about |a| = 3 or pi), the rates; psi = ta (above),
   * phi = ang (fixed) or ang + phi_0 (rotating) */
  for (k = 0; k < N; k += 4, o += 4 * N_BALL_OUT) {
    const size_t m = N - k < 4 ? N - k : 4;
    rotor_v4 c[N_BALL_OUT], a = {0.0, 0.0, 0.0, 0.0}, rt = {0.0, 0.0, 0.0, 0.0};
    load4(ang + k, m, &a);
    load4(rate + k, m, &rt);
    if (frame == AUTOBAL_ROTOR_FIXED) {
      c[0] = a;
      c[2] = ta[k / 4];
      c[4] = rt;
      c[5] = rt - W;
    } else {
      c[0] = a + wt;
      c[2] = a;
      c[4] = rt + W;
      c[5] = rt;
    }
    if (m <= 2) { /* at most 2 balls: phi in lanes 0, 1 and psi in 2, 3 of one wrap */
      const rotor_v4 pk = __builtin_shuffle(c[0], c[2], (rotor_i4){0, 1, 4, 5});
      rotor_v4 wk;
      wrap_pi4(&pk, &wk);
      c[1] = wk;
      c[3] = __builtin_shuffle(wk, (rotor_i4){2, 3, 0, 1});
    } else {
      wrap_pi4(&c[0], &c[1]);
      wrap_pi4(&c[2], &c[3]);
    }
    ball_columns4(o, c, m);
  }
  spin_columns(r, W, out + N_GLOBAL_OUT + N_PLANE_OUT * r->n_planes + N_BALL_OUT * N);
}
#endif

/* The arguments of the outputs calls: AUTOBAL_SUCCESS or AUTOBAL_EINVAL. */
static int outputs_check(const autobal_rotor *r, int frame, double t, const double *y, const double *out,
                         size_t n_out) {
  if (r == NULL || y == NULL || out == NULL || !isfinite(t) ||
      (frame != AUTOBAL_ROTOR_FIXED && frame != AUTOBAL_ROTOR_ROTATING) || n_out != r->nout)
    return AUTOBAL_EINVAL;
  return AUTOBAL_SUCCESS;
}

/* autobal_rotor_outputs; fast = 1 (a constant at both calls: inlined and specialized): sine,
 * cosine and hypot by fastmath.h instead of libm, the same expressions otherwise (with GCC and up
 * to 62 balls in vectors, above). */
static AUTOBAL_FM_INLINE int outputs(const autobal_rotor *r, int frame, double t, const double *y, double *out,
                                     size_t n_out, int fast) {
  size_t j, k;
  double x, yy, al, be, wt, W, cw, sw;
  double *o;
  if (outputs_check(r, frame, t, y, out, n_out) != AUTOBAL_SUCCESS) return AUTOBAL_EINVAL;
#ifdef ROTOR_VEC
  if (fast && r->N < FAST_TRIG) {
    rotor_v4 ta[FAST_VEC];
    double sn[4 * FAST_VEC], cs[4 * FAST_VEC];
    vec_trig(r, frame, t, y, &W, &wt, ta, sn, cs);
    vec_planes(r, y, sn, cs, out);
    vec_columns(r, frame, t, y, W, wt, ta, out);
    return AUTOBAL_SUCCESS;
  }
#endif
  x = y[0] - r->qs[0]; /* the amplitudes are about the static offset under gravity (qs = 0 without) */
  yy = y[1] - r->qs[1];
  al = y[2] - r->qs[2];
  be = y[3] - r->qs[3];
  spin_state(r, t, y, &W, &wt); /* Omega, phi_0 */
  if (fast) {
    autobal_sincos1(wt, &sw, &cw);
  } else {
    cw = cos(wt); /* once for every plane */
    sw = sin(wt);
  }
#define ROTOR_HYPOT(a, b) (fast ? autobal_hypot_fast((a), (b)) : hypot((a), (b)))
  out[0] = ROTOR_HYPOT(x, yy);
  /* a body point at axial coordinate p moves by (x + p beta, y - p alpha) */
  out[1] = ROTOR_HYPOT(x - r->l_L * be, yy + r->l_L * al);
  out[2] = ROTOR_HYPOT(x + r->l_R * be, yy - r->l_R * al);
  o = out + N_GLOBAL_OUT;
  for (j = 0; j < r->n_planes; j++, o += N_PLANE_OUT) {
    const double d = r->p.plane[j].d;
    double s[4], sxi, seta;
    if (fast) plane_sxe_fast(r, j, frame, wt, y, &sxi, &seta);
    else plane_sxe(r, j, frame, wt, y, &sxi, &seta);
    plane_turn(sxi, seta, cw, sw, s);
    plane_columns(o, s, ROTOR_HYPOT(s[2], s[3]), r->sref[j]);
    o[6] = ROTOR_HYPOT(x + d * be, yy - d * al);
  }
#undef ROTOR_HYPOT
  if (r->law != AUTOBAL_ROTOR_FRICTION_NONE) friction_columns(r, frame, t, y, out);
  for (k = 0; k < r->N; k++, o += N_BALL_OUT) {
    const double ang = y[8 + k], rate = y[8 + r->N + k];
    double phi, psi, phid, psid;
    if (frame == AUTOBAL_ROTOR_FIXED) {
      phi = ang;
      psi = ang - wt;
      phid = rate;
      psid = rate - W;
    } else {
      psi = ang;
      phi = ang + wt;
      psid = rate;
      phid = rate + W;
    }
    /* fast without the vectors: wrap_pi's formula without the shortcut (the vector path's numbers) */
    o[0] = phi;
    o[1] = fast ? wrap_pi_formula(phi) : wrap_pi(phi);
    o[2] = psi;
    o[3] = fast ? wrap_pi_formula(psi) : wrap_pi(psi);
    o[4] = phid;
    o[5] = psid;
  }
  spin_columns(r, W, o);
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_outputs(const autobal_rotor *r, int frame, double t, const double *y, double *out,
                          size_t n_out) {
  return outputs(r, frame, t, y, out, n_out, 0);
}

/* compiled for AVX2 too (as ball_sincos; no FMA, so the same bits): the vector path's 4 lanes in
 * one instruction (two with SSE2) */
ROTOR_CLONES int autobal_rotor_outputs_fast(const autobal_rotor *r, int frame, double t, const double *y, double *out,
                                            size_t n_out) {
  return outputs(r, frame, t, y, out, n_out, 1);
}

/* rotor_internal.h.  The vector path in stages over up to 8 points at a time: every point's sines
 * and cosines (vec_trig), then every point's plane columns (vec_planes), then the rest
 * (vec_columns).  The chain from a point's ball angles through the sines, the sums, sqrt and the
 * division to s_rel is long; in short loops of their own the chains of successive points run side
 * by side, where one point at a time waits for its own. */
ROTOR_CLONES int autobal_rotor_outputs_fast_block(const autobal_rotor *r, int frame, size_t n, const double *t,
                                                  const double *y, size_t ystride, double *out, size_t ostride) {
  size_t k;
  if (r == NULL || (n > 0 && (t == NULL || y == NULL || out == NULL)) || ystride < r->dim || ostride < r->nout)
    return AUTOBAL_EINVAL;
  for (k = 0; k < n; k++)
    if (outputs_check(r, frame, t[k], y + k * ystride, out + k * ostride, r->nout) != AUTOBAL_SUCCESS)
      return AUTOBAL_EINVAL;
#ifdef ROTOR_VEC
  if (r->N < FAST_TRIG) {
    enum { CH = 8 };
    rotor_v4 ta[CH][FAST_VEC];
    double sn[CH][4 * FAST_VEC], cs[CH][4 * FAST_VEC], W[CH], wt[CH];
    size_t k0, i, m;
    for (k0 = 0; k0 < n; k0 += m) {
      m = n - k0 < CH ? n - k0 : CH;
      for (i = 0; i < m; i++) vec_trig(r, frame, t[k0 + i], y + (k0 + i) * ystride, &W[i], &wt[i], ta[i], sn[i], cs[i]);
      for (i = 0; i < m; i++) vec_planes(r, y + (k0 + i) * ystride, sn[i], cs[i], out + (k0 + i) * ostride);
      for (i = 0; i < m; i++)
        vec_columns(r, frame, t[k0 + i], y + (k0 + i) * ystride, W[i], wt[i], ta[i], out + (k0 + i) * ostride);
    }
    return AUTOBAL_SUCCESS;
  }
#endif
  for (k = 0; k < n; k++) (void)outputs(r, frame, t[k], y + k * ystride, out + k * ostride, r->nout, 1);
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_output_name(const autobal_rotor *r, size_t k, char *buf, size_t len,
                              const char **unit) {
  static const char *const gname[N_GLOBAL_OUT] = {"amp_G", "amp_L", "amp_R"};
  static const char *const pname[N_PLANE_OUT] = {"s_u", "s_v", "s_xi", "s_eta",
                                                 "s_abs", "s_rel", "amp_D"};
  static const char *const punit[N_PLANE_OUT] = {"kg m", "kg m", "kg m", "kg m", "kg m", "1", "m"};
  static const char *const bname[N_BALL_OUT] = {"phi", "phi_w", "psi", "psi_w", "phi_rate", "psi_rate"};
  static const char *const bunit[N_BALL_OUT] = {"rad", "rad", "rad", "rad", "rad/s", "rad/s"};
  const char *u;
  if (r == NULL || buf == NULL || len == 0 || k >= autobal_rotor_output_count(r)) return AUTOBAL_EINVAL;
  if (k >= output_count_base(r)) { /* friction: stuck flags, then normal forces */
    size_t ball = k - output_count_base(r), j = 0;
    const int isN = ball >= r->N;
    if (isN) ball -= r->N;
    while (j + 1 < r->n_planes && ball >= r->off[j + 1]) j++;
    snprintf(buf, len, "p%zu_b%zu_%s", j + 1, ball - r->off[j] + 1, isN ? "N" : "stuck");
    if (unit) *unit = isN ? "N" : "1";
    return AUTOBAL_SUCCESS;
  }
  if (k < N_GLOBAL_OUT) {
    snprintf(buf, len, "%s", gname[k]);
    u = "m";
  } else if (k < N_GLOBAL_OUT + N_PLANE_OUT * r->n_planes) {
    size_t kk = k - N_GLOBAL_OUT;
    snprintf(buf, len, "p%zu_%s", kk / N_PLANE_OUT + 1, pname[kk % N_PLANE_OUT]);
    u = punit[kk % N_PLANE_OUT];
  } else if (r->dn > 0 && k + 1 == output_count_base(r)) {
    snprintf(buf, len, "Omega");
    u = "rad/s";
  } else if (r->motor && k + 3 >= output_count_base(r)) {
    static const char *const mname[3] = {"Omega", "motor_torque", "motor_power"};
    static const char *const munit[3] = {"rad/s", "N m", "W"};
    const size_t km = k + 3 - output_count_base(r);
    snprintf(buf, len, "%s", mname[km]);
    u = munit[km];
  } else {
    size_t kk = k - N_GLOBAL_OUT - N_PLANE_OUT * r->n_planes;
    size_t ball = kk / N_BALL_OUT, j = 0;
    while (j + 1 < r->n_planes && ball >= r->off[j + 1]) j++;
    snprintf(buf, len, "p%zu_b%zu_%s", j + 1, ball - r->off[j] + 1, bname[kk % N_BALL_OUT]);
    u = bunit[kk % N_BALL_OUT];
  }
  if (unit) *unit = u;
  return AUTOBAL_SUCCESS;
}

/* ---- balanced configurations (3.14) --------------------------------------------- */

int autobal_rotor_balanced_angles_two(double s0, double a1, double a2, double psi0, double psi[2],
                                      autobal_error *err) {
  int st;
  double g1, g2, c1, c2;
  if ((st = autobal_check_param(err, "s0", s0, 0.0, 0, INFINITY, 1, "kg m")) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_check_param(err, "a1", a1, 0.0, 1, INFINITY, 1, "kg m")) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_check_param(err, "a2", a2, 0.0, 1, INFINITY, 1, "kg m")) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_check_param(err, "psi0", psi0, -INFINITY, 1, INFINITY, 1, "rad")) != AUTOBAL_SUCCESS)
    return st;
  if (psi == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "output array psi is NULL");
  {
    const double a[2] = {a1, a2};
    if (!autobal_rotor_plane_can_balance(s0, a, 2))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "two balls with m r = %.6g and %.6g kg m cannot cancel m0 r0 = %.6g kg "
                               "m (need |a1 - a2| <= m0 r0 <= a1 + a2)",
                               a1, a2, s0);
  }
  if (s0 == 0.0) {
    /* a1 == a2 here (can_balance): any diametrically opposite pair */
    g1 = 0.5 * M_PI;
    g2 = 0.5 * M_PI;
  } else {
    /* triangle with sides s0, a1, a2; g1, g2: angles of the balls from the
     * direction psi0 + pi opposite the unbalance (law of cosines) */
    c1 = (s0 * s0 + a1 * a1 - a2 * a2) / (2.0 * a1 * s0);
    c2 = (s0 * s0 + a2 * a2 - a1 * a1) / (2.0 * a2 * s0);
    if (c1 > 1.0) c1 = 1.0;
    if (c1 < -1.0) c1 = -1.0;
    if (c2 > 1.0) c2 = 1.0;
    if (c2 < -1.0) c2 = -1.0;
    g1 = acos(c1);
    g2 = acos(c2);
  }
  /* eq. (3.14): psi_1,2 = pi -/+ arccos(m0 r0 / (2 m r)) for a1 = a2 */
  psi[0] = wrap_pi(psi0 + M_PI - g1);
  psi[1] = wrap_pi(psi0 + M_PI + g2);
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_balanced_angles(const autobal_rotor *r, size_t plane, double *psi, size_t n,
                                  autobal_error *err) {
  const double *a;
  size_t i, n_b;
  double s0, psi0;
  if (r == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "rotor handle is NULL");
  if (plane >= r->n_planes)
    return autobal_error_set(err, AUTOBAL_EINVAL, "plane index %zu is out of range: %zu plane(s)",
                             plane, r->n_planes);
  n_b = r->cnt[plane];
  if (n != n_b || (n > 0 && psi == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "balanced angles: n = %zu must equal the plane's ball count %zu", n, n_b);
  a = r->mr + r->off[plane];
  s0 = r->s0[plane];
  psi0 = r->p.plane[plane].psi0;
  if (!autobal_rotor_plane_can_balance(s0, a, n))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "plane[%zu]: no balanced configuration exists for m0 r0 = %.6g kg m", plane,
                             s0);
  if (n == 0) return AUTOBAL_SUCCESS;
  if (n == 1) {
    psi[0] = wrap_pi(psi0 + M_PI);
    return AUTOBAL_SUCCESS;
  }
  if (n == 2) return autobal_rotor_balanced_angles_two(s0, a[0], a[1], psi0, psi, err);
  {
    int identical = 1;
    for (i = 1; i < n; i++)
      if (fabs(a[i] - a[0]) > 1e-12 * a[0]) identical = 0;
    if (identical) {
      /* symmetric fan: sum_i e^{i (i-(n-1)/2) delta} = sin(n x) / sin(x), x = delta/2,
       * decreasing from n (x -> 0) to 0 (x = pi/n); solve = s0/a by bisection */
      const double target = s0 / a[0], nn = (double)n;
      double lo = 0.0, hi = M_PI / nn, x;
      int it;
      for (it = 0; it < 200; it++) {
        const double mid = 0.5 * (lo + hi);
        const double f = sin(nn * mid) / sin(mid);
        if (f > target) lo = mid;
        else hi = mid;
      }
      x = 0.5 * (lo + hi);
      if (target >= nn) x = 0.0;
      for (i = 0; i < n; i++)
        psi[i] = wrap_pi(psi0 + M_PI + ((double)i - 0.5 * (nn - 1.0)) * 2.0 * x);
      return AUTOBAL_SUCCESS;
    }
  }
  {
    /* general masses: place balls one by one; T = remaining target vector */
    double Tx = -s0 * cos(psi0), Ty = -s0 * sin(psi0);
    for (i = 0; i + 2 < n; i++) {
      double rest = 0.0, amax = 0.0, lrest, tau, lo, hi, rho, ang, cg;
      size_t k;
      for (k = i + 1; k < n; k++) {
        rest += a[k];
        if (a[k] > amax) amax = a[k];
      }
      lrest = 2.0 * amax - rest;
      if (lrest < 0.0) lrest = 0.0;
      tau = hypot(Tx, Ty);
      lo = fmax(lrest, fabs(tau - a[i]));
      hi = fmin(rest, tau + a[i]);
      rho = 0.5 * (lo + hi);
      if (tau > 0.0) {
        cg = (tau * tau + a[i] * a[i] - rho * rho) / (2.0 * tau * a[i]);
        cg = cg > 1.0 ? 1.0 : (cg < -1.0 ? -1.0 : cg);
        ang = atan2(Ty, Tx) + ((i % 2) ? -acos(cg) : acos(cg));
      } else {
        ang = 0.0;
      }
      psi[i] = wrap_pi(ang);
      Tx -= a[i] * cos(ang);
      Ty -= a[i] * sin(ang);
    }
    /* the last two balls: a triangle on the remaining target T = -s e^{i p0} */
    return autobal_rotor_balanced_angles_two(hypot(Tx, Ty), a[n - 2], a[n - 1], atan2(-Ty, -Tx),
                                             psi + n - 2, err);
  }
}

double autobal_rotor_time_to_balance(const double *t, const double *monitor, size_t n,
                                     double threshold) {
  size_t k;
  if (t == NULL || monitor == NULL || n == 0 || !(monitor[n - 1] < threshold)) return NAN;
  k = n - 1;
  while (k > 0 && monitor[k - 1] < threshold) k--;
  return t[k];
}
