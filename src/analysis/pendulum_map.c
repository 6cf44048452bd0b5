/* pendulum_map.c: stability maps of the two-pendulum autobalancer over (R_m, R_w) for one k
 * or every unbalance (docs/pendulum.md, "Maps"): lanes of grid points through the kernel of
 * (6) and the two-stage Routh test, undamped verdicts with a double-precision filter, OpenMP
 * rows.  The verdicts are bitwise those of the one-point functions.
 *
 * Also the maps and sweeps over any parameter (autobal_pendulum_grid*), the physical keys among
 * them: a point with a physical key is converted by the model's autobal_pendulum_params_from_physical
 * (the configuration's own conversion (2)-(3)), never by a copy of it.
 *
 * May use: pendulum_critical.h and pendulum_verdict.h (workspace, verdicts, the Routh kernel,
 * the damped margin), the model's kernel of (6) (models/pendulum/pendulum_internal.h) and its
 * conversion (2)-(3), the numerics, core (internal.h).  Nothing in src/ below calls it. */
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

/* the exact test (long double, else integers) with the map's convention: paper = the
 * first approximation (MARGINAL, exactly on a boundary, counts as STABLE); otherwise the
 * verdict of autobal_pendulum_verdict (autobal_pendulum_undamped_semisimple_): at R_w = 0
 * and, for k = 0, at R_w = 1 the root lambda = 0 is not semisimple (UNSTABLE), any other
 * MARGINAL stays MARGINAL */
static int undamped_map_exact(double Rm, double Rw, double k, int paper) {
  int v = autobal_pendulum_undamped_verdict_exact_(Rm, Rw, k);
  if (v != AUTOBAL_VERDICT_MARGINAL) return v;
  if (paper) return AUTOBAL_VERDICT_STABLE; /* on a boundary */
  return (Rw == 0.0 || (k == 0.0 && Rw == 1.0)) ? AUTOBAL_VERDICT_UNSTABLE : AUTOBAL_VERDICT_MARGINAL;
}

/* The map's undamped verdicts for 0 < k < 1 of MAP_LANES lanes (R_w[l], k[l]):
 * P(x) of (10), c_j with magnitudes m_j; unstable iff c_1 < 0 or the quartic
 * test says so (c_0, c_2, c_3, c_4 > 0 always). */
static MAP_INLINE void undamped_lanes(const mvec *Rwp, double Rm, const mvec *kp, int paper, int *v) {
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
    if (v[l] == 0) v[l] = undamped_map_exact(Rm, MV_L(Rw, l), MV_L(k, l), paper);
  }
}

