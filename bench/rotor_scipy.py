#!/usr/bin/python3
"""Rotor with a ball autobalancer (rotor.md): autobal (GSL rk8pd, C) against
SciPy solve_ivp, for 2 and 8 balls, and the cost of one right-hand side
against the number of balls.

Problem: the spec's default example (rotor.md, "Default example"): housing
M_k = 6, A_k = 0.12; rotor m_p = 4, A_p = 0.04, C_p = 0.03; supports
l_L = 0.20, l_R = 0.15, c_Lx = c_Ly = 1e5, c_Rx = c_Ry = 1.5e5,
h_Lx = h_Ly = 100, h_Rx = h_Ry = 150; one plane d = 0.1 with m_0 = 0.02 at
r_0 = 0.1; omega = 500 rad/s; paper inertia model; no axial motion; rotor at
rest at the origin, balls at rest relative to the rotor.
  2 balls: 0.05 kg each on r = 0.1, h = 0.1, at psi = 1.0 and 2.5 (the default).
  n balls (8, and the RHS-cost sizes): 0.1/n kg each (same total capacity)
  on r = 0.1, h = 0.1, at psi_i = 1.0 + 0.4 i, i = 0 .. n-1.
Fixed-frame state (x, y, alpha, beta, their rates, phi_1..n, phi_1..n'),
t in [0, T1] (T1 = 0.5 s: 40 revolutions), final state only.

The SciPy right-hand side is written here from the spec's equations (3.2),
(3.3), (3.4) and "Solving for the accelerations", independently of the C code
(which, for one plane, also reduces the 4x4 system to the 2x2 one in
(u_D'', v_D''), but from its own derivation), with the 4x4 system
reduced in closed form to a 2x2 one in (u_D'', v_D'') (the mass matrix is
diag(M, M, A, A) plus a rank-2 term, see make_rhs), in two versions:
NumPy-vectorized over the balls (make_rhs: np.sin/np.cos, dot products for
S_ss, S_sc, S_cc, F_u, F_v) and plain Python floats (make_rhs_plain: loops,
math.sin/cos), which is faster below about 35 balls.  Both are checked
against the library's right-hand side at 5 states (`bench_rotor check`)
before anything is timed, and every solver is timed with both.

Error norms differ: GSL's control bounds every component (max norm), SciPy's
the RMS over the dim components, so DOP853 is also run at tol/sqrt(dim).
Accuracy: final states against SciPy DOP853 at rtol = atol = 1e-13, also
compared with autobal rk8pd at 1e-13.  "max rel err" is
max_i |y_i - ref_i| / scale_i, scale_i = the largest |value| over the
reference trajectory of the group of y_i ({x, y}, {alpha, beta}, {x', y'},
{alpha', beta'}, {phi}, {phi'}); "ball err" is the largest absolute error of a
ball angle, in rad.

Times: best of N runs (autobal: --c-repeats, SciPy: --scipy-repeats) of the
process CPU time (C: CLOCK_PROCESS_CPUTIME_ID around autobal_transient_run;
Python: time.process_time around solve_ivp; both single-threaded).  CPU time,
not wall time: on the shared 2-core machine a 50-300 ms SciPy run is almost
always preempted by other jobs when the load is above 2, which doubled SciPy's
best-of-5 wall time (while autobal's best of 201 short runs was unaffected);
CPU time leaves that out, and agrees with the wall time of a quiet machine.
The right-hand-side table times chunks of a few ms by wall clock, best of
many (C: 51, Python: 31), which filters preemption the same way.

Run through bench/run.sh (builds bench_rotor first) with /usr/bin/python3.
"""
import argparse
import json
import math
import platform
import subprocess
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp

# Hardware values of the spec's default example (SI units).
HW = dict(M_k=6.0, A_k=0.12, m_p=4.0, A_p=0.04, C_p=0.03, l_L=0.20, l_R=0.15,
          c_Lx=1.0e5, c_Ly=1.0e5, c_Rx=1.5e5, c_Ry=1.5e5,
          h_Lx=100.0, h_Ly=100.0, h_Rx=150.0, h_Ry=150.0)
PLANE = dict(d=0.10, m0=0.02, r0=0.1, psi0=0.0)
OMEGA = 500.0


