#!/usr/bin/python3
"""Checks of tests/app/gravity.sh against archives of `autobal rotor transient` with gravity.

The equations of motion with gravity are integrated here independently of the C code: the
accelerations come from tools/derive/independent_check.py (device_accelerations: NumPy, the equations
as written in docs/device.md, assembled into the mass-matrix system and solved with numpy.linalg.solve;
it shares nothing with src/models/rotor/), integrated with SciPy's DOP853.

  scipy A.h5            SciPy vs the archive's series (rotor coordinates and ball angles)
  bottom A.h5 T         at t = T (constant speed Omega during a dwell before T) each ball lies where
                        the weight balances the viscous drag of the track: cos(phi) = h r Omega / (m g_s),
                        i.e. phi = -pi/2 + asin(h r Omega / (m g_s)), near the bottom phi = -pi/2
  offset A.h5 T0 T1     /rotor static_offset_y, _alpha against the closed form of docs/device.md
                        (coded here from the lumped coefficients), and the mean y, alpha over [T0, T1]
                        (the dwell at low speed) against it; T1 < T0: the attributes only
  ratio A.h5            /rotor/planeN gravity_ratio_final = g sin(theta) / (r_min Omega_end^2); < 1 and
                        the balls carried round at the end (more than 10 turns in the last second)
  frames A.h5 B.h5      the fixed-frame run A and the rotating-frame run B agree (1e-7)
  same A.h5 B.h5        every series dataset equal bit for bit
"""
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.environ.get('TOOLS', os.path.join(os.path.dirname(__file__), '..', '..', 'tools')),
                                'derive'))
from independent_check import device_accelerations, lumped  # noqa: E402

HW = ['M_k', 'A_k', 'm_p', 'A_p', 'C_p', 'l_L', 'l_R', 'c_Lx', 'c_Ly', 'c_Rx', 'c_Ry', 'h_Lx', 'h_Ly', 'h_Rx', 'h_Ry']


def load(path):
    f = h5py.File(path, 'r')
    r = f['/rotor']
    case = {'parameters': {k: float(r.attrs[k]) for k in HW}, 'planes': []}
    j = 1
    while '/rotor/plane%d' % j in f:
        a = f['/rotor/plane%d' % j].attrs
        case['planes'].append(dict(d=float(a['d']), m0=float(a['m0']), r0=float(a['r0']), psi0=float(a['psi0']),
                                   m=list(a['ball_mass']), r=list(a['ball_radius']), h=list(a['ball_damping']),
                                   psi=list(a['ball_psi_initial']), rate=list(a['ball_rate_initial'])))
        j += 1
    return f, case


def drive(f):
    """The table drive: (times, speeds); Omega(t) and phi_0(t) piecewise."""
    tr = f['/rotor/transient'].attrs
    if tr['drive_mode'] != 'table':
        raise SystemExit('this check needs drive_mode = table, got %s' % tr['drive_mode'])
    return np.array(tr['drive_table_t'], float), np.array(tr['drive_table_omega'], float)


def spin(T, V, t):
    """Omega, Omega', phi_0 of the table drive (constant before the first and after the last point;
    phi_0(0) = 0)."""
    def F(t):  # antiderivative with F = V[0] t before T[0]
        if t < T[0]:
            return V[0] * t
        acc = V[0] * T[0]
        for k in range(len(T) - 1):
            a, b = T[k], T[k + 1]
            if t <= b:
                s = (V[k + 1] - V[k]) / (b - a)
                return acc + (t - a) * (V[k] + 0.5 * s * (t - a))
            acc += (b - a) * 0.5 * (V[k] + V[k + 1])
        return acc + V[-1] * (t - T[-1])
    if t < T[0] or t >= T[-1]:
        W, dW = (V[0], 0.0) if t < T[0] else (V[-1], 0.0)
    else:
        k = np.searchsorted(T, t, side='right') - 1
        dW = (V[k + 1] - V[k]) / (T[k + 1] - T[k])
        W = V[k] + dW * (t - T[k])
    return W, dW, F(t) - F(0.0)


