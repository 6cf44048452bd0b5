#!/usr/bin/env bash
# App test: `autobal rotor stability|sweep|map|campbell` as a user runs them; archives checked by
# rotor_stability_check.py against NumPy/SciPy computations from the formulas of docs/rotor.md; bad input provoked.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
pycheck() {
  local what=$1; shift
  "$PY" "$here/rotor_stability_check.py" "$@" >py.txt 2>&1 && ok "$what" || { bad "$what"; cat py.txt; }
}

# the default example: stable at 500 rad/s, stable speed intervals listed
expect 0 "STABLE speed (omega) intervals" "$AUTOBAL" rotor stability "$DATA/rotor_default.ini" -o st.h5
grep -q "BALANCED MOTION: stable" out.txt && ok "default example stable at 500 rad/s" || bad "verdict line"
pycheck "stability archive vs NumPy (Delta, roots, Floquet, critical speeds)" stability st.h5
expect 0 "unstable" "$AUTOBAL" rotor stability --set rotor.omega=300 -o st300.h5
pycheck "stability archive at 300 rad/s" stability st300.h5
expect 0 "STABLE omega intervals" "$AUTOBAL" rotor sweep "$DATA/rotor_default.ini" -o sw.h5
pycheck "sweep archive vs NumPy" sweep sw.h5
expect 0 "critical values of ball_damping" "$AUTOBAL" rotor sweep --set sweep.param=ball_damping --set sweep.max=2 --set sweep.n=200 -o swh.h5
expect 0 "stable points" "$AUTOBAL" rotor map --set map.n1=40 --set map.n2=20 --set map.threads=2 -o map.h5
pycheck "map archive vs NumPy" map map.h5
expect 0 "stable points" "$AUTOBAL" rotor map --set map.n1=40 --set map.n2=20 --set map.threads=1 -o map1.h5
"$PY" -c "
import h5py, numpy as np
a = h5py.File('map.h5')['rotor/map/margin'][...]; b = h5py.File('map1.h5')['rotor/map/margin'][...]
assert np.array_equal(a, b, equal_nan=True)" && ok "map: 2 threads = 1 thread (bitwise)" || bad "map threads differ"
expect 0 "critical speeds (natural frequency = omega)" "$AUTOBAL" rotor campbell "$DATA/rotor_default.ini" -o cb.h5
grep -q "157.5323" out.txt && ok "natural frequency 157.5323 rad/s printed" || bad "natural frequency"
pycheck "campbell archive vs NumPy" campbell cb.h5
if [ -f "$DATA/rotor_anisotropic.ini" ]; then
  expect 0 "method floquet" "$AUTOBAL" rotor stability "$DATA/rotor_anisotropic.ini" --set stability.critical_speeds=false -o an.h5
  pycheck "anisotropic: Floquet multipliers vs SciPy" floquet an.h5
fi
for f in "$DATA"/rotor_*.ini; do
  expect 0 "BALANCED MOTION" "$AUTOBAL" rotor stability "$f" --set stability.n_omega=100
done
expect 0 "" "$AUTOBAL" rotor stability --json
"$PY" -c "import json; d=json.load(open('out.txt')); assert d['verdict'] == 'stable' and len(d['critical_values']) >= 1 and d['truncated'] is False" \
  && ok "--json summary (truncated = false)" || bad "--json summary"
expect 0 "" "$AUTOBAL" rotor campbell --json
"$PY" -c "import json; d=json.load(open('out.txt')); assert len(d['crossing_omega']) == 4 and d['truncated'] is False" \
  && ok "campbell --json: 4 crossings, truncated = false" || bad "campbell --json"
grep -q "TRUNCATED" out.txt err.txt && bad "campbell reported as truncated" || ok "campbell: no truncation reported"
"$PY" -c "
import h5py
g = h5py.File('swh.h5')['rotor/sweep']
assert int(g.attrs['truncated']) == 0 and int(g.attrs['n_critical']) < 64" && ok "sweep archive: truncated = 0 stored" || bad "sweep archive truncated attribute"
# three identical balls: the family's member is reported, the neutral root excluded
expect 0 "neutral family" "$AUTOBAL" rotor stability --set plane1.ball_mass=0.05,0.05,0.05 --set plane1.ball_radius=0.1 --set plane1.ball_damping=0.1 --set stability.critical_speeds=false
expect 0 "member free" "$AUTOBAL" rotor stability --set plane1.ball_mass=0.05,0.05,0.05 --set plane1.ball_radius=0.1 --set plane1.ball_damping=0.1 --set stability.member1=free --set stability.member1_angles=0.5 --set stability.critical_speeds=false

# bad input
expect 3 "member1" "$AUTOBAL" rotor stability --set stability.member1=someone
expect 3 "member1_angles" "$AUTOBAL" rotor stability --set stability.member1=given
expect 3 "needs 2" "$AUTOBAL" rotor stability --set stability.member1=given --set stability.member1_angles=1
expect 3 "do not balance" "$AUTOBAL" rotor stability --set stability.member1=given --set stability.member1_angles=1,2
expect 3 "method" "$AUTOBAL" rotor stability --set stability.method=magic
expect 3 "isotropic" "$AUTOBAL" rotor stability "$DATA/rotor_anisotropic.ini" --set stability.method=poly
expect 3 "omega = 0" "$AUTOBAL" rotor stability --set rotor.omega=0
expect 3 "no balanced configuration" "$AUTOBAL" rotor stability --set plane1.m0=0.5
expect 3 "did you mean 'stability.tol'" "$AUTOBAL" rotor stability --set stability.tolx=1e-9
expect 3 "is not a parameter" "$AUTOBAL" rotor sweep --set sweep.param=colour
expect 3 "max = 1 rad/s must be larger than min = 5 rad/s" "$AUTOBAL" rotor sweep --set sweep.min=5 --set sweep.max=1
expect 3 "must differ" "$AUTOBAL" rotor map --set map.param2=omega
expect 3 "omega_min" "$AUTOBAL" rotor campbell --set campbell.omega_max=-1
expect 3 "ball_radius" "$AUTOBAL" rotor stability --set plane1.ball_radius=-0.1,0.1
expect 4 "exists" "$AUTOBAL" rotor stability -o st.h5
ls | grep -q partial && bad "temporary files left: $(ls | grep partial)" || ok "no temporary files left"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
