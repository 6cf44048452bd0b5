/* rotor_margin_set.c: the unbalances for which the balanced motion of one plane with two IDENTICAL
 * balls is stable with a margin delta (every root Re lambda < -delta), as a set of the normalized
 * unbalance t = m0 r0 / (m r) in (0, 2), decided by its critical values, not by sampling
 * (docs/rotor.md "Design").  The building block of the design search (src/studies/rotor_design.c).
 *
 * With identical balls (mass m, radius r, damping h) the balanced angles depend on the unbalance
 * s = m0 r0 only through t = s / (m r): c = cos(psi_1 - psi_2) = t^2 / 2 - 1, and
 * u = |Q|^2 / 4 = m^2 c^2.  Delta(lambda; u) = A(lambda) - u G(lambda), G = (lambda^2 + w^2)^4 Bt
 * (rotor_closed.h), A and G independent of the unbalance and of r.  The roots of Delta lie left of
 * Re lambda = -delta iff the roots of Delta~(mu) = Delta(mu - delta) = A~(mu) - u G~(mu) lie in the
 * left half-plane, with A~, G~ the Taylor-shifted polynomials.  A root of Delta~ is on the imaginary
 * axis, mu = i y, only where A~(iy) = u G~(iy) with u real: y = 0 (u = A~_0 / G~_0), or
 * Im(A~(iy) conj G~(iy)) = y h(y^2) = 0, h = Ae Go - Ao Ge (even/odd parts in z = y^2, degree <= 11),
 * u = (Ae Ge + z Ao Go) / (Ge^2 + z Go^2).  A root can also leave through infinity where the
 * leading coefficient A~_12 - u G~_12 vanishes: u = A~_12 / G~_12 is a critical value too.  Each
 * critical u in [0, m^2] gives |c| = sqrt(u) / m and the two t = sqrt(2 (1 +- |c|)).  Between two
 * consecutive critical t the number of roots right of -delta is constant: one verdict per
 * sub-interval (Routh-Hurwitz on the coefficients of Delta~, at its midpoint and just inside both
 * ends; a disagreement makes the sub-interval count as not stable and is counted in n_missed)
 * decides it.
 *
 * Three or more identical balls (n >= 3, the handle's unbalance_member = SYMMETRIC: the symmetric fan
 * psi_i = psi0 + pi + (i - (n-1)/2) delta, the only member rule available for n >= 3): the same
 * closure holds with the same A~, G~ (common kappa = h/m), t = m0 r0 / (m r) ranges over (0, n),
 * t = U_{n-1}(x) and u = m^2 U_{n-1}(y)^2 / 4 with y = cos delta = 2 x^2 - 1 (rotor_unbalance.c,
 * docs/rotor.md "Every unbalance").  u(y) is monotone on [cos(2 pi/n), y1], [y1, cos(pi/n)],
 * [cos(pi/n), 1] (y1 the root of U'_{n-1} between), so a critical u gives at most three t, each by
 * bisection.  The (n - 2) neutral roots of the family and the (n - 2) roots -kappa of the full
 * system are not roots of Delta: the set speaks of Delta's roots only (the design adds kappa).
 *
 * May use: the handle (rotor_stab_handle.h), rotor_closed.h, rotor_fan.h, the numerics (autobal/stability.h),
 * (the margin of single configurations is not used here: the tests check the sets against it). */
#include "autobal/rotor_stability.h"
#include "autobal/stability.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/rotor_closed.h"
#include "analysis/rotor_fan.h"
#include "analysis/rotor_stab_handle.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* p(z) for ascending real coefficients (long double Horner). */
static long double lpoly(const long double *c, size_t len, long double z) {
  long double v = 0.0L;
  while (len-- > 0) v = v * z + c[len];
  return v;
}

/* q(mu) = p(mu + a) in place, ascending coefficients c[0..n] (Horner's Taylor shift). */
static void taylor_shift(long double *c, size_t n, long double a) {
  size_t k, j;
  for (k = 0; k < n; k++)
    for (j = n; j-- > k;) c[j] += a * c[j + 1];
}

