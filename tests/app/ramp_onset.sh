#!/usr/bin/env bash
# App test (docs/device.md, "Slow ramps and the stability windows"): on a slow speed ramp the balls
# balance only where `rotor stability` says the balanced motion is stable, and the slower the ramp,
# the closer the balancing onset to the stability boundary.  The expectation comes from the
# stability analysis (its window edge and balanced configuration), the onsets from ensembles of
# run-ups over the initial angle of ball 1 (one archive per ramp rate, every member's series kept);
# ramp_onset_check.py compares them and prints the table.
#   ramp_onset.sh        fast variant: rates 0.25 and 0.0625 rad/s^2 (CTest app_ramp_onset)
#   ramp_onset.sh slow   rates 0.25, 0.0625, 0.015625, 0.00390625 rad/s^2 and the fitted order
#                        (CTest app_ramp_onset_slow, label slow)
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
here=$(cd "$(dirname "$0")" && pwd)
variant=${1:-fast}
[ "$variant" = slow ] && SCRATCH="${SCRATCH}_slow"
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH" && cd "$SCRATCH" || exit 1
fail=0
run() { "$@" >out.txt 2>err.txt && echo "ok   ran: $*" || { echo "FAIL exit $?: $*"; cat err.txt; fail=1; }; }

# The default rotor with balls of 0.05 and 0.04 kg damped by 10 kg/s (unequal balls: two identical
# balls that meet below the boundary stay together by symmetry).  Its balanced motion is stable
# above Omega_c = 159.57 rad/s; the run-up goes from 150 to 175 rad/s.
cat > rotor.ini <<'INI'
[plane1]
ball_mass = 0.05, 0.04
ball_damping = 10
INI
cat > runup.ini <<'INI'
[plane1]
ball_mass = 0.05, 0.04
ball_damping = 10
[drive]
mode = ramp
omega_a = 150
omega_b = 175
t_a = 0
t_b = 100
[ensemble]
param1 = psi_1
param2 = none
n1 = 6
series = 0, 1, 2, 3, 4, 5
INI
run "$AUTOBAL" rotor stability rotor.ini -o stab.h5
# the mirror image of its balanced configuration (3.14) about the unbalance (psi0 = 0: -psi) balances
# too; its windows must be the same (a run-up may end in either)
mirror=$("$PY" -c "import h5py; p = h5py.File('stab.h5')['rotor/stability/psi_balanced'][()]; print(','.join(repr(-float(x)) for x in p))")
run "$AUTOBAL" rotor stability rotor.ini --set stability.member1=given --set "stability.member1_angles=$mirror" -o stab_mirror.h5

if [ "$variant" = slow ]; then rates="0.25 0.0625 0.015625 0.00390625"; else rates="0.25 0.0625"; fi
files=""
for r in $rates; do
  # t_b = 25/r; samples every 0.005 rad/s of speed; 5 s at the final speed for the dwell
  set -- $("$PY" -c "r = $r; print(repr(25 / r), repr(25 / r + 5), repr(0.005 / r))")
  run "$AUTOBAL" rotor ensemble runup.ini --set drive.t_b="$1" --set transient.t_end="$2" --set transient.dt_out="$3" -o "ramp_$r.h5"
  files="$files ramp_$r.h5"
done
[ $fail -eq 0 ] || exit 1
"$PY" "$here/ramp_onset_check.py" stab.h5 stab_mirror.h5 $files || fail=1
[ $fail -eq 0 ]
