/* autobal/attractor.h: what a transient settled to, from the end of its run (issue 17).
 *
 * A transient of a rotor with ball autobalancers ends in one of a few kinds of motion: the
 * balls compensate the unbalance (balanced), they sit together on the side of the unbalance
 * (heavy side, the state below the first critical speed), they sit at rest somewhere else, a
 * ball keeps circulating round its track behind the rotor (captured by a resonance of the
 * rotor: its absolute angular rate lies near a natural frequency), or the motion is some other
 * periodic (or quasi-periodic) motion, or irregular.  autobal_attractor_classify names it from
 * plain samples of the final window of the run (model-agnostic: the caller turns its states
 * into ball angles relative to the rotor, residual unbalance and amplitude).
 *
 * THE RULE (every threshold an option below, with its default), applied in this order to the
 * samples t_0 < ... < t_{n-1} of the final window (the last window_revs revolutions of the
 * run, not before the member's settle time; the whole run when it is shorter):
 *  1 BALANCED     the run stopped because the residual unbalance stayed below balance_tol for
 *                 the dwell (the ensemble's "balanced"), or the residual unbalance is
 *                 <= balance_tol at every sample of the window.
 *  Each ball i has over the window the range R_i = max psi_i - min psi_i of its angle psi_i
 *  relative to the rotor (continuous, not wrapped), its turn count
 *  T_i = (psi_i(t_{n-1}) - psi_i(t_0)) / 2 pi, its mean relative rate over the window
 *  r_i = (psi_i(t_{n-1}) - psi_i(t_0)) / (t_{n-1} - t_0), over each of its four quarters and
 *  the mean relative rates r_i' and r_i'' over its first and second half (the parts end at the
 *  samples nearest t_0 + j (t_{n-1} - t_0) / 4).
 *  2 HEAVY_SIDE   every ball at rest (R_i <= rest_tol) and, in every plane j with balls and a
 *                 non-zero unbalance U_j at angle psi_j0, the balls' first moment points to the
 *                 side of the unbalance: sum_i m_i r_i cos(psi_i - psi_j0) > 0 at the end.
 *  3 FIXED        every ball at rest, not 1 or 2 (e.g. a partial compensation).
 *  4 CIRCULATING  some ball circulates (|T_i| >= min_turns), every circulating ball steadily
 *                 (its rate over each quarter within rate_tol |r_i| of r_i) and at one common
 *                 rate (each r_i within rate_tol of their mean r).  Its frequency is the balls' absolute rate
 *                 nu = Omega + r (Omega the spin speed at the end; rad/s, signed as Omega), and
 *                 it is compared with the natural frequency f_k of the rotor (given by the
 *                 caller, e.g. autobal_rotor_modes at Omega: the Campbell diagram's column at
 *                 that speed) of the whirl that nu excites (forward when nu has the sign of
 *                 Omega) nearest to |nu|.
 *  5 PERIODIC     none of the above, and the motion repeats: over each half of the window the
 *                 smallest and the largest residual unbalance (and amplitude, when given)
 *                 agree between the two halves within envelope_tol times the largest of them,
 *                 and so do the balls' mean relative rates (within rate_tol of their mean
 *                 absolute value, or within 2 pi / (window duration) rad/s, whichever is
 *                 larger).  This is a test of a stationary envelope: a quasi-periodic motion
 *                 counts as periodic.
 *  6 IRREGULAR    none of the above: the two halves differ (a chaotic motion, or one still in
 *                 its transient: a longer run decides).
 * UNCLASSIFIED (0) is for a member that failed or was not run.
 *
 * Units: SI (rad, rad/s, s); residual unbalance dimensionless, amplitude in the caller's
 * length unit.  The functions allocate nothing, keep no state and never print. */
#ifndef AUTOBAL_ATTRACTOR_H
#define AUTOBAL_ATTRACTOR_H

#include <stddef.h>
#include "autobal/export.h"
#include "autobal/status.h"

AUTOBAL_BEGIN_DECLS

/* The classes (values of the archive's per-member variable `attractor`). */
enum autobal_attractor_class {
  AUTOBAL_ATTRACTOR_UNCLASSIFIED = 0, /* the member failed or was not run                   */
  AUTOBAL_ATTRACTOR_BALANCED = 1,     /* the balls compensate the unbalance                 */
  AUTOBAL_ATTRACTOR_HEAVY_SIDE = 2,   /* balls at rest on the side of the unbalance         */
  AUTOBAL_ATTRACTOR_FIXED = 3,        /* balls at rest elsewhere, not balanced              */
  AUTOBAL_ATTRACTOR_CIRCULATING = 4,  /* a ball circulates steadily: frequency reported      */
  AUTOBAL_ATTRACTOR_PERIODIC = 5,     /* another motion with a stationary envelope          */
  AUTOBAL_ATTRACTOR_IRREGULAR = 6     /* none of these                                      */
};
#define AUTOBAL_ATTRACTOR_N_CLASSES 7

