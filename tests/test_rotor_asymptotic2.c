/* test_rotor_asymptotic2.c: the two-plane light-ball condition of autobal_rotor_asymptotic2_conditions
 * (autobal/rotor_asymptotic.h, docs/rotor.md "Asymptotic conditions", "Two planes") against closed
 * forms written out here and the exact two-plane analysis (the closed 16x16 matrix of
 * autobal_rotor_stab_analyze):
 *  - G_jk = b_j^T K(i omega)^-1 b_k against Cramer's rule on the 2x2 complex system (and G12 = G21);
 *  - G12 = 0 (no coupling, h_t / h = -d1 d2, omega^2 = (c_t + d1 d2 c) / (A - C + d1 d2 M)): the eight ball
 *    roots are the roots of the two one-plane quartics (u - aG)(u - a conj G) = q^2 a^2 |G|^2 (written out
 *    here), and the ball verdict is the one-plane (L1)/(L2) of both planes;
 *  - light balls (masses scaled by 1e-3 .. 1e-5): the predicted ball and rotor roots against the exact
 *    16 roots (error within the small parameter, falling as the balls get lighter), the predicted
 *    verdict against the exact one below, between and above the resonances;
 *  - error paths. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"

#ifndef M_SQRT2
#define M_SQRT2 1.41421356237309504880
#endif

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
  double bm[2][2], br[2][2], bh[2][2];
} setup;

/* Two planes at d[j], two balls of mass m[j] on r = 0.1 m each, ball damping rate kap[j], unbalance
 * s0[j] (r0 = 0.1 m) at psi0[j]; lumped supports L; omega. */
static void make(setup *S, const autobal_rotor_lumped *L, const double *d, const double *m, const double *kap,
                 const double *s0, const double *psi0, double w) {
  size_t j;
  S->p = autobal_rotor_params_default();
  S->p.input = AUTOBAL_ROTOR_LUMPED;
  S->p.lumped = *L;
  S->p.omega = w;
  S->p.n_planes = 2;
  for (j = 0; j < 2; j++) {
    S->p.plane[j] = S->p.plane[0];
    S->bm[j][0] = S->bm[j][1] = m[j];
    S->br[j][0] = S->br[j][1] = 0.1;
    S->bh[j][0] = S->bh[j][1] = kap[j] * m[j];
    S->p.plane[j].d = d[j];
    S->p.plane[j].r0 = 0.1;
    S->p.plane[j].m0 = s0[j] / 0.1;
    S->p.plane[j].psi0 = psi0[j];
    S->p.plane[j].ball_mass = S->bm[j];
    S->p.plane[j].ball_radius = S->br[j];
    S->p.plane[j].ball_damping = S->bh[j];
    S->p.plane[j].ball_psi = NULL;
    S->p.plane[j].ball_rate = NULL;
  }
}

static autobal_rotor_stab *run(setup *S, autobal_rotor_stab_result *res, autobal_rotor_asymptotic2 *q) {
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
  if (!st) st = autobal_rotor_asymptotic2_conditions(&c, q, &err);
  CHECK_STATUS("two-plane asymptotic condition", st, AUTOBAL_SUCCESS);
  if (st) printf("     %s\n", err.message);
  return h;
}

/* G_jk = b_j^T K^-1 b_k at P = i omega by Cramer's rule (test's own) */
static cplx G_direct(const autobal_rotor_lumped *L, const double *d, int j, int k, double w) {
  cplx P = I * w;
  cplx k11 = L->M * P * P + L->h_x * P + L->c_x;
  cplx k12 = -(L->h_xbeta * P + L->c_xbeta);
  cplx k22 = L->A * P * P + (L->h_alpha - I * L->C * w) * P + L->c_alpha;
  cplx det = k11 * k22 - k12 * k12;
  cplx z1 = (1.0 * k22 - k12 * d[k]) / det, z2 = (k11 * d[k] - k12 * 1.0) / det;
  return z1 + d[j] * z2;
}

/* largest |pred_i - nearest exact root| over n predictions */
static double match_err(const double *pr, const double *pi, size_t n, const double *er, const double *ei, size_t ne) {
  double worst = 0.0;
  size_t i, j;
  for (i = 0; i < n; i++) {
    double best = INFINITY;
    for (j = 0; j < ne; j++) best = fmin(best, hypot(er[j] - pr[i], ei[j] - pi[i]));
    worst = fmax(worst, best);
  }
  return worst;
}

