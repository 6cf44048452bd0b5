/* autobal/ensemble.h: the ensemble engine, many transients over a set of
 * parameters (a grid, or seeded random samples), each summarised.
 *
 * A member is a parameter vector -> a transient -> a summary.  The engine
 * knows no physics: the model enters through an autobal_ensemble_member, a
 * table of callbacks (set up a member's system and initial state from its
 * parameter values, observe the run, summarise its end).  Two members are
 * ready-made: autobal_ensemble_rotor_member (the rotor with ball
 * autobalancers; initial ball angles and rates, speed, damping, unbalance,
 * initial displacement) and autobal_ensemble_pendulum_member (the
 * two-pendulum model; initial state, R_w, R_m, H, h, psi0, k).
 *
 * The engine owns: the members (grid or random samples), one transient
 * driver per thread (OpenMP when the library was built with it), a journal
 * of finished members and the resume from journals, progress and
 * cancellation hooks, the tally (probability of balancing, time to balance)
 * and the archive layout /<model>/ensemble written through autobal_archive.
 *
 * Reproducibility.  Every member is computed the same way whichever thread
 * or process runs it (its own model set-up, a driver reset at each run), so
 * the results are bit-for-bit independent of the number of threads and of
 * how the members are dealt out over processes.
 *
 * Members.  Grid mode: n_1 x n_2 x ... members in row-major order (the last
 * parameter varies fastest); parameter j takes
 *     min_j + (max_j - min_j) i / (n_j - 1)     (endpoint = 1)
 *     min_j + (max_j - min_j) i / n_j           (endpoint = 0; periodic axes)
 * (min_j when n_j = 1).  Random mode: member m, parameter j (0-based) takes
 *     min_j + (max_j - min_j) u,  u = (x >> 11) 2^-53,
 * x = output number m*n_params + j (0-based) of splitmix64 seeded with
 * `seed`: x_k = mix(seed + (k + 1) 0x9E3779B97F4A7C15), mix(z): z ^= z >> 30,
 * z *= 0xBF58476D1CE4E5B9, z ^= z >> 27, z *= 0x94D049BB133111EB,
 * z ^= z >> 31 (Steele, Lea, Flood 2014).  A member's sample depends only on
 * (seed, m).
 *
 * A member's run: t from 0 to t_end (the model's time unit: s for the
 * rotor, tau for the pendulum); output every dt_out (or revs_out
 * revolutions of the member's speed); a dwell event on the model's residual
 * unbalance: "balanced" when it stayed below balance_tol for balance_dwell
 * (or balance_revs revolutions), the time to balance being the start of
 * that stretch (not before the member's settle_time, e.g. the end of its
 * speed ramp); the run stops there when stop_at_balance is set.  A member
 * whose set-up or run fails is a result (its status < 0), not a failure of
 * the ensemble.
 *
 * Journal (checkpoints).  With autobal_ensemble_journal_open every finished
 * member is appended at once (fflush) to OUTPUT.journal-<rank>.  Format
 * (native byte order, not portable across architectures): a 48-byte header
 * "ABENSJ01" then 5 uint64 (hash of the settings, see
 * autobal_ensemble_settings.identity; number of members; summary length;
 * series columns; 0), then records of doubles
 *     member, nsum, nrows, ncols_or_0, summary[nsum], t[nrows],
 *     rows[nrows*ncols], member.
 * A truncated last record (a process killed while writing) is ignored.  The
 * same records are what autobal_ensemble_records hands to a gather hook.
 *
 * Processes (MPI).  The engine does not link MPI.  A program that spreads an
 * ensemble over processes gives every process the same settings and an
 * autobal_ensemble_parallel: `mine` picks the members this process runs,
 * `gather` (called once at the end of every run, on every process, whatever
 * its status) sends this process's records to the writing process, which
 * adds them with autobal_ensemble_add_records.  The program's MPI layer
 * (apps/cmd_ensemble.c) is an example with MPI_COMM_WORLD.
 *
 * Threads.  A handle is used by one thread at a time; run() itself uses
 * `threads` OpenMP threads.  Two handles never interfere.  The library never
 * prints.
 */
#ifndef AUTOBAL_ENSEMBLE_H
#define AUTOBAL_ENSEMBLE_H

#include <stddef.h>
#include <stdint.h>
#include "autobal/export.h"
#include "autobal/status.h"
#include "autobal/transient.h"
#include "autobal/rotor.h"
#include "autobal/pendulum.h"
#include "autobal/archive.h"
#include "autobal/attractor.h"

AUTOBAL_BEGIN_DECLS

/* Most parameters an ensemble varies at once. */
#define AUTOBAL_ENSEMBLE_MAX_PARAMS 3
/* Most members an ensemble has (grid product or samples). */
#define AUTOBAL_ENSEMBLE_MAX_MEMBERS 100000000UL
/* Most members whose full time series are kept. */
#define AUTOBAL_ENSEMBLE_MAX_SERIES 1024

/* Member quantities (autobal_ensemble_member.n_quantities) and targets on them. */
#define AUTOBAL_ENSEMBLE_MAX_QUANTITIES 8
#define AUTOBAL_ENSEMBLE_MAX_TARGETS 4
/* Quantiles of a quantity's statistics: at p = 0, 0.05, 0.25, 0.5, 0.75, 0.95, 1
 * (autobal_ensemble_quantile_probability). */
#define AUTOBAL_ENSEMBLE_N_QUANTILES 7

