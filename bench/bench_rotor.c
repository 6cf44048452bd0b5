/* bench_rotor.c: time the rotor model (rotor.md, (3.2) + (3.4)) with the
 * autobal driver, and the cost of its right-hand side against the number of
 * balls.  Companion of bench/rotor_scipy.py (which runs it and prints tables).
 *
 *   bench_rotor run NBALLS STEPPER RTOL ATOL T1 REPEATS [fixed|rotating]
 *       Transient of the spec's default rotor from t = 0 to T1, final state
 *       only (no output grid).  NBALLS = 2: the default example as it is
 *       (two balls of 0.05 kg at psi = 1.0, 2.5); other NBALLS: see
 *       ball_config() (same total ball mass 0.1 kg on r = 0.1 m, h = 0.1
 *       kg/s each, psi_i = 1.0 + 0.4 i).  Fixed-frame state (default) or the
 *       rotating-frame one.  Prints one JSON object: median and best wall
 *       time of REPEATS runs (the driver's CLOCK_MONOTONIC), the best process
 *       CPU time (CLOCK_PROCESS_CPUTIME_ID around the run), the driver's
 *       statistics and the final state.
 *
 *   bench_rotor rhs NMAX SECONDS [REPS]
 *       Wall time of one right-hand-side call (fixed and rotating frame) for
 *       n = 2, 4, 8, ..., NMAX balls (ball_config(n)), each the best of REPS
 *       (default 51) chunks of calls lasting about SECONDS each (short
 *       chunks and many of them: the best is then a chunk that the
 *       scheduler did not interrupt, on a shared machine), cycling through 16
 *       pseudo-random states (so no two consecutive calls see the same
 *       input).  Least-squares line cost = a + b n for each frame with R^2
 *       and the largest relative residual.  Prints one JSON object.
 *
 *   bench_rotor check NBALLS
 *       The initial state and 4 pseudo-random states with the fixed-frame
 *       right-hand side at each (JSON), so that rotor_scipy.py can check its
 *       own independent right-hand side against the library's.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "autobal/rotor.h"
#include "autobal/transient.h"

#define N_STATES 16
#define PI 3.14159265358979323846

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU time of the process (excludes time the scheduler gave to others). */
static double cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Ball arrays of the benchmark configurations (owned by the caller). */
typedef struct ball_config {
  size_t n;
  double *mass, *radius, *damping, *psi, *rate;
} ball_config;

static void ball_config_free(ball_config *b) {
  free(b->mass);
  free(b->radius);
  free(b->damping);
  free(b->psi);
  free(b->rate);
}

/* n balls of 0.1/n kg each (the default's total, 2 x 0.05 kg) on r = 0.1 m
 * with h = 0.1 kg/s, at rest relative to the rotor at psi_i = 1.0 + 0.4 i. */
static int ball_config_make(ball_config *b, size_t n) {
  size_t i;
  b->n = n;
  b->mass = malloc(n * sizeof(double));
  b->radius = malloc(n * sizeof(double));
  b->damping = malloc(n * sizeof(double));
  b->psi = malloc(n * sizeof(double));
  b->rate = malloc(n * sizeof(double));
  if (!b->mass || !b->radius || !b->damping || !b->psi || !b->rate) {
    ball_config_free(b);
    return -1;
  }
  for (i = 0; i < n; i++) {
    b->mass[i] = 0.1 / (double)n;
    b->radius[i] = 0.1;
    b->damping[i] = 0.1;
    b->psi[i] = 1.0 + 0.4 * (double)i;
    b->rate[i] = 0.0;
  }
  return 0;
}

/* The default rotor (n == 2 and use_default: exactly the spec's example;
 * otherwise ball_config(n) in its single plane).  NULL on failure (message
 * printed). */
static autobal_rotor *make_rotor(size_t n, int use_default) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor *r;
  autobal_error err;
  ball_config b;
  if (n == 2 && use_default) {
    r = autobal_rotor_alloc(&p, &err);
  } else {
    if (ball_config_make(&b, n) != 0) {
      fprintf(stderr, "bench_rotor: out of memory\n");
      return NULL;
    }
    p.plane[0].n_balls = n;
    p.plane[0].ball_mass = b.mass;
    p.plane[0].ball_radius = b.radius;
    p.plane[0].ball_damping = b.damping;
    p.plane[0].ball_psi = b.psi;
    p.plane[0].ball_rate = b.rate;
    r = autobal_rotor_alloc(&p, &err); /* copies the arrays */
    ball_config_free(&b);
  }
  if (r == NULL) fprintf(stderr, "bench_rotor: %s\n", err.message);
  return r;
}

