/* rotor_nballs.h: the default machine of autobal_rotor_params_default() with n identical balls in
 * plane 1 (mass mv, track radius rv, damping hv; start angles 2 i rad, at rest), for the tests of
 * three or more balls (test_rotor_design_nballs.c, test_rotor_design_every.c).  The ball arrays
 * m, r, h, psi, rate (n entries each) belong to the caller and must outlive the parameters. */
#ifndef AUTOBAL_TEST_ROTOR_NBALLS_H
#define AUTOBAL_TEST_ROTOR_NBALLS_H

#include <stddef.h>

#include "autobal/rotor.h"

static autobal_rotor_params machine(size_t n, double *m, double *r, double *h, double *psi, double *rate, double mv,
                                    double rv, double hv) {
  autobal_rotor_params p = autobal_rotor_params_default();
  size_t i;
  for (i = 0; i < n; i++) {
    m[i] = mv;
    r[i] = rv;
    h[i] = hv;
    psi[i] = 2.0 * (double)i;
    rate[i] = 0.0;
  }
  p.plane[0].n_balls = n;
  p.plane[0].ball_mass = m;
  p.plane[0].ball_radius = r;
  p.plane[0].ball_damping = h;
  p.plane[0].ball_psi = psi;
  p.plane[0].ball_rate = rate;
  return p;
}

#endif
