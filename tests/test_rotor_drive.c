/* test_rotor_drive.c: the prescribed spin speed Omega(t) of the rotor model (include/autobal/rotor.h,
 * autobal_rotor_drive): closed forms of Omega, Omega', phi_0 for ramps and tables; the constant
 * drive and a flat ramp give the constant-speed model; the fixed-frame and rotating-frame
 * right-hand sides agree during a ramp (instantaneously: psi'' = phi'' - Omega', and over a
 * transient); the Omega' terms against a direct (4+n) mass-matrix solve; the parameter checks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/rotor.h"
#include "autobal/transient.h"
#include "check.h"

#define MAXDIM 64

static int integrate(int (*f)(double, const double *, double *, void *), autobal_rotor *r, double t0, double t1,
                     double *y, double rtol, double atol) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient *tr;
  int st;
  opt.stepper = "rk8pd";
  opt.rtol = rtol;
  opt.atol = atol;
  opt.h_init = 1e-5;
  opt.max_steps = 50000000ul;
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

static autobal_rotor_params ramp_params(double wa, double wb, double ta, double tb) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
  p.drive.omega_a = wa;
  p.drive.omega_b = wb;
  p.drive.t_a = ta;
  p.drive.t_b = tb;
  return p;
}

static void test_closed_forms(void) {
  autobal_rotor_params p = ramp_params(0.0, 500.0, 1.0, 11.0);
  autobal_rotor *R;
  double o[3];
  printf("-- Omega, Omega', phi_0 of a ramp and a table (closed forms by hand)\n");
  R = autobal_rotor_alloc(&p, NULL);
  CHECK("ramp handle", R != NULL);
  if (!R) return;
  autobal_rotor_drive_eval(R, 0.5, o);
  CHECK_CLOSE("ramp Omega(0.5) (before t_a)", o[0], 0.0, 0, 0);
  CHECK_CLOSE("ramp phi_0(0.5)", o[2], 0.0, 0, 0);
  autobal_rotor_drive_eval(R, 6.0, o);
  CHECK_CLOSE("ramp Omega(6) = 50 (6 - 1)", o[0], 250.0, 1e-15, 0);
  CHECK_CLOSE("ramp Omega'(6) = 500/10", o[1], 50.0, 1e-15, 0);
  CHECK_CLOSE("ramp phi_0(6) = 25 (6 - 1)^2", o[2], 625.0, 1e-15, 0);
  autobal_rotor_drive_eval(R, 20.0, o);
  CHECK_CLOSE("ramp Omega(20) (after t_b)", o[0], 500.0, 0, 0);
  CHECK_CLOSE("ramp Omega'(20)", o[1], 0.0, 0, 0);
  CHECK_CLOSE("ramp phi_0(20) = 2500 + 500 * 9", o[2], 7000.0, 1e-15, 0);
  CHECK_CLOSE("drive_speed_max", autobal_rotor_drive_speed_max(R), 500.0, 0, 0);
  CHECK_STATUS("drive_eval(NaN t)", autobal_rotor_drive_eval(R, NAN, o), AUTOBAL_EINVAL);
  CHECK_STATUS("drive_eval(NULL)", autobal_rotor_drive_eval(NULL, 0.0, o), AUTOBAL_EINVAL);
  autobal_rotor_free(R);

  {
    /* a table with a point before t = 0: Omega = 200 + 100 t on [-1, 1], phi_0(0.5) = 100 + 12.5;
     * a dip 300 -> 100 -> 250 later; phi_0 against a fine Simpson quadrature of Omega */
    double tt[5] = {-1.0, 1.0, 2.0, 2.5, 4.0}, ww[5] = {100.0, 300.0, 300.0, 100.0, 250.0};
    double q = 0.0, prev, h;
    int k, n = 1000; /* h = 0.005: the corners 1, 2, 2.5, 4 are grid points */
    autobal_rotor_params pt = autobal_rotor_params_default();
    pt.drive.mode = AUTOBAL_ROTOR_DRIVE_TABLE;
    pt.drive.n_points = 5;
    pt.drive.table_t = tt;
    pt.drive.table_omega = ww;
    R = autobal_rotor_alloc(&pt, NULL);
    CHECK("table handle", R != NULL);
    if (!R) return;
    tt[1] = 1e9; /* the handle owns a copy */
    autobal_rotor_drive_eval(R, 0.5, o);
    CHECK_CLOSE("table Omega(0.5) = 200 + 50", o[0], 250.0, 1e-15, 0);
    CHECK_CLOSE("table phi_0(0.5) = 112.5 (integral from 0, not from the first point)", o[2], 112.5, 1e-15, 0);
    autobal_rotor_drive_eval(R, 2.25, o);
    CHECK_CLOSE("table Omega'(2.25) = -400", o[1], -400.0, 1e-15, 0);
    autobal_rotor_drive_eval(R, -3.0, o);
    CHECK_CLOSE("table Omega(-3) (before the first point)", o[0], 100.0, 0, 0);
    /* Simpson on [0, 5] piece by piece (exact for the piecewise quadratic integrand) */
    h = 5.0 / n;
    prev = 0.0;
    for (k = 0; k < n; k++) {
      double a = k * h, fa[3];
      autobal_rotor_drive_eval(R, a, fa);
      prev = fa[0];
      autobal_rotor_drive_eval(R, a + 0.5 * h, fa);
      q += h / 6.0 * (prev + 4.0 * fa[0]);
      autobal_rotor_drive_eval(R, a + h, fa);
      q += h / 6.0 * fa[0];
    }
    autobal_rotor_drive_eval(R, 5.0, o);
    CHECK_CLOSE("table phi_0(5) vs Simpson quadrature of Omega", o[2], q, 1e-12, 0);
    CHECK_CLOSE("table phi_0(5) by hand: 250 + 300 + 100 + 262.5 + 250",
                o[2], 0.5 * (200.0 + 300.0) * 1.0 + 300.0 + 0.5 * 0.5 * 400.0 + 1.5 * 175.0 + 250.0, 1e-14, 0);
    CHECK("table Omega is an output channel (one more output)",
          autobal_rotor_output_count(R) == 3 + 7 + 6 * 2 + 1);
    {
      double out[3 + 7 + 12 + 1], y[MAXDIM];
      char name[32];
      const char *unit = NULL;
      autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 2.25, y, autobal_rotor_dim(R));
      CHECK_CLOSE("initial phi_1 = phi_0(2.25) + psi_1 = 250 + 300 + 62.5 + 1", y[8], 613.5, 1e-14, 0);
      autobal_rotor_outputs(R, AUTOBAL_ROTOR_FIXED, 2.25, y, out, 23);
      autobal_rotor_output_name(R, 22, name, sizeof name, &unit);
      CHECK("last output is named Omega in rad/s", !strcmp(name, "Omega") && unit && !strcmp(unit, "rad/s"));
      CHECK_CLOSE("output Omega(2.25)", out[22], 200.0, 1e-15, 0);
      CHECK_CLOSE("output psi_rate of ball 1 (at rest relative to the rotor)", out[3 + 7 + 5], 0.0, 0, 1e-12);
    }
    autobal_rotor_free(R);
  }
}

