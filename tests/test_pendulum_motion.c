/* test_pendulum_motion.c: the explicit form of the equations of motion (1)
 * (src/models/pendulum/pendulum_motion.c) driven by the transient engine.
 *
 * Independent checks:
 *  - the accelerations satisfy (1) exactly as written in docs/pendulum.md (residuals);
 *  - (4) is an equilibrium, and so is psi = phi = pi - psi0;
 *  - analytic Jacobian = central differences of the rhs; at (4) it equals
 *    the first-order matrix of (5) built here from (5) of docs/pendulum.md, and the
 *    library's autobal_pendulum_first_order_matrix();
 *  - the nonlinear transient approaches the linear one (5) as O(amplitude^2);
 *  - with H = h = 0 the Jacobi integral (computed here from the point masses'
 *    kinematics, independently of the library's formula) is conserved; with
 *    damping its change equals the work of the damping forces;
 *  - stable parameters (all roots of (5) in the left half plane) converge to
 *    (4), unstable ones do not; the decay/growth rate of a transient equals
 *    the largest real part of the roots;
 *  - rk8pd, rkck and msbdf agree at tight tolerance;
 *  - the residual unbalance and its "time to balance" dwell event;
 *  - error paths: NULL params, a singular acceleration system (R_m = 1/2). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>

#include "autobal/pendulum.h"
#include "autobal/transient.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* stable (R_w above the critical speeds), unstable (R_w = 1.2), heavy
 * pendulums, undamped */
static autobal_pendulum_params P_STABLE = {3.0, 0.1, 0.2, 1.0, 0.5};
static autobal_pendulum_params P_UNSTABLE = {1.2, 0.1, 0.2, 1.0, 0.5};
static autobal_pendulum_params P_HEAVY = {1.7, 0.45, 0.3, 0.7, 1.2};
static autobal_pendulum_params P_UNDAMPED = {2.5, 0.1, 0.0, 0.0, 0.6};

/* deterministic pseudo-random numbers in [-1, 1) */
static double urand(unsigned long *s) {
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

static void random_state(unsigned long *seed, double y[8]) {
  int i;
  for (i = 0; i < 8; i++) y[i] = urand(seed);
  y[2] *= 3.0; /* angles anywhere */
  y[3] *= 3.0;
}

/* the first-order matrix of (5), written out from the spec page:
 * M q'' + C q' + K q = 0, q = (xi, eta, alpha, beta) */
static void spec_linear_matrix(const autobal_pendulum_params *p, double A[64]) {
  const double Rw = p->R_w, Rm = p->R_m, H = p->H, h = p->h;
  const double s0 = sin(p->psi0), c0 = cos(p->psi0), W = Rw * Rw;
  const double M[16] = {1, 0, -Rm * c0, -Rm * c0, 0, 1, -Rm * s0, Rm * s0,
                        -c0, -s0, 1, 0, -c0, s0, 0, 1};
  const double C[16] = {H, -2 * Rw, 2 * Rm * Rw * s0, -2 * Rm * Rw * s0,
                        2 * Rw, H, -2 * Rm * Rw * c0, -2 * Rm * Rw * c0,
                        -2 * Rw * s0, 2 * Rw * c0, h, 0,
                        2 * Rw * s0, 2 * Rw * c0, 0, h};
  const double K[16] = {1 - W, -H * Rw, Rm * W * c0, Rm * W * c0,
                        H * Rw, 1 - W, Rm * W * s0, -Rm * W * s0,
                        W * c0, W * s0, 0, 0,
                        W * c0, -W * s0, 0, 0};
  double Mi[16], aug[4][8];
  int i, j, k;
  /* invert M by Gauss-Jordan with partial pivoting */
  for (i = 0; i < 4; i++)
    for (j = 0; j < 8; j++) aug[i][j] = j < 4 ? M[i * 4 + j] : (j - 4 == i ? 1.0 : 0.0);
  for (k = 0; k < 4; k++) {
    int piv = k;
    for (i = k + 1; i < 4; i++)
      if (fabs(aug[i][k]) > fabs(aug[piv][k])) piv = i;
    for (j = 0; j < 8; j++) {
      double t = aug[k][j];
      aug[k][j] = aug[piv][j];
      aug[piv][j] = t;
    }
    for (j = 7; j >= 0; j--) aug[k][j] /= aug[k][k];
    for (i = 0; i < 4; i++) {
      if (i == k) continue;
      {
        const double f = aug[i][k];
        for (j = 0; j < 8; j++) aug[i][j] -= f * aug[k][j];
      }
    }
  }
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) Mi[i * 4 + j] = aug[i][j + 4];
  memset(A, 0, 64 * sizeof(double));
  for (i = 0; i < 4; i++) A[i * 8 + 4 + i] = 1.0;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) {
      double sk = 0.0, sc = 0.0;
      for (k = 0; k < 4; k++) {
        sk += Mi[i * 4 + k] * K[k * 4 + j];
        sc += Mi[i * 4 + k] * C[k * 4 + j];
      }
      A[(4 + i) * 8 + j] = -sk;
      A[(4 + i) * 8 + 4 + j] = -sc;
    }
}

/* eigen-decomposition of A: the eigenvalue with the largest real part
 * (lam_re, lam_im >= 0) and the real part of its eigenvector (vr[8]) */
