/* test_rotor_stability.c: balanced motions of the rotor with ball autobalancers and their
 * stability (docs/rotor.md (3.14)-(3.16), "Anisotropic supports"): members of the family,
 * the characteristic polynomial Delta against the formulas of docs/rotor.md evaluated directly, its
 * roots against three independent computations (closed first-order matrix, linearization
 * of the full model in rotating coordinates, Floquet multipliers), the linearization
 * against central differences of the model's own right-hand side, Routh-Hurwitz,
 * critical speeds, sweeps, maps (serial = parallel), natural frequencies and the
 * Campbell diagram against closed forms, the unbalance response, a short nonlinear
 * confirmation of the growth rate, and every error path. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>

#include "autobal.h"
#include "check.h"
#include "rotor_stab_internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double m3[3] = {0.05, 0.05, 0.05}, r3[3] = {0.1, 0.1, 0.1}, h3[3] = {0.1, 0.1, 0.1};
static double m4[4] = {0.03, 0.025, 0.02, 0.015}, r4[4] = {0.1, 0.1, 0.1, 0.1},
              h4[4] = {0.06, 0.05, 0.04, 0.03}; /* common h/m = 2 1/s */
static double m2b[2] = {0.04, 0.04}, r2b[2] = {0.09, 0.09}, h2b[2] = {0.4, 0.4}, h2a[2] = {0.5, 0.5};

static autobal_rotor_params three_balls(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.plane[0].n_balls = 3;
  p.plane[0].ball_mass = m3;
  p.plane[0].ball_radius = r3;
  p.plane[0].ball_damping = h3;
  p.plane[0].ball_psi = NULL;
  p.plane[0].ball_rate = NULL;
  return p;
}
static autobal_rotor_params four_balls(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.plane[0].n_balls = 4;
  p.plane[0].ball_mass = m4;
  p.plane[0].ball_radius = r4;
  p.plane[0].ball_damping = h4;
  p.plane[0].ball_psi = NULL;
  p.plane[0].ball_rate = NULL;
  return p;
}
static autobal_rotor_params two_planes(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.plane[0].ball_damping = h2a;
  p.n_planes = 2;
  p.plane[1] = p.plane[0];
  p.plane[1].d = -0.12;
  p.plane[1].m0 = 0.015;
  p.plane[1].r0 = 0.09;
  p.plane[1].psi0 = 2.0;
  p.plane[1].ball_mass = m2b;
  p.plane[1].ball_radius = r2b;
  p.plane[1].ball_damping = h2b;
  return p;
}
static autobal_rotor_params anisotropic(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.hw.c_Ly = 0.7e5;
  p.hw.h_Ry = 90.0;
  return p;
}

/* ---- members ------------------------------------------------------------------- */
static double residual(const autobal_rotor_plane *pl, const double *psi) {
  double sx = pl->m0 * pl->r0 * cos(pl->psi0), sy = pl->m0 * pl->r0 * sin(pl->psi0);
  size_t i;
  for (i = 0; i < pl->n_balls; i++) {
    sx += pl->ball_mass[i] * pl->ball_radius[i] * cos(psi[i]);
    sy += pl->ball_mass[i] * pl->ball_radius[i] * sin(psi[i]);
  }
  return hypot(sx, sy);
}

static void test_members(void) {
  autobal_rotor_params p = autobal_rotor_params_default(), q;
  double psi[4], ref[4], a = 0.7;
  autobal_rotor_member mem;
  autobal_error err;
  autobal_rotor *rot;
  size_t i;
  printf("-- members of the balanced family (3.14)\n");
  CHECK_STATUS("default member n=2", autobal_rotor_member_angles(&p.plane[0], NULL, psi, 2, &err), 0);
  /* (3.14): psi_1,2 = pi -/+ arccos(m0 r0 / (2 m r)) */
  CHECK_CLOSE("psi_1 = pi - arccos(s0/2mr) (wrapped)", psi[0], M_PI - acos(0.002 / 0.01), 1e-14, 0);
  CHECK_CLOSE("psi_2 = -(pi - arccos) (wrapped)", psi[1], -(M_PI - acos(0.002 / 0.01)), 1e-14, 0);
  /* n = 3, 4: the same members as autobal_rotor_balanced_angles of the model */
  q = three_balls();
  rot = autobal_rotor_alloc(&q, NULL);
  CHECK_STATUS("symmetric n=3", autobal_rotor_member_angles(&q.plane[0], NULL, psi, 3, NULL), 0);
  autobal_rotor_balanced_angles(rot, 0, ref, 3, NULL);
  for (i = 0; i < 3; i++) CHECK_CLOSE("n=3 member = rotor.h's balanced angles", psi[i], ref[i], 0, 1e-12);
  CHECK_CLOSE("n=3 member balances", residual(&q.plane[0], psi), 0, 0, 1e-15);
  autobal_rotor_free(rot);
  q = four_balls();
  rot = autobal_rotor_alloc(&q, NULL);
  CHECK_STATUS("default n=4 unequal", autobal_rotor_member_angles(&q.plane[0], NULL, psi, 4, NULL), 0);
  autobal_rotor_balanced_angles(rot, 0, ref, 4, NULL);
  for (i = 0; i < 4; i++) CHECK_CLOSE("n=4 member = rotor.h's balanced angles", psi[i], ref[i], 0, 1e-12);
  autobal_rotor_free(rot);
  /* FREE: ball 1 (and 2) where given, the rest balance */
  q = three_balls();
  mem.kind = AUTOBAL_ROTOR_MEMBER_FREE;
  mem.n_angles = 1;
  mem.angles = &a;
  CHECK_STATUS("free n=3", autobal_rotor_member_angles(&q.plane[0], &mem, psi, 3, NULL), 0);
  CHECK_CLOSE("free: ball 1 at the given angle", psi[0], 0.7, 0, 1e-15);
  CHECK_CLOSE("free: balances", residual(&q.plane[0], psi), 0, 0, 1e-15);
  /* GIVEN: accepted when balanced, refused otherwise */
  mem.kind = AUTOBAL_ROTOR_MEMBER_GIVEN;
  mem.n_angles = 3;
  mem.angles = psi;
  CHECK_STATUS("given balanced angles accepted", autobal_rotor_member_angles(&q.plane[0], &mem, ref, 3, NULL), 0);
  ref[3] = psi[2];
  psi[2] += 1e-3;
  CHECK_STATUS("given unbalanced angles refused", autobal_rotor_member_angles(&q.plane[0], &mem, ref, 3, &err), AUTOBAL_EINVAL);
  CHECK_MSG("message", err.message, "do not balance");
  psi[2] = ref[3];
  /* errors */
  q = four_balls();
  mem.kind = AUTOBAL_ROTOR_MEMBER_SYMMETRIC;
  CHECK_STATUS("symmetric with unequal balls", autobal_rotor_member_angles(&q.plane[0], &mem, psi, 4, &err), AUTOBAL_EINVAL);
  CHECK_MSG("message", err.message, "identical");
  mem.kind = AUTOBAL_ROTOR_MEMBER_FREE;
  mem.n_angles = 1;
  mem.angles = &a;
  CHECK_STATUS("free with a wrong count", autobal_rotor_member_angles(&q.plane[0], &mem, psi, 4, &err), AUTOBAL_EINVAL);
  CHECK_MSG("message", err.message, "n - 2");
  q = three_balls();
  a = M_PI; /* ball 1 opposite the unbalance: the last two cannot reach s0 + a = 0.007 > ... */
  {
    double far[1] = {0.0};   /* ball 1 on the heavy side: remaining target 0.002 + 0.005 = 0.007 <= 0.01: reachable */
    double m3h[3] = {0.05, 0.03, 0.03};
    autobal_rotor_params q2 = q;
    /* a = 0.005, 0.003, 0.003: balanced configurations exist, but with ball 1 on the heavy side
     * the last two must cancel 0.002 + 0.005 = 0.007 > 0.006 */
    q2.plane[0].ball_mass = m3h;
    mem.n_angles = 1;
    mem.angles = far;
    CHECK_STATUS("free: unreachable target for the last two", autobal_rotor_member_angles(&q2.plane[0], &mem, psi, 3, &err), AUTOBAL_EINVAL);
    CHECK_MSG("message", err.message, "cannot reach");
  }
  q = autobal_rotor_params_default();
  q.plane[0].m0 = 0.5; /* 0.05 kg m > 2 m r = 0.01 */
  CHECK_STATUS("no balanced configuration", autobal_rotor_member_angles(&q.plane[0], NULL, psi, 2, &err), AUTOBAL_EINVAL);
  CHECK_MSG("message", err.message, "no balanced configuration");
  CHECK_STATUS("wrong n", autobal_rotor_member_angles(&p.plane[0], NULL, psi, 3, NULL), AUTOBAL_EINVAL);
  mem.kind = 9;
  CHECK_STATUS("bad kind", autobal_rotor_member_angles(&p.plane[0], &mem, psi, 2, NULL), AUTOBAL_EINVAL);
}

/* ---- Delta against the spec's formulas evaluated directly ------------------------- */
static double complex conj_poly_eval(double complex (*f)(const autobal_rotor_closed *, double complex),
                                     const autobal_rotor_closed *c, double complex lam) {
  /* X*(lambda) = conj(X(conj(lambda))) */
  return conj(f(c, conj(lam)));
}
static double complex fK11(const autobal_rotor_closed *c, double complex P) {
  return (c->L.M + c->plane[0].m_add) * P * P + c->L.h_x * P + c->L.c_x;
}
static double complex fK22(const autobal_rotor_closed *c, double complex P) {
  const double d = c->plane[0].d;
  return (c->L.A + c->plane[0].m_add * d * d) * P * P + (c->L.h_alpha - I * c->L.C * c->omega) * P + c->L.c_alpha;
}
static double complex fK12(const autobal_rotor_closed *c, double complex P) {
  return -(c->L.h_xbeta * P + c->L.c_xbeta) + c->plane[0].m_add * c->plane[0].d * P * P;
}
static double complex fN(const autobal_rotor_closed *c, double complex lam) {
  const double complex P = lam + I * c->omega;
  const double d = c->plane[0].d;
  /* spec: N = (A P^2 + (h_t - i C w) P + c_t) + 2 d (h_c P + c_c) + d^2 (M P^2 + h P + c) */
  return (c->L.A * P * P + (c->L.h_alpha - I * c->L.C * c->omega) * P + c->L.c_alpha) +
         2.0 * d * (c->L.h_xbeta * P + c->L.c_xbeta) + d * d * (c->L.M * P * P + c->L.h_x * P + c->L.c_x);
}
static double complex fF(const autobal_rotor_closed *c, double complex lam) {
  const double complex P = lam + I * c->omega;
  const double complex D = fK11(c, P) * fK22(c, P) - fK12(c, P) * fK12(c, P);
  return (lam * lam + c->plane[0].kappa * lam) * D - 0.5 * c->plane[0].mass * cpow(P, 4) * fN(c, lam);
}
static double complex delta_direct(const autobal_rotor_closed *c, double complex lam) {
  const double complex P = lam + I * c->omega, Pb = lam - I * c->omega;
  const double q = hypot(c->plane[0].Q_re, c->plane[0].Q_im);
  return fF(c, lam) * conj_poly_eval(fF, c, lam) -
         0.25 * q * q * cpow(P, 4) * cpow(Pb, 4) * fN(c, lam) * conj_poly_eval(fN, c, lam);
}

