/* test_rotor.c: the rotor - housing - ball autobalancer model (docs/rotor.md).
 *
 * Every expected value has a reason independent of src/models/rotor/rotor.c:
 *  - the stated numbers of docs/rotor.md (lumped coefficients, natural frequencies at rest,
 *    balanced angles), not copied from the program;
 *  - a direct solve of the full (4+N)x(4+N) mass-matrix system assembled here from
 *    (3.2)/(3.5)-(3.8) and (3.4), with the support stiffness built from the potential
 *    energy of the individual supports (not from the lumped formulas), and the
 *    reduced 4x4 system of "Solving for the accelerations" assembled here and solved
 *    by GSL's Cholesky (the library solves one plane in closed form);
 *  - the mass matrix at the paper model's limit sum m (1/M + d^2/A) -> 1, where
 *    I + g C has the eigenvalue 1 - g m at every ball angle;
 *  - energy: the kinetic energy of the model (documented in rotor.h) gives
 *    dE/dt = -dissipation + power of the unbalance drive; with no damping and no
 *    unbalance E is conserved along a transient;
 *  - two implementations (fixed / rotating frame), symmetries (rotation of an
 *    isotropic system, mirror z -> -z, splitting a plane in two), the linear limit
 *    without balls against the complex 4x4 steady harmonic response, and the
 *    equilibrium condition of the balls in a subcritical run.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_complex.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_sort_vector.h>

#include "autobal.h"
#include "check.h"
#include "fastmath.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define MAXDIM 64

/* ---- small helpers -------------------------------------------------------- */

