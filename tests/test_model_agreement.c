/* test_model_agreement.c: the two models where they meet (issue 18 item 6; docs/rotor.md,
 * "Planar limit: the two-pendulum model").
 *
 * A rotor with one plane of two identical balls, isotropic supports, the plane at the centre of
 * mass (d = 0) and no coupling of translation and tilt (c_xbeta = c_yalpha = h_xbeta = h_yalpha
 * = 0) is, in its translation, the two-pendulum balancer of docs/pendulum.md: a ball on a track
 * of radius r about the shaft is a pendulum of length r hinged on the shaft.  With
 *   M_s = M + m0 + 2 m (FULL inertia; the paper's PAPER model: M_s = M),
 *   omega0 = sqrt(c / M_s),  R_w = omega / omega0,  R_m = m / M_s,  H = h_x / (omega0 M_s),
 *   h = h_ball / (m omega0),  sin psi0 = m0 r0 / (2 m r),
 * Delta of the rotor factors exactly (d = 0, K12 = 0: D = K11 K22, N = K22) into
 *   Delta(lambda) = M_s^2 omega0^8 P6(lambda / omega0) * K22(lambda) K22*(lambda),
 * P6 the pendulum's characteristic polynomial (6) and K22 = A P^2 + (h_t - i C w) P + c_t the
 * tilt, P = lambda + i w.  So the 12 rotor roots are omega0 times the 8 pendulum roots plus the
 * 4 tilt roots, which have the closed form lambda = -i w + (-(h_t - i C w) +- sqrt((h_t - i C w)^2
 * - 4 A c_t)) / (2 A) and their conjugates.  The expected values come from the pendulum model's
 * own code (a different model, its roots checked against the eigenvalues of (5) and, in
 * tests/app, against NumPy) and from that closed form; the rotor's roots are checked by all
 * three of its methods (POLY: roots of Delta, CLOSED: eigenvalues of the closed matrix, FULL:
 * eigenvalues of the linearized full model, every ball angle), and its verdict against the
 * pendulum's.  Also: the audit's numbers of issue 18, and that with d != 0 the sets differ
 * (the test can fail). */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal.h"
#include "check.h"

typedef struct {
  const char *name;
  int inertia;           /* AUTOBAL_ROTOR_INERTIA_* */
  double M, A, C;        /* kg, kg m^2, kg m^2 */
  double c, h_s;         /* N/m, N s/m (isotropic translation) */
  double c_t, h_t;       /* N m, N m s (tilt) */
  double m, r, h_b;      /* ball: kg, m, kg/s */
  double m0, r0;         /* unbalance: kg, m */
  double omega;          /* rad/s */
} planar_case;

static double ball_m[2], ball_r[2], ball_h[2];

static autobal_rotor_params rotor_of(const planar_case *pc, double d) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_lumped *L = &p.lumped;
  p.input = AUTOBAL_ROTOR_LUMPED;
  p.inertia = pc->inertia;
  memset(L, 0, sizeof *L);
  L->M = pc->M;
  L->A = pc->A;
  L->C = pc->C;
  L->c_x = L->c_y = pc->c;
  L->c_z = pc->c;
  L->c_alpha = L->c_beta = pc->c_t;
  L->h_x = L->h_y = pc->h_s;
  L->h_alpha = L->h_beta = pc->h_t;
  /* c_xbeta = c_yalpha = h_xbeta = h_yalpha = 0: tilt decoupled from translation */
  ball_m[0] = ball_m[1] = pc->m;
  ball_r[0] = ball_r[1] = pc->r;
  ball_h[0] = ball_h[1] = pc->h_b;
  p.omega = pc->omega;
  p.n_planes = 1;
  p.plane[0].d = d;
  p.plane[0].m0 = pc->m0;
  p.plane[0].r0 = pc->r0;
  p.plane[0].psi0 = 0.0;
  p.plane[0].n_balls = 2;
  p.plane[0].ball_mass = ball_m;
  p.plane[0].ball_radius = ball_r;
  p.plane[0].ball_damping = ball_h;
  p.plane[0].ball_psi = NULL;
  p.plane[0].ball_rate = NULL;
  return p;
}

