#!/usr/bin/env bash
# App test: `autobal rotor transient` with gravity ([rotor] gravity = true, shaft_angle, g;
# docs/device.md section 2) as a user runs it: a horizontal-shaft run-up from rest with a table drive
# (0 -> 1 rad/s in 1 s, a dwell at 1 rad/s to 3 s, then 300 rad/s at 4 s).  Checked with independent
# reasons (tests/app/gravity_check.py): a SciPy DOP853 integration of the equations of docs/device.md
# (the NumPy accelerations of tools/derive/independent_check.py) agrees with the archive; during the
# dwell each ball lies near the bottom of its track where its weight balances the drag of the track,
# cos(phi) = h r Omega / (m g) (phi = -pi/2: the lowest point); the static offset in /rotor equals
# the closed form of docs/device.md and the rotor's mean position during the dwell; the ratio
# g sin(theta) / (r Omega^2) of /rotor/planeN is the formula and the balls circulate at the end.
# The rotating frame agrees with the fixed one (2e-12). A vertical shaft gives the bits of gravity
# off; `autobal rerun` reproduces the run bit for bit;
# a motor drive runs with gravity; rotor stability/sweep/map/campbell refuse gravity (exit 3); an
# ensemble runs with it; bad gravity input exits 3 naming the key and the range, leaving no file.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}" "${DATA:?}"
. "$(dirname "$0")/common.bash"
export TOOLS="${TOOLS:-$here/../../tools}"
check() { local what=$1; shift; if "$PY" "$here/gravity_check.py" "$@"; then ok "$what"; else bad "$what"; fi; }

# the default rotor on a horizontal shaft; ball damping 0.5 kg/s, so that the balls' swing about the
# bottom (released at psi = 1.0, 2.5 rad) has decayed (e^(-h t / 2m) = e^-10 at 2 s) before the check
cat > horiz.ini <<'INI'
[rotor]
gravity = true
shaft_angle = 90 deg
[plane1]
ball_damping = 0.5 kg/s
[drive]
mode = table
table_t = 0, 1, 3, 4
table_omega = 0, 1, 1, 300
[transient]
t_end = 4.5
dt_out = 0.01
rtol = 1e-12
atol = 1e-14
INI
expect 0 "static offset y_s = -0.398163 mm, alpha_s = -0.119014 mrad" "$AUTOBAL" rotor transient horiz.ini -o horiz.h5
grep -qF "g sin(theta) / (r Omega^2) = 0.00109 at the final speed: carried round" out.txt && ok "console: the ratio and 'carried round'" || { bad "console: no ratio line"; cat out.txt; }
check "SciPy DOP853 of the equations with gravity (docs/device.md) == the archive" scipy horiz.h5
check "balls near the bottom at 1 rad/s: phi = -pi/2 + asin(h r Omega/(m g))" bottom horiz.h5 2.9
check "static offset: /rotor attributes = closed form = the rotor's mean position in the dwell" offset horiz.h5 2 3
check "gravity_ratio_final = g/(r Omega^2) < 1, the balls circulate at the end" ratio horiz.h5
expect 0 "" "$AUTOBAL" rotor transient horiz.ini --set transient.frame=rotating -o horiz_rot.h5 -q
check "rotating frame == fixed frame with gravity" frames horiz.h5 horiz_rot.h5

# the washing-machine example of docs/guide.md (data/washer_gravity.ini) runs, balances, and its static
# offset is the closed form
expect 0 "static offset y_s = -17.7206 mm, alpha_s = 2.48435 mrad" "$AUTOBAL" rotor transient "$DATA/washer_gravity.ini" -o washer.h5
grep -qF "BALANCED" out.txt && ok "washer example balances" || bad "washer example: not balanced"
check "washer example: static offset attributes = closed form" offset washer.h5 1 0

# JSON summary
expect 0 '"static_offset_y"' "$AUTOBAL" rotor transient horiz.ini --json --set transient.t_end=0.2
grep -qF '"gravity_ratio_final"' out.txt && ok "JSON: gravity_ratio_final" || bad "JSON: no gravity_ratio_final"

# a vertical shaft is the model without gravity, bit for bit
sed -e 's/^gravity = true/gravity = false/' -e '/^shaft_angle/d' horiz.ini > off.ini
expect 0 "" "$AUTOBAL" rotor transient off.ini -o off.h5 -q
expect 0 "" "$AUTOBAL" rotor transient horiz.ini --set rotor.shaft_angle=0 -o vert.h5 -q
check "vertical shaft == gravity off, every series bit for bit" same off.h5 vert.h5
"$PY" -c "import h5py,sys; a=h5py.File('off.h5')['/rotor'].attrs; sys.exit('gravity' in a)" && ok "no gravity attributes without gravity" || bad "gravity attributes without gravity"

