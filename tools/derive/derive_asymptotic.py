#!/usr/bin/python3
"""Asymptotic stability conditions of the balanced motion of the rotor (one plane), derived with SymPy.

Run with Debian's interpreter:  /usr/bin/python3 tools/derive/derive_asymptotic.py

Starting point: the closed one-plane characteristic polynomial of docs/rotor.md (autobal_rotor_char_poly),
    P = lambda + i w,  K11 = M P^2 + h P + c,  K12 = -(h_c P + c_c),  K22 = A P^2 + (h_t - i C w) P + c_t,
    D = K11 K22 - K12^2,  N = K22 - 2 d K12 + d^2 K11,
    F = (lambda^2 + kappa lambda) D - (m_b/2) P^4 N,  Delta = F F* - (|Q|/2)^2 P^4 Pb^4 N N*.
What is derived and asserted (each check prints a line ending in ': OK', or raises):
 (1) light balls: with D, N, P^4 frozen at lambda = 0, Delta = |D(0)|^2 [(u - a G)(u - a conj G) - q^2 a^2 |G|^2],
     u = lambda^2 + kappa lambda, G = N(0)/D(0), a = m_b w^4 / 2, q = |Q|/m_b;
 (2) lambda^2 + kappa lambda - u (u complex) has both roots in Re < 0 iff kappa > 0 and kappa^2 (-Re u) > (Im u)^2;
 (3) hence the four ball roots are stable iff (L1) Re G < 0 and (L2) kappa^2 (-Re G) > a (Im^2 G - q^2 |G|^2)
     (q < 1): checked against the roots of the quartic at 4000 random points;
 (4) high speed: Re G w^2 -> -(1/M + d^2/(A - C)), Im G w^3 -> -(h/M^2 - 2 d h_c/(M (A - C)) + d^2 h_t/(A - C)^2),
     and at q = 0 the threshold of (L2) tends to kappa_inf = sqrt(m_b g/2) eta/g (g, eta those two limits);
 (5) the planar case (d = 0, no coupling) in the pendulum's variables: (L1) is (7) (R_w > 1), (L2) at q = 0 and
     R_w -> infinity is (8) (h > H sqrt(R_m)), (L2) to leading order in 1/H is the corrected (9)
     (R_m k W^2 / h^2 < W - 1, k = 1 - q^2);
 (6) the first-order shift of a root lambda_k of D, (m_b/2) P^4 N / ((lambda^2 + kappa lambda) D') at lambda_k,
     against the roots of Delta (mpmath, 50 digits) for balls of 1e-6 and 1e-7 kg: the error falls like m^2.
"""
import random
import sys

import numpy as np
import sympy as sp
import mpmath as mp

lam, w, kap = sp.symbols('lambda omega kappa')
M, A, C, c, ct, cc, h, ht, hc, d, mb, Qa = sp.symbols('M A C c c_t c_c h h_t h_c d m_b Qabs', real=True)


def ok(msg):
    print(msg + ': OK')


def conj_coeffs(expr):
    """X*: the polynomial in lambda with conjugated coefficients (lambda unchanged)."""
    return sp.expand(expr.subs(sp.I, -sp.I))


def polys():
    P = lam + sp.I * w
    K11 = M * P**2 + h * P + c
    K12 = -(hc * P + cc)
    K22 = A * P**2 + (ht - sp.I * C * w) * P + ct
    D = sp.expand(K11 * K22 - K12**2)
    N = sp.expand(K22 - 2 * d * K12 + d**2 * K11)
    return P, D, N


def check_light_reduction():
    # (1): freeze D, N, P^4 at lambda = 0 (symbols D0, N0 complex, P^4 = w^4), keep u = lambda^2 + kappa lambda
    u = sp.Symbol('u')
    D0r, D0i, N0r, N0i = sp.symbols('D0r D0i N0r N0i', real=True)
    D0, N0 = D0r + sp.I * D0i, N0r + sp.I * N0i
    a = mb * w**4 / 2
    F = u * D0 - mb / 2 * w**4 * N0
    Fs = u * sp.conjugate(D0) - mb / 2 * w**4 * sp.conjugate(N0)
    Delta0 = F * Fs - (Qa / 2)**2 * w**8 * N0 * sp.conjugate(N0)
    G = N0 / D0
    q = Qa / mb
    rhs = D0 * sp.conjugate(D0) * ((u - a * G) * (u - a * sp.conjugate(G)) - q**2 * a**2 * G * sp.conjugate(G))
    assert sp.simplify(sp.expand(Delta0 - rhs)) == 0
    # and this is the lambda -> 0 freezing of the real Delta: F(0) = -(m_b/2) w^4 N(0) exactly
    P, D, N = polys()
    Fx = (lam**2 + kap * lam) * D - mb / 2 * P**4 * N
    assert sp.simplify(Fx.subs(lam, 0) + mb / 2 * w**4 * N.subs(lam, 0)) == 0
    ok('light balls (1): Delta with D, N, P^4 frozen at 0 = |D0|^2 [(u - aG)(u - a conj G) - q^2 a^2 |G|^2]')


