/* test_rotor_design2.c: `autobal rotor design` with two planes (options.planes = 2; docs/rotor.md
 * "Design", "Two planes"), against analyses that use neither the crossing polynomials of the slices
 * nor the box search: the closed 16x16 matrix's margin (method CLOSED) at single (plane-1 unbalance,
 * plane-2 unbalance, relative phase) points.
 *  - every map cell marked feasible (1): stable at every (s1, s2, phase) of a dense sample at every grid
 *    speed (s1 on 13 values, s2 on plane 2's grid values (where the map is exact) and between them,
 *    phase on 24 values of [0, pi)); every cell marked not stable (0): some point of a dense sample at
 *    some grid speed is unstable;
 *  - every ranked design that the certification calls stable (recheck 1): stable at a dense sample;
 *    its margin is -(the largest margin met) and no dense sample is far below it (the margin of a
 *    sampled point cannot exceed the largest margin by much when the grid is fine);
 *  - the map does not depend on the number of threads (bit for bit);
 *  - the refusals, each naming its key. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"
#include "rotor_two_planes.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static autobal_study_rotor_design_options small_options(void) {
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  o.planes = 2;
  o.omega_min = 471.2389;
  o.omega_max = 942.4778;
  o.n_omega = 4;
  o.unbalance_min = 5e-4;
  o.unbalance_max = 3e-3;
  o.unbalance2_min = 5e-4;
  o.unbalance2_max = 2.5e-3;
  o.n_unbalance2 = 4;
  o.margin = 0.2;
  o.mass_min = 0.03;
  o.mass_max = 0.06;
  o.n_mass = 2;
  o.radius_min = 0.06;
  o.radius_max = 0.12;
  o.n_radius = 3;
  o.damping_min = 0.1;
  o.damping_max = 0.6;
  o.n_damping = 3;
  o.n_best = 2;
  o.n_starts = 0; /* the optimizer: test_nelder_mead */
  o.threads = 1;
  return o;
}

/* The largest closed-matrix margin over a dense sample at design (m, h, r) and speed w; s2 on n2
 * values from lo to hi (and, with between = 1, the midpoints between them). */
static double dense_max(autobal_rotor_stab *s, const autobal_study_rotor_design_options *o, double m, double h, double r,
                        double w, int between, size_t *n_unstable, size_t *n_eval) {
  const size_t n1 = 13, nph = 24, n2 = o->n_unbalance2;
  double worst = -INFINITY;
  size_t a, b, c, e;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_BALL_MASS, m);
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, h);
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_BALL_RADIUS), r);
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(1, AUTOBAL_ROTOR_PLANE_BALL_RADIUS), r);
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  for (b = 0; b < (between ? 2 * n2 - 1 : n2); b++) {
    const double f2 = between ? (double)b / (double)(2 * n2 - 2) : (double)b / (double)(n2 - 1);
    const double s2 = o->unbalance2_min + (o->unbalance2_max - o->unbalance2_min) * f2;
    for (a = 0; a < n1; a++) {
      const double s1 = o->unbalance_min + (o->unbalance_max - o->unbalance_min) * (double)a / (double)(n1 - 1);
      for (c = 0; c < nph; c++) {
        const double ph = M_PI * ((double)c + 0.5) / (double)nph;
        double mg = NAN;
        int v = 0;
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_M0), s1 / 0.1);
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(1, AUTOBAL_ROTOR_PLANE_M0), s2 / 0.09);
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_PLANE(1, AUTOBAL_ROTOR_PLANE_PSI0), ph);
        e = (size_t)autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_CLOSED, &mg, &v);
        (*n_eval)++;
        if (e != 0 || !(mg < 0.0)) (*n_unstable)++;
        if (mg > worst) worst = mg;
      }
    }
  }
  return worst;
}

