/* test_rotor_design_every.c: the every-member certification of the n >= 3 designs of `autobal rotor
 * design` (docs/rotor.md "Design", "Number of balls"; options.unbalance_member = EVERY) and its building
 * block autobal_rotor_stab_margin_u_range, against computations that use neither the enclosure of u nor
 * the crossing polynomial:
 *  - random members: n - 2 ball angles drawn at random, the last two placed by the closed form for two
 *    balls (member FREE) for a random m0 r0 of the range, analysed one by one by the CLOSED method (the
 *    closed first-order system's eigenvalues: no crossing polynomial, no enclosure) at every speed of the
 *    re-check grid: every certified design's members all have every root Re lambda < -margin and
 *    < -member_margin_certified (the certified margin over every member), and their
 *    u = m^2 |sum e^{2 i psi}|^2 / 4 lies in the design's enclosure;
 *  - a constructed case (default rotor, 4 balls of 50 g on 100 mm, h = 0.3 kg/s, 7000..9500 g mm,
 *    700..1100 rad/s): the symmetric fan is stable with margin at every speed (the fan members checked
 *    one by one), so the symmetric search calls the design feasible; but the member of two right-angled
 *    pairs (z, i z, w, i w: Q = sum e^{2 i psi} = 0 exactly) is unstable (CLOSED, a root with
 *    Re lambda > 0), so the certification must reject it: members_certified = -1, feasible = 0.  This
 *    check fails if the certification is skipped;
 *  - 1 and 2 threads give the same certification bit for bit;
 *  - rejected three-ball designs whose range holds t = m0 r0 / (m r) = 1: a member near the line (two balls
 *    together, one opposite) analysed by FULL (every ball angle) has a root right of -margin;
 *  - autobal_rotor_stab_margin_u_range at that machine: not stable over u in [0, u_max] (the Q = 0
 *    member above is unstable), and every random member whose u lies in a range it calls stable with
 *    margin delta has every root left of -delta (delta = 0 and 0.3). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"
#include "rotor_nballs.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A reproducible uniform number in [0, 1) (LCG; no dependence on the C library's rand). */
static unsigned long long rng_state = 88172645463325252ULL;
static double urand(void) {
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

/* A handle for one member: m0 r0 = s, the angles of all n balls given (member GIVEN); NULL if they do not
 * balance.  q: |sum e^{2 i psi}|^2 of the member. */
static autobal_rotor_stab *member_handle(autobal_rotor_params p, double s, const double *ang, size_t n, double *q) {
  autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
  double re = 0.0, im = 0.0;
  size_t k;
  p.plane[0].m0 = s / p.plane[0].r0;
  so.member[0].kind = AUTOBAL_ROTOR_MEMBER_GIVEN;
  so.member[0].n_angles = n;
  so.member[0].angles = ang;
  for (k = 0; k < n; k++) re += cos(2.0 * ang[k]), im += sin(2.0 * ang[k]);
  *q = re * re + im * im;
  return autobal_rotor_stab_alloc(&p, &so, NULL);
}

/* A random member of m0 r0 = s (unbalance at psi0): balls 3..n at random angles, balls 1, 2 by the closed
 * form for two balls: m r (e^{i a1} + e^{i a2}) = W = -(s e^{i psi0} + m r sum_{k>=3} e^{i a_k}), which needs
 * |W| <= 2 m r (redrawn otherwise).  Returns 0 on success. */
static int random_member(size_t n, double mr, double s, double psi0, double *ang) {
  int tries;
  for (tries = 0; tries < 10000; tries++) {
    double wr = -s * cos(psi0), wi = -s * sin(psi0), aw, c;
    size_t k;
    for (k = 2; k < n; k++) {
      ang[k] = 2.0 * M_PI * urand();
      wr -= mr * cos(ang[k]);
      wi -= mr * sin(ang[k]);
    }
    aw = hypot(wr, wi);
    if (!(aw <= 2.0 * mr) || aw < 1e-9 * mr) continue;
    c = acos(aw / (2.0 * mr));
    ang[0] = atan2(wi, wr) - c;
    ang[1] = atan2(wi, wr) + c;
    return 0;
  }
  return 1;
}

/* max Re lambda of the closed system (CLOSED: eigenvalues, no crossing polynomial) of a member handle. */
static double closed_margin(autobal_rotor_stab *s, double w) {
  double mg = NAN;
  int v;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  if (autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_CLOSED, &mg, &v) != AUTOBAL_SUCCESS) return NAN;
  return mg;
}

