/* test_cancel.c: cancellation of the long studies (issue 19, item 2).  A progress callback that
 * asks to stop at its k-th call makes the study return AUTOBAL_ECANCELLED with the points done so
 * far; those must be bitwise the same as the same points of an uncancelled run (the blocks of
 * rows and the cancellation change nothing), the counts must be consistent, and the hooks below
 * the studies (autobal_rotor_stab_set_cancel, autobal_rotor_resonance_speeds_cancellable,
 * autobal_pendulum_workspace_set_cancel) must stop their loops and say so. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal/study.h"
#include "check.h"

/* Stop at the `stop_at`-th call (1-based); count the calls and check the fractions. */
typedef struct stopper {
  int calls, stop_at, bad_fraction;
  double last;
} stopper;

static int stop_cb(double fraction, void *user) {
  stopper *s = (stopper *)user;
  s->calls++;
  if (!(fraction >= 0.0 && fraction <= 1.0) || fraction < s->last) s->bad_fraction = 1;
  s->last = fraction;
  return s->calls >= s->stop_at;
}

static int always(void *user) {
  (*(int *)user)++;
  return 1;
}

static int same_doubles(const double *a, const double *b, size_t n) {
  size_t i;
  for (i = 0; i < n; i++)
    if (memcmp(&a[i], &b[i], sizeof a[i]) != 0) return 0; /* NaN == NaN bitwise */
  return 1;
}

static void rotor_map(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_map_options o = autobal_study_rotor_map_options_default();
  autobal_study_rotor_map_summary full, part;
  autobal_error err;
  stopper s = {0, 3, 0, 0.0};
  size_t nd;
  o.n1 = 400;
  o.n2 = 40;
  o.threads = 2;
  CHECK_STATUS("rotor map: complete", autobal_study_rotor_map(&p, &o, NULL, &full, &err), AUTOBAL_SUCCESS);
  CHECK("rotor map: complete n1_done = n1", full.n1_done == o.n1);
  o.progress = stop_cb;
  o.progress_user = &s;
  CHECK_STATUS("rotor map: cancelled at the 3rd progress call", autobal_study_rotor_map(&p, &o, NULL, &part, &err),
               AUTOBAL_ECANCELLED);
  nd = part.n1_done;
  printf("     %d progress calls, %zu of %zu rows done: %s\n", s.calls, nd, o.n1, err.message);
  CHECK("rotor map: 3 calls, fractions in [0, 1], non-decreasing", s.calls == 3 && !s.bad_fraction);
  CHECK("rotor map: 0 < n1_done < n1", nd > 0 && nd < o.n1);
  CHECK("rotor map: the progress fraction is n1_done/n1", fabs(s.last - (double)nd / (double)o.n1) < 1e-15);
  CHECK("rotor map: rows done bitwise as the complete run (margin)",
        nd > 0 && same_doubles(part.margin, full.margin, nd * o.n2));
  CHECK("rotor map: rows done as the complete run (verdict)",
        nd > 0 && memcmp(part.verdict, full.verdict, nd * o.n2 * sizeof *part.verdict) == 0);
  CHECK("rotor map: the message counts the rows", strstr(err.message, "rows") != NULL);
  autobal_study_rotor_map_summary_free(&full);
  autobal_study_rotor_map_summary_free(&part);
}

