/* rotor_design.c: `autobal rotor design`: sizing a balancer of n identical balls (two by default) in one plane for a
 * machine, a speed range and a range of unbalances, with a required margin (include/autobal/design.h,
 * docs/rotor.md "Design").  The exact test per design and speed is autobal_rotor_stab_margin_ratio_set;
 * the re-check is autobal_rotor_stab_every_unbalance_speeds (an independent path: Delta's critical
 * unbalances without the margin shift, verdicts by the same POLY margin); for n >= 3 balls both run over
 * the symmetric fan, and with unbalance_member = EVERY the re-checked designs are then certified for every
 * member (certify_members: the every-member analysis and autobal_rotor_stab_margin_u_range at every
 * re-check speed, and the certified margin over every member by bisection); the optimizer is GSL's
 * Nelder-Mead simplex (nmsimplex2): the robust margin is a minimum over speeds and unbalances,
 * continuous but with kinks where the worst point moves, and has no gradient. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/attractor.h"
#include "autobal/design.h"
#include "autobal/ensemble.h"
#include "autobal/rotor_stability.h"
#include "autobal/study.h"
#include "internal.h"
#include "analysis/rotor_closed.h"
#include "studies/rotor_design2.h"

#ifdef AUTOBAL_HAVE_OPENMP
#include <omp.h>
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A run-up profile (RAMP or TABLE drive): the transients run it; its top speed is the end of the
 * operating speed range; its end time t_b (a table's last time). */
static int has_profile(const autobal_rotor_params *p) {
  return p->drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP || p->drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE;
}
static double profile_top(const autobal_rotor_params *p) {
  const autobal_rotor_drive *d = &p->drive;
  double m = 0.0;
  size_t k;
  if (d->mode == AUTOBAL_ROTOR_DRIVE_RAMP) return fmax(fabs(d->omega_a), fabs(d->omega_b));
  for (k = 0; k < d->n_points; k++) m = fmax(m, fabs(d->table_omega[k]));
  return m;
}
static double profile_end(const autobal_rotor_params *p) {
  const autobal_rotor_drive *d = &p->drive;
  if (d->mode == AUTOBAL_ROTOR_DRIVE_RAMP) return d->t_b;
  return d->n_points ? d->table_t[d->n_points - 1] : 0.0;
}

autobal_study_rotor_design_options autobal_study_rotor_design_options_default(void) {
  autobal_study_rotor_design_options o;
  memset(&o, 0, sizeof o);
  o.omega_min = o.omega_max = NAN;
  o.n_omega = 101;
  o.n_verify = 0;
  o.unbalance_min = o.unbalance_max = NAN;
  o.margin = 0.1;
  o.mass_min = o.mass_max = NAN;
  o.n_mass = 8;
  o.radius_min = o.radius_max = NAN;
  o.n_radius = 24;
  o.damping_min = o.damping_max = NAN;
  o.n_damping = 8;
  o.position_min = o.position_max = NAN;
  o.n_position = 1;
  o.n_best = 10;
  o.n_starts = 3;
  o.max_iter = 80;
  o.n_transient = 0;
  o.rank_by = AUTOBAL_DESIGN_RANK_MARGIN;
  o.n_start = 3;
  o.n_transient_unbalances = 2;
  o.n_transient_speeds = 2;
  o.t_end = NAN;
  o.balance_tol = 0.01;
  o.balance_revs = 50.0;
  o.threads = 0;
  o.n_balls_min = o.n_balls_max = 2;
  o.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_EVERY;
  o.total_mass_max = NAN;
  o.planes = 1;
  o.unbalance2_min = o.unbalance2_max = NAN;
  o.n_unbalance2 = 5;
  o.unbalance2_boxes = 0;
  return o;
}

void autobal_study_rotor_design_summary_free(autobal_study_rotor_design_summary *s) {
  if (!s) return;
  free(s->mass);
  free(s->damping);
  free(s->position);
  free(s->radius);
  free(s->feasible);
  free(s->window_lo);
  free(s->window_hi);
  free(s->designs);
  free(s->best_config);
  free(s->n_balls);
  free(s->margin_map);
  memset(s, 0, sizeof *s);
}

/* ---- the search context ------------------------------------------------------------ */

typedef struct dctx {
  const autobal_rotor_params *base;
  autobal_study_rotor_design_options o; /* NaN bounds resolved */
  double *omega;                        /* n_omega speeds of the grid */
  autobal_rotor_params work;
  double bm[AUTOBAL_DESIGN_MAX_BALLS], br[AUTOBAL_DESIGN_MAX_BALLS], bh[AUTOBAL_DESIGN_MAX_BALLS];
  double bpsi[AUTOBAL_DESIGN_MAX_BALLS], brate[AUTOBAL_DESIGN_MAX_BALLS];
  autobal_rotor_stab *s;
  double s_d;  /* the handle's plane position */
  size_t s_n;  /* the handle's number of balls */
  autobal_error *err;
  double fraction;
  size_t ratio_sets, evaluations, nm_evals;
  int nm_status; /* a failure inside the optimizer's objective */
  int *stop;     /* a worker's copy (OpenMP): set when the search stops; NULL in the caller's */
} dctx;

static int read_flag(const int *f) {
  int v;
#ifdef AUTOBAL_HAVE_OPENMP
#pragma omp atomic read
#endif
  v = *f;
  return v;
}

static int cancel_hook(void *user) {
  dctx *c = (dctx *)user;
  if (c->stop) return read_flag(c->stop);
  return c->o.progress && c->o.progress(c->fraction, c->o.progress_user) != 0;
}

/* The number of balls of a design (0 read as 2). */
static size_t nballs(const autobal_rotor_design *d) { return d->n_balls ? d->n_balls : 2; }

/* The handle (allocated once per number of balls) with n balls and its plane at position d (the key
 * plane1.d). */
static int handle_at(dctx *c, size_t n, double d) {
  int st;
  if (c->s && c->s_n != n) {
    autobal_rotor_stab_free(c->s);
    c->s = NULL;
  }
  if (c->s && c->s_d == d) return AUTOBAL_SUCCESS;
  c->work.plane[0].d = d;
  if (!c->s) {
    autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
    /* the search's exact test runs over the symmetric fan (n >= 3); every member is the certification's */
    so.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
    c->work.plane[0].n_balls = n;
    c->s_n = n;
    c->s = autobal_rotor_stab_alloc(&c->work, &so, c->err);
    if (!c->s) return c->err ? c->err->status : AUTOBAL_EINVAL;
    autobal_rotor_stab_set_cancel(c->s, cancel_hook, c);
  } else if ((st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_D), d)) !=
             AUTOBAL_SUCCESS) {
    return autobal_error_set(c->err, st, "%s", autobal_rotor_stab_errmsg(c->s));
  }
  c->s_d = d;
  return AUTOBAL_SUCCESS;
}

static int fail_handle(dctx *c, int st) {
  return autobal_error_set(c->err, st, "%s", autobal_rotor_stab_errmsg(c->s));
}

/* The handle at design (n, m, h, d). */
static int set_design(dctx *c, size_t n, double m, double h, double d) {
  int st;
  if ((st = handle_at(c, n, d)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_BALL_MASS, m)) != AUTOBAL_SUCCESS) return fail_handle(c, st);
  if ((st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, h)) != AUTOBAL_SUCCESS)
    return fail_handle(c, st);
  return AUTOBAL_SUCCESS;
}

static int ratio_set_at(dctx *c, size_t k, double delta, autobal_rotor_ratio_set *rs) {
  int st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_OMEGA, c->omega[k]);
  if (st == AUTOBAL_SUCCESS) st = autobal_rotor_stab_margin_ratio_set(c->s, delta, rs);
  c->ratio_sets++;
  c->evaluations += rs->evaluations;
  return st != AUTOBAL_SUCCESS ? fail_handle(c, st) : st;
}

/* Interval lists (open, ascending): a := a intersect b. */
typedef struct ivals {
  size_t n;
  double lo[AUTOBAL_ROTOR_MAX_UCRIT + 1], hi[AUTOBAL_ROTOR_MAX_UCRIT + 1];
} ivals;

static void intersect(ivals *a, const autobal_rotor_ratio_set *b) {
  ivals r;
  size_t i, j;
  r.n = 0;
  for (i = 0; i < a->n; i++)
    for (j = 0; j < b->n; j++) {
      const double lo = fmax(a->lo[i], b->lo[j]), hi = fmin(a->hi[i], b->hi[j]);
      if (lo < hi && r.n < AUTOBAL_ROTOR_MAX_UCRIT + 1) {
        r.lo[r.n] = lo;
        r.hi[r.n] = hi;
        r.n++;
      }
    }
  *a = r;
}

/* The open radius windows of a t-set for ball mass m within [rmin, rmax]: r with
 * (s_lo / (m r), s_hi / (m r)) inside some (a, b), i.e. s_hi / (m b) < r < s_lo / (m a).  The widest
 * into *wlo, *whi (NaN if none); returns the count. */
static size_t radius_windows(const dctx *c, const ivals *T, double m, double *wlo, double *whi) {
  size_t i, n = 0;
  double best = -1.0;
  *wlo = *whi = NAN;
  for (i = 0; i < T->n; i++) {
    const double rl = c->o.unbalance_max / (m * T->hi[i]);
    const double rh = T->lo[i] > 0.0 ? c->o.unbalance_min / (m * T->lo[i]) : INFINITY;
    const double lo = fmax(rl, c->o.radius_min), hi = fmin(rh, c->o.radius_max);
    /* open in r; a fixed radius (min == max) must lie strictly inside */
    const int ok = c->o.radius_min == c->o.radius_max ? (rl < c->o.radius_min && c->o.radius_min < rh) : lo < hi;
    if (!ok) continue;
    n++;
    if (log(hi / lo) > best || (c->o.radius_min == c->o.radius_max && best < 0.0)) {
      best = c->o.radius_min == c->o.radius_max ? 0.0 : log(hi / lo);
      *wlo = lo;
      *whi = hi;
    }
  }
  return n;
}

/* The exact t-set with the required margin at every speed of the grid for (m, h, d); stops early
 * once no radius within the bounds can work. */
static int cell_set(dctx *c, size_t n, double m, double h, double d, ivals *T) {
  autobal_rotor_ratio_set rs;
  size_t k;
  int st;
  double wl, wh;
  if ((st = set_design(c, n, m, h, d)) != AUTOBAL_SUCCESS) return st;
  T->n = 1;
  T->lo[0] = 0.0;
  T->hi[0] = (double)n;
  /* n >= 3: the n - 2 ball modes -h/m of the full system must decay fast enough too */
  if (n >= 3 && !(h / m > c->o.margin)) {
    T->n = 0;
    return AUTOBAL_SUCCESS;
  }
  for (k = 0; k < c->o.n_omega; k++) {
    if ((st = ratio_set_at(c, k, c->o.margin, &rs)) != AUTOBAL_SUCCESS) return st;
    intersect(T, &rs);
    if (radius_windows(c, T, m, &wl, &wh) == 0) {
      T->n = 0;
      break;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* [t_lo, t_hi] inside one open interval of rs. */
static int covers(const autobal_rotor_ratio_set *rs, double t_lo, double t_hi) {
  size_t i;
  for (i = 0; i < rs->n; i++)
    if (rs->lo[i] < t_lo && t_hi < rs->hi[i]) return 1;
  return 0;
}

/* The robust margin rho of a design (see design.h): a value at which the exact test passes at every
 * speed, within about 1e-3 (1 + |rho|) of the largest such value. */
static int robust_margin(dctx *c, const autobal_rotor_design *dsg, double *rho) {
  const double t_lo = c->o.unbalance_min / (dsg->mass * dsg->radius);
  const double t_hi = c->o.unbalance_max / (dsg->mass * dsg->radius);
  const double r0 = c->work.plane[0].r0;
  const size_t nb = nballs(dsg);
  autobal_rotor_ratio_set rs;
  double U = INFINITY, eps;
  size_t k;
  int st;
  *rho = -INFINITY;
  if (!(t_hi < (double)nb)) return AUTOBAL_SUCCESS;
  if ((st = set_design(c, nb, dsg->mass, dsg->damping, dsg->position)) != AUTOBAL_SUCCESS) return st;
  /* an upper bound: the margins at the two ends of the range, every speed */
  for (k = 0; k < c->o.n_omega; k++) {
    double mg[2];
    int v, q;
    if ((st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_OMEGA, c->omega[k])) != AUTOBAL_SUCCESS)
      return fail_handle(c, st);
    for (q = 0; q < 2; q++) {
      /* the handle's balls keep the base radius c->br: the same t needs m0 = t m br / r0 */
      const double t = q == 0 ? t_lo : t_hi;
      if ((st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, t * dsg->mass * c->br[0] / r0)) !=
          AUTOBAL_SUCCESS)
        return fail_handle(c, st);
      st = autobal_rotor_stab_margin(c->s, AUTOBAL_ROTOR_STAB_POLY, &mg[q], &v);
      c->evaluations++;
      /* balls (almost) on one line at an end of the range: no sample there (U is only a start) */
      if (st == AUTOBAL_EUNSUPPORTED || v == AUTOBAL_ROTOR_VERDICT_NONE) mg[q] = -INFINITY;
      else if (st != AUTOBAL_SUCCESS) return fail_handle(c, st);
    }
    U = fmin(U, -fmax(mg[0], mg[1]));
  }
  if (!isfinite(U)) U = 1e3; /* no sample: start high, the exact test bisects down */
  eps = 1e-3 * (1.0 + fabs(U));
  U -= eps;
  /* the exact test at U at every speed; where it fails, bisect that speed down */
  for (k = 0; k < c->o.n_omega; k++) {
    double hi, lo, step;
    if ((st = ratio_set_at(c, k, U, &rs)) != AUTOBAL_SUCCESS) return st;
    if (covers(&rs, t_lo, t_hi)) continue;
    hi = U;
    step = eps + 0.1 * fabs(U);
    for (;;) {
      lo = hi - step;
      if (lo < -1e6) return AUTOBAL_SUCCESS; /* -inf: unstable far beyond any use */
      if ((st = ratio_set_at(c, k, lo, &rs)) != AUTOBAL_SUCCESS) return st;
      if (covers(&rs, t_lo, t_hi)) break;
      hi = lo;
      step *= 2.0;
    }
    while (hi - lo > eps) {
      const double mid = 0.5 * (lo + hi);
      if ((st = ratio_set_at(c, k, mid, &rs)) != AUTOBAL_SUCCESS) return st;
      if (covers(&rs, t_lo, t_hi)) lo = mid;
      else hi = mid;
    }
    U = lo;
  }
  /* n >= 3: the ball modes -h/m (not roots of Delta) */
  *rho = nb >= 3 ? fmin(U, dsg->damping / dsg->mass) : U;
  return AUTOBAL_SUCCESS;
}

/* ---- the optimizer: the box mapped onto R^n by v = lo (hi/lo)^((1 + sin x) / 2) (geometric) or
 * lo + (hi - lo) (1 + sin x) / 2 (linear, the position) ---------------------------------------- */

typedef struct nmvar {
  int which; /* 0 mass, 1 radius, 2 damping, 3 position */
  double lo, hi;
  int geometric;
} nmvar;

typedef struct nmctx {
  dctx *c;
  nmvar var[4];
  size_t n;
  autobal_rotor_design base;
} nmctx;

static double from_x(const nmvar *v, double x) {
  const double f = 0.5 * (1.0 + sin(x));
  return v->geometric ? v->lo * pow(v->hi / v->lo, f) : v->lo + (v->hi - v->lo) * f;
}
static double to_x(const nmvar *v, double val) {
  double f = v->geometric ? log(val / v->lo) / log(v->hi / v->lo) : (val - v->lo) / (v->hi - v->lo);
  f = fmin(1.0, fmax(0.0, f));
  return asin(2.0 * f - 1.0);
}
static void design_of(const nmctx *n, const gsl_vector *x, autobal_rotor_design *d) {
  size_t i;
  *d = n->base;
  for (i = 0; i < n->n; i++) {
    const double v = from_x(&n->var[i], gsl_vector_get(x, i));
    switch (n->var[i].which) {
      case 0: d->mass = v; break;
      case 1: d->radius = v; break;
      case 2: d->damping = v; break;
      default: d->position = v; break;
    }
  }
}

static double nm_objective(const gsl_vector *x, void *user) {
  nmctx *n = (nmctx *)user;
  autobal_rotor_design d;
  double rho;
  int st;
  if (n->c->nm_status != AUTOBAL_SUCCESS) return 1e6;
  design_of(n, x, &d);
  n->c->nm_evals++;
  st = robust_margin(n->c, &d, &rho);
  if (st != AUTOBAL_SUCCESS) {
    n->c->nm_status = st;
    return 1e6;
  }
  if (!isfinite(rho)) { /* cannot balance the range: a slope towards larger m r */
    return 1e5 + 1e3 * (n->c->o.unbalance_max / ((double)nballs(&d) * d.mass * d.radius));
  }
  return -rho;
}

/* Polish a design with the simplex; *out the best found (its rho evaluated). */
static int polish(dctx *c, const autobal_rotor_design *start, autobal_rotor_design *out) {
  nmctx n;
  gsl_multimin_function f;
  gsl_multimin_fminimizer *mz;
  gsl_vector *x, *step;
  size_t i, it;
  int st = AUTOBAL_SUCCESS, gst;
  memset(&n, 0, sizeof n);
  n.c = c;
  n.base = *start;
  {
    const double lo[4] = {c->o.mass_min, c->o.radius_min, c->o.damping_min, c->o.position_min};
    double hi[4] = {c->o.mass_max, c->o.radius_max, c->o.damping_max, c->o.position_max};
    /* the cap on the total ball mass, per ball for this n */
    if (isfinite(c->o.total_mass_max)) hi[0] = fmax(lo[0], fmin(hi[0], c->o.total_mass_max / (double)nballs(start)));
    for (i = 0; i < 4; i++)
      if (lo[i] < hi[i]) {
        n.var[n.n].which = (int)i;
        n.var[n.n].lo = lo[i];
        n.var[n.n].hi = hi[i];
        n.var[n.n].geometric = i < 3;
        n.n++;
      }
  }
  *out = *start;
  if (n.n == 0) return AUTOBAL_SUCCESS;
  f.n = n.n;
  f.f = nm_objective;
  f.params = &n;
  if (autobal_design_nm_alloc_(n.n, &mz, &x, &step) != 0)
    return autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory (optimizer)");
  for (i = 0; i < n.n; i++) {
    const double v = n.var[i].which == 0 ? start->mass
                     : n.var[i].which == 1 ? start->radius
                     : n.var[i].which == 2 ? start->damping
                                           : start->position;
    gsl_vector_set(x, i, to_x(&n.var[i], v));
    gsl_vector_set(step, i, 0.25);
  }
  c->nm_status = AUTOBAL_SUCCESS;
  gst = gsl_multimin_fminimizer_set(mz, &f, x, step);
  for (it = 0; gst == GSL_SUCCESS && it < c->o.max_iter && c->nm_status == AUTOBAL_SUCCESS; it++) {
    if ((gst = gsl_multimin_fminimizer_iterate(mz)) != GSL_SUCCESS) break;
    if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(mz), 1e-3) == GSL_SUCCESS) break;
  }
  if (c->nm_status != AUTOBAL_SUCCESS) st = c->nm_status;
  else {
    design_of(&n, gsl_multimin_fminimizer_x(mz), out);
    out->source = 1;
    st = robust_margin(c, out, &out->margin);
  }
  gsl_multimin_fminimizer_free(mz);
  gsl_vector_free(x);
  gsl_vector_free(step);
  return st;
}

