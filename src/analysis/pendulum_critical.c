/* pendulum_critical.c: critical speeds of the two-pendulum autobalancer (docs/pendulum.md):
 * the discriminant of (10) in W, the critical speeds of the undamped system and their curves
 * over R_m, the critical speeds of the damped system (6), and the closed forms and series
 * (13)-(18), R_m^(1).
 *
 * May use: pendulum_verdict.h (workspace, verdicts, (10) in long double), the model's kernel
 * of (6) (models/pendulum/pendulum_internal.h), the numerics (roots, bracketing), core
 * (internal.h).  Used by pendulum_map.c through pendulum_critical.h; it never calls the
 * maps. */
#include "autobal/pendulum.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/pendulum_critical.h"
#include "analysis/pendulum_verdict.h"
#include "internal.h"
#include "models/pendulum/pendulum_internal.h"

/* ---- discriminant in W, long double polynomial arithmetic ---------------- */

#define LDP_LEN 16

static void ldp_zero(long double *a) {
  int i;
  for (i = 0; i < LDP_LEN; i++) a[i] = 0.0L;
}

/* out = a * b truncated to LDP_LEN (degrees here never exceed 12) */
static void ldp_mul(const long double *a, const long double *b, long double *out) {
  long double t[LDP_LEN];
  int i, j;
  ldp_zero(t);
  for (i = 0; i < LDP_LEN; i++) {
    if (a[i] == 0.0L) continue;
    for (j = 0; i + j < LDP_LEN; j++) t[i + j] += a[i] * b[j];
  }
  memcpy(out, t, sizeof t);
}

static long double ldp_eval(const long double *a, int len, long double x) {
  long double s = 0.0L;
  int j = len;
  while (j-- > 0) s = s * x + a[j];
  return s;
}

/* c_j(W) of (10) as polynomials in W (long double), and |.| versions. */
static void undamped_coef_polys(long double Rm, long double k, long double c[5][LDP_LEN]) {
  long double r2 = k * Rm * Rm;
  int j;
  for (j = 0; j < 5; j++) ldp_zero(c[j]);
  /* c0 = k R_m^2 W^4 */
  c[0][4] = r2;
  /* c1 = a0 + 4 r2 W^3, a0 = 2 R_m W^2 (W - 1) */
  c[1][2] = -2.0L * Rm;
  c[1][3] = 2.0L * Rm + 4.0L * r2;
  /* c2 = a2 + 6 r2 W^2, a2 = (W - 1)^2 + 2 R_m W (W + 6) */
  c[2][0] = 1.0L;
  c[2][1] = -2.0L + 12.0L * Rm;
  c[2][2] = 1.0L + 2.0L * Rm + 6.0L * r2;
  /* c3 = a4 + 4 r2 W, a4 = 2 (1 - R_m)(W + 1) */
  c[3][0] = 2.0L * (1.0L - Rm);
  c[3][1] = 2.0L * (1.0L - Rm) + 4.0L * r2;
  /* c4 = a6 + r2, a6 = 1 - 2 R_m */
  c[4][0] = 1.0L - 2.0L * Rm + r2;
}

/* Discriminant of the quartic sum_j c[j] x^j whose coefficients c[j] are
 * polynomials (in W or R), by polynomial arithmetic on the 16 terms; ca are
 * the coefficient-wise magnitudes; Dm receives the magnitude polynomial
 * (same products on |.|) for rounding-error bounds. */
static void quartic_disc_poly(long double c[5][LDP_LEN], long double ca[5][LDP_LEN],
                              long double D[LDP_LEN], long double Dm[LDP_LEN]) {
  long double pw[5][5][LDP_LEN], pa[5][5][LDP_LEN];
  int i, j, t;
  /* powers 0..4 of each coefficient polynomial; index v: 0=a=c4 ... 4=e=c0 */
  for (i = 0; i < 5; i++) {
    const long double *base = c[4 - i], *basea = ca[4 - i];
    ldp_zero(pw[i][0]);
    ldp_zero(pa[i][0]);
    pw[i][0][0] = 1.0L;
    pa[i][0][0] = 1.0L;
    for (j = 1; j < 5; j++) {
      ldp_mul(pw[i][j - 1], base, pw[i][j]);
      ldp_mul(pa[i][j - 1], basea, pa[i][j]);
    }
  }
  ldp_zero(D);
  ldp_zero(Dm);
  for (t = 0; t < 16; t++) {
    long double term[LDP_LEN], terma[LDP_LEN];
    ldp_zero(term);
    ldp_zero(terma);
    term[0] = (long double)autobal_pendulum_quartic_disc_[t].coef;
    terma[0] = fabsl(term[0]);
    for (i = 0; i < 5; i++) {
      ldp_mul(term, pw[i][autobal_pendulum_quartic_disc_[t].ex[i]], term);
      ldp_mul(terma, pa[i][autobal_pendulum_quartic_disc_[t].ex[i]], terma);
    }
    for (j = 0; j < LDP_LEN; j++) {
      D[j] += term[j];
      Dm[j] += terma[j];
    }
  }
}

/* The discriminant of (10) in x as a polynomial in W (13 coefficients) and
 * the magnitude polynomial. */
static void undamped_disc_poly(long double Rm, long double k, long double D[LDP_LEN],
                               long double Dm[LDP_LEN]) {
  long double c[5][LDP_LEN], ca[5][LDP_LEN];
  int i, j;
  undamped_coef_polys(Rm, k, c);
  for (i = 0; i < 5; i++)
    for (j = 0; j < LDP_LEN; j++) ca[i][j] = fabsl(c[i][j]);
  quartic_disc_poly(c, ca, D, Dm);
  /* Degree <= 11: the W^12 coefficient is the discriminant of the top-degree
   * parts T(y) = sum_j c_j^top y^j, which has the double root y = -1
   * (T = (y+1)^2 [y((1-2R_m) y + 2R_m) + k R_m^2 (y+1)^2]), so it vanishes
   * identically; drop its rounding noise. */
  for (j = 12; j < LDP_LEN; j++) D[j] = 0.0L;
}

