/* cmd_rotor_stability.c: `autobal rotor stability|sweep|map|campbell`: balanced motions of the
 * rotor with ball autobalancers, their stability (docs/rotor.md (3.14)-(3.16), anisotropic
 * supports by Floquet), critical speeds, parameter sweeps, two-parameter maps, natural
 * frequencies, the Campbell diagram and the unbalance-response critical speeds. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/archive.h"
#include "autobal/rotor.h"
#include "autobal/rotor_stability.h"
#include "autobal/study.h"
#include "cli.h"
#include "units.h"

#define MAX_MEMBER_ANGLES 4096
#define TWO_PI 6.283185307179586476925286766559

/* ---- interruption (SIGINT, SIGTERM, SIGHUP) ------------------------------------------ */

/* The studies' progress callback of the commands without a progress bar: stop once a signal
 * arrived. */
/* Range checks of the [sweep]/[map]/[campbell] keys: each names the broken key, its value and
 * the allowed range (exit 3). */
static int need_int(cli_ctx *ctx, const char *sec, const char *key, long v, long lo, long hi) {
  if (v < lo) return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s = %ld is too small: must be >= %ld (allowed range [%ld, %ld])", sec, key, v, lo, lo, hi);
  if (v > hi) return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s = %ld is too large: must be <= %ld (allowed range [%ld, %ld])", sec, key, v, hi, lo, hi);
  return CLI_EXIT_OK;
}
static int need_order(cli_ctx *ctx, const char *sec, const char *klo, double lo, const char *khi, double hi,
                      const char *unit, int strict) {
  if (strict ? lo < hi : lo <= hi) return CLI_EXIT_OK;
  return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s = %g %s must be %s %s = %g %s", sec, khi, hi, unit ? unit : "",
                  strict ? "larger than" : "at least", klo, lo, unit ? unit : "");
}
static int need_xtol(cli_ctx *ctx, const char *sec, double x) {
  if (x > 0 && x < 0.1) return CLI_EXIT_OK;
  return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: xtol_rel = %g is out of range: allowed (0, 0.1)", sec, x);
}

static int stop_requested(double fraction, void *user) {
  (void)fraction;
  (void)user;
  return cli_interrupted();
}

/* After a study returned AUTOBAL_ECANCELLED: exit code 6 with `what` (the study's message);
 * with -o the archive is created and `write` (0: nothing to write) puts the partial results in
 * it; cli_archive_finish marks it incomplete, naming the signal.  Returns the exit code. */
typedef int (*partial_writer)(autobal_archive *a, const void *data);
static int finish_interrupted(cli_ctx *ctx, const char *title, const char *what, partial_writer write,
                              const void *data) {
  autobal_archive *a = NULL;
  int rc, st;
  if ((rc = cli_archive_open(ctx, title, &a))) return rc;
  rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED, "%s: %s; %s", cli_signal_reason(), what,
                a ? "the archive keeps what was computed (status incomplete)" : "nothing written (no -o)");
  if (!a) return rc;
  st = write ? write(a, data) : AUTOBAL_SUCCESS;
  if (st)
    fprintf(stderr, "autobal: error: writing the partial results failed: %s\n", autobal_archive_errmsg(a));
  return cli_archive_finish(ctx, a, rc);
}

/* ---- configuration shared by the commands --------------------------------------- */

typedef struct stab_cfg {
  autobal_rotor_params p;
  void *storage; /* ball arrays of p (cli_rotor_config_read) */
  autobal_rotor_stab_options opt;
  double angles[AUTOBAL_ROTOR_MAX_PLANES][MAX_MEMBER_ANGLES];
  const char *method_name;
  const char *member_name[AUTOBAL_ROTOR_MAX_PLANES];
} stab_cfg;

static int parse_member(cli_ctx *ctx, stab_cfg *c, size_t j) {
  char key[32], akey[40];
  size_t n = 0;
  int rc, present = 0;
  const char *name = "default";
  autobal_rotor_member *m = &c->opt.member[j];
  snprintf(key, sizeof key, "member%zu", j + 1);
  snprintf(akey, sizeof akey, "member%zu_angles", j + 1);
  if ((rc = cli_get_string(ctx, "stability", key, name, &name, NULL))) return rc;
  if ((rc = cli_get_doubles(ctx, "stability", akey, c->angles[j], MAX_MEMBER_ANGLES, &n, &present))) return rc;
  c->member_name[j] = name;
  if (!strcmp(name, "default")) m->kind = AUTOBAL_ROTOR_MEMBER_DEFAULT;
  else if (!strcmp(name, "symmetric")) m->kind = AUTOBAL_ROTOR_MEMBER_SYMMETRIC;
  else if (!strcmp(name, "free")) m->kind = AUTOBAL_ROTOR_MEMBER_FREE;
  else if (!strcmp(name, "given")) m->kind = AUTOBAL_ROTOR_MEMBER_GIVEN;
  else
    return cli_fail(ctx, CLI_EXIT_INPUT, "[stability]: %s = '%s' is not one of: default, symmetric, free, given", key,
                    name);
  if (j >= c->p.n_planes && strcmp(name, "default"))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[stability]: %s is given but there is no plane %zu", key, j + 1);
  if ((m->kind == AUTOBAL_ROTOR_MEMBER_FREE || m->kind == AUTOBAL_ROTOR_MEMBER_GIVEN) && !present)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[stability]: %s = %s needs %s (the angles of balls 1..n-2 for 'free', of every ball for "
                    "'given', rad)",
                    key, name, akey);
  if (present && !(m->kind == AUTOBAL_ROTOR_MEMBER_FREE || m->kind == AUTOBAL_ROTOR_MEMBER_GIVEN))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[stability]: %s is used only with %s = free or given", akey, key);
  m->n_angles = n;
  m->angles = n ? c->angles[j] : NULL;
  return CLI_EXIT_OK;
}

/* [SEC] unbalance_member = every|symmetric: the members of plane 1 that the every-unbalance analysis
 * covers with three or more identical balls (rotor_stability.h, autobal_rotor_unbalance_member). */
static int read_unbalance_member(cli_ctx *ctx, const char *sec, int *rule, const char **name) {
  int rc;
  *name = "every";
  if ((rc = cli_get_string(ctx, sec, "unbalance_member", *name, name, NULL))) return rc;
  if (!strcmp(*name, "every")) *rule = AUTOBAL_ROTOR_UNBALANCE_EVERY;
  else if (!strcmp(*name, "symmetric")) *rule = AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC;
  else
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[%s]: unbalance_member = '%s' is not one of: every, symmetric (the members of the family of "
                    "balanced configurations that 'every unbalance' covers with three or more balls)",
                    sec, *name);
  return CLI_EXIT_OK;
}

/* [SEC] member_boxes = N: the box budget of the enclosure of u over the members (4 to 10 identical balls,
 * unbalance_member = every; rotor_stability.h, autobal_rotor_stab_options.member_boxes). */
static int read_member_boxes(cli_ctx *ctx, const char *sec, long *boxes) {
  int rc;
  long b = 0;
  if ((rc = cli_get_int(ctx, sec, "member_boxes", 0, &b, NULL))) return rc;
  if (b != 0 && (b < 1000 || b > 1000000000L))
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[%s]: member_boxes = %ld is out of range: allowed 0 (the default budget, 4000000) or [1000, 1e9] "
                    "(boxes of the search for the range of |Q| over every member, 4 to 10 identical balls)",
                    sec, b);
  *boxes = b;
  return CLI_EXIT_OK;
}

/* [sec] hill_boxes: the box budget of Hill's method (every unbalance, anisotropic supports). */
static int read_hill_boxes(cli_ctx *ctx, const char *sec, long *boxes) {
  int rc;
  long b = 0;
  if ((rc = cli_get_int(ctx, sec, "hill_boxes", 0, &b, NULL))) return rc;
  if (b != 0 && (b < 100 || b > 100000000L))
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[%s]: hill_boxes = %ld is out of range: allowed 0 (the default budget, 20000) or [100, 1e8] "
                    "(boxes of the Hill exclusion, every unbalance with anisotropic supports)",
                    sec, b);
  *boxes = b;
  return CLI_EXIT_OK;
}

/* gravity = true is refused: these analyses linearize about the weightless balanced state (the
 * library's balanced states and linear analyses ignore gravity, docs/device.md section 2). */
static int refuse_gravity(cli_ctx *ctx, const autobal_rotor_params *p) {
  if (!p->gravity) return CLI_EXIT_OK;
  return cli_fail(ctx, CLI_EXIT_INPUT,
                  "[rotor]: gravity = true is not supported by `autobal %s`: it analyses the weightless balanced "
                  "state (gravity's static offset and 1X ball oscillation are not part of it); run `autobal rotor "
                  "transient` for gravity, or set gravity = false", ctx->command ? ctx->command : "rotor stability");
}