# rerun: bit for bit
expect 0 "" "$AUTOBAL" rerun horiz.h5 -o horiz_rerun.h5 -q
check "rerun of the gravity run, bit for bit" same horiz.h5 horiz_rerun.h5
"$PY" -c "
import h5py, sys
a, b = h5py.File('horiz.h5')['/rotor'].attrs, h5py.File('horiz_rerun.h5')['/rotor'].attrs
ks = ['gravity', 'shaft_angle', 'g', 'g_in_plane', 'static_offset_y', 'static_offset_alpha']
sys.exit(not all(a[k] == b[k] for k in ks) or a['shaft_angle_units'] != 'rad' or a['g_units'] != 'm/s^2')" \
  && ok "rerun: /rotor gravity attributes (with units) equal" || bad "rerun: /rotor gravity attributes"

# a motor drive with gravity (the unbalance's weight torque on phi_0) runs
printf '[rotor]\ngravity = on\nshaft_angle = 1.5707963267948966\ng = 9.81\n[drive]\nmode = motor\nJ = 0.05\nL_0 = 14\nomega_0 = 400\nk_r = 2e-3\n[transient]\nt_end = 0.5\n' > motor.ini
expect 0 "static offset" "$AUTOBAL" rotor transient motor.ini -o motor.h5

# the analyses of the weightless balanced state refuse gravity
for c in stability sweep map campbell; do
  expect 3 "gravity = true is not supported by \`autobal rotor $c\`" "$AUTOBAL" rotor $c horiz.ini
done
# an ensemble runs transients: gravity is accepted and recorded
printf '[rotor]\ngravity = true\nshaft_angle = 90 deg\n[transient]\nt_end = 0.3\n[ensemble]\nparam1 = psi_1\nparam2 = psi_2\nn1 = 2\nn2 = 2\n' > ens.ini
expect 0 "" "$AUTOBAL" rotor ensemble ens.ini -o ens.h5 -q
"$PY" -c "import h5py,sys; sys.exit(0 if h5py.File('ens.h5')['/rotor'].attrs['gravity'] == 1 else 1)" && ok "ensemble: /rotor gravity = 1" || bad "ensemble: gravity not recorded"

# bad input: exit 3 naming the key and the range, no archive
rm -f x.h5
expect 3 "shaft_angle = 181 deg is out of range: allowed [0, 180] deg" "$AUTOBAL" rotor transient horiz.ini --set rotor.shaft_angle=181deg -o x.h5
expect 3 "shaft_angle = -1 deg is out of range: allowed [0, 180] deg" "$AUTOBAL" rotor transient horiz.ini --set "rotor.shaft_angle=-1 deg" -o x.h5
expect 3 "shaft_angle = 200.535 deg is out of range" "$AUTOBAL" rotor transient horiz.ini --set rotor.shaft_angle=3.5 -o x.h5
expect 3 "g = 0 m/s^2 is out of range: allowed (0, inf)" "$AUTOBAL" rotor transient horiz.ini --set rotor.g=0 -o x.h5
expect 3 "g = -9.81 m/s^2 is out of range: allowed (0, inf)" "$AUTOBAL" rotor transient horiz.ini --set rotor.g=-9.81 -o x.h5
expect 3 "rotor.g = 'nan' is not a finite number" "$AUTOBAL" rotor transient horiz.ini --set rotor.g=nan -o x.h5
expect 3 "rotor.shaft_angle = 'nan' is not a finite number" "$AUTOBAL" rotor transient horiz.ini --set rotor.shaft_angle=nan -o x.h5
expect 3 "rotor.g" "$AUTOBAL" rotor transient horiz.ini --set "rotor.g=9.81 m" -o x.h5
expect 3 "rotor.gravity = 'maybe' is not a boolean" "$AUTOBAL" rotor transient horiz.ini --set rotor.gravity=maybe -o x.h5
expect 3 "gravity = true needs shaft_angle" "$AUTOBAL" rotor transient --set rotor.gravity=true -o x.h5
expect 3 "shaft_angle is a key of gravity = true, but gravity = false" "$AUTOBAL" rotor transient --set rotor.shaft_angle=90deg -o x.h5
expect 3 "g is a key of gravity = true, but gravity = false" "$AUTOBAL" rotor transient --set rotor.g=9.81 -o x.h5
[ -e x.h5 ] && bad "bad input left an archive x.h5" || ok "bad input left no archive"
# the closed end of the range: 180 deg is accepted
expect 0 "shaft at 180 deg" "$AUTOBAL" rotor transient --set rotor.gravity=true --set rotor.shaft_angle=180deg --set transient.t_end=0.01

echo "$pass passed, $fail failed"
exit $((fail > 0))
