/* rotor_friction.c: stick-slip switching of the rotor transient study (rotor_friction.h). */
#include "studies/rotor_friction.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* interior points of a step at which the stick-slip switching functions are probed for a grazing
 * crossing (a stuck ball's |H| - mu N follows the rotor's vibration): on the washer of
 * data/washer_friction.ini 1, 3, 7 and 15 probes found 79, 98, 111 and 110 crossings that the step
 * ends missed, 7 and 15 the same switches and final state (docs/device.md "Grazing switches") */
#define STUDY_FRICTION_PROBES 7u

typedef struct ball_event {
  struct study_friction *f;
  size_t k;
} ball_event;

struct study_friction {
  autobal_rotor *rot;
  int frame;
  size_t N, first; /* balls; the index of the first ball's event */
  ball_event *ev;
  int *stuck;       /* the mode at the last switch: 1 stuck */
  double *since;    /* s, when the current stuck interval began */
  double *time_stuck;
  unsigned long sticks, slips, reversals;
  int failed;
  char message[AUTOBAL_ERRMSG_SIZE];
};

static double ball_switch(double t, const double y[], void *user) {
  const ball_event *e = (const ball_event *)user;
  return autobal_rotor_friction_switch(e->f->rot, e->f->frame, e->k, t, y);
}

static void note_modes(study_friction *f, double t) {
  size_t k;
  for (k = 0; k < f->N; k++) {
    const int is = autobal_rotor_ball_mode_get(f->rot, k) == AUTOBAL_ROTOR_BALL_STUCK;
    if (is && !f->stuck[k]) f->since[k] = t;
    if (!is && f->stuck[k]) f->time_stuck[k] += t - f->since[k];
    f->stuck[k] = is;
  }
}

static int ball_reset(const autobal_transient_event_hit *hit, double y[], void *user) {
  study_friction *f = (study_friction *)user;
  size_t ns, nl, nr;
  int rc;
  if (hit->index < f->first || hit->index >= f->first + f->N) return 0; /* not a friction event */
  rc = autobal_rotor_friction_settle(f->rot, f->frame, hit->t, y, 0, &ns, &nl, &nr);
  if (rc < 0) {
    f->failed = rc;
    snprintf(f->message, sizeof f->message, "%s", autobal_rotor_errmsg(f->rot));
    return 2; /* stop the run here */
  }
  f->sticks += ns;
  f->slips += nl;
  f->reversals += nr;
  note_modes(f, hit->t);
  return rc == 1 ? AUTOBAL_TRANSIENT_RESET : 0;
}

void study_friction_free(study_friction *f) {
  if (f == NULL) return;
  free(f->ev);
  free(f->stuck);
  free(f->since);
  free(f->time_stuck);
  free(f);
}

