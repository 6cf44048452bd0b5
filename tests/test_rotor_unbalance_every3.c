/* test_rotor_unbalance_every3.c: stability for EVERY member and every unbalance of one plane with three
 * identical balls (autobal_rotor_stab_every_unbalance with unbalance_member = EVERY, docs/rotor.md
 * "Every unbalance"), against analyses that use neither the crossing polynomial h nor the closed forms
 * of u_min(t), u_max(t):
 *  - the range of u = |Q|^2 / 4 at 59 single unbalances and over 40 random ranges against brute force:
 *    ball 1 on a grid of 200001 angles over the whole circle, the other two solved from
 *    z2 + z3 = t - z1 (every member is met), |sum m e^{2 i psi}|^2 / 4 summed;
 *  - the verdict against ordinary analyses (method POLY, member 'given') of 400 random members (random
 *    unbalance in the range, random angle of ball 1) per case: each sampled member has the verdict of
 *    the sub-interval of u its u lies in; stable for all exactly when every sample is stable and no
 *    critical u lies inside (cases both ways);
 *  - each critical u: at the middle of each reported piece of unbalances brute-force members have u on
 *    both sides of it, and just outside a piece's end (inside the range) none reaches it; members just
 *    below and above it (ordinary analyses) have different numbers of roots with Re > 0;
 *  - the speed set (autobal_rotor_stab_every_unbalance_speeds) against 200 random members at each of
 *    60 speeds: a speed is in the set exactly when every sample there is stable;
 *  - the map point verdict equals the worst sub-interval verdict; eleven balls are refused with a
 *    message naming unbalance_member = symmetric. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define NPHI 200001

static double bm[11] = {0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05},
              br[11] = {0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1},
              bh[11] = {0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1},
              bpsi[11] = {0.0, 0.3, 0.6, 0.9, 1.2, 1.5, 1.8, 2.1, 2.4, 2.7, 3.0};
static const double M = 0.05, A = 0.05 * 0.1; /* ball mass, m r */

static autobal_rotor_params params(size_t n) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.plane[0].n_balls = n;
  p.plane[0].ball_mass = bm;
  p.plane[0].ball_radius = br;
  p.plane[0].ball_damping = bh;
  p.plane[0].ball_psi = bpsi;
  p.plane[0].ball_rate = NULL;
  return p;
}

/* The member of t with ball 1 at phi from S (normalized: S = t real): 0 if z2 + z3 = t - z1 has no unit
 * solution; else z[3] and q = |sum z^2|^2. */
static int member(double t, double phi, double complex z[3], double *q) {
  const double complex z1 = cexp(I * phi), v = t - z1;
  const double av = cabs(v);
  double complex d, s2;
  if (av > 2.0) return 0;
  d = av > 0.0 ? v / av : 1.0;
  z[0] = z1;
  z[1] = 0.5 * v + I * d * sqrt(fmax(0.0, 1.0 - 0.25 * av * av));
  z[2] = 0.5 * v - I * d * sqrt(fmax(0.0, 1.0 - 0.25 * av * av));
  s2 = z[0] * z[0] + z[1] * z[1] + z[2] * z[2];
  *q = creal(s2 * conj(s2));
  return 1;
}

/* brute force: the range of q over the members of t (ball 1 on nphi angles over the circle) */
static void brute_n(double t, size_t nphi, double *qlo, double *qhi) {
  size_t k;
  *qlo = INFINITY, *qhi = -INFINITY;
  for (k = 0; k < nphi; k++) {
    double complex z[3];
    double q;
    if (!member(t, -M_PI + 2.0 * M_PI * (double)k / (double)(nphi - 1), z, &q)) continue;
    if (q < *qlo) *qlo = q;
    if (q > *qhi) *qhi = q;
  }
}

static void brute(double t, double *qlo, double *qhi) { brute_n(t, NPHI, qlo, qhi); }

/* The ordinary verdict (method POLY, member 'given') and u (kg^2) of the member of t with ball 1 at phi:
 * returns 0 if phi gives no member. */
