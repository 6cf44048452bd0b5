/* rotor_every_n.c: the range of q over every member of n >= 4 identical balls (rotor_every_n.h). */
#include "analysis/rotor_every_n.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define NV (AUTOBAL_EVERYN_MAX - 1) /* box variables: psi_2 .. psi_n */
#define TWO_PI (2.0 * M_PI)

double autobal_everyn_q_(size_t n, const double *phi) {
  double re = 0.0, im = 0.0;
  size_t k;
  for (k = 0; k < n; k++) re += cos(2.0 * phi[k]), im += sin(2.0 * phi[k]);
  return re * re + im * im;
}

/* ---- interval ranges of cos and sin (exact range of the function on [a, b], widened outward) ---- */

static void cos_range(double a, double b, double *lo, double *hi) {
  double ca, cb, k;
  if (b - a >= TWO_PI) {
    *lo = -1.0, *hi = 1.0;
    return;
  }
  ca = cos(a), cb = cos(b);
  *lo = fmin(ca, cb) - 1e-15;
  *hi = fmax(ca, cb) + 1e-15;
  /* a maximum 2 pi k or a minimum pi + 2 pi k inside (decided generously) */
  k = ceil((a - 1e-12) / TWO_PI);
  if (TWO_PI * k <= b + 1e-12) *hi = 1.0;
  k = ceil((a - M_PI - 1e-12) / TWO_PI);
  if (M_PI + TWO_PI * k <= b + 1e-12) *lo = -1.0;
  if (*lo < -1.0) *lo = -1.0;
  if (*hi > 1.0) *hi = 1.0;
}

static void sin_range(double a, double b, double *lo, double *hi) { cos_range(a - 0.5 * M_PI, b - 0.5 * M_PI, lo, hi); }

/* ---- box bounds ---- */

typedef struct box {
  double key; /* the bound searched on (max: upper bound of q; min: minus the lower bound) */
  double lo[NV], hi[NV];
} box;

/* Whether a box can hold an ordered configuration with psi_2 the smallest gap: psi_1 = 0 <= psi_2 <=
 * ... <= psi_n <= 2 pi, psi_2 - psi_1 <= every other gap (the cyclic one 2 pi - psi_n included).
 * Every configuration is one of these after a rotation and a renumbering of the balls. */
static int box_valid(size_t n, const double *lo, const double *hi) {
  size_t k;
  const size_t nv = n - 1;
  for (k = 0; k + 1 < nv; k++) {
    if (lo[k] > hi[k + 1]) return 0;
    if (lo[0] > hi[k + 1] - lo[k]) return 0;
  }
  if (lo[0] > TWO_PI - lo[nv - 1]) return 0;
  return 1;
}

/* Enclosures of f = |S|^2 and q over the box: the natural interval form over the pairwise
 * differences (f = n + 2 sum_{j<k} cos(psi_k - psi_j), q the same with 2 (psi_k - psi_j))
 * intersected with the mean-value form at the centre (interval gradients df/dpsi_k =
 * -2 sum_j sin(psi_k - psi_j), dq/dpsi_k = -4 sum_j sin(2 (psi_k - psi_j))), widened by a rounding
 * allowance of 1e-12 n^2. */
