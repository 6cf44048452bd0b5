"""Independent checks of `autobal rotor transient` archives (run by tests/app/rotor.sh).

Expected values come from the formulas of docs/rotor.md evaluated here, not from autobal:
the lumped coefficients (2.7)-(2.11) from the hardware attributes, the balanced angles
(3.14) of two identical balls, the unbalance sums (3.1)/(3.10) from the stored ball angles.
Usage: rotor_check.py balanced|heavy|partial FILE.h5
"""
import sys

import h5py
import numpy as np
import xarray as xr

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures += 1


def common(f, status="complete"):
    check("Conventions", f.attrs.get("Conventions") == "CF-1.8 autobal-1")
    check("status " + status, f.attrs.get("status") == status, str(f.attrs.get("status")))
    r = f["rotor"].attrs
    lu = f["rotor/lumped"].attrs
    if r["input"] == "hardware":
        cx = r["c_Lx"] + r["c_Rx"]
        ca = r["c_Ly"] * r["l_L"] ** 2 + r["c_Ry"] * r["l_R"] ** 2
        cxb = r["c_Lx"] * r["l_L"] - r["c_Rx"] * r["l_R"]
        hxb = r["h_Lx"] * r["l_L"] - r["h_Rx"] * r["l_R"]
        check("lumped c_x = c_Lx + c_Rx (2.9)", np.isclose(lu["c_x"], cx, rtol=1e-15))
        check("lumped c_alpha (2.9)", np.isclose(lu["c_alpha"], ca, rtol=1e-14))
        check("lumped c_xbeta (2.9)", np.isclose(lu["c_xbeta"], cxb, rtol=1e-14))
        check("lumped h_xbeta (2.11)", np.isclose(lu["h_xbeta"], hxb, rtol=1e-14))
        check("lumped M = M_k + m_p (2.7)", np.isclose(lu["M"], r["M_k"] + r["m_p"], rtol=1e-15))
        check("units of c_alpha", lu["c_alpha_units"] == "N m")
    ds = xr.open_dataset(f.filename, engine="h5netcdf", group="rotor/transient")
    check("xarray: time series over 'time' in s", ds["x"].dims == ("time",) and ds["time"].attrs["units"] == "s")
    check("xarray: every variable has units", all("units" in ds[v].attrs for v in ds.variables))
    return ds


def unbalance_check(f, ds):
    """s_xi, s_eta recomputed from the stored relative ball angles by (3.10)."""
    p = f["rotor/plane1"].attrs
    m, r = p["ball_mass"], p["ball_radius"]
    nb = len(m)
    sxi = p["m0"] * p["r0"] * np.cos(p["psi0"]) + sum(m[i] * r[i] * np.cos(ds["p1_b%d_psi" % (i + 1)].values) for i in range(nb))
    seta = p["m0"] * p["r0"] * np.sin(p["psi0"]) + sum(m[i] * r[i] * np.sin(ds["p1_b%d_psi" % (i + 1)].values) for i in range(nb))
    d = max(np.max(abs(sxi - ds["p1_s_xi"].values)), np.max(abs(seta - ds["p1_s_eta"].values)))
    check("s_xi, s_eta agree with (3.10) from the ball angles", d < 1e-12, "%.2e kg m" % d)
    t = ds["time"].values
    w = float(f["rotor"].attrs["omega"])
    su = sxi * np.cos(w * t) - seta * np.sin(w * t)
    d = np.max(abs(su - ds["p1_s_u"].values))
    check("s_u = s_xi cos wt - s_eta sin wt (3.11)", d < 1e-9, "%.2e kg m" % d)


def do_balanced(path):
    with h5py.File(path, "r") as f:
        ds = common(f)
        unbalance_check(f, ds)
        p = f["rotor/plane1"].attrs
        tr = f["rotor/transient"].attrs
        m, r = p["ball_mass"], p["ball_radius"]
        check("two identical balls", len(m) == 2 and m[0] == m[1] and r[0] == r[1])
        c = np.arccos(p["m0"] * p["r0"] / (2 * m[0] * r[0]))
        want = sorted([np.pi - c, np.pi + c])  # modulo 2 pi, in [0, 2 pi)
        got = sorted(np.mod([ds["p1_b1_psi"].values[-1], ds["p1_b2_psi"].values[-1]], 2 * np.pi))
        err = max(abs(np.array(got) - np.array(want)))
        check("balls at pi -/+ arccos(m0 r0/(2 m r)) (3.14)", err < 1e-4, "got %s want %s" % (got, want))
        check("balanced flag and time to balance", int(tr["balanced"]) == 1 and 0 < tr["time_to_balance"] < ds["time"].values[-1])
        check("residual unbalance small at the end", ds["p1_s_rel"].values[-1] < 1e-3, "%.3e" % ds["p1_s_rel"].values[-1])
        # the amplitude drops once balanced: compare last tenth with the unbalanced start
        a = ds["amp_G"].values
        n = len(a)
        check("vibration reduced by > 100x", a[-n // 10:].max() < a[: n // 10].max() / 100)
        rv = xr.open_dataset(path, engine="h5netcdf", group="rotor/revolutions")
        check("per-revolution maxima over 'revolution_end'", rv["max_amp_G"].dims == ("revolution_end",) and len(rv["max_amp_G"]) > 10)


def do_heavy(path):
    """Below the first resonance the balls move to the heavy side: |s| grows above m0 r0."""
    with h5py.File(path, "r") as f:
        ds = common(f)
        unbalance_check(f, ds)
        tr = f["rotor/transient"].attrs
        p = f["rotor/plane1"].attrs
        check("not balanced below resonance", int(tr["balanced"]) == 0)
        s_abs = ds["p1_s_abs"].values
        check("residual unbalance ends above the unbalance alone", s_abs[-1] > p["m0"] * p["r0"] * 1.5,
              "%.4g vs m0 r0 = %.4g" % (s_abs[-1], p["m0"] * p["r0"]))
        # heavy side: the balls gather on the side to which the balancer plane is displaced,
        # i.e. at the rotor-frame angle of D = (x + d beta, y - d alpha) (it lags the unbalance
        # because of the support damping)
        x, y = ds["x"].values[-1], ds["y"].values[-1]
        al, be = ds["alpha"].values[-1], ds["beta"].values[-1]
        t = ds["time"].values[-1]
        w = float(f["rotor"].attrs["omega"])
        d = p["d"]
        ang_D = np.arctan2(y - d * al, x + d * be) - w * t
        for i in range(len(p["ball_mass"])):
            diff = np.angle(np.exp(1j * (ds["p1_b%d_psi" % (i + 1)].values[-1] - ang_D)))
            check("ball %d on the displaced (heavy) side of D" % (i + 1), abs(diff) < 0.05, "%.4f rad from D's direction" % diff)


def do_partial(path):
    with h5py.File(path, "r") as f:
        check("status incomplete", f.attrs.get("status") == "incomplete", str(f.attrs.get("status")))
        check("status_reason given", len(f.attrs.get("status_reason", "")) > 0, str(f.attrs.get("status_reason")))
        n = f["rotor/transient/time"].shape[0]
        check("samples computed before the stop are kept", n > 1, "%d samples" % n)
        t = f["rotor/transient/time"][()]
        check("time strictly increasing", np.all(np.diff(t) > 0))


def main():
    {"balanced": do_balanced, "heavy": do_heavy, "partial": do_partial}[sys.argv[1]](sys.argv[2])
    print("%s: %d failed" % (sys.argv[1], failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