def check_quadratic():
    # (2): lambda^2 + kappa lambda - u, u = ur + i ui: a root on the axis lambda = i y needs
    # -y^2 + i kappa y - ur - i ui = 0, i.e. y = ui / kappa and ur = -y^2: the boundary kappa^2 (-ur) = ui^2
    y, ur, ui = sp.symbols('y u_r u_i', real=True)
    k = sp.Symbol('k', positive=True)
    e = sp.expand(-y**2 + sp.I * k * y - ur - sp.I * ui)
    sol = sp.solve([sp.re(e), sp.im(e)], [y, ur], dict=True)
    assert len(sol) == 1 and sp.simplify(sol[0][ur] + ui**2 / k**2) == 0
    # the stable side: u = -1 (real, negative): roots in Re < 0; numerically over random points
    rng = random.Random(1)
    for _ in range(2000):
        kk = rng.uniform(0.01, 10)
        uu = complex(rng.uniform(-10, 10), rng.uniform(-10, 10))
        r = [complex(x) for x in mp.polyroots([1, kk, -uu])]
        stable = max(x.real for x in r) < 0
        pred = kk**2 * (-uu.real) > uu.imag**2
        if abs(kk**2 * (-uu.real) - uu.imag**2) > 1e-9:
            assert stable == pred, (kk, uu, r)
    ok('light balls (2): lambda^2 + kappa lambda - u stable iff kappa^2 (-Re u) > (Im u)^2 (boundary solved, 2000 points)')


def check_L1_L2():
    # (3): the quartic (u - aG)(u - a conj G) = (q a |G|)^2, u = lambda^2 + kappa lambda, expanded:
    # lambda^4 + 2 kappa lambda^3 + (kappa^2 - 2 a Re G) lambda^2 - 2 a kappa Re G lambda + a^2 |G|^2 (1 - q^2),
    # against (L1), (L2) at random points (roots by mpmath)
    l_, kk_, a_, Gr_, Gi_, q_ = sp.symbols('l kk a Gr Gi q', real=True)
    uu = l_**2 + kk_ * l_
    G_ = Gr_ + sp.I * Gi_
    quart = sp.expand((uu - a_ * G_) * (uu - a_ * sp.conjugate(G_)) - q_**2 * a_**2 * G_ * sp.conjugate(G_))
    want = (l_**4 + 2 * kk_ * l_**3 + (kk_**2 - 2 * a_ * Gr_) * l_**2 - 2 * a_ * kk_ * Gr_ * l_
            + a_**2 * (Gr_**2 + Gi_**2) * (1 - q_**2))
    assert sp.expand(quart - want) == 0
    rng = random.Random(2)
    n = 0
    for _ in range(4000):
        G = complex(rng.uniform(-1, 1), rng.uniform(-1, 1))
        a = 10**rng.uniform(-2, 2)
        q = rng.uniform(0, 0.999)
        kk = 10**rng.uniform(-2, 1.5)
        cf = [1, 2 * kk, kk * kk - 2 * a * G.real, -2 * a * kk * G.real, a * a * abs(G)**2 * (1 - q * q)]
        # NumPy's roots (companion eigenvalues) decide the sign of max Re when it is clear of the
        # axis by 1e-3 of the roots' size (far beyond their error, even for a triple root); the
        # rest get mpmath's roots and the 1e-9 rule below, as before (the same points, 18 -> 1 s)
        r = [complex(x) for x in np.roots(cf)]
        mre = max(x.real for x in r)
        if abs(mre) < 1e-3 * max(1.0, max(abs(x) for x in r)):
            r = [complex(x) for x in mp.polyroots(cf, maxsteps=200, extraprec=60)]
            mre = max(x.real for x in r)
        pred = G.real < 0 and kk**2 * (-G.real) > a * (G.imag**2 - q * q * abs(G)**2)
        if abs(mre) < 1e-9 * max(1.0, max(abs(x) for x in r)):
            continue
        assert (mre < 0) == pred, (G, a, q, kk, r)
        n += 1
    ok('light balls (3): ball roots stable iff (L1) Re G < 0 and (L2) kappa^2 (-Re G) > a (Im^2 G - q^2 |G|^2), '
       '%d random points' % n)


