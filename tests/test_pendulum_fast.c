/* test_pendulum_fast.c: the fast paths of the pendulum stability maps
 * (src/analysis/pendulum_map.c: lanes of grid points or k values, the two-stage Routh
 * kernel with its fall-back to the full test, the double-precision filter of
 * the undamped criterion with its long-double fall-back, k groups with early
 * exit, row tiles).  Independent reference for every map entry: the
 * one-point public functions (autobal_pendulum_verdict,
 * autobal_pendulum_undamped_verdict) called point by point and k by k, whose
 * own correctness is tested in test_pendulum.c (roots, closed forms); and
 * the sign test's two-stage Routh kernel against the generic Routh test of
 * stability.h on the public coefficients of (6).
 * Grids of odd sizes so that the last lane group and the last tile of each
 * row are partial. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/pendulum.h"
#include "check.h"

/* the undamped convention of the maps under test: 0 the exact one of autobal_pendulum_verdict,
 * 1 the paper's (autobal_pendulum_map_spec.paper_convention) */
static int g_paper = 0;

/* worst verdict over ks at (Rm, Rw) from the one-point functions, with the
 * map's conventions (undamped, paper: MARGINAL counts as STABLE; exact: the documented rule of
 * autobal_pendulum_verdict -- lambda = 0 is not semisimple at R_w = 0 and at k = 0, R_w = 1,
 * any other MARGINAL stays) */
static int reference(double Rm, double Rw, double H, double h, const double *ks, size_t nk) {
  int worst = AUTOBAL_VERDICT_STABLE;
  size_t t;
  for (t = 0; t < nk; t++) {
    int v;
    if (H == 0.0 && h == 0.0) {
      autobal_pendulum_undamped_verdict(Rm, Rw, ks[t], &v, NULL);
      if (v == AUTOBAL_VERDICT_MARGINAL)
        v = g_paper ? AUTOBAL_VERDICT_STABLE
                    : (Rw == 0.0 || (ks[t] == 0.0 && Rw == 1.0)) ? AUTOBAL_VERDICT_UNSTABLE : AUTOBAL_VERDICT_MARGINAL;
    } else {
      autobal_pendulum_params p;
      autobal_pendulum_params_from_k(Rw, Rm, H, h, ks[t], &p, NULL);
      autobal_pendulum_verdict(&p, &v, NULL, NULL);
    }
    if (v < worst) worst = v;
  }
  return worst;
}

/* map over [rm0, rm1] x [rw0, rw1] (nm x nw) with 1 and 2 threads: returns
 * the number of entries that differ from the reference; *same = serial ==
 * OpenMP bitwise; counts of the three verdicts in cnt[3] */
static int check_map(size_t nm, size_t nw, double rm0, double rm1, double rw0, double rw1, double H,
                     double h, const double *ks, size_t nk, int *same, long cnt[3]) {
  double *rm = malloc(nm * sizeof *rm), *rw = malloc(nw * sizeof *rw);
  signed char *v1 = malloc(nm * nw), *v2 = malloc(nm * nw);
  double kdef[65];
  autobal_pendulum_map_spec s;
  size_t i, j;
  int bad = 0;
  for (i = 0; i < nm; i++) rm[i] = rm0 + (rm1 - rm0) * (double)i / (double)(nm - 1);
  for (j = 0; j < nw; j++) rw[j] = rw0 + (rw1 - rw0) * (double)j / (double)(nw - 1);
  memset(&s, 0, sizeof s);
  s.R_m = rm, s.n_Rm = nm, s.R_w = rw, s.n_Rw = nw, s.H = H, s.h = h, s.k = ks, s.n_k = nk;
  s.n_threads = 1;
  s.paper_convention = g_paper;
  if (autobal_pendulum_map(&s, v1, NULL, NULL) != AUTOBAL_SUCCESS) bad++;
  s.n_threads = 2;
  if (autobal_pendulum_map(&s, v2, NULL, NULL) != AUTOBAL_SUCCESS) bad++;
  *same = memcmp(v1, v2, nm * nw) == 0;
  if (ks == NULL) { /* the default set */
    for (i = 0; i < 65; i++) kdef[i] = (double)i / 64.0;
    ks = kdef, nk = 65;
  }
  cnt[0] = cnt[1] = cnt[2] = 0;
  for (i = 0; i < nm; i++)
    for (j = 0; j < nw; j++) {
      int v = v1[i * nw + j];
      cnt[v + 1]++;
      if (v != reference(rm[i], rw[j], H, h, ks, nk)) bad++;
    }
  free(rm);
  free(rw);
  free(v1);
  free(v2);
  return bad;
}