static void test_search(void) {
  autobal_rotor_params p = rotor_two_planes(500.0);
  autobal_study_rotor_design_options o = small_options();
  autobal_study_rotor_design_summary S, S1, S2;
  autobal_error err;
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  size_t i, j, q, k, n1 = 0, n0 = 0, bad1 = 0, bad0 = 0, neval = 0;
  double w[4];
  CHECK("handle", s != NULL);
  if (!s) return;
  for (k = 0; k < o.n_omega; k++) w[k] = o.omega_min + (o.omega_max - o.omega_min) * (double)k / (double)(o.n_omega - 1);
  w[o.n_omega - 1] = o.omega_max;
  CHECK_STATUS("two-plane search", autobal_study_rotor_design(&p, &o, NULL, &S, &err), AUTOBAL_SUCCESS);
  if (S.ranked == 0 || !S.feasible) {
    printf("  %s\n", err.message);
    autobal_rotor_stab_free(s);
    autobal_study_rotor_design_summary_free(&S);
    return;
  }
  CHECK("planes recorded", S.planes == 2 && S.n_position == 1 && S.position[0] == 0.10);
  /* the map against dense samples */
  for (i = 0; i < S.n_mass; i++)
    for (j = 0; j < S.n_damping; j++)
      for (q = 0; q < S.n_radius; q++) {
        const size_t idx = (i * S.n_damping + j) * S.n_radius + q;
        const int f = S.feasible[idx];
        size_t nu = 0;
        if (f == 1) {
          n1++;
          for (k = 0; k < o.n_omega; k++) dense_max(s, &o, S.mass[i], S.damping[j], S.radius[q], w[k], 1, &nu, &neval);
          if (nu) {
            bad1++;
            printf("  feasible cell %g g %g kg/s %g mm: %zu unstable samples\n", S.mass[i] * 1e3, S.damping[j],
                   S.radius[q] * 1e3, nu);
          }
        } else if (f == 0 && isnan(S.margin_map[idx])) {
          n0++;
          for (k = 0; k < o.n_omega && nu == 0; k++)
            dense_max(s, &o, S.mass[i], S.damping[j], S.radius[q], w[k], 0, &nu, &neval);
          if (nu == 0) {
            bad0++;
            printf("  not-stable cell %g g %g kg/s %g mm: no unstable sample\n", S.mass[i] * 1e3, S.damping[j],
                   S.radius[q] * 1e3);
          }
        } else if (f == -1) {
          CHECK("-1 exactly where 2 m r <= the largest unbalance", !(2.0 * S.mass[i] * S.radius[q] > 3e-3));
        }
      }
  printf("  map: %zu feasible and %zu not-stable cells checked by %zu closed-matrix samples\n", n1, n0, neval);
  CHECK("the case has feasible and not-stable cells", n1 >= 2 && n0 >= 2);
  CHECK("feasible cells stable at every dense sample", bad1 == 0);
  CHECK("not-stable cells have an unstable dense sample", bad0 == 0);
  /* the ranked designs */
  CHECK("ranked designs", S.n_designs >= 1);
  for (i = 0; i < S.n_designs; i++) {
    const autobal_rotor_design *d = &S.designs[i];
    size_t nu = 0;
    double worst = -INFINITY;
    CHECK("certification ran at every speed", d->n_certify_run == o.n_omega && d->n_certified <= o.n_omega);
    if (d->recheck != 1) continue;
    for (k = 0; k < o.n_omega; k++)
      worst = fmax(worst, dense_max(s, &o, d->mass, d->damping, d->radius, w[k], 1, &nu, &neval));
    CHECK("a certified-stable design is stable at every dense sample", nu == 0);
    /* the reported margin is -(largest margin met at the points evaluated): a denser sample meets at
       least about as large a margin, never one much smaller (the slowest mode hardly moves with s, phase) */
    CHECK("reported margin against the dense samples", -worst <= d->margin * 1.05 + 1e-6 && -worst >= 0.5 * d->margin);
    printf("  design %zu: %g g %g mm %g kg/s margin %g, dense -max %g, certified %zu of %zu speeds\n", i, d->mass * 1e3,
           d->radius * 1e3, d->damping, d->margin, -worst, d->n_certified, d->n_certify_run);
  }
  CHECK("the best is feasible", S.designs[0].feasible == 1 && S.designs[0].recheck == 1);
  CHECK("best config has both planes", S.best_config && strstr(S.best_config, "[plane2]") &&
                                           strstr(S.best_config, "d = -0.12"));
  /* threads: the map bit for bit */
  o.unbalance2_boxes = -1;
  o.threads = 1;
  CHECK_STATUS("map, 1 thread", autobal_study_rotor_design(&p, &o, NULL, &S1, &err), AUTOBAL_SUCCESS);
  o.threads = 2;
  CHECK_STATUS("map, 2 threads", autobal_study_rotor_design(&p, &o, NULL, &S2, &err), AUTOBAL_SUCCESS);
  if (S1.feasible && S2.feasible) {
    const size_t n = S.n_mass * S.n_damping * S.n_radius;
    CHECK("1 and 2 threads: the same map", !memcmp(S1.feasible, S2.feasible, n * sizeof *S1.feasible) &&
                                               !memcmp(S1.margin_map, S2.margin_map, n * sizeof *S1.margin_map));
    CHECK("without certification the same map as with", !memcmp(S.feasible, S1.feasible, n * sizeof *S1.feasible));
    CHECK("without certification: recheck -1", S1.n_designs >= 1 && S1.designs[0].recheck == -1 &&
                                                   S1.designs[0].n_certified == 0);
  }
  autobal_study_rotor_design_summary_free(&S1);
  autobal_study_rotor_design_summary_free(&S2);
  autobal_study_rotor_design_summary_free(&S);
  autobal_rotor_stab_free(s);
}

