/* rotor_stab_handle.c: the rotor stability handle (autobal_rotor_stab, docs/rotor.md
 * "Stability of a balanced motion"): options, allocation of every workspace, the parameters a
 * sweep or a map varies, and the member of the family of balanced configurations at the
 * current parameters (autobal_rotor_stab_update_member_), with its closed linear system.
 *
 * May use: rotor_closed.h (member angles, plane rank, isotropy), the rotor model
 * (autobal/rotor.h), the numerics (autobal/stability.h workspaces), the transient driver
 * (its workspace for the Floquet integration), core (internal.h).  Used by rotor_floquet.c
 * and rotor_stability.c through rotor_stab_handle.h; it calls neither of them. */
#include "autobal/rotor_stability.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/rotor_closed.h"
#include "analysis/rotor_stab_handle.h"
#include "internal.h"

/* Fill the closed system from the handle's current data and member angles. */
void autobal_rotor_stab_closed_from_handle_(const autobal_rotor_stab *s, autobal_rotor_closed *c) {
  size_t j, i;
  memset(c, 0, sizeof *c);
  c->L = s->L;
  c->omega = s->cur.omega;
  c->n_planes = s->n_planes;
  c->isotropic = autobal_rotor_lumped_isotropic_(&s->L);
  c->closure_ok = 1;
  for (j = 0; j < s->n_planes; j++) {
    autobal_rotor_closed_plane *cp = &c->plane[j];
    const size_t o = s->off[j], n = s->cnt[j];
    double k0 = n > 0 ? s->h[o] / s->m[o] : 0.0;
    cp->d = s->cur.plane[j].d;
    cp->n_balls = n;
    for (i = 0; i < n; i++) {
      const double m = s->m[o + i], ph = 2.0 * s->psi[o + i];
      cp->mass += m;
      cp->Q_re += m * cos(ph);
      cp->Q_im += m * sin(ph);
      if (!autobal_rotor_close_rel_(s->h[o + i] / m, k0, 1e-12) && !(s->h[o + i] == 0.0 && k0 == 0.0))
        c->closure_ok = 0;
    }
    cp->kappa = k0;
    cp->m_add = s->cur.inertia == AUTOBAL_ROTOR_INERTIA_FULL ? cp->mass + s->cur.plane[j].m0 : 0.0;
    cp->rank = autobal_rotor_plane_rank_(s->m + o, s->r + o, s->psi + o, n);
    cp->family = n - cp->rank;
    if (cp->rank < 2) c->closure_ok = 0;
  }
}

/* ---- the handle ---------------------------------------------------------------------- */

const char *autobal_rotor_stab_method_name(int method) {
  switch (method) {
    case AUTOBAL_ROTOR_STAB_AUTO: return "auto";
    case AUTOBAL_ROTOR_STAB_POLY: return "poly";
    case AUTOBAL_ROTOR_STAB_CLOSED: return "closed";
    case AUTOBAL_ROTOR_STAB_FULL: return "full";
    case AUTOBAL_ROTOR_STAB_FLOQUET: return "floquet";
    default: return "unknown";
  }
}

static const char *const param_names[] = {"omega",          "ball_damping",   "ball_mass",  "stiffness_scale",
                                          "damping_scale",  "unbalance_mass", "anisotropy", "C_over_A"};
static const char *const param_units[] = {"rad/s", "kg/s", "kg", "1", "1", "kg", "1", "1"};
#define N_PARAMS 8
#define PARAM_HW0 100
#define PARAM_LU0 200
#define PARAM_PL0 300
/* the keys of a plane (autobal_rotor_plane_key) and their names, spelled out for each plane so
 * that the names are static strings */
#define PLANE_KEYS(P)                                                                                        \
  {P ".d", P ".m0", P ".r0", P ".psi0", P ".unbalance", P ".ball_mass", P ".ball_radius", P ".ball_damping"}
static const char *const plane_names[AUTOBAL_ROTOR_MAX_PLANES][AUTOBAL_ROTOR_PLANE_N_KEYS] = {PLANE_KEYS("plane1"),
                                                                                             PLANE_KEYS("plane2")};
#undef PLANE_KEYS
static const char *const plane_units[AUTOBAL_ROTOR_PLANE_N_KEYS] = {"m", "kg", "m", "rad", "kg m", "kg", "m", "kg/s"};

