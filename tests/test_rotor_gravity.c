/* test_rotor_gravity.c: gravity in the rotor right-hand sides (autobal_rotor_params.gravity,
 * shaft_angle, g; src/models/rotor/rotor.c) against the independent SymPy derivation
 * (tools/derive/derive_device.py, docs/device.md section 2; values in tools/derive/check_values.json,
 * key "gravity", which test_derive keeps equal to what the script computes and to a NumPy solve):
 *  1. the accelerations with gravity (shaft angle 1.2 rad) and a prescribed ramp, both frames, one and
 *     two planes, at the derivation's check state (every parameter and state value read from the JSON);
 *  2. shaft angle 0 (vertical shaft) gives the same bits as gravity off;
 *  3. the first-order 1X response of the balanced state of the default rotor on a horizontal shaft
 *     (JSON gravity.perturbation, a harmonic balance of the linearized equations): a transient from
 *     the first-order state, both frames; the 1X coefficients of psi - psi* over revolutions 10-20
 *     equal the closed form within 2 eps^2 and the mean stays below 20 eps^2 (eps = g/(r Omega^2));
 *  4. bad gravity parameters are rejected with the parameter's name;
 *  5. a MOTOR drive with gravity (the unbalance's weight torque on phi_0): the accelerations, phi_0''
 *     included, the energy E = T + V + V_g and dE/dt = motor power - dissipation at the check state
 *     (JSON gravity.planes1/planes2.motor, both frames, one and two planes); a vertical shaft gives
 *     the bits of gravity off; the power balance E(T) - E(0) = work of the motor - dissipation along
 *     a run-up from rest on a horizontal shaft (E with the weights' potential energy V_g);
 *  6. the static offset (autobal_rotor_static_offset) against the JSON's closed form and against
 *     the rest state of a transient at omega = 0 (unbalance and balls at the bottom), where the
 *     output amplitudes (measured from the static offset) vanish. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/rotor.h"
#include "autobal/transient.h"
#include "check.h"
#include "check_json.h"
#include "rotor_energy.h"
#include "rotor_integrate.h"

#define JSON_PATH AUTOBAL_TEST_DATA_DIR "/../tools/derive/check_values.json"
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif


typedef struct ball_data {
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2];
} ball_data;

/* Rotor parameters of the JSON block `which` (one_plane / two_planes). */
static int read_params(const char *json, const char *which, size_t n_planes, autobal_rotor_params *p, ball_data *bd) {
  const char *blk = after_key(json, which), *par = after_key(blk, "parameters"), *pl = after_key(blk, "planes");
  const char *plane_at[2];
  size_t j;
  if (!(blk && par && pl)) return -1;
  *p = autobal_rotor_params_default();
  p->input = AUTOBAL_ROTOR_HARDWARE;
  p->hw.M_k = num(par, "M_k"), p->hw.A_k = num(par, "A_k"), p->hw.m_p = num(par, "m_p");
  p->hw.A_p = num(par, "A_p"), p->hw.C_p = num(par, "C_p");
  p->hw.l_L = num(par, "l_L"), p->hw.l_R = num(par, "l_R");
  p->hw.c_Lx = num(par, "c_Lx"), p->hw.c_Ly = num(par, "c_Ly"), p->hw.c_Rx = num(par, "c_Rx"), p->hw.c_Ry = num(par, "c_Ry");
  p->hw.h_Lx = num(par, "h_Lx"), p->hw.h_Ly = num(par, "h_Ly"), p->hw.h_Rx = num(par, "h_Rx"), p->hw.h_Ry = num(par, "h_Ry");
  p->n_planes = n_planes;
  plane_at[0] = strchr(pl, '{');
  plane_at[1] = plane_at[0] ? strchr(strchr(plane_at[0], '}') + 1, '{') : NULL;
  for (j = 0; j < n_planes; j++) {
    const char *q = plane_at[j];
    autobal_rotor_plane *P = &p->plane[j];
    if (!q) return -1;
    P->d = num(q, "d"), P->m0 = num(q, "m0"), P->r0 = num(q, "r0"), P->psi0 = num(q, "psi0");
    P->n_balls = arr(q, "m", bd->m[j], 2);
    if (P->n_balls != 2 || arr(q, "r", bd->r[j], 2) != 2 || arr(q, "h", bd->h[j], 2) != 2 ||
        arr(q, "psi", bd->psi[j], 2) != 2 || arr(q, "rate", bd->rate[j], 2) != 2)
      return -1;
    P->ball_mass = bd->m[j], P->ball_radius = bd->r[j], P->ball_damping = bd->h[j];
    P->ball_psi = bd->psi[j], P->ball_rate = bd->rate[j];
  }
  return 0;
}

