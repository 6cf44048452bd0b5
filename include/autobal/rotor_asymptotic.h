/* autobal/rotor_asymptotic.h: asymptotic stability conditions of the balanced motion of a rotor
 * with one ball autobalancer, the rotor's analogues of the pendulum's (7)-(9) (docs/rotor.md,
 * "Asymptotic conditions"; derived in tools/derive/derive_asymptotic.py).  They are reported beside
 * the exact verdict (autobal_rotor_stab_analyze), never instead of it.
 *
 * Setting: the closed one-plane system of autobal_rotor_char_poly (isotropic supports, two or more
 * balls with a common kappa = h_i / m_i, closure_ok), omega != 0.  With P = lambda + i omega and the
 * polynomials K11, K12, K22, D, N of Delta (autobal/rotor_stability.h), write
 *     G = N(0) / D(0)   (m/N)
 * for the compliance of the balancer centre to a force of the balls turning with the shaft (the
 * forward synchronous receptance of the rotor-housing at the balancer plane, balls removed),
 * a = m_b omega^4 / 2, q = |Q| / m_b in [0, 1).
 *
 * LIGHT BALLS (slow ball motion: the ball roots small against the rotor's roots, the distance of
 * the roots of D and N from lambda = 0, and |omega|).  Near lambda = 0, D(lambda), N(lambda), P^4
 * are frozen at lambda = 0 and Delta reduces to
 *     (u - a G)(u - a conj G) = (q a)^2 |G|^2,   u = lambda^2 + kappa lambda,
 * four ball roots.  They lie in the left half-plane iff (q < 1, kappa > 0)
 *     (L1) Re G < 0                                   (the balancer runs "supercritical")
 *     (L2) kappa^2 (-Re G) > a (Im^2 G - q^2 |G|^2)   (enough ball damping).
 * (L1) is the pendulum's (7), (L2) contains its (8) (high speed, q = 0) and its corrected (9)
 * (large support damping).  The rotor-housing's own roots (of D D*) move by O(m_b) and must stay
 * stable too: their first-order shifts are part of the prediction (light support damping).
 * Small parameter: the larger of eps_b = max_j c1 |u_j| / |2 lambda_j + kappa| over the ball roots,
 * c1 = sum of 1/|root| over the roots of D D* and N N* plus 4/|omega| (a bound of the logarithmic
 * derivative of a G P^4 near lambda = 0, which the approximation freezes), the relative error
 * bound of each ball root, and eps_r = the largest shift of a rotor root relative to its distance
 * from 0, -kappa and the other roots of D D*.  The prediction is "decided" when a predicted real
 * part is >= its error or all are <= -error (ball root j: eps_bj |lambda_j|; rotor root k:
 * eps_r |shift_k|).  Measured (docs/rotor.md): every decided prediction with small parameter
 * <= 0.2 agreed with the exact verdict.
 *
 * HIGH SPEED (|omega| -> infinity, paper inertia, A != C): Re G omega^2 -> -(1/M + d^2/(A - C))
 * and Im G omega^3 -> -(h/M^2 - 2 d h_c/(M (A - C)) + d^2 h_t/(A - C)^2), so (L1), (L2) become
 *     (H1) (A - C)(A - C + M d^2) > 0,
 *     (H2) kappa > kappa_inf = sqrt(m_b / (2 m_eff)) h_eff / m_eff,
 *          m_eff = 1 / (1/M + d^2/(A - C)),  h_eff = m_eff^2 (h/M^2 - 2 d h_c/(M (A - C)) + d^2 h_t/(A - C)^2),
 * the pendulum's (8) h > H sqrt(R_m) with the rotor's effective mass and damping at the balancer
 * plane.  (H2) is the condition at q = 0 (the balls at right angles, m0 r0 = sqrt(2) m r for two
 * identical balls), the most demanding unbalance: for q > 0 the bracket of (L2) turns negative as
 * omega grows.  Small parameter: max(sqrt(m_b / (2 m_eff)), omega_max / |omega|), omega_max the
 * highest natural frequency of the rotor-housing at rest, undamped.
 *
 * ANISOTROPIC SUPPORTS (one plane, paper inertia, kappa > 0; docs/rotor.md "Anisotropic supports").
 * There is no Delta (the linearization is periodic), but for light balls the same (L1), (L2) hold to
 * leading order with G replaced by the forward receptance of the fixed-frame rotor-housing,
 *     G+ = b^T Z(i omega)^-1 conj(b) / 2,   G- = b^T Z(-i omega)^-1 b / 2,   b = e_u + i e_v,
 * Z(s) = M s^2 + H s + K the 4x4 matrices of (3.2) without balls, e_u = (1, 0, 0, d), e_v = (0, 1, -d, 0):
 * a force F e^{i omega t} at the plane moves its centre by G+ F e^{i omega t} + G- conj(F) e^{-i omega t}.
 * The backward part turns at -2 omega in the rotating frame and averages out to first order (estimate
 * of its second-order effect on u: avg_small).  The rotor-housing's 8 fixed-frame roots s_k are shifted
 * like the isotropic roots of D with N / D' replaced by the residue of G+ at s_k (rotor_re/rotor_im: the
 * four with Im s_k >= 0, in rotating coordinates s_k - i omega); c1 sums 1/|s - i omega| over the roots
 * of det Z and of n n*, n = 2 det(Z) G+.  light_small also contains avg_small.  The high-speed entries use
 * G+ -> -(1/m_eff + i h_eff / (m_eff^2 omega)) / omega^2 with the mean of the x and y planes' damping terms
 * (G- = O(omega^-3)), high_small also contains avg_small; the undamped entry is not derived for
 * anisotropic supports (NaN / 0).  Not a proof: checked against the
 * Floquet multipliers of the full model on random machines (docs/rotor.md), where every decided
 * prediction agreed.
 *
 * Units SI.  Conditions are "applicable" when their small parameter is at most
 * AUTOBAL_ROTOR_ASYMPTOTIC_SMALL.
 */