static int analyse_member_rhp(const autobal_rotor_params *p0, double w, double t, double phi, int *verdict,
                              double *margin, double *u, int *rhp) {
  autobal_rotor_params p = *p0;
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  double complex z[3];
  double q, ang[3];
  autobal_error err;
  autobal_rotor_stab *s;
  size_t k;
  int st;
  if (!member(t, phi, z, &q)) return 0;
  p.omega = w;
  p.plane[0].m0 = t * A / p.plane[0].r0;
  for (k = 0; k < 3; k++) ang[k] = p.plane[0].psi0 + M_PI + carg(z[k]);
  o.member[0].kind = AUTOBAL_ROTOR_MEMBER_GIVEN;
  o.member[0].n_angles = 3;
  o.member[0].angles = ang;
  s = autobal_rotor_stab_alloc(&p, &o, &err);
  if (!s) {
    printf("     alloc: %s\n", err.message);
    return 0;
  }
  st = autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, margin, verdict);
  if (st != AUTOBAL_SUCCESS) printf("     margin: %s\n", autobal_rotor_stab_errmsg(s));
  if (st == AUTOBAL_SUCCESS && rhp) {
    autobal_rotor_stab_result res;
    *rhp = -1;
    if (autobal_rotor_stab_analyze(s, &res) == AUTOBAL_SUCCESS)
      for (*rhp = 0, k = 0; k < res.n_closed; k++) *rhp += res.root_re[k] > 0.0;
  }
  autobal_rotor_stab_free(s);
  {
    double complex qq = 0.0;
    for (k = 0; k < 3; k++) qq += M * cexp(2.0 * I * ang[k]);
    *u = 0.25 * creal(qq * conj(qq));
  }
  return st == AUTOBAL_SUCCESS;
}

static int analyse_member(const autobal_rotor_params *p0, double w, double t, double phi, int *verdict, double *margin,
                          double *u) {
  return analyse_member_rhp(p0, w, t, phi, verdict, margin, u, NULL);
}

/* a random member: t uniform in [ta, tb], phi uniform over its admissible arc */
static void random_member(double ta, double tb, double *t, double *phi) {
  double pe;
  *t = ta + (tb - ta) * ((double)rand() / RAND_MAX);
  pe = *t <= 1.0 ? M_PI : acos((*t * *t - 3.0) / (2.0 * *t));
  *phi = pe * (2.0 * ((double)rand() / RAND_MAX) - 1.0);
}

static void range_checks(autobal_rotor_stab *s) {
  size_t k, bad = 0, far = 0;
  double worst = 0.0;
  char what[240];
  autobal_rotor_unbalance_range ur;
  /* single unbalances */
  for (k = 1; k < 60; k++) {
    const double t = 0.05 * (double)k;
    double qlo, qhi;
    if (autobal_rotor_stab_every_unbalance(s, t * A, t * A, &ur) != AUTOBAL_SUCCESS) {
      printf("     %s\n", autobal_rotor_stab_errmsg(s));
      bad++;
      continue;
    }
    brute(t, &qlo, &qhi);
    qlo *= 0.25 * M * M, qhi *= 0.25 * M * M;
    if (qlo < ur.u_min * (1.0 - 1e-12) - 1e-18 || qhi > ur.u_max * (1.0 + 1e-12) + 1e-18) bad++;
    worst = fmax(worst, fmax(qlo - ur.u_min, ur.u_max - qhi) / (2.25 * M * M));
    if (qlo - ur.u_min > 1e-6 * 2.25 * M * M || ur.u_max - qhi > 1e-6 * 2.25 * M * M) far++;
  }
  snprintf(what, sizeof what, "59 single unbalances t = 0.05..2.95: brute-force members inside [u_min, u_max] (%zu not), "
           "extremes reached to %.2e of 9 m^2/4 (%zu farther than 1e-6)", bad, worst, far);
  CHECK(what, bad == 0 && far == 0);
  /* random ranges */
  bad = far = 0;
  worst = 0.0;
  srand(7);
  for (k = 0; k < 40; k++) {
    double ta = 2.98 * ((double)rand() / RAND_MAX) + 0.01, tb = 2.98 * ((double)rand() / RAND_MAX) + 0.01, lo = INFINITY,
           hi = -INFINITY;
    size_t j;
    if (ta > tb) {
      const double x = ta;
      ta = tb, tb = x;
    }
    if (autobal_rotor_stab_every_unbalance(s, ta * A, tb * A, &ur) != AUTOBAL_SUCCESS) {
      bad++;
      continue;
    }
    for (j = 0; j <= 202; j++) {
      /* 201 equally spaced unbalances, and t = 1 and 2 when inside (the kink of the largest member and the
         zero of the least one: steep there, a grid misses their values by up to 24 x the spacing) */
      const double tj = j <= 200 ? ta + (tb - ta) * (double)j / 200.0 : (j == 201 ? 1.0 : 2.0);
      double qlo, qhi;
      if (!(tj >= ta && tj <= tb)) continue;
      brute_n(tj, 4001, &qlo, &qhi);
      lo = fmin(lo, qlo), hi = fmax(hi, qhi);
    }
    lo *= 0.25 * M * M, hi *= 0.25 * M * M;
    if (lo < ur.u_min * (1.0 - 1e-12) - 1e-18 || hi > ur.u_max * (1.0 + 1e-12) + 1e-18) bad++;
    worst = fmax(worst, fmax(lo - ur.u_min, ur.u_max - hi) / (2.25 * M * M));
    if (lo - ur.u_min > 1e-3 * 2.25 * M * M || ur.u_max - hi > 1e-3 * 2.25 * M * M) far++;
  }
  snprintf(what, sizeof what, "40 random ranges: brute-force members (201 unbalances, 4001 angles each) inside [u_min, u_max] (%zu "
           "not), extremes reached to %.2e of 9 m^2/4", bad, worst);
  CHECK(what, bad == 0 && far == 0);
}

