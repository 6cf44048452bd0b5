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
    # device physics: gravity accelerations, drive torque, normal forces, static offset, impact law,
    # and the first-order gravity response against a SciPy integration
    data_delta[0] = data['impact']['delta']
    worst_dev = device_checks(data, bad)
    perturbation_check(data, bad)
    if not bad:
        print('independent check (device): NumPy mass-matrix solve of docs/device.md with gravity, normal forces, '
              'rolling inertia, rolling resistance, a stuck ball as an extra unbalance (holding force, N), '
              'static offset, impact law (mass matrix, restitution, energy loss, drive work, pair-only limit) equal '
              '%s, largest relative difference %.2e (tolerance 1e-10); gravity 1X response: SciPy vs '
              'the closed form (1X coefficients within 2 eps^2, mean shift O(eps^2): scales by 1/4 with g/2): OK' % (path, worst_dev))
    if bad:
        print('independent check FAILED:')
        for b in bad:
            print('  ' + b)
        return 1
    print('independent check: NumPy solve of the documented equations equals %s, '
          'largest relative difference %.2e (tolerance 1e-10): OK' % (path, worst))
    return 0



# ----------------------------------------------------------------------------------------------
# Device physics (docs/device.md sections 2-4): a second implementation of the equations as they are
# written there, in a different form from derive_device.py: the generalized mass matrix of the kinetic
# energy T assembled entry by entry, the forces as a vector, numpy.linalg.solve; no SymPy.


def mass_matrix_T(k, planes, q, ph0, motor, J, W):
    """Mass matrix and linear velocity part b of T (docs/device.md) for the velocities
    (x', y', alpha', beta', [Omega if motor], balls plane by plane).  T = 1/2 v^T M v + b^T v + ..."""
    balls = [(pl, m, r) for pl in planes for m, r in zip(pl['m'], pl['r'])]
    n0 = 5 if motor else 4
    n = n0 + len(balls)
    Mm = np.zeros((n, n))
    b = np.zeros(n)
    Mm[0, 0] = Mm[1, 1] = k['M']
    Mm[2, 2] = Mm[3, 3] = k['A']
    beta = q[3]

    def couple(col, factor, m, r, d, ang):
        # m r phi' (-u_D' sin + v_D' cos), u_D' = x' + d beta', v_D' = y' - d alpha'
        g = np.zeros(n)
        g[0], g[3] = -m * r * math.sin(ang), -m * r * d * math.sin(ang)
        g[1], g[2] = m * r * math.cos(ang), -m * r * d * math.cos(ang)
        return g
    if motor:
        Mm[4, 4] = J
        Mm[4, 2] = Mm[2, 4] = k['C'] * beta
    else:
        b[2] += k['C'] * W * beta
    for pl in planes:
        th = ph0 + pl['psi0']
        g = couple(None, 1, pl['m0'], pl['r0'], pl['d'], th)
        if motor:
            Mm[4, 4] += pl['m0'] * pl['r0']**2
            Mm[4, :4] += g[:4]
            Mm[:4, 4] += g[:4]
        else:
            b[:4] += W * g[:4]
    for j, (pl, m, r) in enumerate(balls):
        c = n0 + j
        Mm[c, c] = m * r * r
        g = couple(None, 1, m, r, pl['d'], pl['_phi'][j - pl['_first']])
        Mm[c, :4] += g[:4]
        Mm[:4, c] += g[:4]
    return Mm, b


