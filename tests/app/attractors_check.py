"""attractors_check.py: independent checks of the attractor classes of `autobal rotor ensemble`
(tests/app/attractors.sh).  The rotor-housing's linearization is written here from the model
documentation (docs/rotor.md: the lumped coefficients (2.7)-(2.11) from the hardware values of a
configuration file, equations (3.2) without balls), read with configparser, not from the archive:

  circulating ARCHIVE INI   the member circulates; nu from the kept series (the ball's absolute angle
                            over the final window) equals the archived circulation_frequency; the
                            archived natural_frequency is the forward mode of the linearization at
                            the speed nearest to |nu| (numpy eigenvalues); nu lies below it (a ball
                            held on the lower flank of the resonance) and far from the spin speed
  balanced ARCHIVE INI      the member balanced; its final ball angles are the closed form (3.14)
                            psi0 + pi -/+ arccos(m0 r0 / (2 m r))
  heavy ARCHIVE INI         the member is on the heavy side; the speed is below the first forward
                            critical speed of the linearization (f_fwd(w) = w, bisection), and both
                            balls sit where the steady response of the balancer's centre D to the
                            total unbalance (rotor unbalance plus the balls at their final angles)
                            points: the balls' equilibrium condition, (3.4) with phi'' = 0, phi' = w
  map ARCHIVE JSON OUT      the per-member classes: dimensions, units, legend; counts against the
                            --json summary and the group's attributes; the console map (OUT) against
                            the classes, with the symbols of the legend written here
"""
import configparser
import json
import sys

import h5py
import numpy as np

fail = 0


def check(what, cond):
    global fail
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        fail = 1


def read_ini(path):
    c = configparser.ConfigParser(inline_comment_prefixes=(";",))
    c.read(path)
    return c


def lumped(c):
    r, s = c["rotor"], c["supports"]
    g = lambda sec, k: float(sec[k])
    lL, lR = g(s, "l_L"), g(s, "l_R")
    L = dict(M=g(r, "M_k") + g(r, "m_p"), A=g(r, "A_k") + g(r, "A_p"), C=g(r, "C_p"))
    for p in "ch":
        L[p + "_x"] = g(s, p + "_Lx") + g(s, p + "_Rx")
        L[p + "_y"] = g(s, p + "_Ly") + g(s, p + "_Ry")
        L[p + "_alpha"] = g(s, p + "_Ly") * lL**2 + g(s, p + "_Ry") * lR**2
        L[p + "_beta"] = g(s, p + "_Lx") * lL**2 + g(s, p + "_Rx") * lR**2
        L[p + "_xbeta"] = g(s, p + "_Lx") * lL - g(s, p + "_Rx") * lR
        L[p + "_yalpha"] = g(s, p + "_Ly") * lL - g(s, p + "_Ry") * lR
    return L


def matrices(L, w):
    """M q'' + D q' + K q = f, q = (x, y, alpha, beta), (3.2) without balls; D includes C w."""
    Mm = np.diag([L["M"], L["M"], L["A"], L["A"]])
    D = np.array([[L["h_x"], 0, 0, -L["h_xbeta"]],
                  [0, L["h_y"], L["h_yalpha"], 0],
                  [0, L["h_yalpha"], L["h_alpha"], L["C"] * w],
                  [-L["h_xbeta"], 0, -L["C"] * w, L["h_beta"]]])
    K = np.array([[L["c_x"], 0, 0, -L["c_xbeta"]],
                  [0, L["c_y"], L["c_yalpha"], 0],
                  [0, L["c_yalpha"], L["c_alpha"], 0],
                  [-L["c_xbeta"], 0, 0, L["c_beta"]]])
    return Mm, D, K


