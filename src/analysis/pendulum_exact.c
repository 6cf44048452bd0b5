/* pendulum_exact.c: P(x) of (10) in exact integer arithmetic (pendulum_exact.h).  A double is
 * a binary fraction, so R_m = r 2^-E and k = kappa 2^-F exactly, and every coefficient of (10),
 * every discriminant and every deciding quantity of the verdict at a dyadic W is an integer
 * after multiplication by a known power of 2: its sign is exact.  Near R_m -> 1/4 the critical
 * speeds come from a near-cancellation of these integers (the triple root x = -W of (10) at
 * R_m = 1/4, the series (14)), which no fixed floating-point precision survives for long.
 *
 * May use: the numerics (exact_poly.h), core.  Used by pendulum_verdict.c (its fall-back where
 * long double cannot decide), pendulum_critical.c and pendulum_map.c. */
#include "analysis/pendulum_exact.h"

#include "autobal/pendulum.h"
#include "autobal/stability.h"

/* The 16 terms of the discriminant of a x^4 + b x^3 + c x^2 + d x + e: coefficient and
 * exponents of (a, b, c, d, e) (the same table as pendulum_verdict.c's long double test). */
static const struct {
  int coef;
  int ex[5];
} QDISC[16] = {{256, {3, 0, 0, 0, 3}}, {-192, {2, 1, 0, 1, 2}}, {-128, {2, 0, 2, 0, 2}},
               {144, {2, 0, 1, 2, 1}}, {-27, {2, 0, 0, 4, 0}},  {144, {1, 2, 1, 0, 2}},
               {-6, {1, 2, 0, 2, 1}},  {-80, {1, 1, 2, 1, 1}},  {18, {1, 1, 1, 3, 0}},
               {16, {1, 0, 4, 0, 1}},  {-4, {1, 0, 3, 2, 0}},   {-27, {0, 4, 0, 0, 2}},
               {18, {0, 3, 1, 1, 1}},  {-4, {0, 3, 0, 3, 0}},   {-4, {0, 2, 3, 0, 1}},
               {1, {0, 2, 2, 2, 0}}};

static void set_binary_fraction(double v, mpz_t num, long *den_exp) {
  autobal_dyadic d;
  autobal_dyadic_init(&d);
  autobal_dyadic_set_d(&d, v);
  mpz_set(num, d.m);
  if (d.e >= 0) {
    mpz_mul_2exp(num, num, (mp_bitcnt_t)d.e);
    *den_exp = 0;
  } else {
    *den_exp = -d.e;
  }
  autobal_dyadic_clear(&d);
}

void autobal_pendulum_exact_init(autobal_pendulum_exact *x, double R_m, double k) {
  mpz_t G, L, r2k, t;
  int j;
  mpz_init(x->r);
  mpz_init(x->kappa);
  for (j = 0; j < 5; j++) {
    autobal_xpoly_init(&x->C[j]);
    mpz_init(x->v[j]);
  }
  mpz_init(x->t0);
  mpz_init(x->t1);
  mpz_init(x->t2);
  autobal_dyadic_init(&x->W);
  set_binary_fraction(R_m, x->r, &x->E);
  if (k == 0.0) {
    mpz_set_ui(x->kappa, 0);
    x->F = 0;
  } else {
    set_binary_fraction(k, x->kappa, &x->F);
  }
  mpz_inits(G, L, r2k, t, NULL);
  mpz_set_ui(G, 1);
  mpz_mul_2exp(G, G, (mp_bitcnt_t)(x->F + x->E)); /* G = 2^(F+E) */
  mpz_set_ui(L, 1);
  mpz_mul_2exp(L, L, (mp_bitcnt_t)(x->F + 2 * x->E)); /* L = 2^(F+2E) */
  mpz_mul(r2k, x->r, x->r);
  mpz_mul(r2k, r2k, x->kappa); /* kappa r^2 = L k R_m^2 */
  mpz_mul(t, x->r, G);         /* r G = L R_m */
  /* C0 = kappa r^2 W^4 */
  mpz_set(x->C[0].c[4], r2k);
  /* C1 = 2 r G (W^3 - W^2) + 4 kappa r^2 W^3 */
  mpz_mul_ui(x->C[1].c[2], t, 2);
  mpz_neg(x->C[1].c[2], x->C[1].c[2]);
  mpz_mul_ui(x->C[1].c[3], t, 2);
  mpz_addmul_ui(x->C[1].c[3], r2k, 4);
  /* C2 = L (W^2 - 2W + 1) + 2 r G (W^2 + 6W) + 6 kappa r^2 W^2 */
  mpz_set(x->C[2].c[0], L);
  mpz_mul_si(x->C[2].c[1], L, -2);
  mpz_addmul_ui(x->C[2].c[1], t, 12);
  mpz_set(x->C[2].c[2], L);
  mpz_addmul_ui(x->C[2].c[2], t, 2);
  mpz_addmul_ui(x->C[2].c[2], r2k, 6);
  /* C3 = 2 (L - r G)(W + 1) + 4 kappa r^2 W */
  mpz_sub(x->C[3].c[0], L, t);
  mpz_mul_ui(x->C[3].c[0], x->C[3].c[0], 2);
  mpz_set(x->C[3].c[1], x->C[3].c[0]);
  mpz_addmul_ui(x->C[3].c[1], r2k, 4);
  /* C4 = L - 2 r G + kappa r^2 */
  mpz_set(x->C[4].c[0], L);
  mpz_submul_ui(x->C[4].c[0], t, 2);
  mpz_add(x->C[4].c[0], x->C[4].c[0], r2k);
  for (j = 0; j < 5; j++) autobal_xpoly_normalize(&x->C[j]);
  mpz_clears(G, L, r2k, t, NULL);
}

