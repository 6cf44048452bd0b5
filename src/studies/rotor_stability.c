/* rotor_stability.c: the rotor stability study (`autobal rotor stability`): the balanced motion
 * (3.14) analysed by every applicable method at the rotor's speed, the critical speeds in a
 * range, and their archive layout (include/autobal/study.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/study.h"
#include "internal.h"

autobal_study_rotor_stability_options autobal_study_rotor_stability_options_default(void) {
  autobal_study_rotor_stability_options o;
  memset(&o, 0, sizeof o);
  o.stab = autobal_rotor_stab_options_default();
  o.critical_speeds = 1;
  o.omega_min = NAN;
  o.omega_max = NAN;
  o.n_omega = 400;
  o.xtol_rel = 1e-8;
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
  if (o->critical_speeds) {
    double lo = p->omega > 0 ? s->omega_min : -s->omega_max, hi = p->omega > 0 ? s->omega_max : -s->omega_min;
    st = autobal_rotor_stab_critical(h, AUTOBAL_ROTOR_PARAM_OMEGA, lo, hi, o->n_omega, o->xtol_rel, &s->critical);
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

int autobal_study_rotor_stability_write(autobal_archive *a, const autobal_rotor_params *p,
                                        const autobal_study_rotor_stability_options *opt,
                                        const autobal_study_rotor_stability_summary *s) {
  static const char *const method_names[] = {"auto", "poly", "closed", "full", "floquet"};
  static const char *const member_names[] = {"default", "symmetric", "free", "given"};
  static const char *const droot[] = {"root"}, *const dpow[] = {"power"}, *const dfull[] = {"full_root"},
                           *const dmu[] = {"multiplier"}, *const dball[] = {"ball"};
  autobal_study_rotor_stability_options def = autobal_study_rotor_stability_options_default();
  const autobal_study_rotor_stability_options *o = opt ? opt : &def;
  const autobal_rotor_stab_result *r;
  const char *g = "/rotor/stability";
  double power[AUTOBAL_ROTOR_POLY_LEN];
  char grp[64];
  size_t i, j;
  int st;
  if (!a || !p || !s) return AUTOBAL_EINVAL;
  if (o->stab.method < 0 || o->stab.method > 4) return AUTOBAL_EINVAL;
  r = &s->result;
  for (i = 0; i < AUTOBAL_ROTOR_POLY_LEN; i++) power[i] = (double)i;
  /* the model and the balanced configuration analysed in each plane (the member of the family
   * (3.14), with its given angles) */
  st = autobal_study_write_rotor_params(a, p, 0);
  for (j = 0; j < p->n_planes && j < AUTOBAL_ROTOR_MAX_PLANES && !st; j++) {
    const autobal_rotor_member *m = &o->stab.member[j];
    snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
    st = autobal_archive_attr_string(a, grp, "member", m->kind >= 0 && m->kind <= 3 ? member_names[m->kind] : "?");
    if (!st && m->n_angles > 0) st = autobal_archive_attr_double_array(a, grp, "member_angles", m->n_angles, m->angles, "rad");
  }
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "method_option", method_names[o->stab.method]);
  if (!st) st = autobal_archive_attr_double(a, g, "tol", o->stab.tol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "floquet_rtol", o->stab.floquet_rtol, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "floquet_atol", o->stab.floquet_atol, "1");
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
  if (!st && s->have_critical) {
    const char *gc = "/rotor/stability/critical";
    st = autobal_archive_group(a, gc);
    if (!st) st = autobal_archive_attr_double(a, gc, "omega_min", s->omega_min, "rad/s");
    if (!st) st = autobal_archive_attr_double(a, gc, "omega_max", s->omega_max, "rad/s");
    if (!st) st = autobal_archive_attr_int(a, gc, "n_omega", (long)s->n_omega);
    if (!st) st = write_crit(a, gc, &s->critical, "rad/s");
  }
  return st;
}
