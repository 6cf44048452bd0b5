/* bench_pendulum.c: time the pendulum transient (1) with the autobal driver.
 *
 *   bench_pendulum STEPPER RTOL ATOL T1 REPEATS
 *
 * Problem (same as bench/pendulum_scipy.py): R_w = 3, R_m = 0.1, H = 0.05,
 * h = 0.1, psi0 = 0.5; start-up from rest with the pendulums opposite each
 * other along V (psi = phi = 0), xi = eta = 0; tau in [0, T1]; no output
 * grid (final state only).  The right-hand side is the prepared
 * autobal_pendulum_motion_rhs (sin psi0 computed once).  Prints one JSON object: the median wall time of
 * REPEATS runs, the statistics and the final state. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/pendulum.h"
#include "autobal/transient.h"

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  autobal_pendulum_params p = {3.0, 0.1, 0.05, 0.1, 0.5};
  autobal_pendulum_motion m;
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys = {autobal_pendulum_motion_rhs, autobal_pendulum_motion_jac, 8, &m};
  autobal_transient_stats st;
  autobal_transient *tr;
  autobal_error err;
  double y[8], t1, *times;
  int repeats, r, i, rc = 0;
  if (argc != 6) {
    fprintf(stderr, "usage: %s STEPPER RTOL ATOL T1 REPEATS\n", argv[0]);
    return 2;
  }
  gsl_set_error_handler_off();
  if (autobal_pendulum_motion_init(&m, &p, &err) != AUTOBAL_SUCCESS) {
    fprintf(stderr, "bench_pendulum: %s\n", err.message);
    return 1;
  }
  o.stepper = argv[1];
  o.rtol = atof(argv[2]);
  o.atol = atof(argv[3]);
  t1 = atof(argv[4]);
  repeats = atoi(argv[5]);
  if (repeats < 1) repeats = 1;
  tr = autobal_transient_alloc(8, &o, &err);
  if (tr == NULL) {
    fprintf(stderr, "bench_pendulum: %s\n", err.message);
    return 1;
  }
  times = malloc((size_t)repeats * sizeof(double));
  if (times == NULL) return 1;
  for (r = 0; r < repeats; r++) {
    memset(y, 0, sizeof y); /* xi = eta = psi = phi = 0, at rest */
    rc = autobal_transient_run(tr, &sys, 0.0, t1, y, NULL);
    if (rc != AUTOBAL_SUCCESS) {
      fprintf(stderr, "bench_pendulum: %s\n", autobal_transient_errmsg(tr));
      return 1;
    }
    autobal_transient_get_stats(tr, &st);
    times[r] = st.wall_seconds;
  }
  qsort(times, (size_t)repeats, sizeof(double), cmp_double);
  printf("{\"stepper\": \"%s\", \"rtol\": %.3g, \"atol\": %.3g, \"t1\": %.17g, \"repeats\": %d, "
         "\"seconds\": %.9g, \"seconds_min\": %.9g, \"steps\": %lu, \"rejected\": %lu, "
         "\"rhs_evals\": %lu, \"jac_evals\": %lu, \"y\": [",
         o.stepper, o.rtol, o.atol, t1, repeats, times[repeats / 2], times[0], st.steps,
         st.rejected, st.rhs_evals, st.jac_evals);
  for (i = 0; i < 8; i++) printf("%.17g%s", y[i], i < 7 ? ", " : "]}\n");
  free(times);
  autobal_transient_free(tr);
  return 0;
}
