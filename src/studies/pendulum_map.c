/* pendulum_map.c: the pendulum stability-map study (`autobal pendulum map`): the verdict of the
 * main motion over a grid of (R_m, R_w), for one unbalance or every one, and its archive layout
 * (include/autobal/study.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "autobal/study.h"
#include "internal.h"

static double now_seconds(void) {
  struct timespec ts;
  if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) return 0.0;
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

autobal_study_pendulum_map_options autobal_study_pendulum_map_options_default(void) {
  autobal_study_pendulum_map_options o;
  memset(&o, 0, sizeof o);
  o.Rm_min = 0.005;
  o.Rm_max = 0.495;
  o.n_Rm = 200;
  o.Rw_min = 0.05;
  o.Rw_max = 5.0;
  o.n_Rw = 200;
  o.n_k = 65;
  return o;
}

void autobal_study_pendulum_map_summary_free(autobal_study_pendulum_map_summary *s) {
  if (!s) return;
  free(s->R_m);
  free(s->R_w);
  free(s->k);
  free(s->verdict);
  free(s->max_real);
  s->R_m = s->R_w = s->k = s->max_real = NULL;
  s->verdict = NULL;
}

int autobal_study_pendulum_map(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys,
                               const autobal_study_pendulum_map_options *opt, autobal_archive *a,
                               autobal_study_pendulum_map_summary *summary, autobal_error *err) {
  autobal_study_pendulum_map_options def = autobal_study_pendulum_map_options_default();
  const autobal_study_pendulum_map_options *o = opt ? opt : &def;
  autobal_study_pendulum_map_summary *s = summary;
  autobal_pendulum_map_spec spec;
  signed char *v = NULL;
  size_t i, n;
  int st;
  autobal_error_clear(err);
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "summary: NULL");
  memset(s, 0, sizeof *s);
  if (!p) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters: NULL");
  if (!(o->Rm_min > 0 && o->Rm_min <= o->Rm_max && o->Rm_max < 0.5))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: need 0 < Rm_min <= Rm_max < 0.5, got Rm_min = %g, Rm_max = %g",
                             o->Rm_min, o->Rm_max);
  if (!(o->Rw_min >= 0 && o->Rw_min <= o->Rw_max && o->Rw_max <= 1e4))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: need 0 <= Rw_min <= Rw_max <= 1e4, got Rw_min = %g, Rw_max = %g",
                             o->Rw_min, o->Rw_max);
  if (o->n_Rm < 1 || o->n_Rm > 100000)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_Rm = %zu is out of range: allowed [1, 100000]", o->n_Rm);
  if (o->n_Rw < 1 || o->n_Rw > 100000)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_Rw = %zu is out of range: allowed [1, 100000]", o->n_Rw);
  if (o->every_unbalance && (o->n_k < 2 || o->n_k > 100000))
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: n_k = %zu is out of range: allowed [2, 100000]", o->n_k);
  if (o->threads < 0 || o->threads > 1024)
    return autobal_error_set(err, AUTOBAL_EINVAL, "options: threads = %d is out of range: allowed [0, 1024]", o->threads);
  s->n_Rm = o->n_Rm;
  s->n_Rw = o->n_Rw;
  s->every_unbalance = o->every_unbalance != 0;
  s->n_k = o->every_unbalance ? o->n_k : 1;
  n = s->n_Rm * s->n_Rw;
  s->R_m = malloc(s->n_Rm * sizeof *s->R_m);
  s->R_w = malloc(s->n_Rw * sizeof *s->R_w);
  s->k = malloc(s->n_k * sizeof *s->k);
  s->verdict = malloc(n * sizeof *s->verdict);
  v = malloc(n);
  if (o->max_real) s->max_real = malloc(n * sizeof *s->max_real);
  if (!s->R_m || !s->R_w || !s->k || !s->verdict || !v || (o->max_real && !s->max_real)) {
    free(v);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  for (i = 0; i < s->n_Rm; i++)
    s->R_m[i] = s->n_Rm == 1 ? o->Rm_min : o->Rm_min + (o->Rm_max - o->Rm_min) * (double)i / (double)(s->n_Rm - 1);
  for (i = 0; i < s->n_Rw; i++)
    s->R_w[i] = s->n_Rw == 1 ? o->Rw_min : o->Rw_min + (o->Rw_max - o->Rw_min) * (double)i / (double)(s->n_Rw - 1);
  if (o->every_unbalance)
    for (i = 0; i < s->n_k; i++) s->k[i] = (double)i / (double)(s->n_k - 1);
  else
    s->k[0] = autobal_pendulum_k(p);
  memset(&spec, 0, sizeof spec);
  spec.R_m = s->R_m;
  spec.n_Rm = s->n_Rm;
  spec.R_w = s->R_w;
  spec.n_Rw = s->n_Rw;
  spec.H = p->H;
  spec.h = p->h;
  spec.k = s->k;
  spec.n_k = s->n_k;
  spec.n_threads = o->threads;
  {
    /* in blocks of rows, about 0.25-1 s each (every point is independent: the blocks change
     * nothing), with progress and cancellation after each */
    size_t rows = 1;
    int cancelled = 0;
    while (s->n_Rm_done < s->n_Rm && !cancelled) {
      size_t r = s->n_Rm - s->n_Rm_done < rows ? s->n_Rm - s->n_Rm_done : rows, off = s->n_Rm_done * s->n_Rw;
      double t0 = now_seconds(), dt;
      spec.R_m = s->R_m + s->n_Rm_done;
      spec.n_Rm = r;
      st = autobal_pendulum_map(&spec, v + off, s->max_real ? s->max_real + off : NULL, err);
      if (st) {
        free(v);
        return st;
      }
      s->n_Rm_done += r;
      dt = now_seconds() - t0;
      if (dt < 0.25 && rows < ((size_t)1 << 20)) rows *= 2;
      else if (dt > 1.0 && rows > 1) rows /= 2;
      if (o->progress && o->progress((double)s->n_Rm_done / (double)s->n_Rm, o->progress_user)) cancelled = 1;
    }
    n = s->n_Rm_done * s->n_Rw;
    for (i = 0; i < n; i++) {
      s->verdict[i] = v[i];
      s->n_stable += v[i] > 0;
    }
    free(v);
    if (a && (st = autobal_study_pendulum_map_write(a, p, phys, s)))
      return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
    if (s->n_Rm_done < s->n_Rm)
      return autobal_error_set(err, AUTOBAL_ECANCELLED, "cancelled by the progress callback after %zu of %zu rows",
                               s->n_Rm_done, s->n_Rm);
  }
  return AUTOBAL_SUCCESS;
}

