/* rotor_energy.h: the total energy E = T + V and the dissipation of the rotor model with a
 * MOTOR drive, written out from the formulas of docs/device.md ("Energies", PAPER inertia), for
 * the tests (test_rotor_derive.c: against the SymPy check values; test_rotor_drive.c: the power
 * balance along a transient).  Reads the parameters through the public getters; the state is
 * in the FIXED frame (absolute ball angles) with phi_0, Omega as its last two entries. */
#ifndef AUTOBAL_TEST_ROTOR_ENERGY_H
#define AUTOBAL_TEST_ROTOR_ENERGY_H

#include <math.h>

#include "autobal/rotor.h"

/* E = T + V (J):
 *   T = 1/2 M (x'^2 + y'^2) + 1/2 A (alpha'^2 + beta'^2) + 1/2 J Omega^2 + C Omega alpha' beta
 *     + sum_j sum_{i >= 0} [1/2 m r^2 phi'^2 + m r phi' (-u_jD' sin phi + v_jD' cos phi)]
 * (i = 0: the unbalance at phi_0 + psi_j0 with phi' = Omega), V: the four supports. */
static double motor_energy(const autobal_rotor *r, const double *y) {
  const autobal_rotor_params *p = autobal_rotor_get_params(r);
  const autobal_rotor_lumped *L = autobal_rotor_get_lumped(r);
  const size_t N = autobal_rotor_n_balls_total(r), dim = autobal_rotor_dim(r);
  const double x = y[0], yy = y[1], al = y[2], be = y[3], xd = y[4], yd = y[5], ad = y[6], bd = y[7];
  const double ph0 = y[dim - 2], W = y[dim - 1];
  const autobal_rotor_hardware *h = &p->hw;
  double T, V, xl, yl, xr, yr;
  size_t j, i;
  T = 0.5 * L->M * (xd * xd + yd * yd) + 0.5 * L->A * (ad * ad + bd * bd) + 0.5 * p->drive.J * W * W +
      L->C * W * ad * be;
  for (j = 0; j < p->n_planes; j++) {
    const autobal_rotor_plane *P = &p->plane[j];
    const double uDd = xd + P->d * bd, vDd = yd - P->d * ad, th = ph0 + P->psi0;
    T += 0.5 * P->m0 * P->r0 * P->r0 * W * W + P->m0 * P->r0 * W * (-uDd * sin(th) + vDd * cos(th));
    for (i = 0; i < P->n_balls; i++) {
      const size_t k = autobal_rotor_ball_index(r, j, i);
      const double m = P->ball_mass[i], rr = P->ball_radius[i], ph = y[8 + k], phd = y[8 + N + k];
      T += 0.5 * m * rr * rr * phd * phd + m * rr * phd * (-uDd * sin(ph) + vDd * cos(ph));
    }
  }
  xl = x - h->l_L * be, yl = yy + h->l_L * al, xr = x + h->l_R * be, yr = yy - h->l_R * al;
  V = 0.5 * (h->c_Lx * xl * xl + h->c_Ly * yl * yl + h->c_Rx * xr * xr + h->c_Ry * yr * yr);
  return T + V;
}

/* All dissipation (W): 2R of the supports and the balls' resistance plus k_r Omega^2. */
static double motor_dissipation(const autobal_rotor *r, const double *y) {
  const autobal_rotor_params *p = autobal_rotor_get_params(r);
  const autobal_rotor_hardware *h = &p->hw;
  const size_t N = autobal_rotor_n_balls_total(r), dim = autobal_rotor_dim(r);
  const double xd = y[4], yd = y[5], ad = y[6], bd = y[7], W = y[dim - 1];
  const double xl = xd - h->l_L * bd, yl = yd + h->l_L * ad, xr = xd + h->l_R * bd, yr = yd - h->l_R * ad;
  double D = h->h_Lx * xl * xl + h->h_Ly * yl * yl + h->h_Rx * xr * xr + h->h_Ry * yr * yr + p->drive.k_r * W * W;
  size_t j, i;
  for (j = 0; j < p->n_planes; j++)
    for (i = 0; i < p->plane[j].n_balls; i++) {
      const size_t k = autobal_rotor_ball_index(r, j, i);
      const double rr = p->plane[j].ball_radius[i], u = y[8 + N + k] - W;
      D += p->plane[j].ball_damping[i] * rr * rr * u * u;
    }
  return D;
}

#endif