int autobal_pendulum_undamped_discriminant(double R_m, double k, double disc[13],
                                           autobal_error *err) {
  long double D[LDP_LEN], Dm[LDP_LEN];
  int st, j;
  if ((st = autobal_pendulum_check_rm_k_(R_m, k, err)) != 0) return st;
  if (disc == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "undamped_discriminant: NULL output");
  undamped_disc_poly(R_m, k, D, Dm);
  for (j = 0; j < 13; j++) disc[j] = (double)D[j];
  return AUTOBAL_SUCCESS;
}

/* ======================================================================== */
/* Critical speeds of the undamped system                                   */
/* ======================================================================== */

typedef struct {
  const long double *q;
  int len;
} ldpoly_ctx;

static int ldpoly_fn(double x, void *ctx, double *fx) {
  const ldpoly_ctx *c = (const ldpoly_ctx *)ctx;
  long double v = ldp_eval(c->q, c->len, x);
  /* keep the sign even if the magnitude is outside double's range */
  if (v > 0) *fx = v > (long double)DBL_MAX ? DBL_MAX : (v < (long double)DBL_MIN ? DBL_MIN : (double)v);
  else if (v < 0)
    *fx = -v > (long double)DBL_MAX ? -DBL_MAX : (-v < (long double)DBL_MIN ? -DBL_MIN : (double)v);
  else *fx = 0.0;
  return AUTOBAL_SUCCESS;
}

/* sign of q at x, 0 if |q(x)| is within the rounding bound */
static int ld_sign(const long double *q, const long double *qa, int len, long double x) {
  long double v = ldp_eval(q, len, x);
  long double b = PEND_GAMMA * U_LD * ldp_eval(qa, len, fabsl(x));
  if (v > b) return 1;
  if (v < -b) return -1;
  return 0;
}

static int cmp_dbl(const void *pa, const void *pb) {
  double a = *(const double *)pa, b = *(const double *)pb;
  return (a > b) - (a < b);
}

/* Positive real roots of q (long double, len <= LDP_LEN) with magnitude
 * polynomial qa: isolation between the critical points of q (roots of q',
 * by GSL, polished by Newton in long double), sign changes refined by Brent,
 * critical points where |q| is within its rounding bound reported as
 * (double) roots.  Writes up to maxout sorted roots. */
static int positive_roots(autobal_pendulum_workspace *ws, const long double *q0,
                          const long double *qa, int len0, double *out, size_t maxout,
                          size_t *nout) {
  long double q[LDP_LEN], dq[LDP_LEN], ddq[LDP_LEN];
  double dqd[LDP_LEN], rre[LDP_LEN], rim[LDP_LEN];
  double brk[LDP_LEN + 2];
  size_t nb = 0, n = 0, i;
  int len = len0, deg, j, st;
  ldpoly_ctx ctx;
  while (len > 0 && q0[len - 1] == 0.0L) len--;
  *nout = 0;
  if (len < 2) return AUTOBAL_SUCCESS;
  for (j = 0; j < LDP_LEN; j++) q[j] = j < len ? q0[j] : 0.0L;
  deg = len - 1;
  for (j = 0; j < LDP_LEN; j++) {
    dq[j] = j + 1 < len ? (long double)(j + 1) * q[j + 1] : 0.0L;
    ddq[j] = j + 2 < len ? (long double)((j + 2) * (j + 1)) * q[j + 2] : 0.0L;
  }
  brk[nb++] = 0.0;
  if (deg >= 2) {
    /* critical points: roots of q' (degree deg-1) */
    for (j = 0; j < deg; j++) dqd[j] = (double)dq[j];
    st = autobal_poly_roots(ws->pw[deg - 1], dqd, (size_t)deg, rre, rim, &ws->err);
    if (st) return st;
    for (j = 0; j < deg - 1; j++) {
      long double x;
      int it;
      if (!(rre[j] > 0.0) || fabs(rim[j]) > 1e-3 * fabs(rre[j])) continue;
      x = rre[j];
      for (it = 0; it < 6; it++) { /* Newton on q' */
        long double f = ldp_eval(dq, len, x), fp = ldp_eval(ddq, len, x);
        long double nx;
        if (fp == 0.0L) break;
        nx = x - f / fp;
        if (!(nx > 0.0L) || fabsl(nx - x) > 1e-2L * x) break;
        x = nx;
      }
      brk[nb++] = (double)x;
    }
  }
  {
    /* upper bound of the positive roots (Cauchy) */
    long double m = 0.0L;
    for (j = 0; j < deg; j++)
      if (fabsl(q[j] / q[deg]) > m) m = fabsl(q[j] / q[deg]);
    m = 2.0L * (1.0L + m);
    if (m > 1e150L) m = 1e150L;
    brk[nb++] = (double)m;
  }
  qsort(brk + 1, nb - 2, sizeof(double), cmp_dbl);
  ctx.q = q;
  ctx.len = len;
  for (i = 0; i + 1 < nb; i++) {
    double a = brk[i], b = brk[i + 1];
    int sa, sb;
    if (!(b > a)) continue;
    sa = ld_sign(q, qa, len, a);
    sb = ld_sign(q, qa, len, b);
    if (i > 0 && sa == 0) {
      /* (near-)double root at a critical point */
      if (n == 0 || out[n - 1] < a * (1 - 1e-14)) {
        if (n < maxout) out[n++] = a;
      }
    }
    if (sa != 0 && sb != 0 && sa != sb) {
      double root;
      st = autobal_root_brent(ldpoly_fn, &ctx, a, b, 0.0, 1e-15, 400, &root, &ws->err);
      if (st) return st;
      if (n == 0 || out[n - 1] < root * (1 - 1e-14)) {
        if (n < maxout) out[n++] = root;
      }
    }
  }
  *nout = n;
  return AUTOBAL_SUCCESS;
}

/* ---- the colliding pair of roots of (10): a well-conditioned local test ---- */

/* Quadratic factor x^2 + u x + v of the quartic a[0..4] (ascending) near the
 * initial (u, v), by Bairstow's method in long double; b[2..4] receive the
 * quotient b4 x^2 + b3 x + b2.  Returns 0 on convergence. */
