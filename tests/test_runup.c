/* test_runup.c: autobal_runup_analyze (include/autobal/runup.h) on hand-made series whose
 * answers are known in closed form: a linear ramp crosses w_c at t = w_c/a and stays in the band
 * (1 -/+ b) w_c for 2 b w_c/a; a coast-down, a dip (up, down, up), a speed that stops exactly at a
 * resonance, a negative speed; the peak hold of a single spike lasts exactly one revolution (p + 1
 * samples at p samples per revolution at constant speed; t_k^2 - t_m^2 <= 4 pi/a on a ramp from
 * rest); the envelope of a random series against a brute-force maximum over windows computed
 * independently; a quadratic lag psi = psi0 - c t^2 and its revolution average c (2t - T); the
 * time to balance of a linear monitor; truncated lists; every bad input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/runup.h"
#include "check.h"

#define TWO_PI 6.283185307179586476925286766559
#define NMAX 40001

static double t_[NMAX], om_[NMAX], amp_[NMAX], mon_[NMAX], env_[NMAX], psi_[2 * NMAX], lag_[2 * NMAX],
    lrate_[2 * NMAX];
static size_t work_[NMAX];
static autobal_runup_passage pass_[64];
static autobal_runup_capture cap_[64];

static autobal_runup_buffers buffers(void) {
  autobal_runup_buffers b;
  memset(&b, 0, sizeof b);
  b.envelope = env_;
  b.lag = lag_;
  b.lag_rate = lrate_;
  b.work = work_;
  b.passages = pass_;
  b.passage_cap = 64;
  b.captures = cap_;
  b.capture_cap = 64;
  return b;
}

static autobal_runup_series series(size_t n, size_t nb) {
  autobal_runup_series s;
  s.n = n;
  s.t = t_;
  s.omega = om_;
  s.amplitude = amp_;
  s.monitor = mon_;
  s.n_balls = nb;
  s.psi = psi_;
  return s;
}

/* a linear ramp Omega = w0 + a t on t_k = k dt */
static void ramp(size_t n, double dt, double w0, double a) {
  size_t k;
  for (k = 0; k < n; k++) {
    t_[k] = (double)k * dt;
    om_[k] = w0 + a * t_[k];
    amp_[k] = 0.0;
    mon_[k] = 1.0;
  }
}

