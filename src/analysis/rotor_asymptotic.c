/* rotor_asymptotic.c: asymptotic stability conditions of the balanced motion of a rotor with one
 * ball autobalancer (light balls; high speed), the rotor's analogues of the pendulum's (7)-(9)
 * (autobal/rotor_asymptotic.h, docs/rotor.md "Asymptotic conditions", derivation in
 * tools/derive/derive_asymptotic.py).
 *
 * Computed from the closed system's data (autobal_rotor_closed) alone, with its own small complex
 * polynomial arithmetic: G = N(0) / D(0) at P = i omega, the quartic of the ball roots, the roots of
 * D D* and N N* for the small parameter, and the high-speed closed forms.
 *
 * May use: the public headers (autobal/rotor_stability.h for the closed system's data,
 * autobal/stability.h for polynomial roots) and core.  Calls no other analysis file. */
#include "autobal/rotor_asymptotic.h"
#include "autobal/stability.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "internal.h"

typedef double complex cplx;

/* r = a * b for ascending complex coefficient arrays (lengths na, nb; r has na + nb - 1). */
static void cmul(const cplx *a, size_t na, const cplx *b, size_t nb, cplx *r) {
  size_t i, j;
  for (i = 0; i < na + nb - 1; i++) r[i] = 0;
  for (i = 0; i < na; i++)
    for (j = 0; j < nb; j++) r[i + j] += a[i] * b[j];
}

/* Roots (re, im; 2n - 2 of them) of the real polynomial X X* (X complex, ascending, length n <= 5). */
static int roots_xx(const cplx *x, size_t n, double *re, double *im, autobal_error *err) {
  cplx xc[5], pr[9];
  double cr[9];
  size_t i, len = 2 * n - 1;
  for (i = 0; i < n; i++) xc[i] = conj(x[i]);
  cmul(x, n, xc, n, pr);
  for (i = 0; i < len; i++) cr[i] = creal(pr[i]); /* X X* is real: the imaginary parts cancel */
  return autobal_poly_roots_once_(cr, len, re, im, err);
}

/* x(z), ascending complex coefficients; conj_coef = 1 evaluates X* instead. */
static cplx ceval(const cplx *x, size_t n, cplx z, int conj_coef) {
  cplx v = 0;
  while (n-- > 0) v = v * z + (conj_coef ? conj(x[n]) : x[n]);
  return v;
}

/* Undamped balls (kappa = 0; autobal/rotor_asymptotic.h, derive_asymptotic2.py check 6): the four ball
 * roots to the next order where the leading order puts them on the imaginary axis, with their error
 * bounds eb and the largest relative error *eps; sets undamped_on_axis, undamped_delta,
 * undamped_ball_re/im and undamped_stable = 1 (the caller adds the real parts and the rotor roots). */
