/* rotor_unbalance.c: stability of the balanced motion for EVERY unbalance in a range (one plane,
 * two balls, isotropic supports, the paper's inertia model), by the critical unbalances, not by
 * sampling (docs/rotor.md "Every unbalance").
 *
 * With these assumptions the closed characteristic polynomial is
 *     Delta(lambda; u) = A(lambda) - u (lambda^2 + w^2)^4 B(lambda),   u = |Q|^2 / 4  (kg^2),
 * A = F F*, B = N N* (P^4 Pb^4 = (lambda^2 + w^2)^4) independent of the unbalance; the unbalance
 * s = m0 r0 enters through u only: for two balls (a_i = m_i r_i) at the balanced angles,
 * cos(psi_1 - psi_2) = c = (s^2 - a_1^2 - a_2^2) / (2 a_1 a_2) and |Q|^2 = m_1^2 + m_2^2 +
 * 2 m_1 m_2 (2 c^2 - 1).  A root of Delta crosses the imaginary axis at lambda = i y only where
 * A(i y) = u (w^2 - y^2)^4 B(i y) with u real: y = 0 (u = A_0 / (w^8 B_0)), or A(i y) / B(i y) real,
 * i.e. y h(y^2) = Im(A(i y) conj B(i y)) = 0 with h a real polynomial of degree <= 7 in z = y^2,
 * u = Re(A(i y) / B(i y)) / (w^2 - z)^4 (z = w^2 is no crossing: there Delta = A, independent of u).
 * Between two consecutive such critical values the number of roots in the right half-plane is
 * constant, so one verdict per sub-interval decides it.  Candidates are generous (roots of h with a
 * small imaginary part count too: a spurious one only splits a sub-interval), and every
 * sub-interval is checked at both ends and the midpoint; a disagreement (a crossing the polynomial
 * roots missed) is bisected.
 *
 *
 * Three or more identical balls (mass m, track radius r, damping h; a = m r), member rule SYMMETRIC
 * (the fan psi_i = psi0 + pi + (i - (n-1)/2) delta): with theta = delta / 2, x = cos theta and
 * y = cos 2 theta = 2 x^2 - 1, the unbalance is t = s / a = sin(n theta) / sin(theta) = U_{n-1}(x),
 * and |Q| / m = |sin(2 n theta) / sin(2 theta)| = |U_{n-1}(y)| (Chebyshev polynomials of the second
 * kind; tools/derive/derive_nballs.py).  The admissible fan has 2 theta in [0, 2 pi / n], y in
 * [cos(2 pi / n), 1], where t increases with y.  The roots of U_{n-1} are cos(k pi / n) and those of
 * U'_{n-1} interlace them, so on this range u(y) = m^2 U_{n-1}(y)^2 / 4 has exactly two critical
 * points: y1, the one root of U'_{n-1} in (cos(2 pi / n), cos(pi / n)) (a local maximum), and
 * y0 = cos(pi / n) (u = 0); u is monotone between them.  The range of u over [s_lo, s_hi] and the
 * unbalances of a critical u follow exactly (bisection on the monotone pieces); the verdicts use the
 * symmetric member.
 *
 * Three identical balls, member rule EVERY (every member, docs/rotor.md "Every unbalance"): in units of
 * m r, t = s / (m r) and q = |sum e^{2 i psi_k}|^2 = 4 u / m^2.  With S = sum z_k = t (rotated real),
 * e3 = z1 z2 z3 = e^{i chi} and e2 = e3 conj(S) = t e^{i chi}, q = t^4 + 4 t^2 - 4 t^3 cos chi.  The
 * cubic z^3 - t z^2 + t e^{i chi} z - e^{i chi} is self-inversive; its roots can leave the unit circle
 * only through a double root on it (two balls together, |S| in [1, 3]), so the admissible chi at t are
 * all chi for t <= 1 and |chi| <= chi_b(t), cos chi_b = (t^4 + 18 t^2 - 27) / (8 t^3), for t in [1, 3]
 * (tools/derive/derive_every3.py): q_min(t) = t^2 (t - 2)^2 (chi = 0: one ball on S, two symmetric),
 * q_max(t) = t^2 (t + 2)^2 for t <= 1 (chi = pi), 1 + (t^2 - 5)^2 / 2 for t >= 1 (two balls together).
 * Over t in [ta, tb] q takes every value in [min q_min, max q_max] (the ends, t = 2 with q = 0, t = 1
 * with q = 9).  The verdict depends only on u, so the critical u (the roots of h) cut [u_min, u_max]
 * into sub-intervals with one verdict each, taken at a member that has that u: ball 1 at phi from S,
 * the other two placed (member FREE), phi by bisection between a q_min and a q_max member.  The
 * unbalances of a critical u are {t : q_min(t) <= q <= q_max(t)}, at most three intervals, in closed
 * form.
 *
 *
 * Four to ten identical balls, member rule EVERY (docs/rotor.md "Four or more balls, every member"):
 * the same reduction to u, with the range of q over the members of [ta, tb] enclosed by the
 * branch-and-bound of rotor_every_n.c (outer bounds, certified; members found give inner bounds, and
 * every q between them is met: the members form a connected set).  The critical u cut the outer
 * enclosure; each sub-interval that meets the inner range is decided at members built there (all n
 * angles given), their u recomputed; one that lies wholly in the gap between the bounds is left
 * undecided (verdict NONE; then not "stable for all").
 *
 * May use: the handle (rotor_stab_handle.h), rotor_closed.h, rotor_fan.h, rotor_every_n.h, the numerics (autobal/stability.h). */
#include "autobal/rotor_stability.h"
#include "autobal/stability.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/rotor_closed.h"
#include "analysis/rotor_every_n.h"
#include "analysis/rotor_fan.h"
#include "analysis/rotor_stab_handle.h"
#include "analysis/rotor_stability.h"
#include "analysis/rotor_unbalance_aniso.h"
#include "internal.h"

/* p(z) for ascending real coefficients (long double Horner). */
static long double lpoly(const long double *c, size_t len, long double z) {
  long double v = 0.0L;
  while (len-- > 0) v = v * z + c[len];
  return v;
}

/* The even and odd parts of a real polynomial at lambda = i y, in z = y^2:
 * p(i y) = E(z) + i y O(z).  E has 7, O 6 coefficients (len 13 in). */
static void split_iy(const double *p, long double E[7], long double O[6]) {
  size_t j;
  for (j = 0; j < 7; j++) E[j] = (j % 2 == 0 ? 1.0L : -1.0L) * (long double)p[2 * j];
  for (j = 0; j < 6; j++) O[j] = (j % 2 == 0 ? 1.0L : -1.0L) * (long double)p[2 * j + 1];
}

/* u* at the crossing y = sqrt(z): Re(A(iy) / B(iy)) / (w^2 - z)^4 = (Ae Be + z Ao Bo) / ((Be^2 +
 * z Bo^2) (w^2 - z)^4). */
static double u_at(const long double Ae[7], const long double Ao[6], const long double Be[7],
                   const long double Bo[6], long double w2, long double z) {
  const long double ae = lpoly(Ae, 7, z), ao = lpoly(Ao, 6, z), be = lpoly(Be, 7, z), bo = lpoly(Bo, 6, z);
  const long double q = (w2 - z) * (w2 - z), den = (be * be + z * bo * bo) * q * q;
  if (!(den > 0.0L)) return NAN;
  return (double)((ae * be + z * ao * bo) / den);
}

