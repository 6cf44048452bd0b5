/* pendulum_critical.c: the pendulum critical-speed study (`autobal pendulum critical`):
 * critical speeds at the given parameters (undamped from (10), damped from (6)), the curves
 * R_wj(R_m) of figure 2, the paper's closed forms (13), (14), (16)-(18), and their archive
 * layout (include/autobal/study.h). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/study.h"
#include "internal.h"

autobal_study_pendulum_critical_options autobal_study_pendulum_critical_options_default(void) {
  autobal_study_pendulum_critical_options o;
  memset(&o, 0, sizeof o);
  o.Rm_min = 0.001;
  o.Rm_max = 0.499;
  o.n_Rm = 499;
  o.Rw_min = 0.0;
  o.Rw_max = 6.0;
  o.n_sweep = 3000;
  return o;
}

void autobal_study_pendulum_critical_summary_free(autobal_study_pendulum_critical_summary *s) {
  if (!s) return;
  free(s->R_m); /* one block: R_m, R_w_k0, R_w_k1 and the five formula rows */
  s->R_m = s->R_w_k0 = s->R_w_k1 = NULL;
  s->curve_eq14_R_w2_k0 = s->curve_eq14_R_w3_k0 = s->curve_eq16_R_w1_k1 = s->curve_eq17_R_w1_k1 = s->curve_eq18_R_w23_k1 = NULL;
}

/* The workspace's cancel hook calling the study's progress callback (fraction: the damped
 * search is the first half, the curves the second). */
typedef struct progress_hook {
  const autobal_study_pendulum_critical_options *o;
  double fraction;
} progress_hook;

static int progress_cancel(void *user) {
  progress_hook *h = (progress_hook *)user;
  return h->o->progress && h->o->progress(h->fraction, h->o->progress_user) != 0;
}

