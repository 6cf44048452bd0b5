/* cmd_rotor.c: `autobal rotor transient`: the rotor in a massive housing with one or two ball
 * autobalancers (docs/rotor.md), integrated in time, streamed to HDF5, summarised for a person.
 * The run and its archive layout are the library's (autobal_study_rotor_transient, src/studies/);
 * this file reads the configuration into the structs and prints the summary. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/archive.h"
#include "autobal/rotor.h"
#include "autobal/study.h"
#include "autobal/transient.h"
#include "cli.h"
#include "units.h"

#define MAX_CFG_BALLS 4096
#define MAX_CFG_DRIVE_POINTS 100000
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
  const char *output; /* dense | exact */
  int frame, stop_at_balance;
  /* [balance] */
  double grade; /* ISO 21940-11 grade to check, mm/s; NaN: none */
  const char *grade_text;
  /* [drive]: the table's points (p.drive points into them) */
  double drive_t[MAX_CFG_DRIVE_POINTS], drive_w[MAX_CFG_DRIVE_POINTS];
  /* mode = motor: the torque table (p.drive.torque_L points into it; torque_omega into drive_w) */
  double drive_L[MAX_CFG_DRIVE_POINTS];
  /* [transient] run-up outputs (a drive other than constant) */
  double capture_band, capture_time;
  /* [friction] and the planes' ball_f, ball_mu (p.friction points into them) */
  double fric_f[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS], fric_mu[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS];
  const char *friction_law;
  /* the planes' ball_rho (rolling inertia; p.rolling points into it) */
  double rho[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS];
  /* the planes' ball_diameter (contact; p.contact points into it) */
  double diam[AUTOBAL_ROTOR_MAX_PLANES][MAX_CFG_BALLS];
} rotor_cfg;

static int get_d(cli_ctx *ctx, const char *sec, const char *key, double *v) {
  return cli_get_double(ctx, sec, key, *v, v, NULL);
}
/* A quantity in SI unit `unit`; the value may carry a unit (cli_get_quantity). */
static int get_q(cli_ctx *ctx, const char *sec, const char *key, const char *unit, double *v) {
  return cli_get_quantity(ctx, sec, key, unit, *v, v, NULL);
}

/* ---- the rotor model's configuration keys, shared by every rotor command ---------------- */
/* The double fields of the parameter struct with their sections, keys (= field names) and SI
 * units: the library's tables (autobal_rotor_hardware_fields, autobal_rotor_lumped_fields), the
 * same the archive writer uses. */

/* Read the keys of `section` from the table into the struct at base (the current values are the
 * defaults). */
static int read_keys(cli_ctx *ctx, const autobal_rotor_field *keys, size_t n, const char *section, void *base) {
  size_t i;
  int rc;
  for (i = 0; i < n; i++)
    if (!strcmp(keys[i].section, section) &&
        (rc = get_q(ctx, section, keys[i].name, keys[i].unit, autobal_rotor_field_ptr(base, &keys[i]))))
      return rc;
  return CLI_EXIT_OK;
}

static int read_plane(cli_ctx *ctx, rotor_cfg *c, size_t j, const char *sec) {
  autobal_rotor_plane *pl = &c->p.plane[j];
  size_t nm, nr, nh, np, nv;
  int rc, pm, pr, ph, pp, pv;
  int has_m0, has_u;
  double unbalance = NAN;
  if ((rc = get_q(ctx, sec, "d", "m", &pl->d))) return rc;
  if ((rc = cli_get_quantity(ctx, sec, "m0", "kg", pl->m0, &pl->m0, &has_m0))) return rc;
  if ((rc = get_q(ctx, sec, "r0", "m", &pl->r0))) return rc;
  /* unbalance = m0 r0 (e.g. "200 g mm"): m0 follows from it and r0 */
  if ((rc = cli_get_quantity(ctx, sec, "unbalance", "kg m", NAN, &unbalance, &has_u))) return rc;
  if (has_u) {
    if (has_m0)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: give either m0 or unbalance (= m0 r0), not both", sec);
    if (!(pl->r0 > 0.0))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: unbalance needs r0 > 0 (m0 = unbalance / r0); r0 = %g m", sec,
                      pl->r0);
    pl->m0 = unbalance / pl->r0;
  }
  if ((rc = get_q(ctx, sec, "psi0", "rad", &pl->psi0))) return rc;
  if ((rc = cli_get_quantities(ctx, sec, "ball_mass", "kg", c->mass[j], MAX_CFG_BALLS, &nm, &pm))) return rc;
  if ((rc = cli_get_quantities(ctx, sec, "ball_radius", "m", c->radius[j], MAX_CFG_BALLS, &nr, &pr))) return rc;
  if ((rc = cli_get_quantities(ctx, sec, "ball_damping", "kg/s", c->damping[j], MAX_CFG_BALLS, &nh, &ph))) return rc;
  if ((rc = cli_get_quantities(ctx, sec, "ball_psi", "rad", c->psi[j], MAX_CFG_BALLS, &np, &pp))) return rc;
  if ((rc = cli_get_quantities(ctx, sec, "ball_rate", "rad/s", c->rate[j], MAX_CFG_BALLS, &nv, &pv))) return rc;
  {
    /* n = the number of balls: from ball_mass when given, else the current (default) count.  Each
     * other list has n values or one value for all; a list left out keeps the current values when
     * n is unchanged, else radius and damping are required and angles/rates default to 0. */
    /* a recorded default list (autobal rerun: not given, nm > 0) sets n like a given one */
    size_t n = (pm || nm > 0) ? nm : pl->n_balls, i;
    struct {
      const char *name;
      double *v;
      size_t cnt;
      int present;
      double def;
    } lists[4];
    /* present: given, or a recorded default list (autobal rerun) */
    lists[0].name = "ball_radius", lists[0].v = c->radius[j], lists[0].cnt = nr, lists[0].present = pr || nr > 0, lists[0].def = NAN;
    lists[1].name = "ball_damping", lists[1].v = c->damping[j], lists[1].cnt = nh, lists[1].present = ph || nh > 0, lists[1].def = NAN;
    lists[2].name = "ball_psi", lists[2].v = c->psi[j], lists[2].cnt = np, lists[2].present = pp || np > 0, lists[2].def = 0.0;
    lists[3].name = "ball_rate", lists[3].v = c->rate[j], lists[3].cnt = nv, lists[3].present = pv || nv > 0, lists[3].def = 0.0;
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
  /* the lists used, for the effective configuration (the built-in ones when not given) */
  cli_record_doubles_used(ctx, sec, "ball_mass", c->mass[j], pl->n_balls);
  cli_record_doubles_used(ctx, sec, "ball_radius", c->radius[j], pl->n_balls);
  cli_record_doubles_used(ctx, sec, "ball_damping", c->damping[j], pl->n_balls);
  cli_record_doubles_used(ctx, sec, "ball_psi", c->psi[j], pl->n_balls);
  cli_record_doubles_used(ctx, sec, "ball_rate", c->rate[j], pl->n_balls);
  return CLI_EXIT_OK;
}

/* [rotor] gravity = true|false (default false), shaft_angle (angle of the shaft to the vertical:
 * 0 vertical, 90 deg horizontal, allowed [0, 180] deg; required with gravity = true), g (m/s^2,
 * default 9.80665, > 0): docs/device.md section 2.  shaft_angle and g are read (and recorded) only
 * with gravity = true or when given, so that the effective configuration of a run without gravity
 * is unchanged; given without gravity = true they are refused. */
static int read_gravity(cli_ctx *ctx, autobal_rotor_params *p) {
  int rc, on = 0, has_sa = 0, has_g = 0;
  const double half_turn = TWO_PI / 2.0;
  if ((rc = cli_get_bool(ctx, "rotor", "gravity", 0, &on, NULL))) return rc;
  p->gravity = on;
  if (!on && !cli_config_has_key(ctx->cfg, "rotor", "shaft_angle") && !cli_config_has_key(ctx->cfg, "rotor", "g"))
    return CLI_EXIT_OK;
  if ((rc = cli_get_quantity(ctx, "rotor", "shaft_angle", "rad", half_turn / 2.0, &p->shaft_angle, &has_sa))) return rc;
  if ((rc = cli_get_quantity(ctx, "rotor", "g", "m/s^2", 9.80665, &p->g, &has_g))) return rc;
  if (!on)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[rotor]: %s is a key of gravity = true, but gravity = false",
                    has_sa ? "shaft_angle" : "g");
  if (!has_sa && !cli_config_has_key(ctx->cfg, "rotor", "shaft_angle"))
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[rotor]: gravity = true needs shaft_angle, the angle of the shaft to the vertical: allowed "
                    "[0, 180] deg (0: vertical shaft, 90 deg: horizontal)");
  /* 180 deg may convert to pi plus an ulp: the closed end of the range */
  if (p->shaft_angle > half_turn && p->shaft_angle <= half_turn * (1.0 + 4e-16)) p->shaft_angle = half_turn;
  if (!(p->shaft_angle >= 0.0 && p->shaft_angle <= half_turn))
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[rotor]: shaft_angle = %.6g deg is out of range: allowed [0, 180] deg (0: vertical shaft, 90 "
                    "deg: horizontal)", p->shaft_angle * 360.0 / TWO_PI);
  if (!(p->g > 0.0) || !isfinite(p->g))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[rotor]: g = %.6g m/s^2 is out of range: allowed (0, inf)", p->g);
  return CLI_EXIT_OK;
}