static void test_G(void) {
  autobal_rotor_lumped L = default_lumped();
  const double d[2] = {0.1, -0.12}, m[2] = {0.05, 0.04}, kap[2] = {2.0, 3.0}, s0[2] = {0.002, 0.0015},
               psi0[2] = {0.0, 2.0};
  const double ws[] = {100.0, 237.0, 500.0, 3000.0};
  size_t k;
  for (k = 0; k < 4; k++) {
    setup S;
    autobal_rotor_asymptotic2 q;
    autobal_rotor_stab *h;
    int a, b;
    make(&S, &L, d, m, kap, s0, psi0, ws[k]);
    h = run(&S, NULL, &q);
    for (a = 0; a < 2; a++)
      for (b = 0; b < 2; b++) {
        cplx g = G_direct(&L, d, a, b, ws[k]);
        char what[160];
        snprintf(what, sizeof what, "G_%d%d at %g rad/s vs the 2x2 solve (real part, m/N)", a + 1, b + 1, ws[k]);
        CHECK_CLOSE(what, q.G_re[2 * a + b], creal(g), 1e-12, 1e-12 * cabs(g));
        snprintf(what, sizeof what, "G_%d%d at %g rad/s vs the 2x2 solve (imaginary part, m/N)", a + 1, b + 1, ws[k]);
        CHECK_CLOSE(what, q.G_im[2 * a + b], cimag(g), 1e-12, 1e-12 * cabs(g));
      }
    CHECK("G symmetric", q.G_re[1] == q.G_re[2] && q.G_im[1] == q.G_im[2]);
    CHECK_CLOSE("q_1 = |2 x^2 - 1|, x = s0 / (2 m r)", q.q[0], fabs(2.0 * 0.04 - 1.0), 1e-12, 0.0);
    autobal_rotor_stab_free(h);
  }
}

/* G12 = 0: the two planes decouple into the one-plane quartics */
static void test_decoupled(void) {
  autobal_rotor_lumped L = default_lumped();
  /* q = 0 in both planes (m0 r0 = sqrt(2) m r): (L2) needs ball damping; 1e-4 1/s is too little */
  const double d[2] = {0.1, -0.1}, f = 1e-4, m[2] = {0.05 * f, 0.04 * f},
               s0[2] = {M_SQRT2 * 0.005 * f, M_SQRT2 * 0.004 * f}, psi0[2] = {0.3, 1.1};
  const double kaps[3][2] = {{2.0, 3.0}, {1e-4, 3.0}, {2.0, 1e-4}};
  double w;
  size_t t;
  L.c_xbeta = L.c_yalpha = 0.0, L.h_xbeta = L.h_yalpha = 0.0;
  L.h_alpha = L.h_beta = 2.5; /* h_t / h = 0.01 = -d1 d2 */
  w = sqrt((L.c_alpha + d[0] * d[1] * L.c_x) / (L.A - L.C + d[0] * d[1] * L.M));
  for (t = 0; t < 3; t++) {
    setup S;
    autobal_rotor_asymptotic2 q;
    autobal_rotor_stab *h;
    autobal_poly_workspace *pw = autobal_poly_workspace_alloc(4);
    double re[8], im[8], g11, qs[2];
    int j, ball_stable = 1;
    char what[200];
    make(&S, &L, d, m, kaps[t], s0, psi0, w);
    h = run(&S, NULL, &q);
    g11 = hypot(q.G_re[0], q.G_im[0]);
    snprintf(what, sizeof what, "omega %.6g rad/s: G12 = 0 (|G12| / |G11| = %.2e)", w,
             hypot(q.G_re[1], q.G_im[1]) / g11);
    CHECK(what, hypot(q.G_re[1], q.G_im[1]) <= 1e-12 * g11);
    for (j = 0; j < 2; j++) {
      cplx G = G_direct(&L, d, j, j, w);
      double x = s0[j] / (2.0 * m[j] * 0.1), qq = fabs(2.0 * x * x - 1.0), a = m[j] * pow(w, 4), kk = kaps[t][j];
      double Gr = creal(G), Gi = cimag(G), G2 = Gr * Gr + Gi * Gi;
      /* lambda^4 + 2 kappa lambda^3 + (kappa^2 - 2 a Re G) lambda^2 - 2 a kappa Re G lambda + a^2 |G|^2 (1 - q^2) */
      double cf[5] = {a * a * G2 * (1.0 - qq * qq), -2.0 * a * kk * Gr, kk * kk - 2.0 * a * Gr, 2.0 * kk, 1.0};
      qs[j] = qq;
      autobal_poly_roots(pw, cf, 5, re + 4 * j, im + 4 * j, NULL);
      /* (L1) and (L2) */
      ball_stable = ball_stable && Gr < 0.0 && kk * kk * (-Gr) > a * (Gi * Gi - qq * qq * G2);
    }
    {
      double e = match_err(q.ball_re, q.ball_im, 8, re, im, 8), e2 = match_err(re, im, 8, q.ball_re, q.ball_im, 8), mx = 0;
      size_t i;
      for (i = 0; i < 8; i++) mx = fmax(mx, hypot(re[i], im[i]));
      printf("     G12 = 0, kappa (%g, %g), q (%.3g, %.3g): ball roots vs the one-plane quartics %.2e (max |root| %.4g), "
             "(L1)/(L2) both planes %d, predicted ball max Re %.6g\n",
             kaps[t][0], kaps[t][1], qs[0], qs[1], fmax(e, e2), mx, ball_stable, q.ball_re_max);
      snprintf(what, sizeof what, "kappa (%g, %g): the 8 ball roots are the roots of the two one-plane quartics", kaps[t][0],
               kaps[t][1]);
      CHECK(what, fmax(e, e2) <= 1e-9 * mx);
      snprintf(what, sizeof what, "kappa (%g, %g): ball roots stable iff (L1), (L2) in both planes (%d)", kaps[t][0],
               kaps[t][1], ball_stable);
      CHECK(what, (q.ball_re_max < 0.0) == ball_stable);
    }
    if (t == 0) CHECK("kappa (2, 3): both planes satisfy (L1), (L2)", ball_stable);
    if (t > 0) CHECK("one plane with too little damping: (L2) fails", !ball_stable);
    autobal_poly_workspace_free(pw);
    autobal_rotor_stab_free(h);
  }
}

