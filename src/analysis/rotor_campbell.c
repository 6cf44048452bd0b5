/* rotor_campbell.c: the rotor-housing without balls (docs/rotor.md, (3.2) with s = the
 * unbalance only): natural frequencies and damping ratios at a speed (gyroscopic
 * coupling C omega), the Campbell diagram, the steady unbalance response and the
 * resonance (unbalance-response critical) speeds.
 *
 * May use: the rotor model (autobal/rotor.h: lumped coefficients), the numerics (bracketing),
 * GSL (eigenvalues), core (internal.h), and rotor_stab_internal.h for the prototype of its
 * test hook.  No other file of src/analysis/: the stability handle is not needed here. */
#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

#include "autobal/rotor_stability.h"
#include "autobal/stability.h"
#include "analysis/rotor_stab_internal.h"
#include "internal.h"

typedef struct modes_ws {
  gsl_eigen_nonsymmv_workspace *w;
  gsl_matrix *A;
  gsl_vector_complex *eval;
  gsl_matrix_complex *evec;
  autobal_rotor_lumped L;
  double Mq[4][4]; /* mass matrix (with the FULL model's attached masses) */
  const autobal_rotor_params *p;
} modes_ws;

static void modes_ws_free(modes_ws *m) {
  if (m->w) gsl_eigen_nonsymmv_free(m->w);
  if (m->A) gsl_matrix_free(m->A);
  if (m->eval) gsl_vector_complex_free(m->eval);
  if (m->evec) gsl_matrix_complex_free(m->evec);
  memset(m, 0, sizeof *m);
}

static int modes_ws_init(modes_ws *m, const autobal_rotor_params *p, autobal_error *err) {
  autobal_error e;
  int st;
  size_t j, i, a, b;
  memset(m, 0, sizeof *m);
  autobal_error_clear(&e);
  st = autobal_rotor_params_check(p, &e);
  if (st < 0) {
    if (err) *err = e;
    return st;
  }
  if (p->input == AUTOBAL_ROTOR_HARDWARE) (void)autobal_rotor_lumped_from_hardware(&p->hw, &m->L, NULL);
  else m->L = p->lumped;
  m->p = p;
  m->Mq[0][0] = m->Mq[1][1] = m->L.M;
  m->Mq[2][2] = m->Mq[3][3] = m->L.A;
  if (p->inertia == AUTOBAL_ROTOR_INERTIA_FULL) {
    for (j = 0; j < p->n_planes; j++) {
      const double d = p->plane[j].d;
      const double eu[4] = {1.0, 0.0, 0.0, d}, ev[4] = {0.0, 1.0, -d, 0.0};
      double ma = p->plane[j].m0;
      for (i = 0; i < p->plane[j].n_balls; i++) ma += p->plane[j].ball_mass[i];
      for (a = 0; a < 4; a++)
        for (b = 0; b < 4; b++) m->Mq[a][b] += ma * (eu[a] * eu[b] + ev[a] * ev[b]);
    }
  }
  m->w = gsl_eigen_nonsymmv_alloc(8);
  m->A = gsl_matrix_alloc(8, 8);
  m->eval = gsl_vector_complex_alloc(8);
  m->evec = gsl_matrix_complex_alloc(8, 8);
  if (!m->w || !m->A || !m->eval || !m->evec) {
    modes_ws_free(m);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "modes: out of memory");
  }
  return AUTOBAL_SUCCESS;
}

/* Solve the real 4x4 system a x = b in place (partial pivoting); -1 if singular. */
static int solve4(double a[4][4], double b[4]) {
  int i, j, k;
  for (k = 0; k < 4; k++) {
    int piv = k;
    for (i = k + 1; i < 4; i++)
      if (fabs(a[i][k]) > fabs(a[piv][k])) piv = i;
    if (!(fabs(a[piv][k]) > 0.0)) return -1;
    if (piv != k) {
      for (j = 0; j < 4; j++) {
        double t = a[k][j];
        a[k][j] = a[piv][j];
        a[piv][j] = t;
      }
      {
        double t = b[k];
        b[k] = b[piv];
        b[piv] = t;
      }
    }
    for (i = k + 1; i < 4; i++) {
      double f = a[i][k] / a[k][k];
      for (j = k; j < 4; j++) a[i][j] -= f * a[k][j];
      b[i] -= f * b[k];
    }
  }
  for (i = 3; i >= 0; i--) {
    double sum = b[i];
    for (j = i + 1; j < 4; j++) sum -= a[i][j] * b[j];
    b[i] = sum / a[i][i];
  }
  return 0;
}

