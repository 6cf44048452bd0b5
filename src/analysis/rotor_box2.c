/* rotor_box2.c: does Delta16 (two planes, docs/rotor.md "Every unbalance", "Two planes") have a root
 * on the imaginary axis anywhere in the region x = |Q1|^2 in X, y = |Q2|^2 in Y, t = |Q1||Q2| cos(phase)
 * with t^2 <= x y?  A certified branch-and-bound over (z, y), z = w^2:
 *
 * With Delta16 = A0 + x A1 + t A2 (A0 = D0 + y M22, A1 = M11 + y T12, A2 = U0) and p(i w) = pe(z) +
 * i w po(z), a root lambda = i w (w > 0) at (x, t) solves the two real linear equations
 * A0e + x A1e + t A2e = 0, A0o + x A1o + t A2o = 0: x = N / d, t = T / d with
 *     d = A1e A2o - A2e A1o,  N = A2e A0o - A0e A2o,  T = A0e A1o - A1e A0o
 * polynomials in (z, y) (y-degree 1, 1, 2).  The point (z, y) belongs to the set S iff d != 0 and
 *     sign(N - x_lo d) and sign(x_hi d - N) are 0 or sign(d)   (x in X)
 *     G = y N d - T^2 >= 0                                      (t^2 <= x y, times d^2)
 * and "some root on the axis" is "S meets (0, inf) x Y" (or the root lambda = 0, below).  The search
 * covers z in [0, w2] (z = w2 zeta) and [w2, inf] (z = w2 / u, the polynomials reversed: same signs)
 * times Y, by boxes: a box is dropped when the bounds of d, N - x_lo d, x_hi d - N, G on it show
 * two signs that must agree certainly disagree, or G < 0 throughout, or when the even or the odd
 * equation itself, a0 + F (x a1 + t a2) = 0, has no solution with x in X, |t| <= sqrt(x_hi y) (the
 * direct test: it decides the points where d = N = T = 0, the three pieces' even/odd vectors
 * parallel, around which x = N / d and t = T / d take every value and no sign test can drop a box);
 * a box whose centre satisfies all strictly (bounds, not just values) is a point of S (the answer 1);
 * else it is halved across the side its bounds' radii come from (z alone against y).
 *
 * The bounds: the polynomial is shifted to the box's centre (Taylor shift in long double) and bounded
 * by |value| + sum |coefficient| radius^(i, j), widened by a rounding allowance
 * K eps sum |c_ij| z1^i y1^j (K = 8 (degrees) + 32, eps of long double) that covers the a-priori
 * error bound of the shift (gamma_(2 n) times that majorant, the coordinates being >= 0).  So a
 * dropped box is certain for the polynomials as given (their coefficients, computed from the model in
 * long double, are taken as exact); this is not a directed-rounding proof of the model itself.
 *
 * lambda = 0 (w = 0, one real equation): Delta16(0) = a + x m + y n + x y T + t U over the connected
 * region takes every value between min h- and max h+, h-+(u, v) = a + u^2 m + v^2 n + u^2 v^2 T
 * -+ |U| u v (u = sqrt x, v = sqrt y): no root iff h- > 0 everywhere or h+ < 0 everywhere (proved by
 * the same boxes), a root iff points with h- < 0 and with h+ > 0 are found.
 *
 * Model-agnostic numerics on the given polynomials; includes nothing of the project. */
#include "analysis/rotor_box2.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define BZ 33 /* z coefficients (G: degree 30; 32 with the parts given full, in->full) */
#define BY 5  /* y coefficients (G: degree 4) */
#define STACK 512

typedef struct bp {
  int nz, ny;
  long double c[BZ][BY]; /* c[i][j] z^i y^j */
} bp;

/* Bounds of p over [z0, z1] x [y0, y1], 0 <= z0 <= z1, 0 <= y0 <= y1. */
/* hint (may be NULL): the split hint of a box, the parts of the radius from z alone (hint[0]) and from
 * y (hint[1]), added relative to the radius. */
