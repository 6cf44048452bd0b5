/* rotor_floquet.c: the analytic linearization of the full rotor-balls model about a
 * balanced motion (mixed frame: rotor coordinates fixed, ball angles relative), its
 * rotating-coordinate form, the Floquet monodromy matrix over one revolution, and a
 * central-difference Jacobian of the model's own right-hand side (docs/rotor.md,
 * "Stability of a balanced motion" and "Anisotropic supports: Floquet multipliers").
 *
 * May use: rotor_stab_handle.h (the handle's layout and its member of the family), the
 * transient driver (the monodromy integration), the numerics (eigenvalues), the rotor model
 * (its right-hand side for the model's own Jacobian), core (internal.h).  Used by
 * rotor_stability.c through rotor_floquet.h; it never calls rotor_stability.c. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "analysis/rotor_floquet.h"
#include "analysis/rotor_stab_handle.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* State index of second-order variable k (x, y, alpha, beta, dpsi_1..N): position and rate. */
static size_t pos_index(size_t k) { return k < 4 ? k : 8 + (k - 4); }
static size_t vel_index(size_t k, size_t N) { return k < 4 ? 4 + k : 8 + N + (k - 4); }

/* The second-order matrices M(t) (into s->lu_full, not factored), C(t) (s->Ct), K(t) (s->Kt) of the
 * linearization at time t (mixed frame: rotor coordinates fixed, ball angles relative). */
static void lin_assemble(autobal_rotor_stab *s, double t) {
  const autobal_rotor_lumped *L = &s->L;
  const size_t nm = s->nm;
  const double w = s->cur.omega;
  gsl_matrix *Mt = s->lu_full;
  double *Kt = s->Kt, *Ct = s->Ct;
  size_t j, k;
  gsl_matrix_set_zero(Mt);
  memset(Kt, 0, nm * nm * sizeof *Kt);
  memset(Ct, 0, nm * nm * sizeof *Ct);
  /* rotor: diag(M, M, A, A), damping + gyroscopic, stiffness (3.2) */
  gsl_matrix_set(Mt, 0, 0, L->M);
  gsl_matrix_set(Mt, 1, 1, L->M);
  gsl_matrix_set(Mt, 2, 2, L->A);
  gsl_matrix_set(Mt, 3, 3, L->A);
#define CT(r, c) Ct[(r) * nm + (c)]
#define KT(r, c) Kt[(r) * nm + (c)]
  CT(0, 0) = L->h_x;
  CT(0, 3) = -L->h_xbeta;
  CT(1, 1) = L->h_y;
  CT(1, 2) = L->h_yalpha;
  CT(2, 2) = L->h_alpha;
  CT(2, 1) = L->h_yalpha;
  CT(2, 3) = L->C * w;
  CT(3, 3) = L->h_beta;
  CT(3, 0) = -L->h_xbeta;
  CT(3, 2) = -L->C * w;
  KT(0, 0) = L->c_x;
  KT(0, 3) = -L->c_xbeta;
  KT(1, 1) = L->c_y;
  KT(1, 2) = L->c_yalpha;
  KT(2, 2) = L->c_alpha;
  KT(2, 1) = L->c_yalpha;
  KT(3, 3) = L->c_beta;
  KT(3, 0) = -L->c_xbeta;
  for (j = 0; j < s->n_planes; j++) {
    const double d = s->cur.plane[j].d;
    const double eu[4] = {1.0, 0.0, 0.0, d}, ev[4] = {0.0, 1.0, -d, 0.0};
    if (s->cur.inertia == AUTOBAL_ROTOR_INERTIA_FULL) {
      double ma = s->cur.plane[j].m0;
      size_t a, b;
      for (k = 0; k < s->cnt[j]; k++) ma += s->m[s->off[j] + k];
      for (a = 0; a < 4; a++)
        for (b = 0; b < 4; b++)
          gsl_matrix_set(Mt, a, b, gsl_matrix_get(Mt, a, b) + ma * (eu[a] * eu[b] + ev[a] * ev[b]));
    }
    for (k = 0; k < s->cnt[j]; k++) {
      const size_t b = s->off[j] + k, col = 4 + b;
      const double a = s->m[b] * s->r[b], ph = w * t + s->psi[b];
      const double sp = sin(ph), cph = cos(ph);
      /* d(s_u + i s_v) = c dpsi, c = i a e^{i phi}; its second derivative
       * c (dpsi'' + 2 i w dpsi' - w^2 dpsi) enters along e_u (real part) and e_v (imaginary) */
      const double c2r = -a * sp, c2i = a * cph;               /* c */
      const double c1r = -2.0 * w * a * cph, c1i = -2.0 * w * a * sp; /* 2 i w c */
      const double c0r = w * w * a * sp, c0i = -w * w * a * cph;      /* -w^2 c */
      size_t q;
      for (q = 0; q < 4; q++) {
        gsl_matrix_set(Mt, q, col, eu[q] * c2r + ev[q] * c2i);
        CT(q, col) = eu[q] * c1r + ev[q] * c1i;
        KT(q, col) = eu[q] * c0r + ev[q] * c0i;
      }
      /* ball (3.13): dpsi'' + kappa dpsi' - (sin phi u_D'' - cos phi v_D'') / r = 0 */
      gsl_matrix_set(Mt, col, col, 1.0);
      for (q = 0; q < 4; q++) gsl_matrix_set(Mt, col, q, -(sp * eu[q] - cph * ev[q]) / s->r[b]);
      CT(col, col) = s->h[b] / s->m[b];
    }
  }
#undef CT
#undef KT
}

