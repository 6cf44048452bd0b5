/* test_rotor_design_nballs.c: the number of balls as a design bound (docs/rotor.md "Design", "Number
 * of balls") and its exact building block, autobal_rotor_stab_margin_ratio_set for n >= 3 identical
 * balls on the symmetric fan, against computations that do not use the crossing polynomial:
 *  - the t-set of n = 3, 4 balls at several speeds and margins: 2001 sampled t in (0, n) (POLY margins
 *    of single unbalances through autobal_rotor_stab_sweep, the handle's symmetric member) are inside
 *    the set exactly when their margin is < -delta (away from the critical t); the margin is -delta
 *    at every verdict change; delta = 0 gives the critical unbalances of autobal_rotor_stab_every_unbalance
 *    (rotor_unbalance.c's own fan map); the margin depends on the radius only through t (the premise
 *    of the exact radius windows);
 *  - a search over n = 2..4: every ranked design's verdict and robust margin against per-unbalance
 *    analyses on a dense unbalance grid at every grid speed (with n balls), the ball modes -h/m
 *    included for n >= 3; the map's -1 cells are those with n m r <= unbalance_max (closed form);
 *  - total_mass_max: the map's -2 cells are exactly those with n m > the cap, no design exceeds it;
 *  - error paths: n_balls out of range, the member rule every above 10 balls, member_boxes, a bad cap. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"
#include "rotor_nballs.h"

#define NT 2001
#define NS 301

static double mg_s[NT], m0v[NT];
static int vd_s[NT];

static int in_set(const autobal_rotor_ratio_set *rs, double t) {
  size_t i;
  for (i = 0; i < rs->n; i++)
    if (rs->lo[i] < t && t < rs->hi[i]) return 1;
  return 0;
}

static double dist_crit(const autobal_rotor_ratio_set *rs, double t, double n) {
  double d = fmin(t, n - t);
  size_t i;
  for (i = 0; i < rs->n_crit; i++) d = fmin(d, fabs(t - rs->t_crit[i]));
  return d;
}

static void test_fan_sets(void) {
  const double speeds[3] = {420.0, 600.0, 900.0}, deltas[2] = {0.0, 0.5};
  size_t n, a, b, k, bad = 0, nchk = 0, crit_checked = 0, crit_bad = 0, ev_checked = 0, missed = 0;
  for (n = 3; n <= 4; n++) {
    double m[4], r[4], h[4], psi[4], rate[4];
    autobal_rotor_params p = machine(n, m, r, h, psi, rate, 0.05, 0.1, 0.5);
    autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
    autobal_rotor_stab *s;
    const double mr = 0.05 * 0.1, r0 = p.plane[0].r0, nd = (double)n;
    so.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
    s = autobal_rotor_stab_alloc(&p, &so, NULL);
    CHECK("handle", s != NULL);
    if (!s) return;
    for (a = 0; a < 3; a++) {
      autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, speeds[a]);
      for (k = 0; k < NT; k++) m0v[k] = (nd * (double)(k + 1) / (double)(NT + 1)) * mr / r0;
      CHECK_STATUS("sweep of the unbalance",
                   autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0v, NT, mg_s, vd_s), AUTOBAL_SUCCESS);
      for (b = 0; b < 2; b++) {
        autobal_rotor_ratio_set rs;
        const double m0_before = autobal_rotor_stab_get(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS);
        size_t nb = 0;
        CHECK_STATUS("margin set, n balls", autobal_rotor_stab_margin_ratio_set(s, deltas[b], &rs), AUTOBAL_SUCCESS);
        CHECK("m0 restored bitwise", autobal_rotor_stab_get(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS) == m0_before);
        missed += rs.n_missed;
        for (k = 0; k < NT; k++) {
          const double t = m0v[k] * r0 / mr;
          if (dist_crit(&rs, t, nd) < 2e-4 || vd_s[k] == AUTOBAL_ROTOR_VERDICT_NONE) continue;
          nchk++;
          if (in_set(&rs, t) != (mg_s[k] < -deltas[b])) {
            nb++;
            if (nb < 4)
              printf("  n %zu w %g delta %g t %.9g margin %.9g in_set %d\n", n, speeds[a], deltas[b], t, mg_s[k],
                     in_set(&rs, t));
          }
        }
        bad += nb;
        for (k = 0; k < rs.n_crit; k++) {
          const double t = rs.t_crit[k];
          const int lo_in = in_set(&rs, t - 1e-6), hi_in = in_set(&rs, t + 1e-6);
          double mg;
          int v;
          if (lo_in == hi_in || t < 1e-4 || t > nd - 1e-4) continue;
          autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, t * mr / r0);
          autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &mg, &v);
          crit_checked++;
          if (!(fabs(mg + deltas[b]) <= 1e-6 * (1.0 + deltas[b]))) {
            crit_bad++;
            printf("  n %zu critical t %.12g at w %g delta %g: margin %.12g\n", n, t, speeds[a], deltas[b], mg);
          }
        }
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0_before);
        if (b == 0) {
          autobal_rotor_unbalance_range ur;
          const double slo = 0.02 * nd * mr, shi = 0.98 * nd * mr;
          size_t j, n_in = 0, matched = 0;
          CHECK_STATUS("every unbalance (symmetric)", autobal_rotor_stab_every_unbalance(s, slo, shi, &ur), AUTOBAL_SUCCESS);
          for (j = 0; j < rs.n_crit; j++) {
            const double sc = rs.t_crit[j] * mr;
            size_t q;
            if (!(sc > slo && sc < shi)) continue;
            n_in++;
            for (q = 0; q < ur.n_crit; q++)
              if (fabs(ur.s_crit[q] - sc) <= 1e-7 * sc) matched++;
          }
          ev_checked++;
          CHECK("delta 0: the critical values equal every_unbalance's (symmetric fan)", n_in == ur.n_crit && matched == n_in);
        }
      }
    }
    /* the radius enters only through t: the same t at 1.6 r gives the same margin */
    {
      double r2[4], mg1, mg2;
      int v1, v2;
      const double ts[3] = {0.4, 1.3, 2.2};
      autobal_rotor_params q = p;
      autobal_rotor_stab *s2;
      size_t i;
      for (i = 0; i < n; i++) r2[i] = 0.16;
      q.plane[0].ball_radius = r2;
      s2 = autobal_rotor_stab_alloc(&q, &so, NULL);
      CHECK("handle 2", s2 != NULL);
      for (i = 0; s2 && i < 3; i++) {
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, 600.0);
        autobal_rotor_stab_set(s2, AUTOBAL_ROTOR_PARAM_OMEGA, 600.0);
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, ts[i] * 0.05 * 0.1 / r0);
        autobal_rotor_stab_set(s2, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, ts[i] * 0.05 * 0.16 / r0);
        autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &mg1, &v1);
        autobal_rotor_stab_margin(s2, AUTOBAL_ROTOR_STAB_POLY, &mg2, &v2);
        CHECK_CLOSE("margin independent of the radius at fixed t", mg2, mg1, 1e-8, 1e-9);
      }
      autobal_rotor_stab_free(s2);
    }
    autobal_rotor_stab_free(s);
  }
  printf("  fan sets: %zu sampled t compared, %zu mismatches; %zu verdict changes checked, %zu off; n_missed %zu\n",
         nchk, bad, crit_checked, crit_bad, missed);
  CHECK("sampled t agree with the n-ball sets", bad == 0 && nchk > 20000);
  CHECK("margin = -delta at every verdict change (n balls)", crit_bad == 0 && crit_checked > 0);
  CHECK("no missed crossing", missed == 0);
  CHECK("every-unbalance comparisons made", ev_checked == 6);
  /* the member rule every is refused for n >= 3 */
  {
    double m[3], r[3], h[3], psi[3], rate[3];
    autobal_rotor_params p = machine(3, m, r, h, psi, rate, 0.05, 0.1, 0.5);
    autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
    autobal_rotor_stab *s;
    autobal_rotor_ratio_set rs;
    so.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_EVERY;
    s = autobal_rotor_stab_alloc(&p, &so, NULL);
    CHECK_STATUS("every member, three balls: refused", autobal_rotor_stab_margin_ratio_set(s, 0.0, &rs), AUTOBAL_EUNSUPPORTED);
    CHECK_MSG("names unbalance_member", autobal_rotor_stab_errmsg(s), "unbalance_member");
    autobal_rotor_stab_free(s);
  }
}

