#!/usr/bin/python3
"""Asymptotic (light-ball) condition for TWO balancer planes, and undamped balls (kappa = 0) in one plane,
derived with SymPy and checked numerically (docs/rotor.md "Asymptotic conditions", "Two planes", "kappa = 0").

Run with Debian's interpreter:  /usr/bin/python3 tools/derive/derive_asymptotic2.py

The closed two-plane system of docs/rotor.md "Two planes: degree 16" (rotating coordinates X = (W, Theta),
ball coordinates sigma_j, P = lambda + i w, Pb = lambda - i w, B = [[1, 1], [d1, d2]], b_j its columns):
    K(P) X + P^2 B sigma = 0,
    L_j sigma_j + (m_bj/2) P^2 b_j.X - (Q_j/2) Pb^2 b_j.Xb = 0,   L_j = lambda^2 + kappa_j lambda,
and the conjugate rows.  What is derived and asserted (each check prints a line ending in ': OK', or raises):
 (1) freezing K, P^2, Pb^2 at lambda = 0 and eliminating X, Xb gives (U - S)(sigma; sigmab) = 0 with
     U = diag(L1, L2, L1, L2), S = s [Mb G, -Q conj G; -conj Q G, Mb conj G], s = w^4/2, G = B^T K(i w)^-1 B;
 (2) p = det(U - S) has real coefficients (degree 8 in lambda) and G is symmetric;
 (3) G12 = 0: p is the product of the two one-plane quartics (u_j - a_j G_jj)(u_j - a_j conj G_jj) - q_j^2 a_j^2 |G_jj|^2,
     a_j = m_bj w^4/2, q_j = |Q_j|/m_bj, each decided by the one-plane (L1), (L2);
 (4) the 8 roots of p against the 16 exact roots (NumPy companion of the closed system) for balls scaled
     down: the relative error of the ball roots falls like m (balls 1e-4 -> 1e-6 of 0.05 kg), within the small parameter;
 (5) the rotor-housing's roots: lambda_k + sum_j (m_bj/2) P^4 N_jj / (L_j D') at the roots of D = det K,
     N = B^T adj(K) B, against the exact roots: the error relative to the shift falls like m;
 (6) kappa = 0, one plane: with g(lambda) = (m_b/2) P^4 N / D ~ g0 + g1 lambda (g0 = a G), the ball roots are
     lambda = +-i y + delta with u0 = lambda0^2 = Re g0 +- r real (r = sqrt(q^2 |g0|^2 - Im^2 g0) real) and
     delta_(+-) = Re g1 / 2 +- (q^2 Re(g1 conj g0) - Im g0 Im g1) / (2 r)   (real, O(m_b));
     derived symbolically as -f_lambda / (2 f_u), and checked against the exact roots of Delta (kappa = 0) for
     light balls: a machine where undamped balls are asymptotically stable.
"""
import sys

import numpy as np
import sympy as sp
from numpy.polynomial import polynomial as Pn

sys.path.insert(0, __import__('os').path.dirname(__file__))
from asymptotic2_scan import default2, exact_roots, light2, delta1, mul  # noqa: E402


def ok(msg):
    print(msg + ': OK')