static unsigned long long rng_state = 0x9E3779B97F4A7C15ull;
static double urand(double lo, double hi) { /* xorshift64*, deterministic */
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return lo + (hi - lo) * (double)((rng_state * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

static double wrap(double a) { return atan2(sin(a), cos(a)); }

/* integrate with the library's transient driver (rk8pd; tested on its own in test_transient) */
#include "rotor_integrate.h"

/* stiffness / damping of the supports from their potential energy
 * 1/2 c (displacement at the support)^2, a point at p moving by (x + p beta, y - p alpha) */
static void supports_matrix(double l_L, double l_R, double Lx, double Ly, double Rx, double Ry,
                            double K[4][4]) {
  const double eLx[4] = {1, 0, 0, -l_L}, eLy[4] = {0, 1, l_L, 0};
  const double eRx[4] = {1, 0, 0, l_R}, eRy[4] = {0, 1, -l_R, 0};
  int i, k;
  for (i = 0; i < 4; i++)
    for (k = 0; k < 4; k++)
      K[i][k] = Lx * eLx[i] * eLx[k] + Ly * eLy[i] * eLy[k] + Rx * eRx[i] * eRx[k] + Ry * eRy[i] * eRy[k];
}

/* ball data of a handle, flattened */
typedef struct model_view {
  size_t np, N;
  double d[2], s0[2], psi0[2], mfull[2];
  size_t plane_of[MAXDIM];
  double m[MAXDIM], r[MAXDIM], h[MAXDIM];
} model_view;

static void view(const autobal_rotor *R, model_view *v) {
  const autobal_rotor_params *p = autobal_rotor_get_params(R);
  size_t j, i, k = 0;
  v->np = p->n_planes;
  for (j = 0; j < p->n_planes; j++) {
    v->d[j] = p->plane[j].d;
    v->s0[j] = p->plane[j].m0 * p->plane[j].r0;
    v->psi0[j] = p->plane[j].psi0;
    v->mfull[j] = p->inertia == AUTOBAL_ROTOR_INERTIA_FULL ? p->plane[j].m0 : 0.0;
    for (i = 0; i < p->plane[j].n_balls; i++, k++) {
      v->plane_of[k] = j;
      v->m[k] = p->plane[j].ball_mass[i];
      v->r[k] = p->plane[j].ball_radius[i];
      v->h[k] = p->plane[j].ball_damping[i];
      if (p->inertia == AUTOBAL_ROTOR_INERTIA_FULL) v->mfull[j] += v->m[k];
    }
  }
  v->N = k;
}

/* rotor matrices D, K, H, G assembled from the hardware (independent of the lumped formulas) */
static void rotor_matrices(const autobal_rotor_params *p, double Dm[4], double K[4][4],
                           double H[4][4], double G[4][4]) {
  const autobal_rotor_hardware *hw = &p->hw;
  int i, k;
  Dm[0] = Dm[1] = hw->M_k + hw->m_p;
  Dm[2] = Dm[3] = hw->A_k + hw->A_p;
  supports_matrix(hw->l_L, hw->l_R, hw->c_Lx, hw->c_Ly, hw->c_Rx, hw->c_Ry, K);
  supports_matrix(hw->l_L, hw->l_R, hw->h_Lx, hw->h_Ly, hw->h_Rx, hw->h_Ry, H);
  for (i = 0; i < 4; i++)
    for (k = 0; k < 4; k++) G[i][k] = 0.0;
  G[2][3] = hw->C_p * p->omega;  /* + C omega beta' in the alpha equation (3.2) */
  G[3][2] = -hw->C_p * p->omega; /* - C omega alpha' in the beta equation */
}

/* Direct solve of the full (4+N) mass-matrix system of (3.2)/(3.5)-(3.8) and (3.4)
 * at a fixed-frame state; writes q''[4] and phi''[N]. */
static int direct_solve(const autobal_rotor *R, double t, const double *y, double *qdd,
                        double *phidd) {
  const autobal_rotor_params *p = autobal_rotor_get_params(R);
  model_view v;
  double Dm[4], K[4][4], H[4][4], G[4][4];
  size_t n, i, k, j;
  gsl_matrix *A;
  gsl_vector *b, *x;
  gsl_permutation *perm;
  int sgn, st;
  const double w = p->omega;
  view(R, &v);
  rotor_matrices(p, Dm, K, H, G);
  n = 4 + v.N;
  A = gsl_matrix_calloc(n, n);
  b = gsl_vector_calloc(n);
  x = gsl_vector_alloc(n);
  perm = gsl_permutation_alloc(n);
  for (i = 0; i < 4; i++) {
    double f = 0.0;
    gsl_matrix_set(A, i, i, Dm[i]);
    for (k = 0; k < 4; k++) f += (H[i][k] + G[i][k]) * y[4 + k] + K[i][k] * y[k];
    gsl_vector_set(b, i, -f);
  }
  for (j = 0; j < v.np; j++) {
    const double d = v.d[j];
    const double eu[4] = {1, 0, 0, d}, ev[4] = {0, 1, -d, 0};
    const double phi0 = w * t + v.psi0[j];
    /* s_u'' eu + s_v'' ev enters the rotor rows; the unbalance: s'' = -s0 w^2 (cos, sin) */
    for (i = 0; i < 4; i++) {
      gsl_vector_set(b, i, gsl_vector_get(b, i) + v.s0[j] * w * w * (cos(phi0) * eu[i] + sin(phi0) * ev[i]));
      for (k = 0; k < 4; k++) /* FULL inertia: m |v_D|^2 / 2 of balls and unbalance */
        gsl_matrix_set(A, i, k, gsl_matrix_get(A, i, k) + v.mfull[j] * (eu[i] * eu[k] + ev[i] * ev[k]));
    }
  }
  for (k = 0; k < v.N; k++) {
    const size_t jj = v.plane_of[k];
    const double d = v.d[jj];
    const double eu[4] = {1, 0, 0, d}, ev[4] = {0, 1, -d, 0};
    const double phi = y[8 + k], phid = y[8 + v.N + k];
    const double m = v.m[k], r = v.r[k];
    for (i = 0; i < 4; i++) {
      /* s_u'' = sum m r (-sin phi phi'' - cos phi phi'^2), s_v'' = sum m r (cos phi phi'' - sin phi phi'^2) */
      gsl_matrix_set(A, i, 4 + k, m * r * (-sin(phi) * eu[i] + cos(phi) * ev[i]));
      gsl_vector_set(b, i, gsl_vector_get(b, i) + m * r * phid * phid * (cos(phi) * eu[i] + sin(phi) * ev[i]));
      /* (3.4): m r [ r phi'' - u_D'' sin phi + v_D'' cos phi ] + h r^2 (phi' - w) = 0 */
      gsl_matrix_set(A, 4 + k, i, m * r * (-sin(phi) * eu[i] + cos(phi) * ev[i]));
    }
    gsl_matrix_set(A, 4 + k, 4 + k, m * r * r);
    gsl_vector_set(b, 4 + k, -v.h[k] * r * r * (phid - w));
  }
  st = gsl_linalg_LU_decomp(A, perm, &sgn);
  if (st == 0) st = gsl_linalg_LU_solve(A, perm, b, x);
  if (st == 0) {
    for (i = 0; i < 4; i++) qdd[i] = gsl_vector_get(x, i);
    for (k = 0; k < v.N; k++) phidd[k] = gsl_vector_get(x, 4 + k);
  }
  gsl_matrix_free(A);
  gsl_vector_free(b);
  gsl_vector_free(x);
  gsl_permutation_free(perm);
  return st;
}

/* Energy of the model: T (rotor.h) + V, without the prescribed unbalance. */
static double energy(const autobal_rotor *R, const double *y) {
  const autobal_rotor_params *p = autobal_rotor_get_params(R);
  model_view v;
  double Dm[4], K[4][4], H[4][4], G[4][4], E = 0.0;
  size_t i, k, j;
  view(R, &v);
  rotor_matrices(p, Dm, K, H, G);
  for (i = 0; i < 4; i++) {
    E += 0.5 * Dm[i] * y[4 + i] * y[4 + i];
    for (k = 0; k < 4; k++) E += 0.5 * y[i] * K[i][k] * y[k];
  }
  for (j = 0; j < v.np; j++) {
    const double uDd = y[4] + v.d[j] * y[7], vDd = y[5] - v.d[j] * y[6];
    E += 0.5 * v.mfull[j] * (uDd * uDd + vDd * vDd);
  }
  for (k = 0; k < v.N; k++) {
    const double d = v.d[v.plane_of[k]];
    const double phi = y[8 + k], phid = y[8 + v.N + k];
    const double g[4] = {-sin(phi), cos(phi), -d * cos(phi), -d * sin(phi)};
    double gq = 0.0;
    for (i = 0; i < 4; i++) gq += g[i] * y[4 + i];
    E += 0.5 * v.m[k] * v.r[k] * v.r[k] * phid * phid + v.m[k] * v.r[k] * phid * gq;
  }
  if (p->axial) {
    const size_t iz = 8 + 2 * v.N;
    E += 0.5 * (p->hw.M_k + p->hw.m_p) * y[iz + 1] * y[iz + 1] + 0.5 * p->hw.c_Lz * y[iz] * y[iz];
  }
  return E;
}

/* dE/dt along the flow, by the chain rule with the analytic gradient of E */
static double energy_rate(const autobal_rotor *R, const double *y, const double *f) {
  const autobal_rotor_params *p = autobal_rotor_get_params(R);
  model_view v;
  double Dm[4], K[4][4], H[4][4], G[4][4], dEdqd[4], rate = 0.0;
  size_t i, k, j;
  view(R, &v);
  rotor_matrices(p, Dm, K, H, G);
  for (i = 0; i < 4; i++) {
    double kq = 0.0;
    for (k = 0; k < 4; k++) kq += K[i][k] * y[k];
    rate += kq * y[4 + i]; /* dE/dq . q' */
    dEdqd[i] = Dm[i] * y[4 + i];
  }
  for (j = 0; j < v.np; j++) {
    const double d = v.d[j];
    const double uDd = y[4] + d * y[7], vDd = y[5] - d * y[6];
    dEdqd[0] += v.mfull[j] * uDd;
    dEdqd[3] += v.mfull[j] * d * uDd;
    dEdqd[1] += v.mfull[j] * vDd;
    dEdqd[2] -= v.mfull[j] * d * vDd;
  }
  for (k = 0; k < v.N; k++) {
    const double d = v.d[v.plane_of[k]];
    const double phi = y[8 + k], phid = y[8 + v.N + k];
    const double mr = v.m[k] * v.r[k];
    const double g[4] = {-sin(phi), cos(phi), -d * cos(phi), -d * sin(phi)};
    const double gp[4] = {-cos(phi), -sin(phi), d * sin(phi), -d * cos(phi)};
    double gq = 0.0, gpq = 0.0;
    for (i = 0; i < 4; i++) {
      gq += g[i] * y[4 + i];
      gpq += gp[i] * y[4 + i];
      dEdqd[i] += mr * phid * g[i];
    }
    rate += mr * phid * gpq * f[8 + k];                           /* dE/dphi phi' */
    rate += (v.m[k] * v.r[k] * v.r[k] * phid + mr * gq) * f[8 + v.N + k]; /* dE/dphi' phi'' */
  }
  for (i = 0; i < 4; i++) rate += dEdqd[i] * f[4 + i];
  if (p->axial) {
    const size_t iz = 8 + 2 * v.N;
    rate += (p->hw.M_k + p->hw.m_p) * y[iz + 1] * f[iz + 1] + p->hw.c_Lz * y[iz] * f[iz];
  }
  return rate;
}

/* -dissipation + power of the unbalance drive at (t, y) (fixed frame) */
static double power_balance(const autobal_rotor *R, double t, const double *y, double *scale) {
  const autobal_rotor_params *p = autobal_rotor_get_params(R);
  model_view v;
  double Dm[4], K[4][4], H[4][4], G[4][4], P = 0.0, S = 0.0;
  size_t i, k, j;
  const double w = p->omega;
  view(R, &v);
  rotor_matrices(p, Dm, K, H, G);
  for (i = 0; i < 4; i++)
    for (k = 0; k < 4; k++) {
      P -= y[4 + i] * (H[i][k] + G[i][k]) * y[4 + k];
      S += fabs(y[4 + i] * (H[i][k] + G[i][k]) * y[4 + k]);
    }
  for (k = 0; k < v.N; k++) {
    const double phid = y[8 + v.N + k];
    const double term = v.h[k] * v.r[k] * v.r[k] * (phid - w) * phid;
    P -= term;
    S += fabs(term);
  }
  for (j = 0; j < v.np; j++) {
    const double d = v.d[j], phi0 = w * t + v.psi0[j];
    /* generalized force of the unbalance on q: s0 w^2 (cos phi0 eu + sin phi0 ev) */
    const double F[4] = {cos(phi0), sin(phi0), -d * sin(phi0), d * cos(phi0)};
    for (i = 0; i < 4; i++) {
      P += v.s0[j] * w * w * F[i] * y[4 + i];
      S += fabs(v.s0[j] * w * w * F[i] * y[4 + i]);
    }
  }
  if (p->axial) {
    const size_t iz = 8 + 2 * v.N;
    P -= p->hw.h_Lz * y[iz + 1] * y[iz + 1];
    S += fabs(p->hw.h_Lz * y[iz + 1] * y[iz + 1]);
  }
  if (scale) *scale = S;
  return P;
}

static void random_state(const autobal_rotor *R, double *y) {
  const size_t N = autobal_rotor_n_balls_total(R), dim = autobal_rotor_dim(R);
  const double w = autobal_rotor_omega(R);
  size_t k;
  y[0] = urand(-1e-3, 1e-3);
  y[1] = urand(-1e-3, 1e-3);
  y[2] = urand(-5e-3, 5e-3);
  y[3] = urand(-5e-3, 5e-3);
  y[4] = urand(-0.3, 0.3);
  y[5] = urand(-0.3, 0.3);
  y[6] = urand(-2, 2);
  y[7] = urand(-2, 2);
  for (k = 0; k < N; k++) {
    y[8 + k] = urand(-20, 20);
    y[8 + N + k] = w + urand(-80, 80);
  }
  if (dim > 8 + 2 * N) {
    y[8 + 2 * N] = urand(-1e-3, 1e-3);
    y[9 + 2 * N] = urand(-0.1, 0.1);
  }
}

/* ---- parameter sets ----------------------------------------------------------- */

/* two planes, anisotropic supports, unequal balls, axial motion */
static const double tp_m1[2] = {0.05, 0.04}, tp_r1[2] = {0.1, 0.11}, tp_h1[2] = {0.1, 0.3};
static const double tp_psi1[2] = {1.0, 2.5}, tp_rate1[2] = {0.0, 3.0};
static const double tp_m2[3] = {0.02, 0.03, 0.025}, tp_r2[3] = {0.08, 0.08, 0.09};
static const double tp_h2[3] = {0.05, 0.05, 0.2}, tp_psi2[3] = {-1.0, 0.3, 2.0};
static const double tp_rate2[3] = {1.0, -2.0, 0.0};

static autobal_rotor_params two_plane_params(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.hw.c_Ly = 0.8e5;
  p.hw.c_Ry = 1.9e5;
  p.hw.h_Ly = 60.0;
  p.hw.h_Ry = 170.0;
  p.axial = 1;
  p.z0 = 1e-4;
  p.zd0 = -0.01;
  p.q0[0] = 1e-4;
  p.q0[3] = -2e-4;
  p.qd0[2] = 0.05;
  p.n_planes = 2;
  p.plane[0].d = 0.10;
  p.plane[0].m0 = 0.02;
  p.plane[0].r0 = 0.1;
  p.plane[0].psi0 = 0.0;
  p.plane[0].n_balls = 2;
  p.plane[0].ball_mass = tp_m1;
  p.plane[0].ball_radius = tp_r1;
  p.plane[0].ball_damping = tp_h1;
  p.plane[0].ball_psi = tp_psi1;
  p.plane[0].ball_rate = tp_rate1;
  p.plane[1].d = -0.12;
  p.plane[1].m0 = 0.01;
  p.plane[1].r0 = 0.09;
  p.plane[1].psi0 = 0.7;
  p.plane[1].n_balls = 3;
  p.plane[1].ball_mass = tp_m2;
  p.plane[1].ball_radius = tp_r2;
  p.plane[1].ball_damping = tp_h2;
  p.plane[1].ball_psi = tp_psi2;
  p.plane[1].ball_rate = tp_rate2;
  return p;
}


/* ---- the example configs in data/: a minimal INI reader (the app uses inih) ---- */

typedef struct ini_plane_arrays {
  double v[5][16]; /* ball_mass, ball_radius, ball_damping, ball_psi, ball_rate */
  size_t n[5];
} ini_plane_arrays;

static size_t parse_list(const char *s, double *out, size_t cap) {
  size_t n = 0;
  char *end;
  while (*s && n < cap) {
    const double v = strtod(s, &end);
    if (end == s) return (size_t)-1;
    out[n++] = v;
    s = end;
    while (*s == ' ' || *s == '\t') s++;
    if (*s == ',') s++;
    else if (*s) return (size_t)-1;
  }
  return n;
}

/* one key of a [planeN] section: 1 consumed, 0 unknown, -1 bad value */
static int plane_key(size_t j, const char *key, const char *val, autobal_rotor_params *p,
                     ini_plane_arrays pa[2]) {
  static const char *const ball_keys[5] = {"ball_mass", "ball_radius", "ball_damping", "ball_psi", "ball_rate"};
  double *field = NULL;
  char *e;
  size_t i;
  if (strcmp(key, "d") == 0) field = &p->plane[j].d;
  if (strcmp(key, "m0") == 0) field = &p->plane[j].m0;
  if (strcmp(key, "r0") == 0) field = &p->plane[j].r0;
  if (strcmp(key, "psi0") == 0) field = &p->plane[j].psi0;
  if (field) {
    *field = strtod(val, &e);
    return (e == val || *e) ? -1 : 1;
  }
  for (i = 0; i < 5; i++)
    if (strcmp(key, ball_keys[i]) == 0) {
      pa[j].n[i] = parse_list(val, pa[j].v[i], 16);
      return pa[j].n[i] == (size_t)-1 ? -1 : 1;
    }
  return 0;
}

/* Fill p from an INI file in the documented format; returns 0, or -1 with why in bad. */
static int load_rotor_ini(const char *path, autobal_rotor_params *p, ini_plane_arrays pa[2], char *bad,
                          size_t badlen) {
  static const char *const ball_keys[5] = {"ball_mass", "ball_radius", "ball_damping", "ball_psi", "ball_rate"};
  char line[512], section[64] = "";
  FILE *f = fopen(path, "r");
  size_t j, i;
  memset(p, 0, sizeof *p);
  memset(pa, 0, 2 * sizeof *pa);
  if (f == NULL) {
    snprintf(bad, badlen, "cannot open %.200s", path);
    return -1;
  }
  while (fgets(line, sizeof line, f)) {
    char *c = strpbrk(line, ";#"), *key, *val, *eq, *e;
    if (c) *c = '\0';
    key = line;
    while (*key == ' ' || *key == '\t') key++;
    e = key + strlen(key);
    while (e > key && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\n' || e[-1] == '\r')) *--e = '\0';
    if (*key == '\0') continue;
    if (*key == '[') {
      snprintf(section, sizeof section, "%.*s", (int)(strlen(key) - 2), key + 1);
      continue;
    }
    eq = strchr(key, '=');
    if (eq == NULL) {
      snprintf(bad, badlen, "no '=' in line \"%.100s\"", key);
      fclose(f);
      return -1;
    }
    *eq = '\0';
    val = eq + 1;
    while (*val == ' ') val++;
    e = key + strlen(key);
    while (e > key && e[-1] == ' ') *--e = '\0';
#define KEY(sec, name, field)                                        \
  if (strcmp(section, sec) == 0 && strcmp(key, name) == 0) {         \
    field = strtod(val, &e);                                         \
    if (e == val || *e) goto bad_value;                              \
    continue;                                                        \
  }
    KEY("rotor", "M_k", p->hw.M_k)
    KEY("rotor", "A_k", p->hw.A_k)
    KEY("rotor", "m_p", p->hw.m_p)
    KEY("rotor", "A_p", p->hw.A_p)
    KEY("rotor", "C_p", p->hw.C_p)
    KEY("rotor", "omega", p->omega)
    KEY("supports", "l_L", p->hw.l_L)
    KEY("supports", "l_R", p->hw.l_R)
    KEY("supports", "c_Lx", p->hw.c_Lx)
    KEY("supports", "c_Ly", p->hw.c_Ly)
    KEY("supports", "c_Lz", p->hw.c_Lz)
    KEY("supports", "c_Rx", p->hw.c_Rx)
    KEY("supports", "c_Ry", p->hw.c_Ry)
    KEY("supports", "h_Lx", p->hw.h_Lx)
    KEY("supports", "h_Ly", p->hw.h_Ly)
    KEY("supports", "h_Lz", p->hw.h_Lz)
    KEY("supports", "h_Rx", p->hw.h_Rx)
    KEY("supports", "h_Ry", p->hw.h_Ry)
    if (strcmp(section, "plane1") == 0 || strcmp(section, "plane2") == 0) {
      const int rc = plane_key(section[5] == '1' ? 0 : 1, key, val, p, pa);
      if (rc < 0) goto bad_value;
      if (rc > 0) continue;
    }
#undef KEY
    if (strcmp(section, "rotor") == 0 && strcmp(key, "inertia") == 0) {
      if (strcmp(val, "paper") == 0) p->inertia = AUTOBAL_ROTOR_INERTIA_PAPER;
      else if (strcmp(val, "full") == 0) p->inertia = AUTOBAL_ROTOR_INERTIA_FULL;
      else goto bad_value;
      continue;
    }
    if (strcmp(section, "rotor") == 0 && strcmp(key, "axial") == 0) {
      p->axial = atoi(val);
      continue;
    }
    if (strcmp(section, "transient") == 0 &&
        (strcmp(key, "t_end") == 0 || strcmp(key, "dt_out") == 0 || strcmp(key, "rtol") == 0 ||
         strcmp(key, "atol") == 0 || strcmp(key, "balance_tol") == 0 || strcmp(key, "balance_dwell") == 0 ||
         strcmp(key, "revs_out") == 0 || strcmp(key, "balance_revs") == 0)) {
      const double v = strtod(val, &e);
      if (e == val || *e || !(v > 0.0)) goto bad_value;
      continue;
    }
    if (strcmp(section, "transient") == 0 && (strcmp(key, "stepper") == 0 || strcmp(key, "frame") == 0))
      continue;
    snprintf(bad, badlen, "unknown key [%.30s] %.60s", section, key);
    fclose(f);
    return -1;
  bad_value:
    snprintf(bad, badlen, "bad value [%.30s] %.60s = %.100s", section, key, val);
    fclose(f);
    return -1;
  }
  fclose(f);
  p->input = AUTOBAL_ROTOR_HARDWARE;
  p->n_planes = pa[1].n[0] > 0 || p->plane[1].m0 > 0 ? 2 : 1;
  for (j = 0; j < p->n_planes; j++) {
    p->plane[j].n_balls = pa[j].n[0];
    for (i = 1; i < 5; i++)
      if (pa[j].n[i] != pa[j].n[0] && !(i == 4 && pa[j].n[i] == 0)) {
        snprintf(bad, badlen, "plane%zu: %s has %zu entries, ball_mass %zu", j + 1, ball_keys[i], pa[j].n[i], pa[j].n[0]);
        return -1;
      }
    p->plane[j].ball_mass = pa[j].v[0];
    p->plane[j].ball_radius = pa[j].v[1];
    p->plane[j].ball_damping = pa[j].v[2];
    p->plane[j].ball_psi = pa[j].v[3];
    p->plane[j].ball_rate = pa[j].n[4] ? pa[j].v[4] : NULL;
  }
  return 0;
}

static void test_config_files(void) {
  static const char *const files[5] = {"rotor_default.ini", "rotor_two_planes.ini", "rotor_four_balls.ini",
                                       "rotor_anisotropic.ini", "rotor_subcritical.ini"};
  autobal_rotor_params p, d = autobal_rotor_params_default();
  ini_plane_arrays pa[2];
  char path[1024], bad[256];
  autobal_error err;
  size_t i, k;
  printf("-- example configs in data/ (format of rotor_default.ini)\n");
  for (k = 0; k < 5; k++) {
    snprintf(path, sizeof path, "%s/%s", AUTOBAL_TEST_DATA_DIR, files[k]);
    bad[0] = '\0';
    CHECK(files[k], load_rotor_ini(path, &p, pa, bad, sizeof bad) == 0);
    if (bad[0]) printf("     %s\n", bad);
    CHECK_STATUS("   valid parameters, no warning", autobal_rotor_params_check(&p, &err), AUTOBAL_SUCCESS);
    if (err.status) printf("     %s\n", err.message);
    if (k == 0) {
      int same = memcmp(&p.hw, &d.hw, sizeof p.hw) == 0 && p.omega == d.omega && p.n_planes == 1 &&
                 p.axial == d.axial && p.inertia == d.inertia;
      same = same && p.plane[0].d == d.plane[0].d && p.plane[0].m0 == d.plane[0].m0 &&
             p.plane[0].r0 == d.plane[0].r0 && p.plane[0].psi0 == d.plane[0].psi0 &&
             p.plane[0].n_balls == d.plane[0].n_balls;
      for (i = 0; same && i < d.plane[0].n_balls; i++)
        same = p.plane[0].ball_mass[i] == d.plane[0].ball_mass[i] &&
               p.plane[0].ball_radius[i] == d.plane[0].ball_radius[i] &&
               p.plane[0].ball_damping[i] == d.plane[0].ball_damping[i] &&
               p.plane[0].ball_psi[i] == d.plane[0].ball_psi[i] &&
               (p.plane[0].ball_rate ? p.plane[0].ball_rate[i] : 0.0) == d.plane[0].ball_rate[i];
      CHECK("   rotor_default.ini = autobal_rotor_params_default()", same);
    }
    if (k == 1) CHECK("   two planes", p.n_planes == 2 && p.plane[1].n_balls == 2);
    if (k == 2) CHECK("   four balls of different masses", p.plane[0].n_balls == 4 && p.plane[0].ball_mass[0] != p.plane[0].ball_mass[3]);
    if (k == 3) CHECK("   anisotropic supports", p.hw.c_Lx != p.hw.c_Ly);
    if (k == 4) CHECK("   subcritical: omega below the first natural frequency", p.omega < 157.0);
    if (k >= 1 && k <= 3) {
      /* supercritical examples: the run ends balanced (3.14): s_j = 0 in every plane,
       * the rotor at rest; for two identical balls at pi -/+ arccos(m0 r0 / 2 m r) */
      autobal_rotor *R = autobal_rotor_alloc(&p, NULL);
      double y[MAXDIM], out[128], mon;
      if (R == NULL) continue;
      autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, autobal_rotor_dim(R));
      CHECK("   30 s integrated", integrate(autobal_rotor_rhs, R, 0.0, 30.0, y, 1e-10, 1e-12) == 0);
      mon = autobal_rotor_balance_monitor(R, AUTOBAL_ROTOR_FIXED, 30.0, y);
      autobal_rotor_outputs(R, AUTOBAL_ROTOR_FIXED, 30.0, y, out, autobal_rotor_output_count(R));
      CHECK_CLOSE("   balanced at t = 30 s: max_j |s_j| / m_j0 r_j0", mon, 0.0, 0, 1e-6);
      CHECK_CLOSE("   rotor at rest: amplitude at both supports (m)", fmax(out[1], out[2]), 0.0, 0, 1e-10);
      if (k == 3) {
        const double pb = M_PI - acos(0.002 / 0.01);
        CHECK_CLOSE("   anisotropic: |psi| = pi - arccos(m0 r0 / 2 m r)", fabs(out[13]), pb, 0, 1e-6);
        CHECK_CLOSE("   anisotropic: balls on opposite sides", out[13] + out[19], 0.0, 0, 2e-6);
      }
      autobal_rotor_free(R);
    }
  }
}

/* ---- tests ------------------------------------------------------------------------ */

static void test_defaults(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_error err;
  autobal_rotor *R = autobal_rotor_alloc(&p, &err);
  const autobal_rotor_lumped *L;
  printf("-- defaults and lumped coefficients (spec: default example)\n");
  CHECK("default params alloc", R != NULL);
  if (R == NULL) return;
  CHECK_STATUS("default params: no warning", err.status, AUTOBAL_SUCCESS);
  L = autobal_rotor_get_lumped(R);
  /* values stated in the spec */
  CHECK_CLOSE("M = M_k + m_p", L->M, 10.0, 1e-15, 0);
  CHECK_CLOSE("A = A_k + A_p", L->A, 0.16, 1e-15, 0);
  CHECK_CLOSE("C = C_p", L->C, 0.03, 1e-15, 0);
  CHECK_CLOSE("c_x (spec 2.5e5)", L->c_x, 2.5e5, 1e-15, 0);
  CHECK_CLOSE("c_y (spec 2.5e5)", L->c_y, 2.5e5, 1e-15, 0);
  CHECK_CLOSE("c_alpha (spec 7375)", L->c_alpha, 7375.0, 1e-14, 0);
  CHECK_CLOSE("c_beta (spec 7375)", L->c_beta, 7375.0, 1e-14, 0);
  CHECK_CLOSE("c_xbeta (spec -2500)", L->c_xbeta, -2500.0, 1e-13, 0);
  CHECK_CLOSE("c_yalpha (spec -2500)", L->c_yalpha, -2500.0, 1e-13, 0);
  /* by hand from (2.9)/(2.11) with the corrected c_z = c_Lz */
  CHECK_CLOSE("c_z = c_Lz (typo fix)", L->c_z, 2.0e5, 1e-15, 0);
  CHECK_CLOSE("h_z = h_Lz", L->h_z, 200.0, 1e-15, 0);
  CHECK_CLOSE("h_x = 100 + 150", L->h_x, 250.0, 1e-15, 0);
  CHECK_CLOSE("h_alpha = 100*0.2^2 + 150*0.15^2", L->h_alpha, 7.375, 1e-14, 0);
  CHECK_CLOSE("h_xbeta = 100*0.2 - 150*0.15", L->h_xbeta, -2.5, 1e-13, 0);
  CHECK("dim = 8 + 2*2", autobal_rotor_dim(R) == 12);
  CHECK("two balls, one plane", autobal_rotor_n_balls_total(R) == 2 && autobal_rotor_n_planes(R) == 1);
  CHECK("ball index", autobal_rotor_ball_index(R, 0, 1) == 1 && autobal_rotor_ball_index(R, 0, 2) == (size_t)-1);
  CHECK_CLOSE("omega", autobal_rotor_omega(R), 500.0, 0, 0);
  {
    double y[12];
    CHECK_STATUS("initial state", autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.2, y, 12), AUTOBAL_SUCCESS);
    CHECK_CLOSE("initial phi_1 = omega t0 + 1.0", y[8], 500.0 * 0.2 + 1.0, 1e-15, 0);
    CHECK_CLOSE("initial phi_2' = omega", y[11], 500.0, 1e-15, 0);
    CHECK("rotor at rest at the origin", y[0] == 0 && y[3] == 0 && y[4] == 0 && y[7] == 0);
  }
  /* the lumped block of the default params agrees with lumped_from_hardware */
  {
    autobal_rotor_lumped L2;
    CHECK_STATUS("lumped_from_hardware", autobal_rotor_lumped_from_hardware(&p.hw, &L2, &err), AUTOBAL_SUCCESS);
    CHECK("default lumped block consistent", memcmp(&L2, &p.lumped, sizeof L2) == 0);
  }
  autobal_rotor_free(R);
}

static void test_natural_frequencies(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  const autobal_rotor_lumped *L;
  autobal_rotor *R;
  double want[4] = {157.5323, 157.5323, 215.1217, 215.1217};
  size_t i, k;
  printf("-- natural frequencies at rest (spec: 157.5323 and 215.1217 rad/s, each double)\n");
  R = autobal_rotor_alloc(&p, NULL);
  if (R == NULL) return;
  L = autobal_rotor_get_lumped(R);
  {
    /* generalized eigenproblem K v = w^2 diag(M,M,A,A) v with the lumped stiffness (3.2) */
    gsl_matrix *K = gsl_matrix_calloc(4, 4), *Dm = gsl_matrix_calloc(4, 4);
    gsl_vector *ev = gsl_vector_alloc(4);
    gsl_eigen_gensymm_workspace *w = gsl_eigen_gensymm_alloc(4);
    gsl_matrix_set(K, 0, 0, L->c_x);
    gsl_matrix_set(K, 0, 3, -L->c_xbeta);
    gsl_matrix_set(K, 3, 0, -L->c_xbeta);
    gsl_matrix_set(K, 3, 3, L->c_beta);
    gsl_matrix_set(K, 1, 1, L->c_y);
    gsl_matrix_set(K, 1, 2, L->c_yalpha);
    gsl_matrix_set(K, 2, 1, L->c_yalpha);
    gsl_matrix_set(K, 2, 2, L->c_alpha);
    gsl_matrix_set(Dm, 0, 0, L->M);
    gsl_matrix_set(Dm, 1, 1, L->M);
    gsl_matrix_set(Dm, 2, 2, L->A);
    gsl_matrix_set(Dm, 3, 3, L->A);
    CHECK("gensymm", gsl_eigen_gensymm(K, Dm, ev, w) == 0);
    gsl_sort_vector(ev);
    for (i = 0; i < 4; i++) CHECK_CLOSE("natural frequency (lumped K, diag(M,M,A,A))", sqrt(gsl_vector_get(ev, i)), want[i], 0, 1e-4);
    gsl_eigen_gensymm_free(w);
    gsl_vector_free(ev);
    gsl_matrix_free(K);
    gsl_matrix_free(Dm);
  }
  autobal_rotor_free(R);
  {
    /* the right-hand side itself: no spin, no balls, no unbalance, no damping -> its
     * (exact, the system is linear) Jacobian has eigenvalues +-i w_k */
    autobal_rotor_params q = autobal_rotor_params_default();
    double y0[8] = {0}, fp[8], fm[8], im[8];
    gsl_matrix *J = gsl_matrix_alloc(8, 8);
    gsl_vector_complex *ev = gsl_vector_complex_alloc(8);
    gsl_eigen_nonsymm_workspace *w = gsl_eigen_nonsymm_alloc(8);
    double maxre = 0.0;
    q.omega = 0.0;
    q.plane[0].n_balls = 0;
    q.plane[0].m0 = 0.0;
    q.hw.h_Lx = q.hw.h_Ly = q.hw.h_Rx = q.hw.h_Ry = 0.0;
    R = autobal_rotor_alloc(&q, NULL);
    CHECK("no-ball model", R != NULL && autobal_rotor_dim(R) == 8);
    if (R == NULL) return;
    for (k = 0; k < 8; k++) {
      y0[k] = 1e-3;
      autobal_rotor_rhs(0.0, y0, fp, R);
      y0[k] = -1e-3;
      autobal_rotor_rhs(0.0, y0, fm, R);
      y0[k] = 0.0;
      for (i = 0; i < 8; i++) gsl_matrix_set(J, i, k, (fp[i] - fm[i]) / 2e-3);
    }
    CHECK("nonsymm eig", gsl_eigen_nonsymm(J, ev, w) == 0);
    for (i = 0; i < 8; i++) {
      gsl_complex z = gsl_vector_complex_get(ev, i);
      im[i] = GSL_IMAG(z);
      if (fabs(GSL_REAL(z)) > maxre) maxre = fabs(GSL_REAL(z));
    }
    gsl_sort(im, 1, 8);
    for (i = 0; i < 4; i++) CHECK_CLOSE("rhs Jacobian eigenvalue Im (positive half)", im[4 + i], want[i], 0, 1e-4);
    CHECK_CLOSE("rhs Jacobian eigenvalues are imaginary", maxre, 0.0, 0, 1e-6);
    gsl_eigen_nonsymm_free(w);
    gsl_vector_complex_free(ev);
    gsl_matrix_free(J);
    autobal_rotor_free(R);
  }
}

static double g_max_direct = 0.0;

static void check_direct(const char *label, autobal_rotor_params *p, int nstates) {
  autobal_rotor *R = autobal_rotor_alloc(p, NULL);
  double y[MAXDIM], f[MAXDIM], qdd[4], phidd[MAXDIM], worst = 0.0, zworst = 0.0;
  int s, ok = 1;
  size_t N, k, dim;
  CHECK(label, R != NULL);
  if (R == NULL) return;
  N = autobal_rotor_n_balls_total(R);
  dim = autobal_rotor_dim(R);
  for (s = 0; s < nstates; s++) {
    const double t = urand(0, 3);
    double scale_q = 0.0, scale_p = 0.0, dq = 0.0, dp = 0.0;
    random_state(R, y);
    if (autobal_rotor_rhs(t, y, f, R) != 0 || direct_solve(R, t, y, qdd, phidd) != 0) {
      ok = 0;
      continue;
    }
    for (k = 0; k < 4; k++) {
      scale_q = fmax(scale_q, fabs(qdd[k]));
      dq = fmax(dq, fabs(f[4 + k] - qdd[k]));
      if (f[k] != y[4 + k]) ok = 0;
    }
    for (k = 0; k < N; k++) {
      scale_p = fmax(scale_p, fabs(phidd[k]));
      dp = fmax(dp, fabs(f[8 + N + k] - phidd[k]));
      if (f[8 + k] != y[8 + N + k]) ok = 0;
    }
    worst = fmax(worst, dq / scale_q);
    if (N > 0) worst = fmax(worst, dp / scale_p);
    if (dim > 8 + 2 * N) {
      const autobal_rotor_lumped *L = autobal_rotor_get_lumped(R);
      const double zdd = -(p->hw.h_Lz * y[9 + 2 * N] + p->hw.c_Lz * y[8 + 2 * N]) / L->M;
      zworst = fmax(zworst, fabs(f[9 + 2 * N] - zdd) / fabs(zdd));
    }
  }
  CHECK("rhs and direct solve ran; velocity rows are copies", ok);
  printf("     %s:\n", label);
  CHECK_CLOSE("   max relative |rhs - direct (4+N) LU| over random states", worst, 0.0, 0, 1e-10);
  CHECK_CLOSE("   axial z'' (2.12)", zworst, 0.0, 0, 1e-14);
  if (worst > g_max_direct) g_max_direct = worst;
  autobal_rotor_free(R);
}

static void test_direct_solve(void) {
  autobal_rotor_params p;
  printf("-- O(N) 4x4 reduction vs direct solve of the full (4+N) system (GSL LU)\n");
  p = autobal_rotor_params_default();
  check_direct("default", &p, 30);
  p = two_plane_params();
  check_direct("two planes, anisotropic, unequal balls, axial", &p, 30);
  p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  check_direct("same, FULL inertia variant", &p, 30);
  p = autobal_rotor_params_default();
  p.plane[0].n_balls = 0;
  check_direct("no balls", &p, 5);
  printf("     max mismatch over all configurations: %.3g\n", g_max_direct);
}

/* ---- one plane: the closed-form 2x2 reduction of the right-hand sides ------------ */

/* One plane at a random position d with a random unbalance and n balls of random
 * masses (scaled so that sum_i m_i (1/M + d^2/A) = heavy), radii, damping and
 * initial rates; FULL or PAPER inertia.  The arrays (n entries) are the caller's. */
static autobal_rotor_params one_plane_params(size_t n, double heavy, int full, double *m, double *r,
                                             double *h, double *psi, double *rate) {
  autobal_rotor_params p = autobal_rotor_params_default();
  const double M = p.hw.M_k + p.hw.m_p, A = p.hw.A_k + p.hw.A_p;
  double wsum = 0.0, g;
  size_t i;
  p.inertia = full ? AUTOBAL_ROTOR_INERTIA_FULL : AUTOBAL_ROTOR_INERTIA_PAPER;
  p.hw.c_Ly = 0.7e5; /* anisotropic supports */
  p.hw.h_Ry = 210.0;
  p.plane[0].d = urand(-0.25, 0.25);
  p.plane[0].m0 = urand(0.005, 0.03);
  p.plane[0].r0 = urand(0.05, 0.12);
  p.plane[0].psi0 = urand(-3, 3);
  p.plane[0].n_balls = n;
  g = 1.0 / M + p.plane[0].d * p.plane[0].d / A;
  for (i = 0; i < n; i++) {
    m[i] = urand(0.5, 1.5);
    wsum += m[i];
    r[i] = urand(0.05, 0.15);
    h[i] = urand(0.0, 0.5);
    psi[i] = urand(-3, 3);
    rate[i] = urand(-5, 5);
  }
  for (i = 0; i < n; i++) m[i] *= heavy / (g * wsum);
  p.plane[0].ball_mass = m;
  p.plane[0].ball_radius = r;
  p.plane[0].ball_damping = h;
  p.plane[0].ball_psi = psi;
  p.plane[0].ball_rate = rate;
  return p;
}

/* The reduced 4x4 system of "Solving for the accelerations", assembled here from
 * the spec's S_ss, S_sc, S_cc, F_u, F_v and (3.2) with the hardware matrices, and
 * solved by GSL's Cholesky: q'' at a fixed-frame state. */
static int reduced_cholesky(const autobal_rotor *R, double t, const double *y, double *qdd) {
  const autobal_rotor_params *p = autobal_rotor_get_params(R);
  model_view v;
  double Dm[4], K[4][4], H[4][4], G[4][4], a[16], bb[4], xx[4];
  double Sss = 0.0, Ssc = 0.0, Scc = 0.0, Fu, Fv;
  const double w = p->omega;
  size_t i, k;
  int st;
  gsl_matrix_view am = gsl_matrix_view_array(a, 4, 4);
  gsl_vector_view bv = gsl_vector_view_array(bb, 4), xv = gsl_vector_view_array(xx, 4);
  view(R, &v);
  rotor_matrices(p, Dm, K, H, G);
  Fu = -v.s0[0] * w * w * cos(w * t + v.psi0[0]);
  Fv = -v.s0[0] * w * w * sin(w * t + v.psi0[0]);
  for (k = 0; k < v.N; k++) {
    const double s = sin(y[8 + k]), c = cos(y[8 + k]), pd = y[8 + v.N + k];
    Sss += v.m[k] * s * s;
    Ssc += v.m[k] * s * c;
    Scc += v.m[k] * c * c;
    Fu += v.h[k] * v.r[k] * (pd - w) * s - v.m[k] * v.r[k] * pd * pd * c;
    Fv += -v.h[k] * v.r[k] * (pd - w) * c - v.m[k] * v.r[k] * pd * pd * s;
  }
  {
    const double d = v.d[0];
    const double eu[4] = {1, 0, 0, d}, ev[4] = {0, 1, -d, 0};
    /* s_u'' = (mfull - S_ss) u_D'' + S_sc v_D'' + F_u, s_v'' = S_sc u_D'' + (mfull - S_cc) v_D'' + F_v */
    const double cuu = v.mfull[0] - Sss, cuv = Ssc, cvv = v.mfull[0] - Scc;
    for (i = 0; i < 4; i++) {
      double f = 0.0;
      for (k = 0; k < 4; k++) {
        a[4 * i + k] = (i == k ? Dm[i] : 0.0) + cuu * eu[i] * eu[k] +
                       cuv * (eu[i] * ev[k] + ev[i] * eu[k]) + cvv * ev[i] * ev[k];
        f += (H[i][k] + G[i][k]) * y[4 + k] + K[i][k] * y[k];
      }
      bb[i] = -f - Fu * eu[i] - Fv * ev[i];
    }
  }
  st = gsl_linalg_cholesky_decomp1(&am.matrix);
  if (st == 0) st = gsl_linalg_cholesky_solve(&am.matrix, &bv.vector, &xv.vector);
  for (i = 0; i < 4; i++) qdd[i] = xx[i];
  return st;
}

static double g_max_one_plane = 0.0;

/* Both right-hand sides of a one-plane model against the direct (4+N) LU solve and
 * the reduced 4x4 Cholesky at random states.  t = k/1024 s (k = 0..10; omega t =
 * 500 k / 1024 exactly) and ball angles on a 2^-40 grid make the conversion
 * psi = phi - omega t exact, so the two frames see the same configuration.  Relative
 * errors: max |difference| / max |q''_i| for q'', and for the ball accelerations
 * max |difference| / max over balls of the size of the terms of (3.4),
 * (|u_D''| + |v_D''|) / r + (h/m) |phi' - omega| (phi'' itself may cancel to ~0). */
static void check_one_plane(const char *label, const autobal_rotor_params *p, int nstates,
                            double tol) {
  autobal_rotor *R = autobal_rotor_alloc(p, NULL);
  double y[MAXDIM], yr[MAXDIM], f[MAXDIM], fr[MAXDIM], qdd[4], qch[4], phidd[MAXDIM];
  double e_fix = 0.0, e_rot = 0.0, e_chol = 0.0, e_w = 0.0;
  int s, ok = 1;
  size_t N, k, dim;
  CHECK(label, R != NULL);
  if (R == NULL) return;
  N = autobal_rotor_n_balls_total(R);
  dim = autobal_rotor_dim(R);
  for (s = 0; s < nstates; s++) {
    const double t = floor(urand(0, 11)) / 1024.0, w = autobal_rotor_omega(R), d = p->plane[0].d;
    double sq = 0.0, sp = 0.0, dq = 0.0, dqr = 0.0, dqc = 0.0, dp = 0.0, dpr = 0.0, dpw = 0.0;
    random_state(R, y);
    for (k = 0; k < N; k++) y[8 + k] = ldexp(nearbyint(ldexp(y[8 + k], 40)), -40);
    if (autobal_rotor_convert_state(R, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, t, y, yr, dim) != 0 ||
        autobal_rotor_rhs(t, y, f, R) != 0 || autobal_rotor_rhs_rotating(t, yr, fr, R) != 0 ||
        direct_solve(R, t, y, qdd, phidd) != 0 || reduced_cholesky(R, t, y, qch) != 0) {
      ok = 0;
      continue;
    }
    for (k = 0; k < 4; k++) {
      sq = fmax(sq, fabs(qdd[k]));
      dq = fmax(dq, fabs(f[4 + k] - qdd[k]));
      dqr = fmax(dqr, fabs(fr[4 + k] - qdd[k]));
      dqc = fmax(dqc, fabs(f[4 + k] - qch[k]));
    }
    {
      /* (3.3) and (3.4) applied to the returned q'': the ball accelerations must be
       * those of u_D'' = x'' + d beta'', v_D'' = y'' - d alpha'' */
      const double u = f[4] + d * f[7], vv = f[5] - d * f[6];
      for (k = 0; k < N; k++) {
        const double m = p->plane[0].ball_mass[k], r = p->plane[0].ball_radius[k];
        const double hk = p->plane[0].ball_damping[k], ph = y[8 + k], pd = y[8 + N + k];
        const double want = (u * sin(ph) - vv * cos(ph)) / r - hk / m * (pd - w);
        sp = fmax(sp, (fabs(u) + fabs(vv)) / r + hk / m * fabs(pd - w));
        dp = fmax(dp, fabs(f[8 + N + k] - phidd[k]));
        dpr = fmax(dpr, fabs(fr[8 + N + k] - phidd[k]));
        dpw = fmax(dpw, fabs(f[8 + N + k] - want));
      }
    }
    e_fix = fmax(e_fix, dq / sq);
    e_rot = fmax(e_rot, dqr / sq);
    e_chol = fmax(e_chol, dqc / sq);
    if (N > 0) {
      e_fix = fmax(e_fix, dp / sp);
      e_rot = fmax(e_rot, dpr / sp);
      e_w = fmax(e_w, dpw / sp);
    }
  }
  printf("     %s:\n", label);
  CHECK("   all right-hand sides and reference solves ran", ok);
  CHECK_CLOSE("   fixed frame vs direct (4+N) LU, max relative difference", e_fix, 0.0, 0, tol);
  CHECK_CLOSE("   rotating frame vs direct (4+N) LU, max relative difference", e_rot, 0.0, 0, tol);
  CHECK_CLOSE("   fixed-frame q'' vs reduced 4x4 Cholesky (GSL), max relative difference", e_chol,
              0.0, 0, tol);
  CHECK_CLOSE("   ball accelerations vs (3.3)-(3.4) from the returned q''", e_w, 0.0, 0, tol);
  g_max_one_plane = fmax(g_max_one_plane, fmax(fmax(e_fix, e_rot), fmax(e_chol, e_w)));
  autobal_rotor_free(R);
}

static void test_one_plane_closed_form(void) {
  static const size_t nb[3] = {1, 2, 5};
  double m[5], r[5], h[5], psi[5], rate[5];
  char label[160];
  autobal_rotor_params p;
  int c, full;
  printf("-- one plane: closed-form 2x2 reduction vs direct (4+N) LU and reduced 4x4 Cholesky\n");
  p = autobal_rotor_params_default();
  check_one_plane("default example (2 balls, PAPER)", &p, 40, 1e-14);
  p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  check_one_plane("default example, FULL", &p, 40, 1e-14);
  for (full = 0; full < 2; full++)
    for (c = 0; c < 3; c++) {
      p = one_plane_params(nb[c], 0.3, full, m, r, h, psi, rate);
      snprintf(label, sizeof label, "%zu ball(s), random masses, sum m g = 0.3, %s, d = %.4f m", nb[c],
               full ? "FULL" : "PAPER", p.plane[0].d);
      check_one_plane(label, &p, 40, 1e-14);
    }
  /* heavier than the paper model allows: FULL only (I + g C >= I) */
  p = one_plane_params(5, 4.0, 1, m, r, h, psi, rate);
  check_one_plane("5 balls, sum m g = 4, FULL", &p, 40, 1e-14);
  /* close to the paper model's limit: I + g C has eigenvalues down to 1 - 0.99 */
  p = one_plane_params(2, 0.99, 0, m, r, h, psi, rate);
  check_one_plane("2 balls, sum m g = 0.99, PAPER (ill-conditioned, cond <= 100)", &p, 40, 1e-13);
  p = one_plane_params(0, 0.0, 1, m, r, h, psi, rate);
  check_one_plane("no balls, FULL (C = m0 I)", &p, 10, 1e-14);
  printf("     max mismatch over all one-plane configurations: %.3g\n", g_max_one_plane);
}

static void test_frames_instantaneous(void) {
  autobal_rotor_params ps[2];
  int c, s;
  printf("-- fixed-frame rhs vs rotating-frame rhs (3.13) at the same physical states\n");
  ps[0] = autobal_rotor_params_default();
  ps[1] = two_plane_params();
  ps[1].inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  for (c = 0; c < 2; c++) {
    autobal_rotor *R = autobal_rotor_alloc(&ps[c], NULL);
    double worst = 0.0, rworst = 0.0;
    size_t N, k, dim;
    if (R == NULL) continue;
    N = autobal_rotor_n_balls_total(R);
    dim = autobal_rotor_dim(R);
    for (s = 0; s < 30; s++) {
      double y[MAXDIM], yr[MAXDIM], f[MAXDIM], fr[MAXDIM], sc = 0.0;
      const double t = urand(0, 3);
      random_state(R, y);
      autobal_rotor_convert_state(R, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, t, y, yr, dim);
      autobal_rotor_rhs(t, y, f, R);
      autobal_rotor_rhs_rotating(t, yr, fr, R);
      for (k = 0; k < dim; k++) sc = fmax(sc, fabs(f[k]));
      for (k = 4; k < 8; k++) worst = fmax(worst, fabs(f[k] - fr[k]) / fabs(f[k]));
      for (k = 0; k < N; k++) {
        /* psi'' = phi'', psi' = phi' - omega */
        worst = fmax(worst, fabs(f[8 + N + k] - fr[8 + N + k]) / fmax(fabs(f[8 + N + k]), 1.0));
        rworst = fmax(rworst, fabs(fr[8 + k] + autobal_rotor_omega(R) - f[8 + k]));
      }
    }
    CHECK_CLOSE(c == 0 ? "default: max relative difference of accelerations"
                       : "two planes FULL: max relative difference of accelerations",
                worst, 0.0, 0, 1e-10);
    CHECK_CLOSE("angle rates psi' + omega = phi'", rworst, 0.0, 0, 1e-12);
    autobal_rotor_free(R);
  }
}

static double g_frame_diff_q = 0.0, g_frame_diff_ang = 0.0;

static void test_frames_transient(void) {
  autobal_rotor_params p[2];
  int c;
  printf("-- transient in the fixed frame vs the rotating frame (rtol 1e-10)\n");
  p[0] = autobal_rotor_params_default();
  p[1] = two_plane_params();
  for (c = 0; c < 2; c++) {
    autobal_rotor *R = autobal_rotor_alloc(&p[c], NULL);
    double y[MAXDIM], yr[MAXDIM], yc[MAXDIM], dq = 0.0, da = 0.0, amp = 0.0;
    const double T = c == 0 ? 1.0 : 0.5;
    size_t k, dim, N;
    int st1, st2;
    if (R == NULL) continue;
    dim = autobal_rotor_dim(R);
    N = autobal_rotor_n_balls_total(R);
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, dim);
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_ROTATING, 0.0, yr, dim);
    st1 = integrate(autobal_rotor_rhs, R, 0.0, T, y, 1e-10, 1e-13);
    st2 = integrate(autobal_rotor_rhs_rotating, R, 0.0, T, yr, 1e-10, 1e-13);
    CHECK("both integrations succeeded", st1 == 0 && st2 == 0);
    autobal_rotor_convert_state(R, AUTOBAL_ROTOR_ROTATING, AUTOBAL_ROTOR_FIXED, T, yr, yc, dim);
    for (k = 0; k < 2; k++) amp = fmax(amp, fabs(y[k]));
    for (k = 0; k < 4; k++) dq = fmax(dq, fabs(y[k] - yc[k]));
    for (k = 0; k < N; k++) da = fmax(da, fabs(y[8 + k] - yc[8 + k]));
    printf("     %s, t = %g s, |x|,|y| up to %.3g m\n", c == 0 ? "default" : "two planes", T, amp);
    CHECK_CLOSE("   max |q_fixed - q_rotating| (m, rad)", dq, 0.0, 0, 1e-10);
    CHECK_CLOSE("   max |phi_fixed - (psi_rotating + omega t)| (rad)", da, 0.0, 0, 1e-6);
    g_frame_diff_q = fmax(g_frame_diff_q, dq);
    g_frame_diff_ang = fmax(g_frame_diff_ang, da);
    autobal_rotor_free(R);
  }
}