def device_accelerations(case, motor, g_s, W=None, dW=None, state=None, ball_angles=None, ball_rates=None,
                         rho=None, f_roll=0.0):
    """Accelerations with gravity: (M v)' form.  Unknowns as mass_matrix_T's velocities.  The forces:
    supports, gyroscopic C Omega, ball viscosity, weights; the velocity-quadratic terms of T written
    out (the centripetal parts of s'' and the ball-rotor coupling), as in docs/device.md.  Options:
    rho: every ball a rolling solid sphere of that radius (T_rot = 1/5 m ((r + rho) Omega - r phi')^2);
    f_roll: rolling resistance f N sgn(psi') (N from the accelerations: the matrix loses symmetry)."""
    k = lumped(case['parameters'])
    st = state or case['state']
    q = np.array([st['x'], st['y'], st['alpha'], st['beta']])
    qd = np.array([st['x_d'], st['y_d'], st['alpha_d'], st['beta_d']])
    ph0 = st['phi_0']
    if W is None:
        W = case['motor']['Omega'] if motor else case['prescribed']['Omega']
    if dW is None and not motor:
        dW = case['prescribed']['Omega_dot']
    planes = [dict(pl) for pl in case['planes']]
    phis, rates, first = [], [], 0
    for pl in planes:
        pl['_first'] = first
        n = len(pl['m'])
        pl['_phi'] = [ph0 + ps for ps in pl['psi']] if ball_angles is None else ball_angles[first:first + n]
        phis += pl['_phi']
        rates += [W + rt for rt in pl['rate']] if ball_rates is None else ball_rates[first:first + n]
        first += n
    J = case['motor']['J'] if motor else k['C']
    Mm, _ = mass_matrix_T(k, planes, q, ph0, motor, J, W)
    n0 = 5 if motor else 4
    f = np.zeros(len(Mm))          # right-hand side: M a = f
    x, y, a, b = q
    xd, yd, ad, bd = qd
    f[0] = -(k['h_x'] * xd + k['c_x'] * x - k['h_xb'] * bd - k['c_xb'] * b)
    f[1] = -(k['h_y'] * yd + k['c_y'] * y + k['h_ya'] * ad + k['c_ya'] * a)
    f[2] = -(k['h_a'] * ad + k['c_a'] * a + k['C'] * W * bd + k['h_ya'] * yd + k['c_ya'] * y)
    f[3] = -(k['h_b'] * bd + k['c_b'] * b - k['C'] * W * ad - k['h_xb'] * xd - k['c_xb'] * x)
    # weights: -g_s (M + sum m) on y, + g_s sum d m on alpha
    wt = k['M'] + sum(pl['m0'] + sum(pl['m']) for pl in planes)
    dm = sum(pl['d'] * (pl['m0'] + sum(pl['m'])) for pl in planes)
    f[1] -= g_s * wt
    f[2] += g_s * dm
    # centripetal parts of s'': - sum m r phi'^2 (-cos, -sin) on (x, y), with d on (beta, alpha)
    small = [(pl, pl['m0'], pl['r0'], ph0 + pl['psi0'], W) for pl in planes]
    small += [(pl, m, r, phis[pl['_first'] + i], rates[pl['_first'] + i])
              for pl in planes for i, (m, r) in enumerate(zip(pl['m'], pl['r']))]
    for pl, m, r, ang, w in small:
        cu, cv = -m * r * w * w * math.cos(ang), -m * r * w * w * math.sin(ang)
        f[0] -= cu
        f[1] -= cv
        f[2] += pl['d'] * cv
        f[3] -= pl['d'] * cu
    torque_const = 0.0
    for pl in planes:        # the unbalance: tangential part with Omega' (prescribed: known)
        th = ph0 + pl['psi0']
        tu, tv = -pl['m0'] * pl['r0'] * math.sin(th), pl['m0'] * pl['r0'] * math.cos(th)
        if not motor:
            f[0] -= tu * dW
            f[1] -= tv * dW
            f[2] += pl['d'] * tv * dW
            f[3] -= pl['d'] * tu * dW
        torque_const += g_s * pl['m0'] * pl['r0'] * math.cos(th)
    if not motor:
        f[2] -= k['C'] * dW * b
    visc = 0.0
    j = 0
    for pl in planes:
        for i, (m, r, h) in enumerate(zip(pl['m'], pl['r'], pl['h'])):
            ang, w = phis[pl['_first'] + i], rates[pl['_first'] + i]
            f[n0 + j] = -h * r * r * (w - W) - m * r * g_s * math.cos(ang)
            visc += h * r * r * (w - W)
            j += 1
    if motor:
        mo = case['motor']
        L = mo['L_0'] * (1 - W / mo['Omega_0'])
        f[4] = L - mo['k_r'] * W + visc - k['C'] * ad * bd - torque_const
    j = 0
    res_torque = 0.0               # + sum r f N sgn on the phi_0 row's right-hand side, as a row
    res_row = np.zeros(len(Mm))
    for pl in planes:
        d = pl['d']
        for i, (m, r) in enumerate(zip(pl['m'], pl['r'])):
            c = n0 + j
            ang, w = phis[pl['_first'] + i], rates[pl['_first'] + i]
            if rho is not None:     # Hessian of T_rot; prescribed: its Omega' part to the right
                Mm[c, c] += 0.4 * m * r * r
                if motor:
                    Mm[4, 4] += 0.4 * m * (r + rho)**2
                    Mm[4, c] -= 0.4 * m * r * (r + rho)
                    Mm[c, 4] -= 0.4 * m * r * (r + rho)
                else:
                    f[c] += 0.4 * m * r * (r + rho) * dW
            if f_roll:
                kk = r * f_roll * (1.0 if w > W else -1.0)
                # + kk N on the ball row's left, N = m (r w^2 - u_D'' cos - (v_D'' + g_s) sin)
                row = np.zeros(len(Mm))
                row[0], row[3] = -kk * m * math.cos(ang), -kk * m * d * math.cos(ang)
                row[1], row[2] = -kk * m * math.sin(ang), kk * m * d * math.sin(ang)
                const = kk * m * (r * w * w - g_s * math.sin(ang))
                Mm[c] += row
                f[c] -= const
                res_row += row
                res_torque += const
            j += 1
    if f_roll and motor:            # the reaction on the rotor: - sum kk N on the phi_0 row's left
        Mm[4] -= res_row
        f[4] += res_torque
    acc = np.linalg.solve(Mm, f)
    torque = None
    if not motor:
        # drive torque: (C + sum m0 r0^2) Omega' + C (alpha'' beta + alpha' beta') + vibration torque
        # - ball viscosity + weight torque
        torque = (k['C'] + sum(pl['m0'] * pl['r0']**2 for pl in planes)) * dW + k['C'] * (acc[2] * b + ad * bd)
        for pl in planes:
            th = ph0 + pl['psi0']
            uDdd, vDdd = acc[0] + pl['d'] * acc[3], acc[1] - pl['d'] * acc[2]
            torque += pl['m0'] * pl['r0'] * (-uDdd * math.sin(th) + vDdd * math.cos(th))
        torque += -visc + torque_const
    # normal forces N = m (r phi'^2 - u_D'' cos phi - (v_D'' + g_s) sin phi)
    N = []
    for pl in planes:
        uDdd, vDdd = acc[0] + pl['d'] * acc[3], acc[1] - pl['d'] * acc[2]
        for i, (m, r) in enumerate(zip(pl['m'], pl['r'])):
            ang, w = phis[pl['_first'] + i], rates[pl['_first'] + i]
            N.append(m * (r * w * w - uDdd * math.cos(ang) - (vDdd + g_s) * math.sin(ang)))
    return acc, torque, N, Mm


