/* test_rotor_design_aniso.c: `autobal rotor design` on ANISOTROPIC supports (data/rotor_anisotropic.ini's
 * machine; one plane, two balls; docs/rotor.md "Design", "Anisotropic supports"):
 *  - a small search: every design reported feasible is certified by Hill's method (hill_certified 1 at
 *    every re-check speed), and an ordinary Floquet analysis of it at 40 unbalances across the range at each
 *    re-check speed (and at the speeds half-way between them) finds every multiplier |mu| < exp(-margin T);
 *    feasible exactly when certified, the first design a certified one, its config saying so;
 *  - a Hill budget too small to prove anything (hill_boxes = 100): the screened designs undecided, none
 *    feasible, the config saying so;
 *  - a speed range below the first critical speed (100..200 rad/s), where no balancer balances: no design
 *    passes, none is feasible;
 *  - bad input: three balls refused on anisotropic supports, a negative margin; the messages name the key;
 *    autobal_study_rotor_design_margin (isotropic bisection) refused on anisotropic supports. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

#define NU 40

static autobal_rotor_params machine(double *bm, double *br, double *bh, double *bp, double *brt) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.hw.c_Ly = 0.7e5; /* data/rotor_anisotropic.ini */
  p.hw.c_Ry = 1.1e5;
  p.hw.h_Ly = 80;
  p.hw.h_Ry = 120;
  p.plane[0].ball_mass = bm, p.plane[0].ball_radius = br, p.plane[0].ball_damping = bh;
  p.plane[0].ball_psi = bp, p.plane[0].ball_rate = brt;
  return p;
}

static autobal_study_rotor_design_options small_options(void) {
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  o.omega_min = 500.0, o.omega_max = 1000.0, o.n_omega = 3, o.n_verify = 3;
  o.unbalance_min = 0.0015, o.unbalance_max = 0.003;
  o.margin = 0.2;
  o.mass_min = 0.03, o.mass_max = 0.06, o.n_mass = 2;
  o.radius_min = 0.07, o.radius_max = 0.1, o.n_radius = 2;
  o.damping_min = 0.05, o.damping_max = 1.0, o.n_damping = 2;
  o.n_best = 4, o.n_transient = 0;
  return o;
}

/* The largest Floquet margin of design d at speed w over NU unbalances across the range. */
static double floquet_worst(const autobal_rotor_params *base, const autobal_rotor_design *d, double w, double lo,
                            double hi) {
  autobal_rotor_params q = *base;
  double m[2] = {d->mass, d->mass}, r[2] = {d->radius, d->radius}, h[2] = {d->damping, d->damping};
  double ps[2] = {1.0, 2.5}, rt[2] = {0.0, 0.0}, worst = -INFINITY;
  autobal_error err;
  autobal_rotor_stab *s;
  size_t k;
  q.plane[0].ball_mass = m, q.plane[0].ball_radius = r, q.plane[0].ball_damping = h;
  q.plane[0].ball_psi = ps, q.plane[0].ball_rate = rt;
  q.plane[0].d = d->position;
  q.omega = w;
  s = autobal_rotor_stab_alloc(&q, NULL, &err);
  if (!s) return NAN;
  for (k = 0; k < NU; k++) {
    const double sv = lo + (hi - lo) * (double)k / (double)(NU - 1);
    double mg = NAN;
    int v;
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv / q.plane[0].r0);
    if (autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_FLOQUET, &mg, &v) != AUTOBAL_SUCCESS) mg = NAN;
    if (!(mg <= worst)) worst = mg;
  }
  autobal_rotor_stab_free(s);
  return worst;
}

static void feasible_designs(void) {
  double bm[2] = {0.05, 0.05}, br[2] = {0.1, 0.1}, bh[2] = {0.1, 0.1}, bp[2] = {1.0, 2.5}, brt[2] = {0, 0};
  const autobal_rotor_params p = machine(bm, br, bh, bp, brt);
  const autobal_study_rotor_design_options o = small_options();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  size_t i, k, n_feasible = 0, n_screen_only = 0;
  int st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("design on anisotropic supports", st, AUTOBAL_SUCCESS);
  if (st != AUTOBAL_SUCCESS) {
    printf("     %s\n", err.message);
    autobal_study_rotor_design_summary_free(&S);
    return;
  }
  printf("     %zu of %zu designs pass the screen; %zu ranked; %zu Floquet analyses, %zu Hill verdicts\n", S.n_feasible,
         S.n_mass * S.n_damping * S.n_radius, S.n_designs, S.margin_evaluations, S.ratio_sets);
  CHECK("the anisotropic search ran (summary.aniso)", S.aniso == 1 && S.ranked == 1);
  CHECK("some design passes the screen and is ranked", S.n_feasible > 0 && S.n_designs > 0);
  for (i = 0; i < S.n_designs; i++) {
    const autobal_rotor_design *d = &S.designs[i];
    printf("     %zu: m %.4g g, r %.4g mm, h %.4g kg/s: rho_s %.5g, hill_certified %d (%zu speeds, %ld boxes), "
           "feasible %d\n",
           i, d->mass * 1e3, d->radius * 1e3, d->damping, d->margin, d->hill_certified, d->hill_speeds,
           d->hill_boxes, d->feasible);
    CHECK("feasible exactly when certified by Hill's method", d->feasible == (d->hill_certified == 1));
    CHECK("the screen passed (rho_s > margin)", d->margin > o.margin);
    if (!d->feasible) {
      n_screen_only++;
      continue;
    }
    n_feasible++;
    CHECK("certified at every re-check speed", d->hill_speeds == o.n_verify && d->hill_undecided == 0);
    for (k = 0; k < 2 * o.n_verify - 1; k++) {
      const double w = o.omega_min + (o.omega_max - o.omega_min) * (double)k / (double)(2 * o.n_verify - 2);
      const double worst = floquet_worst(&p, d, w, o.unbalance_min, o.unbalance_max);
      char what[160];
      snprintf(what, sizeof what, "omega %g%s: %d Floquet analyses, every |mu| < exp(-margin T) (worst %.5g 1/s)", w,
               k % 2 ? " (between re-check speeds)" : "", NU, worst);
      CHECK(what, worst < -o.margin);
    }
  }
  CHECK("the first design is a certified one", S.designs[0].feasible == 1);
  CHECK("the best config says it is certified", S.best_config && strstr(S.best_config, "PROVEN at every speed"));
  printf("     %zu certified, %zu passed the screen only\n", n_feasible, n_screen_only);
  autobal_study_rotor_design_summary_free(&S);
}

