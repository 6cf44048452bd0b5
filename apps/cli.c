/* cli.c: configuration (inih + --set), errors, progress, signals, JSON. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <ini.h>

#include "units.h"

/* ---- errors ------------------------------------------------------------------ */
int cli_fail(cli_ctx *ctx, int code, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(ctx->err, sizeof ctx->err, fmt, ap);
  va_end(ap);
  return code;
}

int cli_exit_code(int status) {
  switch (status) {
    case AUTOBAL_SUCCESS:
    case AUTOBAL_WARNING:
    case AUTOBAL_EVENT:
      return CLI_EXIT_OK;
    case AUTOBAL_EINVAL:
    case AUTOBAL_ECONFIG:
    case AUTOBAL_EUNSUPPORTED:
      return CLI_EXIT_INPUT;
    case AUTOBAL_EIO:
    case AUTOBAL_EEXIST:
    case AUTOBAL_EFORMAT:
      return CLI_EXIT_IO;
    case AUTOBAL_ECANCELLED:
      return CLI_EXIT_INTERRUPTED;
    case AUTOBAL_ENUMERIC:
    case AUTOBAL_ESTEP:
    case AUTOBAL_EMAXSTEPS:
    case AUTOBAL_ERHS:
      return CLI_EXIT_NUMERIC;
    default:
      return CLI_EXIT_INTERNAL;
  }
}

/* ---- configuration ----------------------------------------------------------- */
typedef struct cli_entry {
  char *section;
  char *key;
  char *value;
  int from_set;   /* 1: --set override, 0: file */
  int is_default; /* 1: a ";default" line of a recorded effective configuration (rerun): the key
                   * counts as not given, and its value replaces the getter's built-in default */
  int used;
  char *comment; /* the comment lines written above the key and after its value in the given
                  * file ('\n'-separated, without the ';'), NULL: none */
} cli_entry;

/* One key read by a getter, for the effective configuration (cli_config_effective_ini). */
typedef struct cli_read {
  char *section;
  char *key;
  char *value;  /* the value used, as text: the given text, or the default formatted so that it
                 * reads back exactly; NULL when the getter knows none (a list, a NULL string) */
  int given;    /* the key was given (file or --set) */
  int presence; /* the command asked whether the key was given (a `present` pointer) */
  int varies;   /* read again, absent, with another default: no single default to record */
} cli_read;

struct cli_config {
  cli_entry *entries;
  size_t n, cap;
  char **known; /* "section.key" declared by getters, or "section.*" */
  size_t nknown, capknown;
  const char *path;
  int dup_error; /* set by the ini handler on a duplicated key */
  int too_many;  /* set by the ini handler past CLI_CONFIG_MAX_KEYS keys */
  char dup_what[256];
  cli_read *reads; /* every key read, in the order of the first read */
  size_t nreads, capreads;
  int nomem;                 /* a read could not be recorded: no effective configuration */
  char **absent_sections;    /* sections cli_section_present() found absent */
  size_t nabsent, capabsent;
  char *given_text;          /* cli_config_set_given_text: recorded instead of cli_config_to_ini */
  unsigned long generation;  /* counts the recorded reads */
  unsigned long archived;    /* generation when the effective configuration was last archived */
  cli_units *units;          /* UDUNITS-2, loaded on the first value with a unit */
  char *preamble;            /* comment lines before the first section of the given file */
};

static char *dupstr(const char *s) {
  size_t len = strlen(s) + 1;
  char *p = malloc(len);
  if (p) memcpy(p, s, len);
  return p;
}

cli_config *cli_config_new(const char *path) {
  cli_config *c = calloc(1, sizeof *c);
  if (c) c->path = path;
  return c;
}

void cli_config_free(cli_config *c) {
  size_t i;
  if (!c) return;
  for (i = 0; i < c->n; i++) {
    free(c->entries[i].section);
    free(c->entries[i].key);
    free(c->entries[i].value);
    free(c->entries[i].comment);
  }
  for (i = 0; i < c->nknown; i++) free(c->known[i]);
  for (i = 0; i < c->nreads; i++) {
    free(c->reads[i].section);
    free(c->reads[i].key);
    free(c->reads[i].value);
  }
  for (i = 0; i < c->nabsent; i++) free(c->absent_sections[i]);
  free(c->entries);
  free(c->known);
  free(c->reads);
  free(c->absent_sections);
  free(c->given_text);
  free(c->preamble);
  cli_units_free(c->units);
  free(c);
}

/* Most keys (given, defaults declared, --set) one configuration may hold. */
#define CLI_CONFIG_MAX_KEYS 4096

static cli_entry *find_entry(const cli_config *c, const char *section, const char *key) {
  size_t i;
  for (i = 0; i < c->n; i++)
    if (strcmp(c->entries[i].section, section) == 0 && strcmp(c->entries[i].key, key) == 0) return &c->entries[i];
  return NULL;
}

static int add_entry(cli_config *c, const char *section, const char *key, const char *value, int from_set) {
  cli_entry *e = find_entry(c, section, key);
  if (e) {
    char *v;
    if (!from_set && !e->from_set) {
      c->dup_error = 1;
      snprintf(c->dup_what, sizeof c->dup_what, "%s.%s", section, key);
      return 0;
    }
    v = dupstr(value);
    if (!v) return -1;
    free(e->value);
    e->value = v;
    e->from_set = from_set;
    e->is_default = 0;
    return 0;
  }
  if (c->n >= CLI_CONFIG_MAX_KEYS) {
    c->too_many = 1; /* bounded: the key lookups are linear, a huge file must not make them crawl */
    return -2;
  }
  if (c->n == c->cap) {
    size_t cap = c->cap ? 2 * c->cap : 32;
    cli_entry *p = realloc(c->entries, cap * sizeof *p);
    if (!p) return -1;
    c->entries = p;
    c->cap = cap;
  }
  e = &c->entries[c->n];
  e->section = dupstr(section);
  e->key = dupstr(key);
  e->value = dupstr(value);
  e->from_set = from_set;
  e->is_default = 0;
  e->used = 0;
  e->comment = NULL;
  if (!e->section || !e->key || !e->value) {
    free(e->section);
    free(e->key);
    free(e->value);
    return -1;
  }
  c->n++;
  return 0;
}

static int ini_handler_fn(void *user, const char *section, const char *name, const char *value) {
  cli_config *c = user;
  if (c->too_many || c->dup_error) return 0; /* inih goes on to the end: skip the rest cheaply */
  return add_entry(c, section, name, value, 0) == 0 && !c->dup_error;
}

