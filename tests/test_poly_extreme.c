/* test_poly_extreme.c: autobal_poly_roots on badly scaled coefficients (issue 19, item 3):
 * it must terminate (a watchdog alarm fails the test after 60 s; the companion-matrix
 * balancing used to loop forever on an infinite entry), return the roots where they are
 * representable (closed forms: c (z^2 + z + 1) and z^3 + 1 scaled by a power of ten), and
 * AUTOBAL_ENUMERIC where a root is beyond the double range; and the workspace size check
 * comes before any allocation count can overflow. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "autobal/stability.h"
#include "check.h"

static void on_alarm(int sig) {
  (void)sig;
  static const char msg[] = "FAIL watchdog: a root computation did not finish within 60 s\n";
  (void)!write(2, msg, sizeof msg - 1);
  _exit(99);
}

/* roots of a z^2 + a z + a scaled: x = s z, z = -1/2 -/+ i sqrt(3)/2 */
static void quad_case(double c0, double c1, double c2, double s) {
  autobal_poly_workspace *w = autobal_poly_workspace_alloc(2);
  double c[3] = {c0, c1, c2}, re[2], im[2];
  autobal_error e;
  char what[128];
  int rc = autobal_poly_roots(w, c, 3, re, im, &e);
  snprintf(what, sizeof what, "{%g, %g, %g}: success", c0, c1, c2);
  CHECK_STATUS(what, rc, AUTOBAL_SUCCESS);
  snprintf(what, sizeof what, "{%g, %g, %g}: Re = -s/2", c0, c1, c2);
  CHECK_CLOSE(what, re[0], -0.5 * s, 1e-13, 0.0);
  CHECK_CLOSE(what, re[1], -0.5 * s, 1e-13, 0.0);
  snprintf(what, sizeof what, "{%g, %g, %g}: Im = -/+ s sqrt(3)/2", c0, c1, c2);
  CHECK_CLOSE(what, im[0], -0.5 * sqrt(3.0) * s, 1e-13, 0.0);
  CHECK_CLOSE(what, im[1], 0.5 * sqrt(3.0) * s, 1e-13, 0.0);
  autobal_poly_workspace_free(w);
}

static uint64_t rng = 0x9E3779B97F4A7C15ULL;
static double urand(void) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (double)(rng >> 11) * 0x1p-53;
}

int main(void) {
  autobal_poly_workspace *w;
  autobal_error e;
  double re[16], im[16];
  int rc, n_ok = 0, n_enum = 0, n_bad = 0, trial;
  signal(SIGALRM, on_alarm);
  alarm(60);

  /* the audit's case: it used to hang */
  quad_case(1e200, 1e0, 1e-200, 1e200);
  quad_case(1e300, 1e0, 1e-300, 1e300);
  quad_case(1e-300, 1e0, 1e300, 1e-300);
  quad_case(3.0, 3.0, 3.0, 1.0); /* the well-scaled path */

  /* z^3 + 1 scaled: 1e300 x^3 + 1e-300 = 0, x = 1e-200 (-1, 1/2 -/+ i sqrt(3)/2); the
   * powers x^3 = 1e-600 underflow, so the unscaled iteration would return zeros */
  {
    double c[4] = {1e-300, 0.0, 0.0, 1e300};
    w = autobal_poly_workspace_alloc(3);
    rc = autobal_poly_roots(w, c, 4, re, im, &e);
    CHECK_STATUS("1e300 x^3 + 1e-300: success", rc, AUTOBAL_SUCCESS);
    CHECK_CLOSE("real root -1e-200", re[0], -1e-200, 1e-13, 0.0);
    CHECK_CLOSE("pair: Re 5e-201", re[1], 0.5e-200, 1e-13, 0.0);
    CHECK_CLOSE("pair: Im 8.66e-201", im[2], 0.5 * sqrt(3.0) * 1e-200, 1e-13, 0.0);
    autobal_poly_workspace_free(w);
  }

  /* a root beyond the double range: 1e300 + 1e-300 x = 0, x = -1e600 */
  {
    double c[2] = {1e300, 1e-300};
    w = autobal_poly_workspace_alloc(1);
    rc = autobal_poly_roots(w, c, 2, re, im, &e);
    CHECK_STATUS("1e300 + 1e-300 x: root -1e600 is not representable", rc, AUTOBAL_ENUMERIC);
    CHECK_MSG("the message says why", e.message, "beyond the double range");
    autobal_poly_workspace_free(w);
  }

  /* random badly scaled polynomials, degrees 1..12, |c_j| = 10^U(-300, 300): every call ends
   * with SUCCESS and finite roots, or ENUMERIC */
  for (trial = 0; trial < 3000; trial++) {
    const size_t n = 1 + (size_t)(urand() * 12.0);
    double c[13];
    size_t j;
    int fin = 1;
    for (j = 0; j <= n; j++) c[j] = (urand() < 0.5 ? -1.0 : 1.0) * pow(10.0, -300.0 + 600.0 * urand());
    w = autobal_poly_workspace_alloc(n);
    rc = autobal_poly_roots(w, c, n + 1, re, im, &e);
    for (j = 0; j < n; j++) fin &= isfinite(re[j]) && isfinite(im[j]);
    if (rc == AUTOBAL_SUCCESS && fin)
      n_ok++;
    else if (rc == AUTOBAL_ENUMERIC)
      n_enum++;
    else
      n_bad++;
    autobal_poly_workspace_free(w);
  }
  printf("random badly scaled polynomials: %d solved, %d beyond the double range, %d bad\n", n_ok,
         n_enum, n_bad);
  CHECK("3000 random badly scaled polynomials: every call ends in SUCCESS (finite) or ENUMERIC",
        n_bad == 0);

  /* the size check before the counts: SIZE_MAX used to overflow a calloc count */
  CHECK("workspace of degree SIZE_MAX: NULL", autobal_poly_workspace_alloc(SIZE_MAX) == NULL);
  CHECK("workspace of degree AUTOBAL_POLY_MAX_DEGREE + 1: NULL",
        autobal_poly_workspace_alloc(AUTOBAL_POLY_MAX_DEGREE + 1) == NULL);
  return check_summary();
}