/* 1 and 2: the check state with a ramp through (Omega, Omega', phi_0) (as test_rotor_derive.c). */
static void accelerations_case(const char *json, const char *which, const char *gkey, size_t n_planes) {
  const char *blk = after_key(json, which), *st = after_key(blk, "state"), *pre = after_key(blk, "prescribed");
  const char *grav = after_key(json, "gravity"), *gpl = after_key(grav, gkey);
  const char *acc = after_key(after_key(gpl, "prescribed"), "accelerations");
  /* the gravity block's own "theta" follows its "planes2" entry (the perturbation has one too) */
  const double g = num(grav, "g"), theta = num(after_key(grav, "planes2"), "theta");
  static const char *const qdd[4] = {"x_dd", "y_dd", "alpha_dd", "beta_dd"};
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};
  autobal_rotor_params p;
  ball_data bd;
  autobal_rotor *rot, *rot0, *rotv;
  autobal_error err;
  double y[16], dy[16], yr[16], dyr[16], d0[16], d0r[16], dv[16], dvr[16], Om, Omd, phi0, t, drv[3];
  size_t j, i, N = 2 * n_planes;
  char what[200];

  CHECK("JSON blocks found", blk && st && pre && grav && gpl && acc && read_params(json, which, n_planes, &p, &bd) == 0);
  if (!(blk && st && pre && grav && gpl && acc)) return;
  CHECK_CLOSE("JSON: g_s = g sin(theta)", g * sin(theta), num(grav, "g_s"), 1e-15, 0);
  Om = num(pre, "Omega"), Omd = num(pre, "Omega_dot"), phi0 = num(st, "phi_0");
  t = (Om - sqrt(Om * Om - 2.0 * Omd * phi0)) / Omd;
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
  p.drive.t_a = 0.0, p.drive.t_b = 10.0;
  p.drive.omega_a = Om - Omd * t, p.drive.omega_b = p.drive.omega_a + Omd * 10.0;
  p.omega = Om;
  rot0 = autobal_rotor_alloc(&p, &err); /* gravity off */
  p.gravity = 1, p.shaft_angle = 0.0, p.g = g;
  rotv = autobal_rotor_alloc(&p, &err); /* vertical shaft */
  p.shaft_angle = theta;
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("rotors with gravity off, vertical, tilted", rot && rot0 && rotv);
  if (!(rot && rot0 && rotv)) {
    autobal_rotor_free(rot), autobal_rotor_free(rot0), autobal_rotor_free(rotv);
    return;
  }
  CHECK("drive evaluated", autobal_rotor_drive_eval(rot, t, drv) == AUTOBAL_SUCCESS);
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
      y[8 + k] = drv[2] + bd.psi[j][i];
      y[8 + N + k] = drv[0] + bd.rate[j][i];
      yr[8 + k] = bd.psi[j][i];
      yr[8 + N + k] = bd.rate[j][i];
    }
  CHECK("fixed-frame rhs", autobal_rotor_rhs(t, y, dy, rot) == GSL_SUCCESS);
  CHECK("rotating-frame rhs", autobal_rotor_rhs_rotating(t, yr, dyr, rot) == GSL_SUCCESS);
  for (i = 0; i < 4; i++) {
    double want = num(acc, qdd[i]);
    snprintf(what, sizeof what, "%s, gravity (theta %g): %s, fixed frame vs SymPy", which, theta, qdd[i]);
    CHECK_CLOSE(what, dy[4 + i], want, 1e-11, 1e-12);
    snprintf(what, sizeof what, "%s, gravity (theta %g): %s, rotating frame vs SymPy", which, theta, qdd[i]);
    CHECK_CLOSE(what, dyr[4 + i], want, 1e-11, 1e-12);
  }
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      char key[32];
      size_t k = autobal_rotor_ball_index(rot, j, i);
      double want;
      snprintf(key, sizeof key, "phi_%zu%zu_dd", j + 1, i + 1);
      want = num(acc, key);
      snprintf(what, sizeof what, "%s, gravity: %s, fixed frame vs SymPy", which, key);
      CHECK_CLOSE(what, dy[8 + N + k], want, 1e-11, 1e-9);
      snprintf(what, sizeof what, "%s, gravity: psi'' = %s - Omega', rotating frame vs SymPy", which, key);
      CHECK_CLOSE(what, dyr[8 + N + k], want - Omd, 1e-11, 1e-9);
    }
  /* 2: a vertical shaft is the model without gravity, bit for bit */
  CHECK("rhs, gravity off", autobal_rotor_rhs(t, y, d0, rot0) == GSL_SUCCESS &&
                                autobal_rotor_rhs_rotating(t, yr, d0r, rot0) == GSL_SUCCESS);
  CHECK("rhs, vertical shaft", autobal_rotor_rhs(t, y, dv, rotv) == GSL_SUCCESS &&
                                   autobal_rotor_rhs_rotating(t, yr, dvr, rotv) == GSL_SUCCESS);
  snprintf(what, sizeof what, "%s: shaft_angle = 0 gives the bits of gravity off (both frames)", which);
  CHECK(what, memcmp(d0, dv, (8 + 2 * N) * sizeof(double)) == 0 && memcmp(d0r, dvr, (8 + 2 * N) * sizeof(double)) == 0);
  snprintf(what, sizeof what, "%s: gravity changes y'' (by %.6g m/s^2)", which, dy[5] - d0[5]);
  CHECK(what, fabs(dy[5] - d0[5]) > 1.0);
  autobal_rotor_free(rot);
  autobal_rotor_free(rot0);
  autobal_rotor_free(rotv);
}

