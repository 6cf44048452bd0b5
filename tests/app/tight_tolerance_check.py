#!/usr/bin/python3
"""Checks of tests/app/tight_tolerance.sh: A.json B.json REF.json B.h5 DEFAULT.h5 (fixed frame at rtol
1e-11, 1e-12; rotating frame at 1e-13; the archive of B; an archive at the default rtol)."""
import json
import math
import sys

import h5py
import numpy as np

failures = 0


def check(what, ok, detail=""):
    global failures
    print("%s %s%s" % ("ok  " if ok else "FAIL", what, (": " + detail) if detail else ""))
    if not ok:
        failures += 1


def main():
    a, b, ref = (json.load(open(p)) for p in sys.argv[1:4])
    ratio = b["steps"] / a["steps"]
    check("steps rtol 1e-11 -> 1e-12 (fixed frame) grow like tol^(-1/8) = 1.33 per decade, at most 2",
          ratio <= 2.0, "%d -> %d steps, ratio %.3f" % (a["steps"], b["steps"], ratio))
    keys = ["contact_impacts", "contact_joins", "contact_releases", "friction_sticks", "friction_slips"]
    for name, d in (("1e-11", a), ("1e-12", b)):
        check("rtol %s: the reference's events %s" % (name, [ref[k] for k in keys]),
              all(d[k] == ref[k] for k in keys), str([d[k] for k in keys]))
        psi = np.array(d["planes"][0]["ball_psi_final"])
        psr = np.array(ref["planes"][0]["ball_psi_final"])
        e = float(np.max(np.abs(np.remainder(psi - psr + math.pi, 2 * math.pi) - math.pi)))
        check("rtol %s: final ball angles (relative, wrapped) vs the rotating frame at 1e-13, within 1e-6 rad" % name,
              e <= 1e-6, "%.2e rad" % e)
        check("rtol %s: final_state in the fixed frame with absolute angles (|phi_1| > 1000 rad)" % name,
              d["final_state_frame"] == "fixed" and abs(d["final_state"][8]) > 1000.0,
              "phi_1 = %.6f rad" % d["final_state"][8])
    with h5py.File(sys.argv[4], "r") as f:
        g = f["rotor/transient"]
        fi = g.attrs.get("frame_integrated", b"")
        fi = fi.decode() if isinstance(fi, bytes) else str(fi)
        check("rtol 1e-12 archive: frame = fixed, frame_integrated says rotating",
              g.attrs["frame"] in (b"fixed", "fixed") and fi.startswith("rotating"), fi)
        worst_out, worst_rel = 0.0, 0.0
        for i in range(1, 11):
            phi = g["state_phi_%d" % i][()]
            worst_out = max(worst_out, float(np.max(np.abs(phi - g["p1_b%d_phi" % i][()]))))
            # phi - psi is the rotor angle phi_0(t), the same for every ball
            d0 = phi - g["p1_b%d_psi" % i][()]
            if i == 1:
                phi0 = d0
            worst_rel = max(worst_rel, float(np.max(np.abs(d0 - phi0))))
        check("state_phi_<i> == the p1_b<i>_phi outputs (absolute angles, rad)", worst_out <= 1e-9, "%.2e" % worst_out)
        check("state_phi_<i> - p1_b<i>_psi is one rotor angle phi_0(t) for all balls", worst_rel <= 1e-9,
              "%.2e rad; phi_0 at the end %.3f rad" % (worst_rel, phi0[-1]))
    with h5py.File(sys.argv[5], "r") as f:
        check("default rtol archive: no frame_integrated attribute (absolute angles integrated)",
              "frame_integrated" not in f["rotor/transient"].attrs)
    print("%d failed" % failures)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