static int read_rotor_model(cli_ctx *ctx, rotor_cfg *c) {
  autobal_rotor_hardware *hw = &c->p.hw;
  autobal_rotor_lumped *lu = &c->p.lumped;
  const char *inertia = "paper";
  int rc, axial = 0, has_plane2;
  size_t i, n_hw, n_lumped;
  const autobal_rotor_field *k_hw_keys, *k_lumped_keys;
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
  k_hw_keys = autobal_rotor_hardware_fields(&n_hw);
  k_lumped_keys = autobal_rotor_lumped_fields(&n_lumped);
  /* [rotor] */
  if ((rc = read_keys(ctx, k_hw_keys, n_hw, "rotor", hw))) return rc;
  if ((rc = get_q(ctx, "rotor", "omega", "rad/s", &c->p.omega))) return rc;
  if ((rc = cli_get_string(ctx, "rotor", "inertia", inertia, &inertia, NULL))) return rc;
  if ((rc = cli_get_bool(ctx, "rotor", "axial", 0, &axial, NULL))) return rc;
  if (!strcmp(inertia, "paper")) c->p.inertia = AUTOBAL_ROTOR_INERTIA_PAPER;
  else if (!strcmp(inertia, "full")) c->p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  else return cli_fail(ctx, CLI_EXIT_INPUT, "[rotor]: inertia = '%s' is not one of: paper, full", inertia);
  c->p.axial = axial;
  if ((rc = read_gravity(ctx, &c->p))) return rc;
  /* [supports] */
  if ((rc = read_keys(ctx, k_hw_keys, n_hw, "supports", hw))) return rc;
  /* [lumped]: if present, the lumped coefficients are authoritative (all must be given) */
  if (cli_section_present(ctx, "lumped")) {
    for (i = 0; i < n_lumped; i++) {
      int present;
      if ((rc = cli_get_quantity(ctx, "lumped", k_lumped_keys[i].name, k_lumped_keys[i].unit, 0.0,
                                 autobal_rotor_field_ptr(lu, &k_lumped_keys[i]), &present)))
        return rc;
      if (!present)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[lumped]: '%s' is missing (with a [lumped] section all of M, A, C, c_x, c_y, c_z, c_alpha, c_beta, c_xbeta, c_yalpha and the h_ analogues are required)", k_lumped_keys[i].name);
    }
    c->p.input = AUTOBAL_ROTOR_LUMPED;
  }
  /* [initial] */
  if ((rc = get_q(ctx, "initial", "x", "m", &c->p.q0[0]))) return rc;
  if ((rc = get_q(ctx, "initial", "y", "m", &c->p.q0[1]))) return rc;
  if ((rc = get_q(ctx, "initial", "alpha", "rad", &c->p.q0[2]))) return rc;
  if ((rc = get_q(ctx, "initial", "beta", "rad", &c->p.q0[3]))) return rc;
  if ((rc = get_q(ctx, "initial", "x_rate", "m/s", &c->p.qd0[0]))) return rc;
  if ((rc = get_q(ctx, "initial", "y_rate", "m/s", &c->p.qd0[1]))) return rc;
  if ((rc = get_q(ctx, "initial", "alpha_rate", "rad/s", &c->p.qd0[2]))) return rc;
  if ((rc = get_q(ctx, "initial", "beta_rate", "rad/s", &c->p.qd0[3]))) return rc;
  if ((rc = get_q(ctx, "initial", "z", "m", &c->p.z0))) return rc;
  if ((rc = get_q(ctx, "initial", "z_rate", "m/s", &c->p.zd0))) return rc;
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

int cli_write_rotor_params(autobal_archive *a, const autobal_rotor_params *p, int initial) {
  return autobal_study_write_rotor_params(a, p, initial);
}

/* ---- messages of the model in the configuration's names ----------------------------------- */
typedef struct msg_buf {
  char *buf;
  size_t len, pos; /* pos < len: characters written so far (the rest is cut) */
} msg_buf;

static void msg_put(msg_buf *m, const char *s, size_t n) {
  size_t k;
  if (m->len == 0) return;
  for (k = 0; k < n && m->pos + 1 < m->len; k++) m->buf[m->pos++] = s[k];
  m->buf[m->pos] = '\0';
}
static void msg_puts(msg_buf *m, const char *s) { msg_put(m, s, strlen(s)); }

static int ident_char(char ch) { return isalnum((unsigned char)ch) || ch == '_'; }
static size_t ident_len(const char *s) {
  size_t n = 0;
  while (ident_char(s[n])) n++;
  return n;
}
/* "[<digits>]" at s: its length (0 if none) and the number in *v. */
static size_t index_len(const char *s, size_t *v) {
  size_t n = 1;
  if (s[0] != '[' || !isdigit((unsigned char)s[1])) return 0;
  *v = 0;
  while (isdigit((unsigned char)s[n])) {
    if (*v < 100000000) *v = 10 * *v + (size_t)(s[n] - '0');
    n++;
  }
  return s[n] == ']' ? n + 1 : 0;
}
/* Whether s starts with the word w (followed by no identifier character). */
static int starts_word(const char *s, const char *w) {
  size_t n = strlen(w);
  return !strncmp(s, w, n) && !ident_char(s[n]);
}

/* Translate the name at s into out; the length of the recognised text, 0 if none.  *field is
 * set to the length of the struct field's name at s worth citing after the message (0: none). */
static size_t translate_name(const char *s, msg_buf *out, size_t *field) {
  static const char *const qn[4] = {"x", "y", "alpha", "beta"};
  static const char *const bare[][2] = {{"omega", "rotor.omega"},
                                        {"tol", "stability.tol"},
                                        {"floquet_rtol", "stability.floquet_rtol"},
                                        {"floquet_atol", "stability.floquet_atol"},
                                        {"z0", "initial.z"},
                                        {"zd0", "initial.z_rate"}};
  char tmp[160];
  size_t n, v = 0, v2 = 0, k;
  *field = 0;
  if (!strncmp(s, "hw.", 3) && (n = ident_len(s + 3)) > 0) {
    size_t n_hw;
    const autobal_rotor_field *k_hw_keys = autobal_rotor_hardware_fields(&n_hw);
    for (k = 0; k < n_hw; k++)
      if (strlen(k_hw_keys[k].name) == n && !strncmp(s + 3, k_hw_keys[k].name, n)) {
        snprintf(tmp, sizeof tmp, "%s.%s", k_hw_keys[k].section, k_hw_keys[k].name);
        msg_puts(out, tmp);
        return *field = 3 + n;
      }
    return 0;
  }
  if (!strncmp(s, "plane", 5) && (n = index_len(s + 5, &v)) > 0) {
    size_t len = 5 + n, m;
    if (s[len] == '.' && (m = ident_len(s + len + 1)) > 0) {
      const char *fname = s + len + 1;
      size_t n2 = index_len(fname + m, &v2);
      if (n2 > 0) /* plane[j].ball_Y[i] */
        snprintf(tmp, sizeof tmp, "plane%zu.%.*s (ball %zu)", v + 1, (int)m, fname, v2 + 1);
      else if (m == 7 && !strncmp(fname, "n_balls", 7))
        snprintf(tmp, sizeof tmp, "plane%zu ball count (values of ball_mass)", v + 1);
      else
        snprintf(tmp, sizeof tmp, "plane%zu.%.*s", v + 1, (int)m, fname);
      msg_puts(out, tmp);
      return *field = len + 1 + m + n2;
    }
    snprintf(tmp, sizeof tmp, "plane%zu", v + 1);
    msg_puts(out, tmp);
    return len;
  }
  if (!strncmp(s, "q0", 2) || !strncmp(s, "qd0", 3)) { /* "q0[2] (alpha)", "qd0[0] (x')" */
    size_t p0 = s[1] == 'd' ? 3 : 2, m;
    if ((n = index_len(s + p0, &v)) > 0 && v < 4) {
      m = p0 + n;
      if (s[m] == ' ' && s[m + 1] == '(') {
        const char *close = strchr(s + m, ')');
        if (close) m = (size_t)(close - s) + 1;
      }
      snprintf(tmp, sizeof tmp, "initial.%s%s", qn[v], p0 == 3 ? "_rate" : "");
      msg_puts(out, tmp);
      *field = p0 + n;
      return m;
    }
    return 0;
  }
  if (!strncmp(s, "option member", 13) && (n = index_len(s + 13, &v)) > 0) {
    size_t len = 13 + n;
    if (starts_word(s + len, ".kind")) len += 5;
    snprintf(tmp, sizeof tmp, "stability.member%zu", v + 1);
    msg_puts(out, tmp);
    return len;
  }
  if (!strncmp(s, "parameter ", 10)) /* a bare field name after "parameter " */
    for (k = 0; k < sizeof bare / sizeof bare[0]; k++)
      if (starts_word(s + 10, bare[k][0]) && !strncmp(s + 10 + strlen(bare[k][0]), " = ", 3)) {
        msg_puts(out, "parameter ");
        msg_puts(out, bare[k][1]);
        if (bare[k][0][0] == 'z') *field = 10 + strlen(bare[k][0]); /* z0, zd0: names of their own */
        return 10 + strlen(bare[k][0]);
      }
  return 0;
}

const char *cli_rotor_message(const char *msg, char *buf, size_t len) {
  msg_buf out, notes;
  char nbuf[256];
  size_t i = 0, nnotes = 0;
  out.buf = buf, out.len = len, out.pos = 0;
  notes.buf = nbuf, notes.len = sizeof nbuf, notes.pos = 0;
  if (len) buf[0] = '\0';
  nbuf[0] = '\0';
  if (!msg) return buf;
  while (msg[i]) {
    size_t n = 0, field = 0;
    if (i == 0 || (!ident_char(msg[i - 1]) && msg[i - 1] != '.')) n = translate_name(msg + i, &out, &field);
    if (n == 0) {
      msg_put(&out, msg + i, 1);
      i++;
      continue;
    }
    if (field > 0) { /* the struct field that was renamed, for those who embed the library */
      const char *f = msg + i;
      if (!strncmp(f, "parameter ", 10)) f += 10, field -= 10;
      msg_puts(&notes, nnotes++ ? ", " : "");
      msg_put(&notes, f, field);
    }
    i += n;
  }
  if (nnotes) {
    msg_puts(&out, nnotes > 1 ? " (model fields " : " (model field ");
    msg_puts(&out, nbuf);
    msg_puts(&out, ")");
  }
  return buf;
}

/* [drive], mode = motor: J (kg m^2, >= C_p), k_r (N m s, >= 0), omega_start (rad/s, default 0),
 * and the characteristic: L_0 (N m, > 0) and omega_0 (rad/s, > 0), or table_omega (speeds,
 * strictly increasing) with table_torque (N m, one per speed, L(0) > 0). */
static int read_motor(cli_ctx *ctx, rotor_cfg *c) {
  autobal_rotor_drive *d = &c->p.drive;
  const double C = c->p.input == AUTOBAL_ROTOR_HARDWARE ? c->p.hw.C_p : c->p.lumped.C;
  int rc, hJ = 0, hL = 0, hw0 = 0, pw = 0, pl = 0;
  size_t k, nw = 0, nl = 0;
  if ((rc = cli_get_quantity(ctx, "drive", "J", "kg m^2", NAN, &d->J, &hJ))) return rc;
  if ((rc = cli_get_quantity(ctx, "drive", "k_r", "N m s", 0.0, &d->k_r, NULL))) return rc;
  if ((rc = cli_get_quantity(ctx, "drive", "omega_start", "rad/s", 0.0, &d->omega_start, NULL))) return rc;
  if ((rc = cli_get_quantity(ctx, "drive", "L_0", "N m", NAN, &d->L_0, &hL))) return rc;
  if ((rc = cli_get_quantity(ctx, "drive", "omega_0", "rad/s", NAN, &d->omega_0, &hw0))) return rc;
  if ((rc = cli_get_quantities(ctx, "drive", "table_omega", "rad/s", c->drive_w, MAX_CFG_DRIVE_POINTS, &nw, &pw)))
    return rc;
  if ((rc = cli_get_quantities(ctx, "drive", "table_torque", "N m", c->drive_L, MAX_CFG_DRIVE_POINTS, &nl, &pl)))
    return rc;
  if (!hJ)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[drive]: mode = motor needs J (kg m^2): the spin inertia of the rotor and the motor's rotor, "
                    "allowed [C_p, inf) = [%.6g, inf) kg m^2", C);
  if (!(d->J >= C) || !isfinite(d->J))
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[drive]: J = %.6g kg m^2 is out of range: allowed [C_p, inf) = [%.6g, inf) kg m^2 (the rotor's "
                    "polar moment C_p plus the motor's rotor)", d->J, C);
  if (!(d->k_r >= 0) || !isfinite(d->k_r))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: k_r = %.6g N m s is out of range: allowed [0, inf)", d->k_r);
  if (!isfinite(d->omega_start))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: omega_start = %g rad/s is out of range: allowed finite", d->omega_start);
  if (pw || pl) { /* a tabulated characteristic */
    double L0;
    if (hL || hw0)
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "[drive]: give the motor characteristic either as L_0 and omega_0 or as table_omega and "
                      "table_torque, not both");
    if (!pw || nw == 0) return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: table_torque needs table_omega (rad/s, a list)");
    if (!pl || nl == 0) return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: table_omega needs table_torque (N m, a list)");
    if (nw != nl)
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "[drive]: table_omega has %zu values but table_torque has %zu (one torque per speed)", nw, nl);
    for (k = 0; k < nw; k++) {
      if (!isfinite(c->drive_w[k]) || !isfinite(c->drive_L[k]))
        return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: table_omega/table_torque value %zu is not finite: allowed finite",
                        k + 1);
      if (k > 0 && !(c->drive_w[k] > c->drive_w[k - 1]))
        return cli_fail(ctx, CLI_EXIT_INPUT,
                        "[drive]: table_omega is not strictly increasing: value %zu (%.17g rad/s) <= value %zu (%.17g "
                        "rad/s) (the torque table must be increasing in speed)",
                        k + 1, c->drive_w[k], k, c->drive_w[k - 1]);
    }
    d->n_torque = nw;
    d->torque_omega = c->drive_w;
    d->torque_L = c->drive_L;
    L0 = c->drive_L[0];
    if (0.0 >= c->drive_w[nw - 1]) L0 = c->drive_L[nw - 1];
    else
      for (k = 0; k + 1 < nw; k++)
        if (c->drive_w[k] <= 0.0 && 0.0 < c->drive_w[k + 1])
          L0 = c->drive_L[k] + (c->drive_L[k + 1] - c->drive_L[k]) * ((0.0 - c->drive_w[k]) / (c->drive_w[k + 1] - c->drive_w[k]));
    if (!(L0 > 0))
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "[drive]: table_torque gives the starting torque L(0) = %.6g N m: allowed (0, inf) (the motor "
                      "cannot start)", L0);
    return CLI_EXIT_OK;
  }
  if (!hL) return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: mode = motor needs L_0 (N m, the starting torque, > 0) and omega_0 (rad/s, > 0), or table_omega and table_torque");
  if (!hw0) return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: mode = motor needs omega_0 (rad/s, the no-load speed, > 0) with L_0");
  if (!(d->L_0 > 0) || !isfinite(d->L_0))
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[drive]: L_0 = %.6g N m is out of range: allowed (0, inf) (the starting torque; L_0 <= 0: the motor "
                    "cannot start)", d->L_0);
  if (!(d->omega_0 > 0) || !isfinite(d->omega_0))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: omega_0 = %.6g rad/s is out of range: allowed (0, inf) (the no-load speed)",
                    d->omega_0);
  return CLI_EXIT_OK;
}