/* Even and odd parts at mu = i y in z = y^2: p(i y) = E(z) + i y O(z) (p of degree 12). */
static void split_iy(const long double *p, long double E[7], long double O[6]) {
  size_t j;
  for (j = 0; j < 7; j++) E[j] = (j % 2 == 0 ? 1.0L : -1.0L) * p[2 * j];
  for (j = 0; j < 6; j++) O[j] = (j % 2 == 0 ? 1.0L : -1.0L) * p[2 * j + 1];
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The two t of a critical u (if 0 <= u <= m^2, generously) into out; returns the count. */
static size_t t_of_u(double u, double m, double *out) {
  double ac;
  if (!(u >= -1e-12 * m * m && u <= m * m * (1.0 + 1e-12))) return 0;
  ac = fmin(1.0, sqrt(fmax(0.0, u)) / m);
  out[0] = sqrt(2.0 * (1.0 - ac));
  out[1] = sqrt(2.0 * (1.0 + ac));
  return 2;
}

/* ---- n >= 3 identical balls, the symmetric fan (analysis/rotor_fan.h) ---- */

typedef autobal_rotor_fan_ fan_n;

/* u of the normalized unbalance t in (0, n). */
static double fan_u_of_t(const fan_n *f, double t) { return autobal_rotor_fan_u_(f, autobal_rotor_fan_y_of_t_(f, t)); }
/* The t of a critical u: one per monotone piece of u(y) that brackets it; returns the count (<= 3). */
static size_t fan_t_of_u(const fan_n *f, double uc, double *out) {
  double y[3];
  const size_t n = autobal_rotor_fan_y_of_u_(f, uc, f->y_min, 1.0, y);
  size_t k;
  for (k = 0; k < n; k++) out[k] = autobal_rotor_fan_t_(f, y[k]);
  return n;
}

/* Every root of Delta(. ; u(t)) left of -delta?  Routh-Hurwitz (with its error bounds, rtol 1e-12 on
 * the coefficients) on Delta~ = A~ - u G~: *ok 1 stable, 0 unstable, -1 within the tolerance of the
 * line Re lambda = -delta (MARGINAL: next to a critical t, or the neutral root at t = 0, 2). */
static int ok_at(const long double *At, const long double *Gt, double m, const fan_n *fan, double t, int *ok,
                 autobal_error *err) {
  const long double cc = (long double)(t * t / 2.0 - 1.0);
  const long double u = fan ? (long double)fan_u_of_t(fan, t) : (long double)m * (long double)m * cc * cc;
  double d[13];
  size_t k;
  int v, st;
  for (k = 0; k < 13; k++) d[k] = (double)(At[k] - u * Gt[k]);
  if (d[12] == 0.0) {
    *ok = -1;
    return AUTOBAL_SUCCESS;
  }
  if ((st = autobal_poly_hurwitz(d, 13, 1e-12, &v, NULL, err)) != AUTOBAL_SUCCESS) return st;
  *ok = v == AUTOBAL_VERDICT_STABLE ? 1 : (v == AUTOBAL_VERDICT_UNSTABLE ? 0 : -1);
  return AUTOBAL_SUCCESS;
}

/* The shifted parts A~, G~ at the handle's omega (m0 set to m r / r0: t = 1, balanceable for any n >= 2)
 * and the candidate critical u (y = 0, infinity, the positive roots of h) into cand (<= 13, unfiltered). */
static int shifted_parts(autobal_rotor_stab *s, double delta, long double At[13], long double Gt[13], double *cand,
                         size_t *nu_out) {
  const autobal_rotor_params *p = &s->cur;
  const autobal_rotor_plane *pl = &p->plane[0];
  const double mr = s->m[0] * s->r[0], r0 = pl->r0;
  double A[13], Bt[13];
  long double Ae[7], Ao[6], Ge[7], Go[6], h[12], w2;
  size_t nu = 0, i, j;
  int st;
  autobal_rotor_closed c;
  /* A and Bt (independent of m0: t = 1 is balanceable) */
  if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, mr / r0)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_closed(s, &c)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_char_parts_(&c, A, Bt, &s->err)) != AUTOBAL_SUCCESS) return st;
  w2 = (long double)p->omega * (long double)p->omega;
  {
    /* G = (lambda^2 + w^2)^4 Bt: multiply Bt (degree <= 4) four times by (lambda^2 + w^2) */
    long double g[13];
    size_t k;
    for (i = 0; i < 13; i++) {
      g[i] = (long double)Bt[i];
      At[i] = (long double)A[i];
    }
    for (k = 0; k < 4; k++) {
      for (i = 12; i >= 2; i--) g[i] = g[i - 2] + w2 * g[i];
      g[1] *= w2;
      g[0] *= w2;
    }
    for (i = 0; i < 13; i++) Gt[i] = g[i];
  }
  taylor_shift(At, 12, -(long double)delta);
  taylor_shift(Gt, 12, -(long double)delta);
  split_iy(At, Ae, Ao);
  split_iy(Gt, Ge, Go);
  /* y = 0 and infinity */
  if (Gt[0] != 0.0L) cand[nu++] = (double)(At[0] / Gt[0]);
  if (Gt[12] != 0.0L) cand[nu++] = (double)(At[12] / Gt[12]);
  /* h(z) = Ae Go - Ao Ge, degree <= 11 */
  for (i = 0; i < 12; i++) h[i] = 0.0L;
  for (i = 0; i < 7; i++)
    for (j = 0; j < 6; j++) h[i + j] += Ae[i] * Go[j];
  for (i = 0; i < 6; i++)
    for (j = 0; j < 7; j++) h[i + j] -= Ao[i] * Ge[j];
  {
    long double zr[11];
    size_t nz, q;
    if ((st = autobal_poly_positive_roots_ld_(h, 12, w2, zr, &nz, &s->err)) != AUTOBAL_SUCCESS) return st;
    for (q = 0; q < nz; q++) {
      const long double zz = zr[q], ge = lpoly(Ge, 7, zz), go = lpoly(Go, 6, zz), den = ge * ge + zz * go * go;
      if (den > 0.0L) cand[nu++] = (double)((lpoly(Ae, 7, zz) * ge + zz * lpoly(Ao, 6, zz) * go) / den);
    }
  }
  *nu_out = nu;
  return AUTOBAL_SUCCESS;
}