/* The pendulum parameters of the planar limit and omega0 (the mapping above). */
static void pendulum_of(const planar_case *pc, autobal_pendulum_params *q, double *omega0) {
  double Ms = pc->inertia == AUTOBAL_ROTOR_INERTIA_FULL ? pc->M + pc->m0 + 2.0 * pc->m : pc->M;
  double w0 = sqrt(pc->c / Ms);
  q->R_w = pc->omega / w0;
  q->R_m = pc->m / Ms;
  q->H = pc->h_s / (w0 * Ms);
  q->h = pc->h_b / (pc->m * w0);
  q->psi0 = asin(pc->m0 * pc->r0 / (2.0 * pc->m * pc->r));
  *omega0 = w0;
}

/* The 12 expected roots: omega0 x the pendulum's 8 and the tilt's 4 (closed form). */
static void expected_roots(const planar_case *pc, const autobal_pendulum_result *pr, double w0,
                           double *re, double *im) {
  double complex b = pc->h_t - I * pc->C * pc->omega, s = csqrt(b * b - 4.0 * pc->A * pc->c_t);
  double complex t[2];
  size_t i;
  for (i = 0; i < 8; i++) {
    re[i] = w0 * pr->root_re[i];
    im[i] = w0 * pr->root_im[i];
  }
  t[0] = (-b + s) / (2.0 * pc->A) - I * pc->omega; /* K22(lambda) = 0 */
  t[1] = (-b - s) / (2.0 * pc->A) - I * pc->omega;
  for (i = 0; i < 2; i++) { /* and the roots of K22*, the conjugates */
    re[8 + 2 * i] = creal(t[i]);
    im[8 + 2 * i] = cimag(t[i]);
    re[9 + 2 * i] = creal(t[i]);
    im[9 + 2 * i] = -cimag(t[i]);
  }
}

static double max_abs(size_t n, const double *re, const double *im) {
  double m = 1.0;
  size_t i;
  for (i = 0; i < n; i++)
    if (hypot(re[i], im[i]) > m) m = hypot(re[i], im[i]);
  return m;
}

/* bottleneck distance between two root sets of 12, relative to the largest root */
static double set_distance(const double *are, const double *aim, const double *bre,
                           const double *bim) {
  size_t perm[12];
  double dist = INFINITY;
  if (autobal_match_roots(12, are, aim, bre, bim, perm, &dist, NULL) != AUTOBAL_SUCCESS)
    return INFINITY;
  return dist / max_abs(12, are, aim);
}

