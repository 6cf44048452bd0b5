/* rotor_design2.c: `autobal rotor design` with two balancer planes (options.planes = 2; docs/rotor.md
 * "Design", "Two planes").  The same balancer (two identical balls: mass m, track radius r, damping h)
 * in both planes of the config's two-plane machine, for every unbalance of both ranges and every
 * relative phase.
 *
 * The map: at every (m, h, r) of the grids and every speed of the grid (in order, stopping at the
 * first speed not stable) autobal_rotor_stab_every_unbalance2 WITHOUT the box search: exact in plane
 * 1's unbalance and in the phase, plane 2's unbalance on n_unbalance2 values.  The ranking: the cells
 * stable at every speed, by their sampled margin -(largest margin met), larger first.  The
 * certification: the first n_best of them again at every grid speed, now WITH the certified box
 * search over plane 2's whole range (budget unbalance2_boxes), which either proves the verdict over
 * all of plane 2's range (n_certified counts those speeds), finds a point not stable (recheck 0,
 * feasible 0), or stays undecided (the grid verdict stands, the speed is not counted certified).
 * Cells and (design, speed) pairs are dealt over OpenMP threads, each with its own handle; every
 * result is per cell / pair, so the output does not depend on the number of threads. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>

#include "autobal/design.h"
#include "autobal/rotor_stability.h"
#include "internal.h"
#include "studies/rotor_design2.h"

#ifdef AUTOBAL_HAVE_OPENMP
#include <omp.h>
#endif

typedef struct d2ctx {
  autobal_rotor_params *work;
  const autobal_study_rotor_design_options *o;
  autobal_study_rotor_design_summary *S;
  double *omega;
  double lo[2], hi[2];
  autobal_rotor_design *des; /* the designs being certified */
  int *stop;
  double f0, df; /* progress */
} d2ctx;

/* A thread's handle (allocated on first use) with the box budget of its phase. */
typedef struct d2thr {
  autobal_rotor_stab *s;
  autobal_error err;
  size_t verdicts;
} d2thr;

static int thr_handle(const d2ctx *c, d2thr *t, long boxes) {
  autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
  if (t->s) return AUTOBAL_SUCCESS;
  so.unbalance2_boxes = boxes;
  t->s = autobal_rotor_stab_alloc(c->work, &so, &t->err);
  return t->s ? AUTOBAL_SUCCESS : (t->err.status ? t->err.status : AUTOBAL_EINVAL);
}

/* The handle at design (m, h, r) in both planes. */
static int set_balls(d2thr *t, double m, double h, double r) {
  int st = autobal_rotor_stab_set(t->s, AUTOBAL_ROTOR_PARAM_BALL_MASS, m);
  if (!st) st = autobal_rotor_stab_set(t->s, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, h);
  if (!st) st = autobal_rotor_stab_set(t->s, AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_BALL_RADIUS), r);
  if (!st) st = autobal_rotor_stab_set(t->s, AUTOBAL_ROTOR_PARAM_PLANE(1, AUTOBAL_ROTOR_PLANE_BALL_RADIUS), r);
  if (st) autobal_error_set(&t->err, st, "%s", autobal_rotor_stab_errmsg(t->s));
  return st;
}