/* A member's summary: doubles at these indices, then n_angles final angles, then the member's
 * n_quantities quantities (quantity k at AUTOBAL_ENSEMBLE_ANGLES + n_angles + k, see
 * autobal_ensemble_quantity_index; added in 0.2.0: the layout before them is unchanged). */
enum autobal_ensemble_summary_index {
  AUTOBAL_ENSEMBLE_STATUS = 0,          /* autobal status of the run: 0 reached t_end, 2 (AUTOBAL_EVENT)
                                           stopped at balance, < 0 failure (set-up or run)          */
  AUTOBAL_ENSEMBLE_BALANCED = 1,        /* 1 balanced, 0 not                                      */
  AUTOBAL_ENSEMBLE_TIME_TO_BALANCE = 2, /* start of the dwell below balance_tol (NaN: not balanced) */
  AUTOBAL_ENSEMBLE_RESIDUAL_INITIAL = 3,/* residual unbalance at t = 0 (dimensionless)            */
  AUTOBAL_ENSEMBLE_RESIDUAL_FINAL = 4,  /* residual unbalance at the end of the run               */
  AUTOBAL_ENSEMBLE_AMPLITUDE_MAX = 5,   /* largest sampled amplitude (model's length unit)        */
  AUTOBAL_ENSEMBLE_AMPLITUDE_FINAL = 6, /* amplitude at the end of the run                        */
  AUTOBAL_ENSEMBLE_T_REACHED = 7,       /* time reached                                           */
  AUTOBAL_ENSEMBLE_STEPS = 8,           /* accepted solver steps                                  */
  AUTOBAL_ENSEMBLE_RHS_EVALS = 9,       /* right-hand-side evaluations                            */
  AUTOBAL_ENSEMBLE_ANGLES = 10          /* first final angle (rad, wrapped to (-pi, pi])          */
};

/* ---- the model: a member's callbacks ------------------------------------------- */

/* What the model says about a parameter name (static strings). */
typedef struct autobal_ensemble_param_info {
  const char *units;     /* UDUNITS string, e.g. "rad", "rad/s", "1"   */
  const char *long_name; /* description for the archive                */
  int periodic;          /* 1: an angle; natural range [-pi, pi), grid without endpoint */
  int positive;          /* 1: only values > 0 are meaningful (a rate, a duration): alloc
                            rejects a range with min <= 0 (added in 0.2.0)              */
} autobal_ensemble_param_info;

/* A quantity the member computes at the end of each run (static strings). */
typedef struct autobal_ensemble_quantity {
  const char *name;      /* archive variable name, e.g. "balance_grade_final"             */
  const char *units;     /* UDUNITS string, e.g. "kg m", "mm/s"                          */
  const char *long_name; /* description for the archive                                  */
} autobal_ensemble_quantity;

/* What the model hands the engine for one member (filled by `setup`). */
typedef struct autobal_ensemble_setup {
  autobal_transient_system sys;      /* the system (valid until the next setup on that worker)   */
  double speed;                      /* rotation speed in rad per time unit: the revolution of
                                        revs_out and balance_revs is 2 pi/|speed|               */
  autobal_transient_scalar_fn monitor; /* residual unbalance s(t, y), dimensionless, >= 0       */
  void *monitor_user;                /* its user pointer                                        */
  double residual_initial;           /* residual unbalance at t = 0                             */
  double settle_time;                /* >= 0: the dwell of "balanced" counts only from this time
                                        on (e.g. the end of a speed ramp: a member balanced while
                                        the speed still changes is not yet balanced at its final
                                        speed); 0: from the start.  Before it the engine sees
                                        2 balance_tol where s < balance_tol, so a stretch below
                                        balance_tol starts at settle_time at the earliest, and
                                        the time to balance is >= settle_time (added in 0.2.0) */
} autobal_ensemble_setup;

/* A model.  `model` is read by every thread at once (it must not change
 * during run); each thread has its own worker (worker_alloc).  Callbacks
 * return AUTOBAL_SUCCESS or a negative status (with a message in err, which
 * may be NULL) unless said otherwise. */
