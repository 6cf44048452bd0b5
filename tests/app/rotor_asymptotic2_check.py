#!/usr/bin/python3
"""rotor_asymptotic2_check.py JSON H5 OMEGA D1 D2 M1 M2 H1 H2 S1 S2 PSI1 PSI2: the two-plane light-ball
condition of `autobal rotor stability` (docs/rotor.md "Asymptotic conditions", "Two planes") recomputed
with NumPy from the default supports' lumped values (M = 10 kg, A = 0.16, C = 0.03 kg m^2, c_x = 2.5e5 N/m,
c_alpha = 7375 N m, c_xbeta = -2500 N, h one thousandth of c), two balls of mass M_j on r = 0.1 m per plane,
ball damping H_j, unbalance S_j = m0 r0 at phase PSI_j: G = B^T K(i w)^-1 B by a 2x2 complex solve, q_j from
the balanced angles, the eight ball roots as eigenvalues of the companion of the 4x4 quadratic eigenproblem
(NumPy, not the polynomial the program expands); JSON = archive attributes (with units).  Exit 1 on a
failed check."""
import json
import sys

import h5py
import numpy as np

fails = 0


def check(what, ok, detail=""):
    global fails
    print(("ok   " if ok else "FAIL ") + what + (" (" + detail + ")" if detail else ""))
    if not ok:
        fails += 1


jf, hf = sys.argv[1], sys.argv[2]
w, d1, d2, m1, m2, h1, h2, s1, s2, p1, p2 = (float(x) for x in sys.argv[3:14])
M, A, C = 10.0, 0.16, 0.03
c, ct, cc = 2.5e5, 7375.0, -2500.0
h, ht, hc = 250.0, 7.375, -2.5
r = 0.1
j = json.load(open(jf))
a_ = j["asymptotic2"]
P = 1j * w
K = np.array([[M * P * P + h * P + c, -(hc * P + cc)], [-(hc * P + cc), A * P * P + (ht - 1j * C * w) * P + ct]])
B = np.array([[1.0, 1.0], [d1, d2]])
G = B.T @ np.linalg.solve(K, B)
for k, (a, b) in enumerate(((0, 0), (0, 1), (1, 0), (1, 1))):
    g = G[a, b]
    check("G_%d%d vs the 2x2 solve" % (a + 1, b + 1),
          abs(a_["G_real"][k] + 1j * a_["G_imag"][k] - g) <= 1e-10 * abs(g))
ms, kap, Q = [m1, m2], [h1 / m1, h2 / m2], []
for mj, sj, pj in ((m1, s1, p1), (m2, s2, p2)):
    x = sj / (2 * mj * r)
    psi = [pj + np.pi - np.arccos(x), pj + np.pi + np.arccos(x)]   # (3.14)
    Q.append(mj * (np.exp(2j * psi[0]) + np.exp(2j * psi[1])))
for k in range(2):
    check("q_%d = |Q| / m_b from the balanced angles" % (k + 1), abs(a_["q"][k] - abs(Q[k]) / (2 * ms[k])) <= 1e-12)
    check("kappa_%d = h / m" % (k + 1), abs(a_["kappa"][k] - kap[k]) <= 1e-12 * kap[k])
s = w**4 / 2
mb = np.diag([2 * m1, 2 * m2])
Qd = np.diag(Q)
S = np.block([[s * mb @ G, -s * Qd @ np.conj(G)], [-s * np.conj(Qd) @ G, s * mb @ np.conj(G)]])
kk = np.array(kap + kap)
comp = np.block([[np.zeros((4, 4)), np.eye(4)], [S, -np.diag(kk)]])
rr = np.linalg.eigvals(comp)
got = np.array(a_["light_ball_root_real"]) + 1j * np.array(a_["light_ball_root_imag"])
err = max(max(min(abs(g - rr)) for g in got), max(min(abs(z - got)) for z in rr)) / max(abs(rr))
check("ball roots = eigenvalues of the 4x4 quadratic eigenproblem (NumPy)", err < 1e-8, "rel. err %.2e" % err)
check("light_predicts_stable: every predicted real part < 0",
      a_["light_predicts_stable"] == bool(max(rr.real) < 0 and max(a_["light_rotor_root_real"]) < 0))
