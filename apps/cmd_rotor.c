/* cmd_rotor.c: `autobal rotor transient`: the rotor in a massive housing with one or two ball
 * autobalancers (spec rotor.md), integrated in time, streamed to HDF5, summarised for a person. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/archive.h"
#include "autobal/rotor.h"
#include "autobal/transient.h"
#include "cli.h"

#define MAX_CFG_BALLS 4096
#define TWO_PI 6.283185307179586476925286766559

typedef struct rotor_cfg {
  autobal_rotor_params p;
  double mass[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS];
  double radius[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS];
  double damping[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS];
  double psi[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS];
  double rate[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS];
  /* [transient] */
  double t_end, dt_out, rtol, atol, h_max, balance_tol, balance_revs;
  long max_steps;
  const char *stepper, *frame_name;
  int frame, stop_at_balance;
} rotor_cfg;

static int get_d(cli_ctx *ctx, const char *sec, const char *key, double *v) {
  return cli_get_double(ctx, sec, key, *v, v, NULL);
}

static int read_plane(cli_ctx *ctx, rotor_cfg *c, size_t j, const char *sec) {
  autobal_rotor_plane *pl = &c->p.plane[j];
  size_t nm, nr, nh, np, nv;
  int rc, pm, pr, ph, pp, pv;
  if ((rc = get_d(ctx, sec, "d", &pl->d))) return rc;
  if ((rc = get_d(ctx, sec, "m0", &pl->m0))) return rc;
  if ((rc = get_d(ctx, sec, "r0", &pl->r0))) return rc;
  if ((rc = get_d(ctx, sec, "psi0", &pl->psi0))) return rc;
  if ((rc = cli_get_doubles(ctx, sec, "ball_mass", c->mass[j], MAX_CFG_BALLS, &nm, &pm))) return rc;
  if ((rc = cli_get_doubles(ctx, sec, "ball_radius", c->radius[j], MAX_CFG_BALLS, &nr, &pr))) return rc;
  if ((rc = cli_get_doubles(ctx, sec, "ball_damping", c->damping[j], MAX_CFG_BALLS, &nh, &ph))) return rc;
  if ((rc = cli_get_doubles(ctx, sec, "ball_psi", c->psi[j], MAX_CFG_BALLS, &np, &pp))) return rc;
  if ((rc = cli_get_doubles(ctx, sec, "ball_rate", c->rate[j], MAX_CFG_BALLS, &nv, &pv))) return rc;
  {
    /* n = the number of balls: from ball_mass when given, else the current (default) count.  Each
     * other list has n values or one value for all; a list left out keeps the current values when
     * n is unchanged, else radius and damping are required and angles/rates default to 0. */
    size_t n = pm ? nm : pl->n_balls, i;
    struct {
      const char *name;
      double *v;
      size_t cnt;
      int present;
      double def;
    } lists[4];
    lists[0].name = "ball_radius", lists[0].v = c->radius[j], lists[0].cnt = nr, lists[0].present = pr, lists[0].def = NAN;
    lists[1].name = "ball_damping", lists[1].v = c->damping[j], lists[1].cnt = nh, lists[1].present = ph, lists[1].def = NAN;
    lists[2].name = "ball_psi", lists[2].v = c->psi[j], lists[2].cnt = np, lists[2].present = pp, lists[2].def = 0.0;
    lists[3].name = "ball_rate", lists[3].v = c->rate[j], lists[3].cnt = nv, lists[3].present = pv, lists[3].def = 0.0;
    for (i = 0; i < 4; i++) {
      size_t k;
      if (!lists[i].present) {
        if (n == pl->n_balls) continue;
        if (isnan(lists[i].def))
          return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: ball_mass has %zu values, so %s is required (%zu values, or one for all)",
                          sec, n, lists[i].name, n);
        for (k = 0; k < n; k++) lists[i].v[k] = lists[i].def;
      } else if (n == 0) {
        return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s is given but there are no balls (give ball_mass)", sec, lists[i].name);
      } else if (lists[i].cnt == 1 && n > 1) {
        for (k = 1; k < n; k++) lists[i].v[k] = lists[i].v[0];
      } else if (lists[i].cnt != n) {
        return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s has %zu values but there are %zu balls (ball_mass)", sec,
                        lists[i].name, lists[i].cnt, n);
      }
    }
    pl->n_balls = n;
  }
  pl->ball_mass = c->mass[j];
  pl->ball_radius = c->radius[j];
  pl->ball_damping = c->damping[j];
  pl->ball_psi = c->psi[j];
  pl->ball_rate = c->rate[j];
  return CLI_EXIT_OK;
}

