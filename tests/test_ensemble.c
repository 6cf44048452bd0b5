/* test_ensemble.c: the ensemble engine (include/autobal/ensemble.h) through the library alone, as
 * an embedding C code runs it.  A small rotor ensemble (initial angles of the two balls) and a
 * small pendulum ensemble (initial angles psi, phi):
 *  - a member against a single autobal_transient run of the same member written here from the
 *    model's own API (bit for bit: status, time to balance, time reached, steps, residuals,
 *    amplitudes, final angles);
 *  - P(balance) against the fraction of balanced members among those single runs, one per member;
 *  - the rotor map's psi_1 <-> psi_2 symmetry (the two balls are identical);
 *  - 1 thread vs 2 threads, bit for bit;
 *  - resume from a journal (also with its last record torn) vs an uninterrupted run, bit for bit;
 *    a journal of other settings refused;
 *  - two "processes" dealt by the `mine` hook and joined by the gather hook vs one;
 *  - the cancel hook; the archive read back; bad settings rejected with the parameter named;
 *  - a third model defined here (y' = -lambda y): time to balance in closed form, a failing
 *    right-hand side recorded as a member's status; journal errors;
 *  - statistics: the Wilson interval against Newcombe's (1998) published values and its closed
 *    forms at k = 0, k = n; type-7 quantiles by hand; a member quantity's quantiles, mean and
 *    target over a grid whose values are known (a failed member left out); bad targets. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "autobal.h"
#include "check.h"

#define TWO_PI 6.283185307179586476925286766559
#define PI_ 3.1415926535897932384626433832795

static int same_doubles(const double *a, const double *b, size_t n) { return memcmp(a, b, n * sizeof *a) == 0; }

/* Every member's summary of two ensembles equal bit for bit (both done or both not). */
static int same_ensembles(const autobal_ensemble *a, const autobal_ensemble *b, size_t ncols) {
  size_t m, n = autobal_ensemble_n_members(a), len = autobal_ensemble_summary_length(a);
  if (n != autobal_ensemble_n_members(b) || len != autobal_ensemble_summary_length(b)) return 0;
  for (m = 0; m < n; m++) {
    const double *x = autobal_ensemble_summary(a, m), *y = autobal_ensemble_summary(b, m);
    size_t na, nb;
    const double *ta, *ra, *tb, *rb;
    if (!x || !y || !same_doubles(x, y, len)) return 0;
    autobal_ensemble_series(a, m, &na, &ta, &ra);
    autobal_ensemble_series(b, m, &nb, &tb, &rb);
    if (na != nb || (na && (!same_doubles(ta, tb, na) || !same_doubles(ra, rb, na * ncols)))) return 0;
  }
  return 1;
}

/* ---- single runs written from the models' own API ------------------------------------------ */
typedef struct single {
  double status, balanced, ttb, res0, res1, amp_max, amp1, t_reached, steps, rhs, angles[8];
} single;

typedef struct rotor_obs {
  autobal_rotor *rot;
  int frame;
  double out[64];
  size_t nout;
  double amp_max;
} rotor_obs;

static int rotor_observer(double t, const double y[], void *user) {
  rotor_obs *o = user;
  if (autobal_rotor_outputs(o->rot, o->frame, t, y, o->out, o->nout) != AUTOBAL_SUCCESS) return 1;
  if (o->out[0] > o->amp_max) o->amp_max = o->out[0];
  return 0;
}

static double rotor_monitor(double t, const double y[], void *user) {
  rotor_obs *o = user;
  return autobal_rotor_balance_monitor(o->rot, o->frame, t, y);
}

/* The rotor with ball angles psi[2] for t_end s: output every revs_out revolutions, balanced when
 * the monitor stays below tol for revs revolutions, stop there. */
static single rotor_single(const autobal_ensemble_settings *s, const double psi[2]) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_transient_options opt = s->transient;
  autobal_transient_system sys;
  autobal_transient_stats st;
  autobal_transient_event_hit hit;
  autobal_transient *tr;
  rotor_obs o;
  single r;
  double y[64], rev, t_reached = 0;
  size_t dim, i;
  int ev;
  memset(&r, 0, sizeof r);
  memset(&o, 0, sizeof o);
  p.plane[0].ball_psi = psi;
  o.rot = autobal_rotor_alloc(&p, NULL);
  o.frame = AUTOBAL_ROTOR_FIXED;
  o.nout = autobal_rotor_output_count(o.rot);
  dim = autobal_rotor_dim(o.rot);
  autobal_rotor_initial_state(o.rot, o.frame, 0.0, y, dim);
  rev = TWO_PI / fabs(p.omega);
  opt.dt_out = s->revs_out * rev;
  opt.event_tol = 1e-9 * s->t_end;
  tr = autobal_transient_alloc(dim, &opt, NULL);
  autobal_transient_set_observer(tr, rotor_observer, &o);
  ev = autobal_transient_add_dwell_event(tr, rotor_monitor, &o, s->balance_tol, s->balance_revs * rev, 1);
  r.res0 = rotor_monitor(0.0, y, &o);
  sys.rhs = autobal_rotor_rhs, sys.jac = NULL, sys.dim = dim, sys.params = o.rot;
  r.status = autobal_transient_run(tr, &sys, 0.0, s->t_end, y, &t_reached);
  autobal_transient_get_stats(tr, &st);
  r.t_reached = t_reached, r.steps = (double)st.steps, r.rhs = (double)st.rhs_evals;
  r.ttb = NAN;
  if (autobal_transient_event_result(tr, (size_t)ev, NULL, &hit) == 1) r.balanced = 1, r.ttb = hit.t_start;
  r.res1 = rotor_monitor(t_reached, y, &o);
  autobal_rotor_outputs(o.rot, o.frame, t_reached, y, o.out, o.nout);
  r.amp1 = o.out[0];
  r.amp_max = o.amp_max > r.amp1 ? o.amp_max : r.amp1;
  for (i = 0; i < 2; i++) r.angles[i] = remainder(y[8 + i] - p.omega * t_reached, TWO_PI);
  autobal_transient_free(tr);
  autobal_rotor_free(o.rot);
  return r;
}

typedef struct pend_obs {
  autobal_pendulum_params p;
  double amp_max;
} pend_obs;

static int pend_observer(double t, const double y[], void *user) {
  pend_obs *o = user;
  autobal_pendulum_motion_derived d;
  (void)t;
  autobal_pendulum_motion_derive(&o->p, y, &d);
  if (d.amplitude > o->amp_max) o->amp_max = d.amplitude;
  return 0;
}

