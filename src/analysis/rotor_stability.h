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

/* Two planes through the one-plane every-unbalance entry points (rotor_unbalance2.c): both planes
 * over [s_lo, s_hi], every relative phase, AUTOBAL_ROTOR_EVERY2_GRID unbalances per plane. */
#define AUTOBAL_ROTOR_EVERY2_GRID 9
int autobal_rotor_every_unbalance_two_planes_(autobal_rotor_stab *s, double s_lo, double s_hi,
                                              autobal_rotor_unbalance_range *out);
int autobal_rotor_every_unbalance_speeds_two_planes_(autobal_rotor_stab *s, double s_lo, double s_hi, double w_lo,
                                                     double w_hi, size_t n_grid, double xtol_rel,
                                                     autobal_rotor_crit *out);

/* The verdict "stable for all" at the handle's current omega (user: the caller's data), with the
 * count of evaluations it took. */
typedef int (*autobal_rotor_speed_verdict_fn_)(autobal_rotor_stab *s, void *user, int *all_stable,
                                               size_t *evaluations);
/* The speeds in [w_lo, w_hi] where fn says stable: n_grid speeds, each change bisected to xtol_rel;
 * out cleared and filled as by autobal_rotor_stab_every_unbalance_speeds; omega restored
 * (rotor_speed_scan.c). */
int autobal_rotor_scan_speeds_(autobal_rotor_stab *s, double w_lo, double w_hi, size_t n_grid, double xtol_rel,
                               autobal_rotor_speed_verdict_fn_ fn, void *user, autobal_rotor_crit *out);

#endif