/* rotate a fixed-frame state by theta about z: W = x + i y and Theta = beta - i alpha
 * turn by e^{i theta}, absolute ball angles increase by theta */
static void rotate_state(double th, const double *y, double *out, size_t N) {
  const double c = cos(th), s = sin(th);
  int o;
  for (o = 0; o < 8; o += 4) {
    const double x = y[o], yy = y[o + 1], al = y[o + 2], be = y[o + 3];
    const double tr = be, ti = -al; /* Theta */
    out[o] = c * x - s * yy;
    out[o + 1] = s * x + c * yy;
    out[o + 3] = c * tr - s * ti;
    out[o + 2] = -(s * tr + c * ti);
  }
  for (size_t k = 0; k < N; k++) {
    out[8 + k] = y[8 + k] + th;
    out[8 + N + k] = y[8 + N + k];
  }
}

static double rotation_mismatch(autobal_rotor_params pa, double th) {
  autobal_rotor_params pb = pa;
  double psi_b[2], ya[MAXDIM], yb[MAXDIM], yrot[MAXDIM], worst = 0.0;
  autobal_rotor *A, *B;
  size_t k, N, dim;
  pa.q0[0] = 2e-4;
  pa.q0[1] = -1e-4;
  pa.q0[2] = 3e-4;
  pa.q0[3] = 1e-4;
  pa.qd0[0] = 0.01;
  pa.qd0[3] = -0.05;
  pb = pa;
  /* rotated problem: unbalance and ball angles + th, rotor state rotated */
  pb.plane[0].psi0 = pa.plane[0].psi0 + th;
  psi_b[0] = pa.plane[0].ball_psi[0] + th;
  psi_b[1] = pa.plane[0].ball_psi[1] + th;
  pb.plane[0].ball_psi = psi_b;
  {
    double in[MAXDIM] = {0}, out[MAXDIM];
    for (k = 0; k < 4; k++) {
      in[k] = pa.q0[k];
      in[4 + k] = pa.qd0[k];
    }
    rotate_state(th, in, out, 0);
    for (k = 0; k < 4; k++) {
      pb.q0[k] = out[k];
      pb.qd0[k] = out[4 + k];
    }
  }
  A = autobal_rotor_alloc(&pa, NULL);
  B = autobal_rotor_alloc(&pb, NULL);
  if (A == NULL || B == NULL) {
    autobal_rotor_free(A);
    autobal_rotor_free(B);
    return INFINITY;
  }
  dim = autobal_rotor_dim(A);
  N = autobal_rotor_n_balls_total(A);
  autobal_rotor_initial_state(A, AUTOBAL_ROTOR_FIXED, 0.0, ya, dim);
  autobal_rotor_initial_state(B, AUTOBAL_ROTOR_FIXED, 0.0, yb, dim);
  integrate(autobal_rotor_rhs, A, 0.0, 0.5, ya, 1e-10, 1e-13);
  integrate(autobal_rotor_rhs, B, 0.0, 0.5, yb, 1e-10, 1e-13);
  rotate_state(th, ya, yrot, N);
  for (k = 0; k < 4; k++) worst = fmax(worst, fabs(yrot[k] - yb[k]) / 1e-4); /* in units of 0.1 mm */
  for (k = 0; k < N; k++) worst = fmax(worst, fabs(yrot[8 + k] - yb[8 + k]));
  autobal_rotor_free(A);
  autobal_rotor_free(B);
  return worst;
}