/* Parse INI text (len bytes, no NUL inside; text[len] must be '\0').  Before inih sees it, two
 * things inih would get wrong silently are rejected: a NUL byte (inih's line reader stops at it
 * and drops the rest of the line) and a line longer than inih's INI_MAX_LINE - 1 bytes (inih
 * parses the remainder as a new line, so the error, if any, names the wrong line). */
static int scan_comments(cli_config *c, const char *text);

static int config_parse_text(cli_ctx *ctx, const char *name, const char *text, size_t len) {
  cli_config *c = ctx->cfg;
  size_t i, line = 1, col = 0;
  int rc;
  for (i = 0; i < len; i++) {
    if (text[i] == '\0')
      return cli_fail(ctx, CLI_EXIT_INPUT, "config file '%s', line %zu: contains a NUL byte (not a text file?)", name,
                      line);
    /* inih reads a line with its newline into INI_MAX_LINE bytes including the terminating NUL */
    if (++col > INI_MAX_LINE - 1)
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "config file '%s', line %zu: longer than %d characters (the limit of the INI reader); "
                      "shorten it (a list of equal values can be given as one value)",
                      name, line, INI_MAX_LINE - 2);
    if (text[i] == '\n') {
      line++;
      col = 0;
    }
  }
  rc = ini_parse_string(text, ini_handler_fn, c);
  if (c->too_many)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "config file '%s': more than %d keys (the limit CLI_CONFIG_MAX_KEYS; a configuration of "
                    "autobal has at most a few hundred)",
                    name, CLI_CONFIG_MAX_KEYS);
  if (c->dup_error)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "config file '%s': key '%s' is given more than once (or continued on an indented line)", name,
                    c->dup_what);
  if (rc > 0)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "config file '%s', line %d: cannot parse (expected '[section]', 'key = value' or a ';' comment)",
                    name, rc);
  if (rc < 0 || scan_comments(c, text) != 0) return cli_fail(ctx, CLI_EXIT_INTERNAL, "config file '%s': out of memory", name);
  return CLI_EXIT_OK;
}

/* Append line (len bytes) to the '\n'-separated text *dst.  Returns 0, -1: no memory. */
static int append_line(char **dst, const char *line, size_t len) {
  size_t old = *dst ? strlen(*dst) + 1 : 0;
  char *p = realloc(*dst, old + len + 1);
  if (!p) return -1;
  if (old) p[old - 1] = '\n';
  memcpy(p + old, line, len);
  p[old + len] = '\0';
  *dst = p;
  return 0;
}

int cli_config_add_comment(cli_config *c, const char *section, const char *key, const char *text) {
  cli_entry *e;
  if (!section) return append_line(&c->preamble, text, strlen(text));
  e = find_entry(c, section, key);
  if (!e) return 0;
  return append_line(&e->comment, text, strlen(text));
}

/* The comments of INI text (already parsed by inih, so well formed): full-line comments (';' or
 * '#') before the first section go to the preamble; the others, and an inline comment (';' after
 * a blank, as inih strips it), to the next key.  Returns 0, -1: no memory. */
/* The comment lines cli_config_effective_ini writes itself (its header, ";default" lines, "KEY not
 * given" notes): an effective configuration used as a configuration file does not take them
 * for the user's comments. */
static int generated_comment(const char *s, size_t n) {
  static const char *const k[] = {"; the effective configuration of ", "; (given in the file or with --set",
                                  "; \";default KEY = VALUE\"", "; so it stays absent;",
                                  "; the comments of the given configuration follow", ";default "};
  size_t i;
  const char *ng;
  for (i = 0; i < sizeof k / sizeof k[0]; i++)
    if (n >= strlen(k[i]) && strncmp(s, k[i], strlen(k[i])) == 0) return 1;
  /* "; KEY not given: ..." */
  ng = n > 2 && s[0] == ';' && s[1] == ' ' ? strstr(s, " not given: ") : NULL;
  if (ng && (size_t)(ng - s) < n) {
    const char *t;
    for (t = s + 2; t < ng; t++)
      if (*t == ' ') return 0;
    return 1;
  }
  return 0;
}

static int scan_comments(cli_config *c, const char *text) {
  char section[256] = "", *pending = NULL;
  const char *p = text;
  int rc = 0;
  while (*p && rc == 0) {
    const char *nl = strchr(p, '\n'), *end = nl ? nl : p + strlen(p), *q = p, *eq;
    while (q < end && (*q == ' ' || *q == '\t')) q++;
    while (end > q && (end[-1] == '\r' || end[-1] == ' ' || end[-1] == '\t')) end--;
    if (q < end && (*q == ';' || *q == '#')) {
      if (generated_comment(q, (size_t)(end - q))) goto next; /* ours, made again from the reads */
      q += (q + 1 < end && q[0] == ';' && q[1] == '#') ? 2 : 1; /* ";#": a comment we recorded */
      if (q < end && *q == ' ') q++;
      rc = section[0] ? append_line(&pending, q, (size_t)(end - q)) : append_line(&c->preamble, q, (size_t)(end - q));
    } else if (q < end && *q == '[') {
      const char *close = memchr(q, ']', (size_t)(end - q));
      size_t n = close ? (size_t)(close - q - 1) : 0;
      if (close && n < sizeof section) {
        memcpy(section, q + 1, n);
        section[n] = '\0';
      }
    } else if (q < end && section[0] && ((eq = memchr(q, '=', (size_t)(end - q))) != NULL ||
                                         (eq = memchr(q, ':', (size_t)(end - q))) != NULL)) {
      char key[256];
      const char *ke = eq, *v;
      while (ke > q && (ke[-1] == ' ' || ke[-1] == '\t')) ke--;
      for (v = eq + 1; v < end; v++)
        if (*v == ';' && (v[-1] == ' ' || v[-1] == '\t')) {
          const char *t = v + 1;
          if (t < end && *t == ' ') t++;
          rc = append_line(&pending, t, (size_t)(end - t));
          break;
        }
      if (rc == 0 && pending && (size_t)(ke - q) < sizeof key) {
        cli_entry *e;
        memcpy(key, q, (size_t)(ke - q));
        key[ke - q] = '\0';
        if ((e = find_entry(c, section, key)) != NULL && !e->comment) {
          e->comment = pending;
          pending = NULL;
        }
      }
      free(pending);
      pending = NULL;
    }
  next:
    p = nl ? nl + 1 : end;
    if (!nl) break;
  }
  free(pending);
  return rc;
}