/* The constant drive is the constant-speed model; a flat ramp gives it to rounding. */
static void test_constant(void) {
  autobal_rotor_params p = autobal_rotor_params_default(), pf = ramp_params(500.0, 500.0, -1.0, 1.0);
  autobal_rotor *A = autobal_rotor_alloc(&p, NULL), *B = autobal_rotor_alloc(&pf, NULL);
  double y[MAXDIM], da[MAXDIM], db[MAXDIM], o[3], dmax = 0.0;
  size_t k, dim;
  printf("-- the constant drive, and a flat ramp (Omega' = 0) vs the constant-speed model\n");
  CHECK("handles", A && B);
  if (!A || !B) return;
  dim = autobal_rotor_dim(A);
  CHECK("constant drive: no Omega output", autobal_rotor_output_count(A) == 3 + 7 + 12);
  autobal_rotor_drive_eval(A, 0.37, o);
  CHECK("constant drive_eval is (omega, 0, omega t) exactly", o[0] == 500.0 && o[1] == 0.0 && o[2] == 500.0 * 0.37);
  autobal_rotor_initial_state(A, AUTOBAL_ROTOR_FIXED, 0.0, y, dim);
  y[0] = 1e-4, y[3] = -2e-4, y[6] = 0.03, y[9] += 3.0, y[10] += 40.0, y[11] -= 25.0;
  autobal_rotor_rhs(0.8, y, da, A);
  autobal_rotor_rhs(0.8, y, db, B);
  for (k = 0; k < dim; k++) dmax = fmax(dmax, fabs(da[k] - db[k]) / (1e-300 + fabs(da[k]) + 1.0));
  CHECK_CLOSE("flat ramp vs constant, fixed-frame rhs (max rel diff)", dmax, 0.0, 0, 1e-12);
  autobal_rotor_rhs_rotating(0.8, y, da, A);
  autobal_rotor_rhs_rotating(0.8, y, db, B);
  dmax = 0.0;
  for (k = 0; k < dim; k++) dmax = fmax(dmax, fabs(da[k] - db[k]) / (fabs(da[k]) + 1.0));
  CHECK_CLOSE("flat ramp vs constant, rotating-frame rhs (max rel diff)", dmax, 0.0, 0, 1e-12);
  autobal_rotor_free(A);
  autobal_rotor_free(B);
}