/* Deterministic uniform numbers in [-1, 1) (64-bit LCG, top 53 bits). */
static double urand(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return 2.0 * ((double)(*s >> 11) * (1.0 / 9007199254740992.0)) - 1.0;
}

/* A plausible fixed-frame state at time t: displacements ~ 2e-4 m, tilts
 * ~ 1e-3 rad, rates ~ omega times those, ball angles omega t + U(-pi, pi),
 * ball rates omega + U(-50, 50) rad/s. */
static void random_state(unsigned long long *seed, double omega, double t, size_t n, double *y) {
  size_t k;
  y[0] = 2e-4 * urand(seed);
  y[1] = 2e-4 * urand(seed);
  y[2] = 1e-3 * urand(seed);
  y[3] = 1e-3 * urand(seed);
  y[4] = 0.1 * urand(seed);
  y[5] = 0.1 * urand(seed);
  y[6] = 0.5 * urand(seed);
  y[7] = 0.5 * urand(seed);
  for (k = 0; k < n; k++) y[8 + k] = omega * t + PI * urand(seed);
  for (k = 0; k < n; k++) y[8 + n + k] = omega + 50.0 * urand(seed);
}

static int mode_run(int argc, char **argv) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient_stats st;
  autobal_transient *tr;
  autobal_rotor *rot;
  autobal_error err;
  double *y, *times, *cpu, t1, c0;
  size_t n, dim, i;
  int repeats, r, frame = AUTOBAL_ROTOR_FIXED;
  if (argc != 8 && argc != 9) return 2;
  n = (size_t)strtoul(argv[2], NULL, 10);
  o.stepper = argv[3];
  o.rtol = atof(argv[4]);
  o.atol = atof(argv[5]);
  t1 = atof(argv[6]);
  repeats = atoi(argv[7]);
  if (argc == 9 && strcmp(argv[8], "rotating") == 0) frame = AUTOBAL_ROTOR_ROTATING;
  else if (argc == 9 && strcmp(argv[8], "fixed") != 0) return 2;
  if (repeats < 1) repeats = 1;
  if (n < 1) return 2;
  rot = make_rotor(n, 1);
  if (rot == NULL) return 1;
  dim = autobal_rotor_dim(rot);
  sys.rhs = frame == AUTOBAL_ROTOR_FIXED ? autobal_rotor_rhs : autobal_rotor_rhs_rotating;
  sys.jac = NULL;
  sys.dim = dim;
  sys.params = rot;
  tr = autobal_transient_alloc(dim, &o, &err);
  if (tr == NULL) {
    fprintf(stderr, "bench_rotor: %s\n", err.message);
    return 1;
  }
  y = malloc(dim * sizeof(double));
  times = malloc((size_t)repeats * sizeof(double));
  cpu = malloc((size_t)repeats * sizeof(double));
  if (y == NULL || times == NULL || cpu == NULL) return 1;
  for (r = 0; r < repeats; r++) {
    if (autobal_rotor_initial_state(rot, frame, 0.0, y, dim) != AUTOBAL_SUCCESS) return 1;
    c0 = cpu_seconds();
    if (autobal_transient_run(tr, &sys, 0.0, t1, y, NULL) != AUTOBAL_SUCCESS) {
      fprintf(stderr, "bench_rotor: %s\n", autobal_transient_errmsg(tr));
      return 1;
    }
    cpu[r] = cpu_seconds() - c0;
    autobal_transient_get_stats(tr, &st);
    times[r] = st.wall_seconds;
  }
  qsort(times, (size_t)repeats, sizeof(double), cmp_double);
  qsort(cpu, (size_t)repeats, sizeof(double), cmp_double);
  printf("{\"n_balls\": %zu, \"frame\": \"%s\", \"dim\": %zu, \"stepper\": \"%s\", "
         "\"rtol\": %.3g, \"atol\": %.3g, \"t1\": %.17g, \"repeats\": %d, "
         "\"seconds\": %.9g, \"seconds_min\": %.9g, \"cpu_seconds_min\": %.9g, "
         "\"steps\": %lu, \"rejected\": %lu, \"rhs_evals\": %lu, \"y\": [",
         n, frame == AUTOBAL_ROTOR_FIXED ? "fixed" : "rotating", dim, o.stepper, o.rtol, o.atol,
         t1, repeats, times[repeats / 2], times[0], cpu[0], st.steps, st.rejected, st.rhs_evals);
  for (i = 0; i < dim; i++) printf("%.17g%s", y[i], i + 1 < dim ? ", " : "]}\n");
  free(times);
  free(cpu);
  free(y);
  autobal_transient_free(tr);
  autobal_rotor_free(rot);
  return 0;
}

