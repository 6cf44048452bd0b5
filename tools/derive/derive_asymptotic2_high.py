#!/usr/bin/python3
"""Two balancer planes at HIGH SPEED with both planes' balls at q_j = 0 (Q1 = Q2 = 0), the two-plane analogue of
the one-plane (H1), (H2) (docs/rotor.md "Asymptotic conditions", "Two planes at high speed"), derived with SymPy
and checked against the exact 16 roots (NumPy companion of the closed system, asymptotic2_scan.exact_roots).

Run with Debian's interpreter:  /usr/bin/python3 tools/derive/derive_asymptotic2_high.py

Each check prints a line ending in ': OK' or raises:
 (7) G = B^T K(i w)^-1 B = -(Gamma + i H / w) / w^2 + O(w^-4), Gamma = B^T Mi B, H = B^T Mi Hs Mi B,
     Mi = diag(1/M, 1/(A - C)), Hs = [[h, -h_c], [-h_c, h_t]] (paper inertia, series in 1/w);
 (8) Q = 0: the sigma rows decouple from the conj(sigma) rows and read (lambda^2 + K lambda) x + (w^2/2)(Gt + i Ht / w) x = 0,
     Gt = Mb^1/2 Gamma Mb^1/2, Ht = Mb^1/2 H Mb^1/2, K = diag(kappa_j); with Gt = sum mu_k z_k z_k^T the root
     +-i w sqrt(mu_k/2) moves to first order (in K and Ht) by -kbar_k/2 -+ eta_k / (2 sqrt(2 mu_k)),
     kbar_k = z_k^T K z_k, eta_k = z_k^T Ht z_k: stable iff kbar_k > kappa_inf_k = |eta_k| / sqrt(2 mu_k) (H2');
 (9) Gamma, H diagonal (no cross receptance at high speed): kappa_inf_k is the one-plane
     kappa_inf = sqrt(m_b / (2 m_eff)) h_eff / m_eff at d_k (1/m_eff = Gamma_kk, h_eff = m_eff^2 H_kk);
 (10) Q != 0 (generic): the leading-order ball roots are simple and the support damping does not move them off
     the axis: with kappa = 0 the frozen high-speed roots have Re = 0 (to rounding), while at Q = 0 the largest is
     max eta_k / (2 sqrt(2 mu_k)) (so Q = 0 is where (H2') is needed; on the curves in (q1, q2, phase) where two
     roots cross for Q != 0 another condition applies, not derived here);
 (11) the predicted real parts against the exact 16 roots at Q = 0: the error falls with lighter balls and higher speed.
"""
import sys

import numpy as np
import sympy as sp

sys.path.insert(0, __import__('os').path.dirname(__file__))
from asymptotic2_scan import ball_system, default2, draw, exact_roots, high_modes, wmax_cD  # noqa: E402


def ok(msg):
    print(msg + ': OK')


def check_series():
    t = sp.Symbol('t', positive=True)  # t = 1/w
    M, Ap, h, hc, ht, c, cc, ct, d1, d2 = sp.symbols('M Ap h h_c h_t c c_c c_t d1 d2', real=True)
    # t^2 K(i w) = -diag(M, A - C) + i t Hs + t^2 Cs, so w^2 G = B^T adj(t^2 K) B / det(t^2 K); the claim
    # w^2 G = -(Gamma + i H t) + O(t^2) is: B^T adj(Kt) B + (Gamma + i H t) det(Kt) has no t^0, t^1 terms
    Kt = sp.Matrix([[-M + sp.I * t * h + t**2 * c, -(sp.I * t * hc + t**2 * cc)],
                    [-(sp.I * t * hc + t**2 * cc), -Ap + sp.I * t * ht + t**2 * ct]])
    B = sp.Matrix([[1, 1], [d1, d2]])
    Mi = sp.diag(1 / M, 1 / Ap)
    Hs = sp.Matrix([[h, -hc], [-hc, ht]])
    Gam = B.T * Mi * B
    H = B.T * Mi * Hs * Mi * B
    lhs = B.T * Kt.adjugate() * B + (Gam + sp.I * H * t) * Kt.det()
    for j in range(2):
        for k in range(2):
            e = sp.expand(lhs[j, k] * M**2 * Ap**2)
            for n in (0, 1):
                assert sp.simplify(e.coeff(t, n)) == 0, (j, k, n)
            assert sp.simplify(sp.expand(Kt.det()).coeff(t, 0) - M * Ap) == 0
    ok('two planes, high speed (7): G = -(Gamma + i H/w)/w^2 + O(w^-4), Gamma = B^T Mi B, H = B^T Mi Hs Mi B')


