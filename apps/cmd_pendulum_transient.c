/* cmd_pendulum_transient.c: `autobal pendulum transient`: the equations of motion (1) of the
 * two-pendulum autobalancer integrated in dimensionless time tau (docs/pendulum.md), streamed to
 * HDF5, summarised for a person: balanced or not, time to balance, residual unbalance, final
 * pendulum angles relative to the main motion (4). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/archive.h"
#include "autobal/pendulum.h"
#include "autobal/transient.h"
#include "cli.h"

#define TWO_PI 6.283185307179586476925286766559

typedef struct ptr_cfg {
  autobal_pendulum_params p;
  autobal_pendulum_physical phys;
  int physical;
  double y0[8];
  /* [transient] */
  double t_end, dt_out, revs_out, rtol, atol, h_max, balance_tol, balance_revs;
  long max_steps;
  const char *stepper;
  int stop_at_balance;
} ptr_cfg;

static int get_d(cli_ctx *ctx, const char *sec, const char *key, double *v) {
  return cli_get_double(ctx, sec, key, *v, v, NULL);
}

static int read_config(cli_ctx *ctx, ptr_cfg *c) {
  static const char *const ikeys[8] = {"xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate"};
  int rc, i, has_dt = 0, has_revs = 0;
  if ((rc = cli_read_pendulum_params(ctx, &c->p, &c->phys, &c->physical))) return rc;
  /* [initial]: default start-up from rest with the pendulums opposite each other along V
   * (psi = phi = 0: they cancel; the residual unbalance is the rotor's own, sin psi0) */
  for (i = 0; i < 8; i++) {
    c->y0[i] = 0.0;
    if ((rc = get_d(ctx, "initial", ikeys[i], &c->y0[i]))) return rc;
  }
  /* [transient] */
  c->t_end = 300.0;
  c->revs_out = 0.25;
  c->dt_out = 0.0;
  c->rtol = 1e-10;
  c->atol = 1e-12;
  c->h_max = 0.0;
  c->max_steps = 100000000L;
  c->balance_tol = 1e-3;
  c->balance_revs = 20.0;
  c->stepper = "rk8pd";
  if ((rc = get_d(ctx, "transient", "t_end", &c->t_end))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "dt_out", 0.0, &c->dt_out, &has_dt))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "revs_out", c->revs_out, &c->revs_out, &has_revs))) return rc;
  if ((rc = get_d(ctx, "transient", "rtol", &c->rtol))) return rc;
  if ((rc = get_d(ctx, "transient", "atol", &c->atol))) return rc;
  if ((rc = get_d(ctx, "transient", "h_max", &c->h_max))) return rc;
  if ((rc = cli_get_int(ctx, "transient", "max_steps", c->max_steps, &c->max_steps, NULL))) return rc;
  if ((rc = cli_get_string(ctx, "transient", "stepper", c->stepper, &c->stepper, NULL))) return rc;
  if ((rc = get_d(ctx, "transient", "balance_tol", &c->balance_tol))) return rc;
  if ((rc = get_d(ctx, "transient", "balance_revs", &c->balance_revs))) return rc;
  if ((rc = cli_get_bool(ctx, "transient", "stop_at_balance", 0, &c->stop_at_balance, NULL))) return rc;
  if (has_dt && has_revs) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give dt_out or revs_out, not both");
  if (!(c->t_end > 0 && isfinite(c->t_end)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: t_end = %g is out of range: allowed (0, inf)", c->t_end);
  if (!has_dt) {
    if (!(c->revs_out > 0))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: revs_out = %g is out of range: allowed (0, inf)", c->revs_out);
    if (!(c->p.R_w > 0))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: revs_out needs R_w > 0; give dt_out (in tau) instead");
    c->dt_out = c->revs_out * TWO_PI / c->p.R_w; /* one revolution lasts 2 pi / R_w in tau */
  } else {
    c->revs_out = c->p.R_w > 0 ? c->dt_out * c->p.R_w / TWO_PI : NAN;
  }
  if (!(c->dt_out > 0))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: dt_out = %g is out of range: allowed (0, inf)", c->dt_out);
  if (c->t_end / c->dt_out > 5e8)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: t_end/dt_out = %.3g samples is too many (at most 5e8)",
                    c->t_end / c->dt_out);
  if (!(c->balance_tol > 0))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_tol = %g is out of range: allowed (0, inf)", c->balance_tol);
  if (!(c->balance_revs >= 0))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_revs = %g is out of range: allowed [0, inf)", c->balance_revs);
  if (c->balance_revs > 0 && !(c->p.R_w > 0))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_revs > 0 needs R_w > 0 (set balance_revs = 0)");
  if (c->max_steps < 1)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: max_steps = %ld is out of range: allowed [1, inf)", c->max_steps);
  return CLI_EXIT_OK;
}