static void run_case(const planar_case *pc, autobal_pendulum_workspace *pws) {
  autobal_rotor_params p = rotor_of(pc, 0.0);
  autobal_pendulum_params q;
  autobal_pendulum_result pr;
  autobal_rotor_stab_result rr;
  autobal_rotor_stab *s;
  autobal_error err;
  double w0, ere[12], eim[12], d;
  char what[256];
  printf("-- %s\n", pc->name);
  pendulum_of(pc, &q, &w0);
  printf("   mapped: omega0 = %.10g rad/s, R_w = %.10g, R_m = %.10g, H = %.10g, h = %.10g, k = %.10g\n", w0,
         q.R_w, q.R_m, q.H, q.h, autobal_pendulum_k(&q));
  CHECK_STATUS("pendulum analyze", autobal_pendulum_analyze(pws, &q, &pr), AUTOBAL_SUCCESS);
  s = autobal_rotor_stab_alloc(&p, NULL, &err);
  CHECK("rotor stability handle", s != NULL);
  if (!s) {
    printf("   %s\n", err.message);
    return;
  }
  CHECK_STATUS("rotor analyze", autobal_rotor_stab_analyze(s, &rr), AUTOBAL_SUCCESS);
  CHECK("rotor: isotropic, closure, 12 closed roots, 12 full eigenvalues",
        rr.isotropic && rr.closure_ok && rr.n_closed == 12 && rr.n_poly == 13 && rr.n_full == 12);
  expected_roots(pc, &pr, w0, ere, eim);
  {
    size_t i;
    for (i = 0; i < 12; i++)
      printf("   expected root %2zu: %+.12e %+.12e i\n", i, ere[i], eim[i]);
  }
  d = set_distance(ere, eim, rr.root_re, rr.root_im);
  snprintf(what, sizeof what, "%s: roots of Delta == omega0 x pendulum (6) + tilt (relative)", pc->name);
  CHECK_CLOSE(what, d, 0.0, 0.0, 1e-9);
  d = set_distance(ere, eim, rr.closed_eig_re, rr.closed_eig_im);
  snprintf(what, sizeof what, "%s: eigenvalues of the closed matrix == the same", pc->name);
  CHECK_CLOSE(what, d, 0.0, 0.0, 1e-9);
  d = set_distance(ere, eim, rr.full_re, rr.full_im);
  snprintf(what, sizeof what, "%s: eigenvalues of the full model (two ball angles) == the same", pc->name);
  CHECK_CLOSE(what, d, 0.0, 0.0, 1e-9);
  snprintf(what, sizeof what, "%s: rotor margin == max(omega0 x pendulum max Re, tilt max Re)", pc->name);
  {
    double m = -INFINITY;
    size_t i;
    for (i = 0; i < 12; i++)
      if (ere[i] > m) m = ere[i];
    CHECK_CLOSE(what, rr.margin, m, 1e-8, 1e-9 * max_abs(12, ere, eim));
  }
  if (pc->h_s > 0 || pc->h_b > 0) {
    snprintf(what, sizeof what, "%s: verdicts agree (rotor %d, pendulum %d)", pc->name, rr.verdict,
             pr.verdict);
    CHECK(what, rr.verdict == pr.verdict);
  }
  /* the plane off the centre of mass couples tilt and translation: the sets differ */
  autobal_rotor_stab_free(s);
  p = rotor_of(pc, 0.05);
  s = autobal_rotor_stab_alloc(&p, NULL, &err);
  if (s && autobal_rotor_stab_analyze(s, &rr) == AUTOBAL_SUCCESS) {
    d = set_distance(ere, eim, rr.root_re, rr.root_im);
    snprintf(what, sizeof what, "%s: with d = 0.05 m the roots differ (relative distance %.3g > 1e-6)",
             pc->name, d);
    CHECK(what, d > 1e-6);
  } else {
    CHECK("d = 0.05 m: analysed", 0);
  }
  autobal_rotor_stab_free(s);
}

int main(void) {
  /* FULL inertia: exact (the balls' and the unbalance's translational inertia in M_s); PAPER:
   * exact too with M_s = M (its equations have the same form with M in place of M + m0 + 2m) */
  static const planar_case cases[] = {
      {"FULL, light balls (R_m 0.005), stable", AUTOBAL_ROTOR_INERTIA_FULL, 10.0, 0.16, 0.03, 2.5e5, 250.0,
       7375.0, 25.0, 0.05, 0.1, 0.1, 0.02, 0.1, 500.0},
      {"FULL, heavy balls (R_m 0.154), k near 0.23", AUTOBAL_ROTOR_INERTIA_FULL, 4.0, 0.1, 0.05, 6500.0,
       30.0, 3000.0, 5.0, 1.0, 0.1, 2.0, 0.5, 0.1, 100.0},
      {"FULL, heavy balls, unstable speed", AUTOBAL_ROTOR_INERTIA_FULL, 4.0, 0.1, 0.05, 6500.0, 30.0,
       3000.0, 5.0, 1.0, 0.1, 0.05, 0.5, 0.1, 45.0},
      {"FULL, k = 1 (m0 r0 = sqrt(2) m r), no damping", AUTOBAL_ROTOR_INERTIA_FULL, 4.0, 0.1, 0.05, 6500.0,
       0.0, 3000.0, 0.0, 1.0, 0.1, 0.0, 1.0, 0.1414213562373095, 80.0},
      {"PAPER, M_s = M = 10 kg, c = 1e4 N/m (omega0 = 31.62 rad/s)", AUTOBAL_ROTOR_INERTIA_PAPER, 10.0, 0.16,
       0.03, 1e4, 20.0, 7375.0, 25.0, 0.05, 0.1, 0.1, 0.02, 0.1, 62.0},
  };
  autobal_pendulum_workspace *pws = autobal_pendulum_workspace_alloc();
  size_t i;
  gsl_set_error_handler_off();
  for (i = 0; i < sizeof cases / sizeof cases[0]; i++) run_case(&cases[i], pws);
  autobal_pendulum_workspace_free(pws);
  return check_summary();
}
