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

#include "analysis/pendulum_exact.h"

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


/* ======================================================================== */
/* The discriminant of (10) in W and the critical speeds of the undamped    */
/* system, in exact integer arithmetic (analysis/pendulum_exact.h)          */
/* ======================================================================== */

int autobal_pendulum_undamped_discriminant(double R_m, double k, double disc[13],
                                           autobal_error *err) {
  autobal_pendulum_exact ex;
  autobal_xpoly D;
  int st, j;
  long shift;
  if ((st = autobal_pendulum_check_rm_k_(R_m, k, err)) != 0) return st;
  if (disc == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "undamped_discriminant: NULL output");
  autobal_pendulum_exact_init(&ex, R_m, k);
  autobal_xpoly_init(&D);
  autobal_pendulum_exact_disc(&ex, &D); /* L^6 disc, L = 2^(F + 2E) */
  shift = 6 * (ex.F + 2 * ex.E);
  for (j = 0; j < 13; j++) {
    long e;
    double d;
    if (j >= D.len || mpz_sgn(D.c[j]) == 0) {
      disc[j] = 0.0;
      continue;
    }
    d = mpz_get_d_2exp(&e, D.c[j]); /* correctly truncated, then one scaling */
    disc[j] = ldexp(d, (int)(e - shift));
  }
  autobal_xpoly_clear(&D);
  autobal_pendulum_exact_clear(&ex);
  return AUTOBAL_SUCCESS;
}

/* One candidate on the W axis: a root of the discriminant known to lie in [lo, hi] (adjacent
 * or equal doubles), and R_w there. */
typedef struct {
  double lo, hi, rw;
} crit_cand;

static int cmp_cand(const void *pa, const void *pb) {
  const crit_cand *a = (const crit_cand *)pa, *b = (const crit_cand *)pb;
  return (a->lo > b->lo) - (a->lo < b->lo);
}

#define CAND_MAX (2 * AUTOBAL_XPOLY_MAXLEN)

int autobal_pendulum_critical_speeds(autobal_pendulum_workspace *ws, double R_m, double k,
                                     autobal_pendulum_crit_set *out) {
  autobal_pendulum_exact ex;
  autobal_xpoly D, Dp, G;
  crit_cand cand[CAND_MAX];
  double lo[CAND_MAX], hi[CAND_MAX], rw[CAND_MAX];
  int vint[CAND_MAX + 1];
  size_t nr = 0, nc = 0, i;
  int st = AUTOBAL_SUCCESS, unresolved = 0, rc = 0;
  if (ws == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&ws->err);
  if ((st = autobal_pendulum_check_rm_k_(R_m, k, &ws->err)) != 0) return st;
  if (out == NULL) return autobal_error_set(&ws->err, AUTOBAL_EINVAL, "critical_speeds: NULL output");
  memset(out, 0, sizeof *out);
  autobal_pendulum_exact_init(&ex, R_m, k);
  autobal_xpoly_init(&D);
  autobal_xpoly_init(&Dp);
  autobal_xpoly_init(&G);
  /* the discriminant of (10) in x, exactly, with its factor W^j (j = 4 for k > 0, from
   * e = c0 ~ W^4 and d^2 = c1^2 ~ W^4 in every term) divided out: the root W = 0 is no speed */
  autobal_pendulum_exact_disc(&ex, &D);
  (void)autobal_xpoly_strip_low(&D);
  /* its simple roots (sign changes) ... */
  rc = autobal_xpoly_positive_roots(&D, lo, hi, CAND_MAX / 2, &nr, &unresolved);
  for (i = 0; rc == 0 && i < nr; i++) {
    cand[nc].lo = lo[i];
    cand[nc].hi = hi[i];
    nc++;
  }
  /* ... and its multiple roots, the roots of gcd(D, D'): the double roots of (10) where the
   * verdict may be kept, e.g. (18) at k = 1 and W = 1 (x = 0 twice) at k = 0 */
  if (rc == 0) {
    autobal_xpoly_deriv(&Dp, &D);
    autobal_xpoly_gcd(&G, &D, &Dp);
    if (G.len >= 2) rc = autobal_xpoly_positive_roots(&G, lo, hi, CAND_MAX / 2, &nr, &unresolved);
    else nr = 0;
  }
  for (i = 0; rc == 0 && i < nr; i++) {
    size_t j, dup = 0;
    for (j = 0; j < nc; j++) /* a root of odd multiplicity >= 3 is in both lists */
      if (!(hi[i] < cand[j].lo || lo[i] > cand[j].hi)) dup = 1;
    if (dup) continue;
    cand[nc].lo = lo[i];
    cand[nc].hi = hi[i];
    nc++;
  }
  if (rc != 0) {
    st = autobal_error_set(&ws->err, AUTOBAL_ENUMERIC,
                           "critical_speeds: root isolation of the discriminant failed at R_m = %.17g, k = %.17g",
                           R_m, k);
    goto done;
  }
  for (i = 0; i < nc; i++) cand[i].rw = (double)sqrtl(0.5L * ((long double)cand[i].lo + (long double)cand[i].hi));
  qsort(cand, nc, sizeof *cand, cmp_cand);
  /* the exact verdict on every interval between consecutive candidates, at a long double
   * strictly inside it (the midpoint of the gap; beyond the last: 2 hi + 1) */
  for (i = 0; i <= nc; i++) {
    long double a = i == 0 ? 0.0L : cand[i - 1].hi;
    long double b = i == nc ? 2.0L * a + 1.0L : cand[i].lo;
    long double m = 0.5L * (a + b);
    int v;
    if (!(m > a && m < b)) m = a; /* candidates in adjacent ulps: the shared end separates them */
    v = autobal_pendulum_exact_verdict_W(&ex, m);
    if (v == AUTOBAL_VERDICT_MARGINAL) {
      /* only on a root of the discriminant, which the gaps exclude */
      st = autobal_error_set(&ws->err, AUTOBAL_ENUMERIC,
                             "critical_speeds: marginal verdict between critical speeds at W = %.17Lg "
                             "(R_m = %.17g, k = %.17g)", m, R_m, k);
      goto done;
    }
    vint[i] = v;
  }
  for (i = 0; i < nc; i++) rw[i] = cand[i].rw;
  st = crit_set_fill(out, rw, vint, nc, 1, 0.0, INFINITY);
  out->unresolved = unresolved;
done:
  if (st != AUTOBAL_SUCCESS) memset(out, 0, sizeof *out);
  autobal_xpoly_clear(&D);
  autobal_xpoly_clear(&Dp);
  autobal_xpoly_clear(&G);
  autobal_pendulum_exact_clear(&ex);
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
