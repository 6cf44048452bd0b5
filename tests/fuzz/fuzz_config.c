/* fuzz_config.c: libFuzzer target for the configuration reader of the command line.
 *
 * Input format (seed files in corpus/config/ are readable text):
 *     <INI text> [ "\n--set " <assignment> ]...
 * The INI text goes through cli_config_load_text() (the parser behind cli_config_load(): the
 * NUL and line-length checks, inih, the duplicate-key handler), every assignment through
 * cli_config_override() exactly as `--set` does.  If that succeeds, the configuration is read by
 * the commands' own readers:
 *   - read_config() of `autobal pendulum transient` ([pendulum] dimensionless or physical,
 *     [initial], [transient]) and, when it accepts, the model: autobal_pendulum_analyze() and
 *     one right-hand-side evaluation of (1) at the initial state;
 *   - read_rotor_config() of `autobal rotor transient` ([rotor], [supports], [lumped],
 *     [initial], [plane1], [plane2], [transient]) and, when it accepts, the model:
 *     autobal_rotor_alloc(), the initial state, both right-hand sides, the derived outputs;
 *   - cli_config_check_unused() (unknown keys, "did you mean") and cli_config_to_ini().
 * Properties checked (abort() = a finding):
 *   - nothing crashes, leaks or trips ASan/UBSan (the sanitizers do that);
 *   - every failure leaves a message (ctx.err non-empty) and a documented exit code (3 or 2);
 *   - when everything was accepted, the effective configuration written by cli_config_to_ini()
 *     (what the apps store in the archive for `autobal rerun`) parses again to the same text
 *     (whitespace aside).
 * Build and run: tests/fuzz/run.sh (see README.md).  The same file, compiled with
 * replay_main.c instead of libFuzzer, replays the corpus as a CTest test. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal.h"
#include "cli.h"
#include "fuzz_readers.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define MAX_SETS 16
static const char set_marker[] = "\n--set ";

static autobal_pendulum_workspace *g_ws; /* fuzz harness only: one workspace for the process */

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  gsl_set_error_handler_off();
  g_ws = autobal_pendulum_workspace_alloc();
  return 0;
}

static void finding(const char *what, const cli_ctx *ctx) {
  fprintf(stderr, "fuzz_config: %s (rc message: '%s')\n", what, ctx->err);
  abort();
}

/* Every non-zero code must come with a message and be one of the documented input codes. */
static void check_failure(int rc, const cli_ctx *ctx) {
  if (rc == CLI_EXIT_OK) return;
  if (ctx->err[0] == '\0') finding("failure without a message", ctx);
  if (rc != CLI_EXIT_INPUT && rc != CLI_EXIT_USAGE && rc != CLI_EXIT_INTERNAL) finding("unexpected exit code", ctx);
}

static char *strip_blanks(const char *s) {
  size_t n = strlen(s), i, j = 0;
  char *out = malloc(n + 1);
  if (!out) return NULL;
  for (i = 0; i < n; i++)
    if (s[i] != ' ' && s[i] != '\t') out[j++] = s[i];
  out[j] = '\0';
  return out;
}

static void model_pendulum(const autobal_pendulum_params *p, const double y0[8]) {
  autobal_pendulum_result res;
  autobal_pendulum_motion motion;
  double dydt[8];
  if (g_ws) (void)autobal_pendulum_analyze(g_ws, p, &res);
  if (autobal_pendulum_motion_init(&motion, p, NULL) == AUTOBAL_SUCCESS)
    (void)autobal_pendulum_motion_rhs(0.0, y0, dydt, &motion);
}

static void model_rotor(const autobal_rotor_params *p) {
  autobal_error err;
  autobal_rotor *r = autobal_rotor_alloc(p, &err);
  size_t dim, nout;
  double *y, *dydt, *out;
  if (!r) return;
  dim = autobal_rotor_dim(r);
  nout = autobal_rotor_output_count(r);
  y = malloc(dim * sizeof *y);
  dydt = malloc(dim * sizeof *dydt);
  out = malloc((nout ? nout : 1) * sizeof *out);
  if (y && dydt && out && autobal_rotor_initial_state(r, AUTOBAL_ROTOR_FIXED, 0.0, y, dim) == AUTOBAL_SUCCESS) {
    (void)autobal_rotor_rhs(0.0, y, dydt, r);
    (void)autobal_rotor_outputs(r, AUTOBAL_ROTOR_FIXED, 0.0, y, out, nout);
    (void)autobal_rotor_balance_monitor(r, AUTOBAL_ROTOR_FIXED, 0.0, y);
    if (autobal_rotor_convert_state(r, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, 0.0, y, y, dim) == AUTOBAL_SUCCESS)
      (void)autobal_rotor_rhs_rotating(0.0, y, dydt, r);
  }
  free(y);
  free(dydt);
  free(out);
  autobal_rotor_free(r);
}

