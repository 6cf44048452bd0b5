#!/usr/bin/python3
"""Two balancer planes: the light-ball prediction (docs/rotor.md "Asymptotic conditions", "Two planes")
against the exact roots of the closed two-plane system, recomputed here with NumPy from the equations of
docs/rotor.md "Two planes: degree 16" (independent of the C code), over random machines; and the
undamped-ball (kappa = 0) scan of the one-plane Delta.

Run:  /usr/bin/python3 tools/derive/asymptotic2_scan.py [scan|rich|high|every|kappa0|all] [n_draws]   (a few minutes)

Two planes j = 1, 2, each with two identical balls (mass m_j each, radius r_j, damping h_j, kappa_j = h_j / m_j,
unbalance m0_j r0_j at phase psi0_j).  Rotating complex coordinates (W, Theta, sigma_1, sigma_2) and their
conjugates; P = lambda + i omega, Pb = lambda - i omega:
    K(P) (W, Theta)^T + P^2 B sigma = 0,            B = [[1, 1], [d1, d2]],
    (lambda^2 + kappa_j lambda) sigma_j + (m_bj/2) P^2 b_j.(W, Theta) - (Q_j/2) Pb^2 b_j.(Wb, Thetab) = 0,
and the conjugate rows (K* at Pb, conj Q_j).  The exact roots: the 16 eigenvalues of its companion matrix.
The light-ball prediction: G = B^T K(i omega)^-1 B (2x2, symmetric), s = omega^4 / 2, the 4x4 quadratic
eigenproblem
    [diag(u_j) - s Mb G,  s Q conj(G);  s conj(Q) G,  diag(u_j) - s Mb conj(G)] (sigma; sigmab) = 0,
u_j = lambda^2 + kappa_j lambda (8 ball roots), plus the roots of D = det K shifted to first order,
    lambda_k + sum_j (m_bj/2) P^4 N_jj / ((lambda^2 + kappa_j lambda) D')   at lambda_k,  N = B^T adj(K) B.
"""
import sys

import mpmath as mp
import numpy as np
from numpy.polynomial import polynomial as Pn

TH = 0.05


def mul(*ps):
    r = np.array([1.0 + 0j])
    for p in ps:
        r = Pn.polymul(r, p)
    return r


def default2():
    # data/rotor_two_planes.ini in lumped form is not needed: random machines around the one-plane default
    return dict(M=10., A=0.16, C=0.03, c=2.5e5, ct=7375., cc=-2500., h=250., ht=7.375, hc=-2.5,
                d=[0.1, -0.12], m=[0.05, 0.04], r=[0.1, 0.09], s0=[0.002, 0.00135], psi0=[0.0, 2.0], hb=[0.1, 0.1])


def kpolys(p, w, conj=False):
    """K11, K12, K22 as ascending complex polynomials in lambda (P = lambda + i w, or Pb for conj)."""
    sgn = -1.0 if conj else 1.0
    P = np.array([sgn * 1j * w, 1.0])
    P2 = mul(P, P)
    K11 = Pn.polyadd(Pn.polyadd(p['M'] * P2, p['h'] * P), [p['c']])
    K12 = -Pn.polyadd(p['hc'] * P, [p['cc']])
    K22 = Pn.polyadd(Pn.polyadd(p['A'] * P2, (p['ht'] - sgn * 1j * p['C'] * w) * P), [p['ct']])
    return K11, K12, K22, P2


def qs(p):
    """Q_j = m_bj (2 x_j^2 - 1) e^{2 i psi0_j}, x_j = s0_j / (2 m_j r_j) (two identical balls)."""
    Q = []
    for j in range(2):
        x = p['s0'][j] / (2 * p['m'][j] * p['r'][j])
        Q.append(2 * p['m'][j] * (2 * x * x - 1) * np.exp(2j * p['psi0'][j]))
    return Q


def exact_roots(p, w):
    """The 16 roots of the closed two-plane system (companion of the 8x8 quadratic matrix polynomial)."""
    C = [np.zeros((8, 8), complex) for _ in range(3)]

    def put(i, k, poly):
        for n, v in enumerate(poly):
            C[n][i, k] += v

    d = p['d']
    mb = [2 * p['m'][j] for j in range(2)]
    kap = [p['hb'][j] / p['m'][j] for j in range(2)]
    Q = qs(p)
    for cj, off, ooff in ((False, 0, 4), (True, 4, 0)):
        K11, K12, K22, P2 = kpolys(p, w, cj)
        _, _, _, P2o = kpolys(p, w, not cj)
        put(off + 0, off + 0, K11); put(off + 0, off + 1, K12)
        put(off + 1, off + 0, K12); put(off + 1, off + 1, K22)
        for j in range(2):
            put(off + 0, off + 2 + j, P2)
            put(off + 1, off + 2 + j, d[j] * P2)
            put(off + 2 + j, off + 2 + j, [0, kap[j], 1])
            put(off + 2 + j, off + 0, mb[j] / 2 * P2)
            put(off + 2 + j, off + 1, mb[j] / 2 * d[j] * P2)
            qj = np.conj(Q[j]) if cj else Q[j]
            put(off + 2 + j, ooff + 0, -qj / 2 * P2o)
            put(off + 2 + j, ooff + 1, -qj / 2 * d[j] * P2o)
    Minv = np.linalg.inv(C[2])
    comp = np.zeros((16, 16), complex)
    comp[:8, 8:] = np.eye(8)
    comp[8:, :8] = -Minv @ C[0]
    comp[8:, 8:] = -Minv @ C[1]
    return np.linalg.eigvals(comp)