/* The unbalances s >= 0 of two balls a1, a2 (kg m), masses m1, m2, whose |Q|^2 / 4 equals u:
 * up to 2 values into out; returns the count. */
static size_t s_of_u(double u, double m1, double m2, double a1, double a2, double out[2]) {
  const double k = (4.0 * u - m1 * m1 - m2 * m2) / (2.0 * m1 * m2); /* cos 2 (psi_1 - psi_2) */
  size_t n = 0;
  int sgn;
  if (!(k >= -1.0 - 1e-12 && k <= 1.0 + 1e-12)) return 0;
  for (sgn = -1; sgn <= 1; sgn += 2) {
    const double c = sgn * sqrt(fmax(0.0, 0.5 * (k + 1.0)));
    const double s2 = a1 * a1 + a2 * a2 + 2.0 * a1 * a2 * c;
    if (s2 >= 0.0) {
      const double s = sqrt(s2);
      if (n == 1 && s == out[0]) continue;
      out[n++] = s;
    }
  }
  return n;
}

/* ---- n >= 3 identical balls, the symmetric fan (analysis/rotor_fan.h) ---- */

/* The symmetric fan of n identical balls (mass m, a = m r) over the range [s_lo, s_hi]. */
typedef struct sym_fan {
  autobal_rotor_fan_ f; /* n, m, y_min, y1, y0 */
  double a;
  double ya, yb; /* the y of s_lo, s_hi */
} sym_fan;

static void fan_init(sym_fan *f, size_t n, double m, double a, double s_lo, double s_hi) {
  autobal_rotor_fan_init_(&f->f, n, m);
  f->a = a;
  f->ya = autobal_rotor_fan_y_of_t_(&f->f, s_lo / a);
  f->yb = autobal_rotor_fan_y_of_t_(&f->f, s_hi / a);
}

/* The range of u over [ya, yb]: the ends and the critical points y1, y0 inside. */
static void fan_u_range(const sym_fan *f, double *umin, double *umax) {
  const double ys[4] = {f->ya, f->yb, f->f.y1, f->f.y0};
  size_t k;
  *umin = INFINITY, *umax = -INFINITY;
  for (k = 0; k < 4; k++) {
    double u;
    if (k >= 2 && !(ys[k] > f->ya && ys[k] < f->yb)) continue;
    u = k == 3 ? 0.0 : autobal_rotor_fan_u_(&f->f, ys[k]);
    if (u < *umin) *umin = u;
    if (u > *umax) *umax = u;
  }
}

/* The unbalances s in [s_lo, s_hi] of the fan whose u equals uc (at most 3, written to out). */
static size_t fan_s_of_u(const sym_fan *f, double uc, double out[3]) {
  double y[3];
  const size_t n = autobal_rotor_fan_y_of_u_(&f->f, uc, f->ya, f->yb, y);
  size_t k;
  for (k = 0; k < n; k++) out[k] = f->a * autobal_rotor_fan_t_(&f->f, y[k]);
  return n;
}

/* ---- three identical balls, every member (member rule EVERY) ---- */

/* q = |sum e^{2 i psi_k}|^2 (units of m r) at the least and the largest members of t = s / (m r). */
static double e3_qmin(double t) {
  const double w = t * (t - 2.0);
  return w * w;
}
static double e3_qmax(double t) {
  double w;
  if (t <= 1.0) {
    w = t * (t + 2.0);
    return w * w;
  }
  w = t * t - 5.0;
  return 1.0 + 0.5 * w * w;
}

/* Up to 4 closed intervals, ascending and disjoint. */
typedef struct ivl4 {
  size_t n;
  double lo[4], hi[4];
} ivl4;

static void ivl_add(ivl4 *v, double lo, double hi) {
  if (lo <= hi && v->n < 4) v->lo[v->n] = lo, v->hi[v->n] = hi, v->n++;
}

static void ivl_and(const ivl4 *a, const ivl4 *b, ivl4 *out) {
  size_t i, j;
  out->n = 0;
  for (i = 0; i < a->n; i++)
    for (j = 0; j < b->n; j++) ivl_add(out, fmax(a->lo[i], b->lo[j]), fmin(a->hi[i], b->hi[j]));
}

/* The t in [ta, tb] where some member has q: {q_min(t) <= q} and {q_max(t) >= q}, in closed form. */
static void e3_t_set(double q, double ta, double tb, ivl4 *out) {
  ivl4 a = {0}, b = {0}, ab, c = {0};
  const double rq = sqrt(fmax(q, 0.0));
  out->n = 0;
  if (!(q >= 0.0 && q <= 9.0)) return;
  /* q_min = (t (t - 2))^2 <= q: t (t - 2) <= rq, and t (t - 2) >= -rq unless rq >= 1 */
  if (rq < 1.0) {
    const double w = sqrt(1.0 - rq);
    ivl_add(&a, 0.0, rq / (1.0 + w));
    ivl_add(&a, 1.0 + w, 1.0 + sqrt(1.0 + rq));
  } else
    ivl_add(&a, 0.0, 1.0 + sqrt(1.0 + rq));
  /* q_max >= q: t (t + 2) >= rq on [0, 1]; (t^2 - 5)^2 >= 2 (q - 1) on [1, 3] */
  {
    const double t0 = rq / (1.0 + sqrt(1.0 + rq));
    if (q <= 1.0) ivl_add(&b, t0, 3.0);
    else {
      const double w = sqrt(2.0 * (q - 1.0));
      ivl_add(&b, t0, sqrt(5.0 - w));
      ivl_add(&b, sqrt(5.0 + w), 3.0);
    }
  }
  ivl_and(&a, &b, &ab);
  ivl_add(&c, ta, tb);
  ivl_and(&ab, &c, out);
}

/* q of the member of t with ball 1 at angle phi from S (the other two placed: z2 + z3 = t - z1). */
static double e3_q_phi(double t, double phi) {
  const double x1 = cos(phi), y1 = sin(phi), vx = t - x1, vy = -y1, av = hypot(vx, vy);
  if (!(av > 0.0)) return 9.0; /* t = 1, phi = 0: the limit along phi -> 0, balls 1, 1, -1 (one line) */
  const double h = sqrt(fmax(0.0, 1.0 - 0.25 * av * av));
  const double dx = av > 0.0 ? vx / av : 1.0, dy = av > 0.0 ? vy / av : 0.0;
  /* z2,3 = v / 2 +- i d h */
  const double x2 = 0.5 * vx - dy * h, y2 = 0.5 * vy + dx * h, x3 = 0.5 * vx + dy * h, y3 = 0.5 * vy - dx * h;
  const double re = x1 * x1 - y1 * y1 + x2 * x2 - y2 * y2 + x3 * x3 - y3 * y3;
  const double im = 2.0 * (x1 * y1 + x2 * y2 + x3 * y3);
  return re * re + im * im;
}