/* ---- the re-check ---------------------------------------------------------------------- */

/* The every-member fields of a design not (yet) certified. */
static void members_init(autobal_rotor_design *d) {
  d->members_certified = 0;
  d->member_speeds = d->member_undecided = 0;
  d->member_undecided_omega[0] = d->member_undecided_omega[1] = NAN;
  d->member_found_omega = d->member_found_u = d->member_found_margin = d->member_margin = NAN;
  d->member_u[0] = d->member_u[1] = NAN;
  d->member_boxes = 0;
  d->member_enclosure_complete = 0;
  d->member_margin_certified = NAN;
  d->member_margin_decided = 0;
  d->member_margin_steps = 0;
}

/* Does every u of the design's enclosure pass the margin test with delta at every re-check speed?  *pass 1
 * yes, 0 no (a failing u between the members found: a member with a root at Re lambda >= -delta), -1 a
 * failing u only in the enclosure's gap (not proven either way). */
static int members_pass(dctx *c, autobal_rotor_stab *s, const autobal_rotor_design *d, double delta,
                        const double inner[2], int *pass) {
  const size_t nv = c->o.n_verify;
  size_t k;
  int st;
  *pass = 1;
  for (k = 0; k < nv; k++) {
    const double w = c->o.omega_min + (c->o.omega_max - c->o.omega_min) * (double)k / (double)(nv - 1);
    autobal_rotor_margin_u_range mu;
    if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w)) != AUTOBAL_SUCCESS ||
        (st = autobal_rotor_stab_margin_u_range(s, delta, d->member_u[0], d->member_u[1], &mu)) != AUTOBAL_SUCCESS) {
      if (st == AUTOBAL_ECANCELLED || st == AUTOBAL_ENOMEM)
        return autobal_error_set(c->err, st, "design, every member: %s", autobal_rotor_stab_errmsg(s));
      *pass = -1;
      return AUTOBAL_SUCCESS;
    }
    c->evaluations += mu.evaluations;
    if (!mu.all_stable) {
      *pass = mu.u_found >= inner[0] && mu.u_found <= inner[1] ? 0 : -1;
      return AUTOBAL_SUCCESS;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* The certified margin over every member of a certified design: bisection in delta between the required
 * margin (proven) and min(h/m, the members' sampled margin) (no larger delta can hold) over the margin
 * test at every re-check speed, to about 1e-3 (1 + |delta|) 1/s.  A step that is not proven counts as
 * failing (member_margin_decided 0 when a step was undecided). */
static int member_margin_certified(dctx *c, autobal_rotor_stab *s, autobal_rotor_design *d) {
  double lo = c->o.margin, hi = d->damping / d->mass, inner[2];
  autobal_rotor_unbalance_range ur;
  int st, pass, it;
  if (isfinite(d->member_margin)) hi = fmin(hi, d->member_margin);
  d->member_margin_certified = lo;
  d->member_margin_decided = 1;
  /* the members found (the inner bounds): every speed's analysis has the same enclosure */
  if ((st = autobal_rotor_stab_every_unbalance(s, c->o.unbalance_min, c->o.unbalance_max, &ur)) != AUTOBAL_SUCCESS)
    return st == AUTOBAL_ECANCELLED || st == AUTOBAL_ENOMEM
               ? autobal_error_set(c->err, st, "design, every member: %s", autobal_rotor_stab_errmsg(s))
               : AUTOBAL_SUCCESS;
  inner[0] = ur.u_min_inner;
  inner[1] = ur.u_max_inner;
  for (it = 0; it < 60 && hi - lo > 1e-3 * (1.0 + fabs(lo)); it++) {
    const double mid = 0.5 * (lo + hi);
    if ((st = members_pass(c, s, d, mid, inner, &pass)) != AUTOBAL_SUCCESS) return st;
    d->member_margin_steps++;
    if (pass == 1) lo = mid;
    else {
      if (pass < 0) d->member_margin_decided = 0;
      hi = mid;
    }
  }
  d->member_margin_certified = lo;
  return AUTOBAL_SUCCESS;
}

/* The certification for every member (n >= 3, unbalance_member EVERY; design.h): at every speed of the
 * re-check grid the every-member analysis (delta = 0, the library's verdict at members built in every
 * sub-interval of u) and the u test with the required margin over its outer enclosure of u.  The first
 * violation stops it. */
static int certify_members(dctx *c, autobal_rotor_stab *s, autobal_rotor_design *d) {
  const size_t nv = c->o.n_verify;
  const double delta = c->o.margin;
  size_t k, j;
  double worst = -INFINITY;
  int st, undecided = 0;
  for (k = 0; k < nv; k++) {
    const double w = c->o.omega_min + (c->o.omega_max - c->o.omega_min) * (double)k / (double)(nv - 1);
    autobal_rotor_unbalance_range ur;
    autobal_rotor_margin_u_range mu;
    int viol = 0, und = 0;
    if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w)) != AUTOBAL_SUCCESS)
      return autobal_error_set(c->err, st, "design, every member: %s", autobal_rotor_stab_errmsg(s));
    st = autobal_rotor_stab_every_unbalance(s, c->o.unbalance_min, c->o.unbalance_max, &ur);
    if (st == AUTOBAL_ECANCELLED || st == AUTOBAL_ENOMEM)
      return autobal_error_set(c->err, st, "design, every member: %s", autobal_rotor_stab_errmsg(s));
    d->member_speeds++;
    if (st != AUTOBAL_SUCCESS) { /* the analysis could not decide here (e.g. no member built): undecided */
      und = 1;
    } else {
      c->evaluations += ur.evaluations;
      d->member_u[0] = ur.u_min;
      d->member_u[1] = ur.u_max;
      d->member_boxes = ur.n_balls >= 4 ? ur.u_boxes : 0;
      d->member_enclosure_complete = ur.u_complete;
      if (isfinite(ur.margin_worst)) worst = fmax(worst, ur.margin_worst);
      /* a sub-interval of u whose member is unstable, or (delta > 0) marginal with its margin >= -delta: a
         violation shown by an actual member; marginal with delta = 0 (a root within the test's tolerance
         of the axis, e.g. next to the members on a line): undecided */
      for (j = 0; j < ur.n_usub && !viol; j++)
        if (ur.usub_verdict[j] == AUTOBAL_VERDICT_UNSTABLE ||
            (ur.usub_verdict[j] == AUTOBAL_VERDICT_MARGINAL && delta > 0.0 && ur.usub_margin[j] >= -delta)) {
          viol = 1;
          d->member_found_u = 0.5 * (fmax(ur.usub_lo[j], ur.u_min_inner) + fmin(ur.usub_hi[j], ur.u_max_inner));
          d->member_found_margin = ur.usub_margin[j];
        } else if (ur.usub_verdict[j] == AUTOBAL_VERDICT_MARGINAL)
          und = 1;
      if (!viol && !und && !ur.all_stable) {
        /* no unstable sub-interval: a critical u inside with stable sides (a root on the axis there: not
           stable with any margin), or a sub-interval in the gap (undecided) */
        if (ur.n_uundecided > 0) und = 1;
        else {
          viol = 1;
          d->member_found_u = ur.n_ucrit > 0 ? ur.u_crit[0] : NAN;
          d->member_found_margin = ur.margin_worst;
        }
      }
      if (!viol && !und && delta > 0.0) { /* delta = 0: the analysis's verdict above is the certificate */
        st = autobal_rotor_stab_margin_u_range(s, delta, ur.u_min, ur.u_max, &mu);
        if (st == AUTOBAL_ECANCELLED || st == AUTOBAL_ENOMEM)
          return autobal_error_set(c->err, st, "design, every member: %s", autobal_rotor_stab_errmsg(s));
        c->evaluations += mu.evaluations;
        if (st != AUTOBAL_SUCCESS) und = 1;
        else if (!mu.all_stable) {
          /* members exist for every u between the inner bounds (connected: docs/rotor.md "Every unbalance") */
          if (mu.u_found >= ur.u_min_inner && mu.u_found <= ur.u_max_inner) {
            viol = 1;
            d->member_found_u = mu.u_found;
            d->member_found_margin = NAN;
          } else
            und = 1;
        }
      }
    }
    if (viol) {
      d->member_found_omega = w;
      d->members_certified = -1;
      d->member_margin = isfinite(worst) ? -worst : NAN;
      return AUTOBAL_SUCCESS;
    }
    if (und) {
      undecided = 1;
      if (d->member_undecided++ == 0) d->member_undecided_omega[0] = w;
      d->member_undecided_omega[1] = w;
    }
  }
  d->member_margin = isfinite(worst) ? -worst : NAN;
  if (!(d->damping / d->mass > delta)) { /* the ball modes -h/m (the re-check has it too) */
    d->members_certified = -1;
    d->member_found_u = NAN;
    return AUTOBAL_SUCCESS;
  }
  d->members_certified = undecided ? -2 : 1;
  if (d->members_certified == 1) return member_margin_certified(c, s, d);
  return AUTOBAL_SUCCESS;
}

static int recheck(dctx *c, autobal_rotor_design *d) {
  autobal_rotor_params q = *c->base;
  autobal_rotor_plane *pl = &q.plane[0];
  const size_t nb = nballs(d);
  double m[AUTOBAL_DESIGN_MAX_BALLS], r[AUTOBAL_DESIGN_MAX_BALLS], h[AUTOBAL_DESIGN_MAX_BALLS];
  double psi[AUTOBAL_DESIGN_MAX_BALLS], rate[AUTOBAL_DESIGN_MAX_BALLS];
  autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
  autobal_rotor_stab *s;
  autobal_rotor_crit cr;
  autobal_rotor_unbalance_range ur;
  size_t k, nv = c->o.n_verify;
  double worst = -INFINITY;
  int st, ok;
  members_init(d);
  memset(&q.drive, 0, sizeof q.drive); /* constant speeds */
  for (k = 0; k < nb; k++) {
    m[k] = d->mass;
    r[k] = d->radius;
    h[k] = d->damping;
    psi[k] = c->bpsi[k];
    rate[k] = c->brate[k];
  }
  pl->d = d->position;
  pl->n_balls = nb;
  pl->ball_mass = m;
  pl->ball_radius = r;
  pl->ball_damping = h;
  pl->ball_psi = psi;
  pl->ball_rate = rate;
  so.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC; /* the fan (n >= 3); every member: below */
  s = autobal_rotor_stab_alloc(&q, &so, c->err);
  if (!s) return c->err ? c->err->status : AUTOBAL_EINVAL;
  autobal_rotor_stab_set_cancel(s, cancel_hook, c);
  st = autobal_rotor_stab_every_unbalance_speeds(s, c->o.unbalance_min, c->o.unbalance_max, c->o.omega_min,
                                                 c->o.omega_max, nv, 1e-6, &cr);
  c->evaluations += cr.evaluations;
  if (st == AUTOBAL_EINVAL) { /* the balls cannot balance the range: not feasible */
    d->recheck = 0;
    d->recheck_margin = -INFINITY;
    d->feasible = 0;
    autobal_rotor_stab_free(s);
    return AUTOBAL_SUCCESS;
  }
  if (st != AUTOBAL_SUCCESS) {
    st = autobal_error_set(c->err, st, "design re-check: %s", autobal_rotor_stab_errmsg(s));
    autobal_rotor_stab_free(s);
    return st;
  }
  ok = cr.n == 0 && cr.n_stable == 1 && cr.stable_lo[0] == c->o.omega_min && cr.stable_hi[0] == c->o.omega_max;
  for (k = 0; k < nv; k++) {
    const double w = c->o.omega_min + (c->o.omega_max - c->o.omega_min) * (double)k / (double)(nv - 1);
    if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w)) != AUTOBAL_SUCCESS ||
        (st = autobal_rotor_stab_every_unbalance(s, c->o.unbalance_min, c->o.unbalance_max, &ur)) != AUTOBAL_SUCCESS) {
      st = autobal_error_set(c->err, st, "design re-check: %s", autobal_rotor_stab_errmsg(s));
      autobal_rotor_stab_free(s);
      return st;
    }
    c->evaluations += ur.evaluations;
    worst = fmax(worst, ur.margin_worst);
    if (!ur.all_stable) ok = 0;
  }
  autobal_rotor_stab_free(s);
  d->recheck_margin = -worst;
  if (nb >= 3) d->recheck_margin = fmin(d->recheck_margin, d->damping / d->mass); /* the ball modes -h/m */
  if (!(d->recheck_margin > c->o.margin)) ok = 0;
  d->recheck = ok;
  if (!ok) d->feasible = 0;
  if (ok && nb >= 3 && c->o.unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY) {
    /* every member: a handle with the member rule EVERY (its enclosure of u is kept across the speeds) */
    so = autobal_rotor_stab_options_default();
    so.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_EVERY;
    so.member_boxes = c->o.member_boxes;
    s = autobal_rotor_stab_alloc(&q, &so, c->err);
    if (!s) return c->err ? c->err->status : AUTOBAL_EINVAL;
    autobal_rotor_stab_set_cancel(s, cancel_hook, c);
    st = certify_members(c, s, d);
    autobal_rotor_stab_free(s);
    if (st != AUTOBAL_SUCCESS) return st;
    if (d->members_certified != 1) d->feasible = 0;
  }
  return AUTOBAL_SUCCESS;
}

/* ---- transients of a design (options.n_transient) -------------------------------------- */

static int ens_cancel(void *user) { return cancel_hook(user); }

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}