void autobal_pendulum_exact_clear(autobal_pendulum_exact *x) {
  int j;
  mpz_clear(x->r);
  mpz_clear(x->kappa);
  for (j = 0; j < 5; j++) {
    autobal_xpoly_clear(&x->C[j]);
    mpz_clear(x->v[j]);
  }
  mpz_clear(x->t0);
  mpz_clear(x->t1);
  mpz_clear(x->t2);
  autobal_dyadic_clear(&x->W);
}

/* D = the discriminant of the quartic whose coefficients (a, b, c, d, e) are the polynomials
 * q[4], q[3], q[2], q[1], q[0] */
static void quartic_disc_poly(const autobal_xpoly q[5], autobal_xpoly *D) {
  autobal_xpoly pw[5][5], term;
  int i, j, t;
  for (i = 0; i < 5; i++)
    for (j = 0; j < 5; j++) autobal_xpoly_init(&pw[i][j]);
  autobal_xpoly_init(&term);
  for (i = 0; i < 5; i++) { /* i: 0 = a = q[4], ..., 4 = e = q[0] */
    mpz_set_ui(pw[i][0].c[0], 1);
    pw[i][0].len = 1;
    for (j = 1; j < 5; j++) (void)autobal_xpoly_mul(&pw[i][j], &pw[i][j - 1], &q[4 - i]);
  }
  autobal_xpoly_zero(D);
  for (t = 0; t < 16; t++) {
    autobal_xpoly_zero(&term);
    mpz_set_si(term.c[0], QDISC[t].coef);
    term.len = 1;
    for (i = 0; i < 5; i++) (void)autobal_xpoly_mul(&term, &term, &pw[i][QDISC[t].ex[i]]);
    (void)autobal_xpoly_addmul_si(D, &term, 1);
  }
  for (i = 0; i < 5; i++)
    for (j = 0; j < 5; j++) autobal_xpoly_clear(&pw[i][j]);
  autobal_xpoly_clear(&term);
}

void autobal_pendulum_exact_disc(autobal_pendulum_exact *x, autobal_xpoly *D) {
  quartic_disc_poly(x->C, D);
}

/* disc of the quartic with values a..e (mpz) into out; t0, t1 scratch */
static void quartic_disc_value(mpz_t out, mpz_t *v, mpz_t t0) {
  int t, i, e;
  mpz_set_ui(out, 0);
  for (t = 0; t < 16; t++) {
    mpz_set_si(t0, QDISC[t].coef);
    for (i = 0; i < 5; i++)
      for (e = 0; e < QDISC[t].ex[i]; e++) mpz_mul(t0, t0, v[4 - i]);
    mpz_add(out, out, t0);
  }
}