/* The map's undamped verdict at one point and one k (see undamped_map_exact for paper). */
static int undamped_map_verdict(double Rm, double Rw, double k, int paper) {
  double W = Rw * Rw;
  int v = 0;
  /* lambda = 0 not semisimple (autobal_pendulum_undamped_semisimple_); the filters below
   * leave these points undecided anyway (a0 = 0), this says it explicitly */
  if (!paper && (Rw == 0.0 || (k == 0.0 && Rw == 1.0))) return AUTOBAL_VERDICT_UNSTABLE;
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
    undamped_lanes(&Rwv, Rm, &kv, paper, vl);
    return vl[0];
  }
  if (v == 0) v = undamped_map_exact(Rm, Rw, k, paper); /* undecided in double */
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
      vv = undamped_map_verdict(Rm, Rw, k, s->paper_convention);
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
    if (mc->has_zero) worst = undamped_map_verdict(Rm, Rw, 0.0, s->paper_convention);
    if (mc->has_one && worst != AUTOBAL_VERDICT_UNSTABLE) {
      int v1 = undamped_map_verdict(Rm, Rw, 1.0, s->paper_convention);
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
      undamped_lanes(&Rwv, Rm, &kv, s->paper_convention, vl);
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
      undamped_lanes(&Rwv, Rm, &kv, s->paper_convention, vl);
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


/* ======================================================================== */
/* Maps and sweeps over any parameter                                       */
/* ======================================================================== */

static const char *const param_names[AUTOBAL_PENDULUM_NPARAM] = {
    "R_w", "R_m", "H", "h", "k", "psi0", "H/h", "M", "e", "m", "l", "c", "H1", "H2", "omega"};
static const char *const param_dims[AUTOBAL_PENDULUM_NPARAM] = {
    "R_w", "R_m", "H", "h", "k", "psi0", "H_over_h", "M", "e", "m", "l", "c", "H1", "H2", "omega"};
/* SI units of the physical keys: those of autobal_pendulum_physical and of the configuration */
static const char *const param_units[AUTOBAL_PENDULUM_NPARAM] = {
    "1", "1", "1", "1", "1", "rad", "1", "kg", "m", "kg", "m", "N/m", "N m s", "N s/m", "rad/s"};
static const char *const param_desc[AUTOBAL_PENDULUM_NPARAM] = {
    "rotor speed omega/omega0",
    "mass ratio m/(M + 2m)",
    "external (shaft) damping H2/(omega0 M_sigma)",
    "pendulum damping H1/(m l^2 omega0)",
    "unbalance parameter sin^2(2 psi0)",
    "pendulum angle of the main motion (4)",
    "ratio of the external to the pendulum damping H/h",
    "rotor mass M (physical key, converted by (2)-(3) at each point)",
    "eccentricity e of the rotor's centre of mass (physical key, converted by (2)-(3) at each point)",
    "mass m of each pendulum (physical key, converted by (2)-(3) at each point)",
    "pendulum rod length l (physical key, converted by (2)-(3) at each point)",
    "shaft stiffness c (physical key, converted by (2)-(3) at each point)",
    "viscous moment coefficient H1 of each pendulum (physical key, converted by (2)-(3) at each point)",
    "external viscous damping H2 of the shaft (physical key, converted by (2)-(3) at each point)",
    "rotor speed omega (physical key, converted by (2)-(3) at each point)"};

#define P_BIT(x) (1u << (x))
/* the physical keys each dimensionless parameter is a function of, by (2)-(3) */
static const unsigned param_deps[AUTOBAL_PENDULUM_PARAM_H_RATIO + 1] = {
    /* R_w  */ P_BIT(AUTOBAL_PENDULUM_PARAM_OMEGA) | P_BIT(AUTOBAL_PENDULUM_PARAM_C) | P_BIT(AUTOBAL_PENDULUM_PARAM_M) |
        P_BIT(AUTOBAL_PENDULUM_PARAM_MP),
    /* R_m  */ P_BIT(AUTOBAL_PENDULUM_PARAM_M) | P_BIT(AUTOBAL_PENDULUM_PARAM_MP),
    /* H    */ P_BIT(AUTOBAL_PENDULUM_PARAM_H2) | P_BIT(AUTOBAL_PENDULUM_PARAM_C) | P_BIT(AUTOBAL_PENDULUM_PARAM_M) |
        P_BIT(AUTOBAL_PENDULUM_PARAM_MP),
    /* h    */ P_BIT(AUTOBAL_PENDULUM_PARAM_H1) | P_BIT(AUTOBAL_PENDULUM_PARAM_MP) | P_BIT(AUTOBAL_PENDULUM_PARAM_L) |
        P_BIT(AUTOBAL_PENDULUM_PARAM_C) | P_BIT(AUTOBAL_PENDULUM_PARAM_M),
    /* k    */ P_BIT(AUTOBAL_PENDULUM_PARAM_M) | P_BIT(AUTOBAL_PENDULUM_PARAM_E) | P_BIT(AUTOBAL_PENDULUM_PARAM_MP) |
        P_BIT(AUTOBAL_PENDULUM_PARAM_L),
    /* psi0 */ P_BIT(AUTOBAL_PENDULUM_PARAM_M) | P_BIT(AUTOBAL_PENDULUM_PARAM_E) | P_BIT(AUTOBAL_PENDULUM_PARAM_MP) |
        P_BIT(AUTOBAL_PENDULUM_PARAM_L),
    /* H/h = H2 m l^2 / (H1 (M + 2m)): c and omega cancel */
    P_BIT(AUTOBAL_PENDULUM_PARAM_H2) | P_BIT(AUTOBAL_PENDULUM_PARAM_H1) | P_BIT(AUTOBAL_PENDULUM_PARAM_MP) |
        P_BIT(AUTOBAL_PENDULUM_PARAM_L) | P_BIT(AUTOBAL_PENDULUM_PARAM_M)};

const char *autobal_pendulum_param_name(int param) {
  return param >= 0 && param < AUTOBAL_PENDULUM_NPARAM ? param_names[param] : NULL;
}
const char *autobal_pendulum_param_dim(int param) {
  return param >= 0 && param < AUTOBAL_PENDULUM_NPARAM ? param_dims[param] : NULL;
}
const char *autobal_pendulum_param_unit(int param) {
  return param >= 0 && param < AUTOBAL_PENDULUM_NPARAM ? param_units[param] : NULL;
}
const char *autobal_pendulum_param_description(int param) {
  return param >= 0 && param < AUTOBAL_PENDULUM_NPARAM ? param_desc[param] : NULL;
}
int autobal_pendulum_param_lookup(const char *name) {
  int i;
  if (name == NULL) return -1;
  for (i = 0; i < AUTOBAL_PENDULUM_NPARAM; i++)
    if (!strcmp(name, param_names[i]) || !strcmp(name, param_dims[i])) return i;
  return -1;
}
int autobal_pendulum_param_is_physical(int param) {
  return param >= AUTOBAL_PENDULUM_PARAM_M && param <= AUTOBAL_PENDULUM_PARAM_OMEGA;
}
int autobal_pendulum_param_depends(int dimensionless, int physical) {
  if (dimensionless < 0 || dimensionless > AUTOBAL_PENDULUM_PARAM_H_RATIO || !autobal_pendulum_param_is_physical(physical))
    return 0;
  return (param_deps[dimensionless] & P_BIT(physical)) != 0;
}

int autobal_pendulum_param_check(int param, double v, autobal_error *err) {
  char name[32];
  double lo = 0.0, hi;
  int lo_open, hi_open;
  const char *unit = "";
  if (param < 0 || param >= AUTOBAL_PENDULUM_NPARAM)
    return autobal_error_set(err, AUTOBAL_EINVAL, "unknown pendulum parameter %d", param);
  switch (param) {
  case AUTOBAL_PENDULUM_PARAM_R_M:
    lo_open = 1, hi = 0.5, hi_open = 1;
    break;
  case AUTOBAL_PENDULUM_PARAM_K:
    lo_open = 0, hi = 1.0, hi_open = 0;
    break;
  case AUTOBAL_PENDULUM_PARAM_PSI0:
    lo_open = 0, hi = 1.5707963267948966, hi_open = 1, unit = "rad";
    break;
  case AUTOBAL_PENDULUM_PARAM_H_RATIO:
    lo_open = 1, hi = AUTOBAL_PENDULUM_MAX_RATIO, hi_open = 0;
    break;
  /* the physical keys: the bounds of autobal_pendulum_params_from_physical for the key alone */
  case AUTOBAL_PENDULUM_PARAM_M:
  case AUTOBAL_PENDULUM_PARAM_MP:
  case AUTOBAL_PENDULUM_PARAM_L:
  case AUTOBAL_PENDULUM_PARAM_C:
    lo_open = 1, hi = INFINITY, hi_open = 1, unit = param_units[param];
    break;
  case AUTOBAL_PENDULUM_PARAM_E:
  case AUTOBAL_PENDULUM_PARAM_H1:
  case AUTOBAL_PENDULUM_PARAM_H2:
  case AUTOBAL_PENDULUM_PARAM_OMEGA:
    lo_open = 0, hi = INFINITY, hi_open = 1, unit = param_units[param];
    break;
  default: /* R_w, H, h */
    lo_open = 0, hi = AUTOBAL_PENDULUM_MAX_RATIO, hi_open = 0;
    break;
  }
  /* the test of autobal_check_param, without formatting the key's name: a sweep checks every
   * axis value (1e7 of them took 5 s in snprintf before its first point) */
  if (isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi)) return AUTOBAL_SUCCESS;
  snprintf(name, sizeof name, "pendulum.%s", param_names[param]);
  return autobal_check_param(err, name, v, lo, lo_open, hi, hi_open, unit);
}

