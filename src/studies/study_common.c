/* study_common.c: what every study shares: the archive writers of the model parameters and of the transient driver's statistics, and the
 * ISO 21940-11 balance quality figures (include/autobal/study.h). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "autobal/study.h"

/* The field tables (autobal_rotor_hardware_fields, autobal_rotor_lumped_fields) live in the model
 * layer: src/models/rotor/rotor_fields.c. */

int autobal_study_write_rotor_params(autobal_archive *a, const autobal_rotor_params *p, int initial) {
  autobal_rotor_lumped L;
  const char *g = "/rotor", *gl = "/rotor/lumped";
  char grp[64];
  size_t i, j, n_hw, n_lumped;
  const autobal_rotor_field *k_hw_fields = autobal_rotor_hardware_fields(&n_hw);
  const autobal_rotor_field *k_lumped_fields = autobal_rotor_lumped_fields(&n_lumped);
  int st;
  if (!a || !p) return AUTOBAL_EINVAL;
  /* the coefficients the model uses (autobal_rotor_alloc does the same) */
  if (p->input == AUTOBAL_ROTOR_HARDWARE) {
    if ((st = autobal_rotor_lumped_from_hardware(&p->hw, &L, NULL))) return st;
  } else {
    L = p->lumped;
  }
  st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "model", "rotor in a massive housing with ball autobalancers (docs/rotor.md)");
  if (!st) st = autobal_archive_attr_string(a, g, "input", p->input == AUTOBAL_ROTOR_LUMPED ? "lumped" : "hardware");
  if (!st) st = autobal_archive_attr_string(a, g, "inertia", p->inertia == AUTOBAL_ROTOR_INERTIA_FULL ? "full" : "paper");
  if (!st) st = autobal_archive_attr_double(a, g, "omega", p->omega, "rad/s");
  if (!st) st = autobal_archive_attr_int(a, g, "axial", p->axial);
  if (!st && p->gravity) { /* docs/device.md section 2; absent when off (the layout before gravity) */
    double qs[4];
    st = autobal_archive_attr_int(a, g, "gravity", 1);
    if (!st) st = autobal_archive_attr_double(a, g, "shaft_angle", p->shaft_angle, "rad");
    if (!st) st = autobal_archive_attr_double(a, g, "g", p->g, "m/s^2");
    if (!st) st = autobal_archive_attr_double(a, g, "g_in_plane", p->g * sin(p->shaft_angle), "m/s^2");
    if (!st) st = autobal_rotor_static_offset(p, qs);
    if (!st) st = autobal_archive_attr_double(a, g, "static_offset_y", qs[1], "m");
    if (!st) st = autobal_archive_attr_double(a, g, "static_offset_alpha", qs[2], "rad");
  }
  for (i = 0; p->input == AUTOBAL_ROTOR_HARDWARE && i < n_hw && !st; i++)
    st = autobal_archive_attr_double(a, g, k_hw_fields[i].name, autobal_rotor_field_get(&p->hw, &k_hw_fields[i]),
                                     k_hw_fields[i].unit);
  if (!st) st = autobal_archive_group(a, gl);
  for (i = 0; i < n_lumped && !st; i++)
    st = autobal_archive_attr_double(a, gl, k_lumped_fields[i].name, autobal_rotor_field_get(&L, &k_lumped_fields[i]),
                                     k_lumped_fields[i].unit);
  for (j = 0; j < p->n_planes && j < AUTOBAL_ROTOR_MAX_PLANES && !st; j++) {
    const autobal_rotor_plane *pl = &p->plane[j];
    snprintf(grp, sizeof grp, "/rotor/plane%zu", j + 1);
    st = autobal_archive_group(a, grp);
    if (!st) st = autobal_archive_attr_double(a, grp, "d", pl->d, "m");
    if (!st) st = autobal_archive_attr_double(a, grp, "m0", pl->m0, "kg");
    if (!st) st = autobal_archive_attr_double(a, grp, "r0", pl->r0, "m");
    if (!st) st = autobal_archive_attr_double(a, grp, "psi0", pl->psi0, "rad");
    if (!st) st = autobal_archive_attr_int(a, grp, "n_balls", (long)pl->n_balls);
    if (!st && pl->n_balls > 0) {
      st = autobal_archive_attr_double_array(a, grp, "ball_mass", pl->n_balls, pl->ball_mass, "kg");
      if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_radius", pl->n_balls, pl->ball_radius, "m");
      if (!st) st = autobal_archive_attr_double_array(a, grp, "ball_damping", pl->n_balls, pl->ball_damping, "kg/s");
      if (!st && initial && pl->ball_psi)
        st = autobal_archive_attr_double_array(a, grp, "ball_psi_initial", pl->n_balls, pl->ball_psi, "rad");
      if (!st && initial && pl->ball_rate)
        st = autobal_archive_attr_double_array(a, grp, "ball_rate_initial", pl->n_balls, pl->ball_rate, "rad/s");
    }
  }
  return st;
}

