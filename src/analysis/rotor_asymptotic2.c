/* rotor_asymptotic2.c: the light-ball asymptotic condition for TWO balancer planes
 * (autobal/rotor_asymptotic.h, docs/rotor.md "Asymptotic conditions", "Two planes"; derivation in
 * tools/derive/derive_asymptotic2.py, scan in tools/derive/asymptotic2_scan.py).
 *
 * With the rotor-housing frozen at lambda = 0 the planes' balls couple through the 2x2 receptance
 * G = B^T K(i omega)^-1 B, B = [[1, 1], [d1, d2]]; the 8 ball roots are the roots of the real
 * degree-8 polynomial p(lambda) = det(U(lambda) - S), U = diag(u1, u2, u1, u2), u_j = lambda^2 + kappa_j lambda,
 *     S = (omega^4 / 2) [Mb G, -Q conj(G); -conj(Q) G, Mb conj(G)],  Mb = diag(m_b1, m_b2), Q = diag(Q1, Q2).
 * The rotor-housing's roots (of D = det K) move to first order by
 *     sum_j (m_bj / 2) P^4 N_jj / ((lambda^2 + kappa_j lambda) D')  at lambda_k,  N = B^T adj(K) B.
 *
 * May use: the public headers (autobal/rotor_stability.h, autobal/stability.h) and core.  Calls no
 * other analysis file. */
#include "autobal/rotor_asymptotic.h"
#include "autobal/stability.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "internal.h"

typedef double complex cplx;

/* r = a * b for ascending complex coefficient arrays (lengths na, nb; r has na + nb - 1). */
static void cmul2(const cplx *a, size_t na, const cplx *b, size_t nb, cplx *r) {
  size_t i, j;
  for (i = 0; i < na + nb - 1; i++) r[i] = 0;
  for (i = 0; i < na; i++)
    for (j = 0; j < nb; j++) r[i + j] += a[i] * b[j];
}

static cplx ceval2(const cplx *x, size_t n, cplx z) {
  cplx v = 0;
  while (n-- > 0) v = v * z + x[n];
  return v;
}