def lumped(hw):
    """(2.7), (2.9), (2.11)."""
    lL, lR = hw["l_L"], hw["l_R"]
    L = dict(M=hw["M_k"] + hw["m_p"], A=hw["A_k"] + hw["A_p"], C=hw["C_p"])
    for k in "ch":
        Lx, Ly, Rx, Ry = hw[k + "_Lx"], hw[k + "_Ly"], hw[k + "_Rx"], hw[k + "_Ry"]
        L[k + "_x"] = Lx + Rx
        L[k + "_y"] = Ly + Ry
        L[k + "_alpha"] = Ly * lL * lL + Ry * lR * lR
        L[k + "_beta"] = Lx * lL * lL + Rx * lR * lR
        L[k + "_xbeta"] = Lx * lL - Rx * lR
        L[k + "_yalpha"] = Ly * lL - Ry * lR
    return L


def balls(n):
    """Ball masses, radii, dampings, initial angles psi (relative to the rotor)."""
    if n == 2:
        return (np.array([0.05, 0.05]), np.array([0.1, 0.1]), np.array([0.1, 0.1]),
                np.array([1.0, 2.5]))
    i = np.arange(n)
    return np.full(n, 0.1 / n), np.full(n, 0.1), np.full(n, 0.1), 1.0 + 0.4 * i


def initial_state(n):
    """Rotor at rest at the origin, balls at rest relative to the rotor, t = 0:
    phi = psi, phi' = omega."""
    psi = balls(n)[3]
    return np.concatenate((np.zeros(8), psi, np.full(n, OMEGA)))


def make_rhs(n):
    """Fixed-frame right-hand side of (3.2) + (3.4) for one plane.

    With q = (x, y, alpha, beta), D = diag(M, M, A, A), eu = (1, 0, 0, d),
    ev = (0, 1, -d, 0), E = [eu; ev] and u = (u_D'', v_D'') = E q'' (3.3),
    (3.2) reads  D q'' + f + E^T (S u + F) = 0  with the support/gyroscopic
    forces f, S = [[-S_ss, S_sc], [S_sc, -S_cc]] and F = (F_u, F_v)
    ("Solving for the accelerations").  Hence q'' = q0 - D^-1 E^T S u with
    q0 = -D^-1 (f + E^T F), and u = E q0 - g S u, g = 1/M + d^2/A
    (E D^-1 E^T = g I): a 2x2 system (I + g S) u = E q0.  Then
    phi_i'' = (u_D'' sin phi_i - v_D'' cos phi_i) / r_i - (h_i/m_i)(phi_i' - omega)."""
    L = lumped(HW)
    M, A, C = L["M"], L["A"], L["C"]
    cx, cy, cal, cbe, cxb, cya = (L[k] for k in ("c_x", "c_y", "c_alpha", "c_beta", "c_xbeta",
                                                 "c_yalpha"))
    hx, hy, hal, hbe, hxb, hya = (L[k] for k in ("h_x", "h_y", "h_alpha", "h_beta", "h_xbeta",
                                                 "h_yalpha"))
    d, psi0 = PLANE["d"], PLANE["psi0"]
    w = OMEGA
    Cw = C * w
    w2s0 = w * w * PLANE["m0"] * PLANE["r0"]
    m, r, h, _ = balls(n)
    mr = m * r
    hr = h * r
    kap = h / m
    g = 1.0 / M + d * d / A
    sin, cos = math.sin, math.cos
    npsin, npcos, concat = np.sin, np.cos, np.concatenate

    def rhs(t, y):
        x, yy, al, be, xd, yd, ald, bed = y[:8].tolist()
        phi = y[8:8 + n]
        phid = y[8 + n:]
        s = npsin(phi)
        c = npcos(phi)
        ms = m * s
        Sss = ms @ s
        Ssc = ms @ c
        Scc = (m * c) @ c
        rel = hr * (phid - w)
        cen = mr * phid * phid
        ph0 = w * t + psi0  # the unbalance, phi_0' = omega
        Fu = rel @ s - cen @ c - w2s0 * cos(ph0)
        Fv = -(rel @ c) - cen @ s - w2s0 * sin(ph0)
        # (3.2) without the s'' terms
        f0 = hx * xd + cx * x - hxb * bed - cxb * be
        f1 = hy * yd + cy * yy + hya * ald + cya * al
        f2 = hal * ald + cal * al + Cw * bed + hya * yd + cya * yy
        f3 = hbe * bed + cbe * be - Cw * ald - hxb * xd - cxb * x
        q0x = -(f0 + Fu) / M
        q0y = -(f1 + Fv) / M
        q0a = -(f2 - d * Fv) / A
        q0b = -(f3 + d * Fu) / A
        bu = q0x + d * q0b
        bv = q0y - d * q0a
        a11 = 1.0 - g * Sss
        a12 = g * Ssc
        a22 = 1.0 - g * Scc
        det = a11 * a22 - a12 * a12
        uD = (a22 * bu - a12 * bv) / det
        vD = (a11 * bv - a12 * bu) / det
        Su = -Sss * uD + Ssc * vD
        Sv = Ssc * uD - Scc * vD
        phidd = (uD * s - vD * c) / r - kap * (phid - w)  # (3.4)
        return concat(([xd, yd, ald, bed,
                        q0x - Su / M, q0y - Sv / M, q0a + d * Sv / A, q0b - d * Su / A],
                       phid, phidd))

    return rhs


