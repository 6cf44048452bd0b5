"""Independent checks of the run-up outputs (/rotor/runup) of `autobal rotor transient` with a
prescribed speed (run by tests/app/runup.sh).  Expected values come from here, not from autobal:

  - the resonance speeds: the Campbell crossings (a natural frequency of the rotor-housing without
    balls equals Omega) from numpy.linalg.eigvals of the 8x8 first-order matrix of (3.2) built from
    the archive's lumped coefficients, refined with scipy.optimize.brentq;
  - the passage times: where the prescribed piecewise-linear profile (the drive attributes) equals
    each of those speeds, solved segment by segment in closed form;
  - captures: where the profile enters and leaves the band (1 -/+ b) w_c, same closed form;
  - the envelope: a brute-force maximum of amp_G over the trailing revolution (rotor angle by
    numpy's cumulative trapezoid of |Omega|), the lag from the psi columns, the time to balance
    after the last passage from the s_rel columns, and against the event-located time to balance
    of /rotor/transient (within one output interval).
Usage: runup_check.py FILE.h5 [capture RESONANCE_COUNT]
"""
import sys

import h5py
import numpy as np
from scipy.optimize import brentq

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures += 1


def s(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def rotor_matrices(L, w):
    M = np.diag([L["M"], L["M"], L["A"], L["A"]])
    H = np.array([[L["h_x"], 0, 0, -L["h_xbeta"]], [0, L["h_y"], L["h_yalpha"], 0],
                  [0, L["h_yalpha"], L["h_alpha"], L["C"] * w], [-L["h_xbeta"], 0, -L["C"] * w, L["h_beta"]]])
    K = np.array([[L["c_x"], 0, 0, -L["c_xbeta"]], [0, L["c_y"], L["c_yalpha"], 0],
                  [0, L["c_yalpha"], L["c_alpha"], 0], [-L["c_xbeta"], 0, 0, L["c_beta"]]])
    return M, H, K


def freqs(L, w):
    M, H, K = rotor_matrices(L, w)
    A = np.block([[np.zeros((4, 4)), np.eye(4)], [-np.linalg.solve(M, K), -np.linalg.solve(M, H)]])
    return np.sort(np.sort(np.linalg.eigvals(A).imag)[-4:])


def crossings(L, hi):
    grid = np.linspace(0.0, hi, 3001)
    f = np.array([freqs(L, x) for x in grid]) - grid[:, None]
    out = []
    for m in range(4):
        for k in np.nonzero(np.sign(f[:-1, m]) != np.sign(f[1:, m]))[0]:
            out.append(brentq(lambda x: freqs(L, x)[m] - x, grid[k], grid[k + 1], xtol=1e-13, rtol=1e-14))
    return np.sort(np.array(out))


def profile(g):
    mode = s(g.attrs["drive_mode"])
    if mode == "ramp":
        tt = np.array([g.attrs["drive_t_a"], g.attrs["drive_t_b"]], float)
        ww = np.array([g.attrs["drive_omega_a"], g.attrs["drive_omega_b"]], float)
    else:
        tt, ww = np.asarray(g.attrs["drive_table_t"], float), np.asarray(g.attrs["drive_table_omega"], float)
    return tt, ww


def profile_crossings(tt, ww, level):
    """(t, direction) where |Omega| of the profile passes `level` (up: from below to >= level)."""
    out = []
    for k in range(len(tt) - 1):
        w0, w1 = abs(ww[k]), abs(ww[k + 1])
        if w0 < level <= w1:
            out.append((tt[k] + (level - w0) / (w1 - w0) * (tt[k + 1] - tt[k]), 1))
        elif w1 < level <= w0:
            out.append((tt[k] + (level - w0) / (w1 - w0) * (tt[k + 1] - tt[k]), -1))
    return out


def main():
    fn = sys.argv[1]
    want_captures = int(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[2] == "capture" else 0
    f = h5py.File(fn, "r")
    g, tr = f["rotor/runup"], f["rotor/transient"]
    L = {k: float(v) for k, v in f["rotor/lumped"].attrs.items() if not k.endswith("_units")}
    tt, ww = profile(tr)
    band = float(g.attrs["capture_band"])
    # (1) resonance speeds: NumPy Campbell crossings up to (1 + b) max |Omega|
    res_np = crossings(L, (1 + band) * np.abs(ww).max())
    res = g["resonance"][:]
    check("resonance units rad/s, rpm attribute = 60/(2 pi) rad/s",
          s(g["resonance"].attrs["units"]) == "rad/s" and np.allclose(g["resonance"].attrs["rpm"], res * 30 / np.pi, rtol=1e-14))
    check("%d resonance speeds, as NumPy finds" % len(res_np), len(res) == len(res_np), "%s vs %s" % (res, res_np))
    if len(res) == len(res_np):
        err = np.abs(res - res_np).max() / res_np.max()
        check("resonance speeds = NumPy Campbell crossings (%s rad/s)" % np.array2string(res_np, precision=6),
              err < 1e-9, "relative %.3g (tolerance 1e-9)" % err)
    # (2) passages: where the prescribed profile equals the NumPy speeds
    want = sorted((t, d, k) for k, x in enumerate(res_np) for t, d in profile_crossings(tt, ww, x))
    pt = g["passage_time"][:] if "passage_time" in g else np.zeros(0)
    check("%d passages, as the profile's closed form" % len(want), len(pt) == len(want), "%d vs %d" % (len(pt), len(want)))
    if len(pt) == len(want) and len(want):
        err = max(abs(a - b[0]) for a, b in zip(pt, want))
        check("passage times = closed-form crossings of the profile (first %.9g s, last %.9g s)" % (want[0][0], want[-1][0]),
              err < 1e-7, "max |diff| %.3g s (tolerance 1e-7 s)" % err)
        check("passage directions and resonance indices",
              list(g["passage_direction"][:]) == [d for _, d, _ in want] and list(g["passage_resonance"][:]) == [k for _, _, k in want])
        check("dims: passage_time over (passage,), units s",
              s(g["passage_time"].attrs["units"]) == "s" and g["passage_time"].dims[0][0].name == "/rotor/runup/passage")
        check("t_last_passage = the last passage", abs(g.attrs["t_last_passage"] - want[-1][0]) < 1e-7)
    # (3) captures: profile stays in the band >= capture_time
    ct = float(g.attrs["capture_time"])
    wantc = []
    for k, x in enumerate(res_np):
        lo, hi = (1 - band) * x, (1 + band) * x
        ins = [(t, +1) for t, d in profile_crossings(tt, ww, lo) if d > 0] + [(t, -1) for t, d in profile_crossings(tt, ww, lo) if d < 0]
        ins += [(t, -1) for t, d in profile_crossings(tt, ww, hi) if d > 0] + [(t, +1) for t, d in profile_crossings(tt, ww, hi) if d < 0]
        ins.sort()
        t_in = tr["time"][0] if lo <= abs(ww[0]) <= hi else None
        for t, e in ins:
            if e > 0:
                t_in = t
            elif t_in is not None:
                if t - t_in >= ct:
                    wantc.append((k, t_in, t))
                t_in = None
        if t_in is not None and tr["time"][-1] - t_in >= ct:
            wantc.append((k, t_in, tr["time"][-1]))
    nc = int(g.attrs["n_captures"])
    check("%d capture(s) (expected by the test: %d; from the profile: %d)" % (nc, want_captures, len(wantc)),
          nc == len(wantc) == want_captures)
    if nc and nc == len(wantc):
        err = max(max(abs(g["capture_t_enter"][i] - c[1]), abs(g["capture_t_leave"][i] - c[2])) for i, c in enumerate(wantc))
        check("capture intervals = where the profile enters and leaves the band", err < 1e-7, "max |diff| %.3g s" % err)
        check("resonance_captured flags", list(np.nonzero(g["resonance_captured"][:])[0]) == sorted({c[0] for c in wantc}))
    # (4) envelope by brute force over the trailing revolution
    t = tr["time"][:]
    w = np.abs(tr["Omega"][:])
    amp = tr["amp_G"][:]
    phi = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))])
    j0 = np.searchsorted(phi, phi - 2 * np.pi * (1 + 1e-9), side="left")
    env = np.array([amp[j0[k]:k + 1].max() for k in range(len(t))])
    env_a = g["envelope"][:]
    ndiff = int(np.sum(env_a != env))
    rel = np.abs(env_a - env).max() / env.max()
    check("envelope(time) = brute-force max of amp_G over the trailing revolution (%d samples)" % len(t),
          ndiff <= 2 and rel < 1e-12, "%d samples differ, max rel %.3g" % (ndiff, rel))
    check("envelope over /rotor/transient/time, units m",
          s(g["envelope"].attrs["units"]) == "m" and g["envelope"].dims[0][0].name == "/rotor/transient/time")
    check("envelope >= amp_G everywhere", bool(np.all(env_a >= amp)))
    # (5) ball lag from the psi columns
    names = sorted(n for n in tr if n.endswith("_psi") and "_b" in n)
    psi = np.stack([tr[n][:] for n in names], axis=1)
    lag = g["ball_lag"][:]
    check("ball_lag(time, ball) = psi(0) - psi(t) of %s" % ", ".join(names),
          lag.shape == psi.shape and np.abs(lag - (psi[0] - psi)).max() < 1e-12)
    # (6) time to balance after the last passage, from the s_rel columns
    tol = float(g.attrs["balance_tol"])
    mon = np.max(np.stack([tr[n][:] for n in tr if n.endswith("_s_rel")], axis=1), axis=1)
    tref = g.attrs["t_last_passage"] if np.isfinite(g.attrs["t_last_passage"]) else t[0]
    above = np.nonzero(~(mon < tol))[0]
    if len(above) and above[-1] == len(t) - 1:
        ttb = np.nan
    else:
        k = above[-1] if len(above) else None
        tb = t[0] if k is None else t[k] + (tol - mon[k]) / (mon[k + 1] - mon[k]) * (t[k + 1] - t[k])
        ttb = max(tb, tref)
    got = g.attrs["time_to_balance_after_last_passage"]
    check("time_to_balance_after_last_passage = %.9g s (from the s_rel columns)" % ttb,
          (np.isnan(ttb) and np.isnan(got)) or abs(got - ttb) < 1e-9, "%.12g" % got)
    if np.isfinite(got) and int(tr.attrs["balanced"]):
        d = abs(got - max(tr.attrs["time_to_balance"], tref))
        check("agrees with the event-located time to balance of /rotor/transient within one output interval",
              d <= tr.attrs["dt_out"], "|diff| %.3g s, dt_out %.3g s" % (d, tr.attrs["dt_out"]))
    print("%d failed" % failures)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
