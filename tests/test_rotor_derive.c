/* test_rotor_derive.c: the C right-hand sides with a prescribed spin speed (autobal_rotor_drive,
 * src/models/rotor/rotor.c) against the accelerations of the independent SymPy derivation
 * (tools/derive/derive_rotor.py, from the energies of docs/device.md; its values are in
 * tools/derive/check_values.json, which test_derive keeps equal to what the script computes).
 *
 * The check state of the JSON has phi_0 = 0.3 rad, Omega = 300 rad/s, Omega' = 50 rad/s^2.  A ramp
 * drive from t = 0 with slope 50 rad/s^2 reaches exactly that at the time t* where
 * Omega(t*) = 300 and phi_0(t*) = integral_0^t* Omega = 0.3: with Omega(t) = omega_a + 50 t,
 * phi_0(t) = 300 t - 25 t^2 = 0.3.  Both frames, one and two planes; every parameter and state
 * value is read from the JSON, nothing is copied from the program's own output.
 *
 * The MOTOR drive (phi_0, Omega in the state) at the JSON's "motor" block: Omega = 300 rad/s,
 * L(Omega) = L_0 (1 - Omega/Omega_0), k_r, J: the accelerations including phi_0'' = Omega', and
 * the total energy E and dE/dt = motor power - dissipation computed here from the documented
 * energies (tests/rotor_energy.h) against the SymPy values. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/rotor.h"
#include "check.h"
#include "check_json.h"
#include "rotor_energy.h"
#include "models/rotor/rotor_internal.h"

#define JSON_PATH AUTOBAL_TEST_DATA_DIR "/../tools/derive/check_values.json"



static void run_case(const char *json, const char *which, size_t n_planes) {
  const char *blk = after_key(json, which), *st = after_key(blk, "state");
  const char *pre = after_key(blk, "prescribed"), *acc = after_key(pre, "accelerations");
  autobal_rotor_params p;
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2], y[8 + 8], dy[8 + 8], yr[8 + 8], dyr[8 + 8];
  double Om, Omd, phi0, t, drv[3];
  autobal_rotor *rot;
  autobal_error err;
  size_t j, i, N = 2 * n_planes;
  char what[160];
  static const char *const qdd[4] = {"x_dd", "y_dd", "alpha_dd", "beta_dd"};
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};

  CHECK("JSON blocks found", blk && st && pre && acc);
  if (!(blk && st && pre && acc)) return;
  if (load_params(blk, n_planes, &p, m, r, h, psi, rate) != 0) return;
  Om = num(pre, "Omega"), Omd = num(pre, "Omega_dot"), phi0 = num(st, "phi_0");
  /* the ramp through (Omega, Omega', phi_0) = (Om, Omd, phi0) at t* */
  t = (Om - sqrt(Om * Om - 2.0 * Omd * phi0)) / Omd;
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
  p.drive.t_a = 0.0, p.drive.t_b = 10.0;
  p.drive.omega_a = Om - Omd * t, p.drive.omega_b = p.drive.omega_a + Omd * 10.0;
  p.omega = Om;
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("rotor with a ramp drive", rot != NULL);
  if (!rot) {
    printf("     %s\n", err.message);
    return;
  }
  CHECK("drive evaluated", autobal_rotor_drive_eval(rot, t, drv) == AUTOBAL_SUCCESS);
  CHECK_CLOSE("Omega(t*)", drv[0], Om, 1e-14, 0);
  CHECK_CLOSE("Omega'(t*)", drv[1], Omd, 1e-14, 0);
  CHECK_CLOSE("phi_0(t*)", drv[2], phi0, 1e-12, 0);
  /* state: fixed frame with absolute ball angles, rotating frame with psi = phi - phi_0 */
  for (i = 0; i < 4; i++) {
    char k2[16];
    y[i] = num(st, qn[i]);
    snprintf(k2, sizeof k2, "%s_d", qn[i]);
    y[4 + i] = num(st, k2);
  }
  memcpy(yr, y, sizeof y);
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      size_t k = autobal_rotor_ball_index(rot, j, i);
      y[8 + k] = drv[2] + psi[j][i];
      y[8 + N + k] = drv[0] + rate[j][i];
      yr[8 + k] = psi[j][i];
      yr[8 + N + k] = rate[j][i];
    }
  CHECK("fixed-frame rhs", autobal_rotor_rhs(t, y, dy, rot) == GSL_SUCCESS);
  CHECK("rotating-frame rhs", autobal_rotor_rhs_rotating(t, yr, dyr, rot) == GSL_SUCCESS);
  for (i = 0; i < 4; i++) {
    double want = num(acc, qdd[i]);
    snprintf(what, sizeof what, "%s prescribed: %s, fixed frame vs SymPy", which, qdd[i]);
    CHECK_CLOSE(what, dy[4 + i], want, 1e-11, 1e-12);
    snprintf(what, sizeof what, "%s prescribed: %s, rotating frame vs SymPy", which, qdd[i]);
    CHECK_CLOSE(what, dyr[4 + i], want, 1e-11, 1e-12);
  }
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      char key[32];
      size_t k = autobal_rotor_ball_index(rot, j, i);
      double want;
      snprintf(key, sizeof key, "phi_%zu%zu_dd", j + 1, i + 1);
      want = num(acc, key);
      snprintf(what, sizeof what, "%s prescribed: %s, fixed frame vs SymPy", which, key);
      CHECK_CLOSE(what, dy[8 + N + k], want, 1e-11, 1e-9);
      snprintf(what, sizeof what, "%s prescribed: psi'' = %s - Omega', rotating frame vs SymPy", which, key);
      CHECK_CLOSE(what, dyr[8 + N + k], want - Omd, 1e-11, 1e-9);
    }
  autobal_rotor_free(rot);
}