/* one speed and range: the verdict against sampled members, the critical u */
static void verdict_case(autobal_rotor_stab *s, const autobal_rotor_params *p, double w, double ta, double tb,
                         int expect_all) {
  autobal_rotor_unbalance_range ur;
  size_t k, j, bad = 0, outside = 0, nunst = 0, nsamp = 0;
  int st, all = 1;
  char what[320];
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  st = autobal_rotor_stab_every_unbalance(s, ta * A, tb * A, &ur);
  snprintf(what, sizeof what, "omega %g, t in [%g, %g]: every member, every unbalance", w, ta, tb);
  CHECK_STATUS(what, st, AUTOBAL_SUCCESS);
  if (st != AUTOBAL_SUCCESS) {
    printf("     %s\n", autobal_rotor_stab_errmsg(s));
    return;
  }
  printf("     u in [%.9g, %.9g] kg^2, %zu critical u:", ur.u_min, ur.u_max, ur.n_ucrit);
  for (k = 0; k < ur.n_ucrit; k++) printf(" %.9g", ur.u_crit[k]);
  printf("; all stable %d; %zu pieces; %zu evaluations\n", ur.all_stable, ur.n_upiece, ur.evaluations);
  CHECK("member rule and n_balls reported, no missed change, one s sub-interval",
        ur.member_rule == AUTOBAL_ROTOR_UNBALANCE_EVERY && ur.n_balls == 3 && ur.n_missed == 0 && ur.n_sub == 1 &&
            ur.n_crit == 0 && ur.n_usub == ur.n_ucrit + 1);
  for (k = 0; k < 400; k++) {
    double t, phi, u, mg;
    int v, near = 0;
    random_member(ta, tb, &t, &phi);
    if (!analyse_member(p, w, t, phi, &v, &mg, &u)) continue;
    nsamp++;
    if (v != AUTOBAL_VERDICT_STABLE) all = 0;
    if (v == AUTOBAL_VERDICT_UNSTABLE) nunst++;
    if (!(u >= ur.u_min * (1.0 - 1e-12) - 1e-18 && u <= ur.u_max * (1.0 + 1e-12) + 1e-18)) outside++;
    for (j = 0; j < ur.n_ucrit; j++)
      if (fabs(u - ur.u_crit[j]) <= 1e-7 * ur.u_max) near = 1;
    if (near) continue;
    for (j = 0; j < ur.n_usub; j++)
      if (u >= ur.usub_lo[j] && u <= ur.usub_hi[j] && v != ur.usub_verdict[j]) bad++;
  }
  snprintf(what, sizeof what, "%zu sampled members (%zu unstable): each has its u sub-interval's verdict (%zu disagree), "
           "u inside the range (%zu not)", nsamp, nunst, bad, outside);
  CHECK(what, nsamp >= 390 && bad == 0 && outside == 0);
  snprintf(what, sizeof what, "stable for all (%d) == every sample stable (%d) and no critical u (%zu); expected %d",
           ur.all_stable, all, ur.n_ucrit, expect_all);
  CHECK(what, ur.all_stable == (all && ur.n_ucrit == 0) && ur.all_stable == expect_all);
  CHECK("the one s sub-interval carries the worst verdict",
        ur.sub_verdict[0] == (nunst > 0 ? AUTOBAL_VERDICT_UNSTABLE : ur.sub_verdict[0]));
  /* critical u: pieces and the change of verdict */
  for (k = 0; k < ur.n_ucrit; k++) {
    const double qc = 4.0 * ur.u_crit[k] / (M * M);
    size_t pbad = 0, np = 0;
    double tm = NAN;
    for (j = 0; j < ur.n_upiece; j++) {
      double tl, th, qlo, qhi;
      if (ur.upiece_crit[j] != k) continue;
      np++;
      tl = ur.upiece_lo[j] / A, th = ur.upiece_hi[j] / A;
      brute(0.5 * (tl + th), &qlo, &qhi);
      if (!(qlo <= qc && qc <= qhi)) pbad++;
      if (isnan(tm) || th - tl > 0.0) tm = 0.5 * (tl + th);
      if (tl > ta + 1e-3) {
        brute(tl - 1e-4, &qlo, &qhi);
        if (qlo <= qc && qc <= qhi) pbad++;
      }
      if (th < tb - 1e-3) {
        brute(th + 1e-4, &qlo, &qhi);
        if (qlo <= qc && qc <= qhi) pbad++;
      }
    }
    snprintf(what, sizeof what, "u* = %.9g kg^2: %zu piece(s) of unbalances; brute force meets u* inside each and not "
             "1e-4 outside (%zu wrong)", ur.u_crit[k], np, pbad);
    CHECK(what, np >= 1 && pbad == 0);
    if (!isnan(tm)) {
      /* members of tm just below and just above u*: opposite verdicts */
      double plo = NAN, phi_ = NAN, dlo = INFINITY, dhi = INFINITY;
      int vlo = 9, vhi = 9, nlo = -1, nhi = -1;
      size_t q;
      for (q = 0; q < NPHI; q++) {
        const double ph = M_PI * (double)q / (double)(NPHI - 1);
        double complex z[3];
        double qq;
        if (!member(tm, ph, z, &qq)) continue;
        if (qq < qc && qc - qq < dlo && qc - qq > 1e-6 * qc) dlo = qc - qq, plo = ph;
        if (qq > qc && qq - qc < dhi && qq - qc > 1e-6 * qc) dhi = qq - qc, phi_ = ph;
      }
      if (!isnan(plo) && !isnan(phi_)) {
        double u1, u2, m1, m2;
        analyse_member_rhp(p, w, tm, plo, &vlo, &m1, &u1, &nlo);
        analyse_member_rhp(p, w, tm, phi_, &vhi, &m2, &u2, &nhi);
      }
      snprintf(what, sizeof what, "u* = %.9g: members just below and above it (ordinary analyses) have different "
               "numbers of roots with Re > 0 (%d, %d)", ur.u_crit[k], nlo, nhi);
      CHECK(what, nlo >= 0 && nhi >= 0 && nlo != nhi);
    }
  }
}

