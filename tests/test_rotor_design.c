/* test_rotor_design.c: the design search (include/autobal/design.h, docs/rotor.md "Design") and its
 * exact building block autobal_rotor_stab_margin_ratio_set, against computations that do not use the
 * shifted crossing polynomial:
 *  - the t-set with margin delta at several speeds and margins: 4001 sampled t (POLY margins through
 *    autobal_rotor_stab_sweep of unbalance_mass) are inside the set exactly when their margin is
 *    < -delta (away from the critical t); at a critical t between sub-intervals of different verdict
 *    the margin equals -delta; the set is symmetric under t^2 -> 4 - t^2 (u depends on c^2 only);
 *    delta = 0 reproduces the critical unbalances of autobal_rotor_stab_every_unbalance;
 *  - the robust margin of a design against dense sampling over speeds and unbalances (an upper
 *    bound that the exact value must not exceed, and must come close to);
 *  - a small design search: every map point's verdict against sampled per-unbalance analyses at the
 *    grid speeds; every ranked design re-checked; the best design's config text parsed back through
 *    its numbers; the track-radius window is exact (its ends are where t_lo or t_hi meets a critical t);
 *  - error paths: two planes, three balls, unequal balls, full inertia, bad options. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

#define NT 4001

static double mg_s[NT], m0v[NT];
static int vd_s[NT];

static int in_set(const autobal_rotor_ratio_set *rs, double t) {
  size_t i;
  for (i = 0; i < rs->n; i++)
    if (rs->lo[i] < t && t < rs->hi[i]) return 1;
  return 0;
}

static double dist_crit(const autobal_rotor_ratio_set *rs, double t) {
  double d = fmin(t, 2.0 - t);
  size_t i;
  for (i = 0; i < rs->n_crit; i++) d = fmin(d, fabs(t - rs->t_crit[i]));
  return d;
}

static void test_ratio_set(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  const double mr = p.plane[0].ball_mass[0] * p.plane[0].ball_radius[0], r0 = p.plane[0].r0;
  const double speeds[4] = {300.0, 420.0, 500.0, 900.0}, deltas[3] = {0.0, 0.3, 1.0};
  size_t a, b, k, bad = 0, nchk = 0, nsym = 0, symbad = 0, crit_checked = 0, crit_bad = 0;
  CHECK("handle", s != NULL);
  if (!s) return;
  for (a = 0; a < 4; a++) {
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, speeds[a]);
    for (k = 0; k < NT; k++) m0v[k] = (2.0 * (double)(k + 1) / (double)(NT + 1)) * mr / r0;
    CHECK_STATUS("sweep of the unbalance", autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0v, NT, mg_s, vd_s),
                 AUTOBAL_SUCCESS);
    for (b = 0; b < 3; b++) {
      autobal_rotor_ratio_set rs;
      const double m0_before = autobal_rotor_stab_get(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS);
      size_t nb = 0;
      int st = autobal_rotor_stab_margin_ratio_set(s, deltas[b], &rs);
      CHECK_STATUS("margin set", st, AUTOBAL_SUCCESS);
      CHECK("m0 restored bitwise", autobal_rotor_stab_get(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS) == m0_before);
      CHECK("no missed crossing", rs.n_missed == 0);
      if (rs.n_missed) {
        size_t j;
        printf("  w %g delta %g: critical t", speeds[a], deltas[b]);
        for (j = 0; j < rs.n_crit; j++) printf(" %.12g", rs.t_crit[j]);
        printf("; set");
        for (j = 0; j < rs.n; j++) printf(" (%.12g, %.12g)", rs.lo[j], rs.hi[j]);
        printf("\n");
      }
      for (k = 0; k < NT; k++) {
        const double t = m0v[k] * r0 / mr;
        if (dist_crit(&rs, t) < 2e-4) continue;
        nchk++;
        if (in_set(&rs, t) != (mg_s[k] < -deltas[b])) {
          nb++;
          if (nb < 4)
            printf("  mismatch w %g delta %g t %.9g margin %.9g in_set %d\n", speeds[a], deltas[b], t, mg_s[k],
                   in_set(&rs, t));
        }
      }
      bad += nb;
      /* symmetry t^2 -> 4 - t^2 of the critical values */
      for (k = 0; k < rs.n_crit; k++) {
        const double tm = sqrt(4.0 - rs.t_crit[k] * rs.t_crit[k]);
        size_t j;
        double best = 1.0;
        if (rs.t_crit[k] < 1e-6 || tm > 2.0 - 1e-12) continue; /* the mirror of t ~ 0 is t ~ 2, not representable */
        for (j = 0; j < rs.n_crit; j++) best = fmin(best, fabs(rs.t_crit[j] - tm));
        nsym++;
        if (best > 1e-7) {
          symbad++;
          printf("  critical t %.12g: mirror %.12g not found (nearest %.3g away)\n", rs.t_crit[k], tm, best);
        }
      }
      /* at a critical t where the verdict changes, the margin is -delta (roots from the solver) */
      for (k = 0; k < rs.n_crit; k++) {
        const double t = rs.t_crit[k];
        const int lo_in = in_set(&rs, t - 1e-6), hi_in = in_set(&rs, t + 1e-6);
        double mg;
        int v;
        if (lo_in == hi_in || t < 1e-4 || t > 2.0 - 1e-4) continue; /* no closure at t ~ 0, 2 */
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, t * mr / r0);
        autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &mg, &v);
        crit_checked++;
        if (!(fabs(mg + deltas[b]) <= 1e-6 * (1.0 + deltas[b]))) {
          crit_bad++;
          printf("  critical t %.12g at w %g delta %g: margin %.12g\n", t, speeds[a], deltas[b], mg);
        }
      }
      autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0_before);
      /* delta = 0: the same critical unbalances as the every-unbalance analysis */
      if (b == 0) {
        autobal_rotor_unbalance_range ur;
        const double slo = 0.02 * mr, shi = 1.98 * mr;
        size_t j, n_in = 0, matched = 0;
        CHECK_STATUS("every unbalance", autobal_rotor_stab_every_unbalance(s, slo, shi, &ur), AUTOBAL_SUCCESS);
        for (j = 0; j < rs.n_crit; j++) {
          const double sc = rs.t_crit[j] * mr;
          size_t q;
          if (!(sc > slo && sc < shi)) continue;
          n_in++;
          for (q = 0; q < ur.n_crit; q++)
            if (fabs(ur.s_crit[q] - sc) <= 1e-7 * sc) matched++;
        }
        printf("  w %g: %zu critical t in range, %zu critical unbalances of every_unbalance, %zu matched\n", speeds[a],
               n_in, ur.n_crit, matched);
        CHECK("delta 0: the critical values equal every_unbalance's", n_in == ur.n_crit && matched == n_in);
      }
    }
  }
  printf("  %zu sampled t compared, %zu mismatches; %zu critical t checked for symmetry, %zu off; %zu verdict changes "
         "checked, %zu off\n",
         nchk, bad, nsym, symbad, crit_checked, crit_bad);
  CHECK("sampled t agree with the set", bad == 0 && nchk > 40000);
  CHECK("critical t symmetric under t^2 -> 4 - t^2", symbad == 0 && nsym > 0);
  CHECK("margin = -delta at every verdict change", crit_bad == 0 && crit_checked > 0);
  autobal_rotor_stab_free(s);
}

