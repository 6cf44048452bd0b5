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
 *   bench_rotor runup STEPPER RTOL ATOL T1 REPEATS OMEGA_B T_B [fixed|rotating]
 *       Run-up of the default rotor (two balls, rotor.md) with the prescribed
 *       RAMP drive Omega(t) = OMEGA_B t / T_B for 0 <= t <= T_B, OMEGA_B after
 *       (autobal_rotor_drive: omega_a = 0, t_a = 0), from rest (balls at rest
 *       relative to the rotor at psi = 1.0, 2.5) to T1; same output as run.
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
 *   bench_rotor check NBALLS [OMEGA_B T_B]
 *       The initial state and 4 pseudo-random states with the fixed-frame
 *       right-hand side at each (JSON), so that rotor_scipy.py can check its
 *       own independent right-hand side against the library's.  With OMEGA_B
 *       and T_B: the run-up drive of `runup` (NBALLS must be 2), states at
 *       t = 0 and t = 0.4 k T_B - 0.0123, k = 1 .. 4 (during and after the
 *       ramp; ball angles phi_0(t) + U(-pi, pi), rates Omega(t) + U(-50, 50)),
 *       so that runup_scipy.py can check its right-hand side.
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
 * otherwise ball_config(n) in its single plane), spinning at the constant
 * omega (drive NULL) or with the given prescribed drive.  NULL on failure
 * (message printed). */
static autobal_rotor *make_rotor_drive(size_t n, int use_default, const autobal_rotor_drive *drive) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor *r;
  autobal_error err;
  ball_config b;
  if (drive != NULL) p.drive = *drive;
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

static autobal_rotor *make_rotor(size_t n, int use_default) {
  return make_rotor_drive(n, use_default, NULL);
}

/* The run-up drive: Omega from 0 at t = 0 linearly to omega_b at t_b, omega_b after. */
static autobal_rotor_drive runup_drive(double omega_b, double t_b) {
  autobal_rotor_drive d;
  memset(&d, 0, sizeof d);
  d.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
  d.omega_a = 0.0;
  d.omega_b = omega_b;
  d.t_a = 0.0;
  d.t_b = t_b;
  return d;
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

/* Transient of rotor n (make_rotor_drive(n, 1, drive)) from its initial state at t = 0 to t1,
 * repeats times; prints the JSON of `run` / `runup`. */
static int run_transient(size_t n, const autobal_rotor_drive *drive, autobal_transient_options o,
                         double t1, int repeats, int frame) {
  autobal_transient_system sys;
  autobal_transient_stats st;
  autobal_transient *tr;
  autobal_rotor *rot;
  autobal_error err;
  double *y, *times, *cpu, c0;
  size_t dim, i;
  int r;
  rot = make_rotor_drive(n, 1, drive);
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
         "\"rtol\": %.3g, \"atol\": %.3g, \"t1\": %.17g, \"repeats\": %d, ",
         n, frame == AUTOBAL_ROTOR_FIXED ? "fixed" : "rotating", dim, o.stepper, o.rtol, o.atol,
         t1, repeats);
  if (drive != NULL)
    printf("\"drive\": {\"mode\": \"ramp\", \"omega_a\": %.17g, \"omega_b\": %.17g, \"t_a\": %.17g, "
           "\"t_b\": %.17g}, ",
           drive->omega_a, drive->omega_b, drive->t_a, drive->t_b);
  printf("\"seconds\": %.9g, \"seconds_min\": %.9g, \"cpu_seconds_min\": %.9g, "
         "\"steps\": %lu, \"rejected\": %lu, \"rhs_evals\": %lu, \"y\": [",
         times[repeats / 2], times[0], cpu[0], st.steps, st.rejected, st.rhs_evals);
  for (i = 0; i < dim; i++) printf("%.17g%s", y[i], i + 1 < dim ? ", " : "]}\n");
  free(times);
  free(cpu);
  free(y);
  autobal_transient_free(tr);
  autobal_rotor_free(rot);
  return 0;
}

/* "fixed" / "rotating" (NULL: fixed) into *frame; 0 on success. */
static int parse_frame(const char *s, int *frame) {
  if (s == NULL || strcmp(s, "fixed") == 0) *frame = AUTOBAL_ROTOR_FIXED;
  else if (strcmp(s, "rotating") == 0) *frame = AUTOBAL_ROTOR_ROTATING;
  else return -1;
  return 0;
}

