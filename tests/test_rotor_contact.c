/* test_rotor_contact.c: ball size and contact (docs/device.md section 4; autobal_rotor_contact).
 *  - the impact law against tools/derive/check_values.json key "impact" (the SymPy/NumPy values: G,
 *    Lambda, every velocity after, one and two planes, prescribed speed and motor, e = 0.5 and 1),
 *    and the energy: the total energy before and after (computed here from the documented energies)
 *    drops by exactly 1/2 (1 - e^2) u^2 / G (motor; with the JSON's G) or changes by the drive's
 *    work (prescribed), none at e = 1; both frames;
 *  - validation: balls that do not fit (naming the plane), overlapping initial positions (naming
 *    the balls), e outside [0, 1], a negative diameter;
 *  - the gap angle and the reachability of two equal balls: capacity 2 m r cos(gamma/2) =
 *    2 m r sqrt(1 - (delta/2r)^2) (docs/device.md: 0.99337 2 m r for delta = 23 mm, r = 0.1 m);
 *  - transients: delta -> 0 with e = 1 reproduces the frictionless transient; two balls whose
 *    balanced separation is below the gap angle are pressed together and come to resting contact
 *    (clusters) without the run failing, at a separation of exactly the gap angle. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal/rotor.h"
#include "autobal/study.h"
#include "autobal/transient.h"
#include "check.h"
#include "check_json.h"
#include "rotor_energy.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define JSON_PATH AUTOBAL_TEST_DATA_DIR "/../tools/derive/check_values.json"



/* Kinetic plus potential energy (docs/device.md "Energies", PAPER inertia) of a FIXED-frame state
 * y (rotor and balls; the spin phi_0, Omega and J given: a prescribed speed holds Omega). */
static double energy(const autobal_rotor *rot, const double *y, double ph0, double W, double J) {
  const autobal_rotor_params *p = autobal_rotor_get_params(rot);
  const autobal_rotor_lumped *L = autobal_rotor_get_lumped(rot);
  const autobal_rotor_hardware *h = &p->hw;
  const size_t N = autobal_rotor_n_balls_total(rot);
  const double x = y[0], yy = y[1], al = y[2], be = y[3], xd = y[4], yd = y[5], ad = y[6], bd = y[7];
  double T, V, xl, yl, xr, yr;
  size_t j, i;
  T = 0.5 * L->M * (xd * xd + yd * yd) + 0.5 * L->A * (ad * ad + bd * bd) + 0.5 * J * W * W + L->C * W * ad * be;
  for (j = 0; j < p->n_planes; j++) {
    const autobal_rotor_plane *P = &p->plane[j];
    const double uDd = xd + P->d * bd, vDd = yd - P->d * ad, th = ph0 + P->psi0;
    T += 0.5 * P->m0 * P->r0 * P->r0 * W * W + P->m0 * P->r0 * W * (-uDd * sin(th) + vDd * cos(th));
    for (i = 0; i < P->n_balls; i++) {
      const size_t k = autobal_rotor_ball_index(rot, j, i);
      const double m = P->ball_mass[i], rr = P->ball_radius[i], ph = y[8 + k], phd = y[8 + N + k];
      T += 0.5 * m * rr * rr * phd * phd + m * rr * phd * (-uDd * sin(ph) + vDd * cos(ph));
    }
  }
  xl = x - h->l_L * be, yl = yy + h->l_L * al, xr = x + h->l_R * be, yr = yy - h->l_R * al;
  V = 0.5 * (h->c_Lx * xl * xl + h->c_Ly * yl * yl + h->c_Rx * xr * xr + h->c_Ry * yr * yr);
  return T + V;
}