static void dominant_mode(const double A[64], double *lam_re, double *lam_im, double vr[8]) {
  gsl_matrix *m = gsl_matrix_alloc(8, 8);
  gsl_vector_complex *ev = gsl_vector_complex_alloc(8);
  gsl_matrix_complex *evec = gsl_matrix_complex_alloc(8, 8);
  gsl_eigen_nonsymmv_workspace *w = gsl_eigen_nonsymmv_alloc(8);
  size_t i, best = 0;
  for (i = 0; i < 64; i++) m->data[i] = A[i];
  gsl_eigen_nonsymmv(m, ev, evec, w);
  for (i = 1; i < 8; i++) {
    const double re = GSL_REAL(gsl_vector_complex_get(ev, i));
    const double im = GSL_IMAG(gsl_vector_complex_get(ev, i));
    const double bre = GSL_REAL(gsl_vector_complex_get(ev, best));
    const double bim = GSL_IMAG(gsl_vector_complex_get(ev, best));
    if (re > bre + 1e-12 || (fabs(re - bre) <= 1e-12 && im > bim)) best = i;
  }
  *lam_re = GSL_REAL(gsl_vector_complex_get(ev, best));
  *lam_im = GSL_IMAG(gsl_vector_complex_get(ev, best));
  for (i = 0; i < 8; i++) vr[i] = GSL_REAL(gsl_matrix_complex_get(evec, i, best));
  gsl_eigen_nonsymmv_free(w);
  gsl_matrix_complex_free(evec);
  gsl_vector_complex_free(ev);
  gsl_matrix_free(m);
}

/* ---- 1. the accelerations satisfy (1) as printed ------------------------------ */

static void spec_residuals(const autobal_pendulum_params *p, const double y[8], const double f[8],
                           double res[4], double *scale) {
  const double Rw = p->R_w, Rm = p->R_m, H = p->H, h = p->h, s0 = sin(p->psi0);
  const double xi = y[0], eta = y[1], psi = y[2], phi = y[3];
  const double dxi = y[4], deta = y[5], dpsi = y[6], dphi = y[7];
  const double ddxi = f[4], ddeta = f[5], ddpsi = f[6], ddphi = f[7];
  const double s1 = sin(psi), c1 = cos(psi), s2 = sin(phi), c2 = cos(phi);
  const double Ax = ddxi - 2 * Rw * deta - Rw * Rw * xi;
  const double By = ddeta + 2 * Rw * dxi - Rw * Rw * eta;
  res[0] = ddxi - 2 * Rw * deta - Rw * Rw * xi + H * (dxi - Rw * eta) + xi -
           Rm * (ddpsi * c1 + ddphi * c2 - 2 * Rw * (dpsi * s1 - dphi * s2) - dpsi * dpsi * s1 -
                 dphi * dphi * s2 + Rw * Rw * (2 * s0 - s1 - s2));
  res[1] = ddeta + 2 * Rw * dxi - Rw * Rw * eta + H * (deta + Rw * xi) + eta -
           Rm * (ddpsi * s1 - ddphi * s2 + 2 * Rw * (dpsi * c1 + dphi * c2) + dpsi * dpsi * c1 -
                 dphi * dphi * c2 + Rw * Rw * (c1 - c2));
  res[2] = ddpsi + h * dpsi - By * s1 - Ax * c1;
  res[3] = ddphi + h * dphi + By * s2 - Ax * c2;
  *scale = 1.0 + fabs(ddxi) + fabs(ddeta) + fabs(ddpsi) + fabs(ddphi) + Rw * Rw + Rw * 2 +
           dpsi * dpsi + dphi * dphi;
}

static void test_equations(void) {
  autobal_pendulum_params *sets[] = {&P_STABLE, &P_UNSTABLE, &P_HEAVY, &P_UNDAMPED};
  unsigned long seed = 12345;
  double worst = 0.0;
  size_t k;
  int i;
  for (k = 0; k < 4; k++) {
    for (i = 0; i < 50; i++) {
      double y[8], f[8], res[4], scale;
      int j;
      random_state(&seed, y);
      CHECK_STATUS("rhs status", autobal_pendulum_rhs(0.0, y, f, sets[k]), 0);
      spec_residuals(sets[k], y, f, res, &scale);
      for (j = 0; j < 4; j++) worst = fmax(worst, fabs(res[j]) / scale);
      if (f[0] != y[4] || f[1] != y[5] || f[2] != y[6] || f[3] != y[7]) worst = INFINITY;
    }
  }
  CHECK_CLOSE("max relative residual of (1) over 200 random states", worst, 0.0, 0.0, 1e-14);

  for (k = 0; k < 4; k++) {
    double y[8], f[8], fmaxabs = 0.0;
    int j;
    autobal_pendulum_main_motion(sets[k], y);
    autobal_pendulum_rhs(0.0, y, f, sets[k]);
    for (j = 0; j < 8; j++) fmaxabs = fmax(fmaxabs, fabs(f[j]));
    CHECK_CLOSE("main motion (4) is an equilibrium: max |f|", fmaxabs, 0.0, 0.0, 1e-15);
    y[2] = y[3] = M_PI - sets[k]->psi0;
    autobal_pendulum_rhs(0.0, y, f, sets[k]);
    fmaxabs = 0.0;
    for (j = 0; j < 8; j++) fmaxabs = fmax(fmaxabs, fabs(f[j]));
    CHECK_CLOSE("psi = phi = pi - psi0 is an equilibrium: max |f|", fmaxabs, 0.0, 0.0, 1e-15);
  }
}

/* ---- 2. Jacobian ---------------------------------------------------------------- */

