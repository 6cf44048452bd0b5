/* cmd_rerun.c: `autobal rerun FILE.h5 -o NEW.h5 [--force] [--json] [-q]`: repeat the run
 * recorded in an archive.  Every archive holds, as root attributes, the command (`command`,
 * e.g. "rotor transient"), the configuration given (`input_config`: the INI text of the
 * configuration file plus the --set overrides) and the effective configuration
 * (`effective_config`: every key the command read with the value it used, built-in defaults
 * included; see cli_config_effective_ini), both written by cli_archive_open.  This command
 * reads the command and the effective configuration, rebuilds the configuration from it (keys
 * recorded as ";default KEY = VALUE" stay "not given" but use the recorded VALUE) and runs the
 * command again, writing NEW.h5.  So the run does not depend on the built-in defaults of this
 * autobal, except for the few values the configuration reader cannot know (lists such as a
 * plane's balls left out of the configuration: commented in effective_config).  Archives of
 * earlier versions without effective_config are re-run from input_config with this version's
 * defaults.  The data are reproduced bit for bit by the same version of autobal (the provenance
 * attributes `created` and `command_line` and the solver's wall time differ).  NEW.h5 records
 * the same `command`, `input_config` and `effective_config`, so it can be re-run in turn. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "autobal/archive.h"
#include "cli.h"
#include "commands.h"

int cli_cmd_rerun(cli_ctx *ctx); /* registered in commands.c */

/* Read string attribute `name` of the root group into a malloc'ed buffer (*out; NULL when
 * absent).  Returns an AUTOBAL status. */
static int read_root_string(autobal_archive *a, const char *name, char **out) {
  size_t len = 0;
  char probe[2];
  int st;
  *out = NULL;
  if (!autobal_archive_has(a, "/", name)) return AUTOBAL_SUCCESS;
  st = autobal_archive_read_attr_string(a, "/", name, probe, sizeof probe, &len);
  if (st < 0) return st;
  *out = malloc(len + 1);
  if (!*out) return AUTOBAL_ENOMEM;
  st = autobal_archive_read_attr_string(a, "/", name, *out, len + 1, NULL);
  if (st != AUTOBAL_SUCCESS) {
    free(*out);
    *out = NULL;
    return st < 0 ? st : AUTOBAL_EFORMAT;
  }
  return AUTOBAL_SUCCESS;
}

/* Apply the INI text written by cli_config_to_ini or cli_config_effective_ini ("[section]" lines,
 * "key = value" lines, ";default key = value" lines, other ';' comment lines, blank lines) to
 * inner->cfg: key = value as section.key=value assignments, ;default lines through
 * cli_config_add_default.  The value is everything after the first " = ", byte for byte (no
 * comment stripping: the text was written by us).  `attr` names the attribute in messages.
 * Returns a CLI_EXIT_* code; on failure the message is in outer->err. */