static void box_bounds(size_t n, const double *lo, const double *hi, double fa, double fb, double fr[2], double qr[2],
                       double *psic) {
  double L[AUTOBAL_EVERYN_MAX], H[AUTOBAL_EVERYN_MAX], W[AUTOBAL_EVERYN_MAX];
  double gfl[AUTOBAL_EVERYN_MAX], gfh[AUTOBAL_EVERYN_MAX], gql[AUTOBAL_EVERYN_MAX], gqh[AUTOBAL_EVERYN_MAX];
  double fl = (double)n, fh = (double)n, ql = (double)n, qh = (double)n, sr = 0.0, si = 0.0, qre = 0.0, qim = 0.0;
  double rf = 0.0, rq = 0.0, fc, qc, gfc[AUTOBAL_EVERYN_MAX], gqc[AUTOBAL_EVERYN_MAX], lam, sff = 0.0, sfq = 0.0;
  const double pad = 1e-12 * (double)(n * n);
  size_t j, k;
  L[0] = H[0] = W[0] = psic[0] = 0.0;
  for (k = 1; k < n; k++) {
    L[k] = lo[k - 1], H[k] = hi[k - 1];
    psic[k] = 0.5 * (L[k] + H[k]);
    W[k] = 0.5 * (H[k] - L[k]);
  }
  for (k = 0; k < n; k++) gfl[k] = gfh[k] = gql[k] = gqh[k] = gfc[k] = gqc[k] = 0.0;
  for (k = 1; k < n; k++)
    for (j = 0; j < k; j++) {
      const double dlo = L[k] - H[j], dhi = H[k] - L[j];
      double cl, ch, sl, sh;
      cos_range(dlo, dhi, &cl, &ch);
      fl += 2.0 * cl, fh += 2.0 * ch;
      sin_range(dlo, dhi, &sl, &sh);
      gfl[k] += -2.0 * sh, gfh[k] += -2.0 * sl;
      gfl[j] += 2.0 * sl, gfh[j] += 2.0 * sh;
      cos_range(2.0 * dlo, 2.0 * dhi, &cl, &ch);
      ql += 2.0 * cl, qh += 2.0 * ch;
      sin_range(2.0 * dlo, 2.0 * dhi, &sl, &sh);
      gql[k] += -4.0 * sh, gqh[k] += -4.0 * sl;
      gql[j] += 4.0 * sl, gqh[j] += 4.0 * sh;
      {
        const double d = psic[k] - psic[j], s1 = sin(d), s2 = sin(2.0 * d);
        gfc[k] -= 2.0 * s1, gfc[j] += 2.0 * s1;
        gqc[k] -= 4.0 * s2, gqc[j] += 4.0 * s2;
      }
    }
  for (k = 0; k < n; k++) {
    sr += cos(psic[k]), si += sin(psic[k]);
    qre += cos(2.0 * psic[k]), qim += sin(2.0 * psic[k]);
    rf += fmax(fabs(gfl[k]), fabs(gfh[k])) * W[k];
    rq += fmax(fabs(gql[k]), fabs(gqh[k])) * W[k];
  }
  fc = sr * sr + si * si;
  qc = qre * qre + qim * qim;
  fr[0] = fmax(fl, fc - rf) - pad, fr[1] = fmin(fh, fc + rf) + pad;
  qr[0] = fmax(ql, qc - rq) - pad, qr[1] = fmin(qh, qc + rq) + pad;
  /* with the constraint: on the members (f in [fa, fb]) q <= q - lam (f - fref) for lam >= 0 with
   * fref = fb (lam <= 0: fa), and q >= q - lam (f - fref) for lam >= 0 with fref = fa (lam <= 0: fb);
   * lam from the gradients at the centre (least squares), the mean-value form on q - lam f (its
   * interval gradient [gq] - lam [gf]) */
  for (k = 1; k < n; k++) sff += gfc[k] * gfc[k], sfq += gfc[k] * gqc[k];
  lam = sff > 0.0 ? sfq / sff : 0.0;
  if (isfinite(lam) && lam != 0.0) {
    double rl = 0.0;
    for (k = 1; k < n; k++) {
      const double pl = lam > 0.0 ? lam * gfl[k] : lam * gfh[k], ph = lam > 0.0 ? lam * gfh[k] : lam * gfl[k];
      rl += fmax(fabs(gql[k] - ph), fabs(gqh[k] - pl)) * W[k];
    }
    {
      const double padl = pad * (1.0 + fabs(lam));
      const double up = qc - lam * (fc - (lam > 0.0 ? fb : fa)) + rl + padl;
      const double dn = qc - lam * (fc - (lam > 0.0 ? fa : fb)) - rl - padl;
      if (up < qr[1]) qr[1] = up;
      if (dn > qr[0]) qr[0] = dn;
    }
  }
  if (qr[0] < 0.0) qr[0] = 0.0;
}

/* ---- members: balls a, b placed by the closed form for two balls (the others and t given) ---- */

typedef struct closer {
  size_t n, a, b;
  int sgn;         /* z_a = V/2 + sgn i V/|V| h */
  double ta, tb;
} closer;

/* v: the n - 2 angles of the balls other than a, b (in ball order), then t.  Returns 0 and fills m,
 * or -1 where balls a, b cannot close (|V| > 2 or V = 0). */
