/* test_rotor_unbalance_n.c: stability for every unbalance in a range with n >= 3 identical balls in
 * one plane, member rule SYMMETRIC (autobal_rotor_stab_every_unbalance, docs/rotor.md "Every
 * unbalance"), for n = 3, 4, 8 at several speeds, against analyses that do not use the crossing
 * polynomial h(z) nor the Chebyshev formulas:
 *  - 2001 sampled unbalances analysed one by one (the ordinary verdict of the symmetric member) have
 *    the verdict of their sub-interval, and "stable for all" holds exactly when every sample is
 *    stable and no critical unbalance lies inside;
 *  - at every critical unbalance, the polynomial solver puts a root of Delta on the imaginary axis and
 *    the number of roots with Re > 0 changes across it;
 *  - the range [u_min, u_max] of u = |Q|^2 / 4 against |sum m e^{2 i psi_i}|^2 / 4 summed from the
 *    member's angles (autobal_rotor_member_angles) at the samples: every sample inside, the extremes
 *    approached;
 *  - the full model's eigenvalues (every ball angle, no closure) at the members of the extreme u
 *    agree with the closed roots plus the family roots (full_mismatch) and give the same verdict;
 *  - the refusals: unequal balls (naming the keys), the member rule EVERY for n >= 4; two balls give
 *    the same bits with either member rule. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

#define NS 2001
#define NMAX 11

static double margins[NS], sv[NS];
static int verdicts[NS];
static double bm[NMAX], br[NMAX], bh[NMAX], bpsi[NMAX];

static autobal_rotor_params params_n(size_t n) {
  autobal_rotor_params p = autobal_rotor_params_default();
  size_t i;
  for (i = 0; i < n; i++) bm[i] = 0.05, br[i] = 0.1, bh[i] = 0.1, bpsi[i] = 0.3 * (double)i;
  p.plane[0].n_balls = n;
  p.plane[0].ball_mass = bm;
  p.plane[0].ball_radius = br;
  p.plane[0].ball_damping = bh;
  p.plane[0].ball_psi = bpsi;
  p.plane[0].ball_rate = NULL;
  return p;
}

/* u = |sum_i m_i e^{2 i psi_i}|^2 / 4 of the symmetric member at m0 (kg^2), from its angles. */
static double u_member(const autobal_rotor_params *p, double m0) {
  autobal_rotor_plane pl = p->plane[0];
  autobal_rotor_member mem = {AUTOBAL_ROTOR_MEMBER_SYMMETRIC, 0, NULL};
  double psi[NMAX];
  double complex q = 0.0;
  size_t i;
  pl.m0 = m0;
  if (autobal_rotor_member_angles(&pl, &mem, psi, pl.n_balls, NULL) != AUTOBAL_SUCCESS) return NAN;
  for (i = 0; i < pl.n_balls; i++) q += pl.ball_mass[i] * cexp(2.0 * I * psi[i]);
  return 0.25 * creal(q * conj(q));
}

static int rhp_count(autobal_rotor_stab *s, double m0) {
  autobal_rotor_stab_result res;
  size_t j;
  int n = 0;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0);
  if (autobal_rotor_stab_analyze(s, &res) != AUTOBAL_SUCCESS) return -1;
  for (j = 0; j + 1 < res.n_poly; j++) n += res.root_re[j] > 0.0;
  return n;
}

