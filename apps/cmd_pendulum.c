/* cmd_pendulum.c: `autobal pendulum roots|critical|map|sweep`. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/archive.h"
#include "autobal/pendulum.h"
#include "autobal/study.h"
#include "cli.h"
#include "units.h"

/* Defaults of the built-in example (dimensionless). */
#define DEF_RW 3.0
#define DEF_RM 0.1
#define DEF_H 0.1
/* omega0 = sqrt(c / (M + 2m)) of the physical set (eq. (2)), rad/s. */
static double pendulum_omega0(const autobal_pendulum_physical *phys) { return sqrt(phys->c / (phys->M + 2.0 * phys->m)); }

#define DEF_HP 0.5
#define DEF_K 0.5

int cli_read_pendulum_params(cli_ctx *ctx, autobal_pendulum_params *p, autobal_pendulum_physical *phys,
                             int *physical) {
  static const char *const pkeys[] = {"M", "e", "m", "l", "c", "H1", "H2", "omega"};
  /* SI units of the physical set (H1: viscous moment per unit relative rate of a pendulum; H2:
   * viscous force per unit velocity of the shaft) */
  static const char *const punits[] = {"kg", "m", "kg", "m", "N/m", "N m s", "N s/m", "rad/s"};
  double pv[8];
  int present[8], any_phys = 0, all_phys = 1, rc, i;
  int has_rw, has_rm, has_H, has_h, has_k, has_psi0;
  double R_w, R_m, H, h, k, psi0;
  autobal_error err;
  autobal_error_clear(&err);
  for (i = 0; i < 8; i++) {
    if ((rc = cli_get_quantity(ctx, "pendulum", pkeys[i], punits[i], 0.0, &pv[i], &present[i]))) return rc;
    any_phys |= present[i];
    all_phys &= present[i];
  }
  if ((rc = cli_get_double(ctx, "pendulum", "R_w", DEF_RW, &R_w, &has_rw))) return rc;
  if ((rc = cli_get_double(ctx, "pendulum", "R_m", DEF_RM, &R_m, &has_rm))) return rc;
  if ((rc = cli_get_double(ctx, "pendulum", "H", DEF_H, &H, &has_H))) return rc;
  if ((rc = cli_get_double(ctx, "pendulum", "h", DEF_HP, &h, &has_h))) return rc;
  if ((rc = cli_get_double(ctx, "pendulum", "k", DEF_K, &k, &has_k))) return rc;
  if ((rc = cli_get_quantity(ctx, "pendulum", "psi0", "rad", 0.0, &psi0, &has_psi0))) return rc;
  *physical = any_phys;
  if (any_phys) {
    if (has_rw || has_rm || has_H || has_h || has_k || has_psi0)
      return cli_fail(ctx, CLI_EXIT_INPUT,
                      "[pendulum]: give either the dimensionless keys (R_w, R_m, H, h, k or psi0) or the physical "
                      "keys (M, e, m, l, c, H1, H2, omega), not both");
    if (!all_phys) {
      for (i = 0; i < 8; i++)
        if (!present[i])
          return cli_fail(ctx, CLI_EXIT_INPUT,
                          "[pendulum]: physical parameters need all of M, e, m, l, c, H1, H2, omega; '%s' is missing",
                          pkeys[i]);
    }
    phys->M = pv[0];
    phys->e = pv[1];
    phys->m = pv[2];
    phys->l = pv[3];
    phys->c = pv[4];
    phys->H1 = pv[5];
    phys->H2 = pv[6];
    phys->omega = pv[7];
    if (autobal_pendulum_params_from_physical(phys, p, &err) != AUTOBAL_SUCCESS)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[pendulum]: %s", err.message);
    return CLI_EXIT_OK;
  }
  if (has_k && has_psi0)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[pendulum]: give k or psi0, not both");
  if (has_psi0) {
    p->R_w = R_w;
    p->R_m = R_m;
    p->H = H;
    p->h = h;
    p->psi0 = psi0;
    if (autobal_pendulum_params_validate(p, &err) != AUTOBAL_SUCCESS)
      return cli_fail(ctx, CLI_EXIT_INPUT, "[pendulum]: %s", err.message);
    return CLI_EXIT_OK;
  }
  if (autobal_pendulum_params_from_k(R_w, R_m, H, h, k, p, &err) != AUTOBAL_SUCCESS)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[pendulum]: %s", err.message);
  return CLI_EXIT_OK;
}

/* Parameters as attributes of /pendulum (dimensionless, units "1"), plus the physical set. */
int cli_write_pendulum_params(cli_ctx *ctx, autobal_archive *a, const autobal_pendulum_params *p,
                              const autobal_pendulum_physical *phys, int physical) {
  int st = autobal_study_write_pendulum_params(a, p, physical ? phys : NULL);
  if (st) return cli_fail(ctx, cli_exit_code(st), "%s", autobal_archive_errmsg(a));
  return CLI_EXIT_OK;
}

static void print_params(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys, int physical) {
  printf("parameters (dimensionless): R_w = %.6g  R_m = %.6g  H = %.6g  h = %.6g  psi0 = %.6g rad  k = %.6g\n", p->R_w,
         p->R_m, p->H, p->h, p->psi0, autobal_pendulum_k(p));
  if (physical) {
    double w0 = pendulum_omega0(phys);
    printf("physical: omega0 = sqrt(c/(M + 2m)) = %.6g rad/s (%.6g rpm); omega = R_w omega0 = %.6g rad/s (%.6g rpm); "
           "unbalance M e = %.4g g mm\n",
           w0, cli_rpm(w0), phys->omega, cli_rpm(phys->omega), phys->M * phys->e * 1e6);
  }
}

static const char *cond_text(const autobal_pendulum_sufficient *c) {
  if (c->predicts_stable) return c->applicable ? "predicts stable (applicable)" : "predicts stable (not applicable here)";
  return c->applicable ? "predicts unstable (applicable)" : "predicts unstable (not applicable here)";
}

