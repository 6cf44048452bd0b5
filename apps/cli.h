/* cli.h: the command-line layer's shared infrastructure (not installed).
 *
 * The apps are the only place that wires a model, an analysis and the
 * archive together.  This header gives every subcommand the same:
 *   - configuration: an INI file read with inih, then `--set section.key=value`
 *     overrides; typed getters that record which keys the command knows, and a
 *     final check that rejects unknown sections/keys with a "did you mean";
 *   - common options (-o, --force, --json, --set, --quiet, --no-progress);
 *   - exit codes (CLI_EXIT_*), error reporting, a progress bar on a terminal,
 *     SIGINT/SIGTERM/SIGHUP turned into a cancellation flag;
 *   - a tiny JSON writer for `--json` summaries on stdout.
 */
#ifndef AUTOBAL_APPS_CLI_H
#define AUTOBAL_APPS_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "autobal.h"

/* Exit codes (documented in README, docs/guide.md and `autobal --help`). */
enum {
  CLI_EXIT_OK = 0,          /* success (the verdict may still be "unstable") */
  CLI_EXIT_USAGE = 2,       /* bad command line */
  CLI_EXIT_INPUT = 3,       /* bad configuration or parameter out of range */
  CLI_EXIT_IO = 4,          /* output/input file problem (exists, unwritable, not an archive) */
  CLI_EXIT_NUMERIC = 5,     /* numerical failure; partial results were written */
  CLI_EXIT_INTERRUPTED = 6, /* SIGINT/SIGTERM; partial results written, archive marked incomplete */
  CLI_EXIT_INTERNAL = 7     /* out of memory or another internal failure */
};

/* ---- configuration -------------------------------------------------------- */
typedef struct cli_config cli_config;

typedef struct cli_ctx {
  int argc;                 /* the full command line, for provenance */
  char **argv;
  const char *command;      /* e.g. "pendulum roots" */
  const char *config_path;  /* NULL: built-in defaults only */
  const char *output;       /* -o FILE.h5, NULL: no archive */
  int force;                /* --force: overwrite an existing output file */
  int json;                 /* --json: machine-readable summary on stdout */
  int quiet;                /* --quiet: no human summary */
  int progress;             /* progress bar allowed (terminal, not --no-progress) */
  cli_config *cfg;
  char err[1024];           /* the message printed on failure */
} cli_ctx;

/* 1 if the configuration holds section.key (given, --set or a recorded default), else 0. */
int cli_config_has_key(const cli_config *c, const char *section, const char *key);

cli_config *cli_config_new(const char *path);
void cli_config_free(cli_config *c);
/* Read ctx->config_path (if any) into ctx->cfg: a duplicated key, an unparsable line, a NUL byte
 * or a line longer than the INI reader's limit (INI_MAX_LINE - 2 characters) is an error naming the
 * file and line; so is a directory, a read error or a file larger than 1 MiB. */
int cli_config_load(cli_ctx *ctx);
/* The same from INI text in memory (len bytes; `name` stands for the file in messages). */
int cli_config_load_text(cli_ctx *ctx, const char *name, const char *text, size_t len);
/* The given configuration (file + overrides) as INI text (malloc'ed; NULL: no memory): the keys
 * given, grouped by section in order of first appearance. */
char *cli_config_to_ini(const cli_config *c);
/* The effective configuration as INI text (malloc'ed; NULL: no memory): every key the command read
 * through the getters below, in the order read, grouped by section in the order of the first read
 * (then given keys of sections declared known as a whole), each with the value the command used:
 *   KEY = VALUE            given (VALUE as given), or not given and the getter's default did not
 *                          depend on it being given (the default, numbers in the shortest text
 *                          that reads back bit for bit);
 *   ;default KEY = VALUE   not given, and the command asked whether it was (the getter's `present`
 *                          pointer), or its section was found absent (cli_section_present), or VALUE
 *                          would not read back as a given value (NaN, empty): KEY must stay absent,
 *                          VALUE is the default that was used.  For the INI reader a comment;
 *                          `autobal rerun` gives it back through cli_config_add_default;
 *   ; KEY not given: ...   a comment where no default is known to the getter (a list of
 *                          cli_get_doubles, a NULL string default) or a key was read with
 *                          different defaults: a re-run uses the built-in value.
 * Preceded by a few ';' comment lines naming `command`. */
