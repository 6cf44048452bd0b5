"""Undamped verdict of `autobal pendulum roots` (H = h = 0) against an independent computation
(run by tests/app/undamped_verdict.sh).  Usage: undamped_verdict_check.py AUTOBAL

Nothing expected here comes from autobal.  The reference verdict is computed from the
linearization (5) of docs/pendulum.md alone, in 50-digit mpmath arithmetic: the first-order
matrix A of (5) (state q, q', q = (xi, eta, alpha, beta)), its eigenvalues (mp.eig), and

    stable   <=>  every eigenvalue on the imaginary axis and semisimple
                  (a cluster of m coincident eigenvalues needs nullity(A - lambda I) = m),

with the structural pair lambda = 0 of k = 0 (the family of balanced states psi = -phi and its
rate; multiplicity 2, one eigenvector) left out, as docs/pendulum.md says.  n_right_half_plane
is the number of eigenvalues with Re > 0.  The critical speeds around which the points are
placed come from SymPy: the discriminant of (10) in x as a polynomial in W = R_w^2 with the
exact rational R_m, k of the run (k = 0: the cubic of (10) and a0 = 0; k = 1: the quartic f(nu)
of (15) and the touch (18)).  Points: R_w = R_wc (1 + d) for d = +-1e-1, 1e-4, 1e-8, 1e-12, 1e-14, 1e-15 at every
critical speed, the case of issue 18 (R_m = 0.1, k = 0, R_w = 2), and the exact double roots
R_w = 0 and (k = 0) R_w = 1.  autobal may answer "marginal" only within 1e-13 relative of a
critical speed (the rounding bound of its long-double criterion; documented in docs/pendulum.md);
every other answer must equal the reference.

In the sanitizer build (environment SANITIZE=1) autobal still runs at every point (the C code under
ASan/UBSan as in the Release pass), but the 50-digit reference, pure Python and the same in both builds,
is computed at every 4th point near the critical speeds only (the Release pass compares all of them).
"""
import json
import os
import subprocess
import sys
from fractions import Fraction

import mpmath as mp
import sympy as sp

mp.mp.dps = 50
AUTOBAL = sys.argv[1]
MARGINAL_BAND = 1e-13
THIN = 4 if os.environ.get("SANITIZE", "0") == "1" else 1
failures = 0
checks = 0


def check(what, ok, detail=""):
    global failures, checks
    checks += 1
    if not ok:
        failures += 1
        print("FAIL " + what + (": " + detail if detail else ""))