/* ---- pendulum roots --------------------------------------------------------------- */
int cli_cmd_pendulum_roots(cli_ctx *ctx) {
  autobal_pendulum_params p;
  autobal_pendulum_physical phys;
  autobal_pendulum_result r;
  autobal_archive *a = NULL;
  autobal_error err;
  int physical = 0, rc, st;
  size_t i;

  if ((rc = cli_read_pendulum_params(ctx, &p, &phys, &physical))) return rc;
  if ((rc = cli_config_check_unused(ctx))) return rc;
  /* the analysis first (autobal_study_pendulum_roots), the archive afterwards: a failed
   * analysis leaves no file */
  st = autobal_study_pendulum_roots(&p, physical ? &phys : NULL, NULL, &r, &err);
  if (st != AUTOBAL_SUCCESS) return cli_fail(ctx, cli_exit_code(st), "%s", err.message);
  if ((rc = cli_archive_open(ctx, "autobal pendulum roots", &a))) return rc;
  if (a) {
    st = autobal_study_pendulum_roots_write(a, &p, physical ? &phys : NULL, &r);
    rc = cli_archive_end(ctx, &a, st, CLI_EXIT_OK);
    if (rc) return rc;
  }

  if (ctx->json) {
    cli_json j;
    cli_json_summary_begin(&j, ctx);
    cli_json_object(&j, "parameters");
    cli_json_number(&j, "R_w", p.R_w);
    cli_json_number(&j, "R_m", p.R_m);
    cli_json_number(&j, "H", p.H);
    cli_json_number(&j, "h", p.h);
    cli_json_number(&j, "psi0", p.psi0);
    cli_json_number(&j, "k", autobal_pendulum_k(&p));
    cli_json_object_end(&j);
    cli_json_string(&j, "verdict", autobal_verdict_name(r.verdict));
    cli_json_string(&j, "criterion", autobal_study_pendulum_roots_criterion(&r));
    cli_json_int(&j, "n_right_half_plane", r.n_rhp);
    cli_json_string(&j, "verdict_roots", autobal_verdict_name(r.verdict_roots));
    cli_json_quantity(&j, "max_real", r.max_real, "1");
    cli_json_quantity(&j, "root_eig_mismatch", r.mismatch, "1");
    cli_json_quantities(&j, "char_poly", r.coef, AUTOBAL_PENDULUM_NCOEF, "1");
    cli_json_quantities(&j, "root_real", r.root_re, AUTOBAL_PENDULUM_ORDER, "1");
    cli_json_quantities(&j, "root_imag", r.root_im, AUTOBAL_PENDULUM_ORDER, "1");
    cli_json_quantities(&j, "eig_real", r.eig_re, AUTOBAL_PENDULUM_ORDER, "1");
    cli_json_quantities(&j, "eig_imag", r.eig_im, AUTOBAL_PENDULUM_ORDER, "1");
    cli_json_bool(&j, "cond7_predicts_stable", r.cond7.predicts_stable);
    cli_json_bool(&j, "cond8_predicts_stable", r.cond8.predicts_stable);
    cli_json_bool(&j, "cond9_predicts_stable", r.cond9.predicts_stable);
    cli_json_summary_end(&j, ctx);
  } else if (!ctx->quiet) {
    print_params(&p, &phys, physical);
    printf("main motion (4): %s (%s); roots say %s; margin max Re(lambda) = %.6e\n",
           autobal_verdict_name(r.verdict), autobal_study_pendulum_roots_criterion(&r),
           autobal_verdict_name(r.verdict_roots), r.max_real);
    printf("  %-3s %24s %24s   %24s %24s\n", "#", "root of (6): Re", "Im", "eigenvalue of (5): Re", "Im");
    for (i = 0; i < AUTOBAL_PENDULUM_ORDER; i++)
      printf("  %-3zu %24.15e %24.15e   %24.15e %24.15e\n", i, r.root_re[i], r.root_im[i], r.eig_re[i], r.eig_im[i]);
    printf("  roots vs eigenvalues: max |difference| = %.3e\n", r.mismatch);
    printf("sufficient conditions (asymptotic, for comparison only):\n");
    printf("  (7) R_m << 1 or h >> 1, stable if R_w > 1:   %s\n", cond_text(&r.cond7));
    printf("  (8) R_w >> 1, stable if h > H sqrt(R_m):     %s\n", cond_text(&r.cond8));
    printf("  (9) H >> 1 (corrected):                       %s\n", cond_text(&r.cond9));
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
  return CLI_EXIT_OK;
}

/* ---- pendulum critical ------------------------------------------------------------- */
static const char *kind_name(int kind) {
  return kind > 0 ? "stability gained" : kind < 0 ? "stability lost" : "touch (no change)";
}

/* The kinds of a set as ints (autobal_crit_kind) and names, for --json. */
static void json_kinds(cli_json *j, const char *prefix, const autobal_pendulum_crit_set *s) {
  char key[64];
  size_t i;
  snprintf(key, sizeof key, "%s_kind", prefix);
  cli_json_array(j, key);
  for (i = 0; i < s->n; i++) cli_json_int(j, NULL, s->kind[i]);
  cli_json_array_end(j);
  snprintf(key, sizeof key, "%s_kind_name", prefix);
  cli_json_array(j, key);
  for (i = 0; i < s->n; i++)
    cli_json_string(j, NULL, s->kind[i] > 0 ? "gained" : s->kind[i] < 0 ? "lost" : "touch");
  cli_json_array_end(j);
  snprintf(key, sizeof key, "%s_unresolved", prefix);
  cli_json_bool(j, key, s->unresolved);
}

/* The speed of the first touch of s (NaN if none). */
static double first_touch(const autobal_pendulum_crit_set *s) {
  size_t i;
  for (i = 0; i < s->n; i++)
    if (s->kind[i] == AUTOBAL_CRIT_TOUCH) return s->R_w[i];
  return NAN;
}

/* |formula - numerical| / numerical, NaN where either is missing */
static double rel_err(double formula, double numerical) {
  return isfinite(formula) && isfinite(numerical) ? fabs(formula - numerical) / numerical : NAN;
}

/* The stable intervals; with omega0 > 0 (physical input) also in rpm. */
static void print_intervals(const autobal_pendulum_crit_set *s, double omega0) {
  size_t i;
  printf("  stable for R_w in:");
  if (s->n_stable == 0) printf(" (none)");
  for (i = 0; i < s->n_stable; i++) {
    if (isinf(s->stable_hi[i])) printf(" (%.10g, inf)", s->stable_lo[i]);
    else printf(" (%.10g, %.10g)", s->stable_lo[i], s->stable_hi[i]);
  }
  printf("\n");
  if (omega0 > 0 && s->n_stable > 0) {
    printf("  stable speeds (rpm):");
    for (i = 0; i < s->n_stable; i++) {
      if (isinf(s->stable_hi[i])) printf(" (%.6g, inf)", cli_rpm(s->stable_lo[i] * omega0));
      else printf(" (%.6g, %.6g)", cli_rpm(s->stable_lo[i] * omega0), cli_rpm(s->stable_hi[i] * omega0));
    }
    printf("\n");
  }
}

/* ---- interruption (SIGINT, SIGTERM, SIGHUP) ------------------------------------------ */

/* The studies' progress callback: stop once a signal arrived. */
static int stop_requested(double fraction, void *user) {
  (void)fraction;
  (void)user;
  return cli_interrupted();
}

/* After a study returned AUTOBAL_ECANCELLED: exit code 6 with `what`; with -o the archive is
 * created, `write` puts the partial results in it and cli_archive_finish marks it incomplete,
 * naming the signal.  Returns the exit code. */
static int finish_interrupted(cli_ctx *ctx, const char *title, const char *what,
                              int (*write)(autobal_archive *a, const void *data), const void *data) {
  autobal_archive *a = NULL;
  int rc, st;
  if ((rc = cli_archive_open(ctx, title, &a))) return rc;
  rc = cli_fail(ctx, CLI_EXIT_INTERRUPTED, "%s: %s; %s", cli_signal_reason(), what,
                a ? "the archive keeps what was computed (status incomplete)" : "nothing written (no -o)");
  if (!a) return rc;
  st = write(a, data);
  if (st)
    fprintf(stderr, "autobal: error: writing the partial results failed: %s\n", autobal_archive_errmsg(a));
  return cli_archive_finish(ctx, a, rc);
}

typedef struct pend_partial {
  const autobal_pendulum_params *p;
  const autobal_pendulum_physical *phys;
  const void *sum;
} pend_partial;
static int write_critical(autobal_archive *a, const void *data) {
  const pend_partial *pp = (const pend_partial *)data;
  return autobal_study_pendulum_critical_write(a, pp->p, pp->phys, pp->sum);
}
static int write_map(autobal_archive *a, const void *data) {
  const pend_partial *pp = (const pend_partial *)data;
  return autobal_study_pendulum_map_write(a, pp->p, pp->phys, pp->sum);
}

int cli_cmd_pendulum_critical(cli_ctx *ctx) {
  autobal_pendulum_params p;
  autobal_pendulum_physical phys;
  autobal_study_pendulum_critical_options o = autobal_study_pendulum_critical_options_default();
  autobal_study_pendulum_critical_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  int physical = 0, rc, st = 0, have_damped;
  double rm_min, rm_max, rw_min, rw_max, k, rm1, rw_rm1;
  long n_rm, n_sweep;
  size_t i;
  /* closed forms at the given R_m */
  double rw1_13, s2, s3, l2, l3, rw1_16, u16, rw1_17, rw23_18;
  autobal_pendulum_crit_set *und = &sum.undamped, *damped = &sum.damped, *k0 = &sum.undamped_k0, *k1 = &sum.undamped_k1;

  memset(&sum, 0, sizeof sum);
  autobal_error_clear(&err);
  if ((rc = cli_read_pendulum_params(ctx, &p, &phys, &physical))) return rc;
  if ((rc = cli_get_double(ctx, "critical", "Rm_min", o.Rm_min, &rm_min, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "critical", "Rm_max", o.Rm_max, &rm_max, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "critical", "n_Rm", (long)o.n_Rm, &n_rm, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "critical", "Rw_min", o.Rw_min, &rw_min, NULL))) return rc;
  if ((rc = cli_get_double(ctx, "critical", "Rw_max", o.Rw_max, &rw_max, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "critical", "n_sweep", (long)o.n_sweep, &n_sweep, NULL))) return rc;
  if ((rc = cli_config_check_unused(ctx))) return rc;
  if (!(rm_min > 0 && rm_min < rm_max && rm_max < 0.5))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[critical]: need 0 < Rm_min < Rm_max < 0.5, got Rm_min = %g, Rm_max = %g",
                    rm_min, rm_max);
  if (n_rm < 2 || n_rm > 1000000)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[critical]: n_Rm = %ld is out of range: allowed [2, 1000000]", n_rm);
  if (!(rw_min >= 0 && rw_min < rw_max && rw_max <= 1e4))
    return cli_fail(ctx, CLI_EXIT_INPUT, "[critical]: need 0 <= Rw_min < Rw_max <= 1e4, got Rw_min = %g, Rw_max = %g",
                    rw_min, rw_max);
  if (n_sweep < 2 || n_sweep > 100000000)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[critical]: n_sweep = %ld is out of range: allowed [2, 1e8]", n_sweep);
  o.Rm_min = rm_min;
  o.Rm_max = rm_max;
  o.n_Rm = (size_t)n_rm;
  o.Rw_min = rw_min;
  o.Rw_max = rw_max;
  o.n_sweep = (size_t)n_sweep;
  o.progress = stop_requested;
  /* the computation first (autobal_study_pendulum_critical), the archive afterwards */
  st = autobal_study_pendulum_critical(&p, physical ? &phys : NULL, &o, NULL, &sum, &err);
  if (sum.damped_truncated_warning && !ctx->json) fprintf(stderr, "autobal: warning: %s\n", sum.warning_message);
  if (st == AUTOBAL_SUCCESS && (sum.undamped.unresolved || sum.undamped_k0.unresolved || sum.undamped_k1.unresolved))
    fprintf(stderr,
            "autobal: warning: two undamped critical speeds lie within one unit in the last place of W = R_w^2 "
            "(%s): an island or window narrower than a double resolves is reported as two equal values "
            "(*_unresolved in the archive and the JSON)\n",
            sum.undamped.unresolved ? "at the given k" : sum.undamped_k0.unresolved ? "at k = 0" : "at k = 1");
  if (st == AUTOBAL_ECANCELLED) {
    pend_partial pp;
    pp.p = &p, pp.phys = physical ? &phys : NULL, pp.sum = &sum;
    rc = finish_interrupted(ctx, "autobal pendulum critical", err.message, write_critical, &pp);
    goto done;
  }
  if (st) {
    rc = cli_fail(ctx, cli_exit_code(st), "%s", err.message);
    goto done;
  }
  k = sum.k;
  have_damped = sum.have_damped;
  rm1 = sum.R_m1, rw_rm1 = sum.R_w_at_R_m1;
  rw1_13 = sum.eq13_R_w1_k0, s2 = sum.eq14_R_w2_k0_small, s3 = sum.eq14_R_w3_k0_small;
  l2 = sum.eq14_R_w2_k0_large, l3 = sum.eq14_R_w3_k0_large;
  rw1_16 = sum.eq16_R_w1_k1, u16 = sum.eq16_u, rw1_17 = sum.eq17_R_w1_k1_series, rw23_18 = sum.eq18_R_w23_k1;
  (void)l2, (void)l3;
  if ((rc = cli_archive_open(ctx, "autobal pendulum critical", &a))) goto done;
  if (a) {
    st = autobal_study_pendulum_critical_write(a, &p, physical ? &phys : NULL, &sum);
    rc = cli_archive_end(ctx, &a, st, CLI_EXIT_OK);
    if (rc) goto done;
  }

  if (ctx->json) {
    cli_json j;
    cli_json_summary_begin(&j, ctx);
    cli_json_quantity(&j, "R_m", p.R_m, "1");
    cli_json_quantity(&j, "k", k, "1");
    cli_json_quantities(&j, "undamped_critical_R_w", und->R_w, und->n, "1");
    if (physical) {
      double w0 = pendulum_omega0(&phys), wc[AUTOBAL_PENDULUM_MAX_CRIT];
      for (i = 0; i < und->n && i < AUTOBAL_PENDULUM_MAX_CRIT; i++) wc[i] = und->R_w[i] * w0;
      cli_json_quantity(&j, "omega0", w0, "rad/s");
      cli_json_quantities(&j, "undamped_critical_omega", wc, i, "rad/s");
    }
    json_kinds(&j, "undamped", und);
    /* two critical speeds closer than this relative width in W = R_w^2 may be reported equal
     * (then *_unresolved = true); every island or window wider than it is reported */
    cli_json_number(&j, "undamped_resolution_W", DBL_EPSILON);
    cli_json_quantities(&j, "undamped_stable_lo", und->stable_lo, und->n_stable, "1");
    cli_json_quantities(&j, "undamped_stable_hi", und->stable_hi, und->n_stable, "1");
    if (have_damped) {
      cli_json_quantities(&j, "damped_critical_R_w", damped->R_w, damped->n, "1");
      cli_json_quantities(&j, "damped_stable_lo", damped->stable_lo, damped->n_stable, "1");
      cli_json_quantities(&j, "damped_stable_hi", damped->stable_hi, damped->n_stable, "1");
      cli_json_bool(&j, "damped_truncated", damped->truncated);
    }
    cli_json_quantities(&j, "k0_critical_R_w", k0->R_w, k0->n, "1");
    json_kinds(&j, "k0", k0);
    cli_json_quantities(&j, "k1_critical_R_w", k1->R_w, k1->n, "1");
    json_kinds(&j, "k1", k1);
    cli_json_quantity(&j, "R_m1", rm1, "1");
    cli_json_quantity(&j, "R_w_at_R_m1", rw_rm1, "1");
    {
      /* the paper's closed forms and series at R_m (null where not defined) and their relative
       * errors against the numerical critical speeds they approximate */
      int small = p.R_m < 0.05;
      double f14_2 = small ? s2 : l2, f14_3 = small ? s3 : l3;
      double n18 = p.R_m > rm1 ? first_touch(k1) : NAN;
      double f18 = p.R_m > rm1 ? rw23_18 : NAN;
      cli_json_object(&j, "closed_forms");
      cli_json_number(&j, "eq13_R_w1_k0", rw1_13);
      cli_json_string(&j, "eq14_form", small ? "R_m < 0.05" : p.R_m < 0.25 ? "0.05 <= R_m < 0.25" : "none");
      cli_json_number(&j, "eq14_R_w2_k0", f14_2);
      cli_json_number(&j, "eq14_R_w3_k0", f14_3);
      cli_json_number(&j, "eq16_R_w1_k1", rw1_16);
      cli_json_number(&j, "eq16_u", u16);
      cli_json_number(&j, "eq17_R_w1_k1", rw1_17);
      cli_json_number(&j, "eq18_R_w23_k1", f18);
      cli_json_object_end(&j);
      cli_json_object(&j, "closed_form_errors");
      cli_json_number(&j, "eq13_R_w1_k0", rel_err(rw1_13, autobal_pendulum_crit_get(k0, 0)));
      cli_json_number(&j, "eq14_R_w2_k0", rel_err(f14_2, autobal_pendulum_crit_get(k0, 1)));
      cli_json_number(&j, "eq14_R_w3_k0", rel_err(f14_3, autobal_pendulum_crit_get(k0, 2)));
      cli_json_number(&j, "eq16_R_w1_k1", rel_err(rw1_16, autobal_pendulum_crit_get(k1, 0)));
      cli_json_number(&j, "eq17_R_w1_k1", rel_err(rw1_17, autobal_pendulum_crit_get(k1, 0)));
      cli_json_number(&j, "eq18_R_w23_k1", rel_err(f18, n18));
      cli_json_object_end(&j);
    }
    cli_json_summary_end(&j, ctx);
  } else if (!ctx->quiet) {
    double w0 = physical ? pendulum_omega0(&phys) : NAN;
    print_params(&p, &phys, physical);
    printf("undamped critical speeds at R_m = %.6g, k = %.6g (exact, from the discriminant of (10)):\n", p.R_m, k);
    for (i = 0; i < und->n; i++) {
      printf("  R_w = %.12f   %s", und->R_w[i], kind_name(und->kind[i]));
      if (physical) printf("   (omega = %.6g rad/s = %.6g rpm)", und->R_w[i] * w0, cli_rpm(und->R_w[i] * w0));
      printf("\n");
    }
    print_intervals(und, w0);
    printf("k = 0 (numerical): ");
    for (i = 0; i < k0->n; i++) printf(" %.12f", k0->R_w[i]);
    printf("\n  paper: (13) R_w1 = %.12f", rw1_13);
    if (p.R_m < 0.05) printf("; (14) R_w2 ~ %.12f, R_w3 ~ %.12f", s2, s3);
    else if (p.R_m < 0.25) printf("; (14) R_w2 ~ %.12f, R_w3 ~ %.12f", l2, l3);
    printf("\nk = 1 (numerical): ");
    for (i = 0; i < k1->n; i++) printf(" %.12f%s", k1->R_w[i], k1->kind[i] == 0 ? "(touch)" : "");
    printf("\n  paper: (16) R_w1 = %.12f (u = %.10f), (17) R_w1 ~ %.12f", rw1_16, u16, rw1_17);
    if (p.R_m > rm1 && p.R_m < 0.25) printf(", (18) R_w2/3 = %.12f", rw23_18);
    printf("\nR_m^(1) = %.12f (curves (16) and (18) touch at R_w = %.12f)\n", rm1, rw_rm1);
    if (have_damped) {
      printf("damped critical speeds (H = %.6g, h = %.6g) on R_w in [%g, %g]:\n", p.H, p.h, rw_min, rw_max);
      for (i = 0; i < damped->n; i++) {
        printf("  R_w = %.12f   %s", damped->R_w[i], kind_name(damped->kind[i]));
        if (physical) printf("   (omega = %.6g rad/s = %.6g rpm)", damped->R_w[i] * w0, cli_rpm(damped->R_w[i] * w0));
        printf("\n");
      }
      print_intervals(damped, w0);
      if (damped->truncated)
        printf("  (TRUNCATED: more critical speeds than the list holds; the results cover R_w in [%g, %.12f] only)\n",
               rw_min, damped->R_w[damped->n - 1]);
    }
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
  rc = CLI_EXIT_OK;
done:
  autobal_study_pendulum_critical_summary_free(&sum);
  return rc;
}

/* ---- pendulum map and sweep: the library's studies (autobal_study_pendulum_map, _sweep) ----- */

/* " " and the unit of a physical key for the summaries ("" for the dimensionless ones) */
static const char *unit_sfx(int param) { return autobal_pendulum_param_is_physical(param) ? " " : ""; }
static const char *unit_of(int param) { return autobal_pendulum_param_unit(param); }

/* A parameter key of [map] param1/param2 or [sweep] param: its AUTOBAL_PENDULUM_PARAM_* */
static int read_param_key(cli_ctx *ctx, const char *section, const char *key, const char *def, int *param) {
  const char *name;
  int rc;
  if ((rc = cli_get_string(ctx, section, key, def, &name, NULL))) return rc;
  *param = autobal_pendulum_param_lookup(name);
  if (*param < 0)
    return cli_fail(ctx, CLI_EXIT_INPUT,
                    "[%s]: %s = '%s' is not a pendulum parameter: allowed R_w, R_m, H, h, k, psi0, H/h (dimensionless) "
                    "and, with a [pendulum] given by its physical keys, M, e, m, l, c, H1, H2, omega (in their units)",
                    section, key, name);
  return CLI_EXIT_OK;
}

/* "auto" (-1), "log" (1) or "linear" (0) */
static int read_scale(cli_ctx *ctx, const char *section, const char *key, int *lg) {
  const char *v;
  int rc;
  if ((rc = cli_get_string(ctx, section, key, "auto", &v, NULL))) return rc;
  if (!strcmp(v, "auto")) *lg = -1;
  else if (!strcmp(v, "log")) *lg = 1;
  else if (!strcmp(v, "linear")) *lg = 0;
  else return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: %s = '%s': allowed auto, log, linear", section, key, v);
  return CLI_EXIT_OK;
}

/* "exact" (0) or "paper" (1) */
static int read_convention(cli_ctx *ctx, const char *section, int *paper) {
  const char *v;
  int rc;
  if ((rc = cli_get_string(ctx, section, "convention", "exact", &v, NULL))) return rc;
  if (!strcmp(v, "exact")) *paper = 0;
  else if (!strcmp(v, "paper")) *paper = 1;
  else return cli_fail(ctx, CLI_EXIT_INPUT, "[%s]: convention = '%s': allowed exact, paper", section, v);
  return CLI_EXIT_OK;
}

/* One axis of the map: min<i>, max<i>, n<i>, log<i>; on the default axes (R_m rows, R_w columns)
 * the former keys Rm_min, Rm_max, n_Rm (Rw_min, Rw_max, n_Rw) give the range, and min<i>, max<i>,
 * n<i>, read only when given, take precedence over them. */
static int read_map_axis(cli_ctx *ctx, int which, int param, const autobal_pendulum_physical *phys, double leg_min,
                         double leg_max, long leg_n, double *mn, double *mx, size_t *n, int *lg) {
  char kmin[8], kmax[8], kn[8], klog[8];
  const char *lmin = which == 1 ? "Rm_min" : "Rw_min", *lmax = which == 1 ? "Rm_max" : "Rw_max";
  const char *ln = which == 1 ? "n_Rm" : "n_Rw";
  int legacy = param == (which == 1 ? AUTOBAL_PENDULUM_PARAM_R_M : AUTOBAL_PENDULUM_PARAM_R_W), rc, scale;
  double dlo, dhi, a, b;
  long nn;
  int pa, pb, pn;
  snprintf(kmin, sizeof kmin, "min%d", which);
  snprintf(kmax, sizeof kmax, "max%d", which);
  snprintf(kn, sizeof kn, "n%d", which);
  snprintf(klog, sizeof klog, "log%d", which);
  const char *unit = autobal_pendulum_param_unit(param); /* a physical key in its units ("3000 rpm") */
  autobal_study_pendulum_param_range_physical(param, phys, &dlo, &dhi, NULL);
  if (legacy) {
    if ((rc = cli_get_double(ctx, "map", lmin, leg_min, &dlo, NULL))) return rc;
    if ((rc = cli_get_double(ctx, "map", lmax, leg_max, &dhi, NULL))) return rc;
    if ((rc = cli_get_int(ctx, "map", ln, leg_n, &leg_n, NULL))) return rc;
  } else {
    leg_n = 200;
  }
  /* on a default axis the former keys are the recorded ones; min<i>/max<i>/n<i> are read only
   * when given (so that an edited Rm_min in an archive's effective configuration counts) */
  a = dlo, b = dhi, nn = leg_n, pa = pb = pn = 0;
  if ((!legacy || cli_config_has_key(ctx->cfg, "map", kmin)) &&
      (rc = cli_get_quantity(ctx, "map", kmin, unit, dlo, &a, &pa)))
    return rc;
  if ((!legacy || cli_config_has_key(ctx->cfg, "map", kmax)) &&
      (rc = cli_get_quantity(ctx, "map", kmax, unit, dhi, &b, &pb)))
    return rc;
  if ((!legacy || cli_config_has_key(ctx->cfg, "map", kn)) && (rc = cli_get_int(ctx, "map", kn, leg_n, &nn, &pn)))
    return rc;
  if ((rc = read_scale(ctx, "map", klog, &scale))) return rc;
  if (nn < 1 || nn > 100000)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[map]: %s = %ld is out of range: allowed [1, 100000]", pn ? kn : ln, nn);
  *mn = a, *mx = b, *n = (size_t)nn, *lg = scale;
  return CLI_EXIT_OK;
}

int cli_cmd_pendulum_map(cli_ctx *ctx) {
  autobal_pendulum_params p;
  autobal_pendulum_physical phys;
  autobal_study_pendulum_map_options o = autobal_study_pendulum_map_options_default();
  autobal_study_pendulum_map_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  int physical = 0, rc, st, every = 0, want_max = 0, k_given = 0, p1, p2, paper = 0;
  long n_k, threads;
  size_t n;
  const char *n1s, *n2s;

  memset(&sum, 0, sizeof sum);
  autobal_error_clear(&err);
  if ((rc = cli_read_pendulum_params(ctx, &p, &phys, &physical))) return rc;
  if ((rc = read_param_key(ctx, "map", "param1", "R_m", &p1))) return rc;
  if ((rc = read_param_key(ctx, "map", "param2", "R_w", &p2))) return rc;
  if ((rc = read_map_axis(ctx, 1, p1, physical ? &phys : NULL, o.Rm_min, o.Rm_max, (long)o.n_Rm, &o.min1, &o.max1,
                          &o.n1, &o.log1)))
    return rc;
  if ((rc = read_map_axis(ctx, 2, p2, physical ? &phys : NULL, o.Rw_min, o.Rw_max, (long)o.n_Rw, &o.min2, &o.max2,
                          &o.n2, &o.log2)))
    return rc;
  if ((rc = cli_get_bool(ctx, "map", "every_unbalance", o.every_unbalance, &every, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "map", "n_k", (long)o.n_k, &n_k, &k_given))) return rc;
  if ((rc = cli_get_bool(ctx, "map", "max_real", o.max_real, &want_max, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "map", "threads", o.threads, &threads, NULL))) return rc;
  if ((rc = read_convention(ctx, "map", &paper))) return rc;
  if ((rc = cli_config_check_unused(ctx))) return rc;
  if (p1 == p2)
    return cli_fail(ctx, CLI_EXIT_INPUT, "[map]: param1 and param2 are both '%s': give two different parameters",
                    autobal_pendulum_param_name(p1));
  if (n_k < 2 || n_k > 100000) return cli_fail(ctx, CLI_EXIT_INPUT, "[map]: n_k = %ld is out of range: allowed [2, 100000]", n_k);
  if (threads < 0 || threads > 1024) return cli_fail(ctx, CLI_EXIT_INPUT, "[map]: threads = %ld is out of range: allowed [0, 1024]", threads);
  if (k_given && !every) return cli_fail(ctx, CLI_EXIT_INPUT, "[map]: n_k is used only with every_unbalance = true");
  o.param1 = p1, o.param2 = p2;
  if (p1 == AUTOBAL_PENDULUM_PARAM_R_M) o.Rm_min = o.min1, o.Rm_max = o.max1, o.n_Rm = o.n1;
  if (p2 == AUTOBAL_PENDULUM_PARAM_R_W) o.Rw_min = o.min2, o.Rw_max = o.max2, o.n_Rw = o.n2;
  o.every_unbalance = every;
  o.n_k = (size_t)n_k;
  o.max_real = want_max;
  o.threads = (int)threads;
  o.paper_convention = paper;
  n = o.n1 * o.n2;
  o.progress = stop_requested;
  /* the map first, the archive afterwards: a failed computation leaves no file */
  st = autobal_study_pendulum_map(&p, physical ? &phys : NULL, &o, NULL, &sum, &err);
  if (st == AUTOBAL_ECANCELLED) {
    pend_partial pp;
    pp.p = &p, pp.phys = physical ? &phys : NULL, pp.sum = &sum;
    rc = finish_interrupted(ctx, every ? "autobal pendulum map (every unbalance)" : "autobal pendulum map", err.message,
                            write_map, &pp);
    goto done;
  }
  if (st) {
    rc = cli_fail(ctx, cli_exit_code(st), st == AUTOBAL_EINVAL ? "[map]: %s" : "%s", err.message);
    goto done;
  }
  if ((rc = cli_archive_open(ctx, every ? "autobal pendulum map (every unbalance)" : "autobal pendulum map", &a)))
    goto done;
  if (a) {
    st = autobal_study_pendulum_map_write(a, &p, physical ? &phys : NULL, &sum);
    rc = cli_archive_end(ctx, &a, st, CLI_EXIT_OK);
    if (rc) goto done;
  }
  n1s = autobal_pendulum_param_name(p1), n2s = autobal_pendulum_param_name(p2);
  if (ctx->json) {
    cli_json j;
    cli_json_summary_begin(&j, ctx);
    cli_json_bool(&j, "every_unbalance", every);
    cli_json_string(&j, "axis1", n1s);
    cli_json_string(&j, "axis2", n2s);
    cli_json_string(&j, "axis1_scale", sum.log1 ? "log" : "linear");
    cli_json_string(&j, "axis2_scale", sum.log2 ? "log" : "linear");
    cli_json_string(&j, "convention", paper ? "paper" : "exact");
    cli_json_int(&j, "n1", (long)sum.n_Rm);
    cli_json_int(&j, "n2", (long)sum.n_Rw);
    if (p1 == AUTOBAL_PENDULUM_PARAM_R_M && p2 == AUTOBAL_PENDULUM_PARAM_R_W) {
      cli_json_int(&j, "n_Rm", (long)sum.n_Rm);
      cli_json_int(&j, "n_Rw", (long)sum.n_Rw);
    }
    cli_json_int(&j, "n_stable", (long)sum.n_stable);
    cli_json_quantity(&j, "stable_fraction", (double)sum.n_stable / (double)n, "1");
    if (sum.undamped) cli_json_string(&j, "note", autobal_study_pendulum_undamped_note());
    cli_json_summary_end(&j, ctx);
  } else if (!ctx->quiet) {
    print_params(&p, &phys, physical);
    printf("map %zu x %zu over %s in [%g, %g]%s%s%s, %s in [%g, %g]%s%s%s, %s\n", sum.n_Rm, sum.n_Rw, n1s,
           sum.R_m[0], sum.R_m[sum.n_Rm - 1], unit_sfx(p1), autobal_pendulum_param_is_physical(p1) ? unit_of(p1) : "",
           sum.log1 ? " (log)" : "", n2s, sum.R_w[0], sum.R_w[sum.n_Rw - 1], unit_sfx(p2),
           autobal_pendulum_param_is_physical(p2) ? unit_of(p2) : "", sum.log2 ? " (log)" : "",
           every ? "stable for every k in the set" : "one k");
    if (autobal_pendulum_param_is_physical(p1) || autobal_pendulum_param_is_physical(p2))
      printf("physical axis: at each point the physical set with the key changed is converted by (2)-(3)\n");
    if (p1 == AUTOBAL_PENDULUM_PARAM_H_RATIO || p2 == AUTOBAL_PENDULUM_PARAM_H_RATIO)
      printf("axis H/h: %s\n", (p1 == AUTOBAL_PENDULUM_PARAM_H || p2 == AUTOBAL_PENDULUM_PARAM_H)
                                   ? "h = H / (H/h), H from its axis"
                                   : (p1 == AUTOBAL_PENDULUM_PARAM_HP || p2 == AUTOBAL_PENDULUM_PARAM_HP)
                                         ? "H = (H/h) h, h from its axis"
                                         : (autobal_pendulum_param_is_physical(p1) ||
                                            autobal_pendulum_param_is_physical(p2))
                                               ? "H = (H/h) h, h of each point's physical set"
                                               : "H = (H/h) h, h held at pendulum.h");
    printf("stable points: %zu of %zu (%.1f%%)\n", sum.n_stable, n, 100.0 * (double)sum.n_stable / (double)n);
    if (sum.undamped) printf("note (undamped%s): %s\n", paper ? ", paper's convention" : "", autobal_study_pendulum_undamped_note());
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
  rc = CLI_EXIT_OK;
done:
  autobal_study_pendulum_map_summary_free(&sum);
  return rc;
}

static int write_sweep(autobal_archive *a, const void *data) {
  const pend_partial *pp = (const pend_partial *)data;
  return autobal_study_pendulum_sweep_write(a, pp->p, pp->phys, pp->sum);
}

int cli_cmd_pendulum_sweep(cli_ctx *ctx) {
  autobal_pendulum_params p;
  autobal_pendulum_physical phys;
  autobal_study_pendulum_sweep_options o = autobal_study_pendulum_sweep_options_default();
  autobal_study_pendulum_sweep_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  int physical = 0, rc, st, every = 0, k_given = 0, param, paper = 0, lg = -1;
  long n, n_k;
  double dlo, dhi, mn, mx, xtol;
  size_t i;
  const char *name;

  memset(&sum, 0, sizeof sum);
  autobal_error_clear(&err);
  if ((rc = cli_read_pendulum_params(ctx, &p, &phys, &physical))) return rc;
  if ((rc = read_param_key(ctx, "sweep", "param", "R_w", &param))) return rc;
  autobal_study_pendulum_param_range_physical(param, physical ? &phys : NULL, &dlo, &dhi, NULL);
  /* a physical key in its units ("3000 rpm"); the others plain numbers (psi0 in rad or deg) */
  if ((rc = cli_get_quantity(ctx, "sweep", "min", autobal_pendulum_param_unit(param), dlo, &mn, NULL))) return rc;
  if ((rc = cli_get_quantity(ctx, "sweep", "max", autobal_pendulum_param_unit(param), dhi, &mx, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "sweep", "n", (long)o.n, &n, NULL))) return rc;
  if ((rc = read_scale(ctx, "sweep", "log", &lg))) return rc;
  if ((rc = cli_get_bool(ctx, "sweep", "every_unbalance", o.every_unbalance, &every, NULL))) return rc;
  if ((rc = cli_get_int(ctx, "sweep", "n_k", (long)o.n_k, &n_k, &k_given))) return rc;
  if ((rc = cli_get_double(ctx, "sweep", "xtol_rel", o.xtol_rel, &xtol, NULL))) return rc;
  if ((rc = read_convention(ctx, "sweep", &paper))) return rc;
  if ((rc = cli_config_check_unused(ctx))) return rc;
  if (n < 2 || n > 10000000) return cli_fail(ctx, CLI_EXIT_INPUT, "[sweep]: n = %ld is out of range: allowed [2, 1e7]", n);
  if (n_k < 2 || n_k > 100000) return cli_fail(ctx, CLI_EXIT_INPUT, "[sweep]: n_k = %ld is out of range: allowed [2, 100000]", n_k);
  if (k_given && !every) return cli_fail(ctx, CLI_EXIT_INPUT, "[sweep]: n_k is used only with every_unbalance = true");
  o.param = param, o.min = mn, o.max = mx, o.n = (size_t)n, o.log_scale = lg, o.every_unbalance = every;
  o.n_k = (size_t)n_k, o.xtol_rel = xtol, o.paper_convention = paper;
  o.progress = stop_requested;
  st = autobal_study_pendulum_sweep(&p, physical ? &phys : NULL, &o, NULL, &sum, &err);
  if (st == AUTOBAL_ECANCELLED) {
    pend_partial pp;
    pp.p = &p, pp.phys = physical ? &phys : NULL, pp.sum = &sum;
    rc = finish_interrupted(ctx, "autobal pendulum sweep", err.message, write_sweep, &pp);
    goto done;
  }
  if (st) {
    rc = cli_fail(ctx, cli_exit_code(st), st == AUTOBAL_EINVAL ? "[sweep]: %s" : "%s", err.message);
    goto done;
  }
  if ((rc = cli_archive_open(ctx, "autobal pendulum sweep", &a))) goto done;
  if (a) {
    st = autobal_study_pendulum_sweep_write(a, &p, physical ? &phys : NULL, &sum);
    rc = cli_archive_end(ctx, &a, st, CLI_EXIT_OK);
    if (rc) goto done;
  }
  name = autobal_pendulum_param_name(param);
  if (ctx->json) {
    cli_json j;
    const char *unit = autobal_pendulum_param_unit(param);
    cli_json_summary_begin(&j, ctx);
    cli_json_string(&j, "param", name);
    cli_json_string(&j, "scale", sum.log_scale ? "log" : "linear");
    cli_json_string(&j, "convention", paper ? "paper" : "exact");
    cli_json_bool(&j, "every_unbalance", every);
    cli_json_int(&j, "n", (long)sum.n);
    cli_json_int(&j, "n_stable", (long)sum.n_stable);
    cli_json_quantity(&j, "stable_fraction", (double)sum.n_stable / (double)sum.n, "1");
    cli_json_quantities(&j, "critical", sum.crit, sum.n_crit, unit);
    cli_json_array(&j, "critical_below");
    for (i = 0; i < sum.n_crit; i++) cli_json_int(&j, NULL, sum.crit_below[i]);
    cli_json_array_end(&j);
    cli_json_array(&j, "critical_above");
    for (i = 0; i < sum.n_crit; i++) cli_json_int(&j, NULL, sum.crit_above[i]);
    cli_json_array_end(&j);
    cli_json_bool(&j, "critical_truncated", sum.crit_truncated);
    if (sum.undamped) cli_json_string(&j, "note", autobal_study_pendulum_undamped_note());
    cli_json_summary_end(&j, ctx);
  } else if (!ctx->quiet) {
    print_params(&p, &phys, physical);
    int phk = autobal_pendulum_param_is_physical(param);
    printf("sweep of %s over [%g, %g]%s%s%s, %zu points, %s: stable at %zu (%.1f%%)\n", name, sum.min, sum.max,
           unit_sfx(param), phk ? unit_of(param) : "", sum.log_scale ? " (log)" : "", sum.n,
           every ? "stable for every k in the set" : "one k", sum.n_stable, 100.0 * (double)sum.n_stable / (double)sum.n);
    if (phk) printf("physical key: at each point the physical set with %s changed is converted by (2)-(3)\n", name);
    if (param == AUTOBAL_PENDULUM_PARAM_H_RATIO) printf("axis H/h: H = (H/h) h, h held at pendulum.h\n");
    printf("critical values of %s (verdict changes, bisection to %g relative):\n", name, xtol);
    if (sum.n_crit == 0) printf("  (none on the grid)\n");
    for (i = 0; i < sum.n_crit; i++) {
      printf("  %s = %.12g%s%s", name, sum.crit[i], unit_sfx(param), phk ? unit_of(param) : "");
      if (param == AUTOBAL_PENDULUM_PARAM_OMEGA) printf(" (%.9g rpm)", cli_rpm(sum.crit[i]));
      printf("   %s -> %s\n", autobal_verdict_name(sum.crit_below[i]), autobal_verdict_name(sum.crit_above[i]));
    }
    if (sum.crit_truncated) printf("  (TRUNCATED: more changes than the list holds)\n");
    if (sum.undamped) printf("note (undamped%s): %s\n", paper ? ", paper's convention" : "", autobal_study_pendulum_undamped_note());
    if (ctx->output) printf("archive: %s\n", ctx->output);
  }
  rc = CLI_EXIT_OK;
done:
  autobal_study_pendulum_sweep_summary_free(&sum);
  return rc;
}
