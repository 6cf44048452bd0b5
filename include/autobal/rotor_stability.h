/* autobal/rotor_stability.h: balanced ("main") motions of the rotor with ball
 * autobalancers, their stability, critical speeds, sweeps and maps, natural
 * frequencies, the Campbell diagram and the unbalance response
 * (docs/rotor.md, "Balanced motions (3.14)", "Stability of a balanced motion
 * (3.15), (3.16)", "Anisotropic supports: Floquet multipliers").
 *
 * The balanced motion.  x = y = alpha = beta = 0, every ball at rest relative
 * to the rotor at angles psi~_i with sum_i m_i r_i e^{i psi~_i} = -m0 r0 e^{i psi0}
 * in every plane (3.14).  For n = 2 balls the configuration is unique (up to
 * swapping); for n >= 3 the balanced angles form an (n-2)-parameter family and
 * the verdict depends on the member: see autobal_rotor_member.
 *
 * Four computations of the linear stability of a balanced motion
 * (autobal_rotor_stab_method):
 *
 *  POLY  (isotropic supports, one plane, common h_i/m_i = kappa): the rotor
 *    equations rotated with the shaft, W = (x + i y) e^{-i w t},
 *    Theta = (beta - i alpha) e^{-i w t}, p(f) = f'' + 2 i w f' - w^2 f,
 *    q(f) = f' + i w f (docs/rotor.md):
 *      M p(W) + h q(W) + c W - h_c q(Theta) - c_c Theta + p(sigma) = 0
 *      A p(Theta) + (h_t - i C w) q(Theta) + c_t Theta - h_c q(W) - c_c W + d p(sigma) = 0
 *    closed by the corrected complex (3.16) for sigma = s_xi + i s_eta,
 *      sigma'' + kappa sigma' = (1/2) (Q conj(a) - m_b a),   a = p(W + d Theta),
 *    m_b = sum_i m_i, Q = sum_i m_i e^{2 i psi~_i} (= m sum e^{2 i psi~_i} for
 *    identical balls).  With P = lambda + i w, Pb = lambda - i w and X* the
 *    polynomial with conjugated coefficients, the degree-12 real characteristic
 *    polynomial is
 *      K11 = M P^2 + h P + c,  K12 = -(h_c P + c_c),  K22 = A P^2 + (h_t - i C w) P + c_t
 *      D = K11 K22 - K12^2,  N = K22 - 2 d K12 + d^2 K11,
 *      F = (lambda^2 + kappa lambda) D - (m_b / 2) P^4 N,
 *      Delta = F F* - (|Q| / 2)^2 P^4 Pb^4 N N*
 *    (D, N, F, Delta of docs/rotor.md; in the FULL inertia model K11 += m_a P^2,
 *    K12 += m_a d P^2, K22 += m_a d^2 P^2 with m_a = m0 + sum m_i, which leaves N
 *    unchanged).  It is built by complex polynomial arithmetic and solved with
 *    GSL (autobal_poly_roots) after the substitution lambda = w_s s, w_s =
 *    |Delta_0 / Delta_12|^{1/12} (roots are returned in 1/s).
 *  CLOSED (isotropic, one or two planes, common kappa per plane): the same closed
 *    linear system written as a real first-order system of dimension 8 + 4 n_planes
 *    (state: Re/Im of W, Theta, sigma_j, then their rates) and its eigenvalues
 *    (GSL gsl_eigen_nonsymm).  For one plane its eigenvalues are the roots of
 *    Delta (an independent computation of the same numbers).
 *  FULL (isotropic): the linearization of the full transient model (every ball
 *    angle, no closure) about the balanced state, written in fully rotating
 *    coordinates.  The model's rotating-frame right-hand side
 *    (autobal_rotor_rhs_rotating) keeps the rotor coordinates in the fixed frame,
 *    so its Jacobian J(t) at the (constant) balanced state is time-periodic.  With
 *    z = T(t) y, T = [[S, 0], [S', S]], S(t) = blockdiag(R(-w t), R(-w t) P)
 *    acting on (x, y) and on (alpha, beta) (R a rotation, P (alpha, beta) =
 *    (beta, -alpha), so that S maps to (Re W, Im W, Re Theta, Im Theta)), one finds
 *    S^-1 S' = Omega = w blockdiag(J2, J2), J2 = [[0, 1], [-1, 0]], hence
 *    T^-1 T' = blockdiag(Omega, Omega), and for isotropic supports
 *        T^-1 (dz/dt Jacobian) T = J(t) + blockdiag(Omega, Omega, 0)
 *    is constant: its eigenvalues (at t = 0, where T = I on the balls) are the
 *    characteristic roots of the full model.  For n balls in a plane they are the
 *    closed roots plus n - 2 zeros (the neutral family) and n - 2 roots
 *    -kappa (identical kappa), when the balls are not all on one line.
 *  FLOQUET (any supports): the variational equation Phi' = J(t) Phi of the
 *    (8 + 2N)-dimensional linearization (mixed frame: rotor coordinates fixed,
 *    ball angles relative), integrated over one period T = 2 pi / |w| from the
 *    identity with the transient driver (rk8pd), and the eigenvalues mu of the
 *    monodromy matrix Phi(T).  For isotropic supports mu = exp(lambda T) for the
 *    roots lambda of FULL (the similarity T(t) is 2 pi / w periodic).  The state
 *    is scaled by a constant diagonal similarity (lengths by sum m_i r_i / M,
 *    rates by a natural frequency) which does not change mu.
 *  J(t) for FULL and FLOQUET is the analytic linearization of (3.2) + (3.13):
 *    M(t) X'' + C(t) X' + K(t) X = 0, X = (x, y, alpha, beta, dpsi_1..N), with
 *    d(s_u + i s_v) = sum_i i m_i r_i e^{i (w t + psi~_i)} dpsi_i and
 *    dpsi_i'' + kappa_i dpsi_i' = (sin phi~_i (x'' + d beta'') - cos phi~_i (y'' - d alpha'')) / r_i,
 *    phi~_i = w t + psi~_i; it is checked in the tests against central differences
 *    of the model's own autobal_rotor_rhs_rotating (autobal_rotor_model_jacobian).
 *
 * Verdict and margin.  The margin is the largest real part of the roots (1/s),
 * for FLOQUET log(max |mu|) / T; the roots (multipliers) of the neutral family,
 * n_j - rank_j per plane (n - 2 for n >= 3 balls not all on one line), are
 * excluded: they are the ones closest to 0 (to 1).  The verdict is then the
 * stability of the family, not asymptotic stability of one configuration.
 * Verdict: STABLE if margin < -tol * scale, UNSTABLE if > tol * scale, else
 * MARGINAL, with scale = max(1/s, largest |root|) (FLOQUET: scale = 1/T).
 * The closure needs the balls of a plane not all on one line through the axis
 * (for n = 2: 0 < m0 r0 < 2 m r strictly); otherwise AUTO uses FULL.
 *
 * Units: SI (rad/s, 1/s, kg, m).  Axial motion (2.12) is decoupled and always
 * ignored here.
 *
 * Threads: a handle (autobal_rotor_stab) owns all its workspaces; one handle per
 * thread; two handles never interfere.  Nothing allocates after _alloc except
 * where said.  The library never prints.  A host program should call
 * gsl_set_error_handler_off() once.
 *
 * Errors: functions return AUTOBAL_SUCCESS or a negative status with the message
 * on the handle (autobal_rotor_stab_errmsg) or in err; autobal_rotor_stab_critical
 * and autobal_rotor_resonance_speeds also return the positive AUTOBAL_WARNING when
 * a list was full (truncated = 1; the data are valid).  After a failure, output
 * arrays hold unspecified values (NaN where possible) and the handle stays usable.
 */
#ifndef AUTOBAL_ROTOR_STABILITY_H
#define AUTOBAL_ROTOR_STABILITY_H

#include <stddef.h>

#include "autobal/export.h"
#include "autobal/rotor.h"
#include "autobal/status.h"

AUTOBAL_BEGIN_DECLS

/* Number of coefficients of Delta (degree 12). */
#define AUTOBAL_ROTOR_POLY_LEN 13
/* Largest dimension of the closed first-order system (two planes). */
#define AUTOBAL_ROTOR_CLOSED_MAX 16
/* Capacity of the critical-speed and interval lists. */
#define AUTOBAL_ROTOR_MAX_CRIT 64
/* Verdict code used in sweeps and maps when no balanced configuration exists
 * (or it cannot be analysed) at a point; the margin is NaN there. */
#define AUTOBAL_ROTOR_VERDICT_NONE (-2)
/* Verdict code of a map point for every unbalance with anisotropic supports (Hill's method) when the
 * box budget (opt.hill_boxes) ran out before the range was proven stable and no member was found
 * unstable: undecided, never counted as stable; the margin is the largest Floquet margin met. */
#define AUTOBAL_ROTOR_VERDICT_UNDECIDED (-3)

/* ---- members of the family of balanced configurations ---------------------- */

