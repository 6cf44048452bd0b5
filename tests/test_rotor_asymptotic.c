/* test_rotor_asymptotic.c: the asymptotic conditions of autobal_rotor_asymptotic_conditions
 * (autobal/rotor_asymptotic.h, docs/rotor.md "Asymptotic conditions") against the exact analysis
 * (roots of Delta, autobal_rotor_stab_analyze; Routh-Hurwitz verdicts and critical values) and
 * against closed forms written out here:
 *  - G = N(0)/D(0) against a direct solve of the 2x2 complex system K(i omega) z = (1, d) (paper and
 *    full inertia);
 * *  - light balls (masses scaled by 1e-4, kappa kept): the predicted ball and rotor roots against the
 *    exact roots (error within the small parameter), and the verdict, below the first resonance
 *    (predicted and exactly UNSTABLE), between the resonances and above them;
 *  - (L2): the exact critical ball damping (autobal_rotor_stab_critical over ball_damping) against
 *    kappa_min at 2000 rad/s for q = 0, and the verdicts at 0.8 and 1.25 kappa_min;
 *  - high speed: kappa_inf against the pendulum's (8) h > H sqrt(R_m) in dimensional form for the
 *    planar case (d = 0, no coupling), and against the exact critical damping at 2e4 rad/s;
 *    (H1): a disk-like rotor (0 < C - A < M d^2) unstable at high speed for any ball damping, stable
 *    once C - A > M d^2;
 *  - the measurement: the default rotor (kappa = 2 < kappa_inf) is unstable at 2000 rad/s
 *    for m0 r0 = sqrt(2) m r (q = 0) and stable for every unbalance with kappa = 1.5 kappa_inf;
 *  - anisotropic supports: G+ and G- against a real 8x8 solve of the fixed-frame response, the isotropic
 *    limit, light balls against the Floquet multipliers (verdict and margin);
 *  - error paths. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

typedef double complex cplx;

static autobal_rotor_lumped default_lumped(void) {
  autobal_rotor_lumped L;
  memset(&L, 0, sizeof L);
  L.M = 10.0, L.A = 0.16, L.C = 0.03;
  L.c_x = L.c_y = 2.5e5, L.c_z = 2e5, L.c_alpha = L.c_beta = 7375.0, L.c_xbeta = L.c_yalpha = -2500.0;
  L.h_x = L.h_y = 250.0, L.h_z = 200.0, L.h_alpha = L.h_beta = 7.375, L.h_xbeta = L.h_yalpha = -2.5;
  return L;
}

typedef struct setup {
  autobal_rotor_params p;
  double bm[2], br[2], bh[2];
} setup;

/* One plane at d with two balls of mass m on r = 0.1 m, ball damping rate kappa, unbalance s0 at
 * r0 = 0.1 m; lumped supports L; omega. */
static void make(setup *S, const autobal_rotor_lumped *L, double d, double m, double kappa, double s0, double w) {
  S->p = autobal_rotor_params_default();
  S->p.input = AUTOBAL_ROTOR_LUMPED;
  S->p.lumped = *L;
  S->p.omega = w;
  S->bm[0] = S->bm[1] = m;
  S->br[0] = S->br[1] = 0.1;
  S->bh[0] = S->bh[1] = kappa * m;
  S->p.plane[0].d = d;
  S->p.plane[0].r0 = 0.1;
  S->p.plane[0].m0 = s0 / 0.1;
  S->p.plane[0].ball_mass = S->bm;
  S->p.plane[0].ball_radius = S->br;
  S->p.plane[0].ball_damping = S->bh;
}

/* Exact analysis and the asymptotic conditions at S; returns the handle (caller frees) or NULL. */
static autobal_rotor_stab *run(setup *S, autobal_rotor_stab_result *res, autobal_rotor_asymptotic *q) {
  autobal_error err;
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_rotor_closed c;
  autobal_rotor_stab *h;
  int st;
  autobal_error_clear(&err);
  h = autobal_rotor_stab_alloc(&S->p, &o, &err);
  if (!h) {
    printf("FAIL alloc: %s\n", err.message);
    check_failures_++;
    return NULL;
  }
  if (res && (st = autobal_rotor_stab_analyze(h, res)) != 0) printf("analyze: %s\n", autobal_rotor_stab_errmsg(h));
  st = autobal_rotor_stab_closed(h, &c);
  if (!st) st = autobal_rotor_asymptotic_conditions(&c, q, &err);
  CHECK_STATUS("asymptotic conditions", st, AUTOBAL_SUCCESS);
  if (st) printf("     %s\n", err.message);
  return h;
}

/* G = (1, d) K^-1 (1, d)^T at P = i omega, by Cramer's rule on the 2x2 system (test's own). */
static cplx G_direct(const autobal_rotor_lumped *L, double d, double w, double m_add) {
  cplx P = I * w;
  cplx k11 = (L->M + m_add) * P * P + L->h_x * P + L->c_x;
  cplx k12 = -(L->h_xbeta * P + L->c_xbeta) + m_add * d * P * P;
  cplx k22 = (L->A + m_add * d * d) * P * P + (L->h_alpha - I * L->C * w) * P + L->c_alpha;
  cplx det = k11 * k22 - k12 * k12;
  cplx z1 = (1.0 * k22 - k12 * d) / det, z2 = (k11 * d - k12 * 1.0) / det;
  return z1 + d * z2;
}