def ball_names(case):
    return ['phi_%d%d' % (j + 1, i + 1) for j, pl in enumerate(case['planes']) for i in range(len(pl['m']))]


def compare(bad, what, got, want, tol):
    rel = abs(got - want) / max(abs(want), 1e-300)
    if not rel <= tol:
        bad.append('%s: numpy %.17g, json %.17g (relative %.2e)' % (what, got, want, rel))
    return rel


def device_checks(data, bad):
    worst = 0.0
    grav = data['gravity']
    gs = grav['g_s']
    if abs(gs - grav['g'] * math.sin(grav['theta'])) > 1e-15 * gs:
        bad.append('gravity: g_s != g sin(theta)')
    for name, key in (('one_plane', 'planes1'), ('two_planes', 'planes2')):
        case = data[name]
        for motor in (False, True):
            mode = 'motor' if motor else 'prescribed'
            acc, torque, N, _ = device_accelerations(case, motor, gs)
            names = ['x_dd', 'y_dd', 'alpha_dd', 'beta_dd'] + (['phi_0_dd'] if motor else []) + \
                [n + '_dd' for n in ball_names(case)]
            ref = grav[key][mode]['accelerations']
            if set(names) != set(ref):
                bad.append('gravity/%s/%s: names' % (key, mode))
                continue
            for n, v in zip(names, acc):
                worst = max(worst, compare(bad, 'gravity/%s/%s/%s' % (key, mode, n), v, ref[n], 1e-10))
            if not motor:
                worst = max(worst, compare(bad, 'gravity/%s/drive_torque' % key, torque,
                                           grav[key]['prescribed']['drive_torque'], 1e-10))
            for n, v in zip(ball_names(case), N):
                worst = max(worst, compare(bad, 'normal_force/%s/gravity/%s/%s' % (key, mode, n), v,
                                           data['normal_force'][key]['gravity'][mode][n], 1e-10))
            # normal force without gravity: from the accelerations of the old check values
            _, _, N0, _ = device_accelerations(case, motor, 0.0)
            for n, v in zip(ball_names(case), N0):
                worst = max(worst, compare(bad, 'normal_force/%s/no_gravity/%s/%s' % (key, mode, n), v,
                                           data['normal_force'][key]['no_gravity'][mode][n], 1e-10))
        # static offset: K q = -g_s w
        k = lumped(case['parameters'])
        K = np.array([[k['c_x'], 0, 0, -k['c_xb']], [0, k['c_y'], k['c_ya'], 0],
                      [0, k['c_ya'], k['c_a'], 0], [-k['c_xb'], 0, 0, k['c_b']]])
        wt = k['M'] + sum(pl['m0'] + sum(pl['m']) for pl in case['planes'])
        dm = sum(pl['d'] * (pl['m0'] + sum(pl['m'])) for pl in case['planes'])
        qs = np.linalg.solve(K, -gs * np.array([0.0, wt, -dm, 0.0]))
        so = grav[key]['static_offset']
        for n, v in zip(['x', 'y', 'alpha', 'beta'], qs):
            if so[n] == 0.0:
                if abs(v) > 1e-25:
                    bad.append('static offset %s: %g vs 0' % (n, v))
            else:
                worst = max(worst, compare(bad, 'gravity/%s/static_offset/%s' % (key, n), v, so[n], 1e-10))
        for motor in (False, True):
            mode = 'motor' if motor else 'prescribed'
            names = ['x_dd', 'y_dd', 'alpha_dd', 'beta_dd'] + (['phi_0_dd'] if motor else []) + \
                [n + '_dd' for n in ball_names(case)]
            # rolling inertia (no gravity)
            acc, _, _, _ = device_accelerations(case, motor, 0.0, rho=data['rolling_inertia']['rho'])
            ref = data['rolling_inertia'][key][mode]['accelerations']
            for n, v in zip(names, acc):
                worst = max(worst, compare(bad, 'rolling_inertia/%s/%s/%s' % (key, mode, n), v, ref[n], 1e-10))
            # rolling resistance (gravity on)
            rr = data['rolling_resistance']
            acc, _, N, _ = device_accelerations(case, motor, rr['g_s'], f_roll=rr['f'])
            ref = rr[key][mode]
            for n, v in zip(names, acc):
                worst = max(worst, compare(bad, 'rolling_resistance/%s/%s/%s' % (key, mode, n), v,
                                           ref['accelerations'][n], 1e-10))
            for n, v in zip(ball_names(case), N):
                worst = max(worst, compare(bad, 'rolling_resistance/%s/%s/N/%s' % (key, mode, n), v, ref['N'][n], 1e-10))
            worst = max(worst, stuck_check(data, case, key, motor, bad))
        # impact law from the mass matrix
        for ikey, blk in data['impact'][key].items():
            worst = max(worst, impact_check(case, ikey, blk, bad))
    return worst