static void test_jacobian(void) {
  autobal_pendulum_params *sets[] = {&P_STABLE, &P_UNSTABLE, &P_HEAVY, &P_UNDAMPED};
  unsigned long seed = 777;
  double worst = 0.0;
  size_t k;
  int i, j, l;
  for (k = 0; k < 4; k++) {
    for (i = 0; i < 10; i++) {
      double y[8], J[64], dfdt[8];
      random_state(&seed, y);
      autobal_pendulum_jac(0.0, y, J, dfdt, sets[k]);
      for (j = 0; j < 8; j++) {
        double yp[8], ym[8], fp[8], fm[8];
        const double d = 1e-5;
        memcpy(yp, y, sizeof yp);
        memcpy(ym, y, sizeof ym);
        yp[j] += d;
        ym[j] -= d;
        autobal_pendulum_rhs(0.0, yp, fp, sets[k]);
        autobal_pendulum_rhs(0.0, ym, fm, sets[k]);
        for (l = 0; l < 8; l++) {
          const double fd = (fp[l] - fm[l]) / (2 * d);
          worst = fmax(worst, fabs(J[l * 8 + j] - fd) / (1.0 + fabs(fd)));
        }
      }
      for (j = 0; j < 8; j++)
        if (dfdt[j] != 0.0) worst = INFINITY;
    }
  }
  CHECK_CLOSE("analytic Jacobian vs central differences (max rel. diff, 40 states)", worst, 0.0,
              0.0, 1e-8);

  for (k = 0; k < 4; k++) {
    double y[8], J[64], dfdt[8], A[64], Alib[64], d1 = 0.0, d2 = 0.0;
    autobal_error err;
    int rc;
    autobal_pendulum_main_motion(sets[k], y);
    autobal_pendulum_jac(0.0, y, J, dfdt, sets[k]);
    spec_linear_matrix(sets[k], A);
    rc = autobal_pendulum_first_order_matrix(sets[k], Alib, &err);
    CHECK_STATUS("library first-order matrix of (5)", rc, AUTOBAL_SUCCESS);
    for (j = 0; j < 64; j++) {
      d1 = fmax(d1, fabs(J[j] - A[j]));
      d2 = fmax(d2, fabs(J[j] - Alib[j]));
    }
    CHECK_CLOSE("Jacobian at (4) = matrix of (5) written from the spec (max diff)", d1, 0.0, 0.0,
                1e-13);
    CHECK_CLOSE("Jacobian at (4) = autobal_pendulum_first_order_matrix (max diff)", d2, 0.0, 0.0,
                1e-13);
  }
}

/* ---- helpers to run the pendulum --------------------------------------------- */

typedef struct linear_sys {
  double A[64];
} linear_sys;

static int linear_rhs(double t, const double z[], double f[], void *p) {
  const linear_sys *L = (const linear_sys *)p;
  int i, j;
  (void)t;
  for (i = 0; i < 8; i++) {
    double s = 0.0;
    for (j = 0; j < 8; j++) s += L->A[i * 8 + j] * z[j];
    f[i] = s;
  }
  return 0;
}

/* observer storing a trajectory on the output grid */
#define MAXREC 2048
typedef struct traj {
  int n;
  double t[MAXREC];
  double y[MAXREC][8];
} traj;

static int record(double t, const double y[], void *user) {
  traj *tj = (traj *)user;
  if (tj->n < MAXREC) {
    tj->t[tj->n] = t;
    memcpy(tj->y[tj->n], y, 8 * sizeof(double));
  }
  tj->n++;
  return 0;
}

static autobal_transient *make(const char *stepper, double tol, double dt_out) {
  autobal_transient_options o = autobal_transient_options_default();
  o.stepper = stepper;
  o.rtol = tol;
  o.atol = tol;
  o.dt_out = dt_out;
  return autobal_transient_alloc(8, &o, NULL);
}

static int run_pendulum(autobal_transient *tr, autobal_pendulum_params *p, double t1,
                        double y[8]) {
  autobal_transient_system sys = {autobal_pendulum_rhs, autobal_pendulum_jac, 8, p};
  return autobal_transient_run(tr, &sys, 0.0, t1, y, NULL);
}

/* deviation from (4) with wrapped angles */
static double deviation_norm(const autobal_pendulum_params *p, const double y[8]) {
  double d[8], s = 0.0;
  int i;
  memcpy(d, y, sizeof d);
  d[2] = autobal_pendulum_wrap_angle(y[2] - p->psi0);
  d[3] = autobal_pendulum_wrap_angle(y[3] - p->psi0);
  for (i = 0; i < 8; i++) s += d[i] * d[i];
  return sqrt(s);
}

/* ---- 3. linearization ------------------------------------------------------------ */

static double lin_vs_nonlin(autobal_pendulum_params *p, double eps) {
  static const double v[8] = {0.3, -0.2, 0.5, -0.4, 0.1, 0.2, -0.3, 0.25};
  static traj tn, tl;
  linear_sys L;
  autobal_transient_system lsys = {linear_rhs, NULL, 8, &L};
  autobal_transient *tr = make("rk8pd", 1e-13, 0.5);
  double y[8], z[8], err = 0.0;
  int i, j;
  spec_linear_matrix(p, L.A);
  autobal_pendulum_main_motion(p, y);
  for (i = 0; i < 8; i++) {
    z[i] = eps * v[i];
    y[i] += z[i];
  }
  tn.n = tl.n = 0;
  autobal_transient_set_observer(tr, record, &tn);
  run_pendulum(tr, p, 20.0, y);
  autobal_transient_set_observer(tr, record, &tl);
  autobal_transient_run(tr, &lsys, 0.0, 20.0, z, NULL);
  for (i = 0; i < tn.n && i < tl.n; i++) {
    double base[8];
    autobal_pendulum_main_motion(p, base);
    for (j = 0; j < 8; j++) err = fmax(err, fabs(tn.y[i][j] - base[j] - tl.y[i][j]));
  }
  if (tn.n != tl.n || tn.n != 41) err = INFINITY;
  autobal_transient_free(tr);
  return err;
}

