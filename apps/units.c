/* units.c: values with units in configuration files (UDUNITS-2); engineering quantities. */
#define _POSIX_C_SOURCE 200809L
#include "units.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <udunits2.h>

struct cli_units {
  ut_system *sys;
  ut_unit *hertz;
};

/* Names of angles (and of the angular speeds UDUNITS defines through one): a rotational-speed
 * unit that contains one of these counts the angle, so UDUNITS' conversion is the right one.
 * UDUNITS cannot tell them itself: it defines the radian as the number 1 (see units.h). */
static const char *const k_angle_names[] = {"rad",   "radian",     "radians",     "deg",       "degree",
                                            "degrees", "arc_degree", "angular_degree", "°",     "rev",
                                            "revolution", "revolutions", "cycle", "cycles", "turn",
                                            "turns", "rotation", "rotations", "circle", "circles",
                                            "rpm",   "rps"};

cli_units *cli_units_new(char *err, size_t len) {
  cli_units *u = calloc(1, sizeof *u);
  ut_unit *rev, *rps, *deg;
  if (!u) {
    snprintf(err, len, "out of memory");
    return NULL;
  }
  ut_set_error_message_handler(ut_ignore); /* statuses are checked; UDUNITS must not print */
  u->sys = ut_read_xml(NULL);
  if (!u->sys) {
    snprintf(err, len,
             "cannot read the UDUNITS-2 unit database (status %d; Debian package libudunits2-data, or set "
             "UDUNITS2_XML_PATH)",
             (int)ut_get_status());
    free(u);
    return NULL;
  }
  u->hertz = ut_parse(u->sys, "Hz", UT_ASCII);
  /* "rev", "rps" and "deg" as people write them (UDUNITS spells out "revolution" and "degree"). */
  rev = ut_parse(u->sys, "revolution", UT_ASCII);
  rps = ut_parse(u->sys, "revolution/s", UT_ASCII);
  deg = ut_parse(u->sys, "degree", UT_ASCII);
  if (!u->hertz || !rev || !rps || !deg || ut_map_symbol_to_unit("rev", UT_UTF8, rev) != UT_SUCCESS ||
      ut_map_symbol_to_unit("rps", UT_UTF8, rps) != UT_SUCCESS ||
      ut_map_symbol_to_unit("deg", UT_UTF8, deg) != UT_SUCCESS) {
    snprintf(err, len, "the UDUNITS-2 unit database lacks hertz, revolution or degree");
    ut_free(rev);
    ut_free(rps);
    ut_free(deg);
    cli_units_free(u);
    return NULL;
  }
  ut_free(rev);
  ut_free(rps);
  ut_free(deg);
  return u;
}

void cli_units_free(cli_units *u) {
  if (!u) return;
  ut_free(u->hertz);
  ut_free_system(u->sys);
  free(u);
}

size_t cli_units_split(const char *text, const char **unit) {
  const char *s = text, *end;
  char *e;
  while (*s == ' ' || *s == '\t') s++;
  errno = 0;
  (void)strtod(s, &e);
  end = e;
  if (end == s) {
    *unit = s;
    return 0;
  }
  *unit = end;
  while (**unit == ' ' || **unit == '\t') (*unit)++;
  return (size_t)(end - text);
}

/* Identifier tokens of a unit string (letters, '_', and UTF-8 bytes such as the degree sign):
 * calls fn on each (NUL-terminated copy); stops at the first non-zero return. */
