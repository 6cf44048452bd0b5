/* autobal/study.h: whole runs ("studies") as the command line runs them, for
 * programs that embed the library.
 *
 * A study takes the model's parameter struct and an options struct (SI units,
 * documented field by field), runs the analysis and returns its summary as a
 * plain struct.  Given an open archive (autobal_archive_create), it also
 * writes the same groups, datasets, dimension scales, units and attributes
 * that the `autobal` program writes for the same inputs, so that
 * `autobal info`, `autobal plot` and h5py/xarray readers work on the file.
 * The program is a thin client of these calls: `autobal rotor transient`
 * reads its configuration, fills the structs, calls
 * autobal_study_rotor_transient() and prints the summary.
 *
 * Archive ownership.  The caller creates the archive, may write provenance
 * (autobal_archive_provenance) and attributes of its own, and closes it
 * (autobal_archive_close) after the study returned, whatever the study
 * returned: what was written stays readable.  A study never closes, discards
 * or sets the status of the archive; after a failure a caller usually calls
 * autobal_archive_set_status(a, "incomplete", reason) before closing.  The
 * study closes the streamed series it opened before it returns.  Passing a
 * NULL archive runs the study without writing anything.
 *
 * Errors.  Every call returns an autobal status (status.h): AUTOBAL_SUCCESS,
 * or a negative code with a message in err (may be NULL).  Messages about the
 * model's parameters name the struct fields (e.g. "plane[0].ball_mass[1]"),
 * messages about the options start with "options: " and name the option field.
 * Nothing is printed, nothing aborts.  A host program should call
 * gsl_set_error_handler_off() once.
 *
 * Threads.  Studies keep no global state; two threads may run two studies at
 * once (with two archives; one archive handle is not shared between threads).
 */
#ifndef AUTOBAL_STUDY_H
#define AUTOBAL_STUDY_H

#include <stddef.h>

#include "autobal/export.h"
#include "autobal/status.h"
#include "autobal/rotor.h"
#include "autobal/rotor_stability.h"
#include "autobal/rotor_asymptotic.h"
#include "autobal/runup.h"
#include "autobal/pendulum.h"
#include "autobal/transient.h"
#include "autobal/archive.h"

AUTOBAL_BEGIN_DECLS

/* ---- progress and cancellation ----------------------------------------------- */

/* Progress of a study: fraction done in [0, 1], non-decreasing, with `user`
 * as given in the options.  Return non-zero to cancel: the study stops at the
 * next check and returns AUTOBAL_ECANCELLED with what was computed so far
 * written and summarised.  Called from the thread that runs the study. */
typedef int (*autobal_study_progress_fn)(double fraction, void *user);

/* The rotor model's parameter-field tables (autobal_rotor_field, autobal_rotor_hardware_fields,
 * autobal_rotor_lumped_fields) are declared in autobal/rotor.h. */

/* ---- shared archive writers ---------------------------------------------------- */

/* Write the rotor model *p: group /rotor (attributes model, input, inertia,
 * omega, axial and, for hardware input, the 17 hardware fields), /rotor/lumped
 * (the 17 lumped coefficients the model uses: (2.7)-(2.11) from the hardware
 * for hardware input) and /rotor/plane<j> (d, m0, r0, psi0, n_balls,
 * ball_mass, ball_radius, ball_damping; with `initial` non-zero also
 * ball_psi_initial and ball_rate_initial where the arrays are given).  Every
 * attribute with its SI unit (attribute <name>_units).  Returns
 * AUTOBAL_SUCCESS; AUTOBAL_EINVAL (bad hardware values: nothing written; or a
 * bad archive name), AUTOBAL_EIO (HDF5; the message in autobal_archive_errmsg);
 * what was written before a failure stays. */
AUTOBAL_API int autobal_study_write_rotor_params(autobal_archive *a, const autobal_rotor_params *p, int initial);

/* Write the pendulum parameters: /pendulum (model, R_w, R_m, H, h (units "1"),
 * psi0 (rad), k (units "1")) and, when `phys` is not NULL, /pendulum/physical
 * (M kg, e m, m kg, l m, c N/m, H1 N m s, H2 N s/m, omega rad/s and
 * omega0 = sqrt(c/(M + 2m)) rad/s).  Returns an autobal status (the archive's
 * message in autobal_archive_errmsg). */
AUTOBAL_API int autobal_study_write_pendulum_params(autobal_archive *a, const autobal_pendulum_params *p,
                                                    const autobal_pendulum_physical *phys);

/* Write a transient driver's statistics as attributes of `group` (created):
 * stepper, steps, rejected_steps, rhs_evaluations, jacobian_evaluations,
 * wall_time (s), h_min_used and h_max_used (in `time_unit`: "s", or "1" for a
 * dimensionless time), stop_reason, message (`message`; NULL: "").  `stepper`
 * NULL: "rk8pd".  Returns an autobal status (the archive's message in
 * autobal_archive_errmsg). */
AUTOBAL_API int autobal_study_write_solver_stats(autobal_archive *a, const char *group, const char *stepper,
                                                 const autobal_transient_stats *stats, const char *message,
                                                 const char *time_unit);

/* ---- ISO 21940-11 balance quality ---------------------------------------------- */

/* Balance quality grade G = e omega in mm/s of a residual unbalance U (kg m)
 * of a rotor of mass m (kg) at speed omega (rad/s): U/m omega 1e3. */
AUTOBAL_API double autobal_balance_grade(double U, double m, double omega);
/* Permissible residual unbalance U_per (kg m) of grade G (mm/s): G 1e-3 m/omega. */
AUTOBAL_API double autobal_permissible_unbalance(double G, double m, double omega);
/* The smallest ISO 21940-11 grade class (0.4, 1, 2.5, 6.3, ..., 4000 mm/s)
 * that G (mm/s) is within; NaN above G4000 or for NaN. */
AUTOBAL_API double autobal_balance_grade_class(double G);

/* ---- rotor transient ---------------------------------------------------------- */

/* Tolerances tighter than this (rtol < 1e-10, the default rtol) integrate a FIXED-frame rotor
 * transient with the ball angles relative to the rotor angle phi_0(t) (the rotating-frame state
 * and right-hand side, autobal_rotor_rhs_rotating), and the fixed-frame state is reconstructed at
 * every output as phi = phi_0(t) + psi, phi' = Omega + psi' (autobal_rotor_convert_state): the
 * absolute angles (|phi| ~ omega t, thousands of rad) carry a rounding of ulp(phi) ~ 5e-13 rad at
 * every step, which below rtol ~ 1e-11 sets the step count (growing ~4x per decade of rtol
 * instead of 10^(1/8)) and the accuracy (docs/rotor.md, "How the ball angles are integrated").
 * At rtol >= 1e-10 the fixed frame integrates the absolute angles as before (bit for bit; a tight
 * atol there still meets the rounding, see the documentation). */
#define AUTOBAL_STUDY_ROTOR_RELATIVE_RTOL 1e-10

/* Options of a rotor transient (`autobal rotor transient`, section [transient]
 * and [balance] of its configuration).  With a prescribed speed profile
 * (autobal_rotor_params.drive a ramp or table), omega below is the largest |Omega|
 * of the profile (autobal_rotor_drive_speed_max): it sets the default output
 * interval and the revolutions counted by balance_revs and /rotor/revolutions. */
