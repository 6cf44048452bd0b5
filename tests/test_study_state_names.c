/* test_study_state_names.c: autobal_study_rotor_transient_state_name (the names and units of the
 * final state in `rotor transient --json`) against the state layout documented in
 * include/autobal/rotor.h: x, y, alpha, beta, their rates, the ball angles and rates in state
 * order, then (z, z') with axial motion, then (phi_0, Omega) with a MOTOR drive.  The layout is
 * also checked on the values: the final ball angles of a fixed-frame run minus omega t_reached
 * are the relative angles of planes[].ball_psi_final (wrapped), and a motor's Omega is the last
 * entry.  Every error path: NULL summary or buffer, k >= dim, a buffer too short. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal.h"
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void names_of(const autobal_study_rotor_transient_summary *s, char names[][32], const char **units) {
  size_t k;
  for (k = 0; k < s->dim; k++)
    if (autobal_study_rotor_transient_state_name(s, k, names[k], 32, &units[k]) != AUTOBAL_SUCCESS) {
      snprintf(names[k], 32, "?");
      units[k] = "?";
    }
}

int main(void) {
  autobal_study_rotor_transient_options o = autobal_study_rotor_transient_options_default();
  autobal_study_rotor_transient_summary s;
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_error err;
  char names[64][32], buf[8];
  const char *units[64], *u = NULL;
  int st;
  gsl_set_error_handler_off();
  o.t_end = 0.01;

  printf("-- fixed frame, one plane, two balls\n");
  st = autobal_study_rotor_transient(&p, &o, NULL, &s, &err);
  CHECK_STATUS("run", st, AUTOBAL_SUCCESS);
  CHECK("dim 12, frame fixed, no axial, no motor",
        s.dim == 12 && s.state_frame == AUTOBAL_ROTOR_FIXED && !s.state_axial && !s.state_motor);
  names_of(&s, names, units);
  CHECK("names x .. beta_rate, phi_1, phi_2, phi_rate_1, phi_rate_2",
        !strcmp(names[0], "x") && !strcmp(names[3], "beta") && !strcmp(names[7], "beta_rate") &&
            !strcmp(names[8], "phi_1") && !strcmp(names[9], "phi_2") && !strcmp(names[10], "phi_rate_1") &&
            !strcmp(names[11], "phi_rate_2"));
  CHECK("units m, rad, m/s, rad/s",
        !strcmp(units[0], "m") && !strcmp(units[2], "rad") && !strcmp(units[4], "m/s") &&
            !strcmp(units[6], "rad/s") && !strcmp(units[8], "rad") && !strcmp(units[11], "rad/s"));
  {
    /* phi_i - omega t = psi_i (relative), wrapped like ball_psi_final */
    double d0 = remainder(s.state_final[8] - p.omega * s.t_reached - s.ball_psi_final[0][0], 2 * M_PI);
    double d1 = remainder(s.state_final[9] - p.omega * s.t_reached - s.ball_psi_final[0][1], 2 * M_PI);
    CHECK_CLOSE("phi_1 - omega t == ball_psi_final[0] (mod 2 pi)", d0, 0.0, 0.0, 1e-9);
    CHECK_CLOSE("phi_2 - omega t == ball_psi_final[1] (mod 2 pi)", d1, 0.0, 0.0, 1e-9);
  }
  printf("-- errors\n");
  CHECK_STATUS("k = dim", autobal_study_rotor_transient_state_name(&s, s.dim, names[0], 32, &u), AUTOBAL_EINVAL);
  CHECK_STATUS("NULL summary", autobal_study_rotor_transient_state_name(NULL, 0, names[0], 32, &u), AUTOBAL_EINVAL);
  CHECK_STATUS("NULL buffer", autobal_study_rotor_transient_state_name(&s, 0, NULL, 32, &u), AUTOBAL_EINVAL);
  CHECK_STATUS("buffer of 8 for 'phi_rate_1'", autobal_study_rotor_transient_state_name(&s, 10, buf, sizeof buf, &u),
               AUTOBAL_EINVAL);
  CHECK_STATUS("unit may be NULL", autobal_study_rotor_transient_state_name(&s, 0, names[0], 32, NULL), AUTOBAL_SUCCESS);
  autobal_study_rotor_transient_summary_free(&s);

  printf("-- rotating frame, axial motion, a motor\n");
  p.axial = 1;
  p.drive.mode = AUTOBAL_ROTOR_DRIVE_MOTOR;
  p.drive.J = 0.05;
  p.drive.L_0 = 5.0;
  p.drive.omega_0 = 600.0;
  p.drive.omega_start = 100.0;
  o.frame = AUTOBAL_ROTOR_ROTATING;
  st = autobal_study_rotor_transient(&p, &o, NULL, &s, &err);
  CHECK_STATUS("run", st, AUTOBAL_SUCCESS);
  if (st) printf("   %s\n", err.message);
  CHECK("dim 16, frame rotating, axial, motor",
        s.dim == 16 && s.state_frame == AUTOBAL_ROTOR_ROTATING && s.state_axial && s.state_motor);
  if (s.dim == 16) {
    names_of(&s, names, units);
    CHECK("psi_1, psi_rate_2, z, z_rate, phi_0, Omega",
          !strcmp(names[8], "psi_1") && !strcmp(names[11], "psi_rate_2") && !strcmp(names[12], "z") &&
              !strcmp(names[13], "z_rate") && !strcmp(names[14], "phi_0") && !strcmp(names[15], "Omega"));
    CHECK("units of z, z_rate, phi_0, Omega: m, m/s, rad, rad/s",
          !strcmp(units[12], "m") && !strcmp(units[13], "m/s") && !strcmp(units[14], "rad") &&
              !strcmp(units[15], "rad/s"));
    /* the motor accelerates from omega_start: Omega(t_reached) > omega_start, and phi_0 is its integral */
    CHECK("Omega (last entry) grew from omega_start, phi_0 between 100 t and Omega t",
          s.state_final[15] > 100.0 && s.state_final[14] > 100.0 * s.t_reached &&
              s.state_final[14] < s.state_final[15] * s.t_reached);
  }
  autobal_study_rotor_transient_summary_free(&s);
  return check_summary();
}
