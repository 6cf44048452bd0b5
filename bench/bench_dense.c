/* bench_dense.c: the cost of output every quarter revolution, dense (dop853 on its continuous
 * extension) or exact (steps cut at the output times), for the pendulum and the rotor; the
 * companion of bench/dense_scipy.py (issue 20), which runs it and prints the tables.
 *
 *   bench_dense MODEL NBALLS STEPPER OUTPUT RTOL ATOL REVS REVS_OUT REPEATS SAMPLES
 *
 * MODEL pendulum (the problem of bench_pendulum.c: R_w = 3, R_m = 0.1, H = 0.05, h = 0.1,
 * psi0 = 0.5, from rest; NBALLS ignored) or rotor (the default rotor of bench_rotor.c, one plane
 * with NBALLS balls: 2 = the default example, others 0.1/n kg each at psi_i = 1.0 + 0.4 i).
 * OUTPUT dense|dense6|exact (exact_output 0, dense_order 7 | exact_output 0, dense_order 6 | exact_output 1).  REVS revolutions, output every REVS_OUT revolutions.
 * Measured, interleaved in REPEATS rounds, best of each (thread CPU time: on the shared machine,
 * load 5-10 on 2 cores, a wall-clock best of N of a few-millisecond run still includes
 * preemption; SciPy's time in dense_scipy.py is time.process_time, the same measure):
 *   out:    the whole transient as the command line runs it, without the archive
 *           (autobal_study_pendulum_transient / autobal_study_rotor_transient with a = NULL:
 *           driver, balance monitor (a dwell event), the derived quantities at every output
 *           point, the summary), output every REVS_OUT revolutions;
 *   none:   the same without an output grid (only t0 and t_end);
 *   bare:   autobal_transient_run with the model's right-hand side only (no observer, no
 *           events, no output grid); then the right-hand side alone on every (t, y) that run
 *           evaluated it at (recorded in one more run), best of REPEATS: rhs_share = that time /
 *           the bare run's;
 *   samples: the driver with the study's stepper, tolerances and output grid and an observer
 *           storing (t, y) at every output time, written to SAMPLES (raw doubles, rows t,
 *           y[0..dim-1]; "-": not written), for the error at the output points.
 * Prints one JSON object.  REPEATS = 0: only one bare integration and nothing printed (for
 * callgrind: the share of the instructions inside the right-hand side, load-independent);
 * REPEATS = -K: K bare integrations and nothing printed (for a sampling profiler: the share of
 * the time inside the right-hand side, bench/issue20.py's perf_share). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "autobal/pendulum.h"
#include "autobal/rotor.h"
#include "autobal/study.h"
#include "autobal/transient.h"

#define PI 3.14159265358979323846

/* CPU time of this thread: on the shared machine (load 5-10 on 2 cores) a wall-clock best of N
 * of a few-millisecond run still includes preemption; the process CPU time does not (SciPy's
 * time in dense_scipy.py is time.process_time, the same measure). */
static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct rec {
  double *buf;
  size_t n, cap, dim;
  FILE *f;
} rec;

static int rec_obs(double t, const double y[], void *user) {
  rec *r = (rec *)user;
  if (r->f) {
    fwrite(&t, sizeof t, 1, r->f);
    fwrite(y, sizeof(double), r->dim, r->f);
  }
  r->n++;
  return 0;
}

/* the rhs with a record of its arguments (t, y), for the rhs-share measurement */
typedef struct rhs_rec {
  autobal_transient_rhs_fn f;
  void *params;
  size_t dim, n, cap;
  double *ty;
} rhs_rec;

static int rhs_recording(double t, const double y[], double dydt[], void *p) {
  rhs_rec *r = (rhs_rec *)p;
  if (r->n < r->cap) {
    double *row = r->ty + r->n * (r->dim + 1);
    row[0] = t;
    memcpy(row + 1, y, r->dim * sizeof(double));
    r->n++;
  }
  return r->f(t, y, dydt, r->params);
}

typedef struct setup {
  int pendulum;
  autobal_pendulum_params pp;
  autobal_rotor_params rp;
  const char *stepper;
  int exact, dense_order;
  double rtol, atol, t_end, period, revs, revs_out;
} setup;

/* One run of the whole transient without archive, with the output grid (grid = 1: every
 * revs_out revolutions) or without (only t0 and t_end); its CPU time, statistics into *st. */
