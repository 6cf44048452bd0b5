/* autobal/transient.h: the transient engine, a model-agnostic driver of
 * GSL's gsl_odeiv2 steppers for first-order systems y' = f(t, y).
 *
 * What it does
 *  - Adaptive integration with a stepper chosen by name (rk8pd by default here: the engine's
 *    default is unchanged in 0.2.0, while the transient studies and commands default to dop853
 *    with dense_order 6, see autobal_study_rotor_transient_options; docs/architecture.md;
 *    rk2, rk4, rkf45, rkck, rk8pd, rk1imp, rk2imp, rk4imp, bsimp, msadams,
 *    msbdf; and autobal's own dop853), GSL's standard error control with a_y = 1,
 *    a_dydt = 0:
 *        |err_i| <= atol + rtol |y_i|   for every component i (max norm),
 *    an initial step (or an automatic one), a maximum and a minimum step,
 *    and a maximum number of steps.  The step loop is the driver's own
 *    (gsl_odeiv2_step_apply + gsl_odeiv2_control_hadjust, with the same
 *    retry rules as gsl_odeiv2_evolve_apply), so the derivative at the end
 *    of an accepted step is reused as the first stage of the next one when
 *    the stepper provides it exactly (rk8pd, rkck, rkf45, ...).
 *  - Implicit steppers (rk1imp, rk2imp, rk4imp, bsimp, msbdf) use the
 *    system's analytic Jacobian when given, else a forward-difference one
 *    computed by the driver into its preallocated workspace:
 *        d f_i / d y_j ~ (f_i(t, y + d_j e_j) - f_i(t, y)) / d_j,
 *        d_j = sqrt(DBL_EPSILON) max(|y_j|, 1),
 *        d f / d t ~ (f(t + d_t, y) - f(t, y)) / d_t, d_t = sqrt(DBL_EPSILON) max(|t|, 1)
 *    (dim + 2 right-hand-side evaluations; suited to O(1)-scaled,
 *    e.g. dimensionless, states).
 *  - Dense output (stepper dop853, option exact_output = 0, the default for it): the
 *    Dormand-Prince 8(5,3) pair DOP853 (Hairer's dop853.f; 12 right-hand sides per accepted
 *    step; the decision of GSL's control, max norm, computed in the step itself (its growth
 *    factor rmax^(-1/8) by square roots, not pow), on Hairer's error estimate, O(h^8):
 *    e5 h |e5| / sqrt(|e5|^2 + 0.01 |e3|^2) with the 5th- and 3rd-order embedded differences e5, e3 and
 *    their 2-norms scaled by atol + rtol max(|y0_i|, |y1_i|)) with its
 *    continuous extension of order 7 (3 more right-hand sides, only in the steps where it is
 *    used).  Then output times, event crossings and dwell completions are taken on the
 *    extension: the steps are not cut (a step may hold many output times), the observer gets
 *    the interpolated state (exactly the integrated one at t1), an event is located by
 *    Illinois iteration on g(t, u(t)) with u the extension, to event_tol, and its state is
 *    u(t_hit) (no re-integration); probes evaluate the extension and need no confirmation.
 *    The extension's local error is O(h^8), one order below the step's O(h^9), and about the
 *    size of the error estimate that the control keeps below atol + rtol |y| (measured: at
 *    most 1.35 times it): at an output point the error is that of the integrated states plus
 *    a few times the per-step tolerance (tests/test_transient_dense.c: 1.6 to 5.7 times
 *    atol + rtol |y| over tolerances 1e-6 .. 1e-12 on a closed form; checked <= 10).
 *    With dense_order = 6 the extension is instead one of order 6 built from the step's own
 *    stages and f(t + h, y1) (no extra right-hand side at all: output is free); its local error
 *    is O(h^7), and measured at the output points it is 0.99-1.12 times contd8's with output
 *    every quarter revolution (more where many output times sample long steps at tight
 *    tolerances: docs/architecture.md, "DOP853's continuous extension of order 6").
 *    With exact_output = 1 (or any other stepper) everything below holds as written.
 *  - Output on a uniform grid t0 + k dt_out (k = 0, 1, ...) plus t1, handed
 *    to an observer callback; the driver stores no history, so memory does
 *    not grow with the length of a run.  The grid points are hit EXACTLY:
 *    a step is never allowed to pass the next output time (no
 *    interpolation), so the output is as accurate as any accepted step.  A
 *    dt_out smaller than the natural step therefore limits the step to dt_out.
 *  - Events: a function g(t, y) whose sign change over an accepted step is
 *    located to event_tol in time on integrated trial points: the first by
 *    RE-INTEGRATING from the start of that step with the same stepper and
 *    tolerances (an auxiliary stepper object, so the main integration is not
 *    disturbed), later ones within 1e-3 of the step from the last trial
 *    point by a short hop from it (one classical Runge-Kutta step, local
 *    error O(hop^5), far below the stepper's).  The trial points are placed
 *    at the crossing of a cubic Hermite interpolant between the nearest
 *    integrated points on either side (at first the whole step), the later
 *    ones just across it from the point before, so that usually three
 *    points bracket the crossing to event_tol; an Illinois (modified regula
 *    falsi) iteration on the integrated g finishes when they do not.  The
 *    interpolant only places the trial points: the reported time and state
 *    are integrated ones, the time on the far side of the crossing.
 *    Events are terminal (the run stops at the event with the state there)
 *    or not (reported, the run continues), and may reset the state or the
 *    system (hybrid systems: impacts, stick-slip; the integration restarts
 *    at the event, see autobal_transient_event_reset_fn).
 *  - Dwell events ("time to balance"): fire the first time a monitored
 *    scalar s(t, y) has stayed below a threshold for a given duration.  The
 *    downward crossing of the threshold is located like an event (t_start),
 *    the run is then made to land exactly on t_start + duration, and the
 *    event fires there if s is still below the threshold.  s is sampled at
 *    the end of every accepted step: an excursion above the threshold that
 *    begins and ends inside one step is not seen.
 *  - Progress (fraction of [t0, t1] done) through a callback that may
 *    cancel; statistics (steps, rejected trial steps, right-hand-side and
 *    Jacobian evaluations, wall time, time reached).
 *
 * Errors and the state after a failure
 *   run() returns AUTOBAL_SUCCESS (reached t1), AUTOBAL_EVENT (> 0: stopped
 *   by a terminal event, an event handler or the observer), or a negative
 *   status:
 *     AUTOBAL_EINVAL      bad arguments (nothing integrated, y untouched)
 *     AUTOBAL_ERHS        the right-hand side (or Jacobian) returned non-zero,
 *                         or returned a non-finite value (tested on every
 *                         step's result and error estimate, into which a NaN
 *                         or inf of any stage propagates)
 *     AUTOBAL_ESTEP       step size below h_min, or below what changes t by
 *                         one ulp, or the stepper failed at that size
 *     AUTOBAL_EMAXSTEPS   max_steps accepted steps did not reach t1
 *     AUTOBAL_ECANCELLED  the progress callback returned non-zero
 *     AUTOBAL_ENUMERIC    an event function returned NaN, or the state
 *                         became non-finite
 *   In every case y holds the state at the last accepted step (or at the
 *   located event), *t_reached and stats.t_end the time of that state, and
 *   the message (autobal_transient_errmsg) says what happened and where.
 *
 * Callbacks must not call run() on the same handle.  One handle per thread;
 * two handles never interfere.  The library never prints.  A host program
 * should call gsl_set_error_handler_off() once (see status.h).
 */