/* least-squares fit of v(t) = c0 + c1 cos(W t) + c2 sin(W t) over n samples (normal equations) */
static void fit1x(const double *tt, const double *v, size_t n, double W, double c[3]) {
  double A[3][4] = {{0}};
  size_t k, a, b;
  for (k = 0; k < n; k++) {
    const double f[3] = {1.0, cos(W * tt[k]), sin(W * tt[k])};
    for (a = 0; a < 3; a++) {
      for (b = 0; b < 3; b++) A[a][b] += f[a] * f[b];
      A[a][3] += f[a] * v[k];
    }
  }
  for (a = 0; a < 3; a++) /* Gauss-Jordan, the matrix is well conditioned (about n/2 I) */
    for (b = 0; b < 3; b++)
      if (b != a) {
        const double f = A[b][a] / A[a][a];
        for (k = 0; k < 4; k++) A[b][k] -= f * A[a][k];
      }
  for (a = 0; a < 3; a++) c[a] = A[a][3] / A[a][a];
}

#define NS 401

/* 3: the first-order response of the balanced state to gravity */
static void perturbation_case(const char *json, int rotating) {
  const char *pt = after_key(after_key(json, "gravity"), "perturbation");
  autobal_rotor_params p;
  ball_data bd;
  autobal_rotor *rot;
  autobal_error err;
  double W, gs, eps, pstar[2], pc[2], ps[2], so[4], qc[4], qs[4], y[12], T, t0, tt[NS], v[2][NS];
  size_t i, k, n;
  int ok = 1;
  char what[200];

  CHECK("perturbation block", pt && read_params(json, "one_plane", 1, &p, &bd) == 0);
  if (!pt) return;
  W = num(pt, "Omega"), gs = num(pt, "g_s"), eps = num(pt, "eps");
  n = arr(pt, "psi_star", pstar, 2) + arr(pt, "psi_cos", pc, 2) + arr(pt, "psi_sin", ps, 2) +
      arr(pt, "static_offset", so, 4) + arr(pt, "q_cos2", qc, 4) + arr(pt, "q_sin2", qs, 4);
  CHECK("perturbation values read", n == 18);
  p.omega = W; /* constant speed: phi_0 = W t */
  p.gravity = 1, p.shaft_angle = num(pt, "theta"), p.g = gs;
  CHECK_CLOSE("horizontal shaft", p.shaft_angle, M_PI / 2, 1e-15, 0);
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("rotor for the perturbation", rot != NULL);
  if (!rot) return;
  for (k = 0; k < 4; k++) y[k] = so[k] + qc[k], y[4 + k] = 2.0 * W * qs[k];
  for (i = 0; i < 2; i++) {
    size_t b = autobal_rotor_ball_index(rot, 0, i);
    y[8 + b] = pstar[i] + pc[i];                       /* phi = psi at t = 0 */
    y[10 + b] = (rotating ? 0.0 : W) + W * ps[i];
  }
  T = 2.0 * M_PI / W;
  ok = integrate(rotating ? autobal_rotor_rhs_rotating : autobal_rotor_rhs, rot, 0.0, 10.0 * T, y, 1e-12, 1e-14) == 0;
  t0 = 10.0 * T;
  for (k = 0; k < NS && ok; k++) {
    const double t1 = 10.0 * T + 10.0 * T * (double)k / (NS - 1);
    if (k > 0) ok = integrate(rotating ? autobal_rotor_rhs_rotating : autobal_rotor_rhs, rot, t0, t1, y, 1e-12, 1e-14) == 0;
    t0 = t1;
    tt[k] = t1;
    for (i = 0; i < 2; i++) {
      size_t b = autobal_rotor_ball_index(rot, 0, i);
      v[i][k] = y[8 + b] - (rotating ? 0.0 : W * t1) - pstar[i];
    }
  }
  snprintf(what, sizeof what, "perturbation transient (%s frame, 20 revolutions)", rotating ? "rotating" : "fixed");
  CHECK(what, ok);
  for (i = 0; ok && i < 2; i++) {
    double c[3];
    fit1x(tt, v[i], NS, W, c);
    snprintf(what, sizeof what, "%s frame, ball %zu: 1X cos coefficient of psi - psi* vs first-order closed form "
             "(2 eps^2)", rotating ? "rotating" : "fixed", i + 1);
    CHECK_CLOSE(what, c[1], pc[i], 0, 2.0 * eps * eps);
    snprintf(what, sizeof what, "%s frame, ball %zu: 1X sin coefficient vs closed form (2 eps^2)",
             rotating ? "rotating" : "fixed", i + 1);
    CHECK_CLOSE(what, c[2], ps[i], 0, 2.0 * eps * eps);
    snprintf(what, sizeof what, "%s frame, ball %zu: mean shift %.3g rad below 20 eps^2 = %.3g rad",
             rotating ? "rotating" : "fixed", i + 1, c[0], 20.0 * eps * eps);
    CHECK(what, fabs(c[0]) < 20.0 * eps * eps);
  }
  autobal_rotor_free(rot);
}