/* [drive]: the spin speed (autobal_rotor_drive).  mode = constant (default: rotor.omega),
 * ramp (omega_a, omega_b in rad/s or any speed unit; t_a < t_b in s), table (table_t in s, strictly
 * increasing; table_omega, one speed per time, each item may carry a unit), motor (read_motor). */
static int read_drive(cli_ctx *ctx, rotor_cfg *c) {
  autobal_rotor_drive *d = &c->p.drive;
  const char *mode = "constant";
  static const char *const ramp_keys[4] = {"omega_a", "omega_b", "t_a", "t_b"};
  static const char *const table_keys[2] = {"table_t", "table_omega"};
  int rc, has_mode = 0, present[4] = {0, 0, 0, 0}, pt = 0, pw = 0;
  size_t k, nt = 0, nw = 0;
  if ((rc = cli_get_string(ctx, "drive", "mode", mode, &mode, &has_mode))) return rc;
  memset(d, 0, sizeof *d);
  if (!strcmp(mode, "constant")) d->mode = AUTOBAL_ROTOR_DRIVE_CONSTANT;
  else if (!strcmp(mode, "ramp")) d->mode = AUTOBAL_ROTOR_DRIVE_RAMP;
  else if (!strcmp(mode, "table")) d->mode = AUTOBAL_ROTOR_DRIVE_TABLE;
  else if (!strcmp(mode, "motor")) d->mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
  else return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: mode = '%s' is not one of: constant, ramp, table, motor", mode);
  if (!cli_section_present(ctx, "drive")) return CLI_EXIT_OK;
  if (d->mode != AUTOBAL_ROTOR_DRIVE_RAMP) {
    for (k = 0; k < 4; k++) {
      double v;
      if ((rc = cli_get_quantity(ctx, "drive", ramp_keys[k], k < 2 ? "rad/s" : "s", 0.0, &v, &present[k]))) return rc;
      if (present[k])
        return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: %s is a key of mode = ramp, but mode = %s", ramp_keys[k], mode);
    }
  }
  if (d->mode != AUTOBAL_ROTOR_DRIVE_MOTOR) {
    static const char *const motor_keys[5] = {"J", "L_0", "omega_0", "k_r", "omega_start"};
    static const char *const motor_units[5] = {"kg m^2", "N m", "rad/s", "N m s", "rad/s"};
    for (k = 0; k < 5; k++) {
      double v;
      if ((rc = cli_get_quantity(ctx, "drive", motor_keys[k], motor_units[k], 0.0, &v, &present[0]))) return rc;
      if (present[0])
        return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: %s is a key of mode = motor, but mode = %s", motor_keys[k], mode);
    }
    if ((rc = cli_get_quantities(ctx, "drive", "table_torque", "N m", c->drive_t, MAX_CFG_DRIVE_POINTS, &nt, &pt)))
      return rc;
    if (pt) return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: table_torque is a key of mode = motor, but mode = %s", mode);
  }
  if (d->mode == AUTOBAL_ROTOR_DRIVE_MOTOR) {
    if ((rc = cli_get_quantities(ctx, "drive", "table_t", "s", c->drive_t, MAX_CFG_DRIVE_POINTS, &nt, &pt))) return rc;
    if (pt) return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: table_t is a key of mode = table, but mode = motor");
    return read_motor(ctx, c);
  }
  if (d->mode != AUTOBAL_ROTOR_DRIVE_TABLE) {
    for (k = 0; k < 2; k++) {
      if ((rc = cli_get_quantities(ctx, "drive", table_keys[k], k ? "rad/s" : "s", c->drive_t, MAX_CFG_DRIVE_POINTS,
                                   &nt, &pt)))
        return rc;
      if (pt)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: %s is a key of mode = table, but mode = %s", table_keys[k], mode);
    }
  }
  if (d->mode == AUTOBAL_ROTOR_DRIVE_RAMP) {
    double *v[4];
    v[0] = &d->omega_a, v[1] = &d->omega_b, v[2] = &d->t_a, v[3] = &d->t_b;
    for (k = 0; k < 4; k++) {
      if ((rc = cli_get_quantity(ctx, "drive", ramp_keys[k], k < 2 ? "rad/s" : "s", NAN, v[k], &present[k]))) return rc;
      if (!present[k])
        return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: mode = ramp needs %s (%s)", ramp_keys[k], k < 2 ? "rad/s" : "s");
    }
    if (!(d->t_b > d->t_a))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: t_b = %.17g s is out of range: allowed t_b > t_a = %.17g s", d->t_b,
                      d->t_a);
  } else if (d->mode == AUTOBAL_ROTOR_DRIVE_TABLE) {
    if ((rc = cli_get_quantities(ctx, "drive", "table_t", "s", c->drive_t, MAX_CFG_DRIVE_POINTS, &nt, &pt))) return rc;
    if ((rc = cli_get_quantities(ctx, "drive", "table_omega", "rad/s", c->drive_w, MAX_CFG_DRIVE_POINTS, &nw, &pw)))
      return rc;
    if (!pt || nt == 0) return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: mode = table needs table_t (s, a list)");
    if (!pw || nw == 0) return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: mode = table needs table_omega (rad/s, a list)");
    if (nt != nw)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[drive]: table_t has %zu values but table_omega has %zu (one speed per time)",
                      nt, nw);
    for (k = 1; k < nt; k++)
      if (!(c->drive_t[k] > c->drive_t[k - 1]))
        return cli_fail(ctx, CLI_EXIT_INPUT,
                        "[drive]: table_t is not strictly increasing: value %zu (%.17g s) <= value %zu (%.17g s)", k + 1,
                        c->drive_t[k], k, c->drive_t[k - 1]);
    d->n_points = nt;
    d->table_t = c->drive_t;
    d->table_omega = c->drive_w;
  }
  return CLI_EXIT_OK;
}