/* The MOTOR drive at the JSON's "motor" block: both frames, phi_0 and Omega in the state. */
static void run_motor_case(const char *json, const char *which, size_t n_planes) {
  const char *blk = after_key(json, which), *st = after_key(blk, "state");
  const char *mot = after_key(blk, "motor"), *acc = after_key(mot, "accelerations");
  autobal_rotor_params p;
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2], y[8 + 8 + 2], dy[8 + 8 + 2], yr[8 + 8 + 2], dyr[8 + 8 + 2];
  double Om, phi0, t = 0.7, E, dE, P, D, L;
  autobal_rotor *rot;
  autobal_error err;
  size_t j, i, N = 2 * n_planes, dim = 8 + 2 * N + 2;
  char what[160];
  static const char *const qdd[4] = {"x_dd", "y_dd", "alpha_dd", "beta_dd"};
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};

  printf("-- %s, MOTOR drive vs SymPy\n", which);
  CHECK("JSON motor blocks found", blk && st && mot && acc);
  if (!(blk && st && mot && acc)) return;
  if (load_params(blk, n_planes, &p, m, r, h, psi, rate) != 0) return;
  Om = num(mot, "Omega"), phi0 = num(st, "phi_0");
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
  p.drive.J = num(mot, "J");
  p.drive.L_0 = num(mot, "L_0");
  p.drive.omega_0 = num(mot, "Omega_0");
  p.drive.k_r = num(mot, "k_r");
  p.drive.omega_start = Om;
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("rotor with a motor drive", rot != NULL);
  if (!rot) {
    printf("     %s\n", err.message);
    return;
  }
  CHECK("dim = 8 + 2N + 2", autobal_rotor_dim(rot) == dim);
  L = autobal_rotor_motor_torque(rot, Om);
  CHECK_CLOSE("L(Omega) = L_0 (1 - Omega/Omega_0) vs the JSON's L", L, num(mot, "L"), 1e-15, 0);
  for (i = 0; i < 4; i++) {
    char k2[16];
    y[i] = num(st, qn[i]);
    snprintf(k2, sizeof k2, "%s_d", qn[i]);
    y[4 + i] = num(st, k2);
  }
  y[dim - 2] = phi0;
  y[dim - 1] = Om;
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      size_t k = autobal_rotor_ball_index(rot, j, i);
      y[8 + k] = phi0 + psi[j][i];
      y[8 + N + k] = Om + rate[j][i];
    }
  /* the rotating-frame state by the library's conversion (the motor's phi_0, Omega from y) */
  CHECK_STATUS("convert to the rotating frame", autobal_rotor_convert_state(rot, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, t, y, yr, dim), AUTOBAL_SUCCESS);
  CHECK_CLOSE("converted psi_1 = psi from the JSON", yr[8], psi[0][0], 1e-15, 1e-15);
  CHECK_CLOSE("converted psi_1' = rate from the JSON", yr[8 + N], rate[0][0], 1e-15, 1e-13);
  CHECK("fixed-frame rhs", autobal_rotor_rhs(t, y, dy, rot) == GSL_SUCCESS);
  CHECK("rotating-frame rhs", autobal_rotor_rhs_rotating(t, yr, dyr, rot) == GSL_SUCCESS);
  for (i = 0; i < 4; i++) {
    double want = num(acc, qdd[i]);
    snprintf(what, sizeof what, "%s motor: %s, fixed frame vs SymPy", which, qdd[i]);
    CHECK_CLOSE(what, dy[4 + i], want, 1e-13, 1e-12);
    snprintf(what, sizeof what, "%s motor: %s, rotating frame vs SymPy", which, qdd[i]);
    CHECK_CLOSE(what, dyr[4 + i], want, 1e-13, 1e-12);
  }
  {
    double want = num(acc, "phi_0_dd");
    snprintf(what, sizeof what, "%s motor: phi_0'' = Omega', fixed frame vs SymPy", which);
    CHECK_CLOSE(what, dy[dim - 1], want, 1e-13, 0);
    snprintf(what, sizeof what, "%s motor: phi_0'' = Omega', rotating frame vs SymPy", which);
    CHECK_CLOSE(what, dyr[dim - 1], want, 1e-13, 0);
    CHECK("phi_0' = Omega (both frames)", dy[dim - 2] == Om && dyr[dim - 2] == Om);
    for (j = 0; j < n_planes; j++)
      for (i = 0; i < 2; i++) {
        char key[32];
        size_t k = autobal_rotor_ball_index(rot, j, i);
        double wb;
        snprintf(key, sizeof key, "phi_%zu%zu_dd", j + 1, i + 1);
        wb = num(acc, key);
        snprintf(what, sizeof what, "%s motor: %s, fixed frame vs SymPy", which, key);
        CHECK_CLOSE(what, dy[8 + N + k], wb, 1e-13, 1e-11);
        snprintf(what, sizeof what, "%s motor: psi'' = %s - Omega', rotating frame vs SymPy", which, key);
        CHECK_CLOSE(what, dyr[8 + N + k], wb - want, 1e-13, 1e-11);
      }
  }
  /* the energies of docs/device.md, coded in the test, against SymPy's; dE/dt along the C
   * right-hand side as the central difference (E(y + e dy) - E(y - e dy)) / (2 e), e = 1e-6:
   * truncation O(e^2) and rounding about 1e-16 E / e = 2e-7 W, hence the tolerance 1e-8 relative */
  E = motor_energy(rot, y);
  snprintf(what, sizeof what, "%s motor: total energy E = T + V vs SymPy", which);
  CHECK_CLOSE(what, E, num(mot, "energy"), 1e-14, 0);
  {
    double yp[8 + 8 + 2], ym[8 + 8 + 2], e = 1e-6;
    for (i = 0; i < dim; i++) {
      yp[i] = y[i] + e * dy[i];
      ym[i] = y[i] - e * dy[i];
    }
    dE = (motor_energy(rot, yp) - motor_energy(rot, ym)) / (2.0 * e);
  }
  P = L * Om;
  D = motor_dissipation(rot, y);
  snprintf(what, sizeof what, "%s motor: motor power L Omega vs SymPy", which);
  CHECK_CLOSE(what, P, num(mot, "motor_power"), 1e-15, 0);
  snprintf(what, sizeof what, "%s motor: dissipation (supports, balls, k_r Omega^2) vs SymPy", which);
  CHECK_CLOSE(what, D, num(mot, "dissipation"), 1e-13, 0);
  snprintf(what, sizeof what, "%s motor: dE/dt along the C rhs (central difference, e = 1e-6) = P - D", which);
  CHECK_CLOSE(what, dE, P - D, 1e-8, 0);
  autobal_rotor_free(rot);
}

