#!/usr/bin/env bash
# App test: `autobal rotor stability` with two planes and [stability] unbalance_min/max (every
# unbalance and every relative phase, docs/rotor.md "Every unbalance"); the critical phases checked by
# rotor_two_planes_phase_check.py against Floquet multipliers of the full linearized model (SciPy);
# the JSON fields; bad input provoked.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
T2="$DATA/rotor_two_planes.ini"
U=(--set "stability.unbalance_min=1000 g mm" --set "stability.unbalance_max=6000 g mm")

# 370 rad/s: the file's unbalances have two critical phases
expect 0 "critical phases:" "$AUTOBAL" rotor stability "$T2" --set rotor.omega=370 --set stability.critical_speeds=false \
  "${U[@]}" --set stability.n_unbalance=3 -o ph.h5
grep -q "NOT stable for all" out.txt && ok "370 rad/s: not stable for every phase" || bad "verdict at 370 rad/s"
"$PY" "$here/rotor_two_planes_phase_check.py" ph.h5 >py.txt 2>&1 && ok "critical phases vs Floquet of the full model" || { bad "phase check"; cat py.txt; }
# 500 rad/s: stable for every phase and every unbalance of the 5 x 5 grid; JSON fields
expect 0 "" "$AUTOBAL" rotor stability "$T2" --set stability.critical_speeds=false "${U[@]}" \
  --set "stability.unbalance2_min=500 g mm" --set "stability.unbalance2_max=7000 g mm" --set stability.n_unbalance=5 --json
"$PY" -c "
import json, sys
d = json.load(open('out.txt'))
e = d['every_unbalance']
assert e['stable_for_all'] is True, e
t = e['two_planes']
assert abs(t['unbalance2_min'] - 5e-4) < 1e-15 and abs(t['unbalance2_max'] - 7e-3) < 1e-15, t
assert t['n_unbalance1'] == 5 and t['n_unbalance2'] == 5 and t['n_points_not_stable'] == 0, t
assert t['exact_in_unbalance1'] is True and t['exact_in_unbalance2'] is True and t['boxes'] > 0, t
assert t['found_unbalance2'] is None and t['found_phase'] is None, t
p = e['phase']
assert p['stable_for_all_phases'] is True and len(p['critical_phase']) == 0, p
" && ok "JSON at 500 rad/s: two_planes and phase objects" || { bad "JSON fields"; head -c 3000 out.txt; }
# unbalance2_boxes = -1: no box search, the same grid verdict, plane 2 reported as sampled; a small budget: undecided
for b in -1 3; do
  expect 0 "" "$AUTOBAL" rotor stability "$T2" --set stability.critical_speeds=false "${U[@]}" \
    --set "stability.unbalance2_min=500 g mm" --set "stability.unbalance2_max=7000 g mm" --set stability.n_unbalance=5 \
    --set stability.unbalance2_boxes=$b --json
  "$PY" -c "
import json
t = json.load(open('out.txt'))['every_unbalance']['two_planes']
assert t['exact_in_unbalance2'] is False and t['n_points_not_stable'] == 0, t
assert (t['boxes'] == 0) == ($b == -1), t
" && ok "unbalance2_boxes = $b: plane 2 sampled (boxes as asked)" || { bad "unbalance2_boxes = $b"; head -c 2000 out.txt; }
done
expect 0 "SAMPLED: no box search" "$AUTOBAL" rotor stability "$T2" --set stability.critical_speeds=false \
  "${U[@]}" --set "stability.unbalance2_min=500 g mm" --set "stability.unbalance2_max=7000 g mm" --set stability.n_unbalance=5 \
  --set stability.unbalance2_boxes=-1
