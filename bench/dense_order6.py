#!/usr/bin/python3
"""Issue 20, output for free: a continuous extension of DOP853 with NO extra stage (prototype).

DOP853's 7th-order extension (Hairer's contd8, autobal's dense output) needs 3 more right-hand
sides in every step that holds an output time.  This script shows that the step's own 12 stages
plus f(t + h, y1) (known anyway: FSAL) admit a continuous extension of order 6, and measures
whether its error at the output points stays matched to contd8's.

1. Order conditions (B-series): rooted trees up to order 8, elementary weights Phi_i(t) of
   SciPy's DOP853 tableau (row 12 = the weights b, c = 1).  Weights b_i(theta) = sum_k beta_ik
   theta^k of order p exist iff for every k <= p the vector (delta_{k,|t|} / gamma(t))_t lies in
   the column space of (Phi_i(t))_{t, i}; printed: the least-squares residual per stage set.
2. The order-6 weights: degree 8 in theta, with u(1) = y1, u'(0) = f0, u'(1) = f1 (C1 at the
   step ends), the order <= 6 conditions as constraints, the order-7 residuals over a theta grid
   minimized (their principal error terms).
3. Local convergence: one step of the pendulum from a point of its trajectory, h halved; the
   largest interpolation error over theta against a tight solution (expected slope 7 for order
   6, 8 for contd8).
4. Output every quarter revolution, the bench's cases (pendulum 500 revolutions, rotor 2 and 8
   balls 100 revolutions), SciPy's DOP853 stepping at rtol = atol = tol; at every output time
   both interpolants on the same step: the error of the output points against SciPy DOP853 at
   1e-13 (pendulum: absolute; rotor: relative to each component's largest |value|).

Usage: /usr/bin/python3 bench/dense_order6.py [--tols 1e-6,1e-8,1e-10] [--cases pendulum,rotor2,rotor8]
"""
import argparse
import math
import os
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.integrate._ivp import dop853_coefficients as dc
from scipy.integrate._ivp.rk import DOP853

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pendulum_scipy  # noqa: E402
import rotor_scipy  # noqa: E402

# the rooted trees and their density gamma: the derivation's own (tools/derive/derive_dense6.py)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "derive"))
from derive_dense6 import gamma, trees_upto  # noqa: E402

A = dc.A.copy()
A[12, :12] = dc.B  # stage 12: f(t + h, y1), its row the weights b


def phi(t, memo):
    if t not in memo:
        v = np.ones(A.shape[0])
        for c in t:
            v = v * (A @ phi(c, memo))
        memo[t] = v
    return memo[t]


def feasibility(stages, p):
    byorder, order = trees_upto(p)
    memo, rows, ko, gam = {}, [], [], []
    for k in range(1, p + 1):
        for t in byorder[k]:
            rows.append(phi(t, memo)[stages])
            ko.append(k)
            gam.append(gamma(t, order))
    M, ko, gam = np.array(rows), np.array(ko), np.array(gam, float)
    worst = 0.0
    for k in range(1, p + 1):
        r = np.where(ko == k, 1.0 / gam, 0.0)
        x = np.linalg.lstsq(M, r, rcond=None)[0]
        worst = max(worst, np.linalg.norm(M @ x - r))
    return worst


def order6_weights(q=8, p=6, grid=np.linspace(0.0, 1.0, 41)):
    """beta (13 x q): b_i(theta) = sum_k beta[i, k-1] theta^k."""
    ns, nv = 13, 13 * q
    byorder, order = trees_upto(p + 1)
    memo, Eq, eqr = {}, [], []
    for k in range(1, p + 1):
        for t in byorder[k]:
            ph, g = phi(t, memo)[:ns], gamma(t, order)
            for kk in range(1, q + 1):
                row = np.zeros(nv)
                row[np.arange(ns) * q + kk - 1] = ph
                Eq.append(row)
                eqr.append(1.0 / g if kk == k else 0.0)
    for i in range(ns):
        row = np.zeros(nv)
        row[i * q:(i + 1) * q] = 1.0  # u(1) = y1
        Eq.append(row)
        eqr.append(A[12, i])
        row = np.zeros(nv)
        row[i * q:(i + 1) * q] = np.arange(1, q + 1)  # u'(1) = f1
        Eq.append(row)
        eqr.append(1.0 if i == 12 else 0.0)
        row = np.zeros(nv)
        row[i * q] = 1.0  # u'(0) = f0
        Eq.append(row)
        eqr.append(1.0 if i == 0 else 0.0)
    Eq, eqr = np.array(Eq), np.array(eqr)
    Ob, obr = [], []
    for t in byorder[p + 1]:
        ph, g = phi(t, memo)[:ns], gamma(t, order)
        for th in grid:
            row = np.zeros(nv)
            for kk in range(1, q + 1):
                row[np.arange(ns) * q + kk - 1] = ph * th ** kk
            Ob.append(row)
            obr.append(th ** (p + 1) / g)
    Ob, obr = np.array(Ob), np.array(obr)
    # constrained least squares through the null space of the constraints
    x0 = np.linalg.lstsq(Eq, eqr, rcond=None)[0]
    for _ in range(3):  # iterative refinement
        x0 += np.linalg.lstsq(Eq, eqr - Eq @ x0, rcond=None)[0]
    _, sv, vt = np.linalg.svd(Eq)
    rank = int(np.sum(sv > sv[0] * 1e-12))
    N = vt[rank:].T
    z = np.linalg.lstsq(Ob @ N, obr - Ob @ x0, rcond=None)[0]
    x = x0 + N @ z
    for _ in range(3):
        x += np.linalg.lstsq(Eq, eqr - Eq @ x, rcond=None)[0]
    return x.reshape(ns, q), np.abs(Eq @ x - eqr).max(), np.sqrt(np.mean((Ob @ x - obr) ** 2))


