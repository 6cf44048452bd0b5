/* rotor_stability.c: the rotor stability study (`autobal rotor stability`): the balanced motion
 * (3.14) analysed by every applicable method at the rotor's speed, the critical speeds in a
 * range, and their archive layout (include/autobal/study.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "autobal/study.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- cancellation and partial results (shared by the studies of this file) ---------------- */

/* The handle's cancel hook (autobal_rotor_stab_set_cancel) calling a study's progress callback
 * with a fixed fraction. */
typedef struct progress_hook {
  autobal_study_progress_fn fn;
  void *user;
  double fraction;
} progress_hook;

static int progress_cancel(void *user) {
  progress_hook *h = (progress_hook *)user;
  return h->fn && h->fn(h->fraction, h->user) != 0;
}

static double now_seconds(void) {
  struct timespec ts;
  if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) return 0.0;
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The next block of rows: twice as many after a block shorter than 0.25 s, half as many after
 * one longer than 1 s (at least 1), so that a cancellation is noticed within about a second and
 * the blocks' ends (the threads wait for the slowest) cost little. */
static size_t next_block(size_t rows, double seconds) {
  if (seconds < 0.25 && rows < ((size_t)1 << 20)) return 2 * rows;
  if (seconds > 1.0 && rows > 1) return rows / 2;
  return rows;
}

/* The attributes of a group holding partial results: partial = 1, done and requested (counts
 * of the unit named in `what`; not written for requested = 0), partial_what (a sentence). */
static int write_partial(autobal_archive *a, const char *g, size_t done, size_t requested, const char *what) {
  int st = autobal_archive_attr_int(a, g, "partial", 1);
  if (requested == 0) return st ? st : autobal_archive_attr_string(a, g, "partial_what", what);
  if (!st) st = autobal_archive_attr_int(a, g, "done", (long)done);
  if (!st) st = autobal_archive_attr_int(a, g, "requested", (long)requested);
  if (!st) st = autobal_archive_attr_string(a, g, "partial_what", what);
  return st;
}

autobal_study_rotor_stability_options autobal_study_rotor_stability_options_default(void) {
  autobal_study_rotor_stability_options o;
  memset(&o, 0, sizeof o);
  o.stab = autobal_rotor_stab_options_default();
  o.critical_speeds = 1;
  o.omega_min = NAN;
  o.omega_max = NAN;
  o.n_omega = 400;
  o.xtol_rel = 1e-8;
  o.every_unbalance = 0;
  o.unbalance_min = NAN;
  o.unbalance_max = NAN;
  o.unbalance2_min = NAN;
  o.unbalance2_max = NAN;
  o.n_unbalance = 9;
  return o;
}

void autobal_study_rotor_speed_range(const autobal_rotor_params *p, double *lo, double *hi) {
  double f[4] = {100, 100, 100, 100};
  (void)autobal_rotor_modes(p, 0.0, 1, f, NULL, NULL, NULL, NULL);
  *lo = 0.05 * (f[0] > 0 ? f[0] : 1.0);
  *hi = 4.0 * fmax(f[3], fabs(p->omega));
  if (!(*hi > *lo)) *hi = *lo + 1.0;
}

void autobal_study_rotor_stability_summary_free(autobal_study_rotor_stability_summary *s) {
  if (!s) return;
  free(s->storage_);
  s->storage_ = NULL;
  free(s->every_speeds2_storage_);
  s->every_speeds2_storage_ = NULL;
  s->every_speeds2.grid_omega = NULL;
  s->every_speeds2.grid_stable = s->every_speeds2.grid_exact = NULL;
  s->every_speeds2.grid_boxes = NULL;
  s->result.psi = s->result.full_re = s->result.full_im = s->result.mu_re = s->result.mu_im = NULL;
}

/* Copy the arrays the result points to (into the handle) into the summary's own storage. */
static int keep_arrays(autobal_study_rotor_stability_summary *s) {
  autobal_rotor_stab_result *r = &s->result;
  size_t n = r->n_balls + 2 * r->n_full + 2 * r->n_floquet, k = 0;
  double *m = malloc((n ? n : 1) * sizeof *m);
  if (!m) return AUTOBAL_ENOMEM;
#define KEEP(ptr, len)                                        \
  do {                                                        \
    if ((len) > 0 && (ptr)) memcpy(m + k, (ptr), (len) * sizeof *m); \
    (ptr) = (len) > 0 ? m + k : NULL;                         \
    k += (len);                                               \
  } while (0)
  KEEP(r->psi, r->n_balls);
  KEEP(r->full_re, r->n_full);
  KEEP(r->full_im, r->n_full);
  KEEP(r->mu_re, r->n_floquet);
  KEEP(r->mu_im, r->n_floquet);
#undef KEEP
  s->storage_ = m;
  return AUTOBAL_SUCCESS;
}

/* A speed search of the stability study: its range on the side of omega's sign into *lo, *hi, and the
 * progress hook ph (reporting `fraction`) installed on the handle when the options have one. */
static void search_setup(const autobal_rotor_params *p, const autobal_study_rotor_stability_options *o,
                         const autobal_study_rotor_stability_summary *s, autobal_rotor_stab *h, double fraction,
                         progress_hook *ph, double *lo, double *hi) {
  *lo = p->omega > 0 ? s->omega_min : -s->omega_max;
  *hi = p->omega > 0 ? s->omega_max : -s->omega_min;
  ph->fn = o->progress;
  ph->user = o->progress_user;
  ph->fraction = fraction;
  if (o->progress) autobal_rotor_stab_set_cancel(h, progress_cancel, ph);
}

/* The asymptotic conditions (autobal/rotor_asymptotic.h) beside the exact verdict: one plane with
 * the closure (Delta exists), kappa >= 0 (kappa = 0: the undamped entry); otherwise none (have_asymptotic = 0). */
static int asymptotic_conditions(autobal_rotor_stab *h, autobal_study_rotor_stability_summary *s,
                                 autobal_error *err) {
  autobal_rotor_closed c;
  autobal_error e;
  int st;
  if (autobal_rotor_stab_closed(h, &c) != AUTOBAL_SUCCESS) return AUTOBAL_SUCCESS;
  if (c.n_planes == 2) { /* two planes: the light-ball condition (autobal_rotor_asymptotic2_conditions) */
    if (!c.isotropic || !c.closure_ok || !(c.plane[0].kappa > 0.0) || !(c.plane[1].kappa > 0.0))
      return AUTOBAL_SUCCESS;
    autobal_error_clear(&e);
    st = autobal_rotor_asymptotic2_conditions(&c, &s->asymptotic2, &e);
    if (st == AUTOBAL_EINVAL) return AUTOBAL_SUCCESS;
    if (st) return autobal_error_set(err, st, "asymptotic conditions (two planes): %s", e.message);
    s->have_asymptotic2 = 1;
    return AUTOBAL_SUCCESS;
  }
  if (s->result.n_poly == 0 && c.isotropic) return AUTOBAL_SUCCESS;
  if (!(c.plane[0].kappa >= 0.0)) return AUTOBAL_SUCCESS; /* kappa = 0: the undamped entry */
  /* anisotropic supports: the light-ball condition with G+ (kappa > 0, paper inertia; else EINVAL: none) */
  autobal_error_clear(&e);
  st = autobal_rotor_asymptotic_conditions(&c, &s->asymptotic, &e);
  if (st == AUTOBAL_EINVAL) return AUTOBAL_SUCCESS; /* not applicable here (e.g. an undamped resonance) */
  if (st) return autobal_error_set(err, st, "asymptotic conditions: %s", e.message);
  s->have_asymptotic = 1;
  return AUTOBAL_SUCCESS;
}