def make_rhs_plain(n):
    """The same right-hand side (same reduction as make_rhs) on plain Python
    floats: y.tolist(), math.sin/cos and loops over the balls.  For a few
    balls this beats the NumPy version (NumPy's per-call overhead of ~1 us per
    array operation dominates); the two cross near n = 40 (see the RHS table)."""
    L = lumped(HW)
    M, A, C = L["M"], L["A"], L["C"]
    cx, cy, cal, cbe, cxb, cya = (L[k] for k in ("c_x", "c_y", "c_alpha", "c_beta", "c_xbeta",
                                                 "c_yalpha"))
    hx, hy, hal, hbe, hxb, hya = (L[k] for k in ("h_x", "h_y", "h_alpha", "h_beta", "h_xbeta",
                                                 "h_yalpha"))
    d, psi0 = PLANE["d"], PLANE["psi0"]
    w = OMEGA
    Cw = C * w
    w2s0 = w * w * PLANE["m0"] * PLANE["r0"]
    m, r, h, _ = balls(n)
    m, r, h = m.tolist(), r.tolist(), h.tolist()
    mr = [a * b for a, b in zip(m, r)]
    hr = [a * b for a, b in zip(h, r)]
    kap = [a / b for a, b in zip(h, m)]
    g = 1.0 / M + d * d / A
    sin, cos = math.sin, math.cos
    idx = range(n)

    def rhs(t, y):
        yl = y.tolist()
        x, yy, al, be, xd, yd, ald, bed = yl[:8]
        phi = yl[8:8 + n]
        phid = yl[8 + n:]
        s = [sin(v) for v in phi]
        c = [cos(v) for v in phi]
        ph0 = w * t + psi0
        Fu = -w2s0 * cos(ph0)
        Fv = -w2s0 * sin(ph0)
        Sss = Ssc = Scc = 0.0
        for i in idx:
            si, ci, mi, pd = s[i], c[i], m[i], phid[i]
            Sss += mi * si * si
            Ssc += mi * si * ci
            Scc += mi * ci * ci
            rel = hr[i] * (pd - w)
            cen = mr[i] * pd * pd
            Fu += rel * si - cen * ci
            Fv += -rel * ci - cen * si
        f0 = hx * xd + cx * x - hxb * bed - cxb * be
        f1 = hy * yd + cy * yy + hya * ald + cya * al
        f2 = hal * ald + cal * al + Cw * bed + hya * yd + cya * yy
        f3 = hbe * bed + cbe * be - Cw * ald - hxb * xd - cxb * x
        q0x = -(f0 + Fu) / M
        q0y = -(f1 + Fv) / M
        q0a = -(f2 - d * Fv) / A
        q0b = -(f3 + d * Fu) / A
        bu = q0x + d * q0b
        bv = q0y - d * q0a
        a11 = 1.0 - g * Sss
        a12 = g * Ssc
        a22 = 1.0 - g * Scc
        det = a11 * a22 - a12 * a12
        uD = (a22 * bu - a12 * bv) / det
        vD = (a11 * bv - a12 * bu) / det
        Su = -Sss * uD + Ssc * vD
        Sv = Ssc * uD - Scc * vD
        return ([xd, yd, ald, bed, q0x - Su / M, q0y - Sv / M, q0a + d * Sv / A, q0b - d * Su / A]
                + phid + [(uD * s[i] - vD * c[i]) / r[i] - kap[i] * (phid[i] - w) for i in idx])

    return rhs


RHS = {"numpy": make_rhs, "plain": make_rhs_plain}


