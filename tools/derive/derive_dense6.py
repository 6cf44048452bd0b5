#!/usr/bin/python3
"""derive_dense6.py: DOP853's continuous extension of order 6 with no extra stage (issue 20).

The step's 12 stages k_0..k_11 plus the FSAL derivative k_12 = f(t + h, y1) carry a continuous
extension u(theta) = y0 + h sum_i b_i(theta) k_i of order 6 (bench/dense_order6.py, the float64
prototype).  Here it is derived at high precision (mpmath, 60 digits) from Hairer's DOP853 tableau
at its full printed precision (30 digits: the literals of src/transient/dop853_coeffs.inc, copied
digit for digit from the transcription of Hairer's dop853.f), in the form of Hairer's contd8 with
one more term (x = theta, x1 = 1 - x):

    u = y0 + x (F0 + x1 (F1 + x (F2 + x1 (F3 + x (F4 + x1 (F5 + x (F6 + x1 F7))))))),
    F0 = y1 - y0, F1 = h f0 - F0, F2 = 2 F0 - h (f0 + f1),  F3..F7 = h sum_i D6[r][i] k_i,

so u(0) = y0, u(1) = y1, u'(0) = f0, u'(1) = f1 hold by construction (C1 at the step ends;
degree 8 in theta).  D6 (5 x 13): every order condition of B-series trees of order <= 6 holds
for every theta (as a polynomial identity: constraints), and the residuals of the order-7 trees
over theta = 0, 1/40, ..., 1 are minimized in least squares (their principal error terms); among
the minimizers the one of least Euclidean norm of D6 (orthonormal null-space basis).

    /usr/bin/python3 tools/derive/derive_dense6.py            # writes src/transient/dop853_dense6.inc
    /usr/bin/python3 tools/derive/derive_dense6.py --check    # fails if the include differs

Checks (each prints a line ending in ': OK'; tests/test_derive.sh looks for them):
  (1) the tableau: the quadrature and order conditions of b up to order 8 to 1e-28;
  (2) the derived D6 (60 digits): order <= 6 conditions to 1e-24 (limited by the tableau's 30 digits), order 7 not (order exactly 6);
  (3) the end conditions u(0) = y0, u(1) = y1, u'(0) = f0, u'(1) = f1 for the rounded D6 (exact);
  (4) after rounding D6 to double (the literals of the include, read back from the file), with the
      30-digit tableau and with its doubles: every order <= 6 condition, in the coordinates of
      F3..F7 (the dot products the C code forms), to <= 1e-15 relative to the sum of the magnitudes
      of its terms; printed too: the residual as a function of theta relative to 1/gamma(t);
  (5) --check: the include equals what this script writes (byte for byte)."""
import argparse
import os
import re
import sys

import mpmath as mp

mp.mp.dps = 60
ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
INC_TABLEAU = os.path.join(ROOT, "src", "transient", "dop853_coeffs.inc")
INC_OUT = os.path.join(ROOT, "src", "transient", "dop853_dense6.inc")
NS = 13  # stages 0..12 (12: f(t + h, y1), its row the weights b)
NR = 5   # F3..F7
DEG = 8


def ok(msg, cond):
    if not cond:
        print(msg + ": FAILED")
        sys.exit(1)
    print(msg + ": OK")


def read_tableau():
    """A (13 x 13, row 12 = b) as the 30-digit decimal strings of dop853_coeffs.inc."""
    text = open(INC_TABLEAU).read()
    m = re.search(r"DOP853_A\[16\]\[16\] = \{(.*?)\n\};", text, re.S)
    rows = re.findall(r"\{([^{}]*)\}", m.group(1))
    assert len(rows) == 16
    A = []
    for r in rows[:NS]:
        vals = [v.strip() for v in r.split(",")]
        A.append(vals[:NS])
    return A


def trees_upto(p):
    byorder, order = {1: [()]}, {(): 1}
    for n in range(2, p + 1):
        pool = [t for k in range(1, n) for t in byorder[k]]
        res = set()

        def gen(rem, lo, cur):
            if rem == 0:
                res.add(tuple(sorted(cur)))
                return
            for idx in range(lo, len(pool)):
                if order[pool[idx]] <= rem:
                    gen(rem - order[pool[idx]], idx, cur + [pool[idx]])
        gen(n - 1, 0, [])
        byorder[n] = sorted(res)
        for t in byorder[n]:
            order[t] = n
    return byorder, order


