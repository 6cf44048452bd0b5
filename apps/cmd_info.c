/* cmd_info.c: `autobal info FILE.h5 [--json]`: a readable summary of any autobal archive:
 * what was run (command, configuration, provenance, status), the headline results
 * (verdicts, critical speeds, stable intervals, time to balance, ...), then every group with
 * its attributes (parameters with units, solver settings and statistics) and its datasets
 * (dimensions, shape, type, units, long_name; values of short ones).
 *
 * It knows the archive layout (archive.h), not the physics: it works on archives of every
 * command, present and future, because it walks the file.  Headline results are attributes
 * and small datasets with well-known names (see is_headline_attr / headline_datasets).
 *
 * Reading.  Only through the archive API (archive.h): it validates the file (Conventions,
 * damaged/truncated/foreign HDF5 files -> exit 4), lists groups and attributes
 * (autobal_archive_list, _list_attrs), reads shapes, types, dimension names and values
 * (_var_describe, _read_var, _read_attr_doubles, _read_attr_string). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/archive.h"
#include "cli.h"

int cli_cmd_info(cli_ctx *ctx); /* registered in commands.c */

#define INFO_MAX_VALUES_JSON 64 /* datasets up to this many elements show their values in --json */
#define INFO_MAX_VALUES_TEXT 8  /* ... and up to this many in the text summary */

/* ---- text output ------------------------------------------------------------------- */
/* printf for the text summary, with every control character that a crafted archive could
 * carry to the terminal (bytes 0x00-0x1f except newline and tab, DEL, and the C1 controls
 * U+0080-U+009F, encoded 0xC2 0x80-0x9F) shown as \xNN: strings of an archive never
 * reach the terminal raw (--json escapes them its own way). */
static void info_printf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void info_printf(const char *fmt, ...) {
  char small[512], *buf = small;
  const unsigned char *p;
  va_list ap;
  int n;
  va_start(ap, fmt);
  n = vsnprintf(small, sizeof small, fmt, ap);
  va_end(ap);
  if (n < 0) return;
  if ((size_t)n >= sizeof small) {
    buf = malloc((size_t)n + 1);
    if (!buf) return;
    va_start(ap, fmt);
    (void)vsnprintf(buf, (size_t)n + 1, fmt, ap);
    va_end(ap);
  }
  for (p = (const unsigned char *)buf; *p; p++) {
    if ((*p < 0x20 && *p != '\n' && *p != '\t') || *p == 0x7f)
      fprintf(stdout, "\\x%02x", *p);
    else if (*p == 0xc2 && p[1] >= 0x80 && p[1] <= 0x9f) {
      fprintf(stdout, "\\xc2\\x%02x", p[1]);
      p++;
    } else
      fputc(*p, stdout);
  }
  if (buf != small) free(buf);
}

/* ---- attributes and dataset descriptions (archive.h) ------------------------------ */
/* Copy src into dst (len bytes), truncated and NUL-terminated. */
static void copy_name(char *dst, size_t len, const char *src) {
  size_t n = strlen(src);
  if (n >= len) n = len - 1;
  memcpy(dst, src, n);
  dst[n] = '\0';
}

typedef enum { ATTR_NUMBER, ATTR_STRING, ATTR_OTHER } attr_kind;

typedef struct info_attr {
  char name[AUTOBAL_ARCHIVE_NAME_MAX + 1];
  attr_kind kind;
  int is_int;     /* integer type (printed without a fraction) */
  size_t n;       /* number of elements */
  double *v;      /* ATTR_NUMBER: the n values */
  char *s;        /* ATTR_STRING: the value (scalar strings only; arrays: ATTR_OTHER) */
} info_attr;

typedef struct info_attrs {
  info_attr *a;
  size_t n, cap;
  int failed; /* out of memory or an unreadable attribute */
  autobal_archive *arch; /* for the readers */
  const char *obj;       /* the object whose attributes are read */
} info_attrs;

static void attrs_free(info_attrs *l) {
  size_t i;
  for (i = 0; i < l->n; i++) {
    free(l->a[i].v);
    free(l->a[i].s);
  }
  free(l->a);
  memset(l, 0, sizeof *l);
}

static const info_attr *attrs_find(const info_attrs *l, const char *name) {
  size_t i;
  for (i = 0; i < l->n; i++)
    if (strcmp(l->a[i].name, name) == 0) return &l->a[i];
  return NULL;
}