/* The effective configuration must survive the trip through the archive's text form. */
static void check_roundtrip(const cli_ctx *ctx) {
  cli_ctx again;
  char *a = cli_config_to_ini(ctx->cfg), *b = NULL, *sa = NULL, *sb = NULL;
  int rc;
  if (!a) return; /* out of memory */
  memset(&again, 0, sizeof again);
  again.command = ctx->command;
  again.config_path = "roundtrip.ini";
  again.cfg = cli_config_new(again.config_path);
  if (!again.cfg) {
    free(a);
    return;
  }
  rc = cli_config_load_text(&again, "roundtrip.ini", a, strlen(a));
  if (rc != CLI_EXIT_OK) {
    fprintf(stderr, "---- effective configuration ----\n%s---- error: %s\n", a, again.err);
    finding("cli_config_to_ini() wrote text that does not parse again", ctx);
  }
  b = cli_config_to_ini(again.cfg);
  sa = strip_blanks(a);
  sb = b ? strip_blanks(b) : NULL;
  if (sa && sb && strcmp(sa, sb) != 0) {
    fprintf(stderr, "---- written ----\n%s---- read back ----\n%s----\n", a, b);
    finding("cli_config_to_ini() text reads back differently", ctx);
  }
  free(a);
  free(b);
  free(sa);
  free(sb);
  cli_config_free(again.cfg);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *text = (const char *)data;
  const char *end = text + size, *cut;
  size_t text_len;
  char *sets[MAX_SETS];
  size_t nsets = 0, i;
  cli_ctx ctx;
  int rc, rc_p, rc_r, accepted = 1;
  autobal_pendulum_params pp;
  double y0[8], t_end, dt_out;
  autobal_rotor_params rp;
  void *storage = NULL;

  /* split off the --set assignments */
  cut = NULL;
  for (i = 0; i + sizeof set_marker - 1 <= size; i++)
    if (memcmp(text + i, set_marker, sizeof set_marker - 1) == 0) {
      cut = text + i;
      break;
    }
  text_len = cut ? (size_t)(cut - text) : size;
  while (cut && nsets < MAX_SETS) {
    const char *start = cut + sizeof set_marker - 1, *next = NULL, *p;
    size_t len;
    for (p = start; p + sizeof set_marker - 1 <= end; p++)
      if (memcmp(p, set_marker, sizeof set_marker - 1) == 0) {
        next = p;
        break;
      }
    len = (size_t)((next ? next : end) - start);
    sets[nsets] = malloc(len + 1);
    if (!sets[nsets]) break;
    memcpy(sets[nsets], start, len);
    sets[nsets][len] = '\0'; /* an argv string ends at its first NUL, as here */
    nsets++;
    cut = next;
  }

  memset(&ctx, 0, sizeof ctx);
  ctx.command = "fuzz";
  ctx.config_path = "fuzz.ini";
  ctx.cfg = cli_config_new(ctx.config_path);
  if (!ctx.cfg) goto done;
  rc = cli_config_load_text(&ctx, ctx.config_path, text, text_len);
  check_failure(rc, &ctx);
  for (i = 0; rc == CLI_EXIT_OK && i < nsets; i++) {
    rc = cli_config_override(&ctx, sets[i]);
    check_failure(rc, &ctx);
  }
  if (rc != CLI_EXIT_OK) goto done;

  ctx.err[0] = '\0';
  rc_p = fuzz_read_pendulum_transient(&ctx, &pp, y0, &t_end, &dt_out);
  check_failure(rc_p, &ctx);
  if (rc_p == CLI_EXIT_OK) {
    if (!(t_end > 0 && dt_out > 0 && isfinite(t_end) && isfinite(dt_out)))
      finding("pendulum transient reader accepted a bad t_end/dt_out", &ctx);
    if (autobal_pendulum_params_validate(&pp, NULL) != AUTOBAL_SUCCESS)
      finding("pendulum reader accepted parameters the library rejects", &ctx);
    model_pendulum(&pp, y0);
  }
  accepted &= rc_p == CLI_EXIT_OK;

  ctx.err[0] = '\0';
  rc_r = fuzz_read_rotor_transient(&ctx, &rp, &storage);
  check_failure(rc_r, &ctx);
  if (rc_r == CLI_EXIT_OK) model_rotor(&rp);
  accepted &= rc_r == CLI_EXIT_OK;

  ctx.err[0] = '\0';
  rc = cli_config_check_unused(&ctx);
  check_failure(rc, &ctx);
  accepted &= rc == CLI_EXIT_OK;
  if (accepted) check_roundtrip(&ctx);

done:
  free(storage);
  cli_config_free(ctx.cfg);
  for (i = 0; i < nsets; i++) free(sets[i]);
  return 0;
}
