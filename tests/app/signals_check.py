#!/usr/bin/env python3
"""Checks of tests/app/signals.sh: an archive left by an interrupted command is readable, marked
incomplete with the signal named, and holds partial data that are consistent (lengths = the
recorded count of what was done, the grid = the requested grid's first points, values in their
ranges).  Usage: signals_check.py KIND FILE SIGNAL [ARGS...]; exit 0 when every check holds.
signals_check.py --batch LIST: every line of LIST is WHAT KIND FILE SIGNAL [ARGS...] (shell-quoted),
each checked as above in this one process and reported as "ok   WHAT" or "FAIL WHAT"; exit 1 when
one fails."""
import math
import shlex
import sys

import h5py
import numpy as np


def fail(msg):
    print("  check failed:", msg)
    sys.exit(1)


def linspace(lo, hi, n):
    """The grid of the studies (src/studies: lo + (hi - lo) i/(n - 1), the last point hi)."""
    v = lo + (hi - lo) * np.arange(n, dtype=float) / (n - 1)
    v[-1] = hi
    return v


def common(f, sig, command):
    st, why = f.attrs.get("status"), f.attrs.get("status_reason")
    if st != "incomplete":
        fail(f"status = {st!r}, want 'incomplete'")
    if why != f"interrupted by {sig}":
        fail(f"status_reason = {why!r}, want 'interrupted by {sig}'")
    if f.attrs.get("command") != command:
        fail(f"command = {f.attrs.get('command')!r}, want {command!r}")


def partial(g, requested=None):
    a = g.attrs
    if a.get("partial") != 1:
        fail(f"{g.name}: partial = {a.get('partial')!r}, want 1")
    if not str(a.get("partial_what", "")).startswith("interrupted"):
        fail(f"{g.name}: partial_what = {a.get('partial_what')!r}")
    if requested is None:
        return None
    done, req = int(a["done"]), int(a["requested"])
    if req != requested:
        fail(f"{g.name}: requested = {req}, want {requested}")
    if not 0 <= done <= req:
        fail(f"{g.name}: done = {done} not in [0, {req}]")
    return done


def verdict_margin(v, m=None, allowed=(-2, -1, 0, 1)):
    if not np.all(np.isin(v, allowed)):
        fail(f"verdict values {np.unique(v)} not all in {allowed}")
    if m is not None:
        if m.shape != v.shape:
            fail(f"margin shape {m.shape} != verdict shape {v.shape}")
        if not np.array_equal(np.isnan(m), v == -2):
            fail("margin is NaN exactly where the verdict is -2 (no balanced configuration): not so")