/* largest |pred_i - nearest exact root| over n predictions */
static double match_err(const double *pr, const double *pi, size_t n, const autobal_rotor_stab_result *res) {
  double worst = 0.0;
  size_t i, j;
  for (i = 0; i < n; i++) {
    double best = INFINITY;
    for (j = 0; j < res->n_closed; j++) best = fmin(best, hypot(res->root_re[j] - pr[i], res->root_im[j] - pi[i]));
    worst = fmax(worst, best);
  }
  return worst;
}

static void test_G(void) {
  autobal_rotor_lumped L = default_lumped();
  const double ws[] = {100.0, 157.0, 237.0, 500.0, 3000.0};
  size_t k;
  for (k = 0; k < 5; k++) {
    setup S;
    autobal_rotor_stab_result res;
    autobal_rotor_asymptotic q;
    autobal_rotor_stab *h;
    cplx g = G_direct(&L, 0.1, ws[k], 0.0);
    char what[120];
    make(&S, &L, 0.1, 0.05, 2.0, 0.002, ws[k]);
    h = run(&S, &res, &q);
    snprintf(what, sizeof what, "G at %g rad/s vs the 2x2 solve: real part (m/N)", ws[k]);
    CHECK_CLOSE(what, q.G_re, creal(g), 1e-12, 1e-12 * cabs(g));
    snprintf(what, sizeof what, "G at %g rad/s vs the 2x2 solve: imaginary part (m/N)", ws[k]);
    CHECK_CLOSE(what, q.G_im, cimag(g), 1e-12, 1e-12 * cabs(g));
    autobal_rotor_stab_free(h);
    /* full inertia: the masses m0 + sum m_i sit at the plane */
    S.p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
    g = G_direct(&L, 0.1, ws[k], 0.002 / 0.1 + 0.1);
    h = run(&S, NULL, &q);
    snprintf(what, sizeof what, "G at %g rad/s, full inertia, vs the 2x2 solve (real part)", ws[k]);
    CHECK_CLOSE(what, q.G_re, creal(g), 1e-12, 1e-12 * cabs(g));
    CHECK("full inertia: no high-speed closed form", !q.high_defined);
    autobal_rotor_stab_free(h);
  }
}

/* light balls: roots and verdicts */
static void test_light(void) {
  autobal_rotor_lumped L = default_lumped();
  const double f = 1e-4, ws[] = {100.0, 150.0, 300.0, 404.0, 500.0, 2000.0};
  const int want_unstable[] = {1, 1, 0, 0, 0, 0};
  size_t k;
  for (k = 0; k < 6; k++) {
    setup S;
    autobal_rotor_stab_result res;
    autobal_rotor_asymptotic q;
    autobal_rotor_stab *h;
    double lmax = 0.0, e_ball, e_rot, rmax = 0.0;
    size_t i;
    char what[200];
    make(&S, &L, 0.1, 0.05 * f, 2.0, 0.002 * f, ws[k]);
    h = run(&S, &res, &q);
    for (i = 0; i < 4; i++) lmax = fmax(lmax, hypot(q.ball_re[i], q.ball_im[i]));
    for (i = 0; i < 4; i++) rmax = fmax(rmax, hypot(q.rotor_re[i], q.rotor_im[i]));
    e_ball = match_err(q.ball_re, q.ball_im, 4, &res);
    e_rot = match_err(q.rotor_re, q.rotor_im, 4, &res);
    printf("     omega %g: small %.3g, ball roots max |lambda| %.4g 1/s, error %.3g; rotor roots error %.3g; "
           "exact margin %.6g, predicted ball max Re %.6g, rotor max Re %.6g\n",
           ws[k], q.light_small, lmax, e_ball, e_rot, res.margin, fmax(fmax(q.ball_re[0], q.ball_re[1]),
           fmax(q.ball_re[2], q.ball_re[3])), q.rotor_re_max);
    snprintf(what, sizeof what, "omega %g, light balls: applicable and decided", ws[k]);
    CHECK(what, q.light_applicable && q.light_decided);
    snprintf(what, sizeof what, "omega %g: ball roots within small * max |ball root| of the exact roots", ws[k]);
    CHECK(what, e_ball <= q.light_small * lmax);
    snprintf(what, sizeof what, "omega %g: rotor roots within small^2 * |root| of the exact roots", ws[k]);
    CHECK(what, e_rot <= q.light_small * q.light_small * rmax + 1e-9 * rmax);
    snprintf(what, sizeof what, "omega %g: exact verdict %s", ws[k], want_unstable[k] ? "UNSTABLE" : "STABLE");
    CHECK(what, res.verdict == (want_unstable[k] ? AUTOBAL_VERDICT_UNSTABLE : AUTOBAL_VERDICT_STABLE));
    snprintf(what, sizeof what, "omega %g: the prediction equals the exact verdict", ws[k]);
    CHECK(what, q.light_stable == (res.verdict == AUTOBAL_VERDICT_STABLE));
    snprintf(what, sizeof what, "omega %g: (L1) supercritical iff Re G < 0 and iff above the first resonance here",
             ws[k]);
    CHECK(what, q.supercritical == !want_unstable[k]);
    autobal_rotor_stab_free(h);
  }
}

