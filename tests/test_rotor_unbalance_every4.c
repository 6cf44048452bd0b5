/* test_rotor_unbalance_every4.c: every member and every unbalance of one plane with four to ten
 * identical balls (unbalance_member = EVERY; src/analysis/rotor_every_n.c, docs/rotor.md "Four or
 * more balls, every member"), against reasons that do not use the branch-and-bound:
 *  - closed forms as limits: four balls in two coincident pairs, 2 e^{ia} + 2 e^{ib} = t, have
 *    q = (t^2/2 - 4)^2 and three together with one, 3 e^{ia} + e^{ib} = t, q = 10 + 6 (2 c^2 - 1),
 *    c = (t^2 - 10) / 6: both are members, so q_lo <= them <= q_hi, and for t in [2 sqrt 2, 4) they are
 *    the least and the largest (the SciPy check of tests/app/rotor_every_unbalance_every4.sh); Q = 0
 *    members exist for even n up to t = n / sqrt 2 (n / 2 balls pairwise at right angles: z, i z) and
 *    for n = 5 at t = 3 (a found member, q < 1e-20); the symmetric fan (angles (k - (n-1)/2) d) is a
 *    member: q_lo <= its q <= q_hi;
 *  - 200000 random configurations per case (angles uniform, kept when |S| lies in the range): every
 *    one has q inside [q_lo, q_hi];
 *  - the members built for a target q: |S| recomputed from their angles lies in the range, S along
 *    the real axis, q recomputed equals the target;
 *  - the library verdict: each u sub-interval's verdict equals ordinary analyses (method POLY, member
 *    'given') of random members whose u lies inside it; members just either side of each critical u
 *    differ in their number of roots with Re > 0; stable for all only when all are stable;
 *  - seven, eight and ten balls: the same checks where the search closes (ranges with a Q = 0 member), and
 *    with a small budget (member_boxes) where it does not: the bounds stay valid (random members inside,
 *    and they contain the bounds of a larger budget), complete = 0;
 *  - eleven balls refused with a message naming unbalance_member = symmetric; member_boxes out of range
 *    refused naming it. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/rotor_every_n.h"
#include "autobal.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define NMAX 11
static double bm[NMAX], br[NMAX], bh[NMAX], bpsi[NMAX];
static const double M = 0.05, A = 0.05 * 0.1;

static autobal_rotor_params params_n(size_t n) {
  autobal_rotor_params p = autobal_rotor_params_default();
  size_t i;
  for (i = 0; i < n; i++) bm[i] = M, br[i] = 0.1, bh[i] = 0.1, bpsi[i] = 0.3 * (double)i;
  p.plane[0].n_balls = n;
  p.plane[0].ball_mass = bm;
  p.plane[0].ball_radius = br;
  p.plane[0].ball_damping = bh;
  p.plane[0].ball_psi = bpsi;
  p.plane[0].ball_rate = NULL;
  return p;
}

static double urand(void) { return (double)rand() / ((double)RAND_MAX + 1.0); }

static double qof(size_t n, const double *phi, double *t) {
  double complex s = 0.0, q = 0.0;
  size_t k;
  for (k = 0; k < n; k++) s += cexp(I * phi[k]), q += cexp(2.0 * I * phi[k]);
  *t = cabs(s);
  return creal(q * conj(q));
}

/* The fan of n balls at spacing d: t and q from its angles. */
static double fan_q(size_t n, double d, double *t) {
  double phi[NMAX];
  size_t k;
  for (k = 0; k < n; k++) phi[k] = ((double)k - 0.5 * (double)(n - 1)) * d;
  return qof(n, phi, t);
}

#ifdef AUTOBAL_TEST_SANITIZE
/* In the sanitizer build (AUTOBAL_TEST_SANITIZE) the same library paths run with fewer repetitions:
 * the enclosure of six balls for t in [4.5, 4.8] (1.8 million boxes, 70% of the test's boxes) stops
 * at 100000 boxes (its outer bounds stay certified, the checks below hold for them; the other ranges
 * run the same search to the end), and 30 random members per verdict case instead of 120 (NSAMP);
 * the Release pass runs all of it. */