def check_reduction():
    w = sp.Symbol('omega', positive=True)
    k11, k12, k22 = sp.symbols('k11 k12 k22')            # K(i w), complex
    d1, d2, m1, m2, L1, L2 = sp.symbols('d1 d2 m1 m2 L1 L2')
    Q1, Q2 = sp.symbols('Q1 Q2')
    K = sp.Matrix([[k11, k12], [k12, k22]])
    Kc = K.applyfunc(sp.conjugate)
    B = sp.Matrix([[1, 1], [d1, d2]])
    P2, Pb2 = -w**2, -w**2                              # P^2, Pb^2 at lambda = 0
    sig = sp.Matrix(sp.symbols('s1 s2'))
    sigb = sp.Matrix(sp.symbols('t1 t2'))
    X = -P2 * K.inv() * B * sig
    Xb = -Pb2 * Kc.inv() * B * sigb
    Ls, ms, Qs = [L1, L2], [m1, m2], [Q1, Q2]
    rows = [Ls[j] * sig[j] + ms[j] / 2 * P2 * (B[:, j].T * X)[0] - Qs[j] / 2 * Pb2 * (B[:, j].T * Xb)[0]
            for j in range(2)]
    G = B.T * K.inv() * B
    Gc = B.T * Kc.inv() * B
    s = w**4 / 2
    S = sp.zeros(4, 4)
    for j in range(2):
        for k in range(2):
            S[j, k] = s * ms[j] * G[j, k]
            S[j, k + 2] = -s * Qs[j] * Gc[j, k]
    U = sp.diag(L1, L2, L1, L2)
    want = (U - S)[:2, :] * sp.Matrix([sig[0], sig[1], sigb[0], sigb[1]])
    for j in range(2):
        assert sp.simplify(rows[j] - want[j]) == 0
    assert sp.simplify(G[0, 1] - G[1, 0]) == 0
    ok('two planes (1): frozen at lambda = 0, the ball rows are (U - S)(sigma; sigmab) = 0, '
       'S = s [Mb G, -Q conj G; -conj Q G, Mb conj G], G = B^T K^-1 B symmetric')


def pdet(kap, G, mb, Q, w, lam):
    s = w**4 / 2
    Gc = G.applyfunc(sp.conjugate)
    S = sp.zeros(4, 4)
    for j in range(2):
        for k in range(2):
            S[j, k] = s * mb[j] * G[j, k]
            S[j, k + 2] = -s * Q[j] * Gc[j, k]
            S[j + 2, k] = -s * sp.conjugate(Q[j]) * G[j, k]
            S[j + 2, k + 2] = s * mb[j] * Gc[j, k]
    U = sp.diag(*[lam**2 + kap[j % 2] * lam for j in range(4)])
    # the determinant over the polynomial ring (DomainMatrix, exact: the same polynomial as
    # (U - S).det(method='berkowitz') on expressions, in a fraction of the time)
    from sympy.polys.matrices import DomainMatrix
    dM = DomainMatrix.from_Matrix(U - S)
    return sp.expand(dM.domain.to_sympy(dM.det()))


def check_real_and_factor():
    lam = sp.Symbol('lambda')
    w, k1, k2, m1, m2 = sp.symbols('omega kappa1 kappa2 m1 m2', positive=True)
    g = sp.symbols('g11r g11i g12r g12i g22r g22i', real=True)
    q = sp.symbols('q1r q1i q2r q2i', real=True)
    G = sp.Matrix([[g[0] + sp.I * g[1], g[2] + sp.I * g[3]], [g[2] + sp.I * g[3], g[4] + sp.I * g[5]]])
    Q = [q[0] + sp.I * q[1], q[2] + sp.I * q[3]]
    p = pdet([k1, k2], G, [m1, m2], Q, w, lam)
    pp = sp.Poly(p, lam)
    assert pp.degree() == 8
    for cf in pp.all_coeffs():
        assert sp.simplify(sp.im(sp.expand(cf))) == 0
    # G12 = 0: the product of the one-plane quartics
    p0 = sp.expand(p.subs({g[2]: 0, g[3]: 0}))
    quart = 1
    for j, (kk, mm, gr, gi, qq) in enumerate(((k1, m1, g[0], g[1], Q[0]), (k2, m2, g[4], g[5], Q[1]))):
        u = lam**2 + kk * lam
        a = mm * w**4 / 2
        Gj = gr + sp.I * gi
        qabs2 = sp.expand(qq * sp.conjugate(qq)) / mm**2
        quart *= (u - a * Gj) * (u - a * sp.conjugate(Gj)) - qabs2 * a**2 * Gj * sp.conjugate(Gj)
    assert sp.expand(p0 - sp.expand(quart)) == 0
    ok('two planes (2): det(U - S) has degree 8 and real coefficients; (3) G12 = 0: the product of the one-plane '
       'quartics (L1)/(L2)')