typedef struct autobal_ensemble_member {
  const char *model_name;  /* archive group /<model_name>/ensemble, e.g. "rotor" */
  void *model;             /* the caller's (or the ready-made member's) model data */
  size_t dim;              /* state dimension (>= 1)                               */
  size_t n_angles;         /* final angles in a summary (0 .. 64)                  */
  size_t n_columns;        /* columns of a kept time series row (>= 1)             */
  const char *time_units;  /* "s" or "1"                                           */
  const char *time_name;   /* name of a series' time axis, e.g. "time", "tau"      */
  const char *time_long_name;
  const char *length_units;/* units of the amplitudes, e.g. "m" or "1"             */
  const char *angle_dim;   /* dimension name of final_angle, e.g. "ball"           */
  const char *angle_dim_long_name, *angle_long_name;
  /* Describe parameter `name` (info filled) or return AUTOBAL_EINVAL with a
   * message listing the valid names. */
  int (*describe)(const void *model, const char *name, autobal_ensemble_param_info *info,
                  autobal_error *err);
  /* Optional (NULL: none): reject a combination of parameter names
   * (AUTOBAL_EINVAL with a message). */
  int (*check)(const void *model, const char *const *names, size_t n, autobal_error *err);
  /* A per-thread workspace (NULL on failure, reason in err); freed by worker_free. */
  void *(*worker_alloc)(const void *model, const char *const *names, size_t n_params,
                        autobal_error *err);
  void (*worker_free)(void *worker);
  /* Set up a member from its parameter values (n_params, in the order of
   * the settings): y0 (dim doubles) receives the initial state at t = 0.  A
   * failure is recorded as the member's status. */
  int (*setup)(void *worker, const double *values, double y0[], autobal_ensemble_setup *setup,
               autobal_error *err);
  /* Observe the state at an output time: *amplitude receives the amplitude;
   * row (n_columns doubles, NULL when no series is kept) the series row.
   * Non-zero stops the run. */
  int (*observe)(void *worker, double t, const double y[], double *amplitude, double *row);
  /* Summarise the final state: residual, amplitude and angles (n_angles). */
  void (*finish)(void *worker, double t, const double y[], double *residual, double *amplitude,
                 double *angles);
  /* Name (into name[size]) and units (static) of series column k. */
  int (*column_name)(const void *model, size_t k, char *name, size_t size, const char **units);
  /* Optional: model attributes written into the ensemble group (e.g. the frame). */
  int (*write_attrs)(const void *model, autobal_archive *a, const char *group);
  /* Optional: a hash of the model's parameters (mixed into the journal's). */
  uint64_t (*hash)(const void *model);
  /* Optional: free `model` (the ready-made members set it). */
  void (*destroy)(void *model);
  /* Optional (added in 0.2.0; a zeroed tail: none): n_quantities (0 .. 8) more numbers per
   * member, described by quantity[k] (borrowed, like the strings above) and filled by
   * finish_quantities(worker, t, y, q) right after `finish`, with the same final state (q has
   * n_quantities doubles; NaN where undefined).  They end each summary (after the angles), enter
   * the statistics (autobal_ensemble_get_stats) and the targets, and are written as per-member
   * variables when settings.write_quantities is set. */
  size_t n_quantities;
  const autobal_ensemble_quantity *quantity;
  void (*finish_quantities)(void *worker, double t, const double y[], double *q);
  /* Optional (added in 0.3.0; a zeroed tail: none): the member's own events.  prepare(worker,
   * tr, y0, err) is called for each member after `setup`, once the engine has cleared the
   * driver's events, removed its event reset and added its dwell event, right before the run:
   * it may add events and an event reset to tr (the worker's driver: one per thread, so the
   * reset's user data must belong to the worker, never to the shared model) and change y0 (dim
   * doubles, the state at t = 0).  A failure is recorded as the member's status.
   * complete(worker, t_reached, run_status, err), after the run and before `finish`, returns
   * the member's status: run_status, or a negative status for a failure of the member's own
   * machinery (e.g. an event reset that stopped the run).  The rotor member uses them for the
   * stick-slip switching of the exact friction law. */
  int (*prepare)(void *worker, autobal_transient *tr, double y0[], autobal_error *err);
  int (*complete)(void *worker, double t_reached, int run_status, autobal_error *err);
  /* Optional (added in 0.3.0, issue 17; a zeroed tail: none): the attractor classification
   * (autobal/attractor.h).  After `finish` (and finish_quantities) of a member that did not fail,
   * classify(worker, opt, balance_tol, stopped_balanced, n, t, y, res, err) receives the samples
   * of the final window the observer saw: the last opt->window_revs revolutions of the member's
   * speed (the whole run when shorter), none before its settle_time; times t[n] and states
   * y[n * dim] (row-major); stopped_balanced is 1 when the run stopped at balance.  It fills res
   * (for instance by autobal_attractor_classify).  Its class, frequency and natural frequency end
   * the member's summary (autobal_ensemble_attractor_index).  A failure (negative status) leaves
   * the member UNCLASSIFIED (its run's status is kept).  The rotor member has it. */
  int (*classify)(void *worker, const autobal_attractor_options *opt, double balance_tol, int stopped_balanced, size_t n,
                  const double *t, const double *y, autobal_attractor_result *res, autobal_error *err);
} autobal_ensemble_member;

/* Release a member made by autobal_ensemble_*_member (calls destroy; the
 * struct is zeroed).  NULL and a zeroed member are safe. */
AUTOBAL_API void autobal_ensemble_member_release(autobal_ensemble_member *member);