/* ---- friction (docs/device.md section 3; keys normal_force, rolling_resistance,
 * stiction_holding).  The friction right-hand sides (law EXACT) at the check state:
 *  NORMAL_*: f = 0 for every ball: the normal forces N_i, without and with gravity (the JSON's
 *    gravity case; gravity enters the friction terms through the test hook of
 *    models/rotor/rotor_internal.h, since the model has no gravity parameter yet);
 *  ROLLING: f = 0.02 for every ball, modes = signs of the check-state relative rates, gravity on:
 *    the accelerations (the 4x4 system is no longer symmetric) and N;
 *  STUCK: ball 11 stuck at its check-state psi (psi' = 0), the other balls frictionless, gravity
 *    on: the constrained accelerations, H_11 and N_11.
 * Prescribed drive (the ramp through the check state, as run_case) and MOTOR (as
 * run_motor_case), both frames. */
enum { F_NORMAL_NOGRAV, F_NORMAL_GRAV, F_ROLLING, F_STUCK };

static void run_friction_case(const char *json, size_t n_planes, int motor, int kind) {
  const char *which = n_planes == 1 ? "one_plane" : "two_planes";
  const char *pk = n_planes == 1 ? "planes1" : "planes2";
  const char *blk = after_key(json, which), *st = after_key(blk, "state");
  const char *drv_blk = after_key(blk, motor ? "motor" : "prescribed");
  const char *sec = NULL, *cas = NULL, *acc = NULL, *nblk = NULL;
  static const char *const kind_name[4] = {"normal force (no gravity)", "normal force (gravity)",
                                           "rolling resistance", "stuck ball 11"};
  static const char *const qdd[4] = {"x_dd", "y_dd", "alpha_dd", "beta_dd"};
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};
  autobal_rotor_params p;
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2], fb[2][2];
  double y[20], dy[20], yr[20], dyr[20], Nf[4], Nr[4], Hf[4], Hr[4];
  double Om, Omd = 0.0, phi0, t = 0.7, gs = 0.0, f = 0.0, drv[3];
  size_t j, i, N = 2 * n_planes, dim = 8 + 2 * N + (motor ? 2u : 0u);
  autobal_rotor *rot;
  autobal_error err;
  char what[200];
  const char *tag = motor ? "motor" : "prescribed";

  printf("-- %s, %s, %s: friction right-hand sides vs SymPy\n", which, tag, kind_name[kind]);
  if (kind == F_NORMAL_NOGRAV || kind == F_NORMAL_GRAV) {
    sec = after_key(json, "normal_force");
    cas = after_key(after_key(after_key(sec, pk), kind == F_NORMAL_GRAV ? "gravity" : "no_gravity"), tag);
    nblk = cas;
  } else {
    sec = after_key(json, kind == F_ROLLING ? "rolling_resistance" : "stiction_holding");
    cas = after_key(after_key(sec, pk), tag);
    acc = after_key(cas, "accelerations");
    nblk = after_key(cas, "N");
  }
  CHECK("JSON friction blocks found", blk && st && drv_blk && sec && cas && nblk);
  if (!(blk && st && drv_blk && sec && cas && nblk)) return;
  if (kind != F_NORMAL_NOGRAV) gs = num(sec, kind == F_NORMAL_GRAV ? "g_s" : "g_s");
  if (kind == F_NORMAL_GRAV) gs = num(after_key(json, "normal_force"), "g_s");
  if (kind == F_ROLLING) f = num(sec, "f");
  if (load_params(blk, n_planes, &p, m, r, h, psi, rate) != 0) return;
  for (j = 0; j < 2; j++)
    for (i = 0; i < 2; i++) fb[j][i] = f;
  p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
  for (j = 0; j < n_planes; j++) {
    p.friction.ball_f[j] = fb[j];
    p.friction.ball_mu[j] = NULL;
  }
  Om = num(drv_blk, "Omega"), phi0 = num(st, "phi_0");
  if (motor) {
    p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
    p.drive.J = num(drv_blk, "J");
    p.drive.L_0 = num(drv_blk, "L_0");
    p.drive.omega_0 = num(drv_blk, "Omega_0");
    p.drive.k_r = num(drv_blk, "k_r");
    p.drive.omega_start = Om;
  } else {
    Omd = num(drv_blk, "Omega_dot");
    t = (Om - sqrt(Om * Om - 2.0 * Omd * phi0)) / Omd;
    p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
    p.drive.t_a = 0.0, p.drive.t_b = 10.0;
    p.drive.omega_a = Om - Omd * t, p.drive.omega_b = p.drive.omega_a + Omd * 10.0;
  }
  p.omega = Om;
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("rotor with friction", rot != NULL);
  if (!rot) {
    printf("     %s\n", err.message);
    return;
  }
  CHECK("gravity inputs set", autobal_rotor_friction_gravity_hook(rot, 0.0, gs) == AUTOBAL_SUCCESS);
  if (motor) {
    drv[0] = Om;
    drv[2] = phi0;
  } else {
    CHECK("drive evaluated", autobal_rotor_drive_eval(rot, t, drv) == AUTOBAL_SUCCESS);
  }
  for (i = 0; i < 4; i++) {
    char k2[16];
    y[i] = num(st, qn[i]);
    snprintf(k2, sizeof k2, "%s_d", qn[i]);
    y[4 + i] = num(st, k2);
  }
  if (motor) {
    y[dim - 2] = phi0;
    y[dim - 1] = Om;
  }
  memcpy(yr, y, sizeof y);
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      size_t k = autobal_rotor_ball_index(rot, j, i);
      double rt = (kind == F_STUCK && k == 0) ? 0.0 : rate[j][i];
      y[8 + k] = drv[2] + psi[j][i];
      y[8 + N + k] = drv[0] + rt;
      yr[8 + k] = psi[j][i];
      yr[8 + N + k] = rt;
    }
  if (kind == F_STUCK)
    CHECK_STATUS("ball 11 set stuck", autobal_rotor_ball_mode_set(rot, 0, AUTOBAL_ROTOR_BALL_STUCK), AUTOBAL_SUCCESS);
  if (kind == F_ROLLING)
    CHECK("modes = signs of the rates", autobal_rotor_ball_mode_get(rot, 0) == 1 &&
                                            autobal_rotor_ball_mode_get(rot, 1) == -1);
  CHECK("fixed-frame rhs", autobal_rotor_rhs(t, y, dy, rot) == GSL_SUCCESS);
  CHECK("rotating-frame rhs", autobal_rotor_rhs_rotating(t, yr, dyr, rot) == GSL_SUCCESS);
  CHECK_STATUS("normal forces, fixed frame", autobal_rotor_normal_forces(rot, AUTOBAL_ROTOR_FIXED, t, y, Nf, N), AUTOBAL_SUCCESS);
  CHECK_STATUS("normal forces, rotating frame", autobal_rotor_normal_forces(rot, AUTOBAL_ROTOR_ROTATING, t, yr, Nr, N), AUTOBAL_SUCCESS);
  CHECK_STATUS("holding forces, fixed frame", autobal_rotor_holding_forces(rot, AUTOBAL_ROTOR_FIXED, t, y, Hf, N), AUTOBAL_SUCCESS);
  CHECK_STATUS("holding forces, rotating frame", autobal_rotor_holding_forces(rot, AUTOBAL_ROTOR_ROTATING, t, yr, Hr, N), AUTOBAL_SUCCESS);
  if (acc) {
    for (i = 0; i < 4; i++) {
      double want = num(acc, qdd[i]);
      snprintf(what, sizeof what, "%s %s %s: %s, fixed frame", which, tag, kind_name[kind], qdd[i]);
      CHECK_CLOSE(what, dy[4 + i], want, 1e-12, 1e-12);
      snprintf(what, sizeof what, "%s %s %s: %s, rotating frame", which, tag, kind_name[kind], qdd[i]);
      CHECK_CLOSE(what, dyr[4 + i], want, 1e-12, 1e-12);
    }
    if (motor) {
      Omd = num(acc, "phi_0_dd");
      snprintf(what, sizeof what, "%s %s %s: phi_0'' = Omega', both frames", which, tag, kind_name[kind]);
      CHECK_CLOSE(what, dy[dim - 1], Omd, 1e-12, 0);
      CHECK_CLOSE(what, dyr[dim - 1], Omd, 1e-12, 0);
    }
  }
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      char key[32];
      size_t k = autobal_rotor_ball_index(rot, j, i);
      snprintf(key, sizeof key, "phi_%zu%zu", j + 1, i + 1);
      if (kind != F_STUCK) {
        snprintf(what, sizeof what, "%s %s %s: N of %s, fixed frame", which, tag, kind_name[kind], key);
        CHECK_CLOSE(what, Nf[k], num(nblk, key), 1e-12, 0);
        snprintf(what, sizeof what, "%s %s %s: N of %s, rotating frame", which, tag, kind_name[kind], key);
        CHECK_CLOSE(what, Nr[k], num(nblk, key), 1e-12, 0);
        CHECK("no holding force for a slipping ball", isnan(Hf[k]) && isnan(Hr[k]));
      }
      if (acc && !(kind == F_STUCK && k == 0)) {
        double want;
        snprintf(key, sizeof key, "phi_%zu%zu_dd", j + 1, i + 1);
        want = num(acc, key);
        snprintf(what, sizeof what, "%s %s %s: %s, fixed frame", which, tag, kind_name[kind], key);
        CHECK_CLOSE(what, dy[8 + N + k], want, 1e-12, 1e-10);
        snprintf(what, sizeof what, "%s %s %s: psi'' = %s - Omega', rotating frame", which, tag, kind_name[kind], key);
        CHECK_CLOSE(what, dyr[8 + N + k], want - Omd, 1e-12, 1e-10);
      }
    }
  if (kind == F_STUCK) {
    snprintf(what, sizeof what, "%s %s: holding force H_11, fixed frame", which, tag);
    CHECK_CLOSE(what, Hf[0], num(cas, "H"), 1e-12, 0);
    snprintf(what, sizeof what, "%s %s: holding force H_11, rotating frame", which, tag);
    CHECK_CLOSE(what, Hr[0], num(cas, "H"), 1e-12, 0);
    snprintf(what, sizeof what, "%s %s: N_11 of the stuck ball, fixed frame", which, tag);
    CHECK_CLOSE(what, Nf[0], num(cas, "N"), 1e-12, 0);
    snprintf(what, sizeof what, "%s %s: N_11 of the stuck ball, rotating frame", which, tag);
    CHECK_CLOSE(what, Nr[0], num(cas, "N"), 1e-12, 0);
    CHECK("stuck ball: psi'' = 0 (rotating), phi'' = Omega' and phi' = Omega (fixed)",
          dyr[8 + N] == 0.0 && dyr[8] == 0.0 && dy[8 + N] == (motor ? dy[dim - 1] : drv[1]) && dy[8] == drv[0]);
    CHECK("the other balls have no holding force", isnan(Hf[1]) && isnan(Hr[1]));
    /* the switching function |H| - mu N: mu = ratio (from the JSON) is the stick limit */
    {
      double ratio = num(cas, "ratio");
      snprintf(what, sizeof what, "%s %s: |H|/N = the JSON's ratio", which, tag);
      CHECK_CLOSE(what, fabs(Hf[0]) / Nf[0], ratio, 1e-12, 0);
    }
  }
  autobal_rotor_free(rot);
}