static int read_rotor_model(cli_ctx *ctx, rotor_cfg *c) {
  autobal_rotor_hardware *hw = &c->p.hw;
  autobal_rotor_lumped *lu = &c->p.lumped;
  const char *inertia = "paper";
  int rc, axial = 0, has_plane2;
  size_t i;
  autobal_rotor_params def = autobal_rotor_params_default();

  c->p = def;
  /* copy the default balls into our own arrays so that lists can be edited */
  for (i = 0; i < def.plane[0].n_balls && i < MAX_CFG_BALLS; i++) {
    c->mass[0][i] = def.plane[0].ball_mass[i];
    c->radius[0][i] = def.plane[0].ball_radius[i];
    c->damping[0][i] = def.plane[0].ball_damping[i];
    c->psi[0][i] = def.plane[0].ball_psi ? def.plane[0].ball_psi[i] : 0.0;
    c->rate[0][i] = def.plane[0].ball_rate ? def.plane[0].ball_rate[i] : 0.0;
  }
  /* [rotor] */
  if ((rc = get_d(ctx, "rotor", "M_k", &hw->M_k))) return rc;
  if ((rc = get_d(ctx, "rotor", "A_k", &hw->A_k))) return rc;
  if ((rc = get_d(ctx, "rotor", "m_p", &hw->m_p))) return rc;
  if ((rc = get_d(ctx, "rotor", "A_p", &hw->A_p))) return rc;
  if ((rc = get_d(ctx, "rotor", "C_p", &hw->C_p))) return rc;
  if ((rc = get_d(ctx, "rotor", "omega", &c->p.omega))) return rc;
  if ((rc = cli_get_string(ctx, "rotor", "inertia", inertia, &inertia, NULL))) return rc;
  if ((rc = cli_get_bool(ctx, "rotor", "axial", 0, &axial, NULL))) return rc;
  if (!strcmp(inertia, "paper")) c->p.inertia = AUTOBAL_ROTOR_INERTIA_PAPER;
  else if (!strcmp(inertia, "full")) c->p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  else return cli_fail(ctx, CLI_EXIT_INPUT, "[rotor]: inertia = '%s' is not one of: paper, full", inertia);
  c->p.axial = axial;
  /* [supports] */
  if ((rc = get_d(ctx, "supports", "l_L", &hw->l_L))) return rc;
  if ((rc = get_d(ctx, "supports", "l_R", &hw->l_R))) return rc;
  if ((rc = get_d(ctx, "supports", "c_Lx", &hw->c_Lx))) return rc;
  if ((rc = get_d(ctx, "supports", "c_Ly", &hw->c_Ly))) return rc;
  if ((rc = get_d(ctx, "supports", "c_Lz", &hw->c_Lz))) return rc;
  if ((rc = get_d(ctx, "supports", "c_Rx", &hw->c_Rx))) return rc;
  if ((rc = get_d(ctx, "supports", "c_Ry", &hw->c_Ry))) return rc;
  if ((rc = get_d(ctx, "supports", "h_Lx", &hw->h_Lx))) return rc;
  if ((rc = get_d(ctx, "supports", "h_Ly", &hw->h_Ly))) return rc;
  if ((rc = get_d(ctx, "supports", "h_Lz", &hw->h_Lz))) return rc;
  if ((rc = get_d(ctx, "supports", "h_Rx", &hw->h_Rx))) return rc;
  if ((rc = get_d(ctx, "supports", "h_Ry", &hw->h_Ry))) return rc;
  /* [lumped]: if present, the lumped coefficients are authoritative (all must be given) */
  if (cli_section_present(ctx, "lumped")) {
    static const char *const keys[] = {"M", "A", "C", "c_x", "c_y", "c_z", "c_alpha", "c_beta", "c_xbeta",
                                       "c_yalpha", "h_x", "h_y", "h_z", "h_alpha", "h_beta", "h_xbeta", "h_yalpha"};
    double *dst[] = {&lu->M, &lu->A, &lu->C, &lu->c_x, &lu->c_y, &lu->c_z, &lu->c_alpha, &lu->c_beta, &lu->c_xbeta,
                     &lu->c_yalpha, &lu->h_x, &lu->h_y, &lu->h_z, &lu->h_alpha, &lu->h_beta, &lu->h_xbeta,
                     &lu->h_yalpha};
    for (i = 0; i < sizeof keys / sizeof keys[0]; i++) {
      int present;
      if ((rc = cli_get_double(ctx, "lumped", keys[i], 0.0, dst[i], &present))) return rc;
      if (!present)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[lumped]: '%s' is missing (with a [lumped] section all of M, A, C, c_x, c_y, c_z, c_alpha, c_beta, c_xbeta, c_yalpha and the h_ analogues are required)", keys[i]);
    }
    c->p.input = AUTOBAL_ROTOR_LUMPED;
  }
  /* [initial] */
  if ((rc = get_d(ctx, "initial", "x", &c->p.q0[0]))) return rc;
  if ((rc = get_d(ctx, "initial", "y", &c->p.q0[1]))) return rc;
  if ((rc = get_d(ctx, "initial", "alpha", &c->p.q0[2]))) return rc;
  if ((rc = get_d(ctx, "initial", "beta", &c->p.q0[3]))) return rc;
  if ((rc = get_d(ctx, "initial", "x_rate", &c->p.qd0[0]))) return rc;
  if ((rc = get_d(ctx, "initial", "y_rate", &c->p.qd0[1]))) return rc;
  if ((rc = get_d(ctx, "initial", "alpha_rate", &c->p.qd0[2]))) return rc;
  if ((rc = get_d(ctx, "initial", "beta_rate", &c->p.qd0[3]))) return rc;
  if ((rc = get_d(ctx, "initial", "z", &c->p.z0))) return rc;
  if ((rc = get_d(ctx, "initial", "z_rate", &c->p.zd0))) return rc;
  /* planes */
  if ((rc = read_plane(ctx, c, 0, "plane1"))) return rc;
  has_plane2 = cli_section_present(ctx, "plane2");
  if (has_plane2) {
    memset(&c->p.plane[1], 0, sizeof c->p.plane[1]);
    if ((rc = read_plane(ctx, c, 1, "plane2"))) return rc;
    c->p.n_planes = 2;
  } else {
    c->p.n_planes = 1;
  }
  return CLI_EXIT_OK;
}

int cli_rotor_config_read(cli_ctx *ctx, autobal_rotor_params *p, void **storage) {
  rotor_cfg *c = calloc(1, sizeof *c);
  int rc;
  *storage = NULL;
  if (!c) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  rc = read_rotor_model(ctx, c);
  if (rc) {
    free(c);
    return rc;
  }
  *p = c->p; /* the ball arrays point into c, which the caller frees with free(*storage) */
  *storage = c;
  return CLI_EXIT_OK;
}

