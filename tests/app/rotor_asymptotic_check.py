#!/usr/bin/python3
"""rotor_asymptotic_check.py JSON H5 OMEGA D M_BALL H_BALL M0 [C]: the asymptotic conditions of
`autobal rotor stability` (docs/rotor.md "Asymptotic conditions") recomputed with NumPy from the
default supports' lumped values of the spec (c_x = 2.5e5 N/m, c_alpha = 7375 N m, c_xbeta = -2500 N,
h one thousandth of c; M = 10 kg, A = 0.16 kg m^2, C = 0.03 kg m^2 unless given), two balls on
r = 0.1 m, the unbalance at r0 = 0.1 m: G by a 2x2 complex solve, q from the balanced angles, the
four ball roots from the quartic, kappa_min, and the high-speed closed forms; JSON = archive
attributes (with units).  Exit 1 on a failed check."""
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


def close(what, got, want, rtol=1e-10):
    got, want = np.asarray(got, float), np.asarray(want, float)
    err = np.max(np.abs(got - want) / np.maximum(np.abs(want), 1e-300)) if want.size else 0.0
    check(what, np.all(np.abs(got - want) <= rtol * np.abs(want) + 1e-300), "rel. err %.2e" % err)


jf, hf = sys.argv[1], sys.argv[2]
w, d, m, hb, m0 = (float(x) for x in sys.argv[3:8])
C = float(sys.argv[8]) if len(sys.argv) > 8 else 0.03
M, A = 10.0, 0.16
c, ct, cc = 2.5e5, 7375.0, -2500.0
h, ht, hc = 250.0, 7.375, -2.5
r = r0 = 0.1
j = json.load(open(jf))
a_ = j["asymptotic"]
P = 1j * w
K = np.array([[M * P * P + h * P + c, -(hc * P + cc)], [-(hc * P + cc), A * P * P + (ht - 1j * C * w) * P + ct]])
e = np.array([1.0, d])
G = e @ np.linalg.solve(K, e)
close("G real part vs the 2x2 solve", a_["G_real"], G.real)
close("G imaginary part vs the 2x2 solve", a_["G_imag"], G.imag)
x = m0 * r0 / (2 * m * r)
psi = np.pi - np.arccos(x)        # the balanced angles pi -/+ arccos(x) (3.14)
q = abs(m * np.exp(2j * psi) + m * np.exp(-2j * psi)) / (2 * m)
close("q = |Q| / m_b from the balanced angles", a_["q"], q, 1e-12) if q > 1e-8 else check("q = 0", a_["q"] < 1e-12)
kap = hb / m
mb = 2 * m
aa = mb * w**4 / 2
br = G.imag**2 - q * q * abs(G)**2
if kap == 0:
    # undamped balls: the next-order ball roots (docs/rotor.md "Undamped balls"), g = (m_b/2) P^4 N / D with its
    # derivative at lambda = 0 by the quotient rule on NumPy polynomials (P = lambda + i omega)
    from numpy.polynomial import polynomial as Pn
    Pp = np.array([1j * w, 1.0])
    K11 = Pn.polyadd(Pn.polyadd(M * Pn.polymul(Pp, Pp), h * Pp), [c])
    K12 = -Pn.polyadd(hc * Pp, [cc])
    K22 = Pn.polyadd(Pn.polyadd(A * Pn.polymul(Pp, Pp), (ht - 1j * C * w) * Pp), [ct])
    D = Pn.polysub(Pn.polymul(K11, K22), Pn.polymul(K12, K12))
    N = Pn.polyadd(Pn.polyadd(K22, -2 * d * K12), d * d * K11)
    X = mb / 2 * Pn.polymul(Pn.polymul(Pn.polymul(Pp, Pp), Pn.polymul(Pp, Pp)), N)
    g0 = Pn.polyval(0, X) / Pn.polyval(0, D)
    g1 = (Pn.polyval(0, Pn.polyder(X)) * D[0] - X[0] * Pn.polyval(0, Pn.polyder(D))) / D[0]**2
    close("undamped: g0 = a G", g0, aa * G, 1e-9)
    disc = q * q * abs(g0)**2 - g0.imag**2
    on_axis = bool(disc > 0 and g0.real + np.sqrt(disc) < 0)
    check("undamped: on the axis iff both u real and negative", a_["undamped_on_axis"] == on_axis)
    if on_axis:
        r_ = np.sqrt(disc)
        dl = [g1.real / 2 + sg * (q * q * (g1 * np.conj(g0)).real - g0.imag * g1.imag) / (2 * r_) for sg in (1, -1)]
        close("undamped: delta_(+-) = Re g1/2 +- (q^2 Re(g1 conj g0) - Im g0 Im g1)/(2r)", a_["undamped_delta"], dl, 1e-8)
        pm = max(max(dl), max(a_["undamped_rotor_root_real"]))
        check("undamped: predicted largest real part = exact margin of the program (rel. 1e-3)",
              abs(pm - j["margin"]) <= 1e-3 * abs(j["margin"]), "%.9g vs %.9g" % (pm, j["margin"]))
    if a_["undamped_decided"]:
        check("decided undamped prediction = exact verdict (%s)" % j["verdict"],
              a_["undamped_predicts_stable"] == (j["verdict"] == "stable"))
    check("undamped: no light-ball keys", "light_predicts_stable" not in a_)
    gg = h5py.File(hf, "r")["/rotor/stability/asymptotic"]
    for k, u in (("undamped_delta", "1/s"), ("undamped_ball_root_real", "1/s"), ("undamped_ball_root_imag", "1/s"),
                 ("undamped_rotor_root_real", "1/s"), ("undamped_small", "1")):
        v = np.asarray(a_[k], float)
        check("archive %s = JSON, units %s" % (k, u),
              np.allclose(gg.attrs[k], v, rtol=1e-15, atol=0, equal_nan=True) and gg.attrs[k + "_units"] == u)
    for k in ("undamped_on_axis", "undamped_predicts_stable", "undamped_decided", "undamped_applicable"):
        check("archive %s = JSON" % k, int(gg.attrs[k]) == int(a_[k]))
    check("archive: no light-ball attributes", "light_predicts_stable" not in gg.attrs)
    sys.exit(1 if fails else 0)