/* ---- rolling inertia (docs/device.md section 3, "Rolling inertia"; key rolling_inertia: every
 * ball a solid sphere of radius rho, no gravity, no friction).  The accelerations at the check
 * state, prescribed drive and MOTOR, both frames; with the MOTOR the total energy E + T_rot
 * (T_rot = 1/5 m ((r + rho) Omega - r phi')^2, written here from the documented formula) against
 * SymPy's and dE/dt along the C right-hand side against the JSON's dE/dt; with friction too
 * (f = 0.02, law EXACT, modes = the signs of the rates) dE/dt = L Omega - D - sum r f N |psi'|. */
static double rolling_T(const autobal_rotor *rot, const double *y, double rho) {
  const autobal_rotor_params *p = autobal_rotor_get_params(rot);
  const size_t N = autobal_rotor_n_balls_total(rot), dim = autobal_rotor_dim(rot);
  const double W = y[dim - 1];
  double T = 0.0;
  size_t j, i;
  for (j = 0; j < p->n_planes; j++)
    for (i = 0; i < p->plane[j].n_balls; i++) {
      const size_t k = autobal_rotor_ball_index(rot, j, i);
      const double m = p->plane[j].ball_mass[i], r = p->plane[j].ball_radius[i];
      const double w = (r + rho) * W - r * y[8 + N + k];
      T += 0.2 * m * w * w;
    }
  return T;
}