int study_friction_begin(autobal_rotor *rot, int frame, autobal_transient *tr, double t0, double *y,
                         study_friction **out, autobal_error *err) {
  study_friction *f;
  size_t k, N = autobal_rotor_n_balls_total(rot);
  int rc;
  *out = NULL;
  if (autobal_rotor_get_params(rot)->friction.law != AUTOBAL_ROTOR_FRICTION_EXACT) return AUTOBAL_SUCCESS;
  f = (study_friction *)calloc(1, sizeof *f);
  if (f) {
    f->ev = (ball_event *)calloc(N + 1, sizeof *f->ev);
    f->stuck = (int *)calloc(N + 1, sizeof *f->stuck);
    f->since = (double *)calloc(N + 1, sizeof *f->since);
    f->time_stuck = (double *)calloc(N + 1, sizeof *f->time_stuck);
  }
  if (!f || !f->ev || !f->stuck || !f->since || !f->time_stuck) {
    study_friction_free(f);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  f->rot = rot;
  f->frame = frame;
  f->N = N;
  rc = autobal_rotor_friction_settle(rot, frame, t0, y, 1, NULL, NULL, NULL);
  if (rc < 0) {
    study_friction_free(f);
    return autobal_error_set(err, rc, "the initial state: %s", autobal_rotor_errmsg(rot));
  }
  note_modes(f, t0);
  for (k = 0; k < N; k++) {
    int idx;
    f->ev[k].f = f;
    f->ev[k].k = k;
    idx = autobal_transient_add_event(tr, ball_switch, &f->ev[k], 0, 0);
    if (idx < 0) {
      study_friction_free(f);
      return autobal_error_set(err, idx, "%s", autobal_transient_errmsg(tr));
    }
    /* a stuck ball's |H| - mu N follows the rotor's vibration and may exceed 0 for less than a step:
     * probed at interior points of every step (autobal_transient_set_event_probes) */
    autobal_transient_set_event_probes(tr, idx, STUDY_FRICTION_PROBES);
    if (k == 0) f->first = (size_t)idx;
  }
  autobal_transient_set_event_reset(tr, ball_reset, f);
  *out = f;
  return AUTOBAL_SUCCESS;
}

int study_friction_finish(study_friction *f, double t_end, autobal_study_rotor_transient_summary *s,
                          autobal_error *err) {
  size_t j, np, k;
  if (f == NULL) return AUTOBAL_SUCCESS;
  for (k = 0; k < f->N; k++)
    if (f->stuck[k]) f->time_stuck[k] += t_end - f->since[k];
  s->have_friction = 1;
  s->friction_sticks = f->sticks;
  s->friction_slips = f->slips;
  s->friction_reversals = f->reversals;
  np = autobal_rotor_n_planes(f->rot);
  for (j = 0; j < np; j++) {
    size_t i, n = autobal_rotor_n_balls(f->rot, j);
    if (n == 0) continue;
    s->ball_time_stuck[j] = (double *)malloc(n * sizeof(double));
    s->ball_stuck_final[j] = (int *)malloc(n * sizeof(int));
    if (!s->ball_time_stuck[j] || !s->ball_stuck_final[j]) return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
    for (i = 0; i < n; i++) {
      k = autobal_rotor_ball_index(f->rot, j, i);
      s->ball_time_stuck[j][i] = f->time_stuck[k];
      s->ball_stuck_final[j][i] = autobal_rotor_ball_mode_get(f->rot, k) == AUTOBAL_ROTOR_BALL_STUCK;
    }
  }
  if (f->failed) return autobal_error_set(err, f->failed, "%s", f->message);
  return AUTOBAL_SUCCESS;
}

void study_friction_summary_free(autobal_study_rotor_transient_summary *s) {
  size_t j;
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++) {
    free(s->ball_time_stuck[j]);
    free(s->ball_stuck_final[j]);
    s->ball_time_stuck[j] = NULL;
    s->ball_stuck_final[j] = NULL;
  }
}

/* ---- contact ------------------------------------------------------------------------------------- */

typedef struct pair_event {
  struct study_contact *c;
  size_t p;
} pair_event;

struct study_contact {
  autobal_rotor *rot;
  int frame;
  size_t np, first;
  pair_event *ev;
  study_friction *fric;
  size_t impacts, joins, releases;
  int failed;
  char message[AUTOBAL_ERRMSG_SIZE];
};

static double pair_switch(double t, const double y[], void *user) {
  const pair_event *e = (const pair_event *)user;
  return autobal_rotor_contact_switch(e->c->rot, e->c->frame, e->p, t, y);
}

/* THE reset of a run with contact: contact events here, the others to the friction collector. */
static int hybrid_reset(const autobal_transient_event_hit *hit, double y[], void *user) {
  study_contact *c = (study_contact *)user;
  int rc;
  if (c->fric) { /* the exact law with contact: impacts and switches settled together, for either event */
    study_friction *f = c->fric;
    size_t n[6] = {0, 0, 0, 0, 0, 0};
    const int ours = hit->index >= c->first && hit->index < c->first + c->np;
    if (!ours && (hit->index < f->first || hit->index >= f->first + f->N)) return 0;
    rc = autobal_rotor_hybrid_settle(c->rot, c->frame, hit->t, y, 0, n);
    if (rc < 0) {
      c->failed = rc;
      snprintf(c->message, sizeof c->message, "contact and friction at t = %.17g s: %s", hit->t, autobal_rotor_errmsg(c->rot));
      return 2;
    }
    f->sticks += n[0], f->slips += n[1], f->reversals += n[2];
    c->impacts += n[3], c->joins += n[4], c->releases += n[5];
    note_modes(f, hit->t);
    return rc == 1 ? AUTOBAL_TRANSIENT_RESET : 0;
  }
  if (hit->index < c->first || hit->index >= c->first + c->np) return 0;
  rc = autobal_rotor_contact_settle(c->rot, c->frame, hit->t, y, &c->impacts, &c->joins, &c->releases);
  if (rc < 0) {
    c->failed = rc;
    snprintf(c->message, sizeof c->message, "contact at t = %.17g s: %s", hit->t, autobal_rotor_errmsg(c->rot));
    return 2;
  }
  return rc == 1 ? AUTOBAL_TRANSIENT_RESET : 0;
}

