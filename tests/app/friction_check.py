#!/usr/bin/python3
"""Checks of `autobal rotor transient` with ball friction (tests/app/friction.sh).

  exact A.h5        [friction] law = exact, rotating frame, dt_out small: the attributes (law, ball_f,
                    ball_mu with units 1), the columns p1_b<i>_stuck (0/1, unit 1) and p1_b<i>_N (N > 0,
                    within 5 % of m r phi'^2: D's acceleration is small against r Omega^2 here); a
                    sample flagged stuck has psi' = 0 exactly and the same psi as the previous stuck
                    sample of that interval; the summary's time stuck per ball equals the sampled
                    stuck time within the number of switches times dt_out; the counts are attributes
  regularized A.h5  law = regularized: the attributes (u_eps in rad/s), stuck flags all 0, N > 0
  none A.h5         no friction: no _stuck or _N column and no friction attribute (the old layout)
  frames F.h5 R.h5  the same exact-law run in both frames: equal stuck flags and switch counts, motion,
                    N and stuck times within the integration tolerance
"""
import sys

import h5py
import numpy as np


def fail(msg):
    print("FAIL " + msg)
    sys.exit(1)


def s(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def balls(g):
    return sorted({k.split("_")[1] for k in g.keys() if k.startswith("p1_b") and k.endswith("_psi")})


def common(h):
    g = h["/rotor/transient"]
    p1 = h["/rotor/plane1"]
    for k in ("ball_f", "ball_mu"):
        if k not in p1.attrs or s(p1.attrs[k + "_units"]) != "1":
            fail("/rotor/plane1 lacks %s (unit 1)" % k)
    if np.any(p1.attrs["ball_mu"] < p1.attrs["ball_f"]):
        fail("mu < f in the archive")
    m, r = p1.attrs["ball_mass"], p1.attrs["ball_radius"]
    for i, b in enumerate(balls(g)):
        st, N = g["p1_%s_stuck" % b], g["p1_%s_N" % b]
        if s(st.attrs["units"]) != "1" or s(N.attrs["units"]) != "N":
            fail("units of the friction columns")
        n = N[...]
        if not np.all(n > 0):
            fail("N <= 0 in p1_%s_N" % b)
        rate = g["p1_%s_phi_rate" % b][...]
        rel = np.max(np.abs(n / (m[i] * r[i] * rate ** 2) - 1))
        if rel > 0.05:
            fail("N of ball %s differs from m r phi'^2 by %.3g" % (b, rel))
    return g


def exact(path):
    h = h5py.File(path, "r")
    g = common(h)
    if s(g.attrs["friction"]) != "exact":
        fail("friction attribute")
    t = g["time"][...]
    dt = t[1] - t[0]
    n_switch = g.attrs["friction_sticks"] + g.attrs["friction_slips"] + g.attrs["friction_reversals"]
    tstuck = g.attrs["p1_ball_time_stuck"]
    for i, b in enumerate(balls(g)):
        st = g["p1_%s_stuck" % b][...]
        if not set(np.unique(st)) <= {0.0, 1.0}:
            fail("stuck flags not 0/1")
        psi, psid = g["p1_%s_psi" % b][...], g["p1_%s_psi_rate" % b][...]
        if np.any(psid[st == 1] != 0.0):
            fail("a stuck sample with psi' != 0")
        for k in range(1, len(t)):
            if st[k] == 1 and st[k - 1] == 1 and psi[k] != psi[k - 1]:
                fail("ball %s moved while stuck at t = %g" % (b, t[k]))
        sampled = dt * np.sum(st == 1)
        if abs(sampled - tstuck[i]) > (n_switch + 2) * dt:
            fail("time stuck of ball %s: summary %.6g s, sampled %.6g s" % (b, tstuck[i], sampled))
        print("ball %s: time stuck %.6g s (summary), %.6g s (samples); stuck at the end %d" %
              (b, tstuck[i], sampled, g.attrs["p1_ball_stuck_final"][i]))
        if g.attrs["p1_ball_stuck_final"][i] != st[-1]:
            fail("final stuck flag")
    if g.attrs["friction_sticks"] < 1 or g.attrs["friction_slips"] < 1:
        fail("expected sticks and slips")


def regularized(path):
    h = h5py.File(path, "r")
    g = common(h)
    if s(g.attrs["friction"]) != "regularized" or s(g.attrs["friction_u_eps_units"]) != "rad/s":
        fail("regularized attributes")
    for b in balls(g):
        if np.any(g["p1_%s_stuck" % b][...] != 0):
            fail("a stuck flag under the regularized law")
    if "friction_sticks" in g.attrs:
        fail("switch counts under the regularized law")


def none(path):
    h = h5py.File(path, "r")
    g = h["/rotor/transient"]
    if any(k.endswith("_stuck") or k.endswith("_N") for k in g.keys()):
        fail("a friction column without friction")
    if any("friction" in k for k in g.attrs.keys()) or "ball_f" in h["/rotor/plane1"].attrs:
        fail("a friction attribute without friction")


def frames(pf, pr):
    """The same exact-law run in the fixed and the rotating frame: the switching happens at the
    same times (equal stuck flags at every sample), the motion agrees to the integration tolerance."""
    a, b = h5py.File(pf, "r")["/rotor/transient"], h5py.File(pr, "r")["/rotor/transient"]
    if len(a["time"]) != len(b["time"]):
        fail("sample counts differ")
    amp = np.max(np.abs(a["x"][:]))
    eq = max(np.max(np.abs(a[k][:] - b[k][:])) for k in ("x", "y")) / amp
    names = [k[:-4] for k in a.keys() if k.endswith("_psi") and "_b" in k]
    ep = max(np.max(np.abs(a[n + "_psi"][:] - b[n + "_psi"][:])) for n in names)
    en = max(np.max(np.abs(a[n + "_N"][:] / b[n + "_N"][:] - 1)) for n in names)
    flags = all(np.array_equal(a[n + "_stuck"][:], b[n + "_stuck"][:]) for n in names)
    same_counts = all(a.attrs[k] == b.attrs[k] for k in ("friction_sticks", "friction_slips", "friction_reversals"))
    dts = max(np.max(np.abs(a.attrs[k] - b.attrs[k])) for k in a.attrs.keys() if k.endswith("_ball_time_stuck"))
    print("fixed vs rotating: %d balls, |dx|/max|x| %.3g, psi %.3g rad, N %.3g relative, time stuck %.3g s"
          % (len(names), eq, ep, en, dts))
    if not (flags and same_counts and eq < 1e-6 and ep < 1e-6 and en < 1e-6 and dts < 1e-8):
        fail("frames disagree")


if __name__ == "__main__":
    if sys.argv[1] == "frames":
        frames(sys.argv[2], sys.argv[3])
    else:
        {"exact": exact, "regularized": regularized, "none": none}[sys.argv[1]](sys.argv[2])
