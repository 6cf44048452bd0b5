/* autobal/pendulum.h: the planar two-pendulum autobalancer
 * (docs/pendulum.md; Filimonikhin 1996, equation numbers (1)-(18)).
 *
 * EVERYTHING IN THIS MODULE IS DIMENSIONLESS (eqs. (2), (3)): time is
 * tau = omega0 t, lengths are in units of the rod length l, and the
 * parameters are
 *     R_w = omega / omega0        rotor speed            (omega0^2 = c / M_sigma)
 *     R_m = m / M_sigma           pendulum mass ratio    (M_sigma = M + 2m), in (0, 1/2)
 *     H   = H2 / (omega0 M_sigma) external (shaft) damping
 *     h   = H1 / (m l^2 omega0)   pendulum damping
 *     psi0                        pendulum angle of the main motion (4), radians,
 *                                 sin psi0 = M e / (2 m l); k = sin^2(2 psi0) in [0, 1].
 * Only autobal_pendulum_physical is in SI units; it is converted with
 * autobal_pendulum_params_from_physical().
 *
 * Status codes: every function returning int returns AUTOBAL_SUCCESS (0) or
 * a negative status (AUTOBAL_EINVAL for a bad parameter: the message names
 * the parameter, its value and the allowed range; AUTOBAL_ENOMEM;
 * AUTOBAL_ENUMERIC for a GSL failure, with GSL's text); the one exception is
 * autobal_pendulum_critical_speeds_damped, which returns the positive
 * AUTOBAL_WARNING when its list was full (valid data, see there).  Functions that take
 * a workspace record the message in it (autobal_pendulum_errmsg()); the
 * others take an `autobal_error *err` (NULL allowed).  After a failure the
 * outputs hold unspecified values (never uninitialised memory) unless a
 * function says more; inputs are never modified.  A function given a NULL
 * workspace returns AUTOBAL_EINVAL without a message (there is nowhere to
 * record it).
 *
 * No validation (plain formulas on the caller's data, no NULL checks, NaN in
 * gives NaN out): autobal_pendulum_k, autobal_pendulum_main_motion,
 * autobal_pendulum_wrap_angle, autobal_pendulum_shaft_amplitude,
 * autobal_pendulum_residual_unbalance, autobal_pendulum_unbalance_scalar,
 * autobal_pendulum_jacobi_integral, autobal_pendulum_jacobi_power,
 * autobal_pendulum_motion_derive; the right-hand sides and Jacobians check
 * their pointers only.  autobal_pendulum_crit_count/crit_get accept NULL
 * (0, NaN).
 *
 * Memory: the library allocates only in autobal_pendulum_workspace_alloc()
 * and (once per thread, up front) inside autobal_pendulum_map() and
 * autobal_pendulum_grid() when max_real is requested; all other outputs are caller-owned structs or arrays of
 * documented size.
 * Threads: every function is reentrant; a workspace is used by one thread
 * at a time (one workspace per thread).
 */
#ifndef AUTOBAL_PENDULUM_H
#define AUTOBAL_PENDULUM_H

#include <stddef.h>
#include "autobal/export.h"
#include "autobal/status.h"
#include "autobal/stability.h"

AUTOBAL_BEGIN_DECLS

/* ======================================================================== */
/* Parameters (2), (3)                                                      */
/* ======================================================================== */

/* Dimensionless parameters (all fields dimensionless, psi0 in radians). */
typedef struct autobal_pendulum_params {
  double R_w;  /* rotor speed omega/omega0, in [0, AUTOBAL_PENDULUM_MAX_RATIO]  */
  double R_m;  /* mass ratio m/(M + 2m), in (0, 1/2)                           */
  double H;    /* external damping H2/(omega0 M_sigma), in [0, MAX_RATIO]     */
  double h;    /* pendulum damping H1/(m l^2 omega0), in [0, MAX_RATIO]       */
  double psi0; /* main-motion angle (4), rad, in [0, pi/2) (sin psi0 = Me/2ml) */
} autobal_pendulum_params;

/* Physical parameters, SI units. */
typedef struct autobal_pendulum_physical {
  double M;     /* rotor mass, kg, > 0                                   */
  double e;     /* eccentricity of the rotor's centre of mass, m, >= 0   */
  double m;     /* mass of each pendulum, kg, > 0                        */
  double l;     /* pendulum rod length, m, > 0                           */
  double c;     /* shaft stiffness, N/m, > 0                             */
  double H1;    /* viscous moment coefficient of each pendulum, N m s, >= 0 */
  double H2;    /* external viscous damping of the shaft, N s/m, >= 0    */
  double omega; /* rotor angular speed, rad/s, >= 0                      */
} autobal_pendulum_physical;

/* Check every field of p (ranges above; finite).  The first bad field is
 * reported, e.g. "parameter R_m = 0.5 is too large: must be < 0.5 (allowed
 * range (0, 0.5))". */
AUTOBAL_API int autobal_pendulum_params_validate(const autobal_pendulum_params *p,
                                                 autobal_error *err);

/* Fill *out from R_w, R_m, H, h and k = sin^2(2 psi0) in [0, 1], choosing
 * psi0 = asin(sqrt(k))/2 in [0, pi/4].  Validates everything (k out of
 * [0, 1] is reported as parameter k).  *out is written only on success. */
AUTOBAL_API int autobal_pendulum_params_from_k(double R_w, double R_m, double H, double h, double k,
                                               autobal_pendulum_params *out, autobal_error *err);

/* k = sin^2(2 psi0) of p (no validation). */
AUTOBAL_API double autobal_pendulum_k(const autobal_pendulum_params *p);

/* Convert physical (SI) to dimensionless parameters by (2)-(3):
 *   M_sigma = M + 2m, omega0 = sqrt(c/M_sigma), R_w = omega/omega0,
 *   R_m = m/M_sigma, H = H2/(omega0 M_sigma), h = H1/(m l^2 omega0),
 *   psi0 = asin(M e/(2 m l)).
 * Rejects non-finite or out-of-range fields by name and M e >= 2 m l (the
 * pendulums cannot balance the unbalance; reported as "M*e" with the limit
 * 2*m*l).  *out is written only on success. */
AUTOBAL_API int autobal_pendulum_params_from_physical(const autobal_pendulum_physical *phys,
                                                      autobal_pendulum_params *out,
                                                      autobal_error *err);

/* ======================================================================== */
/* Linearization (5) and characteristic polynomial (6)                      */
/* ======================================================================== */

/* Upper bound of R_w, H and h (1e6): the coefficients of (6) hold their powers up to the
 * eighth, which must stay finite (a rotor at a million times its natural frequency is far
 * outside the model anyway). */
#define AUTOBAL_PENDULUM_MAX_RATIO 1e6
#define AUTOBAL_PENDULUM_ORDER 8 /* degree of (6) = size of the first-order system */
#define AUTOBAL_PENDULUM_NCOEF 9 /* coefficients of (6)                           */

