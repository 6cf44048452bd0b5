/* cmd_rotor_design.c: `autobal rotor design`: size a ball autobalancer (two identical balls in one
 * plane) for the machine of the config, a speed range and a range of unbalances, with a required
 * margin (the library's autobal_study_rotor_design; docs/rotor.md "Design"). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "autobal/archive.h"
#include "autobal/design.h"
#include "autobal/rotor.h"
#include "autobal/study.h"
#include "cli.h"
#include "units.h"

static double wall_seconds(void) {
  struct timespec ts;
  if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) return 0.0;
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct design_bar {
  cli_ctx *ctx;
  double last;
} design_bar;
static int design_progress(double fraction, void *user) {
  design_bar *b = (design_bar *)user;
  if (fraction == b->last) return cli_interrupted();
  b->last = fraction;
  return cli_progress(b->ctx, "rotor design", fraction);
}

static int need_range(cli_ctx *ctx, const char *kmin, double lo, const char *kmax, double hi, const char *unit,
                      int strict, int positive) {
  if (positive && !(lo > 0.0))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[design]: %s = %g %s is out of range: must be > 0", kmin, lo, unit);
  if (strict ? lo < hi : lo <= hi) return CLI_EXIT_OK;
  return cli_fail(ctx, CLI_EXIT_INPUT, "[design]: %s = %g %s must be %s %s = %g %s", kmax, hi, unit,
                  strict ? "larger than" : "at least", kmin, lo, unit);
}
static int need_count(cli_ctx *ctx, const char *key, long v, long lo, long hi) {
  if (v >= lo && v <= hi) return CLI_EXIT_OK;
  return cli_fail(ctx, CLI_EXIT_INPUT, "[design]: %s = %ld is out of range: allowed [%ld, %ld]", key, v, lo, hi);
}

/* A bound pair of [design]: both or neither (then the library's default). */
static int get_bounds(cli_ctx *ctx, const char *kmin, const char *kmax, const char *unit, double *lo, double *hi) {
  int rc, p1 = 0, p2 = 0;
  if ((rc = cli_get_quantity(ctx, "design", kmin, unit, NAN, lo, &p1))) return rc;
  if ((rc = cli_get_quantity(ctx, "design", kmax, unit, NAN, hi, &p2))) return rc;
  if (p1 != p2)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[design]: %s and %s go together (give both, or neither for the default)",
                    kmin, kmax);
  if (p1) return need_range(ctx, kmin, *lo, kmax, *hi, unit, 0, strcmp(unit, "m") != 0 || strcmp(kmin, "position_min"));
  return CLI_EXIT_OK;
}

/* Anisotropic supports (the lumped set, relative 1e-12): the search then screens by Floquet and certifies by
 * Hill's method (docs/rotor.md "Design", "Anisotropic supports"). */
static int near12(double a, double b) { return fabs(a - b) <= 1e-12 * fmax(fabs(a), fabs(b)); }
static int supports_aniso(const autobal_rotor_params *p) {
  autobal_rotor_lumped L;
  if (p->input == AUTOBAL_ROTOR_LUMPED) L = p->lumped;
  else if (autobal_rotor_lumped_from_hardware(&p->hw, &L, NULL) != AUTOBAL_SUCCESS) return 0;
  return !(near12(L.c_x, L.c_y) && near12(L.c_alpha, L.c_beta) && near12(L.c_xbeta, L.c_yalpha) &&
           near12(L.h_x, L.h_y) && near12(L.h_alpha, L.h_beta) && near12(L.h_xbeta, L.h_yalpha));
}

typedef struct design_partial {
  const autobal_rotor_params *p;
  const autobal_study_rotor_design_options *o;
  const autobal_study_rotor_design_summary *sum;
} design_partial;