/* The member of two right-angled pairs for n = 4: a, a + pi/2, b, b + pi/2 with Q = 0, |S| = t (in units of
 * m r), S turned against the unbalance at psi0. */
static void pairs_member(double t, double psi0, double *ang) {
  /* S = (1 + i)(e^{i a} + e^{i b}); |e^{i a} + e^{i b}| = 2 cos(g/2), g = a - b */
  const double g = 2.0 * acos(t / (2.0 * sqrt(2.0)));
  double a = 0.0, b = -g, sr, si, turn;
  size_t k;
  sr = cos(a) - sin(a) + cos(b) - sin(b);
  si = sin(a) + cos(a) + sin(b) + cos(b);
  turn = (psi0 + M_PI) - atan2(si, sr);
  a += turn;
  b += turn;
  ang[0] = a;
  ang[1] = a + 0.5 * M_PI;
  ang[2] = b;
  ang[3] = b + 0.5 * M_PI;
  for (k = 0; k < 4; k++) ang[k] = remainder(ang[k], 2.0 * M_PI);
}

static autobal_study_rotor_design_options fixed_opts(void) {
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  o.omega_min = 700.0;
  o.omega_max = 1100.0;
  o.n_omega = 5;
  o.n_verify = 9;
  o.unbalance_min = 7000e-6;
  o.unbalance_max = 9500e-6;
  o.margin = 0.1;
  o.mass_min = o.mass_max = 0.05;
  o.n_mass = 1;
  o.radius_min = 0.09;
  o.radius_max = 0.11;
  o.n_radius = 3;
  o.damping_min = o.damping_max = 0.3;
  o.n_damping = 1;
  o.n_best = 1;
  o.n_starts = 0;
  o.n_balls_min = o.n_balls_max = 4;
  o.threads = 1;
  return o;
}