static void run_rolling_case(const char *json, size_t n_planes, int motor, double f) {
  const char *which = n_planes == 1 ? "one_plane" : "two_planes";
  const char *pk = n_planes == 1 ? "planes1" : "planes2";
  const char *tag = motor ? "motor" : "prescribed";
  const char *blk = after_key(json, which), *st = after_key(blk, "state");
  const char *drv_blk = after_key(blk, tag);
  const char *sec = after_key(json, "rolling_inertia");
  const char *cas = after_key(after_key(sec, pk), tag), *acc = after_key(cas, "accelerations");
  static const char *const qdd[4] = {"x_dd", "y_dd", "alpha_dd", "beta_dd"};
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};
  autobal_rotor_params p;
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2], rhob[2][2], fb[2][2];
  double y[20], dy[20], yr[20], dyr[20], Om, Omd = 0.0, phi0, t = 0.7, drv[3], rho;
  size_t j, i, N = 2 * n_planes, dim = 8 + 2 * N + (motor ? 2u : 0u);
  autobal_rotor *rot;
  autobal_error err;
  char what[200];

  printf("-- %s, %s, rolling inertia%s vs SymPy\n", which, tag, f > 0.0 ? " with rolling resistance" : "");
  CHECK("JSON rolling blocks found", blk && st && drv_blk && sec && cas && acc);
  if (!(blk && st && drv_blk && sec && cas && acc)) return;
  rho = num(sec, "rho");
  if (load_params(blk, n_planes, &p, m, r, h, psi, rate) != 0) return;
  for (j = 0; j < 2; j++)
    for (i = 0; i < 2; i++) rhob[j][i] = rho, fb[j][i] = f;
  p.rolling.on = 1;
  for (j = 0; j < n_planes; j++) p.rolling.ball_rho[j] = rhob[j];
  if (f > 0.0) {
    p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT;
    for (j = 0; j < n_planes; j++) p.friction.ball_f[j] = fb[j];
  }
  Om = num(drv_blk, "Omega"), phi0 = num(st, "phi_0");
  if (motor) {
    p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
    p.drive.J = num(drv_blk, "J");
    p.drive.L_0 = num(drv_blk, "L_0");
    p.drive.omega_0 = num(drv_blk, "Omega_0");
    p.drive.k_r = num(drv_blk, "k_r");
    p.drive.omega_start = Om;
  } else {
    Omd = num(drv_blk, "Omega_dot");
    t = (Om - sqrt(Om * Om - 2.0 * Omd * phi0)) / Omd;
    p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
    p.drive.t_a = 0.0, p.drive.t_b = 10.0;
    p.drive.omega_a = Om - Omd * t, p.drive.omega_b = p.drive.omega_a + Omd * 10.0;
  }
  p.omega = Om;
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("rotor with rolling balls", rot != NULL);
  if (!rot) {
    printf("     %s\n", err.message);
    return;
  }
  if (motor) {
    drv[0] = Om;
    drv[2] = phi0;
  } else {
    CHECK("drive evaluated", autobal_rotor_drive_eval(rot, t, drv) == AUTOBAL_SUCCESS);
  }
  for (i = 0; i < 4; i++) {
    char k2[16];
    y[i] = num(st, qn[i]);
    snprintf(k2, sizeof k2, "%s_d", qn[i]);
    y[4 + i] = num(st, k2);
  }
  if (motor) {
    y[dim - 2] = phi0;
    y[dim - 1] = Om;
  }
  memcpy(yr, y, sizeof y);
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      size_t k = autobal_rotor_ball_index(rot, j, i);
      y[8 + k] = drv[2] + psi[j][i];
      y[8 + N + k] = drv[0] + rate[j][i];
      yr[8 + k] = psi[j][i];
      yr[8 + N + k] = rate[j][i];
    }
  CHECK("fixed-frame rhs", autobal_rotor_rhs(t, y, dy, rot) == GSL_SUCCESS);
  CHECK("rotating-frame rhs", autobal_rotor_rhs_rotating(t, yr, dyr, rot) == GSL_SUCCESS);
  if (f == 0.0) {
    for (i = 0; i < 4; i++) {
      double want = num(acc, qdd[i]);
      snprintf(what, sizeof what, "%s %s rolling: %s, fixed frame", which, tag, qdd[i]);
      CHECK_CLOSE(what, dy[4 + i], want, 1e-12, 1e-12);
      snprintf(what, sizeof what, "%s %s rolling: %s, rotating frame", which, tag, qdd[i]);
      CHECK_CLOSE(what, dyr[4 + i], want, 1e-12, 1e-12);
    }
    if (motor) {
      Omd = num(acc, "phi_0_dd");
      snprintf(what, sizeof what, "%s %s rolling: phi_0'' = Omega', fixed and rotating frame", which, tag);
      CHECK_CLOSE(what, dy[dim - 1], Omd, 1e-12, 0);
      CHECK_CLOSE(what, dyr[dim - 1], Omd, 1e-12, 0);
    }
    for (j = 0; j < n_planes; j++)
      for (i = 0; i < 2; i++) {
        char key[32];
        size_t k = autobal_rotor_ball_index(rot, j, i);
        double want;
        snprintf(key, sizeof key, "phi_%zu%zu_dd", j + 1, i + 1);
        want = num(acc, key);
        snprintf(what, sizeof what, "%s %s rolling: %s, fixed frame", which, tag, key);
        CHECK_CLOSE(what, dy[8 + N + k], want, 1e-12, 1e-10);
        snprintf(what, sizeof what, "%s %s rolling: psi'' = %s - Omega', rotating frame", which, tag, key);
        CHECK_CLOSE(what, dyr[8 + N + k], want - Omd, 1e-12, 1e-10);
      }
  } else {
    for (i = 0; i < dim; i++) {
      snprintf(what, sizeof what, "%s %s rolling + friction: row %zu, rotating frame = fixed frame", which, tag, i);
      if (i >= 8 + N && i < 8 + 2 * N) CHECK_CLOSE(what, dyr[i], dy[i] - (motor ? dy[dim - 1] : drv[1]), 1e-12, 1e-9);
      else if (i >= 8 && i < 8 + N) CHECK_CLOSE(what, dyr[i] + (motor ? y[dim - 1] : drv[0]), dy[i], 1e-13, 0);
      else CHECK_CLOSE(what, dyr[i], dy[i], 1e-12, 1e-12);
    }
  }
  if (motor) {
    double E, dE, yp[20], ym[20], e = 1e-6, P, D, Nf[4], Dfr = 0.0;
    E = motor_energy(rot, y) + rolling_T(rot, y, rho);
    if (f == 0.0) {
      snprintf(what, sizeof what, "%s motor rolling: E + T_rot vs SymPy", which);
      CHECK_CLOSE(what, E, num(cas, "energy"), 1e-14, 0);
    }
    for (i = 0; i < dim; i++) {
      yp[i] = y[i] + e * dy[i];
      ym[i] = y[i] - e * dy[i];
    }
    dE = (motor_energy(rot, yp) + rolling_T(rot, yp, rho) - motor_energy(rot, ym) - rolling_T(rot, ym, rho)) / (2.0 * e);
    P = autobal_rotor_motor_torque(rot, Om) * Om;
    D = motor_dissipation(rot, y);
    if (f > 0.0) {
      CHECK_STATUS("normal forces", autobal_rotor_normal_forces(rot, AUTOBAL_ROTOR_FIXED, t, y, Nf, N), AUTOBAL_SUCCESS);
      for (j = 0; j < n_planes; j++)
        for (i = 0; i < 2; i++) {
          size_t k = autobal_rotor_ball_index(rot, j, i);
          Dfr += r[j][i] * f * Nf[k] * fabs(rate[j][i]);
        }
      printf("     friction dissipation sum r f N |psi'| = %.9g W\n", Dfr);
    } else {
      snprintf(what, sizeof what, "%s motor rolling: the JSON's dE/dt = L Omega - D", which);
      CHECK_CLOSE(what, num(cas, "dE_dt"), P - D, 1e-12, 0);
    }
    snprintf(what, sizeof what, "%s motor rolling%s: d(E + T_rot)/dt along the C rhs (central difference) = P - D%s",
             which, f > 0.0 ? " + friction" : "", f > 0.0 ? " - sum r f N |psi'|" : "");
    CHECK_CLOSE(what, dE, P - D - Dfr, 1e-8, 0);
  }
  autobal_rotor_free(rot);
}

