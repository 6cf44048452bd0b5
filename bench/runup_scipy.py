#!/usr/bin/python3
"""Run-up of the default rotor (issue 15, "Speed"): autobal (GSL rk8pd, C) against SciPy
solve_ivp DOP853 on the same prescribed-speed equations, at matched error; and, in the same
run, the constant-speed rotor transient of rotor_scipy.py (is the constant path as fast as
before the drive existed?).

Problem: the spec's default example (rotor.md; rotor_scipy.py lists the values), two balls of
0.05 kg on r = 0.1 m with h = 0.1 kg/s starting at rest relative to the rotor at psi = 1.0 and
2.5, the rotor at rest at the origin; the prescribed RAMP drive (docs/rotor.md, "Prescribed
spin speed") Omega(t) = OMEGA_B t / T_B for 0 <= t <= T_B and OMEGA_B after (omega_a = 0,
t_a = 0; default OMEGA_B = 500 rad/s, T_B = 20 s), phi_0(t) = integral_0^t Omega; fixed-frame
state (the CLI's default frame), t in [0, T1] (default T1 = T_B: the end of the ramp, so that
no corner of Omega(t) lies inside the interval), final state only.

The SciPy right-hand side is rotor_scipy.py's (the 4x4 system reduced in closed form to the
2x2 one in (u_D'', v_D'')) with every omega replaced by Omega(t), as docs/rotor.md states and
tests/app/drive_check.py (an independent full (4+n) mass-matrix solve) implements:
  - the unbalance at phi_00 = phi_0(t) + psi_0 with the tangential term: its part of s_u'' is
    -m0 r0 (Omega^2 cos phi_00 + Omega' sin phi_00), of s_v'' -m0 r0 (Omega^2 sin phi_00 -
    Omega' cos phi_00) (F_u, F_v);
  - the ball resistance on r (phi' - Omega) in (3.4);
  - the gyroscopic terms C Omega beta' (alpha equation), -C Omega alpha' (beta equation) and
    C Omega' beta in the alpha equation.
Omega, Omega' and phi_0 in closed form (piecewise linear / quadratic), as a user who knows
the profile would write them.  Three versions: plain Python floats for two balls with the
ball loop unrolled (make_rhs_plain2, the fastest), plain floats with a loop over n balls
(make_rhs_plain), NumPy-vectorized over the balls (make_rhs_numpy).  All three are checked
against the library's right-hand side with the same drive at 5 states (`bench_rotor check 2
OMEGA_B T_B`) before anything is timed.

Error: "max rel err" is max_i |y_i - ref_i| / scale_i with scale_i the largest |value| over
the reference trajectory of the group of y_i ({x, y}, {alpha, beta}, {x', y'},
{alpha', beta'}, {phi}, {phi'}), as in rotor_scipy.py; "ball err" the largest absolute error
of a ball angle (rad).  Reference: SciPy DOP853 at rtol = atol = 1e-13 (fastest rhs), checked
against DOP853 at 3e-14 (their difference is the floor below which errors mean nothing) and
shown beside autobal rk8pd at 1e-12, 1e-13, 1e-14.

Matched error: SciPy DOP853 (fastest rhs) on a grid of tolerances (--grid, half decades; the
points whose error exceeds 10x the floor), its time-vs-error curve interpolated (log-log,
piecewise linear) at the error autobal reached at each of --matched-tols; the smallest ratio
there is the headline.  The table at equal nominal tolerance (tol and the max-norm-equivalent
tol/sqrt(dim), as in rotor_scipy.py) is printed too.

Times: best of N runs of the process CPU time (C: CLOCK_PROCESS_CPUTIME_ID around
autobal_transient_run, --c-repeats; Python: time.process_time around solve_ivp,
--scipy-repeats); see rotor_scipy.py and README.md for why CPU time on this shared machine.

Run through bench/run.sh runup (builds bench_rotor first) with /usr/bin/python3.
"""
import argparse
import math
import os
import platform
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp

import rotor_scipy as rs


