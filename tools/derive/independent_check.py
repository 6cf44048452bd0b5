#!/usr/bin/python3
"""Independent numeric check of tools/derive/check_values.json (NumPy, no SymPy).

The accelerations are recomputed from the variable-speed equations as they are WRITTEN in
docs/device.md (lumped coefficients (2.9), (2.11) of docs/rotor.md, s_u'' and s_v'' expanded by
hand), assembled into the full mass-matrix system and solved with numpy.linalg.solve.  This code
shares nothing with derive_rotor.py except the parameter values read from the JSON, so agreement
checks the derivation, the documentation and the JSON against each other.

Usage: /usr/bin/python3 tools/derive/independent_check.py tools/derive/check_values.json
Exit status 1 (with the differences listed) if any value differs by more than 1e-10 relative.
"""
import json
import math
import sys

import numpy as np


def lumped(p):
    cLx, cLy, cRx, cRy = p['c_Lx'], p['c_Ly'], p['c_Rx'], p['c_Ry']
    hLx, hLy, hRx, hRy = p['h_Lx'], p['h_Ly'], p['h_Rx'], p['h_Ry']
    lL, lR = p['l_L'], p['l_R']
    return dict(M=p['M_k'] + p['m_p'], A=p['A_k'] + p['A_p'], C=p['C_p'],
                c_x=cLx + cRx, c_y=cLy + cRy, c_a=cLy * lL**2 + cRy * lR**2, c_b=cLx * lL**2 + cRx * lR**2,
                c_xb=cLx * lL - cRx * lR, c_ya=cLy * lL - cRy * lR,
                h_x=hLx + hRx, h_y=hLy + hRy, h_a=hLy * lL**2 + hRy * lR**2, h_b=hLx * lL**2 + hRx * lR**2,
                h_xb=hLx * lL - hRx * lR, h_ya=hLy * lL - hRy * lR)


