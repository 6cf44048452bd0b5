/* embed_study.c: how a legacy C code embeds libautobal.
 *
 * The program has its own inputs: a rotor in SI units filled in code (no configuration file,
 * no `autobal` program).  It runs one rotor transient and one rotor stability analysis through
 * the study API (autobal/study.h), each into its own HDF5 archive, and handles every failure by
 * its status code.  The archives are those `autobal rotor transient|stability` write for the
 * same inputs (tests: examples/embed_study_check.sh), so `autobal info`, `autobal plot` and
 * h5py/xarray readers work on them.  A third run shows cancellation from the progress callback.
 *
 * usage: embed_study OUTDIR      writes OUTDIR/embed_transient.h5 and OUTDIR/embed_stability.h5
 * exit status: 0 success, 1 usage, 2 a library failure (message on stderr).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "autobal.h"

/* The legacy code's rotor: the housing (6 kg), the rotor (4 kg) on two supports, one balancer
 * plane 0.1 m from the centre of mass with two 50 g balls, a 30 g unbalance at 0.1 m, 400 rad/s. */
static const double ball_mass[2] = {0.05, 0.05};       /* kg */
static const double ball_radius[2] = {0.1, 0.1};       /* m */
static const double ball_damping[2] = {0.1, 0.1};      /* kg/s */
static const double ball_psi[2] = {1.0, 2.5};          /* rad, relative to the rotor */
static const double ball_rate[2] = {0.0, 0.0};         /* rad/s */

static autobal_rotor_params legacy_rotor(void) {
  autobal_rotor_params p;
  memset(&p, 0, sizeof p);
  p.input = AUTOBAL_ROTOR_HARDWARE;
  p.inertia = AUTOBAL_ROTOR_INERTIA_PAPER;
  p.hw.M_k = 6.0;   /* kg */
  p.hw.A_k = 0.12;  /* kg m^2 */
  p.hw.m_p = 4.0;   /* kg */
  p.hw.A_p = 0.04;  /* kg m^2 */
  p.hw.C_p = 0.03;  /* kg m^2 */
  p.hw.l_L = 0.20;  /* m */
  p.hw.l_R = 0.15;  /* m */
  p.hw.c_Lx = p.hw.c_Ly = 1e5;  /* N/m */
  p.hw.c_Lz = 2e5;
  p.hw.c_Rx = p.hw.c_Ry = 1.5e5;
  p.hw.h_Lx = p.hw.h_Ly = 100.0; /* N s/m */
  p.hw.h_Lz = 200.0;
  p.hw.h_Rx = p.hw.h_Ry = 150.0;
  p.omega = 400.0;  /* rad/s */
  p.axial = 0;
  p.n_planes = 1;
  p.plane[0].d = 0.1;     /* m */
  p.plane[0].m0 = 0.03;   /* kg */
  p.plane[0].r0 = 0.1;    /* m */
  p.plane[0].psi0 = 0.0;  /* rad */
  p.plane[0].n_balls = 2;
  p.plane[0].ball_mass = ball_mass;
  p.plane[0].ball_radius = ball_radius;
  p.plane[0].ball_damping = ball_damping;
  p.plane[0].ball_psi = ball_psi;
  p.plane[0].ball_rate = ball_rate;
  return p; /* q0, qd0, z0, zd0: 0 (memset) */
}

static int fail(const char *what, int status, const char *message) {
  fprintf(stderr, "embed_study: %s failed: %s (%s): %s\n", what, autobal_status_name(status), autobal_strerror(status),
          message);
  return 2;
}

/* Progress of the transient: counts the calls (a legacy code would update its own display). */
static int count_progress(double fraction, void *user) {
  unsigned long *calls = user;
  (*calls)++;
  return fraction > 1.0; /* never: no cancellation */
}
/* Progress that cancels the run half way. */
static int cancel_half_way(double fraction, void *user) {
  (void)user;
  return fraction >= 0.5;
}

static int open_archive(const char *dir, const char *name, const char *title, autobal_archive **a) {
  char path[4096];
  autobal_error err;
  const char *argv[1];
  int st;
  argv[0] = "embed_study";
  if (snprintf(path, sizeof path, "%s/%s", dir, name) >= (int)sizeof path) return fail("path", AUTOBAL_EINVAL, dir);
  autobal_error_clear(&err);
  st = autobal_archive_create(path, 1, a, &err);
  if (st) return fail("creating the archive", st, err.message);
  st = autobal_archive_provenance(*a, title, 1, argv);
  if (st) {
    int rc = fail("writing provenance", st, autobal_archive_errmsg(*a));
    autobal_archive_discard(*a);
    *a = NULL;
    return rc;
  }
  return 0;
}

/* Close: a failed study leaves its archive readable and marked incomplete. */
static int close_archive(autobal_archive *a, int study_status, const char *message) {
  autobal_error err;
  int st;
  if (study_status != AUTOBAL_SUCCESS) autobal_archive_set_status(a, "incomplete", message);
  autobal_error_clear(&err);
  st = autobal_archive_close(a, &err);
  return st ? fail("closing the archive", st, err.message) : 0;
}