#ifndef AUTOBAL_TRANSIENT_H
#define AUTOBAL_TRANSIENT_H

#include <stddef.h>
#include "autobal/export.h"
#include "autobal/status.h"

AUTOBAL_BEGIN_DECLS

/* ---- the system ----------------------------------------------------------- */

/* Right-hand side dydt = f(t, y): returns 0, or non-zero to report a failure
 * (the run then stops with AUTOBAL_ERHS), or AUTOBAL_TRANSIENT_RHS_REJECT: the
 * state is outside the system's domain (e.g. a ball would leave its track),
 * which at a trial stage of a step means the step was too long: the step is
 * retried with half the size (GSL's rule for failures other than
 * GSL_EBADFUNC); at a state the integration has reached, or when no step
 * down to the smallest avoids it, the run stops with AUTOBAL_ERHS.  Same
 * signature as GSL's gsl_odeiv2_system.function. */
#define AUTOBAL_TRANSIENT_RHS_REJECT (-1000)
typedef int (*autobal_transient_rhs_fn)(double t, const double y[], double dydt[], void *params);

/* Jacobian: dfdy[i*dim + j] = d f_i / d y_j (row-major), dfdt[i] = d f_i / d t.
 * Returns 0 or non-zero (failure, AUTOBAL_ERHS).  Same signature as GSL's
 * gsl_odeiv2_system.jacobian. */