static void impact_case(const char *json, size_t n_planes, int motor, int e1) {
  const char *which = n_planes == 1 ? "one_plane" : "two_planes";
  const char *pk = n_planes == 1 ? "planes1" : "planes2";
  const char *tag = motor ? (e1 ? "motor_e1" : "motor") : (e1 ? "prescribed_e1" : "prescribed");
  const char *blk = after_key(json, which), *st = after_key(blk, "state");
  const char *drv_blk = after_key(blk, motor ? "motor" : "prescribed");
  const char *sec = after_key(json, "impact"), *cas = after_key(after_key(sec, pk), tag);
  const char *va = after_key(cas, "velocities_after");
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};
  autobal_rotor_params p;
  double m[2][2], r[2][2], h[2][2], psi[2][2], rate[2][2], dia[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  double y[20], y0[20], yr[20], Om, Omd, phi0, t = 0.7, drv[3], e, G, Lam, u, E0, E1, loss, want;
  size_t j, i, N = 2 * n_planes, dim = 8 + 2 * N + (motor ? 2u : 0u), pp, np, pair = 99, last = n_planes - 1;
  autobal_rotor *rot;
  autobal_error err;
  char what[200];

  printf("-- impact, %s, %s vs check_values.json\n", which, tag);
  CHECK("JSON impact blocks found", blk && st && drv_blk && sec && cas && va);
  if (!(blk && st && drv_blk && sec && cas && va)) return;
  if (load_params(blk, n_planes, &p, m, r, h, psi, rate) != 0) {
    CHECK("JSON parameters", 0);
    return;
  }
  e = num(cas, "e");
  CHECK("the pair's psi and rates from the JSON", arr(cas, "psi", psi[last], 2) == 2 && arr(cas, "rate", rate[last], 2) == 2);
  dia[last][0] = dia[last][1] = num(sec, "delta");
  p.contact.on = 1;
  p.contact.restitution = e;
  for (j = 0; j < n_planes; j++) p.contact.ball_diameter[j] = dia[j];
  Om = num(drv_blk, "Omega"), phi0 = num(st, "phi_0");
  if (motor) {
    p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
    p.drive.J = num(drv_blk, "J"), p.drive.L_0 = num(drv_blk, "L_0"), p.drive.omega_0 = num(drv_blk, "Omega_0");
    p.drive.k_r = num(drv_blk, "k_r"), p.drive.omega_start = Om;
  } else {
    Omd = num(drv_blk, "Omega_dot");
    t = (Om - sqrt(Om * Om - 2.0 * Omd * phi0)) / Omd;
    p.drive.mode = AUTOBAL_ROTOR_DRIVE_RAMP;
    p.drive.t_a = 0.0, p.drive.t_b = 10.0;
    p.drive.omega_a = Om - Omd * t, p.drive.omega_b = p.drive.omega_a + Omd * 10.0;
  }
  p.omega = Om;
  rot = autobal_rotor_alloc(&p, &err);
  CHECK("rotor with contact (the pair touching)", rot != NULL);
  if (!rot) {
    printf("     %s\n", err.message);
    return;
  }
  if (motor) drv[0] = Om, drv[2] = phi0;
  else CHECK("drive evaluated", autobal_rotor_drive_eval(rot, t, drv) == AUTOBAL_SUCCESS);
  for (i = 0; i < 4; i++) {
    char k2[16];
    y[i] = num(st, qn[i]);
    snprintf(k2, sizeof k2, "%s_d", qn[i]);
    y[4 + i] = num(st, k2);
  }
  if (motor) y[dim - 2] = phi0, y[dim - 1] = Om;
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      const size_t k = autobal_rotor_ball_index(rot, j, i);
      y[8 + k] = drv[2] + psi[j][i];
      y[8 + N + k] = drv[0] + rate[j][i];
    }
  CHECK_STATUS("pairs from the state", autobal_rotor_contact_order(rot, AUTOBAL_ROTOR_FIXED, t, y), AUTOBAL_SUCCESS);
  np = autobal_rotor_contact_n_pairs(rot);
  CHECK("two pairs (two balls on the last plane's track)", np == 2);
  for (pp = 0; pp < np; pp++)
    if (fabs(autobal_rotor_contact_gap(rot, pp, y)) < 1e-12) pair = pp;
  CHECK("the touching pair found (gap 0 to 1e-12 rad)", pair < np);
  if (pair >= np) {
    autobal_rotor_free(rot);
    return;
  }
  memcpy(y0, y, sizeof y);
  CHECK_STATUS("rotating-frame state", autobal_rotor_convert_state(rot, AUTOBAL_ROTOR_FIXED, AUTOBAL_ROTOR_ROTATING, t, y, yr, dim), AUTOBAL_SUCCESS);
  E0 = energy(rot, y, phi0, Om, motor ? p.drive.J : p.hw.C_p);
  CHECK_STATUS("impact applied (fixed frame)", autobal_rotor_contact_impact(rot, AUTOBAL_ROTOR_FIXED, pair, e, t, y, &G, &Lam, &u), AUTOBAL_SUCCESS);
  snprintf(what, sizeof what, "%s %s: G = J M^-1 J^T", which, tag);
  CHECK_CLOSE(what, G, num(cas, "G"), 1e-12, 0);
  snprintf(what, sizeof what, "%s %s: gap rate before u", which, tag);
  CHECK_CLOSE(what, u, num(cas, "relative_speed_before"), 1e-13, 1e-13);
  snprintf(what, sizeof what, "%s %s: impulse Lambda", which, tag);
  CHECK_CLOSE(what, Lam, num(cas, "impulse"), 1e-11, 0);
  for (i = 0; i < 4; i++) {
    char k2[16];
    snprintf(k2, sizeof k2, "%s_d", qn[i]);
    snprintf(what, sizeof what, "%s %s: %s after", which, tag, k2);
    CHECK_CLOSE(what, y[4 + i], num(va, k2), 1e-12, 1e-15);
  }
  for (j = 0; j < n_planes; j++)
    for (i = 0; i < 2; i++) {
      char key[32];
      const size_t k = autobal_rotor_ball_index(rot, j, i);
      snprintf(key, sizeof key, "phi_%zu%zu_d", j + 1, i + 1);
      snprintf(what, sizeof what, "%s %s: %s after", which, tag, key);
      CHECK_CLOSE(what, y[8 + N + k], num(va, key), 1e-14, 0);
      CHECK("angles unchanged by the impact", y[8 + k] == y0[8 + k]);
    }
  if (motor) {
    snprintf(what, sizeof what, "%s %s: phi_0' = Omega after", which, tag);
    CHECK_CLOSE(what, y[dim - 1], num(va, "phi_0_d"), 1e-15, 0);
  }
  /* the energy: before and after from the documented energies */
  E1 = energy(rot, y, phi0, motor ? y[dim - 1] : Om, motor ? p.drive.J : p.hw.C_p);
  loss = 0.5 * (1.0 - e * e) * num(cas, "relative_speed_before") * num(cas, "relative_speed_before") / num(cas, "G");
  snprintf(what, sizeof what, "%s %s: closed-form loss 1/2 (1 - e^2) u^2 / G = the JSON's impact_loss", which, tag);
  CHECK_CLOSE(what, loss, num(cas, "impact_loss"), 1e-12, 1e-30);
  want = motor ? -loss : -loss + num(cas, "drive_work");
  snprintf(what, sizeof what, "%s %s: E(after) - E(before) = %s (E = %.6g J)", which, tag,
           motor ? (e1 ? "0 (e = 1)" : "-loss") : "-loss + drive work", E0);
  printf("     E after - E before = %.9e J, closed form %.9e J\n", E1 - E0, want);
  CHECK_CLOSE(what, E1 - E0, want, 0, 4e-15 * E0);
  /* the rotating frame: the same jump */
  {
    double yb[20], Gr, Lr, ur;
    CHECK_STATUS("impact applied (rotating frame)",
                 autobal_rotor_contact_impact(rot, AUTOBAL_ROTOR_ROTATING, pair, e, t, yr, &Gr, &Lr, &ur), AUTOBAL_SUCCESS);
    CHECK_STATUS("back to the fixed frame", autobal_rotor_convert_state(rot, AUTOBAL_ROTOR_ROTATING, AUTOBAL_ROTOR_FIXED, t, yr, yb, dim), AUTOBAL_SUCCESS);
    snprintf(what, sizeof what, "%s %s: rotating frame G, Lambda = fixed frame's", which, tag);
    CHECK(what, fabs(Gr - G) <= 1e-12 * G && fabs(Lr - Lam) <= 1e-11 * fabs(Lam));
    for (i = 0; i < dim; i++) {
      snprintf(what, sizeof what, "%s %s: rotating-frame impact, state entry %zu = fixed frame's", which, tag, i);
      CHECK_CLOSE(what, yb[i], y[i], 1e-13, 1e-16);
    }
  }
  autobal_rotor_free(rot);
}