/* Read the rotor model and [stability]; validates by allocating a handle once. */
static int read_stab_cfg(cli_ctx *ctx, stab_cfg *c) {
  int rc;
  size_t j;
  autobal_error err;
  autobal_rotor_stab *probe;
  char msg[sizeof ctx->err];
  c->opt = autobal_rotor_stab_options_default();
  if ((rc = cli_rotor_config_read(ctx, &c->p, &c->storage))) return rc;
  if ((rc = refuse_gravity(ctx, &c->p))) return rc;
  cli_declare_section(ctx, "transient"); /* the same config files as `rotor transient` */
  cli_declare_section(ctx, "balance");   /* (its [balance] grade concerns transients) */
  c->method_name = "auto";
  if ((rc = cli_get_string(ctx, "stability", "method", c->method_name, &c->method_name, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "stability", "tol", c->opt.tol, &c->opt.tol, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "stability", "floquet_rtol", c->opt.floquet_rtol, &c->opt.floquet_rtol, NULL)))
    return rc;
  if ((rc = cli_get_double(ctx, "stability", "floquet_atol", c->opt.floquet_atol, &c->opt.floquet_atol, NULL)))
    return rc;
  {
    static const char *const names[] = {"auto", "poly", "closed", "full", "floquet"};
    int k, found = -1;
    for (k = 0; k < 5; k++)
      if (!strcmp(c->method_name, names[k])) found = k;
    if (found < 0)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[stability]: method = '%s' is not one of: auto, poly, closed, full, floquet",
                      c->method_name);
    c->opt.method = found;
  }
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++)
    if ((rc = parse_member(ctx, c, j))) return rc;
  autobal_error_clear(&err);
  probe = autobal_rotor_stab_alloc(&c->p, &c->opt, &err);
  if (!probe) return cli_fail(ctx, cli_exit_code(err.status), "%s",
      cli_rotor_message(err.message, msg, sizeof msg));
  if (err.status == AUTOBAL_WARNING && !ctx->json && !ctx->quiet)
    fprintf(stderr, "autobal: warning: %s\n", cli_rotor_message(err.message, msg, sizeof msg));
  autobal_rotor_stab_free(probe);
  return CLI_EXIT_OK;
}

static void print_intervals(const char *what, const char *unit, const autobal_rotor_crit *cr, double lo, double hi) {
  size_t i;
  printf("  critical values of %s in [%g, %g] %s:", what, lo, hi, unit);
  if (cr->n == 0) printf(" none");
  for (i = 0; i < cr->n; i++)
    printf(" %.10g (%s)", cr->value[i],
           cr->kind[i] > 0 ? "stable above" : (cr->kind[i] < 0 ? "unstable above" : "balanced configuration appears/disappears"));
  printf("\n  STABLE %s intervals:", what);
  if (cr->n_stable == 0) printf(" none in the range");
  for (i = 0; i < cr->n_stable; i++) {
    printf(" [%.10g, %.10g]", cr->stable_lo[i], cr->stable_hi[i]);
    if (cr->stable_hi[i] == hi) printf(" (to the end of the range)");
  }
  printf("\n");
  if (strcmp(unit, "rad/s") == 0 && (cr->n > 0 || cr->n_stable > 0)) { /* the same speeds in rpm */
    printf("  in rpm: critical");
    for (i = 0; i < cr->n; i++) printf(" %.6g", cli_rpm(cr->value[i]));
    printf("; stable");
    for (i = 0; i < cr->n_stable; i++) printf(" [%.6g, %.6g]", cli_rpm(cr->stable_lo[i]), cli_rpm(cr->stable_hi[i]));
    printf("\n");
  }
  if (cr->truncated)
    printf("  (TRUNCATED: more critical values than the list holds; the results cover [%g, %.10g] only)\n", lo,
           cr->value[cr->n - 1]);
}

/* Two planes: per speed whether plane 2's range was decided exactly (the box search). */
static void print_speeds2(const autobal_rotor_crit *cr, const autobal_rotor_speeds2_detail *d, size_t n) {
  size_t i, n_ex = 0;
  for (i = 0; i < n; i++)
    if (d->grid_exact[i]) n_ex++;
  printf("  plane 2's range decided exactly (box search) at %zu of %zu speeds evaluated (%zu of %zu grid speeds); "
         "%zu boxes\n",
         d->n_evaluated - d->n_undecided, d->n_evaluated, n_ex, n, d->boxes);
  if (cr->n_stable > 0) {
    printf("  stable intervals, plane 2:");
    for (i = 0; i < cr->n_stable; i++)
      if (d->interval_exact[i]) printf(" [%.10g, %.10g] exact", cr->stable_lo[i], cr->stable_hi[i]);
      else
        printf(" [%.10g, %.10g] SAMPLED at %zu speed(s)", cr->stable_lo[i], cr->stable_hi[i], d->interval_undecided[i]);
    printf("\n");
  }
  if (cr->n > 0) {
    printf("  critical speeds, plane 2:");
    for (i = 0; i < cr->n; i++) printf(" %.10g %s", cr->value[i], d->critical_exact[i] ? "exact" : "SAMPLED");
    printf("\n");
  }
  if (d->n_undecided > 0) {
    size_t shown = 0;
    printf("  grid speeds where plane 2 was sampled (the box search undecided or off):");
    for (i = 0; i < n && shown < 20; i++)
      if (!d->grid_exact[i] && d->grid_stable[i] >= 0) {
        printf(" %.6g", d->grid_omega[i]);
        shown++;
      }
    if (shown == 20) printf(" ...");
    printf(" rad/s\n");
  }
}

static void json_speeds2(cli_json *j, const autobal_rotor_crit *cr, const autobal_rotor_speeds2_detail *d, size_t n) {
  size_t i;
  cli_json_int(j, "n_speeds_evaluated", (long)d->n_evaluated);
  cli_json_int(j, "n_speeds_undecided_in_unbalance2", (long)d->n_undecided);
  cli_json_int(j, "boxes", (long)d->boxes);
  cli_json_array(j, "critical_exact_in_unbalance2");
  for (i = 0; i < cr->n; i++) cli_json_bool(j, NULL, d->critical_exact[i]);
  cli_json_array_end(j);
  cli_json_array(j, "interval_exact_in_unbalance2");
  for (i = 0; i < cr->n_stable; i++) cli_json_bool(j, NULL, d->interval_exact[i]);
  cli_json_array_end(j);
  cli_json_quantities(j, "grid_omega", d->grid_omega, n, "rad/s");
  cli_json_array(j, "grid_stable");
  for (i = 0; i < n; i++) cli_json_int(j, NULL, d->grid_stable[i]);
  cli_json_array_end(j);
  cli_json_array(j, "grid_exact_in_unbalance2");
  for (i = 0; i < n; i++) cli_json_bool(j, NULL, d->grid_exact[i]);
  cli_json_array_end(j);
  cli_json_array(j, "grid_boxes");
  for (i = 0; i < n; i++) cli_json_int(j, NULL, (long)d->grid_boxes[i]);
  cli_json_array_end(j);
}

static void json_crit(cli_json *j, const autobal_rotor_crit *cr, const char *unit) {
  size_t i;
  cli_json_quantities(j, "critical_values", cr->value, cr->n, unit);
  cli_json_array(j, "critical_kind");
  for (i = 0; i < cr->n; i++) cli_json_int(j, NULL, cr->kind[i]);
  cli_json_array_end(j);
  cli_json_quantities(j, "stable_lo", cr->stable_lo, cr->n_stable, unit);
  cli_json_quantities(j, "stable_hi", cr->stable_hi, cr->n_stable, unit);
  cli_json_bool(j, "truncated", cr->truncated);
}

static const char *verdict_text(int v) {
  return v == AUTOBAL_ROTOR_VERDICT_NONE ? "none (no balanced configuration)" : autobal_verdict_name(v);
}

/* A default speed range for critical speeds: from 5% of the lowest natural frequency at rest to
 * 4 times the larger of the highest one and |omega|. */
static void default_speed_range(const autobal_rotor_params *p, double *lo, double *hi) {
  autobal_study_rotor_speed_range(p, lo, hi);
}

