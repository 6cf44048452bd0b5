/* pendulum_roots.c: the pendulum roots study (`autobal pendulum roots`): the linear stability of
 * the main motion (4) and its archive layout (include/autobal/study.h). */
#include <string.h>

#include "autobal/study.h"
#include "internal.h"

int autobal_study_pendulum_roots(const autobal_pendulum_params *p, const autobal_pendulum_physical *phys,
                                 autobal_archive *a, autobal_pendulum_result *result, autobal_error *err) {
  autobal_pendulum_workspace *ws;
  int st;
  autobal_error_clear(err);
  if (!p || !result) return autobal_error_set(err, AUTOBAL_EINVAL, "parameters or result: NULL");
  memset(result, 0, sizeof *result);
  ws = autobal_pendulum_workspace_alloc();
  if (!ws) return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory");
  st = autobal_pendulum_analyze(ws, p, result);
  if (st != AUTOBAL_SUCCESS) {
    autobal_error_set(err, st, "%s", autobal_pendulum_errmsg(ws));
    autobal_pendulum_workspace_free(ws);
    return st;
  }
  autobal_pendulum_workspace_free(ws);
  if (a && (st = autobal_study_pendulum_roots_write(a, p, phys, result)))
    return autobal_error_set(err, st, "%s", autobal_archive_errmsg(a));
  return AUTOBAL_SUCCESS;
}

const char *autobal_study_pendulum_roots_criterion(const autobal_pendulum_result *r) {
  if (!r) return "";
  return r->undamped ? "exact undamped criterion (10)" : "Routh-Hurwitz on (6)";
}

int autobal_study_pendulum_roots_write(autobal_archive *a, const autobal_pendulum_params *p,
                                       const autobal_pendulum_physical *phys, const autobal_pendulum_result *r) {
  static const char *const dim_root[] = {"root"};
  static const char *const dim_power[] = {"power"};
  double power[AUTOBAL_PENDULUM_NCOEF];
  const char *g = "/pendulum/roots";
  size_t i;
  int st;
  if (!a || !p || !r) return AUTOBAL_EINVAL;
  for (i = 0; i < AUTOBAL_PENDULUM_NCOEF; i++) power[i] = (double)i;
  st = autobal_study_write_pendulum_params(a, p, phys);
  if (!st) st = autobal_archive_group(a, g);
  if (!st) st = autobal_archive_dim(a, g, "root", AUTOBAL_PENDULUM_ORDER, "index of a characteristic root");
  if (!st) st = autobal_archive_coord(a, g, "power", AUTOBAL_PENDULUM_NCOEF, power, "1", "power of lambda");
  if (!st) st = autobal_archive_var(a, g, "char_poly", 1, dim_power, r->coef, "1", "coefficients of the characteristic polynomial (6), ascending powers of lambda");
  if (!st) st = autobal_archive_var(a, g, "root_real", 1, dim_root, r->root_re, "1", "real part of the roots of (6) (dimensionless, per tau)");
  if (!st) st = autobal_archive_var(a, g, "root_imag", 1, dim_root, r->root_im, "1", "imaginary part of the roots of (6)");
  if (!st) st = autobal_archive_var(a, g, "eig_real", 1, dim_root, r->eig_re, "1", "real part of the eigenvalues of the 8x8 matrix of (5), matched to the roots");
  if (!st) st = autobal_archive_var(a, g, "eig_imag", 1, dim_root, r->eig_im, "1", "imaginary part of the eigenvalues of the 8x8 matrix of (5), matched to the roots");
  if (!st) st = autobal_archive_attr_string(a, g, "verdict", autobal_verdict_name(r->verdict));
  if (!st) st = autobal_archive_attr_string(a, g, "criterion", autobal_study_pendulum_roots_criterion(r));
  if (!st) st = autobal_archive_attr_string(a, g, "verdict_roots", autobal_verdict_name(r->verdict_roots));
  if (!st) st = autobal_archive_attr_double(a, g, "max_real", r->max_real, "1");
  if (!st) st = autobal_archive_attr_double(a, g, "root_eig_mismatch", r->mismatch, "1");
  if (!st) st = autobal_archive_attr_int(a, g, "n_right_half_plane", r->n_rhp);
  if (!st) st = autobal_archive_attr_int(a, g, "cond7_applicable", r->cond7.applicable);
  if (!st) st = autobal_archive_attr_int(a, g, "cond7_predicts_stable", r->cond7.predicts_stable);
  if (!st) st = autobal_archive_attr_int(a, g, "cond8_applicable", r->cond8.applicable);
  if (!st) st = autobal_archive_attr_int(a, g, "cond8_predicts_stable", r->cond8.predicts_stable);
  if (!st) st = autobal_archive_attr_int(a, g, "cond9_applicable", r->cond9.applicable);
  if (!st) st = autobal_archive_attr_int(a, g, "cond9_predicts_stable", r->cond9.predicts_stable);
  return st;
}