/* The angle phi of ball 1 (from S) of a member of t with q (clamped to the members' range), by
 * bisection on the sign of q(phi) - q between phi_lo = theta, cos theta = (t - 1) / 2 (ball 1 one of the
 * symmetric pair of chi = 0: q_min) and phi_hi: t <= 1: theta', cos theta' = (t + 1) / 2 (one of the
 * pair of chi = pi), t > 1: alpha, cos alpha = (t^2 + 3) / (4 t) (one of the two balls together,
 * 2 e^{i alpha} + e^{i beta} = t): q_max.  All in the arc of admissible phi; balls 2, 3 never
 * coincide and never sum to zero inside (t = 1: only at phi = 0, the member on one line, q = 9). */
static double e3_phi_of_q(double t, double q) {
  double lo = acos(fmax(-1.0, fmin(1.0, 0.5 * (t - 1.0)))),
         hi = t <= 1.0 ? acos(fmin(1.0, 0.5 * (t + 1.0))) : acos(fmin(1.0, (t * t + 3.0) / (4.0 * t)));
  const int up = e3_q_phi(t, hi) >= e3_q_phi(t, lo);
  int it;
  if (up ? e3_q_phi(t, lo) >= q : e3_q_phi(t, lo) <= q) return lo;
  if (up ? e3_q_phi(t, hi) <= q : e3_q_phi(t, hi) >= q) return hi;
  for (it = 0; it < 200; it++) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid != lo && mid != hi)) break;
    if ((e3_q_phi(t, mid) < q) == up) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

/* The balls' data of the every-unbalance analysis: two balls (m1, m2, a1, a2), a fan, or three balls
 * with every member (every3: ta, tb = s_lo / a, s_hi / a; angle: ball 1 of the FREE member), or four to
 * six (everyn: angle[0..n-1] of the GIVEN member; en the enclosure). */
typedef struct balls_info {
  size_t nb;
  double m1, m2, a1, a2, r0;
  sym_fan fan;
  int every3, everyn;
  int aniso; /* anisotropic supports (two balls): Hill's method, rotor_unbalance_aniso.c */
  double ta, tb;
  double *angle;
  const autobal_everyn_ *en;
} balls_info;

/* The unbalances of a critical u: two balls by the closed form, a fan by fan_s_of_u. */
static size_t map_u(const balls_info *bi, double u, double *out) {
  if (bi->nb == 2) return s_of_u(u, bi->m1, bi->m2, bi->a1, bi->a2, out);
  return fan_s_of_u(&bi->fan, u, out);
}

/* One verdict STABLE and the other UNSTABLE. */
static int opposite(int a, int b) {
  return (a == AUTOBAL_VERDICT_STABLE && b == AUTOBAL_VERDICT_UNSTABLE) ||
         (a == AUTOBAL_VERDICT_UNSTABLE && b == AUTOBAL_VERDICT_STABLE);
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Verdict and margin at unbalance s (kg m) at the handle's omega: m0 = s / r0. */
static int verdict_at(autobal_rotor_stab *s, double r0, double sv, double *margin, int *verdict) {
  int st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv / r0);
  if (st != AUTOBAL_SUCCESS) return st;
  return autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, margin, verdict);
}

/* The verdicts of the sub-intervals of [x_lo, x_hi] between the critical values crit[] (of the
 * unbalance s, or of u for every member of three balls): each at its midpoint and just inside both
 * ends; a stable/unstable disagreement inside one (a crossing the polynomial roots missed; a
 * MARGINAL verdict, within the verdict tolerance of a critical value, is no disagreement) is
 * bisected and added to crit[]; then the two ends of the range.  at() gives the verdict and margin
 * at a value of the variable. */
typedef int (*sub_at_fn)(autobal_rotor_stab *s, const void *ctx, double x, double *margin, int *verdict);
typedef struct {
  double *crit;                 /* ascending critical values; a bisected one is added */
  size_t *n_crit;
  double *sub_lo, *sub_hi, *sub_margin; /* per sub-interval (at most AUTOBAL_ROTOR_MAX_UCRIT + 1) */
  int *sub_verdict;             /* at the midpoint */
  size_t *n_sub;
  int *all_stable;              /* 1: no critical value inside and every verdict stable */
  double *margin_worst;         /* the largest margin met */
  size_t *evaluations, *n_missed;
  int worst;                    /* the worst midpoint verdict */
} sub_result;

static int decide_subintervals(autobal_rotor_stab *s, sub_at_fn at, const void *ctx, double x_lo, double x_hi,
                               sub_result *r) {
  double edges[AUTOBAL_ROTOR_MAX_UCRIT + 2];
  size_t ne = 0, k;
  int st;
  edges[ne++] = x_lo;
  for (k = 0; k < *r->n_crit; k++) edges[ne++] = r->crit[k];
  edges[ne++] = x_hi;
  *r->all_stable = 1;
  *r->margin_worst = -INFINITY;
  r->worst = AUTOBAL_VERDICT_STABLE;
  for (k = 0; k + 1 < ne; k++) {
    const double lo = edges[k], hi = edges[k + 1], wdt = hi - lo;
    const double pts[3] = {lo + 1e-9 * wdt, lo + 0.5 * wdt, hi - 1e-9 * wdt};
    int vv[3], q;
    double mg[3];
    if (autobal_rotor_stab_cancelled_(s))
      return autobal_error_set(&s->err, AUTOBAL_ECANCELLED, "every unbalance: cancelled by the caller");
    for (q = 0; q < 3; q++) {
      if ((st = at(s, ctx, wdt > 0.0 ? pts[q] : lo, &mg[q], &vv[q])) != AUTOBAL_SUCCESS) return st;
      (*r->evaluations)++;
      if (mg[q] > *r->margin_worst) *r->margin_worst = mg[q];
    }
    if (opposite(vv[0], vv[1]) || opposite(vv[1], vv[2])) {
      double x0 = opposite(vv[0], vv[1]) ? pts[0] : pts[1], x1 = opposite(vv[0], vv[1]) ? pts[1] : pts[2];
      int v0 = opposite(vv[0], vv[1]) ? vv[0] : vv[1], it;
      for (it = 0; it < 60 && x1 - x0 > 1e-12 * x1; it++) {
        const double xm = 0.5 * (x0 + x1);
        double mm;
        int vm;
        if ((st = at(s, ctx, xm, &mm, &vm)) != AUTOBAL_SUCCESS) return st;
        (*r->evaluations)++;
        if (vm == v0) x0 = xm;
        else x1 = xm;
      }
      (*r->n_missed)++;
      if (*r->n_crit < AUTOBAL_ROTOR_MAX_UCRIT) {
        r->crit[(*r->n_crit)++] = 0.5 * (x0 + x1);
        qsort(r->crit, *r->n_crit, sizeof r->crit[0], cmp_double);
      }
      *r->all_stable = 0;
    }
    if (*r->n_sub < AUTOBAL_ROTOR_MAX_UCRIT + 1) {
      r->sub_lo[*r->n_sub] = lo;
      r->sub_hi[*r->n_sub] = hi;
      r->sub_verdict[*r->n_sub] = vv[1];
      r->sub_margin[*r->n_sub] = mg[1];
      (*r->n_sub)++;
    }
    if (vv[1] < r->worst) r->worst = vv[1];
    if (vv[0] != AUTOBAL_VERDICT_STABLE || vv[1] != AUTOBAL_VERDICT_STABLE || vv[2] != AUTOBAL_VERDICT_STABLE)
      *r->all_stable = 0;
  }
  /* a critical value inside the range puts a root on the axis there: not stable for it */
  if (*r->n_crit > 0) *r->all_stable = 0;
  /* the ends themselves */
  for (k = 0; k < 2; k++) {
    double mg;
    int vv;
    if ((st = at(s, ctx, k == 0 ? x_lo : x_hi, &mg, &vv)) != AUTOBAL_SUCCESS) return st;
    (*r->evaluations)++;
    if (mg > *r->margin_worst) *r->margin_worst = mg;
    if (vv != AUTOBAL_VERDICT_STABLE) *r->all_stable = 0;
  }
  return AUTOBAL_SUCCESS;
}