static void test_linearization(void) {
  autobal_pendulum_params *sets[] = {&P_STABLE, &P_HEAVY};
  size_t k;
  for (k = 0; k < 2; k++) {
    const double e1 = lin_vs_nonlin(sets[k], 1e-3);
    const double e2 = lin_vs_nonlin(sets[k], 2e-3);
    printf("     nonlinear - linear (5), tau in [0,20]: eps 1e-3: %.3e, eps 2e-3: %.3e, ratio %.3f\n",
           e1, e2, e2 / e1);
    CHECK("nonlinear - linear is O(eps^2): err(1e-3) < 50 eps^2", e1 < 50 * 1e-6);
    CHECK_CLOSE("doubling eps multiplies the difference by 4", e2 / e1, 4.0, 0.0, 0.3);
  }
}

/* ---- 4. Jacobi integral ----------------------------------------------------------- */

/* E = T2 - T0 + V from the point masses (rotating axes, positions relative to
 * K, units of l; masses in units of M_sigma), independently of the library */
static double jacobi_from_masses(const autobal_pendulum_params *p, const double y[8]) {
  const double Rm = p->R_m, W = p->R_w * p->R_w;
  const double e_over_l = 2 * Rm * sin(p->psi0) / (1 - 2 * Rm); /* M e = 2 m l sin psi0 */
  const double mass[3] = {1 - 2 * Rm, Rm, Rm};
  const double r[3][2] = {{y[0] + e_over_l, y[1]},
                          {y[0] - sin(y[2]), y[1] + cos(y[2])},
                          {y[0] - sin(y[3]), y[1] - cos(y[3])}};
  const double v[3][2] = {{y[4], y[5]},
                          {y[4] - cos(y[2]) * y[6], y[5] - sin(y[2]) * y[6]},
                          {y[4] - cos(y[3]) * y[7], y[5] + sin(y[3]) * y[7]}};
  double T2 = 0.0, T0 = 0.0;
  int i;
  for (i = 0; i < 3; i++) {
    T2 += 0.5 * mass[i] * (v[i][0] * v[i][0] + v[i][1] * v[i][1]);
    T0 += 0.5 * mass[i] * W * (r[i][0] * r[i][0] + r[i][1] * r[i][1]);
  }
  return T2 - T0 + 0.5 * (y[0] * y[0] + y[1] * y[1]);
}

/* power of the damping forces, from the spec's forces: -H2 v_abs on the shaft,
 * -H1 psi' on each pendulum (generalized forces times generalized velocities) */
static double damping_power(const autobal_pendulum_params *p, const double y[8]) {
  const double Qxi = -p->H * (y[4] - p->R_w * y[1]);
  const double Qeta = -p->H * (y[5] + p->R_w * y[0]);
  return Qxi * y[4] + Qeta * y[5] - p->R_m * p->h * (y[6] * y[6] + y[7] * y[7]);
}

typedef struct energy_rec {
  const autobal_pendulum_params *p;
  double E0, max_drift;
  int n;
} energy_rec;

static int energy_observer(double t, const double y[], void *user) {
  energy_rec *r = (energy_rec *)user;
  const double E = jacobi_from_masses(r->p, y);
  (void)t;
  if (r->n == 0) r->E0 = E;
  /* with the work W in y[8] (augmented system) E - W is conserved */
  r->max_drift = fmax(r->max_drift, fabs(E - r->E0 - (r->p->H > 0 || r->p->h > 0 ? y[8] : 0.0)));
  r->n++;
  return 0;
}

static int augmented_rhs(double t, const double y[], double f[], void *params) {
  const autobal_pendulum_params *p = (const autobal_pendulum_params *)params;
  int rc = autobal_pendulum_rhs(t, y, f, params);
  f[8] = damping_power(p, y);
  return rc;
}

static void test_jacobi(void) {
  unsigned long seed = 99;
  double worst = 0.0, worst_p = 0.0;
  int i;
  /* the library's formula equals the point-mass one up to a constant */
  for (i = 0; i < 20; i++) {
    double ya[8], yb[8];
    random_state(&seed, ya);
    random_state(&seed, yb);
    worst = fmax(worst, fabs((autobal_pendulum_jacobi_integral(&P_HEAVY, ya) -
                              autobal_pendulum_jacobi_integral(&P_HEAVY, yb)) -
                             (jacobi_from_masses(&P_HEAVY, ya) - jacobi_from_masses(&P_HEAVY, yb))));
    worst_p = fmax(worst_p, fabs(autobal_pendulum_jacobi_power(&P_HEAVY, ya) - damping_power(&P_HEAVY, ya)));
  }
  CHECK_CLOSE("library Jacobi integral = point-mass T2 - T0 + V (+ const)", worst, 0.0, 0.0, 1e-13);
  CHECK_CLOSE("library damping power = generalized forces x velocities", worst_p, 0.0, 0.0, 1e-14);

  /* undamped: E conserved */
  {
    autobal_transient *tr = make("rk8pd", 1e-12, 1.0);
    energy_rec r;
    double y[8];
    autobal_transient_stats st;
    memset(&r, 0, sizeof r);
    r.p = &P_UNDAMPED;
    autobal_pendulum_main_motion(&P_UNDAMPED, y);
    y[0] = 0.1;
    y[2] += 0.5;
    y[3] -= 0.3;
    y[5] = 0.05;
    autobal_transient_set_observer(tr, energy_observer, &r);
    CHECK_STATUS("undamped run", run_pendulum(tr, &P_UNDAMPED, 200.0, y), AUTOBAL_SUCCESS);
    autobal_transient_get_stats(tr, &st);
    printf("     undamped, tau in [0,200], rtol=atol=1e-12: |E - E0| max %.3e (E0 = %.6f), %lu steps\n",
           r.max_drift, r.E0, st.steps);
    CHECK("observer saw 201 grid points", r.n == 201);
    CHECK_CLOSE("Jacobi integral conserved (H = h = 0)", r.max_drift, 0.0, 0.0, 1e-9);
    autobal_transient_free(tr);
  }
  /* damped: E(tau) - E(0) = work of the damping forces */
  {
    autobal_transient_options o = autobal_transient_options_default();
    autobal_transient *tr;
    autobal_transient_system sys = {augmented_rhs, NULL, 9, &P_HEAVY};
    energy_rec r;
    double y[9];
    o.rtol = o.atol = 1e-12;
    o.dt_out = 1.0;
    tr = autobal_transient_alloc(9, &o, NULL);
    memset(&r, 0, sizeof r);
    r.p = &P_HEAVY;
    autobal_pendulum_main_motion(&P_HEAVY, y);
    y[0] = 0.1;
    y[2] += 0.5;
    y[3] -= 0.3;
    y[5] = 0.05;
    y[8] = 0.0;
    autobal_transient_set_observer(tr, energy_observer, &r);
    CHECK_STATUS("damped energy-balance run", autobal_transient_run(tr, &sys, 0.0, 100.0, y, NULL),
                 AUTOBAL_SUCCESS);
    printf("     damped, tau in [0,100]: work of damping %.6f, |E - E0 - W| max %.3e\n", y[8],
           r.max_drift);
    CHECK("damping did real work (|W| > 0.01)", fabs(y[8]) > 0.01);
    CHECK_CLOSE("E(tau) - E(0) = work of the damping forces", r.max_drift, 0.0, 0.0, 1e-9);
    autobal_transient_free(tr);
  }
}