static int apply_ini(cli_ctx *outer, cli_ctx *inner, const char *file, const char *attr, const char *ini) {
  static const char dflt[] = ";default ";
  const char *p = ini;
  char section[256] = "", *pending[64];
  size_t lineno = 0, npending = 0, i;
  int status = CLI_EXIT_OK;
  while (*p && status == CLI_EXIT_OK) {
    const char *nl = strchr(p, '\n');
    size_t len = nl ? (size_t)(nl - p) : strlen(p);
    lineno++;
    if (cli_interrupted()) { /* SIGINT, SIGTERM, SIGHUP: nothing written yet */
      status = cli_fail(outer, CLI_EXIT_INTERRUPTED, "%s while reading the configuration of '%s' (line %zu of %s); "
                        "nothing written", cli_signal_reason(), file, lineno, attr);
      break;
    }
    if (len > 0) {
      char *line = malloc(len + 1), *assign;
      const char *eq, *body;
      int rc, is_default;
      if (!line) return cli_fail(outer, CLI_EXIT_INTERNAL, "out of memory");
      memcpy(line, p, len);
      line[len] = '\0';
      is_default = strncmp(line, dflt, sizeof dflt - 1) == 0;
      body = is_default ? line + sizeof dflt - 1 : line;
      if (!strncmp(line, ";#", 2) && !section[0]) { /* a comment of the given file's preamble */
        if (cli_config_add_comment(inner->cfg, NULL, NULL, line[2] == ' ' ? line + 3 : line + 2) != 0)
          status = cli_fail(outer, CLI_EXIT_INTERNAL, "out of memory");
        free(line);
      } else if (!strncmp(line, ";#", 2) && npending < sizeof pending / sizeof pending[0]) {
        pending[npending++] = line; /* a comment of the next key */
      } else if (line[0] == ';' && !is_default) {
        free(line); /* a comment */
      } else if (!is_default && line[0] == '[' && line[len - 1] == ']' && len - 2 < sizeof section) {
        memcpy(section, line + 1, len - 2);
        section[len - 2] = '\0';
        free(line);
      } else if ((eq = strstr(body, " = ")) != NULL && eq > body && section[0]) {
        size_t klen = (size_t)(eq - body), vlen = strlen(eq + 3);
        char kbuf[256];
        snprintf(kbuf, sizeof kbuf, "%.*s", (int)(klen < sizeof kbuf ? klen : sizeof kbuf - 1), body);
        if (cli_config_has_key(inner->cfg, section, kbuf)) {
          free(line);
          for (i = 0; i < npending; i++) free(pending[i]);
          return cli_fail(outer, CLI_EXIT_IO,
                          "'%s': root attribute %s, line %zu: key '%s.%s' is recorded more than once (a damaged "
                          "or edited archive: autobal records every key once)",
                          file, attr, lineno, section, kbuf);
        }
        if (is_default) {
          char *key = malloc(klen + 1);
          if (!key) {
            free(line);
            return cli_fail(outer, CLI_EXIT_INTERNAL, "out of memory");
          }
          memcpy(key, body, klen);
          key[klen] = '\0';
          rc = cli_config_add_default(inner, section, key, eq + 3);
          free(key);
        } else {
          assign = malloc(strlen(section) + klen + vlen + 3);
          if (!assign) {
            free(line);
            return cli_fail(outer, CLI_EXIT_INTERNAL, "out of memory");
          }
          sprintf(assign, "%s.%.*s=%s", section, (int)klen, body, eq + 3);
          rc = cli_config_override(inner, assign);
          free(assign);
        }
        if (rc == CLI_EXIT_OK) { /* the key's comments */
          char *key = malloc(klen + 1);
          if (!key) rc = CLI_EXIT_INTERNAL;
          else memcpy(key, body, klen), key[klen] = '\0';
          for (i = 0; i < npending && rc == CLI_EXIT_OK; i++)
            if (cli_config_add_comment(inner->cfg, section, key, pending[i][2] == ' ' ? pending[i] + 3 : pending[i] + 2))
              rc = CLI_EXIT_INTERNAL;
          free(key);
          if (rc != CLI_EXIT_OK) snprintf(inner->err, sizeof inner->err, "out of memory");
        }
        for (i = 0; i < npending; i++) free(pending[i]);
        npending = 0;
        free(line);
        if (rc != CLI_EXIT_OK)
          return cli_fail(outer, CLI_EXIT_IO, "'%s': root attribute %s, line %zu: %s", file, attr, lineno, inner->err);
      } else {
        free(line);
        return cli_fail(outer, CLI_EXIT_IO,
                        "'%s': root attribute %s, line %zu is neither '[section]' nor 'key = value' "
                        "(nor ';default key = value')",
                        file, attr, lineno);
      }
    }
    if (!nl) break;
    p = nl + 1;
  }
  for (i = 0; i < npending; i++) free(pending[i]);
  return status;
}