/* Complex 4x4 solve in place; -1 if singular. */
static int csolve4(double complex a[4][4], double complex b[4]) {
  int i, j, k;
  double amax = 0.0;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) amax = fmax(amax, cabs(a[i][j]));
  for (k = 0; k < 4; k++) {
    int piv = k;
    for (i = k + 1; i < 4; i++)
      if (cabs(a[i][k]) > cabs(a[piv][k])) piv = i;
    /* singular to working precision (an undamped resonance) */
    if (!(cabs(a[piv][k]) > 1e-13 * amax)) return -1;
    if (piv != k) {
      for (j = 0; j < 4; j++) {
        double complex t = a[k][j];
        a[k][j] = a[piv][j];
        a[piv][j] = t;
      }
      {
        double complex t = b[k];
        b[k] = b[piv];
        b[piv] = t;
      }
    }
    for (i = k + 1; i < 4; i++) {
      double complex f = a[i][k] / a[k][k];
      for (j = k; j < 4; j++) a[i][j] -= f * a[k][j];
      b[i] -= f * b[k];
    }
  }
  for (i = 3; i >= 0; i--) {
    double complex sum = b[i];
    for (j = i + 1; j < 4; j++) sum -= a[i][j] * b[j];
    b[i] = sum / a[i][i];
  }
  return 0;
}

/* Damping (H + G(omega)) and stiffness K of (3.2) (rows x, y, alpha, beta). */
static void rotor_matrices(const autobal_rotor_lumped *L, double omega, int undamped,
                           double Hg[4][4], double K[4][4]) {
  const double g = undamped ? 0.0 : 1.0;
  memset(Hg, 0, 16 * sizeof(double));
  memset(K, 0, 16 * sizeof(double));
  Hg[0][0] = g * L->h_x;
  Hg[0][3] = -g * L->h_xbeta;
  Hg[1][1] = g * L->h_y;
  Hg[1][2] = g * L->h_yalpha;
  Hg[2][2] = g * L->h_alpha;
  Hg[2][1] = g * L->h_yalpha;
  Hg[3][3] = g * L->h_beta;
  Hg[3][0] = -g * L->h_xbeta;
  Hg[2][3] = L->C * omega;  /* gyroscopic: alpha row + C w beta' */
  Hg[3][2] = -L->C * omega; /* beta row - C w alpha' */
  K[0][0] = L->c_x;
  K[0][3] = -L->c_xbeta;
  K[1][1] = L->c_y;
  K[1][2] = L->c_yalpha;
  K[2][2] = L->c_alpha;
  K[2][1] = L->c_yalpha;
  K[3][3] = L->c_beta;
  K[3][0] = -L->c_xbeta;
}

