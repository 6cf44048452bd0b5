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
 *  4. bad gravity parameters are rejected with the parameter's name. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/rotor.h"
#include "check.h"
#include "rotor_integrate.h"

#define JSON_PATH AUTOBAL_TEST_DATA_DIR "/../tools/derive/check_values.json"
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  char *buf;
  long n;
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  n = ftell(f);
  fseek(f, 0, SEEK_SET);
  buf = malloc((size_t)n + 1);
  if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
    free(buf);
    buf = NULL;
  }
  if (buf) buf[n] = '\0';
  fclose(f);
  return buf;
}

/* Position just after "key": at or after p (NULL if absent). */
static const char *after_key(const char *p, const char *key) {
  char pat[80];
  const char *q;
  snprintf(pat, sizeof pat, "\"%s\":", key);
  q = p ? strstr(p, pat) : NULL;
  return q ? q + strlen(pat) : NULL;
}
static double num(const char *p, const char *key) {
  const char *q = after_key(p, key);
  return q ? strtod(q, NULL) : NAN;
}
/* An array of numbers after "key": up to n values into v; returns the count. */
static size_t arr(const char *p, const char *key, double *v, size_t n) {
  const char *q = after_key(p, key);
  size_t k = 0;
  char *end;
  if (!q || !(q = strchr(q, '['))) return 0;
  q++;
  while (k < n) {
    double x = strtod(q, &end);
    if (end == q) break;
    v[k++] = x;
    q = end;
    while (*q == ' ' || *q == '\n' || *q == ',') q++;
    if (*q == ']') break;
  }
  return k;
}

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
  p.gravity = 0; /* off: the other fields are not looked at */
  r = autobal_rotor_alloc(&p, &err);
  CHECK("gravity off ignores g and shaft_angle", r != NULL);
  autobal_rotor_free(r);
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
  free(json);
  printf("%d checks, %d failed\n", check_count_, check_failures_);
  return check_failures_ ? 1 : 0;
}
