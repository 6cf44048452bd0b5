/* root_bracket.c: model-agnostic root finding in a bracket: Brent's method on a scalar
 * function and bisection of a predicate.  See include/autobal/stability.h for the contracts.
 *
 * May use: core (internal.h), libm.  No model, no I/O. */
#include "autobal/stability.h"
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------------ */
/* Brent's method and bisection of a predicate                              */
/* ------------------------------------------------------------------------ */

int autobal_root_brent(autobal_scalar_fn f, void *ctx, double a, double b, double xtol_abs,
                       double xtol_rel, int max_iter, double *root, autobal_error *err) {
  double fa, fb, c, fc, d, e;
  int st, it;
  if (f == NULL || root == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_root_brent: NULL argument");
  if (!(xtol_abs >= 0.0) || !(xtol_rel >= 0.0) || !isfinite(xtol_abs) || !isfinite(xtol_rel) ||
      (xtol_abs == 0.0 && xtol_rel == 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_root_brent: tolerances xtol_abs = %g, xtol_rel = %g: need "
                             ">= 0, finite, not both 0",
                             xtol_abs, xtol_rel);
  if (max_iter < 1)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "parameter max_iter = %d is out of range: allowed [1, inf)", max_iter);
  if (!isfinite(a) || !isfinite(b))
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_root_brent: bracket [%g, %g] not finite",
                             a, b);
  if ((st = f(a, ctx, &fa)) != AUTOBAL_SUCCESS) return st;
  if ((st = f(b, ctx, &fb)) != AUTOBAL_SUCCESS) return st;
  if (fa == 0.0) {
    *root = a;
    return AUTOBAL_SUCCESS;
  }
  if (fb == 0.0) {
    *root = b;
    return AUTOBAL_SUCCESS;
  }
  if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0)))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_root_brent: f(a) = %g and f(b) = %g at a = %.17g, b = %.17g "
                             "do not bracket a root",
                             fa, fb, a, b);
  c = a;
  fc = fa;
  d = e = b - a;
  for (it = 0; it < max_iter; it++) {
    double tol, m, p, q, r, s;
    if ((fb > 0 && fc > 0) || (fb < 0 && fc < 0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (fabs(fc) < fabs(fb)) {
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    tol = 2.0 * DBL_EPSILON * fabs(b) + 0.5 * (xtol_abs + xtol_rel * fabs(b));
    m = 0.5 * (c - b);
    if (fabs(m) <= tol || fb == 0.0) {
      *root = b;
      return AUTOBAL_SUCCESS;
    }
    if (fabs(e) >= tol && fabs(fa) > fabs(fb)) {
      s = fb / fa;
      if (a == c) {
        p = 2.0 * m * s;
        q = 1.0 - s;
      } else {
        q = fa / fc;
        r = fb / fc;
        p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0));
        q = (q - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0) q = -q;
      else p = -p;
      if (2.0 * p < 3.0 * m * q - fabs(tol * q) && p < fabs(0.5 * e * q)) {
        e = d;
        d = p / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    if (fabs(d) > tol) b += d;
    else b += m > 0 ? tol : -tol;
    if ((st = f(b, ctx, &fb)) != AUTOBAL_SUCCESS) return st;
  }
  *root = b;
  return autobal_error_set(err, AUTOBAL_ENUMERIC,
                           "autobal_root_brent: no convergence in max_iter = %d iterations (best "
                           "estimate %.17g)",
                           max_iter, b);
}

int autobal_bisect_change(autobal_predicate_fn p, void *ctx, double a, double b, double xtol_abs,
                          double xtol_rel, double *lo, double *hi, autobal_error *err) {
  int pa, pb, st;
  if (p == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "autobal_bisect_change: NULL predicate");
  if (!isfinite(a) || !isfinite(b) || !(a < b))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_bisect_change: bracket [%g, %g] must be finite with a < b", a,
                             b);
  if (!(xtol_abs >= 0.0) || !(xtol_rel >= 0.0) || !isfinite(xtol_abs) || !isfinite(xtol_rel) ||
      (xtol_abs == 0.0 && xtol_rel == 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_bisect_change: tolerances xtol_abs = %g, xtol_rel = %g: need "
                             ">= 0, finite, not both 0",
                             xtol_abs, xtol_rel);
  if ((st = p(a, ctx, &pa)) != AUTOBAL_SUCCESS) return st;
  if ((st = p(b, ctx, &pb)) != AUTOBAL_SUCCESS) return st;
  if (pa == pb)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "autobal_bisect_change: the predicate has the same value %d at both "
                             "ends %.17g and %.17g",
                             pa, a, b);
  while (b - a > xtol_abs + xtol_rel * fabs(b)) {
    double mid = a + 0.5 * (b - a);
    int pm;
    if (mid <= a || mid >= b) break; /* adjacent doubles */
    if ((st = p(mid, ctx, &pm)) != AUTOBAL_SUCCESS) return st;
    if (pm == pa) a = mid;
    else b = mid;
  }
  if (lo) *lo = a;
  if (hi) *hi = b;
  return AUTOBAL_SUCCESS;
}