static void bad_input(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor *r;
  autobal_error err;
  CHECK_CLOSE("default g", p.g, 9.80665, 0, 0);
  CHECK("gravity off by default", p.gravity == 0);
  p.gravity = 2;
  r = autobal_rotor_alloc(&p, &err);
  CHECK("gravity = 2 rejected, message names it", r == NULL && strstr(err.message, "gravity = 2") != NULL);
  autobal_rotor_free(r);
  p.gravity = 1, p.shaft_angle = 4.0;
  r = autobal_rotor_alloc(&p, &err);
  CHECK("shaft_angle = 4 rad rejected, message names it", r == NULL && strstr(err.message, "shaft_angle") != NULL);
  autobal_rotor_free(r);
  p.shaft_angle = 1.0, p.g = 0.0;
  r = autobal_rotor_alloc(&p, &err);
  CHECK("g = 0 rejected, message names it", r == NULL && strstr(err.message, "parameter g =") != NULL);
  autobal_rotor_free(r);
  p.g = NAN;
  r = autobal_rotor_alloc(&p, &err);
  CHECK("g = nan rejected", r == NULL);
  autobal_rotor_free(r);
  { /* supports that cannot carry the weight (c_y = c_yalpha = 0): no static equilibrium */
    autobal_rotor_params q = autobal_rotor_params_default();
    q.input = AUTOBAL_ROTOR_LUMPED;
    q.lumped.c_y = 0.0, q.lumped.c_yalpha = 0.0, q.lumped.h_yalpha = 0.0;
    r = autobal_rotor_alloc(&q, &err);
    CHECK("c_y = 0 without gravity: allowed", r != NULL);
    autobal_rotor_free(r);
    q.gravity = 1, q.shaft_angle = M_PI / 2, q.g = 9.81;
    r = autobal_rotor_alloc(&q, &err);
    CHECK("c_y = 0 with a horizontal shaft: rejected, 'carry the weight'",
          r == NULL && strstr(err.message, "carry the weight") != NULL);
    autobal_rotor_free(r);
    q.shaft_angle = 0.0;
    r = autobal_rotor_alloc(&q, &err);
    CHECK("c_y = 0 with a vertical shaft: allowed (no weight in the plane)", r != NULL);
    if (r) {
      double y0[16], out[64];
      const size_t no = autobal_rotor_output_count(r);
      autobal_rotor_initial_state(r, AUTOBAL_ROTOR_FIXED, 0.0, y0, autobal_rotor_dim(r));
      CHECK("   its amplitudes are finite (no static offset to subtract)",
            no <= 64 && autobal_rotor_outputs(r, AUTOBAL_ROTOR_FIXED, 0.0, y0, out, no) == AUTOBAL_SUCCESS &&
                out[0] == 0.0 && out[1] == 0.0 && out[2] == 0.0);
    }
    autobal_rotor_free(r);
  }
  p.gravity = 0; /* off: the other fields are not looked at */
  r = autobal_rotor_alloc(&p, &err);
  CHECK("gravity off ignores g and shaft_angle", r != NULL);
  autobal_rotor_free(r);
}

/* V_g of docs/device.md section 2 (J): g_s [M y + sum_j sum_{i >= 0} m_ji (v_jD + r_ji sin phi_ji)],
 * v_jD = y - d_j alpha, i = 0 the unbalance at phi_0 + psi_j0; the state in the FIXED frame with
 * phi_0, Omega last (tests/rotor_energy.h). */
