/* rotor_runup.c: outputs of a run-up or coast-down from a sampled series (include/autobal/runup.h):
 * the peak-hold envelope over the trailing revolution, the passages of the resonance speeds,
 * captures in a band around them, the time to balance after the last passage, the ball lag.
 *
 * May use: core (internal.h).  No model, no archive, no allocation. */
#include <math.h>
#include <string.h>

#include "autobal/runup.h"
#include "internal.h"

#define TWO_PI 6.283185307179586476925286766559

autobal_runup_options autobal_runup_options_default(void) {
  autobal_runup_options o;
  o.capture_band = 0.05;
  o.capture_time = 2.0;
  o.balance_tol = 0.01;
  return o;
}

static void result_init(autobal_runup_result *r) {
  memset(r, 0, sizeof *r);
  r->t_last_passage = r->time_to_balance = r->balance_delay = NAN;
  r->envelope_max = r->t_envelope_max = r->omega_envelope_max = NAN;
}

static int check_inputs(const autobal_runup_series *s, const double *res, size_t nres, const autobal_runup_options *o,
                        const autobal_runup_buffers *b, autobal_error *err) {
  size_t k;
  int st;
  if (!s) return autobal_error_set(err, AUTOBAL_EINVAL, "runup: series is NULL");
  if (s->n < 1) return autobal_error_set(err, AUTOBAL_EINVAL, "runup: series.n = 0 is out of range: allowed n >= 1");
  if (!s->t || !s->omega)
    return autobal_error_set(err, AUTOBAL_EINVAL, "runup: series.%s is NULL (needs %zu values)", s->t ? "omega" : "t",
                             s->n);
  for (k = 0; k < s->n; k++) {
    if (!isfinite(s->t[k]) || !isfinite(s->omega[k]))
      return autobal_error_set(err, AUTOBAL_EINVAL, "runup: series.%s[%zu] = %g is not a finite number",
                               isfinite(s->t[k]) ? "omega" : "t", k, isfinite(s->t[k]) ? s->omega[k] : s->t[k]);
    if (k > 0 && !(s->t[k] > s->t[k - 1]))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "runup: series.t is not strictly increasing: t[%zu] = %.17g s <= t[%zu] = %.17g s", k,
                               s->t[k], k - 1, s->t[k - 1]);
  }
  if (nres > 0 && !res) return autobal_error_set(err, AUTOBAL_EINVAL, "runup: resonance is NULL (n_resonance = %zu)", nres);
  for (k = 0; k < nres; k++) {
    if (!(isfinite(res[k]) && res[k] > 0))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "runup: resonance[%zu] = %g rad/s is out of range: allowed (0, inf)", k, res[k]);
    if (k > 0 && !(res[k] > res[k - 1]))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "runup: the resonance speeds are not strictly increasing: resonance[%zu] = %.17g <= "
                               "resonance[%zu] = %.17g rad/s",
                               k, res[k], k - 1, res[k - 1]);
  }
  if ((st = autobal_check_param(err, "options.capture_band", o->capture_band, 0, 1, 1, 1, ""))) return st;
  if ((st = autobal_check_param(err, "options.capture_time", o->capture_time, 0, 1, INFINITY, 1, "s"))) return st;
  if ((st = autobal_check_param(err, "options.balance_tol", o->balance_tol, 0, 1, INFINITY, 1, ""))) return st;
  if (!b) return autobal_error_set(err, AUTOBAL_EINVAL, "runup: buffers is NULL");
  if (b->envelope && !s->amplitude)
    return autobal_error_set(err, AUTOBAL_EINVAL, "runup: buffers.envelope needs series.amplitude (NULL)");
  if (b->envelope && !b->work)
    return autobal_error_set(err, AUTOBAL_EINVAL, "runup: buffers.envelope needs buffers.work (%zu entries, NULL)", s->n);
  if ((b->lag || b->lag_rate) && s->n_balls > 0 && !s->psi)
    return autobal_error_set(err, AUTOBAL_EINVAL, "runup: buffers.%s needs series.psi (%zu x %zu values, NULL)",
                             b->lag ? "lag" : "lag_rate", s->n, s->n_balls);
  if (b->passage_cap > 0 && !b->passages)
    return autobal_error_set(err, AUTOBAL_EINVAL, "runup: buffers.passages is NULL (passage_cap = %zu)", b->passage_cap);
  if (b->capture_cap > 0 && !b->captures)
    return autobal_error_set(err, AUTOBAL_EINVAL, "runup: buffers.captures is NULL (capture_cap = %zu)", b->capture_cap);
  return AUTOBAL_SUCCESS;
}

