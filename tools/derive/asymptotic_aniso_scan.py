#!/usr/bin/env python3
"""Anisotropic supports, light balls (docs/rotor.md "Anisotropic supports"): the library's prediction
(autobal_rotor_asymptotic_conditions with G = G+) against the Floquet multipliers of the full model
(autobal rotor stability, method floquet), on random one-plane machines.

For each machine: `autobal rotor stability -o X.h5 --json`; G+ and G- recomputed here from the archived
lumped coefficients (NumPy solve of the 4x4 fixed-frame Z(+-i omega), an implementation apart from the
C code); the verdict of every decided, applicable prediction compared with the exact (Floquet) verdict.

Run:  /usr/bin/python3 tools/derive/asymptotic_aniso_scan.py AUTOBAL [n_machines] [seed] [small]
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


def main():
    autobal = sys.argv[1]
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