char *cli_config_effective_ini(const cli_config *c, const char *command);
/* Whether keys were read since cli_config_effective_archived() (the archive's copy is stale). */
int cli_config_effective_stale(const cli_config *c);
void cli_config_effective_archived(cli_config *c);
/* `autobal rerun`: a key that was not given in the recorded run, with the default it used (a
 * ";default" line): getters return VALUE instead of their built-in default and report the key as
 * not given (*present = 0); cli_section_present ignores it; an unread one is an unknown key for
 * cli_config_check_unused.  Returns a CLI_EXIT_* code (CLI_EXIT_INPUT if the key is also given). */
int cli_config_add_default(cli_ctx *ctx, const char *section, const char *key, const char *value);
/* `autobal rerun`: the text to record as the given configuration (root attribute input_config)
 * instead of cli_config_to_ini (the recorded run's own input_config).  Returns 0, -1: no memory. */
int cli_config_set_given_text(cli_config *c, const char *ini);
/* cli_config_set_given_text's text if set, else cli_config_to_ini (malloc'ed; NULL: no memory). */
char *cli_config_given_ini(const cli_config *c);
/* A comment line of the given configuration (`autobal rerun` hands back the ";# " lines of a
 * recorded effective configuration): section NULL: the preamble (before the first section);
 * else a comment of the key section.key, which must have been added (ignored otherwise).  The
 * effective configuration writes them as ";# TEXT" lines.  Returns 0, -1: no memory. */
int cli_config_add_comment(cli_config *c, const char *section, const char *key, const char *text);
/* Apply one `--set section.key=value` (CLI_EXIT_USAGE naming what is missing: '=', the section
 * or the key). */
int cli_config_override(cli_ctx *ctx, const char *assignment);
/* "Did you mean": the names of cands[0..n-1] closest to `word` (case-insensitive edit distance
 * first, the exact one breaking ties), at most `max_edits` case-insensitive edits away, written
 * as "'a'" or "'a' or 'b'" into buf (len bytes; empty when none is close enough).  Returns the
 * number of names written.  The unknown-key check (cli_config_check_unused) uses 3 edits. */
size_t cli_did_you_mean(const char *word, const char *const *cands, size_t n, size_t max_edits, char *buf,
                        size_t len);

/* A subcommand: parses nothing itself; everything comes through ctx. Returns a CLI_EXIT_* code
 * and, on failure, leaves the message in ctx->err. */
typedef int (*cli_command_fn)(cli_ctx *ctx);