int autobal_pendulum_exact_verdict(autobal_pendulum_exact *x) {
  long sc;
  int j;
  mpz_t *v = x->v;
  /* v[j] = 2^(4s) L c_j(W): one positive factor for all five (scale degree 4) */
  for (j = 0; j < 5; j++) autobal_xpoly_eval_scaled(&x->C[j], &x->W, 4, v[j], x->t0, &sc);
  if (mpz_sgn(x->kappa) == 0) {
    /* x = 0 and the cubic a6 x^3 + a4 x^2 + a2 x + a0 = v4 x^3 + v3 x^2 + v2 x + v1 */
    int s0 = mpz_sgn(v[1]), sd;
    if (s0 < 0) return AUTOBAL_VERDICT_UNSTABLE;
    /* discriminant of the cubic */
    mpz_mul(x->t0, v[4], v[3]);
    mpz_mul(x->t0, x->t0, v[2]);
    mpz_mul(x->t0, x->t0, v[1]);
    mpz_mul_ui(x->t1, x->t0, 18);
    mpz_pow_ui(x->t0, v[3], 3);
    mpz_mul(x->t0, x->t0, v[1]);
    mpz_submul_ui(x->t1, x->t0, 4);
    mpz_mul(x->t0, v[3], v[2]);
    mpz_addmul(x->t1, x->t0, x->t0);
    mpz_pow_ui(x->t0, v[2], 3);
    mpz_mul(x->t0, x->t0, v[4]);
    mpz_submul_ui(x->t1, x->t0, 4);
    mpz_mul(x->t0, v[4], v[1]);
    mpz_mul(x->t0, x->t0, x->t0);
    mpz_submul_ui(x->t1, x->t0, 27);
    sd = mpz_sgn(x->t1);
    if (sd < 0) return AUTOBAL_VERDICT_UNSTABLE;
    if (mpz_sgn(v[2]) <= 0 || mpz_sgn(v[3]) <= 0 || mpz_sgn(v[4]) <= 0)
      return AUTOBAL_VERDICT_UNSTABLE;
    if (sd == 0 || s0 == 0) return AUTOBAL_VERDICT_MARGINAL;
    return AUTOBAL_VERDICT_STABLE;
  }
  {
    /* k > 0: c0 > 0; all roots real and <= 0 iff all c_j > 0 and four real roots */
    int sdisc, neg = 0;
    if (mpz_sgn(v[1]) <= 0 || mpz_sgn(v[2]) <= 0 || mpz_sgn(v[3]) <= 0 || mpz_sgn(v[4]) <= 0)
      return AUTOBAL_VERDICT_UNSTABLE;
    quartic_disc_value(x->t2, v, x->t0);
    sdisc = mpz_sgn(x->t2);
    if (sdisc < 0) return AUTOBAL_VERDICT_UNSTABLE;
    /* P8 = 8ac - 3b^2 (a = v4, b = v3, c = v2, d = v1, e = v0) */
    mpz_mul(x->t0, v[4], v[2]);
    mpz_mul_ui(x->t0, x->t0, 8);
    mpz_mul(x->t1, v[3], v[3]);
    mpz_submul_ui(x->t0, x->t1, 3);
    if (mpz_sgn(x->t0) >= 0) neg = 1;
    /* D4 = 64a^3e - 16a^2c^2 + 16ab^2c - 16a^2bd - 3b^4 */
    mpz_pow_ui(x->t0, v[4], 3);
    mpz_mul(x->t0, x->t0, v[0]);
    mpz_mul_ui(x->t1, x->t0, 64); /* t1 = D4 accumulates */
    mpz_mul(x->t0, v[4], v[2]);
    mpz_mul(x->t0, x->t0, x->t0);
    mpz_submul_ui(x->t1, x->t0, 16);
    mpz_mul(x->t0, v[3], v[3]);
    mpz_mul(x->t0, x->t0, v[4]);
    mpz_mul(x->t0, x->t0, v[2]);
    mpz_addmul_ui(x->t1, x->t0, 16);
    mpz_mul(x->t0, v[4], v[4]);
    mpz_mul(x->t0, x->t0, v[3]);
    mpz_mul(x->t0, x->t0, v[1]);
    mpz_submul_ui(x->t1, x->t0, 16);
    mpz_pow_ui(x->t0, v[3], 4);
    mpz_submul_ui(x->t1, x->t0, 3);
    if (mpz_sgn(x->t1) >= 0) neg = 1;
    if (sdisc == 0) return AUTOBAL_VERDICT_MARGINAL;
    return neg ? AUTOBAL_VERDICT_UNSTABLE : AUTOBAL_VERDICT_STABLE;
  }
}

int autobal_pendulum_exact_verdict_W(autobal_pendulum_exact *x, long double W) {
  autobal_dyadic_set_ld(&x->W, W);
  return autobal_pendulum_exact_verdict(x);
}

int autobal_pendulum_exact_verdict_Rw(autobal_pendulum_exact *x, double R_w) {
  autobal_dyadic_set_d(&x->W, R_w);
  mpz_mul(x->W.m, x->W.m, x->W.m);
  x->W.e *= 2;
  return autobal_pendulum_exact_verdict(x);
}
