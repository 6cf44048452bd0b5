#!/usr/bin/env python3
"""Checks of tests/app/ensemble_dip.sh (a temporary speed reduction, data/washer_dip.ini, as an
ensemble).  The expected values come from the drive table as the test writes it (speeds in rpm,
converted here), not from the program's output.  Modes:
  table A.h5 GROUP T OMEGA_RPM   the drive recorded on GROUP (rotor/ensemble or rotor/transient):
                                 drive_mode = table, drive_table_t = T (s), drive_table_omega =
                                 OMEGA_RPM * pi / 30 (rad/s), both comma-separated, within 1e-12
  final E.h5 OMEGA_RPM M_P       every member ran to t_end and ends at the table's last speed: its
                                 grade G = U Omega / m_p (ISO 21940-11, mm/s) with Omega = OMEGA_RPM
                                 (the table's last speed) and U its residual unbalance (kg m)
  profile T.h5 T OMEGA_RPM       `rotor transient`: Omega(t) is the linear interpolation of the table
                                 at every output time, constant after its last point
  slip T.h5 T0 T1                `rotor transient`: while the drum turns at the dip speed (t in
                                 [T0, T1]) every ball moves relative to the drum (|dpsi/dt| > 1e-6
                                 rad/s; a stuck ball keeps the ~1e-10 rad/s of its stick event) at
                                 most output times (at 900 rpm g / (r Omega^2) = 1.4 mu: the weight
                                 exceeds the stiction during every revolution)
"""
import sys
import h5py
import numpy as np


def fail(msg):
    print("FAIL", msg)
    sys.exit(1)


def floats(s):
    return np.array([float(v) for v in s.split(",")])


def rpm(s):
    return floats(s) * np.pi / 30.0


def table(path, group, t, om):
    a = h5py.File(path, "r")[group].attrs
    mode = a.get("drive_mode")
    mode = mode.decode() if isinstance(mode, bytes) else mode
    if mode != "table":
        fail("%s: drive_mode %r, want 'table'" % (group, mode))
    for key, want in (("drive_table_t", floats(t)), ("drive_table_omega", rpm(om))):
        got = np.atleast_1d(a[key])
        if got.shape != want.shape or np.max(np.abs(got - want)) > 1e-12 * np.max(np.abs(want)):
            fail("%s@%s = %s, want %s" % (group, key, got, want))
    print("%s: drive table of %d points recorded (t %s s; omega %s rpm)" % (group, len(want), t, om))


def final(path, om, m_p):
    g = h5py.File(path, "r")["rotor/ensemble"]
    omega = rpm(om)[-1]
    t_end = float(np.atleast_1d(h5py.File(path, "r")["rotor/ensemble"].attrs["t_end"])[0])
    if not np.all(g["status"][()] == 0):
        fail("status %s (want 0: reached t_end)" % g["status"][()])
    if np.max(np.abs(g["t_reached"][()] - t_end)) > 1e-9 * t_end:
        fail("t_reached %s, t_end %r" % (g["t_reached"][()], t_end))
    u = g["residual_unbalance_abs_final"][()]
    grade = g["balance_grade_final"][()]
    want = u / float(m_p) * omega * 1e3
    r = np.max(np.abs(grade - want) / want)
    print("%d members reached t_end = %g s; grade = U Omega / m_p with Omega = %g rad/s: largest relative "
          "difference %.2g (tolerance 1e-12)" % (len(u), t_end, omega, r))
    if not r <= 1e-12:
        fail("grade differs")


def profile(path, t, om):
    tr = h5py.File(path, "r")["rotor/transient"]
    tt = tr["time"][()]
    got = tr["Omega"][()]
    want = np.interp(tt, floats(t), rpm(om))
    d = np.max(np.abs(got - want))
    print("Omega(t) at %d output times against the table: largest difference %.2g rad/s (tolerance 1e-9); "
          "at the end %.12g rad/s" % (len(tt), d, got[-1]))
    if not d <= 1e-9:
        fail("Omega(t) differs from the table")
    if abs(got[-1] - rpm(om)[-1]) > 1e-9:
        fail("final speed %r, want %r" % (got[-1], rpm(om)[-1]))


def slip(path, t0, t1):
    tr = h5py.File(path, "r")["rotor/transient"]
    tt = tr["time"][()]
    w = (tt >= float(t0)) & (tt <= float(t1))
    n = 0
    while "p1_b%d_psi_rate" % (n + 1) in tr:
        n += 1
    frac = np.array([np.mean(np.abs(tr["p1_b%d_psi_rate" % (i + 1)][()][w]) > 1e-6) for i in range(n)])
    print("%d balls, t in [%s, %s] s (%d output times): fraction of times each moves relative to the "
          "drum: min %.3f (want > 0.5)" % (n, t0, t1, w.sum(), frac.min()))
    if n == 0 or w.sum() < 20 or not frac.min() > 0.5:
        fail("a ball stayed stuck at the dip speed")


if __name__ == "__main__":
    m = sys.argv[1]
    if m == "table":
        table(*sys.argv[2:6])
    elif m == "final":
        final(*sys.argv[2:5])
    elif m == "profile":
        profile(*sys.argv[2:5])
    elif m == "slip":
        slip(*sys.argv[2:5])
    else:
        fail("unknown mode " + m)
