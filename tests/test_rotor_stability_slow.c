/* test_rotor_stability_slow.c (label slow): long checks of the rotor stability analysis.
 *  - nonlinear confirmation: for speeds on either side of every critical speed of the
 *    default example, a transient of the full nonlinear model (autobal_rotor_rhs_rotating)
 *    started on the dominant eigenvector of the linearization decays or grows at the rate
 *    the largest real part predicts;
 *  - Routh-Hurwitz vs roots vs closed-matrix eigenvalues on a fine speed sweep;
 *  - anisotropic supports: Floquet critical speeds tend to the isotropic ones as the
 *    anisotropy vanishes;
 *  - three identical balls: every member of the family is unstable at 500 rad/s and a
 *    nonlinear transient does not settle on a balanced configuration. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>

#include "autobal.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct obs_ctx {
  autobal_rotor *r;
  double *t, *s;
  size_t n, cap;
} obs_ctx;

static int obs(double t, const double y[], void *user) {
  obs_ctx *o = (obs_ctx *)user;
  double s4[4];
  autobal_rotor_plane_unbalance(o->r, 0, AUTOBAL_ROTOR_ROTATING, t, y, s4);
  if (o->n < o->cap) {
    o->t[o->n] = t;
    o->s[o->n] = hypot(s4[2], s4[3]);
    o->n++;
  }
  return 0;
}

/* Why this measures Re(lambda): with u(t) = T_r(t) y(t) (the rotor coordinates rotated
 * back by w t, identity at t = 0) the linearized motion is u(t) = exp(B t) u(0), B the
 * constant rotating-coordinate matrix (autobal_rotor_stab_linearization(.., rotating=1)).
 * Starting on Re(v), v an eigenvector of lambda = r + i nu, the residual unbalance
 * sigma = s_xi + i s_eta (a linear function of the ball angles, frame independent) is
 * a e^{lambda t} + b e^{conj(lambda) t}, so |sigma| e^{-r t} is periodic with period
 * pi / nu: sampling at t = k pi / nu removes the oscillation exactly and log|sigma| is
 * then linear in t with slope r.  Deviations: nonlinear terms of relative size
 * O(amplitude) ~ 1e-5 .. 1e-3 rad, integration error 1e-11. */
static double measure_rate(const autobal_rotor_params *p, double t_end, double *pred) {
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(p, NULL, NULL);
  autobal_rotor *r = autobal_rotor_alloc(p, NULL);
  const size_t N = autobal_rotor_stab_n_balls(s), ns = 8 + 2 * N;
  gsl_matrix *A = gsl_matrix_alloc(ns, ns);
  gsl_vector_complex *ev = gsl_vector_complex_alloc(ns);
  gsl_matrix_complex *evec = gsl_matrix_complex_alloc(ns, ns);
  gsl_eigen_nonsymmv_workspace *w = gsl_eigen_nonsymmv_alloc(ns);
  double *a = malloc(ns * ns * sizeof *a), *y = calloc(ns, sizeof *y), *psi = malloc(N * sizeof *psi);
  obs_ctx oc;
  size_t i, best = 0, k;
  double bre = -INFINITY, bim = 0.0, vmax = 0.0, sx = 0, sy = 0, sxx = 0, sxy = 0, rate, amp;
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_system sys;
  autobal_rotor_stab_balanced_angles(s, psi, N);
  autobal_rotor_stab_linearization(s, 0.0, 1, a, ns);
  for (i = 0; i < ns * ns; i++) A->data[i] = a[i];
  gsl_eigen_nonsymmv(A, ev, evec, w);
  for (i = 0; i < ns; i++) {
    gsl_complex z = gsl_vector_complex_get(ev, i);
    if (hypot(GSL_REAL(z), GSL_IMAG(z)) < 1e-7) continue;
    if (GSL_IMAG(z) >= 0.0 && GSL_REAL(z) > bre) {
      bre = GSL_REAL(z);
      bim = GSL_IMAG(z);
      best = i;
    }
  }
  *pred = bre;
  for (i = 8; i < 8 + N; i++) vmax = fmax(vmax, gsl_complex_abs(gsl_matrix_complex_get(evec, i, best)));
  /* start small enough that the amplitude at the end stays below ~1e-3 rad */
  amp = fmin(1e-5, 1e-3 * exp(-fmax(bre, 0.0) * t_end));
  for (i = 0; i < ns; i++) {
    gsl_complex z = gsl_matrix_complex_get(evec, i, best);
    y[i] = amp * GSL_REAL(z) / vmax;
  }
  for (i = 0; i < N; i++) y[8 + i] += psi[i];
  oc.r = r;
  oc.cap = 200000;
  oc.n = 0;
  oc.t = malloc(oc.cap * sizeof *oc.t);
  oc.s = malloc(oc.cap * sizeof *oc.s);
  o.rtol = 1e-11;
  o.atol = 1e-16;
  o.dt_out = bim > 0 ? M_PI / bim : 0.01;
  tr = autobal_transient_alloc(ns, &o, NULL);
  autobal_transient_set_observer(tr, obs, &oc);
  sys.rhs = autobal_rotor_rhs_rotating;
  sys.jac = NULL;
  sys.dim = ns;
  sys.params = r;
  autobal_transient_run(tr, &sys, 0.0, t_end, y, NULL);
  for (k = 1; k + 1 < oc.n; k++) {
    const double x = oc.t[k], v = log(oc.s[k]);
    sx += x;
    sy += v;
    sxx += x * x;
    sxy += x * v;
  }
  {
    const double n = (double)(oc.n - 2);
    rate = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  }
  printf("   omega %.9g: predicted max Re(lambda) = %.8f 1/s (Im %.4f), measured %.8f 1/s (%zu samples, %.3g s)\n",
         p->omega, bre, bim, rate, oc.n, t_end);
  free(oc.t);
  free(oc.s);
  autobal_transient_free(tr);
  free(a);
  free(y);
  free(psi);
  gsl_eigen_nonsymmv_free(w);
  gsl_matrix_complex_free(evec);
  gsl_vector_complex_free(ev);
  gsl_matrix_free(A);
  autobal_rotor_free(r);
  autobal_rotor_stab_free(s);
  return rate;
}

