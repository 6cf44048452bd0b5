/* cmd_rotor.c: `autobal rotor transient`: the rotor in a massive housing with one or two ball
 * autobalancers (docs/rotor.md), integrated in time, streamed to HDF5, summarised for a person. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/archive.h"
#include "autobal/rotor.h"
#include "autobal/transient.h"
#include "cli.h"
#include "units.h"

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
  /* [balance] */
  double grade; /* ISO 21940-11 grade to check, mm/s; NaN: none */
  const char *grade_text;
} rotor_cfg;

static int get_d(cli_ctx *ctx, const char *sec, const char *key, double *v) {
  return cli_get_double(ctx, sec, key, *v, v, NULL);
}
/* A quantity in SI unit `unit`; the value may carry a unit (cli_get_quantity). */
static int get_q(cli_ctx *ctx, const char *sec, const char *key, const char *unit, double *v) {
  return cli_get_quantity(ctx, sec, key, unit, *v, v, NULL);
}

/* ---- the rotor model's configuration keys, shared by every rotor command ---------------- */
/* One double of a parameter struct: its configuration section and key (= the field's name), its
 * SI unit and where it sits in the struct. */
typedef struct rotor_key {
  const char *section, *key, *unit;
  size_t offset;
} rotor_key;

#define HW(sec, f, u) {sec, #f, u, offsetof(autobal_rotor_hardware, f)}
/* autobal_rotor_hardware: the masses and inertias in [rotor], the supports in [supports] */
static const rotor_key k_hw_keys[] = {
    HW("rotor", M_k, "kg"),         HW("rotor", A_k, "kg m^2"),     HW("rotor", m_p, "kg"),
    HW("rotor", A_p, "kg m^2"),     HW("rotor", C_p, "kg m^2"),     HW("supports", l_L, "m"),
    HW("supports", l_R, "m"),       HW("supports", c_Lx, "N/m"),    HW("supports", c_Ly, "N/m"),
    HW("supports", c_Lz, "N/m"),    HW("supports", c_Rx, "N/m"),    HW("supports", c_Ry, "N/m"),
    HW("supports", h_Lx, "N s/m"),  HW("supports", h_Ly, "N s/m"),  HW("supports", h_Lz, "N s/m"),
    HW("supports", h_Rx, "N s/m"),  HW("supports", h_Ry, "N s/m")};
#undef HW
#define LU(f, u) {"lumped", #f, u, offsetof(autobal_rotor_lumped, f)}
/* autobal_rotor_lumped: [lumped] */
static const rotor_key k_lumped_keys[] = {
    LU(M, "kg"),         LU(A, "kg m^2"),     LU(C, "kg m^2"),      LU(c_x, "N/m"),      LU(c_y, "N/m"),
    LU(c_z, "N/m"),      LU(c_alpha, "N m"),  LU(c_beta, "N m"),    LU(c_xbeta, "N"),    LU(c_yalpha, "N"),
    LU(h_x, "N s/m"),    LU(h_y, "N s/m"),    LU(h_z, "N s/m"),     LU(h_alpha, "N m s"), LU(h_beta, "N m s"),
    LU(h_xbeta, "N s"),  LU(h_yalpha, "N s")};
#undef LU
#define N_HW_KEYS (sizeof k_hw_keys / sizeof k_hw_keys[0])
#define N_LUMPED_KEYS (sizeof k_lumped_keys / sizeof k_lumped_keys[0])

static double *key_field(void *base, const rotor_key *k) {
  return (double *)(void *)((char *)base + k->offset);
}
static double key_value(const void *base, const rotor_key *k) {
  return *(const double *)(const void *)((const char *)base + k->offset);
}

/* Read the keys of `section` from the table into the struct at base (the current values are the
 * defaults). */