def check_perturbation():
    lam, eps = sp.symbols('lambda epsilon')
    w, mu1, mu2 = sp.symbols('omega mu1 mu2', positive=True)
    cs, sn, k1, k2, a, b, cc = sp.symbols('cs sn kappa1 kappa2 a b c', real=True)  # cs^2 + sn^2 = 1
    R = sp.Matrix([[cs, -sn], [sn, cs]])
    Gt = R * sp.diag(mu1, mu2) * R.T
    Ht = sp.Matrix([[a, b], [b, cc]])
    Kd = sp.diag(k1, k2)
    E = (lam**2 * sp.eye(2) + eps * Kd * lam + w**2 / 2 * (Gt + sp.I * eps * Ht / w)).det()
    for k, (mu, z) in enumerate(((mu1, R[:, 0]), (mu2, R[:, 1]))):
        kbar = (z.T * Kd * z)[0]
        eta = (z.T * Ht * z)[0]
        for sg in (1, -1):
            l0 = sg * sp.I * w * sp.sqrt(mu / 2)
            El = sp.diff(E, lam).subs({eps: 0, lam: l0})
            Ee = sp.diff(E, eps).subs({eps: 0, lam: l0})
            delta = -Ee / El
            want = -kbar / 2 - sg * eta / (2 * sp.sqrt(2 * mu))
            num, den = sp.fraction(sp.together(delta - want))
            assert sp.expand(sp.rem(sp.expand(num), sn**2 + cs**2 - 1, sn)) == 0, (k, sg)
    ok('two planes, high speed (8): Q = 0, root +-i w sqrt(mu_k/2) moves by -kbar_k/2 -+ eta_k/(2 sqrt(2 mu_k)) '
       '(first order in K and Ht): (H2\') kbar_k > |eta_k|/sqrt(2 mu_k)')


def check_reduction():
    mb1, mb2, g1, g2, H1, H2 = sp.symbols('m_b1 m_b2 Gamma11 Gamma22 H11 H22', positive=True)
    for mb, g, H in ((mb1, g1, H1), (mb2, g2, H2)):
        mu = mb * g            # Gt diagonal: z_k = e_k
        eta = mb * H
        kinf2 = eta / sp.sqrt(2 * mu)
        m_eff = 1 / g
        h_eff = m_eff**2 * H
        kinf1 = sp.sqrt(mb / (2 * m_eff)) * h_eff / m_eff
        assert sp.simplify(kinf2 - kinf1) == 0
    ok('two planes, high speed (9): Gamma, H diagonal: kappa_inf_k = the one-plane sqrt(m_b/(2 m_eff)) h_eff/m_eff '
       'at d_k')


def frozen_high_roots(p, w, Q):
    """the 8 roots of det(U - S) with G replaced by its high-speed limit (NumPy)"""
    M, Ap = p['M'], p['A'] - p['C']
    B = np.array([[1.0, 1.0], [p['d'][0], p['d'][1]]])
    Mi = np.diag([1 / M, 1 / Ap])
    Hs = np.array([[p['h'], -p['hc']], [-p['hc'], p['ht']]])
    G = -(B.T @ Mi @ B + 1j * B.T @ Mi @ Hs @ Mi @ B / w) / w**2
    mb = np.array([2 * p['m'][0], 2 * p['m'][1]])
    kap = np.array([p['hb'][j] / p['m'][j] for j in range(2)])
    return np.linalg.eigvals(ball_system(G, mb, Q, kap, w)[1])