/* the field of a physical key */
static double *phys_field(autobal_pendulum_physical *q, int param) {
  switch (param) {
  case AUTOBAL_PENDULUM_PARAM_M: return &q->M;
  case AUTOBAL_PENDULUM_PARAM_E: return &q->e;
  case AUTOBAL_PENDULUM_PARAM_MP: return &q->m;
  case AUTOBAL_PENDULUM_PARAM_L: return &q->l;
  case AUTOBAL_PENDULUM_PARAM_C: return &q->c;
  case AUTOBAL_PENDULUM_PARAM_H1: return &q->H1;
  case AUTOBAL_PENDULUM_PARAM_H2: return &q->H2;
  case AUTOBAL_PENDULUM_PARAM_OMEGA: return &q->omega;
  default: return NULL;
  }
}

static double phys_get(const autobal_pendulum_physical *q, int param) {
  autobal_pendulum_physical c = *q;
  return *phys_field(&c, param);
}

/* does the physical set with the key at v convert (the configuration's path) */
static int phys_inside(const autobal_pendulum_physical *phys, int param, double v) {
  autobal_pendulum_physical q = *phys;
  autobal_pendulum_params out;
  *phys_field(&q, param) = v;
  return autobal_pendulum_params_from_physical(&q, &out, NULL) == AUTOBAL_SUCCESS;
}

/* from `good` (inside) towards +inf (dir > 0) or 0 (dir < 0): the last value inside before the
 * domain ends, INFINITY / 0 when it does not (the key's own bound) */
static double phys_domain_end(const autobal_pendulum_physical *phys, int param, double good, int dir) {
  double bad, x;
  int it;
  if (dir > 0) {
    x = good > 0.0 ? 2.0 * good : 1e-300;
    while (phys_inside(phys, param, x)) {
      good = x;
      if (x > 1e300) return INFINITY;
      x *= 2.0;
    }
  } else {
    if (!(good > 0.0)) return 0.0;
    x = 0.5 * good;
    while (phys_inside(phys, param, x)) {
      good = x;
      if (x < 1e-300) return 0.0;
      x *= 0.5;
    }
  }
  bad = x; /* good and bad within a factor 2: bisect to adjacent doubles */
  for (it = 0; it < 2000; it++) {
    double mid = good + 0.5 * (bad - good);
    if (mid == good || mid == bad) break;
    if (phys_inside(phys, param, mid)) good = mid;
    else bad = mid;
  }
  return good;
}