def scipy_run(path):
    from scipy.integrate import solve_ivp
    f, case = load(path)
    r = f['/rotor']
    gs = float(r.attrs['g']) * math.sin(float(r.attrs['shaft_angle']))
    T, V = drive(f)
    ts = f['/rotor/transient/time'][()]
    nb = sum(len(p['m']) for p in case['planes'])
    a = f['/rotor/transient'].attrs
    q0, qd0 = list(a['initial_q']), list(a['initial_q_rate'])
    W0, _, ph00 = spin(T, V, 0.0)
    y0 = np.zeros(8 + 2 * nb)
    y0[0:4], y0[4 + nb:8 + nb] = q0, qd0
    k = 0
    for p in case['planes']:
        for ps, rt in zip(p['psi'], p['rate']):
            y0[4 + k] = ph00 + ps
            y0[8 + nb + k] = W0 + rt
            k += 1

    def rhs(t, yv):
        W, dW, ph0 = spin(T, V, t)
        st = dict(x=yv[0], y=yv[1], alpha=yv[2], beta=yv[3], x_d=yv[4 + nb], y_d=yv[5 + nb], alpha_d=yv[6 + nb],
                  beta_d=yv[7 + nb], phi_0=ph0)
        acc, _, _, _ = device_accelerations(case, False, gs, W=W, dW=dW, state=st, ball_angles=list(yv[4:4 + nb]),
                                            ball_rates=list(yv[8 + nb:8 + 2 * nb]))
        return np.concatenate([yv[4 + nb:], acc])
    # piecewise between the table's corners (the drive is not smooth there)
    cuts = sorted(set([0.0] + [t for t in T if 0.0 < t < ts[-1]] + [float(ts[-1])]))
    Y = np.zeros((8 + 2 * nb, len(ts)))
    y = y0
    for a0, a1 in zip(cuts[:-1], cuts[1:]):
        sel = (ts >= a0) & (ts <= a1)
        sol = solve_ivp(rhs, (a0, a1), y, method='DOP853', rtol=1e-11, atol=1e-14, t_eval=ts[sel])
        if not sol.success:
            raise SystemExit('SciPy failed: %s' % sol.message)
        Y[:, sel] = sol.y
        sol2 = solve_ivp(rhs, (a0, a1), y, method='DOP853', rtol=1e-11, atol=1e-14)
        y = sol2.y[:, -1]
    names = ['x', 'y', 'alpha', 'beta'] + ['state_phi_%d' % (i + 1) for i in range(nb)]
    worst = {}
    ok = True
    for i, n in enumerate(names):
        c = f['/rotor/transient/' + n][()]
        scale = max(np.max(np.abs(Y[i])), 1e-12) if i < 4 else 1.0
        d = np.max(np.abs(c - Y[i])) / scale
        worst[n] = d
        tol = 1e-8   # relative to the largest |q|; rad for the balls (measured: 1e-11)
        if not d <= tol:
            ok = False
    print('SciPy DOP853 (rtol 1e-11) of docs/device.md with gravity vs the archive, %d samples to t = %g s: %s'
          % (len(ts), ts[-1], ', '.join('%s %.2e' % kv for kv in worst.items())))
    return ok


def bottom(path, t_check):
    f, case = load(path)
    r = f['/rotor']
    gs = float(r.attrs['g']) * math.sin(float(r.attrs['shaft_angle']))
    T, V = drive(f)
    ts = f['/rotor/transient/time'][()]
    i = int(np.argmin(np.abs(ts - t_check)))
    W, dW, _ = spin(T, V, ts[i])
    ok = dW == 0.0
    k = 0
    for p in case['planes']:
        for m, rr, h in zip(p['m'], p['r'], p['h']):
            phi = f['/rotor/transient/state_phi_%d' % (k + 1)][i]
            phi_w = math.remainder(phi, 2 * math.pi)
            want = -math.pi / 2 + math.asin(h * rr * W / (m * gs))
            print('ball %d at t = %g s (Omega = %g rad/s, constant): phi = %.7f rad, equilibrium near the bottom '
                  '-pi/2 + asin(h r Omega/(m g_s)) = %.7f rad (the bottom itself: %.7f), difference %.2e rad'
                  % (k + 1, ts[i], W, phi_w, want, -math.pi / 2, phi_w - want))
            if not abs(phi_w - want) < 1e-4:
                ok = False
            k += 1
    return ok