int main(void) {
  static const double kmix[] = {0.5, 0.0, 1.0, 1e-9, 0.999999, 0.25, 0.0, 0.75, 0.1};
  static const double k03[] = {0.3}, k0[] = {0.0}, k1[] = {1.0};
  int same, bad;
  long cnt[3];

  printf("-- damped maps vs autobal_pendulum_verdict point by point and k by k\n");
  bad = check_map(23, 41, 0.01, 0.49, 0.05, 6.0, 0.05, 0.1, NULL, 0, &same, cnt);
  CHECK("65 k (default set): entries == worst one-point verdict", bad == 0);
  CHECK("... serial == 2 threads bitwise", same);
  CHECK("... both verdicts occur", cnt[0] > 0 && cnt[2] > 0);
  bad = check_map(19, 37, 0.01, 0.49, 0.05, 6.0, 0.05, 0.1, kmix, 9, &same, cnt);
  CHECK("k set with 0, 1, 1e-9, repeats (partial lane groups): entries == reference", bad == 0);
  CHECK("... serial == 2 threads bitwise", same);
  bad = check_map(17, 131, 0.01, 0.49, 0.05, 6.0, 0.05, 0.1, k0, 1, &same, cnt);
  CHECK("one k = 0 (lambda = 0 deflated, lanes across R_w, 3 tiles per row): entries == reference",
        bad == 0);
  CHECK("... serial == 2 threads bitwise", same);
  bad = check_map(17, 131, 0.01, 0.49, 0.05, 6.0, 0.05, 0.1, k03, 1, &same, cnt);
  CHECK("one k = 0.3: entries == reference", bad == 0);
  /* H = 0, h > 0: boundary points where the sign test is MARGINAL; those are
   * decided by the full test after the quick stage (the fall-back path) */
  bad = check_map(29, 61, 0.01, 0.49, 0.0, 8.0, 0.0, 0.3, k03, 1, &same, cnt);
  CHECK("H = 0, h = 0.3 (marginal entries, fall-back to the full test): entries == reference",
        bad == 0);
  CHECK("... marginal entries occur", cnt[1] > 0);
  CHECK("... serial == 2 threads bitwise", same);
  bad = check_map(11, 23, 0.01, 0.49, 100.0, 3000.0, 0.05, 0.1, NULL, 0, &same, cnt);
  CHECK("very large speeds (R_w 100..3000, wide rounding bounds): entries == reference", bad == 0);

  printf("-- undamped maps vs autobal_pendulum_undamped_verdict\n");
  bad = check_map(23, 41, 0.01, 0.49, 0.0, 6.0, 0.0, 0.0, NULL, 0, &same, cnt);
  CHECK("65 k (the cubic at k = 0, P1 at k = 1, quartics between): entries == reference", bad == 0);
  CHECK("... serial == 2 threads bitwise", same);
  CHECK("... both verdicts occur", cnt[0] > 0 && cnt[2] > 0);
  bad = check_map(19, 37, 0.01, 0.49, 0.0, 6.0, 0.0, 0.0, kmix, 9, &same, cnt);
  CHECK("k set with 0, 1, 1e-9, 0.999999, repeats: entries == reference", bad == 0);
  bad = check_map(17, 131, 0.01, 0.49, 0.0, 6.0, 0.0, 0.0, k03, 1, &same, cnt);
  CHECK("one k = 0.3 (lanes across R_w): entries == reference", bad == 0);
  bad = check_map(17, 131, 0.01, 0.49, 0.0, 6.0, 0.0, 0.0, k0, 1, &same, cnt);
  CHECK("one k = 0: entries == reference", bad == 0);
  bad = check_map(17, 131, 0.01, 0.49, 0.0, 6.0, 0.0, 0.0, k1, 1, &same, cnt);
  CHECK("one k = 1: entries == reference", bad == 0);
  /* W = 1 exactly (R_w = 1): a_0 of (10) is 0, the double filter cannot
   * decide and the long-double test runs */
  bad = check_map(9, 3, 0.01, 0.49, 0.0, 2.0, 0.0, 0.0, NULL, 0, &same, cnt);
  CHECK("grid through R_w = 1 (long-double fall-back): entries == reference", bad == 0);
  /* the two conventions differ exactly where lambda = 0 is not semisimple: R_w = 0 (every k)
   * and k = 0, R_w = 1; the grid R_w = 0, 1, 2 has both */
  {
    long ce[3], cp[3];
    bad = check_map(9, 3, 0.01, 0.49, 0.0, 2.0, 0.0, 0.0, k0, 1, &same, ce);
    CHECK("exact convention, k = 0 through R_w = 0 and 1: entries == reference", bad == 0);
    g_paper = 1;
    bad = check_map(9, 3, 0.01, 0.49, 0.0, 2.0, 0.0, 0.0, k0, 1, &same, cp);
    CHECK("paper convention, the same grid: entries == reference", bad == 0);
    bad = check_map(23, 41, 0.01, 0.49, 0.0, 6.0, 0.0, 0.0, NULL, 0, &same, cp);
    CHECK("paper convention, 65 k: entries == reference", bad == 0);
    bad = check_map(9, 3, 0.01, 0.49, 0.0, 2.0, 0.0, 0.0, k0, 1, &same, cp);
    g_paper = 0;
    printf("     k = 0, R_w in {0, 1, 2}: exact: %ld unstable, %ld stable; paper: %ld unstable, %ld stable\n",
           ce[0], ce[2], cp[0], cp[2]);
    CHECK("... the exact convention has 18 more unstable points (R_w = 0 and 1 on 9 rows)",
          ce[0] == cp[0] + 18 && ce[2] + 18 == cp[2]);
  }

  printf("-- the sign test's quick Routh stage vs the generic Routh test\n");
  {
    /* autobal_pendulum_verdict (two-stage kernel with the bounds of the
     * coefficient computation) against autobal_poly_hurwitz (the generic
     * test with relative coefficient tolerances) on the public coefficients
     * of (6): wherever the generic test decides robustly (the same verdict
     * with rtol 1e-12 and 1e-9), verdict and number of right-half-plane
     * roots must agree */
    unsigned long long st = 0x853c49e6748fea9bULL;
    int i, disagree = 0, robust = 0;
    for (i = 0; i < 20000; i++) {
      autobal_pendulum_params p;
      double c[9], u[5];
      int v, nr, g1, g2, n1, n2, j, defl;
      for (j = 0; j < 5; j++) {
        st ^= st << 13, st ^= st >> 7, st ^= st << 17;
        u[j] = (double)(st >> 11) * (1.0 / 9007199254740992.0);
      }
      autobal_pendulum_params_from_k(6.0 * u[0], 0.005 + 0.49 * u[1], 0.5 * u[2], 0.5 * u[3],
                                     i % 10 == 0 ? 0.0 : u[4], &p, NULL);
      autobal_pendulum_verdict(&p, &v, &nr, NULL);
      autobal_pendulum_char_poly(&p, c, NULL);
      defl = i % 10 == 0; /* k = 0: lambda = 0 divided out, as the verdict does */
      autobal_poly_hurwitz(c + defl, (size_t)(9 - defl), 1e-12, &g1, &n1, NULL);
      autobal_poly_hurwitz(c + defl, (size_t)(9 - defl), 1e-9, &g2, &n2, NULL);
      if (g1 != g2 || g1 == AUTOBAL_VERDICT_MARGINAL) continue;
      robust++;
      if (v != g1 || nr != n1) disagree++;
    }
    CHECK("20000 random parameter sets: verdict and RHP count == generic Routh test", disagree == 0);
    CHECK("... on most of them (robustly decided)", robust > 19000);
  }

  printf("-- autobal_pendulum_verdict (scalar coefficients + quick Routh stage) vs the lanes path\n");
  {
    /* reference: autobal_pendulum_analyze, whose sign test runs on the lanes
     * form of (6) (char_poly_k) through the map's two-stage kernel and the
     * full test (the path autobal_pendulum_verdict took before); the verdict
     * and the count of right-half-plane roots must agree everywhere, also at
     * points within a few ulps of a stability boundary (where the quick
     * stage declines and the full test decides) */
    autobal_pendulum_workspace *ws = autobal_pendulum_workspace_alloc();
    unsigned long long st = 0x2545F4914F6CDD1DULL;
    int i, nbad = 0, bad_map = 0, nb = 0, nbm = 0, nstab = 0, nunst = 0, nmarg = 0;
#define U01() (st ^= st << 13, st ^= st >> 7, st ^= st << 17, \
               (double)(st >> 11) * (1.0 / 9007199254740992.0))
    for (i = 0; i < 12000; i++) {
      autobal_pendulum_params p;
      autobal_pendulum_result r;
      double Rw = i % 10 == 0 ? pow(10.0, 1.0 + 2.5 * U01()) : 6.0 * U01();
      double Rm = 0.001 + 0.498 * U01(), H = i % 7 == 0 ? 0.0 : 0.5 * U01();
      double h = i % 5 == 0 ? 0.0 : 0.5 * U01();
      double k = i % 10 == 1 ? 0.0 : i % 20 == 3 ? 1.0 : U01();
      int v = -9, nr = -9, s1, s2;
      autobal_pendulum_params_from_k(Rw, Rm, H, h, k, &p, NULL);
      s1 = autobal_pendulum_verdict(&p, &v, &nr, NULL);
      s2 = autobal_pendulum_analyze(ws, &p, &r);
      if (s1 != s2 || (s1 == 0 && (v != r.verdict || nr != r.n_rhp))) nbad++;
      nstab += v == AUTOBAL_VERDICT_STABLE, nunst += v == AUTOBAL_VERDICT_UNSTABLE;
      nmarg += v == AUTOBAL_VERDICT_MARGINAL;
      if (i % 4 == 0) { /* and the one-point map (its own lanes kernel) */
        autobal_pendulum_map_spec sp;
        signed char vm = 9;
        memset(&sp, 0, sizeof sp);
        sp.R_m = &Rm, sp.n_Rm = 1, sp.R_w = &Rw, sp.n_Rw = 1, sp.H = H, sp.h = h, sp.k = &k,
        sp.n_k = 1, sp.n_threads = 1;
        if (H == 0.0 && h == 0.0) continue; /* the map's undamped criterion: another test */
        if (autobal_pendulum_map(&sp, &vm, NULL, NULL) != 0 || vm != v) bad_map++;
      }
    }
    printf("   (12000 random points: %d stable, %d unstable, %d marginal)\n", nstab, nunst, nmarg);
    CHECK("12000 random points (k = 0, 1, H = 0, h = 0, R_w up to 3000): verdict, n_rhp == analyze",
          nbad == 0);
    nbad = 0;
    /* MARGINAL: damped points on a boundary only (k = 0 with h = 0 never occurs here; the
     * undamped ones are decided by (10)) */
    CHECK("... stable and unstable occur, marginal (damped boundaries) rarely",
          nstab > 1000 && nunst > 1000 && nmarg < 10);
    CHECK("... 1-point maps (damped; the map's own lanes kernel) == verdict", bad_map == 0);
    /* boundary points: along lines in R_w, the verdict changes are bracketed
     * to adjacent doubles; the points and 3 ulps either side */
    for (i = 0; i < 60; i++) {
      double Rm = 0.01 + 0.48 * U01(), H = i % 6 == 0 ? 0.0 : 0.3 * U01(), h = 0.02 + 0.3 * U01();
      double k = i % 5 == 0 ? 0.0 : U01(), prev = 0.05;
      int j, vprev = -9;
      for (j = 0; j <= 96; j++) {
        double Rw = 0.05 + 6.0 * j / 96.0;
        autobal_pendulum_params p;
        int v;
        autobal_pendulum_params_from_k(Rw, Rm, H, h, k, &p, NULL);
        autobal_pendulum_verdict(&p, &v, NULL, NULL);
        if (j > 0 && v != vprev) {
          /* every change between prev and Rw (e.g. unstable -> marginal ->
           * stable: both edges of the marginal band) */
          double a = prev;
          int va = vprev, guard;
          for (guard = 0; va != v && guard < 4; guard++) {
            double lo = a, hi = Rw, x;
            int m, d, vh = v;
            for (m = 0; m < 80 && nextafter(lo, hi) < hi; m++) {
              double mid = 0.5 * (lo + hi);
              int vm;
              autobal_pendulum_params_from_k(mid, Rm, H, h, k, &p, NULL);
              autobal_pendulum_verdict(&p, &vm, NULL, NULL);
              if (vm == va) lo = mid;
              else hi = mid, vh = vm;
            }
            for (x = lo, d = 0; d < 3; d++) x = nextafter(x, 0.0);
            for (d = 0; d < 8; d++, x = nextafter(x, INFINITY)) {
              autobal_pendulum_result r;
              int vv, nr;
              autobal_pendulum_params_from_k(x, Rm, H, h, k, &p, NULL);
              autobal_pendulum_verdict(&p, &vv, &nr, NULL);
              autobal_pendulum_analyze(ws, &p, &r);
              nb++;
              nbm += r.verdict == AUTOBAL_VERDICT_MARGINAL;
              if (vv != r.verdict || nr != r.n_rhp) nbad++;
            }
            a = hi, va = vh; /* continue right of this change */
          }
        }
        vprev = v, prev = Rw;
      }
    }
#undef U01
    printf("   (%d points at changes of the verdict, %d of them marginal)\n", nb, nbm);
    CHECK("points within 3 ulps of stability boundaries: verdict, n_rhp == analyze", nbad == 0);
    CHECK("... many boundary points, both edges of marginal bands", nb > 200 && nbm > 50 && nbm < nb - 50);
    autobal_pendulum_workspace_free(ws);
  }

  printf("-- errors\n");
  {
    double rm = 0.1, rw[5] = {1.0, 2.0, 3.0, 1e80, 4.0}, k = 0.5;
    signed char v[5];
    autobal_pendulum_map_spec s;
    autobal_pendulum_params p;
    autobal_error err;
    int vv;
    memset(&s, 0, sizeof s);
    s.R_m = &rm, s.n_Rm = 1, s.R_w = rw, s.n_Rw = 5, s.H = 0.05, s.h = 0.1, s.k = &k, s.n_k = 1;
    CHECK_STATUS("map: R_w = 1e80 (coefficients overflow) is reported",
                 autobal_pendulum_map(&s, v, NULL, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... as a failed grid point", err.message, "grid point");
    s.n_k = 0, s.k = NULL;
    CHECK_STATUS("map, 65 k: the same", autobal_pendulum_map(&s, v, NULL, &err), AUTOBAL_EINVAL);
    CHECK_STATUS("params: R_w = 1e80 is refused (the coefficients of (6) would overflow)",
                 autobal_pendulum_params_from_k(1e80, 0.1, 0.05, 0.1, 0.5, &p, &err), AUTOBAL_EINVAL);
    CHECK_MSG("... naming R_w", err.message, "R_w");
    CHECK_MSG("... and the bound", err.message, "1e+06");
    autobal_pendulum_params_from_k(1e6, 0.1, 0.05, 0.1, 0.5, &p, NULL);
    CHECK_STATUS("verdict: R_w = 1e6 (the bound) is computed", autobal_pendulum_verdict(&p, &vv, NULL, &err),
                 AUTOBAL_SUCCESS);
  }
  {
    /* autobal_pendulum_verdict validates with one combined test and leaves
     * the messages to autobal_pendulum_params_validate: every bad field is
     * reported with the same status and message, the edges are accepted */
    static const struct {
      int field;
      double value;
      const char *name;
    } cases[] = {{0, -1.0, "R_w"}, {0, NAN, "R_w"},      {0, INFINITY, "R_w"}, {1, 0.0, "R_m"},
               {1, 0.5, "R_m"},  {1, NAN, "R_m"},      {1, -0.1, "R_m"},     {2, -1e-300, "H"},
               {2, INFINITY, "H"}, {3, NAN, "h"},      {3, -1.0, "h"},       {4, -0.1, "psi0"},
               {4, 1.5707963267948966, "psi0"}, {4, NAN, "psi0"}, {4, INFINITY, "psi0"}};
    autobal_pendulum_params p0 = {1.0, 0.1, 0.05, 0.1, 0.3}, p;
    autobal_error e1, e2;
    size_t i;
    int v, alike = 1, named = 1, st1, st2;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
      double *f[5];
      p = p0;
      f[0] = &p.R_w, f[1] = &p.R_m, f[2] = &p.H, f[3] = &p.h, f[4] = &p.psi0;
      *f[cases[i].field] = cases[i].value;
      st1 = autobal_pendulum_verdict(&p, &v, NULL, &e1);
      st2 = autobal_pendulum_params_validate(&p, &e2);
      if (st1 != AUTOBAL_EINVAL || st2 != AUTOBAL_EINVAL || strcmp(e1.message, e2.message) != 0)
        alike = 0;
      if (strstr(e1.message, cases[i].name) == NULL) named = 0;
    }
    CHECK("verdict: 15 bad fields (NaN, inf, out of range) -> EINVAL, validate's message", alike);
    CHECK("... each message names the field", named);
    CHECK_STATUS("verdict: NULL parameters", autobal_pendulum_verdict(NULL, &v, NULL, &e1),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... message", e1.message, "NULL pointer");
    CHECK_STATUS("verdict: NULL verdict", autobal_pendulum_verdict(&p0, NULL, NULL, &e1),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... message", e1.message, "verdict: NULL output");
    p = p0, p.R_w = 0.0, p.H = 0.0, p.psi0 = 0.0;
    CHECK_STATUS("verdict: R_w = 0, H = 0, psi0 = 0 (edges) accepted",
                 autobal_pendulum_verdict(&p, &v, NULL, &e1), AUTOBAL_SUCCESS);
    p = p0, p.h = 0.0, p.R_m = 0.49999999999999994;
    CHECK_STATUS("verdict: h = 0, R_m = 0.5 - 2^-54 accepted",
                 autobal_pendulum_verdict(&p, &v, NULL, &e1), AUTOBAL_SUCCESS);
  }
  return check_summary();
}
