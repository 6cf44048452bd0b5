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

    def accel(t, y, modes, Q=None):
        """(dydt, uD, vD, W, Wd); Q: generalized forces (N m) on the slipping balls' angles."""
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
                if Q is not None:
                    K += Q[i] / (mr * ri)
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


V_REST = 1e-3  # rad/s, device.md section 4: slower impacts (e |u| < v_rest) would join the pair


def make_contact(drive, d, e, y0):
    """Ball contact (docs/device.md section 4, "Impact"; "Stiction and contact"), two balls of
    diameter d on the one track: the gap angle gamma = 2 asin(2 d / (4 r)); the pairs (behind,
    ahead) = (0, 1) and (1, 0), their gaps continuous from the unwrapped angles (the multiple of 2 pi
    fixed by the start y0); the impact law with M^-1 J^T as the response of the frictionless
    accelerations to the unit generalized force pair (+1 on the ball ahead, -1 behind), both balls
    free (both are in the pair).  Resting contact is not implemented: a plastic impact raises."""
    r = rs.balls(2)[1][0]
    gam = 2.0 * math.asin(2.0 * d / (4.0 * r))
    d0 = y0[9] - y0[8]
    k0 = math.floor(d0 / (2.0 * math.pi))  # y0's phi_1 - phi_0 - 2 pi k0 in [0, 2 pi)
    accel0 = make_model(drive, 0.0, 0.0)[0]  # friction off
    pairs = ((0, 1), (1, 0))
    vel = (4, 5, 6, 7, 10, 11)

    def gap(p, y):
        dd = y[9] - y[8] - 2.0 * math.pi * k0
        return dd - gam if p == 0 else 2.0 * math.pi - dd - gam

    def response(t, y, p):
        """W = M^-1 J^T (the velocity components of vel)."""
        b, a = pairs[p]
        Q = [0.0, 0.0]
        Q[a], Q[b] = 1.0, -1.0
        a0 = accel0(t, y, (1, 1))[0]
        a1 = accel0(t, y, (1, 1), Q)[0]
        return [a1[i] - a0[i] for i in vel]

    def impact(t, y, p, e_p):
        """Apply the law to pair p in place; returns (G, Lambda, u)."""
        b, a = pairs[p]
        W = response(t, y, p)
        G = W[4 + a] - W[4 + b]
        u = y[10 + a] - y[10 + b]
        lam = -(1.0 + e_p) * u / G
        for j, i in enumerate(vel):
            y[i] += W[j] * lam
        return G, lam, u

    def events():
        evs = []
        for p in range(2):
            def ev(t, y, p=p):
                return gap(p, y) + 1e-12
            ev.direction = -1.0
            ev.terminal = True
            evs.append(ev)
        return evs

    return dict(gamma=gam, gap=gap, impact=impact, events=events, pairs=pairs, e=e)


def hybrid_reset(drive, model, contact, t, y, modes, fired):
    """The event reset with contact (device.md "Stiction and contact", "The reset"): impacts of
    touching closing pairs (their balls free during the impulse, then slipping the way they move;
    gap set to 0 by moving the ball ahead), then the friction rules, in turn until no impact.  fired: the event index (0, 1 balls; 2, 3 pairs).  Returns the counts (sticks, slips,
    reversals, impacts)."""
    settle = model[3]
    cnt = [0, 0, 0, 0]
    W = drive(t)[0]
    for rnd in range(16):
        impacted = False
        for p in range(2):
            b, a = contact["pairs"][p]
            g = contact["gap"](p, y)
            u = y[10 + a] - y[10 + b]
            if not (g <= 1e-9 and u < -1e-12):
                continue
            if contact["e"] * -u < V_REST:
                raise RuntimeError(f"plastic impact at t = {t}: resting contact is not in the SciPy version")
            y[8 + a] -= g  # the ball ahead moved: the gap exactly 0
            for i in (a, b):
                if modes[i] == 0:
                    y[10 + i] = W
            before = [modes[a], modes[b]]
            contact["impact"](t, y, p, contact["e"])
            cnt[3] += 1
            for i, m0 in zip((a, b), before):
                rel = y[10 + i] - W
                modes[i] = 0 if rel == 0.0 else (1 if rel > 0 else -1)
                if m0 == 0 and modes[i] != 0:
                    cnt[1] += 1
                elif m0 != 0 and modes[i] == 0:
                    cnt[0] += 1
                elif m0 != 0 and modes[i] != m0:
                    cnt[2] += 1
            impacted = True
        if rnd > 0 and not impacted:
            break
        # the friction rules once after each round of impacts (the settle's "reached psi' = 0" is
        # judged at its entry: a ball it has just set slipping from rest is not stuck again)
        a_, b_, c_ = settle(t, y, modes, False, fired if (rnd == 0 and fired < 2) else -1)
        cnt[0] += a_
        cnt[1] += b_
        cnt[2] += c_
    else:
        raise RuntimeError(f"the reset did not settle at t = {t}")
    return cnt