/* (L2): the damping threshold at q = 0 (m0 r0 = sqrt(2) m r) */
static void test_kappa_min(double w, const autobal_rotor_lumped *L, double d, double f) {
  setup S;
  autobal_rotor_stab_result res;
  autobal_rotor_asymptotic q;
  autobal_rotor_stab *h;
  autobal_rotor_crit cr;
  double m = 0.05 * f, s0 = sqrt(2.0) * m * 0.1, km, margin;
  int verdict, st;
  char what[200];
  make(&S, L, d, m, 1.0, s0, w);
  h = run(&S, &res, &q);
  km = q.kappa_min;
  printf("     omega %g, d %g, ball mass %g kg, q = %.3g: kappa_min %.8g 1/s, small %.3g, kappa_inf %.8g 1/s\n", w, d,
         m, q.q, km, q.light_small, q.kappa_inf);
  CHECK("q = 0 (balls at right angles)", q.q < 1e-12);
  CHECK("(L2) needs ball damping here (kappa_min > 0)", km > 0);
  st = autobal_rotor_stab_critical(h, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, 0.3 * km * m, 3.0 * km * m, 200, 1e-10, &cr);
  CHECK_STATUS("critical ball damping", st, AUTOBAL_SUCCESS);
  snprintf(what, sizeof what, "omega %g: one critical ball damping in [0.3, 3] kappa_min, stable above", w);
  CHECK(what, cr.n == 1 && cr.kind[0] == 1);
  if (cr.n >= 1) {
    snprintf(what, sizeof what, "omega %g: exact critical kappa vs kappa_min (relative tolerance = small parameter)",
             w);
    CHECK_CLOSE(what, cr.value[0] / m, km, q.light_small, 0.0);
  }
  autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, 0.8 * km * m);
  st = autobal_rotor_stab_margin(h, AUTOBAL_ROTOR_STAB_POLY, &margin, &verdict);
  snprintf(what, sizeof what, "omega %g: kappa = 0.8 kappa_min exactly UNSTABLE (margin %.4g)", w, margin);
  CHECK(what, st == 0 && verdict == AUTOBAL_VERDICT_UNSTABLE);
  autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, 1.25 * km * m);
  st = autobal_rotor_stab_margin(h, AUTOBAL_ROTOR_STAB_POLY, &margin, &verdict);
  snprintf(what, sizeof what, "omega %g: kappa = 1.25 kappa_min exactly STABLE (margin %.4g)", w, margin);
  CHECK(what, st == 0 && verdict == AUTOBAL_VERDICT_STABLE);
  autobal_rotor_stab_free(h);
}

static void test_high_speed(void) {
  autobal_rotor_lumped L = default_lumped(), Lp;
  setup S;
  autobal_rotor_asymptotic q;
  autobal_rotor_stab_result res;
  autobal_rotor_stab *h;
  autobal_rotor_crit cr;
  double w0, H, Rm, m = 0.05e-2, ginf, eta, kinf;
  int st;
  /* closed forms written out: g_inf = 1/M + d^2/(A - C), eta = h/M^2 - 2 d h_c/(M (A - C)) + d^2 h_t/(A - C)^2 */
  ginf = 1.0 / 10.0 + 0.01 / 0.13;
  eta = 250.0 / 100.0 - 2.0 * 0.1 * (-2.5) / (10.0 * 0.13) + 0.01 * 7.375 / (0.13 * 0.13);
  kinf = sqrt(0.5 * 0.1 * ginf) * eta / ginf;
  make(&S, &L, 0.1, 0.05, 2.0, 0.002, 500.0);
  h = run(&S, NULL, &q);
  CHECK_CLOSE("default rotor: m_eff = 1/(1/M + d^2/(A - C)) (kg)", q.m_eff, 1.0 / ginf, 1e-14, 0.0);
  CHECK_CLOSE("default rotor: kappa_inf (1/s) from the closed form", q.kappa_inf, kinf, 1e-14, 0.0);
  autobal_rotor_stab_free(h);
  /* the planar case is the pendulum: kappa_inf = omega0 H sqrt(R_m), (8) in dimensional form */
  Lp = L;
  Lp.c_xbeta = Lp.c_yalpha = 0.0, Lp.h_xbeta = Lp.h_yalpha = 0.0;
  make(&S, &Lp, 0.0, m, 1.0, sqrt(2.0) * m * 0.1, 2e4);
  h = run(&S, &res, &q);
  w0 = sqrt(Lp.c_x / Lp.M), H = Lp.h_x / (w0 * Lp.M), Rm = m / Lp.M;
  CHECK_CLOSE("d = 0: kappa_inf = omega0 H sqrt(R_m) (the pendulum's (8))", q.kappa_inf, w0 * H * sqrt(Rm), 1e-14, 0.0);
  st = autobal_rotor_stab_critical(h, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, 0.3 * q.kappa_inf * m, 3.0 * q.kappa_inf * m, 200,
                                   1e-10, &cr);
  CHECK("d = 0, 2e4 rad/s: one exact critical ball damping", st == 0 && cr.n == 1);
  if (cr.n == 1) CHECK_CLOSE("d = 0, 2e4 rad/s: exact critical kappa vs kappa_inf", cr.value[0] / m, q.kappa_inf, q.high_small, 0.0);
  autobal_rotor_stab_free(h);
  /* the default rotor with light balls at 2e4 rad/s */
  make(&S, &L, 0.1, m, 1.0, sqrt(2.0) * m * 0.1, 2e4);
  h = run(&S, &res, &q);
  printf("     default supports, d = 0.1 m, ball mass %g kg, 2e4 rad/s: kappa_inf %.8g 1/s, high_small %.3g\n", m,
         q.kappa_inf, q.high_small);
  CHECK("2e4 rad/s, light balls: high-speed condition applicable", q.high_applicable);
  st = autobal_rotor_stab_critical(h, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, 0.3 * q.kappa_inf * m, 3.0 * q.kappa_inf * m, 200,
                                   1e-10, &cr);
  CHECK("2e4 rad/s: one exact critical ball damping", st == 0 && cr.n == 1);
  if (cr.n == 1)
    CHECK_CLOSE("2e4 rad/s: exact critical kappa vs kappa_inf (relative tolerance = small parameter)", cr.value[0] / m,
                q.kappa_inf, q.high_small, 0.0);
  autobal_rotor_stab_free(h);
}