static int at_s(autobal_rotor_stab *s, const void *ctx, double x, double *margin, int *verdict) {
  return verdict_at(s, *(const double *)ctx, x, margin, verdict);
}

/* The checks of n >= 3 balls: identical balls, the member rule, the range. */
static int check_fan(autobal_rotor_stab *s, double s_lo, double s_hi, balls_info *bi) {
  const autobal_rotor_plane *pl = &s->cur.plane[0];
  const size_t n = pl->n_balls;
  size_t i;
  for (i = 1; i < n; i++)
    if (!autobal_rotor_close_rel_(pl->ball_mass[i], pl->ball_mass[0], 1e-12) ||
        !autobal_rotor_close_rel_(pl->ball_radius[i], pl->ball_radius[0], 1e-12) ||
        !autobal_rotor_close_rel_(s->h[i], s->h[0], 1e-12))
      return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                               "every unbalance: %zu balls in plane 1 need identical balls (plane1.ball_mass, "
                               "plane1.ball_radius and plane1.ball_damping equal for every ball; ball %zu differs "
                               "from ball 1)",
                               n, i + 1);
  if (s->opt.unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC && n > AUTOBAL_EVERYN_MAX)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance: with %zu balls the member of the family matters; unbalance_member = "
                             "every (every member) is available for 3 to %d balls (the search for the range of "
                             "|Q| over the members grows too fast above): use unbalance_member = symmetric (the "
                             "symmetric fan, the default balanced configuration)",
                             n, AUTOBAL_EVERYN_MAX);
  bi->every3 = s->opt.unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC && n == 3;
  bi->everyn = s->opt.unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC && n >= 4;
  bi->nb = n;
  bi->m1 = bi->m2 = pl->ball_mass[0];
  bi->a1 = bi->a2 = pl->ball_mass[0] * pl->ball_radius[0];
  if (!(isfinite(s_lo) && isfinite(s_hi) && s_lo > 0.0 && s_hi < (double)n * bi->a1 && s_lo <= s_hi))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "every unbalance: the range of m0 r0 [%.9g, %.9g] kg m must lie in (0, %.9g) kg m, "
                             "where the %zu balls (m r = %.9g kg m each) balance it off a line through the axis "
                             "(the closure of Delta), with min <= max",
                             s_lo, s_hi, (double)n * bi->a1, n, bi->a1);
  if (bi->every3 || bi->everyn) bi->ta = s_lo / bi->a1, bi->tb = s_hi / bi->a1;
  else fan_init(&bi->fan, n, bi->m1, bi->a1, s_lo, s_hi);
  return AUTOBAL_SUCCESS;
}

/* The checks of the model's domain; fills the balls' data. */
static int check_domain(autobal_rotor_stab *s, double s_lo, double s_hi, balls_info *bi) {
  const autobal_rotor_params *p = &s->cur;
  const autobal_rotor_plane *pl = &p->plane[0];
  double *m1 = &bi->m1, *m2 = &bi->m2, *a1 = &bi->a1, *a2 = &bi->a2, *r0 = &bi->r0;
  memset(bi, 0, sizeof *bi);
  if (p->n_planes != 1 || pl->n_balls < 2)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance: built for one plane with two or more balls (here %zu plane(s), %zu "
                             "ball(s) in plane 1); use sweeps over unbalance_mass otherwise",
                             p->n_planes, pl->n_balls);
  if (p->inertia != AUTOBAL_ROTOR_INERTIA_PAPER)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance: needs the paper's inertia model (inertia = paper): with "
                             "inertia = full the unbalance mass also enters the mass matrix");
  bi->aniso = !autobal_rotor_lumped_isotropic_(&s->L);
  if (bi->aniso && pl->n_balls != 2)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance: with anisotropic supports only one plane with two balls (a common "
                             "h/m) is supported (Hill's method); here %zu balls in plane 1",
                             pl->n_balls);
  *r0 = pl->r0;
  if (!(*r0 > 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "every unbalance: r0 = %g m must be > 0 (the unbalance s = m0 r0 is varied "
                             "through m0)",
                             *r0);
  if (!(p->omega != 0.0 && isfinite(p->omega)))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance: omega must be finite and non-zero");
  if (pl->n_balls >= 3) return check_fan(s, s_lo, s_hi, bi);
  bi->nb = 2;
  *m1 = pl->ball_mass[0];
  *m2 = pl->ball_mass[1];
  *a1 = pl->ball_mass[0] * pl->ball_radius[0];
  *a2 = pl->ball_mass[1] * pl->ball_radius[1];
  if (!autobal_rotor_close_rel_(s->h[0] / *m1, s->h[1] / *m2, 1e-12))
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance: the two balls need a common h/m (the closure of Delta)");
  {
    const double smin = fabs(*a1 - *a2), smax = *a1 + *a2;
    if (!(isfinite(s_lo) && isfinite(s_hi) && s_lo > smin && s_hi < smax && s_lo <= s_hi))
      return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                               "every unbalance: the range of m0 r0 [%.9g, %.9g] kg m must lie in (%.9g, %.9g) "
                               "kg m, where the two balls (m r = %.9g, %.9g kg m) balance it off a line through "
                               "the axis (the closure of Delta), with min <= max",
                               s_lo, s_hi, smin, smax, *a1, *a2);
  }
  return AUTOBAL_SUCCESS;
}

/* The critical values of u at the handle's omega: u at y = 0 and at the positive roots z = y^2 of h
 * (z = w^2 excluded), unfiltered (NaN possible), into uc (<= 12); A and B from the closed system at
 * m0 = s_mid / r0 (any balanceable m0 will do: they do not depend on it). */
static int critical_u(autobal_rotor_stab *s, double r0, double s_mid, double uc[12], size_t *nu) {
  double A[13], B[13], sc;
  long double Ae[7], Ao[6], Be[7], Bo[6], h[12], w2 = (long double)s->cur.omega * (long double)s->cur.omega;
  size_t i, j;
  int st;
  autobal_rotor_closed c;
  *nu = 0;
  if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, s_mid / r0)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_closed(s, &c)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_char_parts_(&c, A, B, &s->err)) != AUTOBAL_SUCCESS) return st;
  split_iy(A, Ae, Ao);
  split_iy(B, Be, Bo);
  /* y = 0: Delta(0; u) = A_0 - u w^8 B_0 */
  if (B[0] != 0.0) uc[(*nu)++] = u_at(Ae, Ao, Be, Bo, w2, 0.0L);
  /* h(z) = Ae Bo - Ao Be (degree <= 7 with B = N N* of degree 4), scaled z = sc^2 zeta, sc = |omega| */
  sc = fabs(s->cur.omega);
  for (i = 0; i < 12; i++) h[i] = 0.0L;
  for (i = 0; i < 7; i++)
    for (j = 0; j < 6; j++) h[i + j] += Ae[i] * Bo[j] - (i < 6 ? Ao[i] * Be[j] : 0.0L);
  for (i = 0; i < 6; i++) h[i + 6] -= Ao[i] * Be[6];
  {
    long double zr[11];
    size_t nz, q;
    if ((st = autobal_poly_positive_roots_ld_(h, 12, (long double)sc * (long double)sc, zr, &nz, &s->err)) !=
        AUTOBAL_SUCCESS)
      return st;
    for (q = 0; q < nz && *nu < 12; q++)
      if (fabsl(zr[q] - w2) > 1e-12L * w2) uc[(*nu)++] = u_at(Ae, Ao, Be, Bo, w2, zr[q]);
  }
  return AUTOBAL_SUCCESS;
}