/* The two-plane verdict at speed w: *stable, the largest margin met, the record. */
static int verdict_at(const d2ctx *c, d2thr *t, double w, autobal_rotor_unbalance_range2 *u) {
  int st = autobal_rotor_stab_set(t->s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  if (!st) st = autobal_rotor_stab_every_unbalance2(t->s, c->lo, c->hi, c->o->n_unbalance2, u);
  t->verdicts++;
  if (st) autobal_error_set(&t->err, st, "%s", autobal_rotor_stab_errmsg(t->s));
  return st;
}

static int stable_of(const autobal_rotor_unbalance_range2 *u) {
  return u->all_stable && u->n_not_stable == 0 && u->n_slices_not_stable == 0;
}

/* One map cell (i mass, j damping, q radius; n_position is 1).  An analysis that fails (e.g. the
 * cos form of Delta16 does not hold) marks the cell -3: undecided, not feasible. */
static int map_cell(const d2ctx *c, d2thr *t, size_t cell) {
  const autobal_study_rotor_design_options *o = c->o;
  autobal_study_rotor_design_summary *S = c->S;
  const size_t q = cell % o->n_radius, j = (cell / o->n_radius) % o->n_damping, i = cell / (o->n_radius * o->n_damping);
  const double m = S->mass[i], h = S->damping[j], r = S->radius[q];
  const size_t idx = (i * o->n_damping + j) * o->n_radius + q; /* n_position = 1 */
  double worst = -INFINITY;
  size_t k;
  int st;
  S->margin_map[idx] = NAN;
  if (!(2.0 * m * r > fmax(c->hi[0], c->hi[1]))) {
    S->feasible[idx] = -1;
    return AUTOBAL_SUCCESS;
  }
  if ((st = thr_handle(c, t, -1)) != AUTOBAL_SUCCESS) return st;
  if ((st = set_balls(t, m, h, r)) != AUTOBAL_SUCCESS) return st;
  for (k = 0; k < o->n_omega; k++) {
    autobal_rotor_unbalance_range2 u;
    st = verdict_at(c, t, c->omega[k], &u);
    if (st == AUTOBAL_ECANCELLED || st == AUTOBAL_ENOMEM) return st;
    if (st != AUTOBAL_SUCCESS) {
      S->feasible[idx] = -3;
      autobal_error_clear(&t->err);
      return AUTOBAL_SUCCESS;
    }
    if (!stable_of(&u)) {
      S->feasible[idx] = 0;
      return AUTOBAL_SUCCESS;
    }
    if (u.margin_worst > worst) worst = u.margin_worst;
  }
  S->margin_map[idx] = -worst;
  S->feasible[idx] = -worst > o->margin ? 1 : 0;
  return AUTOBAL_SUCCESS;
}

/* One certification job: design k / n_omega, speed k % n_omega, with the box search. */
typedef struct cert_rec {
  int stable, exact, failed;
  size_t boxes;
  double found_s[2], found_phase, margin;
} cert_rec;

static int cert_job(const d2ctx *c, d2thr *t, size_t job, cert_rec *rec) {
  const size_t n = c->o->n_omega, d = job / n, k = job % n;
  const autobal_rotor_design *g = &c->des[d];
  autobal_rotor_unbalance_range2 u;
  int st;
  memset(rec + job, 0, sizeof *rec);
  if ((st = thr_handle(c, t, c->o->unbalance2_boxes)) != AUTOBAL_SUCCESS) return st;
  if ((st = set_balls(t, g->mass, g->damping, g->radius)) != AUTOBAL_SUCCESS) return st;
  st = verdict_at(c, t, c->omega[k], &u);
  if (st == AUTOBAL_ECANCELLED || st == AUTOBAL_ENOMEM) return st;
  if (st != AUTOBAL_SUCCESS) {
    rec[job].failed = 1;
    autobal_error_clear(&t->err);
    return AUTOBAL_SUCCESS;
  }
  rec[job].stable = stable_of(&u);
  rec[job].exact = u.exact_in_s2 && u.exact_in_s1;
  rec[job].boxes = u.boxes;
  rec[job].found_s[0] = u.found_s[0];
  rec[job].found_s[1] = u.found_s[1];
  rec[job].found_phase = u.found_phase;
  rec[job].margin = u.margin_worst;
  return AUTOBAL_SUCCESS;
}

/* The certified margin of design k (see design.h): bisection in delta over the shifted verdict at
 * every grid speed, the most critical speeds (by the sampled margin there) first, and the speed that
 * failed last tried first. */
typedef struct marg_job {
  const cert_rec *rec; /* [n_designs][n_omega] */
} marg_job;

/* 1: proven at every speed, 0: a violation found, -1: undecided somewhere (and none found) */
static int shifted_all(const d2ctx *c, d2thr *t, size_t *order, double delta, size_t *steps, int *st) {
  const size_t n = c->o->n_omega;
  size_t i;
  int und = 0;
  for (i = 0; i < n; i++) {
    autobal_rotor_unbalance_range2 u;
    int v = -1;
    *st = autobal_rotor_stab_set(t->s, AUTOBAL_ROTOR_PARAM_OMEGA, c->omega[order[i]]);
    if (*st == AUTOBAL_SUCCESS) *st = autobal_rotor_stab_every_unbalance2_shift(t->s, c->lo, c->hi, delta, &v, &u);
    (*steps)++;
    t->verdicts++;
    if (*st == AUTOBAL_ECANCELLED || *st == AUTOBAL_ENOMEM) return -1;
    if (*st != AUTOBAL_SUCCESS) { /* an analysis failure: undecided here */
      autobal_error_clear(&t->err);
      *st = AUTOBAL_SUCCESS;
      v = -1;
    }
    if (v == 0) {
      const size_t f = order[i]; /* try it first next time */
      memmove(order + 1, order, i * sizeof *order);
      order[0] = f;
      return 0;
    }
    if (v == -1) und = 1;
  }
  return und ? -1 : 1;
}

static int margin_job(const d2ctx *c, d2thr *t, size_t k, void *user) {
  const marg_job *mj = (const marg_job *)user;
  autobal_rotor_design *g = &c->des[k];
  const size_t n = c->o->n_omega;
  const cert_rec *rec = mj->rec + k * n;
  const double tol = 1e-3, req = c->o->margin;
  size_t *order, i, j;
  double lo = 0.0, hi, viol;
  int st = AUTOBAL_SUCCESS, r, decided = 1;
  g->margin_certified = g->margin_upper = NAN;
  g->margin_decided = 0;
  if (g->recheck != 1) return AUTOBAL_SUCCESS;
  hi = viol = fmin(g->margin, g->recheck_margin); /* a sampled point has a root at Re lambda = -hi */
  if (!(hi > 0.0)) return AUTOBAL_SUCCESS;
  if ((st = thr_handle(c, t, c->o->unbalance2_boxes)) != AUTOBAL_SUCCESS) return st;
  if ((st = set_balls(t, g->mass, g->damping, g->radius)) != AUTOBAL_SUCCESS) return st;
  if (!(order = malloc(n * sizeof *order))) return autobal_error_set(&t->err, AUTOBAL_ENOMEM, "design: out of memory");
  /* the speeds by their sampled margin, the largest (least stable) first */
  for (i = 0; i < n; i++) order[i] = i;
  for (i = 1; i < n; i++)
    for (j = i; j > 0 && rec[order[j]].margin > rec[order[j - 1]].margin; j--) {
      const size_t x = order[j];
      order[j] = order[j - 1];
      order[j - 1] = x;
    }
  /* delta = 0: proven by the certification when every speed was decided there */
  if (g->n_certified != n) {
    r = shifted_all(c, t, order, 0.0, &g->margin_steps, &st);
    if (st != AUTOBAL_SUCCESS || r != 1) {
      free(order);
      return st;
    }
  }
  /* the required margin first (it decides feasibility), then bisection */
  if (req > lo && req < hi) {
    r = shifted_all(c, t, order, req, &g->margin_steps, &st);
    if (st != AUTOBAL_SUCCESS) {
      free(order);
      return st;
    }
    if (r == 1) lo = req;
    else hi = req;
    if (r == 0) viol = req;
    if (r == -1) decided = 0;
  }
  while (hi - lo > tol) {
    const double mid = 0.5 * (lo + hi);
    r = shifted_all(c, t, order, mid, &g->margin_steps, &st);
    if (st != AUTOBAL_SUCCESS) break;
    if (r == 1) lo = mid;
    else hi = mid;
    if (r == 0) viol = mid;
    if (r == -1) decided = 0;
  }
  free(order);
  if (st != AUTOBAL_SUCCESS) return st;
  g->margin_certified = lo;
  g->margin_upper = viol;
  g->margin_decided = decided;
  return AUTOBAL_SUCCESS;
}

/* ---- the optimizer (options.n_starts, max_iter): GSL's Nelder-Mead simplex (nmsimplex2) over
 * (m, h, r), each mapped onto R by v = lo (hi/lo)^((1 + sin x) / 2) as for one plane, from the best
 * cells of the map.  The objective is the map's own: the largest margin met over the speed grid by the
 * grid+slice verdict (no box search), +1 where a speed is not stable (a step up at the boundary), and a
 * slope towards larger m r where the balls cannot balance the largest unbalance.  Its result is then
 * ranked with the cells and certified like them. */
typedef struct nm2ctx {
  const d2ctx *c;
  d2thr *t;
  double lo[3], hi[3]; /* mass, damping, radius */
  int which[3];
  size_t n, evals;
  double base[3];
  int status;
} nm2ctx;

static double nm2_from(const nm2ctx *n, size_t i, double x) {
  const int w = n->which[i];
  return n->lo[w] * pow(n->hi[w] / n->lo[w], 0.5 * (1.0 + sin(x)));
}
static void nm2_point(const nm2ctx *n, const gsl_vector *x, double v[3]) {
  size_t i;
  memcpy(v, n->base, 3 * sizeof *v);
  for (i = 0; i < n->n; i++) v[n->which[i]] = nm2_from(n, i, gsl_vector_get(x, i));
}

/* the objective at v = (m, h, r); *stable: stable at every grid speed */
static double nm2_value(nm2ctx *n, const double v[3], int *stable) {
  const d2ctx *c = n->c;
  const double umax = fmax(c->hi[0], c->hi[1]);
  double worst = -INFINITY;
  size_t k;
  int st, all = 1;
  *stable = 0;
  n->evals++;
  if (!(2.0 * v[0] * v[2] > umax)) return 1e5 + 1e3 * umax / (2.0 * v[0] * v[2]);
  if ((st = set_balls(n->t, v[0], v[1], v[2])) != AUTOBAL_SUCCESS) {
    n->status = st;
    return 1e6;
  }
  for (k = 0; k < c->o->n_omega; k++) {
    autobal_rotor_unbalance_range2 u;
    st = verdict_at(c, n->t, c->omega[k], &u);
    if (st == AUTOBAL_ECANCELLED || st == AUTOBAL_ENOMEM) {
      n->status = st;
      return 1e6;
    }
    if (st != AUTOBAL_SUCCESS) { /* undecided there: as not stable */
      autobal_error_clear(&n->t->err);
      all = 0;
      continue;
    }
    if (!stable_of(&u)) all = 0;
    if (u.margin_worst > worst) worst = u.margin_worst;
  }
  *stable = all;
  return all ? worst : fmax(worst, 0.0) + 1.0;
}

static double nm2_objective(const gsl_vector *x, void *user) {
  nm2ctx *n = (nm2ctx *)user;
  double v[3];
  int stable;
  if (n->status != AUTOBAL_SUCCESS) return 1e6;
  nm2_point(n, x, v);
  return nm2_value(n, v, &stable);
}

/* One start (job k: the k-th best cell) -> out (source 1; margin NaN when not stable at every speed). */
typedef struct nm2job {
  const autobal_rotor_design *start; /* [n_starts] */
  autobal_rotor_design *out;         /* [n_starts] */
  size_t *evals;                     /* [n_starts] */
} nm2job;

static int nm2_run(const d2ctx *c, d2thr *t, size_t k, void *user) {
  const nm2job *J = (const nm2job *)user;
  const autobal_rotor_design *s0 = &J->start[k];
  autobal_rotor_design *out = &J->out[k];
  const autobal_study_rotor_design_options *o = c->o;
  const double lo[3] = {o->mass_min, o->damping_min, o->radius_min}, hi[3] = {o->mass_max, o->damping_max, o->radius_max};
  nm2ctx n;
  gsl_multimin_function f;
  gsl_multimin_fminimizer *mz;
  gsl_vector *x, *step;
  size_t i, it;
  int gst, st, stable = 0;
  double v[3], val;
  *out = *s0;
  out->source = 1;
  out->margin = NAN;
  memset(&n, 0, sizeof n);
  n.c = c;
  n.t = t;
  n.base[0] = s0->mass;
  n.base[1] = s0->damping;
  n.base[2] = s0->radius;
  for (i = 0; i < 3; i++) {
    n.lo[i] = lo[i];
    n.hi[i] = hi[i];
    if (lo[i] < hi[i]) n.which[n.n++] = (int)i;
  }
  if (n.n == 0) return AUTOBAL_SUCCESS;
  if ((st = thr_handle(c, t, -1)) != AUTOBAL_SUCCESS) return st;
  f.n = n.n;
  f.f = nm2_objective;
  f.params = &n;
  if (autobal_design_nm_alloc_(n.n, &mz, &x, &step) != 0)
    return autobal_error_set(&t->err, AUTOBAL_ENOMEM, "design: out of memory (optimizer, two planes)");
  for (i = 0; i < n.n; i++) {
    const int w = n.which[i];
    const double fr = fmin(1.0, fmax(0.0, log(n.base[w] / lo[w]) / log(hi[w] / lo[w])));
    gsl_vector_set(x, i, asin(2.0 * fr - 1.0));
    gsl_vector_set(step, i, 0.25);
  }
  n.status = AUTOBAL_SUCCESS;
  gst = gsl_multimin_fminimizer_set(mz, &f, x, step);
  for (it = 0; gst == GSL_SUCCESS && it < o->max_iter && n.status == AUTOBAL_SUCCESS; it++) {
    if ((gst = gsl_multimin_fminimizer_iterate(mz)) != GSL_SUCCESS) break;
    if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(mz), 1e-3) == GSL_SUCCESS) break;
  }
  if (n.status == AUTOBAL_SUCCESS) {
    nm2_point(&n, gsl_multimin_fminimizer_x(mz), v);
    val = nm2_value(&n, v, &stable); /* its margin, evaluated again at the point itself */
    out->mass = v[0];
    out->damping = v[1];
    out->radius = v[2];
    out->margin = stable ? -val : NAN;
  }
  J->evals[k] = n.evals;
  st = n.status;
  gsl_multimin_fminimizer_free(mz);
  gsl_vector_free(x);
  gsl_vector_free(step);
  return st;
}