typedef int (*autobal_transient_jac_fn)(double t, const double y[], double *dfdy, double dfdt[],
                                        void *params);

/* A first-order system: rhs required, jac optional (NULL: finite differences
 * when an implicit stepper needs it), dim >= 1, params passed to both. */
typedef struct autobal_transient_system {
  autobal_transient_rhs_fn rhs;
  autobal_transient_jac_fn jac;
  size_t dim;
  void *params;
} autobal_transient_system;

/* ---- options ---------------------------------------------------------------- */

/* Smallest relative tolerance: 4 DBL_EPSILON (about 8.9e-16); a smaller one cannot be met in
 * double arithmetic. */
#define AUTOBAL_TRANSIENT_RTOL_MIN 8.8817841970012523e-16

typedef struct autobal_transient_options {
  const char *stepper;    /* GSL stepper name (list above); NULL means "rk8pd" (the engine's
                             default; the transient studies' is "dop853" since 0.2.0)   */
  double rtol;            /* relative tolerance, in [AUTOBAL_TRANSIENT_RTOL_MIN, 1]
                                                                       (default 1e-10)  */
  double atol;            /* absolute tolerance, > 0 and finite        (default 1e-12)  */
  double h_init;          /* first trial step, >= 0; 0: automatic      (default 0)      */
  double h_max;           /* largest step, >= 0; 0: unlimited          (default 0)      */
  double h_min;           /* smallest step, >= 0; a step that would need to be smaller
                             stops the run with AUTOBAL_ESTEP; 0: only the GSL limit of
                             one ulp in t                              (default 0)      */
  unsigned long max_steps; /* accepted steps per run; 0: unlimited     (default 1e8)    */
  double dt_out;          /* output interval of the observer, >= 0; 0: only t0 and t1
                             (default 0)                                                */
  double event_tol;       /* time tolerance of event location, > 0     (default 1e-10)  */
  double progress_step;   /* progress is reported when the fraction done has grown by
                             at least this, in (0, 1]                  (default 0.005)  */
  double progress_wall;   /* and, if > 0, at most once per this many seconds of wall
                             time (0: no wall-time limit), >= 0        (default 0)      */
  int exact_output;       /* 0: with a stepper that has a continuous extension (dop853),
                             output times, events and dwell completions are taken on it
                             (dense output, see "Dense output" above); 1: hit exactly by
                             cutting steps, as every other stepper does; 0 or 1
                             (default 0; added in 0.2.0, at the end)                   */
  int dense_order;        /* the continuous extension of dop853's dense output: 7 (Hairer's
                             contd8, 3 more right-hand sides in each step that holds an output
                             time, event or dwell completion) or 6 (from the step's own 12
                             stages and f(t + h, y1): no extra right-hand side; degree 7, C1
                             at the step ends, local error O(h^7); see "Dense output" above);
                             7 or 6, 0 taken as 7          (default 7; added in 0.2.0, at the end) */
} autobal_transient_options;

/* The defaults listed above. */
AUTOBAL_API autobal_transient_options autobal_transient_options_default(void);

/* Validate options (ranges above, stepper name known).  On failure returns
 * AUTOBAL_EINVAL with a message naming the option, its value and the allowed
 * range (an unknown stepper: the list of valid names). */
AUTOBAL_API int autobal_transient_options_validate(const autobal_transient_options *opt,
                                                   autobal_error *err);

/* The valid stepper names, separated by ", " (static string). */
AUTOBAL_API const char *autobal_transient_stepper_names(void);

/* ---- callbacks -------------------------------------------------------------- */

/* Observer: called at t0, at every output time t0 + k dt_out < t1 and at t1
 * (each once), with the state there.  A run stopped early (event, failure,
 * cancellation) makes no extra observer call at the stopping time: the
 * final state is in y.  Return non-zero to stop the run (status
 * AUTOBAL_EVENT, stop reason OBSERVER). */
typedef int (*autobal_transient_observer_fn)(double t, const double y[], void *user);

