/* consumer.c: what a legacy C code does with an installed autobal. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include <autobal.h>

int main(void) {
  autobal_pendulum_params p;
  autobal_error err;
  int verdict = 0, st;
  gsl_set_error_handler_off();
  /* a bad parameter is reported, not aborted on */
  st = autobal_pendulum_params_from_k(3.0, 0.7, 0.1, 0.5, 0.5, &p, &err);
  if (st != AUTOBAL_EINVAL || strstr(err.message, "R_m") == NULL) {
    fprintf(stderr, "expected EINVAL naming R_m, got %d '%s'\n", st, err.message);
    return 1;
  }
  st = autobal_pendulum_params_from_k(3.0, 0.1, 0.1, 0.5, 0.5, &p, &err);
  if (st == AUTOBAL_SUCCESS) st = autobal_pendulum_verdict(&p, &verdict, NULL, &err);
  if (st != AUTOBAL_SUCCESS) {
    fprintf(stderr, "autobal: %s\n", err.message);
    return 1;
  }
  printf("autobal %s: main motion at R_w = 3 is %s\n", autobal_version(), autobal_verdict_name(verdict));
  return verdict == AUTOBAL_VERDICT_STABLE ? 0 : 1;
}