int autobal_study_rotor_stability(const autobal_rotor_params *p, const autobal_study_rotor_stability_options *opt,
                                  autobal_archive *a, autobal_study_rotor_stability_summary *summary,
                                  autobal_error *err) {
  autobal_study_rotor_stability_options def = autobal_study_rotor_stability_options_default();
  const autobal_study_rotor_stability_options *o = opt ? opt : &def;
  autobal_study_rotor_stability_summary *s = summary;
  autobal_rotor_stab *h = NULL;
  autobal_error e;
  int st;
  autobal_error_clear(err);
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(s, 0, sizeof *s);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  if (!(p->omega != 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter omega = 0: the balanced motion of a rotor at rest has no stability to analyse");
  s->omega_min = o->omega_min;
  s->omega_max = o->omega_max;
  s->n_omega = o->n_omega;
  if (o->critical_speeds) {
    double lo, hi;
    if (isnan(s->omega_min) || isnan(s->omega_max)) {
      autobal_study_rotor_speed_range(p, &lo, &hi);
      if (isnan(s->omega_min)) s->omega_min = lo;
      if (isnan(s->omega_max)) s->omega_max = hi;
    }
    if (!(s->omega_min > 0 && s->omega_min < s->omega_max && isfinite(s->omega_max)) || o->n_omega < 2 ||
        o->n_omega > 10000000 || !(o->xtol_rel > 0 && o->xtol_rel < 0.1))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "options: need 0 < omega_min < omega_max (rad/s), n_omega in [2, 1e7], xtol_rel in "
                               "(0, 0.1); got %g, %g, %zu, %g",
                               s->omega_min, s->omega_max, o->n_omega, o->xtol_rel);
  }
  autobal_error_clear(&e);
  h = autobal_rotor_stab_alloc(p, &o->stab, &e);
  if (!h) return autobal_error_set(err, e.status ? e.status : AUTOBAL_EINVAL, "%s", e.message);
  if (e.status == AUTOBAL_WARNING) {
    s->warning = 1;
    snprintf(s->warning_message, sizeof s->warning_message, "%s", e.message);
  }
  st = autobal_rotor_stab_analyze(h, &s->result);
  if (st) {
    autobal_error_set(err, st, "%s", autobal_rotor_stab_errmsg(h));
    goto fail;
  }
  if ((st = asymptotic_conditions(h, s, err)) != 0) goto fail;
  if (o->critical_speeds) {
    double lo, hi;
    progress_hook ph;
    search_setup(p, o, s, h, 0.5, &ph, &lo, &hi);
    st = autobal_rotor_stab_critical(h, AUTOBAL_ROTOR_PARAM_OMEGA, lo, hi, o->n_omega, o->xtol_rel, &s->critical);
    autobal_rotor_stab_set_cancel(h, NULL, NULL);
    if (st == AUTOBAL_ECANCELLED) {
      /* the analysis at omega stays; the search is dropped (it covered an unknown part of the range) */
      s->critical_cancelled = 1;
      memset(&s->critical, 0, sizeof s->critical);
      st = autobal_rotor_stab_analyze(h, &s->result);
      if (!st && !(st = keep_arrays(s))) {
        autobal_rotor_stab_free(h);
        if (a && (st = autobal_study_rotor_stability_write(a, p, o, s)))
          return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
        return autobal_error_set(err, AUTOBAL_ECANCELLED, "critical speeds: cancelled by the caller");
      }
      if (st == AUTOBAL_ENOMEM) autobal_error_set(err, st, "out of memory");
      else autobal_error_set(err, st, "%s", autobal_rotor_stab_errmsg(h));
      goto fail;
    }
    if (st == AUTOBAL_WARNING) { /* truncated list: the data are valid, the flag is recorded */
      s->critical_truncated = 1;
      snprintf(s->critical_message, sizeof s->critical_message, "%s", autobal_rotor_stab_errmsg(h));
      st = AUTOBAL_SUCCESS;
    }
    if (st) {
      autobal_error_set(err, st, "critical speeds: %s", autobal_rotor_stab_errmsg(h));
      goto fail;
    }
    s->have_critical = 1;
    /* the analysis above stays valid: critical() restores omega but overwrites the workspace */
    st = autobal_rotor_stab_analyze(h, &s->result);
    if (st) {
      autobal_error_set(err, st, "%s", autobal_rotor_stab_errmsg(h));
      goto fail;
    }
  }
  if (o->every_unbalance) {
    /* every unbalance in [unbalance_min, unbalance_max]: at omega, then the speeds */
    const int two = p->n_planes == 2;
    const double lo2[2] = {o->unbalance_min, isnan(o->unbalance2_min) ? o->unbalance_min : o->unbalance2_min},
                 hi2[2] = {o->unbalance_max, isnan(o->unbalance2_max) ? o->unbalance_max : o->unbalance2_max};
    if (two) {
      /* two planes: the grid of magnitudes with every phase, and the phases at the configuration's */
      st = autobal_rotor_stab_every_unbalance2(h, lo2, hi2, o->n_unbalance, &s->every2);
      if (st) {
        autobal_error_set(err, st, "%s", autobal_rotor_stab_errmsg(h));
        goto fail;
      }
      s->have_every2 = 1;
      memset(&s->every, 0, sizeof s->every);
      s->every.omega = s->every2.omega;
      s->every.s_lo = lo2[0];
      s->every.s_hi = hi2[0];
      s->every.all_stable = s->every2.all_stable;
      s->every.margin_worst = s->every2.margin_worst;
      s->every.n_missed = s->every2.n_missed;
      s->every.evaluations = s->every2.evaluations;
      s->every.n_sub = 1;
      s->every.sub_lo[0] = lo2[0];
      s->every.sub_hi[0] = hi2[0];
      s->every.sub_verdict[0] = s->every2.all_stable ? AUTOBAL_VERDICT_STABLE : AUTOBAL_VERDICT_UNSTABLE;
      s->every.sub_margin[0] = s->every2.margin_worst;
      st = autobal_rotor_stab_every_phase(h, p->plane[0].m0 * p->plane[0].r0, p->plane[1].m0 * p->plane[1].r0,
                                          &s->every_phase);
      if (st == AUTOBAL_SUCCESS) s->have_every_phase = 1;
      else if (st != AUTOBAL_EINVAL) {
        autobal_error_set(err, st, "%s", autobal_rotor_stab_errmsg(h));
        goto fail;
      }
      st = AUTOBAL_SUCCESS;
    } else
      st = autobal_rotor_stab_every_unbalance(h, o->unbalance_min, o->unbalance_max, &s->every);
    if (st) {
      autobal_error_set(err, st, "%s", autobal_rotor_stab_errmsg(h));
      goto fail;
    }
    s->have_every = 1;
    if (o->critical_speeds) {
      double lo, hi;
      progress_hook ph;
      search_setup(p, o, s, h, 0.75, &ph, &lo, &hi);
      if (two) {
        /* per speed whether plane 2 was decided exactly: the grid arrays in one block */
        const size_t n = o->n_omega;
        char *m = n >= 2 ? malloc(n * (sizeof(double) + 2 * sizeof(int) + sizeof(size_t))) : NULL;
        autobal_rotor_speeds2_detail *d = &s->every_speeds2;
        if (n >= 2 && m == NULL) {
          st = autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
          goto fail;
        }
        free(s->every_speeds2_storage_);
        s->every_speeds2_storage_ = m;
        memset(d, 0, sizeof *d);
        if (m) {
          d->grid_omega = (double *)(void *)m;
          d->grid_boxes = (size_t *)(void *)(m + n * sizeof(double));
          d->grid_stable = (int *)(void *)(m + n * (sizeof(double) + sizeof(size_t)));
          d->grid_exact = d->grid_stable + n;
          s->every_speeds2_n = n;
        }
        st = autobal_rotor_stab_every_unbalance2_speeds_detail(h, lo2, hi2, o->n_unbalance, lo, hi, o->n_omega,
                                                               o->xtol_rel, &s->every_speeds, m ? d : NULL);
        if ((st == AUTOBAL_SUCCESS || st == AUTOBAL_WARNING) && m) s->have_every_speeds2 = 1;
      } else
        st = autobal_rotor_stab_every_unbalance_speeds(h, o->unbalance_min, o->unbalance_max, lo, hi, o->n_omega,
                                                       o->xtol_rel, &s->every_speeds);
      autobal_rotor_stab_set_cancel(h, NULL, NULL);
      if (st == AUTOBAL_WARNING) st = AUTOBAL_SUCCESS; /* truncated: recorded in every_speeds.truncated */
      if (st) {
        autobal_error_set(err, st, "every unbalance, speeds: %s", autobal_rotor_stab_errmsg(h));
        goto fail;
      }
      s->have_every_speeds = 1;
    }
    st = autobal_rotor_stab_analyze(h, &s->result); /* the analysis at omega, as above */
    if (st) {
      autobal_error_set(err, st, "%s", autobal_rotor_stab_errmsg(h));
      goto fail;
    }
  }
  if ((st = keep_arrays(s))) {
    autobal_error_set(err, st, "out of memory");
    goto fail;
  }
  autobal_rotor_stab_free(h);
  if (a && (st = autobal_study_rotor_stability_write(a, p, o, s)))
    return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
  return AUTOBAL_SUCCESS;
fail:
  autobal_rotor_stab_free(h);
  memset(&s->result, 0, sizeof s->result);
  return st;
}

static const char *verdict_text(int v) {
  return v == AUTOBAL_ROTOR_VERDICT_NONE ? "none (no balanced configuration)" : autobal_verdict_name(v);
}

static int write_crit(autobal_archive *a, const char *g, const autobal_rotor_crit *cr, const char *unit) {
  int st = autobal_archive_attr_int(a, g, "n_critical", (long)cr->n);
  int kinds[AUTOBAL_ROTOR_MAX_CRIT];
  size_t i;
  static const char *const dc[] = {"critical"}, *const di[] = {"interval"};
  if (!st) st = autobal_archive_attr_int(a, g, "n_stable_intervals", (long)cr->n_stable);
  if (!st) st = autobal_archive_attr_int(a, g, "truncated", cr->truncated);
  if (!st && cr->n > 0) {
    for (i = 0; i < cr->n; i++) kinds[i] = cr->kind[i];
    st = autobal_archive_dim(a, g, "critical", cr->n, "index of a critical value (verdict change)");
    if (!st) st = autobal_archive_var(a, g, "critical_value", 1, dc, cr->value, unit, "critical value: the margin crosses 0 here (refined)");
    if (!st) st = autobal_archive_var_int(a, g, "critical_kind", 1, dc, kinds, "1", "1: stable above, -1: unstable above, 0: a balanced configuration exists on one side only");
  }
  if (!st && cr->n_stable > 0) {
    st = autobal_archive_dim(a, g, "interval", cr->n_stable, "index of a stable interval");
    if (!st) st = autobal_archive_var(a, g, "stable_lo", 1, di, cr->stable_lo, unit, "lower end of a stable interval (the sweep's start when stable there)");
    if (!st) st = autobal_archive_var(a, g, "stable_hi", 1, di, cr->stable_hi, unit, "upper end of a stable interval (the sweep's end when stable there)");
  }
  return st;
}

/* Two planes: per speed whether plane 2's range was decided exactly (beside write_crit's datasets,
 * on its dimensions "critical" and "interval", and the grid's own "speed_grid"). */
static int write_speeds2(autobal_archive *a, const char *g, const autobal_rotor_crit *cr,
                         const autobal_rotor_speeds2_detail *d, size_t n) {
  static const char *const dc[] = {"critical"}, *const di[] = {"interval"}, *const dg[] = {"speed_grid"};
  int v[AUTOBAL_ROTOR_MAX_CRIT], *gb = NULL, st;
  size_t i;
  st = autobal_archive_attr_int(a, g, "n_speeds_evaluated", (long)d->n_evaluated);
  if (!st) st = autobal_archive_attr_int(a, g, "n_speeds_undecided_in_unbalance2", (long)d->n_undecided);
  if (!st && cr->n > 0) {
    for (i = 0; i < cr->n; i++) v[i] = d->critical_exact[i];
    st = autobal_archive_var_int(a, g, "critical_exact_in_unbalance2", 1, dc, v, "1", "1: plane 2's range was decided exactly (box search) at both speeds of the final bracket of this critical speed; 0: at one of them the plane-2 grid verdict (sampled)");
  }
  if (!st && cr->n_stable > 0) {
    for (i = 0; i < cr->n_stable; i++) v[i] = d->interval_exact[i];
    st = autobal_archive_var_int(a, g, "interval_exact_in_unbalance2", 1, di, v, "1", "1: at every speed evaluated in this stable interval (grid and bisection) plane 2's range was decided exactly (box search); 0: at some the plane-2 grid verdict (sampled)");
  }
  if (!st && n > 0) {
    gb = malloc(n * sizeof *gb);
    if (gb == NULL) return AUTOBAL_ENOMEM;
    for (i = 0; i < n; i++) gb[i] = d->grid_boxes[i] > (size_t)0x7fffffff ? 0x7fffffff : (int)d->grid_boxes[i];
    st = autobal_archive_dim(a, g, "speed_grid", n, "index of a speed of the scan's grid");
    if (!st) st = autobal_archive_var(a, g, "grid_omega", 1, dg, d->grid_omega, "rad/s", "speed of the grid");
    if (!st) st = autobal_archive_var_int(a, g, "grid_stable", 1, dg, d->grid_stable, "1", "1: stable for every unbalance of both ranges and every phase there; 0: not; -1: not evaluated (a truncated scan)");
    if (!st) st = autobal_archive_var_int(a, g, "grid_exact_in_unbalance2", 1, dg, d->grid_exact, "1", "1: the verdict there holds over plane 2's whole range (box search, or a point not stable); 0: plane 2 sampled at its grid values");
    if (!st) st = autobal_archive_var_int(a, g, "grid_boxes", 1, dg, gb, "1", "boxes the certified search examined there");
    free(gb);
  }
  return st;
}

/* The rotor model and the balanced configuration analysed in each plane (the member of the
 * family (3.14), with its given angles). */
static int write_model(autobal_archive *a, const autobal_rotor_params *p, const autobal_rotor_stab_options *so) {
  static const char *const member_names[] = {"default", "symmetric", "free", "given"};
  char grp[64];
  size_t j;
  int st = autobal_study_write_rotor_params(a, p, 0);
  for (j = 0; j < p->n_planes && j < AUTOBAL_ROTOR_MAX_PLANES && !st; j++) {
    const autobal_rotor_member *m = &so->member[j];
    snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
    st = autobal_archive_attr_string(a, grp, "member", m->kind >= 0 && m->kind <= 3 ? member_names[m->kind] : "?");
    if (!st && m->n_angles > 0) st = autobal_archive_attr_double_array(a, grp, "member_angles", m->n_angles, m->angles, "rad");
  }
  return st;
}

static int write_options(autobal_archive *a, const char *g, const autobal_rotor_stab_options *so) {
  static const char *const method_names[] = {"auto", "poly", "closed", "full", "floquet"};
  int st;
  if (so->method < 0 || so->method > 4) return AUTOBAL_EINVAL;
  st = autobal_archive_attr_string(a, g, "method_option", method_names[so->method]);
  if (!st) st = autobal_archive_attr_double(a, g, "tol", so->tol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "floquet_rtol", so->floquet_rtol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "floquet_atol", so->floquet_atol, "1");
  return st;
}

/* /rotor/stability/asymptotic: the asymptotic conditions (docs/rotor.md, Asymptotic conditions). */
static int write_asymptotic(autobal_archive *a, const autobal_rotor_asymptotic *q) {
  const char *g = "/rotor/stability/asymptotic";
  int st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "description", "ASYMPTOTIC conditions, reported beside the exact verdict, never instead of it (docs/rotor.md, Asymptotic conditions): light balls (L1) Re G < 0, (L2) kappa^2 (-Re G) > a (Im^2 G - q^2 |G|^2); high speed (H1) 1/M + d^2/(A - C) > 0, (H2) kappa > kappa_inf; each applicable when its small parameter is at most small_threshold");
  if (!st) st = autobal_archive_attr_double(a, g, "small_threshold", AUTOBAL_ROTOR_ASYMPTOTIC_SMALL, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "G_real", q->G_re, "m/N");
  if (!st) st = autobal_archive_attr_double(a, g, "G_imag", q->G_im, "m/N");
  if (!st) st = autobal_archive_attr_double(a, g, "kappa", q->kappa, "1/s");
  if (!st) st = autobal_archive_attr_double(a, g, "q", q->q, "1");
  if (!st && q->anisotropic) { /* anisotropic supports: G above is G+ (only then written: isotropic archives unchanged) */
    st = autobal_archive_attr_string(a, g, "anisotropic_description", "anisotropic supports: G_real, G_imag are the forward receptance G+ = b^T Z(i omega)^-1 conj(b) / 2 of the fixed-frame rotor-housing at the plane, G_minus the backward one; (L1), (L2) with G+ to leading order, the backward part averaged out (its estimated second-order effect: avg_small, part of light_small); no high-speed or undamped entry (docs/rotor.md, Anisotropic supports)");
    if (!st) st = autobal_archive_attr_int(a, g, "anisotropic", 1);
    if (!st) st = autobal_archive_attr_double(a, g, "G_minus_real", q->G_minus_re, "m/N");
    if (!st) st = autobal_archive_attr_double(a, g, "G_minus_imag", q->G_minus_im, "m/N");
    if (!st) st = autobal_archive_attr_double(a, g, "avg_small", q->avg_small, "1");
  }
  if (!st && q->undamped_defined) { /* kappa = 0: the undamped entry instead of (L1), (L2) */
    st = autobal_archive_attr_string(a, g, "undamped_description", "kappa = 0: the light-ball roots to the next order, +-i y + delta, delta = Re g1/2 +- (q^2 Re(g1 conj g0) - Im g0 Im g1)/(2 r) where the leading order puts them on the imaginary axis (undamped_on_axis), else the leading order; with the rotor roots shifted to first order (docs/rotor.md, Undamped balls)");
    if (!st) st = autobal_archive_attr_int(a, g, "undamped_on_axis", q->undamped_on_axis);
    if (!st) st = autobal_archive_attr_double_array(a, g, "undamped_delta", 2, q->undamped_delta, "1/s");
    if (!st) st = autobal_archive_attr_double_array(a, g, "undamped_ball_root_real", 4, q->undamped_ball_re, "1/s");
    if (!st) st = autobal_archive_attr_double_array(a, g, "undamped_ball_root_imag", 4, q->undamped_ball_im, "1/s");
    if (!st) st = autobal_archive_attr_double_array(a, g, "undamped_rotor_root_real", 4, q->rotor_re, "1/s");
    if (!st) st = autobal_archive_attr_double_array(a, g, "undamped_rotor_root_imag", 4, q->rotor_im, "1/s");
    if (!st) st = autobal_archive_attr_int(a, g, "undamped_predicts_stable", q->undamped_stable);
    if (!st) st = autobal_archive_attr_int(a, g, "undamped_decided", q->undamped_decided);
    if (!st) st = autobal_archive_attr_double(a, g, "undamped_small", q->undamped_small, "1");
    if (!st) st = autobal_archive_attr_int(a, g, "undamped_applicable", q->undamped_applicable);
    goto high;
  }
  if (!st) st = autobal_archive_attr_int(a, g, "light_supercritical", q->supercritical);
  if (!st) st = autobal_archive_attr_double(a, g, "light_kappa_min", q->kappa_min, "1/s");
  if (!st) st = autobal_archive_attr_int(a, g, "light_predicts_stable", q->light_stable);
  if (!st) st = autobal_archive_attr_double_array(a, g, "light_ball_root_real", 4, q->ball_re, "1/s");
  if (!st) st = autobal_archive_attr_double_array(a, g, "light_ball_root_imag", 4, q->ball_im, "1/s");
  if (!st) st = autobal_archive_attr_double_array(a, g, "light_rotor_root_real", 4, q->rotor_re, "1/s");
  if (!st) st = autobal_archive_attr_double_array(a, g, "light_rotor_root_imag", 4, q->rotor_im, "1/s");
  if (!st) st = autobal_archive_attr_int(a, g, "light_decided", q->light_decided);
  if (!st) st = autobal_archive_attr_double(a, g, "light_small", q->light_small, "1");
  if (!st) st = autobal_archive_attr_int(a, g, "light_applicable", q->light_applicable);
high:
  if (!st) st = autobal_archive_attr_int(a, g, "high_defined", q->high_defined);
  if (!st && q->high_defined) {
    st = autobal_archive_attr_double(a, g, "high_m_eff", q->m_eff, "kg");
    if (!st) st = autobal_archive_attr_double(a, g, "high_h_eff", q->h_eff, "N s/m");
    if (!st) st = autobal_archive_attr_double(a, g, "high_kappa_inf", q->kappa_inf, "1/s");
    if (!st) st = autobal_archive_attr_int(a, g, "high_predicts_stable", q->high_stable);
    if (!st) st = autobal_archive_attr_double(a, g, "high_small", q->high_small, "1");
    if (!st) st = autobal_archive_attr_int(a, g, "high_applicable", q->high_applicable);
  }
  return st;
}