static void rotor_sweep(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_sweep_options o = autobal_study_rotor_sweep_options_default();
  autobal_study_rotor_sweep_summary full, part;
  autobal_error err;
  stopper s = {0, 5, 0, 0.0};
  o.n = 2000;
  o.min = 10.0;
  o.max = 2000.0;
  CHECK_STATUS("rotor sweep: complete", autobal_study_rotor_sweep(&p, &o, NULL, &full, &err), AUTOBAL_SUCCESS);
  CHECK("rotor sweep: complete n_done = n, not cancelled", full.n_done == o.n && !full.cancelled);
  o.progress = stop_cb;
  o.progress_user = &s;
  CHECK_STATUS("rotor sweep: cancelled at the 5th progress call", autobal_study_rotor_sweep(&p, &o, NULL, &part, &err),
               AUTOBAL_ECANCELLED);
  printf("     %zu of %zu points: %s\n", part.n_done, o.n, err.message);
  CHECK("rotor sweep: 5 chunks of 64 points done, cancelled = 1", part.n_done == 5 * 64 && part.cancelled);
  CHECK("rotor sweep: points done bitwise as the complete run",
        same_doubles(part.margin, full.margin, part.n_done) && same_doubles(part.values, full.values, part.n_done));
  CHECK("rotor sweep: no critical values after the cancellation", part.critical.n == 0 && part.critical.n_stable == 0);
  /* cancelled in the critical search (the second half): all points, no critical values */
  autobal_study_rotor_sweep_summary_free(&part); /* the summary is reused below */
  s.calls = 0, s.last = 0.0, s.stop_at = (int)((o.n + 63) / 64) + 1;
  CHECK_STATUS("rotor sweep: cancelled in the critical search", autobal_study_rotor_sweep(&p, &o, NULL, &part, &err),
               AUTOBAL_ECANCELLED);
  CHECK("rotor sweep: every point done, cancelled = 1", part.n_done == o.n && part.cancelled);
  CHECK("rotor sweep: the complete run found critical values, the cancelled one keeps none",
        full.critical.n > 0 && part.critical.n == 0);
  autobal_study_rotor_sweep_summary_free(&full);
  autobal_study_rotor_sweep_summary_free(&part);
}

static void rotor_stability_and_handle(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_stability_options o = autobal_study_rotor_stability_options_default();
  autobal_study_rotor_stability_summary full, part;
  autobal_error err;
  stopper s = {0, 50, 0, 0.0};
  autobal_rotor_stab *h;
  autobal_rotor_crit cr;
  double v[8], mg[8];
  int vd[8], n = 0, k;
  CHECK_STATUS("rotor stability: complete", autobal_study_rotor_stability(&p, &o, NULL, &full, &err), AUTOBAL_SUCCESS);
  o.progress = stop_cb;
  o.progress_user = &s;
  CHECK_STATUS("rotor stability: cancelled in the critical search",
               autobal_study_rotor_stability(&p, &o, NULL, &part, &err), AUTOBAL_ECANCELLED);
  CHECK("rotor stability: polled at every margin evaluation (50 calls)", s.calls == 50);
  CHECK("rotor stability: critical_cancelled = 1, have_critical = 0", part.critical_cancelled && !part.have_critical);
  CHECK("rotor stability: the analysis at omega as the complete run",
        part.result.verdict == full.result.verdict && memcmp(&part.result.margin, &full.result.margin, sizeof(double)) == 0);
  autobal_study_rotor_stability_summary_free(&full);
  autobal_study_rotor_stability_summary_free(&part);
  /* the handle's hook */
  h = autobal_rotor_stab_alloc(&p, NULL, &err);
  CHECK("rotor stab handle allocated", h != NULL);
  if (!h) return;
  autobal_rotor_stab_set_cancel(h, always, &n);
  for (k = 0; k < 8; k++) v[k] = 100.0 + 10.0 * k;
  CHECK_STATUS("autobal_rotor_stab_sweep with a cancelling hook", autobal_rotor_stab_sweep(h, 0, v, 8, mg, vd),
               AUTOBAL_ECANCELLED);
  CHECK_STATUS("autobal_rotor_stab_critical with a cancelling hook",
               autobal_rotor_stab_critical(h, 0, 10.0, 2000.0, 100, 1e-8, &cr), AUTOBAL_ECANCELLED);
  CHECK("the hook was called once per call, the message says cancelled",
        n == 2 && strstr(autobal_rotor_stab_errmsg(h), "cancelled") != NULL);
  CHECK("omega restored after the cancelled search", autobal_rotor_stab_get(h, 0) == p.omega);
  autobal_rotor_stab_set_cancel(h, NULL, NULL);
  CHECK_STATUS("no hook: the sweep runs", autobal_rotor_stab_sweep(h, 0, v, 8, mg, vd), AUTOBAL_SUCCESS);
  autobal_rotor_stab_free(h);
}