int autobal_study_pendulum_critical(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys,
                                    const autobal_study_pendulum_critical_options *opt, autobal_archive *a,
                                    autobal_study_pendulum_critical_summary *summary, autobal_error *err) {
  autobal_study_pendulum_critical_options def = autobal_study_pendulum_critical_options_default();
  const autobal_study_pendulum_critical_options *o = opt ? opt : &def;
  autobal_study_pendulum_critical_summary *s = summary;
  autobal_pendulum_workspace *ws = NULL;
  autobal_error e;
  double *block, rm1;
  size_t i, nrm;
  int st, cancelled = 0;
  progress_hook ph;
  autobal_error_clear(err);
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(s, 0, sizeof *s);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  if (!(o->Rm_min > 0 && o->Rm_min < o->Rm_max && o->Rm_max < 0.5))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: need 0 < Rm_min < Rm_max < 0.5, got Rm_min = %g, Rm_max = %g",
                             o->Rm_min, o->Rm_max);
  if (o->n_Rm < 2 || o->n_Rm > 1000000)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_Rm = %zu is out of range: allowed [2, 1000000]", o->n_Rm);
  if (!(o->Rw_min >= 0 && o->Rw_min < o->Rw_max && o->Rw_max <= 1e4))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: need 0 <= Rw_min < Rw_max <= 1e4, got Rw_min = %g, Rw_max = %g",
                             o->Rw_min, o->Rw_max);
  if (o->n_sweep < 2 || o->n_sweep > 100000000)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_sweep = %zu is out of range: allowed [2, 1e8]", o->n_sweep);
  s->k = autobal_pendulum_k(p);
  nrm = o->n_Rm;
  s->n_Rm = nrm;
  ws = autobal_pendulum_workspace_alloc();
  block = malloc(12 * nrm * sizeof *block);
  if (!ws || !block) {
    autobal_pendulum_workspace_free(ws);
    free(block);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  s->R_m = block;
  s->R_w_k0 = block + nrm;
  s->R_w_k1 = block + 4 * nrm;
  s->curve_eq14_R_w2_k0 = block + 7 * nrm;
  s->curve_eq14_R_w3_k0 = block + 8 * nrm;
  s->curve_eq16_R_w1_k1 = block + 9 * nrm;
  s->curve_eq17_R_w1_k1 = block + 10 * nrm;
  s->curve_eq18_R_w23_k1 = block + 11 * nrm;
  ph.o = o;
  ph.fraction = 0.0;
  if (o->progress) autobal_pendulum_workspace_set_cancel(ws, progress_cancel, &ph);
  st = autobal_pendulum_critical_speeds(ws, p->R_m, s->k, &s->undamped);
  s->have_damped = p->H > 0 || p->h > 0;
  if (!st && s->have_damped) {
    st = autobal_pendulum_critical_speeds_damped(ws, p, o->Rw_min, o->Rw_max, o->n_sweep, &s->damped);
    if (st == AUTOBAL_ECANCELLED) {
      s->have_damped = 0;
      s->damped_cancelled = 1;
      cancelled = 1;
      st = AUTOBAL_SUCCESS;
    }
    if (st == AUTOBAL_WARNING) {
      /* the list was full: the data are valid up to its last entry (archived with the flag) */
      s->damped_truncated_warning = 1;
      snprintf(s->warning_message, sizeof s->warning_message, "%s", autobal_pendulum_errmsg(ws));
      st = AUTOBAL_SUCCESS;
    }
  }
  if (!st) st = autobal_pendulum_critical_speeds(ws, p->R_m, 0.0, &s->undamped_k0);
  if (!st) st = autobal_pendulum_critical_speeds(ws, p->R_m, 1.0, &s->undamped_k1);
  if (st) {
    autobal_error_set(err, st, "%s", autobal_pendulum_errmsg(ws));
    autobal_pendulum_workspace_free(ws);
    return st;
  }
  s->eq13_R_w1_k0 = s->eq14_R_w2_k0_small = s->eq14_R_w3_k0_small = NAN;
  s->eq14_R_w2_k0_large = s->eq14_R_w3_k0_large = NAN;
  s->eq16_R_w1_k1 = s->eq16_u = s->eq17_R_w1_k1_series = s->eq18_R_w23_k1 = NAN;
  s->R_m1 = s->R_w_at_R_m1 = NAN;
  autobal_pendulum_rw1_k0(p->R_m, &s->eq13_R_w1_k0, NULL);
  autobal_pendulum_rw23_k0_series_small(p->R_m, &s->eq14_R_w2_k0_small, &s->eq14_R_w3_k0_small, NULL);
  if (p->R_m < 0.25) autobal_pendulum_rw23_k0_series_large(p->R_m, &s->eq14_R_w2_k0_large, &s->eq14_R_w3_k0_large, NULL);
  autobal_pendulum_rw1_k1(p->R_m, &s->eq16_R_w1_k1, &s->eq16_u, NULL);
  autobal_pendulum_rw1_k1_series(p->R_m, &s->eq17_R_w1_k1_series, NULL);
  if (p->R_m < 0.25) autobal_pendulum_rw23_k1(p->R_m, &s->eq18_R_w23_k1, NULL);
  autobal_error_clear(&e);
  if ((st = autobal_pendulum_rm1(&s->R_m1, &s->R_w_at_R_m1, &e))) {
    autobal_error_set(err, st, "%s", e.message);
    autobal_pendulum_workspace_free(ws);
    return st;
  }
  rm1 = s->R_m1;
  /* curves vs R_m for k = 0 and k = 1, a block of R_m points at a time (each point is
   * independent), with progress; none after a cancellation of the damped search */
  for (i = 0; i < nrm; i++) s->R_m[i] = o->Rm_min + (o->Rm_max - o->Rm_min) * (double)i / (double)(nrm - 1);
  while (!cancelled && s->n_Rm_done < nrm) {
    size_t i0 = s->n_Rm_done, r = nrm - i0 < 16 ? nrm - i0 : 16;
    ph.fraction = 0.5 + 0.5 * (double)i0 / (double)nrm;
    st = autobal_pendulum_critical_curves(ws, 0.0, s->R_m + i0, r, 3, s->R_w_k0 + 3 * i0);
    if (!st) st = autobal_pendulum_critical_curves(ws, 1.0, s->R_m + i0, r, 3, s->R_w_k1 + 3 * i0);
    if (st == AUTOBAL_ECANCELLED) {
      cancelled = 1;
      break; /* the block in progress is dropped */
    }
    if (st) {
      autobal_error_set(err, st, "%s", autobal_pendulum_errmsg(ws));
      autobal_pendulum_workspace_free(ws);
      return st;
    }
    s->n_Rm_done += r;
  }
  autobal_pendulum_workspace_free(ws);
  s->cancelled = cancelled;
  /* the paper's formulas along the grid: (14) small, (14) large (R_w2, R_w3), (16), (17), (18)
   * (at the points of the curves computed: all unless cancelled) */
  for (i = 0; i < s->n_Rm_done; i++) {
    double rm = s->R_m[i], a2 = NAN, a3 = NAN, b2 = NAN, b3 = NAN, f16 = NAN, f17 = NAN, f18 = NAN;
    autobal_pendulum_rw23_k0_series_small(rm, &a2, &a3, NULL);
    if (rm < 0.25) autobal_pendulum_rw23_k0_series_large(rm, &b2, &b3, NULL);
    autobal_pendulum_rw1_k1(rm, &f16, NULL, NULL);
    autobal_pendulum_rw1_k1_series(rm, &f17, NULL);
    if (rm > rm1 && rm < 0.25) autobal_pendulum_rw23_k1(rm, &f18, NULL);
    s->curve_eq14_R_w2_k0[i] = rm < 0.05 ? a2 : b2;
    s->curve_eq14_R_w3_k0[i] = rm < 0.05 ? a3 : b3;
    s->curve_eq16_R_w1_k1[i] = f16;
    s->curve_eq17_R_w1_k1[i] = f17;
    s->curve_eq18_R_w23_k1[i] = f18;
  }
  if (a && (st = autobal_study_pendulum_critical_write(a, p, phys, s)))
    return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
  if (cancelled)
    return autobal_error_set(err, AUTOBAL_ECANCELLED, "cancelled by the progress callback %s",
                             s->damped_cancelled ? "during the damped search" : "during the curves");
  return AUTOBAL_SUCCESS;
}

