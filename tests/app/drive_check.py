#!/usr/bin/python3
"""Checks of `autobal rotor transient` with a prescribed spin speed ([drive], tests/app/drive.sh).

  same A.h5 B.h5             every dataset of A is in B with the same bytes, and B has no others
  frames FIXED.h5 ROT.h5     fixed-frame and rotating-frame runs of one drive agree (integration tolerance)
  scipy A.h5                 an independent SciPy integration (solve_ivp DOP853) of the prescribed-speed
                             equations, written here from the spec's fixed-frame equations (3.2), (3.4)
                             with Omega(t) (a full (4+n) x (4+n) mass-matrix solve, phi_0 integrated as
                             one more state, Omega(t) by numpy.interp of the drive attributes) agrees
                             with the archive's samples
  balanced A.h5              the run ends balanced: |s|/(m0 r0) < 1e-6 and the balls at the spec's
                             balanced angles pi -/+ arccos(m0 r0 / (2 m r)) (3.14)
  attrs A.h5 MODE            the drive's attributes and units, and the Omega column (rad/s)
"""
import math
import sys

import h5py
import numpy as np
from scipy.integrate import solve_ivp

# the spec's default example (SI): only the ball damping is taken from the archive
HW = dict(M_k=6.0, A_k=0.12, m_p=4.0, A_p=0.04, C_p=0.03, l_L=0.20, l_R=0.15,
          c_Lx=1.0e5, c_Ly=1.0e5, c_Rx=1.5e5, c_Ry=1.5e5, h_Lx=100.0, h_Ly=100.0, h_Rx=150.0, h_Ry=150.0)
D_PLANE, M0, R0, PSI0 = 0.10, 0.02, 0.1, 0.0
MB, RB, PSI_INIT = np.array([0.05, 0.05]), np.array([0.1, 0.1]), np.array([1.0, 2.5])


def fail(msg):
    print("FAIL " + msg)
    sys.exit(1)


def datasets(f):
    out = {}
    def walk(g):
        for v in g.values():
            if isinstance(v, h5py.Dataset):
                out[v.name] = v
            else:
                walk(v)
    walk(f)
    return out


def cmd_same(a, b):
    A, B = datasets(h5py.File(a, "r")), datasets(h5py.File(b, "r"))
    bad = [k for k in A if k not in B or A[k].dtype != B[k].dtype or A[k].shape != B[k].shape
           or A[k][()].tobytes() != B[k][()].tobytes()]
    extra = [k for k in B if k not in A]
    print(f"     {len(A)} datasets compared byte for byte; differ: {bad[:5]}; only in B: {extra[:5]}")
    if bad or extra:
        fail("archives differ")


def drive_of(g):
    """Omega(t) of the archive's drive attributes (numpy.interp holds the end values outside)."""
    mode = g.attrs["drive_mode"]
    mode = mode.decode() if isinstance(mode, bytes) else str(mode)
    if mode == "ramp":
        tt = np.array([g.attrs["drive_t_a"], g.attrs["drive_t_b"]], float)
        ww = np.array([g.attrs["drive_omega_a"], g.attrs["drive_omega_b"]], float)
    else:
        tt, ww = np.asarray(g.attrs["drive_table_t"], float), np.asarray(g.attrs["drive_table_omega"], float)
    def W(t):
        return float(np.interp(t, tt, ww))
    def Wd(t):
        # slope of the piece containing t (right derivative; 0 outside)
        k = np.searchsorted(tt, t, side="right") - 1
        if k < 0 or k >= len(tt) - 1:
            return 0.0
        return (ww[k + 1] - ww[k]) / (tt[k + 1] - tt[k])
    return W, Wd, tt