static int close_member(const closer *c, const double *v, autobal_everyn_member_ *m) {
  double vx, vy, r, h, ux, uy, t = v[c->n - 2];
  size_t k, i = 0;
  if (t < c->ta) t = c->ta;
  if (t > c->tb) t = c->tb;
  vx = t, vy = 0.0;
  for (k = 0; k < c->n; k++) {
    if (k == c->a || k == c->b) continue;
    m->phi[k] = v[i++];
    vx -= cos(m->phi[k]), vy -= sin(m->phi[k]);
  }
  r = hypot(vx, vy);
  if (!(r <= 2.0 && r > 0.0)) return -1;
  h = sqrt(fmax(0.0, 1.0 - 0.25 * r * r));
  ux = vx / r, uy = vy / r;
  m->phi[c->a] = atan2(0.5 * vy + c->sgn * ux * h, 0.5 * vx - c->sgn * uy * h);
  m->phi[c->b] = atan2(0.5 * vy - c->sgn * ux * h, 0.5 * vx + c->sgn * uy * h);
  m->t = t;
  m->q = autobal_everyn_q_(c->n, m->phi);
  return 0;
}

/* The closing pair of a member (the two balls whose directions are farthest from parallel), its
 * sign, and the member's variables. */
static void closer_of(const autobal_everyn_member_ *m, size_t n, double ta, double tb, closer *c, double *v) {
  size_t j, k, i = 0;
  double best = -1.0, vx = m->t, vy = 0.0, ex, ey;
  c->n = n, c->ta = ta, c->tb = tb, c->a = 0, c->b = 1, c->sgn = 1;
  for (j = 0; j < n; j++)
    for (k = j + 1; k < n; k++) {
      const double s = fabs(sin(m->phi[j] - m->phi[k]));
      if (s > best) best = s, c->a = j, c->b = k;
    }
  for (k = 0; k < n; k++) {
    if (k == c->a || k == c->b) continue;
    v[i++] = m->phi[k];
    vx -= cos(m->phi[k]), vy -= sin(m->phi[k]);
  }
  v[n - 2] = m->t;
  /* z_a - V/2 along +i V or -i V */
  ex = cos(m->phi[c->a]) - 0.5 * vx, ey = sin(m->phi[c->a]) - 0.5 * vy;
  c->sgn = (-ex * vy + ey * vx) >= 0.0 ? 1 : -1;
}

/* Central differences of q along the members at v (step h in each of the nv parameters; t = v[nv - 1]
 * kept in [ta, tb]): g[k] = dq/dv_k, 0 where a side cannot be closed. */
static void q_gradient(const closer *c, const double v[AUTOBAL_EVERYN_MAX], size_t nv, double ta, double tb, double h,
                       double *g) {
  size_t k;
  for (k = 0; k < nv; k++) {
    double vp[AUTOBAL_EVERYN_MAX], vm[AUTOBAL_EVERYN_MAX];
    autobal_everyn_member_ mp, mm;
    memcpy(vp, v, sizeof vp);
    memcpy(vm, v, sizeof vm);
    vp[k] += h, vm[k] -= h;
    if (k == nv - 1) {
      if (vp[k] > tb) vp[k] = tb;
      if (vm[k] < ta) vm[k] = ta;
    }
    if (vp[k] == vm[k] || close_member(c, vp, &mp) != 0 || close_member(c, vm, &mm) != 0) {
      g[k] = 0.0;
      continue;
    }
    g[k] = (mp.q - mm.q) / (vp[k] - vm[k]);
  }
}

/* Local search on sigma q (sigma = +1 up, -1 down) from member m over the members of [ta, tb]:
 * gradient steps (central differences) with backtracking; m is replaced by the best found. */
static void local_search(autobal_everyn_member_ *m, size_t n, double ta, double tb, int sigma) {
  closer c;
  double v[AUTOBAL_EVERYN_MAX], g[AUTOBAL_EVERYN_MAX], w[AUTOBAL_EVERYN_MAX], alpha = 0.1;
  autobal_everyn_member_ cur, tr;
  const size_t nv = n - 1;
  int it;
  closer_of(m, n, ta, tb, &c, v);
  if (close_member(&c, v, &cur) != 0) return;
  for (it = 0; it < 400; it++) {
    double g2 = 0.0;
    size_t k;
    int ok = 0;
    q_gradient(&c, v, nv, ta, tb, 1e-6, g);
    for (k = 0; k < nv; k++) {
      g[k] = sigma * g[k];
      /* t at an end: no step out of [ta, tb] */
      if (k == nv - 1 && ((v[k] >= tb && g[k] > 0.0) || (v[k] <= ta && g[k] < 0.0))) g[k] = 0.0;
      g2 += g[k] * g[k];
    }
    if (!(g2 > 1e-28)) break;
    while (alpha * sqrt(g2) > 1e-14) {
      for (k = 0; k < nv; k++) w[k] = v[k] + alpha * g[k];
      if (w[nv - 1] < ta) w[nv - 1] = ta;
      if (w[nv - 1] > tb) w[nv - 1] = tb;
      if (close_member(&c, w, &tr) == 0 && sigma * tr.q > sigma * cur.q + 1e-4 * alpha * g2) {
        memcpy(v, w, sizeof w);
        cur = tr;
        alpha *= 2.0;
        ok = 1;
        break;
      }
      alpha *= 0.5;
    }
    if (!ok) break;
  }
  if (sigma * cur.q > sigma * m->q) *m = cur;
}