/* [drive] for the other rotor commands (apps/cmd_ensemble.c): read_drive into the configuration
 * that cli_rotor_config_read left in storage (a table's points stay there), copied to p->drive. */
int cli_rotor_drive_read(cli_ctx *ctx, autobal_rotor_params *p, void *storage) {
  rotor_cfg *c = storage;
  int rc = read_drive(ctx, c);
  p->drive = c->p.drive;
  return rc;
}

/* [friction] and the planes' ball_f, ball_mu for the other rotor commands (apps/cmd_ensemble.c):
 * read_friction into the configuration that cli_rotor_config_read left in storage (the lists stay
 * there), copied to p->friction. */
static int read_friction(cli_ctx *ctx, rotor_cfg *c);
int cli_rotor_friction_read(cli_ctx *ctx, autobal_rotor_params *p, void *storage) {
  rotor_cfg *c = storage;
  int rc = read_friction(ctx, c);
  p->friction = c->p.friction;
  p->rolling = c->p.rolling; /* ball_rho, read with the planes' friction keys */
  return rc;
}

/* [contact] restitution (1, [0, 1]; default 1), v_rest (rad/s; default 1e-3): with ball_diameter,
 * which read_friction read with the planes (contact on when given in some plane).  The ranges
 * (restitution in [0, 1], v_rest >= 0, diameters >= 0, the balls of a track fit) are the library's
 * checks (autobal_rotor_params_check), named in the configuration's terms. */
static int read_contact(cli_ctx *ctx, rotor_cfg *c) {
  int rc, pe = 0, pv = 0;
  c->p.contact.restitution = 1.0;
  c->p.contact.v_rest = 0.0;
  if ((rc = cli_get_double(ctx, "contact", "restitution", 1.0, &c->p.contact.restitution, &pe))) return rc;
  if ((rc = cli_get_quantity(ctx, "contact", "v_rest", "rad/s", 0.0, &c->p.contact.v_rest, &pv))) return rc;
  if ((pe || pv) && !c->p.contact.on)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[contact]: %s is given but no ball has a size: set [plane1] ball_diameter",
                    pe ? "restitution" : "v_rest");
  return CLI_EXIT_OK;
}

/* Ball size and contact for the other rotor commands (apps/cmd_ensemble.c): read_contact into the
 * configuration that cli_rotor_friction_read left in storage (the planes' ball_diameter lists stay
 * there), copied to p->contact.  Call it after cli_rotor_friction_read. */
int cli_rotor_contact_read(cli_ctx *ctx, autobal_rotor_params *p, void *storage) {
  rotor_cfg *c = storage;
  int rc = read_contact(ctx, c);
  p->contact = c->p.contact;
  return rc;
}

/* The speed the revolutions are counted at: rotor.omega, or the largest |speed| of the drive. */
static double speed_ref(const rotor_cfg *c) {
  const autobal_rotor_drive *d = &c->p.drive;
  double m = 0.0;
  size_t k;
  if (d->mode == AUTOBAL_ROTOR_DRIVE_RAMP) return fmax(fabs(d->omega_a), fabs(d->omega_b));
  if (d->mode == AUTOBAL_ROTOR_DRIVE_MOTOR) { /* the no-load speed (a table: its largest speed) */
    m = d->n_torque ? 0.0 : d->omega_0;
    for (k = 0; k < d->n_torque; k++) m = fmax(m, fabs(d->torque_omega[k]));
    return fmax(m, fabs(d->omega_start));
  }
  if (d->mode != AUTOBAL_ROTOR_DRIVE_TABLE) return fabs(c->p.omega);
  for (k = 0; k < d->n_points; k++) m = fmax(m, fabs(d->table_omega[k]));
  return m;
}

/* [friction] law = none | exact | regularized, u_eps (rad/s, regularized only); per plane the
 * lists ball_f (rolling-resistance coefficients, default 0) and ball_mu (static coefficients,
 * default: = ball_f), n values or one for all.  The ranges (f >= 0, mu >= f, u_eps > 0) are the
 * library's checks (autobal_rotor_params_check), named in the configuration's terms. */
