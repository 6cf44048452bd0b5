/* rotor_unbalance_aniso.c: stability of the balanced motion for EVERY unbalance in a range with
 * ANISOTROPIC supports (one plane, two balls with a common h/m, the paper's inertia model), by Hill's
 * method with a guaranteed exclusion of crossings (docs/rotor.md "Every unbalance, anisotropic
 * supports").
 *
 * In the rotating frame (W = (x + i y) e^{-i w t}, Theta = (beta - i alpha) e^{-i w t}, ball angles
 * relative) the balls' coefficients are constant and the supports' anisotropy is periodic with
 * harmonics e^{+-2 i w t}: M X'' + C(t) X' + K(t) X = 0, M constant, C(t) = C0 + C+ e^{2iwt} + C- e^{-2iwt}
 * (likewise K).  The matrices are built from the Floquet code's own linearization (rotor_floquet.c:
 * M(t), C(t), K(t) in the mixed frame) by X_fixed = T(t) X_rot, premultiplied by T^T, and split into
 * harmonics by an 8-point DFT over one revolution (harmonics +-1, +-3, 4 must vanish: checked).
 *
 * Turning the whole ball configuration is a time shift, so the linearization depends on the balls
 * only through the angle between them: psi_1 = theta, psi_2 = -theta (delta = 2 theta), and every
 * matrix entry is a + b cos theta + c sin theta (each entry involves one ball), found from theta = 0,
 * pi/2, pi and checked at theta = 1.  The unbalance is s(theta)^2 = a1^2 + a2^2 + 2 a1 a2 cos 2 theta.
 * The mirror configuration (theta < 0) is a second branch unless the balls are identical.
 *
 * Hill: X = e^{lambda t} sum_k X_k e^{2 i k w t}; H[k][k] = M s_k^2 + C0 s_k + K0, H[k][k-1] =
 * C+ s_{k-1} + K+, H[k][k+1] = C- s_{k+1} + K-, s_k = lambda + 2 i k w.  A Floquet multiplier is on the
 * unit circle iff H(i nu) has a kernel in l^2 for some nu in [0, w].  Truncated at |k| <= N; the tail
 * is bounded by a Neumann series (see tail_bound), the perturbation over a box (nu, theta) by the
 * Lipschitz bounds of box_delta, and a box is excluded when sigma_min(H_N(centre)) exceeds both.
 *
 * May use: the handle (rotor_stab_handle.h), rotor_floquet.h, GSL linear algebra, core (internal.h). */
#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_permutation.h>
#include <gsl/gsl_matrix.h>

#include "analysis/rotor_floquet.h"
#include "analysis/rotor_stab_handle.h"
#include "analysis/rotor_unbalance_aniso.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define NM 6 /* x, y, alpha, beta, dpsi_1, dpsi_2 */
#define NN (NM * NM)
#define HILL_NMAX 40
#define HILL_TAIL_TOL 1e-4   /* the tail bound aimed at when choosing N (scaled units) */
#define HILL_BOXES 20000L   /* box budget (per call) */
#define HILL_FLOQUET_OPEN 24 /* Floquet samples in the boxes left open */

typedef double complex cplx;

/* One harmonic set: M (real, constant), C0, K0 (real), C+, K+ (complex; C- = conj(C+)). */
typedef struct hill_set {
  double M[NN], C0[NN], K0[NN];
  cplx Cp[NN], Kp[NN];
} hill_set;

/* Frobenius norm. */
static double fro_r(const double *a) {
  double v = 0.0;
  size_t i;
  for (i = 0; i < NN; i++) v += a[i] * a[i];
  return sqrt(v);
}
static double fro_c(const cplx *a) {
  double v = 0.0;
  size_t i;
  for (i = 0; i < NN; i++) v += creal(a[i]) * creal(a[i]) + cimag(a[i]) * cimag(a[i]);
  return sqrt(v);
}

/* The rotating-frame matrices at time t (scaled: rows P, columns S; C / w, K / w^2). */
static int rot_mats(autobal_rotor_stab *s, double t, const double P[NM], const double S[NM], double Mr[NN],
                    double Cr[NN], double Kr[NN]) {
  const double w = s->cur.omega, c = cos(w * t), sn = sin(w * t);
  double M[NN], C[NN], K[NN], T[NN] = {0}, Tp[NN] = {0}, Tpp[NN] = {0}, A1[NN], A2[NN], A3[NN];
  size_t i, j, k;
  int st;
  if ((st = autobal_rotor_stab_lin2_(s, t, M, C, K)) != AUTOBAL_SUCCESS) return st;
  /* T: rows fixed (x, y, alpha, beta, psi1, psi2), columns rotating (u, v, a, b, psi1, psi2):
   * x + i y = (u + i v) e^{i w t}, beta - i alpha = (b + i a) e^{i w t} */
  T[0 * NM + 0] = c, T[0 * NM + 1] = -sn, T[1 * NM + 0] = sn, T[1 * NM + 1] = c;
  T[3 * NM + 3] = c, T[3 * NM + 2] = -sn, T[2 * NM + 3] = -sn, T[2 * NM + 2] = -c;
  T[4 * NM + 4] = T[5 * NM + 5] = 1.0;
  Tp[0 * NM + 0] = -sn * w, Tp[0 * NM + 1] = -c * w, Tp[1 * NM + 0] = c * w, Tp[1 * NM + 1] = -sn * w;
  Tp[3 * NM + 3] = -sn * w, Tp[3 * NM + 2] = -c * w, Tp[2 * NM + 3] = -c * w, Tp[2 * NM + 2] = sn * w;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) Tpp[i * NM + j] = -w * w * T[i * NM + j];
  /* A1 = M T, A2 = 2 M T' + C T, A3 = M T'' + C T' + K T */
  for (i = 0; i < NM; i++)
    for (j = 0; j < NM; j++) {
      double a1 = 0.0, a2 = 0.0, a3 = 0.0;
      for (k = 0; k < NM; k++) {
        a1 += M[i * NM + k] * T[k * NM + j];
        a2 += 2.0 * M[i * NM + k] * Tp[k * NM + j] + C[i * NM + k] * T[k * NM + j];
        a3 += M[i * NM + k] * Tpp[k * NM + j] + C[i * NM + k] * Tp[k * NM + j] + K[i * NM + k] * T[k * NM + j];
      }
      A1[i * NM + j] = a1, A2[i * NM + j] = a2, A3[i * NM + j] = a3;
    }
  for (i = 0; i < NM; i++)
    for (j = 0; j < NM; j++) {
      double m = 0.0, cc = 0.0, kk = 0.0;
      for (k = 0; k < NM; k++) {
        m += T[k * NM + i] * A1[k * NM + j];
        cc += T[k * NM + i] * A2[k * NM + j];
        kk += T[k * NM + i] * A3[k * NM + j];
      }
      Mr[i * NM + j] = P[i] * m * S[j];
      Cr[i * NM + j] = P[i] * cc * S[j] / w;
      Kr[i * NM + j] = P[i] * kk * S[j] / (w * w);
    }
  return AUTOBAL_SUCCESS;
}

