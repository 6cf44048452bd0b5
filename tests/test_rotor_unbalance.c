/* test_rotor_unbalance.c: stability for every unbalance in a range (autobal_rotor_stab_every_unbalance,
 * docs/rotor.md "Every unbalance") against dense per-unbalance analyses, which do not use the
 * crossing polynomial:
 *  - at several speeds and ranges, every one of 2001 sampled unbalances has the verdict of its
 *    sub-interval, and "stable for all" holds exactly when every sample is stable and no critical
 *    unbalance lies inside;
 *  - at every critical unbalance reported, Delta has a root on the imaginary axis (its roots from
 *    the polynomial solver at that unbalance) and the number of roots with Re > 0 changes there;
 *  - the measurement: the default rotor with m0 r0 in [0.0061, 0.0079] kg m is unstable at
 *    every speed up to 2000 rad/s, for all of them (every_unbalance_speeds finds no stable speed),
 *    checked by sampling;
 *  - the every-unbalance speed set equals the intersection of the per-unbalance verdicts (120
 *    speeds x 161 unbalances), away from its boundaries;
 *  - the map for every unbalance (omega x ball damping) against 201 sampled unbalances per point,
 *    1 and 2 threads bit for bit, no verdict where the balls cannot balance the range;
 *  - m0 and omega restored bitwise, and the error paths. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

#define NS 2001

static double margins[NS];
static int verdicts[NS];

/* Dense per-unbalance verdicts at the handle's omega for s = m0 r0 in [lo, hi]. */
static int sample(autobal_rotor_stab *s, double r0, double lo, double hi, size_t n, double *sv) {
  size_t k;
  for (k = 0; k < n; k++) sv[k] = (lo + (hi - lo) * (double)k / (double)(n - 1)) / r0;
  return autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv, n, margins, verdicts);
}

/* Roots of Delta with Re > 0 at m0 (the polynomial solver's roots); -1 on failure. */
static int rhp_count(autobal_rotor_stab *s, double m0) {
  autobal_rotor_stab_result res;
  size_t j;
  int n = 0;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  if (autobal_rotor_stab_analyze(s, &res) != AUTOBAL_SUCCESS) return -1;
  for (j = 0; j + 1 < res.n_poly; j++) n += res.root_re[j] > 0.0;
  return n;
}

