/* pendulum_map.c: the pendulum stability-map and sweep studies (`autobal pendulum map`,
 * `autobal pendulum sweep`): the verdict of the main motion over a grid of any one or two
 * parameters (default (R_m, R_w)), for one unbalance or every one, the critical values of a
 * sweep, and their archive layouts (include/autobal/study.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "autobal/study.h"
#include "internal.h"

/* Measured on the grid of data/pendulum_map_every.ini (every unbalance, k = j/32) with this
 * library and reproduced point for point by tests/app/pendulum_smalldamp_check.py (NumPy
 * eigenvalues of (5), 0 of 19200 points differ); docs/pendulum.md has the table over H/h. */
#define AUTOBAL_PENDULUM_UNDAMPED_NOTE_TEXT                                                          \
  "the undamped map is not the small-damping limit. With small damping the set stable for every "   \
  "unbalance depends on the ratio H/h only (the same at H, h ~ 1e-4 and 1e-6) and is smaller at "     \
  "every ratio: on the grid of data/pendulum_map_every.ini (R_m 0.005..0.495 x R_w 0.5..4, k = j/32) " \
  "undamped 42.0% stable; H = h: 28.8%; h = 10H: 29.4%, region B only from R_m = 0.236; "             \
  "H = 10h: 0.4%; H/h = 0.4: 39.3% (the largest of 16 ratios 0.01..10); h = 100H: 4.6%. Every damped "  \
  "stable point is stable undamped, not the converse (docs/pendulum.md, \"The undamped map is not the small-damping limit\")."

static double now_seconds(void) {
  struct timespec ts;
  if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) return 0.0;
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

autobal_study_pendulum_map_options autobal_study_pendulum_map_options_default(void) {
  autobal_study_pendulum_map_options o;
  memset(&o, 0, sizeof o);
  o.Rm_min = 0.005;
  o.Rm_max = 0.495;
  o.n_Rm = 200;
  o.Rw_min = 0.05;
  o.Rw_max = 5.0;
  o.n_Rw = 200;
  o.n_k = 65;
  o.param1 = AUTOBAL_PENDULUM_PARAM_R_M;
  o.param2 = AUTOBAL_PENDULUM_PARAM_R_W;
  o.min1 = o.max1 = o.min2 = o.max2 = NAN;
  o.log1 = o.log2 = -1;
  return o;
}

void autobal_study_pendulum_param_range(int param, double *lo, double *hi, int *log_scale) {
  double a = NAN, b = NAN;
  int lg = 0;
  switch (param) {
  case AUTOBAL_PENDULUM_PARAM_R_W: a = 0.05, b = 5.0; break;
  case AUTOBAL_PENDULUM_PARAM_R_M: a = 0.005, b = 0.495; break;
  case AUTOBAL_PENDULUM_PARAM_H:
  case AUTOBAL_PENDULUM_PARAM_HP: a = 1e-4, b = 1.0, lg = 1; break;
  case AUTOBAL_PENDULUM_PARAM_K: a = 0.0, b = 1.0; break;
  case AUTOBAL_PENDULUM_PARAM_PSI0: a = 0.0, b = 0.78539816339744831; break;
  case AUTOBAL_PENDULUM_PARAM_H_RATIO: a = 0.01, b = 100.0, lg = 1; break;
  default: break;
  }
  if (lo) *lo = a;
  if (hi) *hi = b;
  if (log_scale) *log_scale = lg;
}

void autobal_study_pendulum_param_range_physical(int param, const autobal_pendulum_physical *phys, double *lo,
                                                 double *hi, int *log_scale) {
  double a = NAN, b = NAN, Ms, w0, dlo, dhi, v;
  int lg = 0;
  if (!autobal_pendulum_param_is_physical(param)) {
    autobal_study_pendulum_param_range(param, lo, hi, log_scale);
    return;
  }
  lg = param != AUTOBAL_PENDULUM_PARAM_OMEGA && param != AUTOBAL_PENDULUM_PARAM_E; /* scales: log */
  if (phys != NULL && autobal_pendulum_param_domain(phys, param, &dlo, &dhi, NULL) == AUTOBAL_SUCCESS) {
    Ms = phys->M + 2.0 * phys->m; /* (2) */
    w0 = sqrt(phys->c / Ms);
    switch (param) {
    case AUTOBAL_PENDULUM_PARAM_OMEGA: a = 0.05 * w0, b = 5.0 * w0; break;  /* R_w 0.05 .. 5 */
    case AUTOBAL_PENDULUM_PARAM_E: a = 0.0, b = sqrt(2.0) * phys->m * phys->l / phys->M; break; /* psi0 0 .. pi/4 */
    case AUTOBAL_PENDULUM_PARAM_H2: a = 1e-4 * w0 * Ms, b = w0 * Ms; break; /* H 1e-4 .. 1 */
    case AUTOBAL_PENDULUM_PARAM_H1:                                                   /* h 1e-4 .. 1 */
      a = 1e-4 * phys->m * phys->l * phys->l * w0, b = phys->m * phys->l * phys->l * w0;
      break;
    default: /* M, m, l, c: a quarter to four times the configured value */
      v = param == AUTOBAL_PENDULUM_PARAM_M ? phys->M : param == AUTOBAL_PENDULUM_PARAM_MP ? phys->m
          : param == AUTOBAL_PENDULUM_PARAM_L ? phys->l : phys->c;
      a = 0.25 * v, b = 4.0 * v;
      break;
    }
    /* inside the model's domain at the configured values of the other keys */
    if (a < dlo) a = dlo;
    if (b > dhi) b = dhi;
  }
  if (lo) *lo = a;
  if (hi) *hi = b;
  if (log_scale) *log_scale = lg;
}