/* The harmonic set at the handle's ball angles (psi valid): 8 samples over one revolution, DFT;
 * harmonics other than 0, +-2 of w t must vanish (1e-9 relative), M must be constant. */
static int harmonics(autobal_rotor_stab *s, const double P[NM], const double S[NM], hill_set *h) {
  const double T = 2.0 * M_PI / fabs(s->cur.omega), sg = s->cur.omega > 0.0 ? 1.0 : -1.0;
  double Ms[8][NN], Cs[8][NN], Ks[8][NN], big = 0.0, bad = 0.0;
  size_t j, i, q;
  int st;
  for (j = 0; j < 8; j++)
    if ((st = rot_mats(s, T * (double)j / 8.0, P, S, Ms[j], Cs[j], Ks[j])) != AUTOBAL_SUCCESS) return st;
  for (i = 0; i < NN; i++) {
    cplx hc[8], hk[8], hm[8];
    for (q = 0; q < 8; q++) {
      hc[q] = hk[q] = hm[q] = 0.0;
      for (j = 0; j < 8; j++) {
        /* omega t_j = sg 2 pi j / 8: harmonic e^{i q' w t} with q' = sg q */
        const cplx e = cexp(-I * sg * 2.0 * M_PI * (double)(q * j) / 8.0) / 8.0;
        hc[q] += Cs[j][i] * e, hk[q] += Ks[j][i] * e, hm[q] += Ms[j][i] * e;
      }
    }
    h->M[i] = creal(hm[0]);
    h->C0[i] = creal(hc[0]);
    h->K0[i] = creal(hk[0]);
    h->Cp[i] = hc[2];
    h->Kp[i] = hk[2];
    big = fmax(big, fmax(fabs(h->M[i]), fmax(fabs(h->C0[i]), fabs(h->K0[i]))));
    for (q = 1; q < 8; q++) {
      if (q == 2 || q == 6) bad = fmax(bad, cabs(hm[q]));
      else if (q != 2 && q != 6) bad = fmax(bad, fmax(cabs(hm[q]), fmax(cabs(hc[q]), cabs(hk[q]))));
    }
  }
  if (!(bad <= 1e-9 * big))
    return autobal_error_set(&s->err, AUTOBAL_ENUMERIC,
                             "every unbalance, anisotropic: the rotating-frame linearization has harmonics other "
                             "than 0 and +-2 (relative %.3g; internal error)",
                             bad / big);
  return AUTOBAL_SUCCESS;
}

/* The balls' dependence: every entry is a + b cos theta + c sin theta (psi_1 = theta, psi_2 = -theta). */
typedef struct hill_trig {
  hill_set a, b, c;
  /* amplitude bounds sqrt(|b|^2 + |c|^2), Frobenius: |dF/dtheta| <= rho */
  double rM, rC0, rK0, rCp, rKp;
  double P[NM], S[NM];
} hill_trig;

static void set_at(const hill_trig *g, double th, hill_set *h) {
  const double c = cos(th), sn = sin(th);
  size_t i;
  for (i = 0; i < NN; i++) {
    h->M[i] = g->a.M[i] + g->b.M[i] * c + g->c.M[i] * sn;
    h->C0[i] = g->a.C0[i] + g->b.C0[i] * c + g->c.C0[i] * sn;
    h->K0[i] = g->a.K0[i] + g->b.K0[i] * c + g->c.K0[i] * sn;
    h->Cp[i] = g->a.Cp[i] + g->b.Cp[i] * c + g->c.Cp[i] * sn;
    h->Kp[i] = g->a.Kp[i] + g->b.Kp[i] * c + g->c.Kp[i] * sn;
  }
}

static double set_diff(const hill_set *x, const hill_set *y) {
  double d = 0.0, m = 0.0;
  size_t i;
  for (i = 0; i < NN; i++) {
    d = fmax(d, fmax(fabs(x->M[i] - y->M[i]), fmax(fabs(x->C0[i] - y->C0[i]), fabs(x->K0[i] - y->K0[i]))));
    d = fmax(d, fmax(cabs(x->Cp[i] - y->Cp[i]), cabs(x->Kp[i] - y->Kp[i])));
    m = fmax(m, fmax(fabs(x->M[i]), fmax(fabs(x->C0[i]), fabs(x->K0[i]))));
  }
  return d / fmax(m, DBL_MIN);
}