def check_high_speed():
    P, D, N = polys()
    Ap = sp.Symbol('Ap', nonzero=True)  # A - C
    e = sp.Symbol('e', positive=True)   # 1/omega
    # G = N/D at lambda = 0 in e = 1/omega: N has degree 2 and D degree 4 in omega, so
    # G = e^2 Nt/Dt with the polynomials Nt = e^2 N(1/e), Dt = e^4 D(1/e) (no simplify() of the
    # quotient: that took 25 s)
    N0 = N.subs(lam, 0).subs(C, A - Ap)
    D0 = D.subs(lam, 0).subs(C, A - Ap)
    assert sp.degree(N0, w) == 2 and sp.degree(D0, w) == 4
    Nt = sp.expand(N0.subs(w, 1 / e) * e**2)
    Dt = sp.expand(D0.subs(w, 1 / e) * e**4)
    assert Nt.is_polynomial(e) and Dt.is_polynomial(e) and Dt.subs(e, 0) != 0
    Gs = e**2 * Nt / Dt
    ser = sp.series(Gs, e, 0, 4).removeO()
    re2 = sp.simplify(sp.re(sp.expand(ser)).coeff(e, 2))
    im3 = sp.simplify(sp.im(sp.expand(ser)).coeff(e, 3))
    ginf = 1 / M + d**2 / Ap
    eta = h / M**2 - 2 * d * hc / (M * Ap) + d**2 * ht / Ap**2
    # sympy treats the symbols as real: re/im act on the coefficients of the series
    assert sp.simplify(re2 + ginf) == 0, re2
    assert sp.simplify(im3 + eta) == 0, im3
    assert sp.simplify(sp.re(sp.expand(ser)).coeff(e, 1)) == 0 and sp.simplify(sp.im(sp.expand(ser)).coeff(e, 2)) == 0
    # (L2) at q = 0: kappa^2 > a Im^2 G / (-Re G) -> (m_b w^4/2) eta^2 e^6 / (ginf e^2) = m_b eta^2 / (2 ginf)
    kinf2 = sp.limit(mb / (2 * e**4) * (im3 * e**3)**2 / (-re2 * e**2), e, 0)
    target = (sp.sqrt(mb * ginf / 2) * eta / ginf)**2
    assert sp.simplify(kinf2 - target) == 0
    ok('high speed (4): Re G w^2 -> -(1/M + d^2/(A-C)), Im G w^3 -> -(h/M^2 - 2 d h_c/(M(A-C)) + d^2 h_t/(A-C)^2), '
       'kappa_inf = sqrt(m_b g/2) eta/g')


def check_pendulum():
    # planar case: d = 0, c_c = h_c = 0: G = 1/K11(i w) = 1/(c - M w^2 + i h w); pendulum variables
    Rw, Rm, H, hh, W, k = sp.symbols('R_w R_m H h W k', positive=True)
    w0 = sp.Symbol('omega_0', positive=True)
    m = sp.Symbol('m', positive=True)   # one ball; m_b = 2 m
    Mv = m / Rm
    sub = {M: Mv, c: Mv * w0**2, h: H * w0 * Mv, w: Rw * w0, mb: 2 * m}
    Gx = 1 / (c - M * w**2 + sp.I * h * w)
    Gx = Gx.subs(sub)
    Gr, Gi = sp.simplify(sp.re(Gx)), sp.simplify(sp.im(Gx))
    # (7): Re G < 0 iff R_w > 1
    assert sp.simplify(Gr * (Mv * w0**2) * ((1 - Rw**2)**2 + H**2 * Rw**2) - (1 - Rw**2)) == 0
    kap_ = hh * w0  # the pendulum's h = kappa / omega0
    a = sp.Rational(1, 2) * 2 * m * (Rw * w0)**4
    q2 = 1 - k
    L2 = sp.simplify((kap_**2 * (-Gr) - a * (Gi**2 - q2 * (Gr**2 + Gi**2))) * (Mv * w0**2) * ((1 - Rw**2)**2 + H**2 * Rw**2) ** 2
                     / (w0**2))
    # (8): q = 0 (k = 1), R_w -> infinity: h^2 > H^2 R_m
    lead = sp.limit(L2.subs(k, 1) / Rw**6, Rw, sp.oo)
    assert sp.simplify(lead - (hh**2 - H**2 * Rm)) == 0, lead
    # (9): leading order in H -> infinity: h^2 (W - 1) > R_m k W^2
    lead9 = sp.limit(L2.subs(Rw, sp.sqrt(W)) / H**2, H, sp.oo)
    assert sp.simplify(lead9 / W - (hh**2 * (W - 1) - Rm * k * W**2)) == 0, lead9
    ok('pendulum (5): (L1) is (7) R_w > 1; (L2) at q = 0, R_w -> oo is (8) h > H sqrt(R_m); (L2) for H -> oo is the corrected (9)')


