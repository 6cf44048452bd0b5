#!/usr/bin/env bash
# rotor stability: the asymptotic conditions reported beside the exact verdict (docs/rotor.md
# "Asymptotic conditions"): console lines, JSON field `asymptotic`, archive group
# /rotor/stability/asymptotic with units, each recomputed with NumPy (rotor_asymptotic_check.py):
#  (a) the default rotor at 500 rad/s (balls too heavy: not applicable, undecided);
#  (b) light balls (5e-6 kg) below the first resonance, 100 rad/s: predicted and exactly UNSTABLE;
#  (c) light balls (5e-7 kg) at 2000 rad/s, balls at right angles (q = 0), ball damping below and above kappa_min;
#  (d) a disk-like rotor (C > A, 0 < C - A < M d^2): (H1) fails, high speed predicts UNSTABLE;
#  (e) two planes: the two-plane light-ball condition (rotor_asymptotic2_check.py), not the one-plane ones;
#      light balls below (150 rad/s) and above (800 rad/s) the resonances;
#  (f) undamped balls (kappa = 0): the next-order entry instead of (L1), (L2);
#  (g) two planes at high speed with the balls at q = 0: (H1'), (H2');
#  (h) anisotropic supports: (L1), (L2) with the forward receptance G+ (console, JSON, archive; G+ and G-
#      against NumPy), and the scan tools/derive/asymptotic_aniso_scan.py on 60 random machines against the
#      Floquet multipliers (every decided prediction must agree); isotropic archives carry no anisotropic keys;
#      the high-speed entries (mean damping) on 25 random machines at q = 0 against Floquet.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

one() { # name omega d m hb m0 [C]: run console, JSON and archive, then the NumPy check
  local name=$1 w=$2 d=$3 m=$4 hb=$5 m0=$6 C=${7:-0.03}
  printf '[rotor]\nomega = %s\nC_p = %s\n[plane1]\nd = %s\nball_mass = %s, %s\nball_damping = %s, %s\nm0 = %s\n[stability]\ncritical_speeds = false\n' \
    "$w" "$C" "$d" "$m" "$m" "$hb" "$hb" "$m0" > "$name.ini"
  expect 0 "asymptotic conditions (for comparison only" "$AUTOBAL" rotor stability "$name.ini"
  cp out.txt "$name.txt"
  "$AUTOBAL" rotor stability "$name.ini" --json > "$name.json" 2>err.txt || bad "$name: json run"
  "$AUTOBAL" rotor stability "$name.ini" -o "$name.h5" > /dev/null 2>err.txt || bad "$name: archive run"
  if "$PY" "$here/rotor_asymptotic_check.py" "$name.json" "$name.h5" "$w" "$d" "$m" "$hb" "$m0" "$C" > chk.txt 2>&1; then
    ok "$name: NumPy check ($(grep -c '^ok' chk.txt) checks)"
  else
    bad "$name: NumPy check"; cat chk.txt
  fi
}
verdict_of() { "$PY" -c 'import json,sys; j=json.load(open(sys.argv[1])); print(j["verdict"], j["asymptotic"][sys.argv[2]], j["asymptotic"]["light_decided"], j["asymptotic"]["light_applicable"])' "$1" "$2"; }

one default 500 0.1 0.05 0.1 0.02
grep -q "predicts STABLE (undecided" default.txt && ok "default: light balls undecided (small parameter > 1)" || { bad "default: console line"; cat default.txt; }

one sub 100 0.1 5e-6 1e-5 2e-6
read -r v p dec app < <(verdict_of sub.json light_predicts_stable)
[ "$v $p $dec $app" = "unstable False True True" ] && ok "100 rad/s, light balls: exactly unstable, predicted UNSTABLE, decided, applicable" || bad "100 rad/s: $v $p $dec $app"
grep -q "predicts UNSTABLE; small parameter" sub.txt && ok "console: predicts UNSTABLE" || { bad "console 100 rad/s"; cat sub.txt; }

# q = 0: m0 r0 = sqrt(2) m r; kappa_min at 2000 rad/s is 0.0124 1/s for balls of 5e-7 kg (NumPy check above)
m0q=$("$PY" -c 'print(2**0.5 * 5e-7 * 0.1 / 0.1)')
one lowdamp 2000 0.1 5e-7 4e-9 "$m0q"
read -r v p dec app < <(verdict_of lowdamp.json light_predicts_stable)
[ "$v $p $dec $app" = "unstable False True True" ] && ok "2000 rad/s, q = 0, kappa = 0.008 < kappa_min: unstable, predicted UNSTABLE" || bad "lowdamp: $v $p $dec $app"
one highdamp 2000 0.1 5e-7 1e-8 "$m0q"
read -r v p dec app < <(verdict_of highdamp.json light_predicts_stable)
[ "$v $p $dec $app" = "stable True True True" ] && ok "2000 rad/s, q = 0, kappa = 0.02 > kappa_min: stable, predicted STABLE" || bad "highdamp: $v $p $dec $app"

