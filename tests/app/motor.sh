#!/usr/bin/env bash
# App test: `autobal rotor transient` with a motor of limited power ([drive] mode = motor), as a
# user runs it: a run-up from rest through both resonances with a linear characteristic (speeds in
# rpm, torques in N m), the motor attributes and columns; an independent SciPy integration of the
# motor equations of docs/device.md agrees with the archive (linear and tabulated characteristic,
# one and two planes); fixed and rotating frames agree; `autobal rerun` reproduces motor runs bit
# for bit; bad [drive] motor input exits 3 naming the key and the allowed range, leaving no file.
# (The Sommerfeld effect, which needs a rotor without balls, is checked in tests/test_rotor_drive.c.)
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
check() { local what=$1; shift; if "$PY" "$here/motor_check.py" "$@"; then ok "$what"; else bad "$what"; fi; }
same() { local what=$1; shift; if "$PY" "$here/drive_check.py" same "$@"; then ok "$what"; else bad "$what"; fi; }

# a run-up from rest: L(Omega) = 14 N m (1 - Omega/400 rad/s), J = 0.05 kg m^2, k_r = 2e-3 N m s
cat > motor.ini <<'INI'
[drive]
mode = motor
J = 0.05 kg m^2
L_0 = 14 N m
omega_0 = 3819.7186342 rpm   ; 400 rad/s
k_r = 2e-3
omega_start = 0
[transient]
t_end = 2
INI
expect 0 "rotor transient: motor L = 14 N m (1 - Omega/400 rad/s)" "$AUTOBAL" rotor transient motor.ini -o motor.h5
check "motor attributes, columns, motor_torque = L(Omega), motor_power = L Omega" attrs motor.h5 linear
check "the motor passed both resonances (157.5, 215.1 rad/s at rest)" passes motor.h5 250
check "SciPy DOP853 of the motor equations (docs/device.md) == the archive" scipy motor.h5
expect 0 "" "$AUTOBAL" rotor transient motor.ini --set transient.frame=rotating -o motor_rot.h5
check "fixed frame == rotating frame during the run-up" frames motor.h5 motor_rot.h5

# a tabulated characteristic (a motor with a torque maximum), started at 50 rad/s
cat > table.ini <<'INI'
[drive]
mode = motor
J = 0.04
table_omega = 0, 1000 rpm, 200, 300, 350 rad/s
table_torque = 6, 9, 8 N m, 3, 0
k_r = 1e-3 N m s
omega_start = 50 rad/s
[transient]
t_end = 1.5
INI
expect 0 "motor with a torque table of 5 points" "$AUTOBAL" rotor transient table.ini -o table.h5
check "table motor attributes and columns" attrs table.h5 table
check "SciPy of the motor equations, tabulated characteristic == the archive" scipy table.h5

# two planes (data/rotor_two_planes.ini) with a motor
cp "$DATA/rotor_two_planes.ini" two.ini
printf '\n[drive]\nmode = motor\nJ = 0.05\nL_0 = 10\nomega_0 = 400\nk_r = 1e-3\nomega_start = 100\n' >> two.ini
expect 0 "" "$AUTOBAL" rotor transient two.ini --set transient.t_end=1 -o two.h5
check "SciPy of the motor equations, two planes == the archive" scipy two.h5

# every unit string of the motor archives parses with UDUNITS-2 (the configuration's parser)
if [ -n "${UNITS_CHECK:-}" ]; then
  "$PY" - motor.h5 table.h5 > units.txt <<'PY'
import sys, h5py
seen = set()
def visit(name, obj):
    for k, v in obj.attrs.items():
        if k == "units" or k.endswith("_units"):
            seen.add(v.decode() if isinstance(v, bytes) else str(v))
for f in sys.argv[1:]:
    h = h5py.File(f, "r")
    visit("/", h)
    h.visititems(visit)
print("\n".join(sorted(u for u in seen if u not in ("1",))))
PY
  grep -qx "N m s" units.txt && grep -qx "kg m^2" units.txt && "$UNITS_CHECK" < units.txt >/dev/null \
    && ok "the motor archives' $(wc -l < units.txt) unit strings parse (UDUNITS-2)" || bad "unit strings: $(tr '\n' ';' < units.txt)"
fi