/* The units of parameter `name`: attribute name_units (a string), or NULL. */
static const char *attrs_units(const info_attrs *l, const char *name) {
  char key[AUTOBAL_ARCHIVE_NAME_MAX + 8];
  const info_attr *u;
  snprintf(key, sizeof key, "%s_units", name);
  u = attrs_find(l, key);
  return (u && u->kind == ATTR_STRING) ? u->s : NULL;
}

/* A NAME_units attribute whose NAME is also present: shown together with NAME. */
static int is_units_of_other(const info_attrs *l, const char *name) {
  size_t len = strlen(name);
  char base[AUTOBAL_ARCHIVE_NAME_MAX + 1];
  if (len <= 6 || strcmp(name + len - 6, "_units") != 0 || len - 6 > AUTOBAL_ARCHIVE_NAME_MAX) return 0;
  memcpy(base, name, len - 6);
  base[len - 6] = '\0';
  return attrs_find(l, base) != NULL;
}

/* autobal_archive_list_attrs callback (called outside the archive's iteration, so it may
 * read): numbers of any shape as doubles, scalar strings; other types are listed only.  The
 * format's own attributes (dimension scales, netCDF) are not listed by the archive. */
static int attr_cb(const autobal_archive_attr_info *ai, void *data) {
  info_attrs *l = data;
  info_attr *at;
  if (l->n == l->cap) {
    size_t cap = l->cap ? 2 * l->cap : 32;
    info_attr *p = realloc(l->a, cap * sizeof *p);
    if (!p) {
      l->failed = 1;
      return 1;
    }
    l->a = p;
    l->cap = cap;
  }
  at = &l->a[l->n];
  memset(at, 0, sizeof *at);
  copy_name(at->name, sizeof at->name, ai->name);
  at->kind = ATTR_OTHER;
  at->n = ai->count;
  l->n++;
  switch (ai->type_class) {
    case AUTOBAL_ARCHIVE_CLASS_INTEGER:
    case AUTOBAL_ARCHIVE_CLASS_FLOAT:
      if (at->n == 0) break;
      at->v = malloc(at->n * sizeof *at->v);
      if (!at->v) {
        l->failed = 1;
        break;
      }
      if (autobal_archive_read_attr_doubles(l->arch, l->obj, ai->name, at->v, at->n, NULL) != AUTOBAL_SUCCESS) {
        free(at->v);
        at->v = NULL;
        break;
      }
      at->kind = ATTR_NUMBER;
      at->is_int = ai->type_class == AUTOBAL_ARCHIVE_CLASS_INTEGER;
      break;
    case AUTOBAL_ARCHIVE_CLASS_STRING: {
      size_t len = 0;
      char probe[1];
      if (at->n != 1) break;
      if (autobal_archive_read_attr_string(l->arch, l->obj, ai->name, probe, sizeof probe, &len) >= 0 &&
          (at->s = malloc(len + 1)) != NULL &&
          autobal_archive_read_attr_string(l->arch, l->obj, ai->name, at->s, len + 1, NULL) == AUTOBAL_SUCCESS) {
        at->kind = ATTR_STRING;
      } else {
        free(at->s);
        at->s = NULL;
        l->failed = 1;
      }
      break;
    }
    default:
      break;
  }
  return 0;
}

/* All (non-reserved) attributes of the group or dataset `path`, by name. */
static int read_attrs(autobal_archive *a, const char *path, info_attrs *out) {
  int st;
  memset(out, 0, sizeof *out);
  out->arch = a;
  out->obj = path;
  st = autobal_archive_list_attrs(a, path, AUTOBAL_ARCHIVE_ORDER_NAME, attr_cb, out);
  return (st != AUTOBAL_SUCCESS || out->failed) ? -1 : 0;
}

typedef struct dim_names {
  char name[AUTOBAL_ARCHIVE_MAX_RANK][AUTOBAL_ARCHIVE_NAME_MAX + 1];
  int scale; /* the dataset is itself a dimension scale (a coordinate) */
} dim_names;

/* Dimension names of dataset `path` (empty where no scale is attached) and its type as a
 * numpy-style name ("float64", "int32", "string", ...; "?" if it cannot be described). */
