/* autobal/stability.h: model-agnostic tools for linear stability analysis.
 *
 * Real and complex polynomial arithmetic, polynomial roots (GSL
 * gsl_poly_complex_solve), eigenvalues of a real non-symmetric matrix (GSL
 * gsl_eigen_nonsymm), matching of two root sets, the Routh-Hurwitz sign test,
 * a Sturm-sequence real-root count, and bracketed scalar root finding.
 * Nothing here knows a model; the models (pendulum.h, rotor.h) build on it.
 *
 * Conventions
 *  - A real polynomial is an array c of `len` doubles in ASCENDING powers:
 *        p(x) = c[0] + c[1] x + ... + c[len-1] x^(len-1).
 *    Its degree is len-1 when c[len-1] != 0.
 *  - A complex polynomial is an array of `len` coefficients stored
 *    interleaved: coefficient j is c[2j] + i c[2j+1] (so the array holds
 *    2*len doubles).  No C99 `double complex` appears in this header.
 *  - Roots and eigenvalues are returned in two arrays re[], im[] of length n.
 *  - The routines that work on stack arrays accept at most AUTOBAL_POLY_MAXLEN
 *    coefficients (degree AUTOBAL_POLY_MAXLEN-1) and give AUTOBAL_EINVAL for
 *    larger inputs: autobal_poly_hurwitz, autobal_poly_hurwitz_err and
 *    autobal_poly_sturm_count.  The arithmetic (poly_mul, poly_axpby,
 *    poly_deriv, cpoly_*) and autobal_poly_roots have no such cap;
 *    autobal_match_roots takes n <= AUTOBAL_MATCH_MAXN.  None of the functions
 *    below allocates except the *_workspace_alloc functions.
 *  - The functions that return no status (evaluation, degree, conj, real part,
 *    verdict from roots) do no validation: their pointers must be valid for
 *    the lengths given.
 *  - Every function that can fail returns an autobal status and, when an
 *    `autobal_error *err` is given (NULL allowed), records a message naming
 *    the offending argument.  After a failure the output arrays hold
 *    unspecified (but finite-or-NaN, never uninitialised-memory) values.
 *  - Thread safety: all functions are reentrant; a workspace must not be
 *    used by two threads at the same time (use one workspace per thread).
 *  - GSL: call gsl_set_error_handler_off() once in the host program; the
 *    library checks every GSL return code and reports it as a status.
 */
#ifndef AUTOBAL_STABILITY_H
#define AUTOBAL_STABILITY_H

#include <stddef.h>
#include "autobal/export.h"
#include "autobal/status.h"

AUTOBAL_BEGIN_DECLS

/* Largest degree of autobal_poly_workspace_alloc. */
#define AUTOBAL_POLY_MAX_DEGREE 4096

/* Largest number of coefficients accepted by the stack-based routines. */
#define AUTOBAL_POLY_MAXLEN 33
/* Largest n accepted by autobal_match_roots(). */
#define AUTOBAL_MATCH_MAXN 32

/* Verdict of a stability test. */
typedef enum autobal_verdict {
  AUTOBAL_VERDICT_UNSTABLE = -1, /* a root with positive real part (beyond tolerance) */
  AUTOBAL_VERDICT_MARGINAL = 0,  /* undecided within tolerance: a root on (or within the
                                    tolerance of) the imaginary axis */
  AUTOBAL_VERDICT_STABLE = 1     /* every root has a negative real part (beyond tolerance) */
} autobal_verdict;

/* Static name of a verdict: "stable", "unstable", "marginal" ("unknown" otherwise). */
AUTOBAL_API const char *autobal_verdict_name(int verdict);

/* ------------------------------------------------------------------------ */
/* Real polynomials                                                         */
/* ------------------------------------------------------------------------ */

/* p(x) by Horner's rule.  len == 0 gives 0. */
AUTOBAL_API double autobal_poly_eval(const double *c, size_t len, double x);

/* p(z) at complex z = zre + i zim; result in *re, *im. */
AUTOBAL_API void autobal_poly_eval_complex(const double *c, size_t len, double zre, double zim,
                                           double *re, double *im);

/* Index of the highest non-zero coefficient (0 for the zero polynomial). */
AUTOBAL_API size_t autobal_poly_degree(const double *c, size_t len);

/* out = a * b.  out must hold outlen >= alen + blen - 1 coefficients; the
 * entries beyond the product are set to 0.  out may not alias a or b.
 * Returns AUTOBAL_EINVAL (out untouched) if a, b or out is NULL, alen or blen
 * is 0, or outlen < alen + blen - 1. */
