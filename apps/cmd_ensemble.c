/* cmd_ensemble.c: `autobal rotor ensemble` and `autobal pendulum ensemble`: many transients over a
 * set of initial conditions or parameters (a grid, or seeded random samples), each summarised
 * (balanced or not, time to balance, residual unbalance, amplitude, solver status), optionally with
 * full time series for a chosen subset; the basin-of-attraction map and the probability of
 * balancing.
 *
 * Parallelism
 *  - OpenMP inside a process: one model handle per member and one transient driver per thread;
 *    members are handed out dynamically.  Every member is computed the same way whichever thread
 *    or rank runs it, so the results do not depend on the number of threads or ranks.
 *  - MPI across processes (build option AUTOBAL_MPI, code under AUTOBAL_HAVE_MPI): the members
 *    still to do are dealt out cyclically (member k of the to-do list to rank k mod size: balanced
 *    chunks even when the cost varies smoothly over a map); at the end every rank sends its
 *    records to rank 0, the only process that touches HDF5, and rank 0 writes one ordinary archive.
 *    Why not parallel HDF5 or one file per rank joined by a virtual dataset: Debian's HDF5 is the
 *    serial build; a member's summary is ~20 numbers, so gathering even 10^6 members costs a few
 *    hundred MB of messages at most; and one self-contained file is byte-for-byte the archive of a
 *    serial run (a VDS archive breaks when its per-rank source files are moved or deleted).
 *  - Checkpoints: with -o FILE.h5 every finished member is appended at once (fflush) to a journal
 *    FILE.h5.journal-<rank> (binary records, below).  A killed process or job loses only the
 *    members it was running; `--set ensemble.resume=true` reads every journal of FILE.h5 (written
 *    with any number of ranks), skips the members found there and computes the rest.  The journals
 *    are removed once the complete archive is written.
 *
 * Journal format (native byte order; not portable across architectures): a 48-byte header
 * "ABENSJ01", then 5 uint64: FNV-1a hash of the configuration (sorted section.key=value lines,
 * without the run-control keys threads/resume/max_members/time_limit, plus the model and the
 * autobal version), number of members, summary length nsum, series columns ncols, format flags (0);
 * then records of doubles:
 *   member, nsum, nrows, ncols_or_0, summary[nsum], t[nrows], rows[nrows*ncols], member
 * A truncated last record (a process killed while writing) is ignored.  The same records are the
 * MPI messages.
 *
 * Random samples: member m, parameter j (0-based, nparam parameters) takes
 *   min_j + (max_j - min_j) u,  u = (x >> 11) 2^-53,  x = splitmix64 output number m*nparam + j
 * (0-based) of the generator seeded with `seed`:  x_k = mix(seed + (k + 1) 0x9E3779B97F4A7C15),
 * mix(z) = z ^= z >> 30, z *= 0xBF58476D1CE4E5B9, z ^= z >> 27, z *= 0x94D049BB133111EB,
 * z ^= z >> 31 (Steele, Lea, Flood 2014).  A member's sample depends only on (seed, m), not on
 * the number of members, threads or ranks. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#define ENS_PRAGMA(x) _Pragma(#x)
#else
#define ENS_PRAGMA(x)
#endif
#ifdef AUTOBAL_HAVE_MPI
#include <mpi.h>
#endif

#include "autobal/archive.h"
#include "autobal/pendulum.h"
#include "autobal/rotor.h"
#include "autobal/transient.h"
#include "cli.h"

#define TWO_PI 6.283185307179586476925286766559
#define PI 3.1415926535897932384626433832795
#define ENS_MAX_PARAMS 3
#define ENS_MAX_MEMBERS 100000000UL
#define ENS_MAX_KEEP 1024
#define ENS_MAX_SERIES_DOUBLES (1UL << 28) /* 2 GiB of kept series in all */
#define ENS_PEND_NCOLS 15

enum { MODEL_ROTOR = 0, MODEL_PENDULUM = 1 };

/* summary entries of a member (then nang final angles) */
enum { S_STATUS, S_BALANCED, S_TTB, S_RES0, S_RES1, S_AMPMAX, S_AMP1, S_TREACHED, S_STEPS, S_RHS, S_NBASE };

enum {
  P_R_PSI, P_R_RATE, P_R_OMEGA, P_R_DAMPING, P_R_M0, P_R_X, P_R_Y, /* rotor */
  P_P_STATE, P_P_RW, P_P_RM, P_P_H, P_P_HS, P_P_PSI0, P_P_K       /* pendulum */
};

typedef struct ens_param {
  char name[32];
  int kind;
  size_t index;        /* ball (P_R_PSI, P_R_RATE) or state component (P_P_STATE) */
  int angle;           /* periodic angle (for the default range and endpoint) */
  double lo, hi;
  size_t n;            /* grid points */
  const char *units, *long_name;
} ens_param;

typedef struct ens_spec {
  int model;
  const char *mname;   /* "rotor" / "pendulum" */
  int random;
  size_t nparam;
  ens_param par[ENS_MAX_PARAMS];
  size_t stride[ENS_MAX_PARAMS];
  size_t n_members;
  uint64_t seed;
  int endpoint;
  size_t keep[ENS_MAX_KEEP];
  size_t n_keep;
  long threads, max_members;
  double time_limit;
  int resume;
  /* [transient] */
  double t_end, dt_out, revs_out, rtol, atol, h_max, balance_tol, balance_revs, balance_dwell;
  int use_revs_out, use_dwell, stop_at_balance, frame;
  long max_steps;
  const char *stepper, *frame_name;
  /* the base model */
  autobal_rotor_params rp;
  void *rstorage;
  size_t n_balls, dim, nout;
  autobal_pendulum_params pp;
  autobal_pendulum_physical phys;
  int physical;
  double y0[8];
  /* derived */
  size_t nsum, nang, ncols;
  uint64_t hash;
} ens_spec;

/* ---- random samples and grid ------------------------------------------------------------- */
static double ens_uniform(uint64_t seed, uint64_t k) {
  uint64_t z = seed + (k + 1) * UINT64_C(0x9E3779B97F4A7C15);
  z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-53;
}

static double grid_value(const ens_param *p, size_t i, int endpoint) {
  size_t d = endpoint ? p->n - 1 : p->n;
  if (p->n == 1) return p->lo;
  return p->lo + (p->hi - p->lo) * (double)i / (double)d;
}

static double member_value(const ens_spec *s, size_t m, size_t j) {
  const ens_param *p = &s->par[j];
  if (s->random) return p->lo + (p->hi - p->lo) * ens_uniform(s->seed, (uint64_t)m * s->nparam + j);
  return grid_value(p, (m / s->stride[j]) % p->n, s->endpoint);
}

/* ---- configuration ------------------------------------------------------------------------- */
static int parse_param(cli_ctx *ctx, ens_spec *s, ens_param *p, const char *name, const char *key) {
  static const char *const pstate[8] = {"xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate"};
  static const char *const pstate_u[8] = {"1", "1", "rad", "rad", "1", "1", "1", "1"};
  static const char *const pstate_l[8] = {
      "initial shaft displacement xi (units of l)", "initial shaft displacement eta (units of l)",
      "initial angle psi of pendulum 1", "initial angle phi of pendulum 2", "initial d xi/d tau",
      "initial d eta/d tau", "initial d psi/d tau", "initial d phi/d tau"};
  size_t i;
  memset(p, 0, sizeof *p);
  if (strlen(name) >= sizeof p->name) goto unknown;
  snprintf(p->name, sizeof p->name, "%s", name);
  if (s->model == MODEL_ROTOR) {
    if ((!strncmp(name, "psi_", 4) || !strncmp(name, "rate_", 5))) {
      const char *num = name + (name[0] == 'p' ? 4 : 5);
      char *end;
      unsigned long k;
      if (!(*num >= '1' && *num <= '9')) goto unknown;
      errno = 0;
      k = strtoul(num, &end, 10);
      if (*end || errno) goto unknown;
      if (k < 1 || k > s->n_balls)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %s: ball %lu does not exist (the model has %zu balls: 1..%zu, plane 1 first)",
                        key, name, k, s->n_balls, s->n_balls);
      p->index = k - 1;
      if (name[0] == 'p') {
        p->kind = P_R_PSI, p->angle = 1, p->units = "rad",
        p->long_name = "initial angle of the ball relative to the rotor";
      } else {
        p->kind = P_R_RATE, p->units = "rad/s", p->long_name = "initial angular rate of the ball relative to the rotor";
      }
      return CLI_EXIT_OK;
    }
    if (!strcmp(name, "omega")) {
      p->kind = P_R_OMEGA, p->units = "rad/s", p->long_name = "spin speed omega";
    } else if (!strcmp(name, "ball_damping")) {
      p->kind = P_R_DAMPING, p->units = "kg/s", p->long_name = "damping h of every ball";
    } else if (!strcmp(name, "m0")) {
      p->kind = P_R_M0, p->units = "kg", p->long_name = "unbalance mass m0 of plane 1";
    } else if (!strcmp(name, "x")) {
      p->kind = P_R_X, p->units = "m", p->long_name = "initial displacement x of the centre of mass";
    } else if (!strcmp(name, "y")) {
      p->kind = P_R_Y, p->units = "m", p->long_name = "initial displacement y of the centre of mass";
    } else {
      goto unknown;
    }
    return CLI_EXIT_OK;
  }
  for (i = 0; i < 8; i++)
    if (!strcmp(name, pstate[i])) {
      p->kind = P_P_STATE, p->index = i, p->units = pstate_u[i], p->long_name = pstate_l[i];
      p->angle = (i == 2 || i == 3);
      return CLI_EXIT_OK;
    }
  if (!strcmp(name, "R_w")) p->kind = P_P_RW, p->units = "1", p->long_name = "rotor speed omega/omega0";
  else if (!strcmp(name, "R_m")) p->kind = P_P_RM, p->units = "1", p->long_name = "mass ratio m/(M + 2m)";
  else if (!strcmp(name, "H")) p->kind = P_P_H, p->units = "1", p->long_name = "external damping H";
  else if (!strcmp(name, "h")) p->kind = P_P_HS, p->units = "1", p->long_name = "pendulum damping h";
  else if (!strcmp(name, "psi0")) p->kind = P_P_PSI0, p->units = "rad", p->long_name = "main-motion angle psi0", p->angle = 1;
  else if (!strcmp(name, "k")) p->kind = P_P_K, p->units = "1", p->long_name = "unbalance parameter k = sin^2(2 psi0)";
  else goto unknown;
  return CLI_EXIT_OK;