def pmul(a, b):
    r = [mp.mpc(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            r[i + j] += x * y
    return r


def padd(a, b):
    n = max(len(a), len(b))
    return [(a[i] if i < len(a) else 0) + (b[i] if i < len(b) else 0) for i in range(n)]


def pscale(a, s_):
    return [x * s_ for x in a]


def peval(a, z):
    v = mp.mpc(0)
    for x in reversed(a):
        v = v * z + x
    return v


def check_rotor_shift():
    # Delta built here in 60-digit complex arithmetic (ascending coefficient lists), default rotor at 500 rad/s
    mp.mp.dps = 60
    Mv, Av, Cv, cv, ctv, ccv = mp.mpf(10), mp.mpf('0.16'), mp.mpf('0.03'), mp.mpf(250000), mp.mpf(7375), mp.mpf(-2500)
    hv, htv, hcv, dv, wv, kv = mp.mpf(250), mp.mpf('7.375'), mp.mpf('-2.5'), mp.mpf('0.1'), mp.mpf(500), mp.mpf(2)
    P = [mp.mpc(0, wv), mp.mpc(1)]
    Pb = [mp.mpc(0, -wv), mp.mpc(1)]
    P2 = pmul(P, P)
    K11 = padd(padd(pscale(P2, Mv), pscale(P, hv)), [cv])
    K12 = pscale(padd(pscale(P, hcv), [ccv]), -1)
    K22 = padd(padd(pscale(P2, Av), pscale(P, mp.mpc(htv, -Cv * wv))), [ctv])
    D = padd(pmul(K11, K22), pscale(pmul(K12, K12), -1))
    N = padd(padd(K22, pscale(K12, -2 * dv)), pscale(K11, dv * dv))
    Dd = [i * D[i] for i in range(1, len(D))]
    P4 = pmul(P2, P2)
    Pb4 = pmul(pmul(Pb, Pb), pmul(Pb, Pb))
    conjp = lambda a: [mp.conj(x) for x in a]
    droots = mp.polyroots(list(reversed(D)), maxsteps=400, extraprec=200)
    errs = []
    for m_b in (mp.mpf('2e-6'), mp.mpf('2e-7')):
        Qv = m_b * mp.mpf('0.3')
        F = padd(pmul([0, kv, 1], D), pscale(pmul(P4, N), -m_b / 2))
        De = padd(pmul(F, conjp(F)), pscale(pmul(pmul(P4, Pb4), pmul(N, conjp(N))), -(Qv / 2)**2))
        rts = mp.polyroots([mp.re(x) for x in reversed(De)], maxsteps=800, extraprec=400)
        worst = mp.mpf(0)
        for lk in droots:
            shift = m_b / 2 * peval(P4, lk) * peval(N, lk) / ((lk * lk + kv * lk) * peval(Dd, lk))
            pred = lk + shift
            near = min(rts, key=lambda z: abs(z - pred))
            worst = max(worst, abs(near - pred) / abs(shift))
        errs.append(float(worst))
    # second order: the relative error of the shift falls like m_b (ratio ~10 for a tenfold lighter ball)
    assert errs[1] < 0.2 * errs[0] and errs[1] < 1e-3, errs
    ok('rotor roots (6): first-order shift of the roots of D vs the roots of Delta, relative error %.2e -> %.2e for m_b 2e-6 -> 2e-7 kg'
       % (errs[0], errs[1]))


def main():
    check_light_reduction()
    check_quadratic()
    check_L1_L2()
    check_high_speed()
    check_pendulum()
    check_rotor_shift()
    print('derive_asymptotic: all checks passed')
    return 0


if __name__ == '__main__':
    sys.exit(main())