static void speeds_case(autobal_rotor_stab *s, const autobal_rotor_params *p, double ta, double tb) {
  autobal_rotor_crit cr;
  size_t k, j, bad = 0, skipped = 0;
  char what[240];
  int st = autobal_rotor_stab_every_unbalance_speeds(s, ta * A, tb * A, 100.0, 1500.0, 200, 1e-10, &cr);
  CHECK_STATUS("speed set for every member", st, AUTOBAL_SUCCESS);
  printf("     t in [%g, %g]: %zu stable interval(s):", ta, tb, cr.n_stable);
  for (k = 0; k < cr.n_stable; k++) printf(" [%.7g, %.7g]", cr.stable_lo[k], cr.stable_hi[k]);
  printf("\n");
  srand(11);
  for (k = 0; k < 60; k++) {
    const double w = 100.0 + 1400.0 * ((double)k + 0.5) / 60.0;
    int in = 0, all = 1, near = 0;
    for (j = 0; j < cr.n_stable; j++) {
      if (w >= cr.stable_lo[j] && w <= cr.stable_hi[j]) in = 1;
      if (fabs(w - cr.stable_lo[j]) < 1.0 || fabs(w - cr.stable_hi[j]) < 1.0) near = 1;
    }
    if (near) {
      skipped++;
      continue;
    }
    for (j = 0; j < 200 && all; j++) {
      double t, phi, u, mg;
      int v;
      random_member(ta, tb, &t, &phi);
      if (analyse_member(p, w, t, phi, &v, &mg, &u) && v != AUTOBAL_VERDICT_STABLE) all = 0;
    }
    if (in != all) {
      bad++;
      printf("     omega %g: in the set %d, every sample stable %d\n", w, in, all);
    }
  }
  snprintf(what, sizeof what, "60 speeds: in the set exactly when 200 sampled members are all stable (%zu disagree, "
           "%zu within 1 rad/s of an end skipped)", bad, skipped);
  CHECK(what, bad == 0);
}