def modes(L, w):
    """(frequency Im lambda > 0, forward?) of the 4 modes at spin w."""
    Mm, D, K = matrices(L, w)
    Mi = np.linalg.inv(Mm)
    S = np.block([[np.zeros((4, 4)), np.eye(4)], [-Mi @ K, -Mi @ D]])
    lam, V = np.linalg.eig(S)
    out = []
    for k in np.argsort(-lam.imag)[:4]:
        v = V[:4, k]
        fwd = abs(v[0] + 1j * v[1]) ** 2 * L["M"] + abs(v[3] - 1j * v[2]) ** 2 * L["A"]
        bwd = abs(v[0] - 1j * v[1]) ** 2 * L["M"] + abs(v[3] + 1j * v[2]) ** 2 * L["A"]
        out.append((lam[k].imag, fwd > bwd))
    return sorted(out)


def member(path):
    f = h5py.File(path, "r")
    return f, f["rotor/ensemble"]


def circulating(path, ini):
    c = read_ini(ini)
    L = lumped(c)
    w = float(c["rotor"]["omega"])
    f, g = member(path)
    cls = int(g["attractor"][()].ravel()[0])
    nu = float(g["circulation_frequency"][()].ravel()[0])
    fn = float(g["natural_frequency"][()].ravel()[0])
    check("class 4 circulating (legend: %s)" % g["attractor"].attrs["legend"], cls == 4)
    # nu from the kept series: the ball that turned at least 2 times relative to the rotor over the
    # final window of window_revs revolutions
    s = g["series/member_0"]
    t = s["time"][:]
    win = float(g.attrs["attractor_window_revs"]) * 2 * np.pi / w
    k0 = np.searchsorted(t, t[-1] - win * (1 + 1e-12))
    rates = []
    for b in (1, 2):
        phi = s["state_phi_%d" % b][:]
        turns = ((phi[-1] - w * t[-1]) - (phi[k0] - w * t[k0])) / (2 * np.pi)
        if abs(turns) >= 2:
            rates.append((phi[-1] - phi[k0]) / (t[-1] - t[k0]))
    check("one ball circulates in the series (%d)" % len(rates), len(rates) == 1)
    if rates:
        check("nu = %.9g rad/s from the series, archive %.9g" % (rates[0], nu), abs(rates[0] - nu) <= 1e-9 * abs(nu))
    fw = [fr for fr, fwd in modes(L, w) if fwd]
    near = min(fw, key=lambda fr: abs(fr - abs(nu)))
    check("forward natural frequencies at %g rad/s (numpy): %s; nearest to nu %.9g, archive %.9g"
          % (w, ", ".join("%.6g" % x for x in fw), near, fn), abs(near - fn) <= 1e-8 * fn)
    check("nu %.6g below it (the lower flank of the resonance), ratio %.4f" % (nu, nu / near), 0 < nu < near)
    check("nu far from the spin %g (the ball lags by %.4g rad/s)" % (w, w - nu), w - nu > 0.2 * w)
    print("summary: nu %.6g rad/s, natural frequency %.6g rad/s, ratio %.4f" % (nu, near, nu / near))


def balanced(path, ini):
    c = read_ini(ini)
    p = c["plane1"]
    f, g = member(path)
    cls = int(g["attractor"][()].ravel()[0])
    check("class 1 balanced", cls == 1)
    s0 = float(p["m0"]) * float(p["r0"])
    m = [float(x) for x in p["ball_mass"].split(",")]
    r = [float(x) for x in p["ball_radius"].split(",")]
    a = m[0] * r[0]
    psi0 = float(p["psi0"])
    d = np.arccos(s0 / (2 * a))
    want = np.sort(np.angle(np.exp(1j * np.array([psi0 + np.pi - d, psi0 + np.pi + d]))))
    got = np.sort(g["final_angle"][()].reshape(-1))
    check("final angles %s vs the closed form (3.14) %s within 0.01 rad" % (got, want), np.all(np.abs(got - want) < 0.01))