static int read_friction(cli_ctx *ctx, rotor_cfg *c) {
  autobal_rotor_friction *fr = &c->p.friction;
  size_t j;
  int rc, has_u = 0;
  memset(fr, 0, sizeof *fr);
  c->friction_law = "none";
  if (cli_section_present(ctx, "friction")) {
    double u_eps = NAN;
    if ((rc = cli_get_string(ctx, "friction", "law", c->friction_law, &c->friction_law, NULL))) return rc;
    if ((rc = cli_get_quantity(ctx, "friction", "u_eps", "rad/s", NAN, &u_eps, &has_u))) return rc;
    if (!strcmp(c->friction_law, "none")) fr->law = AUTOBAL_ROTOR_FRICTION_NONE;
    else if (!strcmp(c->friction_law, "exact")) fr->law = AUTOBAL_ROTOR_FRICTION_EXACT;
    else if (!strcmp(c->friction_law, "regularized")) fr->law = AUTOBAL_ROTOR_FRICTION_REGULARIZED;
    else
      return cli_fail(ctx, CLI_EXIT_INPUT, "[friction]: law = '%s' is not one of: none, exact, regularized",
                      c->friction_law);
    if (fr->law == AUTOBAL_ROTOR_FRICTION_REGULARIZED && !has_u)
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "[friction]: law = regularized needs u_eps (rad/s, > 0: the speed of f N tanh(psi'/u_eps))");
    if (fr->law != AUTOBAL_ROTOR_FRICTION_REGULARIZED && has_u)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[friction]: u_eps is a key of law = regularized, but law = %s",
                      c->friction_law);
    fr->u_eps = u_eps;
  }
  for (j = 0; j < c->p.n_planes; j++) {
    const char *sec = j ? "plane2" : "plane1";
    const size_t n = c->p.plane[j].n_balls;
    size_t nf, nm, k;
    int pf, pm;
    if ((rc = cli_get_quantities(ctx, sec, "ball_f", "1", c->fric_f[j], MAX_CFG_BALLS, &nf, &pf))) return rc;
    if ((rc = cli_get_quantities(ctx, sec, "ball_mu", "1", c->fric_mu[j], MAX_CFG_BALLS, &nm, &pm))) return rc;
    if ((nf || nm) && fr->law == AUTOBAL_ROTOR_FRICTION_NONE)
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "[%s]: %s is given but there is no friction law: set [friction] law = exact or regularized", sec,
                      nf ? "ball_f" : "ball_mu");
    if ((nf && nf != 1 && nf != n) || (nm && nm != 1 && nm != n))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s has %zu values but there are %zu balls (one value for all, or one per ball)",
                      sec, (nf && nf != 1 && nf != n) ? "ball_f" : "ball_mu", (nf && nf != 1 && nf != n) ? nf : nm, n);
    { /* ball_rho (m): rolling inertia (docs/device.md section 3), on when given in some plane */
      size_t nr;
      int pr;
      if ((rc = cli_get_quantities(ctx, sec, "ball_rho", "m", c->rho[j], MAX_CFG_BALLS, &nr, &pr))) return rc;
      if (nr && nr != 1 && nr != n)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: ball_rho has %zu values but there are %zu balls (one value for all, or one per ball)",
                        sec, nr, n);
      for (k = 0; nr == 1 && k < n; k++) c->rho[j][k] = c->rho[j][0];
      if (nr) c->p.rolling.on = 1, c->p.rolling.ball_rho[j] = c->rho[j];
      /* ball_diameter (m): contact (docs/device.md section 4), on when given in some plane */
      if ((rc = cli_get_quantities(ctx, sec, "ball_diameter", "m", c->diam[j], MAX_CFG_BALLS, &nr, &pr))) return rc;
      if (nr && nr != 1 && nr != n)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: ball_diameter has %zu values but there are %zu balls (one value for all, or one per ball)",
                        sec, nr, n);
      for (k = 0; nr == 1 && k < n; k++) c->diam[j][k] = c->diam[j][0];
      if (nr) c->p.contact.on = 1, c->p.contact.ball_diameter[j] = c->diam[j];
    }
    if (fr->law == AUTOBAL_ROTOR_FRICTION_NONE || n == 0) continue;
    for (k = 0; k < n; k++) {
      c->fric_f[j][k] = nf == 0 ? 0.0 : c->fric_f[j][nf == 1 ? 0 : k];
      c->fric_mu[j][k] = nm == 0 ? c->fric_f[j][k] : c->fric_mu[j][nm == 1 ? 0 : k];
    }
    fr->ball_f[j] = c->fric_f[j];
    fr->ball_mu[j] = c->fric_mu[j];
  }
  return CLI_EXIT_OK;
}