/* The member nearest the box centre psi (psi_1 = 0): turned so that S is real; if |S| is outside
 * [ta, tb] the closing pair is placed for t clamped into it.  Returns 0, or -1 (none). */
static int project_member(size_t n, const double *psi, double ta, double tb, autobal_everyn_member_ *m) {
  double sr = 0.0, si = 0.0, t, g;
  size_t k;
  for (k = 0; k < n; k++) sr += cos(psi[k]), si += sin(psi[k]);
  t = hypot(sr, si);
  g = t > 0.0 ? atan2(si, sr) : 0.0;
  for (k = 0; k < n; k++) m->phi[k] = psi[k] - g;
  m->t = t;
  m->q = autobal_everyn_q_(n, m->phi);
  if (t >= ta && t <= tb) return 0;
  {
    closer c;
    double v[AUTOBAL_EVERYN_MAX];
    autobal_everyn_member_ o;
    m->t = t < ta ? ta : tb;
    closer_of(m, n, ta, tb, &c, v);
    v[n - 2] = m->t;
    if (close_member(&c, v, &o) != 0) return -1;
    *m = o;
  }
  return 0;
}

static void pool_add(autobal_everyn_ *e, const autobal_everyn_member_ *m) {
  const double qn = (double)(e->n * e->n);
  long b = (long)floor(m->q / qn * AUTOBAL_EVERYN_POOL);
  size_t k;
  if (b < 0) b = 0;
  if (b >= AUTOBAL_EVERYN_POOL) b = AUTOBAL_EVERYN_POOL - 1;
  /* pool[] holds at most one member per bin; bin numbers are not stored, so look it up by q */
  for (k = 0; k < e->n_pool; k++) {
    long bk = (long)floor(e->pool[k].q / qn * AUTOBAL_EVERYN_POOL);
    if (bk >= AUTOBAL_EVERYN_POOL) bk = AUTOBAL_EVERYN_POOL - 1;
    if (bk == b) return;
  }
  if (e->n_pool < AUTOBAL_EVERYN_POOL) e->pool[e->n_pool++] = *m;
}

void autobal_everyn_fan_(size_t n, double t, autobal_everyn_member_ *m) {
  double lo = 1e-300, hi = TWO_PI / (double)n; /* spacing d: t = sin(n d / 2) / sin(d / 2) decreases */
  size_t k;
  int it;
  for (it = 0; it < 200; it++) {
    const double d = 0.5 * (lo + hi), td = sin(0.5 * (double)n * d) / sin(0.5 * d);
    if (!(d > lo && d < hi)) break;
    if (td > t) lo = d;
    else hi = d;
  }
  for (k = 0; k < n; k++) m->phi[k] = ((double)k - 0.5 * (double)(n - 1)) * 0.5 * (lo + hi);
  {
    double sr = 0.0;
    for (k = 0; k < n; k++) sr += cos(m->phi[k]);
    m->t = sr;
  }
  m->q = autobal_everyn_q_(n, m->phi);
}

/* ---- the search ---- */

typedef struct heap {
  box *b;
  size_t n, cap;
} heap;

static int heap_push(heap *h, const box *x, size_t cap_max) {
  size_t i;
  if (h->n == h->cap) {
    size_t nc = h->cap ? 2 * h->cap : 1024;
    box *nb;
    if (nc > cap_max) nc = cap_max;
    if (h->n >= nc) return -1;
    nb = (box *)realloc(h->b, nc * sizeof *nb);
    if (nb == NULL) return -1;
    h->b = nb, h->cap = nc;
  }
  i = h->n++;
  while (i > 0 && h->b[(i - 1) / 2].key < x->key) {
    h->b[i] = h->b[(i - 1) / 2];
    i = (i - 1) / 2;
  }
  h->b[i] = *x;
  return 0;
}

