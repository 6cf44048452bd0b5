"""Independent checks of `autobal rotor stability|sweep|map|campbell` archives
(run by tests/app/rotor_stability.sh).

Expected values are computed here with NumPy/SciPy from the formulas of docs/rotor.md, not taken
from autobal:
  - the balanced angles of two identical balls (3.14): psi = psi0 + pi -/+ arccos(m0 r0 / (2 m r));
  - the degree-12 characteristic polynomial built from the spec's D, N, F, Delta with NumPy
    complex polynomial arithmetic, its roots with numpy.roots;
  - Floquet multipliers for anisotropic supports from a Python linearization of (3.2) + (3.13)
    integrated with scipy.integrate.solve_ivp;
  - the rotor-housing modes from numpy.linalg.eigvals of the 8x8 first-order matrix of (3.2).
Usage: rotor_stability_check.py stability|sweep|map|campbell|floquet FILE.h5
"""
import sys

import h5py
import numpy as np
import numpy.polynomial.polynomial as P
import xarray as xr
from scipy.integrate import solve_ivp
from scipy.optimize import linear_sum_assignment

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures += 1


def load(f):
    r = f["rotor"].attrs
    L = {k: float(v) for k, v in f["rotor/lumped"].attrs.items() if not k.endswith("_units")}
    planes = []
    j = 1
    while "rotor/plane%d" % j in f:
        a = f["rotor/plane%d" % j].attrs
        planes.append(dict(d=float(a["d"]), m0=float(a["m0"]), r0=float(a["r0"]), psi0=float(a["psi0"]),
                           m=np.array(a["ball_mass"]), r=np.array(a["ball_radius"]),
                           h=np.array(a["ball_damping"])))
        j += 1
    return float(r["omega"]), L, planes, r["inertia"]


def match(a, b):
    """max |a_i - b_perm(i)| over the optimal assignment"""
    cost = np.abs(a[:, None] - b[None, :])
    i, j = linear_sum_assignment(cost)
    return cost[i, j].max()


def balanced_two(pl):
    m, r = pl["m"], pl["r"]
    assert len(m) == 2 and np.isclose(m[0] * r[0], m[1] * r[1])
    g = np.arccos(pl["m0"] * pl["r0"] / (2 * m[0] * r[0]))
    return np.array([pl["psi0"] + np.pi - g, pl["psi0"] + np.pi + g])


def delta(w, L, pl, psi):
    """spec: Delta = F F* - (|Q|/2)^2 P^4 Pb^4 N N* (one plane, ascending coefficients)"""
    d, mb = pl["d"], pl["m"].sum()
    kappa = pl["h"][0] / pl["m"][0]
    Q = np.sum(pl["m"] * np.exp(2j * psi))
    Pp = np.array([1j * w, 1.0])
    Pb = np.array([-1j * w, 1.0])
    P2 = P.polymul(Pp, Pp)
    P4 = P.polymul(P2, P2)
    Pb4 = P.polymul(P.polymul(Pb, Pb), P.polymul(Pb, Pb))
    K11 = P.polyadd(P.polyadd(L["M"] * P2, L["h_x"] * Pp), [L["c_x"]])
    K22 = P.polyadd(P.polyadd(L["A"] * P2, (L["h_alpha"] - 1j * L["C"] * w) * Pp), [L["c_alpha"]])
    hc = P.polyadd(L["h_xbeta"] * Pp, [L["c_xbeta"]])
    D = P.polysub(P.polymul(K11, K22), P.polymul(hc, hc))
    N = P.polyadd(P.polyadd(K22, 2 * d * hc), d * d * K11)
    F = P.polysub(P.polymul([0, kappa, 1], D), 0.5 * mb * P.polymul(P4, N))
    Delta = P.polysub(P.polymul(F, np.conj(F)),
                      (abs(Q) / 2) ** 2 * P.polymul(P.polymul(P4, Pb4), P.polymul(N, np.conj(N))))
    return Delta