static int write_crit_set(autobal_archive *a, const char *g, const char *prefix, const autobal_pendulum_crit_set *s) {
  char dimc[64], dimi[64], name[96];
  const char *dc[1], *di[1];
  int st = 0, kinds[AUTOBAL_PENDULUM_MAX_CRIT];
  size_t i;
  snprintf(dimc, sizeof dimc, "%s_critical", prefix);
  snprintf(dimi, sizeof dimi, "%s_interval", prefix);
  dc[0] = dimc;
  di[0] = dimi;
  snprintf(name, sizeof name, "n_%s", dimc);
  st = autobal_archive_attr_int(a, g, name, (long)s->n);
  /* 1: the list was full (the damped search): the set covers R_w up to its last critical speed only */
  snprintf(name, sizeof name, "%s_truncated", prefix);
  if (!st) st = autobal_archive_attr_int(a, g, name, s->truncated);
  /* 1: two critical speeds within one ulp of W = R_w^2 (reported as equal values) */
  snprintf(name, sizeof name, "%s_unresolved", prefix);
  if (!st) st = autobal_archive_attr_int(a, g, name, s->unresolved);
  if (!st && s->n > 0) {
    for (i = 0; i < s->n; i++) kinds[i] = s->kind[i];
    st = autobal_archive_dim(a, g, dimc, s->n, "index of a critical speed");
    snprintf(name, sizeof name, "%s_R_w", prefix);
    if (!st) st = autobal_archive_var(a, g, name, 1, dc, s->R_w, "1", "critical speed R_w = omega/omega0");
    snprintf(name, sizeof name, "%s_kind", prefix);
    if (!st) st = autobal_archive_var_int(a, g, name, 1, dc, kinds, "1", "1: stability gained above, -1: lost above, 0: touch (no change)");
  }
  if (!st && s->n_stable > 0) {
    st = autobal_archive_dim(a, g, dimi, s->n_stable, "index of a stable speed interval");
    snprintf(name, sizeof name, "%s_stable_lo", prefix);
    if (!st) st = autobal_archive_var(a, g, name, 1, di, s->stable_lo, "1", "lower end of a stable R_w interval");
    snprintf(name, sizeof name, "%s_stable_hi", prefix);
    if (!st) st = autobal_archive_var(a, g, name, 1, di, s->stable_hi, "1", "upper end of a stable R_w interval (inf: unbounded; for the damped search, Rw_max: stable to the end of the searched range)");
  }
  return st;
}