/* /rotor/stability/asymptotic2: the two-plane light-ball condition (docs/rotor.md, Asymptotic conditions). */
static int write_asymptotic2(autobal_archive *a, const autobal_rotor_asymptotic2 *q) {
  const char *g = "/rotor/stability/asymptotic2";
  int st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "description", "ASYMPTOTIC light-ball condition for two planes, reported beside the exact verdict, never instead of it (docs/rotor.md, Asymptotic conditions, Two planes): the 8 ball roots of det(U - S) with the 2x2 receptance G (G_11, G_12, G_21, G_22) frozen at lambda = 0, and the rotor-housing's roots shifted to first order; applicable when light_small is at most small_threshold");
  if (!st) st = autobal_archive_attr_double(a, g, "small_threshold", AUTOBAL_ROTOR_ASYMPTOTIC_SMALL, "1");
  if (!st) st = autobal_archive_attr_double_array(a, g, "G_real", 4, q->G_re, "m/N");
  if (!st) st = autobal_archive_attr_double_array(a, g, "G_imag", 4, q->G_im, "m/N");
  if (!st) st = autobal_archive_attr_double_array(a, g, "kappa", 2, q->kappa, "1/s");
  if (!st) st = autobal_archive_attr_double_array(a, g, "q", 2, q->q, "1");
  if (!st) st = autobal_archive_attr_int(a, g, "light_predicts_stable", q->light_stable);
  if (!st) st = autobal_archive_attr_double_array(a, g, "light_ball_root_real", 8, q->ball_re, "1/s");
  if (!st) st = autobal_archive_attr_double_array(a, g, "light_ball_root_imag", 8, q->ball_im, "1/s");
  if (!st) st = autobal_archive_attr_double_array(a, g, "light_rotor_root_real", 4, q->rotor_re, "1/s");
  if (!st) st = autobal_archive_attr_double_array(a, g, "light_rotor_root_imag", 4, q->rotor_im, "1/s");
  if (!st) st = autobal_archive_attr_int(a, g, "light_decided", q->light_decided);
  if (!st) st = autobal_archive_attr_double(a, g, "light_small", q->light_small, "1");
  if (!st) st = autobal_archive_attr_int(a, g, "light_applicable", q->light_applicable);
  if (!st) st = autobal_archive_attr_int(a, g, "high_defined", q->high_defined);
  if (!st && q->high_defined) { /* high speed, balls at q = 0 in both planes */
    st = autobal_archive_attr_string(a, g, "high_description", "high speed, Q1 = Q2 = 0: (H1') Gamma positive definite, (H2') kappa_mode_k > kappa_inf_k for both modes k of Mb^1/2 Gamma Mb^1/2 (docs/rotor.md, Two planes at high speed)");
    if (!st) st = autobal_archive_attr_double_array(a, g, "high_Gamma", 4, q->high_Gamma, "1/kg");
    if (!st) st = autobal_archive_attr_double_array(a, g, "high_H", 4, q->high_H, "1/(kg s)");
    if (!st) st = autobal_archive_attr_double_array(a, g, "high_mu", 2, q->high_mu, "1");
    if (!st) st = autobal_archive_attr_double_array(a, g, "high_kappa_mode", 2, q->high_kappa_mode, "1/s");
    if (!st) st = autobal_archive_attr_double_array(a, g, "high_kappa_inf", 2, q->high_kappa_inf, "1/s");
    if (!st) st = autobal_archive_attr_double_array(a, g, "high_re", 2, q->high_re, "1/s");
    if (!st) st = autobal_archive_attr_int(a, g, "high_predicts_stable", q->high_stable);
    if (!st) st = autobal_archive_attr_int(a, g, "high_decided", q->high_decided);
    if (!st) st = autobal_archive_attr_double(a, g, "high_small", q->high_small, "1");
    if (!st) st = autobal_archive_attr_int(a, g, "high_applicable", q->high_applicable);
    if (!st) st = autobal_archive_attr_string(a, g, "high_every_description", "high speed, every unbalance of both planes and every phase, min(kappa_1, kappa_2) > high_every_kappa = rho sqrt(mu_2), rho the largest |nu| with det(H - nu Gamma) = 0 (sufficient; docs/rotor.md, Two planes at high speed)");
    if (!st) st = autobal_archive_attr_double(a, g, "high_every_kappa", q->high_every_kappa, "1/s");
    if (!st) st = autobal_archive_attr_double(a, g, "high_every_kappa_min", fmin(q->kappa[0], q->kappa[1]), "1/s");
    if (!st) st = autobal_archive_attr_int(a, g, "high_every_predicts_stable", q->high_every_stable);
    if (!st) st = autobal_archive_attr_double(a, g, "high_every_small", q->high_every_small, "1");
    if (!st) st = autobal_archive_attr_int(a, g, "high_every_applicable", q->high_every_applicable);
  }
  return st;
}

