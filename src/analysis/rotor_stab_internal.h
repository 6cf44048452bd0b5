/* rotor_stab_internal.h: test hooks of the rotor analysis (not installed): capacity-limited
 * variants of the critical-value searches (defined in rotor_stability.c and
 * rotor_campbell.c) for the tests of their truncation path (tests/test_rotor_stability.c).
 * Includes no other private header. */
#ifndef AUTOBAL_ROTOR_STAB_INTERNAL_H
#define AUTOBAL_ROTOR_STAB_INTERNAL_H

#include <stddef.h>

#include "autobal/rotor_stability.h"

/* autobal_rotor_stab_critical with the capacity of the list of critical values limited to
 * cap (1 <= cap <= AUTOBAL_ROTOR_MAX_CRIT; the public function uses AUTOBAL_ROTOR_MAX_CRIT),
 * so that the truncation path can be tested with few verdict changes.  AUTOBAL_EINVAL for
 * cap out of range (message on the handle); otherwise exactly the public function. */
int autobal_rotor_stab_critical_cap_(autobal_rotor_stab *s, int param, double lo, double hi,
                                     size_t n_grid, double xtol_rel, size_t cap,
                                     autobal_rotor_crit *out);
/* autobal_rotor_resonance_speeds with both lists limited to cap entries (1 <= cap <=
 * AUTOBAL_ROTOR_MAX_CRIT), for the same purpose. */
int autobal_rotor_resonance_speeds_cap_(const autobal_rotor_params *p, double lo, double hi,
                                        size_t n_grid, double xtol_rel, size_t cap,
                                        autobal_rotor_resonances *out, autobal_error *err);

#endif
