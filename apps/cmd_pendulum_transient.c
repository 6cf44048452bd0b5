/* cmd_pendulum_transient.c: `autobal pendulum transient`: the equations of motion (1) of the
 * two-pendulum autobalancer integrated in dimensionless time tau (docs/pendulum.md), streamed to
 * HDF5, summarised for a person: balanced or not, time to balance, residual unbalance, final
 * pendulum angles relative to the main motion (4).  The run and its archive layout are the
 * library's (autobal_study_pendulum_transient, src/studies/); this file reads and prints. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/archive.h"
#include "autobal/pendulum.h"
#include "autobal/study.h"
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
  const char *output; /* dense | exact */
  int stop_at_balance;
  int has_dt_out; /* dt_out given (else revs_out) */
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
  c->stepper = "dop853"; /* the library's default (autobal_study_pendulum_transient_options_default) */
  c->output = "dense6";
  if ((rc = get_d(ctx, "transient", "t_end", &c->t_end))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "dt_out", 0.0, &c->dt_out, &has_dt))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "revs_out", c->revs_out, &c->revs_out, &has_revs))) return rc;
  if ((rc = get_d(ctx, "transient", "rtol", &c->rtol))) return rc;
  if ((rc = get_d(ctx, "transient", "atol", &c->atol))) return rc;
  if ((rc = get_d(ctx, "transient", "h_max", &c->h_max))) return rc;
  if ((rc = cli_get_int(ctx, "transient", "max_steps", c->max_steps, &c->max_steps, NULL))) return rc;
  if ((rc = cli_get_string(ctx, "transient", "stepper", c->stepper, &c->stepper, NULL))) return rc;
  if ((rc = cli_get_string(ctx, "transient", "output", c->output, &c->output, NULL))) return rc;
  if (strcmp(c->output, "dense") != 0 && strcmp(c->output, "dense6") != 0 &&
        strcmp(c->output, "exact") != 0)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: output = '%s' is not one of: dense, dense6, exact", c->output);
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
  c->has_dt_out = has_dt;
  return CLI_EXIT_OK;
}

/* ---- the run: the library's study (autobal_study_pendulum_transient) ------------------- */
static int progress(double fraction, void *user) { return cli_progress(user, "pendulum transient", fraction); }

/* A message of the study in the configuration's sections. */
static int study_fail(cli_ctx *ctx, int st, const char *msg) {
  if (!strncmp(msg, "options: ", 9)) return cli_fail(ctx, cli_exit_code(st), "[transient]: %s", msg + 9);
  if (!strncmp(msg, "initial state: ", 15))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[initial]: the initial state must be finite");
  return cli_fail(ctx, cli_exit_code(st), "[pendulum]: %s", msg);
}