def stuck_check(data, case, key, motor, bad):
    """Ball 1 of plane 1 stuck: a mass fixed to the rotor, i.e. an extra unbalance (m_11 at r_11,
    psi_11) in a plane of its own at the same d; then the holding force and N of docs/device.md."""
    sh = data['stiction_holding']
    gs = sh['g_s']
    c2 = dict(case)
    p1 = dict(case['planes'][0])
    m, r, ps = p1['m'][0], p1['r'][0], p1['psi'][0]
    for fld in ('m', 'r', 'h', 'psi', 'rate'):
        p1[fld] = p1[fld][1:]
    pseudo = dict(d=p1['d'], m0=m, r0=r, psi0=ps, m=[], r=[], h=[], psi=[], rate=[])
    c2['planes'] = [p1] + list(case['planes'][1:]) + [pseudo]
    mode = 'motor' if motor else 'prescribed'
    acc, _, _, _ = device_accelerations(c2, motor, gs)
    free = [n for n in ball_names(case) if n != 'phi_11']
    names = ['x_dd', 'y_dd', 'alpha_dd', 'beta_dd'] + (['phi_0_dd'] if motor else []) + [n + '_dd' for n in free]
    ref = sh[key][mode]
    worst = 0.0
    if set(names) != set(ref['accelerations']):
        bad.append('stiction_holding/%s/%s: names' % (key, mode))
        return worst
    for n, v in zip(names, acc):
        worst = max(worst, compare(bad, 'stiction_holding/%s/%s/%s' % (key, mode, n), v, ref['accelerations'][n], 1e-10))
    W = case['motor']['Omega'] if motor else case['prescribed']['Omega']
    dW = acc[4] if motor else case['prescribed']['Omega_dot']
    ang = case['state']['phi_0'] + ps
    d = p1['d']
    uDdd, vDdd = acc[0] + d * acc[3], acc[1] - d * acc[2]
    H = m * (r * dW - uDdd * math.sin(ang) + (vDdd + gs) * math.cos(ang))
    N = m * (r * W * W - uDdd * math.cos(ang) - (vDdd + gs) * math.sin(ang))
    worst = max(worst, compare(bad, 'stiction_holding/%s/%s/H' % (key, mode), H, ref['H'], 1e-10))
    worst = max(worst, compare(bad, 'stiction_holding/%s/%s/N' % (key, mode), N, ref['N'], 1e-10))
    return worst


