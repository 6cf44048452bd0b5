/* internal.h: helpers shared by the library's source files (not installed).  Layer: core
 * (docs/architecture.md): every file of src/ may include it, and it includes nothing of a
 * higher layer.  Besides the error helpers of src/core/status.c it declares three test hooks of
 * the numerics (src/numerics/poly.c, sign_tests.c), kept here for the tests that include them
 * by this name. */
#ifndef AUTOBAL_INTERNAL_H
#define AUTOBAL_INTERNAL_H

#include <math.h>
#include <stddef.h>

#include "autobal/status.h"

#if defined(__GNUC__)
#define AUTOBAL_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define AUTOBAL_PRINTF(a, b)
#endif

/* Record status and a formatted message in err (may be NULL); returns status. */
int autobal_error_set(autobal_error *err, int status, const char *fmt, ...) AUTOBAL_PRINTF(3, 4);

/* Range check: value must be finite and inside the interval from lo to hi
 * (lo_open / hi_open: 1 for an open end).  On failure records the bound that
 * was broken, then the whole range, numbers in the shortest form that reads
 * back exactly:
 *   "parameter NAME = VALUE UNIT is too large: must be < hi UNIT (allowed range (lo, hi))"
 *   "parameter NAME = VALUE UNIT is too small: must be >= lo UNIT (allowed range [lo, hi))"
 *   "parameter NAME = nan UNIT is not a finite number (allowed range ...)"
 * and returns AUTOBAL_EINVAL; AUTOBAL_SUCCESS otherwise.  Use -INFINITY/INFINITY
 * for unbounded ends ("inf" in the message). */
int autobal_check_param(autobal_error *err, const char *name, double value, double lo, int lo_open,
                        double hi, int hi_open, const char *unit);

/* The two root finders behind autobal_poly_roots (src/numerics/poly.c), for tests:
 * c has degree(w) + 1 finite coefficients with c[degree] != 0 (not checked);
 * the roots are NOT sorted.  Both return 0, or -1 when the method did not
 * settle (re/im then unspecified).
 * _aberth: exact zero roots split off, Aberth-Ehrlich iteration, real
 *   structure restored (real roots with Im = 0, exact conjugate pairs).
 * _qr: balanced companion matrix, Francis double-shift QR (LAPACK DLAHQR).
 * (The workspace type of autobal/stability.h, declared again so that this core header does
 * not include a numerics header; C11 allows the repeated typedef.) */
typedef struct autobal_poly_workspace autobal_poly_workspace;
int autobal_poly_roots_aberth(autobal_poly_workspace *w, const double *c, double *re, double *im);
int autobal_poly_roots_qr(autobal_poly_workspace *w, const double *c, double *re, double *im);

/* autobal_poly_hurwitz_err without its quick stage (src/numerics/sign_tests.c): the full
 * Routh test with one running error bound per entry, same arguments, checks,
 * messages and results.  For tests (reference of the quick stage) and for
 * the fall-back of autobal_pendulum_verdict after its own quick stage. */
int autobal_poly_hurwitz_err_full(const double *c, const double *cerr, size_t len, int *verdict,
                                  int *n_rhp, autobal_error *err);

/* The positive real roots z of h(z) = sum_k h[k] z^k (n <= 12 long double coefficients) as the
 * critical-value searches of the rotor analysis need them (src/numerics/poly_positive.c): the
 * roots of the scaled, normalized double polynomial h(z2 x) by autobal_poly_roots, those with
 * x > 0 and |Im x| <= 1e-3 Re x (a generous "near real", so that none is lost), each polished by
 * at most 8 Newton steps on the long double h (kept only while within 1e-3 of the start).
 * Coefficients below 1e-13 of the largest scaled one are dropped from the top.  z (capacity 11)
 * receives *nz roots, unsorted.  AUTOBAL_SUCCESS, AUTOBAL_ENOMEM, or the status of
 * autobal_poly_roots (message in err). */
int autobal_poly_positive_roots_ld_(const long double *h, size_t n, long double z2, long double *z, size_t *nz,
                                    autobal_error *err);
/* The same for n <= 64 coefficients (z capacity n - 1), with the top-coefficient cut `trim`
 * (1e-13 above) and the "near real" / Newton window `near` (1e-3 above) given. */
int autobal_poly_positive_roots_tol_(const long double *h, size_t n, long double z2, double trim, double near,
                                     long double *z, size_t *nz, autobal_error *err);
/* autobal_poly_roots with a workspace of its own, allocated and freed in the call (len - 1 roots into
 * re, im).  AUTOBAL_ENOMEM ("polynomial roots: out of memory") or autobal_poly_roots' status. */
int autobal_poly_roots_once_(const double *c, size_t len, double *re, double *im, autobal_error *err);

#endif
