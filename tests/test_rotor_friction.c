/* test_rotor_friction.c: rolling resistance and stiction of the balls (autobal_rotor_friction,
 * docs/device.md section 3) over transients, each check with its own reason:
 *  (b) f = mu = 0: the friction right-hand sides (EXACT with its switching events, REGULARIZED)
 *      reproduce the frictionless transient (to the integration tolerance: the friction path
 *      computes the same equations in a different order, and EXACT restarts at every psi' = 0);
 *  (c) stiction and no vibration drive: the rotor at constant speed, no unbalance, the balls
 *      stuck at random angles with mu well above the holding ratio: nothing moves (the angles
 *      stay bit for bit in the rotating frame, no switch); with mu = f = 0 the same balls move
 *      (the check can fail);
 *  (d) a single stuck ball balanced by an equal unbalance opposite (D stays at rest, so
 *      H = m r Omega' and N = m r Omega^2 exactly) on a coast-down ramp Omega = Omega_a - a t:
 *      it breaks free when mu N = |H|, i.e. at Omega^2 = a / mu, t* = (Omega_a - sqrt(a/mu)) / a;
 *  (d') the critical vibration level: a stuck ball on the rotor's steady whirl (closed-form linear
 *      response to the constant unbalance) holds with mu 2 % above |H|/N and breaks free below;
 *  (e) the regularized law f N tanh(psi'/u_eps) converges to the exact switching result as
 *      u_eps -> 0 (a lagging ball slowed by rolling resistance until it sticks, mu = f): the error
 *      of the final angle and the observed rate;
 *  (f) energy along an EXACT motor run-up with sticks and slips: E(t) - E(0) equals the
 *      integral of L Omega - k_r Omega^2 - supports - ball viscosity - sum r f N |psi'|,
 *      integrated alongside as an extra state entry (energies coded in tests/rotor_energy.h);
 *  and the parameter checks (f > mu, negative, NaN, u_eps <= 0). */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/rotor.h"
#include "autobal/study.h"
#include "autobal/transient.h"
#include "check.h"
#include "rotor_energy.h"
#include "studies/rotor_friction.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A transient through the study (no archive): the final state in y (dim entries). */
static int run_study(const autobal_rotor_params *p, int frame, double t_end, double rtol, double atol,
                     autobal_study_rotor_transient_summary *s) {
  autobal_study_rotor_transient_options o = autobal_study_rotor_transient_options_default();
  autobal_error err;
  int rc;
  o.t_end = t_end;
  o.rtol = rtol;
  o.atol = atol;
  o.frame = frame;
  o.dt_out = t_end / 8.0;
  rc = autobal_study_rotor_transient(p, &o, NULL, s, &err);
  if (rc < 0) printf("     study failed: %s\n", err.message);
  return rc;
}

/* ---- (b) f = mu = 0 --------------------------------------------------------------------- */
static void test_zero_friction(void) {
  static const double zero[2] = {0.0, 0.0};
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_transient_summary s0, s1, s2;
  double dmax1 = 0.0, dmax2 = 0.0;
  size_t i;
  int frame;
  printf("-- (b) f = mu = 0 reproduces the frictionless transient\n");
  for (frame = AUTOBAL_ROTOR_FIXED; frame <= AUTOBAL_ROTOR_ROTATING; frame++) {
    p = autobal_rotor_params_default();
    CHECK_STATUS("frictionless", run_study(&p, frame, 1.0, 1e-12, 1e-13, &s0), AUTOBAL_SUCCESS);
    p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
    p.friction.ball_f[0] = zero;
    p.friction.ball_mu[0] = zero;
    CHECK_STATUS("EXACT, f = mu = 0", run_study(&p, frame, 1.0, 1e-12, 1e-13, &s1), AUTOBAL_SUCCESS);
    p.friction.law = AUTOBAL_ROTOR_FRICTION_REGULARIZED;
    p.friction.u_eps = 1e-3;
    CHECK_STATUS("REGULARIZED, f = 0", run_study(&p, frame, 1.0, 1e-12, 1e-13, &s2), AUTOBAL_SUCCESS);
    printf("     frame %d: EXACT switches: %lu sticks, %lu slips, %lu reversals, %lu resets\n", frame,
           s1.friction_sticks, s1.friction_slips, s1.friction_reversals, s1.solver.resets);
    CHECK("f = mu = 0: no ball ever sticks", s1.friction_sticks == 0 && s1.friction_slips == 0);
    for (i = 0; i < 8; i++) { /* the rotor coordinates, m and rad: relative to their scale */
      const double sc = i < 4 ? 1e-3 : 1e-1;
      double d1 = fabs(s1.state_final[i] - s0.state_final[i]) / sc, d2 = fabs(s2.state_final[i] - s0.state_final[i]) / sc;
      if (d1 > dmax1) dmax1 = d1;
      if (d2 > dmax2) dmax2 = d2;
    }
    for (i = 8; i < s0.dim; i++) { /* ball angles and rates, rad and rad/s */
      double d1 = fabs(s1.state_final[i] - s0.state_final[i]) / (1.0 + fabs(s0.state_final[i]));
      double d2 = fabs(s2.state_final[i] - s0.state_final[i]) / (1.0 + fabs(s0.state_final[i]));
      if (d1 > dmax1) dmax1 = d1;
      if (d2 > dmax2) dmax2 = d2;
    }
    printf("     frame %d: largest scaled difference of the final state: EXACT %.3g, REGULARIZED %.3g\n", frame, dmax1,
           dmax2);
    CHECK("EXACT f = mu = 0 = frictionless to 1e-8 (tolerances 1e-12)", dmax1 < 1e-8);
    CHECK("REGULARIZED f = 0 = frictionless to 1e-8", dmax2 < 1e-8);
    autobal_study_rotor_transient_summary_free(&s0);
    autobal_study_rotor_transient_summary_free(&s1);
    autobal_study_rotor_transient_summary_free(&s2);
  }
}