int cli_config_load_text(cli_ctx *ctx, const char *name, const char *text, size_t len) {
  char *copy;
  int rc;
  if (memchr(text, '\0', len)) return config_parse_text(ctx, name, text, len); /* reports the NUL */
  copy = malloc(len + 1);
  if (!copy) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  memcpy(copy, text, len);
  copy[len] = '\0';
  rc = config_parse_text(ctx, name, copy, len);
  free(copy);
  return rc;
}

/* Largest configuration file read (a config is a few kB; this stops a data file given by mistake). */
#define CLI_CONFIG_MAX_BYTES (1u << 20)

int cli_config_load(cli_ctx *ctx) {
  FILE *f;
  struct stat sb;
  char *buf;
  size_t len = 0;
  int rc, read_errno = 0;
  if (!ctx->config_path) return CLI_EXIT_OK;
  f = fopen(ctx->config_path, "r");
  if (!f)
    return cli_fail(ctx, CLI_EXIT_INPUT, "cannot read config file '%s': %s", ctx->config_path, strerror(errno));
  /* fopen() succeeds on a directory; reading it then fails (or looks like an empty file) */
  if (fstat(fileno(f), &sb) == 0 && S_ISDIR(sb.st_mode)) {
    fclose(f);
    return cli_fail(ctx, CLI_EXIT_INPUT, "cannot read config file '%s': %s", ctx->config_path, strerror(EISDIR));
  }
  buf = malloc(CLI_CONFIG_MAX_BYTES + 1);
  if (!buf) {
    fclose(f);
    return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  }
  errno = 0;
  for (;;) {
    size_t got = fread(buf + len, 1, CLI_CONFIG_MAX_BYTES + 1 - len, f);
    len += got;
    if (got == 0 || len > CLI_CONFIG_MAX_BYTES) break;
  }
  if (ferror(f)) read_errno = errno ? errno : EIO;
  fclose(f);
  if (read_errno) {
    free(buf);
    return cli_fail(ctx, CLI_EXIT_INPUT, "cannot read config file '%s': %s", ctx->config_path, strerror(read_errno));
  }
  if (len > CLI_CONFIG_MAX_BYTES) {
    free(buf);
    return cli_fail(ctx, CLI_EXIT_INPUT, "config file '%s' is larger than %u bytes (not a configuration file?)",
                    ctx->config_path, CLI_CONFIG_MAX_BYTES);
  }
  buf[len] = '\0';
  rc = config_parse_text(ctx, ctx->config_path, buf, len);
  free(buf);
  return rc;
}

int cli_config_override(cli_ctx *ctx, const char *assignment) {
  const char *dot = strchr(assignment, '.');
  const char *eq = strchr(assignment, '=');
  char section[128], key[128];
  size_t ls, lk;
  int rc;
  const char *cmd = ctx->command ? ctx->command : "CMD";
  if (!eq)
    return cli_fail(ctx, CLI_EXIT_USAGE, "--set '%s': '=' is missing; expected --set SECTION.KEY=VALUE", assignment);
  if (!dot || dot > eq || dot == assignment)
    return cli_fail(ctx, CLI_EXIT_USAGE,
                    "--set '%s': the section is missing; expected --set SECTION.KEY=VALUE, here --set SECTION.%s "
                    "(the sections and their keys: 'autobal %s --help')",
                    assignment, dot == assignment ? assignment + 1 : assignment, cmd);
  if (eq == dot + 1)
    return cli_fail(ctx, CLI_EXIT_USAGE,
                    "--set '%s': the key is missing; expected --set SECTION.KEY=VALUE (the keys: 'autobal %s --help')",
                    assignment, cmd);
  ls = (size_t)(dot - assignment);
  lk = (size_t)(eq - dot - 1);
  if (ls >= sizeof section || lk >= sizeof key)
    return cli_fail(ctx, CLI_EXIT_USAGE, "--set: name too long in '%s'", assignment);
  memcpy(section, assignment, ls);
  section[ls] = '\0';
  memcpy(key, dot + 1, lk);
  key[lk] = '\0';
  if ((rc = add_entry(ctx->cfg, section, key, eq + 1, 1)) != 0)
    return rc == -2 ? cli_fail(ctx, CLI_EXIT_INPUT, "too many keys: more than %d in all (the limit CLI_CONFIG_MAX_KEYS)",
                               CLI_CONFIG_MAX_KEYS)
                    : cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  return CLI_EXIT_OK;
}

static void declare(cli_config *c, const char *section, const char *key) {
  char buf[256];
  size_t i;
  char *s;
  snprintf(buf, sizeof buf, "%s.%s", section, key);
  for (i = 0; i < c->nknown; i++)
    if (strcmp(c->known[i], buf) == 0) return;
  if (c->nknown == c->capknown) {
    size_t cap = c->capknown ? 2 * c->capknown : 64;
    char **p = realloc(c->known, cap * sizeof *p);
    if (!p) return;
    c->known = p;
    c->capknown = cap;
  }
  s = dupstr(buf);
  if (s) c->known[c->nknown++] = s;
}

void cli_declare_section(cli_ctx *ctx, const char *section) {
  size_t i;
  declare(ctx->cfg, section, "*");
  for (i = 0; i < ctx->cfg->n; i++)
    if (strcmp(ctx->cfg->entries[i].section, section) == 0) ctx->cfg->entries[i].used = 1;
}

int cli_section_present(cli_ctx *ctx, const char *section) {
  cli_config *c = ctx->cfg;
  size_t i;
  for (i = 0; i < c->n; i++)
    if (!c->entries[i].is_default && strcmp(c->entries[i].section, section) == 0) return 1;
  /* remembered: keys of this section must not be written as given into the effective
   * configuration, which would make the section present in a re-run */
  for (i = 0; i < c->nabsent; i++)
    if (strcmp(c->absent_sections[i], section) == 0) return 0;
  if (c->nabsent == c->capabsent) {
    size_t cap = c->capabsent ? 2 * c->capabsent : 8;
    char **p = realloc(c->absent_sections, cap * sizeof *p);
    if (!p) {
      c->nomem = 1;
      return 0;
    }
    c->absent_sections = p;
    c->capabsent = cap;
  }
  if ((c->absent_sections[c->nabsent] = dupstr(section)) != NULL) c->nabsent++;
  else c->nomem = 1;
  return 0;
}

static const char *where(cli_ctx *ctx, const cli_entry *e) {
  if (e->is_default) return "recorded configuration (;default line)";
  return e->from_set ? "--set" : (ctx->config_path ? ctx->config_path : "config");
}

