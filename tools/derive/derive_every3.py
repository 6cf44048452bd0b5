#!/usr/bin/env python3
"""derive_every3.py: the exact range of u = |Q|^2/4 over EVERY balanced member of three identical balls
(docs/rotor.md "Every unbalance", unbalance_member = every; src/analysis/rotor_unbalance.c, e3_*),
checked with SymPy.  Units of m r: t = m0 r0 / (m r) = |sum z_k|, z_k = e^{i psi_k} rotated so that
S = sum z_k = t > 0, q = |sum z_k^2|^2 = 4 u / m^2.

 (1) e2 = e3 conj(e1) for unit z_k; with e1 = t, e3 = e^{i chi}: q = t^4 + 4 t^2 - 4 t^3 cos chi;
 (2) p(z) = z^3 - t z^2 + t w z - w (w = e^{i chi}, the balls are its roots) is self-inversive:
     z^3 conj(p(1/conj z)) = -conj(w) p(z); so a root off the circle comes with its mirror, a cubic
     cannot have two double roots, and the roots can leave the unit circle (as chi moves) only
     through a double root ON it, where the discriminant vanishes;
 (3) disc(p)/w^2 = t^4 + 18 t^2 - 27 - 8 t^3 cos chi (real on |w| = 1): zero only at
     cos chi = cos chi_b(t) = (t^4 + 18 t^2 - 27) / (8 t^3); cos chi_b - 1 = (t-3)^3 (t+1) / (8 t^3),
     cos chi_b + 1 = (t+3)^3 (t-1) / (8 t^3);
 (4) chi = 0 is a member for t in [0, 3] (one ball on S, two symmetric: p = (z-1)(z^2 - (t-1) z + 1));
     chi = pi is one iff t <= 1 (p = (z+1)(z^2 - (t+1) z + 1)).  With (2), (3): the members of t are
     all chi for t <= 1, cos chi >= cos chi_b(t) for t in [1, 3]: q_min(t) = t^2 (t-2)^2,
     q_max(t) = t^2 (t+2)^2 (t <= 1), 1 + (t^2 - 5)^2 / 2 (t >= 1, two balls together:
     2 e^{i alpha} + e^{i beta} = t, cos alpha = (t^2 + 3) / (4 t));
 (5) the t-extrema: q_min' = 0 at t = 0, 1, 2; q_max increasing on [0, 1], on [1, 3] stationary only
     at sqrt(5) (a minimum): over [ta, tb] min q = min(q_min(ta), q_min(tb), 0 if 2 inside), max q =
     max(q_max(ta), q_max(tb), 9 if 1 inside);
 (6) the ends of {t : q_min(t) <= q <= q_max(t)} used in the code solve q_min = q or q_max = q;
 (7) NumPy: the feasibility criterion (3)-(4) against the roots of p on a (t, chi) grid.
Each check prints a line ending in ': OK' (tests/test_derive.sh looks for them)."""
import sympy as sp
import numpy as np

t, c, x, q = sp.symbols('t c chi q', real=True)
w, z = sp.symbols('w z')


def check(name, ok):
    if not ok:
        raise SystemExit('derive_every3: %s: FAILED' % name)
    print('%s: OK' % name)


# (1)
z1, z2, z3 = sp.symbols('z1 z2 z3')
e1, e2, e3 = z1 + z2 + z3, z1 * z2 + z1 * z3 + z2 * z3, z1 * z2 * z3
check('three balls (1): e2 = e3 conj(e1) on the unit circle', sp.expand(e3 * (1 / z1 + 1 / z2 + 1 / z3) - e2) == 0)
check('three balls (1): sum z^2 = e1^2 - 2 e2', sp.expand(z1**2 + z2**2 + z3**2 - (e1**2 - 2 * e2)) == 0)
P2 = t**2 - 2 * t * sp.exp(sp.I * x)
qq = sp.simplify(sp.expand_complex(P2 * sp.conjugate(P2)))
check('three balls (1): q = t^4 + 4 t^2 - 4 t^3 cos chi', sp.simplify(qq - (t**4 + 4 * t**2 - 4 * t**3 * sp.cos(x))) == 0)

# (2)
p = z**3 - t * z**2 + t * w * z - w
wb = 1 / w  # conj(w) on the circle; t real
pstar = sp.expand(z**3 * (1 / z**3 - t / z**2 + t * wb / z - wb))  # z^3 conj(p(1/conj z))
check('three balls (2): p is self-inversive, p* = -conj(w) p', sp.expand(pstar + wb * p) == 0)

# (3)
D = sp.discriminant(p, z)
Dc = sp.expand(D / w**2)
Dcos = sp.expand(Dc.subs(w, sp.exp(sp.I * x)).rewrite(sp.cos))
check('three balls (3): disc(p)/w^2 = t^4 + 18 t^2 - 27 - 8 t^3 cos chi',
      sp.simplify(sp.expand_complex(Dcos) - (t**4 + 18 * t**2 - 27 - 8 * t**3 * sp.cos(x))) == 0)
cb = (t**4 + 18 * t**2 - 27) / (8 * t**3)
check('three balls (3): cos chi_b - 1 = (t-3)^3 (t+1)/(8 t^3), cos chi_b + 1 = (t+3)^3 (t-1)/(8 t^3)',
      sp.simplify(cb - 1 - (t - 3)**3 * (t + 1) / (8 * t**3)) == 0 and
      sp.simplify(cb + 1 - (t + 3)**3 * (t - 1) / (8 * t**3)) == 0)