typedef struct autobal_study_rotor_transient_options {
  double t_end;         /* s, end of the run (starts at t = 0), > 0                  (default 20) */
  double dt_out;        /* s, output interval of the time series, > 0, at most
                           5e8 samples; 0: a quarter revolution 0.25 2 pi/|omega|     (default 0) */
  double rtol, atol;    /* relative and absolute tolerance of the stepper
                                                                     (default 1e-10, 1e-9) */
  double h_max;         /* s, largest step, >= 0; 0: unlimited                        (default 0) */
  unsigned long max_steps; /* accepted steps, >= 1                                  (default 1e8) */
  const char *stepper;  /* stepper name (autobal_transient_stepper_names()); NULL: "rk8pd"
                           (the engine's default); the string is only read during the call
                                                            (default "dop853"; until 0.2.0 NULL) */
  int frame;            /* AUTOBAL_ROTOR_FIXED or AUTOBAL_ROTOR_ROTATING: the frame of
                           the ball angles in the outputs (state datasets, state_final);
                           FIXED with rtol < AUTOBAL_STUDY_ROTOR_RELATIVE_RTOL is integrated
                           with the angles relative to the rotor (see there)    (default FIXED) */
  double balance_tol;   /* the rotor counts as balanced when the largest relative
                           residual unbalance |s_j|/(m_j0 r_j0) of the planes stays below
                           this (autobal_rotor_balance_monitor), > 0             (default 0.01) */
  double balance_revs;  /* ... for this many revolutions 2 pi/|omega|, >= 0       (default 50) */
  int stop_at_balance;  /* non-zero: stop the run once balanced                     (default 0) */
  double grade;         /* ISO 21940-11 grade (mm/s) to check the final residual
                           unbalance against, > 0; NaN: none                    (default NaN) */
  autobal_study_progress_fn progress; /* NULL: none                              (default NULL) */
  void *progress_user;  /* passed to progress                                  (default NULL) */
  /* run-up outputs (drives other than constant; autobal_runup_options, the tolerance of the time
     to balance after the last resonance passage is balance_tol above) */
  double capture_band;  /* 1, relative half-width of the band around each resonance speed, (0, 1)
                                                                                 (default 0.05) */
  double capture_time;  /* s, a stay in the band this long is a capture, (0, inf)    (default 2) */
  int exact_output;     /* 1: output times and the balance monitor hit exactly (steps cut there);
                           0: on the stepper's continuous extension when it has one (dop853;
                           autobal_transient_options.exact_output)                (default 0) */
  int dense_order;      /* 7 or 6 (0: 7): the continuous extension of that dense output
                           (autobal_transient_options.dense_order)    (default 6; until 0.2.0 0) */
} autobal_study_rotor_transient_options;

/* The defaults listed above. */
AUTOBAL_API autobal_study_rotor_transient_options autobal_study_rotor_transient_options_default(void);

/* Summary of a rotor transient.  Plain data, plus arrays owned by the summary
 * and released by autobal_study_rotor_transient_summary_free().  Vibration
 * figures refer to the synchronous (1X) response: per direction x, y the
 * largest amplitude sqrt(u^2 + (u'/omega)^2) over the samples of the last 10%
 * of the run (exact for a steady whirl at any sampling).  With a drive, omega is
 * |Omega(t)| at each sample (the largest |Omega| where it is 0), and the balance
 * grade and RMS velocity use |Omega(t_reached)| (the largest where that is 0);
 * ball_psi_final is relative to phi_0(t_reached). */
typedef struct autobal_study_rotor_transient_summary {
  int balanced;                    /* 1: the balance criterion held (options.balance_*) */
  double time_to_balance;          /* s, when |s|/(m0 r0) went below balance_tol for good; NaN: not balanced */
  double t_reached;                /* s, the time of the final state (t_end unless stopped early) */
  double revolution_period;        /* s, 2 pi/|omega| (with a drive: at its largest |Omega|) */
  size_t n_planes;                 /* balancer planes (1 or 2) */
  size_t n_balls[AUTOBAL_ROTOR_MAX_PLANES]; /* balls of each plane */
  double residual_unbalance_initial; /* 1, largest |s_j|/(m_j0 r_j0) over the planes at t = 0 (plane 1's) */
  double residual_unbalance_final;   /* 1, the balance monitor at t_reached */
  double residual_unbalance_abs_final[AUTOBAL_ROTOR_MAX_PLANES]; /* kg m, |s_j| of each plane at the end */
  double residual_unbalance_rel_final[AUTOBAL_ROTOR_MAX_PLANES]; /* 1, |s_j|/(m_j0 r_j0); NaN when m_j0 r_j0 = 0 */
  double amplitude_first_10pct_max; /* m, largest sampled amplitude of the centre of mass for t <= 0.1 t_end */
  double amplitude_last_10pct_max;  /* m, the same for t >= 0.9 t_end; NaN if not reached */
  double amplitude_max;             /* m, over the whole run */
  /* ISO 21940-11 (the rotor mass shared equally by the planes; the worst plane counts) */
  double balance_grade_rotor_mass;  /* kg, m_p (hardware input) or M (lumped input) */
  double balance_grade_final;       /* mm/s, grade of the final residual unbalance n_planes max_j |s_j| */
  double balance_grade_class;       /* mm/s, smallest grade class it is within; NaN above G4000 */
  double permissible_unbalance;     /* kg m, U_per of options.grade (whole rotor); NaN: no grade given */
  int permissible_unbalance_met;    /* 1: n_planes max_j |s_j| <= U_per */
  int have_vibration_window;        /* 1: samples in the last 10% exist (else the next three are NaN) */
  double displacement_pk_pk[3];     /* m, 1X peak-to-peak (largest of x, y): [0] centre of mass,
                                       [1] left support, [2] right support (NaN with lumped input) */
  double velocity_rms[3];           /* m/s, 1X RMS velocity omega A/sqrt(2), same points */
  double velocity_rms_supports;     /* m/s, largest of the supports' (the centre of mass's with lumped input) */
  /* ball angles relative to the rotor, wrapped to [-pi, pi] (remainder by 2 pi), per plane;
   * NULL for a plane without balls */
  double *ball_psi_final[AUTOBAL_ROTOR_MAX_PLANES];     /* rad, at t_reached */
  double *ball_psi_balanced[AUTOBAL_ROTOR_MAX_PLANES];  /* rad, the balanced configuration (3.14);
                                                           NULL when none exists */
  size_t dim;                       /* length of state_final */
  double *state_final;              /* the state at t_reached in options.frame (rotor.h) */
  autobal_transient_stats solver;   /* statistics of the driver */
  char stepper[32];                 /* the stepper's name */
  char solver_message[AUTOBAL_ERRMSG_SIZE]; /* the driver's last message ("" after success) */
  int warning;                      /* 1: autobal_rotor_params_check warned (a plane cannot be balanced) */
  char warning_message[AUTOBAL_ERRMSG_SIZE];  /* its message (struct field names) */
  /* run-up outputs (autobal_runup_analyze on the sampled series), for a drive other than constant
     (the series has an "Omega" column); have_runup = 0 and the pointers NULL otherwise.  The
     resonances are the Campbell crossings (natural frequency = Omega) of the rotor-housing
     (autobal_rotor_resonance_speeds, 400 grid points) in [0, (1 + capture_band) max |Omega|].
     The study keeps t, Omega, amp_G, the monitor and each ball's psi of every sample in memory
     for it ((4 + balls) doubles per sample; AUTOBAL_ENOMEM if that fails, after the rest of the
     archive was written). */
  int have_runup;
  autobal_runup_result runup;       /* scalar results: passages, captures, time to balance after the
                                       last passage (balance_tol), the envelope's maximum */
  size_t n_resonances;
  double *resonance_speed;          /* [n_resonances] rad/s, increasing */
  int *resonance_whirl;             /* [n_resonances] +1 forward, -1 backward, 0 undecided */
  autobal_runup_passage *passages;  /* [runup.n_passages], in time order */
  autobal_runup_capture *captures;  /* [runup.n_captures], by resonance, then time */
  /* friction (added in 0.3.0): with the EXACT law (autobal_rotor_friction) have_friction = 1 and
     the stick-slip switches counted over the run (the settling of the initial state not
     counted); 0 and NULL otherwise */
  int have_friction;
  unsigned long friction_sticks;    /* a slipping ball stuck (its psi' reached 0 with |H| <= mu N) */
  unsigned long friction_slips;     /* a stuck ball broke free (|H| > mu N) */
  unsigned long friction_reversals; /* psi' reached 0 but |H| > mu N: the ball slipped on, reversed */
  double *ball_time_stuck[AUTOBAL_ROTOR_MAX_PLANES];  /* s, time each ball spent stuck, per plane */
  int *ball_stuck_final[AUTOBAL_ROTOR_MAX_PLANES];    /* 1: the ball is stuck at t_reached */
  /* gravity (docs/device.md section 2; p.gravity = 1, else the offset is 0 and the ratios NaN): the
     static offset q_s (autobal_rotor_static_offset: m, m, rad, rad) and per plane
     g sin(theta) / (r Omega^2) at |Omega(t_reached)| (autobal_rotor_gravity_ratio; < 1: the balls
     are carried round) */
  double static_offset[4];
  double gravity_ratio_final[AUTOBAL_ROTOR_MAX_PLANES];
  /* ball size and contact (docs/device.md section 4; p.contact.on = 1, else have_contact = 0 and
     the rest 0): impacts over the run (a plastic one that joins a pair counted too), pairs joined
     into resting contact and released, touching pairs (clusters) at t_reached; per plane the
     largest resultant the sizes allow (autobal_rotor_contact_capacity, kg m) and whether the
     unbalance is within it (1) or the balanced angles are out of reach (0) */
  int have_contact;
  unsigned long contact_impacts;
  unsigned long contact_joins;
  unsigned long contact_releases;
  unsigned long contacts_final;
  double contact_capacity[AUTOBAL_ROTOR_MAX_PLANES];
  int contact_reachable[AUTOBAL_ROTOR_MAX_PLANES];
  /* the layout of state_final (added in 0.3.0 at the end of the struct), for
     autobal_study_rotor_transient_state_name: its frame (autobal_rotor_frame: ball angles phi
     absolute or psi relative to the rotor), 1 when (z, z') follow the balls, 1 when a MOTOR's
     (phi_0, Omega) are the last two entries */
  int state_frame;
  int state_axial;
  int state_motor;
} autobal_study_rotor_transient_summary;