/* determinant of a 3x3 complex matrix */
static cplx det3(cplx m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* adj(a)[k][i] = (-1)^(i+k) minor(i, k) of the 4x4 complex matrix a */
static void adj4(cplx a[4][4], cplx adj[4][4]) {
  int i, k, r, s, rr, ss;
  for (i = 0; i < 4; i++)
    for (k = 0; k < 4; k++) {
      cplx m[3][3];
      for (r = 0, rr = 0; r < 4; r++) {
        if (r == i) continue;
        for (s = 0, ss = 0; s < 4; s++) {
          if (s == k) continue;
          m[rr][ss++] = a[r][s];
        }
        rr++;
      }
      adj[k][i] = ((i + k) % 2 ? -1.0 : 1.0) * det3(m);
    }
}

/* High speed, Q1 = Q2 = 0 (autobal/rotor_asymptotic.h; tools/derive/derive_asymptotic2_high.py).  cD: as for
 * the light balls (sum of 1/|root| over D D* plus 4/|omega|). */
static void high_speed(const autobal_rotor_closed *c, autobal_rotor_asymptotic2 *r, const double *mb, const double *kap,
                       const double *dd, double w, double cD) {
  const autobal_rotor_lumped *L = &c->L;
  double Ap = L->A - L->C, v[2][2], Gt[3], Ht[3], z[2][2], tr, det, wmax, gap, kmax, imax;
  size_t j, k;
  r->high_defined = c->plane[0].m_add == 0.0 && c->plane[1].m_add == 0.0 && Ap != 0.0;
  for (k = 0; k < 2; k++) r->high_mu[k] = r->high_kappa_mode[k] = r->high_kappa_inf[k] = r->high_re[k] = NAN;
  r->high_small = NAN;
  r->high_every_kappa = r->high_every_small = NAN;
  r->high_every_stable = r->high_every_applicable = 0;
  if (!r->high_defined) {
    for (k = 0; k < 4; k++) r->high_Gamma[k] = r->high_H[k] = NAN;
    return;
  }
  for (j = 0; j < 2; j++) v[j][0] = 1.0 / L->M, v[j][1] = dd[j] / Ap; /* Mi b_j */
  for (j = 0; j < 2; j++)
    for (k = 0; k < 2; k++) {
      r->high_Gamma[2 * j + k] = 1.0 / L->M + dd[j] * dd[k] / Ap;
      r->high_H[2 * j + k] = L->h_x * v[j][0] * v[k][0] - L->h_xbeta * (v[j][0] * v[k][1] + v[j][1] * v[k][0]) +
                             L->h_alpha * v[j][1] * v[k][1];
    }
  /* Gt = Mb^1/2 Gamma Mb^1/2, Ht likewise (symmetric: [0] = 11, [1] = 12, [2] = 22) */
  Gt[0] = mb[0] * r->high_Gamma[0], Gt[1] = sqrt(mb[0] * mb[1]) * r->high_Gamma[1], Gt[2] = mb[1] * r->high_Gamma[3];
  Ht[0] = mb[0] * r->high_H[0], Ht[1] = sqrt(mb[0] * mb[1]) * r->high_H[1], Ht[2] = mb[1] * r->high_H[3];
  {
    double m = 0.5 * (Gt[0] + Gt[2]), dlt = hypot(0.5 * (Gt[0] - Gt[2]), Gt[1]);
    r->high_mu[0] = m - dlt, r->high_mu[1] = m + dlt;
    for (k = 0; k < 2; k++) { /* unit eigenvector of [[Gt0, Gt1], [Gt1, Gt2]] for mu_k */
      double a0 = Gt[1], a1 = r->high_mu[k] - Gt[0], b0 = r->high_mu[k] - Gt[2], b1 = Gt[1], n;
      if (hypot(a0, a1) < hypot(b0, b1)) a0 = b0, a1 = b1;
      n = hypot(a0, a1);
      if (n > 0.0) z[k][0] = a0 / n, z[k][1] = a1 / n;
      else z[k][0] = k == 0, z[k][1] = k == 1; /* Gt a multiple of the identity */
    }
  }
  tr = L->c_x / L->M + L->c_alpha / L->A;
  det = (L->c_x * L->c_alpha - L->c_xbeta * L->c_xbeta) / (L->M * L->A);
  wmax = sqrt(fmax(0.0, 0.5 * (tr + sqrt(fmax(0.0, tr * tr - 4.0 * det)))));
  if (!(r->high_mu[0] > 0.0)) { /* (H1') fails: a real ball root of order omega sqrt(|mu| / 2) > 0 */
    r->high_stable = 0;
    r->high_decided = 1;
    r->high_small = fmax(fabs(w) * sqrt(0.5 * fmax(fabs(r->high_mu[0]), fabs(r->high_mu[1]))) * cD, wmax / fabs(w));
    r->high_applicable = r->high_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL;
    return;
  }
  {
    /* every unbalance (docs/rotor.md "Two planes at high speed"): with S = -(omega^2 / 2) T (Gamma^ + i H^ /
     * omega), T = [[Mb, -Q], [-conj Q, Mb]] <= 2 diag(Mb, Mb) and K = diag(kappa_1, kappa_2, kappa_1, kappa_2)
     * (commuting with T), every root of det(lambda^2 + K lambda - S) = 0 is stable when min kappa_j >
     * rho sqrt(mu_2), rho = the largest |nu| of det(H - nu Gamma) = 0, for every Q1, Q2 */
    const double *G = r->high_Gamma, *H = r->high_H;
    double a2 = G[0] * G[3] - G[1] * G[1], a1 = -(H[0] * G[3] + H[3] * G[0] - 2.0 * H[1] * G[1]),
           a0 = H[0] * H[3] - H[1] * H[1], dsc = fmax(0.0, a1 * a1 - 4.0 * a2 * a0), rho;
    rho = a2 > 0.0 ? (fabs(a1) + sqrt(dsc)) / (2.0 * a2) : NAN; /* the larger |root| of a2 nu^2 + a1 nu + a0 */
    r->high_every_kappa = rho * sqrt(r->high_mu[1]);
    r->high_every_stable = fmin(kap[0], kap[1]) > r->high_every_kappa;
    r->high_every_small = fmax(fabs(w) * sqrt(r->high_mu[1]) * cD, wmax / fabs(w));
    r->high_every_applicable = r->high_every_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL;
  }
  kmax = fmax(kap[0], kap[1]);
  imax = 0.0;
  r->high_stable = 1;
  for (k = 0; k < 2; k++) {
    double kb = z[k][0] * z[k][0] * kap[0] + z[k][1] * z[k][1] * kap[1];
    double eta = z[k][0] * z[k][0] * Ht[0] + 2.0 * z[k][0] * z[k][1] * Ht[1] + z[k][1] * z[k][1] * Ht[2];
    r->high_kappa_mode[k] = kb;
    r->high_kappa_inf[k] = fabs(eta) / sqrt(2.0 * r->high_mu[k]);
    r->high_re[k] = 0.5 * (r->high_kappa_inf[k] - kb);
    if (!(r->high_re[k] < 0.0)) r->high_stable = 0;
    imax = fmax(imax, r->high_kappa_inf[k]);
  }
  gap = fabs(w) * fabs(sqrt(0.5 * r->high_mu[0]) - sqrt(0.5 * r->high_mu[1]));
  r->high_small = fmax(fmax(fabs(w) * sqrt(0.5 * r->high_mu[1]) * cD, wmax / fabs(w)),
                       gap > 0.0 ? (kmax + imax) / gap : INFINITY);
  {
    int du = 0, ds = 1;
    for (k = 0; k < 2; k++) {
      double e = r->high_small * 0.5 * (r->high_kappa_mode[k] + r->high_kappa_inf[k]);
      if (r->high_re[k] >= e) du = 1;
      if (!(r->high_re[k] <= -e)) ds = 0;
    }
    r->high_decided = du || ds;
  }
  r->high_applicable = r->high_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL;
}

int autobal_rotor_asymptotic2_conditions(const autobal_rotor_closed *c, autobal_rotor_asymptotic2 *out,
                                         autobal_error *err) {
  const autobal_rotor_lumped *L;
  autobal_rotor_asymptotic2 r;
  double w, dd[2], mb[2], kap[2], s;
  cplx Q[2], P[2], P2[3], K11[3], K12[3], K22[3], t1[5], t2[5], D[5], N[2][2][3], G[2][2];
  cplx S[4][4], Ap[4][4][3], pdet[9], pd[8];
  double kk[4];
  size_t i, j, k;
  int st;
  if (c == NULL || out == NULL)
    return autobal_error_set(err, AUTOBAL_EINVAL, "asymptotic conditions (two planes): NULL argument");
  if (c->n_planes != 2 || !c->isotropic || !c->closure_ok)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "asymptotic conditions (two planes): need two planes, isotropic supports and the "
                             "closure (3.16) in both (n_planes %zu, isotropic %d, closure %d)",
                             c->n_planes, c->isotropic, c->closure_ok);
  L = &c->L;
  w = c->omega;
  if (!(w != 0.0) || !isfinite(w))
    return autobal_error_set(err, AUTOBAL_EINVAL, "asymptotic conditions (two planes): omega = %g (must be non-zero)",
                             w);
  memset(&r, 0, sizeof r);
  for (j = 0; j < 2; j++) {
    const autobal_rotor_closed_plane *pl = &c->plane[j];
    dd[j] = pl->d;
    mb[j] = pl->mass;
    kap[j] = pl->kappa;
    Q[j] = pl->Q_re + I * pl->Q_im;
    if (!(kap[j] > 0.0) || !(mb[j] > 0.0))
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "asymptotic conditions (two planes): plane %zu: ball damping rate kappa = %g 1/s, ball "
                               "mass %g kg (both must be > 0)",
                               j + 1, kap[j], mb[j]);
    r.kappa[j] = kap[j];
    r.q[j] = cabs(Q[j]) / mb[j];
  }
  /* K (rotating coordinates, P = lambda + i omega), the FULL inertia terms of both planes included */
  P[0] = I * w;
  P[1] = 1.0;
  cmul2(P, 2, P, 2, P2);
  for (i = 0; i < 3; i++) {
    double m11 = L->M, m12 = 0.0, m22 = L->A;
    for (j = 0; j < 2; j++) {
      m11 += c->plane[j].m_add;
      m12 += c->plane[j].m_add * dd[j];
      m22 += c->plane[j].m_add * dd[j] * dd[j];
    }
    K11[i] = m11 * P2[i] + (i < 2 ? L->h_x * P[i] : 0.0) + (i == 0 ? L->c_x : 0.0);
    K12[i] = -((i < 2 ? L->h_xbeta * P[i] : 0.0) + (i == 0 ? L->c_xbeta : 0.0)) + m12 * P2[i];
    K22[i] = m22 * P2[i] + (i < 2 ? (L->h_alpha - I * L->C * w) * P[i] : 0.0) + (i == 0 ? L->c_alpha : 0.0);
  }
  cmul2(K11, 3, K22, 3, t1);
  cmul2(K12, 3, K12, 3, t2);
  for (i = 0; i < 5; i++) D[i] = t1[i] - t2[i];
  if (!(cabs(D[0]) > 0.0))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "asymptotic conditions (two planes): D(0) = 0 (an undamped resonance of the rotor-housing "
                             "at omega = %g rad/s)",
                             w);
  /* N_jk = b_j^T adj(K) b_k = K22 - (d_j + d_k) K12 + d_j d_k K11, G = N(0) / D(0) */
  for (j = 0; j < 2; j++)
    for (k = 0; k < 2; k++) {
      for (i = 0; i < 3; i++) N[j][k][i] = K22[i] - (dd[j] + dd[k]) * K12[i] + dd[j] * dd[k] * K11[i];
      G[j][k] = N[j][k][0] / D[0];
      r.G_re[2 * j + k] = creal(G[j][k]);
      r.G_im[2 * j + k] = cimag(G[j][k]);
    }
  /* S and the polynomial matrix U(lambda) - S (entries of degree <= 2) */
  s = 0.5 * w * w * w * w;
  for (j = 0; j < 2; j++)
    for (k = 0; k < 2; k++) {
      S[j][k] = s * mb[j] * G[j][k];
      S[j][k + 2] = -s * Q[j] * conj(G[j][k]);
      S[j + 2][k] = -s * conj(Q[j]) * G[j][k];
      S[j + 2][k + 2] = s * mb[j] * conj(G[j][k]);
    }
  for (j = 0; j < 4; j++) kk[j] = kap[j % 2];
  for (j = 0; j < 4; j++)
    for (k = 0; k < 4; k++) {
      Ap[j][k][0] = -S[j][k];
      Ap[j][k][1] = j == k ? kk[j] : 0.0;
      Ap[j][k][2] = j == k ? 1.0 : 0.0;
    }
  /* p = det(U - S): the 24 permutations, each a product of four quadratics */
  for (i = 0; i < 9; i++) pdet[i] = 0;
  {
    int a, b, e, f;
    for (a = 0; a < 4; a++)
      for (b = 0; b < 4; b++) {
        if (b == a) continue;
        for (e = 0; e < 4; e++) {
          int inv;
          cplx q1[5], q2[7], q3[9];
          if (e == a || e == b) continue;
          f = 6 - a - b - e;
          inv = (a > b) + (a > e) + (a > f) + (b > e) + (b > f) + (e > f);
          cmul2(Ap[0][a], 3, Ap[1][b], 3, q1);
          cmul2(q1, 5, Ap[2][e], 3, q2);
          cmul2(q2, 7, Ap[3][f], 3, q3);
          for (i = 0; i < 9; i++) pdet[i] += (inv % 2 ? -1.0 : 1.0) * q3[i];
        }
      }
  }
  for (i = 0; i < 8; i++) pd[i] = (double)(i + 1) * pdet[i + 1];
  {
    double pr[9], dre[8], dim_[8], ratio[8], cD, eps_b = 0.0, eps_r = 0.0, lre = -INFINITY, bre = -INFINITY;
    double errb[8], errr[4];
    size_t pick[8];
    int dec_unstable = 0, dec_stable = 1;
    for (i = 0; i < 9; i++) pr[i] = creal(pdet[i]); /* p is real: the imaginary parts are rounding */
    if ((st = autobal_poly_roots_once_(pr, 9, r.ball_re, r.ball_im, err)) != 0) return st;
    /* the roots of D D* (real, degree 8) for c_D and the rotor roots */
    {
      cplx Dc[5], DD[9];
      double ddr[9];
      for (i = 0; i < 5; i++) Dc[i] = conj(D[i]);
      cmul2(D, 5, Dc, 5, DD);
      for (i = 0; i < 9; i++) ddr[i] = creal(DD[i]);
      if ((st = autobal_poly_roots_once_(ddr, 9, dre, dim_, err)) != 0) return st;
    }
    cD = 4.0 / fabs(w);
    for (k = 0; k < 8; k++) cD += 1.0 / hypot(dre[k], dim_[k]);
    /* ball roots: the frozen entries S_ab(0) against S_ab(lambda), bounded entrywise by
     * |S_ab| [ (|N1| |l| + |N2| |l|^2) / (|D0| |G_ab|) + (c_D + 4/|omega|) |l| ]; the root moves by at most
     * about sum |adj(U - S)_ba| |dS_ab| / |p'(l)| */
    for (j = 0; j < 8; j++) {
      cplx l = r.ball_re[j] + I * r.ball_im[j], A4[4][4], adj[4][4], dp = ceval2(pd, 8, l);
      double e = 0.0, al = cabs(l);
      size_t a, b;
      for (a = 0; a < 4; a++)
        for (b = 0; b < 4; b++) A4[a][b] = (a == b ? l * l + kk[a] * l : 0.0) - S[a][b];
      adj4(A4, adj);
      for (a = 0; a < 4; a++)
        for (b = 0; b < 4; b++) {
          const cplx *Nab = N[a % 2][b % 2];
          double dn = (cabs(Nab[1]) * al + cabs(Nab[2]) * al * al) / cabs(D[0]);
          double g = cabs(G[a % 2][b % 2]);
          double sab = ((a < 2) == (b < 2)) ? s * mb[a % 2] : s * cabs(Q[a % 2]); /* |S_ab| / |G_ab| */
          e += cabs(adj[b][a]) * sab * (dn + g * cD * al);
        }
      e = cabs(dp) > 0.0 ? e / cabs(dp) : INFINITY;
      errb[j] = e;
      eps_b = fmax(eps_b, al > 0.0 ? e / al : INFINITY);
      bre = fmax(bre, r.ball_re[j]);
    }
    /* rotor roots: the 4 roots of D among the 8 of D D*, shifted to first order */
    for (j = 0; j < 8; j++) {
      cplx z = dre[j] + I * dim_[j], a1 = 0, a2 = 0;
      for (i = 5; i-- > 0;) a1 = a1 * z + D[i], a2 = a2 * z + conj(D[i]);
      ratio[j] = cabs(a1) / fmax(cabs(a2), DBL_MIN);
      pick[j] = j;
    }
    for (j = 1; j < 8; j++)
      for (k = j; k > 0 && ratio[pick[k]] < ratio[pick[k - 1]]; k--) {
        size_t t = pick[k];
        pick[k] = pick[k - 1], pick[k - 1] = t;
      }
    {
      cplx Dd[4], dl[4];
      for (i = 0; i < 4; i++) Dd[i] = (double)(i + 1) * D[i + 1];
      for (j = 0; j < 4; j++) {
        size_t m = pick[j];
        cplx lk = dre[m] + I * dim_[m], Pk = lk + I * w, P4 = Pk * Pk * Pk * Pk, dsum = 0;
        double sep = fmin(cabs(lk), fmin(cabs(lk + kap[0]), cabs(lk + kap[1])));
        for (k = 0; k < 8; k++)
          if (k != m) sep = fmin(sep, hypot(dre[k] - dre[m], dim_[k] - dim_[m]));
        for (i = 0; i < 2; i++)
          dsum += 0.5 * mb[i] * P4 * ceval2(N[i][i], 3, lk) / ((lk * lk + kap[i] * lk) * ceval2(Dd, 4, lk));
        dl[j] = dsum;
        r.rotor_re[j] = creal(lk + dsum), r.rotor_im[j] = cimag(lk + dsum);
        eps_r = fmax(eps_r, sep > 0.0 ? cabs(dsum) / sep : INFINITY);
        lre = fmax(lre, r.rotor_re[j]);
      }
      for (j = 0; j < 4; j++) errr[j] = eps_r * cabs(dl[j]);
    }
    for (j = 0; j < 12; j++) {
      double re = j < 8 ? r.ball_re[j] : r.rotor_re[j - 8], e = j < 8 ? errb[j] : errr[j - 8];
      if (re >= e) dec_unstable = 1;
      if (!(re <= -e)) dec_stable = 0;
    }
    r.ball_re_max = bre;
    r.rotor_re_max = lre;
    r.light_stable = bre < 0.0 && lre < 0.0;
    r.light_small = fmax(eps_b, eps_r);
    r.light_decided = dec_unstable || dec_stable;
    r.light_applicable = r.light_small <= AUTOBAL_ROTOR_ASYMPTOTIC_SMALL;
    high_speed(c, &r, mb, kap, dd, w, cD);
  }
  *out = r;
  return AUTOBAL_SUCCESS;
}