#ifndef AUTOBAL_ROTOR_ASYMPTOTIC_H
#define AUTOBAL_ROTOR_ASYMPTOTIC_H

#include "autobal/export.h"
#include "autobal/rotor_stability.h"
#include "autobal/status.h"

AUTOBAL_BEGIN_DECLS

/* Applicability threshold of the small parameters (the pendulum's AUTOBAL_PENDULUM_ASYMPTOTIC_SMALL). */
#define AUTOBAL_ROTOR_ASYMPTOTIC_SMALL 0.05

typedef struct autobal_rotor_asymptotic {
  /* light balls: (L1), (L2) */
  double G_re, G_im;        /* m/N, G = N(0) / D(0) */
  double kappa;             /* 1/s, the balls' common h_i / m_i */
  double q;                 /* 1, |Q| / m_b */
  double kappa_min;         /* 1/s, the smallest kappa with (L2): sqrt(a (Im^2 G - q^2 |G|^2) / (-Re G)),
                               0 when the bracket is <= 0, NaN when Re G >= 0 */
  int supercritical;        /* (L1): Re G < 0 */
  double ball_re[4], ball_im[4]; /* 1/s, the four predicted ball roots */
  double rotor_re[4], rotor_im[4]; /* 1/s, the four roots of D (the rotor-housing's, rotating
                               coordinates) shifted to first order by the balls:
                               lambda_k + (m_b / 2) P^4 N / ((lambda^2 + kappa lambda) D') at lambda_k
                               (the other four of Delta are their conjugates) */
  double rotor_re_max;      /* 1/s, the largest of rotor_re */
  int light_stable;         /* (L1), (L2) and rotor_re_max < 0: predicts STABLE (all 12 roots) */
  double light_small;       /* max(eps_b, eps_r), see above (1) */
  int light_decided;        /* 1 when the prediction lies outside its error band (see above); 0: too
                               close to the boundary to say */
  int light_applicable;     /* light_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL */
  /* high speed: (H1), (H2); defined only for paper inertia and A != C (high_defined) */
  int high_defined;
  double m_eff;             /* kg */
  double h_eff;             /* kg/s (N s/m) */
  double kappa_inf;         /* 1/s */
  int high_stable;          /* (H1) and kappa > kappa_inf: predicts STABLE for every unbalance at high
                               speed (with (H1) false: UNSTABLE at high speed for light balls, any kappa) */
  double high_small;        /* max(sqrt(m_b / (2 m_eff)), omega_max / |omega|) */
  int high_applicable;      /* high_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL */
  /* undamped balls (kappa = 0, undamped_defined): the light-ball roots to the next order.  With
   * kappa = 0 the light-ball entries above are not a condition (light_stable, light_decided and
   * light_applicable are 0, light_small NaN; ball_re/ball_im keep the leading order, rotor_re/rotor_im
   * the rotor roots shifted with kappa = 0) and this entry replaces them:
   * u = a (Re G +- r0), r0 = sqrt(q^2 |G|^2 - Im^2 G); when both u are real and negative (on_axis)
   * the four ball roots are +-i y + delta_(+-) with g(lambda) = (m_b/2) P^4 N / D = g0 + g1 lambda + ...,
   *     delta_(+-) = Re g1 / 2 +- (q^2 Re(g1 conj g0) - Im g0 Im g1) / (2 r),  r = sqrt(q^2 |g0|^2 - Im^2 g0),
   * (O(m_b): the support damping acting on the ball modes through the rotor); otherwise the leading
   * order decides (a root with Re of order sqrt(m_b) > 0: UNSTABLE).  Error of delta: the Taylor
   * terms of g beyond g1 (g2 exactly, |g_n| <= |g0| c1^n for n >= 3) and the second order,
   *     e = s (|g2| y^2 + |g0| rho^3 / (1 - rho)) + 2 D1^2 / sep,  s = (|f_g| + |f_g*|) / (2 |f_u| y),
   *     D1 = s |g1| y,  rho = c1 y,  f = (u - g)(u - g*) - q^2 g g*,
   * sep = the distance of i y to the other three leading-order roots; small parameter max(rho, D1 / sep)
   * over the roots (leading order: c1 |u| / |2 lambda|) and eps_r. */
  int undamped_defined;     /* kappa == 0 */
  int undamped_on_axis;     /* both u real and negative: the next order decides */
  double undamped_delta[2]; /* 1/s, delta_+, delta_- (NaN when not on the axis) */
  double undamped_ball_re[4], undamped_ball_im[4]; /* 1/s, the predicted ball roots (next order on the axis) */
  int undamped_stable;      /* every predicted ball and rotor root has Re < 0: predicts STABLE */
  double undamped_small;    /* 1 */
  int undamped_decided;     /* outside its error band (as light_decided) */
  int undamped_applicable;  /* undamped_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL */
  /* anisotropic supports (see ANISOTROPIC above): G_re, G_im are then G+, these the backward part */
  int anisotropic;          /* 1: the supports are anisotropic, G = G+ */
  double G_minus_re, G_minus_im; /* m/N, G- (0 for isotropic supports) */
  double avg_small;         /* 1, a |G-|^2 / (4 omega^2 |G+|): the averaging estimate (0 for isotropic) */
} autobal_rotor_asymptotic;