def real_coefficients(c):
    """real part, after checking that the imaginary parts cancelled (relative 1e-12)"""
    c = np.asarray(c)
    if np.iscomplexobj(c):
        assert np.abs(c.imag).max() <= 1e-12 * np.abs(c).max(), "Delta is not real"
        c = c.real
    return c


def roots_of(c):
    c = real_coefficients(c)
    ws = abs(c[0] / c[-1]) ** (1.0 / (len(c) - 1))
    cs = c * ws ** np.arange(len(c))
    return np.roots(cs[::-1]) * ws


def check_common(f):
    check("Conventions", f.attrs.get("Conventions") == "CF-1.8 autobal-1")
    check("status complete", f.attrs.get("status") == "complete", str(f.attrs.get("status")))


def do_stability(fn):
    f = h5py.File(fn, "r")
    check_common(f)
    w, L, planes, inertia = load(f)
    g = f["rotor/stability"]
    pl = planes[0]
    psi = balanced_two(pl)
    got = np.array(g["psi_balanced"])
    check("balanced angles (3.14)", np.allclose(np.angle(np.exp(1j * (got - psi))), 0, atol=1e-12),
          "%s vs %s" % (got, psi))
    cc = delta(w, L, pl, psi)
    check("Delta real (imaginary parts cancel to 1e-12)", np.abs(cc.imag).max() <= 1e-12 * np.abs(cc).max(),
          "%.3g" % (np.abs(cc.imag).max() / np.abs(cc).max()))
    c = cc.real
    stored = np.array(g["char_poly"])
    rel = np.abs(stored - c) / np.abs(c).max()
    # coefficients of very different sizes: compare each to its own size where it is not tiny
    rel_each = np.abs(stored - c) / np.maximum(np.abs(c), 1e-12 * np.abs(c).max())
    check("Delta coefficients = NumPy from the spec's formulas", rel_each.max() < 1e-11,
          "max rel %.3g (rel to max %.3g)" % (rel_each.max(), rel.max()))
    lam = roots_of(c)
    sr = np.array(g["root_real"]) + 1j * np.array(g["root_imag"])
    scale = max(1.0, np.abs(lam).max())
    check("roots = numpy.roots of Delta", match(sr, lam) / scale < 1e-10, "%.3g" % (match(sr, lam) / scale))
    se = np.array(g["eig_real"]) + 1j * np.array(g["eig_imag"])
    check("closed-matrix eigenvalues = numpy roots", match(se, lam) / scale < 1e-10)
    sf = np.array(g["full_real"]) + 1j * np.array(g["full_imag"])
    check("full-model roots = numpy roots (n = 2)", match(sf, lam) / scale < 1e-10)
    mu = np.array(g["floquet_real"]) + 1j * np.array(g["floquet_imag"])
    T = 2 * np.pi / abs(w)
    check("Floquet multipliers = exp(lambda T)", match(mu, np.exp(lam * T)) < 1e-8,
          "%.3g" % match(mu, np.exp(lam * T)))
    mr = lam.real.max()
    check("margin = max Re(root)", abs(g.attrs["margin"] - mr) < 1e-9 * scale, "%.12g vs %.12g" % (g.attrs["margin"], mr))
    want = "stable" if mr < -1e-9 * scale else ("unstable" if mr > 1e-9 * scale else "marginal")
    check("verdict", g.attrs["verdict"] == want, "%s vs %s" % (g.attrs["verdict"], want))
    check("units", g["root_real"].attrs["units"] == "1/s" and g.attrs["margin_units"] == "1/s")
    if "rotor/stability/critical" in f:
        check_critical(f["rotor/stability/critical"], lambda x: roots_of(delta(x, L, pl, psi)).real.max())
    ds = xr.open_dataset(fn, engine="h5netcdf", group="rotor/stability")
    check("xarray: roots over 'root'", ds["root_real"].dims == ("root",))


