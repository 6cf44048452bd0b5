/* rotor_fan.h: the symmetric fan of n >= 3 identical balls (not installed), shared by the
 * every-unbalance analysis (rotor_unbalance.c) and the design's margin set (rotor_margin_set.c).
 * The fan psi_i = psi0 + pi + (i - (n-1)/2) delta, y = cos delta: t = m0 r0 / (m r) = U_{n-1}(x),
 * x = sqrt((1 + y) / 2), and u = |Q|^2 / 4 = m^2 U_{n-1}(y)^2 / 4 (docs/rotor.md, "Every unbalance";
 * tools/derive/derive_nballs.py).  Includes no other private header. */
#ifndef AUTOBAL_ROTOR_FAN_H
#define AUTOBAL_ROTOR_FAN_H

#include <stddef.h>

typedef struct autobal_rotor_fan_ {
  size_t n;     /* balls, >= 3 */
  double m;     /* kg, each ball */
  double y_min; /* cos(2 pi / n): t = 0 */
  double y1;    /* the root of U'_{n-1} in (y_min, y0): |U_{n-1}| has its local maximum */
  double y0;    /* cos(pi / n): U_{n-1} = 0, Q = 0 */
} autobal_rotor_fan_;

/* U_{n-1}(y) (Chebyshev, second kind) and, if dU, its derivative, by the recurrences
 * U_{k+1} = 2 y U_k - U_{k-1}, U'_{k+1} = 2 U_k + 2 y U'_k - U'_{k-1}. */
double autobal_rotor_fan_cheb_u_(size_t n, double y, double *dU);
/* n balls of mass m: y_min, y0, and y1 by bisection on the sign of U'_{n-1} (it changes sign once
 * on (y_min, y0): the roots of U_{n-1} and U'_{n-1} interlace). */
void autobal_rotor_fan_init_(autobal_rotor_fan_ *f, size_t n, double m);
/* t of the fan at y (increasing in y on [y_min, 1]). */
double autobal_rotor_fan_t_(const autobal_rotor_fan_ *f, double y);
/* u (kg^2) of the fan at y. */
double autobal_rotor_fan_u_(const autobal_rotor_fan_ *f, double y);
/* The y in [y_min, 1] with t(y) = t, by bisection to the last bit. */
double autobal_rotor_fan_y_of_t_(const autobal_rotor_fan_ *f, double t);
/* The y in [ylo, yhi] whose u equals uc: one per monotone piece of u(y) ([y_min, y1], [y1, y0],
 * [y0, 1] cut to [ylo, yhi]) that brackets it, by bisection; returns the count (<= 3) written to
 * out (none for a non-finite uc). */
size_t autobal_rotor_fan_y_of_u_(const autobal_rotor_fan_ *f, double uc, double ylo, double yhi, double out[3]);

#endif