static void test_char_poly(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab *s;
  autobal_rotor_closed c;
  double coef[13], cerr[13];
  static const double lams[4][2] = {{-3.0, 150.0}, {10.0, -420.0}, {-50.0, 700.0}, {0.5, 0.0}};
  int v;
  printf("-- Delta: polynomial arithmetic vs the spec's formulas evaluated directly\n");
  for (v = 0; v < 2; v++) {
    size_t k;
    p.inertia = v ? AUTOBAL_ROTOR_INERTIA_FULL : AUTOBAL_ROTOR_INERTIA_PAPER;
    s = autobal_rotor_stab_alloc(&p, NULL, NULL);
    CHECK_STATUS("closed system", autobal_rotor_stab_closed(s, &c), 0);
    CHECK("isotropic default", c.isotropic == 1 && c.closure_ok == 1);
    CHECK_CLOSE("kappa = h/m", c.plane[0].kappa, 0.1 / 0.05, 1e-15, 0);
    CHECK_STATUS("char poly", autobal_rotor_char_poly(&c, coef, cerr, NULL), 0);
    for (k = 0; k < 4; k++) {
      double re, im;
      double complex lam = lams[k][0] + I * lams[k][1], want = delta_direct(&c, lam);
      autobal_poly_eval_complex(coef, 13, lams[k][0], lams[k][1], &re, &im);
      CHECK_CLOSE(v ? "Delta(lambda) FULL inertia: Re" : "Delta(lambda): Re", re, creal(want), 0, 1e-11 * cabs(want));
      CHECK_CLOSE(v ? "Delta(lambda) FULL inertia: Im" : "Delta(lambda): Im", im, cimag(want), 0, 1e-11 * cabs(want));
    }
    /* Delta(0) = w^8 |N(0)|^2 (m_b^2 - |Q|^2) / 4 (F(0) = -(m_b/2) w^4 N(0)) */
    {
      const double w = c.omega, q = hypot(c.plane[0].Q_re, c.plane[0].Q_im);
      const double n0 = cabs(fN(&c, 0.0));
      CHECK_CLOSE("Delta(0) closed form", coef[0], pow(w, 8) * n0 * n0 * (c.plane[0].mass * c.plane[0].mass - q * q) / 4.0, 1e-12, 0);
    }
    /* leading coefficient: (A M - m_b (A + d^2 M)/2 - ...)^2 for PAPER: F's leading term is
     * A M - (m_b/2)(A + d^2 M), Delta's = that^2 - (|Q|/2)^2 (A + d^2 M)^2 */
    if (!v) {
      const double d = c.plane[0].d, An = c.L.A + d * d * c.L.M, q = hypot(c.plane[0].Q_re, c.plane[0].Q_im);
      const double f12 = c.L.A * c.L.M - 0.5 * c.plane[0].mass * An;
      CHECK_CLOSE("Delta leading coefficient", coef[12], f12 * f12 - 0.25 * q * q * An * An, 1e-13, 0);
    }
    {
      int ok = 1;
      for (k = 0; k < 13; k++) ok &= isfinite(cerr[k]) && cerr[k] >= 0.0;
      CHECK("coefficient error bounds finite and non-negative", ok);
    }
    autobal_rotor_stab_free(s);
  }
  /* error paths */
  CHECK_STATUS("char_poly NULL", autobal_rotor_char_poly(NULL, coef, NULL, NULL), AUTOBAL_EINVAL);
  {
    autobal_rotor_params q = two_planes();
    autobal_error err;
    s = autobal_rotor_stab_alloc(&q, NULL, NULL);
    autobal_rotor_stab_closed(s, &c);
    CHECK_STATUS("char_poly two planes", autobal_rotor_char_poly(&c, coef, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("message", err.message, "closed matrix");
    autobal_rotor_stab_free(s);
    q = anisotropic();
    s = autobal_rotor_stab_alloc(&q, NULL, NULL);
    autobal_rotor_stab_closed(s, &c);
    CHECK("anisotropic detected", c.isotropic == 0);
    CHECK_STATUS("char_poly anisotropic", autobal_rotor_char_poly(&c, coef, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("message", err.message, "isotropic");
    {
      double a[256];
      CHECK_STATUS("closed matrix anisotropic", autobal_rotor_closed_matrix(&c, a, 12, NULL), AUTOBAL_EINVAL);
      c.isotropic = 1;
      CHECK_STATUS("closed matrix wrong dim", autobal_rotor_closed_matrix(&c, a, 13, NULL), AUTOBAL_EINVAL);
    }
    autobal_rotor_stab_free(s);
  }
}

/* ---- roots, eigenvalues, full model, Floquet at several points -------------------- */
static void analyze_case(const char *name, const autobal_rotor_params *p, size_t fam_want,
                         int want_method) {
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(p, NULL, NULL);
  autobal_rotor_stab_result r;
  char buf[160];
  int st;
  if (!s) {
    CHECK("alloc", 0);
    return;
  }
  st = autobal_rotor_stab_analyze(s, &r);
  snprintf(buf, sizeof buf, "%s: analyze", name);
  CHECK_STATUS(buf, st, 0);
  snprintf(buf, sizeof buf, "%s: method", name);
  CHECK(buf, r.method == want_method);
  snprintf(buf, sizeof buf, "%s: family dimension", name);
  CHECK(buf, r.n_family == fam_want);
  if (r.n_closed > 0) {
    snprintf(buf, sizeof buf, "%s: roots of Delta vs eigenvalues of the closed matrix (relative)", name);
    CHECK_CLOSE(buf, r.root_eig_mismatch, 0, 0, 1e-10);
  }
  if (r.n_full > 0 && r.n_closed > 0) {
    snprintf(buf, sizeof buf, "%s: full-model roots = closed roots + 0^(n-2) + (-kappa)^(n-2)", name);
    CHECK_CLOSE(buf, r.full_mismatch, 0, 0, 1e-10);
    snprintf(buf, sizeof buf, "%s: full margin = closed margin", name);
    CHECK_CLOSE(buf, r.full_margin, r.closed_margin, 0, 1e-9 * 700);
  }
  if (r.n_full > 0) {
    snprintf(buf, sizeof buf, "%s: Floquet multipliers = exp(lambda T) of the full roots", name);
    CHECK_CLOSE(buf, r.floquet_mismatch, 0, 0, 1e-8);
    snprintf(buf, sizeof buf, "%s: Floquet margin = full margin", name);
    CHECK_CLOSE(buf, r.floquet_margin, r.full_margin, 0, 1e-7);
  }
  if (r.n_poly) {
    /* Routh-Hurwitz count of right-half-plane roots = count from the roots */
    int nr = 0;
    size_t i;
    for (i = 0; i < 12; i++) nr += r.root_re[i] > 0.0;
    snprintf(buf, sizeof buf, "%s: Routh-Hurwitz verdict = roots' verdict", name);
    CHECK(buf, r.hurwitz_verdict == r.verdict);
    snprintf(buf, sizeof buf, "%s: Routh-Hurwitz sign changes = roots with Re > 0", name);
    CHECK(buf, r.hurwitz_n_rhp == nr);
  }
  autobal_rotor_stab_free(s);
}

static void test_cross_checks(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  double w;
  printf("-- roots vs eigenvalues vs full model vs Floquet\n");
  for (w = 100.0; w <= 900.0; w += 200.0) {
    char nm[64];
    p.omega = w;
    snprintf(nm, sizeof nm, "n=2, omega=%g", w);
    analyze_case(nm, &p, 0, AUTOBAL_ROTOR_STAB_POLY);
  }
  p = autobal_rotor_params_default();
  p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  analyze_case("n=2 FULL inertia", &p, 0, AUTOBAL_ROTOR_STAB_POLY);
  p = three_balls();
  analyze_case("n=3 symmetric", &p, 1, AUTOBAL_ROTOR_STAB_POLY);
  p.omega = 300;
  analyze_case("n=3 symmetric, omega 300", &p, 1, AUTOBAL_ROTOR_STAB_POLY);
  p = four_balls();
  analyze_case("n=4 unequal masses, common h/m", &p, 2, AUTOBAL_ROTOR_STAB_POLY);
  p = two_planes();
  analyze_case("two planes", &p, 0, AUTOBAL_ROTOR_STAB_CLOSED);
  p = anisotropic();
  analyze_case("anisotropic", &p, 0, AUTOBAL_ROTOR_STAB_FLOQUET);
  /* unequal h/m: no closure; the full model decides */
  {
    static double hu[2] = {0.1, 0.3};
    p = autobal_rotor_params_default();
    p.plane[0].ball_damping = hu;
    analyze_case("unequal h/m (no closure)", &p, 0, AUTOBAL_ROTOR_STAB_FULL);
  }
  /* n = 2 without unbalance: the balanced pair is diametrically opposite and may turn as a
   * whole (a one-parameter family, rank 1): the closure of (3.16) does not apply, Delta(0) = 0
   * (|Q| = m_b), and the full model decides with one neutral root excluded */
  {
    autobal_rotor_stab *s;
    autobal_rotor_closed c;
    double coef[13];
    p = autobal_rotor_params_default();
    p.plane[0].m0 = 0.0;
    analyze_case("n=2, m0 = 0 (the pair can turn)", &p, 1, AUTOBAL_ROTOR_STAB_FULL);
    s = autobal_rotor_stab_alloc(&p, NULL, NULL);
    autobal_rotor_stab_closed(s, &c);
    CHECK("m0 = 0: closure not applicable (rank 1)", c.closure_ok == 0 && c.plane[0].rank == 1);
    autobal_rotor_char_poly(&c, coef, NULL, NULL);
    CHECK_CLOSE("m0 = 0: Delta(0) = 0 (|Q| = m_b)", coef[0], 0, 0, 1e-12 * fabs(coef[1]) * 500.0);
    autobal_rotor_stab_free(s);
  }
  /* n=3: explicitly n-2 = 1 root at 0 and one at -kappa among the full roots */
  {
    autobal_rotor_stab *s;
    autobal_rotor_stab_result r;
    size_t i, nz = 0, nk = 0;
    p = three_balls();
    s = autobal_rotor_stab_alloc(&p, NULL, NULL);
    autobal_rotor_stab_analyze(s, &r);
    for (i = 0; i < r.n_full; i++) {
      if (hypot(r.full_re[i], r.full_im[i]) < 1e-8) nz++;
      if (hypot(r.full_re[i] + 2.0, r.full_im[i]) < 1e-8) nk++;
    }
    CHECK("n=3: exactly one zero root in the full model", nz == 1);
    CHECK("n=3: a root -h/m = -2 in the full model", nk >= 1);
    /* and a Floquet multiplier 1 (the family) */
    nz = 0;
    for (i = 0; i < r.n_floquet; i++) nz += hypot(r.mu_re[i] - 1.0, r.mu_im[i]) < 1e-8;
    CHECK("n=3: one Floquet multiplier equal to 1", nz == 1);
    autobal_rotor_stab_free(s);
  }
  /* the limit of vanishing balls: roots of Delta -> rotor modes seen from the rotating frame
   * (fixed-frame eigenvalues s shifted by -i w: P = s) and 0, 0, -kappa, -kappa */
  {
    static double mt[2] = {1e-9, 1e-9}, ht[2] = {2e-9, 2e-9};
    autobal_rotor_stab *s;
    autobal_rotor_closed c;
    double coef[13], re[12], im[12], f[4], g[4], wre[12], wim[12], dist = 0;
    int wv[4];
    autobal_poly_workspace *pw = autobal_poly_workspace_alloc(12);
    size_t k;
    p = autobal_rotor_params_default();
    p.plane[0].ball_mass = mt;
    p.plane[0].ball_damping = ht;
    p.plane[0].m0 = 1e-10; /* keeps 0 < m0 r0 = 1e-11 < 2 m r = 2e-10 */
    p.omega = 350.0;
    s = autobal_rotor_stab_alloc(&p, NULL, NULL);
    CHECK_STATUS("light balls: closed system", autobal_rotor_stab_closed(s, &c), 0);
    CHECK_STATUS("light balls: Delta", autobal_rotor_char_poly(&c, coef, NULL, NULL), 0);
    {
      /* roots in s = lambda / 300 (coefficients scaled like the library does) */
      double cs[13], pw3 = 1.0;
      for (k = 0; k < 13; k++) {
        cs[k] = coef[k] * pw3;
        pw3 *= 300.0;
      }
      CHECK_STATUS("roots", autobal_poly_roots(pw, cs, 13, re, im, NULL), 0);
      for (k = 0; k < 12; k++) {
        re[k] *= 300.0;
        im[k] *= 300.0;
      }
    }
    autobal_rotor_modes(&p, 350.0, 0, f, NULL, g, wv, NULL);
    for (k = 0; k < 4; k++) {
      /* fixed-frame complex-form root g + i f (forward) or g - i f (backward), seen in the
       * rotating frame: minus i w; and the conjugate (from D*) */
      const double fs = wv[k] == 1 ? f[k] : -f[k];
      wre[2 * k] = g[k];
      wim[2 * k] = fs - 350.0;
      wre[2 * k + 1] = g[k];
      wim[2 * k + 1] = -(fs - 350.0);
    }
    wre[8] = wre[9] = 0.0;
    wim[8] = wim[9] = wim[10] = wim[11] = 0.0;
    wre[10] = wre[11] = -2.0;
    autobal_match_roots(12, re, im, wre, wim, NULL, &dist, NULL);
    CHECK_CLOSE("light balls: Delta's roots -> rotor modes - i w, 0, 0, -kappa, -kappa", dist, 0, 0, 1e-3);
    autobal_poly_workspace_free(pw);
    autobal_rotor_stab_free(s);
  }
}

/* ---- the linearization against the model's own Jacobian ------------------------ */
static void lin_case(const char *name, const autobal_rotor_params *p) {
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(p, NULL, NULL);
  autobal_rotor *r = autobal_rotor_alloc(p, NULL);
  size_t N = autobal_rotor_stab_n_balls(s), ns = 8 + 2 * N, i, k;
  double *A = malloc(ns * ns * sizeof *A), *J = malloc(ns * ns * sizeof *J), *y = calloc(ns, sizeof *y),
         *work = malloc(3 * ns * sizeof *work), *psi = malloc(N * sizeof *psi);
  double t, worst = 0.0, amax = 0.0;
  char buf[160];
  autobal_rotor_stab_balanced_angles(s, psi, N);
  for (t = 0.0; t < 0.02; t += 0.0047) {
    memset(y, 0, ns * sizeof *y);
    for (i = 0; i < N; i++) y[8 + i] = psi[i];
    if (autobal_rotor_model_jacobian(r, t, y, J, ns, work) != 0 ||
        autobal_rotor_stab_linearization(s, t, 0, A, ns) != 0) {
      CHECK("jacobians computed", 0);
      break;
    }
    for (k = 0; k < ns * ns; k++) {
      worst = fmax(worst, fabs(J[k] - A[k]));
      amax = fmax(amax, fabs(A[k]));
    }
  }
  /* central differences with h = 1e-6 of a function whose only nonlinearity at the
   * balanced state is through sin/cos of the ball angles (and rate^2 terms, exact for
   * central differences): truncation ~ h^2 |f'''| / 6 ~ 1e-12 relative, rounding ~ 1e-10 */
  snprintf(buf, sizeof buf, "%s: analytic linearization vs central differences of rhs_rotating (rel. to max |A| = %.3g)", name, amax);
  CHECK_CLOSE(buf, worst / amax, 0, 0, 1e-9);
  free(A);
  free(J);
  free(y);
  free(work);
  free(psi);
  autobal_rotor_free(r);
  autobal_rotor_stab_free(s);
}

static void test_linearization(void) {
  autobal_rotor_params p;
  printf("-- linearization vs the model's finite-difference Jacobian\n");
  p = autobal_rotor_params_default();
  lin_case("default", &p);
  p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  lin_case("FULL inertia", &p);
  p = anisotropic();
  lin_case("anisotropic", &p);
  p = two_planes();
  lin_case("two planes", &p);
  p = four_balls();
  lin_case("four balls", &p);
}

/* ---- Floquet for anisotropic supports against finite-difference columns ------------ */
static void test_floquet_fd(void) {
  autobal_rotor_params p = anisotropic();
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  autobal_rotor *r = autobal_rotor_alloc(&p, NULL);
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_system sys;
  autobal_eigen_workspace *ew = autobal_eigen_workspace_alloc(12);
  double mu_re[12], mu_im[12], Mfd[144], Mfl[144], fre[12], fim[12], psi[2], T, dist = 1, scale[12];
  size_t j, i;
  printf("-- Floquet (anisotropic): variational equations vs columns of the nonlinear flow\n");
  o.rtol = 1e-12;
  o.atol = 1e-16;
  tr = autobal_transient_alloc(12, &o, NULL);
  sys.rhs = autobal_rotor_rhs_rotating;
  sys.jac = NULL;
  sys.dim = 12;
  sys.params = r;
  T = 2.0 * M_PI / p.omega;
  autobal_rotor_stab_balanced_angles(s, psi, 2);
  CHECK_STATUS("floquet", autobal_rotor_stab_floquet(s, mu_re, mu_im, 12, Mfl), 0);
  /* state scales: displacements ~1e-3 m, angles ~1e-2 rad, ball angles 1 */
  for (j = 0; j < 12; j++) scale[j] = j < 2 ? 1e-3 : (j < 4 ? 1e-2 : (j < 8 ? 0.5 : (j < 10 ? 1.0 : 500.0)));
  for (j = 0; j < 4; j++) scale[4 + j] = scale[j] * 500.0;
  for (j = 0; j < 12; j++) {
    double yp[12] = {0}, ym[12] = {0}, h = 1e-5 * scale[j];
    yp[8] = ym[8] = psi[0];
    yp[9] = ym[9] = psi[1];
    yp[j] += h;
    ym[j] -= h;
    autobal_transient_run(tr, &sys, 0.0, T, yp, NULL);
    autobal_transient_run(tr, &sys, 0.0, T, ym, NULL);
    for (i = 0; i < 12; i++) Mfd[i * 12 + j] = (yp[i] - ym[i]) / (2.0 * h);
  }
  {
    double worst = 0.0;
    for (i = 0; i < 12; i++)
      for (j = 0; j < 12; j++)
        worst = fmax(worst, fabs(Mfd[i * 12 + j] - Mfl[i * 12 + j]) * scale[j] / scale[i]);
    /* central differences of a flow: truncation ~ (1e-5)^2 of the scaled state; integration 1e-12 */
    CHECK_CLOSE("monodromy vs finite-difference columns of the nonlinear flow (scaled)", worst, 0, 0, 1e-6);
  }
  autobal_eigen_nonsymm(ew, Mfd, fre, fim, NULL);
  autobal_match_roots(12, mu_re, mu_im, fre, fim, NULL, &dist, NULL);
  CHECK_CLOSE("Floquet multipliers vs eigenvalues of the finite-difference monodromy", dist, 0, 0, 1e-6);
  CHECK("anisotropic default at 500 rad/s: |mu| < 1", hypot(mu_re[0], mu_im[0]) < 1.0);
  autobal_eigen_workspace_free(ew);
  autobal_transient_free(tr);
  autobal_rotor_free(r);
  autobal_rotor_stab_free(s);
}

/* ---- critical speeds, sweeps and maps -------------------------------------------- */
static int hurwitz_rhp(autobal_rotor_stab *s, double w) {
  autobal_rotor_closed c;
  double coef[13], cs[13], pw = 1.0;
  int v, n = -1;
  size_t k;
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w);
  autobal_rotor_stab_closed(s, &c);
  autobal_rotor_char_poly(&c, coef, NULL, NULL);
  for (k = 0; k < 13; k++) {
    cs[k] = coef[k] * pw;
    pw *= 300.0;
  }
  autobal_poly_hurwitz(cs, 13, 1e-13, &v, &n, NULL);
  return n;
}

static void test_critical(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  autobal_rotor_crit c;
  size_t k;
  printf("-- critical speeds of the default example\n");
  CHECK_STATUS("critical", autobal_rotor_stab_critical(s, AUTOBAL_ROTOR_PARAM_OMEGA, 20.0, 1500.0, 300, 1e-9, &c), 0);
  CHECK("at least one critical speed", c.n >= 1);
  CHECK("not truncated (flag 0 in the normal case)", c.truncated == 0);
  CHECK("omega restored", autobal_rotor_stab_get(s, AUTOBAL_ROTOR_PARAM_OMEGA) == 500.0);
  for (k = 0; k < c.n; k++) {
    /* independent: the Routh-Hurwitz count of right-half-plane roots changes across it */
    const double lo = c.value[k] * (1.0 - 1e-6), hi = c.value[k] * (1.0 + 1e-6);
    int nlo = hurwitz_rhp(s, lo), nhi = hurwitz_rhp(s, hi), v;
    double mg;
    printf("   critical speed %.12g rad/s kind %d: RH count %d -> %d\n", c.value[k], c.kind[k], nlo, nhi);
    CHECK("Routh-Hurwitz count changes across the critical speed", nlo != nhi);
    CHECK("kind matches the Hurwitz counts", (c.kind[k] == 1) == (nhi == 0));
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, c.value[k]);
    autobal_rotor_stab_margin(s, 0, &mg, &v);
    CHECK_CLOSE("margin ~ 0 at the critical speed", mg, 0, 0, 1e-5);
  }
  CHECK("the last stable interval reaches the end of the range", c.n_stable >= 1 && c.stable_hi[c.n_stable - 1] == 1500.0);
  CHECK("500 rad/s is in a stable interval", c.n_stable >= 1 && c.stable_lo[c.n_stable - 1] < 500.0);
  /* stable intervals contain stable points only (their midpoints) */
  for (k = 0; k < c.n_stable; k++) {
    double mg;
    int v;
    autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, 0.5 * (c.stable_lo[k] + c.stable_hi[k]));
    autobal_rotor_stab_margin(s, 0, &mg, &v);
    CHECK("midpoint of a stable interval is stable", v == AUTOBAL_VERDICT_STABLE);
  }
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, 500.0);
  /* a sweep in ball mass crosses to "no balanced configuration" below m r = m0 r0 / 2 */
  {
    double vals[4] = {0.005, 0.0099, 0.0101, 0.05}, mg[4];
    int vd[4];
    CHECK_STATUS("sweep ball mass", autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_BALL_MASS, vals, 4, mg, vd), 0);
    CHECK("no balanced configuration below m = m0 r0 / (2 r) = 0.01 kg", vd[0] == AUTOBAL_ROTOR_VERDICT_NONE && vd[1] == AUTOBAL_ROTOR_VERDICT_NONE && isnan(mg[0]));
    CHECK("balanced configuration above", vd[2] != AUTOBAL_ROTOR_VERDICT_NONE && vd[3] == AUTOBAL_VERDICT_STABLE);
    CHECK_STATUS("critical ball mass", autobal_rotor_stab_critical(s, AUTOBAL_ROTOR_PARAM_BALL_MASS, 0.005, 0.05, 20, 1e-10, &c), 0);
    CHECK("existence boundary found", c.n >= 1 && c.kind[0] == 0);
    if (c.n >= 1) CHECK_CLOSE("existence boundary at m = m0 r0 / (2 r)", c.value[0], 0.01, 1e-8, 0);
  }
  /* errors */
  CHECK_STATUS("critical lo >= hi", autobal_rotor_stab_critical(s, 0, 5.0, 5.0, 10, 1e-8, &c), AUTOBAL_EINVAL);
  CHECK_STATUS("critical omega range through 0", autobal_rotor_stab_critical(s, 0, -5.0, 5.0, 10, 1e-8, &c), AUTOBAL_EINVAL);
  CHECK_MSG("message", autobal_rotor_stab_errmsg(s), "must not contain 0");
  CHECK_STATUS("critical n_grid 1", autobal_rotor_stab_critical(s, 0, 5.0, 50.0, 1, 1e-8, &c), AUTOBAL_EINVAL);
  CHECK_STATUS("critical xtol 0", autobal_rotor_stab_critical(s, 0, 5.0, 50.0, 10, 0.0, &c), AUTOBAL_EINVAL);
  CHECK_STATUS("critical bad param", autobal_rotor_stab_critical(s, 42, 5.0, 50.0, 10, 1e-8, &c), AUTOBAL_EINVAL);
  CHECK_STATUS("critical NULL", autobal_rotor_stab_critical(s, 0, 5.0, 50.0, 10, 1e-8, NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("sweep NULL", autobal_rotor_stab_sweep(s, 0, NULL, 3, NULL, NULL), AUTOBAL_EINVAL);
  autobal_rotor_stab_free(s);
}

static void test_map(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  double w[9], h[5], m1[45], m2[45], sm[9];
  int v1[45], v2[45], sv[9], same = 1;
  size_t i, j;
  autobal_error err;
  autobal_rotor_stab *s;
  printf("-- map omega x ball damping: serial = parallel = sweeps\n");
  for (i = 0; i < 9; i++) w[i] = 150.0 + 60.0 * (double)i;
  for (j = 0; j < 5; j++) h[j] = 0.02 + 0.2 * (double)j;
  CHECK_STATUS("map 1 thread", autobal_rotor_stab_map(&p, NULL, 0, w, 9, 1, h, 5, 1, m1, v1, &err), 0);
  CHECK_STATUS("map 2 threads", autobal_rotor_stab_map(&p, NULL, 0, w, 9, 1, h, 5, 2, m2, v2, &err), 0);
  for (i = 0; i < 45; i++) same &= memcmp(&m1[i], &m2[i], sizeof m1[i]) == 0 && v1[i] == v2[i];
  CHECK("map identical with 1 and 2 threads (bitwise)", same);
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, h[3]);
  autobal_rotor_stab_sweep(s, 0, w, 9, sm, sv);
  same = 1;
  for (i = 0; i < 9; i++) same &= memcmp(&sm[i], &m1[i * 5 + 3], sizeof sm[i]) == 0 && sv[i] == v1[i * 5 + 3];
  CHECK("a map column equals a sweep", same);
  CHECK("ball damping restored... set by the test", autobal_rotor_stab_get(s, 1) == h[3]);
  autobal_rotor_stab_free(s);
  CHECK_STATUS("map same parameters", autobal_rotor_stab_map(&p, NULL, 0, w, 9, 0, h, 5, 1, m1, v1, &err), AUTOBAL_EINVAL);
  CHECK_MSG("message", err.message, "must differ");
  CHECK_STATUS("map NULL arrays", autobal_rotor_stab_map(&p, NULL, 0, NULL, 9, 1, h, 5, 1, m1, v1, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("map bad param", autobal_rotor_stab_map(&p, NULL, 0, w, 9, 17, h, 5, 1, m1, v1, &err), AUTOBAL_EINVAL);
  /* a point that fails (omega = 0) stops the map with a message naming the point */
  w[4] = 0.0;
  CHECK_STATUS("map with omega = 0 at a point", autobal_rotor_stab_map(&p, NULL, 0, w, 9, 1, h, 5, 2, m1, v1, &err), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("message names the point", err.message, "omega = 0");
}

/* ---- natural frequencies, Campbell diagram, unbalance response ------------------------ */
static void test_campbell(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_lumped L;
  double f[4], z[4], g[4];
  int wv[4];
  size_t k;
  printf("-- natural frequencies and Campbell diagram\n");
  autobal_rotor_lumped_from_hardware(&p.hw, &L, NULL);
  CHECK_STATUS("modes at rest, undamped", autobal_rotor_modes(&p, 0.0, 1, f, z, g, wv, NULL), 0);
  {
    /* closed form: (c - M nu^2)(c_t - A nu^2) = c_c^2, both 2x2 blocks identical (isotropic) */
    const double a = L.M * L.A, b = -(L.c_x * L.A + L.c_alpha * L.M), c = L.c_x * L.c_alpha - L.c_xbeta * L.c_xbeta;
    const double disc = sqrt(b * b - 4 * a * c), n1 = sqrt((-b - disc) / (2 * a)), n2 = sqrt((-b + disc) / (2 * a));
    CHECK_CLOSE("1st natural frequency (closed form)", f[0], n1, 1e-12, 0);
    CHECK_CLOSE("1st natural frequency, double", f[1], n1, 1e-12, 0);
    CHECK_CLOSE("2nd natural frequency (closed form)", f[2], n2, 1e-12, 0);
    CHECK_CLOSE("2nd natural frequency, double", f[3], n2, 1e-12, 0);
    CHECK_CLOSE("spec: 157.5323 rad/s", f[0], 157.5323, 0, 5e-5);
    CHECK_CLOSE("spec: 215.1217 rad/s", f[2], 215.1217, 0, 5e-5);
    for (k = 0; k < 4; k++) CHECK_CLOSE("undamped: zero damping ratio", z[k], 0, 0, 1e-12);
  }
  CHECK_STATUS("modes at rest, damped", autobal_rotor_modes(&p, 0.0, 0, f, z, g, wv, NULL), 0);
  for (k = 0; k < 4; k++) {
    CHECK("damped: positive damping ratio below 1", z[k] > 0 && z[k] < 1);
    CHECK_CLOSE("zeta = -Re/|lambda|", z[k], -g[k] / hypot(g[k], f[k]), 1e-14, 0);
  }
  /* gyroscopic splitting, undamped, isotropic: (c - M nu^2)(c_t - A nu^2 + C w nu) = c_c^2;
   * nu > 0 forward whirl, nu < 0 backward */
  {
    const double w = 400.0;
    double coef[5], re[4], im[4], fwd[2], bwd[2];
    size_t nf = 0, nb = 0;
    autobal_poly_workspace *pw = autobal_poly_workspace_alloc(4);
    coef[0] = L.c_x * L.c_alpha - L.c_xbeta * L.c_xbeta;
    coef[1] = L.c_x * L.C * w;
    coef[2] = -(L.c_x * L.A + L.M * L.c_alpha);
    coef[3] = -L.M * L.C * w;
    coef[4] = L.M * L.A;
    autobal_poly_roots(pw, coef, 5, re, im, NULL);
    for (k = 0; k < 4; k++) {
      if (re[k] > 0 && nf < 2) fwd[nf++] = re[k];
      else if (re[k] < 0 && nb < 2) bwd[nb++] = -re[k];
    }
    CHECK("quartic has two forward and two backward roots", nf == 2 && nb == 2);
    autobal_rotor_modes(&p, w, 1, f, z, g, wv, NULL);
    for (k = 0; k < 4; k++) {
      double want = NAN;
      size_t q;
      for (q = 0; q < 2; q++) {
        if (wv[k] == 1 && fabs(fwd[q] - f[k]) < 1e-6 * f[k]) want = fwd[q];
        if (wv[k] == -1 && fabs(bwd[q] - f[k]) < 1e-6 * f[k]) want = bwd[q];
      }
      CHECK_CLOSE("gyroscopic frequency = root of the quartic with the right whirl", f[k], want, 1e-10, 0);
    }
    autobal_poly_workspace_free(pw);
  }
  /* Campbell diagram = modes at each speed; negative speed mirrors the whirl */
  {
    double om[3] = {0.0, 250.0, -250.0}, F[12], Z[12];
    int W[12];
    CHECK_STATUS("campbell", autobal_rotor_campbell(&p, om, 3, F, Z, W, NULL), 0);
    autobal_rotor_modes(&p, 250.0, 0, f, z, g, wv, NULL);
    for (k = 0; k < 4; k++) {
      CHECK_CLOSE("campbell row = modes", F[4 + k], f[k], 1e-15, 0);
      CHECK_CLOSE("omega -> -omega: same frequencies", F[8 + k], f[k], 1e-12, 0);
      CHECK("omega -> -omega: whirl relative to the spin unchanged", W[8 + k] == wv[k]);
    }
    CHECK_STATUS("campbell NULL omega", autobal_rotor_campbell(&p, NULL, 3, F, Z, W, NULL), AUTOBAL_EINVAL);
    om[1] = NAN;
    CHECK_STATUS("campbell NaN omega", autobal_rotor_campbell(&p, om, 3, F, Z, W, NULL), AUTOBAL_EINVAL);
  }
  /* unbalance response against the isotropic 2-dof complex closed form (forward whirl only):
   * [K11(i w), K12; K12, K22(i w)] [Z0; T0] = w^2 s0 [1; d] */
  {
    const double w = 180.0, d = 0.1, s0 = 0.002;
    double complex s = I * w;
    double complex k11 = L.M * s * s + L.h_x * s + L.c_x, k22 = L.A * s * s + (L.h_alpha - I * L.C * w) * s + L.c_alpha;
    double complex k12 = -(L.h_xbeta * s + L.c_xbeta), det = k11 * k22 - k12 * k12;
    double complex Z0 = w * w * s0 * (k22 - d * k12) / det, T0 = w * w * s0 * (k11 * d - k12) / det;
    double aG, aD[1];
    CHECK_STATUS("unbalance response", autobal_rotor_unbalance_response(&p, w, &aG, aD, NULL), 0);
    CHECK_CLOSE("|Z0| of the closed form", aG, cabs(Z0), 1e-12, 0);
    CHECK_CLOSE("amplitude at the plane |Z0 + d Theta0|", aD[0], cabs(Z0 + d * T0), 1e-12, 0);
  }
  /* resonance speeds: natural frequency = omega there; peak is a local maximum */
  {
    autobal_rotor_resonances rr;
    autobal_error err;
    CHECK_STATUS("resonances", autobal_rotor_resonance_speeds(&p, 1.0, 1000.0, 400, 1e-10, &rr, NULL), 0);
    CHECK("four crossings (two forward, two backward)", rr.n_cross == 4);
    CHECK("resonance lists not truncated (flag 0)", rr.truncated == 0);
    for (k = 0; k < rr.n_cross; k++) {
      autobal_rotor_modes(&p, rr.cross[k], 0, f, NULL, NULL, wv, NULL);
      CHECK_CLOSE("freq(omega_c) = omega_c", f[rr.cross_mode[k]], rr.cross[k], 1e-9, 0);
    }
    CHECK("at least one peak", rr.n_peak >= 1);
    for (k = 0; k < rr.n_peak; k++) {
      double a0, a1, a2;
      autobal_rotor_unbalance_response(&p, rr.peak[k], &a0, NULL, NULL);
      autobal_rotor_unbalance_response(&p, rr.peak[k] * (1 - 1e-5), &a1, NULL, NULL);
      autobal_rotor_unbalance_response(&p, rr.peak[k] * (1 + 1e-5), &a2, NULL, NULL);
      CHECK("peak is a local maximum of the response", a0 >= a1 && a0 >= a2);
      CHECK("peak near a forward crossing", fabs(rr.peak[k] - rr.cross[1]) < 0.05 * rr.cross[1] || fabs(rr.peak[k] - rr.cross[3]) < 0.05 * rr.cross[3]);
    }
    CHECK_STATUS("resonances bad range", autobal_rotor_resonance_speeds(&p, 10.0, 1.0, 400, 1e-10, &rr, &err), AUTOBAL_EINVAL);
    CHECK_STATUS("resonances n_grid", autobal_rotor_resonance_speeds(&p, 1.0, 10.0, 2, 1e-10, &rr, &err), AUTOBAL_EINVAL);
    CHECK_STATUS("resonances xtol", autobal_rotor_resonance_speeds(&p, 1.0, 10.0, 20, 0.0, &rr, &err), AUTOBAL_EINVAL);
  }
  /* undamped resonance: singular */
  {
    autobal_rotor_params q = p;
    autobal_error err;
    double aG;
    q.hw.h_Lx = q.hw.h_Ly = q.hw.h_Rx = q.hw.h_Ry = 0.0;
    q.hw.C_p = 0.0;
    {
      /* the lower natural frequency from the closed form (c - M nu^2)(c_t - A nu^2) = c_c^2 */
      const double a = L.M * L.A, b = -(L.c_x * L.A + L.c_alpha * L.M), c = L.c_x * L.c_alpha - L.c_xbeta * L.c_xbeta;
      const double n1 = sqrt((-b - sqrt(b * b - 4 * a * c)) / (2 * a));
      CHECK_STATUS("undamped response at resonance is singular", autobal_rotor_unbalance_response(&q, n1, &aG, NULL, &err), AUTOBAL_ENUMERIC);
    }
    CHECK_MSG("message", err.message, "resonance");
    q.hw.M_k = -1;
    CHECK_STATUS("modes bad params", autobal_rotor_modes(&q, 0.0, 1, f, NULL, NULL, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("message names the parameter", err.message, "M_k");
  }
}

/* ---- nonlinear confirmation (short) ------------------------------------------------- */
typedef struct obs_ctx {
  autobal_rotor *r;
  double period;
  double t[4096], s[4096];
  size_t n;
} obs_ctx;

static int obs(double t, const double y[], void *user) {
  obs_ctx *o = (obs_ctx *)user;
  double s4[4];
  autobal_rotor_plane_unbalance(o->r, 0, AUTOBAL_ROTOR_ROTATING, t, y, s4);
  if (o->n < 4096) {
    o->t[o->n] = t;
    o->s[o->n] = hypot(s4[2], s4[3]);
    o->n++;
  }
  return 0;
}

/* Growth rate of |sigma| measured along a nonlinear transient started on the dominant
 * eigenvector of the rotating-coordinate linearization (see test_rotor_stability_slow.c
 * for the reasoning). Returns the fitted rate and the predicted one in *pred. */
static double measure_rate(const autobal_rotor_params *p, double t_end, double *pred) {
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(p, NULL, NULL);
  autobal_rotor *r = autobal_rotor_alloc(p, NULL);
  const size_t N = autobal_rotor_stab_n_balls(s), ns = 8 + 2 * N;
  gsl_matrix *A = gsl_matrix_alloc(ns, ns);
  gsl_vector_complex *ev = gsl_vector_complex_alloc(ns);
  gsl_matrix_complex *evec = gsl_matrix_complex_alloc(ns, ns);
  gsl_eigen_nonsymmv_workspace *w = gsl_eigen_nonsymmv_alloc(ns);
  double *a = malloc(ns * ns * sizeof *a), *y = calloc(ns, sizeof *y), *psi = malloc(N * sizeof *psi);
  obs_ctx *oc = calloc(1, sizeof *oc);
  size_t i, best = 0, k;
  double bre = -INFINITY, bim = 0.0, vmax = 0.0, sx = 0, sy = 0, sxx = 0, sxy = 0, rate;
  autobal_transient_options o = autobal_transient_options_default();
  autobal_transient *tr;
  autobal_transient_system sys;
  autobal_rotor_stab_balanced_angles(s, psi, N);
  autobal_rotor_stab_linearization(s, 0.0, 1, a, ns);
  for (i = 0; i < ns * ns; i++) A->data[i] = a[i];
  gsl_eigen_nonsymmv(A, ev, evec, w);
  for (i = 0; i < ns; i++) {
    gsl_complex z = gsl_vector_complex_get(ev, i);
    if (hypot(GSL_REAL(z), GSL_IMAG(z)) < 1e-7) continue; /* family */
    if (GSL_IMAG(z) >= 0.0 && GSL_REAL(z) > bre) {
      bre = GSL_REAL(z);
      bim = GSL_IMAG(z);
      best = i;
    }
  }
  *pred = bre;
  for (i = 8; i < 8 + N; i++) vmax = fmax(vmax, gsl_complex_abs(gsl_matrix_complex_get(evec, i, best)));
  /* y(0) = balanced + eps Re(v), eps so that the ball angles move by 1e-5 rad */
  for (i = 0; i < ns; i++) {
    gsl_complex z = gsl_matrix_complex_get(evec, i, best);
    y[i] = 1e-5 * GSL_REAL(z) / vmax;
  }
  for (i = 0; i < N; i++) y[8 + i] += psi[i];
  oc->r = r;
  oc->period = bim > 0 ? M_PI / bim : 0.01; /* |sigma| e^{-rt} has period pi / Im(lambda) */
  o.rtol = 1e-11;
  o.atol = 1e-15;
  o.dt_out = oc->period;
  tr = autobal_transient_alloc(ns, &o, NULL);
  autobal_transient_set_observer(tr, obs, oc);
  sys.rhs = autobal_rotor_rhs_rotating;
  sys.jac = NULL;
  sys.dim = ns;
  sys.params = r;
  autobal_transient_run(tr, &sys, 0.0, t_end, y, NULL);
  /* least-squares slope of log|sigma| at t = k pi/Im(lambda) (the same phase of the
   * oscillating factor), skipping the first sample */
  for (k = 1; k + 1 < oc->n; k++) {
    const double x = oc->t[k], v = log(oc->s[k]);
    sx += x;
    sy += v;
    sxx += x * x;
    sxy += x * v;
  }
  {
    const double n = (double)(oc->n - 2);
    rate = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  }
  printf("   omega %.6g: predicted max Re(lambda) = %.8f 1/s (Im %.4f), measured %.8f 1/s over %zu samples\n",
         p->omega, bre, bim, rate, oc->n);
  autobal_transient_free(tr);
  free(oc);
  free(a);
  free(y);
  free(psi);
  gsl_eigen_nonsymmv_free(w);
  gsl_matrix_complex_free(evec);
  gsl_vector_complex_free(ev);
  gsl_matrix_free(A);
  autobal_rotor_free(r);
  autobal_rotor_stab_free(s);
  return rate;
}

static void test_nonlinear_short(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  double pred, got;
  printf("-- nonlinear confirmation of the growth rate (short)\n");
  /* the amplitude stays below ~1e-5 rad e^{|r| t}: the nonlinear terms change log|sigma| by
   * O(1e-5 .. 1e-4), i.e. the slope over t_end by < 1e-4/t_end; integration error 1e-11.
   * Tolerance: 1% of |rate| + 1e-3 1/s. */
  p.omega = 500.0;
  got = measure_rate(&p, 4.0, &pred);
  CHECK("500 rad/s: decays", got < 0);
  CHECK_CLOSE("500 rad/s: measured decay rate = max Re(lambda)", got, pred, 1e-2, 1e-3);
  p.omega = 300.0;
  got = measure_rate(&p, 1.5, &pred);
  CHECK("300 rad/s: grows", got > 0);
  CHECK_CLOSE("300 rad/s: measured growth rate = max Re(lambda)", got, pred, 1e-2, 1e-3);
}

/* ---- handle and option errors ---------------------------------------------------- */
static void test_errors(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_rotor_stab *s;
  autobal_error err;
  double mg, mu[12], mi[12], a[144];
  int v;
  autobal_rotor_stab_result r;
  printf("-- error paths\n");
  o.method = 9;
  CHECK("bad method", autobal_rotor_stab_alloc(&p, &o, &err) == NULL && err.status == AUTOBAL_EINVAL);
  CHECK_MSG("message", err.message, "method");
  o = autobal_rotor_stab_options_default();
  o.tol = -1;
  CHECK("bad tol", autobal_rotor_stab_alloc(&p, &o, &err) == NULL);
  CHECK_MSG("message", err.message, "tol");
  o = autobal_rotor_stab_options_default();
  o.member[0].kind = 7;
  CHECK("bad member kind", autobal_rotor_stab_alloc(&p, &o, &err) == NULL);
  CHECK_MSG("message", err.message, "member[0].kind");
  o.member[0].kind = AUTOBAL_ROTOR_MEMBER_GIVEN;
  o.member[0].n_angles = 1;
  o.member[0].angles = mu;
  CHECK("given member with a wrong count", autobal_rotor_stab_alloc(&p, &o, &err) == NULL);
  CHECK_MSG("message", err.message, "needs 2");
  p.plane[0].m0 = -1;
  CHECK("bad rotor parameter", autobal_rotor_stab_alloc(&p, NULL, &err) == NULL && err.status == AUTOBAL_EINVAL);
  CHECK_MSG("message names the parameter", err.message, "m0");
  p = autobal_rotor_params_default();
  s = autobal_rotor_stab_alloc(&p, NULL, &err);
  CHECK_STATUS("set bad id", autobal_rotor_stab_set(s, 99, 1.0), AUTOBAL_EINVAL);
  CHECK_STATUS("set negative ball mass", autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_BALL_MASS, -1.0), AUTOBAL_EINVAL);
  CHECK_MSG("message", autobal_rotor_stab_errmsg(s), "ball_mass");
  CHECK("value unchanged after a refused set", autobal_rotor_stab_get(s, AUTOBAL_ROTOR_PARAM_BALL_MASS) == 0.05);
  CHECK_STATUS("set NaN omega", autobal_rotor_stab_set(s, 0, NAN), AUTOBAL_EINVAL);
  CHECK("param names", !strcmp(autobal_rotor_stab_param_name(3), "stiffness_scale") && autobal_rotor_stab_param_from_name("ball_damping") == 1 && autobal_rotor_stab_param_from_name("nope") == -1 && autobal_rotor_stab_param_name(8) == NULL);
  CHECK("method names", !strcmp(autobal_rotor_stab_method_name(4), "floquet") && !strcmp(autobal_rotor_stab_method_name(7), "unknown"));
  autobal_rotor_stab_set(s, 0, 0.0);
  CHECK_STATUS("margin at omega = 0", autobal_rotor_stab_margin(s, 0, &mg, &v), AUTOBAL_EUNSUPPORTED);
  CHECK_STATUS("analyze at omega = 0", autobal_rotor_stab_analyze(s, &r), AUTOBAL_EINVAL);
  CHECK_STATUS("floquet at omega = 0", autobal_rotor_stab_floquet(s, mu, mi, 12, NULL), AUTOBAL_EINVAL);
  autobal_rotor_stab_set(s, 0, 500.0);
  CHECK_STATUS("floquet wrong n", autobal_rotor_stab_floquet(s, mu, mi, 11, NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("linearization wrong dim", autobal_rotor_stab_linearization(s, 0.0, 1, a, 13), AUTOBAL_EINVAL);
  CHECK_STATUS("balanced angles wrong n", autobal_rotor_stab_balanced_angles(s, mu, 3), AUTOBAL_EINVAL);
  /* no balanced configuration */
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, 1.0);
  CHECK_STATUS("margin without a balanced configuration: success", autobal_rotor_stab_margin(s, 0, &mg, &v), 0);
  CHECK("... verdict NONE, margin NaN", v == AUTOBAL_ROTOR_VERDICT_NONE && isnan(mg));
  CHECK_STATUS("analyze without a balanced configuration", autobal_rotor_stab_analyze(s, &r), AUTOBAL_EINVAL);
  CHECK_MSG("message", autobal_rotor_stab_errmsg(s), "no balanced configuration");
  autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, 0.02);
  /* methods that do not apply */
  CHECK_STATUS("poly is fine for the default", autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &mg, &v), 0);
  CHECK_STATUS("bad method id", autobal_rotor_stab_margin(s, 17, &mg, &v), AUTOBAL_EINVAL);
  autobal_rotor_stab_free(s);
  p = anisotropic();
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  CHECK_STATUS("poly with anisotropic supports", autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &mg, &v), AUTOBAL_EUNSUPPORTED);
  CHECK_MSG("message", autobal_rotor_stab_errmsg(s), "isotropic");
  CHECK_STATUS("full with anisotropic supports", autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_FULL, &mg, &v), AUTOBAL_EUNSUPPORTED);
  CHECK_STATUS("closed with anisotropic supports", autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_CLOSED, &mg, &v), AUTOBAL_EUNSUPPORTED);
  autobal_rotor_stab_free(s);
  p = two_planes();
  s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  CHECK_STATUS("poly with two planes", autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_POLY, &mg, &v), AUTOBAL_EUNSUPPORTED);
  CHECK_STATUS("closed with two planes", autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_CLOSED, &mg, &v), 0);
  autobal_rotor_stab_free(s);
  /* the model Jacobian: wrong dim, non-finite state */
  {
    autobal_rotor *r2 = autobal_rotor_alloc(&p, NULL);
    double y[16] = {0}, J[256], work[48];
    CHECK_STATUS("model jacobian wrong dim", autobal_rotor_model_jacobian(r2, 0.0, y, J, 15, work), AUTOBAL_EINVAL);
    y[0] = NAN;
    CHECK_STATUS("model jacobian non-finite state", autobal_rotor_model_jacobian(r2, 0.0, y, J, 16, work), AUTOBAL_ERHS);
    autobal_rotor_free(r2);
  }
  autobal_rotor_stab_free(NULL);
  CHECK("errmsg of NULL", autobal_rotor_stab_errmsg(NULL) != NULL);
}