typedef int (*d2job)(const d2ctx *c, d2thr *t, size_t k, void *user);
static int job_cell(const d2ctx *c, d2thr *t, size_t k, void *user) {
  (void)user;
  return map_cell(c, t, k);
}
static int job_cert(const d2ctx *c, d2thr *t, size_t k, void *user) { return cert_job(c, t, k, (cert_rec *)user); }
static int job_margin(const d2ctx *c, d2thr *t, size_t k, void *user) { return margin_job(c, t, k, user); }
static int job_nm2(const d2ctx *c, d2thr *t, size_t k, void *user) { return nm2_run(c, t, k, user); }

static int read_stop(const int *f) {
  int v;
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp atomic read
#endif
  v = *f;
  return v;
}

/* n jobs over the threads; the first failure by index is reported; the caller's progress callback
 * from thread 0 (cancel: AUTOBAL_ECANCELLED). */
static int run_jobs(d2ctx *c, size_t n, d2job job, void *user, size_t *verdicts, autobal_error *err) {
  int stop = 0, cancelled = 0, nth = 1;
  long long fail_idx = -1;
  int fail_st = AUTOBAL_SUCCESS;
  char fail_msg[AUTOBAL_ERRMSG_SIZE] = "";
  size_t ndone = 0;
#ifdef AUTOBAL_HAVE_OPENMP
  nth = c->o->threads > 0 ? c->o->threads : omp_get_max_threads();
#endif
  c->stop = &stop;
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp parallel num_threads(nth)
#endif
  {
    d2thr t;
    long long idx;
    memset(&t, 0, sizeof t);
    autobal_error_clear(&t.err);
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
    for (idx = 0; idx < (long long)n; idx++) {
      int st, me = 0;
      if (read_stop(&stop)) continue;
      st = job(c, &t, (size_t)idx, user);
      if (st != AUTOBAL_SUCCESS) {
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp critical(autobal_design2_fail)
#endif
        {
          if (fail_idx < 0 || idx < fail_idx) {
            fail_idx = idx;
            fail_st = st;
            snprintf(fail_msg, sizeof fail_msg, "%s", t.err.message);
          }
        }
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp atomic write
#endif
        stop = 1;
      }
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp atomic
#endif
      ndone++;
#ifdef AUTOBAL_HAVE_OPENMP
      me = omp_get_thread_num();
#endif
      if (me == 0 && c->o->progress) {
        size_t nd;
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp atomic read
#endif
        nd = ndone;
        if (c->o->progress(c->f0 + c->df * (double)nd / (double)n, c->o->progress_user)) {
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp atomic write
#endif
          cancelled = 1;
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp atomic write
#endif
          stop = 1;
        }
      }
    }
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp critical(autobal_design2_sum)
#endif
    *verdicts += t.verdicts;
    autobal_rotor_stab_free(t.s);
  }
  (void)nth;
  c->stop = NULL;
  if (cancelled) return autobal_error_set(err, AUTOBAL_ECANCELLED, "design: cancelled by the caller (two planes)");
  if (fail_st != AUTOBAL_SUCCESS) return autobal_error_set(err, fail_st, "%s", fail_msg);
  return AUTOBAL_SUCCESS;
}