static void test_rotation_invariance(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  double mis;
  printf("-- rotation invariance of the isotropic default (rotate state and unbalance by 0.9 rad)\n");
  mis = rotation_mismatch(p, 0.9);
  CHECK_CLOSE("isotropic: solution rotates with the data (q in 0.1 mm, angles in rad)", mis, 0.0, 0, 1e-6);
  /* the same check must fail for anisotropic supports (the test has teeth) */
  p.hw.c_Ly = 0.7e5;
  mis = rotation_mismatch(p, 0.9);
  CHECK("anisotropic supports break rotation invariance (mismatch > 1e-3)", mis > 1e-3);
}

static void test_mirror(void) {
  autobal_rotor_params p = two_plane_params(), m;
  autobal_rotor *A, *B;
  double ya[MAXDIM], yb[MAXDIM], worst = 0.0;
  size_t k, N, dim;
  printf("-- mirror z -> -z: swap supports, negate d_j: x, y, phi unchanged, alpha, beta negated\n");
  m = p;
  m.hw.l_L = p.hw.l_R;
  m.hw.l_R = p.hw.l_L;
  m.hw.c_Lx = p.hw.c_Rx;
  m.hw.c_Rx = p.hw.c_Lx;
  m.hw.c_Ly = p.hw.c_Ry;
  m.hw.c_Ry = p.hw.c_Ly;
  m.hw.h_Lx = p.hw.h_Rx;
  m.hw.h_Rx = p.hw.h_Lx;
  m.hw.h_Ly = p.hw.h_Ry;
  m.hw.h_Ry = p.hw.h_Ly;
  m.plane[0].d = -p.plane[0].d;
  m.plane[1].d = -p.plane[1].d;
  m.q0[2] = -p.q0[2];
  m.q0[3] = -p.q0[3];
  m.qd0[2] = -p.qd0[2];
  m.qd0[3] = -p.qd0[3];
  A = autobal_rotor_alloc(&p, NULL);
  B = autobal_rotor_alloc(&m, NULL);
  CHECK("mirror pair alloc", A && B);
  if (A && B) {
    dim = autobal_rotor_dim(A);
    N = autobal_rotor_n_balls_total(A);
    autobal_rotor_initial_state(A, AUTOBAL_ROTOR_FIXED, 0.0, ya, dim);
    autobal_rotor_initial_state(B, AUTOBAL_ROTOR_FIXED, 0.0, yb, dim);
    integrate(autobal_rotor_rhs, A, 0.0, 0.4, ya, 1e-10, 1e-13);
    integrate(autobal_rotor_rhs, B, 0.0, 0.4, yb, 1e-10, 1e-13);
    worst = fmax(fabs(ya[0] - yb[0]), fabs(ya[1] - yb[1])) / 1e-4;
    worst = fmax(worst, fmax(fabs(ya[2] + yb[2]), fabs(ya[3] + yb[3])) / 1e-4);
    for (k = 0; k < N; k++) worst = fmax(worst, fabs(ya[8 + k] - yb[8 + k]));
    CHECK_CLOSE("mirrored solution (q in 0.1 mm, angles rad)", worst, 0.0, 0, 1e-6);
    CHECK("alpha is not trivially zero", fabs(ya[2]) > 1e-7);
  }
  autobal_rotor_free(A);
  autobal_rotor_free(B);
  {
    /* a self-mirrored system: symmetric supports, planes at +-d with the same data ->
     * pure translation (alpha = beta = 0) and equal ball motion in both planes */
    autobal_rotor_params s = autobal_rotor_params_default();
    autobal_rotor *S;
    double y[MAXDIM], maxab = 0.0, dphi = 0.0;
    s.hw.l_L = s.hw.l_R = 0.18;
    s.hw.c_Rx = s.hw.c_Ry = s.hw.c_Lx;
    s.hw.h_Rx = s.hw.h_Ry = s.hw.h_Lx;
    s.n_planes = 2;
    s.plane[1] = s.plane[0];
    s.plane[1].d = -s.plane[0].d;
    S = autobal_rotor_alloc(&s, NULL);
    CHECK("symmetric two-plane alloc", S != NULL);
    if (S) {
      int i;
      autobal_rotor_initial_state(S, AUTOBAL_ROTOR_FIXED, 0.0, y, autobal_rotor_dim(S));
      for (i = 1; i <= 5; i++) {
        integrate(autobal_rotor_rhs, S, 0.1 * (i - 1), 0.1 * i, y, 1e-10, 1e-13);
        maxab = fmax(maxab, fmax(fabs(y[2]), fabs(y[3])));
        dphi = fmax(dphi, fmax(fabs(y[8] - y[10]), fabs(y[9] - y[11])));
      }
      CHECK_CLOSE("symmetric: alpha, beta stay 0 (rad)", maxab, 0.0, 0, 1e-13);
      CHECK_CLOSE("symmetric: plane 1 balls = plane 2 balls (rad)", dphi, 0.0, 0, 1e-10);
      CHECK("symmetric: the rotor does move", fabs(y[0]) + fabs(y[1]) > 1e-7);
    }
    autobal_rotor_free(S);
  }
}

static void test_plane_split(void) {
  static const double m1[1] = {0.05}, r1[1] = {0.1}, h1[1] = {0.1}, psiA[1] = {1.0}, psiB[1] = {2.5};
  autobal_rotor_params a = autobal_rotor_params_default(), b = a, c = a;
  autobal_rotor *A, *B, *C;
  double ya[MAXDIM], yb[MAXDIM], yc[MAXDIM], wb = 0.0, wc = 0.0;
  size_t k;
  printf("-- one code path for planes: a plane split in two at the same d; an empty extra plane\n");
  b.n_planes = 2;
  b.plane[0].n_balls = 1;
  b.plane[0].ball_mass = m1;
  b.plane[0].ball_radius = r1;
  b.plane[0].ball_damping = h1;
  b.plane[0].ball_psi = psiA;
  b.plane[0].ball_rate = NULL;
  b.plane[1] = b.plane[0];
  b.plane[1].ball_psi = psiB;
  b.plane[1].m0 = 0.0;
  c.n_planes = 2;
  memset(&c.plane[1], 0, sizeof c.plane[1]);
  c.plane[1].d = -0.3;
  A = autobal_rotor_alloc(&a, NULL);
  B = autobal_rotor_alloc(&b, NULL);
  C = autobal_rotor_alloc(&c, NULL);
  CHECK("split/empty-plane models alloc", A && B && C);
  if (A && B && C) {
    CHECK("same state dimension", autobal_rotor_dim(A) == 12 && autobal_rotor_dim(B) == 12 && autobal_rotor_dim(C) == 12);
    autobal_rotor_initial_state(A, AUTOBAL_ROTOR_FIXED, 0.0, ya, 12);
    autobal_rotor_initial_state(B, AUTOBAL_ROTOR_FIXED, 0.0, yb, 12);
    autobal_rotor_initial_state(C, AUTOBAL_ROTOR_FIXED, 0.0, yc, 12);
    integrate(autobal_rotor_rhs, A, 0.0, 0.5, ya, 1e-10, 1e-13);
    integrate(autobal_rotor_rhs, B, 0.0, 0.5, yb, 1e-10, 1e-13);
    integrate(autobal_rotor_rhs, C, 0.0, 0.5, yc, 1e-10, 1e-13);
    for (k = 0; k < 12; k++) {
      const double sc = k < 4 ? 1e-4 : (k < 8 ? 1e-1 : 1.0);
      wb = fmax(wb, fabs(ya[k] - yb[k]) / sc);
      wc = fmax(wc, fabs(ya[k] - yc[k]) / sc);
    }
    CHECK_CLOSE("plane split in two at the same d (scaled)", wb, 0.0, 0, 1e-7);
    CHECK_CLOSE("extra plane with no balls and no unbalance (scaled)", wc, 0.0, 0, 1e-7);
  }
  autobal_rotor_free(A);
  autobal_rotor_free(B);
  autobal_rotor_free(C);
}