/* The fields of one unbalance when the verdict comes from u (three or more balls, every member): no critical
 * unbalance, one sub-interval [s_lo, s_hi] with the worst verdict met and the worst margin. */
static void one_subinterval(autobal_rotor_unbalance_range *out, int worst) {
  out->n_crit = 0;
  out->n_sub = 1;
  out->sub_lo[0] = out->s_lo;
  out->sub_hi[0] = out->s_hi;
  out->sub_verdict[0] = worst;
  out->sub_margin[0] = out->margin_worst;
}

static int every3_core(autobal_rotor_stab *s, const balls_info *bi, autobal_rotor_unbalance_range *out);
static int everyn_core(autobal_rotor_stab *s, balls_info *bi, autobal_rotor_unbalance_range *out);

/* The core at the handle's current omega (m0 is changed; the caller restores it). */
static int every_unbalance_core(autobal_rotor_stab *s, double s_lo, double s_hi, double *angle,
                                autobal_rotor_unbalance_range *out) {
  double r0 = 0.0, cand[3 * 13 + 6], uc[12];
  balls_info bi;
  size_t nc = 0, nu = 0, i;
  int st;
  memset(out, 0, sizeof *out);
  out->s_lo = s_lo;
  out->s_hi = s_hi;
  out->omega = s->cur.omega;
  out->n_balls = s->cur.plane[0].n_balls;
  out->member_rule = s->opt.unbalance_member;
  out->u_min = out->u_max = out->u_min_inner = out->u_max_inner = NAN;
  if ((st = check_domain(s, s_lo, s_hi, &bi)) != AUTOBAL_SUCCESS) return st;
  if (bi.aniso) return autobal_rotor_every_unbalance_aniso_(s, s_lo, s_hi, out);
  r0 = bi.r0;
  if (bi.every3 || bi.everyn) {
    if (angle == NULL) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance: internal (no member angle)");
    bi.angle = angle;
    return bi.every3 ? every3_core(s, &bi, out) : everyn_core(s, &bi, out);
  }
  if (bi.nb >= 3) fan_u_range(&bi.fan, &out->u_min, &out->u_max);
  if ((st = critical_u(s, r0, 0.5 * (s_lo + s_hi), uc, &nu)) != AUTOBAL_SUCCESS) return st;
  for (i = 0; i < nu; i++) nc += map_u(&bi, uc[i], cand + nc);
  /* the critical unbalances inside (s_lo, s_hi), sorted, unique */
  qsort(cand, nc, sizeof cand[0], cmp_double);
  for (i = 0; i < nc; i++) {
    if (!(cand[i] > s_lo && cand[i] < s_hi)) continue;
    if (out->n_crit > 0 && cand[i] - out->s_crit[out->n_crit - 1] <= 1e-12 * cand[i]) continue;
    if (out->n_crit >= AUTOBAL_ROTOR_MAX_UCRIT) break;
    out->s_crit[out->n_crit++] = cand[i];
  }
  /* verdicts: each sub-interval at its midpoint and just inside both ends; disagreements bisected */
  {
    sub_result sr = {out->s_crit, &out->n_crit, out->sub_lo, out->sub_hi, out->sub_margin, out->sub_verdict,
                     &out->n_sub, &out->all_stable, &out->margin_worst, &out->evaluations, &out->n_missed, 0};
    if ((st = decide_subintervals(s, at_s, &r0, s_lo, s_hi, &sr)) != AUTOBAL_SUCCESS) return st;
  }
  return AUTOBAL_SUCCESS;
}

/* Verdict and margin at u (kg^2), three balls, every member: a member with this u (t in the middle of
 * the longest piece of e3_t_set, ball 1 at e3_phi_of_q from S: the FREE member whose angle is
 * *bi->angle), analysed as one unbalance; the member's u from the handle's angles is checked. */
static int verdict_at_u(autobal_rotor_stab *s, const balls_info *bi, double u, double *margin, int *verdict) {
  const double m = bi->m1;
  /* q = 9 has one member only, balls at 0, 0, pi from S (t = 1): on one line, where the closure (and the
   * ordinary analysis by Delta) does not hold, and members near it are nearly on one line: q is taken
   * at most 9 (1 - 1e-6) */
  const double q = fmin(4.0 * u / (m * m), 9.0 * (1.0 - 1e-6));
  ivl4 iv;
  size_t k, best = 0;
  double t, psi[3], re = 0.0, im = 0.0, qm;
  int st;
  e3_t_set(q, bi->ta, bi->tb, &iv);
  if (iv.n > 0) {
    for (k = 1; k < iv.n; k++)
      if (iv.hi[k] - iv.lo[k] > iv.hi[best] - iv.lo[best]) best = k;
    t = 0.5 * (iv.lo[best] + iv.hi[best]);
  } else {
    /* rounding at an end of the range of u: the candidate t (ends, 1, 2) nearest to having q */
    const double ts[4] = {bi->ta, bi->tb, 1.0, 2.0};
    double dbest = INFINITY;
    t = bi->ta;
    for (k = 0; k < 4; k++) {
      double d;
      if (!(ts[k] >= bi->ta && ts[k] <= bi->tb)) continue;
      d = fmax(0.0, fmax(e3_qmin(ts[k]) - q, q - e3_qmax(ts[k])));
      if (d < dbest) dbest = d, t = ts[k];
    }
  }
  *bi->angle = s->cur.plane[0].psi0 + M_PI + e3_phi_of_q(t, q);
  if ((st = verdict_at(s, bi->r0, t * bi->a1, margin, verdict)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_balanced_angles(s, psi, 3)) != AUTOBAL_SUCCESS) return st;
  for (k = 0; k < 3; k++) re += cos(2.0 * psi[k]), im += sin(2.0 * psi[k]);
  qm = re * re + im * im;
  if (!(fabs(qm - q) <= 1e-6))
    return autobal_error_set(&s->err, AUTOBAL_ENUMERIC,
                             "every unbalance, every member: the member built for u = %.9g kg^2 has u = %.9g kg^2 "
                             "(internal error)",
                             u, 0.25 * m * m * qm);
  return AUTOBAL_SUCCESS;
}

static int at_u(autobal_rotor_stab *s, const void *ctx, double x, double *margin, int *verdict) {
  return verdict_at_u(s, (const balls_info *)ctx, x, margin, verdict);
}