def rhs_factory(W, Wd, hb):
    M, A, C = HW["M_k"] + HW["m_p"], HW["A_k"] + HW["A_p"], HW["C_p"]
    lL, lR = HW["l_L"], HW["l_R"]
    def L(k):
        Lx, Ly, Rx, Ry = HW[k + "_Lx"], HW[k + "_Ly"], HW[k + "_Rx"], HW[k + "_Ry"]
        return (Lx + Rx, Ly + Ry, Ly * lL**2 + Ry * lR**2, Lx * lL**2 + Rx * lR**2, Lx * lL - Rx * lR,
                Ly * lL - Ry * lR)
    cx, cy, cal, cbe, cxb, cya = L("c")
    hx, hy, hal, hbe, hxb, hya = L("h")
    d, n = D_PLANE, len(MB)

    def rhs(t, s):
        x, y, al, be, xd, yd, ald, bed = s[:8]
        phi, phid, ph0 = s[8:8 + n], s[8 + n:8 + 2 * n], s[8 + 2 * n]
        w, wd = W(t), Wd(t)
        p0 = ph0 + PSI0
        # unknowns z = (x'', y'', al'', be'', phi_1'' .. phi_n''): K z = rhs
        K = np.zeros((4 + n, 4 + n))
        b = np.zeros(4 + n)
        K[0, 0] = K[1, 1] = M
        K[2, 2] = K[3, 3] = A
        # known parts of s_u'', s_v'' (centripetal of balls and unbalance, tangential Omega' of the unbalance)
        su = -np.sum(MB * RB * phid**2 * np.cos(phi)) - M0 * R0 * (w * w * math.cos(p0) + wd * math.sin(p0))
        sv = -np.sum(MB * RB * phid**2 * np.sin(phi)) - M0 * R0 * (w * w * math.sin(p0) - wd * math.cos(p0))
        b[0] = -(hx * xd + cx * x - hxb * bed - cxb * be) - su
        b[1] = -(hy * yd + cy * y + hya * ald + cya * al) - sv
        # gyroscopic d/dt(C Omega beta) = C Omega beta' + C Omega' beta (spin energy 1/2 C (Omega + alpha' beta)^2)
        b[2] = -(hal * ald + cal * al + C * w * bed + C * wd * be + hya * yd + cya * y) + d * sv
        b[3] = -(hbe * bed + cbe * be - C * w * ald - hxb * xd - cxb * x) - d * su
        for i in range(n):
            mr, sn, cs = MB[i] * RB[i], math.sin(phi[i]), math.cos(phi[i])
            # s_u'' has -m r phi'' sin, s_v'' has +m r phi'' cos
            K[0, 4 + i] = -mr * sn
            K[1, 4 + i] = mr * cs
            K[2, 4 + i] = -d * mr * cs
            K[3, 4 + i] = -d * mr * sn
            # (3.4) with Omega(t)
            K[4 + i, 4 + i] = mr * RB[i]
            K[4 + i, 0] = -mr * sn
            K[4 + i, 3] = -mr * d * sn
            K[4 + i, 1] = mr * cs
            K[4 + i, 2] = -mr * d * cs
            b[4 + i] = -hb[i] * RB[i]**2 * (phid[i] - w)
        z = np.linalg.solve(K, b)
        return np.concatenate(([xd, yd, ald, bed], z[:4], phid, z[4:], [w]))
    return rhs


def cmd_scipy(path):
    f = h5py.File(path, "r")
    g = f["/rotor/transient"]
    fr = g.attrs["frame"]
    fr = fr.decode() if isinstance(fr, bytes) else str(fr)
    if fr != "fixed":
        fail("scipy check expects a fixed-frame archive")
    hb = np.asarray(f["/rotor/plane1"].attrs["ball_damping"], float)
    W, Wd, tt = drive_of(g)
    t = g["time"][:]
    n = len(MB)
    s0 = np.concatenate((np.zeros(8), PSI_INIT, np.full(n, W(0.0)), [0.0]))
    # DOP853 with the corners of the drive as step boundaries (integrate piece by piece)
    edges = [0.0] + [c for c in tt if 0.0 < c < t[-1]] + [t[-1]]
    rhs = rhs_factory(W, Wd, hb)
    sols, state = [], s0
    for a, b in zip(edges[:-1], edges[1:]):
        sol = solve_ivp(rhs, (a, b), state, method="DOP853", rtol=1e-11, atol=1e-14, dense_output=True)
        if not sol.success:
            fail("solve_ivp: " + sol.message)
        sols.append((a, b, sol))
        state = sol.y[:, -1]
    def at(tq):
        for a, b, sol in sols:
            if tq <= b:
                return sol.sol(tq)
        return sols[-1][2].sol(tq)
    ref = np.array([at(tq) for tq in t]).T
    xs = {k: g[k][:] for k in ("x", "y", "alpha", "beta", "state_phi_1", "state_phi_2", "Omega")}
    amp = max(np.max(np.abs(ref[0])), np.max(np.abs(ref[1])))
    tilt = max(np.max(np.abs(ref[2])), np.max(np.abs(ref[3])))
    ex = max(np.max(np.abs(xs["x"] - ref[0])), np.max(np.abs(xs["y"] - ref[1]))) / amp
    ea = max(np.max(np.abs(xs["alpha"] - ref[2])), np.max(np.abs(xs["beta"] - ref[3]))) / tilt
    eb = max(np.max(np.abs(xs["state_phi_1"] - ref[8])), np.max(np.abs(xs["state_phi_2"] - ref[9])))
    ew = np.max(np.abs(xs["Omega"] - np.array([W(tq) for tq in t])))
    ep = abs(ref[12][-1] - np.trapz(np.array([W(tq) for tq in np.linspace(0, t[-1], 200001)]),
                                    np.linspace(0, t[-1], 200001)))
    print(f"     {len(t)} samples to t = {t[-1]:.4g} s; |x|,|y| up to {amp:.3g} m, |alpha|,|beta| up to {tilt:.3g} rad")
    print(f"     max |x - x_scipy| / max|x| = {ex:.3g}, tilts {ea:.3g}, ball angles {eb:.3g} rad, Omega column {ew:.3g} rad/s, "
          f"phi_0(t_end) vs trapezoid {ep:.3g} rad")
    # tolerances: both solvers at rtol ~1e-10..1e-11 over ~1e3..1e4 steps; the archive's default
    # atol 1e-9 (absolute, on m and rad) bounds the rotor coordinates
    if not (ex < 1e-5 and ea < 1e-5 and eb < 1e-6 and ew < 1e-9 and ep < 1e-6):
        fail("autobal and SciPy disagree")


