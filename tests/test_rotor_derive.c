/* test_rotor_derive.c: the C right-hand sides with a prescribed spin speed (autobal_rotor_drive,
 * src/models/rotor/rotor.c) against the accelerations of the independent SymPy derivation
 * (tools/derive/derive_rotor.py, from the energies of docs/device.md; its values are in
 * tools/derive/check_values.json, which test_derive keeps equal to what the script computes).
 *
 * The check state of the JSON has phi_0 = 0.3 rad, Omega = 300 rad/s, Omega' = 50 rad/s^2.  A ramp
 * drive from t = 0 with slope 50 rad/s^2 reaches exactly that at the time t* where
 * Omega(t*) = 300 and phi_0(t*) = integral_0^t* Omega = 0.3: with Omega(t) = omega_a + 50 t,
 * phi_0(t) = 300 t - 25 t^2 = 0.3.  Both frames, one and two planes; every parameter and state
 * value is read from the JSON, nothing is copied from the program's own output. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/rotor.h"
#include "check.h"

#define JSON_PATH AUTOBAL_TEST_DATA_DIR "/../tools/derive/check_values.json"

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

static void run_case(const char *json, const char *which, size_t n_planes) {
  const char *blk = after_key(json, which), *par = after_key(blk, "parameters"), *st = after_key(blk, "state");
  const char *pre = after_key(blk, "prescribed"), *acc = after_key(pre, "accelerations"), *pl = after_key(blk, "planes");
  autobal_rotor_params p = autobal_rotor_params_default();
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2], y[8 + 8], dy[8 + 8], yr[8 + 8], dyr[8 + 8];
  double Om, Omd, phi0, t, drv[3];
  autobal_rotor *rot;
  autobal_error err;
  const char *plane_at[2];
  size_t j, i, N = 0;
  char what[160];
  static const char *const qdd[4] = {"x_dd", "y_dd", "alpha_dd", "beta_dd"};
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};

  CHECK("JSON blocks found", blk && par && st && pre && acc && pl);
  if (!(blk && par && st && pre && acc && pl)) return;
  p.input = AUTOBAL_ROTOR_HARDWARE;
  p.hw.M_k = num(par, "M_k"), p.hw.A_k = num(par, "A_k"), p.hw.m_p = num(par, "m_p");
  p.hw.A_p = num(par, "A_p"), p.hw.C_p = num(par, "C_p");
  p.hw.l_L = num(par, "l_L"), p.hw.l_R = num(par, "l_R");
  p.hw.c_Lx = num(par, "c_Lx"), p.hw.c_Ly = num(par, "c_Ly"), p.hw.c_Rx = num(par, "c_Rx"), p.hw.c_Ry = num(par, "c_Ry");
  p.hw.h_Lx = num(par, "h_Lx"), p.hw.h_Ly = num(par, "h_Ly"), p.hw.h_Rx = num(par, "h_Rx"), p.hw.h_Ry = num(par, "h_Ry");
  p.n_planes = n_planes;
  plane_at[0] = strchr(pl, '{');
  plane_at[1] = plane_at[0] ? strchr(strchr(plane_at[0], '}') + 1, '{') : NULL;
  for (j = 0; j < n_planes; j++) {
    const char *q = plane_at[j];
    autobal_rotor_plane *P = &p.plane[j];
    CHECK("plane block found", q != NULL);
    if (!q) return;
    P->d = num(q, "d"), P->m0 = num(q, "m0"), P->r0 = num(q, "r0"), P->psi0 = num(q, "psi0");
    P->n_balls = arr(q, "m", m[j], 2);
    CHECK("two balls per plane", P->n_balls == 2 && arr(q, "r", r[j], 2) == 2 && arr(q, "h", h[j], 2) == 2 &&
                                     arr(q, "psi", psi[j], 2) == 2 && arr(q, "rate", rate[j], 2) == 2);
    P->ball_mass = m[j], P->ball_radius = r[j], P->ball_damping = h[j], P->ball_psi = psi[j], P->ball_rate = rate[j];
    N += 2;
  }
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

int main(void) {
  char *json;
  gsl_set_error_handler_off();
  json = slurp(JSON_PATH);
  CHECK("tools/derive/check_values.json read", json != NULL);
  if (!json) return 1;
  run_case(json, "one_plane", 1);
  run_case(json, "two_planes", 2);
  free(json);
  printf("%d checks, %d failed\n", check_count_, check_failures_);
  return check_failures_ ? 1 : 0;
}