def hybrid_run(drive, model, y0, t1, rtol, atol, keep=False, contact=None):
    """The restart loop; returns (y(t1), nfev, switches, modes, trajectory points or None);
    with contact the switches have a 4th count, impacts."""
    _, _, make_rhs, settle, events = model
    y = list(y0)
    modes = [1, 1]
    settle(0.0, y, modes, True)
    t = 0.0
    nfev = 0
    sw = [0, 0, 0] if contact is None else [0, 0, 0, 0]
    traj = [] if keep else None
    cev = contact["events"]() if contact is not None else []
    while True:
        sol = solve_ivp(make_rhs(modes), (t, t1), np.array(y), method="DOP853", rtol=rtol,
                        atol=atol, events=events(modes) + cev)
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
        if contact is not None:
            for j, n in enumerate(hybrid_reset(drive, model, contact, t, y, modes, k)):
                sw[j] += n
            continue
        a, b, c = settle(t, y, modes, False, k)
        sw[0] += a
        sw[1] += b
        sw[2] += c


def timed_hybrid(drive, model, y0, t1, tol, repeats, contact=None):
    best = math.inf
    for _ in range(repeats):
        c0 = time.process_time()
        out = hybrid_run(drive, model, y0, t1, tol, tol, contact=contact)
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
    ap.add_argument("--contact", action="store_true",
                    help="stiction AND ball contact (bench/run.sh contact): the section below main()")
    ap.add_argument("--diameter", type=float, default=0.02, help="ball diameter [m] with --contact")
    ap.add_argument("--restitutions", default="0.5,1",
                    help="restitutions of the contact members and ensembles (--contact)")
    ap.add_argument("--scipy-restitution", type=float, default=1.0,
                    help="restitution of the SciPy member (--contact; it must have no joins)")
    ap.add_argument("--scipy-seed", type=int, default=14,
                    help="the ensemble member (seed) compared with SciPy (--contact; 0: psi = 1.0, 2.5)")
    ap.add_argument("--scipy-t1", type=float, default=8.0,
                    help="end time [s] of the SciPy comparison (--contact; see docs/guide.md: the elastic "
                         "impacts make 20 s ill-conditioned)")
    args = ap.parse_args()
    if args.contact:
        return main_contact(args)
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
        mtols, grid = tolerances(args)
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
            print(line + matched_columns(e, tc, pts, le, lt, allp, floor, matched, cheap))
        print_matched(matched, cheap)

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


# ---- stiction and contact (issue 16, bench/run.sh contact) ------------------------------------

def cb(args, e, *a):
    """bench_friction with contact (--contact D E) before the mode; e None: no contact, the random
    angles still respecting the gap angle (--psi-gap D), so that both ensembles start alike."""
    if e is None:
        return rs.bench(args.bench_friction, "--psi-gap", args.diameter, *a)
    return rs.bench(args.bench_friction, "--contact", args.diameter, e, *a)


def cmember(args, law, e, tol, repeats, seed=0, event_tol=0.0, h_init=0.0, t1=None):
    f, mu = (F, MU) if law == "exact" else (0, 0)
    return cb(args, e, "run", law, f, mu, tol, tol, args.t1 if t1 is None else t1, repeats, args.omega_a, args.omega_b,
              args.t_b, seed, event_tol, h_init)