static void bp_bound_h(const bp *p, long double z0, long double z1, long double y0, long double y1, long double *lo,
                       long double *hi, long double *hint) {
  long double a[BZ][BY], R = 0.0L, M = 0.0L, err, v, Rz = 0.0L, rzi = 1.0L;
  const long double zc = 0.5L * (z0 + z1), rz = 0.5L * (z1 - z0), yc = 0.5L * (y0 + y1), ry = 0.5L * (y1 - y0);
  int i, j, k;
  const int nz = p->nz, ny = p->ny;
  for (i = 0; i < nz; i++)
    for (j = 0; j < ny; j++) a[i][j] = p->c[i][j];
  if (zc != 0.0L)
    for (j = 0; j < ny; j++)
      for (k = 0; k < nz - 1; k++)
        for (i = nz - 2; i >= k; i--) a[i][j] += zc * a[i + 1][j];
  if (yc != 0.0L)
    for (i = 0; i < nz; i++)
      for (k = 0; k < ny - 1; k++)
        for (j = ny - 2; j >= k; j--) a[i][j] += yc * a[i][j + 1];
  /* R = sum_{(i,j) != 0} |a_ij| rz^i ry^j, M = sum |c_ij| z1^i y1^j (Horner, all terms >= 0) */
  for (i = nz - 1; i >= 0; i--) {
    long double rr = 0.0L, mm = 0.0L;
    for (j = ny - 1; j >= 0; j--) {
      rr = rr * ry + ((i == 0 && j == 0) ? 0.0L : fabsl(a[i][j]));
      mm = mm * y1 + fabsl(p->c[i][j]);
    }
    R = R * rz + rr;
    M = M * z1 + mm;
  }
  for (i = 1; i < nz; i++) {
    rzi *= rz;
    Rz += fabsl(a[i][0]) * rzi;
  }
  if (hint != NULL && R > 0.0L) {
    hint[0] += Rz / R;
    hint[1] += (R - Rz) / R;
  }
  v = a[0][0];
  err = (long double)(8 * (nz + ny) + 32) * LDBL_EPSILON * M;
  R *= 1.0L + (long double)(4 * (nz + ny)) * LDBL_EPSILON;
  *lo = v - R - err;
  *hi = v + R + err;
}

static void bp_bound(const bp *p, long double z0, long double z1, long double y0, long double y1, long double *lo,
                     long double *hi) {
  bp_bound_h(p, z0, z1, y0, y1, lo, hi, NULL);
}

/* -1, 1: the certain sign on the box; 0: unknown */
static int sgn_of(long double lo, long double hi) { return lo > 0.0L ? 1 : hi < 0.0L ? -1 : 0; }

static long double bp_eval(const bp *p, long double z, long double y) {
  long double v = 0.0L;
  int i, j;
  for (i = p->nz - 1; i >= 0; i--) {
    long double r = 0.0L;
    for (j = p->ny - 1; j >= 0; j--) r = r * y + p->c[i][j];
    v = v * z + r;
  }
  return v;
}

static void bp_mul(const bp *a, const bp *b, bp *o) {
  bp r;
  int i, j, k, l;
  memset(&r, 0, sizeof r);
  r.nz = a->nz + b->nz - 1;
  r.ny = a->ny + b->ny - 1;
  for (i = 0; i < a->nz; i++)
    for (j = 0; j < a->ny; j++)
      for (k = 0; k < b->nz; k++)
        for (l = 0; l < b->ny; l++) r.c[i + k][j + l] += a->c[i][j] * b->c[k][l];
  *o = r;
}

/* o = x a + y b (sizes: the larger) */
static void bp_axpy(long double x, const bp *a, long double y, const bp *b, bp *o) {
  bp r;
  int i, j;
  memset(&r, 0, sizeof r);
  r.nz = a->nz > b->nz ? a->nz : b->nz;
  r.ny = a->ny > b->ny ? a->ny : b->ny;
  for (i = 0; i < r.nz; i++)
    for (j = 0; j < r.ny; j++)
      r.c[i][j] = (i < a->nz && j < a->ny ? x * a->c[i][j] : 0.0L) + (i < b->nz && j < b->ny ? y * b->c[i][j] : 0.0L);
  *o = r;
}

