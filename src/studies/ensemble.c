/* ensemble.c: the ensemble engine (include/autobal/ensemble.h): members (grid or splitmix64
 * samples), one transient driver per OpenMP thread, the journal and resume, progress and
 * cancellation hooks, the hook that deals members over processes and gathers their records, the
 * tally and the archive layout /<model>/ensemble.  The model comes in through the member's
 * callbacks (ensemble_members.c has the rotor's and the pendulum's). */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#define ENS_PRAGMA(x) _Pragma(#x)
#else
#define ENS_PRAGMA(x)
#endif

#include "autobal/ensemble.h"
#include "autobal/version.h"
#include "internal.h"

#define TWO_PI 6.283185307179586476925286766559
#define ENS_MAX_SERIES_DOUBLES (1UL << 28) /* 2 GiB of kept series in all */
#define ENS_NAME 64
#define JOURNAL_HEADER 48

typedef struct ens_series {
  size_t n, cap, ncols;
  double *t, *rows;
} ens_series;

typedef struct ens_buf {
  double *v;
  size_t n, cap;
} ens_buf;

struct autobal_ensemble {
  autobal_ensemble_member mb;
  autobal_ensemble_settings s;
  char names[AUTOBAL_ENSEMBLE_MAX_PARAMS][ENS_NAME];
  char stepper[32];
  char tname[AUTOBAL_ENSEMBLE_MAX_TARGETS][ENS_NAME]; /* the targets' quantity names */
  size_t tq[AUTOBAL_ENSEMBLE_MAX_TARGETS];            /* ... and their indices        */
  size_t qoff;                                        /* summary index of quantity 0  */
  size_t aoff;                                        /* ... of the attractor block (-1: none) */
  const char *namep[AUTOBAL_ENSEMBLE_MAX_PARAMS];
  autobal_ensemble_param_info info[AUTOBAL_ENSEMBLE_MAX_PARAMS];
  size_t stride[AUTOBAL_ENSEMBLE_MAX_PARAMS];
  size_t n_members, nsum, ncols;
  size_t *keep, *keep_cap, n_keep;
  uint64_t hash;
  int threads;
  autobal_ensemble_progress_fn progress;
  void *progress_user;
  autobal_ensemble_cancel_fn cancel;
  void *cancel_user;
  autobal_ensemble_parallel par;
  /* the store */
  unsigned char *done;
  double *sum;     /* n_members * nsum (when results are kept) */
  ens_series *ser; /* n_keep slots (when results are kept) */
  size_t n_done;
  /* journal */
  FILE *journal;
  long own_valid;
  int own_rank;
  /* the last run */
  ens_buf outbox;
  size_t computed;
  /* the failed member of the last run with the lowest number, and why (whatever the threads) */
  int have_failure;
  size_t failure_member;
  autobal_error failure;
  autobal_error err;
};

/* The classification rule in words (the archive's attractor_rule; autobal/attractor.h). */
#define ATTRACTOR_RULE                                                                                                         \
  "over the final window (the last attractor_window_revs revolutions, not before the settle time): 1 balanced: stopped at "  \
  "balance or residual unbalance <= balance_tol at every sample; each ball's angle psi relative to the rotor: range R, "     \
  "turns T, mean rates over the window, its quarters and its halves; 2 heavy_side: every ball at rest (R <= attractor_rest_tol) and in every plane "  \
  "sum m r cos(psi - psi0) > 0; 3 fixed: every ball at rest otherwise; 4 circulating: some ball with |T| >= "                \
  "attractor_min_turns, each steady (quarters' rates within attractor_rate_tol) at one common rate r, frequency nu = Omega + " \
  "r, compared with the nearest natural frequency of the whirl it excites; 5 periodic: the halves' ranges of the residual "  \
  "unbalance and the amplitude agree within attractor_envelope_tol and the balls' mean rates within attractor_rate_tol (or " \
  "2 pi / window); 6 irregular: otherwise; 0 unclassified: failed or not run"

/* ---- members --------------------------------------------------------------------------------- */
static double ens_uniform(uint64_t seed, uint64_t k) {
  uint64_t z = seed + (k + 1) * UINT64_C(0x9E3779B97F4A7C15);
  z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-53;
}

static double grid_value(const autobal_ensemble_param *p, size_t i, int endpoint) {
  size_t d = endpoint ? p->n - 1 : p->n;
  if (p->n == 1) return p->min;
  return p->min + (p->max - p->min) * (double)i / (double)d;
}

static double member_value(const autobal_ensemble *e, size_t m, size_t j) {
  const autobal_ensemble_param *p = &e->s.param[j];
  if (e->s.random) return p->min + (p->max - p->min) * ens_uniform(e->s.seed, (uint64_t)m * e->s.n_params + j);
  return grid_value(p, (m / e->stride[j]) % p->n, e->s.endpoint);
}

double autobal_ensemble_member_value(const autobal_ensemble *e, size_t m, size_t j) {
  if (!e || m >= e->n_members || j >= e->s.n_params) return NAN;
  return member_value(e, m, j);
}

double autobal_ensemble_grid_value(const autobal_ensemble *e, size_t j, size_t i) {
  if (!e || j >= e->s.n_params || i >= e->s.param[j].n) return NAN;
  return grid_value(&e->s.param[j], i, e->s.endpoint);
}

autobal_ensemble_settings autobal_ensemble_settings_default(void) {
  autobal_ensemble_settings s;
  memset(&s, 0, sizeof s);
  s.samples = 256;
  s.seed = 1;
  s.t_end = 20.0;
  s.use_revs_out = 1;
  s.revs_out = 0.25;
  s.transient = autobal_transient_options_default();
  s.transient.rtol = 1e-10;
  s.transient.atol = 1e-9;
  s.balance_tol = 0.01;
  s.balance_revs = 50.0;
  s.stop_at_balance = 1;
  s.attractor = autobal_attractor_options_default();
  s.write_attractors = 1;
  return s;
}

/* Output interval and dwell of a member of the given speed. */
static int member_timing(const autobal_ensemble_settings *s, double speed, double *dt_out, double *dwell) {
  double rev = fabs(speed) > 0 ? TWO_PI / fabs(speed) : INFINITY;
  *dt_out = s->use_revs_out ? s->revs_out * rev : s->dt_out;
  *dwell = s->use_dwell ? s->balance_dwell : (s->balance_revs > 0 ? s->balance_revs * rev : 0.0);
  if (!(*dt_out > 0 && isfinite(*dt_out)) || !isfinite(*dwell)) return AUTOBAL_EINVAL;
  return AUTOBAL_SUCCESS;
}

/* Upper bound of the observer calls of a member: t0 + k dt_out < t1 and t1. */
static size_t series_rows_max(const autobal_ensemble_settings *s, double dt_out) {
  return (size_t)floor(s->t_end / dt_out * (1 + 1e-12)) + 2;
}

static long keep_slot(const autobal_ensemble *e, size_t m) {
  size_t lo = 0, hi = e->n_keep;
  while (lo < hi) {
    size_t mid = (lo + hi) / 2;
    if (e->keep[mid] == m) return (long)mid;
    if (e->keep[mid] < m) lo = mid + 1;
    else hi = mid;
  }
  return -1;
}

/* ---- one member (per-thread worker) ------------------------------------------------------------ */
typedef struct ens_worker {
  const autobal_ensemble *e;
  autobal_transient *tr;
  void *mw;
  double *y, *row, *values;
  double amp_max;
  ens_series *ser;
  autobal_error err;
  /* the member's monitor, seen by the dwell event through gated_monitor */
  autobal_transient_scalar_fn mon;
  void *mon_user;
  double settle, tol;
  /* the final window for the attractor classification: a ring of (t, y) rows */
  double *ring_t, *ring_y, *win_t, *win_y;
  size_t ring_cap, ring_n, ring_head;
} ens_worker;

static void worker_free(ens_worker *w) {
  autobal_transient_free(w->tr);
  if (w->mw && w->e->mb.worker_free) w->e->mb.worker_free(w->mw);
  free(w->y);
  free(w->row);
  free(w->values);
  free(w->ring_t), free(w->ring_y), free(w->win_t), free(w->win_y);
  memset(w, 0, sizeof *w);
}

static int worker_init(ens_worker *w, const autobal_ensemble *e, autobal_error *err) {
  memset(w, 0, sizeof *w);
  w->e = e;
  autobal_error_clear(&w->err);
  w->tr = autobal_transient_alloc(e->mb.dim, &e->s.transient, err);
  if (!w->tr) return err && err->status ? err->status : AUTOBAL_ENOMEM;
  w->mw = e->mb.worker_alloc(e->mb.model, e->namep, e->s.n_params, err);
  if (!w->mw) {
    int st = err && err->status ? err->status : AUTOBAL_ENOMEM;
    worker_free(w);
    return st;
  }
  w->y = calloc(e->mb.dim, sizeof *w->y);
  w->row = calloc(e->ncols, sizeof *w->row);
  w->values = calloc(AUTOBAL_ENSEMBLE_MAX_PARAMS, sizeof *w->values);
  if (!w->y || !w->row || !w->values) {
    worker_free(w);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (ensemble worker)");
  }
  return AUTOBAL_SUCCESS;
}

static void series_push(ens_series *sr, double t, const double *row) {
  if (!sr || sr->n >= sr->cap) return;
  sr->t[sr->n] = t;
  memcpy(sr->rows + sr->n * sr->ncols, row, sr->ncols * sizeof *row);
  sr->n++;
}

static int worker_observer(double t, const double y[], void *user) {
  ens_worker *w = user;
  double amp = NAN;
  if (w->e->mb.observe(w->mw, t, y, &amp, w->ser ? w->row : NULL) != 0) return 1;
  if (amp > w->amp_max) w->amp_max = amp;
  if (w->ser) series_push(w->ser, t, w->row);
  if (w->ring_cap) { /* the newest ring_cap rows */
    size_t at = (w->ring_head + w->ring_n) % w->ring_cap;
    if (w->ring_n == w->ring_cap) w->ring_head = (w->ring_head + 1) % w->ring_cap;
    else w->ring_n++;
    w->ring_t[at] = t;
    memcpy(w->ring_y + at * w->e->mb.dim, y, w->e->mb.dim * sizeof *y);
  }
  return 0;
}

/* The ring for a member whose window is window_time long (INFINITY: the whole run) with output
 * interval dt_out: rows enough for the window and its ends (at most the run's observer calls).
 * Sized between members, never during a run.  Status. */
static int ring_prepare(ens_worker *w, double window_time, double dt_out) {
  const autobal_ensemble_settings *s = &w->e->s;
  size_t need = series_rows_max(s, dt_out), dim = w->e->mb.dim;
  if (isfinite(window_time) && window_time / dt_out + 3 < (double)need) need = (size_t)ceil(window_time / dt_out) + 3;
  w->ring_n = w->ring_head = 0;
  if (need > w->ring_cap) {
    double *a = realloc(w->ring_t, need * sizeof *a), *b, *c, *d;
    if (a) w->ring_t = a;
    b = a ? realloc(w->ring_y, need * dim * sizeof *b) : NULL;
    if (b) w->ring_y = b;
    c = b ? realloc(w->win_t, need * sizeof *c) : NULL;
    if (c) w->win_t = c;
    d = c ? realloc(w->win_y, need * dim * sizeof *d) : NULL;
    if (d) w->win_y = d;
    if (!d) {
      w->ring_cap = 0;
      return AUTOBAL_ENOMEM;
    }
  }
  w->ring_cap = need;
  return AUTOBAL_SUCCESS;
}

/* The member's class from its final window: the ring's rows at t >= max(t_from, settle) in time
 * order, handed to the member's classify.  rec's attractor block filled. */
