/* bench_design.c: the design search of `autobal rotor design` (autobal_study_rotor_design) over FOUR
 * balancer parameters -- ball mass, track radius, ball damping and the plane position -- for the
 * default machine (data/rotor_default.ini), speeds 4500..9000 rpm, every unbalance 500..4000 g mm,
 * required margin 0.2 1/s.  Prints the wall and CPU time, the counts of exact every-unbalance tests
 * and of single stability verdicts, and those per second.  Usage: bench_design [n_position]
 * (default 5; 1 fixes the position: a 3-parameter search).  The search runs twice in the same
 * process: on 1 thread (the reference) and on 2 OpenMP threads (options.threads); the two results
 * must agree bit for bit, and the wall-time ratio 1 thread / 2 threads is printed.
 * bench_design N_POSITION N_BALLS_MAX (N_BALLS_MAX >= 3): then the same search with 2 .. N_BALLS_MAX
 * identical balls (unbalance_member = symmetric) on 2 threads, in the same process; its wall time and
 * stability analyses per second against the two-ball run on 2 threads (the reference), and the best
 * design per number of balls.
 * bench_design two: the two-plane design (options.planes = 2, docs/rotor.md "Design", "Two planes") of
 * the two-plane machine of data/design_two_planes.ini, on 2 threads, without and with the certification
 * by the box search, against the one-plane 3-parameter search of the default machine on 2 threads in
 * the same process (the reference): wall times, verdicts (per speed: one every-unbalance test for one
 * plane, one two-plane grid+slice or certified verdict for two) and verdicts per second, as ratios. */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "autobal.h"