static void test_constructed(void) {
  double m[4], r[4], h[4], psi[4], rate[4];
  autobal_rotor_params p = machine(4, m, r, h, psi, rate, 0.05, 0.1, 0.3);
  autobal_study_rotor_design_options o = fixed_opts();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  size_t k, j, fan_bad = 0, unstable_pairs = 0, pairs_bad = 0;
  int st;
  const autobal_rotor_design *d;
  /* independent premises: the fan (the symmetric member of the handle's default) is stable with margin at
     every re-check speed over 41 unbalances; the Q = 0 member of two right-angled pairs is unstable */
  {
    autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
    autobal_rotor_stab *s;
    double ang[4], q;
    for (j = 0; j < 41; j++) {
      const double sv = o.unbalance_min + (o.unbalance_max - o.unbalance_min) * (double)j / 40.0;
      autobal_rotor_params pp = p;
      pp.plane[0].m0 = sv / p.plane[0].r0;
      so.member[0].kind = AUTOBAL_ROTOR_MEMBER_SYMMETRIC;
      s = autobal_rotor_stab_alloc(&pp, &so, NULL);
      if (!s) {
        fan_bad++;
        continue;
      }
      for (k = 0; k < o.n_verify; k++) {
        const double w = o.omega_min + (o.omega_max - o.omega_min) * (double)k / (double)(o.n_verify - 1);
        const double mg = closed_margin(s, w);
        if (!(mg < -o.margin)) fan_bad++;
      }
      autobal_rotor_stab_free(s);
      pairs_member(sv / (0.05 * 0.1), p.plane[0].psi0, ang);
      s = member_handle(p, sv, ang, 4, &q);
      if (!s || !(q < 1e-20)) pairs_bad++;
      if (!s) continue;
      for (k = 0; k < o.n_verify; k++) {
        const double w = o.omega_min + (o.omega_max - o.omega_min) * (double)k / (double)(o.n_verify - 1);
        if (closed_margin(s, w) > 0.0) unstable_pairs++;
      }
      autobal_rotor_stab_free(s);
    }
    CHECK("the pairs members balance and have Q = 0", pairs_bad == 0);
    CHECK("premise: the symmetric fan is stable with the margin at every re-check speed (41 unbalances, CLOSED)",
          fan_bad == 0);
    printf("  Q = 0 members unstable at %zu of %zu (unbalance, speed) points\n", unstable_pairs, (size_t)41 * o.n_verify);
    CHECK("premise: the Q = 0 member (two right-angled pairs) is unstable at some speed (CLOSED)", unstable_pairs > 0);
  }
  /* the symmetric search accepts it */
  o.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
  st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("design, symmetric members", st, AUTOBAL_SUCCESS);
  if (st == AUTOBAL_SUCCESS && S.n_designs > 0) {
    d = &S.designs[0];
    printf("  symmetric: m %.4g r %.4g h %.4g rho %.5g feasible %d recheck %d certified %d\n", d->mass, d->radius,
           d->damping, d->margin, d->feasible, d->recheck, d->members_certified);
    CHECK("symmetric: the fan's design is feasible", d->feasible == 1 && d->recheck == 1);
    CHECK("symmetric: no certification run", d->members_certified == 0);
  } else
    CHECK("symmetric: a design", 0);
  autobal_study_rotor_design_summary_free(&S);
  /* every member: rejected */
  o.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_EVERY;
  st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("design, every member", st, AUTOBAL_SUCCESS);
  if (st == AUTOBAL_SUCCESS && S.n_designs > 0) {
    d = &S.designs[0];
    printf("  every: m %.4g r %.4g h %.4g rho %.5g feasible %d certified %d at %.6g rad/s u %.6g kg^2 (enclosure "
           "[%.6g, %.6g])\n",
           d->mass, d->radius, d->damping, d->margin, d->feasible, d->members_certified, d->member_found_omega,
           d->member_found_u, d->member_u[0], d->member_u[1]);
    CHECK("every member: the certification rejects the design (a member not stable found)",
          d->members_certified == -1 && d->feasible == 0);
    CHECK("every member: the violation at a re-check speed", d->member_found_omega >= o.omega_min &&
                                                               d->member_found_omega <= o.omega_max);
    CHECK("every member: u found inside the enclosure, which reaches Q = 0",
          d->member_found_u >= d->member_u[0] && d->member_found_u <= d->member_u[1] && d->member_u[0] <= 1e-12);
    CHECK("every member: the config comment says symmetric members only",
          S.best_config && strstr(S.best_config, "symmetric members of the family only") &&
              strstr(S.best_config, "not stable"));
  } else
    CHECK("every: a design", 0);
  autobal_study_rotor_design_summary_free(&S);
}

/* u_range at the constructed machine, 800 rad/s. */
static void test_u_range(void) {
  double m[4], r[4], h[4], psi[4], rate[4];
  autobal_rotor_params p = machine(4, m, r, h, psi, rate, 0.05, 0.1, 0.3);
  autobal_rotor_stab *s;
  autobal_rotor_margin_u_range mu;
  const double w = 800.0, mr = 0.005, um = 0.25 * 0.05 * 0.05, deltas[2] = {0.0, 0.3};
  const double ranges[3][2] = {{0.0, 16.0 * um * 0.99}, {0.001, 0.008}, {0.003, 0.006}};
  size_t a, b, j, nin[3][2] = {{0}}, bad = 0;
  int stab[3][2];
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  CHECK("handle", s != NULL);
  if (!s) return;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  for (a = 0; a < 3; a++)
    for (b = 0; b < 2; b++) {
      CHECK_STATUS("u range", autobal_rotor_stab_margin_u_range(s, deltas[b], ranges[a][0], ranges[a][1], &mu),
                   AUTOBAL_SUCCESS);
      stab[a][b] = mu.all_stable;
      printf("  u range [%.5g, %.5g] delta %g: all_stable %d u_found %.6g, %zu critical u\n", ranges[a][0], ranges[a][1],
             deltas[b], mu.all_stable, mu.u_found, mu.n_crit);
    }
  /* the Q = 0 member (u = 0) is unstable there (CLOSED), so [0, ...] cannot be stable */
  {
    double ang[4], q, mg;
    autobal_rotor_stab *sm;
    pairs_member(1.6, p.plane[0].psi0, ang);
    sm = member_handle(p, 1.6 * mr, ang, 4, &q);
    mg = sm ? closed_margin(sm, w) : NAN;
    printf("  Q = 0 member at 800 rad/s: CLOSED margin %.6g\n", mg);
    CHECK("the Q = 0 member is unstable (premise)", mg > 0.0);
    CHECK("u range from 0: not stable (delta 0 and 0.3)", stab[0][0] == 0 && stab[0][1] == 0);
    autobal_rotor_stab_free(sm);
  }
  /* not vacuous: some range is called stable (the random members below then test it) */
  CHECK("some u range called stable", stab[1][0] + stab[1][1] + stab[2][0] + stab[2][1] > 0);
  /* random members: those with u inside a range called stable have every root left of -delta */
  for (j = 0; j < 1500; j++) {
    double ang[4], q, mg, u;
    const double sv = mr * (0.2 + 3.6 * urand());
    autobal_rotor_stab *sm;
    if (random_member(4, mr, sv, p.plane[0].psi0, ang)) continue;
    sm = member_handle(p, sv, ang, 4, &q);
    if (!sm) continue;
    u = um * q;
    mg = closed_margin(sm, w);
    autobal_rotor_stab_free(sm);
    for (a = 0; a < 3; a++)
      for (b = 0; b < 2; b++)
        if (u >= ranges[a][0] && u <= ranges[a][1]) {
          nin[a][b]++;
          if (stab[a][b] == 1 && !(mg < -deltas[b])) {
            bad++;
            printf("  member u %.6g margin %.6g in a range called stable with delta %g\n", u, mg, deltas[b]);
          }
        }
  }
  printf("  random members per range: %zu %zu %zu\n", nin[0][0], nin[1][0], nin[2][0]);
  CHECK("random members in the ranges", nin[1][0] > 100 && nin[2][0] > 50);
  CHECK("every random member in a range called stable with margin delta has every root left of -delta", bad == 0);
  autobal_rotor_stab_free(s);
}