/* z -> zs z, y -> ys y, then divided by the largest |coefficient| (a positive factor: signs kept) */
static void bp_scale(bp *p, long double zs, long double ys) {
  long double zi = 1.0L, big = 0.0L;
  int i, j;
  for (i = 0; i < p->nz; i++, zi *= zs) {
    long double yj = 1.0L;
    for (j = 0; j < p->ny; j++, yj *= ys) {
      p->c[i][j] *= zi * yj;
      big = fmaxl(big, fabsl(p->c[i][j]));
    }
  }
  if (big > 0.0L)
    for (i = 0; i < p->nz; i++)
      for (j = 0; j < p->ny; j++) p->c[i][j] /= big;
}

/* bp_scale for n polynomials with one common positive factor (their ratios kept) */
static void scale_common(bp *p, int n, long double zs, long double ys) {
  long double big = 0.0L;
  int i, j, k;
  for (k = 0; k < n; k++) {
    long double zi = 1.0L;
    for (i = 0; i < p[k].nz; i++, zi *= zs) {
      long double yj = 1.0L;
      for (j = 0; j < p[k].ny; j++, yj *= ys) {
        p[k].c[i][j] *= zi * yj;
        big = fmaxl(big, fabsl(p[k].c[i][j]));
      }
    }
  }
  if (big > 0.0L)
    for (k = 0; k < n; k++)
      for (i = 0; i < p[k].nz; i++)
        for (j = 0; j < p[k].ny; j++) p[k].c[i][j] /= big;
}

/* u^(nz-1) p(1/u): the same sign for u > 0 */
static void bp_reverse(const bp *p, bp *o) {
  int i, j;
  *o = *p;
  for (i = 0; i < p->nz; i++)
    for (j = 0; j < p->ny; j++) o->c[i][j] = p->c[p->nz - 1 - i][j];
}

/* p(i w) = pe(z) + i w po(z) */

typedef struct box {
  long double z0, z1, y0, y1;
} box;

/* The four polynomials of one side (z <= w2, or z >= w2 reversed), and the parts of the two real
 * equations themselves: e[0] + x e[1] + t e[2] (the even one), o[0] + x o[1] + t o[2] (the odd one),
 * each triple with one common length in z and one common positive factor (so comparable). */
typedef struct side {
  bp d, p1, p2, g;
  bp e[3], o[3];
  long double x_lo, x_hi, tq; /* x in [x_lo, x_hi], |t| <= tq sqrt(eta) (eta = y / y_hi) */
} side;

/* The interval of a + x b + t c over x in [x0, x1], |t| <= tm (a, b, c intervals) excludes 0 for
 * certain: the equation has no solution (x, t) in that rectangle (which holds the region t^2 <= x y).
 * The few products and sums are rounded: a relative slack of 16 eps on the sum of magnitudes. */
static int no_solution(const long double a[2], const long double b[2], const long double c[2], long double x0,
                       long double x1, long double tm) {
  const long double p0 = x0 * b[0], p1 = x0 * b[1], p2 = x1 * b[0], p3 = x1 * b[1];
  const long double blo = fminl(fminl(p0, p1), fminl(p2, p3)), bhi = fmaxl(fmaxl(p0, p1), fmaxl(p2, p3));
  const long double cm = tm * fmaxl(fabsl(c[0]), fabsl(c[1]));
  const long double lo = a[0] + blo - cm, hi = a[1] + bhi + cm;
  const long double slack =
      16.0L * LDBL_EPSILON * (fmaxl(fabsl(a[0]), fabsl(a[1])) + fmaxl(fabsl(blo), fabsl(bhi)) + cm);
  return lo > slack || hi < -slack;
}