/* The asymptotic conditions (docs/rotor.md, Asymptotic conditions): beside the exact verdict. */
static const char *asym_word(int applicable) { return applicable ? "applicable" : "NOT applicable"; }
static void print_asymptotic(const autobal_rotor_asymptotic *q) {
  printf("  asymptotic conditions (for comparison only; the verdict above is exact):\n");
  if (q->undamped_defined) {
    if (q->undamped_on_axis)
      printf("    undamped balls (kappa = 0): ball roots on the axis to leading order, next order (O(m_b)) real parts"
             " delta = %.6g, %.6g 1/s, rotor roots max Re %.6g 1/s",
             q->undamped_delta[0], q->undamped_delta[1], q->rotor_re_max);
    else
      printf("    undamped balls (kappa = 0): ball roots off the axis at leading order (max Re %.6g 1/s), rotor roots"
             " max Re %.6g 1/s",
             fmax(fmax(q->undamped_ball_re[0], q->undamped_ball_re[1]), fmax(q->undamped_ball_re[2], q->undamped_ball_re[3])),
             q->rotor_re_max);
    printf(": predicts %s%s; small parameter %.3g (%s, <= %g)\n", q->undamped_stable ? "STABLE" : "UNSTABLE",
           q->undamped_decided ? "" : " (undecided: within its error)", q->undamped_small,
           asym_word(q->undamped_applicable), AUTOBAL_ROTOR_ASYMPTOTIC_SMALL);
  } else {
    if (q->anisotropic)
      printf("    anisotropic supports: G = G+ = %.6g%+.6gi m/N (forward), G- = %.6g%+.6gi m/N (backward, averaged out;"
             " estimate %.3g)\n",
             q->G_re, q->G_im, q->G_minus_re, q->G_minus_im, q->avg_small);
    printf("    light balls: (L1) Re G < 0 [%s], (L2) kappa = %.6g > kappa_min = %.6g 1/s [%s], rotor roots max Re %.6g 1/s:"
           " predicts %s%s; small parameter %.3g (%s, <= %g)\n",
           q->supercritical ? "yes" : "no", q->kappa, q->kappa_min,
           q->supercritical && q->kappa > q->kappa_min ? "yes" : "no", q->rotor_re_max,
           q->light_stable ? "STABLE" : "UNSTABLE", q->light_decided ? "" : " (undecided: within its error)",
           q->light_small, asym_word(q->light_applicable), AUTOBAL_ROTOR_ASYMPTOTIC_SMALL);
  }
  if (q->high_defined)
    printf("    high speed: (H1) 1/m_eff > 0 [%s], (H2) kappa > kappa_inf = %.6g 1/s [%s] (m_eff %.6g kg, h_eff %.6g N s/m):"
           " predicts %s; small parameter %.3g (%s)\n",
           q->m_eff > 0 ? "yes" : "no", q->kappa_inf, q->high_stable ? "yes" : "no", q->m_eff, q->h_eff,
           q->high_stable ? "STABLE for every unbalance"
                          : (q->m_eff > 0 ? "UNSTABLE for unbalances near q = 0" : "UNSTABLE for every unbalance"),
           q->high_small, asym_word(q->high_applicable));
}
static void print_asymptotic2(const autobal_rotor_asymptotic2 *q) {
  printf("  asymptotic condition, two planes (for comparison only; the verdict above is exact):\n");
  printf("    light balls: G11 = %.6g%+.6gi, G12 = %.6g%+.6gi, G22 = %.6g%+.6gi m/N; ball roots max Re %.6g 1/s, rotor roots"
         " max Re %.6g 1/s: predicts %s%s; small parameter %.3g (%s, <= %g)\n",
         q->G_re[0], q->G_im[0], q->G_re[1], q->G_im[1], q->G_re[3], q->G_im[3], q->ball_re_max, q->rotor_re_max,
         q->light_stable ? "STABLE" : "UNSTABLE", q->light_decided ? "" : " (undecided: within its error)",
         q->light_small, asym_word(q->light_applicable), AUTOBAL_ROTOR_ASYMPTOTIC_SMALL);
  if (q->high_defined) {
    if (q->high_mu[0] > 0.0)
      printf("    high speed, balls at q = 0 in both planes: (H1') Gamma positive definite [yes], (H2') mode 1: kappa %.6g >"
             " kappa_inf %.6g 1/s [%s], mode 2: kappa %.6g > kappa_inf %.6g 1/s [%s]: predicts %s%s; small parameter %.3g (%s)\n",
             q->high_kappa_mode[0], q->high_kappa_inf[0], q->high_re[0] < 0.0 ? "yes" : "no", q->high_kappa_mode[1],
             q->high_kappa_inf[1], q->high_re[1] < 0.0 ? "yes" : "no", q->high_stable ? "STABLE" : "UNSTABLE",
             q->high_decided ? "" : " (undecided: within its error)", q->high_small, asym_word(q->high_applicable));
    else
      printf("    high speed, balls at q = 0 in both planes: (H1') Gamma positive definite [no]: predicts UNSTABLE; small"
             " parameter %.3g (%s)\n",
             q->high_small, asym_word(q->high_applicable));
    if (q->high_mu[0] > 0.0)
      printf("    high speed, every unbalance and phase: min kappa %.6g > %.6g 1/s [%s]: predicts %s; small parameter"
             " %.3g (%s)\n",
             fmin(q->kappa[0], q->kappa[1]), q->high_every_kappa, q->high_every_stable ? "yes" : "no",
             q->high_every_stable ? "STABLE for every unbalance" : "nothing (a sufficient condition only)",
             q->high_every_small, asym_word(q->high_every_applicable));
  }
}
static void json_asymptotic2(cli_json *j, const autobal_rotor_asymptotic2 *q) {
  cli_json_object(j, "asymptotic2");
  cli_json_number(j, "small_threshold", AUTOBAL_ROTOR_ASYMPTOTIC_SMALL);
  cli_json_quantities(j, "G_real", q->G_re, 4, "m/N");
  cli_json_quantities(j, "G_imag", q->G_im, 4, "m/N");
  cli_json_quantities(j, "kappa", q->kappa, 2, "1/s");
  cli_json_quantities(j, "q", q->q, 2, "1");
  cli_json_bool(j, "light_predicts_stable", q->light_stable);
  cli_json_quantities(j, "light_ball_root_real", q->ball_re, 8, "1/s");
  cli_json_quantities(j, "light_ball_root_imag", q->ball_im, 8, "1/s");
  cli_json_quantities(j, "light_rotor_root_real", q->rotor_re, 4, "1/s");
  cli_json_quantities(j, "light_rotor_root_imag", q->rotor_im, 4, "1/s");
  cli_json_bool(j, "light_decided", q->light_decided);
  cli_json_number(j, "light_small", q->light_small);
  cli_json_bool(j, "light_applicable", q->light_applicable);
  cli_json_bool(j, "high_defined", q->high_defined);
  if (q->high_defined) { /* high speed, Q1 = Q2 = 0 */
    cli_json_quantities(j, "high_Gamma", q->high_Gamma, 4, "1/kg");
    cli_json_quantities(j, "high_H", q->high_H, 4, "1/(kg s)");
    cli_json_quantities(j, "high_mu", q->high_mu, 2, "1");
    cli_json_quantities(j, "high_kappa_mode", q->high_kappa_mode, 2, "1/s");
    cli_json_quantities(j, "high_kappa_inf", q->high_kappa_inf, 2, "1/s");
    cli_json_quantities(j, "high_re", q->high_re, 2, "1/s");
    cli_json_bool(j, "high_predicts_stable", q->high_stable);
    cli_json_bool(j, "high_decided", q->high_decided);
    cli_json_number(j, "high_small", q->high_small);
    cli_json_bool(j, "high_applicable", q->high_applicable);
    cli_json_quantity(j, "high_every_kappa", q->high_every_kappa, "1/s");
    cli_json_quantity(j, "high_every_kappa_min", fmin(q->kappa[0], q->kappa[1]), "1/s");
    cli_json_bool(j, "high_every_predicts_stable", q->high_every_stable);
    cli_json_number(j, "high_every_small", q->high_every_small);
    cli_json_bool(j, "high_every_applicable", q->high_every_applicable);
  }
  cli_json_object_end(j);
}
static void json_asymptotic(cli_json *j, const autobal_rotor_asymptotic *q) {
  cli_json_object(j, "asymptotic");
  cli_json_number(j, "small_threshold", AUTOBAL_ROTOR_ASYMPTOTIC_SMALL);
  cli_json_quantity(j, "G_real", q->G_re, "m/N");
  cli_json_quantity(j, "G_imag", q->G_im, "m/N");
  cli_json_quantity(j, "kappa", q->kappa, "1/s");
  cli_json_number(j, "q", q->q);
  if (q->anisotropic) { /* G above is G+ */
    cli_json_bool(j, "anisotropic", 1);
    cli_json_quantity(j, "G_minus_real", q->G_minus_re, "m/N");
    cli_json_quantity(j, "G_minus_imag", q->G_minus_im, "m/N");
    cli_json_number(j, "avg_small", q->avg_small);
  }
  if (q->undamped_defined) { /* kappa = 0: the undamped entry instead of (L1), (L2) */
    cli_json_bool(j, "undamped_on_axis", q->undamped_on_axis);
    cli_json_quantities(j, "undamped_delta", q->undamped_delta, 2, "1/s");
    cli_json_quantities(j, "undamped_ball_root_real", q->undamped_ball_re, 4, "1/s");
    cli_json_quantities(j, "undamped_ball_root_imag", q->undamped_ball_im, 4, "1/s");
    cli_json_quantities(j, "undamped_rotor_root_real", q->rotor_re, 4, "1/s");
    cli_json_quantities(j, "undamped_rotor_root_imag", q->rotor_im, 4, "1/s");
    cli_json_bool(j, "undamped_predicts_stable", q->undamped_stable);
    cli_json_bool(j, "undamped_decided", q->undamped_decided);
    cli_json_number(j, "undamped_small", q->undamped_small);
    cli_json_bool(j, "undamped_applicable", q->undamped_applicable);
    goto high;
  }
  cli_json_bool(j, "light_supercritical", q->supercritical);
  cli_json_quantity(j, "light_kappa_min", q->kappa_min, "1/s");
  cli_json_bool(j, "light_predicts_stable", q->light_stable);
  cli_json_quantities(j, "light_ball_root_real", q->ball_re, 4, "1/s");
  cli_json_quantities(j, "light_ball_root_imag", q->ball_im, 4, "1/s");
  cli_json_quantities(j, "light_rotor_root_real", q->rotor_re, 4, "1/s");
  cli_json_quantities(j, "light_rotor_root_imag", q->rotor_im, 4, "1/s");
  cli_json_bool(j, "light_decided", q->light_decided);
  cli_json_number(j, "light_small", q->light_small);
  cli_json_bool(j, "light_applicable", q->light_applicable);
high:
  cli_json_bool(j, "high_defined", q->high_defined);
  if (q->high_defined) {
    cli_json_quantity(j, "high_m_eff", q->m_eff, "kg");
    cli_json_quantity(j, "high_h_eff", q->h_eff, "N s/m");
    cli_json_quantity(j, "high_kappa_inf", q->kappa_inf, "1/s");
    cli_json_bool(j, "high_predicts_stable", q->high_stable);
    cli_json_number(j, "high_small", q->high_small);
    cli_json_bool(j, "high_applicable", q->high_applicable);
  }
  cli_json_object_end(j);
}

/* Equal to 1e-12 (relative), the library's test of isotropic supports (rotor_closed.c). */
static int near(double a, double b) { return fabs(a - b) <= 1e-12 * fmax(fabs(a), fabs(b)); }

/* ---- rotor stability: the library's study (autobal_study_rotor_stability) -------------- */
typedef struct stab_partial {
  const autobal_rotor_params *p;
  const autobal_study_rotor_stability_options *o;
  const autobal_study_rotor_stability_summary *sum;
} stab_partial;
static int write_stability(autobal_archive *a, const void *data) {
  const stab_partial *sp = (const stab_partial *)data;
  return autobal_study_rotor_stability_write(a, sp->p, sp->o, sp->sum);
}