static int mode_run(int argc, char **argv) {
  autobal_transient_options o = autobal_transient_options_default();
  double t1;
  size_t n;
  int repeats, frame;
  if (argc != 8 && argc != 9) return 2;
  n = (size_t)strtoul(argv[2], NULL, 10);
  o.stepper = argv[3];
  o.rtol = atof(argv[4]);
  o.atol = atof(argv[5]);
  t1 = atof(argv[6]);
  repeats = atoi(argv[7]);
  if (parse_frame(argc == 9 ? argv[8] : NULL, &frame) != 0) return 2;
  if (repeats < 1) repeats = 1;
  if (n < 1) return 2;
  return run_transient(n, NULL, o, t1, repeats, frame);
}

static int mode_runup(int argc, char **argv) {
  autobal_transient_options o = autobal_transient_options_default();
  autobal_rotor_drive d;
  double t1, omega_b, t_b;
  int repeats, frame;
  if (argc != 9 && argc != 10) return 2;
  o.stepper = argv[2];
  o.rtol = atof(argv[3]);
  o.atol = atof(argv[4]);
  t1 = atof(argv[5]);
  repeats = atoi(argv[6]);
  omega_b = atof(argv[7]);
  t_b = atof(argv[8]);
  if (parse_frame(argc == 10 ? argv[9] : NULL, &frame) != 0) return 2;
  if (repeats < 1) repeats = 1;
  if (!(t_b > 0) || !isfinite(omega_b) || !(t1 > 0)) return 2;
  d = runup_drive(omega_b, t_b);
  return run_transient(2, &d, o, t1, repeats, frame);
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
  autobal_rotor_drive d;
  size_t n, dim, s, i;
  unsigned long long seed = 777u;
  double *y, *dydt, t_b = 0.0;
  int ramp = argc == 5;
  if (argc != 3 && argc != 5) return 2;
  n = (size_t)strtoul(argv[2], NULL, 10);
  if (n < 1) return 2;
  if (ramp) {
    t_b = atof(argv[4]);
    if (n != 2 || !(t_b > 0) || !isfinite(atof(argv[3]))) return 2;
    d = runup_drive(atof(argv[3]), t_b);
  }
  rot = make_rotor_drive(n, 1, ramp ? &d : NULL);
  if (rot == NULL) return 1;
  dim = autobal_rotor_dim(rot);
  y = malloc(dim * sizeof(double));
  dydt = malloc(dim * sizeof(double));
  if (y == NULL || dydt == NULL) return 1;
  printf("{\"n_balls\": %zu, \"dim\": %zu, \"states\": [", n, dim);
  for (s = 0; s < 5; s++) {
    const double t = s == 0 ? 0.0 : ramp ? 0.4 * t_b * (double)s - 0.0123 : 0.0371 * (double)s;
    if (s == 0) {
      if (autobal_rotor_initial_state(rot, AUTOBAL_ROTOR_FIXED, 0.0, y, dim) != AUTOBAL_SUCCESS)
        return 1;
    } else if (ramp) {
      /* random_state with phi_0(t) for omega t and Omega(t) for omega */
      double w[3];
      if (autobal_rotor_drive_eval(rot, t, w) != AUTOBAL_SUCCESS) return 1;
      random_state(&seed, w[0], 1.0, n, y);
      for (i = 0; i < n; i++) y[8 + i] += w[2] - w[0];
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
  else if (argc >= 2 && strcmp(argv[1], "runup") == 0) rc = mode_runup(argc, argv);
  else if (argc >= 2 && strcmp(argv[1], "rhs") == 0) rc = mode_rhs(argc, argv);
  else if (argc >= 2 && strcmp(argv[1], "check") == 0) rc = mode_check(argc, argv);
  if (rc == 2)
    fprintf(stderr,
            "usage: %s run NBALLS STEPPER RTOL ATOL T1 REPEATS [fixed|rotating]\n"
            "       %s runup STEPPER RTOL ATOL T1 REPEATS OMEGA_B T_B [fixed|rotating]\n"
            "       %s rhs NMAX SECONDS [REPS]\n"
            "       %s check NBALLS [OMEGA_B T_B]\n",
            argv[0], argv[0], argv[0], argv[0]);
  return rc;
}
