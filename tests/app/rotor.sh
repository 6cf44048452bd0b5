#!/usr/bin/env bash
# App test: `autobal rotor transient` as a user runs it; archives checked by rotor_check.py with
# formulas from docs/rotor.md; interruption and bad input provoked.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

expect 0 "BALANCED" "$AUTOBAL" rotor transient -o default.h5
"$PY" "$here/rotor_check.py" balanced default.h5 && ok "default example archive" || bad "default example archive"
# data/rotor_default.ini is the built-in default: the same archive, bit for bit
expect 0 "BALANCED" "$AUTOBAL" rotor transient "$DATA/rotor_default.ini" -o default_ini.h5
"$PY" "$here/rotor_check.py" same default.h5 default_ini.h5 && ok "data/rotor_default.ini = the built-in default" \
  || bad "data/rotor_default.ini differs from the built-in default"
# the default tolerances: |s| at 600 revolutions within 1e-4 (relative) of a tight run (balls in the
# rotating frame, rtol 1e-13) and of SciPy; the former defaults (rtol 1e-8, atol 1e-10) miss it
expect 0 "" "$AUTOBAL" rotor transient --set transient.t_end=7.6 --set transient.frame=rotating \
  --set transient.rtol=1e-13 --set transient.atol=1e-15 -o tight.h5
expect 0 "" "$AUTOBAL" rotor transient --set transient.t_end=7.6 --set transient.rtol=1e-8 --set transient.atol=1e-10 -o old_tol.h5
"$PY" "$here/rotor_check.py" accuracy tight.h5 default.h5 old_tol.h5 && ok "default tolerances: |s| at 600 revolutions to 1e-4" \
  || bad "default tolerances: |s| at 600 revolutions"
expect 0 "BALANCED" "$AUTOBAL" rotor transient --set transient.frame=rotating -o rot.h5
"$PY" "$here/rotor_check.py" balanced rot.h5 && ok "rotating-frame archive" || bad "rotating-frame archive"
if [ -f "$DATA/rotor_subcritical.ini" ]; then
  expect 0 "NOT balanced" "$AUTOBAL" rotor transient "$DATA/rotor_subcritical.ini" -o sub.h5
  "$PY" "$here/rotor_check.py" heavy sub.h5 && ok "subcritical: balls to the heavy side" || bad "subcritical archive"
fi
for f in "$DATA"/rotor_*.ini; do
  expect 0 "" "$AUTOBAL" rotor transient "$f" --set transient.t_end=0.5 -o "cfg_$(basename "$f" .ini).h5"
done
expect 0 "" "$AUTOBAL" rotor transient --json --set transient.t_end=1
"$PY" -c "import json; d=json.load(open('out.txt')); assert 'time_to_balance' in d and d['steps'] > 0" \
  && ok "--json summary" || bad "--json summary"

# interruption: SIGINT during a long run -> exit 6, archive kept, marked incomplete
"$AUTOBAL" rotor transient --set transient.t_end=100000 --set transient.revs_out=20 -o int.h5 >out.txt 2>err.txt &
pid=$!; caught $pid INT; sleep 1; kill -INT $pid; wait $pid; rc=$?
[ $rc -eq 6 ] && ok "SIGINT -> exit 6" || { bad "SIGINT gave exit $rc"; cat err.txt; }
"$PY" "$here/rotor_check.py" partial int.h5 && ok "interrupted archive readable and incomplete" || bad "interrupted archive"
# solver failure: maximum steps -> exit 5 with the partial result
expect 5 "maximum" "$AUTOBAL" rotor transient --set transient.max_steps=200 -o maxs.h5
"$PY" "$here/rotor_check.py" partial maxs.h5 && ok "max-steps archive keeps the partial run" || bad "max-steps archive"

# bad input
expect 3 "ball_radius" "$AUTOBAL" rotor transient --set plane1.ball_radius=-0.1,0.1
expect 3 "ball_damping has 3 values" "$AUTOBAL" rotor transient --set plane1.ball_damping=0.1,0.1,0.1
expect 3 "M_k" "$AUTOBAL" rotor transient --set rotor.M_k=-6
expect 3 "did you mean 'supports.c_Lx'" "$AUTOBAL" rotor transient --set supports.c_lx=1e5
expect 3 "rk8pd" "$AUTOBAL" rotor transient --set transient.stepper=rk99
expect 3 "t_end" "$AUTOBAL" rotor transient --set transient.t_end=0
expect 3 "not a finite number" "$AUTOBAL" rotor transient --set rotor.omega=inf
expect 3 "'c_y' is missing" "$AUTOBAL" rotor transient --set lumped.M=10 --set lumped.A=0.16 --set lumped.C=0.03 --set lumped.c_x=1
expect 0 "warning" "$AUTOBAL" rotor transient --set plane1.m0=0.2 --set transient.t_end=0.2
expect 4 "exists" "$AUTOBAL" rotor transient -o default.h5
ls | grep -q partial && bad "temporary files left: $(ls | grep partial)" || ok "no temporary files left"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