/* Best-of-reps wall time [ns] of one call of rhs over the N_STATES states. */
static double time_rhs(autobal_transient_rhs_fn rhs, autobal_rotor *rot, const double *ys,
                       const double *ts, double *dydt, size_t dim, double seconds, int reps,
                       double *sink) {
  long calls = 256, c;
  double best = INFINITY, dt;
  int rep;
  for (;;) { /* calibrate: calls per chunk so that a chunk lasts >= seconds */
    const double t0 = now_seconds();
    for (c = 0; c < calls; c++) {
      const long s = c % N_STATES;
      if (rhs(ts[s], ys + (size_t)s * dim, dydt, rot) != 0) return NAN;
      *sink += dydt[dim - 1];
    }
    dt = now_seconds() - t0;
    if (dt >= seconds || calls > (1L << 40)) break;
    calls *= 2;
  }
  for (rep = 0; rep < reps; rep++) {
    const double t0 = now_seconds();
    for (c = 0; c < calls; c++) {
      const long s = c % N_STATES;
      if (rhs(ts[s], ys + (size_t)s * dim, dydt, rot) != 0) return NAN;
      *sink += dydt[dim - 1];
    }
    dt = now_seconds() - t0;
    if (dt < best) best = dt;
  }
  return 1e9 * best / (double)calls;
}

/* Least squares c = a + b n; R^2 and the largest |residual| / c. */
static void fit_line(const double *n, const double *c, size_t m, double *a, double *b, double *r2,
                     double *maxrel) {
  double sn = 0, sc = 0, snn = 0, snc = 0, mean, ssres = 0, sstot = 0;
  size_t i;
  for (i = 0; i < m; i++) {
    sn += n[i];
    sc += c[i];
    snn += n[i] * n[i];
    snc += n[i] * c[i];
  }
  *b = ((double)m * snc - sn * sc) / ((double)m * snn - sn * sn);
  *a = (sc - *b * sn) / (double)m;
  mean = sc / (double)m;
  *maxrel = 0;
  for (i = 0; i < m; i++) {
    const double res = c[i] - (*a + *b * n[i]);
    ssres += res * res;
    sstot += (c[i] - mean) * (c[i] - mean);
    if (fabs(res) / c[i] > *maxrel) *maxrel = fabs(res) / c[i];
  }
  *r2 = 1.0 - ssres / sstot;
}

#define MAX_SIZES 32

static void print_array(const char *name, const double *v, size_t m, const char *fmt) {
  size_t i;
  printf("\"%s\": [", name);
  for (i = 0; i < m; i++) {
    printf(fmt, v[i]);
    printf("%s", i + 1 < m ? ", " : "]");
  }
}