/* The common part of design_ensemble and design_ensemble2: the machine q with its balls set, at constant
 * speed w (ignored with a profile) as an ensemble member; es with parameters 0 and 1 (the start
 * angles) set; parameter 2 (plane 1's m0 over the unbalance range), the run settings, the run, and
 * each member's time to balance (+inf when it does not balance) appended to ttb. */
static int run_ensemble(dctx *c, autobal_rotor_params *q, double w, autobal_ensemble_settings *es, const char *what,
                        double *ttb, size_t *nt, size_t *nbal) {
  const autobal_study_rotor_design_options *o = &c->o;
  const double r0 = q->plane[0].r0;
  autobal_ensemble_member mem_, *mem = &mem_;
  autobal_ensemble *e;
  size_t k, ai, nm;
  int st;
  if (!has_profile(q)) {
    q->drive.mode = AUTOBAL_ROTOR_DRIVE_CONSTANT;
    q->omega = w;
  }
  if ((st = autobal_ensemble_rotor_member(q, AUTOBAL_ROTOR_FIXED, "fixed", mem, c->err)) != AUTOBAL_SUCCESS)
    return st;
  es->random = 0;
  es->endpoint = 1;
  es->n_params = 3;
  es->param[2].name = "m0";
  es->param[2].min = (o->n_transient_unbalances > 1 ? o->unbalance_min : o->unbalance_max) / r0;
  es->param[2].max = o->unbalance_max / r0;
  es->param[2].n = o->unbalance_min < o->unbalance_max ? o->n_transient_unbalances : 1;
  es->t_end = o->t_end;
  es->balance_tol = o->balance_tol;
  es->use_dwell = 0;
  es->balance_revs = o->balance_revs;
  es->stop_at_balance = 1;
  es->threads = o->threads;
  e = autobal_ensemble_alloc(mem, es, c->err);
  if (!e) {
    autobal_ensemble_member_release(mem);
    return c->err ? c->err->status : AUTOBAL_EINVAL;
  }
  autobal_ensemble_set_cancel(e, ens_cancel, c);
  st = autobal_ensemble_run(e);
  if (st != AUTOBAL_SUCCESS) {
    st = autobal_error_set(c->err, st, "%s: %s", what, autobal_ensemble_errmsg(e));
  } else {
    nm = autobal_ensemble_n_members(e);
    ai = autobal_ensemble_attractor_index(e);
    for (k = 0; k < nm; k++) {
      const double *sm = autobal_ensemble_summary(e, k);
      const int bal = sm && ai != (size_t)-1 && sm[AUTOBAL_ENSEMBLE_STATUS] >= 0.0 &&
                      (int)sm[ai] == AUTOBAL_ATTRACTOR_BALANCED;
      const double t = sm ? sm[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE] : NAN;
      ttb[(*nt)++] = bal && isfinite(t) ? t : INFINITY;
      *nbal += (size_t)bal;
    }
  }
  autobal_ensemble_free(e);
  autobal_ensemble_member_release(mem);
  return st;
}

/* One ensemble of design d at constant speed w (ignored with a profile); times appended to ttb. */
static int design_ensemble(dctx *c, const autobal_rotor_design *d, double w, double *ttb, size_t *nt,
                           size_t *nbal) {
  const autobal_study_rotor_design_options *o = &c->o;
  autobal_rotor_params q = *c->base;
  autobal_rotor_plane *pl = &q.plane[0];
  const size_t nb = nballs(d);
  double m[AUTOBAL_DESIGN_MAX_BALLS], r[AUTOBAL_DESIGN_MAX_BALLS], h[AUTOBAL_DESIGN_MAX_BALLS];
  double psi[AUTOBAL_DESIGN_MAX_BALLS], rate[AUTOBAL_DESIGN_MAX_BALLS];
  const double n = (double)o->n_start, step = 2.0 * M_PI / n;
  autobal_ensemble_settings es = autobal_ensemble_settings_default();
  size_t k;
  /* balls 1 and 2 on the grid below; balls 3..n at the fixed angles step (2i - 3) / (4 (n - 1)),
   * strictly between 0 and step / 2, so that no two balls start together */
  for (k = 0; k < nb; k++) {
    m[k] = d->mass;
    r[k] = d->radius;
    h[k] = d->damping;
    psi[k] = k < 2 ? 0.0 : step * (2.0 * (double)(k + 1) - 3.0) / (4.0 * ((double)nb - 1.0));
    rate[k] = 0.0;
  }
  pl->d = d->position;
  pl->n_balls = nb;
  pl->ball_mass = m;
  pl->ball_radius = r;
  pl->ball_damping = h;
  pl->ball_psi = psi;
  pl->ball_rate = rate;
  /* ball 1 at 0, step, ..., ball 2 half a step further on: no member starts with the balls together */
  es.param[0].name = "psi_1";
  es.param[0].min = 0.0;
  es.param[0].max = step * (n - 1.0);
  es.param[0].n = o->n_start;
  es.param[1].name = "psi_2";
  es.param[1].min = 0.5 * step;
  es.param[1].max = 0.5 * step + step * (n - 1.0);
  es.param[1].n = o->n_start;
  return run_ensemble(c, &q, w, &es, "design transients", ttb, nt, nbal);
}

/* Two planes (options.planes = 2): one ensemble of design d (the same balls m, r, h in both planes)
 * at constant speed w (ignored with a profile), plane 2's unbalance u2 (kg m) and plane 2's ball start
 * angles psi2[2], over plane 1's ball start angles (as one plane: ball 1 at 0, step, ..., ball 2 half
 * a step on) and plane 1's unbalances (the ensemble has at most three parameters: the caller loops
 * over plane 2's angles); times appended to ttb. */
static int design_ensemble2(dctx *c, const autobal_rotor_design *d, double w, double u2, const double psi2[2],
                            double *ttb, size_t *nt, size_t *nbal) {
  const autobal_study_rotor_design_options *o = &c->o;
  autobal_rotor_params q = *c->base;
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2];
  const double n = (double)o->n_start, step = 2.0 * M_PI / n;
  static const char *const pname[2] = {"psi_1", "psi_2"};
  autobal_ensemble_settings es = autobal_ensemble_settings_default();
  size_t k, j;
  for (j = 0; j < 2; j++) {
    for (k = 0; k < 2; k++) {
      m[j][k] = d->mass;
      r[j][k] = d->radius;
      h[j][k] = d->damping;
      psi[j][k] = j == 1 ? psi2[k] : 0.0;
      rate[j][k] = 0.0;
    }
    q.plane[j].n_balls = 2;
    q.plane[j].ball_mass = m[j];
    q.plane[j].ball_radius = r[j];
    q.plane[j].ball_damping = h[j];
    q.plane[j].ball_psi = psi[j];
    q.plane[j].ball_rate = rate[j];
  }
  q.plane[1].m0 = u2 / q.plane[1].r0;
  for (k = 0; k < 2; k++) {
    es.param[k].name = pname[k];
    es.param[k].min = 0.5 * (double)k * step;
    es.param[k].max = 0.5 * (double)k * step + step * (n - 1.0);
    es.param[k].n = o->n_start;
  }
  return run_ensemble(c, &q, w, &es, "design transients (two planes)", ttb, nt, nbal);
}

/* P(balance), median and worst time to balance of design d (see design.h). */
static int design_transients(dctx *c, autobal_rotor_design *d, size_t *runs) {
  const autobal_study_rotor_design_options *o = &c->o;
  const size_t nsp = has_profile(c->base) ? 1 : o->n_transient_speeds;
  const int two = o->planes == 2;
  const size_t nu2 = two ? (o->unbalance2_min < o->unbalance2_max ? o->n_transient_unbalances : 1) : 1;
  const size_t ns = two ? o->n_start * o->n_start : 1;
  const size_t per = o->n_start * o->n_start * o->n_transient_unbalances * ns * nu2;
  double *ttb = malloc(nsp * per * sizeof *ttb);
  size_t nt = 0, nbal = 0, k, l;
  int st = AUTOBAL_SUCCESS;
  if (!ttb) return autobal_error_set(c->err, AUTOBAL_ENOMEM, "design transients: out of memory");
  for (k = 0; k < nsp && st == AUTOBAL_SUCCESS; k++) {
    const double w = nsp > 1 ? o->omega_min + (o->omega_max - o->omega_min) * (double)k / (double)(nsp - 1)
                             : o->omega_max;
    if (!two) {
      st = design_ensemble(c, d, k == nsp - 1 ? o->omega_max : w, ttb, &nt, &nbal);
      continue;
    }
    /* plane 2's unbalances as plane 1's: linear from unbalance2_min to unbalance2_max (1: the max) */
    for (l = 0; l < nu2 && st == AUTOBAL_SUCCESS; l++) {
      const double u2 = nu2 > 1 ? (l == nu2 - 1 ? o->unbalance2_max
                                                : o->unbalance2_min + (o->unbalance2_max - o->unbalance2_min) *
                                                                          (double)l / (double)(nu2 - 1))
                                : o->unbalance2_max;
      /* plane 2's balls: a quarter and three quarters of a step on from plane 1's grid */
      const double step = 2.0 * M_PI / (double)o->n_start;
      size_t a3, a4;
      for (a3 = 0; a3 < o->n_start && st == AUTOBAL_SUCCESS; a3++)
        for (a4 = 0; a4 < o->n_start && st == AUTOBAL_SUCCESS; a4++) {
          const double psi2[2] = {step * (0.25 + (double)a3), step * (0.75 + (double)a4)};
          st = design_ensemble2(c, d, k == nsp - 1 ? o->omega_max : w, u2, psi2, ttb, &nt, &nbal);
        }
    }
  }
  if (st == AUTOBAL_SUCCESS && nt > 0) {
    qsort(ttb, nt, sizeof *ttb, cmp_double);
    d->n_runs = nt;
    d->n_balanced = nbal;
    d->p_balance = (double)nbal / (double)nt;
    d->ttb_worst = ttb[nt - 1];
    d->ttb_median = nt % 2 ? ttb[nt / 2] : 0.5 * (ttb[nt / 2 - 1] + ttb[nt / 2]);
    *runs += nt;
  }
  free(ttb);
  return st;
}

/* The order of options.rank_by among designs that ran transients (see design.h). */
static int cmp_key(double a, double b, int larger_first) {
  if (a == b) return 0;
  return (larger_first ? a > b : a < b) ? -1 : 1;
}
static int cmp_transient(const autobal_rotor_design *x, const autobal_rotor_design *y, int rank_by_key) {
  int r;
  if ((r = cmp_key(x->feasible, y->feasible, 1))) return r;
  if (rank_by_key == AUTOBAL_DESIGN_RANK_P_BALANCE) {
    if ((r = cmp_key(x->p_balance, y->p_balance, 1))) return r;
    if ((r = cmp_key(x->ttb_worst, y->ttb_worst, 0))) return r;
    if ((r = cmp_key(x->ttb_median, y->ttb_median, 0))) return r;
  } else {
    if ((r = cmp_key(x->ttb_worst, y->ttb_worst, 0))) return r;
    if ((r = cmp_key(x->ttb_median, y->ttb_median, 0))) return r;
    if ((r = cmp_key(x->p_balance, y->p_balance, 1))) return r;
  }
  return cmp_key(x->margin, y->margin, 1);
}

/* Stable insertion sort of the first n designs by cmp_transient. */
static void rank_transients(autobal_rotor_design *d, size_t n, int key) {
  size_t i, j;
  for (i = 1; i < n; i++) {
    autobal_rotor_design t = d[i];
    for (j = i; j > 0 && cmp_transient(&t, &d[j - 1], key) < 0; j--) d[j] = d[j - 1];
    d[j] = t;
  }
}

/* The ranked designs' last steps (one plane, isotropic or anisotropic supports): the transients of the
 * first n_transient, the ranking by rank_by among them. */
static int transients_and_rank(dctx *c, autobal_study_rotor_design_summary *S,
                               const autobal_study_rotor_design_options *o) {
  const size_t nk = o->n_transient < S->n_designs ? o->n_transient : S->n_designs;
  size_t i;
  int st = AUTOBAL_SUCCESS;
  for (i = 0; i < nk && st == AUTOBAL_SUCCESS; i++) {
    c->fraction = 0.95 + 0.05 * (double)i / (double)nk;
    st = design_transients(c, &S->designs[i], &S->transients);
  }
  if (st == AUTOBAL_SUCCESS && o->rank_by != AUTOBAL_DESIGN_RANK_MARGIN) rank_transients(S->designs, nk, o->rank_by);
  return st;
}

/* The ranking is done: the best design's config (the first ranked). */
static int ranked_best_config(dctx *c, autobal_study_rotor_design_summary *S,
                              const autobal_study_rotor_design_options *o) {
  S->ranked = 1;
  if (S->n_designs == 0) return AUTOBAL_SUCCESS;
  S->best_config = autobal_study_rotor_design_config(c->base, &S->designs[0], o->omega_max);
  return S->best_config ? AUTOBAL_SUCCESS : autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory");
}

/* Every member (n_balls_max >= 3, unbalance_member EVERY): the ranked designs are certified for every
 * member, and the margin a design's verdict covers is rho for two balls (one member) and the certified
 * margin over every member for three or more (rho is then the symmetric fan's only). */
static int every_members(const autobal_study_rotor_design_options *o) {
  return o->n_balls_max >= 3 && o->unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY;
}
static double covered_margin(const autobal_rotor_design *d) {
  if (nballs(d) >= 3) return d->members_certified == 1 ? fmin(d->margin, d->member_margin_certified) : -INFINITY;
  return d->margin;
}
/* Stable insertion sort: the feasible designs first, by the margin their verdict covers (larger first);
 * the others keep their order after them. */
static void rank_covered(autobal_rotor_design *d, size_t n) {
  size_t i, j;
  for (i = 1; i < n; i++) {
    autobal_rotor_design t = d[i];
    for (j = i; j > 0; j--) {
      const autobal_rotor_design *u = &d[j - 1];
      const int before = t.feasible && (!u->feasible || covered_margin(&t) > covered_margin(u));
      if (!before) break;
      d[j] = d[j - 1];
    }
    d[j] = t;
  }
}

/* ---- options --------------------------------------------------------------------------- */

/* The two-plane options (docs/rotor.md "Design", "Two planes"): the machine has two planes of two
 * balls, the same balancer is designed for both, no position variable, no transients. */
static int resolve2(const autobal_rotor_params *p, autobal_study_rotor_design_options *o, autobal_error *err) {
  size_t j;
  if (p->n_planes != 2)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[design] planes = 2 needs a two-plane machine: add a [plane2] section (d, m0, r0, psi0 "
                             "and two balls; e.g. data/rotor_two_planes.ini); allowed with one plane: planes = 1");
  for (j = 0; j < 2; j++)
    if (p->plane[j].n_balls != 2 || !(p->plane[j].r0 > 0.0))
      return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                               "[plane%zu] ball_mass: with [design] planes = 2 each plane needs two balls and r0 > 0 "
                               "(here %zu balls, r0 = %g m); the same two-ball balancer is designed for both planes",
                               j + 1, p->plane[j].n_balls, p->plane[j].r0);
  if (!((o->n_balls_min == 0 || o->n_balls_min == 2) && (o->n_balls_max == 0 || o->n_balls_max == 2)))
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[design] n_balls_min = %zu, n_balls_max = %zu: with planes = 2 two balls per plane only "
                             "(allowed 2, 2): the two-plane every-unbalance analysis is built for two balls per plane",
                             o->n_balls_min, o->n_balls_max);
  if (!((isnan(o->position_min) || o->position_min == p->plane[0].d) &&
        (isnan(o->position_max) || o->position_max == p->plane[0].d)))
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[design] position_min, position_max: with planes = 2 the plane positions are the "
                             "config's ([plane1] d = %g m, [plane2] d = %g m); leave them unset",
                             p->plane[0].d, p->plane[1].d);
  if (isnan(o->unbalance2_min) && isnan(o->unbalance2_max)) {
    o->unbalance2_min = o->unbalance_min;
    o->unbalance2_max = o->unbalance_max;
  }
  if (!(isfinite(o->unbalance2_min) && isfinite(o->unbalance2_max) && o->unbalance2_min > 0.0 &&
        o->unbalance2_min <= o->unbalance2_max))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: unbalance2_min = %g, unbalance2_max = %g kg m: need 0 < min <= max (finite; "
                             "both NaN: plane 1's range)",
                             o->unbalance2_min, o->unbalance2_max);
  if (o->n_unbalance2 == 0) o->n_unbalance2 = 5;
  if (!(o->n_unbalance2 >= 2 && o->n_unbalance2 <= 100))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_unbalance2 = %zu must be in [2, 100]", o->n_unbalance2);
  if (!(o->unbalance2_boxes >= -1 && o->unbalance2_boxes <= 1000000000L))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: unbalance2_boxes = %ld: allowed -1 (no certification), 0 (the default budget, "
                             "100000) or [1, 1e9]",
                             o->unbalance2_boxes);
  o->n_balls_min = o->n_balls_max = 2;
  o->n_position = 1;
  o->position_min = o->position_max = p->plane[0].d;
  return AUTOBAL_SUCCESS;
}

