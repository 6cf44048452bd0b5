#!/usr/bin/env python3
"""Independent checks of `autobal pendulum sweep|map` over the physical keys (tests/app/pendulum_physkeys.sh).

Usage: pendulum_physkeys_check.py KIND ARCHIVE [EXTRA]

Everything is recomputed here from the physical set recorded in /pendulum/physical with the swept key
changed, by the conversion (2)-(3) of docs/pendulum.md written out below, and a method that is not the
program's:

  omega_k0   sweep over omega, H1 = H2 = 0, e = 0 (k = 0): the critical speeds are (13) R_w1 = 1 and the
             positive roots W of the negated discriminant (12) of the cubic of (10), found exactly by
             SymPy (real_roots of a polynomial with rational coefficients), kept where the verdict of
             (10) changes (all roots x real and <= 0, tested at the midpoints with mpmath); omega_j =
             sqrt(W_j) omega0.  EXTRA: the sweep's minimum as given in rpm, checked against the
             coordinate (rpm -> rad/s by 2 pi / 60).
  undamped   sweep over any key, H1 = H2 = 0: the verdict of (10) at each point of a finer scan from
             30-digit roots (mpmath.polyroots) of P(x) = x(a6 x^3 + a4 x^2 + a2 x + a0) + k R_m^2 (x + W)^4,
             every change bisected to 1e-13 relative; the program's critical values and kinds must match.
  damped     sweep over any key: the verdict is the sign of the largest real part of the eigenvalues of
             the 8x8 first-order matrix of (5) (NumPy), M, C, K written out from the equations of (5)
             (with every_unbalance: the worst over the recorded k_values); changes on a finer scan
             bisected.
  map        a map over two keys (physical, or one physical and one dimensionless that does not
             depend on it): every point against the NumPy eigenvalue verdict (points with
             |max Re| < 1e-9 skipped).
"""
import math
import sys

import h5py
import mpmath as mp
import numpy as np
import sympy as sp

fails = 0


def check(what, cond, detail=""):
    global fails
    print(("ok   " if cond else "FAIL ") + what + (("  " + detail) if detail else ""))
    if not cond:
        fails += 1


KEYS = ["M", "e", "m", "l", "c", "H1", "H2", "omega"]


def physical(f):
    a = f["pendulum/physical"].attrs
    return {k: float(a[k]) for k in KEYS}


def convert(q):
    """(2)-(3): M_sigma = M + 2m, omega0 = sqrt(c / M_sigma), R_w = omega / omega0, R_m = m / M_sigma,
    H = H2 / (omega0 M_sigma), h = H1 / (m l^2 omega0), sin psi0 = M e / (2 m l)"""
    Ms = q["M"] + 2 * q["m"]
    w0 = math.sqrt(q["c"] / Ms)
    s = q["M"] * q["e"] / (2 * q["m"] * q["l"])
    assert 0 <= s < 1, q
    return dict(R_w=q["omega"] / w0, R_m=q["m"] / Ms, H=q["H2"] / (w0 * Ms), h=q["H1"] / (q["m"] * q["l"] ** 2 * w0),
                psi0=math.asin(s), omega0=w0, Ms=Ms)


def with_key(q, key, v):
    r = dict(q)
    r[key] = v
    return r


def maxre(d):
    """largest real part of the eigenvalues of (5) at the dimensionless set d (at psi0 = 0 without the
    structural lambda = 0)"""
    R, m, H, h, p = d["R_w"], d["R_m"], d["H"], d["h"], d["psi0"]
    s, c = math.sin(p), math.cos(p)
    # rows: the four equations of (5), columns (xi, eta, alpha, beta)
    M = np.array([[1, 0, -m * c, -m * c], [0, 1, -m * s, m * s], [-c, -s, 1, 0], [-c, s, 0, 1]], float)
    C = np.array([[H, -2 * R, 2 * m * R * s, -2 * m * R * s], [2 * R, H, -2 * m * R * c, -2 * m * R * c],
                  [-2 * R * s, 2 * R * c, h, 0], [2 * R * s, 2 * R * c, 0, h]], float)
    K = np.array([[1 - R * R, -H * R, m * R * R * c, m * R * R * c], [H * R, 1 - R * R, m * R * R * s, -m * R * R * s],
                  [R * R * c, R * R * s, 0, 0], [R * R * c, -R * R * s, 0, 0]], float)
    Mi = np.linalg.inv(M)
    A = np.zeros((8, 8))
    A[:4, 4:] = np.eye(4)
    A[4:, :4] = -Mi @ K
    A[4:, 4:] = -Mi @ C
    ev = np.linalg.eigvals(A)
    if p == 0:  # k = 0: the family psi = -phi of balanced states, lambda = 0, left out as the program does
        ev = ev[np.argsort(np.abs(ev))][1:]
    return float(np.max(ev.real))


