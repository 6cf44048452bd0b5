/* transient.c: the transient engine (model-agnostic gsl_odeiv2 driver).
 * See include/autobal/transient.h for the contract. */
#define _POSIX_C_SOURCE 200809L

#include "autobal/transient.h"

#include <float.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "internal.h"
#include "transient/dop853.h"

/* ------------------------------------------------------------------------ */
/* Stepper table                                                            */
/* ------------------------------------------------------------------------ */

typedef struct stepper_entry {
  const char *name;
  const gsl_odeiv2_step_type *const *type; /* address of GSL's exported pointer */
} stepper_entry;

/* autobal's own step type (transient/dop853.c) */
static const gsl_odeiv2_step_type *const k_dop853 = &autobal_transient_dop853_type_;

static const stepper_entry k_steppers[] = {
    {"rk2", &gsl_odeiv2_step_rk2},       {"rk4", &gsl_odeiv2_step_rk4},
    {"rkf45", &gsl_odeiv2_step_rkf45},   {"rkck", &gsl_odeiv2_step_rkck},
    {"rk8pd", &gsl_odeiv2_step_rk8pd},   {"rk1imp", &gsl_odeiv2_step_rk1imp},
    {"rk2imp", &gsl_odeiv2_step_rk2imp}, {"rk4imp", &gsl_odeiv2_step_rk4imp},
    {"bsimp", &gsl_odeiv2_step_bsimp},   {"msadams", &gsl_odeiv2_step_msadams},
    {"msbdf", &gsl_odeiv2_step_msbdf},   {"dop853", &k_dop853},
};
#define N_STEPPERS (sizeof k_steppers / sizeof k_steppers[0])

static const char k_stepper_names[] =
    "rk2, rk4, rkf45, rkck, rk8pd, rk1imp, rk2imp, rk4imp, bsimp, msadams, msbdf, dop853";

const char *autobal_transient_stepper_names(void) { return k_stepper_names; }

static const stepper_entry *find_stepper(const char *name) {
  size_t i;
  if (name == NULL) name = "rk8pd";
  for (i = 0; i < N_STEPPERS; i++)
    if (strcmp(name, k_steppers[i].name) == 0) return &k_steppers[i];
  return NULL;
}

/* ------------------------------------------------------------------------ */
/* Options                                                                  */
/* ------------------------------------------------------------------------ */

autobal_transient_options autobal_transient_options_default(void) {
  autobal_transient_options o;
  o.stepper = "rk8pd";
  o.rtol = 1e-10;
  o.atol = 1e-12;
  o.h_init = 0.0;
  o.h_max = 0.0;
  o.h_min = 0.0;
  o.max_steps = 100000000UL;
  o.dt_out = 0.0;
  o.event_tol = 1e-10;
  o.progress_step = 0.005;
  o.progress_wall = 0.0;
  o.exact_output = 0;
  o.dense_order = 7;
  return o;
}

int autobal_transient_options_validate(const autobal_transient_options *opt, autobal_error *err) {
  int rc;
  if (opt == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "options: NULL pointer");
  if (find_stepper(opt->stepper) == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option stepper = \"%s\" is not a known GSL stepper: valid names are %s",
                             opt->stepper, k_stepper_names);
  /* rtol > 1 would switch the error control off; below 4 DBL_EPSILON (8.9e-16) the rounding of
   * double arithmetic alone exceeds the requested relative error, and the step size shrinks
   * until max_steps (rtol = atol = 1e-300 used to crawl) */
  if ((rc = autobal_check_param(err, "rtol", opt->rtol, AUTOBAL_TRANSIENT_RTOL_MIN, 0, 1.0, 0, "")) != 0)
    return rc;
  if ((rc = autobal_check_param(err, "atol", opt->atol, 0.0, 1, INFINITY, 1, "")) != 0) return rc;
  if ((rc = autobal_check_param(err, "h_init", opt->h_init, 0.0, 0, INFINITY, 1, "")) != 0)
    return rc;
  if ((rc = autobal_check_param(err, "h_max", opt->h_max, 0.0, 0, INFINITY, 1, "")) != 0)
    return rc;
  if ((rc = autobal_check_param(err, "h_min", opt->h_min, 0.0, 0, INFINITY, 1, "")) != 0)
    return rc;
  if (opt->h_max > 0.0 && opt->h_min > opt->h_max)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option h_min = %.17g is larger than h_max = %.17g", opt->h_min,
                             opt->h_max);
  if (opt->h_max > 0.0 && opt->h_init > opt->h_max)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option h_init = %.17g is larger than h_max = %.17g", opt->h_init,
                             opt->h_max);
  if ((rc = autobal_check_param(err, "dt_out", opt->dt_out, 0.0, 0, INFINITY, 1, "")) != 0)
    return rc;
  if ((rc = autobal_check_param(err, "event_tol", opt->event_tol, 0.0, 1, INFINITY, 1, "")) != 0)
    return rc;
  if ((rc = autobal_check_param(err, "progress_step", opt->progress_step, 0.0, 1, 1.0, 0, "")) !=
      0)
    return rc;
  if ((rc = autobal_check_param(err, "progress_wall", opt->progress_wall, 0.0, 0, INFINITY, 1,
                                "s")) != 0)
    return rc;
  if (opt->exact_output != 0 && opt->exact_output != 1)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option exact_output = %d is out of range: allowed 0 or 1",
                             opt->exact_output);
  if (opt->dense_order != 0 && opt->dense_order != 6 && opt->dense_order != 7)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option dense_order = %d is out of range: allowed 7 or 6 (0: 7)",
                             opt->dense_order);
  return AUTOBAL_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* The handle                                                               */
/* ------------------------------------------------------------------------ */

/* One stepper with its error control and the buffers of the step loop.  The
 * GSL driver object is used only because the multistep methods (msadams,
 * msbdf) reach the control object through it; its evolve object is unused. */
typedef struct stepper_ctx {
  gsl_odeiv2_driver *d;
  double *y0;       /* state at the start of the step (restored on rejection) */
  double *yerr;     /* error estimate */
  double *dydt_in;  /* f(t, y) at the start of the step */
  double *dydt_out; /* f at the end of the step */
  int have_dydt;    /* dydt_in is valid for the current (t, y) */
  int own_ctl;      /* dop853: its own step-size control (GSL's decision, computed in the step) */
} stepper_ctx;

enum { DWELL_ABOVE = 0, DWELL_BELOW = 1, DWELL_FIRED = 2 };

typedef struct event_item {
  autobal_transient_scalar_fn g;
  void *user;
  int direction, terminal;
  int dwell;
  unsigned probes; /* interior points checked per step for a grazing crossing (0: none) */
  int at_outputs;  /* dense output: also checked at the output times inside a step */
  double threshold, duration;
  /* state of a run */
  double g_prev; /* g (or s - threshold) at the last accepted step */
  int dwell_state;
  double t_enter;
  unsigned long count;
  autobal_transient_event_hit first;
  /* scratch of one step */
  int pending;
  double t_hit;
  double t_start;
  int dir_hit;
} event_item;

struct autobal_transient {
  size_t dim;
  autobal_transient_options opt;
  const gsl_odeiv2_step_type *type;
  gsl_odeiv2_system gsys; /* the adapters below, params = this handle */
  gsl_odeiv2_system gsys_direct; /* the user's rhs itself, for dop853's steps (see direct_status) */
  stepper_ctx main, aux;
  autobal_transient_system sys; /* the user's system during run() */
  /* finite-difference Jacobian */
  double *fd_f0, *fd_f1, *fd_y;
  /* run workspace */
  double *y_prev; /* state at the start of the last accepted step */
  double *y_work; /* event location */
  double *y_evt;  /* state at a located event */
  double *pr_fa, *pr_fb, *pr_y; /* probes: derivatives at the step's ends (when computed), interpolant */
  double *y_hit;  /* locate: the integrated state at hit_t (far side of the last located crossing) */
  double *loc;    /* locate: its Hermite nodes (4 dim), a hop's stages (4 dim), f at a trial point (dim) */
  double *pc_y;   /* probes: the interpolated states at the probe points of this step (pc_cap x dim),
                     shared by every event with pc_n probes (pc_valid[k]: point k + 1 computed) */
  unsigned pc_cap, pc_n;
  unsigned char pc_valid[64];
  double *y_out;  /* dense output: the interpolated state at an output time */
  int dense;      /* this run: output and events on the main stepper's continuous extension */
  autobal_transient_dop853_at_fn d6_at; /* this run, dense_order 6: the extension at t (its size built in) */
  double t0_run, t1_run, t_out; /* the run's span and its next output time (number k_out) */
  unsigned long k_out;
  double hit_t;   /* its time; hit_valid: it belongs to the step being processed */
  int hit_valid;
  /* events */
  event_item *ev;
  size_t nev, cap;
  size_t *order; /* cap entries: pending events sorted by time */
  /* callbacks */
  autobal_transient_observer_fn observer;
  void *observer_user;
  autobal_transient_progress_fn progress;
  void *progress_user;
  autobal_transient_event_handler_fn handler;
  void *handler_user;
  autobal_transient_event_reset_fn reset;
  void *reset_user;
  unsigned long reset_run; /* resets in a row, each within event_tol of the previous one */
  double t_reset;          /* time of the last reset */
  /* failure record of the adapters */
  int fail_kind; /* 0 none, 1 rhs returned non-zero, 2 rhs non-finite, 3 jac non-zero,
                    4 jac non-finite */
  int fail_code;
  double fail_t;
  size_t fail_index;
  int in_aux;
  double reject_t;              /* time of the last AUTOBAL_TRANSIENT_RHS_REJECT */
  unsigned long n_reject_calls; /* such returns in this run */
  autobal_transient_stats stats;
  unsigned long stats_probe_hits; /* grazing crossings found by probes in this run */
  autobal_error err;
};

/* ---- adapters between GSL and the user's system ---------------------------- */

/* The rhs adapter only counts and maps a non-zero return to GSL_EBADFUNC.
 * Non-finite values are caught once per step, on the stepper's result and
 * error estimate (a NaN or inf in any stage propagates into them), which
 * is cheaper than testing every evaluation (see take_step). */
static int rhs_adapter(double t, const double y[], double dydt[], void *params) {
  autobal_transient *tr = (autobal_transient *)params;
  int rc;
  tr->stats.rhs_evals++;
  rc = tr->sys.rhs(t, y, dydt, tr->sys.params);
  if (rc == AUTOBAL_TRANSIENT_RHS_REJECT) {
    /* the state is outside the system's domain: a trial stage of too long a step (the step is
     * retried shorter, as GSL does for a failure other than GSL_EBADFUNC); remembered so that
     * a rejection at an accepted state, or one that no shorter step avoids, is reported */
    tr->reject_t = t;
    tr->n_reject_calls++;
    return GSL_FAILURE;
  }
  if (rc != 0) {
    if (tr->fail_kind == 0) {
      tr->fail_kind = 1;
      tr->fail_code = rc;
      tr->fail_t = t;
    }
    return GSL_EBADFUNC;
  }
  return GSL_SUCCESS;
}

/* All of v[0..n-1] finite?  NaN fails too.  On the bits (the compiler vectorizes integer and,
 * add, or, not the comparison of doubles): the exponent field plus one carries into the sign bit
 * exactly when it is all ones (inf or NaN). */
static int all_finite(const double *v, size_t n) {
  uint64_t bad = 0;
  size_t i;
  for (i = 0; i < n; i++) {
    uint64_t u;
    memcpy(&u, &v[i], sizeof u);
    bad |= (u & UINT64_C(0x7ff0000000000000)) + UINT64_C(0x0010000000000000);
  }
  return (bad >> 63) == 0;
}

