/* rotor_stability.c: stability of the balanced motions of the rotor with ball
 * autobalancers (docs/rotor.md, (3.14)-(3.16)): margins and verdicts by four methods
 * (Delta's roots, the closed matrix, the full linearization, Floquet multipliers), one point
 * with every method, sweeps, critical values and maps.
 *
 * May use: rotor_floquet.h (linearization, Floquet multipliers), rotor_stab_handle.h (the
 * handle and its member), rotor_closed.h (the closed matrix), the test hooks it defines
 * (rotor_stab_internal.h), the numerics (roots, eigenvalues, bracketing), core (internal.h).
 * Nothing in src/ below it calls back into this file: rotor_stability.c -> rotor_floquet.c
 * -> rotor_stab_handle.c -> rotor_closed.c.  The rotor-housing modes without balls are in
 * rotor_campbell.c. */
#include "autobal/rotor_stability.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#ifdef AUTOBAL_HAVE_OPENMP
#include <omp.h>
#endif

#include "analysis/rotor_closed.h"
#include "analysis/rotor_floquet.h"
#include "analysis/rotor_stab_handle.h"
#include "analysis/rotor_stability.h"
#include "analysis/rotor_stab_internal.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- margins ------------------------------------------------------------------------ */

/* Roots of Delta in 1/s: the polynomial is solved in s = lambda / ws (see the header). */
static int poly_roots(autobal_rotor_stab *s, const double *coef, double *re, double *im,
                      double *ws_out) {
  double cs[AUTOBAL_ROTOR_POLY_LEN], ws, big = 0.0, pw = 1.0;
  size_t k;
  int st;
  if (coef[0] != 0.0 && coef[12] != 0.0) ws = pow(fabs(coef[0] / coef[12]), 1.0 / 12.0);
  else ws = fmax(1.0, fabs(s->cur.omega));
  for (k = 0; k < AUTOBAL_ROTOR_POLY_LEN; k++) {
    cs[k] = coef[k] * pw;
    pw *= ws;
    big = fmax(big, fabs(cs[k]));
  }
  for (k = 0; k < AUTOBAL_ROTOR_POLY_LEN; k++) cs[k] /= big;
  st = autobal_poly_roots(s->pw, cs, AUTOBAL_ROTOR_POLY_LEN, re, im, &s->err);
  if (st != AUTOBAL_SUCCESS) return st;
  for (k = 0; k < AUTOBAL_ROTOR_POLY_LEN - 1; k++) {
    re[k] *= ws;
    im[k] *= ws;
  }
  if (ws_out) *ws_out = ws;
  return AUTOBAL_SUCCESS;
}

/* Margin over n roots excluding `family` roots closest to `center` (0 for roots); the
 * verdict with the handle's tolerance. */
static void roots_margin(const autobal_rotor_stab *s, size_t n, const double *re, const double *im,
                         size_t family, double *margin, int *verdict) {
  double mx = -INFINITY, scale = 1.0;
  size_t i, k;
  unsigned char excl[AUTOBAL_ROTOR_CLOSED_MAX + 2 * AUTOBAL_ROTOR_STAB_MAX_FULL_BALLS + 8];
  memset(excl, 0, sizeof excl);
  for (k = 0; k < family && k < n; k++) {
    size_t best = n;
    double bd = INFINITY;
    for (i = 0; i < n; i++)
      if (!excl[i] && hypot(re[i], im[i]) < bd) {
        bd = hypot(re[i], im[i]);
        best = i;
      }
    if (best < n) excl[best] = 1;
  }
  for (i = 0; i < n; i++) {
    scale = fmax(scale, hypot(re[i], im[i]));
    if (!excl[i] && re[i] > mx) mx = re[i];
  }
  *margin = mx;
  if (mx > s->opt.tol * scale) *verdict = AUTOBAL_VERDICT_UNSTABLE;
  else if (mx < -s->opt.tol * scale) *verdict = AUTOBAL_VERDICT_STABLE;
  else *verdict = AUTOBAL_VERDICT_MARGINAL;
}

