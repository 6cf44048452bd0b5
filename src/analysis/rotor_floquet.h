/* rotor_floquet.h: internal functions of rotor_floquet.c used by rotor_stability.c (not
 * installed).  Includes rotor_stab_handle.h (the handle's layout) only. */
#ifndef AUTOBAL_ROTOR_FLOQUET_H
#define AUTOBAL_ROTOR_FLOQUET_H

#include "analysis/rotor_stab_handle.h"

/* Analytic mixed-frame linearization into s->Afull (see the header); psi of the member valid. */
int autobal_rotor_stab_lin_(autobal_rotor_stab *s, double t, int rotating);
/* The second-order matrices M(t), C(t), K(t) (nm x nm row-major, nm = 4 + N) of the same
 * linearization, M X'' + C X' + K X = 0, X = (x, y, alpha, beta, dpsi_1..N); psi valid. */
int autobal_rotor_stab_lin2_(autobal_rotor_stab *s, double t, double *M, double *C, double *K);
/* Floquet multipliers into s->mu_re/mu_im (sorted by decreasing modulus); monodromy
 * (may be NULL) unscaled. */
int autobal_rotor_stab_floquet_(autobal_rotor_stab *s, double *monodromy);
/* Margin from Floquet multipliers excluding `family` multipliers closest to 1. */
double autobal_rotor_stab_floquet_margin_(const autobal_rotor_stab *s, size_t family);

#endif