int autobal_pendulum_param_domain(const autobal_pendulum_physical *phys, int param, double *lo, double *hi,
                                  autobal_error *err) {
  autobal_pendulum_params out;
  double v;
  int st;
  if (phys == NULL || lo == NULL || hi == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "param_domain: NULL argument");
  if (!autobal_pendulum_param_is_physical(param))
    return autobal_error_set(err, AUTOBAL_EINVAL, "param_domain: %s is not a physical key (allowed M, e, m, l, c, H1, H2, omega)",
                             param >= 0 && param < AUTOBAL_PENDULUM_NPARAM ? param_names[param] : "?");
  if ((st = autobal_pendulum_params_from_physical(phys, &out, err)) != 0) return st;
  v = phys_get(phys, param);
  *lo = phys_domain_end(phys, param, v, -1);
  *hi = phys_domain_end(phys, param, v, +1);
  return AUTOBAL_SUCCESS;
}

/* set one direct parameter (not the ratio, not a physical key) */
static void param_set(autobal_pendulum_params *p, int param, double v) {
  switch (param) {
  case AUTOBAL_PENDULUM_PARAM_R_W: p->R_w = v; break;
  case AUTOBAL_PENDULUM_PARAM_R_M: p->R_m = v; break;
  case AUTOBAL_PENDULUM_PARAM_H: p->H = v; break;
  case AUTOBAL_PENDULUM_PARAM_HP: p->h = v; break;
  case AUTOBAL_PENDULUM_PARAM_K: p->psi0 = 0.5 * asin(sqrt(v)); break;
  case AUTOBAL_PENDULUM_PARAM_PSI0: p->psi0 = v; break;
  default: break;
  }
}

/* the physical keys a dimensionless parameter depends on, as text ("omega, c, M, m") */
static void deps_text(int dimensionless, char *buf, size_t len) {
  int i;
  size_t n = 0;
  buf[0] = '\0';
  for (i = AUTOBAL_PENDULUM_PARAM_M; i <= AUTOBAL_PENDULUM_PARAM_OMEGA && n < len; i++)
    if (autobal_pendulum_param_depends(dimensionless, i)) {
      int w = snprintf(buf + n, len - n, "%s%s", n ? ", " : "", param_names[i]);
      if (w < 0) break;
      n += (size_t)w;
    }
}

/* the combination of two axes (values aside) */
static int params_pair_check(const autobal_pendulum_params *base, const autobal_pendulum_physical *phys, int p1,
                             int p2, autobal_error *err) {
  int r1 = p1 == AUTOBAL_PENDULUM_PARAM_H_RATIO, r2 = p2 == AUTOBAL_PENDULUM_PARAM_H_RATIO;
  int other = r1 ? p2 : p1, i;
  if (p1 < 0 || p1 >= AUTOBAL_PENDULUM_NPARAM || p2 < -1 || p2 >= AUTOBAL_PENDULUM_NPARAM)
    return autobal_error_set(err, AUTOBAL_EINVAL, "unknown pendulum parameter (%d, %d): allowed 0..%d",
                             p1, p2, AUTOBAL_PENDULUM_NPARAM - 1);
  if (p1 == p2)
    return autobal_error_set(err, AUTOBAL_EINVAL, "both axes are pendulum.%s: give two different parameters",
                             param_names[p1]);
  for (i = 0; i < 2; i++) {
    int a = i ? p2 : p1, b = i ? p1 : p2;
    if (!autobal_pendulum_param_is_physical(a)) continue;
    if (phys == NULL)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "pendulum.%s is a physical key: it needs the physical set ([pendulum] given by M, e, m, "
                               "l, c, H1, H2, omega, not by the dimensionless keys R_w, R_m, H, h, k or psi0)",
                               param_names[a]);
    if (b >= 0 && autobal_pendulum_param_depends(b, a)) {
      char deps[64];
      deps_text(b, deps, sizeof deps);
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "axes pendulum.%s and pendulum.%s cannot be combined: %s is a function of %s by (2)-(3) "
                               "(it depends on %s); pair a physical key with a dimensionless one that does not depend "
                               "on it, or with another physical key",
                               param_names[a], param_names[b], param_names[b], param_names[a], deps);
    }
  }
  if ((p1 == AUTOBAL_PENDULUM_PARAM_K && p2 == AUTOBAL_PENDULUM_PARAM_PSI0) ||
      (p2 == AUTOBAL_PENDULUM_PARAM_K && p1 == AUTOBAL_PENDULUM_PARAM_PSI0))
    return autobal_error_set(err, AUTOBAL_EINVAL, "axes k and psi0 are the same parameter (k = sin^2(2 psi0))");
  if ((r1 || r2) && autobal_pendulum_param_is_physical(other)) {
    if (!(phys->H1 > 0.0))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "axis H/h needs pendulum.H1 > 0 (it keeps h of each point and sets H = (H/h) h), got "
                               "pendulum.H1 = %g N m s",
                               phys->H1);
  } else if ((r1 || r2) && other != AUTOBAL_PENDULUM_PARAM_H && other != AUTOBAL_PENDULUM_PARAM_HP && !(base->h > 0.0)) {
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "axis H/h needs pendulum.h > 0 (it keeps h and sets H = (H/h) h), got "
                             "pendulum.h = %g; or put h or H on the other axis",
                             base->h);
  }
  return AUTOBAL_SUCCESS;
}