/* ---- 5. stability: convergence and rates ------------------------------------------ */

typedef struct rate_rec {
  const autobal_pendulum_params *p;
  double ta, tb, na, nb;
} rate_rec;

static int rate_observer(double t, const double y[], void *user) {
  rate_rec *r = (rate_rec *)user;
  if (t == r->ta) r->na = deviation_norm(r->p, y);
  if (t == r->tb) r->nb = deviation_norm(r->p, y);
  return 0;
}

static void test_stability(void) {
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  autobal_pendulum_params *sets[2] = {&P_STABLE, &P_UNSTABLE};
  int k;
  for (k = 0; k < 2; k++) {
    autobal_pendulum_params *p = sets[k];
    double A[64], lre, lim, vr[8], vnorm = 0.0, y[8];
    autobal_pendulum_result res;
    int i, rc;
    spec_linear_matrix(p, A);
    dominant_mode(A, &lre, &lim, vr);
    rc = autobal_pendulum_analyze(ws, p, &res);
    CHECK_STATUS("autobal_pendulum_analyze", rc, AUTOBAL_SUCCESS);
    CHECK_CLOSE("max Re: own eigenvalues of (5) vs library roots of (6)", lre, res.max_real, 0.0,
                1e-9);
    printf("     R_w = %g: dominant root %.6f %+.6fi, library verdict %d\n", p->R_w, lre, lim,
           res.verdict);
    if (k == 0)
      CHECK("precondition: stable parameters (max Re < -0.05)", lre < -0.05 && res.verdict == 1);
    else
      CHECK("precondition: unstable parameters (max Re > 0.03)", lre > 0.03 && res.verdict == -1);

    /* finite perturbation: converges to (4) or not */
    {
      autobal_transient *tr = make("rk8pd", 1e-10, 0.0);
      double y0n;
      autobal_pendulum_main_motion(p, y);
      y[0] = 0.02;
      y[1] = -0.01;
      y[2] += 0.2;
      y[3] -= 0.1;
      if (k == 1)
        for (i = 0; i < 8; i++) y[i] = (i == 2 || i == 3 ? p->psi0 : 0.0) + 1e-6 * (i + 1) / 8.0;
      y0n = deviation_norm(p, y);
      CHECK_STATUS("long run", run_pendulum(tr, p, 300.0, y), AUTOBAL_SUCCESS);
      if (k == 0) {
        autobal_pendulum_motion_derived d;
        autobal_pendulum_motion_derive(p, y, &d);
        printf("     stable: deviation %.3e -> %.3e, unbalance %.3e, amplitude %.3e\n", y0n,
               deviation_norm(p, y), d.unbalance, d.amplitude);
        CHECK("stable: converged to the main motion (4) (deviation < 1e-8)",
              deviation_norm(p, y) < 1e-8);
        CHECK("stable: residual unbalance and amplitude < 1e-8",
              d.unbalance < 1e-8 && d.amplitude < 1e-8);
      } else {
        printf("     unstable: deviation %.3e -> %.3e\n", y0n, deviation_norm(p, y));
        CHECK("unstable: the deviation grew by more than 1e3", deviation_norm(p, y) > 1e3 * y0n);
      }
      autobal_transient_free(tr);
    }

    /* rate: start on the dominant mode, compare norms a whole number of
     * periods apart (for a single complex mode the ratio is exactly
     * exp(Re lambda * T)) */
    {
      const double period = lim > 1e-9 ? 2 * M_PI / lim : 1.0;
      const int nper = k == 0 ? (int)ceil(30.0 / period) : (int)ceil(50.0 / period);
      const double ta = k == 0 ? 2 * period : 1 * period;
      rate_rec r;
      autobal_transient_options o = autobal_transient_options_default();
      autobal_transient *tr;
      autobal_transient_system sys = {autobal_pendulum_rhs, autobal_pendulum_jac, 8, p};
      double rate;
      o.rtol = o.atol = 1e-13;
      o.dt_out = period;
      tr = autobal_transient_alloc(8, &o, NULL);
      for (i = 0; i < 8; i++) vnorm += vr[i] * vr[i];
      vnorm = sqrt(vnorm);
      autobal_pendulum_main_motion(p, y);
      for (i = 0; i < 8; i++) y[i] += 1e-6 * vr[i] / vnorm;
      r.p = p;
      r.ta = ta;
      r.tb = ta + nper * period;
      r.na = r.nb = NAN;
      /* output exactly at whole periods: ta and tb are k * period */
      r.ta = 0.0 + (k == 0 ? 2 : 1) * period;
      r.tb = 0.0 + ((k == 0 ? 2 : 1) + nper) * period;
      autobal_transient_set_observer(tr, rate_observer, &r);
      autobal_transient_run(tr, &sys, 0.0, r.tb, y, NULL);
      rate = log(r.nb / r.na) / (r.tb - r.ta);
      printf("     fitted rate over %d periods: %.8f, max Re of the roots %.8f\n", nper, rate, lre);
      CHECK_CLOSE("fitted decay/growth rate = max Re of the characteristic roots", rate, lre,
                  1e-3, 1e-5);
      autobal_transient_free(tr);
    }
  }
  autobal_pendulum_workspace_free(ws);
}