def ball_system(G, mb, Q, kap, w):
    """The frozen 4x4 ball system of two planes, S = (w^4/2) [[Mb G, -Q conj G], [-conj Q G, Mb conj G]], and the
    8x8 companion matrix of det(lambda^2 + kappa lambda - S) (docs/rotor.md "Two planes at high speed")."""
    s = w**4 / 2
    S = np.zeros((4, 4), complex)
    S[:2, :2] = s * np.diag(mb) @ G
    S[:2, 2:] = -s * np.diag(Q) @ np.conj(G)
    S[2:, :2] = -s * np.diag(np.conj(Q)) @ G
    S[2:, 2:] = s * np.diag(mb) @ np.conj(G)
    comp = np.zeros((8, 8), complex)
    comp[:4, 4:] = np.eye(4)
    comp[4:, :4] = S
    comp[4:, 4:] = -np.diag(np.concatenate([kap, kap]))
    return S, comp


def high_modes(p):
    """At Q1 = Q2 = 0: (mu_k, kbar_k, kappa_inf_k, kappa_j) of the high-speed modes (H1'), (H2'), as the library
    (autobal_rotor_asymptotic2_conditions): mu, Z the eigenpairs of M_b^1/2 Gamma M_b^1/2, kbar_k = Z_k^T diag(kappa)
    Z_k, kappa_inf_k = |Z_k^T H~ Z_k| / sqrt(2 mu_k)."""
    M, Ap = p['M'], p['A'] - p['C']
    B = np.array([[1.0, 1.0], [p['d'][0], p['d'][1]]])
    Mi = np.diag([1 / M, 1 / Ap])
    Hs = np.array([[p['h'], -p['hc']], [-p['hc'], p['ht']]])
    Sq = np.diag(np.sqrt([2 * p['m'][0], 2 * p['m'][1]]))
    Gt = Sq @ B.T @ Mi @ B @ Sq
    Ht = Sq @ B.T @ Mi @ Hs @ Mi @ B @ Sq
    kap = np.array([p['hb'][j] / p['m'][j] for j in range(2)])
    mu, Z = np.linalg.eigh(Gt)
    if mu.min() <= 0:
        return mu, None, None, kap  # (H1') fails: no high-speed modes
    kbar = np.array([Z[:, k] @ np.diag(kap) @ Z[:, k] for k in range(2)])
    kinf = np.array([abs(Z[:, k] @ Ht @ Z[:, k]) for k in range(2)]) / np.sqrt(2 * mu)
    return mu, kbar, kinf, kap