static void classify_member(ens_worker *w, double *rec, double t_from, int stopped_balanced) {
  const autobal_ensemble *e = w->e;
  size_t k, n = 0, dim = e->mb.dim;
  autobal_attractor_result res;
  autobal_error err;
  double *a = rec + e->aoff;
  a[0] = AUTOBAL_ATTRACTOR_UNCLASSIFIED, a[1] = NAN, a[2] = NAN;
  if (t_from < w->settle) t_from = w->settle;
  for (k = 0; k < w->ring_n; k++) {
    size_t at = (w->ring_head + k) % w->ring_cap;
    if (w->ring_t[at] < t_from) continue;
    w->win_t[n] = w->ring_t[at];
    memcpy(w->win_y + n * dim, w->ring_y + at * dim, dim * sizeof *w->win_y);
    n++;
  }
  autobal_error_clear(&err);
  if (e->mb.classify(w->mw, &e->s.attractor, e->s.balance_tol, stopped_balanced, n, w->win_t, w->win_y, &res, &err) != AUTOBAL_SUCCESS)
    return;
  a[0] = res.cls, a[1] = res.frequency, a[2] = res.natural_frequency;
}

/* The monitor the dwell event sees: before the member's settle_time s, or 2 balance_tol where s
 * is below balance_tol (strictly above it, so that the event's root finder puts the start of a
 * stretch below balance_tol at settle_time or later, never before), s from then on; NaN stays NaN. */
static double gated_monitor(double t, const double y[], void *user) {
  const ens_worker *w = user;
  double v = w->mon(t, y, w->mon_user);
  return t < w->settle && v < w->tol ? 2.0 * w->tol : v;
}

static int worker_progress(double fraction, void *user) {
  ens_worker *w = user;
  (void)fraction;
  return w->e->cancel ? w->e->cancel(w->e->cancel_user) : 0;
}

/* Set member m up in w (values and y); *su filled.  Status of the set-up. */
static int member_setup(ens_worker *w, size_t m, autobal_ensemble_setup *su) {
  const autobal_ensemble *e = w->e;
  size_t j;
  int st;
  autobal_error_clear(&w->err);
  memset(su, 0, sizeof *su);
  for (j = 0; j < e->s.n_params; j++) w->values[j] = member_value(e, m, j);
  st = e->mb.setup(w->mw, w->values, w->y, su, &w->err);
  if (st == AUTOBAL_SUCCESS && (!su->sys.rhs || su->sys.dim != e->mb.dim || !su->monitor)) st = AUTOBAL_EINVAL;
  return st;
}

/* Run member m: rec[0..nsum-1] receives its summary; when sr is not NULL (sized by the caller)
 * the series.  Returns 1 when the member is finished (successfully or not: failures are results),
 * 0 when it was cancelled (not done). */
static int run_member(ens_worker *w, size_t m, double *rec, ens_series *sr) {
  const autobal_ensemble *e = w->e;
  const autobal_ensemble_settings *s = &e->s;
  autobal_ensemble_setup su;
  autobal_transient_options opt;
  autobal_transient_stats stats;
  autobal_transient_event_hit hit;
  double dt_out = 0, dwell = 0, t_reached = 0.0, res1 = NAN, amp1 = NAN;
  size_t i;
  int st, ev;

  for (i = 0; i < e->nsum; i++) rec[i] = NAN;
  rec[AUTOBAL_ENSEMBLE_BALANCED] = 0;
  rec[AUTOBAL_ENSEMBLE_STEPS] = 0;
  rec[AUTOBAL_ENSEMBLE_RHS_EVALS] = 0;
  w->amp_max = 0;
  w->ser = NULL;
  st = member_setup(w, m, &su);
  if (st == AUTOBAL_SUCCESS) st = member_timing(s, su.speed, &dt_out, &dwell);
  if (st == AUTOBAL_SUCCESS && !(su.settle_time >= 0 && isfinite(su.settle_time))) st = AUTOBAL_EINVAL;
  if (st != AUTOBAL_SUCCESS) {
    rec[AUTOBAL_ENSEMBLE_STATUS] = st < 0 ? st : AUTOBAL_EINVAL;
    return 1;
  }
  w->ser = sr;
  w->ring_n = w->ring_head = 0;
  if (e->mb.classify) {
    double rev = fabs(su.speed) > 0 ? TWO_PI / fabs(su.speed) : INFINITY;
    if ((st = ring_prepare(w, s->attractor.window_revs * rev, dt_out)) != AUTOBAL_SUCCESS) {
      rec[AUTOBAL_ENSEMBLE_STATUS] = st;
      w->ser = NULL;
      return 1;
    }
    w->settle = su.settle_time;
  }
  opt = s->transient;
  opt.dt_out = dt_out;
  opt.event_tol = 1e-9 * s->t_end;
  if ((st = autobal_transient_set_options(w->tr, &opt)) != AUTOBAL_SUCCESS) {
    rec[AUTOBAL_ENSEMBLE_STATUS] = st;
    w->ser = NULL;
    return 1;
  }
  autobal_transient_clear_events(w->tr);
  autobal_transient_set_progress(w->tr, worker_progress, w);
  autobal_transient_set_observer(w->tr, worker_observer, w);
  rec[AUTOBAL_ENSEMBLE_RESIDUAL_INITIAL] = su.residual_initial;
  w->mon = su.monitor, w->mon_user = su.monitor_user, w->settle = su.settle_time, w->tol = s->balance_tol;
  if (su.settle_time > 0)
    ev = autobal_transient_add_dwell_event(w->tr, gated_monitor, w, s->balance_tol, dwell, s->stop_at_balance);
  else /* no gate: the member's monitor itself (the results of 0.1.0 bit for bit) */
    ev = autobal_transient_add_dwell_event(w->tr, su.monitor, su.monitor_user, s->balance_tol, dwell,
                                           s->stop_at_balance);
  if (ev < 0) {
    rec[AUTOBAL_ENSEMBLE_STATUS] = ev;
    w->ser = NULL;
    return 1;
  }
  autobal_transient_set_event_reset(w->tr, NULL, NULL); /* a previous member's */
  if (e->mb.prepare && (st = e->mb.prepare(w->mw, w->tr, w->y, &w->err)) != AUTOBAL_SUCCESS) {
    rec[AUTOBAL_ENSEMBLE_STATUS] = st < 0 ? st : AUTOBAL_EINVAL;
    w->ser = NULL;
    return 1;
  }
  st = autobal_transient_run(w->tr, &su.sys, 0.0, s->t_end, w->y, &t_reached);
  w->ser = NULL;
  if (st == AUTOBAL_ECANCELLED) return 0;
  if (st < 0) autobal_error_set(&w->err, st, "%s", autobal_transient_errmsg(w->tr));
  if (e->mb.complete) st = e->mb.complete(w->mw, t_reached, st, &w->err);
  autobal_transient_get_stats(w->tr, &stats);
  rec[AUTOBAL_ENSEMBLE_STATUS] = st;
  rec[AUTOBAL_ENSEMBLE_T_REACHED] = t_reached;
  rec[AUTOBAL_ENSEMBLE_STEPS] = (double)stats.steps;
  rec[AUTOBAL_ENSEMBLE_RHS_EVALS] = (double)stats.rhs_evals;
  if (autobal_transient_event_result(w->tr, (size_t)ev, NULL, &hit) == 1) {
    rec[AUTOBAL_ENSEMBLE_BALANCED] = 1;
    rec[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE] = hit.t_start;
  }
  e->mb.finish(w->mw, t_reached, w->y, &res1, &amp1, rec + AUTOBAL_ENSEMBLE_ANGLES);
  if (e->mb.n_quantities) e->mb.finish_quantities(w->mw, t_reached, w->y, rec + e->qoff);
  rec[AUTOBAL_ENSEMBLE_RESIDUAL_FINAL] = res1;
  rec[AUTOBAL_ENSEMBLE_AMPLITUDE_FINAL] = amp1;
  if (amp1 > w->amp_max) w->amp_max = amp1;
  rec[AUTOBAL_ENSEMBLE_AMPLITUDE_MAX] = w->amp_max;
  if (e->mb.classify && st >= 0) {
    double rev = fabs(su.speed) > 0 ? TWO_PI / fabs(su.speed) : INFINITY;
    classify_member(w, rec, t_reached - s->attractor.window_revs * rev * (1 + 1e-12),
                    st == AUTOBAL_EVENT && rec[AUTOBAL_ENSEMBLE_BALANCED] == 1);
  }
  w->ring_n = 0;
  return 1;
}

/* ---- the handle ------------------------------------------------------------------------------ */
static uint64_t fnv1a(uint64_t h, const void *p, size_t n) {
  const unsigned char *c = p;
  size_t i;
  for (i = 0; i < n; i++) {
    h ^= c[i];
    h *= UINT64_C(0x100000001B3);
  }
  return h;
}

static uint64_t fnv_u64(uint64_t h, uint64_t v) {
  unsigned char b[8];
  int i;
  for (i = 0; i < 8; i++) b[i] = (unsigned char)(v >> (8 * i));
  return fnv1a(h, b, 8);
}

static uint64_t fnv_double(uint64_t h, double v) {
  uint64_t u;
  memcpy(&u, &v, sizeof u);
  return fnv_u64(h, u);
}

static uint64_t fnv_str(uint64_t h, const char *s) { return fnv1a(h, s ? s : "", strlen(s ? s : "") + 1); }

/* The journal's hash: everything that decides the members' results and the archive's data. */
static uint64_t settings_hash(const autobal_ensemble *e) {
  const autobal_ensemble_settings *s = &e->s;
  const autobal_transient_options *o = &s->transient;
  uint64_t h = UINT64_C(0xCBF29CE484222325);
  size_t j;
  h = fnv_str(h, e->mb.model_name);
  h = fnv_str(h, autobal_version());
  h = fnv_u64(h, (uint64_t)s->random);
  h = fnv_u64(h, s->n_params);
  for (j = 0; j < s->n_params; j++) {
    h = fnv_str(h, e->names[j]);
    h = fnv_double(h, s->param[j].min);
    h = fnv_double(h, s->param[j].max);
    h = fnv_u64(h, s->random ? 0 : s->param[j].n);
  }
  h = fnv_u64(h, s->random ? 0 : (uint64_t)s->endpoint);
  h = fnv_u64(h, s->random ? s->samples : 0);
  h = fnv_u64(h, s->random ? s->seed : 0);
  h = fnv_double(h, s->t_end);
  h = fnv_u64(h, (uint64_t)s->use_revs_out);
  h = fnv_double(h, s->use_revs_out ? s->revs_out : s->dt_out);
  h = fnv_str(h, o->stepper ? o->stepper : "rk8pd");
  h = fnv_double(h, o->rtol);
  h = fnv_double(h, o->atol);
  h = fnv_double(h, o->h_init);
  h = fnv_double(h, o->h_max);
  h = fnv_double(h, o->h_min);
  h = fnv_u64(h, o->max_steps);
  h = fnv_double(h, s->balance_tol);
  h = fnv_u64(h, (uint64_t)s->use_dwell);
  h = fnv_double(h, s->use_dwell ? s->balance_dwell : s->balance_revs);
  h = fnv_u64(h, (uint64_t)s->stop_at_balance);
  if (e->mb.classify) { /* a member's class depends on them (hashes of members without: as before) */
    h = fnv_double(h, s->attractor.window_revs);
    h = fnv_double(h, s->attractor.rest_tol);
    h = fnv_double(h, s->attractor.min_turns);
    h = fnv_double(h, s->attractor.rate_tol);
    h = fnv_double(h, s->attractor.envelope_tol);
  }
  h = fnv_u64(h, e->n_keep);
  for (j = 0; j < e->n_keep; j++) h = fnv_u64(h, e->keep[j]);
  h = fnv_u64(h, e->mb.hash ? e->mb.hash(e->mb.model) : 0);
  h = fnv_u64(h, s->identity);
  return h;
}