static void undamped(autobal_rotor_asymptotic *r, const cplx *D, const cplx *N, double w, double mb, double q, double c1,
                     const cplx *u, double *eb, double *eps) {
  double w2 = w * w, w4 = w2 * w2;
  /* P^4 N = x0 + x1 lambda + x2 lambda^2 + ..., P^4 = w^4 - 4 i w^3 lambda - 6 w^2 lambda^2 + ... */
  cplx x0 = w4 * N[0], x1 = -4.0 * I * w2 * w * N[0] + w4 * N[1], x2 = -6.0 * w2 * N[0] - 4.0 * I * w2 * w * N[1] + w4 * N[2];
  cplx h0 = x0 / D[0], h1 = (x1 - h0 * D[1]) / D[0], h2 = (x2 - h1 * D[1] - h0 * D[2]) / D[0]; /* Taylor of X / D */
  cplx g0 = 0.5 * mb * h0, g1 = 0.5 * mb * h1, g2 = 0.5 * mb * h2;
  double disc = q * q * creal(g0 * conj(g0)) - cimag(g0) * cimag(g0);
  size_t i;
  *eps = 0.0;
  r->undamped_stable = 1;
  r->undamped_on_axis = disc > 0.0 && creal(g0) + sqrt(disc) < 0.0;
  if (r->undamped_on_axis) {
    double rr = sqrt(disc), y[2];
    for (i = 0; i < 2; i++) y[i] = sqrt(-(creal(g0) + (i == 0 ? rr : -rr)));
    for (i = 0; i < 2; i++) {
      double sg = i == 0 ? 1.0 : -1.0, u0 = creal(g0) + sg * rr;
      double dl = 0.5 * creal(g1) + sg * (q * q * creal(g1 * conj(g0)) - cimag(g0) * cimag(g1)) / (2.0 * rr);
      /* f = (u - g)(u - g*) - q^2 g g*: the root u0 moves by -(f_g dg + f_g* dg*) / f_u, lambda by that over 2 i y */
      double fg = cabs(-(u0 - conj(g0)) - q * q * conj(g0)), fgs = cabs(-(u0 - g0) - q * q * g0), fu = 2.0 * rr;
      double sens = (fg + fgs) / (2.0 * fu * y[i]), rho = c1 * y[i], d1 = sens * cabs(g1) * y[i];
      double sep = fmin(2.0 * y[i], fabs(y[0] - y[1])), e;
      /* the Taylor terms of g beyond g1 (g2 exactly, the rest bounded by |g0| (c1 y)^n) and the second order */
      e = sens * (cabs(g2) * y[i] * y[i] + (rho < 1.0 ? cabs(g0) * rho * rho * rho / (1.0 - rho) : INFINITY)) +
          (sep > 0.0 ? 2.0 * d1 * d1 / sep : INFINITY);
      *eps = fmax(*eps, fmax(rho, sep > 0.0 ? d1 / sep : INFINITY));
      r->undamped_delta[i] = dl;
      r->undamped_ball_re[2 * i] = r->undamped_ball_re[2 * i + 1] = dl;
      r->undamped_ball_im[2 * i] = y[i], r->undamped_ball_im[2 * i + 1] = -y[i];
      eb[2 * i] = eb[2 * i + 1] = e;
    }
  } else { /* the leading order: the roots +-sqrt(u), error c1 |u| / 2 (relative c1 |u| / |2 lambda|) */
    r->undamped_delta[0] = r->undamped_delta[1] = NAN;
    for (i = 0; i < 4; i++) {
      cplx l = r->ball_re[i] + I * r->ball_im[i];
      double al = cabs(l), au = cabs(u[i / 2]);
      r->undamped_ball_re[i] = creal(l), r->undamped_ball_im[i] = cimag(l);
      eb[i] = 0.5 * c1 * au;
      *eps = fmax(*eps, al > 0.0 ? 0.5 * c1 * au / al : INFINITY);
    }
  }
}

/* The light-ball roots (L1), (L2) for the receptance G (autobal/rotor_asymptotic.h): sets G_re, G_im,
 * supercritical, kappa_min, light_stable (the balls' part), ball_re/ball_im; u[0..1] and *a_out = a. */
static void light_ball_roots(autobal_rotor_asymptotic *rp, cplx G, double mb, double w, double q, double kap, cplx *u,
                             double *a_out) {
  autobal_rotor_asymptotic r = *rp;
  double a;
  size_t i;
  r.G_re = creal(G);
  r.G_im = cimag(G);
  /* light balls: (u - a G)(u - a conj G) = (q a |G|)^2, u = lambda^2 + kappa lambda */
  a = 0.5 * mb * w * w * w * w;
  {
    double Gre = creal(G), Gim = cimag(G), G2 = Gre * Gre + Gim * Gim;
    double disc = q * q * G2 - Gim * Gim; /* (u - a Re G)^2 = a^2 disc */
    double br = Gim * Gim - q * q * G2;   /* the bracket of (L2) */
    cplx sq = csqrt((cplx)disc);
    u[0] = a * (Gre + sq);
    u[1] = a * (Gre - sq);
    r.supercritical = Gre < 0.0;
    if (Gre < 0.0) r.kappa_min = br > 0.0 ? sqrt(a * br / (-Gre)) : 0.0;
    else r.kappa_min = NAN;
    r.light_stable = kap > 0.0 && Gre < 0.0 && kap * kap * (-Gre) > a * br && q < 1.0;
    for (i = 0; i < 2; i++) {
      cplx s = csqrt(kap * kap + 4.0 * u[i]);
      cplx l1 = 0.5 * (-kap + s), l2 = 0.5 * (-kap - s);
      r.ball_re[2 * i] = creal(l1), r.ball_im[2 * i] = cimag(l1);
      r.ball_re[2 * i + 1] = creal(l2), r.ball_im[2 * i + 1] = cimag(l2);
    }
  }
  *a_out = a;
  *rp = r;
}

