/* main.c: `autobal`, the command-line program: dispatch, common options, exit codes. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "cli.h"
#include "commands.h"

static void print_usage(FILE *f) {
  size_t i;
  fprintf(f,
          "usage: autobal <model> <action> [CONFIG.ini] [options]\n"
          "       autobal info|rerun|plot FILE.h5 [options]\n"
          "       autobal --help | --version\n"
          "\n"
          "Dynamics of rotors with passive automatic balancers.  Every command runs on built-in\n"
          "defaults when no CONFIG is given; keys in CONFIG (INI) or --set override them.\n"
          "\n"
          "commands:\n");
  for (i = 0; i < cli_ncommands; i++)
    fprintf(f, "  %-28s %s\n", cli_commands[i].name, cli_commands[i].summary);
  fprintf(f,
          "\n"
          "options:\n"
          "  -o, --output FILE.h5    write an HDF5 archive (written to a temporary name, renamed when done)\n"
          "  -f, --force             overwrite FILE.h5 if it exists\n"
          "  -s, --set SEC.KEY=VAL   override a configuration value (repeatable)\n"
          "      --json              machine-readable summary on stdout (instead of the text summary)\n"
          "  -q, --quiet             no text summary\n"
          "      --no-progress       no progress bar (none is drawn unless stderr is a terminal)\n"
          "  -h, --help              help (with a command: its configuration keys)\n"
          "      --version           versions of autobal, GSL and HDF5\n"
          "\n"
          "exit codes:\n"
          "  0 success   2 bad command line   3 bad configuration or parameter   4 file error\n"
          "  5 numerical failure (partial results written)   6 interrupted (partial results written)\n"
          "  7 internal error\n");
}

static void print_version(void) {
  char h5[32];
  autobal_hdf5_version(h5, sizeof h5);
  printf("autobal %s (git %s), GSL %s, HDF5 %s\n", autobal_version(), autobal_git_revision(), autobal_gsl_version(),
         h5);
}

/* A single-word command (info, rerun, plot): it works on an archive FILE.h5, given where the
 * "model action" commands take CONFIG.ini; main passes it as ctx->config_path and loads no
 * configuration. */
static const cli_command *find_archive_command(const char *word) {
  size_t i;
  for (i = 0; i < cli_ncommands; i++)
    if (!strchr(cli_commands[i].name, ' ') && strcmp(cli_commands[i].name, word) == 0) return &cli_commands[i];
  return NULL;
}

static const cli_command *find_command(const char *model, const char *action) {
  size_t i;
  char name[128];
  snprintf(name, sizeof name, "%s %s", model, action ? action : "");
  for (i = 0; i < cli_ncommands; i++)
    if (strcmp(cli_commands[i].name, name) == 0) return &cli_commands[i];
  return NULL;
}

/* Run the command unless `rc` already says the configuration failed; report a failure on stderr;
 * release the configuration.  Returns the exit code. */
static int run_command(cli_ctx *ctx, const cli_command *cmd, int rc) {
  if (rc == CLI_EXIT_OK) {
    cli_signals_install();
    rc = cmd->run(ctx);
  }
  if (rc != CLI_EXIT_OK) fprintf(stderr, "autobal: error: %s\n", ctx->err[0] ? ctx->err : "failed (no message)");
  cli_config_free(ctx->cfg);
  return rc;
}

