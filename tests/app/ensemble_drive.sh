#!/usr/bin/env bash
# App test: `autobal rotor ensemble` with a prescribed speed ([drive] mode = ramp; the ramp parameters
# ramp_rate, ramp_time, omega_b of include/autobal/ensemble.h), archives checked by ensemble_check.py:
# a basin map psi_1 x psi_2 x ramp_rate independent of the thread count and reproduced by `autobal
# rerun`; the drive recorded; each balanced member balanced after the end of its own ramp; the
# probability along each axis recomputed; members equal to single `rotor transient` runs of the same
# ramp; ramp_time and ramp_rate giving the same member; bad input named, exit 3, no file left.
# The single transients run with stepper = rk8pd, the stepper of `rotor ensemble` / `pendulum ensemble`
# (the transients' default is dop853 with output = dense6 since 0.2.0): members equal them bit for bit.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
chk() { "$PY" "$here/ensemble_check.py" "$@" && ok "check $1" || bad "check $*"; }
# expect CODE NEEDLE CMD...: exit code CODE and NEEDLE in the message

# the rotor of docs/device.md "Slow ramps and the stability windows": the default rotor with balls
# of 0.05 and 0.04 kg damped by 10 kg/s; its balanced motion is stable above about 160 rad/s.  A run
# up from 150 to 180 rad/s (t_b is replaced by each member's ramp_rate: t_b = |180 - 150| / rate).
cat > runup.ini <<'INI'
[plane1]
ball_mass = 0.05, 0.04
ball_damping = 10
[drive]
mode = ramp
omega_a = 150
omega_b = 180
t_a = 0
t_b = 30
[transient]
t_end = 40
[ensemble]
param1 = psi_1
param2 = psi_2
param3 = ramp_rate
n1 = 3
n2 = 3
min3 = 1.5
max3 = 3
n3 = 2
INI
run "$AUTOBAL" rotor ensemble runup.ini --set ensemble.threads=1 -o d1.h5
run "$AUTOBAL" rotor ensemble runup.ini --set ensemble.threads=2 -o d2.h5
chk equal d1.h5 d2.h5
chk drive_grid d1.h5
run "$AUTOBAL" rerun d1.h5 -o rr.h5
chk equal d1.h5 rr.h5

# members against `rotor transient` with the same ramp (full runs: stop_at_balance off)
cat > single.ini <<'INI'
[plane1]
ball_mass = 0.05, 0.04
ball_damping = 10
[drive]
mode = ramp
omega_a = 150
omega_b = 180
t_a = 0
t_b = 30
[transient]
t_end = 25
stop_at_balance = false
INI
{ cat single.ini; cat <<'INI'; } > pair.ini
[ensemble]
param1 = psi_1
param2 = ramp_rate
n1 = 2
min2 = 2
max2 = 4
n2 = 2
endpoint = true
INI
run "$AUTOBAL" rotor ensemble pair.ini -o pair.h5
chk drive_grid pair.h5
for ij in "0 0" "1 1" "1 0"; do
  set -- $ij
  vals=$("$PY" -c "import h5py; g=h5py.File('pair.h5')['rotor/ensemble']; print(repr(float(g['psi_1'][$1])), repr(abs(180.0 - 150.0) / float(g['ramp_rate'][$2])))")
  set -- $1 $2 $vals
  run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd single.ini --set "plane1.ball_psi=$3,2.5" --set drive.t_b="$4" -o t$1$2.h5
  chk drive_member pair.h5 t$1$2.h5 "$1" "$2"
done
# ramp_time = 10 s is ramp_rate = 30/10 = 3 rad/s^2 over the same 30 rad/s
run "$AUTOBAL" rotor ensemble pair.ini --set ensemble.param2=ramp_time --set ensemble.min2=10 --set ensemble.max2=10 --set ensemble.n2=1 -o rt.h5
run "$AUTOBAL" rotor ensemble pair.ini --set ensemble.min2=3 --set ensemble.max2=3 --set ensemble.n2=1 -o rr3.h5
chk same_members rt.h5 rr3.h5
# omega_b with ramp_rate: t_b from the member's final speed; omega_b = 180 reproduces the drive's
run "$AUTOBAL" rotor ensemble pair.ini --set ensemble.param3=omega_b --set ensemble.min3=180 --set ensemble.max3=180 --set ensemble.n3=1 -o wb.h5
chk same_members pair.h5 wb.h5