/* The complex polynomials of (6) in lambda, 3 complex coefficients each
 * (ascending powers, interleaved re/im: 6 doubles each):
 *   a11 = (lambda + iR_w)^2 + H (lambda + iR_w) + 1,
 *   a31 = (lambda + iR_w)^2,  a33 = lambda^2 + h lambda.
 * Any output pointer may be NULL.  Validates p. */
AUTOBAL_API int autobal_pendulum_char_blocks(const autobal_pendulum_params *p, double a11[6],
                                             double a31[6], double a33[6], autobal_error *err);

/* Characteristic polynomial (6), ascending powers of lambda, 9 real
 * coefficients, built by complex polynomial arithmetic from a11, a31, a33:
 *   (a11 a33 - R_m a31^2)(conj(a11) a33 - R_m conj(a31)^2)
 *     - R_m^2 cos^2(2 psi0) a31^2 conj(a31)^2.
 * It equals det(M lambda^2 + C lambda + K) of (5) exactly (factor 1).
 * The leading coefficient is 1 - 2R_m + k R_m^2 > 0.  Validates p. */
AUTOBAL_API int autobal_pendulum_char_poly(const autobal_pendulum_params *p, double coef[9],
                                           autobal_error *err);

/* The factor P1 = a11 a33 - R_m a31^2 of (15) (5 complex coefficients,
 * interleaved, ascending).  At k = 1, (6) = P1 conj(P1).  Validates p. */
AUTOBAL_API int autobal_pendulum_char_p1(const autobal_pendulum_params *p, double p1[10],
                                         autobal_error *err);

/* The matrices of the linearization (5), M q'' + C q' + K q = 0 with
 * q = (xi, eta, alpha, beta), each 4x4 row-major (rows: the four equations
 * of (5) in the order of docs/pendulum.md).  Any output may be NULL.  Validates p. */
AUTOBAL_API int autobal_pendulum_linear_matrices(const autobal_pendulum_params *p, double Mm[16],
                                                 double C[16], double K[16], autobal_error *err);

/* The 8x8 first-order matrix A of (5), state (q, q'):
 *   A = [ 0, I ; -M^{-1} K, -M^{-1} C ]   (row-major, 64 doubles);
 * M is inverted by LU with partial pivoting (non-singular for R_m < 1/2;
 * AUTOBAL_ENUMERIC if it is singular to working precision). */
AUTOBAL_API int autobal_pendulum_first_order_matrix(const autobal_pendulum_params *p, double A[64],
                                                    autobal_error *err);

/* ======================================================================== */
/* Workspace and the one-call analysis                                      */
/* ======================================================================== */

/* Holds the GSL workspaces (roots of degree 4, 8, 12; eigenvalues 8x8) and
 * the last error.  Allocate once, reuse; one per thread. */
typedef struct autobal_pendulum_workspace autobal_pendulum_workspace;
AUTOBAL_API autobal_pendulum_workspace *autobal_pendulum_workspace_alloc(void); /* NULL: no memory */
AUTOBAL_API void autobal_pendulum_workspace_free(autobal_pendulum_workspace *ws); /* NULL safe */
/* Last error message of ws ("" after success; never NULL; ws may be NULL). */
AUTOBAL_API const char *autobal_pendulum_errmsg(const autobal_pendulum_workspace *ws);
/* A cancellation hook: return non-zero to stop (called often: read a flag). */
typedef int (*autobal_pendulum_cancel_fn)(void *user);
/* Install (fn NULL: remove) the workspace's cancellation hook, polled with `user` by
 * autobal_pendulum_critical_curves (before each R_m point) and
 * autobal_pendulum_critical_speeds_damped (before each grid point of the scan; a refinement is
 * bounded): they then return AUTOBAL_ECANCELLED ("cancelled by the caller" as the workspace's
 * message).  critical_curves: the rows before the stop are filled; critical_speeds_damped: *out
 * is zeroed (the changes found so far are dropped).  No effect on a NULL workspace. */
AUTOBAL_API void autobal_pendulum_workspace_set_cancel(autobal_pendulum_workspace *ws, autobal_pendulum_cancel_fn fn,
                                                       void *user);
/* Last status of ws (AUTOBAL_SUCCESS after success). */
AUTOBAL_API int autobal_pendulum_status(const autobal_pendulum_workspace *ws);

/* Relative tolerance of the Routh-Hurwitz sign test used by the analysis
 * and the maps (see autobal_poly_hurwitz()). */
#define AUTOBAL_PENDULUM_HURWITZ_RTOL 1e-12
/* Tolerance of the root-based verdict (see autobal_roots_verdict()). */
#define AUTOBAL_PENDULUM_ROOTS_TOL 1e-9
/* An asymptotic condition (7)-(9) is reported "applicable" when its small
 * parameter (R_m or 1/h for (7), 1/R_w for (8), 1/H for (9)) is at most this. */
#define AUTOBAL_PENDULUM_ASYMPTOTIC_SMALL 0.05

/* A sufficient (asymptotic) condition, reported beside the exact verdict. */
typedef struct autobal_pendulum_sufficient {
  int applicable;      /* 1 if its small parameter <= AUTOBAL_PENDULUM_ASYMPTOTIC_SMALL */
  int predicts_stable; /* 1 if the condition predicts stability (evaluated even when
                          not applicable)                                            */
  double small;        /* the value of the small parameter                           */
} autobal_pendulum_sufficient;