def impact_check(case, ikey, blk, bad):
    motor = ikey.startswith('motor')
    e = blk['e']
    pl_index = len(case['planes']) - 1
    st = dict(case['state'])
    ph0 = st['phi_0']
    W = case['motor']['Omega'] if motor else case['prescribed']['Omega']
    pl = case['planes'][pl_index]
    r = pl['r'][0]
    delta = data_delta[0]
    gap = 2 * math.asin(delta / (2 * r))
    worst = compare(bad, 'impact/%s/gap_angle' % ikey, gap, blk['gap_angle'], 1e-13)
    # angles: plane as the check state, balls of the pair touching; approaching pair
    angles, rates = [], []
    for j, p in enumerate(case['planes']):
        ps = list(p['psi'])
        if j == pl_index:
            ahead = 1 if p['rate'][1] < p['rate'][0] else -1
            ps[1] = ps[0] + ahead * gap
        angles += [ph0 + v for v in ps]
        rates += [W + v for v in p['rate']]
    k = lumped(case['parameters'])
    planes = [dict(p) for p in case['planes']]
    first = 0
    for p in planes:
        p['_first'] = first
        p['_phi'] = angles[first:first + len(p['m'])]
        first += len(p['m'])
    q = [st['x'], st['y'], st['alpha'], st['beta']]
    J = case['motor']['J'] if motor else k['C']
    Mm, b = mass_matrix_T(k, planes, q, ph0, motor, J, W)
    v0 = np.array([st['x_d'], st['y_d'], st['alpha_d'], st['beta_d']] + ([W] if motor else []) + rates)
    n0 = 5 if motor else 4
    i1 = n0 + first - len(planes[-1]['m'])
    Jr = np.zeros(len(v0))
    Jr[i1], Jr[i1 + 1] = -ahead, ahead
    u = Jr @ v0
    Minv_J = np.linalg.solve(Mm, Jr)
    G = Jr @ Minv_J
    lam = -(1 + e) * u / G
    v1 = v0 + Minv_J * lam
    dv = v1 - v0
    dT = (Mm @ v0 + b) @ dv + 0.5 * dv @ Mm @ dv          # T(v1) - T(v0) without cancellation
    loss = 0.5 * (1 - e * e) * u * u / G
    worst = max(worst, compare(bad, 'impact/%s/G' % ikey, G, blk['G'], 1e-10))
    worst = max(worst, compare(bad, 'impact/%s/impulse' % ikey, lam, blk['impulse'], 1e-10))
    if e < 1:
        worst = max(worst, compare(bad, 'impact/%s/impact_loss' % ikey, loss, blk['impact_loss'], 1e-10))
    names = ['x_d', 'y_d', 'alpha_d', 'beta_d'] + (['phi_0_d'] if motor else []) + \
        [n + '_d' for n in ball_names(case)]
    for n, v in zip(names, v1):
        worst = max(worst, compare(bad, 'impact/%s/after/%s' % (ikey, n), v, blk['velocities_after'][n], 1e-12))
    # energy: motor: dT = -loss exactly; prescribed: dT = -loss + b.(v1 - v0) (the drive's work)
    work = 0.0 if motor else b @ (v1 - v0)
    scale = u * u / G
    if abs(dT - (-loss + work)) > 1e-8 * scale:          # double-precision mass-matrix solve
        bad.append('impact/%s: energy change %.17g != -loss + drive work %.17g' % (ikey, dT, -loss + work))
    if abs(blk["energy_change"] - dT) > 1e-8 * scale:
        bad.append('impact/%s: energy change numpy %.17g, json %.17g' % (ikey, dT, blk['energy_change']))
    # pair-only law: momentum of the pair and restitution, rotor held
    m1, m2 = pl['m'][0], pl['m'][1]
    w1, w2 = rates[i1 - n0], rates[i1 - n0 + 1]
    P = m1 * w1 + m2 * w2
    ua = w2 - w1
    after = [(P + m2 * e * ua) / (m1 + m2), (P - m1 * e * ua) / (m1 + m2)]
    for kk in range(2):
        worst = max(worst, compare(bad, 'impact/%s/pair_only/%d' % (ikey, kk), after[kk],
                                   blk['pair_only_rates_after'][kk], 1e-13))
    return worst


