#!/usr/bin/env bash
# App test: what a script needs is in the --json summaries (issue 18 items 5, 6): the final state of
# `pendulum transient` and `rotor transient` (values, names, units, frame) and the roots of
# `rotor stability` (Delta, closed matrix, full model, Floquet multipliers), each against an
# independent SciPy/NumPy computation (json_outputs_check.py); the rotor in its planar limit against
# the pendulum model, linear and nonlinear.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

"$PY" "$here/json_outputs_check.py" "$AUTOBAL" "$SCRATCH" > check.txt 2>&1 && ok "JSON outputs == independent computations" \
  || bad "JSON outputs == independent computations"
cat check.txt
# every JSON summary stays one valid JSON document with the new fields (two planes, axial, rotating)
expect 0 "" "$AUTOBAL" rotor transient "$DATA/rotor_two_planes.ini" --set transient.t_end=0.02 --set rotor.axial=1 \
  --set transient.frame=rotating --json
"$PY" -c "
import json, sys
d = json.load(open('out.txt'))
n = len(d['final_state'])
ok = n == len(d['final_state_names']) == len(d['final_state_units']) and d['final_state_names'][-2:] == ['z', 'z_rate'] \
     and d['final_state_frame'] == 'rotating' and all(isinstance(v, (int, float)) for v in d['final_state'])
sys.exit(0 if ok else 1)" && ok "two planes, axial, rotating: final_state with names and units, z and z_rate last" \
  || { bad "two planes, axial: final_state layout"; cat out.txt; }
expect 0 "" "$AUTOBAL" rotor stability "$DATA/rotor_two_planes.ini" --set stability.critical_speeds=false --json
"$PY" -c "
import json, sys
d = json.load(open('out.txt'))
ok = len(d['root_real']) == 16 and 'char_poly' not in d and len(d['floquet_mu_real']) == len(d['floquet_mu_imag'])
sys.exit(0 if ok else 1)" && ok "two planes: 16 closed roots, no char_poly (Delta is one plane's)" || { bad "two planes: roots"; cat out.txt; }
finish