def light2(p, w):
    """The two-plane light-ball prediction: (residual real parts, error bounds, small parameter)."""
    d = p['d']
    mb = np.array([2 * p['m'][j] for j in range(2)])
    kap = np.array([p['hb'][j] / p['m'][j] for j in range(2)])
    Q = np.array(qs(p))
    K11, K12, K22, _ = kpolys(p, w)
    D = Pn.polysub(mul(K11, K22), mul(K12, K12))
    # N_jk = b_j^T adj(K) b_k, adj(K) = [[K22, -K12], [-K12, K11]], b_j = (1, d_j)
    Nm = [[Pn.polyadd(Pn.polyadd(K22, -(d[j] + d[k]) * K12), d[j] * d[k] * K11) for k in range(2)] for j in range(2)]
    G = np.array([[Nm[j][k][0] / D[0] for k in range(2)] for j in range(2)])
    S, comp = ball_system(G, mb, Q, kap, w)
    kk = np.concatenate([kap, kap])
    s = w**4 / 2
    lam = np.linalg.eigvals(comp)
    # error of each ball root: the frozen entries S_ab(0) against S_ab(lambda); |dS_ab| bounded entrywise by
    # |s_ab| [ (|N1| |l| + |N2| |l|^2) / |D0| + |G_ab| (c_D + 4/|w|) |l| ], c_D = sum 1/|root of D D*|;
    # the root moves by sum |adj(U - S)_ba| |dS_ab| / |p'(l)|, p = det(U - S)
    rDD = np.roots(mul(D, np.conj(D))[::-1])
    cD = np.sum(1 / abs(rDD)) + 4 / abs(w)
    sc = np.zeros((4, 4))
    Gb = np.block([[G, np.conj(G)], [G, np.conj(G)]])
    Nb = [[Nm[j % 2][k % 2] for k in range(4)] for j in range(4)]
    errs, res = [], []
    eps_b = 0.0
    for l in lam:
        U = np.diag(l * l + kk * l)
        A_ = U - S
        adj = np.linalg.det(A_) * np.linalg.inv(A_) if abs(np.linalg.det(A_)) > 0 else None
        # adj via cofactors (A_ is singular at an eigenvalue)
        adj = np.zeros((4, 4), complex)
        for i in range(4):
            for k in range(4):
                mnr = np.delete(np.delete(A_, i, 0), k, 1)
                adj[k, i] = (-1)**(i + k) * np.linalg.det(mnr)
        dp = sum(adj[i, i] * (2 * l + kk[i]) for i in range(4))
        e = 0.0
        for a_ in range(4):
            for b_ in range(4):
                N_ = Nb[a_][b_]
                dn = (abs(N_[1]) * abs(l) + abs(N_[2]) * abs(l)**2) / abs(D[0])
                sab = abs(S[a_, b_]) / max(abs(Gb[a_, b_]), 1e-300)
                e += abs(adj[b_, a_]) * sab * (dn + abs(Gb[a_, b_]) * cD * abs(l))
        e /= max(abs(dp), 1e-300)
        errs.append(e)
        res.append(l.real)
        eps_b = max(eps_b, e / max(abs(l), 1e-300))
    # rotor roots: the roots of D shifted to first order
    rD = np.roots(D[::-1])
    Dp = Pn.polyder(D)
    eps_r = 0.0
    shifts = []
    for lk in rD:
        P4 = (lk + 1j * w)**4
        dl = sum(mb[j] / 2 * P4 * Pn.polyval(lk, Nm[j][j]) / ((lk * lk + kap[j] * lk) * Pn.polyval(lk, Dp))
                 for j in range(2))
        sep = min([abs(lk), abs(lk + kap[0]), abs(lk + kap[1])] +
                  [abs(lk - r) for r in rDD if abs(r - lk) > 1e-12 * abs(lk)])
        eps_r = max(eps_r, abs(dl) / sep)
        shifts.append((lk, dl))
    for lk, dl in shifts:
        res.append((lk + dl).real)
        errs.append(eps_r * abs(dl))
    return np.array(res), np.array(errs), max(eps_b, eps_r), lam, G


def draw(rng, rich=False):
    p = default2()
    p['M'] *= np.exp(rng.uniform(-1, 1)); p['A'] *= np.exp(rng.uniform(-1, 1)); p['C'] = p['A'] * rng.uniform(0, 2)
    p['c'] *= np.exp(rng.uniform(-1, 1)); p['ct'] *= np.exp(rng.uniform(-1, 1)); p['cc'] *= rng.uniform(-2, 2)
    if p['cc']**2 >= p['c'] * p['ct']:
        return None
    sh = np.exp(rng.uniform(-6, 2)); p['h'] *= sh; p['ht'] *= sh; p['hc'] *= sh * rng.uniform(-1, 1)
    p['d'] = [rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)]
    p['m'] = [0.05 * np.exp(rng.uniform(np.log(1e-4), 0)) for _ in range(2)]
    p['r'] = [0.1, 0.1]
    p['s0'] = [2 * p['m'][j] * p['r'][j] * rng.uniform(0.02, 0.98) for j in range(2)]
    p['psi0'] = [rng.uniform(0, 2 * np.pi), rng.uniform(0, 2 * np.pi)]
    klo = np.log(0.3) if rich else np.log(0.01)
    p['hb'] = [p['m'][j] * np.exp(rng.uniform(klo, np.log(100))) for j in range(2)]
    return p


def scan(seed, n, th=TH, rich=False):
    """rich: omega in [300, 5000] rad/s and kappa in [0.3, 100] 1/s (more points predicted STABLE)"""
    rng = np.random.default_rng(seed)
    n_app = n_dec = agree = nunst = 0
    bad = []
    for _ in range(n):
        p = draw(rng, rich)
        if p is None:
            continue
        w = np.exp(rng.uniform(np.log(300 if rich else 50), np.log(5000)))
        res, errs, small, _, _ = light2(p, w)
        if not small <= th:
            continue
        n_app += 1
        du = bool(np.any(res >= errs))
        ds = bool(np.all(res <= -errs))
        if not (du or ds):
            continue
        n_dec += 1
        nunst += not ds
        m = exact_roots(p, w).real.max()
        if (m < 0) == ds:
            agree += 1
        else:
            bad.append((w, m, res.max(), small))
    print('two planes, scan seed %d%s, %d draws, small <= %g: applicable %d, decided %d, agree %d (predicted unstable %d)'
          % (seed, ' (rich)' if rich else '', n, th, n_app, n_dec, agree, nunst))
    for b_ in bad:
        print('   DISAGREES: omega %g, exact margin %g, predicted max Re %g, small %g' % b_)
    return not bad