def check_contact(args, model, drive, e):
    """The rhs check of check() with the contact rotor, and the event reset at 6 touching, closing
    states (every mode pattern of the two balls, both pairs) against autobal_rotor_hybrid_settle."""
    accel, forces = model[0], model[1]
    data = cb(args, e, "check", F, MU, args.omega_a, args.omega_b, args.t_b)
    wd = 0.0
    for st in data["states"]:
        mine = np.array(accel(st["t"], st["y"], st["modes"])[0])
        theirs = np.array(st["dydt"])
        sc = rs.group_scales(2, theirs[:, None])
        wd = max(wd, float(np.max(np.abs(mine - theirs) / sc)))
    wj = wp = 0.0
    modes_ok = counts_ok = True
    lines = []
    for st in data["impacts"]:
        y = list(st["y"])
        modes = list(st["modes"])
        contact = make_contact(drive, args.diameter, e, y)
        if abs(contact["gamma"] - data["gap_angle"]) > 1e-15:
            raise RuntimeError("gap angle differs")
        cnt = hybrid_reset(drive, model, contact, st["t"], y, modes, 2)
        y0, ya, yl = np.array(st["y"]), np.array(y), np.array(st["y_after"])
        for g in (slice(4, 6), slice(6, 8), slice(10, 12)):  # the velocity jumps, per group
            dl = yl[g] - y0[g]
            wj = max(wj, float(np.max(np.abs((ya[g] - y0[g]) - dl)) / max(np.max(np.abs(dl)), 1e-300)))
        wp = max(wp, float(np.max(np.abs(ya[:4] - yl[:4]))), float(np.max(np.abs(ya[8:10] - yl[8:10]))))
        modes_ok &= modes == st["modes_after"]
        counts_ok &= cnt[3] == st["counts"][3]
        lines.append(f"    modes {st['modes']} -> library {st['modes_after']}, SciPy {modes}; "
                     f"u = {y0[10 + st['ahead']] - y0[11 - st['ahead']]:+.0f} rad/s -> "
                     f"{yl[10 + st['ahead']] - yl[11 - st['ahead']]:+.4f} (library), "
                     f"{ya[10 + st['ahead']] - ya[11 - st['ahead']]:+.4f} (SciPy); counts library "
                     f"{st['counts']}, SciPy stick/slip/rev/impacts {cnt}")
    return wd, wj, wp, modes_ok, counts_ok, lines, len(data["states"]), len(data["impacts"])