/* The measured small-damping picture (docs/pendulum.md, "The undamped map is not the
 * small-damping limit"): every-unbalance maps of the default grid (R_m 0.005..0.495 x R_w
 * 0.05..5, 200 x 200, k = j/64), measured with `autobal pendulum map` and reproduced
 * independently by tests/app/pendulum_smalldamp_check.py (NumPy eigenvalues of (5)). */
const char *autobal_study_pendulum_undamped_note(void) {
  return AUTOBAL_PENDULUM_UNDAMPED_NOTE_TEXT;
}

void autobal_study_pendulum_map_summary_free(autobal_study_pendulum_map_summary *s) {
  if (!s) return;
  free(s->R_m);
  free(s->R_w);
  free(s->k);
  free(s->verdict);
  free(s->max_real);
  s->R_m = s->R_w = s->k = s->max_real = NULL;
  s->verdict = NULL;
}

/* n values from lo to hi, linear (the expression of the former (R_m, R_w) grids, so that their
 * archives rerun bit for bit) or logarithmic (the ends exact) */
/* The values of k (every unbalance: n_k from 0 to 1; else p's) and a grid over param1 = v1[0 .. n1)
 * with them and the convention (param2 for the caller). */
static void grid_spec_init(autobal_pendulum_grid_spec *spec, const autobal_pendulum_params *p,
                           const autobal_pendulum_physical *phys, int every, double *k, size_t n_k,
                           int paper_convention, int param1, const double *v1, size_t n1) {
  size_t i;
  if (every)
    for (i = 0; i < n_k; i++) k[i] = (double)i / (double)(n_k - 1);
  else
    k[0] = autobal_pendulum_k(p);
  memset(spec, 0, sizeof *spec);
  spec->base = *p;
  spec->param1 = param1;
  spec->v1 = v1;
  spec->n1 = n1;
  if (every) spec->k = k, spec->n_k = n_k;
  spec->paper_convention = paper_convention;
  spec->phys = phys;
}

static void fill_axis(double *v, size_t n, double lo, double hi, int lg) {
  size_t i;
  for (i = 0; i < n; i++) {
    if (n == 1) v[i] = lo;
    else if (lg) v[i] = exp(log(lo) + (log(hi) - log(lo)) * ((double)i / (double)(n - 1)));
    else v[i] = lo + (hi - lo) * (double)i / (double)(n - 1);
  }
  if (lg && n > 1) v[0] = lo, v[n - 1] = hi;
}

/* is H = h = 0 at every point of a grid over param1 (and param2, -1: none) at p */
static int all_undamped(const autobal_pendulum_params *p, int param1, int param2) {
  int i, ax[2];
  ax[0] = param1, ax[1] = param2;
  for (i = 0; i < 2; i++)
    if (ax[i] == AUTOBAL_PENDULUM_PARAM_H || ax[i] == AUTOBAL_PENDULUM_PARAM_HP ||
        ax[i] == AUTOBAL_PENDULUM_PARAM_H_RATIO || ax[i] == AUTOBAL_PENDULUM_PARAM_H1 ||
        ax[i] == AUTOBAL_PENDULUM_PARAM_H2)
      return 0;
  return p->H == 0.0 && p->h == 0.0;
}

/* resolve one axis of the options: range, points, scale; "options: ..." messages.  which = 1, 2:
 * the map's axes (keys min1, max1, n1), 0: the sweep (min, max, n in [2, 1e7]) */