typedef enum autobal_rotor_member_kind {
  /* n <= 2: the unique configuration (n = 2: autobal_rotor_balanced_angles_two,
   * ball 1 on the "-" side); n >= 3 with identical m_i r_i: SYMMETRIC; otherwise
   * FREE with the first n - 2 angles of autobal_rotor_balanced_angles() at the
   * parameters given to autobal_rotor_stab_alloc (held fixed in sweeps). */
  AUTOBAL_ROTOR_MEMBER_DEFAULT = 0,
  /* the symmetric fan psi_i = psi0 + pi + (i - (n-1)/2) delta (identical m_i r_i
   * only; recomputed at every point of a sweep) */
  AUTOBAL_ROTOR_MEMBER_SYMMETRIC = 1,
  /* balls 1 .. n-2 at the given angles (n_angles = n - 2), the last two placed by
   * the closed form for two balls (the "-" solution first) */
  AUTOBAL_ROTOR_MEMBER_FREE = 2,
  /* all n angles given; they must balance: |sum m_i r_i e^{i psi_i} + m0 r0 e^{i psi0}|
   * <= 1e-9 (m0 r0 + sum m_i r_i) */
  AUTOBAL_ROTOR_MEMBER_GIVEN = 3
} autobal_rotor_member_kind;

typedef struct autobal_rotor_member {
  int kind;              /* autobal_rotor_member_kind */
  size_t n_angles;       /* FREE: n - 2; GIVEN: n; else ignored */
  const double *angles;  /* rad, relative to the rotor; copied at alloc */
} autobal_rotor_member;

/* Balanced angles psi[0..n-1] (rad, wrapped to (-pi, pi]) of one plane for the
 * member `mem` (NULL: DEFAULT; DEFAULT for n >= 3 with unequal m_i r_i builds
 * the member like autobal_rotor_balanced_angles).  Returns AUTOBAL_SUCCESS, or
 * AUTOBAL_EINVAL (no balanced configuration, bad member: wrong count, unreachable
 * target for the last two balls, SYMMETRIC with unequal m_i r_i, GIVEN angles
 * that do not balance).  Allocation-free. */
AUTOBAL_API int autobal_rotor_member_angles(const autobal_rotor_plane *pl,
                                            const autobal_rotor_member *mem, double *psi,
                                            size_t n, autobal_error *err);

/* ---- the closed linear system (isotropic supports) ------------------------- */

typedef struct autobal_rotor_closed_plane {
  double d;        /* m, plane coordinate */
  double mass;     /* kg, m_b = sum_i m_i */
  double Q_re;     /* kg, Re sum_i m_i e^{2 i psi~_i} */
  double Q_im;     /* kg, Im of the same */
  double kappa;    /* 1/s, common h_i / m_i */
  double m_add;    /* kg, m0 + sum m_i in the FULL inertia model, else 0 */
  size_t n_balls;
  size_t rank;     /* rank (0..2) of dpsi -> dsigma at the member */
  size_t family;   /* n_balls - rank: dimension of the neutral family */
} autobal_rotor_closed_plane;

typedef struct autobal_rotor_closed {
  autobal_rotor_lumped L;  /* lumped coefficients (c = c_x, c_t = c_alpha, c_c = c_xbeta, ...) */
  double omega;            /* rad/s */
  size_t n_planes;
  autobal_rotor_closed_plane plane[AUTOBAL_ROTOR_MAX_PLANES];
  int isotropic;           /* 1 if c_x = c_y, c_alpha = c_beta, c_xbeta = c_yalpha and the
                              same for h (relative 1e-12) */
  int closure_ok;          /* 1 if every plane has rank 2 and a common kappa (relative 1e-12) */
} autobal_rotor_closed;

/* Characteristic polynomial Delta (see the top) of a one-plane closed system:
 * coef[0..12] ascending powers of lambda (lambda in 1/s).  cerr (may be NULL)
 * receives a running bound of the absolute rounding error of each coefficient
 * (for autobal_poly_hurwitz_err).  AUTOBAL_EINVAL: NULL, n_planes != 1, not
 * isotropic.  Allocation-free. */
AUTOBAL_API int autobal_rotor_char_poly(const autobal_rotor_closed *c, double coef[13],
                                        double cerr[13], autobal_error *err);

/* Dimension of the closed first-order system: 8 + 4 n_planes. */
AUTOBAL_API size_t autobal_rotor_closed_dim(const autobal_rotor_closed *c);

/* The real first-order matrix (row-major, dim x dim, dim = autobal_rotor_closed_dim)
 * of the closed system in rotating coordinates; state (Re W, Im W, Re Theta, Im Theta,
 * Re sigma_1, Im sigma_1, [.. sigma_2], then the rates in the same order).
 * AUTOBAL_EINVAL: NULL, wrong dim, not isotropic; AUTOBAL_ENUMERIC: singular mass
 * matrix.  Allocates a small GSL LU workspace per call. */
AUTOBAL_API int autobal_rotor_closed_matrix(const autobal_rotor_closed *c, double *a, size_t dim,
                                            autobal_error *err);

/* ---- the analysis handle ----------------------------------------------------- */

typedef enum autobal_rotor_stab_method {
  AUTOBAL_ROTOR_STAB_AUTO = 0,    /* POLY if possible, else CLOSED, else FULL, else FLOQUET */
  AUTOBAL_ROTOR_STAB_POLY = 1,
  AUTOBAL_ROTOR_STAB_CLOSED = 2,
  AUTOBAL_ROTOR_STAB_FULL = 3,
  AUTOBAL_ROTOR_STAB_FLOQUET = 4
} autobal_rotor_stab_method;

/* Static name: "auto", "poly", "closed", "full", "floquet" ("unknown"). */
AUTOBAL_API const char *autobal_rotor_stab_method_name(int method);

/* Parameters a sweep or map can vary (autobal_rotor_stab_set).  Besides the named ids below,
 * every numeric key of the rotor's configuration is a parameter (a parameter is a config key):
 *   - a field of autobal_rotor_hardware: AUTOBAL_ROTOR_PARAM_HARDWARE(i), i the index into
 *     autobal_rotor_hardware_fields(), named by its key "rotor.M_k", "supports.c_Lx", ...
 *     (only for parameters given as hardware: the lumped set is recomputed from it);
 *   - a field of autobal_rotor_lumped: AUTOBAL_ROTOR_PARAM_LUMPED(i), "lumped.c_x", ...
 *     (only for parameters given as a lumped set);
 *   - a key of plane j (0-based; "plane1" is j = 0): AUTOBAL_ROTOR_PARAM_PLANE(j, f) with f an
 *     autobal_rotor_plane_key, named "plane1.d", "plane1.m0", "plane1.r0", "plane1.psi0",
 *     "plane1.unbalance" (m0 r0, kg m: sets m0 = value / r0), "plane1.ball_mass",
 *     "plane1.ball_radius" (the track radius), "plane1.ball_damping" (the last three set every
 *     ball of that plane).
 * The hardware and lumped fields may also be named without their section ("c_Lx", "c_x": the
 * names are unique), and omega as "rotor.omega".  Every value goes through the model's own
 * checks (autobal_rotor_params_check): a value the model refuses fails with a message naming
 * the key and the allowed range. */
typedef enum autobal_rotor_stab_param {
  AUTOBAL_ROTOR_PARAM_OMEGA = 0,           /* rad/s, spin speed (!= 0 for the analysis) */
  AUTOBAL_ROTOR_PARAM_BALL_DAMPING = 1,    /* kg/s, h_i of every ball of every plane, >= 0 */
  AUTOBAL_ROTOR_PARAM_BALL_MASS = 2,       /* kg, m_i of every ball of every plane, > 0 */
  AUTOBAL_ROTOR_PARAM_STIFFNESS_SCALE = 3, /* 1, factor on every support stiffness (all c_ of
                                              the lumped set), > 0 */
  AUTOBAL_ROTOR_PARAM_DAMPING_SCALE = 4,   /* 1, factor on every support viscosity, >= 0 */
  AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS = 5,  /* kg, m0 of every plane, >= 0 */
  AUTOBAL_ROTOR_PARAM_ANISOTROPY = 6,      /* 1, "anisotropy" > 0: the y stiffnesses become this
                                              factor times the x ones (hardware: c_Ly = a c_Lx,
                                              c_Ry = a c_Rx; lumped: c_y = a c_x, c_alpha = a c_beta,
                                              c_yalpha = a c_xbeta); 1 is isotropic stiffness */
  AUTOBAL_ROTOR_PARAM_C_OVER_A = 7         /* 1, "C_over_A" >= 0: the polar moment of inertia C
                                              (hardware: C_p) set to this factor times the
                                              transverse one A = A_k + A_p */
} autobal_rotor_stab_param;

/* The keys of a plane (the f of AUTOBAL_ROTOR_PARAM_PLANE). */
typedef enum autobal_rotor_plane_key {
  AUTOBAL_ROTOR_PLANE_D = 0,            /* m, "d" */
  AUTOBAL_ROTOR_PLANE_M0 = 1,           /* kg, "m0" */
  AUTOBAL_ROTOR_PLANE_R0 = 2,           /* m, "r0" */
  AUTOBAL_ROTOR_PLANE_PSI0 = 3,         /* rad, "psi0" (with two planes: the phase of one
                                           unbalance against the other) */
  AUTOBAL_ROTOR_PLANE_UNBALANCE = 4,    /* kg m, "unbalance" = m0 r0 */
  AUTOBAL_ROTOR_PLANE_BALL_MASS = 5,    /* kg, "ball_mass" of every ball of the plane */
  AUTOBAL_ROTOR_PLANE_BALL_RADIUS = 6,  /* m, "ball_radius" (track radius) of every ball */
  AUTOBAL_ROTOR_PLANE_BALL_DAMPING = 7, /* kg/s, "ball_damping" of every ball */
  AUTOBAL_ROTOR_PLANE_N_KEYS = 8
} autobal_rotor_plane_key;

