"""Independent checks of `autobal rotor sweep|map` over configuration keys (run by
tests/app/rotor_keys.sh).  The rotor at each point is built here from the archive's recorded
configuration with the swept key changed: the lumped coefficients from the hardware by (2.7),
(2.9), (2.11) written out below, the balanced angles (3.14) and the degree-12 polynomial Delta
with NumPy (rotor_stability_check.delta), its roots with numpy.roots -- not autobal's numbers.
Usage: rotor_keys_check.py sweep|map FILE.h5
"""
import sys

import h5py
import numpy as np
import xarray as xr

import rotor_stability_check as rc
from rotor_stability_check import check


def lumped(hw):
    """(2.7), (2.9) with c_z = c_Lz, (2.11)"""
    L = dict(M=hw["M_k"] + hw["m_p"], A=hw["A_k"] + hw["A_p"], C=hw["C_p"])
    for t in "ch":
        L[t + "_x"] = hw[t + "_Lx"] + hw[t + "_Rx"]
        L[t + "_y"] = hw[t + "_Ly"] + hw[t + "_Ry"]
        L[t + "_alpha"] = hw[t + "_Ly"] * hw["l_L"] ** 2 + hw[t + "_Ry"] * hw["l_R"] ** 2
        L[t + "_beta"] = hw[t + "_Lx"] * hw["l_L"] ** 2 + hw[t + "_Rx"] * hw["l_R"] ** 2
        L[t + "_xbeta"] = hw[t + "_Lx"] * hw["l_L"] - hw[t + "_Rx"] * hw["l_R"]
        L[t + "_yalpha"] = hw[t + "_Ly"] * hw["l_L"] - hw[t + "_Ry"] * hw["l_R"]
    return L


HW_KEYS = ["M_k", "A_k", "m_p", "A_p", "C_p", "l_L", "l_R", "c_Lx", "c_Ly", "c_Lz", "c_Rx", "c_Ry",
           "h_Lx", "h_Ly", "h_Lz", "h_Rx", "h_Ry"]


def base(f):
    a = f["rotor"].attrs
    check("hardware input recorded", a["input"] == "hardware")
    hw = {k: float(a[k]) for k in HW_KEYS}
    w, L, planes, inertia = rc.load(f)
    check("recorded lumped set = (2.7)-(2.11) of the recorded hardware",
          all(abs(L[k] - v) <= 1e-12 * max(1.0, abs(v)) for k, v in lumped(hw).items()))
    return w, hw, planes[0]


def apply(key, x, hw, pl):
    """the rotor with key = x: (hardware dict, plane dict)"""
    hw, pl = dict(hw), dict(pl)
    sec, _, name = key.partition(".")
    if sec in ("rotor", "supports"):
        hw[name] = x
    elif key == "anisotropy":
        hw["c_Ly"], hw["c_Ry"] = x * hw["c_Lx"], x * hw["c_Rx"]
    elif key == "C_over_A":
        hw["C_p"] = x * (hw["A_k"] + hw["A_p"])
    elif sec == "plane1":
        if name in ("ball_mass", "ball_radius", "ball_damping"):
            pl[{"ball_mass": "m", "ball_radius": "r", "ball_damping": "h"}[name]] = np.full(len(pl["m"]), x)
        elif name == "unbalance":
            pl["m0"] = x / pl["r0"]
        else:
            pl[name] = x
    else:
        raise ValueError(key)
    return hw, pl


def margin(w, key, x, hw, pl):
    hw2, pl2 = apply(key, x, hw, pl)
    L = lumped(hw2)
    iso = all(abs(L[a] - L[b]) <= 1e-12 * max(abs(L[a]), 1e-300) for a, b in
              [("c_x", "c_y"), ("c_alpha", "c_beta"), ("c_xbeta", "c_yalpha"), ("h_x", "h_y"), ("h_alpha", "h_beta"),
               ("h_xbeta", "h_yalpha")])
    assert iso, "this check covers isotropic supports only"
    if pl2["m0"] * pl2["r0"] > np.sum(pl2["m"] * pl2["r"]):
        return np.nan  # (3.14): no balanced configuration
    return rc.roots_of(rc.delta(w, L, pl2, rc.balanced_two(pl2))).real.max()


def do_sweep(fn):
    f = h5py.File(fn, "r")
    rc.check_common(f)
    w, hw, pl = base(f)
    g = f["rotor/sweep"]
    key = g.attrs["param"]
    key = key.decode() if isinstance(key, bytes) else str(key)
    ds = xr.open_dataset(fn, engine="h5netcdf", group="rotor/sweep")
    check("xarray: margin over %s" % key, ds["margin"].dims == (key,))
    x, mg = ds[key].values, ds["margin"].values
    worst, nan_bad = 0.0, 0
    for k in range(0, len(x), 7):
        lam_max = margin(w, key, x[k], hw, pl)
        if np.isnan(lam_max) or np.isnan(mg[k]):
            nan_bad += np.isnan(lam_max) != np.isnan(mg[k])
            continue
        worst = max(worst, abs(lam_max - mg[k]) / max(1.0, abs(lam_max)))
    check("%s sweep: margins = NumPy roots of the rotor rebuilt with the key (every 7th point)" % key, worst < 1e-9,
          "%.3g" % worst)
    check("no balanced configuration (NaN) at the same points", nan_bad == 0)
    rc.check_critical(g, lambda v: margin(w, key, v, hw, pl))
    print("units of %s: %s" % (key, ds[key].attrs["units"]))


def do_map(fn):
    f = h5py.File(fn, "r")
    rc.check_common(f)
    w, hw, pl = base(f)
    g = f["rotor/map"]
    k1, k2 = (str(g.attrs[a]) for a in ("param1", "param2"))
    ds = xr.open_dataset(fn, engine="h5netcdf", group="rotor/map")
    check("xarray: margin over (%s, %s)" % (k1, k2), ds["margin"].dims == (k1, k2))
    x1, x2, mg, vd = ds[k1].values, ds[k2].values, ds["margin"].values, ds["verdict"].values
    worst, nan_bad, n_nan = 0.0, 0, 0
    rng = np.random.default_rng(3)
    for _ in range(20):
        i, j = rng.integers(len(x1)), rng.integers(len(x2))
        hw1, pl1 = apply(k1, x1[i], hw, pl)
        m = margin(w, k2, x2[j], hw1, pl1)
        if np.isnan(m) or np.isnan(mg[i, j]):
            nan_bad += np.isnan(m) != np.isnan(mg[i, j])
            n_nan += 1
            continue
        worst = max(worst, abs(m - mg[i, j]) / max(1.0, abs(m)))
    check("map margins = NumPy roots at 20 random points", worst < 1e-9, "%.3g (%d without balance)" % (worst, n_nan))
    check("no balanced configuration (NaN) at the same points", nan_bad == 0)
    check("verdict = sign of the margin", np.all((vd == 1) == (mg < 0)))


if __name__ == "__main__":
    {"sweep": do_sweep, "map": do_map}[sys.argv[1]](sys.argv[2])
    sys.exit(1 if rc.failures else 0)