/* ---- sweeps and critical searches put the working parameters back exactly ---------------- */

/* Unequal balls in two planes with different unbalances: 3 balls (plane 1) and 2 balls
 * (plane 2), every m_i and h_i different, hardware input (a scale parameter used to turn it
 * into lumped input). */
static double mu3[3] = {0.05, 0.04, 0.03}, ru3[3] = {0.1, 0.1, 0.1}, hu3[3] = {0.1, 0.07, 0.02};
static double mu2[2] = {0.04, 0.035}, ru2[2] = {0.09, 0.09}, hu2[2] = {0.4, 0.3};
static autobal_rotor_params unequal_two_planes(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.n_planes = 2;
  p.plane[0].n_balls = 3;
  p.plane[0].ball_mass = mu3;
  p.plane[0].ball_radius = ru3;
  p.plane[0].ball_damping = hu3;
  p.plane[0].ball_psi = NULL;
  p.plane[0].ball_rate = NULL;
  p.plane[1] = p.plane[0];
  p.plane[1].d = -0.12;
  p.plane[1].m0 = 0.015;
  p.plane[1].r0 = 0.09;
  p.plane[1].psi0 = 2.0;
  p.plane[1].n_balls = 2;
  p.plane[1].ball_mass = mu2;
  p.plane[1].ball_radius = ru2;
  p.plane[1].ball_damping = hu2;
  return p;
}