/* all_finite(a) && all_finite(b) && all_finite(c), in one pass */
static int all_finite3(const double *a, const double *b, const double *c, size_t n) {
  const uint64_t ex = UINT64_C(0x7ff0000000000000), one = UINT64_C(0x0010000000000000);
  uint64_t bad = 0;
  size_t i;
  for (i = 0; i < n; i++) {
    uint64_t u, v, w;
    memcpy(&u, &a[i], sizeof u);
    memcpy(&v, &b[i], sizeof v);
    memcpy(&w, &c[i], sizeof w);
    bad |= ((u & ex) + one) | ((v & ex) + one) | ((w & ex) + one);
  }
  return (bad >> 63) == 0;
}

/* Record a non-finite rhs value (kind 2) at t, first bad component of v. */
static int nonfinite_failure(autobal_transient *tr, double t, const double *v) {
  size_t i = 0;
  while (i < tr->dim && isfinite(v[i])) i++;
  if (tr->fail_kind == 0) {
    tr->fail_kind = 2;
    tr->fail_t = t;
    tr->fail_index = i;
  }
  return GSL_EBADFUNC;
}

/* rhs evaluation with the finiteness test, for the few evaluations made
 * outside a step (first derivative, initial step, finite differences). */
static int rhs_checked(autobal_transient *tr, double t, const double y[], double dydt[]) {
  int rc = rhs_adapter(t, y, dydt, tr);
  if (rc != GSL_SUCCESS) return rc;
  if (!all_finite(dydt, tr->dim)) return nonfinite_failure(tr, t, dydt);
  return GSL_SUCCESS;
}

/* Forward differences (see the header for the increments). */
static int fd_jacobian(autobal_transient *tr, double t, const double y[], double *dfdy,
                       double dfdt[]) {
  const size_t n = tr->dim;
  const double sq = sqrt(DBL_EPSILON);
  size_t i, j;
  int rc;
  tr->stats.fd_jac_evals++;
  if ((rc = rhs_checked(tr, t, y, tr->fd_f0)) != GSL_SUCCESS) return rc;
  memcpy(tr->fd_y, y, n * sizeof(double));
  for (j = 0; j < n; j++) {
    const double yj = y[j];
    double dj = sq * fmax(fabs(yj), 1.0);
    tr->fd_y[j] = yj + dj;
    dj = tr->fd_y[j] - yj; /* the increment actually represented */
    if ((rc = rhs_checked(tr, t, tr->fd_y, tr->fd_f1)) != GSL_SUCCESS) return rc;
    for (i = 0; i < n; i++) dfdy[i * n + j] = (tr->fd_f1[i] - tr->fd_f0[i]) / dj;
    tr->fd_y[j] = yj;
  }
  {
    double dt = sq * fmax(fabs(t), 1.0);
    const double t1 = t + dt;
    dt = t1 - t;
    if ((rc = rhs_checked(tr, t1, y, tr->fd_f1)) != GSL_SUCCESS) return rc;
    for (i = 0; i < n; i++) dfdt[i] = (tr->fd_f1[i] - tr->fd_f0[i]) / dt;
  }
  return GSL_SUCCESS;
}

static int jac_adapter(double t, const double y[], double *dfdy, double dfdt[], void *params) {
  autobal_transient *tr = (autobal_transient *)params;
  const size_t n = tr->dim;
  size_t i;
  int rc;
  tr->stats.jac_evals++;
  if (tr->sys.jac == NULL) return fd_jacobian(tr, t, y, dfdy, dfdt);
  rc = tr->sys.jac(t, y, dfdy, dfdt, tr->sys.params);
  if (rc != 0) {
    if (tr->fail_kind == 0) {
      tr->fail_kind = 3;
      tr->fail_code = rc;
      tr->fail_t = t;
    }
    return GSL_EBADFUNC;
  }
  for (i = 0; i < n * n + n; i++) {
    const double v = i < n * n ? dfdy[i] : dfdt[i - n * n];
    if (!isfinite(v)) {
      if (tr->fail_kind == 0) {
        tr->fail_kind = 4;
        tr->fail_t = t;
        tr->fail_index = i;
      }
      return GSL_EBADFUNC;
    }
  }
  return GSL_SUCCESS;
}

/* ---- allocation -------------------------------------------------------------- */

static void ctx_free(stepper_ctx *c) {
  if (c->d) gsl_odeiv2_driver_free(c->d);
  free(c->y0);
  free(c->yerr);
  free(c->dydt_in);
  free(c->dydt_out);
  memset(c, 0, sizeof *c);
}

/* The GSL driver keeps &tr->gsys; tr must not move (it is heap-allocated). */
static int ctx_alloc(autobal_transient *tr, stepper_ctx *c, const gsl_odeiv2_step_type *T,
                     double atol, double rtol) {
  const size_t n = tr->dim;
  memset(c, 0, sizeof *c);
  /* hstart (1.0) is never used: the step loop keeps its own step size.  The
   * arguments are valid, so GSL's error handler is not invoked except for
   * out-of-memory. */
  c->d = gsl_odeiv2_driver_alloc_y_new(&tr->gsys, T, 1.0, atol, rtol);
  if (c->d && T == k_dop853) {
    autobal_transient_dop853_set_tol_(c->d->s->state, atol, rtol);
    c->own_ctl = atol > 0.0 || rtol > 0.0;
  }
  c->y0 = calloc(n, sizeof(double));
  c->yerr = calloc(n, sizeof(double));
  c->dydt_in = calloc(n, sizeof(double));
  c->dydt_out = calloc(n, sizeof(double));
  if (!c->d || !c->y0 || !c->yerr || !c->dydt_in || !c->dydt_out) {
    ctx_free(c);
    return AUTOBAL_ENOMEM;
  }
  return AUTOBAL_SUCCESS;
}

autobal_transient *autobal_transient_alloc(size_t dim, const autobal_transient_options *opt,
                                           autobal_error *err) {
  autobal_transient_options o = opt ? *opt : autobal_transient_options_default();
  const stepper_entry *se;
  autobal_transient *tr;
  if (dim == 0) {
    autobal_error_set(err, AUTOBAL_EINVAL, "parameter dim = 0 is out of range: allowed >= 1");
    return NULL;
  }
  if (dim > (size_t)1 << 20) {
    autobal_error_set(err, AUTOBAL_EINVAL,
                      "parameter dim = %zu is out of range: allowed [1, 1048576]", dim);
    return NULL;
  }
  if (autobal_transient_options_validate(&o, err) != AUTOBAL_SUCCESS) return NULL;
  se = find_stepper(o.stepper);
  o.stepper = se->name; /* a static string from now on */
  tr = calloc(1, sizeof *tr);
  if (tr == NULL) {
    autobal_error_set(err, AUTOBAL_ENOMEM, "transient: out of memory allocating the handle");
    return NULL;
  }
  tr->dim = dim;
  tr->opt = o;
  tr->type = *se->type;
  tr->d6_at = autobal_transient_dop853_dense6_at_; /* its size's own one at each run */
  tr->gsys.function = rhs_adapter;
  tr->gsys.jacobian = jac_adapter;
  tr->gsys.dimension = dim;
  tr->gsys.params = tr;
  tr->fd_f0 = malloc(dim * sizeof(double));
  tr->fd_f1 = malloc(dim * sizeof(double));
  tr->fd_y = malloc(dim * sizeof(double));
  tr->y_prev = malloc(dim * sizeof(double));
  tr->y_work = malloc(dim * sizeof(double));
  tr->y_evt = malloc(dim * sizeof(double));
  tr->y_out = malloc(dim * sizeof(double));
  tr->pr_fa = malloc(4 * dim * sizeof(double));
  tr->pr_fb = tr->pr_fa ? tr->pr_fa + dim : NULL;
  tr->pr_y = tr->pr_fa ? tr->pr_fa + 2 * dim : NULL;
  tr->y_hit = tr->pr_fa ? tr->pr_fa + 3 * dim : NULL;
  tr->loc = malloc(9 * dim * sizeof(double));
  if (!tr->fd_f0 || !tr->fd_f1 || !tr->fd_y || !tr->y_prev || !tr->y_work || !tr->y_evt || !tr->y_out || !tr->pr_fa || !tr->loc ||
      ctx_alloc(tr, &tr->main, tr->type, o.atol, o.rtol) != AUTOBAL_SUCCESS ||
      ctx_alloc(tr, &tr->aux, tr->type, o.atol, o.rtol) != AUTOBAL_SUCCESS) {
    autobal_transient_free(tr);
    autobal_error_set(err, AUTOBAL_ENOMEM, "transient: out of memory (dim = %zu, stepper %s)",
                      dim, o.stepper);
    return NULL;
  }
  tr->stats.event_index = -1;
  autobal_error_clear(&tr->err);
  autobal_error_clear(err);
  return tr;
}

void autobal_transient_free(autobal_transient *tr) {
  if (tr == NULL) return;
  ctx_free(&tr->main);
  ctx_free(&tr->aux);
  free(tr->fd_f0);
  free(tr->fd_f1);
  free(tr->fd_y);
  free(tr->y_prev);
  free(tr->y_work);
  free(tr->y_evt);
  free(tr->y_out);
  free(tr->pr_fa);
  free(tr->loc);
  free(tr->pc_y);
  free(tr->ev);
  free(tr->order);
  free(tr);
}

const char *autobal_transient_errmsg(const autobal_transient *tr) {
  return tr ? tr->err.message : "";
}

int autobal_transient_set_options(autobal_transient *tr, const autobal_transient_options *opt) {
  autobal_transient_options o;
  const stepper_entry *se;
  stepper_ctx m, a;
  if (tr == NULL) return AUTOBAL_EINVAL;
  if (opt == NULL) return autobal_error_set(&tr->err, AUTOBAL_EINVAL, "options: NULL pointer");
  o = *opt;
  if (autobal_transient_options_validate(&o, &tr->err) != AUTOBAL_SUCCESS) return AUTOBAL_EINVAL;
  se = find_stepper(o.stepper);
  o.stepper = se->name;
  if (ctx_alloc(tr, &m, *se->type, o.atol, o.rtol) != AUTOBAL_SUCCESS)
    return autobal_error_set(&tr->err, AUTOBAL_ENOMEM, "transient: out of memory");
  if (ctx_alloc(tr, &a, *se->type, o.atol, o.rtol) != AUTOBAL_SUCCESS) {
    ctx_free(&m);
    return autobal_error_set(&tr->err, AUTOBAL_ENOMEM, "transient: out of memory");
  }
  ctx_free(&tr->main);
  ctx_free(&tr->aux);
  tr->main = m;
  tr->aux = a;
  tr->type = *se->type;
  tr->opt = o;
  autobal_error_clear(&tr->err);
  return AUTOBAL_SUCCESS;
}

autobal_transient_options autobal_transient_get_options(const autobal_transient *tr) {
  return tr ? tr->opt : autobal_transient_options_default();
}

void autobal_transient_set_observer(autobal_transient *tr, autobal_transient_observer_fn fn,
                                    void *user) {
  if (tr == NULL) return;
  tr->observer = fn;
  tr->observer_user = user;
}

void autobal_transient_set_progress(autobal_transient *tr, autobal_transient_progress_fn fn,
                                    void *user) {
  if (tr == NULL) return;
  tr->progress = fn;
  tr->progress_user = user;
}

void autobal_transient_set_event_handler(autobal_transient *tr,
                                         autobal_transient_event_handler_fn fn, void *user) {
  if (tr == NULL) return;
  tr->handler = fn;
  tr->handler_user = user;
}

void autobal_transient_set_event_reset(autobal_transient *tr, autobal_transient_event_reset_fn fn,
                                       void *user) {
  if (tr == NULL) return;
  tr->reset = fn;
  tr->reset_user = user;
}

