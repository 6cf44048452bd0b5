"""Independent checks of the attractor classes of `autobal pendulum ensemble` (run by
tests/app/pendulum_attractors.sh), each from the model's mechanics (docs/pendulum.md), not from
autobal's classifier:
  heavy FILE     a member below the first critical speed: class heavy_side; at rest relative to the
                 rotor, each pendulum mass feels the centrifugal force m R_w^2 (r_O + l e) from the
                 axis K, which lies along its rod only when r_O is parallel to the rod e: both
                 pendulums point along the shaft centre's deflection (xi, eta), and below the
                 critical speed that deflection lies on the side of the unbalance (+U);
  circulating FILE   class circulating; the frequency = R_w + the mean relative rate of the
                 circulating pendulum over the final window, measured here on the member's series,
                 and the natural frequency = sqrt(1 - H^2/4) (x'' + H x' + x = 0 in units of omega0);
  balanced FILE  class balanced; the final angles are the main motion (4): psi = phi = psi0.
Usage: pendulum_attractors_check.py heavy|circulating|balanced FILE.h5
"""
import sys

import h5py
import numpy as np

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    failures += not ok


def main(mode, fn):
    f = h5py.File(fn, "r")
    g = f["pendulum/ensemble"]
    p = f["pendulum"].attrs
    Rw, H, psi0 = float(p["R_w"]), float(p["H"]), float(p["psi0"])
    if "R_w" in g:  # the member's speed (an ensemble parameter), not the configuration's
        Rw = float(np.array(g["R_w"]).ravel()[0])
    cls = np.array(g["attractor"]).ravel()
    names = {1: "balanced", 2: "heavy_side", 4: "circulating"}
    want = {"heavy": 2, "circulating": 4, "balanced": 1}[mode]
    check("class %s" % names[want], np.all(cls == want), str(cls))
    check("legend on the dataset", "circulating" in str(g["attractor"].attrs["legend"]))
    s = g["series/member_0"] if "series" in g else None
    if mode == "heavy":
        y = {k: np.array(s[k]) for k in ("xi", "eta", "psi", "phi")}
        th1, th2 = y["psi"][-1] + np.pi / 2, -y["phi"][-1] - np.pi / 2
        dirn = np.arctan2(y["eta"][-1], y["xi"][-1])
        d1 = abs(np.angle(np.exp(1j * (th1 - dirn))))
        d2 = abs(np.angle(np.exp(1j * (th2 - dirn))))
        check("pendulum 1 along the deflection (rest in the rotating frame)", d1 < 1e-3, "%.3g rad" % d1)
        check("pendulum 2 along the deflection", d2 < 1e-3, "%.3g rad" % d2)
        check("the deflection on the side of the unbalance (+U)", np.cos(dirn) > 0, "%.4f rad" % dirn)
    elif mode == "circulating":
        tau = np.array(s["tau"])
        win = float(g.attrs["attractor_window_revs"]) * 2 * np.pi / Rw
        k0 = np.searchsorted(tau, tau[-1] - win)
        rates = []
        for th in (np.array(s["psi"]), -np.array(s["phi"])):
            rates.append((th[-1] - th[k0]) / (tau[-1] - tau[k0]))
        turns = [abs(r) * (tau[-1] - tau[k0]) / (2 * np.pi) for r in rates]
        i = int(np.argmax(turns))
        nu = Rw + rates[i]
        got = float(np.array(g["circulation_frequency"]).ravel()[0])
        check("pendulum %d circulates (%.1f turns over the window; the other %.1f)" % (i + 1, turns[i], turns[1 - i]),
              turns[i] >= 2)
        check("circulation frequency = R_w + mean relative rate from the series", abs(got - nu) <= 2e-3 * abs(nu),
              "%.6f vs %.6f" % (got, nu))
        wn = np.sqrt(1 - H * H / 4)
        nat = float(np.array(g["natural_frequency"]).ravel()[0])
        check("natural frequency = sqrt(1 - H^2/4)", abs(nat - wn) <= 1e-12, "%.15g vs %.15g" % (nat, wn))
        check("frequency units: 1 (omega0)", str(g["circulation_frequency"].attrs["units"]) == "1")
    else:
        fa = np.array(g["final_angle"]).reshape(-1, 2)
        check("final angles psi - psi0, phi - psi0 = 0 (main motion (4))", np.abs(fa).max() < 1e-2, str(fa))
    return failures


if __name__ == "__main__":
    sys.exit(1 if main(sys.argv[1], sys.argv[2]) else 0)