int autobal_study_rotor_stability_write(autobal_archive *a, const autobal_rotor_params *p,
                                        const autobal_study_rotor_stability_options *opt,
                                        const autobal_study_rotor_stability_summary *s) {
  static const char *const droot[] = {"root"}, *const dpow[] = {"power"}, *const dfull[] = {"full_root"},
                           *const dmu[] = {"multiplier"}, *const dball[] = {"ball"};
  autobal_study_rotor_stability_options def = autobal_study_rotor_stability_options_default();
  const autobal_study_rotor_stability_options *o = opt ? opt : &def;
  const autobal_rotor_stab_result *r;
  const char *g = "/rotor/stability";
  double power[AUTOBAL_ROTOR_POLY_LEN];
  size_t i;
  int st;
  if (!a || !p || !s) return AUTOBAL_EINVAL;
  r = &s->result;
  for (i = 0; i < AUTOBAL_ROTOR_POLY_LEN; i++) power[i] = (double)i;
  st = write_model(a, p, &o->stab);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = write_options(a, g, &o->stab);
  if (!st) st = autobal_archive_attr_string(a, g, "method", autobal_rotor_stab_method_name(r->method));
  if (!st) st = autobal_archive_attr_string(a, g, "verdict", verdict_text(r->verdict));
  if (!st) st = autobal_archive_attr_double(a, g, "margin", r->margin, "1/s");
  if (!st) st = autobal_archive_attr_double(a, g, "period", r->period, "s");
  if (!st) st = autobal_archive_attr_int(a, g, "isotropic", r->isotropic);
  if (!st) st = autobal_archive_attr_int(a, g, "closure_ok", r->closure_ok);
  if (!st) st = autobal_archive_attr_int(a, g, "n_family", (long)r->n_family);
  if (!st) st = autobal_archive_dim(a, g, "ball", r->n_balls, "ball index in state order (plane 1 first)");
  if (!st) st = autobal_archive_var(a, g, "psi_balanced", 1, dball, r->psi, "rad", "balanced ball angles (3.14) of the analysed member, relative to the rotor");
  if (!st && r->n_closed > 0) {
    st = autobal_archive_dim(a, g, "root", r->n_closed, "index of a characteristic root of the closed system");
    if (!st) st = autobal_archive_var(a, g, "root_real", 1, droot, r->root_re, "1/s", r->n_poly ? "real part of the characteristic roots lambda (rotating coordinates): roots of Delta (GSL polynomial solver)" : "real part of the characteristic roots lambda (rotating coordinates): eigenvalues of the closed first-order matrix");
    if (!st) st = autobal_archive_var(a, g, "root_imag", 1, droot, r->root_im, "1/s", r->n_poly ? "imaginary part of the characteristic roots lambda (rotating coordinates): roots of Delta (GSL polynomial solver)" : "imaginary part of the characteristic roots lambda (rotating coordinates): eigenvalues of the closed first-order matrix");
    if (!st) st = autobal_archive_var(a, g, "eig_real", 1, droot, r->closed_eig_re, "1/s", "real part of the eigenvalues of the closed first-order matrix (rotating coordinates), matched to the roots");
    if (!st) st = autobal_archive_var(a, g, "eig_imag", 1, droot, r->closed_eig_im, "1/s", "imaginary part of the eigenvalues of the closed first-order matrix (rotating coordinates), matched to the roots");
    if (!st) st = autobal_archive_attr_double(a, g, "closed_margin", r->closed_margin, "1/s");
    if (!st) st = autobal_archive_attr_double(a, g, "root_eig_mismatch", r->root_eig_mismatch, "1");
  }
  if (!st && r->n_poly > 0) {
    st = autobal_archive_coord(a, g, "power", AUTOBAL_ROTOR_POLY_LEN, power, "1", "power of lambda");
    if (!st) st = autobal_archive_var(a, g, "char_poly", 1, dpow, r->poly, "1", "coefficients of Delta = F F* - (|Q|/2)^2 P^4 Pb^4 N N*, ascending powers k of lambda (lambda in 1/s), each divided by its SI unit: Delta is in kg^4 m^4 s^-12, so the coefficient of lambda^k is this number times kg^4 m^4 s^(k-12)");
    if (!st) st = autobal_archive_attr_string(a, g, "hurwitz_verdict", autobal_verdict_name(r->hurwitz_verdict));
    if (!st) st = autobal_archive_attr_int(a, g, "hurwitz_n_rhp", r->hurwitz_n_rhp);
  }
  if (!st && r->n_full > 0) {
    st = autobal_archive_dim(a, g, "full_root", r->n_full, "index of an eigenvalue of the full model's linearization");
    if (!st) st = autobal_archive_var(a, g, "full_real", 1, dfull, r->full_re, "1/s", "real part of the eigenvalues of the full model's linearization in rotating coordinates");
    if (!st) st = autobal_archive_var(a, g, "full_imag", 1, dfull, r->full_im, "1/s", "imaginary part of the eigenvalues of the full model's linearization in rotating coordinates");
    if (!st) st = autobal_archive_attr_double(a, g, "full_margin", r->full_margin, "1/s");
    if (!st) st = autobal_archive_attr_double(a, g, "full_mismatch", r->full_mismatch, "1");
  }
  if (!st && r->n_floquet > 0) {
    st = autobal_archive_dim(a, g, "multiplier", r->n_floquet, "index of a Floquet multiplier (by decreasing modulus)");
    if (!st) st = autobal_archive_var(a, g, "floquet_real", 1, dmu, r->mu_re, "1", "real part of the Floquet multipliers mu (eigenvalues of the monodromy matrix over T = 2 pi/|omega|)");
    if (!st) st = autobal_archive_var(a, g, "floquet_imag", 1, dmu, r->mu_im, "1", "imaginary part of the Floquet multipliers mu (eigenvalues of the monodromy matrix over T = 2 pi/|omega|)");
    if (!st) st = autobal_archive_attr_double(a, g, "floquet_margin", r->floquet_margin, "1/s");
    if (!st) st = autobal_archive_attr_double(a, g, "floquet_mismatch", r->floquet_mismatch, "1");
  }
  if (!st && s->critical_cancelled)
    st = write_partial(a, g, 0, 0, "interrupted during the critical-speed search: the analysis at omega is complete, "
                                   "the critical speeds were not found (no /rotor/stability/critical)");
  if (!st && s->have_critical) {
    const char *gc = "/rotor/stability/critical";
    st = autobal_archive_group(a, gc);
    if (!st) st = autobal_archive_attr_double(a, gc, "omega_min", s->omega_min, "rad/s");
    if (!st) st = autobal_archive_attr_double(a, gc, "omega_max", s->omega_max, "rad/s");
    if (!st) st = autobal_archive_attr_int(a, gc, "n_omega", (long)s->n_omega);
    if (!st) st = write_crit(a, gc, &s->critical, "rad/s");
  }
  if (!st && s->have_asymptotic) st = write_asymptotic(a, &s->asymptotic);
  if (!st && s->have_asymptotic2) st = write_asymptotic2(a, &s->asymptotic2);
  if (!st && s->have_every) {
    const char *ge = "/rotor/stability/every_unbalance";
    const autobal_rotor_unbalance_range *u = &s->every;
    static const char *const dcu[] = {"unbalance_critical"}, *const dsub[] = {"sub_interval"};
    st = autobal_archive_group(a, ge);
    if (!st)
      st = autobal_archive_attr_string(a, ge, "description", u->hill
        ? "stability of the balanced motion for every unbalance m0 r0 in [unbalance_min, unbalance_max] at omega, anisotropic supports: Hill's method excludes Floquet multipliers on the unit circle over the whole range (no critical unbalances; one sub-interval with the verdict: 1 stable (proven), -1 unstable (unstable_unbalance), -2 undecided (hill_open boxes left at the budget)) (docs/rotor.md, Anisotropic supports: every unbalance)"
        : "stability of the balanced motion for every unbalance m0 r0 in [unbalance_min, unbalance_max] at omega: the critical unbalances (a root of Delta on the imaginary axis), the verdict between them (docs/rotor.md, Every unbalance)");
    if (!st) st = autobal_archive_attr_double(a, ge, "omega", u->omega, "rad/s");
    if (!st) st = autobal_archive_attr_double(a, ge, "unbalance_min", u->s_lo, "kg m");
    if (!st) st = autobal_archive_attr_double(a, ge, "unbalance_max", u->s_hi, "kg m");
    if (!st) st = autobal_archive_attr_int(a, ge, "stable_for_all", u->all_stable);
    if (!st && u->n_balls >= 3) { /* three or more identical balls: the member rule and the range of u */
      st = autobal_archive_attr_string(a, ge, "unbalance_member",
                                       u->member_rule == AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC ? "symmetric" : "every");
      if (!st) st = autobal_archive_attr_int(a, ge, "n_balls", (long)u->n_balls);
      if (!st) st = autobal_archive_attr_double(a, ge, "u_min", u->u_min, "kg^2");
      if (!st) st = autobal_archive_attr_double(a, ge, "u_max", u->u_max, "kg^2");
    }
    if (!st) st = autobal_archive_attr_double(a, ge, "margin_worst_evaluated", u->margin_worst, "1/s");
    if (!st) st = autobal_archive_attr_int(a, ge, "n_missed", (long)u->n_missed);
    if (!st) st = autobal_archive_attr_int(a, ge, "evaluations", (long)u->evaluations);
    if (!st && u->hill) { /* anisotropic supports: what Hill's method did */
      st = autobal_archive_attr_string(a, ge, "method", "hill");
      if (!st) st = autobal_archive_attr_int(a, ge, "hill_order", (long)u->hill_order);
      if (!st) st = autobal_archive_attr_double(a, ge, "hill_tail", u->hill_tail, "1");
      if (!st) st = autobal_archive_attr_int(a, ge, "hill_boxes", u->hill_boxes);
      if (!st) st = autobal_archive_attr_int(a, ge, "hill_open", (long)u->hill_open);
      if (!st) st = autobal_archive_attr_double(a, ge, "unstable_unbalance", u->s_unstable, "kg m");
    }
    if (!st && u->n_crit > 0) {
      st = autobal_archive_dim(a, ge, "unbalance_critical", u->n_crit, "index of a critical unbalance");
      if (!st) st = autobal_archive_var(a, ge, "critical_unbalance", 1, dcu, u->s_crit, "kg m", "critical unbalance m0 r0: a root of Delta on the imaginary axis");
    }
    if (!st && u->n_balls >= 3 && u->member_rule == AUTOBAL_ROTOR_UNBALANCE_EVERY) {
      /* three balls, every member: the critical u, the unbalances where each is met, the u sub-intervals */
      static const char *const duc[] = {"u_critical"}, *const dup[] = {"u_critical_piece"}, *const dus[] = {"u_sub_interval"};
      int v[AUTOBAL_ROTOR_MAX_UCRIT + 1], ix[3 * AUTOBAL_ROTOR_MAX_UCRIT];
      size_t q;
      if (!st && u->n_ucrit > 0) {
        st = autobal_archive_dim(a, ge, "u_critical", u->n_ucrit, "index of a critical value of u = |Q|^2/4");
        if (!st) st = autobal_archive_var(a, ge, "critical_u", 1, duc, u->u_crit, "kg^2", "critical u = |Q|^2/4: a root of Delta on the imaginary axis");
      }
      if (!st && u->n_upiece > 0) {
        for (q = 0; q < u->n_upiece; q++) ix[q] = (int)u->upiece_crit[q];
        st = autobal_archive_dim(a, ge, "u_critical_piece", u->n_upiece, "index of an interval of m0 r0 where some member has a critical u");
        if (!st) st = autobal_archive_var_int(a, ge, "critical_u_piece_index", 1, dup, ix, "1", "index (along u_critical) of the critical u met in the interval");
        if (!st) st = autobal_archive_var(a, ge, "critical_u_piece_lo", 1, dup, u->upiece_lo, "kg m", "lower end of the interval of m0 r0 where some member has the critical u");
        if (!st) st = autobal_archive_var(a, ge, "critical_u_piece_hi", 1, dup, u->upiece_hi, "kg m", "upper end of the interval of m0 r0 where some member has the critical u");
      }
      if (!st && u->n_usub > 0) {
        for (q = 0; q < u->n_usub; q++) v[q] = u->usub_verdict[q];
        st = autobal_archive_dim(a, ge, "u_sub_interval", u->n_usub, "index of a sub-interval of [u_min, u_max] between critical values of u");
        if (!st) st = autobal_archive_var(a, ge, "u_sub_lo", 1, dus, u->usub_lo, "kg^2", "lower end of the sub-interval of u");
        if (!st) st = autobal_archive_var(a, ge, "u_sub_hi", 1, dus, u->usub_hi, "kg^2", "upper end of the sub-interval of u");
        if (!st) st = autobal_archive_var_int(a, ge, "u_sub_verdict", 1, dus, v, "1", "verdict of every member whose u lies inside the sub-interval: 1 stable, 0 marginal, -1 unstable, -2 undecided (no member found there)");
        if (!st) st = autobal_archive_var(a, ge, "u_sub_margin", 1, dus, u->usub_margin, "1/s", "stability margin (largest real part) at the sub-interval's midpoint");
      }
      if (!st && u->n_balls >= 4) { /* four or more balls: u_min, u_max enclose; the members found */
        st = autobal_archive_attr_double(a, ge, "u_min_inner", u->u_min_inner, "kg^2");
        if (!st) st = autobal_archive_attr_double(a, ge, "u_max_inner", u->u_max_inner, "kg^2");
        if (!st) st = autobal_archive_attr_int(a, ge, "u_enclosure_complete", u->u_complete);
        if (!st) st = autobal_archive_attr_int(a, ge, "u_boxes", u->u_boxes);
        if (!st) st = autobal_archive_attr_int(a, ge, "u_sub_undecided", (long)u->n_uundecided);
      }
    }
    if (!st && u->n_sub > 0) {
      int v[AUTOBAL_ROTOR_MAX_UCRIT + 1];
      size_t q;
      for (q = 0; q < u->n_sub; q++) v[q] = u->sub_verdict[q];
      st = autobal_archive_dim(a, ge, "sub_interval", u->n_sub, "index of a sub-interval between critical unbalances");
      if (!st) st = autobal_archive_var(a, ge, "sub_lo", 1, dsub, u->sub_lo, "kg m", "lower end of the sub-interval (m0 r0)");
      if (!st) st = autobal_archive_var(a, ge, "sub_hi", 1, dsub, u->sub_hi, "kg m", "upper end of the sub-interval (m0 r0)");
      if (!st) st = autobal_archive_var_int(a, ge, "sub_verdict", 1, dsub, v, "1", "verdict inside the sub-interval: 1 stable, 0 marginal, -1 unstable, -2 undecided (anisotropic supports: Hill boxes left open)");
      if (!st) st = autobal_archive_var(a, ge, "sub_margin", 1, dsub, u->sub_margin, "1/s", "stability margin (largest real part) at the sub-interval's midpoint");
    }
    if (!st && s->have_every2) {
      const autobal_rotor_unbalance_range2 *u2 = &s->every2;
      if (!st) st = autobal_archive_attr_string(a, ge, "two_planes", "both planes: unbalance_min..max for plane 1 (exact over the whole range when exact_in_unbalance1 = 1), unbalance2_min..max for plane 2 (exact over the whole range by a certified box search when exact_in_unbalance2 = 1, else at n_unbalance values, SAMPLED), every relative phase (exact); the margins at an n_unbalance x n_unbalance grid; no critical unbalances; one sub-interval with the worst verdict met");
      if (!st) st = autobal_archive_attr_double(a, ge, "unbalance2_min", u2->s_lo[1], "kg m");
      if (!st) st = autobal_archive_attr_double(a, ge, "unbalance2_max", u2->s_hi[1], "kg m");
      if (!st) st = autobal_archive_attr_int(a, ge, "n_unbalance1", (long)u2->n_s[0]);
      if (!st) st = autobal_archive_attr_int(a, ge, "n_unbalance2", (long)u2->n_s[1]);
      if (!st) st = autobal_archive_attr_int(a, ge, "n_points_not_stable", (long)u2->n_not_stable);
      if (!st) st = autobal_archive_attr_int(a, ge, "n_points_with_critical_phase", (long)u2->n_with_crit);
      if (!st) st = autobal_archive_attr_int(a, ge, "exact_in_unbalance1", u2->exact_in_s1);
      if (!st) st = autobal_archive_attr_int(a, ge, "exact_in_unbalance2", u2->exact_in_s2);
      if (!st) st = autobal_archive_attr_int(a, ge, "n_unbalance2_not_stable", (long)u2->n_slices_not_stable);
    }
    if (!st && s->have_every_phase) {
      const char *gp = "/rotor/stability/every_unbalance/phase";
      const autobal_rotor_phase_range *ph = &s->every_phase;
      static const char *const dpc[] = {"phase_critical"}, *const darc[] = {"phase_arc"};
      st = autobal_archive_group(a, gp);
      if (!st) st = autobal_archive_attr_string(a, gp, "description", "every relative phase plane2.psi0 - plane1.psi0 at the configuration's m0 r0 of both planes: the critical phases (a root on the imaginary axis) in [0, pi) (the verdict has period pi) and the verdict on the arcs between them (docs/rotor.md, Every unbalance)");
      if (!st) st = autobal_archive_attr_double(a, gp, "unbalance1", ph->s[0], "kg m");
      if (!st) st = autobal_archive_attr_double(a, gp, "unbalance2", ph->s[1], "kg m");
      if (!st) st = autobal_archive_attr_int(a, gp, "stable_for_all_phases", ph->all_stable);
      if (!st) st = autobal_archive_attr_int(a, gp, "n_missed", (long)ph->n_missed);
      if (!st && ph->n_crit > 0) {
        st = autobal_archive_dim(a, gp, "phase_critical", ph->n_crit, "index of a critical phase");
        if (!st) st = autobal_archive_var(a, gp, "critical_phase", 1, dpc, ph->phase_crit, "rad", "critical relative phase: a root of the closed system on the imaginary axis");
        if (!st) st = autobal_archive_var(a, gp, "crossing_frequency", 1, dpc, ph->y_crit, "1/s", "imaginary part of that root (rotating frame)");
      }
      if (!st && ph->n_sub > 0) {
        int v[AUTOBAL_ROTOR_MAX_PCRIT + 1];
        size_t q;
        for (q = 0; q < ph->n_sub; q++) v[q] = ph->sub_verdict[q];
        st = autobal_archive_dim(a, gp, "phase_arc", ph->n_sub, "index of an arc between critical phases");
        if (!st) st = autobal_archive_var(a, gp, "arc_lo", 1, darc, ph->sub_lo, "rad", "start of the arc (relative phase)");
        if (!st) st = autobal_archive_var(a, gp, "arc_hi", 1, darc, ph->sub_hi, "rad", "end of the arc (may exceed pi: it wraps)");
        if (!st) st = autobal_archive_var_int(a, gp, "arc_verdict", 1, darc, v, "1", "verdict on the arc: 1 stable, 0 marginal, -1 unstable");
      }
    }
    if (!st && s->have_every_speeds) {
      const char *gs = "/rotor/stability/every_unbalance/speeds";
      st = autobal_archive_group(a, gs);
      if (!st) st = autobal_archive_attr_string(a, gs, "description", "speeds where the balanced motion is stable for every unbalance in the range: the changes of that verdict (refined by bisection) and the stable intervals");
      if (!st) st = autobal_archive_attr_double(a, gs, "omega_min", s->omega_min, "rad/s");
      if (!st) st = autobal_archive_attr_double(a, gs, "omega_max", s->omega_max, "rad/s");
      if (!st) st = autobal_archive_attr_int(a, gs, "n_omega", (long)s->n_omega);
      if (!st) st = write_crit(a, gs, &s->every_speeds, "rad/s");
      if (!st && s->have_every_speeds2) st = write_speeds2(a, gs, &s->every_speeds, &s->every_speeds2, s->every_speeds2_n);
    }
  }
  return st;
}