static void test_ramp(void) {
  const double a = 25.0, res[3] = {157.3, 215.1, 404.6}, dt = 0.01;
  size_t n = 2001, q;
  autobal_runup_series s = series(n, 0);
  autobal_runup_buffers b = buffers();
  autobal_runup_options o = autobal_runup_options_default();
  autobal_runup_result r;
  autobal_error e;
  char what[128];
  ramp(n, dt, 0.0, a);
  o.capture_time = 0.6; /* the band of 157.3 lasts 2 0.05 157.3/25 = 0.6292 s */
  CHECK_STATUS("ramp 0 -> 500 rad/s over 20 s", autobal_runup_analyze(&s, res, 3, &o, &b, &r, &e), AUTOBAL_SUCCESS);
  CHECK("three passages, not truncated", r.n_passages == 3 && !r.truncated);
  for (q = 0; q < 3 && q < r.n_passages; q++) {
    snprintf(what, sizeof what, "passage %zu: t = w_c/a = %g s (linear interpolation is exact)", q, res[q] / a);
    CHECK_CLOSE(what, pass_[q].t, res[q] / a, 1e-13, 0);
    CHECK("  resonance index and direction up", pass_[q].resonance == q && pass_[q].direction == 1);
  }
  CHECK_CLOSE("t_last_passage = 404.6/25", r.t_last_passage, 404.6 / a, 1e-13, 0);
  /* bands: 157.3: 0.6292 s >= 0.6: a capture; 215.1: 0.8604 s; 404.6: 1.6184 s */
  CHECK("three captures (every band lasts >= 0.6 s)", r.n_captures == 3);
  CHECK_CLOSE("capture 0: t_enter = 0.95 w_c/a", cap_[0].t_enter, 0.95 * res[0] / a, 1e-13, 0);
  CHECK_CLOSE("capture 0: t_leave = 1.05 w_c/a", cap_[0].t_leave, 1.05 * res[0] / a, 1e-13, 0);
  CHECK("capture 0: not at the start or the end", !cap_[0].at_start && !cap_[0].at_end);
  o.capture_time = 0.63; /* just above 0.6292: only the two higher bands */
  autobal_runup_analyze(&s, res, 3, &o, &b, &r, &e);
  CHECK("capture_time 0.63 s: two captures (0.8604 and 1.6184 s), of resonances 1 and 2",
        r.n_captures == 2 && cap_[0].resonance == 1 && cap_[1].resonance == 2);
  o.capture_time = 1.7;
  autobal_runup_analyze(&s, res, 3, &o, &b, &r, &e);
  CHECK("capture_time 1.7 s: no capture", r.n_captures == 0);
  /* monitor 1 - t/10: below 0.01 from t = 9.9 s on; the last passage is 16.184 s */
  {
    size_t k;
    for (k = 0; k < n; k++) mon_[k] = fmax(1.0 - t_[k] / 10.0, 0.0);
  }
  autobal_runup_analyze(&s, res, 3, &o, &b, &r, &e);
  CHECK_CLOSE("balanced before the last passage: time_to_balance = t_last_passage", r.time_to_balance, 404.6 / a,
              1e-13, 0);
  CHECK_CLOSE("  balance_delay = 0", r.balance_delay, 0.0, 0, 0);
  autobal_runup_analyze(&s, res, 2, &o, &b, &r, &e);
  CHECK_CLOSE("last passage 215.1/25 = 8.604 s: time_to_balance = 9.9 s (the line through the samples)",
              r.time_to_balance, 9.9, 1e-12, 0);
  CHECK_CLOSE("  balance_delay = 9.9 - 8.604 s", r.balance_delay, 9.9 - 215.1 / a, 1e-12, 0);
  mon_[1500] = 0.5; /* a relapse at t = 15 s */
  autobal_runup_analyze(&s, res, 2, &o, &b, &r, &e);
  CHECK_CLOSE("a relapse at t = 15 s (0.5 there, 0 at 15.01 s): time_to_balance = 15 + 0.01 (0.5 - 0.01)/0.5",
              r.time_to_balance, 15.0 + 0.01 * 0.49 / 0.5, 1e-12, 0);
  mon_[1500] = NAN;
  autobal_runup_analyze(&s, res, 2, &o, &b, &r, &e);
  CHECK_CLOSE("a NaN monitor at t = 15 s: time_to_balance = the next sample, 15.01 s", r.time_to_balance, 15.01, 1e-12,
              0);
  mon_[n - 1] = 0.02;
  autobal_runup_analyze(&s, res, 2, &o, &b, &r, &e);
  CHECK("not below the tolerance at the end: time_to_balance NaN", isnan(r.time_to_balance) && isnan(r.balance_delay));
  s.monitor = NULL;
  autobal_runup_analyze(&s, res, 2, &o, &b, &r, &e);
  CHECK("no monitor: time_to_balance NaN", isnan(r.time_to_balance));
  /* no resonance: time to balance from t_0 */
  s.monitor = mon_;
  mon_[n - 1] = 0.0;
  mon_[1500] = 0.0;
  autobal_runup_analyze(&s, NULL, 0, &o, &b, &r, &e);
  CHECK("no resonances: no passage, t_last_passage NaN", r.n_passages == 0 && isnan(r.t_last_passage));
  CHECK_CLOSE("  time_to_balance 9.9 s, delay from t_0 = 0", r.balance_delay, 9.9, 1e-12, 0);
  /* truncation: room for one passage */
  b.passage_cap = 1;
  autobal_runup_analyze(&s, res, 3, &o, &b, &r, &e);
  CHECK("passage_cap 1: n_passages 3, truncated, the first stored", r.n_passages == 3 && r.truncated &&
                                                                         fabs(pass_[0].t - res[0] / a) < 1e-12);
  CHECK_CLOSE("  t_last_passage still the last one", r.t_last_passage, 404.6 / a, 1e-13, 0);
  b.passage_cap = 64;
  b.capture_cap = 0;
  b.captures = NULL;
  o.capture_time = 0.1;
  autobal_runup_analyze(&s, res, 3, &o, &b, &r, &e);
  CHECK("capture_cap 0: n_captures 3 counted, truncated", r.n_captures == 3 && r.truncated);
}