static int event_push(autobal_transient *tr, const event_item *it) {
  if (tr->nev == tr->cap) {
    size_t cap = tr->cap ? 2 * tr->cap : 4;
    event_item *ev = realloc(tr->ev, cap * sizeof *ev);
    size_t *ord;
    if (ev == NULL) return autobal_error_set(&tr->err, AUTOBAL_ENOMEM, "transient: out of memory");
    tr->ev = ev;
    ord = realloc(tr->order, cap * sizeof *ord);
    if (ord == NULL) return autobal_error_set(&tr->err, AUTOBAL_ENOMEM, "transient: out of memory");
    tr->order = ord;
    tr->cap = cap;
  }
  tr->ev[tr->nev] = *it;
  tr->nev++;
  return (int)(tr->nev - 1);
}

int autobal_transient_add_event(autobal_transient *tr, autobal_transient_scalar_fn g, void *user,
                                int direction, int terminal) {
  event_item it;
  if (tr == NULL) return AUTOBAL_EINVAL;
  if (g == NULL) return autobal_error_set(&tr->err, AUTOBAL_EINVAL, "event function g is NULL");
  if (direction < -1 || direction > 1)
    return autobal_error_set(&tr->err, AUTOBAL_EINVAL,
                             "parameter direction = %d is out of range: allowed -1, 0, +1",
                             direction);
  if (tr->nev >= 100000)
    return autobal_error_set(&tr->err, AUTOBAL_EINVAL, "too many events (limit 100000)");
  memset(&it, 0, sizeof it);
  it.g = g;
  it.user = user;
  it.direction = direction;
  it.terminal = terminal != 0;
  return event_push(tr, &it);
}

int autobal_transient_add_dwell_event(autobal_transient *tr, autobal_transient_scalar_fn s,
                                      void *user, double threshold, double duration,
                                      int terminal) {
  event_item it;
  int rc;
  if (tr == NULL) return AUTOBAL_EINVAL;
  if (s == NULL)
    return autobal_error_set(&tr->err, AUTOBAL_EINVAL, "dwell event: monitored scalar is NULL");
  if ((rc = autobal_check_param(&tr->err, "threshold", threshold, -INFINITY, 1, INFINITY, 1,
                                "")) != 0)
    return rc;
  if ((rc = autobal_check_param(&tr->err, "duration", duration, 0.0, 0, INFINITY, 1, "")) != 0)
    return rc;
  if (tr->nev >= 100000)
    return autobal_error_set(&tr->err, AUTOBAL_EINVAL, "too many events (limit 100000)");
  memset(&it, 0, sizeof it);
  it.g = s;
  it.user = user;
  it.direction = -1;
  it.terminal = terminal != 0;
  it.dwell = 1;
  it.threshold = threshold;
  it.duration = duration;
  return event_push(tr, &it);
}

int autobal_transient_set_event_probes(autobal_transient *tr, int index, unsigned n) {
  if (tr == NULL || index < 0 || (size_t)index >= tr->nev || tr->ev[index].dwell || n > 64) return AUTOBAL_EINVAL;
  if (n > tr->pc_cap) { /* the shared probe states (allocated here, not in run()) */
    double *p = realloc(tr->pc_y, (size_t)n * tr->dim * sizeof(double));
    if (!p) return AUTOBAL_ENOMEM;
    tr->pc_y = p;
    tr->pc_cap = n;
  }
  tr->ev[index].probes = n;
  return AUTOBAL_SUCCESS;
}

int autobal_transient_set_event_output_probes(autobal_transient *tr, int index, int on) {
  if (tr == NULL || index < 0 || (size_t)index >= tr->nev || tr->ev[index].dwell || (on != 0 && on != 1))
    return AUTOBAL_EINVAL;
  tr->ev[index].at_outputs = on;
  return AUTOBAL_SUCCESS;
}

unsigned long autobal_transient_probe_hits(const autobal_transient *tr) { return tr ? tr->stats_probe_hits : 0; }

void autobal_transient_clear_events(autobal_transient *tr) {
  if (tr) tr->nev = 0;
}

int autobal_transient_event_result(const autobal_transient *tr, size_t index,
                                   unsigned long *count, autobal_transient_event_hit *first) {
  if (tr == NULL || index >= tr->nev) return AUTOBAL_EINVAL;
  if (count) *count = tr->ev[index].count;
  if (tr->ev[index].count > 0 && first) *first = tr->ev[index].first;
  return tr->ev[index].count > 0 ? 1 : 0;
}

void autobal_transient_get_stats(const autobal_transient *tr, autobal_transient_stats *stats) {
  if (stats == NULL) return;
  if (tr == NULL) {
    memset(stats, 0, sizeof *stats);
    stats->event_index = -1;
    return;
  }
  *stats = tr->stats;
}

const char *autobal_transient_stop_name(int stop_reason) {
  switch (stop_reason) {
    case AUTOBAL_TRANSIENT_STOP_END: return "end";
    case AUTOBAL_TRANSIENT_STOP_EVENT: return "event";
    case AUTOBAL_TRANSIENT_STOP_OBSERVER: return "observer";
    case AUTOBAL_TRANSIENT_STOP_CANCELLED: return "cancelled";
    case AUTOBAL_TRANSIENT_STOP_ERROR: return "error";
    default: return "none";
  }
}

/* ------------------------------------------------------------------------ */
/* The step                                                                 */
/* ------------------------------------------------------------------------ */

static double now_seconds(void) {
  struct timespec ts;
  if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) return 0.0;
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Record the failure of the adapters as AUTOBAL_ERHS. */
static int rhs_failure(autobal_transient *tr) {
  switch (tr->fail_kind) {
    case 1:
      return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                               "right-hand side returned %d at t = %.17g", tr->fail_code,
                               tr->fail_t);
    case 2:
      return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                               "right-hand side returned a non-finite value (component %zu) in "
                               "the step from t = %.17g",
                               tr->fail_index, tr->fail_t);
    case 3:
      return autobal_error_set(&tr->err, AUTOBAL_ERHS, "Jacobian returned %d at t = %.17g",
                               tr->fail_code, tr->fail_t);
    case 4:
      return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                               "Jacobian returned a non-finite value (entry %zu) at t = %.17g",
                               tr->fail_index, tr->fail_t);
    default:
      return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                               "GSL stepper reported a bad function (GSL_EBADFUNC)");
  }
}

/* dop853 with its own control (c->own_ctl) takes its steps on the user's right-hand side
 * directly, without rhs_adapter around each evaluation: count the step's evaluations and map a
 * non-zero return st of one of them as rhs_adapter does (the same statuses and records). */
static int direct_status(autobal_transient *tr, const void *state, int st) {
  unsigned nfev;
  double tf;
  autobal_transient_dop853_evals_(state, &nfev, &tf);
  tr->stats.rhs_evals += nfev;
  if (st == GSL_SUCCESS) return st;
  if (st == AUTOBAL_TRANSIENT_RHS_REJECT) {
    tr->reject_t = tf;
    tr->n_reject_calls++;
    return GSL_FAILURE;
  }
  if (tr->fail_kind == 0) {
    tr->fail_kind = 1;
    tr->fail_code = st;
    tr->fail_t = tf;
  }
  return GSL_EBADFUNC;
}

/* One accepted step of context c from (*t, y) towards t_target (> *t), never
 * past it; *h (> 0) is the trial step on entry and the suggested next step on
 * return.  The retry rules follow gsl_odeiv2_evolve_apply: a stepper failure
 * halves the step, an error estimate above tolerance shrinks it as the
 * control says, until the step no longer changes t (ESTEP) or falls below
 * h_min (ESTEP).  On success *t is advanced (to exactly t_target when the
 * step was cut to reach it); on failure y and *t are unchanged.  *rejected
 * is incremented per rejected trial step. */
static int take_step(autobal_transient *tr, stepper_ctx *c, double *t, double t_target, double *h,
                     double *y, unsigned long *rejected, double *h_taken) {
  const size_t n = tr->dim;
  gsl_odeiv2_step *s = c->d->s;
  const int use_in = s->type->can_use_dydt_in;
  const double t0 = *t;
  const double dt = t_target - t0;
  const double h_in = *h;
  double h0 = *h;
  unsigned long rej = 0;
  memcpy(c->y0, y, n * sizeof(double));
  if (use_in && !c->have_dydt) {
    int rc0 = rhs_checked(tr, t0, y, c->dydt_in);
    if (rc0 == GSL_FAILURE && tr->fail_kind == 0) /* a rejected accepted state: no shorter step helps */
      return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                               "the right-hand side rejected the state at t = %.17g (outside its "
                               "domain), the state the integration has reached",
                               t0);
    if (rc0 != GSL_SUCCESS) return rhs_failure(tr);
    c->have_dydt = 1;
  }
  for (;;) {
    int final_step, st, adj;
    double h_old;
    if (h0 >= dt) {
      h0 = dt;
      final_step = 1;
    } else {
      final_step = 0;
    }
    if (!final_step && tr->opt.h_min > 0.0 && h0 < tr->opt.h_min) {
      *rejected += rej;
      return autobal_error_set(&tr->err, AUTOBAL_ESTEP,
                               "step size %.6g needed at t = %.17g is below h_min = %.6g", h0, t0,
                               tr->opt.h_min);
    }
    if (c->own_ctl) { /* gsl_odeiv2_step_apply without its wrapper */
      st = s->type->apply(s->state, n, t0, h0, y, c->yerr, use_in ? c->dydt_in : NULL, c->dydt_out,
                          &tr->gsys_direct);
      st = direct_status(tr, s->state, st);
    } else {
      st = gsl_odeiv2_step_apply(s, t0, h0, y, c->yerr, use_in ? c->dydt_in : NULL, c->dydt_out,
                                 &tr->gsys);
    }
    if (st == GSL_EBADFUNC || tr->fail_kind != 0) {
      memcpy(y, c->y0, n * sizeof(double));
      *rejected += rej;
      return rhs_failure(tr);
    }
    if (st != GSL_SUCCESS) {
      /* the stepper could not compute the step (e.g. Newton iteration
       * failed): halve, as gsl_odeiv2_evolve_apply does */
      h_old = h0;
      h0 *= 0.5;
      memcpy(y, c->y0, n * sizeof(double));
      if (h0 < h_old && t0 + h0 != t0) {
        rej++;
        continue;
      }
      *rejected += rej;
      if (tr->n_reject_calls > 0 && tr->reject_t >= t0)
        return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                                 "the right-hand side rejected the state (outside its domain) at t = "
                                 "%.17g in every step from t = %.17g, down to the step %.6g",
                                 tr->reject_t, t0, h_old);
      return autobal_error_set(&tr->err, AUTOBAL_ESTEP,
                               "GSL stepper failed (%s) at t = %.17g with step %.6g, which can "
                               "not be reduced further",
                               gsl_strerror(st), t0, h_old);
    }
    if (c->own_ctl ? !autobal_transient_dop853_finite_(s->state)
                   : !all_finite3(y, c->yerr, s->type->gives_exact_dydt_out ? c->dydt_out : y, n)) {
      /* a stage derivative was NaN or inf (or the step overflowed); dydt_out
       * is tested only where it is reused as the next first stage */
      const double *bad = !all_finite(y, n) ? y : !all_finite(c->yerr, n) ? c->yerr : c->dydt_out;
      nonfinite_failure(tr, t0, bad);
      memcpy(y, c->y0, n * sizeof(double));
      *rejected += rej;
      return rhs_failure(tr);
    }
    h_old = h0;
    adj = c->own_ctl ? autobal_transient_dop853_hadjust_(s->state, &h0)
                     : gsl_odeiv2_control_hadjust(c->d->c, s, y, c->yerr, c->dydt_out, &h0);
    if (adj == GSL_ODEIV_HADJ_DEC) {
      memcpy(y, c->y0, n * sizeof(double));
      if (h0 < h_old && t0 + h0 != t0) {
        rej++;
        continue;
      }
      *rejected += rej;
      return autobal_error_set(&tr->err, AUTOBAL_ESTEP,
                               "step size underflow at t = %.17g: the error tolerance can not be "
                               "met with the smallest step that changes t (%.6g)",
                               t0, h_old);
    }
    /* accepted */
    *t = final_step ? t_target : t0 + h_old;
    *h_taken = h_old;
    if (!final_step)
      *h = h0;
    else
      *h = rej ? h0 : fmax(h_in, h0); /* a step cut short to land on t_target says little */
    *rejected += rej;
    if (s->type->gives_exact_dydt_out) {
      double *tmp = c->dydt_in;
      c->dydt_in = c->dydt_out;
      c->dydt_out = tmp;
      c->have_dydt = 1;
    } else {
      c->have_dydt = 0;
    }
    return AUTOBAL_SUCCESS;
  }
}