/* ---- sweep, map, Campbell ------------------------------------------------------------------ */
/* The default range of a configuration key as a parameter: around its value v at p (read
 * through a stability handle): [v/4, 4 v] for v > 0, [4 v, v/4] for v < 0, [0, 1] for v = 0;
 * a phase psi0 over [-pi, pi]; a plane position d over the span of the supports [-l_L, l_R]
 * (hardware) or v -/+ (2 |v| + 0.1) m (lumped).  NaN, NaN for a key that is not a parameter of
 * p (e.g. a hardware key of a lumped rotor). */
static void key_range(const autobal_rotor_params *p, int param, double *lo, double *hi) {
  autobal_rotor_stab *h = autobal_rotor_stab_alloc(p, NULL, NULL);
  const char *name = autobal_rotor_stab_param_name(param);
  const size_t nm = name ? strlen(name) : 0;
  double v = h ? autobal_rotor_stab_get(h, param) : NAN;
  autobal_rotor_stab_free(h);
  *lo = *hi = NAN;
  if (!isfinite(v) || !name) return;
  if (nm > 5 && !strcmp(name + nm - 5, ".psi0")) {
    *lo = -M_PI, *hi = M_PI;
  } else if (nm > 2 && !strcmp(name + nm - 2, ".d")) {
    if (p->input == AUTOBAL_ROTOR_HARDWARE && p->hw.l_L + p->hw.l_R > 0.0)
      *lo = -p->hw.l_L, *hi = p->hw.l_R;
    else
      *lo = v - (2.0 * fabs(v) + 0.1), *hi = v + (2.0 * fabs(v) + 0.1);
  } else if (v > 0.0) {
    *lo = 0.25 * v, *hi = 4.0 * v;
  } else if (v < 0.0) {
    *lo = 4.0 * v, *hi = 0.25 * v;
  } else {
    *lo = 0.0, *hi = 1.0;
  }
}