/* The small searches' options: 4500-9000 rpm, 500-4000 g mm, margin 0.2 1/s, 3 x 6 x 3 cells. */
static autobal_study_rotor_design_options search_opts(void) {
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  o.omega_min = 471.24;
  o.omega_max = 942.48;
  o.n_omega = 5;
  o.n_verify = 9;
  o.unbalance_min = 500e-6;
  o.unbalance_max = 4000e-6;
  o.margin = 0.2;
  o.mass_min = 0.025;
  o.mass_max = 0.1;
  o.n_mass = 3;
  o.radius_min = 0.05;
  o.radius_max = 0.15;
  o.n_radius = 6;
  o.damping_min = 0.1;
  o.damping_max = 1.0;
  o.n_damping = 3;
  return o;
}

/* A small search over 3 and 4 balls with the certification: every certified design's random members at
 * every re-check speed are stable with the margin and have u in the enclosure. */
static void test_search_every(void) {
  double m0[3], r0[3], h0[3], psi0[3], rate0[3];
  autobal_rotor_params p = machine(3, m0, r0, h0, psi0, rate0, 0.05, 0.1, 0.1);
  autobal_study_rotor_design_options o = search_opts();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  size_t i, j, k, ncert = 0, nrej = 0, nchk = 0, bad = 0, ubad = 0, nline = 0, mbad = 0;
  int st;
  o.n_best = 8;
  o.n_starts = 1;
  o.max_iter = 15;
  o.n_balls_min = 3;
  o.n_balls_max = 4;
  o.threads = 1;
  CHECK("the default member rule is every", o.unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY);
  st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("search over 3 and 4 balls, every member", st, AUTOBAL_SUCCESS);
  if (st) {
    printf("  %s\n", err.message);
    autobal_study_rotor_design_summary_free(&S);
    return;
  }
  for (i = 0; i < S.n_designs; i++) {
    const autobal_rotor_design *d = &S.designs[i];
    const size_t n = d->n_balls;
    double m[4], r[4], h[4], psi[4], rate[4];
    autobal_rotor_params q = machine(n, m, r, h, psi, rate, d->mass, d->radius, d->damping);
    const double mr = d->mass * d->radius, um = 0.25 * d->mass * d->mass;
    printf("  design %zu: n %zu m %.4g r %.4g h %.4g rho %.5g feasible %d recheck %d certified %d (u [%.5g, %.5g], "
           "found %.6g rad/s u %.6g)\n",
           i, n, d->mass, d->radius, d->damping, d->margin, d->feasible, d->recheck, d->members_certified,
           d->member_u[0], d->member_u[1], d->member_found_omega, d->member_found_u);
    CHECK("feasible only when certified", !d->feasible || d->members_certified == 1);
    if (d->recheck == 1) CHECK("every re-checked design is certified or not", d->members_certified != 0);
    if (d->members_certified == -1) {
      nrej++;
      /* three balls whose range holds t = 1 (two balls together, one opposite: on one line): the members
         near it have a root near 0 (FULL: every ball angle, no closure), so no margin > 0 holds for every
         member; the rejection is right */
      if (n == 3 && o.unbalance_min < mr && mr < o.unbalance_max) {
        autobal_rotor_stab_options so = autobal_rotor_stab_options_default();
        autobal_rotor_stab *sm;
        double a1 = q.plane[0].psi0 + 2.0 * M_PI + 0.01, mg = NAN;
        int v;
        q.plane[0].m0 = mr / q.plane[0].r0;
        so.member[0].kind = AUTOBAL_ROTOR_MEMBER_FREE;
        so.member[0].n_angles = 1;
        so.member[0].angles = &a1;
        sm = autobal_rotor_stab_alloc(&q, &so, NULL);
        if (sm) {
          autobal_rotor_stab_set(sm, AUTOBAL_ROTOR_PARAM_OMEGA, d->member_found_omega);
          autobal_rotor_stab_margin(sm, AUTOBAL_ROTOR_STAB_FULL, &mg, &v);
          autobal_rotor_stab_free(sm);
        }
        printf("    near-line member (t = 1, ball 1 0.01 rad off): FULL margin %.6g\n", mg);
        CHECK("a rejected 3-ball design with t = 1 in range: a near-line member has a root right of -margin (FULL)",
              mg > -o.margin);
        nline++;
      }
    }
    if (d->members_certified != 1) continue;
    ncert++;
    CHECK("certified margin over every member: between the required margin and the members' sampled one",
          d->member_margin_certified >= o.margin &&
              d->member_margin_certified <= d->member_margin + 1e-3 * (1.0 + d->member_margin) &&
              d->member_margin_certified <= d->damping / d->mass);
    q.plane[0].d = d->position;
    for (j = 0; j < 60; j++) {
      double ang[4], qq;
      const double sv = o.unbalance_min + (o.unbalance_max - o.unbalance_min) * urand();
      autobal_rotor_stab *sm;
      if (random_member(n, mr, sv, q.plane[0].psi0, ang)) continue;
      sm = member_handle(q, sv, ang, n, &qq);
      if (!sm) continue;
      if (!(um * qq >= d->member_u[0] - 1e-12 * um && um * qq <= d->member_u[1] + 1e-12 * um)) ubad++;
      for (k = 0; k < o.n_verify; k++) {
        const double w = o.omega_min + (o.omega_max - o.omega_min) * (double)k / (double)(o.n_verify - 1);
        const double mg = closed_margin(sm, w);
        nchk++;
        if (!(mg < -d->member_margin_certified)) mbad++;
        if (!(mg < -o.margin)) {
          bad++;
          if (bad < 5) printf("    member s %.6g at %.6g rad/s: margin %.6g\n", sv, w, mg);
        }
      }
      autobal_rotor_stab_free(sm);
    }
  }
  printf("  %zu certified, %zu rejected (%zu near-line checked); %zu random (member, speed) checks\n", ncert, nrej, nline,
         nchk);
  CHECK("some designs certified", ncert > 0 && nchk > 0);
  CHECK("certified designs: every random member stable with the margin at every re-check speed (CLOSED)", bad == 0);
  CHECK("certified designs: every random member's u inside the enclosure", ubad == 0);
  CHECK("certified designs: every random member's roots left of -member_margin_certified (CLOSED)", mbad == 0);
  CHECK("the best design is feasible (certified) when any is", S.n_designs == 0 || S.designs[0].feasible || ncert == 0);
  if (S.n_designs > 0 && S.designs[0].members_certified == 1)
    CHECK("the best config says every member", S.best_config && strstr(S.best_config, "EVERY member"));
  /* two threads (the re-checks and certifications in parallel): the same designs and verdicts, bit for bit */
  {
    autobal_study_rotor_design_summary S2;
    size_t same = 1;
    o.threads = 2;
    st = autobal_study_rotor_design(&p, &o, NULL, &S2, &err);
    CHECK_STATUS("the same search on two threads", st, AUTOBAL_SUCCESS);
    if (!st && S2.n_designs == S.n_designs) {
      for (i = 0; i < S.n_designs; i++) {
        const autobal_rotor_design *a = &S.designs[i], *b = &S2.designs[i];
        same &= a->mass == b->mass && a->radius == b->radius && a->members_certified == b->members_certified &&
                a->feasible == b->feasible && a->member_speeds == b->member_speeds &&
                memcmp(&a->member_found_u, &b->member_found_u, sizeof(double)) == 0 &&
                memcmp(&a->member_u, &b->member_u, sizeof a->member_u) == 0 &&
                memcmp(&a->member_margin, &b->member_margin, sizeof(double)) == 0;
      }
    } else
      same = 0;
    CHECK("1 and 2 threads: the same certification, bit for bit", same);
    autobal_study_rotor_design_summary_free(&S2);
  }
  autobal_study_rotor_design_summary_free(&S);
}