#define AUTOBAL_ROTOR_PARAM_HARDWARE(i) (100 + (int)(i))
#define AUTOBAL_ROTOR_PARAM_LUMPED(i) (200 + (int)(i))
#define AUTOBAL_ROTOR_PARAM_PLANE(j, f) (300 + 16 * (int)(j) + (int)(f))

/* Name (the config key: "omega", "ball_damping", "ball_mass", "stiffness_scale",
 * "damping_scale", "unbalance_mass", "anisotropy", "C_over_A", "supports.c_Lx", "lumped.c_x",
 * "plane1.d", ...) and SI unit ("rad/s", "kg/s", "kg", "1", ...) of a parameter id.  Static
 * strings owned by the library (never free them; valid for the life of the program); NULL for
 * an unknown id. */
AUTOBAL_API const char *autobal_rotor_stab_param_name(int param);
AUTOBAL_API const char *autobal_rotor_stab_param_unit(int param);
/* Parameter id from its name (exact, case-sensitive; the aliases above included); -1 if
 * unknown or NULL. */
AUTOBAL_API int autobal_rotor_stab_param_from_name(const char *name);
/* Every parameter id, in a fixed order (the named ids, then hardware, lumped and plane keys):
 * writes min(n, count) ids into ids (may be NULL with n = 0) and returns the count. */
AUTOBAL_API size_t autobal_rotor_stab_param_list(int *ids, size_t n);

typedef struct autobal_rotor_stab_options {
  int method;        /* autobal_rotor_stab_method for verdicts and sweeps (default AUTO) */
  autobal_rotor_member member[AUTOBAL_ROTOR_MAX_PLANES]; /* default: all DEFAULT */
  double tol;        /* relative verdict tolerance (default 1e-9) */
  double floquet_rtol; /* relative tolerance of the monodromy integration (default 1e-11) */
  double floquet_atol; /* absolute tolerance, scaled state (default 1e-13) */
  /* the members of plane 1 that the every-unbalance analysis (autobal_rotor_stab_every_unbalance,
     its speeds and map) covers for three or more identical balls: autobal_rotor_unbalance_member
     (added at the end; no effect with two balls, whose member is unique)     (default EVERY) */
  int unbalance_member;
  /* two planes, every unbalance (autobal_rotor_stab_every_unbalance2 and the calls that use it): the
     budget of the certified box search over plane 2's whole range, boxes per side of the frequency
     axis.  0 (the default; also a zeroed struct): 100000; -1: no box search (plane 2 on its grid
     alone: faster, exact_in_s2 = 0); else in [1, 1e9].  The per-slice searches after an undecided
     range search take at most 5000 (or this budget if smaller).  (Added at the end.) */
  long unbalance2_boxes;
  /* one plane, 4 to 10 identical balls, unbalance_member EVERY: the budget of boxes of the branch-and-bound
     enclosure of u over the members (both searches together; docs/rotor.md "Four or more balls, every
     member").  0 (the default; also a zeroed struct): 4000000; else in [1000, 1e9].  When the budget
     ends first the bounds stay valid, wider (u_enclosure_complete = 0).  (Added at the end.) */
  long member_boxes;
  /* one plane, two balls, ANISOTROPIC supports, every unbalance: the budget of boxes (nu, theta) of the Hill
     exclusion (docs/rotor.md "Anisotropic supports: Hill's method").  0 (the default; also a zeroed
     struct): 20000; else in [100, 1e8].  When the budget ends first, the boxes left open are sampled by
     Floquet: an unstable member found is "not stable", else the verdict is undecided (never "stable").
     (Added at the end.) */
  long hill_boxes;
} autobal_rotor_stab_options;

/* The member rule of the every-unbalance analysis with n >= 3 balls (docs/rotor.md "Every
 * unbalance"). */
typedef enum autobal_rotor_unbalance_member {
  /* every member of the family (wherever the balls settle): three identical balls (exact range of
     u = |Q|^2 / 4 in closed form); four to ten (a certified enclosure of the range of u, members found
     inside it); not available for n >= 11 (AUTOBAL_EUNSUPPORTED with a message) */
  AUTOBAL_ROTOR_UNBALANCE_EVERY = 0,
  /* the symmetric fan psi_i = psi0 + pi + (i - (n-1)/2) delta (AUTOBAL_ROTOR_MEMBER_SYMMETRIC) */
  AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC = 1
} autobal_rotor_unbalance_member;

AUTOBAL_API autobal_rotor_stab_options autobal_rotor_stab_options_default(void);

typedef struct autobal_rotor_stab autobal_rotor_stab;

/* Validate p (autobal_rotor_params_check; a warning is fine) and the options, copy
 * them (ball arrays and member angles included) and allocate every workspace
 * (polynomial and eigenvalue workspaces, LU, the Floquet integrator of dimension
 * (8 + 2N)^2).  The balanced angles are not computed yet (a missing balanced
 * configuration is reported by the analysis, not here).  Returns NULL on failure
 * (err: AUTOBAL_EINVAL, AUTOBAL_ENOMEM). */
AUTOBAL_API autobal_rotor_stab *autobal_rotor_stab_alloc(const autobal_rotor_params *p,
                                                         const autobal_rotor_stab_options *opt,
                                                         autobal_error *err);
AUTOBAL_API void autobal_rotor_stab_free(autobal_rotor_stab *s); /* NULL is safe */
/* The handle's last message (owned by the handle); never NULL: "rotor stability
 * handle is NULL" for s == NULL.  A function given a NULL handle returns
 * AUTOBAL_EINVAL without recording any message (there is nowhere to record it). */
AUTOBAL_API const char *autobal_rotor_stab_errmsg(const autobal_rotor_stab *s);

/* A cancellation hook: return non-zero to stop (it may be called often, e.g. read a
 * sig_atomic_t flag; called from the thread that uses the handle). */
typedef int (*autobal_rotor_stab_cancel_fn)(void *user);
/* Install (fn NULL: remove) the handle's cancellation hook.  autobal_rotor_stab_sweep and
 * autobal_rotor_stab_critical poll it before every margin evaluation (grid points and the
 * evaluations of a refinement) and return AUTOBAL_ECANCELLED ("cancelled by the caller" on
 * the handle) when it returns non-zero; what they computed before stays as after a failure
 * (sweep: the entries before the stop are valid; critical: the changes found before it), and
 * the working parameters are restored.  No effect on a NULL handle. */
AUTOBAL_API void autobal_rotor_stab_set_cancel(autobal_rotor_stab *s, autobal_rotor_stab_cancel_fn fn,
                                               void *user);

/* Change one parameter of the handle's working copy (see autobal_rotor_stab_param);
 * the base values given at alloc are kept for the scale factors.  AUTOBAL_EINVAL for
 * an unknown id or a value out of range (message on the handle; the handle is
 * unchanged) or a NULL handle. */
AUTOBAL_API int autobal_rotor_stab_set(autobal_rotor_stab *s, int param, double value);
/* Current value (for BALL_MASS / BALL_DAMPING the value of ball 1, NaN without
 * balls; for UNBALANCE_MASS plane 1's m0).  NaN for an unknown id or a NULL
 * handle. */
AUTOBAL_API double autobal_rotor_stab_get(const autobal_rotor_stab *s, int param);
/* The working parameters (owned by the handle; ball arrays point into it; valid
 * until autobal_rotor_stab_free and changed by autobal_rotor_stab_set).  NULL for
 * a NULL handle. */
AUTOBAL_API const autobal_rotor_params *autobal_rotor_stab_params(const autobal_rotor_stab *s);
/* Total number of balls N (state dimension of the full model 8 + 2N); 0 for a
 * NULL handle. */
AUTOBAL_API size_t autobal_rotor_stab_n_balls(const autobal_rotor_stab *s);

/* Balanced angles of the analysed member at the current parameters, all planes in
 * state order (n must equal N; rad, wrapped to (-pi, pi]).  Returns
 * AUTOBAL_SUCCESS, or AUTOBAL_EINVAL: NULL handle (no message), n != N or psi
 * NULL with n > 0, or no balanced configuration / an unusable member in some
 * plane (autobal_rotor_member_angles; message "plane j: ..." on the handle).
 * After a failure psi is untouched and the handle stays usable. */
AUTOBAL_API int autobal_rotor_stab_balanced_angles(autobal_rotor_stab *s, double *psi, size_t n);
/* The closed system at the current parameters and member (computes the balanced
 * angles first).  Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL: s or c NULL (no
 * message), or no balanced configuration / an unusable member (message on the
 * handle, as for autobal_rotor_stab_balanced_angles).  After a failure *c is
 * untouched.  Works for anisotropic supports too (c->isotropic = 0 says so). */
AUTOBAL_API int autobal_rotor_stab_closed(autobal_rotor_stab *s, autobal_rotor_closed *c);