unknown:
  if (s->model == MODEL_ROTOR)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[ensemble]: %s = '%s' is not a rotor ensemble parameter: psi_K, rate_K (ball K = 1..%zu), omega, ball_damping, m0, x, y",
                    key, name, s->n_balls);
  return cli_fail(ctx, CLI_EXIT_INPUT,
                  "[ensemble]: %s = '%s' is not a pendulum ensemble parameter: xi, eta, psi, phi, xi_rate, eta_rate, psi_rate, phi_rate, R_w, R_m, H, h, psi0, k",
                  key, name);
}

static int read_transient(cli_ctx *ctx, ens_spec *s) {
  int rc, has_dt = 0, has_revs = 0, has_brevs = 0, has_dwell = 0;
  const int rotor = s->model == MODEL_ROTOR;
  s->t_end = rotor ? 20.0 : 300.0;
  s->rtol = 1e-10; /* rotor: the defaults of `rotor transient` (apps/cmd_rotor.c) */
  s->atol = rotor ? 1e-9 : 1e-12;
  s->h_max = 0.0;
  s->max_steps = 100000000L;
  s->balance_tol = rotor ? 0.01 : 1e-3;
  s->balance_revs = rotor ? 50.0 : 20.0;
  s->revs_out = 0.25;
  s->stepper = "rk8pd";
  s->frame_name = "fixed";
  s->stop_at_balance = 1;
  if ((rc = cli_get_quantity(ctx, "transient", "t_end", s->model == MODEL_PENDULUM ? "1" : "s", s->t_end, &s->t_end, NULL))) return rc;
  if ((rc = cli_get_quantity(ctx, "transient", "dt_out", s->model == MODEL_PENDULUM ? "1" : "s", 0.0, &s->dt_out, &has_dt))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "revs_out", s->revs_out, &s->revs_out, &has_revs))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "rtol", s->rtol, &s->rtol, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "atol", s->atol, &s->atol, NULL))) return rc;
  if ((rc = cli_get_quantity(ctx, "transient", "h_max", s->model == MODEL_PENDULUM ? "1" : "s", s->h_max, &s->h_max, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "transient", "max_steps", s->max_steps, &s->max_steps, NULL))) return rc;
  if ((rc = cli_get_string(ctx, "transient", "stepper", s->stepper, &s->stepper, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "balance_tol", s->balance_tol, &s->balance_tol, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "transient", "balance_revs", s->balance_revs, &s->balance_revs, &has_brevs))) return rc;
  if ((rc = cli_get_bool(ctx, "transient", "stop_at_balance", 1, &s->stop_at_balance, NULL))) return rc;
  if (rotor) {
    if ((rc = cli_get_quantity(ctx, "transient", "balance_dwell", s->model == MODEL_PENDULUM ? "1" : "s", 0.0, &s->balance_dwell, &has_dwell))) return rc;
    if ((rc = cli_get_string(ctx, "transient", "frame", s->frame_name, &s->frame_name, NULL))) return rc;
    if (!strcmp(s->frame_name, "fixed")) s->frame = AUTOBAL_ROTOR_FIXED;
    else if (!strcmp(s->frame_name, "rotating")) s->frame = AUTOBAL_ROTOR_ROTATING;
    else return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: frame = '%s' is not one of: fixed, rotating", s->frame_name);
  }
  if (has_dt && has_revs) return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give dt_out or revs_out, not both");
  if (has_brevs && has_dwell)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: give balance_revs (revolutions) or balance_dwell (s), not both");
  s->use_revs_out = !has_dt;
  s->use_dwell = has_dwell;
  if (!(s->t_end > 0 && isfinite(s->t_end)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: t_end = %g is out of range: allowed (0, inf)", s->t_end);
  if (s->use_revs_out && !(s->revs_out > 0 && isfinite(s->revs_out)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: revs_out = %g is out of range: allowed (0, inf)", s->revs_out);
  if (!s->use_revs_out && !(s->dt_out > 0 && isfinite(s->dt_out)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: dt_out = %g is out of range: allowed (0, inf)", s->dt_out);
  if (!(s->balance_tol > 0 && isfinite(s->balance_tol)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_tol = %g is out of range: allowed (0, inf)", s->balance_tol);
  if (!(s->balance_revs >= 0 && isfinite(s->balance_revs)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_revs = %g is out of range: allowed [0, inf)", s->balance_revs);
  if (has_dwell && !(s->balance_dwell >= 0 && isfinite(s->balance_dwell)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: balance_dwell = %g s is out of range: allowed [0, inf)", s->balance_dwell);
  if (s->max_steps < 1)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: max_steps = %ld is out of range: allowed [1, inf)", s->max_steps);
  {
    autobal_transient_options opt = autobal_transient_options_default();
    autobal_error err;
    autobal_error_clear(&err);
    opt.stepper = s->stepper, opt.rtol = s->rtol, opt.atol = s->atol, opt.h_max = s->h_max;
    opt.max_steps = (unsigned long)s->max_steps;
    if (autobal_transient_options_validate(&opt, &err) != AUTOBAL_SUCCESS)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[transient]: %s", err.message);
  }
  return CLI_EXIT_OK;
}

static int read_ensemble(cli_ctx *ctx, ens_spec *s) {
  static const char *const pk[ENS_MAX_PARAMS] = {"param1", "param2", "param3"};
  static const char *const mink[ENS_MAX_PARAMS] = {"min1", "min2", "min3"};
  static const char *const maxk[ENS_MAX_PARAMS] = {"max1", "max2", "max3"};
  static const char *const nk[ENS_MAX_PARAMS] = {"n1", "n2", "n3"};
  const char *mode = "grid";
  const char *defname[ENS_MAX_PARAMS];
  long samples = 256, seed = 1;
  int rc, has_samples = 0, has_seed = 0, has_endpoint = 0, all_angles = 1;
  size_t j, nser = 0;
  double ser[ENS_MAX_KEEP + 1];
  if (s->model == MODEL_ROTOR) {
    defname[0] = s->n_balls >= 1 ? "psi_1" : "omega";
    defname[1] = s->n_balls >= 2 ? "psi_2" : "none";
  } else {
    defname[0] = "psi";
    defname[1] = "phi";
  }
  defname[2] = "none";
  if ((rc = cli_get_string(ctx, "ensemble", "mode", mode, &mode, NULL))) return rc;
  if (!strcmp(mode, "grid")) s->random = 0;
  else if (!strcmp(mode, "random")) s->random = 1;
  else return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: mode = '%s' is not one of: grid, random", mode);
  s->nparam = 0;
  for (j = 0; j < ENS_MAX_PARAMS; j++) {
    const char *name = defname[j];
    int has_name, has_min, has_max, has_n;
    long n = 16;
    ens_param *p = &s->par[s->nparam];
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
    if (j > s->nparam)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s is given but %s is none (fill the axes in order)", pk[j], pk[j - 1]);
    if ((rc = parse_param(ctx, s, p, name, pk[j]))) return rc;
    {
      size_t i;
      for (i = 0; i < s->nparam; i++)
        if (s->par[i].kind == p->kind && s->par[i].index == p->index)
          return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %s is already %s", pk[j], name, pk[i]);
      if (s->model == MODEL_PENDULUM)
        for (i = 0; i < s->nparam; i++)
          if ((s->par[i].kind == P_P_K && p->kind == P_P_PSI0) || (s->par[i].kind == P_P_PSI0 && p->kind == P_P_K))
            return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: k and psi0 describe the same unbalance; vary one of them");
    }
    p->lo = p->angle ? -PI : 0.0;
    p->hi = p->angle ? PI : 0.0;
    if ((rc = cli_get_double(ctx, "ensemble", mink[j], p->lo, &p->lo, &has_min))) return rc;
    if ((rc = cli_get_double(ctx, "ensemble", maxk[j], p->hi, &p->hi, &has_max))) return rc;
    if ((rc = cli_get_int(ctx, "ensemble", nk[j], n, &n, &has_n))) return rc;
    if (!p->angle && (!has_min || !has_max))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %s needs %s and %s (only angles have a default range [-pi, pi])",
                      pk[j], name, mink[j], maxk[j]);
    if (!(isfinite(p->lo) && isfinite(p->hi) && p->lo <= p->hi))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %g, %s = %g: need finite %s <= %s", mink[j], p->lo, maxk[j], p->hi,
                      mink[j], maxk[j]);
    if (s->random && has_n)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s is for mode = grid; mode = random draws `samples` members", nk[j]);
    if (n < 1 || n > 100000)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: %s = %ld is out of range: allowed [1, 100000]", nk[j], n);
    p->n = (size_t)n;
    if (!p->angle) all_angles = 0;
    s->nparam++;
  }
  if (s->nparam == 0) return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: param1 is none: nothing varies");
  if ((rc = cli_get_int(ctx, "ensemble", "samples", samples, &samples, &has_samples))) return rc;
  if ((rc = cli_get_int(ctx, "ensemble", "seed", seed, &seed, &has_seed))) return rc;
  if (!s->random && (has_samples || has_seed))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: samples and seed are for mode = random");
  if (seed < 0) return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: seed = %ld is out of range: allowed [0, 2^63)", seed);
  s->seed = (uint64_t)seed;
  /* periodic angles: n points over [min, max) by default, else both ends */
  if ((rc = cli_get_bool(ctx, "ensemble", "endpoint", !all_angles, &s->endpoint, &has_endpoint))) return rc;
  if (s->random && has_endpoint) return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: endpoint is for mode = grid");
  if (s->random) {
    if (samples < 1 || (unsigned long)samples > ENS_MAX_MEMBERS)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: samples = %ld is out of range: allowed [1, %lu]", samples, ENS_MAX_MEMBERS);
    s->n_members = (size_t)samples;
  } else {
    size_t total = 1;
    for (j = s->nparam; j-- > 0;) {
      s->stride[j] = total;
      if (total > ENS_MAX_MEMBERS / s->par[j].n)
        return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: the grid has more than %lu members", ENS_MAX_MEMBERS);
      total *= s->par[j].n;
    }
    s->n_members = total;
  }
  if ((rc = cli_get_doubles(ctx, "ensemble", "series", ser, ENS_MAX_KEEP + 1, &nser, NULL))) return rc;
  if (nser > ENS_MAX_KEEP)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: series lists more than %d members", ENS_MAX_KEEP);
  s->n_keep = 0;
  for (j = 0; j < nser; j++) {
    size_t m, i, at;
    if (!(ser[j] >= 0 && ser[j] < (double)s->n_members && ser[j] == floor(ser[j])))
      return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: series = ... %g ...: members are numbered 0..%zu", ser[j], s->n_members - 1);
    m = (size_t)ser[j];
    for (at = 0; at < s->n_keep && s->keep[at] < m; at++) {
    }
    if (at < s->n_keep && s->keep[at] == m) continue; /* duplicate */
    for (i = s->n_keep; i > at; i--) s->keep[i] = s->keep[i - 1];
    s->keep[at] = m;
    s->n_keep++;
  }
  if ((rc = cli_get_int(ctx, "ensemble", "threads", 0, &s->threads, NULL))) return rc;
  if (s->threads < 0 || s->threads > 1024)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: threads = %ld is out of range: allowed [0, 1024] (0: OpenMP default)", s->threads);
  if ((rc = cli_get_bool(ctx, "ensemble", "resume", 0, &s->resume, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "ensemble", "max_members", 0, &s->max_members, NULL))) return rc;
  if (s->max_members < 0)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: max_members = %ld is out of range: allowed [0, inf) (0: all)", s->max_members);
  if ((rc = cli_get_double(ctx, "ensemble", "time_limit", 0.0, &s->time_limit, NULL))) return rc;
  if (!(s->time_limit >= 0 && isfinite(s->time_limit)))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: time_limit = %g s is out of range: allowed [0, inf) (0: none)", s->time_limit);
  return CLI_EXIT_OK;
}

/* FNV-1a over the sorted effective configuration minus the run-control keys. */
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
         !strncmp(p, "time_limit ", 11)))
      continue;
    if (n == cap) {
      char **nlines = realloc(lines, (cap = cap ? 2 * cap : 64) * sizeof *lines);
      if (!nlines) {
        for (i = 0; i < n; i++) free(lines[i]);
        free(lines);
        free(ini);
        return AUTOBAL_ENOMEM;
      }
      lines = nlines;
    }
    lines[n] = malloc(strlen(sec) + strlen(p) + 2);
    if (!lines[n]) {
      for (i = 0; i < n; i++) free(lines[i]);
      free(lines);
      free(ini);
      return AUTOBAL_ENOMEM;
    }
    sprintf(lines[n], "%s%s", sec, p);
    n++;
  }
  if (n > 1) qsort(lines, n, sizeof *lines, cmp_str);
  h = fnv1a(h, s->mname, strlen(s->mname) + 1);
  h = fnv1a(h, autobal_version(), strlen(autobal_version()) + 1);
  for (i = 0; i < n; i++) {
    h = fnv1a(h, lines[i], strlen(lines[i]) + 1);
    free(lines[i]);
  }
  free(lines);
  free(ini);
  *out = h;
  return AUTOBAL_SUCCESS;
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

static int read_spec(cli_ctx *ctx, ens_spec *s) {
  int rc;
  autobal_error err;
  autobal_error_clear(&err);
  if (s->model == MODEL_ROTOR) {
    autobal_rotor *rot;
    if ((rc = cli_rotor_config_read(ctx, &s->rp, &s->rstorage))) return rc;
    rot = autobal_rotor_alloc(&s->rp, &err);
    if (!rot) {
      char msg[sizeof ctx->err];
      return cli_fail(ctx, cli_exit_code(err.status), "%s", cli_rotor_message(err.message, msg, sizeof msg));
    }
    s->n_balls = autobal_rotor_n_balls_total(rot);
    s->dim = autobal_rotor_dim(rot);
    s->nout = autobal_rotor_output_count(rot);
    autobal_rotor_free(rot);
    s->nang = s->n_balls;
    s->ncols = s->dim + s->nout;
  } else {
    autobal_pendulum_motion mo;
    if ((rc = cli_read_pendulum_params(ctx, &s->pp, &s->phys, &s->physical))) return rc;
    if ((rc = read_pendulum_initial(ctx, s))) return rc;
    if (autobal_pendulum_motion_init(&mo, &s->pp, &err) != AUTOBAL_SUCCESS)
      return cli_fail(ctx, cli_exit_code(err.status), "[pendulum]: %s", err.message);
    s->dim = AUTOBAL_PENDULUM_STATE_DIM;
    s->nang = 2;
    s->ncols = ENS_PEND_NCOLS;
  }
  s->nsum = S_NBASE + s->nang;
  if ((rc = read_transient(ctx, s))) return rc;
  if ((rc = read_ensemble(ctx, s))) return rc;
  return CLI_EXIT_OK;
}

/* ---- one member ------------------------------------------------------------------------------ */
typedef struct ens_series {
  size_t n, cap, ncols;
  double *t, *rows;
} ens_series;

/* Per-thread workspace: a transient driver, state and output buffers, the member's model. */
typedef struct ens_worker {
  const ens_spec *s;
  autobal_transient *tr;
  double *y, *out, *row;
  double *bpsi, *brate, *bdamp;   /* per-member ball arrays (n_balls each) */
  autobal_rotor *rot;             /* the current member's handle */
  autobal_pendulum_motion motion; /* the current member's pendulum */
  double omega;
  double amp_max;
  ens_series *ser;                /* series being recorded (NULL: none) */
  autobal_error err;
} ens_worker;

static void worker_free(ens_worker *w) {
  autobal_transient_free(w->tr);
  autobal_rotor_free(w->rot);
  free(w->y);
  free(w->out);
  free(w->row);
  free(w->bpsi);
  free(w->brate);
  free(w->bdamp);
  memset(w, 0, sizeof *w);
}

static int worker_init(ens_worker *w, const ens_spec *s) {
  autobal_transient_options opt = autobal_transient_options_default();
  size_t nb = s->n_balls ? s->n_balls : 1;
  memset(w, 0, sizeof *w);
  w->s = s;
  autobal_error_clear(&w->err);
  opt.stepper = s->stepper, opt.rtol = s->rtol, opt.atol = s->atol, opt.h_max = s->h_max;
  opt.max_steps = (unsigned long)s->max_steps;
  w->tr = autobal_transient_alloc(s->dim, &opt, &w->err);
  w->y = calloc(s->dim, sizeof *w->y);
  w->out = calloc(s->nout ? s->nout : 1, sizeof *w->out);
  w->row = calloc(s->ncols, sizeof *w->row);
  w->bpsi = calloc(nb, sizeof *w->bpsi);
  w->brate = calloc(nb, sizeof *w->brate);
  w->bdamp = calloc(nb, sizeof *w->bdamp);
  if (!w->tr || !w->y || !w->out || !w->row || !w->bpsi || !w->brate || !w->bdamp) {
    worker_free(w);
    return -1;
  }
  return 0;
}

static void series_push(ens_series *sr, double t, const double *row) {
  if (!sr || sr->n >= sr->cap) return;
  sr->t[sr->n] = t;
  memcpy(sr->rows + sr->n * sr->ncols, row, sr->ncols * sizeof *row);
  sr->n++;
}

static int rotor_observer(double t, const double y[], void *user) {
  ens_worker *w = user;
  const ens_spec *s = w->s;
  if (autobal_rotor_outputs(w->rot, s->frame, t, y, w->out, s->nout) != AUTOBAL_SUCCESS) return 1;
  if (w->out[0] > w->amp_max) w->amp_max = w->out[0];
  if (w->ser) {
    memcpy(w->row, y, s->dim * sizeof *y);
    memcpy(w->row + s->dim, w->out, s->nout * sizeof *w->out);
    series_push(w->ser, t, w->row);
  }
  return 0;
}

static double rotor_monitor(double t, const double y[], void *user) {
  ens_worker *w = user;
  return autobal_rotor_balance_monitor(w->rot, w->s->frame, t, y);
}

static int pend_observer(double tau, const double y[], void *user) {
  ens_worker *w = user;
  autobal_pendulum_motion_derived d;
  autobal_pendulum_motion_derive(&w->motion.p, y, &d);
  if (d.amplitude > w->amp_max) w->amp_max = d.amplitude;
  if (w->ser) {
    memcpy(w->row, y, 8 * sizeof *y);
    w->row[8] = d.amplitude, w->row[9] = d.unbalance, w->row[10] = d.unbalance_u, w->row[11] = d.unbalance_v;
    w->row[12] = d.alpha, w->row[13] = d.beta, w->row[14] = d.jacobi;
    series_push(w->ser, tau, w->row);
  }
  return 0;
}

/* Cancel a running member on SIGINT/SIGTERM. */
static int member_progress(double fraction, void *user) {
  (void)fraction;
  (void)user;
  return cli_interrupted();
}

/* Output interval and revolution period of a member (omega or R_w may vary). */
static int member_timing(const ens_spec *s, double speed, double *dt_out, double *dwell) {
  double rev = fabs(speed) > 0 ? TWO_PI / fabs(speed) : INFINITY;
  *dt_out = s->use_revs_out ? s->revs_out * rev : s->dt_out;
  *dwell = s->use_dwell ? s->balance_dwell : (s->balance_revs > 0 ? s->balance_revs * rev : 0.0);
  if (!(*dt_out > 0 && isfinite(*dt_out)) || !isfinite(*dwell)) return AUTOBAL_EINVAL;
  return AUTOBAL_SUCCESS;
}

/* Upper bound of the observer calls of a member: t0 + k dt_out < t1 and t1. */
static size_t series_rows_max(const ens_spec *s, double dt_out) {
  return (size_t)floor(s->t_end / dt_out * (1 + 1e-12)) + 2;
}

/* The speed of member m (for its timing). */
static double member_speed(const ens_spec *s, size_t m) {
  size_t j;
  double v = s->model == MODEL_ROTOR ? s->rp.omega : s->pp.R_w;
  for (j = 0; j < s->nparam; j++)
    if (s->par[j].kind == P_R_OMEGA || s->par[j].kind == P_P_RW) v = member_value(s, m, j);
  return v;
}

/* Set up the member's model in w.  Returns AUTOBAL_SUCCESS or a failure status (the member then
 * fails with that status; message in w->err). */
static int member_model(ens_worker *w, size_t m) {
  const ens_spec *s = w->s;
  size_t j;
  autobal_error_clear(&w->err);
  if (s->model == MODEL_ROTOR) {
    autobal_rotor_params p = s->rp;
    size_t pl, off = 0;
    for (pl = 0; pl < p.n_planes; pl++) {
      const autobal_rotor_plane *b = &s->rp.plane[pl];
      size_t i;
      for (i = 0; i < b->n_balls; i++) {
        w->bpsi[off + i] = b->ball_psi ? b->ball_psi[i] : 0.0;
        w->brate[off + i] = b->ball_rate ? b->ball_rate[i] : 0.0;
        w->bdamp[off + i] = b->ball_damping[i];
      }
      p.plane[pl].ball_psi = w->bpsi + off;
      p.plane[pl].ball_rate = w->brate + off;
      p.plane[pl].ball_damping = w->bdamp + off;
      off += b->n_balls;
    }
    for (j = 0; j < s->nparam; j++) {
      const ens_param *q = &s->par[j];
      double v = member_value(s, m, j);
      size_t i;
      switch (q->kind) {
        case P_R_PSI: w->bpsi[q->index] = v; break;
        case P_R_RATE: w->brate[q->index] = v; break;
        case P_R_OMEGA: p.omega = v; break;
        case P_R_DAMPING:
          for (i = 0; i < s->n_balls; i++) w->bdamp[i] = v;
          break;
        case P_R_M0: p.plane[0].m0 = v; break;
        case P_R_X: p.q0[0] = v; break;
        case P_R_Y: p.q0[1] = v; break;
        default: break;
      }
    }
    autobal_rotor_free(w->rot);
    w->rot = autobal_rotor_alloc(&p, &w->err);
    if (!w->rot) return w->err.status < 0 ? w->err.status : AUTOBAL_EINVAL;
    w->omega = p.omega;
    return autobal_rotor_initial_state(w->rot, s->frame, 0.0, w->y, s->dim);
  } else {
    autobal_pendulum_params p = s->pp;
    int k_given = 0;
    double k = 0;
    memcpy(w->y, s->y0, sizeof s->y0);
    for (j = 0; j < s->nparam; j++) {
      const ens_param *q = &s->par[j];
      double v = member_value(s, m, j);
      switch (q->kind) {
        case P_P_STATE: w->y[q->index] = v; break;
        case P_P_RW: p.R_w = v; break;
        case P_P_RM: p.R_m = v; break;
        case P_P_H: p.H = v; break;
        case P_P_HS: p.h = v; break;
        case P_P_PSI0: p.psi0 = v; break;
        case P_P_K: k_given = 1, k = v; break;
        default: break;
      }
    }
    if (k_given) {
      int st = autobal_pendulum_params_from_k(p.R_w, p.R_m, p.H, p.h, k, &p, &w->err);
      if (st != AUTOBAL_SUCCESS) return st;
    }
    w->omega = p.R_w;
    return autobal_pendulum_motion_init(&w->motion, &p, &w->err);
  }
}

/* Run member m: rec[0..nsum-1] receives its summary; when sr is not NULL (sized by the caller)
 * the series.  Returns 1 when the member is finished (successfully or not: failures are results),
 * 0 when it was cancelled (not done). */
static int run_member(ens_worker *w, size_t m, double *rec, ens_series *sr) {
  const ens_spec *s = w->s;
  autobal_transient_options opt;
  autobal_transient_system sys;
  autobal_transient_stats stats;
  autobal_transient_event_hit hit;
  double dt_out, dwell, t_reached = 0.0;
  size_t i;
  int st, ev;

  for (i = 0; i < s->nsum; i++) rec[i] = NAN;
  rec[S_BALANCED] = 0;
  rec[S_STEPS] = 0;
  rec[S_RHS] = 0;
  w->amp_max = 0;
  w->ser = sr;
  st = member_model(w, m);
  if (st == AUTOBAL_SUCCESS) st = member_timing(s, w->omega, &dt_out, &dwell);
  if (st != AUTOBAL_SUCCESS) {
    rec[S_STATUS] = st < 0 ? st : AUTOBAL_EINVAL;
    return 1;
  }
  opt = autobal_transient_options_default();
  opt.stepper = s->stepper, opt.rtol = s->rtol, opt.atol = s->atol, opt.h_max = s->h_max;
  opt.max_steps = (unsigned long)s->max_steps;
  opt.dt_out = dt_out;
  opt.event_tol = 1e-9 * s->t_end;
  if ((st = autobal_transient_set_options(w->tr, &opt)) != AUTOBAL_SUCCESS) {
    rec[S_STATUS] = st;
    return 1;
  }
  autobal_transient_clear_events(w->tr);
  autobal_transient_set_progress(w->tr, member_progress, w);
  sys.jac = NULL;
  sys.dim = s->dim;
  if (s->model == MODEL_ROTOR) {
    sys.rhs = s->frame == AUTOBAL_ROTOR_FIXED ? autobal_rotor_rhs : autobal_rotor_rhs_rotating;
    sys.params = w->rot;
    autobal_transient_set_observer(w->tr, rotor_observer, w);
    rec[S_RES0] = autobal_rotor_balance_monitor(w->rot, s->frame, 0.0, w->y);
    ev = autobal_transient_add_dwell_event(w->tr, rotor_monitor, w, s->balance_tol, dwell, s->stop_at_balance);
  } else {
    sys.rhs = autobal_pendulum_motion_rhs;
    sys.jac = autobal_pendulum_motion_jac;
    sys.params = &w->motion;
    autobal_transient_set_observer(w->tr, pend_observer, w);
    rec[S_RES0] = autobal_pendulum_residual_unbalance(&w->motion.p, w->y, NULL, NULL);
    ev = autobal_transient_add_dwell_event(w->tr, autobal_pendulum_unbalance_scalar, &w->motion.p, s->balance_tol,
                                           dwell, s->stop_at_balance);
  }
  if (ev < 0) {
    rec[S_STATUS] = ev;
    return 1;
  }
  st = autobal_transient_run(w->tr, &sys, 0.0, s->t_end, w->y, &t_reached);
  if (st == AUTOBAL_ECANCELLED) return 0;
  autobal_transient_get_stats(w->tr, &stats);
  rec[S_STATUS] = st;
  rec[S_TREACHED] = t_reached;
  rec[S_STEPS] = (double)stats.steps;
  rec[S_RHS] = (double)stats.rhs_evals;
  if (autobal_transient_event_result(w->tr, (size_t)ev, NULL, &hit) == 1) {
    rec[S_BALANCED] = 1;
    rec[S_TTB] = hit.t_start;
  }
  if (s->model == MODEL_ROTOR) {
    rec[S_RES1] = autobal_rotor_balance_monitor(w->rot, s->frame, t_reached, w->y);
    if (autobal_rotor_outputs(w->rot, s->frame, t_reached, w->y, w->out, s->nout) == AUTOBAL_SUCCESS)
      rec[S_AMP1] = w->out[0];
    for (i = 0; i < s->n_balls; i++) {
      double a = s->frame == AUTOBAL_ROTOR_FIXED ? w->y[8 + i] - w->omega * t_reached : w->y[8 + i];
      rec[S_NBASE + i] = remainder(a, TWO_PI);
    }
  } else {
    autobal_pendulum_motion_derived d;
    autobal_pendulum_motion_derive(&w->motion.p, w->y, &d);
    rec[S_RES1] = d.unbalance;
    rec[S_AMP1] = d.amplitude;
    rec[S_NBASE] = d.alpha;
    rec[S_NBASE + 1] = d.beta;
  }
  if (rec[S_AMP1] > w->amp_max) w->amp_max = rec[S_AMP1];
  rec[S_AMPMAX] = w->amp_max;
  w->ser = NULL;
  return 1;
}

/* ---- records, the result store, journals --------------------------------------------------- */
typedef struct ens_buf {
  double *v;
  size_t n, cap;
} ens_buf;

static int buf_reserve(ens_buf *b, size_t extra) {
  if (b->n + extra > b->cap) {
    size_t cap = b->cap ? b->cap : 1024;
    double *nv;
    while (cap < b->n + extra) cap *= 2;
    nv = realloc(b->v, cap * sizeof *nv);
    if (!nv) return -1;
    b->v = nv;
    b->cap = cap;
  }
  return 0;
}

/* Append a record; returns its offset or (size_t)-1 (no memory). */
static size_t record_append(ens_buf *b, const ens_spec *s, size_t m, const double *rec, const ens_series *sr) {
  size_t nrows = sr ? sr->n : 0, len = 5 + s->nsum + nrows * (1 + s->ncols), off = b->n;
  double *p;
  if (buf_reserve(b, len)) return (size_t)-1;
  p = b->v + off;
  p[0] = (double)m;
  p[1] = (double)s->nsum;
  p[2] = (double)nrows;
  p[3] = sr ? (double)s->ncols : 0.0;
  memcpy(p + 4, rec, s->nsum * sizeof *rec);
  p += 4 + s->nsum;
  if (nrows) {
    memcpy(p, sr->t, nrows * sizeof *p);
    memcpy(p + nrows, sr->rows, nrows * s->ncols * sizeof *p);
    p += nrows * (1 + s->ncols);
  }
  p[0] = (double)m;
  b->n += len;
  return off;
}

typedef struct ens_store {
  size_t n;
  unsigned char *done;
  double *sum;     /* n * nsum (rank 0 only) */
  ens_series *ser; /* n_keep slots (rank 0 only) */
  size_t n_done;
} ens_store;

static long keep_slot(const ens_spec *s, size_t m) {
  size_t lo = 0, hi = s->n_keep;
  while (lo < hi) {
    size_t mid = (lo + hi) / 2;
    if (s->keep[mid] == m) return (long)mid;
    if (s->keep[mid] < m) lo = mid + 1;
    else hi = mid;
  }
  return -1;
}

static void store_free(ens_store *st, const ens_spec *s) {
  size_t i;
  if (st->ser)
    for (i = 0; i < s->n_keep; i++) {
      free(st->ser[i].t);
      free(st->ser[i].rows);
    }
  free(st->ser);
  free(st->done);
  free(st->sum);
  memset(st, 0, sizeof *st);
}

static int store_init(ens_store *st, const ens_spec *s, int with_data) {
  memset(st, 0, sizeof *st);
  st->n = s->n_members;
  st->done = calloc(s->n_members, 1);
  if (!st->done) return -1;
  if (with_data) {
    st->sum = malloc(s->n_members * s->nsum * sizeof *st->sum);
    st->ser = calloc(s->n_keep ? s->n_keep : 1, sizeof *st->ser);
    if (!st->sum || !st->ser) return -1;
  }
  return 0;
}

/* Parse records from buf[0..n): each valid record of a member not yet done is stored.  Returns
 * the number of doubles that form complete, valid records (parsing stops at the first invalid
 * or truncated one); *nomem set on allocation failure. */
static size_t parse_records(const ens_spec *s, ens_store *st, const double *buf, size_t n, int *nomem) {
  size_t pos = 0;
  while (pos + 5 + s->nsum <= n) {
    const double *p = buf + pos;
    double md = p[0], nrd = p[2], ncd = p[3];
    size_t m, nrows, ncols, len;
    if (!(md >= 0 && md < (double)s->n_members && md == floor(md))) break;
    if (p[1] != (double)s->nsum) break;
    if (!(nrd >= 0 && nrd <= (double)ENS_MAX_SERIES_DOUBLES && nrd == floor(nrd))) break;
    if (!(ncd == 0 || ncd == (double)s->ncols)) break;
    m = (size_t)md, nrows = (size_t)nrd, ncols = (size_t)ncd;
    if (nrows > 0 && ncols == 0) break;
    len = 5 + s->nsum + nrows * (1 + ncols);
    if (pos + len > n || buf[pos + len - 1] != md) break;
    if (!st->done[m]) {
      st->done[m] = 1;
      st->n_done++;
      if (st->sum) {
        long slot = keep_slot(s, m);
        memcpy(st->sum + m * s->nsum, p + 4, s->nsum * sizeof *p);
        if (slot >= 0 && nrows > 0) {
          ens_series *sr = &st->ser[slot];
          sr->t = malloc(nrows * sizeof *sr->t);
          sr->rows = malloc(nrows * ncols * sizeof *sr->rows);
          if (!sr->t || !sr->rows) {
            *nomem = 1;
            return pos;
          }
          memcpy(sr->t, p + 4 + s->nsum, nrows * sizeof *p);
          memcpy(sr->rows, p + 4 + s->nsum + nrows, nrows * ncols * sizeof *p);
          sr->n = sr->cap = nrows;
          sr->ncols = ncols;
        }
      }
    }
    pos += len;
  }
  return pos;
}

#define JOURNAL_HEADER 48
static const char journal_magic[8] = {'A', 'B', 'E', 'N', 'S', 'J', '0', '1'};

static void journal_header(const ens_spec *s, unsigned char hdr[JOURNAL_HEADER]) {
  uint64_t v[5];
  v[0] = s->hash, v[1] = s->n_members, v[2] = s->nsum, v[3] = s->ncols, v[4] = 0;
  memcpy(hdr, journal_magic, 8);
  memcpy(hdr + 8, v, sizeof v);
}

/* The journals of `output`: files named <output>.journal-<digits> in its directory. */
static int journal_list(const char *output, char ***paths, size_t *n) {
  const char *slash = strrchr(output, '/');
  char dir[4096], prefix[1024];
  DIR *d;
  struct dirent *e;
  size_t cap = 0;
  *paths = NULL;
  *n = 0;
  if (slash) snprintf(dir, sizeof dir, "%.*s", (int)(slash - output) + 1, output);
  else snprintf(dir, sizeof dir, "./");
  snprintf(prefix, sizeof prefix, "%s.journal-", slash ? slash + 1 : output);
  d = opendir(dir);
  if (!d) return errno == ENOENT ? 0 : -1;
  while ((e = readdir(d)) != NULL) {
    size_t lp = strlen(prefix);
    const char *q;
    if (strncmp(e->d_name, prefix, lp) != 0 || !e->d_name[lp]) continue;
    for (q = e->d_name + lp; *q >= '0' && *q <= '9'; q++) {
    }
    if (*q) continue;
    if (*n == cap) {
      char **np = realloc(*paths, (cap = cap ? 2 * cap : 8) * sizeof *np);
      if (!np) break;
      *paths = np;
    }
    (*paths)[*n] = malloc(strlen(dir) + strlen(e->d_name) + 1);
    if (!(*paths)[*n]) break;
    sprintf((*paths)[*n], "%s%s", dir, e->d_name);
    (*n)++;
  }
  closedir(d);
  if (*n > 1) qsort(*paths, *n, sizeof **paths, cmp_str);
  return 0;
}

static void free_list(char **paths, size_t n) {
  size_t i;
  for (i = 0; i < n; i++) free(paths[i]);
  free(paths);
}

/* Read one journal into the store.  *valid receives the length of its valid prefix in bytes (0: no
 * usable header).  Returns a CLI exit code (message in ctx). */
static int journal_load(cli_ctx *ctx, const ens_spec *s, ens_store *st, const char *path, long *valid) {
  FILE *f = fopen(path, "rb");
  unsigned char hdr[JOURNAL_HEADER], want[JOURNAL_HEADER];
  double *buf = NULL;
  size_t nd, got, used;
  long size;
  int nomem = 0;
  *valid = 0;
  if (!f) return cli_fail(ctx, CLI_EXIT_IO, "cannot read the journal '%s': %s", path, strerror(errno));
  if (fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
    fclose(f);
    return cli_fail(ctx, CLI_EXIT_IO, "cannot read the journal '%s': %s", path, strerror(errno));
  }
  if (size < JOURNAL_HEADER || fread(hdr, 1, JOURNAL_HEADER, f) != JOURNAL_HEADER) {
    fclose(f);
    return CLI_EXIT_OK; /* killed before the header was complete: empty */
  }
  journal_header(s, want);
  if (memcmp(hdr, journal_magic, 8) != 0) {
    fclose(f);
    return cli_fail(ctx, CLI_EXIT_IO, "'%s' is not an autobal ensemble journal", path);
  }
  if (memcmp(hdr, want, JOURNAL_HEADER) != 0) {
    fclose(f);
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "the journal '%s' was written for a different configuration (or autobal version); "
                    "resume with the same configuration, or start over with --force",
                    path);
  }
  nd = (size_t)(size - JOURNAL_HEADER) / sizeof(double);
  buf = malloc((nd ? nd : 1) * sizeof *buf);
  if (!buf) {
    fclose(f);
    return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory reading '%s'", path);
  }
  got = fread(buf, sizeof *buf, nd, f);
  fclose(f);
  used = parse_records(s, st, buf, got, &nomem);
  free(buf);
  if (nomem) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory reading '%s'", path);
  *valid = (long)(JOURNAL_HEADER + used * sizeof(double));
  return CLI_EXIT_OK;
}

/* ---- MPI ------------------------------------------------------------------------------------- */
typedef struct ens_mpi {
  int rank, size, inited_here;
} ens_mpi;

static void mpi_begin(ens_mpi *mp) {
  mp->rank = 0, mp->size = 1, mp->inited_here = 0;
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

/* Wait for every rank without spinning: a rank that finished its share early sleeps instead of
 * burning the core that a rank still computing (or its OpenMP threads) may share. */
static void mpi_idle_barrier(const ens_mpi *mp) {
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) {
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
  (void)mp;
}

static int mpi_any(const ens_mpi *mp, int flag) {
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) {
    int all = flag;
    MPI_Allreduce(&flag, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return all;
  }
#endif
  (void)mp;
  return flag;
}

#ifdef AUTOBAL_HAVE_MPI
#define ENS_CHUNK (1 << 24) /* doubles per message */
#endif

/* Send every rank's outbox to rank 0, which parses them into its store.  Returns a CLI exit code. */
static int gather_records(cli_ctx *ctx, const ens_mpi *mp, const ens_spec *s, ens_store *st, const ens_buf *out) {
  int nomem = 0, bad = 0;
  if (mp->rank == 0 && parse_records(s, st, out->v, out->n, &nomem) != out->n) bad = 1;
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) {
    int r;
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
        if (!nomem && !bad && parse_records(s, st, buf, (size_t)len, &nomem) != len) bad = 1;
        free(buf);
      }
    } else {
      unsigned long long len = out->n;
      size_t off;
      MPI_Send(&len, 1, MPI_UNSIGNED_LONG_LONG, 0, 1, MPI_COMM_WORLD);
      for (off = 0; off < out->n; off += ENS_CHUNK) {
        size_t c = out->n - off < ENS_CHUNK ? out->n - off : ENS_CHUNK;
        MPI_Send(out->v + off, (int)c, MPI_DOUBLE, 0, 2, MPI_COMM_WORLD);
      }
    }
  }
#endif
  if (nomem) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory collecting the members' results");
  if (bad) return cli_fail(ctx, CLI_EXIT_INTERNAL, "a member's result record is damaged");
  return CLI_EXIT_OK;
}

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the parallel part ----------------------------------------------------------------------- */
typedef struct ens_run {
  cli_ctx *ctx;
  const ens_spec *s;
  const size_t *mine;   /* this rank's members */
  size_t n_mine;
  FILE *journal;        /* NULL: none */
  ens_buf outbox;       /* records of the members finished here */
  size_t finished;      /* members finished here */
  int threads;
  int fatal;            /* CLI exit code of a failure that stops the run */
  char fatal_msg[512];
  double t_start;
} ens_run;

static void compute(ens_run *R) {
  const ens_spec *s = R->s;
  long k, n = (long)R->n_mine;
  int nth = R->threads;
  (void)nth;
  ENS_PRAGMA(omp parallel num_threads(nth))
  {
    ens_worker w;
    double *rec = malloc(s->nsum * sizeof *rec);
    int ok = worker_init(&w, s) == 0 && rec;
    if (!ok) {
      ENS_PRAGMA(omp critical(ens_out))
      if (!R->fatal) {
        R->fatal = CLI_EXIT_INTERNAL;
        snprintf(R->fatal_msg, sizeof R->fatal_msg, "out of memory (worker)");
      }
    }
    ENS_PRAGMA(omp for schedule(dynamic, 1))
    for (k = 0; k < n; k++) {
      size_t m = R->mine[k];
      ens_series sr, *srp = NULL;
      int done, stop;
      ENS_PRAGMA(omp atomic read)
      stop = R->fatal;
      if (!ok || stop || cli_interrupted()) continue;
      if (s->time_limit > 0 && now_seconds() - R->t_start > s->time_limit) continue;
      memset(&sr, 0, sizeof sr);
      if (keep_slot(s, m) >= 0) {
        double dt_out, dwell;
        if (member_timing(s, member_speed(s, m), &dt_out, &dwell) == AUTOBAL_SUCCESS) {
          sr.cap = series_rows_max(s, dt_out);
          sr.ncols = s->ncols;
          sr.t = malloc(sr.cap * sizeof *sr.t);
          sr.rows = malloc(sr.cap * s->ncols * sizeof *sr.rows);
          if (!sr.t || !sr.rows) {
            free(sr.t);
            free(sr.rows);
            ENS_PRAGMA(omp critical(ens_out))
            if (!R->fatal) {
              R->fatal = CLI_EXIT_INTERNAL;
              snprintf(R->fatal_msg, sizeof R->fatal_msg, "out of memory (series of member %zu)", m);
            }
            continue;
          }
          srp = &sr;
        }
      }
      done = run_member(&w, m, rec, srp);
      if (done) {
        ENS_PRAGMA(omp critical(ens_out))
        {
          size_t off = record_append(&R->outbox, s, m, rec, srp);
          if (off == (size_t)-1) {
            if (!R->fatal) {
              R->fatal = CLI_EXIT_INTERNAL;
              snprintf(R->fatal_msg, sizeof R->fatal_msg, "out of memory (results)");
            }
          } else {
            R->finished++;
            if (R->journal && !R->fatal) {
              size_t len = R->outbox.n - off;
              if (fwrite(R->outbox.v + off, sizeof(double), len, R->journal) != len || fflush(R->journal) != 0) {
                R->fatal = CLI_EXIT_IO;
                snprintf(R->fatal_msg, sizeof R->fatal_msg, "writing the journal failed: %s", strerror(errno));
              }
            }
            if (R->n_mine) cli_progress(R->ctx, "ensemble", (double)R->finished / (double)R->n_mine);
          }
        }
      }
      free(sr.t);
      free(sr.rows);
    }
    worker_free(&w);
    free(rec);
  }
}

/* ---- the archive (rank 0) -------------------------------------------------------------------- */
typedef struct ens_tally {
  size_t done, failed, ok, balanced;
  double p, p_se, ttb_mean, ttb_median, ttb_max;
} ens_tally;

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static void tally(const ens_spec *s, const ens_store *st, ens_tally *t) {
  size_t m, nb = 0;
  double *ttb = malloc((s->n_members ? s->n_members : 1) * sizeof *ttb), sum = 0;
  memset(t, 0, sizeof *t);
  t->p = t->p_se = t->ttb_mean = t->ttb_median = t->ttb_max = NAN;
  for (m = 0; m < s->n_members; m++) {
    const double *r = st->sum + m * s->nsum;
    if (!st->done[m]) continue;
    t->done++;
    if (r[S_STATUS] < 0) {
      t->failed++;
      continue;
    }
    t->ok++;
    if (r[S_BALANCED] == 1) {
      t->balanced++;
      sum += r[S_TTB];
      if (ttb) ttb[nb++] = r[S_TTB];
    }
  }
  if (t->ok) {
    t->p = (double)t->balanced / (double)t->ok;
    t->p_se = sqrt(t->p * (1 - t->p) / (double)t->ok);
  }
  if (t->balanced) t->ttb_mean = sum / (double)t->balanced;
  if (ttb && nb) {
    qsort(ttb, nb, sizeof *ttb, cmp_double);
    t->ttb_median = nb % 2 ? ttb[nb / 2] : 0.5 * (ttb[nb / 2 - 1] + ttb[nb / 2]);
    t->ttb_max = ttb[nb - 1];
  }
  free(ttb);
}

/* Column names of a kept series. */
static int series_names(const ens_spec *s, char (*names)[64], const char **units, const char **lnames) {
  size_t k;
  if (s->model == MODEL_PENDULUM) {
    static const char *const n[ENS_PEND_NCOLS] = {"xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate",
                                                  "amplitude", "unbalance", "unbalance_u", "unbalance_v", "alpha", "beta",
                                                  "jacobi"};
    static const char *const u[ENS_PEND_NCOLS] = {"1", "1", "rad", "rad", "1", "1", "rad", "rad",
                                                  "1", "1", "1", "1", "rad", "rad", "1"};
    for (k = 0; k < ENS_PEND_NCOLS; k++) {
      snprintf(names[k], 64, "%s", n[k]);
      units[k] = u[k];
      lnames[k] = NULL;
    }
    return AUTOBAL_SUCCESS;
  } else {
    static const char *const q[8] = {"x", "y", "alpha", "beta", "x_rate", "y_rate", "alpha_rate", "beta_rate"};
    static const char *const qu[8] = {"m", "m", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s"};
    const int fixed = s->frame == AUTOBAL_ROTOR_FIXED;
    size_t nb = s->n_balls;
    autobal_error err;
    autobal_rotor *rot = autobal_rotor_alloc(&s->rp, &err);
    int st = AUTOBAL_SUCCESS;
    if (!rot) return AUTOBAL_EINVAL;
    for (k = 0; k < s->dim; k++) {
      lnames[k] = NULL;
      if (k < 8) snprintf(names[k], 64, "%s", q[k]), units[k] = qu[k];
      else if (k < 8 + nb) snprintf(names[k], 64, fixed ? "state_phi_%zu" : "state_psi_%zu", k - 8 + 1), units[k] = "rad";
      else if (k < 8 + 2 * nb)
        snprintf(names[k], 64, fixed ? "state_phi_rate_%zu" : "state_psi_rate_%zu", k - 8 - nb + 1), units[k] = "rad/s";
      else if (k == 8 + 2 * nb) snprintf(names[k], 64, "z"), units[k] = "m";
      else snprintf(names[k], 64, "z_rate"), units[k] = "m/s";
    }
    for (k = 0; k < s->nout && !st; k++) {
      st = autobal_rotor_output_name(rot, k, names[s->dim + k], 64, &units[s->dim + k]);
      lnames[s->dim + k] = NULL;
    }
    autobal_rotor_free(rot);
    return st;
  }
}

static int write_archive(cli_ctx *ctx, autobal_archive *a, const ens_spec *s, const ens_store *st, const ens_tally *t,
                         const ens_mpi *mp, int threads, double wall) {
  char g[64], buf[256];
  const int rotor = s->model == MODEL_ROTOR;
  const char *tu = rotor ? "s" : "1", *lu = rotor ? "m" : "1";
  const char *dims[ENS_MAX_PARAMS + 1];
  int rank, rc = CLI_EXIT_OK, e = AUTOBAL_SUCCESS;
  size_t n = s->n_members, m, j, i;
  double *dv = NULL, *ang = NULL;
  int *iv = NULL;
  snprintf(g, sizeof g, "/%s/ensemble", s->mname);
  if (rotor) e = cli_write_rotor_params(a, &s->rp, 1);
  else if ((rc = cli_write_pendulum_params(ctx, a, &s->pp, &s->phys, s->physical))) return rc;
  if (!e) e = autobal_archive_group(a, g);
  /* settings */
#define AS(name, v) do { if (!e) e = autobal_archive_attr_string(a, g, name, v); } while (0)
#define AD(name, v, u) do { if (!e) e = autobal_archive_attr_double(a, g, name, v, u); } while (0)
#define AI(name, v) do { if (!e) e = autobal_archive_attr_int(a, g, name, (long)(v)); } while (0)
  AS("mode", s->random ? "random" : "grid");
  buf[0] = '\0';
  for (j = 0; j < s->nparam; j++) {
    size_t l = strlen(buf);
    snprintf(buf + l, sizeof buf - l, "%s%s", j ? ", " : "", s->par[j].name);
  }
  AS("parameters", buf);
  AI("n_members", n);
  if (s->random) {
    snprintf(buf, sizeof buf, "%llu", (unsigned long long)s->seed);
    AS("seed", buf);
    AS("sampler", "splitmix64: member m, parameter j <- output m*nparam + j; min + (max - min) (x >> 11) 2^-53");
    for (j = 0; j < s->nparam; j++) {
      char nm[64];
      snprintf(nm, sizeof nm, "%s_min", s->par[j].name);
      AD(nm, s->par[j].lo, s->par[j].units);
      snprintf(nm, sizeof nm, "%s_max", s->par[j].name);
      AD(nm, s->par[j].hi, s->par[j].units);
    }
  } else {
    AI("endpoint", s->endpoint);
    AS("member_order", "row-major over the parameter axes (the last one varies fastest)");
  }
  AD("t_end", s->t_end, tu);
  if (s->use_revs_out) AD("revs_out", s->revs_out, "1");
  else AD("dt_out", s->dt_out, tu);
  AD("rtol", s->rtol, "1");
  AD("atol", s->atol, "1");
  AD("h_max", s->h_max, tu);
  AI("max_steps", s->max_steps);
  AS("stepper", s->stepper);
  AD("balance_tol", s->balance_tol, "1");
  if (s->use_dwell) AD("balance_dwell", s->balance_dwell, tu);
  else AD("balance_revs", s->balance_revs, "1");
  AI("stop_at_balance", s->stop_at_balance);
  if (rotor) AS("frame", s->frame_name);
  else if (!e) e = autobal_archive_attr_double_array(a, g, "initial_state", 8, s->y0, "1");
  /* results */
  AI("n_done", t->done);
  AI("n_failed", t->failed);
  AI("n_balanced", t->balanced);
  AD("probability_balanced", t->p, "1");
  AD("probability_balanced_stderr", t->p_se, "1");
  AD("time_to_balance_mean", t->ttb_mean, tu);
  AD("time_to_balance_median", t->ttb_median, tu);
  AD("time_to_balance_max", t->ttb_max, tu);
  AS("probability_definition", "n_balanced / (n_done - n_failed): members that ran without failure; stderr sqrt(p (1 - p) / n)");
  /* axes */
  if (s->random) {
    if (!e) e = autobal_archive_dim(a, g, "member", n, "ensemble member");
    dims[0] = "member";
    rank = 1;
  } else {
    for (j = 0; j < s->nparam && !e; j++) {
      double *v = malloc(s->par[j].n * sizeof *v);
      if (!v) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
      for (i = 0; i < s->par[j].n; i++) v[i] = grid_value(&s->par[j], i, s->endpoint);
      e = autobal_archive_coord(a, g, s->par[j].name, s->par[j].n, v, s->par[j].units, s->par[j].long_name);
      free(v);
      dims[j] = s->par[j].name;
    }
    rank = (int)s->nparam;
  }
  dv = malloc((n ? n : 1) * sizeof *dv);
  iv = malloc((n ? n : 1) * sizeof *iv);
  ang = malloc((n ? n : 1) * (s->nang ? s->nang : 1) * sizeof *ang);
  if (!dv || !iv || !ang) {
    free(dv), free(iv), free(ang);
    return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  }
  if (s->random)
    for (j = 0; j < s->nparam && !e; j++) {
      for (m = 0; m < n; m++) dv[m] = member_value(s, m, j);
      e = autobal_archive_var(a, g, s->par[j].name, 1, dims, dv, s->par[j].units, s->par[j].long_name);
    }
  {
    static const struct {
      int col;
      const char *name, *lname;
      int unit; /* 0 "1", 1 time, 2 length */
    } dvars[] = {
        {S_TTB, "time_to_balance", "time from which the residual unbalance stayed below balance_tol (NaN: not balanced)", 1},
        {S_RES0, "residual_unbalance_initial", "relative residual unbalance at the start", 0},
        {S_RES1, "residual_unbalance_final", "relative residual unbalance at the end of the run", 0},
        {S_AMPMAX, "amplitude_max", "largest sampled displacement amplitude of the shaft / centre of mass", 2},
        {S_AMP1, "amplitude_final", "displacement amplitude at the end of the run", 2},
        {S_TREACHED, "t_reached", "time reached (t_end, the balancing stop, or the failure)", 1},
        {S_STEPS, "steps", "accepted solver steps", 0},
        {S_RHS, "rhs_evaluations", "right-hand-side evaluations", 0}};
    static const struct {
      int col;
      const char *name, *lname;
    } ivars[] = {{S_STATUS, "status", "solver status: 0 reached t_end, 2 stopped at balance (AUTOBAL_EVENT), < 0 failure (autobal status code, e.g. -5 AUTOBAL_EMAXSTEPS)"},
                 {S_BALANCED, "balanced", "1: balanced (the residual unbalance stayed below balance_tol for the dwell)"}};
    const char *u3[3];
    u3[0] = "1", u3[1] = tu, u3[2] = lu;
    for (i = 0; i < sizeof ivars / sizeof ivars[0] && !e; i++) {
      for (m = 0; m < n; m++) {
        double v = st->sum[m * s->nsum + (size_t)ivars[i].col];
        iv[m] = st->done[m] && isfinite(v) ? (int)v : 0;
      }
      e = autobal_archive_var_int(a, g, ivars[i].name, rank, dims, iv, "1", ivars[i].lname);
    }
    for (m = 0; m < n; m++) iv[m] = st->done[m];
    if (!e) e = autobal_archive_var_int(a, g, "done", rank, dims, iv, "1", "1: the member was computed (0: still to do; see resume)");
    for (i = 0; i < sizeof dvars / sizeof dvars[0] && !e; i++) {
      for (m = 0; m < n; m++) dv[m] = st->done[m] ? st->sum[m * s->nsum + (size_t)dvars[i].col] : NAN;
      e = autobal_archive_var(a, g, dvars[i].name, rank, dims, dv, u3[dvars[i].unit], dvars[i].lname);
    }
  }
  if (s->nang && !e) {
    const char *an = rotor ? "ball" : "pendulum";
    e = autobal_archive_dim(a, g, an, s->nang, rotor ? "ball (plane 1 first)" : "pendulum (1: psi, 2: phi)");
    for (m = 0; m < n; m++)
      for (i = 0; i < s->nang; i++) ang[m * s->nang + i] = st->done[m] ? st->sum[m * s->nsum + S_NBASE + i] : NAN;
    dims[rank] = an;
    if (!e)
      e = autobal_archive_var(a, g, "final_angle", rank + 1, dims, ang, "rad",
                              rotor ? "ball angle relative to the rotor at the end, wrapped to (-pi, pi]"
                                    : "pendulum angle minus psi0 at the end (alpha, beta), wrapped to (-pi, pi]");
  }
  free(dv), free(iv), free(ang);
  /* kept series */
  if (s->n_keep && !e) {
    char (*names)[64] = calloc(s->ncols, sizeof *names);
    const char **np = calloc(s->ncols, sizeof *np), **up = calloc(s->ncols, sizeof *up), **lp = calloc(s->ncols, sizeof *lp);
    if (!names || !np || !up || !lp) e = AUTOBAL_ENOMEM;
    if (!e) e = series_names(s, names, up, lp);
    for (i = 0; i < s->ncols && !e; i++) np[i] = names[i];
    for (i = 0; i < s->n_keep && !e; i++) {
      char sg[128];
      autobal_archive_series *ser = NULL;
      const ens_series *sr = &st->ser[i];
      m = s->keep[i];
      snprintf(sg, sizeof sg, "%s/series/member_%zu", g, m);
      e = autobal_archive_series_open(a, sg, rotor ? "time" : "tau", tu, rotor ? "time" : "dimensionless time tau",
                                      s->ncols, np, up, lp, &ser);
      if (!e) e = autobal_archive_attr_int(a, sg, "member", (long)m);
      for (j = 0; j < s->nparam && !e; j++)
        e = autobal_archive_attr_double(a, sg, s->par[j].name, member_value(s, m, j), s->par[j].units);
      if (!e) e = autobal_archive_attr_int(a, sg, "done", st->done[m]);
      if (!e && sr->n) e = autobal_archive_series_append(ser, sr->n, sr->t, sr->rows);
      if (ser) {
        int e2 = autobal_archive_series_close(ser);
        if (!e) e = e2;
      }
    }
    free(names), free(np), free(up), free(lp);
  }
  /* how it was run: the only part that depends on threads and ranks */
  if (!e) {
    char ge[80];
    snprintf(ge, sizeof ge, "%s/execution", g);
    e = autobal_archive_group(a, ge);
    if (!e) e = autobal_archive_attr_int(a, ge, "mpi_ranks", mp->size);
    if (!e) e = autobal_archive_attr_int(a, ge, "threads_per_rank", threads);
    if (!e) e = autobal_archive_attr_double(a, ge, "wall_time", wall, "s");
#ifdef AUTOBAL_HAVE_MPI
    if (!e) e = autobal_archive_attr_int(a, ge, "mpi_build", 1);
#else
    if (!e) e = autobal_archive_attr_int(a, ge, "mpi_build", 0);
#endif
  }
#undef AS
#undef AD
#undef AI
  if (e) return cli_fail(ctx, cli_exit_code(e), "%s", e == AUTOBAL_ENOMEM ? "out of memory" : autobal_archive_errmsg(a));
  return CLI_EXIT_OK;
}

/* ---- summary on stdout ------------------------------------------------------------------------ */
static void print_summary(cli_ctx *ctx, const ens_spec *s, const ens_store *st, const ens_tally *t, const ens_mpi *mp,
                          int threads, double wall, size_t computed, int complete) {
  const char *tu = s->model == MODEL_ROTOR ? "s" : "(tau)";
  size_t j;
  if (ctx->json) {
    cli_json jj;
    cli_json_summary_begin(&jj, ctx);
    cli_json_string(&jj, "mode", s->random ? "random" : "grid");
    cli_json_array(&jj, "parameters");
    for (j = 0; j < s->nparam; j++) cli_json_string(&jj, NULL, s->par[j].name);
    cli_json_array_end(&jj);
    cli_json_int(&jj, "n_members", (long)s->n_members);
    cli_json_int(&jj, "n_done", (long)t->done);
    cli_json_int(&jj, "n_computed_now", (long)computed);
    cli_json_int(&jj, "n_failed", (long)t->failed);
    cli_json_int(&jj, "n_balanced", (long)t->balanced);
    cli_json_quantity(&jj, "probability_balanced", t->p, "1");
    cli_json_quantity(&jj, "probability_balanced_stderr", t->p_se, "1");
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
  printf("%s: %zu members (", ctx->command, s->n_members);
  for (j = 0; j < s->nparam; j++)
    if (s->random) printf("%s%s in [%g, %g]", j ? ", " : "random ", s->par[j].name, s->par[j].lo, s->par[j].hi);
    else printf("%s%s[%zu]", j ? " x " : "grid ", s->par[j].name, s->par[j].n);
  if (s->random) printf(", seed %llu", (unsigned long long)s->seed);
  printf("); %zu done (%zu now), %zu failed; %d rank(s) x %d thread(s), %.2f s wall\n", t->done, computed, t->failed,
         mp->size, threads, wall);
  if (t->ok)
    printf("  probability of balancing: %.4f +- %.4f (%zu of %zu members that ran without failure)\n", t->p, t->p_se,
           t->balanced, t->ok);
  if (t->balanced)
    printf("  time to balance %s: mean %.4g, median %.4g, max %.4g\n", tu, t->ttb_mean, t->ttb_median, t->ttb_max);
  if (!s->random && s->nparam == 2 && s->par[0].n <= 48 && s->par[1].n <= 96) {
    size_t i1, i2;
    printf("  basin of attraction (rows %s %g..%g, columns %s %g..%g; # balanced, . not, x failed, ? not run):\n",
           s->par[0].name, s->par[0].lo, grid_value(&s->par[0], s->par[0].n - 1, s->endpoint), s->par[1].name,
           s->par[1].lo, grid_value(&s->par[1], s->par[1].n - 1, s->endpoint));
    for (i1 = 0; i1 < s->par[0].n; i1++) {
      printf("    ");
      for (i2 = 0; i2 < s->par[1].n; i2++) {
        size_t m = i1 * s->par[1].n + i2;
        const double *r = st->sum + m * s->nsum;
        putchar(!st->done[m] ? '?' : r[S_STATUS] < 0 ? 'x' : r[S_BALANCED] == 1 ? '#' : '.');
      }
      putchar('\n');
    }
  }
  if (!complete)
    printf("  INCOMPLETE: %zu of %zu members to do; continue with --set ensemble.resume=true\n", s->n_members - t->done,
           s->n_members);
  if (ctx->output) printf("archive: %s\n", ctx->output);
}

/* ---- the command ------------------------------------------------------------------------------ */
static int file_exists(const char *p) {
  struct stat sb;
  return stat(p, &sb) == 0;
}

/* Before the run (rank 0): journals and the --resume/--force rules. */
static int prepare_output(cli_ctx *ctx, const ens_spec *s) {
  char **paths = NULL;
  size_t n = 0, i;
  int rc = CLI_EXIT_OK;
  if (!ctx->output) {
    if (s->resume) return cli_fail(ctx, CLI_EXIT_USAGE, "[ensemble]: resume needs -o FILE.h5 (the journals live next to it)");
    return CLI_EXIT_OK;
  }
  if (journal_list(ctx->output, &paths, &n) != 0)
    return cli_fail(ctx, CLI_EXIT_IO, "cannot list the directory of '%s': %s", ctx->output, strerror(errno));
  if (!s->resume) {
    if (n && !ctx->force)
      rc = cli_fail(ctx, CLI_EXIT_IO,
                    "journals of an unfinished run exist (%s%s); continue it with --set ensemble.resume=true, "
                    "or start over with --force",
                    paths[0], n > 1 ? ", ..." : "");
    for (i = 0; i < n && rc == CLI_EXIT_OK; i++)
      if (unlink(paths[i]) != 0) rc = cli_fail(ctx, CLI_EXIT_IO, "cannot remove '%s': %s", paths[i], strerror(errno));
  } else if (file_exists(ctx->output) && !ctx->force) {
    /* an incomplete archive of the interrupted run is replaced; a complete one is kept */
    autobal_archive *r = NULL;
    char status[64] = "";
    if (autobal_archive_open_read(ctx->output, &r, NULL) == AUTOBAL_SUCCESS) {
      autobal_archive_read_attr_string(r, "/", "status", status, sizeof status, NULL);
      autobal_archive_close(r, NULL);
    }
    if (!strcmp(status, "incomplete")) ctx->force = 1;
    else
      rc = cli_fail(ctx, CLI_EXIT_IO, "'%s' exists and is %s; nothing to resume (use --force to compute it again)",
                    ctx->output, status[0] ? "complete" : "not an incomplete autobal archive");
  }
  free_list(paths, n);
  return rc;
}

static int ensemble_main(cli_ctx *ctx, int model, const ens_mpi *mp) {
  ens_spec *s = calloc(1, sizeof *s);
  ens_store st;
  ens_run R;
  ens_tally t;
  autobal_archive *a = NULL;
  char jpath[4200];
  size_t *todo = NULL, n_todo = 0, m, k, computed = 0;
  int rc = CLI_EXIT_OK, threads = 1, complete = 0, interrupted;
  double t0 = now_seconds(), wall;

  memset(&st, 0, sizeof st);
  memset(&R, 0, sizeof R);
  if (!s) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  s->model = model;
  s->mname = model == MODEL_ROTOR ? "rotor" : "pendulum";
  if (mp->rank != 0) ctx->progress = 0, ctx->quiet = 1;
  if ((rc = read_spec(ctx, s))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  if (config_hash(ctx, s, &s->hash) != AUTOBAL_SUCCESS) {
    rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
    goto done;
  }
  {
    size_t total = 0, i;
    for (i = 0; i < s->n_keep; i++) {
      double dt_out, dwell;
      if (member_timing(s, member_speed(s, s->keep[i]), &dt_out, &dwell) == AUTOBAL_SUCCESS)
        total += series_rows_max(s, dt_out) * (s->ncols + 1);
    }
    if (total > ENS_MAX_SERIES_DOUBLES) {
      rc = cli_fail(ctx, CLI_EXIT_INPUT, "[ensemble]: the kept series would need %.3g GB; keep fewer members or raise revs_out/dt_out",
                    (double)total * 8e-9);
      goto done;
    }
  }
#ifdef _OPENMP
  threads = s->threads > 0 ? (int)s->threads : omp_get_max_threads();
#endif
  /* rank 0: journals, --resume/--force, the archive */
  if (mp->rank == 0) {
    rc = prepare_output(ctx, s);
    if (rc == CLI_EXIT_OK && ctx->output && !ctx->force && file_exists(ctx->output))
      rc = cli_fail(ctx, CLI_EXIT_IO, "output file '%s' exists; use --force to overwrite it", ctx->output);
  }
  if ((rc = mpi_agree(ctx, mp, rc))) goto done;
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) MPI_Bcast(&ctx->force, 1, MPI_INT, 0, MPI_COMM_WORLD);
#endif
  if (store_init(&st, s, mp->rank == 0)) rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  /* every rank reads every journal (resume), then opens its own */
  /* spelled as journal_list() spells it ("./" before a bare file name) */
  if (ctx->output)
    snprintf(jpath, sizeof jpath, "%s%s.journal-%d", strchr(ctx->output, '/') ? "" : "./", ctx->output, mp->rank);
  {
    long own_valid = -1;
    if (rc == CLI_EXIT_OK && s->resume) {
      char **paths = NULL;
      size_t n = 0, i;
      if (journal_list(ctx->output, &paths, &n) != 0) rc = cli_fail(ctx, CLI_EXIT_IO, "cannot list the journals of '%s'", ctx->output);
      for (i = 0; i < n && rc == CLI_EXIT_OK; i++) {
        long valid;
        rc = journal_load(ctx, s, &st, paths[i], &valid);
        if (!strcmp(paths[i], jpath)) own_valid = valid;
      }
      free_list(paths, n);
    }
    if ((rc = mpi_agree(ctx, mp, rc))) goto done; /* also: nobody writes before everybody has read */
    if (ctx->output) {
      if (own_valid > 0) {
        if (truncate(jpath, (off_t)own_valid) != 0 || !(R.journal = fopen(jpath, "ab")))
          rc = cli_fail(ctx, CLI_EXIT_IO, "cannot append to the journal '%s': %s", jpath, strerror(errno));
      } else {
        unsigned char hdr[JOURNAL_HEADER];
        journal_header(s, hdr);
        if (!(R.journal = fopen(jpath, "wb")) || fwrite(hdr, 1, JOURNAL_HEADER, R.journal) != JOURNAL_HEADER ||
            fflush(R.journal) != 0)
          rc = cli_fail(ctx, CLI_EXIT_IO, "cannot write the journal '%s': %s", jpath, strerror(errno));
      }
    }
    if ((rc = mpi_agree(ctx, mp, rc))) goto done;
  }
  /* the members still to do, cut at max_members, dealt out cyclically over the ranks */
  todo = malloc((s->n_members ? s->n_members : 1) * sizeof *todo);
  if (!todo) {
    rc = cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
    goto done;
  }
  for (m = 0, k = 0; m < s->n_members; m++) {
    if (st.done[m]) continue;
    if (s->max_members > 0 && k >= (size_t)s->max_members) break;
    if (k % (size_t)mp->size == (size_t)mp->rank) todo[n_todo++] = m;
    k++;
  }
  R.ctx = ctx;
  R.s = s;
  R.mine = todo;
  R.n_mine = n_todo;
  R.threads = threads;
  R.t_start = t0;
  if (n_todo) compute(&R);
  cli_progress_done(ctx);
  mpi_idle_barrier(mp);
  if (R.journal) {
    if (fclose(R.journal) != 0 && !R.fatal) {
      R.fatal = CLI_EXIT_IO;
      snprintf(R.fatal_msg, sizeof R.fatal_msg, "writing the journal '%.300s' failed: %s", jpath, strerror(errno));
    }
    R.journal = NULL;
  }
  if (R.fatal) rc = cli_fail(ctx, R.fatal, "%s", R.fatal_msg);
  rc = mpi_agree(ctx, mp, rc);
  interrupted = mpi_any(mp, cli_interrupted());
  {
    unsigned long long mine = R.finished, all = mine;
#ifdef AUTOBAL_HAVE_MPI
    if (mp->size > 1) MPI_Allreduce(&mine, &all, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
#endif
    computed = (size_t)all;
  }
  {
    int g = gather_records(ctx, mp, s, &st, &R.outbox);
    if (rc == CLI_EXIT_OK) rc = g;
  }
  wall = now_seconds() - t0;
  if (mp->rank == 0) {
    tally(s, &st, &t);
    complete = t.done == s->n_members;
    if (rc == CLI_EXIT_OK && interrupted)
      rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED, "interrupted: %zu of %zu members done; the journals keep them "
                    "(continue with --set ensemble.resume=true)", t.done, s->n_members);
    /* opened only now: a long run holds no half-written HDF5 file (the journals are its record) */
    if (ctx->output) {
      int o = cli_archive_open(ctx, s->model == MODEL_ROTOR ? "autobal rotor ensemble" : "autobal pendulum ensemble", &a);
      if (rc == CLI_EXIT_OK) rc = o;
    }
    if (a) {
      int w = write_archive(ctx, a, s, &st, &t, mp, threads, wall);
      if (rc == CLI_EXIT_OK) rc = w;
      if (rc == CLI_EXIT_OK && !complete) {
        char reason[256];
        snprintf(reason, sizeof reason, "%zu of %zu members done; continue with --set ensemble.resume=true",
                 t.done, s->n_members);
        autobal_archive_set_status(a, "incomplete", reason);
      }
      rc = cli_archive_finish(ctx, a, rc);
      a = NULL;
    }
    if (rc == CLI_EXIT_OK && complete && ctx->output) {
      char **paths = NULL;
      size_t n = 0, i;
      if (journal_list(ctx->output, &paths, &n) == 0)
        for (i = 0; i < n; i++) unlink(paths[i]);
      free_list(paths, n);
    }
    if (rc == CLI_EXIT_OK || rc == CLI_EXIT_INTERRUPTED)
      print_summary(ctx, s, &st, &t, mp, threads, wall, computed, complete);
    if (rc == CLI_EXIT_OK && t.failed && !ctx->json)
      fprintf(stderr, "autobal: warning: %zu member(s) failed; their status is recorded in the archive\n", t.failed);
  }
#ifdef AUTOBAL_HAVE_MPI
  if (mp->size > 1) MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (mp->rank != 0 && rc != CLI_EXIT_OK && !ctx->err[0]) cli_fail(ctx, rc, "stopped (see rank 0)");
#endif
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  if (R.journal) fclose(R.journal);
  free(R.outbox.v);
  free(todo);
  store_free(&st, s);
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