/* ---- the record of the keys read (the effective configuration) ---------------------------- */
/* Record that `section.key` was read: given (value = the given text) or not (value = the default
 * used, as text, or NULL if unknown); presence: the caller asked whether it was given. */
static void record_read(cli_config *c, const char *section, const char *key, const char *value, int given,
                        int presence) {
  cli_read *r = NULL;
  size_t i;
  c->generation++;
  for (i = 0; i < c->nreads; i++)
    if (strcmp(c->reads[i].section, section) == 0 && strcmp(c->reads[i].key, key) == 0) {
      r = &c->reads[i];
      break;
    }
  if (r) { /* read again: the last value counts; asking for presence once is enough */
    char *v = NULL;
    if (!given && !r->given && !r->varies &&
        ((r->value == NULL) != (value == NULL) || (value && strcmp(r->value, value) != 0)))
      r->varies = 1;
    if (value && !(v = dupstr(value))) c->nomem = 1;
    free(r->value);
    r->value = v;
    r->given = given;
    r->presence |= presence;
    return;
  }
  if (c->nreads == c->capreads) {
    size_t cap = c->capreads ? 2 * c->capreads : 64;
    cli_read *p = realloc(c->reads, cap * sizeof *p);
    if (!p) {
      c->nomem = 1;
      return;
    }
    c->reads = p;
    c->capreads = cap;
  }
  r = &c->reads[c->nreads];
  memset(r, 0, sizeof *r);
  r->section = dupstr(section);
  r->key = dupstr(key);
  r->value = value ? dupstr(value) : NULL;
  r->given = given;
  r->presence = presence;
  if (!r->section || !r->key || (value && !r->value)) {
    free(r->section);
    free(r->key);
    free(r->value);
    c->nomem = 1;
    return;
  }
  c->nreads++;
}

/* The shortest "%.{15,16,17}g" text that strtod reads back to exactly v (sign of zero kept). */
static void format_double(double v, char *buf, size_t len) {
  int prec;
  for (prec = 15; prec <= 17; prec++) {
    double back;
    snprintf(buf, len, "%.*g", prec, v);
    back = strtod(buf, NULL);
    if (memcmp(&back, &v, sizeof v) == 0 || (isnan(v) && isnan(back))) return;
  }
}

/* Find the key (declaring it known and marking it used).  *present: given, i.e. in the file or
 * --set and not a recorded default. */
static cli_entry *lookup(cli_ctx *ctx, const char *section, const char *key, int *present) {
  cli_entry *e;
  declare(ctx->cfg, section, key);
  e = find_entry(ctx->cfg, section, key);
  if (present) *present = e != NULL && !e->is_default;
  if (e) e->used = 1;
  return e;
}

/* Record a read: e NULL (absent, `def` the default as text) or e given/recorded default. */
static void record(cli_ctx *ctx, const char *section, const char *key, const cli_entry *e, const char *def,
                   const int *present) {
  if (e) record_read(ctx->cfg, section, key, e->value, !e->is_default, present != NULL);
  else record_read(ctx->cfg, section, key, def, 0, present != NULL);
}

/* A number of a recorded default (";default" line): like parse_double, also NaN/infinity (a
 * default may be a "not set" NaN). */
static int parse_default_double(const char *s, double *out) {
  char *end;
  while (*s == ' ' || *s == '\t') s++;
  if (*s == '\0') return -1;
  *out = strtod(s, &end);
  if (end == s) return -1;
  while (*end == ' ' || *end == '\t') end++;
  return *end == '\0' ? 0 : -1;
}

static int parse_double(const char *s, double *out) {
  char *end;
  double v;
  while (*s == ' ' || *s == '\t') s++;
  if (*s == '\0') return -1;
  errno = 0;
  v = strtod(s, &end);
  if (end == s) return -1;
  while (*end == ' ' || *end == '\t') end++;
  if (*end != '\0') return -1;
  if (!isfinite(v) && errno != ERANGE) return -2; /* "nan", "inf" written out */
  if (errno == ERANGE) return -3;                 /* overflow, or underflow below DBL_MIN */
  *out = v;
  return 0;
}

/* The message of a parse_double() failure. */
static const char *parse_double_problem(int rc) {
  switch (rc) {
    case -2: return "is not a finite number (NaN and infinities are not allowed)";
    case -3: return "is outside the range of a double (magnitude 0 or from 2.2e-308 to 1.8e308)";
    default: return "is not a number";
  }
}

int cli_get_double(cli_ctx *ctx, const char *section, const char *key, double def, double *out, int *present) {
  return cli_get_quantity(ctx, section, key, "1", def, out, present);
}

/* "NUMBER UNIT" -> *out in si_unit (units.h).  Returns 0, or CLI_EXIT_INPUT / CLI_EXIT_INTERNAL
 * with the message in ctx->err prefixed by `what` (file:line: section.key = 'text'). */
static int parse_quantity(cli_ctx *ctx, const char *text, const char *si_unit, const char *what, double *out) {
  const char *unit;
  char num[64], msg[512];
  size_t n = cli_units_split(text, &unit);
  int rc;
  if (n == 0 || *unit == '\0') { /* no unit: a plain number in si_unit */
    rc = parse_double(text, out);
    if (rc != 0) return cli_fail(ctx, CLI_EXIT_INPUT, "%s %s", what, parse_double_problem(rc));
    return CLI_EXIT_OK;
  }
  if (n >= sizeof num) return cli_fail(ctx, CLI_EXIT_INPUT, "%s is not a number", what);
  memcpy(num, text, n);
  num[n] = '\0';
  if ((rc = parse_double(num, out)) != 0) return cli_fail(ctx, CLI_EXIT_INPUT, "%s %s", what, parse_double_problem(rc));
  if (!ctx->cfg->units && (ctx->cfg->units = cli_units_new(msg, sizeof msg)) == NULL)
    return cli_fail(ctx, CLI_EXIT_INTERNAL, "%s: %s", what, msg);
  if (cli_units_convert(ctx->cfg->units, *out, unit, si_unit, out, msg, sizeof msg) != 0)
    return cli_fail(ctx, CLI_EXIT_INPUT, "%s: %s", what, msg);
  return CLI_EXIT_OK;
}

/* A given value of a key in si_unit: a quantity (parse_quantity), or for NULL or "1" a plain
 * number, where a unit is an error that says the key is dimensionless. */