if a_["light_decided"]:
    check("decided prediction = exact two-plane verdict (%s)" % j["verdict"],
          a_["light_predicts_stable"] == (j["verdict"] == "stable"))
g5 = h5py.File(hf, "r")["/rotor/stability/asymptotic2"]
units = {"G_real": "m/N", "G_imag": "m/N", "kappa": "1/s", "q": "1", "light_small": "1",
         "light_ball_root_real": "1/s", "light_ball_root_imag": "1/s", "light_rotor_root_real": "1/s",
         "light_rotor_root_imag": "1/s"}
for k, u in units.items():
    check("archive %s = JSON, units %s" % (k, u),
          np.allclose(g5.attrs[k], a_[k], rtol=1e-15, atol=0) and g5.attrs[k + "_units"] == u)
for k in ("light_predicts_stable", "light_applicable", "light_decided"):
    check("archive %s = JSON" % k, int(g5.attrs[k]) == int(a_[k]))
check("archive description says ASYMPTOTIC", "ASYMPTOTIC" in g5.attrs["description"])
# high speed, Q1 = Q2 = 0: Gamma = -lim w^2 Re G, H = -lim w^3 Im G from the 2x2 solve at 1e7 rad/s, the modes
# of Mb^1/2 Gamma Mb^1/2 by NumPy's eigh
check("high speed defined (paper inertia)", a_["high_defined"])
W = 1e7
KW = np.array([[-M * W * W + 1j * W * h + c, -(1j * W * hc + cc)], [-(1j * W * hc + cc), -(A - C) * W * W + 1j * W * ht + ct]])
GW = B.T @ np.linalg.solve(KW, B)
Gam, Hh = -W * W * GW.real, -W**3 * GW.imag
check("high_Gamma = -lim w^2 Re G", np.allclose(a_["high_Gamma"], Gam.ravel(), rtol=1e-8, atol=0))
check("high_H = -lim w^3 Im G", np.allclose(a_["high_H"], Hh.ravel(), rtol=1e-5, atol=0))
Sq = np.diag(np.sqrt([2 * m1, 2 * m2]))
mu, Z = np.linalg.eigh(Sq @ Gam @ Sq)
kbar = np.array([Z[:, k] @ np.diag(kap) @ Z[:, k] for k in range(2)])
kinf = np.array([abs(Z[:, k] @ Sq @ Hh @ Sq @ Z[:, k]) for k in range(2)]) / np.sqrt(2 * mu)
check("high_mu = eigenvalues of Mb^1/2 Gamma Mb^1/2", np.allclose(a_["high_mu"], mu, rtol=1e-8, atol=0))
check("high_kappa_mode = z_k^T diag(kappa) z_k", np.allclose(a_["high_kappa_mode"], kbar, rtol=1e-8, atol=0))
check("high_kappa_inf = |z_k^T Ht z_k| / sqrt(2 mu_k)", np.allclose(a_["high_kappa_inf"], kinf, rtol=1e-5, atol=0))
check("high_predicts_stable = (kbar_k > kappa_inf_k for both modes)", a_["high_predicts_stable"] == bool(np.all(kbar > kinf)))
if a_["high_decided"] and abs(a_["q"][0]) < 1e-9 and abs(a_["q"][1]) < 1e-9:
    check("decided high-speed prediction at Q = 0 = exact two-plane verdict (%s)" % j["verdict"],
          a_["high_predicts_stable"] == (j["verdict"] == "stable"))
for k, u in {"high_Gamma": "1/kg", "high_H": "1/(kg s)", "high_mu": "1", "high_kappa_mode": "1/s",
             "high_kappa_inf": "1/s", "high_re": "1/s", "high_small": "1"}.items():
    check("archive %s = JSON, units %s" % (k, u),
          np.allclose(g5.attrs[k], a_[k], rtol=1e-15, atol=0) and g5.attrs[k + "_units"] == u)
for k in ("high_predicts_stable", "high_applicable", "high_decided"):
    check("archive %s = JSON" % k, int(g5.attrs[k]) == int(a_[k]))
sys.exit(1 if fails else 0)