static void store_free(autobal_ensemble *e) {
  size_t i;
  if (e->ser)
    for (i = 0; i < e->n_keep; i++) {
      free(e->ser[i].t);
      free(e->ser[i].rows);
    }
  free(e->ser);
  free(e->sum);
  e->ser = NULL;
  e->sum = NULL;
}

void autobal_ensemble_free(autobal_ensemble *e) {
  if (!e) return;
  if (e->journal) fclose(e->journal);
  store_free(e);
  free(e->done);
  free(e->keep);
  free(e->keep_cap);
  free(e->outbox.v);
  free(e);
}

const char *autobal_ensemble_errmsg(const autobal_ensemble *e) { return e ? e->err.message : ""; }

static int check_settings(const autobal_ensemble_member *mb, const autobal_ensemble_settings *s, autobal_error *err) {
  int st;
  size_t j;
  if (!mb->model_name || !mb->model_name[0] || strlen(mb->model_name) > 32 || !mb->describe || !mb->worker_alloc ||
      !mb->worker_free || !mb->setup || !mb->observe || !mb->finish || !mb->column_name || !mb->time_units ||
      !mb->time_name || !mb->length_units)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: the member lacks a model name, a callback or units");
  if (mb->dim < 1 || mb->n_columns < 1 || mb->n_angles > 64 || (mb->n_angles && !mb->angle_dim))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "ensemble: member dim = %zu, n_columns = %zu, n_angles = %zu: need dim >= 1, n_columns >= 1, n_angles <= 64 (with angle_dim)",
                             mb->dim, mb->n_columns, mb->n_angles);
  if (mb->n_quantities > AUTOBAL_ENSEMBLE_MAX_QUANTITIES || (mb->n_quantities && (!mb->quantity || !mb->finish_quantities)))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "ensemble: member n_quantities = %zu: allowed [0, %d], with a quantity table and finish_quantities",
                             mb->n_quantities, AUTOBAL_ENSEMBLE_MAX_QUANTITIES);
  for (j = 0; j < mb->n_quantities; j++) {
    const autobal_ensemble_quantity *q = &mb->quantity[j];
    if (!q->name || !q->name[0] || strlen(q->name) >= ENS_NAME || !q->units)
      return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: member quantity %zu has no name (or one of %d characters or more) or no units",
                               j, ENS_NAME);
  }
  if (s->n_targets > AUTOBAL_ENSEMBLE_MAX_TARGETS)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: n_targets = %zu is out of range: allowed [0, %d]", s->n_targets,
                             AUTOBAL_ENSEMBLE_MAX_TARGETS);
  for (j = 0; j < s->n_targets; j++) {
    size_t k, i;
    const char *qn = s->target[j].quantity;
    for (k = 0; k < mb->n_quantities && !(qn && !strcmp(qn, mb->quantity[k].name)); k++) {
    }
    if (k == mb->n_quantities) {
      char list[256] = "";
      for (i = 0; i < mb->n_quantities; i++) {
        size_t l = strlen(list);
        snprintf(list + l, sizeof list - l, "%s%s", i ? ", " : "", mb->quantity[i].name);
      }
      return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: target %zu: '%s' is not a quantity of the %s member (%s)", j + 1,
                               qn ? qn : "(null)", mb->model_name ? mb->model_name : "", list[0] ? list : "it has none");
    }
    for (i = 0; i < j; i++)
      if (!strcmp(s->target[i].quantity, qn))
        return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: target %zu: %s already has a target (target %zu)", j + 1, qn, i + 1);
    if (!isfinite(s->target[j].limit))
      return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: target %zu: the limit of %s = %g is not finite", j + 1, qn,
                               s->target[j].limit);
  }
  if (s->write_quantities != 0 && s->write_quantities != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: write_quantities = %d: allowed 0 or 1", s->write_quantities);
  if (s->write_attractors != 0 && s->write_attractors != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: write_attractors = %d: allowed 0 or 1", s->write_attractors);
  if (mb->classify && (st = autobal_attractor_options_check(&s->attractor, err)) != AUTOBAL_SUCCESS) {
    if (err) {
      char msg[sizeof err->message];
      snprintf(msg, sizeof msg, "%s", err->message);
      autobal_error_set(err, st, "ensemble: %s", msg);
    }
    return st;
  }
  if (s->random != 0 && s->random != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: random = %d: allowed 0 (grid) or 1", s->random);
  if (s->n_params < 1 || s->n_params > AUTOBAL_ENSEMBLE_MAX_PARAMS)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: n_params = %zu is out of range: allowed [1, %d]", s->n_params,
                             AUTOBAL_ENSEMBLE_MAX_PARAMS);
  for (j = 0; j < s->n_params; j++) {
    const autobal_ensemble_param *p = &s->param[j];
    size_t i;
    if (!p->name || !p->name[0] || strlen(p->name) >= ENS_NAME)
      return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: parameter %zu has no name (or one of %d characters or more)",
                               j + 1, ENS_NAME);
    for (i = 0; i < j; i++)
      if (!strcmp(s->param[i].name, p->name))
        return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: parameter %zu (%s) is already parameter %zu", j + 1, p->name,
                                 i + 1);
    if (!(isfinite(p->min) && isfinite(p->max) && p->min <= p->max))
      return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: %s: min = %g, max = %g: need finite min <= max", p->name, p->min,
                               p->max);
    if (!s->random && (p->n < 1 || p->n > 100000))
      return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: %s: n = %zu grid points is out of range: allowed [1, 100000]",
                               p->name, p->n);
  }
  if (s->random && (s->samples < 1 || s->samples > AUTOBAL_ENSEMBLE_MAX_MEMBERS))
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: samples = %zu is out of range: allowed [1, %lu]", s->samples,
                             AUTOBAL_ENSEMBLE_MAX_MEMBERS);
  if (!s->random && s->endpoint != 0 && s->endpoint != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: endpoint = %d: allowed 0 or 1", s->endpoint);
  if ((st = autobal_check_param(err, "ensemble t_end", s->t_end, 0, 1, INFINITY, 1, mb->time_units))) return st;
  if (s->use_revs_out) {
    if ((st = autobal_check_param(err, "ensemble revs_out", s->revs_out, 0, 1, INFINITY, 1, "1"))) return st;
  } else if ((st = autobal_check_param(err, "ensemble dt_out", s->dt_out, 0, 1, INFINITY, 1, mb->time_units))) {
    return st;
  }
  if ((st = autobal_check_param(err, "ensemble balance_tol", s->balance_tol, 0, 1, INFINITY, 1, "1"))) return st;
  if (s->use_dwell) {
    if ((st = autobal_check_param(err, "ensemble balance_dwell", s->balance_dwell, 0, 0, INFINITY, 1, mb->time_units)))
      return st;
  } else if ((st = autobal_check_param(err, "ensemble balance_revs", s->balance_revs, 0, 0, INFINITY, 1, "1"))) {
    return st;
  }
  if (s->stop_at_balance != 0 && s->stop_at_balance != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: stop_at_balance = %d: allowed 0 or 1", s->stop_at_balance);
  if (s->threads < 0 || s->threads > 1024)
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: threads = %d is out of range: allowed [0, 1024] (0: OpenMP default)",
                             s->threads);
  if ((st = autobal_check_param(err, "ensemble time_limit", s->time_limit, 0, 0, INFINITY, 1, "s"))) return st;
  if (s->n_series > AUTOBAL_ENSEMBLE_MAX_SERIES || (s->n_series && !s->series))
    return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: n_series = %zu: allowed [0, %d] (with a series list)", s->n_series,
                             AUTOBAL_ENSEMBLE_MAX_SERIES);
  return autobal_transient_options_validate(&s->transient, err);
}

autobal_ensemble *autobal_ensemble_alloc(const autobal_ensemble_member *member, const autobal_ensemble_settings *s,
                                         autobal_error *err) {
  autobal_ensemble *e;
  size_t j, total = 0;
  int st;
  autobal_error_clear(err);
  if (!member || !s) {
    autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: member or settings is NULL");
    return NULL;
  }
  if (check_settings(member, s, err) != AUTOBAL_SUCCESS) return NULL;
  e = calloc(1, sizeof *e);
  if (!e) {
    autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (ensemble)");
    return NULL;
  }
  e->mb = *member;
  e->s = *s;
  snprintf(e->stepper, sizeof e->stepper, "%s", s->transient.stepper ? s->transient.stepper : "rk8pd");
  e->s.transient.stepper = e->stepper; /* validated: a known name, shorter than this */
  e->s.series = NULL;
  e->s.n_series = 0;
  e->own_valid = -1;
  e->par.results = 1;
  for (j = 0; j < s->n_params; j++) {
    snprintf(e->names[j], ENS_NAME, "%s", s->param[j].name);
    e->namep[j] = e->names[j];
    e->s.param[j].name = e->names[j];
    if (s->random) e->s.param[j].n = 1;
    if ((st = member->describe(member->model, e->names[j], &e->info[j], err)) != AUTOBAL_SUCCESS) goto fail;
    if (e->info[j].positive && !(s->param[j].min > 0)) {
      autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: %s: min = %g %s is out of range: allowed (0, inf)", e->names[j],
                        s->param[j].min, e->info[j].units ? e->info[j].units : "");
      goto fail;
    }
  }
  if (member->check && (st = member->check(member->model, e->namep, s->n_params, err)) != AUTOBAL_SUCCESS) goto fail;
  for (j = 0; j < s->n_targets; j++) { /* validated by check_settings */
    snprintf(e->tname[j], ENS_NAME, "%s", s->target[j].quantity);
    e->s.target[j].quantity = e->tname[j];
    e->tq[j] = (size_t)autobal_ensemble_quantity_find(e, e->tname[j]);
  }
  for (j = s->n_targets; j < AUTOBAL_ENSEMBLE_MAX_TARGETS; j++) e->s.target[j].quantity = NULL; /* not kept */
  if (s->random) {
    e->n_members = s->samples;
    for (j = 0; j < s->n_params; j++) e->stride[j] = 1;
  } else {
    size_t t = 1;
    for (j = s->n_params; j-- > 0;) {
      e->stride[j] = t;
      if (t > AUTOBAL_ENSEMBLE_MAX_MEMBERS / s->param[j].n) {
        autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: the grid has more than %lu members", AUTOBAL_ENSEMBLE_MAX_MEMBERS);
        goto fail;
      }
      t *= s->param[j].n;
    }
    e->n_members = t;
  }
  e->qoff = AUTOBAL_ENSEMBLE_ANGLES + member->n_angles;
  e->nsum = e->qoff + member->n_quantities;
  e->aoff = (size_t)-1;
  if (member->classify) e->aoff = e->nsum, e->nsum += AUTOBAL_ENSEMBLE_N_ATTRACTOR;
  e->ncols = member->n_columns;
  e->keep = calloc(s->n_series ? s->n_series : 1, sizeof *e->keep);
  e->keep_cap = calloc(s->n_series ? s->n_series : 1, sizeof *e->keep_cap);
  if (!e->keep || !e->keep_cap) goto nomem;
  for (j = 0; j < s->n_series; j++) {
    size_t m = s->series[j], at, i;
    if (m >= e->n_members) {
      autobal_error_set(err, AUTOBAL_EINVAL, "ensemble: series member %zu does not exist: members are numbered 0..%zu", m,
                        e->n_members - 1);
      goto fail;
    }
    for (at = 0; at < e->n_keep && e->keep[at] < m; at++) {
    }
    if (at < e->n_keep && e->keep[at] == m) continue; /* duplicate */
    for (i = e->n_keep; i > at; i--) e->keep[i] = e->keep[i - 1];
    e->keep[at] = m;
    e->n_keep++;
  }
  e->s.series = e->keep;
  e->s.n_series = e->n_keep;
  /* the kept series' sizes: a member's output interval needs its speed, from its set-up */
  if (e->n_keep) {
    ens_worker w;
    if ((st = worker_init(&w, e, err)) != AUTOBAL_SUCCESS) goto fail;
    for (j = 0; j < e->n_keep; j++) {
      autobal_ensemble_setup su;
      double dt_out, dwell;
      if (member_setup(&w, e->keep[j], &su) == AUTOBAL_SUCCESS &&
          member_timing(&e->s, su.speed, &dt_out, &dwell) == AUTOBAL_SUCCESS) {
        e->keep_cap[j] = series_rows_max(&e->s, dt_out);
        total += e->keep_cap[j] * (e->ncols + 1);
      }
    }
    worker_free(&w);
    if (total > ENS_MAX_SERIES_DOUBLES) {
      autobal_error_set(err, AUTOBAL_EINVAL,
                        "ensemble: the kept series would need %.3g GB; keep fewer members or raise revs_out/dt_out",
                        (double)total * 8e-9);
      goto fail;
    }
  }
