/* rotor_stab_internal.h: private layout of the rotor stability handle, shared by
 * src/rotor_stability.c, src/rotor_floquet.c, and capacity-limited variants of the
 * critical-value searches (src/rotor_stability.c, src/rotor_campbell.c) for the tests of
 * their truncation path (not installed). */
#ifndef AUTOBAL_ROTOR_STAB_INTERNAL_H
#define AUTOBAL_ROTOR_STAB_INTERNAL_H

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_permutation.h>

#include "autobal/rotor_stability.h"
#include "autobal/stability.h"
#include "autobal/transient.h"

struct autobal_rotor_stab {
  autobal_rotor_params cur;        /* working parameters; ball arrays point into m, r, h, psi0i, rate0 */
  autobal_rotor_lumped Lbase;      /* lumped coefficients at alloc */
  autobal_rotor_lumped L;          /* current lumped coefficients */
  double c_scale, h_scale;         /* current STIFFNESS_SCALE, DAMPING_SCALE */
  autobal_rotor_stab_options opt;  /* member angle pointers into member_store */
  size_t n_planes, N, off[AUTOBAL_ROTOR_MAX_PLANES], cnt[AUTOBAL_ROTOR_MAX_PLANES];
  size_t ns;                       /* 8 + 2N, full linearization dimension */
  size_t nm;                       /* 4 + N, second-order dimension */
  double *store;                   /* one block for every array below */
  double *m, *r, *h, *psi_init, *rate_init; /* N each, current ball data */
  double *member_store;            /* member angles (sum n_j) */
  double *m_save, *h_save;         /* N each: ball masses / dampings saved by a sweep or a
                                      critical search (stab_save / stab_restore) */
  double *psi;                     /* N balanced angles of the member */
  int psi_status;                  /* status of the last member computation */
  /* workspaces */
  autobal_poly_workspace *pw;      /* degree 12 */
  autobal_eigen_workspace *ew_closed; /* 8 + 4 n_planes */
  autobal_eigen_workspace *ew_full;   /* ns */
  gsl_matrix *lu_closed;           /* (4 + 2 n_planes) squared, real mass matrix of the closed system */
  gsl_permutation *perm_closed;
  gsl_matrix *lu_full;             /* nm x nm mass matrix M(t) */
  gsl_permutation *perm_full;
  gsl_vector *vec_full;            /* nm */
  double *Kt, *Ct;                 /* nm x nm */
  double *Afull;                   /* ns x ns */
  double *Ascaled;                 /* ns x ns */
  double *sc;                      /* ns scale factors of the Floquet state */
  double *phi;                     /* ns x ns */
  double *full_re, *full_im, *mu_re, *mu_im; /* ns each */
  double *tmp_re, *tmp_im;         /* ns each */
  autobal_transient *tr;           /* dimension ns^2 */
  double closed_mat[AUTOBAL_ROTOR_CLOSED_MAX * AUTOBAL_ROTOR_CLOSED_MAX];
  autobal_error err;
};

/* Balanced angles of the current member into s->psi (status also in s->psi_status). */
int autobal_rotor_stab_update_member_(autobal_rotor_stab *s);
/* Family dimension (sum over planes of n_j - rank_j) at the current member (psi valid). */
size_t autobal_rotor_stab_family_(const autobal_rotor_stab *s);
/* Analytic mixed-frame linearization into s->Afull (see the header). */
int autobal_rotor_stab_lin_(autobal_rotor_stab *s, double t, int rotating);
/* Floquet multipliers into s->mu_re/mu_im (sorted by decreasing modulus); monodromy
 * (may be NULL) unscaled. */
int autobal_rotor_stab_floquet_(autobal_rotor_stab *s, double *monodromy);
/* Margin from Floquet multipliers excluding `family` multipliers closest to 1. */
double autobal_rotor_stab_floquet_margin_(const autobal_rotor_stab *s, size_t family);
/* Is the lumped set isotropic (relative 1e-12)? */
int autobal_rotor_lumped_isotropic_(const autobal_rotor_lumped *L);

/* autobal_rotor_stab_critical with the capacity of the list of critical values limited to
 * cap (1 <= cap <= AUTOBAL_ROTOR_MAX_CRIT; the public function uses AUTOBAL_ROTOR_MAX_CRIT),
 * so that the truncation path can be tested with few verdict changes.  AUTOBAL_EINVAL for
 * cap out of range (message on the handle); otherwise exactly the public function. */
int autobal_rotor_stab_critical_cap_(autobal_rotor_stab *s, int param, double lo, double hi,
                                     size_t n_grid, double xtol_rel, size_t cap,
                                     autobal_rotor_crit *out);
/* autobal_rotor_resonance_speeds with both lists limited to cap entries (1 <= cap <=
 * AUTOBAL_ROTOR_MAX_CRIT), for the same purpose. */
int autobal_rotor_resonance_speeds_cap_(const autobal_rotor_params *p, double lo, double hi,
                                        size_t n_grid, double xtol_rel, size_t cap,
                                        autobal_rotor_resonances *out, autobal_error *err);

#endif
