/* test_rotor_slow.c: long transients of the rotor model (label "slow").
 *
 *  - a speed sweep of the default: the linear stability of the balanced motion
 *    (Floquet multipliers of the full model over one revolution, monodromy matrix
 *    by central finite differences of the rotating-frame right-hand side) decides
 *    whether a 60 s transient from the default start ends balanced; where stable,
 *    the decay rate of the residual unbalance matches the largest Floquet exponent;
 *  - subcritical speeds: the balls end together at an angle where the steady
 *    harmonic response to the total unbalance (complex 4x4 solve) puts the
 *    balancer plane's displacement along them (the balls' equilibrium condition);
 *  - families of balanced configurations (3, 5 identical balls; 4 different balls),
 *    the FULL inertia variant, and fixed vs rotating frame over 60 s.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_complex.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_sort.h>

#include "autobal.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define MAXDIM 32

static double wrap(double a) { return atan2(sin(a), cos(a)); }

static int integrate(int (*f)(double, const double *, double *, void *), autobal_rotor *r,
                     double t0, double t1, double *y, double rtol, double atol) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient *tr;
  int st;
  opt.rtol = rtol;
  opt.atol = atol;
  opt.h_init = 1e-6;
  opt.max_steps = 100000000ul;
  sys.rhs = f;
  sys.jac = NULL;
  sys.dim = autobal_rotor_dim(r);
  sys.params = r;
  tr = autobal_transient_alloc(sys.dim, &opt, NULL);
  if (tr == NULL) return -1;
  st = autobal_transient_run(tr, &sys, t0, t1, y, NULL);
  autobal_transient_free(tr);
  return st;
}

/* |Floquet multipliers| (sorted, descending) of the motion through the rotating-frame
 * state yb, which must be periodic with period 2 pi / omega (a balanced motion): the
 * monodromy matrix over one revolution by central finite differences */
static int floquet_abs(autobal_rotor *r, const double *yb, double *mu) {
  const size_t n = autobal_rotor_dim(r);
  const double T = 2.0 * M_PI / fabs(autobal_rotor_omega(r));
  gsl_matrix *M = gsl_matrix_alloc(n, n);
  gsl_vector_complex *ev = gsl_vector_complex_alloc(n);
  gsl_eigen_nonsymm_workspace *w = gsl_eigen_nonsymm_alloc(n);
  size_t i, k;
  int st;
  for (k = 0; k < n; k++) {
    const double eps = k < 4 ? 1e-9 : (k < 8 ? 1e-7 : 1e-6);
    double yp[MAXDIM], ym[MAXDIM];
    memcpy(yp, yb, n * sizeof(double));
    memcpy(ym, yb, n * sizeof(double));
    yp[k] += eps;
    ym[k] -= eps;
    integrate(autobal_rotor_rhs_rotating, r, 0.0, T, yp, 1e-12, 1e-15);
    integrate(autobal_rotor_rhs_rotating, r, 0.0, T, ym, 1e-12, 1e-15);
    for (i = 0; i < n; i++) gsl_matrix_set(M, i, k, (yp[i] - ym[i]) / (2.0 * eps));
  }
  st = gsl_eigen_nonsymm(M, ev, w);
  for (i = 0; i < n; i++) mu[i] = gsl_complex_abs(gsl_vector_complex_get(ev, i));
  gsl_sort(mu, 1, n);
  for (i = 0; i < n / 2; i++) { /* descending */
    const double t = mu[i];
    mu[i] = mu[n - 1 - i];
    mu[n - 1 - i] = t;
  }
  gsl_matrix_free(M);
  gsl_vector_complex_free(ev);
  gsl_eigen_nonsymm_free(w);
  return st;
}

/* largest |Floquet multiplier| of the balanced motion of plane 0 given by
 * autobal_rotor_balanced_angles (rotor at rest) */
static double floquet_max(autobal_rotor *r) {
  const size_t N = autobal_rotor_n_balls_total(r);
  double yb[MAXDIM] = {0}, psi[MAXDIM], mu[MAXDIM];
  size_t k;
  if (autobal_rotor_balanced_angles(r, 0, psi, N, NULL) != AUTOBAL_SUCCESS) return NAN;
  for (k = 0; k < N; k++) yb[8 + k] = psi[k];
  if (floquet_abs(r, yb, mu) != 0) return NAN;
  return mu[0];
}

