/* rotor_integrate.h: integrate a rotor right-hand side (either frame) from t0 to t1 with the
 * library's transient driver (rk8pd, given tolerances, h_init 1e-5), for the rotor tests
 * (test_rotor.c, test_rotor_drive.c).  Returns the driver's status, -1 when it cannot be made. */
#ifndef AUTOBAL_TEST_ROTOR_INTEGRATE_H
#define AUTOBAL_TEST_ROTOR_INTEGRATE_H

#include "autobal/rotor.h"
#include "autobal/transient.h"

static int integrate(int (*f)(double, const double *, double *, void *), autobal_rotor *r, double t0, double t1,
                     double *y, double rtol, double atol) {
  autobal_transient_options opt = autobal_transient_options_default();
  autobal_transient_system sys;
  autobal_transient *tr;
  int st;
  opt.stepper = "rk8pd";
  opt.rtol = rtol;
  opt.atol = atol;
  opt.h_init = 1e-5;
  opt.max_steps = 50000000ul;
  sys.rhs = f;
  sys.jac = NULL;
  sys.dim = autobal_rotor_dim(r);
  sys.params = r;
  tr = autobal_transient_alloc(sys.dim, &opt, NULL);
  if (tr == NULL) return -1;
  st = autobal_transient_run(tr, &sys, t0, t1, y, NULL);
  autobal_transient_free(tr);
  return st;
}

#endif