# a table drive (run up, plateau, a temporary speed reduction, up again): members equal single
# transients; balanced counts only after the table's last time
cat > table.ini <<'INI'
[plane1]
ball_mass = 0.05, 0.04
ball_damping = 10
[drive]
mode = table
table_t = 0, 5, 8, 10, 14
table_omega = 150, 175, 175, 165, 175
[transient]
t_end = 20
stop_at_balance = false
INI
{ cat table.ini; printf '[ensemble]\nparam1 = psi_1\nn1 = 2\nparam2 = psi_2\nmin2 = 2.5\nmax2 = 2.5\nn2 = 1\n'; } > table_ens.ini
run "$AUTOBAL" rotor ensemble table_ens.ini -o tab.h5
for i in 0 1; do
  psi=$("$PY" -c "import h5py; print(repr(float(h5py.File('tab.h5')['rotor/ensemble/psi_1'][$i])))")
  run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd table.ini --set "plane1.ball_psi=$psi,2.5" -o tt$i.h5
  chk drive_member tab.h5 tt$i.h5 "$i" 0
done
"$PY" - <<'PY' && ok "table drive recorded; time_to_balance after its last time" || bad "table drive record"
import h5py, numpy as np
g = h5py.File("tab.h5")["rotor/ensemble"]
assert g.attrs["drive_mode"] == "table", g.attrs["drive_mode"]
assert list(g.attrs["drive_table_t"]) == [0, 5, 8, 10, 14] and list(g.attrs["drive_table_omega"]) == [150, 175, 175, 165, 175]
assert g.attrs["drive_table_t_units"] == "s" and g.attrs["drive_table_omega_units"] == "rad/s"
ttb = g["time_to_balance"][()][g["balanced"][()] == 1]
assert np.all(ttb >= 14.0), ttb
print("table members balanced:", len(ttb), "time to balance", ttb)
PY

# bad input: named, exit 3, no archive left
printf '[ensemble]\nparam1 = ramp_rate\nmin1 = 1\nmax1 = 2\nn1 = 2\n' > const.ini
expect_err 3 "needs drive mode = ramp" "$AUTOBAL" rotor ensemble const.ini -o bad1.h5
expect_err 3 "needs drive mode = ramp" "$AUTOBAL" rotor ensemble const.ini --set ensemble.param1=omega_b -o bad1.h5
expect_err 3 "ramp_rate: min = -1 rad/s^2 is out of range: allowed (0, inf)" "$AUTOBAL" rotor ensemble pair.ini --set ensemble.min2=-1 -o bad2.h5
expect_err 3 "ramp_rate: min = 0 rad/s^2 is out of range" "$AUTOBAL" rotor ensemble pair.ini --set ensemble.min2=0 -o bad3.h5
expect_err 3 "ramp_time: min = -2 s is out of range" "$AUTOBAL" rotor ensemble pair.ini --set ensemble.param2=ramp_time --set ensemble.min2=-2 -o bad4.h5
expect_err 3 "vary one of them" "$AUTOBAL" rotor ensemble pair.ini --set ensemble.param3=ramp_time --set ensemble.min3=1 --set ensemble.max3=2 -o bad5.h5
expect_err 3 "omega is the constant speed" "$AUTOBAL" rotor ensemble pair.ini --set ensemble.param2=omega -o bad6.h5
expect_err 3 "omega_a = omega_b = 150" "$AUTOBAL" rotor ensemble pair.ini --set drive.omega_b=150 -o bad7.h5
expect_err 3 "t_b" "$AUTOBAL" rotor ensemble pair.ini --set drive.t_b=-1 -o bad8.h5
expect_err 3 "not one of" "$AUTOBAL" rotor ensemble pair.ini --set drive.mode=sideways -o bad9.h5
ls bad*.h5 >/dev/null 2>&1 && bad "bad input left an archive: $(ls bad*.h5)" || ok "bad input left no archive"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