static void test_coastdown_dip_negative(void) {
  const double res[2] = {157.3, 215.1};
  size_t n = 2001, k;
  autobal_runup_series s = series(n, 0);
  autobal_runup_buffers b = buffers();
  autobal_runup_result r;
  autobal_error e;
  ramp(n, 0.01, 500.0, -25.0);
  autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e);
  CHECK("coast-down 500 -> 0: two passages down, the higher resonance first",
        r.n_passages == 2 && pass_[0].resonance == 1 && pass_[1].resonance == 0 && pass_[0].direction == -1 &&
            pass_[1].direction == -1);
  CHECK_CLOSE("coast-down: passage of 215.1 at (500 - 215.1)/25", pass_[0].t, (500 - 215.1) / 25.0, 1e-13, 0);
  CHECK_CLOSE("coast-down: passage of 157.3 at (500 - 157.3)/25", pass_[1].t, (500 - 157.3) / 25.0, 1e-13, 0);
  /* several resonances inside one sample interval: stored in time order */
  ramp(3, 10.0, 100.0, 20.0); /* 100, 300, 500 */
  s.n = 3;
  autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e);
  CHECK("two resonances within one interval (up): time order", r.n_passages == 2 && pass_[0].resonance == 0 &&
                                                                   pass_[1].t > pass_[0].t);
  ramp(3, 10.0, 500.0, -20.0);
  autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e);
  CHECK("two resonances within one interval (down): time order", r.n_passages == 2 && pass_[0].resonance == 1 &&
                                                                     pass_[1].t > pass_[0].t);
  /* a dip: 300 -> 100 over 0..4 s, back to 300 at 8 s: 215.1 passed down at (300-215.1)/50, up at 4 + (215.1-100)/50 */
  n = 801;
  s.n = n;
  for (k = 0; k < n; k++) {
    t_[k] = 0.01 * (double)k;
    om_[k] = t_[k] <= 4.0 ? 300.0 - 50.0 * t_[k] : 100.0 + 50.0 * (t_[k] - 4.0);
  }
  autobal_runup_analyze(&s, res + 1, 1, NULL, &b, &r, &e);
  CHECK("dip 300 -> 100 -> 300: two passages of 215.1 (down, up)",
        r.n_passages == 2 && pass_[0].direction == -1 && pass_[1].direction == 1);
  CHECK_CLOSE("dip: down at (300 - 215.1)/50", pass_[0].t, (300 - 215.1) / 50.0, 1e-12, 0);
  CHECK_CLOSE("dip: up at 4 + (215.1 - 100)/50 (the last passage)", r.t_last_passage, 4.0 + (215.1 - 100) / 50.0,
              1e-12, 0);
  /* a speed that stops exactly at a resonance (a sample on it), stays, then rises: one passage up */
  for (k = 0; k < n; k++) om_[k] = t_[k] <= 2.0 ? 100.0 * t_[k] : t_[k] <= 5.0 ? 200.0 : 200.0 + 10.0 * (t_[k] - 5.0);
  {
    const double r200 = 200.0;
    autobal_runup_options o = autobal_runup_options_default();
    autobal_runup_analyze(&s, &r200, 1, &o, &b, &r, &e);
    CHECK("a plateau exactly at w_c = 200: one passage, up, where the speed reaches it (t = 2 s)",
          r.n_passages == 1 && pass_[0].direction == 1 && fabs(pass_[0].t - 2.0) < 1e-12);
    CHECK("  and a capture from t = 1.9 s (band edge 190 rad/s) to 6 s (210 rad/s)",
          r.n_captures == 1 && fabs(cap_[0].t_enter - 1.9) < 1e-12 && fabs(cap_[0].t_leave - 6.0) < 1e-12);
    /* the series ends inside the band: at_end */
    s.n = 451; /* to t = 4.5 s */
    autobal_runup_analyze(&s, &r200, 1, &o, &b, &r, &e);
    CHECK("ending on the plateau: capture at_end, t_leave = the last sample",
          r.n_captures == 1 && cap_[0].at_end && fabs(cap_[0].t_leave - 4.5) < 1e-12);
    /* starting inside the band */
    s.t = t_ + 300, s.omega = om_ + 300, s.amplitude = amp_ + 300, s.monitor = mon_ + 300, s.n = 501;
    autobal_runup_analyze(&s, &r200, 1, &o, &b, &r, &e);
    CHECK("starting on the plateau: capture at_start, t_enter = t_0 = 3 s, no passage",
          r.n_captures == 1 && cap_[0].at_start && fabs(cap_[0].t_enter - 3.0) < 1e-12 && r.n_passages == 0);
  }
  /* a negative speed: |Omega| counts */
  s = series(2001, 0);
  ramp(2001, 0.01, 0.0, -25.0);
  autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e);
  CHECK("Omega = -25 t: |Omega| passes both resonances upwards",
        r.n_passages == 2 && pass_[0].direction == 1 && fabs(pass_[1].t - 215.1 / 25.0) < 1e-12);
}