static void test_nonlinear_confirmation(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  autobal_rotor_crit c;
  static const double rel[4] = {-0.02, -0.005, 0.005, 0.02};
  size_t k, q;
  printf("-- nonlinear confirmation on either side of every critical speed\n");
  CHECK_STATUS("critical speeds", autobal_rotor_stab_critical(s, 0, 20.0, 1500.0, 600, 1e-10, &c), 0);
  for (k = 0; k < c.n; k++) {
    for (q = 0; q < 4; q++) {
      double pred, got, w = c.value[k] * (1.0 + rel[q]), t_end;
      int v;
      double mg;
      char buf[200];
      p.omega = w;
      autobal_rotor_stab_set(s, 0, w);
      autobal_rotor_stab_margin(s, 0, &mg, &v);
      /* long enough for |r| t >= 3 (or 60 s), short enough that growth stays small */
      t_end = fmin(60.0, 3.0 / fmax(fabs(mg), 1e-3));
      got = measure_rate(&p, t_end, &pred);
      /* two computations (12x12 eigenvalues vs polynomial roots, roots ~ 700 1/s) */
      CHECK_CLOSE("predicted rate = the analysis' margin", pred, mg, 0, 1e-11 * 700);
      snprintf(buf, sizeof buf, "omega = %.6g (critical %.6g %+g%%): sign of the measured rate = verdict", w,
               c.value[k], 100 * rel[q]);
      CHECK(buf, (got < 0) == (v == AUTOBAL_VERDICT_STABLE));
      /* tolerance: 1% of the rate (nonlinear terms O(amplitude <= 1e-3) change log|sigma| by
       * < 1e-3 over |r| t_end >= 3) plus 2e-4 1/s for the slowest cases */
      snprintf(buf, sizeof buf, "omega = %.6g: measured rate = max Re(lambda)", w);
      CHECK_CLOSE(buf, got, pred, 1e-2, 2e-4);
    }
  }
  autobal_rotor_stab_free(s);
}

static void test_fine_sweep(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  autobal_rotor_stab_result r;
  size_t k, bad_h = 0, bad_m = 0, bad_f = 0, n = 2000;
  double worst = 0.0, worst_f = 0.0;
  printf("-- fine sweep: Hurwitz vs roots vs closed eigenvalues vs Floquet, 2000 speeds\n");
  for (k = 0; k < n; k++) {
    const double w = 5.0 + 3000.0 * (double)k / (double)(n - 1);
    autobal_rotor_stab_set(s, 0, w);
    if (autobal_rotor_stab_analyze(s, &r) != 0) {
      bad_m++;
      continue;
    }
    if (r.hurwitz_verdict != r.verdict && r.hurwitz_verdict != AUTOBAL_VERDICT_MARGINAL) bad_h++;
    worst = fmax(worst, r.root_eig_mismatch);
    worst_f = fmax(worst_f, r.floquet_mismatch);
    if (!(r.floquet_mismatch < 1e-7)) bad_f++;
  }
  CHECK("every point analysed", bad_m == 0);
  CHECK("Routh-Hurwitz never contradicts the roots", bad_h == 0);
  CHECK_CLOSE("max relative root/eigenvalue mismatch over the sweep", worst, 0, 0, 1e-9);
  CHECK("Floquet = exp(lambda T) everywhere (1e-7)", bad_f == 0);
  printf("   worst Floquet mismatch %.3g\n", worst_f);
  autobal_rotor_stab_free(s);
}