def check_critical(g, margin):
    # the truncation flag is always written; these runs have few changes (capacity 64)
    check("attribute truncated present and 0 (%s critical values)" % g.attrs.get("n_critical"),
          "truncated" in g.attrs and int(g.attrs["truncated"]) == 0 and int(g.attrs["n_critical"]) < 64,
          str(g.attrs.get("truncated")))
    vals = np.array(g["critical_value"]) if "critical_value" in g else np.array([])
    kinds = np.array(g["critical_kind"]) if "critical_kind" in g else np.array([])
    check("some critical values", len(vals) >= 1, str(vals))
    for v, k in zip(vals, kinds):
        lo, hi = margin(v - 1e-7 * abs(v)), margin(v + 1e-7 * abs(v))
        check("margin changes sign across %.10g (kind %d)" % (v, k),
              (lo > 0) != (hi > 0) and (k == 1) == (hi < 0), "%.3g -> %.3g" % (lo, hi))
    if "stable_lo" in g:
        for a, b in zip(np.array(g["stable_lo"]), np.array(g["stable_hi"])):
            check("stable interval midpoint is stable", margin(0.5 * (a + b)) < 0, "[%.8g, %.8g]" % (a, b))


def do_sweep(fn):
    f = h5py.File(fn, "r")
    check_common(f)
    w, L, planes, inertia = load(f)
    pl = planes[0]
    psi = balanced_two(pl)
    ds = xr.open_dataset(fn, engine="h5netcdf", group="rotor/sweep")
    check("xarray: margin over omega in rad/s", ds["margin"].dims == ("omega",) and ds["omega"].attrs["units"] == "rad/s")
    om = ds["omega"].values
    mg = ds["margin"].values
    vd = ds["verdict"].values
    worst = 0.0
    for k in range(0, len(om), 37):
        lam = roots_of(delta(om[k], L, pl, psi))
        worst = max(worst, abs(lam.real.max() - mg[k]) / max(1, np.abs(lam).max()))
    check("sweep margins = NumPy roots at sampled speeds", worst < 1e-10, "%.3g" % worst)
    check("verdict = sign of the margin", np.all((vd == 1) == (mg < 0)))
    check_critical(f["rotor/sweep"], lambda x: roots_of(delta(x, L, pl, psi)).real.max())


def do_map(fn):
    f = h5py.File(fn, "r")
    check_common(f)
    w, L, planes, inertia = load(f)
    pl = dict(planes[0])
    ds = xr.open_dataset(fn, engine="h5netcdf", group="rotor/map")
    check("xarray: margin over (omega, ball_damping)", ds["margin"].dims == ("omega", "ball_damping"))
    om, hh = ds["omega"].values, ds["ball_damping"].values
    mg = ds["margin"].values
    rng = np.random.default_rng(1)
    psi = balanced_two(pl)
    worst = 0.0
    for _ in range(25):
        i, j = rng.integers(len(om)), rng.integers(len(hh))
        pl["h"] = np.full(len(pl["m"]), hh[j])
        lam = roots_of(delta(om[i], L, pl, psi))
        worst = max(worst, abs(lam.real.max() - mg[i, j]) / max(1, np.abs(lam).max()))
    check("map margins = NumPy roots at random grid points", worst < 1e-10, "%.3g" % worst)


def rotor_matrices(L, w):
    M = np.diag([L["M"], L["M"], L["A"], L["A"]])
    H = np.array([[L["h_x"], 0, 0, -L["h_xbeta"]], [0, L["h_y"], L["h_yalpha"], 0],
                  [0, L["h_yalpha"], L["h_alpha"], L["C"] * w], [-L["h_xbeta"], 0, -L["C"] * w, L["h_beta"]]])
    K = np.array([[L["c_x"], 0, 0, -L["c_xbeta"]], [0, L["c_y"], L["c_yalpha"], 0],
                  [0, L["c_yalpha"], L["c_alpha"], 0], [-L["c_xbeta"], 0, 0, L["c_beta"]]])
    return M, H, K