def ramp(omega_a, omega_b, t_a, t_b):
    """Omega(t), Omega'(t) (right derivative at the corners) and phi_0(t) = int_0^t Omega of
    the ramp: omega_a for t <= t_a, linear to omega_b at t_b, omega_b after (t_a >= 0)."""
    k = (omega_b - omega_a) / (t_b - t_a)
    p_b = omega_a * t_a + 0.5 * (omega_a + omega_b) * (t_b - t_a)  # phi_0(t_b)

    def drive(t):
        if t < t_a:
            return omega_a, 0.0, omega_a * t
        if t < t_b:
            u = t - t_a
            return omega_a + k * u, k, omega_a * t + 0.5 * k * u * u
        return omega_b, 0.0, p_b + omega_b * (t - t_b)

    return drive


def coefficients():
    L = rs.lumped(rs.HW)
    co = dict(M=L["M"], A=L["A"], C=L["C"])
    for k in ("c_x", "c_y", "c_alpha", "c_beta", "c_xbeta", "c_yalpha",
              "h_x", "h_y", "h_alpha", "h_beta", "h_xbeta", "h_yalpha"):
        co[k] = L[k]
    return co


def make_rhs_plain2(drive):
    """Two balls, plain floats, the ball loop unrolled: the fastest Python version here."""
    co = coefficients()
    M, A, C = co["M"], co["A"], co["C"]
    cx, cy, cal, cbe, cxb, cya = (co[k] for k in ("c_x", "c_y", "c_alpha", "c_beta", "c_xbeta",
                                                  "c_yalpha"))
    hx, hy, hal, hbe, hxb, hya = (co[k] for k in ("h_x", "h_y", "h_alpha", "h_beta", "h_xbeta",
                                                  "h_yalpha"))
    d, psi0 = rs.PLANE["d"], rs.PLANE["psi0"]
    s0 = rs.PLANE["m0"] * rs.PLANE["r0"]
    m, r, h, _ = (v.tolist() for v in rs.balls(2))
    m1, m2 = m
    r1, r2 = r
    mr1, mr2 = m1 * r1, m2 * r2
    hr1, hr2 = h[0] * r1, h[1] * r2
    k1, k2 = h[0] / m1, h[1] / m2
    g = 1.0 / M + d * d / A
    iM, iA = 1.0 / M, 1.0 / A
    sin, cos = math.sin, math.cos

    def rhs(t, y):
        x, yy, al, be, xd, yd, ald, bed, p1, p2, pd1, pd2 = y.tolist()
        W, Wd, ph0 = drive(t)
        p0 = ph0 + psi0
        cp, sp = cos(p0), sin(p0)
        s1, c1, s2, c2 = sin(p1), cos(p1), sin(p2), cos(p2)
        ms1, ms2 = m1 * s1, m2 * s2
        Sss = ms1 * s1 + ms2 * s2
        Ssc = ms1 * c1 + ms2 * c2
        Scc = m1 * c1 * c1 + m2 * c2 * c2
        rel1, rel2 = hr1 * (pd1 - W), hr2 * (pd2 - W)
        cen1, cen2 = mr1 * pd1 * pd1, mr2 * pd2 * pd2
        W2 = W * W
        Fu = rel1 * s1 + rel2 * s2 - cen1 * c1 - cen2 * c2 - s0 * (W2 * cp + Wd * sp)
        Fv = -rel1 * c1 - rel2 * c2 - cen1 * s1 - cen2 * s2 - s0 * (W2 * sp - Wd * cp)
        CW = C * W
        f0 = hx * xd + cx * x - hxb * bed - cxb * be
        f1 = hy * yd + cy * yy + hya * ald + cya * al
        f2 = hal * ald + cal * al + CW * bed + C * Wd * be + hya * yd + cya * yy
        f3 = hbe * bed + cbe * be - CW * ald - hxb * xd - cxb * x
        q0x = -(f0 + Fu) * iM
        q0y = -(f1 + Fv) * iM
        q0a = -(f2 - d * Fv) * iA
        q0b = -(f3 + d * Fu) * iA
        bu = q0x + d * q0b
        bv = q0y - d * q0a
        a11 = 1.0 - g * Sss
        a12 = g * Ssc
        a22 = 1.0 - g * Scc
        idet = 1.0 / (a11 * a22 - a12 * a12)
        uD = (a22 * bu - a12 * bv) * idet
        vD = (a11 * bv - a12 * bu) * idet
        Su = -Sss * uD + Ssc * vD
        Sv = Ssc * uD - Scc * vD
        return [xd, yd, ald, bed, q0x - Su * iM, q0y - Sv * iM, q0a + d * Sv * iA,
                q0b - d * Su * iA, pd1, pd2,
                (uD * s1 - vD * c1) / r1 - k1 * (pd1 - W), (uD * s2 - vD * c2) / r2 - k2 * (pd2 - W)]

    return rhs


