/* pendulum.c: the planar two-pendulum autobalancer model (docs/pendulum.md): parameters
 * (2), (3), the blocks and the characteristic polynomial (6) of the linearization (5) about
 * the main motion, its matrices.  Everything here is dimensionless (see
 * include/autobal/pendulum.h).  The explicit equations of motion (1) are in
 * pendulum_motion.c; the stability analysis (sign tests, (10), critical speeds, maps) is in
 * src/analysis/pendulum_*.c.
 *
 * May use: pendulum_internal.h (the kernel of (6)), core (internal.h), libm.  No analysis,
 * no archive, no I/O. */
#include "autobal/pendulum.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "models/pendulum/pendulum_internal.h"

/* ======================================================================== */
/* Parameters (2), (3)                                                      */
/* ======================================================================== */

int autobal_pendulum_params_validate(const autobal_pendulum_params *p, autobal_error *err) {
  int st;
  if (p == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum parameters: NULL pointer");
  /* fast path: exactly the conditions checked below */
  if (p->R_w >= 0.0 && p->R_w <= AUTOBAL_PENDULUM_MAX_RATIO && isfinite(p->R_m) && p->R_m > 0.0 && p->R_m < 0.5 &&
      p->H >= 0.0 && p->H <= AUTOBAL_PENDULUM_MAX_RATIO && p->h >= 0.0 && p->h <= AUTOBAL_PENDULUM_MAX_RATIO &&
      isfinite(p->psi0) && p->psi0 >= 0.0 && p->psi0 < PEND_PI / 2)
    return AUTOBAL_SUCCESS;
  /* bounded above: the coefficients of (6) hold powers of R_w, H and h up to the eighth, which
   * overflow a double from about 1e38 (R_w = 1e300 used to fail inside the root finder) */
  if ((st = autobal_check_param(err, "R_w", p->R_w, 0.0, 0, AUTOBAL_PENDULUM_MAX_RATIO, 0, "")) != 0) return st;
  if ((st = autobal_check_param(err, "R_m", p->R_m, 0.0, 1, 0.5, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "H", p->H, 0.0, 0, AUTOBAL_PENDULUM_MAX_RATIO, 0, "")) != 0) return st;
  if ((st = autobal_check_param(err, "h", p->h, 0.0, 0, AUTOBAL_PENDULUM_MAX_RATIO, 0, "")) != 0) return st;
  if ((st = autobal_check_param(err, "psi0", p->psi0, 0.0, 0, PEND_PI / 2, 1, "rad")) != 0)
    return st;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_params_from_k(double R_w, double R_m, double H, double h, double k,
                                   autobal_pendulum_params *out, autobal_error *err) {
  autobal_pendulum_params p;
  int st;
  if (out == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum parameters: NULL output");
  if ((st = autobal_check_param(err, "k", k, 0.0, 0, 1.0, 0, "")) != 0) return st;
  p.R_w = R_w;
  p.R_m = R_m;
  p.H = H;
  p.h = h;
  p.psi0 = 0.5 * asin(sqrt(k)); /* in [0, pi/4]; k = sin^2(2 psi0) */
  if ((st = autobal_pendulum_params_validate(&p, err)) != 0) return st;
  *out = p;
  return AUTOBAL_SUCCESS;
}

double autobal_pendulum_k(const autobal_pendulum_params *p) {
  double s = sin(2.0 * p->psi0);
  return s * s;
}

int autobal_pendulum_params_from_physical(const autobal_pendulum_physical *q,
                                          autobal_pendulum_params *out, autobal_error *err) {
  autobal_pendulum_params p;
  double Ms, w0;
  int st;
  if (q == NULL || out == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum physical parameters: NULL pointer");
  if ((st = autobal_check_param(err, "M", q->M, 0.0, 1, INFINITY, 1, "kg")) != 0) return st;
  if ((st = autobal_check_param(err, "e", q->e, 0.0, 0, INFINITY, 1, "m")) != 0) return st;
  if ((st = autobal_check_param(err, "m", q->m, 0.0, 1, INFINITY, 1, "kg")) != 0) return st;
  if ((st = autobal_check_param(err, "l", q->l, 0.0, 1, INFINITY, 1, "m")) != 0) return st;
  if ((st = autobal_check_param(err, "c", q->c, 0.0, 1, INFINITY, 1, "N/m")) != 0) return st;
  if ((st = autobal_check_param(err, "H1", q->H1, 0.0, 0, INFINITY, 1, "N m s")) != 0) return st;
  if ((st = autobal_check_param(err, "H2", q->H2, 0.0, 0, INFINITY, 1, "N s/m")) != 0) return st;
  if ((st = autobal_check_param(err, "omega", q->omega, 0.0, 0, INFINITY, 1, "rad/s")) != 0)
    return st;
  /* sin psi0 = M e / (2 m l) < 1: the pendulums must be able to balance */
  if ((st = autobal_check_param(err, "M*e", q->M * q->e, 0.0, 0, 2.0 * q->m * q->l, 1,
                                "kg m (limit 2*m*l)")) != 0)
    return st;
  Ms = q->M + 2.0 * q->m;    /* (2) M_sigma */
  w0 = sqrt(q->c / Ms);      /* (2) omega0  */
  p.R_w = q->omega / w0;     /* (3) */
  p.R_m = q->m / Ms;         /* (3) */
  p.H = q->H2 / (w0 * Ms);   /* (3) */
  p.h = q->H1 / (q->m * q->l * q->l * w0); /* (3) */
  p.psi0 = asin(q->M * q->e / (2.0 * q->m * q->l)); /* (3) */
  if ((st = autobal_pendulum_params_validate(&p, err)) != 0) return st;
  *out = p;
  return AUTOBAL_SUCCESS;
}


/* ======================================================================== */
/* Characteristic polynomial (6)                                            */
/* ======================================================================== */

/* a11, a31, a33 of (6) as complex quadratics in lambda (interleaved). */
static void blocks(double R_w, double H, double h, double a11[6], double a31[6], double a33[6]) {
  /* (lambda + i R_w)^2 = lambda^2 + 2 i R_w lambda - R_w^2 */
  a31[0] = -R_w * R_w;
  a31[1] = 0.0;
  a31[2] = 0.0;
  a31[3] = 2.0 * R_w;
  a31[4] = 1.0;
  a31[5] = 0.0;
  /* a11 = a31 + H (lambda + i R_w) + 1 */
  a11[0] = 1.0 - R_w * R_w;
  a11[1] = H * R_w;
  a11[2] = H;
  a11[3] = 2.0 * R_w;
  a11[4] = 1.0;
  a11[5] = 0.0;
  /* a33 = lambda^2 + h lambda */
  a33[0] = 0.0;
  a33[1] = 0.0;
  a33[2] = h;
  a33[3] = 0.0;
  a33[4] = 1.0;
  a33[5] = 0.0;
}

void autobal_pendulum_k_and_kc_(const autobal_pendulum_params *p, double *k, double *kc) {
  double s = sin(2.0 * p->psi0), c = cos(2.0 * p->psi0);
  *k = s * s;
  *kc = c * c;
}

int autobal_pendulum_char_blocks(const autobal_pendulum_params *p, double a11[6], double a31[6],
                                 double a33[6], autobal_error *err) {
  double b11[6], b31[6], b33[6];
  int st = autobal_pendulum_params_validate(p, err);
  if (st) return st;
  blocks(p->R_w, p->H, p->h, b11, b31, b33);
  if (a11) memcpy(a11, b11, sizeof b11);
  if (a31) memcpy(a31, b31, sizeof b31);
  if (a33) memcpy(a33, b33, sizeof b33);
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_char_poly(const autobal_pendulum_params *p, double coef[9],
                               autobal_error *err) {
  double k, kc;
  int st = autobal_pendulum_params_validate(p, err);
  if (st) return st;
  if (coef == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "char_poly: NULL output");
  autobal_pendulum_k_and_kc_(p, &k, &kc);
  autobal_pendulum_char_poly_k_(p->R_w, p->R_m, p->H, p->h, k, kc, coef, NULL);
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_char_p1(const autobal_pendulum_params *p, double p1[10], autobal_error *err) {
  autobal_pendulum_char_parts_t_ P;
  int st = autobal_pendulum_params_validate(p, err);
  if (st) return st;
  if (p1 == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "char_p1: NULL output");
  autobal_pendulum_char_parts_(p->R_w, p->R_m, p->H, p->h, &P, p1);
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_linear_matrices(const autobal_pendulum_params *p, double Mm[16], double C[16],
                                     double K[16], autobal_error *err) {
  double s, c, R, Rm, R2;
  int st = autobal_pendulum_params_validate(p, err);
  if (st) return st;
  s = sin(p->psi0);
  c = cos(p->psi0);
  R = p->R_w;
  R2 = R * R;
  Rm = p->R_m;
  /* eq. (5), q = (xi, eta, alpha, beta); rows are the four equations of (5) */
  if (Mm) {
    const double m[16] = {1, 0, -Rm * c, -Rm * c, 0, 1, -Rm * s, Rm * s,
                          -c, -s, 1, 0, -c, s, 0, 1};
    memcpy(Mm, m, sizeof m);
  }
  if (C) {
    const double d[16] = {p->H, -2 * R, 2 * Rm * R * s, -2 * Rm * R * s,
                          2 * R, p->H, -2 * Rm * R * c, -2 * Rm * R * c,
                          -2 * R * s, 2 * R * c, p->h, 0,
                          2 * R * s, 2 * R * c, 0, p->h};
    memcpy(C, d, sizeof d);
  }
  if (K) {
    const double kk[16] = {1 - R2, -p->H * R, Rm * R2 * c, Rm * R2 * c,
                           p->H * R, 1 - R2, Rm * R2 * s, -Rm * R2 * s,
                           R2 * c, R2 * s, 0, 0,
                           R2 * c, -R2 * s, 0, 0};
    memcpy(K, kk, sizeof kk);
  }
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_first_order_matrix(const autobal_pendulum_params *p, double A[64],
                                        autobal_error *err) {
  double Mm[16], C[16], K[16], aug[4][8];
  size_t i, j, r;
  int st = autobal_pendulum_linear_matrices(p, Mm, C, K, err);
  if (st) return st;
  if (A == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "first_order_matrix: NULL output");
  /* solve M X = [K C] by Gaussian elimination with partial pivoting */
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) {
      aug[i][j] = K[4 * i + j];
      aug[i][4 + j] = C[4 * i + j];
    }
  for (r = 0; r < 4; r++) {
    size_t piv = r;
    double best = fabs(Mm[4 * r + r]);
    for (i = r + 1; i < 4; i++)
      if (fabs(Mm[4 * i + r]) > best) {
        best = fabs(Mm[4 * i + r]);
        piv = i;
      }
    if (!(best > 1e-14))
      return autobal_error_set(err, AUTOBAL_ENUMERIC,
                               "first_order_matrix: mass matrix of (5) is singular (pivot %g)",
                               best);
    if (piv != r) {
      for (j = 0; j < 4; j++) {
        double t = Mm[4 * r + j];
        Mm[4 * r + j] = Mm[4 * piv + j];
        Mm[4 * piv + j] = t;
      }
      for (j = 0; j < 8; j++) {
        double t = aug[r][j];
        aug[r][j] = aug[piv][j];
        aug[piv][j] = t;
      }
    }
    for (i = r + 1; i < 4; i++) {
      double f = Mm[4 * i + r] / Mm[4 * r + r];
      for (j = r; j < 4; j++) Mm[4 * i + j] -= f * Mm[4 * r + j];
      for (j = 0; j < 8; j++) aug[i][j] -= f * aug[r][j];
    }
  }
  for (r = 4; r-- > 0;) {
    for (j = 0; j < 8; j++) {
      double s = aug[r][j];
      for (i = r + 1; i < 4; i++) s -= Mm[4 * r + i] * aug[i][j];
      aug[r][j] = s / Mm[4 * r + r];
    }
  }
  for (i = 0; i < 64; i++) A[i] = 0.0;
  for (i = 0; i < 4; i++) {
    A[8 * i + 4 + i] = 1.0;
    for (j = 0; j < 4; j++) {
      A[8 * (4 + i) + j] = -aug[i][j];         /* -M^{-1} K */
      A[8 * (4 + i) + 4 + j] = -aug[i][4 + j]; /* -M^{-1} C */
    }
  }
  return AUTOBAL_SUCCESS;
}