/* (H1): a disk-like rotor, C > A */
static void test_h1(void) {
  autobal_rotor_lumped L = default_lumped();
  const double m = 0.05e-3, ds[] = {0.1, 0.05};
  size_t k;
  L.C = 0.2; /* C - A = 0.04; M d^2 = 0.1 (d = 0.1) or 0.025 (d = 0.05) */
  for (k = 0; k < 2; k++) {
    setup S;
    autobal_rotor_asymptotic q;
    autobal_rotor_stab_result res;
    autobal_rotor_stab *h;
    const int h1 = (L.A - L.C) * (L.A - L.C + L.M * ds[k] * ds[k]) > 0;
    double kap;
    char what[200];
    make(&S, &L, ds[k], m, 1.0, 0.5 * m * 0.1, 5000.0);
    h = run(&S, NULL, &q);
    kap = 10.0 * (isfinite(q.kappa_inf) ? q.kappa_inf : 1.0);
    autobal_rotor_stab_free(h);
    make(&S, &L, ds[k], m, kap, 0.5 * m * 0.1, 5000.0);
    h = run(&S, &res, &q);
    printf("     C = 0.2 > A, d = %g: (H1) %d, kappa %g 1/s, exact margin %.6g, high_small %.3g, light_small %.3g\n", ds[k],
           h1, kap, res.margin, q.high_small, q.light_small);
    snprintf(what, sizeof what, "d = %g: (H1) (A - C)(A - C + M d^2) > 0 is %d: m_eff > 0 iff (H1)", ds[k], h1);
    CHECK(what, (q.m_eff > 0) == h1);
    snprintf(what, sizeof what, "d = %g, 5000 rad/s: high-speed prediction %s = exact verdict", ds[k],
             h1 ? "STABLE" : "UNSTABLE");
    CHECK(what, q.high_stable == h1 && res.verdict == (h1 ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE));
    snprintf(what, sizeof what, "d = %g: light-ball prediction agrees (decided)", ds[k]);
    CHECK(what, q.light_decided && q.light_stable == h1);
    autobal_rotor_stab_free(h);
  }
}

/* the default rotor's every-unbalance measurement of issue 17 */
static void test_default_rotor(void) {
  autobal_rotor_lumped L = default_lumped();
  setup S;
  autobal_rotor_asymptotic q;
  autobal_rotor_stab_result res;
  autobal_rotor_unbalance_range ur;
  autobal_rotor_stab *h;
  const double ws[] = {2000.0, 5000.0};
  double kinf;
  size_t k;
  make(&S, &L, 0.1, 0.05, 2.0, sqrt(2.0) * 0.05 * 0.1, 2000.0);
  h = run(&S, &res, &q);
  kinf = q.kappa_inf;
  printf("     default rotor, q = 0, 2000 rad/s: kappa 2 vs kappa_inf %.6g; exact margin %.6g\n", kinf, res.margin);
  CHECK("default rotor: kappa = 2 < kappa_inf: high speed predicts instability near q = 0", !q.high_stable);
  CHECK("default rotor, m0 r0 = sqrt(2) m r, 2000 rad/s: exactly UNSTABLE", res.verdict == AUTOBAL_VERDICT_UNSTABLE);
  autobal_rotor_stab_free(h);
  for (k = 0; k < 2; k++) {
    char what[200];
    int st;
    make(&S, &L, 0.1, 0.05, 1.5 * kinf, 0.002, ws[k]);
    h = run(&S, &res, &q);
    st = autobal_rotor_stab_every_unbalance(h, 1e-5, 0.0099, &ur);
    snprintf(what, sizeof what, "default rotor, kappa = 1.5 kappa_inf, %g rad/s: stable for every m0 r0 in [10, 9900] g mm",
             ws[k]);
    CHECK(what, st == 0 && ur.all_stable && q.high_stable);
    autobal_rotor_stab_free(h);
  }
}

