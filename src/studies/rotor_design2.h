/* rotor_design2.h: the two-plane search of `autobal rotor design` (src/studies/rotor_design2.c;
 * docs/rotor.md "Design", "Two planes").  Private to src/studies. */
#ifndef AUTOBAL_ROTOR_DESIGN2_H
#define AUTOBAL_ROTOR_DESIGN2_H

#include "autobal/design.h"

/* The search on the machine work (two planes of two balls each, drive constant; its ball arrays
 * writable) with the resolved options o: fills S's grids, map (feasible, margin_map), ranked designs
 * (margins, certification), counts; not best_config.  Statuses as autobal_study_rotor_design. */
int autobal_design2_run_(autobal_rotor_params *work, const autobal_study_rotor_design_options *o,
                         autobal_study_rotor_design_summary *S, autobal_error *err);

#endif
