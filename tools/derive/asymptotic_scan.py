#!/usr/bin/python3
"""The numbers of docs/rotor.md "Asymptotic conditions", recomputed with NumPy/SciPy from the formula of
Delta (independent of the C code): the light-ball prediction against the exact roots of Delta over random
machines (the scan), and the exact critical ball damping at q = 0 against kappa_inf (the high-speed table).

Run:  /usr/bin/python3 tools/derive/asymptotic_scan.py [scan|kappa|all]    (a few minutes)
"""
import sys

import numpy as np
from numpy.polynomial import polynomial as Pn
from scipy.optimize import brentq


def mul(*ps):
    r = np.array([1.0 + 0j])
    for p in ps:
        r = Pn.polymul(r, p)
    return r


def add(a, b):
    return Pn.polyadd(a, b)


def sc(a, s):
    return np.asarray(a) * s


def default():
    return dict(M=10., A=0.16, C=0.03, c=2.5e5, ct=7375., cc=-2500., h=250., ht=7.375, hc=-2.5, d=0.1,
                m=0.05, r=0.1, s0=0.002, hb=0.1)


def delta(p, w):
    """Delta of docs/rotor.md (two identical balls), ascending real coefficients, and its parts."""
    M, A, C, c, ct, cc, h, ht, hc, d = [p[k] for k in 'M A C c ct cc h ht hc d'.split()]
    mb = 2 * p['m']
    kap = p['hb'] / p['m']
    x = p['s0'] / (2 * p['m'] * p['r'])
    Q = abs(mb * (2 * x * x - 1))
    P = np.array([1j * w, 1.0])
    K11 = add(sc(mul(P, P), M), add(sc(P, h), [c]))
    K12 = sc(add(sc(P, hc), [cc]), -1)
    K22 = add(sc(mul(P, P), A), add(sc(P, ht - 1j * C * w), [ct]))
    D = add(mul(K11, K22), sc(mul(K12, K12), -1))
    N = add(add(K22, sc(K12, -2 * d)), sc(K11, d * d))
    P4 = mul(P, P, P, P)
    F = add(mul([0, kap, 1], D), sc(mul(P4, N), -mb / 2))
    Pb = np.array([-1j * w, 1.0])
    Pb4 = mul(Pb, Pb, Pb, Pb)
    De = add(mul(F, np.conj(F)), sc(mul(P4, Pb4, N, np.conj(N)), -(Q / 2)**2))
    return De.real, dict(D=D, N=N, Q=Q, mb=mb, kap=kap)


def margin(p, w):
    return np.roots(delta(p, w)[0][::-1]).real.max()


def light(p, w):
    """ball roots, their u, kappa, the bound c1, and the shifted rotor roots (root, shift, separation)"""
    _, dd = delta(p, w)
    D, N, kap, mb = dd['D'], dd['N'], dd['kap'], dd['mb']
    g = N[0] / D[0]
    a = mb * w**4 / 2
    b = dd['Q'] * w**4 / 2
    s = np.sqrt(complex(b * b * abs(g)**2 - a * a * g.imag**2))
    lam, us = [], []
    for u in (a * g.real + s, a * g.real - s):
        for l in np.roots([1, kap, -u]):
            lam.append(l)
            us.append(u)
    rDD = np.roots(mul(D, np.conj(D))[::-1])
    rNN = np.roots(mul(N, np.conj(N))[::-1])
    c1 = np.sum(1 / abs(rDD)) + np.sum(1 / abs(rNN)) + 4 / abs(w)
    rD = [r for r in rDD if abs(Pn.polyval(r, D)) < abs(Pn.polyval(r, np.conj(D)))]
    Dp = Pn.polyder(D)
    rot = []
    for lk in rD:
        dl = (mb / 2) * (lk + 1j * w)**4 * Pn.polyval(lk, N) / ((lk * lk + kap * lk) * Pn.polyval(lk, Dp))
        sep = min([abs(lk), abs(lk + kap)] + [abs(lk - r) for r in rDD if abs(r - lk) > 1e-12 * abs(lk)])
        rot.append((lk, dl, sep))
    return np.array(lam), np.array(us), kap, c1, rot