static void rotor_campbell(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_study_rotor_campbell_options o = autobal_study_rotor_campbell_options_default();
  autobal_study_rotor_campbell_summary full, part;
  autobal_rotor_resonances rr;
  autobal_error err;
  stopper s = {0, 4, 0, 0.0};
  size_t nd;
  int n = 0;
  o.n = 3000;
  CHECK_STATUS("rotor campbell: complete", autobal_study_rotor_campbell(&p, &o, NULL, &full, &err), AUTOBAL_SUCCESS);
  CHECK("rotor campbell: complete n_done = n, have_resonances", full.n_done == o.n && full.have_resonances);
  o.progress = stop_cb;
  o.progress_user = &s;
  CHECK_STATUS("rotor campbell: cancelled at the 4th call", autobal_study_rotor_campbell(&p, &o, NULL, &part, &err),
               AUTOBAL_ECANCELLED);
  nd = part.n_done;
  printf("     %zu of %zu speeds: %s\n", nd, o.n, err.message);
  CHECK("rotor campbell: 0 < n_done < n, no resonances", nd > 0 && nd < o.n && !part.have_resonances &&
                                                              part.resonances.n_cross == 0);
  CHECK("rotor campbell: speeds done bitwise as the complete run",
        same_doubles(part.frequency, full.frequency, 4 * nd) && same_doubles(part.amp_G, full.amp_G, nd) &&
            memcmp(part.whirl, full.whirl, 4 * nd * sizeof *part.whirl) == 0);
  autobal_study_rotor_campbell_summary_free(&full);
  autobal_study_rotor_campbell_summary_free(&part);
  CHECK_STATUS("autobal_rotor_resonance_speeds_cancellable with a cancelling hook",
               autobal_rotor_resonance_speeds_cancellable(&p, 0.0, 3000.0, 1000, 1e-10, always, &n, &rr, &err),
               AUTOBAL_ECANCELLED);
  CHECK("... stopped before the first grid point", n == 1 && rr.n_cross == 0 && rr.n_peak == 0);
}