static autobal_study_rotor_design_options small_opts(void) {
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  o.omega_min = 450.0;
  o.omega_max = 900.0;
  o.n_omega = 11;
  o.unbalance_min = 0.0005;
  o.unbalance_max = 0.004;
  o.margin = 0.2;
  o.mass_min = 0.02;
  o.mass_max = 0.08;
  o.n_mass = 3;
  o.radius_min = 0.04;
  o.radius_max = 0.15;
  o.n_radius = 6;
  o.damping_min = 0.1;
  o.damping_max = 1.0;
  o.n_damping = 3;
  o.n_best = 8;
  o.n_starts = 1;
  o.max_iter = 15;
  o.n_balls_min = 2;
  o.n_balls_max = 4;
  o.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
  o.threads = 1;
  return o;
}

/* -max over the grid speeds and NS unbalances of the POLY margin of design d (n balls); *allneg: every
 * sampled margin < -delta. */
static double sampled_margin(const autobal_study_rotor_design_options *o, const autobal_rotor_design *d,
                             int *allneg) {
  double m[16], r[16], h[16], psi[16], rate[16], worst = -INFINITY;
  const size_t n = d->n_balls;
  autobal_rotor_params p = machine(n, m, r, h, psi, rate, d->mass, d->radius, d->damping);
  autobal_rotor_stab *s;
  size_t k, j;
  p.plane[0].d = d->position;
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  *allneg = 1;
  if (!s) return NAN;
  for (k = 0; k < o->n_omega; k++) {
    const double w = o->omega_min + (o->omega_max - o->omega_min) * (double)k / (double)(o->n_omega - 1);
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
    for (j = 0; j < NS; j++)
      m0v[j] = (o->unbalance_min + (o->unbalance_max - o->unbalance_min) * (double)j / (double)(NS - 1)) / p.plane[0].r0;
    autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0v, NS, mg_s, vd_s);
    for (j = 0; j < NS; j++) {
      const double mg = vd_s[j] == AUTOBAL_ROTOR_VERDICT_NONE ? INFINITY : mg_s[j];
      worst = fmax(worst, mg);
      if (!(mg < -o->margin)) *allneg = 0;
    }
  }
  autobal_rotor_stab_free(s);
  /* n >= 3: the ball modes -h/m of the full system (the POLY margin is over Delta's roots) */
  if (n >= 3 && !(d->damping / d->mass > o->margin)) *allneg = 0;
  return n >= 3 ? fmin(-worst, d->damping / d->mass) : -worst;
}

