/* test_study.c: the study API (include/autobal/study.h) on its own: known answers computed
 * independently of the studies (the initial residual unbalance from (3.1) by hand, ISO 21940-11
 * figures by hand, the field tables against offsetof), and every error path provoked: bad
 * options, bad parameters, a warning, cancellation, writing into an archive opened for reading.
 * That the archives equal the program's is tested by examples/embed_study_check.sh. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal.h"
#include "check.h"

static int cancel_at_start(double fraction, void *user) {
  int *calls = user;
  (*calls)++;
  return fraction >= 0.0; /* at once */
}

static void test_fields(void) {
  size_t nh = 0, nl = 0, i;
  const autobal_rotor_field *h = autobal_rotor_hardware_fields(&nh), *l = autobal_rotor_lumped_fields(&nl);
  autobal_rotor_hardware hw;
  autobal_rotor_lumped lu;
  CHECK("17 hardware fields", nh == 17);
  CHECK("17 lumped fields", nl == 17);
  CHECK("hardware c_Lx at offsetof", !strcmp(h[7].name, "c_Lx") && h[7].offset == offsetof(autobal_rotor_hardware, c_Lx));
  CHECK("hardware c_Lx in [supports], N/m", !strcmp(h[7].section, "supports") && !strcmp(h[7].unit, "N/m"));
  CHECK("lumped h_yalpha last, N s", !strcmp(l[16].name, "h_yalpha") && l[16].offset == offsetof(autobal_rotor_lumped, h_yalpha) && !strcmp(l[16].unit, "N s"));
  /* every field reaches its own double: write i into each, read back through the struct */
  memset(&hw, 0, sizeof hw);
  memset(&lu, 0, sizeof lu);
  for (i = 0; i < nh; i++) *autobal_rotor_field_ptr(&hw, &h[i]) = (double)i + 1.0;
  for (i = 0; i < nl; i++) *autobal_rotor_field_ptr(&lu, &l[i]) = (double)i + 1.0;
  CHECK("hardware fields distinct: M_k = 1, h_Ry = 17", hw.M_k == 1.0 && hw.h_Ry == 17.0 && hw.l_L == 6.0);
  CHECK("lumped fields distinct: M = 1, c_alpha = 7, h_yalpha = 17", lu.M == 1.0 && lu.c_alpha == 7.0 && lu.h_yalpha == 17.0);
  CHECK("field_get reads what field_ptr wrote", autobal_rotor_field_get(&hw, &h[9]) == 10.0);
}

static void test_iso(void) {
  /* G = U/m omega: 1e-4 kg m on 4 kg at 500 rad/s is e = 25 um, G = 12.5 mm/s */
  CHECK_CLOSE("grade of 1e-4 kg m, 4 kg, 500 rad/s", autobal_balance_grade(1e-4, 4.0, 500.0), 12.5, 1e-15, 0);
  /* U_per of G6.3 at 500 rad/s for 4 kg: e = 6.3e-3/500 m = 12.6 um, U = 5.04e-5 kg m */
  CHECK_CLOSE("permissible of G6.3, 4 kg, 500 rad/s", autobal_permissible_unbalance(6.3, 4.0, 500.0), 5.04e-5, 1e-15, 0);
  CHECK("class of 2.4 is 2.5", autobal_balance_grade_class(2.4) == 2.5);
  CHECK("class of 2.5 is 2.5", autobal_balance_grade_class(2.5) == 2.5);
  CHECK("class of 2.6 is 6.3", autobal_balance_grade_class(2.6) == 6.3);
  CHECK("class above G4000 is NaN", isnan(autobal_balance_grade_class(4001.0)));
}