/* The analytic linearization of the full model at the balanced state, mixed frame
 * (rotor coordinates fixed, dpsi relative), at time t: a (row-major, dim x dim,
 * dim = 8 + 2N, state (x, y, alpha, beta, rates, dpsi_1..N, dpsi_1'..N')).  With
 * rotating = 1 the rotating-coordinate matrix J(t) + blockdiag(Omega, Omega, 0)
 * (constant for isotropic supports; the state's rotor part is then (Re W, Im W,
 * Re Theta, Im Theta) and rates at t = 0).  AUTOBAL_EINVAL, AUTOBAL_ENUMERIC. */
AUTOBAL_API int autobal_rotor_stab_linearization(autobal_rotor_stab *s, double t, int rotating,
                                                 double *a, size_t dim);

/* Margin and verdict at the current parameters with `method` (AUTO: the handle's
 * option).  *margin: 1/s (NaN when no balanced configuration exists: then
 * *verdict = AUTOBAL_ROTOR_VERDICT_NONE and AUTOBAL_SUCCESS is returned).
 * AUTOBAL_EUNSUPPORTED: the method does not apply (e.g. POLY with anisotropic
 * supports or two planes, CLOSED without closure, FULL anisotropic, omega == 0);
 * AUTOBAL_ENUMERIC, integration failures of FLOQUET (its status).  No allocation. */
AUTOBAL_API int autobal_rotor_stab_margin(autobal_rotor_stab *s, int method, double *margin,
                                          int *verdict);

/* Everything at one point.  Arrays of length n_full point into the handle (valid
 * until the next call on it). */
typedef struct autobal_rotor_stab_result {
  int method;          /* the method of the verdict (AUTO resolved) */
  int verdict;         /* AUTOBAL_VERDICT_* or AUTOBAL_ROTOR_VERDICT_NONE */
  double margin;       /* 1/s */
  int isotropic, closure_ok;
  size_t n_balls;      /* N */
  const double *psi;   /* N balanced angles (rad) */
  size_t n_family;     /* neutral roots excluded from the verdict (sum over planes) */
  /* closed system (isotropic, closure_ok): n_closed = 12 or 16, else 0 */
  size_t n_closed;
  double poly[AUTOBAL_ROTOR_POLY_LEN]; /* Delta, one plane only (n_poly = 13), else zeros */
  size_t n_poly;
  double root_re[AUTOBAL_ROTOR_CLOSED_MAX], root_im[AUTOBAL_ROTOR_CLOSED_MAX];
      /* roots of Delta (one plane) or eigenvalues of the closed matrix (two planes), 1/s */
  double closed_eig_re[AUTOBAL_ROTOR_CLOSED_MAX], closed_eig_im[AUTOBAL_ROTOR_CLOSED_MAX];
      /* eigenvalues of the closed matrix, ordered to match root_* */
  double root_eig_mismatch;  /* max |root - eigenvalue| / max(1, max |root|) (0 for two planes) */
  int hurwitz_verdict;       /* Routh-Hurwitz on Delta (one plane), else AUTOBAL_VERDICT_MARGINAL */
  int hurwitz_n_rhp;         /* sign changes of the Routh array (roots with Re > 0) */
  double closed_margin;      /* max real part of root_* (1/s) */
  /* full model (isotropic): eigenvalues of the rotating-coordinate linearization */
  size_t n_full;             /* 8 + 2N if computed, else 0 */
  const double *full_re, *full_im;
  double full_mismatch;      /* full eig vs closed roots + 0^(family) + (-kappa)^(n-2) (relative
                                to max(1, max |root|)); NaN if not comparable */
  double full_margin;        /* max real part excluding the family roots */
  /* Floquet (always computed when omega != 0 and N <= 12) */
  size_t n_floquet;
  const double *mu_re, *mu_im;
  double floquet_margin;     /* log(max |mu|) / T over the non-family multipliers */
  double floquet_mismatch;   /* isotropic: max |mu - exp(lambda T)| over matched pairs (full
                                roots), else NaN */
  double period;             /* T = 2 pi / |omega| (s) */
} autobal_rotor_stab_result;

/* Compute every applicable method at the current parameters: POLY (+ Hurwitz) and
 * CLOSED when the closure applies, FULL when isotropic, FLOQUET always (N <= 12).
 * The verdict/margin come from the handle's method (AUTO: POLY > CLOSED > FULL >
 * FLOQUET).  AUTOBAL_EINVAL: omega == 0 or no balanced configuration (message
 * says which); AUTOBAL_ENUMERIC / integration statuses. */
AUTOBAL_API int autobal_rotor_stab_analyze(autobal_rotor_stab *s, autobal_rotor_stab_result *res);

/* Floquet multipliers alone: mu_re/mu_im (n = 8 + 2N entries, sorted by decreasing
 * modulus); monodromy (may be NULL; n*n, row-major, unscaled mixed-frame state).
 * AUTOBAL_EINVAL (omega == 0, wrong n, no balanced configuration), integration
 * statuses (AUTOBAL_ESTEP, AUTOBAL_EMAXSTEPS, ...). */
AUTOBAL_API int autobal_rotor_stab_floquet(autobal_rotor_stab *s, double *mu_re, double *mu_im,
                                           size_t n, double *monodromy);

/* ---- sweeps, critical speeds and maps ----------------------------------------- */

/* margin[k], verdict[k] at param = values[k] (k < n), with the handle's method.
 * Points without a balanced configuration get AUTOBAL_ROTOR_VERDICT_NONE and NaN.
 * Returns AUTOBAL_SUCCESS; AUTOBAL_EINVAL for a NULL handle (no message), a NULL
 * array, an unknown id, or a value out of the parameter's range (message of
 * autobal_rotor_stab_set); or the status of a failing margin evaluation
 * (autobal_rotor_stab_margin).  A failure at a point stops the sweep: the entries
 * before it are valid, the others unspecified.
 * Afterwards (also after a failure) the working parameters are exactly (bitwise)
 * those before the call: everything the parameter touches is saved first and put
 * back -- every ball's own mass and damping (BALL_MASS / BALL_DAMPING set all balls
 * to one value during the sweep), every plane's own m0 (UNBALANCE_MASS), omega, the
 * scale factors and the lumped set with the input kind (STIFFNESS_SCALE /
 * DAMPING_SCALE), i.e. all of autobal_rotor_stab_params() and
 * autobal_rotor_stab_get().  An analysis after the sweep therefore gives the same
 * results as one before it.  The results of the last autobal_rotor_stab_analyze
 * (arrays pointing into the handle) are overwritten.  No allocation (the saved
 * ball data live in the handle). */
AUTOBAL_API int autobal_rotor_stab_sweep(autobal_rotor_stab *s, int param, const double *values,
                                         size_t n, double *margin, int *verdict);

typedef struct autobal_rotor_crit {
  int param;                  /* the swept parameter */
  size_t n;                   /* number of verdict changes found */
  double value[AUTOBAL_ROTOR_MAX_CRIT];  /* where the margin crosses 0 (refined) */
  int kind[AUTOBAL_ROTOR_MAX_CRIT];      /* +1: stable above, -1: unstable above, 0: to/from NONE */
  size_t n_stable;            /* stable intervals within [lo, hi] */
  double stable_lo[AUTOBAL_ROTOR_MAX_CRIT], stable_hi[AUTOBAL_ROTOR_MAX_CRIT];
  int truncated;              /* 1 if there were more than AUTOBAL_ROTOR_MAX_CRIT changes:
                                 the results cover [lo, value[n-1]] only (see below), else 0 */
  size_t evaluations;         /* margin evaluations used */
} autobal_rotor_crit;

/* Critical values of `param` in [lo, hi] (lo < hi; for OMEGA both of one sign and
 * non-zero): the margin is sampled on n_grid >= 2 equally spaced points, every
 * change of its sign (or to/from NONE) is bracketed and refined by Brent's method
 * (on the margin) to |bracket| <= xtol_rel |value| (e.g. 1e-8; changes to/from NONE
 * by bisection).  Stable intervals are the maximal sub-intervals of [lo, hi] where
 * the verdict is STABLE (their ends are critical values or lo/hi).  The working
 * parameters are saved and restored exactly as by autobal_rotor_stab_sweep (also
 * after a failure or a truncation; the last analysis is overwritten).
 * Changes between two grid points that cancel (a window narrower than the grid)
 * are not seen.
 * Capacity: at most AUTOBAL_ROTOR_MAX_CRIT critical values (the stable intervals,
 * at most n/2 + 1, always fit).  At the first change that does not fit the search
 * stops (that change is not refined), out->truncated = 1 and AUTOBAL_WARNING is
 * returned with a message naming the capacity and the range covered: then n =
 * AUTOBAL_ROTOR_MAX_CRIT, the results describe [lo, value[n-1]] only, and a stable
 * interval that begins at value[n-1] (kind +1) is NOT listed -- nothing is claimed
 * beyond the last recorded change (every listed interval is complete; stable_hi
 * <= value[n-1]).  Narrow [lo, hi] (or split it) to get the rest.
 * Returns AUTOBAL_SUCCESS (out->truncated = 0), AUTOBAL_WARNING (truncated, see
 * above; the data are valid), or:
 *   AUTOBAL_EINVAL: NULL handle (no message, *out untouched); out NULL; unknown
 *     id; lo, hi not finite or lo >= hi; an OMEGA range containing 0; n_grid
 *     outside [2, 1e8]; xtol_rel outside (0, 0.1); a grid value out of the
 *     parameter's range (autobal_rotor_stab_set);
 *   the status of a failing margin evaluation at a grid point or during a
 *   refinement (AUTOBAL_ENUMERIC, AUTOBAL_EUNSUPPORTED, the FLOQUET integration
 *   statuses, ...), except that AUTOBAL_ENUMERIC and AUTOBAL_EINVAL from Brent's
 *   method (no convergence, a lost bracket, a point without a balanced
 *   configuration) are not failures: its best estimate (or the bracket's
 *   midpoint) is kept.
 * *out is zeroed first (out->param set) whenever out is not NULL and s is valid;
 * after a failure during the scan it holds the changes found before it, the
 * stable intervals closed before it (an open one is dropped) and the number of
 * evaluations. */