/* The machine checks shared by the t set and the u range (what = the caller's name); member_rule: refuse
 * n >= 3 without the SYMMETRIC rule (the t set). */
static int check_machine(autobal_rotor_stab *s, double delta, int member_rule, const char *what) {
  const autobal_rotor_params *p = &s->cur;
  const autobal_rotor_plane *pl = &p->plane[0];
  size_t i, nb;
  if (p->n_planes != 1 || pl->n_balls < 2)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "%s: built for one plane with two or more balls (here %zu plane(s), %zu ball(s) "
                             "in plane 1)",
                             what, p->n_planes, pl->n_balls);
  if (p->inertia != AUTOBAL_ROTOR_INERTIA_PAPER)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED, "%s: needs the paper's inertia model (inertia = paper)",
                             what);
  if (!autobal_rotor_lumped_isotropic_(&s->L))
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED, "%s: needs isotropic supports", what);
  nb = pl->n_balls;
  for (i = 1; i < nb; i++)
    if (!(s->m[i] == s->m[0] && s->r[i] == s->r[0] && s->h[i] == s->h[0]))
      return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                               "%s: needs identical balls (the same ball_mass, ball_radius and "
                               "ball_damping)",
                               what);
  if (member_rule && nb >= 3 && s->opt.unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "%s: with %zu balls the member of the family matters; only unbalance_member = "
                             "symmetric (the symmetric fan) is available for three or more balls",
                             what, nb);
  if (!(pl->r0 > 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "%s: r0 = %g m must be > 0 (the unbalance is varied through m0)", what, pl->r0);
  if (!(p->omega != 0.0 && isfinite(p->omega)))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "%s: omega must be finite and non-zero", what);
  if (!isfinite(delta))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "%s: the margin delta = %g 1/s must be finite", what,
                             delta);
  return AUTOBAL_SUCCESS;
}

