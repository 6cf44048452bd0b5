/* test_pendulum_physkeys.c: maps and sweeps of the two-pendulum balancer over its physical keys
 * M, e, m, l, c, H1, H2, omega (src/analysis/pendulum_map.c: autobal_pendulum_params_vary_physical,
 * autobal_pendulum_grid* with spec.phys, autobal_pendulum_param_domain; docs/pendulum.md "Physical
 * keys on an axis").  References, each obtained another way:
 *   - the conversion (2)-(3) written out here, operation for operation as docs/pendulum.md gives it,
 *     so that the dimensionless values agree bit for bit; then the grid over the physical keys must
 *     equal, bit for bit (verdicts and largest real parts), the grid evaluated point by point at
 *     those dimensionless values;
 *   - the dependency table against a perturbation of each key in the conversion itself;
 *   - critical values of omega and c against the exact critical speeds of (10) (discriminant,
 *     autobal_pendulum_critical_speeds) converted by (3): omega_j = R_wj omega0 and
 *     c_j = M_sigma omega^2 / R_wj^2 (R_m and k do not depend on omega or c);
 *   - the domain ends against closed forms (e < 2 m l / M, m > M e / (2 l), omega <= 1e6 omega0,
 *     c >= the largest of M_sigma (omega/1e6)^2, (H2/1e6)^2/M_sigma, M_sigma (H1/(1e6 m l^2))^2);
 *   - every refusal (mixing, no physical set, every unbalance with e, a box corner outside the
 *     domain) with its message, nothing written. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/pendulum.h"
#include "autobal/study.h"
#include "check.h"

/* (2)-(3) as docs/pendulum.md writes them */
static autobal_pendulum_params convert(const autobal_pendulum_physical *q) {
  autobal_pendulum_params p;
  double Ms = q->M + 2.0 * q->m, w0 = sqrt(q->c / Ms);
  p.R_w = q->omega / w0;
  p.R_m = q->m / Ms;
  p.H = q->H2 / (w0 * Ms);
  p.h = q->H1 / (q->m * q->l * q->l * w0);
  p.psi0 = asin(q->M * q->e / (2.0 * q->m * q->l));
  return p;
}

static double *field(autobal_pendulum_physical *q, int param) {
  switch (param) {
  case AUTOBAL_PENDULUM_PARAM_M: return &q->M;
  case AUTOBAL_PENDULUM_PARAM_E: return &q->e;
  case AUTOBAL_PENDULUM_PARAM_MP: return &q->m;
  case AUTOBAL_PENDULUM_PARAM_L: return &q->l;
  case AUTOBAL_PENDULUM_PARAM_C: return &q->c;
  case AUTOBAL_PENDULUM_PARAM_H1: return &q->H1;
  case AUTOBAL_PENDULUM_PARAM_H2: return &q->H2;
  default: return &q->omega;
  }
}

static int same_params(const autobal_pendulum_params *a, const autobal_pendulum_params *b) {
  return memcmp(&a->R_w, &b->R_w, sizeof(double)) == 0 && memcmp(&a->R_m, &b->R_m, sizeof(double)) == 0 &&
         memcmp(&a->H, &b->H, sizeof(double)) == 0 && memcmp(&a->h, &b->h, sizeof(double)) == 0 &&
         memcmp(&a->psi0, &b->psi0, sizeof(double)) == 0;
}

/* the verdict and largest real part at dimensionless q, as a one-point grid without physical keys
 * (ks: every unbalance, NULL: q's own k) */
static int point_dimless(const autobal_pendulum_params *q, const double *ks, size_t nk, int *v, double *mre) {
  autobal_pendulum_grid_spec s;
  autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
  int st;
  memset(&s, 0, sizeof s);
  s.base = *q;
  s.param1 = AUTOBAL_PENDULUM_PARAM_R_W, s.v1 = &q->R_w, s.n1 = 1, s.param2 = -1;
  s.k = ks, s.n_k = nk;
  st = autobal_pendulum_grid_point(&s, q->R_w, 0.0, ws, v, mre, NULL);
  autobal_pendulum_workspace_free(ws);
  return st;
}