static int resolve(const autobal_rotor_params *p, const autobal_study_rotor_design_options *in,
                   autobal_study_rotor_design_options *o, autobal_error *err) {
  const autobal_rotor_plane *pl;
  *o = *in;
  if (o->planes == 0) o->planes = 1;
  if (o->planes != 1 && o->planes != 2)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: planes = %zu: allowed 1 or 2", o->planes);
  if (o->planes == 1 && p->n_planes != 1)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[plane2]: the design covers one balancer plane (here %zu): the guaranteed every-unbalance "
                             "verdict is built for one plane with two balls; for the two-plane machine set "
                             "[design] planes = 2",
                             p->n_planes);
  if (o->planes == 2) {
    int st = resolve2(p, o, err);
    if (st != AUTOBAL_SUCCESS) return st;
  }
  pl = &p->plane[0];
  if (pl->n_balls < 2 || pl->n_balls > AUTOBAL_DESIGN_MAX_BALLS)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[plane1] ball_mass: the design needs a plane with 2 to %d balls (here %zu): their first "
                             "ball gives the default bounds; the number of balls designed is [design] n_balls_min, "
                             "n_balls_max",
                             AUTOBAL_DESIGN_MAX_BALLS, pl->n_balls);
  if (o->n_balls_min == 0) o->n_balls_min = 2;
  if (o->n_balls_max == 0) o->n_balls_max = 2;
  if (!(o->n_balls_min >= 2 && o->n_balls_min <= o->n_balls_max && o->n_balls_max <= AUTOBAL_DESIGN_MAX_BALLS))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: n_balls_min = %zu, n_balls_max = %zu: need 2 <= n_balls_min <= n_balls_max <= %d",
                             o->n_balls_min, o->n_balls_max, AUTOBAL_DESIGN_MAX_BALLS);
  if (o->unbalance_member != AUTOBAL_ROTOR_UNBALANCE_EVERY && o->unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: unbalance_member = %d: allowed 0 (every), 1 (symmetric)",
                             o->unbalance_member);
  if (o->n_balls_max > 10 && o->unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[design] unbalance_member = every: with n_balls_max = %zu the certification for every "
                             "member covers 3 to 10 balls: set n_balls_max <= 10, or unbalance_member = symmetric "
                             "(the verdict then says 'symmetric members only')",
                             o->n_balls_max);
  if (!(o->hill_boxes == 0 || (o->hill_boxes >= 100 && o->hill_boxes <= 100000000L)))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: hill_boxes = %ld: allowed 0 (the default budget, 20000) or [100, 1e8]",
                             o->hill_boxes);
  if (!(o->member_boxes == 0 || (o->member_boxes >= 1000 && o->member_boxes <= 1000000000L)))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: member_boxes = %ld: allowed 0 (the default budget, 4000000) or [1000, 1e9]",
                             o->member_boxes);
  if (pl->n_balls < o->n_balls_min || pl->n_balls > o->n_balls_max)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[plane1] ball_mass: the config has %zu balls, outside the numbers of balls designed, "
                             "[design] n_balls_min = %zu .. n_balls_max = %zu (default 2 .. 2: two balls); widen them",
                             pl->n_balls, o->n_balls_min, o->n_balls_max);
  if (!(isnan(o->total_mass_max) || (isfinite(o->total_mass_max) && o->total_mass_max > 0.0)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: total_mass_max = %g kg must be > 0 (or NaN: no cap)",
                             o->total_mass_max);
  if (p->inertia != AUTOBAL_ROTOR_INERTIA_PAPER)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[rotor] inertia: the design needs inertia = paper (with full inertia the unbalance mass "
                             "enters the mass matrix)");
  if (!(pl->r0 > 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL, "[plane1] r0 = %g m must be > 0 (the unbalance is m0 r0)", pl->r0);
  if (p->drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT && !has_profile(p))
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[drive] mode: the design takes a prescribed run-up profile (mode = ramp or table), not a "
                             "motor (the ensemble of its transients has no motor)");
  if (isnan(o->t_end)) o->t_end = (has_profile(p) ? profile_end(p) : 0.0) + 10.0;
  if (has_profile(p)) {
    const double top = profile_top(p);
    if (isnan(o->omega_max)) o->omega_max = top;
    else if (fabs(o->omega_max - top) > 1e-9 * top)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "options: omega_max = %.10g rad/s disagrees with the run-up profile's top speed %.10g "
                               "rad/s ([drive]): leave omega_max unset (NaN) or make them equal",
                               o->omega_max, top);
    if (!(o->t_end > profile_end(p)))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "options: t_end = %g s must be larger than the end of the run-up profile, %g s ([drive])",
                               o->t_end, profile_end(p));
  }
  if (isnan(o->mass_min)) o->mass_min = 0.5 * pl->ball_mass[0];
  if (isnan(o->mass_max)) o->mass_max = 2.0 * pl->ball_mass[0];
  if (isnan(o->radius_min)) o->radius_min = 0.5 * pl->ball_radius[0];
  if (isnan(o->radius_max)) o->radius_max = 1.5 * pl->ball_radius[0];
  if (isnan(o->damping_min)) o->damping_min = 0.1 * pl->ball_damping[0];
  if (isnan(o->damping_max)) o->damping_max = 10.0 * pl->ball_damping[0];
  if (isnan(o->position_min)) o->position_min = pl->d;
  if (isnan(o->position_max)) o->position_max = pl->d;
#define NEED(cond, ...) \
  if (!(cond)) return autobal_error_set(err, AUTOBAL_EINVAL, __VA_ARGS__)
  NEED(isfinite(o->omega_min) && isfinite(o->omega_max) && o->omega_min > 0.0 && o->omega_min < o->omega_max,
       "options: omega_min = %g, omega_max = %g rad/s: need 0 < omega_min < omega_max (finite)", o->omega_min,
       o->omega_max);
  NEED(o->n_omega >= 2 && o->n_omega <= 100000, "options: n_omega = %zu must be in [2, 100000]", o->n_omega);
  if (o->n_verify == 0) o->n_verify = 4 * (o->n_omega - 1) + 1;
  NEED(o->n_verify >= 2 && o->n_verify <= 1000000, "options: n_verify = %zu must be in [2, 1000000]", o->n_verify);
  NEED(isfinite(o->unbalance_min) && isfinite(o->unbalance_max) && o->unbalance_min > 0.0 &&
           o->unbalance_min <= o->unbalance_max,
       "options: unbalance_min = %g, unbalance_max = %g kg m: need 0 < min <= max (finite)", o->unbalance_min,
       o->unbalance_max);
  NEED(isfinite(o->margin) && o->margin >= 0.0, "options: margin = %g 1/s must be >= 0 (finite)", o->margin);
  NEED(isfinite(o->mass_min) && isfinite(o->mass_max) && o->mass_min > 0.0 && o->mass_min <= o->mass_max,
       "options: mass_min = %g, mass_max = %g kg: need 0 < min <= max", o->mass_min, o->mass_max);
  NEED(isfinite(o->radius_min) && isfinite(o->radius_max) && o->radius_min > 0.0 && o->radius_min <= o->radius_max,
       "options: radius_min = %g, radius_max = %g m: need 0 < min <= max", o->radius_min, o->radius_max);
  NEED(isfinite(o->damping_min) && isfinite(o->damping_max) && o->damping_min > 0.0 &&
           o->damping_min <= o->damping_max,
       "options: damping_min = %g, damping_max = %g kg/s: need 0 < min <= max", o->damping_min, o->damping_max);
  NEED(isfinite(o->position_min) && isfinite(o->position_max) && o->position_min <= o->position_max,
       "options: position_min = %g, position_max = %g m: need min <= max (finite)", o->position_min, o->position_max);
  NEED(o->n_mass >= 1 && o->n_mass <= 1000 && o->n_damping >= 1 && o->n_damping <= 1000 && o->n_position >= 1 &&
           o->n_position <= 1000 && o->n_radius >= 1 && o->n_radius <= 1000,
       "options: n_mass = %zu, n_damping = %zu, n_position = %zu, n_radius = %zu must be in [1, 1000]", o->n_mass,
       o->n_damping, o->n_position, o->n_radius);
  NEED(o->n_best >= 1 && o->n_best <= 1000, "options: n_best = %zu must be in [1, 1000]", o->n_best);
  NEED(o->n_starts <= 100, "options: n_starts = %zu must be in [0, 100]", o->n_starts);
  NEED(o->max_iter >= 1 && o->max_iter <= 10000, "options: max_iter = %zu must be in [1, 10000]", o->max_iter);
  NEED(o->n_transient <= 1000, "options: n_transient = %zu must be in [0, 1000]", o->n_transient);
  NEED(o->rank_by == AUTOBAL_DESIGN_RANK_MARGIN || o->rank_by == AUTOBAL_DESIGN_RANK_TIME ||
           o->rank_by == AUTOBAL_DESIGN_RANK_P_BALANCE,
       "options: rank_by = %d: allowed 0 (margin), 1 (time), 2 (p_balance)", o->rank_by);
  NEED(o->rank_by == AUTOBAL_DESIGN_RANK_MARGIN || o->n_transient > 0,
       "options: rank_by = %s needs transients: n_transient = 0 (allowed [1, 1000] with it)",
       o->rank_by == AUTOBAL_DESIGN_RANK_TIME ? "time" : "p_balance");
  NEED(o->n_start >= 1 && o->n_start <= 64, "options: n_start = %zu must be in [1, 64]", o->n_start);
  NEED(o->n_transient_unbalances >= 1 && o->n_transient_unbalances <= 100,
       "options: n_transient_unbalances = %zu must be in [1, 100]", o->n_transient_unbalances);
  NEED(o->n_transient_speeds >= 1 && o->n_transient_speeds <= 100,
       "options: n_transient_speeds = %zu must be in [1, 100]", o->n_transient_speeds);
  NEED(o->t_end > 0.0 && o->t_end <= 1e6, "options: t_end = %g s must be in (0, 1e6]", o->t_end);
  NEED(o->balance_tol > 0.0 && o->balance_tol < 1.0, "options: balance_tol = %g must be in (0, 1)", o->balance_tol);
  NEED(o->balance_revs >= 0.0 && o->balance_revs <= 1e6, "options: balance_revs = %g must be in [0, 1e6]",
       o->balance_revs);
  NEED(o->threads >= 0 && o->threads <= 4096, "options: threads = %d must be in [0, 4096]", o->threads);
#undef NEED
  if (o->mass_min == o->mass_max) o->n_mass = 1;
  if (o->radius_min == o->radius_max) o->n_radius = 1;
  if (o->damping_min == o->damping_max) o->n_damping = 1;
  if (o->position_min == o->position_max) o->n_position = 1;
  return AUTOBAL_SUCCESS;
}

static int cmp_design(const void *a, const void *b) {
  const autobal_rotor_design *x = (const autobal_rotor_design *)a, *y = (const autobal_rotor_design *)b;
  if (x->margin > y->margin) return -1;
  if (x->margin < y->margin) return 1;
  if (x->source != y->source) return (x->source > y->source) - (x->source < y->source);
  return (nballs(x) > nballs(y)) - (nballs(x) < nballs(y)); /* fewer balls first */
}

static int same_design(const autobal_rotor_design *a, const autobal_rotor_design *b) {
  return nballs(a) == nballs(b) && fabs(a->mass - b->mass) <= 1e-6 * b->mass && fabs(a->radius - b->radius) <= 1e-6 * b->radius &&
         fabs(a->damping - b->damping) <= 1e-6 * b->damping &&
         fabs(a->position - b->position) <= 1e-6 * (fabs(b->position) + 1e-3);
}

/* Appends d to S's ranked designs unless an equal design is there (1: appended). */
static int add_distinct(autobal_study_rotor_design_summary *S, autobal_rotor_design *d,
                        const autobal_study_rotor_design_options *o) {
  size_t j;
  for (j = 0; j < S->n_designs; j++)
    if (same_design(&S->designs[j], d)) return 0;
  d->feasible = d->margin > o->margin;
  d->p_balance = d->ttb_median = d->ttb_worst = NAN;
  d->n_runs = d->n_balanced = 0;
  S->designs[S->n_designs++] = *d;
  return 1;
}

/* One cell (i, j, k) of the map: its radius window and feasible row (n_feasible and the candidates
 * are collected by map_collect, in cell order). */
static int map_cell(dctx *c, autobal_study_rotor_design_summary *S, size_t cell) {
  const autobal_study_rotor_design_options *o = &c->o;
  const size_t k = cell % o->n_position, j = (cell / o->n_position) % o->n_damping,
               row = cell / (o->n_position * o->n_damping), i = row % o->n_mass, b = row / o->n_mass;
  const double m = S->mass[i];
  const size_t nb = (size_t)S->n_balls[b];
  const int capped = isfinite(o->total_mass_max) && (double)nb * m > o->total_mass_max;
  ivals T;
  double wl, wh;
  size_t q;
  int st;
  if (capped) T.n = 0; /* over the cap on the total ball mass: not searched */
  else if ((st = cell_set(c, nb, m, S->damping[j], S->position[k], &T)) != AUTOBAL_SUCCESS) return st;
  radius_windows(c, &T, m, &wl, &wh);
  S->window_lo[cell] = wl;
  S->window_hi[cell] = wh;
  for (q = 0; q < o->n_radius; q++) {
    const double r = S->radius[q], t_lo = o->unbalance_min / (m * r), t_hi = o->unbalance_max / (m * r);
    size_t e;
    int f = 0;
    if (capped) f = -2;
    else if (!(t_hi < (double)nb)) f = -1;
    else
      for (e = 0; e < T.n; e++)
        if (T.lo[e] < t_lo && t_hi < T.hi[e]) f = 1;
    S->feasible[cell * o->n_radius + q] = f;
  }
  return AUTOBAL_SUCCESS;
}

static void map_collect(const dctx *c, autobal_study_rotor_design_summary *S, size_t cell, autobal_rotor_design *cand,
                        size_t *ncand) {
  const autobal_study_rotor_design_options *o = &c->o;
  const size_t k = cell % o->n_position, j = (cell / o->n_position) % o->n_damping,
               row = cell / (o->n_position * o->n_damping), i = row % o->n_mass, b = row / o->n_mass;
  const double wl = S->window_lo[cell], wh = S->window_hi[cell];
  size_t q;
  for (q = 0; q < o->n_radius; q++) S->n_feasible += S->feasible[cell * o->n_radius + q] == 1;
  if (!isnan(wl)) {
    autobal_rotor_design *d = &cand[(*ncand)++];
    memset(d, 0, sizeof *d);
    d->mass = S->mass[i];
    d->damping = S->damping[j];
    d->position = S->position[k];
    d->radius = isfinite(wh) ? sqrt(wl * wh) : wl;
    d->recheck = -1;
    d->n_balls = (size_t)S->n_balls[b];
  }
}

#ifdef AUTOBAL_HAVE_OPENMP
static void raise_flag(int *f) {
#pragma omp atomic write
  *f = 1;
}

static int nthreads(const autobal_study_rotor_design_options *o) {
  return o->threads > 0 ? o->threads : omp_get_max_threads();
}

/* A worker's copy of the search context: its own handle, balls, error and counts; no progress
 * callback (the caller's thread reports), stopped through *stop. */
static void dctx_clone(const dctx *c, dctx *t, autobal_error *e, int *stop) {
  *t = *c;
  t->s = NULL;
  t->s_d = NAN;
  t->s_n = 0;
  t->err = e;
  autobal_error_clear(e);
  t->ratio_sets = t->evaluations = t->nm_evals = 0;
  t->o.progress = NULL;
  t->stop = stop;
  t->work.plane[0].ball_mass = t->bm;
  t->work.plane[0].ball_radius = t->br;
  t->work.plane[0].ball_damping = t->bh;
  t->work.plane[0].ball_psi = t->bpsi;
  t->work.plane[0].ball_rate = t->brate;
}

/* The first failure by index (deterministic whatever the threads), the counts summed. */
typedef struct pfail {
  long long idx;
  int status;
  char msg[AUTOBAL_ERRMSG_SIZE];
} pfail;

