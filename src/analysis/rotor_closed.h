/* rotor_closed.h: internal functions of rotor_closed.c shared with the rest of the rotor
 * stability analysis (not installed).  Includes no other private header. */
#ifndef AUTOBAL_ROTOR_CLOSED_H
#define AUTOBAL_ROTOR_CLOSED_H

#include <gsl/gsl_matrix.h>
#include <gsl/gsl_permutation.h>

#include "autobal/rotor_stability.h"

/* |a - b| <= rtol max(|a|, |b|). */
int autobal_rotor_close_rel_(double a, double b, double rtol);
/* Is the lumped set isotropic (relative 1e-12)? */
int autobal_rotor_lumped_isotropic_(const autobal_rotor_lumped *L);
/* Rank (0..2) of dpsi -> dsigma = sum_i i a_i e^{i psi_i} dpsi_i of one plane's n balls
 * (masses m, radii r, balanced angles psi; Gram determinant test). */
size_t autobal_rotor_plane_rank_(const double *m, const double *r, const double *psi, size_t n);
/* autobal_rotor_closed_matrix with a caller's LU workspace lu/perm (nr x nr, nr = dim/2). */
int autobal_rotor_closed_matrix_ws_(const autobal_rotor_closed *c, double *a, size_t dim,
                                    gsl_matrix *lu, gsl_permutation *perm, autobal_error *err);
/* The parts of Delta = A - (|Q|^2 / 4) (lambda^2 + omega^2)^4 Bt (A = F F*, Bt = N N*, since
 * P^4 Pb^4 = (lambda^2 + omega^2)^4; ascending real coefficients, Bt padded with zeros to 13; see
 * docs/rotor.md) of a one-plane isotropic closed system; with the paper's inertia neither depends on
 * the unbalance.  AUTOBAL_EINVAL / AUTOBAL_ENUMERIC. */
int autobal_rotor_char_parts_(const autobal_rotor_closed *c, double A[13], double Bt[13], autobal_error *err);

#endif