/* The ready-made rotor member.  p is copied (with its ball arrays and a table
 * drive's points), so the caller's p may be freed afterwards.  frame:
 * AUTOBAL_ROTOR_FIXED or AUTOBAL_ROTOR_ROTATING (the frame of the equations,
 * named in the archive by frame_name, e.g. "fixed").  Parameters: psi_K,
 * rate_K (ball K = 1..n, plane 1 first; rad, rad/s, relative to the rotor),
 * omega (rad/s; the constant speed: not with a ramp or table drive),
 * ball_damping (kg/s, every ball), m0 (kg, plane 1), psi0 (rad, the angle of
 * plane 1's unbalance on the rotor; added in 0.2.0), x, y (m, initial
 * displacement); with a RAMP drive (p->drive) also
 *     ramp_rate (rad/s^2, > 0): the member's ramp keeps omega_a and t_a of
 *               p->drive and ends at t_b = t_a + |omega_b - omega_a| / ramp_rate
 *               (needs omega_b != omega_a);
 *     ramp_time (s, > 0): t_b = t_a + ramp_time (not with ramp_rate);
 *     omega_b (rad/s): the final speed (with ramp_rate, t_b follows from the
 *               member's omega_b; without, t_b stays, so the rate changes).
 * A member with a drive: its Omega(t) sets the equations; the revolutions of
 * revs_out and balance_revs are those of its largest |speed| (as in `rotor
 * transient`: max(|omega_a|, |omega_b|) for a ramp); its settle_time is the
 * end of its ramp t_b (a table's last time), so "balanced" means balanced at
 * the final speed; its final angles are relative to the rotor angle
 * phi_0(t).  The ensemble group records the drive (attributes drive_mode,
 * drive_omega_a, drive_omega_b, drive_t_a, drive_t_b or drive_table_t,
 * drive_table_omega, as /rotor/transient; the values of p->drive, before a
 * member's parameters change them).  Residual unbalance: autobal_rotor_balance_monitor; angles:
 * ball angles relative to the rotor; amplitude: output 0 of
 * autobal_rotor_outputs (m); series columns: the state, then the outputs.
 * Quantities (n_quantities = 2), from the final state, as `rotor transient`
 * reports them (autobal_study_rotor_transient_summary):
 *   0 residual_unbalance_abs_final (kg m): U = max_j |s_j|, the residual
 *     unbalance of the worst plane (autobal_rotor_plane_unbalance; one plane:
 *     |s|);
 *   1 balance_grade_final (mm/s): the ISO 21940-11 grade
 *     G = e Omega = n_planes U / m Omega 1e3 (autobal_balance_grade), with m
 *     the rotor mass (hw.m_p; lumped.M with lumped input) shared equally by the
 *     planes (the worst plane counts) and Omega the member's speed at the end
 *     (|omega| of the constant drive, |Omega(t_reached)| of a ramp or table, the
 *     largest |Omega| where that is 0).
 * Friction (added in 0.3.0; p->friction, its ball_f/ball_mu arrays copied):
 * every member runs the friction law of p; with the EXACT law each member
 * gets the stick-slip events and event reset of `rotor transient` on its
 * worker's driver (prepare/complete), so a member equals the single
 * autobal_study_rotor_transient run of its parameters, and three more
 * quantities (n_quantities = 5): 2 balls_stuck_final (balls stuck at the end),
 * 3 time_stuck_max (s, the longest total time one ball was stuck), 4
 * friction_switches (sticks + slips + reversals).  A ball leaving its track
 * during a switch fails the member (status AUTOBAL_ENUMERIC).  Parameters
 * ball_f and ball_mu (1, every ball; need a friction law) vary the
 * coefficients; f > mu fails the member (autobal_rotor_alloc).  The ensemble
 * group records the law (attribute friction; friction_u_eps for the
 * regularized law) and /rotor/plane<j> ball_f, ball_mu, as /rotor/transient.
 * Ball size and contact (added in 0.3.0; p->contact, its ball_diameter arrays
 * copied): every member gets the impact events and the event reset of `rotor
 * transient` (prepare/complete), its pairs ordered from its own initial angles
 * (a new handle per member), so a member equals the single
 * autobal_study_rotor_transient run of its parameters; two more quantities
 * after the others (n_quantities = 4, or 7 with the EXACT law): contact_impacts
 * (impacts during the run) and contacts_final (pairs touching at the end).
 * A member whose balls overlap at its initial angles fails (AUTOBAL_EINVAL,
 * the message naming the balls: autobal_ensemble_first_failure), the others
 * run.  The ensemble group records contact_restitution and contact_v_rest,
 * /rotor/plane<j> ball_diameter, as /rotor/transient; the hash includes
 * contact only when it is on (the journals of 0.2.0 stay valid).
 * Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL (p invalid: message from
 * autobal_rotor_alloc; bad frame; a drive mode other than constant, ramp or
 * table) or AUTOBAL_ENOMEM; on failure *out is zeroed.
 * Release with autobal_ensemble_member_release. */
AUTOBAL_API int autobal_ensemble_rotor_member(const autobal_rotor_params *p, int frame,
                                              const char *frame_name,
                                              autobal_ensemble_member *out, autobal_error *err);

/* The ready-made pendulum member (dimensionless, time tau).  p and y0 (the
 * 8-component initial state) are copied.  Parameters: xi, eta, psi, phi,
 * xi_rate, eta_rate, psi_rate, phi_rate (initial state), R_w, R_m, H, h, psi0,
 * k (k = sin^2(2 psi0): autobal_pendulum_params_from_k; not with psi0).
 * Residual unbalance: autobal_pendulum_unbalance_scalar; angles alpha, beta;
 * amplitude and series columns from autobal_pendulum_motion_derive.
 * Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL (p invalid or y0 not finite) or
 * AUTOBAL_ENOMEM; on failure *out is zeroed. */
AUTOBAL_API int autobal_ensemble_pendulum_member(const autobal_pendulum_params *p,
                                                 const double y0[8],
                                                 autobal_ensemble_member *out,
                                                 autobal_error *err);

/* ---- settings ---------------------------------------------------------------------- */

typedef struct autobal_ensemble_param {
  const char *name; /* the model's parameter name (copied by alloc)                     */
  double min, max;  /* range, finite, min <= max (the parameter's units)                */
  size_t n;         /* grid points, 1 .. 100000 (grid mode; ignored in random mode)     */
} autobal_ensemble_param;

/* A target: P(quantity <= limit) over the members (added in 0.2.0). */
typedef struct autobal_ensemble_target {
  const char *quantity;  /* a member quantity's name (copied by alloc); one target each      */
  double limit;          /* finite, in the quantity's units                                  */
} autobal_ensemble_target;