static single pend_single(const autobal_ensemble_settings *s, const autobal_pendulum_params *pp, double psi, double phi) {
  autobal_transient_options opt = s->transient;
  autobal_transient_system sys;
  autobal_transient_stats st;
  autobal_transient_event_hit hit;
  autobal_pendulum_motion mo;
  autobal_pendulum_motion_derived d;
  autobal_transient *tr;
  pend_obs o;
  single r;
  double y[8] = {0, 0, 0, 0, 0, 0, 0, 0}, rev, t_reached = 0;
  int ev;
  memset(&r, 0, sizeof r);
  y[2] = psi, y[3] = phi;
  autobal_pendulum_motion_init(&mo, pp, NULL);
  o.p = mo.p, o.amp_max = 0;
  rev = TWO_PI / fabs(pp->R_w);
  opt.dt_out = s->revs_out * rev;
  opt.event_tol = 1e-9 * s->t_end;
  tr = autobal_transient_alloc(8, &opt, NULL);
  autobal_transient_set_observer(tr, pend_observer, &o);
  ev = autobal_transient_add_dwell_event(tr, autobal_pendulum_unbalance_scalar, &mo.p, s->balance_tol, s->balance_revs * rev, 1);
  r.res0 = autobal_pendulum_residual_unbalance(&mo.p, y, NULL, NULL);
  sys.rhs = autobal_pendulum_motion_rhs, sys.jac = autobal_pendulum_motion_jac, sys.dim = 8, sys.params = &mo;
  r.status = autobal_transient_run(tr, &sys, 0.0, s->t_end, y, &t_reached);
  autobal_transient_get_stats(tr, &st);
  r.t_reached = t_reached, r.steps = (double)st.steps, r.rhs = (double)st.rhs_evals;
  r.ttb = NAN;
  if (autobal_transient_event_result(tr, (size_t)ev, NULL, &hit) == 1) r.balanced = 1, r.ttb = hit.t_start;
  autobal_pendulum_motion_derive(&mo.p, y, &d);
  r.res1 = d.unbalance, r.amp1 = d.amplitude;
  r.amp_max = o.amp_max > r.amp1 ? o.amp_max : r.amp1;
  r.angles[0] = d.alpha, r.angles[1] = d.beta;
  autobal_transient_free(tr);
  return r;
}

/* A member's summary against a single run, bit for bit. */
static void check_member(const char *what, const double *sum, const single *r, size_t nang) {
  char buf[160];
  double want[AUTOBAL_ENSEMBLE_ANGLES + 8];
  size_t i;
  want[AUTOBAL_ENSEMBLE_STATUS] = r->status;
  want[AUTOBAL_ENSEMBLE_BALANCED] = r->balanced;
  want[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE] = r->ttb;
  want[AUTOBAL_ENSEMBLE_RESIDUAL_INITIAL] = r->res0;
  want[AUTOBAL_ENSEMBLE_RESIDUAL_FINAL] = r->res1;
  want[AUTOBAL_ENSEMBLE_AMPLITUDE_MAX] = r->amp_max;
  want[AUTOBAL_ENSEMBLE_AMPLITUDE_FINAL] = r->amp1;
  want[AUTOBAL_ENSEMBLE_T_REACHED] = r->t_reached;
  want[AUTOBAL_ENSEMBLE_STEPS] = r->steps;
  want[AUTOBAL_ENSEMBLE_RHS_EVALS] = r->rhs;
  for (i = 0; i < nang; i++) want[AUTOBAL_ENSEMBLE_ANGLES + i] = r->angles[i];
  for (i = 0; i < AUTOBAL_ENSEMBLE_ANGLES + nang; i++) {
    int ok = sum && (memcmp(&sum[i], &want[i], sizeof want[i]) == 0 || (isnan(sum[i]) && isnan(want[i])));
    snprintf(buf, sizeof buf, "%s: summary[%zu] = %.17g, single run %.17g (bit for bit)", what, i, sum ? sum[i] : NAN, want[i]);
    CHECK(buf, ok);
  }
}

/* ---- hooks ------------------------------------------------------------------------------------- */
typedef struct deal {
  int rank, size;
  double *records;
  size_t n;
} deal;

static int deal_mine(void *user, size_t k, size_t member) {
  const deal *d = user;
  (void)member;
  return (int)(k % (size_t)d->size) == d->rank;
}

static int deal_gather(void *user, autobal_ensemble *e, int status, const double *records, size_t n) {
  deal *d = user;
  (void)e;
  d->records = malloc((n ? n : 1) * sizeof *records);
  if (!d->records) return AUTOBAL_ENOMEM;
  if (n) memcpy(d->records, records, n * sizeof *records);
  d->n = n;
  return status;
}

typedef struct counter {
  int calls, after;
} counter;

static int cancel_after(void *user) {
  counter *c = user;
  int stop;
#ifdef _OPENMP
#pragma omp atomic capture
#endif
  stop = c->calls++;
  return stop >= c->after;
}

static void progress_count(double fraction, void *user) {
  double *last = user;
  if (fraction > *last) *last = fraction;
}

/* ---- the rotor ------------------------------------------------------------------------------------ */
static autobal_ensemble_settings rotor_settings(void) {
  autobal_ensemble_settings s = autobal_ensemble_settings_default();
  s.n_params = 2;
  s.param[0].name = "psi_1", s.param[0].min = -PI_, s.param[0].max = PI_, s.param[0].n = 3;
  s.param[1].name = "psi_2", s.param[1].min = -PI_, s.param[1].max = PI_, s.param[1].n = 3;
  s.t_end = 10.0;
  return s;
}