void study_contact_free(study_contact *c) {
  if (c == NULL) return;
  free(c->ev);
  free(c);
}

int study_contact_begin(autobal_rotor *rot, int frame, autobal_transient *tr, double t0, double *y,
                        study_friction *fric, study_contact **out, autobal_error *err) {
  study_contact *c;
  size_t p, np;
  int rc;
  *out = NULL;
  if (!autobal_rotor_contact_on(rot)) return AUTOBAL_SUCCESS;
  if ((rc = autobal_rotor_contact_order(rot, frame, t0, y)) != AUTOBAL_SUCCESS)
    return autobal_error_set(err, rc, "%s", autobal_rotor_errmsg(rot));
  np = autobal_rotor_contact_n_pairs(rot);
  c = (study_contact *)calloc(1, sizeof *c);
  if (c) c->ev = (pair_event *)calloc(np + 1, sizeof *c->ev);
  if (!c || !c->ev) {
    study_contact_free(c);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  }
  c->rot = rot;
  c->frame = frame;
  c->np = np;
  c->fric = fric;
  if (fric) { /* the exact law: settle the start again with the contacts (touching balls at rest join) */
    size_t n[6] = {0, 0, 0, 0, 0, 0};
    rc = autobal_rotor_hybrid_settle(rot, frame, t0, y, 1, n);
    if (rc < 0) {
      study_contact_free(c);
      return autobal_error_set(err, rc, "the initial state: %s", autobal_rotor_errmsg(rot));
    }
    c->impacts += n[3], c->joins += n[4], c->releases += n[5];
    note_modes(fric, t0);
  }
  for (p = 0; p < np; p++) {
    int idx;
    c->ev[p].c = c;
    c->ev[p].p = p;
    idx = autobal_transient_add_event(tr, pair_switch, &c->ev[p], -1, 0);
    if (idx < 0) {
      study_contact_free(c);
      return autobal_error_set(err, idx, "%s", autobal_transient_errmsg(tr));
    }
    if (p == 0) c->first = (size_t)idx;
    /* dense output: the gaps also at the output times inside a step, so that no output shows two
     * balls overlapping after an impact the step's ends missed (a dip of the gap within one step) */
    (void)autobal_transient_set_event_output_probes(tr, idx, 1);
  }
  autobal_transient_set_event_reset(tr, hybrid_reset, c);
  *out = c;
  return AUTOBAL_SUCCESS;
}

int study_contact_finish(study_contact *c, const autobal_rotor *rot, autobal_study_rotor_transient_summary *s,
                         autobal_error *err) {
  size_t j;
  if (!autobal_rotor_contact_on(rot)) return AUTOBAL_SUCCESS;
  s->have_contact = 1;
  for (j = 0; j < autobal_rotor_n_planes(rot); j++) {
    s->contact_capacity[j] = autobal_rotor_contact_capacity(rot, j);
    s->contact_reachable[j] = autobal_rotor_contact_reachable(rot, j);
  }
  if (c == NULL) return AUTOBAL_SUCCESS;
  s->contact_impacts = c->impacts;
  s->contact_joins = c->joins;
  s->contact_releases = c->releases;
  s->contacts_final = autobal_rotor_contact_n_active(rot);
  if (c->failed) return autobal_error_set(err, c->failed, "%s", c->message);
  return AUTOBAL_SUCCESS;
}