/* ---- (c) stiction, no unbalance, constant speed: nothing moves -------------------------- */
static void test_stays_put(void) {
  static const double f2[2] = {0.01, 0.01}, mu2[2] = {0.1, 0.1}, z2[2] = {0.0, 0.0};
  double psi[2], rate[2] = {0.0, 0.0};
  unsigned long seed = 12345;
  int c, moved_all = 1;
  printf("-- (c) stiction, constant speed, no unbalance: every configuration stays put\n");
  for (c = 0; c < 6; c++) {
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_study_rotor_transient_summary s;
    size_t k;
    int still = 1;
    for (k = 0; k < 2; k++) { /* a small LCG: reproducible angles in (-pi, pi) */
      seed = (seed * 1103515245UL + 12345UL) & 0x7fffffffUL;
      psi[k] = ((double)seed / 2147483648.0 * 2.0 - 1.0) * M_PI;
    }
    p.plane[0].m0 = 0.0;
    p.plane[0].ball_psi = psi;
    p.plane[0].ball_rate = rate;
    p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
    p.friction.ball_f[0] = f2;
    p.friction.ball_mu[0] = mu2;
    CHECK_STATUS("stuck balls, 0.5 s", run_study(&p, AUTOBAL_ROTOR_ROTATING, 0.5, 1e-10, 1e-12, &s), AUTOBAL_SUCCESS);
    for (k = 0; k < 2; k++)
      if (s.state_final[8 + k] != psi[k] || s.state_final[10 + k] != 0.0) still = 0;
    printf("     psi = (%.6f, %.6f): slips %lu, time stuck %.9g, %.9g s\n", psi[0], psi[1], s.friction_slips,
           s.ball_time_stuck[0][0], s.ball_time_stuck[0][1]);
    CHECK("both balls stuck from t = 0 to the end, angles unchanged bit for bit",
          still && s.friction_slips == 0 && s.ball_time_stuck[0][0] == 0.5 && s.ball_time_stuck[0][1] == 0.5 &&
              s.ball_stuck_final[0][0] && s.ball_stuck_final[0][1]);
    autobal_study_rotor_transient_summary_free(&s);
    /* the same without stiction: the balls move (the vibration of the unbalanced rotor drives them) */
    p.friction.ball_f[0] = z2;
    p.friction.ball_mu[0] = z2;
    CHECK_STATUS("f = mu = 0, 0.5 s", run_study(&p, AUTOBAL_ROTOR_ROTATING, 0.5, 1e-10, 1e-12, &s), AUTOBAL_SUCCESS);
    if (!(fabs(s.state_final[8] - psi[0]) > 1e-6 || fabs(s.state_final[9] - psi[1]) > 1e-6)) moved_all = 0;
    autobal_study_rotor_transient_summary_free(&s);
  }
  CHECK("without stiction the same configurations move (> 1e-6 rad)", moved_all);
}

