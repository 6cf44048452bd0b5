/* dop853.h (private, src/transient/): the Dormand-Prince 8(5,3) pair DOP853 with its
 * 7th-order continuous extension, as a gsl_odeiv2 step type (Hairer, Norsett & Wanner,
 * Solving ODEs I, 2nd ed., II.5 and II.6; Hairer's dop853.f).  Used by transient.c only. */
#ifndef AUTOBAL_TRANSIENT_DOP853_H
#define AUTOBAL_TRANSIENT_DOP853_H

#include <stddef.h>
#include <gsl/gsl_odeiv2.h>

/* The step type "dop853": 12 stages per step, the first taken from dydt_in when given (FSAL:
 * dydt_out, f at the end of the step, is exact and is the 13th stage, used by the error estimate).
 * yerr_i = h e5_i |e5_i| / hypot(e5_i, 0.1 e3_i) with e5, e3 the 5th- and 3rd-order embedded
 * differences, the componentwise form of Hairer's estimate (O(h^8); as SciPy's
 * DOP853._estimate_error).  order() returns 7: GSL's control then shrinks a step by
 * r^(-1/7) and grows it by r^(-1/8), r the largest scaled error, matching the O(h^8) estimate. */
extern const gsl_odeiv2_step_type autobal_transient_dop853_type_;

/* After an accepted step (the last apply() of this state, from (t, y0) with step h): build the
 * continuous extension, 3 more right-hand sides (stages 13..15) through sys (order 6: none).  Returns GSL_SUCCESS
 * or the right-hand side's non-zero status (then no interpolation is available). */
int autobal_transient_dop853_dense_prepare_(void *state, const gsl_odeiv2_system *sys);

/* The continuous extension used from now on: order 7 (Hairer's contd8, 3 more right-hand sides per
 * step where it is used; the state after alloc) or 6 (from the step's 12 stages and f(t + h, y1)
 * alone, no right-hand side: dop853_dense6.inc, tools/derive/derive_dense6.py; degree 7, C1 at
 * the step ends, local error O(h^7)).  Any other value: 7. */
void autobal_transient_dop853_set_dense_order_(void *state, int order);

/* 1 if the continuous extension of the last accepted step is built (prepare succeeded since the
 * last apply or reset; order 6: after every successful apply, nothing to build). */
int autobal_transient_dop853_dense_ready_(const void *state);

/* The continuous extension at t0 + theta h, theta in [0, 1] (theta = 0 gives y0, theta = 1 the
 * step's result, to rounding), into out (dim doubles).  Local error O(h^8). */
void autobal_transient_dop853_dense_eval_(const void *state, double theta, double *out);

/* The continuous extension at time t of the last step, t0 + theta h with theta = (t - t0) / h
 * clamped to [0, 1], into out (dim doubles); returns 1 if every component is finite, else 0
 * (eval_ and the test in one call: the driver's dense output). */
int autobal_transient_dop853_dense_at_(const void *state, double t, double *out);

/* The same for a state whose extension has order 6 (set_dense_order_(state, 6)): the same numbers,
 * a smaller function (the driver's output points with dense6). */
int autobal_transient_dop853_dense6_at_(const void *state, double t, double *out);

/* dense6_at_ itself, or for the sizes with dim a multiple of 4 up to 24 (pendulum 8, one-plane
 * rotors with 2 and 5 balls, ...) a function that computes the same numbers with that size
 * built in (no dispatch per call): the driver takes it once per run and calls it at every output
 * point and trial point of the event location. */
typedef int (*autobal_transient_dop853_at_fn)(const void *state, double t, double *out);
autobal_transient_dop853_at_fn autobal_transient_dop853_dense6_at_fn_(const void *state);

/* The tolerances of the control that judges the steps (GSL's standard control with these atol,
 * rtol, a_y = 1, a_dydt = 0): with them the error estimate is Hairer's normwise one (the factor
 * |e5|^2 / sqrt(|e5|^2 + 0.01 |e3|^2) of the 2-norms scaled by atol + rtol max(|y0_i|, |y1_i|),
 * common to every component: yerr_i = h e5_i |e5| / sqrt(|e5|^2 + 0.01 |e3|^2)); without them
 * (0, 0, the state after alloc) the componentwise one above. */
void autobal_transient_dop853_set_tol_(void *state, double atol, double rtol);

/* The step-size control of the last step taken by apply() in the normwise mode (tolerances set
 * by set_tol_): the same decision as GSL's standard control with these tolerances, a_y = 1,
 * a_dydt = 0 and order 7 (rmax = max_i |yerr_i| / (atol + rtol |y_i|) computed by the step in
 * the pass that writes yerr; rmax > 1.1: *h *= max(0.2, 0.9 rmax^(-1/7)), GSL_ODEIV_HADJ_DEC;
 * rmax < 0.5: *h *= min(5, max(1, 0.9 rmax^(-1/8))), HADJ_INC; else HADJ_NIL), without its
 * second pass over the arrays and with rmax^(1/8) as three square roots instead of pow (the
 * grown step may differ from GSL's in the last bit). */
int autobal_transient_dop853_hadjust_(const void *state, double *h);

/* 1 if the last step taken by apply() in the normwise mode gave a finite result, error estimate
 * and f(t + h, y1) (dydt_out), tested in the step's last pass; 0 otherwise. */
int autobal_transient_dop853_finite_(const void *state);

/* The number of right-hand sides the last apply() (or dense_prepare_) evaluated through sys,
 * and the time of the one that returned non-zero when it failed (then the last one counted):
 * for a caller that passes the user's function as sys directly, without a counting adapter. */
void autobal_transient_dop853_evals_(const void *state, unsigned *nfev, double *t_fail);

/* The start (t0) and the length (h) of the last step taken by apply(). */
void autobal_transient_dop853_last_step_(const void *state, double *t0, double *h);

#endif
