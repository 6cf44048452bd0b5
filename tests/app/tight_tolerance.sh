#!/usr/bin/env bash
# App test: tight tolerances converge in the fixed frame with stick-slip and contact events (issue 18,
# item 3; docs/rotor.md "How the ball angles are integrated").  The washer with ten 25 mm balls, exact
# friction and contact (data/washer_contact.ini without its [ensemble]) runs 30 s, its ball angles
# reach |phi| ~ 2600 rad.  Fixed frame at rtol 1e-11 and 1e-12 (atol 1e-15) against the rotating
# frame at rtol 1e-13: the step count grows like tol^(-1/8) of the 8(7) pair rk8pd (10^(1/8) = 1.33
# per decade; at most 2: integrating the absolute angles took 26097 -> 110698 steps, 4.2x), the same
# events (impacts, joins, releases, sticks, slips), the final angles within 1e-6 rad (measured 4e-7
# and 5e-8: the events' location bounds it).  The archive keeps its meaning: state_phi_<k> are the
# absolute angles (equal to the p1_b<i>_phi outputs, and to phi_0 + psi), the attribute
# frame_integrated says how they were integrated, and the default rtol (1e-10) has no such attribute.
# The fixed-frame runs use the default stepper (dop853, output = dense6, since 0.2.0), then dop853 with
# output = dense and with output = exact, and rk8pd (the default before); the reference stays rk8pd
# (pinned: an independent stepper and exact output, not the one under test).  dop853 with exact output
# took another branch at 1e-12 (events [.., 535, 526], angles 1.8e-3 rad off) until the grazing search
# between the probes also ran with exact output, on the integrated state.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${DATA:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

awk '/^\[ensemble\]/{skip=1;next} /^\[/{skip=0} !skip' "$DATA/washer_contact.ini" > washer.ini
expect 0 "" "$AUTOBAL" rotor transient washer.ini --set transient.stepper=rk8pd --set transient.frame=rotating --set transient.rtol=1e-13 \
  --set transient.atol=1e-15 --no-progress --json
cp out.txt ref.json
expect 0 "" "$AUTOBAL" rotor transient washer.ini --set transient.t_end=1 --no-progress -o default.h5
# before 0.2.0's fixes dop853 (dense, dense6) missed the reference's counts and final angles by up to
# 1.4e-2 rad: hits anywhere within event_tol of the crossing, grazing slips between the probes and
# impacts seen only at output times were missed
for so in default dop853:dense dop853:exact rk8pd:exact; do
  case $so in default) S=""; tag=default;; *) S="--set transient.stepper=${so%%:*} --set transient.output=${so#*:}"; tag=${so%%:*}_${so#*:};; esac
  for r in 1e-11 1e-12; do
    expect 0 "" "$AUTOBAL" rotor transient washer.ini $S --set transient.rtol=$r --set transient.atol=1e-15 \
      --no-progress --json -o fixed_${tag}_$r.h5
    cp out.txt fixed_${tag}_$r.json
  done
  if "$PY" "$here/tight_tolerance_check.py" fixed_${tag}_1e-11.json fixed_${tag}_1e-12.json ref.json fixed_${tag}_1e-12.h5 default.h5; then
    ok "fixed frame ($so), rtol 1e-11 and 1e-12: steps, events and angles converge to the rotating frame at 1e-13"
  else
    bad "fixed frame ($so) at tight tolerances (tight_tolerance_check.py)"
  fi
done
finish