typedef struct autobal_ensemble_settings {
  int random;              /* 0: grid, 1: random samples                                  */
  size_t n_params;         /* 1 .. AUTOBAL_ENSEMBLE_MAX_PARAMS                            */
  autobal_ensemble_param param[AUTOBAL_ENSEMBLE_MAX_PARAMS];
  int endpoint;            /* grid: 1 includes max_j                                      */
  size_t samples;          /* random: number of members, 1 .. AUTOBAL_ENSEMBLE_MAX_MEMBERS  */
  uint64_t seed;           /* random: the seed                                            */
  /* each member's transient (time in the model's unit) */
  double t_end;            /* > 0                                                         */
  int use_revs_out;        /* 1: output every revs_out revolutions, 0: every dt_out       */
  double revs_out, dt_out; /* > 0                                                         */
  autobal_transient_options transient; /* stepper, rtol, atol, h_max, max_steps (dt_out,
                                          event_tol, progress_* are set by the engine)     */
  double balance_tol;      /* > 0, dimensionless                                          */
  int use_dwell;           /* 1: balance_dwell (time), 0: balance_revs (revolutions)      */
  double balance_revs, balance_dwell; /* >= 0                                             */
  int stop_at_balance;     /* 1: a member stops when balanced                             */
  /* kept series: these members' full time series (numbers < n_members; sorted and
     de-duplicated by alloc; at most AUTOBAL_ENSEMBLE_MAX_SERIES; the pointer is not kept) */
  const size_t *series;
  size_t n_series;
  /* running */
  int threads;             /* OpenMP threads, 0: the OpenMP default (1 without OpenMP)   */
  size_t max_members;      /* compute at most this many members per run (0: all)          */
  double time_limit;       /* start no member after this many seconds of run (0: none)    */
  uint64_t identity;       /* mixed into the journal's hash: e.g. a hash of the caller's
                              configuration, so that a journal of another one is refused */
  /* statistics of the member's quantities (added in 0.2.0).  They do not change a member's
     result, so they are not in the journal's hash: a resume may change them. */
  size_t n_targets;        /* 0 .. AUTOBAL_ENSEMBLE_MAX_TARGETS                             */
  autobal_ensemble_target target[AUTOBAL_ENSEMBLE_MAX_TARGETS];
  int write_quantities;    /* 1: autobal_ensemble_write writes each quantity as a per-member
                              variable (0, the default: statistics only, as attributes; the
                              datasets stay those of 0.1.0)                                 */
  /* the attractor classification of a member with `classify` (added in 0.3.0, issue 17): its
     thresholds (checked by alloc: autobal_attractor_options_check; they change a member's
     class, so they are in the journal's hash) and whether autobal_ensemble_write writes the
     per-member variables attractor, circulation_frequency, natural_frequency (1, the default;
     0: the class counts only, as attributes) */
  autobal_attractor_options attractor;
  int write_attractors;
} autobal_ensemble_settings;

/* Settings with the defaults: grid, no parameters, endpoint 0, samples 256,
 * seed 1, t_end 20, revs_out 0.25 (use_revs_out 1), dt_out 0, the transient
 * defaults with rtol 1e-10, atol 1e-9, balance_tol 0.01, balance_revs 50,
 * stop_at_balance 1, threads 0, no series, no limits, identity 0, no targets,
 * write_quantities 0, attractor autobal_attractor_options_default(),
 * write_attractors 1. */
AUTOBAL_API autobal_ensemble_settings autobal_ensemble_settings_default(void);

/* ---- the handle ------------------------------------------------------------------------ */

typedef struct autobal_ensemble autobal_ensemble;

/* Allocate an ensemble of `member` with settings s: validates every setting
 * (message naming it, its value and the allowed range), the parameter names
 * (member->describe, member->check, duplicates), the kept series and their
 * memory (at most 2^28 doubles in all; the kept members are set up once
 * here to know their output interval).  member is copied (its model and
 * strings are borrowed: they must outlive the handle); s is copied (names,
 * stepper and series list too).  Returns NULL on failure with
 * AUTOBAL_EINVAL or AUTOBAL_ENOMEM in err (may be NULL). */
AUTOBAL_API autobal_ensemble *autobal_ensemble_alloc(const autobal_ensemble_member *member,
                                                     const autobal_ensemble_settings *s,
                                                     autobal_error *err);
/* Free the handle (closes an open journal; NULL is safe). */
AUTOBAL_API void autobal_ensemble_free(autobal_ensemble *e);
/* Last error message ("" after success; never NULL; e may be NULL). */
AUTOBAL_API const char *autobal_ensemble_errmsg(const autobal_ensemble *e);

/* Number of members; summary length (AUTOBAL_ENSEMBLE_ANGLES + n_angles
 * + n_quantities);
 * 0 for NULL. */
AUTOBAL_API size_t autobal_ensemble_n_members(const autobal_ensemble *e);
AUTOBAL_API size_t autobal_ensemble_summary_length(const autobal_ensemble *e);
/* The settings as validated (series sorted and de-duplicated; pointer owned
 * by e); NULL for NULL. */
AUTOBAL_API const autobal_ensemble_settings *autobal_ensemble_get_settings(const autobal_ensemble *e);
/* The model's description of parameter j (NULL for a bad j). */
AUTOBAL_API const autobal_ensemble_param_info *autobal_ensemble_param_info_get(const autobal_ensemble *e,
                                                                               size_t j);
/* Value of parameter j of member m (formula above); NaN for bad arguments. */
AUTOBAL_API double autobal_ensemble_member_value(const autobal_ensemble *e, size_t m, size_t j);
/* Grid point i of parameter j (grid mode); NaN for bad arguments. */
AUTOBAL_API double autobal_ensemble_grid_value(const autobal_ensemble *e, size_t j, size_t i);
/* The hash written into the journals (settings, model hash, identity,
 * autobal version). */