# ---- two planes at high speed, balls at q = 0 in both planes (docs/rotor.md "Two planes at high speed") ----------

def wmax_cD(p, w):
    """The highest undamped natural frequency at rest and c_D = 4/|w| + sum 1/|s| over the roots of D D*, as the
    library's two-plane high-speed small parameters use them."""
    M = p['M']
    tr = p['c'] / M + p['ct'] / p['A']
    det = (p['c'] * p['ct'] - p['cc']**2) / (M * p['A'])
    wmax = np.sqrt(0.5 * (tr + np.sqrt(max(0, tr * tr - 4 * det))))
    K11, K12, K22, _ = kpolys(p, w)
    D = Pn.polysub(mul(K11, K22), mul(K12, K12))
    return wmax, np.sum(1 / abs(np.roots(mul(D, np.conj(D))[::-1]))) + 4 / abs(w)


def high2(p, w):
    """The (H1'), (H2') prediction at Q1 = Q2 = 0 as the library computes it (autobal_rotor_asymptotic2_conditions):
    (larger real part per mode, its error, small parameter), or None when Gamma is not positive definite."""
    mu, kbar, kinf, kap = high_modes(p)
    if mu.min() <= 0:
        return None
    wmax, cD = wmax_cD(p, w)
    gap = abs(w) * abs(np.sqrt(mu[0] / 2) - np.sqrt(mu[1] / 2))
    small = max(abs(w) * np.sqrt(mu.max() / 2) * cD, wmax / abs(w), (kap.max() + kinf.max()) / gap)
    return (kinf - kbar) / 2, small * (kbar + kinf) / 2, small, kinf


def high(seed, n, th=TH, rich=False):
    """random two-plane machines (draw(), balls scaled by 1e-4..0.1), Q1 = Q2 = 0, omega in [2000, 50000] rad/s
    (20 % negative); rich: kappa_j = max kappa_inf_k times e^U(-1, 1) (near the boundary).  Exact: the 16 roots."""
    rng = np.random.default_rng(seed)
    nm = n_app = n_dec = agree = nps = 0
    bad = []
    for _ in range(n):
        p = draw(rng)
        if p is None:
            continue
        w = np.exp(rng.uniform(np.log(2000), np.log(50000))) * (1 if rng.uniform() < 0.8 else -1)
        fm = np.exp(rng.uniform(np.log(1e-4), np.log(1e-1)))
        p['m'] = [x * fm for x in p['m']]
        p['hb'] = [x * fm for x in p['hb']]
        p['s0'] = [np.sqrt(2) * p['m'][j] * p['r'][j] for j in range(2)]  # Q_j = 0
        r = high2(p, w)
        if r is None:
            continue
        if rich:
            ks = r[3].max()
            p['hb'] = [p['m'][j] * ks * np.exp(rng.uniform(-1, 1)) for j in range(2)]
            r = high2(p, w)
        nm += 1
        re, err, small, _ = r
        if not small <= th:
            continue
        n_app += 1
        du = bool(np.any(re >= err))
        ds = bool(np.all(re <= -err))
        if not (du or ds):
            continue
        n_dec += 1
        nps += ds
        m = exact_roots(p, w).real.max()
        if (m < 0) == ds:
            agree += 1
        else:
            bad.append((w, m, re.max(), small))
    print('two planes, high speed, Q = 0, seed %d%s: %d machines (Gamma positive definite), small <= %g: applicable %d, '
          'decided %d, agree %d (predicted STABLE %d)' % (seed, ' (rich)' if rich else '', nm, th, n_app, n_dec, agree, nps))
    for b_ in bad:
        print('   DISAGREES: omega %g, exact margin %g, predicted max Re %g, small %g' % b_)
    return not bad