static double run_study(const setup *c, int grid, autobal_transient_stats *st) {
  autobal_error err;
  double w0, w;
  int rc;
  if (c->pendulum) {
    autobal_study_pendulum_transient_options o = autobal_study_pendulum_transient_options_default();
    autobal_study_pendulum_transient_summary s;
    o.t_end = c->t_end;
    o.revs_out = grid ? c->revs_out : c->revs; /* no grid: one interval = the whole run */
    o.rtol = c->rtol;
    o.atol = c->atol;
    o.stepper = c->stepper;
    o.exact_output = c->exact;
    o.dense_order = c->dense_order;
    w0 = now_seconds();
    rc = autobal_study_pendulum_transient(&c->pp, NULL, &o, NULL, &s, &err);
    w = now_seconds() - w0;
    *st = s.solver;
  } else {
    autobal_study_rotor_transient_options o = autobal_study_rotor_transient_options_default();
    autobal_study_rotor_transient_summary s;
    memset(&s, 0, sizeof s);
    o.t_end = c->t_end;
    o.dt_out = grid ? c->revs_out * c->period : c->t_end;
    o.rtol = c->rtol;
    o.atol = c->atol;
    o.stepper = c->stepper;
    o.exact_output = c->exact;
    o.dense_order = c->dense_order;
    w0 = now_seconds();
    rc = autobal_study_rotor_transient(&c->rp, &o, NULL, &s, &err);
    w = now_seconds() - w0;
    *st = s.solver;
    autobal_study_rotor_transient_summary_free(&s);
  }
  if (rc != AUTOBAL_SUCCESS) {
    fprintf(stderr, "bench_dense: %s\n", err.message);
    exit(1);
  }
  return w;
}