static int resolve_axis(int which, int param, const autobal_pendulum_physical *phys, double mn, double mx, size_t n,
                        int lg, double leg_min, double leg_max, size_t leg_n, int legacy, double *omin, double *omax,
                        size_t *on, int *olog, autobal_error *err) {
  const char *key = autobal_pendulum_param_name(param);
  char sfx[4] = "", what[48];
  double dlo, dhi;
  int dlog, st;
  size_t nmin = which ? 1 : 2, nmax = which ? 100000 : 10000000;
  if (which) snprintf(sfx, sizeof sfx, "%d", which);
  if (key == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: param%s = %d is not a pendulum parameter (allowed 0..%d)",
                             sfx, param, AUTOBAL_PENDULUM_NPARAM - 1);
  if (which) snprintf(what, sizeof what, "axis %d (pendulum.%s)", which, key);
  else snprintf(what, sizeof what, "sweep of pendulum.%s", key);
  if (autobal_pendulum_param_is_physical(param) && phys == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "%s: pendulum.%s is a physical key: it needs the physical set ([pendulum] given by M, e, "
                             "m, l, c, H1, H2, omega, not by the dimensionless keys R_w, R_m, H, h, k or psi0)",
                             what, key);
  autobal_study_pendulum_param_range_physical(param, phys, &dlo, &dhi, &dlog);
  if (isnan(mn)) mn = legacy ? leg_min : dlo;
  if (isnan(mx)) mx = legacy ? leg_max : dhi;
  if (n == 0) n = legacy ? leg_n : 200;
  if (lg < 0) lg = dlog && mn > 0.0;
  if ((st = autobal_pendulum_param_check(param, mn, err)) != 0) return st;
  if ((st = autobal_pendulum_param_check(param, mx, err)) != 0) return st;
  if (!(which ? mn <= mx : mn < mx))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: %s: need min%s %s max%s, got %g, %g", what, sfx,
                             which ? "<=" : "<", sfx, mn, mx);
  if (param == AUTOBAL_PENDULUM_PARAM_R_W && mx > 1e4)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: %s: max%s = %g is too large: allowed <= 1e4", what, sfx, mx);
  if (lg && !(mn > 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: %s: a logarithmic axis needs min%s > 0, got %g", what, sfx, mn);
  if (n < nmin || n > nmax)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: %s: n%s = %zu is out of range: allowed [%zu, %zu]", what, sfx,
                             n, nmin, nmax);
  *omin = mn, *omax = mx, *on = n, *olog = lg != 0;
  return AUTOBAL_SUCCESS;
}

int autobal_study_pendulum_map(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys,
                               const autobal_study_pendulum_map_options *opt, autobal_archive *a,
                               autobal_study_pendulum_map_summary *summary, autobal_error *err) {
  autobal_study_pendulum_map_options def = autobal_study_pendulum_map_options_default();
  const autobal_study_pendulum_map_options *o = opt ? opt : &def;
  autobal_study_pendulum_map_summary *s = summary;
  autobal_pendulum_grid_spec spec;
  signed char *v = NULL;
  double min1, max1, min2, max2;
  size_t i, n, n1, n2;
  int st, log1, log2, leg1, leg2;
  autobal_error_clear(err);
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(s, 0, sizeof *s);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  leg1 = o->param1 == AUTOBAL_PENDULUM_PARAM_R_M && isnan(o->min1) && isnan(o->max1);
  leg2 = o->param2 == AUTOBAL_PENDULUM_PARAM_R_W && isnan(o->min2) && isnan(o->max2);
  /* the former options, with their messages, on the default axes */
  if (leg1 && !(o->Rm_min > 0 && o->Rm_min <= o->Rm_max && o->Rm_max < 0.5))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: need 0 < Rm_min <= Rm_max < 0.5, got Rm_min = %g, Rm_max = %g",
                             o->Rm_min, o->Rm_max);
  if (leg2 && !(o->Rw_min >= 0 && o->Rw_min <= o->Rw_max && o->Rw_max <= 1e4))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: need 0 <= Rw_min <= Rw_max <= 1e4, got Rw_min = %g, Rw_max = %g",
                             o->Rw_min, o->Rw_max);
  if (o->param1 == AUTOBAL_PENDULUM_PARAM_R_M && o->n1 == 0 && (o->n_Rm < 1 || o->n_Rm > 100000))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_Rm = %zu is out of range: allowed [1, 100000]", o->n_Rm);
  if (o->param2 == AUTOBAL_PENDULUM_PARAM_R_W && o->n2 == 0 && (o->n_Rw < 1 || o->n_Rw > 100000))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_Rw = %zu is out of range: allowed [1, 100000]", o->n_Rw);
  if ((st = resolve_axis(1, o->param1, phys, o->min1, o->max1, o->n1, o->log1, o->Rm_min, o->Rm_max,
                         o->param1 == AUTOBAL_PENDULUM_PARAM_R_M ? o->n_Rm : 200,
                         o->param1 == AUTOBAL_PENDULUM_PARAM_R_M, &min1, &max1, &n1, &log1, err)))
    return st;
  if ((st = resolve_axis(2, o->param2, phys, o->min2, o->max2, o->n2, o->log2, o->Rw_min, o->Rw_max,
                         o->param2 == AUTOBAL_PENDULUM_PARAM_R_W ? o->n_Rw : 200,
                         o->param2 == AUTOBAL_PENDULUM_PARAM_R_W, &min2, &max2, &n2, &log2, err)))
    return st;
  if (o->every_unbalance && (o->n_k < 2 || o->n_k > 100000))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_k = %zu is out of range: allowed [2, 100000]", o->n_k);
  if (o->threads < 0 || o->threads > 1024)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: threads = %d is out of range: allowed [0, 1024]", o->threads);
  s->param1 = o->param1, s->param2 = o->param2;
  s->log1 = log1, s->log2 = log2;
  s->paper_convention = o->paper_convention != 0;
  s->undamped = all_undamped(p, o->param1, o->param2);
  s->n_Rm = n1;
  s->n_Rw = n2;
  s->every_unbalance = o->every_unbalance != 0;
  s->n_k = o->every_unbalance ? o->n_k : 1;
  n = s->n_Rm * s->n_Rw;
  s->R_m = malloc(s->n_Rm * sizeof *s->R_m);
  s->R_w = malloc(s->n_Rw * sizeof *s->R_w);
  s->k = malloc(s->n_k * sizeof *s->k);
  s->verdict = malloc(n * sizeof *s->verdict);
  v = malloc(n);
  if (o->max_real) s->max_real = malloc(n * sizeof *s->max_real);
  if (!s->R_m || !s->R_w || !s->k || !s->verdict || !v || (o->max_real && !s->max_real)) {
    free(v);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  fill_axis(s->R_m, n1, min1, max1, log1);
  fill_axis(s->R_w, n2, min2, max2, log2);
  grid_spec_init(&spec, p, phys, o->every_unbalance, s->k, s->n_k, s->paper_convention, o->param1, s->R_m, n1);
  spec.param2 = o->param2;
  spec.v2 = s->R_w;
  spec.n2 = n2;
  spec.n_threads = o->threads;
  /* the whole grid is checked before the first point (nothing computed or written on bad input) */
  if ((st = autobal_pendulum_grid_check(&spec, err)) != 0) {
    free(v);
    return st;
  }
  {
    /* in blocks of rows, about 0.25-1 s each (every point is independent: the blocks change
     * nothing), with progress and cancellation after each */
    size_t rows = 1;
    int cancelled = 0;
    while (s->n_Rm_done < s->n_Rm && !cancelled) {
      size_t r = s->n_Rm - s->n_Rm_done < rows ? s->n_Rm - s->n_Rm_done : rows, off = s->n_Rm_done * s->n_Rw;
      double t0 = now_seconds(), dt;
      spec.v1 = s->R_m + s->n_Rm_done;
      spec.n1 = r;
      st = autobal_pendulum_grid(&spec, v + off, s->max_real ? s->max_real + off : NULL, err);
      if (st) {
        free(v);
        return st;
      }
      s->n_Rm_done += r;
      dt = now_seconds() - t0;
      if (dt < 0.25 && rows < ((size_t)1 << 20)) rows *= 2;
      else if (dt > 1.0 && rows > 1) rows /= 2;
      if (o->progress && o->progress((double)s->n_Rm_done / (double)s->n_Rm, o->progress_user)) cancelled = 1;
    }
    n = s->n_Rm_done * s->n_Rw;
    for (i = 0; i < n; i++) {
      s->verdict[i] = v[i];
      s->n_stable += v[i] > 0;
    }
    free(v);
    if (a && (st = autobal_study_pendulum_map_write(a, p, phys, s)))
      return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
    if (s->n_Rm_done < s->n_Rm)
      return autobal_error_set(err, AUTOBAL_ECANCELLED, "cancelled by the progress callback after %zu of %zu rows",
                               s->n_Rm_done, s->n_Rm);
  }
  return AUTOBAL_SUCCESS;
}