static int range_sanitize(autobal_everyn_ *e, size_t n, double ta, double tb, long max_boxes, double tol) {
  return autobal_everyn_range_(e, n, ta, tb, n == 6 && ta > 4.0 && max_boxes > 100000L ? 100000L : max_boxes, tol);
}
#define autobal_everyn_range_ range_sanitize
#define NSAMP 30
#else
#define NSAMP 120
#endif

static void enclosure_checks(void) {
  autobal_everyn_ e;
  char what[200];
  size_t n, j;
  /* four balls, t >= 2 sqrt 2: two pairs (least) and three plus one (largest) */
  {
    const double ts[3] = {3.0, 3.2, 3.6};
    for (j = 0; j < 3; j++) {
      const double t = ts[j], pairs = (t * t / 2.0 - 4.0) * (t * t / 2.0 - 4.0), c = (t * t - 10.0) / 6.0,
                   three1 = 10.0 + 6.0 * (2.0 * c * c - 1.0);
      CHECK("n = 4 enclosure runs", autobal_everyn_range_(&e, 4, t, t, 4000000L, 1.6e-8) == 0);
      snprintf(what, sizeof what, "n = 4, t = %g: q_lo <= two pairs (t^2/2 - 4)^2 <= q_hi", t);
      CHECK(what, e.q_lo <= pairs && pairs <= e.q_hi);
      snprintf(what, sizeof what, "n = 4, t = %g: least member found = two pairs", t);
      CHECK_CLOSE(what, e.q_lo_in, pairs, 0.0, 1e-8);
      snprintf(what, sizeof what, "n = 4, t = %g: largest member found = three together and one", t);
      CHECK_CLOSE(what, e.q_hi_in, three1, 0.0, 1e-8);
      snprintf(what, sizeof what, "n = 4, t = %g: outer bounds within 2e-8 of the members (closed)", t);
      CHECK(what, e.complete && e.q_lo_in - e.q_lo <= 2e-8 && e.q_hi - e.q_hi_in <= 2e-8 && e.q_lo <= e.q_lo_in &&
                      e.q_hi_in <= e.q_hi);
    }
  }
  /* Q = 0 reachable: even n up to n / sqrt 2; n = 5 at t = 3 */
  for (n = 4; n <= 10; n++) {
    const double t = n == 5 ? 3.0 : 0.999 * (double)n / sqrt(2.0);
    if (n == 7 || n == 9) continue;
    CHECK("enclosure runs", autobal_everyn_range_(&e, n, 0.5 * t, t, 4000000L, 1e-9 * (double)(n * n)) == 0);
    snprintf(what, sizeof what, "n = %zu, t in [%g, %g]: a member with Q = 0 found (q < 1e-20), q_lo = 0", n, 0.5 * t, t);
    CHECK(what, e.q_lo_in < 1e-20 && e.q_lo == 0.0);
  }
  /* random configurations and the fan inside the enclosure; built members */
  for (n = 4; n <= 10; n++) {
    const double cases[3][2] = {{0.3, 0.9}, {1.7, 2.6}, {0.75 * (double)n, 0.8 * (double)n}};
    size_t c;
    if (n == 9) continue;
    for (c = 0; c < 3; c++) {
      const double ta = cases[c][0], tb = cases[c][1];
      /* seven balls and more: a budget of 40000 boxes (closed in [1.7, 2.6] for 8 and 10 balls; else not) */
      const long budget = n >= 7 ? 40000L : 4000000L;
      double phi[NMAX], t, q, qmin = INFINITY, qmax = -INFINITY, d;
      long kept = 0, out = 0, it;
      size_t k, bad = 0;
      CHECK("enclosure runs", autobal_everyn_range_(&e, n, ta, tb, budget, 1e-9 * (double)(n * n)) == 0);
      if (budget < 4000000L) {
        /* a tenth of the budget (half per search): closed or out of budget, its outer bounds contain every member either search found */
        autobal_everyn_ e2;
        CHECK("enclosure runs (a tenth of the budget)",
              autobal_everyn_range_(&e2, n, ta, tb, budget / 10, 1e-9 * (double)(n * n)) == 0);
        snprintf(what, sizeof what,
                 "n = %zu, t in [%g, %g]: %ld boxes: closed or budget reached, its bounds [%.6g, %.6g] contain the members of both "
                 "budgets", n, ta, tb, e2.boxes, e2.q_lo, e2.q_hi);
        CHECK(what, (e2.complete || e2.boxes >= budget / 20) && e2.q_lo <= fmin(e.q_lo_in, e2.q_lo_in) && e2.q_hi >= fmax(e.q_hi_in, e2.q_hi_in) &&
                        e.q_lo <= fmin(e.q_lo_in, e2.q_lo_in) && e.q_hi >= fmax(e.q_hi_in, e2.q_hi_in));
      }
      printf("     n = %zu, t in [%g, %g]: q outer [%.12g, %.12g], found [%.12g, %.12g], %ld boxes, complete %d\n", n, ta,
             tb, e.q_lo, e.q_hi, e.q_lo_in, e.q_hi_in, e.boxes, e.complete);
      for (it = 0; it < 200000; it++) {
        for (k = 0; k < n; k++) phi[k] = 2.0 * M_PI * urand();
        q = qof(n, phi, &t);
        if (t < ta || t > tb) continue;
        kept++;
        if (q < qmin) qmin = q;
        if (q > qmax) qmax = q;
        if (q < e.q_lo - 1e-12 || q > e.q_hi + 1e-12) out++;
      }
      snprintf(what, sizeof what,
               "n = %zu, t in [%g, %g]: %ld random members (q in [%.6g, %.6g]) inside the enclosure", n, ta, tb,
               kept, qmin, qmax);
      CHECK(what, kept > 100 && out == 0);
      for (d = 1e-3; d < 2.0 * M_PI / (double)n; d += 0.01) {
        q = fan_q(n, d, &t);
        if (t >= ta && t <= tb && (q < e.q_lo - 1e-12 || q > e.q_hi + 1e-12)) bad++;
      }
      snprintf(what, sizeof what, "n = %zu, t in [%g, %g]: the symmetric fan inside the enclosure", n, ta, tb);
      CHECK(what, bad == 0);
      bad = 0;
      for (k = 1; k < 10; k++) {
        autobal_everyn_member_ mem;
        const double target = e.q_lo_in + (e.q_hi_in - e.q_lo_in) * (double)k / 10.0;
        double complex s = 0.0;
        size_t i;
        if (autobal_everyn_member_at_(&e, target, 1e-12, &mem) != 0) bad++;
        for (i = 0; i < n; i++) s += cexp(I * mem.phi[i]);
        q = qof(n, mem.phi, &t);
        if (!(fabs(q - target) <= 1e-11 && t >= ta - 1e-12 && t <= tb + 1e-12 && fabs(cimag(s)) <= 1e-12 &&
              creal(s) > 0.0 && fabs(t - mem.t) <= 1e-12))
          bad++;
      }
      snprintf(what, sizeof what, "n = %zu, t in [%g, %g]: 9 members built for a target q (recomputed)", n, ta, tb);
      CHECK(what, bad == 0);
    }
  }
}