/* During a ramp: the two right-hand sides at the same motion (psi'' = phi'' - Omega'), and a
 * direct solve of the (4 + n) x (4 + n) mass-matrix system of (3.2), (3.4) with Omega(t). */
static void test_instantaneous(void) {
  autobal_rotor_params p = ramp_params(100.0, 500.0, 0.0, 2.0);
  autobal_rotor *R;
  double y[MAXDIM], yr[MAXDIM], df[MAXDIM], dr[MAXDIM], o[3], dmax = 0.0;
  const double t = 0.7;
  size_t k, dim, N;
  printf("-- instantaneous: fixed vs rotating frame, and a direct solve, during a ramp\n");
  p.inertia = AUTOBAL_ROTOR_INERTIA_PAPER;
  R = autobal_rotor_alloc(&p, NULL);
  CHECK("handle", R != NULL);
  if (!R) return;
  dim = autobal_rotor_dim(R);
  N = autobal_rotor_n_balls_total(R);
  autobal_rotor_drive_eval(R, t, o);
  autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, t, y, dim);
  y[0] = 2e-4, y[1] = -1e-4, y[2] = 3e-3, y[3] = -1e-3, y[4] = 0.02, y[5] = 0.01, y[6] = -0.4, y[7] = 0.3;
  y[8] += 0.3, y[9] -= 1.1, y[10] += 7.0, y[11] -= 3.0;
  autobal_rotor_convert_state(R, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, t, y, yr, dim);
  CHECK("fixed rhs", autobal_rotor_rhs(t, y, df, R) == 0);
  CHECK("rotating rhs", autobal_rotor_rhs_rotating(t, yr, dr, R) == 0);
  for (k = 0; k < 8; k++) dmax = fmax(dmax, fabs(df[k] - dr[k]) / (fabs(df[k]) + 1e-3));
  CHECK_CLOSE("rotor accelerations agree (rel)", dmax, 0.0, 0, 1e-10);
  for (k = 0; k < N; k++) {
    CHECK_CLOSE("psi_i' = phi_i' - Omega", dr[8 + k], df[8 + k] - o[0], 1e-13, 1e-10);
    CHECK_CLOSE("psi_i'' = phi_i'' - Omega'", dr[8 + N + k], df[8 + N + k] - o[1], 1e-10, 1e-8);
  }
  {
    /* direct: unknowns (x'', y'', alpha'', beta'', phi_1'', phi_2''); the fixed-frame equations
     * written out term by term, the unbalance at phi_0 + psi0 with phi_0'' = Omega' */
    const autobal_rotor_lumped *L = autobal_rotor_get_lumped(R);
    const double W = o[0], Wd = o[1], ph0 = o[2], d = p.plane[0].d, s0 = p.plane[0].m0 * p.plane[0].r0;
    double Mx[6][7];
    double su_known = -s0 * (W * W * cos(ph0) + Wd * sin(ph0)), sv_known = -s0 * (W * W * sin(ph0) - Wd * cos(ph0));
    size_t i, j2, c;
    memset(Mx, 0, sizeof Mx);
    /* s_u'' = sum_i m_i r_i (-phi'' sin - phi'^2 cos) + su_known, s_v'' = sum m r (phi'' cos - phi'^2 sin) + sv_known */
    for (i = 0; i < N; i++) {
      const double m = p.plane[0].ball_mass[i], r = p.plane[0].ball_radius[i], ph = y[8 + i], phd = y[8 + N + i];
      su_known -= m * r * phd * phd * cos(ph);
      sv_known -= m * r * phd * phd * sin(ph);
    }
    /* rows 0..3: rotor equations; coefficient of phi_i'' via s'' */
    Mx[0][0] = L->M, Mx[1][1] = L->M, Mx[2][2] = L->A, Mx[3][3] = L->A;
    Mx[0][6] = -(L->h_x * y[4] + L->c_x * y[0] - L->h_xbeta * y[7] - L->c_xbeta * y[3]) - su_known;
    Mx[1][6] = -(L->h_y * y[5] + L->c_y * y[1] + L->h_yalpha * y[6] + L->c_yalpha * y[2]) - sv_known;
    Mx[2][6] = -(L->h_alpha * y[6] + L->c_alpha * y[2] + L->C * W * y[7] + L->C * Wd * y[3] + L->h_yalpha * y[5] +
                 L->c_yalpha * y[1]) + d * sv_known;
    Mx[3][6] = -(L->h_beta * y[7] + L->c_beta * y[3] - L->C * W * y[6] - L->h_xbeta * y[4] - L->c_xbeta * y[0]) -
               d * su_known;
    for (i = 0; i < N; i++) {
      const double m = p.plane[0].ball_mass[i], r = p.plane[0].ball_radius[i], ph = y[8 + i], phd = y[8 + N + i];
      const double h = p.plane[0].ball_damping[i];
      Mx[0][4 + i] += -m * r * sin(ph);
      Mx[1][4 + i] += m * r * cos(ph);
      Mx[2][4 + i] += -d * m * r * cos(ph);
      Mx[3][4 + i] += -d * m * r * sin(ph);
      /* (3.4): m r [r phi'' - (x'' + d beta'') sin + (y'' - d alpha'') cos] + h r^2 (phi' - Omega) = 0 */
      Mx[4 + i][4 + i] = m * r * r;
      Mx[4 + i][0] = -m * r * sin(ph);
      Mx[4 + i][3] = -m * r * d * sin(ph);
      Mx[4 + i][1] = m * r * cos(ph);
      Mx[4 + i][2] = -m * r * d * cos(ph);
      Mx[4 + i][6] = -h * r * r * (phd - W);
    }
    /* Gauss elimination with partial pivoting on the 6 x 6 system */
    for (c = 0; c < 6; c++) {
      size_t piv = c;
      for (i = c + 1; i < 6; i++)
        if (fabs(Mx[i][c]) > fabs(Mx[piv][c])) piv = i;
      for (j2 = 0; j2 < 7; j2++) {
        double tmp = Mx[c][j2];
        Mx[c][j2] = Mx[piv][j2];
        Mx[piv][j2] = tmp;
      }
      for (i = 0; i < 6; i++)
        if (i != c) {
          double f = Mx[i][c] / Mx[c][c];
          for (j2 = c; j2 < 7; j2++) Mx[i][j2] -= f * Mx[c][j2];
        }
    }
    dmax = 0.0;
    for (k = 0; k < 4; k++) dmax = fmax(dmax, fabs(df[4 + k] - Mx[k][6] / Mx[k][k]) / (fabs(df[4 + k]) + 1e-6));
    CHECK_CLOSE("rotor accelerations vs direct solve with Omega, Omega' (rel)", dmax, 0.0, 0, 1e-10);
    for (k = 0; k < N; k++)
      CHECK_CLOSE("phi_i'' vs direct solve", df[8 + N + k], Mx[4 + k][6] / Mx[4 + k][4 + k], 1e-10, 1e-8);
  }
  autobal_rotor_free(R);
}