def scipy_run(n, method, rtol, atol, t1, repeats, t_eval=None, variant="numpy"):
    rhs = RHS[variant](n)
    y0 = initial_state(n)
    best = math.inf
    sol = None
    for _ in range(repeats):
        t0 = time.process_time()  # CPU time: see the module docstring
        sol = solve_ivp(rhs, (0.0, t1), y0, method=method, rtol=rtol, atol=atol, t_eval=t_eval)
        best = min(best, time.process_time() - t0)
        if not sol.success:
            raise RuntimeError(f"{method}: {sol.message}")
    return best, sol.nfev, sol.y[:, -1], sol


def bench(exe, *args):
    out = subprocess.run([exe, *map(str, args)], check=True, capture_output=True,
                         text=True).stdout
    return json.loads(out)


def group_scales(n, Y):
    """Per-component scale: largest |value| over the trajectory Y (dim x nt) in
    the component's group."""
    groups = [slice(0, 2), slice(2, 4), slice(4, 6), slice(6, 8), slice(8, 8 + n),
              slice(8 + n, 8 + 2 * n)]
    sc = np.empty(8 + 2 * n)
    for gs in groups:
        sc[gs] = np.max(np.abs(Y[gs]))
    sc[sc == 0.0] = 1.0  # e.g. x' = y' = 0 at a start from rest
    return sc


def check_rhs(exe, n):
    """Largest difference between this file's rhs (both variants) and the
    library's, relative to the largest |component| of each group at that state."""
    data = bench(exe, "check", n)
    worst = 0.0
    for make in RHS.values():
        rhs = make(n)
        for st in data["states"]:
            mine = np.asarray(rhs(st["t"], np.array(st["y"])))
            theirs = np.array(st["dydt"])
            sc = group_scales(n, theirs[:, None])
            worst = max(worst, np.max(np.abs(mine - theirs) / sc))
    return worst, len(data["states"])


def time_py_rhs(n, seconds, reps, variant):
    """Seconds per call: best of reps chunks of calls lasting >= seconds each
    (short chunks, many of them, as for the C timing: the best one is a chunk
    the scheduler did not interrupt), cycling through 16 random states."""
    rhs = RHS[variant](n)
    rng = np.random.default_rng(1234 + n)
    states = []
    for k in range(16):
        t = 0.01 * k + 0.001
        y = np.concatenate((rng.uniform(-1, 1, 2) * 2e-4, rng.uniform(-1, 1, 2) * 1e-3,
                            rng.uniform(-1, 1, 2) * 0.1, rng.uniform(-1, 1, 2) * 0.5,
                            OMEGA * t + rng.uniform(-math.pi, math.pi, n),
                            OMEGA + rng.uniform(-50, 50, n)))
        states.append((t, y))
    pc = time.perf_counter

    def chunk(calls):
        t0 = pc()
        for k in range(calls):
            t, y = states[k & 15]
            rhs(t, y)
        return pc() - t0

    calls = 4
    while chunk(calls) < seconds:
        calls *= 2
    return min(chunk(calls) for _ in range(reps)) / calls


def fit_line(n, c):
    n = np.asarray(n, float)
    c = np.asarray(c, float)
    b, a = np.polyfit(n, c, 1)
    res = c - (a + b * n)
    r2 = 1.0 - np.sum(res ** 2) / np.sum((c - c.mean()) ** 2)
    return a, b, r2, np.max(np.abs(res) / c)