int autobal_rotor_stab_lin2_(autobal_rotor_stab *s, double t, double *M, double *C, double *K) {
  const size_t nm = s->nm;
  size_t i, j;
  if (s->psi_status != AUTOBAL_SUCCESS)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "linearization: no balanced configuration");
  lin_assemble(s, t);
  for (i = 0; i < nm; i++)
    for (j = 0; j < nm; j++) M[i * nm + j] = gsl_matrix_get(s->lu_full, i, j);
  memcpy(C, s->Ct, nm * nm * sizeof *C);
  memcpy(K, s->Kt, nm * nm * sizeof *K);
  return AUTOBAL_SUCCESS;
}

/* Linearization of (3.2) + (3.13) at the balanced state, time t:
 *   M(t) X'' + C(t) X' + K(t) X = 0,  X = (x, y, alpha, beta, dpsi_1..N),
 * first-order matrix in s->Afull (state order of the model). */
int autobal_rotor_stab_lin_(autobal_rotor_stab *s, double t, int rotating) {
  const size_t N = s->N, nm = s->nm, ns = s->ns;
  const double w = s->cur.omega;
  gsl_matrix *Mt = s->lu_full;
  double *Kt = s->Kt, *Ct = s->Ct, *A = s->Afull;
  size_t i, j, k;
  int signum, gs;
  if (s->psi_status != AUTOBAL_SUCCESS)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "linearization: no balanced configuration");
  lin_assemble(s, t);
  gs = gsl_linalg_LU_decomp(Mt, s->perm_full, &signum);
  if (gs != GSL_SUCCESS)
    return autobal_error_set(&s->err, AUTOBAL_ENUMERIC, "linearization: LU failed: %s",
                             gsl_strerror(gs));
  {
    double dmax = 0.0;
    for (i = 0; i < nm; i++) dmax = fmax(dmax, fabs(gsl_matrix_get(Mt, i, i)));
    for (i = 0; i < nm; i++)
      if (!(fabs(gsl_matrix_get(Mt, i, i)) > 1e-13 * dmax))
        return autobal_error_set(&s->err, AUTOBAL_ENUMERIC,
                                 "linearization: the effective mass matrix is singular");
  }
  memset(A, 0, ns * ns * sizeof *A);
  for (k = 0; k < nm; k++) A[pos_index(k) * ns + vel_index(k, N)] = 1.0;
  for (j = 0; j < 2; j++) {
    const double *R = j == 0 ? Kt : Ct;
    for (k = 0; k < nm; k++) {
      gsl_vector *v = s->vec_full;
      for (i = 0; i < nm; i++) gsl_vector_set(v, i, R[i * nm + k]);
      gs = gsl_linalg_LU_svx(Mt, s->perm_full, v);
      if (gs != GSL_SUCCESS)
        return autobal_error_set(&s->err, AUTOBAL_ENUMERIC, "linearization: solve failed: %s",
                                 gsl_strerror(gs));
      for (i = 0; i < nm; i++) {
        const size_t row = vel_index(i, N), colst = j == 0 ? pos_index(k) : vel_index(k, N);
        A[row * ns + colst] = -gsl_vector_get(v, i);
      }
    }
  }
  if (rotating) {
    /* + blockdiag(Omega, Omega), Omega = w blockdiag(J2, J2), J2 = [[0, 1], [-1, 0]] */
    size_t o;
    for (o = 0; o < 8; o += 4) {
      A[(o + 0) * ns + o + 1] += w;
      A[(o + 1) * ns + o + 0] -= w;
      A[(o + 2) * ns + o + 3] += w;
      A[(o + 3) * ns + o + 2] -= w;
    }
  }
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_stab_linearization(autobal_rotor_stab *s, double t, int rotating, double *a,
                                     size_t dim) {
  int st;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (s->tr == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED,
                             "linearization: too many balls (N = %zu)", s->N);
  if (a == NULL || dim != s->ns)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "linearization: dim = %zu, need %zu", dim,
                             s->ns);
  if (!isfinite(t)) return autobal_error_set(&s->err, AUTOBAL_EINVAL, "linearization: t not finite");
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_lin_(s, t, rotating)) != AUTOBAL_SUCCESS) return st;
  memcpy(a, s->Afull, dim * dim * sizeof *a);
  return AUTOBAL_SUCCESS;
}