def gamma(t, order):
    g = order[t]
    for c in t:
        g *= gamma(c, order)
    return g


def phis(A, trees):
    """Phi_i(t) (stages 0..12) for every tree, in the arithmetic of A's entries."""
    memo = {}

    def phi(t):
        if t not in memo:
            v = [mp.mpf(1)] * NS
            for c in t:
                pc = phi(c)
                Ac = [mp.fsum(A[i][j] * pc[j] for j in range(i)) for i in range(NS)]
                v = [v[i] * Ac[i] for i in range(NS)]
            memo[t] = v
        return memo[t]
    return {t: phi(t) for t in trees}


# polynomials in x: lists of coefficients of x^0..x^DEG
def padd(p, q):
    n = max(len(p), len(q))
    return [(p[k] if k < len(p) else 0) + (q[k] if k < len(q) else 0) for k in range(n)]


def pmul(p, q):
    r = [mp.mpf(0)] * (len(p) + len(q) - 1)
    for a, pa in enumerate(p):
        for b, qb in enumerate(q):
            r[a + b] += pa * qb
    return r


X, X1 = [mp.mpf(0), mp.mpf(1)], [mp.mpf(1), mp.mpf(-1)]


def nested(cs, first_x=True):
    """c0 + x (c1 + x1 (c2 + x (c3 + ...))): the factors alternate x, x1 starting with x if first_x."""
    p = [cs[-1]]
    facs = [X if (k % 2 == 0) == first_x else X1 for k in range(len(cs) - 1)]
    for k in range(len(cs) - 2, -1, -1):
        p = padd([cs[k]], pmul(facs[k], p))
    return p


def weight_polys(b, D):
    """b_i(x) for i = 0..12 (coefficients of x^0..x^8) given the weights b and D (5 x 13)."""
    out = []
    for i in range(NS):
        d0 = mp.mpf(1) if i == 0 else mp.mpf(0)
        d12 = mp.mpf(1) if i == 12 else mp.mpf(0)
        F = [b[i], d0 - b[i], 2 * b[i] - d0 - d12] + [D[r][i] for r in range(NR)]
        # u - y0 = x (F0 + x1 (F1 + x (F2 + x1 (F3 + x (F4 + ...))))) : x times nested starting x1
        inner = nested(F, first_x=False)
        p = pmul(X, inner)
        p = p + [mp.mpf(0)] * (DEG + 1 - len(p))
        out.append(p[:DEG + 1])
        assert all(c == 0 for c in p[DEG + 1:])
    return out


def basis_polys():
    """the weight polynomial's dependence on D: B[r] = coefficients of x^0..x^8 multiplying D[r][i]"""
    zero_b = [mp.mpf(0)] * NS
    B = []
    for r in range(NR):
        D = [[mp.mpf(0)] * NS for _ in range(NR)]
        D[r][1] = mp.mpf(1)  # stage 1: no delta terms
        B.append(weight_polys(zero_b, D)[1])
    return B


