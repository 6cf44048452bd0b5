#!/usr/bin/python3
"""Stiction (issue 16, "Speed"): the default rotor with rolling resistance and stiction (EXACT
law, stick-slip switching at events) against the same rotor without friction (autobal, one
member and an ensemble of 256 members on 2 threads), against SciPy solve_ivp with events at
matched error, and the constant-speed / run-up benches of the library before friction was merged
(does the event machinery cost anything when friction is off?).

Problem: the spec's default example (rotor.md; rotor_scipy.py lists the values: two balls of
0.05 kg on r = 0.1 m, h = 0.1 kg/s, unbalance 0.02 kg at 0.1 m), f = 0.01, mu = 0.02 for both
balls, the prescribed RAMP drive Omega = 50 + 450 t / 20 rad/s (a run-up; it starts at 50
rad/s because with friction a ball needs N > 0: at Omega = 0 it has none), t in [0, 20] s, the rotor at rest at the origin, the balls at rest relative to the rotor
(psi = 1.0, 2.5 for the single member; uniform in [-pi, pi) for the ensemble members); fixed
frame; final state only.  In this run-up the balls start stuck, break free at 136 rad/s, stick
and slip up to 153 rad/s, then slip to the end (the switch counts are printed).

SciPy's right-hand side is written from docs/device.md section 3 ("Equations as coded"),
independently of the C code: a slipping ball with sigma = its mode (+1/-1) has
  phi'' = (A_u u_D'' + A_v v_D'') / r - (h/m) psi' - f sigma phi'^2,
  A_u = sin phi + f sigma cos phi,  A_v = f sigma sin phi - cos phi;
a stuck ball (mode 0) is a mass fixed to the rotor (phi' = Omega, phi'' = Omega') entering
s'' like the unbalance.  s'' is then linear in (u_D'', v_D''), and the rotor equations
M x'' + f_x + s_u'' = 0 (etc., runup_scipy.py's rotor part) reduce to a non-symmetric 2x2
system in (u_D'', v_D'').  Normal force N = m (r phi'^2 - u_D'' cos phi - v_D'' sin phi),
holding force H = m (r Omega' - u_D'' sin phi + v_D'' cos phi).  Switching (section 3,
"Switching (EXACT)"): events sigma psi' (falling, a slipping ball stops) and |H| - mu N
(rising, a stuck ball breaks free), terminal; at an event: every slipping ball with
sigma psi' <= 0 sticks (psi' = 0), then while a stuck ball has |H| > mu N the one with the
largest (|H| - mu N)/N slips opposite to H (a ball that had just reached psi' = 0 gets its rate
back: a reversal); solve_ivp is restarted from there (a restart loop).  The right-hand side is
checked against the library's (`bench_friction check`: 6 states, every mode pattern) and its N
and H against autobal_rotor_normal_forces / holding_forces before anything is timed.

Error: as runup_scipy.py ("max rel err": per group of components, scaled by the group's largest
|value| over the reference trajectory).  Reference: a tight SciPy run (DOP853 1e-13); it must
agree with a tight autobal run (rk8pd 1e-13) first.  Matched error: SciPy DOP853 on a grid of
tolerances, its time-vs-error curve interpolated (log-log) at autobal's error.  Times: best of N
of the process CPU time (C: CLOCK_PROCESS_CPUTIME_ID around the whole member, rotor and driver
allocation included; Python: time.process_time around the restart loop).

Run through bench/run.sh friction (builds bench_friction and bench_rotor) with /usr/bin/python3.
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
import runup_scipy as ru

F, MU = 0.01, 0.02


def load():
    return ru.load()


def make_model(drive, f=F, mu=MU):
    """The friction right-hand side for given modes, the forces, and the settling rules."""
    co = ru.coefficients()
    M, A, C = co["M"], co["A"], co["C"]
    cx, cy, cal, cbe, cxb, cya = (co[k] for k in ("c_x", "c_y", "c_alpha", "c_beta", "c_xbeta",
                                                  "c_yalpha"))
    hx, hy, hal, hbe, hxb, hya = (co[k] for k in ("h_x", "h_y", "h_alpha", "h_beta", "h_xbeta",
                                                  "h_yalpha"))
    d, psi0 = rs.PLANE["d"], rs.PLANE["psi0"]
    s0 = rs.PLANE["m0"] * rs.PLANE["r0"]
    m, r, h, _ = (v.tolist() for v in rs.balls(2))
    g = 1.0 / M + d * d / A
    sin, cos = math.sin, math.cos

    def accel(t, y, modes):
        """(dydt, uD, vD, W, Wd)."""
        x, yy, al, be, xd, yd, ald, bed, p1, p2, pd1, pd2 = y
        W, Wd, ph0 = drive(t)
        p0 = ph0 + psi0
        cp, sp = cos(p0), sin(p0)
        W2 = W * W
        Fu = -s0 * (W2 * cp + Wd * sp)
        Fv = -s0 * (W2 * sp - Wd * cp)
        auu = auv = avu = avv = 0.0
        ball = []
        for i, (ph, pd) in enumerate(((p1, pd1), (p2, pd2))):
            s, c = sin(ph), cos(ph)
            mi, ri = m[i], r[i]
            mr = mi * ri
            sg = modes[i]
            if sg == 0:
                Fu += mr * (-Wd * s - W2 * c)
                Fv += mr * (Wd * c - W2 * s)
                ball.append((s, c, 0.0, 0.0, 0.0))
            else:
                fs = f * sg
                K = -(h[i] / mi) * (pd - W) - fs * pd * pd
                Au = s + fs * c
                Av = fs * s - c
                cen = mr * pd * pd
                Fu += -mr * K * s - cen * c
                Fv += mr * K * c - cen * s
                auu -= mi * s * Au
                auv -= mi * s * Av
                avu += mi * c * Au
                avv += mi * c * Av
                ball.append((s, c, K, Au, Av))
        CW = C * W
        f0 = hx * xd + cx * x - hxb * bed - cxb * be
        f1 = hy * yd + cy * yy + hya * ald + cya * al
        f2 = hal * ald + cal * al + CW * bed + C * Wd * be + hya * yd + cya * yy
        f3 = hbe * bed + cbe * be - CW * ald - hxb * xd - cxb * x
        q0x = -(f0 + Fu) / M
        q0y = -(f1 + Fv) / M
        q0a = -(f2 - d * Fv) / A
        q0b = -(f3 + d * Fu) / A
        bu = q0x + d * q0b
        bv = q0y - d * q0a
        a11, a12, a21, a22 = 1.0 + g * auu, g * auv, g * avu, 1.0 + g * avv
        idet = 1.0 / (a11 * a22 - a12 * a21)
        uD = (a22 * bu - a12 * bv) * idet
        vD = (a11 * bv - a21 * bu) * idet
        su = Fu + auu * uD + auv * vD
        sv = Fv + avu * uD + avv * vD
        out = [xd, yd, ald, bed, -(f0 + su) / M, -(f1 + sv) / M, -(f2 - d * sv) / A,
               -(f3 + d * su) / A]
        vel, acc = [], []
        for i, (s, c, K, Au, Av) in enumerate(ball):
            if modes[i] == 0:
                vel.append(W)
                acc.append(Wd)
            else:
                vel.append((pd1, pd2)[i])
                acc.append(K + (Au * uD + Av * vD) / r[i])
        return out + vel + acc, uD, vD, W, Wd

    def forces(t, y, modes):
        _, uD, vD, W, Wd = accel(t, y, modes)
        N, H = [], []
        for i in range(2):
            s, c = sin(y[8 + i]), cos(y[8 + i])
            pd = W if modes[i] == 0 else y[10 + i]
            N.append(m[i] * (r[i] * pd * pd - uD * c - vD * s))
            H.append(m[i] * (r[i] * Wd - uD * s + vD * c) if modes[i] == 0 else math.nan)
        return N, H

    def make_rhs(modes):
        md = tuple(modes)

        def rhs(t, y):
            return accel(t, y.tolist(), md)[0]

        return rhs

    def settle(t, y, modes, initial, fired=-1):
        """Apply the switching rules in place; returns (sticks, slips, reversals).  fired: the
        ball whose event was located (solve_ivp's root may lie a rounding error before the
        crossing; the library's lies on the far side): it switches even if its switching
        function is still a rounding error short of 0, as on the far side."""
        W = drive(t)[0]
        reached, saved = [False, False], [0.0, 0.0]
        n_stick = n_slip = n_rev = 0
        was_stuck = [md == 0 for md in modes]
        for i in range(2):
            rel = y[10 + i] - W
            if initial:
                modes[i] = 0 if rel == 0.0 else (1 if rel > 0 else -1)
                if modes[i] == 0:
                    reached[i] = True
                    was_stuck[i] = False
            elif modes[i] != 0 and (modes[i] * rel <= 0.0 or i == fired):
                modes[i] = 0
                reached[i] = True
                saved[i] = y[10 + i]
                y[10 + i] = W
        while True:
            N, H = forces(t, list(y), modes)
            best, bi = 0.0, -1
            for i in range(2):
                if modes[i] == 0:
                    if N[i] <= 0.0:
                        raise RuntimeError(f"ball {i} would leave its track at t = {t}")
                    ex = (abs(H[i]) - mu * N[i]) / N[i]
                    if i == fired and was_stuck[i]:
                        ex = max(ex, 1e-300)  # located crossing: on its far side
                    if ex > best:
                        best, bi = ex, i
            if bi < 0:
                break
            modes[bi] = -1 if H[bi] > 0 else 1
            if reached[bi] and not initial:
                y[10 + bi] = saved[bi]
                n_rev += 1
                reached[bi] = False
        for i in range(2):
            if reached[i] and modes[i] == 0 and not initial:
                n_stick += 1
            if was_stuck[i] and modes[i] != 0:
                n_slip += 1
        return n_stick, n_slip, n_rev

    def events(modes):
        evs = []
        for i in range(2):
            if modes[i] == 0:
                def ev(t, y, i=i):
                    N, H = forces(t, y.tolist(), md)
                    return abs(H[i]) - mu * N[i]
                ev.direction = 1.0
            else:
                def ev(t, y, i=i):
                    return md[i] * (y[10 + i] - drive(t)[0])
                ev.direction = -1.0
            ev.terminal = True
            evs.append(ev)
        md = tuple(modes)
        return evs

    return accel, forces, make_rhs, settle, events


def hybrid_run(drive, model, y0, t1, rtol, atol, keep=False):
    """The restart loop; returns (y(t1), nfev, switches, modes, trajectory points or None)."""
    _, _, make_rhs, settle, events = model
    y = list(y0)
    modes = [1, 1]
    settle(0.0, y, modes, True)
    t = 0.0
    nfev = 0
    sw = [0, 0, 0]
    traj = [] if keep else None
    while True:
        sol = solve_ivp(make_rhs(modes), (t, t1), np.array(y), method="DOP853", rtol=rtol,
                        atol=atol, events=events(modes))
        nfev += sol.nfev
        if keep:
            traj.append(sol.y)
        if sol.status == -1:
            raise RuntimeError(f"DOP853 {rtol:g}: {sol.message}")
        if sol.status == 0:
            return sol.y[:, -1], nfev, sw, modes, traj
        te = [ts[0] for ts in sol.t_events if len(ts)]
        k = int(np.argmin([ts[0] if len(ts) else math.inf for ts in sol.t_events]))
        t = min(te)
        y = sol.y_events[k][0].tolist()
        a, b, c = settle(t, y, modes, False, k)
        sw[0] += a
        sw[1] += b
        sw[2] += c


def timed_hybrid(drive, model, y0, t1, tol, repeats):
    best = math.inf
    for _ in range(repeats):
        c0 = time.process_time()
        out = hybrid_run(drive, model, y0, t1, tol, tol)
        best = min(best, time.process_time() - c0)
    return (best,) + out[:4]


def fb(args, *a):
    return rs.bench(args.bench_friction, *a)


def member(args, law, tol, repeats, seed=0, event_tol=0.0, h_init=0.0):
    f, mu = (F, MU) if law == "exact" else (0, 0)
    return fb(args, "run", law, f, mu, tol, tol, args.t1, repeats, args.omega_a, args.omega_b,
              args.t_b, seed, event_tol, h_init)


def check(args, model, drive):
    accel, forces, _, _, _ = model
    data = fb(args, "check", F, MU, args.omega_a, args.omega_b, args.t_b)
    wd = wf = 0.0
    for st in data["states"]:
        mine = np.array(accel(st["t"], st["y"], st["modes"])[0])
        theirs = np.array(st["dydt"])
        sc = rs.group_scales(2, theirs[:, None])
        wd = max(wd, float(np.max(np.abs(mine - theirs) / sc)))
        N, H = forces(st["t"], st["y"], st["modes"])
        for i in range(2):
            wf = max(wf, abs(N[i] - st["N"][i]) / abs(st["N"][i]))
            if st["modes"][i] == 0:
                wf = max(wf, abs(H[i] - st["H"][i]) / abs(st["N"][i]))
    return wd, wf, len(data["states"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench-friction", required=True)
    ap.add_argument("--bench-rotor", required=True)
    ap.add_argument("--before", default=None, help="bench_rotor built on the library before friction")
    ap.add_argument("--omega-a", type=float, default=50.0)
    ap.add_argument("--omega-b", type=float, default=500.0)
    ap.add_argument("--t-b", type=float, default=20.0)
    ap.add_argument("--t1", type=float, default=20.0)
    ap.add_argument("--tols", default="1e-9,1e-10,1e-11", help="per-member table")
    ap.add_argument("--matched-tols", default="1e-6,1e-7,1e-8,1e-9,1e-10,1e-11")
    ap.add_argument("--h-init", type=float, default=1e-4,
                    help="first trial step [s] of autobal's matched-error runs (0: automatic, which "
                         "fails at rtol >= 1e-8 on this problem: a stage state with N < 0)")
    ap.add_argument("--grid", default="1e-5,1e-12")
    ap.add_argument("--members", type=int, default=256)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--ens-tol", type=float, default=1e-10)
    ap.add_argument("--c-repeats", type=int, default=7)
    ap.add_argument("--scipy-repeats", type=int, default=2)
    ap.add_argument("--only", choices=("member", "scipy", "before"), default=None)
    ap.add_argument("--quick", action="store_true", help="smoke run: 2 s, 8 members, few tols")
    args = ap.parse_args()
    if args.quick:
        args.t1 = 2.0
        args.tols, args.matched_tols, args.grid = "1e-9", "1e-7,1e-9,1e-10", "1e-6,1e-11"
        args.members, args.c_repeats, args.scipy_repeats = 8, 1, 1
    drive = ru.ramp(args.omega_a, args.omega_b, 0.0, args.t_b)
    model = make_model(drive)
    print("rotor with stiction (default example, 2 balls, f = %g, mu = %g, EXACT law), run-up "
          "Omega = %g -> %g rad/s over [0, %g] s, t in [0, %g] s; fixed frame"
          % (F, MU, args.omega_a, args.omega_b, args.t_b, args.t1))
    print(f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}; "
          f"{os.cpu_count()} cpus; {load()}")
    print()

    if args.only in (None, "member"):
        print(f"== (a) per member: EXACT friction vs frictionless (law none), same tolerances; "
              f"best of {args.c_repeats} CPU times; {load()} ==")
        hdr = (f"{'tol':>8}{'law':>7}{'cpu [ms]':>10}{'steps':>8}{'rhs evals':>11}{'events':>8}"
               f"{'resets':>8}{'stick/slip/rev':>16}{'friction/none':>15}")
        print(hdr)
        print("-" * len(hdr))
        for tol in [float(s) for s in args.tols.split(",")]:
            res = {}
            for law in ("none", "exact"):
                res[law] = member(args, law, tol, args.c_repeats)
            for law in ("none", "exact"):
                c = res[law]
                ratio = c["cpu_seconds_min"] / res["none"]["cpu_seconds_min"]
                print(f"{tol:>8.0e}{law:>7}{c['cpu_seconds_min'] * 1e3:>10.2f}{c['steps']:>8d}"
                      f"{c['rhs_evals']:>11d}{c['events']:>8d}{c['resets']:>8d}"
                      f"{'%d/%d/%d' % (c['sticks'], c['slips'], c['reversals']):>16}{ratio:>14.2f}x")
        print()
        print(f"ensemble: {args.members} members (psi uniform in [-pi, pi), seeds 1..{args.members}) on "
              f"{args.threads} threads, rtol = atol = {args.ens_tol:g}; {load()}")
        ens = {}
        for law in ("none", "exact", "none", "exact"):  # alternate, keep the best of two
            f, mu = (F, MU) if law == "exact" else (0, 0)
            e = fb(args, "ensemble", law, f, mu, args.ens_tol, args.ens_tol, args.t1, args.members,
                   args.threads, args.omega_a, args.omega_b, args.t_b)
            if law not in ens or e["wall_seconds"] < ens[law]["wall_seconds"]:
                ens[law] = e
        hdr = (f"{'law':>7}{'wall [s]':>10}{'cpu [s]':>9}{'members/s':>11}{'members/cpu-s':>15}"
               f"{'sticks':>8}{'slips':>7}{'rev':>5}{'stuck at end':>14}{'failed':>8}")
        print(hdr)
        print("-" * len(hdr))
        for law in ("none", "exact"):
            e = ens[law]
            print(f"{law:>7}{e['wall_seconds']:>10.2f}{e['cpu_seconds']:>9.2f}"
                  f"{e['members_per_second']:>11.2f}{e['members_per_cpu_second']:>15.2f}"
                  f"{e['sticks']:>8d}{e['slips']:>7d}{e['reversals']:>5d}"
                  f"{e['balls_stuck_final']:>10d}/{2 * e['members']:<3d}{e['failed']:>8d}")
        rw = ens["none"]["members_per_second"] / ens["exact"]["members_per_second"]
        rc = ens["none"]["members_per_cpu_second"] / ens["exact"]["members_per_cpu_second"]
        print(f"frictionless / friction members per second: {rw:.2f}x (wall), {rc:.2f}x (CPU) "
              f"(target: friction no more than 3x slower: {'met' if max(rw, rc) <= 3 else 'NOT met'})")
        print()

    if args.only in (None, "scipy"):
        wd, wf, ns = check(args, model, drive)
        print(f"== (b) SciPy solve_ivp DOP853 with terminal events and a restart loop; {load()} ==")
        print(f"SciPy rhs vs library rhs at {ns} states (every mode pattern): max difference "
              f"{wd:.1e} (relative to each group's largest |component|); N and H: {wf:.1e} "
              "(relative to N)")
        if wd > 1e-12 or wf > 1e-12:  # measured 1.3e-13 (a state where the forces cancel tenfold)
            raise RuntimeError("the SciPy friction right-hand side differs from the library's")
        y0 = ru.initial_state(drive)
        c0 = time.process_time()
        ref, ref_nfev, ref_sw, ref_modes, traj = hybrid_run(drive, model, y0, args.t1, 1e-13, 1e-13,
                                                            keep=True)
        tref = time.process_time() - c0
        scale = rs.group_scales(2, np.concatenate(traj, axis=1))
        ref2, ref2_nfev, _, _, _ = hybrid_run(drive, model, y0, args.t1, 3e-14, 3e-14)
        d2, d2b = ru.err_of(ref2, ref, scale)
        print(f"reference: SciPy DOP853 1e-13 ({ref_nfev} evals, {tref:.1f} s; sticks/slips/"
              f"reversals {ref_sw[0]}/{ref_sw[1]}/{ref_sw[2]}, final modes {ref_modes}); DOP853 at "
              f"3e-14 ({ref2_nfev} evals) differs by {d2:.1e} / {d2b:.1e} rad (balls) (not used as the "
              "floor: see README)")
        floor = 0.0
        for tol in (1e-12, 1e-13):
            c = member(args, "exact", tol, 1, event_tol=1e-14)
            e, eb = ru.err_of(np.array(c["y"]), ref, scale)
            print(f"  autobal rk8pd {tol:.0e}, event_tol 1e-14 s ({c['rhs_evals']} evals, "
                  f"sticks/slips/reversals {c['sticks']}/{c['slips']}/{c['reversals']}, final modes "
                  f"{c['modes']}): differs from it by {e:.1e} / {eb:.1e} rad")
            floor = max(floor, e)
        print(f"error floor (the references agree to): {floor:.1e}")
        print()
        mtols = [float(s) for s in args.matched_tols.split(",")]
        g0, g1 = (round(-2 * math.log10(float(s))) for s in args.grid.split(","))
        grid = [10.0 ** (-k / 2.0) for k in range(g0, g1 + 1)]
        print(f"SciPy DOP853 hybrid on {len(grid)} tolerances (best of {args.scipy_repeats} CPU times):")
        print(f"{'tol':>10}{'rhs evals':>11}{'switches':>10}{'max rel err':>12}{'time [ms]':>12}")
        pts, allp = [], []
        for tol in grid:
            ts_, yend, nfev, sw, _ = timed_hybrid(drive, model, y0, args.t1, tol, args.scipy_repeats)
            e, _ = ru.err_of(yend, ref, scale)
            allp.append((e, ts_))
            used = e > 10.0 * floor
            if used:
                pts.append((e, ts_, nfev))
            print(f"{tol:>10.1e}{nfev:>11d}{'%d/%d/%d' % tuple(sw):>10}{e:>12.2e}{ts_ * 1e3:>12.1f}"
                  + ("" if used else "   (below 10x the floor: not interpolated)"))
        pts.sort()
        le = np.log([p[0] for p in pts])
        lt = np.log([p[1] for p in pts])
        print()
        print(f"matched error; {load()}:")
        print("  'interp': SciPy time interpolated (log-log, points sorted by error) at autobal's "
              "error; 'cheapest': the fastest SciPy run of the grid whose error is <= max(autobal's "
              "error, the floor) (a bound from above on SciPy's time at that error, up to the grid "
              "step)")
        print(f"{'autobal tol':>12}{'evals':>8}{'switches':>10}{'autobal err':>13}{'autobal [ms]':>14}"
              f"{'interp [ms]':>13}{'ratio':>8}{'cheapest [ms]':>15}{'ratio':>8}")
        matched, cheap = [], []
        print(f"  (autobal's runs here with h_init = {args.h_init:g} s)")
        for tol in mtols:
            c = member(args, "exact", tol, args.c_repeats, h_init=args.h_init)
            tc = c["cpu_seconds_min"]
            e, _ = ru.err_of(np.array(c["y"]), ref, scale)
            sw = "%d/%d/%d" % (c["sticks"], c["slips"], c["reversals"])
            line = f"{tol:>12.0e}{c['rhs_evals']:>8d}{sw:>10}{e:>13.2e}{tc * 1e3:>14.3f}"
            if len(pts) >= 2 and le[0] <= math.log(e) <= le[-1]:
                tsp = math.exp(float(np.interp(math.log(e), le, lt)))
                matched.append(tsp / tc)
                line += f"{tsp * 1e3:>13.1f}{tsp / tc:>7.0f}x"
            else:
                line += f"{'-':>13}{'-':>8}"
            ok = [t for (ee, t) in allp if ee <= max(e, floor)]
            if ok:
                cheap.append(min(ok) / tc)
                line += f"{min(ok) * 1e3:>15.1f}{min(ok) / tc:>7.0f}x"
            else:
                line += "   no SciPy run of the grid is this accurate"
            print(line)
        for name, v in (("interpolated", matched), ("cheapest at least as accurate", cheap)):
            if v:
                m = min(v)
                print(f"smallest time ratio SciPy / autobal at matched error ({name}): {m:.0f}x "
                      f"(target >= 30x: {'met' if m >= 30 else 'NOT met'})")
        print()

    if args.only in (None, "before") and args.before:
        print(f"== (c) friction off: the library now vs before friction was merged ({args.before}); "
              f"both binaries alternately, 3 rounds, best of each; {load()} ==")
        print(f"{'bench':<34}{'tol':>8}{'evals now/before':>18}{'now / before':>14}{'same final state':>18}")
        cases = [("constant speed 500 rad/s, 0.5 s", ("run", 2, "rk8pd", "{t}", "{t}", "0.5", 101)),
                 ("run-up 0 -> 500 rad/s, 20 s", ("runup", "rk8pd", "{t}", "{t}", "20", 5, "500", "20"))]
        for name, a in cases:
            for tol in (1e-6, 1e-8, 1e-10):
                aa = [tol if v == "{t}" else v for v in a]
                tb = tn = math.inf
                for _ in range(3):
                    b = rs.bench(args.before, *aa)
                    c = rs.bench(args.bench_rotor, *aa)
                    tb, tn = min(tb, b["cpu_seconds_min"]), min(tn, c["cpu_seconds_min"])
                same = "bit for bit" if b["y"] == c["y"] else \
                    "differ %.1e" % max(abs(u - v) for u, v in zip(b["y"], c["y"]))
                print(f"{name:<34}{tol:>8.0e}{'%d/%d' % (c['rhs_evals'], b['rhs_evals']):>18}"
                      f"{tn / tb:>13.3f}x{same:>18}")
        print()


if __name__ == "__main__":
    main()