static int run_transient(const char *dir, const autobal_rotor_params *p) {
  autobal_study_rotor_transient_options opt = autobal_study_rotor_transient_options_default();
  autobal_study_rotor_transient_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  unsigned long calls = 0;
  int st, rc;
  size_t i;
  opt.t_end = 1.0;      /* s */
  opt.dt_out = 0.002;   /* s */
  opt.grade = 6.3;      /* mm/s: check against ISO 21940-11 G6.3 */
  opt.progress = count_progress;
  opt.progress_user = &calls;
  autobal_error_clear(&err);
  /* check first: bad inputs leave no file behind */
  st = autobal_study_rotor_transient_check(p, &opt, &err);
  if (st < 0) return fail("rotor transient (inputs)", st, err.message);
  if (st == AUTOBAL_WARNING) fprintf(stderr, "embed_study: warning: %s\n", err.message);
  if ((rc = open_archive(dir, "embed_transient.h5", "embed_study: rotor transient", &a))) return rc;
  st = autobal_study_rotor_transient(p, &opt, a, &sum, &err);
  rc = close_archive(a, st, err.message);
  if (st) {
    autobal_study_rotor_transient_summary_free(&sum);
    return fail("rotor transient", st, err.message);
  }
  printf("transient: %.3g s, %s; |s|/(m0 r0) %.4g -> %.4g; residual unbalance %.4g g mm; grade G%.3g (within G%g), "
         "G6.3 %s; %lu steps, %lu progress calls\n",
         sum.t_reached, sum.balanced ? "balanced" : "not balanced", sum.residual_unbalance_initial,
         sum.residual_unbalance_final, sum.residual_unbalance_abs_final[0] * 1e6, sum.balance_grade_final,
         sum.balance_grade_class, sum.permissible_unbalance_met ? "met" : "not met", sum.solver.steps, calls);
  printf("  ball angles at the end (rad):");
  for (i = 0; i < sum.n_balls[0]; i++) printf(" %.5f", sum.ball_psi_final[0][i]);
  printf("\n");
  if (calls == 0) rc = fail("rotor transient", AUTOBAL_EINVAL, "the progress callback was never called");
  autobal_study_rotor_transient_summary_free(&sum);
  return rc;
}

static int run_cancelled(const autobal_rotor_params *p) {
  autobal_study_rotor_transient_options opt = autobal_study_rotor_transient_options_default();
  autobal_study_rotor_transient_summary sum;
  autobal_error err;
  int st;
  opt.t_end = 1.0;
  opt.progress = cancel_half_way;
  st = autobal_study_rotor_transient(p, &opt, NULL, &sum, &err); /* no archive */
  printf("cancelled transient: %s at t = %.4g s of %.4g s\n", autobal_status_name(st), sum.t_reached, opt.t_end);
  autobal_study_rotor_transient_summary_free(&sum);
  if (st != AUTOBAL_ECANCELLED) return fail("cancellation", st, "expected AUTOBAL_ECANCELLED");
  if (!(sum.t_reached >= 0.5 * opt.t_end && sum.t_reached < opt.t_end))
    return fail("cancellation", AUTOBAL_EINVAL, "stopped outside [t_end/2, t_end)");
  return 0;
}

static int run_stability(const char *dir, const autobal_rotor_params *p) {
  autobal_study_rotor_stability_options opt = autobal_study_rotor_stability_options_default();
  autobal_study_rotor_stability_summary sum;
  autobal_archive *a = NULL;
  autobal_error err;
  int st, rc;
  size_t i;
  autobal_error_clear(&err);
  st = autobal_study_rotor_stability(p, &opt, NULL, &sum, &err); /* analyse first, then write */
  if (st) {
    autobal_study_rotor_stability_summary_free(&sum);
    return fail("rotor stability", st, err.message);
  }
  if ((rc = open_archive(dir, "embed_stability.h5", "embed_study: rotor stability", &a))) {
    autobal_study_rotor_stability_summary_free(&sum);
    return rc;
  }
  st = autobal_study_rotor_stability_write(a, p, &opt, &sum);
  rc = close_archive(a, st, st ? autobal_archive_errmsg(a) : NULL);
  if (st) rc = fail("writing the stability archive", st, "see the archive's status_reason");
  printf("stability at %.6g rad/s: %s (method %s), margin %.6e 1/s; %zu critical speed(s):", p->omega,
         autobal_verdict_name(sum.result.verdict), autobal_rotor_stab_method_name(sum.result.method),
         sum.result.margin, sum.critical.n);
  for (i = 0; i < sum.critical.n; i++) printf(" %.6g", sum.critical.value[i]);
  printf(" rad/s\n");
  autobal_study_rotor_stability_summary_free(&sum);
  return rc;
}

int main(int argc, char **argv) {
  autobal_rotor_params p;
  int rc;
  if (argc != 2) {
    fprintf(stderr, "usage: embed_study OUTDIR\n");
    return 1;
  }
  gsl_set_error_handler_off(); /* the library reports GSL failures as statuses */
  p = legacy_rotor();
  if ((rc = run_transient(argv[1], &p))) return rc;
  if ((rc = run_stability(argv[1], &p))) return rc;
  if ((rc = run_cancelled(&p))) return rc;
  return 0;
}
