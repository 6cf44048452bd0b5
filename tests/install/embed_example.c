/* embed.c: autobal inside an existing C program (no HDF5, the host's own error handling). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>
#include <autobal.h>

/* The host's own error reporting; autobal only hands it a status and a message. */
static int host_error(const char *what, int status, const char *message) {
  fprintf(stderr, "host: %s failed: %s [%s]\n", what, message, autobal_status_name(status));
  return 1;
}

/* Residual unbalance relative to m0 r0 (rotor.h): the "time to balance" monitor. */
static double unbalance(double t, const double y[], void *rotor) {
  return autobal_rotor_balance_monitor(rotor, AUTOBAL_ROTOR_FIXED, t, y);
}

/* Called at every output time: the host keeps what it needs (here the largest amplitude of
 * the centre of mass over the last second). */
static int observe(double t, const double y[], void *max_amp) {
  if (t >= 11.0 && hypot(y[0], y[1]) > *(double *)max_amp) *(double *)max_amp = hypot(y[0], y[1]);
  return 0; /* non-zero would stop the run */
}

int main(void) {
  autobal_error err;
  autobal_pendulum_params p;
  autobal_rotor_params rp;
  autobal_rotor *rotor;
  autobal_transient_options opt;
  autobal_transient *tr;
  autobal_transient_event_hit hit;
  double *y, t_end = 0.0, max_amp = 0.0;
  int verdict, st, dwell;

  gsl_set_error_handler_off(); /* once, at start-up: GSL must report, not abort the host */

  /* 1. Stability verdict of the pendulum balancer's main motion, eqs. (2)-(6), dimensionless:
   *    R_w = 3, R_m = 0.1, H = 0.1, h = 0.5, k = 0.5. */
  st = autobal_pendulum_params_from_k(3.0, 0.1, 0.1, 0.5, 0.5, &p, &err);
  if (st == AUTOBAL_SUCCESS) st = autobal_pendulum_verdict(&p, &verdict, NULL, &err);
  if (st != AUTOBAL_SUCCESS) return host_error("pendulum verdict", st, err.message);
  printf("pendulum at R_w = 3: %s\n", autobal_verdict_name(verdict));

  /* 2. Bad input comes back as a status with a message naming parameter, value and range. */
  st = autobal_pendulum_params_from_k(3.0, 0.7, 0.1, 0.5, 0.5, &p, &err);
  if (st != AUTOBAL_EINVAL) return host_error("rejecting R_m = 0.7", st, "not rejected");
  printf("rejected: %s\n", err.message);

  /* 3. A 12 s transient of the default rotor (SI units, rotor.h) with a "time to balance"
   *    event: the residual unbalance below 1% of m0 r0 for 50 revolutions. */
  rp = autobal_rotor_params_default();
  rotor = autobal_rotor_alloc(&rp, &err);
  if (!rotor) return host_error("rotor", err.status, err.message);
  opt = autobal_transient_options_default();
  opt.rtol = 1e-10; /* the command line's tolerances (data/rotor_default.ini): the ball angles */
  opt.atol = 1e-9;  /* grow like omega t in the fixed frame, so rtol bounds them; atol the rotor's */
  opt.dt_out = 0.01; /* s */
  tr = autobal_transient_alloc(autobal_rotor_dim(rotor), &opt, &err);
  y = malloc(autobal_rotor_dim(rotor) * sizeof *y);
  if (!tr || !y) {
    st = tr ? AUTOBAL_ENOMEM : err.status;
    autobal_transient_free(tr);
    autobal_rotor_free(rotor);
    free(y);
    return host_error("transient", st, tr ? "out of memory" : err.message);
  }
  {
    autobal_transient_system sys = {autobal_rotor_rhs, NULL, 0, NULL};
    sys.dim = autobal_rotor_dim(rotor);
    sys.params = rotor;
    autobal_transient_set_observer(tr, observe, &max_amp);
    dwell = autobal_transient_add_dwell_event(tr, unbalance, rotor, 0.01, 50 * 2 * acos(-1.0) / rp.omega, 0);
    st = dwell < 0 ? dwell : autobal_rotor_initial_state(rotor, AUTOBAL_ROTOR_FIXED, 0.0, y, sys.dim);
    if (st == AUTOBAL_SUCCESS) st = autobal_transient_run(tr, &sys, 0.0, 12.0, y, &t_end);
  }
  if (st < 0) {
    /* y holds the state at t_end, the last good step: the host may keep it */
    host_error("rotor transient", st, autobal_transient_errmsg(tr));
  } else if (autobal_transient_event_result(tr, (size_t)dwell, NULL, &hit) == 1) {
    printf("rotor balanced after %.2f s; amplitude in the last second <= %.3g um\n", hit.t_start, 1e6 * max_amp);
  } else {
    printf("rotor not balanced within %.0f s\n", t_end);
  }
  free(y);
  autobal_transient_free(tr);
  autobal_rotor_free(rotor);
  return st < 0;
}