static double gravity_energy(const autobal_rotor *r, const double *y, double gs) {
  const autobal_rotor_params *p = autobal_rotor_get_params(r);
  const autobal_rotor_lumped *L = autobal_rotor_get_lumped(r);
  const size_t N = autobal_rotor_n_balls_total(r), dim = autobal_rotor_dim(r);
  double V = L->M * y[1];
  size_t j, i;
  for (j = 0; j < p->n_planes; j++) {
    const autobal_rotor_plane *P = &p->plane[j];
    const double vD = y[1] - P->d * y[2];
    V += P->m0 * (vD + P->r0 * sin(y[dim - 2] + P->psi0));
    for (i = 0; i < P->n_balls; i++) {
      const size_t k = autobal_rotor_ball_index(r, j, i);
      V += P->ball_mass[i] * (vD + P->ball_radius[i] * sin(y[8 + k]));
    }
  }
  (void)N;
  return gs * V;
}

/* 5: the MOTOR drive with gravity at the check state (JSON one_plane/two_planes "motor" block for
 * the motor, gravity.planesN.motor for the values). */
static void motor_case(const char *json, const char *which, const char *gkey, size_t n_planes) {
  const char *blk = after_key(json, which), *st = after_key(blk, "state"), *mot = after_key(blk, "motor");
  const char *grav = after_key(json, "gravity"), *gm = after_key(after_key(grav, gkey), "motor");
  const char *acc = after_key(gm, "accelerations");
  const double g = num(grav, "g"), theta = num(after_key(grav, "planes2"), "theta"), gs = num(grav, "g_s");
  static const char *const qdd[4] = {"x_dd", "y_dd", "alpha_dd", "beta_dd"};
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};
  autobal_rotor_params p;
  ball_data bd;
  autobal_rotor *rot, *rot0, *rotv;
  autobal_error err;
  double y[18], dy[18], yr[18], dyr[18], d0[18], d0r[18], dv[18], dvr[18], Om, phi0, t = 0.7, E, dE, P, D;
  size_t j, i, N = 2 * n_planes, dim = 8 + 2 * N + 2;
  char what[200];

  printf("-- %s, MOTOR drive with gravity (theta %g) vs SymPy\n", which, theta);
  CHECK("JSON motor blocks found", blk && st && mot && gm && acc && read_params(json, which, n_planes, &p, &bd) == 0);
  if (!(blk && st && mot && gm && acc)) return;
  Om = num(mot, "Omega"), phi0 = num(st, "phi_0");
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
  p.drive.J = num(mot, "J"), p.drive.L_0 = num(mot, "L_0"), p.drive.omega_0 = num(mot, "Omega_0");
  p.drive.k_r = num(mot, "k_r"), p.drive.omega_start = Om;
  rot0 = autobal_rotor_alloc(&p, &err); /* gravity off */
  p.gravity = 1, p.shaft_angle = 0.0, p.g = g;
  rotv = autobal_rotor_alloc(&p, &err); /* vertical shaft */
  p.shaft_angle = theta;
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("motor rotors with gravity off, vertical, tilted (no longer refused)", rot && rot0 && rotv);
  if (!(rot && rot0 && rotv)) {
    printf("     %s\n", err.message);
    autobal_rotor_free(rot), autobal_rotor_free(rot0), autobal_rotor_free(rotv);
    return;
  }
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
      y[8 + k] = phi0 + bd.psi[j][i];
      y[8 + N + k] = Om + bd.rate[j][i];
    }
  CHECK_STATUS("convert to the rotating frame",
               autobal_rotor_convert_state(rot, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, t, y, yr, dim), AUTOBAL_SUCCESS);
  CHECK("fixed-frame rhs", autobal_rotor_rhs(t, y, dy, rot) == GSL_SUCCESS);
  CHECK("rotating-frame rhs", autobal_rotor_rhs_rotating(t, yr, dyr, rot) == GSL_SUCCESS);
  for (i = 0; i < 4; i++) {
    double want = num(acc, qdd[i]);
    snprintf(what, sizeof what, "%s motor + gravity: %s, fixed frame vs SymPy", which, qdd[i]);
    CHECK_CLOSE(what, dy[4 + i], want, 1e-12, 1e-12);
    snprintf(what, sizeof what, "%s motor + gravity: %s, rotating frame vs SymPy", which, qdd[i]);
    CHECK_CLOSE(what, dyr[4 + i], want, 1e-12, 1e-12);
  }
  {
    const double want = num(acc, "phi_0_dd"), want0 = num(after_key(mot, "accelerations"), "phi_0_dd");
    snprintf(what, sizeof what, "%s motor + gravity: phi_0'' = Omega', fixed frame vs SymPy", which);
    CHECK_CLOSE(what, dy[dim - 1], want, 1e-13, 0);
    snprintf(what, sizeof what, "%s motor + gravity: phi_0'' = Omega', rotating frame vs SymPy", which);
    CHECK_CLOSE(what, dyr[dim - 1], want, 1e-13, 0);
    snprintf(what, sizeof what, "%s: gravity changes phi_0'' (%.9g -> %.9g rad/s^2: the weight torque is in)", which,
             want0, want);
    CHECK(what, fabs(want - want0) > 1e-3 && fabs(dy[dim - 1] - want0) > 1e-3);
    for (j = 0; j < n_planes; j++)
      for (i = 0; i < 2; i++) {
        char key[32];
        size_t k = autobal_rotor_ball_index(rot, j, i);
        double wb;
        snprintf(key, sizeof key, "phi_%zu%zu_dd", j + 1, i + 1);
        wb = num(acc, key);
        snprintf(what, sizeof what, "%s motor + gravity: %s, fixed frame vs SymPy", which, key);
        CHECK_CLOSE(what, dy[8 + N + k], wb, 1e-12, 1e-11);
        snprintf(what, sizeof what, "%s motor + gravity: psi'' = %s - Omega', rotating frame vs SymPy", which, key);
        CHECK_CLOSE(what, dyr[8 + N + k], wb - want, 1e-12, 1e-11);
      }
  }
  /* E = T + V + V_g against SymPy's, dE/dt along the C rhs (central difference) = P - D */
  E = motor_energy(rot, y) + gravity_energy(rot, y, gs);
  snprintf(what, sizeof what, "%s motor + gravity: E = T + V + V_g vs SymPy", which);
  CHECK_CLOSE(what, E, num(gm, "energy"), 1e-14, 0);
  {
    double yp[18], ym[18], e = 1e-6;
    for (i = 0; i < dim; i++) yp[i] = y[i] + e * dy[i], ym[i] = y[i] - e * dy[i];
    dE = (motor_energy(rot, yp) + gravity_energy(rot, yp, gs) - motor_energy(rot, ym) - gravity_energy(rot, ym, gs)) /
         (2.0 * e);
  }
  P = autobal_rotor_motor_torque(rot, Om) * Om;
  D = motor_dissipation(rot, y);
  snprintf(what, sizeof what, "%s motor + gravity: dE/dt along the C rhs = P - D (SymPy's dE_dt %.9g W)", which,
           num(gm, "dE_dt"));
  CHECK_CLOSE(what, dE, P - D, 1e-8, 0);
  CHECK_CLOSE("   P - D vs SymPy's dE_dt", P - D, num(gm, "dE_dt"), 1e-12, 0);
  /* a vertical shaft: the bits of gravity off */
  CHECK("rhs, gravity off", autobal_rotor_rhs(t, y, d0, rot0) == GSL_SUCCESS &&
                                autobal_rotor_rhs_rotating(t, yr, d0r, rot0) == GSL_SUCCESS);
  CHECK("rhs, vertical shaft", autobal_rotor_rhs(t, y, dv, rotv) == GSL_SUCCESS &&
                                   autobal_rotor_rhs_rotating(t, yr, dvr, rotv) == GSL_SUCCESS);
  snprintf(what, sizeof what, "%s motor: shaft_angle = 0 gives the bits of gravity off (both frames)", which);
  CHECK(what, memcmp(d0, dv, dim * sizeof(double)) == 0 && memcmp(d0r, dvr, dim * sizeof(double)) == 0);
  autobal_rotor_free(rot);
  autobal_rotor_free(rot0);
  autobal_rotor_free(rotv);
}