int main(void) {
  autobal_rotor_params p = params(3);
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_error err;
  autobal_rotor_stab *s;
  CHECK("the default member rule is EVERY", o.unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY);
  p.omega = 500.0;
  s = autobal_rotor_stab_alloc(&p, &o, &err);
  if (!s) {
    printf("alloc: %s\n", err.message);
    return 1;
  }
  range_checks(s);
  verdict_case(s, &p, 500.0, 0.02, 2.8, 0);
  verdict_case(s, &p, 300.0, 0.5, 1.5, 0);
  verdict_case(s, &p, 500.0, 2.6, 2.9, 1);
  verdict_case(s, &p, 1200.0, 2.6, 2.9, 1);
  verdict_case(s, &p, 460.0, 2.5, 2.98, 0);
  verdict_case(s, &p, 1200.0, 1.9, 2.2, 0);
  speeds_case(s, &p, 2.6, 2.9);
  speeds_case(s, &p, 2.8, 2.98);
  /* the map's point verdict: the worst sub-interval verdict (MARGINAL when a critical u touches only) */
  {
    const double wv[3] = {300.0, 500.0, 1200.0}, hv[2] = {0.1, 0.3};
    double mg[6];
    int vd[6], ok = 1;
    size_t i, j;
    int st = autobal_rotor_stab_map_every_unbalance(&p, &o, AUTOBAL_ROTOR_PARAM_OMEGA, wv, 3,
                                                    AUTOBAL_ROTOR_PARAM_BALL_DAMPING, hv, 2, 2.0 * A, 2.9 * A, 2, mg,
                                                    vd, &err);
    CHECK_STATUS("map for every member", st, AUTOBAL_SUCCESS);
    for (i = 0; i < 3; i++)
      for (j = 0; j < 2; j++) {
        autobal_rotor_unbalance_range ur;
        int worst = AUTOBAL_VERDICT_STABLE;
        size_t k;
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, wv[i]);
        autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, hv[j]);
        if (autobal_rotor_stab_every_unbalance(s, 2.0 * A, 2.9 * A, &ur) != AUTOBAL_SUCCESS) {
          ok = 0;
          continue;
        }
        for (k = 0; k < ur.n_usub; k++)
          if (ur.usub_verdict[k] < worst) worst = ur.usub_verdict[k];
        if (!ur.all_stable && worst == AUTOBAL_VERDICT_STABLE) worst = AUTOBAL_VERDICT_MARGINAL;
        printf("     map omega %g, h %g: %d (direct %d)\n", wv[i], hv[j], vd[i * 2 + j], worst);
        if (vd[i * 2 + j] != worst) ok = 0;
      }
    CHECK("map points = the worst u sub-interval verdict of direct calls", ok);
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, 0.1);
  }
  autobal_rotor_stab_free(s);
  /* eleven balls: refused, naming the rule that works (four to ten: test_rotor_unbalance_every4.c) */
  {
    autobal_rotor_params p4 = params(11);
    autobal_rotor_unbalance_range ur;
    s = autobal_rotor_stab_alloc(&p4, &o, &err);
    CHECK_STATUS("11 balls, member rule every: refused", autobal_rotor_stab_every_unbalance(s, 1e-3, 5e-3, &ur),
                 AUTOBAL_EUNSUPPORTED);
    CHECK_MSG("... naming unbalance_member = symmetric", autobal_rotor_stab_errmsg(s), "unbalance_member = symmetric");
    CHECK_MSG("... saying 3 to 10 balls work", autobal_rotor_stab_errmsg(s), "3 to 10 balls");
    autobal_rotor_stab_free(s);
  }
  return check_summary();
}