/* the value of a parameter at p (H/h: H/h, NaN when h = 0; a physical key: its value in phys,
 * NaN without) */
static double param_value(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys, int param) {
  if (autobal_pendulum_param_is_physical(param) && phys == NULL) return NAN;
  switch (param) {
  case AUTOBAL_PENDULUM_PARAM_M: return phys->M;
  case AUTOBAL_PENDULUM_PARAM_E: return phys->e;
  case AUTOBAL_PENDULUM_PARAM_MP: return phys->m;
  case AUTOBAL_PENDULUM_PARAM_L: return phys->l;
  case AUTOBAL_PENDULUM_PARAM_C: return phys->c;
  case AUTOBAL_PENDULUM_PARAM_H1: return phys->H1;
  case AUTOBAL_PENDULUM_PARAM_H2: return phys->H2;
  case AUTOBAL_PENDULUM_PARAM_OMEGA: return phys->omega;
  case AUTOBAL_PENDULUM_PARAM_R_W: return p->R_w;
  case AUTOBAL_PENDULUM_PARAM_R_M: return p->R_m;
  case AUTOBAL_PENDULUM_PARAM_H: return p->H;
  case AUTOBAL_PENDULUM_PARAM_HP: return p->h;
  case AUTOBAL_PENDULUM_PARAM_K: return autobal_pendulum_k(p);
  case AUTOBAL_PENDULUM_PARAM_PSI0: return p->psi0;
  case AUTOBAL_PENDULUM_PARAM_H_RATIO: return p->h > 0 ? p->H / p->h : NAN;
  default: return NAN;
  }
}

static const char *criterion_text(int undamped, int damped_only, int paper) {
  if (damped_only) return "Routh-Hurwitz sign test on the characteristic polynomial (6)";
  if (undamped)
    return paper ? "undamped, the paper's first approximation: all roots x = lambda^2 of (10) real and <= 0"
                 : "exact undamped criterion (10): every root lambda on the imaginary axis and semisimple (as pendulum roots)";
  return paper ? "per point: Routh-Hurwitz on (6) where H > 0 or h > 0; where H = h = 0 the paper's first approximation of (10)"
               : "per point: Routh-Hurwitz on (6) where H > 0 or h > 0; where H = h = 0 the exact undamped criterion (10)";
}