def transient_tables(args, tols):
    summary = {}
    for n in args.balls:
        dim = 8 + 2 * n
        worst, nst = check_rhs(args.bench, n)
        if worst > 1e-10:
            raise RuntimeError(f"{n} balls: SciPy rhs differs from the library's by {worst:.2e}")
        tgrid = np.linspace(0.0, args.t1, 2001)
        _, ref_nfev, ref, rsol = scipy_run(n, "DOP853", 1e-13, 1e-13, args.t1, 1, t_eval=tgrid)
        scale = group_scales(n, rsol.y)
        ref_c = np.array(bench(args.bench, "run", n, "rk8pd", 1e-13, 1e-13, repr(args.t1), 1)["y"])
        ref_diff = np.max(np.abs(ref - ref_c) / scale)
        ref_dphi = np.max(np.abs(ref - ref_c)[8:8 + n])
        psi_end = ref[8:8 + n] - OMEGA * args.t1
        print(f"== {n} balls (dim {dim}), t in [0, {args.t1:g}] s, omega = {OMEGA:g} rad/s ==")
        print(f"SciPy rhs (NumPy and plain) vs library rhs at {nst} states: max difference "
              f"{worst:.1e} (relative to each group's largest |component|)")
        print(f"reference: SciPy DOP853 rtol=atol=1e-13 ({ref_nfev} rhs evals); autobal rk8pd "
              f"1e-13 differs from it by {ref_diff:.1e} (max rel) / {ref_dphi:.1e} rad (balls)")
        if ref_diff > 1e-9:
            print("WARNING: the two references differ by more than 1e-9: the accuracy columns "
                  "are not reliable below that")
        print("state scales: |x,y| %.2e m, |alpha,beta| %.2e rad, |x',y'| %.2e m/s, "
              "|alpha',beta'| %.2e rad/s" % (scale[0], scale[2], scale[4], scale[6]))
        print("final psi = phi - omega t [rad]: " +
              ", ".join(f"{v:.4f}" for v in np.mod(psi_end + math.pi, 2 * math.pi) - math.pi))
        print()
        hdr = (f"{'':<26}{'':>8}{'':>11}{'':>11}{'':>10}{'--- NumPy rhs ---':>24}"
               f"{'--- plain rhs ---':>24}")
        print(hdr)
        hdr = (f"{'solver':<26}{'tol':>8}{'rhs evals':>11}{'max rel err':>12}{'ball err':>10}"
               f"{'time [ms]':>12}{'/ autobal':>12}{'time [ms]':>12}{'/ autobal':>12}")
        print(hdr)
        print("-" * len(hdr))
        for tol in tols:
            c = bench(args.bench, "run", n, "rk8pd", tol, tol, repr(args.t1), args.c_repeats)
            yc = np.array(c["y"])
            tc = c["cpu_seconds_min"]
            print(f"{'autobal rk8pd (C)':<26}{tol:>8.0e}{c['rhs_evals']:>11d}"
                  f"{np.max(np.abs(yc - ref) / scale):>12.2e}"
                  f"{np.max(np.abs(yc - ref)[8:8 + n]):>10.1e}{tc * 1e3:>12.3f}{1.0:>12.1f}")
            summary[(n, "autobal", tol)] = (tc, c["rhs_evals"])
            for method, fac, label in (("DOP853", 1.0, "SciPy DOP853"),
                                       ("DOP853", 1 / math.sqrt(dim), "SciPy DOP853 tol/sqrt(dim)"),
                                       ("LSODA", 1.0, "SciPy LSODA")):
                ts, nfev, yend, _ = scipy_run(n, method, tol * fac, tol * fac, args.t1,
                                              args.scipy_repeats)
                tp, nfev_p, _, _ = scipy_run(n, method, tol * fac, tol * fac, args.t1,
                                             args.scipy_repeats, variant="plain")
                summary[(n, label, tol)] = (ts / tc, tp / tc, ts / nfev, tp / nfev_p)
                shown = label.replace("dim", str(dim))
                print(f"{shown:<26}{tol * fac:>8.1e}{nfev:>11d}"
                      f"{np.max(np.abs(yend - ref) / scale):>12.2e}"
                      f"{np.max(np.abs(yend - ref)[8:8 + n]):>10.1e}"
                      f"{ts * 1e3:>12.3f}{ts / tc:>12.1f}{tp * 1e3:>12.3f}{tp / tc:>12.1f}"
                      + ("" if nfev_p == nfev else f"  (plain: {nfev_p} evals)"))
            print()
        per_c = min(summary[(n, "autobal", t)][0] / summary[(n, "autobal", t)][1] for t in tols)
        per_n = min(summary[(n, "SciPy DOP853", t)][2] for t in tols)
        per_p = min(summary[(n, "SciPy DOP853", t)][3] for t in tols)
        print(f"time per rhs evaluation incl. the stepper: autobal {per_c * 1e9:.0f} ns, "
              f"SciPy DOP853 {per_n * 1e6:.1f} us (NumPy rhs) / {per_p * 1e6:.1f} us (plain rhs)")
        print()
    print("time ratios SciPy / autobal, min .. max over the tolerances:")
    print(f"  {'':<36}{'NumPy rhs':>16}{'plain rhs':>16}")
    for n in args.balls:
        for label in ("SciPy DOP853", "SciPy DOP853 tol/sqrt(dim)", "SciPy LSODA"):
            rn = [summary[(n, label, t)][0] for t in tols]
            rp = [summary[(n, label, t)][1] for t in tols]
            print(f"  {n} balls, {label:<28}{min(rn):>7.0f} .. {max(rn):<6.0f}"
                  f"{min(rp):>7.0f} .. {max(rp):<6.0f}")
    print()