data_delta = [None]


def perturbation_check(data, bad):
    """Integrate the nonlinear fixed-frame equations with gravity (SciPy DOP853) from the first-order
    periodic state of the JSON, constant Omega, one plane; fit psi_i - psi_i* = mean + a cos + b sin
    over revolutions 10-20; a, b must match the closed form to O(eps^2) and the mean must be O(eps^2)."""
    from scipy.integrate import solve_ivp
    pt = data['gravity']['perturbation']
    case = data['one_plane']
    W, gs, eps = pt['Omega'], pt['g_s'], pt['eps']
    k = lumped(case['parameters'])

    def rhs(t, yv, g):
        ph0 = W * t
        st = dict(x=yv[0], y=yv[1], alpha=yv[2], beta=yv[3], x_d=yv[6], y_d=yv[7], alpha_d=yv[8],
                  beta_d=yv[9], phi_0=ph0)
        acc, _, _, _ = device_accelerations(case, False, g, W=W, dW=0.0, state=st,
                                            ball_angles=list(yv[4:6]), ball_rates=list(yv[10:12]))
        return np.concatenate([yv[6:12], acc])
    T = 2 * math.pi / W
    res = {}
    for sc in (1.0, 0.5):          # gravity scaled: first-order terms scale with sc, the rest with sc^2
        y0 = np.zeros(12)
        for n in range(4):
            y0[n] = sc * (pt['static_offset'][n] + pt['q_cos2'][n])
            y0[6 + n] = sc * 2 * W * pt['q_sin2'][n]
        for i in range(2):
            y0[4 + i] = pt['psi_star'][i] + sc * pt['psi_cos'][i]
            y0[10 + i] = W + sc * W * pt['psi_sin'][i]
        sol = solve_ivp(rhs, (0, 20 * T), y0, method='DOP853', rtol=1e-12, atol=1e-14, dense_output=True,
                        args=(sc * gs,))
        if not sol.success:
            bad.append('perturbation: integration failed: %s' % sol.message)
            return
        tt = np.linspace(10 * T, 20 * T, 2001)
        Y = sol.sol(tt)
        A = np.column_stack([np.ones_like(tt), np.cos(W * tt), np.sin(W * tt)])
        worst_c, worst_m = 0.0, 0.0
        for i in range(2):
            dpsi = Y[4 + i] - W * tt - pt['psi_star'][i]
            c, *_ = np.linalg.lstsq(A, dpsi, rcond=None)
            dc = max(abs(c[1] - sc * pt['psi_cos'][i]), abs(c[2] - sc * pt['psi_sin'][i]))
            worst_c = max(worst_c, dc)
            worst_m = max(worst_m, abs(c[0]))
            dd = max(abs(c[1] - sc * pt['psi_cos_decoupled'][i]), abs(c[2] - sc * pt['psi_sin_decoupled'][i]))
            if not dd > 5 * (sc * eps)**2:
                bad.append('perturbation: the decoupled-ball approximation is as close as the closed form')
        res[sc] = (worst_c, worst_m)
    amp = math.hypot(pt['psi_cos'][0], pt['psi_sin'][0])
    (c1, m1), (c2, m2) = res[1.0], res[0.5]
    print('perturbation (SciPy DOP853, 20 revolutions, Omega = %g rad/s, eps = %.3e, eps^2 = %.2e): 1X coefficients '
          'of psi - psi* differ from the first-order closed form by %.2e rad (amplitude %.3e rad); mean shift '
          '%.2e rad; with g/2: %.2e and %.2e rad (ratios %.3f, %.3f; O(eps^2) gives 0.25)'
          % (W, eps, eps * eps, c1, amp, m1, c2, m2, c2 / c1, m2 / m1))
    if not (c1 <= 2 * eps * eps and m1 <= 20 * eps * eps):
        bad.append('perturbation: closed form off by %.3e, mean %.3e (eps^2 = %.3e)' % (c1, m1, eps * eps))
    if not (0.2 <= m2 / m1 <= 0.3 and 0.2 <= c2 / c1 <= 0.3):
        bad.append('perturbation: deviations do not scale as eps^2: ratios %.3f, %.3f' % (c2 / c1, m2 / m1))


if __name__ == '__main__':
    sys.exit(main())
