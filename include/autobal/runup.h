/* autobal/runup.h: outputs of a run-up, a coast-down or any other speed profile, computed from
 * a sampled time series: the amplitude envelope, the passages of the resonance speeds, captures
 * (the speed dwelling near a resonance), the time to balance after the last passage and the ball
 * lag (docs/device.md, "Run-up outputs").
 *
 * A pure function on plain arrays: it knows no model and no archive.  The samples come from any
 * transient (the rotor transient study calls it on its own series, include/autobal/study.h);
 * the resonance speeds from anywhere (the study takes the Campbell crossings of
 * autobal_rotor_resonance_speeds, rotor_stability.h).  Units: times in s, speeds in rad/s,
 * angles in rad; the amplitude and the monitor in whatever unit the caller uses (the
 * envelope has the amplitude's unit, the tolerance the monitor's).
 *
 * Memory: the caller owns every array; nothing is allocated.  Thread safety: no state. */
#ifndef AUTOBAL_RUNUP_H
#define AUTOBAL_RUNUP_H

#include <stddef.h>

#include "autobal/export.h"
#include "autobal/status.h"

AUTOBAL_BEGIN_DECLS

/* Options (the defaults in brackets; autobal_runup_options_default). */
typedef struct autobal_runup_options {
  double capture_band; /* 1, relative half-width b of the band |Omega| in [(1 - b) w_c, (1 + b) w_c]
                          around each resonance speed w_c, in (0, 1)                    [0.05] */
  double capture_time; /* s, a stay in the band that lasts at least this long is a capture
                          (> 0, finite)                                                   [2] */
  double balance_tol;  /* the monitor's threshold of the time to balance (> 0, finite)   [0.01] */
} autobal_runup_options;

AUTOBAL_API autobal_runup_options autobal_runup_options_default(void);

/* The sampled run (inputs, not modified). */
typedef struct autobal_runup_series {
  size_t n;                /* samples, >= 1 */
  const double *t;         /* [n] s, finite and strictly increasing */
  const double *omega;     /* [n] rad/s, the spin speed Omega(t_k), finite; its magnitude |Omega|
                              is compared with the resonance speeds */
  const double *amplitude; /* [n] the vibration amplitude (e.g. m); NULL: no envelope */
  const double *monitor;   /* [n] the residual unbalance monitor (e.g. max_j |s_j|/s_ref,j);
                              NULL: no time to balance */
  size_t n_balls;          /* balls, >= 0 */
  const double *psi;       /* [n x n_balls] row-major (psi[k n_balls + i]), rad: the ball angles
                              relative to the rotor, unwrapped (continuous in time); may be NULL
                              when no lag is asked for */
} autobal_runup_series;

/* A passage: |Omega| goes through a resonance speed w_c between samples k and k + 1. */
typedef struct autobal_runup_passage {
  size_t resonance; /* index into the resonance list */
  double t;         /* s, where the straight line through (t_k, |Omega_k|), (t_k+1, |Omega_k+1|)
                       equals w_c */
  int direction;    /* +1 up: |Omega_k| < w_c <= |Omega_k+1|; -1 down: |Omega_k| >= w_c > |Omega_k+1| */
} autobal_runup_passage;

/* A capture: |Omega| stays inside the band of a resonance (options.capture_band) without a
 * break for at least options.capture_time. */
typedef struct autobal_runup_capture {
  size_t resonance; /* index into the resonance list */
  double t_enter;   /* s, where |Omega| entered the band (linear between the samples either side
                       of the band edge), or t_0 when the series starts inside */
  double t_leave;   /* s, where it left the band (likewise), or t_n-1 when it ends inside */
  int at_start;     /* 1: the series starts inside the band (t_enter = t_0) */
  int at_end;       /* 1: the series ends inside the band (t_leave = t_n-1: still captured) */
} autobal_runup_capture;

/* Caller-owned output arrays; any pointer may be NULL (that output is not computed, except the
 * scalar results, which always are). */
