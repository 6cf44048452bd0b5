/* rotor_gravity.c: the closed forms of gravity on the rotor model (docs/device.md section 2):
 * the static offset of the rotor under the weights and the ratio g sin(theta) / (r Omega^2) that
 * tells whether the balls lie at the bottom of their track or are carried round.  The weights in
 * the equations of motion are in rotor.c. */
#include <math.h>
#include <stddef.h>

#include "autobal/rotor.h"

int autobal_rotor_static_offset(const autobal_rotor_params *p, double q_s[4]) {
  autobal_rotor_lumped L;
  double gs, W, D = 0.0, det;
  size_t j, i;
  if (!p || !q_s) return AUTOBAL_EINVAL;
  q_s[0] = q_s[1] = q_s[2] = q_s[3] = 0.0;
  if (!p->gravity) return AUTOBAL_SUCCESS;
  if (p->input == AUTOBAL_ROTOR_HARDWARE) {
    if (autobal_rotor_lumped_from_hardware(&p->hw, &L, NULL) != AUTOBAL_SUCCESS) return AUTOBAL_EINVAL;
  } else {
    L = p->lumped;
  }
  if (p->n_planes > AUTOBAL_ROTOR_MAX_PLANES) return AUTOBAL_EINVAL;
  gs = p->g * sin(p->shaft_angle); /* the weight component in the plane of the motion, along -y */
  if (gs == 0.0) return AUTOBAL_SUCCESS; /* a vertical shaft: no weight in the plane */
  W = L.M;
  for (j = 0; j < p->n_planes; j++) { /* m_j = m_j0 + the balls' masses */
    double mj = p->plane[j].m0;
    for (i = 0; i < p->plane[j].n_balls && p->plane[j].ball_mass; i++) mj += p->plane[j].ball_mass[i];
    W += mj;
    D += p->plane[j].d * mj;
  }
  det = L.c_y * L.c_alpha - L.c_yalpha * L.c_yalpha;
  if (!(det > 0.0)) return AUTOBAL_EINVAL;
  q_s[1] = -gs * (W * L.c_alpha + L.c_yalpha * D) / det;
  q_s[2] = gs * (L.c_y * D + L.c_yalpha * W) / det;
  return AUTOBAL_SUCCESS;
}

double autobal_rotor_gravity_ratio(const autobal_rotor_params *p, size_t plane, double omega) {
  const autobal_rotor_plane *pl;
  double r = INFINITY;
  size_t i;
  if (!p || !p->gravity || plane >= p->n_planes || plane >= AUTOBAL_ROTOR_MAX_PLANES) return NAN;
  pl = &p->plane[plane];
  if (pl->n_balls == 0 || !pl->ball_radius) return NAN;
  if (p->g * sin(p->shaft_angle) == 0.0) return 0.0; /* a vertical shaft: no weight in the plane */
  for (i = 0; i < pl->n_balls; i++)
    if (pl->ball_radius[i] < r) r = pl->ball_radius[i];
  return p->g * sin(p->shaft_angle) / (r * omega * omega);
}
