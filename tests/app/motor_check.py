#!/usr/bin/python3
"""Checks of `autobal rotor transient` with a motor drive ([drive] mode = motor, tests/app/motor.sh).

  scipy A.h5               an independent SciPy integration (solve_ivp DOP853) of the motor equations
                           as docs/device.md states them ("(b) Motor": the phi_0 equation with J, L(Omega),
                           k_r, the ball resistance on the rotor; the rotor equations with the unbalance's
                           tangential acceleration m0 r0 Omega' and C Omega' beta): a full
                           (5 + N) x (5 + N) mass-matrix solve per step (numpy.linalg.solve), every
                           parameter read from the archive (one or two planes, linear or tabulated
                           characteristic), the same initial state; agrees with the archive's samples
  frames FIXED.h5 ROT.h5   fixed-frame and rotating-frame runs of one motor agree (integration tolerance)
  attrs A.h5 linear|table  the motor's attributes and units, the state and output columns and units,
                           motor_torque = L(Omega) and motor_power = L(Omega) Omega computed here
  passes A.h5 W            the run ends above W rad/s (it passed the resonances)
"""
import math
import sys

import h5py
import numpy as np
from scipy.integrate import solve_ivp


def fail(msg):
    print("FAIL " + msg)
    sys.exit(1)