void autobal_study_rotor_param_range(const autobal_rotor_params *p, int param, double *lo, double *hi) {
  const autobal_rotor_plane *pl = &p->plane[0];
  double l0, h0;
  switch (param) {
    case AUTOBAL_ROTOR_PARAM_OMEGA:
      autobal_study_rotor_speed_range(p, &l0, &h0);
      *lo = l0, *hi = h0;
      return;
    case AUTOBAL_ROTOR_PARAM_BALL_DAMPING:
      *lo = 0.0, *hi = 10.0 * (pl->n_balls ? pl->ball_damping[0] : 0.1) + 1e-3;
      return;
    case AUTOBAL_ROTOR_PARAM_BALL_MASS:
      *lo = 0.1 * (pl->n_balls ? pl->ball_mass[0] : 0.05), *hi = 4.0 * (pl->n_balls ? pl->ball_mass[0] : 0.05);
      return;
    case AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS:
      *lo = 0.0, *hi = 4.0 * pl->m0 + 1e-3;
      return;
    case AUTOBAL_ROTOR_PARAM_DAMPING_SCALE:
      *lo = 0.0, *hi = 4.0;
      return;
    case AUTOBAL_ROTOR_PARAM_STIFFNESS_SCALE:
      *lo = 0.25, *hi = 4.0;
      return;
    default:
      key_range(p, param, lo, hi);
      return;
  }
}

/* A linear grid [lo, hi] with n points. */
static double *grid(double lo, double hi, size_t n) {
  double *v = malloc((n ? n : 1) * sizeof *v);
  size_t i;
  if (!v) return NULL;
  for (i = 0; i < n; i++) v[i] = n == 1 ? lo : (i + 1 == n ? hi : lo + (hi - lo) * (double)i / (double)(n - 1));
  return v;
}

autobal_study_rotor_sweep_options autobal_study_rotor_sweep_options_default(void) {
  autobal_study_rotor_sweep_options o;
  memset(&o, 0, sizeof o);
  o.stab = autobal_rotor_stab_options_default();
  o.param = AUTOBAL_ROTOR_PARAM_OMEGA;
  o.min = o.max = NAN;
  o.n = 1000;
  o.xtol_rel = 1e-8;
  return o;
}

void autobal_study_rotor_sweep_summary_free(autobal_study_rotor_sweep_summary *s) {
  if (!s) return;
  free(s->values);
  free(s->margin);
  free(s->verdict);
  s->values = s->margin = NULL;
  s->verdict = NULL;
}