/* The field of a hardware or lumped id (NULL otherwise). */
static const autobal_rotor_field *param_field(int param, int *lumped) {
  size_t n;
  const autobal_rotor_field *t;
  if (param >= PARAM_HW0 && param < PARAM_LU0) {
    t = autobal_rotor_hardware_fields(&n);
    *lumped = 0;
    return (size_t)(param - PARAM_HW0) < n ? &t[param - PARAM_HW0] : NULL;
  }
  if (param >= PARAM_LU0 && param < PARAM_PL0) {
    t = autobal_rotor_lumped_fields(&n);
    *lumped = 1;
    return (size_t)(param - PARAM_LU0) < n ? &t[param - PARAM_LU0] : NULL;
  }
  return NULL;
}
/* Plane index and key of a plane id (0 if not one). */
static int param_plane(int param, size_t *j, int *key) {
  int q = param - PARAM_PL0;
  if (param < PARAM_PL0 || q / 16 >= AUTOBAL_ROTOR_MAX_PLANES || q % 16 >= AUTOBAL_ROTOR_PLANE_N_KEYS) return 0;
  *j = (size_t)(q / 16);
  *key = q % 16;
  return 1;
}

const char *autobal_rotor_stab_param_name(int param) {
  const autobal_rotor_field *f;
  int lumped, key;
  size_t j;
  if (param >= 0 && param < N_PARAMS) return param_names[param];
  if ((f = param_field(param, &lumped)) != NULL) return f->key;
  if (param_plane(param, &j, &key)) return plane_names[j][key];
  return NULL;
}
const char *autobal_rotor_stab_param_unit(int param) {
  const autobal_rotor_field *f;
  int lumped, key;
  size_t j;
  if (param >= 0 && param < N_PARAMS) return param_units[param];
  if ((f = param_field(param, &lumped)) != NULL) return f->unit;
  if (param_plane(param, &j, &key)) return plane_units[key];
  return NULL;
}
int autobal_rotor_stab_param_from_name(const char *name) {
  size_t i, j, n;
  const autobal_rotor_field *t;
  if (name == NULL) return -1;
  for (i = 0; i < N_PARAMS; i++)
    if (!strcmp(name, param_names[i])) return (int)i;
  if (!strcmp(name, "rotor.omega")) return AUTOBAL_ROTOR_PARAM_OMEGA;
  t = autobal_rotor_hardware_fields(&n);
  for (i = 0; i < n; i++)
    if (!strcmp(name, t[i].key) || !strcmp(name, t[i].name)) return AUTOBAL_ROTOR_PARAM_HARDWARE(i);
  t = autobal_rotor_lumped_fields(&n);
  for (i = 0; i < n; i++)
    if (!strcmp(name, t[i].key) || !strcmp(name, t[i].name)) return AUTOBAL_ROTOR_PARAM_LUMPED(i);
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++)
    for (i = 0; i < AUTOBAL_ROTOR_PLANE_N_KEYS; i++)
      if (!strcmp(name, plane_names[j][i])) return AUTOBAL_ROTOR_PARAM_PLANE(j, i);
  return -1;
}
size_t autobal_rotor_stab_param_list(int *ids, size_t n) {
  size_t k = 0, i, j, nh, nl;
  (void)autobal_rotor_hardware_fields(&nh);
  (void)autobal_rotor_lumped_fields(&nl);
#define PUT(id)                   \
  do {                            \
    if (ids && k < n) ids[k] = (id); \
    k++;                          \
  } while (0)
  for (i = 0; i < N_PARAMS; i++) PUT((int)i);
  for (i = 0; i < nh; i++) PUT(AUTOBAL_ROTOR_PARAM_HARDWARE(i));
  for (i = 0; i < nl; i++) PUT(AUTOBAL_ROTOR_PARAM_LUMPED(i));
  for (j = 0; j < AUTOBAL_ROTOR_MAX_PLANES; j++)
    for (i = 0; i < AUTOBAL_ROTOR_PLANE_N_KEYS; i++) PUT(AUTOBAL_ROTOR_PARAM_PLANE(j, i));
#undef PUT
  return k;
}

autobal_rotor_stab_options autobal_rotor_stab_options_default(void) {
  autobal_rotor_stab_options o;
  memset(&o, 0, sizeof o);
  o.method = AUTOBAL_ROTOR_STAB_AUTO;
  o.tol = 1e-9;
  o.floquet_rtol = 1e-11;
  o.floquet_atol = 1e-13;
  return o;
}