def accelerations(case, motor):
    """Solve docs/device.md's equations for the accelerations.  Unknowns: x'', y'', alpha'', beta'',
    [phi_0'' if motor], then the balls plane by plane.  Returns (solution, phi_0 residual torque)."""
    k = lumped(case['parameters'])
    st = case['state']
    x, y, a, b = st['x'], st['y'], st['alpha'], st['beta']
    xd, yd, ad, bd = st['x_d'], st['y_d'], st['alpha_d'], st['beta_d']
    ph0 = st['phi_0']
    W = case['motor']['Omega'] if motor else case['prescribed']['Omega']
    balls = []                                         # (plane, m, r, h, phi, phi')
    for pl in case['planes']:
        for m, r, h, ps, rt in zip(pl['m'], pl['r'], pl['h'], pl['psi'], pl['rate']):
            balls.append((pl, m, r, h, ph0 + ps, W + rt))
    n = len(balls)
    i0 = 4 + (1 if motor else 0)                      # index of the first ball
    N = i0 + n
    Amat = np.zeros((N, N))
    rhs = np.zeros(N)
    # rotor rows without the s'' terms
    Amat[0, 0] = k['M']
    rhs[0] = -(k['h_x'] * xd + k['c_x'] * x - k['h_xb'] * bd - k['c_xb'] * b)
    Amat[1, 1] = k['M']
    rhs[1] = -(k['h_y'] * yd + k['c_y'] * y + k['h_ya'] * ad + k['c_ya'] * a)
    Amat[2, 2] = k['A']
    rhs[2] = -(k['h_a'] * ad + k['c_a'] * a + k['C'] * W * bd + k['h_ya'] * yd + k['c_ya'] * y)
    Amat[3, 3] = k['A']
    rhs[3] = -(k['h_b'] * bd + k['c_b'] * b - k['C'] * W * ad - k['h_xb'] * xd - k['c_xb'] * x)
    # Omega' terms: C Omega' beta in the alpha row; the unbalance's tangential terms in s''
    if motor:
        dW_col = 4
        Amat[2, dW_col] += k['C'] * b
    else:
        dW = case['prescribed']['Omega_dot']
        rhs[2] -= k['C'] * dW * b

    # s_u'' = sum m r (-phi'' sin phi - phi'^2 cos phi), s_v'' = sum m r (phi'' cos phi - phi'^2 sin phi);
    # x row: + s_u'', y row: + s_v'', alpha row: - d s_v'', beta row: + d s_u''
    def s_terms(d, m, r, ang, vel, col):
        su_acc, sv_acc = -m * r * math.sin(ang), m * r * math.cos(ang)      # coefficients of phi''
        su_0, sv_0 = -m * r * vel**2 * math.cos(ang), -m * r * vel**2 * math.sin(ang)
        for row, fu, fv in ((0, 1.0, 0.0), (1, 0.0, 1.0), (2, 0.0, -d), (3, d, 0.0)):
            c = fu * su_acc + fv * sv_acc
            if col is None:
                rhs[row] -= c * dW_known
            else:
                Amat[row, col] += c
            rhs[row] -= fu * su_0 + fv * sv_0

    dW_known = None if motor else case['prescribed']['Omega_dot']
    for pl in case['planes']:
        s_terms(pl['d'], pl['m0'], pl['r0'], ph0 + pl['psi0'], W, 4 if motor else None)
    for j, (pl, m, r, h, ph, phd) in enumerate(balls):
        s_terms(pl['d'], m, r, ph, phd, i0 + j)
        # ball row: m r (r phi'' - u_D'' sin phi + v_D'' cos phi) + h r^2 (phi' - Omega) = 0,
        # u_D'' = x'' + d beta'', v_D'' = y'' - d alpha''
        row = i0 + j
        d = pl['d']
        Amat[row, row] += m * r * r
        Amat[row, 0] += -m * r * math.sin(ph)
        Amat[row, 3] += -m * r * math.sin(ph) * d
        Amat[row, 1] += m * r * math.cos(ph)
        Amat[row, 2] += -m * r * math.cos(ph) * d
        rhs[row] = -h * r * r * (phd - W)
    ball_torque = sum(h * r * r * (phd - W) for (pl, m, r, h, ph, phd) in balls)

    def phi0_lhs_rows():
        """(J + sum m_0 r_0^2) Omega' + C (alpha'' beta + alpha' beta')
           + sum_j m_j0 r_j0 (-u_jD'' sin th_j + v_jD'' cos th_j) - sum h r^2 (phi' - Omega):
           coefficients of (x'', y'', alpha'', beta'') and the constant part."""
        cq = np.zeros(4)
        cq[2] += k['C'] * b
        const = k['C'] * ad * bd - ball_torque
        inertia = 0.0
        for pl in case['planes']:
            th = ph0 + pl['psi0']
            s0 = pl['m0'] * pl['r0']
            cq[0] += -s0 * math.sin(th)
            cq[3] += -s0 * math.sin(th) * pl['d']
            cq[1] += s0 * math.cos(th)
            cq[2] += -s0 * math.cos(th) * pl['d']
            inertia += pl['m0'] * pl['r0']**2
        return cq, const, inertia

    cq, const, inertia = phi0_lhs_rows()
    if motor:
        mo = case['motor']
        L = mo['L_0'] * (1 - W / mo['Omega_0'])
        Amat[4, :4] = cq
        Amat[4, 4] = mo['J'] + inertia
        rhs[4] = L - mo['k_r'] * W - const
        sol = np.linalg.solve(Amat, rhs)
        return sol, None
    sol = np.linalg.solve(Amat, rhs)
    torque = float(cq @ sol[:4] + const + (k['C'] + inertia) * dW_known)     # J = C_p
    return sol, torque


def main():
    path = sys.argv[1]
    with open(path) as f:
        data = json.load(f)
    bad = []
    worst = 0.0
    for name in ('one_plane', 'two_planes'):
        case = data[name]
        for motor in (False, True):
            key = 'motor' if motor else 'prescribed'
            sol, torque = accelerations(case, motor)
            names = ['x_dd', 'y_dd', 'alpha_dd', 'beta_dd'] + (['phi_0_dd'] if motor else [])
            names += sorted(n for n in case[key]['accelerations'] if n.startswith('phi_') and n != 'phi_0_dd')
            got = dict(zip(names, sol))
            if torque is not None:
                got['drive_torque'] = torque
            ref = dict(case[key]['accelerations'])
            if torque is not None:
                ref['drive_torque'] = case[key]['drive_torque']
            if set(got) != set(ref):
                bad.append('%s/%s: names %s vs %s' % (name, key, sorted(got), sorted(ref)))
                continue
            for n in sorted(ref):
                rel = abs(got[n] - ref[n]) / max(abs(ref[n]), 1e-300)
                worst = max(worst, rel)
                if rel > 1e-10:
                    bad.append('%s/%s/%s: numpy %.17g, json %.17g (relative %.2e)' % (name, key, n, got[n], ref[n], rel))
    if bad:
        print('independent check FAILED:')
        for b in bad:
            print('  ' + b)
        return 1
    print('independent check: NumPy solve of the documented equations equals %s, '
          'largest relative difference %.2e (tolerance 1e-10): OK' % (path, worst))
    return 0


if __name__ == '__main__':
    sys.exit(main())
