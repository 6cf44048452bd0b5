"""Checks of the residual-unbalance statistics of `autobal rotor ensemble` (tests/app/ensemble_stats.sh),
each against a computation here that does not use the program's own numbers:

  unbalance ARCHIVE [JSON]   per member: |s_j| recomputed from the archived final ball angles and the
                             plane's m0, r0, psi0, ball masses and radii ((3.10), docs/rotor.md), the
                             worst plane, vs residual_unbalance_abs_final; the grade
                             n_planes U Omega / m_p 1e3 with Omega the member's speed at the end (its
                             omega / omega_b variable, the configuration's omega or drive_omega_b) vs
                             balance_grade_final; the statistics group vs numpy.quantile (its default
                             'linear' method) and numpy.mean over the members with status >= 0; each
                             target's count and probability vs a count here and its Wilson interval
                             vs the closed form; the JSON summary (when given) vs the archive.
  nodatasets ARCHIVE         the per-member datasets are absent (write_unbalance not set), the
                             statistics group is there.
"""
import json
import sys

import h5py
import numpy as np

Z = 1.959963984540054
QP = [0.0, 0.05, 0.25, 0.5, 0.75, 0.95, 1.0]
QN = ["min", "q05", "q25", "median", "q75", "q95", "max"]
fails = 0


def check(what, cond, detail=""):
    global fails
    print(("ok   " if cond else "FAIL ") + what + (f"  ({detail})" if detail else ""))
    if not cond:
        fails += 1


def wilson(k, n):
    p = k / n
    d = 1 + Z * Z / n
    c = (p + Z * Z / (2 * n)) / d
    h = Z * np.sqrt(p * (1 - p) / n + Z * Z / (4 * n * n)) / d
    return max(0.0, c - h), min(1.0, c + h)


def plane_unbalance(f, ang, psi0_1=None):
    """|s_j| of each plane from the final angles (members x balls, plane 1 first); psi0_1: plane 1's
    unbalance angle of each member when the ensemble varies it."""
    out, off = [], 0
    j = 1
    while f"rotor/plane{j}" in f:
        a = f[f"rotor/plane{j}"].attrs
        nb = int(a["n_balls"])
        psi0 = psi0_1 if (j == 1 and psi0_1 is not None) else a["psi0"]
        s = a["m0"] * a["r0"] * np.exp(1j * psi0) + np.zeros(ang.shape[0], complex)
        for i in range(nb):
            s = s + a["ball_mass"][i] * a["ball_radius"][i] * np.exp(1j * ang[:, off + i])
        out.append(np.abs(s))
        off += nb
        j += 1
    return np.array(out)


def member_values(g, name, shape):
    """Parameter `name` of every member (None when the ensemble does not vary it)."""
    if name not in g.attrs["parameters"].split(", "):
        return None
    v = g[name][()]
    if g.attrs["mode"] == "random":
        return v.reshape(shape)
    axis = g.attrs["parameters"].split(", ").index(name)  # grid axes in row-major order
    sh = [1] * len(shape)
    sh[axis] = len(v)
    return np.broadcast_to(v.reshape(sh), shape)


def speed_end(g, f, shape):
    """Each member's speed at the end: its own parameter, else the drive's or the rotor's."""
    for name in ("omega", "omega_b"):
        v = member_values(g, name, shape)
        if v is not None:
            return np.abs(v)
    if "drive_mode" in g.attrs:
        assert g.attrs["drive_mode"] == "ramp"
        return np.full(shape, abs(g.attrs["drive_omega_b"]))
    return np.full(shape, abs(f["rotor"].attrs["omega"]))


