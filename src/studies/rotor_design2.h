/* rotor_design2.h: the two-plane search of `autobal rotor design` (src/studies/rotor_design2.c;
 * docs/rotor.md "Design", "Two planes").  Private to src/studies. */
#ifndef AUTOBAL_ROTOR_DESIGN2_H
#define AUTOBAL_ROTOR_DESIGN2_H

#include <gsl/gsl_multimin.h>

#include "autobal/design.h"

/* The search on the machine work (two planes of two balls each, drive constant; its ball arrays
 * writable) with the resolved options o: fills S's grids, map (feasible, margin_map), ranked designs
 * (margins, certification), counts; not best_config.  Statuses as autobal_study_rotor_design. */
/* n values from lo to hi (the last exactly hi), geometric or linear; malloc'ed (NULL when out of memory).
 * The grids of both designs' maps (rotor_design.c uses it too). */
double *autobal_design_grid_(double lo, double hi, size_t n, int geometric);

/* GSL's Nelder-Mead simplex (nmsimplex2) over n variables with its start and step vectors, for both
 * designs' optimizers: 0, or -1 when out of memory (then all three freed and NULL). */
int autobal_design_nm_alloc_(size_t n, gsl_multimin_fminimizer **mz, gsl_vector **x, gsl_vector **step);

int autobal_design2_run_(autobal_rotor_params *work, const autobal_study_rotor_design_options *o,
                         autobal_study_rotor_design_summary *S, autobal_error *err);

#endif