/* ---- anisotropic supports (one plane, paper inertia; autobal/rotor_asymptotic.h "ANISOTROPIC") ---- */

/* The rotor-housing's fixed-frame matrix Z(s) = M s^2 + H s + K (coordinates x, y, alpha, beta; (3.2)
 * without balls) as polynomials in s: Z[i][j][0..2] ascending. */
static void z_poly(const autobal_rotor_lumped *L, double w, cplx Z[4][4][3]) {
  const double Mm[4] = {L->M, L->M, L->A, L->A};
  const double H[4][4] = {{L->h_x, 0, 0, -L->h_xbeta},
                          {0, L->h_y, L->h_yalpha, 0},
                          {0, L->h_yalpha, L->h_alpha, L->C * w},
                          {-L->h_xbeta, 0, -L->C * w, L->h_beta}};
  const double K[4][4] = {{L->c_x, 0, 0, -L->c_xbeta},
                          {0, L->c_y, L->c_yalpha, 0},
                          {0, L->c_yalpha, L->c_alpha, 0},
                          {-L->c_xbeta, 0, 0, L->c_beta}};
  size_t i, j;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) {
      Z[i][j][0] = K[i][j];
      Z[i][j][1] = H[i][j];
      Z[i][j][2] = i == j ? Mm[i] : 0.0;
    }
}

/* det of a 4x4 matrix of quadratics (ascending, out[0..8]) by the permutation expansion, the
 * constant rank-one term c b^T added to every entry's s^0 coefficient when cb != NULL. */
static void det4_poly(cplx Z[4][4][3], const cplx cb[4][4], cplx out[9]) {
  static const int perm[24][4] = {{0,1,2,3},{0,1,3,2},{0,2,1,3},{0,2,3,1},{0,3,1,2},{0,3,2,1},
                                  {1,0,2,3},{1,0,3,2},{1,2,0,3},{1,2,3,0},{1,3,0,2},{1,3,2,0},
                                  {2,0,1,3},{2,0,3,1},{2,1,0,3},{2,1,3,0},{2,3,0,1},{2,3,1,0},
                                  {3,0,1,2},{3,0,2,1},{3,1,0,2},{3,1,2,0},{3,2,0,1},{3,2,1,0}};
  size_t p, i, k;
  for (k = 0; k < 9; k++) out[k] = 0;
  for (p = 0; p < 24; p++) {
    cplx acc[9] = {1.0}, e[3], t[9];
    size_t len = 1;
    int inv = 0, a, b;
    for (a = 0; a < 4; a++)
      for (b = a + 1; b < 4; b++)
        if (perm[p][a] > perm[p][b]) inv++;
    for (i = 0; i < 4; i++) {
      size_t j = (size_t)perm[p][i];
      e[0] = Z[i][j][0] + (cb ? cb[i][j] : 0.0), e[1] = Z[i][j][1], e[2] = Z[i][j][2];
      cmul(acc, len, e, 3, t);
      len += 2;
      for (k = 0; k < len; k++) acc[k] = t[k];
    }
    for (k = 0; k < 9; k++) out[k] += (inv % 2 ? -1.0 : 1.0) * acc[k];
  }
}

/* b^T Z(s)^-1 c for the 4x4 matrix of z_poly at s (Gaussian elimination, partial pivoting);
 * returns NAN + NAN i when Z(s) is singular. */
static cplx bzc(cplx Z[4][4][3], cplx s, const cplx b[4], const cplx c[4]) {
  cplx A[4][5], x[4], v = 0;
  size_t i, j, k;
  for (i = 0; i < 4; i++) {
    for (j = 0; j < 4; j++) A[i][j] = Z[i][j][0] + s * (Z[i][j][1] + s * Z[i][j][2]);
    A[i][4] = c[i];
  }
  for (k = 0; k < 4; k++) {
    size_t piv = k;
    for (i = k + 1; i < 4; i++)
      if (cabs(A[i][k]) > cabs(A[piv][k])) piv = i;
    if (!(cabs(A[piv][k]) > 0.0)) return NAN + NAN * I;
    if (piv != k)
      for (j = 0; j < 5; j++) {
        cplx t = A[k][j];
        A[k][j] = A[piv][j], A[piv][j] = t;
      }
    for (i = k + 1; i < 4; i++) {
      cplx f = A[i][k] / A[k][k];
      for (j = k; j < 5; j++) A[i][j] -= f * A[k][j];
    }
  }
  for (k = 4; k-- > 0;) {
    cplx t = A[k][4];
    for (j = k + 1; j < 4; j++) t -= A[k][j] * x[j];
    x[k] = t / A[k][k];
  }
  for (i = 0; i < 4; i++) v += b[i] * x[i];
  return v;
}