int autobal_study_rotor_sweep(const autobal_rotor_params *p, const autobal_study_rotor_sweep_options *opt,
                              autobal_archive *a, autobal_study_rotor_sweep_summary *summary, autobal_error *err) {
  autobal_study_rotor_sweep_options def = autobal_study_rotor_sweep_options_default();
  const autobal_study_rotor_sweep_options *o = opt ? opt : &def;
  autobal_study_rotor_sweep_summary *s = summary;
  autobal_rotor_stab *h;
  autobal_error e;
  const char *pname, *unit;
  double lo, hi;
  size_t i, n;
  int st;
  autobal_error_clear(err);
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(s, 0, sizeof *s);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  pname = autobal_rotor_stab_param_name(o->param);
  unit = autobal_rotor_stab_param_unit(o->param);
  if (!pname || !unit) return autobal_error_set(err, AUTOBAL_EINVAL, "options: param = %d is not a rotor parameter id", o->param);
  autobal_study_rotor_param_range(p, o->param, &lo, &hi);
  if (!isnan(o->min)) lo = o->min;
  if (!isnan(o->max)) hi = o->max;
  if (!(lo < hi) || o->n < 2 || o->n > 10000000 || !(o->xtol_rel > 0 && o->xtol_rel < 0.1))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: need min < max, n in [2, 1e7], xtol_rel in (0, 0.1); got %g, %g, %zu, %g", lo, hi,
                             o->n, o->xtol_rel);
  if (o->param != AUTOBAL_ROTOR_PARAM_OMEGA && !(p->omega != 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter omega = 0: nothing to analyse");
  n = o->n;
  s->param = o->param, s->min = lo, s->max = hi, s->n = n;
  autobal_error_clear(&e);
  h = autobal_rotor_stab_alloc(p, &o->stab, &e);
  if (!h) return autobal_error_set(err, e.status ? e.status : AUTOBAL_EINVAL, "%s", e.message);
  s->values = grid(lo, hi, n);
  s->margin = malloc(n * sizeof *s->margin);
  s->verdict = malloc(n * sizeof *s->verdict);
  if (!s->values || !s->margin || !s->verdict) {
    st = autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
    goto done;
  }
  /* the sweep in chunks, for progress and cancellation */
  for (i = 0; i < n; i += 64) {
    size_t m = n - i < 64 ? n - i : 64;
    st = autobal_rotor_stab_sweep(h, o->param, s->values + i, m, s->margin + i, s->verdict + i);
    if (st) {
      autobal_error_set(err, st, "%s = %.9g %s: %s", pname, s->values[i], unit, autobal_rotor_stab_errmsg(h));
      goto done;
    }
    s->n_done = i + m;
    if (o->progress && o->progress(0.5 * (double)(i + m) / (double)n, o->progress_user)) {
      st = AUTOBAL_ECANCELLED;
      goto cancelled;
    }
  }
  {
    progress_hook ph;
    ph.fn = o->progress;
    ph.user = o->progress_user;
    ph.fraction = 0.5;
    if (o->progress) autobal_rotor_stab_set_cancel(h, progress_cancel, &ph);
    st = autobal_rotor_stab_critical(h, o->param, lo, hi, n, o->xtol_rel, &s->critical);
    autobal_rotor_stab_set_cancel(h, NULL, NULL);
    if (st == AUTOBAL_ECANCELLED) goto cancelled;
  }
  if (st == AUTOBAL_WARNING) {
    s->critical_truncated = 1;
    snprintf(s->critical_message, sizeof s->critical_message, "%s", autobal_rotor_stab_errmsg(h));
    st = AUTOBAL_SUCCESS;
  }
  if (st) {
    autobal_error_set(err, st, "critical values: %s", autobal_rotor_stab_errmsg(h));
    goto done;
  }
  for (i = 0; i < n; i++) s->n_stable += s->verdict[i] == AUTOBAL_VERDICT_STABLE;
  if (a && (st = autobal_study_rotor_sweep_write(a, p, o, s))) autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
done:
  autobal_rotor_stab_free(h);
  return st;
cancelled: /* the points done stay; the critical values (a partial search) are dropped */
  s->cancelled = 1;
  memset(&s->critical, 0, sizeof s->critical);
  s->critical.param = o->param;
  s->critical_truncated = 0;
  s->critical_message[0] = '\0';
  for (i = 0; i < s->n_done; i++) s->n_stable += s->verdict[i] == AUTOBAL_VERDICT_STABLE;
  autobal_rotor_stab_free(h);
  if (a && (st = autobal_study_rotor_sweep_write(a, p, o, s))) return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
  return autobal_error_set(err, AUTOBAL_ECANCELLED, "cancelled by the progress callback after %zu of %zu points%s", s->n_done, n,
                           s->n_done == n ? " (during the search for critical values)" : "");
}

int autobal_study_rotor_sweep_write(autobal_archive *a, const autobal_rotor_params *p,
                                    const autobal_study_rotor_sweep_options *opt,
                                    const autobal_study_rotor_sweep_summary *s) {
  autobal_study_rotor_sweep_options def = autobal_study_rotor_sweep_options_default();
  const autobal_study_rotor_sweep_options *o = opt ? opt : &def;
  const char *g = "/rotor/sweep", *pname, *unit;
  const char *dims[1];
  char lname[160], what[256];
  size_t nw;
  int st;
  if (!a || !p || !s || !s->values) return AUTOBAL_EINVAL;
  nw = s->cancelled ? s->n_done : s->n;
  pname = autobal_rotor_stab_param_name(s->param);
  unit = autobal_rotor_stab_param_unit(s->param);
  if (!pname || !unit) return AUTOBAL_EINVAL;
  dims[0] = pname;
  snprintf(lname, sizeof lname, "swept parameter %s", pname);
  st = write_model(a, p, &o->stab);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = write_options(a, g, &o->stab);
  if (!st) st = autobal_archive_attr_string(a, g, "param", pname);
  if (!st && s->cancelled) {
    snprintf(what, sizeof what, "interrupted: the first %zu of %zu points of %s (done, requested); the critical values "
             "were not searched", s->n_done, s->n, pname);
    st = write_partial(a, g, s->n_done, s->n, what);
  }
  if (nw == 0) return st;
  if (!st) st = autobal_archive_coord(a, g, pname, nw, s->values, unit, lname);
  if (!st) st = autobal_archive_var(a, g, "margin", 1, dims, s->margin, "1/s", "stability margin: largest real part of the characteristic roots (family roots excluded; Floquet: log max|mu| / T); NaN: no balanced configuration");
  if (!st) st = autobal_archive_var_int(a, g, "verdict", 1, dims, s->verdict, "1", "1 stable, 0 marginal, -1 unstable, -2 no balanced configuration");
  if (!st && !s->cancelled) st = write_crit(a, g, &s->critical, unit);
  return st;
}

autobal_study_rotor_map_options autobal_study_rotor_map_options_default(void) {
  autobal_study_rotor_map_options o;
  memset(&o, 0, sizeof o);
  o.stab = autobal_rotor_stab_options_default();
  o.param1 = AUTOBAL_ROTOR_PARAM_OMEGA;
  o.param2 = AUTOBAL_ROTOR_PARAM_BALL_DAMPING;
  o.min1 = o.max1 = o.min2 = o.max2 = NAN;
  o.n1 = 120;
  o.n2 = 60;
  o.threads = 0;
  o.every_unbalance = 0;
  o.unbalance_min = NAN;
  o.unbalance_max = NAN;
  return o;
}

void autobal_study_rotor_map_summary_free(autobal_study_rotor_map_summary *s) {
  if (!s) return;
  free(s->values1);
  free(s->values2);
  free(s->margin);
  free(s->verdict);
  s->values1 = s->values2 = s->margin = NULL;
  s->verdict = NULL;
}

int autobal_study_rotor_map(const autobal_rotor_params *p, const autobal_study_rotor_map_options *opt,
                            autobal_archive *a, autobal_study_rotor_map_summary *summary, autobal_error *err) {
  autobal_study_rotor_map_options def = autobal_study_rotor_map_options_default();
  const autobal_study_rotor_map_options *o = opt ? opt : &def;
  autobal_study_rotor_map_summary *s = summary;
  size_t i, n;
  int st;
  autobal_error_clear(err);
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(s, 0, sizeof *s);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  if (!autobal_rotor_stab_param_name(o->param1) || !autobal_rotor_stab_param_name(o->param2))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: param1 = %d or param2 = %d is not a rotor parameter id",
                             o->param1, o->param2);
  if (o->param1 == o->param2)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: param1 and param2 must differ (both %s)",
                             autobal_rotor_stab_param_name(o->param1));
  s->param1 = o->param1, s->param2 = o->param2;
  autobal_study_rotor_param_range(p, o->param1, &s->min1, &s->max1);
  autobal_study_rotor_param_range(p, o->param2, &s->min2, &s->max2);
  if (!isnan(o->min1)) s->min1 = o->min1;
  if (!isnan(o->max1)) s->max1 = o->max1;
  if (!isnan(o->min2)) s->min2 = o->min2;
  if (!isnan(o->max2)) s->max2 = o->max2;
  if (!(s->min1 <= s->max1) || !(s->min2 <= s->max2) || o->n1 < 1 || o->n2 < 1 || o->n1 > 100000 || o->n2 > 100000 ||
      o->threads < 0 || o->threads > 1024)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: need min1 <= max1, min2 <= max2, n1, n2 in [1, 100000], threads in [0, 1024]");
  s->n1 = o->n1, s->n2 = o->n2;
  n = s->n1 * s->n2;
  s->values1 = grid(s->min1, s->max1, s->n1);
  s->values2 = grid(s->min2, s->max2, s->n2);
  s->margin = malloc(n * sizeof *s->margin);
  s->verdict = malloc(n * sizeof *s->verdict);
  if (!s->values1 || !s->values2 || !s->margin || !s->verdict)
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  {
    /* in blocks of rows (each point is independent: the blocks change nothing) */
    size_t rows = 1;
    int cancelled = 0;
    while (s->n1_done < s->n1 && !cancelled) {
      size_t r = s->n1 - s->n1_done < rows ? s->n1 - s->n1_done : rows, off = s->n1_done * s->n2;
      double t0 = now_seconds();
      if (o->every_unbalance)
        st = autobal_rotor_stab_map_every_unbalance(p, &o->stab, o->param1, s->values1 + s->n1_done, r, o->param2,
                                                    s->values2, s->n2, o->unbalance_min, o->unbalance_max, o->threads,
                                                    s->margin + off, s->verdict + off, err);
      else
        st = autobal_rotor_stab_map(p, &o->stab, o->param1, s->values1 + s->n1_done, r, o->param2, s->values2, s->n2,
                                    o->threads, s->margin + off, s->verdict + off, err);
      if (st) return st;
      s->n1_done += r;
      rows = next_block(rows, now_seconds() - t0);
      if (o->progress && o->progress((double)s->n1_done / (double)s->n1, o->progress_user)) cancelled = 1;
    }
    for (i = 0; i < s->n1_done * s->n2; i++) s->n_stable += s->verdict[i] == AUTOBAL_VERDICT_STABLE;
    if (a && (st = autobal_study_rotor_map_write(a, p, o, s)))
      return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
    if (cancelled && s->n1_done < s->n1)
      return autobal_error_set(err, AUTOBAL_ECANCELLED, "cancelled by the progress callback after %zu of %zu rows",
                               s->n1_done, s->n1);
  }
  return AUTOBAL_SUCCESS;
}

int autobal_study_rotor_map_write(autobal_archive *a, const autobal_rotor_params *p,
                                  const autobal_study_rotor_map_options *opt,
                                  const autobal_study_rotor_map_summary *s) {
  autobal_study_rotor_map_options def = autobal_study_rotor_map_options_default();
  const autobal_study_rotor_map_options *o = opt ? opt : &def;
  const char *g = "/rotor/map", *n1s, *n2s;
  const char *dims[2];
  char what[256];
  size_t nr;
  int st;
  if (!a || !p || !s || !s->values1) return AUTOBAL_EINVAL;
  nr = s->n1_done > 0 && s->n1_done < s->n1 ? s->n1_done : s->n1; /* n1_done = 0: a summary built by hand */
  n1s = autobal_rotor_stab_param_name(s->param1);
  n2s = autobal_rotor_stab_param_name(s->param2);
  dims[0] = n1s;
  dims[1] = n2s;
  st = write_model(a, p, &o->stab);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = write_options(a, g, &o->stab);
  if (!st) st = autobal_archive_attr_string(a, g, "param1", n1s);
  if (!st) st = autobal_archive_attr_string(a, g, "param2", n2s);
  if (!st && nr < s->n1) {
    snprintf(what, sizeof what, "interrupted: the first %zu of %zu rows (%s values; done, requested)", nr, s->n1, n1s);
    st = write_partial(a, g, nr, s->n1, what);
  }
  if (!st) st = autobal_archive_coord(a, g, n1s, nr, s->values1, autobal_rotor_stab_param_unit(s->param1), "first parameter (rows)");
  if (!st) st = autobal_archive_coord(a, g, n2s, s->n2, s->values2, autobal_rotor_stab_param_unit(s->param2), "second parameter (columns)");
  if (!st && o->every_unbalance) {
    st = autobal_archive_attr_int(a, g, "every_unbalance", 1);
    if (!st) st = autobal_archive_attr_double(a, g, "unbalance_min", o->unbalance_min, "kg m");
    if (!st) st = autobal_archive_attr_double(a, g, "unbalance_max", o->unbalance_max, "kg m");
    if (!st && p->n_planes == 1 && p->plane[0].n_balls >= 3)
      st = autobal_archive_attr_string(a, g, "unbalance_member",
                                       o->stab.unbalance_member == AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC ? "symmetric" : "every");
    if (!st) st = autobal_archive_var(a, g, "margin", 2, dims, s->margin, "1/s", "for every unbalance in [unbalance_min, unbalance_max]: the largest margin met (the least stable unbalance evaluated; NaN: the balls cannot balance every unbalance of the range)");
    if (!st) st = autobal_archive_var_int(a, g, "verdict", 2, dims, s->verdict, "1", "for every unbalance in [unbalance_min, unbalance_max]: 1 stable for all, 0 a critical unbalance touches (stable around it), -1 unstable for some, -2 the balls cannot balance every unbalance of the range, -3 undecided (anisotropic supports: Hill's box budget hill_boxes reached, no unstable member found)");
    return st;
  }
  if (!st) st = autobal_archive_var(a, g, "margin", 2, dims, s->margin, "1/s", "stability margin of the balanced motion (NaN: no balanced configuration)");
  if (!st) st = autobal_archive_var_int(a, g, "verdict", 2, dims, s->verdict, "1", "1 stable, 0 marginal, -1 unstable, -2 no balanced configuration");
  return st;
}

autobal_study_rotor_campbell_options autobal_study_rotor_campbell_options_default(void) {
  autobal_study_rotor_campbell_options o;
  memset(&o, 0, sizeof o);
  o.omega_min = o.omega_max = NAN;
  o.n = 401;
  o.n_resonance = 4000;
  o.xtol_rel = 1e-10;
  return o;
}