/* Name and SI unit of entry k < summary->dim of summary->state_final: "x", "y", "alpha",
 * "beta", "x_rate", "y_rate", "alpha_rate", "beta_rate" (m, m, rad, rad, m/s, m/s, rad/s,
 * rad/s); then per ball in state order (plane by plane) "phi_<n>" (frame fixed: absolute
 * angle) or "psi_<n>" (rotating: relative to the rotor), rad, then "phi_rate_<n>" or
 * "psi_rate_<n>", rad/s, n = 1 .. N; then "z", "z_rate" (axial) and "phi_0", "Omega" (motor).
 * The name is written to buf (len >= 32 is enough); *unit (may be NULL) gets a static string.
 * Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL summary or buf, k >= dim, len too short). */
AUTOBAL_API int autobal_study_rotor_transient_state_name(const autobal_study_rotor_transient_summary *summary,
                                                         size_t k, char *buf, size_t len, const char **unit);

/* Check the inputs of a rotor transient without running it (and without
 * touching an archive): the parameters (autobal_rotor_alloc), the initial
 * state and the options.  Returns AUTOBAL_SUCCESS, AUTOBAL_WARNING (runnable;
 * the warning of autobal_rotor_params_check in err) or a failure (AUTOBAL_EINVAL,
 * AUTOBAL_ENOMEM) with the message in err.  A program that creates its archive
 * only for valid inputs calls this first. */
AUTOBAL_API int autobal_study_rotor_transient_check(const autobal_rotor_params *p,
                                                    const autobal_study_rotor_transient_options *opt,
                                                    autobal_error *err);

/* Run a rotor transient from the initial state of *p (q0, qd0, the balls'
 * ball_psi/ball_rate, z0, zd0) over [0, t_end] with the balance criterion as a
 * dwell event.  opt NULL: defaults.  With an archive `a` (NULL: none) it writes
 *   /rotor, /rotor/lumped, /rotor/plane<j>      autobal_study_write_rotor_params(initial = 1),
 *                                               plus ball_psi_balanced (rad) where (3.14) has a solution
 *   /rotor/transient                            options (t_end, dt_out, rtol, atol, h_max, max_steps,
 *                                               initial_q, initial_q_rate, balance_tol, balance_revs,
 *                                               stepper, frame), then the summary (time_to_balance,
 *                                               balanced, t_reached, residual_unbalance_*,
 *                                               amplitude_*, balance_grade_*, permissible_unbalance*,
 *                                               displacement/velocity figures)
 *   /rotor/transient/<var>(time)                the state and autobal_rotor_outputs every dt_out
 *   /rotor/revolutions/<var>(revolution_end)    per-revolution maxima
 *   /rotor/transient/solver                     autobal_study_write_solver_stats
 *   /rotor/runup                                with a drive other than constant (an Omega column):
 *                                               the resonances, passages, captures, time to balance
 *                                               after the last passage, envelope(time),
 *                                               ball_lag(time, ball), ball_lag_rate(time, ball)
 *                                               (docs/device.md, "Run-up outputs")
 * `summary` (may be NULL) is filled (zeroed first; release it with
 * autobal_study_rotor_transient_summary_free even after a failure).
 * Returns AUTOBAL_SUCCESS (also when the run stopped at balance);
 * AUTOBAL_WARNING never (see summary->warning); a failure of the inputs
 * (as autobal_study_rotor_transient_check: nothing written, summary zeroed);
 * AUTOBAL_ECANCELLED (the progress callback asked to stop); a failure of the
 * integration (AUTOBAL_ESTEP, AUTOBAL_EMAXSTEPS, AUTOBAL_ERHS,
 * AUTOBAL_ENUMERIC: message from the driver); AUTOBAL_EIO or another archive
 * status when writing failed (message from the archive; "writing the time
 * series failed: ..." for the series).  After a cancellation or a failure of
 * the integration the summary describes the run up to summary->t_reached and
 * the archive holds the series and the summary attributes up to there. */
AUTOBAL_API int autobal_study_rotor_transient(const autobal_rotor_params *p,
                                              const autobal_study_rotor_transient_options *opt,
                                              autobal_archive *a,
                                              autobal_study_rotor_transient_summary *summary,
                                              autobal_error *err);

/* Release the arrays of a summary and set their pointers to NULL (NULL or a
 * zeroed summary: nothing). */
AUTOBAL_API void autobal_study_rotor_transient_summary_free(autobal_study_rotor_transient_summary *summary);

/* ---- rotor stability ------------------------------------------------------------ */

/* Options of a rotor stability analysis (`autobal rotor stability`, section [stability]). */
typedef struct autobal_study_rotor_stability_options {
  autobal_rotor_stab_options stab; /* method, verdict tolerance, Floquet tolerances, the analysed
                                      member of each plane (rotor_stability.h; the member angles
                                      are only read during the call)
                                                          (default autobal_rotor_stab_options_default()) */
  int critical_speeds;  /* non-zero: also search the critical speeds                (default 1) */
  double omega_min, omega_max; /* rad/s, the speed range of the search, 0 < omega_min < omega_max,
                           on the side of omega's sign (a negative omega searches [-omega_max,
                           -omega_min]); NaN: autobal_study_rotor_speed_range()   (default NaN, NaN) */
  size_t n_omega;       /* grid points of the search, in [2, 1e7]                 (default 400) */
  double xtol_rel;      /* relative accuracy of each critical speed, in (0, 0.1)  (default 1e-8) */
  autobal_study_progress_fn progress; /* fraction of the critical-speed search; non-zero: cancel
                           (polled before every margin evaluation)             (default NULL) */
  void *progress_user;                                                       /* (default NULL) */
  /* every unbalance in a range (one plane, two balls or n >= 3 identical balls with
     stab.unbalance_member = SYMMETRIC, or three to ten with EVERY; autobal_rotor_stab_every_unbalance; added at
     the end): non-zero = analyse m0 r0 in [unbalance_min, unbalance_max] (kg m) at omega and, with
     critical_speeds, the speeds stable for all of them            (default 0, NaN, NaN) */
  int every_unbalance;
  double unbalance_min, unbalance_max;
  /* two planes (added at the end; autobal_rotor_stab_every_unbalance2): plane 2's range (NaN: the
     same as plane 1's) and the grid points per plane of the magnitudes, in [2, 1000]
                                                                   (default NaN, NaN, 9) */
  double unbalance2_min, unbalance2_max;
  size_t n_unbalance;
} autobal_study_rotor_stability_options;

/* The defaults listed above. */
AUTOBAL_API autobal_study_rotor_stability_options autobal_study_rotor_stability_options_default(void);

/* The default speed range of critical-speed searches: from 5% of the lowest natural frequency
 * at rest (autobal_rotor_modes) to 4 times the larger of the highest one and |omega|, rad/s. */
AUTOBAL_API void autobal_study_rotor_speed_range(const autobal_rotor_params *p, double *lo, double *hi);

/* Summary of a rotor stability analysis.  `result`'s pointers (psi, full_re, full_im, mu_re,
 * mu_im) point into arrays owned by the summary (autobal_study_rotor_stability_summary_free). */