int cli_cmd_rotor_design(cli_ctx *ctx) {
  autobal_rotor_params p;
  void *storage = NULL;
  autobal_study_rotor_design_options o = autobal_study_rotor_design_options_default();
  autobal_study_rotor_design_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  design_bar bar;
  char msg[sizeof ctx->err];
  const char *config_out = NULL;
  long n_speed = (long)o.n_omega, n_verify = 0, n_mass = (long)o.n_mass, n_radius = (long)o.n_radius,
       n_damping = (long)o.n_damping, n_position = (long)o.n_position, n_best = (long)o.n_best,
       n_starts = (long)o.n_starts, max_iter = (long)o.max_iter, n_transient = 5, n_start = (long)o.n_start,
       n_tunb = (long)o.n_transient_unbalances, n_tspeed = (long)o.n_transient_speeds, threads = 0;
  const char *rank_by = "margin", *umember = "every";
  long n_bmin = 2, n_bmax = 2, planes = 1, n_unb2 = 5, boxes2 = 0, mboxes = 0, hboxes = 0;
  double balance_from = NAN;
  int have_from = 0, profile;
  int aniso = 0;
  int rc = CLI_EXIT_OK, st, have_wmin = 0, have_wmax = 0, have_umin = 0, have_umax = 0, have_out = 0;
  double t0, seconds;
  size_t i;
  memset(&sum, 0, sizeof sum);
  if ((rc = cli_rotor_config_read(ctx, &p, &storage))) goto done;
  if (p.gravity) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[rotor]: gravity = true is not supported by `autobal rotor design`: it sizes the balancer on the "
                  "weightless balanced state; set gravity = false");
    goto done;
  }
  cli_declare_section(ctx, "transient");
  cli_declare_section(ctx, "balance");
  cli_declare_section(ctx, "stability");
  if ((rc = cli_rotor_drive_read(ctx, &p, storage))) goto done;
  if ((rc = cli_get_quantity(ctx, "design", "balance_from", "rad/s", NAN, &balance_from, &have_from))) goto done;
  if ((rc = cli_get_quantity(ctx, "design", "speed_min", "rad/s", NAN, &o.omega_min, &have_wmin))) goto done;
  if ((rc = cli_get_quantity(ctx, "design", "speed_max", "rad/s", NAN, &o.omega_max, &have_wmax))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_speed", n_speed, &n_speed, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_verify", n_verify, &n_verify, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "design", "unbalance_min", "kg m", NAN, &o.unbalance_min, &have_umin))) goto done;
  if ((rc = cli_get_quantity(ctx, "design", "unbalance_max", "kg m", NAN, &o.unbalance_max, &have_umax))) goto done;
  if ((rc = cli_get_quantity(ctx, "design", "margin", "1/s", o.margin, &o.margin, NULL))) goto done;
  if ((rc = get_bounds(ctx, "ball_mass_min", "ball_mass_max", "kg", &o.mass_min, &o.mass_max))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_ball_mass", n_mass, &n_mass, NULL))) goto done;
  if ((rc = get_bounds(ctx, "track_radius_min", "track_radius_max", "m", &o.radius_min, &o.radius_max))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_track_radius", n_radius, &n_radius, NULL))) goto done;
  if ((rc = get_bounds(ctx, "ball_damping_min", "ball_damping_max", "kg/s", &o.damping_min, &o.damping_max)))
    goto done;
  if ((rc = cli_get_int(ctx, "design", "n_ball_damping", n_damping, &n_damping, NULL))) goto done;
  if ((rc = get_bounds(ctx, "position_min", "position_max", "m", &o.position_min, &o.position_max))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_position", n_position, &n_position, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_best", n_best, &n_best, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_starts", n_starts, &n_starts, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "max_iter", max_iter, &max_iter, NULL))) goto done;
  if ((rc = cli_get_string(ctx, "design", "config_out", NULL, &config_out, &have_out))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_transient", n_transient, &n_transient, NULL))) goto done;
  if ((rc = cli_get_string(ctx, "design", "rank_by", rank_by, &rank_by, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_start_angles", n_start, &n_start, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_transient_unbalances", n_tunb, &n_tunb, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_transient_speeds", n_tspeed, &n_tspeed, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "design", "transient_t_end", "s", o.t_end, &o.t_end, NULL))) goto done;
  if ((rc = cli_get_double(ctx, "design", "balance_tol", o.balance_tol, &o.balance_tol, NULL))) goto done;
  if ((rc = cli_get_double(ctx, "design", "balance_revs", o.balance_revs, &o.balance_revs, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "threads", threads, &threads, NULL))) goto done;
  /* the number of balls (docs/rotor.md "Design", "Number of balls") */
  if ((rc = cli_get_int(ctx, "design", "n_balls_min", n_bmin, &n_bmin, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "n_balls_max", n_bmax, &n_bmax, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "design", "total_ball_mass_max", "kg", NAN, &o.total_mass_max, NULL))) goto done;
  /* the member rule: [design] unbalance_member, else what [stability] says, else every */
  if ((rc = cli_get_string(ctx, "stability", "unbalance_member", umember, &umember, NULL))) goto done;
  if ((rc = cli_get_string(ctx, "design", "unbalance_member", umember, &umember, NULL))) goto done;
  /* the budget of the every-member enclosure: [design] member_boxes, else [stability]'s, else 0 */
  if ((rc = cli_get_int(ctx, "stability", "member_boxes", mboxes, &mboxes, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "member_boxes", mboxes, &mboxes, NULL))) goto done;
  /* the Hill budget (anisotropic supports): [design] hill_boxes, else [stability]'s, else 0 */
  if ((rc = cli_get_int(ctx, "stability", "hill_boxes", hboxes, &hboxes, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "design", "hill_boxes", hboxes, &hboxes, NULL))) goto done;
  if (!(hboxes == 0 || (hboxes >= 100 && hboxes <= 100000000L))) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[design]: hill_boxes = %ld is out of range: allowed 0 (the default budget, 20000) or [100, 1e8] "
                  "boxes (each Hill verdict of the certification, anisotropic supports)",
                  hboxes);
    goto done;
  }
  o.hill_boxes = hboxes;
  /* two planes (docs/rotor.md "Design", "Two planes") */
  {
    int have_t = 0, h1 = 0, h2 = 0, hn = 0, hb = 0;
    long nt = 0;
    if ((rc = cli_get_int(ctx, "design", "planes", planes, &planes, NULL))) goto done;
    if ((rc = need_count(ctx, "planes", planes, 1, 2))) goto done;
    if ((rc = cli_get_int(ctx, "design", "n_transient", 0, &nt, &have_t))) goto done;
    if ((rc = cli_get_quantity(ctx, "design", "unbalance2_min", "kg m", NAN, &o.unbalance2_min, &h1))) goto done;
    if ((rc = cli_get_quantity(ctx, "design", "unbalance2_max", "kg m", NAN, &o.unbalance2_max, &h2))) goto done;
    if ((rc = cli_get_int(ctx, "design", "n_unbalance2", n_unb2, &n_unb2, &hn))) goto done;
    if ((rc = cli_get_int(ctx, "design", "unbalance2_boxes", boxes2, &boxes2, &hb))) goto done;
    if (planes == 1 && (h1 || h2 || hn || hb)) {
      rc = cli_fail(ctx, CLI_EXIT_INPUT,
                    "[design]: %s is for two planes: allowed with planes = 2 only (here planes = 1)",
                    h1 ? "unbalance2_min" : h2 ? "unbalance2_max" : hn ? "n_unbalance2" : "unbalance2_boxes");
      goto done;
    }
    if (planes == 2) {
      int have_ns = 0;
      long ns = 0;
      if (!have_t) n_transient = 0;
      /* the optimizer costs n_starts x up to max_iter x n_speed two-plane verdicts: asked for only */
      if ((rc = cli_get_int(ctx, "design", "n_starts", 0, &ns, &have_ns))) goto done;
      if (!have_ns) n_starts = 0;
      if (h1 != h2) {
        rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: unbalance2_min and unbalance2_max go together (give both, or neither for plane 1's range)");
        goto done;
      }
      if (h1 && (rc = need_range(ctx, "unbalance2_min", o.unbalance2_min, "unbalance2_max", o.unbalance2_max, "kg m", 0, 1)))
        goto done;
      if ((rc = need_count(ctx, "n_unbalance2", n_unb2, 2, 100))) goto done;
      if ((rc = need_count(ctx, "unbalance2_boxes", boxes2, -1, 1000000000L))) goto done;
      o.planes = 2;
      if (!h1) {
        o.unbalance2_min = NAN; /* plane 1's range, set below once it is read */
        o.unbalance2_max = NAN;
      }
      o.n_unbalance2 = (size_t)n_unb2;
      o.unbalance2_boxes = boxes2;
    }
  }
  if ((rc = cli_config_check_unused(ctx))) goto done;
  if ((rc = need_count(ctx, "n_balls_min", n_bmin, 2, AUTOBAL_DESIGN_MAX_BALLS)) ||
      (rc = need_count(ctx, "n_balls_max", n_bmax, n_bmin, AUTOBAL_DESIGN_MAX_BALLS)))
    goto done;
  if (!strcmp(umember, "every")) o.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_EVERY;
  else if (!strcmp(umember, "symmetric")) o.unbalance_member = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
  else {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: unbalance_member = '%s' is not one of: every, symmetric", umember);
    goto done;
  }
  if (n_bmax > 10 && o.unbalance_member != AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[design]: unbalance_member = every is available for n_balls_max <= 10 (here %ld): the certification "
                  "for every member covers 3 to 10 balls; set n_balls_max <= 10, or unbalance_member = symmetric (the "
                  "verdict then covers the symmetric members only)",
                  n_bmax);
    goto done;
  }
  if (!(mboxes == 0 || (mboxes >= 1000 && mboxes <= 1000000000L))) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[design]: member_boxes = %ld is out of range: allowed 0 (the default budget, 4000000) or [1000, 1e9] "
                  "boxes (the enclosure of u over every member, 4 to 10 balls)",
                  mboxes);
    goto done;
  }
  o.member_boxes = mboxes;
  if (!isnan(o.total_mass_max) && !(o.total_mass_max > 0.0)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: total_ball_mass_max = %g kg is out of range: must be > 0", o.total_mass_max);
    goto done;
  }
  o.n_balls_min = (size_t)n_bmin;
  o.n_balls_max = (size_t)n_bmax;
  profile = p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP || p.drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE;
  if (p.drive.mode == AUTOBAL_ROTOR_DRIVE_MOTOR) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[drive]: mode = motor is not supported by `autobal rotor design`: its transients run a prescribed "
                  "run-up profile (mode = ramp or table)");
    goto done;
  }
  if (have_from && !profile) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[design]: balance_from needs a run-up profile ([drive] mode = ramp or table); without one give "
                  "speed_min and speed_max");
    goto done;
  }
  if (profile) {
    /* the rule: the operating range is [balance_from, the profile's top speed] */
    double top = 0.0;
    size_t k;
    if (p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP) top = fmax(fabs(p.drive.omega_a), fabs(p.drive.omega_b));
    else
      for (k = 0; k < p.drive.n_points; k++) top = fmax(top, fabs(p.drive.table_omega[k]));
    if (have_wmax && fabs(o.omega_max - top) > 1e-9 * top) {
      rc = cli_fail(ctx, CLI_EXIT_INPUT,
                    "[design]: speed_max = %.6g rpm disagrees with the run-up profile's top speed %.6g rpm ([drive]): "
                    "with a profile the operating range ends at its top speed; drop speed_max or make them equal",
                    cli_rpm(o.omega_max), cli_rpm(top));
      goto done;
    }
    if (have_from && have_wmin && o.omega_min != balance_from) {
      rc = cli_fail(ctx, CLI_EXIT_INPUT,
                    "[design]: speed_min = %.6g rpm and balance_from = %.6g rpm disagree: with a run-up profile give "
                    "balance_from only (the lowest speed of the operating range)",
                    cli_rpm(o.omega_min), cli_rpm(balance_from));
      goto done;
    }
    if (!have_from && !have_wmin) {
      rc = cli_fail(ctx, CLI_EXIT_INPUT,
                    "[design]: balance_from is required with a run-up profile: the speed from which the balanced "
                    "motion must be stable, in (0, %.6g rpm) (the profile's top speed), e.g. balance_from = 4500 rpm",
                    cli_rpm(top));
      goto done;
    }
    {
      const double tend = p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP ? p.drive.t_b
                          : p.drive.n_points                       ? p.drive.table_t[p.drive.n_points - 1]
                                                                   : 0.0;
      if (!isnan(o.t_end) && !(o.t_end > tend)) {
        rc = cli_fail(ctx, CLI_EXIT_INPUT,
                      "[design]: transient_t_end = %g s is out of range with the run-up profile: must be larger than "
                      "its end, %g s ([drive])",
                      o.t_end, tend);
        goto done;
      }
    }
    if (have_from) o.omega_min = balance_from;
    o.omega_max = top;
    have_wmin = have_wmax = 1;
    if (!(o.omega_min > 0.0 && o.omega_min < top)) {
      rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: balance_from = %.6g rpm is out of range: allowed (0, %.6g rpm) (the profile's top speed)",
                    cli_rpm(o.omega_min), cli_rpm(top));
      goto done;
    }
  }
  if (!have_wmin || !have_wmax) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[design]: speed_min and speed_max are required (the operating speed range, e.g. speed_min = "
                  "4500 rpm, speed_max = 9000 rpm)");
    goto done;
  }
  if (!have_umin || !have_umax) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[design]: unbalance_min and unbalance_max are required (the range of m0 r0 the machine meets, "
                  "e.g. unbalance_min = 500 g mm, unbalance_max = 4000 g mm)");
    goto done;
  }
  if (o.planes == 2 && isnan(o.unbalance2_min)) {
    o.unbalance2_min = o.unbalance_min;
    o.unbalance2_max = o.unbalance_max;
  }
  if ((rc = need_range(ctx, "speed_min", o.omega_min, "speed_max", o.omega_max, "rad/s", 1, 1)) ||
      (rc = need_range(ctx, "unbalance_min", o.unbalance_min, "unbalance_max", o.unbalance_max, "kg m", 0, 1)) ||
      (rc = need_count(ctx, "n_speed", n_speed, 2, 100000)) || (rc = need_count(ctx, "n_verify", n_verify, 0, 1000000)) ||
      (rc = need_count(ctx, "n_ball_mass", n_mass, 1, 1000)) || (rc = need_count(ctx, "n_track_radius", n_radius, 1, 1000)) ||
      (rc = need_count(ctx, "n_ball_damping", n_damping, 1, 1000)) ||
      (rc = need_count(ctx, "n_position", n_position, 1, 1000)) || (rc = need_count(ctx, "n_best", n_best, 1, 1000)) ||
      (rc = need_count(ctx, "n_starts", n_starts, 0, 100)) || (rc = need_count(ctx, "max_iter", max_iter, 1, 10000)))
    goto done;
  if ((rc = need_count(ctx, "n_transient", n_transient, 0, 1000)) || (rc = need_count(ctx, "n_start_angles", n_start, 1, 64)) ||
      (rc = need_count(ctx, "n_transient_unbalances", n_tunb, 1, 100)) ||
      (rc = need_count(ctx, "n_transient_speeds", n_tspeed, 1, 100)) || (rc = need_count(ctx, "threads", threads, 0, 4096)))
    goto done;
  if (!strcmp(rank_by, "margin")) o.rank_by = AUTOBAL_DESIGN_RANK_MARGIN;
  else if (!strcmp(rank_by, "time")) o.rank_by = AUTOBAL_DESIGN_RANK_TIME;
  else if (!strcmp(rank_by, "p_balance")) o.rank_by = AUTOBAL_DESIGN_RANK_P_BALANCE;
  else {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: rank_by = '%s' is not allowed: margin, time or p_balance", rank_by);
    goto done;
  }
  if (o.rank_by != AUTOBAL_DESIGN_RANK_MARGIN && n_transient == 0) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[design]: rank_by = %s needs the transients: n_transient = 0 is out of range with it, allowed [1, 1000]",
                  rank_by);
    goto done;
  }
  if (!isnan(o.t_end) && !(o.t_end > 0.0 && o.t_end <= 1e6)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: transient_t_end = %g s is out of range: allowed (0, 1e6]", o.t_end);
    goto done;
  }
  if (!(o.balance_tol > 0.0 && o.balance_tol < 1.0)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: balance_tol = %g is out of range: allowed (0, 1)", o.balance_tol);
    goto done;
  }
  if (!(o.balance_revs >= 0.0 && o.balance_revs <= 1e6)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: balance_revs = %g is out of range: allowed [0, 1e6]", o.balance_revs);
    goto done;
  }
  o.n_transient = (size_t)n_transient;
  o.n_start = (size_t)n_start;
  o.n_transient_unbalances = (size_t)n_tunb;
  o.n_transient_speeds = (size_t)n_tspeed;
  o.threads = (int)threads;
  if (n_verify == 1) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: n_verify = 1 is out of range: allowed 0 (default) or [2, 1000000]");
    goto done;
  }
  if (!(o.margin >= 0.0)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[design]: margin = %g 1/s is out of range: must be >= 0", o.margin);
    goto done;
  }
  o.n_omega = (size_t)n_speed;
  o.n_verify = (size_t)n_verify;
  o.n_mass = (size_t)n_mass;
  o.n_radius = (size_t)n_radius;
  o.n_damping = (size_t)n_damping;
  o.n_position = (size_t)n_position;
  o.n_best = (size_t)n_best;
  o.n_starts = (size_t)n_starts;
  o.max_iter = (size_t)max_iter;
  bar.ctx = ctx;
  bar.last = -1.0;
  o.progress = design_progress;
  o.progress_user = &bar;
  aniso = supports_aniso(&p) && o.planes == 1;
  if (aniso && !ctx->json && !ctx->quiet)
    fprintf(stderr,
            "autobal: note: anisotropic supports: a Floquet screen of %zu designs at %zu speeds x 5 unbalances (a few "
            "ms per analysis), then Hill's method with the margin for up to %zu designs at %zu speeds (about a second "
            "each, more when the margin is near the decay rate); keep the grids small (data/design_anisotropic.ini)\n",
            o.n_mass * o.n_damping * o.n_position * o.n_radius, o.n_omega, o.n_best,
            o.n_verify ? o.n_verify : o.n_omega);
  autobal_error_clear(&err);
  t0 = wall_seconds();
  st = autobal_study_rotor_design(&p, &o, NULL, &sum, &err);
  seconds = wall_seconds() - t0;
  cli_progress_done(ctx);
  if (st == AUTOBAL_ECANCELLED) {
    /* exit 6; with -o the map rows done go into the archive, marked incomplete */
    if ((rc = cli_archive_open(ctx, "autobal rotor design", &a))) goto done;
    rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED, "%s: %s; %s", cli_signal_reason(), err.message,
                  a ? "the archive keeps what was computed (status incomplete)" : "nothing written (no -o)");
    if (a && sum.mass && sum.n_mass_done > 0 && autobal_study_rotor_design_write(a, &p, &o, &sum))
      fprintf(stderr, "autobal: error: writing the partial results failed: %s\n", autobal_archive_errmsg(a));
    else if (a && !(sum.mass && sum.n_mass_done > 0) && autobal_study_write_rotor_params(a, &p, 0))
      /* interrupted inside the first row of the map: the machine only */
      fprintf(stderr, "autobal: error: writing the machine failed: %s\n", autobal_archive_errmsg(a));
    goto done;
  }
  if (st) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s", cli_rotor_message(err.message, msg, sizeof msg));
    goto done;
  }
  if ((rc = cli_archive_open(ctx, "autobal rotor design", &a))) goto done;
  if (a) {
    st = autobal_study_rotor_design_write(a, &p, &o, &sum);
    rc = cli_archive_end(ctx, &a, st, rc);
    if (rc) goto done;
  }
  if (have_out && sum.best_config) {
    FILE *f = fopen(config_out, "w");
    if (!f || fputs(sum.best_config, f) < 0 || fclose(f) != 0) {
      rc = cli_fail(ctx, CLI_EXIT_IO, "[design]: config_out = '%s': cannot write the best design's config", config_out);
      goto done;
    }
  }
  if (ctx->json) {
    cli_json j;
    cli_json_summary_begin(&j, ctx);
    cli_json_quantity(&j, "speed_min", o.omega_min, "rad/s");
    cli_json_quantity(&j, "speed_max", o.omega_max, "rad/s");
    cli_json_quantity(&j, "unbalance_min", o.unbalance_min, "kg m");
    cli_json_quantity(&j, "unbalance_max", o.unbalance_max, "kg m");
    cli_json_quantity(&j, "margin", o.margin, "1/s");
    if (o.planes == 2) {
      cli_json_int(&j, "planes", 2);
      cli_json_quantity(&j, "unbalance2_min", o.unbalance2_min, "kg m");
      cli_json_quantity(&j, "unbalance2_max", o.unbalance2_max, "kg m");
      cli_json_int(&j, "n_unbalance2", (long)o.n_unbalance2);
      cli_json_int(&j, "two_plane_verdicts", (long)sum.verdicts2);
      cli_json_int(&j, "n_undecided", (long)sum.n_undecided_cells);
      cli_json_quantity(&j, "seconds", seconds, "s");
    }
    if (sum.aniso) {
      cli_json_bool(&j, "anisotropic", 1);
      cli_json_int(&j, "n_verify", (long)(o.n_verify ? o.n_verify : o.n_omega));
      cli_json_int(&j, "hill_verdicts", (long)sum.ratio_sets);
      cli_json_quantity(&j, "seconds", seconds, "s");
    }
    cli_json_int(&j, "n_feasible", (long)sum.n_feasible);
    cli_json_int(&j, "ratio_sets", (long)sum.ratio_sets);
    cli_json_int(&j, "stability_analyses", (long)sum.margin_evaluations);
    cli_json_array(&j, "designs");
    for (i = 0; i < sum.n_designs; i++) {
      const autobal_rotor_design *d = &sum.designs[i];
      cli_json_object(&j, NULL);
      cli_json_quantity(&j, "ball_mass", d->mass, "kg");
      cli_json_quantity(&j, "track_radius", d->radius, "m");
      cli_json_quantity(&j, "ball_damping", d->damping, "kg/s");
      cli_json_quantity(&j, "position", d->position, "m");
      cli_json_quantity(&j, "robust_margin", d->margin, "1/s");
      if (!(o.n_balls_min == 2 && o.n_balls_max == 2)) {
        cli_json_int(&j, "n_balls", (long)d->n_balls);
        cli_json_string(&j, "verdict_covers", d->n_balls < 3 || d->members_certified == 1 ? "every member" : "symmetric members only");
        if (d->n_balls >= 3 && o.unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY) {
          cli_json_int(&j, "members_certified", d->members_certified);
          cli_json_int(&j, "member_speeds", (long)d->member_speeds);
          cli_json_int(&j, "member_speeds_undecided", (long)d->member_undecided);
          cli_json_quantity(&j, "member_undecided_first", d->member_undecided_omega[0], "rad/s");
          cli_json_quantity(&j, "member_undecided_last", d->member_undecided_omega[1], "rad/s");
          cli_json_quantity(&j, "member_found_speed", d->member_found_omega, "rad/s");
          cli_json_quantity(&j, "member_found_u", d->member_found_u, "kg^2");
          cli_json_quantity(&j, "member_found_margin", d->member_found_margin, "1/s");
          cli_json_quantity(&j, "member_margin", d->member_margin, "1/s");
          cli_json_quantity(&j, "member_u_min", d->member_u[0], "kg^2");
          cli_json_quantity(&j, "member_u_max", d->member_u[1], "kg^2");
          cli_json_int(&j, "member_boxes", d->member_boxes);
          cli_json_bool(&j, "member_enclosure_complete", d->member_enclosure_complete);
          cli_json_quantity(&j, "member_margin_certified", d->member_margin_certified, "1/s");
          cli_json_bool(&j, "member_margin_decided", d->member_margin_decided);
        }
      }
      cli_json_bool(&j, "feasible", d->feasible);
      cli_json_int(&j, "recheck", d->recheck);
      if (sum.aniso) {
        cli_json_string(&j, "margin_is", "sampled: the Floquet screen, -(largest Floquet margin met)");
        cli_json_string(&j, "verdict", d->hill_certified == 1    ? "certified"
                                       : d->hill_certified == 0  ? "not stable with the margin"
                                       : d->hill_certified == -1 ? "undecided"
                                                                 : "not run");
        cli_json_int(&j, "hill_certified", d->hill_certified);
        cli_json_int(&j, "hill_speeds", (long)d->hill_speeds);
        cli_json_int(&j, "hill_speeds_undecided", (long)d->hill_undecided);
        cli_json_int(&j, "hill_boxes", d->hill_boxes);
        cli_json_quantity(&j, "hill_found_speed", d->hill_found_omega, "rad/s");
        cli_json_quantity(&j, "hill_found_unbalance", d->hill_found_s, "kg m");
        cli_json_quantity(&j, "recheck_margin", d->recheck_margin, "1/s");
      }
      if (o.planes == 2) {
        cli_json_string(&j, "margin_is", "sampled: -(largest margin met)");
        cli_json_int(&j, "certified_speeds", (long)d->n_certified);
        cli_json_int(&j, "certify_speeds_run", (long)d->n_certify_run);
        cli_json_int(&j, "boxes", (long)d->boxes);
        if (!isnan(d->margin_certified)) {
          cli_json_quantity(&j, "margin_certified", d->margin_certified, "1/s");
          cli_json_quantity(&j, "margin_upper", d->margin_upper, "1/s");
          cli_json_string(&j, "margin_certified_is", d->margin_decided ? "certified" : "estimate (a step undecided)");
          cli_json_int(&j, "margin_steps", (long)d->margin_steps);
        }
        if (!isnan(d->found_omega)) {
          cli_json_quantity(&j, "found_speed", d->found_omega, "rad/s");
          cli_json_quantity(&j, "found_unbalance1", d->found_s[0], "kg m");
          cli_json_quantity(&j, "found_unbalance2", d->found_s[1], "kg m");
          cli_json_quantity(&j, "found_phase", d->found_phase, "rad");
        }
      }
      if (d->n_runs > 0) {
        cli_json_quantity(&j, "p_balance", d->p_balance, "1");
        cli_json_quantity(&j, "time_to_balance_median", d->ttb_median, "s");
        cli_json_quantity(&j, "time_to_balance_worst", d->ttb_worst, "s");
        cli_json_int(&j, "transient_members", (long)d->n_runs);
      }
      cli_json_object_end(&j);
    }
    cli_json_array_end(&j);
    if (sum.best_config) cli_json_string(&j, "best_config", sum.best_config);
    cli_json_summary_end(&j, ctx);
  } else if (!ctx->quiet && o.planes == 2) {
    const size_t ncells = sum.n_mass * sum.n_damping * sum.n_radius;
    printf("rotor design, two planes: the same two identical balls in both planes (plane 1 at d = %.6g mm, plane 2 at "
           "%.6g mm), speeds [%.6g, %.6g] rad/s ([%.6g, %.6g] rpm, %zu points),\n",
           p.plane[0].d * 1e3, p.plane[1].d * 1e3, o.omega_min, o.omega_max, cli_rpm(o.omega_min), cli_rpm(o.omega_max),
           o.n_omega);
    printf("  every m0 r0 of plane 1 in [%.6g, %.6g] g mm (exact), of plane 2 in [%.6g, %.6g] g mm (map: %zu grid values; "
           "ranked designs: certified by the box search), every relative phase (exact); required margin %.6g 1/s "
           "(checked on the points evaluated: sampled)\n",
           o.unbalance_min * 1e6, o.unbalance_max * 1e6, o.unbalance2_min * 1e6, o.unbalance2_max * 1e6, o.n_unbalance2,
           o.margin);
    printf("  map: %zu ball masses [%.6g, %.6g] g x %zu dampings [%.6g, %.6g] kg/s x %zu radii [%.6g, %.6g] mm: %zu of "
           "%zu feasible%s",
           sum.n_mass, sum.mass[0] * 1e3, sum.mass[sum.n_mass - 1] * 1e3, sum.n_damping, sum.damping[0],
           sum.damping[sum.n_damping - 1], sum.n_radius, sum.radius[0] * 1e3, sum.radius[sum.n_radius - 1] * 1e3,
           sum.n_feasible, ncells, sum.n_undecided_cells ? "" : "\n");
    if (sum.n_undecided_cells) printf(", %zu undecided (the analysis failed there; not feasible)\n", sum.n_undecided_cells);
    printf("    feasible map (rows ball mass g, columns track radius mm; per damping: # feasible, + stable below the "
           "margin, . not stable, x cannot balance, ? undecided)\n");
    for (i = 0; i < sum.n_damping; i++) {
      size_t a_, q;
      printf("    damping %.5g kg/s\n", sum.damping[i]);
      for (a_ = 0; a_ < sum.n_mass; a_++) {
        printf("      %8.4g ", sum.mass[a_] * 1e3);
        for (q = 0; q < sum.n_radius; q++) {
          const int f = sum.feasible[(a_ * sum.n_damping + i) * sum.n_radius + q];
          const double mm = sum.margin_map[(a_ * sum.n_damping + i) * sum.n_radius + q];
          putchar(f == 1 ? '#' : f == -1 ? 'x' : f == -3 ? '?' : !isnan(mm) ? '+' : '.');
        }
        putchar('\n');
      }
    }
    printf("  ranked designs (margin: -(largest margin met), sampled; recheck: the box search over plane 2's whole "
           "range at every grid speed):\n");
    printf("    %4s %10s %10s %12s %12s %8s %8s %10s %22s\n", "rank", "mass g", "radius mm", "damping kg/s", "margin 1/s",
           "feasible", "recheck", "certified", "rho certified 1/s");
    for (i = 0; i < sum.n_designs; i++) {
      const autobal_rotor_design *d = &sum.designs[i];
      char rbuf[48] = "-";
      if (!isnan(d->margin_certified))
        snprintf(rbuf, sizeof rbuf, "%.4f%s", d->margin_certified, d->margin_decided ? "" : " (estimate)");
      printf("    %4zu %10.5g %10.5g %12.5g %12.5g %8s %8s %4zu of %zu %22s\n", i, d->mass * 1e3, d->radius * 1e3,
             d->damping, d->margin, d->feasible ? "yes" : "no", d->recheck == 1 ? "ok" : (d->recheck == 0 ? "FAILED" : "-"),
             d->n_certified, d->n_certify_run, rbuf);
      if (d->source) printf("         (the optimizer)\n");
      if (!isnan(d->found_omega))
        printf("         not stable at %.6g rad/s: plane 1 %.6g g mm, plane 2 %.6g g mm, phase %.6g rad\n", d->found_omega,
               d->found_s[0] * 1e6, d->found_s[1] * 1e6, d->found_phase);
    }
    if (sum.n_designs == 0) printf("    none: no design in the bounds is stable for every unbalance at every grid speed\n");
    printf("  certified: the verdict holds for every m0 r0 of plane 2's range at that speed (box search); the other "
           "speeds: plane 2 on its grid (SAMPLED)\n");
    printf("  rho certified: every root Re lambda < -rho for every unbalance of both ranges and every phase at every grid "
           "speed (bisection to 1e-3 1/s over the box search on the shifted polynomial); (estimate): a step undecided\n");
    if (sum.transients > 0) {
      const int prof = p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP || p.drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE;
      char sbuf[32] = "";
      if (!prof) snprintf(sbuf, sizeof sbuf, "%zu", o.n_transient_speeds);
      printf("  transients of the first %zu designs (ranked by %s): %zu start angles per ball (4 balls) x %zu plane-1 x %zu "
             "plane-2 unbalances x %s%s,\n"
             "  %g s each; balanced = attractor class balanced; time to balance = start of %g revolutions with every "
             "plane's residual unbalance below %g\n",
             o.n_transient < sum.n_designs ? o.n_transient : sum.n_designs, rank_by, o.n_start,
             o.unbalance_min < o.unbalance_max ? o.n_transient_unbalances : (size_t)1,
             o.unbalance2_min < o.unbalance2_max ? o.n_transient_unbalances : (size_t)1, sbuf,
             prof ? "the run-up profile from rest" : " speeds",
             isnan(o.t_end) ? (prof ? (p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP ? p.drive.t_b
                                                                                : p.drive.table_t[p.drive.n_points - 1])
                                    : 0.0) + 10.0
                            : o.t_end,
             o.balance_revs, o.balance_tol);
      printf("    %4s %10s %10s %12s %12s %14s %13s\n", "rank", "mass g", "radius mm", "damping kg/s", "P(balance)",
             "median ttb s", "worst ttb s");
      for (i = 0; i < sum.n_designs; i++) {
        const autobal_rotor_design *d = &sum.designs[i];
        if (d->n_runs == 0) continue;
        printf("    %4zu %10.5g %10.5g %12.5g %5zu/%-6zu %14.4g %13.4g\n", i, d->mass * 1e3, d->radius * 1e3, d->damping,
               d->n_balanced, d->n_runs, d->ttb_median, d->ttb_worst);
      }
      printf("  %zu transients\n", sum.transients);
    }
    printf("  %zu two-plane every-unbalance verdicts in %.3g s (%.1f per second)\n", sum.verdicts2, seconds,
           seconds > 0 ? (double)sum.verdicts2 / seconds : 0.0);
    if (sum.best_config) {
      if (have_out) printf("best design as a config (written to %s):\n", config_out);
      else printf("best design as a config ([design] config_out = FILE writes it):\n");
      fputs(sum.best_config, stdout);
    }
    if (ctx->output) printf("archive: %s\n", ctx->output);
  } else if (!ctx->quiet && sum.aniso) {
    const size_t ncells = sum.n_mass * sum.n_damping * sum.n_position * sum.n_radius;
    const size_t nv = o.n_verify ? o.n_verify : o.n_omega;
    size_t q, k;
    printf("rotor design, anisotropic supports: two identical balls in plane 1, speeds [%.6g, %.6g] rad/s ([%.6g, %.6g] "
           "rpm), every unbalance m0 r0 in [%.6g, %.6g] g mm,\n",
           o.omega_min, o.omega_max, cli_rpm(o.omega_min), cli_rpm(o.omega_max), o.unbalance_min * 1e6,
           o.unbalance_max * 1e6);
    printf("  required margin %.6g 1/s (every Floquet exponent Re < -margin, |mu| < exp(-margin T))\n", o.margin);
    printf("  screen (Floquet, SAMPLED: %zu speeds x 5 unbalances per design): %zu ball masses [%.6g, %.6g] g x %zu "
           "dampings [%.6g, %.6g] kg/s x %zu positions x %zu radii [%.6g, %.6g] mm: %zu of %zu pass\n",
           o.n_omega, sum.n_mass, sum.mass[0] * 1e3, sum.mass[sum.n_mass - 1] * 1e3, sum.n_damping, sum.damping[0],
           sum.damping[sum.n_damping - 1], sum.n_position, sum.n_radius, sum.radius[0] * 1e3,
           sum.radius[sum.n_radius - 1] * 1e3, sum.n_feasible, ncells);
    printf("    screen map (rows ball mass g, columns track radius mm; per damping and position: # passes, . fails, "
           "x cannot balance)\n");
    for (i = 0; i < sum.n_damping; i++)
      for (k = 0; k < sum.n_position; k++) {
        size_t a_;
        printf("    damping %.5g kg/s, d %.5g mm\n", sum.damping[i], sum.position[k] * 1e3);
        for (a_ = 0; a_ < sum.n_mass; a_++) {
          printf("      %8.4g ", sum.mass[a_] * 1e3);
          for (q = 0; q < sum.n_radius; q++) {
            const int f = sum.feasible[((a_ * sum.n_damping + i) * sum.n_position + k) * sum.n_radius + q];
            putchar(f == 1 ? '#' : f == -1 ? 'x' : '.');
          }
          putchar('\n');
        }
      }
    printf("  ranked designs (rho_s: the screen's margin, SAMPLED; verdict: Hill's method with the required margin at "
           "every one of %zu re-check speeds; only CERTIFIED designs are feasible):\n",
           nv);
    printf("    %4s %10s %10s %12s %10s %12s %8s %s\n", "rank", "mass g", "radius mm", "damping kg/s", "d mm",
           "rho_s 1/s", "feasible", "verdict");
    for (i = 0; i < sum.n_designs; i++) {
      const autobal_rotor_design *d = &sum.designs[i];
      char vb[160];
      if (d->hill_certified == 1) snprintf(vb, sizeof vb, "CERTIFIED (%zu speeds)", d->hill_speeds);
      else if (d->hill_certified == 0 && !isnan(d->hill_found_s))
        snprintf(vb, sizeof vb, "NOT STABLE with the margin: %.6g g mm at %.6g rad/s", d->hill_found_s * 1e6,
                 d->hill_found_omega);
      else if (d->hill_certified == 0) snprintf(vb, sizeof vb, "NOT STABLE: the balls cannot balance the range");
      else if (d->hill_certified == -1)
        snprintf(vb, sizeof vb, "UNDECIDED at %zu of %zu speeds (first %.6g rad/s; [design] hill_boxes)",
                 d->hill_undecided, d->hill_speeds, d->hill_found_omega);
      else snprintf(vb, sizeof vb, "not certified (not run)");
      printf("    %4zu %10.5g %10.5g %12.5g %10.5g %12.5g %8s %s\n", i, d->mass * 1e3, d->radius * 1e3, d->damping,
             d->position * 1e3, d->margin, d->feasible ? "yes" : "no", vb);
    }
    if (sum.n_designs == 0)
      printf("    none: no design in the bounds passes the screen (every sample decaying faster than the margin)\n");
    else if (!sum.designs[0].feasible)
      printf("  no design certified: none is reported feasible\n");
    if (sum.transients > 0) {
      printf("  transients of the first %zu designs: %zu start angles per ball x %zu unbalances x %zu speeds\n",
             o.n_transient < sum.n_designs ? o.n_transient : sum.n_designs, o.n_start,
             o.unbalance_min < o.unbalance_max ? o.n_transient_unbalances : (size_t)1, o.n_transient_speeds);
      printf("    %4s %10s %10s %12s %12s %14s %13s\n", "rank", "mass g", "radius mm", "damping kg/s", "P(balance)",
             "median ttb s", "worst ttb s");
      for (i = 0; i < sum.n_designs; i++) {
        const autobal_rotor_design *d = &sum.designs[i];
        if (d->n_runs == 0) continue;
        printf("    %4zu %10.5g %10.5g %12.5g %5zu/%-6zu %14.4g %13.4g\n", i, d->mass * 1e3, d->radius * 1e3,
               d->damping, d->n_balanced, d->n_runs, d->ttb_median, d->ttb_worst);
      }
    }
    printf("  %zu Floquet analyses (screen and certification ends), %zu Hill verdicts, %.3g s\n",
           sum.margin_evaluations, sum.ratio_sets, seconds);
    if (sum.best_config) {
      if (have_out) printf("best design as a config (written to %s):\n", config_out);
      else printf("best design as a config ([design] config_out = FILE writes it):\n");
      fputs(sum.best_config, stdout);
    }
    if (ctx->output) printf("archive: %s\n", ctx->output);
  } else if (!ctx->quiet) {
    const size_t ncells = sum.n_n * sum.n_mass * sum.n_damping * sum.n_position * sum.n_radius;
    const int nball = !(o.n_balls_min == 2 && o.n_balls_max == 2);
    if (!nball)
      printf("rotor design: two identical balls in plane 1, speeds [%.6g, %.6g] rad/s ([%.6g, %.6g] rpm, %zu points),\n",
             o.omega_min, o.omega_max, cli_rpm(o.omega_min), cli_rpm(o.omega_max), o.n_omega);
    else {
      printf("rotor design: %zu to %zu identical balls in plane 1, speeds [%.6g, %.6g] rad/s ([%.6g, %.6g] rpm, %zu points),\n",
             o.n_balls_min, o.n_balls_max, o.omega_min, o.omega_max, cli_rpm(o.omega_min), cli_rpm(o.omega_max), o.n_omega);
      printf("  ball mass bounds per ball%s", isnan(o.total_mass_max) ? "" : ", total ball mass n m at most ");
      if (!isnan(o.total_mass_max)) printf("%.6g g", o.total_mass_max * 1e3);
      printf("; verdict: %s\n", o.n_balls_max < 3 ? "every member"
                               : o.unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY
                                   ? "two balls every member (unique); three or more balls: search over the symmetric "
                                     "fan, then every member certified per design on the re-check grid, ball modes -h/m "
                                     "included"
                                   : "two balls every member (unique); three or more balls symmetric "
                                     "members only (the symmetric fan), ball modes -h/m included");
    }
    if (profile)
      printf("  the speed range from the run-up profile ([drive] mode = %s): balance_from to its top speed\n",
             p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP ? "ramp" : "table");
    printf("  every unbalance m0 r0 in [%.6g, %.6g] g mm, required margin %.6g 1/s (every root Re lambda < -margin)\n",
           o.unbalance_min * 1e6, o.unbalance_max * 1e6, o.margin);
    printf("  map: %zu ball masses [%.6g, %.6g] g x %zu dampings [%.6g, %.6g] kg/s x %zu positions x %zu radii "
           "[%.6g, %.6g] mm: %zu of %zu feasible\n",
           sum.n_mass, sum.mass[0] * 1e3, sum.mass[sum.n_mass - 1] * 1e3, sum.n_damping, sum.damping[0],
           sum.damping[sum.n_damping - 1], sum.n_position, sum.n_radius, sum.radius[0] * 1e3,
           sum.radius[sum.n_radius - 1] * 1e3, sum.n_feasible, ncells);
    if (o.n_balls_max >= 3 && o.unbalance_member == AUTOBAL_ROTOR_UNBALANCE_EVERY)
      printf("  ranked designs (robust margin rho: the exact test passes with it at every grid speed and unbalance, for\n"
             "  three or more balls on the symmetric members; the feasible designs ranked by the margin their verdict\n"
             "  covers: rho for two balls, the certified margin over every member for three or more):\n");
    else
      printf("  ranked designs (robust margin rho: the exact test passes with it at every grid speed and unbalance):\n");
    printf("    %4s %s%10s %10s %12s %10s %12s %8s %8s\n", "rank", nball ? "balls " : "", "mass g", "radius mm",
           "damping kg/s", "d mm", "rho 1/s", "feasible", "recheck");
    for (i = 0; i < sum.n_designs; i++) {
      const autobal_rotor_design *d = &sum.designs[i];
      char nbuf[16] = "";
      if (nball) snprintf(nbuf, sizeof nbuf, "%5zu ", d->n_balls);
      printf("    %4zu %s%10.5g %10.5g %12.5g %10.5g %12.5g %8s %8s%s%s\n", i, nbuf, d->mass * 1e3, d->radius * 1e3,
             d->damping, d->position * 1e3, d->margin, d->feasible ? "yes" : "no",
             d->recheck == 1 ? "ok" : (d->recheck == 0 ? "FAILED" : "-"), d->source ? "  (optimizer)" : "",
             d->n_balls < 3 ? "" : d->members_certified == 1 ? "  (every member)" : "  (symmetric members only)");
      if (d->n_balls >= 3 && d->members_certified == 1)
        printf("           every member certified at %zu re-check speeds: u in [%.6g, %.6g] kg^2 over the members; "
               "margin over every member %.5g 1/s certified%s (members' sampled %.5g 1/s)\n",
               d->member_speeds, d->member_u[0], d->member_u[1], d->member_margin_certified,
               d->member_margin_decided ? "" : " (a step undecided: lower bound)", d->member_margin);
      else if (d->n_balls >= 3 && d->members_certified == -1) {
        char mb[96] = "has a root at Re lambda >= -margin";
        if (!isnan(d->member_found_margin))
          snprintf(mb, sizeof mb, "%s (max Re lambda %.5g 1/s)",
                   d->member_found_margin < 0.0 ? "is not stable with the margin" : "is not stable",
                   d->member_found_margin);
        if (isnan(d->member_found_u))
          printf("           every member: NOT FEASIBLE: the ball modes -h/m = %.5g 1/s are not left of -margin\n",
                 -d->damping / d->mass);
        else
          printf("           every member: NOT FEASIBLE: at %.6g rad/s a member with u = %.6g kg^2 %s\n",
                 d->member_found_omega, d->member_found_u, mb);
      }
      else if (d->n_balls >= 3 && d->members_certified == -2)
        printf("           every member: UNDECIDED at %zu of %zu re-check speeds (%.6g .. %.6g rad/s): not feasible "
               "(a larger member_boxes may decide it)\n",
               d->member_undecided, d->member_speeds, d->member_undecided_omega[0], d->member_undecided_omega[1]);
    }
    if (sum.n_designs == 0) printf("    none: no design in the bounds balances the range with the margin\n");
    if (sum.transients > 0) {
      char sbuf[32] = "";
      if (!(p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP || p.drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE))
        snprintf(sbuf, sizeof sbuf, "%zu", o.n_transient_speeds);
      printf("  transients of the first %zu designs (ranked by %s): %zu start angles per ball x %zu unbalances x %s%s,\n"
             "  %g s each; balanced = attractor class balanced; time to balance = start of %g revolutions with the "
             "residual unbalance below %g\n",
             o.n_transient < sum.n_designs ? o.n_transient : sum.n_designs, rank_by, o.n_start,
             o.unbalance_min < o.unbalance_max ? o.n_transient_unbalances : (size_t)1, sbuf,
             p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP || p.drive.mode == AUTOBAL_ROTOR_DRIVE_TABLE ? "the run-up profile from rest" : " speeds",
             isnan(o.t_end) ? (profile ? (p.drive.mode == AUTOBAL_ROTOR_DRIVE_RAMP ? p.drive.t_b
                                                                                   : p.drive.table_t[p.drive.n_points - 1])
                                       : 0.0) + 10.0
                            : o.t_end,
             o.balance_revs, o.balance_tol);
      if (nball) printf("  (balls 3..n start at fixed angles between balls 1 and 2's first ones)\n");
      printf("    %4s %s%10s %10s %12s %12s %14s %13s\n", "rank", nball ? "balls " : "", "mass g", "radius mm",
             "damping kg/s", "P(balance)", "median ttb s", "worst ttb s");
      for (i = 0; i < sum.n_designs; i++) {
        const autobal_rotor_design *d = &sum.designs[i];
        char nbuf[16] = "";
        if (d->n_runs == 0) continue;
        if (nball) snprintf(nbuf, sizeof nbuf, "%5zu ", d->n_balls);
        printf("    %4zu %s%10.5g %10.5g %12.5g %5zu/%-6zu %14.4g %13.4g\n", i, nbuf, d->mass * 1e3, d->radius * 1e3,
               d->damping, d->n_balanced, d->n_runs, d->ttb_median, d->ttb_worst);
      }
      printf("  %zu transients\n", sum.transients);
    }
    printf("  %zu exact every-unbalance tests, %zu stability analyses (%.0f per second%s), %zu optimizer evaluations\n",
           sum.ratio_sets, sum.margin_evaluations, seconds > 0 ? (double)sum.margin_evaluations / seconds : 0.0,
           sum.transients > 0 ? " of the whole run, transients included" : "", sum.optimizer_evaluations);
    if (sum.best_config) {
      if (have_out) printf("best design as a config (written to %s):\n", config_out);
      else printf("best design as a config ([design] config_out = FILE writes it):\n");
      fputs(sum.best_config, stdout);
    }
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  autobal_study_rotor_design_summary_free(&sum);
  free(storage);
  return rc;
}