/* kappa = 0 (undamped balls): to leading order the ball roots are on the axis (u0 real < 0) or in
 * +- pairs; the next order (docs/rotor.md "Asymptotic conditions", kappa = 0; tools/derive/derive_asymptotic2.py
 * check 6) moves them by the real delta = Re g1/2 +- (q^2 Re(g1 conj g0) - Im g0 Im g1)/(2r),
 * g(lambda) = (m_b/2) P^4 N / D = g0 + g1 lambda + ..., r = sqrt(q^2 |g0|^2 - Im^2 g0).  Written out here
 * and compared with the exact margin: undamped balls can be asymptotically stable (the disk-like case),
 * and are unstable at O(m_b) on the default rotor. */
static double kappa0_delta(const autobal_rotor_lumped *L, double d, double m, double q, double w) {
  cplx P = I * w, P4 = P * P * P * P, P3 = P * P * P;
  cplx k11 = L->M * P * P + L->h_x * P + L->c_x, k11d = 2.0 * L->M * P + L->h_x;
  cplx k12 = -(L->h_xbeta * P + L->c_xbeta), k12d = -L->h_xbeta;
  cplx k22 = L->A * P * P + (L->h_alpha - I * L->C * w) * P + L->c_alpha, k22d = 2.0 * L->A * P + (L->h_alpha - I * L->C * w);
  cplx D = k11 * k22 - k12 * k12, Dd = k11d * k22 + k11 * k22d - 2.0 * k12 * k12d;
  cplx N = k22 - 2.0 * d * k12 + d * d * k11, Nd = k22d - 2.0 * d * k12d + d * d * k11d;
  cplx X = P4 * N, Xd = 4.0 * P3 * N + P4 * Nd;
  cplx g0 = m * X / D, g1 = m * (Xd * D - X * Dd) / (D * D); /* m_b / 2 = m */
  double r = sqrt(q * q * cabs(g0) * cabs(g0) - cimag(g0) * cimag(g0)), b = q * q * creal(g1 * conj(g0)) - cimag(g0) * cimag(g1);
  CHECK("kappa = 0: u0 real (q |G| > |Im G|) and both u0 < 0 (roots on the axis to leading order)",
        q * cabs(g0) > fabs(cimag(g0)) && creal(g0) + r < 0.0);
  return fmax(0.5 * creal(g1) + b / (2.0 * r), 0.5 * creal(g1) - b / (2.0 * r));
}

/* The library's undamped entry (autobal_rotor_asymptotic_conditions at kappa = 0) at the machine S:
 * defined, on the axis or not as expected; on the axis its delta_(+-) equal the test's own formula
 * (kappa0_delta, through K' written out here) and the largest real part equals the exact margin
 * (roots of Delta); decided, applicable, and its verdict is the exact one. */
static void check_undamped(setup *S, const autobal_rotor_lumped *L, double d, double m, double q, double w, int on_axis,
                           int stable) {
  autobal_rotor_stab_result res;
  autobal_rotor_asymptotic a;
  autobal_rotor_stab *h = run(S, &res, &a);
  double mx = -INFINITY;
  size_t i;
  if (!h) return;
  for (i = 0; i < 4; i++) mx = fmax(mx, a.undamped_ball_re[i]);
  mx = fmax(mx, a.rotor_re_max);
  printf("     undamped entry at %g rad/s: on axis %d, delta %.9g %.9g, predicted max Re %.9g, exact margin %.9g, small %.3g\n",
         w, a.undamped_on_axis, a.undamped_delta[0], a.undamped_delta[1], mx, res.margin, a.undamped_small);
  CHECK("kappa = 0: undamped entry defined, light-ball entry not a condition",
        a.undamped_defined && !a.light_applicable && !a.light_decided && isnan(a.light_small));
  CHECK("kappa = 0: on the axis to leading order as expected", a.undamped_on_axis == on_axis);
  if (on_axis) {
    CHECK_CLOSE("kappa = 0: max delta = the test's own next-order formula", fmax(a.undamped_delta[0], a.undamped_delta[1]),
                kappa0_delta(L, d, m, q, w), 1e-9, 0.0);
    CHECK_CLOSE("kappa = 0: predicted largest real part = exact margin", mx, res.margin, 1e-3, 0.0);
  } else {
    CHECK("kappa = 0, off the axis: a predicted ball root with Re > 0 and the exact margin > 0", mx > 0.0 && res.margin > 0.0);
    CHECK_CLOSE("kappa = 0, off the axis: leading-order root vs exact margin (error O(sqrt m_b))", mx, res.margin, 0.05, 0.0);
  }
  CHECK("kappa = 0: decided and applicable", a.undamped_decided && a.undamped_applicable);
  CHECK("kappa = 0: predicted verdict = exact verdict", a.undamped_stable == (res.verdict == AUTOBAL_VERDICT_STABLE) &&
                                                            (res.verdict == AUTOBAL_VERDICT_STABLE) == stable);
  autobal_rotor_stab_free(h);
}