/* Record a failure message (printf-style) and return `code`. */
int cli_fail(cli_ctx *ctx, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Map a library status to an exit code. */
int cli_exit_code(int status);

/* Getters.  Each declares the key as known to this command (for the unknown-key check and the
 * "did you mean" suggestion), marks it used and records the key with the value used for the
 * effective configuration (cli_config_effective_ini).  If the key is absent, *out = def and 0 is
 * returned (*present, when not NULL, is set to 0/1; pass NULL when the command does not care
 * whether the key was given, so that its default can be recorded as a given key).  A malformed
 * value (not a number, NaN, infinity, empty, trailing junk) returns CLI_EXIT_INPUT with ctx->err
 * naming section.key and the file. */
int cli_get_double(cli_ctx *ctx, const char *section, const char *key, double def, double *out, int *present);
/* A physical quantity: like cli_get_double, but the value may carry a unit that UDUNITS-2 parses
 * ("3000 rpm", "20 g", "200 g mm"; apps/units.h has the rules, docs/units.md the user's view); it
 * is converted to `si_unit` (e.g. "rad/s", "kg", "kg m"), the unit the library expects and a
 * plain number is read in.  A unit of another dimension, an unknown unit or an ambiguous speed
 * unit is CLI_EXIT_INPUT with ctx->err naming section.key and the expected unit.  The effective
 * configuration records the text as given, so a re-run converts it again. */
int cli_get_quantity(cli_ctx *ctx, const char *section, const char *key, const char *si_unit, double def, double *out,
                     int *present);
int cli_get_int(cli_ctx *ctx, const char *section, const char *key, long def, long *out, int *present);
int cli_get_bool(cli_ctx *ctx, const char *section, const char *key, int def, int *out, int *present);
/* A string; the returned pointer stays valid until the config is freed. */
int cli_get_string(cli_ctx *ctx, const char *section, const char *key, const char *def, const char **out,
                   int *present);
/* Comma-separated doubles; at most `cap` values; *n set to the count (0 if absent). */
int cli_get_doubles(cli_ctx *ctx, const char *section, const char *key, double *out, size_t cap, size_t *n,
                    int *present);
/* The same for a list of quantities, each item "NUMBER [UNIT]" (cli_get_quantity). */
int cli_get_quantities(cli_ctx *ctx, const char *section, const char *key, const char *si_unit, double *out,
                       size_t cap, size_t *n, int *present);
/* A list read with cli_get_doubles and not given: record the values the command used in their
 * place (they appear as ";default KEY = v1, v2, ..." in the effective configuration, and
 * `autobal rerun` hands them back through cli_get_doubles with *present = 0).  Nothing for a
 * given list or n = 0.  Returns 0, or -1 when out of memory (also flagged for the archive). */
int cli_record_doubles_used(cli_ctx *ctx, const char *section, const char *key, const double *v, size_t n);
/* Declare a whole section as known (for sections whose keys are read elsewhere). */
void cli_declare_section(cli_ctx *ctx, const char *section);
/* After all getters: fail on any key or section in the file/overrides that the command does not
 * know, with a suggestion.  Returns 0 or CLI_EXIT_INPUT. */
int cli_config_check_unused(cli_ctx *ctx);
/* Whether any key of `section` is present in the file or overrides. */
int cli_section_present(cli_ctx *ctx, const char *section);

/* ---- archive helpers (write a parameter with its unit into /parameters etc.) ---- */
struct autobal_archive;
/* Open ctx->output (if any) with provenance; *out is NULL when no -o was given.  Refuses to
 * overwrite without --force.  Returns a CLI_EXIT_* code. */
int cli_archive_open(cli_ctx *ctx, const char *title, struct autobal_archive **out);
/* Close (rename to the final name) or, when `exit_code` says the run failed before anything
 * useful, still close so that what was written stays readable; status attribute set from the
 * code.  Returns exit_code, or CLI_EXIT_IO if closing failed. */
int cli_archive_finish(cli_ctx *ctx, struct autobal_archive *a, int exit_code);
/* The end of a command's archive writes: when `st` (the autobal status of the writes) is a
 * failure and `exit_code` is still CLI_EXIT_OK, the archive's message becomes the failure
 * (cli_exit_code(st)); then cli_archive_finish.  *a is set to NULL.  Returns the exit code. */
int cli_archive_end(cli_ctx *ctx, struct autobal_archive **a, int st, int exit_code);
/* The transient driver's statistics (autobal_transient_get_stats) as attributes of `group`
 * (autobal_study_write_solver_stats with the driver's stepper and last message),
 * which is created: stepper, steps, rejected_steps, rhs_evaluations, jacobian_evaluations,
 * wall_time (s), h_min_used and h_max_used (in `time_unit`: "s", or "1" for a dimensionless
 * time), stop_reason and the driver's last message.  Returns an autobal status (the archive's
 * message in autobal_archive_errmsg). */
int cli_archive_solver_stats(struct autobal_archive *a, const char *group, const autobal_transient *tr,
                             const autobal_transient_stats *stats, const char *time_unit);
/* The same statistics as one line of the human summary on stdout. */
void cli_print_solver_stats(const autobal_transient *tr, const autobal_transient_stats *stats);
/* The same line from the stepper's name (a study's summary). */
void cli_print_solver_line(const char *stepper, const autobal_transient_stats *stats);
/* cli_archive_open records the root attributes command, input_config (the given configuration,
 * cli_config_given_ini) and effective_config (cli_config_effective_ini: every key read, with
 * defaults), which `autobal rerun` runs from; cli_archive_finish writes effective_config again if
 * keys were read after the archive was opened. */

/* ---- progress and signals ------------------------------------------------- */
/* Install SIGINT/SIGTERM/SIGHUP handlers that set a flag (the run stops cleanly at the next check);
 * a SIGHUP ignored by the parent (nohup) stays ignored. */
void cli_signals_install(void);
/* Non-zero once SIGINT/SIGTERM/SIGHUP arrived; the signal number via cli_signal_number(). */
int cli_interrupted(void);
int cli_signal_number(void);
/* "interrupted by SIGINT" (or SIGTERM, SIGHUP): the archive's status_reason after a signal. */
const char *cli_signal_reason(void);
/* Draw/update a progress bar on stderr (only if ctx->progress); fraction in [0,1]. Returns
 * non-zero when the run should stop (a signal arrived). Finish with cli_progress_done. */
int cli_progress(cli_ctx *ctx, const char *label, double fraction);
void cli_progress_done(cli_ctx *ctx);

/* ---- JSON summary on stdout ----------------------------------------------- */
typedef struct cli_json {
  FILE *f;
  int depth;
  int first[16]; /* whether the next member at each depth is the first one */
  /* units of top-level members (cli_json_unit), written as "units": {KEY: UNIT, ...} by
   * cli_json_summary_end; keys and units must outlive the summary (string literals) */
  const char *unit_key[64], *unit_val[64];
  int n_units;
} cli_json;
void cli_json_begin(cli_json *j, FILE *f);      /* opens the top-level object */
void cli_json_end(cli_json *j);                 /* closes it, newline */
void cli_json_key(cli_json *j, const char *key);
void cli_json_object(cli_json *j, const char *key); /* key NULL inside arrays */
void cli_json_object_end(cli_json *j);
void cli_json_array(cli_json *j, const char *key);
void cli_json_array_end(cli_json *j);
void cli_json_number(cli_json *j, const char *key, double v);  /* NaN/inf -> null */
void cli_json_int(cli_json *j, const char *key, long v);
void cli_json_bool(cli_json *j, const char *key, int v);
void cli_json_string(cli_json *j, const char *key, const char *s);
void cli_json_numbers(cli_json *j, const char *key, const double *v, size_t n);
/* Record the unit of a top-level member (a string UDUNITS-2 parses, "1" for a ratio); every
 * summary lists them in its member "units". */
void cli_json_unit(cli_json *j, const char *key, const char *unit);
/* cli_json_number / cli_json_numbers with cli_json_unit. */
void cli_json_quantity(cli_json *j, const char *key, double v, const char *unit);
void cli_json_quantities(cli_json *j, const char *key, const double *v, size_t n, const char *unit);
/* A command's summary: cli_json_begin and "command"; at the end "output" (when -o was given)
 * and cli_json_end. */
void cli_json_summary_begin(cli_json *j, const cli_ctx *ctx);
void cli_json_summary_end(cli_json *j, const cli_ctx *ctx);

/* ---- shared model plumbing ---------------------------------------------------- */
#include "autobal/pendulum.h"
/* Read [pendulum] (dimensionless R_w, R_m, H, h, k|psi0, or the physical M, e, m, l, c, H1, H2,
 * omega) into *p; *physical says which form was given (phys filled then). */
int cli_read_pendulum_params(cli_ctx *ctx, autobal_pendulum_params *p, autobal_pendulum_physical *phys,
                             int *physical);
/* Write them as attributes of /pendulum (and /pendulum/physical). */
int cli_write_pendulum_params(cli_ctx *ctx, struct autobal_archive *a, const autobal_pendulum_params *p,
                              const autobal_pendulum_physical *phys, int physical);

#include "autobal/rotor.h"
/* The rotor plumbing lives in apps/cmd_rotor.c beside the reader of `rotor transient` (the fuzz
 * targets of tests/fuzz compile that file with cli.c, cli_archive.c and cmd_pendulum.c only).
 * Read the rotor model sections [rotor], [supports], [lumped], [initial], [plane1], [plane2]
 * (defaults: the spec's default example) into *p.  The ball arrays of *p point into *storage,
 * which the caller releases with free(*storage) after the last use of *p. */
int cli_rotor_config_read(cli_ctx *ctx, autobal_rotor_params *p, void **storage);
/* Read [drive] (mode = constant|ramp|table and its keys, as `rotor transient` reads them) into
 * p->drive; storage is cli_rotor_config_read's, where a table's points are kept. */
int cli_rotor_drive_read(cli_ctx *ctx, autobal_rotor_params *p, void *storage);
/* Read [friction] (law = none|exact|regularized, u_eps) and the planes' ball_f, ball_mu, as `rotor
 * transient` reads them, into p->friction; storage is cli_rotor_config_read's, where the lists are
 * kept. */
int cli_rotor_friction_read(cli_ctx *ctx, autobal_rotor_params *p, void *storage);
/* Read [contact] (restitution, v_rest) with the planes' ball_diameter that cli_rotor_friction_read
 * read (contact on when some plane gives it), as `rotor transient` reads them, into p->contact;
 * storage is cli_rotor_config_read's, where the diameters are kept. */
int cli_rotor_contact_read(cli_ctx *ctx, autobal_rotor_params *p, void *storage);
/* Write the rotor model *p (autobal_study_write_rotor_params): /rotor (model, input, inertia, omega, axial and,
 * for hardware input, M_k, A_k, m_p, A_p, C_p and the [supports] keys), /rotor/lumped (the 17
 * lumped coefficients the model uses, (2.7)-(2.11) for hardware input) and /rotor/plane<j>
 * (d, m0, r0, psi0, n_balls, ball_mass, ball_radius, ball_damping; with `initial` also the balls'
 * initial angles and rates ball_psi_initial, ball_rate_initial).  SI units on every attribute.
 * Returns an autobal status (the archive's message in autobal_archive_errmsg). */
int cli_write_rotor_params(struct autobal_archive *a, const autobal_rotor_params *p, int initial);
/* A message of the rotor model (autobal_rotor_params_check, autobal_rotor_alloc,
 * autobal_rotor_stab_alloc, ...) that names struct fields, in the configuration's names:
 * hw.M_k -> rotor.M_k, hw.c_Lx -> supports.c_Lx, plane[0].ball_mass[1] -> plane1.ball_mass
 * (ball 2), plane[1].m0 -> plane2.m0, q0[2] (alpha) -> initial.alpha, qd0[0] -> initial.x_rate,
 * z0/zd0 -> initial.z/z_rate, plane[0].n_balls -> plane1 ball count, omega -> rotor.omega,
 * option member[0] -> stability.member1, tol -> stability.tol; lumped.X stays.  The struct
 * fields that were renamed are listed at the end ("(model field plane[0].ball_mass[1])") for
 * those who embed the library (and the app tests' needles).  Writes at most len bytes (NUL
 * included; a longer result is cut) into buf, which must not overlap msg, and returns buf. */
const char *cli_rotor_message(const char *msg, char *buf, size_t len);

/* ---- subcommands ------------------------------------------------------------ */
int cli_cmd_pendulum_roots(cli_ctx *ctx);
int cli_cmd_pendulum_critical(cli_ctx *ctx);
int cli_cmd_pendulum_map(cli_ctx *ctx);
int cli_cmd_pendulum_sweep(cli_ctx *ctx);
int cli_cmd_rotor_transient(cli_ctx *ctx);
int cli_cmd_pendulum_transient(cli_ctx *ctx);
int cli_cmd_rotor_stability(cli_ctx *ctx);
int cli_cmd_rotor_sweep(cli_ctx *ctx);
int cli_cmd_rotor_map(cli_ctx *ctx);
int cli_cmd_rotor_design(cli_ctx *ctx);
int cli_cmd_rotor_campbell(cli_ctx *ctx);
/* apps/cmd_ensemble.c: many transients (grid or seeded random samples), OpenMP and optional MPI */
int cli_cmd_rotor_ensemble(cli_ctx *ctx);
int cli_cmd_pendulum_ensemble(cli_ctx *ctx);
/* Single-word commands on an archive (cmd_info.c, cmd_rerun.c, cmd_plot.c): they take FILE.h5
 * where the others take CONFIG.ini (main.c passes it as ctx->config_path). */
int cli_cmd_info(cli_ctx *ctx);
int cli_cmd_rerun(cli_ctx *ctx);
int cli_cmd_plot(cli_ctx *ctx);

#endif
