/* rotor_transient_runup.c: the run-up part of the rotor transient study
 * (src/studies/rotor_transient_runup.h): keep the columns the analysis needs while the series
 * streams, analyse them after the run (autobal_runup_analyze) against the Campbell crossings,
 * fill the summary and write /rotor/runup. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/runup.h"
#include "studies/rotor_transient_runup.h"
#include "internal.h"

#define TWO_PI 6.283185307179586476925286766559

struct study_runup {
  size_t col_omega, col_amp;         /* output columns */
  size_t n_planes, col_srel[AUTOBAL_ROTOR_MAX_PLANES];
  size_t nb, *col_psi;               /* balls, their unwrapped psi columns */
  size_t n, cap;                     /* samples kept, room */
  double *t, *w, *amp, *mon, *psi;   /* [cap], [cap x nb] */
  int nomem;
};

void study_runup_free(study_runup *ru) {
  if (!ru) return;
  free(ru->col_psi);
  free(ru->t);
  free(ru->w);
  free(ru->amp);
  free(ru->mon);
  free(ru->psi);
  free(ru);
}

int study_runup_begin(const autobal_rotor *r, study_runup **out, autobal_error *err) {
  size_t k, nout = autobal_rotor_output_count(r), nb = autobal_rotor_n_balls_total(r), found_psi = 0;
  size_t found_s = 0, have_w = 0, have_a = 0;
  study_runup *ru;
  char name[64];
  const char *unit0;
  *out = NULL;
  for (k = 0; k < nout; k++)
    if (autobal_rotor_output_name(r, k, name, sizeof name, &unit0) == AUTOBAL_SUCCESS && !strcmp(name, "Omega")) have_w = 1;
  if (!have_w) return AUTOBAL_SUCCESS;
  ru = calloc(1, sizeof *ru);
  if (!ru || (nb && !(ru->col_psi = calloc(nb, sizeof *ru->col_psi)))) {
    free(ru);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  ru->nb = nb;
  ru->n_planes = autobal_rotor_n_planes(r);
  for (k = 0; k < nout; k++) {
    unsigned pl, b;
    char rest[16];
    const char *unit;
    if (autobal_rotor_output_name(r, k, name, sizeof name, &unit) != AUTOBAL_SUCCESS) continue;
    if (!strcmp(name, "Omega")) ru->col_omega = k;
    else if (!strcmp(name, "amp_G")) ru->col_amp = k, have_a = 1;
    else if (sscanf(name, "p%u_b%u_%15s", &pl, &b, rest) == 3) {
      if (!strcmp(rest, "psi") && found_psi < nb) ru->col_psi[found_psi++] = k; /* state order */
    } else if (sscanf(name, "p%u_%15s", &pl, rest) == 2 && !strcmp(rest, "s_rel") && found_s < AUTOBAL_ROTOR_MAX_PLANES)
      ru->col_srel[found_s++] = k;
  }
  if (!have_a || found_psi != nb || found_s != ru->n_planes) {
    study_runup_free(ru);
    return autobal_error_set(err, AUTOBAL_EINVAL, "run-up: the outputs lack amp_G, p<j>_s_rel or p<j>_b<i>_psi");
  }
  *out = ru;
  return AUTOBAL_SUCCESS;
}

static int grow(double **p, size_t n) {
  double *q = realloc(*p, n * sizeof *q);
  if (!q) return 1;
  *p = q;
  return 0;
}

void study_runup_sample(study_runup *ru, double t, const double *out) {
  size_t j, i;
  double m = 0.0;
  if (!ru || ru->nomem) return;
  if (ru->n == ru->cap) {
    size_t c = ru->cap ? 2 * ru->cap : 4096;
    if (grow(&ru->t, c) || grow(&ru->w, c) || grow(&ru->amp, c) || grow(&ru->mon, c) ||
        (ru->nb && grow(&ru->psi, c * ru->nb))) {
      ru->nomem = 1;
      return;
    }
    ru->cap = c;
  }
  ru->t[ru->n] = t;
  ru->w[ru->n] = out[ru->col_omega];
  ru->amp[ru->n] = out[ru->col_amp];
  for (j = 0; j < ru->n_planes; j++) /* autobal_rotor_balance_monitor: the largest over the planes */
    if (!(out[ru->col_srel[j]] <= m)) m = out[ru->col_srel[j]];
  ru->mon[ru->n] = m;
  for (i = 0; i < ru->nb; i++) ru->psi[ru->n * ru->nb + i] = out[ru->col_psi[i]];
  ru->n++;
}

void study_runup_summary_free(autobal_study_rotor_transient_summary *s) {
  if (!s) return;
  free(s->resonance_speed);
  free(s->resonance_whirl);
  free(s->passages);
  free(s->captures);
  s->resonance_speed = NULL;
  s->resonance_whirl = NULL;
  s->passages = NULL;
  s->captures = NULL;
}

/* The Campbell crossings in [0, hi], increasing, without repeats. */
static int resonances(const autobal_rotor *r, double hi, autobal_study_rotor_transient_summary *s, autobal_error *err) {
  autobal_rotor_resonances res;
  size_t k, q, n = 0;
  int st;
  if (!(hi > 0)) return AUTOBAL_SUCCESS;
  /* 400 grid points (as the stability study's search): 0.04 s for the default rotor up to 525 rad/s,
   * against 0.34 s with the Campbell study's 4000, the same four speeds to 3e-11 (measured); a
   * mode that crosses Omega twice within one grid step would be missed */
  st = autobal_rotor_resonance_speeds(autobal_rotor_get_params(r), 0.0, hi, 400, 1e-10, &res, err);
  if (st < 0) return st;
  s->resonance_speed = malloc((res.n_cross ? res.n_cross : 1) * sizeof(double));
  s->resonance_whirl = malloc((res.n_cross ? res.n_cross : 1) * sizeof(int));
  if (!s->resonance_speed || !s->resonance_whirl) return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  for (k = 0; k < res.n_cross; k++) { /* insertion by speed */
    double x = res.cross[k];
    int wh = res.cross_whirl[k];
    if (!(x > 0)) continue;
    for (q = n; q > 0 && s->resonance_speed[q - 1] > x; q--) {
      s->resonance_speed[q] = s->resonance_speed[q - 1];
      s->resonance_whirl[q] = s->resonance_whirl[q - 1];
    }
    if (q > 0 && s->resonance_speed[q - 1] == x) { /* a repeat: drop it again */
      memmove(s->resonance_speed + q, s->resonance_speed + q + 1, (n - q) * sizeof(double));
      memmove(s->resonance_whirl + q, s->resonance_whirl + q + 1, (n - q) * sizeof(int));
      continue;
    }
    s->resonance_speed[q] = x;
    s->resonance_whirl[q] = wh;
    n++;
  }
  s->n_resonances = n;
  return AUTOBAL_SUCCESS;
}

static int write_archive(autobal_archive *a, const study_runup *ru, const autobal_study_rotor_transient_options *o,
                         const autobal_study_rotor_transient_summary *s, const double *env, const double *lag,
                         const double *lag_rate) {
  const char *g = "/rotor/runup";
  const autobal_runup_result *r = &s->runup;
  size_t k, nr = s->n_resonances, np = r->n_passages, nc = r->n_captures;
  int st = autobal_archive_group(a, g);
  if (!st)
    st = autobal_archive_attr_string(a, g, "resonance_source",
                                     "Campbell crossings (natural frequency = Omega) of the rotor-housing without balls "
                                     "(autobal_rotor_resonance_speeds) in [0, (1 + capture_band) max |Omega|]");
  if (!st) st = autobal_archive_attr_double(a, g, "capture_band", o->capture_band, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "capture_time", o->capture_time, "s");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_tol", o->balance_tol, "1");
  if (!st) st = autobal_archive_attr_int(a, g, "n_resonances", (long)nr);
  if (!st) st = autobal_archive_attr_int(a, g, "n_passages", (long)np);
  if (!st) st = autobal_archive_attr_int(a, g, "n_captures", (long)nc);
  if (!st) st = autobal_archive_attr_int(a, g, "captured", nc > 0);
  if (!st) st = autobal_archive_attr_double(a, g, "t_last_passage", r->t_last_passage, "s");
  if (!st) st = autobal_archive_attr_double(a, g, "time_to_balance_after_last_passage", r->time_to_balance, "s");
  if (!st) st = autobal_archive_attr_double(a, g, "balance_delay", r->balance_delay, "s");
  if (!st) st = autobal_archive_attr_double(a, g, "envelope_max", r->envelope_max, "m");
  if (!st) st = autobal_archive_attr_double(a, g, "t_envelope_max", r->t_envelope_max, "s");
  if (!st) st = autobal_archive_attr_double(a, g, "omega_envelope_max", r->omega_envelope_max, "rad/s");
  if (!st && nr > 0) {
    double *rpm = malloc(nr * sizeof *rpm);
    int *cnt = calloc(nr, sizeof *cnt), *capd = calloc(nr, sizeof *capd);
    double *first = malloc(nr * sizeof *first);
    const char *d1[1] = {"resonance"};
    if (!rpm || !cnt || !capd || !first) st = AUTOBAL_ENOMEM;
    for (k = 0; !st && k < nr; k++) rpm[k] = s->resonance_speed[k] * 60.0 / TWO_PI, first[k] = NAN;
    for (k = 0; !st && k < np; k++) {
      cnt[s->passages[k].resonance]++;
      if (isnan(first[s->passages[k].resonance])) first[s->passages[k].resonance] = s->passages[k].t;
    }
    for (k = 0; !st && k < nc; k++) capd[s->captures[k].resonance] = 1;
    if (!st)
      st = autobal_archive_coord(a, g, "resonance", nr, s->resonance_speed, "rad/s",
                                 "resonance speed: a natural frequency of the rotor-housing equals Omega");
    if (!st) st = autobal_archive_attr_double_array(a, "/rotor/runup/resonance", "rpm", nr, rpm, "rpm");
    if (!st) st = autobal_archive_var(a, g, "resonance_rpm", 1, d1, rpm, "rpm", "resonance speed in revolutions per minute");
    if (!st)
      st = autobal_archive_var_int(a, g, "resonance_whirl", 1, d1, s->resonance_whirl, "1",
                                   "whirl of the crossing mode: +1 forward, -1 backward, 0 undecided");
    if (!st) st = autobal_archive_var_int(a, g, "passage_count", 1, d1, cnt, "1", "passages of the resonance speed");
    if (!st)
      st = autobal_archive_var(a, g, "first_passage_time", 1, d1, first, "s",
                               "time of the first passage of the resonance speed (NaN: never passed)");
    if (!st)
      st = autobal_archive_var_int(a, g, "resonance_captured", 1, d1, capd, "1",
                                   "1: |Omega| stayed within the capture band for at least capture_time");
    free(rpm);
    free(cnt);
    free(capd);
    free(first);
  }
  if (!st && np > 0 && np == r->n_passages && !r->truncated) {
    double *pt = malloc(np * sizeof *pt), *pw = malloc(np * sizeof *pw);
    int *pr = malloc(np * sizeof *pr), *pd = malloc(np * sizeof *pd);
    const char *d1[1] = {"passage"};
    if (!pt || !pw || !pr || !pd) st = AUTOBAL_ENOMEM;
    for (k = 0; !st && k < np; k++) {
      pt[k] = s->passages[k].t;
      pw[k] = s->resonance_speed[s->passages[k].resonance];
      pr[k] = (int)s->passages[k].resonance;
      pd[k] = s->passages[k].direction;
    }
    if (!st) st = autobal_archive_dim(a, g, "passage", np, "passage of a resonance speed, in time order");
    if (!st)
      st = autobal_archive_var(a, g, "passage_time", 1, d1, pt, "s",
                               "time where |Omega| passes the resonance speed (linear between samples)");
    if (!st) st = autobal_archive_var(a, g, "passage_speed", 1, d1, pw, "rad/s", "the resonance speed passed");
    if (!st) st = autobal_archive_var_int(a, g, "passage_resonance", 1, d1, pr, "1", "index of the resonance");
    if (!st) st = autobal_archive_var_int(a, g, "passage_direction", 1, d1, pd, "1", "+1 up (run-up), -1 down (coast-down)");
    free(pt);
    free(pw);
    free(pr);
    free(pd);
  }
  if (!st && nc > 0) {
    double *te = malloc(nc * sizeof *te), *tl = malloc(nc * sizeof *tl);
    int *cr = malloc(nc * sizeof *cr), *ce = malloc(nc * sizeof *ce);
    const char *d1[1] = {"capture"};
    if (!te || !tl || !cr || !ce) st = AUTOBAL_ENOMEM;
    for (k = 0; !st && k < nc; k++) {
      te[k] = s->captures[k].t_enter;
      tl[k] = s->captures[k].t_leave;
      cr[k] = (int)s->captures[k].resonance;
      ce[k] = s->captures[k].at_end;
    }
    if (!st) st = autobal_archive_dim(a, g, "capture", nc, "stay of |Omega| in the band of a resonance");
    if (!st) st = autobal_archive_var(a, g, "capture_t_enter", 1, d1, te, "s", "time |Omega| entered the band");
    if (!st)
      st = autobal_archive_var(a, g, "capture_t_leave", 1, d1, tl, "s", "time |Omega| left the band (end of the run if not)");
    if (!st) st = autobal_archive_var_int(a, g, "capture_resonance", 1, d1, cr, "1", "index of the resonance");
    if (!st) st = autobal_archive_var_int(a, g, "capture_at_end", 1, d1, ce, "1", "1: still in the band at the end");
    free(te);
    free(tl);
    free(cr);
    free(ce);
  }
  /* over the transient's time dimension (same samples: the series got every row the collector got) */
  if (!st && env) {
    const char *dt[1] = {"/rotor/transient/time"};
    st = autobal_archive_var(a, g, "envelope", 1, dt, env, "m",
                             "peak hold of amp_G over the trailing revolution (rotor angle from |Omega|)");
  }
  if (!st && env && ru->nb > 0) {
    const char *dtb[2] = {"/rotor/transient/time", "ball"};
    st = autobal_archive_dim(a, g, "ball", ru->nb, "ball in state order (plane 1 first)");
    if (!st)
      st = autobal_archive_var(a, g, "ball_lag", 2, dtb, lag, "rad",
                               "lag psi(0) - psi(t): angle the ball has fallen behind the rotor since the start");
    if (!st)
      st = autobal_archive_var(a, g, "ball_lag_rate", 2, dtb, lag_rate, "rad/s",
                               "rate of the lag averaged over the trailing revolution (-dpsi/dt)");
  }
  return st;
}

int study_runup_finish(study_runup *ru, const autobal_rotor *r, const autobal_study_rotor_transient_options *o,
                       autobal_archive *a, size_t series_rows, autobal_study_rotor_transient_summary *s,
                       autobal_error *err) {
  autobal_runup_series ser;
  autobal_runup_options ro = autobal_runup_options_default();
  autobal_runup_buffers b;
  double *env = NULL, *lag = NULL, *lag_rate = NULL, wmax = 0.0;
  size_t k, *work = NULL;
  int st;
  if (!ru) return AUTOBAL_SUCCESS;
  if (ru->nomem) return autobal_error_set(err, AUTOBAL_ENOMEM, "run-up: out of memory keeping the samples");
  s->have_runup = 1;
  if (ru->n == 0) return AUTOBAL_SUCCESS;
  for (k = 0; k < ru->n; k++) wmax = fmax(wmax, fabs(ru->w[k]));
  ro.capture_band = o->capture_band;
  ro.capture_time = o->capture_time;
  ro.balance_tol = o->balance_tol;
  if ((st = resonances(r, (1.0 + ro.capture_band) * wmax, s, err)) < 0) return st;
  ser.n = ru->n;
  ser.t = ru->t;
  ser.omega = ru->w;
  ser.amplitude = ru->amp;
  ser.monitor = ru->mon;
  ser.n_balls = ru->nb;
  ser.psi = ru->psi;
  memset(&b, 0, sizeof b);
  /* first pass: count the passages and captures */
  if ((st = autobal_runup_analyze(&ser, s->resonance_speed, s->n_resonances, &ro, &b, &s->runup, err))) return st;
  env = malloc(ru->n * sizeof *env);
  work = malloc(ru->n * sizeof *work);
  if (ru->nb) {
    lag = malloc(ru->n * ru->nb * sizeof *lag);
    lag_rate = malloc(ru->n * ru->nb * sizeof *lag_rate);
  }
  s->passages = malloc((s->runup.n_passages ? s->runup.n_passages : 1) * sizeof *s->passages);
  s->captures = malloc((s->runup.n_captures ? s->runup.n_captures : 1) * sizeof *s->captures);
  if (!env || !work || (ru->nb && (!lag || !lag_rate)) || !s->passages || !s->captures)
    st = autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  if (!st) {
    b.envelope = env;
    b.lag = lag;
    b.lag_rate = lag_rate;
    b.work = work;
    b.passages = s->passages;
    b.passage_cap = s->runup.n_passages;
    b.captures = s->captures;
    b.capture_cap = s->runup.n_captures;
    st = autobal_runup_analyze(&ser, s->resonance_speed, s->n_resonances, &ro, &b, &s->runup, err);
  }
  if (!st && a) {
    /* the datasets over the time dimension only when the series holds exactly the kept samples */
    int full = series_rows == ru->n;
    st = write_archive(a, ru, o, s, full ? env : NULL, full ? lag : NULL, full ? lag_rate : NULL);
    if (st) autobal_error_set(err, st, "%s", st == AUTOBAL_ENOMEM ? "out of memory" : autobal_archive_errmsg(a));
  }
  free(env);
  free(work);
  free(lag);
  free(lag_rate);
  return st;
}
