/* test_rotor_keys.c: every numeric configuration key of the rotor as a parameter of sweeps and
 * maps (autobal_rotor_stab_set with the key ids, docs/rotor.md "Sweeps and maps over any key").
 *
 * The handle changes a key on its working copy (the hardware set converted again, the lumped
 * base rescaled, a plane's scalars, every ball of a plane).  Each change is checked against the
 * other way to get the same rotor, which does not go through autobal_rotor_stab_set: the key
 * written into a copy of the parameter struct, and a new handle allocated from it.  Margins and
 * verdicts must agree (bit for bit: the same arithmetic is done on the same numbers).  Also:
 *  - names and ids round trip for every id of autobal_rotor_stab_param_list, bare aliases;
 *  - a critical value of plane1.d (the balancer's axial position) refined by the polynomial
 *    margin is a sign change of the largest real part of the eigenvalues of the closed first-order
 *    matrix (GSL's nonsymmetric eigensolver, not the polynomial);
 *  - a sweep over a hardware key, a track radius and the anisotropy restores every parameter and
 *    the margin bit for bit;
 *  - a map over (anisotropy, supports.c_Lx) equals the transposed map over (supports.c_Lx,
 *    anisotropy) and the direct computation at its points (a relative key is set last);
 *  - the error paths: a lumped key of a hardware rotor and the reverse, plane2 of a one-plane
 *    rotor, NaN, out-of-range values, an unknown id; a refused value changes nothing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>

#include "autobal.h"
#include "check.h"

/* Margin and verdict of a fresh handle on p at its omega. */
static int fresh_margin(const autobal_rotor_params *p, double *mg, int *v) {
  autobal_error e;
  autobal_rotor_stab *h;
  int st;
  autobal_error_clear(&e);
  h = autobal_rotor_stab_alloc(p, NULL, &e);
  if (!h) return e.status ? e.status : AUTOBAL_EINVAL;
  st = autobal_rotor_stab_margin(h, AUTOBAL_ROTOR_STAB_AUTO, mg, v);
  autobal_rotor_stab_free(h);
  return st;
}

/* Margin via a handle that was set to `value` for `param` after allocation from p. */
static int set_margin(const autobal_rotor_params *p, int param, double value, double *mg, int *v) {
  autobal_rotor_stab *h = autobal_rotor_stab_alloc(p, NULL, NULL);
  int st;
  if (!h) return AUTOBAL_ENOMEM;
  st = autobal_rotor_stab_set(h, param, value);
  if (st == AUTOBAL_SUCCESS) st = autobal_rotor_stab_margin(h, AUTOBAL_ROTOR_STAB_AUTO, mg, v);
  autobal_rotor_stab_free(h);
  return st;
}

static void compare(const char *key, const autobal_rotor_params *base, int param, double value,
                    const autobal_rotor_params *direct) {
  double m1 = NAN, m2 = NAN;
  int v1 = 9, v2 = 9, s1, s2;
  char what[200];
  s1 = set_margin(base, param, value, &m1, &v1);
  s2 = fresh_margin(direct, &m2, &v2);
  snprintf(what, sizeof what, "%s = %.6g: status via the key", key, value);
  CHECK_STATUS(what, s1, s2);
  if (s1 != AUTOBAL_SUCCESS || s2 != AUTOBAL_SUCCESS) return;
  snprintf(what, sizeof what, "%s = %.6g: margin via the key = margin of the struct (%.9g, verdict %d)", key, value,
           m2, v2);
  CHECK(what, (m1 == m2 || (isnan(m1) && isnan(m2))) && v1 == v2);
}

/* Largest real part of the eigenvalues of the closed first-order matrix at the handle's state. */
static double matrix_margin(autobal_rotor_stab *h) {
  autobal_rotor_closed c;
  double a[AUTOBAL_ROTOR_CLOSED_MAX * AUTOBAL_ROTOR_CLOSED_MAX], mx = -INFINITY;
  size_t n, i;
  gsl_matrix_view mv;
  gsl_vector_complex *ev;
  gsl_eigen_nonsymm_workspace *w;
  if (autobal_rotor_stab_closed(h, &c) != AUTOBAL_SUCCESS) return NAN;
  n = autobal_rotor_closed_dim(&c);
  if (autobal_rotor_closed_matrix(&c, a, n, NULL) != AUTOBAL_SUCCESS) return NAN;
  mv = gsl_matrix_view_array(a, n, n);
  ev = gsl_vector_complex_alloc(n);
  w = gsl_eigen_nonsymm_alloc(n);
  if (gsl_eigen_nonsymm(&mv.matrix, ev, w) == 0)
    for (i = 0; i < n; i++) {
      const double re = GSL_REAL(gsl_vector_complex_get(ev, i)), im = GSL_IMAG(gsl_vector_complex_get(ev, i));
      /* skip exact zeros (a neutral family root; two balls have none, so nothing is skipped here) */
      if (fabs(re) + fabs(im) > 1e-9 && re > mx) mx = re;
    }
  gsl_eigen_nonsymm_free(w);
  gsl_vector_complex_free(ev);
  return mx;
}