/* a physical set outside the model's domain at a point: the key (and the other physical axis),
 * the conversion's message and the interval of the key at the other values of the point */
static int phys_domain_error(const autobal_pendulum_physical *phys, const autobal_pendulum_physical *q, int pa,
                             int pb, const char *why, autobal_error *err) {
  char other[96] = "", range[160] = "";
  const char *u = param_units[pa];
  autobal_pendulum_physical at = *q;
  double lo, hi, v = phys_get(q, pa);
  if (pb >= 0)
    snprintf(other, sizeof other, " (with pendulum.%s = %.6g %s)", param_names[pb], phys_get(q, pb), param_units[pb]);
  /* the interval of the key with the others at this point, found from the configured value */
  *phys_field(&at, pa) = phys_get(phys, pa);
  if (autobal_pendulum_param_domain(&at, pa, &lo, &hi, NULL) == AUTOBAL_SUCCESS) {
    int lo_open = pa == AUTOBAL_PENDULUM_PARAM_M || pa == AUTOBAL_PENDULUM_PARAM_MP || pa == AUTOBAL_PENDULUM_PARAM_L ||
                  pa == AUTOBAL_PENDULUM_PARAM_C || lo > 0.0;
    if (isinf(hi))
      snprintf(range, sizeof range, ": at the other values of this point pendulum.%s must lie in %c%.6g, inf) %s",
               param_names[pa], lo_open ? '(' : '[', lo, u);
    else
      snprintf(range, sizeof range, ": at the other values of this point pendulum.%s must lie in %c%.6g, %.6g) %s",
               param_names[pa], lo_open ? '(' : '[', lo, hi, u);
  }
  return autobal_error_set(err, AUTOBAL_EINVAL, "pendulum.%s = %.6g %s%s leaves the model's domain (%s)%s",
                           param_names[pa], v, u, other, why, range);
}

static int params_vary_i(const autobal_pendulum_params *base, const autobal_pendulum_physical *phys, int p1,
                         double v1, int p2, double v2, autobal_pendulum_params *out,
                         autobal_pendulum_physical *phys_out, autobal_error *err) {
  autobal_pendulum_params q = *base;
  int st, ph1 = autobal_pendulum_param_is_physical(p1), ph2 = p2 >= 0 && autobal_pendulum_param_is_physical(p2);
  if ((st = autobal_pendulum_param_check(p1, v1, err)) != 0) return st;
  if (p2 >= 0 && (st = autobal_pendulum_param_check(p2, v2, err)) != 0) return st;
  if (ph1 || ph2) {
    /* the physical set with the key(s) changed, converted as the configuration is */
    autobal_pendulum_physical x = *phys;
    autobal_error cerr;
    if (ph1) *phys_field(&x, p1) = v1;
    if (ph2) *phys_field(&x, p2) = v2;
    if (autobal_pendulum_params_from_physical(&x, &q, &cerr) != AUTOBAL_SUCCESS)
      return phys_domain_error(phys, &x, ph1 ? p1 : p2, ph1 && ph2 ? p2 : -1, cerr.message, err);
    if (phys_out) *phys_out = x;
  } else if (phys_out && phys) {
    *phys_out = *phys;
  }
  if (!ph1 && p1 != AUTOBAL_PENDULUM_PARAM_H_RATIO) param_set(&q, p1, v1);
  if (p2 >= 0 && !ph2 && p2 != AUTOBAL_PENDULUM_PARAM_H_RATIO) param_set(&q, p2, v2);
  if (p1 == AUTOBAL_PENDULUM_PARAM_H_RATIO || p2 == AUTOBAL_PENDULUM_PARAM_H_RATIO) {
    double r = p1 == AUTOBAL_PENDULUM_PARAM_H_RATIO ? v1 : v2;
    int other = p1 == AUTOBAL_PENDULUM_PARAM_H_RATIO ? p2 : p1;
    if (other == AUTOBAL_PENDULUM_PARAM_H) q.h = q.H / r;
    else q.H = r * q.h;
    if (!(q.H <= AUTOBAL_PENDULUM_MAX_RATIO && q.h <= AUTOBAL_PENDULUM_MAX_RATIO))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "H/h = %g gives H = %g, h = %g: must be <= %g (allowed range [0, %g])", r,
                               q.H, q.h, AUTOBAL_PENDULUM_MAX_RATIO, AUTOBAL_PENDULUM_MAX_RATIO);
  }
  if ((st = autobal_pendulum_params_validate(&q, err)) != 0) return st;
  *out = q;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_params_vary(const autobal_pendulum_params *base, int param1, double v1,
                                 int param2, double v2, autobal_pendulum_params *out,
                                 autobal_error *err) {
  int st;
  if (base == NULL || out == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "params_vary: NULL argument");
  if ((st = params_pair_check(base, NULL, param1, param2, err)) != 0) return st;
  return params_vary_i(base, NULL, param1, v1, param2, v2, out, NULL, err);
}

