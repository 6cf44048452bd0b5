#!/usr/bin/python3
"""Anisotropic supports at HIGH SPEED (docs/rotor.md "Anisotropic supports"): the expansion of the forward and the
backward receptance of the fixed-frame rotor-housing in t = 1/omega, with SymPy.

Z(s) = M s^2 + H s + K (coordinates x, y, alpha, beta; the gyroscopic C omega in H), b = e_u + i e_v,
e_u = (1, 0, 0, d), e_v = (0, 1, -d, 0), G+ = 1/2 b^T Z(i omega)^-1 conj(b), G- = 1/2 b^T Z(-i omega)^-1 b.
With t^2 Z(i omega) = Z0 + t Z1 + t^2 K, Z0 = -diag(M, M, A, A) + i C J (J: alpha-beta skew), Z1 = i H_damping:
  t^2 coefficient of G+: 1/2 b^T Z0^-1 conj(b), t^3: -1/2 b^T Z0^-1 Z1 Z0^-1 conj(b) (K enters at t^4).
Checks (each prints a line ending in ': OK' or raises):
 (1) G+ = -(1/M + d^2/(A - C)) t^2 - i eta+ t^3 + O(t^4), eta+ the MEAN of the x plane's
     h_x/M^2 - 2 d h_xbeta/(M (A-C)) + d^2 h_beta/(A-C)^2 and the y plane's (h_y, h_yalpha, h_alpha): the library's
     high-speed (H1), (H2) with averaged damping (src/analysis/rotor_asymptotic.c, high_speed);
 (2) G- = O(t^3) (no t^2 term), its t^3 term proportional to the damping anisotropy (zero when h_y = h_x,
     h_yalpha = h_xbeta, h_alpha = h_beta);
 (3) numerically: -w^2 Re G+ and -w^3 Im G+ from a direct 4x4 complex solve at w = 1e5 .. 1e6 tend to the two
     coefficients (a check of the expansion apart from the series algebra).
Run:  /usr/bin/python3 tools/derive/derive_aniso_high.py
"""
import numpy as np
import sympy as sp


def main():
    M, A, C, d = sp.symbols('M A C d', positive=True)
    hx, hy, ha, hb, hxb, hya = sp.symbols('h_x h_y h_alpha h_beta h_xbeta h_yalpha', real=True)
    Mm = sp.diag(M, M, A, A)
    J = sp.zeros(4)
    J[2, 3], J[3, 2] = 1, -1
    Hd = sp.Matrix([[hx, 0, 0, -hxb], [0, hy, hya, 0], [0, hya, ha, 0], [-hxb, 0, 0, hb]])
    eu = sp.Matrix([1, 0, 0, d])
    ev = sp.Matrix([0, 1, -d, 0])
    b, cb = eu + sp.I * ev, eu - sp.I * ev
    Ap = A - C
    # (1) forward: s = i w, t^2 Z = -Mm + i C J + t i Hd + t^2 K
    Z0 = -Mm + sp.I * C * J
    Z0i = Z0.inv()
    g2 = sp.simplify(sp.Rational(1, 2) * (b.T * Z0i * cb)[0])
    g3 = sp.simplify(-sp.Rational(1, 2) * (b.T * Z0i * (sp.I * Hd) * Z0i * cb)[0])
    ginf = 1 / M + d**2 / Ap
    ex = hx / M**2 - 2 * d * hxb / (M * Ap) + d**2 * hb / Ap**2
    ey = hy / M**2 - 2 * d * hya / (M * Ap) + d**2 * ha / Ap**2
    assert sp.simplify(g2 + ginf) == 0, g2
    assert sp.simplify(g3 + sp.I * (ex + ey) / 2) == 0, g3
    print('anisotropic, high speed (1): G+ = -(1/M + d^2/(A-C)) t^2 - i eta+ t^3 + O(t^4), eta+ = the mean of the x and '
          'y planes\' damping terms: OK')
    # (2) backward: s = -i w
    Z0m = -Mm - sp.I * C * J
    Z0mi = Z0m.inv()
    h2 = sp.simplify(sp.Rational(1, 2) * (b.T * Z0mi * b)[0])
    h3 = sp.simplify(-sp.Rational(1, 2) * (b.T * Z0mi * (-sp.I * Hd) * Z0mi * b)[0])
    assert h2 == 0, h2
    assert sp.simplify(h3.subs({hy: hx, hya: hxb, ha: hb})) == 0, h3
    assert sp.simplify(h3) != 0
    print('anisotropic, high speed (2): G- = O(t^3), its t^3 term vanishes for isotropic damping: OK')
    # (3) numbers: a machine with unequal stiffness and damping, direct solves at high speed
    v = dict(M=3.9, A=0.077, C=0.03, d=0.12, h_x=60.0, h_y=140.0, h_alpha=0.9, h_beta=2.1, h_xbeta=-0.4,
             h_yalpha=1.3)
    Kn = np.array([[2e5, 0, 0, -3e3], [0, 5e5, 7e3, 0], [0, 7e3, 9e3, 0], [-3e3, 0, 0, 4e3]])
    Mn = np.diag([v['M'], v['M'], v['A'], v['A']])
    Hn = np.array([[v['h_x'], 0, 0, -v['h_xbeta']], [0, v['h_y'], v['h_yalpha'], 0],
                   [0, v['h_yalpha'], v['h_alpha'], 0], [-v['h_xbeta'], 0, 0, v['h_beta']]])
    bn = np.array([1, 1j, -1j * v['d'], v['d']])
    sub = {M: v['M'], A: v['A'], C: v['C'], d: v['d'], hx: v['h_x'], hy: v['h_y'], ha: v['h_alpha'], hb: v['h_beta'],
           hxb: v['h_xbeta'], hya: v['h_yalpha']}
    g2n, g3n = float(ginf.subs(sub)), float(((ex + ey) / 2).subs(sub))
    errs = []
    for w in (1e5, 1e6):
        Gy = np.zeros((4, 4))
        Gy[2, 3], Gy[3, 2] = v['C'] * w, -v['C'] * w
        Gp = 0.5 * bn @ np.linalg.solve(-Mn * w * w + 1j * w * (Hn + Gy) + Kn, np.conj(bn))
        errs.append((abs(-w * w * Gp.real - g2n) / g2n, abs(-w**3 * Gp.imag - g3n) / abs(g3n)))
    # the remainders are O(w^-2) relative (K / (M w^2)): 1e-6 at 1e6 rad/s and a hundred times smaller than at 1e5
    assert all(errs[1][k] < 1e-6 and errs[1][k] < errs[0][k] / 50 for k in (0, 1)), errs
    print('anisotropic, high speed (3): a direct solve at 1e6 rad/s: -w^2 Re G+ within %.1e, -w^3 Im G+ within %.1e of '
          'the coefficients (at 1e5: %.1e, %.1e): OK' % (errs[1][0], errs[1][1], errs[0][0], errs[0][1]))


if __name__ == '__main__':
    main()
