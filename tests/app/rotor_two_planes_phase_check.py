"""Independent check of the two-plane every-phase analysis in an `autobal rotor stability` archive
(run by tests/app/rotor_two_planes_phase.sh).  Expected values come from the FULL linearized model
(every ball angle, fixed frame, time-periodic; tests/app/rotor_stability_check.py's linearization,
which does not use the closure (3.15)-(3.16) or the rotating frame), its Floquet multipliers by
scipy.integrate.solve_ivp over one revolution:
  - at every critical relative phase stored, the Floquet margin log(max|mu|)/T is 0 (a multiplier on
    the unit circle) and it has opposite signs 0.01 rad either side;
  - at every arc's midpoint its sign is the stored verdict.
Usage: rotor_two_planes_phase_check.py FILE.h5
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rotor_stability_check import floquet_margin_two, load  # noqa: E402

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures += 1


def floquet_margin(w, L, planes, phi):
    return floquet_margin_two(w, L, planes, phi)


f = h5py.File(sys.argv[1], "r")
w, L, planes, inertia = load(f)
g = f["rotor/stability/every_unbalance/phase"]
crit = np.array(g["critical_phase"]) if "critical_phase" in g else np.zeros(0)
check("critical phases found (the case was chosen with some)", len(crit) >= 1, "%d" % len(crit))
check("configuration's unbalances", abs(g.attrs["unbalance1"] - planes[0]["m0"] * planes[0]["r0"]) < 1e-15
      and abs(g.attrs["unbalance2"] - planes[1]["m0"] * planes[1]["r0"]) < 1e-15)
for pc in crit:
    m0 = floquet_margin(w, L, planes, pc)
    ml = floquet_margin(w, L, planes, pc - 0.01)
    mr = floquet_margin(w, L, planes, pc + 0.01)
    check("critical phase %.9f: Floquet margin 0" % pc, abs(m0) < 1e-5 and abs(m0) < 1e-2 * min(abs(ml), abs(mr)),
          "%.3g (%.3g, %.3g either side)" % (m0, ml, mr))
    check("critical phase %.9f: the margin changes sign" % pc, ml * mr < 0)
for lo, hi, v in zip(g["arc_lo"], g["arc_hi"], g["arc_verdict"]):
    m = floquet_margin(w, L, planes, 0.5 * (lo + hi))
    check("arc [%.6f, %.6f] verdict %d" % (lo, hi, v), (m < 0) == (v == 1) and (m > 0) == (v == -1), "margin %.6g" % m)
sys.exit(1 if failures else 0)