/* A run-up transient: fixed frame vs rotating frame to the integration tolerance. */
static void test_ramp_transient(void) {
  autobal_rotor_params p[2];
  int c;
  printf("-- ramp transient: fixed frame vs rotating frame (rtol 1e-10)\n");
  p[0] = ramp_params(0.0, 500.0, 0.1, 1.1);
  p[1] = ramp_params(400.0, 150.0, 0.2, 0.7); /* a coast-down through the second resonance */
  for (c = 0; c < 2; c++) {
    autobal_rotor *R = autobal_rotor_alloc(&p[c], NULL);
    double y[MAXDIM], yr[MAXDIM], yc[MAXDIM], dq = 0.0, da = 0.0, amp = 0.0;
    const double T = 1.3;
    size_t k, dim, N;
    int st1, st2;
    if (R == NULL) continue;
    dim = autobal_rotor_dim(R);
    N = autobal_rotor_n_balls_total(R);
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, dim);
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_ROTATING, 0.0, yr, dim);
    st1 = integrate(autobal_rotor_rhs, R, 0.0, T, y, 1e-10, 1e-13);
    st2 = integrate(autobal_rotor_rhs_rotating, R, 0.0, T, yr, 1e-10, 1e-13);
    CHECK("both integrations succeeded", st1 == 0 && st2 == 0);
    autobal_rotor_convert_state(R, AUTOBAL_ROTOR_ROTATING, AUTOBAL_ROTOR_FIXED, T, yr, yc, dim);
    for (k = 0; k < 2; k++) amp = fmax(amp, fabs(y[k]));
    for (k = 0; k < 4; k++) dq = fmax(dq, fabs(y[k] - yc[k]));
    for (k = 0; k < N; k++) da = fmax(da, fabs(y[8 + k] - yc[8 + k]));
    printf("     %s, t = %g s, |x|,|y| = %.3g m\n", c == 0 ? "run-up 0 -> 500" : "coast-down 400 -> 150", T, amp);
    CHECK("   the rotor moved", amp > 1e-7);
    /* rtol 1e-10 per step on a motion of amplitude amp over ~1e4 steps */
    CHECK_CLOSE("   max |q_fixed - q_rotating| (m, rad), tol 1e-7 amp", dq, 0.0, 0, 1e-7 * amp);
    CHECK_CLOSE("   max |phi_fixed - phi_rotating| (rad)", da, 0.0, 0, 1e-6);
    autobal_rotor_free(R);
  }
}