def heavy(path, ini):
    c = read_ini(ini)
    L = lumped(c)
    w = float(c["rotor"]["omega"])
    p = c["plane1"]
    f, g = member(path)
    cls = int(g["attractor"][()].ravel()[0])
    check("class 2 heavy_side", cls == 2)
    # first forward critical speed: f_fwd(W) = W for the lowest forward mode, by bisection
    h = lambda W: min(fr for fr, fwd in modes(L, W) if fwd) - W
    lo, hi = 1.0, 2000.0
    check("a forward crossing in (1, 2000) rad/s", h(lo) > 0 > h(hi))
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if h(mid) > 0 else (lo, mid)
    check("spin %g rad/s below the first forward critical speed %.6g rad/s (numpy)" % (w, lo), w < lo)
    # steady response of D to the total unbalance S e^{i psi_s} at w: forcing of (3.2) from s'' terms
    psi = g["final_angle"][()].reshape(-1)
    m = [float(x) for x in p["ball_mass"].split(",")]
    r = [float(x) for x in p["ball_radius"].split(",")]
    d = float(p["d"])
    S = float(p["m0"]) * float(p["r0"]) * np.exp(1j * float(p["psi0"])) + sum(mi * ri * np.exp(1j * q) for mi, ri, q in zip(m, r, psi))
    F = w**2 * S * np.array([1.0, -1j, 1j * d, d])  # x, y, alpha, beta: Re(F e^{i w t})
    Mm, D, K = matrices(L, w)
    Q = np.linalg.solve(K + 1j * w * D - w**2 * Mm, F)
    U, V = Q[0] + d * Q[3], Q[1] - d * Q[2]
    dirD = np.angle(U + 1j * V)  # the forward orbit's direction relative to the rotor
    back = abs(U - 1j * V) / abs(U + 1j * V)
    check("D's orbit nearly circular (backward/forward %.2e)" % back, back < 1e-2)
    err = [abs(np.angle(np.exp(1j * (q - dirD)))) for q in psi]
    check("both balls (%s rad) where D's deflection points (%.6f rad): off by %s rad" % (psi, dirD, np.round(err, 5)),
          max(err) < 0.02)


SYMBOL = {0: "?", 1: "#", 2: "h", 3: "f", 4: "c", 5: "p", 6: "i"}


def map_check(path, js, out):
    f, g = member(path)
    a = g["attractor"]
    cls = a[()]
    names = [n.decode() if isinstance(n, bytes) else n for n in a.attrs.get("DIMENSION_LABELS", [])]
    check("attractor over (psi_1, psi_2) %s, shape %s" % (names, cls.shape), cls.shape == g["balanced"].shape and cls.ndim == 2)
    check("units 1 and a description", a.attrs["units"] in ("1", b"1") and len(a.attrs["long_name"]) > 20)
    legend = a.attrs["legend"]
    legend = legend.decode() if isinstance(legend, bytes) else legend
    names = dict((int(x.split()[0]), x.split()[1]) for x in legend.split(", "))
    check("legend of 7 classes: %s" % legend, sorted(names) == list(range(7)))
    d = json.load(open(js))
    counts = np.bincount(cls.ravel(), minlength=7)
    for k, n in names.items():
        check("count %s: dataset %d, json %d, attribute %d" % (n, counts[k], d["attractors"][n], g.attrs["n_attractor_" + n]),
              counts[k] == d["attractors"][n] == g.attrs["n_attractor_" + n])
    check("balanced class = balanced flag where it stopped at balance",
          np.all((cls == 1) >= ((g["balanced"][()] == 1) & (g["status"][()] == 2))))
    nu = g["circulation_frequency"][()]
    check("circulation_frequency finite exactly for class 4 (rad/s)",
          np.array_equal(np.isfinite(nu), cls == 4) and g["circulation_frequency"].attrs["units"] in ("rad/s", b"rad/s"))
    lines = open(out).read().splitlines()
    i = [k for k, l in enumerate(lines) if "basin of attraction" in l][0]
    rows = [l.strip() for l in lines[i + 1:i + 1 + cls.shape[0]]]
    want = ["".join(SYMBOL[int(v)] for v in row) for row in cls]
    check("console map %s = the classes %s" % (rows, want), rows == want)


if __name__ == "__main__":
    cmd = sys.argv[1]
    {"circulating": circulating, "balanced": balanced, "heavy": heavy, "map": map_check}[cmd](*sys.argv[2:])
    sys.exit(fail)