if G.real < 0:
    km = np.sqrt(aa * br / (-G.real)) if br > 0 else 0.0
    close("kappa_min = sqrt(a (Im^2 G - q^2 |G|^2) / (-Re G))", a_["light_kappa_min"], km, 1e-9) if km > 0 else \
        check("kappa_min = 0 (the bracket of (L2) is negative)", a_["light_kappa_min"] == 0)
pred = bool(G.real < 0 and kap * kap * (-G.real) > aa * br)
rr = np.roots([1, 2 * kap, kap * kap - 2 * aa * G.real, -2 * aa * kap * G.real, aa * aa * abs(G)**2 * (1 - q * q)])
got = np.array(a_["light_ball_root_real"]) + 1j * np.array(a_["light_ball_root_imag"])
err = max(min(abs(g - rr)) for g in got) / max(abs(rr))
check("ball roots = the roots of the quartic (NumPy)", err < 1e-8, "rel. err %.2e" % err)
check("(L1), (L2) from the ball roots: all Re < 0 iff the conditions", (max(rr.real) < 0) == pred)
check("light_predicts_stable: (L1) and (L2) and the rotor roots", a_["light_predicts_stable"] == (pred and max(a_["light_rotor_root_real"]) < 0))
if a_["light_decided"]:
    check("decided light-ball prediction = exact verdict (%s)" % j["verdict"],
          a_["light_predicts_stable"] == (j["verdict"] == "stable"))
Ap = A - C
ginf = 1 / M + d * d / Ap
eta = h / M**2 - 2 * d * hc / (M * Ap) + d * d * ht / Ap**2
close("high speed: m_eff = 1/(1/M + d^2/(A - C))", a_["high_m_eff"], 1 / ginf, 1e-12)
close("high speed: h_eff = m_eff^2 eta", a_["high_h_eff"], eta / ginf**2, 1e-12)
if ginf > 0:
    close("high speed: kappa_inf = sqrt(m_b/(2 m_eff)) h_eff/m_eff", a_["high_kappa_inf"], np.sqrt(mb * ginf / 2) * eta / ginf, 1e-12)
check("high speed: prediction = (H1) and kappa > kappa_inf", a_["high_predicts_stable"] == bool(ginf > 0 and kap > np.sqrt(mb * ginf / 2) * eta / ginf))
# the archive
g = h5py.File(hf, "r")["/rotor/stability/asymptotic"]
units = {"G_real": "m/N", "G_imag": "m/N", "kappa": "1/s", "light_kappa_min": "1/s", "light_small": "1",
         "light_ball_root_real": "1/s", "light_rotor_root_real": "1/s", "high_m_eff": "kg", "high_h_eff": "N s/m",
         "high_kappa_inf": "1/s", "high_small": "1"}
for k, u in units.items():
    v = j["asymptotic"][k]
    v = np.nan if v is None else np.asarray([np.nan if z is None else z for z in v]) if isinstance(v, list) else v
    check("archive %s = JSON, units %s" % (k, u),
          np.allclose(g.attrs[k], v, rtol=1e-15, atol=0, equal_nan=True) and g.attrs[k + "_units"] == u)
for k in ("light_predicts_stable", "light_applicable", "light_decided", "high_predicts_stable", "high_applicable"):
    check("archive %s = JSON" % k, int(g.attrs[k]) == int(j["asymptotic"][k]))
check("archive description says ASYMPTOTIC", "ASYMPTOTIC" in g.attrs["description"])
sys.exit(1 if fails else 0)