def make_rhs_plain(drive, n=2):
    """Plain floats, a loop over the n balls (rotor_scipy.make_rhs_plain with Omega(t))."""
    co = coefficients()
    M, A, C = co["M"], co["A"], co["C"]
    cx, cy, cal, cbe, cxb, cya = (co[k] for k in ("c_x", "c_y", "c_alpha", "c_beta", "c_xbeta",
                                                  "c_yalpha"))
    hx, hy, hal, hbe, hxb, hya = (co[k] for k in ("h_x", "h_y", "h_alpha", "h_beta", "h_xbeta",
                                                  "h_yalpha"))
    d, psi0 = rs.PLANE["d"], rs.PLANE["psi0"]
    s0 = rs.PLANE["m0"] * rs.PLANE["r0"]
    m, r, h, _ = (v.tolist() for v in rs.balls(n))
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
        W, Wd, ph0 = drive(t)
        s = [sin(v) for v in phi]
        c = [cos(v) for v in phi]
        p0 = ph0 + psi0
        cp, sp = cos(p0), sin(p0)
        Fu = -s0 * (W * W * cp + Wd * sp)
        Fv = -s0 * (W * W * sp - Wd * cp)
        Sss = Ssc = Scc = 0.0
        for i in idx:
            si, ci, mi, pd = s[i], c[i], m[i], phid[i]
            Sss += mi * si * si
            Ssc += mi * si * ci
            Scc += mi * ci * ci
            rel = hr[i] * (pd - W)
            cen = mr[i] * pd * pd
            Fu += rel * si - cen * ci
            Fv += -rel * ci - cen * si
        f0 = hx * xd + cx * x - hxb * bed - cxb * be
        f1 = hy * yd + cy * yy + hya * ald + cya * al
        f2 = hal * ald + cal * al + C * W * bed + C * Wd * be + hya * yd + cya * yy
        f3 = hbe * bed + cbe * be - C * W * ald - hxb * xd - cxb * x
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
                + phid + [(uD * s[i] - vD * c[i]) / r[i] - kap[i] * (phid[i] - W) for i in idx])

    return rhs


def make_rhs_numpy(drive, n=2):
    """NumPy-vectorized over the balls (rotor_scipy.make_rhs with Omega(t))."""
    co = coefficients()
    M, A, C = co["M"], co["A"], co["C"]
    cx, cy, cal, cbe, cxb, cya = (co[k] for k in ("c_x", "c_y", "c_alpha", "c_beta", "c_xbeta",
                                                  "c_yalpha"))
    hx, hy, hal, hbe, hxb, hya = (co[k] for k in ("h_x", "h_y", "h_alpha", "h_beta", "h_xbeta",
                                                  "h_yalpha"))
    d, psi0 = rs.PLANE["d"], rs.PLANE["psi0"]
    s0 = rs.PLANE["m0"] * rs.PLANE["r0"]
    m, r, h, _ = rs.balls(n)
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
        W, Wd, ph0 = drive(t)
        s = npsin(phi)
        c = npcos(phi)
        ms = m * s
        Sss = ms @ s
        Ssc = ms @ c
        Scc = (m * c) @ c
        rel = hr * (phid - W)
        cen = mr * phid * phid
        p0 = ph0 + psi0
        cp, sp = cos(p0), sin(p0)
        Fu = rel @ s - cen @ c - s0 * (W * W * cp + Wd * sp)
        Fv = -(rel @ c) - cen @ s - s0 * (W * W * sp - Wd * cp)
        f0 = hx * xd + cx * x - hxb * bed - cxb * be
        f1 = hy * yd + cy * yy + hya * ald + cya * al
        f2 = hal * ald + cal * al + C * W * bed + C * Wd * be + hya * yd + cya * yy
        f3 = hbe * bed + cbe * be - C * W * ald - hxb * xd - cxb * x
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
        phidd = (uD * s - vD * c) / r - kap * (phid - W)
        return concat(([xd, yd, ald, bed,
                        q0x - Su / M, q0y - Sv / M, q0a + d * Sv / A, q0b - d * Su / A],
                       phid, phidd))

    return rhs