void autobal_rotor_stab_free(autobal_rotor_stab *s) {
  if (s == NULL) return;
  autobal_poly_workspace_free(s->pw);
  autobal_eigen_workspace_free(s->ew_closed);
  autobal_eigen_workspace_free(s->ew_full);
  if (s->lu_closed) gsl_matrix_free(s->lu_closed);
  if (s->perm_closed) gsl_permutation_free(s->perm_closed);
  if (s->lu_full) gsl_matrix_free(s->lu_full);
  if (s->perm_full) gsl_permutation_free(s->perm_full);
  if (s->vec_full) gsl_vector_free(s->vec_full);
  autobal_transient_free(s->tr);
  free(s->everyn);
  free(s->store);
  free(s);
}

void autobal_rotor_stab_set_cancel(autobal_rotor_stab *s, autobal_rotor_stab_cancel_fn fn, void *user) {
  if (s == NULL) return;
  s->cancel = fn;
  s->cancel_user = user;
}

int autobal_rotor_stab_cancelled_(autobal_rotor_stab *s) {
  if (s->cancel == NULL || !s->cancel(s->cancel_user)) return 0;
  autobal_error_set(&s->err, AUTOBAL_ECANCELLED, "cancelled by the caller");
  return 1;
}

const char *autobal_rotor_stab_errmsg(const autobal_rotor_stab *s) {
  return s ? s->err.message : "rotor stability handle is NULL";
}

static int check_options(const autobal_rotor_stab_options *o, const autobal_rotor_params *p,
                         autobal_error *err) {
  int st;
  size_t j;
  if (o->method < AUTOBAL_ROTOR_STAB_AUTO || o->method > AUTOBAL_ROTOR_STAB_FLOQUET)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option method = %d is not valid: 0 auto, 1 poly, 2 closed, 3 full, 4 floquet",
                             o->method);
  if ((st = autobal_check_param(err, "tol", o->tol, 0.0, 1, 1e-2, 0, "")) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_check_param(err, "floquet_rtol", o->floquet_rtol, 0.0, 1, 1e-3, 0, "")) !=
      AUTOBAL_SUCCESS)
    return st;
  if ((st = autobal_check_param(err, "floquet_atol", o->floquet_atol, 0.0, 1, 1e-3, 0, "")) !=
      AUTOBAL_SUCCESS)
    return st;
  if (o->unbalance_member < AUTOBAL_ROTOR_UNBALANCE_EVERY || o->unbalance_member > AUTOBAL_ROTOR_UNBALANCE_SYMMETRIC)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option unbalance_member = %d is not valid (0 every, 1 symmetric)", o->unbalance_member);
  if (o->unbalance2_boxes < -1 || o->unbalance2_boxes > 1000000000L)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option unbalance2_boxes = %ld is out of range: allowed -1 (no box search), 0 (default "
                             "budget) or [1, 1e9]",
                             o->unbalance2_boxes);
  if (o->member_boxes != 0 && (o->member_boxes < 1000 || o->member_boxes > 1000000000L))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option member_boxes = %ld is out of range: allowed 0 (the default budget, 4000000) or "
                             "[1000, 1e9]",
                             o->member_boxes);
  if (o->hill_boxes != 0 && (o->hill_boxes < 100 || o->hill_boxes > 100000000L))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "option hill_boxes = %ld is out of range: allowed 0 (the default budget, 20000) or "
                             "[100, 1e8]",
                             o->hill_boxes);
  for (j = 0; j < p->n_planes; j++) {
    const autobal_rotor_member *m = &o->member[j];
    if (m->kind < AUTOBAL_ROTOR_MEMBER_DEFAULT || m->kind > AUTOBAL_ROTOR_MEMBER_GIVEN)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "option member[%zu].kind = %d is not valid (0 default, 1 symmetric, 2 "
                               "free, 3 given)",
                               j, m->kind);
    if ((m->kind == AUTOBAL_ROTOR_MEMBER_FREE || m->kind == AUTOBAL_ROTOR_MEMBER_GIVEN)) {
      size_t need = m->kind == AUTOBAL_ROTOR_MEMBER_GIVEN
                        ? p->plane[j].n_balls
                        : (p->plane[j].n_balls >= 2 ? p->plane[j].n_balls - 2 : 0);
      if (m->n_angles != need || (need > 0 && m->angles == NULL))
        return autobal_error_set(err, AUTOBAL_EINVAL,
                                 "option member[%zu]: %zu angles given, the %s member of a plane "
                                 "with %zu balls needs %zu",
                                 j, m->n_angles,
                                 m->kind == AUTOBAL_ROTOR_MEMBER_GIVEN ? "'given'" : "'free'",
                                 p->plane[j].n_balls, need);
    }
  }
  return AUTOBAL_SUCCESS;
}