/* ---- (d) break-free time on a coast-down ------------------------------------------------- */
static void test_break_free(void) {
  const double mus[2] = {0.02, 0.05}, Wa = 100.0, a = 50.0;
  int c;
  printf("-- (d) a single stuck ball breaks free at mu Omega^2 = |Omega'| (D at rest)\n");
  for (c = 0; c < 2; c++) {
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_study_rotor_transient_summary s;
    static const double m1[1] = {0.05}, r1[1] = {0.1}, h1[1] = {0.1}, psi1[1] = {M_PI}, rate1[1] = {0.0};
    double f1[1] = {0.01}, mu1[1];
    const double tstar = (Wa - sqrt(a / mus[c])) / a;
    int frame;
    mu1[0] = mus[c];
    p.plane[0].n_balls = 1;
    p.plane[0].ball_mass = m1;
    p.plane[0].ball_radius = r1;
    p.plane[0].ball_damping = h1;
    p.plane[0].ball_psi = psi1;
    p.plane[0].ball_rate = rate1;
    p.plane[0].m0 = 0.05; /* m0 r0 = m r, opposite: s = 0 while the ball is stuck */
    p.plane[0].r0 = 0.1;
    p.plane[0].psi0 = 0.0;
    p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
    p.drive.omega_a = Wa;
    p.drive.omega_b = 0.0;
    p.drive.t_a = 0.0;
    p.drive.t_b = Wa / a;
    p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
    p.friction.ball_f[0] = f1;
    p.friction.ball_mu[0] = mu1;
    for (frame = AUTOBAL_ROTOR_FIXED; frame <= AUTOBAL_ROTOR_ROTATING; frame++) {
      char what[160];
      CHECK_STATUS("coast-down", run_study(&p, frame, 1.6, 1e-11, 1e-13, &s), AUTOBAL_SUCCESS);
      snprintf(what, sizeof what, "mu = %g, frame %d: time stuck = t* = (Omega_a - sqrt(a/mu))/a", mus[c], frame);
      CHECK_CLOSE(what, s.ball_time_stuck[0][0], tstar, 0.0, 1e-8);
      CHECK("one slip, no stick after it, the ball slips at the end",
            s.friction_slips == 1 && s.friction_sticks == 0 && !s.ball_stuck_final[0][0]);
      autobal_study_rotor_transient_summary_free(&s);
    }
  }
}

/* ---- (d') the critical vibration level of a steady whirl ------------------------------------
 * One ball stuck at psi = 1 with the unbalance m0 r0 at psi0 = 0, constant speed 250 rad/s: a
 * constant unbalance S = m0 r0 + m r e^{i psi}, so the rotor's steady response is the solution of
 * the linear equations (3.2) with the forcing s_u'' + i s_v'' = -Omega^2 S e^{i Omega t}, coded here
 * from docs/rotor.md with the lumped coefficients: q = Re(Q e^{i Omega t}),
 *   (-Omega^2 D + i Omega C + K) Q = -F,  F = (Fu, Fv, -d Fv, d Fu),  Fu = -Omega^2 S, Fv = i Omega^2 S
 * (complex 4x4, Gaussian elimination).  The holding ratio |H|/N of the stuck ball along that whirl
 * (D's acceleration -Omega^2 (Q_x + d Q_beta, Q_y - d Q_alpha) e^{i Omega t}) is the critical mu:
 * started on the whirl, the ball stays with mu 2 % above its largest value and breaks free at
 * once with mu 2 % below its smallest. */
static void cplx_solve4(double complex a[4][4], double complex b[4]) {
  int i, j, k;
  for (k = 0; k < 4; k++) {
    int piv = k;
    for (i = k + 1; i < 4; i++)
      if (cabs(a[i][k]) > cabs(a[piv][k])) piv = i;
    for (j = 0; j < 4; j++) {
      double complex t = a[k][j];
      a[k][j] = a[piv][j];
      a[piv][j] = t;
    }
    {
      double complex t = b[k];
      b[k] = b[piv];
      b[piv] = t;
    }
    for (i = k + 1; i < 4; i++) {
      double complex l = a[i][k] / a[k][k];
      for (j = k; j < 4; j++) a[i][j] -= l * a[k][j];
      b[i] -= l * b[k];
    }
  }
  for (i = 3; i >= 0; i--) {
    for (j = i + 1; j < 4; j++) b[i] -= a[i][j] * b[j];
    b[i] /= a[i][i];
  }
}