static int resolve_method(const autobal_rotor_stab *s, const autobal_rotor_closed *c, int method) {
  if (method == AUTOBAL_ROTOR_STAB_AUTO) method = s->opt.method;
  if (method != AUTOBAL_ROTOR_STAB_AUTO) return method;
  if (c->isotropic && c->closure_ok)
    return c->n_planes == 1 ? AUTOBAL_ROTOR_STAB_POLY : AUTOBAL_ROTOR_STAB_CLOSED;
  if (c->isotropic) return AUTOBAL_ROTOR_STAB_FULL;
  return AUTOBAL_ROTOR_STAB_FLOQUET;
}

static int method_applies(autobal_rotor_stab *s, const autobal_rotor_closed *c, int method) {
  switch (method) {
    case AUTOBAL_ROTOR_STAB_POLY:
      if (c->n_planes != 1 || !c->isotropic || !c->closure_ok)
        return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                                 "method 'poly' needs one plane, isotropic supports, a common h_i/m_i "
                                 "and balls not all on one line (closure of (3.16))");
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_STAB_CLOSED:
      if (!c->isotropic || !c->closure_ok)
        return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                                 "method 'closed' needs isotropic supports, a common h_i/m_i per "
                                 "plane and balls not all on one line");
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_STAB_FULL:
      if (!c->isotropic)
        return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                                 "method 'full' needs isotropic supports (use 'floquet')");
      /* fall through */
    case AUTOBAL_ROTOR_STAB_FLOQUET:
      if (s->tr == NULL)
        return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                                 "methods 'full' and 'floquet' are limited to %d balls (N = %zu)",
                                 AUTOBAL_ROTOR_STAB_MAX_FULL_BALLS, s->N);
      return AUTOBAL_SUCCESS;
    default:
      return autobal_error_set(&s->err, AUTOBAL_EINVAL, "method %d is not valid", method);
  }
}

