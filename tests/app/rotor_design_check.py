"""rotor_design_check.py ARCHIVE BEST_INI AUTOBAL: re-checks `autobal rotor design` with computations
that do not use the library's crossing polynomials:

  - Delta of docs/rotor.md ("Stability of a balanced motion") built here with NumPy from the hardware
    values: K11 = M P^2 + h P + c, K12 = -(h_c P + c_c), K22 = A P^2 + (h_t - i C w) P + c_t,
    D = K11 K22 - K12^2, N = K22 - 2 d K12 + d^2 K11, F = (l^2 + kappa l) D - m P^4 N (two balls of
    mass m: m_b / 2 = m), Delta = F F* - m^2 c^2 P^4 Pb^4 N N*, c = cos(psi_1 - psi_2) = t^2 / 2 - 1,
    t = m0 r0 / (m r); its roots by numpy.roots;
  - the map: every point marked feasible has all sampled margins (grid speeds x 61 unbalances) below
    -margin; every point marked infeasible has a sampled margin above -margin - 0.02 (or cannot
    balance unbalance_max);
  - every ranked design: rho <= -(sampled worst margin) (rho is verified by the exact test) and close
    to it (dense: grid speeds x 401 unbalances); re-checked designs pass a denser sampled check;
  - the best design's config text = the file written = the archive attribute;
  - transients (the autobal binary, `rotor transient`): the best design balances at both ends of the
    speed range and of the unbalance range; an infeasible design at a point where NumPy finds the
    balanced motion unstable does not balance.
"""
import json
import subprocess
import sys

import h5py
import numpy as np
from numpy.polynomial import polynomial as P

path, best_ini, autobal = sys.argv[1], sys.argv[2], sys.argv[3]
f = h5py.File(path, "r")
g = f["/rotor/design"]
fails = 0


def check(what, cond):
    global fails
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        fails += 1


hw = {k: float(f["/rotor"].attrs[k]) for k in ("M_k", "A_k", "m_p", "A_p", "C_p", "l_L", "l_R", "c_Lx", "c_Rx",
                                                "h_Lx", "h_Rx")}
Mt = hw["M_k"] + hw["m_p"]
At = hw["A_k"] + hw["A_p"]
Ct = hw["C_p"]
c = hw["c_Lx"] + hw["c_Rx"]
ct = hw["c_Lx"] * hw["l_L"] ** 2 + hw["c_Rx"] * hw["l_R"] ** 2
cc = hw["c_Lx"] * hw["l_L"] - hw["c_Rx"] * hw["l_R"]
h = hw["h_Lx"] + hw["h_Rx"]
ht = hw["h_Lx"] * hw["l_L"] ** 2 + hw["h_Rx"] * hw["l_R"] ** 2
hc = hw["h_Lx"] * hw["l_L"] - hw["h_Rx"] * hw["l_R"]
r0 = float(f["/rotor/plane1"].attrs["r0"]) if "plane1" in f["/rotor"] else 0.1

wmin, wmax = float(g.attrs["omega_min"]), float(g.attrs["omega_max"])
n_omega = int(g.attrs["n_omega"])
smin, smax = float(g.attrs["unbalance_min"]), float(g.attrs["unbalance_max"])
delta = float(g.attrs["margin_required"])
speeds = np.linspace(wmin, wmax, n_omega)


def parts(w, m, hb, d):
    """A = F F* and G = P^4 Pb^4 N N* (Delta = A - m^2 c^2 G), polynomials in lambda (1/s)."""
    Pp = np.array([1j * w, 1.0])
    Pb = np.array([-1j * w, 1.0])
    P2 = P.polymul(Pp, Pp)
    K11 = P.polyadd(P.polyadd(Mt * P2, h * Pp), [c])
    K12 = -P.polyadd(hc * Pp, [cc])
    K22 = P.polyadd(P.polyadd(At * P2, (ht - 1j * Ct * w) * Pp), [ct])
    D = P.polysub(P.polymul(K11, K22), P.polymul(K12, K12))
    N = P.polyadd(P.polysub(K22, 2 * d * K12), d * d * K11)
    P4 = P.polypow(Pp, 4)
    Pb4 = P.polypow(Pb, 4)
    kappa = hb / m
    F = P.polysub(P.polymul([0, kappa, 1.0], D), m * P.polymul(P4, N))
    A = P.polymul(F, np.conj(F))
    G = P.polymul(P.polymul(P4, Pb4), P.polymul(N, np.conj(N)))
    return A, G


def worst_margin(m, r, hb, d, ws, ss):
    worst = -np.inf
    for w in ws:
        A, G = parts(w, m, hb, d)
        for s in ss:
            t = s / (m * r)
            cosd = t * t / 2 - 1
            Delta = P.polysub(A, (m * cosd) ** 2 * G)
            roots = np.roots(np.real(Delta)[::-1])
            worst = max(worst, float(np.max(roots.real)))
    return worst


# --- the map -------------------------------------------------------------------------------------
mass = g["ball_mass"][:]
damp = g["ball_damping"][:]
pos = g["plane_position"][:]
rad = g["track_radius"][:]
feas = g["feasible"][:]
check("map dimensions named and with units: %s" % [g[n].attrs["units"] for n in
                                                    ("ball_mass", "ball_damping", "plane_position", "track_radius")],
      [g[n].attrs["units"] for n in ("ball_mass", "ball_damping", "plane_position", "track_radius")] ==
      ["kg", "kg/s", "m", "m"] and feas.shape == (len(mass), len(damp), len(pos), len(rad)))
