/* rotor_two_planes.h: the machine of data/rotor_two_planes.ini (also data/design_two_planes.ini's
 * machine) as library parameters, for the two-plane tests (test_rotor_unbalance2.c,
 * test_rotor_design2.c, test_rotor_design2_margin.c): the default rotor with plane 1 at
 * d = 0.10 m (m0 = 20 g at r0 = 0.1 m, phase 0, two balls of 50 g on 0.1 m, h = 0.5 kg/s) and
 * plane 2 at d = -0.12 m (m0 = 15 g at r0 = 0.09 m, phase 2 rad, two balls of 40 g on 0.09 m,
 * h = 0.5 kg/s), at spin speed w (rad/s). */
#ifndef AUTOBAL_TEST_ROTOR_TWO_PLANES_H
#define AUTOBAL_TEST_ROTOR_TWO_PLANES_H

#include "autobal/rotor.h"

static double tp_m1[2] = {0.05, 0.05}, tp_r1[2] = {0.1, 0.1}, tp_h1[2] = {0.5, 0.5};
static double tp_m2[2] = {0.04, 0.04}, tp_r2[2] = {0.09, 0.09}, tp_h2[2] = {0.5, 0.5};

static autobal_rotor_params rotor_two_planes(double w) {
  autobal_rotor_params p = autobal_rotor_params_default();
  p.plane[0].d = 0.10;
  p.plane[0].m0 = 0.02;
  p.plane[0].r0 = 0.1;
  p.plane[0].psi0 = 0.0;
  p.plane[0].ball_mass = tp_m1;
  p.plane[0].ball_radius = tp_r1;
  p.plane[0].ball_damping = tp_h1;
  p.plane[0].ball_psi = NULL;
  p.plane[0].ball_rate = NULL;
  p.n_planes = 2;
  p.plane[1] = p.plane[0];
  p.plane[1].d = -0.12;
  p.plane[1].m0 = 0.015;
  p.plane[1].r0 = 0.09;
  p.plane[1].psi0 = 2.0;
  p.plane[1].ball_mass = tp_m2;
  p.plane[1].ball_radius = tp_r2;
  p.plane[1].ball_damping = tp_h2;
  p.omega = w;
  return p;
}

#endif