int autobal_rotor_stab_margin(autobal_rotor_stab *s, int method, double *margin, int *verdict) {
  autobal_rotor_closed c;
  double re[AUTOBAL_ROTOR_CLOSED_MAX], im[AUTOBAL_ROTOR_CLOSED_MAX];
  int st, m;
  if (s == NULL || margin == NULL || verdict == NULL) return AUTOBAL_EINVAL;
  *margin = NAN;
  *verdict = AUTOBAL_ROTOR_VERDICT_NONE;
  if (!(s->cur.omega != 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "the stability of a balanced motion needs omega != 0");
  if (autobal_rotor_stab_update_member_(s) != AUTOBAL_SUCCESS) return AUTOBAL_SUCCESS;
  autobal_rotor_stab_closed_from_handle_(s, &c);
  m = resolve_method(s, &c, method);
  if ((st = method_applies(s, &c, m)) != AUTOBAL_SUCCESS) return st;
  switch (m) {
    case AUTOBAL_ROTOR_STAB_POLY: {
      double coef[AUTOBAL_ROTOR_POLY_LEN];
      if ((st = autobal_rotor_char_poly(&c, coef, NULL, &s->err)) != AUTOBAL_SUCCESS) return st;
      if ((st = poly_roots(s, coef, re, im, NULL)) != AUTOBAL_SUCCESS) return st;
      roots_margin(s, AUTOBAL_ROTOR_POLY_LEN - 1, re, im, 0, margin, verdict);
      return AUTOBAL_SUCCESS;
    }
    case AUTOBAL_ROTOR_STAB_CLOSED: {
      const size_t dim = autobal_rotor_closed_dim(&c);
      if ((st = autobal_rotor_closed_matrix_ws_(&c, s->closed_mat, dim, s->lu_closed, s->perm_closed, &s->err)))
        return st;
      if ((st = autobal_eigen_nonsymm(s->ew_closed, s->closed_mat, re, im, &s->err))) return st;
      roots_margin(s, dim, re, im, 0, margin, verdict);
      return AUTOBAL_SUCCESS;
    }
    case AUTOBAL_ROTOR_STAB_FULL:
      if ((st = autobal_rotor_stab_lin_(s, 0.0, 1)) != AUTOBAL_SUCCESS) return st;
      if ((st = autobal_eigen_nonsymm(s->ew_full, s->Afull, s->full_re, s->full_im, &s->err)))
        return st;
      roots_margin(s, s->ns, s->full_re, s->full_im, autobal_rotor_stab_family_(s), margin,
                   verdict);
      return AUTOBAL_SUCCESS;
    default: { /* FLOQUET */
      const double T = 2.0 * M_PI / fabs(s->cur.omega);
      const double band = fmax(s->opt.tol, 10.0 * s->opt.floquet_rtol) / T;
      if ((st = autobal_rotor_stab_floquet_(s, NULL)) != AUTOBAL_SUCCESS) return st;
      *margin = autobal_rotor_stab_floquet_margin_(s, autobal_rotor_stab_family_(s));
      *verdict = *margin > band ? AUTOBAL_VERDICT_UNSTABLE
                                : (*margin < -band ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_MARGINAL);
      return AUTOBAL_SUCCESS;
    }
  }
}

/* ---- one point, every method ------------------------------------------------------------ */

int autobal_rotor_stab_analyze(autobal_rotor_stab *s, autobal_rotor_stab_result *res) {
  autobal_rotor_closed c;
  int st, m;
  size_t i, fam;
  double scale = 1.0;
  if (s == NULL || res == NULL) return AUTOBAL_EINVAL;
  memset(res, 0, sizeof *res);
  res->verdict = AUTOBAL_ROTOR_VERDICT_NONE;
  res->margin = res->closed_margin = res->full_margin = res->floquet_margin = NAN;
  res->full_mismatch = res->floquet_mismatch = NAN;
  res->hurwitz_verdict = AUTOBAL_VERDICT_MARGINAL;
  res->n_balls = s->N;
  res->psi = s->psi;
  if (!(s->cur.omega != 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "the stability of a balanced motion needs omega != 0");
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) return st;
  autobal_rotor_stab_closed_from_handle_(s, &c);
  fam = autobal_rotor_stab_family_(s);
  res->n_family = fam;
  res->isotropic = c.isotropic;
  res->closure_ok = c.closure_ok;
  res->period = 2.0 * M_PI / fabs(s->cur.omega);
  m = resolve_method(s, &c, AUTOBAL_ROTOR_STAB_AUTO);
  if ((st = method_applies(s, &c, m)) != AUTOBAL_SUCCESS) return st;
  res->method = m;
  /* closed system */
  if (c.isotropic && c.closure_ok) {
    const size_t dim = autobal_rotor_closed_dim(&c);
    double ere[AUTOBAL_ROTOR_CLOSED_MAX], eim[AUTOBAL_ROTOR_CLOSED_MAX];
    size_t perm[AUTOBAL_ROTOR_CLOSED_MAX];
    int v;
    res->n_closed = dim;
    if ((st = autobal_rotor_closed_matrix_ws_(&c, s->closed_mat, dim, s->lu_closed, s->perm_closed, &s->err)))
      return st;
    if ((st = autobal_eigen_nonsymm(s->ew_closed, s->closed_mat, ere, eim, &s->err))) return st;
    if (c.n_planes == 1) {
      double cerr[AUTOBAL_ROTOR_POLY_LEN], cs[AUTOBAL_ROTOR_POLY_LEN], es[AUTOBAL_ROTOR_POLY_LEN];
      double ws = 1.0, pw = 1.0, dist = 0.0;
      if ((st = autobal_rotor_char_poly(&c, res->poly, cerr, &s->err))) return st;
      res->n_poly = AUTOBAL_ROTOR_POLY_LEN;
      if ((st = poly_roots(s, res->poly, res->root_re, res->root_im, &ws))) return st;
      for (i = 0; i < AUTOBAL_ROTOR_POLY_LEN; i++) {
        cs[i] = res->poly[i] * pw;
        es[i] = cerr[i] * pw;
        pw *= ws;
      }
      if ((st = autobal_poly_hurwitz_err(cs, es, AUTOBAL_ROTOR_POLY_LEN, &res->hurwitz_verdict,
                                         &res->hurwitz_n_rhp, &s->err)))
        return st;
      if ((st = autobal_match_roots(dim, res->root_re, res->root_im, ere, eim, perm, &dist,
                                    &s->err)))
        return st;
      for (i = 0; i < dim; i++) {
        res->closed_eig_re[i] = ere[perm[i]];
        res->closed_eig_im[i] = eim[perm[i]];
        scale = fmax(scale, hypot(res->root_re[i], res->root_im[i]));
      }
      res->root_eig_mismatch = dist / scale;
    } else {
      for (i = 0; i < dim; i++) {
        res->root_re[i] = res->closed_eig_re[i] = ere[i];
        res->root_im[i] = res->closed_eig_im[i] = eim[i];
      }
      res->root_eig_mismatch = 0.0;
    }
    roots_margin(s, dim, res->root_re, res->root_im, 0, &res->closed_margin, &v);
    if (m == AUTOBAL_ROTOR_STAB_POLY || m == AUTOBAL_ROTOR_STAB_CLOSED) {
      res->margin = res->closed_margin;
      res->verdict = v;
    }
  }
  if (s->tr == NULL) return AUTOBAL_SUCCESS; /* too many balls for the full model */
  /* full model in rotating coordinates (isotropic) */
  if (c.isotropic) {
    int v;
    if ((st = autobal_rotor_stab_lin_(s, 0.0, 1)) != AUTOBAL_SUCCESS) return st;
    if ((st = autobal_eigen_nonsymm(s->ew_full, s->Afull, s->full_re, s->full_im, &s->err)))
      return st;
    res->n_full = s->ns;
    res->full_re = s->full_re;
    res->full_im = s->full_im;
    roots_margin(s, s->ns, s->full_re, s->full_im, fam, &res->full_margin, &v);
    if (m == AUTOBAL_ROTOR_STAB_FULL) {
      res->margin = res->full_margin;
      res->verdict = v;
    }
    if (res->n_closed > 0 && s->ns <= AUTOBAL_MATCH_MAXN) {
      /* expected: closed roots + per plane (n-2) zeros and (n-2) roots -kappa */
      size_t k = 0, j, q;
      double dist = 0.0, sc2 = 1.0;
      for (i = 0; i < res->n_closed; i++, k++) {
        s->tmp_re[k] = res->root_re[i];
        s->tmp_im[k] = res->root_im[i];
      }
      for (j = 0; j < c.n_planes; j++)
        for (q = 0; q + 2 < c.plane[j].n_balls; q++) {
          s->tmp_re[k] = 0.0;
          s->tmp_im[k++] = 0.0;
          s->tmp_re[k] = -c.plane[j].kappa;
          s->tmp_im[k++] = 0.0;
        }
      if (k == s->ns &&
          autobal_match_roots(k, s->full_re, s->full_im, s->tmp_re, s->tmp_im, NULL, &dist, NULL) ==
              AUTOBAL_SUCCESS) {
        for (i = 0; i < k; i++) sc2 = fmax(sc2, hypot(s->tmp_re[i], s->tmp_im[i]));
        res->full_mismatch = dist / sc2;
      }
    }
  }
  /* Floquet */
  {
    const double T = res->period;
    const double band = fmax(s->opt.tol, 10.0 * s->opt.floquet_rtol) / T;
    if ((st = autobal_rotor_stab_floquet_(s, NULL)) != AUTOBAL_SUCCESS) return st;
    res->n_floquet = s->ns;
    res->mu_re = s->mu_re;
    res->mu_im = s->mu_im;
    res->floquet_margin = autobal_rotor_stab_floquet_margin_(s, fam);
    if (m == AUTOBAL_ROTOR_STAB_FLOQUET) {
      res->margin = res->floquet_margin;
      res->verdict = res->margin > band ? AUTOBAL_VERDICT_UNSTABLE
                                        : (res->margin < -band ? AUTOBAL_VERDICT_STABLE
                                                               : AUTOBAL_VERDICT_MARGINAL);
    }
    if (res->n_full > 0 && s->ns <= AUTOBAL_MATCH_MAXN) {
      double dist = 0.0;
      for (i = 0; i < s->ns; i++) {
        const double mag = exp(s->full_re[i] * T);
        s->tmp_re[i] = mag * cos(s->full_im[i] * T);
        s->tmp_im[i] = mag * sin(s->full_im[i] * T);
      }
      if (autobal_match_roots(s->ns, s->mu_re, s->mu_im, s->tmp_re, s->tmp_im, NULL, &dist, NULL) ==
          AUTOBAL_SUCCESS)
        res->floquet_mismatch = dist;
    }
  }
  return AUTOBAL_SUCCESS;
}

/* ---- sweeps and critical values ------------------------------------------------------- */

/* Everything autobal_rotor_stab_set can change (any parameter id): the working parameters
 * (omega, input, hardware and lumped sets, every plane's scalars; the ball arrays hold the same
 * pointers), the base and current lumped sets and scale factors, and every ball's mass, damping
 * and track radius (into the handle's m_save / h_save / r_save, sized at alloc).  A sweep or critical search saves them first
 * and puts them back bitwise afterwards, also after a failure. */
typedef struct stab_saved {
  autobal_rotor_params cur;
  autobal_rotor_lumped L, Lbase;
  double c_scale, h_scale;
} stab_saved;

static void stab_save(autobal_rotor_stab *s, stab_saved *sv) {
  sv->cur = s->cur;
  sv->L = s->L;
  sv->Lbase = s->Lbase;
  sv->c_scale = s->c_scale;
  sv->h_scale = s->h_scale;
  if (s->N > 0) {
    memcpy(s->m_save, s->m, s->N * sizeof *s->m);
    memcpy(s->h_save, s->h, s->N * sizeof *s->h);
    memcpy(s->r_save, s->r, s->N * sizeof *s->r);
  }
}

static void stab_restore(autobal_rotor_stab *s, const stab_saved *sv) {
  s->cur = sv->cur;
  s->L = sv->L;
  s->Lbase = sv->Lbase;
  s->c_scale = sv->c_scale;
  s->h_scale = sv->h_scale;
  if (s->N > 0) {
    memcpy(s->m, s->m_save, s->N * sizeof *s->m);
    memcpy(s->h, s->h_save, s->N * sizeof *s->h);
    memcpy(s->r, s->r_save, s->N * sizeof *s->r);
  }
}

int autobal_rotor_stab_sweep(autobal_rotor_stab *s, int param, const double *values, size_t n,
                             double *margin, int *verdict) {
  stab_saved sv;
  size_t k;
  int st = AUTOBAL_SUCCESS;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (values == NULL || margin == NULL || verdict == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "sweep: NULL array");
  if (autobal_rotor_stab_param_name(param) == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "sweep: parameter id %d is not valid", param);
  stab_save(s, &sv);
  for (k = 0; k < n; k++) {
    if (autobal_rotor_stab_cancelled_(s)) {
      st = AUTOBAL_ECANCELLED;
      break;
    }
    if ((st = autobal_rotor_stab_set(s, param, values[k])) != AUTOBAL_SUCCESS) break;
    if ((st = autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_AUTO, &margin[k], &verdict[k])) !=
        AUTOBAL_SUCCESS)
      break;
  }
  stab_restore(s, &sv);
  return st;
}