static void one_case(autobal_rotor_stab *s, const autobal_rotor_params *p, double w, double lo, double hi) {
  autobal_rotor_unbalance_range ur;
  const double r0 = p->plane[0].r0;
  double umin = INFINITY, umax = -INFINITY, m0_before, kmin = 0, kmax = 0;
  size_t k, j, bad = 0, outside = 0;
  int all = 1, st;
  char what[240];
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  m0_before = autobal_rotor_stab_params(s)->plane[0].m0;
  st = autobal_rotor_stab_every_unbalance(s, lo, hi, &ur);
  snprintf(what, sizeof what, "n = %zu, omega %g, m0 r0 in [%g, %g]: every_unbalance", p->plane[0].n_balls, w, lo, hi);
  CHECK_STATUS(what, st, AUTOBAL_SUCCESS);
  if (st != AUTOBAL_SUCCESS) {
    printf("     %s\n", autobal_rotor_stab_errmsg(s));
    return;
  }
  CHECK("m0 restored bitwise", autobal_rotor_stab_params(s)->plane[0].m0 == m0_before);
  printf("     u in [%.9g, %.9g] kg^2, %zu critical unbalance(s):", ur.u_min, ur.u_max, ur.n_crit);
  for (k = 0; k < ur.n_crit; k++) printf(" %.9g", ur.s_crit[k]);
  printf("; all stable %d, %zu evaluations\n", ur.all_stable, ur.evaluations);
  CHECK("n_balls and member rule reported", ur.n_balls == p->plane[0].n_balls &&
                                                ur.member_rule == AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC);
  CHECK("no verdict change missed by the crossing polynomial", ur.n_missed == 0);
  for (k = 0; k < NS; k++) sv[k] = (lo + (hi - lo) * (double)k / (double)(NS - 1)) / r0;
  CHECK_STATUS("dense sampling", autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv, NS, margins, verdicts),
               AUTOBAL_SUCCESS);
  for (k = 0; k < NS; k++) {
    const double x = sv[k] * r0, u = u_member(p, sv[k]);
    int near = 0;
    if (!(u >= ur.u_min * (1.0 - 1e-12) - 1e-18 && u <= ur.u_max * (1.0 + 1e-12) + 1e-18)) outside++;
    if (u < umin) umin = u, kmin = sv[k];
    if (u > umax) umax = u, kmax = sv[k];
    for (j = 0; j < ur.n_crit; j++)
      if (fabs(x - ur.s_crit[j]) <= 1e-7 * (hi - lo)) near = 1;
    if (verdicts[k] != AUTOBAL_VERDICT_STABLE) all = 0;
    if (near) continue;
    for (j = 0; j < ur.n_sub; j++)
      if (x >= ur.sub_lo[j] && x <= ur.sub_hi[j] && verdicts[k] != ur.sub_verdict[j]) bad++;
  }
  snprintf(what, sizeof what, "every sample has its sub-interval's verdict (%zu disagree)", bad);
  CHECK(what, bad == 0);
  snprintf(what, sizeof what, "stable for all (%d) == every sample stable (%d) and no critical value inside (%zu)",
           ur.all_stable, all, ur.n_crit);
  CHECK(what, ur.all_stable == (all && ur.n_crit == 0));
  snprintf(what, sizeof what, "every sampled u inside [u_min, u_max] (%zu outside)", outside);
  CHECK(what, outside == 0);
  snprintf(what, sizeof what, "the sampled extremes approach u_min (%.9g vs %.9g) and u_max (%.9g vs %.9g)", umin,
           ur.u_min, umax, ur.u_max);
  CHECK(what, umin - ur.u_min <= 1e-3 * ur.u_max && ur.u_max - umax <= 1e-3 * ur.u_max);
  /* the full model at the members of the extreme u: its eigenvalues are the closed roots plus the family */
  for (k = 0; k < 2; k++) {
    autobal_rotor_stab_result res;
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, k == 0 ? kmin : kmax);
    st = autobal_rotor_stab_analyze(s, &res);
    snprintf(what, sizeof what, "full model at the member of %s u: eigenvalues = closed roots + family (%.2e), "
             "margins %.9g, %.9g", k == 0 ? "the least" : "the largest", res.full_mismatch, res.full_margin, res.closed_margin);
    CHECK(what, st == AUTOBAL_SUCCESS && res.n_full > 0 && res.full_mismatch < 1e-6 &&
                    fabs(res.full_margin - res.closed_margin) <= 1e-6 * fmax(1.0, fabs(res.closed_margin)));
  }
  for (k = 0; k < ur.n_crit; k++) {
    autobal_rotor_stab_result res;
    double mr = INFINITY, big = 1.0;
    int nlo, nhi;
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, ur.s_crit[k] / r0);
    if (autobal_rotor_stab_analyze(s, &res) == AUTOBAL_SUCCESS)
      for (j = 0; j + 1 < res.n_poly; j++) {
        mr = fmin(mr, fabs(res.root_re[j]));
        big = fmax(big, hypot(res.root_re[j], res.root_im[j]));
      }
    snprintf(what, sizeof what, "s* = %.9g kg m: a root of Delta on the axis (min |Re| / max |root|)", ur.s_crit[k]);
    CHECK_CLOSE(what, mr / big, 0.0, 0.0, 1e-8);
    nlo = rhp_count(s, ur.s_crit[k] * (1.0 - 1e-6) / r0);
    nhi = rhp_count(s, ur.s_crit[k] * (1.0 + 1e-6) / r0);
    snprintf(what, sizeof what, "s* = %.9g: the number of roots with Re > 0 changes across it (%d, %d)", ur.s_crit[k],
             nlo, nhi);
    CHECK(what, nlo != nhi && nlo >= 0 && nhi >= 0);
  }
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, m0_before);
}