int autobal_study_pendulum_map_write(autobal_archive *a, const autobal_pendulum_params *p,
                                     const autobal_pendulum_physical *phys,
                                     const autobal_study_pendulum_map_summary *s) {
  const char *g = "/pendulum/map";
  static const char *const dims[] = {"R_m", "R_w"};
  static const char *const dim_rw[] = {"R_w"};
  int st, every;
  size_t nr;
  if (!a || !p || !s || !s->R_m) return AUTOBAL_EINVAL;
  every = s->every_unbalance;
  nr = s->n_Rm_done > 0 && s->n_Rm_done < s->n_Rm ? s->n_Rm_done : s->n_Rm; /* 0: a summary built by hand */
  st = autobal_study_write_pendulum_params(a, p, phys);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "criterion", (p->H > 0 || p->h > 0) ? "Routh-Hurwitz sign test on the characteristic polynomial (6)" : "undamped: all roots x = lambda^2 of (10) real and <= 0");
  if (!st) st = autobal_archive_attr_int(a, g, "every_unbalance", every);
  if (!st) st = autobal_archive_attr_double_array(a, g, "k_values", s->n_k, s->k, "1");
  if (!st && nr < s->n_Rm) {
    char what[200];
    snprintf(what, sizeof what, "interrupted: the first %zu of %zu rows (R_m values; done, requested)", nr, s->n_Rm);
    st = autobal_archive_attr_int(a, g, "partial", 1);
    if (!st) st = autobal_archive_attr_int(a, g, "done", (long)nr);
    if (!st) st = autobal_archive_attr_int(a, g, "requested", (long)s->n_Rm);
    if (!st) st = autobal_archive_attr_string(a, g, "partial_what", what);
  }
  if (!st) st = autobal_archive_coord(a, g, "R_m", nr, s->R_m, "1", "mass ratio m/(M + 2m)");
  if (!st) st = autobal_archive_coord(a, g, "R_w", s->n_Rw, s->R_w, "1", "rotor speed omega/omega0");
  /* the design point of the configuration ([pendulum]), for marking on the map */
  if (!st) st = autobal_archive_attr_double(a, g, "design_R_m", p->R_m, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "design_R_w", p->R_w, "1");
  if (!st && phys) { /* the R_w axis in physical speed: omega = R_w omega0 */
    double *om = malloc(s->n_Rw * sizeof *om), w0 = sqrt(phys->c / (phys->M + 2.0 * phys->m));
    size_t q;
    if (!om) {
      st = AUTOBAL_ENOMEM;
    } else {
      for (q = 0; q < s->n_Rw; q++) om[q] = s->R_w[q] * w0;
      st = autobal_archive_var(a, g, "omega", 1, dim_rw, om, "rad/s",
                               "rotor speed omega = R_w omega0 of the configuration's physical set");
      free(om);
    }
  }
  if (!st) st = autobal_archive_var_int(a, g, "verdict", 2, dims, s->verdict, "1", every ? "stability of the main motion for every k in k_values: 1 stable, 0 marginal, -1 unstable" : "stability of the main motion (4): 1 stable, 0 marginal, -1 unstable");
  if (!st && s->max_real) st = autobal_archive_var(a, g, "max_real", 2, dims, s->max_real, "1", "largest real part of the roots of (6) (over k_values)");
  return st;
}