/* The trig form from theta = 0, pi/2, pi (handle's psi overridden, restored), checked at theta = 1. */
/* The scales: lengths ell = (a1 + a2) / M, tilts ell / rg; rows so that M's diagonal is 1; balls with a
 * unit diagonal and symmetric couplings sqrt(m_b / M) (the kinetic energy's form). */
static void set_scales(const autobal_rotor_stab *s, hill_trig *g) {
  const autobal_rotor_plane *pl = &s->cur.plane[0];
  const double rg = sqrt(s->L.A / s->L.M);
  const double ell = (pl->ball_mass[0] * pl->ball_radius[0] + pl->ball_mass[1] * pl->ball_radius[1]) / s->L.M;
  g->S[0] = g->S[1] = ell, g->S[2] = g->S[3] = ell / rg;
  g->P[0] = g->P[1] = 1.0 / (s->L.M * ell), g->P[2] = g->P[3] = rg / (s->L.A * ell);
  g->S[4] = ell * sqrt(s->L.M / pl->ball_mass[0]) / pl->ball_radius[0], g->P[4] = 1.0 / g->S[4];
  g->S[5] = ell * sqrt(s->L.M / pl->ball_mass[1]) / pl->ball_radius[1], g->P[5] = 1.0 / g->S[5];
}

static int build_trig(autobal_rotor_stab *s, hill_trig *g) {
  const double save0 = s->psi[0], save1 = s->psi[1], th[4] = {0.0, 0.5 * M_PI, M_PI, 1.0};
  hill_set h[4], chk;
  double ra[5] = {0};
  size_t q, i;
  int st = AUTOBAL_SUCCESS;
  for (q = 0; q < 4 && st == AUTOBAL_SUCCESS; q++) {
    s->psi[0] = th[q];
    s->psi[1] = -th[q];
    st = harmonics(s, g->P, g->S, &h[q]);
  }
  s->psi[0] = save0;
  s->psi[1] = save1;
  if (st != AUTOBAL_SUCCESS) return st;
  /* F(0) = a + b, F(pi) = a - b, F(pi/2) = a + c */
#define TRIG(F)                                                                                                     \
  for (i = 0; i < NN; i++) {                                                                                        \
    g->a.F[i] = 0.5 * (h[0].F[i] + h[2].F[i]);                                                                      \
    g->b.F[i] = 0.5 * (h[0].F[i] - h[2].F[i]);                                                                      \
    g->c.F[i] = h[1].F[i] - g->a.F[i];                                                                              \
  }
  TRIG(M)
  TRIG(C0)
  TRIG(K0)
  TRIG(Cp)
  TRIG(Kp)
#undef TRIG
  set_at(g, th[3], &chk);
  if (!(set_diff(&chk, &h[3]) <= 1e-9))
    return autobal_error_set(&s->err, AUTOBAL_ENUMERIC,
                             "every unbalance, anisotropic: the linearization is not of the form a + b cos theta + "
                             "c sin theta in the balls' half angle (relative %.3g; internal error)",
                             set_diff(&chk, &h[3]));
  for (i = 0; i < NN; i++) {
    ra[0] += g->b.M[i] * g->b.M[i] + g->c.M[i] * g->c.M[i];
    ra[1] += g->b.C0[i] * g->b.C0[i] + g->c.C0[i] * g->c.C0[i];
    ra[2] += g->b.K0[i] * g->b.K0[i] + g->c.K0[i] * g->c.K0[i];
    ra[3] += cabs(g->b.Cp[i]) * cabs(g->b.Cp[i]) + cabs(g->c.Cp[i]) * cabs(g->c.Cp[i]);
    ra[4] += cabs(g->b.Kp[i]) * cabs(g->b.Kp[i]) + cabs(g->c.Kp[i]) * cabs(g->c.Kp[i]);
  }
  g->rM = sqrt(ra[0]), g->rC0 = sqrt(ra[1]), g->rK0 = sqrt(ra[2]), g->rCp = sqrt(ra[3]), g->rKp = sqrt(ra[4]);
  return AUTOBAL_SUCCESS;
}

/* Bounds valid over theta in [th0 - hth, th0 + hth]: sigma_min(M) >= mu, ||C0|| <= c, ||K0|| <= kap,
 * ||C+-|| <= e1, ||K+-|| <= e0 (2-norms bounded by Frobenius). */
typedef struct box_consts {
  double mu, c, kap, e1, e0;
} box_consts;

static double sigma_min_real(const double *a) {
  gsl_matrix *A = gsl_matrix_alloc(NM, NM), *V = gsl_matrix_alloc(NM, NM);
  gsl_vector *Sv = gsl_vector_alloc(NM), *wk = gsl_vector_alloc(NM);
  double r = NAN;
  size_t i;
  if (A && V && Sv && wk) {
    for (i = 0; i < NN; i++) A->data[i] = a[i];
    if (gsl_linalg_SV_decomp_jacobi(A, V, Sv) == 0) r = gsl_vector_min(Sv);
  }
  gsl_matrix_free(A), gsl_matrix_free(V), gsl_vector_free(Sv), gsl_vector_free(wk);
  return r;
}