static int parse_value(cli_ctx *ctx, const char *text, const char *si_unit, const char *what, double *out) {
  const char *unit;
  int rc;
  if (si_unit && strcmp(si_unit, "1") != 0) return parse_quantity(ctx, text, si_unit, what, out);
  if ((rc = parse_double(text, out)) == 0) return CLI_EXIT_OK;
  if (rc == -1 && cli_units_split(text, &unit) > 0 && *unit != '\0')
    return cli_fail(ctx, CLI_EXIT_INPUT, "%s is dimensionless (or a count): give a plain number, no unit", what);
  return cli_fail(ctx, CLI_EXIT_INPUT, "%s %s", what, parse_double_problem(rc));
}

int cli_get_quantity(cli_ctx *ctx, const char *section, const char *key, const char *si_unit, double def, double *out,
                     int *present) {
  cli_entry *e = lookup(ctx, section, key, present);
  char what[600];
  if (!e) {
    char text[40];
    format_double(def, text, sizeof text);
    record(ctx, section, key, NULL, text, present);
    *out = def;
    return CLI_EXIT_OK;
  }
  record(ctx, section, key, e, NULL, present);
  snprintf(what, sizeof what, "%s: %s.%s = '%s'", where(ctx, e), section, key, e->value);
  if (e->is_default) { /* a recorded default (rerun): SI, NaN allowed */
    if (parse_default_double(e->value, out) != 0) return cli_fail(ctx, CLI_EXIT_INPUT, "%s is not a number", what);
    return CLI_EXIT_OK;
  }
  return parse_value(ctx, e->value, si_unit, what, out);
}

int cli_get_int(cli_ctx *ctx, const char *section, const char *key, long def, long *out, int *present) {
  cli_entry *e = lookup(ctx, section, key, present);
  char *end;
  long v;
  if (!e) {
    char text[32];
    snprintf(text, sizeof text, "%ld", def);
    record(ctx, section, key, NULL, text, present);
    *out = def;
    return CLI_EXIT_OK;
  }
  record(ctx, section, key, e, NULL, present);
  errno = 0;
  v = strtol(e->value, &end, 10);
  while (*end == ' ' || *end == '\t') end++;
  if (end == e->value || *end != '\0' || errno == ERANGE)
    return cli_fail(ctx, CLI_EXIT_INPUT, "%s: %s.%s = '%s' is not an integer", where(ctx, e), section, key, e->value);
  *out = v;
  return CLI_EXIT_OK;
}

int cli_get_bool(cli_ctx *ctx, const char *section, const char *key, int def, int *out, int *present) {
  cli_entry *e = lookup(ctx, section, key, present);
  const char *v;
  if (!e) {
    record(ctx, section, key, NULL, def ? "true" : "false", present);
    *out = def;
    return CLI_EXIT_OK;
  }
  record(ctx, section, key, e, NULL, present);
  v = e->value;
  if (!strcasecmp(v, "true") || !strcasecmp(v, "yes") || !strcasecmp(v, "on") || !strcmp(v, "1")) *out = 1;
  else if (!strcasecmp(v, "false") || !strcasecmp(v, "no") || !strcasecmp(v, "off") || !strcmp(v, "0")) *out = 0;
  else
    return cli_fail(ctx, CLI_EXIT_INPUT, "%s: %s.%s = '%s' is not a boolean (true/false, yes/no, on/off, 1/0)",
                    where(ctx, e), section, key, v);
  return CLI_EXIT_OK;
}

int cli_get_string(cli_ctx *ctx, const char *section, const char *key, const char *def, const char **out,
                   int *present) {
  cli_entry *e = lookup(ctx, section, key, present);
  if (!e) {
    record(ctx, section, key, NULL, def, present);
    *out = def;
    return CLI_EXIT_OK;
  }
  record(ctx, section, key, e, NULL, present);
  if (e->is_default) { /* the recorded default, also an empty one */
    *out = e->value;
    return CLI_EXIT_OK;
  }
  if (e->value[0] == '\0')
    return cli_fail(ctx, CLI_EXIT_INPUT, "%s: %s.%s has no value", where(ctx, e), section, key);
  *out = e->value;
  return CLI_EXIT_OK;
}

int cli_get_doubles(cli_ctx *ctx, const char *section, const char *key, double *out, size_t cap, size_t *n,
                    int *present) {
  return cli_get_quantities(ctx, section, key, NULL, out, cap, n, present);
}

int cli_get_quantities(cli_ctx *ctx, const char *section, const char *key, const char *si_unit, double *out,
                       size_t cap, size_t *n, int *present) {
  cli_entry *e = lookup(ctx, section, key, present);
  char buf[4096];
  char *tok, *save = NULL;
  size_t count = 0;
  *n = 0;
  /* an absent list: the caller's default is not known here (out holds it, of unknown length) */
  record(ctx, section, key, e, NULL, present);
  if (!e) return CLI_EXIT_OK;
  if (strlen(e->value) >= sizeof buf)
    return cli_fail(ctx, CLI_EXIT_INPUT, "%s: %s.%s: list too long (%zu characters; at most %zu)", where(ctx, e),
                    section, key, strlen(e->value), sizeof buf - 1);
  strcpy(buf, e->value);
  for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    double v;
    while (*tok == ' ' || *tok == '\t') tok++;
    char what[600];
    int rc;
    snprintf(what, sizeof what, "%s: %s.%s: item %zu '%s'", where(ctx, e), section, key, count + 1, tok);
    /* a recorded default list (rerun) is SI */
    if ((rc = parse_value(ctx, tok, e->is_default ? NULL : si_unit, what, &v)) != CLI_EXIT_OK) return rc;
    if (count == cap)
      return cli_fail(ctx, CLI_EXIT_INPUT, "%s: %s.%s: more than %zu values", where(ctx, e), section, key, cap);
    out[count++] = v;
  }
  if (count == 0) return cli_fail(ctx, CLI_EXIT_INPUT, "%s: %s.%s has no value", where(ctx, e), section, key);
  *n = count;
  return CLI_EXIT_OK;
}

int cli_record_doubles_used(cli_ctx *ctx, const char *section, const char *key, const double *v, size_t n) {
  cli_config *c = ctx->cfg;
  cli_read *r = NULL;
  char *text, num[40];
  size_t i, len = 0, cap = 32 * n + 1;
  for (i = 0; i < c->nreads; i++)
    if (strcmp(c->reads[i].section, section) == 0 && strcmp(c->reads[i].key, key) == 0) r = &c->reads[i];
  if (r && r->given) return 0; /* given: recorded as given */
  if (n == 0) return 0;
  if ((text = malloc(cap)) == NULL) {
    c->nomem = 1;
    return -1;
  }
  text[0] = '\0';
  for (i = 0; i < n; i++) {
    format_double(v[i], num, sizeof num);
    len += (size_t)snprintf(text + len, cap - len, "%s%s", i ? ", " : "", num);
  }
  if (r && r->value == NULL && !r->varies) { /* the getter's "unknown default": now known */
    c->generation++;
    r->value = text;
    r->presence = 1;
    return 0;
  }
  record_read(c, section, key, text, 0, 1);
  free(text);
  return 0;
}