/* Three identical balls, every member: the range of u, the critical u inside, one verdict per
 * sub-interval of u (midpoint and just inside both ends; a disagreement bisected in u), the ends; the
 * unbalances of each critical u. */
static int every3_core(autobal_rotor_stab *s, const balls_info *bi, autobal_rotor_unbalance_range *out) {
  const double m = bi->m1, ta = bi->ta, tb = bi->tb, um = 0.25 * m * m;
  double qlo, qhi, uc[12];
  size_t nu = 0, i, k;
  int st, worst = AUTOBAL_VERDICT_STABLE;
  qlo = fmin(e3_qmin(ta), e3_qmin(tb));
  if (ta < 2.0 && tb > 2.0) qlo = 0.0;
  qhi = fmax(e3_qmax(ta), e3_qmax(tb));
  if (ta < 1.0 && tb > 1.0) qhi = 9.0;
  out->u_min = out->u_min_inner = um * qlo;
  out->u_max = out->u_max_inner = um * qhi;
  out->u_complete = 1;
  *bi->angle = s->cur.plane[0].psi0 + M_PI; /* phi = 0: a member for every t */
  if ((st = critical_u(s, bi->r0, 0.5 * (out->s_lo + out->s_hi), uc, &nu)) != AUTOBAL_SUCCESS) return st;
  qsort(uc, nu, sizeof uc[0], cmp_double);
  for (i = 0; i < nu; i++) {
    if (!(uc[i] > out->u_min && uc[i] < out->u_max)) continue;
    if (out->n_ucrit > 0 && uc[i] - out->u_crit[out->n_ucrit - 1] <= 1e-12 * uc[i]) continue;
    if (out->n_ucrit >= AUTOBAL_ROTOR_MAX_UCRIT) break;
    out->u_crit[out->n_ucrit++] = uc[i];
  }
  {
    sub_result sr = {out->u_crit, &out->n_ucrit, out->usub_lo, out->usub_hi, out->usub_margin, out->usub_verdict,
                     &out->n_usub, &out->all_stable, &out->margin_worst, &out->evaluations, &out->n_missed, 0};
    if ((st = decide_subintervals(s, at_u, bi, out->u_min, out->u_max, &sr)) != AUTOBAL_SUCCESS) return st;
    worst = sr.worst;
  }
  /* the unbalances of each critical u (closed form) */
  for (k = 0; k < out->n_ucrit; k++) {
    ivl4 iv;
    e3_t_set(4.0 * out->u_crit[k] / (m * m), ta, tb, &iv);
    for (i = 0; i < iv.n && out->n_upiece < 3 * AUTOBAL_ROTOR_MAX_UCRIT; i++) {
      out->upiece_crit[out->n_upiece] = k;
      out->upiece_lo[out->n_upiece] = iv.lo[i] * bi->a1;
      out->upiece_hi[out->n_upiece] = iv.hi[i] * bi->a1;
      out->n_upiece++;
    }
  }
  one_subinterval(out, worst);
  return AUTOBAL_SUCCESS;
}

/* ---- four to ten identical balls, every member ---- */

/* Box budget and tolerance (in q) of the enclosure's two searches (rotor_every_n.c). */
#define EVERYN_BOXES 4000000L
#define EVERYN_TOL_REL 1e-9

/* Plane 1's GIVEN member set to m (angles from S, S opposite the unbalance), analysed at its own
 * unbalance t m r; the member's u from the handle's angles is checked against m's. */
static int verdict_member(autobal_rotor_stab *s, const balls_info *bi, const autobal_everyn_member_ *mem,
                          double *margin, int *verdict) {
  const size_t n = bi->nb;
  double psi[AUTOBAL_EVERYN_MAX], re = 0.0, im = 0.0, qm;
  size_t k;
  int st;
  for (k = 0; k < n; k++) bi->angle[k] = s->cur.plane[0].psi0 + M_PI + mem->phi[k];
  if ((st = verdict_at(s, bi->r0, mem->t * bi->a1, margin, verdict)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_balanced_angles(s, psi, n)) != AUTOBAL_SUCCESS) return st;
  for (k = 0; k < n; k++) re += cos(2.0 * psi[k]), im += sin(2.0 * psi[k]);
  qm = re * re + im * im;
  if (!(fabs(qm - mem->q) <= 1e-9 * (double)(n * n)))
    return autobal_error_set(&s->err, AUTOBAL_ENUMERIC,
                             "every unbalance, every member: the member built with u = %.9g kg^2 has u = %.9g kg^2 "
                             "in the analysis (internal error)",
                             0.25 * bi->m1 * bi->m1 * mem->q, 0.25 * bi->m1 * bi->m1 * qm);
  return AUTOBAL_SUCCESS;
}

/* Verdict and margin at u (kg^2): a member of [ta, tb] with this u (u clamped to the members found,
 * and below the one member on a line, q = n^2, where the closure does not hold), built from the
 * enclosure's members by Newton steps; it must reach u to 1e-13 n^2 in q. */
static int verdict_at_un(autobal_rotor_stab *s, const balls_info *bi, double u, double *margin, int *verdict) {
  const size_t n = bi->nb;
  const double m = bi->m1, qn = (double)(n * n), tol = 1e-13 * qn;
  double q = 4.0 * u / (m * m);
  autobal_everyn_member_ mem;
  if (q > bi->en->q_hi_in) q = bi->en->q_hi_in;
  if (q > qn * (1.0 - 1e-6)) q = qn * (1.0 - 1e-6);
  if (q < bi->en->q_lo_in) q = bi->en->q_lo_in;
  if (autobal_everyn_member_at_(bi->en, q, tol, &mem) != 0)
    return autobal_error_set(&s->err, AUTOBAL_ENUMERIC,
                             "every unbalance, every member: no member with u = %.9g kg^2 was built (the nearest "
                             "has %.9g kg^2; %zu balls, m0 r0 in [%.9g, %.9g] kg m)",
                             0.25 * m * m * q, 0.25 * m * m * mem.q, n, bi->ta * bi->a1, bi->tb * bi->a1);
  return verdict_member(s, bi, &mem, margin, verdict);
}

static int at_un(autobal_rotor_stab *s, const void *ctx, double x, double *margin, int *verdict) {
  return verdict_at_un(s, (const balls_info *)ctx, x, margin, verdict);
}

/* Four to ten identical balls, every member: the enclosure of u (kept on the handle for the same n
 * and range), the critical u inside it, the verdicts of the sub-intervals on the inner range [members
 * found], the sub-intervals wholly in the gap undecided. */