#ifdef _OPENMP
  e->threads = s->threads > 0 ? s->threads : omp_get_max_threads();
#else
  e->threads = 1;
#endif
  e->done = calloc(e->n_members, 1); /* the results themselves: store_ready(), when first needed */
  if (!e->done) goto nomem;
  e->hash = settings_hash(e);
  autobal_error_clear(&e->err);
  return e;
nomem:
  autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory (ensemble of %zu members)", e->n_members);
fail:
  autobal_ensemble_free(e);
  return NULL;
}

size_t autobal_ensemble_n_members(const autobal_ensemble *e) { return e ? e->n_members : 0; }
size_t autobal_ensemble_summary_length(const autobal_ensemble *e) { return e ? e->nsum : 0; }
const autobal_ensemble_settings *autobal_ensemble_get_settings(const autobal_ensemble *e) { return e ? &e->s : NULL; }
const autobal_ensemble_param_info *autobal_ensemble_param_info_get(const autobal_ensemble *e, size_t j) {
  return e && j < e->s.n_params ? &e->info[j] : NULL;
}
uint64_t autobal_ensemble_hash(const autobal_ensemble *e) { return e ? e->hash : 0; }
int autobal_ensemble_threads(const autobal_ensemble *e) { return e ? e->threads : 0; }
size_t autobal_ensemble_computed(const autobal_ensemble *e) { return e ? e->computed : 0; }
int autobal_ensemble_first_failure(const autobal_ensemble *e, size_t *member, int *status, const char **message) {
  if (!e || !e->have_failure) return 0;
  if (member) *member = e->failure_member;
  if (status) *status = e->failure.status;
  if (message) *message = e->failure.message;
  return 1;
}
size_t autobal_ensemble_n_done(const autobal_ensemble *e) { return e ? e->n_done : 0; }
int autobal_ensemble_is_done(const autobal_ensemble *e, size_t m) { return e && m < e->n_members && e->done[m]; }

const double *autobal_ensemble_summary(const autobal_ensemble *e, size_t m) {
  if (!e || m >= e->n_members || !e->done[m] || !e->sum) return NULL;
  return e->sum + m * e->nsum;
}

int autobal_ensemble_series(const autobal_ensemble *e, size_t m, size_t *n, const double **t, const double **rows) {
  long slot;
  if (!e || !n || !t || !rows) return AUTOBAL_EINVAL;
  *n = 0, *t = NULL, *rows = NULL;
  slot = keep_slot(e, m);
  if (slot < 0 || !e->ser || m >= e->n_members || !e->done[m]) return AUTOBAL_SUCCESS;
  *n = e->ser[slot].n, *t = e->ser[slot].t, *rows = e->ser[slot].rows;
  return AUTOBAL_SUCCESS;
}

int autobal_ensemble_set_progress(autobal_ensemble *e, autobal_ensemble_progress_fn fn, void *user) {
  if (!e) return AUTOBAL_EINVAL;
  e->progress = fn, e->progress_user = user;
  return AUTOBAL_SUCCESS;
}

int autobal_ensemble_set_cancel(autobal_ensemble *e, autobal_ensemble_cancel_fn fn, void *user) {
  if (!e) return AUTOBAL_EINVAL;
  e->cancel = fn, e->cancel_user = user;
  return AUTOBAL_SUCCESS;
}

/* The result store (summaries, kept series) of a process that keeps results, allocated when first
 * needed (a process that keeps none never holds n_members x nsum doubles).  The summaries of
 * members not done are never read. */
static int store_ready(autobal_ensemble *e) {
  if (!e->par.results || e->sum) return AUTOBAL_SUCCESS;
  e->sum = calloc((e->n_members ? e->n_members : 1) * e->nsum, sizeof *e->sum);
  e->ser = calloc(e->n_keep ? e->n_keep : 1, sizeof *e->ser);
  if (!e->sum || !e->ser) {
    store_free(e);
    return autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory (results of %zu members)", e->n_members);
  }
  return AUTOBAL_SUCCESS;
}

int autobal_ensemble_set_parallel(autobal_ensemble *e, const autobal_ensemble_parallel *par) {
  if (!e || !par) return AUTOBAL_EINVAL;
  if (e->n_done && !par->results != !e->par.results)
    return autobal_error_set(&e->err, AUTOBAL_EINVAL, "ensemble: set_parallel must come before resume and run");
  e->par = *par;
  if (!par->results) store_free(e);
  return AUTOBAL_SUCCESS;
}

/* ---- records ---------------------------------------------------------------------------------- */
static int buf_reserve(ens_buf *b, size_t extra) {
  if (b->n + extra > b->cap) {
    size_t cap = b->cap ? b->cap : 1024;
    double *nv;
    while (cap < b->n + extra) cap *= 2;
    nv = realloc(b->v, cap * sizeof *nv);
    if (!nv) return -1;
    b->v = nv;
    b->cap = cap;
  }
  return 0;
}

/* Append a record; returns its offset or (size_t)-1 (no memory). */
static size_t record_append(ens_buf *b, const autobal_ensemble *e, size_t m, const double *rec, const ens_series *sr) {
  size_t nrows = sr ? sr->n : 0, len = 5 + e->nsum + nrows * (1 + e->ncols), off = b->n;
  double *p;
  if (buf_reserve(b, len)) return (size_t)-1;
  p = b->v + off;
  p[0] = (double)m;
  p[1] = (double)e->nsum;
  p[2] = (double)nrows;
  p[3] = sr ? (double)e->ncols : 0.0;
  memcpy(p + 4, rec, e->nsum * sizeof *rec);
  p += 4 + e->nsum;
  if (nrows) {
    memcpy(p, sr->t, nrows * sizeof *p);
    memcpy(p + nrows, sr->rows, nrows * e->ncols * sizeof *p);
    p += nrows * (1 + e->ncols);
  }
  p[0] = (double)m;
  b->n += len;
  return off;
}

/* Parse records from buf[0..n): each valid record of a member not yet done is stored.  Returns
 * the number of doubles that form complete, valid records (parsing stops at the first invalid or
 * truncated one); *nomem set on allocation failure. */
static size_t parse_records(autobal_ensemble *e, const double *buf, size_t n, int *nomem) {
  size_t pos = 0;
  while (pos + 5 + e->nsum <= n) {
    const double *p = buf + pos;
    double md = p[0], nrd = p[2], ncd = p[3];
    size_t m, nrows, ncols, len;
    if (!(md >= 0 && md < (double)e->n_members && md == floor(md))) break;
    if (p[1] != (double)e->nsum) break;
    if (!(nrd >= 0 && nrd <= (double)ENS_MAX_SERIES_DOUBLES && nrd == floor(nrd))) break;
    if (!(ncd == 0 || ncd == (double)e->ncols)) break;
    m = (size_t)md, nrows = (size_t)nrd, ncols = (size_t)ncd;
    if (nrows > 0 && ncols == 0) break;
    len = 5 + e->nsum + nrows * (1 + ncols);
    if (pos + len > n || buf[pos + len - 1] != md) break;
    if (!e->done[m]) {
      e->done[m] = 1;
      e->n_done++;
      if (e->sum) {
        long slot = keep_slot(e, m);
        memcpy(e->sum + m * e->nsum, p + 4, e->nsum * sizeof *p);
        if (slot >= 0 && nrows > 0) {
          ens_series *sr = &e->ser[slot];
          free(sr->t);
          free(sr->rows);
          sr->t = malloc(nrows * sizeof *sr->t);
          sr->rows = malloc(nrows * ncols * sizeof *sr->rows);
          if (!sr->t || !sr->rows) {
            free(sr->t), free(sr->rows);
            sr->t = sr->rows = NULL;
            sr->n = 0;
            *nomem = 1;
            return pos;
          }
          memcpy(sr->t, p + 4 + e->nsum, nrows * sizeof *p);
          memcpy(sr->rows, p + 4 + e->nsum + nrows, nrows * ncols * sizeof *p);
          sr->n = sr->cap = nrows;
          sr->ncols = ncols;
        }
      }
    }
    pos += len;
  }
  return pos;
}

const double *autobal_ensemble_records(const autobal_ensemble *e, size_t *n) {
  if (n) *n = e ? e->outbox.n : 0;
  return e ? e->outbox.v : NULL;
}

int autobal_ensemble_add_records(autobal_ensemble *e, const double *records, size_t n) {
  int nomem = 0;
  size_t used;
  if (!e || (n && !records)) return AUTOBAL_EINVAL;
  if (store_ready(e) != AUTOBAL_SUCCESS) return AUTOBAL_ENOMEM;
  used = parse_records(e, records, n, &nomem);
  if (nomem) return autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory collecting the members' results");
  if (used != n) return autobal_error_set(&e->err, AUTOBAL_EFORMAT, "a member's result record is damaged (at double %zu of %zu)", used, n);
  return AUTOBAL_SUCCESS;
}

/* ---- journals ---------------------------------------------------------------------------------- */
static const char journal_magic[8] = {'A', 'B', 'E', 'N', 'S', 'J', '0', '1'};

static void journal_header(const autobal_ensemble *e, unsigned char hdr[JOURNAL_HEADER]) {
  uint64_t v[5];
  v[0] = e->hash, v[1] = e->n_members, v[2] = e->nsum, v[3] = e->ncols, v[4] = 0;
  memcpy(hdr, journal_magic, 8);
  memcpy(hdr + 8, v, sizeof v);
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* A regular file whose first 8 bytes are the journal magic (or a prefix of it: a journal torn
 * while its header was written): only such files are listed, read or removed as journals (a
 * file merely named like one, e.g. the configuration, is left alone). */
static int is_journal_file(const char *path) {
  struct stat st;
  char magic[8];
  FILE *f;
  int ok;
  size_t got;
  if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) return 0;
  if (!(f = fopen(path, "rb"))) return 0;
  /* a journal torn while its header was written (a prefix of the magic, or empty) counts too */
  got = fread(magic, 1, sizeof magic, f);
  ok = memcmp(magic, journal_magic, got) == 0;
  fclose(f);
  return ok;
}

void autobal_ensemble_journals_free(char **paths, size_t n) {
  size_t i;
  for (i = 0; i < n; i++) free(paths[i]);
  free(paths);
}