/* Reset a context for a fresh integration. */
static void ctx_reset(stepper_ctx *c) {
  gsl_odeiv2_step_reset(c->d->s);
  gsl_odeiv2_evolve_reset(c->d->e);
  c->have_dydt = 0;
}

/* Integrate with the auxiliary context from (ta, ya) to tb >= ta into yout
 * (adaptive, same stepper and tolerances; usually one step when tb - ta is
 * no longer than an accepted step).  fa (may be NULL): f(ta, ya), known to the
 * caller; a stepper that takes its first stage from outside then does not
 * evaluate it again (the same numbers: it is the same function at the same
 * point). */
static int aux_integrate(autobal_transient *tr, double ta, const double *ya, double tb,
                         double *yout, double h_hint, const double *fa) {
  double t = ta, h = tb - ta, h_taken = 0.0;
  unsigned long nsteps = 0, rej = 0;
  memcpy(yout, ya, tr->dim * sizeof(double));
  if (!(tb > ta)) return AUTOBAL_SUCCESS;
  ctx_reset(&tr->aux);
  if (fa && tr->aux.d->s->type->can_use_dydt_in) {
    memcpy(tr->aux.dydt_in, fa, tr->dim * sizeof(double));
    tr->aux.have_dydt = 1;
  }
  if (h_hint > 0.0 && h_hint < h) h = h_hint;
  if (tr->opt.h_max > 0.0 && h > tr->opt.h_max) h = tr->opt.h_max;
  while (t < tb) {
    int rc;
    if (tr->opt.h_max > 0.0 && h > tr->opt.h_max) h = tr->opt.h_max;
    rc = take_step(tr, &tr->aux, &t, tb, &h, yout, &rej, &h_taken);
    if (rc != AUTOBAL_SUCCESS) return rc;
    nsteps++;
    tr->stats.event_steps++;
    if (tr->opt.max_steps > 0 && nsteps >= tr->opt.max_steps && t < tb)
      return autobal_error_set(&tr->err, AUTOBAL_EMAXSTEPS,
                               "locating an event: %lu steps did not reach t = %.17g", nsteps,
                               tb);
  }
  return AUTOBAL_SUCCESS;
}

/* Value whose sign change is the event: g, or s - threshold for a dwell event. */
static int event_value(autobal_transient *tr, const event_item *e, double t, const double *y,
                       double *v) {
  double g = e->g(t, y, e->user);
  if (e->dwell) g -= e->threshold;
  if (isnan(g))
    return autobal_error_set(&tr->err, AUTOBAL_ENUMERIC,
                             "event function of event %ld returned NaN at t = %.17g",
                             (long)(e - tr->ev), t);
  *v = g;
  return AUTOBAL_SUCCESS;
}

static int sgn(double x) { return (x > 0.0) - (x < 0.0); }

/* ---- dense output (the main stepper's continuous extension) ------------------ */

/* The state at t in [t_prev, tn] of the last accepted step of the main stepper, on its
 * continuous extension (dop853: built at the first call of a step, 3 right-hand sides; with
 * dense_order = 6 none), into
 * out.  Returns AUTOBAL_SUCCESS or AUTOBAL_ERHS (a right-hand side failed or rejected the
 * state of an extra stage, or the interpolated state is not finite). */
#if defined(__GNUC__)
__attribute__((always_inline)) /* the output loop's call: no call overhead per output point */
#endif
static inline int dense_at(autobal_transient *tr, double t, double *out) {
  void *st = tr->main.d->s->state;
  double t0, h;
  /* order 6: nothing to prepare (its prepare only marks the extension ready) */
  if (tr->opt.dense_order != 6 && !autobal_transient_dop853_dense_ready_(st)) {
    int rc = autobal_transient_dop853_dense_prepare_(st, &tr->gsys);
    if (rc == GSL_FAILURE && tr->fail_kind == 0) {
      autobal_transient_dop853_last_step_(st, &t0, &h);
      return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                               "the right-hand side rejected the state (outside its domain) at a "
                               "stage of the continuous extension of the step from t = %.17g",
                               t0);
    }
    if (rc != GSL_SUCCESS || tr->fail_kind != 0) return rhs_failure(tr);
  }
  /* theta = (t - t0) / h clamped to [0, 1], the extension there and its finiteness, one call */
  if (!(tr->opt.dense_order == 6 ? tr->d6_at(st, t, out)
                                  : autobal_transient_dop853_dense_at_(st, t, out))) {
    nonfinite_failure(tr, t, out);
    return rhs_failure(tr);
  }
  return AUTOBAL_SUCCESS;
}

/* Locate the sign change of event e in (ta, tb] (tb <= the end of the last accepted step; values
 * ga at ta, gb at tb of different signs, or gb = 0) on the continuous extension: Illinois
 * (modified regula falsi) on g(t, u(t)) until the bracket is within event_tol; *t_hit is its far
 * end (g there already has the new sign or is 0).  No integration: each trial point is one
 * evaluation of the interpolant (pr_y) and of g. */

/* One Illinois step of a bracket [a, b] with values fa, fb of opposite signs at the trial point
 * c with value fc (a value exactly 0 counts as the near side a): the side that is kept twice has
 * its value halved (side: the side moved last, +1 b, -1 a, 0 none). */