AUTOBAL_API int autobal_rotor_stab_critical(autobal_rotor_stab *s, int param, double lo, double hi,
                                            size_t n_grid, double xtol_rel, autobal_rotor_crit *out);

/* Two-parameter map: margin[i * n2 + j] and verdict[i * n2 + j] at
 * (param1 = v1[i], param2 = v2[j]), with the options' method.  OpenMP-parallel over
 * the grid points when built with OpenMP (n_threads <= 0: the default number), one
 * handle per thread; the results do not depend on the number of threads.
 * AUTOBAL_EINVAL (bad arguments, param1 == param2), AUTOBAL_ENOMEM, or the first
 * failing point's status. */
AUTOBAL_API int autobal_rotor_stab_map(const autobal_rotor_params *p,
                                       const autobal_rotor_stab_options *opt, int param1,
                                       const double *v1, size_t n1, int param2, const double *v2,
                                       size_t n2, int n_threads, double *margin, int *verdict,
                                       autobal_error *err);

/* ---- every unbalance in a range (docs/rotor.md "Every unbalance") -------------- */

/* Largest number of critical unbalances reported at one speed. */
#define AUTOBAL_ROTOR_MAX_UCRIT 32

typedef struct autobal_rotor_unbalance_range {
  double omega;               /* rad/s, the speed analysed */
  double s_lo, s_hi;          /* kg m, the range of m0 r0 analysed */
  size_t n_crit;              /* critical unbalances strictly inside (s_lo, s_hi) */
  double s_crit[AUTOBAL_ROTOR_MAX_UCRIT]; /* kg m, ascending: a root of Delta on the imaginary axis */
  size_t n_sub;               /* sub-intervals of [s_lo, s_hi] between them (n_crit + 1) */
  double sub_lo[AUTOBAL_ROTOR_MAX_UCRIT + 1], sub_hi[AUTOBAL_ROTOR_MAX_UCRIT + 1]; /* kg m */
  int sub_verdict[AUTOBAL_ROTOR_MAX_UCRIT + 1]; /* AUTOBAL_VERDICT_* at the midpoint (constant inside) */
  double sub_margin[AUTOBAL_ROTOR_MAX_UCRIT + 1]; /* 1/s, the margin at the midpoint */
  int all_stable;             /* 1: stable for every m0 r0 in [s_lo, s_hi] (no critical value inside and
                                 stable in every sub-interval and at both ends), else 0 */
  double margin_worst;        /* 1/s, the largest margin (max Re lambda: the least stable) met at the
                                 points evaluated (ends, the midpoints and the points just inside each
                                 end of every sub-interval); not a bound over the range */
  size_t n_missed;            /* verdict changes inside a sub-interval that the crossing polynomial did
                                 not give (found by bisection, added to s_crit); 0 expected */
  size_t evaluations;         /* margin evaluations */
  /* added at the end: three or more identical balls (n_balls >= 3) */
  size_t n_balls;             /* balls in plane 1 */
  int member_rule;            /* autobal_rotor_unbalance_member analysed (n_balls >= 3) */
  double u_min, u_max;        /* kg^2, the range of u = |Q|^2 / 4 over the range's members (n_balls >= 3;
                                 NaN for two balls) */
  /* added at the end: three identical balls with member_rule EVERY (every member, every unbalance in
     the range).  The verdict depends on the member and the unbalance only through u, so the critical
     values and the sub-intervals are in u; the fields above then hold n_crit = 0 and one sub-interval
     [s_lo, s_hi] with the worst verdict of the u sub-intervals (sub_margin = margin_worst).  Zero
     (n_ucrit = n_usub = n_upiece = 0) otherwise. */
  size_t n_ucrit;             /* critical u strictly inside (u_min, u_max) */
  double u_crit[AUTOBAL_ROTOR_MAX_UCRIT]; /* kg^2, ascending: a root of Delta on the imaginary axis */
  size_t n_upiece;            /* pieces of the unbalances where a critical u is met */
  size_t upiece_crit[3 * AUTOBAL_ROTOR_MAX_UCRIT]; /* index into u_crit of the piece */
  double upiece_lo[3 * AUTOBAL_ROTOR_MAX_UCRIT], upiece_hi[3 * AUTOBAL_ROTOR_MAX_UCRIT]; /* kg m: some
                                 member of every m0 r0 in [lo, hi] has u = u_crit (at most 3 per value) */
  size_t n_usub;              /* sub-intervals of [u_min, u_max] between the critical u (n_ucrit + 1) */
  double usub_lo[AUTOBAL_ROTOR_MAX_UCRIT + 1], usub_hi[AUTOBAL_ROTOR_MAX_UCRIT + 1]; /* kg^2 */
  int usub_verdict[AUTOBAL_ROTOR_MAX_UCRIT + 1]; /* AUTOBAL_VERDICT_* at the midpoint (constant inside) */
  double usub_margin[AUTOBAL_ROTOR_MAX_UCRIT + 1]; /* 1/s, the margin at the midpoint */
  /* added at the end: four to ten identical balls with member_rule EVERY (docs/rotor.md "Four or
     more balls, every member").  u_min, u_max above are then an outer enclosure (every member has u
     in it, by a branch-and-bound); the members found have u_min_inner and u_max_inner (every u
     between is met).  A u sub-interval with no member found (between u_min and u_min_inner or
     u_max_inner and u_max, past a critical u there) has usub_verdict AUTOBAL_ROTOR_VERDICT_NONE and
     margin NaN; the verdict is then not "stable for all".  The fields n_upiece.. stay 0 (the
     unbalances of a critical u are not listed).  For three balls u_min_inner = u_min, u_max_inner =
     u_max, u_complete = 1; NaN and 0 otherwise. */
  double u_min_inner, u_max_inner; /* kg^2, u of the least and the largest members found */
  int u_complete;             /* 1: both searches closed to their tolerance (1e-9 n^2 in q = 4 u / m^2)
                                 within the budget; 0: the enclosure is valid but wider */
  long u_boxes;               /* boxes evaluated by the searches */
  size_t n_uundecided;        /* u sub-intervals with no member (verdict NONE) */
  /* added at the end: anisotropic supports (one plane, two balls; docs/rotor.md "Anisotropic supports:
     Hill's method").  No critical unbalances are computed: n_crit = 0 and one sub-interval [s_lo, s_hi]
     whose verdict is STABLE (no Floquet multiplier can reach the unit circle anywhere in the range,
     proven, and the Floquet verdict at the middle is stable), UNSTABLE (a member found unstable by
     Floquet: s_unstable), or AUTOBAL_ROTOR_VERDICT_NONE (boxes left open at the budget and no unstable
     member found there: undecided, never "stable"); sub_margin the Floquet margin at the middle,
     margin_worst the largest Floquet margin met, evaluations the Floquet runs, u_min, u_max the range
     of u = |Q|^2 / 4.  hill = 0 and the rest 0 otherwise. */
  int hill;                   /* 1: anisotropic supports, Hill's method */
  size_t hill_order;          /* N: harmonics e^{2 i k w t}, |k| <= N; 0: no N <= 40 bounds the truncation
                                 (low speeds), the range is then undecided unless a member is unstable */
  double hill_tail;           /* the bound of the truncated harmonics (weighted, scaled units) */
  long hill_boxes;            /* boxes (nu, theta) evaluated */
  size_t hill_open;           /* boxes not excluded when the budget ran out (0: proven) */
  double s_unstable;          /* kg m: an unbalance whose balanced motion Floquet finds unstable, NaN if none */
} autobal_rotor_unbalance_range;