static double wall(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double m1[2] = {0.05, 0.05}, r1[2] = {0.1, 0.1}, h1[2] = {0.5, 0.5};
static double m2[2] = {0.04, 0.04}, r2[2] = {0.09, 0.09}, h2[2] = {0.5, 0.5};

static int bench_two(void) {
  const double pi = 3.14159265358979323846;
  autobal_rotor_params p1 = autobal_rotor_params_default(), p2 = autobal_rotor_params_default();
  autobal_study_rotor_design_options o1 = autobal_study_rotor_design_options_default(), o2;
  autobal_study_rotor_design_summary S1, Sm, Sc;
  autobal_error err;
  double t0, w1, wm, wc;
  size_t k;
  /* the reference: one plane, the default machine, 3 parameters (bench_design 1), 2 threads */
  o1.omega_min = 4500.0 * pi / 30.0;
  o1.omega_max = 9000.0 * pi / 30.0;
  o1.unbalance_min = 500e-6;
  o1.unbalance_max = 4000e-6;
  o1.margin = 0.2;
  o1.mass_min = 0.025, o1.mass_max = 0.1, o1.n_mass = 8;
  o1.radius_min = 0.05, o1.radius_max = 0.15, o1.n_radius = 24;
  o1.damping_min = 0.01, o1.damping_max = 1.0, o1.n_damping = 8;
  o1.threads = 2;
  t0 = wall();
  if (autobal_study_rotor_design(&p1, &o1, NULL, &S1, &err)) {
    fprintf(stderr, "bench_design: %s\n", err.message);
    return 1;
  }
  w1 = wall() - t0;
  /* data/design_two_planes.ini */
  p2.plane[0].d = 0.10, p2.plane[0].m0 = 0.02, p2.plane[0].r0 = 0.1, p2.plane[0].psi0 = 0.0;
  p2.plane[0].ball_mass = m1, p2.plane[0].ball_radius = r1, p2.plane[0].ball_damping = h1;
  p2.plane[0].ball_psi = NULL, p2.plane[0].ball_rate = NULL;
  p2.n_planes = 2;
  p2.plane[1] = p2.plane[0];
  p2.plane[1].d = -0.12, p2.plane[1].m0 = 0.015, p2.plane[1].r0 = 0.09, p2.plane[1].psi0 = 2.0;
  p2.plane[1].ball_mass = m2, p2.plane[1].ball_radius = r2, p2.plane[1].ball_damping = h2;
  o2 = autobal_study_rotor_design_options_default();
  o2.planes = 2;
  o2.omega_min = 4500.0 * pi / 30.0;
  o2.omega_max = 9000.0 * pi / 30.0;
  o2.n_omega = 9;
  o2.unbalance_min = 500e-6, o2.unbalance_max = 3000e-6;
  o2.unbalance2_min = 500e-6, o2.unbalance2_max = 2500e-6;
  o2.n_unbalance2 = 5;
  o2.margin = 0.2;
  o2.mass_min = 0.025, o2.mass_max = 0.1, o2.n_mass = 4;
  o2.radius_min = 0.05, o2.radius_max = 0.15, o2.n_radius = 6;
  o2.damping_min = 0.1, o2.damping_max = 1.0, o2.n_damping = 4;
  o2.n_best = 3;
  o2.threads = 2;
  o2.unbalance2_boxes = -1;
  t0 = wall();
  if (autobal_study_rotor_design(&p2, &o2, NULL, &Sm, &err)) {
    fprintf(stderr, "bench_design: %s\n", err.message);
    return 1;
  }
  wm = wall() - t0;
  o2.unbalance2_boxes = 0;
  t0 = wall();
  if (autobal_study_rotor_design(&p2, &o2, NULL, &Sc, &err)) {
    fprintf(stderr, "bench_design: %s\n", err.message);
    return 1;
  }
  wc = wall() - t0;
  printf("one plane (reference), default machine, 3 parameters, %zu speeds, 2 threads: wall %.2f s, %zu every-unbalance "
         "tests (%.0f per wall second), %zu map cells\n",
         o1.n_omega, w1, S1.ratio_sets, (double)S1.ratio_sets / w1, S1.n_mass * S1.n_damping * S1.n_radius);
  printf("two planes, data/design_two_planes.ini, %zu speeds, %zu x %zu x %zu map, 2 threads:\n", o2.n_omega, o2.n_mass,
         o2.n_damping, o2.n_radius);
  printf("  map + ranking only (unbalance2_boxes = -1): wall %.2f s (%.2f x the one-plane run), %zu verdicts (%.1f per "
         "wall second, %.2e x the one-plane rate), %zu feasible\n",
         wm, wm / w1, Sm.verdicts2, (double)Sm.verdicts2 / wm, ((double)Sm.verdicts2 / wm) / ((double)S1.ratio_sets / w1),
         Sm.n_feasible);
  printf("  with the certification of the %zu best (box search at every speed): wall %.2f s (%.2f x the one-plane run), "
         "%zu verdicts; the certification: %zu verdicts in %.2f s (%.2f per wall second)\n",
         Sc.n_designs, wc, wc / w1, Sc.verdicts2, Sc.verdicts2 - Sm.verdicts2, wc - wm,
         (double)(Sc.verdicts2 - Sm.verdicts2) / (wc - wm));
  printf("  map identical with and without the certification: %s\n",
         !memcmp(Sm.feasible, Sc.feasible, o2.n_mass * o2.n_damping * o2.n_radius * sizeof *Sm.feasible) ? "yes" : "NO");
  for (k = 0; k < Sc.n_designs; k++)
    printf("  #%zu: m %.4g g, r %.4g mm, h %.4g kg/s: margin %.4g 1/s (sampled), recheck %s, certified at %zu of %zu "
           "speeds, %zu boxes\n",
           k, Sc.designs[k].mass * 1e3, Sc.designs[k].radius * 1e3, Sc.designs[k].damping, Sc.designs[k].margin,
           Sc.designs[k].recheck == 1 ? "ok" : "FAILED", Sc.designs[k].n_certified, Sc.designs[k].n_certify_run,
           Sc.designs[k].boxes);
  autobal_study_rotor_design_summary_free(&S1);
  autobal_study_rotor_design_summary_free(&Sm);
  autobal_study_rotor_design_summary_free(&Sc);
  return 0;
}

int main(int argc, char **argv) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  const double pi = 3.14159265358979323846;
  double t0, c0, tw, tc;
  int st;
  size_t k;
  gsl_set_error_handler_off();
  if (argc > 1 && !strcmp(argv[1], "two")) return bench_two();
  o.omega_min = 4500.0 * pi / 30.0;
  o.omega_max = 9000.0 * pi / 30.0;
  o.unbalance_min = 500e-6;
  o.unbalance_max = 4000e-6;
  o.margin = 0.2;
  o.mass_min = 0.025, o.mass_max = 0.1, o.n_mass = 8;
  o.radius_min = 0.05, o.radius_max = 0.15, o.n_radius = 24;
  o.damping_min = 0.01, o.damping_max = 1.0, o.n_damping = 8;
  o.position_min = 0.05, o.position_max = 0.15, o.n_position = argc > 1 ? (size_t)atoi(argv[1]) : 5;
  if (o.n_position == 1) o.position_min = o.position_max = p.plane[0].d;
  {
    autobal_study_rotor_design_summary S1;
    double tw1, tc1;
    size_t ncell;
    int same;
    o.threads = 1;
    t0 = wall();
    c0 = (double)clock() / CLOCKS_PER_SEC;
    st = autobal_study_rotor_design(&p, &o, NULL, &S1, &err);
    tw1 = wall() - t0;
    tc1 = (double)clock() / CLOCKS_PER_SEC - c0;
    if (st) {
      fprintf(stderr, "bench_design: %s\n", err.message);
      return 1;
    }
    o.threads = 2;
    t0 = wall();
    c0 = (double)clock() / CLOCKS_PER_SEC;
    st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
    tw = wall() - t0;
    tc = (double)clock() / CLOCKS_PER_SEC - c0;
    if (st) {
      fprintf(stderr, "bench_design: %s\n", err.message);
      return 1;
    }
    ncell = S.n_mass * S.n_damping * S.n_position;
    same = S.n_designs == S1.n_designs && S.ratio_sets == S1.ratio_sets &&
           S.margin_evaluations == S1.margin_evaluations && S.n_feasible == S1.n_feasible &&
           !memcmp(S.feasible, S1.feasible, ncell * S.n_radius * sizeof *S.feasible) &&
           !memcmp(S.window_lo, S1.window_lo, ncell * sizeof *S.window_lo) &&
           !memcmp(S.designs, S1.designs, S.n_designs * sizeof *S.designs);
    printf("design search, default machine, %s: %zu speeds in [4500, 9000] rpm, every m0 r0 in [500, 4000] g mm, "
           "margin 0.2 1/s\n",
           o.n_position > 1 ? "4 parameters (mass, radius, damping, position)" : "3 parameters (mass, radius, damping)",
           o.n_omega);
    printf("  map %zu x %zu x %zu (x %zu radii, exact windows): %zu feasible points\n", S.n_mass, S.n_damping,
           S.n_position, S.n_radius, S.n_feasible);
    printf("  1 thread:  wall %.2f s, CPU %.2f s\n", tw1, tc1);
    printf("  2 threads: wall %.2f s, CPU %.2f s (all threads)\n", tw, tc);
    printf("  speed-up (wall, 1 thread / 2 threads, same run): %.2f; results bit for bit equal: %s\n", tw1 / tw,
           same ? "yes" : "NO");
    printf("  exact every-unbalance tests: %zu (%.0f per CPU second)\n", S.ratio_sets, (double)S.ratio_sets / tc1);
    printf("  single stability verdicts: %zu (%.0f per CPU second; %.0f per wall second on 1, %.0f on 2 threads)\n",
           S.margin_evaluations, (double)S.margin_evaluations / tc1, (double)S.margin_evaluations / tw1,
           (double)S.margin_evaluations / tw);
    autobal_study_rotor_design_summary_free(&S1);
    if (!same) return 1;
  }
  printf("  optimizer evaluations: %zu\n", S.optimizer_evaluations);
  for (k = 0; k < S.n_designs && k < 3; k++)
    printf("  #%zu: m %.4g g, r %.4g mm, h %.4g kg/s, d %.4g mm: rho %.4g 1/s, re-check %s\n", k,
           S.designs[k].mass * 1e3, S.designs[k].radius * 1e3, S.designs[k].damping, S.designs[k].position * 1e3,
           S.designs[k].margin, S.designs[k].recheck == 1 ? "ok" : "FAILED");
  if (argc > 2 && atoi(argv[2]) >= 3) {
    autobal_study_rotor_design_summary Sn;
    const double ref_rate = (double)S.margin_evaluations / tw;
    size_t nmax = (size_t)atoi(argv[2]), n;
    double twn;
    o.n_balls_min = 2;
    o.n_balls_max = nmax;
    o.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
    o.threads = 2;
    t0 = wall();
    st = autobal_study_rotor_design(&p, &o, NULL, &Sn, &err);
    twn = wall() - t0;
    if (st) {
      fprintf(stderr, "bench_design: %s\n", err.message);
      autobal_study_rotor_design_summary_free(&S);
      return 1;
    }
    printf("number of balls 2..%zu (symmetric members for n >= 3), 2 threads: wall %.2f s (%.2f x the two-ball run), "
           "%zu feasible map points\n",
           nmax, twn, twn / tw, Sn.n_feasible);
    printf("  exact every-unbalance tests: %zu; single stability verdicts: %zu (%.0f per wall second; two balls: %.0f, "
           "ratio %.2f)\n",
           Sn.ratio_sets, Sn.margin_evaluations, (double)Sn.margin_evaluations / twn, ref_rate,
           (double)Sn.margin_evaluations / twn / ref_rate);
    for (n = 2; n <= nmax; n++)
      for (k = 0; k < Sn.n_designs; k++)
        if (Sn.designs[k].n_balls == n) {
          printf("  best with %zu balls (rank %zu of the %zu re-checked): m %.4g g, r %.4g mm, h %.4g kg/s, d %.4g mm: rho %.4g 1/s, re-check %s\n",
                 n, k, Sn.n_designs, Sn.designs[k].mass * 1e3, Sn.designs[k].radius * 1e3, Sn.designs[k].damping,
                 Sn.designs[k].position * 1e3, Sn.designs[k].margin, Sn.designs[k].recheck == 1 ? "ok" : "FAILED");
          break;
        }
    autobal_study_rotor_design_summary_free(&Sn);
  }
  autobal_study_rotor_design_summary_free(&S);
  return 0;
}