autobal_rotor_stab *autobal_rotor_stab_alloc(const autobal_rotor_params *p,
                                             const autobal_rotor_stab_options *opt,
                                             autobal_error *err) {
  autobal_rotor_stab *s;
  autobal_rotor_stab_options o = opt ? *opt : autobal_rotor_stab_options_default();
  size_t j, i, N = 0, nmem = 0, nstore;
  int st;
  autobal_error e;
  autobal_error_clear(&e);
  st = autobal_rotor_params_check(p, &e);
  if (st < 0) {
    if (err) *err = e;
    return NULL;
  }
  if ((st = check_options(&o, p, err)) != AUTOBAL_SUCCESS) return NULL;
  for (j = 0; j < p->n_planes; j++) {
    N += p->plane[j].n_balls;
    nmem += p->plane[j].n_balls;
  }
  s = (autobal_rotor_stab *)calloc(1, sizeof *s);
  if (s == NULL) {
    autobal_error_set(err, AUTOBAL_ENOMEM, "rotor stability: out of memory");
    return NULL;
  }
  s->N = N;
  s->n_planes = p->n_planes;
  s->ns = 8 + 2 * N;
  s->nm = 4 + N;
  s->opt = o;
  s->cur = *p;
  s->cur.axial = 0;
  s->c_scale = 1.0;
  s->h_scale = 1.0;
  s->input0 = p->input;
  if (p->input == AUTOBAL_ROTOR_HARDWARE)
    (void)autobal_rotor_lumped_from_hardware(&p->hw, &s->Lbase, NULL);
  else
    s->Lbase = p->lumped;
  s->L = s->Lbase;
  nstore = 9 * N + nmem + 1;
  if (N <= AUTOBAL_ROTOR_STAB_MAX_FULL_BALLS)
    nstore += 7 * s->ns * s->ns + 9 * s->ns + 2 * s->nm * s->nm;
  s->store = (double *)calloc(nstore, sizeof(double));
  if (s->store == NULL) goto nomem;
  s->m = s->store;
  s->r = s->m + N;
  s->h = s->r + N;
  s->psi_init = s->h + N;
  s->rate_init = s->psi_init + N;
  s->psi = s->rate_init + N;
  s->member_store = s->psi + N;
  s->m_save = s->member_store + nmem;
  s->h_save = s->m_save + N;
  s->r_save = s->h_save + N;
  {
    double *q = s->r_save + N;
    size_t o2 = 0;
    for (j = 0; j < p->n_planes; j++) {
      const autobal_rotor_plane *pl = &p->plane[j];
      s->off[j] = o2;
      s->cnt[j] = pl->n_balls;
      for (i = 0; i < pl->n_balls; i++) {
        s->m[o2 + i] = pl->ball_mass[i];
        s->r[o2 + i] = pl->ball_radius[i];
        s->h[o2 + i] = pl->ball_damping[i];
        s->psi_init[o2 + i] = pl->ball_psi ? pl->ball_psi[i] : 0.0;
        s->rate_init[o2 + i] = pl->ball_rate ? pl->ball_rate[i] : 0.0;
      }
      s->cur.plane[j].ball_mass = s->m + o2;
      s->cur.plane[j].ball_radius = s->r + o2;
      s->cur.plane[j].ball_damping = s->h + o2;
      s->cur.plane[j].ball_psi = s->psi_init + o2;
      s->cur.plane[j].ball_rate = s->rate_init + o2;
      /* member angles: copied; DEFAULT with n >= 3 unequal balls becomes FREE with the first
       * n - 2 angles of the default member at these parameters */
      {
        autobal_rotor_member *mb = &s->opt.member[j];
        double *dst = s->member_store + o2;
        if (mb->kind == AUTOBAL_ROTOR_MEMBER_FREE || mb->kind == AUTOBAL_ROTOR_MEMBER_GIVEN) {
          for (i = 0; i < mb->n_angles; i++) dst[i] = mb->angles[i];
          mb->angles = dst;
        } else if (mb->kind == AUTOBAL_ROTOR_MEMBER_DEFAULT && pl->n_balls >= 3) {
          int identical = 1;
          for (i = 1; i < pl->n_balls; i++)
            if (!autobal_rotor_close_rel_(pl->ball_mass[i] * pl->ball_radius[i],
                                          pl->ball_mass[0] * pl->ball_radius[0], 1e-12))
              identical = 0;
          if (!identical &&
              autobal_rotor_member_angles(&s->cur.plane[j], NULL, dst, pl->n_balls, NULL) ==
                  AUTOBAL_SUCCESS) {
            mb->kind = AUTOBAL_ROTOR_MEMBER_FREE;
            mb->n_angles = pl->n_balls - 2;
            mb->angles = dst;
          } else {
            mb->angles = NULL;
            mb->n_angles = 0;
          }
        } else {
          mb->angles = NULL;
          mb->n_angles = 0;
        }
      }
      o2 += pl->n_balls;
    }
    for (; j < AUTOBAL_ROTOR_MAX_PLANES; j++) memset(&s->opt.member[j], 0, sizeof s->opt.member[j]);
    if (N <= AUTOBAL_ROTOR_STAB_MAX_FULL_BALLS) {
      const size_t ns = s->ns, nm = s->nm;
      s->Afull = q;
      q += ns * ns;
      s->Ascaled = q;
      q += ns * ns;
      s->phi = q;
      q += 5 * ns * ns; /* phi and scratch for products */
      s->sc = q;
      q += ns;
      s->full_re = q;
      q += ns;
      s->full_im = q;
      q += ns;
      s->mu_re = q;
      q += ns;
      s->mu_im = q;
      q += ns;
      s->tmp_re = q;
      q += ns;
      s->tmp_im = q;
      q += ns;
      q += 2 * ns;
      s->Kt = q;
      q += nm * nm;
      s->Ct = q;
    }
  }
  s->pw = autobal_poly_workspace_alloc(AUTOBAL_ROTOR_POLY_LEN - 1);
  s->ew_closed = autobal_eigen_workspace_alloc(8 + 4 * s->n_planes);
  s->lu_closed = gsl_matrix_alloc(4 + 2 * s->n_planes, 4 + 2 * s->n_planes);
  s->perm_closed = gsl_permutation_alloc(4 + 2 * s->n_planes);
  if (!s->pw || !s->ew_closed || !s->lu_closed || !s->perm_closed) goto nomem;
  if (N <= AUTOBAL_ROTOR_STAB_MAX_FULL_BALLS) {
    autobal_transient_options to = autobal_transient_options_default();
    to.rtol = o.floquet_rtol;
    to.atol = o.floquet_atol;
    to.max_steps = 10000000UL;
    s->ew_full = autobal_eigen_workspace_alloc(s->ns);
    s->lu_full = gsl_matrix_alloc(s->nm, s->nm);
    s->perm_full = gsl_permutation_alloc(s->nm);
    s->vec_full = gsl_vector_alloc(s->nm);
    s->tr = autobal_transient_alloc(s->ns * s->ns, &to, NULL);
    if (!s->ew_full || !s->lu_full || !s->perm_full || !s->vec_full || !s->tr) goto nomem;
  }
  s->psi_status = AUTOBAL_EINVAL;
  autobal_error_clear(&s->err);
  if (err) *err = e; /* success or the warning of autobal_rotor_params_check */
  return s;
nomem:
  autobal_rotor_stab_free(s);
  autobal_error_set(err, AUTOBAL_ENOMEM, "rotor stability: out of memory");
  return NULL;
}