/* Anisotropic supports: G = G+, Gm = G-, the rotor-housing's roots and the small parameter. The light-ball
 * roots r->ball_*, u and q, kappa, a are already set by the caller.  Fills rotor_*, light_small,
 * light_decided, light_applicable, G_minus_*, avg_small and clears the high-speed and undamped entries. */
static int aniso_rest(const autobal_rotor_closed *c, autobal_rotor_asymptotic *r, cplx Z[4][4][3], const cplx *u,
                      double a, cplx Gm, autobal_error *err) {
  const double w = c->omega, d = c->plane[0].d, mb = c->plane[0].mass, kap = c->plane[0].kappa;
  const cplx eu[4] = {1.0, 0.0, 0.0, d}, ev[4] = {0.0, 1.0, -d, 0.0};
  cplx b[4], cv[4], cb[4][4], cb2[4][4], dz[9], dzc[9], dzc2[9], nn[9], n2[9], dd[8];
  double dr[9], rre[8], rim[8], zre[12], zim[12], c1, eps_b = 0.0, eps_r = 0.0, lre = -INFINITY, eavg;
  size_t i, j, k, nr = 0;
  int st, dec_unstable = 0, dec_stable = 1;
  for (i = 0; i < 4; i++) b[i] = eu[i] + I * ev[i], cv[i] = eu[i] - I * ev[i];
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) cb[i][j] = cv[i] * b[j], cb2[i][j] = b[i] * cv[j];
  /* det Z (real coefficients, degree 8) and n = b^T adj(Z) c = det(Z + c b^T) - det Z (degree 6: the s^8
   * and s^7 coefficients depend on M and H only and cancel), G+(s) = n / (2 det Z) */
  det4_poly(Z, NULL, dz);
  det4_poly(Z, cb, dzc);
  det4_poly(Z, cb2, dzc2); /* n2 = conj(b)^T adj(Z) b: the backward-backward receptance G~ = n2 / (2 det Z) */
  for (k = 0; k < 9; k++) dr[k] = creal(dz[k]);
  for (k = 0; k < 7; k++) nn[k] = dzc[k] - dz[k], n2[k] = dzc2[k] - dz[k];
  for (k = 0; k < 8; k++) dd[k] = (double)(k + 1) * dz[k + 1];
  if ((st = autobal_poly_roots_once_(dr, 9, rre, rim, err)) != 0) return st;
  {
    cplx n6[7];
    size_t len = 7;
    for (k = 0; k < 7; k++) n6[k] = nn[k];
    while (len > 1 && !(cabs(n6[len - 1]) > 0.0)) len--;
    if (len > 1) {
      /* roots of n n* (real), 2 (len - 1) of them; n n* may exceed roots_xx's cap of 5 coefficients */
      cplx nc[7], pr[13];
      double cr[13];
      for (k = 0; k < len; k++) nc[k] = conj(n6[k]);
      cmul(n6, len, nc, len, pr);
      for (k = 0; k < 2 * len - 1; k++) cr[k] = creal(pr[k]);
      if ((st = autobal_poly_roots_once_(cr, 2 * len - 1, zre, zim, err)) != 0) return st;
      nr = 2 * (len - 1);
    }
  }
  /* c1: a bound of |d log(a G+(i omega + lambda) P^4) / d lambda| near lambda = 0, as for isotropic supports:
   * 4/|omega| + sum 1/|s_k - i omega| over the poles (the roots of det Z) and the zeros (of n n*) */
  c1 = 4.0 / fabs(w);
  for (k = 0; k < 8; k++) c1 += 1.0 / hypot(rre[k], rim[k] - w);
  for (k = 0; k < nr; k++) c1 += 1.0 / hypot(zre[k], zim[k] - w);
  /* averaging: the backward part G- turns at -2 omega in the rotating frame; its effect on u is of second
   * order, a^2 |G-|^2 / (4 omega^2), relative to |u| ~ a |G+| (an estimate, checked by the scan of
   * docs/rotor.md, not a bound) */
  eavg = a * cabs(Gm) * cabs(Gm) / (4.0 * w * w * fmax(cabs(r->G_re + I * r->G_im), DBL_MIN));
  r->avg_small = eavg;
  /* the rotor-housing's 8 roots s_k (fixed frame), shifted to first order by the balls like the isotropic
   * roots of D, through both channels: the centre's forward part seen by the balls at lambda = s_k - i omega
   * (weight Res(G+, s_k)) and its backward part at mu = s_k + i omega (weight Res(G~, s_k)),
   *     delta_k = (m_b / 2) s_k^4 (Res(G+, s_k) / (lambda^2 + kappa lambda) + Res(G~, s_k) / (mu^2 + kappa mu)),
   * Res(G, s_k) = n(s_k) / (2 det'(s_k)).  For isotropic supports one of the two residues vanishes and this is
   * the shift of the roots of D (and of their conjugates).  Reported in rotating coordinates s_k - i omega
   * (real parts: the Floquet exponents'), the four with Im s_k >= 0; the error of each is eps_r |delta_k|. */
  {
    cplx shift[8];
    j = 0;
    for (k = 0; k < 8; k++) {
      cplx sk = rre[k] + I * rim[k], lk = sk - I * w, mk = sk + I * w, s4 = sk * sk * sk * sk, dp = ceval(dd, 8, sk, 0);
      double sep = fmin(fmin(cabs(lk), cabs(lk + kap)), fmin(cabs(mk), cabs(mk + kap)));
      size_t m;
      for (m = 0; m < 8; m++)
        if (m != k) sep = fmin(sep, hypot(rre[m] - rre[k], rim[m] - rim[k]));
      shift[k] = 0.5 * mb * s4 *
                 (ceval(nn, 7, sk, 0) / (2.0 * dp * (lk * lk + kap * lk)) + ceval(n2, 7, sk, 0) / (2.0 * dp * (mk * mk + kap * mk)));
      eps_r = fmax(eps_r, sep > 0.0 ? cabs(shift[k]) / sep : INFINITY);
    }
    for (k = 0; k < 8; k++) {
      cplx nl = rre[k] + I * (rim[k] - w) + shift[k];
      lre = fmax(lre, creal(nl));
      if (rim[k] >= 0.0 && j < 4) r->rotor_re[j] = creal(nl), r->rotor_im[j] = cimag(nl), j++;
      if (creal(nl) >= eps_r * cabs(shift[k])) dec_unstable = 1;
      if (!(creal(nl) <= -eps_r * cabs(shift[k]))) dec_stable = 0; /* STABLE: every root below minus its error */
    }
  }
  for (; j < 4; j++) r->rotor_re[j] = r->rotor_im[j] = NAN;
  for (j = 0; j < 4; j++) {
    cplx lj = r->ball_re[j] + I * r->ball_im[j];
    double rel = (c1 * cabs(u[j / 2]) + eavg * cabs(u[j / 2])) / cabs(2.0 * lj + kap), e = rel * cabs(lj);
    eps_b = fmax(eps_b, rel);
    if (r->ball_re[j] >= e) dec_unstable = 1;
    if (!(r->ball_re[j] <= -e)) dec_stable = 0;
  }
  r->rotor_re_max = lre;
  r->light_stable = r->light_stable && lre < 0.0;
  r->light_small = fmax(fmax(eps_b, eps_r), eavg);
  r->light_decided = dec_unstable || dec_stable;
  r->light_applicable = r->light_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL;
  r->G_minus_re = creal(Gm);
  r->G_minus_im = cimag(Gm);
  r->undamped_delta[0] = r->undamped_delta[1] = r->undamped_small = NAN;
  r->m_eff = r->h_eff = r->kappa_inf = r->high_small = NAN;
  return AUTOBAL_SUCCESS;
}