/* A deep copy of everything reachable through autobal_rotor_stab_params and _get. */
typedef struct params_copy {
  autobal_rotor_params p;
  double m[8], r[8], h[8], psi[8], rate[8];
  double get[6];
} params_copy;

static void params_take(autobal_rotor_stab *s, params_copy *c) {
  const autobal_rotor_params *p = autobal_rotor_stab_params(s);
  size_t j, i, o = 0;
  int id;
  memset(c, 0, sizeof *c);
  c->p = *p;
  for (j = 0; j < p->n_planes; j++)
    for (i = 0; i < p->plane[j].n_balls; i++, o++) {
      c->m[o] = p->plane[j].ball_mass[i];
      c->r[o] = p->plane[j].ball_radius[i];
      c->h[o] = p->plane[j].ball_damping[i];
      c->psi[o] = p->plane[j].ball_psi[i];
      c->rate[o] = p->plane[j].ball_rate[i];
    }
  for (id = 0; id < 6; id++) c->get[id] = autobal_rotor_stab_get(s, id);
}

#define SAME_BITS(a, b) (memcmp(&(a), &(b), sizeof(a)) == 0)

/* Field by field, bitwise (doubles by memcmp, so -0.0 != 0.0 and NaN == NaN bits). */
static int params_same(const params_copy *a, const params_copy *b, char *what, size_t len) {
  size_t j;
  int ok = 1;
  what[0] = '\0';
#define FIELD(x)                                                      \
  if (ok && !SAME_BITS(a->x, b->x)) {                                 \
    ok = 0;                                                           \
    snprintf(what, len, "%s", #x);                                    \
  }
  FIELD(p.input) FIELD(p.hw) FIELD(p.lumped) FIELD(p.inertia) FIELD(p.omega) FIELD(p.axial)
  FIELD(p.n_planes) FIELD(p.q0) FIELD(p.qd0) FIELD(p.z0) FIELD(p.zd0)
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++) {
    FIELD(p.plane[j].d) FIELD(p.plane[j].m0) FIELD(p.plane[j].r0) FIELD(p.plane[j].psi0)
    FIELD(p.plane[j].n_balls) FIELD(p.plane[j].ball_mass) FIELD(p.plane[j].ball_radius)
    FIELD(p.plane[j].ball_damping) FIELD(p.plane[j].ball_psi) FIELD(p.plane[j].ball_rate)
  }
  FIELD(m) FIELD(r) FIELD(h) FIELD(psi) FIELD(rate) FIELD(get)
#undef FIELD
  return ok;
}