static void test_refusals(void) {
  autobal_rotor_params p = rotor_two_planes(500.0), one = autobal_rotor_params_default();
  autobal_study_rotor_design_options o = small_options(), b;
  autobal_study_rotor_design_summary S;
  autobal_error err;
  CHECK("default planes = 1", autobal_study_rotor_design_options_default().planes == 1);
  CHECK_STATUS("planes = 2 with one plane", autobal_study_rotor_design(&one, &o, NULL, &S, &err), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("names [plane2]", err.message, "[plane2]");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.planes = 3;
  CHECK_STATUS("planes = 3", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names planes", err.message, "planes = 3: allowed 1 or 2");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.planes = 1;
  CHECK_STATUS("two-plane machine, planes = 1", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("says planes = 2", err.message, "planes = 2");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.unbalance2_min = 3e-3;
  b.unbalance2_max = 1e-3;
  CHECK_STATUS("unbalance2 range", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names unbalance2_min", err.message, "unbalance2_min");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.n_unbalance2 = 1;
  CHECK_STATUS("n_unbalance2", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names n_unbalance2", err.message, "n_unbalance2 = 1 must be in [2, 100]");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.position_min = 0.0;
  b.position_max = 0.2;
  CHECK_STATUS("position", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("names position_min", err.message, "position_min");
  autobal_study_rotor_design_summary_free(&S);
  b = o;
  b.n_balls_max = 3;
  b.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
  CHECK_STATUS("three balls", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("names n_balls_max", err.message, "n_balls_max");
  autobal_study_rotor_design_summary_free(&S);
  {
    autobal_rotor_design d;
    double rho = 0.0;
    memset(&d, 0, sizeof d);
    d.mass = 0.04, d.radius = 0.1, d.damping = 0.5, d.position = 0.1;
    CHECK_STATUS("margin of one design, two planes", autobal_study_rotor_design_margin(&p, &o, &d, &rho, &err),
                 AUTOBAL_EUNSUPPORTED);
    CHECK_MSG("names planes", err.message, "planes = 2");
  }
  b = o;
  b.unbalance2_boxes = -2;
  CHECK_STATUS("boxes", autobal_study_rotor_design(&p, &b, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK_MSG("names unbalance2_boxes", err.message, "unbalance2_boxes = -2");
  autobal_study_rotor_design_summary_free(&S);
}

/* Transients of two-plane designs (autobal_study_rotor_design_transients with planes = 2): a design
 * whose balanced motion is linearly unstable at 4500 rpm for 500 g mm in both planes (40 g on 98 mm
 * with 0.1 kg/s: the constructed case of tests/app/rotor_design_two_planes.sh, unstable there by the
 * exact analysis and by SciPy's Floquet multipliers) cannot balance: the balanced state is not an
 * attractor, so P(balance) = 0 and the worst time is +inf whatever the start.  The same balls with
 * 0.46 kg/s (stable at every unbalance there) balance from every start: P = 1, finite times.  The
 * member count is n_start^4 (the four balls) x plane-1 x plane-2 unbalances x speeds. */
static void test_transients(void) {
  autobal_rotor_params p = rotor_two_planes(500.0);
  autobal_study_rotor_design_options o = small_options();
  autobal_rotor_design d;
  autobal_error err;
  o.omega_min = 471.0;
  o.omega_max = 471.238898038469;
  o.unbalance_min = o.unbalance_max = 5e-4;
  o.unbalance2_min = o.unbalance2_max = 5e-4;
  o.n_transient = 1;
  o.n_start = 2;
  o.n_transient_speeds = 1;
  o.t_end = 20.0;
  memset(&d, 0, sizeof d);
  d.mass = 0.04, d.radius = 0.098, d.damping = 0.1, d.position = 0.10;
  CHECK_STATUS("transients, unstable design", autobal_study_rotor_design_transients(&p, &o, &d, &err), AUTOBAL_SUCCESS);
  CHECK("16 members (2^4 starts, one unbalance each, one speed)", d.n_runs == 16);
  CHECK("the unstable design never balances", d.n_balanced == 0 && d.p_balance == 0.0 && isinf(d.ttb_worst) &&
                                                  isinf(d.ttb_median));
  d.damping = 0.46;
  CHECK_STATUS("transients, stable design", autobal_study_rotor_design_transients(&p, &o, &d, &err), AUTOBAL_SUCCESS);
  CHECK("the stable design balances from every start", d.n_runs == 16 && d.n_balanced == 16 && d.p_balance == 1.0 &&
                                                           isfinite(d.ttb_worst) && d.ttb_median <= d.ttb_worst &&
                                                           d.ttb_median > 0.0);
  printf("two-plane transients: stable design median %.4g s, worst %.4g s\n", d.ttb_median, d.ttb_worst);
  /* plane 2's unbalance range adds members: 2 plane-1 x 2 plane-2 values */
  o.unbalance_max = 3e-3;
  o.unbalance2_max = 2.5e-3;
  o.n_transient_unbalances = 2;
  o.n_start = 1;
  CHECK_STATUS("transients, unbalance corners", autobal_study_rotor_design_transients(&p, &o, &d, &err), AUTOBAL_SUCCESS);
  CHECK("1 start x 2 x 2 unbalances", d.n_runs == 4);
}

/* The optimizer (n_starts, max_iter): Nelder-Mead over (m, h, r) from the best cell.  Its start is a
 * vertex of the simplex and the result is the best vertex, so its sampled margin is at least the best
 * cell's (the same map without the optimizer); it stays within the bounds; it is certified like the
 * cells (box search at every grid speed, the certified margin) and, when certified stable, every point
 * of the dense closed-matrix sample is stable with every margin below -margin_certified. */
static void test_nelder_mead(void) {
  autobal_rotor_params p = rotor_two_planes(500.0);
  autobal_study_rotor_design_options o = small_options();
  autobal_study_rotor_design_summary S0, S;
  autobal_error err;
  autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, &so, &err);
  size_t k, nopt = 0;
  o.n_omega = 3;
  o.n_best = 3;
  /* the reference: the map's best cell by the sampled margin, where the optimizer starts (the certification
     comes after the optimizer and does not move that start: without it here, which is most of this run's cost) */
  o.unbalance2_boxes = -1;
  CHECK_STATUS("map without the optimizer", autobal_study_rotor_design(&p, &o, NULL, &S0, &err), AUTOBAL_SUCCESS);
  CHECK("the reference is not certified", S0.n_designs >= 1 && S0.designs[0].recheck == -1);
  o.unbalance2_boxes = 0;
  o.n_starts = 1;
  o.max_iter = 15;
  CHECK_STATUS("with the optimizer", autobal_study_rotor_design(&p, &o, NULL, &S, &err), AUTOBAL_SUCCESS);
  CHECK("optimizer evaluated", S.optimizer_evaluations > 0 && S0.optimizer_evaluations == 0);
  CHECK("ranked designs", S.n_designs >= 1 && S0.n_designs >= 1);
  for (k = 0; k < S.n_designs && S0.n_designs >= 1 && s; k++) {
    const autobal_rotor_design *d = &S.designs[k];
    size_t nu = 0, ne = 0, q;
    double worst = -INFINITY;
    if (!d->source) continue;
    nopt++;
    printf("optimizer: %.5g g, %.5g mm, %.5g kg/s: sampled margin %.5f (best cell %.5f), recheck %d, certified %.5f\n",
           d->mass * 1e3, d->radius * 1e3, d->damping, d->margin, S0.designs[0].margin, d->recheck, d->margin_certified);
    CHECK("within the bounds", d->mass >= o.mass_min && d->mass <= o.mass_max && d->damping >= o.damping_min &&
                                   d->damping <= o.damping_max && d->radius >= o.radius_min && d->radius <= o.radius_max);
    CHECK("not worse than its start (the best cell)", d->margin >= S0.designs[0].margin);
    CHECK("certified like the cells", d->n_certify_run == o.n_omega && (d->recheck == 0 || d->recheck == 1));
    if (d->recheck == 1) {
      CHECK("certified margin computed", isfinite(d->margin_certified) && d->margin_certified <= d->margin_upper);
      for (q = 0; q < o.n_omega; q++) {
        const double w = o.omega_min + (o.omega_max - o.omega_min) * (double)q / (double)(o.n_omega - 1);
        worst = fmax(worst, dense_max(s, &o, d->mass, d->damping, d->radius, w, 1, &nu, &ne));
      }
      CHECK("dense sample: stable, every margin below -margin_certified", nu == 0 && worst < -d->margin_certified);
    }
  }
  CHECK("an optimizer design is ranked", nopt == 1);
  CHECK("the best ranked margin is at least the map's best", S.designs[0].margin >= S0.designs[0].margin ||
                                                               !S.designs[0].feasible);
  autobal_study_rotor_design_summary_free(&S0);
  autobal_study_rotor_design_summary_free(&S);
  autobal_rotor_stab_free(s);
}

int main(void) {
  test_refusals();
  test_nelder_mead();
  test_transients();
  test_search();
  return check_summary();
}
