/* pendulum_map.c: stability maps of the two-pendulum autobalancer over (R_m, R_w) for one k
 * or every unbalance (docs/pendulum.md, "Maps"): lanes of grid points through the kernel of
 * (6) and the two-stage Routh test, undamped verdicts with a double-precision filter, OpenMP
 * rows.  The verdicts are bitwise those of the one-point functions.
 *
 * May use: pendulum_critical.h and pendulum_verdict.h (workspace, verdicts, the Routh kernel,
 * the damped margin), the model's kernel of (6) (models/pendulum/pendulum_internal.h), the
 * numerics, core (internal.h).  Nothing in src/ below calls it. */
#include "autobal/pendulum.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef AUTOBAL_HAVE_OPENMP
#include <omp.h>
#endif

#include "analysis/pendulum_critical.h"
#include "analysis/pendulum_verdict.h"
#include "internal.h"
#include "models/pendulum/pendulum_internal.h"

/* ======================================================================== */
/* Maps                                                                     */
/* ======================================================================== */

#define MAP_DEFAULT_NK 65
/* Grid points per OpenMP work item (one row segment; a multiple of MAP_LANES,
 * so that the grouping of points into lanes does not depend on the schedule) */
#define MAP_TILE 64
/* Damped verdicts of MAP_LANES polynomials (6) with coefficients c[j] and
 * bounds ce[j], j = 0..8 (deflate: lambda = 0 divided out, degree 7, for
 * k == 0), s2 = max(1, W) per lane.  A lane with a non-finite coefficient
 * or bound (overflow at huge R_w) or a leading coefficient <= 0 goes to the
 * scalar test, which reports it (AUTOBAL_EINVAL) like autobal_pendulum_verdict. */