/* The numbers of one analysis, copied out of the handle. */
typedef struct analysis_copy {
  int st, method, verdict;
  double margin, closed_margin, full_margin, floquet_margin;
  size_t n_full, n_floquet, n_closed;
  double psi[8], full_re[32], full_im[32], mu_re[32], mu_im[32];
} analysis_copy;

static void analysis_take(autobal_rotor_stab *s, analysis_copy *c) {
  autobal_rotor_stab_result r;
  size_t n;
  memset(c, 0, sizeof *c);
  memset(&r, 0, sizeof r);
  c->st = autobal_rotor_stab_analyze(s, &r);
  c->method = r.method;
  c->verdict = r.verdict;
  c->margin = r.margin;
  c->closed_margin = r.closed_margin;
  c->full_margin = r.full_margin;
  c->floquet_margin = r.floquet_margin;
  c->n_full = r.n_full;
  c->n_floquet = r.n_floquet;
  c->n_closed = r.n_closed;
  n = r.n_balls < 8 ? r.n_balls : 8;
  if (r.psi) memcpy(c->psi, r.psi, n * sizeof(double));
  if (r.full_re && r.n_full <= 32) {
    memcpy(c->full_re, r.full_re, r.n_full * sizeof(double));
    memcpy(c->full_im, r.full_im, r.n_full * sizeof(double));
  }
  if (r.mu_re && r.n_floquet <= 32) {
    memcpy(c->mu_re, r.mu_re, r.n_floquet * sizeof(double));
    memcpy(c->mu_im, r.mu_im, r.n_floquet * sizeof(double));
  }
}

