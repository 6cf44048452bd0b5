"""The JSON summaries a script reads (issue 18 items 5 and 6), against independent computations
(run by tests/app/json_outputs.sh).  Usage: json_outputs_check.py AUTOBAL SCRATCH_DIR

Nothing expected here is taken from autobal:
  - pendulum transient --json: final_state (names, units, values) against an integration of the
    equations of motion (1) of docs/pendulum.md written here (the 4x4 system for the
    accelerations solved at every step, scipy DOP853, rtol 1e-12);
  - rotor transient --json: final_state of a rotor in the planar limit (docs/rotor.md, "Planar
    limit": FULL inertia, plane at the centre of mass, isotropic supports, tilt decoupled)
    against the same pendulum integration mapped to the rotor's coordinates and SI units
    (x + i y = l (xi + i eta) e^{i w t}, ball 1 at phi_1 = w t + psi + pi/2, ball 2 at
    phi_2 = w t - phi - pi/2, t = tau / omega0), in both frames;
  - rotor stability --json: the roots of the same rotor against omega0 x the NumPy roots of (6)
    plus the tilt's closed form, and for the default rotor against the NumPy roots of Delta built
    from the formulas of docs/rotor.md (rotor_stability_check.delta); the Floquet multipliers
    against exp(lambda T) of those roots; the full model's eigenvalues against the same set.
"""
import json
import os
import subprocess
import sys

import numpy as np
from numpy.polynomial import Polynomial as Poly
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rotor_stability_check as rsc  # noqa: E402  (its delta(), roots_of(), match())

AUTOBAL, SCRATCH = sys.argv[1], sys.argv[2]
failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    failures += 0 if ok else 1