/* Sampled worst margin of a design over n_w speeds x n_s unbalances (an upper bound of -rho). */
static double sampled_worst(const autobal_rotor_params *base, const autobal_rotor_design *d, double wlo, double whi,
                            size_t n_w, double slo, double shi, size_t n_s) {
  autobal_rotor_params p = *base;
  double m[2] = {d->mass, d->mass}, r[2] = {d->radius, d->radius}, h[2] = {d->damping, d->damping}, worst = -INFINITY;
  autobal_rotor_stab *s;
  size_t i, j;
  p.plane[0].ball_mass = m;
  p.plane[0].ball_radius = r;
  p.plane[0].ball_damping = h;
  p.plane[0].d = d->position;
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  if (!s) return NAN;
  for (i = 0; i < n_w; i++) {
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, wlo + (whi - wlo) * (double)i / (double)(n_w - 1));
    for (j = 0; j < n_s; j++) {
      double mg;
      int v;
      autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS,
                             (slo + (shi - slo) * (double)j / (double)(n_s - 1)) / p.plane[0].r0);
      autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &mg, &v);
      worst = fmax(worst, mg);
    }
  }
  autobal_rotor_stab_free(s);
  return worst;
}

static void test_search(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  size_t i, j, k, q, bad = 0, checked = 0;
  int st;
  o.omega_min = 450.0;
  o.omega_max = 900.0;
  o.n_omega = 11;
  o.unbalance_min = 0.0005;
  o.unbalance_max = 0.004;
  o.margin = 0.2;
  o.n_mass = 4;
  o.n_damping = 4;
  o.n_radius = 6;
  o.n_best = 4;
  o.n_starts = 1;
  o.max_iter = 30;
  st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("design search", st, AUTOBAL_SUCCESS);
  if (st) {
    printf("  %s\n", err.message);
    autobal_study_rotor_design_summary_free(&S);
    return;
  }
  printf("  %zu feasible map points, %zu designs, %zu exact tests, %zu margin evaluations, %zu optimizer evaluations\n",
         S.n_feasible, S.n_designs, S.ratio_sets, S.margin_evaluations, S.optimizer_evaluations);
  CHECK("some feasible, some not", S.n_feasible > 0 && S.n_feasible < S.n_mass * S.n_damping * S.n_radius);
  /* every map point against sampled per-unbalance margins at the grid speeds */
  for (i = 0; i < S.n_mass; i++)
    for (j = 0; j < S.n_damping; j++)
      for (q = 0; q < S.n_radius; q++) {
        autobal_rotor_design d;
        const int f = S.feasible[(i * S.n_damping + j) * S.n_radius + q];
        double worst;
        memset(&d, 0, sizeof d);
        d.mass = S.mass[i];
        d.damping = S.damping[j];
        d.radius = S.radius[q];
        d.position = p.plane[0].d;
        if (f == -1) {
          if (!(o.unbalance_max >= 2.0 * d.mass * d.radius)) bad++;
          continue;
        }
        worst = sampled_worst(&p, &d, o.omega_min, o.omega_max, o.n_omega, o.unbalance_min, o.unbalance_max, 61);
        checked++;
        /* feasible: every sample below -margin; infeasible: some sample above -margin, unless the
           worst point falls between samples (then the sample must at least come close) */
        if (f == 1 && !(worst < -o.margin)) bad++;
        if (f == 0 && !(worst > -o.margin - 0.02)) {
          bad++;
          printf("  infeasible point m %g h %g r %g: sampled worst %g\n", d.mass, d.damping, d.radius, worst);
        }
      }
  printf("  %zu map points compared with 11 x 61 sampled analyses, %zu disagree\n", checked, bad);
  CHECK("map against sampling", bad == 0 && checked > 0);
  /* ranked designs: sorted, re-checked, their rho consistent with dense sampling */
  CHECK("designs", S.n_designs >= 1 && S.designs[0].feasible == 1 && S.designs[0].recheck == 1);
  for (k = 0; k < S.n_designs; k++) {
    const autobal_rotor_design *d = &S.designs[k];
    const double worst = sampled_worst(&p, d, o.omega_min, o.omega_max, o.n_omega, o.unbalance_min, o.unbalance_max, 401);
    double rho2;
    printf("  design %zu: m %.6g kg r %.6g m h %.6g kg/s rho %.6g recheck %d (%.6g) source %d; sampled -worst %.6g\n", k,
           d->mass, d->radius, d->damping, d->margin, d->recheck, d->recheck_margin, d->source, -worst);
    /* rho is a verified lower bound (the exact test passes there) of -max margin; sampling gives an upper bound */
    CHECK("rho <= sampled -worst", d->margin <= -worst + 1e-9);
    CHECK("rho close to sampled -worst", d->margin >= -worst - 2e-3 * (1.0 + fabs(worst)) - 0.02 * fabs(worst));
    if (k > 0 && S.designs[0].feasible && d->feasible) CHECK("ranked by rho", d->margin <= S.designs[0].margin);
    CHECK_STATUS("design margin alone", autobal_study_rotor_design_margin(&p, &o, d, &rho2, &err), AUTOBAL_SUCCESS);
    CHECK_CLOSE("design margin alone = the summary's", rho2, d->margin, 0.0, 1e-12);
  }
  /* the optimizer does not lose: its design is at least as good as its start */
  {
    double best_grid = -INFINITY, best_nm = -INFINITY;
    for (k = 0; k < S.n_designs; k++) {
      if (S.designs[k].source == 0) best_grid = fmax(best_grid, S.designs[k].margin);
      else best_nm = fmax(best_nm, S.designs[k].margin);
    }
    printf("  best grid rho %.6g, best optimizer rho %.6g\n", best_grid, best_nm);
    CHECK("optimizer >= best grid design", best_nm >= best_grid - 1e-3 * (1 + fabs(best_grid)));
  }
  /* the radius window of a cell is exact: just inside it feasible, just outside not (sampled margins) */
  {
    size_t c, done = 0, wbad = 0;
    for (c = 0; c < S.n_mass * S.n_damping && done < 3; c++) {
      const double wl = S.window_lo[c], wh = S.window_hi[c];
      autobal_rotor_design d;
      int e;
      if (isnan(wl)) continue;
      memset(&d, 0, sizeof d);
      d.mass = S.mass[c / S.n_damping];
      d.damping = S.damping[c % S.n_damping];
      d.position = p.plane[0].d;
      for (e = 0; e < 2; e++) {
        const double end = e == 0 ? wl : wh, in = e == 0 ? 1.0 + 1e-4 : 1.0 - 1e-4;
        double rho_in, rho_out;
        if ((e == 0 && wl <= S.radius[0]) || (e == 1 && wh >= S.radius[S.n_radius - 1]))
          continue; /* a bound of the box, not of the window */
        d.radius = end * in;
        autobal_study_rotor_design_margin(&p, &o, &d, &rho_in, &err);
        d.radius = end / in;
        autobal_study_rotor_design_margin(&p, &o, &d, &rho_out, &err);
        printf("  window end %.9g m: rho inside %.6g, outside %.6g (required %g)\n", end, rho_in, rho_out, o.margin);
        if (!(rho_in > o.margin - 5e-3 && rho_out < o.margin + 5e-3 && rho_in > rho_out)) wbad++;
        done++;
      }
    }
    CHECK("radius window ends exact", wbad == 0 && done > 0);
  }
  /* the config text carries the design */
  {
    char needle[128];
    CHECK("best config", S.best_config != NULL);
    if (S.best_config) {
      snprintf(needle, sizeof needle, "ball_mass = %.17g, %.17g", S.designs[0].mass, S.designs[0].mass);
      CHECK_MSG("config has the ball mass", S.best_config, needle);
      snprintf(needle, sizeof needle, "ball_radius = %.17g, %.17g", S.designs[0].radius, S.designs[0].radius);
      CHECK_MSG("config has the radius", S.best_config, needle);
      CHECK_MSG("config has the supports", S.best_config, "[supports]");
    }
  }
  autobal_study_rotor_design_summary_free(&S);
}