int cli_cmd_pendulum_transient(cli_ctx *ctx) {
  ptr_cfg c;
  autobal_study_pendulum_transient_options opt = autobal_study_pendulum_transient_options_default();
  autobal_study_pendulum_transient_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  int rc = CLI_EXIT_OK, st;

  memset(&sum, 0, sizeof sum);
  autobal_error_clear(&err);
  memset(&c, 0, sizeof c);
  if ((rc = read_config(ctx, &c))) return rc;
  if ((rc = cli_config_check_unused(ctx))) return rc;
  memcpy(opt.y0, c.y0, sizeof opt.y0);
  opt.t_end = c.t_end;
  opt.dt_out = c.has_dt_out ? c.dt_out : 0.0;
  opt.revs_out = c.revs_out;
  opt.rtol = c.rtol;
  opt.atol = c.atol;
  opt.h_max = c.h_max;
  opt.max_steps = (unsigned long)c.max_steps;
  opt.stepper = c.stepper;
  opt.exact_output = strcmp(c.output, "exact") == 0;
  opt.dense_order = strcmp(c.output, "dense6") == 0 ? 6 : 7;
  opt.balance_tol = c.balance_tol;
  opt.balance_revs = c.balance_revs;
  opt.stop_at_balance = c.stop_at_balance;
  opt.progress = progress;
  opt.progress_user = ctx;
  /* the inputs are checked before the archive is created: bad input leaves no file */
  if ((st = autobal_study_pendulum_transient_check(&c.p, &opt, &err)) < 0) return study_fail(ctx, st, err.message);
  if ((rc = cli_archive_open(ctx, "autobal pendulum transient", &a))) goto done;
  st = autobal_study_pendulum_transient(&c.p, c.physical ? &c.phys : NULL, &opt, a, &sum, &err);
  cli_progress_done(ctx);
  if (st == AUTOBAL_ECANCELLED)
    rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED,
                  "interrupted at tau = %.6g of %.6g; the archive keeps everything computed so far (status incomplete)",
                  sum.t_reached, c.t_end);
  else if (st < 0 && st == sum.solver.status) /* the integration failed */
    rc = cli_fail(ctx, cli_exit_code(st), "%s (tau reached %.9g of %.6g; partial results kept)", sum.solver_message,
                  sum.t_reached, c.t_end);
  else if (st < 0)
    rc = cli_fail(ctx, cli_exit_code(st), "%s", err.message);
  if (a) rc = cli_archive_end(ctx, &a, AUTOBAL_SUCCESS, rc);
  if ((rc == CLI_EXIT_OK || rc == CLI_EXIT_NUMERIC || rc == CLI_EXIT_INTERRUPTED) && sum.solver.stop_reason != 0) {
    if (ctx->json) {
      cli_json jj;
      cli_json_summary_begin(&jj, ctx);
      if (sum.have_linear_verdict) cli_json_string(&jj, "linear_verdict", autobal_verdict_name(sum.linear_verdict));
      cli_json_bool(&jj, "balanced", sum.balanced);
      cli_json_quantity(&jj, "time_to_balance", sum.time_to_balance, "1");
      cli_json_quantity(&jj, "t_reached", sum.t_reached, "1");
      cli_json_quantity(&jj, "unbalance_initial", sum.unbalance_initial, "1");
      cli_json_quantity(&jj, "unbalance_final", sum.unbalance_final, "1");
      cli_json_quantity(&jj, "amplitude_max", sum.amplitude_max, "1");
      cli_json_quantity(&jj, "amplitude_final", sum.amplitude_final, "1");
      cli_json_quantity(&jj, "alpha_final", sum.alpha_final, "rad");
      cli_json_quantity(&jj, "beta_final", sum.beta_final, "rad");
      {
        static const char *const names[8] = {"xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate"};
        /* dimensionless: lengths in units of l, rates per tau = omega0 t */
        static const char *const units[8] = {"1", "1", "rad", "rad", "1", "1", "rad", "rad"};
        int k;
        cli_json_numbers(&jj, "final_state", sum.final_state, 8);
        cli_json_array(&jj, "final_state_names");
        for (k = 0; k < 8; k++) cli_json_string(&jj, NULL, names[k]);
        cli_json_array_end(&jj);
        cli_json_array(&jj, "final_state_units");
        for (k = 0; k < 8; k++) cli_json_string(&jj, NULL, units[k]);
        cli_json_array_end(&jj);
      }
      cli_json_int(&jj, "steps", (long)sum.solver.steps);
      cli_json_int(&jj, "rhs_evaluations", (long)sum.solver.rhs_evals);
      cli_json_quantity(&jj, "wall_time", sum.solver.wall_seconds, "s");
      if (c.physical) {
        const double w0 = sqrt(c.phys.c / (c.phys.M + 2 * c.phys.m)), ml2 = 2.0 * c.phys.m * c.phys.l;
        cli_json_quantity(&jj, "omega0", w0, "rad/s");
        cli_json_quantity(&jj, "time_to_balance_s", sum.time_to_balance / w0, "s");
        cli_json_quantity(&jj, "unbalance_final_abs", sum.unbalance_final * ml2, "kg m");
        cli_json_quantity(&jj, "amplitude_max_m", sum.amplitude_max * c.phys.l, "m");
      }
      cli_json_summary_end(&jj, ctx);
    } else if (!ctx->quiet) {
      printf("pendulum transient: R_w = %.6g  R_m = %.6g  H = %.6g  h = %.6g  psi0 = %.6g rad; tau in [0, %.6g] "
             "(%.1f revolutions)\n",
             c.p.R_w, c.p.R_m, c.p.H, c.p.h, c.p.psi0, sum.t_reached, sum.t_reached / sum.revolution_period);
      if (sum.have_linear_verdict)
        printf("  main motion (4) by the linear analysis (6): %s\n", autobal_verdict_name(sum.linear_verdict));
      printf("  residual unbalance |d| (units of 2 m l): %.4g at the start -> %.4g at the end\n", sum.unbalance_initial,
             sum.unbalance_final);
      printf("  shaft amplitude (units of l): %.4g at the start, max %.4g, %.4g at the end\n", sum.amplitude_initial,
             sum.amplitude_max, sum.amplitude_final);
      printf("  pendulum angles at the end relative to psi0: alpha = %.6g rad, beta = %.6g rad\n", sum.alpha_final,
             sum.beta_final);
      if (sum.balanced)
        printf("  BALANCED: |d| below %.3g from tau = %.6g on (held for %.6g revolutions)\n", c.balance_tol,
               sum.time_to_balance, c.balance_revs);
      else
        printf("  NOT balanced: |d| did not stay below %.3g for %.6g revolutions\n", c.balance_tol, c.balance_revs);
      if (c.physical) { /* the same in physical units: t = tau / omega0, lengths in l, unbalance in 2 m l */
        const double w0 = sqrt(c.phys.c / (c.phys.M + 2 * c.phys.m)), ml2 = 2.0 * c.phys.m * c.phys.l;
        printf("  physical: omega0 = %.6g rad/s, t in [0, %.6g] s; residual unbalance %.4g g mm -> %.4g g mm; "
               "shaft amplitude max %.4g um, %.4g um at the end",
               w0, sum.t_reached / w0, sum.unbalance_initial * ml2 * 1e6, sum.unbalance_final * ml2 * 1e6,
               sum.amplitude_max * c.phys.l * 1e6, sum.amplitude_final * c.phys.l * 1e6);
        if (sum.balanced) printf("; balanced from t = %.6g s", sum.time_to_balance / w0);
        printf("\n");
      }
      cli_print_solver_line(sum.stepper, &sum.solver);
      if (ctx->output) printf("archive: %s\n", ctx->output);
    }
  }
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  return rc;
}