int main(void) {
  static const size_t ns[] = {3, 4, 8};
  static const double speeds[] = {300.0, 500.0, 1200.0};
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_error err;
  size_t a, k;
  o.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
  o.member[0].kind = AUTOBAL_ROTOR_MEMBER_SYMMETRIC;
  for (a = 0; a < 3; a++) {
    const autobal_rotor_params p = params_n(ns[a]);
    const double amr = 0.05 * 0.1 * (double)ns[a];
    autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, &o, &err);
    if (!s) {
      printf("alloc: %s\n", err.message);
      return 1;
    }
    for (k = 0; k < 3; k++) {
      one_case(s, &p, speeds[k], 1e-4, 0.97 * amr);
      one_case(s, &p, speeds[k], 0.2 * amr, 0.5 * amr);
    }
    autobal_rotor_stab_free(s);
  }
  /* refusals */
  {
    autobal_rotor_params p = params_n(11);
    autobal_rotor_unbalance_range ur;
    autobal_rotor_stab *s;
    autobal_rotor_stab_options oe = autobal_rotor_stab_options_default();
    s = autobal_rotor_stab_alloc(&p, &oe, &err);
    CHECK_STATUS("11 balls, member rule every: refused", autobal_rotor_stab_every_unbalance(s, 1e-3, 5e-3, &ur),
                 AUTOBAL_EUNSUPPORTED);
    CHECK_MSG("... naming the key", autobal_rotor_stab_errmsg(s), "unbalance_member = symmetric");
    autobal_rotor_stab_free(s);
    p = params_n(3);
    bm[2] = 0.06;
    s = autobal_rotor_stab_alloc(&p, &o, &err);
    CHECK_STATUS("3 unequal balls: refused", autobal_rotor_stab_every_unbalance(s, 1e-3, 5e-3, &ur), AUTOBAL_EUNSUPPORTED);
    CHECK_MSG("... naming the keys", autobal_rotor_stab_errmsg(s), "plane1.ball_mass");
    autobal_rotor_stab_free(s);
    bm[2] = 0.05;
    s = autobal_rotor_stab_alloc(&p, &o, &err);
    CHECK_STATUS("3 balls, range beyond n m r: refused", autobal_rotor_stab_every_unbalance(s, 1e-3, 0.0151, &ur),
                 AUTOBAL_EINVAL);
    printf("     %s\n", autobal_rotor_stab_errmsg(s));
    autobal_rotor_stab_free(s);
  }
  /* two balls: the member rule changes no bit */
  {
    autobal_rotor_params p = autobal_rotor_params_default();
    autobal_rotor_unbalance_range u1, u2;
    autobal_rotor_stab *s1 = autobal_rotor_stab_alloc(&p, NULL, &err), *s2 = autobal_rotor_stab_alloc(&p, &o, &err);
    CHECK_STATUS("two balls, rule every", autobal_rotor_stab_every_unbalance(s1, 1e-4, 9.5e-3, &u1), AUTOBAL_SUCCESS);
    CHECK_STATUS("two balls, rule symmetric", autobal_rotor_stab_every_unbalance(s2, 1e-4, 9.5e-3, &u2), AUTOBAL_SUCCESS);
    u1.member_rule = u2.member_rule;
    CHECK("two balls: the same bits with either rule", memcmp(&u1, &u2, sizeof u1) == 0);
    CHECK("two balls: no u range", isnan(u1.u_min) && isnan(u1.u_max) && u1.n_balls == 2);
    autobal_rotor_stab_free(s1);
    autobal_rotor_stab_free(s2);
  }
  return check_summary();
}