const autobal_rotor_params *autobal_rotor_stab_params(const autobal_rotor_stab *s) {
  return s ? &s->cur : NULL;
}
size_t autobal_rotor_stab_n_balls(const autobal_rotor_stab *s) { return s ? s->N : 0; }

static void scale_lumped(autobal_rotor_stab *s) {
  const autobal_rotor_lumped *B = &s->Lbase;
  autobal_rotor_lumped *L = &s->L;
  const double f = s->c_scale, g = s->h_scale;
  L->M = B->M; /* the inertias are not scaled */
  L->A = B->A;
  L->C = B->C;
  L->c_x = f * B->c_x;
  L->c_y = f * B->c_y;
  L->c_z = f * B->c_z;
  L->c_alpha = f * B->c_alpha;
  L->c_beta = f * B->c_beta;
  L->c_xbeta = f * B->c_xbeta;
  L->c_yalpha = f * B->c_yalpha;
  L->h_x = g * B->h_x;
  L->h_y = g * B->h_y;
  L->h_z = g * B->h_z;
  L->h_alpha = g * B->h_alpha;
  L->h_beta = g * B->h_beta;
  L->h_xbeta = g * B->h_xbeta;
  L->h_yalpha = g * B->h_yalpha;
  /* keep the working parameters consistent (lumped input with the scaled set) */
  s->cur.input = AUTOBAL_ROTOR_LUMPED;
  s->cur.lumped = *L;
}