static void test_whirl(void) {
  static const double m1[1] = {0.05}, r1[1] = {0.1}, h1[1] = {0.1}, psi1[1] = {1.0}, rate1[1] = {0.0};
  autobal_rotor_params p = autobal_rotor_params_default();
  const double W = 250.0, d = 0.10, m = 0.05, r = 0.1, psi = 1.0;
  double complex a[4][4], Q[4], S, Fu, Fv;
  const autobal_rotor_lumped *L;
  autobal_rotor *rot;
  double rmin = 1e300, rmax = 0.0, H0 = 0.0, N0 = 0.0, y[12], Hc[1], Nc[1];
  int k, c;
  printf("-- (d') a stuck ball on a steady whirl: the critical mu = |H|/N of the closed-form response\n");
  p.omega = W;
  p.plane[0].n_balls = 1;
  p.plane[0].ball_mass = m1;
  p.plane[0].ball_radius = r1;
  p.plane[0].ball_damping = h1;
  p.plane[0].ball_psi = psi1;
  p.plane[0].ball_rate = rate1;
  rot = autobal_rotor_alloc(&p, NULL);
  L = autobal_rotor_get_lumped(rot);
  memset(a, 0, sizeof a);
  /* -Omega^2 D + i Omega C + K, rows x, y, alpha, beta (3.2) */
  a[0][0] = -W * W * L->M + I * W * L->h_x + L->c_x;
  a[0][3] = -I * W * L->h_xbeta - L->c_xbeta;
  a[1][1] = -W * W * L->M + I * W * L->h_y + L->c_y;
  a[1][2] = I * W * L->h_yalpha + L->c_yalpha;
  a[2][1] = I * W * L->h_yalpha + L->c_yalpha;
  a[2][2] = -W * W * L->A + I * W * L->h_alpha + L->c_alpha;
  a[2][3] = I * W * L->C * W;
  a[3][0] = -I * W * L->h_xbeta - L->c_xbeta;
  a[3][2] = -I * W * L->C * W;
  a[3][3] = -W * W * L->A + I * W * L->h_beta + L->c_beta;
  S = 0.02 * 0.1 + m * r * cexp(I * psi);
  Fu = -W * W * S;
  Fv = I * W * W * S;
  Q[0] = -Fu;
  Q[1] = -Fv;
  Q[2] = d * Fv;
  Q[3] = -d * Fu;
  cplx_solve4(a, Q);
  for (k = 0; k < 64; k++) { /* |H|/N over one revolution */
    const double t = k * (2.0 * M_PI / W) / 64.0;
    const double complex e = cexp(I * W * t);
    const double ud = creal(-W * W * (Q[0] + d * Q[3]) * e), vd = creal(-W * W * (Q[1] - d * Q[2]) * e);
    const double ph = W * t + psi;
    const double H = m * (-ud * sin(ph) + vd * cos(ph)), N = m * (r * W * W - ud * cos(ph) - vd * sin(ph));
    if (k == 0) H0 = H, N0 = N;
    if (fabs(H) / N < rmin) rmin = fabs(H) / N;
    if (fabs(H) / N > rmax) rmax = fabs(H) / N;
  }
  printf("     closed-form whirl: |x| = %.4g um; |H|/N from %.6g to %.6g over a revolution\n", cabs(Q[0]) * 1e6, rmin,
         rmax);
  /* the initial state on the whirl; the library's H and N there (the constrained solve) */
  for (k = 0; k < 4; k++) {
    p.q0[k] = creal(Q[k]);
    p.qd0[k] = creal(I * W * Q[k]);
  }
  autobal_rotor_free(rot);
  p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
  for (c = 0; c < 2; c++) {
    double mu1[1], f1[1];
    autobal_study_rotor_transient_summary s;
    mu1[0] = c == 0 ? 1.02 * rmax : 0.98 * rmin;
    f1[0] = 0.5 * mu1[0];
    p.friction.ball_f[0] = f1;
    p.friction.ball_mu[0] = mu1;
    rot = autobal_rotor_alloc(&p, NULL);
    autobal_rotor_initial_state(rot, AUTOBAL_ROTOR_ROTATING, 0.0, y, 10);
    autobal_rotor_ball_mode_set(rot, 0, AUTOBAL_ROTOR_BALL_STUCK);
    autobal_rotor_holding_forces(rot, AUTOBAL_ROTOR_ROTATING, 0.0, y, Hc, 1);
    autobal_rotor_normal_forces(rot, AUTOBAL_ROTOR_ROTATING, 0.0, y, Nc, 1);
    if (c == 0) {
      CHECK_CLOSE("the library's H at the whirl state = the closed form", Hc[0], H0, 1e-12, 0);
      CHECK_CLOSE("the library's N at the whirl state = the closed form", Nc[0], N0, 1e-12, 0);
    }
    CHECK_STATUS("settle at t = 0", autobal_rotor_friction_settle(rot, AUTOBAL_ROTOR_ROTATING, 0.0, y, 1, NULL, NULL, NULL) >= 0, 1);
    if (c == 0) {
      CHECK("mu = 1.02 max |H|/N: the ball stays stuck at t = 0", autobal_rotor_ball_mode_get(rot, 0) == AUTOBAL_ROTOR_BALL_STUCK);
      CHECK_STATUS("0.3 s on the whirl", run_study(&p, AUTOBAL_ROTOR_ROTATING, 0.3, 1e-11, 1e-13, &s), AUTOBAL_SUCCESS);
      printf("     mu = %.6g: slips %lu, time stuck %.9g s, final psi %.17g\n", mu1[0], s.friction_slips,
             s.ball_time_stuck[0][0], s.state_final[8]);
      CHECK("... and for 0.3 s (no slip, psi unchanged)", s.friction_slips == 0 && s.ball_time_stuck[0][0] == 0.3 &&
                                                            s.state_final[8] == psi);
    } else {
      CHECK("mu = 0.98 min |H|/N: the ball breaks free at t = 0", autobal_rotor_ball_mode_get(rot, 0) != AUTOBAL_ROTOR_BALL_STUCK);
      CHECK_STATUS("0.3 s from the whirl", run_study(&p, AUTOBAL_ROTOR_ROTATING, 0.3, 1e-11, 1e-13, &s), AUTOBAL_SUCCESS);
      printf("     mu = %.6g: time stuck %.9g s, psi moved by %.4g rad\n", mu1[0], s.ball_time_stuck[0][0],
             s.state_final[8] - psi);
      CHECK("... and moves (> 1e-3 rad in 0.3 s)", fabs(s.state_final[8] - psi) > 1e-3);
    }
    autobal_study_rotor_transient_summary_free(&s);
    autobal_rotor_free(rot);
  }
}