static void test_kappa0(void) {
  autobal_rotor_lumped Ld = default_lumped(), Lk = default_lumped();
  const double m = 5e-6, q = 0.9, x = sqrt((1.0 + q) / 2.0);
  setup S;
  autobal_rotor_stab_result res;
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_rotor_stab *h;
  autobal_error err;
  double dl;
  /* a disk-like rotor (C = 1.3 A), c_c = -1250 N/rad, d = -0.04 m, 4440 rad/s */
  Lk.C = 0.208, Lk.c_xbeta = Lk.c_yalpha = -1250.0;
  make(&S, &Lk, -0.04, m, 0.0, 2.0 * m * 0.1 * x, 4440.0);
  autobal_error_clear(&err);
  h = autobal_rotor_stab_alloc(&S.p, &o, &err);
  CHECK("kappa = 0: analysis allocated", h != NULL);
  if (!h) return;
  autobal_rotor_stab_analyze(h, &res);
  dl = kappa0_delta(&Lk, -0.04, m, q, 4440.0);
  printf("     kappa = 0, disk-like rotor, 4440 rad/s, q = 0.9: exact margin %.8g, next-order ball roots max Re %.8g 1/s\n",
         res.margin, dl);
  CHECK("kappa = 0, disk-like rotor: exactly asymptotically STABLE", res.verdict == AUTOBAL_VERDICT_STABLE);
  CHECK_CLOSE("kappa = 0, disk-like rotor: exact margin = next-order ball-root real part", res.margin, dl, 1e-3, 0.0);
  autobal_rotor_stab_free(h);
  check_undamped(&S, &Lk, -0.04, m, q, 4440.0, 1, 1);
  /* the default rotor at 500 rad/s: unstable at O(m_b) */
  make(&S, &Ld, 0.1, m, 0.0, 2.0 * m * 0.1 * x, 500.0);
  h = autobal_rotor_stab_alloc(&S.p, &o, &err);
  if (!h) return;
  autobal_rotor_stab_analyze(h, &res);
  dl = kappa0_delta(&Ld, 0.1, m, q, 500.0);
  printf("     kappa = 0, default rotor, 500 rad/s, q = 0.9: exact margin %.8g, next-order ball roots max Re %.8g 1/s\n",
         res.margin, dl);
  CHECK("kappa = 0, default rotor: exactly UNSTABLE", res.verdict == AUTOBAL_VERDICT_UNSTABLE);
  CHECK_CLOSE("kappa = 0, default rotor: exact margin = next-order ball-root real part", res.margin, dl, 1e-3, 0.0);
  autobal_rotor_stab_free(h);
  check_undamped(&S, &Ld, 0.1, m, q, 500.0, 1, 0);
  /* q = 0 (balls at right angles): q |G| < |Im G|, u complex, a root with Re of order sqrt(m_b) > 0 */
  make(&S, &Ld, 0.1, m, 0.0, sqrt(2.0) * m * 0.1, 2000.0);
  check_undamped(&S, &Ld, 0.1, m, 0.0, 2000.0, 0, 0);
}

/* G+ and G- by the test's own real route: the steady response X = Xc cos(w t) + Xs sin(w t) of the
 * fixed-frame rotor-housing (M, H, K of (3.2) without balls) to f_u = cos(w t), f_v = sin(w t)
 * (F = 1) at the plane, an 8x8 real solve; then u + i v = Wc cos + Ws sin = G+ e^{iwt} + G- e^{-iwt}. */
static void Gpm_real(const autobal_rotor_lumped *L, double d, double w, cplx *Gp, cplx *Gm) {
  const double Mm[4] = {L->M, L->M, L->A, L->A};
  const double H[4][4] = {{L->h_x, 0, 0, -L->h_xbeta}, {0, L->h_y, L->h_yalpha, 0},
                          {0, L->h_yalpha, L->h_alpha, L->C * w}, {-L->h_xbeta, 0, -L->C * w, L->h_beta}};
  const double K[4][4] = {{L->c_x, 0, 0, -L->c_xbeta}, {0, L->c_y, L->c_yalpha, 0},
                          {0, L->c_yalpha, L->c_alpha, 0}, {-L->c_xbeta, 0, 0, L->c_beta}};
  const double eu[4] = {1, 0, 0, d}, ev[4] = {0, 1, -d, 0};
  double A[8][9], x[8];
  cplx Wc = 0, Ws = 0;
  int i, j, k;
  memset(A, 0, sizeof A);
  for (i = 0; i < 4; i++) {
    for (j = 0; j < 4; j++) {
      double kk = K[i][j] - (i == j ? Mm[i] * w * w : 0.0);
      A[i][j] = kk, A[i][4 + j] = w * H[i][j];      /* cos rows: (K - M w^2) Xc + w H Xs = e_u */
      A[4 + i][4 + j] = kk, A[4 + i][j] = -w * H[i][j]; /* sin rows: (K - M w^2) Xs - w H Xc = e_v */
    }
    A[i][8] = eu[i], A[4 + i][8] = ev[i];
  }
  for (k = 0; k < 8; k++) {
    int p = k;
    for (i = k + 1; i < 8; i++)
      if (fabs(A[i][k]) > fabs(A[p][k])) p = i;
    for (j = 0; j < 9; j++) {
      double t = A[k][j];
      A[k][j] = A[p][j], A[p][j] = t;
    }
    for (i = k + 1; i < 8; i++) {
      double f = A[i][k] / A[k][k];
      for (j = k; j < 9; j++) A[i][j] -= f * A[k][j];
    }
  }
  for (k = 7; k >= 0; k--) {
    double t = A[k][8];
    for (j = k + 1; j < 8; j++) t -= A[k][j] * x[j];
    x[k] = t / A[k][k];
  }
  for (i = 0; i < 4; i++) Wc += (eu[i] + I * ev[i]) * x[i], Ws += (eu[i] + I * ev[i]) * x[4 + i];
  *Gp = Wc / 2.0 + Ws / (2.0 * I);
  *Gm = Wc / 2.0 - Ws / (2.0 * I);
}