/* The state with the work done on the system appended: W' = L(Omega) Omega - dissipation. */
typedef struct work_ctx {
  autobal_rotor *R;
  int frame;
} work_ctx;

static int work_rhs(double t, const double y[], double dydt[], void *user) {
  work_ctx *c = user;
  const size_t dim = autobal_rotor_dim(c->R);
  double yf[32];
  int st = (c->frame == AUTOBAL_ROTOR_FIXED ? autobal_rotor_rhs : autobal_rotor_rhs_rotating)(t, y, dydt, c->R);
  if (st) return st;
  autobal_rotor_convert_state(c->R, c->frame, AUTOBAL_ROTOR_FIXED, t, y, yf, dim);
  dydt[dim] = autobal_rotor_motor_torque(c->R, yf[dim - 1]) * yf[dim - 1] - motor_dissipation(c->R, yf);
  return 0;
}

/* 5: power balance along a motor run-up from rest on a horizontal shaft: E(T) - E(0) = work - dissipation
 * with E = T + V + V_g.  The unbalance's weight torque (up to m0 r0 g = 0.0196 N m) does work up to
 * 2 m0 r0 g = 0.039 J per half turn: with it left out of the phi_0 equation this balance misses by
 * 1.2e-5 of E(T) (measured), 1e7 times the tolerance. */