/* ---- (e) regularized -> exact ------------------------------------------------------------ */
static void conv_params(autobal_rotor_params *p, const double *f1, const double *rate1) {
  static const double m1[1] = {0.05}, r1[1] = {0.1}, h1[1] = {0.001}, psi1[1] = {2.0};
  *p = autobal_rotor_params_default();
  p->omega = 100.0;
  p->plane[0].n_balls = 1;
  p->plane[0].ball_mass = m1;
  p->plane[0].ball_radius = r1;
  p->plane[0].ball_damping = h1;
  p->plane[0].ball_psi = psi1;
  p->plane[0].ball_rate = rate1;
  p->plane[0].m0 = 0.02;
  p->friction.ball_f[0] = f1;
  p->friction.ball_mu[0] = f1;
}

static void test_regularized_convergence(void) {
  static const double f1[1] = {0.02}, rate1[1] = {-20.0};
  const double ueps[4] = {1e-1, 1e-2, 1e-3, 1e-4};
  autobal_rotor_params p;
  autobal_study_rotor_transient_summary se, sr;
  double err[4], psi_exact;
  int c;
  printf("-- (e) the regularized law converges to the exact switching result as u_eps -> 0\n");
  conv_params(&p, f1, rate1);
  p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
  CHECK_STATUS("exact law", run_study(&p, AUTOBAL_ROTOR_ROTATING, 1.0, 1e-12, 1e-14, &se), AUTOBAL_SUCCESS);
  psi_exact = se.state_final[8];
  printf("     exact: sticks %lu, slips %lu, reversals %lu, time stuck %.9g s, final psi %.12f rad\n",
         se.friction_sticks, se.friction_slips, se.friction_reversals, se.ball_time_stuck[0][0], psi_exact);
  CHECK("the ball slips, then sticks for good", se.friction_sticks >= 1 && se.ball_stuck_final[0][0] &&
                                                    se.ball_time_stuck[0][0] > 0.2);
  for (c = 0; c < 4; c++) {
    conv_params(&p, f1, rate1);
    p.friction.law = AUTOBAL_ROTOR_FRICTION_REGULARIZED;
    p.friction.u_eps = ueps[c];
    CHECK_STATUS("regularized law", run_study(&p, AUTOBAL_ROTOR_ROTATING, 1.0, 1e-12, 1e-14, &sr), AUTOBAL_SUCCESS);
    err[c] = fabs(sr.state_final[8] - psi_exact);
    printf("     u_eps = %.0e rad/s: |psi - psi_exact| = %.4e rad, psi' = %.3e rad/s, steps %lu%s\n", ueps[c], err[c],
           sr.state_final[9], sr.solver.steps, c ? "" : "");
    if (c) printf("       observed rate log10(err ratio) / log10(u_eps ratio) = %.3f\n", log10(err[c - 1] / err[c]));
    autobal_study_rotor_transient_summary_free(&sr);
  }
  CHECK("the error falls with u_eps (each step by a factor > 5)", err[1] < err[0] / 5 && err[2] < err[1] / 5 &&
                                                                       err[3] < err[2] / 5);
  CHECK("observed order >= 0.9 over the last decade", log10(err[2] / err[3]) > 0.9);
  autobal_study_rotor_transient_summary_free(&se);
}