/* A new base lumped set (before the scale factors): checked as the model checks its input
 * (autobal_rotor_params_check on the working parameters with it), then taken. */
static int take_lumped_base(autobal_rotor_stab *s, const char *key, const autobal_rotor_lumped *Lb) {
  autobal_rotor_params cand = s->cur;
  autobal_rotor_lumped save = s->Lbase, Lsave = s->L;
  const int input_save = s->cur.input;
  autobal_error e;
  int st;
  s->Lbase = *Lb;
  scale_lumped(s); /* s->L and s->cur.lumped from the new base */
  cand.input = AUTOBAL_ROTOR_LUMPED;
  cand.lumped = s->L;
  autobal_error_clear(&e);
  st = autobal_rotor_params_check(&cand, &e);
  if (st < 0) {
    s->Lbase = save;
    s->L = Lsave;
    s->cur.lumped = Lsave;
    s->cur.input = input_save;
    return autobal_error_set(&s->err, st, "%s: %.900s", key, e.message);
  }
  return AUTOBAL_SUCCESS;
}

/* A hardware set: converted to the lumped base ((2.7), (2.9), (2.11)) and taken. */
static int take_hardware(autobal_rotor_stab *s, const char *key, const autobal_rotor_hardware *hw) {
  autobal_rotor_lumped Lb;
  autobal_error e;
  int st;
  autobal_error_clear(&e);
  if ((st = autobal_rotor_lumped_from_hardware(hw, &Lb, &e)) != AUTOBAL_SUCCESS)
    return autobal_error_set(&s->err, st, "%s: %.900s", key, e.message);
  if ((st = take_lumped_base(s, key, &Lb)) != AUTOBAL_SUCCESS) return st;
  s->cur.hw = *hw;
  return AUTOBAL_SUCCESS;
}

static int need_input(autobal_rotor_stab *s, const char *key, int input) {
  if (s->input0 == input) return AUTOBAL_SUCCESS;
  return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                           "%s: the rotor is given %s, so this key is not one of its parameters (use the %s keys)", key,
                           s->input0 == AUTOBAL_ROTOR_HARDWARE ? "by its hardware ([rotor], [supports])"
                                                              : "as a lumped set ([lumped])",
                           s->input0 == AUTOBAL_ROTOR_HARDWARE ? "rotor.* and supports.*" : "lumped.*");
}

/* autobal_rotor_stab_set for the ids beyond the named ones that change the supports or the
 * inertia (ANISOTROPY, C_OVER_A), the hardware and lumped fields, and the plane keys. */