typedef struct crit_ctx {
  autobal_rotor_stab *s;
  int param;
  size_t evals;
  int status;
} crit_ctx;

static int crit_margin(double x, void *ctx, double *fx) {
  crit_ctx *c = (crit_ctx *)ctx;
  int v, st;
  c->evals++;
  if (autobal_rotor_stab_cancelled_(c->s)) return AUTOBAL_ECANCELLED;
  if ((st = autobal_rotor_stab_set(c->s, c->param, x)) != AUTOBAL_SUCCESS) return st;
  st = autobal_rotor_stab_margin(c->s, AUTOBAL_ROTOR_STAB_AUTO, fx, &v);
  if (st == AUTOBAL_SUCCESS && v == AUTOBAL_ROTOR_VERDICT_NONE) return AUTOBAL_EINVAL;
  return st;
}

static int crit_exists(double x, void *ctx, int *value) {
  crit_ctx *c = (crit_ctx *)ctx;
  double mg;
  int v, st;
  c->evals++;
  if (autobal_rotor_stab_cancelled_(c->s)) return AUTOBAL_ECANCELLED;
  if ((st = autobal_rotor_stab_set(c->s, c->param, x)) != AUTOBAL_SUCCESS) return st;
  st = autobal_rotor_stab_margin(c->s, AUTOBAL_ROTOR_STAB_AUTO, &mg, &v);
  *value = v != AUTOBAL_ROTOR_VERDICT_NONE;
  return st;
}