one disk 5000 0.1 5e-5 5e-4 2e-5 0.2
read -r v p dec app < <(verdict_of disk.json high_predicts_stable)
[ "$v $p" = "unstable False" ] && ok "disk-like rotor (C - A = 0.04 < M d^2 = 0.1), 5000 rad/s: unstable, high speed predicts UNSTABLE" || bad "disk: $v $p"
grep -q "UNSTABLE for every unbalance" disk.txt && ok "console: UNSTABLE for every unbalance" || { bad "console disk"; cat disk.txt; }

# (f) undamped balls (kappa = 0): the default rotor at 500 rad/s, balls of 5e-6 kg, q = 0.9: on the axis to leading
#     order, the next order says UNSTABLE (exact margin +9.64e-6 1/s, tests/test_rotor_asymptotic.c)
m0u=$("$PY" -c 'print(2 * 5e-6 * 0.1 * (1.9 / 2) ** 0.5 / 0.1)')
one undamped 500 0.1 5e-6 0 "$m0u"
read -r v p dec app < <("$PY" -c 'import json,sys; j=json.load(open(sys.argv[1])); a=j["asymptotic"]; print(j["verdict"], a["undamped_predicts_stable"], a["undamped_decided"], a["undamped_applicable"])' undamped.json)
[ "$v $p $dec $app" = "unstable False True True" ] && ok "kappa = 0, light balls, 500 rad/s: exactly unstable, next order predicts UNSTABLE, decided, applicable" || bad "undamped: $v $p $dec $app"
grep -q "undamped balls (kappa = 0): ball roots on the axis to leading order, next order" undamped.txt && ok "console: the undamped line" || { bad "console undamped"; cat undamped.txt; }
grep -q "light balls: (L1)" undamped.txt && bad "kappa = 0: (L1)/(L2) line printed" || ok "kappa = 0: no (L1)/(L2) line"

expect 0 "" "$AUTOBAL" rotor stability "$DATA/rotor_two_planes.ini" --set stability.critical_speeds=false
grep -q "asymptotic conditions (for comparison" out.txt && bad "two planes: one-plane conditions printed" || ok "two planes: no one-plane conditions"
grep -q "asymptotic condition, two planes (for comparison only" out.txt && ok "two planes: the two-plane condition printed" || bad "two planes: no two-plane condition"