/* The ordinary verdict (POLY, member 'given') of the member phi (from S) of t; rhp roots. */
static int analyse(const autobal_rotor_params *p0, double w, size_t n, double t, const double *phi, int *verdict,
                   int *rhp) {
  autobal_rotor_params p = *p0;
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  double ang[NMAX], margin;
  autobal_error err;
  autobal_rotor_stab *s;
  autobal_rotor_stab_result res;
  size_t k;
  int st;
  p.omega = w;
  p.plane[0].m0 = t * A / p.plane[0].r0;
  for (k = 0; k < n; k++) ang[k] = p.plane[0].psi0 + M_PI + phi[k];
  o.member[0].kind = AUTOBAL_ROTOR_MEMBER_GIVEN;
  o.member[0].n_angles = n;
  o.member[0].angles = ang;
  s = autobal_rotor_stab_alloc(&p, &o, &err);
  if (!s) return 0;
  st = autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &margin, verdict);
  *rhp = -1;
  if (st == AUTOBAL_SUCCESS && autobal_rotor_stab_analyze(s, &res) == AUTOBAL_SUCCESS)
    for (*rhp = 0, k = 0; k < res.n_closed; k++) *rhp += res.root_re[k] > 0.0;
  autobal_rotor_stab_free(s);
  return st == AUTOBAL_SUCCESS;
}