typedef struct autobal_study_rotor_stability_summary {
  autobal_rotor_stab_result result; /* autobal_rotor_stab_analyze at p->omega */
  int have_critical;                /* 1: `critical` holds the search (options.critical_speeds) */
  autobal_rotor_crit critical;      /* critical speeds in rad/s (signed like omega) */
  double omega_min, omega_max;      /* rad/s, the range searched (positive, as in the options) */
  size_t n_omega;                   /* its grid points */
  int warning;                      /* 1: the parameters drew a warning (warning_message) */
  char warning_message[AUTOBAL_ERRMSG_SIZE];
  int critical_truncated;           /* 1: more critical speeds than AUTOBAL_ROTOR_MAX_CRIT
                                       (critical.truncated; critical_message says so) */
  char critical_message[AUTOBAL_ERRMSG_SIZE];
  double *storage_;                 /* the arrays behind result's pointers (private) */
  int critical_cancelled;           /* 1: the critical-speed search was cancelled (have_critical = 0;
                                       the analysis at omega in `result` is complete) */
  /* every unbalance (options.every_unbalance; added at the end) */
  int have_every;                   /* 1: `every` holds the analysis at omega */
  autobal_rotor_unbalance_range every;
  int have_every_speeds;            /* 1: `every_speeds` holds the speeds stable for every unbalance */
  autobal_rotor_crit every_speeds;  /* rad/s (signed like omega) */
  /* asymptotic conditions at omega (added at the end; autobal/rotor_asymptotic.h): computed when
     Delta exists (one plane, isotropic, closure) and kappa > 0; written to
     /rotor/stability/asymptotic */
  int have_asymptotic;
  autobal_rotor_asymptotic asymptotic;
  /* two planes, every unbalance (added at the end): `every2` the grid of magnitudes with every
     phase (then `every` holds its verdict only: no critical unbalances, one sub-interval);
     `every_phase` the critical phases at the configuration's own m0 r0 of both planes (when they
     lie where the balls balance off a line) */
  int have_every2;
  autobal_rotor_unbalance_range2 every2;
  int have_every_phase;
  autobal_rotor_phase_range every_phase;
  /* two planes: the light-ball asymptotic condition at omega (added at the end;
     autobal_rotor_asymptotic2_conditions): computed for two planes with the closure and kappa_j > 0;
     written to /rotor/stability/asymptotic2 */
  int have_asymptotic2;
  autobal_rotor_asymptotic2 asymptotic2;
  /* two planes, the speeds for every unbalance (added at the end): per grid speed, stable interval
     and critical speed whether plane 2's range was decided exactly
     (autobal_rotor_stab_every_unbalance2_speeds_detail); its grid arrays have every_speeds2_n
     entries, owned by the summary */
  int have_every_speeds2;
  autobal_rotor_speeds2_detail every_speeds2;
  size_t every_speeds2_n;
  void *every_speeds2_storage_;     /* private */
} autobal_study_rotor_stability_summary;

/* Analyse the balanced motion of the rotor *p at its speed p->omega (non-zero): every
 * applicable method (autobal_rotor_stab_analyze), and with options.critical_speeds the
 * critical speeds in the range (autobal_rotor_stab_critical).  opt NULL: defaults.  With an
 * archive (NULL: none) the result is written afterwards by
 * autobal_study_rotor_stability_write.  `summary` (not NULL) is zeroed first; release it with
 * autobal_study_rotor_stability_summary_free, also after a failure.
 * Returns AUTOBAL_SUCCESS; AUTOBAL_EINVAL (bad parameters or options, omega = 0, no balanced
 * configuration: messages name the field, options as "options: ..."), AUTOBAL_ENOMEM,
 * AUTOBAL_ENUMERIC or an integration status of the Floquet analysis; "critical speeds: ..."
 * for a failure of the search; an archive status when writing failed.  Nothing is written to
 * the archive unless the analysis succeeded.  AUTOBAL_ECANCELLED when options.progress asked to
 * stop during the critical-speed search: the analysis at omega is complete in `result`,
 * critical_cancelled = 1, have_critical = 0, and with an archive the result is written (with
 * the attributes partial = 1 and partial_what on /rotor/stability, no critical group). */
AUTOBAL_API int autobal_study_rotor_stability(const autobal_rotor_params *p,
                                              const autobal_study_rotor_stability_options *opt,
                                              autobal_archive *a,
                                              autobal_study_rotor_stability_summary *summary,
                                              autobal_error *err);

/* Write an analysis (summary of a successful autobal_study_rotor_stability with the same p and
 * opt) into the archive: /rotor, /rotor/lumped, /rotor/plane<j> (autobal_study_write_rotor_params
 * with initial = 0, plus the analysed member and member_angles), /rotor/stability (options,
 * method, verdict, margin, period, isotropic, closure_ok, n_family, psi_balanced(ball), the
 * roots root_real/root_imag/eig_real/eig_imag(root), char_poly(power), full_real/full_imag
 * (full_root), floquet_real/floquet_imag(multiplier) where computed) and
 * /rotor/stability/critical (omega_min, omega_max, n_omega, critical_value/critical_kind
 * (critical), stable_lo/stable_hi(interval)).  Returns an autobal status (the archive's
 * message in autobal_archive_errmsg). */
AUTOBAL_API int autobal_study_rotor_stability_write(autobal_archive *a, const autobal_rotor_params *p,
                                                    const autobal_study_rotor_stability_options *opt,
                                                    const autobal_study_rotor_stability_summary *summary);

/* Release the arrays of a summary (NULL or zeroed: nothing); result's pointers become NULL. */
AUTOBAL_API void autobal_study_rotor_stability_summary_free(autobal_study_rotor_stability_summary *summary);

/* ---- pendulum transient --------------------------------------------------------- */

/* Options of a pendulum transient (`autobal pendulum transient`, sections [initial] and
 * [transient]).  Times are dimensionless: tau = omega0 t, one revolution lasts 2 pi/R_w. */
typedef struct autobal_study_pendulum_transient_options {
  double y0[8];         /* initial state (xi, eta, psi, phi, xi', eta', psi', phi'): lengths in l,
                           angles in rad, rates per unit tau; finite   (default 0: at rest, the
                           pendulums opposite each other along V) */
  double t_end;         /* end of the run in tau, > 0                             (default 300) */
  double dt_out;        /* output interval in tau, > 0; 0: revs_out revolutions     (default 0) */
  double revs_out;      /* output interval in revolutions when dt_out = 0 (needs R_w > 0), > 0
                                                                                   (default 0.25) */
  double rtol, atol;    /* tolerances of the stepper                  (default 1e-10, 1e-12) */
  double h_max;         /* largest step in tau, >= 0; 0: unlimited                  (default 0) */
  unsigned long max_steps; /* accepted steps, >= 1                                (default 1e8) */
  const char *stepper;  /* stepper name; NULL: "rk8pd" (the engine's default; only read during the
                           call)                                 (default "dop853"; until 0.2.0 NULL) */
  double balance_tol;   /* balanced: the residual unbalance |d| (units of 2 m l) stays below
                           this, > 0                                               (default 1e-3) */
  double balance_revs;  /* ... for this many revolutions, >= 0 (> 0 needs R_w > 0) (default 20) */
  int stop_at_balance;  /* non-zero: stop once balanced                             (default 0) */
  autobal_study_progress_fn progress; /* NULL: none                              (default NULL) */
  void *progress_user;                                                       /* (default NULL) */
  int exact_output;     /* 1: output times and the balance monitor hit exactly (steps cut there);
                           0: on the stepper's continuous extension when it has one (dop853;
                           autobal_transient_options.exact_output)                (default 0) */
  int dense_order;      /* 7 or 6 (0: 7): the continuous extension of that dense output
                           (autobal_transient_options.dense_order)    (default 6; until 0.2.0 0) */
} autobal_study_pendulum_transient_options;

AUTOBAL_API autobal_study_pendulum_transient_options autobal_study_pendulum_transient_options_default(void);

/* Summary of a pendulum transient (plain data, nothing to release); dimensionless like the
 * model (lengths in l, unbalance in 2 m l, time in tau). */
typedef struct autobal_study_pendulum_transient_summary {
  int balanced;               /* 1: the balance criterion held */
  double time_to_balance;     /* tau when |d| went below balance_tol for good; NaN: not balanced */
  double t_reached;           /* tau of the final state */
  double revolution_period;   /* 2 pi/R_w in tau (inf for R_w = 0) */
  double dt_out, revs_out;    /* the output interval used, in tau and revolutions (NaN for R_w = 0) */
  double final_state[8];      /* the state at t_reached */
  double unbalance_initial, unbalance_final;   /* |d| at the first sample and at the end */
  double amplitude_initial, amplitude_max, amplitude_final; /* shaft amplitude sqrt(xi^2 + eta^2) */
  double alpha_final, beta_final; /* rad, pendulum angles minus psi0 at the end, wrapped */
  int have_linear_verdict;    /* 1: linear_verdict holds autobal_pendulum_verdict of p */
  int linear_verdict;         /* AUTOBAL_VERDICT_* of the main motion (4) by (6) */
  autobal_transient_stats solver; /* statistics of the driver */
  char stepper[32];               /* the stepper's name */
  char solver_message[AUTOBAL_ERRMSG_SIZE]; /* the driver's last message */
} autobal_study_pendulum_transient_summary;

