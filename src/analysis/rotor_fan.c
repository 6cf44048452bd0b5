/* rotor_fan.c: the symmetric fan of n >= 3 identical balls (see rotor_fan.h). */
#include "analysis/rotor_fan.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double autobal_rotor_fan_cheb_u_(size_t n, double y, double *dU) {
  double u0 = 1.0, u1 = 2.0 * y, d0 = 0.0, d1 = 2.0;
  size_t k;
  if (n == 1) {
    if (dU) *dU = 0.0;
    return 1.0;
  }
  for (k = 2; k < n; k++) {
    const double u2 = 2.0 * y * u1 - u0, d2 = 2.0 * u1 + 2.0 * y * d1 - d0;
    u0 = u1, u1 = u2, d0 = d1, d1 = d2;
  }
  if (dU) *dU = d1;
  return u1;
}

void autobal_rotor_fan_init_(autobal_rotor_fan_ *f, size_t n, double m) {
  double lo, hi, dlo;
  int it;
  f->n = n, f->m = m;
  f->y_min = cos(2.0 * M_PI / (double)n);
  f->y0 = cos(M_PI / (double)n);
  lo = f->y_min, hi = f->y0;
  (void)autobal_rotor_fan_cheb_u_(n, lo, &dlo);
  for (it = 0; it < 200; it++) {
    const double mid = 0.5 * (lo + hi);
    double dm;
    if (!(mid > lo && mid < hi)) break;
    (void)autobal_rotor_fan_cheb_u_(n, mid, &dm);
    if ((dm > 0.0) == (dlo > 0.0)) lo = mid;
    else hi = mid;
  }
  f->y1 = 0.5 * (lo + hi);
}

double autobal_rotor_fan_t_(const autobal_rotor_fan_ *f, double y) {
  return autobal_rotor_fan_cheb_u_(f->n, sqrt(0.5 * (1.0 + y)), NULL);
}

double autobal_rotor_fan_u_(const autobal_rotor_fan_ *f, double y) {
  const double g = autobal_rotor_fan_cheb_u_(f->n, y, NULL);
  return 0.25 * f->m * f->m * g * g;
}

double autobal_rotor_fan_y_of_t_(const autobal_rotor_fan_ *f, double t) {
  double lo = f->y_min, hi = 1.0;
  int it;
  for (it = 0; it < 200; it++) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (autobal_rotor_fan_t_(f, mid) < t) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

size_t autobal_rotor_fan_y_of_u_(const autobal_rotor_fan_ *f, double uc, double ylo, double yhi, double out[3]) {
  const double br[4] = {f->y_min, f->y1, f->y0, 1.0};
  size_t k, n = 0;
  if (!isfinite(uc)) return 0;
  for (k = 0; k < 3; k++) {
    double lo = fmax(br[k], ylo), hi = fmin(br[k + 1], yhi), flo, fhi;
    int it;
    if (!(lo <= hi)) continue;
    flo = autobal_rotor_fan_u_(f, lo) - uc;
    fhi = autobal_rotor_fan_u_(f, hi) - uc;
    if ((flo > 0.0 && fhi > 0.0) || (flo < 0.0 && fhi < 0.0)) continue;
    for (it = 0; it < 200; it++) {
      const double mid = 0.5 * (lo + hi), fm = autobal_rotor_fan_u_(f, mid) - uc;
      if (!(mid > lo && mid < hi)) break;
      if ((fm > 0.0) == (flo > 0.0)) lo = mid, flo = fm;
      else hi = mid;
    }
    out[n++] = 0.5 * (lo + hi);
  }
  return n;
}