int study_contact_write_summary(autobal_archive *a, const autobal_study_rotor_transient_summary *s, const char *group) {
  int st;
  double reach[AUTOBAL_ROTOR_MAX_PLANES];
  size_t j;
  if (!s->have_contact) return 0;
  st = autobal_archive_attr_double(a, group, "contact_impacts", (double)s->contact_impacts, "1");
  if (!st) st = autobal_archive_attr_double(a, group, "contact_joins", (double)s->contact_joins, "1");
  if (!st) st = autobal_archive_attr_double(a, group, "contact_releases", (double)s->contact_releases, "1");
  if (!st) st = autobal_archive_attr_double(a, group, "contacts_final", (double)s->contacts_final, "1");
  for (j = 0; j < s->n_planes; j++) reach[j] = s->contact_reachable[j];
  if (!st && s->n_planes)
    st = autobal_archive_attr_double_array(a, group, "contact_capacity", s->n_planes, s->contact_capacity, "kg m");
  if (!st && s->n_planes) st = autobal_archive_attr_double_array(a, group, "contact_reachable", s->n_planes, reach, "1");
  return st;
}

static const char *law_name(int law) {
  return law == AUTOBAL_ROTOR_FRICTION_EXACT ? "exact" : law == AUTOBAL_ROTOR_FRICTION_REGULARIZED ? "regularized" : "none";
}

int study_friction_write_inputs(autobal_archive *a, const autobal_rotor *rot, const char *group) {
  const autobal_rotor_params *p = autobal_rotor_get_params(rot);
  size_t j;
  int st = 0;
  for (j = 0; j < p->n_planes && p->rolling.on && !st; j++) { /* rolling inertia: the balls' radii */
    char grp[48];
    if (p->plane[j].n_balls == 0) continue;
    snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
    st = autobal_archive_attr_double_array(a, grp, "ball_rho", p->plane[j].n_balls, p->rolling.ball_rho[j], "m");
  }
  for (j = 0; j < p->n_planes && p->contact.on && !st; j++) { /* contact: the balls' diameters */
    char grp[48];
    if (p->plane[j].n_balls == 0) continue;
    snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
    st = autobal_archive_attr_double_array(a, grp, "ball_diameter", p->plane[j].n_balls, p->contact.ball_diameter[j], "m");
  }
  if (!st && p->contact.on) st = autobal_archive_attr_double(a, group, "contact_restitution", p->contact.restitution, "1");
  if (!st && p->contact.on)
    st = autobal_archive_attr_double(a, group, "contact_v_rest", p->contact.v_rest > 0.0 ? p->contact.v_rest : 1e-3, "rad/s");
  if (st || p->friction.law == AUTOBAL_ROTOR_FRICTION_NONE) return st;
  st = autobal_archive_attr_string(a, group, "friction", law_name(p->friction.law));
  if (!st && p->friction.law == AUTOBAL_ROTOR_FRICTION_REGULARIZED)
    st = autobal_archive_attr_double(a, group, "friction_u_eps", p->friction.u_eps, "rad/s");
  for (j = 0; j < p->n_planes && !st; j++) {
    char grp[48];
    const size_t n = p->plane[j].n_balls;
    if (n == 0) continue;
    snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
    st = autobal_archive_attr_double_array(a, grp, "ball_f", n, p->friction.ball_f[j], "1");
    if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_mu", n, p->friction.ball_mu[j], "1");
  }
  return st;
}

int study_friction_write_summary(autobal_archive *a, const autobal_study_rotor_transient_summary *s,
                                 const char *group) {
  size_t j;
  int st;
  if (!s->have_friction) return 0;
  st = autobal_archive_attr_double(a, group, "friction_sticks", (double)s->friction_sticks, "1");
  if (!st) st = autobal_archive_attr_double(a, group, "friction_slips", (double)s->friction_slips, "1");
  if (!st) st = autobal_archive_attr_double(a, group, "friction_reversals", (double)s->friction_reversals, "1");
  for (j = 0; j < s->n_planes && !st; j++) {
    char name[48];
    double *flags;
    size_t i, n = s->n_balls[j];
    if (n == 0 || !s->ball_time_stuck[j] || !s->ball_stuck_final[j]) continue;
    snprintf(name, sizeof name, "p%zu_ball_time_stuck", j + 1);
    st = autobal_archive_attr_double_array(a, group, name, n, s->ball_time_stuck[j], "s");
    if (st) break;
    flags = (double *)malloc(n * sizeof *flags);
    if (!flags) return AUTOBAL_ENOMEM;
    for (i = 0; i < n; i++) flags[i] = s->ball_stuck_final[j][i];
    snprintf(name, sizeof name, "p%zu_ball_stuck_final", j + 1);
    st = autobal_archive_attr_double_array(a, group, name, n, flags, "1");
    free(flags);
  }
  return st;
}