/* the rule of an H/h axis, for the archive and the summaries ("" without one) */
static const char *ratio_rule(int param1, int param2) {
  int other;
  if (param1 == AUTOBAL_PENDULUM_PARAM_H_RATIO) other = param2;
  else if (param2 == AUTOBAL_PENDULUM_PARAM_H_RATIO) other = param1;
  else return "";
  if (other == AUTOBAL_PENDULUM_PARAM_H) return "h = H / (H/h), H from its axis";
  if (other == AUTOBAL_PENDULUM_PARAM_HP) return "H = (H/h) h, h from its axis";
  if (autobal_pendulum_param_is_physical(other))
    return "H = (H/h) h, h of each point's physical set (converted by (2)-(3))";
  return "H = (H/h) h, h held at pendulum.h";
}

/* can the damped criterion apply somewhere / everywhere on the grid */
static int damped_everywhere(const autobal_pendulum_params *p, int param1, int param2, double lo1, double lo2) {
  int ax[2], i;
  double lo[2];
  ax[0] = param1, ax[1] = param2, lo[0] = lo1, lo[1] = lo2;
  if (p->H > 0 || p->h > 0) {
    for (i = 0; i < 2; i++) /* an axis of H or h (H2 or H1) starting at 0 can reach H = h = 0 */
      if (((ax[i] == AUTOBAL_PENDULUM_PARAM_H || ax[i] == AUTOBAL_PENDULUM_PARAM_H2) && p->h == 0 && lo[i] == 0) ||
          ((ax[i] == AUTOBAL_PENDULUM_PARAM_HP || ax[i] == AUTOBAL_PENDULUM_PARAM_H1) && p->H == 0 && lo[i] == 0))
        return 0;
    return 1;
  }
  return 0;
}

static int write_axis_attrs(autobal_archive *a, const char *g, int which, int param, int lg) {
  char key[32], val[48];
  int st;
  snprintf(key, sizeof key, "axis%d", which);
  snprintf(val, sizeof val, "pendulum.%s", autobal_pendulum_param_name(param));
  st = autobal_archive_attr_string(a, g, key, val);
  snprintf(key, sizeof key, "axis%d_dim", which);
  if (!st) st = autobal_archive_attr_string(a, g, key, autobal_pendulum_param_dim(param));
  snprintf(key, sizeof key, "axis%d_scale", which);
  if (!st) st = autobal_archive_attr_string(a, g, key, lg ? "log" : "linear");
  return st;
}

/* omega = R_w omega0 of an R_w coordinate of a physical set */
static int write_omega(autobal_archive *a, const char *g, const char *dim, const double *rw, size_t n,
                       const autobal_pendulum_physical *phys) {
  const char *dims[1];
  double *om = malloc((n ? n : 1) * sizeof *om), w0 = sqrt(phys->c / (phys->M + 2.0 * phys->m));
  size_t q;
  int st;
  dims[0] = dim;
  if (!om) return AUTOBAL_ENOMEM;
  for (q = 0; q < n; q++) om[q] = rw[q] * w0;
  st = autobal_archive_var(a, g, "omega", 1, dims, om, "rad/s",
                           "rotor speed omega = R_w omega0 of the configuration's physical set");
  free(om);
  return st;
}

/* With a physical key on an axis every point has its own dimensionless set (the key moves R_w, R_m,
 * H, h or psi0): written as point/<name> over the axes (dims: absolute paths into g), each point
 * converted as the study converted it (autobal_pendulum_params_vary_physical; NaN where that
 * fails, which a grid the study accepted does not do).  k = sin^2(2 psi0) only for one unbalance. */