static void dataset_meta(autobal_archive *a, const char *path, dim_names *dn, char *dtype, size_t dtlen) {
  autobal_archive_var_info vi;
  int d;
  memset(dn, 0, sizeof *dn);
  snprintf(dtype, dtlen, "?");
  if (autobal_archive_var_describe(a, path, &vi) != AUTOBAL_SUCCESS) return;
  dn->scale = vi.is_coordinate;
  for (d = 0; d < vi.rank && d < AUTOBAL_ARCHIVE_MAX_RANK; d++) copy_name(dn->name[d], sizeof dn->name[d], vi.dim_names[d]);
  switch (vi.type_class) {
    case AUTOBAL_ARCHIVE_CLASS_FLOAT:
      snprintf(dtype, dtlen, "float%zu", 8 * vi.size);
      break;
    case AUTOBAL_ARCHIVE_CLASS_INTEGER:
      snprintf(dtype, dtlen, "%sint%zu", vi.is_unsigned ? "u" : "", 8 * vi.size);
      break;
    case AUTOBAL_ARCHIVE_CLASS_STRING:
      snprintf(dtype, dtlen, "string");
      break;
    default:
      snprintf(dtype, dtlen, "other");
      break;
  }
}

/* ---- walking the archive ------------------------------------------------------------- */
typedef struct member {
  char name[AUTOBAL_ARCHIVE_NAME_MAX + 1];
  int is_group;
} member;

typedef struct members {
  member *m;
  size_t n, cap;
  int failed;
} members;

static int list_cb(const char *name, int is_group, void *ctx) {
  members *l = ctx;
  if (l->n == l->cap) {
    size_t cap = l->cap ? 2 * l->cap : 32;
    member *p = realloc(l->m, cap * sizeof *p);
    if (!p) {
      l->failed = 1;
      return 1;
    }
    l->m = p;
    l->cap = cap;
  }
  copy_name(l->m[l->n].name, sizeof l->m[l->n].name, name);
  l->m[l->n].is_group = is_group;
  l->n++;
  return 0;
}

typedef struct info_run {
  cli_ctx *ctx;
  autobal_archive *a;
  cli_json j;
  int json;
  int pass; /* text: 0 headline pass, 1 full listing */
  size_t nheadline;
  int failed;
  /* the walk: groups already visited in this pass (their object ids: hard links to a group
   * are listed once, a cycle of links ends) and the nesting depth */
  uint64_t *seen;
  size_t nseen, capseen;
  int depth;
} info_run;

/* Deepest group nesting listed (autobal archives nest 4 deep; a crafted file could nest
 * thousands). */
#define INFO_MAX_DEPTH 32

/* A member name the archive API refuses (control characters; autobal never writes one):
 * such a member of a crafted file is named, escaped, and skipped. */
static int bad_name(const char *name) {
  const unsigned char *p;
  for (p = (const unsigned char *)name; *p; p++)
    if (*p < 0x20 || *p == 0x7f || (*p == 0xc2 && p[1] >= 0x80 && p[1] <= 0x9f)) return 1;
  return 0;
}

static void join_path(char *out, size_t len, const char *group, const char *name) {
  if (!strcmp(group, "/")) snprintf(out, len, "/%s", name);
  else snprintf(out, len, "%s/%s", group, name);
}

/* Print n numbers: "%.10g" joined by ", "; at most `max` then "...". */
static void print_numbers(FILE *f, const double *v, size_t n, int is_int, size_t max) {
  size_t i;
  for (i = 0; i < n && i < max; i++) {
    if (is_int && isfinite(v[i])) fprintf(f, "%s%.0f", i ? ", " : "", v[i]);
    else fprintf(f, "%s%.10g", i ? ", " : "", v[i]);
  }
  if (n > max) fprintf(f, ", ... (%zu values)", n);
}

static void json_attr_value(cli_json *j, const info_attr *at) {
  if (at->kind == ATTR_STRING) cli_json_string(j, "value", at->s);
  else if (at->kind == ATTR_NUMBER && at->n == 1 && at->is_int) cli_json_int(j, "value", (long)at->v[0]);
  else if (at->kind == ATTR_NUMBER && at->n == 1) cli_json_number(j, "value", at->v[0]);
  else if (at->kind == ATTR_NUMBER) cli_json_numbers(j, "value", at->v, at->n);
  else cli_json_string(j, "value", NULL);
}