/* ---- (f) energy along an EXACT motor run-up ---------------------------------------------- */
typedef struct energy_ctx {
  autobal_rotor *rot;
  size_t dim;
  double *Nb; /* normal forces */
  double fric_max;
} energy_ctx;

/* the model's rhs for y[0 .. dim-1]; y[dim] = integral of the net power, y[dim + 1] that of the
 * friction dissipation alone */
static int energy_rhs(double t, const double y[], double dydt[], void *user) {
  energy_ctx *c = (energy_ctx *)user;
  const autobal_rotor_params *p = autobal_rotor_get_params(c->rot);
  const size_t N = autobal_rotor_n_balls_total(c->rot);
  const double W = y[c->dim - 1];
  double P, Dfr = 0.0;
  size_t k;
  int rc = autobal_rotor_rhs(t, y, dydt, c->rot);
  if (rc) return rc;
  if (autobal_rotor_normal_forces(c->rot, AUTOBAL_ROTOR_FIXED, t, y, c->Nb, N) != AUTOBAL_SUCCESS) return GSL_EBADFUNC;
  for (k = 0; k < N; k++) {
    const size_t j = k < p->plane[0].n_balls ? 0 : 1, i = j ? k - p->plane[0].n_balls : k;
    if (autobal_rotor_ball_mode_get(c->rot, k) == AUTOBAL_ROTOR_BALL_STUCK) continue;
    Dfr += p->plane[j].ball_radius[i] * p->friction.ball_f[j][i] * c->Nb[k] * fabs(y[8 + N + k] - W);
  }
  P = autobal_rotor_motor_torque(c->rot, W) * W;
  dydt[c->dim] = P - motor_dissipation(c->rot, y) - Dfr;
  dydt[c->dim + 1] = Dfr;
  return 0;
}

static void test_energy(void) {
  static const double f2[2] = {0.01, 0.01}, mu2[2] = {0.02, 0.02}, rate2[2] = {-20.0, -10.0};
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_system sys;
  autobal_transient_stats st;
  study_friction *fr = NULL;
  autobal_study_rotor_transient_summary s;
  energy_ctx c;
  autobal_rotor *rot;
  autobal_error err;
  double y[64], E0, E1, Nb[4], te = 0.0;
  int rc;
  printf("-- (f) energy along an EXACT motor run-up: dE = work of the motor - all dissipation\n");
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
  p.drive.J = 0.04;
  p.drive.L_0 = 5.0;
  p.drive.omega_0 = 600.0;
  p.drive.k_r = 1e-3;
  p.drive.omega_start = 100.0;
  p.plane[0].ball_rate = rate2; /* the balls lag: they stick first, then break free */
  p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
  p.friction.ball_f[0] = f2;
  p.friction.ball_mu[0] = mu2;
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("motor rotor with friction", rot != NULL);
  if (!rot) return;
  c.rot = rot;
  c.dim = autobal_rotor_dim(rot);
  c.Nb = Nb;
  c.fric_max = 0.0;
  o.rtol = 1e-12;
  o.atol = 1e-13;
  o.event_tol = 1e-12;
  tr = autobal_transient_alloc(c.dim + 2, &o, &err);
  CHECK("driver", tr != NULL);
  autobal_rotor_initial_state(rot, AUTOBAL_ROTOR_FIXED, 0.0, y, c.dim);
  y[c.dim] = 0.0;
  y[c.dim + 1] = 0.0;
  CHECK_STATUS("friction events installed", study_friction_begin(rot, AUTOBAL_ROTOR_FIXED, tr, 0.0, y, &fr, &err),
               AUTOBAL_SUCCESS);
  E0 = motor_energy(rot, y);
  sys.rhs = energy_rhs;
  sys.jac = NULL;
  sys.dim = c.dim + 2;
  sys.params = &c;
  rc = autobal_transient_run(tr, &sys, 0.0, 3.0, y, &te);
  CHECK_STATUS("run-up to 3 s", rc, AUTOBAL_SUCCESS);
  memset(&s, 0, sizeof s);
  s.n_planes = 1;
  s.n_balls[0] = 2;
  CHECK_STATUS("friction summary", study_friction_finish(fr, te, &s, &err), AUTOBAL_SUCCESS);
  autobal_transient_get_stats(tr, &st);
  E1 = motor_energy(rot, y);
  printf("     %lu sticks, %lu slips, %lu reversals, %lu resets; Omega(3 s) = %.6f rad/s; time stuck %.6f, %.6f s\n",
         s.friction_sticks, s.friction_slips, s.friction_reversals, st.resets, y[c.dim - 1], s.ball_time_stuck[0][0],
         s.ball_time_stuck[0][1]);
  CHECK("the run has both sticks and slips", s.friction_sticks >= 1 && s.friction_slips >= 1);
  printf("     E(0) = %.12g J, E(3 s) = %.12g J, integral of the net power = %.12g J\n", E0, E1, y[c.dim]);
  printf("     friction dissipation sum r f N |psi'| integrated: %.9g J\n", y[c.dim + 1]);
  CHECK_CLOSE("E(3 s) - E(0) = integral of (motor power - dissipation - sum r f N |psi'|)", E1 - E0, y[c.dim],
              0.0, 1e-10 * E1);
  CHECK("the friction dissipation is 1e6 times larger than that tolerance", y[c.dim + 1] > 1e-4 * E1);
  study_friction_summary_free(&s);
  study_friction_free(fr);
  autobal_transient_free(tr);
  autobal_rotor_free(rot);
}