static int set_key(autobal_rotor_stab *s, int param, double value) {
  const autobal_rotor_field *f;
  const char *key = autobal_rotor_stab_param_name(param);
  int lumped, pk, st;
  size_t j, i;
  if (key == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "parameter id %d is not valid (see autobal_rotor_stab_param_list)", param);
  if (param == AUTOBAL_ROTOR_PARAM_ANISOTROPY || param == AUTOBAL_ROTOR_PARAM_C_OVER_A) {
    const int an = param == AUTOBAL_ROTOR_PARAM_ANISOTROPY;
    if ((st = autobal_check_param(&s->err, key, value, 0.0, an, INFINITY, 1, "")) != AUTOBAL_SUCCESS) return st;
    if (s->input0 == AUTOBAL_ROTOR_HARDWARE) {
      autobal_rotor_hardware hw = s->cur.hw;
      if (an) {
        hw.c_Ly = value * hw.c_Lx;
        hw.c_Ry = value * hw.c_Rx;
      } else {
        hw.C_p = value * (hw.A_k + hw.A_p);
      }
      return take_hardware(s, key, &hw);
    } else {
      autobal_rotor_lumped Lb = s->Lbase;
      if (an) {
        Lb.c_y = value * Lb.c_x;
        Lb.c_alpha = value * Lb.c_beta;
        Lb.c_yalpha = value * Lb.c_xbeta;
      } else {
        Lb.C = value * Lb.A;
      }
      return take_lumped_base(s, key, &Lb);
    }
  }
  if ((f = param_field(param, &lumped)) != NULL) {
    if ((st = need_input(s, key, lumped ? AUTOBAL_ROTOR_LUMPED : AUTOBAL_ROTOR_HARDWARE)) != AUTOBAL_SUCCESS)
      return st;
    if (!isfinite(value))
      return autobal_check_param(&s->err, key, value, -INFINITY, 1, INFINITY, 1, f->unit);
    if (lumped) {
      autobal_rotor_lumped Lb = s->Lbase;
      *autobal_rotor_field_ptr(&Lb, f) = value;
      return take_lumped_base(s, key, &Lb);
    } else {
      autobal_rotor_hardware hw = s->cur.hw;
      *autobal_rotor_field_ptr(&hw, f) = value;
      return take_hardware(s, key, &hw);
    }
  }
  if (!param_plane(param, &j, &pk))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "parameter id %d is not valid", param);
  if (j >= s->n_planes)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "%s: the rotor has %zu balancing plane%s", key, s->n_planes,
                             s->n_planes == 1 ? "" : "s");
  if (pk >= AUTOBAL_ROTOR_PLANE_BALL_MASS) {
    const size_t o = s->off[j], n = s->cnt[j];
    double *a = pk == AUTOBAL_ROTOR_PLANE_BALL_MASS ? s->m : (pk == AUTOBAL_ROTOR_PLANE_BALL_RADIUS ? s->r : s->h);
    if (n == 0) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "%s: plane %zu has no balls", key, j + 1);
    if ((st = autobal_check_param(&s->err, key, value, 0.0, pk != AUTOBAL_ROTOR_PLANE_BALL_DAMPING, INFINITY, 1,
                                  plane_units[pk])) != AUTOBAL_SUCCESS)
      return st;
    for (i = 0; i < n; i++) a[o + i] = value;
    return AUTOBAL_SUCCESS;
  }
  {
    autobal_rotor_plane *pl = &s->cur.plane[j];
    switch (pk) {
      case AUTOBAL_ROTOR_PLANE_D:
      case AUTOBAL_ROTOR_PLANE_PSI0:
        if ((st = autobal_check_param(&s->err, key, value, -INFINITY, 1, INFINITY, 1, plane_units[pk])))
          return st;
        if (pk == AUTOBAL_ROTOR_PLANE_D)
          pl->d = value;
        else
          pl->psi0 = value;
        return AUTOBAL_SUCCESS;
      case AUTOBAL_ROTOR_PLANE_M0:
      case AUTOBAL_ROTOR_PLANE_R0:
        if ((st = autobal_check_param(&s->err, key, value, 0.0, 0, INFINITY, 1, plane_units[pk]))) return st;
        if (pk == AUTOBAL_ROTOR_PLANE_M0)
          pl->m0 = value;
        else
          pl->r0 = value;
        return AUTOBAL_SUCCESS;
      default: /* UNBALANCE: m0 = value / r0 */
        if ((st = autobal_check_param(&s->err, key, value, 0.0, 0, INFINITY, 1, plane_units[pk]))) return st;
        if (!(pl->r0 > 0.0))
          return autobal_error_set(&s->err, AUTOBAL_EINVAL, "%s: needs r0 > 0 (m0 = unbalance / r0); r0 = %g m", key,
                                   pl->r0);
        pl->m0 = value / pl->r0;
        return AUTOBAL_SUCCESS;
    }
  }
}

static double get_key(const autobal_rotor_stab *s, int param) {
  const autobal_rotor_field *f;
  int lumped, pk;
  size_t j;
  if (param == AUTOBAL_ROTOR_PARAM_ANISOTROPY) return s->Lbase.c_y / s->Lbase.c_x;
  if (param == AUTOBAL_ROTOR_PARAM_C_OVER_A) return s->Lbase.C / s->Lbase.A;
  if ((f = param_field(param, &lumped)) != NULL) {
    if (lumped != (s->input0 == AUTOBAL_ROTOR_LUMPED)) return NAN;
    return lumped ? autobal_rotor_field_get(&s->Lbase, f) : autobal_rotor_field_get(&s->cur.hw, f);
  }
  if (!param_plane(param, &j, &pk) || j >= s->n_planes) return NAN;
  switch (pk) {
    case AUTOBAL_ROTOR_PLANE_D: return s->cur.plane[j].d;
    case AUTOBAL_ROTOR_PLANE_M0: return s->cur.plane[j].m0;
    case AUTOBAL_ROTOR_PLANE_R0: return s->cur.plane[j].r0;
    case AUTOBAL_ROTOR_PLANE_PSI0: return s->cur.plane[j].psi0;
    case AUTOBAL_ROTOR_PLANE_UNBALANCE: return s->cur.plane[j].m0 * s->cur.plane[j].r0;
    case AUTOBAL_ROTOR_PLANE_BALL_MASS: return s->cnt[j] ? s->m[s->off[j]] : NAN;
    case AUTOBAL_ROTOR_PLANE_BALL_RADIUS: return s->cnt[j] ? s->r[s->off[j]] : NAN;
    default: return s->cnt[j] ? s->h[s->off[j]] : NAN;
  }
}