/* light balls against the exact 16 roots */
static void test_light(void) {
  autobal_rotor_lumped L = default_lumped();
  const double d[2] = {0.1, -0.12}, kap[2] = {2.0, 3.0}, psi0[2] = {0.0, 2.0};
  const double ws[] = {150.0, 800.0, 2000.0}, fs[] = {1e-3, 1e-4, 1e-5};
  size_t k, n;
  for (k = 0; k < 3; k++) {
    double prev = INFINITY;
    for (n = 0; n < 3; n++) {
      setup S;
      autobal_rotor_stab_result res;
      autobal_rotor_asymptotic2 q;
      autobal_rotor_stab *h;
      const double m[2] = {0.05 * fs[n], 0.04 * fs[n]}, s0[2] = {0.002 * fs[n], 0.0015 * fs[n]};
      double lmax = 0.0, e_ball, e_rot, rmax = 0.0, pm;
      size_t i;
      char what[200];
      make(&S, &L, d, m, kap, s0, psi0, ws[k]);
      h = run(&S, &res, &q);
      for (i = 0; i < 8; i++) lmax = fmax(lmax, hypot(q.ball_re[i], q.ball_im[i]));
      for (i = 0; i < 4; i++) rmax = fmax(rmax, hypot(q.rotor_re[i], q.rotor_im[i]));
      e_ball = match_err(q.ball_re, q.ball_im, 8, res.root_re, res.root_im, res.n_closed);
      e_rot = match_err(q.rotor_re, q.rotor_im, 4, res.root_re, res.root_im, res.n_closed);
      pm = fmax(q.ball_re_max, q.rotor_re_max);
      printf("     omega %g, balls x %g: small %.3g, ball roots error %.3g (max |root| %.4g), rotor roots error %.3g; "
             "exact margin %.8g, predicted %.8g (%s, decided %d)\n",
             ws[k], fs[n], q.light_small, e_ball, lmax, e_rot, res.margin, pm, q.light_stable ? "STABLE" : "UNSTABLE",
             q.light_decided);
      CHECK("16 exact roots", res.n_closed == 16);
      snprintf(what, sizeof what, "omega %g, balls x %g: %s", ws[k], fs[n],
               n == 0 ? "decided (balls too heavy to be applicable)" : "applicable and decided");
      CHECK(what, (n == 0 || q.light_applicable) && q.light_decided);
      snprintf(what, sizeof what, "omega %g, balls x %g: ball roots within small * max |ball root|", ws[k], fs[n]);
      CHECK(what, e_ball <= q.light_small * lmax);
      snprintf(what, sizeof what, "omega %g, balls x %g: rotor roots within small^2 * |root|", ws[k], fs[n]);
      CHECK(what, e_rot <= q.light_small * q.light_small * rmax + 1e-9 * rmax);
      snprintf(what, sizeof what, "omega %g, balls x %g: the prediction equals the exact verdict", ws[k], fs[n]);
      CHECK(what, q.light_stable == (res.verdict == AUTOBAL_VERDICT_STABLE) && res.verdict != AUTOBAL_VERDICT_MARGINAL);
      if (n > 0) {
        snprintf(what, sizeof what, "omega %g, balls x %g: predicted margin within small * |exact margin|", ws[k], fs[n]);
        CHECK(what, fabs(pm - res.margin) <= q.light_small * fabs(res.margin));
      }
      snprintf(what, sizeof what, "omega %g: below the first resonance unstable, above stable", ws[k]);
      CHECK(what, res.verdict == (ws[k] < 200.0 ? AUTOBAL_VERDICT_UNSTABLE : AUTOBAL_VERDICT_STABLE));
      snprintf(what, sizeof what, "omega %g, balls x %g: the ball roots' error falls as the balls get lighter", ws[k], fs[n]);
      CHECK(what, e_ball / lmax < prev);
      prev = e_ball / lmax;
      autobal_rotor_stab_free(h);
    }
  }
}