def derive(A, Phi, byorder, order, b):
    B = basis_polys()
    hermite = weight_polys(b, [[mp.mpf(0)] * NS for _ in range(NR)])
    nv = NR * NS
    rows, rhs = [], []
    for k in range(1, 7):
        for t in byorder[k]:
            ph, g = Phi[t], gamma(t, order)
            herm = [mp.fsum(hermite[i][e] * ph[i] for i in range(NS)) for e in range(DEG + 1)]
            for e in range(DEG + 1):
                row = [mp.mpf(0)] * nv
                for r in range(NR):
                    for i in range(NS):
                        row[r * NS + i] = B[r][e] * ph[i]
                if all(v == 0 for v in row):
                    continue
                rows.append(row)
                rhs.append((mp.mpf(1) / g if e == k else mp.mpf(0)) - herm[e])
    M, r = mp.matrix(rows), mp.matrix(rhs)
    # null space and least-norm particular solution from the Gram matrix (symmetric eigenproblem)
    G = M.T * M
    ev, V = mp.eigsy(G)
    big = max(abs(x) for x in ev)
    keep = [j for j in range(nv) if abs(ev[j]) > big * mp.mpf(10) ** (-40)]
    null = [j for j in range(nv) if j not in keep]
    Mtr = M.T * r
    x0 = mp.matrix(nv, 1)
    for j in keep:
        vj = V[:, j]
        x0 += vj * ((vj.T * Mtr)[0] / ev[j])
    cres = max(abs(v) for v in (M * x0 - r))
    N = mp.matrix(nv, len(null))
    for a, j in enumerate(null):
        N[:, a] = V[:, j]
    # objective: order-7 residuals over the theta grid
    grid = [mp.mpf(k) / 40 for k in range(41)]
    orow, orhs = [], []
    for t in byorder[7]:
        ph, g = Phi[t], gamma(t, order)
        herm = [mp.fsum(hermite[i][e] * ph[i] for i in range(NS)) for e in range(DEG + 1)]
        for th in grid:
            pw = [th ** e for e in range(DEG + 1)]
            row = [mp.mpf(0)] * nv
            for rr in range(NR):
                be = mp.fsum(B[rr][e] * pw[e] for e in range(DEG + 1))
                for i in range(NS):
                    row[rr * NS + i] = be * ph[i]
            orow.append(row)
            orhs.append(th ** 7 / g - mp.fsum(herm[e] * pw[e] for e in range(DEG + 1)))
    O, o = mp.matrix(orow), mp.matrix(orhs)
    ON = O * N
    H = ON.T * ON
    hv, W = mp.eigsy(H)
    hbig = max(abs(x) for x in hv)
    g = ON.T * (o - O * x0)
    z = mp.matrix(len(null), 1)
    nfree = 0
    for j in range(len(null)):
        if abs(hv[j]) > hbig * mp.mpf(10) ** (-40):
            wj = W[:, j]
            z += wj * ((wj.T * g)[0] / hv[j])
        else:
            nfree += 1
    x = x0 + N * z
    D = [[x[rr * NS + i] for i in range(NS)] for rr in range(NR)]
    ores = mp.sqrt(mp.fsum(v ** 2 for v in (O * x - o)) / len(orhs))
    return D, cres, len(keep), len(null), nfree, ores


def cond_residuals(b, D, Phi, byorder, order, pmax):
    """worst residual of the order <= pmax conditions, coefficient by coefficient of x:
    (relative to the sum of the magnitudes of the terms, relative to 1/gamma)"""
    W = weight_polys(b, D)
    worst_mag, worst_g = mp.mpf(0), mp.mpf(0)
    for k in range(1, pmax + 1):
        for t in byorder[k]:
            ph, g = Phi[t], gamma(t, order)
            for e in range(DEG + 1):
                terms = [W[i][e] * ph[i] for i in range(NS)]
                res = abs(mp.fsum(terms) - (mp.mpf(1) / g if e == k else 0))
                mag = mp.fsum(abs(v) for v in terms)
                if mag > 0:
                    worst_mag = max(worst_mag, res / mag)
                worst_g = max(worst_g, res * g)
    return worst_mag, worst_g


def nested_residuals(b, D, Phi, byorder, order, pmax, B):
    """The conditions as the C code forms them: for every tree of order <= pmax the residual
    polynomial sum_i b_i(x) Phi_i(t) - x^|t| / gamma(t) written in the basis of F3..F7 (the
    functions multiplying F3..F7 in u), coordinate r against the magnitude of its terms
    sum_i |D6[r][i] Phi_i(t)| (the dot product F_{3+r} = h sum_i D6[r][i] k_i): the worst ratio;
    and the worst |residual(theta)| gamma(t) over theta = 0, 1/40, ..., 1."""
    W = weight_polys(b, D)
    Bm = mp.matrix([[B[r][e] for r in range(NR)] for e in range(DEG + 1)])
    worst, worst_fun, worst_span = mp.mpf(0), mp.mpf(0), mp.mpf(0)
    for k in range(1, pmax + 1):
        for t in byorder[k]:
            ph, g = Phi[t], gamma(t, order)
            Rm = [mp.fsum(W[i][e] * ph[i] for i in range(NS)) - (mp.mpf(1) / g if e == k else 0)
                  for e in range(DEG + 1)]
            Rv = mp.matrix(Rm)
            rho = mp.lu_solve(Bm.T * Bm, Bm.T * Rv)
            lres = mp.norm(Bm * rho - Rv)
            worst_span = max(worst_span, lres * g)
            for r in range(NR):
                mag = mp.fsum(abs(D[r][i] * ph[i]) for i in range(NS))
                if mag == 0:  # F7 = 0: its coordinate must vanish to the tableau's digits
                    worst_span = max(worst_span, abs(rho[r]) * g)
                    continue
                worst = max(worst, abs(rho[r]) / mag)
            for j in range(41):
                th = mp.mpf(j) / 40
                worst_fun = max(worst_fun, abs(mp.polyval(Rm[::-1], th)) * g)
    return worst, worst_fun, worst_span


