/* exact_poly.c: integer polynomials (GMP), exact signs at dyadic points, certified isolation
 * of positive real roots (exact_poly.h).  No rounding decides anything here: every sign is the
 * sign of an exact integer; doubles only say where to look next. */
#include "numerics/exact_poly.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

void autobal_xpoly_init(autobal_xpoly *p) {
  int i;
  p->len = 0;
  for (i = 0; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_init(p->c[i]);
}

void autobal_xpoly_clear(autobal_xpoly *p) {
  int i;
  for (i = 0; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_clear(p->c[i]);
  p->len = 0;
}

void autobal_xpoly_zero(autobal_xpoly *p) {
  int i;
  for (i = 0; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_set_ui(p->c[i], 0);
  p->len = 0;
}

void autobal_xpoly_normalize(autobal_xpoly *p) {
  int n = AUTOBAL_XPOLY_MAXLEN;
  while (n > 0 && mpz_sgn(p->c[n - 1]) == 0) n--;
  p->len = n;
}

int autobal_xpoly_mul(autobal_xpoly *out, const autobal_xpoly *a, const autobal_xpoly *b) {
  autobal_xpoly t;
  int i, j, st = 0;
  autobal_xpoly_init(&t);
  for (i = 0; i < a->len; i++) {
    if (mpz_sgn(a->c[i]) == 0) continue;
    for (j = 0; j < b->len; j++) {
      if (i + j >= AUTOBAL_XPOLY_MAXLEN) {
        if (mpz_sgn(b->c[j]) != 0) st = -1;
        continue;
      }
      mpz_addmul(t.c[i + j], a->c[i], b->c[j]);
    }
  }
  for (i = 0; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_swap(out->c[i], t.c[i]);
  autobal_xpoly_normalize(out);
  autobal_xpoly_clear(&t);
  return st;
}

int autobal_xpoly_addmul_si(autobal_xpoly *out, const autobal_xpoly *a, long s) {
  int i;
  for (i = 0; i < a->len; i++) {
    if (s >= 0) mpz_addmul_ui(out->c[i], a->c[i], (unsigned long)s);
    else mpz_submul_ui(out->c[i], a->c[i], (unsigned long)(-(s + 1)) + 1UL);
  }
  autobal_xpoly_normalize(out);
  return 0;
}

int autobal_xpoly_strip_low(autobal_xpoly *p) {
  int j = 0, i;
  if (p->len == 0) return 0;
  while (j < p->len && mpz_sgn(p->c[j]) == 0) j++;
  if (j == 0) return 0;
  for (i = 0; i + j < AUTOBAL_XPOLY_MAXLEN; i++) mpz_swap(p->c[i], p->c[i + j]);
  for (i = AUTOBAL_XPOLY_MAXLEN - j; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_set_ui(p->c[i], 0);
  autobal_xpoly_normalize(p);
  return j;
}

void autobal_xpoly_deriv(autobal_xpoly *out, const autobal_xpoly *p) {
  int i, n = p->len;
  for (i = 0; i + 1 < n; i++) mpz_mul_ui(out->c[i], p->c[i + 1], (unsigned long)(i + 1));
  for (i = n > 0 ? n - 1 : 0; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_set_ui(out->c[i], 0);
  autobal_xpoly_normalize(out);
}

static void xpoly_copy(autobal_xpoly *out, const autobal_xpoly *a) {
  int i;
  for (i = 0; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_set(out->c[i], a->c[i]);
  out->len = a->len;
}

/* divide by the gcd of the coefficients, leading coefficient made positive */
static void xpoly_primitive(autobal_xpoly *p, mpz_t g) {
  int i;
  if (p->len == 0) return;
  mpz_set_ui(g, 0);
  for (i = 0; i < p->len; i++) mpz_gcd(g, g, p->c[i]);
  if (mpz_sgn(p->c[p->len - 1]) < 0) mpz_neg(g, g);
  for (i = 0; i < p->len; i++) mpz_divexact(p->c[i], p->c[i], g);
}

void autobal_xpoly_gcd(autobal_xpoly *out, const autobal_xpoly *a, const autobal_xpoly *b) {
  autobal_xpoly A, B;
  mpz_t g, fa, fb, t;
  autobal_xpoly_init(&A);
  autobal_xpoly_init(&B);
  mpz_inits(g, fa, fb, t, NULL);
  xpoly_copy(&A, a);
  xpoly_copy(&B, b);
  autobal_xpoly_normalize(&A);
  autobal_xpoly_normalize(&B);
  if (A.len < B.len) {
    int i;
    for (i = 0; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_swap(A.c[i], B.c[i]);
    i = A.len, A.len = B.len, B.len = i;
  }
  xpoly_primitive(&A, g);
  xpoly_primitive(&B, g);
  while (B.len > 0) {
    /* A := prem(A, B), made primitive; then swap */
    int i;
    while (A.len >= B.len && A.len > 0) {
      int sh = A.len - B.len;
      mpz_gcd(g, A.c[A.len - 1], B.c[B.len - 1]);
      mpz_divexact(fa, B.c[B.len - 1], g); /* A := fa A - fb x^sh B */
      mpz_divexact(fb, A.c[A.len - 1], g);
      for (i = 0; i < A.len; i++) mpz_mul(A.c[i], A.c[i], fa);
      for (i = 0; i < B.len; i++) mpz_submul(A.c[i + sh], B.c[i], fb);
      autobal_xpoly_normalize(&A);
      xpoly_primitive(&A, g);
    }
    for (i = 0; i < AUTOBAL_XPOLY_MAXLEN; i++) mpz_swap(A.c[i], B.c[i]);
    i = A.len, A.len = B.len, B.len = i;
  }
  xpoly_primitive(&A, g);
  xpoly_copy(out, &A);
  autobal_xpoly_clear(&A);
  autobal_xpoly_clear(&B);
  mpz_clears(g, fa, fb, t, NULL);
}

void autobal_dyadic_init(autobal_dyadic *d) {
  mpz_init(d->m);
  d->e = 0;
}

void autobal_dyadic_clear(autobal_dyadic *d) { mpz_clear(d->m); }

void autobal_dyadic_set_ld(autobal_dyadic *d, long double x) {
  int e;
  long double f;
  uint64_t m;
  int neg = x < 0;
  if (x == 0.0L) {
    mpz_set_ui(d->m, 0);
    d->e = 0;
    return;
  }
  f = frexpl(neg ? -x : x, &e); /* x = f 2^e, f in [1/2, 1): 64 bits of mantissa */
  m = (uint64_t)ldexpl(f, 64);
  e -= 64;
  while ((m & 1u) == 0) {
    m >>= 1;
    e++;
  }
  mpz_set_ui(d->m, (unsigned long)m);
  if (neg) mpz_neg(d->m, d->m);
  d->e = e;
}

void autobal_dyadic_set_d(autobal_dyadic *d, double x) { autobal_dyadic_set_ld(d, (long double)x); }

void autobal_dyadic_mul(autobal_dyadic *out, const autobal_dyadic *a, const autobal_dyadic *b) {
  mpz_mul(out->m, a->m, b->m);
  out->e = a->e + b->e;
}

void autobal_xpoly_eval_scaled(const autobal_xpoly *p, const autobal_dyadic *x, int N, mpz_t val,
                               mpz_t tmp, long *log2_scale) {
  int n = p->len - 1, i;
  *log2_scale = 0;
  if (p->len == 0) {
    mpz_set_ui(val, 0);
    return;
  }
  mpz_set(val, p->c[n]);
  if (x->e >= 0) {
    /* x is an integer */
    mpz_mul_2exp(tmp, x->m, (mp_bitcnt_t)x->e);
    for (i = n - 1; i >= 0; i--) {
      mpz_mul(val, val, tmp);
      mpz_add(val, val, p->c[i]);
    }
    return;
  }
  {
    /* acc = sum_i c_i m^i 2^(s(n-i)), s = -e; then times 2^(s(N-n)) */
    unsigned long s = (unsigned long)(-x->e);
    for (i = n - 1; i >= 0; i--) {
      mpz_mul(val, val, x->m);
      mpz_mul_2exp(tmp, p->c[i], (mp_bitcnt_t)(s * (unsigned long)(n - i)));
      mpz_add(val, val, tmp);
    }
    if (N > n) mpz_mul_2exp(val, val, (mp_bitcnt_t)(s * (unsigned long)(N - n)));
    *log2_scale = (long)(s * (unsigned long)(N > n ? N : n));
  }
}

int autobal_xpoly_sign(const autobal_xpoly *p, const autobal_dyadic *x, mpz_t val, mpz_t tmp) {
  long sc;
  autobal_xpoly_eval_scaled(p, x, p->len > 0 ? p->len - 1 : 0, val, tmp, &sc);
  return mpz_sgn(val);
}

/* ---- root isolation ------------------------------------------------------ */

typedef struct {
  autobal_dyadic x;
  mpz_t val, tmp;
} xeval;

/* sign of q at the double (or long double) t and log2 |q(t)| (-inf for 0) */
static int sign_at(const autobal_xpoly *q, xeval *w, long double t, double *l2) {
  long sc;
  long ex;
  double d;
  autobal_dyadic_set_ld(&w->x, t);
  autobal_xpoly_eval_scaled(q, &w->x, q->len > 0 ? q->len - 1 : 0, w->val, w->tmp, &sc);
  if (mpz_sgn(w->val) == 0) {
    if (l2) *l2 = -INFINITY;
    return 0;
  }
  if (l2) {
    d = mpz_get_d_2exp(&ex, w->val);
    *l2 = (double)ex - (double)sc + log2(fabs(d));
  }
  return mpz_sgn(w->val);
}

typedef struct {
  double lo, hi;
} bracket;

/* The single root of q in (a, b) where q is strictly monotone and sa, sb (the signs at a, b)
 * are opposite and non-zero: a bracket of adjacent doubles (or an exact double). Illinois
 * steps on the exact signs with the magnitudes as weights; a bisection step whenever the
 * bracket did not halve in three steps. */
static bracket refine(const autobal_xpoly *q, xeval *w, double a, double b, int sa, double la,
                      double lb) {
  bracket r;
  int side = 0, it = 0;
  double width0 = b - a;
  int force = 0;
  while (nextafter(a, INFINITY) < b) {
    double x;
    int sx;
    double lx;
    if (force || !isfinite(la) || !isfinite(lb)) {
      if (a == 0.0) x = b / 256.0;
      else if (b > 4.0 * a) x = sqrt(a) * sqrt(b);
      else x = a + 0.5 * (b - a);
      force = 0;
    } else {
      double dl = lb - la, t;
      t = dl > 1000 ? 0.0 : dl < -1000 ? 1.0 : 1.0 / (1.0 + exp2(dl));
      x = (double)((long double)a + (long double)t * ((long double)b - (long double)a));
    }
    if (!(x > a && x < b)) {
      x = a + 0.5 * (b - a);
      if (!(x > a && x < b)) break;
    }
    sx = sign_at(q, w, x, &lx);
    if (sx == 0) {
      r.lo = r.hi = x;
      return r;
    }
    if (sx == sa) {
      a = x;
      la = lx;
      if (side == -1) lb -= 1.0; /* Illinois */
      side = -1;
    } else {
      b = x;
      lb = lx;
      if (side == 1) la -= 1.0;
      side = 1;
    }
    if (++it % 3 == 0) {
      if (b - a > 0.5 * width0) force = 1;
      width0 = b - a;
    }
  }
  r.lo = a;
  r.hi = b;
  return r;
}

/* roots of q on [0, B] given the sorted roots crit[0..nc) of q' (brackets); appended to out */
static int roots_between(const autobal_xpoly *q, xeval *w, const bracket *crit, size_t nc,
                         double B, bracket *out, size_t max, size_t *n, int *unresolved) {
  double s0 = 0.0, l0, l1;
  size_t i;
  int sa, sb;
  /* the root 0 (a partition point only) */
  sa = sign_at(q, w, 0.0L, &l0);
  if (sa == 0) {
    if (*n >= max) return -1;
    out[(*n)++] = (bracket){0.0, 0.0};
  }
  for (i = 0; i <= nc; i++) {
    double e = i < nc ? crit[i].lo : B;
    if (e > s0) {
      sa = sign_at(q, w, s0, &l0);
      sb = sign_at(q, w, e, &l1);
      if (sa != 0 && sb != 0 && sa != sb) {
        if (*n >= max) return -1;
        out[(*n)++] = refine(q, w, s0, e, sa, l0, l1);
      }
    }
    if (i < nc) {
      double lo = crit[i].lo, hi = crit[i].hi;
      sa = sign_at(q, w, lo, NULL);
      sb = lo == hi ? sa : sign_at(q, w, hi, NULL);
      if (sa == 0 && lo > 0.0) {
        if (*n >= max) return -1;
        out[(*n)++] = (bracket){lo, lo};
      } else if (lo < hi && sb == 0) {
        if (*n >= max) return -1;
        out[(*n)++] = (bracket){hi, hi};
      } else if (lo < hi && sa != sb) {
        if (*n >= max) return -1;
        out[(*n)++] = (bracket){lo, hi};
      } else if (lo < hi && sa != 0) {
        /* same sign at both ends of the ulp holding a critical point: a pair of roots inside
         * it shows as a sign change at its midpoint */
        long double mid = 0.5L * ((long double)lo + (long double)hi);
        int sm = sign_at(q, w, mid, NULL);
        if (sm != sa) {
          if (*n + 2 > max) return -1;
          out[(*n)++] = (bracket){lo, hi};
          out[(*n)++] = (bracket){lo, hi};
          *unresolved = 1;
        }
      }
      s0 = hi;
    }
  }
  return 0;
}

int autobal_xpoly_positive_roots(const autobal_xpoly *p, double *lo, double *hi, size_t max,
                                 size_t *n, int *unresolved) {
  autobal_xpoly d[AUTOBAL_XPOLY_MAXLEN];
  bracket cur[AUTOBAL_XPOLY_MAXLEN * 2], nxt[AUTOBAL_XPOLY_MAXLEN * 2];
  size_t nc = 0, nn, i, m = 0;
  int deg = p->len - 1, j, st = 0;
  double B;
  xeval w;
  *n = 0;
  if (deg < 1) return 0;
  {
    /* Cauchy: every root has modulus < 1 + max |c_i / c_deg| <= 2^(bits_max - bits_deg + 2);
     * by Gauss-Lucas the roots of the derivatives too */
    long bmax = 0, bd = (long)mpz_sizeinbase(p->c[deg], 2), e;
    for (j = 0; j < deg; j++)
      if (mpz_sgn(p->c[j]) != 0 && (long)mpz_sizeinbase(p->c[j], 2) > bmax)
        bmax = (long)mpz_sizeinbase(p->c[j], 2);
    e = bmax - bd + 2;
    if (e < 1) e = 1;
    if (e > 1000) e = 1000;
    B = ldexp(1.0, (int)e);
  }
  autobal_dyadic_init(&w.x);
  mpz_init(w.val);
  mpz_init(w.tmp);
  for (j = 0; j < deg; j++) autobal_xpoly_init(&d[j]);
  autobal_xpoly_deriv(&d[0], p); /* d[j] = p^(j+1) */
  for (j = 1; j < deg; j++) autobal_xpoly_deriv(&d[j], &d[j - 1]);
  /* from the linear p^(deg-1) upwards */
  for (j = deg - 1; j >= 0; j--) {
    const autobal_xpoly *q = j == 0 ? p : &d[j - 1];
    int unres = 0;
    nn = 0;
    if (roots_between(q, &w, cur, nc, B, nxt, sizeof nxt / sizeof nxt[0], &nn,
                      j == 0 ? unresolved : &unres) != 0) {
      st = -1;
      break;
    }
    if (j > 0) {
      /* a pair of a derivative's roots inside one ulp is one partition point */
      size_t a, b = 0;
      for (a = 0; a < nn; a++)
        if (b == 0 || nxt[a].lo != nxt[b - 1].lo || nxt[a].hi != nxt[b - 1].hi) nxt[b++] = nxt[a];
      nn = b;
    }
    memcpy(cur, nxt, nn * sizeof *cur);
    nc = nn;
  }
  for (j = 0; j < deg; j++) autobal_xpoly_clear(&d[j]);
  mpz_clear(w.val);
  mpz_clear(w.tmp);
  autobal_dyadic_clear(&w.x);
  if (st) return st;
  for (i = 0; i < nc; i++) {
    if (!(cur[i].hi > 0.0)) continue;
    if (m >= max) return -1;
    lo[m] = cur[i].lo;
    hi[m] = cur[i].hi;
    m++;
  }
  *n = m;
  return 0;
}
