/* test_rotor_tight.c: rotor transients at tight tolerances converge in both frames (issue 18,
 * item 3; docs/rotor.md "How the ball angles are integrated").
 *
 * The default example (docs/rotor.md) run for 600 revolutions (t1 = 600 2 pi/omega = 7.54 s, ball
 * angles |phi| ~ 3700 rad there) with `frame = fixed` at rtol 1e-11, 1e-12, 1e-13 (atol 1e-15)
 * against the rotating-frame solution at rtol 1e-14 (the ball angles relative to the rotor, the
 * separate right-hand side autobal_rotor_rhs_rotating, itself checked against SciPy's DOP853 in
 * tests/app/rotor.sh and against the fixed-frame right-hand side in tests/test_rotor.c).
 *
 * Expected behaviour, not taken from the program: rk8pd is an 8(7) pair, its step size goes like
 * tol^(1/8), so the step count grows by 10^(1/8) = 1.33 per decade of rtol (checked: at most 2);
 * the error falls with every decade of rtol, and at rtol 1e-13 the state agrees with the reference
 * within 5e-11 rad (ball angles relative to the rotor; the absolute phi to 4 ulp(phi) more;
 * measured 1.1e-11) and 1e-7 of the rotor's vibration amplitude (x, y, alpha, beta and rates at t1:
 * the balanced state's small whirl, whose phase is the demanding part; measured 1.7e-8).
 * Integrating the absolute angles (before the fix) fails these: 48533, 184523, 642639 steps at
 * rtol 1e-11, 1e-12, 1e-13 (3.8x and 3.5x per decade), errors 2.9e-7, 1.3e-7, 2.6e-7 (rotor) and
 * 2.1e-10, 6.5e-11, 2.0e-10 rad (angles): the rounding of |phi| ~ 3700 rad (ulp 4.5e-13) at every
 * step.  The output keeps its meaning: state_final holds the absolute angles phi = omega t + psi. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "autobal.h"
#include "check.h"

#define TWO_PI 6.283185307179586476925286766559

typedef struct run_result {
  unsigned long steps;
  double q[8];
  double phi[2], psi[2]; /* state_final's angles (phi absolute in the fixed frame) and ball_psi_final */
  int frame;
} run_result;

static int run(int frame, double rtol, double t1, run_result *out) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_transient_options o = autobal_study_rotor_transient_options_default();
  autobal_study_rotor_transient_summary s;
  autobal_error err;
  size_t k;
  int st;
  o.t_end = t1;
  o.frame = frame;
  o.rtol = rtol;
  o.atol = 1e-15;
  st = autobal_study_rotor_transient(&p, &o, NULL, &s, &err);
  if (st != AUTOBAL_SUCCESS || s.dim != 12 || !s.state_final) {
    printf("run failed: status %d: %s\n", st, err.message);
    autobal_study_rotor_transient_summary_free(&s);
    return -1;
  }
  out->steps = s.solver.steps;
  for (k = 0; k < 8; k++) out->q[k] = s.state_final[k];
  for (k = 0; k < 2; k++) {
    out->phi[k] = s.state_final[8 + k];
    out->psi[k] = s.ball_psi_final[0][k];
  }
  out->frame = s.state_frame;
  printf("     %s frame, rtol %.0e, atol 1e-15: %lu steps, angles %.17g %.17g\n",
         frame == AUTOBAL_ROTOR_FIXED ? "fixed" : "rotating", rtol, out->steps, out->phi[0], out->phi[1]);
  autobal_study_rotor_transient_summary_free(&s);
  return 0;
}

/* the rotor state's distance from the reference, relative to the reference's largest entry of
 * each kind (x, y; alpha, beta; their rates), the worst of the four */
static double q_err(const double *q, const double *r) {
  double e = 0.0;
  int g;
  for (g = 0; g < 4; g++) {
    const int i = 2 * g;
    const double sc = fmax(fabs(r[i]), fabs(r[i + 1]));
    const double d = fmax(fabs(q[i] - r[i]), fabs(q[i + 1] - r[i + 1])) / sc;
    if (d > e) e = d;
  }
  return e;
}

static double wrap(double a) { return remainder(a, TWO_PI); }

int main(void) {
  const double omega = 500.0, t1 = 600.0 * TWO_PI / omega;
  const double rtols[3] = {1e-11, 1e-12, 1e-13};
  run_result ref, f[3];
  double eq[3], ep[3], ea[3];
  char what[200];
  int i, k;

  printf("rotor transient, default example, 600 revolutions (t1 = %.10g s)\n", t1);
  if (run(AUTOBAL_ROTOR_ROTATING, 1e-14, t1, &ref) != 0) return 1;
  for (i = 0; i < 3; i++)
    if (run(AUTOBAL_ROTOR_FIXED, rtols[i], t1, &f[i]) != 0) return 1;

  for (i = 0; i < 3; i++) {
    eq[i] = q_err(f[i].q, ref.q);
    ep[i] = 0.0;
    ea[i] = 0.0;
    for (k = 0; k < 2; k++) {
      /* relative angle of the summary; absolute angle of the state against omega t1 + psi_ref */
      const double dp = fabs(wrap(f[i].psi[k] - ref.psi[k]));
      const double da = fabs(f[i].phi[k] - (omega * t1 + ref.phi[k]));
      if (dp > ep[i]) ep[i] = dp;
      if (da > ea[i]) ea[i] = da;
    }
    printf("     fixed, rtol %.0e: rotor state error %.3g (relative), ball angles %.3g rad (psi), %.3g rad (phi)\n",
           rtols[i], eq[i], ep[i], ea[i]);
  }

  CHECK("state_final is in the fixed frame", f[0].frame == AUTOBAL_ROTOR_FIXED && f[2].frame == AUTOBAL_ROTOR_FIXED);
  CHECK("state_final holds the absolute angles: phi - psi_ref = omega t1 (3770 rad) within 1e-6 rad",
        fabs(f[2].phi[0] - ref.phi[0] - omega * t1) < 1e-6 && fabs(f[2].phi[1] - ref.phi[1] - omega * t1) < 1e-6);
  for (i = 1; i < 3; i++) {
    const double ratio = (double)f[i].steps / (double)f[i - 1].steps;
    snprintf(what, sizeof what, "step count rtol %.0e -> %.0e grows like tol^(-1/8) (10^(1/8) = 1.33; at most 2)",
             rtols[i - 1], rtols[i]);
    CHECK_CLOSE(what, ratio, 1.0, 0, 1.0);
    snprintf(what, sizeof what, "rotor state error falls with rtol %.0e -> %.0e", rtols[i - 1], rtols[i]);
    CHECK_CLOSE(what, eq[i], 0.0, 0, eq[i - 1]);
    snprintf(what, sizeof what, "ball angle error falls with rtol %.0e -> %.0e", rtols[i - 1], rtols[i]);
    CHECK_CLOSE(what, ep[i], 0.0, 0, ep[i - 1]);
  }
  CHECK_CLOSE("rtol 1e-13: rotor state vs the rotating frame at rtol 1e-14 (relative)", eq[2], 0.0, 0, 1e-7);
  CHECK_CLOSE("rtol 1e-13: ball angles psi vs the rotating frame at rtol 1e-14 (rad)", ep[2], 0.0, 0, 5e-11);
  CHECK_CLOSE("rtol 1e-13: absolute angles phi vs omega t1 + psi of the reference (rad, + 4 ulp(phi))", ea[2], 0.0,
              0, 5e-11 + 4.0 * 4.547473508864641e-13);
  printf("%d checks, %d failed\n", check_count_, check_failures_);
  return check_failures_ ? 1 : 0;
}