static void consts_at(const hill_trig *g, const hill_set *hc, double hth, box_consts *b) {
  const double sm = sigma_min_real(hc->M);
  /* rounding allowance of the 6 x 6 SVD: 1e-12 ||M|| */
  b->mu = sm - 1e-12 * fro_r(hc->M) - hth * g->rM;
  b->c = fro_r(hc->C0) + hth * g->rC0;
  b->kap = fro_r(hc->K0) + hth * g->rK0;
  b->e1 = fro_c(hc->Cp) + hth * g->rCp;
  b->e0 = fro_c(hc->Kp) + hth * g->rKp;
}

/* The tail bound ||B T^{-1} C|| of harmonics |k| > N, for nu / w in [0, 1] and lambda / w = -d + i nu / w
 * (d = delta / w >= 0, the margin's shift): |s_k| / w >= 2N + 1 for |k| > N (the imaginary part alone),
 * |s_{k+-1}| <= |s_k| + 2, and the couplings of the truncation to the tail have |s_{+-(N+1)}| / w <=
 * 2N + 3 + d; +inf when the Neumann series does not converge. */
static double tail_bound(const box_consts *b, size_t N, double d) {
  const double s0 = 2.0 * (double)N + 1.0, den = b->mu * s0 * s0 - b->c * s0 - b->kap;
  double dinv, g, bc;
  if (!(b->mu > 0.0) || !(den > 0.0) || !(s0 >= b->c / (2.0 * b->mu))) return INFINITY;
  dinv = 1.0 / den;
  g = 2.0 * (b->e1 * (s0 + 2.0) + b->e0) * dinv; /* ||D^{-1} E|| (Schur test, two neighbours) */
  if (!(g < 1.0)) return INFINITY;
  bc = b->e1 * (s0 + 2.0 + d) + b->e0; /* ||B||, ||C|| */
  return bc * bc * dinv / (1.0 - g);
}

/* The weight of block row k (a fixed row scaling W: W H_N is singular iff H_N is; it keeps the far
 * harmonics, whose blocks grow like (2k)^2, from dominating the norms). */
static double row_weight(double k) {
  const double a = fmax(1.0, 2.0 * fabs(k) - 1.0);
  return 1.0 / (a * a);
}

/* The weighted Hill matrix of a set h at nu / w = nuh, as a polynomial in i dnu (dnu the change of nu / w):
 * W H_N(nuh + dnu) = H0 + (i dnu) H1 + (i dnu)^2 H2, exactly:
 *   H0: diagonal blocks M s_k^2 + C0 s_k + K0, H[k][k-1] = C+ s_{k-1} + K+, H[k][k+1] = C- s_{k+1} + K-;
 *   H1: diagonal blocks 2 M s_k + C0, off-diagonal C+, C-;   H2: diagonal blocks M
 * (s_k = i (nuh + 2k)), each block row k times row_weight(k).  Linear in the set. */
static void hill_matrix_l(const hill_set *h, size_t N, cplx lam, int which, gsl_matrix_complex *H) {
  const size_t nb = 2 * N + 1;
  size_t kb, i, j;
  gsl_matrix_complex_set_zero(H);
  for (kb = 0; kb < nb; kb++) {
    const double k = (double)kb - (double)N, wk = row_weight(k);
    const cplx sk = lam + I * 2.0 * k, sm = lam + I * 2.0 * (k - 1.0), sp = lam + I * 2.0 * (k + 1.0);
    for (i = 0; i < NM; i++)
      for (j = 0; j < NM; j++) {
        const size_t e = i * NM + j;
        cplx v, lo = 0.0, up = 0.0;
        if (which == 0) {
          v = h->M[e] * sk * sk + h->C0[e] * sk + h->K0[e];
          lo = h->Cp[e] * sm + h->Kp[e];
          up = conj(h->Cp[e]) * sp + conj(h->Kp[e]);
        } else if (which == 1) {
          v = 2.0 * h->M[e] * sk + h->C0[e];
          lo = h->Cp[e];
          up = conj(h->Cp[e]);
        } else
          v = h->M[e];
        gsl_matrix_complex_set(H, kb * NM + i, kb * NM + j, gsl_complex_rect(wk * creal(v), wk * cimag(v)));
        if (kb > 0 && which < 2)
          gsl_matrix_complex_set(H, kb * NM + i, (kb - 1) * NM + j, gsl_complex_rect(wk * creal(lo), wk * cimag(lo)));
        if (kb + 1 < nb && which < 2)
          gsl_matrix_complex_set(H, kb * NM + i, (kb + 1) * NM + j, gsl_complex_rect(wk * creal(up), wk * cimag(up)));
      }
  }
}

/* The Hill matrix on the line Re lambda / w = -d (d = delta / w: the margin's shift) at Im lambda / w = nuh. */
static void hill_matrix(const hill_set *h, size_t N, double d, double nuh, int which, gsl_matrix_complex *H) {
  hill_matrix_l(h, N, -d + I * nuh, which, H);
}

static double fro_m(const gsl_matrix_complex *A) {
  double v = 0.0;
  size_t i;
  for (i = 0; i < 2 * A->size1 * A->size2; i++) v += A->data[i] * A->data[i];
  return sqrt(v);
}

/* ||R X - sub I||_F for X block tridiagonal (blocks NM, 2N + 1 block rows): row i of X has non-zeros only
 * in the block columns next to its own, so the product costs n * 3 NM per row (row-wise, contiguous). */