static void test_search_n(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_design_options o = small_opts();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  size_t i, q, nbad = 0, ncount[5] = {0, 0, 0, 0, 0};
  int st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("search over n = 2..4", st, AUTOBAL_SUCCESS);
  if (st) {
    printf("  %s\n", err.message);
    autobal_study_rotor_design_summary_free(&S);
    return;
  }
  CHECK("three numbers of balls", S.n_n == 3 && S.n_balls[0] == 2 && S.n_balls[2] == 4);
  CHECK("designs ranked", S.n_designs > 0);
  for (i = 0; i < S.n_designs; i++) {
    const autobal_rotor_design *d = &S.designs[i];
    int allneg;
    const double up = sampled_margin(&o, d, &allneg), acc = 1e-3 * (1.0 + fabs(d->margin));
    if (d->n_balls <= 4) ncount[d->n_balls]++;
    printf("  design %zu: n %zu m %.4g r %.4g h %.4g rho %.6g sampled %.6g feasible %d recheck %d\n", i, d->n_balls,
           d->mass, d->radius, d->damping, d->margin, up, d->feasible, d->recheck);
    if (d->feasible && !allneg) nbad++;
    if (!(d->margin <= up + acc)) nbad++;
    if (isfinite(up) && !(d->margin >= up - 0.02 * fabs(up) - acc)) nbad++;
  }
  CHECK("every ranked design: verdict and robust margin agree with dense per-unbalance analyses", nbad == 0);
  CHECK("designs with three or more balls ranked", ncount[3] + ncount[4] > 0);
  {
    const size_t per = S.n_mass * S.n_damping * S.n_position;
    size_t b, bad1 = 0;
    for (b = 0; b < S.n_n; b++)
      for (i = 0; i < per; i++)
        for (q = 0; q < S.n_radius; q++) {
          const double m = S.mass[i / (S.n_damping * S.n_position)], r = S.radius[q];
          const int f = S.feasible[(b * per + i) * S.n_radius + q];
          if ((f == -1) != ((double)S.n_balls[b] * m * r <= o.unbalance_max)) bad1++;
        }
    CHECK("map: -1 exactly where n m r <= unbalance_max", bad1 == 0);
  }
  CHECK("the best config has n balls", S.best_config && strstr(S.best_config, "ball_mass = "));
  if (S.best_config && S.designs[0].n_balls >= 3)
    CHECK("n >= 3: the config says symmetric members", strstr(S.best_config, "symmetric members of the family only") != NULL);
  autobal_study_rotor_design_summary_free(&S);
  /* total_mass_max */
  o.total_mass_max = 0.1;
  o.n_best = 5;
  st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("search with a cap on the total ball mass", st, AUTOBAL_SUCCESS);
  if (!st) {
    const size_t per = S.n_mass * S.n_damping * S.n_position;
    size_t b, bad2 = 0, over = 0;
    for (b = 0; b < S.n_n; b++)
      for (i = 0; i < per; i++)
        for (q = 0; q < S.n_radius; q++) {
          const double m = S.mass[i / (S.n_damping * S.n_position)];
          const int f = S.feasible[(b * per + i) * S.n_radius + q];
          if ((f == -2) != ((double)S.n_balls[b] * m > 0.1)) bad2++;
        }
    for (i = 0; i < S.n_designs; i++) over += (double)S.designs[i].n_balls * S.designs[i].mass > 0.1 * (1.0 + 1e-12);
    CHECK("map: -2 exactly where n m > total_mass_max", bad2 == 0);
    CHECK("no ranked design over the cap", over == 0 && S.n_designs > 0);
  }
  autobal_study_rotor_design_summary_free(&S);
}