/* A random member of [ta, tb]: n - 2 random angles, t uniform, the last two closed; returns 0 if none. */
static int random_member(size_t n, double ta, double tb, double *phi, double *t, double *q) {
  double complex v;
  double av, h;
  size_t k;
  *t = ta + (tb - ta) * urand();
  v = *t;
  for (k = 0; k + 2 < n; k++) phi[k] = 2.0 * M_PI * urand(), v -= cexp(I * phi[k]);
  av = cabs(v);
  if (!(av < 2.0 && av > 0.0)) return 0;
  h = sqrt(1.0 - 0.25 * av * av);
  phi[n - 2] = carg(0.5 * v + I * v / av * h);
  phi[n - 1] = carg(0.5 * v - I * v / av * h);
  {
    double tt;
    *q = qof(n, phi, &tt);
  }
  return 1;
}

static void verdict_case(size_t n, double w, double s_lo, double s_hi) {
  autobal_rotor_params p = params_n(n);
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_rotor_unbalance_range ur;
  autobal_error err;
  autobal_rotor_stab *s;
  const double um = 0.25 * M * M, ta = s_lo / A, tb = s_hi / A;
  char what[240];
  size_t k, i, nbad = 0, nsamp = 0, side_bad = 0, sides = 0;
  int all = 1;
  p.omega = w;
  s = autobal_rotor_stab_alloc(&p, &o, &err);
  CHECK("alloc", s != NULL);
  if (!s) return;
  CHECK_STATUS("every unbalance, every member", autobal_rotor_stab_every_unbalance(s, s_lo, s_hi, &ur), AUTOBAL_SUCCESS);
  printf("     n = %zu, %g rad/s, [%g, %g] kg m: u in [%.9g, %.9g] (found [%.9g, %.9g]), %zu critical u, stable_for_all %d\n",
         n, w, s_lo, s_hi, ur.u_min, ur.u_max, ur.u_min_inner, ur.u_max_inner, ur.n_ucrit, ur.all_stable);
  /* random members: the verdict of their u sub-interval */
  for (k = 0; k < 20000 && nsamp < NSAMP; k++) {
    double phi[NMAX], t, q, u;
    int v, rhp;
    if (!random_member(n, ta, tb, phi, &t, &q)) continue;
    u = um * q;
    for (i = 0; i < ur.n_usub; i++)
      if (u > ur.usub_lo[i] + 1e-9 * um && u < ur.usub_hi[i] - 1e-9 * um) break;
    if (i == ur.n_usub || q > (double)(n * n) * (1.0 - 1e-4)) continue;
    if (!analyse(&p, w, n, t, phi, &v, &rhp)) {
      nbad++;
      continue;
    }
    nsamp++;
    if (v != ur.usub_verdict[i]) nbad++;
    if (v != AUTOBAL_VERDICT_STABLE) all = 0;
  }
  snprintf(what, sizeof what, "n = %zu, %g rad/s: %zu random members have their u sub-interval's verdict", n, w, nsamp);
  CHECK(what, nsamp >= NSAMP * 5 / 6 && nbad == 0);
  snprintf(what, sizeof what, "n = %zu, %g rad/s: stable_for_all = %d agrees with the members (and no critical u)", n,
           w, ur.all_stable);
  CHECK(what, ur.all_stable == (all && ur.n_ucrit == 0));
  /* either side of each critical u: members (Newton-built by the test's own bisection on a segment of
   * random members) with u = uc (1 -+ 1e-4) differ in their count of roots with Re > 0 */
  for (i = 0; i < ur.n_ucrit; i++) {
    const double uc = ur.u_crit[i];
    int rh[2] = {-1, -1}, sd;
    for (sd = 0; sd < 2; sd++) {
      const double target = uc * (sd == 0 ? 1.0 - 1e-4 : 1.0 + 1e-4) / um;
      /* bisection on the angle of ball 1 between a random member below and one above at the same t */
      for (k = 0; k < 20000 && rh[sd] < 0; k++) {
        double phi[NMAX], t, q, phi2[NMAX], q2, lo, hi, tt;
        double complex v;
        size_t j, it;
        int vv, ok = 1;
        if (!random_member(n, ta, tb, phi, &t, &q) || q >= target) continue;
        memcpy(phi2, phi, sizeof phi);
        /* move ball 1 (index 0) along the circle, re-closing the last two, until q passes the target */
        lo = phi[0], hi = NAN;
        for (j = 1; j <= 720; j++) {
          const double a = phi[0] + 2.0 * M_PI * (double)j / 720.0;
          double av, h;
          v = t;
          phi2[0] = a;
          for (it = 0; it + 2 < n; it++) v -= cexp(I * phi2[it]);
          av = cabs(v);
          if (!(av < 2.0 && av > 0.0)) {
            ok = 0;
            break;
          }
          h = sqrt(1.0 - 0.25 * av * av);
          phi2[n - 2] = carg(0.5 * v + I * v / av * h);
          phi2[n - 1] = carg(0.5 * v - I * v / av * h);
          q2 = qof(n, phi2, &tt);
          if (q2 > target) {
            hi = a;
            break;
          }
          lo = a;
        }
        if (!ok || isnan(hi)) continue;
        for (it = 0; it < 80; it++) {
          const double mid = 0.5 * (lo + hi);
          double av, h;
          phi2[0] = mid;
          v = t;
          for (j = 0; j + 2 < n; j++) v -= cexp(I * phi2[j]);
          av = cabs(v);
          h = sqrt(fmax(0.0, 1.0 - 0.25 * av * av));
          phi2[n - 2] = carg(0.5 * v + I * v / av * h);
          phi2[n - 1] = carg(0.5 * v - I * v / av * h);
          q2 = qof(n, phi2, &tt);
          if (q2 > target) hi = mid;
          else lo = mid;
        }
        if (fabs(q2 - target) > 1e-9 * target) continue;
        if (analyse(&p, w, n, t, phi2, &vv, &rh[sd]) && rh[sd] >= 0) break;
        rh[sd] = -1;
      }
    }
    sides++;
    if (!(rh[0] >= 0 && rh[1] >= 0 && rh[0] != rh[1])) side_bad++;
    printf("     critical u = %.9g kg^2: roots with Re > 0 just below %d, just above %d\n", uc, rh[0], rh[1]);
  }
  snprintf(what, sizeof what, "n = %zu, %g rad/s: members either side of each of %zu critical u differ", n, w, sides);
  CHECK(what, side_bad == 0);
  autobal_rotor_stab_free(s);
}