static int write_point_params(autobal_archive *a, const char *g, int rank, const char *const *dims,
                              const double *v1, size_t n1, int p1, const double *v2, size_t n2, int p2,
                              const autobal_pendulum_params *p, const autobal_pendulum_physical *phys, int every) {
  static const char *names[6] = {"R_w", "R_m", "H", "h", "psi0", "k"};
  static const char *units[6] = {"1", "1", "1", "1", "rad", "1"};
  static const char *what[6] = {"rotor speed R_w = omega/omega0 at each point",
                                "mass ratio R_m = m/(M + 2m) at each point",
                                "external damping H = H2/(omega0 (M + 2m)) at each point",
                                "pendulum damping h = H1/(m l^2 omega0) at each point",
                                "main-motion angle psi0 (sin psi0 = M e/(2 m l)) at each point",
                                "unbalance k = sin^2(2 psi0) at each point"};
  char grp[64], full[2][64];
  const char *pd[2];
  size_t n = n1 * (rank == 2 ? n2 : 1), q, i, j;
  double *buf;
  int st = AUTOBAL_SUCCESS, c;
  if (!phys || !(autobal_pendulum_param_is_physical(p1) || (rank == 2 && autobal_pendulum_param_is_physical(p2))))
    return AUTOBAL_SUCCESS;
  if (!n) return AUTOBAL_SUCCESS;
  buf = malloc(6 * n * sizeof *buf);
  if (!buf) return AUTOBAL_ENOMEM;
  for (i = 0; i < n1; i++)
    for (j = 0; j < (rank == 2 ? n2 : 1); j++) {
      autobal_pendulum_params o;
      q = i * (rank == 2 ? n2 : 1) + j;
      if (autobal_pendulum_params_vary_physical(p, phys, p1, v1[i], rank == 2 ? p2 : -1, rank == 2 ? v2[j] : 0.0, &o,
                                                NULL, NULL) != AUTOBAL_SUCCESS) {
        for (c = 0; c < 6; c++) buf[(size_t)c * n + q] = NAN;
        continue;
      }
      buf[0 * n + q] = o.R_w, buf[1 * n + q] = o.R_m, buf[2 * n + q] = o.H, buf[3 * n + q] = o.h;
      buf[4 * n + q] = o.psi0, buf[5 * n + q] = autobal_pendulum_k(&o);
    }
  snprintf(grp, sizeof grp, "%s/point", g);
  for (c = 0; c < rank; c++) {
    snprintf(full[c], sizeof full[c], "%s/%s", g, dims[c]);
    pd[c] = full[c];
  }
  st = autobal_archive_group(a, grp);
  if (!st) st = autobal_archive_attr_string(a, grp, "description",
                                            "the dimensionless parameters of each point, converted from the physical set "
                                            "with the axis keys set (the group's attributes of /pendulum are the configuration's)");
  for (c = 0; c < (every ? 4 : 6) && !st; c++)
    st = autobal_archive_var(a, grp, names[c], rank, pd, buf + (size_t)c * n, units[c], what[c]);
  free(buf);
  return st;
}

int autobal_study_pendulum_map_write(autobal_archive *a, const autobal_pendulum_params *p,
                                     const autobal_pendulum_physical *phys,
                                     const autobal_study_pendulum_map_summary *s) {
  const char *g = "/pendulum/map";
  const char *dims[2];
  char name[48];
  int st, every, p1, p2, damped;
  size_t nr;
  if (!a || !p || !s || !s->R_m) return AUTOBAL_EINVAL;
  /* a summary of an earlier version (zeroed new fields) has the default axes */
  p1 = s->param1, p2 = s->param2;
  if (p1 == p2) p1 = AUTOBAL_PENDULUM_PARAM_R_M, p2 = AUTOBAL_PENDULUM_PARAM_R_W;
  if (!autobal_pendulum_param_name(p1) || !autobal_pendulum_param_name(p2)) return AUTOBAL_EINVAL;
  dims[0] = autobal_pendulum_param_dim(p1);
  dims[1] = autobal_pendulum_param_dim(p2);
  every = s->every_unbalance;
  nr = s->n_Rm_done > 0 && s->n_Rm_done < s->n_Rm ? s->n_Rm_done : s->n_Rm; /* 0: a summary built by hand */
  damped = damped_everywhere(p, p1, p2, s->R_m[0], s->R_w[0]);
  st = autobal_study_write_pendulum_params(a, p, phys);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "criterion", criterion_text(s->undamped, damped, s->paper_convention));
  if (!st) st = autobal_archive_attr_string(a, g, "convention", s->paper_convention ? "paper" : "exact");
  if (!st) st = autobal_archive_attr_int(a, g, "every_unbalance", every);
  if (!st) st = autobal_archive_attr_double_array(a, g, "k_values", s->n_k, s->k, "1");
  if (!st) st = write_axis_attrs(a, g, 1, p1, s->log1);
  if (!st) st = write_axis_attrs(a, g, 2, p2, s->log2);
  if (!st && *ratio_rule(p1, p2)) st = autobal_archive_attr_string(a, g, "ratio_rule", ratio_rule(p1, p2));
  if (!st && s->undamped) st = autobal_archive_attr_string(a, g, "note", autobal_study_pendulum_undamped_note());
  if (!st && nr < s->n_Rm) {
    char what[200];
    snprintf(what, sizeof what, "interrupted: the first %zu of %zu rows (%s values; done, requested)", nr, s->n_Rm,
             dims[0]);
    st = autobal_archive_attr_int(a, g, "partial", 1);
    if (!st) st = autobal_archive_attr_int(a, g, "done", (long)nr);
    if (!st) st = autobal_archive_attr_int(a, g, "requested", (long)s->n_Rm);
    if (!st) st = autobal_archive_attr_string(a, g, "partial_what", what);
  }
  if (!st) st = autobal_archive_coord(a, g, dims[0], nr, s->R_m, autobal_pendulum_param_unit(p1),
                                      autobal_pendulum_param_description(p1));
  if (!st) st = autobal_archive_coord(a, g, dims[1], s->n_Rw, s->R_w, autobal_pendulum_param_unit(p2),
                                      autobal_pendulum_param_description(p2));
  /* the design point of the configuration ([pendulum]), for marking on the map */
  snprintf(name, sizeof name, "design_%s", dims[0]);
  if (!st) st = autobal_archive_attr_double(a, g, name, param_value(p, phys, p1), autobal_pendulum_param_unit(p1));
  snprintf(name, sizeof name, "design_%s", dims[1]);
  if (!st) st = autobal_archive_attr_double(a, g, name, param_value(p, phys, p2), autobal_pendulum_param_unit(p2));
  if (!st && phys && p2 == AUTOBAL_PENDULUM_PARAM_R_W) st = write_omega(a, g, dims[1], s->R_w, s->n_Rw, phys);
  else if (!st && phys && p1 == AUTOBAL_PENDULUM_PARAM_R_W) st = write_omega(a, g, dims[0], s->R_m, nr, phys);
  if (!st) st = autobal_archive_var_int(a, g, "verdict", 2, dims, s->verdict, "1", every ? "stability of the main motion for every k in k_values: 1 stable, 0 marginal, -1 unstable" : "stability of the main motion (4): 1 stable, 0 marginal, -1 unstable");
  if (!st && s->max_real) st = autobal_archive_var(a, g, "max_real", 2, dims, s->max_real, "1", "largest real part of the roots of (6) (over k_values)");
  if (!st) st = write_point_params(a, g, 2, dims, s->R_m, nr, p1, s->R_w, s->n_Rw, p2, p, phys, every);
  return st;
}