int autobal_study_write_pendulum_params(autobal_archive *a, const autobal_pendulum_params *p,
                                        const autobal_pendulum_physical *phys) {
  const char *g = "/pendulum", *gp = "/pendulum/physical";
  int st;
  if (!a || !p) return AUTOBAL_EINVAL;
  st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_attr_string(a, g, "model", "planar two-pendulum autobalancer (docs/pendulum.md)");
  if (!st) st = autobal_archive_attr_double(a, g, "R_w", p->R_w, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "R_m", p->R_m, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "H", p->H, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "h", p->h, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "psi0", p->psi0, "rad");
  if (!st) st = autobal_archive_attr_double(a, g, "k", autobal_pendulum_k(p), "1");
  if (!st && phys) {
    st = autobal_archive_group(a, gp);
    if (!st) st = autobal_archive_attr_double(a, gp, "M", phys->M, "kg");
    if (!st) st = autobal_archive_attr_double(a, gp, "e", phys->e, "m");
    if (!st) st = autobal_archive_attr_double(a, gp, "m", phys->m, "kg");
    if (!st) st = autobal_archive_attr_double(a, gp, "l", phys->l, "m");
    if (!st) st = autobal_archive_attr_double(a, gp, "c", phys->c, "N/m");
    if (!st) st = autobal_archive_attr_double(a, gp, "H1", phys->H1, "N m s");
    if (!st) st = autobal_archive_attr_double(a, gp, "H2", phys->H2, "N s/m");
    if (!st) st = autobal_archive_attr_double(a, gp, "omega", phys->omega, "rad/s");
    if (!st) st = autobal_archive_attr_double(a, gp, "omega0", sqrt(phys->c / (phys->M + 2.0 * phys->m)), "rad/s");
  }
  return st;
}

int autobal_study_write_solver_stats(autobal_archive *a, const char *group, const char *stepper,
                                     const autobal_transient_stats *stats, const char *message,
                                     const char *time_unit) {
  int st;
  if (!a || !group || !stats || !time_unit) return AUTOBAL_EINVAL;
  st = autobal_archive_group(a, group);
  if (!st) st = autobal_archive_attr_string(a, group, "stepper", stepper ? stepper : "rk8pd");
  if (!st) st = autobal_archive_attr_int(a, group, "steps", (long)stats->steps);
  if (!st) st = autobal_archive_attr_int(a, group, "rejected_steps", (long)stats->rejected);
  if (!st) st = autobal_archive_attr_int(a, group, "rhs_evaluations", (long)stats->rhs_evals);
  if (!st) st = autobal_archive_attr_int(a, group, "jacobian_evaluations", (long)stats->jac_evals);
  if (!st) st = autobal_archive_attr_double(a, group, "wall_time", stats->wall_seconds, "s");
  if (!st) st = autobal_archive_attr_double(a, group, "h_min_used", stats->h_min_used, time_unit);
  if (!st) st = autobal_archive_attr_double(a, group, "h_max_used", stats->h_max_used, time_unit);
  if (!st) st = autobal_archive_attr_string(a, group, "stop_reason", autobal_transient_stop_name(stats->stop_reason));
  if (!st) st = autobal_archive_attr_string(a, group, "message", message ? message : "");
  return st;
}

double autobal_balance_grade(double U, double m, double omega) { return U / m * omega * 1e3; }
double autobal_permissible_unbalance(double G, double m, double omega) { return G * 1e-3 / omega * m; }
double autobal_balance_grade_class(double G) {
  static const double k[] = {0.4, 1, 2.5, 6.3, 16, 40, 100, 250, 630, 1600, 4000};
  size_t i;
  for (i = 0; i < sizeof k / sizeof k[0]; i++)
    if (G <= k[i]) return k[i];
  return NAN;
}