static int read_keys(cli_ctx *ctx, const rotor_key *keys, size_t n, const char *section, void *base) {
  size_t i;
  int rc;
  for (i = 0; i < n; i++)
    if (!strcmp(keys[i].section, section) && (rc = get_q(ctx, section, keys[i].key, keys[i].unit, key_field(base, &keys[i]))))
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
  if ((rc = read_keys(ctx, k_hw_keys, N_HW_KEYS, "rotor", hw))) return rc;
  if ((rc = get_q(ctx, "rotor", "omega", "rad/s", &c->p.omega))) return rc;
  if ((rc = cli_get_string(ctx, "rotor", "inertia", inertia, &inertia, NULL))) return rc;
  if ((rc = cli_get_bool(ctx, "rotor", "axial", 0, &axial, NULL))) return rc;
  if (!strcmp(inertia, "paper")) c->p.inertia = AUTOBAL_ROTOR_INERTIA_PAPER;
  else if (!strcmp(inertia, "full")) c->p.inertia = AUTOBAL_ROTOR_INERTIA_FULL;
  else return cli_fail(ctx, CLI_EXIT_INPUT, "[rotor]: inertia = '%s' is not one of: paper, full", inertia);
  c->p.axial = axial;
  /* [supports] */
  if ((rc = read_keys(ctx, k_hw_keys, N_HW_KEYS, "supports", hw))) return rc;
  /* [lumped]: if present, the lumped coefficients are authoritative (all must be given) */
  if (cli_section_present(ctx, "lumped")) {
    for (i = 0; i < N_LUMPED_KEYS; i++) {
      int present;
      if ((rc = cli_get_quantity(ctx, "lumped", k_lumped_keys[i].key, k_lumped_keys[i].unit, 0.0,
                                 key_field(lu, &k_lumped_keys[i]), &present)))
        return rc;
      if (!present)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[lumped]: '%s' is missing (with a [lumped] section all of M, A, C, c_x, c_y, c_z, c_alpha, c_beta, c_xbeta, c_yalpha and the h_ analogues are required)", k_lumped_keys[i].key);
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
  autobal_rotor_lumped L;
  const char *g = "/rotor", *gl = "/rotor/lumped";
  char grp[64];
  size_t i, j;
  int st;
  /* the coefficients the model uses (autobal_rotor_alloc does the same) */
  if (p->input == AUTOBAL_ROTOR_HARDWARE) {
    if ((st = autobal_rotor_lumped_from_hardware(&p->hw, &L, NULL))) return st;
  } else {
    L = p->lumped;
  }
  st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "model", "rotor in a massive housing with ball autobalancers (docs/rotor.md)");
  if (!st) st = autobal_archive_attr_string(a, g, "input", p->input == AUTOBAL_ROTOR_LUMPED ? "lumped" : "hardware");
  if (!st) st = autobal_archive_attr_string(a, g, "inertia", p->inertia == AUTOBAL_ROTOR_INERTIA_FULL ? "full" : "paper");
  if (!st) st = autobal_archive_attr_double(a, g, "omega", p->omega, "rad/s");
  if (!st) st = autobal_archive_attr_int(a, g, "axial", p->axial);
  for (i = 0; p->input == AUTOBAL_ROTOR_HARDWARE && i < N_HW_KEYS && !st; i++)
    st = autobal_archive_attr_double(a, g, k_hw_keys[i].key, key_value(&p->hw, &k_hw_keys[i]), k_hw_keys[i].unit);
  if (!st) st = autobal_archive_group(a, gl);
  for (i = 0; i < N_LUMPED_KEYS && !st; i++)
    st = autobal_archive_attr_double(a, gl, k_lumped_keys[i].key, key_value(&L, &k_lumped_keys[i]), k_lumped_keys[i].unit);
  for (j = 0; j < p->n_planes && !st; j++) {
    const autobal_rotor_plane *pl = &p->plane[j];
    snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
    st = autobal_archive_group(a, grp);
    if (!st) st = autobal_archive_attr_double(a, grp, "d", pl->d, "m");
    if (!st) st = autobal_archive_attr_double(a, grp, "m0", pl->m0, "kg");
    if (!st) st = autobal_archive_attr_double(a, grp, "r0", pl->r0, "m");
    if (!st) st = autobal_archive_attr_double(a, grp, "psi0", pl->psi0, "rad");
    if (!st) st = autobal_archive_attr_int(a, grp, "n_balls", (long)pl->n_balls);
    if (!st && pl->n_balls > 0) {
      st = autobal_archive_attr_double_array(a, grp, "ball_mass", pl->n_balls, pl->ball_mass, "kg");
      if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_radius", pl->n_balls, pl->ball_radius, "m");
      if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_damping", pl->n_balls, pl->ball_damping, "kg/s");
      if (!st && initial && pl->ball_psi)
        st = autobal_archive_attr_double_array(a, grp, "ball_psi_initial", pl->n_balls, pl->ball_psi, "rad");
      if (!st && initial && pl->ball_rate)
        st = autobal_archive_attr_double_array(a, grp, "ball_rate_initial", pl->n_balls, pl->ball_rate, "rad/s");
    }
  }
  return st;
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
    for (k = 0; k < N_HW_KEYS; k++)
      if (strlen(k_hw_keys[k].key) == n && !strncmp(s + 3, k_hw_keys[k].key, n)) {
        snprintf(tmp, sizeof tmp, "%s.%s", k_hw_keys[k].section, k_hw_keys[k].key);
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

static int read_rotor_config(cli_ctx *ctx, rotor_cfg *c) {
  int rc;
  if ((rc = read_rotor_model(ctx, c))) return rc;
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
   * example's |s| at 600 revolutions, 1e-10/1e-9 leaves 2e-5 with 11% fewer rhs evaluations (README) */
  c->rtol = 1e-10;
  c->atol = 1e-9;
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
    if ((rc = get_q(ctx, "transient", "t_end", "s", &c->t_end))) return rc;
    if ((rc = cli_get_quantity(ctx, "transient", "dt_out", "s", 0.0, &c->dt_out, &has_dt))) return rc;
    if ((rc = cli_get_double(ctx, "transient", "revs_out", revs_out, &revs_out, &has_revs))) return rc;
    if ((rc = get_d(ctx, "transient", "rtol", &c->rtol))) return rc;
    if ((rc = get_d(ctx, "transient", "atol", &c->atol))) return rc;
    if ((rc = get_q(ctx, "transient", "h_max", "s", &c->h_max))) return rc;
    if ((rc = cli_get_int(ctx, "transient", "max_steps", c->max_steps, &c->max_steps, NULL))) return rc;
    if ((rc = cli_get_string(ctx, "transient", "stepper", c->stepper, &c->stepper, NULL))) return rc;
    if ((rc = cli_get_string(ctx, "transient", "frame", c->frame_name, &c->frame_name, NULL))) return rc;
    if ((rc = get_d(ctx, "transient", "balance_tol", &c->balance_tol))) return rc;
    if ((rc = cli_get_double(ctx, "transient", "balance_revs", c->balance_revs, &c->balance_revs, &has_brevs))) return rc;
    if ((rc = cli_get_quantity(ctx, "transient", "balance_dwell", "s", 0.0, &dwell, &has_dwell))) return rc;
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
  /* vibration in the last 10% of the run at the centre of mass (0) and the supports (1: left,
   * 2: right; NaN positions with lumped input): per direction x, y the largest synchronous (1X)
   * amplitude sqrt(u^2 + (u'/omega)^2) over the samples: the amplitude of the harmonic at the
   * running speed through (u, u') at each sample, exact for a steady whirl whatever the
   * sampling (a sampled maximum or RMS of 4 samples per revolution is not) */
  double l_sup[3], omega_abs;
  double amax[3][2];
  unsigned long win_n;
} run_ctx;

/* Displacement and velocity at axial position p (eq. (3.3) kinematics: (x + p beta, y - p alpha)). */
static void point_motion(const double y[], double p, double d[2], double v[2]) {
  d[0] = y[0] + p * y[3];
  d[1] = y[1] - p * y[2];
  v[0] = y[4] + p * y[7];
  v[1] = y[5] - p * y[6];
}

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
  if (t >= r->t_last_window_start) {
    size_t k, q;
    for (k = 0; k < 3; k++) {
      double d[2], v[2];
      point_motion(y, r->l_sup[k], d, v);
      for (q = 0; q < 2; q++) {
        double amp = hypot(d[q], v[q] / r->omega_abs);
        if (r->win_n == 0 || amp > r->amax[k][q]) r->amax[k][q] = amp;
      }
    }
    r->win_n++;
  }
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
  int st = cli_write_rotor_params(a, p, 1);
#define AD(obj, name, v, u) \
  if (!st) st = autobal_archive_attr_double(a, obj, name, v, u)
  if (!st) st = autobal_archive_group(a, "/rotor/transient");
  AD("/rotor/transient", "t_end", c->t_end, "s");
  AD("/rotor/transient", "dt_out", c->dt_out, "s");
  AD("/rotor/transient", "rtol", c->rtol, "1");
  AD("/rotor/transient", "atol", c->atol, "1");
  AD("/rotor/transient", "h_max", c->h_max, "s");
  AD("/rotor/transient", "max_steps", (double)c->max_steps, "1");
  /* components of different units: no single (CF) units attribute; they are named instead */
  if (!st) st = autobal_archive_attr_double_array(a, "/rotor/transient", "initial_q", 4, p->q0, NULL);
  if (!st)
    st = autobal_archive_attr_string(a, "/rotor/transient", "initial_q_components", "x (m), y (m), alpha (rad), beta (rad)");
  if (!st) st = autobal_archive_attr_double_array(a, "/rotor/transient", "initial_q_rate", 4, p->qd0, NULL);
  if (!st)
    st = autobal_archive_attr_string(a, "/rotor/transient", "initial_q_rate_components",
                                     "x_rate (m/s), y_rate (m/s), alpha_rate (rad/s), beta_rate (rad/s)");
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

/* ---- engineering quantities of the summary (docs/units.md) ------------------------------ */
typedef struct engineering_summary {
  double s_abs[AUTOBAL_ROTOR_MAX_PLANES]; /* |s_j| at the end, kg m */
  double mass;                            /* rotor mass for the grade, kg (m_p, or M with lumped input) */
  double grade;                           /* ISO 21940-11 grade reached at the end, mm/s */
  double permissible;                     /* of [balance] grade: U_per in kg m (whole rotor); NaN: none */
  int meets;                              /* every plane within U_per / n_planes */
  int have_window;                        /* samples in the last 10% */
  double pkpk[3], vrms[3];                /* centre of mass, left, right support: m, m/s (1X) */
  double vrms_support;                    /* the largest support RMS velocity (G when no supports), m/s */
} engineering_summary;

/* The smallest ISO 21940-11 grade class that G (mm/s) is within; NaN above G4000. */
static double grade_class(double G) {
  static const double k[] = {0.4, 1, 2.5, 6.3, 16, 40, 100, 250, 630, 1600, 4000};
  size_t i;
  for (i = 0; i < sizeof k / sizeof k[0]; i++)
    if (G <= k[i]) return k[i];
  return NAN;
}

static void engineering_compute(engineering_summary *e, const autobal_rotor *rot, const rotor_cfg *c,
                                const run_ctx *r, double t, const double *y) {
  size_t j, k, q, np = r->n_planes;
  double omega = fabs(c->p.omega), worst = 0.0;
  memset(e, 0, sizeof *e);
  e->mass = c->p.input == AUTOBAL_ROTOR_HARDWARE ? c->p.hw.m_p : c->p.lumped.M;
  for (j = 0; j < np; j++) {
    double s4[4];
    e->s_abs[j] = autobal_rotor_plane_unbalance(rot, j, c->frame, t, y, s4) == AUTOBAL_SUCCESS ? hypot(s4[0], s4[1])
                                                                                                : NAN;
    if (!(e->s_abs[j] <= worst)) worst = e->s_abs[j];
  }
  /* the rotor's mass shared equally by the planes (ISO 21940-11's allocation for a rotor with
   * its planes symmetric to the bearings): grade of the worst plane */
  e->grade = cli_balance_grade(worst * (double)np, e->mass, omega);
  e->permissible = isnan(c->grade) ? NAN : cli_permissible_unbalance(c->grade, e->mass, omega);
  e->meets = !isnan(e->permissible) && worst * (double)np <= e->permissible;
  e->have_window = r->win_n > 0;
  e->vrms_support = NAN;
  for (k = 0; k < 3; k++) {
    e->pkpk[k] = e->vrms[k] = NAN;
    if (!e->have_window || isnan(r->l_sup[k])) continue;
    for (q = 0; q < 2; q++) { /* harmonic: peak-to-peak 2 A, RMS velocity omega A / sqrt(2) */
      double pp = 2.0 * r->amax[k][q], v = omega * r->amax[k][q] / sqrt(2.0);
      if (!(pp <= e->pkpk[k])) e->pkpk[k] = pp;
      if (!(v <= e->vrms[k])) e->vrms[k] = v;
    }
    if (k > 0 && !(e->vrms[k] <= e->vrms_support)) e->vrms_support = e->vrms[k];
  }
  if (isnan(e->vrms_support)) e->vrms_support = e->vrms[0];
}

static int engineering_write(autobal_archive *a, const char *g, const engineering_summary *e, size_t np) {
  int st = autobal_archive_attr_double_array(a, g, "residual_unbalance_abs_final", np, e->s_abs, "kg m");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_grade_final", e->grade, "mm/s");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_grade_rotor_mass", e->mass, "kg");
  if (!st && !isnan(e->permissible)) {
    st = autobal_archive_attr_double(a, g, "permissible_unbalance", e->permissible, "kg m");
    if (!st) st = autobal_archive_attr_int(a, g, "permissible_unbalance_met", e->meets);
  }
  if (!st) st = autobal_archive_attr_double(a, g, "displacement_pk_pk_G_last_10pct", e->pkpk[0], "m");
  if (!st) st = autobal_archive_attr_double(a, g, "velocity_rms_G_last_10pct", e->vrms[0], "m/s");
  if (!st) st = autobal_archive_attr_double(a, g, "velocity_rms_left_support_last_10pct", e->vrms[1], "m/s");
  if (!st) st = autobal_archive_attr_double(a, g, "velocity_rms_right_support_last_10pct", e->vrms[2], "m/s");
  return st;
}

static void engineering_json(cli_json *j, const engineering_summary *e, size_t np) {
  cli_json_quantities(j, "residual_unbalance_abs_final", e->s_abs, np, "kg m");
  cli_json_quantity(j, "balance_grade_final", e->grade, "mm/s");
  cli_json_quantity(j, "balance_grade_rotor_mass", e->mass, "kg");
  if (!isnan(e->permissible)) {
    cli_json_quantity(j, "permissible_unbalance", e->permissible, "kg m");
    cli_json_bool(j, "permissible_unbalance_met", e->meets);
  }
  cli_json_quantity(j, "displacement_pk_pk_G_last_10pct", e->pkpk[0], "m");
  cli_json_quantity(j, "velocity_rms_supports_last_10pct", e->vrms_support, "m/s");
}

static void engineering_print(const engineering_summary *e, const rotor_cfg *c) {
  double cls = grade_class(e->grade), rpm = cli_rpm(fabs(c->p.omega));
  char cbuf[32] = "above G4000";
  if (!isnan(cls)) snprintf(cbuf, sizeof cbuf, "within G%g", cls);
  printf("  balance quality at the end: G %.3g mm/s, %s (ISO 21940-11: G = e omega, e = U/m with rotor mass %s = %g kg%s)\n",
         e->grade, cbuf, c->p.input == AUTOBAL_ROTOR_HARDWARE ? "m_p" : "M", e->mass,
         c->p.n_planes > 1 ? " shared equally by the planes" : "");
  if (!isnan(e->permissible))
    printf("  grade G%g permits %.4g g mm at %.1f rpm%s: %s\n", c->grade, e->permissible * 1e6, rpm,
           c->p.n_planes > 1 ? " (half per plane)" : "", e->meets ? "MET" : "NOT met");
  if (e->have_window)
    printf("  vibration at the running speed (1X) in the last 10%% of the run: centre of mass %.4g um 0-peak, %.4g um "
           "peak-to-peak (largest of x, y); velocity %.4g mm/s RMS %s\n",
           e->pkpk[0] * 0.5e6, e->pkpk[0] * 1e6, e->vrms_support * 1e3,
           isnan(e->vrms[1]) ? "at the centre of mass" : "at the supports (ISO 20816 measure: largest of left/right, x/y)");
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
  char msg[sizeof ctx->err];
  double *y = NULL, t_reached = 0, *psi_bal[AUTOBAL_ROTOR_MAX_PLANES] = {NULL}, s_final = NAN, ttb = NAN;
  engineering_summary eng;
  int rc = CLI_EXIT_OK, st, warn = 0, balanced = 0, ev = -1;
  size_t j;

  memset(&r, 0, sizeof r);
  autobal_error_clear(&err);
  if (!c) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  if ((rc = read_rotor_config(ctx, c))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  rot = autobal_rotor_alloc(&c->p, &err);
  if (!rot) {
    rc = cli_fail(ctx, cli_exit_code(err.status), "%s", cli_rotor_message(err.message, msg, sizeof msg));
    goto done;
  }
  if (err.status == AUTOBAL_WARNING) {
    warn = 1;
    if (!ctx->json) fprintf(stderr, "autobal: warning: %s\n",
        cli_rotor_message(err.message, msg, sizeof msg));
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
  r.l_sup[0] = 0.0;
  r.omega_abs = fabs(c->p.omega);
  r.l_sup[1] = c->p.input == AUTOBAL_ROTOR_HARDWARE ? -c->p.hw.l_L : NAN;
  r.l_sup[2] = c->p.input == AUTOBAL_ROTOR_HARDWARE ? c->p.hw.l_R : NAN;
  r.row = calloc(r.ncols, sizeof *r.row);
  r.rev_max_D = calloc(r.n_planes, sizeof *r.rev_max_D);
  r.rev_row = calloc(2 + r.n_planes, sizeof *r.rev_row);
  y = calloc(r.dim, sizeof *y);
  if (!r.row || !r.rev_max_D || !r.rev_row || !y) {
    rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
    goto done;
  }
  if ((st = autobal_rotor_initial_state(rot, c->frame, 0.0, y, r.dim))) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s",
        cli_rotor_message(autobal_rotor_errmsg(rot), msg, sizeof msg));
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
  engineering_compute(&eng, rot, c, &r, t_reached, y);
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
      psi_bal[j] = pb;
      pb = NULL;
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
    if (!st) st = engineering_write(a, g, &eng, r.n_planes);
    if (!st) st = cli_archive_solver_stats(a, "/rotor/transient/solver", tr, &stats, "s");
    rc = cli_archive_end(ctx, &a, st, rc);
  }
finish:
  if (a) rc = cli_archive_end(ctx, &a, AUTOBAL_SUCCESS, rc);
  if (rc == CLI_EXIT_OK || rc == CLI_EXIT_NUMERIC || rc == CLI_EXIT_INTERRUPTED) {
    double s0 = c->p.plane[0].m0 * c->p.plane[0].r0;
    if (ctx->json) {
      cli_json jj;
      cli_json_summary_begin(&jj, ctx);
      cli_json_bool(&jj, "balanced", balanced);
      cli_json_quantity(&jj, "time_to_balance", ttb, "s");
      cli_json_quantity(&jj, "t_reached", t_reached, "s");
      cli_json_quantity(&jj, "residual_unbalance_initial", r.s_rel_initial, "1");
      cli_json_quantity(&jj, "residual_unbalance_final", s_final, "1");
      cli_json_quantity(&jj, "amplitude_first_10pct_max", r.amp_first, "m");
      cli_json_quantity(&jj, "amplitude_last_10pct_max", r.amp_last, "m");
      engineering_json(&jj, &eng, r.n_planes);
      /* every plane: residual unbalance, ball angles relative to the rotor at the end, the
       * balanced configuration (3.14) when it exists */
      cli_json_array(&jj, "planes");
      for (j = 0; j < r.n_planes; j++) {
        size_t i, nbj = c->p.plane[j].n_balls;
        double s0j = c->p.plane[j].m0 * c->p.plane[j].r0;
        cli_json_object(&jj, NULL);
        cli_json_int(&jj, "plane", (long)j + 1);
        cli_json_number(&jj, "residual_unbalance_abs", eng.s_abs[j]);
        cli_json_number(&jj, "residual_unbalance_rel", s0j > 0 ? eng.s_abs[j] / s0j : NAN);
        cli_json_array(&jj, "ball_psi_final");
        for (i = 0; i < nbj; i++) {
          size_t k = autobal_rotor_ball_index(rot, j, i);
          double ang = c->frame == AUTOBAL_ROTOR_FIXED ? y[8 + k] - c->p.omega * t_reached : y[8 + k];
          cli_json_number(&jj, NULL, remainder(ang, TWO_PI));
        }
        cli_json_array_end(&jj);
        if (psi_bal[j]) cli_json_numbers(&jj, "ball_psi_balanced", psi_bal[j], nbj);
        cli_json_object(&jj, "units");
        cli_json_string(&jj, "residual_unbalance_abs", "kg m");
        cli_json_string(&jj, "residual_unbalance_rel", "1");
        cli_json_string(&jj, "ball_psi_final", "rad");
        cli_json_string(&jj, "ball_psi_balanced", "rad");
        cli_json_object_end(&jj);
        cli_json_object_end(&jj);
      }
      cli_json_array_end(&jj);
      cli_json_int(&jj, "steps", (long)stats.steps);
      cli_json_int(&jj, "rhs_evaluations", (long)stats.rhs_evals);
      cli_json_quantity(&jj, "wall_time", stats.wall_seconds, "s");
      cli_json_bool(&jj, "warning", warn);
      cli_json_summary_end(&jj, ctx);
    } else if (!ctx->quiet) {
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
      for (j = 0; j < r.n_planes; j++) {
        size_t i, nbj = c->p.plane[j].n_balls;
        printf("  plane %zu: residual unbalance %.4g g mm at the end (its unbalance m0 r0 = %.4g g mm)\n", j + 1,
               eng.s_abs[j] * 1e6, c->p.plane[j].m0 * c->p.plane[j].r0 * 1e6);
        if (nbj == 0) continue;
        printf("  plane %zu ball angles relative to the rotor at the end (rad, wrapped):", j + 1);
        for (i = 0; i < nbj && i < 8; i++) {
          size_t k = autobal_rotor_ball_index(rot, j, i);
          double ang = c->frame == AUTOBAL_ROTOR_FIXED ? y[8 + k] - c->p.omega * t_reached : y[8 + k];
          ang = remainder(ang, TWO_PI);
          printf(" %.5f", ang);
        }
        printf("%s\n", nbj > 8 ? " ..." : "");
        if (psi_bal[j]) {
          printf("  balanced configuration (3.14) of plane %zu:", j + 1);
          for (i = 0; i < nbj && i < 8; i++) printf(" %.5f", psi_bal[j][i]);
          printf("%s\n", nbj > 8 ? " ..." : "");
        }
      }
      engineering_print(&eng, c);
      cli_print_solver_stats(tr, &stats);
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
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++) free(psi_bal[j]);
  free(c);
  return rc;
}