typedef struct autobal_pendulum_result {
  double coef[AUTOBAL_PENDULUM_NCOEF];      /* (6), ascending powers of lambda           */
  double root_re[AUTOBAL_PENDULUM_ORDER];   /* roots of (6) (GSL), sorted by Re, then Im  */
  double root_im[AUTOBAL_PENDULUM_ORDER];
  double eig_re[AUTOBAL_PENDULUM_ORDER];    /* eigenvalues of the 8x8 matrix of (5),     */
  double eig_im[AUTOBAL_PENDULUM_ORDER];    /* reordered so eig[i] is matched to root[i] */
  double max_real;      /* margin: largest real part of the roots of (6)                */
  double max_real_eig;  /* largest real part of the eigenvalues                         */
  double mismatch;      /* bottleneck-optimal max_i |root_i - eig_i| (autobal_match_roots) */
  double mismatch_rel;  /* mismatch / max(1, max |root|)                                 */
  int verdict;          /* autobal_verdict of the main motion.  Damped (H > 0 or h > 0): the
                           Routh-Hurwitz sign test on coef (AUTOBAL_PENDULUM_HURWITZ_RTOL),
                           STABLE = asymptotically stable; when k == 0 the structural root
                           lambda = 0 (the family psi = -phi of balanced states) is divided
                           out first, see zero_root_deflated.  Undamped (H = h = 0: (6) is
                           even in lambda and the Routh array breaks down): the exact
                           criterion (10) (long double with rounding bounds, else exactly
                           in integers, see autobal_pendulum_undamped_verdict): STABLE = every
                           root on the imaginary axis and semisimple (every x = lambda^2 of
                           (10) real, negative and simple; at k = 1 also the double roots where
                           P1 and conj(P1) of (15) meet, which are semisimple), UNSTABLE
                           otherwise (a root off the axis, or, at R_w = 0 and at k = 0,
                           R_w = 1, a multiple lambda = 0 without enough eigenvectors);
                           MARGINAL only exactly on a critical speed (a double root of (10)
                           whose semisimplicity is not decided).  At k == 0
                           lambda = 0 is then double (the family and its rate) and left out  */
  int verdict_roots;    /* verdict from the roots alone (AUTOBAL_PENDULUM_ROOTS_TOL),
                           with the same deflation (two roots at k == 0 undamped); undamped,
                           roots on the axis within the tolerance give STABLE (rounded roots
                           cannot tell whether a multiple root is semisimple: verdict does) */
  int verdicts_agree;   /* verdict == verdict_roots                                      */
  int n_rhp;            /* roots with Re > 0: damped, by the Routh array (see
                           autobal_poly_hurwitz); undamped, from the roots x of (10) (a
                           positive x gives one, a complex pair of x two); on a boundary a
                           lower bound                                                    */
  int zero_root_deflated; /* 1 when k == 0 exactly and lambda = 0 was divided out        */
  int undamped;         /* 1 when H == 0 and h == 0: (6) is even in lambda, verdict from (10) */
  int undamped_verdict; /* the paper's "first approximation" of (10) as the maps use it:
                           STABLE when all roots x = lambda^2 of (10) are real and <= 0,
                           UNSTABLE otherwise, MARGINAL exactly on a boundary
                           (autobal_pendulum_undamped_verdict; no semisimplicity check);
                           0 when not undamped                                             */
  autobal_pendulum_sufficient cond7; /* (7): R_m << 1 or h >> 1: stable if R_w > 1
                                        (converges slowly: the exact threshold at k = 1 is
                                        R_w1 ~ 1 + 1.5 R_m^(1/3), (17))                 */
  autobal_pendulum_sufficient cond8; /* (8): R_w >> 1: stable if h > H sqrt(R_m) (sharp
                                        at k = 1, sufficient for every k: the threshold
                                        on h is lower for k < 1)                       */
  autobal_pendulum_sufficient cond9; /* (9) corrected: H >> 1: stable iff
                                        R_m k W^2 / h^2 < W - 1, W = R_w^2 (h > 0)       */
} autobal_pendulum_result;

/* Everything about the main motion (4) at p, in one call: (6) and its roots,
 * the eigenvalues of (5), their matching, the sign-test verdict
 * cross-checked with the roots, the margin max Re, the flags of (7)-(9).
 * Allocates nothing (uses ws).  On failure *res is unspecified, the status is
 * returned and recorded in ws.  For very large speeds (R_w of order 1e4) the
 * rounding bounds of the sign test grow like R_w^8 and it may
 * answer MARGINAL where verdict_roots still decides. */
AUTOBAL_API int autobal_pendulum_analyze(autobal_pendulum_workspace *ws,
                                         const autobal_pendulum_params *p,
                                         autobal_pendulum_result *res);

/* The verdict of autobal_pendulum_analyze without roots (cheap, no workspace): damped, builds
 * (6) and runs the Routh test, with the k == 0 deflation; undamped (H = h = 0), the exact
 * criterion (10) (see autobal_pendulum_result.verdict).  *n_rhp (may be NULL): the count of
 * autobal_pendulum_result.n_rhp. */
AUTOBAL_API int autobal_pendulum_verdict(const autobal_pendulum_params *p, int *verdict,
                                         int *n_rhp, autobal_error *err);

/* ======================================================================== */
/* No damping (10)-(12)                                                     */
/* ======================================================================== */

/* P(x) of (10), x = lambda^2, 5 coefficients ascending in x:
 *   P = x (a6 x^3 + a4 x^2 + a2 x + a0) + k R_m^2 (x + R_w^2)^4.
 * Requires R_m in (0, 1/2), R_w >= 0, k in [0, 1]. */
AUTOBAL_API int autobal_pendulum_undamped_poly(double R_m, double R_w, double k, double coef[5],
                                               autobal_error *err);

/* Stability in the first approximation of the undamped system: *verdict =
 * AUTOBAL_VERDICT_STABLE when every root x of (10) is real and <= 0,
 * AUTOBAL_VERDICT_UNSTABLE otherwise, decided by exact sign criteria on the
 * coefficients evaluated in long double with rounding-error bounds (no
 * roots): k = 0: (12) for the cubic (x = 0 divided out); 0 < k < 1: all
 * c_j > 0 and the quartic's discriminant > 0 with 8ac - 3b^2 < 0 and
 * 64a^3e - 16a^2c^2 + 16ab^2c - 16a^2bd - 3b^4 < 0; k = 1: the same test on
 * the factor P1 of (15) at lambda = i mu (four real mu).
 * Where a deciding quantity is within its long double rounding bound the same
 * criteria are evaluated exactly in integers (GMP; R_m, k and W = R_w^2 as the
 * binary fractions they are).  AUTOBAL_VERDICT_MARGINAL only when a deciding
 * quantity is exactly zero (on a critical speed, e.g. a double root).  No
 * workspace. */
AUTOBAL_API int autobal_pendulum_undamped_verdict(double R_m, double R_w, double k, int *verdict,
                                                  autobal_error *err);

/* Condition (12) at k = 0: *lhs = -a2^2 a4^2 + 4 a2^3 a6 + 27 a0^2 a6^2
 * - 18 a0 a2 a4 a6 + 4 a0 a4^3 (the negated discriminant of the cubic) and
 * *stable = (a0 > 0 && a2 > 0 && a4 > 0 && a6 > 0 && lhs <= 0).  Either
 * output may be NULL. */
AUTOBAL_API int autobal_pendulum_cond12(double R_m, double R_w, double *lhs, int *stable,
                                        autobal_error *err);

/* Discriminant of P(x) of (10) with respect to x, as a polynomial in
 * W = R_w^2 of degree <= 12: disc[0..12] ascending in W, built exactly
 * (integer polynomial arithmetic on the coefficients of (10), GMP) and rounded
 * once per coefficient.  Its positive roots are the candidate critical speeds
 * (autobal_pendulum_critical_speeds uses the exact polynomial, not these
 * rounded coefficients: near R_m -> 1/4 its roots are ill-conditioned in them). */
AUTOBAL_API int autobal_pendulum_undamped_discriminant(double R_m, double k, double disc[13],
                                                       autobal_error *err);

/* ======================================================================== */
/* Critical speeds                                                          */
/* ======================================================================== */

typedef enum autobal_crit_kind {
  AUTOBAL_CRIT_LOST = -1,  /* stable just below, not stable just above          */
  AUTOBAL_CRIT_TOUCH = 0,  /* a root of the discriminant where the verdict does
                              not change (e.g. the double root at (18), k = 1)  */
  AUTOBAL_CRIT_GAINED = 1  /* not stable just below, stable just above          */
} autobal_crit_kind;

#define AUTOBAL_PENDULUM_MAX_CRIT 32

/* Critical speeds on the R_w axis, sorted ascending.  Stable intervals:
 * (stable_lo[i], stable_hi[i]) for i < n_stable, stable_hi may be INFINITY. */
