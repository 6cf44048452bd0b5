#!/usr/bin/env bash
# App test: `autobal pendulum transient`, archives checked by pendulum_transient_check.py.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

run "$AUTOBAL" pendulum transient "$DATA/pendulum_transient.ini" -o bal.h5
"$PY" "$here/pendulum_transient_check.py" balanced bal.h5 && ok "balanced transient" || bad "balanced transient"
run "$AUTOBAL" pendulum transient --set pendulum.H=0 --set pendulum.h=0 --set transient.t_end=100 --set initial.psi=0.3 -o cons.h5
"$PY" "$here/pendulum_transient_check.py" conserved cons.h5 && ok "conservative transient" || bad "conservative transient"
# R_w = 1.2 lies below the damped critical speed of this parameter set (stable only above ~2.17)
run "$AUTOBAL" pendulum transient "$DATA/pendulum_transient.ini" --set pendulum.R_w=1.2 -o unst.h5
"$PY" "$here/pendulum_transient_check.py" unstable unst.h5 && ok "unstable transient" || bad "unstable transient"
"$AUTOBAL" pendulum transient --set transient.max_steps=10 -o maxs.h5 >out.txt 2>err.txt; rc=$?
[ $rc -eq 5 ] && ok "max steps -> exit 5" || bad "max steps gave $rc"
"$PY" -c "import h5py; f=h5py.File('maxs.h5'); assert f.attrs['status']=='incomplete'" && ok "partial archive marked incomplete" || bad "partial archive"
"$AUTOBAL" pendulum transient --set transient.rtol=-1 >out.txt 2>err.txt; rc=$?
[ $rc -eq 3 ] && grep -q rtol err.txt && ok "negative rtol -> exit 3 naming rtol" || bad "negative rtol gave $rc"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