RHS = {"plain2": make_rhs_plain2, "plain": make_rhs_plain, "numpy": make_rhs_numpy}
LABEL = {"plain2": "plain, 2 balls unrolled", "plain": "plain, loop over balls",
         "numpy": "NumPy over balls"}


def initial_state(drive):
    """Rotor at rest at the origin, balls at rest relative to the rotor: phi = phi_0(0) + psi,
    phi' = Omega(0)."""
    W, _, ph0 = drive(0.0)
    psi = rs.balls(2)[3]
    return np.concatenate((np.zeros(8), ph0 + psi, np.full(2, W)))


def scipy_run(drive, variant, rtol, atol, t1, repeats, t_eval=None):
    rhs = RHS[variant](drive)
    y0 = initial_state(drive)
    best = math.inf
    sol = None
    for _ in range(repeats):
        c0 = time.process_time()
        sol = solve_ivp(rhs, (0.0, t1), y0, method="DOP853", rtol=rtol, atol=atol, t_eval=t_eval)
        best = min(best, time.process_time() - c0)
        if not sol.success:
            raise RuntimeError(f"DOP853 {variant} {rtol:g}: {sol.message}")
    return best, sol.nfev, sol.y[:, -1], sol


def c_runup(args, tol, repeats):
    return rs.bench(args.bench, "runup", "rk8pd", tol, tol, repr(args.t1), repeats,
                    repr(args.omega_b), repr(args.t_b))


def check_rhs(args, drive):
    data = rs.bench(args.bench, "check", 2, repr(args.omega_b), repr(args.t_b))
    worst = {}
    for v, make in RHS.items():
        rhs = make(drive)
        w = 0.0
        for st in data["states"]:
            mine = np.asarray(rhs(st["t"], np.array(st["y"])), float)
            theirs = np.array(st["dydt"])
            sc = rs.group_scales(2, theirs[:, None])
            w = max(w, float(np.max(np.abs(mine - theirs) / sc)))
        worst[v] = w
    return worst, [st["t"] for st in data["states"]]


def time_per_call(rhs, drive, seconds=0.003, reps=31):
    """Seconds per call of rhs on 16 plausible run-up states (best of reps chunks)."""
    rng = np.random.default_rng(4321)
    states = []
    for k in range(16):
        t = 1.0 + 1.1 * k
        W, _, ph0 = drive(t)
        y = np.concatenate((rng.uniform(-1, 1, 2) * 2e-4, rng.uniform(-1, 1, 2) * 1e-3,
                            rng.uniform(-1, 1, 2) * 0.1, rng.uniform(-1, 1, 2) * 0.5,
                            ph0 + rng.uniform(-math.pi, math.pi, 2), W + rng.uniform(-50, 50, 2)))
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


def err_of(y, ref, scale):
    return float(np.max(np.abs(y - ref) / scale)), float(np.max(np.abs(y - ref)[8:10]))


def load():
    try:
        return "load average %.2f %.2f %.2f" % os.getloadavg()
    except OSError:
        return "load average unknown"