/* ---- the run ------------------------------------------------------------------------------ */
#define NCOLS 15 /* 8 state components + 7 derived quantities */

typedef struct run_ctx {
  cli_ctx *ctx;
  const autobal_pendulum_params *p;
  autobal_archive_series *series;
  int io_failed;
  double row[NCOLS];
  double amp_max, unb_initial, amp_initial;
  int first_done;
} run_ctx;

static int observer(double tau, const double y[], void *user) {
  run_ctx *r = user;
  autobal_pendulum_motion_derived d;
  autobal_pendulum_motion_derive(r->p, y, &d);
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
  return cli_progress(r->ctx, "pendulum transient", fraction);
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

static int write_settings(autobal_archive *a, const ptr_cfg *c) {
  const char *g = "/pendulum/transient";
  int st = autobal_archive_group(a, g);
#define AD(name, v, u) \
  if (!st) st = autobal_archive_attr_double(a, g, name, v, u)
  AD("t_end", c->t_end, "1");
  AD("dt_out", c->dt_out, "1");
  AD("revs_out", c->revs_out, "1");
  AD("rtol", c->rtol, "1");
  AD("atol", c->atol, "1");
  AD("h_max", c->h_max, "1");
  AD("balance_tol", c->balance_tol, "1");
  AD("balance_revs", c->balance_revs, "1");
  if (!st) st = autobal_archive_attr_string(a, g, "stepper", c->stepper);
  if (!st) st = autobal_archive_attr_double_array(a, g, "initial_state", 8, c->y0, "1");
  if (!st)
    st = autobal_archive_attr_string(a, g, "state_order",
                                     "xi, eta, psi, phi, xi_rate, eta_rate, psi_rate, phi_rate (lengths in l, angles in rad)");
  if (!st && c->physical) {
    /* tau = omega0 t with omega0 = sqrt(c/(M + 2m)) */
    const double omega0 = sqrt(c->phys.c / (c->phys.M + 2 * c->phys.m));
    AD("time_unit", 1.0 / omega0, "s");
    AD("length_unit", c->phys.l, "m");
  }
#undef AD
  return st;
}

int cli_cmd_pendulum_transient(cli_ctx *ctx) {
  ptr_cfg c;
  autobal_pendulum_motion motion;
  autobal_transient *tr = NULL;
  autobal_transient_options opt;
  autobal_transient_system sys;
  autobal_transient_stats stats;
  autobal_transient_event_hit hit;
  autobal_archive *a = NULL;
  autobal_error err;
  autobal_pendulum_motion_derived dfin;
  run_ctx r;
  double y[8], t_reached = 0.0, ttb = NAN, rev_period;
  int rc = CLI_EXIT_OK, st, balanced = 0, ev = -1, verdict = 0, have_verdict;

  memset(&r, 0, sizeof r);
  memset(&stats, 0, sizeof stats);
  memset(&dfin, 0, sizeof dfin);
  autobal_error_clear(&err);
  memset(&c, 0, sizeof c);
  if ((rc = read_config(ctx, &c))) return rc;
  if ((rc = cli_config_check_unused(ctx))) return rc;
  if (autobal_pendulum_motion_init(&motion, &c.p, &err) != AUTOBAL_SUCCESS)
    return cli_fail(ctx, cli_exit_code(err.status), "[pendulum]: %s", err.message);
  {
    int i;
    for (i = 0; i < 8; i++)
      if (!isfinite(c.y0[i])) return cli_fail(ctx, CLI_EXIT_INPUT, "[initial]: the initial state must be finite");
  }
  have_verdict = autobal_pendulum_verdict(&c.p, &verdict, NULL, NULL) == AUTOBAL_SUCCESS;
  rev_period = c.p.R_w > 0 ? TWO_PI / c.p.R_w : INFINITY;

  opt = autobal_transient_options_default();
  opt.stepper = c.stepper;
  opt.rtol = c.rtol;
  opt.atol = c.atol;
  opt.h_max = c.h_max;
  opt.max_steps = (unsigned long)c.max_steps;
  opt.dt_out = c.dt_out;
  opt.event_tol = 1e-9 * c.t_end;
  tr = autobal_transient_alloc(8, &opt, &err);
  if (!tr) return cli_fail(ctx, cli_exit_code(err.status), "[transient]: %s", err.message);
  r.ctx = ctx;
  r.p = &c.p;
  memcpy(y, c.y0, sizeof y);

  if ((rc = cli_archive_open(ctx, "autobal pendulum transient", &a))) goto done;
  if (a) {
    rc = cli_write_pendulum_params(ctx, a, &c.p, &c.phys, c.physical);
    if (rc) goto finish;
    st = write_settings(a, &c);
    if (!st) st = open_series(&r, a);
    if (st) {
      rc = cli_fail(ctx, cli_exit_code(st), "%s", autobal_archive_errmsg(a));
      goto finish;
    }
  }
  sys.rhs = autobal_pendulum_motion_rhs;
  sys.jac = autobal_pendulum_motion_jac;
  sys.dim = AUTOBAL_PENDULUM_STATE_DIM;
  sys.params = &motion;
  autobal_transient_set_observer(tr, observer, &r);
  autobal_transient_set_progress(tr, progress, &r);
  ev = autobal_transient_add_dwell_event(tr, autobal_pendulum_unbalance_scalar, &motion.p, c.balance_tol,
                                         c.balance_revs > 0 ? c.balance_revs * rev_period : 0.0, c.stop_at_balance);
  if (ev < 0) {
    rc = cli_fail(ctx, cli_exit_code(ev), "%s", autobal_transient_errmsg(tr));
    goto finish;
  }
  st = autobal_transient_run(tr, &sys, 0.0, c.t_end, y, &t_reached);
  cli_progress_done(ctx);
  autobal_transient_get_stats(tr, &stats);
  if (st < 0) {
    if (st == AUTOBAL_ECANCELLED)
      rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED,
                    "interrupted at tau = %.6g of %.6g; the archive keeps everything computed so far (status incomplete)",
                    t_reached, c.t_end);
    else
      rc = cli_fail(ctx, cli_exit_code(st), "%s (tau reached %.9g of %.6g; partial results kept)",
                    autobal_transient_errmsg(tr), t_reached, c.t_end);
  }
  if (r.io_failed && rc == CLI_EXIT_OK)
    rc = cli_fail(ctx, CLI_EXIT_IO, "writing the time series failed: %s", autobal_archive_errmsg(a));
  balanced = autobal_transient_event_result(tr, (size_t)ev, NULL, &hit) == 1;
  if (balanced) ttb = hit.t_start;
  autobal_pendulum_motion_derive(&c.p, y, &dfin);

  if (a) {
    const char *g = "/pendulum/transient";
    st = autobal_archive_attr_double(a, g, "time_to_balance", ttb, "1");
    if (!st) st = autobal_archive_attr_int(a, g, "balanced", balanced);
    if (!st) st = autobal_archive_attr_double(a, g, "t_reached", t_reached, "1");
    if (!st) st = autobal_archive_attr_double_array(a, g, "final_state", 8, y, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "unbalance_initial", r.unb_initial, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "unbalance_final", dfin.unbalance, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "amplitude_max", r.amp_max, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "alpha_final", dfin.alpha, "rad");
    if (!st) st = autobal_archive_attr_double(a, g, "beta_final", dfin.beta, "rad");
    if (!st && have_verdict)
      st = autobal_archive_attr_string(a, g, "linear_verdict", autobal_verdict_name(verdict));
    if (!st) st = cli_archive_solver_stats(a, "/pendulum/transient/solver", tr, &stats, "1");
    rc = cli_archive_end(ctx, &a, st, rc);
  }
finish:
  if (a) rc = cli_archive_end(ctx, &a, AUTOBAL_SUCCESS, rc);
  if (rc == CLI_EXIT_OK || rc == CLI_EXIT_NUMERIC || rc == CLI_EXIT_INTERRUPTED) {
    if (ctx->json) {
      cli_json jj;
      cli_json_summary_begin(&jj, ctx);
      if (have_verdict) cli_json_string(&jj, "linear_verdict", autobal_verdict_name(verdict));
      cli_json_bool(&jj, "balanced", balanced);
      cli_json_quantity(&jj, "time_to_balance", ttb, "1");
      cli_json_quantity(&jj, "t_reached", t_reached, "1");
      cli_json_quantity(&jj, "unbalance_initial", r.unb_initial, "1");
      cli_json_quantity(&jj, "unbalance_final", dfin.unbalance, "1");
      cli_json_quantity(&jj, "amplitude_max", r.amp_max, "1");
      cli_json_quantity(&jj, "amplitude_final", dfin.amplitude, "1");
      cli_json_quantity(&jj, "alpha_final", dfin.alpha, "rad");
      cli_json_quantity(&jj, "beta_final", dfin.beta, "rad");
      cli_json_numbers(&jj, "final_state", y, 8);
      cli_json_int(&jj, "steps", (long)stats.steps);
      cli_json_int(&jj, "rhs_evaluations", (long)stats.rhs_evals);
      cli_json_quantity(&jj, "wall_time", stats.wall_seconds, "s");
      if (c.physical) {
        const double w0 = sqrt(c.phys.c / (c.phys.M + 2 * c.phys.m)), ml2 = 2.0 * c.phys.m * c.phys.l;
        cli_json_quantity(&jj, "omega0", w0, "rad/s");
        cli_json_quantity(&jj, "time_to_balance_s", ttb / w0, "s");
        cli_json_quantity(&jj, "unbalance_final_abs", dfin.unbalance * ml2, "kg m");
        cli_json_quantity(&jj, "amplitude_max_m", r.amp_max * c.phys.l, "m");
      }
      cli_json_summary_end(&jj, ctx);
    } else if (!ctx->quiet) {
      printf("pendulum transient: R_w = %.6g  R_m = %.6g  H = %.6g  h = %.6g  psi0 = %.6g rad; tau in [0, %.6g] "
             "(%.1f revolutions)\n",
             c.p.R_w, c.p.R_m, c.p.H, c.p.h, c.p.psi0, t_reached, t_reached / rev_period);
      if (have_verdict) printf("  main motion (4) by the linear analysis (6): %s\n", autobal_verdict_name(verdict));
      printf("  residual unbalance |d| (units of 2 m l): %.4g at the start -> %.4g at the end\n", r.unb_initial,
             dfin.unbalance);
      printf("  shaft amplitude (units of l): %.4g at the start, max %.4g, %.4g at the end\n", r.amp_initial,
             r.amp_max, dfin.amplitude);
      printf("  pendulum angles at the end relative to psi0: alpha = %.6g rad, beta = %.6g rad\n", dfin.alpha,
             dfin.beta);
      if (balanced)
        printf("  BALANCED: |d| below %.3g from tau = %.6g on (held for %.6g revolutions)\n", c.balance_tol, ttb,
               c.balance_revs);
      else
        printf("  NOT balanced: |d| did not stay below %.3g for %.6g revolutions\n", c.balance_tol, c.balance_revs);
      if (c.physical) { /* the same in physical units: t = tau / omega0, lengths in l, unbalance in 2 m l */
        const double w0 = sqrt(c.phys.c / (c.phys.M + 2 * c.phys.m)), ml2 = 2.0 * c.phys.m * c.phys.l;
        printf("  physical: omega0 = %.6g rad/s, t in [0, %.6g] s; residual unbalance %.4g g mm -> %.4g g mm; "
               "shaft amplitude max %.4g um, %.4g um at the end",
               w0, t_reached / w0, r.unb_initial * ml2 * 1e6, dfin.unbalance * ml2 * 1e6, r.amp_max * c.phys.l * 1e6,
               dfin.amplitude * c.phys.l * 1e6);
        if (balanced) printf("; balanced from t = %.6g s", ttb / w0);
        printf("\n");
      }
      cli_print_solver_stats(tr, &stats);
      if (ctx->output) printf("archive: %s\n", ctx->output);
    }
  }
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  autobal_transient_free(tr);
  return rc;
}