int cli_cmd_rotor_stability(cli_ctx *ctx) {
  stab_cfg *c = calloc(1, sizeof *c);
  autobal_study_rotor_stability_options o = autobal_study_rotor_stability_options_default();
  autobal_study_rotor_stability_summary sum;
  const autobal_rotor_stab_result *r = &sum.result;
  const autobal_rotor_crit *cr = &sum.critical;
  autobal_archive *a = NULL;
  autobal_error err;
  char msg[sizeof ctx->err];
  double clo = 0, chi = 0, xtol = o.xtol_rel;
  long cn = (long)o.n_omega;
  int rc = CLI_EXIT_OK, st, have_lo = 0, have_hi = 0, do_crit = o.critical_speeds, have_umin = 0, have_umax = 0;
  const char *umember = "every";
  double umin = NAN, umax = NAN, u2min = NAN, u2max = NAN;
  long n_unb = 9, n_boxes = 0;
  int have_u2min = 0, have_u2max = 0, have_nunb = 0, have_boxes = 0;
  size_t i;
  memset(&sum, 0, sizeof sum);
  if (!c) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  if ((rc = read_stab_cfg(ctx, c))) goto done;
  autobal_study_rotor_speed_range(&c->p, &clo, &chi);
  if ((rc = cli_get_bool(ctx, "stability", "critical_speeds", do_crit, &do_crit, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "stability", "omega_min", "rad/s", clo, &clo, &have_lo))) goto done;
  if ((rc = cli_get_quantity(ctx, "stability", "omega_max", "rad/s", chi, &chi, &have_hi))) goto done;
  if ((rc = cli_get_int(ctx, "stability", "n_omega", cn, &cn, NULL))) goto done;
  if ((rc = cli_get_double(ctx, "stability", "xtol_rel", xtol, &xtol, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "stability", "unbalance_min", "kg m", NAN, &umin, &have_umin))) goto done;
  if ((rc = cli_get_quantity(ctx, "stability", "unbalance_max", "kg m", NAN, &umax, &have_umax))) goto done;
  if ((rc = read_unbalance_member(ctx, "stability", &c->opt.unbalance_member, &umember))) goto done;
  if ((rc = read_member_boxes(ctx, "stability", &c->opt.member_boxes))) goto done;
  if ((rc = read_hill_boxes(ctx, "stability", &c->opt.hill_boxes))) goto done;
  if ((rc = cli_get_quantity(ctx, "stability", "unbalance2_min", "kg m", NAN, &u2min, &have_u2min))) goto done;
  if ((rc = cli_get_quantity(ctx, "stability", "unbalance2_max", "kg m", NAN, &u2max, &have_u2max))) goto done;
  if ((rc = cli_get_int(ctx, "stability", "n_unbalance", n_unb, &n_unb, &have_nunb))) goto done;
  if ((rc = cli_get_int(ctx, "stability", "unbalance2_boxes", 0, &n_boxes, &have_boxes))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  if ((have_u2min || have_u2max || have_nunb || have_boxes) && (c->p.n_planes != 2 || !have_umin)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[stability]: unbalance2_min, unbalance2_max, n_unbalance and unbalance2_boxes are for two planes "
                  "(here %zu) with unbalance_min and unbalance_max (every unbalance)",
                  c->p.n_planes);
    goto done;
  }
  if (n_boxes < -1 || n_boxes > 1000000000L) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[stability]: unbalance2_boxes = %ld is out of range: allowed -1 (no box search: plane 2 on its grid "
                  "alone), 0 (the default budget, 100000) or [1, 1e9]",
                  n_boxes);
    goto done;
  }
  c->opt.unbalance2_boxes = n_boxes;
  if (have_u2min != have_u2max) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[stability]: unbalance2_min and unbalance2_max go together (plane 2's range of m0 r0; default: "
                  "plane 1's)");
    goto done;
  }
  if (n_unb < 2 || n_unb > 1000) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[stability]: n_unbalance = %ld must be in [2, 1000] (grid points per plane)",
                  n_unb);
    goto done;
  }
  if (have_umin != have_umax) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[stability]: unbalance_min and unbalance_max go together (the range of m0 r0 for 'every unbalance', "
                  "e.g. unbalance_min = 10 g mm, unbalance_max = 4000 g mm)");
    goto done;
  }
  if (!(c->p.omega != 0.0)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[rotor]: omega = 0: the balanced motion of a rotor at rest has no stability to analyse");
    goto done;
  }
  if (do_crit && (!(clo > 0 && clo < chi) || cn < 2 || cn > 10000000 || !(xtol > 0 && xtol < 0.1))) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[stability]: need 0 < omega_min < omega_max, n_omega in [2, 1e7], xtol_rel in (0, 0.1); got %g, %g, %ld, %g",
                  clo, chi, cn, xtol);
    goto done;
  }
  o.stab = c->opt;
  o.critical_speeds = do_crit;
  o.omega_min = clo;
  o.omega_max = chi;
  o.n_omega = (size_t)cn;
  o.xtol_rel = xtol;
  o.every_unbalance = have_umin && have_umax;
  o.unbalance_min = umin;
  o.unbalance_max = umax;
  o.unbalance2_min = u2min;
  o.unbalance2_max = u2max;
  o.n_unbalance = (size_t)n_unb;
  o.progress = stop_requested;
  /* anisotropic supports, every unbalance and the speed scan: Hill's box search at every grid speed
   * takes seconds per speed (docs/rotor.md "Anisotropic supports: Hill's method"), so say so first */
  if (o.every_unbalance && o.critical_speeds && c->p.n_planes == 1 && !ctx->json && !ctx->quiet) {
    autobal_rotor_lumped L;
    autobal_error lerr;
    int have_l = 1;
    autobal_error_clear(&lerr);
    if (c->p.input == AUTOBAL_ROTOR_LUMPED) L = c->p.lumped;
    else have_l = autobal_rotor_lumped_from_hardware(&c->p.hw, &L, &lerr) == AUTOBAL_SUCCESS;
    if (have_l && !(near(L.c_x, L.c_y) && near(L.c_alpha, L.c_beta) && near(L.c_xbeta, L.c_yalpha) &&
                    near(L.h_x, L.h_y) && near(L.h_alpha, L.h_beta) && near(L.h_xbeta, L.h_yalpha)))
      fprintf(stderr,
              "autobal: note: anisotropic supports: every unbalance runs Hill's method at each of the %zu speeds of "
              "the scan (seconds per speed; [stability] n_omega = 40 or critical_speeds = false for a quicker run)\n",
              o.n_omega);
  }
  /* the analysis first, the archive afterwards: a failed analysis leaves no file */
  autobal_error_clear(&err);
  st = autobal_study_rotor_stability(&c->p, &o, NULL, &sum, &err);
  if (sum.critical_truncated && !ctx->json)
    fprintf(stderr, "autobal: warning: critical speeds: %s\n", cli_rotor_message(sum.critical_message, msg, sizeof msg));
  if (st == AUTOBAL_ECANCELLED) {
    stab_partial sp;
    sp.p = &c->p, sp.o = &o, sp.sum = &sum;
    rc = finish_interrupted(ctx, "autobal rotor stability",
                            sum.critical_cancelled ? "the analysis at omega is complete, the critical-speed search was not"
                                                   : err.message,
                            sum.critical_cancelled ? write_stability : NULL, &sp);
    goto done;
  }
  if (st) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s", cli_rotor_message(err.message, msg, sizeof msg));
    goto done;
  }
  if ((rc = cli_archive_open(ctx, "autobal rotor stability", &a))) goto done;
  if (a) {
    st = autobal_study_rotor_stability_write(a, &c->p, &o, &sum);
    rc = cli_archive_end(ctx, &a, st, rc);
    if (rc) goto done;
  }
  if (ctx->json) {
    cli_json j;
    cli_json_summary_begin(&j, ctx);
    cli_json_quantity(&j, "omega", c->p.omega, "rad/s");
    cli_json_string(&j, "method", autobal_rotor_stab_method_name(r->method));
    cli_json_string(&j, "verdict", verdict_text(r->verdict));
    cli_json_quantity(&j, "margin", r->margin, "1/s");
    cli_json_quantities(&j, "psi_balanced", r->psi, r->n_balls, "rad");
    cli_json_int(&j, "n_family", (long)r->n_family);
    if (r->n_poly) cli_json_string(&j, "hurwitz_verdict", autobal_verdict_name(r->hurwitz_verdict));
    cli_json_number(&j, "root_eig_mismatch", r->n_closed ? r->root_eig_mismatch : NAN);
    cli_json_number(&j, "full_mismatch", r->full_mismatch);
    cli_json_number(&j, "floquet_mismatch", r->floquet_mismatch);
    /* the roots behind the verdict: Delta's (one plane) or the closed matrix's eigenvalues (two
     * planes), the closed matrix's eigenvalues matched to them, the full model's eigenvalues
     * (isotropic), the Floquet multipliers; arrays present only where computed */
    if (r->n_poly) cli_json_numbers(&j, "char_poly", r->poly, r->n_poly);
    if (r->n_closed) {
      cli_json_quantities(&j, "root_real", r->root_re, r->n_closed, "1/s");
      cli_json_quantities(&j, "root_imag", r->root_im, r->n_closed, "1/s");
      cli_json_quantities(&j, "closed_eig_real", r->closed_eig_re, r->n_closed, "1/s");
      cli_json_quantities(&j, "closed_eig_imag", r->closed_eig_im, r->n_closed, "1/s");
    }
    if (r->n_full) {
      cli_json_quantities(&j, "full_eig_real", r->full_re, r->n_full, "1/s");
      cli_json_quantities(&j, "full_eig_imag", r->full_im, r->n_full, "1/s");
    }
    if (r->n_floquet) {
      cli_json_quantities(&j, "floquet_mu_real", r->mu_re, r->n_floquet, "1");
      cli_json_quantities(&j, "floquet_mu_imag", r->mu_im, r->n_floquet, "1");
      cli_json_quantity(&j, "period", r->period, "s");
    }
    if (do_crit) json_crit(&j, cr, "rad/s");
    if (sum.have_asymptotic) json_asymptotic(&j, &sum.asymptotic);
    if (sum.have_asymptotic2) json_asymptotic2(&j, &sum.asymptotic2);
    if (sum.have_every) {
      const autobal_rotor_unbalance_range *u = &sum.every;
      cli_json_object(&j, "every_unbalance");
      cli_json_quantity(&j, "unbalance_min", u->s_lo, "kg m");
      cli_json_quantity(&j, "unbalance_max", u->s_hi, "kg m");
      cli_json_bool(&j, "stable_for_all", u->all_stable);
      if (u->n_balls >= 3) {
        cli_json_string(&j, "unbalance_member", umember);
        cli_json_int(&j, "n_balls", (long)u->n_balls);
        cli_json_quantity(&j, "u_min", u->u_min, "kg^2");
        cli_json_quantity(&j, "u_max", u->u_max, "kg^2");
        if (u->member_rule == AUTOBAL_ROTOR_UNBALANCE_EVERY) {
          double ix[3 * AUTOBAL_ROTOR_MAX_UCRIT];
          for (i = 0; i < u->n_upiece; i++) ix[i] = (double)u->upiece_crit[i];
          cli_json_quantities(&j, "critical_u", u->u_crit, u->n_ucrit, "kg^2");
          cli_json_numbers(&j, "critical_u_piece_index", ix, u->n_upiece);
          cli_json_quantities(&j, "critical_u_piece_lo", u->upiece_lo, u->n_upiece, "kg m");
          cli_json_quantities(&j, "critical_u_piece_hi", u->upiece_hi, u->n_upiece, "kg m");
          cli_json_quantities(&j, "u_sub_lo", u->usub_lo, u->n_usub, "kg^2");
          cli_json_quantities(&j, "u_sub_hi", u->usub_hi, u->n_usub, "kg^2");
          cli_json_array(&j, "u_sub_verdict");
          for (i = 0; i < u->n_usub; i++) cli_json_string(&j, NULL, autobal_verdict_name(u->usub_verdict[i]));
          cli_json_array_end(&j);
          cli_json_quantities(&j, "u_sub_margin", u->usub_margin, u->n_usub, "1/s");
          if (u->n_balls >= 4) { /* four or more balls: u_min, u_max enclose; the members found */
            cli_json_quantity(&j, "u_min_inner", u->u_min_inner, "kg^2");
            cli_json_quantity(&j, "u_max_inner", u->u_max_inner, "kg^2");
            cli_json_quantity(&j, "u_gap", (u->u_min_inner - u->u_min) + (u->u_max - u->u_max_inner), "kg^2");
            cli_json_bool(&j, "u_enclosure_complete", u->u_complete);
            cli_json_int(&j, "u_boxes", u->u_boxes);
            cli_json_int(&j, "u_sub_undecided", (long)u->n_uundecided);
          }
        }
      }
      if (u->hill) { /* anisotropic supports: Hill's method */
        cli_json_string(&j, "method", "hill");
        cli_json_int(&j, "hill_order", (long)u->hill_order);
        cli_json_number(&j, "hill_tail", u->hill_tail);
        cli_json_int(&j, "hill_boxes", u->hill_boxes);
        cli_json_int(&j, "hill_open", (long)u->hill_open);
        cli_json_quantity(&j, "unstable_unbalance", u->s_unstable, "kg m");
        cli_json_quantity(&j, "u_min", u->u_min, "kg^2");
        cli_json_quantity(&j, "u_max", u->u_max, "kg^2");
      }
      cli_json_quantities(&j, "critical_unbalance", u->s_crit, u->n_crit, "kg m");
      cli_json_quantities(&j, "sub_lo", u->sub_lo, u->n_sub, "kg m");
      cli_json_quantities(&j, "sub_hi", u->sub_hi, u->n_sub, "kg m");
      cli_json_array(&j, "sub_verdict");
      for (i = 0; i < u->n_sub; i++) cli_json_string(&j, NULL, autobal_verdict_name(u->sub_verdict[i]));
      cli_json_array_end(&j);
      cli_json_int(&j, "n_missed", (long)u->n_missed);
      if (sum.have_every2) {
        const autobal_rotor_unbalance_range2 *u2 = &sum.every2;
        cli_json_object(&j, "two_planes");
        cli_json_quantity(&j, "unbalance2_min", u2->s_lo[1], "kg m");
        cli_json_quantity(&j, "unbalance2_max", u2->s_hi[1], "kg m");
        cli_json_int(&j, "n_unbalance1", (long)u2->n_s[0]);
        cli_json_int(&j, "n_unbalance2", (long)u2->n_s[1]);
        cli_json_int(&j, "n_points_not_stable", (long)u2->n_not_stable);
        cli_json_bool(&j, "exact_in_unbalance1", u2->exact_in_s1);
        cli_json_bool(&j, "exact_in_unbalance2", u2->exact_in_s2);
        cli_json_int(&j, "boxes", (long)u2->boxes);
        cli_json_quantity(&j, "found_unbalance1", u2->found_s[0], "kg m");
        cli_json_quantity(&j, "found_unbalance2", u2->found_s[1], "kg m");
        cli_json_quantity(&j, "found_phase", u2->found_phase, "rad");
        cli_json_int(&j, "n_unbalance2_not_stable", (long)u2->n_slices_not_stable);
        cli_json_quantity(&j, "margin_worst", u2->margin_worst, "1/s");
        cli_json_object_end(&j);
      }
      if (sum.have_every_phase) {
        const autobal_rotor_phase_range *ph = &sum.every_phase;
        cli_json_object(&j, "phase");
        cli_json_quantity(&j, "unbalance1", ph->s[0], "kg m");
        cli_json_quantity(&j, "unbalance2", ph->s[1], "kg m");
        cli_json_bool(&j, "stable_for_all_phases", ph->all_stable);
        cli_json_quantities(&j, "critical_phase", ph->phase_crit, ph->n_crit, "rad");
        cli_json_quantities(&j, "crossing_frequency", ph->y_crit, ph->n_crit, "1/s");
        cli_json_quantities(&j, "arc_lo", ph->sub_lo, ph->n_sub, "rad");
        cli_json_quantities(&j, "arc_hi", ph->sub_hi, ph->n_sub, "rad");
        cli_json_array(&j, "arc_verdict");
        for (i = 0; i < ph->n_sub; i++) cli_json_string(&j, NULL, autobal_verdict_name(ph->sub_verdict[i]));
        cli_json_array_end(&j);
        cli_json_int(&j, "n_missed", (long)ph->n_missed);
        cli_json_object_end(&j);
      }
      if (sum.have_every_speeds) {
        cli_json_object(&j, "speeds");
        json_crit(&j, &sum.every_speeds, "rad/s");
        if (sum.have_every_speeds2) json_speeds2(&j, &sum.every_speeds, &sum.every_speeds2, sum.every_speeds2_n);
        cli_json_object_end(&j);
      }
      cli_json_object_end(&j);
    }
    cli_json_summary_end(&j, ctx);
  } else if (!ctx->quiet) {
    printf("rotor stability at omega = %.6g rad/s (%.1f rpm), %zu plane(s), %zu ball(s), %s supports\n", c->p.omega,
           c->p.omega * 60.0 / TWO_PI, c->p.n_planes, r->n_balls, r->isotropic ? "isotropic" : "anisotropic");
    printf("  balanced configuration (3.14), member %s:", c->member_name[0]);
    for (i = 0; i < r->n_balls && i < 16; i++) printf(" %.7f", r->psi[i]);
    printf(" rad\n");
    if (r->n_family)
      printf("  neutral family: %zu root(s) at 0 (Floquet multipliers 1) excluded: the verdict is the stability of the family\n",
             r->n_family);
    printf("  BALANCED MOTION: %s (method %s), margin max Re(lambda) = %.6e 1/s\n", verdict_text(r->verdict),
           autobal_rotor_stab_method_name(r->method), r->margin);
    if (r->n_poly)
      printf("  Routh-Hurwitz on Delta: %s (%d root(s) with Re > 0)\n", autobal_verdict_name(r->hurwitz_verdict),
             r->hurwitz_n_rhp);
    if (r->n_closed) {
      printf("  %-3s %22s %22s\n", "#", "root: Re (1/s)", "Im (1/s)");
      for (i = 0; i < r->n_closed; i++) printf("  %-3zu %22.12e %22.12e\n", i, r->root_re[i], r->root_im[i]);
      printf("  roots vs closed-matrix eigenvalues: %.3e (relative)\n", r->root_eig_mismatch);
    }
    if (r->n_full) printf("  full model (rotating coordinates) vs closed roots + family: %.3e (relative)\n", r->full_mismatch);
    if (r->n_floquet) {
      printf("  Floquet (T = %.6g s): margin log|mu|/T = %.6e 1/s; ", r->period, r->floquet_margin);
      if (isnan(r->floquet_mismatch)) printf("vs exp(lambda T): not applicable (no constant-coefficient roots to compare)\n");
      else printf("vs exp(lambda T): %.3e\n", r->floquet_mismatch);
    }
    if (sum.have_asymptotic) print_asymptotic(&sum.asymptotic);
    if (sum.have_asymptotic2) print_asymptotic2(&sum.asymptotic2);
    if (do_crit) print_intervals("speed (omega)", "rad/s", cr, c->p.omega > 0 ? clo : -chi, c->p.omega > 0 ? chi : -clo);
    if (sum.have_every) {
      const autobal_rotor_unbalance_range *u = &sum.every;
      printf("  EVERY UNBALANCE m0 r0 in [%.6g, %.6g] g mm at this speed: %s\n", u->s_lo * 1e6, u->s_hi * 1e6,
             u->all_stable                                                   ? "STABLE for all"
             : u->hill && u->sub_verdict[0] == AUTOBAL_ROTOR_VERDICT_NONE ? "UNDECIDED (not shown stable for all)"
                                                                             : "NOT stable for all");
      if (u->n_balls >= 3)
        printf("  %zu identical balls, unbalance_member = %s: u = |Q|^2/4 in [%.9g, %.9g] kg^2 over the range\n",
               u->n_balls, umember, u->u_min, u->u_max);
      if (u->n_balls >= 4 && u->member_rule == AUTOBAL_ROTOR_UNBALANCE_EVERY)
        printf("  (an enclosure: members found have u from %.9g to %.9g kg^2, every u between met; gap %.3g kg^2 "
               "below, %.3g above; %ld boxes, %s; %zu sub-interval(s) of u undecided)\n",
               u->u_min_inner, u->u_max_inner, u->u_min_inner - u->u_min, u->u_max - u->u_max_inner, u->u_boxes,
               u->u_complete ? "closed to tolerance" : "budget reached", u->n_uundecided);
      if (sum.have_every2) {
        const autobal_rotor_unbalance_range2 *u2 = &sum.every2;
        printf("  two planes: plane 1 m0 r0 in [%.6g, %.6g] g mm (%s), plane 2 in [%.6g, %.6g] g mm (%s; %zu grid "
               "value(s)), every relative phase (exact): %zu plane-2 grid value(s) not stable; %zu of %zu grid points "
               "not stable; worst margin %.6e 1/s\n",
               u2->s_lo[0] * 1e6, u2->s_hi[0] * 1e6, u2->exact_in_s1 ? "all of it, exact" : "a grid, sampled",
               u2->s_lo[1] * 1e6, u2->s_hi[1] * 1e6,
               u2->exact_in_s2 ? "all of it, exact"
               : u2->boxes     ? "SAMPLED: the box search was undecided"
                               : "SAMPLED: no box search",
               u2->n_s[1],
               u2->n_slices_not_stable, u2->n_not_stable, u2->n_points, u2->margin_worst);
        if (!isnan(u2->found_s[1]))
          printf("  a root on the imaginary axis (box search): m0 r0 = %.6g, %.6g g mm, phase %.6g rad\n",
                 u2->found_s[0] * 1e6, u2->found_s[1] * 1e6, u2->found_phase);
        if (!u2->all_stable)
        {
          if (isnan(u2->first_bad_s[0]))
            printf("  first not stable: plane 2 m0 r0 = %.6g g mm, plane 1 between its grid points\n",
                   u2->first_bad_s[1] * 1e6);
          else
            printf("  first not stable: m0 r0 = %.6g, %.6g g mm\n", u2->first_bad_s[0] * 1e6, u2->first_bad_s[1] * 1e6);
        }
      } else if (u->hill) {
        /* anisotropic supports: Hill's method (no critical unbalances computed) */
        if (u->hill_order == 0) /* no bounded truncation at this speed */
          printf("  anisotropic supports, Hill's method: no truncation with |k| <= 40 harmonics is bounded at this "
                 "speed (tail bound %.3g > 1e-4), so the range is not proven stable%s\n",
                 u->hill_tail, isnan(u->s_unstable) ? "" : "; a member is unstable");
        else
          printf("  anisotropic supports, Hill's method (harmonics |k| <= %zu, tail bound %.3g): %ld boxes of "
                 "(frequency, unbalance), %zu left open%s\n",
                 u->hill_order, u->hill_tail, u->hill_boxes, u->hill_open,
                 u->hill_open ? " (budget reached: [stability] hill_boxes)"
                 : u->hill_boxes ? ": no Floquet multiplier on the unit circle anywhere in the range"
                                 : " (not needed: a member is not stable)");
        if (!isnan(u->s_unstable))
          printf("  unstable member (Floquet): m0 r0 = %.8g g mm\n", u->s_unstable * 1e6);
        printf("  verdict: [%.6g, %.6g] %s (g mm); Floquet margin at the middle %.6e 1/s, largest met %.6e 1/s (%zu "
               "Floquet runs)\n",
               u->sub_lo[0] * 1e6, u->sub_hi[0] * 1e6, autobal_verdict_name(u->sub_verdict[0]), u->sub_margin[0],
               u->margin_worst, u->evaluations);
      } else if (u->n_balls >= 3 && u->member_rule == AUTOBAL_ROTOR_UNBALANCE_EVERY) {
        /* three balls, every member: the verdict depends only on u, so the critical values are u's */
        size_t k;
        printf("  critical values of u (a root of Delta on the imaginary axis):%s\n",
               u->n_ucrit == 0 ? " none inside the range of u" : "");
        for (i = 0; i < u->n_ucrit; i++) {
          if (u->n_balls >= 4) {
            printf("    u = %.9g kg^2\n", u->u_crit[i]);
            continue;
          }
          printf("    u = %.9g kg^2, met by some member for m0 r0 in", u->u_crit[i]);
          for (k = 0; k < u->n_upiece; k++)
            if (u->upiece_crit[k] == i) printf(" [%.8g, %.8g]", u->upiece_lo[k] * 1e6, u->upiece_hi[k] * 1e6);
          printf(" g mm\n");
        }
        printf("  verdict between them (every member whose u lies there):");
        for (i = 0; i < u->n_usub; i++)
          printf(" [%.9g, %.9g] %s", u->usub_lo[i], u->usub_hi[i], autobal_verdict_name(u->usub_verdict[i]));
        printf(" (u, kg^2)\n");
      } else {
        printf("  critical unbalances (a root of Delta on the imaginary axis):");
        if (u->n_crit == 0) printf(" none in the range");
        for (i = 0; i < u->n_crit; i++) printf(" %.8g", u->s_crit[i] * 1e6);
        printf("%s\n  verdict between them:", u->n_crit > 0 ? " g mm" : "");
        for (i = 0; i < u->n_sub; i++)
          printf(" [%.6g, %.6g] %s", u->sub_lo[i] * 1e6, u->sub_hi[i] * 1e6, autobal_verdict_name(u->sub_verdict[i]));
        printf(" (g mm)\n");
      }
      if (sum.have_every_phase) {
        const autobal_rotor_phase_range *ph = &sum.every_phase;
        printf("  every relative phase (plane2.psi0 - plane1.psi0, period pi) at this configuration's m0 r0 = %.6g, %.6g g "
               "mm: %s\n  critical phases:",
               ph->s[0] * 1e6, ph->s[1] * 1e6, ph->all_stable ? "STABLE for all" : "NOT stable for all");
        if (ph->n_crit == 0) printf(" none");
        for (i = 0; i < ph->n_crit; i++) printf(" %.9f", ph->phase_crit[i]);
        printf(" rad\n  verdict between them:");
        for (i = 0; i < ph->n_sub; i++)
          printf(" [%.6f, %.6f] %s", ph->sub_lo[i], ph->sub_hi[i], autobal_verdict_name(ph->sub_verdict[i]));
        printf(" (rad)\n");
      }
      if (u->n_missed)
        printf("  (%zu change(s) of the verdict found by bisection, not by the crossing polynomial)\n", u->n_missed);
      if (sum.have_every_speeds)
        print_intervals("speed for every unbalance", "rad/s", &sum.every_speeds,
                        c->p.omega > 0 ? clo : -chi, c->p.omega > 0 ? chi : -clo);
      if (sum.have_every_speeds2) print_speeds2(&sum.every_speeds, &sum.every_speeds2, sum.every_speeds2_n);
    }
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  autobal_study_rotor_stability_summary_free(&sum);
  if (c) free(c->storage);
  free(c);
  (void)have_lo;
  (void)have_hi;
  return rc;
}

