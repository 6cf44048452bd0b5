/* test_headers_c99.c: the public headers compile as strict C99 (this file is built with
 * -std=c99 -pedantic-errors -Wall -Wextra -Werror, see tests/CMakeLists.txt), and a program that
 * uses only the public API (no internal.h) runs: a few functions of every module are called and
 * their answers checked against values with an independent reason.
 * Companion tests: test_headers_cpp.cpp (C++11, extern "C" linkage proven by linking) and
 * test_headers.sh (every header on its own, twice, in C99 and C++; every declared AUTOBAL_API
 * function exported by the shared library). */
#include <autobal.h>
/* every module header once more, directly (include guards) */
#include <autobal/archive.h>
#include <autobal/export.h>
#include <autobal/pendulum.h>
#include <autobal/rotor.h>
#include <autobal/runup.h>
#include <autobal/stability.h>
#include <autobal/status.h>
#include <autobal/transient.h>
#include <autobal/version.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"

/* y'' = -y as a first-order system: y = (cos t, -sin t) from (1, 0). */
static int oscillator(double t, const double y[], double dydt[], void *params) {
  (void)t;
  (void)params;
  dydt[0] = y[1];
  dydt[1] = -y[0];
  return 0;
}

int main(void) {
  autobal_error err;
  autobal_pendulum_params p;
  autobal_transient *tr;
  autobal_transient_system sys;
  autobal_rotor_params rp;
  double y[2] = {1.0, 0.0}, t_reached = 0.0, c[3] = {2.0, 3.0, 1.0};
  double re[2], im[2];
  autobal_poly_workspace *pw;
  int verdict = 99, st;

  autobal_error_clear(&err);
  CHECK("status names come from one list", strcmp(autobal_status_name(AUTOBAL_EIO), "AUTOBAL_EIO") == 0);
  CHECK("version macro matches the library", strcmp(autobal_version(), AUTOBAL_VERSION_STRING) == 0);

  /* R_m = 0.5 is outside (0, 1/2): EINVAL naming R_m */
  st = autobal_pendulum_params_from_k(3.0, 0.5, 0.1, 0.5, 0.5, &p, &err);
  CHECK_STATUS("pendulum: R_m = 0.5 rejected", st, AUTOBAL_EINVAL);
  CHECK_MSG("pendulum: message names R_m", err.message, "R_m");

  /* (x + 1)(x + 2) = x^2 + 3x + 2: Hurwitz-stable, roots -2 and -1 */
  CHECK_STATUS("stability: Routh-Hurwitz on x^2 + 3x + 2", autobal_poly_hurwitz(c, 3, 1e-12, &verdict, NULL, &err),
               AUTOBAL_SUCCESS);
  CHECK("stability: verdict stable", verdict == AUTOBAL_VERDICT_STABLE);
  pw = autobal_poly_workspace_alloc(2);
  CHECK("stability: workspace", pw != NULL);
  if (pw) {
    CHECK_STATUS("stability: roots", autobal_poly_roots(pw, c, 3, re, im, &err), AUTOBAL_SUCCESS);
    CHECK_CLOSE("stability: first root -2", re[0], -2.0, 1e-14, 0.0);
    CHECK_CLOSE("stability: second root -1", re[1], -1.0, 1e-14, 0.0);
  }
  autobal_poly_workspace_free(pw);

  /* transient: one period of the oscillator returns to (1, 0) */
  tr = autobal_transient_alloc(2, NULL, &err);
  CHECK("transient: handle", tr != NULL);
  if (tr) {
    sys.rhs = oscillator;
    sys.jac = NULL;
    sys.dim = 2;
    sys.params = NULL;
    st = autobal_transient_run(tr, &sys, 0.0, 2.0 * 3.14159265358979323846, y, &t_reached);
    CHECK_STATUS("transient: run", st, AUTOBAL_SUCCESS);
    CHECK_CLOSE("transient: y(2 pi) = cos(2 pi) = 1", y[0], 1.0, 0.0, 1e-8);
    CHECK_CLOSE("transient: y'(2 pi) = -sin(2 pi) = 0", y[1], 0.0, 0.0, 1e-8);
  }
  autobal_transient_free(tr);

  /* rotor: the default example is valid, a zero housing mass is not */
  rp = autobal_rotor_params_default();
  CHECK_STATUS("rotor: default parameters valid", autobal_rotor_params_check(&rp, &err), AUTOBAL_SUCCESS);
  rp.hw.M_k = 0.0;
  CHECK_STATUS("rotor: M_k = 0 rejected", autobal_rotor_params_check(&rp, &err), AUTOBAL_EINVAL);
  CHECK_MSG("rotor: message names M_k", err.message, "M_k");

  /* archive: no HDF5 touched, only the NULL-handle contract */
  CHECK("archive: errmsg(NULL) is \"\"", strcmp(autobal_archive_errmsg(NULL), "") == 0);
  /* run-up: Omega 0 -> 200 rad/s over 2 s passes 100 rad/s at t = 1 s (linear) */
  {
    const double rt[2] = {0.0, 2.0}, rw[2] = {0.0, 200.0}, wc = 100.0;
    autobal_runup_series rs;
    autobal_runup_buffers rb;
    autobal_runup_passage pass[2];
    autobal_runup_result rr;
    memset(&rs, 0, sizeof rs);
    memset(&rb, 0, sizeof rb);
    rs.n = 2, rs.t = rt, rs.omega = rw;
    rb.passages = pass, rb.passage_cap = 2;
    CHECK_STATUS("runup: a two-sample ramp", autobal_runup_analyze(&rs, &wc, 1, NULL, &rb, &rr, &err), AUTOBAL_SUCCESS);
    CHECK("runup: one passage up at t = 1 s", rr.n_passages == 1 && pass[0].direction == 1 && fabs(pass[0].t - 1.0) < 1e-15);
  }
  return check_summary();
}