/* sign class of a margin: +1 stable side (< 0), -1 unstable side (>= 0), 0 none */
static int side_of(double margin) { return isnan(margin) ? 0 : (margin < 0.0 ? 1 : -1); }

/* The scan of autobal_rotor_stab_critical with at most `cap` critical values (arguments
 * checked by the caller, *out zeroed, the parameters saved and restored by the caller). */
static int critical_scan(autobal_rotor_stab *s, int param, double lo, double hi, size_t n_grid,
                         double xtol_rel, size_t cap, autobal_rotor_crit *out) {
  crit_ctx cc;
  double prev_x = lo, start = NAN;
  size_t k;
  int st = AUTOBAL_SUCCESS, prev_side = 0, in_stable = 0;
  cc.s = s;
  cc.param = param;
  cc.evals = 0;
  cc.status = 0;
  for (k = 0; k < n_grid; k++) {
    const double x = k + 1 == n_grid ? hi : lo + (hi - lo) * (double)k / (double)(n_grid - 1);
    double mg;
    int v, side;
    cc.evals++;
    if (autobal_rotor_stab_cancelled_(s)) {
      st = AUTOBAL_ECANCELLED;
      break;
    }
    if ((st = autobal_rotor_stab_set(s, param, x)) != AUTOBAL_SUCCESS) break;
    if ((st = autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_AUTO, &mg, &v)) != AUTOBAL_SUCCESS)
      break;
    side = side_of(mg);
    if (k == 0) {
      if (side == 1) {
        in_stable = 1;
        start = lo;
      }
    } else if (side != prev_side) {
      double xc = NAN;
      int kind;
      if (out->n >= cap) {
        /* one change more than the list holds: stop here, before refining it.  The
         * results cover [lo, value[n-1]]: an open stable interval (it began at the last
         * recorded change) is not reported, nothing beyond it is claimed. */
        out->truncated = 1;
        break;
      }
      if (side != 0 && prev_side != 0) {
        /* margin changes sign: Brent on the margin */
        st = autobal_root_brent(crit_margin, &cc, prev_x, x, 0.0, xtol_rel, 200, &xc, &s->err);
        if (st == AUTOBAL_EINVAL && !isfinite(xc)) xc = 0.5 * (prev_x + x);
        if (st == AUTOBAL_ENUMERIC || st == AUTOBAL_EINVAL) st = AUTOBAL_SUCCESS; /* best estimate */
        kind = side == 1 ? 1 : -1;
      } else {
        double blo = prev_x, bhi = x;
        st = autobal_bisect_change(crit_exists, &cc, prev_x, x, 0.0, xtol_rel, &blo, &bhi, &s->err);
        xc = 0.5 * (blo + bhi);
        kind = 0;
      }
      if (st != AUTOBAL_SUCCESS) break;
      out->value[out->n] = xc;
      out->kind[out->n] = kind;
      out->n++;
      if (in_stable && side != 1) {
        /* at most n/2 + 1 <= AUTOBAL_ROTOR_MAX_CRIT closed intervals: never full */
        if (out->n_stable < AUTOBAL_ROTOR_MAX_CRIT) {
          out->stable_lo[out->n_stable] = start;
          out->stable_hi[out->n_stable] = xc;
          out->n_stable++;
        }
        in_stable = 0;
      } else if (!in_stable && side == 1) {
        in_stable = 1;
        start = xc;
      }
    }
    prev_side = side;
    prev_x = x;
  }
  if (st == AUTOBAL_SUCCESS && in_stable && !out->truncated &&
      out->n_stable < AUTOBAL_ROTOR_MAX_CRIT) {
    out->stable_lo[out->n_stable] = start;
    out->stable_hi[out->n_stable] = hi;
    out->n_stable++;
  }
  out->evaluations = cc.evals;
  if (st == AUTOBAL_SUCCESS && out->truncated)
    st = autobal_error_set(&s->err, AUTOBAL_WARNING,
                           "critical: more than %zu verdict changes of %s in [%.9g, %.9g] (the "
                           "capacity of the list): the first %zu are kept and the search stopped "
                           "at the next one; the results cover [%.9g, %.12g] only (up to the last "
                           "kept change). Narrow the range (e.g. an upper end <= %.12g) or split it",
                           cap, autobal_rotor_stab_param_name(param), lo, hi, out->n, lo,
                           out->value[out->n - 1], out->value[out->n - 1]);
  return st;
}