/* rho -> 0: the accelerations converge to the rho = 0 rolling values at rate O(rho) (rho enters only
 * the Euler term (1 - 2 rho/(5 r)) Omega' and, with a motor, the spin inertia), and rolling.on = 0
 * with ball_rho set is the point-mass model bit for bit. */
static void run_rolling_limit(const char *json) {
  const char *blk = after_key(json, "one_plane"), *st = after_key(blk, "state");
  const char *mot = after_key(blk, "motor");
  autobal_rotor_params p, p0;
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2], rhob[2] = {0.0, 0.0};
  double y[14], base[14], dy[14], diff[3] = {0.0, 0.0, 0.0};
  const double rhos[3] = {1e-3, 1e-4, 1e-5};
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};
  size_t i, n, dim = 14;
  autobal_rotor *rot;
  char what[160];
  printf("-- rolling inertia: rho -> 0 and the switch\n");
  if (!(blk && st && mot) || load_params(blk, 1, &p0, m, r, h, psi, rate) != 0) {
    CHECK("JSON blocks found", 0);
    return;
  }
  p0.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
  p0.drive.J = num(mot, "J"), p0.drive.L_0 = num(mot, "L_0"), p0.drive.omega_0 = num(mot, "Omega_0");
  p0.drive.k_r = num(mot, "k_r"), p0.drive.omega_start = num(mot, "Omega");
  for (i = 0; i < 4; i++) {
    char k2[16];
    y[i] = num(st, qn[i]);
    snprintf(k2, sizeof k2, "%s_d", qn[i]);
    y[4 + i] = num(st, k2);
  }
  y[8] = 0.3 + psi[0][0], y[9] = 0.3 + psi[0][1], y[10] = 300.0 + rate[0][0], y[11] = 300.0 + rate[0][1];
  y[12] = 0.3, y[13] = 300.0;
  for (n = 0; n <= 3; n++) {
    p = p0;
    p.rolling.on = 1;
    rhob[0] = rhob[1] = n == 0 ? 0.0 : rhos[n - 1];
    p.rolling.ball_rho[0] = rhob;
    rot = autobal_rotor_alloc(&p, NULL);
    CHECK("rolling rotor allocated", rot != NULL);
    if (!rot) return;
    CHECK("rhs", autobal_rotor_rhs(0.0, y, n == 0 ? base : dy, rot) == GSL_SUCCESS);
    if (n > 0)
      for (i = 0; i < dim; i++) diff[n - 1] = fmax(diff[n - 1], fabs(dy[i] - base[i]) / (1.0 + fabs(base[i])));
    autobal_rotor_free(rot);
  }
  printf("     largest scaled difference from rho = 0: %.3e, %.3e, %.3e for rho = 1e-3, 1e-4, 1e-5 m\n", diff[0],
         diff[1], diff[2]);
  CHECK("rho changes the accelerations", diff[2] > 0.0);
  snprintf(what, sizeof what, "rho -> 0 at rate 1: ratios %.6f, %.6f = 10", diff[0] / diff[1], diff[1] / diff[2]);
  CHECK(what, fabs(diff[0] / diff[1] - 10.0) < 0.05 && fabs(diff[1] / diff[2] - 10.0) < 0.005);
  /* the switch off: ball_rho ignored, the point-mass bits */
  {
    double d1[14], d2[14];
    autobal_rotor *a, *b;
    p = p0;
    a = autobal_rotor_alloc(&p, NULL);
    rhob[0] = rhob[1] = 0.0115;
    p.rolling.on = 0;
    p.rolling.ball_rho[0] = rhob;
    b = autobal_rotor_alloc(&p, NULL);
    CHECK("rotors allocated", a && b);
    if (a && b) {
      CHECK("rhs", autobal_rotor_rhs(0.0, y, d1, a) == GSL_SUCCESS && autobal_rotor_rhs(0.0, y, d2, b) == GSL_SUCCESS);
      CHECK("rolling.on = 0: the point-mass right-hand side bit for bit", memcmp(d1, d2, sizeof d1) == 0);
    }
    autobal_rotor_free(a);
    autobal_rotor_free(b);
  }
  /* bad input */
  {
    autobal_error e;
    p = p0;
    p.rolling.on = 1;
    rhob[0] = 0.01, rhob[1] = -1e-3;
    p.rolling.ball_rho[0] = rhob;
    CHECK_STATUS("negative rho refused", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
    CHECK_MSG("the message names plane[0].ball_rho[1]", e.message, "plane[0].ball_rho[1]");
    p.rolling.on = 2;
    CHECK_STATUS("rolling.on = 2 refused", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  }
}


/* A stuck rolling ball (friction EXACT, MOTOR, one plane): ball 11 stuck at its check-state psi with
 * rolling inertia rho: its spin adds 2/5 m rho^2 to the spin inertia, which the energy balance
 * d(E + T_rot)/dt = L Omega - D - r f N |psi'| of the slipping ball checks (T_rot of the stuck ball
 * = 1/5 m rho^2 Omega^2), and its holding force is the documented
 * H = m [r Omega' - u_D'' sin phi + v_D'' cos phi] - 2/5 m rho Omega', evaluated here from the
 * right-hand side's accelerations. */
static void run_rolling_stuck(const char *json) {
  const char *blk = after_key(json, "one_plane"), *st = after_key(blk, "state"), *mot = after_key(blk, "motor");
  const char *sec = after_key(json, "rolling_inertia");
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};
  autobal_rotor_params p;
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2], rhob[2], fb[2] = {0.02, 0.02}, mub[2] = {0.5, 0.5};
  double y[14], dy[14], yp[14], ym[14], Nf[2], Hf[2], rho, Om, phi0, e = 1e-6, dE, P, D, Dfr, Hwant, uDdd, vDdd;
  size_t i, dim = 14;
  autobal_rotor *rot;
  char what[200];
  printf("-- one_plane, motor, rolling inertia with ball 11 stuck\n");
  if (!(blk && st && mot && sec) || load_params(blk, 1, &p, m, r, h, psi, rate) != 0) {
    CHECK("JSON blocks found", 0);
    return;
  }
  rho = num(sec, "rho");
  rhob[0] = rhob[1] = rho;
  p.rolling.on = 1, p.rolling.ball_rho[0] = rhob;
  p.friction.law = AUTOBAL_ROTOR_FRICTION_EXACT, p.friction.ball_f[0] = fb, p.friction.ball_mu[0] = mub;
  Om = num(mot, "Omega"), phi0 = num(st, "phi_0");
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
  p.drive.J = num(mot, "J"), p.drive.L_0 = num(mot, "L_0"), p.drive.omega_0 = num(mot, "Omega_0");
  p.drive.k_r = num(mot, "k_r"), p.drive.omega_start = Om;
  rate[0][0] = 0.0;
  rot = autobal_rotor_alloc(&p, NULL);
  CHECK("rotor", rot != NULL);
  if (!rot) return;
  for (i = 0; i < 4; i++) {
    char k2[16];
    y[i] = num(st, qn[i]);
    snprintf(k2, sizeof k2, "%s_d", qn[i]);
    y[4 + i] = num(st, k2);
  }
  y[8] = phi0 + psi[0][0], y[9] = phi0 + psi[0][1], y[10] = Om, y[11] = Om + rate[0][1], y[12] = phi0, y[13] = Om;
  CHECK_STATUS("ball 11 set stuck", autobal_rotor_ball_mode_set(rot, 0, AUTOBAL_ROTOR_BALL_STUCK), AUTOBAL_SUCCESS);
  CHECK("rhs", autobal_rotor_rhs(0.7, y, dy, rot) == GSL_SUCCESS);
  CHECK_STATUS("normal forces", autobal_rotor_normal_forces(rot, AUTOBAL_ROTOR_FIXED, 0.7, y, Nf, 2), AUTOBAL_SUCCESS);
  CHECK_STATUS("holding forces", autobal_rotor_holding_forces(rot, AUTOBAL_ROTOR_FIXED, 0.7, y, Hf, 2), AUTOBAL_SUCCESS);
  for (i = 0; i < dim; i++) {
    yp[i] = y[i] + e * dy[i];
    ym[i] = y[i] - e * dy[i];
  }
  dE = (motor_energy(rot, yp) + rolling_T(rot, yp, rho) - motor_energy(rot, ym) - rolling_T(rot, ym, rho)) / (2.0 * e);
  P = autobal_rotor_motor_torque(rot, Om) * Om;
  D = motor_dissipation(rot, y);
  Dfr = r[0][1] * fb[1] * Nf[1] * fabs(rate[0][1]);
  snprintf(what, sizeof what, "stuck rolling ball: d(E + T_rot)/dt = L Omega - D - r f N |psi'| (%.6f W of friction)", Dfr);
  CHECK_CLOSE(what, dE, P - D - Dfr, 1e-8, 0);
  uDdd = dy[4] + p.plane[0].d * dy[7];
  vDdd = dy[5] - p.plane[0].d * dy[6];
  Hwant = m[0][0] * (r[0][0] * dy[13] - uDdd * sin(y[8]) + vDdd * cos(y[8])) - 0.4 * m[0][0] * rho * dy[13];
  CHECK_CLOSE("stuck rolling ball: H = m [r Omega' - u_D'' sin + v_D'' cos] - 2/5 m rho Omega'", Hf[0], Hwant, 1e-12, 1e-14);
  CHECK("stuck: phi' = Omega, phi'' = Omega'", dy[8] == Om && dy[10] == dy[13]);
  autobal_rotor_free(rot);
}

int main(void) {
  char *json;
  gsl_set_error_handler_off();
  json = slurp(JSON_PATH);
  CHECK("tools/derive/check_values.json read", json != NULL);
  if (!json) return 1;
  run_case(json, "one_plane", 1);
  run_case(json, "two_planes", 2);
  run_motor_case(json, "one_plane", 1);
  run_motor_case(json, "two_planes", 2);
  {
    int kind, motor;
    size_t np;
    for (np = 1; np <= 2; np++)
      for (motor = 0; motor <= 1; motor++)
        for (kind = F_NORMAL_NOGRAV; kind <= F_STUCK; kind++) run_friction_case(json, np, motor, kind);
    for (np = 1; np <= 2; np++)
      for (motor = 0; motor <= 1; motor++) {
        run_rolling_case(json, np, motor, 0.0);
        run_rolling_case(json, np, motor, 0.02);
      }
    run_rolling_limit(json);
    run_rolling_stuck(json);
  }
  free(json);
  printf("%d checks, %d failed\n", check_count_, check_failures_);
  return check_failures_ ? 1 : 0;
}
