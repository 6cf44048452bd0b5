/* cmd_ensemble.c: `autobal rotor ensemble` and `autobal pendulum ensemble`: the configuration
 * becomes an autobal_ensemble_settings and a ready-made member (autobal_ensemble_rotor_member /
 * autobal_ensemble_pendulum_member); the library's ensemble engine (include/autobal/ensemble.h)
 * runs it, keeps the journals, and writes /<model>/ensemble; this file prints the summary.
 *
 * What stays here: the [ensemble] and [transient] keys and their messages; the --resume/--force
 * rules for journals and an existing archive; the journal's identity (an FNV-1a hash of the sorted
 * configuration without the run-control keys threads/resume/max_members/time_limit and the
 * statistics keys target_grade/target_unbalance/write_unbalance/write_attractors, which change no member's result,
 * so that a resume may change them); SIGINT as the
 * engine's cancel hook; the progress bar; and the MPI layer.
 *
 * MPI (build option AUTOBAL_MPI, code under AUTOBAL_HAVE_MPI), through the engine's
 * autobal_ensemble_parallel hooks: the members still to do are dealt out cyclically (member k of
 * the to-do list to rank k mod size: balanced chunks even when the cost varies smoothly over a
 * map); at the end every rank sends its records to rank 0, the only process that touches HDF5,
 * and rank 0 writes one ordinary archive.  Why not parallel HDF5 or one file per rank joined by a
 * virtual dataset: Debian's HDF5 is the serial build; a member's summary is ~20 numbers, so
 * gathering even 10^6 members costs a few hundred MB of messages at most; and one self-contained
 * file is byte-for-byte the archive of a serial run.  Every rank writes its own journal
 * FILE.h5.journal-<rank>; a resume reads them all, whatever the number of ranks that wrote them. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#ifdef AUTOBAL_HAVE_MPI
#include <mpi.h>
#endif

#include "autobal/archive.h"
#include "autobal/ensemble.h"
#include "autobal/pendulum.h"
#include "autobal/rotor.h"
#include "autobal/study.h"
#include "autobal/transient.h"
#include "cli.h"
#include "units.h"

#define PI 3.1415926535897932384626433832795
#define NP AUTOBAL_ENSEMBLE_MAX_PARAMS

enum { MODEL_ROTOR = 0, MODEL_PENDULUM = 1 };

typedef struct ens_spec {
  int model;
  const char *mname;        /* "rotor" / "pendulum" */
  autobal_ensemble_settings set;
  char pname[NP][32];
  size_t series[AUTOBAL_ENSEMBLE_MAX_SERIES];
  int resume;
  const char *frame_name;
  autobal_rotor_params rp;
  void *rstorage;
  autobal_pendulum_params pp;
  autobal_pendulum_physical phys;
  int physical;
  double y0[8];
  autobal_ensemble_member mb;
  /* rotor: the residual unbalance's targets ([ensemble] target_grade, target_unbalance) */
  double target_grade;      /* mm/s; NaN: none */
  double target_unbalance;  /* kg m, the whole rotor's permissible residual unbalance; NaN: none */
  const char *target_grade_text;
} ens_spec;