def high_every(seed=11, n_mach=150, n_q=40):
    """Machines where (H2') is decided STABLE at Q = 0 (kappa_j = max kappa_inf_k e^U(0.1, 1), small <= 0.05) and
    exactly stable there: the exact verdict at n_q random unbalances (q_j, phases) each."""
    rng = np.random.default_rng(seed)
    nm = nq = nun = 0
    worst = -np.inf
    for _ in range(40 * n_mach):
        p = draw(rng)
        if p is None:
            continue
        w = np.exp(rng.uniform(np.log(2000), np.log(50000)))
        fm = np.exp(rng.uniform(np.log(1e-4), np.log(1e-1)))
        p['m'] = [x * fm for x in p['m']]
        p['hb'] = [x * fm for x in p['hb']]
        p['s0'] = [np.sqrt(2) * p['m'][j] * p['r'][j] for j in range(2)]
        r = high2(p, w)
        if r is None:
            continue
        p['hb'] = [p['m'][j] * r[3].max() * np.exp(rng.uniform(0.1, 1)) for j in range(2)]
        re, err, small, _ = high2(p, w)
        if not (small <= TH and np.all(re <= -err)) or exact_roots(p, w).real.max() >= 0:
            continue
        nm += 1
        for _ in range(n_q):
            q = dict(p)
            q['s0'] = [2 * p['m'][j] * p['r'][j] * rng.uniform(0.02, 0.98) for j in range(2)]
            q['psi0'] = [rng.uniform(0, 2 * np.pi), rng.uniform(0, 2 * np.pi)]
            m = exact_roots(q, w).real.max()
            nq += 1
            nun += m >= 0
            worst = max(worst, m)
        if nm >= n_mach:
            break
    print('two planes, high speed: %d machines with (H2\') decided STABLE and exactly stable at Q = 0; %d random '
          'unbalances: exactly unstable %d (largest margin %.3g 1/s)' % (nm, nq, nun, worst))
    return True


def crossings(seed=1, f=1e-3, w=2e4):
    """The default two-plane machine (balls x f) at w: points (q1, q2, phase of Q2 / Q1) where two leading-order
    ball roots coincide (Nelder-Mead on the smallest gap of the eigenvalues of T = (1/2)[[Mb, -Q], [-conj Q, Mb]]
    diag(Gamma, Gamma)), and the exact margin there and 0.02 away in q1 for ball damping 0.01, 0.3 and 1.2 times
    max kappa_inf_k (of Q = 0)."""
    from scipy.optimize import minimize
    p = default2()
    p['m'] = [x * f for x in p['m']]
    M, Ap = p['M'], p['A'] - p['C']
    B = np.array([[1.0, 1.0], [p['d'][0], p['d'][1]]])
    Gam = B.T @ np.diag([1 / M, 1 / Ap]) @ B
    mb = np.array([2 * p['m'][0], 2 * p['m'][1]])

    def gap(x):
        Q = np.diag([mb[0] * x[0], mb[1] * x[1] * np.exp(1j * x[2])])
        T = 0.5 * np.block([[np.diag(mb), -Q], [-np.conj(Q), np.diag(mb)]]) @ np.kron(np.eye(2), Gam)
        e = np.sort(np.linalg.eigvals(T).real)
        return min(np.diff(e)) / e.max()
    p['s0'] = [np.sqrt(2) * p['m'][j] * p['r'][j] for j in range(2)]
    p['hb'] = list(p['m'])
    kmax = high2(p, w)[3].max()
    rng = np.random.default_rng(seed)
    found = []
    for _ in range(60):
        r = minimize(gap, [rng.uniform(0.05, 0.95), rng.uniform(0.05, 0.95), rng.uniform(0, 2 * np.pi)],
                     method='Nelder-Mead', options=dict(xatol=1e-10, fatol=1e-14, maxiter=4000))
        if r.fun < 1e-7 and 0.02 < r.x[0] < 0.96 and 0.02 < r.x[1] < 0.98:
            found.append(r.x)
    print('crossings of the leading-order ball roots (default machine, balls x %g, %g rad/s): %d found; max kappa_inf '
          '(Q = 0) %.5g 1/s' % (f, w, len(found), kmax))
    for fac in (0.01, 0.3, 1.2):
        for dq in (0.0, 0.02):
            ms = []
            for x in found[:12]:
                q = dict(p)
                q['hb'] = [p['m'][j] * fac * kmax for j in range(2)]
                q['s0'] = [2 * p['m'][j] * p['r'][j] * np.sqrt((1 + [x[0] + dq, x[1]][j]) / 2) for j in range(2)]
                q['psi0'] = [0.0, x[2] / 2]
                ms.append(exact_roots(q, w).real.max())
            print('   kappa = %.2f max kappa_inf, %s: exact margins %.3g .. %.3g 1/s, %d of %d unstable'
                  % (fac, 'at the crossings' if dq == 0 else '0.02 away in q1', min(ms), max(ms),
                     sum(m >= 0 for m in ms), len(ms)))
    return True


# ---- kappa = 0: the one-plane Delta with undamped balls ----------------------------------------------