def main(argv):
    kind, path, sig = argv[0], argv[1], argv[2]
    args = argv[3:]
    f = h5py.File(path, "r")
    if kind == "stability":  # args: reference archive (the same analysis, critical_speeds = false)
        common(f, sig, "rotor stability")
        g = f["rotor/stability"]
        partial(g)
        if "critical" in g:
            fail("a /rotor/stability/critical group after an interrupted search")
        ref = h5py.File(args[0], "r")["rotor/stability"]
        for k in ("margin", "verdict", "method"):
            if g.attrs[k] != ref.attrs[k]:
                fail(f"{k} = {g.attrs[k]!r}, the complete analysis at omega gives {ref.attrs[k]!r}")
        if not np.array_equal(g["psi_balanced"][:], ref["psi_balanced"][:]):
            fail("psi_balanced differs from the complete analysis")
        print(f"  stability: verdict {g.attrs['verdict']}, margin {g.attrs['margin']:.6g} 1/s as the complete analysis")
    elif kind == "sweep":  # args: lo hi n [k margin_k]: the grid and an independent margin at point k
        common(f, sig, "rotor sweep")
        lo, hi, n = float(args[0]), float(args[1]), int(args[2])
        g = f["rotor/sweep"]
        done = partial(g, n)
        if not 0 < done < n:
            fail(f"done = {done}: want a partial sweep")
        om, mg, vd = g["omega"][:], g["margin"][:], g["verdict"][:]
        if om.shape != (done,) or vd.shape != (done,):
            fail(f"lengths {om.shape}, {vd.shape}, want ({done},)")
        if not np.allclose(om, linspace(lo, hi, n)[:done], rtol=1e-13, atol=0):
            fail("omega is not the first points of the requested grid")
        verdict_margin(vd, mg)
        if "critical_value" in g or "n_critical" in g.attrs:
            fail("critical values after an interrupted sweep")
        if len(args) > 3:
            k, ref = int(args[3]), float(args[4])
            if not math.isclose(mg[k], ref, rel_tol=1e-9, abs_tol=1e-12):
                fail(f"margin at omega[{k}] = {om[k]!r}: {mg[k]!r}, `rotor stability` there: {ref!r}")
            print(f"  sweep: margin at omega[{k}] = {om[k]:.9g} rad/s is {mg[k]:.9g} 1/s, `rotor stability` gives {ref:.9g}")
        print(f"  sweep: {done} of {n} points")
    elif kind == "map":  # args: lo1 hi1 n1 lo2 hi2 n2
        common(f, sig, "rotor map")
        lo1, hi1, n1, lo2, hi2, n2 = float(args[0]), float(args[1]), int(args[2]), float(args[3]), float(args[4]), int(args[5])
        g = f["rotor/map"]
        done = partial(g, n1)
        if not 0 < done < n1:
            fail(f"done = {done}: want a partial map")
        v1, v2 = g["omega"][:], g["ball_damping"][:]
        if v1.shape != (done,) or v2.shape != (n2,):
            fail(f"coordinates {v1.shape}, {v2.shape}, want ({done},), ({n2},)")
        if not np.allclose(v1, linspace(lo1, hi1, n1)[:done], rtol=1e-13, atol=0) or not np.allclose(
                v2, linspace(lo2, hi2, n2), rtol=1e-13, atol=1e-300):
            fail("the coordinates are not the requested grid (its first rows)")
        vd, mg = g["verdict"][:], g["margin"][:]
        if vd.shape != (done, n2):
            fail(f"verdict shape {vd.shape}, want ({done}, {n2})")
        verdict_margin(vd, mg)
        print(f"  map: {done} of {n1} rows")
    elif kind == "campbell":  # args: lo hi n
        common(f, sig, "rotor campbell")
        lo, hi, n = float(args[0]), float(args[1]), int(args[2])
        g = f["rotor/campbell"]
        done = partial(g, n)
        if not 0 < done <= n:
            fail(f"done = {done}")
        om = g["omega"][:]
        if om.shape != (done,) or not np.allclose(om, linspace(lo, hi, n)[:done], rtol=1e-13, atol=0):
            fail("omega is not the first points of the requested grid")
        for name, shape in (("frequency", (done, 4)), ("damping_ratio", (done, 4)), ("whirl", (done, 4)), ("amp_G", (done,))):
            if g[name].shape != shape:
                fail(f"{name} shape {g[name].shape}, want {shape}")
        fr = g["frequency"][:]
        if not np.all(np.isfinite(fr)) or not np.all(np.diff(fr, axis=1) >= 0):
            fail("frequencies not finite or not sorted at every speed")
        if not np.all(np.isin(g["whirl"][:], (-1, 0, 1))):
            fail("whirl values outside {-1, 0, 1}")
        if "n_crossing" in g.attrs:
            fail("n_crossing written although the resonance search did not finish")
        print(f"  campbell: {done} of {n} speeds{' (stopped in the resonance search)' if done == n else ''}")
    elif kind == "pmap":  # args: n_Rm n_Rw [i j verdict max_real]: a point checked by `pendulum roots`
        common(f, sig, "pendulum map")
        n_rm, n_rw = int(args[0]), int(args[1])
        g = f["pendulum/map"]
        done = partial(g, n_rm)
        if not 0 < done < n_rm:
            fail(f"done = {done}: want a partial map")
        rm, rw, vd = g["R_m"][:], g["R_w"][:], g["verdict"][:]
        if rm.shape != (done,) or rw.shape != (n_rw,) or vd.shape != (done, n_rw):
            fail(f"shapes {rm.shape}, {rw.shape}, {vd.shape}")
        lo, hi = 0.005, 0.495  # the defaults of [map]
        if not np.allclose(rm, (lo + (hi - lo) * np.arange(n_rm) / (n_rm - 1))[:done], rtol=1e-13, atol=0):
            fail("R_m is not the first points of the requested grid")
        verdict_margin(vd, None, (-1, 0, 1))
        mr = g["max_real"][:] if "max_real" in g else None
        if mr is not None and (mr.shape != (done, n_rw) or not np.all(np.isfinite(mr))):
            fail("max_real: wrong shape or not finite")
        if len(args) > 2:
            i, j, ref, ref_mr = int(args[2]), int(args[3]), int(args[4]), float(args[5])
            if vd[i, j] != ref:
                fail(f"verdict at R_m = {rm[i]!r}, R_w = {rw[j]!r}: {vd[i, j]}, `pendulum roots` gives {ref}")
            if not math.isclose(mr[i, j], ref_mr, rel_tol=1e-9, abs_tol=1e-12):
                fail(f"max_real at R_m = {rm[i]!r}, R_w = {rw[j]!r}: {mr[i, j]!r}, `pendulum roots` gives {ref_mr!r}")
            print(f"  pendulum map: verdict {ref}, max_real {ref_mr:.9g} at (R_m[{i}], R_w[{j}]) as `pendulum roots`")
        print(f"  pendulum map: {done} of {n_rm} rows")
    elif kind == "psweep":  # args: lo hi n k verdict_k: a partial pendulum sweep, point k by `pendulum roots`
        common(f, sig, "pendulum sweep")
        lo, hi, n = float(args[0]), float(args[1]), int(args[2])
        g = f["pendulum/sweep"]
        done = partial(g, n)
        if not 0 < done < n:
            fail(f"done = {done}: want a partial sweep")
        rw, vd = g["R_w"][:], g["verdict"][:]
        if rw.shape != (done,) or vd.shape != (done,):
            fail(f"lengths {rw.shape}, {vd.shape}, want ({done},)")
        if not np.allclose(rw, linspace(lo, hi, n)[:done], rtol=1e-13, atol=0):
            fail("R_w is not the first points of the requested grid")
        verdict_margin(vd, None, (-1, 0, 1))
        if "critical" in g:
            fail("critical values after an interrupted sweep")
        k, ref = int(args[3]), int(args[4])
        if vd[k] != ref:
            fail(f"verdict at R_w = {rw[k]!r}: {vd[k]}, `pendulum roots` gives {ref}")
        print(f"  pendulum sweep: {done} of {n} points; verdict {ref} at R_w[{k}] as `pendulum roots`")
    elif kind == "pcrit":  # args: n_Rm damped|curves
        common(f, sig, "pendulum critical")
        n_rm, where = int(args[0]), args[1]
        g = f["pendulum/critical"]
        done = partial(g, n_rm)
        if "undamped_R_w" not in g or not np.all(np.isfinite(g["undamped_R_w"][:])):
            fail("the undamped critical speeds at R_m are missing")
        if where == "damped":
            if done != 0 or "damped_R_w" in g or "curves" in g:
                fail(f"interrupted in the damped search: done = {done}, damped_R_w or curves present")
        else:
            if not 0 < done < n_rm or "damped_R_w" not in g:
                fail(f"interrupted in the curves: done = {done}, damped_R_w present: {'damped_R_w' in g}")
            c = g["curves"]
            if c["R_m"].shape != (done,) or c["R_w_k0"].shape != (done, 3) or c["eq16_R_w1_k1"].shape != (done,):
                fail("curve lengths differ from done")
            r1 = c["R_w_k1"][:, 0]
            ok = np.isfinite(r1)
            if not np.allclose(r1[ok], c["eq16_R_w1_k1"][:][ok], rtol=1e-9):
                fail("R_w1(R_m, k=1) differs from the closed form (16) on the partial curve")
        print(f"  pendulum critical: {done} of {n_rm} curve points ({where})")
    else:
        fail("unknown kind " + kind)


def batch(listfile):
    """Every check of LIST in this process (fail() exits: caught per check)."""
    nbad = 0
    with open(listfile) as lf:
        lines = [shlex.split(line) for line in lf if line.strip()]
    for words in lines:
        what, argv = words[0], words[1:]
        try:
            main(argv)
            ok = True
        except SystemExit as e:
            ok = e.code in (None, 0)
        except Exception as e:  # an unreadable archive, a missing dataset: this check fails
            print(f"  check failed: {type(e).__name__}: {e}")
            ok = False
        print(("ok   " if ok else "FAIL ") + what, flush=True)
        nbad += not ok
    return 1 if nbad else 0


if __name__ == "__main__":
    if sys.argv[1] == "--batch":
        sys.exit(batch(sys.argv[2]))
    main(sys.argv[1:])
