#!/usr/bin/env python3
"""Independent check of the small-damping picture of the two-pendulum balancer (docs/pendulum.md,
"The undamped map is not the small-damping limit") and of the note the undamped maps carry.

Usage: pendulum_smalldamp_check.py DIR [quick|slow]   (DIR: the archives of pendulum_smalldamp.sh)

quick: NumPy on every 4th row and column of the grid (all k), pointwise against the archives, and the
note's percentages against the archives' own fractions; slow: NumPy on the whole grid, and the
note's percentages against NumPy's fractions (independent), the ratios 0.4 and 0.01 included.

The verdicts are recomputed here without the library: the 8x8 first-order matrix of the
linearization (5) is written out from the equations of docs/pendulum.md (M q'' + C q' + K q = 0,
q = (xi, eta, alpha, beta)) and its eigenvalues are taken with NumPy (LAPACK), for every point of
the grid of data/pendulum_map_every.ini (R_m 0.005..0.495 x R_w 0.5..4, 120 x 160) and every k = j/32.
Damped: stable iff every eigenvalue has Re < 0 (at k = 0 the structural eigenvalue 0 of the family
psi = -phi is left out: the one of smallest modulus).  Undamped: stable iff every eigenvalue lies on
the imaginary axis (|Re| < 1e-6; at k = 0 the two of smallest modulus, the family and its rate, are
left out).  No grid point lies on a critical speed, so rounding decides nothing here.
"""
import os
import re
import sys

import h5py
import numpy as np

FAIL = 0


def check(what, ok, detail=""):
    global FAIL
    print("%s %s%s" % ("ok  " if ok else "FAIL", what, ("  [" + detail + "]") if detail else ""))
    if not ok:
        FAIL += 1


def matrices(Rw, Rm, H, h, psi0):
    """M, C, K of (5) for arrays of points (last two axes 4x4)."""
    s, c = np.sin(psi0), np.cos(psi0)
    R = Rw
    n = np.broadcast(Rw, Rm, psi0).shape
    z, o = np.zeros(n), np.ones(n)
    Rm = Rm * o
    M = np.stack([np.stack([o, z, -Rm * c, -Rm * c], -1),
                  np.stack([z, o, -Rm * s, Rm * s], -1),
                  np.stack([-c * o, -s * o, o, z], -1),
                  np.stack([-c * o, s * o, z, o], -1)], -2)
    C = np.stack([np.stack([H * o, -2 * R * o, 2 * R * Rm * s, -2 * R * Rm * s], -1),
                  np.stack([2 * R * o, H * o, -2 * R * Rm * c, -2 * R * Rm * c], -1),
                  np.stack([-2 * R * s * o, 2 * R * c * o, h * o, z], -1),
                  np.stack([2 * R * s * o, 2 * R * c * o, z, h * o], -1)], -2)
    K = np.stack([np.stack([(1 - R * R) * o, -H * R * o, Rm * R * R * c, Rm * R * R * c], -1),
                  np.stack([H * R * o, (1 - R * R) * o, Rm * R * R * s, -Rm * R * R * s], -1),
                  np.stack([R * R * c * o, R * R * s * o, z, z], -1),
                  np.stack([R * R * c * o, -R * R * s * o, z, z], -1)], -2)
    return M, C, K


def stable_grid(rm, rw, H, h, ks):
    """every-unbalance verdict (True = stable for all k) on the grid rm x rw"""
    RM, RW = np.meshgrid(rm, rw, indexing="ij")
    out = np.ones(RM.shape, bool)
    for k in ks:
        psi0 = 0.5 * np.arcsin(np.sqrt(k))
        M, C, K = matrices(RW, RM, H, h, psi0 * np.ones(RM.shape))
        Mi = np.linalg.inv(M)
        n = RM.shape
        A = np.zeros(n + (8, 8))
        A[..., :4, 4:] = np.eye(4)
        A[..., 4:, :4] = -Mi @ K
        A[..., 4:, 4:] = -Mi @ C
        ev = np.linalg.eigvals(A)
        order = np.argsort(np.abs(ev), axis=-1)
        ev = np.take_along_axis(ev, order, -1)
        drop = (2 if H == 0 and h == 0 else 1) if k == 0 else 0
        ev = ev[..., drop:]
        if H == 0 and h == 0:
            ok = np.all(np.abs(ev.real) < 1e-6, axis=-1)
        else:
            ok = np.all(ev.real < 0, axis=-1)
        out &= ok
    return out