def cmd_frames(pf, pr):
    a, b = h5py.File(pf, "r")["/rotor/transient"], h5py.File(pr, "r")["/rotor/transient"]
    ta, tb = a["time"][:], b["time"][:]
    if len(ta) != len(tb) or np.max(np.abs(ta - tb)) > 1e-12 * ta[-1]:
        fail("sample times differ")
    amp = np.max(np.abs(a["x"][:]))
    eq = max(np.max(np.abs(a[k][:] - b[k][:])) for k in ("x", "y")) / amp
    ep = max(np.max(np.abs(a[f"p1_b{i}_psi"][:] - b[f"p1_b{i}_psi"][:])) for i in (1, 2))
    eo = np.max(np.abs(a["Omega"][:] - b["Omega"][:]))
    print(f"     fixed vs rotating frame: max |dx|/max|x| = {eq:.3g} (max|x| {amp:.3g} m), ball psi {ep:.3g} rad, Omega {eo:.3g}")
    if not (eq < 1e-6 and ep < 1e-6 and eo == 0.0):
        fail("frames disagree")


def cmd_balanced(path):
    f = h5py.File(path, "r")
    g = f["/rotor/transient"]
    srel = g["p1_s_rel"][-1]
    psi = np.sort([g["p1_b1_psi_w"][-1], g["p1_b2_psi_w"][-1]])
    want = np.sort([math.remainder(math.pi - math.acos(M0 * R0 / (2 * 0.05 * 0.1)), 2 * math.pi),
                    math.remainder(math.pi + math.acos(M0 * R0 / (2 * 0.05 * 0.1)), 2 * math.pi)])
    om = g["Omega"][-1]
    print(f"     at the end: Omega = {om:.6g} rad/s, |s|/(m0 r0) = {srel:.3g}, psi = {psi}, spec (3.14) {want}")
    if not (srel < 1e-6 and np.max(np.abs(psi - want)) < 1e-5 and om == 500.0):
        fail("not balanced at the end")


def cmd_attrs(path, mode):
    f = h5py.File(path, "r")
    g = f["/rotor/transient"]
    got = g.attrs["drive_mode"]
    got = got.decode() if isinstance(got, bytes) else str(got)
    keys = {"ramp": ["drive_omega_a", "drive_omega_b", "drive_t_a", "drive_t_b"],
            "table": ["drive_table_t", "drive_table_omega"]}[mode]
    units = [g.attrs.get(k + "_units", g.attrs.get("units")) for k in keys]
    ou = g["Omega"].attrs.get("units")
    ou = ou.decode() if isinstance(ou, bytes) else ou
    print(f"     drive_mode = {got}; {dict(zip(keys, [np.asarray(g.attrs[k]).tolist() for k in keys]))}; units {units}; Omega column in {ou}")
    want_units = ["rad/s" if "omega" in k else "s" for k in keys]
    units = [u.decode() if isinstance(u, bytes) else u for u in units]
    if got != mode or units != want_units or ou != "rad/s":
        fail("drive attributes")


if __name__ == "__main__":
    c = sys.argv[1]
    {"same": cmd_same, "frames": cmd_frames, "scipy": cmd_scipy, "balanced": cmd_balanced,
     "attrs": cmd_attrs}[c](*sys.argv[2:])