static int everyn_core(autobal_rotor_stab *s, balls_info *bi, autobal_rotor_unbalance_range *out) {
  const size_t n = bi->nb;
  const double m = bi->m1, um = 0.25 * m * m, qn = (double)(n * n);
  double uc[12], ilo, ihi, gap_lo[AUTOBAL_ROTOR_MAX_UCRIT], gap_hi[AUTOBAL_ROTOR_MAX_UCRIT];
  size_t nu = 0, i, ngl = 0, ngh = 0;
  int st, worst = AUTOBAL_VERDICT_STABLE;
  autobal_everyn_ *e = s->everyn;
  if (e == NULL || e->n != n || e->ta != bi->ta || e->tb != bi->tb) {
    if (e == NULL && (e = s->everyn = (autobal_everyn_ *)malloc(sizeof *e)) == NULL)
      return autobal_error_set(&s->err, AUTOBAL_ENOMEM, "every unbalance: no memory for the member search");
    const long budget = s->opt.member_boxes > 0 ? s->opt.member_boxes : EVERYN_BOXES;
    if (autobal_everyn_range_(e, n, bi->ta, bi->tb, budget, EVERYN_TOL_REL * qn) != 0) {
      e->n = 0;
      return autobal_error_set(&s->err, AUTOBAL_ENOMEM, "every unbalance: the member search for %zu balls failed (no memory)", n);
    }
  }
  bi->en = e;
  out->u_min = um * e->q_lo;
  out->u_max = um * e->q_hi;
  out->u_min_inner = um * e->q_lo_in;
  out->u_max_inner = um * fmin(e->q_hi_in, qn * (1.0 - 1e-6));
  out->u_complete = e->complete;
  out->u_boxes = e->boxes;
  ilo = out->u_min_inner, ihi = out->u_max_inner;
  /* a member for the crossing polynomial (any member of an unbalance in the range will do) */
  {
    autobal_everyn_member_ fan;
    autobal_everyn_fan_(n, 0.5 * (bi->ta + bi->tb), &fan);
    fan.t = 0.5 * (bi->ta + bi->tb);
    for (i = 0; i < n; i++) bi->angle[i] = s->cur.plane[0].psi0 + M_PI + fan.phi[i];
    if ((st = critical_u(s, bi->r0, fan.t * bi->a1, uc, &nu)) != AUTOBAL_SUCCESS) return st;
  }
  qsort(uc, nu, sizeof uc[0], cmp_double);
  /* the critical u inside the inner range go to the sub-interval decision; those in the gaps aside */
  for (i = 0; i < nu; i++) {
    /* inside the enclosure; one at an end (to 1e-12 of the largest u, n^2 m^2 / 4: e.g. at the member on
     * a line, q = n^2) is no cut */
    if (!(uc[i] > out->u_min + 1e-12 * um * qn && uc[i] < out->u_max - 1e-12 * um * qn)) continue;
    if (uc[i] > ilo && uc[i] < ihi) {
      if (out->n_ucrit > 0 && uc[i] - out->u_crit[out->n_ucrit - 1] <= 1e-12 * uc[i]) continue;
      if (out->n_ucrit < AUTOBAL_ROTOR_MAX_UCRIT) out->u_crit[out->n_ucrit++] = uc[i];
    } else if (uc[i] <= ilo) {
      if (ngl < AUTOBAL_ROTOR_MAX_UCRIT) gap_lo[ngl++] = uc[i];
    } else if (ngh < AUTOBAL_ROTOR_MAX_UCRIT)
      gap_hi[ngh++] = uc[i];
  }
  {
    sub_result sr = {out->u_crit, &out->n_ucrit, out->usub_lo, out->usub_hi, out->usub_margin, out->usub_verdict,
                     &out->n_usub, &out->all_stable, &out->margin_worst, &out->evaluations, &out->n_missed, 0};
    if ((st = decide_subintervals(s, at_un, bi, ilo, ihi, &sr)) != AUTOBAL_SUCCESS) return st;
    worst = sr.worst;
  }
  /* the sub-intervals reach the outer bounds: the first and the last extended to the nearest critical
   * u in the gap (or the bound); those wholly in a gap (past a critical u there) are undecided */
  if (out->n_usub > 0 && ngl + ngh + out->n_usub <= AUTOBAL_ROTOR_MAX_UCRIT + 1 &&
      out->n_ucrit + ngl + ngh <= AUTOBAL_ROTOR_MAX_UCRIT) {
    double lo2[AUTOBAL_ROTOR_MAX_UCRIT + 1], hi2[AUTOBAL_ROTOR_MAX_UCRIT + 1], mg2[AUTOBAL_ROTOR_MAX_UCRIT + 1];
    double cr2[AUTOBAL_ROTOR_MAX_UCRIT];
    int v2[AUTOBAL_ROTOR_MAX_UCRIT + 1];
    size_t ns = 0, nc = 0;
    for (i = 0; i < ngl; i++) {
      lo2[ns] = i == 0 ? out->u_min : gap_lo[i - 1], hi2[ns] = gap_lo[i], v2[ns] = AUTOBAL_ROTOR_VERDICT_NONE,
      mg2[ns] = NAN, ns++;
      cr2[nc++] = gap_lo[i];
    }
    for (i = 0; i < out->n_ucrit; i++) cr2[nc++] = out->u_crit[i];
    for (i = 0; i < out->n_usub; i++) {
      lo2[ns] = out->usub_lo[i], hi2[ns] = out->usub_hi[i], v2[ns] = out->usub_verdict[i], mg2[ns] = out->usub_margin[i];
      if (i == 0) lo2[ns] = ngl > 0 ? gap_lo[ngl - 1] : out->u_min;
      if (i + 1 == out->n_usub) hi2[ns] = ngh > 0 ? gap_hi[0] : out->u_max;
      ns++;
    }
    for (i = 0; i < ngh; i++) {
      lo2[ns] = gap_hi[i], hi2[ns] = i + 1 < ngh ? gap_hi[i + 1] : out->u_max, v2[ns] = AUTOBAL_ROTOR_VERDICT_NONE,
      mg2[ns] = NAN, ns++;
      cr2[nc++] = gap_hi[i];
    }
    out->n_uundecided = ngl + ngh;
    out->n_ucrit = nc;
    for (i = 0; i < nc; i++) out->u_crit[i] = cr2[i];
    out->n_usub = ns;
    for (i = 0; i < ns; i++)
      out->usub_lo[i] = lo2[i], out->usub_hi[i] = hi2[i], out->usub_verdict[i] = v2[i], out->usub_margin[i] = mg2[i];
  } else if (ngl + ngh > 0)
    out->n_uundecided = ngl + ngh;
  if (out->n_uundecided > 0) out->all_stable = 0;
  one_subinterval(out, worst);
  return AUTOBAL_SUCCESS;
}

/* The core with plane 1's member set to the rule's (n >= 3 balls, SYMMETRIC: the symmetric fan) for the
 * verdicts; the member option is restored afterwards. */
static int every_unbalance(autobal_rotor_stab *s, double s_lo, double s_hi, autobal_rotor_unbalance_range *out) {
  autobal_rotor_member save;
  /* ball 1 of the FREE member (three balls, every member); every ball of the GIVEN member (four to ten) */
  double angle[AUTOBAL_EVERYN_MAX] = {0.0};
  int st;
  const size_t nb = s->cur.plane[0].n_balls;
  const int every3 = s->opt.unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC && nb == 3;
  const int everyn = s->opt.unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC && nb >= 4 && nb <= AUTOBAL_EVERYN_MAX;
  if (s->n_planes != 1 || nb < 3 || (s->opt.unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC && !every3 && !everyn))
    return every_unbalance_core(s, s_lo, s_hi, NULL, out);
  save = s->opt.member[0];
  if (every3) {
    s->opt.member[0].kind = AUTOBAL_ROTOR_MEMBER_FREE;
    s->opt.member[0].n_angles = 1;
    s->opt.member[0].angles = angle;
  } else if (everyn) {
    s->opt.member[0].kind = AUTOBAL_ROTOR_MEMBER_GIVEN;
    s->opt.member[0].n_angles = nb;
    s->opt.member[0].angles = angle;
  } else {
    s->opt.member[0].kind = AUTOBAL_ROTOR_MEMBER_SYMMETRIC;
    s->opt.member[0].n_angles = 0;
    s->opt.member[0].angles = NULL;
  }
  st = every_unbalance_core(s, s_lo, s_hi, angle, out);
  s->opt.member[0] = save;
  return st;
}

