/* rotor_box2.h: the two-plane every-unbalance question over BOTH planes' unbalances at once, by a
 * certified box search in (frequency, plane-2 unbalance) (src/analysis/rotor_box2.c; docs/rotor.md
 * "Every unbalance", "Two planes").  Private to src/analysis; includes nothing of the project. */
#ifndef AUTOBAL_ROTOR_BOX2_H
#define AUTOBAL_ROTOR_BOX2_H

#include <stddef.h>

/* Delta16(lambda) = D0 + F (x M11 + y M22 + t U0) + F^2 x y T12 (real polynomials in lambda,
 * ascending, 17 coefficients, zero above their degree), F = (lambda^2 + w2)^4, x = |Q1|^2,
 * y = |Q2|^2, t = |Q1||Q2| cos(phase).  (The factor F is common to every part but D0; kept apart, it
 * does not make the polynomials of the search vanish together at lambda = i sqrt(w2).) */
typedef struct autobal_rotor_box2_in {
  long double D0[17], M11[17], M22[17], T12[17], U0[17];
  long double x_lo, x_hi; /* the range of x (plane 1's unbalances) */
  long double y_lo, y_hi; /* the range of y (plane 2's), 0 < y_hi */
  long double w2;         /* omega^2 > 0: in F, and the frequency scale z = w2 zeta */
  size_t max_boxes;       /* the budget of boxes (each side); 0: a default (200000) */
  int full;               /* 1: the parts already carry F (M11, M22, U0 times F, T12 times F^2: Delta16 =
                             D0 + x M11 + y M22 + t U0 + x y T12), F is taken as 1; this is how a shifted
                             Delta16(mu - delta) (no longer of the form above in F) is given */
} autobal_rotor_box2_in;

typedef struct autobal_rotor_box2_out {
  int verdict;     /* 0: Delta16 has no root on the imaginary axis for any (x, y, phase) of the region
                      (proved for the polynomials as given); 1: it has one (a point found, below);
                      -1: undecided (the budget or the resolution ran out) */
  int at_zero;     /* verdict 1 by the root lambda = 0 (z, x, t below not set) */
  long double z, x, y, t; /* verdict 1, at_zero 0: a root lambda = i sqrt(z) at (x, y, t) inside */
  size_t boxes;    /* boxes examined (both searches) */
} autobal_rotor_box2_out;

/* Decide whether Delta16(i w) = 0 for some w >= 0 and (x, y, t) with x in [x_lo, x_hi], y in
 * [y_lo, y_hi], t^2 <= x y.  Returns 0 (out filled), or -1 for bad input. */
int autobal_rotor_box2_(const autobal_rotor_box2_in *in, autobal_rotor_box2_out *out);

#endif