def delta1(p, w):
    """Delta of docs/rotor.md (one plane, two identical balls), ascending real coefficients."""
    M, A, C, c, ct, cc, h, ht, hc, d = [p[k] for k in 'M A C c ct cc h ht hc d'.split()]
    mb = 2 * p['m']
    kap = p['hb'] / p['m']
    x = p['s0'] / (2 * p['m'] * p['r'])
    Q = abs(mb * (2 * x * x - 1))
    P = np.array([1j * w, 1.0])
    K11 = Pn.polyadd(M * mul(P, P), Pn.polyadd(h * P, [c]))
    K12 = -Pn.polyadd(hc * P, [cc])
    K22 = Pn.polyadd(A * mul(P, P), Pn.polyadd((ht - 1j * C * w) * P, [ct]))
    D = Pn.polysub(mul(K11, K22), mul(K12, K12))
    N = Pn.polyadd(Pn.polyadd(K22, -2 * d * K12), d * d * K11)
    P4 = mul(P, P, P, P)
    F = Pn.polysub(mul([0, kap, 1], D), mb / 2 * mul(P4, N))
    Pb = np.array([-1j * w, 1.0])
    De = Pn.polysub(mul(F, np.conj(F)), (Q / 2)**2 * mul(P4, mul(Pb, Pb, Pb, Pb), N, np.conj(N)))
    return De.real


def one_polys(p, w):
    M, A, C, c, ct, cc, h, ht, hc, d = [p[k] for k in 'M A C c ct cc h ht hc d'.split()]
    P = np.array([1j * w, 1.0])
    K11 = Pn.polyadd(M * mul(P, P), Pn.polyadd(h * P, [c]))
    K12 = -Pn.polyadd(hc * P, [cc])
    K22 = Pn.polyadd(A * mul(P, P), Pn.polyadd((ht - 1j * C * w) * P, [ct]))
    D = Pn.polysub(mul(K11, K22), mul(K12, K12))
    N = Pn.polyadd(Pn.polyadd(K22, -2 * d * K12), d * d * K11)
    return K11, K12, K22, D, N

def exact1(p, w):
    """12 roots of the closed one-plane system: companion of the 6x6 quadratic matrix polynomial"""
    Cm = [np.zeros((6, 6), complex) for _ in range(3)]
    def put(i, k, poly):
        for n, v in enumerate(poly):
            Cm[n][i, k] += v
    d = p['d']; mb = 2 * p['m']; kap = p['hb'] / p['m']
    x = p['s0'] / (2 * p['m'] * p['r'])
    Q = mb * (2 * x * x - 1)
    for cj, off, ooff in ((False, 0, 3), (True, 3, 0)):
        sg = -1.0 if cj else 1.0
        P = np.array([sg * 1j * w, 1.0]); P2 = mul(P, P)
        Po = np.array([-sg * 1j * w, 1.0]); P2o = mul(Po, Po)
        K11 = Pn.polyadd(Pn.polyadd(p['M'] * P2, p['h'] * P), [p['c']])
        K12 = -Pn.polyadd(p['hc'] * P, [p['cc']])
        K22 = Pn.polyadd(Pn.polyadd(p['A'] * P2, (p['ht'] - sg * 1j * p['C'] * w) * P), [p['ct']])
        put(off, off, K11); put(off, off + 1, K12); put(off + 1, off, K12); put(off + 1, off + 1, K22)
        put(off, off + 2, P2); put(off + 1, off + 2, d * P2)
        put(off + 2, off + 2, [0, kap, 1])
        put(off + 2, off, mb / 2 * P2); put(off + 2, off + 1, mb / 2 * d * P2)
        put(off + 2, ooff, -Q / 2 * P2o); put(off + 2, ooff + 1, -Q / 2 * d * P2o)
    Minv = np.linalg.inv(Cm[2])
    comp = np.zeros((12, 12), complex)
    comp[:6, 6:] = np.eye(6)
    comp[6:, :6] = -Minv @ Cm[0]
    comp[6:, 6:] = -Minv @ Cm[1]
    return np.linalg.eigvals(comp)

