"""Independent checks for tests/app/rotor_design_two_planes.sh: Floquet multipliers of the FULL
linearized two-plane model (every ball angle, fixed frame; tests/app/rotor_stability_check.py's
linearization, which uses neither the closure (3.15)-(3.16) nor the rotating frame), integrated over one
revolution with scipy.integrate.solve_ivp, at sampled (plane-1 m0 r0, plane-2 m0 r0, relative phase).
Usage: rotor_design_two_planes_check.py FILE.h5 OMEGA SIGN S1_LO S1_HI S2_LO S2_HI N1 N2 NPH
  FILE.h5: a `rotor stability` archive of the machine with the design's balls (its hardware);
  SIGN = -1: every sample must have a negative Floquet margin (stable); +1: some sample positive.
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rotor_stability_check import floquet_margin_two, load  # noqa: E402


def floquet_margin(w, L, planes, s, phi):
    return floquet_margin_two(w, L, planes, phi, s, rtol=1e-10, atol=1e-12)


fn, w, sign = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
s1lo, s1hi, s2lo, s2hi = (float(x) for x in sys.argv[4:8])
n1, n2, nph = (int(x) for x in sys.argv[8:11])
_, L, planes, _ = load(h5py.File(fn, "r"))
worst, where = -np.inf, None
for s1 in np.linspace(s1lo, s1hi, n1):
    for s2 in np.linspace(s2lo, s2hi, n2):
        for phi in np.pi * (np.arange(nph) + 0.5) / nph:
            m = floquet_margin(w, L, planes, (s1, s2), phi)
            if m > worst:
                worst, where = m, (s1, s2, phi)
            if sign > 0 and m > 0:
                break
        if sign > 0 and worst > 0:
            break
    if sign > 0 and worst > 0:
        break
print("omega %g: largest Floquet margin %.6g 1/s at s1 %.6g, s2 %.6g kg m, phase %.4f rad" % (w, worst, *where))
ok = worst < 0 if sign < 0 else worst > 0
print("ok" if ok else "FAIL")
sys.exit(0 if ok else 1)