def predict(p):
    """(kbar, kappa_inf, predicted larger real part per mode) at Q = 0 (as the library)"""
    _, kbar, kinf, _ = high_modes(p)
    return kbar, kinf, (kinf - kbar) / 2


def light(p, f):
    q = dict(p)
    q['m'] = [x * f for x in p['m']]
    q['hb'] = [x * f for x in p['hb']]
    q['s0'] = [np.sqrt(2) * q['m'][j] * q['r'][j] for j in range(2)]  # Q_j = 0
    return q


def check_q_nonzero():
    p = light(default2(), 1e-3)
    p['hb'] = [0.0, 0.0]
    Qg = [2 * p['m'][0] * 0.4 * np.exp(0.7j), 2 * p['m'][1] * 0.25 * np.exp(2.1j)]
    mq, m0 = [], []
    for w in (1e4, 1e5, 1e6):
        mq.append(frozen_high_roots(p, w, Qg).real.max())
        m0.append(frozen_high_roots(p, w, [0, 0]).real.max())
    _, kinf, _ = predict(p)
    assert max(abs(x) for x in mq) < 1e-9 * kinf.max(), mq
    assert all(abs(x - kinf.max() / 2) < 1e-4 * kinf.max() for x in m0), (m0, kinf)
    ok('two planes, high speed (10): kappa = 0, Q != 0 (q 0.4, 0.25): largest Re of the frozen high-speed roots %.1e, '
       '%.1e, %.1e 1/s at 1e4, 1e5, 1e6 rad/s (on the axis: the support damping does not move simple roots); Q = 0: '
       '%.6g, %.6g, %.6g = max kappa_inf_k / 2 = %.6g' % (tuple(mq) + tuple(m0) + (kinf.max() / 2,)))


def check_exact():
    p = default2()
    p['hb'] = [p['m'][0] * 2.0, p['m'][1] * 3.0]
    errs = []
    for f, w in ((1e-2, 1e4), (1e-3, 3e4)):
        q = light(p, f)
        _, _, re = predict(q)
        ex = exact_roots(q, w)
        # the ball roots: the eight closest to the predicted +-i w sqrt(mu_k/2) + re_k band; compare the largest real part
        # of the exact roots with |Im| < 2 w sqrt(mu_max/2) (the rotor-housing's are much further) with max re
        M, Ap = q['M'], q['A'] - q['C']
        B = np.array([[1.0, 1.0], [q['d'][0], q['d'][1]]])
        Sq = np.diag(np.sqrt([2 * q['m'][0], 2 * q['m'][1]]))
        mu = np.linalg.eigvalsh(Sq @ B.T @ np.diag([1 / M, 1 / Ap]) @ B @ Sq)
        ball = ex[abs(ex.imag) < 2 * w * np.sqrt(mu.max() / 2)]
        assert len(ball) == 8, len(ball)
        errs.append(abs(ball.real.max() - re.max()) / abs(re.max()))
    assert errs[1] < errs[0] / 2 and errs[1] < 0.02, errs
    ok('two planes, high speed (11): Q = 0, predicted largest ball-root real part vs the exact 16 roots: relative error '
       '%.2e (balls x 1e-2, 1e4 rad/s), %.2e (x 1e-3, 3e4 rad/s)' % tuple(errs))


def every_kappa(p):
    """kappa_all = rho sqrt(mu_2) (docs/rotor.md "Two planes at high speed", every unbalance), and (Gamma, H)"""
    M, Ap = p['M'], p['A'] - p['C']
    B = np.array([[1.0, 1.0], [p['d'][0], p['d'][1]]])
    Mi = np.diag([1 / M, 1 / Ap])
    Gam = B.T @ Mi @ B
    H = B.T @ Mi @ np.array([[p['h'], -p['hc']], [-p['hc'], p['ht']]]) @ Mi @ B
    rho = np.abs(np.linalg.eigvals(np.linalg.solve(Gam, H))).max()
    mu = high_modes(p)[0]
    return rho * np.sqrt(mu.max()), Gam, H