def case(name):
    if name == "pendulum":
        rhs = pendulum_scipy.make_rhs(**pendulum_scipy.P)
        period, revs, y0, ref_atol = 2 * math.pi / pendulum_scipy.P["Rw"], 500, np.zeros(8), 1e-13
    else:
        n = int(name[5:])
        rhs = rotor_scipy.RHS["numpy"](n)
        period, revs, y0, ref_atol = 2 * math.pi / rotor_scipy.OMEGA, 100, rotor_scipy.initial_state(n), 1e-15
    t_end = revs * period
    k = int(round(revs / 0.25))
    grid = np.array([min(i * 0.25 * period, t_end) for i in range(k + 1)])
    grid[-1] = t_end
    return rhs, y0, t_end, grid, ref_atol


def local_order(beta):
    rhs, y0, t_end, grid, _ = case("pendulum")
    ya = solve_ivp(rhs, (0, 30.0), y0, method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
    print("local error of one step from the pendulum's state at tau = 30 (max over theta):")
    prev = None
    for h in [0.8, 0.4, 0.2, 0.1]:
        s = DOP853(rhs, 30.0, ya, 30.0 + 2 * h, rtol=1e3, atol=1e3, first_step=h)
        s.step()
        h = s.t - s.t_old  # the step taken (accepted at these tolerances)
        ths = np.linspace(0, 1, 21)[1:-1]
        ex = solve_ivp(rhs, (30.0, 30.0 + h), ya, method="DOP853", rtol=1e-14, atol=1e-14,
                       t_eval=30.0 + ths * h).y
        u6 = np.array([ya + h * (s.K[:13].T @ (beta @ th ** np.arange(1, beta.shape[1] + 1))) for th in ths]).T
        u8 = s.dense_output()(30.0 + ths * h)
        e6, e8 = np.abs(u6 - ex).max(), np.abs(u8 - ex).max()
        line = f"  h = {h:4.2f}: order-6 extension {e6:.3e}, contd8 {e8:.3e}"
        if prev:
            line += f"   slopes {math.log2(prev[0] / e6):.2f}, {math.log2(prev[1] / e8):.2f}"
        print(line)
        prev = (e6, e8)


def output_errors(name, tols, beta):
    rhs, y0, t_end, grid, ref_atol = case(name)
    ref = solve_ivp(rhs, (0, t_end), y0, method="DOP853", rtol=1e-13, atol=ref_atol, t_eval=grid).y
    if name == "pendulum":
        scale = np.ones(len(y0))
    else:
        scale = np.abs(ref).max(axis=1)
        scale[scale == 0] = 1.0
    q = beta.shape[1]
    for tol in tols:
        s = DOP853(rhs, 0.0, y0, t_end, rtol=tol, atol=tol)
        u8 = np.zeros((len(y0), len(grid)))
        u6 = np.zeros_like(u8)
        u8[:, 0] = u6[:, 0] = y0
        j, nsteps, nout = 1, 0, 0
        while s.status == "running":
            s.step()
            nsteps += 1
            t0, t1 = s.t_old, s.t
            h = t1 - t0
            had = False
            while j < len(grid) and grid[j] <= t1:
                th = (grid[j] - t0) / h
                u8[:, j] = s.dense_output()(grid[j])
                u6[:, j] = s.y_old + h * (s.K[:13].T @ (beta @ th ** np.arange(1, q + 1)))
                j += 1
                had = True
            nout += had
        e8 = np.max(np.abs(u8 - ref) / scale[:, None])
        e6 = np.max(np.abs(u6 - ref) / scale[:, None])
        d = np.max(np.abs(u6 - u8) / scale[:, None])
        print(f"  {name:8s} {tol:7.0e} {nsteps:6d} {nout:6d}   {e8:.3e}   {e6:.3e}   {e6 / e8:5.3f}   {d:.2e}"
              f"   {3 * nout / (12 * nsteps):6.1%}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tols", default="1e-6,1e-8,1e-10")
    ap.add_argument("--cases", default="pendulum,rotor2,rotor8")
    a = ap.parse_args()
    print("order conditions: largest least-squares residual (0 to rounding: weights b_i(theta) exist)")
    for p in (5, 6, 7):
        print(f"  order {p}: stages 0..12 (no extra stage) {feasibility(list(range(13)), p):.1e}, "
              f"stages 0..15 (contd8's 3 extra) {feasibility(list(range(16)), p):.1e}")
    beta, cres, ores = order6_weights()
    print(f"order-6 weights (degree 8, u(1) = y1, u'(0) = f0, u'(1) = f1): constraint residual {cres:.1e}, "
          f"order-7 residual (rms over trees and theta) {ores:.2e}")
    local_order(beta)
    print("error of the output points (every quarter revolution), SciPy DOP853 stepping:")
    print("  case     tol     steps  w/out   contd8      order 6     ratio   |o6-contd8|  contd8's extra rhs")
    for name in a.cases.split(","):
        output_errors(name, [float(x) for x in a.tols.split(",")], beta)


if __name__ == "__main__":
    main()
