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
 * design per number of balls. */
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