/* n jobs over the threads: job(t, k) on a worker's copy t; thread 0 reports progress
 * (f0 + df * done / n) and stops everything when the caller asks. */
typedef int (*pjob)(dctx *t, size_t k, void *user);
static int run_parallel(dctx *c, size_t n, pjob job, void *user, double f0, double df, unsigned char *done,
                        int *cancelled) {
  int stop = 0, nth = nthreads(&c->o);
  size_t ndone = 0;
  pfail fail;
  fail.idx = -1;
  fail.status = AUTOBAL_SUCCESS;
  fail.msg[0] = '\0';
  *cancelled = 0;
#pragma omp parallel num_threads(nth)
  {
    dctx t;
    autobal_error e;
    long long idx;
    dctx_clone(c, &t, &e, &stop);
#pragma omp for schedule(dynamic, 1)
    for (idx = 0; idx < (long long)n; idx++) {
      int st;
      if (read_flag(&stop)) continue;
      st = job(&t, (size_t)idx, user);
      if (st != AUTOBAL_SUCCESS) {
#pragma omp critical(autobal_design_fail)
        {
          if (fail.idx < 0 || idx < fail.idx) {
            fail.idx = idx;
            fail.status = st;
            snprintf(fail.msg, sizeof fail.msg, "%s", e.message);
          }
        }
        raise_flag(&stop);
        continue;
      }
      if (done) done[idx] = 1;
#pragma omp atomic
      ndone++;
      if (omp_get_thread_num() == 0 && c->o.progress) {
        size_t nd;
#pragma omp atomic read
        nd = ndone;
        if (c->o.progress(f0 + df * (double)nd / (double)n, c->o.progress_user)) {
#pragma omp atomic write
          *cancelled = 1;
          raise_flag(&stop);
        }
      }
    }
#pragma omp critical(autobal_design_sum)
    {
      c->ratio_sets += t.ratio_sets;
      c->evaluations += t.evaluations;
      c->nm_evals += t.nm_evals;
    }
    autobal_rotor_stab_free(t.s);
  }
  if (*cancelled) return AUTOBAL_ECANCELLED;
  if (fail.status != AUTOBAL_SUCCESS) return autobal_error_set(c->err, fail.status, "%s", fail.msg);
  return AUTOBAL_SUCCESS;
}

static int job_cell(dctx *t, size_t k, void *user) { return map_cell(t, (autobal_study_rotor_design_summary *)user, k); }

/* The map over the threads, cell by cell; the rows of ball mass done in full (a prefix) count. */
static int map_parallel(dctx *c, autobal_study_rotor_design_summary *S, autobal_rotor_design *cand, size_t *ncand) {
  const autobal_study_rotor_design_options *o = &c->o;
  const size_t per = o->n_damping * o->n_position, nrow = S->n_n * o->n_mass, ncell = nrow * per;
  unsigned char *done = calloc(ncell ? ncell : 1, 1);
  size_t i, k;
  int st, cancelled;
  if (!done) return autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory");
  st = run_parallel(c, ncell, job_cell, S, 0.0, 0.7, done, &cancelled);
  for (i = 0; i < nrow; i++) {
    int full = 1;
    for (k = 0; k < per; k++) full &= done[i * per + k];
    if (!full) break;
    for (k = 0; k < per; k++) map_collect(c, S, i * per + k, cand, ncand);
    S->n_mass_done = i + 1;
  }
  free(done);
  if (cancelled)
    return autobal_error_set(c->err, AUTOBAL_ECANCELLED, "design: cancelled by the caller after %zu of %zu rows of the map",
                             S->n_mass_done, nrow);
  return st;
}

static int job_margin(dctx *t, size_t k, void *user) {
  autobal_rotor_design *cand = (autobal_rotor_design *)user;
  return robust_margin(t, &cand[k], &cand[k].margin);
}

typedef struct polish_job {
  const autobal_rotor_design *start;
  autobal_rotor_design *out;
} polish_job;
static int job_polish(dctx *t, size_t k, void *user) {
  polish_job *pj = (polish_job *)user;
  int st = polish(t, &pj->start[k], &pj->out[k]);
  pj->out[k].recheck = -1;
  return st;
}
/* The optimizer from the first n starts, over the threads; out[k] from start[k]. */
static int polish_parallel(dctx *c, const autobal_rotor_design *start, size_t n, autobal_rotor_design *out) {
  polish_job pj;
  int cancelled, st;
  pj.start = start;
  pj.out = out;
  st = run_parallel(c, n, job_polish, &pj, 0.8, 0.1, NULL, &cancelled);
  if (cancelled) return autobal_error_set(c->err, AUTOBAL_ECANCELLED, "design: cancelled by the caller (optimizer)");
  return st;
}

static int job_recheck(dctx *t, size_t k, void *user) { return recheck(t, &((autobal_rotor_design *)user)[k]); }
static int recheck_parallel(dctx *c, autobal_rotor_design *d, size_t n) {
  int cancelled, st = run_parallel(c, n, job_recheck, d, 0.9, 0.1, NULL, &cancelled);
  if (cancelled) return autobal_error_set(c->err, AUTOBAL_ECANCELLED, "design: cancelled by the caller (re-check)");
  return st;
}

static int margins_parallel(dctx *c, autobal_rotor_design *cand, size_t ncand) {
  int cancelled, st = run_parallel(c, ncand, job_margin, cand, 0.7, 0.1, NULL, &cancelled);
  if (cancelled) return autobal_error_set(c->err, AUTOBAL_ECANCELLED, "design: cancelled by the caller (ranking)");
  return st;
}
#endif

/* ---- the study ------------------------------------------------------------------------- */

static int run(dctx *c, autobal_study_rotor_design_summary *S) {
  const autobal_study_rotor_design_options *o = &c->o;
  const size_t n_n = o->n_balls_max - o->n_balls_min + 1, nrow = n_n * o->n_mass;
  const size_t ncell = nrow * o->n_damping * o->n_position;
  autobal_rotor_design *cand = NULL, *starts = NULL;
  size_t ncand = 0, i, j, k;
  int st = AUTOBAL_SUCCESS;
  S->n_n = n_n;
  S->n_balls = malloc(n_n * sizeof *S->n_balls);
  if (!S->n_balls) return autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory");
  for (i = 0; i < n_n; i++) S->n_balls[i] = (int)(o->n_balls_min + i);
  S->n_mass = o->n_mass;
  S->n_damping = o->n_damping;
  S->n_position = o->n_position;
  S->n_radius = o->n_radius;
  S->mass = autobal_design_grid_(o->mass_min, o->mass_max, o->n_mass, 1);
  S->damping = autobal_design_grid_(o->damping_min, o->damping_max, o->n_damping, 1);
  S->position = autobal_design_grid_(o->position_min, o->position_max, o->n_position, 0);
  S->radius = autobal_design_grid_(o->radius_min, o->radius_max, o->n_radius, 1);
  S->feasible = malloc(ncell * o->n_radius * sizeof *S->feasible);
  S->window_lo = malloc(ncell * sizeof *S->window_lo);
  S->window_hi = malloc(ncell * sizeof *S->window_hi);
  cand = malloc((ncell + o->n_starts + n_n) * sizeof *cand);
  starts = malloc((o->n_starts + n_n) * sizeof *starts);
  c->omega = autobal_design_grid_(o->omega_min, o->omega_max, o->n_omega, 0);
  if (!S->mass || !S->damping || !S->position || !S->radius || !S->feasible || !S->window_lo || !S->window_hi ||
      !cand || !starts || !c->omega) {
    free(cand);
    free(starts);
    return autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory");
  }
  /* 1. the map, row by row of ball mass */
#ifdef AUTOBAL_HAVE_OPENMP
  if (nthreads(o) > 1) {
    st = map_parallel(c, S, cand, &ncand);
  } else
#endif
  for (i = 0; i < nrow && st == AUTOBAL_SUCCESS; i++) {
    c->fraction = 0.7 * (double)i / (double)nrow;
    for (j = 0; j < o->n_damping && st == AUTOBAL_SUCCESS; j++)
      for (k = 0; k < o->n_position && st == AUTOBAL_SUCCESS; k++) {
        const size_t cell = (i * o->n_damping + j) * o->n_position + k;
        if ((st = map_cell(c, S, cell)) != AUTOBAL_SUCCESS) break;
        map_collect(c, S, cell, cand, &ncand);
      }
    if (st == AUTOBAL_SUCCESS) S->n_mass_done = i + 1;
    if (st == AUTOBAL_SUCCESS && o->progress && o->progress(0.7 * (double)(i + 1) / (double)nrow, o->progress_user))
      st = autobal_error_set(c->err, AUTOBAL_ECANCELLED, "design: cancelled by the caller after %zu of %zu rows of the map",
                             i + 1, nrow);
  }
  if (st == AUTOBAL_ECANCELLED && c->err && strstr(c->err->message, "cancelled by the caller") &&
      !strstr(c->err->message, "rows of the map"))
    autobal_error_set(c->err, AUTOBAL_ECANCELLED, "design: cancelled by the caller after %zu of %zu rows of the map",
                      S->n_mass_done, nrow);
  /* 2. the robust margin of every cell's design; 3. the optimizer from the best */
#ifdef AUTOBAL_HAVE_OPENMP
  if (st == AUTOBAL_SUCCESS && nthreads(o) > 1) st = margins_parallel(c, cand, ncand);
  else
#endif
  for (i = 0; i < ncand && st == AUTOBAL_SUCCESS; i++) {
    c->fraction = 0.7 + 0.1 * (double)i / (double)ncand;
    st = robust_margin(c, &cand[i], &cand[i].margin);
  }
  if (st == AUTOBAL_SUCCESS) {
    /* the optimizer's starts: the best n_starts cells; with every member also the best feasible cell of
     * each number of balls not among them (the ranking by the covered margin needs each n's optimum) */
    size_t ns = 0, n;
    qsort(cand, ncand, sizeof *cand, cmp_design);
    for (i = 0; i < o->n_starts && i < ncand; i++) starts[ns++] = cand[i];
    if (every_members(o) && o->n_starts > 0)
      for (n = o->n_balls_min; n <= o->n_balls_max; n++) {
        int have = 0;
        for (j = 0; j < ns; j++) have |= nballs(&starts[j]) == n;
        for (i = 0; i < ncand && !have; i++)
          if (nballs(&cand[i]) == n && cand[i].margin > o->margin) starts[ns++] = cand[i], have = 1;
      }
#ifdef AUTOBAL_HAVE_OPENMP
    if (nthreads(o) > 1) {
      st = polish_parallel(c, starts, ns, cand + ncand);
      if (st == AUTOBAL_SUCCESS) ncand += ns;
    } else
#endif
    for (i = 0; i < ns && st == AUTOBAL_SUCCESS; i++) {
      autobal_rotor_design d;
      c->fraction = 0.8 + 0.1 * (double)i / (double)ns;
      if ((st = polish(c, &starts[i], &d)) != AUTOBAL_SUCCESS) break;
      d.recheck = -1;
      cand[ncand++] = d;
    }
  }
  /* 4. rank (distinct designs), re-check the best n_best (with every member: plus the best of each number
   * of balls not among them, and then the order by the margin the verdict covers) */
  if (st == AUTOBAL_SUCCESS) {
    qsort(cand, ncand, sizeof *cand, cmp_design);
    S->designs = malloc((ncand ? ncand : 1) * sizeof *S->designs);
    if (!S->designs) st = autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory");
  }
  if (st == AUTOBAL_SUCCESS) {
    for (i = 0; i < ncand && S->n_designs < o->n_best; i++) add_distinct(S, &cand[i], o);
    if (every_members(o)) {
      size_t n;
      for (n = o->n_balls_min; n <= o->n_balls_max; n++) {
        int have = 0;
        for (j = 0; j < S->n_designs; j++) have |= nballs(&S->designs[j]) == n;
        for (i = 0; i < ncand && !have; i++)
          if (nballs(&cand[i]) == n && cand[i].margin > o->margin) have = add_distinct(S, &cand[i], o);
      }
    }
#ifdef AUTOBAL_HAVE_OPENMP
    if (nthreads(o) > 1) {
      st = recheck_parallel(c, S->designs, S->n_designs);
    } else
#endif
    for (i = 0; i < S->n_designs && st == AUTOBAL_SUCCESS; i++) {
      c->fraction = 0.9 + 0.1 * (double)i / (double)S->n_designs;
      st = recheck(c, &S->designs[i]);
    }
    if (st != AUTOBAL_SUCCESS) S->n_designs = 0;
    if (st == AUTOBAL_SUCCESS && every_members(o)) rank_covered(S->designs, S->n_designs);
  }
  if (st == AUTOBAL_SUCCESS && S->n_designs > 0) {
    /* the best design: the first feasible one (re-check passed and, n >= 3 with every member,
     * certified), else the first */
    size_t b = 0;
    for (i = 0; i < S->n_designs; i++)
      if (S->designs[i].feasible) {
        b = i;
        break;
      }
    if (b != 0) {
      autobal_rotor_design t = S->designs[b];
      memmove(S->designs + 1, S->designs, b * sizeof *S->designs);
      S->designs[0] = t;
    }
    /* 5. transients of the first n_transient designs; the ranking by rank_by among them */
    st = transients_and_rank(c, S, o);
  }
  if (st == AUTOBAL_SUCCESS) st = ranked_best_config(c, S, o);
  free(cand);
  free(starts);
  return st;
}

/* ---- anisotropic supports (one plane, two identical balls; docs/rotor.md "Design", "Anisotropic
 * supports") ------------------------------------------------------------------------------------ */

#define ANISO_NU 5 /* unbalances of the Floquet screen per speed, evenly in the balls' half angle */

/* Are the machine's supports anisotropic (the lumped set, relative 1e-12)? */
static int params_aniso(const autobal_rotor_params *p) {
  autobal_rotor_lumped L;
  if (p->input == AUTOBAL_ROTOR_LUMPED) L = p->lumped;
  else if (autobal_rotor_lumped_from_hardware(&p->hw, &L, NULL) != AUTOBAL_SUCCESS) return 0;
  return !autobal_rotor_lumped_isotropic_(&L);
}

/* The Floquet screen of one design (m, h, d, r): the Floquet margin at every speed of the search grid and
 * ANISO_NU unbalances spread evenly in the half angle theta (s = 2 m r cos theta) over [unbalance_min,
 * unbalance_max]; *worst the largest met (stops at the first >= -margin: then not passed).  Sampled, no
 * proof.  *pass 1: every sample decays faster than the margin. */
static int aniso_screen(dctx *c, double m, double h, double d, double r, double *worst, int *pass) {
  const autobal_study_rotor_design_options *o = &c->o;
  const double a = m * r, r0 = c->work.plane[0].r0;
  const double tha = acos(fmin(1.0, o->unbalance_max / (2.0 * a))), thb = acos(fmin(1.0, o->unbalance_min / (2.0 * a)));
  const size_t nu = o->unbalance_min < o->unbalance_max ? ANISO_NU : 1;
  size_t k, j;
  int st;
  *worst = -INFINITY;
  *pass = 0;
  if ((st = set_design(c, 2, m, h, d)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_BALL_RADIUS), r)) !=
      AUTOBAL_SUCCESS)
    return fail_handle(c, st);
  for (k = 0; k < o->n_omega; k++) {
    if ((st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_OMEGA, c->omega[k])) != AUTOBAL_SUCCESS)
      return fail_handle(c, st);
    for (j = 0; j < nu; j++) {
      const double th = nu > 1 ? tha + (thb - tha) * (double)j / (double)(nu - 1) : tha;
      const double sv = j == 0 ? o->unbalance_max : j == nu - 1 ? o->unbalance_min : 2.0 * a * cos(th);
      double mg = NAN;
      int v = AUTOBAL_ROTOR_VERDICT_NONE;
      if ((st = autobal_rotor_stab_set(c->s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv / r0)) != AUTOBAL_SUCCESS)
        return fail_handle(c, st);
      st = autobal_rotor_stab_margin(c->s, AUTOBAL_ROTOR_STAB_FLOQUET, &mg, &v);
      c->evaluations++;
      if (st == AUTOBAL_ECANCELLED) return fail_handle(c, st);
      if (st != AUTOBAL_SUCCESS || !(mg < -o->margin)) { /* a sample that fails (or cannot be analysed) */
        if (st == AUTOBAL_SUCCESS && mg > *worst) *worst = mg;
        return AUTOBAL_SUCCESS;
      }
      if (mg > *worst) *worst = mg;
    }
  }
  *pass = 1;
  return AUTOBAL_SUCCESS;
}