AUTOBAL_API uint64_t autobal_ensemble_hash(const autobal_ensemble *e);

/* Hooks, each (fn, user); fn NULL removes it.
 *  progress: fraction of this run's members finished on this process, called
 *            after each member from one thread at a time.
 *  cancel:   polled before each member and during each transient (as the
 *            transient driver's progress callback), from any of run()'s
 *            threads at once (so it must be thread-safe, e.g. read a
 *            sig_atomic_t flag); non-zero cancels: members being computed are
 *            dropped (not recorded), run() returns AUTOBAL_ECANCELLED.
 * Return AUTOBAL_SUCCESS or AUTOBAL_EINVAL (e NULL). */
typedef void (*autobal_ensemble_progress_fn)(double fraction, void *user);
typedef int (*autobal_ensemble_cancel_fn)(void *user);
AUTOBAL_API int autobal_ensemble_set_progress(autobal_ensemble *e, autobal_ensemble_progress_fn fn,
                                              void *user);
AUTOBAL_API int autobal_ensemble_set_cancel(autobal_ensemble *e, autobal_ensemble_cancel_fn fn,
                                            void *user);

/* Dealing members over processes (see the top of this file). */
typedef struct autobal_ensemble_parallel {
  /* 1 if this process runs `member`, the k-th (k = 0, 1, ...) of the members
   * still to do (after resume, cut at max_members); NULL: all.  The MPI
   * layer of the program deals k mod size == rank. */
  int (*mine)(void *user, size_t k, size_t member);
  /* Called once at the end of every run() on every process, with this
   * process's status and records (n doubles; the journal's record format).
   * The writing process adds the others' records with
   * autobal_ensemble_add_records.  Returns the status run() then returns
   * (e.g. the worst over the processes).  NULL: nothing. */
  int (*gather)(void *user, autobal_ensemble *e, int status, const double *records, size_t n);
  void *user;
  int results;             /* 1: this process keeps the members' results (the writer);
                              0: only which members are done (saves memory)             */
} autobal_ensemble_parallel;
/* Set the dealing (copied).  Must come before resume and run.  Returns
 * AUTOBAL_SUCCESS or AUTOBAL_EINVAL (e or par NULL; or `results` changed after
 * members were done).  The result store (n_members x summary length doubles)
 * is allocated when first needed, and only when results = 1 (the default
 * without this call). */
AUTOBAL_API int autobal_ensemble_set_parallel(autobal_ensemble *e,
                                              const autobal_ensemble_parallel *par);

/* ---- journals ----------------------------------------------------------------------------- */

/* The journals of an output file: files named <output>.journal-<digits> in
 * its directory (sorted; "./" before a bare file name).  *paths (malloc'ed
 * array of malloc'ed strings, free with autobal_ensemble_journals_free) and
 * *n.  Returns AUTOBAL_SUCCESS (none: *n = 0), AUTOBAL_EIO or AUTOBAL_ENOMEM. */
AUTOBAL_API int autobal_ensemble_journals(const char *output, char ***paths, size_t *n,
                                          autobal_error *err);
/* Free a list from autobal_ensemble_journals (the n strings and the array; NULL is safe). */
AUTOBAL_API void autobal_ensemble_journals_free(char **paths, size_t n);
/* Only regular files that begin with the journal header's magic "ABENSJ01" are listed (and so
 * read or removed): a file merely named like a journal is never touched. */
/* Remove every journal of output.  Returns AUTOBAL_SUCCESS or AUTOBAL_EIO
 * (the message names the file; the ones before it are removed). */
AUTOBAL_API int autobal_ensemble_journals_remove(const char *output, autobal_error *err);

/* Resume: read every journal of output (written with any number of
 * processes); the members found there are done (their records kept when
 * this process keeps results).  rank: this process's journal, whose valid
 * length is remembered for journal_open.  Returns AUTOBAL_SUCCESS,
 * AUTOBAL_ECONFIG (a journal of other settings), AUTOBAL_EFORMAT (not a
 * journal), AUTOBAL_EIO or AUTOBAL_ENOMEM; the members read before the
 * failure stay done. */
AUTOBAL_API int autobal_ensemble_resume(autobal_ensemble *e, const char *output, int rank);

/* Open this process's journal <output>.journal-<rank>: appended to after its
 * valid records when resume read it, else created with a new header.  Every
 * member finished by run() is then appended and flushed; run() closes it.
 * Returns AUTOBAL_SUCCESS, AUTOBAL_EIO (message naming the file; no journal
 * is then open and run() keeps none) or AUTOBAL_ENOMEM.  Two handles must not
 * write the journal of the same output and rank. */
AUTOBAL_API int autobal_ensemble_journal_open(autobal_ensemble *e, const char *output, int rank);

/* ---- running ----------------------------------------------------------------------------- */

/* Compute the members not yet done (cut at max_members, dealt by `mine`),
 * with `threads` threads, each member appended to the journal.  Then the
 * gather hook.  Returns AUTOBAL_SUCCESS (also when some members failed:
 * see the tally), AUTOBAL_ECANCELLED (cancel hook), AUTOBAL_EIO (journal),
 * AUTOBAL_ENOMEM, or the gather hook's status.  The members finished stay
 * recorded whatever the status; run() may be called again to continue. */
AUTOBAL_API int autobal_ensemble_run(autobal_ensemble *e);

/* The records of the members finished by this process's runs (n doubles;
 * owned by e, valid until the next run or free). */