int autobal_pendulum_params_vary_physical(const autobal_pendulum_params *base, const autobal_pendulum_physical *phys,
                                          int param1, double v1, int param2, double v2, autobal_pendulum_params *out,
                                          autobal_pendulum_physical *phys_out, autobal_error *err) {
  int st;
  if (base == NULL || out == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "params_vary: NULL argument");
  if ((st = params_pair_check(base, phys, param1, param2, err)) != 0) return st;
  return params_vary_i(base, phys, param1, v1, param2, v2, out, phys_out, err);
}

int autobal_pendulum_grid_check(const autobal_pendulum_grid_spec *s, autobal_error *err) {
  size_t i, n2;
  int st;
  char name[40];
  autobal_pendulum_params q;
  if (s == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "grid: NULL spec");
  if ((st = autobal_pendulum_params_validate(&s->base, err)) != 0) return st;
  if ((st = params_pair_check(&s->base, s->phys, s->param1, s->param2, err)) != 0) return st;
  n2 = s->param2 < 0 ? 1 : s->n2;
  if ((s->n1 > 0 && s->v1 == NULL) || (s->param2 >= 0 && n2 > 0 && s->v2 == NULL))
    return autobal_error_set(err, AUTOBAL_EINVAL, "grid: NULL axis array");
  if (s->n_threads < 0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter n_threads = %d is out of range: allowed [0, inf)",
                             s->n_threads);
  if (s->k == NULL && s->n_k != 0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "grid: k is NULL but n_k = %zu", s->n_k);
  if (s->k != NULL && s->n_k > 0) {
    if (s->param1 == AUTOBAL_PENDULUM_PARAM_K || s->param1 == AUTOBAL_PENDULUM_PARAM_PSI0 ||
        s->param2 == AUTOBAL_PENDULUM_PARAM_K || s->param2 == AUTOBAL_PENDULUM_PARAM_PSI0)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "every unbalance (a set of k) cannot be combined with a k or psi0 axis");
    if (s->param1 == AUTOBAL_PENDULUM_PARAM_E || s->param2 == AUTOBAL_PENDULUM_PARAM_E)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "every unbalance (a set of k) cannot be combined with an e axis (pendulum.e changes "
                               "only the unbalance, psi0, which the k set replaces)");
    for (i = 0; i < s->n_k; i++) {
      snprintf(name, sizeof name, "k[%zu]", i);
      if ((st = autobal_check_param(err, name, s->k[i], 0.0, 0, 1.0, 0, "")) != 0) return st;
    }
  }
  if (s->n1 > 0 && (s->param2 < 0 || n2 > 0) &&
      (autobal_pendulum_param_is_physical(s->param1) || autobal_pendulum_param_is_physical(s->param2))) {
    /* a physical axis: first the ends of the axes, so that a range leaving the model's domain is
     * reported at its end.  Every condition of the domain is monotone in each key (M e < 2 m l;
     * R_w, H, h <= 1e6), so on a box the worst point is a corner, whatever the order of the
     * axis values. */
    size_t c1, c2, ii[2], jj[2];
    double x;
    ii[0] = ii[1] = jj[0] = jj[1] = 0;
    for (i = 1, x = s->v1[0]; i < s->n1; i++) if (s->v1[i] < x) x = s->v1[i], ii[0] = i;
    for (i = 1, x = s->v1[0]; i < s->n1; i++) if (s->v1[i] > x) x = s->v1[i], ii[1] = i;
    if (s->param2 >= 0) {
      for (i = 1, x = s->v2[0]; i < n2; i++) if (s->v2[i] < x) x = s->v2[i], jj[0] = i;
      for (i = 1, x = s->v2[0]; i < n2; i++) if (s->v2[i] > x) x = s->v2[i], jj[1] = i;
    }
    for (c1 = 0; c1 < 2; c1++)
      for (c2 = 0; c2 < 2; c2++)
        if ((st = params_vary_i(&s->base, s->phys, s->param1, s->v1[ii[c1]], s->param2,
                                s->param2 >= 0 ? s->v2[jj[c2]] : 0.0, &q, NULL, err)) != 0)
          return st;
  }
  /* every value of each axis alone, then the pairs that the ratio rule couples (an axis
   * value is checked with the other axis at its first value) */
  for (i = 0; i < s->n1; i++)
    if ((st = params_vary_i(&s->base, s->phys, s->param1, s->v1[i], s->param2,
                            s->param2 >= 0 && n2 > 0 ? s->v2[0] : 0.0, &q, NULL, err)) != 0)
      return st;
  if (s->param2 >= 0 && s->n1 > 0)
    for (i = 0; i < n2; i++)
      if ((st = params_vary_i(&s->base, s->phys, s->param1, s->v1[0], s->param2, s->v2[i], &q, NULL, err)) != 0)
        return st;
  if (s->param1 == AUTOBAL_PENDULUM_PARAM_H_RATIO || s->param2 == AUTOBAL_PENDULUM_PARAM_H_RATIO) {
    size_t j; /* the ratio couples the axes: check every pair */
    for (i = 0; i < s->n1; i++)
      for (j = 0; j < n2 && s->param2 >= 0; j++)
        if ((st = params_vary_i(&s->base, s->phys, s->param1, s->v1[i], s->param2, s->v2[j], &q, NULL, err)) != 0)
          return st;
  }
  return AUTOBAL_SUCCESS;
}

