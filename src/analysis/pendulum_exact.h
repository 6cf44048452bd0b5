/* pendulum_exact.h: the undamped two-pendulum balancer in exact integer arithmetic (GMP):
 * P(x) of (10) with R_m and k taken as the exact binary fractions they are, its discriminants
 * as integer polynomials in W = R_w^2, and the exact verdict at a dyadic W
 * (src/analysis/pendulum_exact.c; not installed).  Used by pendulum_critical.c and
 * pendulum_map.c. */
#ifndef AUTOBAL_PENDULUM_EXACT_H
#define AUTOBAL_PENDULUM_EXACT_H

#include "numerics/exact_poly.h"

/* R_m = r 2^-E, k = kappa 2^-F (integers r, kappa; E, F >= 0) and the coefficients of (10)
 * times L = 2^(F + 2E): C[j](W) = L c_j(W), integer polynomials in W of degree <= 4. */
typedef struct autobal_pendulum_exact {
  mpz_t r, kappa;
  long E, F;
  autobal_xpoly C[5];
  mpz_t v[5], t0, t1, t2; /* scratch of the verdict */
  autobal_dyadic W;
} autobal_pendulum_exact;

/* R_m in (0, 1/2), k in [0, 1] (checked by the caller). */
void autobal_pendulum_exact_init(autobal_pendulum_exact *x, double R_m, double k);
void autobal_pendulum_exact_clear(autobal_pendulum_exact *x);

/* The discriminant of P(x) in x (a quartic, also at k = 0, where it is a0^2 times the cubic's)
 * as an integer polynomial in W: L^6 disc_x P(W).  Degree <= 12. */
void autobal_pendulum_exact_disc(autobal_pendulum_exact *x, autobal_xpoly *D);
/* The exact verdict of the undamped system at W = R_w^2 (the dyadic in x->W, set by the
 * caller, or by the two wrappers): AUTOBAL_VERDICT_STABLE when every root x of (10) is real
 * and <= 0 with distinct roots, AUTOBAL_VERDICT_MARGINAL on the boundary (a deciding quantity
 * exactly 0: a double root, or x = 0 twice at W = 1 for k = 0), AUTOBAL_VERDICT_UNSTABLE
 * otherwise.  Criteria as autobal_pendulum_undamped_verdict, on exact integers. */
int autobal_pendulum_exact_verdict(autobal_pendulum_exact *x);
int autobal_pendulum_exact_verdict_W(autobal_pendulum_exact *x, long double W);
int autobal_pendulum_exact_verdict_Rw(autobal_pendulum_exact *x, double R_w); /* W = R_w^2 exactly */

#endif