/* 1: on the box neither the even nor the odd equation has a solution in the region */
static int direct_excluded(const side *S, const box *b, long double *hint) {
  long double e[3][2], t;
  int k, q;
  t = S->tq * sqrtl(b->y1);
  for (q = 0; q < 2; q++) {
    const bp *P = q ? S->o : S->e;
    for (k = 0; k < 3; k++) bp_bound_h(&P[k], b->z0, b->z1, b->y0, b->y1, &e[k][0], &e[k][1], hint);
    if (no_solution(e[0], e[1], e[2], S->x_lo, S->x_hi, t)) return 1;
  }
  return 0;
}

/* 1: box excluded; 2: its centre is a point of S; 0: neither (then hint says which side of the box
 * to split: hint[0] >= hint[1] its z side, where the bounds' radii come mostly from z) */
static int classify(const side *S, const box *b, long double *hint) {
  long double l[4], h[4];
  int sd, s1, s2;
  hint[0] = hint[1] = 0.0L;
  /* the cheap ones first (G has twice their degree) */
  bp_bound_h(&S->d, b->z0, b->z1, b->y0, b->y1, &l[0], &h[0], hint);
  bp_bound_h(&S->p1, b->z0, b->z1, b->y0, b->y1, &l[1], &h[1], hint);
  sd = sgn_of(l[0], h[0]);
  s1 = sgn_of(l[1], h[1]);
  if (sd && s1 && s1 != sd) return 1;
  bp_bound_h(&S->p2, b->z0, b->z1, b->y0, b->y1, &l[2], &h[2], hint);
  s2 = sgn_of(l[2], h[2]);
  if ((sd && s2 && s2 != sd) || (s1 && s2 && s1 != s2)) return 1;
  if (direct_excluded(S, b, hint)) return 1;
  bp_bound_h(&S->g, b->z0, b->z1, b->y0, b->y1, &l[3], &h[3], hint);
  if (h[3] < 0.0L) return 1;
  {
    const long double zc = 0.5L * (b->z0 + b->z1), yc = 0.5L * (b->y0 + b->y1);
    bp_bound(&S->g, zc, zc, yc, yc, &l[3], &h[3]);
    bp_bound(&S->d, zc, zc, yc, yc, &l[0], &h[0]);
    bp_bound(&S->p1, zc, zc, yc, yc, &l[1], &h[1]);
    bp_bound(&S->p2, zc, zc, yc, yc, &l[2], &h[2]);
    sd = sgn_of(l[0], h[0]);
    if (zc > 0.0L && l[3] > 0.0L && sd != 0 && sgn_of(l[1], h[1]) == sd && sgn_of(l[2], h[2]) == sd) return 2;
  }
  return 0;
}

/* Split box b across its wider side (wz, wy: its widths, each relative to its axis's range) and push
 * the two halves (the lower one on top).  -1 when the stack is full or b is too small to resolve
 * (both relative widths below 1e-15): the caller is then undecided. */
static int push_halves(box *st, size_t *n, const box *b, long double wz, long double wy, int hint_z) {
  box a1 = *b, a2 = *b;
  if (*n + 2 > STACK) return -1;
  if (wz < 1e-15L && wy < 1e-15L) return -1;
  if (hint_z >= 0 ? (wy < 1e-15L || (hint_z && wz >= 1e-15L)) : wz >= wy) {
    const long double m = 0.5L * (b->z0 + b->z1);
    a1.z1 = m;
    a2.z0 = m;
  } else {
    const long double m = 0.5L * (b->y0 + b->y1);
    a1.y1 = m;
    a2.y0 = m;
  }
  st[(*n)++] = a2;
  st[(*n)++] = a1;
  return 0;
}