static int bairstow(const long double a[5], long double *u, long double *v, long double q[3]) {
  long double b[5], c[5], prev = INFINITY, best = INFINITY, bu = *u, bv = *v;
  int it, i, conv = 0;
  for (it = 0; it < 100; it++) {
    long double det, du, dv;
    b[4] = a[4];
    b[3] = a[3] - *u * b[4];
    for (i = 2; i >= 0; i--) b[i] = a[i] - *u * b[i + 1] - *v * b[i + 2];
    c[4] = b[4];
    c[3] = b[3] - *u * c[4];
    for (i = 2; i >= 1; i--) c[i] = b[i] - *u * c[i + 1] - *v * c[i + 2];
    det = c[2] * c[2] - c[1] * c[3];
    if (det == 0.0L) return -1;
    du = (b[1] * c[2] - b[0] * c[3]) / det;
    dv = (c[2] * b[0] - c[1] * b[1]) / det;
    *u += du;
    *v += dv;
    {
      /* converged when the step is at rounding level, or stops shrinking
       * once small (quadratic convergence has ended in rounding noise);
       * the iterate after the smallest step is kept */
      long double step = fabsl(du) / (1 + fabsl(*u)) + fabsl(dv) / (1 + fabsl(*v));
      if (step < best) {
        best = step;
        bu = *u;
        bv = *v;
      }
      if (step <= 16 * U_LD || (step < 1e-14L && step >= 0.5L * prev)) {
        conv = 1;
        break;
      }
      prev = step;
    }
  }
  if (!conv && best < 1e-13L) conv = 1;
  *u = bu;
  *v = bv;
  b[4] = a[4];
  b[3] = a[3] - *u * b[4];
  b[2] = a[2] - *u * b[3] - *v * b[4];
  q[0] = b[2];
  q[1] = b[3];
  q[2] = b[4];
  return conv ? 0 : -1;
}

/* The closest pair of roots of (10) at W as a quadratic factor: *g = u^2 - 4v
 * (> 0: the pair is real and distinct, < 0: complex), *rest_ok = 1 when both
 * quadratics have real roots <= 0 apart from the sign of g. */
static int undamped_cluster(autobal_pendulum_workspace *ws, long double Rm, long double W,
                            long double k, long double *g, int *rest_ok) {
  long double c[5], u, v, q[3];
  double cd[5], re[4], im[4], best = INFINITY;
  int i, j, bi = 0, bj = 1, st;
  autobal_pendulum_undamped_coefs_ld_(Rm, W, k, c);
  for (i = 0; i < 5; i++) cd[i] = (double)c[i];
  if ((st = autobal_poly_roots(ws->pw[4], cd, 5, re, im, &ws->err)) != 0) return st;
  for (i = 0; i < 4; i++)
    for (j = i + 1; j < 4; j++) {
      double d;
      int conj = im[i] != 0.0 && im[i] == -im[j] && re[i] == re[j];
      int reals = im[i] == 0.0 && im[j] == 0.0;
      if (!conj && !reals) continue;
      d = hypot(re[i] - re[j], im[i] - im[j]);
      if (d < best) {
        best = d;
        bi = i;
        bj = j;
      }
    }
  u = -((long double)re[bi] + re[bj]);
  v = (long double)re[bi] * re[bj] - (long double)im[bi] * im[bj];
  if (bairstow(c, &u, &v, q) != 0) {
    /* no convergence (e.g. a third root close by): fall back on the double
     * precision roots themselves */
    long double dr = (long double)re[bi] - re[bj], di = (long double)im[bi] - im[bj];
    int m, okr = 1;
    *g = dr * dr - di * di;
    for (m = 0; m < 4; m++)
      if (m != bi && m != bj && (im[m] != 0.0 || re[m] > 0.0)) okr = 0;
    *rest_ok = okr && re[bi] + re[bj] <= 0.0;
    return AUTOBAL_SUCCESS;
  }
  *g = u * u - 4.0L * v;
  *rest_ok = (q[1] * q[1] - 4.0L * q[2] * q[0] >= 0.0L) && q[1] * q[2] >= 0.0L &&
             q[0] * q[2] >= 0.0L && u >= 0.0L && v >= 0.0L;
  return AUTOBAL_SUCCESS;
}

typedef struct {
  autobal_pendulum_workspace *ws;
  long double Rm, k;
} cluster_ctx;

static int cluster_fn(double W, void *vctx, double *fx) {
  const cluster_ctx *c = (const cluster_ctx *)vctx;
  long double g;
  int ok, st = undamped_cluster(c->ws, c->Rm, W, c->k, &g, &ok);
  *fx = (double)g;
  return st;
}

/* Verdict with the cluster test as fallback where the quartic criterion is
 * undecided (very narrow windows, double roots). */
static int undamped_verdict_robust(autobal_pendulum_workspace *ws, long double Rm, long double W,
                                   long double k, int *verdict) {
  long double g;
  int ok, st, sure;
  *verdict = autobal_pendulum_undamped_verdict_ld_(Rm, W, k, &sure);
  if (sure || k == 0.0L || k == 1.0L) return AUTOBAL_SUCCESS;
  if ((st = undamped_cluster(ws, Rm, W, k, &g, &ok)) != 0) return st;
  if (g < 0.0L || !ok) *verdict = AUTOBAL_VERDICT_UNSTABLE;
  else if (g > 0.0L) *verdict = AUTOBAL_VERDICT_STABLE;
  return AUTOBAL_SUCCESS;
}

/* Refine a root W0 of the discriminant on the pair discriminant g: find a
 * sign change of g within W0 (1 -+ h), h = 1e-12 ... 1e-3, then Brent. */