AUTOBAL_API int autobal_poly_mul(const double *a, size_t alen, const double *b, size_t blen,
                                 double *out, size_t outlen, autobal_error *err);

/* out = alpha a + beta b, outlen >= max(alen, blen) (extra entries zeroed).
 * out may alias a or b.  An empty input (length 0, pointer may then be NULL)
 * counts as the zero polynomial.  Returns AUTOBAL_EINVAL (out untouched) if
 * out is NULL, a is NULL with alen > 0, b is NULL with blen > 0, or
 * outlen < max(alen, blen). */
AUTOBAL_API int autobal_poly_axpby(double alpha, const double *a, size_t alen, double beta,
                                   const double *b, size_t blen, double *out, size_t outlen,
                                   autobal_error *err);

/* out = p'(x): outlen >= len - 1 (at least 1); extra entries zeroed (the
 * derivative of a constant is the one coefficient 0).  out may alias c.
 * Returns AUTOBAL_EINVAL (out untouched) if c or out is NULL, len is 0, or
 * outlen < max(len - 1, 1). */
AUTOBAL_API int autobal_poly_deriv(const double *c, size_t len, double *out, size_t outlen,
                                   autobal_error *err);

/* ------------------------------------------------------------------------ */
/* Complex polynomials (interleaved re/im coefficients)                     */
/* ------------------------------------------------------------------------ */

/* out = a * b; out holds outlen >= alen + blen - 1 complex coefficients
 * (2*outlen doubles; the entries beyond the product are set to 0); no
 * aliasing.  Returns AUTOBAL_EINVAL (out untouched) if a, b or out is NULL,
 * alen or blen is 0, or outlen < alen + blen - 1. */
AUTOBAL_API int autobal_cpoly_mul(const double *a, size_t alen, const double *b, size_t blen,
                                  double *out, size_t outlen, autobal_error *err);

/* out = (ar + i ai) a + (br + i bi) b; outlen >= max(alen, blen) (extra
 * entries zeroed); out may alias a or b; an empty input counts as zero.
 * Returns AUTOBAL_EINVAL (out untouched) if out is NULL, a is NULL with
 * alen > 0, b is NULL with blen > 0, or outlen < max(alen, blen). */
AUTOBAL_API int autobal_cpoly_axpby(double ar, double ai, const double *a, size_t alen, double br,
                                    double bi, const double *b, size_t blen, double *out,
                                    size_t outlen, autobal_error *err);

/* out = conj(a): conjugates the coefficients (i -> -i), not the variable.
 * out may alias a. */
AUTOBAL_API void autobal_cpoly_conj(const double *a, size_t len, double *out);

/* a(z) at complex z; result in *re, *im. */
AUTOBAL_API void autobal_cpoly_eval(const double *a, size_t len, double zre, double zim,
                                    double *re, double *im);

/* Real parts of the coefficients into out[len]; *max_imag (may be NULL)
 * receives max_j |Im a_j| / max(1e-300, max_j |a_j|), the relative size of
 * the discarded imaginary parts (a check that the product was real). */
AUTOBAL_API void autobal_cpoly_real_part(const double *a, size_t len, double *out,
                                         double *max_imag);

/* ------------------------------------------------------------------------ */
/* Roots and eigenvalues                                                    */
/* ------------------------------------------------------------------------ */

/* Workspace for the roots of real polynomials of one fixed degree >= 1
 * (iterates, a companion matrix and GSL's gsl_poly_complex_workspace).
 * NULL if out of memory, degree 0 or degree > AUTOBAL_POLY_MAX_DEGREE. */
typedef struct autobal_poly_workspace autobal_poly_workspace;
AUTOBAL_API autobal_poly_workspace *autobal_poly_workspace_alloc(size_t degree);
AUTOBAL_API void autobal_poly_workspace_free(autobal_poly_workspace *w); /* NULL is safe */
AUTOBAL_API size_t autobal_poly_workspace_degree(const autobal_poly_workspace *w);

