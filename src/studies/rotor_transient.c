/* rotor_transient.c: the rotor transient study (`autobal rotor transient`): the rotor with its
 * ball autobalancers integrated in time from its initial state, the state and the model's
 * outputs streamed to the archive, per-revolution maxima, the balance criterion as a dwell
 * event, and the summary with the ISO 21940-11 figures (include/autobal/study.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/study.h"
#include "internal.h"
#include "numerics/fastmath.h"
#include "studies/rotor_transient_runup.h"
#include "studies/rotor_friction.h"
#include "models/rotor/rotor_internal.h"

#define TWO_PI 6.283185307179586476925286766559

autobal_study_rotor_transient_options autobal_study_rotor_transient_options_default(void) {
  autobal_study_rotor_transient_options o;
  memset(&o, 0, sizeof o);
  o.t_end = 20.0;
  o.dt_out = 0.0;
  /* rtol bounds the fixed-frame ball angles (|phi| ~ omega t: 3770 rad at 600 revolutions), atol
   * the rotor coordinates, which set the step count (docs/guide.md: the default tolerances) */
  o.rtol = 1e-10;
  o.atol = 1e-9;
  o.h_max = 0.0;
  o.max_steps = 100000000UL;
  /* the default since 0.2.0: DOP853 with output on its order-6 extension (no extra right-hand side
   * for the output points; bench/README.md, "The default output"); until then rk8pd, exact hits */
  o.stepper = "dop853";
  o.dense_order = 6;
  o.frame = AUTOBAL_ROTOR_FIXED;
  o.balance_tol = 0.01;
  o.balance_revs = 50.0;
  o.stop_at_balance = 0;
  o.grade = NAN;
  o.progress = NULL;
  o.progress_user = NULL;
  o.capture_band = 0.05;
  o.capture_time = 2.0;
  return o;
}

/* ---- inputs ----------------------------------------------------------------------------- */
/* The speed that sets the sampling and the revolution counts: omega for the constant drive, the
 * largest |speed| of a ramp or table (NaN for a table the model would reject); a motor: its
 * no-load speed omega_0 (a torque table: its largest |speed|) or |omega_start| if larger. */
static double speed_ref(const autobal_rotor_params *p) {
  const autobal_rotor_drive *d = &p->drive;
  double m = 0.0;
  size_t k;
  if (d->mode == AUTOBAL_ROTOR_DRIVE_CONSTANT) return p->omega;
  if (d->mode == AUTOBAL_ROTOR_DRIVE_RAMP) return fmax(fabs(d->omega_a), fabs(d->omega_b));
  if (d->mode == AUTOBAL_ROTOR_DRIVE_MOTOR) {
    m = d->n_torque ? 0.0 : d->omega_0;
    for (k = 0; k < d->n_torque && d->torque_omega; k++) m = fmax(m, fabs(d->torque_omega[k]));
    return fmax(m, fabs(d->omega_start));
  }
  if (d->mode != AUTOBAL_ROTOR_DRIVE_TABLE || !d->table_omega || d->n_points < 1) return NAN;
  for (k = 0; k < d->n_points; k++) m = fabs(d->table_omega[k]) > m ? fabs(d->table_omega[k]) : m;
  return m;
}

/* 1 if the run interpolates with DOP853's order-6 extension (output = dense6): then the output
 * columns use the library's sine, cosine and hypot (archive attribute derived_math = "fastmath";
 * every other mode libm's, as in 0.1.0: "libm"). */
static int fast_derived(const autobal_study_rotor_transient_options *o) {
  return o->stepper && strcmp(o->stepper, "dop853") == 0 && !o->exact_output && o->dense_order == 6;
}

/* The output interval actually used (0: a quarter revolution). */
static double dt_out_used(const autobal_study_rotor_transient_options *o, double omega) {
  return o->dt_out > 0 ? o->dt_out : 0.25 * TWO_PI / fabs(omega);
}

static autobal_transient_options driver_options(const autobal_study_rotor_transient_options *o, double omega) {
  autobal_transient_options t = autobal_transient_options_default();
  t.stepper = o->stepper ? o->stepper : "rk8pd";
  t.rtol = o->rtol;
  t.atol = o->atol;
  t.h_max = o->h_max;
  t.max_steps = o->max_steps;
  t.exact_output = o->exact_output;
  t.dense_order = o->dense_order;
  t.dt_out = dt_out_used(o, omega);
  t.event_tol = 1e-9 * o->t_end;
  return t;
}

