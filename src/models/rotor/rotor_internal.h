/* rotor_internal.h: private to the library and its tests (not installed).
 *
 * The gravity inputs of the friction terms (docs/device.md sections 2-3).  With
 * autobal_rotor_params.gravity on, alloc sets gu = 0, gv = g sin(shaft_angle); the friction
 * right-hand sides (autobal_rotor_friction) are written for any in-plane gravity field (-gu, -gv) (m/s^2, fixed axes; the
 * shaft at theta to the vertical gives gu = 0, gv = g sin theta), which enters as an
 * acceleration (gu, gv) of D in every ball equation, the normal and the holding forces, the
 * weights W = M + sum m and sum d_j m_j in the rotor rows and the unbalance's and stuck balls'
 * weight torque on phi_0.  The frictionless right-hand sides ignore it.  This hook sets it, for
 * the tests against the SymPy check values (which are given with gravity on) only. */
#ifndef AUTOBAL_MODELS_ROTOR_INTERNAL_H
#define AUTOBAL_MODELS_ROTOR_INTERNAL_H

#include "autobal/rotor.h"

/* Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (NULL r, non-finite values). */
int autobal_rotor_friction_gravity_hook(autobal_rotor *r, double gu, double gv);

/* autobal_rotor_outputs_fast for n output points at once, the same numbers as n calls: t[k], the
 * state y + k ystride (ystride >= autobal_rotor_dim), the outputs out + k ostride (ostride >=
 * autobal_rotor_output_count).  The rotor transient study's buffered output points (output =
 * dense6, src/studies/rotor_transient.c).  Returns AUTOBAL_SUCCESS, or AUTOBAL_EINVAL (as
 * outputs_fast for any point; then nothing is written). */
int autobal_rotor_outputs_fast_block(const autobal_rotor *r, int frame, size_t n, const double *t, const double *y,
                                     size_t ystride, double *out, size_t ostride);

#endif