/* ---- Floquet ---------------------------------------------------------------------- */

/* Variational equation in scaled coordinates: Y' = (S^-1 A(t) S) Y, Y ns x ns row-major. */
static int floquet_rhs(double t, const double y[], double dydt[], void *params) {
  autobal_rotor_stab *s = (autobal_rotor_stab *)params;
  const size_t ns = s->ns;
  size_t i, j, k;
  if (autobal_rotor_stab_lin_(s, t, 0) != AUTOBAL_SUCCESS) return GSL_EBADFUNC;
  for (i = 0; i < ns; i++)
    for (j = 0; j < ns; j++) s->Ascaled[i * ns + j] = s->Afull[i * ns + j] * s->sc[j] / s->sc[i];
  for (i = 0; i < ns; i++) {
    double *out = dydt + i * ns;
    const double *arow = s->Ascaled + i * ns;
    for (j = 0; j < ns; j++) out[j] = 0.0;
    for (k = 0; k < ns; k++) {
      const double aik = arow[k];
      const double *yk = y + k * ns;
      if (aik == 0.0) continue;
      for (j = 0; j < ns; j++) out[j] += aik * yk[j];
    }
  }
  return GSL_SUCCESS;
}

/* Scale factors of the state (y = S z): lengths sum m r / M, angles that over sqrt(A/M),
 * ball angles 1; rates times a natural frequency. */
static void floquet_scales(autobal_rotor_stab *s) {
  const autobal_rotor_lumped *L = &s->L;
  const size_t N = s->N;
  double amass = 0.0, ell, rg, wn;
  size_t i;
  for (i = 0; i < N; i++) amass += s->m[i] * s->r[i];
  ell = amass > 0.0 ? amass / L->M : 1e-3;
  rg = sqrt(L->A / L->M);
  wn = fabs(s->cur.omega) + sqrt(fmax(fmax(L->c_x, L->c_y), 1e-300) / L->M);
  s->sc[0] = s->sc[1] = ell;
  s->sc[2] = s->sc[3] = ell / rg;
  for (i = 0; i < 4; i++) s->sc[4 + i] = s->sc[i] * wn;
  for (i = 0; i < N; i++) {
    s->sc[8 + i] = 1.0;
    s->sc[8 + N + i] = wn;
  }
}