# the rerun reproduces motor runs bit for bit
expect 0 "" "$AUTOBAL" rerun motor.h5 -o motor_rerun.h5 -q
same "rerun of the linear motor run, bit for bit" motor.h5 motor_rerun.h5
expect 0 "" "$AUTOBAL" rerun table.h5 -o table_rerun.h5 -q
same "rerun of the table motor run, bit for bit" table.h5 table_rerun.h5

# bad input: exit 3, the key and the allowed range named, no file left
m() { printf '[drive]\nmode = motor\n%b' "$1" > "$2"; }
m 'J = -1\nL_0 = 1\nomega_0 = 100\n' b1.ini;  expect 3 "J = -1 kg m^2 is out of range: allowed [C_p, inf)" "$AUTOBAL" rotor transient b1.ini -o x.h5
m 'J = 0.01\nL_0 = 1\nomega_0 = 100\n' b2.ini; expect 3 "J = 0.01 kg m^2 is out of range: allowed [C_p, inf) = [0.03, inf)" "$AUTOBAL" rotor transient b2.ini -o x.h5
m 'J = 0.05\nL_0 = 0\nomega_0 = 100\n' b3.ini; expect 3 "L_0 = 0 N m is out of range: allowed (0, inf)" "$AUTOBAL" rotor transient b3.ini -o x.h5
m 'J = 0.05\nL_0 = -2\nomega_0 = 100\n' b4.ini; expect 3 "the motor cannot start" "$AUTOBAL" rotor transient b4.ini -o x.h5
m 'J = 0.05\nL_0 = 1\nomega_0 = 0\n' b5.ini;  expect 3 "omega_0 = 0 rad/s is out of range: allowed (0, inf)" "$AUTOBAL" rotor transient b5.ini -o x.h5
m 'J = 0.05\nL_0 = 1\nomega_0 = -100\n' b6.ini; expect 3 "omega_0" "$AUTOBAL" rotor transient b6.ini -o x.h5
m 'J = 0.05\ntable_omega = 0, 200, 100\ntable_torque = 1, 2, 3\n' b7.ini; expect 3 "table_omega is not strictly increasing" "$AUTOBAL" rotor transient b7.ini -o x.h5
m 'J = 0.05\ntable_omega = 0, 100\ntable_torque = 0, 2\n' b8.ini; expect 3 "table_torque gives the starting torque L(0) = 0 N m: allowed (0, inf)" "$AUTOBAL" rotor transient b8.ini -o x.h5
m 'J = 0.05\ntable_omega = 0, 100\ntable_torque = 1, 2, 3\n' b9.ini; expect 3 "table_torque has 3" "$AUTOBAL" rotor transient b9.ini -o x.h5
m 'J = 0.05\nL_0 = 1\nomega_0 = 100\nk_r = -1\n' b10.ini; expect 3 "k_r = -1 N m s is out of range: allowed [0, inf)" "$AUTOBAL" rotor transient b10.ini -o x.h5
m 'L_0 = 1\nomega_0 = 100\n' b11.ini; expect 3 "needs J" "$AUTOBAL" rotor transient b11.ini -o x.h5
m 'J = 0.05\nomega_0 = 100\n' b12.ini; expect 3 "needs L_0" "$AUTOBAL" rotor transient b12.ini -o x.h5
m 'J = 0.05\nL_0 = 1 m\nomega_0 = 100\n' b13.ini; expect 3 "L_0" "$AUTOBAL" rotor transient b13.ini -o x.h5
m 'J = 0.05\nL_0 = 1\nomega_0 = 100\ntable_omega = 0, 1\ntable_torque = 1, 1\n' b14.ini; expect 3 "not both" "$AUTOBAL" rotor transient b14.ini -o x.h5
m 'J = 0.05\nL_0 = 1\nomega_0 = 100\ntable_t = 0, 1\n' b15.ini; expect 3 "table_t is a key of mode = table" "$AUTOBAL" rotor transient b15.ini -o x.h5
printf '[drive]\nmode = ramp\nomega_a = 0\nomega_b = 100\nt_a = 0\nt_b = 1\nJ = 0.05\n' > b16.ini
expect 3 "J is a key of mode = motor" "$AUTOBAL" rotor transient b16.ini -o x.h5
m 'J = 0.05\nL_0 = 1\nomega_0 = 100\n[rotor]\ninertia = full\n' b17.ini; expect 3 "PAPER inertia" "$AUTOBAL" rotor transient b17.ini -o x.h5
[ -e x.h5 ] && bad "bad input left an archive x.h5" || ok "bad input left no archive"

echo "$pass passed, $fail failed"
exit $((fail > 0))
