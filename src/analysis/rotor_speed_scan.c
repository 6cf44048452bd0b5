/* rotor_speed_scan.c: the speed scan behind the every-unbalance speed sets (one plane:
 * rotor_unbalance.c, two planes: rotor_unbalance2.c): a verdict "stable for all" on a grid of
 * speeds, each change bisected (docs/rotor.md "Every unbalance").
 *
 * May use: the handle (rotor_stab_handle.h). */
#include <math.h>
#include <string.h>

#include "analysis/rotor_stab_handle.h"
#include "analysis/rotor_stability.h"
#include "internal.h"

int autobal_rotor_scan_speeds_(autobal_rotor_stab *s, double w_lo, double w_hi, size_t n_grid, double xtol_rel,
                               autobal_rotor_speed_verdict_fn_ fn, void *user, autobal_rotor_crit *out) {
  double w0, prev_w = 0.0;
  int prev = 0, st = AUTOBAL_SUCCESS, open = 0;
  size_t k;
  memset(out, 0, sizeof *out);
  out->param = AUTOBAL_ROTOR_PARAM_OMEGA;
  if (!(isfinite(w_lo) && isfinite(w_hi) && w_lo < w_hi && (w_lo > 0.0 || w_hi < 0.0)))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL,
                             "every unbalance: the speed range [%g, %g] rad/s must be finite, lo < hi, and not "
                             "contain 0",
                             w_lo, w_hi);
  if (n_grid < 2 || n_grid > 100000000)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance: n_grid = %zu must be in [2, 1e8]", n_grid);
  if (!(xtol_rel > 0.0 && xtol_rel < 0.1))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "every unbalance: xtol_rel = %g must be in (0, 0.1)",
                             xtol_rel);
  w0 = s->cur.omega;
  for (k = 0; k < n_grid; k++) {
    const double w = w_lo + (w_hi - w_lo) * (double)k / (double)(n_grid - 1);
    int v;
    size_t ev = 0;
    if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w)) != AUTOBAL_SUCCESS) break;
    if ((st = fn(s, user, &v, &ev)) != AUTOBAL_SUCCESS) break;
    out->evaluations += ev;
    if (k > 0 && v != prev) {
      /* refine the change by bisection on the verdict */
      double x0 = prev_w, x1 = w;
      while (fabs(x1 - x0) > xtol_rel * fmax(fabs(x0), fabs(x1))) {
        const double xm = 0.5 * (x0 + x1);
        int vm;
        if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, xm)) != AUTOBAL_SUCCESS) break;
        ev = 0;
        if ((st = fn(s, user, &vm, &ev)) != AUTOBAL_SUCCESS) break;
        out->evaluations += ev;
        if (vm == prev) x0 = xm;
        else x1 = xm;
      }
      if (st != AUTOBAL_SUCCESS) break;
      if (out->n >= AUTOBAL_ROTOR_MAX_CRIT) {
        out->truncated = 1;
        st = AUTOBAL_WARNING;
        autobal_error_set(&s->err, AUTOBAL_WARNING,
                          "every unbalance: more than %d changes of the verdict; the results cover [%g, %g] rad/s",
                          AUTOBAL_ROTOR_MAX_CRIT, w_lo, out->value[out->n - 1]);
        break;
      }
      out->value[out->n] = 0.5 * (x0 + x1);
      out->kind[out->n] = v ? 1 : -1;
      if (v) {
        out->stable_lo[out->n_stable] = out->value[out->n];
        open = 1;
      } else if (open) {
        out->stable_hi[out->n_stable++] = out->value[out->n];
        open = 0;
      }
      out->n++;
    } else if (k == 0 && v) {
      out->stable_lo[0] = w_lo;
      open = 1;
    }
    prev = v;
    prev_w = w;
    if (autobal_rotor_stab_cancelled_(s)) {
      st = autobal_error_set(&s->err, AUTOBAL_ECANCELLED, "every unbalance: cancelled by the caller");
      break;
    }
  }
  if (st == AUTOBAL_SUCCESS && open) out->stable_hi[out->n_stable++] = w_hi;
  {
    const int st1 = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_OMEGA, w0);
    if (st == AUTOBAL_SUCCESS) st = st1;
  }
  return st;
}