/* Complex steady harmonic response of the rotor to a rotating unbalance S (complex, rotor
 * axes, kg m) in plane d: D q'' + (H + G) q' + K q = Re(w^2 S (eu - i ev) e^{i w t}).
 * Q[2k], Q[2k+1] = Re, Im of coordinate k's complex amplitude. */
static int steady_response(const autobal_rotor_params *p, const double *S_re, const double *S_im,
                           const double *dplanes, size_t np, double Q[8]) {
  double Dm[4], K[4][4], H[4][4], G[4][4];
  const double w = p->omega;
  gsl_matrix_complex *Z = gsl_matrix_complex_alloc(4, 4);
  gsl_vector_complex *F = gsl_vector_complex_calloc(4), *X = gsl_vector_complex_alloc(4);
  gsl_permutation *perm = gsl_permutation_alloc(4);
  int i, k, sgn, st;
  size_t j;
  rotor_matrices(p, Dm, K, H, G);
  for (i = 0; i < 4; i++)
    for (k = 0; k < 4; k++)
      gsl_matrix_complex_set(Z, (size_t)i, (size_t)k,
                             gsl_complex_rect(K[i][k] - (i == k ? w * w * Dm[i] : 0.0), w * (H[i][k] + G[i][k])));
  for (j = 0; j < np; j++) {
    const double d = dplanes[j];
    const double eu[4] = {1, 0, 0, d}, ev[4] = {0, 1, -d, 0};
    const gsl_complex S = gsl_complex_rect(S_re[j], S_im[j]);
    for (i = 0; i < 4; i++) {
      gsl_complex f = gsl_complex_mul(gsl_complex_mul_real(S, w * w), gsl_complex_rect(eu[i], -ev[i]));
      gsl_vector_complex_set(F, (size_t)i, gsl_complex_add(gsl_vector_complex_get(F, (size_t)i), f));
    }
  }
  st = gsl_linalg_complex_LU_decomp(Z, perm, &sgn);
  if (st == 0) st = gsl_linalg_complex_LU_solve(Z, perm, F, X);
  for (i = 0; i < 4 && st == 0; i++) {
    Q[2 * i] = GSL_REAL(gsl_vector_complex_get(X, (size_t)i));
    Q[2 * i + 1] = GSL_IMAG(gsl_vector_complex_get(X, (size_t)i));
  }
  gsl_matrix_complex_free(Z);
  gsl_vector_complex_free(F);
  gsl_vector_complex_free(X);
  gsl_permutation_free(perm);
  return st;
}

static double g_steady_err = 0.0;

static void test_no_balls_steady(void) {
  const double omegas[3] = {500.0, 180.0, 100.0};
  int c;
  printf("-- no balls: transient after decay vs the closed-form steady unbalance response\n");
  for (c = 0; c < 3; c++) {
    autobal_rotor_params p = two_plane_params();
    autobal_rotor *R;
    double y[MAXDIM], Q[8], amp = 0.0, err = 0.0, t = 0.0;
    double sre[2], sim[2], dpl[2];
    int i, k;
    p.omega = omegas[c];
    p.axial = 0;
    p.plane[0].n_balls = 0;
    p.plane[1].n_balls = 0;
    for (i = 0; i < 2; i++) {
      sre[i] = p.plane[i].m0 * p.plane[i].r0 * cos(p.plane[i].psi0);
      sim[i] = p.plane[i].m0 * p.plane[i].r0 * sin(p.plane[i].psi0);
      dpl[i] = p.plane[i].d;
    }
    R = autobal_rotor_alloc(&p, NULL);
    if (R == NULL || steady_response(&p, sre, sim, dpl, 2, Q) != 0) {
      CHECK("no-ball model and steady response", 0);
      autobal_rotor_free(R);
      continue;
    }
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, 8);
    integrate(autobal_rotor_rhs, R, 0.0, 3.0, y, 1e-11, 1e-14);
    t = 3.0;
    for (k = 0; k < 4; k++) amp = fmax(amp, hypot(Q[2 * k], Q[2 * k + 1]) * (k < 2 ? 1.0 : 0.1));
    for (i = 0; i < 8; i++) { /* 8 samples over one revolution */
      const double t1 = 3.0 + (i + 1) * (2.0 * M_PI / p.omega) / 8.0;
      integrate(autobal_rotor_rhs, R, t, t1, y, 1e-11, 1e-14);
      t = t1;
      for (k = 0; k < 4; k++) {
        const double want = Q[2 * k] * cos(p.omega * t) - Q[2 * k + 1] * sin(p.omega * t);
        err = fmax(err, fabs(y[k] - want) * (k < 2 ? 1.0 : 0.1));
      }
    }
    printf("     omega = %g rad/s: steady amplitude %.4g (m-equivalent)\n", p.omega, amp);
    CHECK_CLOSE("   max |q(t) - Re(Q e^{iwt})| / amplitude over one revolution at t = 3 s", err / amp, 0.0, 0, 1e-7);
    g_steady_err = fmax(g_steady_err, err / amp);
    autobal_rotor_free(R);
  }
}

static double g_energy_rate_err = 0.0, g_energy_drift = 0.0;

static void test_energy(void) {
  autobal_rotor_params ps[3];
  int c, s;
  printf("-- energy: dE/dt = -dissipation + power of the unbalance drive (random states)\n");
  ps[0] = autobal_rotor_params_default();
  ps[1] = two_plane_params();
  ps[2] = two_plane_params();
  ps[2].inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  for (c = 0; c < 3; c++) {
    autobal_rotor *R = autobal_rotor_alloc(&ps[c], NULL);
    double worst = 0.0;
    if (R == NULL) continue;
    for (s = 0; s < 30; s++) {
      double y[MAXDIM], f[MAXDIM], scale;
      const double t = urand(0, 2);
      double P, dE;
      random_state(R, y);
      autobal_rotor_rhs(t, y, f, R);
      dE = energy_rate(R, y, f);
      P = power_balance(R, t, y, &scale);
      worst = fmax(worst, fabs(dE - P) / scale);
    }
    CHECK_CLOSE(c == 0 ? "default: |dE/dt - P| / scale" : (c == 1 ? "two planes: |dE/dt - P| / scale" : "two planes FULL inertia: |dE/dt - P| / scale"),
                worst, 0.0, 0, 1e-9);
    g_energy_rate_err = fmax(g_energy_rate_err, worst);
    autobal_rotor_free(R);
  }
  printf("-- energy conservation: no damping, no unbalance, omega = 500 (gyroscopic terms on)\n");
  for (c = 0; c < 2; c++) {
    static const double zero[3] = {0, 0, 0}, rates1[2] = {3.0, -5.0};
    autobal_rotor_params p = two_plane_params();
    autobal_rotor *R;
    double y[MAXDIM], E0, E1, Emax = 0.0, t = 0.0;
    int i;
    p.inertia = c == 0 ? AUTOBAL_ROTOR_INERTIA_PAPER : AUTOBAL_ROTOR_INERTIA_FULL;
    p.hw.h_Lx = p.hw.h_Ly = p.hw.h_Lz = p.hw.h_Rx = p.hw.h_Ry = 0.0;
    p.plane[0].ball_damping = zero;
    p.plane[1].ball_damping = zero;
    p.plane[0].m0 = 0.0;
    p.plane[1].m0 = 0.0;
    p.plane[0].ball_rate = rates1;
    p.q0[1] = -2e-4;
    p.q0[2] = 1e-3;
    R = autobal_rotor_alloc(&p, NULL);
    if (R == NULL) continue;
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, autobal_rotor_dim(R));
    E0 = energy(R, y);
    for (i = 1; i <= 10; i++) {
      integrate(autobal_rotor_rhs, R, t, 0.05 * i, y, 1e-11, 1e-14);
      t = 0.05 * i;
      E1 = energy(R, y);
      Emax = fmax(Emax, fabs(E1 - E0) / E0);
    }
    CHECK_CLOSE(c == 0 ? "paper model: max |E(t) - E(0)| / E(0) over 0.5 s" : "FULL inertia: max |E(t) - E(0)| / E(0) over 0.5 s",
                Emax, 0.0, 0, 1e-8);
    g_energy_drift = fmax(g_energy_drift, Emax);
    autobal_rotor_free(R);
  }
}

static void test_balanced_angles(void) {
  autobal_error err;
  double psi[8];
  printf("-- balanced angles (3.14) and the existence test\n");
  /* spec: default example psi~ = +-1.7721542 */
  CHECK_STATUS("two identical balls", autobal_rotor_balanced_angles_two(0.002, 0.005, 0.005, 0.0, psi, &err), AUTOBAL_SUCCESS);
  CHECK_CLOSE("psi_1 = pi - arccos(0.2) (spec 1.7721542)", psi[0], 1.7721542, 0, 1e-7);
  CHECK_CLOSE("psi_2 = pi + arccos(0.2) = -1.7721542 mod 2pi", psi[1], -1.7721542, 0, 1e-7);
  {
    /* unequal balls, nonzero psi0: the vector sum must vanish */
    const double a1 = 0.006, a2 = 0.004, s0 = 0.003, p0 = 0.8;
    double sx, sy;
    CHECK_STATUS("two unequal balls", autobal_rotor_balanced_angles_two(s0, a1, a2, p0, psi, &err), AUTOBAL_SUCCESS);
    sx = s0 * cos(p0) + a1 * cos(psi[0]) + a2 * cos(psi[1]);
    sy = s0 * sin(p0) + a1 * sin(psi[0]) + a2 * sin(psi[1]);
    CHECK_CLOSE("unequal pair cancels the unbalance (kg m)", hypot(sx, sy), 0.0, 0, 1e-15);
  }
  CHECK_STATUS("s0 = 0, identical: opposite pair", autobal_rotor_balanced_angles_two(0.0, 0.005, 0.005, 0.0, psi, &err), AUTOBAL_SUCCESS);
  CHECK_CLOSE("opposite pair", fabs(wrap(psi[0] - psi[1])), M_PI, 0, 1e-14);
  CHECK_STATUS("too light pair", autobal_rotor_balanced_angles_two(0.011, 0.005, 0.005, 0.0, psi, &err), AUTOBAL_EINVAL);
  CHECK_MSG("too light pair message", err.message, "cannot cancel");
  CHECK_STATUS("dominant ball", autobal_rotor_balanced_angles_two(0.001, 0.008, 0.002, 0.0, psi, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("negative s0", autobal_rotor_balanced_angles_two(-1.0, 0.008, 0.002, 0.0, psi, &err), AUTOBAL_EINVAL);
  CHECK_MSG("negative s0 message", err.message, "s0");
  {
    const double a[3] = {0.004, 0.003, 0.002};
    CHECK("can balance: inside the annulus", autobal_rotor_plane_can_balance(0.005, a, 3) == 1);
    CHECK("can balance: at the outer edge", autobal_rotor_plane_can_balance(0.009, a, 3) == 1);
    CHECK("cannot: beyond sum", autobal_rotor_plane_can_balance(0.0091, a, 3) == 0);
    CHECK("can: s0 = 0 when 2 max <= sum", autobal_rotor_plane_can_balance(0.0, a, 3) == 1);
    const double b[2] = {0.008, 0.002};
    CHECK("cannot: heaviest ball dominates", autobal_rotor_plane_can_balance(0.005, b, 2) == 0);
    CHECK("can: at the inner edge", autobal_rotor_plane_can_balance(0.006, b, 2) == 1);
    CHECK("no balls, no unbalance", autobal_rotor_plane_can_balance(0.0, NULL, 0) == 1);
    CHECK("no balls, unbalance", autobal_rotor_plane_can_balance(1e-6, NULL, 0) == 0);
  }
  /* plane-level balanced configurations for n = 1, 2, 5 identical, 4 different */
  {
    static const double m5[5] = {0.01, 0.01, 0.01, 0.01, 0.01}, r5[5] = {0.1, 0.1, 0.1, 0.1, 0.1};
    static const double m4[4] = {0.01, 0.02, 0.015, 0.008}, r4[4] = {0.1, 0.09, 0.1, 0.12};
    static const double h5[5] = {0.1, 0.1, 0.1, 0.1, 0.1};
    static const double m1[1] = {0.02};
    struct { size_t n; const double *m, *r; double m0, psi0; } cases[4] = {
      {5, m5, r5, 0.02, 0.3}, {4, m4, r4, 0.025, -1.1}, {1, m1, r5, 0.02, 0.5}, {5, m5, r5, 0.0, 0.0}};
    int c;
    for (c = 0; c < 4; c++) {
      autobal_rotor_params p = autobal_rotor_params_default();
      autobal_rotor *R;
      double sx, sy;
      size_t i;
      p.plane[0].n_balls = cases[c].n;
      p.plane[0].ball_mass = cases[c].m;
      p.plane[0].ball_radius = cases[c].r;
      p.plane[0].ball_damping = h5;
      p.plane[0].ball_psi = NULL;
      p.plane[0].ball_rate = NULL;
      p.plane[0].m0 = cases[c].m0;
      p.plane[0].psi0 = cases[c].psi0;
      R = autobal_rotor_alloc(&p, NULL);
      if (R == NULL) {
        CHECK("plane model alloc", 0);
        continue;
      }
      CHECK_STATUS("plane balanced angles", autobal_rotor_balanced_angles(R, 0, psi, cases[c].n, &err), AUTOBAL_SUCCESS);
      sx = p.plane[0].m0 * p.plane[0].r0 * cos(p.plane[0].psi0);
      sy = p.plane[0].m0 * p.plane[0].r0 * sin(p.plane[0].psi0);
      for (i = 0; i < cases[c].n; i++) {
        sx += cases[c].m[i] * cases[c].r[i] * cos(psi[i]);
        sy += cases[c].m[i] * cases[c].r[i] * sin(psi[i]);
      }
      CHECK_CLOSE("   configuration cancels the unbalance (kg m)", hypot(sx, sy), 0.0, 0, 1e-15);
      {
        /* and the model agrees: monitor is 0 on that configuration */
        double y[MAXDIM] = {0};
        for (i = 0; i < cases[c].n; i++) y[8 + i] = psi[i];
        CHECK_CLOSE("   monitor on the balanced configuration", autobal_rotor_balance_monitor(R, AUTOBAL_ROTOR_ROTATING, 0.0, y), 0.0, 0, 1e-12);
      }
      if (c == 0) { /* symmetric fan about psi0 + pi */
        CHECK_CLOSE("   fan is symmetric about psi0 + pi", wrap(psi[0] + psi[4] - 2.0 * (0.3 + M_PI)), 0.0, 0, 1e-12);
      }
      autobal_rotor_free(R);
    }
  }
  {
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_rotor *R;
    p.plane[0].m0 = 0.2; /* far beyond 2 m r */
    R = autobal_rotor_alloc(&p, &err);
    CHECK_STATUS("unbalanceable plane: alloc warns", err.status, AUTOBAL_WARNING);
    CHECK("unbalanceable plane: handle still usable", R != NULL);
    if (R) {
      CHECK_MSG("warning is on the handle", autobal_rotor_errmsg(R), "cannot cancel");
      CHECK_STATUS("no balanced angles", autobal_rotor_balanced_angles(R, 0, psi, 2, &err), AUTOBAL_EINVAL);
      CHECK_MSG("no balanced angles message", err.message, "no balanced configuration");
      CHECK_STATUS("wrong n", autobal_rotor_balanced_angles(R, 0, psi, 3, &err), AUTOBAL_EINVAL);
      CHECK_STATUS("wrong plane", autobal_rotor_balanced_angles(R, 1, psi, 2, &err), AUTOBAL_EINVAL);
    }
    autobal_rotor_free(R);
  }
}

static double monitor_fixed(double t, const double y[], void *user) {
  return autobal_rotor_balance_monitor((const autobal_rotor *)user, AUTOBAL_ROTOR_FIXED, t, y);
}

/* Supercritical: the default (omega = 500 > 215 rad/s) reaches the balanced angles. */
static double g_bal_err = 0.0, g_ttb = 0.0;
#define SUPER_NS 30001
typedef struct series_rec {
  const autobal_rotor *R;
  double *t, *mon;
  size_t n;
} series_rec;

static int record_monitor(double t, const double y[], void *user) {
  series_rec *s = (series_rec *)user;
  if (s->n < SUPER_NS) {
    s->t[s->n] = t;
    s->mon[s->n] = autobal_rotor_balance_monitor(s->R, AUTOBAL_ROTOR_FIXED, t, y);
    s->n++;
  }
  return 0;
}

static void test_supercritical(void) {
  static double ts[SUPER_NS], mon[SUPER_NS];
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor *R = autobal_rotor_alloc(&p, NULL);
  double y[12], out[32], psi_b[2], e1, e2;
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient_system sys = {autobal_rotor_rhs, NULL, 12, NULL};
  autobal_transient *tr;
  series_rec rec;
  printf("-- supercritical run (omega = 500): balls reach psi~ = pi -/+ arccos(m0 r0 / 2 m r)\n");
  if (R == NULL) return;
  sys.params = R;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.dt_out = 1e-3;
  tr = autobal_transient_alloc(12, &opt, NULL);
  if (tr == NULL) {
    CHECK("transient driver", 0);
    autobal_rotor_free(R);
    return;
  }
  rec.R = R;
  rec.t = ts;
  rec.mon = mon;
  rec.n = 0;
  autobal_transient_set_observer(tr, record_monitor, &rec);
  autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, 12);
  CHECK_STATUS("30 s integrated, monitor recorded every 1 ms", autobal_transient_run(tr, &sys, 0.0, 30.0, y, NULL), AUTOBAL_SUCCESS);
  CHECK("30001 samples", rec.n == SUPER_NS);
  autobal_rotor_outputs(R, AUTOBAL_ROTOR_FIXED, 30.0, y, out, autobal_rotor_output_count(R));
  /* (3.14), computed from the formula here */
  psi_b[0] = M_PI - acos(0.02 * 0.1 / (2.0 * 0.05 * 0.1));
  psi_b[1] = -psi_b[0];
  /* compare as a set, modulo 2 pi (outputs 13 and 19: wrapped psi of balls 1, 2; 15, 21: psi') */
  e1 = fmax(fabs(wrap(out[13] - psi_b[0])), fabs(wrap(out[19] - psi_b[1])));
  e2 = fmax(fabs(wrap(out[13] - psi_b[1])), fabs(wrap(out[19] - psi_b[0])));
  g_bal_err = fmin(e1, e2);
  CHECK_CLOSE("balanced angles reached at t = 30 s (rad, mod 2 pi, as a set)", g_bal_err, 0.0, 0, 1e-6);
  CHECK_CLOSE("residual unbalance |s| / m0 r0", out[8], 0.0, 0, 1e-6);
  CHECK_CLOSE("rotor amplitude at the centre of mass (m)", out[0], 0.0, 0, 1e-10);
  CHECK_CLOSE("relative rates psi' (rad/s)", fmax(fabs(out[15]), fabs(out[21])), 0.0, 0, 1e-6);
  CHECK("monitor started large", mon[0] > 1.0);
  g_ttb = autobal_rotor_time_to_balance(ts, mon, rec.n, 1e-2);
  printf("     time to balance (|s| / m0 r0 < 1e-2 for good): %.3f s\n", g_ttb);
  CHECK("time to balance found, within the run", isfinite(g_ttb) && g_ttb > 0.0 && g_ttb < 30.0);
  {
    /* the same quantity from the transient driver's dwell event on the monitor scalar:
     * its located crossing vs the first 1 ms sample of the final run below the threshold */
    autobal_transient_event_hit hit;
    opt.dt_out = 0.0;
    autobal_transient_set_options(tr, &opt);
    autobal_transient_set_observer(tr, NULL, NULL);
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, 12);
    if (autobal_transient_add_dwell_event(tr, monitor_fixed, R, 1e-2, 29.9 - g_ttb, 1) == 0) {
      CHECK_STATUS("dwell event stops the run", autobal_transient_run(tr, &sys, 0.0, 30.0, y, NULL), AUTOBAL_EVENT);
      CHECK("dwell event fired", autobal_transient_event_result(tr, 0, NULL, &hit) == 1);
      CHECK_CLOSE("time to balance: driver's located crossing vs 1 ms samples (s)", hit.t_start, g_ttb - 0.0005, 0, 0.0005 + 1e-9);
    } else {
      CHECK("transient driver with a dwell event", 0);
    }
  }
  autobal_transient_free(tr);
  autobal_rotor_free(R);
}