static int tolower_ascii(int ch) { return (ch >= 'A' && ch <= 'Z') ? ch - 'A' + 'a' : ch; }

/* Levenshtein distance, case-insensitive, for "did you mean". */
static size_t edit_distance(const char *a, const char *b, int fold) {
  size_t la = strlen(a), lb = strlen(b), i, j;
  size_t row[256];
  if (la > 255 || lb > 255) return (size_t)-1;
  for (j = 0; j <= lb; j++) row[j] = j;
  for (i = 1; i <= la; i++) {
    size_t prev = row[0];
    row[0] = i;
    for (j = 1; j <= lb; j++) {
      size_t cur = row[j];
      size_t cost = (fold ? tolower_ascii(a[i - 1]) == tolower_ascii(b[j - 1]) : a[i - 1] == b[j - 1]) ? 0 : 1;
      size_t best = prev + cost;
      if (row[j] + 1 < best) best = row[j] + 1;
      if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
      row[j] = best;
      prev = cur;
    }
  }
  return row[lb];
}

/* The closeness of two names: the case-insensitive distance first, the exact one breaks ties. */
static size_t name_distance(const char *a, const char *b) {
  size_t f = edit_distance(a, b, 1), e = edit_distance(a, b, 0);
  return f == (size_t)-1 || e == (size_t)-1 ? (size_t)-1 : 4 * f + e;
}

size_t cli_did_you_mean(const char *word, const char *const *cands, size_t n, size_t max_edits, char *buf,
                        size_t len) {
  size_t k, best = (size_t)-1, count = 0, pos = 0;
  if (len) buf[0] = '\0';
  for (k = 0; k < n; k++) {
    size_t d = name_distance(word, cands[k]);
    if (d < best && d <= 6 * max_edits && edit_distance(word, cands[k], 1) <= max_edits) best = d;
  }
  if (best == (size_t)-1) return 0;
  /* every candidate at the best distance: "'a' or 'b'" */
  for (k = 0; k < n; k++) {
    size_t need = strlen(cands[k]) + (pos ? 6 : 2);
    if (name_distance(word, cands[k]) != best) continue;
    if (pos + need >= len) break; /* the list is full */
    pos += (size_t)snprintf(buf + pos, len - pos, "%s'%s'", pos ? " or " : "", cands[k]);
    count++;
  }
  return count;
}

int cli_config_check_unused(cli_ctx *ctx) {
  cli_config *c = ctx->cfg;
  size_t i, k;
  for (i = 0; i < c->n; i++) {
    cli_entry *e = &c->entries[i];
    char full[256], sect_star[256], list[512];
    const char **keys;
    size_t nkeys = 0;
    int section_known = 0;
    if (e->used) continue;
    snprintf(full, sizeof full, "%s.%s", e->section, e->key);
    snprintf(sect_star, sizeof sect_star, "%s.", e->section);
    keys = calloc(c->nknown + 1, sizeof *keys);
    if (!keys) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
    for (k = 0; k < c->nknown; k++) {
      if (strncmp(c->known[k], sect_star, strlen(sect_star)) == 0) section_known = 1;
      if (!strstr(c->known[k], ".*")) keys[nkeys++] = c->known[k];
    }
    nkeys = cli_did_you_mean(full, keys, nkeys, 3, list, sizeof list);
    free(keys);
    if (nkeys > 0)
      return cli_fail(ctx, CLI_EXIT_INPUT, "%s: unknown %s '%s' for 'autobal %s'; did you mean %s?", where(ctx, e),
                      section_known ? "key" : "section/key", full, ctx->command, list);
    if (section_known)
      return cli_fail(ctx, CLI_EXIT_INPUT, "%s: unknown key '%s' for 'autobal %s' (see 'autobal %s --help' for the keys)",
                      where(ctx, e), full, ctx->command, ctx->command);
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "%s: unknown section [%s] (key '%s') for 'autobal %s' (see 'autobal %s --help' for the keys)",
                    where(ctx, e), e->section, full, ctx->command, ctx->command);
  }
  return CLI_EXIT_OK;
}

/* ---- signals and progress ------------------------------------------------------ */
static volatile sig_atomic_t g_signal = 0; /* app-level only: the library has no globals */

static void on_signal(int sig) { g_signal = sig; }

void cli_signals_install(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  { /* the terminal closed: stop and keep what was computed; unless SIGHUP is ignored (nohup) */
    struct sigaction old;
    if (sigaction(SIGHUP, NULL, &old) == 0 && old.sa_handler != SIG_IGN) sigaction(SIGHUP, &sa, NULL);
  }
}

const char *cli_signal_reason(void) {
  switch ((int)g_signal) {
    case SIGTERM: return "interrupted by SIGTERM";
    case SIGHUP: return "interrupted by SIGHUP";
    default: return "interrupted by SIGINT";
  }
}

int cli_interrupted(void) { return g_signal != 0; }
int cli_signal_number(void) { return (int)g_signal; }

int cli_progress(cli_ctx *ctx, const char *label, double fraction) {
  if (ctx->progress) {
    int width = 40, filled, i;
    if (fraction < 0) fraction = 0;
    if (fraction > 1) fraction = 1;
    filled = (int)(fraction * width + 0.5);
    fprintf(stderr, "\r%-18s [", label);
    for (i = 0; i < width; i++) fputc(i < filled ? '#' : '.', stderr);
    fprintf(stderr, "] %5.1f%%", 100.0 * fraction);
    fflush(stderr);
  }
  return cli_interrupted();
}

void cli_progress_done(cli_ctx *ctx) {
  if (ctx->progress) {
    fputc('\n', stderr);
    fflush(stderr);
  }
}

/* ---- JSON ---------------------------------------------------------------------- */
static void json_sep(cli_json *j, const char *key) {
  if (!j->first[j->depth]) fputc(',', j->f);
  j->first[j->depth] = 0;
  if (key) {
    const char *p;
    fputc('"', j->f);
    for (p = key; *p; p++) {
      if (*p == '"' || *p == '\\') fputc('\\', j->f);
      fputc(*p, j->f);
    }
    fputs("\":", j->f);
  }
}