def scaled(p, f):
    q = dict(p)
    q['m'] = [x * f for x in p['m']]
    q['s0'] = [x * f for x in p['s0']]
    q['hb'] = [x * f for x in p['hb']]
    return q


def check_convergence():
    p = default2()
    p['hb'] = [p['m'][0] * 2.0, p['m'][1] * 3.0]  # kappa 2 and 3 1/s
    w = 800.0
    rel_b = []
    for f in (1e-4, 1e-5, 1e-6):
        q = scaled(p, f)
        ex = exact_roots(q, w)
        res, errs, small, lam, G = light2(q, w)
        eb = max(min(abs(ex - l)) / abs(l) for l in lam)
        rel_b.append(eb)
        assert eb <= small, (f, eb, small)
    assert rel_b[1] < rel_b[0] / 5 and rel_b[2] < rel_b[1] / 5, rel_b
    ok('two planes (4): ball roots of det(U - S) vs the exact 16 roots, relative error %.2e, %.2e, %.2e for balls '
       'x 1e-4, 1e-5, 1e-6 (falls like m or faster, within the small parameter)' % tuple(rel_b))


def rotor_shift_error(p, w):
    d = p['d']
    mb = [2 * x for x in p['m']]
    kap = [p['hb'][j] / p['m'][j] for j in range(2)]
    P = np.array([1j * w, 1.0])
    P2 = mul(P, P)
    K11 = Pn.polyadd(Pn.polyadd(p['M'] * P2, p['h'] * P), [p['c']])
    K12 = -Pn.polyadd(p['hc'] * P, [p['cc']])
    K22 = Pn.polyadd(Pn.polyadd(p['A'] * P2, (p['ht'] - 1j * p['C'] * w) * P), [p['ct']])
    D = Pn.polysub(mul(K11, K22), mul(K12, K12))
    Dp = Pn.polyder(D)
    ex = exact_roots(p, w)
    worst = 0.0
    for lk in np.roots(D[::-1]):
        sh = 0
        for j in range(2):
            Njj = Pn.polyadd(Pn.polyadd(K22, -2 * d[j] * K12), d[j]**2 * K11)
            sh += mb[j] / 2 * (lk + 1j * w)**4 * Pn.polyval(lk, Njj) / ((lk * lk + kap[j] * lk) * Pn.polyval(lk, Dp))
        pred = lk + sh
        worst = max(worst, min(abs(ex - pred)) / abs(sh))
    return worst


def check_rotor_shift():
    p = default2()
    p['hb'] = [p['m'][0] * 2.0, p['m'][1] * 3.0]
    # (below 1e-3 the double-precision eigenvalues of the 16x16 companion limit the comparison)
    e = [rotor_shift_error(scaled(p, f), 800.0) for f in (1e-1, 1e-2)]
    assert e[1] < e[0] / 5 and e[1] < 1e-3, e
    ok('two planes (5): first-order shift of the roots of D vs the exact roots, error relative to the shift '
       '%.2e -> %.2e for balls x 0.1 -> 0.01 (falls like m)' % tuple(e))


def kappa0_prediction(p, w):
    """(u0, delta) of (6) for the one-plane machine p (two identical balls) at w, or None if u0 is not real."""
    M, A, C, c, ct, cc, h, ht, hc, d = [p[k] for k in 'M A C c ct cc h ht hc d'.split()]
    P = np.array([1j * w, 1.0])
    K11 = Pn.polyadd(M * mul(P, P), Pn.polyadd(h * P, [c]))
    K12 = -Pn.polyadd(hc * P, [cc])
    K22 = Pn.polyadd(A * mul(P, P), Pn.polyadd((ht - 1j * C * w) * P, [ct]))
    D = Pn.polysub(mul(K11, K22), mul(K12, K12))
    N = Pn.polyadd(Pn.polyadd(K22, -2 * d * K12), d * d * K11)
    num = mul(P, P, P, P, N)
    mb = 2 * p['m']
    x = p['s0'] / (2 * p['m'] * p['r'])
    q = abs(2 * x * x - 1)
    g0 = mb / 2 * num[0] / D[0]
    g1 = mb / 2 * (num[1] * D[0] - num[0] * D[1]) / D[0]**2
    r2 = q * q * abs(g0)**2 - g0.imag**2
    if r2 <= 0:
        return None
    r = np.sqrt(r2)
    u0 = [g0.real + r, g0.real - r]
    dl = [g1.real / 2 + sg * (q * q * (g1 * np.conj(g0)).real - g0.imag * g1.imag) / (2 * r) for sg in (1, -1)]
    return u0, dl