static void test_transient(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_transient_options o = autobal_study_rotor_transient_options_default();
  autobal_study_rotor_transient_summary s;
  autobal_error err;
  double su, sv, want;
  int st, calls = 0;
  const autobal_rotor_plane *pl = &p.plane[0];

  /* a short run, no archive */
  o.t_end = 0.2;
  o.grade = 6.3;
  st = autobal_study_rotor_transient(&p, &o, NULL, &s, &err);
  CHECK_STATUS("rotor transient 0.2 s without archive", st, AUTOBAL_SUCCESS);
  /* (3.1) in the rotor frame at t = 0: s = m0 r0 e^{i psi0} + sum m_i r_i e^{i psi_i}, by hand */
  su = pl->m0 * pl->r0 * cos(pl->psi0) + pl->ball_mass[0] * pl->ball_radius[0] * cos(pl->ball_psi[0]) +
       pl->ball_mass[1] * pl->ball_radius[1] * cos(pl->ball_psi[1]);
  sv = pl->m0 * pl->r0 * sin(pl->psi0) + pl->ball_mass[0] * pl->ball_radius[0] * sin(pl->ball_psi[0]) +
       pl->ball_mass[1] * pl->ball_radius[1] * sin(pl->ball_psi[1]);
  want = hypot(su, sv) / (pl->m0 * pl->r0);
  CHECK_CLOSE("initial |s|/(m0 r0) from (3.1) by hand", s.residual_unbalance_initial, want, 1e-12, 0);
  CHECK_CLOSE("t_reached = t_end", s.t_reached, 0.2, 0, 0);
  CHECK("one plane, two balls, final angles in [-pi, pi]",
        s.n_planes == 1 && s.n_balls[0] == 2 && s.ball_psi_final[0] && fabs(s.ball_psi_final[0][0]) <= 3.14159265358979324);
  CHECK("relative final = absolute / (m0 r0)",
        fabs(s.residual_unbalance_rel_final[0] - s.residual_unbalance_abs_final[0] / (pl->m0 * pl->r0)) <= 1e-15 * s.residual_unbalance_rel_final[0]);
  CHECK_CLOSE("grade = U/m_p |omega| 1e3 of the final |s|", s.balance_grade_final,
              s.residual_unbalance_abs_final[0] / p.hw.m_p * p.omega * 1e3, 1e-15, 0);
  CHECK_CLOSE("permissible unbalance of G6.3 at 500 rad/s, m_p = 4 kg", s.permissible_unbalance, 5.04e-5, 1e-15, 0);
  CHECK("not balanced within 0.2 s (the balance needs 50 revolutions = 0.63 s)", !s.balanced && isnan(s.time_to_balance));
  CHECK("the state is kept (dim 12)", s.dim == 12 && s.state_final != NULL);
  /* the default since 0.2.0: dop853 with output on its order-6 extension (the CLI's too, apps/) */
  CHECK("solver statistics, the default stepper dop853", s.solver.steps > 0 && !strcmp(s.stepper, "dop853"));
  CHECK("default options: stepper dop853, dense_order 6, exact_output 0",
        o.stepper && !strcmp(o.stepper, "dop853") && o.dense_order == 6 && o.exact_output == 0);
  {
    autobal_study_pendulum_transient_options po = autobal_study_pendulum_transient_options_default();
    CHECK("pendulum default options: stepper dop853, dense_order 6, exact_output 0",
          po.stepper && !strcmp(po.stepper, "dop853") && po.dense_order == 6 && po.exact_output == 0);
  }
  autobal_study_rotor_transient_summary_free(&s);
  CHECK("summary_free clears the pointers", s.state_final == NULL && s.ball_psi_final[0] == NULL);
  autobal_study_rotor_transient_summary_free(&s); /* twice: harmless */

  /* bad options: message names the option, nothing allocated */
  o = autobal_study_rotor_transient_options_default();
  o.t_end = 0.0;
  st = autobal_study_rotor_transient(&p, &o, NULL, &s, &err);
  CHECK_STATUS("t_end = 0 rejected", st, AUTOBAL_EINVAL);
  CHECK_MSG("t_end = 0", err.message, "options: t_end");
  CHECK("summary zeroed after an input failure", s.state_final == NULL && s.n_planes == 0);
  o = autobal_study_rotor_transient_options_default();
  o.stepper = "euler-maruyama";
  CHECK_STATUS("unknown stepper rejected by check", autobal_study_rotor_transient_check(&p, &o, &err), AUTOBAL_EINVAL);
  CHECK_MSG("unknown stepper", err.message, "options: ");
  o = autobal_study_rotor_transient_options_default();
  o.frame = 7;
  CHECK_STATUS("frame 7 rejected", autobal_study_rotor_transient_check(&p, &o, &err), AUTOBAL_EINVAL);
  CHECK_MSG("frame 7", err.message, "frame");

  /* bad parameters: the model's message with the struct field */
  {
    autobal_rotor_params q = autobal_rotor_params_default();
    double bad_mass[2] = {0.05, -0.01};
    q.plane[0].ball_mass = bad_mass;
    st = autobal_study_rotor_transient_check(&q, NULL, &err);
    CHECK_STATUS("negative ball mass rejected", st, AUTOBAL_EINVAL);
    CHECK_MSG("negative ball mass", err.message, "plane[0].ball_mass[1]");
  }
  /* a plane whose balls cannot cancel its unbalance: a warning, and the run says so */
  {
    autobal_rotor_params q = autobal_rotor_params_default();
    q.plane[0].m0 = 0.2; /* m0 r0 = 0.02 > sum m r = 0.01 */
    CHECK_STATUS("unbalanceable plane: check warns", autobal_study_rotor_transient_check(&q, NULL, &err), AUTOBAL_WARNING);
    o = autobal_study_rotor_transient_options_default();
    o.t_end = 0.05;
    st = autobal_study_rotor_transient(&q, &o, NULL, &s, &err);
    CHECK("unbalanceable plane: run succeeds with summary.warning", st == AUTOBAL_SUCCESS && s.warning && s.warning_message[0]);
    CHECK("no balanced configuration (3.14)", s.ball_psi_balanced[0] == NULL);
    autobal_study_rotor_transient_summary_free(&s);
  }
  /* cancellation from the progress callback */
  o = autobal_study_rotor_transient_options_default();
  o.t_end = 5.0;
  o.progress = cancel_at_start;
  o.progress_user = &calls;
  st = autobal_study_rotor_transient(&p, &o, NULL, &s, &err);
  CHECK_STATUS("cancelled at the first progress call", st, AUTOBAL_ECANCELLED);
  CHECK("cancelled: progress called once, t_reached < t_end", calls == 1 && s.t_reached < 5.0);
  autobal_study_rotor_transient_summary_free(&s);
}