static void motor_power_balance(void) {
  int fr, it;
  printf("-- motor + gravity: power balance along a run-up from rest, horizontal shaft\n");
  for (fr = 0; fr < 2; fr++) {
    double err_tol[2] = {0.0, 0.0};
    for (it = 0; it < 2; it++) {
      autobal_rotor_params p = autobal_rotor_params_default();
      autobal_transient_options opt = autobal_transient_options_default();
      autobal_transient_system sys;
      autobal_transient *tr;
      work_ctx w;
      double y[32], yf[32], E0, E1, Win, gs;
      const double T = 1.0, rtol = it == 0 ? 1e-9 : 1e-12;
      size_t dim;
      int st;
      p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
      p.drive.J = 0.05, p.drive.L_0 = 14.0, p.drive.omega_0 = 400.0, p.drive.k_r = 2e-3, p.drive.omega_start = 0.0;
      p.gravity = 1, p.shaft_angle = M_PI / 2, p.g = 9.80665;
      p.plane[0].psi0 = 0.4; /* the unbalance off the horizontal at the start: its weight torque is not 0 */
      gs = p.g * sin(p.shaft_angle);
      w.R = autobal_rotor_alloc(&p, NULL);
      w.frame = fr;
      CHECK("motor + gravity handle", w.R != NULL);
      if (!w.R) return;
      dim = autobal_rotor_dim(w.R);
      autobal_rotor_initial_state(w.R, fr, 0.0, y, dim);
      y[dim] = 0.0;
      autobal_rotor_convert_state(w.R, fr, AUTOBAL_ROTOR_FIXED, 0.0, y, yf, dim);
      E0 = motor_energy(w.R, yf) + gravity_energy(w.R, yf, gs);
      opt.stepper = "rk8pd", opt.rtol = rtol, opt.atol = rtol * 1e-3, opt.h_init = 1e-5, opt.max_steps = 50000000ul;
      sys.rhs = work_rhs, sys.jac = NULL, sys.dim = dim + 1, sys.params = &w;
      tr = autobal_transient_alloc(sys.dim, &opt, NULL);
      st = tr ? autobal_transient_run(tr, &sys, 0.0, T, y, NULL) : -1;
      autobal_transient_free(tr);
      CHECK("integration", st == 0);
      autobal_rotor_convert_state(w.R, fr, AUTOBAL_ROTOR_FIXED, T, y, yf, dim);
      E1 = motor_energy(w.R, yf) + gravity_energy(w.R, yf, gs);
      Win = y[dim];
      err_tol[it] = fabs(E1 - E0 - Win) / E1;
      printf("     %s frame, rtol %.0e: Omega(T) = %.6g rad/s, E(T) - E(0) = %.12g J, work - dissipation = %.12g J, "
             "|difference|/E(T) = %.3g\n",
             fr ? "rotating" : "fixed", rtol, yf[dim - 1], E1 - E0, Win, err_tol[it]);
      if (it == 0) CHECK("   the motor ran up (Omega(T) > 100 rad/s)", yf[dim - 1] > 100.0);
      autobal_rotor_free(w.R);
    }
    CHECK_CLOSE("   energy balance with V_g at rtol 1e-12 (relative to E(T))", err_tol[1], 0.0, 0, 1e-12);
    CHECK("   the imbalance shrinks with the tolerance", err_tol[1] < err_tol[0] || err_tol[0] < 1e-12);
  }
}