/* The envelope: a spike held for one revolution, and a random series against brute force. */
static void test_envelope(void) {
  size_t n = 400, k, m = 100, p = 16;
  autobal_runup_series s = series(n, 0);
  autobal_runup_buffers b = buffers();
  autobal_runup_result r;
  autobal_error e;
  int ok = 1;
  const double W = 300.0, dt = TWO_PI / W / (double)p; /* p samples per revolution */
  for (k = 0; k < n; k++) t_[k] = (double)k * dt, om_[k] = W, amp_[k] = k == m ? 1.0 : 0.0;
  autobal_runup_analyze(&s, NULL, 0, NULL, &b, &r, &e);
  for (k = 0; k < n; k++) ok &= env_[k] == ((k >= m && k <= m + p) ? 1.0 : 0.0);
  CHECK("constant speed, 16 samples per revolution: a spike at sample 100 is held for samples 100..116", ok);
  CHECK("envelope_max 1 at the spike", r.envelope_max == 1.0 && r.t_envelope_max == t_[m] && r.omega_envelope_max == W);
  /* a ramp from rest Omega = a t: the window of k reaches back to t_j with t_k^2 - t_j^2 <= 4 pi/a */
  {
    const double a = 7.0, h = 0.013;
    size_t held = 0, want = 0;
    for (k = 0; k < n; k++) t_[k] = (double)k * h, om_[k] = a * t_[k], amp_[k] = k == m ? 1.0 : 0.0;
    autobal_runup_analyze(&s, NULL, 0, NULL, &b, &r, &e);
    ok = 1;
    for (k = 0; k < n; k++) {
      double d = (t_[k] * t_[k] - t_[m] * t_[m]) - 4.0 * (0.5 * TWO_PI) / a;
      int in = k >= m && d <= 0;
      if (fabs(d) < 1e-6) ok = 0; /* a tie: choose other numbers */
      ok &= env_[k] == (in ? 1.0 : 0.0);
      held += env_[k] == 1.0;
      want += (size_t)in;
    }
    printf("ramp from rest: the spike is held for %zu samples (closed form %zu)\n", held, want);
    CHECK("ramp from rest a = 7 rad/s^2: the spike is held while t_k^2 - t_m^2 <= 4 pi/a", ok && want > 1);
  }
  /* random amplitudes, a speed profile with a stop: brute force over windows from the cumulative angle */
  {
    unsigned long long x = 12345;
    double phi[400], worst = 0;
    for (k = 0; k < n; k++) {
      x = x * 6364136223846793005ULL + 1442695040888963407ULL;
      amp_[k] = (double)(x >> 11) / 9007199254740992.0;
      if (k % 37 == 5) amp_[k] = NAN;
      t_[k] = 0.002 * (double)k + 1e-4 * (double)(k % 3);
      om_[k] = 400.0 * fabs(sin(0.01 * (double)k)) - (k > 200 ? 50.0 : 0.0);
    }
    phi[0] = 0;
    for (k = 1; k < n; k++) phi[k] = phi[k - 1] + 0.5 * (fabs(om_[k]) + fabs(om_[k - 1])) * (t_[k] - t_[k - 1]);
    autobal_runup_analyze(&s, NULL, 0, NULL, &b, &r, &e);
    ok = 1;
    for (k = 0; k < n; k++) {
      size_t j;
      double mx = NAN;
      for (j = 0; j <= k; j++)
        if (phi[k] - phi[j] <= TWO_PI * (1 + 1e-9) && !isnan(amp_[j]) && !(amp_[j] <= mx)) mx = amp_[j];
      if (!(env_[k] == mx || (isnan(mx) && isnan(env_[k])))) ok = 0;
      if (!isnan(mx)) worst = fmax(worst, fabs(env_[k] - mx));
    }
    CHECK("random amplitudes with NaNs, varying speed: envelope = brute-force maximum over the trailing revolution", ok);
  }
}