/* ---- sweep ---------------------------------------------------------------------------- */

autobal_study_pendulum_sweep_options autobal_study_pendulum_sweep_options_default(void) {
  autobal_study_pendulum_sweep_options o;
  memset(&o, 0, sizeof o);
  o.param = AUTOBAL_PENDULUM_PARAM_R_W;
  o.min = o.max = NAN;
  o.n = 1000;
  o.log_scale = -1;
  o.n_k = 65;
  o.xtol_rel = 1e-10;
  return o;
}

void autobal_study_pendulum_sweep_summary_free(autobal_study_pendulum_sweep_summary *s) {
  if (!s) return;
  free(s->values);
  free(s->k);
  free(s->verdict);
  s->values = s->k = NULL;
  s->verdict = NULL;
}

int autobal_study_pendulum_sweep(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys,
                                 const autobal_study_pendulum_sweep_options *opt, autobal_archive *a,
                                 autobal_study_pendulum_sweep_summary *summary, autobal_error *err) {
  autobal_study_pendulum_sweep_options def = autobal_study_pendulum_sweep_options_default();
  const autobal_study_pendulum_sweep_options *o = opt ? opt : &def;
  autobal_study_pendulum_sweep_summary *s = summary;
  autobal_pendulum_grid_spec spec;
  signed char *v = NULL;
  double mn, mx;
  size_t i, n, chunk = 256;
  int st, lg;
  autobal_error_clear(err);
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(s, 0, sizeof *s);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  if (o->n < 2 || o->n > 10000000)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n = %zu is out of range: allowed [2, 1e7]", o->n);
  if ((st = resolve_axis(0, o->param, phys, o->min, o->max, o->n, o->log_scale, NAN, NAN, 0, 0, &mn, &mx, &n, &lg, err)))
    return st;
  if (o->every_unbalance && (o->n_k < 2 || o->n_k > 100000))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_k = %zu is out of range: allowed [2, 100000]", o->n_k);
  if (!(o->xtol_rel > 0 && o->xtol_rel < 0.1))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: xtol_rel = %g is out of range: allowed (0, 0.1)", o->xtol_rel);
  s->param = o->param, s->log_scale = lg, s->min = mn, s->max = mx, s->n = n, s->xtol_rel = o->xtol_rel;
  s->every_unbalance = o->every_unbalance != 0;
  s->paper_convention = o->paper_convention != 0;
  s->undamped = all_undamped(p, o->param, -1);
  s->n_k = o->every_unbalance ? o->n_k : 1;
  s->values = malloc(n * sizeof *s->values);
  s->k = malloc(s->n_k * sizeof *s->k);
  s->verdict = malloc(n * sizeof *s->verdict);
  v = malloc(n);
  if (!s->values || !s->k || !s->verdict || !v) {
    free(v);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  fill_axis(s->values, n, mn, mx, lg);
  grid_spec_init(&spec, p, phys, o->every_unbalance, s->k, s->n_k, s->paper_convention, o->param, s->values, n);
  spec.param2 = -1;
  if ((st = autobal_pendulum_grid_check(&spec, err)) != 0) {
    free(v);
    return st;
  }
  while (s->n_done < n && !s->cancelled) {
    size_t r = n - s->n_done < chunk ? n - s->n_done : chunk;
    spec.v1 = s->values + s->n_done;
    spec.n1 = r;
    if ((st = autobal_pendulum_grid(&spec, v + s->n_done, NULL, err)) != 0) {
      free(v);
      return st;
    }
    s->n_done += r;
    if (o->progress && o->progress(0.5 * (double)s->n_done / (double)n, o->progress_user)) s->cancelled = 1;
  }
  for (i = 0; i < s->n_done; i++) {
    s->verdict[i] = v[i];
    s->n_stable += v[i] > 0;
  }
  free(v);
  spec.v1 = s->values, spec.n1 = n;
  for (i = 0; i + 1 < s->n_done && !s->cancelled; i++) {
    double x;
    int vl, vh;
    if (s->verdict[i] == s->verdict[i + 1]) continue;
    if (s->n_crit == AUTOBAL_STUDY_PENDULUM_MAX_CRIT) {
      s->crit_truncated = 1;
      break;
    }
    if ((st = autobal_pendulum_grid_critical(&spec, s->values[i], s->values[i + 1], lg, o->xtol_rel, &x, &vl, &vh, err)))
      return st;
    (void)vl, (void)vh; /* the ends of the final bracket may be MARGINAL (within the rounding
                          bounds of the sign test): the kinds are the grid neighbours' verdicts */
    s->crit[s->n_crit] = x;
    s->crit_below[s->n_crit] = s->verdict[i];
    s->crit_above[s->n_crit] = s->verdict[i + 1];
    s->n_crit++;
    if (o->progress && o->progress(0.5 + 0.5 * (double)(i + 1) / (double)n, o->progress_user)) s->cancelled = 1;
  }
  if (s->cancelled) s->n_crit = 0, s->crit_truncated = 0;
  if (a && (st = autobal_study_pendulum_sweep_write(a, p, phys, s)))
    return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
  if (s->cancelled)
    return autobal_error_set(err, AUTOBAL_ECANCELLED, "cancelled by the progress callback after %zu of %zu points",
                             s->n_done, n);
  return AUTOBAL_SUCCESS;
}

int autobal_study_pendulum_sweep_write(autobal_archive *a, const autobal_pendulum_params *p,
                                       const autobal_pendulum_physical *phys,
                                       const autobal_study_pendulum_sweep_summary *s) {
  const char *g = "/pendulum/sweep", *dim;
  const char *dims[1], *cdims[1];
  int st, damped;
  size_t nd;
  if (!a || !p || !s || !s->values || !autobal_pendulum_param_name(s->param)) return AUTOBAL_EINVAL;
  dim = autobal_pendulum_param_dim(s->param);
  dims[0] = dim;
  nd = s->n_done;
  damped = damped_everywhere(p, s->param, -1, s->values[0], 0.0);
  st = autobal_study_write_pendulum_params(a, p, phys);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "criterion", criterion_text(s->undamped, damped, s->paper_convention));
  if (!st) st = autobal_archive_attr_string(a, g, "convention", s->paper_convention ? "paper" : "exact");
  if (!st) st = autobal_archive_attr_int(a, g, "every_unbalance", s->every_unbalance);
  if (!st) st = autobal_archive_attr_double_array(a, g, "k_values", s->n_k, s->k, "1");
  if (!st) st = write_axis_attrs(a, g, 1, s->param, s->log_scale);
  if (!st && *ratio_rule(s->param, -1)) st = autobal_archive_attr_string(a, g, "ratio_rule", ratio_rule(s->param, -1));
  if (!st) st = autobal_archive_attr_double(a, g, "xtol_rel", s->xtol_rel, "1");
  if (!st && s->undamped) st = autobal_archive_attr_string(a, g, "note", autobal_study_pendulum_undamped_note());
  if (!st && nd < s->n) {
    char what[200];
    snprintf(what, sizeof what, "interrupted: the first %zu of %zu points (%s values; done, requested); no critical values",
             nd, s->n, dim);
    st = autobal_archive_attr_int(a, g, "partial", 1);
    if (!st) st = autobal_archive_attr_int(a, g, "done", (long)nd);
    if (!st) st = autobal_archive_attr_int(a, g, "requested", (long)s->n);
    if (!st) st = autobal_archive_attr_string(a, g, "partial_what", what);
  }
  if (!st) st = autobal_archive_coord(a, g, dim, nd, s->values, autobal_pendulum_param_unit(s->param),
                                      autobal_pendulum_param_description(s->param));
  if (!st && phys && s->param == AUTOBAL_PENDULUM_PARAM_R_W) st = write_omega(a, g, dim, s->values, nd, phys);
  if (!st) st = autobal_archive_var_int(a, g, "verdict", 1, dims, s->verdict, "1",
                                        s->every_unbalance ? "stability of the main motion for every k in k_values: 1 stable, 0 marginal, -1 unstable"
                                                           : "stability of the main motion (4): 1 stable, 0 marginal, -1 unstable");
  if (!st && !s->cancelled) {
    cdims[0] = "critical";
    st = autobal_archive_coord(a, g, "critical", s->n_crit, s->crit, autobal_pendulum_param_unit(s->param),
                               "where the verdict changes (refined by bisection)");
    if (!st) st = autobal_archive_var_int(a, g, "critical_below", 1, cdims, s->crit_below, "1", "verdict just below the critical value");
    if (!st) st = autobal_archive_var_int(a, g, "critical_above", 1, cdims, s->crit_above, "1", "verdict just above the critical value");
    if (!st) st = autobal_archive_attr_int(a, g, "critical_truncated", s->crit_truncated);
  }
  if (!st) st = write_point_params(a, g, 1, dims, s->values, nd, s->param, NULL, 0, -1, p, phys, s->every_unbalance);
  return st;
}