def k0pred(p, w):
    """kappa = 0, one plane: predicted real parts, error bounds, small parameter, branch"""
    K11, K12, K22, D, N = one_polys(p, w)
    mb = 2 * p['m']
    x = p['s0'] / (2 * p['m'] * p['r'])
    q = abs(2 * x * x - 1)
    P = np.array([1j * w, 1.0])
    num = mul(P, P, P, P, N)
    g0 = mb / 2 * num[0] / D[0]
    h0 = num[0] / D[0]; h1 = (num[1] - h0 * D[1]) / D[0]; h2 = (num[2] - h1 * D[1] - h0 * D[2]) / D[0]
    g1 = mb / 2 * h1; g2 = mb / 2 * h2
    rDD = np.roots(mul(D, np.conj(D))[::-1]); rNN = np.roots(mul(N, np.conj(N))[::-1])
    c1 = np.sum(1 / abs(rDD)) + np.sum(1 / abs(rNN)) + 4 / abs(w)
    disc = q * q * abs(g0)**2 - g0.imag**2
    res, errs, eps = [], [], 0.0
    axis = disc > 0 and g0.real + np.sqrt(disc) < 0
    if axis:
        r = np.sqrt(disc)
        ys = [np.sqrt(-(g0.real + sg * r)) for sg in (1, -1)]
        lam0 = [1j * ys[0], -1j * ys[0], 1j * ys[1], -1j * ys[1]]
        for i, sg in enumerate((1, -1)):
            u0 = g0.real + sg * r
            dl = g1.real / 2 + sg * (q * q * (g1 * np.conj(g0)).real - g0.imag * g1.imag) / (2 * r)
            fg = abs(-(u0 - np.conj(g0)) - q * q * np.conj(g0)); fgs = abs(-(u0 - g0) - q * q * g0)
            fu = 2 * r
            y = ys[i]
            sens = (fg + fgs) / (fu * 2 * y)
            rho = c1 * y
            Dl = sens * abs(g1) * y
            sep = min(abs(1j * y - z) for z in lam0 if abs(z - 1j * y) > 0)
            e = sens * (abs(g2) * y * y + (abs(g0) * rho**3 / (1 - rho) if rho < 1 else np.inf)) + 2 * Dl * Dl / sep
            eps = max(eps, rho, Dl / sep)
            res += [dl, dl]; errs += [e, e]
    else:
        sq = np.sqrt(complex(disc))
        for u in (g0.real + sq, g0.real - sq):
            s = np.sqrt(u)
            for l in (s, -s):
                rel = c1 * abs(u) / abs(2 * l)
                eps = max(eps, rel)
                res.append(l.real); errs.append(rel * abs(l))
    # rotor roots shifted (kappa = 0)
    rD = np.roots(D[::-1]); Dp = Pn.polyder(D)
    eps_r = 0.0; sh = []
    for lk in rD:
        dl = mb / 2 * (lk + 1j * w)**4 * Pn.polyval(lk, N) / (lk * lk * Pn.polyval(lk, Dp))
        sep = min([abs(lk)] + [abs(lk - z) for z in rDD if abs(z - lk) > 1e-12 * abs(lk)])
        eps_r = max(eps_r, abs(dl) / sep); sh.append((lk, dl))
    for lk, dl in sh:
        res.append((lk + dl).real); errs.append(eps_r * abs(dl))
    return np.array(res), np.array(errs), max(eps, eps_r), axis