static void json_push(cli_json *j, char open) {
  fputc(open, j->f);
  if (j->depth < 15) j->depth++;
  j->first[j->depth] = 1;
}

void cli_json_begin(cli_json *j, FILE *f) {
  j->f = f;
  j->depth = 0;
  j->n_units = 0;
  j->first[0] = 1;
  json_push(j, '{');
}
void cli_json_end(cli_json *j) {
  fputs("}\n", j->f);
  j->depth = 0;
}
void cli_json_key(cli_json *j, const char *key) { json_sep(j, key); }
void cli_json_object(cli_json *j, const char *key) {
  json_sep(j, key);
  json_push(j, '{');
}
void cli_json_object_end(cli_json *j) {
  fputc('}', j->f);
  if (j->depth > 0) j->depth--;
}
void cli_json_array(cli_json *j, const char *key) {
  json_sep(j, key);
  json_push(j, '[');
}
void cli_json_array_end(cli_json *j) {
  fputc(']', j->f);
  if (j->depth > 0) j->depth--;
}
static void json_num(FILE *f, double v) {
  if (isfinite(v)) fprintf(f, "%.17g", v);
  else fputs("null", f);
}
void cli_json_number(cli_json *j, const char *key, double v) {
  json_sep(j, key);
  json_num(j->f, v);
}
void cli_json_int(cli_json *j, const char *key, long v) {
  json_sep(j, key);
  fprintf(j->f, "%ld", v);
}
void cli_json_bool(cli_json *j, const char *key, int v) {
  json_sep(j, key);
  fputs(v ? "true" : "false", j->f);
}
void cli_json_string(cli_json *j, const char *key, const char *s) {
  const unsigned char *p;
  json_sep(j, key);
  fputc('"', j->f);
  for (p = (const unsigned char *)(s ? s : ""); *p; p++) {
    if (*p == '"' || *p == '\\') fprintf(j->f, "\\%c", *p);
    else if (*p < 0x20 || *p == 0x7f) fprintf(j->f, "\\u%04x", *p);
    else if (*p == 0xc2 && p[1] >= 0x80 && p[1] <= 0x9f) { /* C1 controls (U+0080-U+009F) */
      fprintf(j->f, "\\u%04x", p[1]);
      p++;
    } else fputc(*p, j->f);
  }
  fputc('"', j->f);
}
void cli_json_numbers(cli_json *j, const char *key, const double *v, size_t n) {
  size_t i;
  cli_json_array(j, key);
  for (i = 0; i < n; i++) {
    if (i) fputc(',', j->f);
    json_num(j->f, v[i]);
  }
  j->first[j->depth] = n == 0;
  cli_json_array_end(j);
}
void cli_json_summary_begin(cli_json *j, const cli_ctx *ctx) {
  cli_json_begin(j, stdout);
  cli_json_string(j, "command", ctx->command);
}
void cli_json_unit(cli_json *j, const char *key, const char *unit) {
  int i;
  for (i = 0; i < j->n_units; i++)
    if (strcmp(j->unit_key[i], key) == 0) return;
  if (j->n_units < (int)(sizeof j->unit_key / sizeof j->unit_key[0])) {
    j->unit_key[j->n_units] = key;
    j->unit_val[j->n_units++] = unit;
  }
}
void cli_json_quantity(cli_json *j, const char *key, double v, const char *unit) {
  cli_json_number(j, key, v);
  if (j->depth == 1) cli_json_unit(j, key, unit);
}
void cli_json_quantities(cli_json *j, const char *key, const double *v, size_t n, const char *unit) {
  cli_json_numbers(j, key, v, n);
  if (j->depth == 1) cli_json_unit(j, key, unit);
}
void cli_json_summary_end(cli_json *j, const cli_ctx *ctx) {
  if (ctx->output) cli_json_string(j, "output", ctx->output);
  if (j->n_units > 0) {
    int i;
    cli_json_object(j, "units");
    for (i = 0; i < j->n_units; i++) cli_json_string(j, j->unit_key[i], j->unit_val[i]);
    cli_json_object_end(j);
  }
  cli_json_end(j);
}

char *cli_config_to_ini(const cli_config *c) {
  size_t i, j, len = 1, pos = 0;
  char *out;
  for (i = 0; i < c->n; i++)
    len += strlen(c->entries[i].section) + strlen(c->entries[i].key) + strlen(c->entries[i].value) + 8;
  out = malloc(len);
  if (!out) return NULL;
  out[0] = '\0';
  /* group by section, in order of first appearance; recorded defaults (rerun) are not given */
  for (i = 0; i < c->n; i++) {
    int seen = 0;
    if (c->entries[i].is_default) continue;
    for (j = 0; j < i; j++)
      if (!c->entries[j].is_default && strcmp(c->entries[j].section, c->entries[i].section) == 0) seen = 1;
    if (seen) continue;
    pos += (size_t)snprintf(out + pos, len - pos, "[%s]\n", c->entries[i].section);
    for (j = i; j < c->n; j++)
      if (!c->entries[j].is_default && strcmp(c->entries[j].section, c->entries[i].section) == 0)
        pos += (size_t)snprintf(out + pos, len - pos, "%s = %s\n", c->entries[j].key, c->entries[j].value);
  }
  return out;
}

/* ---- the effective configuration ---------------------------------------------------------- */
typedef struct sbuf {
  char *p;
  size_t len, cap;
  int nomem;
} sbuf;