int autobal_ensemble_journals(const char *output, char ***paths, size_t *n, autobal_error *err) {
  const char *slash;
  char *dir, *prefix;
  size_t cap = 0, lp;
  DIR *d;
  struct dirent *de;
  int st = AUTOBAL_SUCCESS;
  if (!output || !paths || !n) return autobal_error_set(err, AUTOBAL_EINVAL, "ensemble journals: NULL argument");
  *paths = NULL;
  *n = 0;
  slash = strrchr(output, '/');
  dir = malloc(strlen(output) + 3);
  prefix = malloc(strlen(output) + 16);
  if (!dir || !prefix) {
    free(dir), free(prefix);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  if (slash) snprintf(dir, strlen(output) + 3, "%.*s", (int)(slash - output) + 1, output);
  else snprintf(dir, strlen(output) + 3, "./");
  snprintf(prefix, strlen(output) + 16, "%s.journal-", slash ? slash + 1 : output);
  lp = strlen(prefix);
  d = opendir(dir);
  if (!d) {
    if (errno != ENOENT) st = autobal_error_set(err, AUTOBAL_EIO, "cannot list the directory '%s': %s", dir, strerror(errno));
    free(dir), free(prefix);
    return st;
  }
  while ((de = readdir(d)) != NULL) {
    const char *q;
    if (strncmp(de->d_name, prefix, lp) != 0 || !de->d_name[lp]) continue;
    for (q = de->d_name + lp; *q >= '0' && *q <= '9'; q++) {
    }
    if (*q) continue;
    if (*n == cap) {
      char **np = realloc(*paths, (cap = cap ? 2 * cap : 8) * sizeof *np);
      if (!np) {
        st = AUTOBAL_ENOMEM;
        break;
      }
      *paths = np;
    }
    (*paths)[*n] = malloc(strlen(dir) + strlen(de->d_name) + 1);
    if (!(*paths)[*n]) {
      st = AUTOBAL_ENOMEM;
      break;
    }
    sprintf((*paths)[*n], "%s%s", dir, de->d_name);
    if (!is_journal_file((*paths)[*n])) { /* named like one, but not a journal: never touched */
      free((*paths)[*n]);
      continue;
    }
    (*n)++;
  }
  closedir(d);
  free(dir), free(prefix);
  if (st != AUTOBAL_SUCCESS) {
    autobal_ensemble_journals_free(*paths, *n);
    *paths = NULL, *n = 0;
    return autobal_error_set(err, st, "out of memory listing journals");
  }
  if (*n > 1) qsort(*paths, *n, sizeof **paths, cmp_str);
  return AUTOBAL_SUCCESS;
}

int autobal_ensemble_journals_remove(const char *output, autobal_error *err) {
  char **paths = NULL;
  size_t n = 0, i;
  int st = autobal_ensemble_journals(output, &paths, &n, err);
  for (i = 0; i < n && st == AUTOBAL_SUCCESS; i++)
    if (unlink(paths[i]) != 0) st = autobal_error_set(err, AUTOBAL_EIO, "cannot remove '%s': %s", paths[i], strerror(errno));
  autobal_ensemble_journals_free(paths, n);
  return st;
}

/* This process's journal path: <output>.journal-<rank>, "./" before a bare name (as listed). */
static char *journal_path(const char *output, int rank) {
  size_t len = strlen(output) + 40;
  char *p = malloc(len);
  if (p) snprintf(p, len, "%s%s.journal-%d", strchr(output, '/') ? "" : "./", output, rank);
  return p;
}

/* Read one journal; *valid receives the length of its valid prefix in bytes (0: no usable header). */
static int journal_load(autobal_ensemble *e, const char *path, long *valid) {
  FILE *f = fopen(path, "rb");
  unsigned char hdr[JOURNAL_HEADER], want[JOURNAL_HEADER];
  double *buf;
  size_t nd, got, used;
  long size;
  int nomem = 0;
  *valid = 0;
  if (!f) return autobal_error_set(&e->err, AUTOBAL_EIO, "cannot read the journal '%s': %s", path, strerror(errno));
  if (fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
    fclose(f);
    return autobal_error_set(&e->err, AUTOBAL_EIO, "cannot read the journal '%s': %s", path, strerror(errno));
  }
  if (size < JOURNAL_HEADER || fread(hdr, 1, JOURNAL_HEADER, f) != JOURNAL_HEADER) {
    fclose(f);
    return AUTOBAL_SUCCESS; /* killed before the header was complete: empty */
  }
  journal_header(e, want);
  if (memcmp(hdr, journal_magic, 8) != 0) {
    fclose(f);
    return autobal_error_set(&e->err, AUTOBAL_EFORMAT, "'%s' is not an autobal ensemble journal", path);
  }
  if (memcmp(hdr, want, JOURNAL_HEADER) != 0) {
    fclose(f);
    return autobal_error_set(&e->err, AUTOBAL_ECONFIG,
                             "the journal '%s' was written for a different configuration (or autobal version); "
                             "resume with the same configuration, or start over with --force",
                             path);
  }
  nd = (size_t)(size - JOURNAL_HEADER) / sizeof(double);
  buf = malloc((nd ? nd : 1) * sizeof *buf);
  if (!buf) {
    fclose(f);
    return autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory reading '%s'", path);
  }
  got = fread(buf, sizeof *buf, nd, f);
  fclose(f);
  used = parse_records(e, buf, got, &nomem);
  free(buf);
  if (nomem) return autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory reading '%s'", path);
  *valid = (long)(JOURNAL_HEADER + used * sizeof(double));
  return AUTOBAL_SUCCESS;
}

int autobal_ensemble_resume(autobal_ensemble *e, const char *output, int rank) {
  char **paths = NULL, *own;
  size_t n = 0, i;
  int st;
  if (!e || !output || rank < 0) return e ? autobal_error_set(&e->err, AUTOBAL_EINVAL, "ensemble resume: bad argument") : AUTOBAL_EINVAL;
  autobal_error_clear(&e->err);
  if (store_ready(e) != AUTOBAL_SUCCESS) return AUTOBAL_ENOMEM;
  own = journal_path(output, rank);
  if (!own) return autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory");
  st = autobal_ensemble_journals(output, &paths, &n, &e->err);
  for (i = 0; i < n && st == AUTOBAL_SUCCESS; i++) {
    long valid;
    st = journal_load(e, paths[i], &valid);
    if (!strcmp(paths[i], own)) e->own_valid = valid, e->own_rank = rank;
  }
  autobal_ensemble_journals_free(paths, n);
  free(own);
  return st;
}

int autobal_ensemble_journal_open(autobal_ensemble *e, const char *output, int rank) {
  char *path;
  int st = AUTOBAL_SUCCESS;
  if (!e || !output || rank < 0) return e ? autobal_error_set(&e->err, AUTOBAL_EINVAL, "ensemble journal: bad argument") : AUTOBAL_EINVAL;
  autobal_error_clear(&e->err);
  if (e->journal) fclose(e->journal), e->journal = NULL;
  path = journal_path(output, rank);
  if (!path) return autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory");
  if (e->own_valid > 0 && e->own_rank == rank) {
    if (truncate(path, (off_t)e->own_valid) != 0 || !(e->journal = fopen(path, "ab")))
      st = autobal_error_set(&e->err, AUTOBAL_EIO, "cannot append to the journal '%s': %s", path, strerror(errno));
  } else if (access(path, F_OK) == 0 && !is_journal_file(path)) {
    /* a file of this name that is not a journal (a configuration, another program's data):
     * never truncated */
    st = autobal_error_set(&e->err, AUTOBAL_EIO,
                           "'%s' exists and is not an ensemble journal: not overwritten (move it, or choose "
                           "another output name)",
                           path);
  } else {
    unsigned char hdr[JOURNAL_HEADER];
    journal_header(e, hdr);
    if (!(e->journal = fopen(path, "wb")) || fwrite(hdr, 1, JOURNAL_HEADER, e->journal) != JOURNAL_HEADER ||
        fflush(e->journal) != 0)
      st = autobal_error_set(&e->err, AUTOBAL_EIO, "cannot write the journal '%s': %s", path, strerror(errno));
  }
  if (st != AUTOBAL_SUCCESS && e->journal) fclose(e->journal), e->journal = NULL;
  e->own_valid = -1;
  free(path);
  return st;
}

/* ---- running ------------------------------------------------------------------------------------- */
static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct ens_run {
  autobal_ensemble *e;
  const size_t *mine;
  size_t n_mine, finished;
  int fatal;
  char fatal_msg[AUTOBAL_ERRMSG_SIZE];
  double t_start;
} ens_run;

static void set_fatal(ens_run *R, int st, const char *msg) {
  if (!R->fatal) {
    R->fatal = st;
    snprintf(R->fatal_msg, sizeof R->fatal_msg, "%s", msg);
  }
}

/* A finished member (inside the critical section): the outbox, the journal, the store. */
static void member_done(ens_run *R, size_t m, const double *rec, ens_series *sr, const autobal_error *why) {
  autobal_ensemble *e = R->e;
  size_t off = record_append(&e->outbox, e, m, rec, sr);
  if (rec[AUTOBAL_ENSEMBLE_STATUS] < 0 && (!e->have_failure || m < e->failure_member)) {
    const int st = (int)rec[AUTOBAL_ENSEMBLE_STATUS];
    e->have_failure = 1;
    e->failure_member = m;
    autobal_error_set(&e->failure, st, "%s", why->message[0] ? why->message : autobal_strerror(st));
  }
  if (off == (size_t)-1) {
    set_fatal(R, AUTOBAL_ENOMEM, "out of memory (results)");
    return;
  }
  R->finished++;
  if (e->journal && !R->fatal) {
    size_t len = e->outbox.n - off;
    if (fwrite(e->outbox.v + off, sizeof(double), len, e->journal) != len || fflush(e->journal) != 0) {
      char msg[300];
      snprintf(msg, sizeof msg, "writing the journal failed: %s", strerror(errno));
      set_fatal(R, AUTOBAL_EIO, msg);
    }
  }
  if (!e->done[m]) {
    e->done[m] = 1;
    e->n_done++;
    if (e->sum) {
      long slot = keep_slot(e, m);
      memcpy(e->sum + m * e->nsum, rec, e->nsum * sizeof *rec);
      if (slot >= 0 && sr) { /* hand the buffers over */
        ens_series *dst = &e->ser[slot];
        free(dst->t), free(dst->rows);
        *dst = *sr;
        sr->t = sr->rows = NULL;
      }
    }
  }
  if (e->progress && R->n_mine) e->progress((double)R->finished / (double)R->n_mine, e->progress_user);
}

static void compute(ens_run *R) {
  autobal_ensemble *e = R->e;
  long k, n = (long)R->n_mine;
  int nth = e->threads;
  (void)nth;
  ENS_PRAGMA(omp parallel num_threads(nth))
  {
    ens_worker w;
    autobal_error werr;
    double *rec = malloc(e->nsum * sizeof *rec);
    int ok = rec && worker_init(&w, e, &werr) == AUTOBAL_SUCCESS;
    if (!ok) {
      ENS_PRAGMA(omp critical(ens_out))
      set_fatal(R, rec ? werr.status : AUTOBAL_ENOMEM, rec ? werr.message : "out of memory (worker)");
    }
    ENS_PRAGMA(omp for schedule(dynamic, 1))
    for (k = 0; k < n; k++) {
      size_t m = R->mine[k];
      ens_series sr, *srp = NULL;
      long slot;
      int done, stop;
      ENS_PRAGMA(omp atomic read)
      stop = R->fatal;
      if (!ok || stop || (e->cancel && e->cancel(e->cancel_user))) continue;
      if (e->s.time_limit > 0 && now_seconds() - R->t_start > e->s.time_limit) continue;
      memset(&sr, 0, sizeof sr);
      slot = keep_slot(e, m);
      if (slot >= 0 && e->keep_cap[slot] > 0) {
        sr.cap = e->keep_cap[slot];
        sr.ncols = e->ncols;
        sr.t = malloc(sr.cap * sizeof *sr.t);
        sr.rows = malloc(sr.cap * e->ncols * sizeof *sr.rows);
        if (!sr.t || !sr.rows) {
          free(sr.t);
          free(sr.rows);
          ENS_PRAGMA(omp critical(ens_out))
          set_fatal(R, AUTOBAL_ENOMEM, "out of memory (series of a kept member)");
          continue;
        }
        srp = &sr;
      }
      done = run_member(&w, m, rec, srp);
      if (done) {
        ENS_PRAGMA(omp critical(ens_out))
        member_done(R, m, rec, srp, &w.err);
      }
      free(sr.t);
      free(sr.rows);
    }
    if (ok) worker_free(&w);
    free(rec);
  }
}

int autobal_ensemble_run(autobal_ensemble *e) {
  ens_run R;
  size_t *todo, m, k, n_todo = 0;
  int st = AUTOBAL_SUCCESS;
  if (!e) return AUTOBAL_EINVAL;
  autobal_error_clear(&e->err);
  memset(&R, 0, sizeof R);
  e->outbox.n = 0;
  e->computed = 0;
  e->have_failure = 0;
  autobal_error_clear(&e->failure);
  todo = store_ready(e) == AUTOBAL_SUCCESS ? malloc((e->n_members ? e->n_members : 1) * sizeof *todo) : NULL;
  if (!todo) {
    st = autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory");
  } else {
    /* the members still to do, cut at max_members, dealt by the `mine` hook */
    for (m = 0, k = 0; m < e->n_members; m++) {
      if (e->done[m]) continue;
      if (e->s.max_members > 0 && k >= e->s.max_members) break;
      if (!e->par.mine || e->par.mine(e->par.user, k, m)) todo[n_todo++] = m;
      k++;
    }
    R.e = e;
    R.mine = todo;
    R.n_mine = n_todo;
    R.t_start = now_seconds();
    if (n_todo) compute(&R);
    e->computed = R.finished;
    if (R.fatal) st = autobal_error_set(&e->err, R.fatal, "%s", R.fatal_msg);
    else if (e->cancel && e->cancel(e->cancel_user))
      st = autobal_error_set(&e->err, AUTOBAL_ECANCELLED, "cancelled: %zu of %zu members done", e->n_done, e->n_members);
  }
  free(todo);
  if (e->journal) {
    if (fclose(e->journal) != 0 && st == AUTOBAL_SUCCESS)
      st = autobal_error_set(&e->err, AUTOBAL_EIO, "closing the journal failed: %s", strerror(errno));
    e->journal = NULL;
  }
  if (e->par.gather) {
    int g = e->par.gather(e->par.user, e, st, e->outbox.v, e->outbox.n);
    if (g != st && g != AUTOBAL_SUCCESS && !e->err.message[0]) autobal_error_set(&e->err, g, "%s", autobal_strerror(g));
    st = g;
  }
  return st;
}

/* ---- the tally ------------------------------------------------------------------------------------ */
static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

int autobal_ensemble_get_tally(const autobal_ensemble *e, autobal_ensemble_tally *t) {
  size_t m, nb = 0;
  double *ttb, sum = 0;
  if (!e || !t) return AUTOBAL_EINVAL;
  memset(t, 0, sizeof *t);
  t->p = t->p_stderr = t->ttb_mean = t->ttb_median = t->ttb_max = NAN;
  t->n_members = e->n_members;
  if (!e->sum) return e->par.results && !e->n_done ? AUTOBAL_SUCCESS : AUTOBAL_EINVAL; /* nothing done yet */
  ttb = malloc((e->n_members ? e->n_members : 1) * sizeof *ttb);
  if (!ttb) return AUTOBAL_ENOMEM;
  for (m = 0; m < e->n_members; m++) {
    const double *r = e->sum + m * e->nsum;
    if (!e->done[m]) continue;
    t->n_done++;
    if (r[AUTOBAL_ENSEMBLE_STATUS] < 0) {
      t->n_failed++;
      continue;
    }
    t->n_ok++;
    if (r[AUTOBAL_ENSEMBLE_BALANCED] == 1) {
      t->n_balanced++;
      sum += r[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE];
      ttb[nb++] = r[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE];
    }
  }
  if (t->n_ok) {
    t->p = (double)t->n_balanced / (double)t->n_ok;
    t->p_stderr = sqrt(t->p * (1 - t->p) / (double)t->n_ok);
  }
  if (t->n_balanced) t->ttb_mean = sum / (double)t->n_balanced;
  if (nb) {
    qsort(ttb, nb, sizeof *ttb, cmp_double);
    t->ttb_median = nb % 2 ? ttb[nb / 2] : 0.5 * (ttb[nb / 2 - 1] + ttb[nb / 2]);
    t->ttb_max = ttb[nb - 1];
  }
  free(ttb);
  return AUTOBAL_SUCCESS;
}

/* ---- statistics of the member quantities ------------------------------------------------------- */
#define WILSON_Z95 1.959963984540054 /* the 0.975 quantile of the standard normal distribution */

static const double quantile_p[AUTOBAL_ENSEMBLE_N_QUANTILES] = {0.0, 0.05, 0.25, 0.5, 0.75, 0.95, 1.0};

size_t autobal_ensemble_n_quantities(const autobal_ensemble *e) { return e ? e->mb.n_quantities : 0; }

size_t autobal_ensemble_quantity_index(const autobal_ensemble *e, size_t k) {
  return e && k < e->mb.n_quantities ? e->qoff + k : (size_t)-1;
}

const autobal_ensemble_quantity *autobal_ensemble_quantity_get(const autobal_ensemble *e, size_t k) {
  return e && k < e->mb.n_quantities ? &e->mb.quantity[k] : NULL;
}

long autobal_ensemble_quantity_find(const autobal_ensemble *e, const char *name) {
  size_t k;
  if (!e || !name) return -1;
  for (k = 0; k < e->mb.n_quantities; k++)
    if (!strcmp(e->mb.quantity[k].name, name)) return (long)k;
  return -1;
}

double autobal_ensemble_quantile_probability(size_t i) { return i < AUTOBAL_ENSEMBLE_N_QUANTILES ? quantile_p[i] : NAN; }

double autobal_ensemble_quantile_sorted(const double *x, size_t n, double p) {
  double h, f;
  size_t lo;
  if (!x || n == 0 || !(p >= 0.0 && p <= 1.0)) return NAN;
  h = (double)(n - 1) * p;
  f = floor(h);
  lo = (size_t)f;
  if (lo >= n - 1) return x[n - 1];
  return x[lo] + (h - f) * (x[lo + 1] - x[lo]);
}

int autobal_ensemble_wilson_interval(size_t k, size_t n, double z, double *low, double *high) {
  double nn, p, z2, den, centre, half;
  if (low) *low = NAN;
  if (high) *high = NAN;
  if (!low || !high || n == 0 || k > n || !(z > 0 && isfinite(z))) return AUTOBAL_EINVAL;
  nn = (double)n, p = (double)k / nn, z2 = z * z;
  den = 1.0 + z2 / nn;
  centre = (p + z2 / (2.0 * nn)) / den;
  half = z * sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn)) / den;
  *low = fmax(0.0, centre - half);
  *high = fmin(1.0, centre + half);
  return AUTOBAL_SUCCESS;
}

