#!/usr/bin/env bash
# test_derive: the SymPy derivation of the variable-speed rotor equations and of the device physics
# (gravity, normal force, rolling resistance, stiction, rolling inertia, contact; tools/derive/).
# Runs tools/derive/derive_rotor.py with Debian's python3 (sympy); the script itself asserts
#  (a) Omega constant -> exactly (3.2)/(3.4) and (3.5)-(3.8) of docs/rotor.md (one and two planes),
#  (b) the rotating-frame ball equation with the Euler terms follows from the fixed-frame one,
#  (c) dE/dt = P_drive - D identically along the equations and to 1e-12 at the check state,
#  (e) the device checks of tools/derive/derive_device.py (each line listed below must end in ': OK'),
# and with --check-json (d) that tools/derive/check_values.json equals what it computes now;
# then tools/derive/independent_check.py re-solves the equations as written in docs/device.md with
# NumPy (no SymPy) and compares with the JSON (1e-10), and the device values (gravity accelerations,
# drive torque, normal forces, rolling inertia, rolling resistance, stuck ball, static offset, impact
# law) from a mass-matrix assembly of docs/device.md,
# and integrates the gravity-loaded balanced state with SciPy against the first-order closed form.
# Usage: test_derive.sh <source dir> [python3] [part]
#   part: rotor (derive_rotor.py, independent_check.py), asymptotic (derive_asymptotic.py), more (the
#   rest), or all (the default).  CTest runs the three parts as three tests, side by side.
set -euo pipefail
src=${1:?usage: test_derive.sh <source dir> [python3] [part]}
py=${2:-/usr/bin/python3}
part=${3:-all}
case $part in rotor|asymptotic|more|all) ;; *) echo "test_derive: part '$part' is not rotor, asymptotic, more or all"; exit 2;; esac
want() { [ "$part" = all ] || [ "$part" = "$1" ]; }
"$py" -c 'import sympy' 2>/dev/null || { echo "test_derive: $py has no sympy (bash scripts/deps.sh installs python3-sympy)"; exit 1; }
if want rotor; then
out=$("$py" "$src/tools/derive/derive_rotor.py" --quiet --check-json "$src/tools/derive/check_values.json" 2>&1) || {
  echo "$out"; echo "test_derive: FAILED"; exit 1; }
echo "$out"
# every check must have reported OK (the script raises on failure; this guards against a check
# being skipped silently)
for pat in 'exact energy truncated' 'rotating-frame ball equation' \
           'one_plane): Omega constant' 'two_planes): Omega constant' \
           'one_plane): variable speed' 'two_planes): variable speed' \
           'one_plane): dE/dt' 'two_planes): dE/dt' \
           'one_plane, prescribed' 'one_plane, motor' 'two_planes, prescribed' 'two_planes, motor' \
           'check_values.json equals' \
           'height of a small mass' 'N = -(residual of the radial coordinate' 'rotating frame: N = m' \
           'planes1): gravity adds' 'planes2): gravity adds' \
           'planes1): energy identity with gravity' 'planes2): energy identity with gravity' \
           'planes1): static offset' 'planes2): static offset' \
           'planes1): gravity check values' 'planes2): gravity check values' \
           'planes1): rolling resistance' 'planes2): rolling resistance' \
           'planes1): stuck ball' 'planes2): stuck ball' \
           'planes1): rolling inertia adds' 'planes2): rolling inertia adds' \
           'planes1): impact: restitution' 'planes2): impact: restitution' \
           'resting contact: the pair as one body' 'rolling ball on the outer race' \
           'first-order 1X response'; do
  grep -F "$pat" <<<"$out" | grep -q ': OK' || { echo "test_derive: check '$pat' did not report OK"; exit 1; }
done
ind=$("$py" "$src/tools/derive/independent_check.py" "$src/tools/derive/check_values.json" 2>&1) || {
  echo "$ind"; echo "test_derive: FAILED (independent NumPy check)"; exit 1; }
echo "$ind"
for pat in 'independent check: NumPy' 'independent check (device)'; do
  grep -F "$pat" <<<"$ind" | grep -q ': OK' || { echo "test_derive: independent check '$pat' did not report OK"; exit 1; }
done
fi
if want asymptotic; then
# the asymptotic stability conditions of the rotor (tools/derive/derive_asymptotic.py, docs/rotor.md
# "Asymptotic conditions")
asy=$("$py" "$src/tools/derive/derive_asymptotic.py" 2>&1) || { echo "$asy"; echo "test_derive: FAILED (asymptotic conditions)"; exit 1; }
echo "$asy"
for pat in 'light balls (1)' 'light balls (2)' 'light balls (3)' 'high speed (4)' 'pendulum (5)' 'rotor roots (6)'; do
  grep -F "$pat" <<<"$asy" | grep -q ': OK' || { echo "test_derive: asymptotic check '$pat' did not report OK"; exit 1; }
