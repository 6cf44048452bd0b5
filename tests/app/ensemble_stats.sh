#!/usr/bin/env bash
# App test: the residual-unbalance statistics of `autobal rotor ensemble` ([ensemble] target_grade,
# target_unbalance, write_unbalance; apps/cmd_ensemble.c, src/studies/ensemble*.c), checked by
# ensemble_stats_check.py against computations in Python: U from the archived final angles, the
# grade from U and the speed at the end, quantiles vs numpy.quantile, P(target) vs a count, the
# Wilson interval vs its closed form; one plane, two planes, a random omega, a random unbalance
# angle psi0, a ramp with a varied final speed; the per-member datasets only on request; bad targets (exit 3 naming the key).
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${DATA:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
chk() { "$PY" "$here/ensemble_stats_check.py" "$@" || bad "check $*"; }
T="--set ensemble.target_grade=G6.3 --set ensemble.write_unbalance=true"

# one plane, random initial angles and speed: runs of 6 s, so that some members are not yet balanced
run "$AUTOBAL" rotor ensemble --set ensemble.mode=random --set ensemble.samples=40 --set ensemble.seed=7 \
    --set ensemble.param3=omega --set ensemble.min3=300 --set ensemble.max3=600 --set transient.t_end=6 \
    $T --set "ensemble.target_unbalance=50 g mm" --json -o r1.h5
cp out.txt r1.json
chk unbalance r1.h5 r1.json
# the console summary prints the same numbers in g mm and mm/s
run "$AUTOBAL" rotor ensemble --set ensemble.mode=random --set ensemble.samples=40 --set ensemble.seed=7 \
    --set ensemble.param3=omega --set ensemble.min3=300 --set ensemble.max3=600 --set transient.t_end=6 \
    $T --set "ensemble.target_unbalance=50 g mm" -o r1b.h5
want=$("$PY" -c "import h5py; s=h5py.File('r1.h5')['rotor/ensemble/statistics']; u=s['residual_unbalance_abs_final'].attrs; g=s['balance_grade_final'].attrs; print('median %.4g,' % (u['median']*1e6)); print('median %.4g,' % g['median']); print('= %.4f: %d of %d' % (g['probability_within_target'], g['n_within_target'], g['n_evaluated']))")
while IFS= read -r w; do grep -qF -- "$w" out.txt && ok "console shows '$w'" || { bad "console lacks '$w'"; cat out.txt; }; done <<< "$want"

# the unbalance's angle varied too (psi0 of plane 1): U with each member's psi0
run "$AUTOBAL" rotor ensemble --set ensemble.mode=random --set ensemble.samples=24 --set ensemble.seed=3 \
    --set ensemble.param3=psi0 --set transient.t_end=6 --set transient.stop_at_balance=false $T -o psi0.h5
chk unbalance psi0.h5

# two planes: the worst plane's |s_j|, the grade of 2 U, target_unbalance shared by the planes
run "$AUTOBAL" rotor ensemble "$DATA/rotor_two_planes.ini" --set ensemble.param1=psi_1 --set ensemble.param2=psi_3 \
    --set ensemble.n1=4 --set ensemble.n2=4 --set transient.t_end=2 --set ensemble.write_unbalance=true \
    --set ensemble.target_grade=G0.4 --set "ensemble.target_unbalance=3 g mm" -o two.h5
chk unbalance two.h5
"$PY" -c "import h5py,sys; a=h5py.File('two.h5')['rotor/ensemble/statistics/residual_unbalance_abs_final'].attrs; sys.exit(0 if abs(a['target']-1.5e-6)<1e-20 else 1)" \
  && ok "two planes: target_unbalance 3 g mm is 1.5 g mm per plane" || bad "two planes: per-plane target"

# a ramp whose final speed varies: the grade at the member's omega_b
run "$AUTOBAL" rotor ensemble --set drive.mode=ramp --set drive.omega_a=100 --set drive.omega_b=400 --set drive.t_a=0 \
    --set drive.t_b=0.5 --set ensemble.param2=omega_b --set ensemble.min2=300 --set ensemble.max2=500 --set ensemble.n2=3 \
    --set ensemble.n1=4 --set transient.t_end=2 --set ensemble.write_unbalance=true --set ensemble.target_grade=G1000 -o ramp.h5
chk unbalance ramp.h5

# without write_unbalance: no new datasets (the datasets of 0.1.0), the statistics as attributes
run "$AUTOBAL" rotor ensemble --set ensemble.n1=3 --set ensemble.n2=3 --set transient.t_end=1 -o plain.h5
chk nodatasets plain.h5

# the targets change no member: a resume may change them (the journal's identity leaves them out),
# and the result equals a run in one go with the new targets
run "$AUTOBAL" rotor ensemble --set ensemble.n1=3 --set ensemble.n2=3 --set transient.t_end=1 --set ensemble.max_members=4 \
    --set ensemble.target_grade=G100 -o part.h5
run "$AUTOBAL" rotor ensemble --set ensemble.n1=3 --set ensemble.n2=3 --set transient.t_end=1 --set ensemble.resume=true \
    --set ensemble.target_grade=G630 --set ensemble.write_unbalance=true -o part.h5
run "$AUTOBAL" rotor ensemble --set ensemble.n1=3 --set ensemble.n2=3 --set transient.t_end=1 \
    --set ensemble.target_grade=G630 --set ensemble.write_unbalance=true -o whole.h5
"$PY" - <<'PY' && ok "resume with another target = one run with it" || bad "resume with another target differs"
import h5py, numpy as np, sys
a, b = h5py.File("part.h5")["rotor/ensemble"], h5py.File("whole.h5")["rotor/ensemble"]
sa, sb = dict(a["statistics/balance_grade_final"].attrs), dict(b["statistics/balance_grade_final"].attrs)
same = np.array_equal(a["balance_grade_final"][()], b["balance_grade_final"][()]) and sa == sb and sa["target"] == 630
print(sa["target"], sa["n_within_target"], sb["n_within_target"])
sys.exit(0 if same else 1)
PY

# autobal rerun repeats the targets and the per-member datasets (effective_config)
run "$AUTOBAL" rerun whole.h5 -o whole2.h5
"$PY" - <<'PY' && ok "rerun: same per-member grades and statistics" || bad "rerun differs"
import h5py, numpy as np, sys
a, b = h5py.File("whole.h5")["rotor/ensemble"], h5py.File("whole2.h5")["rotor/ensemble"]
sys.exit(0 if np.array_equal(a["balance_grade_final"][()], b["balance_grade_final"][()])
         and dict(a["statistics/balance_grade_final"].attrs) == dict(b["statistics/balance_grade_final"].attrs) else 1)
PY

# the pendulum ensemble has no residual unbalance in g mm: the keys are refused
expect_err 3 "target_grade" "$AUTOBAL" pendulum ensemble --set ensemble.target_grade=G6.3 -o bad.h5

# bad targets: exit 3, the key named, nothing written
expect_err 3 "target_grade" "$AUTOBAL" rotor ensemble --set ensemble.target_grade=0 -o bad.h5
expect_err 3 "target_grade" "$AUTOBAL" rotor ensemble --set ensemble.target_grade=-6.3 -o bad.h5
expect_err 3 "target_grade = 'H7'" "$AUTOBAL" rotor ensemble --set ensemble.target_grade=H7 -o bad.h5
expect_err 3 "target_grade = 'G6.3 m'" "$AUTOBAL" rotor ensemble "--set" "ensemble.target_grade=G6.3 m" -o bad.h5
expect_err 3 "target_unbalance" "$AUTOBAL" rotor ensemble "--set" "ensemble.target_unbalance=0 g mm" -o bad.h5
expect_err 3 "target_unbalance" "$AUTOBAL" rotor ensemble "--set" "ensemble.target_unbalance=-5 g mm" -o bad.h5
expect_err 3 "target_unbalance" "$AUTOBAL" rotor ensemble "--set" "ensemble.target_unbalance=5 m/s" -o bad.h5
[ ! -e bad.h5 ] && ok "nothing written for bad targets" || bad "bad.h5 written"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