def do_campbell(fn):
    f = h5py.File(fn, "r")
    check_common(f)
    w, L, planes, inertia = load(f)
    gc = f["rotor/campbell"]
    check("campbell: attribute truncated present and 0 (%s crossings, %s peaks)" % (gc.attrs.get("n_crossing"), gc.attrs.get("n_peak")),
          "truncated" in gc.attrs and int(gc.attrs["truncated"]) == 0, str(gc.attrs.get("truncated")))
    ds = xr.open_dataset(fn, engine="h5netcdf", group="rotor/campbell")
    check("xarray: frequency over (omega, mode)", ds["frequency"].dims == ("omega", "mode"))
    # (c - M nu^2)(c_t - A nu^2) = c_c^2 at rest, undamped (x-beta block)
    a, b, c = L["M"] * L["A"], -(L["c_x"] * L["A"] + L["c_beta"] * L["M"]), L["c_x"] * L["c_beta"] - L["c_xbeta"] ** 2
    nu = np.sqrt(np.sort(np.roots([a, b, c])))
    fu = ds["natural_frequency_undamped"].values
    check("undamped natural frequencies at rest (closed form)", np.allclose(np.sort(fu)[::2], nu, rtol=1e-12),
          "%s vs %s" % (fu, nu))
    om = ds["omega"].values
    fr = ds["frequency"].values
    worst = 0.0
    for k in range(0, len(om), 17):
        M, H, K = rotor_matrices(L, om[k])
        A = np.block([[np.zeros((4, 4)), np.eye(4)], [-np.linalg.solve(M, K), -np.linalg.solve(M, H)]])
        ev = np.linalg.eigvals(A)
        want = np.sort(np.sort(ev.imag)[-4:])
        worst = max(worst, np.abs(fr[k] - want).max() / want.max())
    check("Campbell frequencies = numpy eigvals", worst < 1e-10, "%.3g" % worst)
    if "crossing_omega" in ds:
        for x, m in zip(ds["crossing_omega"].values, ds["crossing_mode"].values):
            M, H, K = rotor_matrices(L, x)
            A = np.block([[np.zeros((4, 4)), np.eye(4)], [-np.linalg.solve(M, K), -np.linalg.solve(M, H)]])
            want = np.sort(np.sort(np.linalg.eigvals(A).imag)[-4:])[m]
            check("natural frequency = omega at %.8g" % x, abs(want - x) < 1e-8 * x)
    # unbalance response of the isotropic rotor: forward circular orbit |Z0|
    pl = planes[0]
    s0 = pl["m0"] * pl["r0"]
    for k in (len(om) // 7, len(om) // 3):
        x = om[k]
        s = 1j * x
        k11 = L["M"] * s * s + L["h_x"] * s + L["c_x"]
        k22 = L["A"] * s * s + (L["h_alpha"] - 1j * L["C"] * x) * s + L["c_alpha"]
        k12 = -(L["h_xbeta"] * s + L["c_xbeta"])
        Z0 = x * x * s0 * (k22 - pl["d"] * k12) / (k11 * k22 - k12 * k12)
        check("unbalance response at %.6g rad/s" % x, abs(ds["amp_G"].values[k] - abs(Z0)) < 1e-10 * abs(Z0))


def linearization(t, w, L, planes, psis):
    """M(t) X'' + C(t) X' + K(t) X = 0 of (3.2) + (3.13) about the balanced motion (PAPER inertia)"""
    N = sum(len(p["m"]) for p in planes)
    n = 4 + N
    M3, H, K = rotor_matrices(L, w)
    Mt = np.zeros((n, n)); Ct = np.zeros((n, n)); Kt = np.zeros((n, n))
    Mt[:4, :4] = M3; Ct[:4, :4] = H; Kt[:4, :4] = K
    b = 4
    for pl, psi in zip(planes, psis):
        d = pl["d"]
        eu = np.array([1, 0, 0, d]); ev = np.array([0, 1, -d, 0])
        for m, r, h, ps in zip(pl["m"], pl["r"], pl["h"], psi):
            ph = w * t + ps
            cc = 1j * m * r * np.exp(1j * ph)  # d(s_u + i s_v) / d psi
            for coef, mat in ((cc, Mt), (2j * w * cc, Ct), (-w * w * cc, Kt)):
                mat[:4, b] += eu * coef.real + ev * coef.imag
            Mt[b, b] = 1.0
            Mt[b, :4] = -(np.sin(ph) * eu - np.cos(ph) * ev) / r
            Ct[b, b] = h / m
            b += 1
    Minv = np.linalg.inv(Mt)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ Kt, -Minv @ Ct]])
    return A  # state (X, X'): a permutation of autobal's order (same eigenvalues)