static int modes_eval(modes_ws *m, double omega, int undamped, double freq[4], double zeta[4],
                      double growth[4], int whirl[4], autobal_error *err) {
  double Hg[4][4], K[4][4], lam_re[8], lam_im[8];
  size_t idx[8], i, j, k;
  int gs;
  rotor_matrices(&m->L, omega, undamped, Hg, K);
  gsl_matrix_set_zero(m->A);
  for (i = 0; i < 4; i++) gsl_matrix_set(m->A, i, 4 + i, 1.0);
  for (k = 0; k < 8; k++) {
    /* column k of -M^-1 [K Hg] */
    double a[4][4], b[4];
    for (i = 0; i < 4; i++) {
      for (j = 0; j < 4; j++) a[i][j] = m->Mq[i][j];
      b[i] = k < 4 ? K[i][k] : Hg[i][k - 4];
    }
    if (solve4(a, b) != 0) return autobal_error_set(err, AUTOBAL_ENUMERIC, "modes: singular mass matrix");
    for (i = 0; i < 4; i++) gsl_matrix_set(m->A, 4 + i, k, -b[i]);
  }
  gs = gsl_eigen_nonsymmv(m->A, m->eval, m->evec, m->w);
  if (gs != GSL_SUCCESS)
    return autobal_error_set(err, AUTOBAL_ENUMERIC, "modes: gsl_eigen_nonsymmv: %s", gsl_strerror(gs));
  for (i = 0; i < 8; i++) {
    gsl_complex z = gsl_vector_complex_get(m->eval, i);
    lam_re[i] = GSL_REAL(z);
    lam_im[i] = GSL_IMAG(z);
    idx[i] = i;
  }
  /* the 4 with the largest imaginary parts, then by increasing frequency */
  for (i = 1; i < 8; i++) {
    size_t t = idx[i];
    j = i;
    while (j > 0 && (lam_im[idx[j - 1]] < lam_im[t] ||
                     (lam_im[idx[j - 1]] == lam_im[t] && lam_re[idx[j - 1]] < lam_re[t]))) {
      idx[j] = idx[j - 1];
      j--;
    }
    idx[j] = t;
  }
  for (i = 1; i < 4; i++) {
    size_t t = idx[i];
    j = i;
    while (j > 0 && lam_im[idx[j - 1]] > lam_im[t]) {
      idx[j] = idx[j - 1];
      j--;
    }
    idx[j] = t;
  }
  for (k = 0; k < 4; k++) {
    const size_t e = idx[k];
    const double re = lam_re[e], im = lam_im[e], mod = hypot(re, im);
    if (freq) freq[k] = im;
    if (zeta) zeta[k] = mod > 0.0 ? -re / mod : 1.0;
    if (growth) growth[k] = re;
    if (whirl) {
      /* forward part |v_x + i v_y|^2 M + |v_beta - i v_alpha|^2 A, backward with -i */
      gsl_complex vx = gsl_matrix_complex_get(m->evec, 0, e), vy = gsl_matrix_complex_get(m->evec, 1, e);
      gsl_complex va = gsl_matrix_complex_get(m->evec, 2, e), vb = gsl_matrix_complex_get(m->evec, 3, e);
      double complex cx = GSL_REAL(vx) + I * GSL_IMAG(vx), cy = GSL_REAL(vy) + I * GSL_IMAG(vy);
      double complex ca = GSL_REAL(va) + I * GSL_IMAG(va), cb = GSL_REAL(vb) + I * GSL_IMAG(vb);
      double fwd = m->L.M * pow(cabs(cx + I * cy), 2) + m->L.A * pow(cabs(cb - I * ca), 2);
      double bwd = m->L.M * pow(cabs(cx - I * cy), 2) + m->L.A * pow(cabs(cb + I * ca), 2);
      int wv = 0;
      if (im > 0.0 && fabs(fwd - bwd) > 1e-6 * (fwd + bwd)) wv = fwd > bwd ? 1 : -1;
      if (omega < 0.0) wv = -wv;
      whirl[k] = wv;
    }
  }
  return AUTOBAL_SUCCESS;
}

int autobal_rotor_modes(const autobal_rotor_params *p, double omega, int undamped, double freq[4],
                        double zeta[4], double growth[4], int whirl[4], autobal_error *err) {
  modes_ws m;
  int st;
  if ((st = autobal_check_param(err, "omega", omega, -INFINITY, 1, INFINITY, 1, "rad/s"))) return st;
  if ((st = modes_ws_init(&m, p, err)) != AUTOBAL_SUCCESS) return st;
  st = modes_eval(&m, omega, undamped, freq, zeta, growth, whirl, err);
  modes_ws_free(&m);
  return st;
}