static void sb_add(sbuf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void sb_add(sbuf *b, const char *fmt, ...) {
  va_list ap;
  int n;
  if (b->nomem) return;
  for (;;) {
    size_t room = b->cap - b->len;
    va_start(ap, fmt);
    n = vsnprintf(b->p ? b->p + b->len : NULL, b->p ? room : 0, fmt, ap);
    va_end(ap);
    if (n < 0) {
      b->nomem = 1;
      return;
    }
    if (b->p && (size_t)n < room) {
      b->len += (size_t)n;
      return;
    }
    {
      size_t cap = b->cap ? 2 * b->cap : 1024;
      char *q;
      while (cap - b->len <= (size_t)n) cap *= 2;
      q = realloc(b->p, cap);
      if (!q) {
        b->nomem = 1;
        return;
      }
      b->p = q;
      b->cap = cap;
    }
  }
}

static int section_known_absent(const cli_config *c, const char *section) {
  size_t i;
  for (i = 0; i < c->nabsent; i++)
    if (strcmp(c->absent_sections[i], section) == 0) return 1;
  return 0;
}

/* A default whose text would not read back as the same given value: a non-finite number (the
 * number getters reject NaN/inf), an empty value (rejected as "no value"), surrounding blanks
 * (stripped by the INI reader) or an inline-comment " ;". */
static int default_needs_marker(const char *v) {
  size_t len = strlen(v);
  char *end;
  double d;
  if (len == 0 || v[0] == ' ' || v[0] == '\t' || v[len - 1] == ' ' || v[len - 1] == '\t' || strstr(v, " ;") ||
      strstr(v, "\t;"))
    return 1;
  d = strtod(v, &end);
  return end != v && *end == '\0' && !isfinite(d);
}

/* The comment lines of the given file, each as ";# TEXT" (`autobal rerun` gives them back). */
static void comment_lines(sbuf *b, const char *text) {
  const char *p = text;
  while (p && *p) {
    const char *nl = strchr(p, '\n');
    size_t n = nl ? (size_t)(nl - p) : strlen(p);
    sb_add(b, ";# %.*s\n", (int)n, p);
    p = nl ? nl + 1 : NULL;
  }
}

static void effective_line(sbuf *b, const cli_config *c, const cli_read *r) {
  const cli_entry *e = find_entry(c, r->section, r->key);
  if (e && e->comment) comment_lines(b, e->comment);
  if (r->given) {
    sb_add(b, "%s = %s\n", r->key, r->value ? r->value : "");
  } else if (r->varies) {
    sb_add(b, "; %s not given: read with different built-in defaults (none recorded)\n", r->key);
  } else if (!r->value) {
    sb_add(b, "; %s not given: the command's built-in value (not known to the configuration reader)\n", r->key);
  } else if (strchr(r->value, '\n') || strchr(r->value, '\r')) {
    sb_add(b, "; %s not given: a built-in default of several lines (not recorded)\n", r->key);
  } else if (r->presence || section_known_absent(c, r->section) || default_needs_marker(r->value)) {
    sb_add(b, ";default %s = %s\n", r->key, r->value);
  } else {
    sb_add(b, "%s = %s\n", r->key, r->value);
  }
}

char *cli_config_effective_ini(const cli_config *c, const char *command) {
  sbuf b;
  size_t i, j, k;
  memset(&b, 0, sizeof b);
  if (c->nomem) return NULL;
  sb_add(&b,
         "; the effective configuration of 'autobal %s': every key the command read, with the value it used\n"
         "; (given in the file or with --set, else the built-in default); `autobal rerun` runs from this text.\n"
         "; \";default KEY = VALUE\": KEY was not given, and the command tells a given KEY from an absent one,\n"
         "; so it stays absent; VALUE is the built-in default that was used (a re-run uses this VALUE).\n",
         command ? command : "?");
  if (c->preamble) {
    sb_add(&b, "; the comments of the given configuration follow as \";# ...\" lines.\n");
    comment_lines(&b, c->preamble);
  }
  /* sections in the order of their first read; keys in the order read */
  for (i = 0; i < c->nreads; i++) {
    const char *sec = c->reads[i].section;
    int seen = 0;
    for (j = 0; j < i && !seen; j++) seen = strcmp(c->reads[j].section, sec) == 0;
    if (seen) continue;
    sb_add(&b, "[%s]\n", sec);
    for (j = i; j < c->nreads; j++)
      if (strcmp(c->reads[j].section, sec) == 0) effective_line(&b, c, &c->reads[j]);
    /* given keys of this section that were not read (a section declared known as a whole) */
    for (k = 0; k < c->n; k++) {
      const cli_entry *e = &c->entries[k];
      int read = 0;
      if (e->is_default || strcmp(e->section, sec) != 0) continue;
      for (j = 0; j < c->nreads && !read; j++) read = !strcmp(c->reads[j].section, sec) && !strcmp(c->reads[j].key, e->key);
      if (!read) {
        if (e->comment) comment_lines(&b, e->comment);
        sb_add(&b, "%s = %s\n", e->key, e->value);
      }
    }
  }
  /* sections given but never read from (declared known as a whole) */
  for (k = 0; k < c->n; k++) {
    const char *sec = c->entries[k].section;
    int seen = 0;
    if (c->entries[k].is_default) continue;
    for (j = 0; j < c->nreads && !seen; j++) seen = strcmp(c->reads[j].section, sec) == 0;
    for (j = 0; j < k && !seen; j++) seen = !c->entries[j].is_default && strcmp(c->entries[j].section, sec) == 0;
    if (seen) continue;
    sb_add(&b, "[%s]\n", sec);
    for (j = k; j < c->n; j++)
      if (!c->entries[j].is_default && strcmp(c->entries[j].section, sec) == 0) {
        if (c->entries[j].comment) comment_lines(&b, c->entries[j].comment);
        sb_add(&b, "%s = %s\n", c->entries[j].key, c->entries[j].value);
      }
  }
  if (b.nomem || !b.p) {
    free(b.p);
    return NULL;
  }
  return b.p;
}

int cli_config_has_key(const cli_config *c, const char *section, const char *key) {
  return c && find_entry(c, section, key) != NULL;
}

int cli_config_add_default(cli_ctx *ctx, const char *section, const char *key, const char *value) {
  cli_config *c = ctx->cfg;
  cli_entry *e;
  int rc;
  if (find_entry(c, section, key))
    return cli_fail(ctx, CLI_EXIT_INPUT, "key '%s.%s' is given and recorded as a default (;default)", section, key);
  if ((rc = add_entry(c, section, key, value, 1)) != 0)
    return rc == -2 ? cli_fail(ctx, CLI_EXIT_INPUT, "more than %d keys in all (the limit CLI_CONFIG_MAX_KEYS)",
                               CLI_CONFIG_MAX_KEYS)
                    : cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  e = find_entry(c, section, key);
  if (e) e->is_default = 1;
  return CLI_EXIT_OK;
}

int cli_config_set_given_text(cli_config *c, const char *ini) {
  char *t = NULL;
  if (ini && !(t = dupstr(ini))) return -1;
  free(c->given_text);
  c->given_text = t;
  return 0;
}

char *cli_config_given_ini(const cli_config *c) {
  if (c->given_text) return dupstr(c->given_text);
  return cli_config_to_ini(c);
}

int cli_config_effective_stale(const cli_config *c) { return c->generation != c->archived; }
void cli_config_effective_archived(cli_config *c) { c->archived = c->generation; }