/* The certification of one design: autobal_rotor_stab_every_unbalance_margin with the required margin at
 * every speed of the re-check grid (n_verify).  hill_certified 1: proven at every speed; 0: a member that
 * decays slower than the margin found (stops there); -1: undecided at some speed, no violation. */
static int aniso_certify(dctx *c, autobal_rotor_design *d) {
  autobal_rotor_params q = *c->base;
  autobal_rotor_plane *pl = &q.plane[0];
  double m[2], r[2], h[2], psi[2], rate[2], worst = -INFINITY;
  autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
  autobal_rotor_stab *s;
  autobal_rotor_unbalance_range ur;
  const size_t nv = c->o.n_verify;
  size_t k, i;
  int st = AUTOBAL_SUCCESS, undecided = 0;
  memset(&q.drive, 0, sizeof q.drive);
  for (i = 0; i < 2; i++) {
    m[i] = d->mass, r[i] = d->radius, h[i] = d->damping;
    psi[i] = c->bpsi[i], rate[i] = c->brate[i];
  }
  pl->d = d->position;
  pl->n_balls = 2;
  pl->ball_mass = m, pl->ball_radius = r, pl->ball_damping = h, pl->ball_psi = psi, pl->ball_rate = rate;
  d->hill_certified = -2;
  d->hill_speeds = d->hill_undecided = 0;
  d->hill_found_omega = d->hill_found_s = NAN;
  d->hill_boxes = 0;
  if (!(c->o.unbalance_max < 2.0 * d->mass * d->radius)) { /* the balls cannot balance the range */
    d->hill_certified = 0, d->recheck = 0, d->feasible = 0, d->recheck_margin = -INFINITY;
    return AUTOBAL_SUCCESS;
  }
  so.hill_boxes = c->o.hill_boxes;
  s = autobal_rotor_stab_alloc(&q, &so, c->err);
  if (!s) return c->err ? c->err->status : AUTOBAL_EINVAL;
  autobal_rotor_stab_set_cancel(s, cancel_hook, c);
  d->hill_certified = 1;
  for (k = 0; k < nv; k++) {
    const double w = k == nv - 1 ? c->o.omega_max
                                 : c->o.omega_min + (c->o.omega_max - c->o.omega_min) * (double)k / (double)(nv - 1);
    int v = -1;
    if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w)) != AUTOBAL_SUCCESS ||
        (st = autobal_rotor_stab_every_unbalance_margin(s, c->o.unbalance_min, c->o.unbalance_max, c->o.margin, &v,
                                                        &ur)) != AUTOBAL_SUCCESS) {
      st = autobal_error_set(c->err, st, "design certification (anisotropic supports): %s", autobal_rotor_stab_errmsg(s));
      break;
    }
    c->evaluations += ur.evaluations;
    c->ratio_sets++;
    d->hill_speeds++;
    d->hill_boxes += ur.hill_boxes;
    worst = fmax(worst, ur.margin_worst);
    if (v == 0) {
      d->hill_certified = 0;
      d->hill_found_omega = w;
      d->hill_found_s = ur.s_unstable;
      break;
    }
    if (v != 1) {
      undecided = 1;
      d->hill_undecided++;
      if (isnan(d->hill_found_omega)) d->hill_found_omega = w; /* the first undecided speed */
    }
  }
  autobal_rotor_stab_free(s);
  if (st != AUTOBAL_SUCCESS) return st;
  if (d->hill_certified == 1 && undecided) d->hill_certified = -1;
  d->recheck_margin = -worst;
  d->recheck = d->hill_certified == 1 ? 1 : 0;
  d->feasible = d->hill_certified == 1;
  return AUTOBAL_SUCCESS;
}

/* Certified designs first, each group in the order of the screen's margin. */
static int cmp_aniso(const void *a, const void *b) {
  const autobal_rotor_design *x = (const autobal_rotor_design *)a, *y = (const autobal_rotor_design *)b;
  if (x->feasible != y->feasible) return y->feasible - x->feasible;
  return cmp_design(a, b);
}

static int run_aniso(dctx *c, autobal_study_rotor_design_summary *S) {
  const autobal_study_rotor_design_options *o = &c->o;
  const size_t ncell = o->n_mass * o->n_damping * o->n_position, nr = o->n_radius;
  autobal_rotor_design *cand = NULL;
  size_t ncand = 0, cell, q, i;
  int st = AUTOBAL_SUCCESS;
  S->aniso = 1;
  S->n_n = 1;
  S->n_balls = malloc(sizeof *S->n_balls);
  S->n_mass = o->n_mass;
  S->n_damping = o->n_damping;
  S->n_position = o->n_position;
  S->n_radius = nr;
  S->mass = autobal_design_grid_(o->mass_min, o->mass_max, o->n_mass, 1);
  S->damping = autobal_design_grid_(o->damping_min, o->damping_max, o->n_damping, 1);
  S->position = autobal_design_grid_(o->position_min, o->position_max, o->n_position, 0);
  S->radius = autobal_design_grid_(o->radius_min, o->radius_max, nr, 1);
  S->feasible = malloc(ncell * nr * sizeof *S->feasible);
  S->window_lo = malloc(ncell * sizeof *S->window_lo);
  S->window_hi = malloc(ncell * sizeof *S->window_hi);
  cand = malloc(ncell * nr * sizeof *cand);
  c->omega = autobal_design_grid_(o->omega_min, o->omega_max, o->n_omega, 0);
  if (!S->n_balls || !S->mass || !S->damping || !S->position || !S->radius || !S->feasible || !S->window_lo ||
      !S->window_hi || !cand || !c->omega) {
    free(cand);
    return autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory");
  }
  S->n_balls[0] = 2;
  /* 1. the map: the Floquet screen of every grid design */
  for (cell = 0; cell < ncell && st == AUTOBAL_SUCCESS; cell++) {
    const size_t k = cell % o->n_position, j = (cell / o->n_position) % o->n_damping,
                 im = cell / (o->n_position * o->n_damping);
    S->window_lo[cell] = S->window_hi[cell] = NAN; /* not exact in r with anisotropic supports */
    for (q = 0; q < nr && st == AUTOBAL_SUCCESS; q++) {
      double worst;
      int pass;
      c->fraction = 0.6 * (double)(cell * nr + q) / (double)(ncell * nr);
      if (!(o->unbalance_max < 2.0 * S->mass[im] * S->radius[q])) {
        S->feasible[cell * nr + q] = -1;
        continue;
      }
      if ((st = aniso_screen(c, S->mass[im], S->damping[j], S->position[k], S->radius[q], &worst, &pass)) !=
          AUTOBAL_SUCCESS)
        break;
      S->feasible[cell * nr + q] = pass;
      if (pass) {
        autobal_rotor_design *d = &cand[ncand++];
        memset(d, 0, sizeof *d);
        d->mass = S->mass[im], d->radius = S->radius[q], d->damping = S->damping[j], d->position = S->position[k];
        d->margin = -worst;
        d->n_balls = 2;
        d->recheck = -1;
        d->recheck_margin = NAN;
        S->n_feasible++;
      }
    }
    if (st == AUTOBAL_SUCCESS && (cell + 1) % (o->n_damping * o->n_position) == 0) S->n_mass_done = im + 1;
    if (st == AUTOBAL_SUCCESS && o->progress && o->progress(0.6 * (double)(cell + 1) / (double)ncell, o->progress_user))
      st = autobal_error_set(c->err, AUTOBAL_ECANCELLED, "design: cancelled by the caller after %zu of %zu rows of the map",
                             S->n_mass_done, o->n_mass);
  }
  if (st == AUTOBAL_ECANCELLED && c->err && !strstr(c->err->message, "rows of the map"))
    autobal_error_set(c->err, AUTOBAL_ECANCELLED, "design: cancelled by the caller after %zu of %zu rows of the map",
                      S->n_mass_done, o->n_mass);
  /* 2. the best n_best by the screen's margin, certified by Hill's method at every re-check speed */
  if (st == AUTOBAL_SUCCESS) {
    qsort(cand, ncand, sizeof *cand, cmp_design);
    S->designs = malloc((ncand ? ncand : 1) * sizeof *S->designs);
    if (!S->designs) st = autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory");
  }
  for (i = 0; st == AUTOBAL_SUCCESS && i < ncand && S->n_designs < o->n_best; i++) add_distinct(S, &cand[i], o);
  for (i = 0; st == AUTOBAL_SUCCESS && i < S->n_designs; i++) {
    c->fraction = 0.6 + 0.35 * (double)i / (double)S->n_designs;
    st = aniso_certify(c, &S->designs[i]);
  }
  if (st != AUTOBAL_SUCCESS) S->n_designs = 0;
  if (st == AUTOBAL_SUCCESS && S->n_designs > 0) {
    qsort(S->designs, S->n_designs, sizeof *S->designs, cmp_aniso);
    /* 3. transients of the first n_transient designs; the ranking by rank_by among them */
    st = transients_and_rank(c, S, o);
  }
  if (st == AUTOBAL_SUCCESS) st = ranked_best_config(c, S, o);
  free(cand);
  return st;
}

/* Two planes (options.planes = 2): the search of rotor_design2.c on the machine with the config's
 * balls in writable arrays, then the best config and the archive as for one plane. */
static int design_two_planes(dctx *c, autobal_archive *a, autobal_study_rotor_design_summary *summary) {
  double bm[2][2], br[2][2], bh[2][2], bpsi[2][2], brate[2][2];
  size_t j, i;
  int st, wst;
  for (j = 0; j < 2; j++) {
    const autobal_rotor_plane *pl = &c->base->plane[j];
    for (i = 0; i < 2; i++) {
      bm[j][i] = pl->ball_mass[i];
      br[j][i] = pl->ball_radius[i];
      bh[j][i] = pl->ball_damping[i];
      bpsi[j][i] = pl->ball_psi ? pl->ball_psi[i] : 0.0;
      brate[j][i] = pl->ball_rate ? pl->ball_rate[i] : 0.0;
    }
    c->work.plane[j].ball_mass = bm[j];
    c->work.plane[j].ball_radius = br[j];
    c->work.plane[j].ball_damping = bh[j];
    c->work.plane[j].ball_psi = bpsi[j];
    c->work.plane[j].ball_rate = brate[j];
  }
  st = autobal_design2_run_(&c->work, &c->o, summary, c->err);
  /* transients of the first n_transient designs; the ranking by rank_by among them (as one plane) */
  if (st == AUTOBAL_SUCCESS && summary->n_designs > 0 && c->o.n_transient > 0) {
    const size_t nk = c->o.n_transient < summary->n_designs ? c->o.n_transient : summary->n_designs;
    for (i = 0; i < nk && st == AUTOBAL_SUCCESS; i++) {
      autobal_rotor_design *d = &summary->designs[i];
      c->fraction = 0.95 + 0.05 * (double)i / (double)nk;
      d->p_balance = d->ttb_median = d->ttb_worst = NAN;
      d->n_runs = d->n_balanced = 0;
      st = design_transients(c, d, &summary->transients);
    }
    if (st == AUTOBAL_SUCCESS && c->o.rank_by != AUTOBAL_DESIGN_RANK_MARGIN)
      rank_transients(summary->designs, nk, c->o.rank_by);
    if (st != AUTOBAL_SUCCESS) summary->ranked = 0;
  }
  if (st == AUTOBAL_SUCCESS && summary->n_designs > 0) {
    summary->best_config = autobal_study_rotor_design_config(c->base, &summary->designs[0], c->o.omega_max);
    if (!summary->best_config) st = autobal_error_set(c->err, AUTOBAL_ENOMEM, "design: out of memory");
  }
  if (a && st == AUTOBAL_SUCCESS) {
    if ((wst = autobal_study_rotor_design_write(a, c->base, &c->o, summary)) != AUTOBAL_SUCCESS)
      return autobal_error_set(c->err, wst, "%s", autobal_archive_errmsg(a));
  }
  return st;
}

int autobal_study_rotor_design(const autobal_rotor_params *p, const autobal_study_rotor_design_options *opt,
                               autobal_archive *a, autobal_study_rotor_design_summary *summary, autobal_error *err) {
  autobal_study_rotor_design_options def = autobal_study_rotor_design_options_default();
  dctx c;
  int st, wst, aniso;
  autobal_error_clear(err);
  if (!summary) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(summary, 0, sizeof *summary);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  memset(&c, 0, sizeof c);
  c.err = err;
  c.base = p;
  if ((st = resolve(p, opt ? opt : &def, &c.o, err)) != AUTOBAL_SUCCESS) return st;
  c.work = *p;
  memset(&c.work.drive, 0, sizeof c.work.drive); /* the stability analyses: constant speeds */
  aniso = params_aniso(p);
  if (aniso && c.o.planes == 2)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[supports]: anisotropic supports are designed for one plane of two balls (planes = 1); "
                             "two planes need isotropic supports (c_Lx = c_Ly, c_Rx = c_Ry, h_Lx = h_Ly, h_Rx = h_Ry)");
  if (aniso && c.o.n_balls_max != 2)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[design] n_balls_max = %zu: with anisotropic supports the design covers two balls "
                             "(Hill's method); set n_balls_min = n_balls_max = 2",
                             c.o.n_balls_max);
  if (aniso && (opt ? opt : &def)->n_verify == 0) c.o.n_verify = c.o.n_omega; /* Hill verdicts: seconds each */
  if (c.o.planes == 2) return design_two_planes(&c, a, summary);
  {
    const autobal_rotor_plane *pl = &p->plane[0];
    size_t i;
    for (i = 0; i < AUTOBAL_DESIGN_MAX_BALLS; i++) {
      c.bm[i] = pl->ball_mass[0];
      c.br[i] = pl->ball_radius[0];
      c.bh[i] = pl->ball_damping[0];
      /* the config's start angles for its balls; further balls evenly spread */
      c.bpsi[i] = i < pl->n_balls ? (pl->ball_psi ? pl->ball_psi[i] : 0.0) : 2.0 * M_PI * (double)i / (double)AUTOBAL_DESIGN_MAX_BALLS;
      c.brate[i] = i < pl->n_balls && pl->ball_rate ? pl->ball_rate[i] : 0.0;
    }
    c.work.plane[0].ball_mass = c.bm;
    c.work.plane[0].ball_radius = c.br;
    c.work.plane[0].ball_damping = c.bh;
    c.work.plane[0].ball_psi = c.bpsi;
    c.work.plane[0].ball_rate = c.brate;
  }
  c.s_d = NAN;
  st = aniso ? run_aniso(&c, summary) : run(&c, summary);
  summary->ratio_sets = c.ratio_sets;
  summary->margin_evaluations = c.evaluations;
  summary->optimizer_evaluations = c.nm_evals;
  autobal_rotor_stab_free(c.s);
  free(c.omega);
  if (a && (st == AUTOBAL_SUCCESS || (st == AUTOBAL_ECANCELLED && summary->feasible && summary->n_mass_done > 0))) {
    if ((wst = autobal_study_rotor_design_write(a, p, &c.o, summary)) != AUTOBAL_SUCCESS)
      return autobal_error_set(err, wst, "%s", autobal_archive_errmsg(a));
  }
  return st;
}

int autobal_study_rotor_design_margin(const autobal_rotor_params *p, const autobal_study_rotor_design_options *opt,
                                      const autobal_rotor_design *design, double *rho, autobal_error *err) {
  autobal_study_rotor_design_options def = autobal_study_rotor_design_options_default();
  dctx c;
  int st;
  if (!p || !design || !rho) return autobal_error_set(err, AUTOBAL_EINVAL, "design margin: NULL argument");
  memset(&c, 0, sizeof c);
  c.err = err;
  c.base = p;
  if ((st = resolve(p, opt ? opt : &def, &c.o, err)) != AUTOBAL_SUCCESS) return st;
  if (c.o.planes == 2)
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "options: planes = 2: the robust margin of one design is for one plane (allowed planes = 1); "
                             "two-plane margins come from autobal_study_rotor_design (sampled)");
  if (params_aniso(p))
    return autobal_error_set(err, AUTOBAL_EUNSUPPORTED,
                             "[supports]: anisotropic supports: the robust margin of one design by bisection is for "
                             "isotropic supports; check a margin delta with autobal_rotor_stab_every_unbalance_margin "
                             "(Hill's method) at each speed");
  if (!(design->mass > 0.0 && design->radius > 0.0 && design->damping > 0.0 && isfinite(design->position)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "design margin: mass, radius, damping must be > 0, position finite");
  c.work = *p;
  memset(&c.work.drive, 0, sizeof c.work.drive);
  {
    size_t i;
    for (i = 0; i < AUTOBAL_DESIGN_MAX_BALLS; i++) {
      c.bm[i] = p->plane[0].ball_mass[0];
      c.br[i] = p->plane[0].ball_radius[0];
      c.bh[i] = p->plane[0].ball_damping[0];
    }
  }
  c.work.plane[0].ball_mass = c.bm;
  c.work.plane[0].ball_radius = c.br;
  c.work.plane[0].ball_damping = c.bh;
  c.work.plane[0].ball_psi = NULL;
  c.work.plane[0].ball_rate = NULL;
  c.s_d = NAN;
  c.omega = autobal_design_grid_(c.o.omega_min, c.o.omega_max, c.o.n_omega, 0);
  if (!c.omega) return autobal_error_set(err, AUTOBAL_ENOMEM, "design margin: out of memory");
  st = robust_margin(&c, design, rho);
  autobal_rotor_stab_free(c.s);
  free(c.omega);
  return st;
}