static void heap_pop(heap *h, box *out) {
  size_t i = 0;
  box last;
  *out = h->b[0];
  last = h->b[--h->n];
  for (;;) {
    size_t c = 2 * i + 1;
    if (c >= h->n) break;
    if (c + 1 < h->n && h->b[c + 1].key > h->b[c].key) c++;
    if (!(h->b[c].key > last.key)) break;
    h->b[i] = h->b[c];
    i = c;
  }
  if (h->n > 0) h->b[i] = last;
}

/* One search: sigma = +1 for the largest q (returns the outer upper bound), -1 for the least
 * (returns the outer lower bound); *best the member found. */
static double search(autobal_everyn_ *e, int sigma, long max_boxes, double tol, autobal_everyn_member_ *best,
                     int *complete) {
  const size_t n = e->n, nv = n - 1;
  const double fa = e->ta * e->ta, fb = e->tb * e->tb;
  const size_t cap_max = 1u << 20; /* live boxes (at most 152 MB: NV = 9) */
  heap h = {NULL, 0, 0};
  box b0, cur;
  double bestv = -INFINITY, stuck = -INFINITY, outer;
  size_t k;
  *complete = 0;
  for (k = 0; k < nv; k++) b0.lo[k] = 0.0, b0.hi[k] = TWO_PI;
  b0.hi[0] = TWO_PI / (double)n;
  b0.key = INFINITY;
  /* a first member: the symmetric fan of t = ta (one exists for every t in (0, n)) */
  {
    autobal_everyn_member_ m;
    autobal_everyn_fan_(n, e->ta, &m);
    local_search(&m, n, e->ta, e->tb, sigma);
    *best = m;
    bestv = sigma * m.q;
    pool_add(e, &m);
  }
  if (heap_push(&h, &b0, cap_max) != 0) return sigma > 0 ? INFINITY : -INFINITY;
  while (h.n > 0) {
    size_t dim = 0;
    int c;
    heap_pop(&h, &cur);
    if (cur.key <= bestv + tol) {
      heap_push(&h, &cur, cap_max); /* keep it for the bound */
      *complete = 1;
      break;
    }
    if (e->boxes >= max_boxes) {
      heap_push(&h, &cur, cap_max);
      break;
    }
    for (k = 1; k < nv; k++)
      if (cur.hi[k] - cur.lo[k] > cur.hi[dim] - cur.lo[dim]) dim = k;
    if (cur.hi[dim] - cur.lo[dim] < 1e-10) { /* too small to split: its bound stays */
      if (cur.key > stuck) stuck = cur.key;
      continue;
    }
    for (c = 0; c < 2; c++) {
      box ch = cur;
      double fr[2], qr[2], psic[AUTOBAL_EVERYN_MAX];
      const double mid = 0.5 * (cur.lo[dim] + cur.hi[dim]);
      autobal_everyn_member_ m;
      if (c == 0) ch.hi[dim] = mid;
      else ch.lo[dim] = mid;
      if (!box_valid(n, ch.lo, ch.hi)) continue;
      e->boxes++;
      box_bounds(n, ch.lo, ch.hi, fa, fb, fr, qr, psic);
      if (fr[1] < fa || fr[0] > fb) continue; /* no member of [ta, tb] in it */
      ch.key = sigma > 0 ? qr[1] : -qr[0];
      if (ch.key > cur.key) ch.key = cur.key; /* a child's bound is also its parent's */
      if (project_member(n, psic, e->ta, e->tb, &m) == 0) {
        pool_add(e, &m);
        if (sigma * m.q > bestv) {
          local_search(&m, n, e->ta, e->tb, sigma);
          pool_add(e, &m);
          if (sigma * m.q > bestv) bestv = sigma * m.q, *best = m;
        }
      }
      if (ch.key <= bestv) continue;
      if (heap_push(&h, &ch, cap_max) != 0) { /* out of room: keep its bound */
        if (ch.key > stuck) stuck = ch.key;
      }
    }
  }
  outer = bestv;
  if (h.n > 0 && h.b[0].key > outer) outer = h.b[0].key;
  if (stuck > outer) outer = stuck;
  if (stuck > bestv + tol) *complete = 0;
  free(h.b);
  return sigma * outer;
}