two() { # name omega d1 d2 m1 m2 h1 h2 s1 s2 psi1 psi2: two planes, console, JSON, archive, NumPy check
  local name=$1 w=$2 d1=$3 d2=$4 m1=$5 m2=$6 h1=$7 h2=$8 s1=$9 s2=${10} p1=${11} p2=${12}
  printf '[rotor]\nomega = %s\n[plane1]\nd = %s\nr0 = 0.1\nm0 = %s\npsi0 = %s\nball_mass = %s, %s\nball_radius = 0.1, 0.1\nball_damping = %s, %s\n[plane2]\nd = %s\nr0 = 0.1\nm0 = %s\npsi0 = %s\nball_mass = %s, %s\nball_radius = 0.1, 0.1\nball_damping = %s, %s\n[stability]\ncritical_speeds = false\n' \
    "$w" "$d1" "$("$PY" -c "print($s1 / 0.1)")" "$p1" "$m1" "$m1" "$h1" "$h1" "$d2" "$("$PY" -c "print($s2 / 0.1)")" "$p2" "$m2" "$m2" "$h2" "$h2" > "$name.ini"
  expect 0 "asymptotic condition, two planes (for comparison only" "$AUTOBAL" rotor stability "$name.ini"
  cp out.txt "$name.txt"
  "$AUTOBAL" rotor stability "$name.ini" --json > "$name.json" 2>err.txt || bad "$name: json run"
  "$AUTOBAL" rotor stability "$name.ini" -o "$name.h5" > /dev/null 2>err.txt || bad "$name: archive run"
  if "$PY" "$here/rotor_asymptotic2_check.py" "$name.json" "$name.h5" "$w" "$d1" "$d2" "$m1" "$m2" "$h1" "$h2" "$s1" "$s2" "$p1" "$p2" > chk.txt 2>&1; then
    ok "$name: NumPy check ($(grep -c '^ok' chk.txt) checks)"
  else
    bad "$name: NumPy check"; cat chk.txt
  fi
}
verdict2() { "$PY" -c 'import json,sys; j=json.load(open(sys.argv[1])); a=j["asymptotic2"]; print(j["verdict"], a["light_predicts_stable"], a["light_decided"], a["light_applicable"])' "$1"; }
# light balls (balls of 5e-6 / 4e-6 kg, kappa 2 and 3 1/s): below the first resonance and above it
two two_sub 150 0.1 -0.12 5e-6 4e-6 1e-5 1.2e-5 2e-7 1.5e-7 0 2
read -r v p dec app < <(verdict2 two_sub.json)
[ "$v $p $dec $app" = "unstable False True True" ] && ok "two planes, 150 rad/s, light balls: exactly unstable, predicted UNSTABLE, decided, applicable" || bad "two_sub: $v $p $dec $app"
two two_super 800 0.1 -0.12 5e-6 4e-6 1e-5 1.2e-5 2e-7 1.5e-7 0 2
read -r v p dec app < <(verdict2 two_super.json)
[ "$v $p $dec $app" = "stable True True True" ] && ok "two planes, 800 rad/s, light balls: exactly stable, predicted STABLE, decided, applicable" || bad "two_super: $v $p $dec $app"
# (g) two planes at high speed, balls at q = 0 in both planes (m0 r0 = sqrt(2) m r), 1e5 rad/s, kappa 0.0615 1/s in both
#     planes, 1.25 times the larger kappa_inf_k = 0.0492 1/s (tests/test_rotor_asymptotic2.c): stable, (H2') holds
s1q=$("$PY" -c 'print(2**0.5 * 5e-6 * 0.1)'); s2q=$("$PY" -c 'print(2**0.5 * 4e-6 * 0.1)')
two two_high 1e5 0.1 -0.12 5e-6 4e-6 3.075e-7 2.46e-7 "$s1q" "$s2q" 0 0
read -r v p dec app < <("$PY" -c 'import json,sys; j=json.load(open(sys.argv[1])); a=j["asymptotic2"]; print(j["verdict"], a["high_predicts_stable"], a["high_decided"], a["high_applicable"])' two_high.json)
[ "$v $p $dec $app" = "stable True True True" ] && ok "two planes, 1e5 rad/s, q = 0: exactly stable, (H2') predicts STABLE, decided, applicable" || bad "two_high: $v $p $dec $app"
grep -q "high speed, balls at q = 0 in both planes: (H1') Gamma positive definite \[yes\]" two_high.txt && ok "console: the two-plane high-speed line" || { bad "console two_high"; cat two_high.txt; }
# every unbalance and phase: kappa_all = rho sqrt(mu_2) from the archived Gamma, H (NumPy eigenvalues of Gamma^-1 H;
# mu_2 of Mb^1/2 Gamma Mb^1/2 with Mb = 2 m_j), JSON = archive, console line; kappa 0.08 1/s in both planes
# (> kappa_all = 0.0765), q1 = 0.28, q2 = 0.61, phase 1 rad: predicted STABLE for every unbalance, exactly stable; then
# unequal kappa, 0.08 and 0.3 1/s (min > kappa_all): the same claim, exactly stable
for hb2 in 3.2e-7 1.2e-6; do
ev=two_every_$hb2
two "$ev" 1e5 0.1 -0.12 5e-6 4e-6 4e-7 $hb2 8e-7 5e-7 0 1
if "$PY" - "$ev.json" "$ev.h5" 5e-6 4e-6 > chk.txt 2>&1 <<'PY'
import json, sys
import h5py, numpy as np
j = json.load(open(sys.argv[1]))['asymptotic2']; g = h5py.File(sys.argv[2], 'r')['rotor/stability/asymptotic2'].attrs
G = np.array(j['high_Gamma']).reshape(2, 2); H = np.array(j['high_H']).reshape(2, 2)
Sq = np.diag(np.sqrt([2 * float(sys.argv[3]), 2 * float(sys.argv[4])]))
ka = np.abs(np.linalg.eigvals(np.linalg.solve(G, H))).max() * np.sqrt(np.linalg.eigvalsh(Sq @ G @ Sq).max())
assert abs(j['high_every_kappa'] - ka) < 1e-12 * ka, (j['high_every_kappa'], ka)
assert abs(j['high_every_kappa_min'] - 0.08) < 1e-12 and g['high_every_kappa_min'] == j['high_every_kappa_min'] and j['high_every_predicts_stable'] and j['high_every_applicable']
assert g['high_every_kappa'] == j['high_every_kappa'] and g['high_every_kappa_units'] == '1/s' and g['high_every_predicts_stable'] == 1
assert json.load(open(sys.argv[1]))['verdict'] == 'stable'
print('ok', ka)
PY
then ok "two planes, every unbalance at high speed (ball damping of plane 2 $hb2): kappa_all = NumPy, JSON = archive, predicted and exactly stable ($(cat chk.txt))"; else bad "$ev"; cat chk.txt; fi
done
grep -q "high speed, every unbalance and phase: min kappa 0.0615 > 0.0764853 1/s \[no\]" two_high.txt \
  && ok "console: 0.0615 < kappa_all: no claim for every unbalance" || { bad "console two_high every"; cat two_high.txt; }