static int critical_checked(autobal_rotor_stab *s, int param, double lo, double hi, size_t n_grid,
                            double xtol_rel, size_t cap, autobal_rotor_crit *out) {
  stab_saved sv;
  int st;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: NULL output");
  memset(out, 0, sizeof *out);
  out->param = param;
  if (autobal_rotor_stab_param_name(param) == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: parameter id %d is not valid", param);
  if (!(isfinite(lo) && isfinite(hi) && lo < hi))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "critical: need finite lo < hi, got [%g, %g]", lo, hi);
  if (param == AUTOBAL_ROTOR_PARAM_OMEGA && !(lo > 0.0 || hi < 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "critical: the omega range [%g, %g] must not contain 0", lo, hi);
  if (n_grid < 2 || n_grid > 100000000)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: n_grid = %zu out of range [2, 1e8]",
                             n_grid);
  if (!(xtol_rel > 0.0 && xtol_rel < 0.1))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: xtol_rel = %g out of range (0, 0.1)",
                             xtol_rel);
  if (cap < 1 || cap > AUTOBAL_ROTOR_MAX_CRIT)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "critical: capacity %zu out of range [1, %d]",
                             cap, AUTOBAL_ROTOR_MAX_CRIT);
  stab_save(s, &sv);
  st = critical_scan(s, param, lo, hi, n_grid, xtol_rel, cap, out);
  stab_restore(s, &sv);
  return st;
}