def main_contact(args):
    rests = [float(v) for v in args.restitutions.split(",")]
    if args.quick:
        args.t1 = 2.0
        args.tols, args.matched_tols, args.grid = "1e-9", "1e-7,1e-9", "1e-6,1e-10"
        args.members, args.c_repeats, args.scipy_repeats = 8, 1, 1
    drive = ru.ramp(args.omega_a, args.omega_b, 0.0, args.t_b)
    model = make_model(drive)
    r = rs.balls(2)[1][0]
    gam = 2.0 * math.asin(2.0 * args.diameter / (4.0 * r))
    print("rotor with stiction AND ball contact (default example, 2 balls, f = %g, mu = %g, EXACT law; "
          "ball diameter %g mm, gap angle %.5f rad, restitution %s, v_rest 1e-3 rad/s), run-up Omega = "
          "%g -> %g rad/s over [0, %g] s, t in [0, %g] s; fixed frame"
          % (F, MU, args.diameter * 1e3, gam, "/".join("%g" % e for e in rests), args.omega_a,
             args.omega_b, args.t_b, args.t1))
    print(f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}; "
          f"{os.cpu_count()} cpus; {load()}")
    print()

    if args.only in (None, "member"):
        print(f"== (a) per member (psi = 1.0, 2.5): frictionless (none), stiction alone (exact), "
              f"stiction and contact (e = ...), same tolerances; best of {args.c_repeats} CPU times; "
              f"{load()} ==")
        hdr = (f"{'tol':>8}{'case':>14}{'cpu [ms]':>10}{'steps':>8}{'rhs evals':>11}{'events':>8}"
               f"{'resets':>8}{'stick/slip/rev':>16}{'imp/join/rel':>14}{'/ none':>9}")
        print(hdr)
        print("-" * len(hdr))
        for tol in [float(v) for v in args.tols.split(",")]:
            rows = [("none", cmember(args, "none", None, tol, args.c_repeats)),
                    ("exact", cmember(args, "exact", None, tol, args.c_repeats))]
            for e in rests:
                rows.append((f"exact, e={e:g}", cmember(args, "exact", e, tol, args.c_repeats)))
            t0 = rows[0][1]["cpu_seconds_min"]
            for name, c in rows:
                print(f"{tol:>8.0e}{name:>14}{c['cpu_seconds_min'] * 1e3:>10.2f}{c['steps']:>8d}"
                      f"{c['rhs_evals']:>11d}{c['events']:>8d}{c['resets']:>8d}"
                      f"{'%d/%d/%d' % (c['sticks'], c['slips'], c['reversals']):>16}"
                      f"{'%d/%d/%d' % (c['impacts'], c['joins'], c['releases']):>14}"
                      f"{c['cpu_seconds_min'] / t0:>8.2f}x")
        print()
        print(f"ensemble: {args.members} members (psi uniform in [-pi, pi), the second angle redrawn until "
              f"the balls are at least the gap angle + 1e-3 rad apart, the same angles in every "
              f"ensemble; seeds 1..{args.members}) on {args.threads} threads, rtol = atol = "
              f"{args.ens_tol:g}; {load()}")
        cases = [("none", None)] + [("exact", e) for e in rests]
        ens = {}
        for _ in range(2):  # alternate, keep the best of two
            for law, e in cases:
                f, mu = (F, MU) if law == "exact" else (0, 0)
                x = cb(args, e, "ensemble", law, f, mu, args.ens_tol, args.ens_tol, args.t1,
                       args.members, args.threads, args.omega_a, args.omega_b, args.t_b)
                print(f"  run: {law} e={e}: wall {x['wall_seconds']:.2f} s, cpu {x['cpu_seconds']:.2f} s; "
                      f"{load()}")
                if (law, e) not in ens or x["wall_seconds"] < ens[(law, e)]["wall_seconds"]:
                    ens[(law, e)] = x
        hdr = (f"{'case':>14}{'wall [s]':>10}{'cpu [s]':>9}{'members/s':>11}{'members/cpu-s':>15}"
               f"{'stick/slip/rev':>18}{'impacts':>9}{'joins':>7}{'rel':>7}{'with imp':>10}"
               f"{'imp min-max':>13}{'with joins':>12}{'failed':>8}")
        print(hdr)
        print("-" * len(hdr))
        for law, e in cases:
            x = ens[(law, e)]
            name = "none" if e is None else f"exact, e={e:g}"
            print(f"{name:>14}{x['wall_seconds']:>10.2f}{x['cpu_seconds']:>9.2f}"
                  f"{x['members_per_second']:>11.2f}{x['members_per_cpu_second']:>15.2f}"
                  f"{'%d/%d/%d' % (x['sticks'], x['slips'], x['reversals']):>18}{x['impacts']:>9d}"
                  f"{x['joins']:>7d}{x['releases']:>7d}{x['members_with_impacts']:>10d}"
                  f"{'%d-%d' % (x['min_impacts'], x['max_impacts']):>13}{x['members_with_joins']:>12d}"
                  f"{x['failed']:>8d}")
            if x["failed"]:
                print(f"    failed: {x['message']}")
        for e in rests:
            x, n = ens[("exact", e)], ens[("none", None)]
            rw = n["members_per_second"] / x["members_per_second"]
            rc = n["members_per_cpu_second"] / x["members_per_cpu_second"]
            print(f"frictionless / (stiction and contact, e = {e:g}) members per second: {rw:.2f}x (wall), "
                  f"{rc:.2f}x (CPU) (target: no more than 3x slower: "
                  f"{'met' if max(rw, rc) <= 3 else 'NOT met'})")
        print()

    if args.only in (None, "scipy"):
        e = args.scipy_restitution
        T1 = min(args.scipy_t1, args.t1)
        wd, wj, wp, mok, cok, lines, ns, ni = check_contact(args, model, drive, e)
        print(f"== (b) SciPy solve_ivp DOP853 with terminal events (friction and gaps) and a restart loop, "
              f"e = {e:g}, t in [0, {T1:g}] s; {load()} ==")
        print(f"SciPy rhs vs library rhs (contact rotor) at {ns} states: max difference {wd:.1e} (group-relative)")
        print(f"event reset at {ni} touching, closing states (both pairs; slip/slip, stuck/slip, slip/stuck): "
              f"velocity jumps differ by {wj:.1e} (relative to each group's largest jump), positions by "
              f"{wp:.1e} rad/m; modes after {'the same' if mok else 'DIFFER'}; impact counts "
              f"{'the same' if cok else 'DIFFER'}")
        for ln in lines:
            print(ln)
        if wd > 1e-12 or wj > 1e-10 or wp > 1e-12 or not mok or not cok:
            raise RuntimeError("the SciPy contact reset or rhs differs from the library's")
        lib = cmember(args, "exact", e, 1e-10, 1, seed=args.scipy_seed, t1=T1)
        print(f"the library's member (seed {args.scipy_seed}: psi = {lib['y0'][8]:.6f}, {lib['y0'][9]:.6f} rad), t in [0, {T1:g}] s, at 1e-10: impacts/joins/releases "
              f"{lib['impacts']}/{lib['joins']}/{lib['releases']}, sticks/slips/reversals "
              f"{lib['sticks']}/{lib['slips']}/{lib['reversals']}")
        if lib["joins"] != 0:
            raise RuntimeError("the member joins pairs (resting contact): not in the SciPy version")
        y0 = np.array(lib["y0"])
        contact = make_contact(drive, args.diameter, e, list(y0))
        c0 = time.process_time()
        ref, ref_nfev, ref_sw, ref_modes, traj = hybrid_run(drive, model, y0, T1, 1e-13, 1e-13,
                                                            keep=True, contact=contact)
        tref = time.process_time() - c0
        scale = rs.group_scales(2, np.concatenate(traj, axis=1))
        print(f"reference: SciPy DOP853 1e-13 ({ref_nfev} evals, {tref:.1f} s; sticks/slips/"
              f"reversals/impacts {'/'.join(map(str, ref_sw))}, final modes {ref_modes})")
        # the branch: which switch and impact sequence a run follows (see README: a ball left at rest
        # relative to the rotor by an impact on a stuck ball); runs are compared within SciPy's branch
        branch = ref_sw[3]
        floor, same = 0.0, 0
        for tol in (1e-11, 1e-12, 1e-13):
            c = cmember(args, "exact", e, tol, 1, seed=args.scipy_seed, event_tol=1e-14, t1=T1)
            er, eb = ru.err_of(np.array(c["y"]), ref, scale)
            ok = c["impacts"] == branch
            print(f"  autobal rk8pd {tol:.0e}, event_tol 1e-14 s ({c['rhs_evals']} evals, "
                  f"sticks/slips/reversals {c['sticks']}/{c['slips']}/{c['reversals']}, impacts/joins "
                  f"{c['impacts']}/{c['joins']}, final modes {c['modes']}): differs from it by "
                  f"{er:.1e} / {eb:.1e} rad" + ("" if ok else "  (other branch: not in the floor)"))
            if ok:
                floor = max(floor, er)
                same += 1
        if same == 0:
            print("  no tight autobal run follows SciPy's branch: the floor is unknown (0 used)")
        print(f"error floor (the references agree to): {floor:.1e}")
        print()
        mtols, grid = tolerances(args)
        print(f"SciPy DOP853 hybrid on {len(grid)} tolerances (best of {args.scipy_repeats} CPU times):")
        print(f"{'tol':>10}{'rhs evals':>11}{'st/sl/rev/imp':>16}{'max rel err':>12}{'time [ms]':>12}")
        pts, allp = [], []
        for tol in grid:
            try:
                ts_, yend, nfev, sw, _ = timed_hybrid(drive, model, y0, T1, tol,
                                                      args.scipy_repeats, contact=contact)
            except RuntimeError as ex:
                print(f"{tol:>10.1e}   failed: {ex}")
                continue
            er, _ = ru.err_of(yend, ref, scale)
            if sw[3] != branch:
                print(f"{tol:>10.1e}{nfev:>11d}{'/'.join(map(str, sw)):>16}{er:>12.2e}{ts_ * 1e3:>12.1f}"
                      "   (other branch: not used)", flush=True)
                continue
            allp.append((er, ts_))
            used = er > 10.0 * floor
            if used:
                pts.append((er, ts_, nfev))
            print(f"{tol:>10.1e}{nfev:>11d}{'/'.join(map(str, sw)):>16}{er:>12.2e}{ts_ * 1e3:>12.1f}"
                  + ("" if used else "   (below 10x the floor: not interpolated)"), flush=True)
        pts.sort()
        le = np.log([p[0] for p in pts]) if pts else np.array([])
        lt = np.log([p[1] for p in pts]) if pts else np.array([])
        print()
        print(f"matched error; {load()}:")
        print(f"{'autobal tol':>12}{'evals':>8}{'st/sl/rev/imp':>15}{'autobal err':>13}{'autobal [ms]':>14}"
              f"{'interp [ms]':>13}{'ratio':>8}{'cheapest [ms]':>15}{'ratio':>8}")
        print(f"  (autobal's runs here with h_init = {args.h_init:g} s)")
        matched, cheap = [], []
        for tol in mtols:
            c = cmember(args, "exact", e, tol, args.c_repeats, seed=args.scipy_seed, h_init=args.h_init,
                        t1=T1)
            tc = c["cpu_seconds_min"]
            er, _ = ru.err_of(np.array(c["y"]), ref, scale)
            sw = "%d/%d/%d/%d" % (c["sticks"], c["slips"], c["reversals"], c["impacts"])
            line = f"{tol:>12.0e}{c['rhs_evals']:>8d}{sw:>15}{er:>13.2e}{tc * 1e3:>14.3f}"
            if c["joins"]:
                line += f"  ({c['joins']} joins)"
            if c["impacts"] != branch:
                print(line + "   other branch: not compared")
                continue
            print(line + matched_columns(er, tc, pts, le, lt, allp, floor, matched, cheap))
        print_matched(matched, cheap)