static int ratio_set(autobal_rotor_stab *s, double delta, autobal_rotor_ratio_set *out) {
  const autobal_rotor_params *p = &s->cur;
  const autobal_rotor_plane *pl = &p->plane[0];
  double m, cand[2 * 14], tcand[4 * 14 + 4 * 14];
  long double At[13], Gt[13];
  size_t nu = 0, nt = 0, i, nb;
  int st;
  double tmax;
  fan_n fan, *fanp = NULL;
  if ((st = check_machine(s, delta, 1, "margin set")) != AUTOBAL_SUCCESS) return st;
  nb = pl->n_balls;
  m = s->m[0];
  tmax = (double)nb;
  if (nb >= 3) {
    autobal_rotor_fan_init_(&fan, nb, m);
    fanp = &fan;
  }
  out->omega = p->omega;
  out->delta = delta;
  if ((st = shifted_parts(s, delta, At, Gt, cand, &nu)) != AUTOBAL_SUCCESS) return st;
  for (i = 0; i < nu; i++) nt += fanp ? fan_t_of_u(fanp, cand[i], tcand + nt) : t_of_u(cand[i], m, tcand + nt);
  qsort(tcand, nt, sizeof tcand[0], cmp_double);
  out->n_crit = 0;
  for (i = 0; i < nt; i++) {
    if (!(tcand[i] > 0.0 && tcand[i] < tmax)) continue;
    if (out->n_crit > 0 && tcand[i] - out->t_crit[out->n_crit - 1] <= 1e-12) continue;
    if (out->n_crit >= AUTOBAL_ROTOR_MAX_UCRIT)
      return autobal_error_set(&s->err, AUTOBAL_ENUMERIC,
                               "margin set: more than %d critical unbalances at %g rad/s", AUTOBAL_ROTOR_MAX_UCRIT,
                               p->omega);
    out->t_crit[out->n_crit++] = tcand[i];
  }
  /* one verdict per sub-interval of (0, n) */
  {
    double edges[AUTOBAL_ROTOR_MAX_UCRIT + 2];
    size_t ne = 0, k;
    edges[ne++] = 0.0;
    for (k = 0; k < out->n_crit; k++) edges[ne++] = out->t_crit[k];
    edges[ne++] = tmax;
    out->n = 0;
    for (k = 0; k + 1 < ne; k++) {
      const double lo = edges[k], hi = edges[k + 1], wdt = hi - lo;
      const double pts[3] = {lo + 1e-7 * wdt, lo + 0.5 * wdt, hi - 1e-7 * wdt};
      int ok[3], q;
      if (autobal_rotor_stab_cancelled_(s))
        return autobal_error_set(&s->err, AUTOBAL_ECANCELLED, "margin set: cancelled by the caller");
      for (q = 0; q < 3; q++) {
        if ((st = ok_at(At, Gt, m, fanp, pts[q], &ok[q], &s->err)) != AUTOBAL_SUCCESS) return st;
        out->evaluations++;
      }
      /* the ends just inside a critical t may be within the test's tolerance (-1): they do not vote */
      /* (not counted in sub-intervals narrower than 1e-6, e.g. (0, sqrt(eps)) next to the neutral
       * root at t = 0, where the coefficients cannot decide; such a one is accepted only if all agree) */
      if (wdt >= 1e-6 &&
          ((ok[0] >= 0 && ok[1] >= 0 && ok[0] != ok[1]) || (ok[2] >= 0 && ok[1] >= 0 && ok[2] != ok[1])))
        out->n_missed++;
      if (ok[1] == 1 && ok[0] != 0 && ok[2] != 0) {
        int merge = 0;
        if (out->n > 0 && out->hi[out->n - 1] == lo) {
          /* two stable neighbours: at a true critical t a root touches -delta (no STABLE verdict
           * there); a spurious candidate (a near-real root of h) is no crossing: merge them */
          int okc;
          if ((st = ok_at(At, Gt, m, fanp, lo, &okc, &s->err)) != AUTOBAL_SUCCESS) return st;
          out->evaluations++;
          merge = okc == 1;
        }
        if (merge) out->hi[out->n - 1] = hi;
        else {
          out->lo[out->n] = lo;
          out->hi[out->n] = hi;
          out->n++;
        }
      }
    }
  }
  return AUTOBAL_SUCCESS;
}

/* Every root of Delta~(. ; u) = A~ - u G~ left of the imaginary axis?  (ok_at's test, in u.) */
static int ok_u(const long double *At, const long double *Gt, double u, int *ok, autobal_error *err) {
  double d[13];
  size_t k;
  int v, st;
  for (k = 0; k < 13; k++) d[k] = (double)(At[k] - (long double)u * Gt[k]);
  if (d[12] == 0.0) {
    *ok = -1;
    return AUTOBAL_SUCCESS;
  }
  if ((st = autobal_poly_hurwitz(d, 13, 1e-12, &v, NULL, err)) != AUTOBAL_SUCCESS) return st;
  *ok = v == AUTOBAL_VERDICT_STABLE ? 1 : (v == AUTOBAL_VERDICT_UNSTABLE ? 0 : -1);
  return AUTOBAL_SUCCESS;
}