done
# anisotropic supports at high speed: the expansion of G+ and G- (tools/derive/derive_aniso_high.py)
anh=$("$py" "$src/tools/derive/derive_aniso_high.py" 2>&1) || { echo "$anh"; echo "test_derive: FAILED (anisotropic, high speed)"; exit 1; }
echo "$anh"
for pat in 'high speed (1)' 'high speed (2)' 'high speed (3)'; do
  grep -F "anisotropic, $pat" <<<"$anh" | grep -q ': OK' || { echo "test_derive: anisotropic check '$pat' did not report OK"; exit 1; }
done
fi
if want more; then
# two planes and kappa = 0 (tools/derive/derive_asymptotic2.py, docs/rotor.md "Asymptotic conditions")
asy2=$("$py" "$src/tools/derive/derive_asymptotic2.py" 2>&1) || { echo "$asy2"; echo "test_derive: FAILED (asymptotic, two planes)"; exit 1; }
echo "$asy2"
for pat in 'two planes (1)' 'two planes (2)' 'two planes (4)' 'two planes (5)' 'kappa = 0 (6)'; do
  grep -F "$pat" <<<"$asy2" | grep -q ': OK' || { echo "test_derive: asymptotic check '$pat' did not report OK"; exit 1; }
done
# two planes at high speed, balls at q = 0 (tools/derive/derive_asymptotic2_high.py, docs/rotor.md "Two planes at high speed")
ah=$("$py" "$src/tools/derive/derive_asymptotic2_high.py" 2>&1) || { echo "$ah"; echo "test_derive: FAILED (asymptotic, two planes, high speed)"; exit 1; }
echo "$ah"
for pat in 'high speed (7)' 'high speed (8)' 'high speed (9)' 'high speed (10)' 'high speed (11)' 'high speed (12)'; do
  grep -F "$pat" <<<"$ah" | grep -q ': OK' || { echo "test_derive: asymptotic check '$pat' did not report OK"; exit 1; }
done
# every unbalance with n >= 3 identical balls (tools/derive/derive_nballs.py, docs/rotor.md "Every unbalance")
nb=$("$py" "$src/tools/derive/derive_nballs.py" 2>&1) || { echo "$nb"; echo "test_derive: FAILED (n balls)"; exit 1; }
echo "$nb"
for pat in 'n balls, common kappa' 'symmetric fan: t = ' 'symmetric fan: u(y) monotone'; do
  grep -F "$pat" <<<"$nb" | grep -q ': OK' || { echo "test_derive: n-balls check '$pat' did not report OK"; exit 1; }
done
# every member of three identical balls: the exact range of u (tools/derive/derive_every3.py)
e3=$("$py" "$src/tools/derive/derive_every3.py" 2>&1) || { echo "$e3"; echo "test_derive: FAILED (three balls, every member)"; exit 1; }
echo "$e3"
[ "$(grep -c ': OK' <<<"$e3")" = 20 ] || { echo "test_derive: three balls, every member: not 20 checks OK"; exit 1; }
# two planes: Delta16 depends on the relative phase through cos(arg Q1 conj Q2) only (rotor_unbalance2.c)
tp=$("$py" "$src/tools/derive/derive_two_planes_phase.py" 2>&1) || { echo "$tp"; echo "test_derive: FAILED (two planes phase)"; exit 1; }
echo "$tp"
[ "$(grep -c ': OK' <<<"$tp")" = 4 ] || { echo "test_derive: two planes phase: not 4 checks OK"; exit 1; }
# DOP853's order-6 continuous extension with no extra stage (tools/derive/derive_dense6.py,
# src/transient/dop853_dense6.inc, docs/transient.md): derived at 60 digits, the include must equal
# what the script writes, the order conditions hold after rounding
d6=$("$py" "$src/tools/derive/derive_dense6.py" --check 2>&1) || { echo "$d6"; echo "test_derive: FAILED (dense6)"; exit 1; }
echo "$d6"
for pat in 'dense6 (1)' 'dense6 (2)' 'dense6 (2b)' 'dense6 (2c)' 'dense6 (3)' 'dense6 (4)' 'dense6 (5)'; do
  grep -F "$pat" <<<"$d6" | grep -q ': OK' || { echo "test_derive: dense6 check '$pat' did not report OK"; exit 1; }
done
fi
echo "test_derive ($part): all checks passed"