def run_roots(Rm, Rw, k):
    out = subprocess.run([AUTOBAL, "pendulum", "roots", "--json", "-s", "pendulum.H=0", "-s", "pendulum.h=0",
                          "-s", "pendulum.R_m=%r" % Rm, "-s", "pendulum.R_w=%r" % Rw, "-s", "pendulum.k=%r" % k],
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError("autobal failed: " + out.stderr)
    return json.loads(out.stdout)


def first_order_matrix(Rm, Rw, k):
    """The 8x8 matrix of (5) with H = h = 0 (s = sin psi0, c = cos psi0 with 4 s^2 c^2 = k)."""
    Rm, Rw, k = mp.mpf(Rm), mp.mpf(Rw), mp.mpf(k)
    r = mp.sqrt(1 - k)  # cos(2 psi0) >= 0 for psi0 in [0, pi/4]
    c, s = mp.sqrt((1 + r) / 2), mp.sqrt((1 - r) / 2)
    W = Rw**2
    # M q'' + G q' + K q = 0, rows: the four equations of (5)
    M = mp.matrix([[1, 0, -Rm * c, -Rm * c],
                   [0, 1, -Rm * s, Rm * s],
                   [-c, -s, 1, 0],
                   [-c, s, 0, 1]])
    G = mp.matrix([[0, -2 * Rw, 2 * Rm * Rw * s, -2 * Rm * Rw * s],
                   [2 * Rw, 0, -2 * Rm * Rw * c, -2 * Rm * Rw * c],
                   [-2 * Rw * s, 2 * Rw * c, 0, 0],
                   [2 * Rw * s, 2 * Rw * c, 0, 0]])
    K = mp.matrix([[1 - W, 0, Rm * W * c, Rm * W * c],
                   [0, 1 - W, Rm * W * s, -Rm * W * s],
                   [W * c, W * s, 0, 0],
                   [W * c, -W * s, 0, 0]])
    Mi = mp.inverse(M)
    A = mp.zeros(8, 8)
    for i in range(4):
        A[i, 4 + i] = 1
    MK, MG = Mi * K, Mi * G
    for i in range(4):
        for j in range(4):
            A[4 + i, j] = -MK[i, j]
            A[4 + i, 4 + j] = -MG[i, j]
    return A


def nullity(B, tol):
    sv = mp.svd_c(B, compute_uv=False)
    return sum(1 for v in sv if abs(v) < tol)


def reference(Rm, Rw, k):
    """(verdict, n_rhp) from the eigenvalues of (5) and their semisimplicity."""
    A = first_order_matrix(Rm, Rw, k)
    ev = mp.eig(A, left=False, right=False)
    scale = max([1] + [abs(e) for e in ev])
    n_rhp = sum(1 for e in ev if mp.re(e) > mp.mpf(10) ** -15 * scale)
    # clusters of coincident eigenvalues (a double root splits by ~sqrt(1e-50), a triple by
    # ~1e-17; distinct ones are >= 1e-8 apart at the points below)
    tol = mp.mpf(10) ** -15 * scale
    clusters = []
    for e in ev:
        for cl in clusters:
            if abs(cl[0] - e) < tol:
                cl.append(e)
                break
        else:
            clusters.append([e])
    stable = n_rhp == 0
    for cl in clusters:
        lam = sum(cl) / len(cl)
        if abs(mp.re(lam)) > mp.mpf(10) ** -15 * scale:
            stable = False
            continue
        m, nul = len(cl), None
        if m == 1:
            continue
        nul = nullity(A - lam * mp.eye(8), mp.mpf(10) ** -12 * scale)
        if k == 0 and abs(lam) < tol:
            m, nul = m - 2, nul - 1  # the structural pair: multiplicity 2, one eigenvector
        if nul < m:
            stable = False
    return ("stable" if stable else "unstable"), n_rhp


def critical_W(Rm, k):
    """Positive roots W of the discriminant of (10) in x (exact rational R_m, k), as mpf."""
    x, W = sp.symbols("x W")
    R, K = sp.Rational(Fraction(Rm)), sp.Rational(Fraction(k))
    a0 = 2 * R * W**2 * (W - 1)
    a2 = (W - 1)**2 + 2 * R * W * (W + 6)
    a4 = 2 * (1 - R) * (W + 1)
    a6 = 1 - 2 * R
    cands = []
    if K == 0:
        disc = sp.discriminant(a6 * x**3 + a4 * x**2 + a2 * x + a0, x)
        cands.append(sp.Integer(1))
    elif K == 1:
        # (15): four real nu of f; its discriminant in nu, as a polynomial in Rr = R_w
        nu, Rr = sp.symbols("nu Rr")
        f = (1 - R) * nu**4 - 2 * Rr * nu**3 + (Rr**2 - 1) * nu**2 + 2 * Rr * nu - Rr**2
        d = sp.Poly(sp.discriminant(f, nu), Rr)
        m0 = min(e[0] for e in d.monoms())  # the root R_w = 0 divided out (as below)
        d = sp.Poly(sp.expand(d.as_expr() / Rr**m0), Rr)
        out = [mp.mpf(str(sp.re(r)))**2 for r in d.nroots(n=60, maxsteps=400)
               if abs(sp.im(r)) < 1e-40 and sp.re(r) > 0]
        if R < sp.Rational(1, 4):  # the touch (18)
            out.append(mp.mpf(2 * (1 - 2 * mp.mpf(Rm))) / (1 - 4 * mp.mpf(Rm))**2)
        return sorted(out)
    else:
        P = x * (a6 * x**3 + a4 * x**2 + a2 * x + a0) + K * R**2 * (x + W)**4
        disc = sp.discriminant(sp.expand(P), x)
    poly = sp.Poly(sp.expand(disc), W)
    # the root W = 0 (of some multiplicity) divided out first: nroots converges slowly at multiple roots
    m0 = min(e[0] for e in poly.monoms())
    poly = sp.Poly(sp.expand(poly.as_expr() / W**m0), W)
    out = [mp.mpf(str(sp.re(r))) for r in poly.nroots(n=60, maxsteps=400) if abs(sp.im(r)) < 1e-40 and sp.re(r) > 0]
    out += [mp.mpf(str(c)) for c in cands]
    return sorted(set(out))


def check_point(Rm, Rw, k, near=None, with_reference=True):
    """Compare autobal with the reference at one point; near: relative distance to the nearest
    critical speed (None: not near one).  with_reference False: autobal only (sanitizer build)."""
    d = run_roots(Rm, Rw, k)
    kk = d["parameters"]["k"]  # the k autobal used (sin^2(2 psi0) rounded), exactly
    got = d["verdict"]
    where = "R_m = %r, k = %r, R_w = %r" % (Rm, kk, Rw)
    check("criterion is (10) at " + where, d["criterion"] == "exact undamped criterion (10)", d["criterion"])
    if not with_reference:
        check("a verdict at " + where, got in ("stable", "unstable", "marginal"), got)
        return got, None
    ref, nr = reference(Rm, Rw, kk)
    if got == "marginal":
        ok = near is not None and near < MARGINAL_BAND
        check("marginal only within %g of a critical speed at %s" % (MARGINAL_BAND, where), ok,
              "distance %s, reference %s" % (near, ref))
        return got, ref
    check("verdict at " + where, got == ref, "autobal %s, reference %s (distance %s)" % (got, ref, near))
    check("n_right_half_plane at " + where, d["n_right_half_plane"] == nr,
          "autobal %d, reference %d" % (d["n_right_half_plane"], nr))
    # roots: unstable iff some Re > 0 beyond rounding (except for the special double roots)
    return got, ref


def main():
    # 1. the case of issue 18: R_m = 0.1, k = 0, R_w = 2 (max Re 0.159)
    d = run_roots(0.1, 2.0, 0.0)
    ref, nr = reference(0.1, 2.0, 0.0)
    ev = mp.eig(first_order_matrix(0.1, 2.0, 0.0), left=False, right=False)
    mre = max(mp.re(e) for e in ev)
    check("issue 18 case: reference unstable with max Re 0.1591082182137...",
          ref == "unstable" and abs(mre - mp.mpf("0.1591082182137382")) < 1e-15, mp.nstr(mre, 17))
    check("issue 18 case: autobal says unstable (was marginal)", d["verdict"] == "unstable", d["verdict"])
    check("issue 18 case: n_right_half_plane = 2", d["n_right_half_plane"] == nr == 2, str(d["n_right_half_plane"]))
    check("issue 18 case: max_real == reference to 1e-12", abs(d["max_real"] - float(mre)) < 1e-12,
          "%r vs %s" % (d["max_real"], mp.nstr(mre, 17)))
    check("issue 18 case: verdict_roots unstable, agrees", d["verdict_roots"] == "unstable")

    # 2. exact double roots of (10) for double input
    for Rm, Rw, k, what in [(0.1, 1.0, 0.0, "k = 0, R_w = 1 (a0 = 0)"), (0.1, 0.0, 0.0, "R_w = 0, k = 0"),
                            (0.2, 0.0, 0.5, "R_w = 0, k = 0.5")]:
        d = run_roots(Rm, Rw, k)
        ref, nr = reference(Rm, Rw, k)
        check("%s: reference unstable (lambda = 0 not semisimple)" % what, ref == "unstable")
        check("%s: autobal unstable" % what, d["verdict"] == ref, d["verdict"])

    # 3. dense points around every critical speed
    cases = [(0.1, 0.0), (0.2, 0.0), (0.1, 0.5), (0.2, 0.3), (0.05, 0.9), (0.3, 0.7), (0.1, 1.0), (0.2, 1.0),
             (0.24, 0.999)]
    deltas = [s * 10.0**-e for e in (1, 4, 8, 12, 14, 15) for s in (1, -1)]
    npts = nmarg = nstab = nunst = 0
    for Rm, k in cases:
        d0 = run_roots(Rm, 1.5, k)
        kk = d0["parameters"]["k"]
        Ws = critical_W(Rm, kk)
        # (discriminant roots below R_w = 1e-3 are left out: there every root is O(R_w^2) small
        # and the reference's threshold for "on the axis" would decide, not the criterion)
        rws = [mp.sqrt(w) for w in Ws if 1e-6 < w < 1e6]
        print("R_m = %g, k = %r: %d critical speeds (discriminant roots) %s" %
              (Rm, kk, len(rws), ", ".join(mp.nstr(r, 12) for r in rws)))
        for rc in rws:
            for dl in deltas:
                Rw = float(rc * (1 + mp.mpf(dl)))
                near = min(float(abs(mp.mpf(Rw) / r - 1)) for r in rws)
                got, ref = check_point(Rm, Rw, k, near, npts % THIN == 0)
                npts += 1
                nmarg += got == "marginal"
                nstab += ref == "stable"
                nunst += ref == "unstable"
    print("%d points near critical speeds (the reference at every %s): %d stable, %d unstable by the reference; "
          "autobal marginal at %d" % (npts, "one" if THIN == 1 else "%dth" % THIN, nstab, nunst, nmarg))
    check("both verdicts occur near the boundaries", nstab > 50 // THIN and nunst > 50 // THIN, "%d, %d" % (nstab, nunst))
    print("%d checks, %d failed" % (checks, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