int cli_cmd_rerun(cli_ctx *ctx) {
  const char *path = ctx->config_path; /* the archive argument (see main.c) */
  autobal_archive *a = NULL;
  autobal_error err;
  char *command = NULL, *ini = NULL, *eff = NULL, *status = NULL, *version = NULL;
  const cli_command *cmd = NULL;
  cli_ctx inner;
  struct stat si, so;
  size_t i;
  int rc = CLI_EXIT_OK, st;

  if (!path) return cli_fail(ctx, CLI_EXIT_USAGE, "rerun: give an archive: autobal rerun FILE.h5 -o NEW.h5");
  if (!ctx->output)
    return cli_fail(ctx, CLI_EXIT_USAGE, "rerun: give the new archive with -o NEW.h5 (FILE.h5 is never modified)");
  autobal_error_clear(&err);
  st = autobal_archive_open_read(path, &a, &err);
  if (st != AUTOBAL_SUCCESS && cli_interrupted()) /* e.g. a read interrupted by the signal */
    return cli_fail(ctx, CLI_EXIT_INTERRUPTED, "%s while opening '%s'; nothing written", cli_signal_reason(), path);
  if (st != AUTOBAL_SUCCESS)
    return cli_fail(ctx, st == AUTOBAL_ENOMEM ? CLI_EXIT_INTERNAL : CLI_EXIT_IO, "%s", err.message);
  st = read_root_string(a, "command", &command);
  if (st == AUTOBAL_SUCCESS) st = read_root_string(a, "input_config", &ini);
  if (st == AUTOBAL_SUCCESS) st = read_root_string(a, "effective_config", &eff);
  if (st == AUTOBAL_SUCCESS) st = read_root_string(a, "status", &status);
  if (st == AUTOBAL_SUCCESS) st = read_root_string(a, "autobal_version", &version);
  if (st != AUTOBAL_SUCCESS) {
    rc = cli_fail(ctx, st == AUTOBAL_ENOMEM ? CLI_EXIT_INTERNAL : CLI_EXIT_IO, "'%s': %s", path,
                  autobal_archive_errmsg(a)[0] ? autobal_archive_errmsg(a) : autobal_strerror(st));
    goto done;
  }
  autobal_archive_close(a, NULL);
  a = NULL;
  if (!command || (!ini && !eff)) {
    rc = cli_fail(ctx, CLI_EXIT_IO, "'%s' cannot be re-run: it has no root attribute %s", path,
                  command ? "'effective_config' (nor 'input_config')" : "'command'");
    goto done;
  }
  for (i = 0; i < cli_ncommands; i++)
    if (strcmp(cli_commands[i].name, command) == 0 && strchr(command, ' ')) cmd = &cli_commands[i];
  if (!cmd) {
    rc = cli_fail(ctx, CLI_EXIT_IO, "'%s' records the command '%s', which this autobal cannot run", path, command);
    goto done;
  }
  if (stat(path, &si) == 0 && stat(ctx->output, &so) == 0 && si.st_dev == so.st_dev && si.st_ino == so.st_ino) {
    rc = cli_fail(ctx, CLI_EXIT_USAGE, "rerun: the new archive '%s' is the archive being re-run; choose another name",
                  ctx->output);
    goto done;
  }
  if (!ctx->json) {
    if (version && strcmp(version, autobal_version()) != 0)
      fprintf(stderr, "autobal: warning: '%s' was written by autobal %s, this is %s: results may differ\n", path,
              version, autobal_version());
    if (status && strcmp(status, "complete") != 0)
      fprintf(stderr, "autobal: note: the recorded run did not complete (status '%s'); running it in full\n", status);
  }

  inner = *ctx;
  inner.command = cmd->name;
  inner.config_path = NULL;
  inner.err[0] = '\0';
  inner.cfg = cli_config_new(NULL);
  if (!inner.cfg) {
    rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
    goto done;
  }
  /* the effective configuration (every key); archives of earlier versions: the given one */
  rc = apply_ini(ctx, &inner, path, eff ? "effective_config" : "input_config", eff ? eff : ini);
  /* an ensemble recorded before the attractor classification (no write_attractors among its
   * keys) writes the datasets it wrote then: its per-member attractor variables stay off (the
   * class counts are attributes) */
  if (rc == CLI_EXIT_OK && (!strcmp(cmd->name, "rotor ensemble") || !strcmp(cmd->name, "pendulum ensemble")) &&
      !cli_config_has_key(inner.cfg, "ensemble", "write_attractors") &&
      (rc = cli_config_add_default(&inner, "ensemble", "write_attractors", "false")) != CLI_EXIT_OK)
    cli_fail(ctx, rc, "%s", inner.err[0] ? inner.err : "out of memory");
  /* NEW.h5 records the recorded run's given configuration, not the effective one as "given" */
  if (rc == CLI_EXIT_OK && ini && cli_config_set_given_text(inner.cfg, ini) != 0)
    rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  if (rc == CLI_EXIT_OK && cli_interrupted())
    rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED, "%s before the run started; nothing written", cli_signal_reason());
  if (rc == CLI_EXIT_OK) {
    rc = cmd->run(&inner);
    if (rc != CLI_EXIT_OK) cli_fail(ctx, rc, "%s", inner.err[0] ? inner.err : "re-run failed (no message)");
  }
  cli_config_free(inner.cfg);
done:
  if (a) autobal_archive_close(a, NULL);
  free(command);
  free(ini);
  free(eff);
  free(status);
  free(version);
  return rc;
}