# (4)
check('three balls (4): chi = 0: p = (z - 1)(z^2 - (t - 1) z + 1)',
      sp.expand(p.subs(w, 1) - (z - 1) * (z**2 - (t - 1) * z + 1)) == 0)
check('three balls (4): chi = pi: p = (z + 1)(z^2 - (t + 1) z + 1)',
      sp.expand(p.subs(w, -1) - (z + 1) * (z**2 - (t + 1) * z + 1)) == 0)
qf = t**4 + 4 * t**2 - 4 * t**3 * c
check('three balls (4): q_min = q(cos chi = 1) = t^2 (t - 2)^2', sp.expand(qf.subs(c, 1) - t**2 * (t - 2)**2) == 0)
check('three balls (4): q(cos chi = -1) = t^2 (t + 2)^2', sp.expand(qf.subs(c, -1) - t**2 * (t + 2)**2) == 0)
check('three balls (4): q(cos chi_b) = 1 + (t^2 - 5)^2 / 2',
      sp.simplify(qf.subs(c, cb) - (1 + (t**2 - 5)**2 / 2)) == 0)
al, be = sp.symbols('alpha beta', real=True)
ca = (t**2 + 3) / (4 * t)
# two balls at alpha, one at beta with 2 e^{i alpha} + e^{i beta} = t: |t - 2 e^{i alpha}| = 1 fixes cos alpha
check('three balls (4): two together: |t - 2 e^{i alpha}|^2 = 1 at cos alpha = (t^2 + 3)/(4 t)',
      sp.simplify(t**2 - 4 * t * ca + 4 - 1) == 0)
# q of that member: |2 e^{2 i alpha} + e^{2 i beta}|^2 = 5 + 4 cos 2(alpha - beta), cos(alpha - beta) = (t^2 - 5)/4
cab = (t**2 - 5) / 4
check('three balls (4): two together: q = 5 + 4 (2 cos^2(alpha - beta) - 1) = 1 + (t^2 - 5)^2 / 2',
      sp.simplify(5 + 4 * (2 * cab**2 - 1) - (1 + (t**2 - 5)**2 / 2)) == 0)
# numerically at a few t: the member {alpha, alpha, beta} has S = t and e3 = e^{i chi_b}
okm = True
for tv in [1.1, 1.5, 2.0, 2.5, 2.9]:
    a = float(sp.acos(ca.subs(t, tv)))
    zb = tv - 2 * np.exp(1j * a)
    zz = np.array([np.exp(1j * a), np.exp(1j * a), zb])
    okm &= abs(abs(zb) - 1) < 1e-12 and abs(zz.sum() - tv) < 1e-12
    okm &= abs(np.prod(zz).real - float(cb.subs(t, tv))) < 1e-12
check('three balls (4): the member with two balls together has e3 = e^{i chi_b} (5 values of t)', okm)

# (5)
qmin = t**2 * (t - 2)**2
qmax1 = t**2 * (t + 2)**2
qmax2 = 1 + (t**2 - 5)**2 / 2
check('three balls (5): q_min\' = 0 at t = 0, 1, 2 only', set(sp.solve(sp.diff(qmin, t), t)) == {0, 1, 2})
check('three balls (5): q_max increasing on [0, 1]: q_max\' = 4 t (t + 1)(t + 2)',
      sp.expand(sp.diff(qmax1, t) - 4 * t * (t + 1) * (t + 2)) == 0)
check('three balls (5): on [1, 3] q_max\' = 2 t (t^2 - 5), zero only at sqrt(5)',
      sp.expand(sp.diff(qmax2, t) - 2 * t * (t**2 - 5)) == 0)
check('three balls (5): q_max continuous at t = 1 (9) and q_min = q_max = 9 at t = 3',
      qmax1.subs(t, 1) == 9 and qmax2.subs(t, 1) == 9 and qmin.subs(t, 3) == 9 and qmax2.subs(t, 3) == 9)

# (6) the ends used in e3_t_set
rq = sp.symbols('r', positive=True)  # r = sqrt(q)
ends_min = [rq / (1 + sp.sqrt(1 - rq)), 1 + sp.sqrt(1 - rq), 1 + sp.sqrt(1 + rq)]
ok6 = all(sp.simplify(sp.expand(qmin.subs(t, e)) - rq**2) == 0 for e in ends_min)
ok6 &= sp.simplify(sp.expand(qmax1.subs(t, rq / (1 + sp.sqrt(1 + rq)))) - rq**2) == 0
ok6 &= all(sp.simplify(sp.expand(qmax2.subs(t, sp.sqrt(5 + s * sp.sqrt(2 * (q - 1))))) - q) == 0 for s in (-1, 1))
check('three balls (6): the ends of {q_min <= q <= q_max} solve q_min = q or q_max = q', ok6)

# (7) NumPy: all roots of p on the circle <=> chi = 0-side of chi_b
bad = 0
for tv in np.linspace(0.02, 2.98, 149):
    cbv = (tv**4 + 18 * tv**2 - 27) / (8 * tv**3)
    for xv in np.linspace(0.0, np.pi, 181):
        if abs(np.cos(xv) - cbv) < 1e-3:
            continue  # next to the boundary a double root: the root finder's error is sqrt(eps)
        r = np.roots([1, -tv, tv * np.exp(1j * xv), -np.exp(1j * xv)])
        on = np.max(np.abs(np.abs(r) - 1)) < 1e-6
        bad += on != (np.cos(xv) >= cbv)
check('three balls (7): NumPy roots of p: on the circle iff cos chi >= cos chi_b (149 x 181 grid)', bad == 0)