/* ---- rotor sweep ------------------------------------------------------------------------ */
static int read_param(cli_ctx *ctx, const char *sec, const char *key, const char *def, int *param) {
  const char *name = def;
  int rc;
  if ((rc = cli_get_string(ctx, sec, key, def, &name, NULL))) return rc;
  *param = autobal_rotor_stab_param_from_name(name);
  if (*param < 0)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[%s]: %s = '%s' is not a parameter: one of omega, ball_damping, ball_mass, stiffness_scale, "
                    "damping_scale, unbalance_mass, anisotropy, C_over_A, a key of [rotor] or [supports] (e.g. "
                    "supports.c_Lx, rotor.M_k) or of [lumped] (e.g. lumped.h_x), or planeN.KEY with KEY one of d, m0, "
                    "r0, psi0, unbalance, ball_mass, ball_radius, ball_damping (docs/rotor.md \"Sweeps and maps\")",
                    sec, key, name);
  return CLI_EXIT_OK;
}

/* The ends of a parameter's range are values the model accepts: each is set on a handle of the
 * rotor (autobal_rotor_stab_set), whose message names the key and its allowed range; a key that
 * is not a parameter of this rotor (a hardware key of a lumped rotor, plane2 of a one-plane
 * rotor) fails the same way.  Exit 3 before anything is computed. */
