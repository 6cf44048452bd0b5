/* rotor_unbalance_aniso.h: the every-unbalance analysis with anisotropic supports (one plane, two balls,
 * Hill's method with a guaranteed exclusion; rotor_unbalance_aniso.c).  Not installed. */
#ifndef AUTOBAL_ROTOR_UNBALANCE_ANISO_H
#define AUTOBAL_ROTOR_UNBALANCE_ANISO_H

#include "analysis/rotor_stab_handle.h"

/* out zeroed and s_lo, s_hi, omega, n_balls set by the caller; the domain checked (one plane, two balls
 * with a common h/m, the paper's inertia model, the range inside (|a1 - a2|, a1 + a2)).  m0 and the
 * member option are changed: the caller restores m0. */
int autobal_rotor_every_unbalance_aniso_(autobal_rotor_stab *s, double s_lo, double s_hi,
                                         autobal_rotor_unbalance_range *out);

/* The same with a margin delta >= 0 (1/s): the line Re lambda = -delta instead of the imaginary axis, and a
 * member "fails" when its Floquet margin is >= -delta (delta = 0: exactly the call above).  Any supports
 * (isotropic ones too: the harmonics +-2 then vanish).  all_stable 1: every Floquet exponent Re < -delta for
 * every unbalance of the range (proven); sub_verdict[0] UNSTABLE with s_unstable: a member that fails;
 * NONE: undecided. */
int autobal_rotor_every_unbalance_hill_(autobal_rotor_stab *s, double s_lo, double s_hi, double delta,
                                        autobal_rotor_unbalance_range *out);

/* For tests: the least singular value of the weighted, scaled Hill matrix W H_N(lambda) (lambda in 1/s,
 * rotating frame) at the configuration psi_1 = theta, psi_2 = -theta (any phase: a time shift); the
 * handle's balanced state must be valid (its psi is restored).  NaN on failure. */
double autobal_rotor_hill_sigma_min_(autobal_rotor_stab *s, double theta, size_t N, double lam_re, double lam_im);

#endif