static void one_case(autobal_rotor_stab *s, double w, double lo, double hi) {
  autobal_rotor_unbalance_range ur;
  const double r0 = autobal_rotor_stab_params(s)->plane[0].r0;
  double sv[NS], m0_before, w_before;
  size_t k, j, bad = 0;
  int all = 1, st;
  char what[200];
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  m0_before = autobal_rotor_stab_params(s)->plane[0].m0;
  w_before = autobal_rotor_stab_params(s)->omega;
  st = autobal_rotor_stab_every_unbalance(s, lo, hi, &ur);
  snprintf(what, sizeof what, "omega %g, m0 r0 in [%g, %g]: every_unbalance", w, lo, hi);
  CHECK_STATUS(what, st, AUTOBAL_SUCCESS);
  if (st != AUTOBAL_SUCCESS) {
    printf("     %s\n", autobal_rotor_stab_errmsg(s));
    return;
  }
  CHECK("m0 and omega restored bitwise",
        autobal_rotor_stab_params(s)->plane[0].m0 == m0_before && autobal_rotor_stab_params(s)->omega == w_before);
  printf("     %zu critical unbalance(s):", ur.n_crit);
  for (k = 0; k < ur.n_crit; k++) printf(" %.9g", ur.s_crit[k]);
  printf("; all stable %d, %zu evaluations\n", ur.all_stable, ur.evaluations);
  CHECK("no verdict change missed by the crossing polynomial", ur.n_missed == 0);
  CHECK_STATUS("dense sampling", sample(s, r0, lo, hi, NS, sv), AUTOBAL_SUCCESS);
  for (k = 0; k < NS; k++) {
    const double x = sv[k] * r0;
    int near = 0;
    for (j = 0; j < ur.n_crit; j++)
      if (fabs(x - ur.s_crit[j]) <= 1e-7 * (hi - lo)) near = 1;
    if (verdicts[k] != AUTOBAL_VERDICT_STABLE) all = 0;
    if (near) continue;
    for (j = 0; j < ur.n_sub; j++)
      if (x >= ur.sub_lo[j] && x <= ur.sub_hi[j] && verdicts[k] != ur.sub_verdict[j]) bad++;
  }
  snprintf(what, sizeof what, "every sample has its sub-interval's verdict (%zu disagree)", bad);
  CHECK(what, bad == 0);
  snprintf(what, sizeof what, "stable for all (%d) == every sample stable (%d) and no critical value inside (%zu)",
           ur.all_stable, all, ur.n_crit);
  CHECK(what, ur.all_stable == (all && ur.n_crit == 0));
  /* each critical unbalance: a root of Delta on the imaginary axis there */
  for (k = 0; k < ur.n_crit; k++) {
    autobal_rotor_stab_result res;
    double mr = INFINITY, big = 1.0;
    int nlo, nhi;
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, ur.s_crit[k] / r0);
    if (autobal_rotor_stab_analyze(s, &res) == AUTOBAL_SUCCESS)
      for (j = 0; j < res.n_poly - 1; j++) {
        mr = fmin(mr, fabs(res.root_re[j]));
        big = fmax(big, hypot(res.root_re[j], res.root_im[j]));
      }
    snprintf(what, sizeof what, "s* = %.9g kg m: a root of Delta on the axis (min |Re| / max |root|)", ur.s_crit[k]);
    CHECK_CLOSE(what, mr / big, 0.0, 0.0, 1e-8);
    nlo = rhp_count(s, ur.s_crit[k] * (1.0 - 1e-6) / r0);
    nhi = rhp_count(s, ur.s_crit[k] * (1.0 + 1e-6) / r0);
    snprintf(what, sizeof what, "s* = %.9g: the number of roots with Re > 0 changes across it (%d, %d)",
             ur.s_crit[k], nlo, nhi);
    CHECK(what, nlo != nhi && nlo >= 0 && nhi >= 0);
  }
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0_before);
}