/* Check the inputs without running (parameters by autobal_pendulum_motion_init: message as the
 * model's; the initial state: "initial state: ..."; the options: "options: ...").  Returns
 * AUTOBAL_SUCCESS or a failure with the message in err. */
AUTOBAL_API int autobal_study_pendulum_transient_check(const autobal_pendulum_params *p,
                                                       const autobal_study_pendulum_transient_options *opt,
                                                       autobal_error *err);

/* Integrate the equations of motion (1) from options.y0 over [0, t_end] (tau) with the balance
 * criterion as a dwell event.  opt NULL: defaults.  phys (NULL: none) are the physical
 * parameters p came from (autobal_pendulum_params_from_physical): they are recorded in the
 * archive with the time and length units.  With an archive (NULL: none) it writes
 *   /pendulum (+ /pendulum/physical)       autobal_study_write_pendulum_params
 *   /pendulum/transient                    options (t_end, dt_out, revs_out, rtol, atol, h_max,
 *                                          balance_tol, balance_revs, stepper, initial_state,
 *                                          state_order; time_unit (s) and length_unit (m) with
 *                                          phys), then the summary (time_to_balance, balanced,
 *                                          t_reached, final_state, unbalance_initial/final,
 *                                          amplitude_max, alpha_final, beta_final, linear_verdict)
 *   /pendulum/transient/<var>(tau)         the state, amplitude, unbalance (+ components), alpha,
 *                                          beta, jacobi every dt_out
 *   /pendulum/transient/solver             autobal_study_write_solver_stats (time unit "1")
 * `summary` (may be NULL) is zeroed first.  Returns like autobal_study_rotor_transient:
 * AUTOBAL_SUCCESS, an input failure (nothing written), AUTOBAL_ECANCELLED, a failure of the
 * integration (summary and archive hold the run up to t_reached), or an archive status. */
AUTOBAL_API int autobal_study_pendulum_transient(const autobal_pendulum_params *p,
                                                 const autobal_pendulum_physical *phys,
                                                 const autobal_study_pendulum_transient_options *opt,
                                                 autobal_archive *a,
                                                 autobal_study_pendulum_transient_summary *summary,
                                                 autobal_error *err);

/* ---- pendulum roots ---------------------------------------------------------------- */

/* The linear stability of the main motion (4) of the two-pendulum balancer at p: the
 * characteristic polynomial (6), its roots, the eigenvalues of (5), the verdict and the
 * sufficient conditions (7)-(9) (autobal_pendulum_analyze) into *result (not NULL; plain data).
 * phys (NULL: none): the physical parameters p came from, recorded in the archive.  With an
 * archive (NULL: none), after a successful analysis: /pendulum (+ /pendulum/physical) and
 * /pendulum/roots (char_poly(power), root_real, root_imag, eig_real, eig_imag (root), verdict,
 * criterion (autobal_study_pendulum_roots_criterion), verdict_roots, max_real,
 * root_eig_mismatch, n_right_half_plane, cond7/8/9 _applicable and _predicts_stable).  Returns AUTOBAL_SUCCESS; AUTOBAL_EINVAL (bad parameters: the model's
 * message, nothing written), AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC; an archive status when writing
 * failed (what was written stays). */
AUTOBAL_API int autobal_study_pendulum_roots(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys,
                                             autobal_archive *a, autobal_pendulum_result *result, autobal_error *err);
/* The criterion that gave result->verdict, as text: "Routh-Hurwitz on (6)" (damped), or
 * "exact undamped criterion (10)" (H = h = 0: (6) is even in lambda, see
 * autobal_pendulum_analyze).  A static string; never NULL (result NULL gives ""). */
AUTOBAL_API const char *autobal_study_pendulum_roots_criterion(const autobal_pendulum_result *result);
/* The archive part of autobal_study_pendulum_roots for a result computed before (the archive
 * may then be created only after a successful analysis).  Returns an autobal status (the
 * archive's message in autobal_archive_errmsg). */
AUTOBAL_API int autobal_study_pendulum_roots_write(autobal_archive *a, const autobal_pendulum_params *p,
                                                   const autobal_pendulum_physical *phys,
                                                   const autobal_pendulum_result *result);

/* ---- pendulum critical speeds ------------------------------------------------------------ */

/* Options of `autobal pendulum critical` (section [critical]). */
typedef struct autobal_study_pendulum_critical_options {
  double Rm_min, Rm_max; /* the R_m grid of the curves R_wj(R_m), 0 < Rm_min < Rm_max < 0.5
                                                                        (default 0.001, 0.499) */
  size_t n_Rm;           /* its points, in [2, 1e6]                               (default 499) */
  double Rw_min, Rw_max; /* the R_w range of the damped search, 0 <= Rw_min < Rw_max <= 1e4
                                                                               (default 0, 6) */
  size_t n_sweep;        /* grid points of the damped search, in [2, 1e8]        (default 3000) */
  autobal_study_progress_fn progress; /* fraction done, polled at every R_m point of the curves
                            and every grid point of the damped search; non-zero: cancel
                                                                               (default NULL) */
  void *progress_user;                                                       /* (default NULL) */
} autobal_study_pendulum_critical_options;

AUTOBAL_API autobal_study_pendulum_critical_options autobal_study_pendulum_critical_options_default(void);

/* Summary of the critical speeds (dimensionless R_w = omega/omega0).  The curve arrays are
 * owned by the summary (autobal_study_pendulum_critical_summary_free). */
typedef struct autobal_study_pendulum_critical_summary {
  double k;                           /* the unbalance parameter k of p */
  autobal_pendulum_crit_set undamped; /* H = h = 0 at p's R_m and k, from the discriminant of (10) */
  int have_damped;                    /* 1: H > 0 or h > 0, `damped` holds the search on [Rw_min, Rw_max] */
  autobal_pendulum_crit_set damped;   /* at p's H and h, from (6); may be truncated */
  autobal_pendulum_crit_set undamped_k0, undamped_k1; /* the same at k = 0 and k = 1 */
  double R_m1, R_w_at_R_m1;           /* R_m^(1), where (16) and (18) touch, and R_w there */
  double eq13_R_w1_k0, eq14_R_w2_k0_small, eq14_R_w3_k0_small, eq14_R_w2_k0_large, eq14_R_w3_k0_large;
  double eq16_R_w1_k1, eq16_u, eq17_R_w1_k1_series, eq18_R_w23_k1; /* the paper's formulas at p's
                                                                        R_m (NaN where they do not apply) */
  size_t n_Rm;                        /* points of the curves */
  double *R_m;                        /* [n_Rm] the grid */
  double *R_w_k0, *R_w_k1;            /* [n_Rm x 3] row-major: R_w1..3 at each R_m (NaN: none) */
  double *curve_eq14_R_w2_k0, *curve_eq14_R_w3_k0; /* [n_Rm] series (14) along R_m */
  double *curve_eq16_R_w1_k1, *curve_eq17_R_w1_k1, *curve_eq18_R_w23_k1; /* [n_Rm] (16), (17), (18) */
  int damped_truncated_warning;       /* 1: the damped list was full (warning_message) */
  char warning_message[AUTOBAL_ERRMSG_SIZE];
  size_t n_Rm_done;                   /* points of the curves computed: n_Rm, or fewer after a
                                         cancellation */
  int damped_cancelled;               /* 1: the damped search was cancelled (have_damped = 0) */
  int cancelled;                      /* 1: cancelled (in the damped search or in the curves) */
} autobal_study_pendulum_critical_summary;

/* Critical speeds of the pendulum balancer at p, the curves R_wj(R_m) for k = 0 and 1 (figure 2)
 * and the paper's closed forms (13), (14), (16)-(18).  opt NULL: defaults.  phys (NULL: none)
 * recorded in the archive.  With an archive (NULL: none), after a successful computation:
 * /pendulum, /pendulum/critical (undamped_*, damped_*, undamped_k0_*, undamped_k1_* critical
 * speeds, kinds and stable intervals with their dimensions; R_m1, R_w_at_R_m1, eq13..eq18
 * attributes) and /pendulum/critical/curves (R_m, branch; R_w_k0, R_w_k1 (R_m, branch) and the
 * formulas along R_m).  `summary` (not NULL) is zeroed first; free it also after a failure.
 * Returns AUTOBAL_SUCCESS; AUTOBAL_EINVAL (parameters: the model's message; options:
 * "options: ..."), AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC; an archive status when writing failed;
 * AUTOBAL_ECANCELLED (options.progress asked to stop): the critical speeds at p (undamped;
 * damped unless damped_cancelled) and the first n_Rm_done points of the curves are valid and,
 * with an archive, written (curves of length n_Rm_done; partial = 1, done = n_Rm_done,
 * requested = n_Rm, partial_what on /pendulum/critical). */
