/* pendulum_transient.c: the pendulum transient study (`autobal pendulum transient`): the
 * equations of motion (1) of the two-pendulum autobalancer integrated in dimensionless time
 * tau, streamed to the archive, summarised (include/autobal/study.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "autobal/study.h"
#include "internal.h"

#define TWO_PI 6.283185307179586476925286766559
#define NCOLS 15 /* 8 state components + 7 derived quantities */
#define BLOCK 64 /* output points derived at a time with output = dense6 */

autobal_study_pendulum_transient_options autobal_study_pendulum_transient_options_default(void) {
  autobal_study_pendulum_transient_options o;
  memset(&o, 0, sizeof o);
  o.t_end = 300.0;
  o.dt_out = 0.0;
  o.revs_out = 0.25;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  o.h_max = 0.0;
  o.max_steps = 100000000UL;
  /* the default since 0.2.0: DOP853 with output on its order-6 extension (rotor_transient.c) */
  o.stepper = "dop853";
  o.dense_order = 6;
  o.balance_tol = 1e-3;
  o.balance_revs = 20.0;
  return o;
}

/* 1 if the run interpolates with DOP853's order-6 extension (output = dense6): then the derived
 * quantities use the library's sine, cosine and hypot (archive attribute derived_math =
 * "fastmath"; every other mode libm's, as in 0.1.0: "libm"). */
static int fast_derived(const autobal_study_pendulum_transient_options *o) {
  return o->stepper && strcmp(o->stepper, "dop853") == 0 && !o->exact_output && o->dense_order == 6;
}

/* The output interval in tau and in revolutions. */
static void output_interval(const autobal_pendulum_params *p, const autobal_study_pendulum_transient_options *o,
                            double *dt, double *revs) {
  if (o->dt_out > 0) {
    *dt = o->dt_out;
    *revs = p->R_w > 0 ? o->dt_out * p->R_w / TWO_PI : NAN;
  } else {
    *dt = o->revs_out * TWO_PI / p->R_w; /* one revolution lasts 2 pi / R_w in tau */
    *revs = o->revs_out;
  }
}