/* ---- 6. steppers agree -------------------------------------------------------------- */

static void test_steppers_agree(void) {
  static const char *names[3] = {"rk8pd", "rkck", "msbdf"};
  double yf[3][8];
  unsigned long steps[3];
  int k, i;
  for (k = 0; k < 3; k++) {
    autobal_transient *tr = make(names[k], 1e-12, 0.0);
    autobal_transient_stats st;
    double y[8];
    autobal_pendulum_main_motion(&P_HEAVY, y);
    y[0] = 0.05;
    y[2] += 0.4;
    y[3] -= 0.6;
    y[7] = 0.1;
    CHECK_STATUS(names[k], run_pendulum(tr, &P_HEAVY, 50.0, y), AUTOBAL_SUCCESS);
    autobal_transient_get_stats(tr, &st);
    steps[k] = st.steps;
    memcpy(yf[k], y, sizeof y);
    autobal_transient_free(tr);
  }
  for (k = 1; k < 3; k++) {
    double d = 0.0;
    char what[128];
    for (i = 0; i < 8; i++) d = fmax(d, fabs(yf[k][i] - yf[0][i]));
    printf("     tau = 50, tol 1e-12: %s (%lu steps) vs rk8pd (%lu steps): max diff %.3e\n",
           names[k], steps[k], steps[0], d);
    snprintf(what, sizeof what, "%s agrees with rk8pd at tau = 50 (tol 1e-12)", names[k]);
    CHECK_CLOSE(what, d, 0.0, 0.0, 1e-8);
  }
}

/* ---- 7. derived quantities and time to balance -------------------------------------- */

typedef struct tb_rec {
  const autobal_pendulum_params *p;
  double t_start, worst_after;
} tb_rec;

static int tb_observer(double t, const double y[], void *user) {
  tb_rec *r = (tb_rec *)user;
  if (t >= r->t_start)
    r->worst_after = fmax(r->worst_after, autobal_pendulum_residual_unbalance(r->p, y, NULL, NULL));
  return 0;
}

