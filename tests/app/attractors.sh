#!/usr/bin/env bash
# App test: the attractor classes of `autobal rotor ensemble` (include/autobal/attractor.h,
# docs/guide.md "Attractors"), one member per class of the default rotor, each checked by
# attractors_check.py for a reason of its own:
#  - circulating: 500 rad/s, balls from -3 pi/4 and -pi/2 (a member of the 8 x 8 map of issue 17
#    that does not balance), 3 s: the frequency against the series and against the forward natural
#    frequency of the rotor's linearization computed by numpy;
#  - balanced: 500 rad/s from the default start: final angles against the closed form (3.14);
#  - heavy side: 100 rad/s, below the first critical speed (numpy): the balls where the balancer's
#    centre deflects (their equilibrium condition);
#  - a 4 x 4 map at 500 rad/s (3 s): the per-member classes, the counts (dataset, --json,
#    attributes) and the console map;
#  - bad thresholds and keys: exit 3 naming the key and the range.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${DATA:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
chk() { "$PY" "$here/attractors_check.py" "$@" && ok "check $1 $2" || bad "check $*"; }
one() { # one member at (psi_1, psi_2)
  echo "--set ensemble.n1=1 --set ensemble.min1=$1 --set ensemble.max1=$1 --set ensemble.n2=1 --set ensemble.min2=$2 --set ensemble.max2=$2"
}

run "$AUTOBAL" rotor ensemble "$DATA/rotor_default.ini" $(one -2.356194490192345 -1.5707963267948966) \
    --set transient.t_end=3 --set ensemble.series=0 -o circ.h5
grep -q "attractors: 0 balanced, 0 heavy_side, 0 fixed, 1 circulating" out.txt && ok "summary: 1 circulating" || { bad "summary"; cat out.txt; }
grep -q "circulating: a ball at nu = " out.txt && ok "summary: the frequency" || bad "summary: no frequency"
chk circulating circ.h5 "$DATA/rotor_default.ini"

run "$AUTOBAL" rotor ensemble "$DATA/rotor_default.ini" $(one 1.0 2.5) --set transient.t_end=20 -o bal.h5
chk balanced bal.h5 "$DATA/rotor_default.ini"

sed 's/^omega = 500 /omega = 100 /' "$DATA/rotor_default.ini" > sub.ini
grep -q "^omega = 100 " sub.ini && ok "sub.ini at 100 rad/s" || bad "sub.ini"
run "$AUTOBAL" rotor ensemble sub.ini $(one 1.0 2.5) --set transient.t_end=10 -o heavy.h5
chk heavy heavy.h5 sub.ini

run "$AUTOBAL" rotor ensemble "$DATA/rotor_default.ini" --set ensemble.n1=4 --set ensemble.n2=4 --set transient.t_end=3 \
    --set ensemble.threads=2 -o map.h5
cp out.txt map.txt
run "$AUTOBAL" rotor ensemble "$DATA/rotor_default.ini" --set ensemble.n1=4 --set ensemble.n2=4 --set transient.t_end=3 \
    --set ensemble.threads=1 --json -o map1.h5
cp out.txt map.json
chk map map.h5 map.json map.txt
# the classes do not depend on the number of threads
"$PY" -c "import h5py,sys,numpy as np; a,b=(h5py.File(f)['rotor/ensemble'] for f in ('map.h5','map1.h5')); sys.exit(0 if all(np.array_equal(a[k][()],b[k][()],equal_nan=True) for k in ('attractor','circulation_frequency','natural_frequency')) else 1)" \
  && ok "classes and frequencies: 1 thread = 2 threads" || bad "classes differ between thread counts"
# write_attractors = false: the class counts only
run "$AUTOBAL" rotor ensemble "$DATA/rotor_default.ini" --set ensemble.n1=2 --set ensemble.n2=1 --set transient.t_end=1 \
    --set ensemble.write_attractors=false -o nowrite.h5
"$PY" -c "import h5py,sys; g=h5py.File('nowrite.h5')['rotor/ensemble']; sys.exit(0 if 'attractor' not in g and 'natural_frequency' not in g and sum(int(g.attrs['n_attractor_'+n]) for n in ('unclassified','balanced','heavy_side','fixed','circulating','periodic','irregular'))==2 else 1)" \
  && ok "write_attractors = false: counts only" || bad "write_attractors = false"

# bad input: the key, its value and the range named; exit 3
expect 3 "attractor_rest_tol = 0 rad is too small" "$AUTOBAL" rotor ensemble --set ensemble.attractor_rest_tol=0
expect 3 "(0, 3.14159" "$AUTOBAL" rotor ensemble --set ensemble.attractor_rest_tol=4
expect 3 "attractor_window_revs = 'nan' is not a finite number" "$AUTOBAL" rotor ensemble --set ensemble.attractor_window_revs=nan
expect 3 "attractor_window_revs = 0 is too small" "$AUTOBAL" rotor ensemble --set ensemble.attractor_window_revs=0
expect 3 "attractor_min_turns" "$AUTOBAL" rotor ensemble --set ensemble.attractor_min_turns=0.5
expect 3 "attractor_rate_tol" "$AUTOBAL" rotor ensemble --set ensemble.attractor_rate_tol=1
expect 3 "attractor_envelope_tol" "$AUTOBAL" rotor ensemble --set ensemble.attractor_envelope_tol=-0.1
expect 3 "attractor_rest_toll" "$AUTOBAL" rotor ensemble --set ensemble.attractor_rest_toll=0.1
expect 3 "write_attractors" "$AUTOBAL" rotor ensemble --set ensemble.write_attractors=maybe
expect 3 "attractor_rest_tol" "$AUTOBAL" pendulum ensemble --set ensemble.attractor_rest_tol=0   # the pendulum ensemble takes the same keys
finish
