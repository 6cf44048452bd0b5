/* cmd_plot.c: `autobal plot FILE.h5 [-o DIR] [-q]`: draw the pictures of an archive with
 * matplotlib by running the Python script autobal_plot.py (which reads only the archive)
 * with Debian's /usr/bin/python3.  Equivalent one-liner:
 *     /usr/bin/python3 tools/autobal_plot.py FILE.h5 -o DIR
 *
 * The script is looked up, first found wins:
 *   1. $AUTOBAL_TOOLS_DIR/autobal_plot.py
 *   2. <directory of the autobal executable>/../share/autobal/tools/autobal_plot.py
 *      (the installed layout: `cmake --install` puts autobal_plot.py there)
 *   3. AUTOBAL_SOURCE_TOOLS_DIR/autobal_plot.py, the source tree's tools/ (compile-time
 *      definition from apps/CMakeLists.txt: works from the build tree)
 * The interpreter is $AUTOBAL_PYTHON, else AUTOBAL_PYTHON3 (compile time, /usr/bin/python3).
 * Exit codes: the script's 0, 2, 3, 4 are passed on; a missing interpreter, script or
 * Python package and any other failure give 7 (internal). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "autobal/archive.h"
#include "cli.h"

#ifndef AUTOBAL_PYTHON3
#define AUTOBAL_PYTHON3 "/usr/bin/python3"
#endif

int cli_cmd_plot(cli_ctx *ctx); /* registered in commands.c */

static int readable(const char *p) { return access(p, R_OK) == 0; }

/* Find autobal_plot.py; returns 1 and fills buf, or 0. */
static int find_script(char *buf, size_t len) {
  const char *env = getenv("AUTOBAL_TOOLS_DIR");
  char exe[PATH_MAX];
  ssize_t n;
  if (env && env[0]) {
    snprintf(buf, len, "%s/autobal_plot.py", env);
    if (readable(buf)) return 1;
  }
  n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    char *slash;
    exe[n] = '\0';
    slash = strrchr(exe, '/');
    if (slash) {
      *slash = '\0';
      snprintf(buf, len, "%s/../share/autobal/tools/autobal_plot.py", exe);
      if (readable(buf)) return 1;
    }
  }
#ifdef AUTOBAL_SOURCE_TOOLS_DIR
  snprintf(buf, len, "%s/autobal_plot.py", AUTOBAL_SOURCE_TOOLS_DIR);
  if (readable(buf)) return 1;
#endif
  return 0;
}

int cli_cmd_plot(cli_ctx *ctx) {
  const char *path = ctx->config_path; /* the archive argument (see main.c) */
  const char *python = getenv("AUTOBAL_PYTHON");
  const char *argv[8];
  char script[PATH_MAX + 64];
  autobal_archive *a = NULL;
  autobal_error err;
  pid_t pid;
  int st, status = 0, k = 0;

  if (!path) return cli_fail(ctx, CLI_EXIT_USAGE, "plot: give an archive: autobal plot FILE.h5 [-o DIR]");
  if (ctx->output && !ctx->output[0])
    return cli_fail(ctx, CLI_EXIT_USAGE, "plot: -o needs a directory name (it is empty)");
  /* the same checks and messages as `autobal info` before starting Python */
  autobal_error_clear(&err);
  st = autobal_archive_open_read(path, &a, &err);
  if (st != AUTOBAL_SUCCESS)
    return cli_fail(ctx, st == AUTOBAL_ENOMEM ? CLI_EXIT_INTERNAL : CLI_EXIT_IO, "%s", err.message);
  autobal_archive_close(a, NULL);
  if (!python || !python[0]) python = AUTOBAL_PYTHON3;
  if (!find_script(script, sizeof script))
    return cli_fail(ctx, CLI_EXIT_INTERNAL,
                    "plot: cannot find autobal_plot.py (set AUTOBAL_TOOLS_DIR to the tools/ directory)");
  argv[k++] = python;
  argv[k++] = script;
  argv[k++] = path;
  argv[k++] = "-o";
  argv[k++] = ctx->output ? ctx->output : ".";
  if (ctx->quiet || ctx->json) argv[k++] = "--quiet";
  argv[k] = NULL;
  fflush(stdout);
  fflush(stderr);
  pid = fork();
  if (pid < 0) return cli_fail(ctx, CLI_EXIT_INTERNAL, "plot: fork failed: %s", strerror(errno));
  if (pid == 0) {
    execv(python, (char *const *)(void *)argv);
    fprintf(stderr, "autobal: error: cannot run '%s': %s\n", python, strerror(errno));
    _exit(127);
  }
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return cli_fail(ctx, CLI_EXIT_INTERNAL, "plot: waitpid failed: %s", strerror(errno));
    if (cli_interrupted()) kill(pid, SIGTERM); /* SIGINT/SIGTERM/SIGHUP sent to autobal alone: stop the child */
  }
  if (WIFEXITED(status)) {
    int code = WEXITSTATUS(status);
    if (code == 0) return CLI_EXIT_OK;
    if (code == 127)
      return cli_fail(ctx, CLI_EXIT_INTERNAL, "plot: cannot run the Python interpreter '%s' (set AUTOBAL_PYTHON)",
                      python);
    if (code == CLI_EXIT_USAGE || code == CLI_EXIT_INPUT || code == CLI_EXIT_IO)
      return cli_fail(ctx, code, "plot: %s failed (exit %d, see its message above)", script, code);
    return cli_fail(ctx, CLI_EXIT_INTERNAL,
                    "plot: %s failed (exit %d; needs /usr/bin/python3 with h5py, numpy and matplotlib)", script,
                    code);
  }
  if (WIFSIGNALED(status) && cli_interrupted()) return cli_fail(ctx, CLI_EXIT_INTERRUPTED, "plot: %s", cli_signal_reason());
  return cli_fail(ctx, CLI_EXIT_INTERNAL, "plot: %s was killed by signal %d", script,
                  WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}