def scan(seed, lo, hi, th):
    rng = np.random.default_rng(seed)
    n_app = agree = undec = nunst = 0
    bad = []
    for _ in range(4000):
        p = default()
        p['M'] *= np.exp(rng.uniform(-1, 1)); p['A'] *= np.exp(rng.uniform(-1, 1)); p['C'] = p['A'] * rng.uniform(0, 2)
        p['c'] *= np.exp(rng.uniform(-1, 1)); p['ct'] *= np.exp(rng.uniform(-1, 1)); p['cc'] *= rng.uniform(-2, 2)
        if p['cc']**2 >= p['c'] * p['ct']:
            continue
        sh = np.exp(rng.uniform(lo, hi)); p['h'] *= sh; p['ht'] *= sh; p['hc'] *= sh * rng.uniform(-1, 1)
        p['d'] = rng.uniform(-0.3, 0.3)
        p['m'] *= np.exp(rng.uniform(np.log(1e-4), 0))
        p['s0'] = 2 * p['m'] * p['r'] * rng.uniform(0.02, 0.98)
        p['hb'] = p['m'] * np.exp(rng.uniform(np.log(0.01), np.log(100)))
        w = np.exp(rng.uniform(np.log(50), np.log(5000)))
        lam, us, kap, c1, rot = light(p, w)
        eps_b = max(c1 * abs(u) / abs(2 * l + kap) for l, u in zip(lam, us))
        eps_r = max(abs(dl) / sep for lk, dl, sep in rot)
        if max(eps_b, eps_r) > th:
            continue
        n_app += 1
        errs = [c1 * abs(l) * abs(u) / max(abs(2 * l + kap), 1e-300) for l, u in zip(lam, us)] + \
               [eps_r * abs(dl) for lk, dl, sep in rot]
        res = list(lam.real) + [(lk + dl).real for lk, dl, sep in rot]
        du = any(r >= e for r, e in zip(res, errs))
        ds = all(r <= -e for r, e in zip(res, errs))
        if not (du or ds):
            undec += 1
            continue
        nunst += not ds
        m = margin(p, w)
        if (m < 0) == ds:
            agree += 1
        else:
            bad.append((w, m, max(res)))
    print('scan seed %d, support damping factor e^[%g, %g], small <= %g: applicable %d, decided %d, agree %d '
          '(predicted unstable %d)' % (seed, lo, hi, th, n_app, n_app - undec, agree, nunst))
    for b_ in bad:
        print('   DISAGREES: omega %g, exact margin %g, predicted max Re %g' % b_)
    return not bad


def kthr(p, w):
    def f(kap):
        q = dict(p)
        q['hb'] = kap * q['m']
        return margin(q, w)
    ks = np.geomspace(1e-3, 1e3, 200)
    v = [f(k) for k in ks]
    return [brentq(f, ks[i], ks[i + 1], xtol=1e-12) for i in range(len(ks) - 1) if np.sign(v[i]) != np.sign(v[i + 1])]


def kinf(p):
    M, A, C, h, ht, hc, d = [p[k] for k in 'M A C h ht hc d'.split()]
    Ap = A - C
    g = 1 / M + d * d / Ap
    eta = h / M**2 - 2 * d * hc / (M * Ap) + d * d * ht / Ap**2
    return np.sqrt(p['m'] * g) * eta / g


def kappa_table():
    p = default()
    p['s0'] = np.sqrt(2) * p['m'] * p['r']
    print('default supports, q = 0, 0.05 kg balls: kappa_inf %.6g 1/s' % kinf(p))
    for w in (500, 1000, 2000, 5000, 1e4, 3e4):
        print('   omega %g: exact critical kappa %s' % (w, kthr(p, w)))
    for f in (0.1, 0.01):
        q = dict(p); q['m'] *= f; q['s0'] *= f
        print('   balls x %g, 1e4 rad/s: kappa_inf %.6g, exact %s' % (f, kinf(q), kthr(q, 1e4)))
    q = dict(p); q['d'] = 0.0; q['cc'] = q['hc'] = 0.0
    print('   d = 0, no coupling, 1e4 rad/s: kappa_inf %.6g, exact %s' % (kinf(q), kthr(q, 1e4)))


if __name__ == '__main__':
    what = sys.argv[1] if len(sys.argv) > 1 else 'all'
    okay = True
    if what in ('scan', 'all'):
        for s, lo, hi, th in ((2, -10, -3, 0.05), (3, -3, 2, 0.05), (4, -3, 2, 0.05), (5, -6, 2, 0.05),
                              (6, -6, 2, 0.2), (7, -6, 2, 0.2)):
            okay &= scan(s, lo, hi, th)
    if what in ('kappa', 'all'):
        kappa_table()
    sys.exit(0 if okay else 1)
