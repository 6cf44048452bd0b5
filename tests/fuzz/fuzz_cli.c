/* fuzz_cli.c: libFuzzer target for the command line as a whole: apps/main.c (option parsing,
 * dispatch, --set, -o, --help, --version, exit codes) with a configuration FILE, but with a
 * command table whose commands only READ their configuration (no computation, no files
 * written), so that one input takes microseconds.
 *
 * Input format: NUL-separated arguments, then "\0\0", then the contents of a configuration
 * file:
 *     arg1 \0 arg2 \0 ... argN \0 \0 <config file bytes>
 * argv[0] is "autobal"; an argument "@CONFIG@" is replaced by the path of a temporary file that
 * holds the configuration bytes (so cli_config_load() reads a real file: fopen, fstat, fread).
 * apps/main.c is compiled through main_renamed.c: main() becomes autobal_cli_main() and no signal
 * handler is installed (libFuzzer keeps its own SIGINT handling).
 * Properties: no crash, no leak, no sanitizer report; the exit code is one of the documented
 * ones (0, 2, 3, 4, 7). */
#define _POSIX_C_SOURCE 200809L
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "autobal.h"
#include "cli.h"
#include "commands.h"
#include "fuzz_readers.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int autobal_cli_main(int argc, char **argv);
void fuzz_no_signals(void);

void fuzz_no_signals(void) {}

static int run_pendulum(cli_ctx *ctx, const char *section) {
  autobal_pendulum_params p;
  autobal_pendulum_physical phys;
  int physical, rc;
  if ((rc = cli_read_pendulum_params(ctx, &p, &phys, &physical))) return rc;
  if (section) cli_declare_section(ctx, section);
  return cli_config_check_unused(ctx);
}
static int run_roots(cli_ctx *ctx) { return run_pendulum(ctx, NULL); }
static int run_critical(cli_ctx *ctx) { return run_pendulum(ctx, "critical"); }
static int run_map(cli_ctx *ctx) { return run_pendulum(ctx, "map"); }
static int run_ptr(cli_ctx *ctx) {
  autobal_pendulum_params p;
  double y0[8], t_end, dt_out;
  int rc = fuzz_read_pendulum_transient(ctx, &p, y0, &t_end, &dt_out);
  return rc ? rc : cli_config_check_unused(ctx);
}
static int run_rotor(cli_ctx *ctx) {
  autobal_rotor_params p;
  void *storage = NULL;
  int rc = fuzz_read_rotor_transient(ctx, &p, &storage);
  if (!rc) {
    autobal_error err;
    autobal_rotor *r = autobal_rotor_alloc(&p, &err);
    if (!r) rc = cli_fail(ctx, CLI_EXIT_INPUT, "%s", err.message);
    autobal_rotor_free(r);
  }
  free(storage);
  return rc ? rc : cli_config_check_unused(ctx);
}
static int run_archive(cli_ctx *ctx) {
  return ctx->config_path ? CLI_EXIT_OK : cli_fail(ctx, CLI_EXIT_USAGE, "no archive given");
}

const cli_command cli_commands[] = {
    {"pendulum roots", "", "", run_roots},          {"pendulum critical", "", "", run_critical},
    {"pendulum map", "", "", run_map},              {"pendulum transient", "", "", run_ptr},
    {"rotor transient", "", "", run_rotor},         {"info", "", "", run_archive},
    {"rerun", "", "", run_archive},                 {"plot", "", "", run_archive},
};
const size_t cli_ncommands = sizeof cli_commands / sizeof cli_commands[0];

#define MAX_ARGS 24
static char g_config_path[4096];

static void remove_config(void) { remove(g_config_path); }

int LLVMFuzzerInitialize(int *argc, char **argv[]) {
  (void)argc;
  (void)argv;
  const char *tmp = getenv("TMPDIR");
  snprintf(g_config_path, sizeof g_config_path, "%s/autobal-fuzz-cli-%ld.ini", tmp && *tmp ? tmp : "/tmp",
           (long)getpid());
  atexit(remove_config);
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *buf = malloc(size + 1), *p, *end;
  char *argv[MAX_ARGS + 2];
  int argc = 1, rc;
  const char *config = NULL;
  size_t config_len = 0;
  FILE *f;
  if (!buf) return 0;
  memcpy(buf, data, size);
  buf[size] = '\0';
  end = buf + size;
  argv[0] = (char *)"autobal";
  /* arguments up to the first empty one ("\0\0") */
  for (p = buf; p < end && argc <= MAX_ARGS;) {
    size_t len = strlen(p);
    if (len == 0) {
      config = p + 1;
      config_len = (size_t)(end - config);
      break;
    }
    argv[argc++] = strcmp(p, "@CONFIG@") == 0 ? g_config_path : p;
    p += len + 1;
  }
  argv[argc] = NULL;
  f = fopen(g_config_path, "wb");
  if (f) {
    if (config && config_len) fwrite(config, 1, config_len, f);
    fclose(f);
  }
  rc = autobal_cli_main(argc, argv);
  if (rc != 0 && rc != 2 && rc != 3 && rc != 4 && rc != 7) {
    fprintf(stderr, "fuzz_cli: undocumented exit code %d\n", rc);
    abort();
  }
  free(buf);
  return 0;
}