int autobal_rotor_stab_every_unbalance(autobal_rotor_stab *s, double s_lo, double s_hi,
                                       autobal_rotor_unbalance_range *out) {
  double m0;
  int st, st2;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance: out is NULL");
  if (s->cur.n_planes == 2) return autobal_rotor_every_unbalance_two_planes_(s, s_lo, s_hi, out);
  m0 = s->cur.plane[0].m0;
  st = every_unbalance(s, s_lo, s_hi, out);
  st2 = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  return st != AUTOBAL_SUCCESS ? st : st2;
}

int autobal_rotor_stab_every_unbalance_margin(autobal_rotor_stab *s, double s_lo, double s_hi, double delta,
                                              int *verdict, autobal_rotor_unbalance_range *out) {
  balls_info bi;
  double m0;
  int st, st2;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL || verdict == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance (margin): out or verdict is NULL");
  *verdict = -1;
  if (!(delta >= 0.0 && isfinite(delta)))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance (margin): delta = %g 1/s: allowed [0, inf)",
                             delta);
  if (s->cur.n_planes != 1 || s->cur.plane[0].n_balls != 2)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "every unbalance (margin): built for one plane with two balls (here %zu plane(s), %zu "
                             "ball(s) in plane 1); autobal_rotor_stab_margin_ratio_set for n identical balls, "
                             "autobal_rotor_stab_every_unbalance2_shift for two planes",
                             s->cur.n_planes, s->cur.plane[0].n_balls);
  memset(out, 0, sizeof *out);
  out->s_lo = s_lo;
  out->s_hi = s_hi;
  out->omega = s->cur.omega;
  out->n_balls = 2;
  out->member_rule = s->opt.unbalance_member;
  out->u_min = out->u_max = out->u_min_inner = out->u_max_inner = NAN;
  if ((st = check_domain(s, s_lo, s_hi, &bi)) != AUTOBAL_SUCCESS) return st;
  m0 = s->cur.plane[0].m0;
  st = autobal_rotor_every_unbalance_hill_(s, s_lo, s_hi, delta, out);
  st2 = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  if (st == AUTOBAL_SUCCESS) st = st2;
  if (st == AUTOBAL_SUCCESS)
    *verdict = out->all_stable ? 1 : out->sub_verdict[0] == AUTOBAL_VERDICT_UNSTABLE ? 0 : -1;
  return st;
}

typedef struct {
  double s_lo, s_hi;
} speeds_ctx;

/* autobal_rotor_speed_verdict_fn_ of the one-plane speed set. */
static int speeds_verdict(autobal_rotor_stab *s, void *user, int *all_stable, size_t *evaluations) {
  const speeds_ctx *c = (const speeds_ctx *)user;
  autobal_rotor_unbalance_range ur;
  const int st = every_unbalance(s, c->s_lo, c->s_hi, &ur);
  if (st != AUTOBAL_SUCCESS) return st;
  *evaluations = ur.evaluations;
  *all_stable = ur.all_stable;
  return st;
}

int autobal_rotor_stab_every_unbalance_speeds(autobal_rotor_stab *s, double s_lo, double s_hi, double w_lo,
                                              double w_hi, size_t n_grid, double xtol_rel, autobal_rotor_crit *out) {
  speeds_ctx c;
  double m0;
  int st, st2;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (out == NULL) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance: out is NULL");
  if (s->cur.n_planes == 2)
    return autobal_rotor_every_unbalance_speeds_two_planes_(s, s_lo, s_hi, w_lo, w_hi, n_grid, xtol_rel, out);
  c.s_lo = s_lo;
  c.s_hi = s_hi;
  m0 = s->cur.plane[0].m0;
  st = autobal_rotor_scan_speeds_(s, w_lo, w_hi, n_grid, xtol_rel, speeds_verdict, &c, out);
  st2 = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  return st != AUTOBAL_SUCCESS ? st : st2;
}

/* A map point's verdict for every unbalance in [s_lo, s_hi] (the map's per-point function). */
typedef struct every_map {
  double s_lo, s_hi;
} every_map;

static int every_point(autobal_rotor_stab *s, void *user, double *mg, int *v) {
  const every_map *em = (const every_map *)user;
  autobal_rotor_unbalance_range ur;
  size_t k;
  int st = autobal_rotor_stab_every_unbalance(s, em->s_lo, em->s_hi, &ur);
  *mg = NAN;
  *v = AUTOBAL_ROTOR_VERDICT_NONE;
  if (st == AUTOBAL_EINVAL) return AUTOBAL_SUCCESS; /* the balls cannot balance every unbalance here: NONE */
  if (st != AUTOBAL_SUCCESS) return st;
  /* the worst verdict over the range: a critical unbalance inside with stable sides is a touch */
  *v = AUTOBAL_VERDICT_STABLE;
  for (k = 0; k < ur.n_sub; k++)
    if (ur.sub_verdict[k] < *v) *v = ur.sub_verdict[k];
  if (!ur.all_stable && *v == AUTOBAL_VERDICT_STABLE) *v = AUTOBAL_VERDICT_MARGINAL;
  if (ur.hill && *v == AUTOBAL_ROTOR_VERDICT_NONE) *v = AUTOBAL_ROTOR_VERDICT_UNDECIDED; /* budget reached */
  *mg = ur.margin_worst;
  return AUTOBAL_SUCCESS;
}

/* Whether a parameter sets the unbalance itself (the map for every unbalance varies it). */
static int unbalance_axis(int param) {
  return param == AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS || param == AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_M0) ||
         param == AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_UNBALANCE);
}

int autobal_rotor_stab_map_every_unbalance(const autobal_rotor_params *p, const autobal_rotor_stab_options *opt,
                                           int param1, const double *v1, size_t n1, int param2, const double *v2,
                                           size_t n2, double s_lo, double s_hi, int n_threads, double *margin,
                                           int *verdict, autobal_error *err) {
  every_map em;
  if (unbalance_axis(param1) || unbalance_axis(param2))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "map for every unbalance: %s cannot be an axis (the unbalance is the range "
                             "[%g, %g] kg m)",
                             autobal_rotor_stab_param_name(unbalance_axis(param1) ? param1 : param2), s_lo, s_hi);
  if (!(isfinite(s_lo) && isfinite(s_hi) && s_lo > 0.0 && s_lo <= s_hi))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "map for every unbalance: the range of m0 r0 [%g, %g] kg m needs 0 < min <= max, finite",
                             s_lo, s_hi);
  em.s_lo = s_lo;
  em.s_hi = s_hi;
  return autobal_rotor_stab_map_run_(p, opt, every_point, &em, param1, v1, n1, param2, v2, n2, n_threads, margin,
                                     verdict, err);
}
