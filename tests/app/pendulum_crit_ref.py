#!/usr/bin/python3
"""Independent reference for the undamped critical speeds of the two-pendulum balancer.

For R_m, k given as decimal strings (taken exactly as the IEEE doubles the program reads, via
fractions.Fraction(float(s))), the discriminant of P(x) of (10) with respect to x is built
EXACTLY as a polynomial in W = R_w^2 with rational coefficients (SymPy), its positive real
roots are isolated exactly (SymPy's real-root isolation on the square-free part) and refined to
~40 digits; between consecutive roots the verdict is taken at an exact rational midpoint from
the roots of P at 80 digits (mpmath): stable iff every root x is real and <= 0.  A root of the
discriminant where the verdict changes is a critical speed (kind +1 gained, -1 lost above);
one inside a stable region on both sides is a touch (kind 0); the others are dropped, as the
library does.  Nothing here uses autobal.

Usage: pendulum_crit_ref.py R_m k [R_m k ...]
Prints one JSON line per case: {"R_m": s, "k": s, "R_w": [...], "kind": [...],
"stable_lo": [...], "stable_hi": [...]} with R_w as decimal strings (25 digits).
"""
import json
import sys
from fractions import Fraction

import mpmath
import sympy as sp

mpmath.mp.dps = 80
W, x = sp.symbols("W x")


def char_poly(Rm, k):
    # (10): P(x) = x (a6 x^3 + a4 x^2 + a2 x + a0) + k R_m^2 (x + W)^4, straight from the spec
    a0 = 2 * Rm * W**2 * (W - 1)
    a2 = (W - 1) ** 2 + 2 * Rm * W * (W + 6)
    a4 = 2 * (1 - Rm) * (W + 1)
    a6 = 1 - 2 * Rm
    return sp.expand(x * (a6 * x**3 + a4 * x**2 + a2 * x + a0) + k * Rm**2 * (x + W) ** 4)


def stable_at(P, Wv):
    c = sp.Poly(P.subs(W, Wv), x).all_coeffs()
    roots = mpmath.polyroots([mpmath.mpf(sp.Rational(ci).p) / sp.Rational(ci).q for ci in c],
                             maxsteps=400, extraprec=400)
    for r in roots:
        r = mpmath.mpc(r)
        scale = max(abs(r), mpmath.mpf(1))
        if abs(r.imag) > mpmath.mpf(10) ** -50 * scale:
            return False
        if r.real > mpmath.mpf(10) ** -50 * scale:
            return False
    return True


def critical(rm_s, k_s):
    Rm = sp.Rational(Fraction(float(rm_s)))
    k = sp.Rational(Fraction(float(k_s)))
    P = char_poly(Rm, k)
    D = sp.Poly(sp.discriminant(sp.Poly(P, x)), W)
    Dsf = sp.Poly(sp.quo(D, sp.gcd(D, D.diff(W))), W)
    ivs = [iv for iv in Dsf.intervals(eps=sp.Rational(1, 10**12)) if iv[0][1] > 0]
    roots = []
    for (a, b), _m in ivs:
        a, b = sp.Rational(a), sp.Rational(b)
        if b <= 0:
            continue
        if a == b:
            roots.append((a, b))
            continue
        roots.append((max(a, sp.Rational(0)), b))
    # refine each root by exact bisection on the square-free part to ~1e-40 relative
    fine = []
    for a, b in roots:
        if a == b:
            fine.append((a, b))
            continue
        fa = Dsf.eval(a)
        while (b - a) > sp.Rational(1, 10**40) * b:
            m = (a + b) / 2
            fm = Dsf.eval(m)
            if fm == 0:
                a = b = m
                break
            if (fm > 0) == (fa > 0):
                a, fa = m, fm
            else:
                b = m
        fine.append((a, b))
    fine.sort()
    # verdicts on the intervals between the roots
    pts = [sp.Rational(0)] + [(a + b) / 2 for a, b in fine]
    verdicts = []
    for i in range(len(fine) + 1):
        lo = fine[i - 1][1] if i > 0 else sp.Rational(0)
        hi = fine[i][0] if i < len(fine) else 2 * lo + 1
        verdicts.append(stable_at(P, (lo + hi) / 2))
    out_rw, out_kind = [], []
    for i, (a, b) in enumerate(fine):
        l, r = verdicts[i], verdicts[i + 1]
        wv = mpmath.mpf(((a + b) / 2).p) / ((a + b) / 2).q
        if l != r:
            out_rw.append(mpmath.sqrt(wv))
            out_kind.append(1 if r else -1)
        elif l:
            out_rw.append(mpmath.sqrt(wv))
            out_kind.append(0)
    # stable intervals
    lo_l, hi_l = [], []
    edges = [mpmath.mpf(0)] + [mpmath.sqrt(mpmath.mpf(((a + b) / 2).p) / ((a + b) / 2).q) for a, b in fine] + [mpmath.inf]
    cur = None
    for i, v in enumerate(verdicts):
        if v and cur is None:
            cur = edges[i]
        if not v and cur is not None:
            lo_l.append(cur)
            hi_l.append(edges[i])
            cur = None
    if cur is not None:
        lo_l.append(cur)
        hi_l.append(mpmath.inf)
    del pts
    s = lambda v: mpmath.nstr(v, 25) if v != mpmath.inf else "inf"
    return {"R_m": rm_s, "k": k_s, "R_w": [s(v) for v in out_rw], "kind": out_kind,
            "stable_lo": [s(v) for v in lo_l], "stable_hi": [s(v) for v in hi_l]}


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) < 2 or len(args) % 2:
        sys.exit("usage: pendulum_crit_ref.py R_m k [R_m k ...]")
    for i in range(0, len(args), 2):
        print(json.dumps(critical(args[i], args[i + 1])), flush=True)