static void test_errors_n(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_design_options o = small_opts(), b;
  autobal_study_rotor_design_summary S;
  autobal_error err;
  b = o;
  b.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_EVERY;
  b.n_balls_max = 11; /* every member: 3 to 10 balls (test_rotor_design_every.c covers 3 and 4) */
  CHECK_STATUS("every member with n_balls_max 11 refused", autobal_study_rotor_design(&p, &b, NULL, &S, &err),
               AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("names unbalance_member", err.message, "unbalance_member = symmetric");
  CHECK_MSG("says 3 to 10 balls", err.message, "3 to 10 balls");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_EVERY;
  b.member_boxes = 999;
  CHECK_STATUS("member_boxes 999 refused", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names member_boxes", err.message, "member_boxes");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.n_balls_min = 1;
  CHECK_STATUS("n_balls_min 1", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names n_balls_min", err.message, "n_balls_min");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.n_balls_min = 4;
  b.n_balls_max = 3;
  CHECK_STATUS("min > max", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.n_balls_max = AUTOBAL_DESIGN_MAX_BALLS + 1;
  CHECK_STATUS("too many balls", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.total_mass_max = -1.0;
  CHECK_STATUS("negative cap", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names total_mass_max", err.message, "total_mass_max");
  autobal_study_rotor_design_summary_free(&S);
}

int main(void) {
  gsl_set_error_handler_off();
  test_fan_sets();
  test_search_n();
  test_errors_n();
  return check_summary();
}