static double fro_prod(const gsl_matrix_complex *R, const gsl_matrix_complex *X, size_t N, int sub) {
  const size_t n = R->size1, nb = 2 * N + 1;
  double v = 0.0;
  size_t r, i, c;
  double *row = (double *)malloc(2 * n * sizeof *row); /* re, im interleaved */
  if (row == NULL) return INFINITY;
  for (r = 0; r < n; r++) {
    const double *rr = R->data + 2 * r * R->tda;
    for (c = 0; c < 2 * n; c++) row[c] = 0.0;
    for (i = 0; i < n; i++) {
      const double ar = rr[2 * i], ai = rr[2 * i + 1];
      const size_t ib = i / NM, c0 = (ib > 0 ? ib - 1 : 0) * NM, c1 = (ib + 1 < nb ? ib + 2 : ib + 1) * NM;
      const double *xr = X->data + 2 * i * X->tda;
      for (c = c0; c < c1; c++) {
        const double xre = xr[2 * c], xim = xr[2 * c + 1];
        row[2 * c] += ar * xre - ai * xim;
        row[2 * c + 1] += ar * xim + ai * xre;
      }
    }
    if (sub) row[2 * r] -= 1.0;
    for (c = 0; c < 2 * n; c++) v += row[c] * row[c];
  }
  free(row);
  return sqrt(v);
}

/* Workspace of the box test. */
typedef struct hill_ws {
  size_t N, n;
  double d; /* delta / w: the line Re lambda = -delta of the margin */
  gsl_matrix_complex *H0, *R, *T1, *T2;
  gsl_permutation *perm;
} hill_ws;

static void ws_free(hill_ws *w) {
  gsl_matrix_complex_free(w->H0);
  gsl_matrix_complex_free(w->R);
  gsl_matrix_complex_free(w->T1);
  gsl_matrix_complex_free(w->T2);
  gsl_permutation_free(w->perm);
}

static int ws_alloc(hill_ws *w, size_t N) {
  memset(w, 0, sizeof *w);
  w->N = N;
  w->n = NM * (2 * N + 1);
  w->H0 = gsl_matrix_complex_alloc(w->n, w->n);
  w->R = gsl_matrix_complex_alloc(w->n, w->n);
  w->T1 = gsl_matrix_complex_alloc(w->n, w->n);
  w->T2 = gsl_matrix_complex_alloc(w->n, w->n);
  w->perm = gsl_permutation_alloc(w->n);
  return w->H0 && w->R && w->T1 && w->T2 && w->perm ? 0 : -1;
}

/* The sets of the theta expansion at th: X(th + d) = X(th) + X'(th) sin d + Y (cos d - 1), Y = X(th) - a. */
static void sets_deriv(const hill_trig *g, double th, hill_set *dx, hill_set *y) {
  const double c = cos(th), sn = sin(th);
  size_t i;
  for (i = 0; i < NN; i++) {
    dx->M[i] = -g->b.M[i] * sn + g->c.M[i] * c;
    dx->C0[i] = -g->b.C0[i] * sn + g->c.C0[i] * c;
    dx->K0[i] = -g->b.K0[i] * sn + g->c.K0[i] * c;
    dx->Cp[i] = -g->b.Cp[i] * sn + g->c.Cp[i] * c;
    dx->Kp[i] = -g->b.Kp[i] * sn + g->c.Kp[i] * c;
    y->M[i] = g->b.M[i] * c + g->c.M[i] * sn;
    y->C0[i] = g->b.C0[i] * c + g->c.C0[i] * sn;
    y->K0[i] = g->b.K0[i] * c + g->c.K0[i] * sn;
    y->Cp[i] = g->b.Cp[i] * c + g->c.Cp[i] * sn;
    y->Kp[i] = g->b.Kp[i] * c + g->c.Kp[i] * sn;
  }
}

/* The box test.  R ~ (W H_N(centre))^{-1} (LU), E0 = I - R H0 (its Frobenius norm: the inverse's
 * rounding), and for p in the box
 *   ||R W S(p) - I|| <= ||E0|| + hnu ||R H1|| + hnu^2 ||R|| ||H2||
 *     + sin(hth) (||R H0'|| + hnu ||R|| ||H1'|| + hnu^2 ||R|| ||H2'||)
 *     + (1 - cos hth) ||R|| (||H0_Y|| + hnu ||H1_Y|| + hnu^2 ||H2_Y||) + ||R|| w_N tail
 * (primes: the Hill matrices of the theta-derivative set, _Y of the set Y; all norms Frobenius).  Returns
 * that bound (the box is excluded when it is < 1: then W S(p), so det H(p), is non-zero for every p);
 * *pnu, *pth its nu and theta shares; a singular centre gives +inf. */