/* Progress: fraction of [t0, t1] done, in [0, 1], non-decreasing; called at
 * the start (0), as options.progress_step/progress_wall allow (and, within the
 * progress_wall limit, at least every 4096 accepted steps so that a request to
 * cancel is noticed even when t hardly advances), and at the end (1) of a run
 * that reaches t1.  Return non-zero to cancel
 * (AUTOBAL_ECANCELLED). */
typedef int (*autobal_transient_progress_fn)(double fraction, void *user);

/* Event function g(t, y) (a sign change is an event) or monitored scalar
 * s(t, y) of a dwell event.  Must return a finite value (NaN stops the run
 * with AUTOBAL_ENUMERIC). */
typedef double (*autobal_transient_scalar_fn)(double t, const double y[], void *user);

/* A located event. */
typedef struct autobal_transient_event_hit {
  size_t index;    /* the event, numbered in the order of adding, from 0                  */
  double t;        /* event time: the sign change of g, located to event_tol, on the far
                      side of the crossing (g already has its new sign or is 0); for a
                      dwell event the time the duration was completed                     */
  double t_start;  /* dwell event: time the scalar went below the threshold (the "time to
                      balance" when the scalar is a residual unbalance); else equal to t   */
  int direction;   /* +1: g went from < 0 to >= 0; -1: from > 0 to <= 0 (dwell: -1)        */
  int terminal;    /* 1 if the run stops here                                             */
} autobal_transient_event_hit;

/* Event handler: called for every located event, in time order, with the
 * state at hit->t.  Return non-zero to stop the run there (AUTOBAL_EVENT). */
typedef int (*autobal_transient_event_handler_fn)(const autobal_transient_event_hit *hit,
                                                  const double y[], void *user);

/* Event reset (hybrid systems: impacts, stick-slip switching): called for a
 * located event after the handler, with the state at hit->t in y, which it
 * may change (an impact reverses a velocity); it may also change what the
 * system's right-hand side and event functions compute (a mode held in their
 * params: a ball sticks).  Return
 *   0                          nothing changed: the run goes on as without it;
 *   AUTOBAL_TRANSIENT_RESET    y and/or the system changed: the driver drops
 *                              the rest of the step, restarts the integration
 *                              at (hit->t, y) (stepper history and the reused
 *                              derivative discarded, the output grid kept),
 *                              and re-evaluates every event function there;
 *   anything else              stop the run there (AUTOBAL_EVENT, user_code).
 * Events pending later in the same step are dropped (they are found again if
 * they still happen), and an event function that is already past its crossing
 * at the reset state is not reported: a reset should settle every switching
 * condition that holds at hit->t (e.g. all balls that stop together).  More
 * than 1000 resets in a row, each within event_tol of the previous one
 * (chattering: a Zeno point), stop the run with AUTOBAL_ESTEP. */
#define AUTOBAL_TRANSIENT_RESET 1
typedef int (*autobal_transient_event_reset_fn)(const autobal_transient_event_hit *hit, double y[],
                                                void *user);

/* ---- statistics --------------------------------------------------------------- */

typedef enum autobal_transient_stop {
  AUTOBAL_TRANSIENT_STOP_NONE = 0,      /* no run yet                              */
  AUTOBAL_TRANSIENT_STOP_END = 1,       /* reached t1                              */
  AUTOBAL_TRANSIENT_STOP_EVENT = 2,     /* terminal event, or the handler said stop */
  AUTOBAL_TRANSIENT_STOP_OBSERVER = 3,  /* the observer returned non-zero          */
  AUTOBAL_TRANSIENT_STOP_CANCELLED = 4, /* the progress callback returned non-zero */
  AUTOBAL_TRANSIENT_STOP_ERROR = 5      /* a failure (see status)                  */
} autobal_transient_stop;