/* The conditions above for the closed system c (autobal_rotor_stab_closed).  Returns
 * AUTOBAL_SUCCESS, AUTOBAL_EINVAL (NULL, n_planes != 1, no closure, omega == 0, anisotropic with full
 * inertia or kappa == 0,
 * kappa < 0: message in err; *out untouched; kappa = 0 gives the undamped entry), AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC (the roots of
 * D D* or N N*).  Allocates two small polynomial workspaces per call. */
AUTOBAL_API int autobal_rotor_asymptotic_conditions(const autobal_rotor_closed *c, autobal_rotor_asymptotic *out,
                                                    autobal_error *err);

/* TWO PLANES, light balls (docs/rotor.md "Asymptotic conditions", "Two planes"; derived in
 * tools/derive/derive_asymptotic2.py).  Both planes with the closure and a common kappa_j > 0 each.
 * Frozen at lambda = 0, the planes' balls couple through the 2x2 receptance
 *     G_jk = b_j^T K(i omega)^-1 b_k   (m/N),  b_j = (1, d_j)
 * (displacement of plane j's centre per force turning with the shaft at plane k; symmetric), and the
 * 8 ball roots are those of the real degree-8 polynomial det(U - S),
 *     U = diag(u1, u2, u1, u2), u_j = lambda^2 + kappa_j lambda,
 *     S = (omega^4 / 2) [Mb G, -Q conj(G); -conj(Q) G, Mb conj(G)],  Mb = diag(m_b1, m_b2), Q = diag(Q1, Q2).
 * For G12 = 0 it is the product of the two one-plane quartics, each decided by (L1), (L2).  The four
 * roots of D = det K shift to first order by sum_j (m_bj / 2) P^4 N_jj / ((lambda^2 + kappa_j lambda) D')
 * at lambda_k, N = B^T adj(K) B.  Small parameter: the larger of eps_b, the largest relative error bound
 * of a ball root (entrywise bound of S(lambda) - S(0) through the exact coefficients of N_jk and the
 * roots of D D*, carried to the root by the adjugate: sum |adj_ba| |dS_ab| / |p'|), and eps_r as for one
 * plane (separations also from -kappa_1, -kappa_2).  "Decided" as for one plane. */