static double box_test(hill_ws *w, const hill_trig *g, const hill_set *hc, const box_consts *bc, double nuh,
                       double hnu, double th, double hth, double *pnu, double *pth) {
  const size_t n = w->n, N = w->N;
  hill_set dx, y;
  double nR, e0, rh1, rh0d, nH2, nH1d, nH2d, nY0, nY1, nY2, tb, rest;
  size_t i;
  int sgn;
  *pnu = *pth = INFINITY;
  hill_matrix(hc, N, w->d, nuh, 0, w->H0);
  gsl_matrix_complex_memcpy(w->T1, w->H0);
  if (gsl_linalg_complex_LU_decomp(w->T1, w->perm, &sgn) != 0) return INFINITY;
  for (i = 0; i < n; i++) {
    const gsl_complex d = gsl_matrix_complex_get(w->T1, i, i);
    if (!(GSL_REAL(d) != 0.0 || GSL_IMAG(d) != 0.0)) return INFINITY;
  }
  if (gsl_linalg_complex_LU_invert(w->T1, w->perm, w->R) != 0) return INFINITY;
  nR = fro_m(w->R);
  if (!isfinite(nR)) return INFINITY;
  /* R H1 */
  hill_matrix(hc, N, w->d, nuh, 1, w->T2);
  rh1 = fro_prod(w->R, w->T2, N, 0);
  hill_matrix(hc, N, w->d, nuh, 2, w->T2);
  nH2 = fro_m(w->T2);
  /* the theta parts */
  sets_deriv(g, th, &dx, &y);
  hill_matrix(&dx, N, w->d, nuh, 0, w->T2);
  rh0d = fro_prod(w->R, w->T2, N, 0);
  hill_matrix(&dx, N, w->d, nuh, 1, w->T2);
  nH1d = fro_m(w->T2);
  hill_matrix(&dx, N, w->d, nuh, 2, w->T2);
  nH2d = fro_m(w->T2);
  hill_matrix(&y, N, w->d, nuh, 0, w->T2);
  nY0 = fro_m(w->T2);
  hill_matrix(&y, N, w->d, nuh, 1, w->T2);
  nY1 = fro_m(w->T2);
  hill_matrix(&y, N, w->d, nuh, 2, w->T2);
  nY2 = fro_m(w->T2);
  tb = tail_bound(bc, N, w->d);
  *pnu = hnu * rh1 + hnu * hnu * nR * nH2;
  *pth = sin(hth) * (rh0d + hnu * nR * nH1d + hnu * hnu * nR * nH2d) +
         (1.0 - cos(hth)) * nR * (nY0 + hnu * nY1 + hnu * hnu * nY2);
  rest = *pnu + *pth + nR * row_weight((double)N) * tb;
  if (!(rest < 1.0)) return rest; /* fails anyway: the residual is not needed */
  /* E0 = I - R H0 */
  e0 = fro_prod(w->R, w->H0, N, 1);
  return e0 + rest;
}

typedef struct box {
  double nu, th, hnu, hth; /* centre and half-widths (nu in units of w) */
} box;

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Unbalance of the half angle theta: s^2 = a1^2 + a2^2 + 2 a1 a2 cos 2 theta. */
static double s_of_theta(double a1, double a2, double th) {
  return sqrt(fmax(0.0, a1 * a1 + a2 * a2 + 2.0 * a1 * a2 * cos(2.0 * th)));
}
static double theta_of_s(double a1, double a2, double sv) {
  const double c = (sv * sv - a1 * a1 - a2 * a2) / (2.0 * a1 * a2);
  return 0.5 * acos(fmax(-1.0, fmin(1.0, c)));
}

/* Floquet verdict at the configuration of half angle theta (sign: the branch): member GIVEN with the
 * angles psi0 + pi + phi_i, a1 e^{i phi1} + a2 e^{i phi2} = s real, phi1 - phi2 = 2 theta. */
static int floquet_at(autobal_rotor_stab *s, double a1, double a2, double r0, double th, double *margin, int *verdict,
                      double *sv_out) {
  const double dl = 2.0 * th, sv = s_of_theta(a1, a2, th);
  const double beta = atan2(a2 * sin(dl), a1 + a2 * cos(dl));
  double ang[2];
  autobal_rotor_member save = s->opt.member[0];
  int st;
  ang[0] = s->cur.plane[0].psi0 + M_PI + beta;
  ang[1] = s->cur.plane[0].psi0 + M_PI + beta - dl;
  s->opt.member[0].kind = AUTOBAL_ROTOR_MEMBER_GIVEN;
  s->opt.member[0].n_angles = 2;
  s->opt.member[0].angles = ang;
  st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, sv / r0);
  if (st == AUTOBAL_SUCCESS) st = autobal_rotor_stab_margin(s, AUTOBAL_ROTOR_STAB_FLOQUET, margin, verdict);
  s->opt.member[0] = save;
  *sv_out = sv;
  return st;
}

int autobal_rotor_every_unbalance_aniso_(autobal_rotor_stab *s, double s_lo, double s_hi,
                                         autobal_rotor_unbalance_range *out) {
  return autobal_rotor_every_unbalance_hill_(s, s_lo, s_hi, 0.0, out);
}

/* A Floquet margin that fails the test: delta = 0, the verdict (not stable); delta > 0, mg >= -delta. */
static int fails_margin(double delta, double mg, int v) {
  return delta > 0.0 ? !(mg < -delta) : v != AUTOBAL_VERDICT_STABLE;
}