/* Subcritical: below the first resonance the balls gather on the heavy side at the
 * angle where the displacement of D (steady response to the total unbalance) points
 * along them: the tangential force on the balls (3.13) vanishes. */
static double eq_residual(const autobal_rotor_params *p, double psi, double Q[8]) {
  const double s0 = p->plane[0].m0 * p->plane[0].r0;
  double sre = s0, sim = 0.0, d = p->plane[0].d, uD, vD;
  size_t i;
  for (i = 0; i < p->plane[0].n_balls; i++) {
    sre += p->plane[0].ball_mass[i] * p->plane[0].ball_radius[i] * cos(psi);
    sim += p->plane[0].ball_mass[i] * p->plane[0].ball_radius[i] * sin(psi);
  }
  steady_response(p, &sre, &sim, &d, 1, Q);
  /* position of D in the rotor axes (= fixed axes at t = 0) */
  uD = Q[0] + d * Q[6];
  vD = Q[2] - d * Q[4];
  return wrap(atan2(vD, uD) - psi);
}

static void test_subcritical(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor *R;
  double y[12], out[32], Q[8], m0, m1, lo, hi, root;
  int i;
  printf("-- subcritical run (omega = 100 < 157.5 rad/s): balls go to the heavy side\n");
  p.omega = 100.0;
  R = autobal_rotor_alloc(&p, NULL);
  if (R == NULL) return;
  autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, 12);
  m0 = autobal_rotor_balance_monitor(R, AUTOBAL_ROTOR_FIXED, 0.0, y);
  CHECK("30 s integrated", integrate(autobal_rotor_rhs, R, 0.0, 30.0, y, 1e-10, 1e-12) == 0);
  autobal_rotor_outputs(R, AUTOBAL_ROTOR_FIXED, 30.0, y, out, autobal_rotor_output_count(R));
  m1 = out[8];
  CHECK_CLOSE("balls together (psi_1 - psi_2, rad)", wrap(out[13] - out[19]), 0.0, 0, 1e-6);
  CHECK("residual unbalance grew", m1 > m0 && m1 > 1.0);
  CHECK_CLOSE("|s| = |m0 r0 + 2 m r e^{i psi}| / m0 r0",
              m1, hypot(0.002 + 0.01 * cos(out[13]), 0.01 * sin(out[13])) / 0.002, 1e-9, 0);
  CHECK("balls on the heavy side (cos psi > 0)", cos(out[13]) > 0.0);
  /* equilibrium angle from the closed-form steady response, by bisection on
   * [-pi/2, pi/2] (eq_residual changes sign there), independent of the transient */
  lo = -0.5 * M_PI;
  hi = 0.5 * M_PI;
  CHECK("equilibrium bracketed", eq_residual(&p, lo, Q) * eq_residual(&p, hi, Q) < 0.0);
  for (i = 0; i < 100; i++) {
    const double mid = 0.5 * (lo + hi);
    if (eq_residual(&p, mid, Q) * eq_residual(&p, lo, Q) > 0.0) lo = mid;
    else hi = mid;
  }
  root = 0.5 * (lo + hi);
  printf("     equilibrium angle of the balls from the steady response: %.9f rad\n", root);
  CHECK_CLOSE("transient ball angle = equilibrium of the steady response (rad)", out[13], root, 0, 1e-6);
  eq_residual(&p, root, Q);
  CHECK_CLOSE("rotor amplitude = closed form |Q_x| (m)", out[0], hypot(Q[0], Q[1]), 1e-6, 0);
  autobal_rotor_free(R);
}

static void test_outputs(void) {
  autobal_rotor_params p = two_plane_params();
  autobal_rotor *R = autobal_rotor_alloc(&p, NULL);
  double y[MAXDIM], yr[MAXDIM], o1[64], o2[64], s[4];
  char name[64], prev[64][64];
  const char *unit = NULL;
  size_t n, k, dim, i;
  int uniq = 1, wrapped = 1, same = 1;
  const double t = 0.37;
  printf("-- derived outputs: layout, names, frames\n");
  if (R == NULL) return;
  n = autobal_rotor_output_count(R);
  dim = autobal_rotor_dim(R);
  CHECK("output count = 3 + 7 planes + 6 balls", n == 3 + 7 * 2 + 6 * 5);
  random_state(R, y);
  autobal_rotor_convert_state(R, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, t, y, yr, dim);
  CHECK_STATUS("outputs (fixed)", autobal_rotor_outputs(R, AUTOBAL_ROTOR_FIXED, t, y, o1, n), AUTOBAL_SUCCESS);
  CHECK_STATUS("outputs (rotating)", autobal_rotor_outputs(R, AUTOBAL_ROTOR_ROTATING, t, yr, o2, n), AUTOBAL_SUCCESS);
  for (k = 0; k < n; k++)
    if (fabs(o1[k] - o2[k]) > 1e-12 * fmax(1.0, fabs(o1[k]))) same = 0;
  CHECK("fixed and rotating states give the same outputs", same);
  CHECK_CLOSE("amp_G", o1[0], hypot(y[0], y[1]), 1e-15, 0);
  CHECK_CLOSE("amp_L: point p = -l_L", o1[1], hypot(y[0] - 0.2 * y[3], y[1] + 0.2 * y[2]), 1e-15, 0);
  CHECK_CLOSE("amp_R: point p = +l_R", o1[2], hypot(y[0] + 0.15 * y[3], y[1] - 0.15 * y[2]), 1e-15, 0);
  CHECK_CLOSE("p2_amp_D: point p = d_2", o1[3 + 7 + 6], hypot(y[0] - 0.12 * y[3], y[1] + 0.12 * y[2]), 1e-15, 0);
  {
    /* s_u, s_v of plane 1 from (3.1) with absolute angles */
    double su = 0.002 * cos(500 * t), sv = 0.002 * sin(500 * t);
    for (i = 0; i < 2; i++) {
      su += tp_m1[i] * tp_r1[i] * cos(y[8 + i]);
      sv += tp_m1[i] * tp_r1[i] * sin(y[8 + i]);
    }
    CHECK_CLOSE("p1_s_u (3.1)", o1[3], su, 1e-12, 1e-17);
    CHECK_CLOSE("p1_s_v (3.1)", o1[4], sv, 1e-12, 1e-17);
    CHECK_CLOSE("|s| invariant: hypot(s_u, s_v) = hypot(s_xi, s_eta)", hypot(o1[3], o1[4]), hypot(o1[5], o1[6]), 1e-12, 0);
    CHECK_CLOSE("p1_s_rel = |s| / m0 r0", o1[8], o1[7] / 0.002, 1e-15, 0);
    CHECK_STATUS("plane_unbalance", autobal_rotor_plane_unbalance(R, 1, AUTOBAL_ROTOR_FIXED, t, y, s), AUTOBAL_SUCCESS);
    CHECK_CLOSE("plane_unbalance p2 s_xi = output", s[2], o1[3 + 7 + 2], 1e-15, 0);
    CHECK_CLOSE("monitor = max_j s_rel", autobal_rotor_balance_monitor(R, AUTOBAL_ROTOR_FIXED, t, y),
                fmax(o1[8], o1[3 + 7 + 5]), 1e-15, 0);
  }
  {
    /* The outputs and the monitor, bit for bit, against their definitions written out here in
     * the order of operations of the documented formulas (eqs. (3.10), (3.11); ball angles wrapped
     * by w = a - 2 pi ceil((a - pi) / 2 pi), folded to (-pi, pi]): cos and sin of psi0 and of
     * phi_0 = omega t, computed per plane in the definition, are computed once by the library, and
     * the wrap skips its formula for |a| <= 3.  States: 400, both frames, ball angles in
     * [-12, 12] and the edges +-0, +-3, +-pi and their neighbours. */
    const double edges[] = {0.0, -0.0, 3.0, -3.0, nextafter(3.0, 4.0), -nextafter(3.0, 4.0), M_PI, -M_PI,
                            nextafter(M_PI, 0.0), -nextafter(M_PI, 0.0), 1e-300, -2.5e-9, 7.0, -7.0};
    const size_t ne = sizeof edges / sizeof edges[0];
    double yt[MAXDIM];
    size_t trial, nbad_s = 0, nbad_w = 0, nbad_m = 0;
    for (trial = 0; trial < 400; trial++) {
      const int frame = trial % 2 ? AUTOBAL_ROTOR_ROTATING : AUTOBAL_ROTOR_FIXED;
      const double tt = 0.013 * (double)trial, wt = p.omega * tt;
      double oo[64], mon_def = 0.0, mon;
      size_t j2, kb = 0;
      random_state(R, yt);
      for (k = 0; k < 5; k++) {
        const double e = edges[(trial * 5 + k) % ne];
        yt[8 + k] = trial % 3 == 0 ? e : urand(-12.0, 12.0);
      }
      if (autobal_rotor_outputs(R, frame, tt, yt, oo, n) != AUTOBAL_SUCCESS) {
        nbad_s++;
        continue;
      }
      for (j2 = 0; j2 < 2; j2++) {
        const autobal_rotor_plane *pl = &p.plane[j2];
        double sxi = pl->m0 * pl->r0 * cos(pl->psi0), seta = pl->m0 * pl->r0 * sin(pl->psi0), def[4];
        const double shift = frame == AUTOBAL_ROTOR_FIXED ? wt : 0.0;
        for (i = 0; i < pl->n_balls; i++, kb++) {
          const double psi = yt[8 + kb] - shift, mr = pl->ball_mass[i] * pl->ball_radius[i];
          sxi += mr * cos(psi);
          seta += mr * sin(psi);
        }
        def[0] = sxi * cos(wt) - seta * sin(wt);
        def[1] = sxi * sin(wt) + seta * cos(wt);
        def[2] = sxi;
        def[3] = seta;
        if (memcmp(def, oo + 3 + 7 * j2, sizeof def) != 0 || oo[3 + 7 * j2 + 4] != hypot(sxi, seta)) nbad_s++;
        if (oo[3 + 7 * j2 + 5] > mon_def) mon_def = oo[3 + 7 * j2 + 5];
      }
      mon = autobal_rotor_balance_monitor(R, frame, tt, yt);
      if (memcmp(&mon, &mon_def, sizeof mon) != 0) nbad_m++;
      for (k = 0; k < 5; k++) {
        const double *b = oo + 3 + 14 + 6 * k;
        double wdef[2];
        int q;
        for (q = 0; q < 2; q++) {
          const double a = b[2 * q];
          double w = a - 2.0 * M_PI * ceil((a - M_PI) / (2.0 * M_PI));
          if (w <= -M_PI) w += 2.0 * M_PI;
          if (w > M_PI) w -= 2.0 * M_PI;
          wdef[q] = w;
        }
        if (memcmp(&wdef[0], &b[1], sizeof(double)) != 0 || memcmp(&wdef[1], &b[3], sizeof(double)) != 0) {
          if (nbad_w++ < 3) printf("     wrap(%.17g) = %.17g, definition %.17g\n", b[2], b[3], wdef[1]);
        }
      }
    }
    CHECK("s_u, s_v, s_xi, s_eta, s_abs of both planes = (3.10), (3.11) as written, bit for bit (400 states)",
          nbad_s == 0);
    CHECK("monitor = max_j s_rel, bit for bit (400 states)", nbad_m == 0);
    CHECK("phi_w, psi_w = the wrap formula, bit for bit (2000 angles each, edges +-0, +-3, +-pi)", nbad_w == 0);
  }
  for (k = 0; k < 5; k++) {
    const double *b = o1 + 3 + 14 + 6 * k;
    if (!(b[1] > -M_PI && b[1] <= M_PI && b[3] > -M_PI && b[3] <= M_PI)) wrapped = 0;
    if (fabs(wrap(b[1] - b[0])) > 1e-9 || fabs(wrap(b[3] - b[2])) > 1e-9) wrapped = 0;
    if (b[0] != y[8 + k] || fabs(b[2] - (y[8 + k] - 500 * t)) > 1e-12) wrapped = 0;
    if (b[4] != y[13 + k] || fabs(b[5] - (y[13 + k] - 500)) > 1e-12) wrapped = 0;
  }
  CHECK("ball angles: wrapped in (-pi, pi], equal mod 2 pi, psi = phi - omega t", wrapped);
  for (k = 0; k < n && k < 64; k++) {
    autobal_rotor_output_name(R, k, name, sizeof name, &unit);
    for (i = 0; i < k; i++)
      if (strcmp(prev[i], name) == 0) uniq = 0;
    snprintf(prev[k], sizeof prev[k], "%s", name);
  }
  CHECK("output names unique", uniq);
  autobal_rotor_output_name(R, 3 + 14 + 6 * 3 + 3, name, sizeof name, &unit);
  CHECK("name of plane 2 ball 2 psi_w", strcmp(name, "p2_b2_psi_w") == 0 && strcmp(unit, "rad") == 0);
  autobal_rotor_output_name(R, 3 + 7 + 5, name, sizeof name, &unit);
  CHECK("name p2_s_rel dimensionless", strcmp(name, "p2_s_rel") == 0 && strcmp(unit, "1") == 0);
  CHECK_STATUS("output name out of range", autobal_rotor_output_name(R, n, name, sizeof name, &unit), AUTOBAL_EINVAL);
  CHECK_STATUS("outputs: wrong count", autobal_rotor_outputs(R, AUTOBAL_ROTOR_FIXED, t, y, o1, n - 1), AUTOBAL_EINVAL);
  CHECK_STATUS("outputs: bad frame", autobal_rotor_outputs(R, 7, t, y, o1, n), AUTOBAL_EINVAL);
  CHECK_STATUS("plane_unbalance: bad plane", autobal_rotor_plane_unbalance(R, 2, AUTOBAL_ROTOR_FIXED, t, y, s), AUTOBAL_EINVAL);
  CHECK("monitor: bad frame gives NaN", isnan(autobal_rotor_balance_monitor(R, 5, t, y)));
  autobal_rotor_free(R);
  {
    const double ts[6] = {0, 1, 2, 3, 4, 5}, mo[6] = {5, 0.5, 2, 0.9, 0.1, 0.05};
    CHECK_CLOSE("time_to_balance: last entry below stays", autobal_rotor_time_to_balance(ts, mo, 6, 1.0), 3.0, 0, 0);
    CHECK("time_to_balance: never settles -> NaN", isnan(autobal_rotor_time_to_balance(ts, mo, 6, 0.01)));
    CHECK_CLOSE("time_to_balance: always below", autobal_rotor_time_to_balance(ts, mo, 6, 10.0), 0.0, 0, 0);
  }
}