static void test_restore(void) {
  autobal_rotor_params p = unequal_two_planes();
  autobal_rotor_stab_options o = autobal_rotor_stab_options_default();
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, NULL, NULL), *sc;
  params_copy before, after;
  analysis_copy a0, a1;
  autobal_rotor_crit cr;
  char what[64];
  /* per id: values that change it, some of them to "no balanced configuration" */
  static const double vals[6][3] = {{300.0, 450.0, 700.0},   {0.05, 0.2, 0.6},  {0.03, 0.06, 0.045},
                                    {0.5, 1.5, 2.0},         {0.0, 0.5, 3.0},   {0.0, 0.01, 0.03}};
  static const double crange[6][2] = {{300.0, 700.0}, {0.01, 0.5}, {0.02, 0.08},
                                      {0.5, 2.0},     {0.0, 3.0},  {0.0, 0.04}};
  double mg[3];
  int vd[3], id, st;
  printf("-- sweeps and critical searches restore every parameter bitwise (unequal balls, two planes)\n");
  CHECK("handle allocated", s != NULL);
  if (s == NULL) return;
  params_take(s, &before);
  CHECK("setup: ball masses and dampings all differ, m0 differ, hardware input",
        before.m[0] != before.m[1] && before.m[1] != before.m[2] && before.m[3] != before.m[4] &&
            before.h[0] != before.h[1] && before.h[3] != before.h[4] &&
            before.p.plane[0].m0 != before.p.plane[1].m0 && before.p.input == AUTOBAL_ROTOR_HARDWARE);
  analysis_take(s, &a0);
  CHECK_STATUS("analysis before the sweeps", a0.st, 0);
  CHECK("analysis computed the full model and Floquet (N = 5)", a0.n_full == 18 && a0.n_floquet == 18);
  for (id = 0; id < 6; id++) {
    char label[160];
    st = autobal_rotor_stab_sweep(s, id, vals[id], 3, mg, vd);
    snprintf(label, sizeof label, "sweep over %s", autobal_rotor_stab_param_name(id));
    CHECK_STATUS(label, st, 0);
    params_take(s, &after);
    snprintf(label, sizeof label, "after the sweep over %s: parameters bitwise as before", autobal_rotor_stab_param_name(id));
    CHECK(label, params_same(&before, &after, what, sizeof what));
    if (what[0]) printf("   first difference: %s\n", what);
    st = autobal_rotor_stab_critical(s, id, crange[id][0], crange[id][1], 6, 1e-6, &cr);
    snprintf(label, sizeof label, "critical search over %s", autobal_rotor_stab_param_name(id));
    CHECK(label, st == AUTOBAL_SUCCESS && cr.truncated == 0);
    params_take(s, &after);
    snprintf(label, sizeof label, "after the critical search over %s: parameters bitwise as before",
             autobal_rotor_stab_param_name(id));
    CHECK(label, params_same(&before, &after, what, sizeof what));
    if (what[0]) printf("   first difference: %s\n", what);
  }
  analysis_take(s, &a1);
  CHECK_STATUS("analysis after the sweeps", a1.st, 0);
  CHECK("analysis after = before (verdict, margins, psi, full roots, Floquet multipliers; bitwise)",
        a1.method == a0.method && a1.verdict == a0.verdict && SAME_BITS(a1.margin, a0.margin) &&
            SAME_BITS(a1.full_margin, a0.full_margin) && SAME_BITS(a1.floquet_margin, a0.floquet_margin) &&
            a1.n_full == a0.n_full && a1.n_floquet == a0.n_floquet && SAME_BITS(a1.psi, a0.psi) &&
            SAME_BITS(a1.full_re, a0.full_re) && SAME_BITS(a1.full_im, a0.full_im) &&
            SAME_BITS(a1.mu_re, a0.mu_re) && SAME_BITS(a1.mu_im, a0.mu_im));
  /* a sweep that fails midway: the third value is out of range (after two changes) */
  {
    const double bad[3] = {0.045, 0.05, -1.0};
    vd[0] = vd[1] = vd[2] = 99;
    CHECK_STATUS("sweep of ball_mass failing at the third value", autobal_rotor_stab_sweep(s, AUTOBAL_ROTOR_PARAM_BALL_MASS, bad, 3, mg, vd), AUTOBAL_EINVAL);
    CHECK_MSG("... names the parameter", autobal_rotor_stab_errmsg(s), "ball_mass");
    CHECK("the first two points were evaluated (the parameters did change)", vd[0] != 99 && vd[1] != 99 && vd[2] == 99);
    params_take(s, &after);
    CHECK("after the failed sweep: parameters bitwise as before", params_same(&before, &after, what, sizeof what));
    if (what[0]) printf("   first difference: %s\n", what);
  }
  autobal_rotor_stab_free(s);
  /* margin failures midway: with the CLOSED method the closure needs a common h_i/m_i per
   * plane: true at h = 0 for every ball, false for any common h > 0 with unequal masses */
  o.method = AUTOBAL_ROTOR_STAB_CLOSED;
  sc = autobal_rotor_stab_alloc(&p, &o, NULL);
  CHECK("handle (method closed) allocated", sc != NULL);
  if (sc == NULL) return;
  params_take(sc, &before);
  {
    const double hv[3] = {0.0, 0.1, 0.2};
    CHECK_STATUS("closed-method sweep of ball_damping: 0 works, 0.1 fails (no common kappa)",
                 autobal_rotor_stab_sweep(sc, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, hv, 3, mg, vd), AUTOBAL_EUNSUPPORTED);
    CHECK("the point h = 0 was evaluated (closure holds there)", vd[0] != AUTOBAL_ROTOR_VERDICT_NONE && isfinite(mg[0]));
    params_take(sc, &after);
    CHECK("after the failed sweep (margin failure): parameters bitwise as before", params_same(&before, &after, what, sizeof what));
    if (what[0]) printf("   first difference: %s\n", what);
    CHECK_STATUS("closed-method critical search over ball_damping fails at the second grid point",
                 autobal_rotor_stab_critical(sc, AUTOBAL_ROTOR_PARAM_BALL_DAMPING, 0.0, 0.2, 5, 1e-8, &cr), AUTOBAL_EUNSUPPORTED);
    CHECK("... after two grid evaluations, no change recorded", cr.evaluations == 2 && cr.n == 0);
    params_take(sc, &after);
    CHECK("after the failed critical search: parameters bitwise as before", params_same(&before, &after, what, sizeof what));
    if (what[0]) printf("   first difference: %s\n", what);
  }
  autobal_rotor_stab_free(sc);
}