int autobal_ensemble_get_stats(const autobal_ensemble *e, size_t k, autobal_ensemble_stats *st) {
  size_t m, i, n = 0;
  double *v, sum = 0.0;
  if (!st) return AUTOBAL_EINVAL;
  memset(st, 0, sizeof *st);
  for (i = 0; i < AUTOBAL_ENSEMBLE_N_QUANTILES; i++) st->quantile[i] = NAN;
  st->mean = NAN;
  if (!e || k >= e->mb.n_quantities || !e->par.results) return AUTOBAL_EINVAL;
  if (!e->sum) return AUTOBAL_SUCCESS; /* nothing done yet */
  v = malloc((e->n_members ? e->n_members : 1) * sizeof *v);
  if (!v) return AUTOBAL_ENOMEM;
  for (m = 0; m < e->n_members; m++) {
    const double *r = e->sum + m * e->nsum;
    double x;
    if (!e->done[m] || !(r[AUTOBAL_ENSEMBLE_STATUS] >= 0)) continue;
    x = r[e->qoff + k];
    if (!isfinite(x)) {
      st->n_nan++;
      continue;
    }
    v[n++] = x;
    sum += x;
  }
  st->n = n;
  if (n) {
    qsort(v, n, sizeof *v, cmp_double);
    for (i = 0; i < AUTOBAL_ENSEMBLE_N_QUANTILES; i++) st->quantile[i] = autobal_ensemble_quantile_sorted(v, n, quantile_p[i]);
    st->mean = sum / (double)n;
  }
  free(v);
  return AUTOBAL_SUCCESS;
}

int autobal_ensemble_get_target(const autobal_ensemble *e, size_t i, autobal_ensemble_target_result *r) {
  size_t m, k;
  double lim;
  if (!r) return AUTOBAL_EINVAL;
  memset(r, 0, sizeof *r);
  r->limit = r->p = r->wilson_low = r->wilson_high = NAN;
  if (!e || i >= e->s.n_targets || !e->par.results) return AUTOBAL_EINVAL;
  k = e->tq[i], lim = e->s.target[i].limit;
  r->quantity = k, r->limit = lim;
  if (e->sum)
    for (m = 0; m < e->n_members; m++) {
      const double *rr = e->sum + m * e->nsum;
      if (!e->done[m] || !(rr[AUTOBAL_ENSEMBLE_STATUS] >= 0)) continue;
      r->n++;
      if (rr[e->qoff + k] <= lim) r->n_within++; /* NaN: not within */
    }
  if (r->n) {
    r->p = (double)r->n_within / (double)r->n;
    autobal_ensemble_wilson_interval(r->n_within, r->n, WILSON_Z95, &r->wilson_low, &r->wilson_high);
  }
  return AUTOBAL_SUCCESS;
}

/* ---- the archive ------------------------------------------------------------------------------------ */
#define WILSON_RANDOM                                                                                                  \
  "Wilson score interval at 95 % (z = 1.959964) of k of n: the members are independent draws, so it is a 95 % "     \
  "confidence interval of the probability over the sampled box"
#define WILSON_GRID                                                                                                    \
  "Wilson score interval at 95 % (z = 1.959964) of k of n, as n independent draws would give it; the members are a " \
  "grid, not random: the probability is the fraction of the grid points, and this is no confidence interval"

/* statistics/<quantity>: the distribution of each member quantity over the members that ran
 * without failure, and its target (attributes of groups: no datasets beyond those of 0.1.0). */