static void test_speed_sweep(void) {
  const double oms[8] = {170, 230, 300, 400, 500, 700, 1000, 1500};
  int c;
  printf("-- speed sweep: Floquet verdict of the balanced motion vs the 60 s transient\n");
  for (c = 0; c < 8; c++) {
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_rotor *r;
    double mu, y[12], mon60, rate_fit = NAN, rate_floq, t = 0.0;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int k, nfit = 0;
    p.omega = oms[c];
    r = autobal_rotor_alloc(&p, NULL);
    if (r == NULL) continue;
    mu = floquet_max(r);
    autobal_rotor_initial_state(r, AUTOBAL_ROTOR_ROTATING, 0.0, y, 12);
    /* 60 s; log |s| sampled every 0.05 s while 1e-9 < |s|/m0r0 < 1e-3 (the slowest mode
     * dominates, roundoff does not): least-squares slope = decay rate */
    for (k = 1; k <= 1200; k++) {
      const double t1 = 0.05 * k;
      double m;
      integrate(autobal_rotor_rhs_rotating, r, t, t1, y, 1e-10, 1e-12);
      t = t1;
      m = autobal_rotor_balance_monitor(r, AUTOBAL_ROTOR_ROTATING, t, y);
      if (m < 1e-3 && m > 1e-9) {
        sx += t;
        sy += log(m);
        sxx += t * t;
        sxy += t * log(m);
        nfit++;
      }
    }
    mon60 = autobal_rotor_balance_monitor(r, AUTOBAL_ROTOR_ROTATING, 60.0, y);
    if (nfit > 20) rate_fit = (nfit * sxy - sx * sy) / (nfit * sxx - sx * sx);
    rate_floq = log(mu) * fabs(p.omega) / (2.0 * M_PI);
    printf("     omega = %6.0f rad/s: max |mu| = %.8f (exponent %+.4f 1/s), |s|/m0r0 at 60 s = %.3g\n",
           p.omega, mu, rate_floq, mon60);
    if (mu < 1.0) {
      CHECK_CLOSE("   linearly stable -> balanced at 60 s", mon60, 0.0, 0, 1e-8);
      CHECK_CLOSE("   decay rate of |s| fitted to the transient = largest Floquet exponent (1/s)", rate_fit, rate_floq, 0.1, 0);
    } else {
      CHECK("   linearly unstable -> not balanced at 60 s (|s|/m0r0 > 0.1)", mon60 > 0.1);
    }
    autobal_rotor_free(r);
  }
}

/* steady harmonic response of the default-type rotor to the unbalance S (complex, rotor
 * axes) in plane d; returns the angle of D's displacement in the rotor axes */
static double displacement_angle(const autobal_rotor *r, double Sre, double Sim, double d, double *amp) {
  const autobal_rotor_lumped *L = autobal_rotor_get_lumped(r);
  const double w = autobal_rotor_omega(r);
  double K[4][4] = {{L->c_x, 0, 0, -L->c_xbeta}, {0, L->c_y, L->c_yalpha, 0}, {0, L->c_yalpha, L->c_alpha, 0},
                    {-L->c_xbeta, 0, 0, L->c_beta}};
  double H[4][4] = {{L->h_x, 0, 0, -L->h_xbeta}, {0, L->h_y, L->h_yalpha, 0}, {0, L->h_yalpha, L->h_alpha, 0},
                    {-L->h_xbeta, 0, 0, L->h_beta}};
  const double Dm[4] = {L->M, L->M, L->A, L->A};
  const double eu[4] = {1, 0, 0, d}, ev[4] = {0, 1, -d, 0};
  gsl_matrix_complex *Z = gsl_matrix_complex_alloc(4, 4);
  gsl_vector_complex *F = gsl_vector_complex_alloc(4), *X = gsl_vector_complex_alloc(4);
  gsl_permutation *perm = gsl_permutation_alloc(4);
  double Q[8], ang;
  size_t i, k;
  int sgn;
  H[2][3] += L->C * w;
  H[3][2] -= L->C * w;
  for (i = 0; i < 4; i++) {
    for (k = 0; k < 4; k++)
      gsl_matrix_complex_set(Z, i, k, gsl_complex_rect(K[i][k] - (i == k ? w * w * Dm[i] : 0.0), w * H[i][k]));
    gsl_vector_complex_set(F, i, gsl_complex_mul(gsl_complex_rect(w * w * Sre, w * w * Sim), gsl_complex_rect(eu[i], -ev[i])));
  }
  gsl_linalg_complex_LU_decomp(Z, perm, &sgn);
  gsl_linalg_complex_LU_solve(Z, perm, F, X);
  for (i = 0; i < 4; i++) {
    Q[2 * i] = GSL_REAL(gsl_vector_complex_get(X, i));
    Q[2 * i + 1] = GSL_IMAG(gsl_vector_complex_get(X, i));
  }
  ang = atan2(Q[2] - d * Q[4], Q[0] + d * Q[6]);
  if (amp) *amp = hypot(Q[0], Q[1]);
  gsl_matrix_complex_free(Z);
  gsl_vector_complex_free(F);
  gsl_vector_complex_free(X);
  gsl_permutation_free(perm);
  return ang;
}