def rhs_table(args):
    sizes = [2 ** k for k in range(1, int(math.log2(args.nmax)) + 1)]
    c = bench(args.bench, "rhs", args.nmax, args.rhs_seconds)
    pyn = [time_py_rhs(n, args.py_seconds, args.py_reps, "numpy") * 1e9 for n in sizes]
    pyp = [time_py_rhs(n, args.py_seconds, args.py_reps, "plain") * 1e9 for n in sizes]
    print(f"== cost of one right-hand side vs number of balls n (balls of 0.1/n kg; C: best of "
          f"51 chunks of >= {args.rhs_seconds * 1e3:g} ms; SciPy: best of {args.py_reps} chunks of "
          f">= {args.py_seconds * 1e3:g} ms) ==")
    hdr = (f"{'n':>5}{'dim':>6}{'C fixed [ns]':>14}{'per ball':>10}{'C rotating [ns]':>17}"
           f"{'per ball':>10}{'NumPy rhs [us]':>16}{'plain rhs [us]':>16}{'best Py / C':>13}")
    print(hdr)
    print("-" * len(hdr))
    for i, n in enumerate(sizes):
        cf, cr = c["fixed_ns"][i], c["rotating_ns"][i]
        print(f"{n:>5d}{8 + 2 * n:>6d}{cf:>14.1f}{cf / n:>10.1f}{cr:>17.1f}{cr / n:>10.1f}"
              f"{pyn[i] / 1e3:>16.2f}{pyp[i] / 1e3:>16.2f}{min(pyn[i], pyp[i]) / cf:>13.0f}")
    print()
    print("least-squares line cost = a + b n over all n:")
    for label, vals, unit, k in (("autobal fixed frame", c["fixed_ns"], "ns", 1.0),
                                 ("autobal rotating frame", c["rotating_ns"], "ns", 1.0),
                                 ("SciPy rhs, NumPy", pyn, "us", 1e-3),
                                 ("SciPy rhs, plain Python", pyp, "us", 1e-3)):
        a, b, r2, mr = fit_line(c["n"], vals)
        print(f"  {label:<24} a = {a * k:8.2f} {unit}, b = {b * k:7.3f} {unit}/ball, "
              f"R^2 = {r2:.6f}, max |residual| / cost = {mr * 100:.1f}%")
    # increments per added ball between consecutive sizes (constant if linear)
    inc = [(c["fixed_ns"][i + 1] - c["fixed_ns"][i]) / (sizes[i + 1] - sizes[i])
           for i in range(len(sizes) - 1)]
    print("  autobal fixed frame, marginal cost per added ball between consecutive n [ns]: " +
          ", ".join(f"{v:.1f}" for v in inc))
    print()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", required=True, help="path of the bench_rotor binary")
    ap.add_argument("--t1", type=float, default=0.5, help="end time [s]")
    ap.add_argument("--tols", default="1e-6,1e-8,1e-10")
    ap.add_argument("--balls", default="2,8", help="ball counts of the transient tables")
    ap.add_argument("--scipy-repeats", type=int, default=5)
    ap.add_argument("--c-repeats", type=int, default=201)
    ap.add_argument("--nmax", type=int, default=256, help="largest n of the RHS-cost table")
    ap.add_argument("--rhs-seconds", type=float, default=0.002,
                    help="length of one timed chunk of C rhs calls (best of 51 chunks)")
    ap.add_argument("--py-seconds", type=float, default=0.003,
                    help="length of one timed chunk of Python rhs calls")
    ap.add_argument("--py-reps", type=int, default=31)
    ap.add_argument("--only", choices=("transient", "rhs"), default=None)
    args = ap.parse_args()
    args.balls = [int(s) for s in args.balls.split(",")]
    tols = [float(s) for s in args.tols.split(",")]

    print("rotor with a ball autobalancer (rotor.md default example), fixed-frame state; "
          "autobal rk8pd vs SciPy solve_ivp")
    print(f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}; "
          f"{platform.processor() or platform.machine()}")
    print()
    if args.only != "rhs":
        transient_tables(args, tols)
    if args.only != "transient":
        rhs_table(args)


if __name__ == "__main__":
    main()
