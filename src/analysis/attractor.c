/* attractor.c: the classification of the end of a transient (include/autobal/attractor.h):
 * balanced, heavy side, fixed elsewhere, circulating (with its frequency against the natural
 * frequencies given), periodic, irregular.  Model-agnostic: plain samples in, a class out.
 *
 * May use: core (internal.h).  Nothing else. */
#include <math.h>
#include <stddef.h>

#include "autobal/attractor.h"
#include "internal.h"

#define TWO_PI 6.283185307179586476925286766559
#define PI_ 3.1415926535897932384626433832795
#define MAX_BALLS 64
#define N_PARTS 4 /* the parts of the window over which a circulation must be steady */

static const char *const class_name[AUTOBAL_ATTRACTOR_N_CLASSES] = {"unclassified", "balanced", "heavy_side", "fixed",
                                                                    "circulating",  "periodic", "irregular"};
static const char *const class_symbol[AUTOBAL_ATTRACTOR_N_CLASSES] = {"?", "#", "h", "f", "c", "p", "i"};

const char *autobal_attractor_class_name(int c) {
  return c >= 0 && c < AUTOBAL_ATTRACTOR_N_CLASSES ? class_name[c] : NULL;
}

const char *autobal_attractor_class_symbol(int c) {
  return c >= 0 && c < AUTOBAL_ATTRACTOR_N_CLASSES ? class_symbol[c] : NULL;
}

const char *autobal_attractor_legend(void) {
  return "0 unclassified, 1 balanced, 2 heavy_side, 3 fixed, 4 circulating, 5 periodic, 6 irregular";
}

autobal_attractor_options autobal_attractor_options_default(void) {
  autobal_attractor_options o;
  o.window_revs = 100.0;
  o.rest_tol = 0.05;
  o.min_turns = 2.0;
  o.rate_tol = 0.02;
  o.envelope_tol = 0.05;
  return o;
}

int autobal_attractor_options_check(const autobal_attractor_options *o, autobal_error *err) {
  int st;
  if (!o) return autobal_error_set(err, AUTOBAL_EINVAL, "attractor options: NULL");
  if ((st = autobal_check_param(err, "attractor_window_revs", o->window_revs, 0.0, 1, 1e6, 0, "")) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_check_param(err, "attractor_rest_tol", o->rest_tol, 0.0, 1, PI_, 0, "rad")) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_check_param(err, "attractor_min_turns", o->min_turns, 1.0, 0, 1e9, 0, "")) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_check_param(err, "attractor_rate_tol", o->rate_tol, 0.0, 1, 1.0, 1, "")) != AUTOBAL_SUCCESS) return st;
  return autobal_check_param(err, "attractor_envelope_tol", o->envelope_tol, 0.0, 1, 1.0, 1, "");
}

/* min and max of x[k*stride] for k in [a, b) */
static void range_of(const double *x, size_t stride, size_t a, size_t b, double *lo, double *hi) {
  size_t k;
  *lo = INFINITY, *hi = -INFINITY;
  for (k = a; k < b; k++) {
    double v = x[k * stride];
    if (v < *lo) *lo = v;
    if (v > *hi) *hi = v;
  }
}

/* The sample nearest time `target` (t increasing, n >= 1). */
static size_t nearest_sample(const double *t, size_t n, double target) {
  size_t lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    if (t[mid] < target) lo = mid;
    else hi = mid;
  }
  return fabs(t[lo] - target) <= fabs(t[hi] - target) ? lo : hi;
}

/* Two envelopes [lo1, hi1], [lo2, hi2] agree within tol times the largest magnitude. */
static int same_envelope(double lo1, double hi1, double lo2, double hi2, double tol) {
  double scale = fmax(fmax(fabs(lo1), fabs(hi1)), fmax(fabs(lo2), fabs(hi2)));
  return fabs(lo1 - lo2) <= tol * scale && fabs(hi1 - hi2) <= tol * scale;
}