# (h) anisotropic supports, light balls (1e-5 kg, kappa 2 1/s) at 1000 rad/s: decided STABLE, and the Floquet
#     verdict; G+ and G- recomputed with NumPy (asymptotic_aniso_scan.g_pm, a 4x4 complex solve of its own)
printf '[rotor]\nomega = 1000\n[supports]\nc_Ly = 1.6e5\nc_Ry = 2.4e5\nh_Ly = 160\n[plane1]\nd = 0.1\nball_mass = 1e-5, 1e-5\nball_damping = 2e-5, 2e-5\nm0 = 1.9e-5\n[stability]\ncritical_speeds = false\n' > aniso.ini
expect 0 "anisotropic supports: G = G+ = " "$AUTOBAL" rotor stability aniso.ini
grep -q "predicts STABLE; small parameter" out.txt && ok "anisotropic: console predicts STABLE (decided)" || { bad "anisotropic console"; cat out.txt; }
"$AUTOBAL" rotor stability aniso.ini --json > aniso.json 2>err.txt || bad "anisotropic: json run"
"$AUTOBAL" rotor stability aniso.ini -o aniso.h5 > /dev/null 2>err.txt || bad "anisotropic: archive run"
if "$PY" - "$TOOLS/derive" aniso.json aniso.h5 > chk.txt 2>&1 <<'PY'
import json, sys
import h5py
sys.path.insert(0, sys.argv[1])
from asymptotic_aniso_scan import g_pm
j = json.load(open(sys.argv[2])); a = j['asymptotic']
f = h5py.File(sys.argv[3], 'r'); g = f['rotor/stability/asymptotic'].attrs
L = {k: float(v) for k, v in f['rotor/lumped'].attrs.items() if not k.endswith('_units')}
gp, gm = g_pm(L, 1000.0, 0.1)
assert j['method'] == 'floquet' and j['verdict'] == 'stable', (j['method'], j['verdict'])
assert a['anisotropic'] is True and a['light_decided'] and a['light_applicable'] and a['light_predicts_stable']
assert abs(complex(a['G_real'], a['G_imag']) - gp) < 1e-12 * abs(gp), (a['G_real'], a['G_imag'], gp)
assert abs(complex(a['G_minus_real'], a['G_minus_imag']) - gm) < 1e-12 * abs(gp), (a['G_minus_real'], gm)
assert abs(gm) > 1e-3 * abs(gp), gm
assert g['anisotropic'] == 1 and g['G_minus_real_units'] == 'm/N' and g['avg_small_units'] == '1'
assert g['G_minus_real'] == a['G_minus_real'] and g['G_real'] == a['G_real']
print('ok')
PY
then ok "anisotropic: JSON and archive, G+ and G- = NumPy (1e-12)"; else bad "anisotropic: JSON/archive check"; cat chk.txt; fi
"$PY" -c 'import h5py,sys; sys.exit(1 if "anisotropic" in h5py.File(sys.argv[1], "r")["rotor/stability/asymptotic"].attrs else 0)' default.h5 \
  && ok "isotropic archive: no anisotropic keys (unchanged)" || bad "isotropic archive has anisotropic keys"
if "$PY" "$TOOLS/derive/asymptotic_aniso_scan.py" "$AUTOBAL" 60 1 0.2 > scan.txt 2>&1; then
  n=$(sed -n 's/.*decided \([0-9]*\), agree \([0-9]*\).*/\1 \2/p' scan.txt)
  set -- $n
  [ "${1:-0}" -ge 10 ] && [ "$1" = "${2:-x}" ] && ok "anisotropic scan: $1 decided predictions, all agree with Floquet" || { bad "anisotropic scan counts: $n"; cat scan.txt; }
else
  bad "anisotropic scan"; cat scan.txt
fi
# anisotropic supports at high speed (H1), (H2) with the mean damping: 25 random machines at q = 0 against Floquet
# (every applicable prediction must agree) and the scan's own kappa_inf from the archived lumped coefficients
if "$PY" "$TOOLS/derive/asymptotic_aniso_scan.py" "$AUTOBAL" high 25 3 > scanh.txt 2>&1; then
  n=$(sed -n 's/.*applicable \([0-9]*\), agree \([0-9]*\).*/\1 \2/p' scanh.txt)
  set -- $n
  [ "${1:-0}" -ge 10 ] && [ "$1" = "${2:-x}" ] && ok "anisotropic high-speed scan: $1 applicable predictions, all agree with Floquet" || { bad "anisotropic high-speed scan counts: $n"; cat scanh.txt; }
else
  bad "anisotropic high-speed scan"; cat scanh.txt
fi
finish