int autobal_rotor_campbell(const autobal_rotor_params *p, const double *omega, size_t n,
                           double *freq, double *zeta, int *whirl, autobal_error *err) {
  modes_ws m;
  size_t k;
  int st;
  if (omega == NULL && n > 0) return autobal_error_set(err, AUTOBAL_EINVAL, "campbell: omega is NULL");
  for (k = 0; k < n; k++)
    if (!isfinite(omega[k]))
      return autobal_error_set(err, AUTOBAL_EINVAL, "campbell: omega[%zu] = %g is not finite", k,
                               omega[k]);
  if ((st = modes_ws_init(&m, p, err)) != AUTOBAL_SUCCESS) return st;
  for (k = 0; k < n && st == AUTOBAL_SUCCESS; k++)
    st = modes_eval(&m, omega[k], 0, freq ? freq + 4 * k : NULL, zeta ? zeta + 4 * k : NULL, NULL,
                    whirl ? whirl + 4 * k : NULL, err);
  modes_ws_free(&m);
  return st;
}

/* Steady response amplitude (see the header); lumped L and mass matrix Mq given. */
static int response(const autobal_rotor_params *p, const autobal_rotor_lumped *L,
                    const double Mq[4][4], double omega, double *amp_G, double *amp_D) {
  double Hg[4][4], K[4][4];
  double complex a[4][4], b[4];
  size_t i, j;
  rotor_matrices(L, omega, 0, Hg, K);
  for (i = 0; i < 4; i++) {
    for (j = 0; j < 4; j++) a[i][j] = K[i][j] - omega * omega * Mq[i][j] + I * omega * Hg[i][j];
    b[i] = 0.0;
  }
  for (j = 0; j < p->n_planes; j++) {
    const double d = p->plane[j].d;
    const double complex f = omega * omega * p->plane[j].m0 * p->plane[j].r0 * cexp(I * p->plane[j].psi0);
    /* e_u - i e_v = (1, -i, i d, d) */
    b[0] += f;
    b[1] += -I * f;
    b[2] += I * d * f;
    b[3] += d * f;
  }
  if (csolve4(a, b) != 0) return -1;
  if (amp_G) *amp_G = 0.5 * (cabs(b[0] + I * b[1]) + cabs(b[0] - I * b[1]));
  if (amp_D)
    for (j = 0; j < p->n_planes; j++) {
      const double d = p->plane[j].d;
      const double complex u = b[0] + d * b[3], v = b[1] - d * b[2];
      amp_D[j] = 0.5 * (cabs(u + I * v) + cabs(u - I * v));
    }
  return isfinite(creal(b[0])) ? 0 : -1;
}

int autobal_rotor_unbalance_response(const autobal_rotor_params *p, double omega, double *amp_G,
                                     double *amp_D, autobal_error *err) {
  modes_ws m;
  int st;
  if ((st = autobal_check_param(err, "omega", omega, -INFINITY, 1, INFINITY, 1, "rad/s"))) return st;
  if ((st = modes_ws_init(&m, p, err)) != AUTOBAL_SUCCESS) return st;
  if (response(p, &m.L, (const double(*)[4])m.Mq, omega, amp_G, amp_D) != 0)
    st = autobal_error_set(err, AUTOBAL_ENUMERIC,
                           "unbalance response: singular dynamic stiffness at omega = %.9g rad/s "
                           "(an undamped resonance)",
                           omega);
  modes_ws_free(&m);
  return st;
}

typedef struct res_ctx {
  modes_ws *m;
  int mode;
  autobal_error *err;
} res_ctx;

static int cross_fn(double x, void *ctx, double *fx) {
  res_ctx *c = (res_ctx *)ctx;
  double f[4];
  int st = modes_eval(c->m, x, 0, f, NULL, NULL, NULL, c->err);
  *fx = f[c->mode] - x;
  return st;
}

static double amp_at(res_ctx *c, double x) {
  double a = NAN;
  if (response(c->m->p, &c->m->L, (const double(*)[4])c->m->Mq, x, &a, NULL) != 0) return INFINITY;
  return a;
}