static int check_param_range(cli_ctx *ctx, const autobal_rotor_params *p, const char *sec, int param, const char *klo,
                             double lo, const char *khi, double hi) {
  autobal_error e;
  autobal_rotor_stab *h;
  int st, rc = CLI_EXIT_OK;
  autobal_error_clear(&e);
  if (!(h = autobal_rotor_stab_alloc(p, NULL, &e))) return cli_fail(ctx, CLI_EXIT_INPUT, "%s", e.message);
  if ((st = autobal_rotor_stab_set(h, param, lo)) != AUTOBAL_SUCCESS)
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s: %s", sec, klo, autobal_rotor_stab_errmsg(h));
  else if ((st = autobal_rotor_stab_set(h, param, hi)) != AUTOBAL_SUCCESS)
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s: %s", sec, khi, autobal_rotor_stab_errmsg(h));
  autobal_rotor_stab_free(h);
  return rc;
}

static double param_default_hi(const stab_cfg *c, int param) {
  double lo, hi;
  autobal_study_rotor_param_range(&c->p, param, &lo, &hi);
  return hi;
}
static double param_default_lo(const stab_cfg *c, int param) {
  double lo, hi;
  autobal_study_rotor_param_range(&c->p, param, &lo, &hi);
  return lo;
}

/* The progress bar of the sweep, drawn when the fraction changed (the critical-value search
 * calls with the same fraction before every margin evaluation, to poll the signal flag). */