/* the point verdict without the spec's checks */
static int grid_point_i(const autobal_pendulum_grid_spec *s, double v1, double v2,
                        autobal_pendulum_workspace *ws, int *verdict, double *max_real,
                        autobal_error *err) {
  autobal_pendulum_params q;
  double kone, kcone, mre = -INFINITY;
  const double *ks;
  size_t nk, i;
  int st, worst = AUTOBAL_VERDICT_STABLE, und;
  if ((st = params_vary_i(&s->base, s->phys, s->param1, v1, s->param2, v2, &q, NULL, err)) != 0) return st;
  und = q.H == 0.0 && q.h == 0.0;
  if (s->k != NULL && s->n_k > 0) {
    ks = s->k, nk = s->n_k;
  } else {
    autobal_pendulum_k_and_kc_(&q, &kone, &kcone);
    ks = &kone, nk = 1;
  }
  for (i = 0; i < nk; i++) {
    double k = ks[i], kc = nk == 1 && ks == &kone ? kcone : 1.0 - k;
    int v;
    if (und) {
      v = s->paper_convention ? undamped_map_exact(q.R_m, q.R_w, k, 1)
                              : autobal_pendulum_undamped_semisimple_(q.R_m, q.R_w, k, NULL);
    } else if ((st = autobal_pendulum_damped_verdict_k_(q.R_w, q.R_m, q.H, q.h, k, kc, &v, NULL, err)) != 0) {
      return st;
    }
    if (v < worst) worst = v;
    if (max_real) {
      autobal_pendulum_damped_ctx_ c;
      double m;
      if (ws == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "grid: max_real needs a workspace");
      c.ws = ws;
      c.R_m = q.R_m;
      c.H = q.H;
      c.h = q.h;
      c.k = k;
      c.kc = kc;
      if ((st = autobal_pendulum_damped_maxre_fn_(q.R_w, &c, &m)) != 0)
        return autobal_error_set(err, st, "%s", autobal_pendulum_errmsg(ws));
      if (m > mre) mre = m;
    } else if (worst == AUTOBAL_VERDICT_UNSTABLE) {
      break; /* the worst verdict is known */
    }
  }
  *verdict = worst;
  if (max_real) *max_real = mre;
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_grid_point(const autobal_pendulum_grid_spec *s, double v1, double v2,
                                autobal_pendulum_workspace *ws, int *verdict, double *max_real,
                                autobal_error *err) {
  int st;
  if (verdict == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "grid_point: NULL output");
  if (s == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "grid: NULL spec");
  if ((st = params_pair_check(&s->base, s->phys, s->param1, s->param2, err)) != 0) return st;
  if (s->k == NULL && s->n_k != 0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "grid: k is NULL but n_k = %zu", s->n_k);
  return grid_point_i(s, v1, v2, ws, verdict, max_real, err);
}

int autobal_pendulum_grid(const autobal_pendulum_grid_spec *s, signed char *verdict, double *max_real,
                          autobal_error *err) {
  size_t n2, ntot;
  int st, fail = AUTOBAL_SUCCESS;
  autobal_error ferr;
  if (verdict == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "grid: NULL output");
  if ((st = autobal_pendulum_grid_check(s, err)) != 0) return st;
  n2 = s->param2 < 0 ? 1 : s->n2;
  ntot = s->n1 * n2;
  if (ntot == 0) return AUTOBAL_SUCCESS;
  if (s->param1 == AUTOBAL_PENDULUM_PARAM_R_M && s->param2 == AUTOBAL_PENDULUM_PARAM_R_W) {
    /* the fast map, the same verdicts (its one-k case takes k, 1 - k) */
    autobal_pendulum_map_spec m;
    double k1 = autobal_pendulum_k(&s->base);
    memset(&m, 0, sizeof m);
    m.R_m = s->v1, m.n_Rm = s->n1, m.R_w = s->v2, m.n_Rw = s->n2;
    m.H = s->base.H, m.h = s->base.h;
    if (s->k != NULL && s->n_k > 0) m.k = s->k, m.n_k = s->n_k;
    else m.k = &k1, m.n_k = 1;
    m.n_threads = s->n_threads;
    m.paper_convention = s->paper_convention;
    return autobal_pendulum_map(&m, verdict, max_real, err);
  }
  autobal_error_clear(&ferr);
#ifdef AUTOBAL_HAVE_OPENMP
  {
    int nth = s->n_threads > 0 ? s->n_threads : omp_get_max_threads();
#pragma omp parallel num_threads(nth)
    {
      autobal_pendulum_workspace *ws = NULL;
      autobal_error lerr;
      int local = AUTOBAL_SUCCESS;
      long long t;
      autobal_error_clear(&lerr);
      if (max_real && (ws = autobal_pendulum_workspace_alloc()) == NULL) local = AUTOBAL_ENOMEM;
#pragma omp for schedule(dynamic, 16)
      for (t = 0; t < (long long)ntot; t++) {
        size_t i = (size_t)t / n2, j = (size_t)t % n2;
        int v = 0;
        if (local != AUTOBAL_SUCCESS) continue;
        local = grid_point_i(s, s->v1[i], s->param2 >= 0 ? s->v2[j] : 0.0, ws, &v,
                             max_real ? &max_real[t] : NULL, &lerr);
        verdict[t] = (signed char)v;
      }
      if (local != AUTOBAL_SUCCESS) {
#pragma omp critical(autobal_pendulum_grid_fail)
        {
          if (fail == AUTOBAL_SUCCESS) fail = local, ferr = lerr;
        }
      }
      autobal_pendulum_workspace_free(ws);
    }
  }
#else
  {
    autobal_pendulum_workspace *ws = NULL;
    size_t t;
    if (max_real && (ws = autobal_pendulum_workspace_alloc()) == NULL) fail = AUTOBAL_ENOMEM;
    for (t = 0; t < ntot && fail == AUTOBAL_SUCCESS; t++) {
      size_t i = t / n2, j = t % n2;
      int v = 0;
      fail = grid_point_i(s, s->v1[i], s->param2 >= 0 ? s->v2[j] : 0.0, ws, &v,
                          max_real ? &max_real[t] : NULL, &ferr);
      verdict[t] = (signed char)v;
    }
    autobal_pendulum_workspace_free(ws);
  }
#endif
  if (fail == AUTOBAL_ENOMEM)
    return autobal_error_set(err, AUTOBAL_ENOMEM, "grid: cannot allocate a per-thread workspace");
  if (fail != AUTOBAL_SUCCESS)
    return autobal_error_set(err, fail, "grid: evaluation failed at a point: %s", ferr.message);
  return AUTOBAL_SUCCESS;
}

int autobal_pendulum_grid_critical(const autobal_pendulum_grid_spec *s, double lo, double hi,
                                   int log_scale, double xtol_rel, double *x, int *v_lo, int *v_hi,
                                   autobal_error *err) {
  int st, vl, vh, vm, it;
  if (s == NULL || x == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "grid_critical: NULL argument");
  if (s->param2 >= 0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "grid_critical: the spec must be a line (param2 = -1)");
  if (!(lo < hi) || (log_scale && !(lo > 0.0)) || !(xtol_rel > 0.0 && xtol_rel < 0.1))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "grid_critical: need lo < hi (lo > 0 on a log scale) and 0 < xtol_rel < 0.1, "
                             "got lo = %g, hi = %g, xtol_rel = %g",
                             lo, hi, xtol_rel);
  if ((st = autobal_pendulum_grid_point(s, lo, 0.0, NULL, &vl, NULL, err)) != 0) return st;
  if ((st = grid_point_i(s, hi, 0.0, NULL, &vh, NULL, err)) != 0) return st;
  if (vl == vh)
    return autobal_error_set(err, AUTOBAL_EINVAL, "grid_critical: the verdicts at %.17g and %.17g are equal (%d)",
                             lo, hi, vl);
  for (it = 0; it < 2000; it++) {
    double mid = log_scale ? sqrt(lo) * sqrt(hi) : lo + 0.5 * (hi - lo);
    double scale = fabs(lo) > fabs(hi) ? fabs(lo) : fabs(hi);
    if (hi - lo <= xtol_rel * scale || hi - lo <= 1e-300 || !(mid > lo && mid < hi)) break;
    if ((st = grid_point_i(s, mid, 0.0, NULL, &vm, NULL, err)) != 0) return st;
    if (vm == vl) lo = mid; /* the change lies above mid */
    else hi = mid, vh = vm;
  }
  *x = log_scale ? sqrt(lo) * sqrt(hi) : lo + 0.5 * (hi - lo);
  if (v_lo) *v_lo = vl;
  if (v_hi) *v_hi = vh;
  return AUTOBAL_SUCCESS;
}
