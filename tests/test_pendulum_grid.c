/* test_pendulum_grid.c: maps and sweeps of the two-pendulum balancer over any parameter
 * (src/analysis/pendulum_map.c: autobal_pendulum_params_vary, autobal_pendulum_grid*,
 * docs/pendulum.md "Maps and sweeps over any parameter").  References, each computed another
 * way: the one-point autobal_pendulum_verdict on parameters built by hand (the rule of the
 * H/h axis written out here); the (R_m, R_w) map of the lanes (autobal_pendulum_map) against
 * the same grid with the axes swapped, which goes point by point; the bisection of a sweep
 * against the exact critical speeds (discriminant of (10), autobal_pendulum_critical_speeds);
 * every error path. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/pendulum.h"
#include "check.h"

static int verdict_of(double R_w, double R_m, double H, double h, double k) {
  autobal_pendulum_params p;
  int v = 99;
  if (autobal_pendulum_params_from_k(R_w, R_m, H, h, k, &p, NULL) != AUTOBAL_SUCCESS) return 98;
  if (autobal_pendulum_verdict(&p, &v, NULL, NULL) != AUTOBAL_SUCCESS) return 97;
  return v;
}

int main(void) {
  autobal_pendulum_params base, q;
  autobal_error err;
  int v, st;

  printf("-- names and ranges\n");
  CHECK("names round-trip, H/h also as H_over_h",
        autobal_pendulum_param_lookup("H/h") == AUTOBAL_PENDULUM_PARAM_H_RATIO &&
            autobal_pendulum_param_lookup("H_over_h") == AUTOBAL_PENDULUM_PARAM_H_RATIO &&
            autobal_pendulum_param_lookup("h") == AUTOBAL_PENDULUM_PARAM_HP &&
            autobal_pendulum_param_lookup("H") == AUTOBAL_PENDULUM_PARAM_H &&
            autobal_pendulum_param_lookup("R_x") == -1 && autobal_pendulum_param_name(AUTOBAL_PENDULUM_NPARAM) == NULL &&
            !strcmp(autobal_pendulum_param_unit(AUTOBAL_PENDULUM_PARAM_PSI0), "rad"));
  CHECK_STATUS("R_m = 0.5 rejected", autobal_pendulum_param_check(AUTOBAL_PENDULUM_PARAM_R_M, 0.5, &err), AUTOBAL_EINVAL);
  CHECK_MSG("... names the key and the range", err.message, "pendulum.R_m = 0.5 is too large: must be < 0.5 (allowed range (0, 0.5))");
  CHECK_STATUS("k = 1.5 rejected", autobal_pendulum_param_check(AUTOBAL_PENDULUM_PARAM_K, 1.5, &err), AUTOBAL_EINVAL);
  CHECK_MSG("... names the key", err.message, "pendulum.k = 1.5");
  CHECK_STATUS("H/h = 0 rejected (open at 0)", autobal_pendulum_param_check(AUTOBAL_PENDULUM_PARAM_H_RATIO, 0.0, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("h = NaN rejected", autobal_pendulum_param_check(AUTOBAL_PENDULUM_PARAM_HP, NAN, &err), AUTOBAL_EINVAL);

  printf("-- the rule of the H/h axis\n");
  autobal_pendulum_params_from_k(3.0, 0.1, 0.2, 0.5, 0.5, &base, NULL);
  st = autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_H_RATIO, 4.0, AUTOBAL_PENDULUM_PARAM_R_W, 2.0, &q, &err);
  CHECK("(H/h, R_w): h held (0.5), H = 4 h = 2, R_w = 2", st == 0 && q.h == 0.5 && q.H == 2.0 && q.R_w == 2.0);
  st = autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_HP, 0.25, AUTOBAL_PENDULUM_PARAM_H_RATIO, 4.0, &q, &err);
  CHECK("(h, H/h): h from its axis, H = 4 * 0.25 = 1", st == 0 && q.h == 0.25 && q.H == 1.0);
  st = autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_H_RATIO, 4.0, AUTOBAL_PENDULUM_PARAM_H, 2.0, &q, &err);
  CHECK("(H/h, H): H from its axis, h = 2 / 4", st == 0 && q.H == 2.0 && q.h == 0.5);
  st = autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_K, 1.0, -1, 0.0, &q, &err);
  CHECK("k = 1 sets psi0 = pi/4", st == 0 && fabs(q.psi0 - 0.78539816339744831) < 1e-15);
  q = base, q.h = 0.0;
  CHECK_STATUS("H/h with h = 0 held: rejected", autobal_pendulum_params_vary(&q, AUTOBAL_PENDULUM_PARAM_H_RATIO, 2.0, AUTOBAL_PENDULUM_PARAM_R_W, 1.0, &q, &err), AUTOBAL_EINVAL);
  CHECK_MSG("... message", err.message, "axis H/h needs pendulum.h > 0");
  CHECK_STATUS("k with psi0: rejected", autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_K, 0.5, AUTOBAL_PENDULUM_PARAM_PSI0, 0.1, &q, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("the same parameter twice: rejected", autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_H, 0.5, AUTOBAL_PENDULUM_PARAM_H, 0.1, &q, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("H/h = 1e6 at H = 10: h = 1e-5 fine", autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_H_RATIO, 1e6, AUTOBAL_PENDULUM_PARAM_H, 10.0, &q, &err), AUTOBAL_SUCCESS);
  CHECK_STATUS("H/h = 1e6 at h = 10: H = 1e7 too large", autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_H_RATIO, 1e6, AUTOBAL_PENDULUM_PARAM_HP, 10.0, &q, &err), AUTOBAL_EINVAL);
  CHECK_MSG("... message names H and its limit", err.message, "must be <= 1e+06");

  printf("-- grids against the one-point verdict\n");
  {
    /* (H, h) with both log, every unbalance (k = j/8), at R_m = 0.1, R_w = 3 */
    double Hs[7], hs[6], ks[9];
    signed char vv[42];
    autobal_pendulum_grid_spec s;
    size_t i, j, t, bad = 0, nst = 0;
    for (i = 0; i < 7; i++) Hs[i] = pow(10.0, -3.0 + 0.5 * (double)i);
    for (j = 0; j < 6; j++) hs[j] = pow(10.0, -2.5 + 0.5 * (double)j);
    for (t = 0; t < 9; t++) ks[t] = (double)t / 8.0;
    memset(&s, 0, sizeof s);
    s.base = base;
    s.param1 = AUTOBAL_PENDULUM_PARAM_H, s.v1 = Hs, s.n1 = 7;
    s.param2 = AUTOBAL_PENDULUM_PARAM_HP, s.v2 = hs, s.n2 = 6;
    s.k = ks, s.n_k = 9;
    CHECK_STATUS("grid (H, h), every unbalance", autobal_pendulum_grid(&s, vv, NULL, &err), AUTOBAL_SUCCESS);
    for (i = 0; i < 7; i++)
      for (j = 0; j < 6; j++) {
        int w = AUTOBAL_VERDICT_STABLE;
        for (t = 0; t < 9; t++) {
          int x = verdict_of(3.0, 0.1, Hs[i], hs[j], ks[t]);
          if (x < w) w = x;
        }
        bad += vv[i * 6 + j] != w;
        nst += vv[i * 6 + j] > 0;
      }
    printf("     %zu of 42 stable\n", nst);
    CHECK("... every entry = the worst autobal_pendulum_verdict over k (both verdicts occur)", bad == 0 && nst > 0 && nst < 42);
  }
  {
    /* the fast (R_m, R_w) map against the point-by-point (R_w, R_m) grid, damped and undamped,
     * one k and every unbalance */
    double rm[13], rw[29];
    signed char a[13 * 29], b[29 * 13];
    autobal_pendulum_grid_spec s;
    size_t i, j, bad;
    int c, nst;
    for (i = 0; i < 13; i++) rm[i] = 0.01 + 0.48 * (double)i / 12.0;
    for (j = 0; j < 29; j++) rw[j] = 0.2 * (double)j; /* through R_w = 0 and 1 */
    for (c = 0; c < 4; c++) {
      autobal_pendulum_params_from_k(1.0, 0.1, c < 2 ? 0.0 : 0.05, c < 2 ? 0.0 : 0.1, c % 2 ? 0.0 : 0.3, &base, NULL);
      memset(&s, 0, sizeof s);
      s.base = base;
      if (c % 2) s.k = NULL, s.n_k = 0; /* k = 0 of base */
      s.param1 = AUTOBAL_PENDULUM_PARAM_R_M, s.v1 = rm, s.n1 = 13;
      s.param2 = AUTOBAL_PENDULUM_PARAM_R_W, s.v2 = rw, s.n2 = 29;
      st = autobal_pendulum_grid(&s, a, NULL, &err);
      s.param1 = AUTOBAL_PENDULUM_PARAM_R_W, s.v1 = rw, s.n1 = 29;
      s.param2 = AUTOBAL_PENDULUM_PARAM_R_M, s.v2 = rm, s.n2 = 13;
      st |= autobal_pendulum_grid(&s, b, NULL, &err);
      bad = 0, nst = 0;
      for (i = 0; i < 13; i++)
        for (j = 0; j < 29; j++) bad += a[i * 29 + j] != b[j * 13 + i], nst += a[i * 29 + j] > 0;
      printf("     case %d (%s, k = %s): %d of 377 stable, %zu differ\n", c, c < 2 ? "undamped" : "damped",
             c % 2 ? "0" : "0.3", nst, bad);
      CHECK("(R_m, R_w) lanes == (R_w, R_m) point by point, transposed", st == 0 && bad == 0 && nst > 0 && nst < 377);
      if (c == 1) { /* the exact convention at k = 0: R_w = 0 and R_w = 1 (row 5 of b) unstable */
        bad = 0;
        for (i = 0; i < 13; i++) bad += b[0 * 13 + i] != -1 || b[5 * 13 + i] != -1;
        CHECK("undamped k = 0: R_w = 0 and R_w = 1 unstable for every R_m (lambda = 0 not semisimple)", bad == 0);
      }
    }
  }

  printf("-- a sweep's bisection against the exact critical speeds\n");
  {
    autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
    autobal_pendulum_crit_set cs;
    autobal_pendulum_grid_spec s;
    double x, lo, hi;
    size_t j;
    int vl, vh, ok = 1;
    autobal_pendulum_params_from_k(1.0, 0.2, 0.0, 0.0, 0.9, &base, NULL);
    CHECK_STATUS("exact critical speeds (R_m = 0.2, k = 0.9)", autobal_pendulum_critical_speeds(ws, 0.2, 0.9, &cs), AUTOBAL_SUCCESS);
    memset(&s, 0, sizeof s);
    s.base = base;
    s.param1 = AUTOBAL_PENDULUM_PARAM_R_W;
    s.param2 = -1;
    for (j = 0; j < cs.n; j++) {
      if (cs.kind[j] == AUTOBAL_CRIT_TOUCH) continue;
      lo = cs.R_w[j] * (1 - 1e-3), hi = cs.R_w[j] * (1 + 1e-3);
      st = autobal_pendulum_grid_critical(&s, lo, hi, 1, 1e-12, &x, &vl, &vh, &err);
      printf("     R_w%zu = %.15f exact, %.15f bisection (%d -> %d)\n", j + 1, cs.R_w[j], x, vl, vh);
      ok &= st == 0 && fabs(x - cs.R_w[j]) <= 3e-12 * cs.R_w[j] && vl == -cs.kind[j] && vh == cs.kind[j];
    }
    CHECK("every critical speed found by bisection to 3e-12, kinds as the exact ones", ok && cs.n >= 3);
    CHECK_STATUS("bisection with equal verdicts at the ends: rejected",
                 autobal_pendulum_grid_critical(&s, 0.1, 0.2, 0, 1e-10, &x, NULL, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... message", err.message, "are equal");
    s.param2 = AUTOBAL_PENDULUM_PARAM_R_M;
    CHECK_STATUS("bisection on a map (not a line): rejected",
                 autobal_pendulum_grid_critical(&s, 1.0, 2.0, 0, 1e-10, &x, NULL, NULL, &err), AUTOBAL_EINVAL);
    autobal_pendulum_workspace_free(ws);
  }

  printf("-- grid errors: nothing written\n");
  {
    double vals[3] = {0.1, 0.2, 0.7}, ks[2] = {0.0, 1.0};
    signed char out[3] = {7, 7, 7};
    autobal_pendulum_grid_spec s;
    autobal_pendulum_params_from_k(3.0, 0.1, 0.1, 0.5, 0.5, &base, NULL);
    memset(&s, 0, sizeof s);
    s.base = base;
    s.param1 = AUTOBAL_PENDULUM_PARAM_R_M, s.v1 = vals, s.n1 = 3, s.param2 = -1;
    CHECK_STATUS("R_m axis through 0.7", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... names pendulum.R_m and the value", err.message, "pendulum.R_m = 0.7 is too large");
    CHECK("... nothing written", out[0] == 7 && out[1] == 7 && out[2] == 7);
    s.param1 = AUTOBAL_PENDULUM_PARAM_K, s.k = ks, s.n_k = 2;
    CHECK_STATUS("k axis with a k set", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... message", err.message, "cannot be combined with a k or psi0 axis");
    s.param1 = AUTOBAL_PENDULUM_PARAM_H, s.k = NULL, s.n_k = 0, s.n_threads = -1;
    CHECK_STATUS("n_threads = -1", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    s.n_threads = 0, s.v1 = NULL;
    CHECK_STATUS("NULL axis", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    CHECK("... nothing written", out[0] == 7);
    s.v1 = vals, s.param1 = 99;
    CHECK_STATUS("unknown parameter", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    CHECK_STATUS("grid_point: NULL output", autobal_pendulum_grid_point(&s, 0.1, 0.0, NULL, NULL, NULL, &err), AUTOBAL_EINVAL);
    s.param1 = AUTOBAL_PENDULUM_PARAM_H;
    st = autobal_pendulum_grid_point(&s, 0.1, 0.0, NULL, &v, NULL, &err);
    CHECK("grid_point on a line = autobal_pendulum_verdict with H set", st == 0 && v == verdict_of(3.0, 0.1, 0.1, 0.5, 0.5));
  }
  return check_summary();
}