/* ---- configuration ------------------------------------------------------------------------- */
static int read_transient(cli_ctx *ctx, ens_spec *s) {
  autobal_ensemble_settings *t = &s->set;
  int rc, has_dt = 0, has_revs = 0, has_brevs = 0, has_dwell = 0;
  const int rotor = s->model == MODEL_ROTOR;
  const char *tu = rotor ? "s" : "1";
  long max_steps = 100000000L;
  t->t_end = rotor ? 20.0 : 300.0;
  t->transient.rtol = 1e-10; /* rotor: the defaults of `rotor transient` (apps/cmd_rotor.c) */
  t->transient.atol = rotor ? 1e-9 : 1e-12;
  t->transient.h_max = 0.0;
  t->balance_tol = rotor ? 0.01 : 1e-3;
  t->balance_revs = rotor ? 50.0 : 20.0;
  t->revs_out = 0.25;
  t->transient.stepper = "rk8pd";
  s->frame_name = "fixed";
  if ((rc = cli_get_quantity(ctx, "transient", "t_end", tu, t->t_end, &t->t_end, NULL))) return rc;
  if ((rc = cli_get_quantity(ctx, "transient", "dt_out", tu, 0.0, &t->dt_out, &has_dt))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "revs_out", t->revs_out, &t->revs_out, &has_revs))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "rtol", t->transient.rtol, &t->transient.rtol, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "atol", t->transient.atol, &t->transient.atol, NULL))) return rc;
  if ((rc = cli_get_quantity(ctx, "transient", "h_max", tu, t->transient.h_max, &t->transient.h_max, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "transient", "max_steps", max_steps, &max_steps, NULL))) return rc;
  if ((rc = cli_get_string(ctx, "transient", "stepper", t->transient.stepper, &t->transient.stepper, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "balance_tol", t->balance_tol, &t->balance_tol, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "balance_revs", t->balance_revs, &t->balance_revs, &has_brevs))) return rc;
  if ((rc = cli_get_bool(ctx, "transient", "stop_at_balance", 1, &t->stop_at_balance, NULL))) return rc;
  if (rotor) {
    if ((rc = cli_get_quantity(ctx, "transient", "balance_dwell", tu, 0.0, &t->balance_dwell, &has_dwell))) return rc;
    if ((rc = cli_get_string(ctx, "transient", "frame", s->frame_name, &s->frame_name, NULL))) return rc;
    if (strcmp(s->frame_name, "fixed") && strcmp(s->frame_name, "rotating"))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: frame = '%s' is not one of: fixed, rotating", s->frame_name);
  }
  if (has_dt && has_revs) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give dt_out or revs_out, not both");
  if (has_brevs && has_dwell)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give balance_revs (revolutions) or balance_dwell (s), not both");
  t->use_revs_out = !has_dt;
  t->use_dwell = has_dwell;
  if (!(t->t_end > 0 && isfinite(t->t_end)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: t_end = %g is out of range: allowed (0, inf)", t->t_end);
  if (t->use_revs_out && !(t->revs_out > 0 && isfinite(t->revs_out)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: revs_out = %g is out of range: allowed (0, inf)", t->revs_out);
  if (!t->use_revs_out && !(t->dt_out > 0 && isfinite(t->dt_out)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: dt_out = %g is out of range: allowed (0, inf)", t->dt_out);
  if (!(t->balance_tol > 0 && isfinite(t->balance_tol)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_tol = %g is out of range: allowed (0, inf)", t->balance_tol);
  if (!(t->balance_revs >= 0 && isfinite(t->balance_revs)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_revs = %g is out of range: allowed [0, inf)", t->balance_revs);
  if (has_dwell && !(t->balance_dwell >= 0 && isfinite(t->balance_dwell)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_dwell = %g s is out of range: allowed [0, inf)", t->balance_dwell);
  if (max_steps < 1)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: max_steps = %ld is out of range: allowed [1, inf)", max_steps);
  t->transient.max_steps = (unsigned long)max_steps;
  {
    autobal_error err;
    autobal_error_clear(&err);
    if (autobal_transient_options_validate(&t->transient, &err) != AUTOBAL_SUCCESS)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: %s", err.message);
  }
  return CLI_EXIT_OK;
}

/* [ensemble] attractor_window_revs, attractor_rest_tol (rad), attractor_min_turns,
 * attractor_rate_tol, attractor_envelope_tol: the thresholds of the attractor classification
 * (include/autobal/attractor.h; checked here so that the message names the key); write_attractors
 * (default true: the per-member attractor, circulation_frequency, natural_frequency). */
static int read_attractor_keys(cli_ctx *ctx, ens_spec *s) {
  autobal_attractor_options *o = &s->set.attractor;
  autobal_error err;
  int rc;
  *o = autobal_attractor_options_default();
  if ((rc = cli_get_double(ctx, "ensemble", "attractor_window_revs", o->window_revs, &o->window_revs, NULL))) return rc;
  if ((rc = cli_get_quantity(ctx, "ensemble", "attractor_rest_tol", "rad", o->rest_tol, &o->rest_tol, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "ensemble", "attractor_min_turns", o->min_turns, &o->min_turns, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "ensemble", "attractor_rate_tol", o->rate_tol, &o->rate_tol, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "ensemble", "attractor_envelope_tol", o->envelope_tol, &o->envelope_tol, NULL))) return rc;
  if ((rc = cli_get_bool(ctx, "ensemble", "write_attractors", 1, &s->set.write_attractors, NULL))) return rc;
  autobal_error_clear(&err);
  if (autobal_attractor_options_check(o, &err) != AUTOBAL_SUCCESS) return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s", err.message);
  return CLI_EXIT_OK;
}

/* [ensemble] target_grade = G6.3 (P(G <= 6.3 mm/s) at the end), target_unbalance = 50 g mm (the
 * whole rotor's permissible residual unbalance: with two planes each plane's |s_j| against half of
 * it, as `rotor transient` checks [balance] grade), write_unbalance = true (the per-member
 * datasets; off by default so that a configuration of 0.1.0 writes its datasets of 0.1.0). */
static int read_unbalance_targets(cli_ctx *ctx, ens_spec *s) {
  autobal_ensemble_settings *t = &s->set;
  int rc, has_u = 0;
  s->target_grade = s->target_unbalance = NAN;
  s->target_grade_text = NULL;
  if ((rc = cli_get_string(ctx, "ensemble", "target_grade", NULL, &s->target_grade_text, NULL))) return rc;
  if (s->target_grade_text && cli_parse_grade(s->target_grade_text, &s->target_grade) != 0)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[ensemble]: target_grade = '%s' is not a balance quality grade: write G followed by a positive number "
                    "in mm/s, or the number with mm/s (ISO 21940-11 grades: G0.4, G1, G2.5, G6.3, G16, G40, ...); allowed (0, inf) mm/s",
                    s->target_grade_text);
  if ((rc = cli_get_quantity(ctx, "ensemble", "target_unbalance", "kg m", NAN, &s->target_unbalance, &has_u))) return rc;
  if (has_u && !(s->target_unbalance > 0 && isfinite(s->target_unbalance)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: target_unbalance = %g g mm is out of range: allowed (0, inf) (e.g. 50 g mm)",
                    s->target_unbalance * 1e6);
  if ((rc = cli_get_bool(ctx, "ensemble", "write_unbalance", 0, &t->write_quantities, NULL))) return rc;
  if ((rc = read_attractor_keys(ctx, s))) return rc;
  t->n_targets = 0;
  if (!isnan(s->target_grade)) {
    t->target[t->n_targets].quantity = "balance_grade_final";
    t->target[t->n_targets++].limit = s->target_grade;
  }
  if (has_u) {
    t->target[t->n_targets].quantity = "residual_unbalance_abs_final";
    t->target[t->n_targets++].limit = s->target_unbalance / (double)s->rp.n_planes;
  }
  return CLI_EXIT_OK;
}

static int read_ensemble(cli_ctx *ctx, ens_spec *s) {
  static const char *const pk[NP] = {"param1", "param2", "param3"};
  static const char *const mink[NP] = {"min1", "min2", "min3"};
  static const char *const maxk[NP] = {"max1", "max2", "max3"};
  static const char *const nk[NP] = {"n1", "n2", "n3"};
  autobal_ensemble_settings *t = &s->set;
  const char *mode = "grid", *defname[NP], *names[NP];
  long samples = 256, seed = 1, threads = 0, max_members = 0;
  int rc, has_samples = 0, has_seed = 0, has_endpoint = 0, all_angles = 1;
  size_t j, nser = 0;
  double ser[AUTOBAL_ENSEMBLE_MAX_SERIES + 1];
  autobal_error err;
  autobal_error_clear(&err);
  if (s->model == MODEL_ROTOR) {
    size_t nb = s->mb.n_angles;
    defname[0] = nb >= 1 ? "psi_1" : "omega";
    defname[1] = nb >= 2 ? "psi_2" : "none";
  } else {
    defname[0] = "psi";
    defname[1] = "phi";
  }
  defname[2] = "none";
  if ((rc = cli_get_string(ctx, "ensemble", "mode", mode, &mode, NULL))) return rc;
  if (!strcmp(mode, "grid")) t->random = 0;
  else if (!strcmp(mode, "random")) t->random = 1;
  else return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: mode = '%s' is not one of: grid, random", mode);
  t->n_params = 0;
  for (j = 0; j < NP; j++) {
    const char *name = defname[j];
    int has_name, has_min, has_max, has_n;
    long n = 16;
    autobal_ensemble_param *p = &t->param[t->n_params];
    autobal_ensemble_param_info info;
    size_t i;
    if ((rc = cli_get_string(ctx, "ensemble", pk[j], name, &name, &has_name))) return rc;
    if (!strcmp(name, "none") || !name[0]) {
      /* the keys of an unused axis must not be given */
      int a, b, c;
      double dd;
      long nn;
      if ((rc = cli_get_double(ctx, "ensemble", mink[j], 0, &dd, &a))) return rc;
      if ((rc = cli_get_double(ctx, "ensemble", maxk[j], 0, &dd, &b))) return rc;
      if ((rc = cli_get_int(ctx, "ensemble", nk[j], 0, &nn, &c))) return rc;
      if (a || b || c)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s/%s/%s are given but %s is none", mink[j], maxk[j], nk[j], pk[j]);
      continue;
    }
    if (j > t->n_params)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s is given but %s is none (fill the axes in order)", pk[j], pk[j - 1]);
    if (strlen(name) >= sizeof s->pname[0] || s->mb.describe(s->mb.model, name, &info, &err) != AUTOBAL_SUCCESS)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %s", pk[j], err.message[0] ? err.message : name);
    for (i = 0; i < t->n_params; i++)
      if (!strcmp(s->pname[i], name)) return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %s is already %s", pk[j], name, pk[i]);
    snprintf(s->pname[t->n_params], sizeof s->pname[0], "%s", name);
    for (i = 0; i <= t->n_params; i++) names[i] = s->pname[i];
    if (s->mb.check && s->mb.check(s->mb.model, names, t->n_params + 1, &err) != AUTOBAL_SUCCESS)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s", err.message);
    p->name = s->pname[t->n_params];
    p->min = info.periodic ? -PI : 0.0;
    p->max = info.periodic ? PI : 0.0;
    if ((rc = cli_get_double(ctx, "ensemble", mink[j], p->min, &p->min, &has_min))) return rc;
    if ((rc = cli_get_double(ctx, "ensemble", maxk[j], p->max, &p->max, &has_max))) return rc;
    if ((rc = cli_get_int(ctx, "ensemble", nk[j], n, &n, &has_n))) return rc;
    if (!info.periodic && (!has_min || !has_max))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %s needs %s and %s (only angles have a default range [-pi, pi])",
                      pk[j], name, mink[j], maxk[j]);
    if (!(isfinite(p->min) && isfinite(p->max) && p->min <= p->max))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %g, %s = %g: need finite %s <= %s", mink[j], p->min, maxk[j], p->max,
                      mink[j], maxk[j]);
    if (t->random && has_n)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s is for mode = grid; mode = random draws `samples` members", nk[j]);
    if (n < 1 || n > 100000)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %ld is out of range: allowed [1, 100000]", nk[j], n);
    p->n = (size_t)n;
    if (!info.periodic) all_angles = 0;
    t->n_params++;
  }
  if (t->n_params == 0) return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: param1 is none: nothing varies");
  if ((rc = cli_get_int(ctx, "ensemble", "samples", samples, &samples, &has_samples))) return rc;
  if ((rc = cli_get_int(ctx, "ensemble", "seed", seed, &seed, &has_seed))) return rc;
  if (!t->random && (has_samples || has_seed))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: samples and seed are for mode = random");
  if (seed < 0) return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: seed = %ld is out of range: allowed [0, 2^63)", seed);
  t->seed = (uint64_t)seed;
  /* periodic angles: n points over [min, max) by default, else both ends */
  if ((rc = cli_get_bool(ctx, "ensemble", "endpoint", !all_angles, &t->endpoint, &has_endpoint))) return rc;
  if (t->random && has_endpoint) return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: endpoint is for mode = grid");
  if (t->random && (samples < 1 || (unsigned long)samples > AUTOBAL_ENSEMBLE_MAX_MEMBERS))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: samples = %ld is out of range: allowed [1, %lu]", samples,
                    AUTOBAL_ENSEMBLE_MAX_MEMBERS);
  t->samples = (size_t)samples;
  if ((rc = cli_get_doubles(ctx, "ensemble", "series", ser, AUTOBAL_ENSEMBLE_MAX_SERIES + 1, &nser, NULL))) return rc;
  if (nser > AUTOBAL_ENSEMBLE_MAX_SERIES)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: series lists more than %d members", AUTOBAL_ENSEMBLE_MAX_SERIES);
  for (j = 0; j < nser; j++) {
    if (!(ser[j] >= 0 && ser[j] < 0x1p53 && ser[j] == floor(ser[j])))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: series = ... %g ...: members are numbered 0, 1, ...", ser[j]);
    s->series[j] = (size_t)ser[j];
  }
  t->series = s->series;
  t->n_series = nser;
  if ((rc = cli_get_int(ctx, "ensemble", "threads", 0, &threads, NULL))) return rc;
  if (threads < 0 || threads > 1024)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: threads = %ld is out of range: allowed [0, 1024] (0: OpenMP default)", threads);
  t->threads = (int)threads;
  if ((rc = cli_get_bool(ctx, "ensemble", "resume", 0, &s->resume, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "ensemble", "max_members", 0, &max_members, NULL))) return rc;
  if (max_members < 0)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: max_members = %ld is out of range: allowed [0, inf) (0: all)", max_members);
  t->max_members = (size_t)max_members;
  if ((rc = cli_get_double(ctx, "ensemble", "time_limit", 0.0, &t->time_limit, NULL))) return rc;
  if (!(t->time_limit >= 0 && isfinite(t->time_limit)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: time_limit = %g s is out of range: allowed [0, inf) (0: none)", t->time_limit);
  if (s->model == MODEL_ROTOR) return read_unbalance_targets(ctx, s);
  return CLI_EXIT_OK;
}

/* FNV-1a over the sorted effective configuration minus the run-control keys: the journals'
 * identity (autobal_ensemble_settings.identity). */
static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static uint64_t fnv1a(uint64_t h, const char *s, size_t n) {
  size_t i;
  for (i = 0; i < n; i++) {
    h ^= (unsigned char)s[i];
    h *= UINT64_C(0x100000001B3);
  }
  return h;
}

static int config_hash(const cli_ctx *ctx, const ens_spec *s, uint64_t *out) {
  char *ini = cli_config_to_ini(ctx->cfg), *p, *line, **lines = NULL;
  char sec[128] = "";
  size_t n = 0, cap = 0, i;
  uint64_t h = UINT64_C(0xCBF29CE484222325);
  if (!ini) return AUTOBAL_ENOMEM;
  for (p = ini; *p; p = line) {
    char *nl = strchr(p, '\n'), *eq;
    line = nl ? nl + 1 : p + strlen(p);
    if (nl) *nl = '\0';
    if (p[0] == '[') {
      snprintf(sec, sizeof sec, "%s", p);
      continue;
    }
    eq = strstr(p, " = ");
    if (!strcmp(sec, "[ensemble]") && eq &&
        (!strncmp(p, "threads ", 8) || !strncmp(p, "resume ", 7) || !strncmp(p, "max_members ", 12) ||
         !strncmp(p, "time_limit ", 11) || !strncmp(p, "target_grade ", 13) || !strncmp(p, "target_unbalance ", 17) ||
         !strncmp(p, "write_unbalance ", 16) || !strncmp(p, "write_attractors ", 17)))
      continue;
    if (n == cap) {
      char **nlines = realloc(lines, (cap = cap ? 2 * cap : 64) * sizeof *lines);
      if (!nlines) goto nomem;
      lines = nlines;
    }
    if (!(lines[n] = malloc(strlen(sec) + strlen(p) + 2))) goto nomem;
    sprintf(lines[n], "%s%s", sec, p);
    n++;
  }
  if (n > 1) qsort(lines, n, sizeof *lines, cmp_str);
  h = fnv1a(h, s->mname, strlen(s->mname) + 1);
  for (i = 0; i < n; i++) {
    h = fnv1a(h, lines[i], strlen(lines[i]) + 1);
    free(lines[i]);
  }
  free(lines);
  free(ini);
  *out = h;
  return AUTOBAL_SUCCESS;
nomem:
  for (i = 0; i < n; i++) free(lines[i]);
  free(lines);
  free(ini);
  return AUTOBAL_ENOMEM;
}

static int read_pendulum_initial(cli_ctx *ctx, ens_spec *s) {
  static const char *const ikeys[8] = {"xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate"};
  int i, rc;
  for (i = 0; i < 8; i++) {
    s->y0[i] = 0.0;
    if ((rc = cli_get_double(ctx, "initial", ikeys[i], 0.0, &s->y0[i], NULL))) return rc;
    if (!isfinite(s->y0[i])) return cli_fail(ctx, CLI_EXIT_INPUT, "[initial]: %s must be finite", ikeys[i]);
  }
  return CLI_EXIT_OK;
}

/* The model's parameters, the member, [transient], [ensemble]. */
static int read_spec(cli_ctx *ctx, ens_spec *s) {
  int rc;
  autobal_error err;
  autobal_error_clear(&err);
  if (s->model == MODEL_ROTOR) {
    if ((rc = cli_rotor_config_read(ctx, &s->rp, &s->rstorage))) return rc;
    /* [drive]: the prescribed speed of every member, as `rotor transient` reads it */
    if ((rc = cli_rotor_drive_read(ctx, &s->rp, s->rstorage))) return rc;
    /* [friction], ball_f, ball_mu: the balls' rolling resistance and stiction, as `rotor transient` */
    if ((rc = cli_rotor_friction_read(ctx, &s->rp, s->rstorage))) return rc;
    /* [plane1]/[plane2] ball_diameter, [contact] restitution, v_rest: ball size and contact, as `rotor transient` */
    if ((rc = cli_rotor_contact_read(ctx, &s->rp, s->rstorage))) return rc;
    if ((rc = read_transient(ctx, s))) return rc;
    if (autobal_ensemble_rotor_member(&s->rp, strcmp(s->frame_name, "fixed") ? AUTOBAL_ROTOR_ROTATING : AUTOBAL_ROTOR_FIXED,
                                      s->frame_name, &s->mb, &err) != AUTOBAL_SUCCESS) {
      char msg[sizeof ctx->err];
      return cli_fail(ctx, cli_exit_code(err.status), "%s", cli_rotor_message(err.message, msg, sizeof msg));
    }
  } else {
    if ((rc = cli_read_pendulum_params(ctx, &s->pp, &s->phys, &s->physical))) return rc;
    if ((rc = read_pendulum_initial(ctx, s))) return rc;
    if (autobal_ensemble_pendulum_member(&s->pp, s->y0, &s->mb, &err) != AUTOBAL_SUCCESS)
      return cli_fail(ctx, cli_exit_code(err.status), "[pendulum]: %s", err.message);
    if ((rc = read_transient(ctx, s))) return rc;
    if ((rc = read_attractor_keys(ctx, s))) return rc;
  }
  return read_ensemble(ctx, s);
}

/* ---- MPI: the engine's dealing and gathering hooks ------------------------------------------ */
typedef struct ens_mpi {
  int rank, size, inited_here;
  cli_ctx *ctx;
  size_t computed;   /* members computed now, all ranks */
  int other_failed;  /* another rank's failure stopped the run */
} ens_mpi;

static void mpi_begin(ens_mpi *mp) {
  memset(mp, 0, sizeof *mp);
  mp->size = 1;
#ifdef AUTOBAL_HAVE_MPI
  {
    int flag = 0, provided;
    MPI_Initialized(&flag);
    if (!flag) {
      MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided);
      mp->inited_here = 1;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &mp->rank);
    MPI_Comm_size(MPI_COMM_WORLD, &mp->size);
  }
#endif
}

static void mpi_end(ens_mpi *mp) {
#ifdef AUTOBAL_HAVE_MPI
  if (mp->inited_here) MPI_Finalize();
#endif
  (void)mp;
}

/* All ranks agree on a failure: the largest exit code wins. */
static int mpi_agree(cli_ctx *ctx, const ens_mpi *mp, int rc) {
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) {
    int all = rc;
    MPI_Allreduce(&rc, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (all != CLI_EXIT_OK && rc == CLI_EXIT_OK) rc = cli_fail(ctx, all, "stopped: another MPI rank failed (see its message)");
    return all;
  }
#endif
  (void)ctx;
  (void)mp;
  return rc;
}

/* Member k of the to-do list runs on rank k mod size. */
static int mpi_mine(void *user, size_t k, size_t member) {
  const ens_mpi *mp = user;
  (void)member;
  return k % (size_t)mp->size == (size_t)mp->rank;
}

#ifdef AUTOBAL_HAVE_MPI
#define ENS_CHUNK (1 << 24) /* doubles per message */

/* Wait for every rank without spinning: a rank that finished its share early sleeps instead of
 * burning the core that a rank still computing (or its OpenMP threads) may share. */
static void mpi_idle_barrier(void) {
  MPI_Request rq;
  int flag = 0;
  MPI_Ibarrier(MPI_COMM_WORLD, &rq);
  for (;;) {
    struct timespec ts;
    MPI_Test(&rq, &flag, MPI_STATUS_IGNORE);
    if (flag) break;
    ts.tv_sec = 0;
    ts.tv_nsec = 2000000L;
    nanosleep(&ts, NULL);
  }
}
#endif

/* The end of a run on every rank: agree on the status (a failure wins over a cancellation), count
 * the members computed, and send every rank's records to rank 0. */
static int mpi_gather(void *user, autobal_ensemble *e, int status, const double *records, size_t n) {
  ens_mpi *mp = user;
  cli_progress_done(mp->ctx);
  mp->computed = autobal_ensemble_computed(e);
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) {
    int fail = status < 0 && status != AUTOBAL_ECANCELLED ? status : 0, fail_all = fail;
    int cancel = status == AUTOBAL_ECANCELLED, cancel_all = cancel, r, bad = AUTOBAL_SUCCESS;
    unsigned long long mine = mp->computed, all = mine;
    mpi_idle_barrier();
    MPI_Allreduce(&fail, &fail_all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(&cancel, &cancel_all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    MPI_Allreduce(&mine, &all, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    mp->computed = (size_t)all;
    if (mp->rank == 0) {
      for (r = 1; r < mp->size; r++) {
        unsigned long long len = 0;
        double *buf;
        size_t off;
        MPI_Recv(&len, 1, MPI_UNSIGNED_LONG_LONG, r, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        buf = malloc((len ? (size_t)len : 1) * sizeof *buf);
        if (!buf) MPI_Abort(MPI_COMM_WORLD, CLI_EXIT_INTERNAL); /* the journals keep the results */
        for (off = 0; off < len; off += ENS_CHUNK) {
          size_t c = (size_t)len - off < ENS_CHUNK ? (size_t)len - off : ENS_CHUNK;
          MPI_Recv(buf + off, (int)c, MPI_DOUBLE, r, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        }
        if (bad == AUTOBAL_SUCCESS) bad = autobal_ensemble_add_records(e, buf, (size_t)len);
        free(buf);
      }
    } else {
      unsigned long long len = n;
      size_t off;
      MPI_Send(&len, 1, MPI_UNSIGNED_LONG_LONG, 0, 1, MPI_COMM_WORLD);
      for (off = 0; off < n; off += ENS_CHUNK) {
        size_t c = n - off < ENS_CHUNK ? n - off : ENS_CHUNK;
        MPI_Send(records + off, (int)c, MPI_DOUBLE, 0, 2, MPI_COMM_WORLD);
      }
    }
    if (fail_all && !fail) mp->other_failed = 1;
    if (fail_all) return fail ? fail : fail_all;
    if (bad != AUTOBAL_SUCCESS) return bad;
    return cancel_all ? AUTOBAL_ECANCELLED : AUTOBAL_SUCCESS;
  }
#endif
  (void)records;
  (void)n;
  return status;
}

/* ---- hooks -------------------------------------------------------------------------------------- */
static void ens_progress(double fraction, void *user) { cli_progress(user, "ensemble", fraction); }
static int ens_cancel(void *user) {
  (void)user;
  return cli_interrupted();
}

typedef struct model_writer {
  cli_ctx *ctx;
  const ens_spec *s;
  int rc; /* CLI exit code of a failure of the pendulum's writer */
} model_writer;

/* The model's own group (/rotor or /pendulum): the app's writers, for now. */
static int write_model(void *user, autobal_archive *a) {
  model_writer *mw = user;
  const ens_spec *s = mw->s;
  if (s->model == MODEL_ROTOR) return cli_write_rotor_params(a, &s->rp, 1);
  if ((mw->rc = cli_write_pendulum_params(mw->ctx, a, &s->pp, &s->phys, s->physical)) != CLI_EXIT_OK) return AUTOBAL_EIO;
  return AUTOBAL_SUCCESS;
}

/* ---- summary on stdout ------------------------------------------------------------------------ */
/* The residual unbalance's distribution and targets (rotor), for the JSON summary. */
static void json_unbalance(cli_json *jj, const ens_spec *s, const autobal_ensemble *e) {
  size_t k, i;
  double qp[AUTOBAL_ENSEMBLE_N_QUANTILES];
  for (i = 0; i < AUTOBAL_ENSEMBLE_N_QUANTILES; i++) qp[i] = autobal_ensemble_quantile_probability(i);
  cli_json_numbers(jj, "quantile_probabilities", qp, AUTOBAL_ENSEMBLE_N_QUANTILES);
  for (k = 0; k < autobal_ensemble_n_quantities(e); k++) {
    const autobal_ensemble_quantity *q = autobal_ensemble_quantity_get(e, k);
    autobal_ensemble_stats sx;
    if (autobal_ensemble_get_stats(e, k, &sx) != AUTOBAL_SUCCESS) continue;
    cli_json_object(jj, q->name);
    cli_json_string(jj, "units", q->units);
    cli_json_int(jj, "n", (long)sx.n);
    cli_json_numbers(jj, "quantiles", sx.quantile, AUTOBAL_ENSEMBLE_N_QUANTILES);
    cli_json_number(jj, "mean", sx.mean);
    for (i = 0; i < s->set.n_targets; i++) {
      autobal_ensemble_target_result tr;
      double ci[2];
      if (autobal_ensemble_get_target(e, i, &tr) != AUTOBAL_SUCCESS || tr.quantity != k) continue;
      cli_json_number(jj, "target", tr.limit);
      cli_json_int(jj, "n_within_target", (long)tr.n_within);
      cli_json_int(jj, "n_evaluated", (long)tr.n);
      cli_json_number(jj, "probability_within_target", tr.p);
      ci[0] = tr.wilson_low, ci[1] = tr.wilson_high;
      cli_json_numbers(jj, "probability_within_target_wilson95", ci, 2);
    }
    cli_json_object_end(jj);
  }
}

/* The same on the console: g mm and mm/s. */
static void print_unbalance(const ens_spec *s, const autobal_ensemble *e) {
  static const char *const ql[AUTOBAL_ENSEMBLE_N_QUANTILES] = {"min", "5%", "25%", "median", "75%", "95%", "max"};
  const int two = s->rp.n_planes > 1, hw = s->rp.input == AUTOBAL_ROTOR_HARDWARE;
  const double mass = hw ? s->rp.hw.m_p : s->rp.lumped.M;
  const char *grid_note = s->set.random ? "" : "; a grid: the fraction of its points, the interval as for random draws";
  char nplanes[24];
  size_t k, i;
  snprintf(nplanes, sizeof nplanes, "%zu", s->rp.n_planes);
  for (k = 0; k < autobal_ensemble_n_quantities(e) && k < 2; k++) {
    autobal_ensemble_stats sx;
    const double f = k == 0 ? 1e6 : 1.0; /* kg m -> g mm; the grade is in mm/s */
    if (autobal_ensemble_get_stats(e, k, &sx) != AUTOBAL_SUCCESS || !sx.n) continue;
    if (k == 0)
      printf("  residual unbalance at the end, g mm (%s; %zu members without failure):\n    ",
             two ? "the worst plane's |s_j|" : "|s|", sx.n);
    else
      printf("  balance grade at the end, mm/s (ISO 21940-11 G = e Omega, e = %s%sU/%s, %s = %g kg, Omega at the end):\n    ",
             two ? nplanes : "", two ? " " : "", hw ? "m_p" : "M", hw ? "m_p" : "M", mass);
    for (i = 0; i < AUTOBAL_ENSEMBLE_N_QUANTILES; i++) printf("%s %.4g, ", ql[i], sx.quantile[i] * f);
    printf("mean %.4g%s\n", sx.mean * f, sx.n_nan ? " (some values not finite, left out)" : "");
  }
  if (autobal_ensemble_quantity_find(e, "balls_stuck_final") >= 0) { /* the exact friction law: stuck balls, time stuck */
    autobal_ensemble_stats b, ts;
    const size_t qb = (size_t)autobal_ensemble_quantity_find(e, "balls_stuck_final");
    size_t nb = 0;
    for (i = 0; i < s->rp.n_planes; i++) nb += s->rp.plane[i].n_balls;
    if (autobal_ensemble_get_stats(e, qb, &b) == AUTOBAL_SUCCESS && b.n && autobal_ensemble_get_stats(e, qb + 1, &ts) == AUTOBAL_SUCCESS)
      printf("  friction (exact): balls stuck at the end (of %zu): min %.4g, median %.4g, max %.4g, mean %.4g; the longest time "
             "one ball was stuck, s: median %.4g, max %.4g\n",
             nb, b.quantile[0], b.quantile[3], b.quantile[6], b.mean, ts.quantile[3], ts.quantile[6]);
  }
  if (autobal_ensemble_quantity_find(e, "contact_impacts") >= 0) { /* contact: impacts, touching pairs */
    autobal_ensemble_stats im, cf;
    const size_t qc = (size_t)autobal_ensemble_quantity_find(e, "contact_impacts");
    if (autobal_ensemble_get_stats(e, qc, &im) == AUTOBAL_SUCCESS && im.n && autobal_ensemble_get_stats(e, qc + 1, &cf) == AUTOBAL_SUCCESS)
      printf("  contact: impacts per member: min %.4g, median %.4g, max %.4g, mean %.4g; pairs touching at the end: min %.4g, "
             "median %.4g, max %.4g, mean %.4g\n",
             im.quantile[0], im.quantile[3], im.quantile[6], im.mean, cf.quantile[0], cf.quantile[3], cf.quantile[6], cf.mean);
  }
  for (i = 0; i < s->set.n_targets; i++) {
    autobal_ensemble_target_result tr;
    if (autobal_ensemble_get_target(e, i, &tr) != AUTOBAL_SUCCESS || !tr.n) continue;
    if (tr.quantity == 1)
      printf("  P(G <= %g mm/s) = %.4f: %zu of %zu members; Wilson 95%% interval [%.4f, %.4f]%s\n", tr.limit, tr.p, tr.n_within,
             tr.n, tr.wilson_low, tr.wilson_high, grid_note);
    else
      printf("  P(U <= %.4g g mm%s) = %.4f: %zu of %zu members; Wilson 95%% interval [%.4f, %.4f]%s\n", s->target_unbalance * 1e6,
             two ? ", each plane within half of it" : "", tr.p, tr.n_within, tr.n, tr.wilson_low, tr.wilson_high, grid_note);
  }
}

/* The attractor counts and the circulating members' frequencies against the natural frequencies. */
static void print_attractors(const autobal_ensemble_attractors *at, int pendulum) {
  int c, first = 1;
  printf("  attractors:");
  for (c = 1; c < AUTOBAL_ATTRACTOR_N_CLASSES; c++) {
    printf("%s %zu %s", first ? "" : ",", at->count[c], autobal_attractor_class_name(c));
    first = 0;
  }
  if (at->count[0]) printf(", %zu unclassified (failed)", at->count[0]);
  printf("\n");
  if (at->count[AUTOBAL_ATTRACTOR_CIRCULATING])
    printf("  circulating: a %s at nu = %.6g..%.6g %s absolute, %.4g..%.4g x the nearest natural frequency of its whirl "
           "at the member's speed (%s)\n",
           pendulum ? "pendulum" : "ball", at->frequency_min, at->frequency_max, pendulum ? "x omega0" : "rad/s",
           at->ratio_min, at->ratio_max, pendulum ? "the shaft, sqrt(1 - H^2/4)" : "Campbell");
}

static void print_summary(cli_ctx *ctx, const ens_spec *s, const autobal_ensemble *e, const autobal_ensemble_tally *t,
                          const ens_mpi *mp, int threads, double wall, int complete) {
  const autobal_ensemble_settings *p = &s->set;
  const char *tu = s->model == MODEL_ROTOR ? "s" : "(tau)";
  size_t j, n = autobal_ensemble_n_members(e), aix = autobal_ensemble_attractor_index(e);
  autobal_ensemble_attractors at;
  const int have_attr = autobal_ensemble_get_attractors(e, &at) == AUTOBAL_SUCCESS;
  if (ctx->json) {
    cli_json jj;
    cli_json_summary_begin(&jj, ctx);
    cli_json_string(&jj, "mode", p->random ? "random" : "grid");
    cli_json_array(&jj, "parameters");
    for (j = 0; j < p->n_params; j++) cli_json_string(&jj, NULL, p->param[j].name);
    cli_json_array_end(&jj);
    cli_json_int(&jj, "n_members", (long)n);
    cli_json_int(&jj, "n_done", (long)t->n_done);
    cli_json_int(&jj, "n_computed_now", (long)mp->computed);
    cli_json_int(&jj, "n_failed", (long)t->n_failed);
    cli_json_int(&jj, "n_balanced", (long)t->n_balanced);
    cli_json_quantity(&jj, "probability_balanced", t->p, "1");
    cli_json_quantity(&jj, "probability_balanced_stderr", t->p_stderr, "1");
    {
      double ci[2] = {NAN, NAN};
      if (t->n_ok) autobal_ensemble_wilson_interval(t->n_balanced, t->n_ok, 1.959963984540054, &ci[0], &ci[1]);
      cli_json_quantities(&jj, "probability_balanced_wilson95", ci, 2, "1");
    }
    if (s->model == MODEL_ROTOR) json_unbalance(&jj, s, e);
    if (have_attr) {
      int c;
      cli_json_object(&jj, "attractors");
      for (c = 0; c < AUTOBAL_ATTRACTOR_N_CLASSES; c++) cli_json_int(&jj, autobal_attractor_class_name(c), (long)at.count[c]);
      cli_json_object_end(&jj);
      cli_json_quantity(&jj, "circulation_frequency_min", at.frequency_min, "rad/s");
      cli_json_quantity(&jj, "circulation_frequency_max", at.frequency_max, "rad/s");
      cli_json_quantity(&jj, "circulation_frequency_ratio_min", at.ratio_min, "1");
      cli_json_quantity(&jj, "circulation_frequency_ratio_max", at.ratio_max, "1");
    }
    cli_json_quantity(&jj, "time_to_balance_mean", t->ttb_mean, s->model == MODEL_PENDULUM ? "1" : "s");
    cli_json_quantity(&jj, "time_to_balance_median", t->ttb_median, s->model == MODEL_PENDULUM ? "1" : "s");
    cli_json_bool(&jj, "complete", complete);
    cli_json_int(&jj, "mpi_ranks", mp->size);
    cli_json_int(&jj, "threads_per_rank", threads);
    cli_json_quantity(&jj, "wall_time", wall, "s");
    cli_json_summary_end(&jj, ctx);
    return;
  }
  if (ctx->quiet) return;
  printf("%s: %zu members (", ctx->command, n);
  for (j = 0; j < p->n_params; j++)
    if (p->random) printf("%s%s in [%g, %g]", j ? ", " : "random ", p->param[j].name, p->param[j].min, p->param[j].max);
    else printf("%s%s[%zu]", j ? " x " : "grid ", p->param[j].name, p->param[j].n);
  if (p->random) printf(", seed %llu", (unsigned long long)p->seed);
  printf("); %zu done (%zu now), %zu failed; %d rank(s) x %d thread(s), %.2f s wall\n", t->n_done, mp->computed, t->n_failed,
         mp->size, threads, wall);
  if (s->model == MODEL_ROTOR && s->rp.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP)
    printf("  drive: ramp %g -> %g rad/s from t = %g s to %g s (before a member's parameters change it); balanced counts "
           "after the end of each member's ramp\n",
           s->rp.drive.omega_a, s->rp.drive.omega_b, s->rp.drive.t_a, s->rp.drive.t_b);
  else if (s->model == MODEL_ROTOR && s->rp.drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE)
    printf("  drive: table of %zu points from t = %g s to %g s; balanced counts after its last time\n", s->rp.drive.n_points,
           s->rp.drive.table_t[0], s->rp.drive.table_t[s->rp.drive.n_points - 1]);
  if (t->n_ok) {
    double lo, hi;
    autobal_ensemble_wilson_interval(t->n_balanced, t->n_ok, 1.959963984540054, &lo, &hi);
    printf("  probability of balancing: %.4f +- %.4f (%zu of %zu members that ran without failure); Wilson 95%% "
           "interval [%.4f, %.4f]\n",
           t->p, t->p_stderr, t->n_balanced, t->n_ok, lo, hi);
  }
  if (t->n_balanced)
    printf("  time to balance %s: mean %.4g, median %.4g, max %.4g\n", tu, t->ttb_mean, t->ttb_median, t->ttb_max);
  if (s->model == MODEL_ROTOR) print_unbalance(s, e);
  if (have_attr) print_attractors(&at, s->model == MODEL_PENDULUM);
  if (!p->random && p->n_params == 2 && p->param[0].n <= 48 && p->param[1].n <= 96) {
    size_t i1, i2;
    printf("  basin of attraction (rows %s %g..%g, columns %s %g..%g; %s):\n", p->param[0].name, p->param[0].min,
           autobal_ensemble_grid_value(e, 0, p->param[0].n - 1), p->param[1].name, p->param[1].min,
           autobal_ensemble_grid_value(e, 1, p->param[1].n - 1),
           have_attr ? "# balanced, h heavy side, f fixed elsewhere, c circulating, p periodic, i irregular, x failed, ? not run"
                     : "# balanced, . not, x failed, ? not run");
    for (i1 = 0; i1 < p->param[0].n; i1++) {
      printf("    ");
      for (i2 = 0; i2 < p->param[1].n; i2++) {
        const double *r = autobal_ensemble_summary(e, i1 * p->param[1].n + i2);
        const char *sym = r && have_attr ? autobal_attractor_class_symbol((int)r[aix]) : NULL;
        putchar(!r ? '?' : r[AUTOBAL_ENSEMBLE_STATUS] < 0 ? 'x' : sym ? sym[0] : r[AUTOBAL_ENSEMBLE_BALANCED] == 1 ? '#' : '.');
      }
      putchar('\n');
    }
  }
  if (!complete)
    printf("  INCOMPLETE: %zu of %zu members to do; continue with --set ensemble.resume=true\n", n - t->n_done, n);
  if (ctx->output) printf("archive: %s\n", ctx->output);
}

/* ---- the command ------------------------------------------------------------------------------ */
static int file_exists(const char *p) {
  struct stat sb;
  return stat(p, &sb) == 0;
}

/* Before the run (rank 0): journals and the --resume/--force rules. */
static int prepare_output(cli_ctx *ctx, const ens_spec *s, const autobal_ensemble *e) {
  char **paths = NULL;
  size_t n = 0;
  int rc = CLI_EXIT_OK;
  autobal_error err;
  if (!ctx->output) {
    if (s->resume) return cli_fail(ctx, CLI_EXIT_USAGE, "[ensemble]: resume needs -o FILE.h5 (the journals live next to it)");
    return CLI_EXIT_OK;
  }
  if (autobal_ensemble_journals(ctx->output, &paths, &n, &err) != AUTOBAL_SUCCESS)
    return cli_fail(ctx, cli_exit_code(err.status), "%s", err.message);
  if (!s->resume) {
    if (n && !ctx->force)
      rc = cli_fail(ctx, CLI_EXIT_IO,
                    "journals of an unfinished run exist (%s%s); continue it with --set ensemble.resume=true, "
                    "or start over with --force",
                    paths[0], n > 1 ? ", ..." : "");
    else if (n && autobal_ensemble_journals_remove(ctx->output, &err) != AUTOBAL_SUCCESS)
      rc = cli_fail(ctx, CLI_EXIT_IO, "%s", err.message);
  } else if (file_exists(ctx->output) && !ctx->force) {
    /* an incomplete archive of the interrupted run is replaced; a complete one is kept */
    /* ... if it is this command's, with these settings: another command's archive or another
     * configuration's is never replaced without --force */
    autobal_archive *r = NULL;
    char status[64] = "", command[128] = "", hash[64] = "", want[32];
    snprintf(want, sizeof want, "%016llx", (unsigned long long)autobal_ensemble_hash(e));
    if (autobal_archive_open_read(ctx->output, &r, NULL) == AUTOBAL_SUCCESS) {
      autobal_archive_read_attr_string(r, "/", "status", status, sizeof status, NULL);
      autobal_archive_read_attr_string(r, "/", "command", command, sizeof command, NULL);
      if (autobal_archive_read_attr_string(r, "/rotor/ensemble", "settings_hash", hash, sizeof hash, NULL) < 0)
        autobal_archive_read_attr_string(r, "/pendulum/ensemble", "settings_hash", hash, sizeof hash, NULL);
      autobal_archive_close(r, NULL);
    }
    if (strcmp(status, "incomplete") != 0)
      rc = cli_fail(ctx, CLI_EXIT_IO, "'%s' exists and is %s; nothing to resume (use --force to compute it again)",
                    ctx->output, status[0] ? "complete" : "not an incomplete autobal archive");
    else if (strcmp(command, ctx->command) != 0)
      rc = cli_fail(ctx, CLI_EXIT_IO,
                    "'%s' is an incomplete archive of 'autobal %s', not of 'autobal %s': not replaced (choose "
                    "another -o, or --force to replace it)",
                    ctx->output, command[0] ? command : "(unknown)", ctx->command);
    else if (strcmp(hash, want) != 0)
      rc = cli_fail(ctx, CLI_EXIT_INPUT,
                    "'%s' is an incomplete ensemble of a different configuration (settings_hash %s, this "
                    "configuration %s): not resumed, not replaced (the configuration of the interrupted run, or "
                    "--force to start over)",
                    ctx->output, hash[0] ? hash : "not recorded", want);
    else
      ctx->force = 1;
  }
  autobal_ensemble_journals_free(paths, n);
  return rc;
}

/* A library message for the [ensemble] section (the engine's "ensemble: " prefix dropped). */
static int fail_ensemble(cli_ctx *ctx, int status, const char *msg) {
  if (!strncmp(msg, "ensemble: ", 10)) msg += 10;
  return cli_fail(ctx, cli_exit_code(status), "[ensemble]: %s", msg);
}

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int ensemble_main(cli_ctx *ctx, int model, ens_mpi *mp) {
  ens_spec *s = calloc(1, sizeof *s);
  autobal_ensemble *e = NULL;
  autobal_archive *a = NULL;
  autobal_error err;
  int rc = CLI_EXIT_OK, threads, st;
  double t0 = now_seconds(), wall;

  if (!s) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  autobal_error_clear(&err);
  s->model = model;
  s->mname = model == MODEL_ROTOR ? "rotor" : "pendulum";
  s->set = autobal_ensemble_settings_default();
  mp->ctx = ctx;
  if (mp->rank != 0) ctx->progress = 0, ctx->quiet = 1;
  if ((rc = read_spec(ctx, s))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  if (config_hash(ctx, s, &s->set.identity) != AUTOBAL_SUCCESS) {
    rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
    goto done;
  }
  if (!(e = autobal_ensemble_alloc(&s->mb, &s->set, &err))) {
    rc = fail_ensemble(ctx, err.status, err.message);
    goto done;
  }
  threads = autobal_ensemble_threads(e);
  /* rank 0: journals, --resume/--force, the archive */
  if (mp->rank == 0) {
    rc = prepare_output(ctx, s, e);
    if (rc == CLI_EXIT_OK && ctx->output && !ctx->force && file_exists(ctx->output))
      rc = cli_fail(ctx, CLI_EXIT_IO, "output file '%s' exists; use --force to overwrite it", ctx->output);
  }
  if ((rc = mpi_agree(ctx, mp, rc))) goto done;
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) MPI_Bcast(&ctx->force, 1, MPI_INT, 0, MPI_COMM_WORLD);
#endif
  {
    autobal_ensemble_parallel par;
    memset(&par, 0, sizeof par);
    par.mine = mpi_mine;
    par.gather = mpi_gather;
    par.user = mp;
    par.results = mp->rank == 0;
    if (autobal_ensemble_set_parallel(e, &par) != AUTOBAL_SUCCESS) rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  }
  autobal_ensemble_set_progress(e, ens_progress, ctx);
  autobal_ensemble_set_cancel(e, ens_cancel, NULL);
  /* every rank reads every journal (resume), then opens its own */
  if (rc == CLI_EXIT_OK && s->resume && (st = autobal_ensemble_resume(e, ctx->output, mp->rank)) != AUTOBAL_SUCCESS)
    rc = cli_fail(ctx, cli_exit_code(st), "%s", autobal_ensemble_errmsg(e));
  if ((rc = mpi_agree(ctx, mp, rc))) goto done; /* also: nobody writes before everybody has read */
  if (ctx->output && (st = autobal_ensemble_journal_open(e, ctx->output, mp->rank)) != AUTOBAL_SUCCESS)
    rc = cli_fail(ctx, cli_exit_code(st), "%s", autobal_ensemble_errmsg(e));
  if ((rc = mpi_agree(ctx, mp, rc))) goto done;

  st = autobal_ensemble_run(e);
  if (mp->other_failed) rc = cli_fail(ctx, cli_exit_code(st), "stopped: another MPI rank failed (see its message)");
  else if (st != AUTOBAL_SUCCESS && st != AUTOBAL_ECANCELLED) rc = cli_fail(ctx, cli_exit_code(st), "%s", autobal_ensemble_errmsg(e));
  wall = now_seconds() - t0;
  if (mp->rank == 0) {
    autobal_ensemble_tally t;
    int complete;
    autobal_ensemble_get_tally(e, &t);
    complete = t.n_done == t.n_members;
    if (rc == CLI_EXIT_OK && st == AUTOBAL_ECANCELLED)
      rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED, "interrupted: %zu of %zu members done; the journals keep them "
                    "(continue with --set ensemble.resume=true)", t.n_done, t.n_members);
    /* opened only now: a long run holds no half-written HDF5 file (the journals are its record) */
    if (ctx->output) {
      int o = cli_archive_open(ctx, s->model == MODEL_ROTOR ? "autobal rotor ensemble" : "autobal pendulum ensemble", &a);
      if (rc == CLI_EXIT_OK) rc = o;
    }
    if (a) {
      model_writer mw;
      autobal_ensemble_execution ex;
      int w;
      mw.ctx = ctx, mw.s = s, mw.rc = CLI_EXIT_OK;
      ex.ranks = mp->size, ex.threads = threads, ex.wall_time = wall;
#ifdef AUTOBAL_HAVE_MPI
      ex.mpi_build = 1;
#else
      ex.mpi_build = 0;
#endif
      w = autobal_ensemble_write(e, a, write_model, &mw, &ex);
      if (w != AUTOBAL_SUCCESS && rc == CLI_EXIT_OK)
        rc = mw.rc != CLI_EXIT_OK ? mw.rc : cli_fail(ctx, cli_exit_code(w), "%s", autobal_ensemble_errmsg(e));
      if (rc == CLI_EXIT_OK && !complete) {
        char reason[256];
        snprintf(reason, sizeof reason, "%zu of %zu members done; continue with --set ensemble.resume=true", t.n_done,
                 t.n_members);
        autobal_archive_set_status(a, "incomplete", reason);
      }
      rc = cli_archive_finish(ctx, a, rc);
      a = NULL;
    }
    if (rc == CLI_EXIT_OK && complete && ctx->output) autobal_ensemble_journals_remove(ctx->output, NULL);
    if (rc == CLI_EXIT_OK || rc == CLI_EXIT_INTERRUPTED) print_summary(ctx, s, e, &t, mp, threads, wall, complete);
    if (rc == CLI_EXIT_OK && t.n_failed && !ctx->json) {
      size_t fm, j;
      int fst;
      const char *why;
      fprintf(stderr, "autobal: warning: %zu member(s) failed; their status is recorded in the archive\n", t.n_failed);
      if (autobal_ensemble_first_failure(e, &fm, &fst, &why)) { /* the first one of this run, and why */
        char msg[sizeof ctx->err];
        fprintf(stderr, "autobal: warning: the first, member %zu (", fm);
        for (j = 0; j < s->set.n_params; j++)
          fprintf(stderr, "%s%s = %.17g", j ? ", " : "", s->set.param[j].name, autobal_ensemble_member_value(e, fm, j));
        fprintf(stderr, "), status %d: %s\n", fst, s->model == MODEL_ROTOR ? cli_rotor_message(why, msg, sizeof msg) : why);
      }
    }
  }
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (mp->rank != 0 && rc != CLI_EXIT_OK && !ctx->err[0]) cli_fail(ctx, rc, "stopped (see rank 0)");
#endif
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  autobal_ensemble_free(e);
  autobal_ensemble_member_release(&s->mb);
  free(s->rstorage);
  free(s);
  return rc;
}

static int ensemble_command(cli_ctx *ctx, int model) {
  ens_mpi mp;
  int rc;
  mpi_begin(&mp);
  rc = ensemble_main(ctx, model, &mp);
  mpi_end(&mp);
  return rc;
}

int cli_cmd_rotor_ensemble(cli_ctx *ctx) { return ensemble_command(ctx, MODEL_ROTOR); }
int cli_cmd_pendulum_ensemble(cli_ctx *ctx) { return ensemble_command(ctx, MODEL_PENDULUM); }