typedef struct autobal_pendulum_crit_set {
  size_t n;                                  /* entries of R_w[]/kind[] (incl. touches) */
  double R_w[AUTOBAL_PENDULUM_MAX_CRIT];
  int kind[AUTOBAL_PENDULUM_MAX_CRIT];       /* autobal_crit_kind                      */
  size_t n_stable;
  double stable_lo[AUTOBAL_PENDULUM_MAX_CRIT + 1];
  double stable_hi[AUTOBAL_PENDULUM_MAX_CRIT + 1];
  int truncated;  /* 1: more changes than the capacity; the set covers only up to
                     R_w[n-1] (autobal_pendulum_critical_speeds_damped); else 0 */
  int unresolved; /* 1: two critical speeds of autobal_pendulum_critical_speeds lie in the same
                     ulp of W = R_w^2 (an island or window narrower than a double can show:
                     reported as equal values); else 0 */
} autobal_pendulum_crit_set;

/* Number of entries of s with kind != TOUCH, and the j-th of them (j from
 * 0; NaN if it does not exist). */
AUTOBAL_API size_t autobal_pendulum_crit_count(const autobal_pendulum_crit_set *s);
AUTOBAL_API double autobal_pendulum_crit_get(const autobal_pendulum_crit_set *s, size_t j);

/* Critical speeds of the UNDAMPED system (H = h = 0) for R_m in (0, 1/2),
 * k in [0, 1], located exactly (no sampling, no rounding in any decision), R_w = sqrt(W):
 *  1. the discriminant D(W) of (10) in x is formed as a polynomial in W with
 *     integer coefficients (GMP): R_m and k are the binary fractions r 2^-E and
 *     kappa 2^-F they are, so the coefficients of (10) times 2^(F+2E) are
 *     integer polynomials in W;
 *  2. its positive roots are isolated exactly, recursively between the roots of
 *     its derivatives (D is monotone between them), each down to a bracket of two
 *     adjacent doubles, by exact signs of D at doubles; the multiple roots of D
 *     (double roots of (10), e.g. (18) at k = 1 and W = 1 at k = 0) are the roots
 *     of gcd(D, D'), isolated the same way;
 *  3. the verdict on each interval between consecutive candidates is exact (the
 *     criteria of autobal_pendulum_undamped_verdict on integers) and gives the
 *     kind.  A TOUCH is reported only inside a stable region (a double root of (10)
 *     where stability is kept, e.g. (18) at k = 1, for R_m > R_m^(1) and also
 *     above 1/4); touches in unstable regions are dropped.
 * Accuracy: a few units in the last place (about 1e-16 relative) for every R_m
 * and k, also near R_m -> 1/4 where R_w2, R_w3 ~ 1/(1 - 4R_m).  Resolution: every
 * stable island or unstable window whose ends lie more than one ulp of W apart is
 * reported; two critical speeds within one ulp of W are reported as two equal
 * values with out->unresolved = 1 when D changes sign in the middle of that ulp
 * (a pair closer than half an ulp without that change is not seen).  Cost: 0.1
 * to 1 ms.
 * Capacity: at most 8 candidates (the degree of D after its factor W^4): well
 * below AUTOBAL_PENDULUM_MAX_CRIT, so nothing is ever cut off.
 * Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL ws; R_m outside (0, 1/2) or
 * k outside [0, 1], message naming it; out NULL): *out untouched; or
 * AUTOBAL_ENUMERIC (root isolation or verdict inconsistent; not expected for
 * valid input): *out is then all zeros (n = n_stable = 0).  The message is in
 * ws ("" after success). */
AUTOBAL_API int autobal_pendulum_critical_speeds(autobal_pendulum_workspace *ws, double R_m,
                                                 double k, autobal_pendulum_crit_set *out);

/* Critical speeds of the DAMPED system: p gives R_m, H, h, psi0 (p->R_w is
 * ignored).  The sign-test verdict (autobal_pendulum_verdict) is sampled at
 * n_sweep >= 2 points evenly spaced on [rw_min, rw_max] (0 <= rw_min <
 * rw_max); every change is refined to 1e-12 relative by Brent's method on
 * max Re of the roots of (6) (bisection on the verdict where that is not
 * bracketing).  Kinds are GAINED/LOST only; changes narrower than the
 * sampling step can be missed (documented limitation of any sweep).  The
 * stable intervals are clipped to [rw_min, rw_max] (stable_hi = rw_max for
 * the last one, not INFINITY).  A failure of the final Brent polish is not an
 * error (the bisection's midpoint is kept).
 * Capacity: at most AUTOBAL_PENDULUM_MAX_CRIT changes are recorded (far more
 * than the damped system shows in practice: a scan over R_m, k and H = h from
 * 1e-14 to 1e-3 on R_w in [0, 100] found at most 3).  At the first change that
 * does not fit the search stops (that change is not refined), out->truncated = 1 and
 * AUTOBAL_WARNING is returned with a message naming the capacity and the range
 * covered.  The set then describes [rw_min, R_w[n-1]] only (n = the capacity):
 * the stable intervals end at or before R_w[n-1] -- the verdict after the last
 * recorded change is not extended to rw_max, and a stable interval that begins
 * at R_w[n-1] (kind GAINED) is not listed.  Narrow [rw_min, rw_max] (or split it)
 * to get the rest.  out->truncated = 0 otherwise.
 * Returns AUTOBAL_SUCCESS, AUTOBAL_WARNING (truncated, see above; the data are
 * valid; the message is in ws), or AUTOBAL_EINVAL (NULL ws or p; p invalid apart
 * from R_w, which is ignored; rw_min < 0 or not finite; rw_max <= rw_min or
 * not finite; n_sweep < 2; out NULL): *out untouched; or the status of a
 * verdict or bisection at some speed (AUTOBAL_ENUMERIC, ...): *out is then all
 * zeros.  The message is in ws ("" after success). */
AUTOBAL_API int autobal_pendulum_critical_speeds_damped(autobal_pendulum_workspace *ws,
                                                        const autobal_pendulum_params *p,
                                                        double rw_min, double rw_max,
                                                        size_t n_sweep,
                                                        autobal_pendulum_crit_set *out);

/* Critical-speed curves of the undamped system for one k over an R_m grid:
 * rw[i*n_curve + j] = the j-th critical speed (kind != TOUCH) at R_m[i], or
 * NaN where that branch does not exist (e.g. k = 0, n_curve = 3 gives
 * R_w1 = 1, R_w2, R_w3 of figure 2, R_w2/3 NaN for R_m >= 1/4).
 * Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL ws; k outside [0, 1]; R_m
 * NULL with n_Rm > 0 or rw NULL with n_Rm n_curve > 0; some R_m[i] outside
 * (0, 1/2), named "R_m[i]"): rw untouched (everything is checked before the
 * first row is written); or the status of autobal_pendulum_critical_speeds at
 * R_m[i]: rows 0..i-1 are filled, the others untouched.  Message in ws. */
AUTOBAL_API int autobal_pendulum_critical_curves(autobal_pendulum_workspace *ws, double k,
                                                 const double *R_m, size_t n_Rm, size_t n_curve,
                                                 double *rw);