typedef struct sweep_bar {
  cli_ctx *ctx;
  double last;
} sweep_bar;
static int sweep_progress(double fraction, void *user) {
  sweep_bar *b = (sweep_bar *)user;
  if (fraction == b->last) return cli_interrupted();
  b->last = fraction;
  return cli_progress(b->ctx, "rotor sweep", fraction);
}

typedef struct sweep_partial {
  const autobal_rotor_params *p;
  const autobal_study_rotor_sweep_options *o;
  const autobal_study_rotor_sweep_summary *sum;
} sweep_partial;
static int write_sweep(autobal_archive *a, const void *data) {
  const sweep_partial *sp = (const sweep_partial *)data;
  return autobal_study_rotor_sweep_write(a, sp->p, sp->o, sp->sum);
}

int cli_cmd_rotor_sweep(cli_ctx *ctx) {
  stab_cfg *c = calloc(1, sizeof *c);
  autobal_study_rotor_sweep_options o = autobal_study_rotor_sweep_options_default();
  autobal_study_rotor_sweep_summary sum;
  sweep_bar bar;
  const autobal_rotor_crit *cr = &sum.critical;
  autobal_archive *a = NULL;
  autobal_error err;
  char msg[sizeof ctx->err];
  double lo, hi, xtol = o.xtol_rel;
  int param = 0, rc = CLI_EXIT_OK, st;
  long n = (long)o.n;
  const char *pname, *unit;
  memset(&sum, 0, sizeof sum);
  if (!c) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  if ((rc = read_stab_cfg(ctx, c))) goto done;
  if ((rc = read_param(ctx, "sweep", "param", "omega", &param))) goto done;
  lo = param_default_lo(c, param);
  hi = param_default_hi(c, param);
  unit = autobal_rotor_stab_param_unit(param);
  if ((rc = cli_get_quantity(ctx, "sweep", "min", unit, lo, &lo, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "sweep", "max", unit, hi, &hi, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "sweep", "n", n, &n, NULL))) goto done;
  if ((rc = cli_get_double(ctx, "sweep", "xtol_rel", xtol, &xtol, NULL))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  pname = autobal_rotor_stab_param_name(param);
  unit = autobal_rotor_stab_param_unit(param);
  if ((rc = check_param_range(ctx, &c->p, "sweep", param, "min", lo, "max", hi)) ||
      (rc = need_order(ctx, "sweep", "min", lo, "max", hi, unit, 1)) || (rc = need_int(ctx, "sweep", "n", n, 2, 10000000)) ||
      (rc = need_xtol(ctx, "sweep", xtol)))
    goto done;
  if (param != AUTOBAL_ROTOR_PARAM_OMEGA && !(c->p.omega != 0.0)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[rotor]: omega = 0: nothing to analyse");
    goto done;
  }
  o.stab = c->opt;
  o.param = param;
  o.min = lo;
  o.max = hi;
  o.n = (size_t)n;
  o.xtol_rel = xtol;
  bar.ctx = ctx;
  bar.last = -1.0;
  o.progress = sweep_progress;
  o.progress_user = &bar;
  /* the sweep first (autobal_study_rotor_sweep), the archive afterwards */
  autobal_error_clear(&err);
  st = autobal_study_rotor_sweep(&c->p, &o, NULL, &sum, &err);
  cli_progress_done(ctx);
  if (sum.critical_truncated && !ctx->json)
    fprintf(stderr, "autobal: warning: critical values: %s\n", cli_rotor_message(sum.critical_message, msg, sizeof msg));
  if (st == AUTOBAL_ECANCELLED) {
    sweep_partial sp;
    sp.p = &c->p, sp.o = &o, sp.sum = &sum;
    rc = finish_interrupted(ctx, "autobal rotor sweep", err.message, sum.values ? write_sweep : NULL, &sp);
    goto done;
  }
  if (st) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s", cli_rotor_message(err.message, msg, sizeof msg));
    goto done;
  }
  if ((rc = cli_archive_open(ctx, "autobal rotor sweep", &a))) goto done;
  if (a) {
    st = autobal_study_rotor_sweep_write(a, &c->p, &o, &sum);
    rc = cli_archive_end(ctx, &a, st, rc);
    if (rc) goto done;
  }
  if (ctx->json) {
    cli_json j;
    cli_json_summary_begin(&j, ctx);
    cli_json_string(&j, "param", pname);
    cli_json_string(&j, "unit", unit);
    cli_json_quantity(&j, "min", lo, unit);
    cli_json_quantity(&j, "max", hi, unit);
    cli_json_int(&j, "n", n);
    cli_json_int(&j, "n_stable_points", (long)sum.n_stable);
    json_crit(&j, cr, unit);
    cli_json_summary_end(&j, ctx);
  } else if (!ctx->quiet) {
    printf("rotor sweep of %s over [%g, %g] %s, %ld points (omega = %.6g rad/s unless swept)\n", pname, lo, hi, unit, n,
           c->p.omega);
    printf("  stable points: %zu of %ld; %zu evaluations for the refinement\n", sum.n_stable, n, cr->evaluations);
    print_intervals(pname, unit, cr, lo, hi);
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  autobal_study_rotor_sweep_summary_free(&sum);
  if (c) free(c->storage);
  free(c);
  return rc;
}

/* ---- rotor map: the library's study (autobal_study_rotor_map) ---------------------------- */
typedef struct map_partial {
  const autobal_rotor_params *p;
  const autobal_study_rotor_map_options *o;
  const autobal_study_rotor_map_summary *sum;
} map_partial;
static int write_map(autobal_archive *a, const void *data) {
  const map_partial *mp = (const map_partial *)data;
  return autobal_study_rotor_map_write(a, mp->p, mp->o, mp->sum);
}

int cli_cmd_rotor_map(cli_ctx *ctx) {
  stab_cfg *c = calloc(1, sizeof *c);
  autobal_study_rotor_map_options o = autobal_study_rotor_map_options_default();
  autobal_study_rotor_map_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  char msg[sizeof ctx->err];
  double lo1, hi1, lo2, hi2;
  int p1 = 0, p2 = 1, rc = CLI_EXIT_OK, st, have_umin = 0, have_umax = 0;
  const char *umember = "every";
  double umin = NAN, umax = NAN;
  long n1 = (long)o.n1, n2 = (long)o.n2, threads = o.threads;
  size_t n, k, n_undecided = 0;
  memset(&sum, 0, sizeof sum);
  if (!c) return cli_fail(ctx, CLI_EXIT_INTERNAL, "out of memory");
  if ((rc = read_stab_cfg(ctx, c))) goto done;
  if ((rc = read_param(ctx, "map", "param1", "omega", &p1))) goto done;
  if ((rc = read_param(ctx, "map", "param2", "ball_damping", &p2))) goto done;
  lo1 = param_default_lo(c, p1);
  hi1 = param_default_hi(c, p1);
  lo2 = param_default_lo(c, p2);
  hi2 = param_default_hi(c, p2);
  if ((rc = cli_get_quantity(ctx, "map", "min1", autobal_rotor_stab_param_unit(p1), lo1, &lo1, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "map", "max1", autobal_rotor_stab_param_unit(p1), hi1, &hi1, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "map", "n1", n1, &n1, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "map", "min2", autobal_rotor_stab_param_unit(p2), lo2, &lo2, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "map", "max2", autobal_rotor_stab_param_unit(p2), hi2, &hi2, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "map", "n2", n2, &n2, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "map", "threads", threads, &threads, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "map", "unbalance_min", "kg m", NAN, &umin, &have_umin))) goto done;
  if ((rc = cli_get_quantity(ctx, "map", "unbalance_max", "kg m", NAN, &umax, &have_umax))) goto done;
  if ((rc = read_unbalance_member(ctx, "map", &c->opt.unbalance_member, &umember))) goto done;
  if ((rc = read_member_boxes(ctx, "map", &c->opt.member_boxes))) goto done;
  if ((rc = read_hill_boxes(ctx, "map", &c->opt.hill_boxes))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  if (have_umin != have_umax) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT,
                  "[map]: unbalance_min and unbalance_max go together (the range of m0 r0 of a map for every "
                  "unbalance, e.g. unbalance_min = 10 g mm, unbalance_max = 4000 g mm)");
    goto done;
  }
  if (p1 == p2) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[map]: param1 and param2 must differ (both %s)", autobal_rotor_stab_param_name(p1));
    goto done;
  }
  if ((rc = check_param_range(ctx, &c->p, "map", p1, "min1", lo1, "max1", hi1)) ||
      (rc = check_param_range(ctx, &c->p, "map", p2, "min2", lo2, "max2", hi2)) ||
      (rc = need_order(ctx, "map", "min1", lo1, "max1", hi1, autobal_rotor_stab_param_unit(p1), 0)) ||
      (rc = need_order(ctx, "map", "min2", lo2, "max2", hi2, autobal_rotor_stab_param_unit(p2), 0)) ||
      (rc = need_int(ctx, "map", "n1", n1, 1, 100000)) || (rc = need_int(ctx, "map", "n2", n2, 1, 100000)) ||
      (rc = need_int(ctx, "map", "threads", threads, 0, 1024)))
    goto done;
  n = (size_t)n1 * (size_t)n2;
  o.stab = c->opt;
  o.param1 = p1, o.param2 = p2;
  o.min1 = lo1, o.max1 = hi1, o.min2 = lo2, o.max2 = hi2;
  o.n1 = (size_t)n1, o.n2 = (size_t)n2;
  o.threads = (int)threads;
  o.every_unbalance = have_umin && have_umax;
  o.unbalance_min = umin;
  o.unbalance_max = umax;
  o.progress = stop_requested;
  autobal_error_clear(&err);
  st = autobal_study_rotor_map(&c->p, &o, NULL, &sum, &err);
  if (st == AUTOBAL_ECANCELLED) {
    map_partial mp;
    mp.p = &c->p, mp.o = &o, mp.sum = &sum;
    rc = finish_interrupted(ctx, "autobal rotor map", err.message, write_map, &mp);
    goto done;
  }
  if (st) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s", cli_rotor_message(err.message, msg, sizeof msg));
    goto done;
  }
  for (k = 0; k < sum.n1_done * sum.n2; k++) n_undecided += sum.verdict[k] == AUTOBAL_ROTOR_VERDICT_UNDECIDED;
  if ((rc = cli_archive_open(ctx, "autobal rotor map", &a))) goto done;
  if (a) {
    st = autobal_study_rotor_map_write(a, &c->p, &o, &sum);
    rc = cli_archive_end(ctx, &a, st, rc);
    if (rc) goto done;
  }
  if (ctx->json) {
    cli_json j;
    cli_json_summary_begin(&j, ctx);
    cli_json_string(&j, "param1", autobal_rotor_stab_param_name(p1));
    cli_json_string(&j, "param2", autobal_rotor_stab_param_name(p2));
    cli_json_int(&j, "n1", n1);
    cli_json_int(&j, "n2", n2);
    cli_json_int(&j, "n_stable", (long)sum.n_stable);
    cli_json_int(&j, "n_undecided", (long)n_undecided);
    cli_json_bool(&j, "every_unbalance", o.every_unbalance);
    if (o.every_unbalance && c->p.plane[0].n_balls >= 3) cli_json_string(&j, "unbalance_member", umember);
    cli_json_quantity(&j, "stable_fraction", (double)sum.n_stable / (double)n, "1");
    cli_json_summary_end(&j, ctx);
  } else if (!ctx->quiet) {
    printf("rotor map %ld x %ld: %s in [%g, %g] %s x %s in [%g, %g] %s\n", n1, n2, autobal_rotor_stab_param_name(p1), lo1,
           hi1, autobal_rotor_stab_param_unit(p1), autobal_rotor_stab_param_name(p2), lo2, hi2,
           autobal_rotor_stab_param_unit(p2));
    if (o.every_unbalance)
      printf("  for EVERY unbalance m0 r0 in [%.6g, %.6g] g mm (each point's verdict covers the whole range)%s%s\n",
             umin * 1e6, umax * 1e6, c->p.plane[0].n_balls >= 3 ? ", unbalance_member = " : "",
             c->p.plane[0].n_balls >= 3 ? umember : "");
    printf("  stable points: %zu of %zu (%.1f%%)\n", sum.n_stable, n, 100.0 * (double)sum.n_stable / (double)n);
    if (n_undecided)
      printf("  undecided points: %zu (anisotropic supports: Hill's box budget reached, no unstable member found; "
             "[map] hill_boxes raises it)\n", n_undecided);
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
done:
  autobal_study_rotor_map_summary_free(&sum);
  if (c) free(c->storage);
  free(c);
  return rc;
}