def tolerances(args):
    """autobal's tolerances for the matched-error runs and SciPy's grid (half decades between the
    two ends of --grid)."""
    mtols = [float(v) for v in args.matched_tols.split(",")]
    g0, g1 = (round(-2 * math.log10(float(v))) for v in args.grid.split(","))
    return mtols, [10.0 ** (-k / 2.0) for k in range(g0, g1 + 1)]


def matched_columns(err, tc, pts, le, lt, allp, floor, matched, cheap):
    """The matched-error columns of one autobal run (error err, CPU time tc) against the SciPy runs:
    SciPy's time interpolated (log-log) at err, and the cheapest SciPy run at least as accurate;
    the ratios appended to matched and cheap."""
    col = ""
    if len(pts) >= 2 and le[0] <= math.log(err) <= le[-1]:
        tsp = math.exp(float(np.interp(math.log(err), le, lt)))
        matched.append(tsp / tc)
        col += f"{tsp * 1e3:>13.1f}{tsp / tc:>7.0f}x"
    else:
        col += f"{'-':>13}{'-':>8}"
    ok = [t for (ee, t) in allp if ee <= max(err, floor)]
    if ok:
        cheap.append(min(ok) / tc)
        col += f"{min(ok) * 1e3:>15.1f}{min(ok) / tc:>7.0f}x"
    else:
        col += "   no SciPy run of the grid is this accurate"
    return col


def print_matched(matched, cheap):
    for name, v in (("interpolated", matched), ("cheapest at least as accurate", cheap)):
        if v:
            m = min(v)
            print(f"smallest time ratio SciPy / autobal at matched error ({name}): {m:.0f}x "
                  f"(target >= 30x: {'met' if m >= 30 else 'NOT met'})")
    print()


if __name__ == "__main__":
    main()