def main():
    d = sys.argv[1]
    mode = sys.argv[2] if len(sys.argv) > 2 else "quick"
    step = 1 if mode == "slow" else 4
    rm_all = np.linspace(0.005, 0.495, 120)
    rw_all = np.linspace(0.5, 4.0, 160)
    rm, rw = rm_all[::step], rw_all[::step]
    ks = np.arange(33) / 32.0
    cases = [("und", 0.0, 0.0), ("hh", 1e-4, 1e-4), ("h10", 1e-5, 1e-4), ("H10", 1e-4, 1e-5),
             ("hh6", 1e-6, 1e-6)]
    if mode == "slow":
        cases += [("r04", 0.3981e-5, 1e-5), ("h100", 1e-6, 1e-4)]
    ref = {}
    for name, H, h in cases:
        ref[name] = stable_grid(rm, rw, H, h, ks)
        with h5py.File(os.path.join(d, name + ".h5"), "r") as f:
            g = f["pendulum/map"]
            v = g["verdict"][:]
            ok_axes = (np.allclose(g["R_m"][:], rm_all, rtol=0, atol=1e-15) and
                       np.allclose(g["R_w"][:], rw_all, rtol=0, atol=1e-15))
            note = g.attrs.get("note", b"")
            note = note.decode() if isinstance(note, bytes) else str(note)
        check("%s (H = %g, h = %g): the archive's axes are the grid of data/pendulum_map_every.ini" % (name, H, h), ok_axes)
        prog_all = v > 0
        prog = prog_all[::step, ::step]
        nbad = int((prog != ref[name]).sum())
        fp, fr = 100 * prog.mean(), 100 * ref[name].mean()
        print("     %s: program %.2f%% stable, NumPy %.2f%% (%d points), %d differ" % (name, fp, fr, prog.size, nbad))
        check("%s: verdicts agree with NumPy at all but 0.1%% of the points" % name, nbad <= prog.size // 1000,
              "%d differ" % nbad)
        # the fraction the note must state: NumPy's on the whole grid (slow), else the archive's
        ref[name + "_frac"] = fr if mode == "slow" else 100 * prog_all.mean()
        ref[name + "_note"] = note
    note = ref["und_note"]
    check("the undamped map carries a note", len(note) > 40, note[:60])
    labels = [("und", "undamped "), ("hh", "H = h: "), ("h10", "h = 10H: "), ("H10", "H = 10h: ")]
    if mode == "slow":
        labels += [("r04", "H/h = 0.4: "), ("h100", "h = 100H: ")]
    for name, label in labels:
        want = label + "%.1f%%" % ref[name + "_frac"]
        check("note states '%s' (%s)" % (want, "NumPy" if mode == "slow" else "the archive"), want in note, note)
    check("the damped maps carry no note", ref["hh_note"] == "" and ref["h10_note"] == "")
    # only the ratio matters at small damping: H = h = 1e-4 and 1e-6 give the same verdicts (NumPy)
    check("NumPy: H = h = 1e-6 gives the verdicts of H = h = 1e-4",
          int((ref["hh"] != ref["hh6"]).sum()) <= ref["hh"].size // 1000)
    # every damped stable point is stable without damping
    for name in ("hh", "h10", "H10"):
        check("NumPy: %s stable only where the undamped map is stable" % name, not np.any(ref[name] & ~ref["und"]))
    if mode == "slow":
        # the largest of the 16 ratios is 0.4: the neighbours 0.25 and 0.63 give less (archives)
        fr = {}
        for r in ("0.2512", "0.631"):
            with h5py.File(os.path.join(d, "r_%s.h5" % r), "r") as f:
                fr[r] = 100 * (f["pendulum/map/verdict"][:] > 0).mean()
        check("H/h = 0.4 beats its neighbours 0.25 and 0.63", fr["0.2512"] < ref["r04_frac"] > fr["0.631"],
              "%.2f, %.2f, %.2f" % (fr["0.2512"], ref["r04_frac"], fr["0.631"]))
    # region B (below the second critical speed without unbalance, R_w2(R_m, 0)) at h = 10H: the rows
    # that keep a stable point there, at full resolution in R_w (quick: only the rows within 4 of the
    # note's value); R_w2 from the undamped k = 0 verdicts of the same grid (NumPy)
    m = re.search(r"region B only from R_m = ([0-9.]+)", note)
    if mode == "slow" or m is None:
        idx = np.arange(len(rm_all))
    else:
        i0 = int(np.argmin(np.abs(rm_all - float(m.group(1)))))
        idx = np.arange(max(0, i0 - 4), min(len(rm_all), i0 + 5))
    rsub = rm_all[idx]
    s0 = stable_grid(rsub, rw_all, 0.0, 0.0, [0.0])
    sB = stable_grid(rsub, rw_all, 1e-5, 1e-4, ks)
    rows = []
    for i in range(len(rsub)):
        if rsub[i] >= 0.25:
            continue
        st = np.nonzero(s0[i])[0]
        if len(st) == 0:
            continue
        j = st[0]
        while j < len(rw_all) and s0[i, j]:
            j += 1
        if np.any(sB[i, :j]):
            rows.append(rsub[i])
    bmin = min(rows) if rows else float("nan")
    print("     h = 10H: region B from R_m = %.4f (NumPy, rows %.4f..%.4f)" % (bmin, rsub[0], rsub[-1]))
    check("note's lower end of region B at h = 10H is NumPy's first grid row (to 5e-4) and not the first row tried",
          m is not None and abs(float(m.group(1)) - bmin) <= 5e-4 and bmin > rsub[0], m.group(0) if m else "not in the note")
    print("%d failed" % FAIL)
    return 1 if FAIL else 0


if __name__ == "__main__":
    sys.exit(main())