static void test_rotor(void) {
  autobal_rotor_params p = autobal_rotor_params_default();
  autobal_ensemble_member mb;
  autobal_ensemble_settings s = rotor_settings();
  autobal_ensemble *e1, *e2, *er;
  autobal_ensemble_tally t;
  autobal_error err;
  size_t keep[2] = {5, 1}, m, n, balanced = 0, i, j;
  char out[512], jpath[600];
  int st;
  double last = 0;
  counter cc;

  printf("# rotor ensemble: psi_1 x psi_2, 3 x 3 over [-pi, pi), t_end %g s\n", s.t_end);
  CHECK_STATUS("rotor member", autobal_ensemble_rotor_member(&p, AUTOBAL_ROTOR_FIXED, "fixed", &mb, &err), AUTOBAL_SUCCESS);
  s.series = keep, s.n_series = 2;
  s.threads = 1;
  e1 = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK("alloc (1 thread)", e1 != NULL);
  if (!e1) {
    printf("  %s\n", err.message);
    return;
  }
  n = autobal_ensemble_n_members(e1);
  CHECK("9 members", n == 9);
  autobal_ensemble_set_progress(e1, progress_count, &last);
  CHECK_STATUS("run (1 thread)", autobal_ensemble_run(e1), AUTOBAL_SUCCESS);
  CHECK("progress reached 1", last == 1.0);
  CHECK("computed 9", autobal_ensemble_computed(e1) == 9);

  /* every member against a single run: P(balance) from the single runs */
  for (m = 0; m < n; m++) {
    double psi[2];
    single r;
    char what[64];
    psi[0] = autobal_ensemble_member_value(e1, m, 0);
    psi[1] = autobal_ensemble_member_value(e1, m, 1);
    CHECK("grid value (row-major, no endpoint)", psi[0] == -PI_ + TWO_PI * (double)(m / 3) / 3.0 &&
                                                    psi[1] == -PI_ + TWO_PI * (double)(m % 3) / 3.0);
    r = rotor_single(&s, psi);
    snprintf(what, sizeof what, "rotor member %zu (psi %.4f, %.4f)", m, psi[0], psi[1]);
    check_member(what, autobal_ensemble_summary(e1, m), &r, 2);
    if (r.balanced == 1 && r.status >= 0) balanced++;
  }
  CHECK_STATUS("tally", autobal_ensemble_get_tally(e1, &t), AUTOBAL_SUCCESS);
  printf("  P(balance) = %zu/%zu = %.4f\n", t.n_balanced, t.n_ok, t.p);
  CHECK("P(balance) equals the single runs' fraction", t.n_failed == 0 && t.n_ok == 9 && t.n_balanced == balanced &&
                                                         t.p == (double)balanced / 9.0);
  CHECK("both outcomes occur (the comparison means something)", balanced > 0 && balanced < 9);
  /* identical balls: member (i, j) and (j, i) balance alike, in the same time within 1e-6 s */
  for (i = 0; i < 3; i++)
    for (j = i + 1; j < 3; j++) {
      const double *a = autobal_ensemble_summary(e1, i * 3 + j), *b = autobal_ensemble_summary(e1, j * 3 + i);
      CHECK("psi_1 <-> psi_2 symmetry: balanced alike", a[AUTOBAL_ENSEMBLE_BALANCED] == b[AUTOBAL_ENSEMBLE_BALANCED]);
      if (a[AUTOBAL_ENSEMBLE_BALANCED] == 1)
        CHECK_CLOSE("psi_1 <-> psi_2 symmetry: time to balance", a[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE],
                    b[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE], 0, 1e-6);
    }
  {
    size_t nr;
    const double *tt, *rows;
    autobal_ensemble_series(e1, 5, &nr, &tt, &rows);
    CHECK("kept series of member 5 has rows from t = 0", nr > 2 && tt[0] == 0.0);
    autobal_ensemble_series(e1, 4, &nr, &tt, &rows);
    CHECK("member 4 keeps no series", nr == 0);
  }

  /* 2 threads: bit for bit */
  s.threads = 2;
  e2 = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK_STATUS("run (2 threads)", e2 ? autobal_ensemble_run(e2) : err.status, AUTOBAL_SUCCESS);
  CHECK("2 threads == 1 thread, bit for bit (summaries and series)", e2 && same_ensembles(e1, e2, mb.n_columns));
  autobal_ensemble_free(e2);

  /* resume: 4 members, then the rest after the journal's last record was torn */
  snprintf(out, sizeof out, "%s/test_ensemble_rotor.h5", AUTOBAL_TEST_TMP_DIR);
  snprintf(jpath, sizeof jpath, "%s.journal-0", out);
  autobal_ensemble_journals_remove(out, NULL);
  s.threads = 2;
  s.max_members = 4;
  er = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK_STATUS("journal open", autobal_ensemble_journal_open(er, out, 0), AUTOBAL_SUCCESS);
  CHECK_STATUS("run 4 members", autobal_ensemble_run(er), AUTOBAL_SUCCESS);
  CHECK("4 done", autobal_ensemble_n_done(er) == 4);
  autobal_ensemble_free(er);
  {
    FILE *f = fopen(jpath, "rb");
    long size = -1;
    if (f && fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    if (f) fclose(f);
    CHECK("journal written", size > 48);
    CHECK("journal torn by 100 bytes", size > 148 && truncate(jpath, size - 100) == 0);
  }
  {
    autobal_ensemble_settings other = s;
    autobal_ensemble *eo;
    other.t_end = 5.0;
    eo = autobal_ensemble_alloc(&mb, &other, &err);
    st = autobal_ensemble_resume(eo, out, 0);
    CHECK_STATUS("resume with other settings refused", st, AUTOBAL_ECONFIG);
    CHECK_MSG("resume with other settings", autobal_ensemble_errmsg(eo), "different configuration");
    autobal_ensemble_free(eo);
  }
  s.max_members = 0;
  s.threads = 1;
  er = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK_STATUS("resume", autobal_ensemble_resume(er, out, 0), AUTOBAL_SUCCESS);
  CHECK("3 members read back (the torn 4th dropped)", autobal_ensemble_n_done(er) == 3);
  CHECK_STATUS("journal reopened", autobal_ensemble_journal_open(er, out, 0), AUTOBAL_SUCCESS);
  CHECK_STATUS("run the rest", autobal_ensemble_run(er), AUTOBAL_SUCCESS);
  CHECK("6 computed now", autobal_ensemble_computed(er) == 6);
  CHECK("resumed == uninterrupted, bit for bit", same_ensembles(e1, er, mb.n_columns));
  /* the archive */
  {
    autobal_archive *a = NULL, *r = NULL;
    autobal_ensemble_execution ex = {1, 1, 0.0, 0};
    double v = NAN, ttb[9];
    st = autobal_archive_create(out, 1, &a, &err);
    if (st == AUTOBAL_SUCCESS) st = autobal_ensemble_write(er, a, NULL, NULL, &ex);
    CHECK_STATUS("archive written", st, AUTOBAL_SUCCESS);
    if (a) autobal_archive_close(a, NULL);
    CHECK_STATUS("archive read", autobal_archive_open_read(out, &r, NULL), AUTOBAL_SUCCESS);
    if (r) {
      autobal_archive_read_attr_double(r, "/rotor/ensemble", "probability_balanced", &v);
      CHECK("archive: probability_balanced", v == t.p);
      autobal_archive_read_var(r, "/rotor/ensemble/time_to_balance", ttb, 9);
      for (m = 0; m < 9; m++) {
        const double *x = autobal_ensemble_summary(e1, m);
        CHECK("archive: time_to_balance", memcmp(&ttb[m], &x[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE], sizeof v) == 0 ||
                                              (isnan(ttb[m]) && isnan(x[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE])));
      }
      CHECK("archive: series/member_5", autobal_archive_has(r, "/rotor/ensemble/series/member_5", NULL) == 1);
      autobal_archive_close(r, NULL);
    }
  }
  autobal_ensemble_free(er);
  autobal_ensemble_journals_remove(out, NULL);
  remove(out);

  /* two "processes": the mine hook deals, the gather hook collects, rank 0 adds rank 1's records */
  {
    deal d0 = {0, 2, NULL, 0}, d1 = {1, 2, NULL, 0};
    autobal_ensemble_parallel p0, p1;
    autobal_ensemble *a0 = autobal_ensemble_alloc(&mb, &s, &err), *a1 = autobal_ensemble_alloc(&mb, &s, &err);
    memset(&p0, 0, sizeof p0);
    p0.mine = deal_mine, p0.gather = deal_gather, p0.user = &d0, p0.results = 1;
    p1 = p0;
    p1.user = &d1, p1.results = 0;
    autobal_ensemble_set_parallel(a0, &p0);
    autobal_ensemble_set_parallel(a1, &p1);
    CHECK_STATUS("rank 1 runs", autobal_ensemble_run(a1), AUTOBAL_SUCCESS);
    CHECK_STATUS("rank 0 runs", autobal_ensemble_run(a0), AUTOBAL_SUCCESS);
    CHECK("rank 0 ran members 0, 2, 4, 6, 8; rank 1 the others", autobal_ensemble_computed(a0) == 5 &&
                                                                     autobal_ensemble_computed(a1) == 4);
    CHECK("rank 1 keeps no results", autobal_ensemble_summary(a1, 1) == NULL && autobal_ensemble_is_done(a1, 1));
    CHECK_STATUS("rank 0 adds rank 1's records", autobal_ensemble_add_records(a0, d1.records, d1.n), AUTOBAL_SUCCESS);
    CHECK("2 ranks == 1 rank, bit for bit", same_ensembles(e1, a0, mb.n_columns));
    if (d1.n > 10) {
      d1.records[d1.n - 1] = -1; /* a damaged record */
      autobal_ensemble_free(a0);
      a0 = autobal_ensemble_alloc(&mb, &s, &err);
      CHECK_STATUS("a damaged record", autobal_ensemble_add_records(a0, d1.records, d1.n), AUTOBAL_EFORMAT);
    }
    free(d0.records), free(d1.records);
    autobal_ensemble_free(a0);
    autobal_ensemble_free(a1);
  }

  /* cancel: polled during the transients; members cancelled are not recorded */
  cc.calls = 0, cc.after = 500;
  er = autobal_ensemble_alloc(&mb, &s, &err);
  autobal_ensemble_set_cancel(er, cancel_after, &cc);
  CHECK_STATUS("cancelled", autobal_ensemble_run(er), AUTOBAL_ECANCELLED);
  printf("  cancelled after %d polls: %zu members done\n", cc.after, autobal_ensemble_n_done(er));
  CHECK("some members done, not all", autobal_ensemble_n_done(er) > 0 && autobal_ensemble_n_done(er) < 9);
  for (m = 0; m < 9; m++)
    if (autobal_ensemble_is_done(er, m))
      CHECK("a member done before the cancel is the uninterrupted one",
            same_doubles(autobal_ensemble_summary(er, m), autobal_ensemble_summary(e1, m), autobal_ensemble_summary_length(er)));
  autobal_ensemble_set_cancel(er, NULL, NULL);
  CHECK_STATUS("run again completes", autobal_ensemble_run(er), AUTOBAL_SUCCESS);
  CHECK("completed == uninterrupted", same_ensembles(e1, er, mb.n_columns));
  autobal_ensemble_free(er);

  /* bad settings: the parameter is named */
  {
    autobal_ensemble_settings b = rotor_settings();
    size_t bad = 9;
    b.param[1].name = "psi_3";
    CHECK("ball 3 of 2 rejected", autobal_ensemble_alloc(&mb, &b, &err) == NULL && err.status == AUTOBAL_EINVAL);
    CHECK_MSG("ball 3", err.message, "ball 3 does not exist");
    b = rotor_settings();
    b.param[1].name = "psi_1";
    CHECK("a parameter twice rejected", autobal_ensemble_alloc(&mb, &b, &err) == NULL);
    CHECK_MSG("twice", err.message, "already");
    b = rotor_settings();
    b.series = &bad, b.n_series = 1;
    CHECK("series member 9 of 9 rejected", autobal_ensemble_alloc(&mb, &b, &err) == NULL);
    CHECK_MSG("series", err.message, "series member 9");
    b = rotor_settings();
    b.t_end = -1;
    CHECK("t_end < 0 rejected", autobal_ensemble_alloc(&mb, &b, &err) == NULL);
    CHECK_MSG("t_end", err.message, "t_end");
    b = rotor_settings();
    b.param[0].n = 0;
    CHECK("n = 0 rejected", autobal_ensemble_alloc(&mb, &b, &err) == NULL);
    CHECK_MSG("n", err.message, "grid points");
  }
  autobal_ensemble_free(e1);
  autobal_ensemble_member_release(&mb);
  autobal_ensemble_member_release(&mb); /* a zeroed member is safe */
  autobal_ensemble_free(NULL);
}

/* ---- the pendulum ---------------------------------------------------------------------------------- */
static void test_pendulum(void) {
  autobal_pendulum_params pp;
  autobal_ensemble_member mb;
  autobal_ensemble_settings s = autobal_ensemble_settings_default();
  autobal_ensemble *e1, *e2;
  autobal_ensemble_tally t;
  autobal_error err;
  double y0[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  size_t m, balanced = 0;

  pp.R_w = 3.0, pp.R_m = 0.1, pp.H = 0.1, pp.h = 0.5, pp.psi0 = 0.4;
  printf("# pendulum ensemble: psi x phi, 3 x 3 over [0.1, 0.7], psi0 = 0.4, t_end 125\n");
  CHECK_STATUS("pendulum member", autobal_ensemble_pendulum_member(&pp, y0, &mb, &err), AUTOBAL_SUCCESS);
  if (err.status) printf("  %s\n", err.message);
  s.n_params = 2;
  s.param[0].name = "psi", s.param[0].min = 0.1, s.param[0].max = 0.7, s.param[0].n = 3;
  s.param[1].name = "phi", s.param[1].min = 0.1, s.param[1].max = 0.7, s.param[1].n = 3;
  s.endpoint = 1;
  s.t_end = 125;
  s.transient.atol = 1e-12;
  s.balance_tol = 1e-3;
  s.balance_revs = 20;
  s.threads = 1;
  e1 = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK("alloc", e1 != NULL);
  if (!e1) {
    printf("  %s\n", err.message);
    autobal_ensemble_member_release(&mb);
    return;
  }
  CHECK_STATUS("run (1 thread)", autobal_ensemble_run(e1), AUTOBAL_SUCCESS);
  for (m = 0; m < 9; m++) {
    double psi = autobal_ensemble_member_value(e1, m, 0), phi = autobal_ensemble_member_value(e1, m, 1);
    single r;
    char what[80];
    CHECK("grid value (endpoint)", psi == 0.1 + 0.6 * (double)(m / 3) / 2.0 && phi == 0.1 + 0.6 * (double)(m % 3) / 2.0);
    r = pend_single(&s, &pp, psi, phi);
    snprintf(what, sizeof what, "pendulum member %zu (psi %.2f, phi %.2f)", m, psi, phi);
    check_member(what, autobal_ensemble_summary(e1, m), &r, 2);
    if (r.balanced == 1 && r.status >= 0) balanced++;
  }
  autobal_ensemble_get_tally(e1, &t);
  printf("  P(balance) = %zu/%zu = %.4f\n", t.n_balanced, t.n_ok, t.p);
  CHECK("P(balance) equals the single runs' fraction", t.n_ok == 9 && t.n_balanced == balanced && t.p == (double)balanced / 9.0);
  CHECK("both outcomes occur (the comparison means something)", balanced > 0 && balanced < 9);
  /* the main motion psi = phi = psi0 = 0.4 (member 4) balances at once: residual 0 at t = 0 */
  {
    const double *c = autobal_ensemble_summary(e1, 4);
    CHECK_CLOSE("member 4 starts on the main motion: residual unbalance", c[AUTOBAL_ENSEMBLE_RESIDUAL_INITIAL], 0.0, 0, 1e-12);
    CHECK("member 4 balanced from t = 0", c[AUTOBAL_ENSEMBLE_BALANCED] == 1 && c[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE] == 0.0);
  }
  s.threads = 2;
  e2 = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK_STATUS("run (2 threads)", e2 ? autobal_ensemble_run(e2) : err.status, AUTOBAL_SUCCESS);
  CHECK("2 threads == 1 thread, bit for bit", e2 && same_ensembles(e1, e2, mb.n_columns));
  autobal_ensemble_free(e2);
  {
    autobal_ensemble_settings b = s;
    b.param[1].name = "k", b.param[0].name = "psi0";
    CHECK("k with psi0 rejected", autobal_ensemble_alloc(&mb, &b, &err) == NULL);
    CHECK_MSG("k and psi0", err.message, "same unbalance");
    b = s;
    b.param[0].name = "bogus";
    CHECK("an unknown name rejected", autobal_ensemble_alloc(&mb, &b, &err) == NULL);
    CHECK_MSG("unknown", err.message, "not a pendulum ensemble parameter");
  }
  autobal_ensemble_free(e1);
  autobal_ensemble_member_release(&mb);
  y0[0] = NAN;
  CHECK_STATUS("a NaN initial state rejected", autobal_ensemble_pendulum_member(&pp, y0, &mb, &err), AUTOBAL_EINVAL);
}

/* ---- a third model written here: y' = -lambda y, the engine knows nothing else ---------------------
 * The residual |y| = exp(-lambda t) falls below tol at t* = ln(1/tol)/lambda: the time to balance in
 * closed form.  The right-hand side refuses lambda > 5 (a failure the engine must record). */
typedef struct decay_worker {
  double lambda;
  double settle; /* settle_time of every member: *(double *)model, 0 without a model */
} decay_worker;

static int decay_describe(const void *model, const char *name, autobal_ensemble_param_info *info, autobal_error *err) {
  (void)model;
  if (strcmp(name, "lambda") != 0) {
    if (err) err->status = AUTOBAL_EINVAL, snprintf(err->message, sizeof err->message, "'%s' is not lambda", name);
    return AUTOBAL_EINVAL;
  }
  info->units = "1/s", info->long_name = "decay rate", info->periodic = 0;
  info->positive = model != NULL; /* the settle test's lambda must be > 0 */
  return AUTOBAL_SUCCESS;
}
static void *decay_alloc(const void *model, const char *const *names, size_t n, autobal_error *err) {
  decay_worker *w = calloc(1, sizeof(decay_worker));
  (void)names, (void)n, (void)err;
  if (w) w->settle = model ? *(const double *)model : 0.0;
  return w;
}
static void decay_free(void *w) { free(w); }
static int decay_rhs(double t, const double y[], double dydt[], void *params) {
  const decay_worker *w = params;
  (void)t;
  if (w->lambda > 5) return 1;
  dydt[0] = -w->lambda * y[0];
  return 0;
}
static double decay_monitor(double t, const double y[], void *user) {
  (void)t, (void)user;
  return fabs(y[0]);
}
static int decay_setup(void *wp, const double *values, double y0[], autobal_ensemble_setup *su, autobal_error *err) {
  decay_worker *w = wp;
  (void)err;
  w->lambda = values[0];
  y0[0] = 1.0;
  su->sys.rhs = decay_rhs, su->sys.jac = NULL, su->sys.dim = 1, su->sys.params = w;
  su->speed = TWO_PI; /* one "revolution" per second */
  su->monitor = decay_monitor, su->monitor_user = NULL;
  su->residual_initial = 1.0;
  su->settle_time = w->settle;
  return AUTOBAL_SUCCESS;
}
static int decay_observe(void *wp, double t, const double y[], double *amplitude, double *row) {
  (void)wp, (void)t;
  *amplitude = fabs(y[0]);
  if (row) row[0] = y[0];
  return 0;
}
static void decay_finish(void *wp, double t, const double y[], double *residual, double *amplitude, double *angles) {
  (void)wp, (void)t, (void)angles;
  *residual = *amplitude = fabs(y[0]);
}
static int decay_column(const void *model, size_t k, char *name, size_t size, const char **units) {
  (void)model, (void)k;
  snprintf(name, size, "y");
  *units = "1";
  return AUTOBAL_SUCCESS;
}

static void test_third_model(void) {
  autobal_ensemble_member mb;
  autobal_ensemble_settings s = autobal_ensemble_settings_default();
  autobal_ensemble_tally t;
  autobal_ensemble *e;
  autobal_error err;
  size_t m, keep = 2;
  char out[512];
  FILE *f;
  int st;
  printf("# a model defined by the caller: y' = -lambda y, lambda = 1..6\n");
  memset(&mb, 0, sizeof mb);
  mb.model_name = "decay";
  mb.dim = 1, mb.n_angles = 0, mb.n_columns = 1;
  mb.time_units = "s", mb.time_name = "time", mb.time_long_name = "time", mb.length_units = "1";
  mb.describe = decay_describe, mb.worker_alloc = decay_alloc, mb.worker_free = decay_free, mb.setup = decay_setup;
  mb.observe = decay_observe, mb.finish = decay_finish, mb.column_name = decay_column;
  s.n_params = 1;
  s.param[0].name = "lambda", s.param[0].min = 1, s.param[0].max = 6, s.param[0].n = 6;
  s.endpoint = 1;
  s.t_end = 10, s.balance_tol = 1e-3, s.balance_revs = 1, s.revs_out = 0.5;
  s.transient.rtol = 1e-12, s.transient.atol = 1e-14;
  s.series = &keep, s.n_series = 1;
  s.threads = 2;
  e = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK("alloc", e != NULL);
  if (!e) {
    printf("  %s\n", err.message);
    return;
  }
  CHECK_STATUS("run", autobal_ensemble_run(e), AUTOBAL_SUCCESS);
  for (m = 0; m < 5; m++) {
    const double *r = autobal_ensemble_summary(e, m);
    double lambda = 1.0 + (double)m;
    CHECK("balanced and stopped at the end of the dwell", r[AUTOBAL_ENSEMBLE_BALANCED] == 1 &&
                                                             r[AUTOBAL_ENSEMBLE_STATUS] == AUTOBAL_EVENT);
    CHECK_CLOSE("time to balance = ln(1/tol)/lambda", r[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE], log(1e3) / lambda, 0, 1e-7);
    CHECK_CLOSE("stopped at t* + 1 s", r[AUTOBAL_ENSEMBLE_T_REACHED], log(1e3) / lambda + 1.0, 0, 1e-7);
    CHECK_CLOSE("final residual exp(-lambda t_reached)", r[AUTOBAL_ENSEMBLE_RESIDUAL_FINAL],
                exp(-lambda * r[AUTOBAL_ENSEMBLE_T_REACHED]), 1e-8, 0);
    CHECK("largest amplitude 1 (at t = 0)", r[AUTOBAL_ENSEMBLE_AMPLITUDE_MAX] == 1.0);
  }
  CHECK_STATUS("lambda = 6: the right-hand side's failure recorded", (int)autobal_ensemble_summary(e, 5)[AUTOBAL_ENSEMBLE_STATUS],
               AUTOBAL_ERHS);
  autobal_ensemble_get_tally(e, &t);
  CHECK("tally: 1 failed, 5 of 5 balanced", t.n_failed == 1 && t.n_ok == 5 && t.n_balanced == 5 && t.p == 1.0);
  {
    size_t fm = 99;
    int fst = 0;
    const char *why = NULL;
    int has = autobal_ensemble_first_failure(e, &fm, &fst, &why);
    printf("  first failure: %d, member %zu, status %d, '%s'\n", has, fm, fst, why ? why : "(null)");
    CHECK("first failure: member 5 (lambda = 6), AUTOBAL_ERHS, with the driver's message",
          has == 1 && fm == 5 && fst == AUTOBAL_ERHS && why && why[0]);
    CHECK("first failure of NULL: none", autobal_ensemble_first_failure(NULL, &fm, NULL, NULL) == 0);
  }
  CHECK_CLOSE("median time to balance (lambda = 3)", t.ttb_median, log(1e3) / 3.0, 0, 1e-7);
  {
    size_t nr, i;
    const double *tt, *rows;
    int ok = 1;
    autobal_ensemble_series(e, 2, &nr, &tt, &rows);
    for (i = 0; i < nr; i++) ok = ok && fabs(rows[i] - exp(-3.0 * tt[i])) <= 1e-10;
    printf("  kept series of lambda = 3: %zu rows\n", nr);
    CHECK("kept series: y = exp(-3 t) within 1e-10 at every row", nr >= 3 && ok && tt[1] == 0.5);
  }
  /* the archive of a model without angles */
  snprintf(out, sizeof out, "%s/test_ensemble_decay.h5", AUTOBAL_TEST_TMP_DIR);
  {
    autobal_archive *a = NULL, *r = NULL;
    autobal_ensemble_execution ex = {1, 2, 0.0, 0};
    double v[6];
    st = autobal_archive_create(out, 1, &a, &err);
    if (st == AUTOBAL_SUCCESS) st = autobal_ensemble_write(e, a, NULL, NULL, &ex);
    CHECK_STATUS("archive /decay/ensemble written", st, AUTOBAL_SUCCESS);
    if (a) autobal_archive_close(a, NULL);
    if (autobal_archive_open_read(out, &r, NULL) == AUTOBAL_SUCCESS) {
      CHECK_STATUS("lambda axis read", autobal_archive_read_var(r, "/decay/ensemble/lambda", v, 6), AUTOBAL_SUCCESS);
      CHECK("lambda axis 1..6", v[0] == 1 && v[5] == 6);
      CHECK("no final_angle without angles", autobal_archive_has(r, "/decay/ensemble/final_angle", NULL) == 0);
      autobal_archive_close(r, NULL);
    }
    remove(out);
  }
  /* journals: an unwritable place, a file that is not a journal */
  CHECK_STATUS("journal in a missing directory", autobal_ensemble_journal_open(e, "/nonexistent-dir/x.h5", 0), AUTOBAL_EIO);
  CHECK_MSG("journal in a missing directory", autobal_ensemble_errmsg(e), "/nonexistent-dir/x.h5.journal-0");
  snprintf(out, sizeof out, "%s/test_ensemble_junk.h5.journal-3", AUTOBAL_TEST_TMP_DIR);
  f = fopen(out, "wb");
  if (f) {
    fputs("this is not an autobal ensemble journal, but long enough for a header", f);
    fclose(f);
  }
  snprintf(out, sizeof out, "%s/test_ensemble_junk.h5", AUTOBAL_TEST_TMP_DIR);
  /* a file merely named like a journal is not one (no "ABENSJ01" header): it is not read, not
   * truncated by journal_open and not removed (issue 19: --force used to delete any such file) */
  CHECK_STATUS("resume ignores a file that is not a journal", autobal_ensemble_resume(e, out, 0), AUTOBAL_SUCCESS);
  CHECK_STATUS("journal_open refuses to overwrite it", autobal_ensemble_journal_open(e, out, 3), AUTOBAL_EIO);
  CHECK_MSG("... saying why", autobal_ensemble_errmsg(e), "not an ensemble journal");
  CHECK_STATUS("journals_remove", autobal_ensemble_journals_remove(out, NULL), AUTOBAL_SUCCESS);
  {
    char junk[1024];
    FILE *g;
    snprintf(junk, sizeof junk, "%s/test_ensemble_junk.h5.journal-3", AUTOBAL_TEST_TMP_DIR);
    g = fopen(junk, "rb");
    CHECK("... which leaves the file alone", g != NULL);
    if (g) fclose(g);
    remove(junk);
  }
  autobal_ensemble_free(e);
  mb.worker_alloc = NULL;
  CHECK("a member without worker_alloc rejected", autobal_ensemble_alloc(&mb, &s, &err) == NULL && err.status == AUTOBAL_EINVAL);
}

/* settle_time (a member whose speed still changes is not yet balanced): the dwell counts from
 * settle_time = 2 s on, so the time to balance is max(ln(1/tol)/lambda, 2) in closed form, and the
 * stop comes a dwell (1 s) later; a positive-only parameter refuses min <= 0 with its name. */
static void test_settle(void) {
  autobal_ensemble_member mb;
  autobal_ensemble_settings s = autobal_ensemble_settings_default();
  autobal_ensemble *e;
  autobal_error err;
  double settle = 2.0;
  size_t m;
  printf("# settle_time = 2 s: y' = -lambda y, lambda = 1..5\n");
  memset(&mb, 0, sizeof mb);
  mb.model_name = "decay";
  mb.model = &settle;
  mb.dim = 1, mb.n_angles = 0, mb.n_columns = 1;
  mb.time_units = "s", mb.time_name = "time", mb.time_long_name = "time", mb.length_units = "1";
  mb.describe = decay_describe, mb.worker_alloc = decay_alloc, mb.worker_free = decay_free, mb.setup = decay_setup;
  mb.observe = decay_observe, mb.finish = decay_finish, mb.column_name = decay_column;
  s.n_params = 1;
  s.param[0].name = "lambda", s.param[0].min = 1, s.param[0].max = 5, s.param[0].n = 5;
  s.endpoint = 1;
  s.t_end = 10, s.balance_tol = 1e-3, s.balance_revs = 1, s.revs_out = 0.5;
  s.transient.rtol = 1e-12, s.transient.atol = 1e-14;
  s.threads = 1;
  e = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK("alloc", e != NULL);
  if (!e) return;
  CHECK_STATUS("run", autobal_ensemble_run(e), AUTOBAL_SUCCESS);
  for (m = 0; m < 5; m++) {
    const double *r = autobal_ensemble_summary(e, m);
    double lambda = 1.0 + (double)m, want = fmax(log(1e3) / lambda, 2.0);
    CHECK("balanced and stopped", r[AUTOBAL_ENSEMBLE_BALANCED] == 1 && r[AUTOBAL_ENSEMBLE_STATUS] == AUTOBAL_EVENT);
    CHECK_CLOSE("time to balance = max(ln(1/tol)/lambda, settle_time)", r[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE], want, 0, 1e-7);
    CHECK("time to balance never before settle_time", r[AUTOBAL_ENSEMBLE_TIME_TO_BALANCE] >= 2.0);
    CHECK_CLOSE("stopped a dwell (1 s) later", r[AUTOBAL_ENSEMBLE_T_REACHED], want + 1.0, 0, 1e-7);
  }
  autobal_ensemble_free(e);
  s.param[0].min = 0;
  CHECK("a positive-only parameter with min = 0 rejected", autobal_ensemble_alloc(&mb, &s, &err) == NULL && err.status == AUTOBAL_EINVAL);
  CHECK_MSG("the parameter and the range named", err.message, "lambda: min = 0 1/s is out of range: allowed (0, inf)");
  s.param[0].min = -1;
  CHECK("min = -1 rejected", autobal_ensemble_alloc(&mb, &s, &err) == NULL && err.status == AUTOBAL_EINVAL);
}

/* ---- statistics of member quantities --------------------------------------------------------------- */
/* The decay model's quantity: its own rate lambda, so the distribution over the grid is known. */
static void decay_quantities(void *wp, double t, const double y[], double *q) {
  const decay_worker *w = wp;
  (void)t, (void)y;
  q[0] = w->lambda;
}

static void test_stats(void) {
  static const autobal_ensemble_quantity rate = {"rate", "1/s", "the member's decay rate"};
  static const double x5[5] = {1, 2, 4, 8, 16};
  const double z = 1.959963984540054, z2 = z * z;
  /* Newcombe (1998), Statist. Med. 17:857-872, Table I, method 3 (Wilson score), to 4 decimals */
  static const struct { size_t k, n; double lo, hi; } newcombe[4] = {
      {81, 263, 0.2553, 0.3662}, {15, 148, 0.0624, 0.1605}, {0, 20, 0.0, 0.1611}, {1, 29, 0.0061, 0.1718}};
  autobal_ensemble_member mb;
  autobal_ensemble_settings s = autobal_ensemble_settings_default();
  autobal_ensemble *e;
  autobal_ensemble_stats st;
  autobal_ensemble_target_result tr;
  autobal_error err;
  double lo, hi;
  size_t i;
  printf("# statistics: Wilson interval, type-7 quantiles, a member quantity's distribution and target\n");
  for (i = 0; i < 4; i++) {
    CHECK_STATUS("wilson", autobal_ensemble_wilson_interval(newcombe[i].k, newcombe[i].n, z, &lo, &hi), AUTOBAL_SUCCESS);
    printf("  %zu of %zu: [%.6f, %.6f] (Newcombe 1998: [%.4f, %.4f])\n", newcombe[i].k, newcombe[i].n, lo, hi, newcombe[i].lo,
           newcombe[i].hi);
    CHECK_CLOSE("Wilson low vs Newcombe 1998", lo, newcombe[i].lo, 0, 5e-5);
    CHECK_CLOSE("Wilson high vs Newcombe 1998", hi, newcombe[i].hi, 0, 5e-5);
  }
  /* k = 0 and k = n in closed form: [0, z^2/(n + z^2)] and [n/(n + z^2), 1] */
  autobal_ensemble_wilson_interval(0, 40, z, &lo, &hi);
  CHECK("k = 0: low = 0", lo == 0.0);
  CHECK_CLOSE("k = 0: high = z^2/(n + z^2)", hi, z2 / (40 + z2), 1e-14, 0);
  autobal_ensemble_wilson_interval(40, 40, z, &lo, &hi);
  CHECK_CLOSE("k = n: low = n/(n + z^2)", lo, 40 / (40 + z2), 1e-14, 0);
  CHECK("k = n: high = 1", hi == 1.0);
  /* z = 2, 8 of 10, by hand: (0.8 + 0.2 -+ 2 sqrt(0.016 + 0.01)) / 1.4 */
  autobal_ensemble_wilson_interval(8, 10, 2.0, &lo, &hi);
  CHECK_CLOSE("z = 2, 8/10: low (1 - 2 sqrt(0.026))/1.4", lo, (1 - 2 * sqrt(0.026)) / 1.4, 1e-14, 0);
  CHECK_CLOSE("z = 2, 8/10: high (1 + 2 sqrt(0.026))/1.4", hi, (1 + 2 * sqrt(0.026)) / 1.4, 1e-14, 0);
  CHECK_STATUS("wilson k > n", autobal_ensemble_wilson_interval(3, 2, z, &lo, &hi), AUTOBAL_EINVAL);
  CHECK("k > n: NaN", isnan(lo) && isnan(hi));
  CHECK_STATUS("wilson n = 0", autobal_ensemble_wilson_interval(0, 0, z, &lo, &hi), AUTOBAL_EINVAL);
  CHECK_STATUS("wilson z = 0", autobal_ensemble_wilson_interval(1, 2, 0.0, &lo, &hi), AUTOBAL_EINVAL);
  /* type 7 by hand on 1, 2, 4, 8, 16: h = 4 p */
  CHECK("Q(0) = min", autobal_ensemble_quantile_sorted(x5, 5, 0.0) == 1.0);
  CHECK_CLOSE("Q(0.05): h = 0.2, 1 + 0.2 (2 - 1)", autobal_ensemble_quantile_sorted(x5, 5, 0.05), 1.2, 1e-15, 0);
  CHECK("Q(0.25): h = 1, x[1]", autobal_ensemble_quantile_sorted(x5, 5, 0.25) == 2.0);
  CHECK("Q(0.5): x[2]", autobal_ensemble_quantile_sorted(x5, 5, 0.5) == 4.0);
  CHECK_CLOSE("Q(0.95): h = 3.8, 8 + 0.8 (16 - 8)", autobal_ensemble_quantile_sorted(x5, 5, 0.95), 14.4, 1e-15, 0);
  CHECK("Q(1) = max", autobal_ensemble_quantile_sorted(x5, 5, 1.0) == 16.0);
  CHECK("one value: every quantile is it", autobal_ensemble_quantile_sorted(x5 + 3, 1, 0.05) == 8.0 &&
                                              autobal_ensemble_quantile_sorted(x5 + 3, 1, 1.0) == 8.0);
  CHECK("p outside [0, 1] or n = 0: NaN", isnan(autobal_ensemble_quantile_sorted(x5, 5, 1.5)) &&
                                             isnan(autobal_ensemble_quantile_sorted(x5, 0, 0.5)));
  CHECK("quantile probabilities 0, .05, .25, .5, .75, .95, 1",
        autobal_ensemble_quantile_probability(0) == 0 && autobal_ensemble_quantile_probability(1) == 0.05 &&
            autobal_ensemble_quantile_probability(3) == 0.5 && autobal_ensemble_quantile_probability(6) == 1 &&
            isnan(autobal_ensemble_quantile_probability(7)));

  /* lambda = 1..6 on a grid: the member lambda = 6 fails (decay_rhs), the others' quantity is
   * lambda: the statistics are those of 1, 2, 3, 4, 5 (h = 4 p), the target rate <= 2.5 holds for
   * 2 of 5 */
  memset(&mb, 0, sizeof mb);
  mb.model_name = "decay";
  mb.dim = 1, mb.n_angles = 0, mb.n_columns = 1;
  mb.time_units = "s", mb.time_name = "time", mb.time_long_name = "time", mb.length_units = "1";
  mb.describe = decay_describe, mb.worker_alloc = decay_alloc, mb.worker_free = decay_free, mb.setup = decay_setup;
  mb.observe = decay_observe, mb.finish = decay_finish, mb.column_name = decay_column;
  mb.n_quantities = 1, mb.quantity = &rate, mb.finish_quantities = decay_quantities;
  s.n_params = 1;
  s.param[0].name = "lambda", s.param[0].min = 1, s.param[0].max = 6, s.param[0].n = 6;
  s.endpoint = 1;
  s.t_end = 2, s.balance_tol = 1e-3, s.balance_revs = 1, s.revs_out = 0.5;
  s.threads = 1;
  s.n_targets = 1;
  s.target[0].quantity = "rate", s.target[0].limit = 2.5;
  e = autobal_ensemble_alloc(&mb, &s, &err);
  CHECK("alloc with a quantity and a target", e != NULL);
  if (!e) {
    printf("  %s\n", err.message);
    return;
  }
  CHECK("summary length: the angles (none), then the quantity", autobal_ensemble_summary_length(e) == AUTOBAL_ENSEMBLE_ANGLES + 1 &&
                                                                    autobal_ensemble_quantity_index(e, 0) == AUTOBAL_ENSEMBLE_ANGLES &&
                                                                    autobal_ensemble_quantity_index(e, 1) == (size_t)-1);
  CHECK("quantity found by name", autobal_ensemble_quantity_find(e, "rate") == 0 && autobal_ensemble_quantity_find(e, "x") == -1);
  CHECK_STATUS("run", autobal_ensemble_run(e), AUTOBAL_SUCCESS);
  CHECK("member lambda = 6 failed", autobal_ensemble_summary(e, 5)[AUTOBAL_ENSEMBLE_STATUS] < 0);
  CHECK("each member's quantity is its lambda", autobal_ensemble_summary(e, 2)[AUTOBAL_ENSEMBLE_ANGLES] == 3.0);
  CHECK_STATUS("stats", autobal_ensemble_get_stats(e, 0, &st), AUTOBAL_SUCCESS);
  printf("  rate: n %zu, quantiles %g %g %g %g %g %g %g, mean %g\n", st.n, st.quantile[0], st.quantile[1], st.quantile[2],
         st.quantile[3], st.quantile[4], st.quantile[5], st.quantile[6], st.mean);
  CHECK("the failed member is left out: n = 5", st.n == 5 && st.n_nan == 0);
  CHECK("min 1, q25 2, median 3, q75 4, max 5", st.quantile[0] == 1 && st.quantile[2] == 2 && st.quantile[3] == 3 &&
                                                    st.quantile[4] == 4 && st.quantile[6] == 5);
  CHECK_CLOSE("q05 = 1 + 0.2", st.quantile[1], 1.2, 1e-15, 0);
  CHECK_CLOSE("q95 = 4 + 0.8", st.quantile[5], 4.8, 1e-15, 0);
  CHECK_CLOSE("mean 3", st.mean, 3.0, 1e-15, 0);
  CHECK_STATUS("target", autobal_ensemble_get_target(e, 0, &tr), AUTOBAL_SUCCESS);
  CHECK("target: 2 of 5 (1 and 2 <= 2.5)", tr.n == 5 && tr.n_within == 2 && tr.p == 0.4 && tr.quantity == 0 && tr.limit == 2.5);
  CHECK("target interval around p", tr.wilson_low < 0.4 && tr.wilson_high > 0.4);
  CHECK_STATUS("bad quantity", autobal_ensemble_get_stats(e, 1, &st), AUTOBAL_EINVAL);
  CHECK_STATUS("bad target", autobal_ensemble_get_target(e, 1, &tr), AUTOBAL_EINVAL);
  autobal_ensemble_free(e);
  /* bad targets */
  s.target[0].quantity = "speed";
  CHECK("a target on an unknown quantity rejected", autobal_ensemble_alloc(&mb, &s, &err) == NULL && err.status == AUTOBAL_EINVAL);
  CHECK_MSG("the name and the member's quantities named", err.message, "'speed' is not a quantity of the decay member (rate)");
  s.target[0].quantity = "rate", s.target[0].limit = NAN;
  CHECK("a NaN limit rejected", autobal_ensemble_alloc(&mb, &s, &err) == NULL && err.status == AUTOBAL_EINVAL);
  CHECK_MSG("the limit named", err.message, "the limit of rate = nan is not finite");
  s.target[0].limit = 1, s.n_targets = 2, s.target[1].quantity = "rate", s.target[1].limit = 2;
  CHECK("two targets on one quantity rejected", autobal_ensemble_alloc(&mb, &s, &err) == NULL && err.status == AUTOBAL_EINVAL);
  CHECK_MSG("the duplicate named", err.message, "target 2: rate already has a target");
  s.n_targets = 5;
  CHECK("five targets rejected", autobal_ensemble_alloc(&mb, &s, &err) == NULL && err.status == AUTOBAL_EINVAL);
  CHECK_MSG("the count named", err.message, "n_targets = 5 is out of range: allowed [0, 4]");
  s.n_targets = 0;
  mb.finish_quantities = NULL;
  CHECK("a quantity without finish_quantities rejected", autobal_ensemble_alloc(&mb, &s, &err) == NULL && err.status == AUTOBAL_EINVAL);
}

int main(void) {
  gsl_set_error_handler_off();
  test_rotor();
  test_pendulum();
  test_third_model();
  test_settle();
  test_stats();
  return check_summary();
}