int autobal_design_nm_alloc_(size_t n, gsl_multimin_fminimizer **mz, gsl_vector **x, gsl_vector **step) {
  *mz = gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, n);
  *x = gsl_vector_alloc(n);
  *step = gsl_vector_alloc(n);
  if (*mz && *x && *step) return 0;
  gsl_multimin_fminimizer_free(*mz);
  gsl_vector_free(*x);
  gsl_vector_free(*step);
  *mz = NULL;
  *x = *step = NULL;
  return -1;
}

double *autobal_design_grid_(double lo, double hi, size_t n, int geometric) {
  double *g = malloc((n ? n : 1) * sizeof *g);
  size_t i;
  if (!g) return NULL;
  for (i = 0; i < n; i++) {
    const double f = n > 1 ? (double)i / (double)(n - 1) : 0.0;
    g[i] = geometric ? lo * pow(hi / lo, f) : lo + (hi - lo) * f;
  }
  if (n > 1) g[n - 1] = hi;
  return g;
}

typedef struct rankc {
  double rho;
  size_t idx;
} rankc;
static int cmp_rank(const void *a, const void *b) {
  const rankc *x = (const rankc *)a, *y = (const rankc *)b;
  if (x->rho > y->rho) return -1;
  if (x->rho < y->rho) return 1;
  return (x->idx > y->idx) - (x->idx < y->idx);
}