static int write_statistics(autobal_ensemble *e, autobal_archive *a, const char *g) {
  static const char *const qname[AUTOBAL_ENSEMBLE_N_QUANTILES] = {"min", "q05", "q25", "median", "q75", "q95", "max"};
  char gs[ENS_NAME + 96];
  size_t k, i;
  int st = AUTOBAL_SUCCESS;
  if (!e->mb.n_quantities) return AUTOBAL_SUCCESS;
  snprintf(gs, sizeof gs, "%s/statistics", g);
  st = autobal_archive_group(a, gs);
  if (!st)
    st = autobal_archive_attr_string(a, gs, "description",
                                     "distribution over the members that ran without failure (status >= 0, balanced or "
                                     "not) of each member quantity at the end of its run; one group per quantity");
  for (k = 0; k < e->mb.n_quantities && !st; k++) {
    const autobal_ensemble_quantity *q = &e->mb.quantity[k];
    autobal_ensemble_stats sx;
    char gq[2 * ENS_NAME + 112];
    const char *u = q->units;
    if ((st = autobal_ensemble_get_stats(e, k, &sx)) != AUTOBAL_SUCCESS) return st;
    snprintf(gq, sizeof gq, "%s/%s", gs, q->name);
    st = autobal_archive_group(a, gq);
    if (!st) st = autobal_archive_attr_string(a, gq, "long_name", q->long_name ? q->long_name : q->name);
    if (!st) st = autobal_archive_attr_string(a, gq, "units", u);
    if (!st) st = autobal_archive_attr_int(a, gq, "n", (long)sx.n);
    if (!st) st = autobal_archive_attr_int(a, gq, "n_not_finite", (long)sx.n_nan);
    for (i = 0; i < AUTOBAL_ENSEMBLE_N_QUANTILES && !st; i++) st = autobal_archive_attr_double(a, gq, qname[i], sx.quantile[i], u);
    if (!st) st = autobal_archive_attr_double(a, gq, "mean", sx.mean, u);
    if (!st)
      st = autobal_archive_attr_string(a, gq, "quantile_definition",
                                       "q05 .. q95: quantiles at p = 0.05, 0.25, 0.5, 0.75, 0.95 of the n finite values "
                                       "sorted x[0] <= .. <= x[n-1]: linear interpolation between order statistics, "
                                       "h = (n - 1) p, x[floor h] + (h - floor h) (x[floor h + 1] - x[floor h]) "
                                       "(Hyndman and Fan 1996 type 7; numpy.quantile's default)");
    for (i = 0; i < e->s.n_targets && !st; i++) {
      autobal_ensemble_target_result tr;
      if (e->tq[i] != k) continue;
      if ((st = autobal_ensemble_get_target(e, i, &tr)) != AUTOBAL_SUCCESS) return st;
      st = autobal_archive_attr_double(a, gq, "target", tr.limit, u);
      if (!st) st = autobal_archive_attr_int(a, gq, "n_evaluated", (long)tr.n);
      if (!st) st = autobal_archive_attr_int(a, gq, "n_within_target", (long)tr.n_within);
      if (!st) st = autobal_archive_attr_double(a, gq, "probability_within_target", tr.p, "1");
      if (!st) st = autobal_archive_attr_double(a, gq, "probability_within_target_wilson_low", tr.wilson_low, "1");
      if (!st) st = autobal_archive_attr_double(a, gq, "probability_within_target_wilson_high", tr.wilson_high, "1");
      if (!st)
        st = autobal_archive_attr_string(a, gq, "probability_definition",
                                         "n_within_target / n_evaluated: members that ran without failure whose value is "
                                         "<= target (a value that is not finite is not within)");
      if (!st) st = autobal_archive_attr_string(a, gq, "probability_interval_definition", e->s.random ? WILSON_RANDOM : WILSON_GRID);
    }
  }
  return st;
}

/* ---- attractors ------------------------------------------------------------------------------ */
size_t autobal_ensemble_attractor_index(const autobal_ensemble *e) { return e ? e->aoff : (size_t)-1; }

int autobal_ensemble_get_attractors(const autobal_ensemble *e, autobal_ensemble_attractors *out) {
  size_t m;
  if (out) {
    memset(out, 0, sizeof *out);
    out->frequency_min = out->frequency_max = out->ratio_min = out->ratio_max = NAN;
  }
  if (!e || !out || e->aoff == (size_t)-1 || !e->par.results || !e->sum) return AUTOBAL_EINVAL;
  for (m = 0; m < e->n_members; m++) {
    const double *r = e->sum + m * e->nsum + e->aoff;
    int c;
    if (!e->done[m]) continue;
    c = r[0] >= 0 && r[0] < AUTOBAL_ATTRACTOR_N_CLASSES ? (int)r[0] : AUTOBAL_ATTRACTOR_UNCLASSIFIED;
    if (!(e->sum[m * e->nsum + AUTOBAL_ENSEMBLE_STATUS] >= 0)) c = AUTOBAL_ATTRACTOR_UNCLASSIFIED;
    out->count[c]++;
    if (c == AUTOBAL_ATTRACTOR_CIRCULATING) {
      double q = r[1] / r[2];
      if (!(r[1] >= out->frequency_min)) out->frequency_min = r[1];
      if (!(r[1] <= out->frequency_max)) out->frequency_max = r[1];
      if (isfinite(q) && !(q >= out->ratio_min)) out->ratio_min = q;
      if (isfinite(q) && !(q <= out->ratio_max)) out->ratio_max = q;
    }
  }
  return AUTOBAL_SUCCESS;
}

static int write_attractors(autobal_ensemble *e, autobal_archive *a, const char *g, int rank, const char **dims, int *iv,
                            double *dv) {
  const autobal_attractor_options *o = &e->s.attractor;
  autobal_ensemble_attractors at;
  char obj[128], nm[64];
  size_t m, n = e->n_members;
  int st = autobal_ensemble_get_attractors(e, &at), c;
  /* rates in rad/s for a model in seconds; in units of omega0 (dimensionless "1") for the pendulum's tau */
  const char *fu = strcmp(e->mb.time_units, "s") ? "1" : "rad/s";
  if (st) return st;
  st = autobal_archive_attr_double(a, g, "attractor_window_revs", o->window_revs, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "attractor_rest_tol", o->rest_tol, "rad");
  if (!st) st = autobal_archive_attr_double(a, g, "attractor_min_turns", o->min_turns, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "attractor_rate_tol", o->rate_tol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "attractor_envelope_tol", o->envelope_tol, "1");
  if (!st) st = autobal_archive_attr_string(a, g, "attractor_legend", autobal_attractor_legend());
  if (!st) st = autobal_archive_attr_string(a, g, "attractor_rule", ATTRACTOR_RULE);
  for (c = 0; c < AUTOBAL_ATTRACTOR_N_CLASSES && !st; c++) {
    snprintf(nm, sizeof nm, "n_attractor_%s", autobal_attractor_class_name(c));
    st = autobal_archive_attr_int(a, g, nm, (long)at.count[c]);
  }
  if (!st) st = autobal_archive_attr_double(a, g, "circulation_frequency_min", at.frequency_min, fu);
  if (!st) st = autobal_archive_attr_double(a, g, "circulation_frequency_max", at.frequency_max, fu);
  if (!st) st = autobal_archive_attr_double(a, g, "circulation_frequency_ratio_min", at.ratio_min, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "circulation_frequency_ratio_max", at.ratio_max, "1");
  if (st || !e->s.write_attractors) return st;
  for (m = 0; m < n; m++) {
    const double *r = e->sum + m * e->nsum;
    iv[m] = e->done[m] && r[AUTOBAL_ENSEMBLE_STATUS] >= 0 && r[e->aoff] >= 0 && r[e->aoff] < AUTOBAL_ATTRACTOR_N_CLASSES ? (int)r[e->aoff] : 0;
  }
  st = autobal_archive_var_int(a, g, "attractor", rank, dims, iv, "1",
                               "what the member's motion settled to over the final window (attractor_rule; legend)");
  snprintf(obj, sizeof obj, "%s/attractor", g);
  if (!st) st = autobal_archive_attr_string(a, obj, "legend", autobal_attractor_legend());
  if (!st) st = autobal_archive_attr_string(a, obj, "description", ATTRACTOR_RULE);
  for (m = 0; m < n; m++) dv[m] = e->done[m] ? e->sum[m * e->nsum + e->aoff + 1] : NAN;
  if (!st)
    st = autobal_archive_var(a, g, "circulation_frequency", rank, dims, dv, fu,
                             "circulating members: absolute angular rate nu = Omega + mean relative rate of the circulating "
                             "ball(s) over the final window (NaN: not circulating)");
  for (m = 0; m < n; m++) dv[m] = e->done[m] ? e->sum[m * e->nsum + e->aoff + 2] : NAN;
  if (!st)
    st = autobal_archive_var(a, g, "natural_frequency", rank, dims, dv, fu,
                             "circulating members: the natural frequency of the rotor at the member's speed (rotor: the "
                             "Campbell diagram, autobal_rotor_modes; pendulum: the shaft, sqrt(1 - H^2/4) in units of omega0) of the whirl "
                             "nu excites, nearest to |nu| (NaN: not circulating)");
  return st;
}