/* Headline attributes: verdicts, balance, margins, critical values. */
static int is_headline_attr(const char *name) {
  static const char *const exact[] = {"balanced", "time_to_balance", "max_real", "margin", "n_right_half_plane",
                                      "R_m1", "R_w_at_R_m1", "residual_unbalance_initial",
                                      "residual_unbalance_final", "unbalance_initial", "unbalance_final",
                                      "amplitude_first_10pct_max", "amplitude_last_10pct_max", "t_reached",
                                      "stop_reason", "method"};
  size_t i, len = strlen(name);
  for (i = 0; i < sizeof exact / sizeof exact[0]; i++)
    if (!strcmp(name, exact[i])) return 1;
  if (strstr(name, "verdict")) return 1;                                       /* verdict, linear_verdict */
  if (!strncmp(name, "n_", 2) && len > 8 && !strcmp(name + len - 8, "critical")) return 1; /* n_*critical */
  if (strstr(name, "critical_speed") || strstr(name, "stable_fraction")) return 1;
  return 0;
}

static int is_first_headline(const char *name) {
  return strstr(name, "verdict") != NULL || !strcmp(name, "balanced") || !strcmp(name, "time_to_balance");
}

static void headline_attr(info_run *r, const char *path, const info_attrs *al, const info_attr *at) {
  const char *u = attrs_units(al, at->name);
  if (r->json) {
    cli_json_object(&r->j, NULL);
    cli_json_string(&r->j, "path", path);
    cli_json_string(&r->j, "name", at->name);
    json_attr_value(&r->j, at);
    if (u) cli_json_string(&r->j, "units", u);
    cli_json_object_end(&r->j);
  } else {
    info_printf("  %-28s %-26s = ", path, at->name);
    if (at->kind == ATTR_STRING) info_printf("%s", at->s);
    else if (at->kind == ATTR_NUMBER && !strcmp(at->name, "balanced") && at->n == 1)
      info_printf("%s", at->v[0] != 0 ? "yes" : "no");
    else if (at->kind == ATTR_NUMBER) print_numbers(stdout, at->v, at->n, at->is_int, INFO_MAX_VALUES_TEXT);
    if (u && strcmp(u, "1") != 0) info_printf(" %s", u);
    info_printf("\n");
  }
  r->nheadline++;
}

/* A headline dataset: a short 1-D list of critical speeds, or a verdict grid (counts). */
static int dataset_headline_kind(const char *name, size_t count, int rank) {
  size_t len = strlen(name);
  if (rank == 1 && count <= INFO_MAX_VALUES_JSON) {
    if (len >= 3 && !strcmp(name + len - 3, "R_w")) return 1;             /* pendulum critical speeds */
    if (strstr(name, "critical") || strstr(name, "stable_lo") || strstr(name, "stable_hi")) return 1;
    if (!strncmp(name, "omega_", 6) || strstr(name, "_omega")) return 1;      /* rotor critical speeds */
    if (!strncmp(name, "natural_frequency", 17)) return 1;                     /* rotor at rest */
  }
  if (!strcmp(name, "verdict") && rank >= 1) return 2;
  return 0;
}

static int headline_dataset(info_run *r, const char *group, const char *dpath, const char *name, int rank,
                            size_t count, const char *units, int kind) {
  double *v = malloc((count ? count : 1) * sizeof *v);
  size_t i;
  if (!v) return cli_fail(r->ctx, CLI_EXIT_INTERNAL, "out of memory");
  if (autobal_archive_read_var(r->a, dpath, v, count) != AUTOBAL_SUCCESS) {
    free(v);
    return CLI_EXIT_OK; /* not numeric: no headline */
  }
  if (kind == 1) {
    if (r->json) {
      cli_json_object(&r->j, NULL);
      cli_json_string(&r->j, "path", group);
      cli_json_string(&r->j, "name", name);
      cli_json_numbers(&r->j, "value", v, count);
      if (units) cli_json_string(&r->j, "units", units);
      cli_json_object_end(&r->j);
    } else {
      info_printf("  %-28s %-26s = ", group, name);
      if (count == 0) info_printf("(none)");
      print_numbers(stdout, v, count, 0, 16);
      if (units && strcmp(units, "1") != 0) info_printf(" %s", units);
      info_printf("\n");
    }
  } else {
    size_t nst = 0, nmarg = 0, nun = 0, nother = 0;
    for (i = 0; i < count; i++) {
      if (v[i] == 1) nst++;
      else if (v[i] == 0) nmarg++;
      else if (v[i] == -1) nun++;
      else nother++;
    }
    if (r->json) {
      cli_json_object(&r->j, NULL);
      cli_json_string(&r->j, "path", group);
      cli_json_string(&r->j, "name", name);
      cli_json_object(&r->j, "value");
      cli_json_int(&r->j, "points", (long)count);
      cli_json_int(&r->j, "stable", (long)nst);
      cli_json_int(&r->j, "marginal", (long)nmarg);
      cli_json_int(&r->j, "unstable", (long)nun);
      cli_json_int(&r->j, "other", (long)nother);
      cli_json_object_end(&r->j);
      cli_json_object_end(&r->j);
    } else {
      info_printf("  %-28s %-26s = %zu points: %zu stable (%.1f%%), %zu marginal, %zu unstable", group, name, count, nst,
             count ? 100.0 * (double)nst / (double)count : 0.0, nmarg, nun);
      if (nother) info_printf(", %zu without a verdict", nother);
      info_printf("\n");
    }
    (void)rank;
  }
  r->nheadline++;
  free(v);
  return CLI_EXIT_OK;
}