def pmul(a, b):
    r = [mp.mpc(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            r[i + j] += x * y
    return r
def padd(a, b, cb=1):
    n = max(len(a), len(b)); a = a + [mp.mpc(0)] * (n - len(a)); b = b + [mp.mpc(0)] * (n - len(b))
    return [x + cb * y for x, y in zip(a, b)]
def exact_mp(p, w, dps=60):
    """max Re of the 12 roots of Delta (one plane), coefficients and roots with dps digits"""
    with mp.workdps(dps):
        M, A, C, c, ct, cc, h, ht, hc, d = [mp.mpf(p[k]) for k in 'M A C c ct cc h ht hc d'.split()]
        w = mp.mpf(w); m = mp.mpf(p['m']); mb = 2 * m; kap = mp.mpf(p['hb']) / m
        x = mp.mpf(p['s0']) / (2 * m * mp.mpf(p['r'])); Q = abs(mb * (2 * x * x - 1))
        P = [mp.mpc(0, w), mp.mpc(1)]; Pb = [mp.mpc(0, -w), mp.mpc(1)]
        P2 = pmul(P, P)
        K11 = padd(padd([M * t for t in P2], [h * t for t in P]), [c])
        K12 = [-(hc * P[0] + cc), -hc]
        K22 = padd(padd([A * t for t in P2], [(ht - mp.mpc(0, 1) * C * w) * t for t in P]), [ct])
        D = padd(pmul(K11, K22), pmul(K12, K12), -1)
        N = padd(padd(K22, [-2 * d * t for t in K12]), [d * d * t for t in K11])
        P4 = pmul(P2, P2); Pb4 = pmul(pmul(Pb, Pb), pmul(Pb, Pb))
        F = padd(pmul([0, kap, 1], D), [mb / 2 * t for t in pmul(P4, N)], -1)
        Fc = [mp.conj(t) for t in F]; Nc = [mp.conj(t) for t in N]
        De = padd(pmul(F, Fc), [(Q / 2)**2 * t for t in pmul(pmul(P4, Pb4), pmul(N, Nc))], -1)
        co = [mp.re(t) for t in De][::-1]
        r = mp.polyroots(co, maxsteps=400, extraprec=400)
        return float(max(mp.re(z) for z in r))


def kappa0(seed, n, mlo=1e-4, mhi=1.0, th=TH):
    """kappa = 0 over random one-plane machines (asymptotic_scan.py's ranges, any ball mass up to 0.05 kg):
    how often is the largest real part of the 12 roots of Delta negative (asymptotically stable)?  And the
    undamped entry (k0pred, the library's rule) against the exact verdict: the 12 eigenvalues of the closed
    one-plane system (exact1), recomputed from Delta with 60 digits (exact_mp) where the margin is below 1e-8 of
    the largest root.  mlo, mhi: the ball mass range as fractions of 0.05 kg."""
    rng = np.random.default_rng(seed)
    n_ok = n_stable = n_marg = n_disk = 0
    n_app = n_dec = n_next = n_agree = n_ps = n_mp = 0
    bad = []
    worst = -np.inf
    for _ in range(n):
        p = dict(M=10., A=0.16, C=0.03, c=2.5e5, ct=7375., cc=-2500., h=250., ht=7.375, hc=-2.5, d=0.1,
                 m=0.05, r=0.1, s0=0.002, hb=0.0)
        p['M'] *= np.exp(rng.uniform(-1, 1)); p['A'] *= np.exp(rng.uniform(-1, 1)); p['C'] = p['A'] * rng.uniform(0, 2)
        p['c'] *= np.exp(rng.uniform(-1, 1)); p['ct'] *= np.exp(rng.uniform(-1, 1)); p['cc'] *= rng.uniform(-2, 2)
        if p['cc']**2 >= p['c'] * p['ct']:
            continue
        sh = np.exp(rng.uniform(-6, 2)); p['h'] *= sh; p['ht'] *= sh; p['hc'] *= sh * rng.uniform(-1, 1)
        p['d'] = rng.uniform(-0.3, 0.3)
        p['m'] *= np.exp(rng.uniform(np.log(mlo), np.log(mhi)))
        p['s0'] = 2 * p['m'] * p['r'] * rng.uniform(0.02, 0.98)
        w = np.exp(rng.uniform(np.log(50), np.log(5000))) * (1 if rng.uniform() < 0.8 else -1)
        De = delta1(p, w)
        n_ok += 1
        r = np.roots(De[::-1])
        mre = r.real.max()
        scale = max(1.0, abs(r).max())
        if mre < -1e-9 * scale:
            n_stable += 1
            n_disk += p['C'] > p['A']
        elif mre <= 1e-9 * scale:
            n_marg += 1
        worst = max(worst, -mre / scale)
        res, errs, small, axis = k0pred(p, w)
        if not small <= th:
            continue
        n_app += 1
        du = bool(np.any(res >= errs))
        ds = bool(np.all(res <= -errs))
        if not (du or ds):
            continue
        n_dec += 1
        n_next += bool(axis)
        n_ps += ds
        ex = exact1(p, w)
        m_ex = ex.real.max()
        if abs(m_ex) < 1e-8 * max(1.0, abs(ex).max()):
            n_mp += 1
            m_ex = exact_mp(p, w)
        if (m_ex < 0) == ds:
            n_agree += 1
        else:
            bad.append((w, m_ex, res.max(), small))
    print('kappa = 0, one plane, seed %d, balls %g..%g x 0.05 kg: %d machines, asymptotically stable %d (%d of them with '
          'C > A), within 1e-9 of the axis %d (largest -max Re / scale %.3g)'
          % (seed, mlo, mhi, n_ok, n_stable, n_disk, n_marg, worst))
    print('   undamped entry, small <= %g: applicable %d, decided %d (%d by the next order), agree %d (predicted STABLE %d; '
          '%d exact margins from 60 digits)' % (th, n_app, n_dec, n_next, n_agree, n_ps, n_mp))
    for b_ in bad:
        print('   DISAGREES: omega %g, exact margin %g, predicted max Re %g, small %g' % b_)
    return not bad


if __name__ == '__main__':
    what = sys.argv[1] if len(sys.argv) > 1 else 'all'
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 4000
    okay = True
    if what in ('scan', 'all'):
        for s, th in ((2, TH), (3, TH), (4, TH), (5, TH), (6, 0.2), (7, 0.2)):
            okay &= scan(s, n, th)
    if what in ('rich', 'all'):
        for s, th in ((8, TH), (9, TH), (10, 0.2)):
            okay &= scan(s, n, th, True)
    if what in ('high', 'all'):
        okay &= high(2, n)
        okay &= high(3, n, 0.2)
        okay &= high(4, n, TH, True)
        okay &= high(5, n, 0.2, True)
    if what in ('every', 'all'):
        okay &= high_every()
        okay &= crossings()
    if what in ('kappa0', 'all'):
        okay &= kappa0(2, n)
        okay &= kappa0(3, n, 1e-6, 1e-3)
        okay &= kappa0(4, n, 1e-6, 1e-3, 0.2)
    sys.exit(0 if okay else 1)