int main(void) {
  const autobal_rotor_params def = autobal_rotor_params_default();
  autobal_rotor_params p;
  const autobal_rotor_field *hw = NULL, *lu = NULL;
  size_t nh = 0, nl = 0, i, n, k;
  int *ids;
  char what[256];

  /* ---- names and ids ---- */
  hw = autobal_rotor_hardware_fields(&nh);
  lu = autobal_rotor_lumped_fields(&nl);
  n = autobal_rotor_stab_param_list(NULL, 0);
  CHECK("param_list counts 8 named ids, the hardware and lumped fields and 2 x 8 plane keys",
        n == 8 + nh + nl + 2 * AUTOBAL_ROTOR_PLANE_N_KEYS);
  ids = (int *)malloc(n * sizeof *ids);
  CHECK("param_list fills n ids", ids && autobal_rotor_stab_param_list(ids, n) == n);
  {
    size_t bad = 0;
    for (k = 0; ids && k < n; k++) {
      const char *nm = autobal_rotor_stab_param_name(ids[k]);
      if (!nm || !autobal_rotor_stab_param_unit(ids[k]) || autobal_rotor_stab_param_from_name(nm) != ids[k]) bad++;
    }
    CHECK("every id: name, unit, and the name maps back to the id", bad == 0);
  }
  CHECK("supports.c_Lx is hardware field", autobal_rotor_stab_param_from_name("supports.c_Lx") ==
                                               AUTOBAL_ROTOR_PARAM_HARDWARE(7));
  CHECK("bare c_Lx is the same key", autobal_rotor_stab_param_from_name("c_Lx") ==
                                         autobal_rotor_stab_param_from_name("supports.c_Lx"));
  CHECK("bare h_yalpha is lumped.h_yalpha", autobal_rotor_stab_param_from_name("h_yalpha") ==
                                                autobal_rotor_stab_param_from_name("lumped.h_yalpha"));
  CHECK("rotor.omega is omega", autobal_rotor_stab_param_from_name("rotor.omega") == AUTOBAL_ROTOR_PARAM_OMEGA);
  CHECK("plane2.psi0 id", autobal_rotor_stab_param_from_name("plane2.psi0") ==
                              AUTOBAL_ROTOR_PARAM_PLANE(1, AUTOBAL_ROTOR_PLANE_PSI0));
  CHECK("unknown names: -1", autobal_rotor_stab_param_from_name("supports.c_Lq") == -1 &&
                                 autobal_rotor_stab_param_from_name("plane3.d") == -1 &&
                                 autobal_rotor_stab_param_from_name("d") == -1 &&
                                 autobal_rotor_stab_param_from_name(NULL) == -1);
  CHECK("unknown ids: NULL names", !autobal_rotor_stab_param_name(8) && !autobal_rotor_stab_param_name(99) &&
                                       !autobal_rotor_stab_param_name(100 + (int)nh) &&
                                       !autobal_rotor_stab_param_name(AUTOBAL_ROTOR_PARAM_PLANE(2, 0)) &&
                                       !autobal_rotor_stab_param_name(AUTOBAL_ROTOR_PARAM_PLANE(0, 8)));
  free(ids);

  /* ---- every hardware field of the default rotor ---- */
  for (i = 0; i < nh; i++) {
    double v;
    p = def;
    v = autobal_rotor_field_get(&p.hw, &hw[i]);
    v = v != 0.0 ? 1.37 * v : 0.5 * (hw[i].unit[0] == 'N' ? 1e5 : 1.0);
    *autobal_rotor_field_ptr(&p.hw, &hw[i]) = v;
    compare(hw[i].key, &def, AUTOBAL_ROTOR_PARAM_HARDWARE(i), v, &p);
  }

  /* ---- every lumped field of the same rotor given as a lumped set ---- */
  {
    autobal_rotor_params pl = def;
    pl.input = AUTOBAL_ROTOR_LUMPED;
    CHECK_STATUS("lumped set of the default hardware", autobal_rotor_lumped_from_hardware(&def.hw, &pl.lumped, NULL),
                 AUTOBAL_SUCCESS);
    for (i = 0; i < nl; i++) {
      double v;
      p = pl;
      v = autobal_rotor_field_get(&p.lumped, &lu[i]);
      /* 0.9: keeps the 2x2 blocks positive semidefinite when an off-diagonal term grows */
      v = v != 0.0 ? 0.9 * v : 1.0;
      *autobal_rotor_field_ptr(&p.lumped, &lu[i]) = v;
      compare(lu[i].key, &pl, AUTOBAL_ROTOR_PARAM_LUMPED(i), v, &p);
    }
    /* anisotropy and C/A on the lumped set */
    p = pl;
    p.lumped.c_y = 0.6 * p.lumped.c_x;
    p.lumped.c_alpha = 0.6 * p.lumped.c_beta;
    p.lumped.c_yalpha = 0.6 * p.lumped.c_xbeta;
    compare("anisotropy (lumped)", &pl, AUTOBAL_ROTOR_PARAM_ANISOTROPY, 0.6, &p);
    p = pl;
    p.lumped.C = 0.8 * p.lumped.A;
    compare("C_over_A (lumped)", &pl, AUTOBAL_ROTOR_PARAM_C_OVER_A, 0.8, &p);
    {
      autobal_rotor_stab *h = autobal_rotor_stab_alloc(&pl, NULL, NULL);
      int st = autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_HARDWARE(0), 3.0);
      CHECK_STATUS("a hardware key of a lumped rotor is refused", st, AUTOBAL_EINVAL);
      CHECK_MSG("... naming the key", autobal_rotor_stab_errmsg(h), "rotor.M_k");
      CHECK("get of a hardware key of a lumped rotor is NaN", isnan(autobal_rotor_stab_get(h, AUTOBAL_ROTOR_PARAM_HARDWARE(0))));
      autobal_rotor_stab_free(h);
    }
  }

  /* ---- anisotropy and C/A on the hardware ---- */
  p = def;
  p.hw.c_Ly = 1.5 * p.hw.c_Lx;
  p.hw.c_Ry = 1.5 * p.hw.c_Rx;
  compare("anisotropy", &def, AUTOBAL_ROTOR_PARAM_ANISOTROPY, 1.5, &p);
  p = def;
  p.hw.C_p = 0.3 * (p.hw.A_k + p.hw.A_p);
  compare("C_over_A", &def, AUTOBAL_ROTOR_PARAM_C_OVER_A, 0.3, &p);

  /* ---- the keys of plane 1 ---- */
  {
    double mass[2], rad[2], damp[2];
    const autobal_rotor_plane *d0 = &def.plane[0];
    struct {
      int key;
      double v;
    } cases[] = {{AUTOBAL_ROTOR_PLANE_D, -0.05},        {AUTOBAL_ROTOR_PLANE_M0, 0.9 * d0->m0},
                 {AUTOBAL_ROTOR_PLANE_R0, 1.2 * d0->r0}, {AUTOBAL_ROTOR_PLANE_PSI0, 0.7},
                 {AUTOBAL_ROTOR_PLANE_UNBALANCE, 0.004}, {AUTOBAL_ROTOR_PLANE_BALL_MASS, 0.07},
                 {AUTOBAL_ROTOR_PLANE_BALL_RADIUS, 0.12}, {AUTOBAL_ROTOR_PLANE_BALL_DAMPING, 3.0}};
    for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
      p = def;
      memcpy(mass, d0->ball_mass, 2 * sizeof *mass);
      memcpy(rad, d0->ball_radius, 2 * sizeof *rad);
      memcpy(damp, d0->ball_damping, 2 * sizeof *damp);
      p.plane[0].ball_mass = mass;
      p.plane[0].ball_radius = rad;
      p.plane[0].ball_damping = damp;
      switch (cases[k].key) {
        case AUTOBAL_ROTOR_PLANE_D: p.plane[0].d = cases[k].v; break;
        case AUTOBAL_ROTOR_PLANE_M0: p.plane[0].m0 = cases[k].v; break;
        case AUTOBAL_ROTOR_PLANE_R0: p.plane[0].r0 = cases[k].v; break;
        case AUTOBAL_ROTOR_PLANE_PSI0: p.plane[0].psi0 = cases[k].v; break;
        case AUTOBAL_ROTOR_PLANE_UNBALANCE: p.plane[0].m0 = cases[k].v / p.plane[0].r0; break;
        case AUTOBAL_ROTOR_PLANE_BALL_MASS: mass[0] = mass[1] = cases[k].v; break;
        case AUTOBAL_ROTOR_PLANE_BALL_RADIUS: rad[0] = rad[1] = cases[k].v; break;
        default: damp[0] = damp[1] = cases[k].v; break;
      }
      compare(autobal_rotor_stab_param_name(AUTOBAL_ROTOR_PARAM_PLANE(0, cases[k].key)), &def,
              AUTOBAL_ROTOR_PARAM_PLANE(0, cases[k].key), cases[k].v, &p);
    }
  }

  /* ---- a critical value of plane1.d against the closed matrix's eigenvalues ---- */
  {
    autobal_rotor_stab *h = autobal_rotor_stab_alloc(&def, NULL, NULL);
    autobal_rotor_crit cr;
    const int pd = AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_D);
    int st = autobal_rotor_stab_critical(h, pd, -0.2, 0.15, 200, 1e-10, &cr);
    CHECK_STATUS("critical values of plane1.d in [-0.2, 0.15] m", st, AUTOBAL_SUCCESS);
    CHECK("at least one critical value of plane1.d", cr.n >= 1);
    for (k = 0; k < cr.n; k++) {
      const double x = cr.value[k], dx = 1e-6 * (1.0 + fabs(x));
      double below, above;
      autobal_rotor_stab_set(h, pd, x - dx);
      below = matrix_margin(h);
      autobal_rotor_stab_set(h, pd, x + dx);
      above = matrix_margin(h);
      snprintf(what, sizeof what,
               "plane1.d critical %.10g m: closed-matrix eigenvalues change side there (max Re %.3g below, %.3g above, "
               "kind %+d)",
               x, below, above, cr.kind[k]);
      CHECK(what, cr.kind[k] == +1 ? (below > 0 && above < 0) : (below < 0 && above > 0));
    }
    autobal_rotor_stab_free(h);
  }

  /* ---- sweeps restore everything ---- */
  {
    autobal_rotor_stab *h = autobal_rotor_stab_alloc(&def, NULL, NULL);
    const int keys[3] = {AUTOBAL_ROTOR_PARAM_HARDWARE(7), AUTOBAL_ROTOR_PARAM_PLANE(0, AUTOBAL_ROTOR_PLANE_BALL_RADIUS),
                         AUTOBAL_ROTOR_PARAM_ANISOTROPY};
    const double vals[3][3] = {{5e4, 2e5, 4e5}, {0.05, 0.1, 0.2}, {0.5, 1.0, 1.5}};
    double m0, m1, mg[3], before[3];
    int v0, v1, vd[3];
    autobal_rotor_stab_margin(h, AUTOBAL_ROTOR_STAB_AUTO, &m0, &v0);
    for (k = 0; k < 3; k++) before[k] = autobal_rotor_stab_get(h, keys[k]);
    for (k = 0; k < 3; k++) {
      size_t j;
      int st = autobal_rotor_stab_sweep(h, keys[k], vals[k], 3, mg, vd);
      snprintf(what, sizeof what, "sweep over %s", autobal_rotor_stab_param_name(keys[k]));
      CHECK_STATUS(what, st, AUTOBAL_SUCCESS);
      for (j = 0; j < 3; j++) {
        double md;
        int vdd;
        set_margin(&def, keys[k], vals[k][j], &md, &vdd);
        snprintf(what, sizeof what, "sweep over %s at %g = a handle set there", autobal_rotor_stab_param_name(keys[k]),
                 vals[k][j]);
        CHECK(what, md == mg[j] && vdd == vd[j]);
      }
    }
    autobal_rotor_stab_margin(h, AUTOBAL_ROTOR_STAB_AUTO, &m1, &v1);
    CHECK("after the sweeps: the same margin bit for bit", m0 == m1 && v0 == v1);
    for (k = 0; k < 3; k++) {
      snprintf(what, sizeof what, "after the sweeps: %s restored", autobal_rotor_stab_param_name(keys[k]));
      CHECK(what, autobal_rotor_stab_get(h, keys[k]) == before[k]);
    }
    /* refused values change nothing */
    CHECK_STATUS("plane2.d of a one-plane rotor", autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_PLANE(1, 0), 0.0),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... names it", autobal_rotor_stab_errmsg(h), "plane2.d");
    CHECK_STATUS("lumped.c_x of a hardware rotor", autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_LUMPED(3), 1e5),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... names it", autobal_rotor_stab_errmsg(h), "lumped.c_x");
    CHECK_STATUS("supports.c_Lx = NaN", autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_HARDWARE(7), NAN),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... names it", autobal_rotor_stab_errmsg(h), "c_Lx");
    CHECK_STATUS("supports.c_Lx = -1", autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_HARDWARE(7), -1.0),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... names it with its range", autobal_rotor_stab_errmsg(h), "allowed range");
    CHECK_STATUS("supports.l_L = -l_R (supports in one plane)",
                 autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_HARDWARE(5), -def.hw.l_R), AUTOBAL_EINVAL);
    CHECK_MSG("... names the key", autobal_rotor_stab_errmsg(h), "supports.l_L");
    CHECK_STATUS("plane1.ball_radius = 0", autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_PLANE(0, 6), 0.0),
                 AUTOBAL_EINVAL);
    CHECK_MSG("... names it", autobal_rotor_stab_errmsg(h), "plane1.ball_radius");
    CHECK_STATUS("anisotropy = 0", autobal_rotor_stab_set(h, AUTOBAL_ROTOR_PARAM_ANISOTROPY, 0.0), AUTOBAL_EINVAL);
    CHECK_STATUS("id 999", autobal_rotor_stab_set(h, 999, 1.0), AUTOBAL_EINVAL);
    autobal_rotor_stab_margin(h, AUTOBAL_ROTOR_STAB_AUTO, &m1, &v1);
    CHECK("after the refused values: the same margin bit for bit", m0 == m1 && v0 == v1);
    for (k = 0; k < 3; k++) {
      snprintf(what, sizeof what, "after the refused values: %s unchanged", autobal_rotor_stab_param_name(keys[k]));
      CHECK(what, autobal_rotor_stab_get(h, keys[k]) == before[k]);
    }
    autobal_rotor_stab_free(h);
  }

  /* ---- a map with a relative key: the order of the axes does not matter ---- */
  {
    const double va[2] = {0.7, 1.3}, vc[2] = {1e5, 2.5e5};
    const int pa = AUTOBAL_ROTOR_PARAM_ANISOTROPY, pc = AUTOBAL_ROTOR_PARAM_HARDWARE(7);
    double ma[4], mc[4];
    int da[4], dc[4], st1, st2;
    size_t a, c, bad = 0, bad_direct = 0;
    autobal_error e;
    autobal_error_clear(&e);
    st1 = autobal_rotor_stab_map(&def, NULL, pa, va, 2, pc, vc, 2, 1, ma, da, &e);
    st2 = autobal_rotor_stab_map(&def, NULL, pc, vc, 2, pa, va, 2, 1, mc, dc, &e);
    CHECK_STATUS("map (anisotropy, supports.c_Lx)", st1, AUTOBAL_SUCCESS);
    CHECK_STATUS("map (supports.c_Lx, anisotropy)", st2, AUTOBAL_SUCCESS);
    for (a = 0; a < 2; a++)
      for (c = 0; c < 2; c++) {
        double md;
        int vdd;
        if (!(ma[a * 2 + c] == mc[c * 2 + a] && da[a * 2 + c] == dc[c * 2 + a])) bad++;
        p = def;
        p.hw.c_Lx = vc[c];
        p.hw.c_Ly = va[a] * vc[c];
        p.hw.c_Ry = va[a] * p.hw.c_Rx;
        if (fresh_margin(&p, &md, &vdd) != AUTOBAL_SUCCESS || md != ma[a * 2 + c] || vdd != da[a * 2 + c])
          bad_direct++;
      }
    CHECK("the two maps are transposes of each other", bad == 0);
    CHECK("every map point = the rotor with c_Lx and c_Ly = a c_Lx, c_Ry = a c_Rx", bad_direct == 0);
  }
  return check_summary();
}