static void test_lumped_input(void) {
  autobal_rotor_params h = two_plane_params(), l;
  autobal_rotor *A, *B;
  double y[MAXDIM], fa[MAXDIM], fb[MAXDIM], oa[64], ob[64], worst = 0.0;
  size_t k;
  printf("-- lumped input gives the same model as the hardware values\n");
  l = h;
  l.input = AUTOBAL_ROTOR_LUMPED;
  autobal_rotor_lumped_from_hardware(&h.hw, &l.lumped, NULL);
  memset(&l.hw, 0, sizeof l.hw);
  l.hw.l_L = NAN;
  l.hw.l_R = NAN;
  A = autobal_rotor_alloc(&h, NULL);
  B = autobal_rotor_alloc(&l, NULL);
  CHECK("both alloc", A && B);
  if (A && B) {
    random_state(A, y);
    autobal_rotor_rhs(0.3, y, fa, A);
    autobal_rotor_rhs(0.3, y, fb, B);
    for (k = 0; k < autobal_rotor_dim(A); k++) worst = fmax(worst, fabs(fa[k] - fb[k]));
    CHECK_CLOSE("identical right-hand sides", worst, 0.0, 0, 0);
    autobal_rotor_outputs(B, AUTOBAL_ROTOR_FIXED, 0.3, y, ob, autobal_rotor_output_count(B));
    autobal_rotor_outputs(A, AUTOBAL_ROTOR_FIXED, 0.3, y, oa, autobal_rotor_output_count(A));
    CHECK("support outputs NaN with unknown l_L, l_R", isnan(ob[1]) && isnan(ob[2]) && !isnan(oa[1]));
    CHECK("other outputs available", ob[0] == oa[0]);
  }
  autobal_rotor_free(A);
  autobal_rotor_free(B);
}

/* Failure of the right-hand sides when the effective mass matrix is (numerically)
 * singular, with parameters that pass validation. */
static int rhs_status_at(autobal_rotor *R, int frame, double phi) {
  double y[MAXDIM], f[MAXDIM];
  const size_t dim = autobal_rotor_dim(R);
  autobal_rotor_initial_state(R, frame, 0.0, y, dim); /* t = 0: phi = psi */
  y[8] = phi;
  return frame == AUTOBAL_ROTOR_FIXED ? autobal_rotor_rhs(0.0, y, f, R)
                                      : autobal_rotor_rhs_rotating(0.0, y, f, R);
}

static void test_mass_matrix_failures(void) {
  static double m1[1], r1[1] = {0.1}, h1[1] = {0.1}, psi1[1] = {0.0};
  autobal_rotor_params p = autobal_rotor_params_default();
  const double M = p.hw.M_k + p.hw.m_p, A = p.hw.A_k + p.hw.A_p, d = p.plane[0].d;
  const double g = 1.0 / M + d * d / A; /* spec: u_D'' per unit force along eu or ev */
  autobal_error err;
  autobal_rotor *R;
  int c, j, fails, frame;
  printf("-- effective mass matrix singular to working precision: the rhs fails cleanly\n");
  /* One ball of mass m in the PAPER model: C = -m (s, -c)(s, -c)^T, so I + g C has the
   * eigenvalues 1 and 1 - g m at every ball angle; the mass matrix is singular to
   * working precision when 1 - g m = 1e-15 (params_check only requires g m < 1). */
  p.plane[0].n_balls = 1;
  p.plane[0].ball_mass = m1;
  p.plane[0].ball_radius = r1;
  p.plane[0].ball_damping = h1;
  p.plane[0].ball_psi = psi1;
  p.plane[0].ball_rate = NULL;
  for (c = 0; c < 4; c++) {
    /* c = 0, 1: one plane; c = 2, 3: a second plane without balls (4x4 path) */
    const int two = c >= 2, near = (c % 2) == 0;
    const double gap = near ? 1e-15 : 1e-9;
    char label[200];
    m1[0] = (1.0 - gap) / g;
    p.n_planes = two ? 2 : 1;
    if (two) {
      p.plane[1] = autobal_rotor_params_default().plane[0];
      p.plane[1].d = -0.12;
      p.plane[1].m0 = 0.01;
      p.plane[1].r0 = 0.09;
      p.plane[1].n_balls = 0;
      p.plane[1].ball_mass = p.plane[1].ball_radius = p.plane[1].ball_damping = NULL;
      p.plane[1].ball_psi = p.plane[1].ball_rate = NULL;
    }
    R = autobal_rotor_alloc(&p, &err);
    snprintf(label, sizeof label, "%s, one ball with 1 - g m = %g: parameters accepted",
             two ? "two planes" : "one plane", gap);
    CHECK(label, R != NULL && err.status >= 0);
    if (R == NULL) continue;
    fails = 0;
    if (!two) {
      /* every angle, both frames */
      for (frame = 0; frame < 2; frame++)
        for (j = 0; j < 16; j++)
          fails += rhs_status_at(R, frame, 2.0 * M_PI * j / 16.0 + 0.05) == GSL_EBADFUNC;
      snprintf(label, sizeof label, "   calls that fail (16 ball angles x 2 frames; want %d)",
               near ? 32 : 0);
      CHECK_CLOSE(label, fails, near ? 32 : 0, 0, 0);
    } else {
      /* Cholesky of the 4x4 matrix, ball at phi = pi/2: the near-null vector
       * D^-1 eu has beta-component d/A, and the last pivot relative to a_33 is
       * about (1 - g m) g^2 M A / d^2 = 4.2 (1 - g m) */
      for (frame = 0; frame < 2; frame++) fails += rhs_status_at(R, frame, 0.5 * M_PI) == GSL_EBADFUNC;
      snprintf(label, sizeof label, "   calls that fail (ball at pi/2, 2 frames; want %d)", near ? 2 : 0);
      CHECK_CLOSE(label, fails, near ? 2 : 0, 0, 0);
    }
    if (near) CHECK_MSG("   message", autobal_rotor_errmsg(R), "not positive definite");
    if (!near) {
      /* well-posed but ill-conditioned (cond ~ 1e9): still the direct solve's answer */
      double y[MAXDIM], f[MAXDIM], qdd[4], phidd[MAXDIM], e = 0.0, sc = 0.0;
      size_t k;
      autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, autobal_rotor_dim(R));
      y[8] = 0.7;
      y[4] = 0.01;
      if (autobal_rotor_rhs(0.0, y, f, R) == 0 && direct_solve(R, 0.0, y, qdd, phidd) == 0) {
        for (k = 0; k < 4; k++) {
          sc = fmax(sc, fabs(qdd[k]));
          e = fmax(e, fabs(f[4 + k] - qdd[k]));
        }
        CHECK_CLOSE("   q'' vs direct (4+N) LU, relative (cond ~ 1e9)", e / sc, 0.0, 0, 1e-5);
      } else {
        CHECK("   rhs and direct solve succeed", 0);
      }
    }
    autobal_rotor_free(R);
  }
  /* FULL model: I + g C >= I analytically, but a ball of 1e300 kg (valid: any
   * positive finite mass) overflows the products of the 2x2 solve */
  p = autobal_rotor_params_default();
  p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  p.plane[0].n_balls = 1;
  m1[0] = 1e300;
  p.plane[0].ball_mass = m1;
  p.plane[0].ball_radius = r1;
  p.plane[0].ball_damping = h1;
  p.plane[0].ball_psi = psi1;
  p.plane[0].ball_rate = NULL;
  R = autobal_rotor_alloc(&p, &err);
  CHECK("FULL, one ball of 1e300 kg: parameters accepted", R != NULL && err.status >= 0);
  if (R != NULL) {
    fails = 0;
    for (frame = 0; frame < 2; frame++)
      for (j = 0; j < 4; j++) fails += rhs_status_at(R, frame, 1.0 + j) == GSL_EBADFUNC;
    CHECK_CLOSE("   calls that fail (overflow; 4 angles x 2 frames)", fails, 8, 0, 0);
    CHECK_MSG("   message", autobal_rotor_errmsg(R), "not finite");
  }
  autobal_rotor_free(R);
  /* NaN state with two planes (the 4x4 path) */
  p = two_plane_params();
  R = autobal_rotor_alloc(&p, NULL);
  if (R != NULL) {
    double y[MAXDIM], f[MAXDIM];
    const size_t dim = autobal_rotor_dim(R);
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, dim);
    y[8 + 3] = NAN; /* a ball of the second plane */
    CHECK_STATUS("two planes, NaN ball angle: fixed-frame rhs fails", autobal_rotor_rhs(0.0, y, f, R),
                 GSL_EBADFUNC);
    CHECK_MSG("   message", autobal_rotor_errmsg(R), "fixed-frame");
    CHECK_STATUS("two planes, NaN ball angle: rotating-frame rhs fails",
                 autobal_rotor_rhs_rotating(0.0, y, f, R), GSL_EBADFUNC);
    CHECK_MSG("   message", autobal_rotor_errmsg(R), "rotating-frame");
  }
  autobal_rotor_free(R);
}

static void test_errors(void) {
  autobal_rotor_params p;
  autobal_error err;
  autobal_rotor *R;
  static const double negr[2] = {0.1, -0.1}, zerom[2] = {0.05, 0.0}, nanpsi[2] = {1.0, NAN};
  static const double negh[2] = {0.1, -0.1}, heavy[2] = {4.0, 4.0};
  printf("-- validation and failure paths\n");
#define EXPECT_BAD(label, needle)                                                  \
  do {                                                                             \
    R = autobal_rotor_alloc(&p, &err);                                             \
    CHECK(label ": alloc refused", R == NULL);                                     \
    CHECK_STATUS(label ": status", err.status, AUTOBAL_EINVAL);                    \
    CHECK_MSG(label ": message", err.message, needle);                             \
    CHECK_STATUS(label ": params_check agrees", autobal_rotor_params_check(&p, NULL), AUTOBAL_EINVAL); \
    autobal_rotor_free(R);                                                         \
  } while (0)
  R = autobal_rotor_alloc(NULL, &err);
  CHECK("NULL params", R == NULL && err.status == AUTOBAL_EINVAL);
  p = autobal_rotor_params_default();
  p.plane[0].ball_radius = negr;
  EXPECT_BAD("ball on a negative radius", "plane[0].ball_radius[1] = -0.1");
  p = autobal_rotor_params_default();
  p.plane[0].ball_mass = zerom;
  EXPECT_BAD("zero ball mass", "plane[0].ball_mass[1]");
  p = autobal_rotor_params_default();
  p.plane[0].ball_damping = negh;
  EXPECT_BAD("negative ball damping", "ball_damping[1]");
  p = autobal_rotor_params_default();
  p.plane[0].ball_psi = nanpsi;
  EXPECT_BAD("NaN initial angle", "ball_psi[1]");
  p = autobal_rotor_params_default();
  p.hw.M_k = 0.0;
  EXPECT_BAD("zero housing mass", "hw.M_k = 0");
  p = autobal_rotor_params_default();
  p.hw.c_Rx = -1.0;
  EXPECT_BAD("negative stiffness", "hw.c_Rx");
  p = autobal_rotor_params_default();
  p.hw.h_Lz = INFINITY;
  EXPECT_BAD("infinite viscosity", "hw.h_Lz");
  p = autobal_rotor_params_default();
  p.hw.l_L = -0.2;
  p.hw.l_R = 0.1;
  EXPECT_BAD("supports in the wrong order", "l_L + l_R > 0");
  p = autobal_rotor_params_default();
  p.omega = NAN;
  EXPECT_BAD("NaN omega", "omega");
  p = autobal_rotor_params_default();
  p.n_planes = 0;
  EXPECT_BAD("no planes", "n_planes = 0");
  p = autobal_rotor_params_default();
  p.n_planes = 3;
  EXPECT_BAD("three planes", "n_planes = 3");
  p = autobal_rotor_params_default();
  p.plane[0].m0 = -0.01;
  EXPECT_BAD("negative unbalance mass", "plane[0].m0");
  p = autobal_rotor_params_default();
  p.plane[0].ball_mass = NULL;
  EXPECT_BAD("NULL ball array", "NULL");
  p = autobal_rotor_params_default();
  p.input = 7;
  EXPECT_BAD("bad input kind", "input = 7");
  p = autobal_rotor_params_default();
  p.inertia = 3;
  EXPECT_BAD("bad inertia model", "inertia = 3");
  p = autobal_rotor_params_default();
  p.axial = 2;
  EXPECT_BAD("bad axial flag", "axial = 2");
  p = autobal_rotor_params_default();
  p.q0[2] = NAN;
  EXPECT_BAD("NaN initial alpha", "q0[2]");
  p = autobal_rotor_params_default();
  p.plane[0].ball_mass = heavy;
  EXPECT_BAD("balls too heavy for the paper model", "too heavy");
  p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  R = autobal_rotor_alloc(&p, &err);
  CHECK("heavy balls accepted by the FULL inertia model", R != NULL && err.status == AUTOBAL_SUCCESS);
  autobal_rotor_free(R);
  p = autobal_rotor_params_default();
  p.input = AUTOBAL_ROTOR_LUMPED;
  p.lumped.c_xbeta = 5e4; /* c_xbeta^2 > c_x c_beta */
  EXPECT_BAD("lumped stiffness not positive semidefinite", "c_xbeta");
  p = autobal_rotor_params_default();
  p.input = AUTOBAL_ROTOR_LUMPED;
  p.lumped.A = 0.0;
  EXPECT_BAD("lumped zero inertia", "lumped.A");
  p = autobal_rotor_params_default();
  p.input = AUTOBAL_ROTOR_LUMPED;
  p.hw.l_L = INFINITY;
  EXPECT_BAD("lumped with infinite l_L", "hw.l_L");
  {
    autobal_rotor_lumped L;
    autobal_rotor_hardware hw = autobal_rotor_params_default().hw;
    hw.A_p = -1.0;
    CHECK_STATUS("lumped_from_hardware validates", autobal_rotor_lumped_from_hardware(&hw, &L, &err), AUTOBAL_EINVAL);
    CHECK_MSG("lumped_from_hardware message", err.message, "hw.A_p");
  }
  /* warnings: the balls cannot cancel the unbalance */
  p = autobal_rotor_params_default();
  p.plane[0].m0 = 0.05; /* m0 r0 = 0.005 < 2 m r = 0.01: fine */
  CHECK_STATUS("enough balancing capacity", autobal_rotor_params_check(&p, &err), AUTOBAL_SUCCESS);
  p.plane[0].m0 = 0.11;
  CHECK_STATUS("sum m r < m0 r0: warning", autobal_rotor_params_check(&p, &err), AUTOBAL_WARNING);
  CHECK_MSG("warning names the plane", err.message, "plane[0]");
  CHECK_MSG("warning names the sums", err.message, "sum m_i r_i");
  {
    static const double unequal[2] = {0.09, 0.01};
    p = autobal_rotor_params_default();
    p.plane[0].ball_mass = unequal;
    CHECK_STATUS("heaviest ball dominates: warning", autobal_rotor_params_check(&p, &err), AUTOBAL_WARNING);
    CHECK_MSG("dominant-ball warning", err.message, "heaviest ball");
  }
  /* failing right-hand side */
  p = autobal_rotor_params_default();
  R = autobal_rotor_alloc(&p, &err);
  if (R) {
    double y[12], f[12];
    int i;
    autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, 12);
    y[9] = NAN;
    CHECK_STATUS("rhs with a NaN state fails", autobal_rotor_rhs(0.0, y, f, R), GSL_EBADFUNC);
    CHECK_MSG("rhs failure recorded on the handle", autobal_rotor_errmsg(R), "right-hand side failed");
    CHECK_STATUS("rotating rhs with a NaN state fails", autobal_rotor_rhs_rotating(0.0, y, f, R), GSL_EBADFUNC);
    CHECK_MSG("rotating rhs failure message", autobal_rotor_errmsg(R), "rotating-frame");
    for (i = 0; i < 12; i++) y[i] = 0.0;
    y[4] = INFINITY;
    CHECK_STATUS("rhs with an infinite rate fails", autobal_rotor_rhs(0.0, y, f, R), GSL_EBADFUNC);
    CHECK_STATUS("set_omega NaN", autobal_rotor_set_omega(R, NAN), AUTOBAL_EINVAL);
    CHECK_MSG("set_omega message", autobal_rotor_errmsg(R), "omega");
    CHECK_STATUS("set_omega", autobal_rotor_set_omega(R, 300.0), AUTOBAL_SUCCESS);
    CHECK_CLOSE("omega changed", autobal_rotor_omega(R), 300.0, 0, 0);
    CHECK_STATUS("initial state: wrong dim", autobal_rotor_initial_state(R, AUTOBAL_ROTOR_FIXED, 0.0, y, 11), AUTOBAL_EINVAL);
    CHECK_STATUS("initial state: bad frame", autobal_rotor_initial_state(R, 9, 0.0, y, 12), AUTOBAL_EINVAL);
    CHECK_STATUS("convert: wrong dim", autobal_rotor_convert_state(R, 0, 1, 0.0, y, f, 13), AUTOBAL_EINVAL);
  }
  autobal_rotor_free(R);
  autobal_rotor_free(NULL);
  CHECK("errmsg(NULL) not NULL", autobal_rotor_errmsg(NULL) != NULL);
  CHECK("dim(NULL) = 0", autobal_rotor_dim(NULL) == 0);