int autobal_rotor_stab_critical(autobal_rotor_stab *s, int param, double lo, double hi,
                                size_t n_grid, double xtol_rel, autobal_rotor_crit *out) {
  return critical_checked(s, param, lo, hi, n_grid, xtol_rel, AUTOBAL_ROTOR_MAX_CRIT, out);
}

int autobal_rotor_stab_critical_cap_(autobal_rotor_stab *s, int param, double lo, double hi,
                                     size_t n_grid, double xtol_rel, size_t cap,
                                     autobal_rotor_crit *out) {
  return critical_checked(s, param, lo, hi, n_grid, xtol_rel, cap, out);
}

/* ---- maps ---------------------------------------------------------------------------- */

/* The default point of a map: the margin and verdict at the handle's unbalance. */
static int margin_point(autobal_rotor_stab *s, void *user, double *mg, int *v) {
  (void)user;
  return autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_AUTO, mg, v);
}

/* Parameters defined relative to others at the moment they are set: ANISOTROPY (the y
 * stiffnesses from the x ones), C_OVER_A (C from A), a plane's unbalance (m0 from r0). */
static int relative_param(int p) {
  return p == AUTOBAL_ROTOR_PARAM_ANISOTROPY || p == AUTOBAL_ROTOR_PARAM_C_OVER_A ||
         p == AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_UNBALANCE) ||
         p == AUTOBAL_ROTOR_PARAM_PLANE(1, AUTOBAL_ROTOR_PLANE_UNBALANCE);
}

/* One point: a relative parameter is set after the other one, so that its value holds at the
 * point whatever the other changes (e.g. anisotropy with supports.c_Lx). */
static int map_point(autobal_rotor_stab *s, autobal_rotor_map_point_fn_ fn, void *user, int p1, double x1, int p2,
                     double x2, double *mg, int *v) {
  int st;
  const int swap = relative_param(p1) && !relative_param(p2);
  *mg = NAN;
  *v = AUTOBAL_ROTOR_VERDICT_NONE;
  if ((st = autobal_rotor_stab_set(s, swap ? p2 : p1, swap ? x2 : x1)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_set(s, swap ? p1 : p2, swap ? x1 : x2)) != AUTOBAL_SUCCESS) return st;
  return fn(s, user, mg, v);
}