AUTOBAL_API int autobal_study_pendulum_critical(const autobal_pendulum_params *p,
                                                const autobal_pendulum_physical *phys,
                                                const autobal_study_pendulum_critical_options *opt,
                                                autobal_archive *a,
                                                autobal_study_pendulum_critical_summary *summary,
                                                autobal_error *err);
/* The archive part, for a summary computed before.  Returns an autobal status. */
AUTOBAL_API int autobal_study_pendulum_critical_write(autobal_archive *a, const autobal_pendulum_params *p,
                                                      const autobal_pendulum_physical *phys,
                                                      const autobal_study_pendulum_critical_summary *summary);
/* Release the curve arrays (NULL or zeroed: nothing). */
AUTOBAL_API void autobal_study_pendulum_critical_summary_free(autobal_study_pendulum_critical_summary *summary);

/* ---- pendulum stability map ------------------------------------------------------------- */

/* Options of `autobal pendulum map` (section [map]). */
typedef struct autobal_study_pendulum_map_options {
  double Rm_min, Rm_max; /* R_m axis, 0 < Rm_min <= Rm_max < 0.5                (default 0.005, 0.495) */
  size_t n_Rm;           /* its points, in [1, 1e5]                                   (default 200) */
  double Rw_min, Rw_max; /* R_w axis, 0 <= Rw_min <= Rw_max <= 1e4                (default 0.05, 5) */
  size_t n_Rw;           /* its points, in [1, 1e5]                                   (default 200) */
  int every_unbalance;   /* non-zero: stable for every k of n_k values in [0, 1]; else p's k (default 0) */
  size_t n_k;            /* k values with every_unbalance, in [2, 1e5]                 (default 65) */
  int max_real;          /* non-zero: also the largest real part of the roots of (6)     (default 0) */
  int threads;           /* OpenMP threads, in [0, 1024]; 0: the OpenMP default         (default 0) */
  autobal_study_progress_fn progress; /* fraction of the rows done, called after each block of
                            rows (0.25 to 1 s of work); non-zero: cancel         (default NULL) */
  void *progress_user;                                                       /* (default NULL) */
  /* any two parameters (added in 0.3; docs/pendulum.md, "Maps and sweeps"): */
  int param1, param2;    /* AUTOBAL_PENDULUM_PARAM_* of the rows and the columns  (default R_M, R_W) */
  double min1, max1, min2, max2; /* their ranges (a physical key in SI units); NaN: Rm_min/Rm_max for
                            an R_m axis, Rw_min/Rw_max for an R_w axis, else
                            autobal_study_pendulum_param_range_physical               (default NaN) */
  size_t n1, n2;         /* points; 0: n_Rm (R_m axis), n_Rw (R_w axis), else 200     (default 0) */
  int log1, log2;        /* 1: logarithmic spacing (min > 0), 0: linear, -1: log for H, h, H/h
                            when min > 0, else linear                                (default -1) */
  int paper_convention;  /* undamped: 0 the exact verdict of `pendulum roots` (semisimple roots),
                            1 the paper's first approximation (autobal_pendulum_map_spec)
                                                                                     (default 0) */
} autobal_study_pendulum_map_options;

/* The default range of a pendulum parameter on a map or sweep axis (AUTOBAL_PENDULUM_PARAM_*):
 * R_w [0.05, 5], R_m [0.005, 0.495], H and h [1e-4, 1], k [0, 1], psi0 [0, pi/4], H/h [0.01, 100];
 * *log_scale (may be NULL) 1 for H, h and H/h.  Unknown param: NaN. */
AUTOBAL_API void autobal_study_pendulum_param_range(int param, double *lo, double *hi, int *log_scale);
/* The same for any parameter, a physical key (AUTOBAL_PENDULUM_PARAM_M .. _OMEGA) from the physical
 * set phys (added in 0.3): omega 0.05 .. 5 omega0 and e 0 .. sqrt(2) m l / M (the ranges of R_w and
 * psi0), H2 and H1 the range of H and h converted, M, m, l, c a quarter to four times their value;
 * each cut to the model's domain at the other keys' values (autobal_pendulum_param_domain).
 * *log_scale 1 for all physical keys but omega and e.  phys NULL: NaN for a physical key. */
AUTOBAL_API void autobal_study_pendulum_param_range_physical(int param, const autobal_pendulum_physical *phys,
                                                             double *lo, double *hi, int *log_scale);

/* The note an undamped map or sweep carries (console, archive attribute `note`): the measured
 * small-damping picture of docs/pendulum.md ("The undamped map is not the small-damping
 * limit").  A static string, never NULL. */
AUTOBAL_API const char *autobal_study_pendulum_undamped_note(void);

AUTOBAL_API autobal_study_pendulum_map_options autobal_study_pendulum_map_options_default(void);

/* A stability map over (R_m, R_w) at p's H and h (autobal_pendulum_map).  The arrays are owned
 * by the summary (autobal_study_pendulum_map_summary_free). */
typedef struct autobal_study_pendulum_map_summary {
  size_t n_Rm, n_Rw, n_k;   /* points of axis 1 and 2 (named so for the default axes R_m, R_w)
                               and the number of k values */
  int every_unbalance;      /* options.every_unbalance: the verdict holds for every k */
  double *R_m, *R_w, *k;    /* [n_Rm], [n_Rw]: the values of axis 1 and axis 2 (whatever their
                               parameters: see param1, param2), [n_k] */
  int *verdict;             /* [n_Rm x n_Rw] row-major: 1 stable, 0 marginal, -1 unstable */
  double *max_real;         /* [n_Rm x n_Rw] with options.max_real, else NULL */
  size_t n_stable;          /* points with verdict 1 */
  size_t n_Rm_done;         /* rows (axis 1) computed: n_Rm, or fewer after a cancellation */
  /* added in 0.3 */
  int param1, param2;       /* AUTOBAL_PENDULUM_PARAM_* of axis 1 (rows) and 2 (columns) */
  int log1, log2;           /* 1: the axis was spaced logarithmically */
  int paper_convention;     /* options.paper_convention */
  int undamped;             /* 1: H = h = 0 at every point (then the note applies) */
} autobal_study_pendulum_map_summary;

/* Compute the map over options.param1 x options.param2 (autobal_pendulum_grid; the other
 * parameters at p); opt NULL: defaults; phys (NULL: none) recorded in the archive with an omega
 * axis when an axis is R_w, and needed for a physical key on an axis (M, e, m, l, c, H1, H2, omega:
 * each point is phys with the key changed, converted by autobal_pendulum_params_from_physical;
 * the coordinate is named by the key, in its SI unit).  With an archive (NULL: none), after a successful computation:
 * /pendulum and /pendulum/map (criterion, convention, every_unbalance, k_values, axis1, axis2
 * (the keys), axis1_dim, axis2_dim, axis1_scale, axis2_scale ("linear"/"log"), ratio_rule with an
 * H/h axis, note (undamped maps: autobal_study_pendulum_undamped_note), the two coordinates named
 * by autobal_pendulum_param_dim (default R_m and R_w) with units, design_<dim> of each axis,
 * omega(R_w) with phys, verdict(axis1, axis2), max_real(axis1, axis2)).  `summary` (not
 * NULL) is zeroed first; free it also after a failure.  Returns AUTOBAL_SUCCESS,
 * AUTOBAL_EINVAL ("options: ..." or the model's message), AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC or
 * an archive status, or AUTOBAL_ECANCELLED (options.progress asked to stop; the rows are
 * computed in blocks, the results do not depend on them): the first n_Rm_done rows are valid
 * and, with an archive, written (R_m, verdict, max_real with n_Rm_done rows; partial = 1,
 * done = n_Rm_done, requested = n_Rm, partial_what on /pendulum/map). */
AUTOBAL_API int autobal_study_pendulum_map(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys,
                                           const autobal_study_pendulum_map_options *opt, autobal_archive *a,
                                           autobal_study_pendulum_map_summary *summary, autobal_error *err);