/* Visit `group`: pass 0 (headline) prints only headline items; pass 1 the full listing. */
static int visit_group(info_run *r, const char *group) {
  members ml;
  info_attrs al;
  size_t i;
  int rc = CLI_EXIT_OK, st, printed_attr_heading = 0, printed_ds_heading = 0;
  char path[2048];

  memset(&ml, 0, sizeof ml);
  if (cli_interrupted()) /* SIGINT, SIGTERM, SIGHUP: stop listing */
    return cli_fail(r->ctx, CLI_EXIT_INTERRUPTED, "%s: the listing stopped before group '%s'", cli_signal_reason(), group);
  {
    uint64_t id = 0;
    size_t k;
    if (r->depth > INFO_MAX_DEPTH)
      return cli_fail(r->ctx, CLI_EXIT_IO,
                      "group '%s' is nested deeper than %d levels: not the layout of an autobal archive",
                      group, INFO_MAX_DEPTH);
    if (autobal_archive_object_id(r->a, group, &id) != AUTOBAL_SUCCESS)
      return cli_fail(r->ctx, CLI_EXIT_IO, "cannot identify group '%s': %s", group, autobal_archive_errmsg(r->a));
    for (k = 0; k < r->nseen; k++)
      if (r->seen[k] == id) {
        if (r->pass == 1 && !r->json)
          info_printf("\n%s   (a hard link to a group listed above: not repeated)\n", group);
        return CLI_EXIT_OK;
      }
    if (r->nseen == r->capseen) {
      size_t cap = r->capseen ? 2 * r->capseen : 64;
      uint64_t *p = realloc(r->seen, cap * sizeof *p);
      if (!p) return cli_fail(r->ctx, CLI_EXIT_INTERNAL, "out of memory listing group '%s'", group);
      r->seen = p;
      r->capseen = cap;
    }
    r->seen[r->nseen++] = id;
  }
  st = autobal_archive_list(r->a, group, list_cb, &ml);
  if (st != AUTOBAL_SUCCESS || ml.failed) {
    free(ml.m);
    return cli_fail(r->ctx, ml.failed ? CLI_EXIT_INTERNAL : CLI_EXIT_IO, "cannot list group '%s': %s", group,
                    ml.failed ? "out of memory" : autobal_archive_errmsg(r->a));
  }
  if (read_attrs(r->a, group, &al) != 0) {
    attrs_free(&al);
    free(ml.m);
    return cli_fail(r->ctx, CLI_EXIT_IO, "cannot read the attributes of group '%s'", group);
  }

  if (r->pass == 0) {
    int first;
    for (first = 1; first >= 0; first--) /* verdicts, balanced, time to balance first */
      for (i = 0; i < al.n; i++)
        if (is_headline_attr(al.a[i].name) && !is_units_of_other(&al, al.a[i].name) &&
            is_first_headline(al.a[i].name) == first)
          headline_attr(r, group, &al, &al.a[i]);
  } else if (strcmp(group, "/") != 0) {
    /* group heading and its attributes */
    if (r->json) {
      cli_json_object(&r->j, NULL);
      cli_json_string(&r->j, "path", group);
      cli_json_object(&r->j, "attributes");
    } else {
      const char *slash = strrchr(group, '/');
      info_printf("\n%s%s\n", group, (slash && !strcmp(slash, "/solver")) ? "   (solver statistics)" : "");
    }
    for (i = 0; i < al.n; i++) {
      const info_attr *at = &al.a[i];
      const char *u;
      if (is_units_of_other(&al, at->name)) continue;
      u = attrs_units(&al, at->name);
      if (r->json) {
        cli_json_object(&r->j, at->name);
        json_attr_value(&r->j, at);
        if (u) cli_json_string(&r->j, "units", u);
        cli_json_object_end(&r->j);
      } else {
        if (!printed_attr_heading) info_printf("  attributes\n");
        printed_attr_heading = 1;
        info_printf("    %-26s = ", at->name);
        if (at->kind == ATTR_STRING) {
          const char *nl = strchr(at->s, '\n');
          if (nl) info_printf("%.*s ...", (int)(nl - at->s), at->s);
          else info_printf("%s", at->s);
        } else if (at->kind == ATTR_NUMBER) print_numbers(stdout, at->v, at->n, at->is_int, INFO_MAX_VALUES_TEXT);
        else info_printf("(%zu element(s) of a type not shown)", at->n);
        if (u) info_printf("   [%s]", u);
        info_printf("\n");
      }
    }
    if (r->json) {
      cli_json_object_end(&r->j);
      cli_json_array(&r->j, "datasets");
    }
  }

  /* datasets */
  for (i = 0; i < ml.n && rc == CLI_EXIT_OK; i++) {
    int rank = 0, d;
    if (cli_interrupted()) {
      rc = cli_fail(r->ctx, CLI_EXIT_INTERRUPTED, "%s: the listing stopped in group '%s'", cli_signal_reason(), group);
      break;
    }
    size_t dims[AUTOBAL_ARCHIVE_MAX_RANK], count = 0;
    char units[128] = "", lname[1024] = "", dtype[32];
    dim_names dn;
    int has_units, has_lname;
    if (ml.m[i].is_group) continue;
    if (bad_name(ml.m[i].name)) {
      if (r->pass == 1 && !r->json)
        info_printf("    %s   (a name with control characters, not an autobal name: not listed)\n", ml.m[i].name);
      continue;
    }
    join_path(path, sizeof path, group, ml.m[i].name);
    st = autobal_archive_var_shape(r->a, path, &rank, dims, &count);
    if (st != AUTOBAL_SUCCESS) {
      if (r->pass == 1 && !r->json) info_printf("  %s: %s\n", ml.m[i].name, autobal_archive_errmsg(r->a));
      continue;
    }
    has_units = autobal_archive_read_attr_string(r->a, path, "units", units, sizeof units, NULL) >= 0;
    has_lname = autobal_archive_read_attr_string(r->a, path, "long_name", lname, sizeof lname, NULL) >= 0;
    dataset_meta(r->a, path, &dn, dtype, sizeof dtype);
    if (r->pass == 0) {
      int kind = dn.scale ? 0 : dataset_headline_kind(ml.m[i].name, count, rank);
      const char *base = strrchr(group, '/');
      /* the curves of figure 2 are long; the point values are in their parent group */
      if (kind && !(base && !strcmp(base, "/curves")))
        rc = headline_dataset(r, group, path, ml.m[i].name, rank, count, has_units ? units : NULL, kind);
      continue;
    }
    if (r->json) {
      info_attrs dl;
      size_t k;
      cli_json_object(&r->j, NULL);
      cli_json_string(&r->j, "name", ml.m[i].name);
      cli_json_string(&r->j, "path", path);
      cli_json_array(&r->j, "shape");
      for (d = 0; d < rank; d++) cli_json_int(&r->j, NULL, (long)dims[d]);
      cli_json_array_end(&r->j);
      cli_json_array(&r->j, "dims");
      for (d = 0; d < rank; d++) cli_json_string(&r->j, NULL, dn.name[d]);
      cli_json_array_end(&r->j);
      cli_json_string(&r->j, "dtype", dtype);
      cli_json_bool(&r->j, "coordinate", dn.scale);
      if (has_units) cli_json_string(&r->j, "units", units);
      if (has_lname) cli_json_string(&r->j, "long_name", lname);
      if (count <= INFO_MAX_VALUES_JSON && strcmp(dtype, "string") != 0) {
        double v[INFO_MAX_VALUES_JSON];
        if (count > 0 && autobal_archive_read_var(r->a, path, v, count) == AUTOBAL_SUCCESS)
          cli_json_numbers(&r->j, "values", v, count);
      }
      /* further attributes of the dataset (parameters attached to a variable) */
      if (read_attrs(r->a, path, &dl) == 0) {
        int any = 0;
        for (k = 0; k < dl.n; k++) {
          const info_attr *at = &dl.a[k];
          if (!strcmp(at->name, "units") || !strcmp(at->name, "long_name") || is_units_of_other(&dl, at->name))
            continue;
          if (!any) cli_json_object(&r->j, "attributes");
          any = 1;
          cli_json_object(&r->j, at->name);
          json_attr_value(&r->j, at);
          if (attrs_units(&dl, at->name)) cli_json_string(&r->j, "units", attrs_units(&dl, at->name));
          cli_json_object_end(&r->j);
        }
        if (any) cli_json_object_end(&r->j);
      }
      attrs_free(&dl);
      cli_json_object_end(&r->j);
    } else {
      char shape[512];
      size_t pos = 0;
      shape[0] = '\0';
      for (d = 0; d < rank; d++)
        pos += (size_t)snprintf(shape + pos, sizeof shape - pos, "%s%s=%zu", d ? ", " : "",
                                dn.name[d][0] ? dn.name[d] : "?", dims[d]);
      if (!printed_ds_heading) info_printf("  datasets\n");
      printed_ds_heading = 1;
      info_printf("    %s(%s) %s [%s]%s  %s\n", ml.m[i].name, rank ? shape : "", dtype, has_units ? units : "NO UNITS",
             dn.scale ? " coordinate," : "", has_lname ? lname : "(no long_name)");
      if (count > 0 && count <= INFO_MAX_VALUES_TEXT && strcmp(dtype, "string") != 0 && !dn.scale) {
        double v[INFO_MAX_VALUES_TEXT];
        if (autobal_archive_read_var(r->a, path, v, count) == AUTOBAL_SUCCESS) {
          info_printf("        = ");
          print_numbers(stdout, v, count, !strncmp(dtype, "int", 3), INFO_MAX_VALUES_TEXT);
          info_printf("\n");
        }
      }
    }
  }
  if (r->pass == 1 && strcmp(group, "/") != 0 && r->json) {
    cli_json_array_end(&r->j);
    cli_json_object_end(&r->j);
  }
  /* subgroups */
  for (i = 0; i < ml.n && rc == CLI_EXIT_OK; i++) {
    if (!ml.m[i].is_group) continue;
    if (bad_name(ml.m[i].name)) {
      if (r->pass == 1 && !r->json)
        info_printf("\n%s/%s   (a name with control characters, not an autobal name: not listed)\n",
                    strcmp(group, "/") ? group : "", ml.m[i].name);
      continue;
    }
    join_path(path, sizeof path, group, ml.m[i].name);
    r->depth++;
    rc = visit_group(r, path);
    r->depth--;
  }
  attrs_free(&al);
  free(ml.m);
  return rc;
}