/* ---- truncated lists: flag, status, message, meaning -------------------------------------- */

/* The speed named after "complete for omega <= " in a resonance warning (NaN if absent). */
static double complete_speed(const char *msg) {
  const char *k = strstr(msg, "complete for omega <= ");
  return k ? strtod(k + strlen("complete for omega <= "), NULL) : NAN;
}

static void test_truncation(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_rotor_stab *s = autobal_rotor_stab_alloc(&p, NULL, NULL);
  autobal_rotor_crit full, c;
  size_t k;
  int same, st;
  printf("-- truncated critical-value and resonance lists (capacity lowered for the test)\n");
  CHECK_STATUS("critical speeds, full capacity", autobal_rotor_stab_critical(s, AUTOBAL_ROTOR_PARAM_OMEGA, 20.0, 1500.0, 300, 1e-9, &full), 0);
  CHECK("not truncated; three changes (gained, lost, gained) for this test", full.truncated == 0 && full.n == 3 &&
        full.kind[0] == 1 && full.kind[1] == -1 && full.kind[2] == 1 && full.n_stable == 2);
  /* capacity = number of changes: exactly full, not truncated */
  st = autobal_rotor_stab_critical_cap_(s, AUTOBAL_ROTOR_PARAM_OMEGA, 20.0, 1500.0, 300, 1e-9, full.n, &c);
  CHECK_STATUS("capacity = number of changes: success", st, 0);
  same = c.n == full.n && c.n_stable == full.n_stable && c.truncated == 0;
  for (k = 0; same && k < c.n; k++) same = SAME_BITS(c.value[k], full.value[k]);
  for (k = 0; same && k < c.n_stable; k++) same = SAME_BITS(c.stable_lo[k], full.stable_lo[k]) && SAME_BITS(c.stable_hi[k], full.stable_hi[k]);
  CHECK("... and identical to the full result (nothing dropped is not truncation)", same);
  /* capacity 2: the third change (gained) is dropped */
  st = autobal_rotor_stab_critical_cap_(s, AUTOBAL_ROTOR_PARAM_OMEGA, 20.0, 1500.0, 300, 1e-9, 2, &c);
  CHECK_STATUS("capacity 2 < 3 changes: AUTOBAL_WARNING", st, AUTOBAL_WARNING);
  CHECK("truncated = 1, n = 2", c.truncated == 1 && c.n == 2);
  CHECK("the kept changes are the first ones of the full search (bitwise)", c.n == 2 && SAME_BITS(c.value[0], full.value[0]) &&
        SAME_BITS(c.value[1], full.value[1]) && c.kind[0] == full.kind[0] && c.kind[1] == full.kind[1]);
  CHECK("stable intervals: only the closed one [value0, value1]", c.n_stable == 1 && SAME_BITS(c.stable_lo[0], full.value[0]) &&
        SAME_BITS(c.stable_hi[0], full.value[1]));
  CHECK_MSG("message names the capacity", autobal_rotor_stab_errmsg(s), "more than 2 verdict changes");
  CHECK_MSG("message says what to do", autobal_rotor_stab_errmsg(s), "Narrow the range");
  CHECK("the search stopped early (fewer evaluations than the full one)", c.evaluations < full.evaluations);
  CHECK("omega restored after a truncated search", autobal_rotor_stab_get(s, AUTOBAL_ROTOR_PARAM_OMEGA) == 500.0);
  /* capacity 1: the first change gains stability; the stable interval that begins there is
   * not extended past it (not listed at all) */
  st = autobal_rotor_stab_critical_cap_(s, AUTOBAL_ROTOR_PARAM_OMEGA, 20.0, 1500.0, 300, 1e-9, 1, &c);
  CHECK_STATUS("capacity 1: AUTOBAL_WARNING", st, AUTOBAL_WARNING);
  CHECK("n = 1, no stable interval claimed beyond the last kept change", c.truncated == 1 && c.n == 1 && c.n_stable == 0 &&
        SAME_BITS(c.value[0], full.value[0]));
  CHECK_STATUS("capacity 0 rejected", autobal_rotor_stab_critical_cap_(s, 0, 20.0, 1500.0, 300, 1e-9, 0, &c), AUTOBAL_EINVAL);
  CHECK_STATUS("capacity above AUTOBAL_ROTOR_MAX_CRIT rejected",
               autobal_rotor_stab_critical_cap_(s, 0, 20.0, 1500.0, 300, 1e-9, AUTOBAL_ROTOR_MAX_CRIT + 1, &c), AUTOBAL_EINVAL);
  autobal_rotor_stab_free(s);

  /* resonances of the default rotor: 4 crossings, then capacity 2 (dropped by a crossing) */
  {
    autobal_rotor_resonances rf, rc;
    autobal_error err;
    double xc;
    int missing = 0;
    CHECK_STATUS("resonances, full capacity", autobal_rotor_resonance_speeds(&p, 1.0, 1000.0, 400, 1e-10, &rf, &err), 0);
    CHECK("not truncated, 4 crossings", rf.truncated == 0 && rf.n_cross == 4);
    st = autobal_rotor_resonance_speeds_cap_(&p, 1.0, 1000.0, 400, 1e-10, 4, &rc, &err);
    CHECK("capacity 4 = number of crossings: success, not truncated, same lists",
          st == 0 && rc.truncated == 0 && rc.n_cross == rf.n_cross && rc.n_peak == rf.n_peak &&
              memcmp(rc.cross, rf.cross, rf.n_cross * sizeof(double)) == 0 &&
              memcmp(rc.peak, rf.peak, rf.n_peak * sizeof(double)) == 0);
    st = autobal_rotor_resonance_speeds_cap_(&p, 1.0, 1000.0, 400, 1e-10, 2, &rc, &err);
    CHECK_STATUS("capacity 2 < 4 crossings: AUTOBAL_WARNING", st, AUTOBAL_WARNING);
    CHECK_STATUS("... also in err", err.status, AUTOBAL_WARNING);
    CHECK("truncated = 1, two crossings = the first two of the full search (bitwise)", rc.truncated == 1 && rc.n_cross == 2 &&
          memcmp(rc.cross, rf.cross, 2 * sizeof(double)) == 0);
    CHECK_MSG("message names the capacity", err.message, "more than 2 crossings");
    CHECK_MSG("message says what to do", err.message, "Narrow the range");
    xc = complete_speed(err.message);
    printf("   lists complete for omega <= %.9g (message)\n", xc);
    CHECK("that speed lies below the first dropped crossing", isfinite(xc) && xc < rf.cross[2]);
    for (k = 0; k < rf.n_cross; k++)
      if (rf.cross[k] <= xc && (k >= rc.n_cross || !SAME_BITS(rc.cross[k], rf.cross[k]))) missing++;
    for (k = 0; k < rf.n_peak; k++)
      if (rf.peak[k] <= xc && (k >= rc.n_peak || !SAME_BITS(rc.peak[k], rf.peak[k]))) missing++;
    CHECK("every crossing and peak of the full search below that speed is kept", missing == 0);
    CHECK_STATUS("resonances capacity 0 rejected", autobal_rotor_resonance_speeds_cap_(&p, 1.0, 1000.0, 400, 1e-10, 0, &rc, &err), AUTOBAL_EINVAL);
  }
  /* anisotropic, lightly damped supports: separated modes, each with a peak just above its
   * crossing.  A range starting between the crossing and the peak of mode 2 and ending
   * before the last crossing holds two peaks and one crossing: capacity 1 drops a peak. */
  {
    autobal_rotor_params q = autobal_rotor_params_default();
    autobal_rotor_resonances rf, rw, rc;
    autobal_error err;
    double lo, hi, xc;
    q.hw.c_Ly = 0.4e5;
    q.hw.c_Ry = 0.8e5;
    q.hw.h_Lx = q.hw.h_Ly = q.hw.h_Rx = q.hw.h_Ry = 5.0;
    CHECK_STATUS("anisotropic resonances", autobal_rotor_resonance_speeds(&q, 1.0, 1000.0, 2000, 1e-10, &rf, &err), 0);
    CHECK("4 crossings and 4 peaks, each peak above its crossing and below the next",
          rf.n_cross == 4 && rf.n_peak == 4 && rf.peak[1] > rf.cross[1] && rf.peak[1] < rf.cross[2] &&
              rf.peak[2] > rf.cross[2] && rf.peak[2] < rf.cross[3]);
    if (rf.n_cross == 4 && rf.n_peak == 4) {
      lo = rf.cross[1] + 0.25 * (rf.peak[1] - rf.cross[1]);
      hi = 0.5 * (rf.peak[2] + rf.cross[3]);
      CHECK_STATUS("sub-range, full capacity", autobal_rotor_resonance_speeds(&q, lo, hi, 2000, 1e-10, &rw, &err), 0);
      CHECK("sub-range: 1 crossing, 2 peaks, not truncated", rw.n_cross == 1 && rw.n_peak == 2 && rw.truncated == 0);
      st = autobal_rotor_resonance_speeds_cap_(&q, lo, hi, 2000, 1e-10, 1, &rc, &err);
      CHECK_STATUS("capacity 1, two peaks: AUTOBAL_WARNING", st, AUTOBAL_WARNING);
      CHECK("truncated by the peaks: 1 crossing, 1 peak (the first, bitwise)", rc.truncated == 1 && rc.n_cross == 1 &&
            rc.n_peak == 1 && SAME_BITS(rc.peak[0], rw.peak[0]) && SAME_BITS(rc.cross[0], rw.cross[0]));
      CHECK_MSG("message names the peaks", err.message, "more than 1 peaks");
      xc = complete_speed(err.message);
      CHECK("complete-up-to speed lies below the dropped peak", isfinite(xc) && xc < rw.peak[1]);
    }
  }
}

int main(void) {
  gsl_set_error_handler_off();
  test_members();
  test_char_poly();
  test_cross_checks();
  test_linearization();
  test_floquet_fd();
  test_critical();
  test_map();
  test_campbell();
  test_nonlinear_short();
  test_errors();
  test_restore();
  test_truncation();
  return check_summary();
}