static int refine_on_cluster(cluster_ctx *cc, double W0, double *W) {
  double h, fa, fb, f0;
  int st;
  *W = W0;
  if ((st = cluster_fn(W0, cc, &f0)) != 0) return st;
  for (h = 1e-12; h <= 1e-3; h *= 4) {
    double a = W0 * (1 - h), b = W0 * (1 + h);
    if ((st = cluster_fn(a, cc, &fa)) != 0) return st;
    if ((st = cluster_fn(b, cc, &fb)) != 0) return st;
    if ((fa < 0) != (f0 < 0) || (fb < 0) != (f0 < 0)) {
      double lo = (fa < 0) != (f0 < 0) ? a : W0, hi = (fa < 0) != (f0 < 0) ? W0 : b;
      if (lo == W0 && (fb < 0) == (f0 < 0)) return AUTOBAL_SUCCESS;
      return autobal_root_brent(cluster_fn, cc, lo, hi, 0.0, 1e-15, 200, W, &cc->ws->err);
    }
  }
  return AUTOBAL_SUCCESS; /* no sign change of g nearby (touch): keep W0 */
}

/* The degenerate points of the limits k -> 1 and k -> 0 open into windows
 * where a pair of roots of (10) is complex, of width ~ sqrt(1-k) resp.
 * sqrt(k), too narrow for the discriminant in W when k is close to 1 or 0:
 *  - k -> 1: the double root of (10) at k = 1, W18 = 2(1-2R_m)/(1-4R_m)^2
 *    ((18) squared), an unstable window when R_m^(1) < R_m < 1/4;
 *  - k -> 0: W = 1, where x = 0 meets the cubic (13).
 * Look for a window at such a point W18 directly: if the pair is complex
 * there, walk outwards until it is real and refine both ends on g. */
static int window_at(cluster_ctx *cc, double W18, double *lo, double *hi, int *found) {
  double g0, h, ga, gb, a = 0, b = 0;
  int st, fa = 0, fb = 0;
  *found = 0;
  if (!isfinite(W18) || !(W18 > 0)) return AUTOBAL_SUCCESS;
  if ((st = cluster_fn(W18, cc, &g0)) != 0) return st;
  if (!(g0 < 0)) return AUTOBAL_SUCCESS;
  for (h = 1e-15; h < 0.5 && !(fa && fb); h *= 2) {
    if (!fa) {
      if ((st = cluster_fn(W18 * (1 - h), cc, &ga)) != 0) return st;
      if (ga > 0) fa = 1, a = W18 * (1 - h);
    }
    if (!fb) {
      if ((st = cluster_fn(W18 * (1 + h), cc, &gb)) != 0) return st;
      if (gb > 0) fb = 1, b = W18 * (1 + h);
    }
  }
  if (!(fa && fb)) return AUTOBAL_SUCCESS;
  if ((st = autobal_root_brent(cluster_fn, cc, a, W18, 0.0, 1e-15, 300, lo, &cc->ws->err)) != 0) return st;
  if ((st = autobal_root_brent(cluster_fn, cc, W18, b, 0.0, 1e-15, 300, hi, &cc->ws->err)) != 0) return st;
  *found = 1;
  return AUTOBAL_SUCCESS;
}