void autobal_study_rotor_campbell_summary_free(autobal_study_rotor_campbell_summary *s) {
  if (!s) return;
  free(s->omega);
  free(s->frequency);
  free(s->damping_ratio);
  free(s->whirl);
  free(s->amp_G);
  free(s->amp_D);
  s->omega = s->frequency = s->damping_ratio = s->amp_G = s->amp_D = NULL;
  s->whirl = NULL;
}

int autobal_study_rotor_campbell(const autobal_rotor_params *p, const autobal_study_rotor_campbell_options *opt,
                                 autobal_archive *a, autobal_study_rotor_campbell_summary *summary,
                                 autobal_error *err) {
  autobal_study_rotor_campbell_options def = autobal_study_rotor_campbell_options_default();
  const autobal_study_rotor_campbell_options *o = opt ? opt : &def;
  autobal_study_rotor_campbell_summary *s = summary;
  autobal_error e;
  size_t i, j, n, np;
  int st;
  autobal_error_clear(err);
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(s, 0, sizeof *s);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  s->omega_min = isnan(o->omega_min) ? 0.0 : o->omega_min;
  if (isnan(o->omega_max)) {
    double l0, h0;
    autobal_study_rotor_speed_range(p, &l0, &h0);
    s->omega_max = h0;
  } else {
    s->omega_max = o->omega_max;
  }
  if (!(s->omega_min >= 0 && s->omega_min < s->omega_max) || o->n < 2 || o->n > 10000000 || o->n_resonance < 3 ||
      o->n_resonance > 10000000 || !(o->xtol_rel > 0 && o->xtol_rel < 0.1))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "options: need 0 <= omega_min < omega_max, n in [2, 1e7], n_resonance in [3, 1e7], xtol_rel in (0, 0.1)");
  n = o->n;
  np = p->n_planes;
  s->n = n, s->n_planes = np;
  s->omega = grid(s->omega_min, s->omega_max, n);
  s->frequency = malloc(4 * n * sizeof *s->frequency);
  s->damping_ratio = malloc(4 * n * sizeof *s->damping_ratio);
  s->whirl = malloc(4 * n * sizeof *s->whirl);
  s->amp_G = malloc(n * sizeof *s->amp_G);
  s->amp_D = malloc((np ? np : 1) * n * sizeof *s->amp_D);
  if (!s->omega || !s->frequency || !s->damping_ratio || !s->whirl || !s->amp_G || !s->amp_D)
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  if ((st = autobal_rotor_modes(p, 0.0, 1, s->natural_frequency_undamped, NULL, NULL, NULL, err)) ||
      (st = autobal_rotor_modes(p, 0.0, 0, s->natural_frequency_damped, s->damping_ratio_at_rest, NULL, NULL, err)))
    return st;
  {
    /* the diagram and the response in blocks of speeds (for progress and cancellation) */
    size_t rows = 1;
    while (s->n_done < n) {
      size_t r = n - s->n_done < rows ? n - s->n_done : rows, i0 = s->n_done;
      double t0 = now_seconds();
      if ((st = autobal_rotor_campbell(p, s->omega + i0, r, s->frequency + 4 * i0, s->damping_ratio + 4 * i0,
                                       s->whirl + 4 * i0, err)))
        return st;
      for (i = i0; i < i0 + r; i++) {
        double d2[AUTOBAL_ROTOR_MAX_PLANES];
        if (autobal_rotor_unbalance_response(p, s->omega[i], &s->amp_G[i], d2, NULL) != AUTOBAL_SUCCESS) {
          s->amp_G[i] = INFINITY; /* an undamped resonance exactly on the grid */
          for (j = 0; j < np; j++) d2[j] = INFINITY;
        }
        for (j = 0; j < np; j++) s->amp_D[i * np + j] = d2[j];
      }
      s->n_done += r;
      rows = next_block(rows, now_seconds() - t0);
      if (o->progress && o->progress(0.5 * (double)s->n_done / (double)n, o->progress_user)) {
        st = AUTOBAL_ECANCELLED;
        break;
      }
    }
  }
  autobal_error_clear(&e);
  if (st != AUTOBAL_ECANCELLED) {
    progress_hook ph;
    ph.fn = o->progress;
    ph.user = o->progress_user;
    ph.fraction = 0.5;
    st = autobal_rotor_resonance_speeds_cancellable(p, s->omega_min, s->omega_max, o->n_resonance, o->xtol_rel,
                                                    o->progress ? progress_cancel : NULL, &ph, &s->resonances, &e);
  }
  if (st == AUTOBAL_ECANCELLED) {
    memset(&s->resonances, 0, sizeof s->resonances);
    if (a && (st = autobal_study_rotor_campbell_write(a, p, s)))
      return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
    return autobal_error_set(err, AUTOBAL_ECANCELLED, "cancelled by the progress callback after %zu of %zu speeds%s",
                             s->n_done, n, s->n_done == n ? " (during the resonance search)" : "");
  }
  s->have_resonances = 1;
  if (st == AUTOBAL_WARNING) {
    s->resonances_truncated = 1;
    snprintf(s->resonance_message, sizeof s->resonance_message, "%s", e.message);
    st = AUTOBAL_SUCCESS;
  }
  if (st) return autobal_error_set(err, st, "%s", e.message);
  if (a && (st = autobal_study_rotor_campbell_write(a, p, s)))
    return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
  return AUTOBAL_SUCCESS;
}

int autobal_study_rotor_campbell_write(autobal_archive *a, const autobal_rotor_params *p,
                                       const autobal_study_rotor_campbell_summary *s) {
  const char *g = "/rotor/campbell";
  static const char *const d2[] = {"omega", "mode"}, *const d1[] = {"omega"}, *const dp[] = {"omega", "plane"},
                           *const dm[] = {"mode"}, *const dc[] = {"crossing"}, *const dk[] = {"peak"};
  autobal_rotor_stab_options so = autobal_rotor_stab_options_default(); /* every member "default" */
  const autobal_rotor_resonances *rr;
  size_t j, nw;
  int st, partial;
  char what[256];
  if (!a || !p || !s || !s->omega) return AUTOBAL_EINVAL;
  rr = &s->resonances;
  /* n_done = 0 and have_resonances = 0: a summary built by hand (complete) */
  partial = (s->n_done > 0 && s->n_done < s->n) || (s->n_done == s->n && !s->have_resonances);
  nw = s->n_done > 0 && s->n_done < s->n ? s->n_done : s->n;
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++) {
    so.member[j].kind = AUTOBAL_ROTOR_MEMBER_DEFAULT;
    so.member[j].n_angles = 0;
  }
  st = write_model(a, p, &so);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "description", "rotor-housing without balls (the unbalances drive the response; FULL inertia keeps their masses): natural frequencies, damping ratios and whirl vs omega (gyroscopic C omega), steady unbalance response");
  if (!st && partial) {
    if (nw < s->n)
      snprintf(what, sizeof what, "interrupted: the first %zu of %zu speeds of the diagram (done, requested); the "
               "resonance search did not run (no n_crossing, n_peak)", nw, s->n);
    else
      snprintf(what, sizeof what, "interrupted during the resonance search: the diagram is complete (%zu speeds), the "
               "crossings and peaks were not found (no n_crossing, n_peak)", nw);
    st = write_partial(a, g, nw, s->n, what);
  }
  if (!st) st = autobal_archive_coord(a, g, "omega", nw, s->omega, "rad/s", "spin speed");
  if (!st) st = autobal_archive_dim(a, g, "mode", 4, "mode index, by increasing frequency at each speed");
  if (!st) st = autobal_archive_dim(a, g, "plane", s->n_planes, "balancer plane index");
  if (!st) st = autobal_archive_var(a, g, "frequency", 2, d2, s->frequency, "rad/s", "damped natural frequency Im(lambda) in the fixed frame");
  if (!st) st = autobal_archive_var(a, g, "damping_ratio", 2, d2, s->damping_ratio, "1", "-Re(lambda)/|lambda|");
  if (!st) st = autobal_archive_var_int(a, g, "whirl", 2, d2, s->whirl, "1", "1 forward, -1 backward, 0 undecided");
  if (!st) st = autobal_archive_var(a, g, "amp_G", 1, d1, s->amp_G, "m", "steady unbalance response: major semi-axis of the orbit of the centre of mass");
  if (!st) st = autobal_archive_var(a, g, "amp_D", 2, dp, s->amp_D, "m", "steady unbalance response at each balancer plane");
  if (!st) st = autobal_archive_var(a, g, "natural_frequency_undamped", 1, dm, s->natural_frequency_undamped, "rad/s", "natural frequencies at rest without damping");
  if (!st) st = autobal_archive_var(a, g, "natural_frequency_damped", 1, dm, s->natural_frequency_damped, "rad/s", "damped natural frequencies at rest");
  if (!st) st = autobal_archive_var(a, g, "damping_ratio_at_rest", 1, dm, s->damping_ratio_at_rest, "1", "damping ratios at rest");
  if (partial) return st;
  if (!st) st = autobal_archive_attr_int(a, g, "n_crossing", (long)rr->n_cross);
  if (!st) st = autobal_archive_attr_int(a, g, "n_peak", (long)rr->n_peak);
  if (!st) st = autobal_archive_attr_int(a, g, "truncated", rr->truncated);
  if (!st && rr->n_cross > 0) {
    st = autobal_archive_dim(a, g, "crossing", rr->n_cross, "index of a speed where a natural frequency equals omega");
    if (!st) st = autobal_archive_var(a, g, "crossing_omega", 1, dc, rr->cross, "rad/s", "critical speed: natural frequency = omega");
    if (!st) st = autobal_archive_var_int(a, g, "crossing_mode", 1, dc, rr->cross_mode, "1", "mode index");
    if (!st) st = autobal_archive_var_int(a, g, "crossing_whirl", 1, dc, rr->cross_whirl, "1", "1 forward, -1 backward");
  }
  if (!st && rr->n_peak > 0) {
    st = autobal_archive_dim(a, g, "peak", rr->n_peak, "index of a peak of the unbalance response");
    if (!st) st = autobal_archive_var(a, g, "peak_omega", 1, dk, rr->peak, "rad/s", "unbalance-response critical speed (local maximum of amp_G)");
    if (!st) st = autobal_archive_var(a, g, "peak_amp_G", 1, dk, rr->peak_amp, "m", "amp_G at the peak");
  }
  return st;
}
