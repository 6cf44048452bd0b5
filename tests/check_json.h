/* check_json.h: just enough of a JSON reader for the tests that compare the C code with the
 * check values of the SymPy derivation (tools/derive/check_values.json): read a file, find a
 * key at or after a position, read a number or an array of numbers after it.  Not a parser:
 * the JSON is ours, written by derive_rotor.py with one key per ("key": value) occurrence. */
#ifndef AUTOBAL_TEST_CHECK_JSON_H
#define AUTOBAL_TEST_CHECK_JSON_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The whole file as a NUL-terminated string (malloc'ed), or NULL. */
static inline char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  char *buf;
  long n;
  if (!f) return NULL;
  if (fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
    fclose(f);
    return NULL;
  }
  buf = malloc((size_t)n + 1);
  if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
    free(buf);
    buf = NULL;
  }
  if (buf) buf[n] = '\0';
  fclose(f);
  return buf;
}

/* Position just after "key": at or after p (NULL if absent). */
static inline const char *after_key(const char *p, const char *key) {
  char pat[80];
  const char *q;
  snprintf(pat, sizeof pat, "\"%s\":", key);
  q = p ? strstr(p, pat) : NULL;
  return q ? q + strlen(pat) : NULL;
}

/* The number after "key" (NAN if absent). */
static inline double num(const char *p, const char *key) {
  const char *q = after_key(p, key);
  return q ? strtod(q, NULL) : NAN;
}

/* An array of numbers after "key": up to n values into v; returns the count. */
static inline size_t arr(const char *p, const char *key, double *v, size_t n) {
  const char *q = after_key(p, key);
  size_t k = 0;
  char *end;
  if (!q || !(q = strchr(q, '['))) return 0;
  q++;
  while (k < n) {
    double x = strtod(q, &end);
    if (end == q) break;
    v[k++] = x;
    q = end;
    while (*q == ' ' || *q == '\n' || *q == ',') q++;
    if (*q == ']') break;
  }
  return k;
}

#endif