/* ---- parameter checks ---------------------------------------------------------------------- */
static void test_params(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_error err;
  double f[2] = {0.02, 0.01}, mu[2] = {0.01, 0.03};
  autobal_rotor *r;
  printf("-- parameter checks\n");
  p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
  p.friction.ball_f[0] = f;
  p.friction.ball_mu[0] = mu;
  CHECK_STATUS("f > mu", autobal_rotor_params_check(&p, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names plane[0].ball_mu[0] and the range", err.message, "plane[0].ball_mu[0]");
  CHECK_MSG("... the range", err.message, "[0.02, inf)");
  mu[0] = 0.02;
  f[1] = -0.01;
  CHECK_STATUS("negative f", autobal_rotor_params_check(&p, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names plane[0].ball_f[1]", err.message, "plane[0].ball_f[1]");
  f[1] = 0.01;
  mu[1] = NAN;
  CHECK_STATUS("NaN mu", autobal_rotor_params_check(&p, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names plane[0].ball_mu[1]", err.message, "plane[0].ball_mu[1]");
  mu[1] = 0.03;
  CHECK_STATUS("valid friction", autobal_rotor_params_check(&p, &err), AUTOBAL_SUCCESS);
  p.friction.law = AUTOBAL_ROTOR_FRICTION_REGULARIZED;
  p.friction.u_eps = 0.0;
  CHECK_STATUS("u_eps = 0", autobal_rotor_params_check(&p, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names friction.u_eps", err.message, "friction.u_eps");
  p.friction.law = 7;
  CHECK_STATUS("unknown law", autobal_rotor_params_check(&p, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names friction.law", err.message, "friction.law");
  /* modes: only under EXACT */
  p.friction.law = AUTOBAL_ROTOR_FRICTION_REGULARIZED;
  p.friction.u_eps = 0.1;
  r = autobal_rotor_alloc(&p, &err);
  CHECK("regularized handle", r != NULL);
  CHECK_STATUS("set a mode under REGULARIZED: EINVAL", autobal_rotor_ball_mode_set(r, 0, AUTOBAL_ROTOR_BALL_STUCK),
               AUTOBAL_EINVAL);
  CHECK("outputs gain 2 N friction columns", autobal_rotor_output_count(r) == 3 + 7 + 12 + 4);
  {
    char name[64];
    const char *unit;
    autobal_rotor_output_name(r, 3 + 7 + 12 + 0, name, sizeof name, &unit);
    CHECK_MSG("first friction column", name, "p1_b1_stuck");
    autobal_rotor_output_name(r, 3 + 7 + 12 + 3, name, sizeof name, &unit);
    CHECK_MSG("last friction column", name, "p1_b2_N");
    CHECK_MSG("its unit", unit, "N");
  }
  autobal_rotor_free(r);
  /* a ball that would leave its track (N <= 0): the rhs fails, naming the ball and the time */
  {
    static const double z[2] = {0.0, 0.0};
    autobal_rotor_params q = autobal_rotor_params_default();
    double y[12], dy[12];
    q.omega = 0.0;
    q.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
    q.friction.ball_f[0] = z;
    r = autobal_rotor_alloc(&q, &err);
    autobal_rotor_initial_state(r, AUTOBAL_ROTOR_FIXED, 0.0, y, 12);
    CHECK("at rest (Omega = 0) N = 0: the rhs refuses the state (LEAVES_TRACK)", autobal_rotor_rhs(0.25, y, dy, r) == AUTOBAL_ROTOR_RHS_LEAVES_TRACK);
    CHECK_MSG("the message names the ball", autobal_rotor_errmsg(r), "ball 1 of plane 1");
    CHECK_MSG("and the time", autobal_rotor_errmsg(r), "t = 0.25");
    autobal_rotor_free(r);
  }
}

/* Gravity (autobal_rotor_params.gravity) reaches the friction right-hand sides: with f = mu = 0
 * every slipping ball feels no friction, so the EXACT law's right-hand sides must equal the
 * frictionless ones with gravity on (an independent path: the gravity terms of the SPD solve),
 * both frames, one and two planes, a ramp drive; and gravity must change them. */
static void test_gravity_reaches_friction(void) {
  int planes, frame;
  for (planes = 1; planes <= 2; planes++)
    for (frame = 0; frame < 2; frame++) {
      autobal_rotor_params p = autobal_rotor_params_default(), q;
      static const double zero2[2] = {0.0, 0.0};
      autobal_rotor *a, *b, *c;
      double y[32], fa[32], fb[32], fc[32], dmax = 0.0, dgrav = 0.0;
      size_t i, n;
      char what[128];
      p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
      p.drive.omega_a = 100.0, p.drive.omega_b = 300.0, p.drive.t_a = 0.0, p.drive.t_b = 2.0;
      if (planes == 2) {
        p.n_planes = 2;
        p.plane[1] = p.plane[0];
        p.plane[1].d = -0.08;
        p.plane[1].psi0 = 1.0;
      }
      p.gravity = 1;
      p.shaft_angle = 1.2;
      p.g = 9.80665;
      q = p;
      q.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
      q.friction.ball_f[0] = q.friction.ball_mu[0] = zero2;
      if (planes == 2) q.friction.ball_f[1] = q.friction.ball_mu[1] = zero2;
      a = autobal_rotor_alloc(&p, NULL);
      b = autobal_rotor_alloc(&q, NULL);
      p.gravity = 0;
      c = autobal_rotor_alloc(&p, NULL);
      n = autobal_rotor_dim(a);
      autobal_rotor_initial_state(a, frame, 0.7, y, n);
      for (i = 0; i < 8; i++) y[i] += 1e-5 * (double)(i + 1); /* the rotor moving */
      for (i = 8; i < n; i++) y[i] += 0.1 * (double)i;         /* balls slipping (positive) */
      if (frame) {
        autobal_rotor_rhs_rotating(0.7, y, fa, a), autobal_rotor_rhs_rotating(0.7, y, fb, b),
            autobal_rotor_rhs_rotating(0.7, y, fc, c);
      } else {
        autobal_rotor_rhs(0.7, y, fa, a), autobal_rotor_rhs(0.7, y, fb, b), autobal_rotor_rhs(0.7, y, fc, c);
      }
      for (i = 0; i < n; i++) {
        dmax = fmax(dmax, fabs(fa[i] - fb[i]) / (1.0 + fabs(fa[i])));
        dgrav = fmax(dgrav, fabs(fa[i] - fc[i]) / (1.0 + fabs(fa[i])));
      }
      snprintf(what, sizeof what, "gravity, %d plane(s), %s frame: friction RHS (f = mu = 0) == frictionless RHS",
               planes, frame ? "rotating" : "fixed");
      CHECK_CLOSE(what, dmax, 0.0, 0.0, 1e-12);
      snprintf(what, sizeof what, "... and gravity changes the derivative (%.3g)", dgrav);
      CHECK(what, dgrav > 1e-6);
      autobal_rotor_free(a), autobal_rotor_free(b), autobal_rotor_free(c);
    }
}

int main(void) {
  test_gravity_reaches_friction();
  gsl_set_error_handler_off();
  test_params();
  test_zero_friction();
  test_stays_put();
  test_break_free();
  test_whirl();
  test_regularized_convergence();
  test_energy();
  return check_summary();
}
