#!/usr/bin/env bash
# App test: a temporary speed reduction (data/washer_dip.ini: 1200 rpm -> 900 rpm -> slowly back to
# 1200 rpm) as a `rotor ensemble` with the exact friction law, as a user runs it, checked by
# ensemble_dip_check.py and ensemble_friction_check.py: the file's drive table is recorded in the
# archive; on a shortened dip (4 members) each member equals the single `rotor transient` run of its
# psi0 and m0 with the same table drive (residual, angles, stuck balls, time stuck, switches), every
# member ends at the table's last speed (its grade is U Omega / m_p with that speed), the transient's
# speed follows the table, and at 900 rpm (g / (r Omega^2) = 1.4 mu) the balls slip.
# The single transients run with stepper = rk8pd, the stepper of `rotor ensemble` / `pendulum ensemble`
# (the transients' default is dop853 with output = dense6 since 0.2.0): members equal them bit for bit.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${DATA:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
chk() { local what=$1 py=$2; shift 2; if "$PY" "$here/$py" "$@"; then ok "$what"; else bad "$what"; fi; }

# the file as given: its 8-point table (written here from the file's lines, rpm) is what the archive
# records; one member, stopped at 0.2 s (the drive is recorded whatever t_end)
T_FILE=$(sed -n 's/^table_t *= *//p' "$DATA/washer_dip.ini" | tr -d ' ')
W_FILE=$(sed -n 's/^table_omega *= *//p' "$DATA/washer_dip.ini" | sed 's/ *rpm//g' | tr -d ' ')
[ "$T_FILE" = "0,5,15,20,22,27,47,49" ] && [ "$W_FILE" = "100,100,1200,1200,900,900,1150,1200" ] \
  && ok "data/washer_dip.ini: the dip 1200 -> 900 -> 1150 -> 1200 rpm" || bad "washer_dip.ini table: $T_FILE / $W_FILE"
run "$AUTOBAL" rotor ensemble "$DATA/washer_dip.ini" --set ensemble.samples=1 --set transient.t_end=0.2 -o file.h5
chk "data/washer_dip.ini: the drive table on /rotor/ensemble" ensemble_dip_check.py table file.h5 rotor/ensemble "$T_FILE" "$W_FILE"

# the same dip, shortened: 1 s at 100 rpm, up in 4 s, down to 900 rpm in 0.5 s, 1.5 s there, back to
# 1150 rpm in 2 s and to 1200 rpm in 0.5 s, 0.5 s at 1200 rpm; 4 members
T=0,1,5,6,6.5,8,10,10.5
W=100,100,1200,1200,900,900,1150,1200
S=(--set "drive.table_t=$T" --set "drive.table_omega=$(echo "$W" | sed 's/,/ rpm,/g') rpm" --set transient.t_end=11)
run "$AUTOBAL" rotor ensemble "$DATA/washer_dip.ini" "${S[@]}" --set ensemble.samples=4 --set ensemble.threads=2 -o dip.h5
grep -q "friction (exact): balls stuck at the end (of 10)" out.txt && ok "console: the stuck balls" || { bad "console lacks the friction line"; cat out.txt; }
chk "short dip: the drive table on /rotor/ensemble" ensemble_dip_check.py table dip.h5 rotor/ensemble "$T" "$W"
chk "short dip: every member ends at 1200 rpm (grade = U Omega / m_p, m_p = 10 kg)" ensemble_dip_check.py final dip.h5 "$W" 10

# each member against `rotor transient` of its parameters: the file without [ensemble], m0 for unbalance
sed '/^\[ensemble\]/,$d' "$DATA/washer_dip.ini" | grep -v '^unbalance' > single.ini
for k in 0 1 2 3; do
  p=$("$PY" "$here/ensemble_friction_check.py" params dip.h5 $k)
  psi0=$(echo "$p" | awk '$1 == "psi0" {print $2}'); m0=$(echo "$p" | awk '$1 == "m0" {print $2}')
  run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd single.ini "${S[@]}" --set "plane1.psi0=$psi0" --set "plane1.m0=$m0" -q -o t$k.h5
  chk "member $k = rotor transient with psi0 = $psi0, m0 = $m0 and the dip" ensemble_friction_check.py member dip.h5 $k t$k.h5
done
chk "rotor transient: the drive table on /rotor/transient" ensemble_dip_check.py table t0.h5 rotor/transient "$T" "$W"
chk "rotor transient: Omega(t) follows the table, 1200 rpm at the end" ensemble_dip_check.py profile t0.h5 "$T" "$W"
chk "rotor transient: the balls slip at 900 rpm (t in [7, 8] s)" ensemble_dip_check.py slip t0.h5 7 8

finish