static int mode_rhs(int argc, char **argv) {
  size_t nmax, n, m = 0, dim, s;
  double seconds, sink = 0.0;
  int reps = 51;
  double nn[MAX_SIZES], fixed_ns[MAX_SIZES], rot_ns[MAX_SIZES];
  double fa, fb, fr2, fmr, ra, rb, rr2, rmr;
  if (argc != 4 && argc != 5) return 2;
  nmax = (size_t)strtoul(argv[2], NULL, 10);
  seconds = atof(argv[3]);
  if (argc == 5) reps = atoi(argv[4]);
  if (nmax < 2 || !(seconds > 0) || reps < 1) return 2;
  for (n = 2; n <= nmax && m < MAX_SIZES; n *= 2) {
    autobal_rotor *rot = make_rotor(n, 0);
    unsigned long long seed = 12345u + n;
    double *ys, *dydt, ts[N_STATES];
    if (rot == NULL) return 1;
    dim = autobal_rotor_dim(rot);
    ys = malloc(N_STATES * dim * sizeof(double));
    dydt = malloc(dim * sizeof(double));
    if (ys == NULL || dydt == NULL) return 1;
    for (s = 0; s < N_STATES; s++) {
      ts[s] = 0.01 * (double)s + 0.001;
      random_state(&seed, autobal_rotor_omega(rot), ts[s], n, ys + s * dim);
    }
    nn[m] = (double)n;
    fixed_ns[m] = time_rhs(autobal_rotor_rhs, rot, ys, ts, dydt, dim, seconds, reps, &sink);
    rot_ns[m] = time_rhs(autobal_rotor_rhs_rotating, rot, ys, ts, dydt, dim, seconds, reps, &sink);
    if (!isfinite(fixed_ns[m]) || !isfinite(rot_ns[m])) {
      fprintf(stderr, "bench_rotor: rhs failed: %s\n", autobal_rotor_errmsg(rot));
      return 1;
    }
    m++;
    free(ys);
    free(dydt);
    autobal_rotor_free(rot);
  }
  fit_line(nn, fixed_ns, m, &fa, &fb, &fr2, &fmr);
  fit_line(nn, rot_ns, m, &ra, &rb, &rr2, &rmr);
  printf("{");
  print_array("n", nn, m, "%.0f");
  printf(", ");
  print_array("fixed_ns", fixed_ns, m, "%.4g");
  printf(", ");
  print_array("rotating_ns", rot_ns, m, "%.4g");
  printf(", \"fixed_fit\": {\"a\": %.6g, \"b\": %.6g, \"r2\": %.8f, \"max_rel_resid\": %.4g}",
         fa, fb, fr2, fmr);
  printf(", \"rotating_fit\": {\"a\": %.6g, \"b\": %.6g, \"r2\": %.8f, \"max_rel_resid\": %.4g}",
         ra, rb, rr2, rmr);
  printf(", \"checksum\": %.6g}\n", sink);
  return 0;
}

static int mode_check(int argc, char **argv) {
  autobal_rotor *rot;
  size_t n, dim, s, i;
  unsigned long long seed = 777u;
  double *y, *dydt;
  if (argc != 3) return 2;
  n = (size_t)strtoul(argv[2], NULL, 10);
  if (n < 1) return 2;
  rot = make_rotor(n, 1);
  if (rot == NULL) return 1;
  dim = autobal_rotor_dim(rot);
  y = malloc(dim * sizeof(double));
  dydt = malloc(dim * sizeof(double));
  if (y == NULL || dydt == NULL) return 1;
  printf("{\"n_balls\": %zu, \"dim\": %zu, \"states\": [", n, dim);
  for (s = 0; s < 5; s++) {
    const double t = s == 0 ? 0.0 : 0.0371 * (double)s;
    if (s == 0) {
      if (autobal_rotor_initial_state(rot, AUTOBAL_ROTOR_FIXED, 0.0, y, dim) != AUTOBAL_SUCCESS)
        return 1;
    } else {
      random_state(&seed, autobal_rotor_omega(rot), t, n, y);
    }
    if (autobal_rotor_rhs(t, y, dydt, rot) != 0) {
      fprintf(stderr, "bench_rotor: %s\n", autobal_rotor_errmsg(rot));
      return 1;
    }
    printf("%s{\"t\": %.17g, \"y\": [", s ? ", " : "", t);
    for (i = 0; i < dim; i++) printf("%.17g%s", y[i], i + 1 < dim ? ", " : "], \"dydt\": [");
    for (i = 0; i < dim; i++) printf("%.17g%s", dydt[i], i + 1 < dim ? ", " : "]}");
  }
  printf("]}\n");
  free(y);
  free(dydt);
  autobal_rotor_free(rot);
  return 0;
}

int main(int argc, char **argv) {
  int rc = 2;
  gsl_set_error_handler_off();
  if (argc >= 2 && strcmp(argv[1], "run") == 0) rc = mode_run(argc, argv);
  else if (argc >= 2 && strcmp(argv[1], "rhs") == 0) rc = mode_rhs(argc, argv);
  else if (argc >= 2 && strcmp(argv[1], "check") == 0) rc = mode_check(argc, argv);
  if (rc == 2)
    fprintf(stderr,
            "usage: %s run NBALLS STEPPER RTOL ATOL T1 REPEATS [fixed|rotating]\n"
            "       %s rhs NMAX SECONDS [REPS]\n"
            "       %s check NBALLS\n",
            argv[0], argv[0], argv[0]);
  return rc;
}