int autobal_rotor_stab_map_run_(const autobal_rotor_params *p, const autobal_rotor_stab_options *opt,
                                autobal_rotor_map_point_fn_ fn, void *user, int param1, const double *v1, size_t n1,
                                int param2, const double *v2, size_t n2, int n_threads, double *margin, int *verdict,
                                autobal_error *err) {
  size_t ntot;
  int fail = AUTOBAL_SUCCESS;
  char failmsg[AUTOBAL_ERRMSG_SIZE];
  autobal_rotor_stab *probe;
  failmsg[0] = '\0';
  if (autobal_rotor_stab_param_name(param1) == NULL || autobal_rotor_stab_param_name(param2) == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: parameter ids %d, %d: not valid", param1,
                             param2);
  if (param1 == param2)
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: the two parameters must differ (both %s)",
                             autobal_rotor_stab_param_name(param1));
  if ((n1 > 0 && v1 == NULL) || (n2 > 0 && v2 == NULL) || margin == NULL || verdict == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "map: NULL array");
  if (n_threads < 0) n_threads = 0;
  /* validate once (and report parameter/option errors before going parallel) */
  probe = autobal_rotor_stab_alloc(p, opt, err);
  if (probe == NULL) return err ? err->status : AUTOBAL_EINVAL;
  autobal_rotor_stab_free(probe);
  ntot = n1 * n2;
  if (ntot == 0) return AUTOBAL_SUCCESS;
#ifdef AUTOBAL_HAVE_OPENMP
  {
    int nth = n_threads > 0 ? n_threads : omp_get_max_threads();
#pragma omp parallel num_threads(nth)
    {
      autobal_rotor_stab *s = autobal_rotor_stab_alloc(p, opt, NULL);
      int local = s ? AUTOBAL_SUCCESS : AUTOBAL_ENOMEM;
      char msg[AUTOBAL_ERRMSG_SIZE];
      long long idx;
      msg[0] = '\0';
#pragma omp for schedule(dynamic, 8)
      for (idx = 0; idx < (long long)ntot; idx++) {
        const size_t i = (size_t)idx / n2, j = (size_t)idx % n2;
        if (local != AUTOBAL_SUCCESS) continue;
        local = map_point(s, fn, user, param1, v1[i], param2, v2[j], &margin[idx], &verdict[idx]);
        if (local != AUTOBAL_SUCCESS)
          snprintf(msg, sizeof msg, "map point (%s = %.9g, %s = %.9g): %.400s",
                   autobal_rotor_stab_param_name(param1), v1[i],
                   autobal_rotor_stab_param_name(param2), v2[j], s->err.message);
      }
      if (local != AUTOBAL_SUCCESS) {
#pragma omp critical(autobal_rotor_stab_map_fail)
        {
          if (fail == AUTOBAL_SUCCESS) {
            fail = local;
            snprintf(failmsg, sizeof failmsg, "%s", msg[0] ? msg : "out of memory");
          }
        }
      }
      autobal_rotor_stab_free(s);
    }
  }
#else
  {
    autobal_rotor_stab *s = autobal_rotor_stab_alloc(p, opt, NULL);
    size_t idx;
    (void)n_threads;
    if (s == NULL) fail = AUTOBAL_ENOMEM;
    for (idx = 0; idx < ntot && fail == AUTOBAL_SUCCESS; idx++) {
      const size_t i = idx / n2, j = idx % n2;
      fail = map_point(s, fn, user, param1, v1[i], param2, v2[j], &margin[idx], &verdict[idx]);
      if (fail != AUTOBAL_SUCCESS)
        snprintf(failmsg, sizeof failmsg, "map point (%s = %.9g, %s = %.9g): %.400s",
                 autobal_rotor_stab_param_name(param1), v1[i],
                 autobal_rotor_stab_param_name(param2), v2[j], s->err.message);
    }
    autobal_rotor_stab_free(s);
  }
#endif
  if (fail != AUTOBAL_SUCCESS) return autobal_error_set(err, fail, "%s", failmsg);
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_stab_map(const autobal_rotor_params *p, const autobal_rotor_stab_options *opt,
                           int param1, const double *v1, size_t n1, int param2, const double *v2,
                           size_t n2, int n_threads, double *margin, int *verdict,
                           autobal_error *err) {
  return autobal_rotor_stab_map_run_(p, opt, margin_point, NULL, param1, v1, n1, param2, v2, n2, n_threads, margin,
                                     verdict, err);
}