/* The archive part, for a summary computed before.  Returns an autobal status. */
AUTOBAL_API int autobal_study_pendulum_map_write(autobal_archive *a, const autobal_pendulum_params *p,
                                                 const autobal_pendulum_physical *phys,
                                                 const autobal_study_pendulum_map_summary *summary);
AUTOBAL_API void autobal_study_pendulum_map_summary_free(autobal_study_pendulum_map_summary *summary);

/* ---- pendulum sweep ----------------------------------------------------------------------- */

/* Options of `autobal pendulum sweep` (section [sweep]). */
typedef struct autobal_study_pendulum_sweep_options {
  int param;             /* AUTOBAL_PENDULUM_PARAM_* swept                             (default R_W) */
  double min, max;       /* range, min < max (a physical key in SI units); NaN:
                            autobal_study_pendulum_param_range_physical               (default NaN) */
  size_t n;              /* grid points, in [2, 1e7]                                    (default 1000) */
  int log_scale;         /* as log1 of the map options                                    (default -1) */
  int every_unbalance;   /* non-zero: stable for every k of n_k values in [0, 1]          (default 0) */
  size_t n_k;            /* k values with every_unbalance, in [2, 1e5]                    (default 65) */
  double xtol_rel;       /* relative accuracy of the critical values, in (0, 0.1)       (default 1e-10) */
  int paper_convention;  /* as in the map options                                        (default 0) */
  autobal_study_progress_fn progress; /* fraction done; non-zero: cancel               (default NULL) */
  void *progress_user;
} autobal_study_pendulum_sweep_options;
AUTOBAL_API autobal_study_pendulum_sweep_options autobal_study_pendulum_sweep_options_default(void);

#define AUTOBAL_STUDY_PENDULUM_MAX_CRIT 64
/* A sweep: the verdict on the grid and the critical values where it changes.  Arrays owned by
 * the summary (autobal_study_pendulum_sweep_summary_free). */
typedef struct autobal_study_pendulum_sweep_summary {
  int param, log_scale, every_unbalance, paper_convention, undamped;
  double min, max;          /* the range used */
  double xtol_rel;          /* options.xtol_rel */
  size_t n, n_k;            /* grid points, k values */
  double *values;           /* [n] */
  double *k;                /* [n_k] (the k of p when not every_unbalance) */
  int *verdict;             /* [n] 1 stable, 0 marginal, -1 unstable */
  size_t n_stable;
  size_t n_crit;            /* critical values found (<= AUTOBAL_STUDY_PENDULUM_MAX_CRIT) */
  double crit[AUTOBAL_STUDY_PENDULUM_MAX_CRIT];   /* where the verdict changes, ascending */
  int crit_below[AUTOBAL_STUDY_PENDULUM_MAX_CRIT]; /* the verdicts at the grid points below and above */
  int crit_above[AUTOBAL_STUDY_PENDULUM_MAX_CRIT];
  int crit_truncated;       /* 1: more changes on the grid than the list holds */
  size_t n_done;            /* grid points computed (n, or fewer after a cancellation) */
  int cancelled;
} autobal_study_pendulum_sweep_summary;

/* Sweep options.param over its grid (autobal_pendulum_grid on a line, the other parameters at
 * p) and refine every change of the verdict between neighbouring points by bisection
 * (autobal_pendulum_grid_critical) to xtol_rel.  Changes between two grid points that undo each
 * other (a window narrower than the step) are not seen: for the undamped system over R_w at one
 * k, `pendulum critical` (autobal_pendulum_critical_speeds) is exact.  With an archive:
 * /pendulum and /pendulum/sweep (param, key, dim, scale, criterion, convention, every_unbalance,
 * k_values, note when undamped, the coordinate named by autobal_pendulum_param_dim, verdict,
 * critical_<dim>, critical_below, critical_above).  Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL
 * ("options: ..." or the model's message naming the key), AUTOBAL_ENOMEM, a point's status,
 * AUTOBAL_ECANCELLED (the first n_done points valid and written with partial = 1, no critical
 * values), or an archive status.  `summary` (not NULL) is zeroed first; free it also after a
 * failure. */
AUTOBAL_API int autobal_study_pendulum_sweep(const autobal_pendulum_params *p,
                                             const autobal_pendulum_physical *phys,
                                             const autobal_study_pendulum_sweep_options *opt,
                                             autobal_archive *a,
                                             autobal_study_pendulum_sweep_summary *summary,
                                             autobal_error *err);
AUTOBAL_API int autobal_study_pendulum_sweep_write(autobal_archive *a, const autobal_pendulum_params *p,
                                                   const autobal_pendulum_physical *phys,
                                                   const autobal_study_pendulum_sweep_summary *summary);
AUTOBAL_API void autobal_study_pendulum_sweep_summary_free(autobal_study_pendulum_sweep_summary *summary);

/* ---- rotor sweep, map and Campbell diagram ------------------------------------------------ */

/* The default range of a swept rotor parameter (AUTOBAL_ROTOR_PARAM_*, in its unit
 * autobal_rotor_stab_param_unit): OMEGA: autobal_study_rotor_speed_range; BALL_DAMPING:
 * [0, 10 h_1 + 1e-3]; BALL_MASS: [0.1 m_1, 4 m_1] (h_1, m_1: plane 1's first ball, 0.1 and
 * 0.05 without balls); UNBALANCE_MASS: [0, 4 m0 + 1e-3]; DAMPING_SCALE: [0, 4];
 * STIFFNESS_SCALE: [0.25, 4]; any other key (a hardware, lumped or plane key, anisotropy,
 * C_over_A) around its value v at p: [v/4, 4 v] for v > 0, [4 v, v/4] for v < 0, [0, 1] for
 * v = 0, a plane's psi0 over [-pi, pi], a plane's d over [-l_L, l_R] (hardware input) or
 * v -/+ (2 |v| + 0.1) m; NaN, NaN for a key that is not a parameter of p (a hardware key of a
 * lumped rotor, plane2 of a one-plane rotor). */
AUTOBAL_API void autobal_study_rotor_param_range(const autobal_rotor_params *p, int param, double *lo, double *hi);

/* Options of `autobal rotor sweep` (section [sweep]; [stability] in stab). */
typedef struct autobal_study_rotor_sweep_options {
  autobal_rotor_stab_options stab; /* as in autobal_study_rotor_stability_options */
  int param;            /* AUTOBAL_ROTOR_PARAM_* swept                          (default OMEGA) */
  double min, max;      /* the range, min < max, in the parameter's unit; NaN:
                           autobal_study_rotor_param_range                      (default NaN, NaN) */
  size_t n;             /* grid points, in [2, 1e7]                              (default 1000) */
  double xtol_rel;      /* relative accuracy of the critical values, in (0, 0.1)  (default 1e-8) */
  autobal_study_progress_fn progress; /* fraction of the sweep; non-zero: cancel (default NULL) */
  void *progress_user;
} autobal_study_rotor_sweep_options;
AUTOBAL_API autobal_study_rotor_sweep_options autobal_study_rotor_sweep_options_default(void);

/* A sweep: margin and verdict on the grid and the critical values.  Arrays owned by the
 * summary (autobal_study_rotor_sweep_summary_free). */
typedef struct autobal_study_rotor_sweep_summary {
  int param;                  /* the swept parameter */
  double min, max;            /* the range used */
  size_t n;                   /* grid points */
  double *values;             /* [n] the grid */
  double *margin;             /* [n] 1/s (NaN: no balanced configuration) */
  int *verdict;               /* [n] 1 stable, 0 marginal, -1 unstable, -2 none */
  size_t n_stable;            /* points with verdict 1 */
  autobal_rotor_crit critical; /* critical values in the parameter's unit */
  int critical_truncated;     /* 1: more critical values than the list holds (critical_message) */
  char critical_message[AUTOBAL_ERRMSG_SIZE];
  size_t n_done;              /* grid points computed: n, or fewer after a cancellation (the
                                 first n_done entries of values/margin/verdict are valid) */
  int cancelled;              /* 1: cancelled; the critical values were not searched (or not to
                                 the end) and critical is zeroed */
} autobal_study_rotor_sweep_summary;

