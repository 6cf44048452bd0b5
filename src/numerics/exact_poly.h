/* exact_poly.h: polynomials with integer coefficients (GMP), exact signs at dyadic points and
 * certified isolation of their positive real roots (src/numerics/exact_poly.c; not installed).
 * Model-agnostic: a caller that can write its polynomial with integer (or dyadic, scaled)
 * coefficients gets every sign it asks for without rounding.  Includes core only. */
#ifndef AUTOBAL_EXACT_POLY_H
#define AUTOBAL_EXACT_POLY_H

#include <gmp.h>
#include <stddef.h>

#define AUTOBAL_XPOLY_MAXLEN 24

/* c[0] + c[1] x + ... + c[len-1] x^(len-1); len = 0 is the zero polynomial.  Entries at
 * index >= len are kept zero. */
typedef struct autobal_xpoly {
  int len;
  mpz_t c[AUTOBAL_XPOLY_MAXLEN];
} autobal_xpoly;

void autobal_xpoly_init(autobal_xpoly *p);  /* the zero polynomial (allocates GMP limbs) */
void autobal_xpoly_clear(autobal_xpoly *p); /* frees them */
void autobal_xpoly_zero(autobal_xpoly *p);
/* len := 1 + the index of the highest non-zero coefficient (0 for the zero polynomial) */
void autobal_xpoly_normalize(autobal_xpoly *p);
/* out = a * b (out may be a or b); returns -1 when the degree would exceed MAXLEN - 1 */
int autobal_xpoly_mul(autobal_xpoly *out, const autobal_xpoly *a, const autobal_xpoly *b);
/* out += s * a */
int autobal_xpoly_addmul_si(autobal_xpoly *out, const autobal_xpoly *a, long s);
/* divide out the factor x^j of the lowest non-zero coefficient (returns j) */
int autobal_xpoly_strip_low(autobal_xpoly *p);
/* out = p' */
void autobal_xpoly_deriv(autobal_xpoly *out, const autobal_xpoly *p);

/* out = the primitive greatest common divisor of a and b over the rationals (positive leading
 * coefficient; primitive pseudo-remainder sequence).  Its roots are the common roots of a and
 * b: with b = a' the multiple roots of a, each once less often.  The zero polynomial when both
 * are zero. */
void autobal_xpoly_gcd(autobal_xpoly *out, const autobal_xpoly *a, const autobal_xpoly *b);

/* A dyadic number m 2^e (m an integer of any size). */
typedef struct autobal_dyadic {
  mpz_t m;
  long e;
} autobal_dyadic;
void autobal_dyadic_init(autobal_dyadic *d);
void autobal_dyadic_clear(autobal_dyadic *d);
void autobal_dyadic_set_ld(autobal_dyadic *d, long double x); /* exact (x finite) */
void autobal_dyadic_set_d(autobal_dyadic *d, double x);       /* exact (x finite) */
void autobal_dyadic_mul(autobal_dyadic *out, const autobal_dyadic *a, const autobal_dyadic *b);

/* The exact value of 2^(N e) p(m 2^e) for e < 0, or p(m 2^e) for e >= 0, into val (an integer
 * with the sign of p(x)); N >= deg p is the scale degree (several polynomials evaluated with
 * one N share one positive factor).  *log2_scale receives the base-2 exponent of that factor
 * (val = p(x) 2^(*log2_scale)).  tmp is scratch. */
void autobal_xpoly_eval_scaled(const autobal_xpoly *p, const autobal_dyadic *x, int N, mpz_t val,
                               mpz_t tmp, long *log2_scale);
/* Exact sign (-1, 0, 1) of p at the dyadic x. */
int autobal_xpoly_sign(const autobal_xpoly *p, const autobal_dyadic *x, mpz_t val, mpz_t tmp);

/* Positive real roots of p (len >= 2, p(0) may be zero: the root 0 is not reported), each
 * as a bracket lo <= root <= hi with lo, hi doubles that are equal (a root that is exactly a
 * double) or adjacent (nextafter(lo, inf) == hi): the root is known to the last bit of a
 * double.  Every simple root is found, by the signs of p (exact) on the intervals where it is
 * monotone, recursively between the roots of its derivatives; a root of even multiplicity
 * that is not a double is not (p does not change sign there).  Two roots inside the same ulp
 * are found when p changes sign at the midpoint of that ulp and are then reported as two equal
 * brackets with *unresolved set to 1 (they cannot be told apart in double).  Sorted ascending.
 * Returns 0, or -1 when more than max roots would be written (the first max are kept). */
int autobal_xpoly_positive_roots(const autobal_xpoly *p, double *lo, double *hi, size_t max,
                                 size_t *n, int *unresolved);

#endif