static void test_stability_and_pendulum(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_stability_summary s;
  autobal_study_rotor_stability_options o = autobal_study_rotor_stability_options_default();
  autobal_pendulum_params pp = {3.0, 0.1, 0.1, 0.5, 0.3};
  autobal_pendulum_result r;
  autobal_error err;
  int st;
  p.omega = 0.0;
  st = autobal_study_rotor_stability(&p, NULL, NULL, &s, &err);
  CHECK_STATUS("stability at omega = 0 rejected", st, AUTOBAL_EINVAL);
  CHECK_MSG("omega = 0", err.message, "omega");
  autobal_study_rotor_stability_summary_free(&s);
  p = autobal_rotor_params_default();
  o.n_omega = 1;
  CHECK_STATUS("n_omega = 1 rejected", autobal_study_rotor_stability(&p, &o, NULL, &s, &err), AUTOBAL_EINVAL);
  CHECK_MSG("n_omega = 1", err.message, "options: ");
  autobal_study_rotor_stability_summary_free(&s);
  o = autobal_study_rotor_stability_options_default();
  o.critical_speeds = 0;
  st = autobal_study_rotor_stability(&p, &o, NULL, &s, &err);
  CHECK_STATUS("default rotor stability (no critical speeds)", st, AUTOBAL_SUCCESS);
  /* the balanced angles of two equal balls (3.14): cos psi = -m0 r0 / (2 m r) = -0.2 */
  CHECK("two balanced angles kept by the summary", s.result.n_balls == 2 && s.result.psi != NULL && !s.have_critical);
  if (s.result.psi) CHECK_CLOSE("cos psi_1 = -m0 r0/(2 m r) (3.14)", cos(s.result.psi[0]), -0.2, 1e-12, 1e-12);
  autobal_study_rotor_stability_summary_free(&s);
  CHECK("stability summary_free clears psi", s.result.psi == NULL);

  pp.R_m = 0.7;
  CHECK_STATUS("pendulum roots: R_m = 0.7 rejected", autobal_study_pendulum_roots(&pp, NULL, NULL, &r, &err), AUTOBAL_EINVAL);
  CHECK_MSG("R_m = 0.7", err.message, "R_m");
}

/* Writing into an archive opened for reading fails with a status and a message, no crash. */
static void test_readonly_archive(void) {
  char path[512];
  autobal_archive *a = NULL, *ro = NULL;
  autobal_error err;
  autobal_pendulum_params pp = {3.0, 0.1, 0.1, 0.5, 0.3};
  autobal_pendulum_result r;
  autobal_study_pendulum_transient_summary s;
  autobal_study_pendulum_transient_options o = autobal_study_pendulum_transient_options_default();
  int st;
  snprintf(path, sizeof path, "%s/test_study_ro.h5", AUTOBAL_TEST_TMP_DIR);
  st = autobal_archive_create(path, 1, &a, &err);
  CHECK_STATUS("create an archive", st, AUTOBAL_SUCCESS);
  if (st) return;
  st = autobal_archive_close(a, &err);
  CHECK_STATUS("close it", st, AUTOBAL_SUCCESS);
  st = autobal_archive_open_read(path, &ro, &err);
  CHECK_STATUS("open it for reading", st, AUTOBAL_SUCCESS);
  if (st) return;
  st = autobal_study_pendulum_roots(&pp, NULL, ro, &r, &err);
  CHECK("pendulum roots into a read-only archive: a failure status", st < 0);
  CHECK("... with a message", err.message[0] != '\0');
  o.t_end = 10.0;
  st = autobal_study_pendulum_transient(&pp, NULL, &o, ro, &s, &err);
  CHECK("pendulum transient into a read-only archive: a failure status", st < 0);
  CHECK("... with a message", err.message[0] != '\0');
  autobal_archive_close(ro, NULL);
  remove(path);
}

int main(void) {
  gsl_set_error_handler_off();
  test_fields();
  test_iso();
  test_transient();
  test_stability_and_pendulum();
  test_readonly_archive();
  return check_summary();
}