static void validation(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_error e;
  double dia[2] = {0.023, 0.023}, big[2] = {0.35, 0.35}, neg[2] = {0.01, -0.001}, psi[2] = {1.0, 1.2};
  double gam = autobal_rotor_gap_angle(0.023, 0.023, 0.1);
  printf("-- validation, gap angle, reachability\n");
  CHECK_CLOSE("gap angle 2 asin(0.046/0.4) (docs: 0.23051 rad)", gam, 2.0 * asin(0.115), 1e-15, 0);
  CHECK_CLOSE("gap angle = the JSON's note 0.2305099993351552", gam, 0.2305099993351552, 1e-15, 0);
  CHECK("gap angle of (delta_i + delta_j) > 4 r is NaN", isnan(autobal_rotor_gap_angle(0.3, 0.2, 0.1)));
  p.contact.on = 1;
  p.contact.restitution = 1.5;
  p.contact.ball_diameter[0] = dia;
  CHECK_STATUS("e = 1.5 refused", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("names contact.restitution", e.message, "contact.restitution");
  p.contact.restitution = -0.1;
  CHECK_STATUS("e = -0.1 refused", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  p.contact.restitution = 0.5;
  p.contact.ball_diameter[0] = neg;
  CHECK_STATUS("negative diameter refused", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("names plane[0].ball_diameter[1]", e.message, "plane[0].ball_diameter[1]");
  /* two balls of 0.35 m on r = 0.1: sum 0.7 m > the circumference? 0.628 m: and 0.7 > 4 r: do not fit */
  p.contact.ball_diameter[0] = big;
  CHECK_STATUS("balls that do not fit refused", autobal_rotor_params_check(&p, &e), AUTOBAL_EINVAL);
  CHECK_MSG("names plane 1", e.message, "plane 1");
  /* four balls of 0.15 m: sum 0.6 m < circumference 0.628 m, but the gap angles 4 x 2 asin(0.75) = 6.78 > 2 pi */
  {
    autobal_rotor_params q = autobal_rotor_params_default();
    double m4[4] = {0.05, 0.05, 0.05, 0.05}, r4[4] = {0.1, 0.1, 0.1, 0.1}, h4[4] = {0.1, 0.1, 0.1, 0.1};
    double d4[4] = {0.15, 0.15, 0.15, 0.15}, p4[4] = {0.0, 1.6, 3.2, 4.8};
    q.plane[0].n_balls = 4, q.plane[0].ball_mass = m4, q.plane[0].ball_radius = r4, q.plane[0].ball_damping = h4;
    q.plane[0].ball_psi = p4, q.plane[0].ball_rate = NULL;
    q.contact.on = 1, q.contact.restitution = 1.0, q.contact.ball_diameter[0] = d4;
    CHECK_STATUS("four 0.15 m balls on r = 0.1 m (gap angles sum to 6.78 rad) refused", autobal_rotor_params_check(&q, &e), AUTOBAL_EINVAL);
    CHECK_MSG("names plane 1", e.message, "plane 1");
    d4[0] = d4[1] = d4[2] = d4[3] = 0.14; /* 4 x 2 asin(0.7) = 6.21 < 2 pi: fits */
    CHECK_STATUS("four 0.14 m balls fit", autobal_rotor_params_check(&q, &e), AUTOBAL_SUCCESS);
  }
  /* overlap at the initial positions (psi 1.0 and 1.2 < gamma = 0.2305 apart) */
  p.contact.ball_diameter[0] = dia;
  p.plane[0].ball_psi = psi;
  {
    autobal_rotor *rot = autobal_rotor_alloc(&p, &e);
    CHECK("overlapping initial balls refused by alloc", rot == NULL && e.status == AUTOBAL_EINVAL);
    CHECK_MSG("names the balls", e.message, "balls 1 and 2 of plane 1");
    autobal_rotor_free(rot);
  }
  /* reachability: two equal balls of the default plane (m r = 0.005 kg m), delta = 23 mm */
  {
    const double cap_want = 2.0 * 0.005 * sqrt(1.0 - 0.115 * 0.115);
    autobal_rotor *rot;
    p.plane[0].ball_psi = NULL; /* default positions 1.0, 2.5 */
    p = autobal_rotor_params_default();
    p.contact.on = 1, p.contact.restitution = 1.0, p.contact.ball_diameter[0] = dia;
    rot = autobal_rotor_alloc(&p, &e);
    CHECK("default rotor with 23 mm balls", rot != NULL);
    if (rot) {
      CHECK_CLOSE("capacity = 2 m r sqrt(1 - (delta/2r)^2)", autobal_rotor_contact_capacity(rot, 0), cap_want, 1e-14, 0);
      CHECK_CLOSE("capacity / (2 m r) = 0.99337 (docs/device.md)", autobal_rotor_contact_capacity(rot, 0) / 0.01, 0.99337, 0, 5e-6);
      CHECK("default unbalance 0.002 kg m reachable", autobal_rotor_contact_reachable(rot, 0) == 1);
      autobal_rotor_free(rot);
    }
    p.plane[0].m0 = 0.0996; /* m0 r0 = 0.00996 kg m: 2 m r > s0 > capacity 0.0099337 */
    rot = autobal_rotor_alloc(&p, &e);
    CHECK("rotor allocated", rot != NULL);
    if (rot) {
      CHECK("m0 r0 = 0.00996 kg m > capacity: out of reach", autobal_rotor_contact_reachable(rot, 0) == 0);
      autobal_rotor_free(rot);
    }
    p.plane[0].m0 = 0.0993; /* 0.00993 < 0.0099337 */
    rot = autobal_rotor_alloc(&p, &e);
    if (rot) {
      CHECK("m0 r0 = 0.00993 kg m < capacity: reachable", autobal_rotor_contact_reachable(rot, 0) == 1);
      autobal_rotor_free(rot);
    }
  }
}


/* A study run of the default rotor (one plane, two balls) with the given changes; returns the status. */
static int run_study(autobal_rotor_params *p, int frame, double t_end, autobal_study_rotor_transient_summary *s) {
  autobal_study_rotor_transient_options o = autobal_study_rotor_transient_options_default();
  autobal_error e;
  int st;
  o.t_end = t_end;
  o.frame = frame;
  o.rtol = 1e-11;
  o.atol = 1e-13;
  st = autobal_study_rotor_transient(p, &o, NULL, s, &e);
  if (st < 0) printf("     study failed: %s\n", e.message);
  return st;
}

/* delta -> 0 with e = 1: two equal balls exchange their velocities at an impact (the generalized law
 * with a prescribed speed: J is an eigenvector of the rotor coupling) and the rotor's jump is
 * O(gamma m/M): the run converges to the frictionless one, where the point balls pass through each
 * other (the same motion with the labels exchanged).  The rotor's x, y and the residual unbalance at
 * the end, 1 s of the default rotor with ball 1 at psi = 1.0 moving at 5 rad/s towards ball 2 at 1.3
 * (17 impacts: the balls circle relative to each other). */
static void delta_limit(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_transient_summary s0, s;
  double psi[2] = {1.0, 1.3}, rate[2] = {5.0, 0.0}, dia[2], diff[3];
  const double deltas[3] = {1e-6, 1e-7, 1e-8};
  size_t n;
  char what[200];
  printf("-- delta -> 0 (e = 1) against the frictionless transient\n");
  p.plane[0].ball_psi = psi;
  p.plane[0].ball_rate = rate;
  memset(&s0, 0, sizeof s0);
  if (run_study(&p, AUTOBAL_ROTOR_FIXED, 1.0, &s0) != AUTOBAL_SUCCESS) {
    CHECK("frictionless run", 0);
    return;
  }
  for (n = 0; n < 3; n++) {
    memset(&s, 0, sizeof s);
    dia[0] = dia[1] = deltas[n];
    p.contact.on = 1, p.contact.restitution = 1.0, p.contact.ball_diameter[0] = dia;
    CHECK_STATUS("run with contact", run_study(&p, AUTOBAL_ROTOR_FIXED, 1.0, &s), AUTOBAL_SUCCESS);
    CHECK("impacts happened", s.have_contact && s.contact_impacts > 0);
    diff[n] = fabs(s.residual_unbalance_abs_final[0] - s0.residual_unbalance_abs_final[0]) / s0.residual_unbalance_abs_final[0];
    printf("     delta = %g m: %lu impacts, residual unbalance %.12g vs %.12g kg m (relative difference %.3e)\n", deltas[n],
           s.contact_impacts, s.residual_unbalance_abs_final[0], s0.residual_unbalance_abs_final[0], diff[n]);
    autobal_study_rotor_transient_summary_free(&s);
  }
  /* the jumps are O(gamma) = O(delta): first order expected */
  snprintf(what, sizeof what, "converges at order 1: differences %.3e, %.3e, %.3e, orders %.4f, %.4f in [0.9, 1.1]", diff[0],
           diff[1], diff[2], log10(diff[0] / diff[1]), log10(diff[1] / diff[2]));
  CHECK(what, fabs(log10(diff[0] / diff[1]) - 1.0) < 0.1 && fabs(log10(diff[1] / diff[2]) - 1.0) < 0.1);
  autobal_study_rotor_transient_summary_free(&s0);
}

/* Resting contact: the unbalance m0 r0 = 0.00996 kg m needs the two balls (m r = 0.005 kg m) 0.1795 rad
 * apart (3.14), less than the gap angle 0.2305 rad of 23 mm balls: the balls are pressed together
 * towards the balanced position.  With e = 0.5 they bounce, join in resting contact (a cluster) and
 * stay there: the run must not fail (no chattering), the pair touches at the end at exactly the gap
 * angle, and the summary reports the balanced angles out of reach.  Both frames. */
static void resting_contact(int frame) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_transient_summary s;
  double psi[2] = {2.5, 3.5}, dia[2] = {0.023, 0.023}, sep, gam = autobal_rotor_gap_angle(0.023, 0.023, 0.1);
  char what[200];
  printf("-- resting contact (%s frame)\n", frame == AUTOBAL_ROTOR_FIXED ? "fixed" : "rotating");
  p.plane[0].m0 = 0.0996;
  p.plane[0].ball_psi = psi;
  p.contact.on = 1, p.contact.restitution = 0.5, p.contact.ball_diameter[0] = dia;
  memset(&s, 0, sizeof s);
  CHECK_STATUS("5 s run with contact: no failure", run_study(&p, frame, 5.0, &s), AUTOBAL_SUCCESS);
  printf("     %lu impacts, %lu joins, %lu releases, %lu touching at the end; resets %lu\n", s.contact_impacts,
         s.contact_joins, s.contact_releases, s.contacts_final, s.solver.resets);
  CHECK("impacts and at least one join", s.contact_impacts > 0 && s.contact_joins > 0);
  CHECK("the pair touches at the end (one cluster)", s.contacts_final == 1);
  CHECK("out of reach reported", s.have_contact && s.contact_reachable[0] == 0);
  CHECK_CLOSE("capacity 2 m r cos(gamma/2)", s.contact_capacity[0], 0.01 * cos(0.5 * gam), 1e-14, 0);
  if (s.ball_psi_final[0]) {
    sep = s.ball_psi_final[0][1] - s.ball_psi_final[0][0];
    sep -= 2.0 * M_PI * floor(sep / (2.0 * M_PI));
    if (sep > M_PI) sep = 2.0 * M_PI - sep;
    snprintf(what, sizeof what, "final separation %.12f rad = the gap angle", sep);
    CHECK_CLOSE(what, sep, gam, 0, 1e-8);
  }
  autobal_study_rotor_transient_summary_free(&s);
}


/* Energy along a run with impacts (MOTOR drive, fixed frame, the library's events and reset as the
 * study uses them): the state is extended by W = integral of (L Omega - D) (motor power minus all
 * dissipation, tests/rotor_energy.h); the reset wrapper records the energy jump of every reset.
 * Between events E changes only by L Omega - D, so E(end) - E(0) - W - sum of the jumps = 0 (to the
 * integration tolerance); each jump is <= 0, and 0 (to rounding) at e = 1. */
typedef struct erun {
  autobal_rotor *rot;
  size_t dim, n_resets, n_imp;
  double jumps, worst_jump_e1, largest_jump;
} erun;
static int erun_rhs(double t, const double y[], double dydt[], void *par) {
  erun *E = (erun *)par;
  int st = autobal_rotor_rhs(t, y, dydt, E->rot);
  const double W = y[E->dim - 1];
  dydt[E->dim] = autobal_rotor_motor_torque(E->rot, W) * W - motor_dissipation(E->rot, y);
  return st;
}
typedef struct erun_ev {
  erun *E;
  size_t p;
} erun_ev;
static double erun_gap(double t, const double y[], void *u) {
  const erun_ev *ev = (const erun_ev *)u;
  return autobal_rotor_contact_switch(ev->E->rot, AUTOBAL_ROTOR_FIXED, ev->p, t, y);
}
static int erun_reset(const autobal_transient_event_hit *hit, double y[], void *u) {
  erun *E = (erun *)u;
  const double e0 = motor_energy(E->rot, y);
  int rc = autobal_rotor_contact_settle(E->rot, AUTOBAL_ROTOR_FIXED, hit->t, y, &E->n_imp, NULL, NULL);
  const double d = motor_energy(E->rot, y) - e0;
  if (rc < 0) return 2;
  E->n_resets++;
  E->jumps += d;
  if (d > E->largest_jump) E->largest_jump = d;
  return rc == 1 ? AUTOBAL_TRANSIENT_RESET : 0;
}
static void energy_run(double e) {
  autobal_rotor_params p = autobal_rotor_params_default();
  double psi[2] = {1.0, 1.3}, rate[2] = {20.0, -20.0}, dia[2] = {0.023, 0.023}, y[16], E0, E1;
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient *tr;
  erun E;
  erun_ev ev[2];
  size_t k;
  char what[200];
  printf("-- energy along a motor run with impacts, e = %g\n", e);
  p.plane[0].ball_psi = psi, p.plane[0].ball_rate = rate;
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
  p.drive.J = p.hw.C_p + 0.01, p.drive.L_0 = 5.0, p.drive.omega_0 = 600.0, p.drive.k_r = 1e-3;
  p.drive.omega_start = 300.0;
  p.contact.on = 1, p.contact.restitution = e, p.contact.ball_diameter[0] = dia;
  memset(&E, 0, sizeof E);
  E.rot = autobal_rotor_alloc(&p, NULL);
  CHECK("motor rotor with contact", E.rot != NULL);
  if (!E.rot) return;
  E.dim = autobal_rotor_dim(E.rot);
  CHECK("initial state", autobal_rotor_initial_state(E.rot, AUTOBAL_ROTOR_FIXED, 0.0, y, E.dim) == AUTOBAL_SUCCESS);
  y[E.dim] = 0.0;
  E0 = motor_energy(E.rot, y);
  o.rtol = 1e-12, o.atol = 1e-14, o.stepper = "rk8pd";
  sys.rhs = erun_rhs, sys.jac = NULL, sys.dim = E.dim + 1, sys.params = &E;
  tr = autobal_transient_alloc(sys.dim, &o, NULL);
  CHECK("engine", tr != NULL);
  if (!tr) {
    autobal_rotor_free(E.rot);
    return;
  }
  for (k = 0; k < autobal_rotor_contact_n_pairs(E.rot) && k < 2; k++) {
    ev[k].E = &E, ev[k].p = k;
    autobal_transient_add_event(tr, erun_gap, &ev[k], -1, 0);
  }
  autobal_transient_set_event_reset(tr, erun_reset, &E);
  CHECK_STATUS("1 s run", autobal_transient_run(tr, &sys, 0.0, 1.0, y, NULL), AUTOBAL_SUCCESS);
  E1 = motor_energy(E.rot, y);
  printf("     %zu resets, %zu impacts; E(1 s) - E(0) = %.12g J, work integral %.12g J, impact jumps %.6e J\n", E.n_resets,
         E.n_imp, E1 - E0, y[E.dim], E.jumps);
  CHECK("impacts happened", E.n_imp > 0);
  snprintf(what, sizeof what, "e = %g: E(end) - E(0) = integral (L Omega - D) + the impact jumps", e);
  CHECK_CLOSE(what, E1 - E0, y[E.dim] + E.jumps, 0, 1e-8);
  snprintf(what, sizeof what, "e = %g: no reset adds energy (largest jump %.3e J)", e, E.largest_jump);
  CHECK(what, E.largest_jump <= 1e-12 * fabs(E0));
  if (e == 1.0) {
    /* rounding of E and the gap closed at the reset (|g| <= 1e-9 rad moves T by ~ m r phi' |v_D'| g) */
    snprintf(what, sizeof what, "e = 1: the impacts change the energy by %.3e J (within 1e-12 E = %.4g J per impact)", E.jumps, E0);
    CHECK(what, fabs(E.jumps) <= 1e-12 * fabs(E0) * (double)E.n_imp);
  } else {
    CHECK("e < 1: the impacts dissipate", E.jumps < 0.0);
  }
  autobal_transient_free(tr);
  autobal_rotor_free(E.rot);
}

int main(void) {
  char *json;
  size_t np;
  int motor, e1;
  gsl_set_error_handler_off();
  json = slurp(JSON_PATH);
  CHECK("tools/derive/check_values.json read", json != NULL);
  if (!json) return 1;
  for (np = 1; np <= 2; np++)
    for (motor = 0; motor <= 1; motor++)
      for (e1 = 0; e1 <= 1; e1++) impact_case(json, np, motor, e1);
  free(json);
  validation();
  delta_limit();
  energy_run(1.0);
  energy_run(0.5);
  resting_contact(AUTOBAL_ROTOR_FIXED);
  resting_contact(AUTOBAL_ROTOR_ROTATING);
  printf("%d checks, %d failed\n", check_count_, check_failures_);
  return check_failures_ ? 1 : 0;
}