static void test_errors(void) {
  autobal_error e;
  autobal_rotor_params p;
  double tt[3] = {0.0, 1.0, 1.0}, ww[3] = {0.0, 100.0, 200.0};
  printf("-- bad drives are rejected, naming the parameter\n");
  p = ramp_params(0.0, 500.0, 2.0, 2.0);
  CHECK("t_b == t_a", autobal_rotor_alloc(&p, &e) == NULL);
  CHECK_MSG("t_b == t_a", e.message, "drive.t_b");
  p = ramp_params(0.0, 500.0, 2.0, 1.0);
  CHECK_STATUS("t_b < t_a", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("t_b < t_a", e.message, "drive.t_b");
  p = ramp_params(NAN, 500.0, 0.0, 1.0);
  CHECK_STATUS("omega_a NaN", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("omega_a NaN", e.message, "drive.omega_a");
  p = ramp_params(0.0, INFINITY, 0.0, 1.0);
  CHECK_STATUS("omega_b inf", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("omega_b inf", e.message, "drive.omega_b");
  p = ramp_params(0.0, 1.0, NAN, 1.0);
  CHECK_STATUS("t_a NaN", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("t_a NaN", e.message, "drive.t_a");
  p = autobal_rotor_params_default();
  p.drive.mode = 7;
  CHECK_STATUS("mode 7", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("mode 7", e.message, "drive.mode");
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_TABLE;
  p.drive.n_points = 0;
  CHECK_STATUS("table of 0 points", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("table of 0 points", e.message, "drive.n_points");
  p.drive.n_points = 3;
  CHECK_STATUS("table arrays NULL", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("table arrays NULL", e.message, "table_t");
  p.drive.table_t = tt;
  p.drive.table_omega = ww;
  CHECK_STATUS("table times not strictly increasing", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("table times not strictly increasing", e.message, "drive.table_t[2]");
  tt[2] = 2.0;
  ww[1] = NAN;
  CHECK_STATUS("table speed NaN", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("table speed NaN", e.message, "drive.table_omega[1]");
  ww[1] = 100.0;
  CHECK_STATUS("the repaired table", autobal_rotor_params_check(&p, &e), AUTOBAL_SUCCESS);
}

int main(void) {
  test_closed_forms();
  test_constant();
  test_instantaneous();
  test_ramp_transient();
  test_errors();
  return check_summary();
}