int autobal_rotor_every_unbalance_hill_(autobal_rotor_stab *s, double s_lo, double s_hi, double delta,
                                        autobal_rotor_unbalance_range *out) {
  const autobal_rotor_plane *pl = &s->cur.plane[0];
  const double m1 = pl->ball_mass[0], m2 = pl->ball_mass[1];
  const double a1 = m1 * pl->ball_radius[0], a2 = m2 * pl->ball_radius[1], r0 = pl->r0;
  const int identical = autobal_rotor_close_rel_(m1, m2, 1e-12) && autobal_rotor_close_rel_(a1, a2, 1e-12);
  const double tha = theta_of_s(a1, a2, s_hi), thb = theta_of_s(a1, a2, s_lo);
  const long budget = s->opt.hill_boxes > 0 ? s->opt.hill_boxes : HILL_BOXES;
  hill_trig *g = NULL;
  box *q = NULL;
  hill_ws ws;
  size_t N, head = 0, tail = 0, cap, nbr = identical ? 1 : 2, br, i, j;
  int st = AUTOBAL_SUCCESS;
  memset(&ws, 0, sizeof ws);
  out->hill = 1;
  out->s_unstable = NAN;
  {
    const double q1 = m1 * m1 + m2 * m2;
    double ulo = INFINITY, uhi = -INFINITY;
    const double ths[3] = {tha, thb, 0.25 * M_PI};
    for (i = 0; i < 3; i++) {
      double u;
      if (i == 2 && !(tha < ths[2] && ths[2] < thb)) continue;
      u = 0.25 * (q1 + 2.0 * m1 * m2 * cos(4.0 * ths[i]));
      ulo = fmin(ulo, u), uhi = fmax(uhi, u);
    }
    out->u_min = ulo, out->u_max = uhi;
  }
  g = (hill_trig *)calloc(1, sizeof *g);
  if (g == NULL) return autobal_error_set(&s->err, AUTOBAL_ENOMEM, "every unbalance, anisotropic: no memory");
  set_scales(s, g);
  /* a balanced state on the handle (m0 of the middle of the range), then the trig form */
  if ((st = autobal_rotor_stab_set(s, AUTOBAL_ROTOR_PARAM_UNBALANCE_MASS, 0.5 * (s_lo + s_hi) / r0)) !=
      AUTOBAL_SUCCESS)
    goto done;
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) goto done;
  if ((st = build_trig(s, g)) != AUTOBAL_SUCCESS) goto done;
  /* N: the least with the tail bound over the whole range <= HILL_TAIL_TOL.  Where no N <= HILL_NMAX
   * gets there (low speeds: the anisotropy is not small against the harmonics' (2 k w)^2), the range
   * cannot be proven stable: after the Floquet checks below it is undecided (hill_order 0, hill_tail
   * the bound at HILL_NMAX), not an error, so that a speed scan goes on */
  {
    hill_set hc;
    box_consts bc;
    double tb = INFINITY;
    set_at(g, 0.5 * (tha + thb), &hc);
    consts_at(g, &hc, 0.5 * (thb - tha), &bc);
    for (N = 2; N <= HILL_NMAX; N++)
      if ((tb = row_weight((double)N) * tail_bound(&bc, N, delta / fabs(s->cur.omega))) <= HILL_TAIL_TOL) break;
    out->hill_order = N <= HILL_NMAX ? N : 0;
    out->hill_tail = tb;
  }
  /* Floquet at the middle and both ends of each branch: a member not stable there decides it ("not stable
   * for all", shown by that member), and the box search is not needed */
  out->margin_worst = -INFINITY;
  out->all_stable = 1;
  out->n_sub = 1;
  out->sub_lo[0] = s_lo;
  out->sub_hi[0] = s_hi;
  out->sub_verdict[0] = AUTOBAL_VERDICT_STABLE;
  for (br = 0; br < nbr; br++)
    for (i = 0; i < 3; i++) {
      const double th = (br == 0 ? 1.0 : -1.0) * (i == 0 ? 0.5 * (tha + thb) : i == 1 ? tha : thb);
      double mg, sv;
      int v;
      if ((st = floquet_at(s, a1, a2, r0, th, &mg, &v, &sv)) != AUTOBAL_SUCCESS) goto done;
      out->evaluations++;
      if (br == 0 && i == 0) out->sub_margin[0] = mg;
      if (mg > out->margin_worst) out->margin_worst = mg;
      if (delta > 0.0 && fails_margin(delta, mg, v)) { /* a member that decays slower than delta */
        out->all_stable = 0;
        out->sub_verdict[0] = AUTOBAL_VERDICT_UNSTABLE;
        if (isnan(out->s_unstable)) out->s_unstable = sv;
      } else if (v != AUTOBAL_VERDICT_STABLE) {
        out->all_stable = 0;
        if (v < out->sub_verdict[0]) out->sub_verdict[0] = v;
        if (v == AUTOBAL_VERDICT_UNSTABLE && isnan(out->s_unstable)) out->s_unstable = sv;
      }
    }
  if (!out->all_stable) goto done;
  if (out->hill_order == 0) { /* no bounded truncation: undecided (the members checked are stable) */
    out->all_stable = 0;
    out->sub_verdict[0] = AUTOBAL_ROTOR_VERDICT_NONE;
    goto done;
  }
  if (ws_alloc(&ws, N) != 0) {
    st = autobal_error_set(&s->err, AUTOBAL_ENOMEM, "every unbalance, anisotropic: no memory (Hill matrix)");
    goto done;
  }
  ws.d = delta / fabs(s->cur.omega);
  /* the box search: FIFO, initial grid 16 (nu) x 4 (theta) per branch */
  cap = (size_t)budget + 2 * 64 + 16 * 16 + 8;
  q = (box *)malloc(cap * sizeof *q);
  if (q == NULL) {
    st = autobal_error_set(&s->err, AUTOBAL_ENOMEM, "every unbalance, anisotropic: no memory (boxes)");
    goto done;
  }
  for (br = 0; br < nbr; br++)
    for (i = 0; i < 16; i++)
      for (j = 0; j < 4; j++) {
        const double sg = br == 0 ? 1.0 : -1.0, ht = 0.125 * (thb - tha);
        box b;
        b.hnu = 1.0 / 32.0;
        b.nu = (2.0 * (double)i + 1.0) * b.hnu;
        b.hth = ht;
        b.th = sg * (tha + (2.0 * (double)j + 1.0) * ht);
        q[tail++] = b;
      }
  out->hill_boxes = 0;
  while (head != tail) {
    const box b = q[head];
    hill_set hc;
    box_consts bc;
    double bound, lnu, lth;
    size_t knu, kth, live = (tail + cap - head) % cap, u, v;
    if (out->hill_boxes >= budget) break;
    if ((out->hill_boxes & 255) == 255 && autobal_rotor_stab_cancelled_(s)) {
      st = autobal_error_set(&s->err, AUTOBAL_ECANCELLED, "every unbalance: cancelled by the caller");
      goto done;
    }
    set_at(g, b.th, &hc);
    consts_at(g, &hc, b.hth, &bc);
    bound = box_test(&ws, g, &hc, &bc, b.nu, b.hnu, b.th, b.hth, &lnu, &lth);
    out->hill_boxes++;
    if (bound < 1.0 - 1e-9) { /* excluded */
      head = (head + 1) % cap;
      continue;
    }
    /* split into knu x kth pieces sized so that each share would be about 0.4 (the bound is about linear
     * in the half-widths), at most 16 a side; halves when the centre is (nearly) singular */
    if (isfinite(lnu) && isfinite(lth)) {
      knu = (size_t)fmin(16.0, fmax(1.0, ceil(lnu / 0.4)));
      kth = (size_t)fmin(16.0, fmax(1.0, ceil(lth / 0.4)));
      if (knu * kth < 2) {
        if (lnu >= lth) knu = 2;
        else kth = 2;
      }
    } else
      knu = kth = 2;
    /* finishing needs at least one evaluation per waiting box: stop when they exceed the budget left */
    if (live - 1 + knu * kth > (size_t)(budget - out->hill_boxes) || live - 1 + knu * kth >= cap) break;
    head = (head + 1) % cap;
    for (u = 0; u < knu; u++)
      for (v = 0; v < kth; v++) {
        box c = b;
        c.hnu = b.hnu / (double)knu;
        c.hth = b.hth / (double)kth;
        c.nu = b.nu - b.hnu + (2.0 * (double)u + 1.0) * c.hnu;
        c.th = b.th - b.hth + (2.0 * (double)v + 1.0) * c.hth;
        q[tail] = c, tail = (tail + 1) % cap;
      }
  }
  out->hill_open = (tail + cap - head) % cap;
  if (out->hill_open > 0) {
    /* theta of the open boxes, sorted; up to HILL_FLOQUET_OPEN of them spread evenly */
    const size_t no = out->hill_open;
    double *ths = (double *)malloc(no * sizeof *ths);
    size_t p, nf = no < HILL_FLOQUET_OPEN ? no : HILL_FLOQUET_OPEN;
    int found = 0;
    if (ths == NULL) {
      st = autobal_error_set(&s->err, AUTOBAL_ENOMEM, "every unbalance, anisotropic: no memory");
      goto done;
    }
    for (p = 0; p < no; p++) ths[p] = q[(head + p) % cap].th;
    qsort(ths, no, sizeof *ths, cmp_double);
    out->all_stable = 0;
    for (p = 0; p < nf; p++) {
      const double th = ths[nf > 1 ? (p * (no - 1)) / (nf - 1) : 0];
      double mg, sv;
      int v;
      if ((st = floquet_at(s, a1, a2, r0, th, &mg, &v, &sv)) != AUTOBAL_SUCCESS) break;
      out->evaluations++;
      if (mg > out->margin_worst) out->margin_worst = mg;
      if (delta > 0.0 ? fails_margin(delta, mg, v) : v == AUTOBAL_VERDICT_UNSTABLE) {
        if (!found || sv < out->s_unstable) out->s_unstable = sv;
        found = 1;
      }
    }
    free(ths);
    if (st != AUTOBAL_SUCCESS) goto done;
    if (found) out->sub_verdict[0] = AUTOBAL_VERDICT_UNSTABLE;
    else if (out->sub_verdict[0] == AUTOBAL_VERDICT_STABLE) out->sub_verdict[0] = AUTOBAL_ROTOR_VERDICT_NONE;
  }