/* t where the line through (t0, v0), (t1, v1) takes the value v (v0 != v1). */
static double cross_time(double t0, double v0, double t1, double v1, double v) {
  double f = (v - v0) / (v1 - v0);
  if (f < 0) f = 0;
  if (f > 1) f = 1;
  return t0 + f * (t1 - t0);
}

/* Trailing-revolution windows: envelope (monotonic deque of indices in work) and lag rate. */
static void windows(const autobal_runup_series *s, autobal_runup_buffers *b) {
  size_t n = s->n, nb = s->n_balls, k, i, j = 0, head = 0, tail = 0;
  double span = 0.0; /* Phi_k - Phi_j */
  const double lim = TWO_PI * (1.0 + 1e-9);
  for (k = 0; k < n; k++) {
    if (k > 0) span += 0.5 * (fabs(s->omega[k - 1]) + fabs(s->omega[k])) * (s->t[k] - s->t[k - 1]);
    while (j < k && span > lim) {
      span -= 0.5 * (fabs(s->omega[j]) + fabs(s->omega[j + 1])) * (s->t[j + 1] - s->t[j]);
      j++;
    }
    if (j == k) span = 0.0; /* drop the rounding of the running sums */
    if (b->envelope) {
      /* the deque holds indices with decreasing amplitude; NaN samples never enter it */
      double a = s->amplitude[k];
      while (head < tail && b->work[head] < j) head++;
      if (!isnan(a)) {
        while (head < tail && s->amplitude[b->work[tail - 1]] <= a) tail--;
        b->work[tail++] = k;
      }
      b->envelope[k] = head < tail ? s->amplitude[b->work[head]] : NAN;
    }
    if (b->lag_rate) {
      size_t j0 = j < k ? j : (k > 0 ? k - 1 : 0);
      for (i = 0; i < nb; i++)
        b->lag_rate[k * nb + i] = k == 0 ? NAN : (s->psi[j0 * nb + i] - s->psi[k * nb + i]) / (s->t[k] - s->t[j0]);
    }
  }
}

static void passages(const autobal_runup_series *s, const double *res, size_t nres, autobal_runup_buffers *b,
                     autobal_runup_result *out) {
  size_t k, q;
  for (k = 0; k + 1 < s->n; k++) {
    double w0 = fabs(s->omega[k]), w1 = fabs(s->omega[k + 1]);
    int up = w1 > w0;
    if (w0 == w1) continue;
    for (q = 0; q < nres; q++) {
      size_t r = up ? q : nres - 1 - q; /* in the order of time within the interval */
      double wc = res[r];
      int dir = (w0 < wc && w1 >= wc) ? 1 : (w0 >= wc && w1 < wc) ? -1 : 0;
      if (!dir) continue;
      if (out->n_passages < b->passage_cap) {
        autobal_runup_passage *p = &b->passages[out->n_passages];
        p->resonance = r;
        p->t = cross_time(s->t[k], w0, s->t[k + 1], w1, wc);
        p->direction = dir;
        out->t_last_passage = p->t;
      } else {
        out->truncated = 1;
        out->t_last_passage = cross_time(s->t[k], w0, s->t[k + 1], w1, wc);
      }
      out->n_passages++;
    }
  }
}