def machines(rng, n, scale=1.0):
    """n draws of random two-plane machines (balls scaled by scale), those with Gamma positive definite:
    (p, kappa_all, Gamma, H)"""
    for _ in range(n):
        p = draw(rng)
        if p is None:
            continue
        p['m'] = [x * scale for x in p['m']]
        ka, Gam, H = every_kappa(p)
        if np.linalg.eigvalsh(Gam).min() <= 0:
            continue
        yield p, ka, Gam, H


def every_small(p, w):
    """the small parameter of the every-unbalance condition, as the library: max(|w| sqrt(mu_2) c_D, w_max / |w|)"""
    mu = high_modes(p)[0]
    wmax, cD = wmax_cD(p, w)
    return max(abs(w) * np.sqrt(mu.max()) * cD, wmax / abs(w))


def check_every():
    """(12) every unbalance (for Hermitian A >= 0, B and a unit eigenvector y of A + i B / w the
    eigenvalue is y*Ay + i y*By / w, so the ratio bound follows from |x*H^x| <= rho x*G^x): (b) numerically on random machines and random Q (q_j up to 1, every phase): every eigenvalue mu of the frozen S(Q)
    has (Im mu)^2 / (-Re mu) <= kappa_all^2 and Re mu < 0; (c) planes decoupled: kappa_all = sqrt(2) kappa_inf of
    the plane that sets it; (d) the exact 16 roots at 1.02 kappa_all (both planes), random Q, high speed: stable;
    (e), (f) unequal kappa: min kappa_j > kappa_all, the frozen and the exact roots stable."""
    rng = np.random.default_rng(12)
    worst = 0.0
    nm = 0
    for p, ka, Gam, H in machines(rng, 60):
        nm += 1
        w = 3e4
        mb = np.array([2 * p['m'][0], 2 * p['m'][1]])
        G = -(Gam + 1j * H / w) / w**2
        for _ in range(200):
            q = rng.uniform(0, 1, 2) ** rng.choice([0.2, 1.0, 5.0])
            Q = mb * q * np.exp(1j * rng.uniform(0, 2 * np.pi, 2))
            mu = np.linalg.eigvals(ball_system(G, mb, Q, np.zeros(2), w)[0])
            assert mu.real.max() < 0, mu
            worst = max(worst, np.sqrt(np.max(mu.imag**2 / -mu.real)) / ka)
    assert nm >= 10 and worst <= 1 + 1e-9, (nm, worst)
    # (e) unequal kappa: K = diag(kappa_1, kappa_2, kappa_1, kappa_2) commutes with T (T couples sigma_j with
    # conj(sigma_j) of the same plane), so min kappa_j > kappa_all suffices (docs/rotor.md); the frozen quadratic
    # eigenproblem det(lambda^2 + K lambda - S(Q)) on the same machines, min kappa_j = 1.0001 kappa_all, the other
    # 1 to 20 times larger (either plane), 200 unbalances each (q_j up to 1): every root has Re < 0
    rng = np.random.default_rng(14)
    nu = 0
    worst_u = -np.inf
    for p, ka, Gam, H in machines(rng, 60):
        w = 3e4
        mb = np.array([2 * p['m'][0], 2 * p['m'][1]])
        G = -(Gam + 1j * H / w) / w**2
        for _ in range(200):
            q = rng.uniform(0, 1, 2) ** rng.choice([0.2, 1.0, 5.0])
            Q = mb * q * np.exp(1j * rng.uniform(0, 2 * np.pi, 2))
            kap = 1.0001 * ka * np.array([1.0, rng.uniform(1, 20)])
            rng.shuffle(kap)
            lam = np.linalg.eigvals(ball_system(G, mb, Q, kap, w)[1])
            nu += 1
            worst_u = max(worst_u, lam.real.max() / ka)
    assert nu >= 2000 and worst_u < 0, (nu, worst_u)
    # (c) decoupled planes (d_1 = 0 and 1/M terms dropped: Gamma, H diagonal): kappa_all = sqrt(2) max kappa_inf
    p = default2()
    M, Ap = p['M'], p['A'] - p['C']
    Gam = np.diag([1.0 / M, 0.12**2 / Ap])
    H = np.diag([p['h'] / M**2, p['ht'] * 0.12**2 / Ap**2])
    rho = np.abs(np.diag(H) / np.diag(Gam)).max()
    mb = np.array([2 * p['m'][0], 2 * p['m'][1]])
    mu = mb * np.diag(Gam)
    kinf = np.abs(mb * np.diag(H)) / np.sqrt(2 * mu)
    # the plane with the larger mu sets kappa_all = rho sqrt(mu_2); per plane rho_j sqrt(mu_j) = sqrt(2) kappa_inf_j
    per = np.abs(np.diag(H) / np.diag(Gam)) * np.sqrt(mu)
    assert np.allclose(per, np.sqrt(2) * kinf, rtol=1e-13), (per, kinf)
    assert rho * np.sqrt(mu.max()) >= np.sqrt(2) * kinf.max() * (1 - 1e-13)
    # (d) exact 16 roots: light balls at high speed, kappa = 1.02 kappa_all in both planes, random unbalances
    rng = np.random.default_rng(13)
    nst = nex = 0
    for p, ka, Gam, H in machines(rng, 30, 1e-3):
        p['hb'] = [1.02 * ka * p['m'][j] for j in range(2)]
        for _ in range(4):
            q = rng.uniform(0, 1, 2) ** 0.3
            p['s0'] = [2 * p['m'][j] * p['r'][j] * np.sqrt((1 + q[j]) / 2) for j in range(2)]
            p['psi0'] = [0.0, rng.uniform(0, np.pi)]
            nex += 1
            nst += exact_roots(p, 3e4).real.max() < 0
    assert nex >= 24 and nst == nex, (nst, nex)
    # (f) the exact 16 roots with unequal kappa: min kappa_j = 1.02 kappa_all, the other plane 1 to 10 times that,
    # on machines where the condition is applicable (high_every_small <= 0.05, as the library; a machine with C close
    # to A, e.g. C/A = 0.987, has an unstable rotor root near 450 rad/s at 3e4 rad/s whatever the ball damping)
    rng = np.random.default_rng(15)
    nst_u = nex_u = 0
    for p, ka, Gam, H in machines(rng, 200, 1e-3):
        if nex_u >= 32:
            break
        if every_small(p, 3e4) > 0.05:
            continue
        f = [1.0, rng.uniform(1, 10)]
        rng.shuffle(f)
        p['hb'] = [1.02 * ka * f[j] * p['m'][j] for j in range(2)]
        for _ in range(4):
            q = rng.uniform(0, 1, 2) ** 0.3
            p['s0'] = [2 * p['m'][j] * p['r'][j] * np.sqrt((1 + q[j]) / 2) for j in range(2)]
            p['psi0'] = [0.0, rng.uniform(0, np.pi)]
            nex_u += 1
            nst_u += exact_roots(p, 3e4).real.max() < 0
    assert nex_u >= 24 and nst_u == nex_u, (nst_u, nex_u)
    ok('two planes, high speed (12): every unbalance, the same kappa in both planes: (Im mu)^2 / (-Re mu) <= '
       'kappa_all^2 = rho^2 mu_2 for every eigenvalue of S(Q) (%d machines x 200 unbalances, largest ratio %.3f); '
       'decoupled planes: rho_j sqrt(mu_j) = sqrt(2) kappa_inf_j; exact 16 roots at 1.02 kappa_all, 3e4 rad/s: '
       '%d of %d stable; unequal kappa (min kappa_j > kappa_all suffices): frozen roots of det(lambda^2 + K lambda - S) '
       'at min kappa_j = 1.0001 kappa_all, %d cases: largest Re / kappa_all %.2e < 0; exact 16 roots at min kappa_j = '
       '1.02 kappa_all: %d of %d stable' % (nm, worst, nst, nex, nu, worst_u, nst_u, nex_u))


def main():
    check_series()
    check_perturbation()
    check_reduction()
    check_q_nonzero()
    check_exact()
    check_every()
    print('derive_asymptotic2_high: all checks passed')
    return 0


if __name__ == '__main__':
    sys.exit(main())