/* Anisotropic supports (autobal/rotor_asymptotic.h "ANISOTROPIC"): G+ and G- against the real solve
 * above; the isotropic limit (the anisotropic route forced on isotropic supports gives the isotropic
 * entry's G, ball roots and rotor roots, G- = 0); light balls against the Floquet multipliers. */
static void test_aniso(void) {
  autobal_rotor_lumped L = default_lumped(), La = default_lumped();
  autobal_rotor_asymptotic qi, qa;
  autobal_rotor_closed c;
  autobal_rotor_stab_result res;
  autobal_error err;
  setup S;
  autobal_rotor_stab *h;
  const double ws[] = {120.0, 300.0, 1000.0, -800.0};
  size_t k;
  cplx Gp, Gm;
  /* y supports 1.6x stiffer on the left-right combination, damping unequal */
  La.c_y = 4.0e5, La.c_beta = 9000.0, La.c_yalpha = -4000.0, La.h_y = 400.0, La.h_beta = 10.0, La.h_yalpha = -4.0;
  for (k = 0; k < 4; k++) {
    double w = ws[k];
    make(&S, &La, 0.1, 1e-4, 2.0, 0.1 * 1e-4 * 0.1 * 2.0 * cos(0.6) / 0.1, w);
    h = run(&S, NULL, &qa);
    if (!h) continue;
    Gpm_real(&La, 0.1, w, &Gp, &Gm);
    CHECK("anisotropic: flagged", qa.anisotropic == 1);
    CHECK_CLOSE("anisotropic: G+ = the real 8x8 solve (real)", qa.G_re, creal(Gp), 1e-10, 0.0);
    CHECK_CLOSE("anisotropic: G+ = the real 8x8 solve (imag)", qa.G_im, cimag(Gp), 1e-9, 1e-12 * cabs(Gp));
    CHECK_CLOSE("anisotropic: G- = the real 8x8 solve (real)", qa.G_minus_re, creal(Gm), 1e-9, 1e-12 * cabs(Gp));
    CHECK_CLOSE("anisotropic: G- = the real 8x8 solve (imag)", qa.G_minus_im, cimag(Gm), 1e-9, 1e-12 * cabs(Gp));
    CHECK("anisotropic: G- is not negligible here", cabs(Gm) > 1e-3 * cabs(Gp));
    /* high speed: G+ -> -(1/m_eff + i h_eff / (m_eff^2 omega)) / omega^2 (the means of the x and y planes'
     * damping; tools/derive/derive_aniso_high.py): against the test's own real 8x8 solve at 1e6 rad/s */
    {
      const double wb = 1e6;
      cplx Gpb, Gmb;
      double ginf, eta;
      Gpm_real(&La, 0.1, wb, &Gpb, &Gmb);
      ginf = -wb * wb * creal(Gpb), eta = -wb * wb * wb * cimag(Gpb);
      CHECK("anisotropic: high-speed entries defined", qa.high_defined && isfinite(qa.kappa_inf));
      CHECK_CLOSE("anisotropic, high speed: 1/m_eff = -lim w^2 Re G+", 1.0 / qa.m_eff, ginf, 1e-6, 0.0);
      CHECK_CLOSE("anisotropic, high speed: h_eff / m_eff^2 = -lim w^3 Im G+", qa.h_eff / (qa.m_eff * qa.m_eff), eta,
                  1e-4, 0.0);
      CHECK_CLOSE("anisotropic, high speed: kappa_inf = sqrt(m_b/(2 m_eff)) h_eff / m_eff", qa.kappa_inf,
                  sqrt(0.5 * 2e-4 * ginf) * eta / ginf, 1e-4, 0.0);
      CHECK("anisotropic, high speed: G- = O(w^-3) (the stiffness of G+ only at w^-4)",
            cabs(Gmb) * wb * wb < 1e-4 * ginf);
    }
    autobal_rotor_stab_free(h);
  }
  /* isotropic limit: the anisotropic route on isotropic supports */
  make(&S, &L, 0.1, 1e-4, 2.0, 2.0 * 1e-4 * 0.1 * cos(0.6), 1000.0);
  h = run(&S, NULL, &qi);
  if (h) {
    autobal_error_clear(&err);
    autobal_rotor_stab_closed(h, &c);
    c.isotropic = 0;
    CHECK_STATUS("isotropic supports through the anisotropic route", autobal_rotor_asymptotic_conditions(&c, &qa, &err),
                 AUTOBAL_SUCCESS);
    CHECK_CLOSE("isotropic limit: G+ = G (real)", qa.G_re, qi.G_re, 1e-12, 0.0);
    CHECK_CLOSE("isotropic limit: G+ = G (imag)", qa.G_im, qi.G_im, 1e-11, 0.0);
    CHECK("isotropic limit: G- = 0", hypot(qa.G_minus_re, qa.G_minus_im) < 1e-12 * hypot(qi.G_re, qi.G_im));
    for (k = 0; k < 4; k++) {
      CHECK_CLOSE("isotropic limit: ball root (real)", qa.ball_re[k], qi.ball_re[k], 1e-10, 1e-14);
      CHECK_CLOSE("isotropic limit: ball root (imag)", qa.ball_im[k], qi.ball_im[k], 1e-10, 1e-14);
    }
    CHECK_CLOSE("isotropic limit: largest shifted rotor root real part", qa.rotor_re_max, qi.rotor_re_max, 1e-8, 0.0);
    CHECK("isotropic limit: same prediction", qa.light_stable == qi.light_stable);
    autobal_rotor_stab_free(h);
  }
  /* light balls against Floquet: stable (kappa 2 above kappa_min) and unstable (below the first resonance) */
  {
    const double wv[] = {1000.0, 1000.0, 150.0};
    const double kv[] = {2.0, 0.002, 2.0};
    for (k = 0; k < 3; k++) {
      double pred;
      size_t j;
      make(&S, &La, 0.1, 1e-5, kv[k], 2.0 * 1e-5 * 0.1 * cos(0.3), wv[k]);
      h = run(&S, &res, &qa);
      if (!h) continue;
      pred = qa.rotor_re_max;
      for (j = 0; j < 4; j++) pred = fmax(pred, qa.ball_re[j]);
      printf("     %g rad/s, kappa %g: Floquet margin %.9g, predicted %.9g (%s, small %.3g, decided %d)\n", wv[k], kv[k],
             res.margin, pred, qa.light_stable ? "STABLE" : "UNSTABLE", qa.light_small, qa.light_decided);
      CHECK("light balls, anisotropic: applicable", qa.light_applicable);
      if (k != 1) /* kappa 0.002: the ball roots' real part -kappa/2 is inside their error (undecided) */
        CHECK("light balls, anisotropic: decided", qa.light_decided);
      if (qa.light_decided)
        CHECK("light balls, anisotropic: the prediction = the Floquet verdict", qa.light_stable == (res.margin < 0.0));
      CHECK("light balls, anisotropic: max Re within 2 small parameters of the Floquet margin",
            fabs(pred - res.margin) <= 2.0 * qa.light_small * fabs(res.margin) + 1e-9);
      autobal_rotor_stab_free(h);
    }
  }
}

