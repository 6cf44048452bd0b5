"""Independent checks of `autobal rotor transient` archives (run by tests/app/rotor.sh).

Expected values come from the formulas of docs/rotor.md evaluated here, not from autobal:
the lumped coefficients (2.7)-(2.11) from the hardware attributes, the balanced angles
(3.14) of two identical balls, the unbalance sums (3.1)/(3.10) from the stored ball angles.
Usage: rotor_check.py balanced|heavy|partial FILE.h5
       rotor_check.py same A.h5 B.h5            every dataset and every non-provenance attribute
                                                equal bit for bit
       rotor_check.py accuracy TIGHT.h5 DEFAULT.h5 OLD.h5
                                                |s| at 600 revolutions of the default example:
                                                DEFAULT within 1e-4 (relative) of TIGHT and of an
                                                independent SciPy DOP853 run, OLD (the former
                                                default tolerances) not
"""
import math
import os
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


# root attributes that say when, how and from which text a run was made, not what it computed
PROVENANCE = {"created", "command_line", "history", "input_config", "effective_config"}


def deref(f, v):
    """An attribute holding object references (dimension scales), with each reference replaced by
    the name of the object it points to."""
    if isinstance(v, h5py.Reference):
        return f[v].name
    if isinstance(v, (np.ndarray, list, tuple, np.void)):
        return [deref(f, x) for x in v]
    return v.item() if isinstance(v, np.generic) else v


def do_same(a_path, b_path):
    """Two archives of the same computation: same groups, datasets (dtype, shape, every bit of
    the values) and attributes, except the provenance attributes of the root and the solver's
    wall time."""
    with h5py.File(a_path, "r") as a, h5py.File(b_path, "r") as b:
        def items(f):
            out = {}
            f.visititems(lambda n, o: out.__setitem__(n, o))
            return out
        ia, ib = items(a), items(b)
        check("same groups and datasets", sorted(ia) == sorted(ib), str(sorted(set(ia) ^ set(ib))))
        nd = nbad = 0
        for name in sorted(set(ia) & set(ib)):
            oa, ob = ia[name], ib[name]
            if isinstance(oa, h5py.Dataset):
                nd += 1
                va, vb = oa[()], ob[()]
                same = (oa.dtype == ob.dtype and oa.shape == ob.shape
                        and np.asarray(va).tobytes() == np.asarray(vb).tobytes())
                if not same:
                    nbad += 1
                    check("dataset %s bit for bit" % name, False)
        check("%d datasets equal bit for bit" % nd, nd > 0 and nbad == 0, "%d differ" % nbad)
        na = nbad = 0
        for name, oa, ob in [("/", a, b)] + [(n, ia[n], ib[n]) for n in sorted(set(ia) & set(ib))]:
            skip = PROVENANCE if name == "/" else ({"wall_time"} if name.endswith("solver") else set())
            ka, kb = set(oa.attrs) - skip, set(ob.attrs) - skip
            if ka != kb:
                nbad += 1
                check("attribute names of %s" % name, False, str(sorted(ka ^ kb)))
            for k in sorted(ka & kb):
                na += 1
                va, vb = oa.attrs[k], ob.attrs[k]
                if isinstance(va, (str, bytes)) or isinstance(vb, (str, bytes)):
                    same = va == vb
                elif k in ("DIMENSION_LIST", "REFERENCE_LIST"):  # dimension scales: compare the targets
                    same = deref(a, va) == deref(b, vb)
                else:
                    same = np.asarray(va).dtype == np.asarray(vb).dtype and np.asarray(va).tobytes() == np.asarray(vb).tobytes()
                if not same:
                    nbad += 1
                    check("attribute %s:%s" % (name, k), False, "%r vs %r" % (va, vb))
        check("%d attributes equal (provenance and wall time left out)" % na, na > 0 and nbad == 0, "%d differ" % nbad)


def s_at_revs(path, revs):
    """|s| (p1_s_abs, kg m) of an archive at the output sample t = revs 2 pi / omega."""
    with h5py.File(path, "r") as f:
        g = f["rotor/transient"]
        t = g["time"][()]
        t1 = revs * 2 * math.pi / float(f["rotor"].attrs["omega"])
        i = int(np.argmin(abs(t - t1)))
        if not abs(t[i] - t1) <= 1e-12 * t1:
            check("%s has a sample at %g revolutions" % (path, revs), False, "nearest t = %.17g s, want %.17g s" % (t[i], t1))
            return math.nan, dict(g.attrs)
        return float(g["p1_s_abs"][i]), dict(g.attrs)