/* The scan of autobal_rotor_resonance_speeds with at most cap entries in each list.  At the
 * first crossing or peak that does not fit, out->truncated = 1 and the scan stops there
 * (nothing is refined further); *x_complete receives the speed up to which both lists are
 * complete (to the grid's resolution): two grid steps before the step where the entry was
 * dropped (a peak found at step k lies around grid point k - 1), lo at the earliest;
 * *by_peak = 1 if the dropped entry was a peak, 0 if a crossing. */
static int resonance_scan(const autobal_rotor_params *p, double lo, double hi, size_t n_grid,
                          double xtol_rel, size_t cap, autobal_rotor_stab_cancel_fn cancel, void *user,
                          autobal_rotor_resonances *out, double *x_complete, int *by_peak,
                          autobal_error *err) {
  modes_ws m;
  res_ctx rc;
  double fprev[4] = {0, 0, 0, 0}, aprev2 = NAN, aprev = NAN, xprev = lo, xprev2 = lo;
  size_t k;
  int st, mode;
  *x_complete = hi;
  *by_peak = 0;
  if ((st = modes_ws_init(&m, p, err)) != AUTOBAL_SUCCESS) return st;
  rc.m = &m;
  rc.err = err;
  for (k = 0; k < n_grid && st == AUTOBAL_SUCCESS && !out->truncated; k++) {
    const double x = k + 1 == n_grid ? hi : lo + (hi - lo) * (double)k / (double)(n_grid - 1);
    double f[4], a;
    int w4[4];
    if (cancel && cancel(user)) {
      st = autobal_error_set(err, AUTOBAL_ECANCELLED, "cancelled by the caller");
      break;
    }
    if ((st = modes_eval(&m, x, 0, f, NULL, NULL, w4, err)) != AUTOBAL_SUCCESS) break;
    a = amp_at(&rc, x);
    if (k > 0) {
      for (mode = 0; mode < 4; mode++) {
        const double g0 = fprev[mode] - xprev, g1 = f[mode] - x;
        if ((g0 > 0.0) != (g1 > 0.0)) {
          double root = NAN;
          int wv[4];
          if (out->n_cross >= cap) {
            out->truncated = 1;
            break;
          }
          rc.mode = mode;
          st = autobal_root_brent(cross_fn, &rc, xprev, x, 0.0, xtol_rel, 200, &root, err);
          if (st == AUTOBAL_ENUMERIC) st = AUTOBAL_SUCCESS;
          if (st != AUTOBAL_SUCCESS) break;
          out->cross[out->n_cross] = root;
          out->cross_mode[out->n_cross] = mode;
          if ((st = modes_eval(&m, root, 0, f, NULL, NULL, wv, err)) != AUTOBAL_SUCCESS) break;
          out->cross_whirl[out->n_cross] = wv[mode];
          out->n_cross++;
          /* restore f at x */
          if ((st = modes_eval(&m, x, 0, f, NULL, NULL, w4, err)) != AUTOBAL_SUCCESS) break;
        }
      }
      if (st != AUTOBAL_SUCCESS || out->truncated) {
        *x_complete = xprev2;
        break;
      }
    }
    if (k >= 2 && aprev > aprev2 && aprev >= a && isfinite(aprev)) {
      /* golden-section search for the maximum on [xprev2, x] */
      const double gr = 0.5 * (sqrt(5.0) - 1.0);
      double aa = xprev2, bb = x, c1 = bb - gr * (bb - aa), c2 = aa + gr * (bb - aa);
      double f1, f2;
      int it;
      if (out->n_peak >= cap) {
        out->truncated = 1;
        *by_peak = 1;
        *x_complete = xprev2;
        break;
      }
      f1 = amp_at(&rc, c1);
      f2 = amp_at(&rc, c2);
      for (it = 0; it < 300 && (bb - aa) > xtol_rel * fabs(bb); it++) {
        if (f1 > f2) {
          bb = c2;
          c2 = c1;
          f2 = f1;
          c1 = bb - gr * (bb - aa);
          f1 = amp_at(&rc, c1);
        } else {
          aa = c1;
          c1 = c2;
          f1 = f2;
          c2 = aa + gr * (bb - aa);
          f2 = amp_at(&rc, c2);
        }
      }
      out->peak[out->n_peak] = 0.5 * (aa + bb);
      out->peak_amp[out->n_peak] = amp_at(&rc, 0.5 * (aa + bb));
      out->n_peak++;
    }
    memcpy(fprev, f, sizeof fprev);
    aprev2 = aprev;
    aprev = a;
    xprev2 = xprev;
    xprev = x;
  }
  modes_ws_free(&m);
  return st;
}