int main(int argc, char **argv) {
  const char *model, *samples;
  size_t nballs, dim, i;
  double dt_out;
  double best_out = INFINITY, best_none = INFINITY, best_bare = INFINITY, best_rhs = INFINITY;
  int repeats, r, only_bare;
  autobal_transient_stats st_out, st_none, st_bare, st_samp;
  autobal_transient_options to = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient *tr;
  autobal_error err;
  autobal_pendulum_motion pm;
  autobal_rotor *rot = NULL;
  double *mass = NULL, *rad = NULL, *damp = NULL, *psi = NULL, *rate = NULL;
  double *y, *y0, *dydt;
  rec rc_out;
  rhs_rec rr;
  setup c;
  if (argc != 11) {
    fprintf(stderr, "usage: %s pendulum|rotor NBALLS STEPPER dense|dense6|exact RTOL ATOL REVS REVS_OUT REPEATS SAMPLES|-\n",
            argv[0]);
    return 2;
  }
  gsl_set_error_handler_off();
  memset(&c, 0, sizeof c);
  model = argv[1];
  nballs = (size_t)strtoul(argv[2], NULL, 10);
  c.stepper = argv[3];
  c.exact = strcmp(argv[4], "exact") == 0;
  c.dense_order = strcmp(argv[4], "dense6") == 0 ? 6 : 7;
  c.rtol = atof(argv[5]);
  c.atol = atof(argv[6]);
  c.revs = atof(argv[7]);
  c.revs_out = atof(argv[8]);
  repeats = atoi(argv[9]);
  samples = argv[10];
  only_bare = repeats <= 0;
  repeats = repeats < 0 ? -repeats : repeats < 1 ? 1 : repeats;
  c.pendulum = strcmp(model, "pendulum") == 0;
  if (c.pendulum) {
    const autobal_pendulum_params pp = {3.0, 0.1, 0.05, 0.1, 0.5};
    c.pp = pp;
    if (autobal_pendulum_motion_init(&pm, &c.pp, &err) != AUTOBAL_SUCCESS) return 1;
    dim = 8;
    c.period = 2.0 * PI / c.pp.R_w;
    sys.rhs = autobal_pendulum_motion_rhs;
    sys.params = &pm;
  } else {
    c.rp = autobal_rotor_params_default();
    if (nballs != 2) {
      mass = malloc(nballs * sizeof(double));
      rad = malloc(nballs * sizeof(double));
      damp = malloc(nballs * sizeof(double));
      psi = malloc(nballs * sizeof(double));
      rate = malloc(nballs * sizeof(double));
      for (i = 0; i < nballs; i++) {
        mass[i] = 0.1 / (double)nballs;
        rad[i] = 0.1;
        damp[i] = 0.1;
        psi[i] = 1.0 + 0.4 * (double)i;
        rate[i] = 0.0;
      }
      c.rp.plane[0].n_balls = nballs;
      c.rp.plane[0].ball_mass = mass;
      c.rp.plane[0].ball_radius = rad;
      c.rp.plane[0].ball_damping = damp;
      c.rp.plane[0].ball_psi = psi;
      c.rp.plane[0].ball_rate = rate;
    }
    rot = autobal_rotor_alloc(&c.rp, &err);
    if (!rot) {
      fprintf(stderr, "bench_dense: %s\n", err.message);
      return 1;
    }
    dim = autobal_rotor_dim(rot);
    c.period = 2.0 * PI / fabs(c.rp.omega);
    sys.rhs = autobal_rotor_rhs;
    sys.params = rot;
  }
  sys.jac = NULL;
  sys.dim = dim;
  c.t_end = c.revs * c.period;
  dt_out = c.revs_out * c.period;
  y = malloc(dim * sizeof(double));
  y0 = malloc(dim * sizeof(double));
  dydt = malloc(dim * sizeof(double));
  if (rot) autobal_rotor_initial_state(rot, AUTOBAL_ROTOR_FIXED, 0.0, y0, dim);
  else memset(y0, 0, dim * sizeof(double));

  to.stepper = c.stepper;
  to.rtol = c.rtol;
  to.atol = c.atol;
  to.exact_output = c.exact;
  to.dense_order = c.dense_order;
  to.event_tol = 1e-9 * c.t_end;
  tr = autobal_transient_alloc(dim, &to, &err);
  if (!tr) {
    fprintf(stderr, "bench_dense: %s\n", err.message);
    return 1;
  }
  /* interleaved: the study with and without the output grid and the bare integration, so that
   * the three see the same machine; best of REPEATS each */
  for (r = 0; r < repeats; r++) {
    double w;
    if (!only_bare) {
      w = run_study(&c, 1, &st_out);
      if (w < best_out) best_out = w;
      w = run_study(&c, 0, &st_none);
      if (w < best_none) best_none = w;
    }
    memcpy(y, y0, dim * sizeof(double));
    w = now_seconds();
    if (autobal_transient_run(tr, &sys, 0.0, c.t_end, y, NULL) != AUTOBAL_SUCCESS) return 1;
    w = now_seconds() - w;
    autobal_transient_get_stats(tr, &st_bare);
    if (w < best_bare) best_bare = w;
  }
  if (only_bare) {
    autobal_transient_free(tr);
    autobal_rotor_free(rot);
    free(mass), free(rad), free(damp), free(psi), free(rate);
    free(y), free(y0), free(dydt);
    return 0;
  }
  /* the bare run's right-hand sides alone, on the recorded arguments */
  rr.f = sys.rhs;
  rr.params = sys.params;
  rr.dim = dim;
  rr.n = 0;
  rr.cap = st_bare.rhs_evals + 16;
  rr.ty = malloc(rr.cap * (dim + 1) * sizeof(double));
  {
    autobal_transient_system sr = sys;
    sr.rhs = rhs_recording;
    sr.params = &rr;
    memcpy(y, y0, dim * sizeof(double));
    if (!rr.ty || autobal_transient_run(tr, &sr, 0.0, c.t_end, y, NULL) != AUTOBAL_SUCCESS) return 1;
  }
  for (r = 0; r < repeats; r++) {
    const double w0 = now_seconds();
    double acc = 0.0, w;
    size_t k;
    for (k = 0; k < rr.n; k++) {
      const double *row = rr.ty + k * (dim + 1);
      sys.rhs(row[0], row + 1, dydt, sys.params);
      acc += dydt[dim - 1];
    }
    w = now_seconds() - w0;
    if (!(acc == acc)) return 1; /* keeps the calls */
    if (w < best_rhs) best_rhs = w;
  }

  /* the samples at the output times */
  to.dt_out = dt_out;
  autobal_transient_set_options(tr, &to);
  memset(&rc_out, 0, sizeof rc_out);
  rc_out.dim = dim;
  if (strcmp(samples, "-") != 0) {
    rc_out.f = fopen(samples, "wb");
    if (!rc_out.f) return 1;
  }
  autobal_transient_set_observer(tr, rec_obs, &rc_out);
  memcpy(y, y0, dim * sizeof(double));
  if (autobal_transient_run(tr, &sys, 0.0, c.t_end, y, NULL) != AUTOBAL_SUCCESS) return 1;
  autobal_transient_get_stats(tr, &st_samp);
  if (rc_out.f) fclose(rc_out.f);

  printf("{\"model\": \"%s\", \"nballs\": %zu, \"dim\": %zu, \"stepper\": \"%s\", \"output\": \"%s\", "
         "\"rtol\": %.3g, \"atol\": %.3g, \"revs\": %g, \"revs_out\": %g, \"t_end\": %.17g, \"dt_out\": %.17g, "
         "\"repeats\": %d, \"out_seconds\": %.9g, \"out_rhs\": %lu, \"out_steps\": %lu, \"out_rejected\": %lu, "
         "\"none_seconds\": %.9g, \"none_rhs\": %lu, \"none_steps\": %lu, "
         "\"bare_seconds\": %.9g, \"bare_rhs\": %lu, \"bare_steps\": %lu, "
         "\"rhs_only_seconds\": %.9g, \"rhs_share\": %.4f, \"samples\": %lu, \"samples_rhs\": %lu}\n",
         model, nballs, dim, c.stepper, c.exact ? "exact" : c.dense_order == 6 ? "dense6" : "dense", c.rtol, c.atol, c.revs, c.revs_out, c.t_end,
         dt_out, repeats, best_out, st_out.rhs_evals, st_out.steps, st_out.rejected, best_none, st_none.rhs_evals,
         st_none.steps, best_bare, st_bare.rhs_evals, st_bare.steps, best_rhs, best_rhs / best_bare, rc_out.n,
         st_samp.rhs_evals);
  autobal_transient_free(tr);
  autobal_rotor_free(rot);
  free(mass), free(rad), free(damp), free(psi), free(rate);
  free(y), free(y0), free(dydt), free(rr.ty);
  return 0;
}