AUTOBAL_API const double *autobal_ensemble_records(const autobal_ensemble *e, size_t *n);
/* Add records (another process's, or a journal's content without its
 * header): members not yet done become done.  Returns AUTOBAL_SUCCESS,
 * AUTOBAL_EFORMAT (a damaged record; the ones before it are added) or
 * AUTOBAL_ENOMEM. */
AUTOBAL_API int autobal_ensemble_add_records(autobal_ensemble *e, const double *records, size_t n);

/* Threads a run uses (after the OpenMP default is resolved); members
 * computed by this process's last run; done members (all processes' after
 * gather, on the writer). */
AUTOBAL_API int autobal_ensemble_threads(const autobal_ensemble *e);
AUTOBAL_API size_t autobal_ensemble_computed(const autobal_ensemble *e);
/* Why a member failed: of the members this process's last run computed with a
 * negative status, the one with the lowest number (the same whatever the
 * number of threads), its status and its message (e.g. the rotor member's
 * "balls 1 and 2 of plane 1 (p1_b1, p1_b2) overlap at the initial position:
 * ..."; owned by e, valid until the next run).  Any output may be NULL.
 * Returns 1 when such a member exists, 0 when none failed (outputs untouched)
 * or e is NULL.  Members read from journals carry no message.  (Added in 0.3.0.) */
AUTOBAL_API int autobal_ensemble_first_failure(const autobal_ensemble *e, size_t *member, int *status,
                                               const char **message);
AUTOBAL_API size_t autobal_ensemble_n_done(const autobal_ensemble *e);
/* 1 if member m is done, 0 if not or m out of range. */
AUTOBAL_API int autobal_ensemble_is_done(const autobal_ensemble *e, size_t m);
/* Member m's summary (summary_length doubles, owned by e), or NULL when m is
 * not done or this process keeps no results. */
AUTOBAL_API const double *autobal_ensemble_summary(const autobal_ensemble *e, size_t m);
/* Member m's kept series: *n rows, times t[*n], rows[*n * n_columns] (owned
 * by e).  Returns AUTOBAL_SUCCESS (*n = 0 when not kept or not done) or
 * AUTOBAL_EINVAL. */
AUTOBAL_API int autobal_ensemble_series(const autobal_ensemble *e, size_t m, size_t *n,
                                        const double **t, const double **rows);

/* The tally over the done members.  p = n_balanced / (n_done - n_failed),
 * p_stderr = sqrt(p (1 - p) / (n_done - n_failed)); NaN where undefined.
 * Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL (NULL argument, or this process
 * keeps no results: *t then has n_members and NaNs) or AUTOBAL_ENOMEM. */
typedef struct autobal_ensemble_tally {
  size_t n_members, n_done, n_failed, n_ok, n_balanced;
  double p, p_stderr;                       /* probability of balancing, its standard error */
  double ttb_mean, ttb_median, ttb_max;     /* time to balance of the balanced members      */
} autobal_ensemble_tally;
AUTOBAL_API int autobal_ensemble_get_tally(const autobal_ensemble *e, autobal_ensemble_tally *t);

/* ---- statistics of the member quantities (added in 0.2.0) ------------------------------------- */

/* Number of member quantities (0 for NULL); the summary index of quantity k
 * (AUTOBAL_ENSEMBLE_ANGLES + n_angles + k; (size_t)-1 for a bad k or NULL);
 * its description (NULL for a bad k); the k of a name (-1: none). */
AUTOBAL_API size_t autobal_ensemble_n_quantities(const autobal_ensemble *e);
AUTOBAL_API size_t autobal_ensemble_quantity_index(const autobal_ensemble *e, size_t k);
AUTOBAL_API const autobal_ensemble_quantity *autobal_ensemble_quantity_get(const autobal_ensemble *e, size_t k);
AUTOBAL_API long autobal_ensemble_quantity_find(const autobal_ensemble *e, const char *name);

/* The probability p_i of quantile i: 0, 0.05, 0.25, 0.5, 0.75, 0.95, 1 (NaN for
 * i >= AUTOBAL_ENSEMBLE_N_QUANTILES). */
AUTOBAL_API double autobal_ensemble_quantile_probability(size_t i);

/* Quantile of probability p in [0, 1] of n >= 1 values x sorted ascending, by
 * linear interpolation between order statistics (Hyndman and Fan 1996,
 * definition 7; R's default, numpy.quantile's "linear"):
 *     h = (n - 1) p,  Q(p) = x[floor h] + (h - floor h) (x[floor h + 1] - x[floor h]),
 * so Q(0) = min, Q(1) = max.  NaN for n = 0, x NULL or p outside [0, 1]. */
AUTOBAL_API double autobal_ensemble_quantile_sorted(const double *x, size_t n, double p);

/* Wilson score interval (Wilson 1927) of a proportion: k successes in n
 * trials, p = k/n, z the normal quantile (1.959963984540054 for 95 %):
 *     (p + z^2/(2n) -+ z sqrt(p (1 - p)/n + z^2/(4 n^2))) / (1 + z^2/n),
 * clipped to [0, 1].  It stays inside [0, 1] and is not empty at k = 0 or
 * k = n, unlike p -+ z sqrt(p (1 - p)/n).  Returns AUTOBAL_SUCCESS, or
 * AUTOBAL_EINVAL (k > n, n = 0, z not > 0 and finite, low or high NULL; both
 * NaN then where not NULL). */
AUTOBAL_API int autobal_ensemble_wilson_interval(size_t k, size_t n, double z, double *low, double *high);

/* Statistics of quantity k over the members done without failure (status >= 0;
 * a member that did not balance counts with its value at the end of its run).
 * Values that are not finite are counted apart (n_nan) and left out. */