static int crit_set_fill(autobal_pendulum_crit_set *out, const double *rw, const int *vint,
                         size_t nc, int keep_touch_stable_only, double lo_end, double hi_end) {
  /* vint[i] = verdict (1 stable) on interval i: (rw[i-1], rw[i]), i = 0..nc */
  size_t i;
  out->n = 0;
  out->n_stable = 0;
  for (i = 0; i < nc; i++) {
    int l = vint[i] == AUTOBAL_VERDICT_STABLE, r = vint[i + 1] == AUTOBAL_VERDICT_STABLE;
    int kind = l == r ? AUTOBAL_CRIT_TOUCH : (r ? AUTOBAL_CRIT_GAINED : AUTOBAL_CRIT_LOST);
    if (kind == AUTOBAL_CRIT_TOUCH && keep_touch_stable_only && !l) continue;
    if (out->n < AUTOBAL_PENDULUM_MAX_CRIT) {
      out->R_w[out->n] = rw[i];
      out->kind[out->n] = kind;
      out->n++;
    }
  }
  for (i = 0; i <= nc; i++) {
    double a = i == 0 ? lo_end : rw[i - 1];
    double b = i == nc ? hi_end : rw[i];
    if (vint[i] != AUTOBAL_VERDICT_STABLE) continue;
    if (out->n_stable > 0 && out->stable_hi[out->n_stable - 1] == a) {
      out->stable_hi[out->n_stable - 1] = b; /* merge across a touch */
    } else if (out->n_stable < AUTOBAL_PENDULUM_MAX_CRIT + 1) {
      out->stable_lo[out->n_stable] = a;
      out->stable_hi[out->n_stable] = b;
      out->n_stable++;
    }
  }
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_critical_speeds(autobal_pendulum_workspace *ws, double R_m, double k,
                                     autobal_pendulum_crit_set *out) {
  long double D[LDP_LEN], Dm[LDP_LEN];
  double Wr[AUTOBAL_PENDULUM_MAX_CRIT], rw[AUTOBAL_PENDULUM_MAX_CRIT];
  int vint[AUTOBAL_PENDULUM_MAX_CRIT + 1];
  size_t nW = 0, i;
  int st, len;
  if (ws == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&ws->err);
  if ((st = autobal_pendulum_check_rm_k_(R_m, k, &ws->err)) != 0) return st;
  if (out == NULL) return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_speeds: NULL output");
  memset(out, 0, sizeof *out);
  if (k == 0.0) {
    /* x = 0 plus the cubic: its discriminant in W (degree 6), and W = 1
     * where a0 = 2 R_m W^2 (W - 1) changes sign (13) */
    long double c[5][LDP_LEN], ca[5][LDP_LEN], t[LDP_LEN], ta[LDP_LEN];
    long double *a0, *a2, *a4, *a6;
    static const int TERMS[5][5] = {/* coef, exps of a6, a4, a2, a0 */
                                    {18, 1, 1, 1, 1},
                                    {-4, 0, 3, 0, 1},
                                    {1, 0, 2, 2, 0},
                                    {-4, 1, 0, 3, 0},
                                    {-27, 2, 0, 0, 2}};
    int tt, v, e, j;
    undamped_coef_polys(R_m, 0.0L, c);
    for (v = 0; v < 5; v++)
      for (j = 0; j < LDP_LEN; j++) ca[v][j] = fabsl(c[v][j]);
    a0 = c[1];
    a2 = c[2];
    a4 = c[3];
    a6 = c[4];
    ldp_zero(D);
    ldp_zero(Dm);
    for (tt = 0; tt < 5; tt++) {
      long double *base[4], *basea[4];
      base[0] = a6;
      base[1] = a4;
      base[2] = a2;
      base[3] = a0;
      basea[0] = ca[4];
      basea[1] = ca[3];
      basea[2] = ca[2];
      basea[3] = ca[1];
      ldp_zero(t);
      ldp_zero(ta);
      t[0] = TERMS[tt][0];
      ta[0] = fabsl(t[0]);
      for (v = 0; v < 4; v++)
        for (e = 0; e < TERMS[tt][v + 1]; e++) {
          ldp_mul(t, base[v], t);
          ldp_mul(ta, basea[v], ta);
        }
      for (j = 0; j < LDP_LEN; j++) {
        D[j] += t[j];
        Dm[j] += ta[j];
      }
    }
    /* Degree <= 5: the W^6 coefficient is the discriminant of the top-degree
     * parts (1-2R_m) y^3 + 2(1-R_m) y^2 + (1+2R_m) y + 2R_m = (y+1)^2 ((1-2R_m) y
     * + 2R_m), which has a double root, so it vanishes identically. */
    for (j = 6; j < LDP_LEN; j++) D[j] = 0.0L;
    len = 6;
    if ((st = positive_roots(ws, D, Dm, len, Wr, AUTOBAL_PENDULUM_MAX_CRIT - 1, &nW)) != 0)
      return st;
    /* add W = 1 */
    {
      int have = 0;
      for (i = 0; i < nW; i++)
        if (fabs(Wr[i] - 1.0) <= 1e-14) {
          Wr[i] = 1.0;
          have = 1;
        }
      if (!have) Wr[nW++] = 1.0;
      qsort(Wr, nW, sizeof(double), cmp_dbl);
    }
  } else {
    size_t nT = 0;
    double T[AUTOBAL_PENDULUM_MAX_CRIT];
    if (k == 1.0) {
      /* (15): at k = 1, with lambda = i mu and nu = mu + R_w, P1 becomes the
       * real quartic f(nu) = (nu - R_w)^2 (nu^2 - 1) - R_m nu^4 and (6) is
       * stable in the first approximation iff f has four real roots; the
       * verdict changes only where disc_nu(f) = 0.  Its roots are located on
       * their own (the double root of (6) at (18) is not one of them, so no
       * near-triple root arises near R_m^(1)). */
      long double F[5][LDP_LEN], Fa[5][LDP_LEN], E[LDP_LEN], Ea[LDP_LEN];
      long double Q1[LDP_LEN], Q1a[LDP_LEN];
      int j;
      for (j = 0; j < 5; j++) ldp_zero(F[j]);
      F[0][2] = -1.0L;             /* -R^2          */
      F[1][1] = 2.0L;              /* 2R nu         */
      F[2][0] = -1.0L;             /* (R^2 - 1) nu^2 */
      F[2][2] = 1.0L;
      F[3][1] = -2.0L;             /* -2R nu^3      */
      F[4][0] = 1.0L - (long double)R_m; /* (1 - R_m) nu^4 */
      for (j = 0; j < 5; j++) {
        int m;
        for (m = 0; m < LDP_LEN; m++) Fa[j][m] = fabsl(F[j][m]);
      }
      quartic_disc_poly(F, Fa, E, Ea);
      /* disc is even in R (each term has an even number of odd factors b, d),
       * so it is a polynomial in W = R^2 */
      ldp_zero(Q1);
      ldp_zero(Q1a);
      for (j = 0; 2 * j < LDP_LEN; j++) {
        Q1[j] = E[2 * j];
        Q1a[j] = Ea[2 * j];
      }
      if ((st = positive_roots(ws, Q1, Q1a, 8, T, AUTOBAL_PENDULUM_MAX_CRIT / 2, &nT)) != 0)
        return st;
    }
    undamped_disc_poly(R_m, k, D, Dm);
    /* D = W^4 Q(W): the coefficients of W^0..W^3 vanish exactly (every term
     * of the discriminant holds e = c0 ~ W^4 or d^2 = c1^2 ~ W^4) */
    if ((st = positive_roots(ws, D + 4, Dm + 4, 8, Wr, AUTOBAL_PENDULUM_MAX_CRIT / 2, &nW)) != 0)
      return st;
    if (k == 1.0) {
      /* keep the exact transitions T, plus the candidates of D that are not
       * one of them (touches such as the double root at (18)) */
      size_t n2 = 0, a, b;
      for (a = 0; a < nW; a++) {
        int dup = 0;
        for (b = 0; b < nT; b++)
          if (fabs(Wr[a] - T[b]) <= 1e-6 * T[b]) dup = 1;
        if (!dup) Wr[n2++] = Wr[a];
      }
      for (b = 0; b < nT; b++) Wr[n2++] = T[b];
      nW = n2;
      qsort(Wr, nW, sizeof(double), cmp_dbl);
    }
  }
  if (k < 1.0) {
    /* refine every candidate on the pair discriminant (well conditioned,
     * from the coefficients of (10) at W rather than the expanded
     * discriminant in W), then look for a window at (18) too narrow for the
     * discriminant in W */
    cluster_ctx cc;
    double wlo, whi;
    int found, pt;
    cc.ws = ws;
    cc.Rm = R_m;
    cc.k = k;
    for (i = 0; i < nW; i++) {
      double Wn;
      if (k == 0.0 && Wr[i] == 1.0) continue; /* exact (13) */
      if ((st = refine_on_cluster(&cc, Wr[i], &Wn)) != 0) return st;
      Wr[i] = Wn;
    }
    for (pt = 0; pt < 2 && k > 0.0; pt++) {
      double Wc = pt == 0 ? 2.0 * (1.0 - 2.0 * R_m) / ((1.0 - 4.0 * R_m) * (1.0 - 4.0 * R_m)) : 1.0;
      if ((st = window_at(&cc, Wc, &wlo, &whi, &found)) != 0) return st;
      if (!found) continue;
      /* candidates that approximated the ends were refined onto them above
       * (merged below); inside a window too narrow for the discriminant in W
       * any candidate is an artefact */
      size_t n2 = 0;
      int narrow = whi - wlo < 1e-6 * whi;
      for (i = 0; i < nW; i++)
        if (!(narrow && Wr[i] > wlo && Wr[i] < whi)) Wr[n2++] = Wr[i];
      if (n2 + 2 <= AUTOBAL_PENDULUM_MAX_CRIT) {
        Wr[n2++] = wlo;
        Wr[n2++] = whi;
      }
      nW = n2;
      qsort(Wr, nW, sizeof(double), cmp_dbl);
    }
    qsort(Wr, nW, sizeof(double), cmp_dbl);
    {
      /* merge duplicates produced by the refinement */
      size_t n2 = 0;
      for (i = 0; i < nW; i++)
        if (n2 == 0 || Wr[i] > Wr[n2 - 1] * (1 + 1e-13)) Wr[n2++] = Wr[i];
      nW = n2;
    }
  }
  /* verdict on every interval between consecutive candidates */
  for (i = 0; i <= nW; i++) {
    long double a = i == 0 ? 0.0L : Wr[i - 1];
    long double b = i == nW ? 2.0L * a + 1.0L : Wr[i];
    if ((st = undamped_verdict_robust(ws, R_m, 0.5L * (a + b), k, &vint[i])) != 0) return st;

  }
  for (i = 0; i < nW; i++) rw[i] = sqrt(Wr[i]);
  st = crit_set_fill(out, rw, vint, nW, 1, 0.0, INFINITY);
  {
    /* a touch within 1e-8 of a transition is an artefact of the rounding of
     * the pair discriminant (large W): drop it */
    size_t n2 = 0;
    for (i = 0; i < out->n; i++) {
      int drop = 0;
      if (out->kind[i] == AUTOBAL_CRIT_TOUCH) {
        if (i > 0 && out->kind[i - 1] != AUTOBAL_CRIT_TOUCH && out->R_w[i] - out->R_w[i - 1] < 1e-8 * out->R_w[i])
          drop = 1;
        if (i + 1 < out->n && out->kind[i + 1] != AUTOBAL_CRIT_TOUCH &&
            out->R_w[i + 1] - out->R_w[i] < 1e-8 * out->R_w[i])
          drop = 1;
      }
      if (!drop) {
        out->R_w[n2] = out->R_w[i];
        out->kind[n2] = out->kind[i];
        n2++;
      }
    }
    out->n = n2;
  }
  return st;
}

size_t autobal_pendulum_crit_count(const autobal_pendulum_crit_set *s) {
  size_t i, n = 0;
  if (s == NULL) return 0;
  for (i = 0; i < s->n; i++)
    if (s->kind[i] != AUTOBAL_CRIT_TOUCH) n++;
  return n;
}

double autobal_pendulum_crit_get(const autobal_pendulum_crit_set *s, size_t j) {
  size_t i, n = 0;
  if (s == NULL) return NAN;
  for (i = 0; i < s->n; i++)
    if (s->kind[i] != AUTOBAL_CRIT_TOUCH) {
      if (n == j) return s->R_w[i];
      n++;
    }
  return NAN;
}

int autobal_pendulum_critical_curves(autobal_pendulum_workspace *ws, double k, const double *R_m,
                                     size_t n_Rm, size_t n_curve, double *rw) {
  size_t i, j;
  int st;
  if (ws == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&ws->err);
  if ((st = autobal_check_param(&ws->err, "k", k, 0.0, 0, 1.0, 0, "")) != 0) return st;
  if ((n_Rm > 0 && R_m == NULL) || (n_Rm * n_curve > 0 && rw == NULL))
    return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_curves: NULL array");
  for (i = 0; i < n_Rm; i++) {
    char name[32];
    snprintf(name, sizeof name, "R_m[%zu]", i);
    if ((st = autobal_check_param(&ws->err, name, R_m[i], 0.0, 1, 0.5, 1, "")) != 0) return st;
  }
  for (i = 0; i < n_Rm; i++) {
    autobal_pendulum_crit_set s;
    if (autobal_pendulum_cancelled_(ws)) return AUTOBAL_ECANCELLED;
    if ((st = autobal_pendulum_critical_speeds(ws, R_m[i], k, &s)) != 0) return st;
    for (j = 0; j < n_curve; j++) rw[i * n_curve + j] = autobal_pendulum_crit_get(&s, j);
  }
  return AUTOBAL_SUCCESS;
}

/* ======================================================================== */
/* Critical speeds of the damped system                                     */
/* ======================================================================== */

static int damped_stable_pred(double R_w, void *vctx, int *value) {
  const autobal_pendulum_damped_ctx_ *c = (const autobal_pendulum_damped_ctx_ *)vctx;
  int v, st;
  st = autobal_pendulum_damped_verdict_k_(R_w, c->R_m, c->H, c->h, c->k, c->kc, &v, NULL, &c->ws->err);
  *value = v == AUTOBAL_VERDICT_STABLE;
  return st;
}

/* max Re of the roots of (6) (deflated at k = 0) */
int autobal_pendulum_damped_maxre_fn_(double R_w, void *vctx, double *fx) {
  const autobal_pendulum_damped_ctx_ *c = (const autobal_pendulum_damped_ctx_ *)vctx;
  double coef[9], re[8], im[8];
  int st;
  autobal_pendulum_char_poly_k_(R_w, c->R_m, c->H, c->h, c->k, c->kc, coef, NULL);
  if (c->k == 0.0) st = autobal_poly_roots(c->ws->pw[7], coef + 1, 8, re, im, &c->ws->err);
  else st = autobal_poly_roots(c->ws->pw[8], coef, 9, re, im, &c->ws->err);
  if (st) return st;
  autobal_roots_verdict(c->k == 0.0 ? 7 : 8, re, im, 0.0, fx);
  return AUTOBAL_SUCCESS;
}

/* The damped search with at most cap recorded changes (1 <= cap <= AUTOBAL_PENDULUM_MAX_CRIT;
 * the public function uses AUTOBAL_PENDULUM_MAX_CRIT).  A test hook for the truncation path
 * (the damped system has far fewer changes than the capacity, see the header); declared here
 * and in tests/test_pendulum.c, not part of the API.  AUTOBAL_EINVAL for cap out of range. */
int autobal_pendulum_critical_speeds_damped_cap_(autobal_pendulum_workspace *ws,
                                                 const autobal_pendulum_params *p, double rw_min,
                                                 double rw_max, size_t n_sweep, size_t cap,
                                                 autobal_pendulum_crit_set *out);

int autobal_pendulum_critical_speeds_damped_cap_(autobal_pendulum_workspace *ws,
                                                 const autobal_pendulum_params *p, double rw_min,
                                                 double rw_max, size_t n_sweep, size_t cap,
                                                 autobal_pendulum_crit_set *out) {
  autobal_pendulum_damped_ctx_ ctx;
  double rw[AUTOBAL_PENDULUM_MAX_CRIT];
  int vint[AUTOBAL_PENDULUM_MAX_CRIT + 1];
  size_t nc = 0, i;
  int st, prev, truncated = 0;
  autobal_pendulum_params q;
  if (ws == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&ws->err);
  if (p == NULL) return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_speeds_damped: NULL parameters");
  q = *p;
  q.R_w = 0.0;
  if ((st = autobal_pendulum_params_validate(&q, &ws->err)) != 0) return st;
  if ((st = autobal_check_param(&ws->err, "rw_min", rw_min, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if ((st = autobal_check_param(&ws->err, "rw_max", rw_max, rw_min, 1, INFINITY, 1, "")) != 0)
    return st;
  if (n_sweep < 2)
    return autobal_error_set(&ws->err, AUTOBAL_EINVAL,
                             "parameter n_sweep = %zu is out of range: allowed [2, inf)", n_sweep);
  if (cap < 1 || cap > AUTOBAL_PENDULUM_MAX_CRIT)
    return autobal_error_set(&ws->err, AUTOBAL_EINVAL,
                             "critical_speeds_damped: capacity %zu out of range [1, %d]", cap,
                             AUTOBAL_PENDULUM_MAX_CRIT);
  if (out == NULL) return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_speeds_damped: NULL output");
  memset(out, 0, sizeof *out);
  ctx.ws = ws;
  ctx.R_m = p->R_m;
  ctx.H = p->H;
  ctx.h = p->h;
  autobal_pendulum_k_and_kc_(p, &ctx.k, &ctx.kc);
  if ((st = damped_stable_pred(rw_min, &ctx, &prev)) != 0) return st;
  vint[0] = prev ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
  for (i = 1; i < n_sweep; i++) {
    double a = rw_min + (rw_max - rw_min) * (double)(i - 1) / (double)(n_sweep - 1);
    double b = i + 1 == n_sweep ? rw_max : rw_min + (rw_max - rw_min) * (double)i / (double)(n_sweep - 1);
    int cur;
    if (autobal_pendulum_cancelled_(ws)) return AUTOBAL_ECANCELLED;
    if ((st = damped_stable_pred(b, &ctx, &cur)) != 0) return st;
    if (cur != prev && nc >= cap) {
      /* one change more than the list holds: stop before refining it */
      truncated = 1;
      break;
    }
    if (cur != prev) {
      double lo, hi, x, fa, fb;
      if ((st = autobal_bisect_change(damped_stable_pred, &ctx, a, b, 0.0, 1e-13, &lo, &hi,
                                      &ws->err)) != 0)
        return st;
      x = 0.5 * (lo + hi);
      /* polish on max Re (continuous, crosses 0 transversally) */
      {
        double wa = lo - 1e-9 * (1 + lo), wb = hi + 1e-9 * (1 + hi);
        if (wa < a) wa = a;
        if (wb > b) wb = b;
        if ((st = autobal_pendulum_damped_maxre_fn_(wa, &ctx, &fa)) != 0) return st;
        if ((st = autobal_pendulum_damped_maxre_fn_(wb, &ctx, &fb)) != 0) return st;
        if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
          double root;
          if (autobal_root_brent(autobal_pendulum_damped_maxre_fn_, &ctx, wa, wb, 0.0, 1e-14, 200, &root, &ws->err) ==
              AUTOBAL_SUCCESS)
            x = root;
        }
      }
      autobal_error_clear(&ws->err);
      rw[nc] = x;
      vint[nc + 1] = cur ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
      nc++;
    }
    prev = cur;
  }
  if (!truncated) return crit_set_fill(out, rw, vint, nc, 0, rw_min, rw_max);
  /* truncated (nc = cap >= 1): the results cover [rw_min, rw[nc-1]] only.  The interval
   * after the last recorded change becomes (rw[nc-1], rw[nc-1]) and is dropped when stable:
   * no stable interval extends past the last recorded change. */
  (void)crit_set_fill(out, rw, vint, nc, 0, rw_min, rw[nc - 1]);
  if (out->n_stable > 0 && out->stable_lo[out->n_stable - 1] == rw[nc - 1] &&
      out->stable_hi[out->n_stable - 1] == rw[nc - 1]) {
    out->n_stable--;
    out->stable_lo[out->n_stable] = 0.0;
    out->stable_hi[out->n_stable] = 0.0;
  }
  out->truncated = 1;
  return autobal_error_set(&ws->err, AUTOBAL_WARNING,
                           "critical_speeds_damped: more than %zu stability changes for R_w in "
                           "[%.9g, %.9g] (the capacity of the list): the first %zu are kept and "
                           "the search stopped at the next one; the results cover R_w in [%.9g, "
                           "%.12g] only (up to the last kept change). Narrow the range (e.g. "
                           "rw_max <= %.12g) or split it",
                           cap, rw_min, rw_max, nc, rw_min, rw[nc - 1], rw[nc - 1]);
}

int autobal_pendulum_critical_speeds_damped(autobal_pendulum_workspace *ws,
                                            const autobal_pendulum_params *p, double rw_min,
                                            double rw_max, size_t n_sweep,
                                            autobal_pendulum_crit_set *out) {
  return autobal_pendulum_critical_speeds_damped_cap_(ws, p, rw_min, rw_max, n_sweep,
                                                      AUTOBAL_PENDULUM_MAX_CRIT, out);
}

/* ======================================================================== */
/* Closed forms and series (13)-(18), R_m^(1)                               */
/* ======================================================================== */

int autobal_pendulum_rw1_k0(double R_m, double *rw1, autobal_error *err) {
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "");
  if (st) return st;
  if (rw1) *rw1 = 1.0; /* (13) */
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw23_k0_series_small(double R_m, double *rw2, double *rw3,
                                          autobal_error *err) {
  double eps;
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "");
  if (st) return st;
  eps = cbrt(R_m / 2.0);
  /* (14), 0 < R_m < 0.05 */
  if (rw2) *rw2 = 1.0 + (49.0 / 16.0) * R_m + (12397.0 / 1024.0) * R_m * R_m;
  if (rw3) *rw3 = 1.0 + 2.0 * eps + (7.0 / 3.0) * eps * eps + (29.0 / 8.0) * eps * eps * eps;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw23_k0_series_large(double R_m, double *rw2, double *rw3,
                                          autobal_error *err) {
  double q, q2, pre, even, odd;
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.25, 1, "");
  if (st) return st;
  q = sqrt((0.25 - R_m) / 2.0); /* (14), corrected q */
  q2 = q * q;
  pre = 1.0 / (8.0 * q2);
  even = 1.0 + 5.5 * q2 - (155.0 / 8.0) * q2 * q2;
  odd = 2.0 * q - (37.0 / 4.0) * q2 * q;
  /* upper signs R_w3, lower signs R_w2 */
  if (rw3) *rw3 = pre * (even + odd);
  if (rw2) *rw2 = pre * (even - odd);
  return AUTOBAL_SUCCESS;
}

typedef struct {
  double s;
} u_ctx;

/* R_m = (u^3/(1-2u^2))^2  <=>  u^3 + 2 sqrt(R_m) u^2 - sqrt(R_m) = 0 on (0, 1/sqrt 2) */
static int u_fn(double u, void *vctx, double *fx) {
  const u_ctx *c = (const u_ctx *)vctx;
  *fx = u * u * u + 2.0 * c->s * u * u - c->s;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw1_k1(double R_m, double *rw1, double *u_out, autobal_error *err) {
  u_ctx c;
  double u;
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "");
  if (st) return st;
  c.s = sqrt(R_m);
  /* f(0) = -s < 0, f(1/sqrt 2) = 2^{-3/2} > 0, f increasing on u > 0 */
  st = autobal_root_brent(u_fn, &c, 0.0, sqrt(0.5), 1e-300, 4 * DBL_EPSILON, 400, &u, err);
  if (st) return st;
  if (u_out) *u_out = u;
  if (rw1) *rw1 = sqrt(1.0 - u * u) / (1.0 - 2.0 * u * u); /* (16) */
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw1_k1_series(double R_m, double *rw1, autobal_error *err) {
  double s;
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.5, 1, "");
  if (st) return st;
  s = cbrt(R_m);
  if (rw1) *rw1 = 1.0 + 1.5 * s + 0.875 * s * s + (1.0 / 48.0) * s * s * s; /* (17) */
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rw23_k1(double R_m, double *rw23, autobal_error *err) {
  int st = autobal_check_param(err, "R_m", R_m, 0.0, 1, 0.25, 1, "");
  if (st) return st;
  if (rw23) *rw23 = sqrt(2.0 * (1.0 - 2.0 * R_m)) / (1.0 - 4.0 * R_m); /* (18) */
  return AUTOBAL_SUCCESS;
}

/* g'(u) for g(u) = R_w1(u) of (16) - R_w2/3(R_m(u)) of (18) */
static int g_prime_fn(double u, void *vctx, double *fx) {
  double A = sqrt(1.0 - u * u), B = 1.0 - 2.0 * u * u;
  double t = u * u * u / B, tp = (3.0 * u * u * B + 4.0 * u * u * u * u) / (B * B);
  double Rm = t * t, Rmp = 2.0 * t * tp;
  double C = sqrt(2.0 * (1.0 - 2.0 * Rm)), E = 1.0 - 4.0 * Rm;
  double d16 = (-u * B / A + 4.0 * u * A) / (B * B);
  double d18 = (-2.0 * E / C + 4.0 * C) / (E * E);
  (void)vctx;
  *fx = d16 - d18 * Rmp;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_rm1(double *rm1, double *rw, autobal_error *err) {
  /* The curves touch where g has a double zero: g <= 0 near it with a
   * maximum 0, so g'(u) = 0 there.  Bracket the sign change of g' from + to -
   * by a scan over u (R_m(u) < 1/4 needs u < 0.5615), then Brent. */
  double a = 0.30, fa, u = 0.0, g;
  int i, st, found = 0;
  g_prime_fn(a, NULL, &fa);
  for (i = 1; i <= 200 && !found; i++) {
    double b = 0.30 + (0.56 - 0.30) * i / 200.0, fb;
    g_prime_fn(b, NULL, &fb);
    if (fa > 0 && fb <= 0) {
      st = autobal_root_brent(g_prime_fn, NULL, a, b, 1e-300, 4 * DBL_EPSILON, 400, &u, err);
      if (st) return st;
      found = 1;
    }
    a = b;
    fa = fb;
  }
  if (!found)
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "rm1: no maximum of (16) - (18) found");
  {
    double B = 1.0 - 2.0 * u * u, t = u * u * u / B, Rm = t * t;
    double r16 = sqrt(1.0 - u * u) / B;
    double r18 = sqrt(2.0 * (1.0 - 2.0 * Rm)) / (1.0 - 4.0 * Rm);
    g = r16 - r18;
    if (fabs(g) > 1e-8 * r16)
      return autobal_error_set(err, AUTOBAL_ENUMERIC,
                               "rm1: curves (16) and (18) do not touch at u = %.17g (gap %g)", u, g);
    if (rm1) *rm1 = Rm;
    if (rw) *rw = r16;
  }
  return AUTOBAL_SUCCESS;
}