/* The high-speed entries (H1), (H2) (paper inertia, A != C): G -> -(ginf + i eta / omega) / omega^2.  With
 * anisotropic supports G = G+ and eta is the mean of the x and the y planes' damping terms (the stiffness enters
 * G+ only at omega^-4; G- = O(omega^-3) turns at -2 omega and averages out: tools/derive/derive_aniso_high.py);
 * for isotropic supports the means are the isotropic coefficients themselves, bit for bit.  The highest
 * undamped natural frequency at rest wmax is that of the x plane and of the y plane, the larger. */
static void high_speed(autobal_rotor_asymptotic *r, const autobal_rotor_lumped *L, double d, double mb, double ma,
                       double kap, double w) {
  r->high_defined = ma == 0.0 && L->A != L->C;
  if (r->high_defined) {
    const double hx = 0.5 * (L->h_x + L->h_y), hxb = 0.5 * (L->h_xbeta + L->h_yalpha),
                 ha = 0.5 * (L->h_alpha + L->h_beta);
    double M = L->M, Ap = L->A - L->C, ginf = 1.0 / M + d * d / Ap;
    double eta = hx / (M * M) - 2.0 * d * hxb / (M * Ap) + d * d * ha / (Ap * Ap);
    /* highest undamped natural frequency at rest: eigenvalues of diag(M, A)^-1 [[c, -c_c], [-c_c, c_t]] */
    double tr = L->c_x / M + L->c_alpha / L->A;
    double det = (L->c_x * L->c_alpha - L->c_xbeta * L->c_xbeta) / (M * L->A);
    double wmax = sqrt(fmax(0.0, 0.5 * (tr + sqrt(fmax(0.0, tr * tr - 4.0 * det)))));
    if (r->anisotropic) {
      double tr_y = L->c_y / M + L->c_beta / L->A;
      double det_y = (L->c_y * L->c_beta - L->c_yalpha * L->c_yalpha) / (M * L->A);
      wmax = fmax(wmax, sqrt(fmax(0.0, 0.5 * (tr_y + sqrt(fmax(0.0, tr_y * tr_y - 4.0 * det_y))))));
    }
    r->m_eff = 1.0 / ginf;
    r->h_eff = eta / (ginf * ginf);
    if (ginf > 0.0) {
      r->kappa_inf = sqrt(0.5 * mb * ginf) * eta / ginf;
      r->high_stable = kap > r->kappa_inf;
      r->high_small = fmax(sqrt(0.5 * mb * ginf), wmax / fabs(w));
    } else { /* (H1) fails: Re G > 0 at high speed */
      r->kappa_inf = NAN;
      r->high_stable = 0;
      r->high_small = fmax(sqrt(0.5 * mb * fabs(ginf)), wmax / fabs(w));
    }
    if (r->anisotropic) r->high_small = fmax(r->high_small, r->avg_small);
    r->high_applicable = r->high_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL;
  } else {
    r->m_eff = r->h_eff = r->kappa_inf = r->high_small = NAN;
  }
}

