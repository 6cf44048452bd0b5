/* rotor_stability.h: internal functions of rotor_stability.c for the rest of the rotor stability
 * analysis (not installed).  Includes no other private header. */
#ifndef AUTOBAL_ANALYSIS_ROTOR_STABILITY_H
#define AUTOBAL_ANALYSIS_ROTOR_STABILITY_H

#include "autobal/rotor_stability.h"

/* The verdict and margin of a map point on handle s, its two parameters already set (user: the
 * caller's data).  Returns a status; AUTOBAL_SUCCESS with verdict AUTOBAL_ROTOR_VERDICT_NONE and a
 * NaN margin for a point without an answer. */
typedef int (*autobal_rotor_map_point_fn_)(autobal_rotor_stab *s, void *user, double *margin, int *verdict);

/* autobal_rotor_stab_map with the point's verdict from fn (the same grid, threads, determinism and
 * errors); so that an analysis built on the margin can map its own verdict without a circle of
 * calls. */
int autobal_rotor_stab_map_run_(const autobal_rotor_params *p, const autobal_rotor_stab_options *opt,
                                autobal_rotor_map_point_fn_ fn, void *user, int param1, const double *v1, size_t n1,
                                int param2, const double *v2, size_t n2, int n_threads, double *margin, int *verdict,
                                autobal_error *err);

#endif