def check_kappa0():
    # symbolic: lambda^2 = u, f(u, lambda) = (u - g)(u - g*) - q^2 g g*, g = g0 + g1 lambda, g* = conj(g0) + conj(g1) lambda;
    # at lambda0 = i y (u0 = -y^2 real) the root moves by delta = -f_lambda / (2 f_u) (first order in g1)
    g0r, g0i, g1r, g1i, q, rr = sp.symbols('g0r g0i g1r g1i q r', real=True)
    lam, u = sp.symbols('lambda u')
    g0, g1 = g0r + sp.I * g0i, g1r + sp.I * g1i
    f = (u - g0 - g1 * lam) * (u - sp.conjugate(g0) - sp.conjugate(g1) * lam) - q**2 * (g0 + g1 * lam) * (
        sp.conjugate(g0) + sp.conjugate(g1) * lam)
    for sg in (1, -1):
        u0 = g0r + sg * rr
        fu = sp.diff(f, u).subs({lam: 0, u: u0})
        fl = sp.diff(f, lam).subs({lam: 0, u: u0})
        delta = sp.expand(-fl / (2 * fu))
        want = g1r / 2 + sg * (q**2 * (g1r * g0r + g1i * g0i) - g0i * g1i) / (2 * rr)
        diff = sp.simplify((delta - want).subs(rr**2, q**2 * (g0r**2 + g0i**2) - g0i**2))
        diff = sp.simplify(sp.expand(diff * rr).subs(rr**2, q**2 * (g0r**2 + g0i**2) - g0i**2))
        assert diff == 0, diff
    # numeric: a disk-like rotor (C = 1.3 A, c_c = -1250 N/rad, d = -0.04 m, otherwise the default supports)
    # at 4440 rad/s, undamped light balls, q = 0.9 (one of the machines the kappa0 scan found stable)
    p = dict(M=10., A=0.16, C=0.208, c=2.5e5, ct=7375., cc=-1250., h=250., ht=7.375, hc=-2.5, d=-0.04,
             m=5e-6, r=0.1, hb=0.0)
    x = np.sqrt((1 + 0.9) / 2)
    errs = []
    for m in (5e-6, 5e-7):
        p['m'] = m
        p['s0'] = 2 * m * p['r'] * x
        u0, dl = kappa0_prediction(p, 4440.0)
        assert max(u0) < 0 and max(dl) < 0, (u0, dl)
        roots = np.roots(delta1(p, 4440.0)[::-1])
        small = sorted(roots, key=abs)[:4]
        ys = [np.sqrt(-u) for u in u0]
        e = 0.0
        for y, dd in zip(ys, dl):
            near = min(small, key=lambda z: abs(z - (dd + 1j * y)))
            e = max(e, abs(near.real - dd) / abs(dd))
        errs.append(e)
        assert roots.real.max() < 0
    assert errs[1] < errs[0] / 2 and errs[1] < 0.05, errs
    ok('kappa = 0 (6): ball roots +-i y + delta, delta = Re g1/2 +- (q^2 Re(g1 conj g0) - Im g0 Im g1)/(2r) (symbolic); '
       'disk-like rotor, 4440 rad/s, q = 0.9, undamped balls 5e-6 / 5e-7 kg: exactly asymptotically stable, relative '
       'error of Re %.2e -> %.2e' % tuple(errs))


def main():
    check_reduction()
    check_real_and_factor()
    check_convergence()
    check_rotor_shift()
    check_kappa0()
    print('derive_asymptotic2: all checks passed')
    return 0


if __name__ == '__main__':
    sys.exit(main())