/* Every u in [u_lo, u_hi] with margin delta: the critical u inside cut it; the test at both ends, at every
 * critical u inside (a root on the line there: not stable), and at the midpoint and just inside both ends
 * of every sub-interval.  The first u that fails goes to u_found. */
static int u_range(autobal_rotor_stab *s, double delta, double u_lo, double u_hi, autobal_rotor_margin_u_range *out) {
  double cand[2 * 14], edges[AUTOBAL_ROTOR_MAX_UCRIT + 2];
  long double At[13], Gt[13];
  size_t nu = 0, i, ne = 0, k;
  int st, ok;
  if ((st = check_machine(s, delta, 0, "margin u range")) != AUTOBAL_SUCCESS) return st;
  if (!(isfinite(u_lo) && isfinite(u_hi) && u_lo >= 0.0 && u_lo <= u_hi))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "margin u range: [%g, %g] kg^2 needs 0 <= u_lo <= u_hi, finite", u_lo, u_hi);
  out->omega = s->cur.omega;
  out->delta = delta;
  out->u_lo = u_lo;
  out->u_hi = u_hi;
  out->u_found = NAN;
  out->all_stable = 1;
  if ((st = shifted_parts(s, delta, At, Gt, cand, &nu)) != AUTOBAL_SUCCESS) return st;
  qsort(cand, nu, sizeof cand[0], cmp_double);
  for (i = 0; i < nu; i++) {
    if (!(cand[i] > u_lo && cand[i] < u_hi)) continue;
    if (out->n_crit > 0 && cand[i] - out->u_crit[out->n_crit - 1] <= 1e-15 * u_hi) continue;
    if (out->n_crit >= AUTOBAL_ROTOR_MAX_UCRIT) break;
    out->u_crit[out->n_crit++] = cand[i];
  }
  edges[ne++] = u_lo;
  for (k = 0; k < out->n_crit; k++) edges[ne++] = out->u_crit[k];
  edges[ne++] = u_hi;
  for (k = 0; k < ne; k++) {
    /* the point itself (an end or a critical u), then the sub-interval after it */
    double pts[4];
    size_t np = 0, q;
    pts[np++] = edges[k];
    if (k + 1 < ne && edges[k + 1] > edges[k]) {
      const double lo = edges[k], hi = edges[k + 1], wdt = hi - lo;
      pts[np++] = lo + 1e-7 * wdt;
      pts[np++] = lo + 0.5 * wdt;
      pts[np++] = hi - 1e-7 * wdt;
    }
    if (autobal_rotor_stab_cancelled_(s))
      return autobal_error_set(&s->err, AUTOBAL_ECANCELLED, "margin u range: cancelled by the caller");
    for (q = 0; q < np; q++) {
      if ((st = ok_u(At, Gt, pts[q], &ok, &s->err)) != AUTOBAL_SUCCESS) return st;
      out->evaluations++;
      if (ok != 1 && out->all_stable) {
        out->all_stable = 0;
        out->u_found = pts[q];
      }
    }
  }
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_stab_margin_u_range(autobal_rotor_stab *s, double delta, double u_lo, double u_hi,
                                      autobal_rotor_margin_u_range *out) {
  double m0;
  int st, st2;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "margin u range: out is NULL");
  memset(out, 0, sizeof *out);
  if (s->cur.n_planes < 1) return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED, "margin u range: no plane");
  m0 = s->cur.plane[0].m0;
  st = u_range(s, delta, u_lo, u_hi, out);
  st2 = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  return st != AUTOBAL_SUCCESS ? st : st2;
}

int autobal_rotor_stab_margin_ratio_set(autobal_rotor_stab *s, double delta, autobal_rotor_ratio_set *out) {
  double m0;
  int st, st2;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "margin set: out is NULL");
  memset(out, 0, sizeof *out);
  if (s->cur.n_planes < 1) return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED, "margin set: no plane");
  m0 = s->cur.plane[0].m0;
  st = ratio_set(s, delta, out);
  st2 = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  return st != AUTOBAL_SUCCESS ? st : st2;
}
