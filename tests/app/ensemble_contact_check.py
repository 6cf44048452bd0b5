#!/usr/bin/env python3
"""Checks of tests/app/ensemble_contact.sh (`autobal rotor ensemble` with ball size and contact).
Modes:
  same A.h5 B.h5            every dataset of /rotor/ensemble equal bit for bit (NaN = NaN), the
                            contact attributes present in both (runs with 1 and 2 threads)
  params A.h5 K             print the parameter values of member K (flat index), as exact decimals
  member A.h5 K T.h5 [N]    member K of the ensemble against the single `rotor transient` run T.h5
                            of the same parameters: impacts, pairs touching at the end, final
                            angles, residual (relative and in kg m); with N: at least N impacts
                            (so that the comparison covers the impact events)
  overlap A.h5 D R          two balls of diameter D (m) on the track of radius R (m), psi_1 and psi_2
                            random: a member fails (status < 0) exactly when its balls overlap at
                            the start, i.e. their angular distance is below the gap angle
                            2 asin(2 D / (4 R)) (docs/device.md section 4), computed here from the
                            parameter values; at least one fails and one runs; the contact
                            quantities are NaN exactly for the failed ones.  Prints the lowest
                            failed member's number last.
  inputs A.h5 D E V         /rotor/plane1 ball_diameter = D (every ball), /rotor/ensemble
                            contact_restitution = E, contact_v_rest = V
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ensemble_common import ens, fail, params as params_of, same as same_of  # noqa: E402


def same(a, b):
    same_of(a, b, ("contact_impacts", "contacts_final"), "contact_restitution")


PARAMS = ("psi_1", "psi_2", "psi_3", "rate_1", "rate_2", "m0", "omega")


def params(path, k):
    params_of(path, k, PARAMS)


def member(path, k, tpath, nmin=0):
    g = ens(path)
    idx = np.unravel_index(k, g["status"].shape)
    a = h5py.File(tpath, "r")["rotor/transient"]
    if g["status"][idx] < 0:
        fail("member %d failed (status %d)" % (k, g["status"][idx]))
    imp_e, imp_t = g["contact_impacts"][idx], a.attrs["contact_impacts"]
    fin_e, fin_t = g["contacts_final"][idx], a.attrs["contacts_final"]
    if imp_e != imp_t or fin_e != fin_t:
        fail("member %d: impacts %r, touching at the end %r (ensemble) vs %r, %r (transient)" % (k, imp_e, fin_e, imp_t, fin_t))
    if imp_e < nmin:
        fail("member %d: %d impacts, fewer than the %d this check needs" % (k, imp_e, nmin))
    res_e, res_t = g["residual_unbalance_final"][idx], a.attrs["residual_unbalance_final"]
    if not abs(res_e - res_t) <= 1e-12 * abs(res_t):
        fail("member %d: residual %r (ensemble) vs %r (transient)" % (k, res_e, res_t))
    ang = g["final_angle"][idx]
    angt = np.array([a["p1_b%d_psi_w" % (i + 1)][-1] for i in range(ang.shape[-1])])
    d = np.max(np.abs(np.angle(np.exp(1j * (ang - angt)))))
    if d > 1e-9:
        fail("member %d: final angles %s vs %s" % (k, ang, angt))
    ue, ut = g["residual_unbalance_abs_final"][idx], np.max(a.attrs["residual_unbalance_abs_final"])
    if not abs(ue - ut) <= 1e-12 * abs(ut):
        fail("member %d: |s| %r kg m vs %r" % (k, ue, ut))
    print("member %d: %d impacts, %d touching at the end, residual %.17g, angles within %.1e rad: equal to rotor transient"
          % (k, imp_e, fin_e, res_e, d))


def overlap(path, d, r):
    g = ens(path)
    st = g["status"][()]
    p1, p2 = g["psi_1"][()], g["psi_2"][()]
    gam = 2 * np.arcsin(2 * d / (4 * r))
    dist = np.abs(np.angle(np.exp(1j * (p2 - p1))))
    want = dist < gam
    if np.any(np.abs(dist - gam) < 1e-9):
        fail("a member on the boundary of overlap: choose another seed")
    if not want.any() or want.all():
        fail("need members that overlap and members that do not (%d of %d overlap)" % (want.sum(), want.size))
    if not np.array_equal(st < 0, want):
        fail("failed members %s, expected (overlap) %s" % (list(np.flatnonzero(st < 0)), list(np.flatnonzero(want))))
    for q in ("contact_impacts", "contacts_final"):
        v = g[q][()]
        if not np.all(np.isnan(v[want])) or np.any(np.isnan(v[~want])):
            fail("%s: NaN exactly for the failed members expected, got %s" % (q, v))
    print("gap angle %.6f rad: members %s overlap (distances %s) and failed (status %s); the other %d ran"
          % (gam, list(np.flatnonzero(want)), np.round(dist[want], 4).tolist(), list(st[want]), int((~want).sum())))
    print(int(np.flatnonzero(want)[0]))


def inputs(path, d, e, v):
    f = h5py.File(path, "r")
    dia = np.atleast_1d(f["rotor/plane1"].attrs["ball_diameter"])
    g = f["rotor/ensemble"].attrs
    if not (np.all(dia == d) and g["contact_restitution"] == e and g["contact_v_rest"] == v):
        fail("ball_diameter %s, contact_restitution %r, contact_v_rest %r; expected %r, %r, %r"
             % (dia, g.get("contact_restitution"), g.get("contact_v_rest"), d, e, v))
    print("ball_diameter %s m, contact_restitution %r, contact_v_rest %r rad/s" % (dia, e, v))


if __name__ == "__main__":
    m = sys.argv[1]
    if m == "same":
        same(sys.argv[2], sys.argv[3])
    elif m == "params":
        params(sys.argv[2], int(sys.argv[3]))
    elif m == "member":
        member(sys.argv[2], int(sys.argv[3]), sys.argv[4], int(sys.argv[5]) if len(sys.argv) > 5 else 0)
    elif m == "overlap":
        overlap(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
    elif m == "inputs":
        inputs(sys.argv[2], *(float(x) for x in sys.argv[3:6]))
    else:
        fail("unknown mode " + m)