static void test_derived(void) {
  autobal_pendulum_params *p = &P_STABLE;
  double y[8], du, dv;
  autobal_pendulum_motion_derived d;
  autobal_pendulum_main_motion(p, y);
  CHECK_CLOSE("unbalance at (4) = 0", autobal_pendulum_residual_unbalance(p, y, NULL, NULL), 0.0,
              0.0, 1e-16);
  y[2] = y[3] = M_PI - p->psi0;
  CHECK_CLOSE("unbalance at psi = phi = pi - psi0 = 0",
              autobal_pendulum_residual_unbalance(p, y, NULL, NULL), 0.0, 0.0, 1e-15);
  y[2] = y[3] = 0.0;
  CHECK_CLOSE("pendulums cancelling each other: unbalance = sin psi0 (rotor's own)",
              autobal_pendulum_residual_unbalance(p, y, &du, &dv), sin(p->psi0), 1e-15, 0.0);
  CHECK("... along +U", dv == 0.0 && du > 0.0);
  /* pendulums both at +U side (psi = -pi/2, phi = pi/2 put both masses at +U... check: pendulum 1
   * at (-sin psi, cos psi) = (1, 0) for psi = -pi/2, pendulum 2 at (-sin phi, -cos phi) = (-1, 0)
   * for phi = pi/2 */
  y[2] = -M_PI / 2;
  y[3] = -M_PI / 2; /* pendulum 2 at (1, 0) too */
  CHECK_CLOSE("both pendulums along +U add to the unbalance: sin psi0 + 1",
              autobal_pendulum_residual_unbalance(p, y, &du, &dv), sin(p->psi0) + 1.0, 1e-15, 0.0);
  /* the forcing of (1) is 2 R_m R_w^2 d: at rest with xi = eta = 0 and
   * psi = phi (so the pendulum coupling matrix is simple) compare with rhs */
  {
    double f[8];
    int j;
    for (j = 0; j < 8; j++) y[j] = 0.0;
    y[2] = 0.3;
    y[3] = -1.1;
    autobal_pendulum_residual_unbalance(p, y, &du, &dv);
    autobal_pendulum_rhs(0.0, y, f, p);
    /* shaft equations of (1) at rest: A - R_m (psi'' c1 + phi'' c2) = 2 R_m R_w^2 d_u, etc. */
    CHECK_CLOSE("forcing of (1a) = 2 R_m R_w^2 d_u",
                f[4] - p->R_m * (f[6] * cos(y[2]) + f[7] * cos(y[3])),
                2 * p->R_m * p->R_w * p->R_w * du, 1e-14, 1e-15);
    CHECK_CLOSE("forcing of (1b) = 2 R_m R_w^2 d_v",
                f[5] - p->R_m * (f[6] * sin(y[2]) - f[7] * sin(y[3])),
                2 * p->R_m * p->R_w * p->R_w * dv, 1e-14, 1e-15);
  }
  CHECK_CLOSE("wrap: 2 pi + 0.1 -> 0.1", autobal_pendulum_wrap_angle(2 * M_PI + 0.1), 0.1, 0.0,
              1e-15);
  CHECK("wrap: -pi -> +pi (interval (-pi, pi])", autobal_pendulum_wrap_angle(-M_PI) == M_PI);
  CHECK_CLOSE("wrap: -7 pi/2 -> pi/2", autobal_pendulum_wrap_angle(-3.5 * M_PI), 0.5 * M_PI, 0.0,
              1e-15);
  y[0] = 3.0;
  y[1] = -4.0;
  y[2] = p->psi0 + 2 * M_PI - 0.25;
  y[3] = p->psi0 - 4 * M_PI + 0.125;
  autobal_pendulum_motion_derive(p, y, &d);
  CHECK_CLOSE("amplitude = hypot(3, -4) = 5", d.amplitude, 5.0, 1e-15, 0.0);
  CHECK_CLOSE("alpha wrapped", d.alpha, -0.25, 0.0, 1e-14);
  CHECK_CLOSE("beta wrapped", d.beta, 0.125, 0.0, 1e-14);
  CHECK("derived jacobi = jacobi_integral", d.jacobi == autobal_pendulum_jacobi_integral(p, y));
  /* derive computes the shared sines once: every field must still be exactly what the separate
   * definitions give (the archive's columns are documented as these functions), on a few states */
  {
    int trial;
    for (trial = 0; trial < 5; trial++) {
      double yy[8], u, v, unb;
      int i2;
      for (i2 = 0; i2 < 8; i2++) yy[i2] = sin(1.7 * (trial + 1) + 0.9 * i2) * (1.0 + 3.0 * trial);
      autobal_pendulum_motion_derive(p, yy, &d);
      unb = autobal_pendulum_residual_unbalance(p, yy, &u, &v);
      CHECK("derive: all fields equal the separate functions bit for bit",
            d.amplitude == autobal_pendulum_shaft_amplitude(yy) && d.unbalance == unb &&
                d.unbalance_u == u && d.unbalance_v == v &&
                d.alpha == autobal_pendulum_wrap_angle(yy[2] - p->psi0) &&
                d.beta == autobal_pendulum_wrap_angle(yy[3] - p->psi0) &&
                d.jacobi == autobal_pendulum_jacobi_integral(p, yy));
    }
  }

  /* wrap_angle skips remainder() for |a| <= pi and derive_m takes sin(psi0) from the motion: both
   * must give exactly the bits of the definitions (remainder(a, 2 pi), folded to (-pi, pi];
   * autobal_pendulum_motion_derive), compared as bytes (so -0 vs +0 and NaN count too) */
  {
    const double pim = nextafter(M_PI, 0.0), pip = nextafter(M_PI, 4.0);
    const double edge[] = {0.0, -0.0, M_PI, -M_PI, pim, -pim, pip, -pip, 3.0, -3.0, 1e-300, -1e-300,
                           4.0, -4.0, 2 * M_PI, -2 * M_PI, 3 * M_PI, -3 * M_PI, 1e6, -1e6, 1e300, INFINITY,
                           -INFINITY, NAN};
    int i2, bad_wrap = 0, bad_derive = 0;
    autobal_pendulum_motion m;
    autobal_error e;
    for (i2 = 0; i2 < (int)(sizeof edge / sizeof edge[0]) + 2000; i2++) {
      const double a = i2 < (int)(sizeof edge / sizeof edge[0]) ? edge[i2] : 9.0 * sin(0.37 * i2 + 0.1) * (i2 % 3 ? 1.0 : 0.4);
      double want = remainder(a, 2.0 * M_PI), got = autobal_pendulum_wrap_angle(a);
      if (want <= -M_PI) want += 2.0 * M_PI;
      if (memcmp(&want, &got, sizeof want) != 0 && !(isnan(want) && isnan(got))) {
        if (bad_wrap++ < 3) printf("     wrap(%.17g) = %.17g, definition %.17g\n", a, got, want);
      }
    }
    CHECK("wrap: equals remainder(a, 2 pi) folded to (-pi, pi], bit for bit (edges +-0, +-pi and neighbours, 2000 angles)",
          bad_wrap == 0);
    CHECK_STATUS("derive_m: motion", autobal_pendulum_motion_init(&m, p, &e), AUTOBAL_SUCCESS);
    for (i2 = 0; i2 < 200; i2++) {
      autobal_pendulum_motion_derived d1, d2;
      double yy[8];
      int j2;
      for (j2 = 0; j2 < 8; j2++) yy[j2] = sin(0.77 * (i2 + 1) + 1.3 * j2) * (0.5 + 0.05 * i2);
      if (i2 == 0) yy[2] = yy[3] = p->psi0; /* alpha = beta = 0 exactly */
      autobal_pendulum_motion_derive(p, yy, &d1);
      autobal_pendulum_motion_derive_m(&m, yy, &d2);
      if (memcmp(&d1, &d2, sizeof d1) != 0) bad_derive++;
    }
    CHECK("derive_m: the same bytes as derive on 200 states", bad_derive == 0);
  }

  /* time to balance: unbalance below 1e-4 for 20 time units */
  {
    autobal_transient *tr = make("rk8pd", 1e-10, 0.5);
    autobal_transient_system sys = {autobal_pendulum_rhs, autobal_pendulum_jac, 8, p};
    autobal_transient_event_hit hit;
    unsigned long count;
    tb_rec r;
    double t_end, yb[8];
    int rc;
    autobal_pendulum_main_motion(p, y);
    y[2] += 0.2;
    y[3] -= 0.1;
    memcpy(yb, y, sizeof y);
    autobal_transient_add_dwell_event(tr, autobal_pendulum_unbalance_scalar, (void *)p, 1e-4, 20.0, 1);
    rc = autobal_transient_run(tr, &sys, 0.0, 1000.0, y, &t_end);
    CHECK_STATUS("time to balance: terminal dwell event", rc, AUTOBAL_EVENT);
    CHECK("time to balance: fired once", autobal_transient_event_result(tr, 0, &count, &hit) == 1 && count == 1);
    printf("     time to balance (|d| < 1e-4 for 20): t_start = %.6f, stop at %.6f\n", hit.t_start,
           t_end);
    CHECK_CLOSE("stopped at t_start + 20", t_end, hit.t_start + 20.0, 0.0, 1e-9);
    CHECK("final unbalance below 1e-4", autobal_pendulum_residual_unbalance(p, y, NULL, NULL) < 1e-4);
    /* independent re-run without events: the unbalance at t_start is the threshold,
     * and it stays below afterwards (sampled on the output grid) */
    autobal_transient_clear_events(tr);
    memset(&r, 0, sizeof r);
    r.p = p;
    r.t_start = hit.t_start + 1e-9;
    autobal_transient_set_observer(tr, tb_observer, &r);
    memcpy(y, yb, sizeof y);
    run_pendulum(tr, p, hit.t_start, y);
    CHECK_CLOSE("unbalance at t_start = threshold 1e-4",
                autobal_pendulum_residual_unbalance(p, y, NULL, NULL), 1e-4, 1e-6, 0.0);
    memcpy(y, yb, sizeof y);
    run_pendulum(tr, p, hit.t_start + 20.0, y);
    CHECK("unbalance stays below 1e-4 after t_start (grid 0.5)", r.worst_after < 1e-4);
    autobal_transient_free(tr);
  }
}