#undef EXPECT_BAD
}

/* ---- the branch-free sin/cos of the ball loops (src/fastmath.h) ------------------- */

/* Size of one unit in the last place of v (double), at least the smallest subnormal. */
static double ulp_of(double v) {
  int e;
  double u;
  if (v == 0.0 || !isfinite(v)) return DBL_TRUE_MIN;
  (void)frexp(v, &e);
  u = ldexp(1.0, e - DBL_MANT_DIG);
  return u < DBL_TRUE_MIN ? DBL_TRUE_MIN : u;
}

/* |got - want| in units of ulp(want), want given in long double (x86-64: 64-bit
 * significand, so want is ~2^-11 ulp of a double from the true value). */
static double ulp_err(double got, long double want) {
  return (double)fabsl((long double)got - want) / ulp_of((double)want);
}

typedef struct sincos_err {
  double libm_s, libm_c; /* max ulp against libm's sin, cos */
  double ref_s, ref_c;   /* max ulp against sinl, cosl */
  double x_worst;        /* argument of the largest of the four */
  size_t n, nbad;        /* arguments, fallbacks reported */
  int bit_mismatch;      /* array vs scalar (autobal_sincos1) or odd symmetry broken */
} sincos_err;

/* Evaluate n arguments through autobal_sincos_array (in blocks of up to 64, odd
 * lengths too) and accumulate the errors; also the scalar entry point (must give
 * the same bits) and the symmetry sin(-x) = -sin(x), cos(-x) = cos(x) (bitwise: the
 * reduction and the kernels are odd/even operation by operation). */
static void sincos_accumulate(const double *x, size_t n, sincos_err *e) {
  double s[64], c[64], xn[64], sm[64], cm[64];
  size_t i0, i;
  for (i0 = 0; i0 < n; i0 += 61) {
    const size_t m = n - i0 < 61 ? n - i0 : 61;
    e->nbad += autobal_sincos_array(x + i0, s, c, m);
    for (i = 0; i < m; i++) xn[i] = -x[i0 + i];
    (void)autobal_sincos_array(xn, sm, cm, m);
    for (i = 0; i < m; i++) {
      const double xi = x[i0 + i];
      double s1, c1, es, ec, rs, rc;
      autobal_sincos1(xi, &s1, &c1);
      if (memcmp(&s1, &s[i], sizeof s1) != 0 || memcmp(&c1, &c[i], sizeof c1) != 0) e->bit_mismatch = 1;
      if (!isnan(xi) && (sm[i] != -s[i] || cm[i] != c[i])) e->bit_mismatch = 1;
      es = ulp_err(s[i], (long double)sin(xi));
      ec = ulp_err(c[i], (long double)cos(xi));
      rs = ulp_err(s[i], sinl((long double)xi));
      rc = ulp_err(c[i], cosl((long double)xi));
      if (fmax(fmax(es, ec), fmax(rs, rc)) > fmax(fmax(e->libm_s, e->libm_c), fmax(e->ref_s, e->ref_c)))
        e->x_worst = xi;
      e->libm_s = fmax(e->libm_s, es);
      e->libm_c = fmax(e->libm_c, ec);
      e->ref_s = fmax(e->ref_s, rs);
      e->ref_c = fmax(e->ref_c, rc);
    }
    e->n += m;
  }
}

static void sincos_report(const char *label, const sincos_err *e) {
  char what[240];
  printf("     %s: %zu arguments, worst at x = %.17g\n", label, e->n, e->x_worst);
  /* fdlibm's kernels with an exact reduction: < 1 ulp from the true value; libm (glibc)
   * is itself < 1 ulp, so the two may differ by up to 2 ulp */
  snprintf(what, sizeof what, "   max error of sin, ulp against sinl (%d-bit long double)", LDBL_MANT_DIG);
  if (LDBL_MANT_DIG >= 64) CHECK_CLOSE(what, e->ref_s, 0.0, 0, 1.0);
  snprintf(what, sizeof what, "   max error of cos, ulp against cosl (%d-bit long double)", LDBL_MANT_DIG);
  if (LDBL_MANT_DIG >= 64) CHECK_CLOSE(what, e->ref_c, 0.0, 0, 1.0);
  CHECK_CLOSE("   max |sin - libm sin|, ulp", e->libm_s, 0.0, 0, 2.0);
  CHECK_CLOSE("   max |cos - libm cos|, ulp", e->libm_c, 0.0, 0, 2.0);
  CHECK("   array = scalar autobal_sincos1 bit for bit; sin odd, cos even bit for bit",
        !e->bit_mismatch);
}

static void test_sincos_kernel(void) {
  /* ranges of |x| (random signs); the last ones reach the fast path's bound 2^21 */
  static const double lo[7] = {0.0, 0.78, 1.0, 10.0, 1e3, 1e5, 0x1p21 - 1024.0};
  static const double hi[7] = {0.78, 1.0, 10.0, 1e3, 1e5, 0x1p21, 0x1p21};
  /* the k with the closest approach of a double to k pi/2 in the binades 2^5 .. 2^21
   * (continued fractions of 2^(52-e) pi/2; |x - k pi/2| >= 6.2e-19 at k = 29), and small k */
  static const double khard[] = {1, 2, 3, 4, 5, 29, 58, 116, 232, 464, 928, 1856, 3712, 7424,
                                 29327, 204551, 409102, 1081409, 1335088};
  static double xs[4096];
  const long double pio2 = 1.570796326794896619231321691639751442L;
  sincos_err e;
  size_t r, i, n;
  printf("-- branch-free sin/cos (fastmath.h) against libm and long double\n");
  memset(&e, 0, sizeof e);
  for (r = 0; r < 7; r++) {
    size_t rep;
    for (rep = 0; rep < (r == 6 ? 4u : 20u); rep++) {
      for (i = 0; i < 4096; i++) {
        const double a = urand(lo[r], hi[r]);
        xs[i] = (i & 1u) ? -a : a;
      }
      sincos_accumulate(xs, 4096, &e);
    }
  }
  sincos_report("random arguments, |x| in [0, 2^21] (7 ranges)", &e);
  CHECK_CLOSE("   fallbacks to libm reported", (double)e.nbad, 0.0, 0, 0);
  /* next to multiples of pi/2: the nearest double to k pi/2 and 3 neighbours each side,
   * for the hard k and for 1000 more k spread up to 2^21 2/pi */
  memset(&e, 0, sizeof e);
  n = 0;
  for (i = 0; i < sizeof khard / sizeof khard[0] + 1000; i++) {
    const double k = i < sizeof khard / sizeof khard[0] ? khard[i] : floor(urand(1.0, 1335088.0));
    double x0 = (double)(k * pio2);
    int j;
    for (j = 0; j < 3; j++) x0 = nextafter(x0, 0.0);
    for (j = 0; j < 7; j++, x0 = nextafter(x0, INFINITY)) xs[n++] = (i & 1u) ? -x0 : x0;
    if (n + 7 > 4096) {
      sincos_accumulate(xs, n, &e);
      n = 0;
    }
  }
  sincos_accumulate(xs, n, &e);
  sincos_report("next to k pi/2 (sin or cos down to 6e-19)", &e);
  /* signed zeros, subnormals: sin x = x exactly, cos x = 1 */
  {
    static const double z[6] = {0.0, -0.0, DBL_TRUE_MIN, -DBL_TRUE_MIN, 1e-310, -1e-300};
    double s[6], c[6];
    int ok = 1;
    (void)autobal_sincos_array(z, s, c, 6);
    for (i = 0; i < 6; i++) ok = ok && s[i] == z[i] && c[i] == 1.0;
    CHECK("+-0, subnormals, 1e-300: sin x = x, cos x = 1", ok);
    CHECK("sin(+0) = +0, sin(-0) = -0 (sign bits)", !signbit(s[0]) && signbit(s[1]));
  }
  /* the bound: 2^21 itself is on the fast path; above it, NaN and inf go to libm */
  {
    static double xb[11];
    double s[11], c[11];
    size_t nb;
    int same = 1, nan_ok;
    xb[0] = 0x1p21;
    xb[1] = -0x1p21;
    xb[2] = nextafter(0x1p21, INFINITY);
    xb[3] = -nextafter(0x1p21, INFINITY);
    xb[4] = 3.0e6;
    xb[5] = 1.0e10;
    xb[6] = -1.0e22;
    xb[7] = DBL_MAX;
    xb[8] = NAN;
    xb[9] = INFINITY;
    xb[10] = -INFINITY;
    nb = autobal_sincos_array(xb, s, c, 11);
    CHECK_CLOSE("above 2^21 and non-finite: elements sent to libm", (double)nb, 9.0, 0, 0);
    CHECK("   +-2^21 (fast path) within 1 ulp of sinl, cosl",
          ulp_err(s[0], sinl(0x1p21L)) <= 1.0 && ulp_err(c[0], cosl(0x1p21L)) <= 1.0 &&
              s[1] == -s[0] && c[1] == c[0]);
    for (i = 2; i < 8; i++) same = same && s[i] == sin(xb[i]) && c[i] == cos(xb[i]);
    CHECK("   |x| > 2^21: libm's sin and cos exactly", same);
    nan_ok = isnan(s[8]) && isnan(c[8]) && isnan(s[9]) && isnan(c[9]) && isnan(s[10]) && isnan(c[10]);
    CHECK("   NaN and +-inf give NaN", nan_ok);
    /* the same through the scalar entry point */
    {
      double s1, c1;
      autobal_sincos1(xb[4], &s1, &c1);
      same = s1 == sin(xb[4]) && c1 == cos(xb[4]);
      autobal_sincos1(NAN, &s1, &c1);
      CHECK("   autobal_sincos1: libm above 2^21, NaN for NaN", same && isnan(s1) && isnan(c1));
    }
  }
  /* an independent identity: sin^2 + cos^2 = 1 (a few ulp of 1) */
  {
    double worst = 0.0, s, c;
    for (i = 0; i < 20000; i++) {
      autobal_sincos1(urand(-0x1p21, 0x1p21), &s, &c);
      worst = fmax(worst, fabs(s * s + c * c - 1.0));
    }
    CHECK_CLOSE("max |sin^2 + cos^2 - 1| over |x| <= 2^21", worst, 0.0, 0, 4.5e-16);
  }
}

/* The right-hand sides with ball angles (and omega t) near and beyond the fast
 * path's bound 2^21 rad (and mixed), against the direct (4+N) LU solve, which
 * uses libm: max |difference| / max |component| over q'' and over phi''. */
static double rhs_vs_direct_at(autobal_rotor *R, double t, const double *y, int *ok) {
  double f[MAXDIM], qdd[4], phidd[MAXDIM], sq = 0.0, sp = 0.0, dq = 0.0, dp = 0.0;
  const size_t N = autobal_rotor_n_balls_total(R);
  size_t k;
  if (autobal_rotor_rhs(t, y, f, R) != 0 || direct_solve(R, t, y, qdd, phidd) != 0) {
    *ok = 0;
    return INFINITY;
  }
  for (k = 0; k < 4; k++) {
    sq = fmax(sq, fabs(qdd[k]));
    dq = fmax(dq, fabs(f[4 + k] - qdd[k]));
  }
  for (k = 0; k < N; k++) {
    sp = fmax(sp, fabs(phidd[k]));
    dp = fmax(dp, fabs(f[8 + N + k] - phidd[k]));
    if (f[8 + k] != y[8 + N + k]) *ok = 0;
  }
  return N > 0 ? fmax(dq / sq, dp / sp) : dq / sq;
}

static void test_rhs_large_angles(void) {
  autobal_rotor_params ps[2];
  int c, s;
  printf("-- right-hand side with ball angles near and beyond 2^21 rad (libm fallback)\n");
  ps[0] = autobal_rotor_params_default();
  ps[1] = two_plane_params();
  for (c = 0; c < 2; c++) {
    autobal_rotor *R = autobal_rotor_alloc(&ps[c], NULL);
    const size_t N = R ? autobal_rotor_n_balls_total(R) : 0;
    double y[MAXDIM], worst[4] = {0.0, 0.0, 0.0, 0.0};
    int ok = 1, kind;
    size_t k;
    CHECK(c == 0 ? "default model" : "two planes", R != NULL);
    if (R == NULL) continue;
    for (kind = 0; kind < 4; kind++) {
      for (s = 0; s < 10; s++) {
        /* kind 0: all balls just below 2^21 (fast path), 1: all above (libm), 2: mixed,
         * 3 (default model, psi0 = 0): also omega t above 2^21 (t = 4200 s, omega t =
         * 2.1e6 rad exactly) */
        const double t = kind == 3 && c == 0 ? 4200.0 : urand(0, 3);
        random_state(R, y);
        for (k = 0; k < N; k++) {
          const int above = kind == 1 || ((kind == 2 || kind == 3) && (k + (size_t)s) % 2 == 1);
          y[8 + k] += above ? 0x1p21 + 40.0 : 0x1p21 - 40.0;
          if (kind == 1 && k == 0) y[8 + k] = -3.0e7 + y[8 + k]; /* far above, negative */
        }
        worst[kind] = fmax(worst[kind], rhs_vs_direct_at(R, t, y, &ok));
      }
    }
    CHECK("   rhs and direct solve ran; angle rows are copies of the rates", ok);
    CHECK_CLOSE("   balls at 2^21 - 40 rad (fast path): max relative |rhs - direct LU|", worst[0], 0.0, 0, 1e-10);
    CHECK_CLOSE("   balls at 2^21 + 40 rad and -3e7 rad (libm): max relative |rhs - direct LU|", worst[1],
                0.0, 0, 1e-10);
    CHECK_CLOSE("   mixed below/above 2^21: max relative |rhs - direct LU|", worst[2], 0.0, 0, 1e-10);
    if (c == 0)
      CHECK_CLOSE("   mixed, and omega t = 2.1e6 rad > 2^21: max relative |rhs - direct LU|", worst[3],
                  0.0, 0, 1e-10);
    autobal_rotor_free(R);
  }
}

int main(void) {
  gsl_set_error_handler_off();
  test_defaults();
  test_natural_frequencies();
  test_sincos_kernel();
  test_direct_solve();
  test_rhs_large_angles();
  test_one_plane_closed_form();
  test_frames_instantaneous();
  test_frames_transient();
  test_rotation_invariance();
  test_mirror();
  test_plane_split();
  test_no_balls_steady();
  test_energy();
  test_balanced_angles();
  test_supercritical();
  test_subcritical();
  test_outputs();
  test_lumped_input();
  test_errors();
  test_mass_matrix_failures();
  test_config_files();
  printf("summary: rhs vs direct solve %.3g; fixed vs rotating frame |dq| %.3g, |dangle| %.3g rad; "
         "steady response rel. error %.3g; energy-rate rel. error %.3g, drift %.3g; "
         "balanced angle error %.3g rad; time to balance %.2f s\n",
         g_max_direct, g_frame_diff_q, g_frame_diff_ang, g_steady_err, g_energy_rate_err,
         g_energy_drift, g_bal_err, g_ttb);
  return check_summary();
}