def autobal_json(*args):
    out = subprocess.run([AUTOBAL, *args, "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError("autobal %s failed: %s" % (" ".join(args), out.stderr))
    return json.loads(out.stdout)


# ---- the pendulum model (1), independently ----------------------------------------------------
def pendulum_rhs(Rw, Rm, H, h, psi0):
    s0 = np.sin(psi0)

    def f(tau, y):
        xi, eta, ps, ph, xd, ed, psd, phd = y
        sp, cp, sf, cf = np.sin(ps), np.cos(ps), np.sin(ph), np.cos(ph)
        M = np.array([[1, 0, -Rm * cp, -Rm * cf],
                      [0, 1, -Rm * sp, Rm * sf],
                      [-cp, -sp, 1, 0],
                      [-cf, sf, 0, 1]])
        b = np.array([
            2 * Rw * ed + Rw**2 * xi - H * (xd - Rw * eta) - xi
            + Rm * (-2 * Rw * (psd * sp - phd * sf) - psd**2 * sp - phd**2 * sf + Rw**2 * (2 * s0 - sp - sf)),
            -2 * Rw * xd + Rw**2 * eta - H * (ed + Rw * xi) - eta
            + Rm * (2 * Rw * (psd * cp + phd * cf) + psd**2 * cp - phd**2 * cf + Rw**2 * (cp - cf)),
            -h * psd + (2 * Rw * xd - Rw**2 * eta) * sp + (-2 * Rw * ed - Rw**2 * xi) * cp,
            -h * phd - (2 * Rw * xd - Rw**2 * eta) * sf + (-2 * Rw * ed - Rw**2 * xi) * cf])
        return np.concatenate([y[4:], np.linalg.solve(M, b)])
    return f


def integrate_pendulum(Rw, Rm, H, h, psi0, y0, tau_end):
    sol = solve_ivp(pendulum_rhs(Rw, Rm, H, h, psi0), (0, tau_end), y0, method="DOP853", rtol=1e-12, atol=1e-14)
    assert sol.success, sol.message
    return sol.y[:, -1]


def char_poly6(Rw, Rm, H, h, psi0):
    """(6) as a real NumPy polynomial in lambda (docs/pendulum.md)"""
    lam = Poly([0, 1])
    Pl = lam + 1j * Rw
    a11, a31, a33 = Pl**2 + H * Pl + 1, Pl**2, lam**2 + h * lam
    cj = lambda p: Poly(np.conj(p.coef))  # noqa: E731
    f = (a11 * a33 - Rm * a31**2) * (cj(a11) * a33 - Rm * cj(a31) ** 2) \
        - Rm**2 * np.cos(2 * psi0) ** 2 * a31**2 * cj(a31) ** 2
    assert np.abs(f.coef.imag).max() <= 1e-12 * np.abs(f.coef).max()
    return Poly(f.coef.real)


# ---- 1. pendulum transient -------------------------------------------------------------------
def check_pendulum_transient():
    Rw, Rm, H, h, psi0 = 2.2, 0.12, 0.15, 0.4, 0.35
    y0 = [0.05, -0.02, 1.1, -0.4, 0.0, 0.03, 0.2, -0.1]
    keys = ["xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate"]
    args = ["pendulum", "transient", "--set", "pendulum.R_w=%r" % Rw, "--set", "pendulum.R_m=%r" % Rm,
            "--set", "pendulum.H=%r" % H, "--set", "pendulum.h=%r" % h, "--set", "pendulum.psi0=%r" % psi0,
            "--set", "transient.t_end=40", "--set", "transient.rtol=1e-12", "--set", "transient.atol=1e-14"]
    for k, v in zip(keys, y0):
        args += ["--set", "initial.%s=%r" % (k, v)]
    d = autobal_json(*args)
    check("pendulum: final_state_names", d.get("final_state_names") == keys, str(d.get("final_state_names")))
    check("pendulum: final_state_units", d.get("final_state_units") == ["1", "1", "rad", "rad", "1", "1", "rad", "rad"],
          str(d.get("final_state_units")))
    check("pendulum: t_reached = t_end", d["t_reached"] == 40)
    ref = integrate_pendulum(Rw, Rm, H, h, psi0, y0, 40.0)
    err = np.abs(np.array(d["final_state"]) - ref).max()
    check("pendulum: final_state == SciPy integration of (1) (1e-8)", err < 1e-8, "max |diff| %.2e" % err)
    wrap = lambda a: (a + np.pi) % (2 * np.pi) - np.pi  # noqa: E731
    check("pendulum: alpha_final, beta_final == final psi, phi - psi0 (wrapped)",
          abs(wrap(d["alpha_final"] - (ref[2] - psi0))) < 1e-8 and abs(wrap(d["beta_final"] - (ref[3] - psi0))) < 1e-8)


# ---- 2. the rotor in the planar limit ----------------------------------------------------------
PL = dict(M=4.0, A=0.1, C=0.05, c=6500.0, h_s=30.0, c_t=3000.0, h_t=5.0, m=1.0, r=0.1, h_b=2.0, m0=0.5, r0=0.1)


def planar_ini(path, omega, ball_psi, q0, qd0, t_end, frame):
    p = PL
    with open(path, "w") as f:
        f.write("[rotor]\nomega = %r\ninertia = full\n" % omega)
        f.write("[lumped]\nM = %r\nA = %r\nC = %r\nc_x = %r\nc_y = %r\nc_z = %r\nc_alpha = %r\nc_beta = %r\n"
                "c_xbeta = 0\nc_yalpha = 0\nh_x = %r\nh_y = %r\nh_z = 0\nh_alpha = %r\nh_beta = %r\n"
                "h_xbeta = 0\nh_yalpha = 0\n" % (p["M"], p["A"], p["C"], p["c"], p["c"], p["c"], p["c_t"], p["c_t"],
                                                 p["h_s"], p["h_s"], p["h_t"], p["h_t"]))
        f.write("[plane1]\nd = 0\nm0 = %r\nr0 = %r\npsi0 = 0\nball_mass = %r, %r\nball_radius = %r, %r\n"
                "ball_damping = %r, %r\nball_psi = %r, %r\n" % (p["m0"], p["r0"], p["m"], p["m"], p["r"], p["r"],
                                                                 p["h_b"], p["h_b"], ball_psi[0], ball_psi[1]))
        f.write("[initial]\nx = %r\ny = %r\nx_rate = %r\ny_rate = %r\n" % (q0[0], q0[1], qd0[0], qd0[1]))
        f.write("[transient]\nt_end = %r\nrtol = 1e-12\natol = 1e-13\nframe = %s\n" % (t_end, frame))


def planar_pendulum(omega):
    """the mapping of docs/rotor.md, "Planar limit" (FULL inertia)"""
    p = PL
    Ms = p["M"] + p["m0"] + 2 * p["m"]
    w0 = np.sqrt(p["c"] / Ms)
    return dict(w0=w0, Rw=omega / w0, Rm=p["m"] / Ms, H=p["h_s"] / (w0 * Ms), h=p["h_b"] / (p["m"] * w0),
                psi0=np.arcsin(p["m0"] * p["r0"] / (2 * p["m"] * p["r"])), l=p["r"])


def check_rotor_transient():
    omega, t_end = 100.0, 0.6
    ball_psi = (1.2, -2.4)
    q0, qd0 = (0.002, -0.001), (0.01, 0.02)
    pp = planar_pendulum(omega)
    w0, l = pp["w0"], pp["l"]
    z0 = complex(*q0) / l
    zd0 = (complex(*qd0) / l - 1j * omega * z0) / w0
    y0 = [z0.real, z0.imag, ball_psi[0] - np.pi / 2, -ball_psi[1] - np.pi / 2, zd0.real, zd0.imag, 0.0, 0.0]
    ref = integrate_pendulum(pp["Rw"], pp["Rm"], pp["H"], pp["h"], pp["psi0"], y0, w0 * t_end)
    xi, eta, ps, ph, xd, ed, psd, phd = ref
    e = np.exp(1j * omega * t_end)
    z = l * complex(xi, eta) * e
    zd = l * e * (w0 * complex(xd, ed) + 1j * omega * complex(xi, eta))
    for frame in ("fixed", "rotating"):
        ini = os.path.join(SCRATCH, "planar_%s.ini" % frame)
        planar_ini(ini, omega, ball_psi, q0, qd0, t_end, frame)
        d = autobal_json("rotor", "transient", ini)
        names = d.get("final_state_names", [])
        want_names = ["x", "y", "alpha", "beta", "x_rate", "y_rate", "alpha_rate", "beta_rate"] + \
            ["%s_%d" % ("phi" if frame == "fixed" else "psi", i) for i in (1, 2)] + \
            ["%s_rate_%d" % ("phi" if frame == "fixed" else "psi", i) for i in (1, 2)]
        check("rotor (%s frame): final_state_frame, names" % frame,
              d.get("final_state_frame") == frame and names == want_names, str(names))
        check("rotor (%s frame): final_state_units" % frame,
              d.get("final_state_units") == ["m", "m", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s", "rad", "rad",
                                             "rad/s", "rad/s"], str(d.get("final_state_units")))
        y = dict(zip(names, d["final_state"]))
        wt = omega * t_end if frame == "fixed" else 0.0
        wr = omega if frame == "fixed" else 0.0
        a = "phi" if frame == "fixed" else "psi"
        want = {"x": z.real, "y": z.imag, "alpha": 0.0, "beta": 0.0, "x_rate": zd.real, "y_rate": zd.imag,
                "alpha_rate": 0.0, "beta_rate": 0.0,
                a + "_1": wt + ps + np.pi / 2, a + "_2": wt - ph - np.pi / 2,
                a + "_rate_1": wr + w0 * psd, a + "_rate_2": wr - w0 * phd}
        scale = {"x": l, "y": l, "x_rate": l * omega, "y_rate": l * omega, "alpha": 1, "beta": 1, "alpha_rate": omega,
                 "beta_rate": omega, a + "_1": 1, a + "_2": 1, a + "_rate_1": omega, a + "_rate_2": omega}
        err = max(abs(y[k] - want[k]) / scale[k] for k in want)
        check("rotor (%s frame, planar limit): final_state == the pendulum model (1) mapped, SciPy (relative 1e-8)"
              % frame, err < 1e-8, "max scaled |diff| %.2e" % err)


# ---- 3. rotor stability roots ------------------------------------------------------------------
def check_rotor_roots():
    omega = 100.0
    ini = os.path.join(SCRATCH, "planar_stab.ini")
    planar_ini(ini, omega, (1.2, -2.4), (0, 0), (0, 0), 1.0, "fixed")
    d = autobal_json("rotor", "stability", ini, "--set", "stability.critical_speeds=false")
    pp = planar_pendulum(omega)
    lam6 = char_poly6(pp["Rw"], pp["Rm"], pp["H"], pp["h"], pp["psi0"]).roots() * pp["w0"]
    p = PL
    b = p["h_t"] - 1j * p["C"] * omega
    s = np.sqrt(b * b - 4 * p["A"] * p["c_t"])
    tilt = np.array([(-b + s) / (2 * p["A"]), (-b - s) / (2 * p["A"])]) - 1j * omega
    want = np.concatenate([lam6, tilt, np.conj(tilt)])
    for key in ("root", "closed_eig", "full_eig"):
        got = np.array(d[key + "_real"]) + 1j * np.array(d[key + "_imag"])
        err = rsc.match(want, got) / np.abs(want).max()
        check("planar rotor: %s_real/imag (12) == omega0 x roots of (6) + tilt (NumPy; relative 1e-9)" % key,
              len(got) == 12 and err < 1e-9, "%.2e" % err)
        check("planar rotor: units of %s_real are 1/s" % key, d["units"].get(key + "_real") == "1/s")
    check("planar rotor: margin == max Re of the expected roots",
          abs(d["margin"] - want.real.max()) < 1e-9 * np.abs(want).max(), "%r vs %r" % (d["margin"], want.real.max()))
    # the default rotor (hardware input, d = 0.1: no planar limit) against Delta of docs/rotor.md
    d = autobal_json("rotor", "stability", "--set", "stability.critical_speeds=false")
    L = dict(M=10.0, A=0.16, C=0.03, c_x=2.5e5, c_alpha=7375.0, c_xbeta=-2500.0, h_x=250.0,
             h_alpha=0.2 * 0.2 * 100 + 0.15 * 0.15 * 150, h_xbeta=0.2 * 100 - 0.15 * 150)
    pl = dict(d=0.1, m0=0.02, r0=0.1, psi0=0.0, m=np.array([0.05, 0.05]), r=np.array([0.1, 0.1]),
              h=np.array([0.1, 0.1]))
    want = rsc.roots_of(rsc.delta(500.0, L, pl, rsc.balanced_two(pl)))
    got = np.array(d["root_real"]) + 1j * np.array(d["root_imag"])
    err = rsc.match(want, got) / np.abs(want).max()
    check("default rotor: root_real/imag == NumPy roots of Delta (docs/rotor.md; relative 1e-9)",
          len(got) == 12 and err < 1e-9, "%.2e" % err)
    coef = rsc.real_coefficients(rsc.delta(500.0, L, pl, rsc.balanced_two(pl)))
    cp = np.array(d["char_poly"])
    check("default rotor: char_poly == Delta's coefficients (relative 1e-12 of the largest)",
          len(cp) == 13 and np.abs(cp - coef).max() <= 1e-12 * np.abs(coef).max(),
          "%.2e" % (np.abs(cp - coef).max() / np.abs(coef).max()))
    mu = np.array(d["floquet_mu_real"]) + 1j * np.array(d["floquet_mu_imag"])
    T = 2 * np.pi / 500.0
    check("default rotor: period = 2 pi / omega", abs(d["period"] - T) < 1e-15)
    err = rsc.match(np.exp(want * T), mu)
    check("default rotor: floquet_mu == exp(lambda T) of Delta's roots (1e-7)", len(mu) == 12 and err < 1e-7,
          "%.2e" % err)
    check("default rotor: full_eig (8 + 2N = 12) == Delta's roots (relative 1e-9)",
          rsc.match(want, np.array(d["full_eig_real"]) + 1j * np.array(d["full_eig_imag"])) / np.abs(want).max() < 1e-9)


def main():
    check_pendulum_transient()
    check_rotor_transient()
    check_rotor_roots()
    print("%d failed" % failures)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