int autobal_design2_run_(autobal_rotor_params *work, const autobal_study_rotor_design_options *o,
                         autobal_study_rotor_design_summary *S, autobal_error *err) {
  d2ctx c;
  const size_t ncell = o->n_mass * o->n_damping * o->n_radius;
  rankc *rk = NULL;
  cert_rec *rec = NULL;
  size_t i, k, nr = 0, nopt;
  int st;
  memset(&c, 0, sizeof c);
  c.work = work;
  c.o = o;
  c.S = S;
  c.lo[0] = o->unbalance_min;
  c.hi[0] = o->unbalance_max;
  c.lo[1] = o->unbalance2_min;
  c.hi[1] = o->unbalance2_max;
  S->planes = 2;
  S->n_n = 1;
  S->n_balls = malloc(sizeof *S->n_balls);
  S->n_mass = o->n_mass;
  S->n_damping = o->n_damping;
  S->n_position = 1;
  S->n_radius = o->n_radius;
  S->mass = autobal_design_grid_(o->mass_min, o->mass_max, o->n_mass, 1);
  S->damping = autobal_design_grid_(o->damping_min, o->damping_max, o->n_damping, 1);
  S->position = autobal_design_grid_(work->plane[0].d, work->plane[0].d, 1, 0);
  S->radius = autobal_design_grid_(o->radius_min, o->radius_max, o->n_radius, 1);
  S->feasible = malloc(ncell * sizeof *S->feasible);
  S->margin_map = malloc(ncell * sizeof *S->margin_map);
  S->window_lo = malloc(o->n_mass * o->n_damping * sizeof *S->window_lo);
  S->window_hi = malloc(o->n_mass * o->n_damping * sizeof *S->window_hi);
  c.omega = autobal_design_grid_(o->omega_min, o->omega_max, o->n_omega, 0);
  rk = malloc(ncell * sizeof *rk);
  if (!S->n_balls || !S->mass || !S->damping || !S->position || !S->radius || !S->feasible || !S->margin_map ||
      !S->window_lo || !S->window_hi || !c.omega || !rk) {
    free(c.omega);
    free(rk);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "design: out of memory");
  }
  S->n_balls[0] = 2;
  for (i = 0; i < o->n_mass * o->n_damping; i++) S->window_lo[i] = S->window_hi[i] = NAN; /* not computed */
  /* 1. the map */
  c.f0 = 0.0;
  c.df = 0.6;
  st = run_jobs(&c, ncell, job_cell, NULL, &S->verdicts2, err);
  if (st != AUTOBAL_SUCCESS) {
    free(c.omega);
    free(rk);
    return st;
  }
  S->n_mass_done = o->n_mass;
  for (i = 0; i < ncell; i++) {
    S->n_feasible += S->feasible[i] == 1;
    S->n_undecided_cells += S->feasible[i] == -3;
    if (isfinite(S->margin_map[i])) {
      rk[nr].rho = S->margin_map[i];
      rk[nr++].idx = i;
    }
  }
  /* 2. the ranking by the sampled margin; 3. the certification of the first n_best */
  qsort(rk, nr, sizeof *rk, cmp_rank);
  nopt = o->n_starts < nr ? o->n_starts : nr;
  if (nr > o->n_best) nr = o->n_best;
  S->designs = calloc(nr + nopt + 1, sizeof *S->designs);
  rec = malloc((nr ? nr : 1) * o->n_omega * sizeof *rec);
  if (!S->designs || !rec) {
    free(c.omega);
    free(rk);
    free(rec);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "design: out of memory");
  }
  for (k = 0; k < (nr > nopt ? nr : nopt); k++) { /* the best cells (the first nopt: the optimizer's starts) */
    autobal_rotor_design *d = &S->designs[k];
    const size_t idx = rk[k].idx, q = idx % o->n_radius, j = (idx / o->n_radius) % o->n_damping,
                 m = idx / (o->n_radius * o->n_damping);
    d->mass = S->mass[m];
    d->damping = S->damping[j];
    d->radius = S->radius[q];
    d->position = work->plane[0].d;
    d->margin = rk[k].rho;
    d->source = 0;
    d->n_balls = 2;
    d->recheck = -1;
    d->recheck_margin = NAN;
    d->p_balance = d->ttb_median = d->ttb_worst = NAN;
    d->found_omega = d->found_s[0] = d->found_s[1] = d->found_phase = NAN;
    d->margin_certified = d->margin_upper = NAN;
  }
  S->n_designs = nr;
  /* 2b. the optimizer from the best nopt cells; its results ranked with the cells (distinct ones) */
  if (nopt > 0) {
    autobal_rotor_design *outs = calloc(nopt, sizeof *outs), *starts = malloc(nopt * sizeof *starts);
    size_t *ev = calloc(nopt, sizeof *ev);
    nm2job J;
    if (!outs || !starts || !ev) st = autobal_error_set(err, AUTOBAL_ENOMEM, "design: out of memory");
    if (st == AUTOBAL_SUCCESS) {
      memcpy(starts, S->designs, nopt * sizeof *starts);
      J.start = starts;
      J.out = outs;
      J.evals = ev;
      c.f0 = 0.6;
      c.df = 0.0;
      st = run_jobs(&c, nopt, job_nm2, &J, &S->verdicts2, err);
    }
    for (k = 0; k < nopt && st == AUTOBAL_SUCCESS; k++) {
      size_t q, pos;
      int dup = 0;
      S->optimizer_evaluations += ev[k];
      if (!isfinite(outs[k].margin)) continue;
      for (q = 0; q < S->n_designs; q++)
        dup |= fabs(S->designs[q].mass - outs[k].mass) <= 1e-9 * outs[k].mass &&
               fabs(S->designs[q].damping - outs[k].damping) <= 1e-9 * outs[k].damping &&
               fabs(S->designs[q].radius - outs[k].radius) <= 1e-9 * outs[k].radius;
      if (dup) continue;
      /* insert by margin, after the designs of equal margin */
      for (pos = S->n_designs; pos > 0 && S->designs[pos - 1].margin < outs[k].margin; pos--) S->designs[pos] = S->designs[pos - 1];
      S->designs[pos] = outs[k];
      S->n_designs++;
    }
    free(outs);
    free(starts);
    free(ev);
    if (S->n_designs > o->n_best) S->n_designs = o->n_best;
    nr = S->n_designs;
    free(rec);
    rec = malloc((nr ? nr : 1) * o->n_omega * sizeof *rec);
    if (!rec && st == AUTOBAL_SUCCESS) st = autobal_error_set(err, AUTOBAL_ENOMEM, "design: out of memory");
    if (st != AUTOBAL_SUCCESS) {
      S->n_designs = 0;
      free(c.omega);
      free(rk);
      free(rec);
      return st;
    }
  }
  c.des = S->designs;
  c.f0 = 0.6;
  c.df = 0.2;
  if (o->unbalance2_boxes >= 0 && nr > 0)
    st = run_jobs(&c, nr * o->n_omega, job_cert, rec, &S->verdicts2, err);
  if (st == AUTOBAL_SUCCESS) {
    for (k = 0; k < nr; k++) {
      autobal_rotor_design *d = &S->designs[k];
      double worst = -INFINITY;
      int all = 1;
      if (o->unbalance2_boxes < 0) {
        d->feasible = d->margin > o->margin;
        continue;
      }
      for (i = 0; i < o->n_omega; i++) {
        const cert_rec *r = &rec[k * o->n_omega + i];
        d->n_certify_run++;
        d->boxes += r->boxes;
        if (r->failed || !r->stable) {
          if (all && !r->failed) {
            d->found_omega = c.omega[i];
            d->found_s[0] = r->found_s[0];
            d->found_s[1] = r->found_s[1];
            d->found_phase = r->found_phase;
          }
          all = 0;
          continue;
        }
        d->n_certified += r->exact != 0;
        if (r->margin > worst) worst = r->margin;
      }
      d->recheck = all;
      d->recheck_margin = all ? -worst : NAN;
      d->feasible = all && d->margin > o->margin;
    }
    /* 4. the certified margin of the ranked designs that passed (bisection over the shifted verdict) */
    {
      marg_job mj;
      mj.rec = rec;
      c.f0 = 0.8;
      c.df = 0.2;
      if (o->unbalance2_boxes >= 0 && nr > 0) st = run_jobs(&c, nr, job_margin, &mj, &S->verdicts2, err);
      for (k = 0; k < nr && st == AUTOBAL_SUCCESS; k++) {
        autobal_rotor_design *d = &S->designs[k];
        /* feasibility from the proven bracket: the required margin is proven (certified >= it) or
           violated (upper <= it); otherwise (undecided there) the sampled rule stands */
        if (isnan(d->margin_certified)) continue;
        if (d->margin_certified >= o->margin) d->feasible = 1;
        else if (d->margin_upper <= o->margin) d->feasible = 0;
      }
    }
    /* the best: the first feasible one */
    for (k = 0; k < nr; k++)
      if (S->designs[k].feasible) {
        if (k) {
          autobal_rotor_design t = S->designs[k];
          memmove(S->designs + 1, S->designs, k * sizeof *S->designs);
          S->designs[0] = t;
        }
        break;
      }
    if (st == AUTOBAL_SUCCESS) S->ranked = 1;
  }
  free(c.omega);
  free(rk);
  free(rec);
  return st;
}