static double eq_res(const autobal_rotor *r, double psi) {
  /* default: s0 = 0.002 at psi0 = 0, two balls with m r = 0.005 each, d = 0.1 */
  return wrap(displacement_angle(r, 0.002 + 0.01 * cos(psi), 0.01 * sin(psi), 0.1, NULL) - psi);
}

/* roots of the balls' equilibrium condition on the whole circle (scan + bisection);
 * returns the number found and the distance of the nearest one to psi */
static int equilibria(const autobal_rotor *r, double psi, double *nearest) {
  int i, count = 0;
  *nearest = INFINITY;
  for (i = 0; i < 720; i++) {
    double a = -M_PI + 2.0 * M_PI * i / 720.0, b = a + 2.0 * M_PI / 720.0;
    double fa = eq_res(r, a), fb = eq_res(r, b);
    int it;
    if (!(fa * fb <= 0.0) || fabs(fa - fb) > 1.0) continue; /* skip the +-pi jumps of wrap() */
    for (it = 0; it < 80; it++) {
      const double m = 0.5 * (a + b), fm = eq_res(r, m);
      if (fm * fa > 0.0) {
        a = m;
        fa = fm;
      } else {
        b = m;
      }
    }
    count++;
    *nearest = fmin(*nearest, fabs(wrap(0.5 * (a + b) - psi)));
  }
  return count;
}

static void test_subcritical_sweep(void) {
  const double oms[3] = {60, 100, 140};
  int c;
  printf("-- subcritical speeds: balls together at an equilibrium of the steady response\n");
  for (c = 0; c < 3; c++) {
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_rotor *r;
    double y[12], psi, best, amp;
    int nroots;
    p.omega = oms[c];
    r = autobal_rotor_alloc(&p, NULL);
    if (r == NULL) continue;
    autobal_rotor_initial_state(r, AUTOBAL_ROTOR_ROTATING, 0.0, y, 12);
    integrate(autobal_rotor_rhs_rotating, r, 0.0, 60.0, y, 1e-10, 1e-12);
    psi = wrap(y[8]);
    nroots = equilibria(r, psi, &best);
    printf("     omega = %g rad/s: balls at %.6f and %.6f rad, rates %.3g, %.3g rad/s; %d equilibria\n",
           p.omega, psi, wrap(y[9]), y[10], y[11], nroots);
    CHECK_CLOSE("   balls together (rad)", wrap(y[8] - y[9]), 0.0, 0, 1e-6);
    CHECK("   residual unbalance larger than the unbalance alone",
          autobal_rotor_balance_monitor(r, AUTOBAL_ROTOR_ROTATING, 60.0, y) > 1.0);
    if (nroots > 0) {
      CHECK_CLOSE("   ball angle = nearest equilibrium of the steady response (rad)", best, 0.0, 0, 1e-6);
      displacement_angle(r, 0.002 + 0.01 * cos(psi), 0.01 * sin(psi), 0.1, &amp);
      CHECK_CLOSE("   centre-of-mass amplitude = |Q_x| of the steady response (m)", hypot(y[0], y[1]), amp, 1e-6, 0);
    } else {
      /* no synchronous equilibrium with the balls together exists: they must keep moving
       * relative to the rotor (they lag it, circulating slower than the shaft) */
      CHECK("   no equilibrium: the balls keep moving relative to the rotor (|psi'| > 1 rad/s)",
            fabs(y[10]) > 1.0 && fabs(y[11]) > 1.0);
    }
    autobal_rotor_free(r);
  }
}