/* ---- the command ---------------------------------------------------------------------- */
static const char *root_str(const info_attrs *root, const char *name) {
  const info_attr *at = attrs_find(root, name);
  return (at && at->kind == ATTR_STRING) ? at->s : NULL;
}

/* Keys of an INI text written by autobal: "key = value" lines, and with `defaults` also
 * ";default key = value" lines (cli_config_effective_ini); other ';' lines are comments. */
static size_t count_keys_of(const char *ini, int defaults) {
  size_t n = 0;
  const char *p = ini;
  while (p && *p) {
    const char *nl = strchr(p, '\n');
    size_t len = nl ? (size_t)(nl - p) : strlen(p);
    if (len > 0 && p[0] != '[' && memchr(p, '=', len) &&
        (p[0] != ';' || (defaults && len > 9 && !strncmp(p, ";default ", 9))))
      n++;
    p = nl ? nl + 1 : NULL;
  }
  return n;
}
static size_t count_keys(const char *ini) { return count_keys_of(ini, 0); }

int cli_cmd_info(cli_ctx *ctx) {
  info_run r;
  info_attrs root;
  autobal_error err;
  const char *path = ctx->config_path; /* the archive argument (see main.c) */
  const char *s, *cmd, *ini, *eff;
  int rc = CLI_EXIT_OK, st;
  size_t i;

  memset(&r, 0, sizeof r);
  memset(&root, 0, sizeof root);
  r.ctx = ctx;
  r.json = ctx->json;
  if (!path) return cli_fail(ctx, CLI_EXIT_USAGE, "info: give an archive: autobal info FILE.h5 [--json]");
  if (ctx->output) return cli_fail(ctx, CLI_EXIT_USAGE, "info: -o is not used (the summary goes to stdout)");
  autobal_error_clear(&err);
  st = autobal_archive_open_read(path, &r.a, &err);
  if (st != AUTOBAL_SUCCESS && cli_interrupted()) /* e.g. a read interrupted by the signal */
    return cli_fail(ctx, CLI_EXIT_INTERRUPTED, "%s while opening '%s'", cli_signal_reason(), path);
  if (st != AUTOBAL_SUCCESS)
    return cli_fail(ctx, st == AUTOBAL_ENOMEM ? CLI_EXIT_INTERNAL : CLI_EXIT_IO, "%s", err.message);
  if (read_attrs(r.a, "/", &root) != 0) {
    rc = cli_fail(ctx, CLI_EXIT_IO, "'%s': cannot read the root attributes", path);
    goto done;
  }
  cmd = root_str(&root, "command");
  ini = root_str(&root, "input_config");
  eff = root_str(&root, "effective_config");

  /* what was run */
  if (r.json) {
    cli_json_begin(&r.j, stdout);
    cli_json_string(&r.j, "file", path);
    cli_json_object(&r.j, "root");
    for (i = 0; i < root.n; i++) {
      const info_attr *at = &root.a[i];
      if (at->kind == ATTR_STRING) cli_json_string(&r.j, at->name, at->s);
      else if (at->kind == ATTR_NUMBER && at->n == 1) cli_json_number(&r.j, at->name, at->v[0]);
    }
    cli_json_object_end(&r.j);
    cli_json_string(&r.j, "command", cmd ? cmd : "");
    cli_json_string(&r.j, "status", root_str(&root, "status"));
    cli_json_int(&r.j, "input_config_keys", (long)count_keys(ini));
    if (eff) cli_json_int(&r.j, "effective_config_keys", (long)count_keys_of(eff, 1));
  } else {
    info_printf("archive       %s\n", path);
    info_printf("command       autobal %s\n", cmd ? cmd : "(unknown: no root attribute 'command')");
    s = root_str(&root, "status");
    info_printf("status        %s", s ? s : "(none)");
    if ((s = root_str(&root, "status_reason"))) info_printf(" (%s)", s);
    info_printf("\n");
    if ((s = root_str(&root, "title"))) info_printf("title         %s\n", s);
    info_printf("created       %s by autobal %s (git %s), GSL %s, HDF5 %s\n", root_str(&root, "created") ? root_str(&root, "created") : "?",
           root_str(&root, "autobal_version") ? root_str(&root, "autobal_version") : "?",
           root_str(&root, "git_revision") ? root_str(&root, "git_revision") : "?",
           root_str(&root, "gsl_version") ? root_str(&root, "gsl_version") : "?",
           root_str(&root, "hdf5_version") ? root_str(&root, "hdf5_version") : "?");
    if ((s = root_str(&root, "command_line"))) info_printf("command line  %s\n", s);
    if (!ini) info_printf("configuration (%s)\n", eff ? "the given one not recorded" : "not recorded: this archive cannot be re-run");
    else if (count_keys(ini) == 0) info_printf("configuration built-in defaults (no keys given)\n");
    else {
      const char *p = ini;
      info_printf("configuration %zu key(s), file plus --set overrides (autobal rerun repeats the run):\n",
             count_keys(ini));
      while (*p) {
        const char *nl = strchr(p, '\n');
        int len = nl ? (int)(nl - p) : (int)strlen(p);
        info_printf("    %.*s\n", len, p);
        if (!nl) break;
        p = nl + 1;
      }
    }
    if (eff)
      info_printf("effective     %zu key(s) read by the command with the values used, defaults included "
             "(root attribute effective_config; autobal rerun runs from it)\n",
             count_keys_of(eff, 1));
    s = root_str(&root, "status");
    if (s && strcmp(s, "complete") != 0)
      info_printf("WARNING: the run did not complete; the data below are partial.\n");
    info_printf("\nheadline results\n");
  }

  /* headline results */
  if (r.json) cli_json_array(&r.j, "headline");
  r.pass = 0;
  r.nseen = 0;
  rc = visit_group(&r, "/");
  if (r.json) cli_json_array_end(&r.j);
  else if (rc == CLI_EXIT_OK && r.nheadline == 0) info_printf("  (none recognised)\n");

  /* everything */
  if (rc == CLI_EXIT_OK) {
    if (r.json) cli_json_array(&r.j, "groups");
    else info_printf("\ngroups: attributes = value [units]; datasets(dimension=size) type [units] long_name\n");
    r.pass = 1;
    r.nseen = 0;
    rc = visit_group(&r, "/");
    if (r.json) cli_json_array_end(&r.j);
  }
  if (r.json) cli_json_end(&r.j);
done:
  free(r.seen);
  attrs_free(&root);
  autobal_archive_close(r.a, NULL);
  fflush(stdout);
  return rc;
}