/* Two to four balls with every member: each number of balls with a feasible map cell is among the
 * ranked designs, and the feasible designs come first, ordered by the margin their verdict covers (rho
 * for two balls, the certified margin over every member for three or more: docs/rotor.md "Number of
 * balls"), computed here from the designs' own fields. */
static void test_rank_covered(void) {
  double m0[3], r0[3], h0[3], psi0[3], rate0[3];
  autobal_rotor_params p = machine(3, m0, r0, h0, psi0, rate0, 0.05, 0.1, 0.1);
  autobal_study_rotor_design_options o = search_opts();
  autobal_study_rotor_design_summary S;
  autobal_error err;
  size_t i, n, cells, order_bad = 0, missing = 0, infeasible_seen = 0;
  double prev = INFINITY;
  int st;
  o.n_best = 3;
  o.n_starts = 1;
  o.max_iter = 15;
  o.n_balls_min = 2;
  o.n_balls_max = 4;
  o.threads = 1;
  printf("-- two to four balls, every member: each n present, feasible designs by the covered margin\n");
  st = autobal_study_rotor_design(&p, &o, NULL, &S, &err);
  CHECK_STATUS("search over 2 to 4 balls, every member", st, AUTOBAL_SUCCESS);
  if (st) {
    printf("  %s\n", err.message);
    autobal_study_rotor_design_summary_free(&S);
    return;
  }
  cells = S.n_mass * S.n_damping * S.n_position * S.n_radius;
  for (n = 2; n <= 4; n++) {
    int feas = 0, have = 0;
    for (i = 0; i < cells; i++) feas |= S.feasible[(n - 2) * cells + i] == 1;
    for (i = 0; i < S.n_designs; i++) have |= S.designs[i].n_balls == n;
    printf("  n = %zu: feasible map cells %s, among the ranked designs %s\n", n, feas ? "yes" : "no", have ? "yes" : "no");
    if (feas && !have) missing++;
  }
  for (i = 0; i < S.n_designs; i++) {
    const autobal_rotor_design *d = &S.designs[i];
    double cov = d->margin;
    if (d->n_balls >= 3) cov = d->members_certified == 1 ? fmin(d->margin, d->member_margin_certified) : -INFINITY;
    printf("  %zu: n %zu rho %.5g certified %d member margin %.5g covered %.5g feasible %d\n", i, d->n_balls, d->margin,
           d->members_certified, d->member_margin_certified, cov, d->feasible);
    if (!d->feasible) {
      infeasible_seen = 1;
      continue;
    }
    if (infeasible_seen || !(cov <= prev) || !(cov > o.margin)) order_bad++;
    prev = cov;
  }
  CHECK("every number of balls with a feasible map cell is among the ranked designs", missing == 0);
  CHECK("feasible designs first, by the covered margin (larger first), each above the required margin", order_bad == 0);
  CHECK("some design feasible", S.n_designs > 0 && S.designs[0].feasible);
  if (S.n_designs > 0 && S.designs[0].n_balls >= 3)
    CHECK("the best config states the margin over every member", S.best_config && strstr(S.best_config, "over every member"));
  autobal_study_rotor_design_summary_free(&S);
}

int main(void) {
  test_u_range();
  test_constructed();
  test_search_every();
  test_rank_covered();
  return check_summary();
}