static void test_lag(void) {
  const size_t p = 20, n = 401, nb = 2;
  const double W = 250.0, T = TWO_PI / W, dt = T / (double)p, c[2] = {3.0, -0.5};
  size_t k, i;
  autobal_runup_series s = series(n, nb);
  autobal_runup_buffers b = buffers();
  autobal_runup_result r;
  autobal_error e;
  double worst_lag = 0, worst_rate = 0;
  for (k = 0; k < n; k++) {
    t_[k] = (double)k * dt, om_[k] = W, amp_[k] = 0;
    for (i = 0; i < nb; i++) psi_[k * nb + i] = 1.0 + (double)i - c[i] * t_[k] * t_[k];
  }
  CHECK_STATUS("quadratic lag psi = psi0 - c t^2", autobal_runup_analyze(&s, NULL, 0, NULL, &b, &r, &e),
               AUTOBAL_SUCCESS);
  for (k = 0; k < n; k++)
    for (i = 0; i < nb; i++) {
      double want_rate = k == 0 ? NAN : k < p ? c[i] * t_[k] : c[i] * (2.0 * t_[k] - T);
      worst_lag = fmax(worst_lag, fabs(lag_[k * nb + i] - c[i] * t_[k] * t_[k]));
      if (k > 0) worst_rate = fmax(worst_rate, fabs(lrate_[k * nb + i] - want_rate) / fabs(c[i]));
    }
  CHECK_CLOSE("lag = c t^2 (max error)", worst_lag, 0, 0, 1e-13);
  CHECK_CLOSE("lag_rate = c (2 t - T) over the trailing revolution, c t before one revolution (max rel. error)",
              worst_rate, 0, 0, 1e-9);
  CHECK("lag_rate NaN at the first sample", isnan(lrate_[0]) && isnan(lrate_[1]));
  /* a window of one sample (sampling coarser than a revolution): the last interval */
  for (k = 0; k < n; k++) {
    t_[k] = (double)k * 2.0 * T;
    for (i = 0; i < nb; i++) psi_[k * nb + i] = 1.0 + (double)i - c[i] * t_[k] * t_[k];
  }
  autobal_runup_analyze(&s, NULL, 0, NULL, &b, &r, &e);
  CHECK_CLOSE("two revolutions per sample: lag_rate over the last interval, c (t_k + t_k-1)", lrate_[10 * nb],
              c[0] * (t_[10] + t_[9]), 1e-12, 0);
}