/* Statistics of the last run (plain data; the app may store it). */
typedef struct autobal_transient_stats {
  unsigned long steps;       /* accepted steps of the main integration                       */
  unsigned long rejected;    /* rejected trial steps (error too large or stepper failure)     */
  unsigned long rhs_evals;   /* calls of the system's rhs (including those made for the
                                finite-difference Jacobian and for locating events)          */
  unsigned long jac_evals;   /* Jacobian evaluations (analytic or finite-difference)         */
  unsigned long fd_jac_evals; /* of which by finite differences                              */
  unsigned long events;      /* events reported to the handler (dwell events included)       */
  unsigned long event_steps; /* accepted steps of the auxiliary integrations and short hops
                                that located events (not counted in steps)                   */
  unsigned long observer_calls;
  double wall_seconds;       /* wall time of the run (CLOCK_MONOTONIC)                       */
  double t_start;            /* t0                                                           */
  double t_end;              /* time of the state left in y                                  */
  double h_last;             /* last accepted step size                                      */
  double h_min_used, h_max_used; /* smallest and largest accepted step (main integration)   */
  int status;                /* the status run() returned                                    */
  int stop_reason;           /* autobal_transient_stop                                       */
  int user_code;             /* the non-zero value returned by the callback or the rhs that
                                stopped the run (0 otherwise)                                */
  int event_index;           /* the event that stopped the run, else -1                      */
  unsigned long resets;      /* restarts after an event reset (added in 0.3.0, at the end)   */
} autobal_transient_stats;

/* ---- the handle --------------------------------------------------------------- */

typedef struct autobal_transient autobal_transient;

/* Allocate a driver for systems of dimension dim >= 1 with the given options
 * (NULL: defaults).  All workspaces (GSL stepper, control, the Jacobian,
 * event location) are allocated here; run() allocates nothing.  Returns NULL
 * on failure, with the reason in err (may be NULL): AUTOBAL_EINVAL (bad dim
 * or option) or AUTOBAL_ENOMEM. */
AUTOBAL_API autobal_transient *autobal_transient_alloc(size_t dim,
                                                       const autobal_transient_options *opt,
                                                       autobal_error *err);
/* Free the handle (NULL is safe). */
AUTOBAL_API void autobal_transient_free(autobal_transient *tr);

/* Last error message ("" after success; never NULL; tr may be NULL). */
AUTOBAL_API const char *autobal_transient_errmsg(const autobal_transient *tr);

/* Replace the options (validated first; on failure the old ones stay).  A
 * different stepper re-allocates the GSL objects (not to be called from a
 * callback).  Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL or AUTOBAL_ENOMEM. */
AUTOBAL_API int autobal_transient_set_options(autobal_transient *tr,
                                              const autobal_transient_options *opt);
/* The current options (the stepper name points to a static string); the
 * defaults of autobal_transient_options_default() when tr is NULL. */
AUTOBAL_API autobal_transient_options autobal_transient_get_options(const autobal_transient *tr);

/* Callbacks (fn NULL removes one; user is stored as given and passed back).
 * They replace the previous callback of the same kind, take effect at the next
 * run, and do nothing when tr is NULL (there is no status to return). */
AUTOBAL_API void autobal_transient_set_observer(autobal_transient *tr,
                                                autobal_transient_observer_fn fn, void *user);
AUTOBAL_API void autobal_transient_set_progress(autobal_transient *tr,
                                                autobal_transient_progress_fn fn, void *user);
AUTOBAL_API void autobal_transient_set_event_handler(autobal_transient *tr,
                                                     autobal_transient_event_handler_fn fn,
                                                     void *user);

/* The event reset (NULL removes it; see autobal_transient_event_reset_fn). */
AUTOBAL_API void autobal_transient_set_event_reset(autobal_transient *tr,
                                                   autobal_transient_event_reset_fn fn, void *user);

/* Add an event g(t, y) = 0.  direction: +1 only rising crossings (g from < 0
 * to >= 0), -1 only falling ones, 0 both.  terminal: 1 to stop the run at
 * the first such event.  Returns the event's index (>= 0) or a negative
 * status (AUTOBAL_EINVAL: g NULL, bad direction, more than 100000 events, or
 * tr NULL; AUTOBAL_ENOMEM); the events already added are kept. */
AUTOBAL_API int autobal_transient_add_event(autobal_transient *tr, autobal_transient_scalar_fn g,
                                            void *user, int direction, int terminal);