int autobal_rotor_stab_set(autobal_rotor_stab *s, int param, double value) {
  int st;
  size_t i, j;
  if (s == NULL) return AUTOBAL_EINVAL;
  switch (param) {
    case AUTOBAL_ROTOR_PARAM_OMEGA:
      if ((st = autobal_check_param(&s->err, "omega", value, -INFINITY, 1, INFINITY, 1, "rad/s")))
        return st;
      s->cur.omega = value;
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_BALL_DAMPING:
      if ((st = autobal_check_param(&s->err, "ball_damping", value, 0.0, 0, INFINITY, 1, "kg/s")))
        return st;
      for (i = 0; i < s->N; i++) s->h[i] = value;
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_BALL_MASS:
      if ((st = autobal_check_param(&s->err, "ball_mass", value, 0.0, 1, INFINITY, 1, "kg")))
        return st;
      for (i = 0; i < s->N; i++) s->m[i] = value;
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_STIFFNESS_SCALE:
      if ((st = autobal_check_param(&s->err, "stiffness_scale", value, 0.0, 1, INFINITY, 1, "")))
        return st;
      s->c_scale = value;
      scale_lumped(s);
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_DAMPING_SCALE:
      if ((st = autobal_check_param(&s->err, "damping_scale", value, 0.0, 0, INFINITY, 1, "")))
        return st;
      s->h_scale = value;
      scale_lumped(s);
      return AUTOBAL_SUCCESS;
    case AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS:
      if ((st = autobal_check_param(&s->err, "unbalance_mass", value, 0.0, 0, INFINITY, 1, "kg")))
        return st;
      for (j = 0; j < s->n_planes; j++) s->cur.plane[j].m0 = value;
      return AUTOBAL_SUCCESS;
    default:
      return set_key(s, param, value);
  }
}

double autobal_rotor_stab_get(const autobal_rotor_stab *s, int param) {
  if (s == NULL) return NAN;
  switch (param) {
    case AUTOBAL_ROTOR_PARAM_OMEGA: return s->cur.omega;
    case AUTOBAL_ROTOR_PARAM_BALL_DAMPING: return s->N ? s->h[0] : NAN;
    case AUTOBAL_ROTOR_PARAM_BALL_MASS: return s->N ? s->m[0] : NAN;
    case AUTOBAL_ROTOR_PARAM_STIFFNESS_SCALE: return s->c_scale;
    case AUTOBAL_ROTOR_PARAM_DAMPING_SCALE: return s->h_scale;
    case AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS: return s->cur.plane[0].m0;
    default: return get_key(s, param);
  }
}

int autobal_rotor_stab_update_member_(autobal_rotor_stab *s) {
  size_t j;
  int st = AUTOBAL_SUCCESS;
  for (j = 0; j < s->n_planes && st == AUTOBAL_SUCCESS; j++) {
    st = autobal_rotor_member_angles(&s->cur.plane[j], &s->opt.member[j], s->psi + s->off[j],
                                     s->cnt[j], &s->err);
    if (st != AUTOBAL_SUCCESS) {
      char tmp[AUTOBAL_ERRMSG_SIZE];
      snprintf(tmp, sizeof tmp, "%s", s->err.message);
      autobal_error_set(&s->err, st, "plane %zu: %.480s", j + 1, tmp);
    }
  }
  s->psi_status = st;
  return st;
}

size_t autobal_rotor_stab_family_(const autobal_rotor_stab *s) {
  size_t j, f = 0;
  for (j = 0; j < s->n_planes; j++)
    f += s->cnt[j] - autobal_rotor_plane_rank_(s->m + s->off[j], s->r + s->off[j], s->psi + s->off[j], s->cnt[j]);
  return f;
}

int autobal_rotor_stab_balanced_angles(autobal_rotor_stab *s, double *psi, size_t n) {
  int st;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (n != s->N || (n > 0 && psi == NULL))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "balanced angles: n = %zu, need N = %zu", n,
                             s->N);
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) return st;
  if (n) memcpy(psi, s->psi, n * sizeof *psi);
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_stab_closed(autobal_rotor_stab *s, autobal_rotor_closed *c) {
  int st;
  if (s == NULL || c == NULL) return AUTOBAL_EINVAL;
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) return st;
  autobal_rotor_stab_closed_from_handle_(s, c);
  return AUTOBAL_SUCCESS;
}