static void pendulum(void) {
  autobal_pendulum_params pp = {3.0, 0.1, 0.1, 0.5, 0.3};
  autobal_study_pendulum_map_options o = autobal_study_pendulum_map_options_default();
  autobal_study_pendulum_map_summary full, part;
  autobal_study_pendulum_critical_options co = autobal_study_pendulum_critical_options_default();
  autobal_study_pendulum_critical_summary cf, cp;
  autobal_pendulum_workspace *ws;
  autobal_pendulum_crit_set set;
  autobal_error err;
  stopper s = {0, 2, 0, 0.0};
  double rm[4] = {0.1, 0.2, 0.3, 0.4}, rw[12];
  size_t nd;
  int n = 0;
  o.n_Rm = 3000;
  o.n_Rw = 100;
  o.max_real = 1;
  CHECK_STATUS("pendulum map: complete", autobal_study_pendulum_map(&pp, NULL, &o, NULL, &full, &err), AUTOBAL_SUCCESS);
  o.progress = stop_cb;
  o.progress_user = &s;
  CHECK_STATUS("pendulum map: cancelled at the 2nd call", autobal_study_pendulum_map(&pp, NULL, &o, NULL, &part, &err),
               AUTOBAL_ECANCELLED);
  nd = part.n_Rm_done;
  printf("     %zu of %zu rows: %s\n", nd, o.n_Rm, err.message);
  CHECK("pendulum map: 0 < n_Rm_done < n_Rm", nd > 0 && nd < o.n_Rm);
  CHECK("pendulum map: rows done bitwise as the complete run",
        memcmp(part.verdict, full.verdict, nd * o.n_Rw * sizeof *part.verdict) == 0 &&
            same_doubles(part.max_real, full.max_real, nd * o.n_Rw));
  autobal_study_pendulum_map_summary_free(&full);
  autobal_study_pendulum_map_summary_free(&part);
  /* critical: cancelled in the curves (the damped search polls too: stop late enough) */
  co.n_Rm = 2000;
  CHECK_STATUS("pendulum critical: complete", autobal_study_pendulum_critical(&pp, NULL, &co, NULL, &cf, &err),
               AUTOBAL_SUCCESS);
  co.progress = stop_cb;
  co.progress_user = &s;
  s.calls = 0, s.last = 0.0, s.stop_at = (int)co.n_sweep + 200;
  CHECK_STATUS("pendulum critical: cancelled in the curves",
               autobal_study_pendulum_critical(&pp, NULL, &co, NULL, &cp, &err), AUTOBAL_ECANCELLED);
  nd = cp.n_Rm_done;
  printf("     %zu of %zu curve points, damped search %s: %s\n", nd, co.n_Rm, cp.have_damped ? "done" : "not done",
         err.message);
  CHECK("pendulum critical: damped search done, 0 < n_Rm_done < n_Rm, fractions ok",
        cp.have_damped && !cp.damped_cancelled && nd > 0 && nd < co.n_Rm && !s.bad_fraction);
  CHECK("pendulum critical: curve points done bitwise as the complete run",
        same_doubles(cp.R_w_k0, cf.R_w_k0, 3 * nd) && same_doubles(cp.R_w_k1, cf.R_w_k1, 3 * nd));
  /* cancelled at the first poll of the curves: no curve point, the archive still says partial */
  autobal_study_pendulum_critical_summary_free(&cp); /* the summary is reused below */
  s.calls = 0, s.last = 0.0, s.stop_at = (int)co.n_sweep;
  CHECK_STATUS("pendulum critical: cancelled at the first point of the curves",
               autobal_study_pendulum_critical(&pp, NULL, &co, NULL, &cp, &err), AUTOBAL_ECANCELLED);
  CHECK("pendulum critical: cancelled = 1, damped search done, n_Rm_done = 0",
        cp.cancelled && cp.have_damped && !cp.damped_cancelled && cp.n_Rm_done == 0);
  {
    char path[1024];
    autobal_archive *a = NULL;
    double v = 0.0;
    snprintf(path, sizeof path, "%s/test_cancel_pcrit.h5", AUTOBAL_TEST_TMP_DIR);
    CHECK_STATUS("archive created", autobal_archive_create(path, 1, &a, &err), AUTOBAL_SUCCESS);
    if (a) {
      CHECK_STATUS("the partial summary written",
                   autobal_study_pendulum_critical_write(a, &pp, NULL, &cp), AUTOBAL_SUCCESS);
      CHECK_STATUS("closed", autobal_archive_close(a, &err), AUTOBAL_SUCCESS);
    }
    a = NULL;
    CHECK_STATUS("reopened", autobal_archive_open_read(path, &a, &err), AUTOBAL_SUCCESS);
    if (a) {
      CHECK("partial = 1 on /pendulum/critical",
            autobal_archive_read_attr_double(a, "/pendulum/critical", "partial", &v) == AUTOBAL_SUCCESS && v == 1.0);
      CHECK("done = 0", autobal_archive_read_attr_double(a, "/pendulum/critical", "done", &v) == AUTOBAL_SUCCESS &&
                            v == 0.0);
      CHECK("no curves group, the damped set written",
            !autobal_archive_has(a, "/pendulum/critical/curves", NULL) &&
                autobal_archive_has(a, "/pendulum/critical/damped_R_w", NULL));
      autobal_archive_close(a, NULL);
    }
  }
  autobal_study_pendulum_critical_summary_free(&cp); /* reused below */
  s.calls = 0, s.last = 0.0, s.stop_at = 10;
  CHECK_STATUS("pendulum critical: cancelled in the damped search",
               autobal_study_pendulum_critical(&pp, NULL, &co, NULL, &cp, &err), AUTOBAL_ECANCELLED);
  CHECK("pendulum critical: damped_cancelled, no damped set, no curve point",
        cp.damped_cancelled && cp.cancelled && !cp.have_damped && cp.n_Rm_done == 0);
  autobal_study_pendulum_critical_summary_free(&cf);
  autobal_study_pendulum_critical_summary_free(&cp);
  ws = autobal_pendulum_workspace_alloc();
  CHECK("pendulum workspace allocated", ws != NULL);
  if (!ws) return;
  autobal_pendulum_workspace_set_cancel(ws, always, &n);
  CHECK_STATUS("autobal_pendulum_critical_curves with a cancelling hook",
               autobal_pendulum_critical_curves(ws, 0.0, rm, 4, 3, rw), AUTOBAL_ECANCELLED);
  CHECK_STATUS("autobal_pendulum_critical_speeds_damped with a cancelling hook",
               autobal_pendulum_critical_speeds_damped(ws, &pp, 0.0, 6.0, 1000, &set), AUTOBAL_ECANCELLED);
  CHECK("the hook was called once per call, the message says cancelled",
        n == 2 && strstr(autobal_pendulum_errmsg(ws), "cancelled") != NULL && set.n == 0);
  autobal_pendulum_workspace_free(ws);
}

int main(void) {
  rotor_map();
  rotor_sweep();
  rotor_stability_and_handle();
  rotor_campbell();
  pendulum();
  return check_summary();
}