def offset(path, t0, t1):
    f, case = load(path)
    r = f['/rotor']
    k = lumped(case['parameters'])
    gs = float(r.attrs['g']) * math.sin(float(r.attrs['shaft_angle']))
    W = k['M'] + sum(p['m0'] + sum(p['m']) for p in case['planes'])
    D = sum(p['d'] * (p['m0'] + sum(p['m'])) for p in case['planes'])
    det = k['c_y'] * k['c_a'] - k['c_ya'] ** 2
    ys = -gs * (W * k['c_a'] + k['c_ya'] * D) / det
    als = gs * (k['c_y'] * D + k['c_ya'] * W) / det
    ok = abs(r.attrs['static_offset_y'] - ys) <= 1e-14 * abs(ys) and abs(r.attrs['static_offset_alpha'] - als) <= 1e-14 * abs(als)
    if t1 < t0:  # the attributes only
        print('static offset: archive y_s = %.9g m, alpha_s = %.9g rad; closed form %.9g m, %.9g rad'
              % (r.attrs['static_offset_y'], r.attrs['static_offset_alpha'], ys, als))
        return ok
    ts = f['/rotor/transient/time'][()]
    sel = (ts >= t0) & (ts <= t1)
    ym, am = np.mean(f['/rotor/transient/y'][()][sel]), np.mean(f['/rotor/transient/alpha'][()][sel])
    print('static offset: archive y_s = %.9g m, alpha_s = %.9g rad; closed form %.9g m, %.9g rad; mean over '
          '[%g, %g] s: y = %.9g m, alpha = %.9g rad (relative %.1e, %.1e)'
          % (r.attrs['static_offset_y'], r.attrs['static_offset_alpha'], ys, als, t0, t1, ym, am,
             abs(ym / ys - 1), abs(am / als - 1)))
    return ok and abs(ym / ys - 1) < 1e-3 and abs(am / als - 1) < 1e-3


def ratio(path):
    f, case = load(path)
    r = f['/rotor']
    gs = float(r.attrs['g']) * math.sin(float(r.attrs['shaft_angle']))
    W = abs(f['/rotor/transient/Omega'][-1])
    ok = True
    nb0 = 0
    for j, p in enumerate(case['planes']):
        want = gs / (min(p['r']) * W * W)
        got = f['/rotor/plane%d' % (j + 1)].attrs['gravity_ratio_final']
        # carried round: over the last second each ball turns many times (lying at the bottom it would not)
        ts = f['/rotor/transient/time'][()]
        i0 = int(np.argmin(np.abs(ts - (ts[-1] - 1.0))))
        turns = [(f['/rotor/transient/state_phi_%d' % (nb0 + i + 1)][-1] - f['/rotor/transient/state_phi_%d' % (nb0 + i + 1)][i0])
                 / (2 * math.pi) for i in range(len(p['m']))]
        print('plane %d: gravity_ratio_final %.9g, g_s/(r Omega^2) at Omega = %g rad/s: %.9g; turns of the balls '
              'in the last second: %s' % (j + 1, got, W, want, ', '.join('%.1f' % x for x in turns)))
        ok = ok and abs(got - want) <= 1e-14 * want and want < 1 and min(turns) > 10
        nb0 += len(p['m'])
    return ok


def frames(a, b):
    """The fixed-frame and the rotating-frame run of the same configuration: rotor coordinates and the
    balls' angles relative to the rotor (outputs p<j>_b<i>_psi) agree to the integration tolerance."""
    fa, fb = h5py.File(a, 'r'), h5py.File(b, 'r')
    ga, gb = fa['/rotor/transient'], fb['/rotor/transient']
    names = ['x', 'y', 'alpha', 'beta'] + [n for n in ga if n.endswith('_psi') and n.startswith('p')]
    worst = 0.0
    for n in names:
        va, vb = ga[n][()], gb[n][()]
        scale = max(np.max(np.abs(va)), 1e-12) if n in ('x', 'y', 'alpha', 'beta') else 1.0
        worst = max(worst, np.max(np.abs(va - vb)) / scale)
    print('fixed vs rotating frame: %s largest difference %.2e (relative to the largest |q|; rad for psi)'
          % (', '.join(names), worst))
    return worst < 1e-7 and fb['/rotor/transient'].attrs['frame'] == 'rotating'


def same(a, b):
    fa, fb = h5py.File(a, 'r'), h5py.File(b, 'r')
    ga, gb = fa['/rotor/transient'], fb['/rotor/transient']
    names = [n for n in ga if isinstance(ga[n], h5py.Dataset)]
    diff = [n for n in names if n not in gb or not np.array_equal(ga[n][()], gb[n][()], equal_nan=True)]
    print('%d series compared bit for bit, %d differ%s' % (len(names), len(diff), (': ' + ', '.join(diff)) if diff else ''))
    return not diff and len(names) > 10


if __name__ == '__main__':
    cmd = sys.argv[1]
    if cmd == 'scipy':
        r = scipy_run(sys.argv[2])
    elif cmd == 'bottom':
        r = bottom(sys.argv[2], float(sys.argv[3]))
    elif cmd == 'offset':
        r = offset(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
    elif cmd == 'ratio':
        r = ratio(sys.argv[2])
    elif cmd == 'frames':
        r = frames(sys.argv[2], sys.argv[3])
    elif cmd == 'same':
        r = same(sys.argv[2], sys.argv[3])
    else:
        raise SystemExit('unknown check ' + cmd)
    sys.exit(0 if r else 1)
