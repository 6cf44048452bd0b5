#!/usr/bin/env bash
# App test: the small-damping picture of the two-pendulum balancer and the note of the undamped map
# (docs/pendulum.md, "The undamped map is not the small-damping limit").  Every-unbalance maps on the
# grid of data/pendulum_map_every.ini, undamped and at small H, h, checked point by point against
# NumPy eigenvalues of (5) written out in pendulum_smalldamp_check.py (quick: every 4th row and
# column; `slow`: the whole grid, and the note's percentages against NumPy's).
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
mode=${1:-quick}
here=$(cd "$(dirname "$0")" && pwd)
[ "$mode" = slow ] && SCRATCH=${SCRATCH}_slow
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH" && cd "$SCRATCH" || exit 1
fail=0
run() { "$@" || { echo "FAIL: $*"; fail=1; }; }
map() { run "$AUTOBAL" pendulum map "$DATA/pendulum_map_every.ini" --set pendulum.H=$1 --set pendulum.h=$2 -q -o "$3.h5"; }
map 0 0 und; map 1e-4 1e-4 hh; map 1e-5 1e-4 h10; map 1e-4 1e-5 H10; map 1e-6 1e-6 hh6
if [ "$mode" = slow ]; then
  map 0.3981e-5 1e-5 r04; map 1e-6 1e-4 h100; map 0.2512e-5 1e-5 r_0.2512; map 0.631e-5 1e-5 r_0.631
fi
# the console shows the note too
"$AUTOBAL" pendulum map "$DATA/pendulum_map_every.ini" --set map.n_Rm=4 --set map.n_Rw=4 >note.txt 2>&1
grep -q "note (undamped): the undamped map is not the small-damping limit" note.txt && echo "ok   console note" || { echo "FAIL console note"; cat note.txt; fail=1; }
"$AUTOBAL" pendulum map "$DATA/pendulum_map_every.ini" --set pendulum.H=1e-3 --set map.n_Rm=4 --set map.n_Rw=4 >note2.txt 2>&1
grep -q "note" note2.txt && { echo "FAIL a damped map printed the note"; fail=1; } || echo "ok   no note on a damped map"
"$PY" "$here/pendulum_smalldamp_check.py" "$SCRATCH" "$mode" || fail=1
exit $fail
