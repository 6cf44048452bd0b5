#!/usr/bin/env python3
"""Slow ramps against the stability windows (tests/app/ramp_onset.sh; docs/device.md, "Slow ramps and the
stability windows").

usage: ramp_onset_check.py STAB.h5 [STAB.h5 ...] ENS.h5 [ENS.h5 ...]
  STAB.h5  `autobal rotor stability` of the rotor: the stable speed windows of the balanced motion
           (/rotor/stability/critical stable_lo, stable_hi) and the balanced configuration psi_balanced;
           several: the configurations of (3.14) the analysis was given (e.g. a configuration and its
           mirror image), whose windows must agree
  ENS.h5   `autobal rotor ensemble` of the same rotor over initial ball angles, one ramp each
           ([drive] mode = ramp from omega_a to omega_b), every member's series kept

The expectation comes from the stability analysis alone:
  * the ramp crosses exactly one window edge Omega_c (stable above it);
  * no member balances below Omega_c: every stretch in which the monitor |s|/s_ref stays below
    balance_tol for the dwell (balance_revs revolutions at the largest speed) starts at a speed in a
    stable window;
  * every member balances during its ramp: the onset, the speed at the first sample after the last
    one with |s|/s_ref >= balance_tol, lies in (Omega_c, omega_b) with the dwell after it still in
    the ramp, and the final ball angles are the balanced configuration of the analysis;
  * the slower the ramp, the closer the onset to Omega_c: the median gap (onset - Omega_c) over the
    initial angles decreases as the rate decreases; with three rates or more the fitted order p of
    gap ~ rate^p lies in [0.2, 1] (slow passage through a stability boundary where Re(lambda) is
    linear in Omega - Omega_c: p = 1/2).
Prints the table rate -> onset -> gap.
"""
import math
import sys

import h5py
import numpy as np


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def ok(msg):
    print("ok:", msg)


def in_window(w, lo, hi):
    return any(a <= w <= b for a, b in zip(lo, hi))


def main(args):
    stabs = [a for a in args if "rotor/stability" in h5py.File(a, "r")]
    paths = [a for a in args if a not in stabs]
    if not stabs or not paths:
        fail("need stability and ensemble archives")
    lo = hi = None
    configs = []
    for a in stabs:
        s = h5py.File(a, "r")["rotor/stability"]
        l2, h2 = s["critical/stable_lo"][()], s["critical/stable_hi"][()]
        if lo is None:
            lo, hi = l2, h2
        elif l2.shape != lo.shape or np.max(np.abs(l2 - lo)) > 1e-9 * np.max(hi) or np.max(np.abs(h2 - hi)) > 1e-9 * np.max(hi):
            fail(f"{a}: stable windows {list(zip(l2, h2))} differ from {list(zip(lo, hi))}")
        configs.append(s["psi_balanced"][()])
    rows = []
    oc = None
    for p in paths:
        g = h5py.File(p, "r")["rotor/ensemble"]
        if g.attrs["drive_mode"] != "ramp":
            fail(f"{p}: not a ramp drive")
        wa, wb, ta, tb = (float(g.attrs[k]) for k in ("drive_omega_a", "drive_omega_b", "drive_t_a", "drive_t_b"))
        rate = (wb - wa) / (tb - ta)
        edges = [e for e in lo if wa < e < wb]
        if len(edges) != 1 or any(wa < e < wb for e in hi):
            fail(f"{p}: the ramp {wa}..{wb} rad/s must cross exactly one lower window edge (windows {lo}..{hi})")
        if oc is None:
            oc = float(edges[0])
        tol = float(g.attrs["balance_tol"])
        dwell = float(g.attrs["balance_revs"]) * 2 * math.pi / max(abs(wa), abs(wb))
        ons = []
        for name in sorted(g["series"], key=lambda n: int(n.split("_")[1])):
            sg = g["series"][name]
            t, w, sr = sg["time"][()], sg["Omega"][()], sg["p1_s_rel"][()]
            m = int(sg.attrs["member"])
            # stretches below balance_tol lasting the dwell: they start in a stable window
            below = sr < tol
            i = 0
            while i < len(t):
                if below[i]:
                    j = i
                    while j + 1 < len(t) and below[j + 1]:
                        j += 1
                    if t[j] - t[i] >= dwell and not in_window(w[i], lo, hi):
                        fail(f"{p} member {m}: |s|/s_ref < {tol} for {t[j] - t[i]:.3g} s from Omega = {w[i]:.4f} rad/s, "
                             f"outside the stable windows")
                    i = j + 1
                else:
                    i += 1
            ramp = t <= tb
            above = np.nonzero(sr[ramp] >= tol)[0]
            if len(above) == 0 or above[-1] + 1 >= ramp.sum():
                fail(f"{p} member {m}: not balanced during the ramp (|s|/s_ref = {sr[ramp][-1]:.3g} at its end)")
            k = above[-1] + 1
            if not (t[k] + dwell <= tb):
                fail(f"{p} member {m}: onset at t = {t[k]:.4g} s leaves less than the dwell before t_b = {tb:.4g} s")
            onset = float(w[k])
            if not onset > oc:
                fail(f"{p} member {m}: onset {onset:.4f} rad/s at or below the stability boundary {oc:.4f} rad/s")
            ons.append(onset)
        fa = g["final_angle"][()]
        err = np.min([np.max(np.abs(np.remainder(fa - c + math.pi, 2 * math.pi) - math.pi), axis=-1) for c in configs],
                     axis=0)
        if np.max(err) > 0.02:
            fail(f"{p}: final ball angles {fa.tolist()} differ from the balanced configurations {configs} by "
                 f"{np.max(err):.3g} rad")
        if int(g.attrs["n_balanced"]) != len(ons):
            fail(f"{p}: n_balanced = {g.attrs['n_balanced']}, members {len(ons)}")
        rows.append((rate, ons))
    rows.sort(key=lambda r: -r[0])
    print(f"stability boundary Omega_c = {oc:.6f} rad/s (stable windows {list(zip(lo, hi))})")
    print(f"{'rate rad/s^2':>14} {'onset median':>13} {'min':>9} {'max':>9} {'gap median':>11} {'gap/sqrt(rate)':>15}")
    gaps = []
    for rate, ons in rows:
        med = float(np.median(ons))
        gap = med - oc
        gaps.append(gap)
        print(f"{rate:14.8g} {med:13.4f} {min(ons):9.4f} {max(ons):9.4f} {gap:11.4f} {gap / math.sqrt(rate):15.4f}")
    ok(f"{sum(len(o) for _, o in rows)} members: every onset above Omega_c = {oc:.4f} rad/s, no balancing outside the "
       "stable windows, final angles = the balanced configuration of the analysis (0.02 rad)")
    for a, b, (ra, _), (rb, _) in zip(gaps, gaps[1:], rows, rows[1:]):
        if not b < a:
            fail(f"the median gap does not shrink from rate {ra:g} ({a:.4f}) to rate {rb:g} ({b:.4f})")
    if len(rows) >= 2:
        lr = np.log([r for r, _ in rows])
        lg = np.log(gaps)
        pfit = float(np.polyfit(lr, lg, 1)[0])
        print(f"observed order: gap ~ rate^p with p = {pfit:.3f} (least squares over {len(rows)} rates)")
        if len(rows) >= 3 and not 0.2 <= pfit <= 1.0:
            fail(f"order p = {pfit:.3f} outside [0.2, 1]")
        ok(f"the median gap shrinks as the ramp slows: {gaps[0]:.4f} -> {gaps[-1]:.4f} rad/s")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        fail(__doc__)
    main(sys.argv[1:])
