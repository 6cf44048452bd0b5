"""Independent checks of `autobal pendulum ...` archives (run by tests/app/pendulum.sh).

Everything expected here is recomputed from the formulas of docs/pendulum.md with NumPy/SciPy, not
taken from autobal: the characteristic polynomial (6) built with numpy polynomials, the
undamped polynomial (10), the closed form (16), (18), and R_m^(1) as the point where
(16) and (18) touch.  Usage: pendulum_check.py roots|critical|map FILE.h5
"""
import sys

import h5py
import numpy as np
import xarray as xr
from numpy.polynomial import Polynomial as P
from scipy.optimize import brentq, minimize_scalar

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures += 1


def char_poly(Rw, Rm, H, h, psi0):
    """(6) as a numpy Polynomial in lambda with real coefficients."""
    lam = P([0, 1])
    Pl = lam + 1j * Rw
    a11 = Pl**2 + H * Pl + 1
    a31 = Pl**2
    a33 = lam**2 + h * lam
    cj = lambda p: P(np.conj(p.coef))
    f = (a11 * a33 - Rm * a31**2) * (cj(a11) * a33 - Rm * cj(a31) ** 2) - Rm**2 * np.cos(2 * psi0) ** 2 * a31**2 * cj(a31) ** 2
    return P(f.coef.real), np.max(np.abs(f.coef.imag))


def undamped_roots(Rm, Rw, k):
    W = Rw**2
    a0 = 2 * Rm * W**2 * (W - 1)
    a2 = (W - 1) ** 2 + 2 * Rm * W * (W + 6)
    a4 = 2 * (1 - Rm) * (W + 1)
    a6 = 1 - 2 * Rm
    x = P([0, 1])
    p = x * P([a0, a2, a4, a6]) + k * Rm**2 * (x + W) ** 4
    return p.roots()


def undamped_class(Rm, Rw, k):
    """+1 stable, -1 unstable, 0 too close to call (in floating point)."""
    r = undamped_roots(Rm, Rw, k)
    scale = max(1.0, np.max(np.abs(r)))
    if np.all(np.abs(r.imag) < 1e-9 * scale) and np.all(r.real <= 1e-12 * scale):
        return 1
    if np.any(np.abs(r.imag) > 1e-4 * scale) or np.any(r.real > 1e-6 * scale):
        return -1
    return 0


def rw16(Rm):
    u = brentq(lambda u: (u**3 / (1 - 2 * u * u)) ** 2 - Rm, 1e-12, 1 / np.sqrt(2) - 1e-14, xtol=1e-16, rtol=1e-15)
    return np.sqrt(1 - u * u) / (1 - 2 * u * u)


def rw18(Rm):
    return np.sqrt(2 * (1 - 2 * Rm)) / (1 - 4 * Rm)


def params(f):
    a = f["pendulum"].attrs
    return float(a["R_w"]), float(a["R_m"]), float(a["H"]), float(a["h"]), float(a["psi0"])


def check_common(f):
    for key in ("Conventions", "autobal_version", "command_line", "created", "status", "input_config"):
        check("root attribute " + key, key in f.attrs)
    check("status complete", f.attrs.get("status") == "complete", str(f.attrs.get("status")))
    for name in ("R_w", "R_m", "H", "h", "psi0", "k"):
        check("parameter %s with unit" % name, f["pendulum"].attrs.get(name + "_units") is not None)


def do_roots(path):
    with h5py.File(path, "r") as f:
        check_common(f)
        Rw, Rm, H, h, psi0 = params(f)
        g = f["pendulum/roots"]
        roots = g["root_real"][()] + 1j * g["root_imag"][()]
        coef = g["char_poly"][()]
        verdict = g.attrs["verdict"]
    poly, imag = char_poly(Rw, Rm, H, h, psi0)
    check("(6) has real coefficients", imag < 1e-12, "max |imag| %.2e" % imag)
    scale = np.max(np.abs(poly.coef))
    d = np.max(np.abs(poly.coef - coef)) / scale
    check("coefficients of (6) match numpy's", d < 1e-13, "rel diff %.2e" % d)
    ref = poly.roots()
    used = set()
    worst = 0.0
    for r in roots:
        j = min((j for j in range(len(ref)) if j not in used), key=lambda j: abs(ref[j] - r))
        used.add(j)
        worst = max(worst, abs(ref[j] - r))
    check("roots match numpy's roots of (6)", worst < 1e-8, "max diff %.2e" % worst)
    want = "stable" if np.max(ref.real) < -1e-9 else "unstable"
    check("verdict matches numpy roots", verdict == want, "%s vs %s (max Re %.3e)" % (verdict, want, np.max(ref.real)))
    ds = xr.open_dataset(path, engine="h5netcdf", group="pendulum/roots")
    check("xarray: root_real over dim 'root'", ds["root_real"].dims == ("root",))
    check("xarray: char_poly over 'power'", ds["char_poly"].dims == ("power",) and ds["power"].attrs["units"] == "1")


