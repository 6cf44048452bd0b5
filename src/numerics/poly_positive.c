/* poly_positive.c: the positive real roots of a long double polynomial of degree <= 63, found in
 * double precision on a scaled variable and polished in long double (src/internal.h).  Shared by
 * the critical-unbalance searches of src/analysis/rotor_unbalance.c, rotor_unbalance2.c and
 * rotor_margin_set.c. */
#include <math.h>

#include "autobal/stability.h"
#include "internal.h"

int autobal_poly_positive_roots_tol_(const long double *h, size_t n, long double z2, double trim, double near,
                                     long double *z, size_t *nz, autobal_error *err) {
  double hs[64], re[63], im[63], big = 0.0;
  long double pw = 1.0L;
  size_t i, deg;
  int st;
  *nz = 0;
  if (n > 64 || n < 2) return autobal_error_set(err, AUTOBAL_EINVAL, "positive roots: %zu coefficients (2 .. 64)", n);
  for (i = 0; i < n; i++) {
    hs[i] = (double)(h[i] * pw);
    pw *= z2;
    big = fmax(big, fabs(hs[i]));
  }
  deg = n - 1;
  while (deg > 0 && !(fabs(hs[deg]) > trim * big)) deg--;
  if (deg < 1 || !(big > 0.0)) return AUTOBAL_SUCCESS;
  {
    autobal_poly_workspace *w = autobal_poly_workspace_alloc(deg);
    if (!w) return autobal_error_set(err, AUTOBAL_ENOMEM, "positive roots: out of memory");
    for (i = 0; i <= deg; i++) hs[i] /= big;
    st = autobal_poly_roots(w, hs, deg + 1, re, im, err);
    autobal_poly_workspace_free(w);
    if (st != AUTOBAL_SUCCESS) return st;
  }
  for (i = 0; i < deg; i++) {
    const long double z0 = (long double)re[i] * z2;
    long double zz = z0;
    int it;
    if (!(re[i] > 0.0) || fabs(im[i]) > near * fabs(re[i])) continue;
    for (it = 0; it < 8; it++) { /* Newton on the long double h, kept only while it stays close */
      long double v = 0.0L, dv = 0.0L, zn;
      size_t k;
      for (k = n; k-- > 0;) {
        dv = dv * zz + v;
        v = v * zz + h[k];
      }
      if (dv == 0.0L) break;
      zn = zz - v / dv;
      if (!(fabsl(zn - z0) <= (long double)near * z0)) break;
      zz = zn;
    }
    z[(*nz)++] = zz;
  }
  return AUTOBAL_SUCCESS;
}

int autobal_poly_positive_roots_ld_(const long double *h, size_t n, long double z2, long double *z, size_t *nz,
                                    autobal_error *err) {
  if (n > 12) return autobal_error_set(err, AUTOBAL_EINVAL, "positive roots: %zu coefficients (2 .. 12)", n);
  return autobal_poly_positive_roots_tol_(h, n, z2, 1e-13, 1e-3, z, nz, err);
}