# the speed set over 360..400 rad/s (3 grid speeds): per speed whether plane 2 was decided exactly, in
# JSON and the archive (named dimensions); with the search off every stable speed is sampled
for b in 0 -1; do
  rm -f sp$b.h5
  expect 0 "" "$AUTOBAL" rotor stability "$T2" "${U[@]}" --set stability.omega_min=360 --set stability.omega_max=400 \
    --set stability.n_omega=3 --set stability.unbalance2_boxes=$b --json -o sp$b.h5
  "$PY" -c "
import json, h5py
b = $b
s = json.load(open('out.txt'))['every_unbalance']['speeds']
n = len(s['grid_omega'])
assert n == 3 and len(s['grid_stable']) == n and len(s['grid_exact_in_unbalance2']) == n and len(s['grid_boxes']) == n, s
assert abs(s['grid_omega'][0] - 360) < 1e-9 and abs(s['grid_omega'][2] - 400) < 1e-9, s
assert len(s['interval_exact_in_unbalance2']) == len(s['stable_lo']) and len(s['critical_exact_in_unbalance2']) == len(s['critical_values']), s
# where stable: exact iff the search ran (and then boxes were examined); not stable: decided by a point
for st, ex, bx in zip(s['grid_stable'], s['grid_exact_in_unbalance2'], s['grid_boxes']):
    assert st in (0, 1), s
    assert ex == (st == 0 or b == 0) and (bx > 0) == (b == 0), s
assert all(s['interval_exact_in_unbalance2']) == (b == 0) and s['n_speeds_evaluated'] >= n, s
assert (s['n_speeds_undecided_in_unbalance2'] == 0) == (b == 0), s
f = h5py.File('sp$b.h5', 'r')
g = f['/rotor/stability/every_unbalance/speeds']
def dim(name):
    return [f[r].name.rsplit('/', 1)[1] for r in g[name].attrs['DIMENSION_LIST'][0]]
for k in ('grid_omega', 'grid_stable', 'grid_exact_in_unbalance2', 'grid_boxes'):
    assert dim(k) == ['speed_grid'] and len(g[k]) == n, k
assert g['grid_omega'].attrs['units'] == 'rad/s'
assert list(g['grid_exact_in_unbalance2'][()]) == [int(x) for x in s['grid_exact_in_unbalance2']]
if len(s['stable_lo']):
    assert dim('interval_exact_in_unbalance2') == ['interval']
if len(s['critical_values']):
    assert dim('critical_exact_in_unbalance2') == ['critical']
assert g.attrs['n_speeds_evaluated'] == s['n_speeds_evaluated']
" && ok "speed set, unbalance2_boxes = $b: per-speed exact_in_unbalance2 in JSON and archive" || { bad "speed set detail ($b)"; head -c 3000 out.txt; }
done
expect 0 "stable intervals, plane 2:" "$AUTOBAL" rotor stability "$T2" "${U[@]}" --set stability.omega_min=360 \
  --set stability.omega_max=400 --set stability.n_omega=3
# bad input
expect 3 "unbalance2_boxes = -2 is out of range: allowed -1" "$AUTOBAL" rotor stability "$T2" --set stability.critical_speeds=false \
  "${U[@]}" --set stability.unbalance2_boxes=-2
expect 3 "unbalance2_min and unbalance2_max go together" "$AUTOBAL" rotor stability "$T2" --set stability.critical_speeds=false \
  "${U[@]}" --set "stability.unbalance2_min=500 g mm"
expect 3 "n_unbalance = 1 must be in [2, 1000]" "$AUTOBAL" rotor stability "$T2" --set stability.critical_speeds=false \
  "${U[@]}" --set stability.n_unbalance=1
expect 3 "are for two planes (here 1)" "$AUTOBAL" rotor stability --set stability.critical_speeds=false \
  "${U[@]}" --set stability.n_unbalance=5
expect 3 "plane 2's m0 r0" "$AUTOBAL" rotor stability "$T2" --set stability.critical_speeds=false \
  "${U[@]}" --set "stability.unbalance2_min=500 g mm" --set "stability.unbalance2_max=8000 g mm"
echo "rotor_two_planes_phase: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