typedef struct autobal_ensemble_stats {
  size_t n;       /* finite values in the statistics                                       */
  size_t n_nan;   /* members done without failure whose value is not finite                */
  double quantile[AUTOBAL_ENSEMBLE_N_QUANTILES]; /* at autobal_ensemble_quantile_probability(i)
                                      by autobal_ensemble_quantile_sorted: [0] min .. [6] max */
  double mean;    /* arithmetic mean                                                        */
} autobal_ensemble_stats;
/* Returns AUTOBAL_SUCCESS (NaNs when n = 0), AUTOBAL_EINVAL (bad k, NULL, or this
 * process keeps no results) or AUTOBAL_ENOMEM. */
AUTOBAL_API int autobal_ensemble_get_stats(const autobal_ensemble *e, size_t k, autobal_ensemble_stats *st);

/* Target i of the settings over the members done without failure: n_within of
 * the n have quantity <= limit (a value that is not finite is not within),
 * p = n_within / n, and its Wilson 95 % interval (z = 1.959963984540054).
 * Random members are independent draws: [low, high] is a 95 % confidence
 * interval of the probability over the sampled box (uniform in each
 * parameter).  On a grid the members are not random: p is the fraction of the
 * grid points (a quadrature of that probability, whose error depends on how
 * the region within the target meets the grid), and the interval is only the
 * one n independent draws would give, not a confidence interval. */
typedef struct autobal_ensemble_target_result {
  size_t quantity;         /* its index k                                                */
  double limit;            /* the settings' limit (the quantity's units)                 */
  size_t n, n_within;
  double p, wilson_low, wilson_high; /* NaN when n = 0                                    */
} autobal_ensemble_target_result;
/* Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (bad i, NULL, no results kept). */
AUTOBAL_API int autobal_ensemble_get_target(const autobal_ensemble *e, size_t i, autobal_ensemble_target_result *r);

/* ---- attractors (added in 0.3.0, issue 17) ----------------------------------------------------- */

/* A member's summary with a classifying member ends with AUTOBAL_ENSEMBLE_N_ATTRACTOR doubles
 * from autobal_ensemble_attractor_index(e) on: the class (enum autobal_attractor_class, 0 for a
 * failed member), the circulation frequency nu (rad/s) and the nearest natural frequency (rad/s;
 * both NaN unless CIRCULATING).  The index is (size_t)-1 when the member does not classify. */
#define AUTOBAL_ENSEMBLE_N_ATTRACTOR 3
AUTOBAL_API size_t autobal_ensemble_attractor_index(const autobal_ensemble *e);
/* Members of each class among the done ones (count[c], c < AUTOBAL_ATTRACTOR_N_CLASSES; failed
 * members count as UNCLASSIFIED), and over the CIRCULATING ones the smallest and the largest
 * frequency nu and ratio nu / natural frequency (NaN when there is none; any of them may be NULL).
 * Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (e or count NULL, the member does not classify, or
 * this process keeps no results). */
typedef struct autobal_ensemble_attractors {
  size_t count[AUTOBAL_ATTRACTOR_N_CLASSES];
  double frequency_min, frequency_max;  /* rad/s                                 */
  double ratio_min, ratio_max;          /* nu / natural frequency, 1            */
} autobal_ensemble_attractors;
AUTOBAL_API int autobal_ensemble_get_attractors(const autobal_ensemble *e, autobal_ensemble_attractors *a);

/* ---- the archive ---------------------------------------------------------------------------- */


/* How the run went (the only part of the archive that depends on it). */
typedef struct autobal_ensemble_execution {
  int ranks;          /* processes                        */
  int threads;        /* threads per process              */
  double wall_time;   /* s                                */
  int mpi_build;      /* 1: the program was built with MPI */
} autobal_ensemble_execution;

/* Write the ensemble (the writer process, results kept) into archive a:
 * first write_model(user, a) (the model's own parameter group, e.g. /rotor;
 * NULL: none), then /<model>/ensemble: the settings and tally as attributes,
 * the parameter axes (grid: coordinates, with two axes or more each with the
 * attribute probability_balanced: at each point of the axis, balanced /
 * members done without failure, over the other axes; random: a member
 * dimension and one variable per parameter), the summaries (status, balanced, done,
 * time_to_balance, residual_unbalance_initial/final, amplitude_max/final,
 * t_reached, steps, rhs_evaluations, final_angle), the kept series under
 * series/member_<m>, and execution/.  Added in 0.2.0: the attributes
 * probability_balanced_wilson_low/high (autobal_ensemble_wilson_interval);
 * with member quantities, a group statistics/<quantity> each (attributes
 * long_name, units, n, n_not_finite, min, q05, q25, median, q75, q95, max,
 * mean, quantile_definition; with a target on it also target, n_evaluated,
 * n_within_target, probability_within_target, its _wilson_low/_wilson_high and
 * probability_definition), and, only when settings.write_quantities is set,
 * each quantity as a per-member variable (so that a configuration of 0.1.0
 * writes exactly its datasets of 0.1.0: tests/app/rerun_old.sh).  Members not done are NaN (0 for the
 * integer variables, done = 0).  Returns AUTOBAL_SUCCESS, write_model's
 * status, or the archive's (message in e); what was written stays. */
AUTOBAL_API int autobal_ensemble_write(autobal_ensemble *e, autobal_archive *a,
                                       int (*write_model)(void *user, autobal_archive *a),
                                       void *user, const autobal_ensemble_execution *exec);

AUTOBAL_END_DECLS

#endif
