/* bench_perf.c: the C side of the performance benchmarks (bench/perf/perf.py
 * runs it and measures the NumPy references side by side).  Every command
 * prints one JSON object on stdout.  Times are wall times (CLOCK_MONOTONIC),
 * best of REPS repetitions (the machine is shared; the best run is the one
 * least disturbed by other processes); the one-thread measurements of
 * `roots` use the process CPU time instead (CLOCK_PROCESS_CPUTIME_ID).
 *
 *   bench_perf roots N REPS FILE
 *       N pendulum polynomials (6) from deterministic pseudo-random
 *       parameters (R_w in [0, 5], R_m in [0.005, 0.495], H, h in [0, 0.5],
 *       k in [0, 1]); their coefficients are written to FILE (N x 9
 *       float64, ascending) for the NumPy side.  Times per polynomial:
 *       autobal_poly_roots (degree 8, Aberth / companion QR), the sign-test verdict
 *       autobal_pendulum_verdict (builds (6) + Routh test with rounding
 *       bounds, validation included) and autobal_poly_hurwitz on the stored
 *       coefficients.
 *   bench_perf map N_RM N_RW H h NK THREADS REPS [FILE]
 *       autobal_pendulum_map over R_m in [0.005, 0.495] x R_w in [0.05, 5]
 *       (the CLI's default ranges); NK = 1: k = sin^2(1) (psi0 = 0.5),
 *       NK = 0: the default 65 values k = j/64 ("every unbalance").  FILE:
 *       the verdicts (int8, row-major [R_m][R_w]).
 *   bench_perf hdf5 NSAMP NCH REPS FILE
 *       the pendulum transient (rk8pd, rtol 1e-10, atol 1e-12, R_w = 3,
 *       R_m = 0.1, H = 0.05, h = 0.1, psi0 = 0.5, from rest) with NSAMP
 *       output samples (dt_out = 0.1); at every sample the observer computes
 *       NCH <= 20 channels (the state, autobal_pendulum_motion_derive, the
 *       damping power, the accelerations); run once without writing and
 *       once appending every sample to an archive series
 *       (autobal_archive_series_append) in FILE, alternately, REPS times.
 *   bench_perf rhs T1 RTOL REPS
 *       share of the run time spent in the right-hand side: the transient of
 *       bench/bench_pendulum.c (rk8pd, tau in [0, T1], no output); a second
 *       run records every (t, y) at which the rhs is called, and the time of
 *       calling the rhs alone on those states is compared with the run time.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "autobal/archive.h"
#include "autobal/pendulum.h"
#include "autobal/stability.h"
#include "autobal/transient.h"

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* CPU time of the calling thread (the HDF5 measurement: the archive's writer
 * thread is not counted) */
static double thread_cpu_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* process CPU time: for the one-thread measurements (roots, verdicts), so
 * that time the process spends preempted by other processes does not count */
