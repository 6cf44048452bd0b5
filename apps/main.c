/* main.c: `autobal`, the command-line program: dispatch, common options, exit codes. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "cli.h"
#include "commands.h"
#include "help.h"

static void print_usage(FILE *f) {
  size_t i;
  fputs(HELP_USAGE_HEAD, f);
  for (i = 0; i < cli_ncommands; i++)
    fprintf(f, "  %-28s %s\n", cli_commands[i].name, cli_commands[i].summary);
  fputs(HELP_USAGE_TAIL, f);
}

static void print_version(void) {
  char h5[32];
  autobal_hdf5_version(h5, sizeof h5);
  printf("autobal %s (git %s), GSL %s, HDF5 %s\n", autobal_version(), autobal_git_revision(), autobal_gsl_version(),
         h5);
}

/* The models, with the text of `autobal MODEL --help` and their documentation; a model is the
 * first word of the "model action" commands of the table. */
static const char *const model_help[][3] = {
    {"pendulum", HELP_MODEL_PENDULUM, HELP_DOCS_PENDULUM},
    {"rotor", HELP_MODEL_ROTOR, HELP_DOCS_ROTOR},
};

/* The length of the first word of a command name. */
static size_t first_word_len(const char *name) {
  const char *sp = strchr(name, ' ');
  return sp ? (size_t)(sp - name) : strlen(name);
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

/* The action of a "model action" command, or NULL when `name` is not one of `model`. */
static const char *action_of(const char *name, const char *model) {
  size_t lm = strlen(model);
  return strncmp(name, model, lm) == 0 && name[lm] == ' ' ? name + lm + 1 : NULL;
}

static const cli_command *find_command(const char *model, const char *action) {
  size_t i;
  if (!action) return NULL;
  for (i = 0; i < cli_ncommands; i++) {
    const char *a = action_of(cli_commands[i].name, model);
    if (a && strcmp(a, action) == 0) return &cli_commands[i];
  }
  return NULL;
}

static int is_model(const char *word) {
  size_t i;
  for (i = 0; i < cli_ncommands; i++)
    if (action_of(cli_commands[i].name, word)) return 1;
  return 0;
}

typedef char cli_word[64];

/* With model NULL: the first words of the table (the models and the single-word commands) and
 * "help"; else that model's actions.  Distinct, in the order of the table, into w (room for
 * cli_ncommands + 1 words), with ptr[k] = w[k].  Returns the count. */
static size_t list_words(const char *model, cli_word *w, const char **ptr) {
  size_t i, j, n = 0;
  for (i = 0; i < cli_ncommands; i++) {
    const char *name = cli_commands[i].name, *word = model ? action_of(name, model) : name;
    size_t len;
    if (!word) continue;
    len = model ? strlen(word) : first_word_len(name);
    if (len >= sizeof w[0]) continue;
    for (j = 0; j < n; j++)
      if (strlen(w[j]) == len && strncmp(w[j], word, len) == 0) break;
    if (j < n) continue;
    memcpy(w[n], word, len);
    w[n][len] = '\0';
    ptr[n] = w[n];
    n++;
  }
  if (!model) {
    snprintf(w[n], sizeof w[n], "help");
    ptr[n] = w[n];
    n++;
  }
  return n;
}

/* How many edits a mistyped command word may have for a suggestion: 1 for up to 3 letters, 2 up
 * to 5, 3 from 6 on. */
static size_t word_edits(const char *word) {
  size_t m = strlen(word) / 2;
  return m < 1 ? 1 : m > 3 ? 3 : m;
}

/* An unknown word on stderr: the model or command `word` (model NULL; `next` the word after it),
 * or the action `word` of `model`; with "did you mean" when a name is close, else the list of
 * names.  Returns the exit code. */
static int unknown_word(const char *model, const char *word, const char *next) {
  size_t n, i, pos = 0;
  cli_word *w = malloc((cli_ncommands + 1) * sizeof *w);
  const char **ptr = malloc((cli_ncommands + 1) * sizeof *ptr);
  char close[512], names[512];
  if (!w || !ptr) {
    free(w);
    free(ptr);
    fprintf(stderr, "autobal: error: out of memory\n");
    return CLI_EXIT_INTERNAL;
  }
  n = list_words(model, w, ptr);
  names[0] = '\0';
  for (i = 0; i < n && pos + strlen(ptr[i]) + 3 < sizeof names; i++)
    pos += (size_t)snprintf(names + pos, sizeof names - pos, "%s%s", i ? ", " : "", ptr[i]);
  if (model) {
    const cli_command *elsewhere = NULL;
    for (i = 0; i < cli_ncommands && !elsewhere; i++) {
      const char *sp = strchr(cli_commands[i].name, ' ');
      if (sp && strcmp(sp + 1, word) == 0) elsewhere = &cli_commands[i];
    }
    if (elsewhere)
      fprintf(stderr, "autobal: error: unknown action '%s' for model '%s'; did you mean 'autobal %s'?\n", word, model,
              elsewhere->name);
    else if (cli_did_you_mean(word, ptr, n, word_edits(word), close, sizeof close))
      fprintf(stderr, "autobal: error: unknown action '%s' for model '%s'; did you mean %s?\n", word, model, close);
    else
      fprintf(stderr, "autobal: error: unknown action '%s' for model '%s' (actions: %s; see 'autobal %s --help')\n",
              word, model, names, model);
  } else if (next && find_command(next, word)) { /* the action before the model */
    fprintf(stderr, "autobal: error: unknown model or command '%s'; did you mean 'autobal %s %s'?\n", word, next,
            word);
  } else if (cli_did_you_mean(word, ptr, n, word_edits(word), close, sizeof close)) {
    fprintf(stderr, "autobal: error: unknown model or command '%s'; did you mean %s?\n", word, close);
  } else {
    fprintf(stderr, "autobal: error: unknown model or command '%s' (one of: %s; see 'autobal --help')\n", word, names);
  }
  free(w);
  free(ptr);
  return CLI_EXIT_USAGE;
}

/* `autobal MODEL --help`: the model in a few lines, its actions one line each, its documentation. */
static void print_model_help(FILE *f, const char *model) {
  size_t i, m;
  fprintf(f, "usage: autobal %s <action> [CONFIG.ini] [options]\n", model);
  for (m = 0; m < sizeof model_help / sizeof model_help[0]; m++)
    if (strcmp(model_help[m][0], model) == 0) break;
  if (m < sizeof model_help / sizeof model_help[0]) fprintf(f, "\n%s", model_help[m][1]);
  fprintf(f, "\nactions:\n");
  for (i = 0; i < cli_ncommands; i++) {
    const char *a = action_of(cli_commands[i].name, model);
    if (a) fprintf(f, "  %-12s %s\n", a, cli_commands[i].summary);
  }
  fprintf(f, "\n'autobal %s ACTION --help' (or 'autobal help %s ACTION') lists the configuration keys of an action.\n",
          model, model);
  if (m < sizeof model_help / sizeof model_help[0]) fputs(model_help[m][2], f);
}

/* `autobal CMD --help` and `autobal help CMD`. */
static void print_command_help(FILE *f, const cli_command *cmd) {
  if (strchr(cmd->name, ' ')) fprintf(f, "usage: autobal %s [CONFIG.ini] [options]\n\n%s", cmd->name, cmd->help);
  else fprintf(f, "usage: autobal %s FILE.h5 [options]\n\n%s", cmd->name, cmd->help);
}

/* `--set X` where X has no '=' (e.g. `--set rotor.omega 300`, whose 300 would otherwise be taken
 * for the CONFIG file): say so at once, with the assignment meant when the next argument is a
 * number.  Returns the exit code. */
static int set_without_equals(const char *assignment, const char *next) {
  char *end = NULL;
  int number = 0;
  if (next && next[0]) {
    (void)strtod(next, &end);
    number = end != next && *end == '\0';
  }
  if (number)
    fprintf(stderr,
            "autobal: error: --set '%s': '=' is missing; expected --set SECTION.KEY=VALUE, here --set %s=%s\n",
            assignment, assignment, next);
  else
    fprintf(stderr, "autobal: error: --set '%s': '=' is missing; expected --set SECTION.KEY=VALUE\n", assignment);
  return CLI_EXIT_USAGE;
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

/* Everything after the options are read: `words` are the positional arguments (after "help"
 * when help_cmd), `sets` the --set assignments. */
static int dispatch(cli_ctx *ctx, const char **words, int nwords, int want_help, int help_cmd, const char **sets,
                    int nsets) {
  const cli_command *cmd;
  const char *model = nwords > 0 ? words[0] : NULL, *action = nwords > 1 ? words[1] : NULL;
  int i, rc;
  if (!model || (help_cmd && strcmp(model, "help") == 0 && nwords == 1)) {
    print_usage(want_help ? stdout : stderr);
    return want_help ? CLI_EXIT_OK : CLI_EXIT_USAGE;
  }
  cmd = find_archive_command(model);
  if (!cmd && !is_model(model)) return unknown_word(NULL, model, action);
  if (!cmd && action) {
    cmd = find_command(model, action);
    if (!cmd) return unknown_word(model, action, NULL);
  }
  if (help_cmd && nwords > (cmd && strchr(cmd->name, ' ') ? 2 : 1)) {
    fprintf(stderr, "autobal: error: unexpected argument '%s' after 'autobal help %s'\n",
            words[cmd && strchr(cmd->name, ' ') ? 2 : 1], cmd ? cmd->name : model);
    return CLI_EXIT_USAGE;
  }
  if (!cmd) { /* a model alone: its actions */
    print_model_help(want_help ? stdout : stderr, model);
    return want_help ? CLI_EXIT_OK : CLI_EXIT_USAGE;
  }
  if (want_help) {
    print_command_help(stdout, cmd);
    return CLI_EXIT_OK;
  }
  if (nwords > 3) {
    fprintf(stderr, "autobal: error: unexpected argument '%s' (one CONFIG file at most)\n", words[3]);
    return CLI_EXIT_USAGE;
  }
  ctx->command = cmd->name;
  if (ctx->json) ctx->progress = 0;
  if (!strchr(cmd->name, ' ')) {
    if (nwords > 2 || nsets > 0) {
      fprintf(stderr, "autobal: error: '%s' takes one archive FILE.h5%s (see 'autobal %s --help')\n", cmd->name,
              nsets > 0 ? " and no --set" : "", cmd->name);
      return CLI_EXIT_USAGE;
    }
    ctx->config_path = action; /* the archive; NULL: the command says what is missing */
    ctx->cfg = cli_config_new(NULL);
    if (!ctx->cfg) return CLI_EXIT_INTERNAL;
    return run_command(ctx, cmd, CLI_EXIT_OK);
  }
  ctx->config_path = nwords > 2 ? words[2] : NULL;
  ctx->cfg = cli_config_new(ctx->config_path);
  if (!ctx->cfg) return CLI_EXIT_INTERNAL;
  rc = cli_config_load(ctx);
  for (i = 0; rc == CLI_EXIT_OK && i < nsets; i++) rc = cli_config_override(ctx, sets[i]);
  return run_command(ctx, cmd, rc);
}

int main(int argc, char **argv) {
  cli_ctx ctx;
  int i, rc, want_help = 0, help_cmd = 0, nsets = 0, nwords = 0;
  const char **sets = NULL, **words = NULL;

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
  words = calloc((size_t)argc, sizeof *words);
  if (!sets || !words) {
    free(sets);
    free(words);
    return CLI_EXIT_INTERNAL;
  }
  rc = -1;
  for (i = 1; i < argc && rc < 0; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) want_help = 1;
    else if (!strcmp(a, "--version")) {
      print_version();
      rc = CLI_EXIT_OK;
    } else if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "-s") || !strcmp(a, "--set")) {
      if (i + 1 >= argc) {
        fprintf(stderr, "autobal: error: %s needs a value\n", a);
        rc = CLI_EXIT_USAGE;
      } else if (a[1] == 'o' || !strcmp(a, "--output")) {
        ctx.output = argv[++i];
      } else {
        sets[nsets++] = argv[++i];
        if (!strchr(sets[nsets - 1], '=')) rc = set_without_equals(sets[nsets - 1], i + 1 < argc ? argv[i + 1] : NULL);
      }
    } else if (!strncmp(a, "--output=", 9)) ctx.output = a + 9;
    else if (!strncmp(a, "--set=", 6)) {
      sets[nsets++] = a + 6;
      if (!strchr(a + 6, '=')) rc = set_without_equals(a + 6, i + 1 < argc ? argv[i + 1] : NULL);
    } else if (!strcmp(a, "-f") || !strcmp(a, "--force")) ctx.force = 1;
    else if (!strcmp(a, "--json")) ctx.json = 1;
    else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) ctx.quiet = 1;
    else if (!strcmp(a, "--no-progress")) ctx.progress = 0;
    else if (a[0] == '-' && a[1] != '\0') {
      fprintf(stderr, "autobal: error: unknown option '%s' (see 'autobal --help')\n", a);
      rc = CLI_EXIT_USAGE;
    } else if (nwords == 0 && !help_cmd && !strcmp(a, "help")) {
      help_cmd = want_help = 1; /* `autobal help CMD` is `autobal CMD --help` */
    } else {
      words[nwords++] = a;
    }
  }
  if (rc < 0) rc = dispatch(&ctx, words, nwords, want_help, help_cmd, sets, nsets);
  free(sets);
  free(words);
  return rc;
}