done:
  ws_free(&ws);
  free(q);
  free(g);
  return st;
}

double autobal_rotor_hill_sigma_min_(autobal_rotor_stab *s, double theta, size_t N, double lam_re, double lam_im) {
  const autobal_rotor_plane *pl = &s->cur.plane[0];
  const double w = fabs(s->cur.omega);
  hill_trig *g;
  hill_set hc;
  double r = NAN;
  gsl_matrix_complex *H = NULL, *G = NULL;
  gsl_vector *ev = NULL;
  gsl_eigen_herm_workspace *ew = NULL;
  size_t n = NM * (2 * N + 1);
  if (s->n_planes != 1 || pl->n_balls != 2 || s->psi_status != AUTOBAL_SUCCESS) return NAN;
  g = (hill_trig *)calloc(1, sizeof *g);
  if (g == NULL) return NAN;
  set_scales(s, g);
  if (build_trig(s, g) != AUTOBAL_SUCCESS) goto out;
  set_at(g, theta, &hc);
  H = gsl_matrix_complex_alloc(n, n), G = gsl_matrix_complex_alloc(n, n);
  ev = gsl_vector_alloc(n), ew = gsl_eigen_herm_alloc(n);
  if (!H || !G || !ev || !ew) goto out;
  hill_matrix_l(&hc, N, (lam_re + I * lam_im) / w, 0, H);
  gsl_blas_zherk(CblasLower, CblasConjTrans, 1.0, H, 0.0, G);
  if (gsl_eigen_herm(G, ev, ew) == 0) r = sqrt(fmax(0.0, gsl_vector_min(ev)));
out:
  gsl_matrix_complex_free(H), gsl_matrix_complex_free(G), gsl_vector_free(ev);
  if (ew) gsl_eigen_herm_free(ew);
  free(g);
  return r;
}