static void test_errors(void) {
  autobal_rotor_closed c;
  autobal_rotor_asymptotic q;
  autobal_error err;
  autobal_rotor_lumped L = default_lumped();
  setup S;
  autobal_rotor_stab *h;
  make(&S, &L, 0.1, 0.05, 2.0, 0.002, 500.0);
  h = run(&S, NULL, &q);
  autobal_rotor_stab_closed(h, &c);
  autobal_error_clear(&err);
  CHECK_STATUS("NULL closed system", autobal_rotor_asymptotic_conditions(NULL, &q, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("NULL output", autobal_rotor_asymptotic_conditions(&c, NULL, &err), AUTOBAL_EINVAL);
  c.isotropic = 0;
  c.plane[0].m_add = 0.1;
  CHECK_STATUS("anisotropic, full inertia", autobal_rotor_asymptotic_conditions(&c, &q, &err), AUTOBAL_EINVAL);
  printf("     message: %s\n", err.message);
  c.plane[0].m_add = 0.0;
  c.plane[0].kappa = 0.0;
  CHECK_STATUS("anisotropic, kappa = 0", autobal_rotor_asymptotic_conditions(&c, &q, &err), AUTOBAL_EINVAL);
  c.plane[0].kappa = 2.0;
  c.isotropic = 1;
  c.n_planes = 2;
  CHECK_STATUS("two planes", autobal_rotor_asymptotic_conditions(&c, &q, &err), AUTOBAL_EINVAL);
  c.n_planes = 1;
  c.plane[0].kappa = -1.0;
  CHECK_STATUS("negative ball damping", autobal_rotor_asymptotic_conditions(&c, &q, &err), AUTOBAL_EINVAL);
  printf("     message: %s\n", err.message);
  c.plane[0].kappa = 2.0;
  c.omega = 0.0;
  CHECK_STATUS("omega = 0", autobal_rotor_asymptotic_conditions(&c, &q, &err), AUTOBAL_EINVAL);
  autobal_rotor_stab_free(h);
}

int main(void) {
  autobal_rotor_lumped L = default_lumped();
  printf("== G = N(0)/D(0) ==\n");
  test_G();
  printf("== light balls: roots and verdicts ==\n");
  test_light();
  printf("== (L2): the critical ball damping ==\n");
  test_kappa_min(2000.0, &L, 0.1, 1e-3);
  test_kappa_min(500.0, &L, 0.1, 1e-3);
  printf("== high speed ==\n");
  test_high_speed();
  test_h1();
  printf("== the default rotor ==\n");
  test_default_rotor();
  printf("== kappa = 0 ==\n");
  test_kappa0();
  printf("== anisotropic supports ==\n");
  test_aniso();
  printf("== errors ==\n");
  test_errors();
  return check_summary();
}