def do_critical(path):
    with h5py.File(path, "r") as f:
        check_common(f)
        Rw, Rm, H, h, psi0 = params(f)
        k = float(f["pendulum"].attrs["k"])
        g = f["pendulum/critical"]
        crit = g["undamped_R_w"][()] if "undamped_R_w" in g else np.array([])
        kind = g["undamped_kind"][()] if "undamped_kind" in g else np.array([])
        k1 = g["undamped_k1_R_w"][()]
        rm1 = float(g.attrs["R_m1"])
        prefixes = ["undamped", "undamped_k0", "undamped_k1"] + (["damped"] if "n_damped_critical" in g.attrs else [])
        trunc = {pre: g.attrs.get(pre + "_truncated") for pre in prefixes}
        ncrit = {pre: int(g.attrs["n_%s_critical" % pre]) for pre in prefixes}
        dcrit = g["damped_R_w"][()] if "damped_R_w" in g else np.array([])
        dkind = g["damped_kind"][()] if "damped_kind" in g else np.array([])
        dlo = g["damped_stable_lo"][()] if "damped_stable_lo" in g else np.array([])
        dhi = g["damped_stable_hi"][()] if "damped_stable_hi" in g else np.array([])
    # every list carries its truncation flag; these runs have few changes, far below the
    # capacity (32), so none is truncated
    for pre in prefixes:
        check("attribute %s_truncated present and 0 (%d critical speeds)" % (pre, ncrit[pre]),
              trunc[pre] is not None and int(trunc[pre]) == 0 and ncrit[pre] < 32, str(trunc[pre]))
    # damped critical speeds: max Re of numpy's roots of (6) changes sign across each
    if "damped" in prefixes:
        maxre = lambda x: np.max(char_poly(x, Rm, H, h, psi0)[0].roots().real)
        check("damped: some critical speeds", len(dcrit) >= 1, str(dcrit))
        for c, kd in zip(dcrit, dkind):
            lo, hi = maxre(c * (1 - 1e-6)), maxre(c * (1 + 1e-6))
            check("damped: max Re of the roots of (6) changes sign at R_w = %.10f (kind %d)" % (c, kd),
                  (lo < 0) != (hi < 0) and (hi < 0) == (kd > 0), "%.3e -> %.3e" % (lo, hi))
        for a, b in zip(dlo, dhi):
            check("damped: stable interval midpoint is stable (numpy roots)", maxre(0.5 * (a + b)) < 0, "[%.8g, %.8g]" % (a, b))
    # every reported change of stability is a real change for the independent (10)
    for c, kd in zip(crit, kind):
        if kd == 0:
            continue
        lo, hi = undamped_class(Rm, c * (1 - 1e-4), k), undamped_class(Rm, c * (1 + 1e-4), k)
        check("undamped verdict changes at R_w = %.10f" % c, (lo, hi) == ((-1, 1) if kd > 0 else (1, -1)), "below %d above %d" % (lo, hi))
    # and between them nothing changes: sample each interval
    edges = np.concatenate(([0.05], crit[kind != 0] if len(crit) else [], [6.0]))
    bad = 0
    for a, b in zip(edges[:-1], edges[1:]):
        cls = [undamped_class(Rm, x, k) for x in np.linspace(a, b, 202)[1:-1]]
        cls = [c for c in cls if c != 0]
        bad += len(set(cls)) > 1
    check("no stability change between reported critical speeds (sampled)", bad == 0, "%d intervals mixed" % bad)
    # k = 1: first critical speed is (16)
    want = rw16(Rm)
    check("R_w1(R_m, 1) equals closed form (16)", abs(k1[0] - want) < 1e-9 * want, "%.12f vs %.12f" % (k1[0], want))
    # R_m^(1): where (16) and (18) touch = the maximum of (16) - (18), which is 0 there
    res = minimize_scalar(lambda r: -(rw16(r) - rw18(r)), bounds=(0.03, 0.06), method="bounded", options={"xatol": 1e-12})
    check("R_m^(1) is where (16) and (18) touch", abs(res.x - rm1) < 2e-6, "%.10f vs %.10f" % (rm1, res.x))
    check("(16) - (18) vanishes at R_m^(1)", abs(rw16(rm1) - rw18(rm1)) < 1e-9, "%.2e" % abs(rw16(rm1) - rw18(rm1)))
    ds = xr.open_dataset(path, engine="h5netcdf", group="pendulum/critical/curves")
    check("xarray: curves over (R_m, branch)", ds["R_w_k0"].dims == ("R_m", "branch"))
    rm = ds["R_m"].values
    r0 = ds["R_w_k0"].values
    sel = rm < 0.2
    check("k = 0: R_w1 = 1 (13)", np.allclose(r0[sel, 0], 1.0, atol=1e-9))
    i = np.argmin(abs(rm - 0.01))
    q = rm[i]
    eps = (q / 2) ** (1 / 3)
    s2 = 1 + 49 / 16 * q + 12397 / 1024 * q * q
    s3 = 1 + 2 * eps + 7 / 3 * eps**2 + 29 / 8 * eps**3
    check("k = 0, R_m = %.3f: R_w2 close to series (14)" % q, abs(r0[i, 1] - s2) < 5 * q**3 * 100, "%.8f vs %.8f" % (r0[i, 1], s2))
    check("k = 0, R_m = %.3f: R_w3 close to series (14)" % q, abs(r0[i, 2] - s3) < 50 * eps**4, "%.8f vs %.8f" % (r0[i, 2], s3))
    check("no R_w2, R_w3 at k = 0 above R_m = 0.25", np.all(np.isnan(r0[rm > 0.2501, 1:])))


