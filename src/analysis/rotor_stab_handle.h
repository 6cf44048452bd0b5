/* rotor_stab_handle.h: private layout of the rotor stability handle and the internal
 * functions of rotor_stab_handle.c (not installed).  Included by rotor_stab_handle.c,
 * rotor_floquet.c and rotor_stability.c; includes rotor_closed.h only. */
#ifndef AUTOBAL_ROTOR_STAB_HANDLE_H
#define AUTOBAL_ROTOR_STAB_HANDLE_H

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_permutation.h>

#include "analysis/rotor_closed.h"
#include "autobal/rotor_stability.h"
#include "autobal/stability.h"
#include "autobal/transient.h"

/* Largest number of balls for which the full linearization and Floquet analysis
 * workspaces are allocated ((8 + 2N)^2 ODE states). */
#define AUTOBAL_ROTOR_STAB_MAX_FULL_BALLS 64

struct autobal_rotor_stab {
  autobal_rotor_params cur;        /* working parameters; ball arrays point into m, r, h, psi0i, rate0 */
  autobal_rotor_lumped Lbase;      /* lumped coefficients before the scale factors (at alloc, or
                                      after a hardware, lumped, ANISOTROPY or C_OVER_A change) */
  int input0;                      /* the input kind given at alloc (AUTOBAL_ROTOR_HARDWARE or
                                      _LUMPED): which of the keys are parameters */
  autobal_rotor_lumped L;          /* current lumped coefficients */
  double c_scale, h_scale;         /* current STIFFNESS_SCALE, DAMPING_SCALE */
  autobal_rotor_stab_options opt;  /* member angle pointers into member_store */
  size_t n_planes, N, off[AUTOBAL_ROTOR_MAX_PLANES], cnt[AUTOBAL_ROTOR_MAX_PLANES];
  size_t ns;                       /* 8 + 2N, full linearization dimension */
  size_t nm;                       /* 4 + N, second-order dimension */
  double *store;                   /* one block for every array below */
  double *m, *r, *h, *psi_init, *rate_init; /* N each, current ball data */
  double *member_store;            /* member angles (sum n_j) */
  double *m_save, *h_save, *r_save; /* N each: ball masses / dampings / track radii saved by a
                                      sweep or a critical search (stab_save / stab_restore) */
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
  autobal_rotor_stab_cancel_fn cancel; /* autobal_rotor_stab_set_cancel (NULL: none) */
  void *cancel_user;
  struct autobal_everyn_ *everyn;  /* the every-unbalance enclosure of n >= 4 balls, kept for the last
                                      (n, t range) analysed (rotor_unbalance.c); NULL before */
};

/* Non-zero (message "cancelled by the caller" on the handle, status AUTOBAL_ECANCELLED) when
 * the cancel hook of autobal_rotor_stab_set_cancel asks to stop. */
int autobal_rotor_stab_cancelled_(autobal_rotor_stab *s);
/* Balanced angles of the current member into s->psi (status also in s->psi_status). */
int autobal_rotor_stab_update_member_(autobal_rotor_stab *s);
/* Family dimension (sum over planes of n_j - rank_j) at the current member (psi valid). */
size_t autobal_rotor_stab_family_(const autobal_rotor_stab *s);
/* Fill the closed system from the handle's current data and member angles (psi valid). */
void autobal_rotor_stab_closed_from_handle_(const autobal_rotor_stab *s, autobal_rotor_closed *c);

#endif