typedef struct autobal_runup_buffers {
  double *envelope;  /* [n] peak hold: max of amplitude over the trailing revolution (below); needs
                        series.amplitude and work */
  double *lag;       /* [n x n_balls] rad, lag angle psi_i(t_0) - psi_i(t_k): how far ball i has
                        fallen behind the rotor since the start (negative: ahead); needs psi */
  double *lag_rate;  /* [n x n_balls] rad/s, the lag's rate averaged over the trailing revolution:
                        (psi_i(t_j) - psi_i(t_k)) / (t_k - t_j), j the first sample of the window
                        (j = k - 1 when the window has one sample; NaN at k = 0); needs psi */
  size_t *work;      /* [n] scratch, needed with envelope */
  autobal_runup_passage *passages; /* [passage_cap], in time order */
  size_t passage_cap;
  autobal_runup_capture *captures; /* [capture_cap], by resonance, then time */
  size_t capture_cap;
} autobal_runup_buffers;

/* Scalar results. */
typedef struct autobal_runup_result {
  size_t n_passages;      /* passages found (all of them; only passage_cap are stored) */
  size_t n_captures;      /* captures found (all of them; only capture_cap are stored) */
  int truncated;          /* 1: n_passages > passage_cap or n_captures > capture_cap */
  double t_last_passage;  /* s, the last passage; NaN: none */
  double time_to_balance; /* s, the first time t >= t_ref (t_ref = t_last_passage, or t_0 when
                             there is no passage) from which the monitor stays below balance_tol
                             to the end of the series: the later of t_ref and the time where the
                             straight line between the last sample at or above the tolerance
                             (or NaN) and the next one reaches it (t_0 if every sample is
                             below); NaN: the last sample is not below, or no monitor */
  double balance_delay;   /* s, time_to_balance - t_ref; NaN with time_to_balance */
  double envelope_max;    /* largest amplitude (NaN: no amplitude or all NaN) */
  double t_envelope_max;  /* s, its time (first sample of the maximum) */
  double omega_envelope_max; /* rad/s, Omega there */
} autobal_runup_result;

/* Analyse a sampled run.
 *
 * The trailing revolution of sample k (window of the envelope and the lag rate): the samples
 * j <= k with Phi_k - Phi_j <= 2 pi (1 + 1e-9), Phi the rotor angle integrated from |Omega|
 * by the trapezoidal rule over the samples (exact for a piecewise-linear speed sampled at its
 * corners).  At low speed the window reaches far back (at rest, to the start); a sampling
 * coarser than a revolution gives a window of one sample.  envelope[k] is the largest
 * amplitude in the window (NaN amplitudes are skipped; NaN if all are).  For a whirl with a
 * circular orbit the amplitude |(x, y)| is already the envelope; for an elliptic orbit the
 * window's maximum is the major semi-axis.
 *
 * Passages: for every pair of neighbouring samples and every resonance w_c (as defined in
 * autobal_runup_passage), |Omega| linear in between; within one pair they are stored in the
 * order of time.  A speed profile that stops exactly at w_c counts as having passed it on the
 * way up (the passage is where it reaches w_c) and passes again downwards only once it falls
 * below.  Captures: each maximal run of consecutive samples inside the band of a resonance is a
 * capture when t_leave - t_enter >= capture_time (a band jumped over between two samples is no
 * stay).  Bands of close resonances may overlap; each resonance is treated on its own.
 *
 * resonance[0 .. n_resonance-1]: rad/s, finite, > 0, strictly increasing (n_resonance may be 0;
 * resonance may then be NULL).  opt NULL: defaults.  Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL
 * with a message naming the argument and its allowed range (series, t not increasing,
 * non-finite speeds or times, resonances not increasing, an option out of range, a missing
 * array that an output needs, out NULL); then nothing is written but *out, which is zeroed with
 * its NaN fields set to NaN. */
AUTOBAL_API int autobal_runup_analyze(const autobal_runup_series *series, const double *resonance,
                                      size_t n_resonance, const autobal_runup_options *opt,
                                      autobal_runup_buffers *buf, autobal_runup_result *out,
                                      autobal_error *err);

AUTOBAL_END_DECLS

#endif
