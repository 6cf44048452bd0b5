/* autobal.h: umbrella header of the autobal library.
 *
 * autobal computes the dynamics of rotors with passive automatic balancers:
 * the planar two-pendulum autobalancer and a rotor in a massive housing with
 * one or two ball autobalancers.  See README.md and include/autobal/ for the
 * modules.  A host program should call gsl_set_error_handler_off() once. */
#ifndef AUTOBAL_H
#define AUTOBAL_H

#include "autobal/export.h"
#include "autobal/status.h"
#include "autobal/version.h"
#include "autobal/rotor.h"
#include "autobal/rotor_stability.h"
#include "autobal/rotor_asymptotic.h"
#include "autobal/runup.h"
#include "autobal/stability.h"
#include "autobal/transient.h"
#include "autobal/pendulum.h"
#include "autobal/archive.h"
#include "autobal/study.h"
#include "autobal/attractor.h"
#include "autobal/ensemble.h"
#include "autobal/design.h"

#endif
