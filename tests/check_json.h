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

#ifdef AUTOBAL_ROTOR_H
/* The rotor parameters of a case block of check_values.json (one or two planes of two balls;
 * include check.h and autobal/rotor.h first); the ball arrays point into the caller's arrays.
 * Returns 0, or -1 (a check has failed). */
static inline int load_params(const char *blk, size_t n_planes, autobal_rotor_params *pp, double m[2][2],
                              double r[2][2], double h[2][2], double psi[2][2], double rate[2][2]) {

  const char *par = after_key(blk, "parameters"), *pl = after_key(blk, "planes");
  autobal_rotor_params p = autobal_rotor_params_default();
  const char *plane_at[2];
  size_t j;
  CHECK("JSON parameter blocks found", par && pl);
  if (!(par && pl)) return -1;
  p.input = AUTOBAL_ROTOR_HARDWARE;
  p.hw.M_k = num(par, "M_k"), p.hw.A_k = num(par, "A_k"), p.hw.m_p = num(par, "m_p");
  p.hw.A_p = num(par, "A_p"), p.hw.C_p = num(par, "C_p");
  p.hw.l_L = num(par, "l_L"), p.hw.l_R = num(par, "l_R");
  p.hw.c_Lx = num(par, "c_Lx"), p.hw.c_Ly = num(par, "c_Ly"), p.hw.c_Rx = num(par, "c_Rx"), p.hw.c_Ry = num(par, "c_Ry");
  p.hw.h_Lx = num(par, "h_Lx"), p.hw.h_Ly = num(par, "h_Ly"), p.hw.h_Rx = num(par, "h_Rx"), p.hw.h_Ry = num(par, "h_Ry");
  p.n_planes = n_planes;
  plane_at[0] = strchr(pl, '{');
  plane_at[1] = plane_at[0] ? strchr(strchr(plane_at[0], '}') + 1, '{') : NULL;
  for (j = 0; j < n_planes; j++) {
    const char *q = plane_at[j];
    autobal_rotor_plane *P = &p.plane[j];
    CHECK("plane block found", q != NULL);
    if (!q) return -1;
    P->d = num(q, "d"), P->m0 = num(q, "m0"), P->r0 = num(q, "r0"), P->psi0 = num(q, "psi0");
    P->n_balls = arr(q, "m", m[j], 2);
    CHECK("two balls per plane", P->n_balls == 2 && arr(q, "r", r[j], 2) == 2 && arr(q, "h", h[j], 2) == 2 &&
                                     arr(q, "psi", psi[j], 2) == 2 && arr(q, "rate", rate[j], 2) == 2);
    P->ball_mass = m[j], P->ball_radius = r[j], P->ball_damping = h[j], P->ball_psi = psi[j], P->ball_rate = rate[j];
  }
  *pp = p;
  return 0;
}
#endif

#endif