def s(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def params(f):
    r = f["/rotor"]
    if s(r.attrs["input"]) != "hardware" or s(r.attrs["inertia"]) != "paper" or int(r.attrs["axial"]) != 0:
        fail("the check expects hardware input, paper inertia, no axial motion")
    hw = {k: float(r.attrs[k]) for k in ("M_k", "A_k", "m_p", "A_p", "C_p", "l_L", "l_R", "c_Lx", "c_Ly", "c_Rx",
                                         "c_Ry", "h_Lx", "h_Ly", "h_Rx", "h_Ry")}
    planes = []
    j = 1
    while f"/rotor/plane{j}" in f:
        p = f[f"/rotor/plane{j}"].attrs
        nb = int(p["n_balls"])
        planes.append(dict(d=float(p["d"]), m0=float(p["m0"]), r0=float(p["r0"]), psi0=float(p["psi0"]),
                           m=np.asarray(p["ball_mass"], float).reshape(nb), r=np.asarray(p["ball_radius"], float).reshape(nb),
                           h=np.asarray(p["ball_damping"], float).reshape(nb),
                           psi=np.asarray(p["ball_psi_initial"], float).reshape(nb),
                           rate=np.asarray(p["ball_rate_initial"], float).reshape(nb)))
        j += 1
    g = f["/rotor/transient"]
    if s(g.attrs["drive_mode"]) != "motor":
        fail("not a motor run")
    mot = dict(J=float(g.attrs["drive_J"]), k_r=float(g.attrs["drive_k_r"]), w_start=float(g.attrs["drive_omega_start"]))
    if "drive_L_0" in g.attrs:
        L0, W0 = float(g.attrs["drive_L_0"]), float(g.attrs["drive_omega_0"])
        mot["L"] = lambda W: L0 * (1.0 - W / W0)
    else:
        tw, tl = np.asarray(g.attrs["drive_torque_omega"], float), np.asarray(g.attrs["drive_torque_L"], float)
        mot["L"] = lambda W: float(np.interp(W, tw, tl))  # constant outside, as the model documents
    return hw, planes, mot


def rhs_factory(hw, planes, mot):
    """The motor equations of docs/device.md, unknowns (x'', y'', alpha'', beta'', Omega', phi_1'' ..)."""
    M, A, C = hw["M_k"] + hw["m_p"], hw["A_k"] + hw["A_p"], hw["C_p"]
    lL, lR = hw["l_L"], hw["l_R"]

    def lump(k):
        Lx, Ly, Rx, Ry = hw[k + "_Lx"], hw[k + "_Ly"], hw[k + "_Rx"], hw[k + "_Ry"]
        return (Lx + Rx, Ly + Ry, Ly * lL**2 + Ry * lR**2, Lx * lL**2 + Rx * lR**2, Lx * lL - Rx * lR,
                Ly * lL - Ry * lR)
    cx, cy, cal, cbe, cxb, cya = lump("c")
    hx, hy, hal, hbe, hxb, hya = lump("h")
    balls = [(p, i) for p in planes for i in range(len(p["m"]))]
    n = len(balls)
    J, kr, L = mot["J"], mot["k_r"], mot["L"]
    Jeff = J + sum(p["m0"] * p["r0"]**2 for p in planes)

    def rhs(t, st):
        x, y, al, be, xd, yd, ald, bed = st[:8]
        phi, phid = st[8:8 + n], st[8 + n:8 + 2 * n]
        ph0, W = st[8 + 2 * n], st[9 + 2 * n]
        K = np.zeros((5 + n, 5 + n))
        b = np.zeros(5 + n)
        K[0, 0] = K[1, 1] = M
        K[2, 2] = K[3, 3] = A
        b[0] = -(hx * xd + cx * x - hxb * bed - cxb * be)
        b[1] = -(hy * yd + cy * y + hya * ald + cya * al)
        b[2] = -(hal * ald + cal * al + C * W * bed + hya * yd + cya * y)
        b[3] = -(hbe * bed + cbe * be - C * W * ald - hxb * xd - cxb * x)
        K[2, 4] += C * be                      # + C Omega' beta in the alpha equation
        # phi_0 equation: Jeff Omega' + C (alpha'' beta + alpha' beta') + sum m0 r0 (-u_D'' sin th + v_D'' cos th)
        #                 = L(Omega) - k_r Omega + sum h r^2 (phi' - Omega)
        K[4, 4] = Jeff
        K[4, 2] += C * be
        b[4] = L(W) - kr * W - C * ald * bed
        # every small mass: rows x, y (s_u'', s_v''), alpha (-d s_v''), beta (+d s_u'')
        def small_mass(mr, ang, angd, col, d):
            sn, cs = math.sin(ang), math.cos(ang)
            # s_u'' = mr (-ang'' sin - ang'^2 cos), s_v'' = mr (ang'' cos - ang'^2 sin)
            K[0, col] += -mr * sn
            K[1, col] += mr * cs
            K[2, col] += -d * mr * cs
            K[3, col] += -d * mr * sn
            b[0] -= -mr * angd**2 * cs
            b[1] -= -mr * angd**2 * sn
            b[2] += d * (-mr * angd**2 * sn)
            b[3] -= d * (-mr * angd**2 * cs)
        for p in planes:
            d, mr0, th = p["d"], p["m0"] * p["r0"], ph0 + p["psi0"]
            small_mass(mr0, th, W, 4, d)
            sn, cs = math.sin(th), math.cos(th)
            # vibration torque m0 r0 (-u_D'' sin th + v_D'' cos th), u_D'' = x'' + d beta'', v_D'' = y'' - d alpha''
            K[4, 0] += -mr0 * sn
            K[4, 3] += -mr0 * d * sn
            K[4, 1] += mr0 * cs
            K[4, 2] += -mr0 * d * cs
        for k, (p, i) in enumerate(balls):
            d, m, r, h = p["d"], p["m"][i], p["r"][i], p["h"][i]
            small_mass(m * r, phi[k], phid[k], 5 + k, d)
            sn, cs = math.sin(phi[k]), math.cos(phi[k])
            # m r [r phi'' - u_D'' sin phi + v_D'' cos phi] + h r^2 (phi' - Omega) = 0
            K[5 + k, 5 + k] = m * r * r
            K[5 + k, 0] = -m * r * sn
            K[5 + k, 3] = -m * r * d * sn
            K[5 + k, 1] = m * r * cs
            K[5 + k, 2] = -m * r * d * cs
            b[5 + k] = -h * r * r * (phid[k] - W)
            b[4] += h * r * r * (phid[k] - W)  # the ball resistance acts back on the rotor
        z = np.linalg.solve(K, b)
        return np.concatenate(([xd, yd, ald, bed], z[:4], phid, z[5:], [W, z[4]]))
    return rhs, n


def cmd_scipy(path):
    f = h5py.File(path, "r")
    g = f["/rotor/transient"]
    if s(g.attrs["frame"]) != "fixed":
        fail("scipy check expects a fixed-frame archive")
    hw, planes, mot = params(f)
    rhs, n = rhs_factory(hw, planes, mot)
    q0 = np.asarray(g.attrs["initial_q"], float)
    qd0 = np.asarray(g.attrs["initial_q_rate"], float)
    W0 = mot["w_start"]
    psi = np.concatenate([p["psi"] for p in planes]) if n else np.zeros(0)
    rate = np.concatenate([p["rate"] for p in planes]) if n else np.zeros(0)
    st0 = np.concatenate((q0, qd0, 0.0 + psi, W0 + rate, [0.0, W0]))
    t = g["time"][:]
    sol = solve_ivp(rhs, (0.0, t[-1]), st0, method="DOP853", rtol=1e-12, atol=1e-15, dense_output=True)
    if not sol.success:
        fail("solve_ivp: " + sol.message)
    ref = sol.sol(t)
    amp = max(np.max(np.abs(ref[0])), np.max(np.abs(ref[1])))
    tilt = max(np.max(np.abs(ref[2])), np.max(np.abs(ref[3])))
    ex = max(np.max(np.abs(g["x"][:] - ref[0])), np.max(np.abs(g["y"][:] - ref[1]))) / amp
    ea = max(np.max(np.abs(g["alpha"][:] - ref[2])), np.max(np.abs(g["beta"][:] - ref[3]))) / tilt
    eb = max([np.max(np.abs(g[f"state_phi_{k + 1}"][:] - ref[8 + k])) for k in range(n)] + [0.0])
    e0 = np.max(np.abs(g["state_phi_0"][:] - ref[8 + 2 * n]))
    ew = np.max(np.abs(g["state_Omega"][:] - ref[9 + 2 * n]))
    wend = ref[9 + 2 * n][-1]
    print(f"     {len(t)} samples to t = {t[-1]:.4g} s, {sol.nfev} SciPy rhs evaluations; Omega {W0:.4g} -> {wend:.6g} rad/s; "
          f"|x|,|y| up to {amp:.3g} m, |alpha|,|beta| up to {tilt:.3g} rad")
    print(f"     max |x - x_scipy| / max|x| = {ex:.3g}, tilts {ea:.3g}, ball angles {eb:.3g} rad, phi_0 {e0:.3g} rad, "
          f"Omega {ew:.3g} rad/s")
    # tolerances: the archive at its default rtol 1e-10, atol 1e-9 (rk8pd), SciPy at 1e-12.  Measured
    # (tests/app/motor.sh): 2e-10 .. 7e-10 with a linear characteristic, 1e-8 .. 6e-8 with the torque
    # table (its corners are kinks of the right-hand side that both integrators step across)
    if not (ex < 1e-6 and ea < 1e-6 and eb < 1e-6 and e0 < 1e-6 and ew < 1e-8 * max(1.0, abs(wend))):
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
    e0 = np.max(np.abs(a["state_phi_0"][:] - b["state_phi_0"][:]))
    print(f"     fixed vs rotating frame: max |dx|/max|x| = {eq:.3g} (max|x| {amp:.3g} m), ball psi {ep:.3g} rad, "
          f"Omega {eo:.3g} rad/s, phi_0 {e0:.3g} rad")
    if not (eq < 1e-6 and ep < 1e-6 and eo < 1e-6 and e0 < 1e-6):
        fail("frames disagree")


def cmd_attrs(path, kind):
    f = h5py.File(path, "r")
    g = f["/rotor/transient"]
    keys = ["drive_J", "drive_k_r", "drive_omega_start"] + (
        ["drive_L_0", "drive_omega_0"] if kind == "linear" else ["drive_torque_omega", "drive_torque_L"])
    want = {"drive_J": "kg m^2", "drive_k_r": "N m s", "drive_omega_start": "rad/s", "drive_L_0": "N m",
            "drive_omega_0": "rad/s", "drive_torque_omega": "rad/s", "drive_torque_L": "N m"}
    units = {k: s(g.attrs.get(k + "_units", "")) for k in keys}
    cols = {k: s(g[k].attrs.get("units")) for k in ("state_phi_0", "state_Omega", "Omega", "motor_torque", "motor_power")}
    print(f"     drive_mode = {s(g.attrs['drive_mode'])}; " +
          ", ".join(f"{k} = {np.asarray(g.attrs[k]).tolist()} {units[k]}" for k in keys) + f"; columns {cols}")
    if s(g.attrs["drive_mode"]) != "motor" or any(units[k] != want[k] for k in keys):
        fail("motor attributes")
    if cols != {"state_phi_0": "rad", "state_Omega": "rad/s", "Omega": "rad/s", "motor_torque": "N m", "motor_power": "W"}:
        fail("motor columns")
    _, _, mot = params(f)
    W = g["Omega"][:]
    eL = np.max(np.abs(g["motor_torque"][:] - np.array([mot["L"](w) for w in W])))
    eP = np.max(np.abs(g["motor_power"][:] - g["motor_torque"][:] * W))
    es = np.max(np.abs(W - g["state_Omega"][:]))
    print(f"     motor_torque vs L(Omega) here: {eL:.3g} N m; motor_power vs L Omega: {eP:.3g} W; Omega vs state_Omega {es:.3g}")
    if not (eL < 1e-12 * max(1.0, np.max(np.abs(g["motor_torque"][:]))) and eP < 1e-12 * np.max(np.abs(g["motor_power"][:]) + 1)
            and es == 0.0):
        fail("motor outputs")


def cmd_passes(path, w):
    g = h5py.File(path, "r")["/rotor/transient"]
    we = g["Omega"][-1]
    print(f"     Omega at the end: {we:.6g} rad/s (want > {w})")
    if not we > float(w):
        fail("the motor did not pass")


if __name__ == "__main__":
    c = sys.argv[1]
    {"scipy": cmd_scipy, "frames": cmd_frames, "attrs": cmd_attrs, "passes": cmd_passes}[c](*sys.argv[2:])