ss61 = np.linspace(smin, smax, 61)
nbad = nchk = 0
for i, m in enumerate(mass):
    for j, hb in enumerate(damp):
        for k, d in enumerate(pos):
            for q, r in enumerate(rad):
                v = int(feas[i, j, k, q])
                if v == -1:
                    nchk += 1
                    nbad += not (smax >= 2 * m * r)
                    continue
                wm = worst_margin(m, r, hb, d, speeds, ss61)
                nchk += 1
                if (v == 1 and not wm < -delta) or (v == 0 and not wm > -delta - 0.02):
                    nbad += 1
                    print("  map point m %g h %g d %g r %g: feasible %d, NumPy sampled worst margin %g" % (m, hb, d, r, v, wm))
check("map: %d points against NumPy roots of Delta (grid speeds x 61 unbalances), %d disagree" % (nchk, nbad),
      nbad == 0 and nchk == feas.size)

# --- the ranked designs ---------------------------------------------------------------------------
rk = g["ranked"]
n = rk["ball_mass"].shape[0]
ss401 = np.linspace(smin, smax, 401)
dense = np.linspace(wmin, wmax, 4 * (n_omega - 1) + 1)
for k in range(n):
    m, r, hb, d = (float(rk[x][k]) for x in ("ball_mass", "track_radius", "ball_damping", "plane_position"))
    rho, fe, rc = float(rk["robust_margin"][k]), int(rk["feasible"][k]), int(rk["recheck"][k])
    wm = worst_margin(m, r, hb, d, speeds, ss401)
    tol = 1e-3 * (1 + abs(rho))
    check("design %d (m %.5g g, r %.5g mm, h %.5g kg/s): rho %.6g <= NumPy -worst %.6g + 1e-9" % (k, m * 1e3, r * 1e3, hb, rho, -wm),
          rho <= -wm + 1e-9)
    check("design %d: rho %.6g within %.3g + 2%% of NumPy -worst %.6g" % (k, rho, tol, -wm), rho >= -wm - tol - 0.02 * abs(wm))
    check("design %d: feasible %d = (rho > margin) and re-check %d" % (k, fe, rc), fe == int(rho > delta and rc == 1))
    if rc == 1:
        wd = worst_margin(m, r, hb, d, dense, np.linspace(smin, smax, 101))
        check("design %d re-checked: NumPy worst margin on the 4x finer speed grid %.6g < -margin %g" % (k, wd, delta),
              wd < -delta)
check("ranked by rho among the feasible", all(rk["robust_margin"][i] >= rk["robust_margin"][i + 1] - 1e-12
                                              for i in range(1, n - 1) if rk["feasible"][i] and rk["feasible"][i + 1]))

# --- the config -------------------------------------------------------------------------------------
text = open(best_ini).read()
cfg = g.attrs["best_config"]
cfg = cfg.decode() if isinstance(cfg, bytes) else cfg
check("best_config attribute = the written .ini", cfg == text)
m0, r0b = float(rk["ball_mass"][0]), float(rk["track_radius"][0])
check("best config carries design 0", "ball_mass = %r, %r" % (m0, m0) in text.replace("e-0", "e-0") or
      ("ball_mass = %.17g, %.17g" % (m0, m0)) in text)


# --- transients -------------------------------------------------------------------------------------
def transient(ini, omega, m0, t_end):
    out = subprocess.run([autobal, "rotor", "transient", ini, "--json", "--set", "rotor.omega=%r" % omega,
                          "--set", "plane1.m0=%r" % m0, "--set", "transient.t_end=%r" % t_end,
                          "--set", "transient.revs_out=5"], capture_output=True, text=True)
    if out.returncode != 0:
        print(out.stderr)
        return None
    return json.loads(out.stdout)


r0cfg = float([ln.split("=")[1] for ln in text.splitlines() if ln.startswith("r0 =")][0])
for w in (wmin, wmax):
    for s in (smin, smax):
        res = transient(best_ini, w, s / r0cfg, 30.0)
        check("transient of the best design at %.6g rad/s, %.6g g mm: balanced (time to balance %s s)" %
              (w, s * 1e6, res and res.get("time_to_balance")), res is not None and res["balanced"])

# an infeasible map point where NumPy finds the balanced motion unstable: the transient does not balance
found = None
for i, m in enumerate(mass):
    for j, hb in enumerate(damp):
        for q, r in enumerate(rad):
            if feas[i, j, 0, q] != 0 or found:
                continue
            for w in speeds[::max(1, n_omega // 5)]:
                for s in (smin, 0.5 * (smin + smax), smax):
                    if worst_margin(m, r, hb, pos[0], [w], [s]) > 0.5 and not found:
                        found = (m, r, hb, w, s)
if found:
    m, r, hb, w, s = found
    bad_ini = "infeasible.ini"
    t2 = []
    for ln in text.splitlines():
        if ln.startswith("ball_mass ="):
            ln = "ball_mass = %r, %r" % (m, m)
        elif ln.startswith("ball_radius ="):
            ln = "ball_radius = %r, %r" % (r, r)
        elif ln.startswith("ball_damping ="):
            ln = "ball_damping = %r, %r" % (hb, hb)
        t2.append(ln)
    open(bad_ini, "w").write("\n".join(t2) + "\n")
    res = transient(bad_ini, w, s / r0cfg, 30.0)
    check("transient of an infeasible design (m %.5g g, r %.5g mm, h %.5g kg/s) at %.6g rad/s, %.6g g mm, where NumPy "
          "finds a root with Re > 0.5 1/s: not balanced" % (m * 1e3, r * 1e3, hb, w, s * 1e6),
          res is not None and not res["balanced"])
else:
    check("an infeasible map point with an unstable balanced motion exists for the transient check", False)

print("%d failed" % fails)
sys.exit(1 if fails else 0)