/* A budget too small to prove anything (hill_boxes = 100): the designs that pass the screen stay undecided
 * and none is feasible. */
static void undecided(void) {
  double bm[2] = {0.05, 0.05}, br[2] = {0.1, 0.1}, bh[2] = {0.1, 0.1}, bp[2] = {1.0, 2.5}, brt[2] = {0, 0};
  const autobal_rotor_params p = machine(bm, br, bh, bp, brt);
  autobal_study_rotor_design_options o = small_options();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  size_t i, nf = 0, nu = 0;
  int st;
  o.hill_boxes = 100;
  o.n_best = 2;
  st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("hill_boxes = 100", st, AUTOBAL_SUCCESS);
  for (i = 0; i < S.n_designs; i++) {
    nf += S.designs[i].feasible ? 1u : 0u;
    nu += S.designs[i].hill_certified == -1 ? 1u : 0u;
  }
  printf("     hill_boxes = 100: %zu ranked, %zu undecided, %zu feasible\n", S.n_designs, nu, nf);
  CHECK("screened designs ranked, every one undecided, none feasible", S.n_designs == 2 && nu == 2 && nf == 0);
  CHECK("the best config says it is undecided", S.best_config && strstr(S.best_config, "UNDECIDED"));
  autobal_study_rotor_design_summary_free(&S);
  o = small_options();
  o.hill_boxes = 50;
  CHECK_STATUS("hill_boxes = 50 refused", autobal_study_rotor_design(&p, &o, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK("the message names hill_boxes and its range", strstr(err.message, "hill_boxes") && strstr(err.message, "[100, 1e8]"));
  autobal_study_rotor_design_summary_free(&S);
}

static void none_feasible(void) {
  double bm[2] = {0.05, 0.05}, br[2] = {0.1, 0.1}, bh[2] = {0.1, 0.1}, bp[2] = {1.0, 2.5}, brt[2] = {0, 0};
  const autobal_rotor_params p = machine(bm, br, bh, bp, brt);
  autobal_study_rotor_design_options o = small_options();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  size_t i, nf = 0;
  int st;
  o.omega_min = 100.0, o.omega_max = 200.0;
  st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("below the critical speeds", st, AUTOBAL_SUCCESS);
  for (i = 0; i < S.n_designs; i++) nf += S.designs[i].feasible ? 1u : 0u;
  printf("     100..200 rad/s: %zu pass the screen, %zu ranked, %zu feasible\n", S.n_feasible, S.n_designs, nf);
  CHECK("no design passes the screen, none is feasible", S.n_feasible == 0 && S.n_designs == 0 && nf == 0);
  autobal_study_rotor_design_summary_free(&S);
}

static void refusals(void) {
  double bm[2] = {0.05, 0.05}, br[2] = {0.1, 0.1}, bh[2] = {0.1, 0.1}, bp[2] = {1.0, 2.5}, brt[2] = {0, 0};
  const autobal_rotor_params p = machine(bm, br, bh, bp, brt);
  autobal_study_rotor_design_options o = small_options();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  o.n_balls_max = 3;
  CHECK_STATUS("three balls on anisotropic supports refused", autobal_study_rotor_design(&p, &o, NULL, &S, &err),
               AUTOBAL_EUNSUPPORTED);
  CHECK("the message names n_balls_max and two balls", strstr(err.message, "n_balls_max") && strstr(err.message, "two balls"));
  autobal_study_rotor_design_summary_free(&S);
  o = small_options();
  o.margin = -1.0;
  CHECK_STATUS("margin < 0 refused", autobal_study_rotor_design(&p, &o, NULL, &S, &err), AUTOBAL_EINVAL);
  CHECK("the message names margin and its range", strstr(err.message, "margin") && strstr(err.message, ">= 0"));
  autobal_study_rotor_design_summary_free(&S);
  { /* the robust margin of one design by bisection is isotropic only: refused, not a wrong number */
    autobal_rotor_design d;
    double rho = 0.0;
    memset(&d, 0, sizeof d);
    d.mass = 0.05, d.radius = 0.1, d.damping = 0.1, d.position = p.plane[0].d, d.n_balls = 2;
    o = small_options();
    CHECK_STATUS("design margin on anisotropic supports refused",
                 autobal_study_rotor_design_margin(&p, &o, &d, &rho, &err), AUTOBAL_EUNSUPPORTED);
    CHECK("its message names the supports and the call to use",
          strstr(err.message, "[supports]") && strstr(err.message, "autobal_rotor_stab_every_unbalance_margin"));
  }
}

int main(void) {
  printf("a small search: feasible designs re-checked by dense Floquet sampling\n");
  feasible_designs();
  printf("a budget too small: undecided, not feasible\n");
  undecided();
  printf("a speed range where no balancer works\n");
  none_feasible();
  printf("refusals\n");
  refusals();
  return check_summary();
}