static void test_anisotropic_limit(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab *s;
  autobal_rotor_crit ci, ca;
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  size_t k;
  printf("-- anisotropic supports: Floquet critical speeds -> isotropic ones\n");
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  autobal_rotor_stab_critical(s, 0, 150.0, 600.0, 200, 1e-9, &ci);
  autobal_rotor_stab_free(s);
  /* the isotropic set analysed by Floquet gives the same speeds */
  o.method = AUTOBAL_ROTOR_STAB_FLOQUET;
  s = autobal_rotor_stab_alloc(&p, &o, NULL);
  CHECK_STATUS("floquet critical (isotropic)", autobal_rotor_stab_critical(s, 0, 150.0, 600.0, 200, 1e-9, &ca), 0);
  CHECK("same number", ca.n == ci.n);
  for (k = 0; k < ca.n && k < ci.n; k++)
    CHECK_CLOSE("Floquet critical speed = polynomial critical speed", ca.value[k], ci.value[k], 1e-7, 0);
  autobal_rotor_stab_free(s);
  /* small anisotropy: close to them */
  p.hw.c_Ly = 0.999e5;
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  CHECK_STATUS("floquet critical (0.1% anisotropy)", autobal_rotor_stab_critical(s, 0, 150.0, 600.0, 200, 1e-9, &ca), 0);
  CHECK("same number", ca.n == ci.n);
  for (k = 0; k < ca.n && k < ci.n; k++) {
    printf("   %.9g (anisotropic) vs %.9g\n", ca.value[k], ci.value[k]);
    CHECK_CLOSE("0.1% anisotropy moves critical speeds by < 1%", ca.value[k], ci.value[k], 1e-2, 0);
  }
  autobal_rotor_stab_free(s);
}

static void test_three_balls(void) {
  static double m3[3] = {0.05, 0.05, 0.05}, r3[3] = {0.1, 0.1, 0.1}, h3[3] = {0.1, 0.1, 0.1};
  static double ps[3] = {1.0, 2.5, 4.0};
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_rotor_stab *s;
  double a, mg, minm = INFINITY;
  int v, all_unstable = 1;
  printf("-- three identical balls at 500 rad/s: every member unstable\n");
  p.plane[0].n_balls = 3;
  p.plane[0].ball_mass = m3;
  p.plane[0].ball_radius = r3;
  p.plane[0].ball_damping = h3;
  p.plane[0].ball_psi = ps;
  p.plane[0].ball_rate = NULL;
  for (a = -M_PI; a < M_PI; a += M_PI / 90.0) {
    o.member[0].kind = AUTOBAL_ROTOR_MEMBER_FREE;
    o.member[0].n_angles = 1;
    o.member[0].angles = &a;
    s = autobal_rotor_stab_alloc(&p, &o, NULL);
    if (autobal_rotor_stab_margin(s, 0, &mg, &v) == 0 && v != AUTOBAL_ROTOR_VERDICT_NONE) {
      all_unstable &= v == AUTOBAL_VERDICT_UNSTABLE;
      minm = fmin(minm, mg);
    }
    autobal_rotor_stab_free(s);
  }
  printf("   smallest margin over the family: %.6g 1/s\n", minm);
  CHECK("every member of the family is unstable", all_unstable);
  {
    /* and the nonlinear model: no balanced state is reached in 60 s */
    autobal_rotor *r = autobal_rotor_alloc(&p, NULL);
    autobal_transient_options to = autobal_transient_options_default();
    autobal_transient *tr;
    autobal_transient_system sys;
    double y[14];
    to.rtol = 1e-9;
    to.atol = 1e-12;
    tr = autobal_transient_alloc(14, &to, NULL);
    autobal_rotor_initial_state(r, AUTOBAL_ROTOR_ROTATING, 0.0, y, 14);
    sys.rhs = autobal_rotor_rhs_rotating;
    sys.jac = NULL;
    sys.dim = 14;
    sys.params = r;
    CHECK_STATUS("transient", autobal_transient_run(tr, &sys, 0.0, 60.0, y, NULL), 0);
    printf("   after 60 s: residual unbalance %.4g (relative), ball rates %.4g %.4g %.4g rad/s\n",
           autobal_rotor_balance_monitor(r, AUTOBAL_ROTOR_ROTATING, 60.0, y), y[11], y[12], y[13]);
    CHECK("not balanced after 60 s", autobal_rotor_balance_monitor(r, AUTOBAL_ROTOR_ROTATING, 60.0, y) > 0.1);
    autobal_transient_free(tr);
    autobal_rotor_free(r);
  }
}

int main(void) {
  gsl_set_error_handler_off();
  test_nonlinear_confirmation();
  test_fine_sweep();
  test_anisotropic_limit();
  test_three_balls();
  return check_summary();
}