static void test_errors(void) {
  autobal_rotor_params p = autobal_rotor_params_default(), q;
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  double m3[3] = {0.05, 0.05, 0.05}, r3[3] = {0.1, 0.1, 0.1}, h3[3] = {0.1, 0.1, 0.1}, m2[2] = {0.05, 0.06};
  autobal_rotor_stab *s;
  autobal_rotor_ratio_set rs;
  o.omega_min = 450.0;
  o.omega_max = 900.0;
  o.unbalance_min = 0.0005;
  o.unbalance_max = 0.004;
  q = p;
  q.plane[0].n_balls = 3;
  q.plane[0].ball_mass = m3;
  q.plane[0].ball_radius = r3;
  q.plane[0].ball_damping = h3;
  q.plane[0].ball_psi = NULL;
  q.plane[0].ball_rate = NULL;
  CHECK_STATUS("three balls refused", autobal_study_rotor_design(&q, &o, NULL, &S, &err), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("names the key", err.message, "ball_mass");
  autobal_study_rotor_design_summary_free(&S);
  q = p;
  q.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  CHECK_STATUS("full inertia refused", autobal_study_rotor_design(&q, &o, NULL, &S, &err), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("names the key", err.message, "inertia");
  autobal_study_rotor_design_summary_free(&S);
  q = p;
  q.n_planes = 2;
  q.plane[1] = p.plane[0];
  q.plane[1].d = -0.1;
  CHECK_STATUS("two planes refused", autobal_study_rotor_design(&q, &o, NULL, &S, &err), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("names the key", err.message, "plane2");
  autobal_study_rotor_design_summary_free(&S);
  {
    autobal_study_rotor_design_options b = o;
    b.omega_min = 900.0;
    CHECK_STATUS("omega_min >= omega_max", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
    CHECK_MSG("names the field", err.message, "omega_min");
    autobal_study_rotor_design_summary_free(&S);
    b = o;
    b.margin = -1.0;
    CHECK_STATUS("negative margin", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
    CHECK_MSG("names the field", err.message, "margin");
    autobal_study_rotor_design_summary_free(&S);
    b = o;
    b.unbalance_min = NAN;
    CHECK_STATUS("no unbalance range", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
    CHECK_MSG("names the field", err.message, "unbalance_min");
    autobal_study_rotor_design_summary_free(&S);
  }
  q = p;
  q.plane[0].ball_mass = m2;
  s = autobal_rotor_stab_alloc(&q, NULL, NULL);
  CHECK_STATUS("unequal balls refused by the margin set", autobal_rotor_stab_margin_ratio_set(s, 0.0, &rs),
               AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("says identical", autobal_rotor_stab_errmsg(s), "identical");
  CHECK_STATUS("NULL out", autobal_rotor_stab_margin_ratio_set(s, 0.0, NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("NULL handle", autobal_rotor_stab_margin_ratio_set(NULL, 0.0, &rs), AUTOBAL_EINVAL);
  autobal_rotor_stab_free(s);
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  CHECK_STATUS("delta NaN", autobal_rotor_stab_margin_ratio_set(s, NAN, &rs), AUTOBAL_EINVAL);
  autobal_rotor_stab_free(s);
}

/* Transients of designs (options.n_transient): a design fixed by its bounds (one candidate).
 * (a) unbalance_max = 7000 g mm with the default balls (t = 1.4): the exact single-unbalance
 *     analysis finds the balanced motion unstable there (checked here), so no member started at that
 *     unbalance can settle to it: P(balance) <= 1/2 (half the members have that unbalance);
 * (b) a robust design (rho > 4 1/s by the exact test) balances from every start: P = 1, times finite;
 * (c) a search with three designs run: rank_by = p_balance and time order them by their own numbers,
 *     rank_by = margin leaves the ranking of n_transient = 0 unchanged. */
static void one_design(autobal_rotor_params *p, autobal_study_rotor_design_options *o, double m, double r, double h) {
  o->mass_min = o->mass_max = m;
  o->radius_min = o->radius_max = r;
  o->damping_min = o->damping_max = h;
  o->n_starts = 0;
  o->n_best = 1;
  o->n_transient = 1;
  (void)p;
}

static void test_transients(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default(), b;
  autobal_study_rotor_design_summary S, S0;
  autobal_error err;
  size_t i;
  int st;
  o.omega_min = 450.0;
  o.omega_max = 900.0;
  o.n_omega = 11;
  o.unbalance_min = 0.0005;
  o.unbalance_max = 0.007;
  o.margin = 0.0;
  b = o;
  one_design(&p, &b, 0.05, 0.1, 0.1);
  {
    autobal_rotor_params q = p;
    autobal_rotor_stab *s;
    double mg;
    int v;
    q.omega = 900.0;
    q.plane[0].m0 = o.unbalance_max / q.plane[0].r0;
    s = autobal_rotor_stab_alloc(&q, NULL, NULL);
    st = autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &mg, &v);
    printf("  (a) exact margin at 900 rad/s, 7000 g mm: %g 1/s\n", mg);
    CHECK("(a) the balanced motion is unstable at the corner", st == AUTOBAL_SUCCESS && mg > 0.0);
    autobal_rotor_stab_free(s);
  }
  {
    autobal_rotor_design d;
    memset(&d, 0, sizeof d);
    d.mass = 0.05;
    d.radius = 0.1;
    d.damping = 0.1;
    d.position = p.plane[0].d;
    st = autobal_study_rotor_design_margin(&p, &b, &d, &d.margin, &err);
    CHECK_STATUS("(a) robust margin", st, AUTOBAL_SUCCESS);
    st = autobal_study_rotor_design_transients(&p, &b, &d, &err);
    CHECK_STATUS("(a) transients of one design", st, AUTOBAL_SUCCESS);
    printf("  (a) rho %g, P %zu/%zu, median %g s, worst %g s\n", d.margin, d.n_balanced, d.n_runs, d.ttb_median,
           d.ttb_worst);
    CHECK("(a) infeasible by the exact analysis", d.margin < 0.0);
    CHECK("(a) 3 x 3 starts x 2 unbalances x 2 speeds", d.n_runs == 36);
    CHECK("(a) P(balance) <= 1/2", d.p_balance <= 0.5 && d.p_balance == (double)d.n_balanced / 36.0);
    CHECK("(a) worst time infinite", isinf(d.ttb_worst));
  }
  b = o;
  b.unbalance_max = 0.004;
  one_design(&p, &b, 0.0758, 0.05, 0.88);
  st = autobal_study_rotor_design(&p, &b, NULL, &S, &err);
  CHECK_STATUS("(b) design with transients", st, AUTOBAL_SUCCESS);
  if (st == AUTOBAL_SUCCESS && S.n_designs == 1) {
    const autobal_rotor_design *d = &S.designs[0];
    printf("  (b) rho %g, P %zu/%zu, median %g s, worst %g s\n", d->margin, d->n_balanced, d->n_runs, d->ttb_median,
           d->ttb_worst);
    CHECK("(b) robust by the exact analysis", d->feasible && d->margin > 1.0);
    CHECK("(b) P(balance) = 1", d->n_runs == 36 && d->p_balance == 1.0);
    CHECK("(b) times finite, 0 < median <= worst < t_end = 10 s",
          d->ttb_median > 0.0 && d->ttb_median <= d->ttb_worst && d->ttb_worst < 10.0); /* t_end: 10 s by default without a profile */
  } else CHECK("(b) one design", 0);
  autobal_study_rotor_design_summary_free(&S);
  /* (c) the ranking keys */
  b = o;
  b.unbalance_max = 0.004;
  b.n_mass = 3;
  b.n_damping = 3;
  b.n_radius = 4;
  b.n_best = 4;
  b.n_starts = 0;
  b.n_start = 2;
  b.n_transient_speeds = 1;
  st = autobal_study_rotor_design(&p, &b, NULL, &S0, &err);
  CHECK_STATUS("(c) search without transients", st, AUTOBAL_SUCCESS);
  b.n_transient = 3;
  st = autobal_study_rotor_design(&p, &b, NULL, &S, &err);
  CHECK_STATUS("(c) rank_by margin with transients", st, AUTOBAL_SUCCESS);
  if (st == AUTOBAL_SUCCESS && S.n_designs == S0.n_designs && S.n_designs >= 3) {
    int same = 1;
    for (i = 0; i < S.n_designs; i++)
      same &= S.designs[i].mass == S0.designs[i].mass && S.designs[i].radius == S0.designs[i].radius &&
              S.designs[i].damping == S0.designs[i].damping && S.designs[i].margin == S0.designs[i].margin;
    CHECK("(c) rank_by = margin: the ranking of n_transient = 0, bit for bit", same);
    CHECK("(c) the first three ran, the fourth not",
          S.designs[2].n_runs == 8 && (S.n_designs < 4 || (S.designs[3].n_runs == 0 && isnan(S.designs[3].p_balance))));
  } else CHECK("(c) same designs", 0);
  autobal_study_rotor_design_summary_free(&S);
  {
    int key;
    for (key = AUTOBAL_DESIGN_RANK_TIME; key <= AUTOBAL_DESIGN_RANK_P_BALANCE; key++) {
      int ordered = 1;
      b.rank_by = key;
      st = autobal_study_rotor_design(&p, &b, NULL, &S, &err);
      CHECK_STATUS("(c) rank_by time / p_balance", st, AUTOBAL_SUCCESS);
      for (i = 0; st == AUTOBAL_SUCCESS && i + 1 < 3 && i + 1 < S.n_designs; i++) {
        const autobal_rotor_design *x = &S.designs[i], *y = &S.designs[i + 1];
        printf("  rank_by %d: #%zu P %g worst %g median %g rho %g\n", key, i, x->p_balance, x->ttb_worst, x->ttb_median,
               x->margin);
        if (x->feasible != y->feasible) ordered &= x->feasible > y->feasible;
        else if (key == AUTOBAL_DESIGN_RANK_P_BALANCE)
          ordered &= x->p_balance > y->p_balance || (x->p_balance == y->p_balance && x->ttb_worst <= y->ttb_worst);
        else
          ordered &= x->ttb_worst < y->ttb_worst || (x->ttb_worst == y->ttb_worst && x->ttb_median <= y->ttb_median);
      }
      CHECK("(c) ordered by the stated key", ordered);
      /* the same three designs as by margin, only reordered */
      if (st == AUTOBAL_SUCCESS) {
        size_t k, found = 0;
        for (i = 0; i < 3; i++)
          for (k = 0; k < 3; k++) found += S.designs[i].mass == S0.designs[k].mass && S.designs[i].radius == S0.designs[k].radius &&
                                         S.designs[i].damping == S0.designs[k].damping;
        CHECK("(c) the same three designs, reordered", found == 3);
        {
          char needle[128];
          snprintf(needle, sizeof needle, "ball_mass = %.17g, %.17g", S.designs[0].mass, S.designs[0].mass);
          CHECK("(c) best config is the first design's", S.best_config && strstr(S.best_config, needle));
        }
      }
      autobal_study_rotor_design_summary_free(&S);
    }
  }
  autobal_study_rotor_design_summary_free(&S0);
}

static int same_designs(const autobal_rotor_design *a, const autobal_rotor_design *b, size_t n) {
  size_t i;
  int same = 1;
  for (i = 0; i < n; i++)
    same &= !memcmp(&a[i].mass, &b[i].mass, sizeof(double)) && !memcmp(&a[i].radius, &b[i].radius, sizeof(double)) &&
            !memcmp(&a[i].damping, &b[i].damping, sizeof(double)) &&
            !memcmp(&a[i].position, &b[i].position, sizeof(double)) &&
            !memcmp(&a[i].margin, &b[i].margin, sizeof(double)) &&
            !memcmp(&a[i].recheck_margin, &b[i].recheck_margin, sizeof(double)) && a[i].feasible == b[i].feasible &&
            a[i].source == b[i].source && a[i].recheck == b[i].recheck;
  return same;
}

/* OpenMP over the map cells, the candidates' margins, the optimizer's starts and the re-checks: 1 and 2 threads give the same summary
 * bit for bit (map, windows, counts, ranked designs); a 4-parameter search (the position free). */
static void test_threads(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  autobal_study_rotor_design_summary S1, S2;
  autobal_error err;
  int st1, st2;
  o.omega_min = 450.0;
  o.omega_max = 900.0;
  o.n_omega = 11;
  o.unbalance_min = 0.0005;
  o.unbalance_max = 0.004;
  o.margin = 0.2;
  o.n_mass = 3;
  o.n_damping = 3;
  o.n_radius = 5;
  o.position_min = 0.05;
  o.position_max = 0.15;
  o.n_position = 3;
  o.n_best = 4;
  o.n_starts = 3;
  o.max_iter = 20;
  o.threads = 1;
  st1 = autobal_study_rotor_design(&p, &o, NULL, &S1, &err);
  o.threads = 2;
  st2 = autobal_study_rotor_design(&p, &o, NULL, &S2, &err);
  CHECK("threads: both searches ran", st1 == AUTOBAL_SUCCESS && st2 == AUTOBAL_SUCCESS);
  if (st1 == AUTOBAL_SUCCESS && st2 == AUTOBAL_SUCCESS) {
    const size_t nc = S1.n_mass * S1.n_damping * S1.n_position;
    printf("  threads: %zu feasible, %zu exact tests, %zu verdicts, %zu designs\n", S1.n_feasible, S1.ratio_sets,
           S1.margin_evaluations, S1.n_designs);
    CHECK("threads: some feasible, some not", S1.n_feasible > 0 && S1.n_feasible < nc * S1.n_radius);
    CHECK("threads: counts equal", S1.n_feasible == S2.n_feasible && S1.ratio_sets == S2.ratio_sets &&
                                       S1.margin_evaluations == S2.margin_evaluations &&
                                       S1.optimizer_evaluations == S2.optimizer_evaluations && S1.n_mass_done == S2.n_mass_done);
    CHECK("threads: map bit for bit", !memcmp(S1.feasible, S2.feasible, nc * S1.n_radius * sizeof *S1.feasible) &&
                                          !memcmp(S1.window_lo, S2.window_lo, nc * sizeof *S1.window_lo) &&
                                          !memcmp(S1.window_hi, S2.window_hi, nc * sizeof *S1.window_hi));
    CHECK("threads: ranked designs bit for bit",
          S1.n_designs == S2.n_designs && S1.n_designs > 0 &&
              same_designs(S1.designs, S2.designs, S1.n_designs) && S1.best_config && S2.best_config &&
              !strcmp(S1.best_config, S2.best_config));
  }
  autobal_study_rotor_design_summary_free(&S1);
  autobal_study_rotor_design_summary_free(&S2);
}

int main(void) {
  gsl_set_error_handler_off();
  test_ratio_set();
  test_search();
  test_errors();
  test_transients();
  test_threads();
  return check_summary();
}