/* t where |Omega| crosses the band [lo, hi] edge between samples k0 (one side) and k1. */
static double edge_time(const autobal_runup_series *s, size_t k0, size_t k1, double lo, double hi) {
  double w0 = fabs(s->omega[k0]), w1 = fabs(s->omega[k1]);
  double outside = (w0 < lo || w0 > hi) ? w0 : w1, edge = outside < lo ? lo : hi;
  return cross_time(s->t[k0], w0, s->t[k1], w1, edge);
}

static void captures(const autobal_runup_series *s, const double *res, size_t nres, double band, double dwell,
                     autobal_runup_buffers *b, autobal_runup_result *out) {
  size_t r, k, n = s->n;
  for (r = 0; r < nres; r++) {
    double lo = (1.0 - band) * res[r], hi = (1.0 + band) * res[r];
    k = 0;
    while (k < n) {
      size_t first, last;
      double te, tl;
      double w = fabs(s->omega[k]);
      if (!(w >= lo && w <= hi)) {
        k++;
        continue;
      }
      first = k;
      while (k + 1 < n && fabs(s->omega[k + 1]) >= lo && fabs(s->omega[k + 1]) <= hi) k++;
      last = k;
      te = first == 0 ? s->t[0] : edge_time(s, first - 1, first, lo, hi);
      tl = last == n - 1 ? s->t[n - 1] : edge_time(s, last, last + 1, lo, hi);
      if (tl - te >= dwell) {
        if (out->n_captures < b->capture_cap) {
          autobal_runup_capture *c = &b->captures[out->n_captures];
          c->resonance = r;
          c->t_enter = te;
          c->t_leave = tl;
          c->at_start = first == 0;
          c->at_end = last == n - 1;
        } else
          out->truncated = 1;
        out->n_captures++;
      }
      k++;
    }
  }
}

static void balance(const autobal_runup_series *s, double tol, autobal_runup_result *out) {
  size_t n = s->n, k, last_above = n; /* n: none */
  double t_ref = isnan(out->t_last_passage) ? s->t[0] : out->t_last_passage, tb;
  if (!s->monitor) return;
  for (k = n; k-- > 0;)
    if (!(s->monitor[k] < tol)) {
      last_above = k;
      break;
    }
  if (last_above == n - 1) return; /* not below at the end */
  if (last_above == n) tb = s->t[0];
  else if (isnan(s->monitor[last_above])) tb = s->t[last_above + 1];
  else
    tb = cross_time(s->t[last_above], s->monitor[last_above], s->t[last_above + 1], s->monitor[last_above + 1], tol);
  out->time_to_balance = tb > t_ref ? tb : t_ref;
  out->balance_delay = out->time_to_balance - t_ref;
}

int autobal_runup_analyze(const autobal_runup_series *series, const double *resonance, size_t n_resonance,
                          const autobal_runup_options *opt, autobal_runup_buffers *buf, autobal_runup_result *out,
                          autobal_error *err) {
  autobal_runup_options def = autobal_runup_options_default();
  const autobal_runup_options *o = opt ? opt : &def;
  size_t k, i;
  int st;
  if (!out) return autobal_error_set(err, AUTOBAL_EINVAL, "runup: out is NULL");
  result_init(out);
  if ((st = check_inputs(series, resonance, n_resonance, o, buf, err))) return st;
  if (buf->lag)
    for (k = 0; k < series->n; k++)
      for (i = 0; i < series->n_balls; i++)
        buf->lag[k * series->n_balls + i] = series->psi[i] - series->psi[k * series->n_balls + i];
  if (buf->envelope || buf->lag_rate) windows(series, buf);
  if (series->amplitude)
    for (k = 0; k < series->n; k++)
      if (series->amplitude[k] > out->envelope_max || (isnan(out->envelope_max) && !isnan(series->amplitude[k]))) {
        out->envelope_max = series->amplitude[k];
        out->t_envelope_max = series->t[k];
        out->omega_envelope_max = series->omega[k];
      }
  passages(series, resonance, n_resonance, buf, out);
  captures(series, resonance, n_resonance, o->capture_band, o->capture_time, buf, out);
  balance(series, o->balance_tol, out);
  autobal_error_clear(err);
  return AUTOBAL_SUCCESS;
}