def fmt(v):
    return "%.17e" % float(v)


def include_text(D):
    L = []
    L.append("/* dop853_dense6.inc: generated by tools/derive/derive_dense6.py (mpmath, 60 digits, from the")
    L.append(" * 30-digit DOP853 tableau of dop853_coeffs.inc); do not edit (test_derive checks it).")
    L.append(" * DOP853's continuous extension of order 6 with no extra stage: F3..F6 = h sum_i D6[r][i] k_i")
    L.append(" * (stages 0..11 and k_12 = f(t + h, y1)), evaluated by dop853.c exactly as contd8:")
    L.append(" *   u = y0 + x (F0 + x1 (F1 + x (F2 + x1 (F3 + x (F4 + x1 (F5 + x F6)))))). */")
    L.append("static const double DOP853_D6[4][13] = {")
    for r in range(NR - 1):
        L.append("    {%s}," % ", ".join(fmt(D[r][i]) for i in range(NS)))
    L.append("};")
    L.append("/* f + r n = h sum_j D6[r][j] k_j (r = 0..3: F3..F6), every component in one loop */")
    L.append("static DOP853_INLINE void dop853_dense6_rows(size_t n, double h, const double *restrict k, "
             "double *restrict f) {")
    L.append("  size_t b, i;")
    L.append("  for (b = 0; b < n; b += DOP853_LANES)")
    L.append("    for (i = b; i < b + DOP853_LANES; i++) {")
    for r in range(NR - 1):
        terms = " + ".join("(%s) * k[%d * n + i]" % (fmt(D[r][i]), i) for i in range(NS) if D[r][i] != 0)
        L.append("      f[%d * n + i] = h * (%s);" % (r, terms))
    L.append("    }")
    L.append("}")
    return "\n".join(L) + "\n"


