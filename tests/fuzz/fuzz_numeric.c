/* fuzz_numeric.c: libFuzzer target for the library's numerical entry points (issue 19 item 3):
 * the polynomial root finder, the Routh-Hurwitz test, the pendulum verdict and the rotor's two
 * right-hand sides, on inputs no configuration check has filtered.  Byte 0 picks the entry
 * point; the rest are raw doubles (any bit pattern: NaN, inf, 1e300, subnormals) or, for the
 * rotor, factors 2^((b - 128) / 8) applied to the default parameters plus a raw finite state.
 *
 * A finding is a crash, a sanitizer report, a hang (libFuzzer -timeout) or a broken contract,
 * which calls abort():
 *  - autobal_poly_roots: SUCCESS with a non-finite root, or a status other than SUCCESS,
 *    EINVAL (bad input) and ENUMERIC;
 *  - autobal_poly_hurwitz: SUCCESS with a verdict outside the enum;
 *  - autobal_rotor_rhs / _rotating: 0 with a non-finite derivative, or a code other than 0 and
 *    GSL_EBADFUNC.
 * Replayed over tests/fuzz/corpus/numeric by CTest (fuzz_numeric_replay); fuzzed by run.sh. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/pendulum.h"
#include "autobal/rotor.h"
#include "autobal/stability.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  gsl_set_error_handler_off();
  return 0;
}

/* the k-th raw double of the input after the selector (0 past the end) */
static double raw(const uint8_t *d, size_t n, size_t k) {
  double v = 0.0;
  if (1 + 8 * (k + 1) <= n) memcpy(&v, d + 1 + 8 * k, 8);
  return v;
}
static double finite_raw(const uint8_t *d, size_t n, size_t k) {
  double v = raw(d, n, k);
  return isfinite(v) ? v : 0.0;
}
/* a factor 2^((b - 128)/8) from byte k after the selector (1 past the end) */
static double factor(const uint8_t *d, size_t n, size_t k) {
  return 1 + k < n ? exp2(((double)d[1 + k] - 128.0) / 8.0) : 1.0;
}

static void fuzz_roots(const uint8_t *d, size_t n) {
  size_t len = (n - 1) / 8, i;
  double c[AUTOBAL_POLY_MAXLEN], re[AUTOBAL_POLY_MAXLEN], im[AUTOBAL_POLY_MAXLEN];
  autobal_poly_workspace *w;
  int st;
  if (len < 2) return;
  if (len > 17) len = 17; /* degree <= 16 */
  for (i = 0; i < len; i++) c[i] = raw(d, n, i);
  w = autobal_poly_workspace_alloc(len - 1);
  if (!w) return;
  st = autobal_poly_roots(w, c, len, re, im, NULL);
  if (st == AUTOBAL_SUCCESS) {
    for (i = 0; i + 1 < len; i++)
      if (!isfinite(re[i]) || !isfinite(im[i])) abort();
  } else if (st != AUTOBAL_EINVAL && st != AUTOBAL_ENUMERIC) {
    abort();
  }
  autobal_poly_workspace_free(w);
}

static void fuzz_hurwitz(const uint8_t *d, size_t n) {
  size_t len = (n - 1) / 8, i;
  double c[AUTOBAL_POLY_MAXLEN];
  int verdict = -99, nrhp = -1, st;
  if (len < 1) return;
  if (len > AUTOBAL_POLY_MAXLEN) len = AUTOBAL_POLY_MAXLEN;
  for (i = 0; i < len; i++) c[i] = raw(d, n, i);
  st = autobal_poly_hurwitz(c, len, 1e-12, &verdict, &nrhp, NULL);
  if (st == AUTOBAL_SUCCESS && (verdict < -1 || verdict > 1)) abort();
}

static void fuzz_pendulum(const uint8_t *d, size_t n) {
  autobal_pendulum_params p;
  int verdict = 0;
  p.R_w = raw(d, n, 0);
  p.R_m = raw(d, n, 1);
  p.H = raw(d, n, 2);
  p.h = raw(d, n, 3);
  p.psi0 = raw(d, n, 4);
  (void)autobal_pendulum_verdict(&p, &verdict, NULL, NULL);
}

static void fuzz_rotor(const uint8_t *d, size_t n, int two_planes) {
  autobal_rotor_params p = autobal_rotor_params_default();
  double mass[3], radius[3], damping[3];
  double y[64], f[64];
  autobal_rotor *r;
  size_t dim, i, k = 0;
  int rc;
  p.hw.M_k *= factor(d, n, k++);
  p.hw.m_p *= factor(d, n, k++);
  p.hw.A_k *= factor(d, n, k++);
  p.hw.C_p *= factor(d, n, k++);
  p.hw.c_Lx *= factor(d, n, k++);
  p.hw.c_Ry *= factor(d, n, k++);
  p.hw.h_Lx *= factor(d, n, k++);
  p.omega *= factor(d, n, k++);
  p.plane[0].m0 *= factor(d, n, k++);
  for (i = 0; i < 3; i++) {
    mass[i] = 0.05 * factor(d, n, k++);
    radius[i] = 0.1 * factor(d, n, k++);
    damping[i] = 0.1 * factor(d, n, k++);
  }
  p.plane[0].n_balls = 1 + (1 + k < n ? d[1 + k] % 3 : 1);
  p.plane[0].ball_mass = mass;
  p.plane[0].ball_radius = radius;
  p.plane[0].ball_damping = damping;
  p.plane[0].ball_psi = NULL;
  p.plane[0].ball_rate = NULL;
  if (two_planes) {
    p.n_planes = 2;
    p.plane[1] = p.plane[0];
    p.plane[1].d = -0.1;
    p.plane[1].n_balls = 1;
  }
  r = autobal_rotor_alloc(&p, NULL);
  if (!r) return;
  dim = autobal_rotor_dim(r);
  if (dim <= 64) {
    for (i = 0; i < dim; i++) y[i] = finite_raw(d, n, 4 + i); /* the factor bytes overlap the first doubles */
    rc = autobal_rotor_rhs(0.5, y, f, r);
    if (rc != 0 && rc != GSL_EBADFUNC && rc != AUTOBAL_ROTOR_RHS_LEAVES_TRACK) abort();
    if (rc == 0)
      for (i = 0; i < dim; i++)
        if (!isfinite(f[i])) abort();
    rc = autobal_rotor_rhs_rotating(0.5, y, f, r);
    if (rc != 0 && rc != GSL_EBADFUNC && rc != AUTOBAL_ROTOR_RHS_LEAVES_TRACK) abort();
    if (rc == 0)
      for (i = 0; i < dim; i++)
        if (!isfinite(f[i])) abort();
  }
  autobal_rotor_free(r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1) return 0;
  switch (data[0] % 5) {
    case 0: fuzz_roots(data, size); break;
    case 1: fuzz_hurwitz(data, size); break;
    case 2: fuzz_pendulum(data, size); break;
    case 3: fuzz_rotor(data, size, 0); break;
    default: fuzz_rotor(data, size, 1); break;
  }
  return 0;
}