static double cpu_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static unsigned long long rng = 0x9E3779B97F4A7C15ULL;
static double urand(void) {
  rng ^= rng >> 12;
  rng ^= rng << 25;
  rng ^= rng >> 27;
  return (double)((rng * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

static int die(const char *what, const char *msg) {
  fprintf(stderr, "bench_perf: %s: %s\n", what, msg);
  return 1;
}

/* ---- roots and verdicts ------------------------------------------------ */

static int cmd_roots(int argc, char **argv) {
  size_t n, i;
  int reps, r, st;
  autobal_pendulum_params *ps;
  double *c, re[8], im[8], t, best_roots = INFINITY, best_verdict = INFINITY,
                             best_hurwitz = INFINITY, sink = 0.0;
  long nstable = 0;
  autobal_poly_workspace *w;
  autobal_error err;
  FILE *f;
  if (argc != 5) return die("roots", "usage: roots N REPS FILE");
  n = (size_t)atol(argv[2]);
  reps = atoi(argv[3]);
  ps = malloc(n * sizeof *ps);
  c = malloc(n * 9 * sizeof *c);
  w = autobal_poly_workspace_alloc(8);
  if (!ps || !c || !w) return die("roots", "out of memory");
  for (i = 0; i < n; i++) {
    double k = urand();
    st = autobal_pendulum_params_from_k(5.0 * urand(), 0.005 + 0.49 * urand(), 0.5 * urand(),
                                        0.5 * urand(), k, &ps[i], &err);
    if (st) return die("params", err.message);
    if ((st = autobal_pendulum_char_poly(&ps[i], c + 9 * i, &err)) != 0)
      return die("char_poly", err.message);
  }
  f = fopen(argv[4], "wb");
  if (!f || fwrite(c, sizeof *c, 9 * n, f) != 9 * n || fclose(f)) return die("roots", "cannot write FILE");
  for (r = 0; r < reps; r++) {
    t = cpu_now();
    for (i = 0; i < n; i++) {
      if ((st = autobal_poly_roots(w, c + 9 * i, 9, re, im, &err)) != 0)
        return die("poly_roots", err.message);
      sink += re[7];
    }
    t = cpu_now() - t;
    if (t < best_roots) best_roots = t;
    t = cpu_now();
    for (i = 0; i < n; i++) {
      int v;
      if ((st = autobal_pendulum_verdict(&ps[i], &v, NULL, &err)) != 0)
        return die("verdict", err.message);
      nstable += v == AUTOBAL_VERDICT_STABLE;
    }
    t = cpu_now() - t;
    if (t < best_verdict) best_verdict = t;
    t = cpu_now();
    for (i = 0; i < n; i++) {
      int v;
      if ((st = autobal_poly_hurwitz(c + 9 * i, 9, 1e-12, &v, NULL, &err)) != 0)
        return die("hurwitz", err.message);
      sink += v;
    }
    t = cpu_now() - t;
    if (t < best_hurwitz) best_hurwitz = t;
  }
  { /* the roots, for the agreement check against NumPy: FILE.roots, (re, im) x 8 per polynomial */
    char path[4096];
    double *z = malloc(16 * n * sizeof *z);
    if (!z) return die("roots", "out of memory");
    for (i = 0; i < n; i++) {
      size_t j;
      if ((st = autobal_poly_roots(w, c + 9 * i, 9, re, im, &err)) != 0)
        return die("poly_roots", err.message);
      for (j = 0; j < 8; j++) {
        z[16 * i + 2 * j] = re[j];
        z[16 * i + 2 * j + 1] = im[j];
      }
    }
    snprintf(path, sizeof path, "%s.roots", argv[4]);
    f = fopen(path, "wb");
    if (!f || fwrite(z, sizeof *z, 16 * n, f) != 16 * n || fclose(f))
      return die("roots", "cannot write FILE.roots");
    free(z);
  }
  printf("{\"n\": %zu, \"reps\": %d, \"roots_s_per_poly\": %.6g, \"roots_per_s\": %.6g, "
         "\"verdict_s\": %.6g, \"hurwitz_s\": %.6g, \"stable_fraction\": %.4f, \"sink\": %.6g}\n",
         n, reps, best_roots / (double)n, 8.0 * (double)n / best_roots, best_verdict / (double)n,
         best_hurwitz / (double)n, (double)nstable / (double)(n * (size_t)reps), sink);
  autobal_poly_workspace_free(w);
  free(ps);
  free(c);
  return 0;
}

/* ---- maps -------------------------------------------------------------- */

static int cmd_map(int argc, char **argv) {
  size_t nrm, nrw, i, ntot;
  int nk, thr, reps, r, st;
  double H, h, k1, *rm, *rw, best = INFINITY, tot = 0.0;
  long cnt[3] = {0, 0, 0};
  signed char *v;
  autobal_pendulum_map_spec s;
  autobal_error err;
  if (argc != 9 && argc != 10) return die("map", "usage: map N_RM N_RW H h NK THREADS REPS [FILE]");
  nrm = (size_t)atol(argv[2]);
  nrw = (size_t)atol(argv[3]);
  H = atof(argv[4]);
  h = atof(argv[5]);
  nk = atoi(argv[6]);
  thr = atoi(argv[7]);
  reps = atoi(argv[8]);
  ntot = nrm * nrw;
  rm = malloc(nrm * sizeof *rm);
  rw = malloc(nrw * sizeof *rw);
  v = malloc(ntot);
  if (!rm || !rw || !v) return die("map", "out of memory");
  for (i = 0; i < nrm; i++) rm[i] = 0.005 + 0.49 * (double)i / (double)(nrm > 1 ? nrm - 1 : 1);
  for (i = 0; i < nrw; i++) rw[i] = 0.05 + 4.95 * (double)i / (double)(nrw > 1 ? nrw - 1 : 1);
  k1 = sin(1.0) * sin(1.0);
  memset(&s, 0, sizeof s);
  s.R_m = rm, s.n_Rm = nrm, s.R_w = rw, s.n_Rw = nrw, s.H = H, s.h = h, s.n_threads = thr;
  if (nk == 1) s.k = &k1, s.n_k = 1;
  for (r = 0; r < reps; r++) {
    double t = now();
    st = autobal_pendulum_map(&s, v, NULL, &err);
    t = now() - t;
    if (st) return die("map", err.message);
    if (t < best) best = t;
    tot += t;
  }
  for (i = 0; i < ntot; i++) cnt[v[i] + 1]++;
  if (argc == 10) {
    FILE *f = fopen(argv[9], "wb");
    if (!f || fwrite(v, 1, ntot, f) != ntot || fclose(f)) return die("map", "cannot write FILE");
  }
  printf("{\"n_Rm\": %zu, \"n_Rw\": %zu, \"H\": %g, \"h\": %g, \"n_k\": %d, \"threads\": %d, "
         "\"reps\": %d, \"seconds\": %.6g, \"seconds_mean\": %.6g, \"ns_per_point\": %.4g, "
         "\"stable\": %ld, \"marginal\": %ld, \"unstable\": %ld}\n",
         nrm, nrw, H, h, nk == 1 ? 1 : 65, thr, reps, best, tot / reps,
         1e9 * best / (double)ntot, cnt[2], cnt[1], cnt[0]);
  free(rm);
  free(rw);
  free(v);
  return 0;
}

/* ---- HDF5 output ---------------------------------------------------------- */

#define NCH_MAX 20
typedef struct {
  autobal_pendulum_motion m;
  autobal_archive_series *series; /* NULL: compute the channels, write nothing */
  size_t nch;
  double sink;
  int status;
} obs_ctx;

static void channels(obs_ctx *o, const double y[], double out[NCH_MAX]) {
  autobal_pendulum_motion_derived d;
  double dy[8];
  size_t i;
  for (i = 0; i < 8; i++) out[i] = y[i];
  autobal_pendulum_motion_derive(&o->m.p, y, &d);
  out[8] = d.amplitude, out[9] = d.unbalance, out[10] = d.unbalance_u, out[11] = d.unbalance_v;
  out[12] = d.alpha, out[13] = d.beta, out[14] = d.jacobi;
  out[15] = autobal_pendulum_jacobi_power(&o->m.p, y);
  autobal_pendulum_motion_rhs(0.0, y, dy, &o->m);
  for (i = 0; i < 4; i++) out[16 + i] = dy[4 + i];
}

static int observer(double t, const double y[], void *user) {
  obs_ctx *o = (obs_ctx *)user;
  double ch[NCH_MAX];
  channels(o, y, ch);
  if (o->series) {
    int st = autobal_archive_series_append(o->series, 1, &t, ch);
    if (st) {
      o->status = st;
      return 1;
    }
  } else {
    o->sink += ch[0] + ch[o->nch - 1];
  }
  return 0;
}

static int cmd_hdf5(int argc, char **argv) {
  static const char *names[NCH_MAX] = {"xi", "eta", "psi", "phi", "dxi", "deta", "dpsi",
                                       "dphi", "amplitude", "unbalance", "unbalance_u",
                                       "unbalance_v", "alpha", "beta", "jacobi", "power",
                                       "ddxi", "ddeta", "ddpsi", "ddphi"};
  static const char *units[NCH_MAX] = {"1", "1", "rad", "rad", "1", "1", "1", "1", "1", "1",
                                       "1", "1", "rad", "rad", "1", "1", "1", "1", "1", "1"};
  autobal_pendulum_params p = {3.0, 0.1, 0.05, 0.1, 0.5};
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient *tr;
  autobal_transient_stats stats;
  autobal_error err;
  obs_ctx oc;
  size_t nsamp, nch;
  int reps, r, st;
  double best_plain = INFINITY, best_write = INFINITY, t1, y[8];
  double cpu_write = 0.0, main_cpu_write = 0.0, main_cpu_plain = INFINITY;
  long long fsize = 0;
  if (argc != 6) return die("hdf5", "usage: hdf5 NSAMP NCH REPS FILE");
  nsamp = (size_t)atol(argv[2]);
  nch = (size_t)atol(argv[3]);
  reps = atoi(argv[4]);
  if (nch < 1 || nch > NCH_MAX || nsamp < 2) return die("hdf5", "need 1 <= NCH <= 20, NSAMP >= 2");
  memset(&oc, 0, sizeof oc);
  if (autobal_pendulum_motion_init(&oc.m, &p, &err)) return die("motion_init", err.message);
  oc.nch = nch;
  sys.rhs = autobal_pendulum_motion_rhs;
  sys.jac = autobal_pendulum_motion_jac;
  sys.dim = 8;
  sys.params = &oc.m;
  o.dt_out = 0.1;
  t1 = 0.1 * (double)(nsamp - 1); /* samples at 0, 0.1, ..., t1 */
  tr = autobal_transient_alloc(8, &o, &err);
  if (!tr) return die("transient_alloc", err.message);
  autobal_transient_set_observer(tr, observer, &oc);
  for (r = 0; r < reps; r++) {
    int mode;
    for (mode = 0; mode < 2; mode++) {
      autobal_archive *a = NULL;
      double t, cpu0 = cpu_now(), th0 = thread_cpu_now();
      oc.series = NULL;
      oc.status = 0;
      t = now();
      if (mode == 1) {
        if ((st = autobal_archive_create(argv[5], 1, &a, &err)) != 0) return die("archive", err.message);
        if ((st = autobal_archive_series_open(a, "/bench", "time", "1", "dimensionless time",
                                              nch, names, units, NULL, &oc.series)) != 0)
          return die("series_open", autobal_archive_errmsg(a));
      }
      memset(y, 0, sizeof y);
      st = autobal_transient_run(tr, &sys, 0.0, t1, y, NULL);
      if (st) return die("run", oc.status ? autobal_archive_errmsg(a) : autobal_transient_errmsg(tr));
      if (mode == 1) {
        if ((st = autobal_archive_series_close(oc.series)) != 0)
          return die("series_close", autobal_archive_errmsg(a));
        if ((st = autobal_archive_close(a, &err)) != 0) return die("archive_close", err.message);
      }
      t = now() - t;
      if (mode == 0 && t < best_plain) best_plain = t;
      if (mode == 0 && thread_cpu_now() - th0 < main_cpu_plain) main_cpu_plain = thread_cpu_now() - th0;
      if (mode == 1 && t < best_write) {
        best_write = t;
        cpu_write = cpu_now() - cpu0;
        main_cpu_write = thread_cpu_now() - th0;
      }
    }
  }
  autobal_transient_get_stats(tr, &stats);
  {
    FILE *f = fopen(argv[5], "rb");
    if (f && fseek(f, 0, SEEK_END) == 0) fsize = (long long)ftell(f);
    if (f) fclose(f);
  }
  printf("{\"samples\": %lu, \"channels\": %zu, \"reps\": %d, \"steps\": %lu, \"rhs_evals\": %lu, "
         "\"seconds_no_write\": %.6g, \"seconds_write\": %.6g, \"overhead\": %.4f, "
         "\"raw_bytes\": %lld, \"file_bytes\": %lld, \"ratio\": %.3f, "
         "\"main_cpu_no_write\": %.6g, \"main_cpu_write\": %.6g, \"process_cpu_write\": %.6g}\n",
         stats.observer_calls, nch, reps, stats.steps, stats.rhs_evals, best_plain, best_write,
         best_write / best_plain - 1.0, (long long)(stats.observer_calls * (nch + 1) * 8), fsize,
         fsize > 0 ? (double)(stats.observer_calls * (nch + 1) * 8) / (double)fsize : 0.0, main_cpu_plain,
         main_cpu_write, cpu_write);
  autobal_transient_free(tr);
  return 0;
}

/* ---- share of the right-hand side --------------------------------------- */

typedef struct {
  autobal_pendulum_motion m;
  double *ty; /* recorded (t, y[8]) per call */
  size_t n, cap;
} rec_ctx;

static int rhs_rec(double t, const double y[], double dydt[], void *params) {
  rec_ctx *rc = (rec_ctx *)params;
  if (rc->n < rc->cap) {
    rc->ty[9 * rc->n] = t;
    memcpy(rc->ty + 9 * rc->n + 1, y, 8 * sizeof(double));
    rc->n++;
  }
  return autobal_pendulum_motion_rhs(t, y, dydt, &rc->m);
}

static int cmd_rhs(int argc, char **argv) {
  autobal_pendulum_params p = {3.0, 0.1, 0.05, 0.1, 0.5};
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient *tr;
  autobal_transient_stats stats;
  autobal_error err;
  rec_ctx rc;
  double t1, y[8], dy[8], best_run = INFINITY, best_rhs = INFINITY, sink = 0.0;
  int reps, r, st;
  size_t i;
  if (argc != 5) return die("rhs", "usage: rhs T1 RTOL REPS");
  t1 = atof(argv[2]);
  o.rtol = o.atol = atof(argv[3]);
  reps = atoi(argv[4]);
  memset(&rc, 0, sizeof rc);
  if (autobal_pendulum_motion_init(&rc.m, &p, &err)) return die("motion_init", err.message);
  tr = autobal_transient_alloc(8, &o, &err);
  if (!tr) return die("transient_alloc", err.message);
  sys.rhs = autobal_pendulum_motion_rhs;
  sys.jac = autobal_pendulum_motion_jac;
  sys.dim = 8;
  sys.params = &rc.m;
  for (r = 0; r < reps; r++) {
    double t;
    memset(y, 0, sizeof y);
    t = now();
    st = autobal_transient_run(tr, &sys, 0.0, t1, y, NULL);
    t = now() - t;
    if (st) return die("run", autobal_transient_errmsg(tr));
    if (t < best_run) best_run = t;
  }
  autobal_transient_get_stats(tr, &stats);
  rc.cap = stats.rhs_evals + 16;
  rc.ty = malloc(rc.cap * 9 * sizeof(double));
  if (!rc.ty) return die("rhs", "out of memory");
  sys.rhs = rhs_rec;
  sys.params = &rc;
  memset(y, 0, sizeof y);
  if (autobal_transient_run(tr, &sys, 0.0, t1, y, NULL)) return die("run", autobal_transient_errmsg(tr));
  for (r = 0; r < reps; r++) {
    double t = now();
    for (i = 0; i < rc.n; i++) {
      autobal_pendulum_motion_rhs(rc.ty[9 * i], rc.ty + 9 * i + 1, dy, &rc.m);
      sink += dy[7];
    }
    t = now() - t;
    if (t < best_rhs) best_rhs = t;
  }
  printf("{\"t1\": %g, \"tol\": %g, \"reps\": %d, \"rhs_evals\": %lu, \"steps\": %lu, "
         "\"seconds_run\": %.6g, \"seconds_rhs\": %.6g, \"rhs_share\": %.4f, "
         "\"ns_per_eval_run\": %.4g, \"ns_per_rhs\": %.4g, \"sink\": %.6g}\n",
         t1, o.rtol, reps, stats.rhs_evals, stats.steps, best_run, best_rhs, best_rhs / best_run,
         1e9 * best_run / (double)stats.rhs_evals, 1e9 * best_rhs / (double)rc.n, sink);
  free(rc.ty);
  autobal_transient_free(tr);
  return 0;
}

int main(int argc, char **argv) {
  gsl_set_error_handler_off();
  if (argc >= 2 && strcmp(argv[1], "roots") == 0) return cmd_roots(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "map") == 0) return cmd_map(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "hdf5") == 0) return cmd_hdf5(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "rhs") == 0) return cmd_rhs(argc, argv);
  fprintf(stderr, "usage: bench_perf roots|map|hdf5|rhs ... (see the comment at the top)\n");
  return 2;
}