def unbalance(path, jpath=None):
    f = h5py.File(path, "r")
    g = f["rotor/ensemble"]
    status = g["status"][()]
    shape = status.shape
    ang = g["final_angle"][()].reshape(-1, g["final_angle"].shape[-1])
    psi0 = member_values(g, "psi0", shape)
    sj = plane_unbalance(f, ang, None if psi0 is None else np.ravel(psi0))
    npl = sj.shape[0]
    U_py = sj.max(axis=0).reshape(shape)
    U = g["residual_unbalance_abs_final"][()]
    G = g["balance_grade_final"][()]
    check(f"{path}: units kg m and mm/s", g["residual_unbalance_abs_final"].attrs["units"] == "kg m"
          and g["balance_grade_final"].attrs["units"] == "mm/s")
    err = np.max(np.abs(U - U_py) / U_py)
    check(f"{path}: U = max_j |s_j| from the final angles ({npl} plane(s), {U.size} members)", err < 1e-9,
          f"largest relative difference {err:.2e}, U {U.min()*1e6:.4g}..{U.max()*1e6:.4g} g mm")
    m = f["rotor"].attrs["m_p"] if f["rotor"].attrs["input"] == "hardware" else f["rotor/lumped"].attrs["M"]
    G_py = npl * U_py * speed_end(g, f, shape) / m * 1e3
    err = np.max(np.abs(G - G_py) / G_py)
    check(f"{path}: G = n_planes U Omega_end / m 1e3 (m = {m} kg)", err < 1e-9, f"largest relative difference {err:.2e}")
    ok = status >= 0
    check(f"{path}: some members ran without failure", ok.sum() > 0, f"{ok.sum()} of {ok.size}")
    js = json.load(open(jpath)) if jpath else None
    for name, vals in (("residual_unbalance_abs_final", U), ("balance_grade_final", G)):
        st = g[f"statistics/{name}"].attrs
        v = vals[ok]
        want = np.quantile(v, QP)
        got = np.array([st[q] for q in QN])
        err = np.max(np.abs(got - want) / np.abs(want))
        check(f"{path}: {name} quantiles vs numpy.quantile over {v.size} members", st["n"] == v.size and err < 1e-13,
              f"got {got}, numpy {want}, largest relative difference {err:.1e}")
        check(f"{path}: {name} mean vs numpy.mean", abs(st["mean"] - v.mean()) <= 1e-13 * abs(v.mean()))
        check(f"{path}: {name} statistics carry units and a long name", st["units"] == g[name].attrs["units"]
              and st["min_units"] == st["units"] and len(st["long_name"]) > 10)
        if "target" in st:
            k = int(np.sum(v <= st["target"]))
            lo, hi = wilson(k, v.size)
            check(f"{path}: P({name} <= {st['target']:.4g}) = {k}/{v.size} counted here", st["n_within_target"] == k
                  and st["n_evaluated"] == v.size and st["probability_within_target"] == k / v.size)
            check(f"{path}: its Wilson interval vs the closed form", abs(st["probability_within_target_wilson_low"] - lo) < 1e-14
                  and abs(st["probability_within_target_wilson_high"] - hi) < 1e-14, f"[{lo:.4f}, {hi:.4f}]")
            check(f"{path}: both outcomes occur (the count means something)", 0 < k < v.size, f"{k} of {v.size}")
        if js is not None:
            q = js[name]
            check(f"{path}: JSON {name} = archive", q["n"] == st["n"] and np.allclose(q["quantiles"], got, rtol=1e-15, atol=0)
                  and ("target" not in st or q["n_within_target"] == st["n_within_target"]))
    nb, nok = int(g.attrs["n_balanced"]), int(ok.sum())
    lo, hi = wilson(nb, nok)
    check(f"{path}: P(balanced) Wilson interval vs the closed form", abs(g.attrs["probability_balanced_wilson_low"] - lo) < 1e-14
          and abs(g.attrs["probability_balanced_wilson_high"] - hi) < 1e-14, f"{nb} of {nok}: [{lo:.4f}, {hi:.4f}]")


def nodatasets(path):
    g = h5py.File(path, "r")["rotor/ensemble"]
    check(f"{path}: no per-member unbalance datasets without write_unbalance",
          "residual_unbalance_abs_final" not in g and "balance_grade_final" not in g)
    check(f"{path}: the statistics are there (attributes)", "statistics/balance_grade_final" in g
          and g["statistics/balance_grade_final"].attrs["n"] > 0)


if __name__ == "__main__":
    {"unbalance": unbalance, "nodatasets": nodatasets}[sys.argv[1]](*sys.argv[2:])
    sys.exit(1 if fails else 0)