int autobal_attractor_classify(const autobal_attractor_options *opt, const autobal_attractor_window *w,
                               autobal_attractor_result *r, autobal_error *err) {
  size_t n, nb, i, k, mid;
  int st;
  double t0, t1, tm, rate1[MAX_BALLS], rate2[MAX_BALLS], rate[MAX_BALLS];
  size_t part[N_PARTS + 1];
  int rest[MAX_BALLS], circ[MAX_BALLS];
  if (r) {
    r->cls = AUTOBAL_ATTRACTOR_UNCLASSIFIED;
    r->frequency = r->natural_frequency = NAN;
    r->mode = -1;
    r->n_circulating = r->n_at_rest = 0;
  }
  if (!opt || !w || !r) return autobal_error_set(err, AUTOBAL_EINVAL, "attractor classify: NULL argument");
  if ((st = autobal_attractor_options_check(opt, err)) != AUTOBAL_SUCCESS) return st;
  n = w->n, nb = w->n_balls;
  if (nb > MAX_BALLS) return autobal_error_set(err, AUTOBAL_EINVAL, "attractor classify: n_balls = %zu: allowed [0, %d]", nb, MAX_BALLS);
  if ((n && (!w->t || !w->residual)) || (n && nb && !w->psi) ||
      (nb && (!w->plane_of_ball || !w->ball_moment || (w->n_planes && (!w->unbalance_moment || !w->unbalance_angle)))) ||
      (w->n_modes && (!w->mode_frequency || !w->mode_whirl)))
    return autobal_error_set(err, AUTOBAL_EINVAL, "attractor classify: NULL array with a non-zero length");
  for (i = 0; i < nb; i++)
    if (w->plane_of_ball[i] >= w->n_planes)
      return autobal_error_set(err, AUTOBAL_EINVAL, "attractor classify: ball %zu is in plane %zu of %zu", i, w->plane_of_ball[i],
                               w->n_planes);
  for (k = 1; k < n; k++)
    if (!(w->t[k] > w->t[k - 1]))
      return autobal_error_set(err, AUTOBAL_EINVAL, "attractor classify: times not increasing at sample %zu", k);

  /* 1 balanced */
  if (w->stopped_balanced) {
    r->cls = AUTOBAL_ATTRACTOR_BALANCED;
    return AUTOBAL_SUCCESS;
  }
  if (n >= 1) {
    int bal = 1;
    for (k = 0; k < n; k++)
      if (!(w->residual[k] <= w->balance_tol)) bal = 0;
    if (bal) {
      r->cls = AUTOBAL_ATTRACTOR_BALANCED;
      return AUTOBAL_SUCCESS;
    }
  }
  r->cls = AUTOBAL_ATTRACTOR_IRREGULAR;
  if (n < 2) return AUTOBAL_SUCCESS;
  for (k = 0; k < n; k++) {
    if (!isfinite(w->residual[k]) || (w->amplitude && !isfinite(w->amplitude[k]))) return AUTOBAL_SUCCESS;
    for (i = 0; i < nb; i++)
      if (!isfinite(w->psi[k * nb + i])) return AUTOBAL_SUCCESS;
  }
  if (!isfinite(w->speed)) return AUTOBAL_SUCCESS;

  /* each ball: range, turns, rates over the two halves (split at the sample nearest the middle) */
  t0 = w->t[0], t1 = w->t[n - 1], tm = 0.5 * (t0 + t1);
  for (mid = 1; mid + 1 < n && w->t[mid] < tm; mid++) {}
  if (mid + 1 < n && fabs(w->t[mid - 1] - tm) < fabs(w->t[mid] - tm)) mid--;
  if (mid == 0) mid = 1;
  if (mid >= n) mid = n - 1;
  /* the window's quarters: between the samples nearest t0 + j (t1 - t0) / 4 (a part of no sample
   * is left out) */
  for (k = 0; k <= N_PARTS; k++) part[k] = nearest_sample(w->t, n, t0 + (t1 - t0) * (double)k / N_PARTS);
  for (i = 0; i < nb; i++) {
    double lo, hi, turns;
    range_of(w->psi + i, nb, 0, n, &lo, &hi);
    rest[i] = hi - lo <= opt->rest_tol;
    turns = (w->psi[(n - 1) * nb + i] - w->psi[i]) / TWO_PI;
    rate[i] = (w->psi[(n - 1) * nb + i] - w->psi[i]) / (t1 - t0); /* over the whole window */
    circ[i] = fabs(turns) >= opt->min_turns;
    rate1[i] = (w->psi[mid * nb + i] - w->psi[i]) / (w->t[mid] - t0);
    /* two samples: one rate */
    rate2[i] = mid < n - 1 ? (w->psi[(n - 1) * nb + i] - w->psi[mid * nb + i]) / (t1 - w->t[mid]) : rate1[i];
    r->n_at_rest += (size_t)rest[i];
    r->n_circulating += (size_t)circ[i];
  }

  /* 2, 3: every ball at rest */
  if (r->n_at_rest == nb) {
    int heavy = 1, any = 0;
    size_t j;
    for (j = 0; j < w->n_planes; j++) {
      double proj = 0.0;
      int has = 0;
      for (i = 0; i < nb; i++)
        if (w->plane_of_ball[i] == j) {
          proj += w->ball_moment[i] * cos(w->psi[(n - 1) * nb + i] - w->unbalance_angle[j]);
          has = 1;
        }
      if (!has) continue;
      if (!(w->unbalance_moment[j] > 0)) {
        heavy = 0;
        continue;
      }
      any = 1;
      if (!(proj > 0)) heavy = 0;
    }
    r->cls = heavy && any ? AUTOBAL_ATTRACTOR_HEAVY_SIDE : AUTOBAL_ATTRACTOR_FIXED;
    return AUTOBAL_SUCCESS;
  }

  /* 4 circulating: steady, one common rate */
  if (r->n_circulating) {
    int steady = 1;
    double mean = 0.0;
    size_t nc = 0;
    for (i = 0; i < nb; i++)
      if (circ[i]) { /* steady: its rate over each quarter within rate_tol of its rate over the window */
        for (k = 0; k < N_PARTS; k++) {
          size_t a = part[k], b = part[k + 1];
          double rq;
          if (b <= a) continue;
          rq = (w->psi[b * nb + i] - w->psi[a * nb + i]) / (w->t[b] - w->t[a]);
          if (!(fabs(rq - rate[i]) <= opt->rate_tol * fabs(rate[i]))) steady = 0;
        }
        mean += rate[i], nc++;
      }
    mean /= (double)nc;
    for (i = 0; i < nb && steady; i++)
      if (circ[i] && !(fabs(rate[i] - mean) <= opt->rate_tol * fabs(mean))) steady = 0;
    if (steady) {
      double nu = w->speed + mean, best = INFINITY;
      int sense = nu * w->speed > 0 ? 1 : -1; /* the whirl nu excites */
      r->cls = AUTOBAL_ATTRACTOR_CIRCULATING;
      r->frequency = nu;
      for (k = 0; k < w->n_modes; k++) {
        double d = fabs(fabs(nu) - w->mode_frequency[k]);
        if (w->mode_whirl[k] != 0 && w->mode_whirl[k] != sense) continue;
        if (!(w->mode_frequency[k] > 0) || !(d < best)) continue;
        best = d, r->mode = (int)k, r->natural_frequency = w->mode_frequency[k];
      }
      return AUTOBAL_SUCCESS;
    }
  }

  /* 5 periodic: the two halves' envelopes and the balls' mean rates agree */
  {
    double lo1, hi1, lo2, hi2, floor_rate = TWO_PI / (t1 - t0);
    int same = 1;
    range_of(w->residual, 1, 0, mid + 1, &lo1, &hi1);
    range_of(w->residual, 1, mid, n, &lo2, &hi2);
    if (!same_envelope(lo1, hi1, lo2, hi2, opt->envelope_tol)) same = 0;
    if (w->amplitude) {
      range_of(w->amplitude, 1, 0, mid + 1, &lo1, &hi1);
      range_of(w->amplitude, 1, mid, n, &lo2, &hi2);
      if (!same_envelope(lo1, hi1, lo2, hi2, opt->envelope_tol)) same = 0;
    }
    for (i = 0; i < nb && same; i++) {
      double tol = fmax(opt->rate_tol * 0.5 * (fabs(rate1[i]) + fabs(rate2[i])), floor_rate);
      if (!(fabs(rate1[i] - rate2[i]) <= tol)) same = 0;
    }
    r->cls = same ? AUTOBAL_ATTRACTOR_PERIODIC : AUTOBAL_ATTRACTOR_IRREGULAR;
  }
  return AUTOBAL_SUCCESS;
}