int autobal_study_rotor_design_transients(const autobal_rotor_params *p, const autobal_study_rotor_design_options *opt,
                                          autobal_rotor_design *design, autobal_error *err) {
  autobal_study_rotor_design_options def = autobal_study_rotor_design_options_default();
  dctx c;
  size_t runs = 0;
  int st;
  autobal_error_clear(err);
  if (!p || !design) return autobal_error_set(err, AUTOBAL_EINVAL, "design transients: NULL argument");
  memset(&c, 0, sizeof c);
  c.err = err;
  c.base = p;
  if ((st = resolve(p, opt ? opt : &def, &c.o, err)) != AUTOBAL_SUCCESS) return st;
  if (!(design->mass > 0.0 && design->radius > 0.0 && design->damping > 0.0 && isfinite(design->position)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "design transients: mass, radius, damping must be > 0, position finite");
  design->p_balance = design->ttb_median = design->ttb_worst = NAN;
  design->n_runs = design->n_balanced = 0;
  return design_transients(&c, design, &runs);
}

/* ---- the config text ------------------------------------------------------------------- */

typedef struct sbuf {
  char *p;
  size_t n, cap;
  int oom;
} sbuf;

static void put(sbuf *b, const char *fmt, ...) AUTOBAL_PRINTF(2, 3);
static void put(sbuf *b, const char *fmt, ...) {
  va_list ap;
  int k;
  if (b->oom) return;
  for (;;) {
    va_start(ap, fmt);
    k = vsnprintf(b->p + b->n, b->cap - b->n, fmt, ap);
    va_end(ap);
    if (k < 0) {
      b->oom = 1;
      return;
    }
    if ((size_t)k < b->cap - b->n) {
      b->n += (size_t)k;
      return;
    }
    {
      size_t nc = 2 * b->cap + (size_t)k + 64;
      char *q = realloc(b->p, nc);
      if (!q) {
        b->oom = 1;
        return;
      }
      b->p = q;
      b->cap = nc;
    }
  }
}

char *autobal_study_rotor_design_config(const autobal_rotor_params *p, const autobal_rotor_design *d, double omega) {
  sbuf b;
  size_t nf, i;
  const autobal_rotor_field *f;
  const char *sec = "";
  const autobal_rotor_plane *pl;
  if (!p || !d || p->n_planes < 1) return NULL;
  pl = &p->plane[0];
  memset(&b, 0, sizeof b);
  b.cap = 4096;
  b.p = malloc(b.cap);
  if (!b.p) return NULL;
  b.p[0] = '\0';
  put(&b, "; written by autobal rotor design: the machine with the design's balancer (docs/rotor.md \"Design\")\n");
  if (p->n_planes == 2) {
    put(&b,
        "; two planes, the same balancer in both: stable at every speed of the grid for every unbalance of both\n"
        "; ranges and every relative phase (certified over plane 2's range at %zu of %zu grid speeds, the others\n"
        "; on plane 2's grid); largest margin met -%.6g 1/s (sampled).  For its analysis: rotor stability with\n"
        "; [stability] unbalance_min/max, unbalance2_min/max (docs/rotor.md \"Design\", \"Two planes\")\n",
        d->n_certified, d->n_certify_run, d->margin);
    if (!isnan(d->margin_certified) && (d->margin_certified > 0.0 || d->margin_steps > 0))
      put(&b, "; certified margin: every root Re lambda < -%.6g 1/s at every grid speed, every unbalance and phase%s\n",
          d->margin_certified, d->margin_decided ? "" : " (a lower bound; a bisection step was undecided: estimate)");
  } else if (d->hill_certified != 0 || d->hill_speeds > 0) {
    put(&b,
        "; anisotropic supports: Floquet screen margin %.6g 1/s (sampled: the search grid's speeds x 5 unbalances);\n"
        "; certification by Hill's method with the required margin at the re-check speeds: %s\n",
        d->margin,
        d->hill_certified == 1    ? "PROVEN at every speed (every Floquet exponent Re < -margin, every unbalance)"
        : d->hill_certified == -1 ? "UNDECIDED at some speed (not feasible)"
        : d->hill_certified == 0  ? "NOT STABLE with the margin (a member found; not feasible)"
                                  : "not run");
  } else if (nballs(d) >= 3 && d->members_certified == 1)
    put(&b,
        "; robust margin %.6g 1/s over the speed grid and every unbalance of the range on the symmetric members;\n"
        "; over every member %.6g 1/s (certified at every speed of the re-check grid)\n",
        d->margin, d->member_margin_certified);
  else
    put(&b, "; robust margin %.6g 1/s over the speed grid and every unbalance of the range\n", d->margin);
  if (nballs(d) >= 3 && d->members_certified == 1)
    put(&b,
        "; %zu identical balls: the verdict covers EVERY member of the family (every balanced configuration of every\n"
        "; unbalance of the range, with the required margin, certified at %zu speeds of the re-check grid); its\n"
        "; every-unbalance analysis: rotor stability with [stability] unbalance_min/max (unbalance_member = every)\n",
        nballs(d), d->member_speeds);
  else if (nballs(d) >= 3)
    put(&b,
        "; %zu identical balls: the verdict covers the symmetric members of the family only (the symmetric fan, the\n"
        "; default balanced configuration of `rotor stability`)%s; for its every-unbalance analysis add\n"
        "; --set stability.unbalance_member=symmetric\n",
        nballs(d),
        d->members_certified == -1 ? ": a member that is not stable (or below the required margin) was found"
        : d->members_certified == -2 ? ": every member was undecided at some speed" : "");
  if (p->input == AUTOBAL_ROTOR_HARDWARE) {
    f = autobal_rotor_hardware_fields(&nf);
    for (i = 0; i < nf; i++) {
      if (strcmp(sec, f[i].section)) {
        sec = f[i].section;
        put(&b, "%s[%s]\n", i ? "\n" : "\n", sec);
        if (!strcmp(sec, "rotor"))
          put(&b, "omega = %.17g\ninertia = paper\naxial = %d\n", omega, p->axial ? 1 : 0);
      }
      put(&b, "%s = %.17g\n", f[i].name, autobal_rotor_field_get(&p->hw, &f[i]));
    }
  } else {
    put(&b, "\n[rotor]\nomega = %.17g\ninertia = paper\naxial = %d\n", omega, p->axial ? 1 : 0);
    put(&b, "\n[supports]\nl_L = %.17g\nl_R = %.17g\n", p->hw.l_L, p->hw.l_R);
    f = autobal_rotor_lumped_fields(&nf);
    put(&b, "\n[lumped]\n");
    for (i = 0; i < nf; i++) put(&b, "%s = %.17g\n", f[i].name, autobal_rotor_field_get(&p->lumped, &f[i]));
  }
  put(&b, "\n[plane1]\nd = %.17g\nm0 = %.17g\nr0 = %.17g\npsi0 = %.17g\n", d->position, pl->m0, pl->r0, pl->psi0);
  if (nballs(d) == 2) {
    put(&b, "ball_mass = %.17g, %.17g\nball_radius = %.17g, %.17g\nball_damping = %.17g, %.17g\n", d->mass, d->mass,
        d->radius, d->radius, d->damping, d->damping);
    put(&b, "ball_psi = %.17g, %.17g\nball_rate = %.17g, %.17g\n", pl->ball_psi && pl->n_balls >= 2 ? pl->ball_psi[0] : 0.0,
        pl->ball_psi && pl->n_balls >= 2 ? pl->ball_psi[1] : 0.0, pl->ball_rate && pl->n_balls >= 2 ? pl->ball_rate[0] : 0.0,
        pl->ball_rate && pl->n_balls >= 2 ? pl->ball_rate[1] : 0.0);
  } else {
    /* n balls: start angles evenly spread (the transient from this config starts with no two
       balls together), at rest relative to the rotor */
    const size_t nb = nballs(d);
    const char *key[5] = {"ball_mass", "ball_radius", "ball_damping", "ball_psi", "ball_rate"};
    size_t q, k;
    for (q = 0; q < 5; q++) {
      put(&b, "%s = ", key[q]);
      for (k = 0; k < nb; k++) {
        const double v = q == 0 ? d->mass : q == 1 ? d->radius : q == 2 ? d->damping
                       : q == 3 ? 2.0 * M_PI * (double)k / (double)nb : 0.0;
        put(&b, "%s%.17g", k ? ", " : "", v);
      }
      put(&b, "\n");
    }
  }
  if (p->n_planes == 2) {
    const autobal_rotor_plane *p2 = &p->plane[1];
    put(&b, "\n[plane2]\nd = %.17g\nm0 = %.17g\nr0 = %.17g\npsi0 = %.17g\n", p2->d, p2->m0, p2->r0, p2->psi0);
    put(&b, "ball_mass = %.17g, %.17g\nball_radius = %.17g, %.17g\nball_damping = %.17g, %.17g\n", d->mass, d->mass,
        d->radius, d->radius, d->damping, d->damping);
    put(&b, "ball_psi = %.17g, %.17g\nball_rate = %.17g, %.17g\n", p2->ball_psi && p2->n_balls >= 2 ? p2->ball_psi[0] : 0.0,
        p2->ball_psi && p2->n_balls >= 2 ? p2->ball_psi[1] : 0.0, p2->ball_rate && p2->n_balls >= 2 ? p2->ball_rate[0] : 0.0,
        p2->ball_rate && p2->n_balls >= 2 ? p2->ball_rate[1] : 0.0);
  }
  if (has_profile(p)) {
    const autobal_rotor_drive *dr = &p->drive;
    if (dr->mode == AUTOBAL_ROTOR_DRIVE_RAMP) {
      put(&b, "\n[drive]\nmode = ramp\nomega_a = %.17g\nomega_b = %.17g\nt_a = %.17g\nt_b = %.17g\n", dr->omega_a,
          dr->omega_b, dr->t_a, dr->t_b);
    } else {
      put(&b, "\n[drive]\nmode = table\ntable_t = ");
      for (i = 0; i < dr->n_points; i++) put(&b, "%s%.17g", i ? ", " : "", dr->table_t[i]);
      put(&b, "\ntable_omega = ");
      for (i = 0; i < dr->n_points; i++) put(&b, "%s%.17g", i ? ", " : "", dr->table_omega[i]);
      put(&b, "\n");
    }
  }
  if (b.oom) {
    free(b.p);
    return NULL;
  }
  return b.p;
}

/* ---- the archive --------------------------------------------------------------------------- */

int autobal_study_rotor_design_write(autobal_archive *a, const autobal_rotor_params *p,
                                     const autobal_study_rotor_design_options *opt,
                                     const autobal_study_rotor_design_summary *S) {
  const char *g = "/rotor/design", *gr = "/rotor/design/ranked";
  const char *dims4[4] = {"ball_mass", "ball_damping", "plane_position", "track_radius"};
  const char *rank1[1] = {"rank"};
  autobal_study_rotor_design_options res;
  size_t nm, i, nn = 0;
  int st, nball; /* nball: the number of balls is a design variable (not today's two balls only) */
  if (!a || !p || !opt || !S || !S->mass) return AUTOBAL_EINVAL;
  if (resolve(p, opt, &res, NULL) == AUTOBAL_SUCCESS) opt = &res; /* the bounds and counts as used */
  nball = !(S->n_n == 1 && S->n_balls && S->n_balls[0] == 2);
  nm = S->n_mass_done;
  if (nball) {
    /* the map's rows are (n, ball mass): the complete n slices are written */
    nn = S->n_mass ? nm / S->n_mass : 0;
    nm = nn == S->n_n ? S->n_mass : (nn > 0 ? S->n_mass : 0);
  }
  if (nm == 0) return AUTOBAL_EINVAL;
  st = autobal_study_write_rotor_params(a, p, 0);
  if (!st) st = autobal_archive_group(a, g);
  if (!st && S->planes == 2) {
    st = autobal_archive_attr_string(a, g, "method", "docs/rotor.md \"Design\", \"Two planes\": the same two-ball balancer in both planes; map: autobal_rotor_stab_every_unbalance2 without the box search at every grid speed (exact in plane 1's unbalance and the relative phase, plane 2's unbalance on n_unbalance2 values); the first n_best stable cells by their sampled margin certified over plane 2's whole range by the box search at every grid speed; sampled in speed, ball mass, damping, track radius");
    if (!st) st = autobal_archive_attr_int(a, g, "planes", 2);
    if (!st) st = autobal_archive_attr_double(a, g, "unbalance2_min", opt->unbalance2_min, "kg m");
    if (!st) st = autobal_archive_attr_double(a, g, "unbalance2_max", opt->unbalance2_max, "kg m");
    if (!st) st = autobal_archive_attr_int(a, g, "n_unbalance2", (long)opt->n_unbalance2);
    if (!st) st = autobal_archive_attr_int(a, g, "unbalance2_boxes", opt->unbalance2_boxes);
    if (!st) st = autobal_archive_attr_int(a, g, "two_plane_verdicts", (long)S->verdicts2);
    if (!st) st = autobal_archive_attr_int(a, g, "n_undecided", (long)S->n_undecided_cells);
    if (!st) st = autobal_archive_attr_double(a, g, "plane2_position", p->plane[1].d, "m");
  } else if (!st && S->aniso) {
    st = autobal_archive_attr_string(a, g, "method", "docs/rotor.md \"Design\", \"Anisotropic supports\": map = Floquet screen (SAMPLED: the grid speeds x 5 unbalances; feasible 1 = every sample decays faster than margin_required; robust_margin = -(largest Floquet margin met)); the first n_best screened designs certified by Hill's method with margin_required at every re-check speed (hill_certified); feasible designs are the certified ones");
    if (!st) st = autobal_archive_attr_int(a, g, "anisotropic", 1);
  } else if (!st)
    st = autobal_archive_attr_string(a, g, "method", "docs/rotor.md \"Design\": exact in the unbalance and the track radius (critical values), sampled in the speed, grid + Nelder-Mead (GSL nmsimplex2) in ball mass, damping, plane position");
  if (!st) st = autobal_archive_attr_double(a, g, "omega_min", opt->omega_min, "rad/s");
  if (!st) st = autobal_archive_attr_double(a, g, "omega_max", opt->omega_max, "rad/s");
  if (!st) st = autobal_archive_attr_int(a, g, "n_omega", (long)opt->n_omega);
  if (!st) st = autobal_archive_attr_int(a, g, "n_verify", (long)opt->n_verify);
  if (!st) st = autobal_archive_attr_double(a, g, "unbalance_min", opt->unbalance_min, "kg m");
  if (!st) st = autobal_archive_attr_double(a, g, "unbalance_max", opt->unbalance_max, "kg m");
  if (!st) st = autobal_archive_attr_double(a, g, "margin_required", opt->margin, "1/s");
  if (!st) st = autobal_archive_attr_int(a, g, "n_feasible", (long)S->n_feasible);
  if (!st) st = autobal_archive_attr_int(a, g, "ratio_sets", (long)S->ratio_sets);
  if (!st) st = autobal_archive_attr_int(a, g, "margin_evaluations", (long)S->margin_evaluations);
  if (!st) st = autobal_archive_attr_int(a, g, "optimizer_evaluations", (long)S->optimizer_evaluations);
  if (!st && opt->n_transient > 0) {
    static const char *const rk[3] = {"margin", "time", "p_balance"};
    st = autobal_archive_attr_string(a, g, "rank_by", rk[opt->rank_by]);
    if (!st) st = autobal_archive_attr_int(a, g, "n_transient", (long)opt->n_transient);
    if (!st) st = autobal_archive_attr_int(a, g, "transient_n_start", (long)opt->n_start);
    if (!st) st = autobal_archive_attr_int(a, g, "transient_n_unbalances", (long)opt->n_transient_unbalances);
    if (!st) st = autobal_archive_attr_int(a, g, "transient_n_speeds", has_profile(p) ? 0L : (long)opt->n_transient_speeds);
    if (!st) st = autobal_archive_attr_double(a, g, "transient_t_end", opt->t_end, "s");
    if (!st) st = autobal_archive_attr_double(a, g, "transient_balance_tol", opt->balance_tol, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "transient_balance_revs", opt->balance_revs, "1");
    if (!st) st = autobal_archive_attr_int(a, g, "transients", (long)S->transients);
    if (!st && S->planes == 2)
      st = autobal_archive_attr_string(a, g, "transient_method", "docs/rotor.md \"Design\", \"Two planes\": per design, per speed (or the run-up profile from rest) and per plane-2 unbalance (transient_n_unbalances values from unbalance2_min to unbalance2_max) an ensemble grid over the start angles of all four balls (plane 1's ball 2 half a step on, plane 2's balls a quarter and three quarters of a step on) and plane 1's unbalances; balanced = attractor class balanced; time to balance = start of the stretch of transient_balance_revs revolutions with every plane's residual unbalance below transient_balance_tol, inf when not balanced by transient_t_end");
    else if (!st) st = autobal_archive_attr_string(a, g, "transient_method", "docs/rotor.md \"Design\": per design an ensemble grid over the start angles of both balls (ball 2 half a step on), the unbalances and the speeds (or the run-up profile from rest); balanced = attractor class balanced; time to balance = start of the stretch of transient_balance_revs revolutions with the residual unbalance below transient_balance_tol, inf when not balanced by transient_t_end");
  }
  if (!st && nball) {
    st = autobal_archive_attr_int(a, g, "n_balls_min", (long)opt->n_balls_min);
    if (!st) st = autobal_archive_attr_int(a, g, "n_balls_max", (long)opt->n_balls_max);
    if (!st) st = autobal_archive_attr_double(a, g, "total_ball_mass_max", opt->total_mass_max, "kg");
    if (!st)
      st = autobal_archive_attr_string(a, g, "unbalance_member",
                                       opt->unbalance_member == AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC ? "symmetric" : "every");
    if (!st)
      st = autobal_archive_attr_string(a, g, "verdict_covers",
                                       opt->n_balls_max < 3 ? "every member (two balls: the balanced configuration is unique)"
                                       : opt->unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY
                                           ? "two balls: every member (the unique one); three or more: the search and robust_margin cover the symmetric fan; every member is certified per design at every speed of the re-check grid with the required margin (ranked/members_certified = 1: every member; else symmetric members only and not feasible), the ball modes -h/m included"
                                           : "two balls: every member (the unique one); three or more: symmetric members only (the symmetric fan), the ball modes -h/m included in the margin");
    if (!st && opt->n_balls_max >= 3 && opt->unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY)
      st = autobal_archive_attr_int(a, g, "member_boxes", opt->member_boxes > 0 ? opt->member_boxes : 4000000L);
  }
  if (!st && (nball ? nn == S->n_n : nm == S->n_mass) && !S->ranked) {
    st = autobal_archive_attr_int(a, g, "partial", 1);
    if (!st) st = autobal_archive_attr_string(a, g, "partial_what", "interrupted during the ranking: the map is complete, no ranked designs");
  }
  if (!st && nball && nn < S->n_n) {
    char what[200];
    snprintf(what, sizeof what, "interrupted: the first %zu of %zu numbers of balls of the map; no ranking", nn, S->n_n);
    st = autobal_archive_attr_int(a, g, "partial", 1);
    if (!st) st = autobal_archive_attr_int(a, g, "done", (long)nn);
    if (!st) st = autobal_archive_attr_int(a, g, "requested", (long)S->n_n);
    if (!st) st = autobal_archive_attr_string(a, g, "partial_what", what);
  }
  if (!st && !nball && nm < S->n_mass) {
    char what[200];
    snprintf(what, sizeof what, "interrupted: the first %zu of %zu rows of the map (ball_mass values); no ranking", nm,
             S->n_mass);
    st = autobal_archive_attr_int(a, g, "partial", 1);
    if (!st) st = autobal_archive_attr_int(a, g, "done", (long)nm);
    if (!st) st = autobal_archive_attr_int(a, g, "requested", (long)S->n_mass);
    if (!st) st = autobal_archive_attr_string(a, g, "partial_what", what);
  }
  if (!st) st = autobal_archive_coord(a, g, "ball_mass", nm, S->mass, "kg", nball ? "ball mass (each ball)" : "ball mass (each of the two balls)");
  if (!st) st = autobal_archive_coord(a, g, "ball_damping", S->n_damping, S->damping, "kg/s", "ball damping h (each ball)");
  if (!st) st = autobal_archive_coord(a, g, "plane_position", S->n_position, S->position, "m", "axial position d of the plane");
  if (!st) st = autobal_archive_coord(a, g, "track_radius", S->n_radius, S->radius, "m", nball ? "track radius r of every ball" : "track radius r of both balls");
  if (!st && nball) {
    double *nv = malloc(nn * sizeof *nv);
    if (!nv) return AUTOBAL_ENOMEM;
    for (i = 0; i < nn; i++) nv[i] = (double)S->n_balls[i];
    st = autobal_archive_coord(a, g, "n_balls", nn, nv, "1", "number of identical balls in the plane");
    free(nv);
    /* one group per number of balls (the archive's datasets have rank <= 4), the dimensions are
       those of /rotor/design */
    for (i = 0; i < nn && !st; i++) {
      const size_t per = S->n_mass * S->n_damping * S->n_position;
      char sg[80];
      snprintf(sg, sizeof sg, "%s/n_balls_%d", g, S->n_balls[i]);
      st = autobal_archive_group(a, sg);
      if (!st) st = autobal_archive_attr_int(a, sg, "n_balls", (long)S->n_balls[i]);
      if (!st) st = autobal_archive_var_int(a, sg, "feasible", 4, dims4, S->feasible + i * per * S->n_radius, "1", "1: every root Re lambda < -margin_required at every speed of the grid for every unbalance of the range (three or more balls: symmetric members, and h/m > margin_required); 0: not; -1: the balls cannot balance unbalance_max (n m r <= m0 r0); -2: n m exceeds total_ball_mass_max");
      if (!st) st = autobal_archive_var(a, sg, "radius_window_lo", 3, dims4, S->window_lo + i * per, "m", "lower end of the widest open interval of feasible track radii within the bounds (exact in r; NaN: none)");
      if (!st) st = autobal_archive_var(a, sg, "radius_window_hi", 3, dims4, S->window_hi + i * per, "m", "upper end of the same interval");
    }
  } else if (S->planes == 2) {
    if (!st) st = autobal_archive_var_int(a, g, "feasible", 4, dims4, S->feasible, "1", "two planes, the same balancer in both: 1: stable at every speed of the grid for every unbalance of both ranges and every phase (plane 2 on its grid) and every margin met below -margin_required; 0: not; -1: the balls cannot balance the largest unbalance (2 m r <= max(unbalance_max, unbalance2_max)); -3: the analysis could not decide (an error)");
    if (!st) st = autobal_archive_var(a, g, "margin_map", 4, dims4, S->margin_map, "1/s", "-(largest margin met over the speed grid, plane-1 unbalances, phases and plane-2 grid values evaluated): sampled; NaN where not stable at some speed");
  } else {
  if (!st) st = autobal_archive_var_int(a, g, "feasible", 4, dims4, S->feasible, "1", "1: every root Re lambda < -margin_required at every speed of the grid for every unbalance of the range; 0: not; -1: the balls cannot balance unbalance_max (2 m r <= m0 r0)");
  if (!st) st = autobal_archive_var(a, g, "radius_window_lo", 3, dims4, S->window_lo, "m", "lower end of the widest open interval of feasible track radii within the bounds (exact in r; NaN: none)");
  if (!st) st = autobal_archive_var(a, g, "radius_window_hi", 3, dims4, S->window_hi, "m", "upper end of the same interval");
  }
  if (st || S->n_designs == 0 || !S->ranked) return st;
  {
    const size_t n = S->n_designs;
    double *v = malloc(n * sizeof *v);
    int *iv = malloc(n * sizeof *iv);
    if (!v || !iv) {
      free(v);
      free(iv);
      return AUTOBAL_ENOMEM;
    }
    st = autobal_archive_group(a, gr);
    if (!st) st = autobal_archive_dim(a, gr, "rank", n, "rank of the design, 0 the best");
#define COL(field, name, unit, lname)                                           \
  if (!st) {                                                                    \
    for (i = 0; i < n; i++) v[i] = S->designs[i].field;                         \
    st = autobal_archive_var(a, gr, name, 1, rank1, v, unit, lname);            \
  }
#define ICOL(field, name, lname)                                                \
  if (!st) {                                                                    \
    for (i = 0; i < n; i++) iv[i] = S->designs[i].field;                        \
    st = autobal_archive_var_int(a, gr, name, 1, rank1, iv, "1", lname);        \
  }
    COL(mass, "ball_mass", "kg", nball ? "ball mass (each ball)" : "ball mass (each of the two balls)")
    COL(radius, "track_radius", "m", "track radius")
    COL(damping, "ball_damping", "kg/s", "ball damping h")
    COL(position, "plane_position", "m", "plane position d")
    COL(margin, "robust_margin", "1/s", "robust margin rho: the exact test passes with this margin at every speed of the grid for every unbalance of the range")
    COL(recheck_margin, "recheck_margin", "1/s", "-(largest margin evaluated by the re-check on the finer speed grid): a sampled upper estimate of rho")
    ICOL(feasible, "feasible", "1: robust_margin > margin_required and the re-check agrees (n >= 3 with unbalance_member = every: and members_certified = 1)")
    ICOL(recheck, "recheck", "1: the exact every-unbalance analysis finds it stable for every unbalance on the re-check grid with margins below -margin_required; 0: not; -1: not re-checked")
    ICOL(source, "source", "0: a grid point of the map, 1: the Nelder-Mead optimizer")
    if (nball && !st) {
      for (i = 0; i < n; i++) iv[i] = (int)nballs(&S->designs[i]);
      st = autobal_archive_var_int(a, gr, "n_balls", 1, rank1, iv, "1", "number of identical balls of the design");
    }
    if (nball && opt->n_balls_max >= 3 && opt->unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY) {
      ICOL(members_certified, "members_certified", "n >= 3: 1 every member (every balanced configuration of every unbalance of the range) has every root Re lambda < -margin_required at every speed of the re-check grid (certified); -1 a violation found (member_found_*); -2 undecided at some speed; 0 not run (two balls: the member is unique; or recheck != 1)")
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].member_speeds;
        st = autobal_archive_var_int(a, gr, "member_speeds", 1, rank1, iv, "1", "re-check speeds evaluated by the every-member certification");
      }
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].member_undecided;
        st = autobal_archive_var_int(a, gr, "member_speeds_undecided", 1, rank1, iv, "1", "of them undecided (a u failing only in the enclosure's gap, or no member built)");
      }
      COL(member_undecided_omega[0], "member_undecided_first", "rad/s", "first undecided speed (NaN: none)")
      COL(member_undecided_omega[1], "member_undecided_last", "rad/s", "last undecided speed (NaN: none)")
      COL(member_found_omega, "member_found_speed", "rad/s", "speed of the violation found (NaN: none)")
      COL(member_found_u, "member_found_u", "kg^2", "u = |Q|^2/4 of the violation: a member with this u is not stable, or has a root at Re lambda >= -margin_required (NaN: none, or the ball modes h/m <= margin_required)")
      COL(member_found_margin, "member_found_margin", "1/s", "max Re lambda of the member analysed there (NaN: found by the u test with the margin)")
      COL(member_margin, "member_margin", "1/s", "-(largest margin of the members analysed over the speeds): a sampled upper estimate")
      COL(member_u[0], "member_u_min", "kg^2", "outer bound: every member of every unbalance of the range has u >= this")
      COL(member_u[1], "member_u_max", "kg^2", "outer bound: every member has u <= this")
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].member_boxes;
        st = autobal_archive_var_int(a, gr, "member_boxes", 1, rank1, iv, "1", "boxes of the enclosure's branch-and-bound (4 to 10 balls; 0 for three: closed form)");
      }
      ICOL(member_enclosure_complete, "member_enclosure_complete", "1: the enclosure of u closed to its tolerance within member_boxes (else valid but wider)")
      COL(member_margin_certified, "member_margin_certified", "1/s", "certified designs: the largest delta proven by bisection (to about 1e-3 1/s): every root Re lambda < -delta for every member of every unbalance of the range at every re-check speed (Delta's roots and -h/m); NaN: not certified")
      ICOL(member_margin_decided, "member_margin_decided", "1: every bisection step was decided; 0: a step failed only in the enclosure's gap (member_margin_certified still proven)")
    }
    if (S->aniso) {
      ICOL(hill_certified, "hill_certified", "anisotropic supports: 1 every Floquet exponent Re < -margin_required for every unbalance of the range at every re-check speed (Hill's method, proven); 0 a member decaying slower found (hill_found_*); -1 undecided at some speed; -2 not run")
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].hill_speeds;
        st = autobal_archive_var_int(a, gr, "hill_speeds", 1, rank1, iv, "1", "re-check speeds evaluated by the certification");
      }
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].hill_undecided;
        st = autobal_archive_var_int(a, gr, "hill_speeds_undecided", 1, rank1, iv, "1", "of them undecided (boxes left open at the budget)");
      }
      COL(hill_found_omega, "hill_found_speed", "rad/s", "speed of the violation (hill_certified 0) or the first undecided speed (-1); NaN: none")
      COL(hill_found_s, "hill_found_unbalance", "kg m", "m0 r0 of a member whose Floquet margin is >= -margin_required (NaN: none)")
    }
    if (S->planes == 2) {
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].n_certified;
        st = autobal_archive_var_int(a, gr, "certified_speeds", 1, rank1, iv, "1", "grid speeds where the verdict is certified over plane 2's whole unbalance range (box search); the others sampled on plane 2's grid");
      }
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].n_certify_run;
        st = autobal_archive_var_int(a, gr, "certify_speeds_run", 1, rank1, iv, "1", "grid speeds the certification ran at (0: unbalance2_boxes = -1)");
      }
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].boxes;
        st = autobal_archive_var_int(a, gr, "boxes", 1, rank1, iv, "1", "boxes of the certification's search");
      }
      COL(found_omega, "found_speed", "rad/s", "the first grid speed where the certification found the design not stable (NaN: none)")
      COL(found_s[0], "found_unbalance1", "kg m", "plane 1's m0 r0 of a point not stable found there (NaN: none or between the slices)")
      COL(found_s[1], "found_unbalance2", "kg m", "plane 2's m0 r0 of that point")
      COL(found_phase, "found_phase", "rad", "relative phase of that point")
      COL(margin_certified, "margin_certified", "1/s", "the largest delta proven by bisection: every root Re lambda < -delta for every unbalance of both ranges and every phase at every grid speed (box search on Delta16(mu - delta)); NaN: not run")
      COL(margin_upper, "margin_upper", "1/s", "the smallest delta where a root at Re lambda >= -delta was found (or the sampled margin)")
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = S->designs[i].margin_decided;
        st = autobal_archive_var_int(a, gr, "margin_decided", 1, rank1, iv, "1", "1: every bisection step decided (margin_certified is certified to about 1e-3 1/s); 0: some step undecided (an estimate)");
      }
    }
    if (opt->n_transient > 0) {
      COL(p_balance, "p_balance", "1", "share of the design's transients whose attractor is balanced (NaN: not run)")
      COL(ttb_median, "time_to_balance_median", "s", "median time to balance over the design's transients (inf: more than half do not balance)")
      COL(ttb_worst, "time_to_balance_worst", "s", "largest time to balance over the design's transients (inf: some member does not balance within transient_t_end)")
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].n_runs;
        st = autobal_archive_var_int(a, gr, "transient_members", 1, rank1, iv, "1", "transients run for the design (0: none)");
      }
      if (!st) {
        for (i = 0; i < n; i++) iv[i] = (int)S->designs[i].n_balanced;
        st = autobal_archive_var_int(a, gr, "transient_balanced", 1, rank1, iv, "1", "of them balanced (attractor class balanced)");
      }
    }
#undef COL
#undef ICOL
    free(v);
    free(iv);
  }
  if (!st && S->best_config) st = autobal_archive_attr_string(a, g, "best_config", S->best_config);
  return st;
}