int main(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab *s;
  autobal_error err;
  static const double speeds[] = {300.0, 500.0, 800.0, 1200.0, 2000.0};
  size_t k;
  s = autobal_rotor_stab_alloc(&p, NULL, &err);
  if (!s) {
    printf("alloc: %s\n", err.message);
    return 1;
  }
  for (k = 0; k < sizeof speeds / sizeof speeds[0]; k++) {
    one_case(s, speeds[k], 1e-5, 0.0095);
    one_case(s, speeds[k], 0.0005, 0.003);
  }
  /* the measurement: m0 = 0.061..0.079 kg (r0 = 0.1 m) unstable at every speed to 2000 rad/s */
  {
    autobal_rotor_crit cr;
    double sv[41];
    size_t i, j, n_stable = 0;
    int st = autobal_rotor_stab_every_unbalance_speeds(s, 0.0061, 0.0079, 20.0, 2000.0, 200, 1e-8, &cr);
    CHECK_STATUS("speeds for m0 r0 in [0.0061, 0.0079]", st, AUTOBAL_SUCCESS);
    printf("     %zu stable speed interval(s), %zu evaluations\n", cr.n_stable, cr.evaluations);
    CHECK("no speed in [20, 2000] rad/s is stable for all of them", cr.n_stable == 0);
    for (i = 0; i < 100; i++) {
      autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, 20.0 + 1980.0 * (double)i / 99.0);
      for (j = 0; j < 41; j++) sv[j] = (0.0061 + 0.0018 * (double)j / 40.0) / 0.1;
      autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv, 41, margins, verdicts);
      {
        int all = 1;
        for (j = 0; j < 41; j++) all &= verdicts[j] == AUTOBAL_VERDICT_STABLE;
        n_stable += (size_t)all;
      }
    }
    CHECK("sampling agrees: no sampled speed stable for all 41 sampled unbalances", n_stable == 0);
  }
  /* the every-unbalance speed set = intersection of per-unbalance verdicts, away from boundaries */
  {
    autobal_rotor_crit cr;
    double sv[161];
    size_t i, j, bad = 0, n_in = 0;
    int st = autobal_rotor_stab_every_unbalance_speeds(s, 1e-5, 0.004, 100.0, 2000.0, 300, 1e-9, &cr);
    CHECK_STATUS("speeds for m0 r0 in [1e-5, 0.004]", st, AUTOBAL_SUCCESS);
    printf("     stable for all at:");
    for (i = 0; i < cr.n_stable; i++) printf(" [%.6f, %.6f]", cr.stable_lo[i], cr.stable_hi[i]);
    printf(" rad/s\n");
    CHECK("at least one stable speed interval for all unbalances in [1e-5, 0.004] kg m", cr.n_stable >= 1);
    for (j = 0; j < 161; j++) sv[j] = (1e-5 + (0.004 - 1e-5) * (double)j / 160.0) / 0.1;
    for (i = 0; i < 120; i++) {
      const double w = 100.0 + 1900.0 * ((double)i + 0.37) / 120.0;
      int inside = 0, near = 0, all = 1;
      for (j = 0; j < cr.n_stable; j++) inside |= w > cr.stable_lo[j] && w < cr.stable_hi[j];
      for (j = 0; j < cr.n; j++) near |= fabs(w - cr.value[j]) < 2.0;
      if (near) continue;
      autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
      autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv, 161, margins, verdicts);
      for (j = 0; j < 161; j++) all &= verdicts[j] == AUTOBAL_VERDICT_STABLE;
      n_in += (size_t)inside;
      if (inside != all) {
        bad++;
        printf("     omega %.6f: every-unbalance %d, sampled %d\n", w, inside, all);
      }
    }
    printf("     %zu of the sampled speeds inside the set\n", n_in);
    CHECK("the speed set equals the intersection of the sampled per-unbalance verdicts", bad == 0);
  }
  /* the map for every unbalance: each point against 201 sampled unbalances; 1 and 2 threads alike */
  {
    static const double w[6] = {300.0, 405.0, 420.0, 600.0, 900.0, 1500.0}, hb[4] = {0.02, 0.1, 0.3, 0.6};
    static const double bm[2] = {0.05, 0.01};
    double mg1[24], mg2[24], sv[201];
    int vd1[24], vd2[24], st1, st2;
    size_t i, j, bad = 0, same = 1;
    autobal_rotor_params q = autobal_rotor_params_default();
    st1 = autobal_rotor_stab_map_every_unbalance(&q, NULL, AUTOBAL_ROTOR_PARAM_OMEGA, w, 6,
                                                 AUTOBAL_ROTOR_PARAM_BALL_DAMPING, hb, 4, 1e-4, 0.004, 1, mg1, vd1, &err);
    st2 = autobal_rotor_stab_map_every_unbalance(&q, NULL, AUTOBAL_ROTOR_PARAM_OMEGA, w, 6,
                                                 AUTOBAL_ROTOR_PARAM_BALL_DAMPING, hb, 4, 1e-4, 0.004, 2, mg2, vd2, &err);
    CHECK_STATUS("map for every unbalance, 1 thread", st1, AUTOBAL_SUCCESS);
    CHECK_STATUS("map for every unbalance, 2 threads", st2, AUTOBAL_SUCCESS);
    for (i = 0; i < 24; i++) same &= vd1[i] == vd2[i] && memcmp(&mg1[i], &mg2[i], sizeof mg1[i]) == 0;
    CHECK("1 and 2 threads give the same map bit for bit", same);
    for (j = 0; j < 201; j++) sv[j] = (1e-4 + (0.004 - 1e-4) * (double)j / 200.0) / 0.1;
    for (i = 0; i < 24; i++) {
      autobal_rotor_stab *t = autobal_rotor_stab_alloc(&q, NULL, &err);
      int all = 1;
      if (!t) break;
      autobal_rotor_stab_set(t, AUTOBAL_ROTOR_PARAM_OMEGA, w[i / 4]);
      autobal_rotor_stab_set(t, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, hb[i % 4]);
      autobal_rotor_stab_sweep(t, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv, 201, margins, verdicts);
      for (j = 0; j < 201; j++) all &= verdicts[j] == AUTOBAL_VERDICT_STABLE;
      if ((vd1[i] == AUTOBAL_VERDICT_STABLE) != all) {
        bad++;
        printf("     omega %g, h %g: map %d, sampled all stable %d\n", w[i / 4], hb[i % 4], vd1[i], all);
      }
      autobal_rotor_stab_free(t);
    }
    CHECK("each map point: stable for all == every sampled unbalance stable", bad == 0);
    /* ball mass 0.01 kg (2 m r = 0.002 kg m) cannot balance 0.004 kg m: no verdict there */
    st1 = autobal_rotor_stab_map_every_unbalance(&q, NULL, AUTOBAL_ROTOR_PARAM_OMEGA, w + 3, 1,
                                                 AUTOBAL_ROTOR_PARAM_BALL_MASS, bm, 2, 1e-4, 0.004, 1, mg1, vd1, &err);
    CHECK("ball mass 0.05: a verdict; 0.01: none (the balls cannot balance the range)",
          st1 == AUTOBAL_SUCCESS && vd1[0] != AUTOBAL_ROTOR_VERDICT_NONE && vd1[1] == AUTOBAL_ROTOR_VERDICT_NONE &&
              isnan(mg1[1]));
    CHECK_STATUS("unbalance_mass as an axis", autobal_rotor_stab_map_every_unbalance(&q, NULL, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, w, 1, AUTOBAL_ROTOR_PARAM_OMEGA, w, 1, 1e-4, 0.004, 1, mg1, vd1, &err), AUTOBAL_EINVAL);
  }
  /* errors */
  {
    autobal_rotor_unbalance_range ur;
    autobal_rotor_params q = autobal_rotor_params_default();
    autobal_rotor_stab *s2;
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, 500.0);
    CHECK_STATUS("range beyond what the balls balance (2 m r = 0.01 kg m)", autobal_rotor_stab_every_unbalance(s, 0.001, 0.0101, &ur),
                 AUTOBAL_EINVAL);
    CHECK_MSG("message names m0 r0 and the range", autobal_rotor_stab_errmsg(s), "m0 r0");
    CHECK_STATUS("min > max", autobal_rotor_stab_every_unbalance(s, 0.003, 0.002, &ur), AUTOBAL_EINVAL);
    CHECK_STATUS("NaN", autobal_rotor_stab_every_unbalance(s, NAN, 0.002, &ur), AUTOBAL_EINVAL);
    CHECK_STATUS("NULL out", autobal_rotor_stab_every_unbalance(s, 0.001, 0.002, NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("NULL handle", autobal_rotor_stab_every_unbalance(NULL, 0.001, 0.002, &ur), AUTOBAL_EINVAL);
    q.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
    s2 = autobal_rotor_stab_alloc(&q, NULL, &err);
    CHECK_STATUS("full inertia: unsupported", s2 ? autobal_rotor_stab_every_unbalance(s2, 0.001, 0.002, &ur) : -99,
                 AUTOBAL_EUNSUPPORTED);
    if (s2) CHECK_MSG("message says inertia", autobal_rotor_stab_errmsg(s2), "inertia");
    autobal_rotor_stab_free(s2);
  }
  autobal_rotor_stab_free(s);
  return check_summary();
}