/* ---- rotor campbell: the library's study (autobal_study_rotor_campbell) --------------------- */
typedef struct campbell_partial {
  const autobal_rotor_params *p;
  const autobal_study_rotor_campbell_summary *sum;
} campbell_partial;
static int write_campbell(autobal_archive *a, const void *data) {
  const campbell_partial *cp = (const campbell_partial *)data;
  return autobal_study_rotor_campbell_write(a, cp->p, cp->sum);
}

int cli_cmd_rotor_campbell(cli_ctx *ctx) {
  autobal_rotor_params p;
  void *storage = NULL;
  autobal_study_rotor_campbell_options o = autobal_study_rotor_campbell_options_default();
  autobal_study_rotor_campbell_summary sum;
  const autobal_rotor_resonances *rr = &sum.resonances;
  const double *fu = sum.natural_frequency_undamped, *fd = sum.natural_frequency_damped, *zd = sum.damping_ratio_at_rest;
  autobal_archive *a = NULL;
  autobal_error err;
  char msg[sizeof ctx->err];
  double lo = 0.0, hi = 0.0, xtol = o.xtol_rel;
  int rc, st;
  long n = (long)o.n, nres = (long)o.n_resonance;
  size_t i;
  memset(&sum, 0, sizeof sum);
  autobal_error_clear(&err);
  if ((rc = cli_rotor_config_read(ctx, &p, &storage))) return rc;
  if ((rc = refuse_gravity(ctx, &p))) {
    free(storage);
    return rc;
  }
  cli_declare_section(ctx, "transient");
  cli_declare_section(ctx, "stability");
  cli_declare_section(ctx, "balance");
  {
    double l0, h0;
    default_speed_range(&p, &l0, &h0);
    hi = h0;
  }
  if ((rc = cli_get_quantity(ctx, "campbell", "omega_min", "rad/s", lo, &lo, NULL))) goto done;
  if ((rc = cli_get_quantity(ctx, "campbell", "omega_max", "rad/s", hi, &hi, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "campbell", "n", n, &n, NULL))) goto done;
  if ((rc = cli_get_int(ctx, "campbell", "n_resonance", nres, &nres, NULL))) goto done;
  if ((rc = cli_get_double(ctx, "campbell", "xtol_rel", xtol, &xtol, NULL))) goto done;
  if ((rc = cli_config_check_unused(ctx))) goto done;
  if (!(lo >= 0)) {
    rc = cli_fail(ctx, CLI_EXIT_INPUT, "[campbell]: omega_min = %g rad/s is too small: must be >= 0", lo);
    goto done;
  }
  if ((rc = need_order(ctx, "campbell", "omega_min", lo, "omega_max", hi, "rad/s", 1)) ||
      (rc = need_int(ctx, "campbell", "n", n, 2, 10000000)) ||
      (rc = need_int(ctx, "campbell", "n_resonance", nres, 3, 10000000)) || (rc = need_xtol(ctx, "campbell", xtol)))
    goto done;
  o.omega_min = lo;
  o.omega_max = hi;
  o.n = (size_t)n;
  o.n_resonance = (size_t)nres;
  o.xtol_rel = xtol;
  o.progress = stop_requested;
  st = autobal_study_rotor_campbell(&p, &o, NULL, &sum, &err);
  if (sum.resonances_truncated && !ctx->json)
    fprintf(stderr, "autobal: warning: resonance speeds: %s\n", cli_rotor_message(sum.resonance_message, msg, sizeof msg));
  if (st == AUTOBAL_ECANCELLED) {
    campbell_partial cp;
    cp.p = &p, cp.sum = &sum;
    rc = finish_interrupted(ctx, "autobal rotor campbell", err.message, sum.n_done > 0 ? write_campbell : NULL, &cp);
    goto done;
  }
  if (st) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s", cli_rotor_message(err.message, msg, sizeof msg));
    goto done;
  }
  if ((rc = cli_archive_open(ctx, "autobal rotor campbell", &a))) goto done;
  if (a) {
    st = autobal_study_rotor_campbell_write(a, &p, &sum);
    rc = cli_archive_end(ctx, &a, st, rc);
    if (rc) goto done;
  }
  if (ctx->json) {
    cli_json jj;
    cli_json_summary_begin(&jj, ctx);
    cli_json_quantities(&jj, "natural_frequency_undamped", fu, 4, "rad/s");
    cli_json_quantities(&jj, "natural_frequency_damped", fd, 4, "rad/s");
    cli_json_quantities(&jj, "damping_ratio_at_rest", zd, 4, "1");
    cli_json_quantities(&jj, "crossing_omega", rr->cross, rr->n_cross, "rad/s");
    cli_json_array(&jj, "crossing_whirl");
    for (i = 0; i < rr->n_cross; i++) cli_json_int(&jj, NULL, rr->cross_whirl[i]);
    cli_json_array_end(&jj);
    cli_json_quantities(&jj, "peak_omega", rr->peak, rr->n_peak, "rad/s");
    cli_json_bool(&jj, "truncated", rr->truncated);
    cli_json_summary_end(&jj, ctx);
  } else if (!ctx->quiet) {
    printf("rotor-housing (balls removed): natural frequencies at rest\n");
    printf("  undamped: %.7g %.7g %.7g %.7g rad/s = %.5g %.5g %.5g %.5g Hz\n", fu[0], fu[1], fu[2], fu[3],
           fu[0] / TWO_PI, fu[1] / TWO_PI, fu[2] / TWO_PI, fu[3] / TWO_PI);
    printf("  damped:   %.7g %.7g %.7g %.7g rad/s = %.5g %.5g %.5g %.5g Hz (damping ratios %.4g %.4g %.4g %.4g)\n",
           fd[0], fd[1], fd[2], fd[3], fd[0] / TWO_PI, fd[1] / TWO_PI, fd[2] / TWO_PI, fd[3] / TWO_PI, zd[0],
           zd[1], zd[2], zd[3]);
    printf("Campbell diagram over omega in [%g, %g] rad/s (%ld points)\n", lo, hi, n);
    printf("  critical speeds (natural frequency = omega):");
    if (rr->n_cross == 0) printf(" none");
    for (i = 0; i < rr->n_cross; i++)
      printf(" %.8g rad/s = %.6g rpm (%s)", rr->cross[i], cli_rpm(rr->cross[i]),
             rr->cross_whirl[i] > 0 ? "forward" : (rr->cross_whirl[i] < 0 ? "backward" : "?"));
    printf("\n  unbalance-response peaks (centre of mass):");
    if (rr->n_peak == 0) printf(" none");
    for (i = 0; i < rr->n_peak; i++)
      printf(" %.8g rad/s = %.6g rpm (%.4g um)", rr->peak[i], cli_rpm(rr->peak[i]), rr->peak_amp[i] * 1e6);
    printf("\n");
    if (rr->truncated)
      printf("  (TRUNCATED: more crossings or peaks than the lists hold; see the warning for the range covered)\n");
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
  rc = CLI_EXIT_OK;
done:
  if (a) rc = cli_archive_finish(ctx, a, rc);
  autobal_study_rotor_campbell_summary_free(&sum);
  free(storage);
  return rc;
}