static void test_families_and_variants(void) {
  static const double m3[3] = {0.03, 0.03, 0.03}, r3[3] = {0.1, 0.1, 0.1}, h3[3] = {0.06, 0.06, 0.06};
  static const double p3[3] = {0.3, 1.6, 2.9};
  static const double m5[5] = {0.02, 0.02, 0.02, 0.02, 0.02}, r5[5] = {0.1, 0.1, 0.1, 0.1, 0.1};
  static const double h5[5] = {0.04, 0.04, 0.04, 0.04, 0.04}, p5[5] = {0.3, 1.6, 2.9, 4.2, 5.5};
  static const double m4[4] = {0.03, 0.025, 0.02, 0.015}, r4[4] = {0.1, 0.1, 0.1, 0.1};
  static const double h4[4] = {0.06, 0.05, 0.04, 0.03}, p4[4] = {0.5, 1.5, 2.5, 3.5};
  int c;
  printf("-- families of balanced configurations (h_i/m_i = 2 1/s), FULL inertia (omega = 500)\n");
  for (c = 0; c < 4; c++) {
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_rotor *r;
    double y[MAXDIM], mon, mu[MAXDIM];
    const char *label[4] = {"3 identical balls", "5 identical balls", "4 different balls", "FULL inertia, default balls"};
    size_t n = 2, k, dim;
    if (c == 0) {
      n = 3;
      p.plane[0].ball_mass = m3;
      p.plane[0].ball_radius = r3;
      p.plane[0].ball_damping = h3;
      p.plane[0].ball_psi = p3;
    } else if (c == 1) {
      n = 5;
      p.plane[0].ball_mass = m5;
      p.plane[0].ball_radius = r5;
      p.plane[0].ball_damping = h5;
      p.plane[0].ball_psi = p5;
    } else if (c == 2) {
      n = 4;
      p.plane[0].ball_mass = m4;
      p.plane[0].ball_radius = r4;
      p.plane[0].ball_damping = h4;
      p.plane[0].ball_psi = p4;
    } else {
      p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
    }
    p.plane[0].n_balls = n;
    if (c < 3) p.plane[0].ball_rate = NULL;
    r = autobal_rotor_alloc(&p, NULL);
    if (r == NULL) continue;
    dim = autobal_rotor_dim(r);
    autobal_rotor_initial_state(r, AUTOBAL_ROTOR_ROTATING, 0.0, y, dim);
    integrate(autobal_rotor_rhs_rotating, r, 0.0, 60.0, y, 1e-10, 1e-12);
    mon = autobal_rotor_balance_monitor(r, AUTOBAL_ROTOR_ROTATING, 60.0, y);
    printf("     %s:\n", label[c]);
    CHECK_CLOSE("   balanced at 60 s: |s| / m0 r0", mon, 0.0, 0, 1e-6);
    CHECK_CLOSE("   rotor at rest (m)", hypot(y[0], y[1]), 0.0, 0, 1e-10);
    if (c == 3) {
      const double pb = M_PI - acos(0.2);
      CHECK_CLOSE("   FULL inertia: same balanced angles (3.14)", fabs(wrap(y[8])), pb, 0, 1e-6);
    }
    /* the member reached: exactly balanced copy of it, rotor at rest, balls at rest */
    for (k = 0; k < 8; k++) y[k] = 0.0;
    for (k = 0; k < n; k++) y[8 + n + k] = 0.0;
    if (floquet_abs(r, y, mu) == 0) {
      const double kappa_mu = exp(-2.0 * 2.0 * M_PI / 500.0); /* e^{-(h/m) T}, h/m = 2 1/s */
      size_t n1 = 0, nk = 0;
      for (k = 0; k < dim; k++) {
        if (fabs(mu[k] - 1.0) < 1e-6) n1++;
        if (fabs(mu[k] - kappa_mu) < 1e-6) nk++;
      }
      printf("     largest |mu| at the member reached: %.9f %.9f %.9f\n", mu[0], mu[1], mu[2]);
      CHECK_CLOSE("   member reached is not linearly unstable: max |mu| <= 1", fmax(mu[0] - 1.0, 0.0), 0.0, 0, 1e-6);
      CHECK("   n - 2 neutral multipliers (|mu| = 1) of the family", n1 == n - 2);
      CHECK("   at least n - 2 multipliers e^{-(h/m) 2 pi / omega}", nk >= n - 2);
    } else {
      CHECK("   Floquet multipliers", 0);
    }
    autobal_rotor_free(r);
  }
  {
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_rotor *r = autobal_rotor_alloc(&p, NULL);
    double yf[12], yr[12], yc[12], worst = 0.0;
    int k;
    if (r == NULL) return;
    autobal_rotor_initial_state(r, AUTOBAL_ROTOR_FIXED, 0.0, yf, 12);
    autobal_rotor_initial_state(r, AUTOBAL_ROTOR_ROTATING, 0.0, yr, 12);
    integrate(autobal_rotor_rhs, r, 0.0, 60.0, yf, 1e-11, 1e-13);
    integrate(autobal_rotor_rhs_rotating, r, 0.0, 60.0, yr, 1e-11, 1e-13);
    autobal_rotor_convert_state(r, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, 60.0, yf, yc, 12);
    for (k = 8; k < 10; k++) worst = fmax(worst, fabs(wrap(yc[k] - yr[k])));
    CHECK_CLOSE("fixed vs rotating frame after 60 s: ball angles (rad, mod 2 pi)", worst, 0.0, 0, 1e-6);
    autobal_rotor_free(r);
  }
}

int main(void) {
  gsl_set_error_handler_off();
  test_speed_sweep();
  test_subcritical_sweep();
  test_families_and_variants();
  return check_summary();
}