typedef struct autobal_rotor_asymptotic2 {
  double G_re[4], G_im[4];       /* m/N, G_11, G_12, G_21, G_22 (G_21 = G_12) */
  double kappa[2];               /* 1/s */
  double q[2];                   /* 1, |Q_j| / m_bj */
  double ball_re[8], ball_im[8]; /* 1/s, the eight predicted ball roots */
  double rotor_re[4], rotor_im[4]; /* 1/s, the roots of D shifted to first order */
  double ball_re_max, rotor_re_max; /* 1/s */
  int light_stable;              /* every predicted real part < 0: predicts STABLE (all 16 roots) */
  double light_small;            /* max(eps_b, eps_r) */
  int light_decided;             /* outside its error band */
  int light_applicable;          /* light_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL */
  /* HIGH SPEED with both planes' balls at q_j = 0 (Q1 = Q2 = 0: two identical balls at right angles in
   * each plane), defined for paper inertia and A != C (high_defined); derived in
   * tools/derive/derive_asymptotic2_high.py.  G -> -(Gamma + i H / omega) / omega^2 with
   *     Gamma = B^T Mi B,  H = B^T Mi [[h, -h_c], [-h_c, h_t]] Mi B,  Mi = diag(1/M, 1/(A - C)).
   * At Q = 0 the sigma and conj(sigma) rows decouple; with Gt = Mb^1/2 Gamma Mb^1/2 = sum mu_k z_k z_k^T
   * (z_k unit) each mode k gives the ball roots +-i omega sqrt(mu_k / 2) with real parts
   *     -kbar_k / 2 +- eta_k / (2 sqrt(2 mu_k)),  kbar_k = z_k^T diag(kappa) z_k,  eta_k = z_k^T Mb^1/2 H Mb^1/2 z_k,
   * so (H1') Gamma positive definite and (H2') kbar_k > kappa_inf_k = |eta_k| / sqrt(2 mu_k), k = 1, 2.
   * With G12 = 0 (Gamma, H diagonal) this is the one-plane (H1), (H2) in each plane.  Only Q = 0: for
   * Q != 0 the leading-order ball roots are simple except on crossing curves, where the condition is
   * another one (docs/rotor.md "Two planes at high speed").  Small parameter: the largest of
   * |omega| sqrt(mu_max / 2) c_D (the ball roots against the rotor-housing's, c_D as for light balls),
   * omega_max / |omega| and (max kappa_j + max kappa_inf_k) / (|omega| |sqrt(mu_1 / 2) - sqrt(mu_2 / 2)|)
   * (the two modes apart); decided when every |real part| exceeds small (kbar_k + kappa_inf_k) / 2. */
  int high_defined;
  double high_Gamma[4];          /* 1/kg, Gamma_11, Gamma_12, Gamma_21, Gamma_22 */
  double high_H[4];              /* 1/(kg s) */
  double high_mu[2];             /* 1, eigenvalues of Mb^1/2 Gamma Mb^1/2, ascending */
  double high_kappa_mode[2];     /* 1/s, kbar_k (NaN when Gamma is not positive definite) */
  double high_kappa_inf[2];      /* 1/s */
  double high_re[2];             /* 1/s, the larger predicted real part of mode k's ball roots */
  int high_stable;               /* (H1') and (H2'): predicts STABLE at high speed for Q1 = Q2 = 0 */
  double high_small;             /* 1 */
  int high_decided;              /* outside its error band */
  int high_applicable;           /* high_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL */
  /* HIGH SPEED, EVERY UNBALANCE (every q1, q2 < 1 and phase; Gamma positive definite): the frozen ball system
   * (lambda^2 + K lambda) v = S v, S = -(omega^2 / 2) T (Gamma^ + i H^ / omega), T = [[Mb, -Q], [-conj Q, Mb]],
   * Gamma^ = diag(Gamma, Gamma), H^ = diag(H, -H), K = diag(kappa_1, kappa_2, kappa_1, kappa_2), which commutes
   * with T.  With P = T^-1: lambda^2 a + lambda d + (omega^2/2)(g + i eta/omega) = 0, a = v*Pv, d = v*PKv >=
   * min kappa_j a, g = v*Gamma^v, eta = v*H^v, |eta| <= rho g (rho the largest |nu| with det(H - nu Gamma) = 0),
   * g / a <= 2 mu_2 (T <= 2 diag(Mb, Mb)); a scalar lambda^2 + b lambda + c is stable iff b > 0 and
   * b^2 Re c > (Im c)^2.  Hence min(kappa_1, kappa_2) > high_every_kappa = rho sqrt(mu_2) makes every ball root
   * stable, for every unbalance (no perturbation argument: exact for the frozen high-speed system).
   * Sufficient, not necessary: at Q = 0 it is at least sqrt(2) max_k kappa_inf_k (equal when the planes
   * decouple).  Small parameter: max(|omega| sqrt(mu_2) c_D, omega_max / |omega|). */
  double high_every_kappa;       /* 1/s, rho sqrt(mu_2) (NaN when not high_defined or Gamma not positive definite) */
  int high_every_stable;         /* min(kappa_1, kappa_2) > high_every_kappa: predicts STABLE for every unbalance */
  double high_every_small;       /* 1 */
  int high_every_applicable;     /* high_every_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL */
} autobal_rotor_asymptotic2;

/* The two-plane light-ball condition above for the closed system c.  Returns AUTOBAL_SUCCESS,
 * AUTOBAL_EINVAL (NULL, n_planes != 2, not isotropic, no closure, omega == 0, kappa_j <= 0, D(0) = 0:
 * message in err; *out untouched), AUTOBAL_ENOMEM, AUTOBAL_ENUMERIC (polynomial roots). */
AUTOBAL_API int autobal_rotor_asymptotic2_conditions(const autobal_rotor_closed *c, autobal_rotor_asymptotic2 *out,
                                                     autobal_error *err);

AUTOBAL_END_DECLS

#endif