/* All complex roots of the real polynomial c[0..len-1].  len must equal
 * degree(w) + 1, c[len-1] must be non-zero and every coefficient finite.
 * re[], im[] (length len-1) receive the roots sorted by increasing real
 * part, then increasing imaginary part (deterministic order).  Real roots
 * have im == 0 exactly, the others come in exact conjugate pairs, and
 * zero coefficients c[0..j-1] give j roots exactly 0.
 * Method: the Aberth-Ehrlich simultaneous iteration (Bini's starting
 * points; a root is accepted when |p(z)| is within the rounding error of
 * evaluating p, i.e. it is an exact root of a polynomial whose coefficients
 * differ from c by a relative ~4 n eps), accepted when the Newton inclusion
 * disks of the roots are pairwise disjoint; otherwise (clusters, multiple
 * roots) the eigenvalues of the balanced companion matrix by the Francis
 * double-shift QR (LAPACK DLAHQR), and GSL's gsl_poly_complex_solve if that
 * does not converge either.  When neither settles (coefficients so badly
 * scaled that c_i / c_n or the powers of the roots overflow, e.g. 1e200,
 * 1, 1e-200), the same is done for z = x / 2^k with 2^k about the
 * geometric mean of the roots' moduli and the coefficients normalised by
 * a power of 2; a root whose modulus is beyond the double range, or roots
 * spanning more than it, give AUTOBAL_ENUMERIC.  Every iteration is bounded.
 * About 2x faster than GSL alone for degree 8.
 * Returns AUTOBAL_EINVAL (bad length, zero leading coefficient, NaN/inf)
 * or AUTOBAL_ENUMERIC (no method converged; message carries GSL's text). */
AUTOBAL_API int autobal_poly_roots(autobal_poly_workspace *w, const double *c, size_t len,
                                   double *re, double *im, autobal_error *err);

/* Workspace for the eigenvalues of real n x n matrices (GSL
 * gsl_eigen_nonsymm_workspace plus a copy of the matrix). */
typedef struct autobal_eigen_workspace autobal_eigen_workspace;
AUTOBAL_API autobal_eigen_workspace *autobal_eigen_workspace_alloc(size_t n);
AUTOBAL_API void autobal_eigen_workspace_free(autobal_eigen_workspace *w); /* NULL is safe */
AUTOBAL_API size_t autobal_eigen_workspace_size(const autobal_eigen_workspace *w);

/* Eigenvalues of the real n x n matrix a (row-major, n = size(w); a is
 * not modified) by balancing + Francis QR (gsl_eigen_nonsymm).  re[], im[]
 * (length n) are sorted like autobal_poly_roots().  Returns AUTOBAL_EINVAL
 * (NaN/inf entries) or AUTOBAL_ENUMERIC (QR did not converge). */
AUTOBAL_API int autobal_eigen_nonsymm(autobal_eigen_workspace *w, const double *a, double *re,
                                      double *im, autobal_error *err);

/* ------------------------------------------------------------------------ */
/* Matching two root sets                                                   */
/* ------------------------------------------------------------------------ */

/* Bottleneck-optimal assignment between two sets of n complex numbers
 * a and b: finds the permutation perm minimising max_i |a_i - b_perm[i]|
 * (threshold search over the n^2 distances + bipartite matching), so the
 * reported mismatch is the smallest achievable by any pairing.
 * perm (length n, may be NULL) receives the pairing; *max_dist the
 * minimal maximal distance.  n <= AUTOBAL_MATCH_MAXN, else AUTOBAL_EINVAL;
 * n == 0 gives *max_dist = 0. */
AUTOBAL_API int autobal_match_roots(size_t n, const double *a_re, const double *a_im,
                                    const double *b_re, const double *b_im, size_t *perm,
                                    double *max_dist, autobal_error *err);

/* ------------------------------------------------------------------------ */
/* Sign tests on real coefficients                                          */
/* ------------------------------------------------------------------------ */

/* Routh-Hurwitz test of the real polynomial c[0..len-1] (degree len-1 >= 1,
 * c[len-1] != 0; any sign of the leading coefficient).
 *
 * The Routh array is built in floating point together with a first-order
 * running bound on the absolute error of each entry, starting from
 * coefficient errors rtol*|c_j| (plus rounding, so rtol = 0 means "the
 * coefficients are exact": only rounding errors count).  Then
 *   STABLE    every first-column entry has the sign of the leading
 *             coefficient and exceeds its error bound: all roots have
 *             Re < 0 for every perturbation of the coefficients within rtol;
 *   UNSTABLE  some first-column entry has the wrong sign beyond its bound:
 *             *n_rhp (may be NULL) = number of sign changes = number of
 *             roots with Re > 0;
 *   MARGINAL  an entry is zero within its bound (a root on or within the
 *             tolerance of the imaginary axis, e.g. c[0] == 0 or an even
 *             polynomial); *n_rhp is then the number of sign changes
 *             counted over the decided entries (a lower bound).
 * A tolerance rtol between 1e-14 and 1e-10 is sensible; AUTOBAL_EINVAL for
 * rtol < 0 or not finite, bad length, zero leading coefficient, NaN.
 * Cost O(len^2), no allocation.  For degrees 3..12 a cheaper first stage
 * (the same first-column values, one coarser bound per row) decides when
 * every entry is far from zero, which gives the same verdict and count as
 * the full test; otherwise the full test runs (about 27 ns at degree 8). */