/* High speed, Q1 = Q2 = 0 (balls at right angles in both planes, balls 5e-6, 4e-6 kg, 1e5 rad/s): Gamma, H against w^2 G, w^3 Im G of the
 * test's own Cramer solve at 1e5 rad/s; the verdict just below and above max kappa_inf_k against the exact 16x16
 * verdict, and the predicted largest real part against the exact margin; with no cross receptance at high speed
 * (Gamma_12 = H_12 = 0: d1 d2 = -(A - C)/M, h_c = 0, h_t = h (A - C)/M) kappa_inf_k = the one-plane
 * sqrt(m_b/(2 m_eff)) h_eff/m_eff at d_k, written out here. */
static void test_high(void) {
  autobal_rotor_lumped L = default_lumped();
  const double d[2] = {0.1, -0.12}, m[2] = {5e-6, 4e-6}, psi[2] = {0.0, 0.0}, w = 1e5;
  double s0[2], kap[2] = {1.0, 1.0}, kstar;
  setup S;
  autobal_rotor_asymptotic2 q;
  autobal_rotor_stab_result res;
  autobal_rotor_stab *h;
  int j, k;
  for (j = 0; j < 2; j++) s0[j] = M_SQRT2 * m[j] * 0.1; /* Q_j = 0 */
  make(&S, &L, d, m, kap, s0, psi, w);
  h = run(&S, NULL, &q);
  if (!h) return;
  autobal_rotor_stab_free(h);
  CHECK("high speed: defined (paper inertia, A != C)", q.high_defined);
  for (j = 0; j < 2; j++)
    for (k = 0; k < 2; k++) {
      double W = 1e5;
      cplx G = G_direct(&L, d, j, k, W);
      CHECK_CLOSE("high speed: Gamma_jk = -lim w^2 Re G_jk", q.high_Gamma[2 * j + k], -W * W * creal(G), 1e-4, 0.0);
      CHECK_CLOSE("high speed: H_jk = -lim w^3 Im G_jk", q.high_H[2 * j + k], -W * W * W * cimag(G), 1e-3, 0.0);
    }
  kstar = fmax(q.high_kappa_inf[0], q.high_kappa_inf[1]);
  printf("     Q = 0, 1e5 rad/s: kappa_inf = %.6g, %.6g 1/s, small %.3g\n", q.high_kappa_inf[0], q.high_kappa_inf[1],
         q.high_small);
  {
    const double fac[2] = {0.8, 1.25};
    int i;
    for (i = 0; i < 2; i++) {
      double mx;
      kap[0] = kap[1] = fac[i] * kstar;
      make(&S, &L, d, m, kap, s0, psi, w);
      h = run(&S, &res, &q);
      if (!h) return;
      mx = fmax(q.high_re[0], q.high_re[1]);
      printf("     kappa = %.3g kappa_inf: predicted max Re %.9g, exact margin %.9g 1/s (small %.3g, decided %d)\n", fac[i],
             mx, res.margin, q.high_small, q.high_decided);
      CHECK("high speed, Q = 0: applicable and decided", q.high_applicable && q.high_decided);
      CHECK("high speed, Q = 0: predicted verdict = exact 16x16 verdict (unstable below kappa_inf, stable above)",
            q.high_stable == (i == 1) && (res.verdict == AUTOBAL_VERDICT_STABLE) == (i == 1));
      CHECK_CLOSE("high speed, Q = 0: predicted largest real part = exact margin", mx, res.margin, 0.05, 0.0);
      autobal_rotor_stab_free(h);
    }
  }
  /* every unbalance and phase: kappa_all = rho sqrt(mu_2) (test's own: rho from the 2x2 matrix Gamma^-1 H, mu_2
   * the larger eigenvalue of Mb^1/2 Gamma Mb^1/2); at min kappa = 1.05 kappa_all the exact 16x16
   * verdict is stable for unbalances with q_j in {0.1, 0.6, 0.95} and relative phases {0, 1, 2.5} rad */
  {
    const double *G = q.high_Gamma, *H = q.high_H;
    double dG = G[0] * G[3] - G[1] * G[2], Ri[4], tr, dt, rho, gt0, gt1, gt2, mu2, kall;
    const double qs[3] = {0.1, 0.6, 0.95}, ph[3] = {0.0, 1.0, 2.5};
    int a, b, nst = 0;
    Ri[0] = (G[3] * H[0] - G[1] * H[2]) / dG, Ri[1] = (G[3] * H[1] - G[1] * H[3]) / dG;
    Ri[2] = (G[0] * H[2] - G[2] * H[0]) / dG, Ri[3] = (G[0] * H[3] - G[2] * H[1]) / dG;
    tr = Ri[0] + Ri[3], dt = Ri[0] * Ri[3] - Ri[1] * Ri[2];
    rho = fmax(fabs(0.5 * tr + sqrt(fmax(0.0, 0.25 * tr * tr - dt))), fabs(0.5 * tr - sqrt(fmax(0.0, 0.25 * tr * tr - dt))));
    gt0 = 2.0 * m[0] * G[0], gt1 = 2.0 * sqrt(m[0] * m[1]) * G[1], gt2 = 2.0 * m[1] * G[3];
    mu2 = 0.5 * (gt0 + gt2) + hypot(0.5 * (gt0 - gt2), gt1);
    kall = rho * sqrt(mu2);
    CHECK_CLOSE("high speed, every unbalance: kappa_all = rho sqrt(mu_2)", q.high_every_kappa, kall, 1e-12, 0.0);
    CHECK("high speed, every unbalance: kappa_all >= sqrt(2) max kappa_inf (Q = 0)",
          q.high_every_kappa >= M_SQRT2 * kstar * (1.0 - 1e-12));
    printf("     every unbalance: kappa_all = %.6g 1/s (%.3f x max kappa_inf), small %.3g\n", q.high_every_kappa,
           q.high_every_kappa / kstar, q.high_every_small);
    /* the same kappa in both planes, then unequal (plane 2 three times plane 1's, then plane 1 three times plane
     * 2's): min kappa = 1.05 kappa_all each time */
    for (a = 0; a < 9 * 3; a++) {
      int c = a / 9;
      b = a % 9;
      kap[0] = (c == 2 ? 3.0 : 1.0) * 1.05 * kall, kap[1] = (c == 1 ? 3.0 : 1.0) * 1.05 * kall;
      {
        double s1[2], p2[2] = {0.0, ph[b % 3]};
        for (j = 0; j < 2; j++) s1[j] = 2.0 * m[j] * 0.1 * cos(0.5 * acos(qs[b / 3] * (j ? 0.7 : 1.0)));
        make(&S, &L, d, m, kap, s1, p2, w);
        h = run(&S, &res, &q);
        if (!h) return;
        nst += res.verdict == AUTOBAL_VERDICT_STABLE;
        CHECK("high speed, every unbalance: predicts STABLE, applicable", q.high_every_stable && q.high_every_applicable);
        autobal_rotor_stab_free(h);
      }
    }
    CHECK("high speed, every unbalance: 27 of 27 exact verdicts stable at min kappa = 1.05 kappa_all (equal and unequal kappa)",
          nst == 27);
    kap[0] = 0.95 * kall, kap[1] = 10.0 * kall;
    make(&S, &L, d, m, kap, s0, psi, w);
    h = run(&S, NULL, &q);
    if (!h) return;
    CHECK("high speed, every unbalance: min kappa < kappa_all: not claimed", !q.high_every_stable);
    autobal_rotor_stab_free(h);
  }
  /* no cross receptance at high speed: the one-plane kappa_inf in each plane */
  {
    double Ap = L.A - L.C, dd[2], kone;
    L.h_xbeta = L.h_yalpha = 0.0;
    L.h_alpha = L.h_beta = L.h_x * Ap / L.M;
    dd[0] = 0.1, dd[1] = -Ap / (L.M * 0.1);
    kap[0] = kap[1] = 1.0;
    make(&S, &L, dd, m, kap, s0, psi, w);
    h = run(&S, NULL, &q);
    if (!h) return;
    autobal_rotor_stab_free(h);
    CHECK("high speed, no cross receptance: Gamma_12 = H_12 = 0",
          fabs(q.high_Gamma[1]) < 1e-12 * q.high_Gamma[0] && fabs(q.high_H[1]) < 1e-12 * fabs(q.high_H[0]));
    for (j = 0; j < 2; j++) {
      double meff = 1.0 / (1.0 / L.M + dd[j] * dd[j] / Ap), mb = 2.0 * m[j];
      double heff = meff * meff * (L.h_x / (L.M * L.M) + dd[j] * dd[j] * L.h_alpha / (Ap * Ap));
      kone = sqrt(mb / (2.0 * meff)) * heff / meff;
      /* the modes are the planes; mu ascending, so match by value */
      CHECK_CLOSE("high speed, no cross receptance: kappa_inf = the one-plane kappa_inf of that plane",
                  fabs(q.high_kappa_inf[0] - kone) < fabs(q.high_kappa_inf[1] - kone) ? q.high_kappa_inf[0]
                                                                                    : q.high_kappa_inf[1],
                  kone, 1e-9, 0.0);
    }
  }
}