/* ---- the paper's closed forms and series (for comparison) ------------- */

/* (13): R_w1(R_m, 0) = 1. */
AUTOBAL_API int autobal_pendulum_rw1_k0(double R_m, double *rw1, autobal_error *err);

/* (14), first form (meant for 0 < R_m < 0.05; accepted for R_m in (0, 1/2)):
 *   R_w2 = 1 + (49/16) R_m + (12397/1024) R_m^2,
 *   R_w3 = 1 + 2 eps + (7/3) eps^2 + (29/8) eps^3, eps = (R_m/2)^(1/3). */
AUTOBAL_API int autobal_pendulum_rw23_k0_series_small(double R_m, double *rw2, double *rw3,
                                                      autobal_error *err);

/* (14), second form (meant for 0.05 <= R_m < 0.25; accepted for R_m in
 * (0, 1/4)): R_w2/3 = (1/(8q^2)) (1 -/+ 2q + (11/2) q^2 +/- (37/4) q^3
 * - (155/8) q^4), q = sqrt((0.25 - R_m)/2). */
AUTOBAL_API int autobal_pendulum_rw23_k0_series_large(double R_m, double *rw2, double *rw3,
                                                      autobal_error *err);

/* (16): R_w1(R_m, 1) = sqrt(1 - u^2)/(1 - 2u^2), where u in (0, 1/sqrt 2)
 * solves R_m = (u^3/(1 - 2u^2))^2 (monotone; solved by Brent to 1e-15).
 * *u may be NULL. */
AUTOBAL_API int autobal_pendulum_rw1_k1(double R_m, double *rw1, double *u, autobal_error *err);

/* (17): R_w1(R_m, 1) = 1 + (3/2) s + (7/8) s^2 + (1/48) s^3, s = R_m^(1/3). */
AUTOBAL_API int autobal_pendulum_rw1_k1_series(double R_m, double *rw1, autobal_error *err);

/* (18): R_w2/3(R_m, 1) = sqrt(2(1 - 2R_m))/(1 - 4R_m) (defined for
 * R_m in (0, 1/4); a critical speed only for R_m^(1) < R_m < 1/4, where it is
 * the k -> 1 limit of a narrow unstable window). */
AUTOBAL_API int autobal_pendulum_rw23_k1(double R_m, double *rw23, autobal_error *err);

/* R_m^(1): the R_m at which curves (16) and (18) touch with a common
 * tangent (three critical speeds coincide), computed from the equations to
 * 1e-12; *rw (may be NULL) receives the common R_w there. */
AUTOBAL_API int autobal_pendulum_rm1(double *rm1, double *rw, autobal_error *err);

/* ======================================================================== */
/* Stability maps                                                           */
/* ======================================================================== */

typedef struct autobal_pendulum_map_spec {
  const double *R_m; /* n_Rm values in (0, 1/2)                                  */
  size_t n_Rm;
  const double *R_w; /* n_Rw values >= 0                                         */
  size_t n_Rw;
  double H, h;       /* damping (both 0: the undamped criterion of (10) is used) */
  const double *k;   /* n_k values in [0, 1]; a point is STABLE only if stable
                        for every k ("every unbalance"); NULL with n_k = 0 means
                        the default set k = j/64, j = 0..64                      */
  size_t n_k;
  int n_threads;     /* OpenMP threads: 0 = runtime default, 1 = serial          */
  int paper_convention; /* undamped only (added in 0.3): 0 (what a zeroed spec gives) =
                        the exact verdict of autobal_pendulum_verdict (`pendulum roots`):
                        a root lambda on the imaginary axis must be semisimple, so R_w = 0
                        and, at k = 0, R_w = 1 are UNSTABLE, and a point exactly on a
                        critical speed is MARGINAL (0); non-zero = the paper's "first
                        approximation" of autobal_pendulum_undamped_verdict (all x <= 0;
                        a MARGINAL point counts as STABLE)                                */
} autobal_pendulum_map_spec;

/* Stability map over the grid, row-major [n_Rm][n_Rw]:
 * verdict[i*n_Rw + j] (int8) = the worst verdict over the k set at
 * (R_m[i], R_w[j]):
 *  - damped (H > 0 or h > 0): the Routh-Hurwitz sign test on (6)
 *    (autobal_pendulum_verdict): 1 stable, 0 marginal, -1 unstable;
 *  - undamped (H = h = 0): by default the verdict of autobal_pendulum_verdict (the exact
 *    criterion (10) with semisimplicity: 1 stable, 0 exactly on a critical speed, -1
 *    unstable); with spec->paper_convention that of autobal_pendulum_undamped_verdict
 *    (1 stable in the first approximation, also on a boundary, -1 unstable).
 * max_real (may be NULL) receives the largest real part of the roots of (6)
 * over the k set (for the undamped system this is about 0 when stable, at
 * rounding level); computing it costs a root solve per point and k.
 * Parallel over grid points with OpenMP when built with it; the result is
 * bitwise identical to the serial one.
 * Returns AUTOBAL_SUCCESS (also for an empty grid: nothing written), or:
 *   AUTOBAL_EINVAL, nothing written (the whole spec is validated first): spec
 *     or verdict NULL; R_m or R_w NULL with a non-zero count; H or h < 0 or not
 *     finite; n_threads < 0; k NULL with n_k > 0; an entry R_m[i] outside
 *     (0, 1/2), R_w[j] < 0, k[i] outside [0, 1] or non-finite (named, e.g.
 *     "R_m[3]");
 *   AUTOBAL_ENOMEM: a per-thread workspace (needed only for max_real) could
 *     not be allocated;
 *   the status of a failing grid point (e.g. AUTOBAL_ENUMERIC from a root
 *     solve for max_real), message "map: evaluation failed at a grid point".
 * After AUTOBAL_ENOMEM or a failing point the arrays are partially written
 * (which points are done depends on the threads' schedule); the message is in
 * err. */
AUTOBAL_API int autobal_pendulum_map(const autobal_pendulum_map_spec *spec, signed char *verdict,
                                     double *max_real, autobal_error *err);

/* ======================================================================== */
/* Maps and sweeps over any parameter (docs/pendulum.md, "Maps and sweeps") */
/* ======================================================================== */

/* The parameters (configuration keys of [pendulum]) a map or a sweep can vary.  0 .. 6 are
 * dimensionless (psi0 in rad); H_RATIO is the derived ratio H/h (see
 * autobal_pendulum_params_vary for the rule that turns it into H and h).  7 .. 14 are the
 * physical keys, in SI units (added in 0.3; docs/pendulum.md, "Physical keys on an axis"):
 * at each point the physical set with the key changed is converted by
 * autobal_pendulum_params_from_physical, as the configuration is.  Their ranges here are
 * those of the key alone; the model's domain (M e < 2 m l; R_w, H, h <= 1e6) is checked on
 * the whole set (autobal_pendulum_param_domain). */