/* The search over [0, 1] x [y_rel, 1] of one side: 0 empty, 1 found (*at), -1 undecided. */
static int search(const side *S, long double y_rel, size_t max_boxes, size_t *boxes, box *at) {
  box st[STACK];
  size_t n = 0;
  const long double yw = 1.0L - y_rel;
  long double hint[2];
  st[n].z0 = 0.0L;
  st[n].z1 = 1.0L;
  st[n].y0 = y_rel;
  st[n].y1 = 1.0L;
  n++;
  while (n > 0) {
    const box b = st[--n];
    int c;
    if (++*boxes > max_boxes) return -1;
    c = classify(S, &b, hint);
    if (c == 1) continue;
    if (c == 2) {
      *at = b;
      return 1;
    }
    if (push_halves(st, &n, &b, b.z1 - b.z0, yw > 0.0L ? (b.y1 - b.y0) / yw : 0.0L, hint[0] >= hint[1])) return -1;
  }
  return 0;
}

/* Positivity over [u0, 1] x [v0, 1]: 1 p > 0 proved, 0 a point with p < 0 found, -1 undecided. */
static int positive(const bp *p, long double u0, long double v0, size_t max_boxes, size_t *boxes) {
  box st[STACK];
  size_t n = 0;
  const long double uw = 1.0L - u0, vw = 1.0L - v0;
  st[n].z0 = u0;
  st[n].z1 = 1.0L;
  st[n].y0 = v0;
  st[n].y1 = 1.0L;
  n++;
  while (n > 0) {
    const box b = st[--n];
    long double lo, hi;
    if (++*boxes > max_boxes) return -1;
    bp_bound(p, b.z0, b.z1, b.y0, b.y1, &lo, &hi);
    if (lo > 0.0L) continue;
    {
      const long double uc = 0.5L * (b.z0 + b.z1), vc = 0.5L * (b.y0 + b.y1);
      bp_bound(p, uc, uc, vc, vc, &lo, &hi);
      if (hi < 0.0L) return 0;
    }
    if (push_halves(st, &n, &b, uw > 0.0L ? (b.z1 - b.z0) / uw : 0.0L, vw > 0.0L ? (b.y1 - b.y0) / vw : 0.0L, -1))
      return -1;
  }
  return 1;
}

/* lambda = 0: 0 no root, 1 a root, -1 undecided */
static int at_zero(const autobal_rotor_box2_in *in, size_t max_boxes, size_t *boxes) {
  const long double xh = in->x_hi, yh = in->y_hi, s = sqrtl(xh * yh);
  const long double u0 = xh > 0.0L ? sqrtl(fmaxl(0.0L, in->x_lo) / xh) : 1.0L, v0 = sqrtl(fmaxl(0.0L, in->y_lo) / yh);
  bp hm, hp;
  int rm, rp;
  const long double F0 = in->full ? 1.0L : in->w2 * in->w2 * in->w2 * in->w2; /* F(0) */
  memset(&hm, 0, sizeof hm);
  hm.nz = hm.ny = 3;
  hm.c[0][0] = in->D0[0];
  hm.c[2][0] = F0 * in->M11[0] * xh;
  hm.c[0][2] = F0 * in->M22[0] * yh;
  hm.c[2][2] = F0 * F0 * in->T12[0] * xh * yh;
  hm.c[1][1] = -F0 * fabsl(in->U0[0]) * s;
  bp_scale(&hm, 1.0L, 1.0L);
  hp = hm;
  hp.c[1][1] = -hp.c[1][1];
  rm = positive(&hm, u0, v0, max_boxes, boxes); /* h- > 0 everywhere: no root */
  if (rm == 1) return 0;
  {
    bp nhp = hp;
    int i, j;
    for (i = 0; i < 3; i++)
      for (j = 0; j < 3; j++) nhp.c[i][j] = -hp.c[i][j];
    rp = positive(&nhp, u0, v0, max_boxes, boxes); /* -h+ > 0 everywhere: no root */
  }
  if (rp == 1) return 0;
  if (rm == 0 && rp == 0) return 1;
  return -1;
}

/* drop trailing rows / columns that are exactly zero */
static void bp_trim(bp *p) {
  int j;
  for (;;) {
    int zero = 1;
    if (p->nz <= 1) break;
    for (j = 0; j < p->ny; j++)
      if (p->c[p->nz - 1][j] != 0.0L) zero = 0;
    if (!zero) break;
    p->nz--;
  }
  for (;;) {
    int zero = 1, i;
    if (p->ny <= 1) break;
    for (i = 0; i < p->nz; i++)
      if (p->c[i][p->ny - 1] != 0.0L) zero = 0;
    if (!zero) break;
    p->ny--;
  }
}