/* Name of class c ("unclassified", "balanced", "heavy_side", "fixed", "circulating",
 * "periodic", "irregular"; NULL for another c); a static string. */
AUTOBAL_API const char *autobal_attractor_class_name(int c);
/* One character per class for text maps: "?", "#", "h", "f", "c", "p", "i" (NULL for another c). */
AUTOBAL_API const char *autobal_attractor_class_symbol(int c);
/* The legend "0 unclassified, 1 balanced, 2 heavy_side, 3 fixed, 4 circulating, 5 periodic,
 * 6 irregular" (a static string, as the archive's `legend` attribute). */
AUTOBAL_API const char *autobal_attractor_legend(void);

/* Thresholds of the rule (see the top of this file). */
typedef struct autobal_attractor_options {
  double window_revs;  /* length of the final window, revolutions of the spin speed; (0, 1e6],
                          default 100                                                           */
  double rest_tol;     /* rad, a ball is at rest when its angle's range over the window is at
                          most this; (0, pi], default 0.05                                      */
  double min_turns;    /* relative revolutions over the window that make a ball circulate;
                          [1, 1e9], default 2                                                   */
  double rate_tol;     /* relative tolerance of "the same rate"; (0, 1), default 0.02           */
  double envelope_tol; /* relative tolerance of "the same envelope"; (0, 1), default 0.05       */
} autobal_attractor_options;

/* The defaults above. */
AUTOBAL_API autobal_attractor_options autobal_attractor_options_default(void);
/* AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (o NULL, or a field out of its range or NaN: the message
 * names the field, its value and the allowed range, e.g. "attractor rest_tol = 0 rad is out of
 * range: allowed (0, 3.14159]"). */
AUTOBAL_API int autobal_attractor_options_check(const autobal_attractor_options *o, autobal_error *err);

/* The final window of one run (plain data, borrowed). */
typedef struct autobal_attractor_window {
  size_t n;                  /* samples, >= 2 (fewer: IRREGULAR unless balanced)              */
  const double *t;           /* n times, increasing (s)                                       */
  size_t n_balls;            /* balls, 0 .. 64                                                */
  const double *psi;         /* n x n_balls row-major: angle of each ball relative to the rotor
                                (rad), continuous in time (not wrapped)                      */
  const double *residual;    /* n residual unbalances (dimensionless, >= 0)                   */
  const double *amplitude;   /* n vibration amplitudes, or NULL                               */
  double balance_tol;        /* > 0: the residual unbalance of "balanced"                     */
  int stopped_balanced;      /* 1: the run stopped at balance (rule 1)                        */
  double speed;              /* spin speed Omega at the end, rad/s                            */
  /* the planes: ball i belongs to plane plane_of_ball[i] (< n_planes) and has first moment
   * ball_moment[i] = m_i r_i (kg m); plane j's unbalance has moment unbalance_moment[j] >= 0
   * at angle unbalance_angle[j] (rad, relative to the rotor) */
  size_t n_planes;
  const size_t *plane_of_ball;
  const double *ball_moment;
  const double *unbalance_moment;
  const double *unbalance_angle;
  /* natural frequencies of the rotor at `speed` (rad/s, > 0) and their whirl (+1 forward,
   * -1 backward, 0 undecided: compared with either sense); n_modes may be 0 */
  size_t n_modes;
  const double *mode_frequency;
  const int *mode_whirl;
} autobal_attractor_window;

/* What the rule found. */
typedef struct autobal_attractor_result {
  int cls;                   /* enum autobal_attractor_class                                  */
  double frequency;          /* CIRCULATING: nu = Omega + r, rad/s; NaN otherwise             */
  double natural_frequency;  /* CIRCULATING: the nearest natural frequency of the whirl nu
                                excites, rad/s; NaN otherwise or when there is none           */
  int mode;                  /* its index in mode_frequency, -1 when none                     */
  size_t n_circulating;      /* balls that circulate (|T_i| >= min_turns)                     */
  size_t n_at_rest;          /* balls at rest (R_i <= rest_tol)                               */
} autobal_attractor_result;

/* Classify one window (the rule above).  Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL
 * arguments, a bad option, n_balls > 64, a plane index out of range, times not increasing;
 * *r then says UNCLASSIFIED).  Samples that are not finite make the member IRREGULAR. */
AUTOBAL_API int autobal_attractor_classify(const autobal_attractor_options *opt, const autobal_attractor_window *w,
                                           autobal_attractor_result *r, autobal_error *err);

AUTOBAL_END_DECLS

#endif