int main(void) {
  autobal_error err;
  srand(12345);
  enclosure_checks();
  verdict_case(4, 500.0, 1e-4, 0.019);
  verdict_case(5, 500.0, 1e-4, 0.024);
  verdict_case(6, 500.0, 1e-4, 0.029);
  verdict_case(4, 1200.0, 0.018, 0.0195);
  verdict_case(7, 500.0, 1e-4, 0.034);
  verdict_case(8, 500.0, 1e-4, 0.039);
  verdict_case(10, 500.0, 1e-4, 0.049);
  /* eleven balls: refused */
  {
    autobal_rotor_params p = params_n(11);
    autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
    autobal_rotor_unbalance_range ur;
    autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, &o, &err);
    CHECK_STATUS("11 balls, member rule every: refused", autobal_rotor_stab_every_unbalance(s, 1e-3, 5e-3, &ur),
                 AUTOBAL_EUNSUPPORTED);
    CHECK_MSG("... naming unbalance_member = symmetric", autobal_rotor_stab_errmsg(s), "unbalance_member = symmetric");
    autobal_rotor_stab_free(s);
  }
  /* member_boxes out of range: refused naming it */
  {
    const long bad[3] = {-1, 999, 2000000000L};
    size_t k;
    for (k = 0; k < 3; k++) {
      autobal_rotor_params p = params_n(4);
      autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
      autobal_rotor_stab *s;
      o.member_boxes = bad[k];
      s = autobal_rotor_stab_alloc(&p, &o, &err);
      CHECK("member_boxes out of range: refused", s == NULL && err.status == AUTOBAL_EINVAL);
      CHECK_MSG("... naming member_boxes", err.message, "member_boxes");
      autobal_rotor_stab_free(s);
    }
  }
  return check_summary();
}