def scipy_s_at(path, t1):
    """|s| at t1 of the default example by SciPy's DOP853 on the right-hand side of
    bench/rotor_scipy.py (written from the spec's (3.2)-(3.4), independently of the C code), with
    the ball angles integrated relative to the rotor (psi = phi - omega t) so that the tolerance
    bounds them rather than omega t.  The archive's parameters must be that bench's."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench"))
    import rotor_scipy as R
    from scipy.integrate import solve_ivp
    n = 2
    with h5py.File(path, "r") as f:
        r, p, tr = f["rotor"].attrs, f["rotor/plane1"].attrs, f["rotor/transient"].attrs
        m, rad, h, psi = R.balls(n)
        same = (all(float(r[k]) == v for k, v in R.HW.items()) and float(r["omega"]) == R.OMEGA
                and r["inertia"] == "paper" and int(r["axial"]) == 0 and "plane2" not in f["rotor"]
                and all(float(p[k]) == v for k, v in R.PLANE.items())
                and np.array_equal(p["ball_mass"], m) and np.array_equal(p["ball_radius"], rad)
                and np.array_equal(p["ball_damping"], h) and np.array_equal(p["ball_psi_initial"], psi)
                and not np.any(p["ball_rate_initial"]) and not np.any(tr["initial_q"])
                and not np.any(tr["initial_q_rate"]))
    check("the archive's rotor is bench/rotor_scipy.py's (the spec's default example)", same)
    w = R.OMEGA
    fixed = R.make_rhs_plain(n)

    def rhs(t, z):  # z = (q, q', psi, psi'), psi = phi - omega t
        y = z.copy()
        y[8:8 + n] += w * t
        y[8 + n:] += w
        d = fixed(t, y)
        for k in range(8, 8 + n):
            d[k] -= w
        return d

    z0 = R.initial_state(n)
    z0[8:8 + n] = psi
    z0[8 + n:] = 0.0
    sol = solve_ivp(rhs, (0.0, t1), z0, method="DOP853", rtol=1e-12, atol=1e-15)
    check("SciPy DOP853 (rtol 1e-12, atol 1e-15) reached %.6g s" % t1, sol.success and sol.t[-1] == t1, sol.message)
    ps = sol.y[8:8 + n, -1]
    s = complex(R.PLANE["m0"] * R.PLANE["r0"] * math.cos(R.PLANE["psi0"]),
                R.PLANE["m0"] * R.PLANE["r0"] * math.sin(R.PLANE["psi0"]))
    s += complex(np.sum(m * rad * np.cos(ps)), np.sum(m * rad * np.sin(ps)))  # (3.10)
    return abs(s), sol.nfev


def do_accuracy(tight, default, old, revs=600, bound=1e-4):
    """|s| at 600 revolutions sits near a zero of the slowly decaying oscillation of s (about 0.1
    of its envelope), so its relative error is a demanding measure of the ball-angle phase."""
    st, at = s_at_revs(tight, revs)
    sd, ad = s_at_revs(default, revs)
    so, ao = s_at_revs(old, revs)
    t1 = revs * 2 * math.pi / omega_of(default)
    sp, nfev = scipy_s_at(default, t1)
    e_ref = abs(st - sp) / sp
    check("the two references agree: autobal (%s frame, rtol %g, atol %g) vs SciPy: |s| = %.10e vs %.10e kg m"
          % (at["frame"], at["rtol"], at["atol"], st, sp), e_ref < 1e-6, "%.2e relative (bound 1e-6; SciPy %d rhs)" % (e_ref, nfev))
    for what, ref in (("the tight autobal run", st), ("SciPy", sp)):
        e = abs(sd - ref) / ref
        check("default (%s frame, rtol %g, atol %g) |s| at %d revs = %.10e kg m vs %s"
              % (ad["frame"], ad["rtol"], ad["atol"], revs, sd, what), e < bound, "%.2e relative (bound %g)" % (e, bound))
    e = abs(so - st) / st
    check("the bound can fail: rtol %g, atol %g gives |s| = %.10e kg m" % (ao["rtol"], ao["atol"], so), e > bound,
          "%.2e relative (bound %g)" % (e, bound))


def omega_of(path):
    with h5py.File(path, "r") as f:
        return float(f["rotor"].attrs["omega"])


def main():
    if sys.argv[1] == "same":
        do_same(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "accuracy":
        do_accuracy(*sys.argv[2:5])
    else:
        {"balanced": do_balanced, "heavy": do_heavy, "partial": do_partial}[sys.argv[1]](sys.argv[2])
    print("%s: %d failed" % (sys.argv[1], failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
