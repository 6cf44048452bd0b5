#!/usr/bin/env python3
"""Checks of tests/app/ensemble_friction.sh (`autobal rotor ensemble` with rolling resistance and
stiction).  Modes:
  same A.h5 B.h5            every dataset of /rotor/ensemble equal bit for bit (NaN = NaN), the
                            friction attributes present in both (runs with 1 and 2 threads)
  params A.h5 K             print the parameter values of member K (flat index), as exact decimals
  member A.h5 K T.h5        member K of the ensemble against the single `rotor transient` run T.h5
                            of the same parameters: final residual, final angles, stuck balls,
                            time stuck, switch count, residual in kg m
  close A.h5 B.h5 TOL       residual_unbalance_abs_final of A and B within TOL (relative)
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ensemble_common import ens, fail, params as params_of, same as same_of  # noqa: E402


def same(a, b):
    same_of(a, b, (), "friction")


PARAMS = ("psi_1", "psi_2", "ball_f", "ball_mu", "psi0", "m0", "omega")


def params(path, k):
    params_of(path, k, PARAMS)


def member(path, k, tpath):
    g = ens(path)
    shape = g["status"].shape
    idx = np.unravel_index(k, shape)
    t = h5py.File(tpath, "r")["rotor/transient"]
    a = t.attrs
    res_e = g["residual_unbalance_final"][idx]
    res_t = a["residual_unbalance_final"]
    if not abs(res_e - res_t) <= 1e-12 * abs(res_t):
        fail("member %d: residual %r (ensemble) vs %r (transient)" % (k, res_e, res_t))
    ang = g["final_angle"][idx]
    nb = ang.shape[-1]
    angt = np.array([t["p1_b%d_psi_w" % (i + 1)][-1] for i in range(nb)])
    d = np.angle(np.exp(1j * (ang - angt)))
    if np.max(np.abs(d)) > 1e-9:
        fail("member %d: final angles %s vs %s" % (k, ang, angt))
    if "p1_ball_stuck_final" in a:
        stuck = np.sum(a["p1_ball_stuck_final"])
        tmax = np.max(a["p1_ball_time_stuck"])
        sw = a["friction_sticks"] + a["friction_slips"] + a["friction_reversals"]
        got = (g["balls_stuck_final"][idx], g["time_stuck_max"][idx], g["friction_switches"][idx])
        if got[0] != stuck or abs(got[1] - tmax) > 1e-12 * max(1.0, tmax) or got[2] != sw:
            fail("member %d: stuck %s, time stuck max %s, switches %s vs transient %s %s %s" % (k, *got, stuck, tmax, sw))
        print("member %d: residual %.17g, %d stuck, longest stuck %.6f s, %d switches: equal to rotor transient"
              % (k, res_e, stuck, tmax, sw))
    else:
        if "balls_stuck_final" in g:
            fail("regularized law: no stuck quantities expected")
        print("member %d: residual %.17g equal to rotor transient" % (k, res_e))
    if "residual_unbalance_abs_final" in g:
        ue, ut = g["residual_unbalance_abs_final"][idx], np.max(a["residual_unbalance_abs_final"])
        if not abs(ue - ut) <= 1e-12 * abs(ut):
            fail("member %d: |s| %r kg m vs %r" % (k, ue, ut))


def close(a, b, tol):
    x = ens(a)["residual_unbalance_abs_final"][()]
    y = ens(b)["residual_unbalance_abs_final"][()]
    r = np.max(np.abs(x - y) / np.abs(y))
    print("largest relative difference %.3g (tolerance %g)" % (r, tol))
    if not r <= tol:
        fail("differ")


if __name__ == "__main__":
    m = sys.argv[1]
    if m == "same":
        same(sys.argv[2], sys.argv[3])
    elif m == "params":
        params(sys.argv[2], int(sys.argv[3]))
    elif m == "member":
        member(sys.argv[2], int(sys.argv[3]), sys.argv[4])
    elif m == "close":
        close(sys.argv[2], sys.argv[3], float(sys.argv[4]))
    else:
        fail("unknown mode " + m)