int autobal_rotor_stab_floquet_(autobal_rotor_stab *s, double *monodromy) {
  const size_t ns = s->ns;
  const double T = 2.0 * M_PI / fabs(s->cur.omega);
  autobal_transient_system sys;
  double tr_end = 0.0;
  size_t i, j;
  int st;
  if (s->tr == NULL)
    return autobal_error_set(&s->err, AUTOBAL_EUNSUPPORTED, "floquet: too many balls (N = %zu)",
                             s->N);
  if (!(s->cur.omega != 0.0) || !isfinite(T))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "floquet: needs omega != 0");
  if (s->psi_status != AUTOBAL_SUCCESS)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "floquet: no balanced configuration");
  floquet_scales(s);
  memset(s->phi, 0, ns * ns * sizeof *s->phi);
  for (i = 0; i < ns; i++) s->phi[i * ns + i] = 1.0;
  sys.rhs = floquet_rhs;
  sys.jac = NULL;
  sys.dim = ns * ns;
  sys.params = s;
  st = autobal_transient_run(s->tr, &sys, 0.0, T, s->phi, &tr_end);
  if (st != AUTOBAL_SUCCESS) {
    if (st > 0) st = AUTOBAL_ENUMERIC;
    return autobal_error_set(&s->err, st, "floquet: the monodromy integration failed at t = %.9g s "
                                          "of T = %.9g s: %s",
                             tr_end, T, autobal_transient_errmsg(s->tr));
  }
  st = autobal_eigen_nonsymm(s->ew_full, s->phi, s->mu_re, s->mu_im, &s->err);
  if (st != AUTOBAL_SUCCESS) return st;
  /* sort by decreasing modulus (insertion sort; ties by real part then imaginary) */
  for (i = 1; i < ns; i++) {
    const double r = s->mu_re[i], m = s->mu_im[i], a = hypot(r, m);
    j = i;
    while (j > 0) {
      const double aj = hypot(s->mu_re[j - 1], s->mu_im[j - 1]);
      if (aj > a || (aj == a && (s->mu_re[j - 1] > r || (s->mu_re[j - 1] == r && s->mu_im[j - 1] >= m))))
        break;
      s->mu_re[j] = s->mu_re[j - 1];
      s->mu_im[j] = s->mu_im[j - 1];
      j--;
    }
    s->mu_re[j] = r;
    s->mu_im[j] = m;
  }
  if (monodromy) {
    for (i = 0; i < ns; i++)
      for (j = 0; j < ns; j++) monodromy[i * ns + j] = s->phi[i * ns + j] * s->sc[i] / s->sc[j];
  }
  return AUTOBAL_SUCCESS;
}

double autobal_rotor_stab_floquet_margin_(const autobal_rotor_stab *s, size_t family) {
  const size_t ns = s->ns;
  const double T = 2.0 * M_PI / fabs(s->cur.omega);
  double mx = 0.0;
  size_t i, k;
  unsigned char excl[8 + 2 * 64];
  memset(excl, 0, sizeof excl);
  for (k = 0; k < family && k < ns; k++) {
    size_t best = ns;
    double bd = INFINITY;
    for (i = 0; i < ns; i++) {
      const double dd = hypot(s->mu_re[i] - 1.0, s->mu_im[i]);
      if (!excl[i] && dd < bd) {
        bd = dd;
        best = i;
      }
    }
    if (best < ns) excl[best] = 1;
  }
  for (i = 0; i < ns; i++)
    if (!excl[i]) mx = fmax(mx, hypot(s->mu_re[i], s->mu_im[i]));
  return log(mx) / T;
}

int autobal_rotor_stab_floquet(autobal_rotor_stab *s, double *mu_re, double *mu_im, size_t n,
                               double *monodromy) {
  int st;
  if (s == NULL) return AUTOBAL_EINVAL;
  if (mu_re == NULL || mu_im == NULL || n != s->ns)
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "floquet: n = %zu, need 8 + 2N = %zu", n, s->ns);
  if (!(s->cur.omega != 0.0))
    return autobal_error_set(&s->err, AUTOBAL_EINVAL, "floquet: needs omega != 0");
  if ((st = autobal_rotor_stab_update_member_(s)) != AUTOBAL_SUCCESS) return st;
  if ((st = autobal_rotor_stab_floquet_(s, monodromy)) != AUTOBAL_SUCCESS) return st;
  memcpy(mu_re, s->mu_re, n * sizeof *mu_re);
  memcpy(mu_im, s->mu_im, n * sizeof *mu_im);
  return AUTOBAL_SUCCESS;
}

/* ---- the model's own Jacobian ------------------------------------------------------- */

int autobal_rotor_model_jacobian(autobal_rotor *r, double t, const double *y, double *J, size_t dim,
                                 double *work) {
  double *yp, *fp, *fm;
  size_t i, j;
  if (r == NULL || y == NULL || J == NULL || work == NULL || dim != autobal_rotor_dim(r))
    return AUTOBAL_EINVAL;
  yp = work;
  fp = work + dim;
  fm = work + 2 * dim;
  memcpy(yp, y, dim * sizeof *y);
  for (j = 0; j < dim; j++) {
    const double h = 1e-6 * fmax(fabs(y[j]), 1.0);
    yp[j] = y[j] + h;
    if (autobal_rotor_rhs_rotating(t, yp, fp, r) != GSL_SUCCESS) return AUTOBAL_ERHS;
    yp[j] = y[j] - h;
    if (autobal_rotor_rhs_rotating(t, yp, fm, r) != GSL_SUCCESS) return AUTOBAL_ERHS;
    yp[j] = y[j];
    for (i = 0; i < dim; i++) J[i * dim + j] = (fp[i] - fm[i]) / (2.0 * h);
  }
  return AUTOBAL_SUCCESS;
}
