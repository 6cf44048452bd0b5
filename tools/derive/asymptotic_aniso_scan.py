#!/usr/bin/env python3
"""Anisotropic supports, light balls (docs/rotor.md "Anisotropic supports"): the library's prediction
(autobal_rotor_asymptotic_conditions with G = G+) against the Floquet multipliers of the full model
(autobal rotor stability, method floquet), on random one-plane machines.

For each machine: `autobal rotor stability -o X.h5 --json`; G+ and G- recomputed here from the archived
lumped coefficients (NumPy solve of the 4x4 fixed-frame Z(+-i omega), an implementation apart from the
C code); the verdict of every decided, applicable prediction compared with the exact (Floquet) verdict.

Run:  /usr/bin/python3 tools/derive/asymptotic_aniso_scan.py AUTOBAL [n_machines] [seed] [small]
      /usr/bin/python3 tools/derive/asymptotic_aniso_scan.py AUTOBAL high|high-any-q [n_machines] [seed]
Prints one summary line and exits 1 on a disagreement or a G+/G- mismatch."""
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

# M, H, K of (3.2) without balls, coordinates (x, y, alpha, beta): the app tests' Python model
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tests', 'app'))
from rotor_stability_check import rotor_matrices  # noqa: E402


def g_pm(L, w, d):
    """(G+, G-): a force F e^{i w t} on the plane moves its centre u + i v by G+ F e^{i w t} + G- conj(F) e^{-i w t}"""
    M, H, K = rotor_matrices(L, w)
    eu = np.array([1, 0, 0, d]); ev = np.array([0, 1, -d, 0])
    # f_u = Re(F e^{iwt}), f_v = Im(F e^{iwt}): generalized force (e_u - i e_v)/2 F e^{iwt} + c.c.
    xp = np.linalg.solve(-M * w * w + 1j * w * H + K, (eu - 1j * ev) / 2)
    xm = np.linalg.solve(-M * w * w - 1j * w * H + K, (eu + 1j * ev) / 2)
    return (eu + 1j * ev) @ xp, (eu + 1j * ev) @ xm


def draw(rng):
    """a random anisotropic machine around the default rotor: (omega, --set list, plane d)"""
    w = np.exp(rng.uniform(np.log(120), np.log(3000))) * (1 if rng.uniform() < 0.85 else -1)
    a1, a2 = np.exp(rng.uniform(np.log(0.4), np.log(2.5), 2))
    hs = np.exp(rng.uniform(np.log(20), np.log(600)))
    hy = np.exp(rng.uniform(np.log(0.5), np.log(2), 2))
    mb = np.exp(rng.uniform(np.log(1e-6), np.log(3e-3)))
    g = rng.uniform(0.05, 1.5)                      # balls at psi0 + pi -+ g: q = |cos 2g|
    kap = np.exp(rng.uniform(np.log(0.003), np.log(10)))
    d = rng.uniform(-0.15, 0.15)
    s0 = 2 * mb * 0.1 * np.cos(g)
    sets = ['rotor.omega=%.17g' % w, 'supports.c_Lx=1e5', 'supports.c_Ly=%.17g' % (1e5 * a1),
            'supports.c_Rx=1.5e5', 'supports.c_Ry=%.17g' % (1.5e5 * a2),
            'supports.h_Lx=%.17g' % hs, 'supports.h_Ly=%.17g' % (hs * hy[0]),
            'supports.h_Rx=%.17g' % (1.5 * hs), 'supports.h_Ry=%.17g' % (1.5 * hs * hy[1]),
            'plane1.d=%.17g' % d, 'plane1.m0=%.17g' % (s0 / 0.1), 'plane1.r0=0.1',
            'plane1.ball_mass=%.17g,%.17g' % (mb, mb), 'plane1.ball_radius=0.1,0.1',
            'plane1.ball_damping=%.17g,%.17g' % (kap * mb, kap * mb), 'stability.critical_speeds=false']
    return w, sets, d