static int read_rotor_config(cli_ctx *ctx, rotor_cfg *c) {
  int rc;
  double wref;
  if ((rc = read_rotor_model(ctx, c))) return rc;
  if ((rc = read_drive(ctx, c))) return rc;
  if ((rc = read_friction(ctx, c))) return rc;
  if ((rc = read_contact(ctx, c))) return rc;
  wref = speed_ref(c);
  /* [balance] grade = G2.5: the permissible residual unbalance of that grade is reported */
  c->grade = NAN;
  if ((rc = cli_get_string(ctx, "balance", "grade", NULL, &c->grade_text, NULL))) return rc;
  if (c->grade_text && cli_parse_grade(c->grade_text, &c->grade) != 0)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[balance]: grade = '%s' is not a balance quality grade: write G followed by a positive number "
                    "in mm/s (ISO 21940-11 grades: G0.4, G1, G2.5, G6.3, G16, G40, ...)",
                    c->grade_text);
  /* [transient] */
  c->t_end = 20.0;
  c->dt_out = 0.0; /* 0: revs_out */
  /* rtol bounds the fixed-frame ball angles (|phi| ~ omega t: 3770 rad at 600 revolutions), atol
   * the rotor coordinates, which set the step count: 1e-8/1e-10 left 9e-4 (relative) in the default
   * example's |s| at 600 revolutions, 1e-10/1e-9 leaves 2e-5 with 11% fewer rhs evaluations (docs/guide.md, "Tolerances") */
  c->rtol = 1e-10;
  c->atol = 1e-9;
  c->h_max = 0.0;
  c->max_steps = 100000000L;
  c->balance_tol = 0.01;
  c->balance_revs = 50;
  c->stepper = "dop853"; /* the library's default (autobal_study_rotor_transient_options_default) */
  c->output = "dense6";
  c->frame_name = "fixed";
  {
    double revs_out = 0.25;
    int has_dt = 0, has_revs = 0, has_brevs = 0, has_dwell = 0;
    double dwell = 0.0;
    if ((rc = get_q(ctx, "transient", "t_end", "s", &c->t_end))) return rc;
    if ((rc = cli_get_quantity(ctx, "transient", "dt_out", "s", 0.0, &c->dt_out, &has_dt))) return rc;
    if ((rc = cli_get_double(ctx, "transient", "revs_out", revs_out, &revs_out, &has_revs))) return rc;
    if ((rc = get_d(ctx, "transient", "rtol", &c->rtol))) return rc;
    if ((rc = get_d(ctx, "transient", "atol", &c->atol))) return rc;
    if ((rc = get_q(ctx, "transient", "h_max", "s", &c->h_max))) return rc;
    if ((rc = cli_get_int(ctx, "transient", "max_steps", c->max_steps, &c->max_steps, NULL))) return rc;
    if ((rc = cli_get_string(ctx, "transient", "stepper", c->stepper, &c->stepper, NULL))) return rc;
    if ((rc = cli_get_string(ctx, "transient", "output", c->output, &c->output, NULL))) return rc;
    if (strcmp(c->output, "dense") != 0 && strcmp(c->output, "dense6") != 0 &&
        strcmp(c->output, "exact") != 0)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: output = '%s' is not one of: dense, dense6, exact", c->output);
    if ((rc = cli_get_string(ctx, "transient", "frame", c->frame_name, &c->frame_name, NULL))) return rc;
    if ((rc = get_d(ctx, "transient", "balance_tol", &c->balance_tol))) return rc;
    if ((rc = cli_get_double(ctx, "transient", "balance_revs", c->balance_revs, &c->balance_revs, &has_brevs))) return rc;
    if ((rc = cli_get_quantity(ctx, "transient", "balance_dwell", "s", 0.0, &dwell, &has_dwell))) return rc;
    if ((rc = cli_get_bool(ctx, "transient", "stop_at_balance", 0, &c->stop_at_balance, NULL))) return rc;
    c->capture_band = 0.05; /* run-up outputs; checked by the study (autobal_study_rotor_transient_check) */
    c->capture_time = 2.0;
    if ((rc = get_d(ctx, "transient", "capture_band", &c->capture_band))) return rc;
    if ((rc = get_q(ctx, "transient", "capture_time", "s", &c->capture_time))) return rc;
    if (has_dt && has_revs) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give dt_out or revs_out, not both");
    if (!(c->t_end > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: t_end = %g s is out of range: allowed (0, inf)", c->t_end);
    if (!has_dt) {
      if (!(revs_out > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: revs_out = %g is out of range: allowed (0, inf)", revs_out);
      if (!(wref > 0))
        return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: revs_out needs omega != 0 (with a drive: a non-zero speed); give dt_out (s) instead");
      c->dt_out = revs_out * TWO_PI / wref;
      if (!(c->t_end / c->dt_out <= 5e8)) /* e.g. omega = 1e308: name the speed, not only t_end/dt_out */
        return cli_fail(ctx, CLI_EXIT_INPUT,
                        "[transient]: revs_out = %g at %g rad/s gives dt_out = %.3g s, %.3g samples in t_end = %g s: too "
                        "many (at most 5e8); give dt_out, or a smaller speed or t_end",
                        revs_out, wref, c->dt_out, c->t_end / c->dt_out, c->t_end);
    }
    if (!(c->dt_out > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: dt_out = %g s is out of range: allowed (0, inf)", c->dt_out);
    if (c->t_end / c->dt_out > 5e8)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: t_end/dt_out = %.3g samples is too many (at most 5e8)", c->t_end / c->dt_out);
    if (!(c->balance_tol > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_tol = %g is out of range: allowed (0, inf)", c->balance_tol);
    if (!(wref > 0) && !has_dwell)
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "[transient]: with rotor.omega = 0 there are no revolutions: give balance_dwell (s) instead of "
                      "balance_revs, and dt_out (s)");
    if (has_brevs && has_dwell)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give balance_revs (revolutions) or balance_dwell (s), not both");
    if (has_dwell) {
      if (!(dwell >= 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_dwell = %g s is out of range: allowed [0, inf)", dwell);
      if (!(wref > 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_dwell needs omega != 0");
      c->balance_revs = dwell * wref / TWO_PI;
    }
    if (!(c->balance_revs >= 0)) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_revs = %g is out of range: allowed [0, inf)", c->balance_revs);
    if (c->max_steps < 1) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: max_steps = %ld is out of range: allowed [1, inf)", c->max_steps);
    if (!strcmp(c->frame_name, "fixed")) c->frame = AUTOBAL_ROTOR_FIXED;
    else if (!strcmp(c->frame_name, "rotating")) c->frame = AUTOBAL_ROTOR_ROTATING;
    else return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: frame = '%s' is not one of: fixed, rotating", c->frame_name);
  }
  return CLI_EXIT_OK;
}


/* ---- the run: the library's study (autobal_study_rotor_transient) ------------------------- */
static autobal_study_rotor_transient_options study_options(const rotor_cfg *c) {
  autobal_study_rotor_transient_options o = autobal_study_rotor_transient_options_default();
  o.t_end = c->t_end;
  o.dt_out = c->dt_out;
  o.rtol = c->rtol;
  o.atol = c->atol;
  o.h_max = c->h_max;
  o.max_steps = (unsigned long)c->max_steps;
  o.stepper = c->stepper;
  o.exact_output = strcmp(c->output, "exact") == 0;
  o.dense_order = strcmp(c->output, "dense6") == 0 ? 6 : 7;
  o.frame = c->frame;
  o.balance_tol = c->balance_tol;
  o.balance_revs = c->balance_revs;
  o.stop_at_balance = c->stop_at_balance;
  o.grade = c->grade;
  o.capture_band = c->capture_band;
  o.capture_time = c->capture_time;
  return o;
}

static int progress(double fraction, void *user) { return cli_progress(user, "rotor transient", fraction); }

/* A message of the study in the configuration's names: its option messages ("options: ...")
 * are about [transient], the others about the model (cli_rotor_message). */
static const char *study_message(const char *msg, char *buf, size_t len) {
  if (!strncmp(msg, "options: ", 9)) {
    snprintf(buf, len, "[transient]: %s", msg + 9);
    return buf;
  }
  return cli_rotor_message(msg, buf, len);
}

static void engineering_json(cli_json *j, const autobal_study_rotor_transient_summary *s) {
  cli_json_quantities(j, "residual_unbalance_abs_final", s->residual_unbalance_abs_final, s->n_planes, "kg m");
  cli_json_quantity(j, "balance_grade_final", s->balance_grade_final, "mm/s");
  cli_json_quantity(j, "balance_grade_rotor_mass", s->balance_grade_rotor_mass, "kg");
  if (!isnan(s->permissible_unbalance)) {
    cli_json_quantity(j, "permissible_unbalance", s->permissible_unbalance, "kg m");
    cli_json_bool(j, "permissible_unbalance_met", s->permissible_unbalance_met);
  }
  cli_json_quantity(j, "displacement_pk_pk_G_last_10pct", s->displacement_pk_pk[0], "m");
  cli_json_quantity(j, "velocity_rms_supports_last_10pct", s->velocity_rms_supports, "m/s");
}

/* The spin speed at the end of the run (rad/s): rotor.omega, the drive's Omega(t), or the motor's
 * Omega in the final state. */
static double speed_at(const rotor_cfg *c, const autobal_study_rotor_transient_summary *s) {
  double v[2] = {c->p.omega, 0.0};
  if (c->p.drive.mode != AUTOBAL_ROTOR_DRIVE_CONSTANT) {
    autobal_rotor *r = autobal_rotor_alloc(&c->p, NULL);
    if (!r || !s->state_final || s->dim != autobal_rotor_dim(r) ||
        autobal_rotor_spin(r, s->t_reached, s->state_final, v) != AUTOBAL_SUCCESS)
      v[0] = NAN;
    autobal_rotor_free(r);
  }
  return v[0];
}

static void engineering_print(const autobal_study_rotor_transient_summary *s, const rotor_cfg *c) {
  double w_end = fabs(speed_at(c, s));
  double cls = s->balance_grade_class, rpm = cli_rpm(w_end > 0 ? w_end : speed_ref(c));
  char cbuf[32] = "above G4000";
  if (!isnan(cls)) snprintf(cbuf, sizeof cbuf, "within G%g", cls);
  printf("  balance quality at the end: G %.3g mm/s, %s (ISO 21940-11: G = e omega, e = U/m with rotor mass %s = %g kg%s)\n",
         s->balance_grade_final, cbuf, c->p.input == AUTOBAL_ROTOR_HARDWARE ? "m_p" : "M", s->balance_grade_rotor_mass,
         c->p.n_planes > 1 ? " shared equally by the planes" : "");
  if (!isnan(s->permissible_unbalance))
    printf("  grade G%g permits %.4g g mm at %.1f rpm%s: %s\n", c->grade, s->permissible_unbalance * 1e6, rpm,
           c->p.n_planes > 1 ? " (half per plane)" : "", s->permissible_unbalance_met ? "MET" : "NOT met");
  if (s->have_vibration_window)
    printf("  vibration at the running speed (1X) in the last 10%% of the run: centre of mass %.4g um 0-peak, %.4g um "
           "peak-to-peak (largest of x, y); velocity %.4g mm/s RMS %s\n",
           s->displacement_pk_pk[0] * 0.5e6, s->displacement_pk_pk[0] * 1e6, s->velocity_rms_supports * 1e3,
           isnan(s->velocity_rms[1]) ? "at the centre of mass" : "at the supports (ISO 20816 measure: largest of left/right, x/y)");
}

/* Gravity (docs/device.md section 2): the static offset and, per plane, g sin(theta) / (r Omega^2)
 * at the final speed. */
static void gravity_print(const autobal_study_rotor_transient_summary *s, const rotor_cfg *c) {
  size_t j;
  printf("  gravity: shaft at %.6g deg to the vertical, g = %.6g m/s^2 (%.6g m/s^2 in the plane of the motion); "
         "static offset y_s = %.6g mm, alpha_s = %.6g mrad\n",
         c->p.shaft_angle * 360.0 / TWO_PI, c->p.g, c->p.g * sin(c->p.shaft_angle), s->static_offset[1] * 1e3,
         s->static_offset[2] * 1e3);
  for (j = 0; j < s->n_planes; j++) {
    const double q = s->gravity_ratio_final[j];
    if (isnan(q)) continue;
    printf("  gravity, plane %zu: g sin(theta) / (r Omega^2) = %.4g at the final speed: %s\n", j + 1, q,
           q < 1.0 ? "carried round (centrifugal acceleration above the weight)"
                   : "NOT carried round (the balls lie at the bottom of the track)");
  }
}

/* The run-up outputs of a drive (docs/device.md, "Run-up outputs"). */
static void runup_print(const autobal_study_rotor_transient_summary *s, const rotor_cfg *c) {
  const autobal_runup_result *r = &s->runup;
  size_t k;
  printf("  run-up: resonance speeds (Campbell crossings, rad/s):");
  for (k = 0; k < s->n_resonances; k++)
    printf(" %.6g (%.0f rpm, %s)", s->resonance_speed[k], s->resonance_speed[k] * 60.0 / TWO_PI,
           s->resonance_whirl[k] > 0 ? "forward" : s->resonance_whirl[k] < 0 ? "backward" : "whirl undecided");
  printf("%s\n", s->n_resonances ? "" : " none below the largest speed");
  if (r->n_passages) {
    printf("  run-up: %zu passage(s):", r->n_passages);
    for (k = 0; k < r->n_passages && k < 8; k++)
      printf(" %.6g rad/s %s at t = %.6g s%s", s->resonance_speed[s->passages[k].resonance],
             s->passages[k].direction > 0 ? "up" : "down", s->passages[k].t, k + 1 < r->n_passages ? ";" : "");
    printf("%s\n", r->n_passages > 8 ? " ..." : "");
  }
  if (!r->n_captures)
    printf("  run-up: no capture (|Omega| never within %g%% of a resonance speed for %g s or longer)\n",
           c->capture_band * 100.0, c->capture_time);
  for (k = 0; k < r->n_captures && k < 8; k++)
    printf("  run-up: CAPTURED within %g%% of %.6g rad/s from t = %.6g s to %.6g s%s\n", c->capture_band * 100.0,
           s->resonance_speed[s->captures[k].resonance], s->captures[k].t_enter, s->captures[k].t_leave,
           s->captures[k].at_end ? " (still at the end)" : "");
  if (r->n_passages && !isnan(r->time_to_balance))
    printf("  run-up: balanced (|s|/(m0 r0) < %g to the end) from t = %.6g s, %.6g s after the last passage\n",
           c->balance_tol, r->time_to_balance, r->balance_delay);
  else if (r->n_passages)
    printf("  run-up: not balanced at the end (|s|/(m0 r0) >= %g after the last passage at t = %.6g s)\n",
           c->balance_tol, r->t_last_passage);
  printf("  run-up: largest amplitude of the centre of mass %.4g um at t = %.6g s, Omega = %.6g rad/s (%.0f rpm)\n",
         r->envelope_max * 1e6, r->t_envelope_max, r->omega_envelope_max, r->omega_envelope_max * 60.0 / TWO_PI);
}

static void runup_json(cli_json *j, const autobal_study_rotor_transient_summary *s) {
  size_t k;
  cli_json_object(j, "runup");
  cli_json_quantities(j, "resonance_speed", s->resonance_speed, s->n_resonances, "rad/s");
  cli_json_array(j, "passage_time");
  for (k = 0; k < s->runup.n_passages; k++) cli_json_number(j, NULL, s->passages[k].t);
  cli_json_array_end(j);
  cli_json_int(j, "n_captures", (long)s->runup.n_captures);
  cli_json_quantity(j, "t_last_passage", s->runup.t_last_passage, "s");
  cli_json_quantity(j, "time_to_balance_after_last_passage", s->runup.time_to_balance, "s");
  cli_json_quantity(j, "envelope_max", s->runup.envelope_max, "m");
  cli_json_object(j, "units");
  cli_json_string(j, "resonance_speed", "rad/s");
  cli_json_string(j, "passage_time", "s");
  cli_json_string(j, "t_last_passage", "s");
  cli_json_string(j, "time_to_balance_after_last_passage", "s");
  cli_json_string(j, "envelope_max", "m");
  cli_json_object_end(j);
  cli_json_object_end(j);
}

static void print_json(cli_ctx *ctx, const rotor_cfg *c, const autobal_study_rotor_transient_summary *s, int warn) {
  cli_json jj;
  size_t j;
  cli_json_summary_begin(&jj, ctx);
  cli_json_bool(&jj, "balanced", s->balanced);
  cli_json_quantity(&jj, "time_to_balance", s->time_to_balance, "s");
  cli_json_quantity(&jj, "t_reached", s->t_reached, "s");
  cli_json_quantity(&jj, "residual_unbalance_initial", s->residual_unbalance_initial, "1");
  cli_json_quantity(&jj, "residual_unbalance_final", s->residual_unbalance_final, "1");
  cli_json_quantity(&jj, "amplitude_first_10pct_max", s->amplitude_first_10pct_max, "m");
  cli_json_quantity(&jj, "amplitude_last_10pct_max", s->amplitude_last_10pct_max, "m");
  engineering_json(&jj, s);
  if (s->have_runup) runup_json(&jj, s);
  if (s->have_contact) {
    cli_json_int(&jj, "contact_impacts", (long)s->contact_impacts);
    cli_json_int(&jj, "contact_joins", (long)s->contact_joins);
    cli_json_int(&jj, "contact_releases", (long)s->contact_releases);
    cli_json_int(&jj, "contacts_final", (long)s->contacts_final);
    cli_json_quantities(&jj, "contact_capacity", s->contact_capacity, s->n_planes, "kg m");
    cli_json_array(&jj, "contact_reachable");
    for (j = 0; j < s->n_planes; j++) cli_json_bool(&jj, NULL, s->contact_reachable[j]);
    cli_json_array_end(&jj);
  }
  if (c->p.gravity) {
    cli_json_quantity(&jj, "static_offset_y", s->static_offset[1], "m");
    cli_json_quantity(&jj, "static_offset_alpha", s->static_offset[2], "rad");
    cli_json_quantities(&jj, "gravity_ratio_final", s->gravity_ratio_final, s->n_planes, "1");
  }
  /* every plane: residual unbalance, ball angles relative to the rotor at the end, the
   * balanced configuration (3.14) when it exists */
  cli_json_array(&jj, "planes");
  for (j = 0; j < s->n_planes; j++) {
    size_t i, nbj = s->ball_psi_final[j] ? s->n_balls[j] : 0;
    cli_json_object(&jj, NULL);
    cli_json_int(&jj, "plane", (long)j + 1);
    cli_json_number(&jj, "residual_unbalance_abs", s->residual_unbalance_abs_final[j]);
    cli_json_number(&jj, "residual_unbalance_rel", s->residual_unbalance_rel_final[j]);
    cli_json_array(&jj, "ball_psi_final");
    for (i = 0; i < nbj; i++) cli_json_number(&jj, NULL, s->ball_psi_final[j][i]);
    cli_json_array_end(&jj);
    if (s->ball_psi_balanced[j]) cli_json_numbers(&jj, "ball_psi_balanced", s->ball_psi_balanced[j], s->n_balls[j]);
    if (s->have_friction && s->ball_time_stuck[j]) {
      cli_json_numbers(&jj, "ball_time_stuck", s->ball_time_stuck[j], s->n_balls[j]);
      cli_json_array(&jj, "ball_stuck_final");
      for (i = 0; i < s->n_balls[j]; i++) cli_json_bool(&jj, NULL, s->ball_stuck_final[j][i]);
      cli_json_array_end(&jj);
    }
    cli_json_object(&jj, "units");
    cli_json_string(&jj, "residual_unbalance_abs", "kg m");
    cli_json_string(&jj, "residual_unbalance_rel", "1");
    cli_json_string(&jj, "ball_psi_final", "rad");
    cli_json_string(&jj, "ball_psi_balanced", "rad");
    if (s->have_friction) cli_json_string(&jj, "ball_time_stuck", "s");
    cli_json_object_end(&jj);
    cli_json_object_end(&jj);
  }
  cli_json_array_end(&jj);
  if (s->have_friction) {
    cli_json_int(&jj, "friction_sticks", (long)s->friction_sticks);
    cli_json_int(&jj, "friction_slips", (long)s->friction_slips);
    cli_json_int(&jj, "friction_reversals", (long)s->friction_reversals);
  }
  if (s->state_final) { /* the state at t_reached: values, names and units entry by entry */
    size_t k;
    char nm[64];
    const char *u;
    cli_json_string(&jj, "final_state_frame", s->state_frame == AUTOBAL_ROTOR_FIXED ? "fixed" : "rotating");
    cli_json_numbers(&jj, "final_state", s->state_final, s->dim);
    cli_json_array(&jj, "final_state_names");
    for (k = 0; k < s->dim; k++)
      cli_json_string(&jj, NULL, autobal_study_rotor_transient_state_name(s, k, nm, sizeof nm, &u) ? "?" : nm);
    cli_json_array_end(&jj);
    cli_json_array(&jj, "final_state_units");
    for (k = 0; k < s->dim; k++)
      cli_json_string(&jj, NULL, autobal_study_rotor_transient_state_name(s, k, nm, sizeof nm, &u) ? "?" : u);
    cli_json_array_end(&jj);
  }
  cli_json_int(&jj, "steps", (long)s->solver.steps);
  cli_json_int(&jj, "rhs_evaluations", (long)s->solver.rhs_evals);
  cli_json_quantity(&jj, "wall_time", s->solver.wall_seconds, "s");
  cli_json_bool(&jj, "warning", warn);
  cli_json_summary_end(&jj, ctx);
  (void)c;
}

static void print_text(cli_ctx *ctx, const rotor_cfg *c, const autobal_study_rotor_transient_summary *s) {
  double s0 = c->p.plane[0].m0 * c->p.plane[0].r0;
  size_t j, nb = 0;
  for (j = 0; j < s->n_planes; j++) nb += s->n_balls[j];
  const autobal_rotor_drive *d = &c->p.drive;
  if (d->mode == AUTOBAL_ROTOR_DRIVE_CONSTANT)
    printf("rotor transient: omega = %.6g rad/s (%.1f rpm), %zu plane(s), %zu ball(s), %.6g s simulated (%.0f revolutions)\n",
           c->p.omega, c->p.omega * 60.0 / (TWO_PI), s->n_planes, nb, s->t_reached, s->t_reached / s->revolution_period);
  else {
    double w_end = speed_at(c, s);
    if (d->mode == AUTOBAL_ROTOR_DRIVE_MOTOR && d->n_torque == 0)
      printf("rotor transient: motor L = %.6g N m (1 - Omega/%.6g rad/s), J = %.6g kg m^2, k_r = %.6g N m s, from "
             "Omega = %.6g rad/s", d->L_0, d->omega_0, d->J, d->k_r, d->omega_start);
    else if (d->mode == AUTOBAL_ROTOR_DRIVE_MOTOR)
      printf("rotor transient: motor with a torque table of %zu points (%.6g .. %.6g rad/s), J = %.6g kg m^2, k_r = "
             "%.6g N m s, from Omega = %.6g rad/s", d->n_torque, d->torque_omega[0], d->torque_omega[d->n_torque - 1],
             d->J, d->k_r, d->omega_start);
    else if (d->mode == AUTOBAL_ROTOR_DRIVE_RAMP)
      printf("rotor transient: ramp drive %.6g -> %.6g rad/s (%.1f -> %.1f rpm) from t = %.6g s to %.6g s",
             d->omega_a, d->omega_b, d->omega_a * 60.0 / TWO_PI, d->omega_b * 60.0 / TWO_PI, d->t_a, d->t_b);
    else
      printf("rotor transient: table drive of %zu points from t = %.6g s to %.6g s", d->n_points, d->table_t[0],
             d->table_t[d->n_points - 1]);
    printf(", %zu plane(s), %zu ball(s), %.6g s simulated, Omega = %.6g rad/s (%.1f rpm) at the end\n", s->n_planes, nb,
           s->t_reached, w_end, w_end * 60.0 / TWO_PI);
  }
  printf("  residual unbalance |s|/(m0 r0): %.4g at the start -> %.4g at the end%s\n", s->residual_unbalance_initial,
         s->residual_unbalance_final, s0 > 0 ? "" : " (relative to the balls' capacity: no unbalance)");
  printf("  vibration amplitude of the centre of mass: max %.4g um in the first 10%% of the run, %.4g um in the last 10%%\n",
         s->amplitude_first_10pct_max * 1e6, s->amplitude_last_10pct_max * 1e6);
  if (s->balanced)
    printf("  BALANCED: residual unbalance below %.3g (relative) from t = %.6g s on (held for %.0f revolutions)\n",
           c->balance_tol, s->time_to_balance, c->balance_revs);
  else
    printf("  NOT balanced: the residual unbalance did not stay below %.3g (relative) for %.0f revolutions\n",
           c->balance_tol, c->balance_revs);
  for (j = 0; j < s->n_planes; j++) {
    size_t i, nbj = s->ball_psi_final[j] ? s->n_balls[j] : 0;
    printf("  plane %zu: residual unbalance %.4g g mm at the end (its unbalance m0 r0 = %.4g g mm)\n", j + 1,
           s->residual_unbalance_abs_final[j] * 1e6, c->p.plane[j].m0 * c->p.plane[j].r0 * 1e6);
    if (nbj == 0) continue;
    printf("  plane %zu ball angles relative to the rotor at the end (rad, wrapped):", j + 1);
    for (i = 0; i < nbj && i < 8; i++) printf(" %.5f", s->ball_psi_final[j][i]);
    printf("%s\n", nbj > 8 ? " ..." : "");
    if (s->ball_psi_balanced[j]) {
      printf("  balanced configuration (3.14) of plane %zu:", j + 1);
      for (i = 0; i < nbj && i < 8; i++) printf(" %.5f", s->ball_psi_balanced[j][i]);
      printf("%s\n", nbj > 8 ? " ..." : "");
    }
  }
  if (s->have_contact) {
    printf("  contact: %lu impact(s), %lu pair(s) joined in resting contact, %lu released, %lu touching at the end\n",
           s->contact_impacts, s->contact_joins, s->contact_releases, s->contacts_final);
    for (j = 0; j < s->n_planes; j++)
      if (!s->contact_reachable[j])
        printf("  plane %zu: the balanced angles are out of reach with these ball sizes: unbalance %.4g g mm > the "
               "largest resultant of the packed balls %.4g g mm\n",
               j + 1, c->p.plane[j].m0 * c->p.plane[j].r0 * 1e6, s->contact_capacity[j] * 1e6);
  }
  if (s->have_friction) {
    printf("  friction (exact): %lu stick(s), %lu slip(s) from stuck, %lu reversal(s) at psi' = 0\n", s->friction_sticks,
           s->friction_slips, s->friction_reversals);
    for (j = 0; j < s->n_planes; j++) {
      size_t i, nbj = s->ball_time_stuck[j] ? s->n_balls[j] : 0;
      if (nbj == 0) continue;
      printf("  plane %zu time stuck (s):", j + 1);
      for (i = 0; i < nbj && i < 8; i++) printf(" %.6g%s", s->ball_time_stuck[j][i], s->ball_stuck_final[j][i] ? "*" : "");
      printf("%s   (* stuck at the end)\n", nbj > 8 ? " ..." : "");
    }
  }
  engineering_print(s, c);
  if (c->p.gravity) gravity_print(s, c);
  if (s->have_runup) runup_print(s, c);
  cli_print_solver_line(s->stepper, &s->solver);
  if (ctx->output) printf("archive: %s\n", ctx->output);
}

int cli_cmd_rotor_transient(cli_ctx *ctx) {
  rotor_cfg *c = calloc(1, sizeof *c);
  autobal_study_rotor_transient_options opt;
  autobal_study_rotor_transient_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  char msg[sizeof ctx->err];
  int rc = CLI_EXIT_OK, st, warn = 0;

  memset(&sum, 0, sizeof sum);
  autobal_error_clear(&err);
  if (!c) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  if ((rc = read_rotor_config(ctx, c))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  opt = study_options(c);
  opt.progress = progress;
  opt.progress_user = ctx;
  /* the inputs are checked before the archive is created: bad input leaves no file */
  st = autobal_study_rotor_transient_check(&c->p, &opt, &err);
  if (st < 0) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s", study_message(err.message, msg, sizeof msg));
    goto done;
  }
  if (st == AUTOBAL_WARNING) {
    warn = 1;
    if (!ctx->json) fprintf(stderr, "autobal: warning: %s\n", cli_rotor_message(err.message, msg, sizeof msg));
  }
  if ((rc = cli_archive_open(ctx, "autobal rotor transient", &a))) goto done;
  st = autobal_study_rotor_transient(&c->p, &opt, a, &sum, &err);
  cli_progress_done(ctx);
  if (st == AUTOBAL_ECANCELLED)
    rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED,
                  "interrupted at t = %.6g s of %.6g s; the archive keeps everything computed so far (status incomplete)",
                  sum.t_reached, c->t_end);
  else if (st < 0 && st == sum.solver.status) /* the integration failed */
    rc = cli_fail(ctx, cli_exit_code(st), "%s (t reached %.9g s of %.6g s; partial results kept)", sum.solver_message,
                  sum.t_reached, c->t_end);
  else if (st < 0)
    rc = cli_fail(ctx, cli_exit_code(st), "%s", study_message(err.message, msg, sizeof msg));
  if (a) rc = cli_archive_end(ctx, &a, AUTOBAL_SUCCESS, rc);
  /* the summary only of a run that started (not after a failure of its set-up) */
  if ((rc == CLI_EXIT_OK || rc == CLI_EXIT_NUMERIC || rc == CLI_EXIT_INTERRUPTED) && sum.n_planes > 0 &&
      (st >= 0 || st == AUTOBAL_ECANCELLED || st == sum.solver.status)) {
    if (ctx->json) print_json(ctx, c, &sum, warn);
    else if (!ctx->quiet) print_text(ctx, c, &sum);
  }
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  autobal_study_rotor_transient_summary_free(&sum);
  free(c);
  return rc;
}