int main(void) {
  /* data/pendulum_physical.ini: omega0 = 99.0148 rad/s, R_w = 3.03, R_m = 0.0098, psi0 = 0.73 */
  const autobal_pendulum_physical P0 = {10.0, 0.002, 0.1, 0.15, 1.0e5, 0.002, 50.0, 300.0};
  autobal_pendulum_physical P = P0, Q;
  autobal_pendulum_params base, q, r;
  autobal_error err;
  int st, i, j;

  printf("-- names, units, dependencies\n");
  CHECK("lookup: M, m, H1, H2, omega; M and m differ",
        autobal_pendulum_param_lookup("M") == AUTOBAL_PENDULUM_PARAM_M &&
            autobal_pendulum_param_lookup("m") == AUTOBAL_PENDULUM_PARAM_MP &&
            autobal_pendulum_param_lookup("H1") == AUTOBAL_PENDULUM_PARAM_H1 &&
            autobal_pendulum_param_lookup("H2") == AUTOBAL_PENDULUM_PARAM_H2 &&
            autobal_pendulum_param_lookup("omega") == AUTOBAL_PENDULUM_PARAM_OMEGA &&
            autobal_pendulum_param_lookup("Omega") == -1 && autobal_pendulum_param_name(AUTOBAL_PENDULUM_NPARAM) == NULL);
  CHECK("units: the SI units of autobal_pendulum_physical",
        !strcmp(autobal_pendulum_param_unit(AUTOBAL_PENDULUM_PARAM_OMEGA), "rad/s") &&
            !strcmp(autobal_pendulum_param_unit(AUTOBAL_PENDULUM_PARAM_H1), "N m s") &&
            !strcmp(autobal_pendulum_param_unit(AUTOBAL_PENDULUM_PARAM_H2), "N s/m") &&
            !strcmp(autobal_pendulum_param_unit(AUTOBAL_PENDULUM_PARAM_C), "N/m") &&
            !strcmp(autobal_pendulum_param_unit(AUTOBAL_PENDULUM_PARAM_E), "m") &&
            !strcmp(autobal_pendulum_param_dim(AUTOBAL_PENDULUM_PARAM_MP), "m"));
  CHECK("is_physical: 7..14 only", !autobal_pendulum_param_is_physical(AUTOBAL_PENDULUM_PARAM_H_RATIO) &&
                                       autobal_pendulum_param_is_physical(AUTOBAL_PENDULUM_PARAM_M) &&
                                       autobal_pendulum_param_is_physical(AUTOBAL_PENDULUM_PARAM_OMEGA) &&
                                       !autobal_pendulum_param_is_physical(AUTOBAL_PENDULUM_NPARAM));
  {
    /* the table against a 3% change of each key in the library's own conversion */
    int bad = 0;
    autobal_pendulum_params_from_physical(&P, &base, NULL);
    for (j = AUTOBAL_PENDULUM_PARAM_M; j <= AUTOBAL_PENDULUM_PARAM_OMEGA; j++) {
      autobal_pendulum_params a;
      double d[7], d0[7];
      Q = P;
      *field(&Q, j) *= 1.03;
      if (autobal_pendulum_params_from_physical(&Q, &a, NULL) != 0) { bad++; continue; }
      d0[0] = base.R_w, d0[1] = base.R_m, d0[2] = base.H, d0[3] = base.h, d0[4] = autobal_pendulum_k(&base);
      d0[5] = base.psi0, d0[6] = base.H / base.h;
      d[0] = a.R_w, d[1] = a.R_m, d[2] = a.H, d[3] = a.h, d[4] = autobal_pendulum_k(&a), d[5] = a.psi0, d[6] = a.H / a.h;
      for (i = 0; i <= AUTOBAL_PENDULUM_PARAM_H_RATIO; i++) {
        int changes = fabs(d[i] - d0[i]) > 1e-9 * fabs(d0[i]);
        if (changes != autobal_pendulum_param_depends(i, j)) {
          printf("     %s of %s: changes %d, table %d\n", autobal_pendulum_param_name(i), autobal_pendulum_param_name(j),
                 changes, autobal_pendulum_param_depends(i, j));
          bad++;
        }
      }
    }
    CHECK("autobal_pendulum_param_depends = which dimensionless values a 3% change of each key moves (56 pairs)", bad == 0);
  }

  printf("-- one code path: a point is the configuration's conversion\n");
  {
    int bad = 0;
    for (j = AUTOBAL_PENDULUM_PARAM_M; j <= AUTOBAL_PENDULUM_PARAM_OMEGA; j++) {
      autobal_pendulum_physical out;
      double v = *field(&P, j) * 1.1 + (j == AUTOBAL_PENDULUM_PARAM_E ? 1e-4 : 0.0);
      Q = P;
      *field(&Q, j) = v;
      st = autobal_pendulum_params_vary_physical(&base, &P, j, v, -1, 0.0, &q, &out, &err);
      autobal_pendulum_params_from_physical(&Q, &r, NULL);
      if (st != 0 || !same_params(&q, &r) || memcmp(&out, &Q, sizeof Q) != 0) bad++;
      r = convert(&Q);
      if (!same_params(&q, &r)) bad++;
    }
    CHECK("each key: vary_physical = from_physical of the changed set = (2)-(3) written out, bit for bit", bad == 0);
    st = autobal_pendulum_params_vary_physical(&base, &P, AUTOBAL_PENDULUM_PARAM_MP, 0.2, AUTOBAL_PENDULUM_PARAM_L, 0.3,
                                               &q, NULL, &err);
    Q = P, Q.m = 0.2, Q.l = 0.3;
    r = convert(&Q);
    CHECK("two keys (m, l): both set, then converted", st == 0 && same_params(&q, &r));
    st = autobal_pendulum_params_vary_physical(&base, &P, AUTOBAL_PENDULUM_PARAM_C, 2e5, AUTOBAL_PENDULUM_PARAM_R_M, 0.2,
                                               &q, NULL, &err);
    Q = P, Q.c = 2e5;
    r = convert(&Q), r.R_m = 0.2;
    CHECK("(c, R_m): c converted, then R_m set on the result", st == 0 && same_params(&q, &r));
    st = autobal_pendulum_params_vary_physical(&base, &P, AUTOBAL_PENDULUM_PARAM_C, 2e5, AUTOBAL_PENDULUM_PARAM_H_RATIO,
                                               3.0, &q, NULL, &err);
    r = convert(&Q), r.H = 3.0 * r.h;
    CHECK("(c, H/h): h of the point's conversion, H = 3 h", st == 0 && same_params(&q, &r));
    st = autobal_pendulum_params_vary_physical(&base, &P, AUTOBAL_PENDULUM_PARAM_R_M, 0.2, -1, 0.0, &q, NULL, &err);
    r = base, r.R_m = 0.2;
    CHECK("no physical axis: autobal_pendulum_params_vary on base", st == 0 && same_params(&q, &r));
  }

  printf("-- grid over omega = grid over R_w = omega/omega0, bit for bit\n");
  {
    enum { N = 240 };
    double om[N], rw[N], mre_a[N], mre_b[N], ks[9];
    signed char va[N], vb[N];
    autobal_pendulum_grid_spec s;
    size_t t;
    int c, nst, ndiff;
    for (t = 0; t < 9; t++) ks[t] = (double)t / 8.0;
    for (c = 0; c < 4; c++) {
      P = P0;
      if (c < 2) P.H1 = 0.0, P.H2 = 0.0, P.e = 0.0; /* undamped, k = 0: the exact criterion */
      autobal_pendulum_params_from_physical(&P, &base, NULL);
      for (t = 0; t < N; t++) {
        om[t] = 20.0 + 480.0 * (double)t / (double)(N - 1);
        Q = P, Q.omega = om[t];
        rw[t] = convert(&Q).R_w;
      }
      memset(&s, 0, sizeof s);
      s.base = base;
      s.phys = &P;
      s.param1 = AUTOBAL_PENDULUM_PARAM_OMEGA, s.v1 = om, s.n1 = N, s.param2 = -1;
      if (c % 2) s.k = ks, s.n_k = 9;
      st = autobal_pendulum_grid(&s, va, mre_a, &err);
      s.phys = NULL;
      s.param1 = AUTOBAL_PENDULUM_PARAM_R_W, s.v1 = rw;
      st |= autobal_pendulum_grid(&s, vb, mre_b, &err);
      nst = 0, ndiff = 0;
      for (t = 0; t < N; t++) {
        nst += va[t] > 0;
        ndiff += va[t] != vb[t] || memcmp(&mre_a[t], &mre_b[t], sizeof(double)) != 0;
      }
      printf("     case %d (%s, %s): %d of %d stable, %d differ\n", c, c < 2 ? "undamped, e = 0" : "damped",
             c % 2 ? "every unbalance" : "one k", nst, N, ndiff);
      CHECK("omega line == R_w line (verdicts and max_real bitwise; both verdicts occur)",
            st == 0 && ndiff == 0 && nst > 0 && nst < N);
    }
  }

  printf("-- a map over (m, l) and (c, omega): each point = the one-point grid at its conversion\n");
  {
    enum { N1 = 11, N2 = 9 };
    double v1[N1], v2[N2], mre[N1 * N2], ks[5];
    signed char vv[N1 * N2];
    autobal_pendulum_grid_spec s;
    size_t a, b;
    int c, nst, ndiff;
    for (a = 0; a < 5; a++) ks[a] = (double)a / 4.0;
    for (c = 0; c < 2; c++) {
      int p1 = c == 0 ? AUTOBAL_PENDULUM_PARAM_MP : AUTOBAL_PENDULUM_PARAM_C;
      int p2 = c == 0 ? AUTOBAL_PENDULUM_PARAM_L : AUTOBAL_PENDULUM_PARAM_OMEGA;
      P = P0;
      if (c == 0) P.H2 = 300.0;         /* H = 0.3, h = 0.009: unstable and stable points */
      else P.H1 = 0.05;                 /* H = 0.05, h = 0.22: stable for every k at some points */
      autobal_pendulum_params_from_physical(&P, &base, NULL);
      for (a = 0; a < N1; a++) v1[a] = c == 0 ? 0.12 + 0.4 * (double)a / (N1 - 1) : 2e4 * pow(20.0, (double)a / (N1 - 1));
      for (b = 0; b < N2; b++) v2[b] = c == 0 ? 0.15 + 0.3 * (double)b / (N2 - 1) : 50.0 + 450.0 * (double)b / (N2 - 1);
      memset(&s, 0, sizeof s);
      s.base = base, s.phys = &P;
      s.param1 = p1, s.v1 = v1, s.n1 = N1, s.param2 = p2, s.v2 = v2, s.n2 = N2;
      if (c == 1) s.k = ks, s.n_k = 5;
      st = autobal_pendulum_grid(&s, vv, mre, &err);
      if (st) printf("     %s\n", err.message);
      nst = 0, ndiff = 0;
      for (a = 0; a < N1; a++)
        for (b = 0; b < N2; b++) {
          int w = 9;
          double m = NAN;
          Q = P;
          *field(&Q, p1) = v1[a], *field(&Q, p2) = v2[b];
          q = convert(&Q);
          if (point_dimless(&q, c == 1 ? ks : NULL, c == 1 ? 5 : 0, &w, &m) != 0) w = 9;
          nst += vv[a * N2 + b] > 0;
          ndiff += vv[a * N2 + b] != w || memcmp(&m, &mre[a * N2 + b], sizeof m) != 0;
        }
      printf("     (%s, %s)%s: %d of %d stable, %d differ\n", autobal_pendulum_param_name(p1),
             autobal_pendulum_param_name(p2), c == 1 ? ", every unbalance" : "", nst, N1 * N2, ndiff);
      CHECK("physical map == dimensionless one-point grids at (2)-(3), bitwise (both verdicts occur)",
            st == 0 && ndiff == 0 && nst > 0 && nst < N1 * N2);
    }
  }

  printf("-- critical values of omega and c against the exact critical speeds of (10)\n");
  {
    autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
    autobal_pendulum_crit_set cs;
    autobal_pendulum_grid_spec s;
    double Ms, w0, x, k;
    size_t n;
    int vl, vh, ok = 1, okc = 1, nfound = 0;
    P = P0;
    P.H1 = 0.0, P.H2 = 0.0, P.m = 1.0, P.e = 0.01; /* undamped, R_m = 1/12, psi0 = asin(1/3): k = 0.395 */
    autobal_pendulum_params_from_physical(&P, &base, NULL);
    Ms = P.M + 2.0 * P.m, w0 = sqrt(P.c / Ms), k = autobal_pendulum_k(&base);
    CHECK_STATUS("exact critical speeds at R_m, k of the set", autobal_pendulum_critical_speeds(ws, base.R_m, k, &cs), 0);
    memset(&s, 0, sizeof s);
    s.base = base, s.phys = &P, s.param2 = -1;
    for (n = 0; n < cs.n; n++) {
      double oc = cs.R_w[n] * w0, cc = Ms * P.omega * P.omega / (cs.R_w[n] * cs.R_w[n]);
      if (cs.kind[n] == AUTOBAL_CRIT_TOUCH) continue;
      s.param1 = AUTOBAL_PENDULUM_PARAM_OMEGA;
      st = autobal_pendulum_grid_critical(&s, oc * (1 - 1e-4), oc * (1 + 1e-4), 0, 1e-13, &x, &vl, &vh, &err);
      printf("     omega_%zu = %.15g rad/s exact R_w omega0, %.15g bisection (%d -> %d)\n", n + 1, oc, x, vl, vh);
      ok &= st == 0 && fabs(x - oc) <= 1e-12 * oc && vl == -cs.kind[n] && vh == cs.kind[n];
      s.param1 = AUTOBAL_PENDULUM_PARAM_C; /* R_w falls as c grows: the kinds reverse */
      st = autobal_pendulum_grid_critical(&s, cc * (1 - 1e-4), cc * (1 + 1e-4), 1, 1e-13, &x, &vl, &vh, &err);
      printf("     c_%zu = %.15g N/m = M_sigma omega^2 / R_w^2, %.15g bisection (%d -> %d)\n", n + 1, cc, x, vl, vh);
      okc &= st == 0 && fabs(x - cc) <= 1e-11 * cc && vl == cs.kind[n] && vh == -cs.kind[n];
      nfound++;
    }
    CHECK("omega: every critical speed R_wj omega0 found by bisection to 1e-12, kinds as the exact ones", ok && nfound >= 3);
    CHECK("c: every critical stiffness M_sigma omega^2 / R_wj^2 to 1e-11, kinds reversed", okc && nfound >= 3);
    autobal_pendulum_workspace_free(ws);
  }

  printf("-- the study: a sweep over omega with its default range\n");
  {
    autobal_study_pendulum_sweep_options o = autobal_study_pendulum_sweep_options_default();
    autobal_study_pendulum_sweep_summary sum;
    autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
    autobal_pendulum_crit_set cs;
    double w0, lo, hi;
    size_t n, m = 0;
    int lg = -1, ok = 1;
    P = P0;
    P.H1 = 0.0, P.H2 = 0.0, P.m = 1.0, P.e = 0.01;
    autobal_pendulum_params_from_physical(&P, &base, NULL);
    w0 = sqrt(P.c / (P.M + 2.0 * P.m));
    autobal_study_pendulum_param_range_physical(AUTOBAL_PENDULUM_PARAM_OMEGA, &P, &lo, &hi, &lg);
    CHECK("default omega range: 0.05 .. 5 omega0, linear (that of R_w)",
          fabs(lo - 0.05 * w0) <= 1e-15 * lo && fabs(hi - 5.0 * w0) <= 1e-15 * hi && lg == 0);
    autobal_study_pendulum_param_range_physical(AUTOBAL_PENDULUM_PARAM_E, &P, &lo, &hi, &lg);
    CHECK("default e range: 0 .. sqrt(2) m l / M (psi0 0 .. pi/4)",
          lo == 0.0 && fabs(asin(P.M * hi / (2.0 * P.m * P.l)) - 0.78539816339744831) < 1e-15 && lg == 0);
    autobal_study_pendulum_param_range_physical(AUTOBAL_PENDULUM_PARAM_MP, NULL, &lo, &hi, &lg);
    CHECK("no physical set: NaN", isnan(lo) && isnan(hi));
    o.param = AUTOBAL_PENDULUM_PARAM_OMEGA;
    o.n = 500;
    st = autobal_study_pendulum_sweep(&base, &P, &o, NULL, &sum, &err);
    autobal_pendulum_critical_speeds(ws, base.R_m, autobal_pendulum_k(&base), &cs);
    for (n = 0; n < cs.n; n++) {
      if (cs.kind[n] == AUTOBAL_CRIT_TOUCH || cs.R_w[n] < 0.05 || cs.R_w[n] > 5.0) continue;
      ok &= m < sum.n_crit && fabs(sum.crit[m] - cs.R_w[n] * w0) <= 1e-9 * cs.R_w[n] * w0;
      m++;
    }
    CHECK("autobal_study_pendulum_sweep over omega: the exact critical speeds times omega0 (1e-9)",
          st == 0 && ok && m == sum.n_crit && m >= 3 && sum.min == 0.05 * w0);
    autobal_study_pendulum_sweep_summary_free(&sum);
    st = autobal_study_pendulum_sweep(&base, NULL, &o, NULL, &sum, &err);
    CHECK_STATUS("... without the physical set: refused", st, AUTOBAL_EINVAL);
    CHECK_MSG("... message", err.message, "pendulum.omega is a physical key");
    autobal_study_pendulum_sweep_summary_free(&sum);
    autobal_pendulum_workspace_free(ws);
  }

  printf("-- the model's domain of a key\n");
  {
    double lo, hi, Ms = P0.M + 2.0 * P0.m, w0 = sqrt(P0.c / Ms), want;
    P = P0;
    st = autobal_pendulum_param_domain(&P, AUTOBAL_PENDULUM_PARAM_E, &lo, &hi, &err);
    CHECK("e: [0, 2 m l / M)", st == 0 && lo == 0.0 && fabs(hi - 2.0 * P.m * P.l / P.M) <= 4e-16 * hi);
    st = autobal_pendulum_param_domain(&P, AUTOBAL_PENDULUM_PARAM_MP, &lo, &hi, &err);
    CHECK_CLOSE("m: lower end M e / (2 l)", lo, P.M * P.e / (2.0 * P.l), 1e-15, 0);
    st = autobal_pendulum_param_domain(&P, AUTOBAL_PENDULUM_PARAM_OMEGA, &lo, &hi, &err);
    CHECK("omega: [0, 1e6 omega0]", st == 0 && lo == 0.0 && fabs(hi - 1e6 * w0) <= 1e-15 * hi);
    st = autobal_pendulum_param_domain(&P, AUTOBAL_PENDULUM_PARAM_C, &lo, &hi, &err);
    want = fmax(fmax(Ms * pow(P.omega / 1e6, 2), pow(P.H2 / 1e6, 2) / Ms), Ms * pow(P.H1 / (1e6 * P.m * P.l * P.l), 2));
    CHECK("c: lower end from R_w, H, h <= 1e6, no upper end", st == 0 && fabs(lo - want) <= 1e-15 * want && isinf(hi));
    st = autobal_pendulum_param_domain(&P, AUTOBAL_PENDULUM_PARAM_H2, &lo, &hi, &err);
    CHECK("H2: [0, 1e6 omega0 M_sigma]", st == 0 && lo == 0.0 && fabs(hi - 1e6 * w0 * Ms) <= 1e-15 * hi);
    CHECK_STATUS("not a physical key", autobal_pendulum_param_domain(&P, AUTOBAL_PENDULUM_PARAM_R_W, &lo, &hi, &err),
                 AUTOBAL_EINVAL);
    Q = P, Q.e = 1.0;
    CHECK_STATUS("a set outside the domain", autobal_pendulum_param_domain(&Q, AUTOBAL_PENDULUM_PARAM_C, &lo, &hi, &err),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... the conversion's message", err.message, "M*e");
  }

  printf("-- refusals, nothing written\n");
  {
    double vals[3] = {0.001, 0.002, 0.05}, ms[2] = {0.2, 0.07}, ls[2] = {0.2, 0.11}, ks[2] = {0.0, 1.0};
    signed char out[4] = {7, 7, 7, 7};
    autobal_pendulum_grid_spec s;
    P = P0;
    autobal_pendulum_params_from_physical(&P, &base, NULL);
    memset(&s, 0, sizeof s);
    s.base = base, s.phys = &P;
    s.param1 = AUTOBAL_PENDULUM_PARAM_E, s.v1 = vals, s.n1 = 3, s.param2 = -1;
    CHECK_STATUS("e through 0.05 m (M e > 2 m l)", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... names the key at the end of the range", err.message, "pendulum.e = 0.05 m leaves the model's domain");
    CHECK_MSG("... and the allowed interval", err.message, "pendulum.e must lie in [0, 0.003) m");
    CHECK("... nothing written", out[0] == 7 && out[1] == 7 && out[2] == 7);
    s.param1 = AUTOBAL_PENDULUM_PARAM_MP, s.v1 = ms, s.n1 = 2, s.param2 = AUTOBAL_PENDULUM_PARAM_L, s.v2 = ls, s.n2 = 2;
    CHECK_STATUS("(m, l): every value fine with the other at its first, the corner (0.07, 0.11) outside",
                 autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... names both keys", err.message, "pendulum.m = 0.07 kg (with pendulum.l = 0.11 m)");
    CHECK("... nothing written", out[0] == 7 && out[3] == 7);
    s.param1 = AUTOBAL_PENDULUM_PARAM_OMEGA, s.v1 = vals, s.n1 = 3, s.param2 = AUTOBAL_PENDULUM_PARAM_R_W, s.v2 = vals,
    s.n2 = 3;
    CHECK_STATUS("(omega, R_w)", autobal_pendulum_grid_check(&s, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... says why", err.message, "R_w is a function of omega");
    s.param1 = AUTOBAL_PENDULUM_PARAM_R_M, s.param2 = AUTOBAL_PENDULUM_PARAM_MP;
    CHECK_STATUS("(R_m, m)", autobal_pendulum_grid_check(&s, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... names both", err.message, "axes pendulum.m and pendulum.R_m cannot be combined");
    CHECK_STATUS("(e, k)", autobal_pendulum_params_vary_physical(&base, &P, AUTOBAL_PENDULUM_PARAM_E, 0.001,
                                                                 AUTOBAL_PENDULUM_PARAM_K, 0.5, &q, NULL, &err),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("(H2, H)", autobal_pendulum_params_vary_physical(&base, &P, AUTOBAL_PENDULUM_PARAM_H2, 1.0,
                                                                  AUTOBAL_PENDULUM_PARAM_H, 0.5, &q, NULL, &err),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("(H1, H/h)", autobal_pendulum_params_vary_physical(&base, &P, AUTOBAL_PENDULUM_PARAM_H1, 1.0,
                                                                    AUTOBAL_PENDULUM_PARAM_H_RATIO, 0.5, &q, NULL, &err),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("(e, R_w) is fine: R_w does not depend on e",
                 autobal_pendulum_params_vary_physical(&base, &P, AUTOBAL_PENDULUM_PARAM_E, 0.001,
                                                       AUTOBAL_PENDULUM_PARAM_R_W, 2.5, &q, NULL, &err),
                 AUTOBAL_SUCCESS);
    CHECK("... R_w set, psi0 from e", q.R_w == 2.5 && q.psi0 == asin(P.M * 0.001 / (2.0 * P.m * P.l)));
    Q = P, Q.H1 = 0.0;
    CHECK_STATUS("(c, H/h) with H1 = 0", autobal_pendulum_params_vary_physical(&base, &Q, AUTOBAL_PENDULUM_PARAM_C, 1e5,
                                                                              AUTOBAL_PENDULUM_PARAM_H_RATIO, 2.0, &q,
                                                                              NULL, &err),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... message", err.message, "axis H/h needs pendulum.H1 > 0");
    CHECK_STATUS("a physical key without the physical set (vary)",
                 autobal_pendulum_params_vary(&base, AUTOBAL_PENDULUM_PARAM_OMEGA, 100.0, -1, 0.0, &q, &err),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... message", err.message, "pendulum.omega is a physical key: it needs the physical set");
    s.phys = NULL, s.param1 = AUTOBAL_PENDULUM_PARAM_C, s.v1 = vals, s.n1 = 3, s.param2 = -1;
    CHECK_STATUS("... (grid)", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    s.phys = &P, s.param1 = AUTOBAL_PENDULUM_PARAM_E, s.k = ks, s.n_k = 2;
    CHECK_STATUS("every unbalance with an e axis", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... message", err.message, "cannot be combined with an e axis");
    s.param1 = AUTOBAL_PENDULUM_PARAM_M, s.k = NULL, s.n_k = 0, vals[0] = -1.0;
    CHECK_STATUS("M = -1", autobal_pendulum_grid(&s, out, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... names the key, its unit and range", err.message, "pendulum.M = -1 kg is too small: must be > 0 kg");
    CHECK("... nothing written", out[0] == 7);
  }

  printf("-- with the physical set but no physical axis: the dimensionless grid unchanged\n");
  {
    double rm[7], rw[9];
    signed char a[63], b[63];
    autobal_pendulum_grid_spec s;
    int nd = 0;
    P = P0;
    autobal_pendulum_params_from_physical(&P, &base, NULL);
    for (i = 0; i < 7; i++) rm[i] = 0.01 + 0.07 * i;
    for (i = 0; i < 9; i++) rw[i] = 0.5 + 0.5 * i;
    memset(&s, 0, sizeof s);
    s.base = base;
    s.param1 = AUTOBAL_PENDULUM_PARAM_R_M, s.v1 = rm, s.n1 = 7, s.param2 = AUTOBAL_PENDULUM_PARAM_H, s.v2 = rw, s.n2 = 9;
    st = autobal_pendulum_grid(&s, a, NULL, &err);
    s.phys = &P;
    st |= autobal_pendulum_grid(&s, b, NULL, &err);
    for (i = 0; i < 63; i++) nd += a[i] != b[i];
    CHECK("(R_m, H) with and without spec.phys: the same verdicts", st == 0 && nd == 0);
  }
  return check_summary();
}