def high(autobal, n, seed, small, any_q=False):
    """High speed (H1), (H2) with G = G+ (eta the mean of the x and y planes' damping): random anisotropic machines
    (draw(), omega |w| in [3000, 40000] rad/s, balls of 1e-6 .. 1e-4 kg at q = 0, i.e. at right angles), ball
    damping kappa = kappa_inf e^(+-U(0.2, 1)) (kappa_inf from a first run); the prediction kappa > kappa_inf against
    the Floquet verdict where applicable, and the predicted largest real part (kappa_inf - kappa) / 2 against the
    Floquet margin.  any_q: the balls at a random angle apart (q uniform in the angle) and kappa > kappa_inf only: the
    claim "stable for every unbalance" when kappa > kappa_inf.  Returns the number of disagreements."""
    rng = np.random.default_rng(seed)
    tmp = tempfile.mkdtemp(prefix='aniso_high')
    fn = os.path.join(tmp, 'x.h5')
    nm = n_app = agree = nps = 0
    rel = []
    relxy = []
    bad = []
    for _ in range(n):
        _, sets, d = draw(rng)
        w = np.exp(rng.uniform(np.log(3000), np.log(40000))) * (1 if rng.uniform() < 0.85 else -1)
        mb = np.exp(rng.uniform(np.log(1e-6), np.log(1e-4)))
        f = np.exp(rng.choice([-1, 1]) * rng.uniform(0.2, 1.0))
        g = rng.uniform(0.05, np.pi / 2 - 0.05) if any_q else np.pi / 4
        if any_q:
            f = abs(f) if f > 1 else 1 / f
        sets = [x for x in sets if not x.startswith(('rotor.omega=', 'plane1.ball_mass=', 'plane1.ball_damping=',
                                                      'plane1.m0='))]
        sets += ['rotor.omega=%.17g' % w, 'plane1.ball_mass=%.17g,%.17g' % (mb, mb),
                 'plane1.m0=%.17g' % (2 * mb * np.cos(g))]
        out = None
        for kap in (1.0, None):
            if kap is None:
                kap = out['asymptotic']['high_kappa_inf'] * f
            cmd = [autobal, 'rotor', 'stability', '--json', '--force', '-o', fn] + sum(
                [['--set', x] for x in sets + ['plane1.ball_damping=%.17g,%.17g' % (kap * mb, kap * mb)]], [])
            r = subprocess.run(cmd, capture_output=True, text=True)
            if r.returncode != 0:
                out = None
                break
            out = json.loads(r.stdout)
            if not out.get('asymptotic', {}).get('high_defined') or not out['asymptotic'].get('anisotropic'):
                out = None
                break
        if out is None or out.get('method') != 'floquet':
            continue
        a = out['asymptotic']
        nm += 1
        if a['high_small'] > small:
            continue
        n_app += 1
        exact = out['margin']
        pred = (a['high_kappa_inf'] - a['kappa']) / 2
        if any_q:  # only the verdict: stable
            nps += a['high_predicts_stable']
            agree += (exact < 0) and a['high_predicts_stable']
            if not ((exact < 0) and a['high_predicts_stable']):
                bad.append((w, mb, f, exact, pred, a['high_small']))
            continue
        rel.append(abs(pred - exact) / abs(pred))
        # the same from the archived lumped coefficients (this file's own formula): kappa_inf with eta the mean of
        # the planes' terms, and with the x plane's or the y plane's alone (the mean must win)
        with h5py.File(fn, 'r') as h:
            L = {k: float(v) for k, v in h['rotor/lumped'].attrs.items() if not k.endswith('_units')}
        Ap = L['A'] - L['C']
        ginf = 1 / L['M'] + d * d / Ap
        ex_ = L['h_x'] / L['M']**2 - 2 * d * L['h_xbeta'] / (L['M'] * Ap) + d * d * L['h_beta'] / Ap**2
        ey_ = L['h_y'] / L['M']**2 - 2 * d * L['h_yalpha'] / (L['M'] * Ap) + d * d * L['h_alpha'] / Ap**2
        ki = [np.sqrt(0.5 * 2 * mb * ginf) * e / ginf for e in (0.5 * (ex_ + ey_), ex_, ey_)]  # both balls' mass
        assert abs(ki[0] - a['high_kappa_inf']) <= 1e-12 * abs(ki[0]), (ki, a['high_kappa_inf'])
        for j in (1, 2):
            relxy.append(abs((ki[j] - a['kappa']) / 2 - exact) / abs(pred))
        nps += a['high_predicts_stable']
        if (exact < 0) == bool(a['high_predicts_stable']):
            agree += 1
        else:
            bad.append((w, mb, f, exact, pred, a['high_small']))
    print('anisotropic supports, high speed, %s, seed %d: %d machines; small <= %g: applicable %d, agree %d '
          '(predicted STABLE %d); predicted max Re (kappa_inf - kappa)/2 vs the Floquet margin: median rel. error %.2e, '
          'largest %.2e; with the damping of one plane alone (x or y) instead of the mean: median %.2e'
          % ('q random, kappa > kappa_inf' if any_q else 'q = 0', seed, nm, small, n_app, agree, nps,
             np.median(rel) if rel else np.nan, np.max(rel) if rel else np.nan,
             np.median(relxy) if relxy else np.nan))
    for b in bad:
        print('   DISAGREES: omega %g, m_b %g, kappa/kappa_inf %g, exact margin %g, predicted %g, small %g' % b)
    return len(bad)