static int resonances_checked(const autobal_rotor_params *p, double lo, double hi, size_t n_grid,
                              double xtol_rel, size_t cap, autobal_rotor_stab_cancel_fn cancel,
                              void *user, autobal_rotor_resonances *out, autobal_error *err) {
  double xc = hi;
  int st, by_peak = 0;
  if (out == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "resonances: NULL output");
  memset(out, 0, sizeof *out);
  if (!(isfinite(lo) && isfinite(hi) && lo >= 0.0 && lo < hi))
    return autobal_error_set(err, AUTOBAL_EINVAL, "resonances: need 0 <= lo < hi, got [%g, %g]", lo, hi);
  if (n_grid < 3 || n_grid > 100000000)
    return autobal_error_set(err, AUTOBAL_EINVAL, "resonances: n_grid = %zu out of range [3, 1e8]",
                             n_grid);
  if (!(xtol_rel > 0.0 && xtol_rel < 0.1))
    return autobal_error_set(err, AUTOBAL_EINVAL, "resonances: xtol_rel = %g out of range (0, 0.1)",
                             xtol_rel);
  if (cap < 1 || cap > AUTOBAL_ROTOR_MAX_CRIT)
    return autobal_error_set(err, AUTOBAL_EINVAL, "resonances: capacity %zu out of range [1, %d]",
                             cap, AUTOBAL_ROTOR_MAX_CRIT);
  st = resonance_scan(p, lo, hi, n_grid, xtol_rel, cap, cancel, user, out, &xc, &by_peak, err);
  if (st == AUTOBAL_SUCCESS && out->truncated)
    st = autobal_error_set(err, AUTOBAL_WARNING,
                           "resonances: more than %zu %s in [%.9g, %.9g] rad/s (the capacity of "
                           "the list): the search stopped there; the lists hold %zu crossings and "
                           "%zu peaks and are complete for omega <= %.9g rad/s only. Narrow the "
                           "range (e.g. omega_max <= %.9g) or split it",
                           cap, by_peak ? "peaks of the unbalance response"
                                        : "crossings (natural frequency = omega)",
                           lo, hi, out->n_cross, out->n_peak, xc, xc);
  return st;
}

int autobal_rotor_resonance_speeds(const autobal_rotor_params *p, double lo, double hi,
                                   size_t n_grid, double xtol_rel, autobal_rotor_resonances *out,
                                   autobal_error *err) {
  return resonances_checked(p, lo, hi, n_grid, xtol_rel, AUTOBAL_ROTOR_MAX_CRIT, NULL, NULL, out, err);
}

int autobal_rotor_resonance_speeds_cancellable(const autobal_rotor_params *p, double lo, double hi,
                                               size_t n_grid, double xtol_rel,
                                               autobal_rotor_stab_cancel_fn cancel, void *user,
                                               autobal_rotor_resonances *out, autobal_error *err) {
  return resonances_checked(p, lo, hi, n_grid, xtol_rel, AUTOBAL_ROTOR_MAX_CRIT, cancel, user, out, err);
}

int autobal_rotor_resonance_speeds_cap_(const autobal_rotor_params *p, double lo, double hi,
                                        size_t n_grid, double xtol_rel, size_t cap,
                                        autobal_rotor_resonances *out, autobal_error *err) {
  return resonances_checked(p, lo, hi, n_grid, xtol_rel, cap, NULL, NULL, out, err);
}
