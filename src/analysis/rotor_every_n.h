/* rotor_every_n.h: the range of q = |sum_k e^{2 i psi_k}|^2 over every member of n >= 4 identical
 * balls with |sum_k e^{i psi_k}| = t in [ta, tb] (units of m r), for the every-unbalance analysis
 * with unbalance_member = every (rotor_unbalance.c; docs/rotor.md "Four or more balls, every
 * member").  Not installed; includes no other private header.
 *
 * Outer bounds (certified up to a stated rounding allowance): a branch-and-bound over the ball
 * angles (psi_1 = 0 by rotation; the others ordered and psi_2 the smallest gap, by the balls'
 * permutations), boxes bounded by the natural interval form over pairwise angle differences
 * intersected with the mean-value form (interval gradients), boxes certainly outside
 * t in [ta, tb] dropped.  Inner bounds: members actually found (box centres moved onto the
 * constraint and improved by a local search), each with its q recomputed from its angles. */
#ifndef AUTOBAL_ROTOR_EVERY_N_H
#define AUTOBAL_ROTOR_EVERY_N_H

#include <stddef.h>

/* Largest number of balls supported (the search time grows fast with n: docs/rotor.md). */
#define AUTOBAL_EVERYN_MAX 10
/* Members kept to start the search for a member of a given q (bins over [0, n^2]). */
#define AUTOBAL_EVERYN_POOL 128

typedef struct autobal_everyn_member_ {
  double t;                        /* |S| (units of m r), S = sum e^{i phi} real positive */
  double q;                        /* |sum e^{2 i phi}|^2, recomputed from phi */
  double phi[AUTOBAL_EVERYN_MAX];  /* rad, the ball angles from S */
} autobal_everyn_member_;

typedef struct autobal_everyn_ {
  size_t n;
  double ta, tb;
  double q_lo, q_hi;       /* outer: every member has q in [q_lo, q_hi] */
  double q_lo_in, q_hi_in; /* inner: q of the members mlo, mhi found (every q between is met: the
                              members of [ta, tb] form a connected set, docs/rotor.md) */
  autobal_everyn_member_ mlo, mhi;
  size_t n_pool;
  autobal_everyn_member_ pool[AUTOBAL_EVERYN_POOL];
  long boxes;              /* boxes evaluated (both searches) */
  int complete;            /* 1: both searches closed to the tolerance within the budget */
} autobal_everyn_;

/* q of n angles (no constraint). */
double autobal_everyn_q_(size_t n, const double *phi);

/* The symmetric fan of t (0 < t < n): phi_k = (k - (n-1)/2) d, m->t its |S| recomputed. */
void autobal_everyn_fan_(size_t n, double t, autobal_everyn_member_ *m);

/* The enclosure for 4 <= n <= AUTOBAL_EVERYN_MAX, 0 < ta <= tb < n: each search (max, min) stops
 * when its outer bound is within tol (absolute, in q) of its inner bound or after max_boxes boxes
 * (then complete = 0 and the bounds are still valid, wider).  Returns 0, or -1 (no memory; bad
 * arguments). */
int autobal_everyn_range_(autobal_everyn_ *e, size_t n, double ta, double tb, long max_boxes, double tol);

/* A member of [ta, tb] whose q is as close to q_target as found (Newton steps along the members
 * from the pool's members nearest in q).  Returns 0 when |q - q_target| <= tol, 1 otherwise (out is
 * the closest found). */
int autobal_everyn_member_at_(const autobal_everyn_ *e, double q_target, double tol, autobal_everyn_member_ *out);

#endif