int autobal_rotor_asymptotic_conditions(const autobal_rotor_closed *c, autobal_rotor_asymptotic *out,
                                        autobal_error *err) {
  const autobal_rotor_closed_plane *pl;
  const autobal_rotor_lumped *L;
  autobal_rotor_asymptotic r;
  double w, d, mb, ma, kap, a, q;
  cplx P[2], P2[3], K11[3], K12[3], K22[3], t1[5], t2[5], D[5], N[3], G, u[2];
  size_t i;
  int st;
  if (c == NULL || out == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "asymptotic conditions: NULL argument");
  if (c->n_planes != 1 || !c->closure_ok)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "asymptotic conditions: need one plane and the closure (3.16) (n_planes %zu, closure %d)",
                             c->n_planes, c->closure_ok);
  if (!c->isotropic && (c->plane[0].m_add != 0.0 || !(c->plane[0].kappa > 0.0)))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "asymptotic conditions: anisotropic supports need the paper inertia and kappa > 0 "
                             "(m_add %g kg, kappa %g 1/s)",
                             c->plane[0].m_add, c->plane[0].kappa);
  pl = &c->plane[0];
  L = &c->L;
  w = c->omega;
  d = pl->d;
  mb = pl->mass;
  ma = pl->m_add;
  kap = pl->kappa;
  if (!(w != 0.0) || !isfinite(w))
    return autobal_error_set(err, AUTOBAL_EINVAL, "asymptotic conditions: omega = %g (must be non-zero)", w);
  if (!(kap >= 0.0) || !(mb > 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "asymptotic conditions: ball damping rate kappa = %g 1/s (must be >= 0), ball mass %g kg "
                             "(must be > 0)",
                             kap, mb);
  memset(&r, 0, sizeof r);
  r.kappa = kap;
  q = hypot(pl->Q_re, pl->Q_im) / mb;
  r.q = q;
  r.G_minus_re = r.G_minus_im = 0.0;
  r.avg_small = 0.0;
  if (!c->isotropic) { /* G = G+, the forward receptance of the fixed-frame rotor-housing at i omega */
    const cplx eu[4] = {1.0, 0.0, 0.0, d}, ev[4] = {0.0, 1.0, -d, 0.0};
    cplx Z[4][4][3], b[4], cv[4], Gm;
    for (i = 0; i < 4; i++) b[i] = eu[i] + I * ev[i], cv[i] = eu[i] - I * ev[i];
    z_poly(L, w, Z);
    G = 0.5 * bzc(Z, I * w, b, cv);
    Gm = 0.5 * bzc(Z, -I * w, b, b);
    if (!isfinite(creal(G)) || !isfinite(cimag(G)) || !isfinite(creal(Gm)) || !isfinite(cimag(Gm)))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "asymptotic conditions: Z(+-i omega) singular (an undamped resonance of the "
                               "rotor-housing at omega = %g rad/s)",
                               w);
    r.anisotropic = 1;
    light_ball_roots(&r, G, mb, w, q, kap, u, &a);
    if ((st = aniso_rest(c, &r, Z, u, a, Gm, err)) != 0) return st;
    high_speed(&r, L, d, mb, 0.0, kap, w);
    *out = r;
    return AUTOBAL_SUCCESS;
  }
  /* the polynomials of Delta (autobal/rotor_stability.h), P = lambda + i omega */
  P[0] = I * w;
  P[1] = 1.0;
  cmul(P, 2, P, 2, P2);
  for (i = 0; i < 3; i++) {
    K11[i] = (L->M + ma) * P2[i] + (i < 2 ? L->h_x * P[i] : 0.0) + (i == 0 ? L->c_x : 0.0);
    K12[i] = -((i < 2 ? L->h_xbeta * P[i] : 0.0) + (i == 0 ? L->c_xbeta : 0.0)) + ma * d * P2[i];
    K22[i] = (L->A + ma * d * d) * P2[i] + (i < 2 ? (L->h_alpha - I * L->C * w) * P[i] : 0.0) +
             (i == 0 ? L->c_alpha : 0.0);
  }
  cmul(K11, 3, K22, 3, t1);
  cmul(K12, 3, K12, 3, t2);
  for (i = 0; i < 5; i++) D[i] = t1[i] - t2[i];
  for (i = 0; i < 3; i++) N[i] = K22[i] - 2.0 * d * K12[i] + d * d * K11[i];
  if (!(cabs(D[0]) > 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "asymptotic conditions: D(0) = 0 (an undamped resonance of the rotor-housing at omega = %g rad/s)",
                             w);
  G = N[0] / D[0];
  light_ball_roots(&r, G, mb, w, q, kap, u, &a);
  {
    /* the rotor-housing's roots: the 4 roots of D among the 8 of D D*, shifted to first order in
     * the balls, delta_k = (m_b / 2) P^4 N / ((lambda^2 + kappa lambda) D') at lambda_k; their
     * small parameter |delta_k| / (distance of lambda_k from 0, -kappa and the other roots) */
    double dre[8], dim_[8], nre[4], nim[4], ratio[8], eps_b, eps_r = 0.0, lre = -INFINITY, c1;
    cplx Dd[4];
    size_t j, k, pick[8];
    int dec_unstable = 0, dec_stable = 1;
    if ((st = roots_xx(D, 5, dre, dim_, err)) != 0) return st;
    if ((st = roots_xx(N, 3, nre, nim, err)) != 0) return st;
    for (j = 0; j < 4; j++) Dd[j] = (double)(j + 1) * D[j + 1];
    for (j = 0; j < 8; j++) {
      cplx z = dre[j] + I * dim_[j];
      double a1 = cabs(ceval(D, 5, z, 0)), a2 = cabs(ceval(D, 5, z, 1));
      ratio[j] = a1 / fmax(a2, DBL_MIN);
      pick[j] = j;
    }
    for (j = 1; j < 8; j++) /* the 4 smallest |D| / |D*| (insertion sort) */
      for (k = j; k > 0 && ratio[pick[k]] < ratio[pick[k - 1]]; k--) {
        size_t t = pick[k];
        pick[k] = pick[k - 1], pick[k - 1] = t;
      }
    for (j = 0; j < 4; j++) {
      size_t m = pick[j];
      cplx lk = dre[m] + I * dim_[m], Pk = lk + I * w, P4 = Pk * Pk * Pk * Pk, dl, nl;
      double sep = fmin(cabs(lk), cabs(lk + kap));
      for (k = 0; k < 8; k++)
        if (k != m) sep = fmin(sep, hypot(dre[k] - dre[m], dim_[k] - dim_[m]));
      dl = 0.5 * mb * P4 * ceval(N, 3, lk, 0) / ((lk * lk + kap * lk) * ceval(Dd, 4, lk, 0));
      nl = lk + dl;
      r.rotor_re[j] = creal(nl), r.rotor_im[j] = cimag(nl);
      eps_r = fmax(eps_r, sep > 0.0 ? cabs(dl) / sep : INFINITY);
      lre = fmax(lre, creal(nl));
    }
    /* the ball roots' error: freezing a G P^4 at lambda = 0 changes u_j by at most |u_j| |lambda_j| c1,
     * c1 = sum 1/|root| over D D* and N N* plus 4/|omega| (a bound of |d log(a G P^4)/d lambda| near 0),
     * so lambda_j by e_j = c1 |lambda_j| |u_j| / |2 lambda_j + kappa|: relative c1 |u_j| / |2 lambda_j + kappa| */
    c1 = 4.0 / fabs(w);
    for (k = 0; k < 8; k++) c1 += 1.0 / hypot(dre[k], dim_[k]);
    for (k = 0; k < 4; k++) c1 += 1.0 / hypot(nre[k], nim[k]);
    eps_b = 0.0;
    /* decided: some predicted real part >= its error (UNSTABLE) or all <= -error (STABLE); rotor root
     * k: error eps_r |shift_k| */
    for (j = 0; j < 8; j++) {
      double re, e;
      if (j < 4) {
        cplx lj = r.ball_re[j] + I * r.ball_im[j];
        double rel = c1 * cabs(u[j / 2]) / cabs(2.0 * lj + kap);
        eps_b = fmax(eps_b, rel);
        re = r.ball_re[j];
        e = rel * cabs(lj);
      } else {
        cplx dl = (r.rotor_re[j - 4] + I * r.rotor_im[j - 4]) - (dre[pick[j - 4]] + I * dim_[pick[j - 4]]);
        re = r.rotor_re[j - 4];
        e = eps_r * cabs(dl);
      }
      if (re >= e) dec_unstable = 1;
      if (!(re <= -e)) dec_stable = 0;
    }
    r.rotor_re_max = lre;
    r.light_stable = r.light_stable && lre < 0.0;
    r.light_small = fmax(eps_b, eps_r);
    r.light_decided = dec_unstable || dec_stable;
    r.light_applicable = r.light_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL;
    if (kap == 0.0) { /* undamped balls: the light-ball entry is no condition, the next order decides */
      double eb[4], epsu = 0.0;
      r.light_stable = r.light_decided = r.light_applicable = 0;
      r.light_small = NAN;
      r.undamped_defined = 1;
      undamped(&r, D, N, w, mb, q, c1, u, eb, &epsu);
      dec_unstable = 0, dec_stable = 1;
      for (j = 0; j < 8; j++) {
        double re, e;
        if (j < 4) {
          re = r.undamped_ball_re[j];
          e = eb[j];
        } else {
          cplx dl = (r.rotor_re[j - 4] + I * r.rotor_im[j - 4]) - (dre[pick[j - 4]] + I * dim_[pick[j - 4]]);
          re = r.rotor_re[j - 4];
          e = eps_r * cabs(dl);
        }
        if (re >= e) dec_unstable = 1;
        if (!(re <= -e)) dec_stable = 0;
        if (j < 4 && !(re < 0.0)) r.undamped_stable = 0;
      }
      r.undamped_stable = r.undamped_stable && lre < 0.0;
      r.undamped_small = fmax(epsu, eps_r);
      r.undamped_decided = dec_unstable || dec_stable;
      r.undamped_applicable = r.undamped_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL;
    } else {
      r.undamped_delta[0] = r.undamped_delta[1] = r.undamped_small = NAN;
    }
  }
  high_speed(&r, L, d, mb, ma, kap, w);
  *out = r;
  return AUTOBAL_SUCCESS;
}