static void test_errors(void) {
  autobal_rotor_closed c;
  autobal_rotor_asymptotic2 q;
  autobal_error err;
  autobal_rotor_lumped L = default_lumped();
  const double d[2] = {0.1, -0.12}, m[2] = {0.05, 0.04}, kap[2] = {2.0, 3.0}, s0[2] = {0.002, 0.0015},
               psi0[2] = {0.0, 2.0};
  setup S;
  autobal_rotor_stab *h;
  make(&S, &L, d, m, kap, s0, psi0, 500.0);
  h = run(&S, NULL, &q);
  autobal_rotor_stab_closed(h, &c);
  autobal_error_clear(&err);
  CHECK_STATUS("NULL closed system", autobal_rotor_asymptotic2_conditions(NULL, &q, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("NULL output", autobal_rotor_asymptotic2_conditions(&c, NULL, &err), AUTOBAL_EINVAL);
  c.n_planes = 1;
  CHECK_STATUS("one plane", autobal_rotor_asymptotic2_conditions(&c, &q, &err), AUTOBAL_EINVAL);
  printf("     message: %s\n", err.message);
  c.n_planes = 2;
  c.plane[1].kappa = 0.0;
  CHECK_STATUS("no ball damping in plane 2", autobal_rotor_asymptotic2_conditions(&c, &q, &err), AUTOBAL_EINVAL);
  printf("     message: %s\n", err.message);
  CHECK("the message names plane 2", strstr(err.message, "plane 2") != NULL);
  c.plane[1].kappa = 3.0;
  c.omega = 0.0;
  CHECK_STATUS("omega = 0", autobal_rotor_asymptotic2_conditions(&c, &q, &err), AUTOBAL_EINVAL);
  autobal_rotor_stab_free(h);
}

int main(void) {
  printf("== G, two planes ==\n");
  test_G();
  printf("== G12 = 0: the one-plane quartics ==\n");
  test_decoupled();
  printf("== light balls against the exact 16 roots ==\n");
  test_light();
  printf("== high speed, Q = 0 ==\n");
  test_high();
  printf("== errors ==\n");
  test_errors();
  return check_summary();
}