int main(int argc, char **argv) {
  cli_ctx ctx;
  const cli_command *cmd;
  int i, rc, want_help = 0;
  const char *model = NULL, *action = NULL;
  const char **sets = NULL;
  int nsets = 0;

  gsl_set_error_handler_off(); /* GSL failures come back as status codes */
  memset(&ctx, 0, sizeof ctx);
  ctx.argc = argc;
  ctx.argv = argv;
  ctx.progress = isatty(STDERR_FILENO) && isatty(STDOUT_FILENO);

  if (argc < 2) {
    print_usage(stderr);
    return CLI_EXIT_USAGE;
  }
  sets = calloc((size_t)argc, sizeof *sets);
  if (!sets) return CLI_EXIT_INTERNAL;
  for (i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) want_help = 1;
    else if (!strcmp(a, "--version")) {
      print_version();
      free(sets);
      return CLI_EXIT_OK;
    } else if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "-s") || !strcmp(a, "--set")) {
      if (i + 1 >= argc) {
        fprintf(stderr, "autobal: error: %s needs a value\n", a);
        free(sets);
        return CLI_EXIT_USAGE;
      }
      if (a[1] == 'o' || !strcmp(a, "--output")) ctx.output = argv[++i];
      else sets[nsets++] = argv[++i];
    } else if (!strncmp(a, "--output=", 9)) ctx.output = a + 9;
    else if (!strncmp(a, "--set=", 6)) sets[nsets++] = a + 6;
    else if (!strcmp(a, "-f") || !strcmp(a, "--force")) ctx.force = 1;
    else if (!strcmp(a, "--json")) ctx.json = 1;
    else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) ctx.quiet = 1;
    else if (!strcmp(a, "--no-progress")) ctx.progress = 0;
    else if (a[0] == '-' && a[1] != '\0') {
      fprintf(stderr, "autobal: error: unknown option '%s' (see 'autobal --help')\n", a);
      free(sets);
      return CLI_EXIT_USAGE;
    } else if (!model) model = a;
    else if (!action) action = a;
    else if (!ctx.config_path) ctx.config_path = a;
    else {
      fprintf(stderr, "autobal: error: unexpected argument '%s' (one CONFIG file at most)\n", a);
      free(sets);
      return CLI_EXIT_USAGE;
    }
  }
  if (!model) {
    free(sets);
    if (want_help) {
      print_usage(stdout);
      return CLI_EXIT_OK;
    }
    print_usage(stderr);
    return CLI_EXIT_USAGE;
  }
  cmd = find_archive_command(model);
  if (cmd) {
    if (want_help) {
      free(sets);
      printf("usage: autobal %s FILE.h5 [options]\n\n%s", cmd->name, cmd->help);
      return CLI_EXIT_OK;
    }
    if (ctx.config_path || nsets > 0) {
      fprintf(stderr, "autobal: error: '%s' takes one archive FILE.h5%s (see 'autobal %s --help')\n", cmd->name,
              nsets > 0 ? " and no --set" : "", cmd->name);
      free(sets);
      return CLI_EXIT_USAGE;
    }
    free(sets);
    ctx.command = cmd->name;
    ctx.config_path = action; /* the archive; NULL: the command says what is missing */
    if (ctx.json) ctx.progress = 0;
    ctx.cfg = cli_config_new(NULL);
    if (!ctx.cfg) return CLI_EXIT_INTERNAL;
    return run_command(&ctx, cmd, CLI_EXIT_OK);
  }
  cmd = find_command(model, action);
  if (!cmd) {
    free(sets);
    if (want_help && !action) {
      print_usage(stdout);
      return CLI_EXIT_OK;
    }
    fprintf(stderr, "autobal: error: unknown command '%s%s%s' (see 'autobal --help')\n", model, action ? " " : "",
            action ? action : "");
    return CLI_EXIT_USAGE;
  }
  if (want_help) {
    free(sets);
    printf("usage: autobal %s [CONFIG.ini] [options]\n\n%s\n", cmd->name, cmd->help);
    return CLI_EXIT_OK;
  }
  ctx.command = cmd->name;
  if (ctx.json) ctx.progress = 0;
  ctx.cfg = cli_config_new(ctx.config_path);
  if (!ctx.cfg) {
    free(sets);
    return CLI_EXIT_INTERNAL;
  }
  rc = cli_config_load(&ctx);
  for (i = 0; rc == CLI_EXIT_OK && i < nsets; i++) rc = cli_config_override(&ctx, sets[i]);
  free(sets);
  return run_command(&ctx, cmd, rc);
}