int autobal_ensemble_write(autobal_ensemble *e, autobal_archive *a, int (*write_model)(void *user, autobal_archive *a),
                           void *user, const autobal_ensemble_execution *exec) {
  char g[64], buf[256];
  const autobal_ensemble_settings *s;
  const char *tu, *lu;
  const char *dims[AUTOBAL_ENSEMBLE_MAX_PARAMS + 1];
  int rank, st = AUTOBAL_SUCCESS;
  size_t n, m, j, i, nang;
  double *dv = NULL, *ang = NULL;
  int *iv = NULL;
  autobal_ensemble_tally t;
  if (!e || !a || !exec) return AUTOBAL_EINVAL;
  autobal_error_clear(&e->err);
  if (!e->par.results) return autobal_error_set(&e->err, AUTOBAL_EINVAL, "ensemble: this process keeps no results to write");
  if ((st = store_ready(e)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_ensemble_get_tally(e, &t)) != AUTOBAL_SUCCESS)
    return autobal_error_set(&e->err, st, "out of memory (tally)");
  s = &e->s;
  tu = e->mb.time_units, lu = e->mb.length_units;
  n = e->n_members;
  nang = e->mb.n_angles;
  snprintf(g, sizeof g, "/%s/ensemble", e->mb.model_name);
  if (write_model && (st = write_model(user, a)) != AUTOBAL_SUCCESS) {
    if (!e->err.message[0]) autobal_error_set(&e->err, st, "%s", autobal_archive_errmsg(a));
    return st;
  }
  st = autobal_archive_group(a, g);
#define AS(name, v) do { if (!st) st = autobal_archive_attr_string(a, g, name, v); } while (0)
#define AD(name, v, u) do { if (!st) st = autobal_archive_attr_double(a, g, name, v, u); } while (0)
#define AI(name, v) do { if (!st) st = autobal_archive_attr_int(a, g, name, (long)(v)); } while (0)
  AS("mode", s->random ? "random" : "grid");
  /* the identity of the settings (what a resume must match; autobal_ensemble_hash) */
  snprintf(buf, sizeof buf, "%016llx", (unsigned long long)e->hash);
  AS("settings_hash", buf);
  buf[0] = '\0';
  for (j = 0; j < s->n_params; j++) {
    size_t l = strlen(buf);
    snprintf(buf + l, sizeof buf - l, "%s%s", j ? ", " : "", e->names[j]);
  }
  AS("parameters", buf);
  AI("n_members", n);
  if (s->random) {
    snprintf(buf, sizeof buf, "%llu", (unsigned long long)s->seed);
    AS("seed", buf);
    AS("sampler", "splitmix64: member m, parameter j <- output m*nparam + j; min + (max - min) (x >> 11) 2^-53");
    for (j = 0; j < s->n_params; j++) {
      char nm[ENS_NAME + 8];
      snprintf(nm, sizeof nm, "%s_min", e->names[j]);
      AD(nm, s->param[j].min, e->info[j].units);
      snprintf(nm, sizeof nm, "%s_max", e->names[j]);
      AD(nm, s->param[j].max, e->info[j].units);
    }
  } else {
    AI("endpoint", s->endpoint);
    AS("member_order", "row-major over the parameter axes (the last one varies fastest)");
  }
  AD("t_end", s->t_end, tu);
  if (s->use_revs_out) AD("revs_out", s->revs_out, "1");
  else AD("dt_out", s->dt_out, tu);
  AD("rtol", s->transient.rtol, "1");
  AD("atol", s->transient.atol, "1");
  AD("h_max", s->transient.h_max, tu);
  AI("max_steps", s->transient.max_steps);
  AS("stepper", s->transient.stepper ? s->transient.stepper : "rk8pd");
  AD("balance_tol", s->balance_tol, "1");
  if (s->use_dwell) AD("balance_dwell", s->balance_dwell, tu);
  else AD("balance_revs", s->balance_revs, "1");
  AI("stop_at_balance", s->stop_at_balance);
  if (!st && e->mb.write_attrs) st = e->mb.write_attrs(e->mb.model, a, g);
  /* results */
  AI("n_done", t.n_done);
  AI("n_failed", t.n_failed);
  AI("n_balanced", t.n_balanced);
  AD("probability_balanced", t.p, "1");
  AD("probability_balanced_stderr", t.p_stderr, "1");
  AD("time_to_balance_mean", t.ttb_mean, tu);
  AD("time_to_balance_median", t.ttb_median, tu);
  AD("time_to_balance_max", t.ttb_max, tu);
  AS("probability_definition", "n_balanced / (n_done - n_failed): members that ran without failure; stderr sqrt(p (1 - p) / n)");
  if (!st) { /* added in 0.2.0 (attributes: the datasets of 0.1.0 stay) */
    double lo = NAN, hi = NAN;
    if (t.n_ok) autobal_ensemble_wilson_interval(t.n_balanced, t.n_ok, WILSON_Z95, &lo, &hi);
    AD("probability_balanced_wilson_low", lo, "1");
    AD("probability_balanced_wilson_high", hi, "1");
    AS("probability_interval_definition", s->random ? WILSON_RANDOM : WILSON_GRID);
  }
  /* axes */
  if (s->random) {
    if (!st) st = autobal_archive_dim(a, g, "member", n, "ensemble member");
    dims[0] = "member";
    rank = 1;
  } else {
    for (j = 0; j < s->n_params && !st; j++) {
      double *v = malloc(s->param[j].n * sizeof *v);
      if (!v) return autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory");
      for (i = 0; i < s->param[j].n; i++) v[i] = grid_value(&s->param[j], i, s->endpoint);
      st = autobal_archive_coord(a, g, e->names[j], s->param[j].n, v, e->info[j].units, e->info[j].long_name);
      free(v);
      dims[j] = e->names[j];
    }
    rank = (int)s->n_params;
  }
  dv = malloc((n ? n : 1) * sizeof *dv);
  iv = malloc((n ? n : 1) * sizeof *iv);
  ang = malloc((n ? n : 1) * (nang ? nang : 1) * sizeof *ang);
  if (!dv || !iv || !ang) {
    free(dv), free(iv), free(ang);
    return autobal_error_set(&e->err, AUTOBAL_ENOMEM, "out of memory");
  }
  if (s->random)
    for (j = 0; j < s->n_params && !st; j++) {
      for (m = 0; m < n; m++) dv[m] = member_value(e, m, j);
      st = autobal_archive_var(a, g, e->names[j], 1, dims, dv, e->info[j].units, e->info[j].long_name);
    }
  {
    static const struct {
      int col;
      const char *name, *lname;
      int unit; /* 0 "1", 1 time, 2 length */
    } dvars[] = {
        {AUTOBAL_ENSEMBLE_TIME_TO_BALANCE, "time_to_balance", "time from which the residual unbalance stayed below balance_tol (NaN: not balanced)", 1},
        {AUTOBAL_ENSEMBLE_RESIDUAL_INITIAL, "residual_unbalance_initial", "relative residual unbalance at the start", 0},
        {AUTOBAL_ENSEMBLE_RESIDUAL_FINAL, "residual_unbalance_final", "relative residual unbalance at the end of the run", 0},
        {AUTOBAL_ENSEMBLE_AMPLITUDE_MAX, "amplitude_max", "largest sampled displacement amplitude of the shaft / centre of mass", 2},
        {AUTOBAL_ENSEMBLE_AMPLITUDE_FINAL, "amplitude_final", "displacement amplitude at the end of the run", 2},
        {AUTOBAL_ENSEMBLE_T_REACHED, "t_reached", "time reached (t_end, the balancing stop, or the failure)", 1},
        {AUTOBAL_ENSEMBLE_STEPS, "steps", "accepted solver steps", 0},
        {AUTOBAL_ENSEMBLE_RHS_EVALS, "rhs_evaluations", "right-hand-side evaluations", 0}};
    static const struct {
      int col;
      const char *name, *lname;
    } ivars[] = {{AUTOBAL_ENSEMBLE_STATUS, "status", "solver status: 0 reached t_end, 2 stopped at balance (AUTOBAL_EVENT), < 0 failure (autobal status code, e.g. -5 AUTOBAL_EMAXSTEPS)"},
                 {AUTOBAL_ENSEMBLE_BALANCED, "balanced", "1: balanced (the residual unbalance stayed below balance_tol for the dwell)"}};
    const char *u3[3];
    u3[0] = "1", u3[1] = tu, u3[2] = lu;
    for (i = 0; i < sizeof ivars / sizeof ivars[0] && !st; i++) {
      for (m = 0; m < n; m++) {
        double v = e->sum[m * e->nsum + (size_t)ivars[i].col];
        iv[m] = e->done[m] && isfinite(v) ? (int)v : 0;
      }
      st = autobal_archive_var_int(a, g, ivars[i].name, rank, dims, iv, "1", ivars[i].lname);
    }
    for (m = 0; m < n; m++) iv[m] = e->done[m];
    if (!st) st = autobal_archive_var_int(a, g, "done", rank, dims, iv, "1", "1: the member was computed (0: still to do; see resume)");
    for (i = 0; i < sizeof dvars / sizeof dvars[0] && !st; i++) {
      for (m = 0; m < n; m++) dv[m] = e->done[m] ? e->sum[m * e->nsum + (size_t)dvars[i].col] : NAN;
      st = autobal_archive_var(a, g, dvars[i].name, rank, dims, dv, u3[dvars[i].unit], dvars[i].lname);
    }
  }
  /* the member quantities per member: only when asked for (a configuration of 0.1.0 writes the
   * datasets it wrote then; tests/app/rerun_old.sh) */
  for (i = 0; i < e->mb.n_quantities && s->write_quantities && !st; i++) {
    const autobal_ensemble_quantity *q = &e->mb.quantity[i];
    for (m = 0; m < n; m++) dv[m] = e->done[m] ? e->sum[m * e->nsum + e->qoff + i] : NAN;
    st = autobal_archive_var(a, g, q->name, rank, dims, dv, q->units, q->long_name);
  }
  if (nang && !st) {
    st = autobal_archive_dim(a, g, e->mb.angle_dim, nang, e->mb.angle_dim_long_name);
    for (m = 0; m < n; m++)
      for (i = 0; i < nang; i++) ang[m * nang + i] = e->done[m] ? e->sum[m * e->nsum + AUTOBAL_ENSEMBLE_ANGLES + i] : NAN;
    dims[rank] = e->mb.angle_dim;
    if (!st) st = autobal_archive_var(a, g, "final_angle", rank + 1, dims, ang, "rad", e->mb.angle_long_name);
  }
  /* the attractors: the rule's thresholds and the class counts (attributes), the per-member class
   * and circulation frequencies (with write_attractors) */
  if (e->mb.classify && !st) st = write_attractors(e, a, g, rank, dims, iv, dv);
  /* grid of two or more axes: the probability of balancing along each axis, over the others
   * (e.g. over the initial ball angles at each ramp rate), as attributes of the axis' coordinate
   * (attributes, not variables: the datasets of an archive of 0.1.0 stay exactly those a rerun
   * writes) */
  if (!s->random && s->n_params >= 2 && !st) {
    for (j = 0; j < s->n_params && !st; j++) {
      size_t nj = s->param[j].n;
      double *pb = calloc(2 * nj, sizeof *pb); /* balanced, then ran without failure */
      char obj[ENS_NAME + 80];
      if (!pb) {
        st = AUTOBAL_ENOMEM;
        break;
      }
      for (m = 0; m < n; m++) {
        const double *r = e->sum + m * e->nsum;
        size_t k = (m / e->stride[j]) % nj;
        if (!e->done[m] || !(r[AUTOBAL_ENSEMBLE_STATUS] >= 0)) continue;
        pb[nj + k] += 1;
        if (r[AUTOBAL_ENSEMBLE_BALANCED] == 1) pb[k] += 1;
      }
      for (i = 0; i < nj; i++) pb[i] = pb[nj + i] > 0 ? pb[i] / pb[nj + i] : NAN;
      snprintf(obj, sizeof obj, "%s/%s", g, e->names[j]);
      st = autobal_archive_attr_double_array(a, obj, "probability_balanced", nj, pb, "1");
      if (!st)
        st = autobal_archive_attr_string(a, obj, "probability_balanced_definition",
                                         "at each point of this axis: balanced / members done without failure, over the "
                                         "other axes (NaN: none)");
      free(pb);
    }
  }
  free(dv), free(iv), free(ang);
  if (!st) st = write_statistics(e, a, g);
  /* kept series */
  if (e->n_keep && !st) {
    char(*names)[64] = calloc(e->ncols, sizeof *names);
    const char **np = calloc(e->ncols, sizeof *np), **up = calloc(e->ncols, sizeof *up), **lp = calloc(e->ncols, sizeof *lp);
    if (!names || !np || !up || !lp) st = AUTOBAL_ENOMEM;
    for (i = 0; i < e->ncols && !st; i++) {
      st = e->mb.column_name(e->mb.model, i, names[i], 64, &up[i]);
      np[i] = names[i];
      lp[i] = NULL;
    }
    for (i = 0; i < e->n_keep && !st; i++) {
      char sg[128];
      autobal_archive_series *ser = NULL;
      const ens_series *sr = &e->ser[i];
      m = e->keep[i];
      snprintf(sg, sizeof sg, "%s/series/member_%zu", g, m);
      st = autobal_archive_series_open(a, sg, e->mb.time_name, tu, e->mb.time_long_name, e->ncols, np, up, lp, &ser);
      if (!st) st = autobal_archive_attr_int(a, sg, "member", (long)m);
      for (j = 0; j < s->n_params && !st; j++)
        st = autobal_archive_attr_double(a, sg, e->names[j], member_value(e, m, j), e->info[j].units);
      if (!st) st = autobal_archive_attr_int(a, sg, "done", e->done[m]);
      if (!st && sr->n && e->done[m]) st = autobal_archive_series_append(ser, sr->n, sr->t, sr->rows);
      if (ser) {
        int e2 = autobal_archive_series_close(ser);
        if (!st) st = e2;
      }
    }
    free(names), free(np), free(up), free(lp);
  }
  /* how it was run: the only part that depends on threads and ranks */
  if (!st) {
    char ge[80];
    snprintf(ge, sizeof ge, "%s/execution", g);
    st = autobal_archive_group(a, ge);
    if (!st) st = autobal_archive_attr_int(a, ge, "mpi_ranks", exec->ranks);
    if (!st) st = autobal_archive_attr_int(a, ge, "threads_per_rank", exec->threads);
    if (!st) st = autobal_archive_attr_double(a, ge, "wall_time", exec->wall_time, "s");
    if (!st) st = autobal_archive_attr_int(a, ge, "mpi_build", exec->mpi_build);
  }
#undef AS
#undef AD
#undef AI
  if (st) autobal_error_set(&e->err, st, "%s", st == AUTOBAL_ENOMEM ? "out of memory" : autobal_archive_errmsg(a));
  return st;
}