/* 6: the static offset: closed form of the library vs the JSON (SymPy), and vs a transient at rest */
static void static_offset_case(const char *json) {
  const char *grav = after_key(json, "gravity"), *pt = after_key(grav, "perturbation");
  const char *so1 = after_key(after_key(grav, "planes1"), "static_offset");
  const char *so2 = after_key(after_key(grav, "planes2"), "static_offset");
  const double theta = num(after_key(grav, "planes2"), "theta"), g = num(grav, "g");
  autobal_rotor_params p;
  ball_data bd;
  double qs[4], so[4], y[32];
  autobal_rotor *rot;
  printf("-- static offset (docs/device.md section 2)\n");
  CHECK("JSON static offsets found", pt && so1 && so2 && arr(pt, "static_offset", so, 4) == 4);
  if (!(pt && so1 && so2)) return;
  if (read_params(json, "one_plane", 1, &p, &bd) != 0) return;
  p.gravity = 1, p.shaft_angle = M_PI / 2, p.g = num(pt, "g_s");
  CHECK_STATUS("static offset, horizontal", autobal_rotor_static_offset(&p, qs), AUTOBAL_SUCCESS);
  CHECK_CLOSE("one plane, horizontal: y_s vs gravity.perturbation.static_offset", qs[1], so[1], 1e-13, 0);
  CHECK_CLOSE("one plane, horizontal: alpha_s vs gravity.perturbation.static_offset", qs[2], so[2], 1e-13, 0);
  CHECK("x_s = beta_s = 0", qs[0] == 0.0 && qs[3] == 0.0);
  p.shaft_angle = theta, p.g = g;
  CHECK_STATUS("static offset, theta", autobal_rotor_static_offset(&p, qs), AUTOBAL_SUCCESS);
  CHECK_CLOSE("one plane, theta: y_s vs gravity.planes1.static_offset", qs[1], num(so1, "y"), 1e-13, 0);
  CHECK_CLOSE("one plane, theta: alpha_s vs gravity.planes1.static_offset", qs[2], num(so1, "alpha"), 1e-13, 0);
  p.gravity = 0;
  CHECK("gravity off: offset 0", autobal_rotor_static_offset(&p, qs) == AUTOBAL_SUCCESS && qs[1] == 0.0 && qs[2] == 0.0);
  {
    ball_data bd2;
    if (read_params(json, "two_planes", 2, &p, &bd2) == 0) {
      p.gravity = 1, p.shaft_angle = theta, p.g = g;
      CHECK_STATUS("static offset, two planes", autobal_rotor_static_offset(&p, qs), AUTOBAL_SUCCESS);
      CHECK_CLOSE("two planes, theta: y_s vs gravity.planes2.static_offset", qs[1], num(so2, "y"), 1e-13, 0);
      CHECK_CLOSE("two planes, theta: alpha_s vs gravity.planes2.static_offset", qs[2], num(so2, "alpha"), 1e-13, 0);
    }
  }
  /* the rest state of the equations: omega = 0, balls at rest, started on q_s: q stays at q_s */
  p = autobal_rotor_params_default();
  p.omega = 0.0, p.gravity = 1, p.shaft_angle = M_PI / 2, p.g = 9.80665;
  {
    static const double bpsi[2] = {-M_PI / 2, -M_PI / 2}; /* the balls at the bottom (phi = -pi/2) */
    p.plane[0].ball_psi = bpsi;
    p.plane[0].psi0 = -M_PI / 2; /* the unbalance at the bottom too: an equilibrium */
    CHECK_STATUS("static offset, default rotor", autobal_rotor_static_offset(&p, qs), AUTOBAL_SUCCESS);
    memcpy(p.q0, qs, sizeof qs);
    rot = autobal_rotor_alloc(&p, NULL);
    CHECK("rotor at rest", rot != NULL);
    if (rot) {
      autobal_rotor_initial_state(rot, AUTOBAL_ROTOR_FIXED, 0.0, y, autobal_rotor_dim(rot));
      CHECK("transient at rest", integrate(autobal_rotor_rhs, rot, 0.0, 0.5, y, 1e-12, 1e-15) == 0);
      printf("     default rotor, horizontal: y_s = %.9g mm, alpha_s = %.9g rad; after 0.5 s: y = %.9g mm\n", qs[1] * 1e3,
             qs[2], y[1] * 1e3);
      CHECK_CLOSE("rest at the static offset: y(0.5 s) = y_s", y[1], qs[1], 1e-9, 1e-15);
      CHECK_CLOSE("rest at the static offset: alpha(0.5 s) = alpha_s", y[2], qs[2], 1e-9, 1e-15);
      {
        /* the amplitudes are measured from the static offset: at rest there they are 0 */
        double out[64];
        const size_t no = autobal_rotor_output_count(rot);
        CHECK("outputs", no <= 64 && autobal_rotor_outputs(rot, AUTOBAL_ROTOR_FIXED, 0.5, y, out, no) == AUTOBAL_SUCCESS);
        printf("     amp_G, amp_L, amp_R at rest on the static offset: %.3g, %.3g, %.3g m (|y| = %.3g m)\n", out[0], out[1],
               out[2], fabs(y[1]));
        CHECK("amp_G, amp_L, amp_R about the static offset: below 1e-12 m at rest there",
              out[0] < 1e-12 && out[1] < 1e-12 && out[2] < 1e-12);
      }
      autobal_rotor_free(rot);
    }
  }
}

int main(void) {
  char *json;
  gsl_set_error_handler_off();
  json = slurp(JSON_PATH);
  CHECK("tools/derive/check_values.json read", json != NULL);
  if (!json) return 1;
  accelerations_case(json, "one_plane", "planes1", 1);
  accelerations_case(json, "two_planes", "planes2", 2);
  perturbation_case(json, 0);
  perturbation_case(json, 1);
  bad_input();
  motor_case(json, "one_plane", "planes1", 1);
  motor_case(json, "two_planes", "planes2", 2);
  motor_power_balance();
  static_offset_case(json);
  free(json);
  printf("%d checks, %d failed\n", check_count_, check_failures_);
  return check_failures_ ? 1 : 0;
}