static void test_bad_input(void) {
  const double res[2] = {100.0, 200.0}, bad_order[2] = {200.0, 100.0}, neg = -5.0;
  autobal_runup_series s = series(101, 1);
  autobal_runup_buffers b = buffers();
  autobal_runup_options o = autobal_runup_options_default();
  autobal_runup_result r;
  autobal_error e;
  ramp(101, 0.1, 0.0, 30.0);
  CHECK_STATUS("out NULL", autobal_runup_analyze(&s, res, 2, NULL, &b, NULL, &e), AUTOBAL_EINVAL);
  CHECK_STATUS("series NULL", autobal_runup_analyze(NULL, res, 2, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK("  result zeroed with NaN fields", r.n_passages == 0 && isnan(r.t_last_passage) && isnan(r.time_to_balance));
  s.n = 0;
  CHECK_STATUS("n = 0", autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "series.n");
  s.n = 101;
  t_[50] = t_[49];
  CHECK_STATUS("t not increasing", autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "t[50]");
  t_[50] = 5.0;
  om_[7] = NAN;
  CHECK_STATUS("NaN speed", autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "omega[7]");
  om_[7] = 21.0;
  CHECK_STATUS("resonances decreasing", autobal_runup_analyze(&s, bad_order, 2, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "strictly increasing");
  CHECK_STATUS("negative resonance", autobal_runup_analyze(&s, &neg, 1, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "resonance[0]");
  CHECK_STATUS("resonance NULL with n_resonance 2", autobal_runup_analyze(&s, NULL, 2, NULL, &b, &r, &e),
               AUTOBAL_EINVAL);
  o.capture_band = 1.0;
  CHECK_STATUS("capture_band 1", autobal_runup_analyze(&s, res, 2, &o, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "options.capture_band");
  o = autobal_runup_options_default();
  o.capture_time = 0;
  CHECK_STATUS("capture_time 0", autobal_runup_analyze(&s, res, 2, &o, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "options.capture_time");
  o = autobal_runup_options_default();
  o.balance_tol = NAN;
  CHECK_STATUS("balance_tol NaN", autobal_runup_analyze(&s, res, 2, &o, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "options.balance_tol");
  b.work = NULL;
  CHECK_STATUS("envelope without work", autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "buffers.work");
  b.work = work_;
  s.psi = NULL;
  CHECK_STATUS("lag without psi", autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  CHECK_MSG("  message", e.message, "series.psi");
  b.lag = b.lag_rate = NULL;
  CHECK_STATUS("no lag asked: psi may be NULL", autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e), AUTOBAL_SUCCESS);
  s.amplitude = NULL;
  CHECK_STATUS("envelope without amplitude", autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e), AUTOBAL_EINVAL);
  b.envelope = NULL;
  CHECK_STATUS("no envelope asked: amplitude and work may be NULL",
               autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e), AUTOBAL_SUCCESS);
  CHECK("  envelope_max NaN without amplitude", isnan(r.envelope_max));
  b.passages = NULL;
  CHECK_STATUS("passages NULL with passage_cap 64", autobal_runup_analyze(&s, res, 2, NULL, &b, &r, &e),
               AUTOBAL_EINVAL);
}

int main(void) {
  test_ramp();
  test_coastdown_dip_negative();
  test_envelope();
  test_lag();
  test_bad_input();
  return check_summary();
}