static int each_token(const char *s, int (*fn)(cli_units *, const char *), cli_units *u) {
  char tok[64];
  while (*s) {
    size_t n = 0;
    while (*s && !((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || *s == '_' || (unsigned char)*s >= 0x80))
      s++;
    while (*s && ((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || *s == '_' || (unsigned char)*s >= 0x80)) {
      if (n + 1 < sizeof tok) tok[n++] = *s;
      s++;
    }
    tok[n] = '\0';
    if (n > 0) {
      int rc = fn(u, tok);
      if (rc) return rc;
    }
  }
  return 0;
}

static int is_angle_token(cli_units *u, const char *tok) {
  size_t i;
  (void)u;
  for (i = 0; i < sizeof k_angle_names / sizeof k_angle_names[0]; i++)
    if (strcmp(tok, k_angle_names[i]) == 0) return 1;
  return 0;
}

/* The hertz with an SI prefix (Hz, kHz, hertz, kilohertz). */
static int is_hertz_token(cli_units *u, const char *tok) {
  size_t n = strlen(tok);
  ut_unit *t;
  int yes;
  if (!((n >= 2 && strcmp(tok + n - 2, "Hz") == 0) || (n >= 5 && strcmp(tok + n - 5, "hertz") == 0))) return 0;
  t = ut_parse(u->sys, tok, UT_UTF8);
  yes = t != NULL && ut_are_convertible(t, u->hertz);
  ut_free(t);
  return yes;
}

/* A short description of what a unit of si_unit is, for messages. */
static const char *expected_examples(const char *si_unit) {
  static const struct {
    const char *si, *text;
  } k[] = {{"rad/s", "an angular speed: rad/s, rpm, Hz (revolutions per second), rev/s"},
           {"kg", "a mass: kg, g"},
           {"m", "a length: m, mm, um"},
           {"kg m", "an unbalance (mass times radius): kg m, g mm, g*mm"},
           {"kg m2", "a moment of inertia: kg m2, kg mm2"},
           {"N/m", "a stiffness: N/m, N/mm, kN/mm"},
           {"N m", "an angular stiffness: N m (per radian)"},
           {"N s/m", "a damping coefficient: N s/m, kg/s"},
           {"N m s", "an angular damping coefficient: N m s (per radian)"},
           {"kg/s", "a damping coefficient: kg/s, N s/m"},
           {"N", "a force or cross stiffness: N"},
           {"N s", "a cross damping coefficient: N s"},
           {"s", "a time: s, ms, min"},
           {"rad", "an angle: rad, deg"},
           {"mm/s", "a velocity: mm/s, m/s"}};
  size_t i;
  for (i = 0; i < sizeof k / sizeof k[0]; i++)
    if (strcmp(k[i].si, si_unit) == 0) return k[i].text;
  return NULL;
}

int cli_units_convert(cli_units *u, double value, const char *unit_text, const char *si_unit, double *out, char *msg,
                      size_t len) {
  ut_unit *from, *to;
  cv_converter *cv;
  const char *what = expected_examples(si_unit);
  int angular = strcmp(si_unit, "rad/s") == 0, hertz = 0;
  double v;
  from = ut_parse(u->sys, unit_text, UT_UTF8);
  if (!from) {
    snprintf(msg, len, "unknown unit '%s' (expected %s%s)", unit_text, what ? what : "a unit convertible to ",
             what ? "" : si_unit);
    return -1;
  }
  to = ut_parse(u->sys, si_unit, UT_ASCII);
  if (!to) { /* a programming error: the key's own unit must parse */
    snprintf(msg, len, "internal error: the unit '%s' does not parse", si_unit);
    ut_free(from);
    return -1;
  }
  if (!ut_are_convertible(from, to)) {
    snprintf(msg, len, "'%s' cannot be converted to %s (expected %s%s)", unit_text, si_unit,
             what ? what : "a unit of ", what ? "" : si_unit);
    ut_free(from);
    ut_free(to);
    return -1;
  }
  if (angular && !each_token(unit_text, is_angle_token, u)) {
    hertz = each_token(unit_text, is_hertz_token, u);
    if (!hertz) {
      snprintf(msg, len,
               "'%s' is ambiguous for a rotational speed (radians or revolutions per unit time?): write "
               "rad/s, rpm, Hz or rev/s (Hz counts revolutions)",
               unit_text);
      ut_free(from);
      ut_free(to);
      return -1;
    }
  }
  /* the hertz: revolutions per second, so convert to Hz, then 2 pi rad per revolution */
  cv = ut_get_converter(from, hertz ? u->hertz : to);
  if (!cv) {
    snprintf(msg, len, "cannot convert '%s' to %s", unit_text, si_unit);
    ut_free(from);
    ut_free(to);
    return -1;
  }
  v = cv_convert_double(cv, value);
  if (hertz) v *= 2.0 * acos(-1.0);
  cv_free(cv);
  ut_free(from);
  ut_free(to);
  if (!isfinite(v)) {
    snprintf(msg, len, "%g %s is outside the range of a double in %s", value, unit_text, si_unit);
    return -1;
  }
  *out = v;
  return 0;
}

int cli_units_parses(cli_units *u, const char *unit_text) {
  ut_unit *t = ut_parse(u->sys, unit_text, UT_UTF8);
  int ok = t != NULL;
  ut_free(t);
  return ok;
}

/* ---- engineering quantities ---------------------------------------------------------- */
double cli_rpm(double omega) { return omega * 60.0 / (2.0 * acos(-1.0)); }

int cli_parse_grade(const char *text, double *G) {
  const char *s = text, *rest;
  char *end;
  double g;
  while (*s == ' ' || *s == '\t') s++;
  if (*s == 'G' || *s == 'g') s++;
  while (*s == ' ' || *s == '\t') s++;
  errno = 0;
  g = strtod(s, &end);
  if (end == s || errno == ERANGE || !isfinite(g) || g <= 0.0) return -1;
  rest = end;
  while (*rest == ' ' || *rest == '\t') rest++;
  if (*rest != '\0' && strcmp(rest, "mm/s") != 0) return -1;
  *G = g;
  return 0;
}