def undamped_verdict(q):
    """1 / -1: every root x of (10) real and <= 0, from 30-digit roots; mpmath throughout"""
    mp.mp.dps = 30
    Ms = mp.mpf(q["M"]) + 2 * mp.mpf(q["m"])
    W = mp.mpf(q["omega"]) ** 2 * Ms / mp.mpf(q["c"])
    Rm = mp.mpf(q["m"]) / Ms
    s = mp.mpf(q["M"]) * mp.mpf(q["e"]) / (2 * mp.mpf(q["m"]) * mp.mpf(q["l"]))
    k = 4 * s * s * (1 - s * s)  # sin^2(2 psi0)
    a0 = 2 * Rm * W ** 2 * (W - 1)
    a2 = (W - 1) ** 2 + 2 * Rm * W * (W + 6)
    a4 = 2 * (1 - Rm) * (W + 1)
    a6 = 1 - 2 * Rm
    # P(x) = x (a6 x^3 + a4 x^2 + a2 x + a0) + k Rm^2 (x + W)^4, highest power first
    b = k * Rm ** 2
    coef = [a6 + b, a4 + 4 * b * W, a2 + 6 * b * W ** 2, a0 + 4 * b * W ** 3, b * W ** 4]
    roots = mp.polyroots(coef, maxsteps=200, extraprec=200)
    ok = all(abs(mp.im(r)) < mp.mpf(10) ** -25 and mp.re(r) <= mp.mpf(10) ** -25 for r in roots)
    return 1 if ok else -1


def changes(fun, lo, hi, n, log):
    """the changes of fun on an n-point scan of [lo, hi], each bisected to 1e-13 relative"""
    xs = np.geomspace(lo, hi, n) if log else np.linspace(lo, hi, n)
    vs = [fun(x) for x in xs]
    out = []
    for i in range(n - 1):
        if vs[i] == vs[i + 1]:
            continue
        a, b = xs[i], xs[i + 1]
        while b - a > 1e-13 * abs(b):
            mid = 0.5 * (a + b)
            if fun(mid) == vs[i]:
                a = mid
            else:
                b = mid
        out.append((0.5 * (a + b), vs[i], vs[i + 1]))
    return out


def sweep_data(f):
    g = f["pendulum/sweep"]
    key = g.attrs["axis1"]
    key = key.decode() if isinstance(key, bytes) else str(key)
    assert key.startswith("pendulum.")
    key = key[len("pendulum."):]
    dim = g.attrs["axis1_dim"]
    dim = dim.decode() if isinstance(dim, bytes) else str(dim)
    x = g[dim][:]
    units = g[dim].attrs["units"]
    units = units.decode() if isinstance(units, bytes) else str(units)
    log = (g.attrs["axis1_scale"].decode() if isinstance(g.attrs["axis1_scale"], bytes)
           else str(g.attrs["axis1_scale"])) == "log"
    crit = g["critical"][:]
    below = g["critical_below"][:]
    above = g["critical_above"][:]
    return g, key, dim, x, units, log, crit, below, above


SI = {"M": "kg", "e": "m", "m": "kg", "l": "m", "c": "N/m", "H1": "N m s", "H2": "N s/m", "omega": "rad/s"}


def compare(key, crit, below, above, ref, rtol):
    print(f"     {key}: program {list(map(float, crit))}")
    print(f"     {key}: here    {[r[0] for r in ref]}")
    check(f"{len(ref)} critical values of {key}, as many as found here", len(crit) == len(ref) and len(ref) > 0)
    if len(crit) == len(ref):
        err = max(abs(c - r[0]) / abs(r[0]) for c, r in zip(crit, ref))
        check(f"critical values of {key} agree to {rtol:g} relative", err <= rtol, f"max rel. diff {err:.3g}")
        check(f"kinds of the changes of {key} agree (verdict below -> above)",
              all(int(b) == r[1] and int(a) == r[2] for b, a, r in zip(below, above, ref)))