/* Stability of the balanced motion for EVERY unbalance s = m0 r0 in [s_lo, s_hi] (kg m) at the
 * handle's current omega: one plane with two balls with a common h/m, or n >= 3 identical balls (same
 * m, r, h) with the member rule opt.unbalance_member: SYMMETRIC (the symmetric fan) for any n, EVERY
 * (every member of the family, n_ucrit.. filled: exact range of u for n = 3, a certified enclosure for n = 4..10; refused above), isotropic supports, the paper's inertia model (AUTOBAL_EUNSUPPORTED
 * otherwise, with a message; ANISOTROPIC supports with one plane of two balls (common h/m): Hill's method,
 * the fields hill.. filled (below the struct's last block): a guaranteed exclusion of Floquet multipliers on
 * the unit circle over boxes of (frequency, half angle between the balls), bounded truncation, plus Floquet
 * at the range's ends and middle; stable for all only when proven, "not stable" shown by an unstable member,
 * otherwise undecided (sub_verdict AUTOBAL_ROTOR_VERDICT_NONE); budget opt.hill_boxes; docs/rotor.md
 * "Anisotropic supports: Hill's method"; two planes of two balls: autobal_rotor_stab_every_unbalance2 with
 * [s_lo, s_hi] for both planes, 9 x 9 grid, every phase, only all_stable, margin_worst, n_missed,
 * evaluations and one sub-interval filled).  Method (guaranteed, not
 * sampled): Delta(lambda; s) = A(lambda) - (|Q(s)|^2 / 4) B(lambda) with A, B independent of s, so
 * a root crosses the imaginary axis only at the critical unbalances where A(i y) = u B(i y) for a real
 * u = |Q|^2 / 4 and real y (the real roots of a polynomial of degree <= 11 in y^2, and y = 0), mapped
 * back to s through the balanced angles; one verdict (method POLY) per sub-interval between them, checked
 * at both ends too (a disagreement is bisected and counted in n_missed).  s_lo > |m1 r1 - m2 r2|,
 * s_hi < m1 r1 + m2 r2 (the balls must balance every s off a line through the axis), r0 > 0 (s is varied through m0).  The working
 * m0 is restored (bitwise) afterwards.  Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL (range, NULL),
 * AUTOBAL_EUNSUPPORTED, AUTOBAL_ECANCELLED (the handle's hook), AUTOBAL_ENUMERIC, AUTOBAL_ENOMEM. */
AUTOBAL_API int autobal_rotor_stab_every_unbalance(autobal_rotor_stab *s, double s_lo, double s_hi,
                                                   autobal_rotor_unbalance_range *out);

/* The speeds in [w_lo, w_hi] (rad/s, one sign) where the balanced motion is stable for every
 * unbalance in [s_lo, s_hi]: autobal_rotor_stab_every_unbalance on n_grid equally spaced speeds, every
 * change of its all_stable verdict refined by bisection to xtol_rel (relative).  out: value[] the
 * changes, kind[] +1 (stable for all above) / -1, stable_lo/hi the intervals, evaluations the margin
 * evaluations.  A window narrower than the grid spacing can be missed (in speed; never in unbalance).
 * omega and m0 are restored.  Statuses as above, AUTOBAL_WARNING when more than
 * AUTOBAL_ROTOR_MAX_CRIT changes (truncated = 1). */
AUTOBAL_API int autobal_rotor_stab_every_unbalance_speeds(autobal_rotor_stab *s, double s_lo, double s_hi,
                                                          double w_lo, double w_hi, size_t n_grid,
                                                          double xtol_rel, autobal_rotor_crit *out);

/* One plane with two balls (common h/m, the paper's inertia model), a margin: is every Floquet exponent
 * of the balanced motion left of -delta (Re lambda < -delta, delta >= 0, 1/s) for every m0 r0 in
 * [s_lo, s_hi] at the handle's speed?  Hill's method of autobal_rotor_stab_every_unbalance (anisotropic
 * supports; isotropic ones are accepted too, where autobal_rotor_stab_margin_ratio_set is exact and faster)
 * on the line Re lambda = -delta instead of the imaginary axis (docs/rotor.md "Anisotropic supports: Hill's
 * method", "Margin"), plus Floquet at the range's ends and middle.  *verdict 1: proven (out->all_stable
 * 1); 0: a member whose Floquet margin is >= -delta was found (out->s_unstable; sub_verdict[0] UNSTABLE,
 * which here means "not stable with the margin"); -1: undecided (boxes left open at the budget
 * opt.hill_boxes, or no bounded truncation).  The rest of out as autobal_rotor_stab_every_unbalance
 * (the hill fields).  delta = 0 gives that call's anisotropic verdict.  m0 restored (bitwise).  Statuses
 * as autobal_rotor_stab_every_unbalance; AUTOBAL_EINVAL also for delta < 0 or not finite,
 * AUTOBAL_EUNSUPPORTED for other than one plane of two balls. */
AUTOBAL_API int autobal_rotor_stab_every_unbalance_margin(autobal_rotor_stab *s, double s_lo, double s_hi,
                                                          double delta, int *verdict,
                                                          autobal_rotor_unbalance_range *out);

/* ---- every unbalance and every phase, two planes of two balls (rotor_unbalance2.c) ----- */

#define AUTOBAL_ROTOR_MAX_PCRIT 64

/* The relative phase phi = plane2.psi0 - plane1.psi0 (rad) at fixed unbalances s1, s2 (kg m) of two
 * planes: every phase at which a root of the closed system is on the imaginary axis, and the verdict
 * between them.  The verdict has period pi in phi (turning one unbalance by pi turns its balls by pi
 * and leaves Q_j = sum m e^{2 i psi} unchanged), so phases are reported in [0, pi). */
typedef struct autobal_rotor_phase_range {
  double omega;               /* rad/s */
  double s[2];                /* kg m, m0 r0 of plane 1 and 2 */
  size_t n_crit;              /* critical phases in [0, pi) */
  double phase_crit[AUTOBAL_ROTOR_MAX_PCRIT]; /* rad, ascending */
  double y_crit[AUTOBAL_ROTOR_MAX_PCRIT];     /* 1/s, the root i y on the axis (rotating frame, y >= 0; NaN
                                                 for a phase found by bisection, see n_missed) */
  size_t n_sub;               /* arcs of [0, pi) between them (cyclic: the last wraps to the first + pi) */
  double sub_lo[AUTOBAL_ROTOR_MAX_PCRIT + 1], sub_hi[AUTOBAL_ROTOR_MAX_PCRIT + 1]; /* rad */
  int sub_verdict[AUTOBAL_ROTOR_MAX_PCRIT + 1]; /* AUTOBAL_VERDICT_* at the arc's midpoint */
  double sub_margin[AUTOBAL_ROTOR_MAX_PCRIT + 1]; /* 1/s */
  int all_stable;             /* 1: stable for every phase (no critical phase, every check stable) */
  double margin_worst;        /* 1/s, the largest margin met at the phases evaluated */
  double phase_worst;         /* rad, where it was met */
  size_t n_missed;            /* verdict changes the crossing polynomial did not give (bisected); 0 expected */
  size_t evaluations;         /* margin evaluations (closed 16x16 matrix) */
} autobal_rotor_phase_range;

/* Every relative phase at the unbalances s1, s2 (kg m) at the handle's omega: two planes, two balls
 * per plane with a common h/m per plane, isotropic supports, the paper's inertia model.  Method: the
 * closed characteristic polynomial is Delta = E + p Y + conj(p) Y*, p = e^{i arg(Q1 conj(Q2))}, with
 * E, Y built exactly by polynomial arithmetic (docs/rotor.md "Every unbalance"); a root on the axis at
 * lambda = i y needs E(iy) + a U(iy) + b V(iy) = 0 (p = a + i b, U = Y + Y*, V = i (Y - Y*)), two real
 * linear equations whose solution has a^2 + b^2 = 1 only at the real roots of one polynomial R(y^2)
 * (and at y = 0 separately).  Every arc between critical phases is checked at its midpoint and near
 * both ends by the closed matrix (method CLOSED); disagreements are bisected (n_missed) and the phase
 * found is added to phase_crit (its y_crit NaN).  The working
 * m0 and psi0 are restored bitwise.  Statuses as autobal_rotor_stab_every_unbalance. */
AUTOBAL_API int autobal_rotor_stab_every_phase(autobal_rotor_stab *s, double s1, double s2,
                                               autobal_rotor_phase_range *out);

/* Every phase and every unbalance s1 in [s_lo[0], s_hi[0]], s2 in [s_lo[1], s_hi[1]] (kg m) of two
 * planes, on n_grid values of s2 (one if its range is a single value): at each, EXACT over every s1 in
 * the range and every phase (with y = |Q2|^2 fixed, a root on the axis at lambda = i w has (|Q1|^2,
 * |Q1||Q2| cos) rational in w: the region's boundary crossings are polynomial roots, docs/rotor.md
 * "Every unbalance"), plus autobal_rotor_stab_every_phase at n_grid values of s1 (the margins and a
 * cross-check).  Over s2's whole range (not only its grid values): a certified box search over
 * (w^2, |Q2|^2) of the same equations either proves that no (s1, s2, phase) of the ranges has a root
 * on the imaginary axis (then, with the grid's stable points, stable for all: exact_in_s2 = 1), or
 * finds such a point (found_s, found_phase: not stable for all), or runs out of its budget
 * (exact_in_s2 = 0: the s2 grid verdict stands, a window narrower than the grid can be missed). */