def main():
    autobal = sys.argv[1]
    if len(sys.argv) > 2 and sys.argv[2] in ('high', 'high-any-q'):
        n = int(sys.argv[3]) if len(sys.argv) > 3 else 100
        seed = int(sys.argv[4]) if len(sys.argv) > 4 else 1
        return 1 if high(autobal, n, seed, 0.05, sys.argv[2] == 'high-any-q') else 0
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    small = float(sys.argv[4]) if len(sys.argv) > 4 else 0.05
    rng = np.random.default_rng(seed)
    tmp = tempfile.mkdtemp(prefix='aniso_scan')
    fn = os.path.join(tmp, 'x.h5')
    nm = n_app = n_dec = agree = n_pst = 0
    worst_g = 0.0
    errs = []
    rerrs = []
    bad = []
    for _ in range(n):
        w, sets, d = draw(rng)
        cmd = [autobal, 'rotor', 'stability', '--json', '--force', '-o', fn] + sum([['--set', s] for s in sets], [])
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            continue                                # e.g. no balanced configuration: not a machine here
        js = json.loads(r.stdout)
        a = js.get('asymptotic')
        if a is None or not a.get('anisotropic'):
            continue
        with h5py.File(fn, 'r') as f:
            L = {k: float(v) for k, v in f['rotor/lumped'].attrs.items() if not k.endswith('_units')}
            method = f['rotor/stability'].attrs['method']
        gp, gm = g_pm(L, w, d)
        worst_g = max(worst_g, abs(complex(a['G_real'], a['G_imag']) - gp) / abs(gp),
                      abs(complex(a['G_minus_real'], a['G_minus_imag']) - gm) / abs(gp))
        nm += 1
        if method != 'floquet':
            continue
        exact = js['margin']
        pred = max(max(a['light_ball_root_real']), a.get('light_rotor_root_real') and max(
            x for x in a['light_rotor_root_real'] if x == x) or -np.inf)
        # all 12 real parts: the Floquet exponents log|mu| / T against the 4 ball roots and the 8 shifted rotor
        # roots (4 reported, each with its partner of the same real part), sorted
        mu = np.array(js['floquet_mu_real']) + 1j * np.array(js['floquet_mu_imag'])
        ex = np.sort(np.log(np.abs(mu)) / js['period'])
        pr = np.sort(np.array(a['light_ball_root_real'] + 2 * a['light_rotor_root_real']))
        if a['light_small'] <= small:
            n_app += 1
            errs.append(abs(pred - exact) / max(abs(exact), 1e-300))
            if len(ex) == len(pr):
                rerrs.append(np.max(np.abs(ex - pr) / np.maximum(np.abs(ex), 1e-300)))
            if a['light_decided']:
                n_dec += 1
                n_pst += a['light_predicts_stable']
                if (exact < 0) == bool(a['light_predicts_stable']):
                    agree += 1
                else:
                    bad.append((w, exact, pred, a['light_small']))
    print('anisotropic supports, light balls, seed %d: %d machines, G+/G- vs NumPy max rel. diff %.2e; small <= %g: '
          'applicable %d, decided %d, agree %d (predicted STABLE %d); max Re predicted vs Floquet, median rel. '
          'error %.2e; all 12 real parts vs the Floquet exponents, median of the largest rel. error %.2e'
          % (seed, nm, worst_g, small, n_app, n_dec, agree, n_pst, np.median(errs) if errs else np.nan,
             np.median(rerrs) if rerrs else np.nan))
    for b in bad:
        print('   DISAGREES: omega %g, exact margin %g, predicted max Re %g, small %g' % b)
    return 0 if not bad and worst_g < 1e-9 else 1


if __name__ == '__main__':
    sys.exit(main())