def main():
    kind, path = sys.argv[1], sys.argv[2]
    with h5py.File(path, "r") as f:
        q0 = physical(f)
        if kind in ("omega_k0", "undamped", "damped"):
            g, key, dim, x, units, log, crit, below, above = sweep_data(f)
            check(f"the coordinate is named after the key ({dim}) in its SI unit ({units})",
                  dim == key and units == SI[key])
            check("the dimension of verdict is that coordinate",
                  g["verdict"].dims[0][0].name == f"/pendulum/sweep/{dim}")
        if kind == "omega_k0":
            assert key == "omega" and q0["e"] == 0 and q0["H1"] == 0 and q0["H2"] == 0
            if len(sys.argv) > 3:
                want = float(sys.argv[3]) * 2 * math.pi / 60
                check("the range given in rpm is the coordinate's first value in rad/s", abs(x[0] - want) <= 1e-14 * want,
                      f"{x[0]!r} vs {want!r}")
            d = convert(q0)
            w0 = d["omega0"]
            Rm = sp.Rational(q0["m"]) / (sp.Rational(q0["M"]) + 2 * sp.Rational(q0["m"]))
            W = sp.symbols("W")
            a0 = 2 * Rm * W**2 * (W - 1)
            a2 = (W - 1)**2 + 2 * Rm * W * (W + 6)
            a4 = 2 * (1 - Rm) * (W + 1)
            a6 = 1 - 2 * Rm
            F = sp.Poly(sp.expand(-a2**2 * a4**2 + 4 * a2**3 * a6 + 27 * a0**2 * a6**2 - 18 * a0 * a2 * a4 * a6
                                  + 4 * a0 * a4**3), W)  # (12)
            cand = sorted({float(r) for r in sp.real_roots(F) if r > 0} | {1.0})  # (13): W = 1
            lo, hi = (x[0] / w0) ** 2, (x[-1] / w0) ** 2
            cand = [c for c in cand if lo < c < hi]
            ref = []
            edges = [lo] + cand + [hi]
            verd = [undamped_verdict(with_key(q0, "omega", math.sqrt(0.5 * (edges[i] + edges[i + 1])) * w0))
                    for i in range(len(edges) - 1)]
            for i, c in enumerate(cand):
                if verd[i] != verd[i + 1]:
                    ref.append((math.sqrt(c) * w0, verd[i], verd[i + 1]))
            print(f"     (12), (13): W = {cand}, R_w = {[math.sqrt(c) for c in cand]}")
            compare("omega", crit, below, above, ref, 1e-8)
        elif kind == "undamped":
            assert q0["H1"] == 0 and q0["H2"] == 0
            ref = changes(lambda v: undamped_verdict(with_key(q0, key, v)), x[0], x[-1], 300, log)
            compare(key, crit, below, above, ref, 1e-8)
        elif kind == "damped":
            if int(g.attrs["every_unbalance"]):  # stable only if it is for every k of the set
                ks = [float(k) for k in g.attrs["k_values"]]

                def fun(v):
                    d = convert(with_key(q0, key, v))
                    for k in ks:
                        d["psi0"] = 0.5 * math.asin(math.sqrt(k))
                        if maxre(d) >= 0:
                            return -1
                    return 1
                ref = changes(fun, x[0], x[-1], 300, log)
            else:
                ref = changes(lambda v: 1 if maxre(convert(with_key(q0, key, v))) < 0 else -1, x[0], x[-1], 600, log)
            compare(key, crit, below, above, ref, 1e-7)
        elif kind == "map":
            g = f["pendulum/map"]
            keys = []
            for a in ("axis1", "axis2"):
                t = g.attrs[a]
                t = t.decode() if isinstance(t, bytes) else str(t)
                keys.append(t[len("pendulum."):])
            dims = [g.attrs[a].decode() if isinstance(g.attrs[a], bytes) else str(g.attrs[a])
                    for a in ("axis1_dim", "axis2_dim")]
            v1, v2 = g[dims[0]][:], g[dims[1]][:]
            ver = g["verdict"][:]
            check("verdict(axis1, axis2) with the keys' coordinates as its dimensions",
                  [d[0].name for d in g["verdict"].dims] == [f"/pendulum/map/{dims[0]}", f"/pendulum/map/{dims[1]}"])
            for key, dim in zip(keys, dims):
                if key in SI:
                    u = g[dim].attrs["units"]
                    u = u.decode() if isinstance(u, bytes) else str(u)
                    check(f"coordinate {dim} in {u}", dim == key and u == SI[key])
            bad = skipped = nst = 0
            for i, a in enumerate(v1):
                for j, b in enumerate(v2):
                    q = dict(q0)
                    dimless = {}
                    for key, val in ((keys[0], a), (keys[1], b)):
                        if key in SI:
                            q[key] = float(val)
                        else:
                            dimless[key] = float(val)
                    d = convert(q)
                    for key, val in dimless.items():  # a dimensionless axis is set on the converted point
                        if key == "k":
                            d["psi0"] = 0.5 * math.asin(math.sqrt(val))
                        else:
                            d[key] = val
                    mr = maxre(d)
                    if abs(mr) < 1e-9:
                        skipped += 1
                        continue
                    want = 1 if mr < 0 else -1
                    nst += want > 0
                    bad += int(ver[i, j]) != want
            n = ver.size
            print(f"     map ({keys[0]}, {keys[1]}): {nst} stable of {n - skipped} compared, {skipped} skipped, {bad} differ")
            check(f"map over ({keys[0]}, {keys[1]}) = the NumPy eigenvalue verdict at every point (both occur)",
                  bad == 0 and 0 < nst < n - skipped and skipped < n // 10)
        else:
            raise SystemExit("unknown kind " + kind)
    print(f"{'FAILED' if fails else 'passed'}: {fails} failures")
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