def floquet_margin_two(w, L, planes, phi, s=None, rtol=1e-11, atol=1e-13):
    """log max|mu| / T of the two-plane linearization with plane 2's unbalance at phase phi from plane 1's
    (and the planes' m0 r0 = s[j] when given): SciPy DOP853 over one period from the identity, scaled state"""
    pl = [dict(p) for p in planes]
    if s is not None:
        for j in range(2):
            pl[j]["m0"] = s[j] / pl[j]["r0"]
    pl[1]["psi0"] = pl[0]["psi0"] + phi
    psis = [balanced_two(p) for p in pl]
    n = 2 * (4 + sum(len(p["m"]) for p in pl))
    T = 2 * np.pi / abs(w)
    ell = 1e-3
    sc = np.array([ell, ell, ell / 0.1, ell / 0.1] + [1.0] * (n // 2 - 4))
    sc = np.concatenate([sc, sc * (abs(w) + 160.0)])

    def rhs(t, y):
        A = linearization(t, w, L, pl, psis)
        As = A * sc[None, :] / sc[:, None]
        return (As @ y.reshape(n, n)).ravel()

    sol = solve_ivp(rhs, (0, T), np.eye(n).ravel(), method="DOP853", rtol=rtol, atol=atol)
    mu = np.linalg.eigvals(sol.y[:, -1].reshape(n, n))
    return np.log(np.abs(mu).max()) / T


def do_floquet(fn):
    f = h5py.File(fn, "r")
    check_common(f)
    w, L, planes, inertia = load(f)
    g = f["rotor/stability"]
    psis = []
    off = 0
    allpsi = np.array(g["psi_balanced"])
    for pl in planes:
        psis.append(allpsi[off:off + len(pl["m"])])
        off += len(pl["m"])
    for pl, psi in zip(planes, psis):
        res = pl["m0"] * pl["r0"] * np.exp(1j * pl["psi0"]) + np.sum(pl["m"] * pl["r"] * np.exp(1j * psi))
        check("stored balanced angles balance the plane", abs(res) < 1e-12)
    n = 2 * (4 + sum(len(p["m"]) for p in planes))
    T = 2 * np.pi / abs(w)
    # constant diagonal scaling of the state (does not change the multipliers)
    ell = 1e-3
    sc = np.array([ell, ell, ell / 0.1, ell / 0.1] + [1.0] * (n // 2 - 4))
    sc = np.concatenate([sc, sc * (abs(w) + 160.0)])

    def rhs(t, y):
        A = linearization(t, w, L, planes, psis)
        As = A * sc[None, :] / sc[:, None]
        return (As @ y.reshape(n, n)).ravel()

    sol = solve_ivp(rhs, (0, T), np.eye(n).ravel(), method="DOP853", rtol=1e-11, atol=1e-13)
    mu = np.linalg.eigvals(sol.y[:, -1].reshape(n, n))
    stored = np.array(g["floquet_real"]) + 1j * np.array(g["floquet_imag"])
    check("Floquet multipliers = SciPy integration of a Python linearization", match(stored, mu) < 1e-7,
          "%.3g" % match(stored, mu))
    marg = np.log(np.abs(mu).max()) / T
    check("Floquet margin log(max|mu|)/T", abs(g.attrs["margin"] - marg) < 1e-6, "%.10g vs %.10g" % (g.attrs["margin"], marg))
    check("method floquet", g.attrs["method"] == "floquet")


if __name__ == "__main__":
    mode, fn = sys.argv[1], sys.argv[2]
    {"stability": do_stability, "sweep": do_sweep, "map": do_map, "campbell": do_campbell,
     "floquet": do_floquet}[mode](fn)
    sys.exit(1 if failures else 0)