static MAP_INLINE int damped_lanes(const mvec *c, const mvec *ce, const mvec *s2, int deflate,
                                   int *v) {
  mvec col[9], colU[9], chk = ce[0];
  mmask alive, neg = MV_MASK0;
  size_t l, j, row, n = deflate ? 7 : 8, off = deflate ? 1 : 0;
  for (j = 1; j < 9; j++) chk = chk + ce[j];
  /* lanes stage 1 may decide: finite coefficients and bounds (chk - chk is
   * NaN for inf and NaN) and a positive leading coefficient; the kernel
   * runs on all lanes, the others' results are not used */
  alive = MV_CMP(chk - chk == 0.0) & MV_CMP(c[8] > 0.0);
  if (deflate) autobal_pendulum_routh_lanes7_(c + 1, ce + 1, s2, col, colU);
  else autobal_pendulum_routh_lanes8_(c, ce, s2, col, colU);
  /* the verdict rule, on all lanes at once: alive = every row so far
   * clears its bound, neg = a decided negative entry was met while alive */
  for (row = 1; row <= n; row++) {
    alive = alive & MV_CMP(MV_ABS(col[row]) > 2.0 * colU[row]);
    neg = neg | (alive & MV_CMP(col[row] < 0.0));
  }
  for (l = 0; l < MAP_LANES; l++) {
    v[l] = MV_L(neg, l) ? AUTOBAL_VERDICT_UNSTABLE : MV_L(alive, l) ? AUTOBAL_VERDICT_STABLE : 2;
    if (v[l] == 2) { /* near the boundary (or a bad lane): the full test */
      double cl[9], cel[9];
      int st;
      for (j = 0; j < 9; j++) cl[j] = MV_L(c[j], l), cel[j] = MV_L(ce[j], l);
      st = autobal_poly_hurwitz_err(cl + off, cel + off, n + 1, &v[l], NULL, NULL);
      if (st) return st;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* ---- undamped verdicts with a double-precision filter ------------------- */

/* The map's undamped verdict (MARGINAL, a point on a boundary, counts as
 * STABLE) is that of autobal_pendulum_undamped_verdict_ld_.  Its deciding quantities are
 * evaluated first in double together with the magnitude sums of their terms
 * (built from magnitudes of the coefficients, W - 1 counted as W + 1); a
 * quantity whose value exceeds MAP_FILTER times its magnitude sum has the
 * same sign in long double, far beyond the long-double rounding bound
 * PEND_GAMMA * LDBL_EPSILON (the double evaluation and the difference
 * between W in double and in long double perturb it by < 1e3 DBL_EPSILON of
 * the same sum).  Only when a needed quantity is below that threshold (near
 * a critical speed) is the long-double test run: the verdicts are those of
 * autobal_pendulum_undamped_verdict. */
#define MAP_FILTER 1e-10

/* The deciding quantities of the quartic c (ascending, lane-wise) and the
 * sums of the magnitudes of their terms evaluated on m (>= |c|): the
 * discriminant (the 16 terms of autobal_pendulum_quartic_disc_ld_), P8 = 8ac - 3b^2 and
 * D4 = 64a^3e - 16a^2c^2 + 16ab^2c - 16a^2bd - 3b^4 (autobal_pendulum_quartic_aux_ld_). */
typedef struct {
  mvec disc, mag, P8, m8, D4, m4;
} quartic_q;

static MAP_INLINE void quartic_quantities(const mvec *c, const mvec *m, quartic_q *r) {
  mvec a = c[4], b = c[3], cc = c[2], d = c[1], e = c[0];
  mvec a2 = a * a, b2 = b * b, c2 = cc * cc, d2 = d * d, e2 = e * e;
  mvec ma = m[4], mb = m[3], mc = m[2], md = m[1], me = m[0];
  mvec ma2 = ma * ma, mb2 = mb * mb, mc2 = mc * mc, md2 = md * md, me2 = me * me;
  r->disc = 256.0 * a2 * a * e2 * e - 192.0 * a2 * b * d * e2 - 128.0 * a2 * c2 * e2 +
            144.0 * a2 * cc * d2 * e - 27.0 * a2 * d2 * d2 + 144.0 * a * b2 * cc * e2 -
            6.0 * a * b2 * d2 * e - 80.0 * a * b * c2 * d * e + 18.0 * a * b * cc * d2 * d +
            16.0 * a * c2 * c2 * e - 4.0 * a * c2 * cc * d2 - 27.0 * b2 * b2 * e2 +
            18.0 * b2 * b * cc * d * e - 4.0 * b2 * b * d2 * d - 4.0 * b2 * c2 * cc * e +
            b2 * c2 * d2;
  r->mag = 256.0 * ma2 * ma * me2 * me + 192.0 * ma2 * mb * md * me2 + 128.0 * ma2 * mc2 * me2 +
           144.0 * ma2 * mc * md2 * me + 27.0 * ma2 * md2 * md2 + 144.0 * ma * mb2 * mc * me2 +
           6.0 * ma * mb2 * md2 * me + 80.0 * ma * mb * mc2 * md * me +
           18.0 * ma * mb * mc * md2 * md + 16.0 * ma * mc2 * mc2 * me +
           4.0 * ma * mc2 * mc * md2 + 27.0 * mb2 * mb2 * me2 + 18.0 * mb2 * mb * mc * md * me +
           4.0 * mb2 * mb * md2 * md + 4.0 * mb2 * mc2 * mc * me + mb2 * mc2 * md2;
  r->P8 = 8.0 * a * cc - 3.0 * b2;
  r->m8 = 8.0 * ma * mc + 3.0 * mb2;
  r->D4 = 64.0 * a2 * a * e - 16.0 * a2 * c2 + 16.0 * a * b2 * cc - 16.0 * a2 * b * d -
          3.0 * b2 * b2;
  r->m4 = 64.0 * ma2 * ma * me + 16.0 * ma2 * mc2 + 16.0 * ma * mb2 * mc + 16.0 * ma2 * mb * md +
          3.0 * mb2 * mb2;
}

/* sign of x if |x| > MAP_FILTER * mag, else 0 (undecided) */
static MAP_INLINE int filt_sign(double x, double mag) {
  if (x > MAP_FILTER * mag) return 1;
  if (x < -MAP_FILTER * mag) return -1;
  return 0;
}

/* The quartic part of the undamped test (k > 0) for lane l: UNSTABLE iff
 * disc < 0 or P8 >= 0 or D4 >= 0; 0 when undecided. */
static MAP_INLINE int quartic_decide(const quartic_q *q, size_t l) {
  int sd = filt_sign(MV_L(q->disc, l), MV_L(q->mag, l)), s8, s4;
  if (sd < 0) return AUTOBAL_VERDICT_UNSTABLE;
  if (sd == 0) return 0;
  s8 = filt_sign(MV_L(q->P8, l), MV_L(q->m8, l));
  if (s8 > 0) return AUTOBAL_VERDICT_UNSTABLE;
  s4 = filt_sign(MV_L(q->D4, l), MV_L(q->m4, l));
  if (s4 > 0) return AUTOBAL_VERDICT_UNSTABLE;
  if (s8 < 0 && s4 < 0) return AUTOBAL_VERDICT_STABLE;
  return 0;
}

/* the exact long-double test, with the map's convention MARGINAL -> STABLE */
static int undamped_map_exact(double Rm, double Rw, double k) {
  int v = autobal_pendulum_undamped_verdict_exact_(Rm, Rw, k);
  return v == AUTOBAL_VERDICT_MARGINAL ? AUTOBAL_VERDICT_STABLE : v; /* on a boundary */
}

/* The map's undamped verdicts for 0 < k < 1 of MAP_LANES lanes (R_w[l], k[l]):
 * P(x) of (10), c_j with magnitudes m_j; unstable iff c_1 < 0 or the quartic
 * test says so (c_0, c_2, c_3, c_4 > 0 always). */
static MAP_INLINE void undamped_lanes(const mvec *Rwp, double Rm, const mvec *kp, int *v) {
  mvec Rw = *Rwp, k = *kp, W = Rw * Rw, r2 = k * Rm * Rm, W2 = W * W, W3 = W2 * W;
  mvec a0 = 2.0 * Rm * W2 * (W - 1.0), m0 = 2.0 * Rm * W2 * (W + 1.0);
  mvec a2 = (W - 1.0) * (W - 1.0) + 2.0 * Rm * W * (W + 6.0);
  mvec m2 = (W + 1.0) * (W + 1.0) + 2.0 * Rm * W * (W + 6.0);
  mvec a4 = 2.0 * (1.0 - Rm) * (W + 1.0);
  mvec c[5], m[5];
  quartic_q q;
  size_t l;
  c[0] = r2 * W2 * W2, m[0] = c[0];
  c[1] = a0 + 4.0 * r2 * W3, m[1] = m0 + 4.0 * r2 * W3;
  c[2] = a2 + 6.0 * r2 * W2, m[2] = m2 + 6.0 * r2 * W2;
  c[3] = a4 + 4.0 * r2 * W, m[3] = c[3];
  c[4] = (1.0 - 2.0 * Rm) + r2, m[4] = c[4];
  quartic_quantities(c, m, &q);
  for (l = 0; l < MAP_LANES; l++) {
    int sd = filt_sign(MV_L(c[1], l), MV_L(m[1], l));
    v[l] = sd < 0 ? AUTOBAL_VERDICT_UNSTABLE : sd > 0 ? quartic_decide(&q, l) : 0;
    if (v[l] == 0) v[l] = undamped_map_exact(Rm, MV_L(Rw, l), MV_L(k, l));
  }
}

/* The map's undamped verdict at one point and one k: STABLE or UNSTABLE. */
static int undamped_map_verdict(double Rm, double Rw, double k) {
  double W = Rw * Rw;
  int v = 0;
  if (k == 1.0) {
    mvec c[5], m[5];
    quartic_q q;
    c[0] = MV_BCAST(-W), m[0] = MV_BCAST(W);
    c[1] = MV_BCAST(2.0 * Rw), m[1] = c[1];
    c[2] = MV_BCAST(W - 1.0), m[2] = MV_BCAST(W + 1.0);
    c[3] = MV_BCAST(-2.0 * Rw), m[3] = c[1];
    c[4] = MV_BCAST(1.0 - Rm), m[4] = c[4];
    quartic_quantities(c, m, &q);
    v = quartic_decide(&q, 0);
  } else if (k == 0.0) {
    /* x times the cubic a6 x^3 + a4 x^2 + a2 x + a0: unstable iff a0 < 0 or
     * its discriminant < 0 */
    double a0 = 2.0 * Rm * W * W * (W - 1.0), m0 = 2.0 * Rm * W * W * (W + 1.0);
    double a2 = (W - 1.0) * (W - 1.0) + 2.0 * Rm * W * (W + 6.0);
    double m2 = (W + 1.0) * (W + 1.0) + 2.0 * Rm * W * (W + 6.0);
    double a4 = 2.0 * (1.0 - Rm) * (W + 1.0), a6 = 1.0 - 2.0 * Rm;
    int s0 = filt_sign(a0, m0);
    if (s0 < 0) v = AUTOBAL_VERDICT_UNSTABLE;
    else if (s0 > 0) {
      double d = 18.0 * a6 * a4 * a2 * a0 - 4.0 * a4 * a4 * a4 * a0 + a4 * a4 * a2 * a2 -
                 4.0 * a6 * a2 * a2 * a2 - 27.0 * a6 * a6 * a0 * a0;
      double md = 18.0 * a6 * a4 * m2 * m0 + 4.0 * a4 * a4 * a4 * m0 + a4 * a4 * m2 * m2 +
                  4.0 * a6 * m2 * m2 * m2 + 27.0 * a6 * a6 * m0 * m0;
      int sd = filt_sign(d, md);
      v = sd < 0 ? AUTOBAL_VERDICT_UNSTABLE : sd > 0 ? AUTOBAL_VERDICT_STABLE : 0;
    }
  } else {
    mvec Rwv = MV_BCAST(Rw), kv = MV_BCAST(k);
    int vl[MAP_LANES];
    undamped_lanes(&Rwv, Rm, &kv, vl);
    return vl[0];
  }
  if (v == 0) v = undamped_map_exact(Rm, Rw, k); /* undecided in double */
  return v;
}

/* ---- grid points --------------------------------------------------------- */

typedef struct {
  const autobal_pendulum_map_spec *s;
  const double *ks;
  size_t nk;
  int undamped;
  int has_zero; /* some k == 0 (the damped test deflates lambda = 0 there) */
  int has_one;  /* some k == 1 (the undamped test uses the factor P1 there) */
} map_ctx;

/* Point (Rm, Rw) with a root solve per k for max_real (the slow path). */
static int map_point(const map_ctx *mc, double Rm, double Rw, autobal_pendulum_workspace *ws,
                     signed char *v, double *mr) {
  const autobal_pendulum_map_spec *s = mc->s;
  size_t i;
  int worst = AUTOBAL_VERDICT_STABLE;
  double mre = -INFINITY;
  autobal_pendulum_char_parts_t_ P;
  memset(&P, 0, sizeof P);
  if (!mc->undamped) autobal_pendulum_char_parts_(Rw, Rm, s->H, s->h, &P, NULL); /* independent of k */
  for (i = 0; i < mc->nk; i++) {
    double k = mc->ks[i], kc = 1.0 - k, m;
    int vv, st;
    autobal_pendulum_damped_ctx_ c;
    if (mc->undamped) {
      vv = undamped_map_verdict(Rm, Rw, k);
    } else {
      double coef[9], cerr[9];
      autobal_pendulum_char_poly_from_parts_(Rw, Rm, &P, k, kc, coef, cerr);
      st = autobal_pendulum_sign_test_poly_(coef, cerr, Rw * Rw, k == 0.0, &vv, NULL, NULL);
      if (st) return st;
    }
    if (vv < worst) worst = vv;
    c.ws = ws;
    c.R_m = Rm;
    c.H = s->H;
    c.h = s->h;
    c.k = k;
    c.kc = kc;
    st = autobal_pendulum_damped_maxre_fn_(Rw, &c, &m);
    if (st) return st;
    if (m > mre) mre = m;
  }
  *v = (signed char)worst;
  *mr = mre;
  return AUTOBAL_SUCCESS;
}

/* Verdict at one point over the whole k set (no max_real): the k set is
 * taken MAP_LANES at a time and the scan stops at the first UNSTABLE group.
 * *hint (per thread) is the group that was unstable last time, tried first:
 * the verdict (a minimum over all k) does not depend on the order. */
MAP_CLONES static int map_point_all_k(const map_ctx *mc, double Rm, double Rw, size_t *hint,
                                      signed char *v) {
  const autobal_pendulum_map_spec *s = mc->s;
  size_t ng = (mc->nk + MAP_LANES - 1) / MAP_LANES, t, l;
  int worst = AUTOBAL_VERDICT_STABLE, st, und = mc->undamped;
  autobal_pendulum_char_parts_t_ P;
  mvec c[9], ce[9], s2 = MV_BCAST(Rw * Rw > 1.0 ? Rw * Rw : 1.0), Rwv = MV_BCAST(Rw);
  /* the special values, once each: k == 0 (damped: lambda = 0 deflated;
   * undamped: the cubic) and, undamped, k == 1 (the factor P1) */
  autobal_pendulum_char_parts_v_(&Rwv, Rm, s->H, s->h, P.A, P.Aa, P.B, NULL); /* (unused when undamped) */
  if (und) {
    if (mc->has_zero) worst = undamped_map_verdict(Rm, Rw, 0.0);
    if (mc->has_one && worst != AUTOBAL_VERDICT_UNSTABLE) {
      int v1 = undamped_map_verdict(Rm, Rw, 1.0);
      if (v1 < worst) worst = v1;
    }
  } else if (mc->has_zero) {
    mvec kz = MV_BCAST(0.0), kcz = MV_BCAST(1.0);
    int vz[MAP_LANES];
    autobal_pendulum_char_poly_from_parts_v_(&Rwv, Rm, P.A, P.Aa, P.B, &kz, &kcz, c, ce);
    if ((st = damped_lanes(c, ce, &s2, 1, vz)) != 0) return st;
    worst = vz[0];
  }
  for (t = 0; t < ng && worst != AUTOBAL_VERDICT_UNSTABLE; t++) {
    size_t g = (*hint + t) % ng, i0 = g * MAP_LANES, n = 0;
    double fill = 0.0;
    mvec kv;
    int vl[MAP_LANES];
    for (l = 0; l < MAP_LANES && i0 + l < mc->nk; l++) {
      double k = mc->ks[i0 + l];
      if (k != 0.0 && !(und && k == 1.0)) fill = k, n++;
    }
    if (n == 0) continue; /* only special values here, done above */
    kv = MV_BCAST(fill);
    for (l = 0; l < MAP_LANES && i0 + l < mc->nk; l++) {
      double k = mc->ks[i0 + l];
      if (k != 0.0 && !(und && k == 1.0)) MV_L(kv, l) = k;
    }
    if (und) {
      undamped_lanes(&Rwv, Rm, &kv, vl);
    } else {
      mvec kcv = 1.0 - kv;
      autobal_pendulum_char_poly_from_parts_v_(&Rwv, Rm, P.A, P.Aa, P.B, &kv, &kcv, c, ce);
      if ((st = damped_lanes(c, ce, &s2, 0, vl)) != 0) return st;
    }
    for (l = 0; l < MAP_LANES; l++)
      if (vl[l] < worst) worst = vl[l];
    if (worst == AUTOBAL_VERDICT_UNSTABLE) *hint = g;
  }
  *v = (signed char)worst;
  return AUTOBAL_SUCCESS;
}

/* One work item: row i, columns [j0, j1). */
MAP_CLONES static int map_tile(const map_ctx *mc, size_t i, size_t j0, size_t j1,
                    autobal_pendulum_workspace *ws, size_t *hint, signed char *verdict,
                    double *max_real) {
  const autobal_pendulum_map_spec *s = mc->s;
  double Rm = s->R_m[i];
  size_t j, l, base = i * s->n_Rw;
  int st;
  if (max_real) {
    for (j = j0; j < j1; j++)
      if ((st = map_point(mc, Rm, s->R_w[j], ws, &verdict[base + j], &max_real[base + j])) != 0)
        return st;
    return AUTOBAL_SUCCESS;
  }
  if (mc->nk > 1 || (mc->undamped && (mc->ks[0] == 0.0 || mc->ks[0] == 1.0))) {
    for (j = j0; j < j1; j++)
      if ((st = map_point_all_k(mc, Rm, s->R_w[j], hint, &verdict[base + j])) != 0) return st;
    return AUTOBAL_SUCCESS;
  }
  if (mc->undamped) { /* one k in (0, 1): MAP_LANES neighbouring R_w at once */
    for (j = j0; j < j1; j += MAP_LANES) {
      mvec Rwv, kv = MV_BCAST(mc->ks[0]);
      int vl[MAP_LANES];
      for (l = 0; l < MAP_LANES; l++) MV_L(Rwv, l) = s->R_w[j + l < j1 ? j + l : j1 - 1];
      undamped_lanes(&Rwv, Rm, &kv, vl);
      for (l = 0; l < MAP_LANES && j + l < j1; l++) verdict[base + j + l] = (signed char)vl[l];
    }
    return AUTOBAL_SUCCESS;
  }
  /* damped, one k: MAP_LANES neighbouring R_w at once (the last group is
   * padded with copies of its last point) */
  for (j = j0; j < j1; j += MAP_LANES) {
    mvec c[9], ce[9], s2, Rwv, kv = MV_BCAST(mc->ks[0]), kcv = 1.0 - kv;
    autobal_pendulum_char_parts_t_ P;
    int vl[MAP_LANES];
    for (l = 0; l < MAP_LANES; l++) {
      double Rw = s->R_w[j + l < j1 ? j + l : j1 - 1];
      MV_L(Rwv, l) = Rw;
      MV_L(s2, l) = Rw * Rw > 1.0 ? Rw * Rw : 1.0;
    }
    autobal_pendulum_char_parts_v_(&Rwv, Rm, s->H, s->h, P.A, P.Aa, P.B, NULL);
    autobal_pendulum_char_poly_from_parts_v_(&Rwv, Rm, P.A, P.Aa, P.B, &kv, &kcv, c, ce);
    if ((st = damped_lanes(c, ce, &s2, mc->ks[0] == 0.0, vl)) != 0) return st;
    for (l = 0; l < MAP_LANES && j + l < j1; l++) verdict[base + j + l] = (signed char)vl[l];
  }
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_map(const autobal_pendulum_map_spec *s, signed char *verdict,
                         double *max_real, autobal_error *err) {
  double kdef[MAP_DEFAULT_NK];
  const double *ks;
  size_t nk, i, ntot, tpr, ntiles;
  int st, fail = AUTOBAL_SUCCESS;
  char name[40];
  map_ctx mc;
  if (s == NULL || verdict == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: NULL spec or output");
  if ((s->n_Rm > 0 && s->R_m == NULL) || (s->n_Rw > 0 && s->R_w == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: NULL grid array");
  if ((st = autobal_check_param(err, "H", s->H, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if ((st = autobal_check_param(err, "h", s->h, 0.0, 0, INFINITY, 1, "")) != 0) return st;
  if (s->n_threads < 0)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter n_threads = %d is out of range: allowed [0, inf)",
                             s->n_threads);
  for (i = 0; i < s->n_Rm; i++) {
    snprintf(name, sizeof name, "R_m[%zu]", i);
    if ((st = autobal_check_param(err, name, s->R_m[i], 0.0, 1, 0.5, 1, "")) != 0) return st;
  }
  for (i = 0; i < s->n_Rw; i++) {
    snprintf(name, sizeof name, "R_w[%zu]", i);
    if ((st = autobal_check_param(err, name, s->R_w[i], 0.0, 0, INFINITY, 1, "")) != 0) return st;
  }
  if (s->k == NULL || s->n_k == 0) {
    if (s->k == NULL && s->n_k != 0)
      return autobal_error_set(err, AUTOBAL_EINVAL, "map: k is NULL but n_k = %zu", s->n_k);
    for (i = 0; i < MAP_DEFAULT_NK; i++) kdef[i] = (double)i / (double)(MAP_DEFAULT_NK - 1);
    ks = kdef;
    nk = MAP_DEFAULT_NK;
  } else {
    for (i = 0; i < s->n_k; i++) {
      snprintf(name, sizeof name, "k[%zu]", i);
      if ((st = autobal_check_param(err, name, s->k[i], 0.0, 0, 1.0, 0, "")) != 0) return st;
    }
    ks = s->k;
    nk = s->n_k;
  }
  ntot = s->n_Rm * s->n_Rw;
  if (ntot == 0) return AUTOBAL_SUCCESS;
  mc.s = s;
  mc.ks = ks;
  mc.nk = nk;
  mc.undamped = s->H == 0.0 && s->h == 0.0;
  mc.has_zero = mc.has_one = 0;
  for (i = 0; i < nk; i++) {
    if (ks[i] == 0.0) mc.has_zero = 1;
    if (ks[i] == 1.0) mc.has_one = 1;
  }
  tpr = (s->n_Rw + MAP_TILE - 1) / MAP_TILE;
  ntiles = s->n_Rm * tpr;
#ifdef AUTOBAL_HAVE_OPENMP
  {
    int nth = s->n_threads > 0 ? s->n_threads : omp_get_max_threads();
#pragma omp parallel num_threads(nth)
    {
      autobal_pendulum_workspace *ws = NULL;
      int local = AUTOBAL_SUCCESS;
      size_t hint = 0;
      long long t;
      if (max_real) {
        ws = autobal_pendulum_workspace_alloc();
        if (ws == NULL) local = AUTOBAL_ENOMEM;
      }
#pragma omp for schedule(dynamic, 1)
      for (t = 0; t < (long long)ntiles; t++) {
        size_t ii = (size_t)t / tpr, j0 = ((size_t)t % tpr) * MAP_TILE;
        size_t j1 = j0 + MAP_TILE < s->n_Rw ? j0 + MAP_TILE : s->n_Rw;
        if (local != AUTOBAL_SUCCESS) continue;
        local = map_tile(&mc, ii, j0, j1, ws, &hint, verdict, max_real);
      }
      if (local != AUTOBAL_SUCCESS) {
#pragma omp critical(autobal_pendulum_map_fail)
        {
          if (fail == AUTOBAL_SUCCESS) fail = local;
        }
      }
      autobal_pendulum_workspace_free(ws);
    }
  }
#else
  {
    autobal_pendulum_workspace *ws = NULL;
    size_t t, hint = 0;
    if (max_real) {
      ws = autobal_pendulum_workspace_alloc();
      if (ws == NULL) fail = AUTOBAL_ENOMEM;
    }
    for (t = 0; t < ntiles && fail == AUTOBAL_SUCCESS; t++) {
      size_t ii = t / tpr, j0 = (t % tpr) * MAP_TILE;
      size_t j1 = j0 + MAP_TILE < s->n_Rw ? j0 + MAP_TILE : s->n_Rw;
      fail = map_tile(&mc, ii, j0, j1, ws, &hint, verdict, max_real);
    }
    autobal_pendulum_workspace_free(ws);
  }
#endif
  if (fail == AUTOBAL_ENOMEM)
    return autobal_error_set(err, AUTOBAL_ENOMEM, "map: cannot allocate a per-thread workspace");
  if (fail != AUTOBAL_SUCCESS)
    return autobal_error_set(err, fail, "map: evaluation failed at a grid point (%s)",
                             autobal_strerror(fail));
  return AUTOBAL_SUCCESS;
}