/* ---- 8. error paths --------------------------------------------------------------------- */

static void test_errors(void) {
  double y[8] = {0}, f[8], J[64], dfdt[8];
  autobal_pendulum_params bad = {2.0, 0.5, 0.1, 0.1, 0.3};
  CHECK("rhs with NULL params fails", autobal_pendulum_rhs(0.0, y, f, NULL) == AUTOBAL_EINVAL);
  CHECK("jac with NULL params fails", autobal_pendulum_jac(0.0, y, J, dfdt, NULL) == AUTOBAL_EINVAL);
  /* R_m = 1/2, psi = phi = 0: the acceleration system is singular */
  CHECK("rhs with R_m = 1/2 at psi = phi = 0: ENUMERIC",
        autobal_pendulum_rhs(0.0, y, f, &bad) == AUTOBAL_ENUMERIC);
  CHECK("jac with R_m = 1/2 at psi = phi = 0: ENUMERIC",
        autobal_pendulum_jac(0.0, y, J, dfdt, &bad) == AUTOBAL_ENUMERIC);
  {
    autobal_transient *tr = make("rk8pd", 1e-10, 0.0);
    autobal_transient_system sys = {autobal_pendulum_rhs, NULL, 8, &bad};
    CHECK_STATUS("transient with a singular system: ERHS", autobal_transient_run(tr, &sys, 0.0, 1.0, y, NULL),
                 AUTOBAL_ERHS);
    CHECK_MSG("message carries the model's status", autobal_transient_errmsg(tr), "returned -3");
    autobal_transient_free(tr);
  }
}

/* ---- 9. prepared parameters ------------------------------------------------------------- */

static void test_prepared(void) {
  autobal_pendulum_motion m;
  autobal_pendulum_params bad = P_HEAVY;
  autobal_error err;
  unsigned long seed = 4242;
  int i, j, same = 1;
  CHECK_STATUS("motion_init", autobal_pendulum_motion_init(&m, &P_HEAVY, &err), AUTOBAL_SUCCESS);
  CHECK("motion_init stores sin(psi0)", m.sin_psi0 == sin(P_HEAVY.psi0));
  for (i = 0; i < 20; i++) {
    double y[8], f1[8], f2[8], J1[64], J2[64], d1[8], d2[8];
    random_state(&seed, y);
    autobal_pendulum_rhs(0.0, y, f1, &P_HEAVY);
    autobal_pendulum_motion_rhs(0.0, y, f2, &m);
    autobal_pendulum_jac(0.0, y, J1, d1, &P_HEAVY);
    autobal_pendulum_motion_jac(0.0, y, J2, d2, &m);
    for (j = 0; j < 8; j++) same &= f1[j] == f2[j];
    for (j = 0; j < 64; j++) same &= J1[j] == J2[j];
  }
  CHECK("prepared rhs and Jacobian are bitwise equal to the plain ones", same);
  bad.R_m = 0.6;
  CHECK_STATUS("motion_init rejects R_m = 0.6", autobal_pendulum_motion_init(&m, &bad, &err),
               AUTOBAL_EINVAL);
  CHECK_MSG("motion_init message names R_m", err.message, "R_m");
  CHECK("motion_rhs with NULL fails", autobal_pendulum_motion_rhs(0.0, NULL, NULL, &m) != 0);
}

int main(void) {
  gsl_set_error_handler_off();
  test_equations();
  test_jacobian();
  test_linearization();
  test_jacobi();
  test_stability();
  test_steppers_agree();
  test_derived();
  test_errors();
  test_prepared();
  return check_summary();
}