def constant_speed(args):
    """The constant-speed transient of rotor_scipy.py (2 balls, omega = 500, t in [0, 0.5] s),
    the same commands, in the same run: autobal vs SciPy DOP853 (plain and NumPy rhs)."""
    tols = [float(s) for s in args.tols.split(",")]
    print(f"== constant speed, same run: rotor_scipy.py's 2-ball transient, omega = {rs.OMEGA:g} "
          f"rad/s, t in [0, 0.5] s; {load()} ==")
    hdr = (f"{'tol':>8}{'autobal [ms]':>14}{'evals':>8}{'ns/eval':>9}{'DOP853 plain [ms]':>19}"
           f"{'ratio':>8}{'DOP853 NumPy [ms]':>19}{'ratio':>8}")
    print(hdr)
    print("-" * len(hdr))
    out = []
    for tol in tols:
        c = rs.bench(args.bench, "run", 2, "rk8pd", tol, tol, "0.5", args.c_const_repeats)
        tc = c["cpu_seconds_min"]
        tp, _, _, _ = rs.scipy_run(2, "DOP853", tol, tol, 0.5, args.scipy_repeats, variant="plain")
        tn, _, _, _ = rs.scipy_run(2, "DOP853", tol, tol, 0.5, args.scipy_repeats, variant="numpy")
        out.append((tol, tc, c["rhs_evals"], tp / tc, tn / tc))
        print(f"{tol:>8.0e}{tc * 1e3:>14.3f}{c['rhs_evals']:>8d}{tc / c['rhs_evals'] * 1e9:>9.0f}"
              f"{tp * 1e3:>19.3f}{tp / tc:>7.0f}x{tn * 1e3:>19.3f}{tn / tc:>7.0f}x")
    if args.before:
        print(f"  the library before the drive ({args.before}): constant-speed runs of both "
              f"binaries alternately, 3 rounds of best-of-{args.c_const_repeats}, best of each:")
        for tol, _, ev, _, _ in out:
            tb = tc = math.inf
            for _ in range(3):
                b = rs.bench(args.before, "run", 2, "rk8pd", tol, tol, "0.5", args.c_const_repeats)
                c = rs.bench(args.bench, "run", 2, "rk8pd", tol, tol, "0.5", args.c_const_repeats)
                tb, tc = min(tb, b["cpu_seconds_min"]), min(tc, c["cpu_seconds_min"])
            print(f"{tol:>8.0e}  before {tb * 1e3:.3f} ms ({b['rhs_evals']} evals), now "
                  f"{tc * 1e3:.3f} ms ({ev} evals): now / before = {tc / tb:.3f}"
                  + ("" if b["y"] == c["y"] else "  (final states differ: "
                     f"{max(abs(u - v) for u, v in zip(b['y'], c['y'])):.1e})"))
    print("  (README, vectorized sin/cos library, 2026-11-21: DOP853 plain / autobal 72-74x, "
          "NumPy 197-202x; 0.243, 0.428, 0.746 ms at 1e-6, 1e-8, 1e-10)")
    print()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", required=True, help="path of the bench_rotor binary")
    ap.add_argument("--omega-b", type=float, default=500.0, help="speed at the end of the ramp [rad/s]")
    ap.add_argument("--t-b", type=float, default=20.0, help="end of the ramp [s]")
    ap.add_argument("--t1", type=float, default=None, help="end time [s] (default: t_b)")
    ap.add_argument("--tols", default="1e-6,1e-8,1e-10",
                    help="tolerances of the table at equal nominal tolerance")
    ap.add_argument("--matched-tols", default="1e-5,1e-6,1e-7,1e-8,1e-9,1e-10",
                    help="autobal's tolerances at matched error")
    ap.add_argument("--grid", default="1e-5,1e-12",
                    help="range of SciPy's tolerances for the matched-error curve (half decades)")
    ap.add_argument("--scipy-repeats", type=int, default=3)
    ap.add_argument("--c-repeats", type=int, default=21)
    ap.add_argument("--c-const-repeats", type=int, default=201)
    ap.add_argument("--before", default=None,
                    help="a bench_rotor built on an older library: its constant-speed runs are "
                         "timed beside this one's")
    ap.add_argument("--only", choices=("runup", "constant"), default=None)
    ap.add_argument("--quick", action="store_true",
                    help="smoke run: t_b = t1 = 1 s, omega_b = 25 rad/s, one repeat, tols 1e-6,1e-8, "
                         "grid 1e-5..1e-9; checks the right-hand sides and that the table is made")
    args = ap.parse_args()
    if args.quick:
        args.t_b, args.omega_b, args.t1 = 1.0, 25.0, 1.0
        args.tols, args.grid, args.matched_tols = "1e-6,1e-8", "1e-5,1e-9", "1e-6,1e-7"
        args.scipy_repeats = args.c_repeats = args.c_const_repeats = 1
    if args.t1 is None:
        args.t1 = args.t_b
    tols = [float(s) for s in args.tols.split(",")]
    mtols = [float(s) for s in args.matched_tols.split(",")]
    g0, g1 = (round(-2 * math.log10(float(s))) for s in args.grid.split(","))
    grid = [10.0 ** (-e / 2.0) for e in range(g0, g1 + 1)]

    print("run-up of the rotor with a ball autobalancer (rotor.md default example, 2 balls), "
          "fixed-frame state; autobal rk8pd vs SciPy solve_ivp DOP853")
    print(f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}; "
          f"{platform.processor() or platform.machine()}; {load()}")
    print()
    if args.only != "runup":
        constant_speed(args)
    if args.only == "constant":
        return

    drive = ramp(0.0, args.omega_b, 0.0, args.t_b)
    worst, ts = check_rhs(args, drive)
    print(f"== run-up: Omega = {args.omega_b:g} t / {args.t_b:g} rad/s (ramp from 0 at t = 0 to "
          f"{args.omega_b:g} rad/s at t = {args.t_b:g} s), t in [0, {args.t1:g}] s ==")
    print("SciPy rhs vs library rhs (same drive) at t = " + ", ".join(f"{t:g}" for t in ts) +
          ": max difference " + ", ".join(f"{LABEL[v]} {w:.1e}" for v, w in worst.items()) +
          " (relative to each group's largest |component|)")
    if max(worst.values()) > 1e-10:
        raise RuntimeError("a SciPy right-hand side differs from the library's")
    per_call = {v: time_per_call(RHS[v](drive), drive) for v in RHS}
    print("one SciPy rhs call: " + ", ".join(f"{LABEL[v]} {per_call[v] * 1e6:.2f} us"
                                              for v in RHS))
    fast = min(per_call, key=per_call.get)
    print(f"fastest: {LABEL[fast]}; the matched-error curve uses it")

    tgrid = np.linspace(0.0, args.t1, 20001)
    tref0 = time.process_time()
    _, ref_nfev, ref, rsol = scipy_run(drive, fast, 1e-13, 1e-13, args.t1, 1, t_eval=tgrid)
    tref = time.process_time() - tref0
    scale = rs.group_scales(2, rsol.y)
    _, ref2_nfev, ref2, _ = scipy_run(drive, fast, 3e-14, 3e-14, args.t1, 1)
    floor, floorb = err_of(ref2, ref, scale)
    cref = {}
    for tol in (1e-12, 1e-13, 1e-14):
        c = c_runup(args, tol, 1)
        cref[tol] = (c["rhs_evals"],) + err_of(np.array(c["y"]), ref, scale)
    print(f"reference: SciPy DOP853 rtol=atol=1e-13 ({ref_nfev} rhs evals, {tref:.1f} s); DOP853 "
          f"at 3e-14 ({ref2_nfev} evals) differs from it by {floor:.1e} (max rel) / {floorb:.1e} rad "
          "(balls)")
    print("  autobal rk8pd near its limit differs from it by: " +
          "; ".join(f"tol {tol:.0e} ({v[0]} evals) {v[1]:.1e} / {v[2]:.1e} rad"
                    for tol, v in cref.items()))
    print("state scales: |x,y| %.2e m, |alpha,beta| %.2e rad, |x',y'| %.2e m/s, "
          "|alpha',beta'| %.2e rad/s, |phi| %.1f rad, |phi'| %.1f rad/s"
          % (scale[0], scale[2], scale[4], scale[6], scale[8], scale[10]))
    W, _, ph0 = drive(args.t1)
    psi_end = np.mod(ref[8:10] - ph0 + math.pi, 2 * math.pi) - math.pi
    print(f"at t1: Omega = {W:g} rad/s; ball rates {ref[10]:.3f}, {ref[11]:.3f} rad/s; "
          f"psi = phi - phi_0 = {psi_end[0]:.4f}, {psi_end[1]:.4f} rad")
    print()

    # equal nominal tolerance
    hdr = (f"{'solver':<34}{'tol':>8}{'rhs evals':>11}{'max rel err':>12}{'ball err':>10}"
           f"{'time [ms]':>12}{'/ autobal':>11}")
    print(hdr)
    print("-" * len(hdr))
    crun = {}
    for tol in tols:
        c = c_runup(args, tol, args.c_repeats)
        tc = c["cpu_seconds_min"]
        e, eb = err_of(np.array(c["y"]), ref, scale)
        crun[tol] = (tc, e, c["rhs_evals"])
        print(f"{'autobal rk8pd (C)':<34}{tol:>8.0e}{c['rhs_evals']:>11d}{e:>12.2e}{eb:>10.1e}"
              f"{tc * 1e3:>12.3f}{1.0:>11.1f}")
        for v in ("plain2", "plain", "numpy"):
            for fac, lab in ((1.0, ""), (1.0 / math.sqrt(12), " tol/sqrt(12)")):
                ts_, nfev, yend, _ = scipy_run(drive, v, tol * fac, tol * fac, args.t1,
                                               args.scipy_repeats)
                e, eb = err_of(yend, ref, scale)
                print(f"{'DOP853 ' + v + lab:<34}{tol * fac:>8.1e}{nfev:>11d}{e:>12.2e}{eb:>10.1e}"
                      f"{ts_ * 1e3:>12.1f}{ts_ / tc:>11.1f}")
        print()
    per_c = min(v[0] / v[2] for v in crun.values())
    print(f"time per rhs evaluation incl. the stepper: autobal {per_c * 1e9:.0f} ns")
    print()

    # matched error
    pts = []
    print(f"SciPy DOP853 ({LABEL[fast]}) on {len(grid)} tolerances for the matched-error curve:")
    print(f"{'tol':>10}{'rhs evals':>11}{'max rel err':>12}{'time [ms]':>12}")
    for tol in grid:
        ts_, nfev, yend, _ = scipy_run(drive, fast, tol, tol, args.t1, args.scipy_repeats)
        e, _ = err_of(yend, ref, scale)
        used = e > 10.0 * floor
        if used:
            pts.append((e, ts_, nfev))
        print(f"{tol:>10.1e}{nfev:>11d}{e:>12.2e}{ts_ * 1e3:>12.1f}"
              + ("" if used else "   (below 10x the references' difference: not used)"))
    pts.sort()
    le = np.log([p[0] for p in pts])
    lt = np.log([p[1] for p in pts])
    ln = np.log([p[2] for p in pts])
    per_eval = float(np.median([p[1] / p[2] for p in pts])) if pts else math.nan
    print()
    print("matched error: SciPy DOP853 time interpolated (log-log) at autobal's error; "
          f"{load()}")
    print("(also the DOP853 evaluations interpolated the same way, their ratio to autobal's, and "
          "the time ratio recomputed as evaluations x the median time per evaluation over the "
          f"grid, {per_eval * 1e6:.2f} us, which smooths SciPy's timing noise)")
    print(f"{'autobal tol':>12}{'evals':>8}{'autobal err':>13}{'autobal [ms]':>14}{'DOP853 [ms]':>13}"
          f"{'ratio':>8}{'DOP853 evals':>14}{'evals ratio':>13}{'ratio (evals)':>15}")
    matched = []
    for tol in mtols:
        if tol not in crun:
            c = c_runup(args, tol, args.c_repeats)
            crun[tol] = (c["cpu_seconds_min"], err_of(np.array(c["y"]), ref, scale)[0],
                         c["rhs_evals"])
        tc, e, ev = crun[tol]
        if len(pts) < 2 or not (le[0] <= math.log(e) <= le[-1]):
            print(f"{tol:>12.0e}{ev:>8d}{e:>13.2e}{tc * 1e3:>14.3f}   outside the DOP853 error range")
            continue
        tsp = math.exp(float(np.interp(math.log(e), le, lt)))
        nsp = math.exp(float(np.interp(math.log(e), le, ln)))
        matched.append(tsp / tc)
        print(f"{tol:>12.0e}{ev:>8d}{e:>13.2e}{tc * 1e3:>14.3f}{tsp * 1e3:>13.1f}{tsp / tc:>7.0f}x"
              f"{nsp:>14.0f}{nsp / ev:>13.2f}{nsp * per_eval / tc:>14.0f}x")
    if matched:
        m = min(matched)
        print(f"smallest time ratio SciPy DOP853 / autobal at matched error: {m:.0f}x "
              f"(target >= 50x: {'met' if m >= 50 else 'NOT met'})")
    else:
        print("no autobal error inside the DOP853 error range: no matched ratio")


if __name__ == "__main__":
    main()