AUTOBAL_API int autobal_poly_hurwitz(const double *c, size_t len, double rtol, int *verdict,
                                     int *n_rhp, autobal_error *err);

/* Same test with explicit absolute error bounds cerr[j] >= 0 on each
 * coefficient c[j] (e.g. from a running error analysis of how c was
 * computed); rounding in the Routh array is added on top.  cerr may be NULL
 * (exact coefficients). */
AUTOBAL_API int autobal_poly_hurwitz_err(const double *c, const double *cerr, size_t len,
                                         int *verdict, int *n_rhp, autobal_error *err);

/* Verdict from computed roots: with m = max Re(root) (written to *max_re,
 * may be NULL) and scale = max(1, max |root|):
 *   STABLE if m < -tol*scale, UNSTABLE if m > tol*scale, else MARGINAL.
 * n == 0 gives STABLE with *max_re = -inf.  Returns the verdict itself (not a
 * status; no validation).  Non-finite input: a NaN real part anywhere gives
 * m = NaN (written to *max_re) and MARGINAL; a NaN imaginary part does not
 * enter scale (and changes nothing else); with tol >= 0 an infinite root
 * makes scale infinite, hence MARGINAL; a NaN tol gives MARGINAL (n > 0). */
AUTOBAL_API int autobal_roots_verdict(size_t n, const double *re, const double *im, double tol,
                                      double *max_re);

/* Number of DISTINCT real roots of c[0..len-1] in the half-open interval
 * (a, b] (a may be -INFINITY, b may be +INFINITY), by a Sturm sequence with
 * remainders treated as zero when they fall below rtol (relative to the
 * size of the sequence's entries; rtol = 0 gives 1e3*DBL_EPSILON).
 * Multiple roots count once (the sequence ends at the gcd).  A root exactly
 * at a or b where a Sturm-sequence value vanishes is handled by the usual
 * convention (zeros are skipped when counting sign changes).
 * AUTOBAL_EINVAL for bad length/zero polynomial/NaN, a > b. */
AUTOBAL_API int autobal_poly_sturm_count(const double *c, size_t len, double a, double b,
                                         double rtol, int *count, autobal_error *err);

/* ------------------------------------------------------------------------ */
/* Bracketed scalar root finding and refinement of verdict changes          */
/* ------------------------------------------------------------------------ */

/* A scalar function: writes f(x) to *fx and returns an autobal status
 * (non-zero aborts the search and is passed back to the caller). */
typedef int (*autobal_scalar_fn)(double x, void *ctx, double *fx);

/* Brent's method (inverse quadratic interpolation + bisection safeguard;
 * allocation-free re-implementation, not gsl_root_fsolver, so that it can
 * run in hot loops).  f(a) and f(b) must have opposite signs (or one of
 * them be zero).  Stops when the bracket is shorter than
 * xtol_abs + xtol_rel*|x|, or f(x) == 0.  *root receives the best
 * estimate.  Returns AUTOBAL_EINVAL (no sign change, bad tolerances),
 * AUTOBAL_ENUMERIC (max_iter reached; *root still holds the best estimate)
 * or the status of f. */
AUTOBAL_API int autobal_root_brent(autobal_scalar_fn f, void *ctx, double a, double b,
                                   double xtol_abs, double xtol_rel, int max_iter, double *root,
                                   autobal_error *err);

/* An integer-valued predicate on the real line (e.g. a verdict): writes the
 * value to *value and returns an autobal status. */
typedef int (*autobal_predicate_fn)(double x, void *ctx, int *value);

/* Bisection of a change of the predicate p on [a, b], a < b, with
 * p(a) != p(b): shrinks a bracket [lo, hi] keeping p(lo) == p(a) and
 * p(hi) != p(a) until hi - lo <= xtol_abs + xtol_rel*|hi| (so a change of p
 * lies in (lo, hi]).  *lo, *hi receive the final bracket (either may be
 * NULL).  Returns AUTOBAL_EINVAL if p(a) == p(b), a >= b or the tolerances
 * are bad, or the status of p. */
AUTOBAL_API int autobal_bisect_change(autobal_predicate_fn p, void *ctx, double a, double b,
                                      double xtol_abs, double xtol_rel, double *lo, double *hi,
                                      autobal_error *err);

AUTOBAL_END_DECLS

#endif