static int read_rotor_config(cli_ctx *ctx, rotor_cfg *c) {
  int rc;
  if ((rc = read_rotor_model(ctx, c))) return rc;
  /* [transient] */
  c->t_end = 20.0;
  c->dt_out = 0.0; /* 0: revs_out */
  c->rtol = 1e-8;
  c->atol = 1e-10;
  c->h_max = 0.0;
  c->max_steps = 100000000L;
  c->balance_tol = 0.01;
  c->balance_revs = 50;
  c->stepper = "rk8pd";
  c->frame_name = "fixed";
  {
    double revs_out = 0.25;
    int has_dt = 0, has_revs = 0, has_brevs = 0, has_dwell = 0;
    double dwell = 0.0;
    if ((rc = get_d(ctx, "transient", "t_end", &c->t_end))) return rc;
    if ((rc = cli_get_double(ctx, "transient", "dt_out", 0.0, &c->dt_out, &has_dt))) return rc;
    if ((rc = cli_get_double(ctx, "transient", "revs_out", revs_out, &revs_out, &has_revs))) return rc;
    if ((rc = get_d(ctx, "transient", "rtol", &c->rtol))) return rc;
    if ((rc = get_d(ctx, "transient", "atol", &c->atol))) return rc;
    if ((rc = get_d(ctx, "transient", "h_max", &c->h_max))) return rc;
    if ((rc = cli_get_int(ctx, "transient", "max_steps", c->max_steps, &c->max_steps, NULL))) return rc;
    if ((rc = cli_get_string(ctx, "transient", "stepper", c->stepper, &c->stepper, NULL))) return rc;
    if ((rc = cli_get_string(ctx, "transient", "frame", c->frame_name, &c->frame_name, NULL))) return rc;
    if ((rc = get_d(ctx, "transient", "balance_tol", &c->balance_tol))) return rc;
    if ((rc = cli_get_double(ctx, "transient", "balance_revs", c->balance_revs, &c->balance_revs, &has_brevs))) return rc;
    if ((rc = cli_get_double(ctx, "transient", "balance_dwell", 0.0, &dwell, &has_dwell))) return rc;
    if ((rc = cli_get_bool(ctx, "transient", "stop_at_balance", 0, &c->stop_at_balance, NULL))) return rc;
    if (has_dt && has_revs) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give dt_out or revs_out, not both");
    if (!(c->t_end > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: t_end = %g s is out of range: allowed (0, inf)", c->t_end);
    if (!has_dt) {
      if (!(revs_out > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: revs_out = %g is out of range: allowed (0, inf)", revs_out);
      if (!(fabs(c->p.omega) > 0))
        return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: revs_out needs omega != 0; give dt_out (s) instead");
      c->dt_out = revs_out * TWO_PI / fabs(c->p.omega);
    }
    if (!(c->dt_out > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: dt_out = %g s is out of range: allowed (0, inf)", c->dt_out);
    if (c->t_end / c->dt_out > 5e8)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: t_end/dt_out = %.3g samples is too many (at most 5e8)", c->t_end / c->dt_out);
    if (!(c->balance_tol > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_tol = %g is out of range: allowed (0, inf)", c->balance_tol);
    if (!(fabs(c->p.omega) > 0) && !has_dwell)
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "[transient]: with rotor.omega = 0 there are no revolutions: give balance_dwell (s) instead of "
                      "balance_revs, and dt_out (s)");
    if (has_brevs && has_dwell)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give balance_revs (revolutions) or balance_dwell (s), not both");
    if (has_dwell) {
      if (!(dwell >= 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_dwell = %g s is out of range: allowed [0, inf)", dwell);
      if (!(fabs(c->p.omega) > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_dwell needs omega != 0");
      c->balance_revs = dwell * fabs(c->p.omega) / TWO_PI;
    }
    if (!(c->balance_revs >= 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_revs = %g is out of range: allowed [0, inf)", c->balance_revs);
    if (c->max_steps < 1) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: max_steps = %ld is out of range: allowed [1, inf)", c->max_steps);
    if (!strcmp(c->frame_name, "fixed")) c->frame = AUTOBAL_ROTOR_FIXED;
    else if (!strcmp(c->frame_name, "rotating")) c->frame = AUTOBAL_ROTOR_ROTATING;
    else return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: frame = '%s' is not one of: fixed, rotating", c->frame_name);
  }
  return CLI_EXIT_OK;
}

/* ---- the run -------------------------------------------------------------------------- */
typedef struct run_ctx {
  cli_ctx *ctx;
  autobal_rotor *rotor;
  int frame;
  size_t dim, nout, ncols;
  double *row;         /* one sample: state + outputs */
  autobal_archive_series *series;
  autobal_archive_series *revs;
  int io_failed;
  /* per-revolution summary */
  double rev_period, rev_t0, rev_max_G, rev_max_s;
  unsigned long rev_index; /* revolutions completed */
  double *rev_max_D;   /* per plane */
  double *rev_row;
  size_t n_planes;
  /* summary */
  size_t idx_amp_G, idx_s_rel0;
  double amp_first, amp_last, t_first_window, t_last_window_start;
  double max_amp;
  double t_end;
  int first_sample_done;
  double s_rel_initial, amp_initial;
} run_ctx;

static size_t plane_base(size_t j) { return 3 + 7 * j; }

static int observer(double t, const double y[], void *user) {
  run_ctx *r = user;
  double *out = r->row + r->dim;
  size_t j;
  memcpy(r->row, y, r->dim * sizeof *y);
  if (autobal_rotor_outputs(r->rotor, r->frame, t, y, out, r->nout) != AUTOBAL_SUCCESS) return 1;
  if (!r->first_sample_done) {
    r->first_sample_done = 1;
    r->amp_initial = out[0];
    r->s_rel_initial = out[plane_base(0) + 5];
    r->rev_t0 = t;
    r->rev_index = 0;
  }
  if (out[0] > r->max_amp) r->max_amp = out[0];
  if (t <= r->t_first_window && out[0] > r->amp_first) r->amp_first = out[0];
  if (t >= r->t_last_window_start && !(out[0] <= r->amp_last)) r->amp_last = out[0]; /* NaN until sampled */
  if (r->series && !r->io_failed && autobal_archive_series_append(r->series, 1, &t, r->row) != AUTOBAL_SUCCESS)
    r->io_failed = 1;
  /* per-revolution maxima (of the sampled values) */
  if (out[0] > r->rev_max_G) r->rev_max_G = out[0];
  for (j = 0; j < r->n_planes; j++) {
    if (out[plane_base(j) + 6] > r->rev_max_D[j]) r->rev_max_D[j] = out[plane_base(j) + 6];
    if (out[plane_base(j) + 5] > r->rev_max_s) r->rev_max_s = out[plane_base(j) + 5];
  }
  /* revolution k ends at rev_t0 + (k+1) period; a sample within 1e-9 period of it closes it */
  if (t >= r->rev_t0 + ((double)r->rev_index + 1.0 - 1e-9) * r->rev_period) {
    r->rev_row[0] = r->rev_max_G;
    r->rev_row[1] = r->rev_max_s;
    for (j = 0; j < r->n_planes; j++) r->rev_row[2 + j] = r->rev_max_D[j];
    if (r->revs && !r->io_failed && autobal_archive_series_append(r->revs, 1, &t, r->rev_row) != AUTOBAL_SUCCESS)
      r->io_failed = 1;
    r->rev_max_G = r->rev_max_s = 0;
    for (j = 0; j < r->n_planes; j++) r->rev_max_D[j] = 0;
    r->rev_index++;
  }
  return 0;
}

static int progress(double fraction, void *user) {
  run_ctx *r = user;
  return cli_progress(r->ctx, "rotor transient", fraction);
}

static double monitor(double t, const double y[], void *user) {
  run_ctx *r = user;
  return autobal_rotor_balance_monitor(r->rotor, r->frame, t, y);
}

static const char *state_name(size_t k, size_t nb, int axial, int frame, char *buf, size_t len, const char **unit,
                              const char **lname) {
  static const char *const q[8] = {"x", "y", "alpha", "beta", "x_rate", "y_rate", "alpha_rate", "beta_rate"};
  static const char *const qu[8] = {"m", "m", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s"};
  static const char *const ql[8] = {"displacement x of the centre of mass", "displacement y of the centre of mass",
                                    "Resal angle alpha (about x)", "Resal angle beta (about y)", "dx/dt", "dy/dt",
                                    "d alpha/dt", "d beta/dt"};
  if (k < 8) {
    *unit = qu[k];
    *lname = ql[k];
    return q[k];
  }
  if (k < 8 + nb) {
    snprintf(buf, len, frame == AUTOBAL_ROTOR_FIXED ? "state_phi_%zu" : "state_psi_%zu", k - 8 + 1);
    *unit = "rad";
    *lname = frame == AUTOBAL_ROTOR_FIXED ? "integrated ball angle phi (absolute)" : "integrated ball angle psi (relative)";
    return buf;
  }
  if (k < 8 + 2 * nb) {
    snprintf(buf, len, frame == AUTOBAL_ROTOR_FIXED ? "state_phi_rate_%zu" : "state_psi_rate_%zu", k - 8 - nb + 1);
    *unit = "rad/s";
    *lname = "integrated ball angular rate";
    return buf;
  }
  (void)axial;
  if (k == 8 + 2 * nb) {
    *unit = "m";
    *lname = "axial displacement z";
    return "z";
  }
  *unit = "m/s";
  *lname = "axial velocity dz/dt";
  return "z_rate";
}

static int write_rotor_params(autobal_archive *a, const autobal_rotor *rot, const rotor_cfg *c) {
  const autobal_rotor_params *p = autobal_rotor_get_params(rot);
  const autobal_rotor_lumped *l = autobal_rotor_get_lumped(rot);
  const char *g = "/rotor";
  int st = autobal_archive_group(a, g);
  size_t j;
  char grp[64];
#define AD(obj, name, v, u) \
  if (!st) st = autobal_archive_attr_double(a, obj, name, v, u)
  if (!st) st = autobal_archive_attr_string(a, g, "model", "rotor in a massive housing with ball autobalancers (spec rotor.md)");
  if (!st) st = autobal_archive_attr_string(a, g, "input", p->input == AUTOBAL_ROTOR_LUMPED ? "lumped" : "hardware");
  if (!st) st = autobal_archive_attr_string(a, g, "inertia", p->inertia == AUTOBAL_ROTOR_INERTIA_FULL ? "full" : "paper");
  AD(g, "omega", p->omega, "rad/s");
  if (!st) st = autobal_archive_attr_int(a, g, "axial", p->axial);
  if (p->input == AUTOBAL_ROTOR_HARDWARE) {
    AD(g, "M_k", p->hw.M_k, "kg");
    AD(g, "A_k", p->hw.A_k, "kg m^2");
    AD(g, "m_p", p->hw.m_p, "kg");
    AD(g, "A_p", p->hw.A_p, "kg m^2");
    AD(g, "C_p", p->hw.C_p, "kg m^2");
    AD(g, "l_L", p->hw.l_L, "m");
    AD(g, "l_R", p->hw.l_R, "m");
    AD(g, "c_Lx", p->hw.c_Lx, "N/m");
    AD(g, "c_Ly", p->hw.c_Ly, "N/m");
    AD(g, "c_Lz", p->hw.c_Lz, "N/m");
    AD(g, "c_Rx", p->hw.c_Rx, "N/m");
    AD(g, "c_Ry", p->hw.c_Ry, "N/m");
    AD(g, "h_Lx", p->hw.h_Lx, "N s/m");
    AD(g, "h_Ly", p->hw.h_Ly, "N s/m");
    AD(g, "h_Lz", p->hw.h_Lz, "N s/m");
    AD(g, "h_Rx", p->hw.h_Rx, "N s/m");
    AD(g, "h_Ry", p->hw.h_Ry, "N s/m");
  }
  if (!st) st = autobal_archive_group(a, "/rotor/lumped");
  AD("/rotor/lumped", "M", l->M, "kg");
  AD("/rotor/lumped", "A", l->A, "kg m^2");
  AD("/rotor/lumped", "C", l->C, "kg m^2");
  AD("/rotor/lumped", "c_x", l->c_x, "N/m");
  AD("/rotor/lumped", "c_y", l->c_y, "N/m");
  AD("/rotor/lumped", "c_z", l->c_z, "N/m");
  AD("/rotor/lumped", "c_alpha", l->c_alpha, "N m");
  AD("/rotor/lumped", "c_beta", l->c_beta, "N m");
  AD("/rotor/lumped", "c_xbeta", l->c_xbeta, "N");
  AD("/rotor/lumped", "c_yalpha", l->c_yalpha, "N");
  AD("/rotor/lumped", "h_x", l->h_x, "N s/m");
  AD("/rotor/lumped", "h_y", l->h_y, "N s/m");
  AD("/rotor/lumped", "h_z", l->h_z, "N s/m");
  AD("/rotor/lumped", "h_alpha", l->h_alpha, "N m s");
  AD("/rotor/lumped", "h_beta", l->h_beta, "N m s");
  AD("/rotor/lumped", "h_xbeta", l->h_xbeta, "N s");
  AD("/rotor/lumped", "h_yalpha", l->h_yalpha, "N s");
  for (j = 0; j < p->n_planes && !st; j++) {
    const autobal_rotor_plane *pl = &p->plane[j];
    snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
    st = autobal_archive_group(a, grp);
    AD(grp, "d", pl->d, "m");
    AD(grp, "m0", pl->m0, "kg");
    AD(grp, "r0", pl->r0, "m");
    AD(grp, "psi0", pl->psi0, "rad");
    if (!st) st = autobal_archive_attr_int(a, grp, "n_balls", (long)pl->n_balls);
    if (!st && pl->n_balls > 0) {
      st = autobal_archive_attr_double_array(a, grp, "ball_mass", pl->n_balls, pl->ball_mass, "kg");
      if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_radius", pl->n_balls, pl->ball_radius, "m");
      if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_damping", pl->n_balls, pl->ball_damping, "kg/s");
      if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_psi_initial", pl->n_balls, pl->ball_psi, "rad");
      if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_rate_initial", pl->n_balls, pl->ball_rate, "rad/s");
    }
  }
  if (!st) st = autobal_archive_group(a, "/rotor/transient");
  AD("/rotor/transient", "t_end", c->t_end, "s");
  AD("/rotor/transient", "dt_out", c->dt_out, "s");
  AD("/rotor/transient", "rtol", c->rtol, "1");
  AD("/rotor/transient", "atol", c->atol, "1");
  AD("/rotor/transient", "h_max", c->h_max, "s");
  AD("/rotor/transient", "max_steps", (double)c->max_steps, "1");
  if (!st) st = autobal_archive_attr_double_array(a, "/rotor/transient", "initial_q", 4, p->q0, "m, m, rad, rad");
  if (!st) st = autobal_archive_attr_double_array(a, "/rotor/transient", "initial_q_rate", 4, p->qd0, "m/s, m/s, rad/s, rad/s");
  AD("/rotor/transient", "balance_tol", c->balance_tol, "1");
  AD("/rotor/transient", "balance_revs", c->balance_revs, "1");
  if (!st) st = autobal_archive_attr_string(a, "/rotor/transient", "stepper", c->stepper);
  if (!st) st = autobal_archive_attr_string(a, "/rotor/transient", "frame", c->frame_name);
#undef AD
  return st;
}

/* A readable long_name for a derived output named by autobal_rotor_output_name. */
static void output_long_name(const char *name, char *buf, size_t len) {
  unsigned pl = 0, b = 0;
  char rest[48] = "";
  if (!strcmp(name, "amp_G")) snprintf(buf, len, "displacement amplitude of the centre of mass");
  else if (!strcmp(name, "amp_L")) snprintf(buf, len, "displacement amplitude at the left support (z = -l_L)");
  else if (!strcmp(name, "amp_R")) snprintf(buf, len, "displacement amplitude at the right support (z = +l_R)");
  else if (sscanf(name, "p%u_b%u_%47s", &pl, &b, rest) == 3) {
    const char *what = !strcmp(rest, "phi") ? "absolute angle phi (unwrapped)"
                       : !strcmp(rest, "phi_w") ? "absolute angle phi wrapped to (-pi, pi]"
                       : !strcmp(rest, "psi") ? "angle psi relative to the rotor (unwrapped)"
                       : !strcmp(rest, "psi_w") ? "angle psi relative to the rotor wrapped to (-pi, pi]"
                       : !strcmp(rest, "phi_rate") ? "absolute angular rate dphi/dt"
                       : !strcmp(rest, "psi_rate") ? "angular rate relative to the rotor dpsi/dt" : rest;
    snprintf(buf, len, "ball %u of plane %u: %s", b, pl, what);
  } else if (sscanf(name, "p%u_%47s", &pl, rest) == 2) {
    const char *what = !strcmp(rest, "s_u") ? "unbalance s_u of rotor plus balls along fixed x (3.1)"
                       : !strcmp(rest, "s_v") ? "unbalance s_v of rotor plus balls along fixed y (3.1)"
                       : !strcmp(rest, "s_xi") ? "unbalance s_xi along the rotor axis xi (3.10)"
                       : !strcmp(rest, "s_eta") ? "unbalance s_eta along the rotor axis eta (3.10)"
                       : !strcmp(rest, "s_abs") ? "residual unbalance |s|"
                       : !strcmp(rest, "s_rel") ? "residual unbalance |s| relative to m0 r0"
                       : !strcmp(rest, "amp_D") ? "displacement amplitude at the balancer plane" : rest;
    snprintf(buf, len, "plane %u: %s", pl, what);
  } else
    snprintf(buf, len, "%s", name);
}

static int open_series(run_ctx *r, autobal_archive *a, const rotor_cfg *c) {
  size_t n = r->ncols, k, nb = autobal_rotor_n_balls_total(r->rotor), j;
  char (*names)[64] = calloc(n, sizeof *names);
  char (*lnames)[96] = calloc(n, sizeof *lnames);
  const char **np = calloc(n, sizeof *np), **up = calloc(n, sizeof *up), **lp = calloc(n, sizeof *lp);
  const char *rn[2 + AUTOBAL_ROTOR_MAX_PLANES], *ru[2 + AUTOBAL_ROTOR_MAX_PLANES], *rl[2 + AUTOBAL_ROTOR_MAX_PLANES];
  char rnb[AUTOBAL_ROTOR_MAX_PLANES][32];
  int st = AUTOBAL_SUCCESS;
  if (!names || !lnames || !np || !up || !lp) st = AUTOBAL_ENOMEM;
  for (k = 0; !st && k < r->dim; k++) {
    const char *nm = state_name(k, nb, c->p.axial, r->frame, names[k], sizeof names[k], &up[k], &lp[k]);
    if (nm != names[k]) snprintf(names[k], sizeof names[k], "%s", nm);
    np[k] = names[k];
    if (k >= 8 && k < 8 + 2 * nb) { /* one long_name per ball */
      snprintf(lnames[k], sizeof lnames[k], "%s of ball %zu (state order)", lp[k], (k - 8) % nb + 1);
      lp[k] = lnames[k];
    }
  }
  for (k = 0; !st && k < r->nout; k++) {
    const char *unit = NULL;
    st = autobal_rotor_output_name(r->rotor, k, names[r->dim + k], sizeof names[0], &unit);
    np[r->dim + k] = names[r->dim + k];
    up[r->dim + k] = unit;
    output_long_name(names[r->dim + k], lnames[r->dim + k], sizeof lnames[0]);
    lp[r->dim + k] = lnames[r->dim + k];
  }
  if (!st)
    st = autobal_archive_series_open(a, "/rotor/transient", "time", "s", "time", n, np, up, lp, &r->series);
  rn[0] = "max_amp_G";
  ru[0] = "m";
  rl[0] = "largest sampled displacement amplitude of the centre of mass during the revolution";
  rn[1] = "max_s_rel";
  ru[1] = "1";
  rl[1] = "largest sampled relative residual unbalance |s|/s_ref over the planes during the revolution";
  for (j = 0; j < r->n_planes; j++) {
    snprintf(rnb[j], sizeof rnb[j], "p%zu_max_amp_D", j + 1);
    rn[2 + j] = rnb[j];
    ru[2 + j] = "m";
    rl[2 + j] = "largest sampled displacement amplitude at the balancer plane during the revolution";
  }
  if (!st)
    st = autobal_archive_series_open(a, "/rotor/revolutions", "revolution_end", "s",
                                     "time at the end of each revolution 2 pi/omega", 2 + r->n_planes, rn, ru, rl,
                                     &r->revs);
  free(names);
  free(lnames);
  free(np);
  free(up);
  free(lp);
  return st;
}

int cli_cmd_rotor_transient(cli_ctx *ctx) {
  rotor_cfg *c = calloc(1, sizeof *c);
  autobal_rotor *rot = NULL;
  autobal_transient *tr = NULL;
  autobal_transient_options opt;
  autobal_transient_system sys;
  autobal_transient_stats stats;
  autobal_transient_event_hit hit;
  autobal_archive *a = NULL;
  autobal_error err;
  run_ctx r;
  double *y = NULL, t_reached = 0, *psi_bal = NULL, s_final = NAN, ttb = NAN;
  int rc = CLI_EXIT_OK, st, warn = 0, balanced = 0, ev = -1;
  size_t j;

  memset(&r, 0, sizeof r);
  autobal_error_clear(&err);
  if (!c) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  if ((rc = read_rotor_config(ctx, c))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  rot = autobal_rotor_alloc(&c->p, &err);
  if (!rot) {
    rc = cli_fail(ctx, cli_exit_code(err.status), "%s", err.message);
    goto done;
  }
  if (err.status == AUTOBAL_WARNING) {
    warn = 1;
    if (!ctx->json) fprintf(stderr, "autobal: warning: %s\n", err.message);
  }
  opt = autobal_transient_options_default();
  opt.stepper = c->stepper;
  opt.rtol = c->rtol;
  opt.atol = c->atol;
  opt.h_max = c->h_max;
  opt.max_steps = (unsigned long)c->max_steps;
  opt.dt_out = c->dt_out;
  opt.event_tol = 1e-9 * c->t_end;
  tr = autobal_transient_alloc(autobal_rotor_dim(rot), &opt, &err);
  if (!tr) {
    rc = cli_fail(ctx, cli_exit_code(err.status), "[transient]: %s", err.message);
    goto done;
  }
  r.ctx = ctx;
  r.rotor = rot;
  r.frame = c->frame;
  r.dim = autobal_rotor_dim(rot);
  r.nout = autobal_rotor_output_count(rot);
  r.ncols = r.dim + r.nout;
  r.n_planes = autobal_rotor_n_planes(rot);
  r.rev_period = TWO_PI / fabs(c->p.omega);
  r.t_end = c->t_end;
  r.t_first_window = 0.1 * c->t_end;
  r.t_last_window_start = 0.9 * c->t_end;
  r.amp_last = NAN; /* stays NaN when the run stops (e.g. at balance) before the last 10% */
  r.row = calloc(r.ncols, sizeof *r.row);
  r.rev_max_D = calloc(r.n_planes, sizeof *r.rev_max_D);
  r.rev_row = calloc(2 + r.n_planes, sizeof *r.rev_row);
  y = calloc(r.dim, sizeof *y);
  if (!r.row || !r.rev_max_D || !r.rev_row || !y) {
    rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
    goto done;
  }
  if ((st = autobal_rotor_initial_state(rot, c->frame, 0.0, y, r.dim))) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s", autobal_rotor_errmsg(rot));
    goto done;
  }
  if ((rc = cli_archive_open(ctx, "autobal rotor transient", &a))) goto done;
  if (a) {
    st = write_rotor_params(a, rot, c);
    if (!st) st = open_series(&r, a, c);
    if (st) {
      rc = cli_fail(ctx, cli_exit_code(st), "%s", autobal_archive_errmsg(a));
      goto finish;
    }
  }
  sys.rhs = c->frame == AUTOBAL_ROTOR_FIXED ? autobal_rotor_rhs : autobal_rotor_rhs_rotating;
  sys.jac = NULL;
  sys.dim = r.dim;
  sys.params = rot;
  autobal_transient_set_observer(tr, observer, &r);
  autobal_transient_set_progress(tr, progress, &r);
  ev = autobal_transient_add_dwell_event(tr, monitor, &r, c->balance_tol, c->balance_revs * r.rev_period,
                                         c->stop_at_balance);
  if (ev < 0) {
    rc = cli_fail(ctx, cli_exit_code(ev), "%s", autobal_transient_errmsg(tr));
    goto finish;
  }
  st = autobal_transient_run(tr, &sys, 0.0, c->t_end, y, &t_reached);
  cli_progress_done(ctx);
  autobal_transient_get_stats(tr, &stats);
  if (st < 0) {
    if (st == AUTOBAL_ECANCELLED)
      rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED, "interrupted at t = %.6g s of %.6g s; the archive keeps everything computed so far (status incomplete)", t_reached, c->t_end);
    else
      rc = cli_fail(ctx, cli_exit_code(st), "%s (t reached %.9g s of %.6g s; partial results kept)",
                    autobal_transient_errmsg(tr), t_reached, c->t_end);
  }
  if (r.io_failed && rc == CLI_EXIT_OK)
    rc = cli_fail(ctx, CLI_EXIT_IO, "writing the time series failed: %s", autobal_archive_errmsg(a));
  balanced = autobal_transient_event_result(tr, (size_t)ev, NULL, &hit) == 1;
  if (balanced) ttb = hit.t_start;
  s_final = autobal_rotor_balance_monitor(rot, c->frame, t_reached, y);
  /* balanced angles (3.14) of each plane for comparison (when they exist); plane 1 is printed */
  for (j = 0; j < c->p.n_planes; j++) {
    size_t nbj = c->p.plane[j].n_balls;
    double *pb;
    if (nbj == 0) continue;
    pb = calloc(nbj, sizeof *pb);
    if (pb && autobal_rotor_balanced_angles(rot, j, pb, nbj, NULL) == AUTOBAL_SUCCESS) {
      if (a) {
        char grp[64];
        snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
        if (autobal_archive_attr_double_array(a, grp, "ball_psi_balanced", nbj, pb, "rad") != AUTOBAL_SUCCESS &&
            rc == CLI_EXIT_OK)
          rc = cli_fail(ctx, CLI_EXIT_IO, "%s", autobal_archive_errmsg(a));
      }
      if (j == 0) {
        psi_bal = pb;
        pb = NULL;
      }
    }
    free(pb);
  }

  if (a) {
    const char *g = "/rotor/transient";
    st = autobal_archive_attr_double(a, g, "time_to_balance", ttb, "s");
    if (!st) st = autobal_archive_attr_int(a, g, "balanced", balanced);
    if (!st) st = autobal_archive_attr_double(a, g, "t_reached", t_reached, "s");
    if (!st) st = autobal_archive_attr_double(a, g, "residual_unbalance_initial", r.s_rel_initial, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "residual_unbalance_final", s_final, "1");
    if (!st) st = autobal_archive_attr_double(a, g, "amplitude_first_10pct_max", r.amp_first, "m");
    if (!st) st = autobal_archive_attr_double(a, g, "amplitude_last_10pct_max", r.amp_last, "m");
    if (!st) st = autobal_archive_attr_double(a, g, "amplitude_max", r.max_amp, "m");
    if (!st) st = autobal_archive_group(a, "/rotor/transient/solver");
    if (!st) {
      const char *gs = "/rotor/transient/solver";
      st = autobal_archive_attr_string(a, gs, "stepper", c->stepper);
      if (!st) st = autobal_archive_attr_int(a, gs, "steps", (long)stats.steps);
      if (!st) st = autobal_archive_attr_int(a, gs, "rejected_steps", (long)stats.rejected);
      if (!st) st = autobal_archive_attr_int(a, gs, "rhs_evaluations", (long)stats.rhs_evals);
      if (!st) st = autobal_archive_attr_int(a, gs, "jacobian_evaluations", (long)stats.jac_evals);
      if (!st) st = autobal_archive_attr_double(a, gs, "wall_time", stats.wall_seconds, "s");
      if (!st) st = autobal_archive_attr_double(a, gs, "h_min_used", stats.h_min_used, "s");
      if (!st) st = autobal_archive_attr_double(a, gs, "h_max_used", stats.h_max_used, "s");
      if (!st) st = autobal_archive_attr_string(a, gs, "stop_reason", autobal_transient_stop_name(stats.stop_reason));
      if (!st) st = autobal_archive_attr_string(a, gs, "message", autobal_transient_errmsg(tr));
    }
    if (st && rc == CLI_EXIT_OK) rc = cli_fail(ctx, cli_exit_code(st), "%s", autobal_archive_errmsg(a));
  }
finish:
  if (a) {
    rc = cli_archive_finish(ctx, a, rc);
    a = NULL;
  }
  if (rc == CLI_EXIT_OK || rc == CLI_EXIT_NUMERIC || rc == CLI_EXIT_INTERRUPTED) {
    double s0 = c->p.plane[0].m0 * c->p.plane[0].r0;
    if (ctx->json) {
      cli_json jj;
      cli_json_begin(&jj, stdout);
      cli_json_string(&jj, "command", ctx->command);
      cli_json_bool(&jj, "balanced", balanced);
      cli_json_number(&jj, "time_to_balance", ttb);
      cli_json_number(&jj, "t_reached", t_reached);
      cli_json_number(&jj, "residual_unbalance_initial", r.s_rel_initial);
      cli_json_number(&jj, "residual_unbalance_final", s_final);
      cli_json_number(&jj, "amplitude_first_10pct_max", r.amp_first);
      cli_json_number(&jj, "amplitude_last_10pct_max", r.amp_last);
      cli_json_int(&jj, "steps", (long)stats.steps);
      cli_json_int(&jj, "rhs_evaluations", (long)stats.rhs_evals);
      cli_json_number(&jj, "wall_time", stats.wall_seconds);
      cli_json_bool(&jj, "warning", warn);
      if (ctx->output) cli_json_string(&jj, "output", ctx->output);
      cli_json_end(&jj);
    } else if (!ctx->quiet) {
      size_t nb0 = c->p.plane[0].n_balls;
      printf("rotor transient: omega = %.6g rad/s (%.1f rpm), %zu plane(s), %zu ball(s), %.6g s simulated (%.0f revolutions)\n",
             c->p.omega, c->p.omega * 60.0 / (TWO_PI), r.n_planes, autobal_rotor_n_balls_total(rot), t_reached,
             t_reached / r.rev_period);
      printf("  residual unbalance |s|/(m0 r0): %.4g at the start -> %.4g at the end%s\n", r.s_rel_initial, s_final,
             s0 > 0 ? "" : " (relative to the balls' capacity: no unbalance)");
      printf("  vibration amplitude of the centre of mass: max %.4g um in the first 10%% of the run, %.4g um in the last 10%%\n",
             r.amp_first * 1e6, r.amp_last * 1e6);
      if (balanced)
        printf("  BALANCED: residual unbalance below %.3g (relative) from t = %.6g s on (held for %.0f revolutions)\n",
               c->balance_tol, ttb, c->balance_revs);
      else
        printf("  NOT balanced: the residual unbalance did not stay below %.3g (relative) for %.0f revolutions\n",
               c->balance_tol, c->balance_revs);
      if (nb0 > 0) {
        size_t i;
        printf("  plane 1 ball angles relative to the rotor at the end (rad, wrapped):");
        for (i = 0; i < nb0 && i < 8; i++) {
          size_t k = autobal_rotor_ball_index(rot, 0, i);
          double ang = c->frame == AUTOBAL_ROTOR_FIXED ? y[8 + k] - c->p.omega * t_reached : y[8 + k];
          ang = remainder(ang, TWO_PI);
          printf(" %.5f", ang);
        }
        printf("\n");
        if (psi_bal) {
          printf("  balanced configuration (3.14) of plane 1:");
          for (i = 0; i < nb0 && i < 8; i++) printf(" %.5f", psi_bal[i]);
          printf("\n");
        }
      }
      printf("  solver %s: %lu steps, %lu rejected, %lu rhs evaluations, %.3f s wall\n", c->stepper, stats.steps,
             stats.rejected, stats.rhs_evals, stats.wall_seconds);
      if (ctx->output) printf("archive: %s\n", ctx->output);
    }
  }
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  autobal_transient_free(tr);
  autobal_rotor_free(rot);
  free(r.row);
  free(r.rev_max_D);
  free(r.rev_row);
  free(y);
  free(psi_bal);
  free(c);
  return rc;
}