def do_map(path):
    with h5py.File(path, "r") as f:
        check_common(f)
        Rw, Rm, H, h, psi0 = params(f)
        g = f["pendulum/map"]
        ks = g.attrs["k_values"]
        every = int(g.attrs["every_unbalance"])
    ds = xr.open_dataset(path, engine="h5netcdf", group="pendulum/map")
    v = ds["verdict"]
    check("xarray: verdict over (R_m, R_w)", v.dims == ("R_m", "R_w"))
    check("xarray: units on coordinates", ds["R_m"].attrs.get("units") == "1" and ds["R_w"].attrs.get("units") == "1")
    rng = np.random.default_rng(7)
    rms, rws = ds["R_m"].values, ds["R_w"].values
    agree = skipped = 0
    n = 150
    for _ in range(n):
        i, j = rng.integers(len(rms)), rng.integers(len(rws))
        if H == 0 and h == 0:
            cls = [undamped_class(rms[i], rws[j], kk) for kk in ks]
            want = -1 if -1 in cls else (0 if 0 in cls else 1)
        else:
            mx = max(np.max(char_poly(rws[j], rms[i], H, h, 0.5 * np.arcsin(np.sqrt(kk)))[0].roots().real) for kk in ks)
            want = 1 if mx < -1e-7 else (-1 if mx > 1e-7 else 0)
        if want == 0:
            skipped += 1
            continue
        agree += int(v.values[i, j]) == want
    check("map verdicts agree with numpy at random points", agree == n - skipped, "%d/%d (skipped %d near a boundary)" % (agree, n - skipped, skipped))
    if every and H == 0 and h == 0:
        # Region A: above R_w3(R_m, 0) (R_m < 0.25) the balancer works for every unbalance.
        pass


def main():
    what, path = sys.argv[1], sys.argv[2]
    {"roots": do_roots, "critical": do_critical, "map": do_map}[what](path)
    print("%s: %d failed" % (what, failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