enum {
  AUTOBAL_PENDULUM_PARAM_R_W = 0,  /* "R_w"  speed ratio, [0, 1e6]                       */
  AUTOBAL_PENDULUM_PARAM_R_M = 1,  /* "R_m"  mass ratio, (0, 0.5)                        */
  AUTOBAL_PENDULUM_PARAM_H = 2,    /* "H"    external (shaft) damping, [0, 1e6]          */
  AUTOBAL_PENDULUM_PARAM_HP = 3,   /* "h"    pendulum damping, [0, 1e6]                  */
  AUTOBAL_PENDULUM_PARAM_K = 4,    /* "k"    unbalance sin^2(2 psi0), [0, 1]             */
  AUTOBAL_PENDULUM_PARAM_PSI0 = 5, /* "psi0" main-motion angle, rad, [0, pi/2)          */
  AUTOBAL_PENDULUM_PARAM_H_RATIO = 6, /* "H/h" ratio of the dampings, (0, 1e6]           */
  AUTOBAL_PENDULUM_PARAM_M = 7,     /* "M"     rotor mass, kg, > 0                        */
  AUTOBAL_PENDULUM_PARAM_E = 8,     /* "e"     eccentricity, m, >= 0                      */
  AUTOBAL_PENDULUM_PARAM_MP = 9,    /* "m"     mass of each pendulum, kg, > 0             */
  AUTOBAL_PENDULUM_PARAM_L = 10,    /* "l"     rod length, m, > 0                         */
  AUTOBAL_PENDULUM_PARAM_C = 11,    /* "c"     shaft stiffness, N/m, > 0                  */
  AUTOBAL_PENDULUM_PARAM_H1 = 12,   /* "H1"    pendulum viscous moment coeff., N m s, >= 0 */
  AUTOBAL_PENDULUM_PARAM_H2 = 13,   /* "H2"    external viscous damping, N s/m, >= 0      */
  AUTOBAL_PENDULUM_PARAM_OMEGA = 14, /* "omega" rotor speed, rad/s, >= 0                  */
  AUTOBAL_PENDULUM_NPARAM = 15
};

/* The key of a parameter as in the configuration ("R_w", ..., "H/h", "M", ..., "omega"); NULL if
 * unknown. */
AUTOBAL_API const char *autobal_pendulum_param_name(int param);
/* Its name as an HDF5 dimension / dataset name ("H/h" -> "H_over_h"; the others as the key);
 * NULL if unknown. */
AUTOBAL_API const char *autobal_pendulum_param_dim(int param);
/* Its unit ("1", "rad" for psi0, the SI unit of a physical key: "kg", "m", "N/m", "N m s",
 * "N s/m", "rad/s") and a one-line description; NULL if unknown. */
AUTOBAL_API const char *autobal_pendulum_param_unit(int param);
AUTOBAL_API const char *autobal_pendulum_param_description(int param);
/* The parameter of a name ("R_w", "R_m", "H", "h", "k", "psi0", "H/h" or "H_over_h", "M", "e",
 * "m", "l", "c", "H1", "H2", "omega"; exact case: H and h, M and m differ), or -1. */
AUTOBAL_API int autobal_pendulum_param_lookup(const char *name);
/* 1 for a physical key (AUTOBAL_PENDULUM_PARAM_M .. _OMEGA), else 0. */
AUTOBAL_API int autobal_pendulum_param_is_physical(int param);
/* 1 when the dimensionless parameter `dimensionless` (R_w .. H/h) is a function of the physical
 * key `physical` by (2)-(3) (R_w of omega, c, M, m; R_m of M, m; H of H2, c, M, m; h of H1, m, l,
 * c, M; k and psi0 of M, e, m, l; H/h = H2 m l^2 / (H1 (M + 2m)) of H2, H1, m, l, M), else 0.
 * Such a pair cannot be the two axes of a map. */
AUTOBAL_API int autobal_pendulum_param_depends(int dimensionless, int physical);
/* Check one value of a parameter against its range (message: "parameter pendulum.R_m = 0.6
 * is too large: must be < 0.5 (allowed range (0, 0.5))"; a physical key with its unit). */
AUTOBAL_API int autobal_pendulum_param_check(int param, double value, autobal_error *err);
/* The values of the physical key `param` for which phys with that key changed (the others kept)
 * lies in the model's domain (autobal_pendulum_params_from_physical succeeds): an interval,
 * since every condition is monotone in each key.  *lo, *hi: its ends, each the last value found
 * inside (to about 1e-15 relative) or the key's own bound (0; *hi = INFINITY when unbounded).
 * Needs phys itself in the domain.  Returns AUTOBAL_SUCCESS or AUTOBAL_EINVAL (not a physical
 * key; phys outside the domain: the conversion's message). */
AUTOBAL_API int autobal_pendulum_param_domain(const autobal_pendulum_physical *phys, int param, double *lo,
                                              double *hi, autobal_error *err);

/* *out = base with up to two parameters set (param2 = -1: only param1), validated.
 * R_w, R_m, H, h, psi0 are set as given; k sets psi0 = asin(sqrt k)/2 (the convention of
 * autobal_pendulum_params_from_k).  The ratio H/h = r is applied after the other parameter:
 * if the other parameter is H, then h = H / r; otherwise H = r h with h the other
 * parameter's value (when it is h) or base->h.  So a map over (H/h, h) scans the ratio at
 * each pendulum damping, (H/h, R_w) keeps the configured h and sets H.  param1 == param2,
 * H/h together with k or psi0 alone is fine, but H/h with base->h = 0 and no H or h axis
 * is rejected ("H/h needs pendulum.h > 0"), as are k with psi0 and a ratio with both H and
 * h on the other axis (impossible with two axes), and a physical key (it needs the physical
 * set: autobal_pendulum_params_vary_physical).  Returns AUTOBAL_SUCCESS or AUTOBAL_EINVAL
 * (message naming the key, its value and the allowed range); *out is written only on success. */
AUTOBAL_API int autobal_pendulum_params_vary(const autobal_pendulum_params *base, int param1,
                                             double v1, int param2, double v2,
                                             autobal_pendulum_params *out, autobal_error *err);

/* The same with the physical set `phys` that base was converted from (NULL: none; then a physical
 * key is refused, "needs the physical set").  With a physical key on an axis, *out is the
 * conversion (autobal_pendulum_params_from_physical, the configuration's own path) of phys with
 * that key (or both keys) set, and then a dimensionless parameter of the other axis set on it as
 * above; base is then not used.  Without one it is autobal_pendulum_params_vary (phys ignored).
 * Refused (AUTOBAL_EINVAL, message naming the keys): a physical key with a dimensionless one that
 * depends on it (autobal_pendulum_param_depends: e.g. omega with R_w, m with R_m, e with k), H/h
 * with a physical key and phys->H1 = 0, and a point outside the model's domain ("pendulum.e =
 * 0.05 m leaves the model's domain (...): at the other values of this point pendulum.e must lie
 * in [0, 0.04) m").  phys_out (may be NULL): the physical set of the point (phys with the keys
 * set; a copy of phys without a physical axis). */