/* the even (e = 1) or odd part of the ascending p (17) as a polynomial in z, in column col of o */
static void part_col(const long double *p, int e, bp *o, int col) {
  int j;
  for (j = 0; j < 9; j++) {
    const int k = 2 * j + (e ? 0 : 1);
    o->c[j][col] = k < 17 ? ((j % 2) ? -1.0L : 1.0L) * p[k] : 0.0L;
  }
}

int autobal_rotor_box2_(const autobal_rotor_box2_in *in, autobal_rotor_box2_out *out) {
  bp d, N, T, t1, t2, f, yb, a0[2], a1[2], a2[2], D0x, m22x, m11x, t12x;
  side S[2];
  size_t max_boxes;
  int r0, k, big = 0;
  memset(out, 0, sizeof *out);
  out->verdict = -1;
  if (!(in->w2 > 0.0L && in->y_hi > 0.0L && in->y_lo >= 0.0L && in->y_lo <= in->y_hi && in->x_lo >= 0.0L &&
        in->x_lo <= in->x_hi && isfinite(in->w2) && isfinite(in->y_hi) && isfinite(in->x_hi)))
    return -1;
  max_boxes = in->max_boxes ? in->max_boxes : 200000;
  r0 = at_zero(in, max_boxes, &out->boxes);
  if (r0 == 1) {
    out->verdict = 1;
    out->at_zero = 1;
    return 0;
  }
  /* F(i w) = (w2 - z)^4 */
  memset(&f, 0, sizeof f);
  f.nz = 5;
  f.ny = 1;
  f.c[0][0] = in->w2 * in->w2 * in->w2 * in->w2;
  f.c[1][0] = -4.0L * in->w2 * in->w2 * in->w2;
  f.c[2][0] = 6.0L * in->w2 * in->w2;
  f.c[3][0] = -4.0L * in->w2;
  f.c[4][0] = 1.0L;
  if (in->full) { /* the parts carry F already */
    memset(&f, 0, sizeof f);
    f.nz = f.ny = 1;
    f.c[0][0] = 1.0L;
  }
  memset(&yb, 0, sizeof yb);
  yb.nz = 1;
  yb.ny = 2;
  yb.c[0][1] = 1.0L;
  /* a0 = D0 + y F M22, a1 = M11 + y F T12, a2 = U0 (e, o): Delta16 = a0 + F (x a1 + t a2) */
  for (k = 0; k < 2; k++) {
    memset(&D0x, 0, sizeof D0x);
    D0x.nz = 9;
    D0x.ny = 1;
    m22x = m11x = t12x = a2[k] = D0x;
    part_col(in->D0, k == 0, &D0x, 0);
    part_col(in->M22, k == 0, &m22x, 0);
    part_col(in->M11, k == 0, &m11x, 0);
    part_col(in->T12, k == 0, &t12x, 0);
    part_col(in->U0, k == 0, &a2[k], 0);
    bp_trim(&D0x);
    bp_trim(&m22x);
    bp_trim(&m11x);
    bp_trim(&t12x);
    bp_trim(&a2[k]);
    bp_mul(&f, &m22x, &t1);
    bp_mul(&yb, &t1, &t2);
    bp_axpy(1.0L, &D0x, 1.0L, &t2, &a0[k]);
    bp_mul(&f, &t12x, &t1);
    bp_mul(&yb, &t1, &t2);
    bp_axpy(1.0L, &m11x, 1.0L, &t2, &a1[k]);
    bp_trim(&a0[k]);
    bp_trim(&a1[k]);
  }
  /* x = N / d, t = T / d: d = F (a1e a2o - a2e a1o), N = a2e A0o - A0e a2o, T = A0e a1o - a1e A0o */
  bp_mul(&a1[0], &a2[1], &t1);
  bp_mul(&a2[0], &a1[1], &t2);
  bp_axpy(1.0L, &t1, -1.0L, &t2, &t1);
  bp_trim(&t1);
  bp_mul(&f, &t1, &d);
  bp_mul(&a2[0], &a0[1], &t1);
  bp_mul(&a0[0], &a2[1], &t2);
  bp_axpy(1.0L, &t1, -1.0L, &t2, &N);
  bp_mul(&a0[0], &a1[1], &t1);
  bp_mul(&a1[0], &a0[1], &t2);
  bp_axpy(1.0L, &t1, -1.0L, &t2, &T);
  bp_trim(&d);
  bp_trim(&N);
  bp_trim(&T);
  /* a common length in z for d, N - x_lo d, x_hi d - N (their reversals must share the power) */
  {
    int nz = d.nz > N.nz ? d.nz : N.nz;
    if (2 * nz - 1 > BZ || 2 * T.nz - 1 > BZ || d.ny + N.ny > BY || 2 * T.ny - 1 > BY) big = 1;
    if (big) return 0; /* undecided: larger than the search is built for */
    d.nz = N.nz = nz;
  }
  bp_axpy(1.0L, &N, -in->x_lo, &d, &S[0].p1);
  bp_axpy(in->x_hi, &d, -1.0L, &N, &S[0].p2);
  S[0].d = d;
  {
    bp yN;
    bp_mul(&yb, &N, &yN);
    bp_mul(&yN, &d, &t1);
    bp_mul(&T, &T, &t2);
    bp_axpy(1.0L, &t1, -1.0L, &t2, &S[0].g);
  }
  bp_scale(&S[0].d, in->w2, in->y_hi);
  bp_scale(&S[0].p1, in->w2, in->y_hi);
  bp_scale(&S[0].p2, in->w2, in->y_hi);
  bp_scale(&S[0].g, in->w2, in->y_hi);
  /* the two equations' parts: a0 + F (x a1 + t a2), even (k = 0) and odd */
  for (k = 0; k < 2; k++) {
    bp *P = k ? S[0].o : S[0].e, *Q = k ? S[1].o : S[1].e;
    int j, nzm = 0;
    P[0] = a0[k];
    bp_mul(&f, &a1[k], &P[1]);
    bp_mul(&f, &a2[k], &P[2]);
    for (j = 0; j < 3; j++) {
      bp_trim(&P[j]);
      if (P[j].nz > nzm) nzm = P[j].nz;
    }
    for (j = 0; j < 3; j++) P[j].nz = nzm; /* one length: the reversals share the power */
    scale_common(P, 3, in->w2, in->y_hi);
    for (j = 0; j < 3; j++) bp_reverse(&P[j], &Q[j]);
  }
  for (k = 0; k < 2; k++) {
    S[k].x_lo = in->x_lo;
    S[k].x_hi = in->x_hi;
    S[k].tq = sqrtl(in->x_hi * in->y_hi);
  }
  bp_reverse(&S[0].d, &S[1].d);
  bp_reverse(&S[0].p1, &S[1].p1);
  bp_reverse(&S[0].p2, &S[1].p2);
  bp_reverse(&S[0].g, &S[1].g);
  {
    int undecided = r0 == -1;
    for (k = 0; k < 2; k++) {
      box at;
      const int r = search(&S[k], in->y_lo / in->y_hi, max_boxes, &out->boxes, &at);
      if (r == 1) {
        const long double zeta = 0.5L * (at.z0 + at.z1), eta = 0.5L * (at.y0 + at.y1);
        const long double z = k == 0 ? in->w2 * zeta : in->w2 / zeta, y = in->y_hi * eta;
        const long double dv = bp_eval(&d, z, y);
        out->verdict = 1;
        out->z = z;
        out->y = y;
        out->x = bp_eval(&N, z, y) / dv;
        out->t = bp_eval(&T, z, y) / dv;
        return 0;
      }
      if (r == -1) undecided = 1;
    }
    out->verdict = undecided ? -1 : 0;
  }
  return 0;
}
