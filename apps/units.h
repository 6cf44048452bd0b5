/* units.h: values with units in configuration files (UDUNITS-2), and the engineering units of
 * the summaries (not installed; the command-line layer only: the library works in SI).
 *
 * A configuration value is a number, optionally followed by a unit that UDUNITS-2 parses:
 * `omega = 3000 rpm`, `m0 = 20 g`, `unbalance = 200 g mm` (or `g*mm`, `kg m`), `d = 100 mm`,
 * `c_Lx = 1e5 N/m`.  A number without a unit is in the key's SI unit (as before units were
 * accepted).  The value is converted to the key's SI unit; a unit of another dimension is an
 * error that names the key and the unit expected.
 *
 * Rotational speeds.  UDUNITS follows SI in treating the radian as the number 1, so it converts
 * 1 Hz to 1 rad/s.  For a shaft speed an engineer means 50 Hz = 50 revolutions per second, so a
 * key in rad/s reads:
 *   - a unit that names an angle (rad, deg, rev, revolution, cycle, turn, rotation, rpm, ...)
 *     by UDUNITS (3000 rpm = 314.159... rad/s, 10 rev/s = 62.83... rad/s);
 *   - the hertz (with any SI prefix: Hz, kHz) as revolutions per second (50 Hz = 314.159 rad/s);
 *   - any other unit of dimension 1/s (1/s, 1/min, s-1) is refused as ambiguous (radians or
 *     revolutions?), with a message that says what to write instead.
 * The model documentation (docs/units.md) lists this with examples.
 */
#ifndef AUTOBAL_APPS_UNITS_H
#define AUTOBAL_APPS_UNITS_H

#include <stddef.h>

typedef struct cli_units cli_units;

/* The UDUNITS-2 unit system (the XML database of the system's UDUNITS installation, or the one
 * named by the environment variable UDUNITS2_XML_PATH).  NULL on failure, with a message in
 * err (len bytes). */
cli_units *cli_units_new(char *err, size_t len);
void cli_units_free(cli_units *u);

/* Convert `value` given in `unit_text` (UTF-8, e.g. "rpm", "g mm") to the SI unit `si_unit`
 * (e.g. "rad/s", "kg m"); the rule for rotational speeds above applies when si_unit is "rad/s".
 * Returns 0 and *out, or -1 with a message in msg (len bytes) that names the unit and says what
 * is expected (the caller prefixes the key). */
int cli_units_convert(cli_units *u, double value, const char *unit_text, const char *si_unit, double *out, char *msg,
                      size_t len);

/* Whether `unit_text` parses as a unit (UDUNITS-2, UTF-8): for tests of the archive's unit
 * strings. */
int cli_units_parses(cli_units *u, const char *unit_text);

/* Split "NUMBER [UNIT]" (leading/trailing blanks allowed) into the number's text length and the
 * unit's start: *unit points at the first non-blank character after the number ("" when none).
 * Returns the number of characters of the number (0 when the text does not start with one). */
size_t cli_units_split(const char *text, const char **unit);

/* ---- engineering quantities of the summaries ------------------------------------------- */
/* rad/s -> rpm and Hz (revolutions per minute / second). */
double cli_rpm(double omega);
/* (The ISO 21940-11 grade and permissible unbalance are library functions: autobal/study.h.) */
/* Read a grade "G2.5", "G 6.3", "2.5" or "2.5 mm/s" (a number in mm/s, optionally prefixed by
 * G): returns 0 and *G in mm/s, -1 when not a positive finite grade. */
int cli_parse_grade(const char *text, double *G);

#endif