/* Grazing crossings: events are sampled at the ends of the accepted steps, so an event function
 * that crosses 0 and comes back within one step is missed.  With n > 0 probes, when event `index`
 * has the same sign at both ends of a step, the driver also evaluates it at n interior points,
 * t_prev + k h / (n + 1), on the cubic Hermite interpolant of the state (y and y' at both ends:
 * the stepper's own where it hands them over, as rk8pd does, else two right-hand sides per step);
 * the first point past 0 in a watched direction is checked on the integrated state and, if
 * confirmed, the crossing is located between the step's start and that point as usual.  When no
 * probe is past 0 but the samples show an extremum towards 0 whose parabola through it and its
 * neighbours comes near 0 (within the sampled prominence), that extremum is searched between the
 * neighbours (golden section down to event_tol) on the same interpolant and checked on the
 * integrated state where it peaks (dense output: on the extension, no check needed).  A crossing shorter than h / (n + 1) that leaves no such trace at the samples can
 * still be missed.  n = 0 (the default) turns it off; at most
 * 64; not for dwell events.  Events with the same n share the interpolated states of a step.  Returns
 * AUTOBAL_SUCCESS, AUTOBAL_EINVAL or AUTOBAL_ENOMEM (the shared states are allocated here). */
AUTOBAL_API int autobal_transient_set_event_probes(autobal_transient *tr, int index, unsigned n);
/* Dense output (stepper dop853, output not exact): on = 1 also evaluates event `index` at every output
 * time inside a step whose ends show no crossing, on the continuous extension (the state the observer
 * then receives); the first output time past 0 in a watched direction brackets the crossing, located
 * and handled as above before that output is emitted.  So no output point shows the event function
 * past 0 unnoticed (e.g. balls of `rotor transient` overlapping at an output point: a grazing impact
 * between the step's ends), as with exact output, where the output times are step ends.  Without
 * dense output it changes nothing.  Default 0; not for dwell events.  Returns AUTOBAL_SUCCESS or
 * AUTOBAL_EINVAL.  Counted with the probes' crossings (autobal_transient_probe_hits). */
AUTOBAL_API int autobal_transient_set_event_output_probes(autobal_transient *tr, int index, int on);
/* Grazing crossings found by probes since the handle was allocated. */
AUTOBAL_API unsigned long autobal_transient_probe_hits(const autobal_transient *tr);

/* Add a dwell event: fires (once per run) the first time s(t, y) <
 * threshold has held continuously for `duration` (>= 0, time units) - e.g.
 * the residual unbalance below a tolerance for N revolutions: "time to
 * balance" = hit.t_start.  If s(t0) < threshold, t_start = t0.  Returns the
 * index or a negative status (as autobal_transient_add_event; also
 * AUTOBAL_EINVAL for a non-finite threshold or a duration < 0 or not finite). */
AUTOBAL_API int autobal_transient_add_dwell_event(autobal_transient *tr,
                                                  autobal_transient_scalar_fn s, void *user,
                                                  double threshold, double duration,
                                                  int terminal);

/* Remove all events (their indices become invalid); nothing when tr is NULL. */
AUTOBAL_API void autobal_transient_clear_events(autobal_transient *tr);

/* After a run: how many times event `index` fired (*count, may be NULL) and
 * its first hit (*first, may be NULL; written only if it fired).  Returns 1
 * if it fired, 0 if not, AUTOBAL_EINVAL for a bad index or a NULL tr (then
 * nothing is written and no message is recorded). */
AUTOBAL_API int autobal_transient_event_result(const autobal_transient *tr, size_t index,
                                               unsigned long *count,
                                               autobal_transient_event_hit *first);

/* Integrate sys from (t0, y) to t1 (t1 >= t0, both finite; sys->dim must be
 * the handle's dim).  y (dim doubles, finite) is the initial state on entry
 * and the final state on return (see "Errors" above for every outcome).
 * t_reached (may be NULL) receives the time of the returned state.  Each run
 * starts afresh (stepper history, counters, events reset). */
AUTOBAL_API int autobal_transient_run(autobal_transient *tr, const autobal_transient_system *sys,
                                      double t0, double t1, double y[], double *t_reached);

/* Statistics of the last run (zeros before the first; zeros with
 * event_index = -1 when tr is NULL; nothing when stats is NULL). */
AUTOBAL_API void autobal_transient_get_stats(const autobal_transient *tr,
                                             autobal_transient_stats *stats);

/* Name of a stop reason ("end", "event", "observer", "cancelled", "error", "none"). */
AUTOBAL_API const char *autobal_transient_stop_name(int stop_reason);

AUTOBAL_END_DECLS

#endif