static void illinois(double c, double fc, double *a, double *fa, double *b, double *fb, int *side) {
  if (fc != 0.0 && sgn(fc) == sgn(*fb)) {
    *b = c;
    *fb = fc;
    if (*side == 1) *fa *= 0.5;
    *side = 1;
  } else {
    *a = c;
    *fa = fc;
    if (*side == -1) *fb *= 0.5;
    *side = -1;
  }
}
static int locate_dense(autobal_transient *tr, const event_item *e, double ta, double ga, double tb,
                        double gb, double *t_hit) {
  /* the bracket closed to 1e-3 event_tol (at least a few ulps of t), as close to the crossing as
   * locate() puts its far point (its margin m): a hit up to event_tol late made dop853's runs
   * differ from the other steppers' in chains of near-simultaneous impacts, which pairs a reset
   * settles together depending on their gaps at the hit (data/washer_contact.ini at rtol 1e-11);
   * only interpolant evaluations, no integration */
  const double m = fmax(1e-3 * tr->opt.event_tol, 8.0 * DBL_EPSILON * fmax(fabs(ta), fabs(tb)));
  const double tol = 1e-3 * m;
  double a = ta, fa = ga, b = tb, fb = gb;
  int side = 0, iter, rc;
  for (iter = 0; iter < 200 && fb != 0.0 && b - a > tol; iter++) {
    double c = b - fb * (b - a) / (fb - fa), fc = 0.0;
    if (!(c > a && c < b)) c = a + 0.5 * (b - a);
    if (!(c > a && c < b)) break; /* a and b adjacent doubles */
    if ((rc = dense_at(tr, c, tr->pr_y)) != AUTOBAL_SUCCESS) return rc;
    if ((rc = event_value(tr, e, c, tr->pr_y, &fc)) != AUTOBAL_SUCCESS) return rc;
    /* a value exactly 0 counts as the near side, as in locate() */
    illinois(c, fc, &a, &fa, &b, &fb, &side);
  }
  *t_hit = b;
  if (fb != 0.0) { /* the hit m past the crossing, where locate() puts its far point */
    const double c = a + m;
    double fc = 0.0;
    if (c >= tb) {
      *t_hit = tb;
    } else if (c > b) {
      if ((rc = dense_at(tr, c, tr->pr_y)) != AUTOBAL_SUCCESS) return rc;
      if ((rc = event_value(tr, e, c, tr->pr_y, &fc)) != AUTOBAL_SUCCESS) return rc;
      if (fc != 0.0 && sgn(fc) == sgn(fb)) *t_hit = c;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* The derivatives at both ends of the accepted step (t_prev, y_prev) -> (tn, yn) into *fa, *fb: the
 * main stepper's own when it hands them over (f(tn) is the next step's first stage, f(t_prev) was
 * this one's), else two evaluations into pr_fa, pr_fb. */
static int step_ends(autobal_transient *tr, double t_prev, double tn, const double *yn, const double **fa,
                     const double **fb) {
  const gsl_odeiv2_step_type *T = tr->main.d->s->type;
  if (T->can_use_dydt_in && T->gives_exact_dydt_out && tr->main.have_dydt) {
    *fa = tr->main.dydt_out;
    *fb = tr->main.dydt_in;
    return AUTOBAL_SUCCESS;
  }
  if (rhs_checked(tr, t_prev, tr->y_prev, tr->pr_fa) != GSL_SUCCESS ||
      rhs_checked(tr, tn, yn, tr->pr_fb) != GSL_SUCCESS)
    return rhs_failure(tr);
  *fa = tr->pr_fa;
  *fb = tr->pr_fb;
  return AUTOBAL_SUCCESS;
}

/* A cubic Hermite segment: the states and derivatives y0, f0 at t0 and y1, f1 at t1 (t0 < t1). */
typedef struct hseg {
  double t0, t1;
  const double *y0, *f0, *y1, *f1;
} hseg;

/* The cubic Hermite interpolant of the segment at t, into out. */
static void hermite(const autobal_transient *tr, const hseg *sg, double t, double *out) {
  const double h = sg->t1 - sg->t0, th = (t - sg->t0) / h, th2 = th * th, th3 = th2 * th;
  const double h00 = 2.0 * th3 - 3.0 * th2 + 1.0, h10 = (th3 - 2.0 * th2 + th) * h;
  const double h01 = -2.0 * th3 + 3.0 * th2, h11 = (th3 - th2) * h;
  const double *y0 = sg->y0, *f0 = sg->f0, *y1 = sg->y1, *f1 = sg->f1;
  size_t i;
  for (i = 0; i < tr->dim; i++) out[i] = h00 * y0[i] + h10 * f0[i] + h01 * y1[i] + h11 * f1[i];
}

/* After the probes of event e found no crossing in the step (t_prev, t_prev + h), its values gs[0]
 * (t_prev), gs[1..n] (the n probes) and g at the end: a crossing narrower than the probes' spacing
 * shows as a sampled extremum towards 0 (a maximum when g_prev < 0).  At every interior sample that
 * is such an extremum and whose parabola through it and its neighbours comes within the sampled
 * prominence of 0 (or crosses it), the extremum is searched between the neighbours (golden section,
 * at most 40 evaluations, down to event_tol): dense output, on the continuous extension (the
 * solution there), the first point past 0 in a watched direction is returned (*found = 1, *tc,
 * *gc); exact output, on the cubic Hermite interpolant of the step (as the probes), whose maximum
 * (or first point past 0) only points the place: g there on the state integrated from the step's
 * start (aux_integrate, one step of the same stepper and tolerances) decides, as the probes'
 * confirmation does (one integration per searched extremum, not one per trial point).
 * Without this a stuck ball's |H| briefly above mu N (a slip of 0.2 ms in a step of 1.8 ms,
 * data/washer_contact.ini at rtol 1e-12) fell between dop853's probes and the run went on along
 * another branch (dense output before 0.2.0, exact output until this search was shared). */
static int probe_extremum(autobal_transient *tr, event_item *e, double t_prev, double h, double *gs, double tn,
                          const double *yn, const double *fa, const double *fb, double *tc, double *gc, int *found) {
  const unsigned n = e->probes;
  const double s = e->g_prev < 0.0 ? 1.0 : -1.0; /* s g rises towards 0 at a crossing */
  const double d = h / (double)(n + 1), phi = 0.6180339887498949;
  unsigned k;
  int rc;
  if ((s > 0.0 && e->direction == -1) || (s < 0.0 && e->direction == 1)) return AUTOBAL_SUCCESS;
  if ((rc = event_value(tr, e, tn, yn, &gs[n + 1])) != AUTOBAL_SUCCESS) return rc;
  for (k = 1; k <= n; k++) {
    const double a = s * gs[k - 1], b = s * gs[k], c = s * gs[k + 1], den = a - 2.0 * b + c;
    const double vert = den < 0.0 ? b - (a - c) * (a - c) / (8.0 * den) : b, prom = b - fmin(a, c);
    double lo, hi, x1, x2, f1 = 0.0, f2 = 0.0, g = 0.0, x_best = 0.0, f_best = -INFINITY;
    int m, past = 0;
    if (!(b >= a && b >= c) || vert < -prom) continue; /* no extremum, or one far from 0 */
    lo = t_prev + (double)(k - 1) * d;
    hi = k + 1 == n + 1 ? tn : t_prev + (double)(k + 1) * d;
    x1 = hi - phi * (hi - lo);
    x2 = lo + phi * (hi - lo);
    for (m = 0; m < 40 && !past; m++) {
      /* evaluate the new point(s): both at the start, then the one golden section adds */
      const int both = m == 0;
      int w;
      for (w = 0; w < (both ? 2 : 1); w++) {
        const double x = both ? (w == 0 ? x1 : x2) : (f1 == -INFINITY ? x1 : x2);
        if (tr->dense) {
          if ((rc = dense_at(tr, x, tr->pr_y)) != AUTOBAL_SUCCESS) return rc;
        } else {
          const hseg sg = {t_prev, tn, tr->y_prev, fa, yn, fb};
          hermite(tr, &sg, x, tr->pr_y);
        }
        if ((rc = event_value(tr, e, x, tr->pr_y, &g)) != AUTOBAL_SUCCESS) return rc;
        if (s * g > f_best) {
          f_best = s * g;
          x_best = x;
        }
        if (s * g >= 0.0) { /* past 0: the crossing lies in (t_prev, x] */
          if (!tr->dense) { /* to confirm below */
            past = 1;
            break;
          }
          *tc = x;
          *gc = g;
          *found = 1;
          return AUTOBAL_SUCCESS;
        }
        if (x == x1) f1 = s * g;
        else f2 = s * g;
      }
      if (past || hi - lo <= tr->opt.event_tol) break;
      if (f1 > f2) { /* the maximum of s g in [lo, x2] */
        hi = x2;
        x2 = x1;
        f2 = f1;
        x1 = hi - phi * (hi - lo);
        f1 = -INFINITY; /* to evaluate */
      } else {
        lo = x1;
        x1 = x2;
        f1 = f2;
        x2 = lo + phi * (hi - lo);
        f2 = -INFINITY;
      }
      if (!(x1 > lo && x2 < hi && x1 <= x2)) break; /* adjacent doubles */
    }
    if (!tr->dense && f_best > -INFINITY) { /* g on the integrated state where the cubic peaks */
      if ((rc = aux_integrate(tr, t_prev, tr->y_prev, x_best, tr->pr_y, h, fa)) != AUTOBAL_SUCCESS) return rc;
      if ((rc = event_value(tr, e, x_best, tr->pr_y, &g)) != AUTOBAL_SUCCESS) return rc;
      if (s * g >= 0.0) {
        *tc = x_best;
        *gc = g;
        *found = 1;
        return AUTOBAL_SUCCESS;
      }
    }
  }
  return AUTOBAL_SUCCESS;
}

/* Probe event e for a grazing crossing inside the accepted step (t_prev, y_prev) -> (tn, yn), its
 * values g_prev and gn of one sign: g on the cubic Hermite interpolant of the state at e->probes
 * interior points; the first point past 0 (in a watched direction) is checked on the integrated
 * state and, if confirmed, bracketed with t_prev for locate.  *found = 1 with *tc, *gc then. */
static int probe(autobal_transient *tr, event_item *e, double t_prev, double tn, const double *yn,
                 const double **fa, const double **fb, double *tc, double *gc, int *found) {
  const double h = tn - t_prev;
  /* the interpolated states at the probe points are shared by the events with the same number of
   * probes in this step (pc_n: that number, 0 until the first probe of the step) */
  const int shared = e->probes <= tr->pc_cap && (tr->pc_n == 0 || tr->pc_n == e->probes);
  unsigned k;
  int rc;
  double gs[66]; /* g at t_prev, the probe points and tn (the extremum search below) */
  *found = 0;
  gs[0] = e->g_prev;
  if (!tr->dense && !*fa && (rc = step_ends(tr, t_prev, tn, yn, fa, fb)) != AUTOBAL_SUCCESS) return rc;
  if (shared && tr->pc_n == 0) {
    tr->pc_n = e->probes;
    memset(tr->pc_valid, 0, sizeof tr->pc_valid);
  }
  for (k = 1; k <= e->probes; k++) {
    const double t = t_prev + (double)k / (double)(e->probes + 1) * h;
    double g = 0.0, *yk = shared ? tr->pc_y + (size_t)(k - 1) * tr->dim : tr->pr_y;
    if (!shared || !tr->pc_valid[k - 1]) {
      if (tr->dense) {
        if ((rc = dense_at(tr, t, yk)) != AUTOBAL_SUCCESS) return rc;
      } else {
        const hseg sg = {t_prev, tn, tr->y_prev, *fa, yn, *fb};
        hermite(tr, &sg, t, yk);
      }
      if (shared) tr->pc_valid[k - 1] = 1;
    }
    if ((rc = event_value(tr, e, t, yk, &g)) != AUTOBAL_SUCCESS) return rc;
    gs[k] = g;
    if (!((e->g_prev < 0.0 && g >= 0.0 && e->direction != -1) || (e->g_prev > 0.0 && g <= 0.0 && e->direction != 1)))
      continue;
    if (tr->dense) { /* the continuous extension is the solution: nothing to confirm */
      *tc = t;
      *gc = g;
      *found = 1;
      return AUTOBAL_SUCCESS;
    }
    /* confirm on the integrated state */
    if ((rc = aux_integrate(tr, t_prev, tr->y_prev, t, tr->y_evt, h, *fa)) != AUTOBAL_SUCCESS) return rc;
    if ((rc = event_value(tr, e, t, tr->y_evt, &g)) != AUTOBAL_SUCCESS) return rc;
    if ((e->g_prev < 0.0 && g >= 0.0) || (e->g_prev > 0.0 && g <= 0.0)) {
      *tc = t;
      *gc = g;
      *found = 1;
      return AUTOBAL_SUCCESS;
    }
  }
  return probe_extremum(tr, e, t_prev, h, gs, tn, yn, *fa, *fb, tc, gc, found);
}

static double output_time(const autobal_transient *tr, double t0, double t1, unsigned long k);

/* Dense output: event e (its values g_prev and gn of one sign at the step's ends) at the output
 * times strictly inside the accepted step (t_prev, tn), on the continuous extension (the states
 * that will be emitted there): the first one past 0 in a watched direction gives *tc, *gc and
 * *found = 1 (a crossing that the step's ends missed, which an output would otherwise show, e.g.
 * two balls overlapping at an output point).  Nothing is emitted here. */
static int probe_outputs(autobal_transient *tr, event_item *e, double tn, double *tc, double *gc, int *found) {
  unsigned long k = tr->k_out;
  double to = tr->t_out;
  int rc;
  *found = 0;
  while (to < tn) {
    double g = 0.0;
    if ((rc = dense_at(tr, to, tr->pr_y)) != AUTOBAL_SUCCESS) return rc;
    if ((rc = event_value(tr, e, to, tr->pr_y, &g)) != AUTOBAL_SUCCESS) return rc;
    if ((e->g_prev < 0.0 && g >= 0.0 && e->direction != -1) || (e->g_prev > 0.0 && g <= 0.0 && e->direction != 1)) {
      *tc = to;
      *gc = g;
      *found = 1;
      return AUTOBAL_SUCCESS;
    }
    if (to >= tr->t1_run) break;
    k++;
    to = output_time(tr, tr->t0_run, tr->t1_run, k);
  }
  return AUTOBAL_SUCCESS;
}

/* Event value on a Hermite segment at t (no integration); *ok = 0 when it is NaN. */
static double interp_value(autobal_transient *tr, const event_item *e, const hseg *sg, double t, int *ok) {
  double g;
  hermite(tr, sg, t, tr->pr_y);
  g = e->g(t, tr->pr_y, e->user);
  if (e->dwell) g -= e->threshold;
  *ok = !isnan(g);
  return g;
}

/* The crossing of g(interpolant(t)) in (a, b) (a Hermite segment containing [a, b]), the far side
 * the sign of far: Illinois iteration to a bracket far below event_tol, cheap (no integration); the
 * midpoint of that bracket in *ts.  *found = 0 when g on the segment does not change sign between
 * a and b (or is NaN there). */
static void interp_root(autobal_transient *tr, const event_item *e, const hseg *sg, double a, double b, double far,
                        double *ts, int *found) {
  const double tol = 1e-5 * tr->opt.event_tol;
  double fa, fb;
  int side = 0, iter, ok_a, ok_b;
  *found = 0;
  fa = interp_value(tr, e, sg, a, &ok_a);
  fb = interp_value(tr, e, sg, b, &ok_b);
  if (!ok_a || !ok_b || fb == 0.0 || sgn(fb) != sgn(far) || (fa != 0.0 && sgn(fa) == sgn(far))) return;
  for (iter = 0; iter < 100 && b - a > tol; iter++) {
    double c = b - fb * (b - a) / (fb - fa), fc;
    int ok;
    if (!(c > a && c < b)) c = a + 0.5 * (b - a);
    if (!(c > a && c < b)) break;
    fc = interp_value(tr, e, sg, c, &ok);
    if (!ok) return;
    illinois(c, fc, &a, &fa, &b, &fb, &side);
  }
  *ts = a + 0.5 * (b - a);
  *found = 1;
}

/* A short hop: one classical Runge-Kutta step (4th order) from an integrated point (tp, yp, fp) to
 * tc = tp + d (d of either sign, |d| at most 1e-3 of the accepted step, where its local error,
 * O(d^5), is far below the stepper's), into yc, with f(tc, yc) into fc (4 evaluations).  Returns
 * GSL_SUCCESS or the right-hand side's failure (then yc is not valid). */
static int hop(autobal_transient *tr, double tp, const double *yp, const double *fp, double tc, double *yc,
               double *fc) {
  const size_t n = tr->dim;
  const double d = tc - tp;
  double *k2 = tr->loc + 4 * n, *k3 = k2 + n, *k4 = k3 + n, *yt = k4 + n;
  size_t i;
  int rc;
  for (i = 0; i < n; i++) yt[i] = yp[i] + 0.5 * d * fp[i];
  if ((rc = rhs_checked(tr, tp + 0.5 * d, yt, k2)) != GSL_SUCCESS) return rc;
  for (i = 0; i < n; i++) yt[i] = yp[i] + 0.5 * d * k2[i];
  if ((rc = rhs_checked(tr, tp + 0.5 * d, yt, k3)) != GSL_SUCCESS) return rc;
  for (i = 0; i < n; i++) yt[i] = yp[i] + d * k3[i];
  if ((rc = rhs_checked(tr, tc, yt, k4)) != GSL_SUCCESS) return rc;
  for (i = 0; i < n; i++) yc[i] = yp[i] + d / 6.0 * (fp[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  return rhs_checked(tr, tc, yc, fc);
}

/* Locate the sign change of event e in (ta, tb], with values ga (at ta = t_prev, the start of the
 * accepted step (t_prev, y_prev) -> (tn, yn), state ya = y_prev) and gb (at tb <= tn, non-zero sign
 * different from ga, or 0).  *fpa, *fpb: the step's end derivatives (NULL until step_ends gives
 * them).  Every trial point is integrated; *t_hit is on the far side of the crossing, within
 * event_tol of it.
 * The trial points follow an estimate ts of the crossing: the root of g on a cubic Hermite segment
 * between two integrated points with their derivatives, at first the accepted step itself, then the
 * last trial points on either side of the crossing (the segment shrinks onto it, and its error, of
 * order (length)^4, with it).  The first trial point is ts itself, integrated from (ta, ya) by the
 * stepper (its derivative there comes with the step when the stepper gives it); each later one is
 * put just across the new estimate from the trial point before, by a margin m (1e-3 event_tol, at
 * least a few ulps of t; tenfold whenever a trial point lands on the same side as the one before),
 * so that two trial points close the bracket once the estimate is good to event_tol (typically the
 * third point).  A later trial point within 1e-3 of the accepted step from the last one is reached
 * by a short hop from it (one classical Runge-Kutta step, 4 evaluations, local error O(d^5) far
 * below the stepper's), else integrated from (ta, ya) by the stepper.  Illinois iteration on the
 * integrated g finishes in whatever bracket is left (the whole (ta, tb] if the segment gave
 * nothing, or after 8 guided points).  The integrated state at the last far-side point is kept in
 * y_hit (hit_t, hit_valid), so that the caller need not integrate to *t_hit again. */
static int locate(autobal_transient *tr, const event_item *e, double ta, const double *ya, double ga,
                  double tb, double gb, double h_hint, double tn, const double *yn, const double **fpa,
                  const double **fpb, double *t_hit) {
  const size_t n = tr->dim;
  const double tol = tr->opt.event_tol;
  double a = ta, fa = ga, b = tb, fb = gb, ts = 0.0, m, tp = ta;
  /* node buffers: [0] near side, [1] far side (state, derivative); the last trial point's index */
  double *ny[2] = {tr->loc, tr->loc + 2 * n}, *nf[2] = {tr->loc + n, tr->loc + 3 * n};
  hseg sg;
  int side = 0, iter, found = 0, nguided = 0, last = 0, rc, have_p = 0;
  if (fb == 0.0) {
    *t_hit = tb;
    return AUTOBAL_SUCCESS;
  }
  m = fmax(1e-3 * tol, 8.0 * DBL_EPSILON * fmax(fabs(ta), fabs(tb)));
  if (b - a > tol) {
    if (!*fpa && (rc = step_ends(tr, ta, tn, yn, fpa, fpb)) != AUTOBAL_SUCCESS) return rc;
    sg.t0 = ta, sg.y0 = ya, sg.f0 = *fpa, sg.t1 = tn, sg.y1 = yn, sg.f1 = *fpb;
    interp_root(tr, e, &sg, a, b, gb, &ts, &found);
  }
  for (iter = 0; iter < 200 && b - a > tol; iter++) {
    double c, fc = 0.0;
    const double *fcd = NULL; /* f(c, y(c)) when known */
    int guided = 0, far, hopped = 0;
    if (found && nguided < 8) {
      /* the estimate, then just across it from the last trial point */
      c = last == 0 ? ts : last > 0 ? ts - m : ts + m;
      if (!(c > a && c < b)) c = a + 0.5 * (b - a);
      if (!(c > a && c < b)) break; /* a and b adjacent doubles */
      guided = 1;
      nguided++;
    } else {
      c = b - fb * (b - a) / (fb - fa);
      if (!(c > a && c < b)) c = a + 0.5 * (b - a);
      if (!(c > a && c < b)) break; /* a and b adjacent doubles */
    }
    if (guided && have_p && fabs(c - tp) <= 1e-3 * h_hint) {
      /* the node the hop starts from is the last trial point; the new point goes to the other
       * node's buffer only if it lands on that side, so hop into y_work and copy after */
      const int pi = last > 0 ? 1 : 0;
      rc = hop(tr, tp, ny[pi], nf[pi], c, tr->y_work, tr->loc + 8 * n);
      if (rc == GSL_SUCCESS) {
        hopped = 1;
        fcd = tr->loc + 8 * n;
        tr->stats.event_steps++;
      } else if (!(rc == GSL_FAILURE && tr->fail_kind == 0)) {
        return rhs_failure(tr);
      }
    }
    if (!hopped) {
      const gsl_odeiv2_step_type *T = tr->aux.d->s->type;
      rc = aux_integrate(tr, ta, ya, c, tr->y_work, h_hint, *fpa);
      if (rc != AUTOBAL_SUCCESS) return rc;
      if (guided) {
        if (T->gives_exact_dydt_out && tr->aux.have_dydt) {
          fcd = tr->aux.dydt_in; /* f at the step's end (take_step swapped it in) */
        } else {
          if (rhs_checked(tr, c, tr->y_work, tr->loc + 8 * n) != GSL_SUCCESS) return rhs_failure(tr);
          fcd = tr->loc + 8 * n;
        }
      }
    }
    if ((rc = event_value(tr, e, c, tr->y_work, &fc)) != AUTOBAL_SUCCESS) return rc;
    /* a value exactly 0 counts as the near side: the hit stays strictly past the crossing, where
     * the reset sees the new sign (a stuck ball's |H| - mu N exactly 0 would not break it free) */
    far = fc != 0.0 && sgn(fc) == sgn(fb);
    if (far) {
      b = c;
      fb = fc;
      memcpy(tr->y_hit, tr->y_work, n * sizeof(double));
      tr->hit_t = c;
      tr->hit_valid = 1;
      if (side == 1 && !guided) fa *= 0.5;
      side = guided ? 0 : 1;
    } else {
      a = c;
      fa = fc;
      if (side == -1 && !guided) fb *= 0.5;
      side = guided ? 0 : -1;
    }
    if (guided) {
      const int now = far ? 1 : -1, k = far ? 1 : 0;
      if (last == now) m *= 10.0; /* the estimate was off by more than m */
      last = now;
      /* the new point becomes the segment's node on its side */
      memcpy(ny[k], tr->y_work, n * sizeof(double));
      memcpy(nf[k], fcd, n * sizeof(double));
      tp = c;
      have_p = 1;
      if (far) sg.t1 = c, sg.y1 = ny[1], sg.f1 = nf[1];
      else sg.t0 = c, sg.y0 = ny[0], sg.f0 = nf[0];
      if (b - a > tol) {
        int ok;
        double ts_new = ts;
        interp_root(tr, e, &sg, a, b, gb, &ts_new, &ok);
        if (ok) ts = ts_new;
        else found = 0; /* Illinois from here */
      }
    }
  }
  *t_hit = b;
  return AUTOBAL_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* run                                                                      */
/* ------------------------------------------------------------------------ */

/* Automatic first step (Hairer, Norsett & Wanner, Solving ODEs I, II.4),
 * with the max norm of GSL's control.  Leaves f(t0, y0) in main.dydt_in. */
static int initial_step(autobal_transient *tr, double t0, const double *y0, double span,
                        double *h_out) {
  const size_t n = tr->dim;
  const double atol = tr->opt.atol, rtol = tr->opt.rtol;
  double *f0 = tr->main.dydt_in, *f1 = tr->main.dydt_out, *y1 = tr->y_work;
  double d0 = 0.0, d1 = 0.0, d2 = 0.0, h0, h1, dmax;
  *h_out = 0.0;
  unsigned int p;
  size_t i;
  int rc, tries = 0;
  rc = rhs_checked(tr, t0, y0, f0);
  if (rc == GSL_FAILURE && tr->fail_kind == 0)
    return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                             "the right-hand side rejected the initial state at t = %.17g (outside its "
                             "domain)",
                             t0);
  if (rc != GSL_SUCCESS) return rhs_failure(tr);
  tr->main.have_dydt = 1;
  for (i = 0; i < n; i++) {
    const double sc = atol + rtol * fabs(y0[i]);
    d0 = fmax(d0, fabs(y0[i]) / sc);
    d1 = fmax(d1, fabs(f0[i]) / sc);
  }
  h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  h0 = fmin(h0, span);
  /* the Euler probe may leave the system's domain (AUTOBAL_TRANSIENT_RHS_REJECT): shorten it */
  for (;;) {
    for (i = 0; i < n; i++) y1[i] = y0[i] + h0 * f0[i];
    rc = rhs_checked(tr, t0 + h0, y1, f1);
    if (rc == GSL_FAILURE && tr->fail_kind == 0 && ++tries <= 40 && t0 + 0.1 * h0 != t0) {
      h0 *= 0.1;
      continue;
    }
    break;
  }
  if (rc == GSL_FAILURE && tr->fail_kind == 0)
    return autobal_error_set(&tr->err, AUTOBAL_ERHS,
                             "the right-hand side rejected every probe of the first step from t = %.17g "
                             "(outside its domain), down to %.6g",
                             t0, h0);
  if (rc != GSL_SUCCESS) return rhs_failure(tr);
  for (i = 0; i < n; i++) {
    const double sc = atol + rtol * fabs(y0[i]);
    d2 = fmax(d2, fabs(f1[i] - f0[i]) / sc);
  }
  d2 /= h0;
  p = gsl_odeiv2_step_order(tr->main.d->s);
  if (p < 1) p = 1;
  dmax = fmax(d1, d2);
  h1 = dmax <= 1e-15 ? fmax(1e-6, 1e-3 * h0) : pow(0.01 / dmax, 1.0 / (double)(p + 1));
  *h_out = fmin(100.0 * h0, h1);
  return AUTOBAL_SUCCESS;
}

static void insertion_sort_pending(autobal_transient *tr, size_t np) {
  size_t i, j;
  for (i = 1; i < np; i++) {
    size_t k = tr->order[i];
    j = i;
    while (j > 0 && tr->ev[tr->order[j - 1]].t_hit > tr->ev[k].t_hit) {
      tr->order[j] = tr->order[j - 1];
      j--;
    }
    tr->order[j] = k;
  }
}

/* Output time number k (k >= 1), clamped to t1 near the end. */
static double output_time(const autobal_transient *tr, double t0, double t1, unsigned long k) {
  double to;
  if (tr->opt.dt_out <= 0.0) return t1;
  to = t0 + (double)k * tr->opt.dt_out;
  if (to > t1 - 1e-9 * tr->opt.dt_out) to = t1;
  return to;
}

/* Finish: fill the statistics, return status. */
static int finish(autobal_transient *tr, int status, int reason, double t, double *t_reached,
                  double wall0) {
  tr->stats.status = status;
  tr->stats.stop_reason = reason;
  tr->stats.t_end = t;
  tr->stats.wall_seconds = now_seconds() - wall0;
  if (tr->stats.h_min_used == INFINITY) tr->stats.h_min_used = 0.0;
  if (t_reached) *t_reached = t;
  if (status == AUTOBAL_SUCCESS) autobal_error_clear(&tr->err);
  tr->err.status = status;
  return status;
}

/* After an event reset at (t, y): check the state, count the reset (a run of
 * more than 1000 within event_tol of each other is chattering), discard the
 * stepper's history and re-evaluate every event function at the new state.
 * Returns RESTARTED or a failure. */
enum { RESTARTED = 1000 };
static int reset_restart(autobal_transient *tr, double t, const double *y) {
  size_t i;
  int rc;
  for (i = 0; i < tr->dim; i++)
    if (!isfinite(y[i]))
      return autobal_error_set(&tr->err, AUTOBAL_ENUMERIC,
                               "the event reset at t = %.17g made state component %zu non-finite",
                               t, i);
  tr->stats.resets++;
  if (tr->stats.resets > 1 && t - tr->t_reset <= tr->opt.event_tol) {
    if (++tr->reset_run > 1000)
      return autobal_error_set(&tr->err, AUTOBAL_ESTEP,
                               "more than 1000 event resets in a row, each within event_tol = "
                               "%.3g of the previous one, at t = %.17g (chattering: the events "
                               "accumulate at a point)",
                               tr->opt.event_tol, t);
  } else {
    tr->reset_run = 0;
  }
  tr->t_reset = t;
  ctx_reset(&tr->main);
  for (i = 0; i < tr->nev; i++) {
    event_item *e = &tr->ev[i];
    double g = 0.0;
    e->pending = 0;
    if (e->dwell && e->dwell_state == DWELL_FIRED) continue;
    if ((rc = event_value(tr, e, t, y, &g)) != AUTOBAL_SUCCESS) return rc;
    if (!e->dwell && g == 0.0) {
      /* g is exactly 0 at the reset (a velocity set to 0, a position put on a wall): its
       * sign just after the reset decides the next crossing (as CVODE's root finding does),
       * else a function that leaves 0 and comes back within one step would be missed */
      const double ts = t + fmax(tr->opt.event_tol, 4.0 * DBL_EPSILON * fabs(t));
      if ((rc = aux_integrate(tr, t, y, ts, tr->y_work, 0.0, NULL)) != AUTOBAL_SUCCESS) return rc;
      if ((rc = event_value(tr, e, ts, tr->y_work, &g)) != AUTOBAL_SUCCESS) return rc;
    }
    if (e->dwell) {
      if (e->dwell_state == DWELL_ABOVE && g < 0.0) {
        e->dwell_state = DWELL_BELOW;
        e->t_enter = t;
      } else if (e->dwell_state == DWELL_BELOW && g >= 0.0) {
        e->dwell_state = DWELL_ABOVE;
      }
    }
    e->g_prev = g;
  }
  return RESTARTED;
}

/* Dense mode: the observer at every output time t_out < t_upto (also = t_upto when incl) not yet
 * reported, in the last accepted step (its end (tn, yn)), the state interpolated on the
 * continuous extension (yn itself at tn; nothing interpolated without an observer).  Returns
 * AUTOBAL_SUCCESS, OBSERVER_STOP (the observer asked to stop: the state in y_out, its time in
 * *t_stop) or a failure. */
enum { OBSERVER_STOP = 1001 };
#if defined(__GNUC__)
__attribute__((always_inline)) /* one call site per step with an output time: no call overhead */
#endif
static inline int emit_outputs(autobal_transient *tr, double t_upto, int incl, double tn, const double *yn,
                               double *t_stop) {
  while (tr->t_out < t_upto || (incl && tr->t_out == t_upto)) {
    const double to = tr->t_out;
    if (tr->observer) {
      int uc, rc;
      if (to == tn) {
        memcpy(tr->y_out, yn, tr->dim * sizeof(double));
      } else if ((rc = dense_at(tr, to, tr->y_out)) != AUTOBAL_SUCCESS) {
        return rc;
      }
      uc = tr->observer(to, tr->y_out, tr->observer_user);
      tr->stats.observer_calls++;
      if (uc != 0) {
        tr->stats.user_code = uc;
        *t_stop = to;
        tr->k_out++;
        tr->t_out = to >= tr->t1_run ? INFINITY : output_time(tr, tr->t0_run, tr->t1_run, tr->k_out);
        return OBSERVER_STOP;
      }
    }
    tr->k_out++;
    tr->t_out = to >= tr->t1_run ? INFINITY : output_time(tr, tr->t0_run, tr->t1_run, tr->k_out);
  }
  return AUTOBAL_SUCCESS;
}

/* Process the events of the accepted step (t_prev, y_prev) -> (*t, y).
 * Returns AUTOBAL_SUCCESS (continue), RESTARTED (an event reset the state: y
 * and *t hold it, the stepper starts afresh there), AUTOBAL_EVENT (stop; y and
 * *t hold the event state) or a failure. */
static int process_events(autobal_transient *tr, double t_prev, double *t, double *y,
                          double h_taken) {
  const double tn = *t;
  const double *fa = NULL, *fb = NULL; /* the step's end derivatives, once a probe needs them */
  size_t i, np = 0;
  int rc;
  tr->hit_valid = 0;
  tr->pc_n = 0; /* no probe state of this step yet */
  for (i = 0; i < tr->nev; i++) {
    event_item *e = &tr->ev[i];
    double gn = 0.0;
    e->pending = 0;
    if (e->dwell && e->dwell_state == DWELL_FIRED) continue;
    if ((rc = event_value(tr, e, tn, y, &gn)) != AUTOBAL_SUCCESS) return rc;
    if (!e->dwell) {
      const int rising = e->g_prev < 0.0 && gn >= 0.0;
      const int falling = e->g_prev > 0.0 && gn <= 0.0;
      if ((rising && e->direction != -1) || (falling && e->direction != 1)) {
        rc = tr->dense ? locate_dense(tr, e, t_prev, e->g_prev, tn, gn, &e->t_hit)
                       : locate(tr, e, t_prev, tr->y_prev, e->g_prev, tn, gn, h_taken, tn, y, &fa, &fb, &e->t_hit);
        if (rc != AUTOBAL_SUCCESS) return rc;
        e->t_start = e->t_hit;
        e->dir_hit = rising ? 1 : -1;
        e->pending = 1;
      } else if (e->probes > 0 && sgn(gn) == sgn(e->g_prev) && gn != 0.0) {
        double tc = tn, gc = gn;
        int found = 0;
        if ((rc = probe(tr, e, t_prev, tn, y, &fa, &fb, &tc, &gc, &found)) != AUTOBAL_SUCCESS) return rc;
        if (found) { /* a grazing crossing: located in (t_prev, tc] */
          tr->stats_probe_hits++;
          rc = tr->dense ? locate_dense(tr, e, t_prev, e->g_prev, tc, gc, &e->t_hit)
                         : locate(tr, e, t_prev, tr->y_prev, e->g_prev, tc, gc, h_taken, tn, y, &fa, &fb, &e->t_hit);
          if (rc != AUTOBAL_SUCCESS) return rc;
          e->t_start = e->t_hit;
          e->dir_hit = e->g_prev < 0.0 ? 1 : -1;
          e->pending = 1;
        }
      }
      if (!e->pending && e->at_outputs && tr->dense && tr->t_out < tn && sgn(gn) == sgn(e->g_prev) && gn != 0.0) {
        double tc = tn, gc = gn;
        int found = 0;
        if ((rc = probe_outputs(tr, e, tn, &tc, &gc, &found)) != AUTOBAL_SUCCESS) return rc;
        if (found) { /* a crossing that an output point would have shown: located in (t_prev, tc] */
          tr->stats_probe_hits++;
          if ((rc = locate_dense(tr, e, t_prev, e->g_prev, tc, gc, &e->t_hit)) != AUTOBAL_SUCCESS) return rc;
          e->t_start = e->t_hit;
          e->dir_hit = e->g_prev < 0.0 ? 1 : -1;
          e->pending = 1;
        }
      }
    } else {
      if (e->dwell_state == DWELL_ABOVE && gn < 0.0) {
        double tc;
        rc = tr->dense ? locate_dense(tr, e, t_prev, e->g_prev, tn, gn, &tc)
                       : locate(tr, e, t_prev, tr->y_prev, e->g_prev, tn, gn, h_taken, tn, y, &fa, &fb, &tc);
        if (rc != AUTOBAL_SUCCESS) return rc;
        e->dwell_state = DWELL_BELOW;
        e->t_enter = tc;
      } else if (e->dwell_state == DWELL_BELOW && gn >= 0.0) {
        e->dwell_state = DWELL_ABOVE;
      }
      if (e->dwell_state == DWELL_BELOW && tn >= e->t_enter + e->duration) {
        e->t_hit = fmax(e->t_enter + e->duration, t_prev);
        if (e->t_hit > tn) e->t_hit = tn;
        e->t_start = e->t_enter;
        e->dir_hit = -1;
        e->pending = 1;
      }
    }
    e->g_prev = gn;
    if (e->pending) tr->order[np++] = i;
  }
  if (np == 0) return AUTOBAL_SUCCESS;
  insertion_sort_pending(tr, np);
  for (i = 0; i < np; i++) {
    event_item *e = &tr->ev[tr->order[i]];
    autobal_transient_event_hit hit;
    int stop;
    double *ys;
    if (tr->dense) {
      double t_stop = 0.0;
      rc = emit_outputs(tr, e->t_hit, 0, tn, y, &t_stop);
      if (rc == OBSERVER_STOP) {
        memcpy(y, tr->y_out, tr->dim * sizeof(double));
        *t = t_stop;
      }
      if (rc != AUTOBAL_SUCCESS) return rc;
    }
    if (e->t_hit >= tn) {
      ys = y;
    } else if (tr->dense) {
      if ((rc = dense_at(tr, e->t_hit, tr->y_evt)) != AUTOBAL_SUCCESS) return rc;
      ys = tr->y_evt;
    } else if (tr->hit_valid && e->t_hit == tr->hit_t) { /* locate integrated to it already */
      memcpy(tr->y_evt, tr->y_hit, tr->dim * sizeof(double));
      ys = tr->y_evt;
    } else {
      rc = aux_integrate(tr, t_prev, tr->y_prev, e->t_hit, tr->y_evt, h_taken, fa);
      if (rc != AUTOBAL_SUCCESS) return rc;
      ys = tr->y_evt;
    }
    hit.index = tr->order[i];
    hit.t = e->t_hit;
    hit.t_start = e->t_start;
    hit.direction = e->dir_hit;
    hit.terminal = e->terminal;
    if (e->dwell) e->dwell_state = DWELL_FIRED;
    stop = e->terminal;
    if (tr->handler) {
      int uc = tr->handler(&hit, ys, tr->handler_user);
      if (uc != 0) {
        stop = 1;
        tr->stats.user_code = uc;
      }
    }
    if (!stop && tr->reset) {
      /* ys is y or tr->y_evt: both writable */
      int uc = tr->reset(&hit, ys, tr->reset_user);
      if (uc == AUTOBAL_TRANSIENT_RESET) {
        hit.terminal = 0;
        e->count++;
        if (e->count == 1) e->first = hit;
        tr->stats.events++;
        if (ys != y) memcpy(y, ys, tr->dim * sizeof(double));
        *t = e->t_hit;
        return reset_restart(tr, *t, y);
      }
      if (uc != 0) {
        stop = 1;
        tr->stats.user_code = uc;
      }
    }
    hit.terminal = stop;
    e->count++;
    if (e->count == 1) e->first = hit;
    tr->stats.events++;
    if (stop) {
      if (ys != y) memcpy(y, ys, tr->dim * sizeof(double));
      *t = e->t_hit;
      tr->stats.event_index = (int)tr->order[i];
      return AUTOBAL_EVENT;
    }
  }
  return AUTOBAL_SUCCESS;
}

int autobal_transient_run(autobal_transient *tr, const autobal_transient_system *sys, double t0,
                          double t1, double y[], double *t_reached) {
  const double wall0 = now_seconds();
  size_t i, n;
  double t, h = 0.0, span, prog_last = 0.0, wall_last = wall0, t_out;
  unsigned long k_out = 1;
  int rc;

  if (tr == NULL) return AUTOBAL_EINVAL;
  n = tr->dim;
  memset(&tr->stats, 0, sizeof tr->stats);
  tr->stats.event_index = -1;
  tr->stats.t_start = t0;
  tr->stats.t_end = t0;
  tr->stats.h_min_used = INFINITY;
  tr->fail_kind = 0;
  tr->n_reject_calls = 0;
  tr->reject_t = -INFINITY;
  if (t_reached) *t_reached = t0;
  if (sys == NULL || sys->rhs == NULL) {
    autobal_error_set(&tr->err, AUTOBAL_EINVAL, "system or its right-hand side is NULL");
    return finish(tr, AUTOBAL_EINVAL, AUTOBAL_TRANSIENT_STOP_ERROR, t0, t_reached, wall0);
  }
  if (sys->dim != n) {
    autobal_error_set(&tr->err, AUTOBAL_EINVAL,
                      "system dimension %zu differs from the driver's dimension %zu", sys->dim,
                      n);
    return finish(tr, AUTOBAL_EINVAL, AUTOBAL_TRANSIENT_STOP_ERROR, t0, t_reached, wall0);
  }
  if (y == NULL) {
    autobal_error_set(&tr->err, AUTOBAL_EINVAL, "state y is NULL");
    return finish(tr, AUTOBAL_EINVAL, AUTOBAL_TRANSIENT_STOP_ERROR, t0, t_reached, wall0);
  }
  if ((rc = autobal_check_param(&tr->err, "t0", t0, -INFINITY, 1, INFINITY, 1, "")) != 0 ||
      (rc = autobal_check_param(&tr->err, "t1", t1, t0, 0, INFINITY, 1, "")) != 0)
    return finish(tr, rc, AUTOBAL_TRANSIENT_STOP_ERROR, t0, t_reached, wall0);
  for (i = 0; i < n; i++) {
    if (!isfinite(y[i])) {
      autobal_error_set(&tr->err, AUTOBAL_EINVAL,
                        "initial state y[%zu] = %g is not finite", i, y[i]);
      return finish(tr, AUTOBAL_EINVAL, AUTOBAL_TRANSIENT_STOP_ERROR, t0, t_reached, wall0);
    }
  }
  tr->sys = *sys;
  tr->gsys_direct.function = sys->rhs;
  tr->gsys_direct.jacobian = NULL;
  tr->gsys_direct.dimension = n;
  tr->gsys_direct.params = sys->params;
  ctx_reset(&tr->main);
  tr->dense = tr->type == k_dop853 && !tr->opt.exact_output;
  if (tr->type == k_dop853)
    autobal_transient_dop853_set_dense_order_(tr->main.d->s->state, tr->opt.dense_order == 6 ? 6 : 7);
  tr->d6_at = tr->type == k_dop853 ? autobal_transient_dop853_dense6_at_fn_(tr->main.d->s->state)
                                   : autobal_transient_dop853_dense6_at_;
  tr->t0_run = t0;
  tr->t1_run = t1;
  tr->reset_run = 0;
  tr->t_reset = t0;
  span = t1 - t0;
  t = t0;

  /* events at t0 */
  for (i = 0; i < tr->nev; i++) {
    event_item *e = &tr->ev[i];
    e->count = 0;
    e->pending = 0;
    e->dwell_state = DWELL_ABOVE;
    if ((rc = event_value(tr, e, t0, y, &e->g_prev)) != AUTOBAL_SUCCESS)
      return finish(tr, rc, AUTOBAL_TRANSIENT_STOP_ERROR, t0, t_reached, wall0);
    if (e->dwell && e->g_prev < 0.0) {
      e->dwell_state = DWELL_BELOW;
      e->t_enter = t0;
    }
  }

  if (tr->observer) {
    int uc = tr->observer(t0, y, tr->observer_user);
    tr->stats.observer_calls++;
    if (uc != 0) {
      tr->stats.user_code = uc;
      autobal_error_set(&tr->err, AUTOBAL_EVENT, "observer requested a stop (%d) at t = %.17g",
                        uc, t0);
      return finish(tr, AUTOBAL_EVENT, AUTOBAL_TRANSIENT_STOP_OBSERVER, t0, t_reached, wall0);
    }
  }
  if (tr->progress) {
    int uc = tr->progress(0.0, tr->progress_user);
    if (uc != 0) {
      tr->stats.user_code = uc;
      autobal_error_set(&tr->err, AUTOBAL_ECANCELLED, "cancelled by the progress callback (%d) at t = %.17g", uc, t0);
      return finish(tr, AUTOBAL_ECANCELLED, AUTOBAL_TRANSIENT_STOP_CANCELLED, t0, t_reached,
                    wall0);
    }
  }
  if (!(span > 0.0)) {
    if (tr->progress) (void)tr->progress(1.0, tr->progress_user);
    return finish(tr, AUTOBAL_SUCCESS, AUTOBAL_TRANSIENT_STOP_END, t0, t_reached, wall0);
  }

  /* first step */
  if (tr->opt.h_init > 0.0) {
    h = tr->opt.h_init;
  } else {
    rc = initial_step(tr, t0, y, span, &h);
    if (rc != AUTOBAL_SUCCESS)
      return finish(tr, rc, AUTOBAL_TRANSIENT_STOP_ERROR, t0, t_reached, wall0);
    if (tr->opt.h_min > 0.0 && h < tr->opt.h_min) h = tr->opt.h_min;
  }
  t_out = output_time(tr, t0, t1, k_out);
  tr->k_out = k_out;
  tr->t_out = t_out;

  while (t < t1) {
    /* dense output: the steps are not cut at output times (nor at dwell completions) */
    double target = tr->dense ? t1 : t_out, t_prev = t, h_taken = 0.0;
    if (tr->opt.max_steps > 0 && tr->stats.steps >= tr->opt.max_steps) {
      autobal_error_set(&tr->err, AUTOBAL_EMAXSTEPS,
                        "maximum number of steps (%lu) reached at t = %.17g before t1 = %.17g",
                        tr->opt.max_steps, t, t1);
      return finish(tr, AUTOBAL_EMAXSTEPS, AUTOBAL_TRANSIENT_STOP_ERROR, t, t_reached, wall0);
    }
    /* land exactly on pending dwell completions */
    for (i = 0; i < tr->nev && !tr->dense; i++) {
      const event_item *e = &tr->ev[i];
      if (e->dwell && e->dwell_state == DWELL_BELOW) {
        const double tf = e->t_enter + e->duration;
        if (tf > t && tf < target) target = tf;
      }
    }
    if (tr->opt.h_max > 0.0 && h > tr->opt.h_max) h = tr->opt.h_max;
    memcpy(tr->y_prev, y, n * sizeof(double));
    rc = take_step(tr, &tr->main, &t, target, &h, y, &tr->stats.rejected, &h_taken);
    if (rc != AUTOBAL_SUCCESS) {
      tr->stats.user_code = tr->fail_code;
      return finish(tr, rc, AUTOBAL_TRANSIENT_STOP_ERROR, t, t_reached, wall0);
    }
    if (!(h_taken > 0.0) || t <= t_prev) {
      /* a step that does not advance t (e.g. the initial step computed from an overflowing
       * derivative is 0): stop instead of repeating it until max_steps */
      memcpy(y, tr->y_prev, n * sizeof(double));
      t = t_prev;
      autobal_error_set(&tr->err, AUTOBAL_ESTEP,
                        "step size underflow at t = %.17g: the step %.6g does not advance t "
                        "(is the right-hand side overflowing?)",
                        t_prev, h_taken);
      return finish(tr, AUTOBAL_ESTEP, AUTOBAL_TRANSIENT_STOP_ERROR, t_prev, t_reached, wall0);
    }
    tr->stats.steps++;
    tr->stats.h_last = h_taken;
    if (h_taken < tr->stats.h_min_used) tr->stats.h_min_used = h_taken;
    if (h_taken > tr->stats.h_max_used) tr->stats.h_max_used = h_taken;
    /* y is finite here: take_step tested it (with the error estimate) before accepting */
    if (tr->nev > 0) {
      rc = process_events(tr, t_prev, &t, y, h_taken);
      if (rc == OBSERVER_STOP) {
        autobal_error_set(&tr->err, AUTOBAL_EVENT, "observer requested a stop (%d) at t = %.17g",
                          tr->stats.user_code, t);
        return finish(tr, AUTOBAL_EVENT, AUTOBAL_TRANSIENT_STOP_OBSERVER, t, t_reached, wall0);
      }
      if (rc == AUTOBAL_EVENT) {
        autobal_error_set(&tr->err, AUTOBAL_EVENT, "stopped at event %d at t = %.17g",
                          tr->stats.event_index, t);
        return finish(tr, AUTOBAL_EVENT, AUTOBAL_TRANSIENT_STOP_EVENT, t, t_reached, wall0);
      }
      /* rc == RESTARTED: an event reset the state at t (<= the end of the step); the run goes
       * on from there (the output below only if t reached t_out) */
      if (rc != AUTOBAL_SUCCESS && rc != RESTARTED) {
        /* keep the last good state: the end of this accepted step */
        if (tr->fail_kind != 0) rc = rhs_failure(tr);
        return finish(tr, rc, AUTOBAL_TRANSIENT_STOP_ERROR, t, t_reached, wall0);
      }
    }
    if (tr->dense) {
      if (tr->t_out <= t) { /* an output time in this step (emit_outputs' first test) */
        double t_stop = 0.0;
        rc = emit_outputs(tr, t, 1, t, y, &t_stop);
        if (rc == OBSERVER_STOP) {
          memcpy(y, tr->y_out, n * sizeof(double));
          autobal_error_set(&tr->err, AUTOBAL_EVENT, "observer requested a stop (%d) at t = %.17g",
                            tr->stats.user_code, t_stop);
          return finish(tr, AUTOBAL_EVENT, AUTOBAL_TRANSIENT_STOP_OBSERVER, t_stop, t_reached, wall0);
        }
        if (rc != AUTOBAL_SUCCESS) {
          tr->stats.user_code = tr->fail_code;
          return finish(tr, rc, AUTOBAL_TRANSIENT_STOP_ERROR, t, t_reached, wall0);
        }
      }
    } else if (t >= t_out) {
      if (tr->observer) {
        int uc = tr->observer(t, y, tr->observer_user);
        tr->stats.observer_calls++;
        if (uc != 0) {
          tr->stats.user_code = uc;
          autobal_error_set(&tr->err, AUTOBAL_EVENT,
                            "observer requested a stop (%d) at t = %.17g", uc, t);
          return finish(tr, AUTOBAL_EVENT, AUTOBAL_TRANSIENT_STOP_OBSERVER, t, t_reached, wall0);
        }
      }
      k_out++;
      t_out = output_time(tr, t0, t1, k_out);
    }
    if (tr->progress && t < t1) {
      const double frac = (t - t0) / span;
      /* also every 4096 accepted steps, so that a cancellation is noticed when t hardly
       * advances */
      if (frac - prog_last >= tr->opt.progress_step || (tr->stats.steps & 4095UL) == 0) {
        int call = 1;
        double wnow = 0.0;
        if (tr->opt.progress_wall > 0.0) {
          wnow = now_seconds();
          call = wnow - wall_last >= tr->opt.progress_wall;
        }
        if (call) {
          int uc = tr->progress(frac, tr->progress_user);
          prog_last = frac;
          wall_last = wnow;
          if (uc != 0) {
            tr->stats.user_code = uc;
            autobal_error_set(&tr->err, AUTOBAL_ECANCELLED,
                              "cancelled by the progress callback (%d) at t = %.17g", uc, t);
            return finish(tr, AUTOBAL_ECANCELLED, AUTOBAL_TRANSIENT_STOP_CANCELLED, t,
                          t_reached, wall0);
          }
        }
      }
    }
  }
  /* the run is complete: a request to cancel at 1 changes nothing */
  if (tr->progress) (void)tr->progress(1.0, tr->progress_user);
  return finish(tr, AUTOBAL_SUCCESS, AUTOBAL_TRANSIENT_STOP_END, t, t_reached, wall0);
}