typedef struct autobal_rotor_unbalance_range2 {
  double omega;               /* rad/s */
  double s_lo[2], s_hi[2];    /* kg m, per plane */
  size_t n_s[2];              /* grid points per plane */
  size_t n_points;            /* n_s[0] n_s[1] */
  size_t n_not_stable;        /* grid points where some phase is not stable */
  size_t n_with_crit;         /* grid points with a critical phase */
  int all_stable;             /* 1: every grid point stable for every phase */
  double margin_worst;        /* 1/s, the largest margin met */
  double worst_s[2], worst_phase; /* kg m, rad: where */
  double first_bad_s[2];      /* kg m: the first grid point not stable (NaN if none; s1 NaN: a slice whose
                                 instability lies between the grid points of plane 1) */
  size_t n_missed, evaluations;
  int exact_in_s1;            /* 1: every slice was decided exactly over plane 1's whole range (the
                                 cos form of Delta16 held); 0: some slice fell back to plane 1's grid */
  size_t n_slices_not_stable; /* plane-2 grid values at which some s1 in the range and some phase is
                                 not stable (exact over s1 when exact_in_s1) */
  int exact_in_s2;            /* 1: also decided over plane 2's whole range, not only at its grid values
                                 (a certified box search over (frequency, |Q2|^2), docs/rotor.md "Every
                                 unbalance"); 0: undecided there (budget), the grid verdict stands */
  size_t boxes;               /* boxes the search examined */
  double found_s[2], found_phase; /* kg m, rad: a point (s1, s2, phase) with a root on the imaginary axis
                                 that the search found (NaN if none; found between the grid values when
                                 the grid is stable) */
} autobal_rotor_unbalance_range2;

AUTOBAL_API int autobal_rotor_stab_every_unbalance2(autobal_rotor_stab *s, const double s_lo[2],
                                                    const double s_hi[2], size_t n_grid,
                                                    autobal_rotor_unbalance_range2 *out);

/* Two planes, a margin: is every root of the balanced motion left of -delta (Re lambda < -delta,
 * delta >= 0) for every m0 r0 of both ranges and every relative phase at the handle's speed?  The
 * box search of autobal_rotor_stab_every_unbalance2 on the shifted Delta16(mu - delta) (each part
 * Taylor-shifted; docs/rotor.md "Every unbalance", "Margin shift, two planes"), then the closed matrix
 * at the 8 corners (both ranges' ends, phases 0 and pi/2).  *verdict 1: certified (no root on
 * Re lambda = -delta anywhere in the connected region, and the corners left of it); 0: a point with
 * a root at Re lambda >= -delta found (out->found_s, found_phase; NaN when it was lambda = -delta
 * itself); -1: undecided (the budget unbalance2_boxes, or the parts not of the cos form).  out gets
 * omega, all_stable (= *verdict == 1), boxes, evaluations, margin_worst (of the corners evaluated). */
AUTOBAL_API int autobal_rotor_stab_every_unbalance2_shift(autobal_rotor_stab *s, const double s_lo[2],
                                                          const double s_hi[2], double delta, int *verdict,
                                                          autobal_rotor_unbalance_range2 *out);

/* The speeds where autobal_rotor_stab_every_unbalance2 says stable, as
 * autobal_rotor_stab_every_unbalance_speeds (grid in speed, each change bisected to xtol_rel). */
AUTOBAL_API int autobal_rotor_stab_every_unbalance2_speeds(autobal_rotor_stab *s, const double s_lo[2],
                                                           const double s_hi[2], size_t n_grid, double w_lo,
                                                           double w_hi, size_t n_omega, double xtol_rel,
                                                           autobal_rotor_crit *out);

/* Per speed: was plane 2's whole range decided exactly (exact_in_s2 of
 * autobal_rotor_stab_every_unbalance2 at that speed)?  Filled by
 * autobal_rotor_stab_every_unbalance2_speeds_detail.  The per-grid arrays are the caller's (n_omega
 * entries each; any may be NULL); the rest is filled in place. */
typedef struct autobal_rotor_speeds2_detail {
  double *grid_omega;      /* [n_omega] rad/s, the grid speeds */
  int *grid_stable;        /* [n_omega] 1 stable for all, 0 not, -1 not evaluated (a truncated scan) */
  int *grid_exact;         /* [n_omega] 1 decided exactly over plane 2's range (stable: the box search
                              proved it; not stable: a grid point or an exact slice or a point found),
                              0 the plane-2 grid verdict (undecided, or the search off) */
  size_t *grid_boxes;      /* [n_omega] boxes the search examined there */
  int interval_exact[AUTOBAL_ROTOR_MAX_CRIT];        /* per stable interval of out: 1 every speed evaluated
                                                        in it (grid and bisection) was decided exactly */
  size_t interval_undecided[AUTOBAL_ROTOR_MAX_CRIT]; /* speeds evaluated in it that were not */
  int critical_exact[AUTOBAL_ROTOR_MAX_CRIT];        /* per critical speed of out: 1 both speeds of its
                                                        final bracket were decided exactly */
  size_t n_evaluated;      /* speeds evaluated (grid and bisection) */
  size_t n_undecided;      /* of them, not decided exactly over plane 2 */
  size_t boxes;            /* boxes examined in all */
} autobal_rotor_speeds2_detail;

/* autobal_rotor_stab_every_unbalance2_speeds, and per speed whether plane 2 was decided exactly
 * (detail NULL: the same as autobal_rotor_stab_every_unbalance2_speeds).  AUTOBAL_ENOMEM if the
 * record of the speeds cannot be kept. */
AUTOBAL_API int autobal_rotor_stab_every_unbalance2_speeds_detail(autobal_rotor_stab *s, const double s_lo[2],
                                                                  const double s_hi[2], size_t n_grid, double w_lo,
                                                                  double w_hi, size_t n_omega, double xtol_rel,
                                                                  autobal_rotor_crit *out,
                                                                  autobal_rotor_speeds2_detail *detail);

/* autobal_rotor_stab_map with, at every grid point, the verdict for EVERY unbalance m0 r0 in
 * [s_lo, s_hi] (autobal_rotor_stab_every_unbalance): STABLE (stable for all), UNSTABLE (unstable for
 * some), MARGINAL (a critical unbalance inside with stable sides: a touch), AUTOBAL_ROTOR_VERDICT_NONE
 * (the balls cannot balance every unbalance of the range at this point, e.g. a small ball mass);
 * margin: margin_worst (1/s).  unbalance_mass, plane1.m0 and plane1.unbalance cannot be axes.  Same threads, errors and
 * determinism as autobal_rotor_stab_map; AUTOBAL_EUNSUPPORTED where the every-unbalance analysis does
 * not apply (two planes, three or more balls unless identical with opt->unbalance_member = SYMMETRIC
 * or, for three to ten balls, EVERY, full inertia, anisotropic supports).  Four to ten balls with EVERY:
 * a u sub-interval left undecided (no member found in it) makes the point MARGINAL at best. */
AUTOBAL_API int autobal_rotor_stab_map_every_unbalance(const autobal_rotor_params *p,
                                                       const autobal_rotor_stab_options *opt, int param1,
                                                       const double *v1, size_t n1, int param2,
                                                       const double *v2, size_t n2, double s_lo, double s_hi,
                                                       int n_threads, double *margin, int *verdict,
                                                       autobal_error *err);

/* ---- every unbalance with a margin, two or more identical balls (the design search) ---- */

/* The normalized unbalances t = m0 r0 / (m r) in (0, n) of one plane with n identical balls (mass m,
 * radius r) for which every root of Delta (the balanced motion) has Re lambda < -delta. */
typedef struct autobal_rotor_ratio_set {
  double omega;          /* rad/s, the speed analysed (the handle's) */
  double delta;          /* 1/s, the margin demanded (any sign; 0: plain stability) */
  size_t n_crit;         /* critical t in (0, n): a root of Delta on Re lambda = -delta */
  double t_crit[AUTOBAL_ROTOR_MAX_UCRIT]; /* 1, ascending */
  size_t n;              /* open intervals of t where every root has Re lambda < -delta */
  double lo[AUTOBAL_ROTOR_MAX_UCRIT + 1], hi[AUTOBAL_ROTOR_MAX_UCRIT + 1]; /* 1, ascending, disjoint */
  size_t n_missed;       /* sub-intervals whose midpoint and ends disagreed (counted as not stable); 0 expected */
  size_t evaluations;    /* stability verdicts of single unbalances (Routh-Hurwitz on the shifted Delta) */
} autobal_rotor_ratio_set;

/* The set above at the handle's omega (docs/rotor.md "Design"): one plane with two identical balls
 * (same m, r, h), or n >= 3 identical balls with the handle's unbalance_member = SYMMETRIC (the
 * symmetric fan; t in (0, n); Delta's roots only: the n - 2 roots -h/m of the full system are
 * not in the set), isotropic supports, the paper's inertia; r0 > 0.  Guaranteed in t (not sampled):
 * the critical t are those where Delta(mu - delta; u) has a root on the imaginary axis or loses its
 * degree (u = |Q|^2 / 4 = m^2 (t^2 / 2 - 1)^2), one verdict per sub-interval between them.  The
 * verdict depends on the balls' radius only through t, so the set serves every track radius.  m0
 * is restored (bitwise).  Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL (NULL out, r0 <= 0, omega 0,
 * delta not finite), AUTOBAL_EUNSUPPORTED (message names what), AUTOBAL_ENUMERIC (root finder;
 * more than AUTOBAL_ROTOR_MAX_UCRIT critical values), AUTOBAL_ENOMEM, AUTOBAL_ECANCELLED (the
 * handle's hook).  *out is zeroed first. */
AUTOBAL_API int autobal_rotor_stab_margin_ratio_set(autobal_rotor_stab *s, double delta,
                                                    autobal_rotor_ratio_set *out);

