#!/usr/bin/env python3
"""derive_nballs.py: the closed forms behind 'every unbalance' with n >= 3 identical balls
(docs/rotor.md "Every unbalance"; src/analysis/rotor_unbalance.c), checked with SymPy:

 (1) closure: for n balls with a common kappa = h_i/m_i (any m_i, r_i), the linearized sum of the
     ball equations (3.13) is sigma'' + kappa sigma' = (Q conj(a) - m_b a) / 2, Q = sum m_i e^{2 i psi_i};
 (2) the symmetric fan psi_k = c + (k - (n-1)/2) delta: |sum e^{i psi_k}| = sin(n theta)/sin(theta)
     = U_{n-1}(x) and |sum e^{2 i psi_k}| = |sin(2 n theta)/sin(2 theta)| = |U_{n-1}(2 x^2 - 1)|,
     theta = delta/2, x = cos(theta) (Chebyshev U);
 (3) on y = cos(2 theta) in [cos(2 pi/n), 1]: U_{n-1}(y) vanishes only at cos(pi/n), U'_{n-1} has
     exactly one root in (cos(2 pi/n), cos(pi/n)) and none in (cos(pi/n), 1); t = U_{n-1}(x)
     increases with y there.
Each check prints a line ending in ': OK' (tests/test_derive.sh looks for them)."""
import sympy as sp

NMAX = 10


def closure(n):
    """Linearized about a balanced configuration psi_i, sigma = sum m_i r_i e^{i psi_i} has
    sigma'' + kappa sigma' = sum_i i e^{i psi_i} (m_i r_i dpsi_i'' + h_i r_i dpsi_i') (h_i = kappa m_i;
    the psi'^2 terms are second order), and the ball equations (3.13) divided by r_i make the bracket
    m_i (a_xi sin psi_i - a_eta cos psi_i): the closure is the identity below, for any m_i, r_i."""
    m = sp.symbols('m1:%d' % (n + 1), positive=True)
    z = sp.symbols('z1:%d' % (n + 1))  # z_i = e^{i psi_i}: sin = (z - 1/z)/(2i), cos = (z + 1/z)/2
    axi, aeta = sp.symbols('a_xi a_eta', real=True)
    sn = [(z[i] - 1 / z[i]) / (2 * sp.I) for i in range(n)]
    cs = [(z[i] + 1 / z[i]) / 2 for i in range(n)]
    lhs = sum(sp.I * z[i] * m[i] * (axi * sn[i] - aeta * cs[i]) for i in range(n))
    Q = sum(m[i] * z[i] ** 2 for i in range(n))
    rhs = (Q * (axi - sp.I * aeta) - sum(m) * (axi + sp.I * aeta)) / 2
    return sp.expand(lhs - rhs) == 0


def fan(n):
    th, c = sp.symbols('theta c', real=True)
    x = sp.cos(th)
    s1 = sum(sp.exp(sp.I * (k - sp.Rational(n - 1, 2)) * 2 * th) for k in range(n))
    s2 = sum(sp.exp(sp.I * (k - sp.Rational(n - 1, 2)) * 4 * th) for k in range(n))
    ok = True
    for val in [sp.Rational(1, 7), sp.Rational(3, 11), sp.pi / (n + 1), sp.Rational(2, 5)]:
        for expr, want in [(s1, sp.sin(n * th) / sp.sin(th)), (s1, sp.chebyshevu(n - 1, x)),
                           (s2, sp.sin(2 * n * th) / sp.sin(2 * th)), (s2, sp.chebyshevu(n - 1, 2 * x ** 2 - 1))]:
            d = sp.N((expr - want).subs(th, val), 40)
            ok = ok and abs(d) < 1e-30
    return ok


def pieces(n):
    y = sp.symbols('y', real=True)
    U = sp.chebyshevu(n - 1, y)
    dU = sp.diff(U, y)
    lo, mid = sp.cos(2 * sp.pi / n), sp.cos(sp.pi / n)
    rU = [r for r in sp.Poly(U, y).real_roots()]
    rd = [r for r in sp.Poly(dU, y).real_roots()] if n > 2 else []
    inU = [r for r in rU if sp.N(r - lo, 30) > -1e-25 and sp.N(r - 1, 30) <= 0]
    in1 = [r for r in rd if sp.N(r - lo, 30) > 0 and sp.N(r - mid, 30) < 0]
    in2 = [r for r in rd if sp.N(r - mid, 30) > 0 and sp.N(r - 1, 30) < 0]
    ok = len(in1) == 1 and len(in2) == 0
    # the roots of U in [lo, 1] are lo itself and mid
    ok = ok and len(inU) == 2 and abs(sp.N(min(inU) - lo, 30)) < 1e-25 and abs(sp.N(max(inU) - mid, 30)) < 1e-25
    # t = U_{n-1}(sqrt((1 + y)/2)) increasing on [lo, 1]: its derivative in x has no root in (cos(pi/n), 1)
    X = sp.symbols('X', real=True)
    dT = sp.diff(sp.chebyshevu(n - 1, X), X)
    rT = [r for r in sp.Poly(dT, X).real_roots() if sp.N(r - sp.cos(sp.pi / n), 30) > 0] if n > 2 else []
    ok = ok and len(rT) == 0
    return ok


def main():
    for n in range(2, NMAX + 1):
        assert closure(n), n
    print('n balls, common kappa: sigma\'\' + kappa sigma\' = (Q conj(a) - m_b a)/2 (n = 2..%d, any m_i, r_i)' % NMAX + ': OK')
    assert all(fan(n) for n in range(3, NMAX + 1))
    print('symmetric fan: t = sin(n theta)/sin(theta) = U_{n-1}(x), |Q|/m = |U_{n-1}(2 x^2 - 1)| (n = 3..%d): OK' % NMAX)
    assert all(pieces(n) for n in range(3, NMAX + 1))
    print('symmetric fan: u(y) monotone on [cos(2pi/n), y1], [y1, cos(pi/n)], [cos(pi/n), 1], t increasing (n = 3..%d): OK' % NMAX)


if __name__ == '__main__':
    main()