/* The study's own option checks (the driver's are autobal_transient_options_validate). */
static int check_options(const autobal_study_rotor_transient_options *o, double omega, autobal_error *err) {
  if (!(o->t_end > 0 && isfinite(o->t_end)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: t_end = %g s is out of range: allowed (0, inf)", o->t_end);
  if (!(fabs(omega) > 0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: the transient counts revolutions 2 pi/|omega|: parameter omega = %g rad/s is "
                             "out of range: allowed omega != 0 (with a drive: its largest |speed|)",
                             omega);
  if (!(o->dt_out >= 0 && isfinite(o->dt_out)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: dt_out = %g s is out of range: allowed (0, inf), or 0 for a quarter revolution", o->dt_out);
  if (!(o->t_end / dt_out_used(o, omega) <= 5e8)) {
    if (o->dt_out > 0)
      return autobal_error_set(err, AUTOBAL_EINVAL, "options: t_end/dt_out = %.3g samples is too many (at most 5e8)",
                               o->t_end / dt_out_used(o, omega));
    /* the output interval follows from the speed: name it (omega = 1e308 used to end as "the
     * right-hand side returned 9") */
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: %.3g samples is too many (at most 5e8): the output interval is a quarter "
                             "revolution, 2 pi/(4 |omega|) = %.3g s at omega = %g rad/s (with a drive: its largest "
                             "|speed|); give dt_out, or a smaller omega or t_end",
                             o->t_end / dt_out_used(o, omega), dt_out_used(o, omega), omega);
  }
  if (!(o->balance_tol > 0))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: balance_tol = %g is out of range: allowed (0, inf)", o->balance_tol);
  if (!(o->balance_revs >= 0 && isfinite(o->balance_revs)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: balance_revs = %g is out of range: allowed [0, inf)", o->balance_revs);
  if (o->max_steps < 1)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: max_steps = %lu is out of range: allowed [1, inf)", o->max_steps);
  if (o->frame != AUTOBAL_ROTOR_FIXED && o->frame != AUTOBAL_ROTOR_ROTATING)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: frame = %d is not one of AUTOBAL_ROTOR_FIXED (%d), AUTOBAL_ROTOR_ROTATING (%d)",
                             o->frame, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING);
  if (!(o->capture_band > 0 && o->capture_band < 1))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: capture_band = %g is out of range: allowed (0, 1)", o->capture_band);
  if (!(o->capture_time > 0 && isfinite(o->capture_time)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: capture_time = %g s is out of range: allowed (0, inf)", o->capture_time);
  if (!isnan(o->grade) && !(o->grade > 0 && isfinite(o->grade)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: grade = %g mm/s is out of range: allowed (0, inf), or NaN for none", o->grade);
  return AUTOBAL_SUCCESS;
}

/* The frame the run integrates in: o->frame, except FIXED at rtol < AUTOBAL_STUDY_ROTOR_RELATIVE_RTOL,
 * which integrates the ball angles relative to the rotor (the rotating frame) and gives the
 * fixed-frame state at the outputs (include/autobal/study.h). */
static int integration_frame(const autobal_study_rotor_transient_options *o) {
  return o->frame == AUTOBAL_ROTOR_FIXED && o->rtol < AUTOBAL_STUDY_ROTOR_RELATIVE_RTOL ? AUTOBAL_ROTOR_ROTATING
                                                                                        : o->frame;
}

/* Model, driver and initial state; on failure nothing is left allocated.  Returns
 * AUTOBAL_SUCCESS or AUTOBAL_WARNING (the model's warning in err) or a failure. */
static int setup(const autobal_rotor_params *p, const autobal_study_rotor_transient_options *o, autobal_rotor **rot_out,
                 autobal_transient **tr_out, double **y_out, autobal_error *err) {
  autobal_error e, w;
  autobal_rotor *rot;
  autobal_transient *tr;
  autobal_transient_options to;
  double *y;
  int st;
  *rot_out = NULL, *tr_out = NULL, *y_out = NULL;
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  /* a drive is checked first: its speeds set the sampling */
  if (p->drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT && (st = autobal_rotor_params_check(p, err)) < 0) return st;
  if ((st = check_options(o, speed_ref(p), err))) return st;
  autobal_error_clear(&w);
  rot = autobal_rotor_alloc(p, &w);
  if (!rot) return autobal_error_set(err, w.status ? w.status : AUTOBAL_EINVAL, "%s", w.message);
  to = driver_options(o, speed_ref(p));
  autobal_error_clear(&e);
  tr = autobal_transient_alloc(autobal_rotor_dim(rot), &to, &e);
  if (!tr) {
    autobal_rotor_free(rot);
    return autobal_error_set(err, e.status ? e.status : AUTOBAL_EINVAL, "options: %s", e.message);
  }
  y = calloc(autobal_rotor_dim(rot), sizeof *y);
  if (!y) {
    autobal_transient_free(tr);
    autobal_rotor_free(rot);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  if ((st = autobal_rotor_initial_state(rot, integration_frame(o), 0.0, y, autobal_rotor_dim(rot)))) {
    autobal_error_set(err, st, "%s", autobal_rotor_errmsg(rot));
    free(y);
    autobal_transient_free(tr);
    autobal_rotor_free(rot);
    return st;
  }
  if (autobal_rotor_friction_on(rot)) {
    /* with friction a ball needs a positive normal force from the start (it cannot leave its
     * track): refuse such an initial state here, before an archive is created (a check, exit 3),
     * rather than as a failure of the run */
    const size_t nb = autobal_rotor_n_balls_total(rot);
    double *N = calloc(nb ? nb : 1, sizeof *N);
    size_t k, j, i;
    int bad = -1;
    st = N ? autobal_rotor_normal_forces(rot, integration_frame(o), 0.0, y, N, nb) : AUTOBAL_ENOMEM;
    for (k = 0; st == AUTOBAL_SUCCESS && k < nb && bad < 0; k++)
      if (!(N[k] > 0)) bad = (int)k;
    if (st != AUTOBAL_SUCCESS || bad >= 0) {
      if (st == AUTOBAL_ENOMEM) autobal_error_set(err, st, "out of memory");
      else if (st != AUTOBAL_SUCCESS) autobal_error_set(err, st, "%s", autobal_rotor_errmsg(rot));
      else {
        for (j = 0, i = (size_t)bad; j < autobal_rotor_n_planes(rot) && i >= autobal_rotor_n_balls(rot, j); j++)
          i -= autobal_rotor_n_balls(rot, j);
        st = autobal_error_set(err, AUTOBAL_EINVAL,
                               "initial state: ball %zu of plane %zu (p%zu_b%zu) would leave its track at t = 0: "
                               "normal force N = %.6g N (must be > 0 with friction: the speed, or the balls' "
                               "positions against gravity, cannot hold it on the track)",
                               i + 1, j + 1, j + 1, i + 1, N[bad]);
      }
      free(N);
      free(y);
      autobal_transient_free(tr);
      autobal_rotor_free(rot);
      return st;
    }
    free(N);
  }
  *rot_out = rot, *tr_out = tr, *y_out = y;
  if (w.status == AUTOBAL_WARNING) return autobal_error_set(err, AUTOBAL_WARNING, "%s", w.message);
  autobal_error_clear(err);
  return AUTOBAL_SUCCESS;
}

int autobal_study_rotor_transient_check(const autobal_rotor_params *p, const autobal_study_rotor_transient_options *opt,
                                        autobal_error *err) {
  autobal_study_rotor_transient_options def = autobal_study_rotor_transient_options_default();
  autobal_rotor *rot;
  autobal_transient *tr;
  double *y;
  int st = setup(p, opt ? opt : &def, &rot, &tr, &y, err);
  free(y);
  autobal_transient_free(tr);
  autobal_rotor_free(rot);
  return st;
}

/* the rotor's "outside the model" return is the driver's "reject this trial state" */
_Static_assert(AUTOBAL_ROTOR_RHS_LEAVES_TRACK == AUTOBAL_TRANSIENT_RHS_REJECT,
               "autobal_rotor_rhs's LEAVES_TRACK must be the transient driver's RHS_REJECT");

/* ---- the run -------------------------------------------------------------------------- */
typedef struct run_ctx {
  autobal_rotor *rotor;
  int fast;      /* output = dense6: the output columns by autobal_rotor_outputs_fast */
  int frame;     /* the frame of y, integrated (integration_frame) */
  int out_frame; /* the frame of the state datasets (options.frame) */
  size_t dim, nout, ncols;
  double *row; /* one sample: state + outputs */
  autobal_archive_series *series;
  autobal_archive_series *revs;
  int io_failed;
  autobal_study_progress_fn progress;
  void *progress_user;
  /* per-revolution summary */
  double rev_period, rev_t0, rev_max_G, rev_max_s;
  unsigned long rev_index; /* revolutions completed */
  double rev_end;          /* the end of revolution rev_index (sample_summary: computed once a revolution) */
  double rev_max_D[AUTOBAL_ROTOR_MAX_PLANES]; /* per plane */
  double *rev_row;
  size_t n_planes;
  /* summary */
  double amp_first, amp_last, t_first_window, t_last_window_start;
  double max_amp;
  int first_sample_done;
  double s_rel_initial;
  /* vibration in the last 10% of the run at the centre of mass (0) and the supports (1: left,
   * 2: right; NaN positions with lumped input): per direction x, y the largest synchronous (1X)
   * amplitude sqrt(u^2 + (u'/omega)^2) over the samples: the amplitude of the harmonic at the
   * running speed through (u, u') at each sample, exact for a steady whirl whatever the
   * sampling (a sampled maximum or RMS of 4 samples per revolution is not) */
  double l_sup[3], omega_abs;
  int drive; /* a ramp, table or motor: the 1X amplitude uses Omega at the sample */
  int motor; /* a motor: phi_0 and Omega are the state's last two entries */
  double amax[3][2];
  double qs[4]; /* the static offset under gravity (0 without): the 1X amplitudes are about it */
  unsigned long win_n;
  study_runup *runup; /* run-up outputs: a drive with an Omega column (rotor_transient_runup.h) */
  /* output = dense6 without friction: the output points buffered (bt, by: their times and states),
   * their rows (state columns with an archive, then the outputs) derived a block at a time, then
   * the summary's quantities in their order and one append (flush_block): the same numbers as one
   * point at a time (the outputs are functions of (t, y) alone without friction, whose columns read
   * the balls' stick-slip modes of the moment), but the points' independent chains of sines,
   * square roots and divisions overlap instead of each point waiting for its own */
  int buffered;
  size_t nb;
  double *bt, *by, *rows;
} run_ctx;

enum { OUT_BLOCK = 16 }; /* output points derived at a time (buffered) */

/* Displacement and velocity at axial position p (eq. (3.3) kinematics: (x + p beta, y - p alpha)). */
static void point_motion(const double y[], double p, double d[2], double v[2]) {
  d[0] = y[0] + p * y[3];
  d[1] = y[1] - p * y[2];
  v[0] = y[4] + p * y[7];
  v[1] = y[5] - p * y[6];
}

static size_t plane_base(size_t j) { return 3 + 7 * j; }

/* The summary's quantities of one output point (t, y) with its outputs out, in the order of the
 * points: the first sample, the running maxima, the last 10%'s synchronous amplitudes, the run-up
 * outputs, the per-revolution maxima (a completed revolution appended to its series). */
static void sample_summary(run_ctx *r, double t, const double y[], const double *out) {
  size_t j;
  if (!r->first_sample_done) {
    r->first_sample_done = 1;
    r->s_rel_initial = out[plane_base(0) + 5];
    r->rev_t0 = t;
    r->rev_index = 0;
    r->rev_end = r->rev_t0 + ((double)r->rev_index + 1.0 - 1e-9) * r->rev_period;
  }
  /* the running maxima by selects, not branches: a comparison with a sample computed just before
   * is mispredicted often, and then costs the whole dependent chain that computed the sample */
  r->max_amp = out[0] > r->max_amp ? out[0] : r->max_amp;
  if (t <= r->t_first_window) r->amp_first = out[0] > r->amp_first ? out[0] : r->amp_first;
  if (t >= r->t_last_window_start) r->amp_last = !(out[0] <= r->amp_last) ? out[0] : r->amp_last; /* NaN until sampled */
  if (t >= r->t_last_window_start) {
    size_t k, q;
    double w1x = r->omega_abs, dv[3];
    if (r->drive && autobal_rotor_spin(r->rotor, t, y, dv) == AUTOBAL_SUCCESS && fabs(dv[0]) > 0) w1x = fabs(dv[0]);
    double yq[8];
    for (k = 0; k < 8; k++) yq[k] = k < 4 ? y[k] - r->qs[k] : y[k];
    for (k = 0; k < 3; k++) {
      double d[2], v[2];
      point_motion(yq, r->l_sup[k], d, v);
      for (q = 0; q < 2; q++) {
        /* hypot as the output columns compute it (fastmath with output = dense6) */
        double amp = r->fast ? autobal_hypot_fast(d[q], v[q] / w1x) : hypot(d[q], v[q] / w1x);
        r->amax[k][q] = r->win_n == 0 || amp > r->amax[k][q] ? amp : r->amax[k][q];
      }
    }
    r->win_n++;
  }
  study_runup_sample(r->runup, t, out);
  /* per-revolution maxima (of the sampled values) */
  r->rev_max_G = out[0] > r->rev_max_G ? out[0] : r->rev_max_G;
  {
    double ms = r->rev_max_s;
    for (j = 0; j < r->n_planes; j++) {
      const double d = out[plane_base(j) + 6], s_rel = out[plane_base(j) + 5];
      r->rev_max_D[j] = d > r->rev_max_D[j] ? d : r->rev_max_D[j];
      ms = s_rel > ms ? s_rel : ms;
    }
    r->rev_max_s = ms;
  }
  /* revolution k ends at rev_t0 + (k+1) period; a sample within 1e-9 period of it closes it */
  if (t >= r->rev_end) {
    r->rev_row[0] = r->rev_max_G;
    r->rev_row[1] = r->rev_max_s;
    for (j = 0; j < r->n_planes; j++) r->rev_row[2 + j] = r->rev_max_D[j];
    if (r->revs && !r->io_failed && autobal_archive_series_append(r->revs, 1, &t, r->rev_row) != AUTOBAL_SUCCESS)
      r->io_failed = 1;
    r->rev_max_G = r->rev_max_s = 0;
    for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++) r->rev_max_D[j] = 0; /* two stores, no memset call */
    r->rev_index++;
    r->rev_end = r->rev_t0 + ((double)r->rev_index + 1.0 - 1e-9) * r->rev_period;
  }
}

/* The buffered output points: their rows first (independent of one another), then the summary's
 * quantities in their order, then one append.  0, or 1 if the model refused (as the observer). */
static int flush_block(run_ctx *r) {
  const size_t n = r->nb, dim = r->dim, nc = r->ncols;
  size_t k;
  r->nb = 0;
  if (r->series) /* the state columns of the rows: only the archive reads them */
    for (k = 0; k < n; k++) {
      double *row = r->rows + k * nc;
      const double *y = r->by + k * dim;
      if (r->frame == r->out_frame) memcpy(row, y, dim * sizeof *y);
      else if (autobal_rotor_convert_state(r->rotor, r->frame, r->out_frame, r->bt[k], y, row, dim) != AUTOBAL_SUCCESS)
        return 1;
    }
  if (autobal_rotor_outputs_fast_block(r->rotor, r->frame, n, r->bt, r->by, dim, r->rows + dim, nc) != AUTOBAL_SUCCESS)
    return 1;
  for (k = 0; k < n; k++) sample_summary(r, r->bt[k], r->by + k * dim, r->rows + k * nc + dim);
  if (n > 0 && r->series && !r->io_failed && autobal_archive_series_append(r->series, n, r->bt, r->rows) != AUTOBAL_SUCCESS)
    r->io_failed = 1;
  return 0;
}

static int observer(double t, const double y[], void *user) {
  run_ctx *r = user;
  if (r->buffered) {
    r->bt[r->nb] = t;
    memcpy(r->by + r->nb * r->dim, y, r->dim * sizeof *y);
    return ++r->nb == OUT_BLOCK ? flush_block(r) : 0;
  }
  if (r->series) { /* the state columns of the row: only the archive reads them */
    if (r->frame == r->out_frame) memcpy(r->row, y, r->dim * sizeof *y);
    else if (autobal_rotor_convert_state(r->rotor, r->frame, r->out_frame, t, y, r->row, r->dim) != AUTOBAL_SUCCESS)
      return 1;
  }
  if ((r->fast ? autobal_rotor_outputs_fast : autobal_rotor_outputs)(r->rotor, r->frame, t, y, r->row + r->dim,
                                                                     r->nout) != AUTOBAL_SUCCESS)
    return 1;
  if (r->series && !r->io_failed && autobal_archive_series_append(r->series, 1, &t, r->row) != AUTOBAL_SUCCESS)
    r->io_failed = 1;
  sample_summary(r, t, y, r->row + r->dim);
  return 0;
}

static int progress(double fraction, void *user) {
  run_ctx *r = user;
  return r->progress ? r->progress(fraction, r->progress_user) : 0;
}

static double monitor(double t, const double y[], void *user) {
  run_ctx *r = user;
  return autobal_rotor_balance_monitor(r->rotor, r->frame, t, y);
}

/* ---- the archive layout ------------------------------------------------------------------ */
static const char *state_name(size_t k, size_t nb, int frame, char *buf, size_t len, const char **unit,
                              const char **lname) {
  static const char *const q[8] = {"x", "y", "alpha", "beta", "x_rate", "y_rate", "alpha_rate", "beta_rate"};
  static const char *const qu[8] = {"m", "m", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s"};
  static const char *const ql[8] = {"displacement x of the centre of mass", "displacement y of the centre of mass",
                                    "Resal angle alpha (about x)", "Resal angle beta (about y)", "dx/dt", "dy/dt",
                                    "d alpha/dt", "d beta/dt"};
  if (k < 8) {
    *unit = qu[k];
    *lname = ql[k];
    return q[k];
  }
  if (k < 8 + nb) {
    snprintf(buf, len, frame == AUTOBAL_ROTOR_FIXED ? "state_phi_%zu" : "state_psi_%zu", k - 8 + 1);
    *unit = "rad";
    *lname = frame == AUTOBAL_ROTOR_FIXED ? "integrated ball angle phi (absolute)" : "integrated ball angle psi (relative)";
    return buf;
  }
  if (k < 8 + 2 * nb) {
    snprintf(buf, len, frame == AUTOBAL_ROTOR_FIXED ? "state_phi_rate_%zu" : "state_psi_rate_%zu", k - 8 - nb + 1);
    *unit = "rad/s";
    *lname = "integrated ball angular rate";
    return buf;
  }
  if (k == 8 + 2 * nb) {
    *unit = "m";
    *lname = "axial displacement z";
    return "z";
  }
  *unit = "m/s";
  *lname = "axial velocity dz/dt";
  return "z_rate";
}

int autobal_study_rotor_transient_state_name(const autobal_study_rotor_transient_summary *s, size_t k, char *buf,
                                             size_t len, const char **unit) {
  size_t nb = 0, j;
  const char *u = NULL;
  int n;
  if (!s || !buf || k >= s->dim) return AUTOBAL_EINVAL;
  for (j = 0; j < s->n_planes && j < AUTOBAL_ROTOR_MAX_PLANES; j++) nb += s->n_balls[j];
  if (k < 8) {
    static const char *const q[8] = {"x", "y", "alpha", "beta", "x_rate", "y_rate", "alpha_rate", "beta_rate"};
    static const char *const qu[8] = {"m", "m", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s"};
    n = snprintf(buf, len, "%s", q[k]);
    u = qu[k];
  } else if (k < 8 + nb) {
    n = snprintf(buf, len, "%s_%zu", s->state_frame == AUTOBAL_ROTOR_FIXED ? "phi" : "psi", k - 8 + 1);
    u = "rad";
  } else if (k < 8 + 2 * nb) {
    n = snprintf(buf, len, "%s_rate_%zu", s->state_frame == AUTOBAL_ROTOR_FIXED ? "phi" : "psi", k - 8 - nb + 1);
    u = "rad/s";
  } else if (s->state_axial && k < 8 + 2 * nb + 2) {
    n = snprintf(buf, len, "%s", k == 8 + 2 * nb ? "z" : "z_rate");
    u = k == 8 + 2 * nb ? "m" : "m/s";
  } else if (s->state_motor && k + 2 >= s->dim) {
    n = snprintf(buf, len, "%s", k + 2 == s->dim ? "phi_0" : "Omega");
    u = k + 2 == s->dim ? "rad" : "rad/s";
  } else {
    return AUTOBAL_EINVAL; /* not a layout this summary describes */
  }
  if (n < 0 || (size_t)n >= len) return AUTOBAL_EINVAL;
  if (unit) *unit = u;
  return AUTOBAL_SUCCESS;
}

static int write_inputs(autobal_archive *a, const autobal_rotor *rot, const autobal_study_rotor_transient_options *o) {
  const autobal_rotor_params *p = autobal_rotor_get_params(rot);
  const char *g = "/rotor/transient";
  int st = autobal_study_write_rotor_params(a, p, 1);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_double(a, g, "t_end", o->t_end, "s");
  if (!st) st = autobal_archive_attr_double(a, g, "dt_out", dt_out_used(o, speed_ref(p)), "s");
  if (!st) st = autobal_archive_attr_double(a, g, "rtol", o->rtol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "atol", o->atol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "h_max", o->h_max, "s");
  if (!st) st = autobal_archive_attr_double(a, g, "max_steps", (double)o->max_steps, "1");
  /* components of different units: no single (CF) units attribute; they are named instead */
  if (!st) st = autobal_archive_attr_double_array(a, g, "initial_q", 4, p->q0, NULL);
  if (!st) st = autobal_archive_attr_string(a, g, "initial_q_components", "x (m), y (m), alpha (rad), beta (rad)");
  if (!st) st = autobal_archive_attr_double_array(a, g, "initial_q_rate", 4, p->qd0, NULL);
  if (!st)
    st = autobal_archive_attr_string(a, g, "initial_q_rate_components",
                                     "x_rate (m/s), y_rate (m/s), alpha_rate (rad/s), beta_rate (rad/s)");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_tol", o->balance_tol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_revs", o->balance_revs, "1");
  if (!st) st = autobal_archive_attr_string(a, g, "stepper", o->stepper ? o->stepper : "rk8pd");
  if (!st) st = autobal_archive_attr_string(a, g, "frame", o->frame == AUTOBAL_ROTOR_FIXED ? "fixed" : "rotating");
  /* a fixed-frame run at rtol < 1e-10 integrates the angles relative to the rotor (only then said) */
  if (!st && integration_frame(o) != o->frame)
    st = autobal_archive_attr_string(a, g, "frame_integrated",
                                     "rotating: ball angles psi = phi - phi_0 integrated (rtol < 1e-10), the "
                                     "state datasets phi = phi_0 + psi");
  /* dense output (only a stepper with a continuous extension has a choice: the others' archives
   * keep their layout) */
  if (!st && o->stepper && strcmp(o->stepper, "dop853") == 0)
    st = autobal_archive_attr_string(a, g, "output",
                                      o->exact_output ? "exact" : o->dense_order == 6 ? "dense6" : "dense");
  /* how the output columns were computed (libm's sin, cos, hypot, or the library's) */
  if (!st) st = autobal_archive_attr_string(a, g, "derived_math", fast_derived(o) ? "fastmath" : "libm");
  /* the prescribed speed (only when not constant: the constant drive keeps the 0.1.0 layout) */
  if (!st && p->drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP) {
    st = autobal_archive_attr_string(a, g, "drive_mode", "ramp");
    if (!st) st = autobal_archive_attr_double(a, g, "drive_omega_a", p->drive.omega_a, "rad/s");
    if (!st) st = autobal_archive_attr_double(a, g, "drive_omega_b", p->drive.omega_b, "rad/s");
    if (!st) st = autobal_archive_attr_double(a, g, "drive_t_a", p->drive.t_a, "s");
    if (!st) st = autobal_archive_attr_double(a, g, "drive_t_b", p->drive.t_b, "s");
  } else if (!st && p->drive.mode == AUTOBAL_ROTOR_DRIVE_MOTOR) {
    st = autobal_archive_attr_string(a, g, "drive_mode", "motor");
    if (!st) st = autobal_archive_attr_double(a, g, "drive_J", p->drive.J, "kg m^2");
    if (!st) st = autobal_archive_attr_double(a, g, "drive_k_r", p->drive.k_r, "N m s");
    if (!st) st = autobal_archive_attr_double(a, g, "drive_omega_start", p->drive.omega_start, "rad/s");
    if (!st && p->drive.n_torque == 0) st = autobal_archive_attr_double(a, g, "drive_L_0", p->drive.L_0, "N m");
    if (!st && p->drive.n_torque == 0) st = autobal_archive_attr_double(a, g, "drive_omega_0", p->drive.omega_0, "rad/s");
    if (!st && p->drive.n_torque > 0)
      st = autobal_archive_attr_double_array(a, g, "drive_torque_omega", p->drive.n_torque, p->drive.torque_omega, "rad/s");
    if (!st && p->drive.n_torque > 0)
      st = autobal_archive_attr_double_array(a, g, "drive_torque_L", p->drive.n_torque, p->drive.torque_L, "N m");
  } else if (!st && p->drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE) {
    st = autobal_archive_attr_string(a, g, "drive_mode", "table");
    if (!st) st = autobal_archive_attr_double_array(a, g, "drive_table_t", p->drive.n_points, p->drive.table_t, "s");
    if (!st)
      st = autobal_archive_attr_double_array(a, g, "drive_table_omega", p->drive.n_points, p->drive.table_omega,
                                             "rad/s");
  }
  return st;
}

/* A readable long_name for a derived output named by autobal_rotor_output_name. */
static void output_long_name(const char *name, char *buf, size_t len) {
  unsigned pl = 0, b = 0;
  char rest[48] = "";
  if (!strcmp(name, "amp_G")) snprintf(buf, len, "displacement amplitude of the centre of mass");
  else if (!strcmp(name, "amp_L")) snprintf(buf, len, "displacement amplitude at the left support (z = -l_L)");
  else if (!strcmp(name, "amp_R")) snprintf(buf, len, "displacement amplitude at the right support (z = +l_R)");
  else if (!strcmp(name, "Omega")) snprintf(buf, len, "spin speed Omega of the drive (prescribed or the motor's)");
  else if (!strcmp(name, "motor_torque")) snprintf(buf, len, "motor torque L(Omega) (without the resistance k_r Omega)");
  else if (!strcmp(name, "motor_power")) snprintf(buf, len, "motor power L(Omega) Omega");
  else if (sscanf(name, "p%u_b%u_%47s", &pl, &b, rest) == 3) {
    const char *what = !strcmp(rest, "phi") ? "absolute angle phi (unwrapped)"
                       : !strcmp(rest, "phi_w") ? "absolute angle phi wrapped to (-pi, pi]"
                       : !strcmp(rest, "psi") ? "angle psi relative to the rotor (unwrapped)"
                       : !strcmp(rest, "psi_w") ? "angle psi relative to the rotor wrapped to (-pi, pi]"
                       : !strcmp(rest, "phi_rate") ? "absolute angular rate dphi/dt"
                       : !strcmp(rest, "psi_rate") ? "angular rate relative to the rotor dpsi/dt"
                       : !strcmp(rest, "stuck") ? "stuck on its track (1) or slipping (0) (friction)"
                       : !strcmp(rest, "N") ? "normal force of the track on the ball (friction)" : rest;
    snprintf(buf, len, "ball %u of plane %u: %s", b, pl, what);
  } else if (sscanf(name, "p%u_%47s", &pl, rest) == 2) {
    const char *what = !strcmp(rest, "s_u") ? "unbalance s_u of rotor plus balls along fixed x (3.1)"
                       : !strcmp(rest, "s_v") ? "unbalance s_v of rotor plus balls along fixed y (3.1)"
                       : !strcmp(rest, "s_xi") ? "unbalance s_xi along the rotor axis xi (3.10)"
                       : !strcmp(rest, "s_eta") ? "unbalance s_eta along the rotor axis eta (3.10)"
                       : !strcmp(rest, "s_abs") ? "residual unbalance |s|"
                       : !strcmp(rest, "s_rel") ? "residual unbalance |s| relative to m0 r0"
                       : !strcmp(rest, "amp_D") ? "displacement amplitude at the balancer plane" : rest;
    snprintf(buf, len, "plane %u: %s", pl, what);
  } else
    snprintf(buf, len, "%s", name);
}

static int open_series(run_ctx *r, autobal_archive *a) {
  size_t n = r->ncols, k, nb = autobal_rotor_n_balls_total(r->rotor), j;
  char (*names)[64] = calloc(n, sizeof *names);
  char (*lnames)[96] = calloc(n, sizeof *lnames);
  const char **np = calloc(n, sizeof *np), **up = calloc(n, sizeof *up), **lp = calloc(n, sizeof *lp);
  const char *rn[2 + AUTOBAL_ROTOR_MAX_PLANES], *ru[2 + AUTOBAL_ROTOR_MAX_PLANES], *rl[2 + AUTOBAL_ROTOR_MAX_PLANES];
  char rnb[AUTOBAL_ROTOR_MAX_PLANES][32];
  int st = AUTOBAL_SUCCESS;
  if (!names || !lnames || !np || !up || !lp) st = AUTOBAL_ENOMEM;
  for (k = 0; !st && k < r->dim; k++) {
    const char *nm = state_name(k, nb, r->out_frame, names[k], sizeof names[k], &up[k], &lp[k]);
    if (r->motor && k + 2 >= r->dim) { /* a motor's phi_0 and Omega: the state's last two entries */
      nm = k + 2 == r->dim ? "state_phi_0" : "state_Omega";
      up[k] = k + 2 == r->dim ? "rad" : "rad/s";
      lp[k] = k + 2 == r->dim ? "integrated rotor angle phi_0 (motor)" : "integrated spin speed Omega (motor)";
    }
    if (nm != names[k]) snprintf(names[k], sizeof names[k], "%s", nm);
    np[k] = names[k];
    if (k >= 8 && k < 8 + 2 * nb) { /* one long_name per ball */
      snprintf(lnames[k], sizeof lnames[k], "%s of ball %zu (state order)", lp[k], (k - 8) % nb + 1);
      lp[k] = lnames[k];
    }
  }
  for (k = 0; !st && k < r->nout; k++) {
    const char *unit = NULL;
    st = autobal_rotor_output_name(r->rotor, k, names[r->dim + k], sizeof names[0], &unit);
    np[r->dim + k] = names[r->dim + k];
    up[r->dim + k] = unit;
    output_long_name(names[r->dim + k], lnames[r->dim + k], sizeof lnames[0]);
    lp[r->dim + k] = lnames[r->dim + k];
  }
  if (!st) st = autobal_archive_series_open(a, "/rotor/transient", "time", "s", "time", n, np, up, lp, &r->series);
  rn[0] = "max_amp_G";
  ru[0] = "m";
  rl[0] = "largest sampled displacement amplitude of the centre of mass during the revolution";
  rn[1] = "max_s_rel";
  ru[1] = "1";
  rl[1] = "largest sampled relative residual unbalance |s|/s_ref over the planes during the revolution";
  for (j = 0; j < r->n_planes; j++) {
    snprintf(rnb[j], sizeof rnb[j], "p%zu_max_amp_D", j + 1);
    rn[2 + j] = rnb[j];
    ru[2 + j] = "m";
    rl[2 + j] = "largest sampled displacement amplitude at the balancer plane during the revolution";
  }
  if (!st)
    st = autobal_archive_series_open(a, "/rotor/revolutions", "revolution_end", "s",
                                     "time at the end of each revolution 2 pi/omega", 2 + r->n_planes, rn, ru, rl,
                                     &r->revs);
  free(names);
  free(lnames);
  free(np);
  free(up);
  free(lp);
  return st;
}

/* ---- engineering quantities of the summary (docs/units.md) ------------------------------ */
static void engineering_compute(autobal_study_rotor_transient_summary *s, const autobal_rotor *rot,
                                const autobal_rotor_params *p, const autobal_study_rotor_transient_options *o,
                                const run_ctx *r, double t, const double *y) {
  size_t j, k, q, np = r->n_planes;
  double omega = fabs(p->omega), worst = 0.0, dv[3];
  if (r->drive) { /* the speed at the end of the run (the largest one if that is 0) */
    omega = autobal_rotor_spin(rot, t, y, dv) == AUTOBAL_SUCCESS ? fabs(dv[0]) : NAN;
    if (!(omega > 0)) omega = autobal_rotor_drive_speed_max(rot);
  }
  s->balance_grade_rotor_mass = p->input == AUTOBAL_ROTOR_HARDWARE ? p->hw.m_p : p->lumped.M;
  for (j = 0; j < np; j++) {
    double s4[4], s0 = p->plane[j].m0 * p->plane[j].r0;
    s->residual_unbalance_abs_final[j] =
        autobal_rotor_plane_unbalance(rot, j, r->frame, t, y, s4) == AUTOBAL_SUCCESS ? hypot(s4[0], s4[1]) : NAN;
    s->residual_unbalance_rel_final[j] = s0 > 0 ? s->residual_unbalance_abs_final[j] / s0 : NAN;
    if (!(s->residual_unbalance_abs_final[j] <= worst)) worst = s->residual_unbalance_abs_final[j];
  }
  /* the rotor's mass shared equally by the planes (ISO 21940-11's allocation for a rotor with
   * its planes symmetric to the bearings): grade of the worst plane */
  s->balance_grade_final = autobal_balance_grade(worst * (double)np, s->balance_grade_rotor_mass, omega);
  s->balance_grade_class = autobal_balance_grade_class(s->balance_grade_final);
  s->permissible_unbalance =
      isnan(o->grade) ? NAN : autobal_permissible_unbalance(o->grade, s->balance_grade_rotor_mass, omega);
  s->permissible_unbalance_met = !isnan(s->permissible_unbalance) && worst * (double)np <= s->permissible_unbalance;
  s->have_vibration_window = r->win_n > 0;
  s->velocity_rms_supports = NAN;
  for (k = 0; k < 3; k++) {
    s->displacement_pk_pk[k] = s->velocity_rms[k] = NAN;
    if (!s->have_vibration_window || isnan(r->l_sup[k])) continue;
    for (q = 0; q < 2; q++) { /* harmonic: peak-to-peak 2 A, RMS velocity omega A / sqrt(2) */
      double pp = 2.0 * r->amax[k][q], v = omega * r->amax[k][q] / sqrt(2.0);
      if (!(pp <= s->displacement_pk_pk[k])) s->displacement_pk_pk[k] = pp;
      if (!(v <= s->velocity_rms[k])) s->velocity_rms[k] = v;
    }
    if (k > 0 && !(s->velocity_rms[k] <= s->velocity_rms_supports)) s->velocity_rms_supports = s->velocity_rms[k];
  }
  if (isnan(s->velocity_rms_supports)) s->velocity_rms_supports = s->velocity_rms[0];
}

static int write_summary(autobal_archive *a, const autobal_study_rotor_transient_summary *s) {
  const char *g = "/rotor/transient";
  int st = autobal_archive_attr_double(a, g, "time_to_balance", s->time_to_balance, "s");
  if (!st) st = autobal_archive_attr_int(a, g, "balanced", s->balanced);
  if (!st) st = autobal_archive_attr_double(a, g, "t_reached", s->t_reached, "s");
  if (!st) st = autobal_archive_attr_double(a, g, "residual_unbalance_initial", s->residual_unbalance_initial, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "residual_unbalance_final", s->residual_unbalance_final, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "amplitude_first_10pct_max", s->amplitude_first_10pct_max, "m");
  if (!st) st = autobal_archive_attr_double(a, g, "amplitude_last_10pct_max", s->amplitude_last_10pct_max, "m");
  if (!st) st = autobal_archive_attr_double(a, g, "amplitude_max", s->amplitude_max, "m");
  if (!st)
    st = autobal_archive_attr_double_array(a, g, "residual_unbalance_abs_final", s->n_planes,
                                           s->residual_unbalance_abs_final, "kg m");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_grade_final", s->balance_grade_final, "mm/s");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_grade_rotor_mass", s->balance_grade_rotor_mass, "kg");
  if (!st && !isnan(s->permissible_unbalance)) {
    st = autobal_archive_attr_double(a, g, "permissible_unbalance", s->permissible_unbalance, "kg m");
    if (!st) st = autobal_archive_attr_int(a, g, "permissible_unbalance_met", s->permissible_unbalance_met);
  }
  if (!st) st = autobal_archive_attr_double(a, g, "displacement_pk_pk_G_last_10pct", s->displacement_pk_pk[0], "m");
  if (!st) st = autobal_archive_attr_double(a, g, "velocity_rms_G_last_10pct", s->velocity_rms[0], "m/s");
  if (!st) st = autobal_archive_attr_double(a, g, "velocity_rms_left_support_last_10pct", s->velocity_rms[1], "m/s");
  if (!st) st = autobal_archive_attr_double(a, g, "velocity_rms_right_support_last_10pct", s->velocity_rms[2], "m/s");
  if (!st)
    st = autobal_study_write_solver_stats(a, "/rotor/transient/solver", s->stepper, &s->solver, s->solver_message, "s");
  return st;
}

void autobal_study_rotor_transient_summary_free(autobal_study_rotor_transient_summary *s) {
  size_t j;
  if (!s) return;
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++) {
    free(s->ball_psi_final[j]);
    free(s->ball_psi_balanced[j]);
    s->ball_psi_final[j] = s->ball_psi_balanced[j] = NULL;
  }
  free(s->state_final);
  s->state_final = NULL;
  study_runup_summary_free(s);
  study_friction_summary_free(s);
}

int autobal_study_rotor_transient(const autobal_rotor_params *p, const autobal_study_rotor_transient_options *opt,
                                  autobal_archive *a, autobal_study_rotor_transient_summary *summary,
                                  autobal_error *err) {
  autobal_study_rotor_transient_options def = autobal_study_rotor_transient_options_default();
  const autobal_study_rotor_transient_options *o = opt ? opt : &def;
  autobal_study_rotor_transient_summary local, *s = summary ? summary : &local;
  const autobal_rotor_params *rp;
  autobal_rotor *rot = NULL;
  autobal_transient *tr = NULL;
  autobal_transient_system sys;
  autobal_transient_event_hit hit;
  autobal_error e;
  run_ctx r;
  study_friction *fric = NULL;
  study_contact *cont = NULL;
  double *y = NULL, t_reached = 0.0;
  int st, rc = AUTOBAL_SUCCESS, ev, fl;
  size_t j;

  memset(s, 0, sizeof *s);
  memset(&r, 0, sizeof r);
  autobal_error_clear(err);
  autobal_error_clear(&e);
  st = setup(p, o, &rot, &tr, &y, &e);
  if (st < 0) {
    rc = autobal_error_set(err, st, "%s", e.message);
    goto done;
  }
  if (st == AUTOBAL_WARNING) {
    s->warning = 1;
    snprintf(s->warning_message, sizeof s->warning_message, "%s", e.message);
  }
  rp = autobal_rotor_get_params(rot);
  r.rotor = rot;
  r.fast = fast_derived(o);
  r.frame = integration_frame(o);
  r.out_frame = o->frame;
  r.progress = o->progress;
  r.progress_user = o->progress_user;
  r.dim = autobal_rotor_dim(rot);
  r.nout = autobal_rotor_output_count(rot);
  r.ncols = r.dim + r.nout;
  r.n_planes = autobal_rotor_n_planes(rot);
  r.drive = rp->drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT;
  r.motor = rp->drive.mode == AUTOBAL_ROTOR_DRIVE_MOTOR;
  r.rev_period = TWO_PI / fabs(speed_ref(rp));
  r.t_first_window = 0.1 * o->t_end;
  r.t_last_window_start = 0.9 * o->t_end;
  r.amp_last = NAN; /* stays NaN when the run stops (e.g. at balance) before the last 10% */
  (void)autobal_rotor_static_offset(rp, r.qs);
  r.l_sup[0] = 0.0;
  r.omega_abs = fabs(speed_ref(rp));
  r.l_sup[1] = rp->input == AUTOBAL_ROTOR_HARDWARE ? -rp->hw.l_L : NAN;
  r.l_sup[2] = rp->input == AUTOBAL_ROTOR_HARDWARE ? rp->hw.l_R : NAN;
  r.row = calloc(r.ncols, sizeof *r.row);
  r.rev_row = calloc(2 + r.n_planes, sizeof *r.rev_row);
  r.buffered = r.fast && !autobal_rotor_friction_on(rot);
  if (r.buffered) {
    r.bt = malloc(OUT_BLOCK * sizeof *r.bt);
    r.by = malloc(OUT_BLOCK * r.dim * sizeof *r.by);
    r.rows = malloc(OUT_BLOCK * r.ncols * sizeof *r.rows); /* every column read is written first */
  }
  if (!r.row || !r.rev_row || (r.buffered && (!r.bt || !r.by || !r.rows))) {
    rc = autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
    goto done;
  }
  if ((st = study_runup_begin(rot, &r.runup, &e))) {
    rc = autobal_error_set(err, st, "%s", e.message);
    goto done;
  }
  s->n_planes = r.n_planes;
  s->revolution_period = r.rev_period;
  s->time_to_balance = NAN;
  if (a) {
    st = write_inputs(a, rot, o);
    if (!st) st = study_friction_write_inputs(a, rot, "/rotor/transient");
    if (!st) st = open_series(&r, a);
    if (st) {
      rc = autobal_error_set(err, st, "%s", st == AUTOBAL_ENOMEM ? "out of memory" : autobal_archive_errmsg(a));
      goto done;
    }
  }
  sys.rhs = r.frame == AUTOBAL_ROTOR_FIXED ? autobal_rotor_rhs : autobal_rotor_rhs_rotating;
  sys.jac = NULL;
  sys.dim = r.dim;
  sys.params = rot;
  autobal_transient_set_observer(tr, observer, &r);
  autobal_transient_set_progress(tr, progress, &r);
  ev = autobal_transient_add_dwell_event(tr, monitor, &r, o->balance_tol, o->balance_revs * r.rev_period,
                                         o->stop_at_balance);
  if (ev < 0) {
    rc = autobal_error_set(err, ev, "%s", autobal_transient_errmsg(tr));
    goto done;
  }
  if ((st = study_friction_begin(rot, r.frame, tr, 0.0, y, &fric, &e))) { /* EXACT law: stick-slip events */
    rc = autobal_error_set(err, st, "%s", e.message);
    goto done;
  }
  if ((st = study_contact_begin(rot, r.frame, tr, 0.0, y, fric, &cont, &e))) { /* contact: impact events */
    rc = autobal_error_set(err, st, "%s", e.message);
    goto done;
  }
  st = autobal_transient_run(tr, &sys, 0.0, o->t_end, y, &t_reached);
  fl = r.buffered ? flush_block(&r) : 0; /* the output points still buffered */
  autobal_transient_get_stats(tr, &s->solver);
  snprintf(s->stepper, sizeof s->stepper, "%s", autobal_transient_get_options(tr).stepper);
  snprintf(s->solver_message, sizeof s->solver_message, "%s", autobal_transient_errmsg(tr));
  if (st == AUTOBAL_ERHS && (autobal_rotor_friction_on(rot) || autobal_rotor_contact_on(rot))) /* with the reason, e.g. a ball leaving its track */
    snprintf(s->solver_message, sizeof s->solver_message, "%s: %s", autobal_transient_errmsg(tr),
             autobal_rotor_errmsg(rot));
  if (st < 0) rc = autobal_error_set(err, st, "%s", s->solver_message);
  if (fl && rc == AUTOBAL_SUCCESS) /* as the observer's refusal (not expected: checked arguments, finite t) */
    rc = autobal_error_set(err, AUTOBAL_EINVAL, "the model refused the derived quantities of a buffered output point");
  st = study_friction_finish(fric, t_reached, s, &e);
  if (st && rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, st, "%s", e.message);
  st = study_contact_finish(cont, rot, s, &e);
  if (st && rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, st, "%s", e.message);
  if (r.io_failed && rc == AUTOBAL_SUCCESS)
    rc = autobal_error_set(err, AUTOBAL_EIO, "writing the time series failed: %s", autobal_archive_errmsg(a));

  /* the summary */
  s->balanced = autobal_transient_event_result(tr, (size_t)ev, NULL, &hit) == 1;
  if (s->balanced) s->time_to_balance = hit.t_start;
  s->t_reached = t_reached;
  s->residual_unbalance_initial = r.s_rel_initial;
  s->residual_unbalance_final = autobal_rotor_balance_monitor(rot, r.frame, t_reached, y);
  s->amplitude_first_10pct_max = r.amp_first;
  s->amplitude_last_10pct_max = r.amp_last;
  s->amplitude_max = r.max_amp;
  engineering_compute(s, rot, rp, o, &r, t_reached, y);
  (void)autobal_rotor_static_offset(rp, s->static_offset); /* zeros without gravity */
  for (j = 0; j < r.n_planes; j++) {
    size_t i, nbj = rp->plane[j].n_balls;
    double *pb, dw[3];
    s->n_balls[j] = nbj;
    s->gravity_ratio_final[j] = NAN;
    if (rp->gravity) { /* g sin(theta) / (r Omega^2) at the final speed (docs/device.md section 2) */
      s->gravity_ratio_final[j] = autobal_rotor_gravity_ratio(
          rp, j, autobal_rotor_spin(rot, t_reached, y, dw) == AUTOBAL_SUCCESS ? fabs(dw[0]) : NAN);
      if (a) {
        char grp[64];
        snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
        st = autobal_archive_attr_double(a, grp, "gravity_ratio_final", s->gravity_ratio_final[j], "1");
        if (st && rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
      }
    }
    if (nbj == 0) continue;
    s->ball_psi_final[j] = malloc(nbj * sizeof(double));
    if (!s->ball_psi_final[j]) {
      if (rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
      continue;
    }
    for (i = 0; i < nbj; i++) {
      size_t k = autobal_rotor_ball_index(rot, j, i);
      double dv[3], ang;
      (void)autobal_rotor_spin(rot, t_reached, y, dv); /* dv[1] = phi_0 (omega t for a constant speed) */
      ang = r.frame == AUTOBAL_ROTOR_FIXED ? y[8 + k] - dv[1] : y[8 + k];
      s->ball_psi_final[j][i] = remainder(ang, TWO_PI);
    }
    /* the balanced configuration (3.14), where it exists */
    pb = calloc(nbj, sizeof *pb);
    if (pb && autobal_rotor_balanced_angles(rot, j, pb, nbj, NULL) == AUTOBAL_SUCCESS) {
      if (a) {
        char grp[64];
        snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
        st = autobal_archive_attr_double_array(a, grp, "ball_psi_balanced", nbj, pb, "rad");
        if (st && rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
      }
      s->ball_psi_balanced[j] = pb;
      pb = NULL;
    }
    free(pb);
  }
  s->dim = r.dim;
  s->state_frame = o->frame;
  s->state_axial = rp->axial != 0;
  s->state_motor = r.motor;
  s->state_final = malloc(r.dim * sizeof(double));
  if (s->state_final) { /* in options.frame: phi = phi_0 + psi when integrated relative */
    if (autobal_rotor_convert_state(rot, r.frame, o->frame, t_reached, y, s->state_final, r.dim) != AUTOBAL_SUCCESS &&
        rc == AUTOBAL_SUCCESS)
      rc = autobal_error_set(err, AUTOBAL_EINVAL, "the final state could not be converted to the fixed frame");
  } else if (rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");

  if (a) {
    st = write_summary(a, s);
    if (!st) st = study_friction_write_summary(a, s, "/rotor/transient");
    if (!st) st = study_contact_write_summary(a, s, "/rotor/transient");
    if (st && rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
  }
  st = study_runup_finish(r.runup, rot, o, a, autobal_archive_series_length(r.series), s, &e);
  if (st && rc == AUTOBAL_SUCCESS) rc = autobal_error_set(err, st, "%s", e.message);
done:
  if (r.series || r.revs) {
    int s1 = autobal_archive_series_close(r.series), s2 = autobal_archive_series_close(r.revs);
    if ((s1 || s2) && rc == AUTOBAL_SUCCESS)
      rc = autobal_error_set(err, s1 ? s1 : s2, "writing the time series failed: %s", autobal_archive_errmsg(a));
  }
  autobal_transient_free(tr);
  autobal_rotor_free(rot);
  free(r.row);
  free(r.rev_row);
  free(r.bt);
  free(r.by);
  free(r.rows);
  study_runup_free(r.runup);
  study_friction_free(fric);
  study_contact_free(cont);
  free(y);
  if (s == &local) autobal_study_rotor_transient_summary_free(&local);
  return rc;
}