int autobal_everyn_range_(autobal_everyn_ *e, size_t n, double ta, double tb, long max_boxes, double tol) {
  int c1, c2;
  if (e == NULL || n < 4 || n > AUTOBAL_EVERYN_MAX || !(ta > 0.0 && ta <= tb && tb < (double)n)) return -1;
  memset(e, 0, sizeof *e);
  e->n = n, e->ta = ta, e->tb = tb;
  e->q_hi = search(e, 1, max_boxes / 2, tol, &e->mhi, &c1);
  e->q_lo = search(e, -1, e->boxes + max_boxes / 2, tol, &e->mlo, &c2);
  if (!isfinite(e->q_hi) || !isfinite(e->q_lo)) return -1;
  if (e->q_lo < 0.0) e->q_lo = 0.0;
  if (e->q_hi > (double)(n * n)) e->q_hi = (double)(n * n);
  e->q_hi_in = e->mhi.q;
  e->q_lo_in = e->mlo.q;
  e->complete = c1 && c2;
  return 0;
}

/* Newton steps on q along the members (the closing pair's parametrization) from m towards q_target. */
static void newton_to(autobal_everyn_member_ *m, size_t n, double ta, double tb, double q_target, double tol) {
  closer c;
  double v[AUTOBAL_EVERYN_MAX], g[AUTOBAL_EVERYN_MAX], w[AUTOBAL_EVERYN_MAX];
  autobal_everyn_member_ cur, tr;
  const size_t nv = n - 1;
  int it;
  closer_of(m, n, ta, tb, &c, v);
  if (close_member(&c, v, &cur) != 0) return;
  for (it = 0; it < 100 && fabs(cur.q - q_target) > tol; it++) {
    double g2 = 0.0, step = 1.0;
    size_t k;
    int ok = 0;
    q_gradient(&c, v, nv, ta, tb, 1e-7, g);
    for (k = 0; k < nv; k++) {
      if (k == nv - 1 && ((v[k] >= tb && g[k] * (q_target - cur.q) > 0.0) ||
                          (v[k] <= ta && g[k] * (q_target - cur.q) < 0.0)))
        g[k] = 0.0;
      g2 += g[k] * g[k];
    }
    if (!(g2 > 1e-24)) break;
    for (; step > 1e-6; step *= 0.5) {
      const double a = step * (q_target - cur.q) / g2;
      for (k = 0; k < nv; k++) w[k] = v[k] + a * g[k];
      if (w[nv - 1] < ta) w[nv - 1] = ta;
      if (w[nv - 1] > tb) w[nv - 1] = tb;
      if (close_member(&c, w, &tr) == 0 && fabs(tr.q - q_target) < fabs(cur.q - q_target)) {
        memcpy(v, w, sizeof w);
        cur = tr;
        ok = 1;
        break;
      }
    }
    if (!ok) break;
  }
  if (fabs(cur.q - q_target) < fabs(m->q - q_target)) *m = cur;
}

int autobal_everyn_member_at_(const autobal_everyn_ *e, double q_target, double tol, autobal_everyn_member_ *out) {
  /* candidates: the pool and the two extreme members, tried in order of |q - q_target| */
  const autobal_everyn_member_ *cand[AUTOBAL_EVERYN_POOL + 2];
  size_t nc = 0, k, tried;
  cand[nc++] = &e->mlo;
  cand[nc++] = &e->mhi;
  for (k = 0; k < e->n_pool; k++) cand[nc++] = &e->pool[k];
  /* selection sort by distance, a few at most */
  *out = *cand[0];
  for (tried = 0; tried < 8 && tried < nc; tried++) {
    size_t bi = tried;
    autobal_everyn_member_ m;
    for (k = tried + 1; k < nc; k++)
      if (fabs(cand[k]->q - q_target) < fabs(cand[bi]->q - q_target)) bi = k;
    {
      const autobal_everyn_member_ *x = cand[tried];
      cand[tried] = cand[bi], cand[bi] = x;
    }
    m = *cand[tried];
    if (m.t < e->ta || m.t > e->tb) continue;
    newton_to(&m, e->n, e->ta, e->tb, q_target, tol);
    if (fabs(m.q - q_target) < fabs(out->q - q_target)) *out = m;
    if (fabs(out->q - q_target) <= tol) return 0;
  }
  return 1;
}