/* Every u = |Q|^2 / 4 (kg^2) in [u_lo, u_hi] with margin delta (docs/rotor.md "Design", "Number of balls"):
 * Delta(lambda; u) = A(lambda) - u G(lambda) depends on the unbalance and on the member of the family only
 * through u (one plane, n >= 2 identical balls, a common h/m), so "every root Re lambda < -delta for every
 * member and every unbalance whose u lies in [u_lo, u_hi]" is decided in u alone: the critical u where
 * Delta(mu - delta; u) has a root on the imaginary axis or loses its degree (as in
 * autobal_rotor_stab_margin_ratio_set) cut the range; Routh-Hurwitz at both ends, at every critical u
 * inside and at the midpoint and just inside both ends of every sub-interval.  Delta's roots only (the
 * n - 2 roots -h/m of the full system are not in it).  With [u_lo, u_hi] an outer enclosure of the
 * members' u (autobal_rotor_stab_every_unbalance, unbalance_member EVERY: u_min, u_max) all_stable = 1
 * certifies every member.  Any member rule on the handle.  Added at the end (0.2.0). */
typedef struct autobal_rotor_margin_u_range {
  double omega, delta;     /* rad/s, 1/s */
  double u_lo, u_hi;       /* kg^2, the range decided */
  size_t n_crit;           /* critical u strictly inside */
  double u_crit[AUTOBAL_ROTOR_MAX_UCRIT]; /* kg^2, ascending */
  int all_stable;          /* 1: every u of the range passes the test; 0: u_found does not (or is within the
                              test's tolerance of the line Re lambda = -delta) */
  double u_found;          /* kg^2, the first u that failed (NaN when all_stable) */
  size_t evaluations;      /* Routh-Hurwitz tests */
} autobal_rotor_margin_u_range;

/* The test above at the handle's omega; m0 restored (bitwise).  Statuses as
 * autobal_rotor_stab_margin_ratio_set, AUTOBAL_EINVAL also for u_lo < 0 or u_lo > u_hi.  *out zeroed first. */
AUTOBAL_API int autobal_rotor_stab_margin_u_range(autobal_rotor_stab *s, double delta, double u_lo, double u_hi,
                                                  autobal_rotor_margin_u_range *out);

/* ---- the rotor-housing without balls: natural frequencies, Campbell diagram,
 *      unbalance response (the balls are removed; in the FULL inertia model the
 *      masses m0 + sum m_i stay attached at their planes) ------------------------- */

/* Number of modes: 4 (two translational-angular pairs in x-beta and y-alpha). */
#define AUTOBAL_ROTOR_N_MODES 4

/* Natural frequencies at omega (rad/s) of M q'' + (H + G(omega)) q' + K q = 0,
 * G the gyroscopic coupling C omega.  The 4 modes with the largest imaginary parts
 * (>= 0) of the 8 eigenvalues, sorted by increasing frequency:
 *   freq[k]  = Im lambda (rad/s, the damped natural frequency),
 *   zeta[k]  = -Re lambda / |lambda| (damping ratio, 1),
 *   growth[k] = Re lambda (1/s),
 *   whirl[k] = +1 forward (orbit in the sense of omega), -1 backward, 0 undecided
 *              (from the eigenvector: |v_x + i v_y|^2 M + |v_beta - i v_alpha|^2 A vs the
 *              same with -i; at omega = 0 the sense of +x -> +y counts as forward).
 * undamped = 1 drops H.  Any of the outputs may be NULL.  AUTOBAL_EINVAL,
 * AUTOBAL_ENUMERIC.  Allocates GSL workspaces per call. */
AUTOBAL_API int autobal_rotor_modes(const autobal_rotor_params *p, double omega, int undamped,
                                    double freq[4], double zeta[4], double growth[4], int whirl[4],
                                    autobal_error *err);

/* Campbell diagram: modes at omega[k] (k < n); freq, zeta, whirl are n x 4 row-major
 * (any may be NULL).  Modes sorted by frequency at every speed.  Returns
 * AUTOBAL_SUCCESS (also for n = 0: nothing written), or AUTOBAL_EINVAL (omega
 * NULL with n > 0, a non-finite omega[k], invalid parameters: nothing written),
 * AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC (singular mass matrix or GSL eigensolver
 * failure at some omega[k]: rows 0..k-1 are filled, the rest untouched); the
 * message in err.  Allocates GSL workspaces once per call. */
AUTOBAL_API int autobal_rotor_campbell(const autobal_rotor_params *p, const double *omega, size_t n,
                                       double *freq, double *zeta, int *whirl, autobal_error *err);

/* Steady unbalance response of the rotor-housing without balls at omega: the
 * unbalances m_j0 r_j0 at psi_j0 of every plane drive
 *   (K + i omega (H + G) - omega^2 M) Q = omega^2 sum_j m_j0 r_j0 e^{i psi_j0} (e_u,j - i e_v,j),
 * q(t) = Re(Q e^{i omega t}).  amp_G: major semi-axis of the orbit of the centre of
 * mass (m) = (|Q_x + i Q_y| + |Q_x - i Q_y|) / 2; amp_D[j] (may be NULL; n_planes
 * entries) the same at each balancer plane (x + d beta, y - d alpha).  AUTOBAL_EINVAL,
 * AUTOBAL_ENUMERIC (singular: an undamped resonance). */
AUTOBAL_API int autobal_rotor_unbalance_response(const autobal_rotor_params *p, double omega,
                                                 double *amp_G, double *amp_D, autobal_error *err);

/* Critical speeds of the rotor-housing in [lo, hi] (0 <= lo < hi, rad/s, n_grid >= 3):
 *  - crossings: where a natural frequency (Campbell) equals omega, freq_k(omega) =
 *    omega, refined by Brent to xtol_rel; whirl of that mode there in cross_whirl;
 *  - peaks: local maxima of amp_G(omega), refined by golden-section search to xtol_rel.
 * A Brent refinement that does not converge keeps its best estimate.
 * Capacity: up to AUTOBAL_ROTOR_MAX_CRIT of each (n_cross, n_peak).  At the first
 * crossing or peak that does not fit, the scan stops, out->truncated = 1 and
 * AUTOBAL_WARNING is returned with a message naming the capacity and the speed
 * omega_c up to which both lists are complete (two grid steps before the point
 * where the entry was dropped); the entries found before the stop are kept (some
 * may lie above omega_c).  Narrow the range (or split it) to get the rest.
 * Returns AUTOBAL_SUCCESS (truncated = 0), AUTOBAL_WARNING (truncated; the data
 * are valid), or AUTOBAL_EINVAL (out NULL; lo, hi not finite or not 0 <= lo < hi;
 * n_grid outside [3, 1e8]; xtol_rel outside (0, 0.1); invalid parameters, the
 * message of autobal_rotor_params_check), AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC
 * (singular mass matrix, GSL eigensolver failure); the message in err.  *out is
 * zeroed first whenever out is not NULL; after a failure during the scan it holds
 * the crossings and peaks found before it.  Allocates GSL workspaces per call. */
typedef struct autobal_rotor_resonances {
  size_t n_cross;
  double cross[AUTOBAL_ROTOR_MAX_CRIT];
  int cross_mode[AUTOBAL_ROTOR_MAX_CRIT]; /* mode index 0..3 (by frequency) */
  int cross_whirl[AUTOBAL_ROTOR_MAX_CRIT];
  size_t n_peak;
  double peak[AUTOBAL_ROTOR_MAX_CRIT];
  double peak_amp[AUTOBAL_ROTOR_MAX_CRIT]; /* amp_G at the peak, m */
  int truncated; /* 1 if a crossing or peak was dropped (capacity reached; the lists are
                    complete only up to the speed named in the message), else 0 */
} autobal_rotor_resonances;

AUTOBAL_API int autobal_rotor_resonance_speeds(const autobal_rotor_params *p, double lo, double hi,
                                               size_t n_grid, double xtol_rel,
                                               autobal_rotor_resonances *out, autobal_error *err);
/* The same, polling `cancel` (NULL: never) with `user` before every grid point (a refinement
 * between two grid points is bounded: at most 200 Brent or 300 golden-section steps): when it returns non-zero the search stops and returns
 * AUTOBAL_ECANCELLED ("cancelled by the caller" in err); *out then holds the crossings and
 * peaks found before the stop, as after a failure. */
AUTOBAL_API int autobal_rotor_resonance_speeds_cancellable(const autobal_rotor_params *p, double lo, double hi,
                                                           size_t n_grid, double xtol_rel,
                                                           autobal_rotor_stab_cancel_fn cancel, void *user,
                                                           autobal_rotor_resonances *out, autobal_error *err);

/* ---- the full model's own Jacobian (for cross-checks) ---------------------------- */

/* Central-difference Jacobian of autobal_rotor_rhs_rotating (rotor coordinates in
 * the fixed frame, ball angles relative) at (t, y): J[i*dim + j] = d f_i / d y_j,
 * step h_j = 1e-6 max(|y_j|, 1) (positions/angles) and the same for rates; work
 * must hold 3*dim doubles.  dim = autobal_rotor_dim(r) (axial included if on).
 * Returns AUTOBAL_SUCCESS, AUTOBAL_EINVAL, AUTOBAL_ERHS (message on the rotor). */
AUTOBAL_API int autobal_rotor_model_jacobian(autobal_rotor *r, double t, const double *y, double *J,
                                             size_t dim, double *work);

AUTOBAL_END_DECLS

#endif