static int check_inputs(const autobal_pendulum_params *p, const autobal_study_pendulum_transient_options *o,
                        autobal_pendulum_motion *motion, autobal_error *err) {
  autobal_transient_options to;
  autobal_error e;
  double dt, revs;
  int i, st;
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  autobal_error_clear(&e);
  if ((st = autobal_pendulum_motion_init(motion, p, &e)) != AUTOBAL_SUCCESS)
    return autobal_error_set(err, st < 0 ? st : AUTOBAL_EINVAL, "%s", e.message);
  for (i = 0; i < 8; i++)
    if (!isfinite(o->y0[i]))
      return autobal_error_set(err, AUTOBAL_EINVAL, "initial state: y0[%d] = %g is not finite", i, o->y0[i]);
  if (!(o->t_end > 0 && isfinite(o->t_end)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: t_end = %g is out of range: allowed (0, inf)", o->t_end);
  if (!(o->dt_out >= 0))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: dt_out = %g is out of range: allowed (0, inf), or 0 for revs_out", o->dt_out);
  if (o->dt_out == 0) {
    if (!(o->revs_out > 0))
      return autobal_error_set(err, AUTOBAL_EINVAL, "options: revs_out = %g is out of range: allowed (0, inf)", o->revs_out);
    if (!(p->R_w > 0))
      return autobal_error_set(err, AUTOBAL_EINVAL, "options: revs_out needs R_w > 0; give dt_out (in tau) instead");
  }
  output_interval(p, o, &dt, &revs);
  if (!(dt > 0 && isfinite(dt)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: dt_out = %g is out of range: allowed (0, inf)", dt);
  if (o->t_end / dt > 5e8)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: t_end/dt_out = %.3g samples is too many (at most 5e8)", o->t_end / dt);
  if (!(o->balance_tol > 0))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: balance_tol = %g is out of range: allowed (0, inf)", o->balance_tol);
  if (!(o->balance_revs >= 0 && isfinite(o->balance_revs)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: balance_revs = %g is out of range: allowed [0, inf)", o->balance_revs);
  if (o->balance_revs > 0 && !(p->R_w > 0))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: balance_revs > 0 needs R_w > 0 (set balance_revs = 0)");
  if (o->max_steps < 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: max_steps = %lu is out of range: allowed [1, inf)", o->max_steps);
  to = autobal_transient_options_default();
  to.stepper = o->stepper ? o->stepper : "rk8pd";
  to.rtol = o->rtol;
  to.atol = o->atol;
  to.h_max = o->h_max;
  to.max_steps = o->max_steps;
  to.exact_output = o->exact_output;
  to.dense_order = o->dense_order;
  to.dt_out = dt;
  to.event_tol = 1e-9 * o->t_end;
  if ((st = autobal_transient_options_validate(&to, &e)))
    return autobal_error_set(err, st, "options: %s", e.message);
  return AUTOBAL_SUCCESS;
}

int autobal_study_pendulum_transient_check(const autobal_pendulum_params *p,
                                           const autobal_study_pendulum_transient_options *opt, autobal_error *err) {
  autobal_study_pendulum_transient_options def = autobal_study_pendulum_transient_options_default();
  autobal_pendulum_motion motion;
  autobal_error_clear(err);
  return check_inputs(p, opt ? opt : &def, &motion, err);
}

typedef struct run_ctx {
  const autobal_pendulum_motion *m; /* the parameters with sin(psi0) computed once */
  int fast; /* output = dense6: the derived quantities by autobal_pendulum_motion_derive_fast */
  autobal_archive_series *series;
  int io_failed;
  double row[NCOLS];
  double amp_max, unb_initial, amp_initial;
  int first_done;
  autobal_study_progress_fn progress;
  void *progress_user;
  /* fast: the output points buffered by columns, derived and appended a block at a time
   * (autobal_pendulum_motion_derive_fast_cols: the numbers of derive_fast, 4 states per
   * instruction with AVX2); flushed when full and after the run */
  size_t nb;
  double bt[BLOCK], by[8][BLOCK], bd[7][BLOCK], rows[BLOCK * NCOLS];
} run_ctx;

/* derive the buffered output points, update the summary's extremes in their order, append them */
static void flush_block(run_ctx *r) {
  const double *const ycols[8] = {r->by[0], r->by[1], r->by[2], r->by[3],
                                  r->by[4], r->by[5], r->by[6], r->by[7]};
  double *const dcols[7] = {r->bd[0], r->bd[1], r->bd[2], r->bd[3], r->bd[4], r->bd[5], r->bd[6]};
  const size_t n = r->nb;
  size_t k, j;
  if (n == 0) return;
  r->nb = 0;
  autobal_pendulum_motion_derive_fast_cols(r->m, n, ycols, dcols);
  if (!r->first_done) {
    r->first_done = 1;
    r->unb_initial = r->bd[1][0];
    r->amp_initial = r->bd[0][0];
  }
  for (k = 0; k < n; k++)
    if (r->bd[0][k] > r->amp_max) r->amp_max = r->bd[0][k];
  if (r->series && !r->io_failed) {
    for (k = 0; k < n; k++) {
      double *row = r->rows + k * NCOLS;
      for (j = 0; j < 8; j++) row[j] = r->by[j][k];
      for (j = 0; j < 7; j++) row[8 + j] = r->bd[j][k];
    }
    if (autobal_archive_series_append(r->series, n, r->bt, r->rows) != AUTOBAL_SUCCESS) r->io_failed = 1;
  }
}

static int observer(double tau, const double y[], void *user) {
  run_ctx *r = user;
  autobal_pendulum_motion_derived d;
  if (r->fast) {
    const size_t k = r->nb;
    r->bt[k] = tau;
    r->by[0][k] = y[0];
    r->by[1][k] = y[1];
    r->by[2][k] = y[2];
    r->by[3][k] = y[3];
    r->by[4][k] = y[4];
    r->by[5][k] = y[5];
    r->by[6][k] = y[6];
    r->by[7][k] = y[7];
    if ((r->nb = k + 1) == BLOCK) flush_block(r);
    return 0;
  }
  autobal_pendulum_motion_derive_m(r->m, y, &d);
  memcpy(r->row, y, 8 * sizeof *y);
  r->row[8] = d.amplitude;
  r->row[9] = d.unbalance;
  r->row[10] = d.unbalance_u;
  r->row[11] = d.unbalance_v;
  r->row[12] = d.alpha;
  r->row[13] = d.beta;
  r->row[14] = d.jacobi;
  if (!r->first_done) {
    r->first_done = 1;
    r->unb_initial = d.unbalance;
    r->amp_initial = d.amplitude;
  }
  if (d.amplitude > r->amp_max) r->amp_max = d.amplitude;
  if (r->series && !r->io_failed && autobal_archive_series_append(r->series, 1, &tau, r->row) != AUTOBAL_SUCCESS)
    r->io_failed = 1;
  return 0;
}

static int progress(double fraction, void *user) {
  run_ctx *r = user;
  return r->progress ? r->progress(fraction, r->progress_user) : 0;
}

static int open_series(run_ctx *r, autobal_archive *a) {
  static const char *const names[NCOLS] = {"xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate",
                                           "amplitude", "unbalance", "unbalance_u", "unbalance_v", "alpha", "beta",
                                           "jacobi"};
  static const char *const units[NCOLS] = {"1", "1", "rad", "rad", "1", "1", "rad", "rad",
                                           "1", "1", "1", "1", "rad", "rad", "1"};
  static const char *const lnames[NCOLS] = {
      "shaft-centre displacement along X (parallel to U, rotating), in units of l",
      "shaft-centre displacement along Y (parallel to V, rotating), in units of l",
      "angle psi of pendulum 1, counter-clockwise from +V",
      "angle phi of pendulum 2, clockwise from -V",
      "d xi/d tau",
      "d eta/d tau",
      "d psi/d tau (rad per unit tau)",
      "d phi/d tau (rad per unit tau)",
      "shaft displacement amplitude sqrt(xi^2 + eta^2), in units of l",
      "residual unbalance |d| of rotor plus pendulums about the shaft centre, in units of 2 m l",
      "residual unbalance along U: sin psi0 - (sin psi + sin phi)/2, in units of 2 m l",
      "residual unbalance along V: (cos psi - cos phi)/2, in units of 2 m l",
      "psi - psi0 wrapped to (-pi, pi] (deviation from the main motion (4))",
      "phi - psi0 wrapped to (-pi, pi] (deviation from the main motion (4))",
      "Jacobi integral T2 - T0 + V of the rotating frame, units of (M + 2m) l^2 omega0^2 (constant when H = h = 0)"};
  return autobal_archive_series_open(a, "/pendulum/transient", "tau", "1",
                                     "dimensionless time tau = omega0 t (one revolution = 2 pi / R_w)", NCOLS, names,
                                     units, lnames, &r->series);
}

static int write_settings(autobal_archive *a, const autobal_pendulum_physical *phys,
                          const autobal_study_pendulum_transient_options *o, double dt, double revs) {
  const char *g = "/pendulum/transient";
  int st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_double(a, g, "t_end", o->t_end, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "dt_out", dt, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "revs_out", revs, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "rtol", o->rtol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "atol", o->atol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "h_max", o->h_max, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_tol", o->balance_tol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_revs", o->balance_revs, "1");
  if (!st) st = autobal_archive_attr_string(a, g, "stepper", o->stepper ? o->stepper : "rk8pd");
  /* dense output (only a stepper with a continuous extension has a choice) */
  if (!st && o->stepper && strcmp(o->stepper, "dop853") == 0)
    st = autobal_archive_attr_string(a, g, "output",
                                      o->exact_output ? "exact" : o->dense_order == 6 ? "dense6" : "dense");
  /* how the derived quantities were computed (libm's sin, cos, hypot, or the library's) */
  if (!st) st = autobal_archive_attr_string(a, g, "derived_math", fast_derived(o) ? "fastmath" : "libm");
  if (!st) st = autobal_archive_attr_double_array(a, g, "initial_state", 8, o->y0, "1");
  if (!st)
    st = autobal_archive_attr_string(a, g, "state_order",
                                     "xi, eta, psi, phi, xi_rate, eta_rate, psi_rate, phi_rate (lengths in l, angles in rad)");
  if (!st && phys) {
    /* tau = omega0 t with omega0 = sqrt(c/(M + 2m)) */
    const double omega0 = sqrt(phys->c / (phys->M + 2 * phys->m));
    st = autobal_archive_attr_double(a, g, "time_unit", 1.0 / omega0, "s");
    if (!st) st = autobal_archive_attr_double(a, g, "length_unit", phys->l, "m");
  }
  return st;
}

int autobal_study_pendulum_transient(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys,
                                     const autobal_study_pendulum_transient_options *opt, autobal_archive *a,
                                     autobal_study_pendulum_transient_summary *summary, autobal_error *err) {
  autobal_study_pendulum_transient_options def = autobal_study_pendulum_transient_options_default();
  const autobal_study_pendulum_transient_options *o = opt ? opt : &def;
  autobal_study_pendulum_transient_summary local, *s = summary ? summary : &local;
  autobal_pendulum_motion motion;
  autobal_transient *tr = NULL;
  autobal_transient_options to;
  autobal_transient_system sys;
  autobal_transient_event_hit hit;
  autobal_pendulum_motion_derived dfin;
  autobal_error e;
  run_ctx r;
  double dt, revs, t_reached = 0.0;
  int st, rc = AUTOBAL_SUCCESS, ev, verdict = 0;

  memset(s, 0, sizeof *s);
  memset(&r, 0, sizeof r);
  autobal_error_clear(err);
  autobal_error_clear(&e);
  if ((st = check_inputs(p, o, &motion, &e))) return autobal_error_set(err, st, "%s", e.message);
  output_interval(p, o, &dt, &revs);
  s->dt_out = dt;
  s->revs_out = revs;
  s->time_to_balance = NAN;
  s->have_linear_verdict = autobal_pendulum_verdict(p, &verdict, NULL, NULL) == AUTOBAL_SUCCESS;
  s->linear_verdict = verdict;
  s->revolution_period = p->R_w > 0 ? TWO_PI / p->R_w : INFINITY;
  to = autobal_transient_options_default();
  to.stepper = o->stepper ? o->stepper : "rk8pd";
  to.rtol = o->rtol;
  to.atol = o->atol;
  to.h_max = o->h_max;
  to.max_steps = o->max_steps;
  to.exact_output = o->exact_output;
  to.dense_order = o->dense_order;
  to.dt_out = dt;
  to.event_tol = 1e-9 * o->t_end;
  tr = autobal_transient_alloc(8, &to, &e);
  if (!tr) return autobal_error_set(err, e.status ? e.status : AUTOBAL_ENOMEM, "options: %s", e.message);
  r.m = &motion;
  r.fast = fast_derived(o);
  r.progress = o->progress;
  r.progress_user = o->progress_user;
  memcpy(s->final_state, o->y0, sizeof s->final_state);
  if (a) {
    st = autobal_study_write_pendulum_params(a, p, phys);
    if (!st) st = write_settings(a, phys, o, dt, revs);
    if (!st) st = open_series(&r, a);
    if (st) {
      rc = autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
      goto done;
    }
  }
  sys.rhs = autobal_pendulum_motion_rhs;
  sys.jac = autobal_pendulum_motion_jac;
  sys.dim = AUTOBAL_PENDULUM_STATE_DIM;
  sys.params = &motion;
  autobal_transient_set_observer(tr, observer, &r);
  autobal_transient_set_progress(tr, progress, &r);
  ev = autobal_transient_add_dwell_event(tr, autobal_pendulum_unbalance_scalar, &motion.p, o->balance_tol,
                                         o->balance_revs > 0 ? o->balance_revs * s->revolution_period : 0.0,
                                         o->stop_at_balance);
  if (ev < 0) {
    rc = autobal_error_set(err, ev, "%s", autobal_transient_errmsg(tr));
    goto done;
  }
  st = autobal_transient_run(tr, &sys, 0.0, o->t_end, s->final_state, &t_reached);
  if (r.fast) flush_block(&r); /* the output points still buffered */
  autobal_transient_get_stats(tr, &s->solver);
  snprintf(s->stepper, sizeof s->stepper, "%s", autobal_transient_get_options(tr).stepper);
  snprintf(s->solver_message, sizeof s->solver_message, "%s", autobal_transient_errmsg(tr));
  if (st < 0) rc = autobal_error_set(err, st, "%s", autobal_transient_errmsg(tr));
  if (r.io_failed && rc == AUTOBAL_SUCCESS)
    rc = autobal_error_set(err, AUTOBAL_EIO, "writing the time series failed: %s", autobal_archive_errmsg(a));
  s->balanced = autobal_transient_event_result(tr, (size_t)ev, NULL, &hit) == 1;
  if (s->balanced) s->time_to_balance = hit.t_start;
  s->t_reached = t_reached;
  if (r.fast) autobal_pendulum_motion_derive_fast(&motion, s->final_state, &dfin);
  else autobal_pendulum_motion_derive(p, s->final_state, &dfin);
  s->unbalance_initial = r.unb_initial;
  s->unbalance_final = dfin.unbalance;
  s->amplitude_initial = r.amp_initial;
  s->amplitude_max = r.amp_max;
  s->amplitude_final = dfin.amplitude;
  s->alpha_final = dfin.alpha;
  s->beta_final = dfin.beta;
  if (a) {
    const char *g = "/pendulum/transient";
    st = autobal_archive_attr_double(a, g, "time_to_balance", s->time_to_balance, "1");
    if (!st) st = autobal_archive_attr_int(a, g, "balanced", s->balanced);
    if (!st) st = autobal_archive_attr_double(a, g, "t_reached", t_reached, "1");
    if (!st) st = autobal_archive_attr_double_array(a, g, "final_state", 8, s->final_state, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "unbalance_initial", s->unbalance_initial, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "unbalance_final", s->unbalance_final, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "amplitude_max", s->amplitude_max, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "alpha_final", s->alpha_final, "rad");
    if (!st) st = autobal_archive_attr_double(a, g, "beta_final", s->beta_final, "rad");
    if (!st && s->have_linear_verdict)
      st = autobal_archive_attr_string(a, g, "linear_verdict", autobal_verdict_name(s->linear_verdict));
    if (!st)
      st = autobal_study_write_solver_stats(a, "/pendulum/transient/solver", s->stepper, &s->solver,
                                            s->solver_message, "1");
    if (st && rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
  }
done:
  if (r.series) {
    st = autobal_archive_series_close(r.series);
    if (st && rc == AUTOBAL_SUCCESS)
      rc = autobal_error_set(err, st, "writing the time series failed: %s", autobal_archive_errmsg(a));
  }
  autobal_transient_free(tr);
  return rc;
}