/* Sweep options.param over its grid (autobal_rotor_stab_sweep, in chunks of 64 points with
 * progress) and refine its critical values (autobal_rotor_stab_critical).  opt NULL: defaults.
 * With an archive (NULL: none), after success: /rotor (as the stability study) and /rotor/sweep
 * (options, param, the coordinate named after the parameter, margin, verdict, critical values).
 * Returns AUTOBAL_SUCCESS; AUTOBAL_EINVAL ("options: ..."; the model's messages; "<param> =
 * <value> <unit>: ..." for a failing point; "critical values: ..."), AUTOBAL_ECANCELLED (the
 * progress callback asked to stop, polled after every chunk and before every margin evaluation
 * of the critical search: the summary holds the first n_done points, cancelled = 1, and with an
 * archive they are written: the coordinate, margin and verdict of length n_done, the
 * attributes partial = 1, done = n_done, requested = n, partial_what, and no critical values),
 * AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC, an archive status.  `summary` (not NULL) is zeroed
 * first; free it also after a failure. */
AUTOBAL_API int autobal_study_rotor_sweep(const autobal_rotor_params *p, const autobal_study_rotor_sweep_options *opt,
                                          autobal_archive *a, autobal_study_rotor_sweep_summary *summary,
                                          autobal_error *err);
AUTOBAL_API int autobal_study_rotor_sweep_write(autobal_archive *a, const autobal_rotor_params *p,
                                                const autobal_study_rotor_sweep_options *opt,
                                                const autobal_study_rotor_sweep_summary *summary);
AUTOBAL_API void autobal_study_rotor_sweep_summary_free(autobal_study_rotor_sweep_summary *summary);

/* Options of `autobal rotor map` (section [map]). */
typedef struct autobal_study_rotor_map_options {
  autobal_rotor_stab_options stab;
  int param1, param2;   /* two different AUTOBAL_ROTOR_PARAM_* (default OMEGA, BALL_DAMPING) */
  double min1, max1, min2, max2; /* ranges, min <= max; NaN: autobal_study_rotor_param_range */
  size_t n1, n2;        /* grid points, in [1, 1e5]                              (default 120, 60) */
  int threads;          /* OpenMP threads, [0, 1024]; 0: the OpenMP default          (default 0) */
  autobal_study_progress_fn progress; /* fraction of the rows done, called after each block of
                           rows (0.25 to 1 s of work); non-zero: cancel           (default NULL) */
  void *progress_user;                                                       /* (default NULL) */
  /* every unbalance (added at the end): non-zero = each point's verdict is the one for every m0 r0
     in [unbalance_min, unbalance_max] kg m (autobal_rotor_stab_map_every_unbalance)
                                                                   (default 0, NaN, NaN) */
  int every_unbalance;
  double unbalance_min, unbalance_max;
} autobal_study_rotor_map_options;
AUTOBAL_API autobal_study_rotor_map_options autobal_study_rotor_map_options_default(void);

/* A map over two parameters.  Arrays owned by the summary (autobal_study_rotor_map_summary_free). */
typedef struct autobal_study_rotor_map_summary {
  int param1, param2;         /* the parameters of the rows and the columns */
  double min1, max1, min2, max2; /* the ranges used, in the parameters' units */
  size_t n1, n2;              /* grid points of each */
  double *values1, *values2;  /* [n1], [n2] the grids */
  double *margin;             /* [n1 x n2] row-major, 1/s (NaN: no balanced configuration) */
  int *verdict;               /* [n1 x n2] 1 stable, 0 marginal, -1 unstable, -2 none, -3 undecided
                                 (every unbalance on anisotropic supports: AUTOBAL_ROTOR_VERDICT_UNDECIDED) */
  size_t n_stable;            /* points with verdict 1 */
  size_t n1_done;             /* rows (values1) computed: n1, or fewer after a cancellation */
} autobal_study_rotor_map_summary;

/* Margin and verdict over a grid of two parameters (autobal_rotor_stab_map).  With an archive:
 * /rotor and /rotor/map (options, param1, param2, the two coordinates, margin, verdict).
 * The rows are computed in blocks (the results do not depend on the blocks or the threads).
 * Returns like autobal_study_rotor_sweep; after a cancellation the first n1_done rows are
 * valid and written (the first coordinate, margin and verdict with n1_done rows; partial = 1,
 * done = n1_done, requested = n1, partial_what on /rotor/map; the progress callback is first
 * called after the first block, so n1_done >= 1). */
AUTOBAL_API int autobal_study_rotor_map(const autobal_rotor_params *p, const autobal_study_rotor_map_options *opt,
                                        autobal_archive *a, autobal_study_rotor_map_summary *summary,
                                        autobal_error *err);
AUTOBAL_API int autobal_study_rotor_map_write(autobal_archive *a, const autobal_rotor_params *p,
                                              const autobal_study_rotor_map_options *opt,
                                              const autobal_study_rotor_map_summary *summary);
AUTOBAL_API void autobal_study_rotor_map_summary_free(autobal_study_rotor_map_summary *summary);

/* Options of `autobal rotor campbell` (section [campbell]). */
typedef struct autobal_study_rotor_campbell_options {
  double omega_min, omega_max; /* rad/s, 0 <= omega_min < omega_max; NaN: 0 and the upper end of
                                  autobal_study_rotor_speed_range             (default NaN, NaN) */
  size_t n;                    /* speeds of the diagram, [2, 1e7]                    (default 401) */
  size_t n_resonance;          /* grid of the resonance search, [3, 1e7]            (default 4000) */
  double xtol_rel;             /* accuracy of the resonance speeds, (0, 0.1)       (default 1e-10) */
  autobal_study_progress_fn progress; /* fraction done, after each block of speeds and polled at
                                  every grid point of the resonance search; non-zero: cancel
                                                                                (default NULL) */
  void *progress_user;                                                       /* (default NULL) */
} autobal_study_rotor_campbell_options;
AUTOBAL_API autobal_study_rotor_campbell_options autobal_study_rotor_campbell_options_default(void);

/* The Campbell diagram and the unbalance response.  Arrays owned by the summary
 * (autobal_study_rotor_campbell_summary_free). */
typedef struct autobal_study_rotor_campbell_summary {
  double omega_min, omega_max;   /* rad/s, the range used */
  size_t n, n_planes;            /* speeds of the diagram; balancer planes of p */
  double *omega;                 /* [n] rad/s */
  double *frequency;             /* [n x 4] rad/s, damped natural frequencies by increasing value */
  double *damping_ratio;         /* [n x 4] */
  int *whirl;                    /* [n x 4] 1 forward, -1 backward, 0 undecided */
  double *amp_G;                 /* [n] m, unbalance response of the centre of mass (inf: an
                                    undamped resonance on the grid) */
  double *amp_D;                 /* [n x n_planes] m, at the balancer planes */
  double natural_frequency_undamped[4]; /* rad/s, at rest without damping */
  double natural_frequency_damped[4];   /* rad/s, at rest */
  double damping_ratio_at_rest[4];      /* 1 */
  autobal_rotor_resonances resonances; /* crossings and unbalance-response peaks */
  int resonances_truncated;      /* 1: lists full (resonance_message says up to where) */
  char resonance_message[AUTOBAL_ERRMSG_SIZE];
  size_t n_done;                 /* speeds of the diagram computed (rows of frequency ... amp_D):
                                    n, or fewer after a cancellation */
  int have_resonances;           /* 1: the resonance search ran to its end (else resonances is
                                    zeroed) */
} autobal_study_rotor_campbell_summary;

/* The rotor-housing without balls: natural frequencies at rest, the Campbell diagram, the steady
 * unbalance response and the critical speeds.  With an archive: /rotor and /rotor/campbell.
 * Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL ("options: ..." or the model's message),
 * AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC, an archive status, or AUTOBAL_ECANCELLED (options.progress
 * asked to stop): the first n_done speeds are valid, have_resonances says whether the
 * resonance search finished, and with an archive they are written (the omega axis and the
 * arrays with n_done rows; partial = 1, done = n_done, requested = n, partial_what on
 * /rotor/campbell; no crossings or peaks unless have_resonances). */
AUTOBAL_API int autobal_study_rotor_campbell(const autobal_rotor_params *p,
                                             const autobal_study_rotor_campbell_options *opt, autobal_archive *a,
                                             autobal_study_rotor_campbell_summary *summary, autobal_error *err);
AUTOBAL_API int autobal_study_rotor_campbell_write(autobal_archive *a, const autobal_rotor_params *p,
                                                   const autobal_study_rotor_campbell_summary *summary);
AUTOBAL_API void autobal_study_rotor_campbell_summary_free(autobal_study_rotor_campbell_summary *summary);

AUTOBAL_END_DECLS

#endif