int autobal_study_pendulum_critical_write(autobal_archive *a, const autobal_pendulum_params *p,
                                          const autobal_pendulum_physical *phys,
                                          const autobal_study_pendulum_critical_summary *s) {
  const char *g = "/pendulum/critical", *gc = "/pendulum/critical/curves";
  static const char *const dims2[] = {"R_m", "branch"};
  static const char *const dims1[] = {"R_m"};
  size_t nrm;
  int st, partial;
  if (!a || !p || !s || !s->R_m) return AUTOBAL_EINVAL;
  /* not cancelled: complete (also a summary built by hand, n_Rm_done = 0) */
  partial = s->cancelled || s->damped_cancelled;
  nrm = partial ? s->n_Rm_done : s->n_Rm;
  st = autobal_study_write_pendulum_params(a, p, phys);
  if (!st) st = autobal_archive_group(a, g);
  if (!st && partial) {
    char what[300];
    snprintf(what, sizeof what, "interrupted: %s; the first %zu of %zu points of the curves (done, requested)",
             s->damped_cancelled ? "the damped search did not finish (no damped_*)" : "the critical speeds at R_m are complete",
             nrm, s->n_Rm);
    st = autobal_archive_attr_int(a, g, "partial", 1);
    if (!st) st = autobal_archive_attr_int(a, g, "done", (long)nrm);
    if (!st) st = autobal_archive_attr_int(a, g, "requested", (long)s->n_Rm);
    if (!st) st = autobal_archive_attr_string(a, g, "partial_what", what);
  }
  if (!st) st = autobal_archive_attr_string(a, g, "description", "critical speeds of the undamped balancer (H = h = 0) at the R_m and k of /pendulum, from the discriminant of (10); damped_* at the given H, h from (6)");
  if (!st) st = autobal_archive_attr_double(a, g, "undamped_resolution_W", DBL_EPSILON, "1");
  if (!st) st = write_crit_set(a, g, "undamped", &s->undamped);
  if (!st && s->have_damped) st = write_crit_set(a, g, "damped", &s->damped);
  if (!st) st = write_crit_set(a, g, "undamped_k0", &s->undamped_k0);
  if (!st) st = write_crit_set(a, g, "undamped_k1", &s->undamped_k1);
  if (!st) st = autobal_archive_attr_double(a, g, "R_m1", s->R_m1, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "R_w_at_R_m1", s->R_w_at_R_m1, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "eq13_R_w1_k0", s->eq13_R_w1_k0, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "eq14_R_w2_k0_small", s->eq14_R_w2_k0_small, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "eq14_R_w3_k0_small", s->eq14_R_w3_k0_small, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "eq14_R_w2_k0_large", s->eq14_R_w2_k0_large, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "eq14_R_w3_k0_large", s->eq14_R_w3_k0_large, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "eq16_R_w1_k1", s->eq16_R_w1_k1, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "eq17_R_w1_k1_series", s->eq17_R_w1_k1_series, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "eq18_R_w23_k1", s->eq18_R_w23_k1, "1");
  if (!st && nrm == 0) return st; /* interrupted before the curves */
  if (!st) st = autobal_archive_group(a, gc);
  if (!st) st = autobal_archive_attr_string(a, gc, "description", "critical-speed curves R_wj(R_m) of the undamped balancer (figure 2): region A is R_w > R_w3(R_m, k=0); region B is R_w1(R_m, k=1) < R_w < R_w2(R_m, k=0); for R_m >= 0.25 the region stable for every unbalance is R_w > R_w1(R_m, k=1)");
  if (!st) st = autobal_archive_coord(a, gc, "R_m", nrm, s->R_m, "1", "mass ratio m/(M + 2m)");
  if (!st) st = autobal_archive_dim(a, gc, "branch", 3, "critical speed index j-1 (R_w1, R_w2, R_w3)");
  if (!st) st = autobal_archive_var(a, gc, "R_w_k0", 2, dims2, s->R_w_k0, "1", "critical speeds R_wj(R_m, k=0), NaN where the branch does not exist");
  if (!st) st = autobal_archive_var(a, gc, "R_w_k1", 2, dims2, s->R_w_k1, "1", "critical speeds R_wj(R_m, k=1), NaN where the branch does not exist");
  if (!st) st = autobal_archive_var(a, gc, "eq14_R_w2_k0", 1, dims1, s->curve_eq14_R_w2_k0, "1", "series (14) for R_w2(R_m, 0) (first form below R_m = 0.05, second above)");
  if (!st) st = autobal_archive_var(a, gc, "eq14_R_w3_k0", 1, dims1, s->curve_eq14_R_w3_k0, "1", "series (14) for R_w3(R_m, 0)");
  if (!st) st = autobal_archive_var(a, gc, "eq16_R_w1_k1", 1, dims1, s->curve_eq16_R_w1_k1, "1", "closed form (16) for R_w1(R_m, 1)");
  if (!st) st = autobal_archive_var(a, gc, "eq17_R_w1_k1", 1, dims1, s->curve_eq17_R_w1_k1, "1", "series (17) for R_w1(R_m, 1)");
  if (!st) st = autobal_archive_var(a, gc, "eq18_R_w23_k1", 1, dims1, s->curve_eq18_R_w23_k1, "1", "closed form (18) for R_w2/3(R_m, 1), for R_m^(1) < R_m < 0.25");
  return st;
}