AUTOBAL_API int autobal_pendulum_params_vary_physical(const autobal_pendulum_params *base,
                                                      const autobal_pendulum_physical *phys, int param1,
                                                      double v1, int param2, double v2,
                                                      autobal_pendulum_params *out,
                                                      autobal_pendulum_physical *phys_out,
                                                      autobal_error *err);

/* A grid over one or two parameters. */
typedef struct autobal_pendulum_grid_spec {
  autobal_pendulum_params base; /* the values of the parameters not on an axis            */
  int param1;                   /* AUTOBAL_PENDULUM_PARAM_* of the rows                   */
  const double *v1;             /* n1 values                                              */
  size_t n1;
  int param2;                   /* of the columns; -1: a line (n2 = 1, v2 ignored)        */
  const double *v2;
  size_t n2;
  const double *k;              /* every unbalance: a point is STABLE only if it is for
                                   every k of these n_k values in [0, 1] (the worst verdict
                                   is kept); NULL and n_k = 0: base's psi0 (one unbalance).
                                   Not with a k or psi0 axis.                             */
  size_t n_k;
  int paper_convention;         /* as in autobal_pendulum_map_spec (0: exact, semisimple) */
  int n_threads;                /* OpenMP threads: 0 = runtime default, 1 = serial        */
  const autobal_pendulum_physical *phys; /* (added in 0.3) the physical set base came from,
                                   needed for a physical axis (each point converted as in
                                   autobal_pendulum_params_vary_physical); NULL: none.
                                   Not with every unbalance and an e axis.               */
} autobal_pendulum_grid_spec;

/* Check a grid spec (every value of both axes, the combination of the axes, the k set)
 * without computing; the message names the bad key and value ("R_m[3]" style for the k set,
 * "pendulum.H = -1 ..." for an axis value). */
AUTOBAL_API int autobal_pendulum_grid_check(const autobal_pendulum_grid_spec *s, autobal_error *err);

/* Verdict at one point (v1, v2) of the grid's parameters (v2 ignored for a line): the worst
 * over the k set, per k that of autobal_pendulum_verdict (damped: Routh-Hurwitz on (6);
 * undamped: the exact criterion (10), or the paper's first approximation with
 * paper_convention).  max_real (may be NULL): the largest real part of the roots of (6)
 * over the k set (a root solve per k; ws is then needed, else ws may be NULL). */
AUTOBAL_API int autobal_pendulum_grid_point(const autobal_pendulum_grid_spec *s, double v1,
                                            double v2, autobal_pendulum_workspace *ws,
                                            int *verdict, double *max_real, autobal_error *err);

/* Stability over the grid: verdict[i*n2 + j] at (v1[i], v2[j]) (n2 = 1 for a line), and
 * max_real likewise (may be NULL; a root solve per point and k).  The axes (R_m, R_w) go
 * through autobal_pendulum_map (bitwise the same verdicts); any other pair is evaluated
 * point by point with autobal_pendulum_grid_point.  OpenMP over points; the result does not
 * depend on the threads.  Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL (nothing written; see
 * autobal_pendulum_grid_check), AUTOBAL_ENOMEM, or the status of a failing point (the
 * arrays then partially written). */
AUTOBAL_API int autobal_pendulum_grid(const autobal_pendulum_grid_spec *s, signed char *verdict,
                                      double *max_real, autobal_error *err);

/* A critical value of param1 on a line (s->param2 = -1): given lo < hi with different
 * verdicts (as autobal_pendulum_grid_point gives them), bisect on the verdict (in log lo ..
 * log hi when log_scale, lo > 0) until hi - lo <= xtol_rel max(|lo|, |hi|) (or 1e-300);
 * *x = the midpoint of the final bracket, *v_lo, *v_hi (may be NULL) the verdicts at its
 * ends.  Where more than one change lies in [lo, hi] one of them is found.  Returns
 * AUTOBAL_SUCCESS, AUTOBAL_EINVAL (bad arguments; equal verdicts at lo and hi) or the
 * status of a point. */
AUTOBAL_API int autobal_pendulum_grid_critical(const autobal_pendulum_grid_spec *s, double lo,
                                               double hi, int log_scale, double xtol_rel,
                                               double *x, int *v_lo, int *v_hi,
                                               autobal_error *err);

/* ======================================================================== */
/* Equations of motion (1)                                                  */
/* (reserved: transients, src/models/pendulum/pendulum_motion.c, another module owner)      */
/* ======================================================================== */

/* The explicit first-order form of (1) (src/models/pendulum/pendulum_motion.c).
 *
 * State: 8 doubles, dimensionless, in this order
 *     y = (xi, eta, psi, phi, xi', eta', psi', phi'),
 * displacements of the shaft centre in units of l along the rotating axes
 * X, Y (parallel to U, V), pendulum angles in radians (psi counter-clockwise
 * from +V, phi clockwise from -V), primes d/dtau, tau = omega0 t.
 * The 4x4 acceleration system of (1) reduces to a 2x2 system for the
 * absolute acceleration of the shaft centre, solved in closed form (its
 * determinant is >= 1 - 2R_m > 0); no allocation, O(1).
 *
 * The right-hand side and Jacobian have GSL's signatures (and those of
 * autobal_transient_system): params is a `const autobal_pendulum_params *`
 * passed as void*; it is not validated per call (validate once with
 * autobal_pendulum_params_validate() before a run).  They return
 * AUTOBAL_SUCCESS, AUTOBAL_EINVAL (NULL argument) or AUTOBAL_ENUMERIC (the
 * acceleration system is singular: only for R_m >= 1/2 or NaN input).
 * Use, with transient.h:
 *     autobal_transient_system sys = {autobal_pendulum_rhs, autobal_pendulum_jac,
 *                                     AUTOBAL_PENDULUM_STATE_DIM, (void *)&params};
 */
#define AUTOBAL_PENDULUM_STATE_DIM 8
enum {
  AUTOBAL_PENDULUM_Y_XI = 0,
  AUTOBAL_PENDULUM_Y_ETA = 1,
  AUTOBAL_PENDULUM_Y_PSI = 2,
  AUTOBAL_PENDULUM_Y_PHI = 3,
  AUTOBAL_PENDULUM_Y_DXI = 4,
  AUTOBAL_PENDULUM_Y_DETA = 5,
  AUTOBAL_PENDULUM_Y_DPSI = 6,
  AUTOBAL_PENDULUM_Y_DPHI = 7
};

/* dydt = f(tau, y) of (1) (autonomous: tau is unused). */
AUTOBAL_API int autobal_pendulum_rhs(double tau, const double y[], double dydt[], void *params);

/* Analytic Jacobian of autobal_pendulum_rhs: dfdy[i*8 + j] = d f_i / d y_j
 * (64 doubles, row-major), dfdt[8] = 0.  At the main motion (4) it equals
 * the first-order matrix of the linearization (5). */
AUTOBAL_API int autobal_pendulum_jac(double tau, const double y[], double *dfdy, double dfdt[],
                                     void *params);

/* Prepared parameters for long runs: the same right-hand side and Jacobian
 * with sin(psi0) computed once (about 15% faster per evaluation).
 * autobal_pendulum_motion_init() validates p (autobal_pendulum_params_validate)
 * and fills *m; the *_motion_rhs/jac functions take params = an
 * autobal_pendulum_motion * and are otherwise identical to the ones above. */