def read_include(path):
    text = open(path).read()
    m = re.search(r"DOP853_D6\[4\]\[13\] = \{(.*?)\n\};", text, re.S)
    rows = re.findall(r"\{([^{}]*)\}", m.group(1))
    D = [[mp.mpf(float(v)) for v in r.split(",")] for r in rows] + [[mp.mpf(0)] * NS]
    assert len(D) == NR and all(len(r) == NS for r in D)
    return text, D


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true", help="compare with the committed include; write nothing")
    ap.add_argument("--out", default=INC_OUT)
    a = ap.parse_args()

    As = read_tableau()
    A = [[mp.mpf(v) for v in row] for row in As]
    Ad = [[mp.mpf(float(v)) for v in row] for row in As]  # the doubles the C step uses
    b, bd = A[12], Ad[12]
    byorder, order = trees_upto(8)
    trees = [t for k in range(1, 9) for t in byorder[k]]
    Phi = phis(A, trees)
    # (1) the tableau: sum_i b_i Phi_i(t) = 1/gamma(t) for |t| <= 8 (row 12's Phi is stage 12's)
    w1 = max(abs(mp.fsum(b[i] * Phi[t][i] for i in range(NS)) - mp.mpf(1) / gamma(t, order)) * gamma(t, order)
             for t in trees)
    ok("dense6 (1) DOP853 tableau (30 digits): order conditions of b up to order 8 to %.1e" % float(w1),
       w1 < mp.mpf(10) ** -27)

    D, cres, rank, nnull, nfree, ores = derive(A, Phi, byorder, order, b)
    w6 = cond_residuals(b, D, Phi, byorder, order, 6)
    w7 = cond_residuals(b, D, Phi, byorder, order, 7)
    print("  constraints: rank %d of %d unknowns, null space %d (%d not fixed by the objective: "
          "least norm); order-7 residual rms %.3e" % (rank, NR * NS, nnull, nfree, float(ores)))
    ok("dense6 (2) derived (60 digits): order <= 6 conditions to %.1e (the tableau's 30 digits), order 7 "
       "residual %.2e (> 1e-6: order exactly 6)" % (float(w6[1]), float(w7[1])),
       w6[1] < mp.mpf(10) ** -24 and w7[1] > mp.mpf(10) ** -6)

    # the least-norm optimum has F7 = 0 (to the tableau's 30 digits): the extension is of degree 7,
    # in exactly the form of Hairer's contd8 (F3..F6), only with other coefficients
    f7 = max(abs(v) for v in D[4])
    ok("dense6 (2b) the optimum of degree 8 has F7 = 0: largest |D6[4][i]| %.1e (degree 7, contd8's form)"
       % float(f7), f7 < mp.mpf(10) ** -20)
    D[4] = [mp.mpf(0)] * NS
    # likewise the stages 1..4 (unused by b too) and F6's k_11, k_12 get coefficients at the level of
    # the tableau's digits: exactly 0
    tiny = [(r, i) for r in range(NR - 1) for i in range(NS) if abs(D[r][i]) < mp.mpf(10) ** -20]
    big_small = min(abs(D[r][i]) for r in range(NR - 1) for i in range(NS) if (r, i) not in tiny)
    ok("dense6 (2c) %d coefficients below 1e-20 (stages 1..4, F6's k_11, k_12) set to 0; the smallest other %.2e"
       % (len(tiny), float(big_small)), len(tiny) == 18 and big_small > mp.mpf(10) ** -3)
    for r, i in tiny:
        D[r][i] = mp.mpf(0)
    text = include_text(D)
    if a.check:
        have, Dd = read_include(a.out)
        ok("dense6 (5) %s equals what derive_dense6.py writes" % os.path.relpath(a.out, ROOT), have == text)
    else:
        with open(a.out, "w") as f:
            f.write(text)
        print("  wrote " + a.out)
        _, Dd = read_include(a.out)

    # (3) end conditions of the rounded extension, exactly (rational arithmetic of the doubles)
    Wd = weight_polys(bd, Dd)
    e3 = mp.mpf(0)
    for i in range(NS):
        p = Wd[i]
        dp = [e * p[e] for e in range(1, DEG + 1)]
        e3 = max(e3, abs(p[0]), abs(mp.fsum(p) - bd[i]), abs(dp[0] - (1 if i == 0 else 0)),
                 abs(mp.fsum(dp) - (1 if i == 12 else 0)))
    ok("dense6 (3) u(0) = y0, u(1) = y1, u'(0) = f0, u'(1) = f1 for the rounded D6: largest deviation %.1e"
       % float(e3), e3 < mp.mpf(10) ** -45)
    # (4) the rounded D6 against the exact tableau (our rounding alone), and everything in doubles
    B = basis_polys()
    r_mag, r_fun, r_span = nested_residuals(b, Dd, Phi, byorder, order, 6, B)
    Phid = phis(Ad, [t for k in range(1, 7) for t in byorder[k]])
    rd_mag, rd_fun, rd_span = nested_residuals(bd, Dd, Phid, byorder, order, 6, B)
    print("  rounded D6, 30-digit tableau: worst %.2e of the terms' magnitudes; |residual(theta)| gamma <= %.2e"
          " (outside F3..F7's span: %.1e, the tableau's digits)" % (r_mag, r_fun, r_span))
    print("  rounded D6 and tableau (the doubles of the C code): %.2e; %.2e (outside the span: %.1e, the"
          " tableau's rounding)" % (rd_mag, rd_fun, rd_span))
    ok("dense6 (4) every order <= 6 condition after rounding D6 to double within 1e-15 of its terms' magnitude",
       r_mag <= mp.mpf(10) ** -15 and r_span < mp.mpf(10) ** -24)
    mx = max(abs(v) for r in Dd for v in r)
    print("  largest |D6| %.3g" % float(mx))


if __name__ == "__main__":
    main()
