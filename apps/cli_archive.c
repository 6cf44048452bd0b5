/* cli_archive.c: opening and finishing an archive for a command (provenance, the given and the
 * effective configuration for re-runs, the status attribute from the exit code), and the
 * transient driver's statistics shared by the transient commands. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "autobal/archive.h"
#include "autobal/study.h"
#include "cli.h"

/* Root attribute effective_config: every key the command read, with the value used (defaults
 * included), so that `autobal rerun` does not depend on the built-in defaults. */
static int write_effective_config(cli_ctx *ctx, autobal_archive *a) {
  char *eff = cli_config_effective_ini(ctx->cfg, ctx->command);
  int st;
  if (!eff) return AUTOBAL_ENOMEM;
  st = autobal_archive_attr_string(a, "/", "effective_config", eff);
  free(eff);
  if (st == AUTOBAL_SUCCESS) cli_config_effective_archived(ctx->cfg);
  return st;
}

int cli_archive_open(cli_ctx *ctx, const char *title, autobal_archive **out) {
  autobal_error err;
  int st;
  char *ini = NULL;
  *out = NULL;
  if (!ctx->output) return CLI_EXIT_OK;
  if (ctx->output[0] == '\0') return cli_fail(ctx, CLI_EXIT_USAGE, "-o needs a file name, got an empty one");
  if (ctx->config_path) {
    struct stat so, sc;
    if (stat(ctx->output, &so) == 0 && stat(ctx->config_path, &sc) == 0 && so.st_dev == sc.st_dev &&
        so.st_ino == sc.st_ino)
      return cli_fail(ctx, CLI_EXIT_IO, "output file '%s' is the configuration file itself; refusing to overwrite it",
                      ctx->output);
  }
  autobal_error_clear(&err);
  st = autobal_archive_create(ctx->output, ctx->force, out, &err);
  if (st == AUTOBAL_EEXIST)
    return cli_fail(ctx, CLI_EXIT_IO, "output file '%s' exists; use --force to overwrite it", ctx->output);
  if (st != AUTOBAL_SUCCESS) return cli_fail(ctx, cli_exit_code(st), "%s", err.message);
  st = autobal_archive_provenance(*out, title, ctx->argc, (const char *const *)ctx->argv);
  if (st == AUTOBAL_SUCCESS) st = autobal_archive_attr_string(*out, "/", "command", ctx->command);
  if (st == AUTOBAL_SUCCESS) {
    ini = cli_config_given_ini(ctx->cfg);
    if (!ini) st = AUTOBAL_ENOMEM;
    else st = autobal_archive_attr_string(*out, "/", "input_config", ini);
    free(ini);
  }
  if (st == AUTOBAL_SUCCESS) st = write_effective_config(ctx, *out);
  if (st != AUTOBAL_SUCCESS) {
    int code = cli_fail(ctx, cli_exit_code(st), "%s",
                        st == AUTOBAL_ENOMEM ? "out of memory recording the configuration" : autobal_archive_errmsg(*out));
    autobal_archive_discard(*out);
    *out = NULL;
    return code;
  }
  return CLI_EXIT_OK;
}

int cli_archive_finish(cli_ctx *ctx, autobal_archive *a, int exit_code) {
  autobal_error err;
  if (!a) return exit_code;
  if (cli_config_effective_stale(ctx->cfg)) { /* keys read after cli_archive_open */
    int st = write_effective_config(ctx, a);
    if (st != AUTOBAL_SUCCESS && exit_code == CLI_EXIT_OK)
      exit_code = cli_fail(ctx, cli_exit_code(st), "%s",
                           st == AUTOBAL_ENOMEM ? "out of memory recording the configuration" : autobal_archive_errmsg(a));
  }
  if (exit_code == CLI_EXIT_INTERRUPTED) {
    autobal_archive_set_status(a, "incomplete", cli_signal_reason());
  } else if (exit_code != CLI_EXIT_OK) {
    autobal_archive_set_status(a, "incomplete", ctx->err[0] ? ctx->err : "failed");
  }
  autobal_error_clear(&err);
  if (autobal_archive_close(a, &err) != AUTOBAL_SUCCESS) {
    /* HDF5 1.10 can crash in its exit handler after a failed close (disk full; fixed upstream
     * in 1.14.1): report and leave at once, as archive.h advises. */
    fprintf(stderr, "autobal: error: %s\n", exit_code == CLI_EXIT_OK ? err.message : ctx->err);
    if (exit_code != CLI_EXIT_OK) fprintf(stderr, "autobal: error: %s\n", err.message);
    fflush(stdout);
    fflush(stderr);
    _exit(exit_code == CLI_EXIT_OK ? CLI_EXIT_IO : exit_code);
  }
  return exit_code;
}

int cli_archive_end(cli_ctx *ctx, autobal_archive **a, int st, int exit_code) {
  if (st != AUTOBAL_SUCCESS && exit_code == CLI_EXIT_OK)
    exit_code = cli_fail(ctx, cli_exit_code(st), "%s", autobal_archive_errmsg(*a));
  exit_code = cli_archive_finish(ctx, *a, exit_code);
  *a = NULL;
  return exit_code;
}

int cli_archive_solver_stats(autobal_archive *a, const char *group, const autobal_transient *tr,
                             const autobal_transient_stats *stats, const char *time_unit) {
  return autobal_study_write_solver_stats(a, group, autobal_transient_get_options(tr).stepper, stats,
                                          autobal_transient_errmsg(tr), time_unit);
}

void cli_print_solver_stats(const autobal_transient *tr, const autobal_transient_stats *stats) {
  cli_print_solver_line(autobal_transient_get_options(tr).stepper, stats);
}

void cli_print_solver_line(const char *stepper, const autobal_transient_stats *stats) {
  printf("  solver %s: %lu steps, %lu rejected, %lu rhs evaluations, %.3f s wall\n", stepper, stats->steps,
         stats->rejected, stats->rhs_evals, stats->wall_seconds);
}