typedef struct autobal_pendulum_motion {
  autobal_pendulum_params p; /* the parameters */
  double sin_psi0;           /* sin(p.psi0) */
} autobal_pendulum_motion;
AUTOBAL_API int autobal_pendulum_motion_init(autobal_pendulum_motion *m,
                                             const autobal_pendulum_params *p, autobal_error *err);
AUTOBAL_API int autobal_pendulum_motion_rhs(double tau, const double y[], double dydt[],
                                            void *motion);
AUTOBAL_API int autobal_pendulum_motion_jac(double tau, const double y[], double *dfdy,
                                            double dfdt[], void *motion);

/* The state of the main motion (4): xi = eta = 0, psi = phi = psi0, at rest
 * in the rotating frame (8 doubles). */
AUTOBAL_API void autobal_pendulum_main_motion(const autobal_pendulum_params *p, double y[]);

/* Angle wrapped to (-pi, pi]. */
AUTOBAL_API double autobal_pendulum_wrap_angle(double a);

/* Shaft displacement amplitude sqrt(xi^2 + eta^2), in units of l. */
AUTOBAL_API double autobal_pendulum_shaft_amplitude(const double y[]);

/* Residual unbalance of rotor plus pendulums about the shaft centre O, in
 * units of 2 m l: the vector sum of M e along +U and the pendulum moments
 * m l (-sin psi, cos psi) and m l (-sin phi, -cos phi), divided by 2 m l:
 *     d_u = sin psi0 - (sin psi + sin phi)/2,   d_v = (cos psi - cos phi)/2
 * (sin psi0 = M e/(2 m l)).  In (1) it enters as the centrifugal forcing
 * 2 R_m R_w^2 (d_u, d_v).  Zero at the main motion (4) and at
 * psi = phi = pi - psi0; equals sin psi0 for pendulums that cancel each
 * other (psi = phi = 0).  Multiply by 2 R_m for units of M_sigma l.
 * Returns |d|; d_u, d_v may be NULL. */
AUTOBAL_API double autobal_pendulum_residual_unbalance(const autobal_pendulum_params *p,
                                                       const double y[], double *d_u,
                                                       double *d_v);

/* |d| above with the signature of a transient scalar/event function
 * (params = const autobal_pendulum_params *), for the "time to balance"
 * dwell event: autobal_transient_add_dwell_event(tr,
 * autobal_pendulum_unbalance_scalar, &params, tolerance, duration, 0). */
AUTOBAL_API double autobal_pendulum_unbalance_scalar(double tau, const double y[], void *params);

/* Jacobi integral of the rotating frame (the model at constant speed), in
 * units of M_sigma l^2 omega0^2, constants dropped:  E = T2 - T0 + V, where
 * with the positions of the rotor's centre of mass and the pendulum masses
 * relative to K in the rotating axes,
 *   T2 = 1/2 sum m |r'|^2  (velocities relative to the rotating frame)
 *      = 1/2 (xi'^2 + eta'^2 + R_m (psi'^2 + phi'^2))
 *        - R_m xi' (psi' cos psi + phi' cos phi) - R_m eta' (psi' sin psi - phi' sin phi),
 *   T0 = 1/2 R_w^2 sum m |r|^2
 *      = 1/2 R_w^2 (xi^2 + eta^2 + 2 R_m (xi (2 sin psi0 - sin psi - sin phi)
 *                                        + eta (cos psi - cos phi))) + const,
 *   V  = 1/2 (xi^2 + eta^2).
 * The Lagrangian in the rotating frame is T2 + T1 + T0 - V (T1 linear in
 * the velocities, gyroscopic); it does not depend on time, so
 * dE/dtau = the power of the damping forces (autobal_pendulum_jacobi_power),
 * and E is conserved when H = h = 0. */
AUTOBAL_API double autobal_pendulum_jacobi_integral(const autobal_pendulum_params *p,
                                                    const double y[]);

/* dE/dtau = -H [(xi' - R_w eta) xi' + (eta' + R_w xi) eta'] - R_m h (psi'^2 + phi'^2)
 * (<= 0 is not guaranteed: the external damping force is opposite to the
 * absolute velocity, the power is taken in the rotating frame). */
AUTOBAL_API double autobal_pendulum_jacobi_power(const autobal_pendulum_params *p,
                                                 const double y[]);

/* Quantities derived from a state, as written to the archive. */
typedef struct autobal_pendulum_motion_derived {
  double amplitude;   /* sqrt(xi^2 + eta^2), units of l                              */
  double unbalance;   /* |residual unbalance|, units of 2 m l                        */
  double unbalance_u; /* its components along U and V                                */
  double unbalance_v;
  double alpha;       /* psi - psi0 wrapped to (-pi, pi], rad (the other balanced
                         state psi = phi = pi - psi0 shows alpha = beta = pi - 2 psi0) */
  double beta;        /* phi - psi0 wrapped to (-pi, pi], rad                        */
  double jacobi;      /* Jacobi integral E, units of M_sigma l^2 omega0^2            */
} autobal_pendulum_motion_derived;

AUTOBAL_API void autobal_pendulum_motion_derive(const autobal_pendulum_params *p,
                                                const double y[],
                                                autobal_pendulum_motion_derived *out);
/* The same numbers, bit for bit, for a state of the motion m (autobal_pendulum_motion_init):
 * sin(psi0) taken from m instead of computed at every call (the transient's output points). */
AUTOBAL_API void autobal_pendulum_motion_derive_m(const autobal_pendulum_motion *m,
                                                  const double y[],
                                                  autobal_pendulum_motion_derived *out);
/* The same quantities by the library's own sine, cosine and hypot instead of libm's (the
 * transient study with output = dense6, whose interpolated states are new in 0.2.0): sin and cos
 * within 1 ulp of libm's (branch-free fdlibm kernels), hypot as sqrt(a^2 + b^2) below 1.5 ulp
 * (libm's hypot for tiny, huge or non-finite arguments); the other expressions as derive_m. */
AUTOBAL_API void autobal_pendulum_motion_derive_fast(const autobal_pendulum_motion *m,
                                                     const double y[],
                                                     autobal_pendulum_motion_derived *out);
/* The numbers of autobal_pendulum_motion_derive_fast, bit for bit, for n states at once (the
 * buffered output points of a run with output = dense6), by columns: y[j][k] is component j of
 * state k (j < 8, k < n), and d[0..6][k] receive amplitude, unbalance, unbalance_u, unbalance_v,
 * alpha, beta and jacobi of state k (the order of autobal_pendulum_motion_derived).  One
 * vectorizable pass over the states (4 per instruction with AVX2), then libm for the rare states
 * out of the fast paths' ranges.  The arrays must not overlap. */
AUTOBAL_API void autobal_pendulum_motion_derive_fast_cols(const autobal_pendulum_motion *m, size_t n,
                                                          const double *const y[8], double *const d[7]);

AUTOBAL_END_DECLS

#endif
