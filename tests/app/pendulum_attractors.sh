#!/usr/bin/env bash
# App test: the attractor classes of `autobal pendulum ensemble` (docs/guide.md "Attractors"): one member per
# class of the default balancer, each checked by pendulum_attractors_check.py from the mechanics:
#  - heavy side at R_w = 0.4 (below the first critical speed): both pendulums along the deflection;
#  - circulating at R_w = 1.5 from psi = phi = 0: frequency against the member's series, natural
#    frequency sqrt(1 - H^2/4);
#  - balanced at R_w = 3: the main motion;
#  - a window longer than the run counts as irregular; bad thresholds exit 3 naming the key.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${DATA:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
chk() { "$PY" "$here/pendulum_attractors_check.py" "$@" && ok "check $1" || bad "check $*"; }
one() { # one member at R_w = $1 from psi = phi = 0
  echo "--set ensemble.param1=R_w --set ensemble.n1=1 --set ensemble.min1=$1 --set ensemble.max1=$1 --set ensemble.param2=psi --set ensemble.n2=1 --set ensemble.min2=0 --set ensemble.max2=0 --set ensemble.series=0"
}
run "$AUTOBAL" pendulum ensemble "$DATA/pendulum_default.ini" $(one 0.4) --set transient.t_end=3000 \
    --set ensemble.attractor_window_revs=20 -o heavy.h5
grep -q "attractors: 0 balanced, 1 heavy_side" out.txt && ok "summary: heavy side" || { bad "summary"; cat out.txt; }
chk heavy heavy.h5
run "$AUTOBAL" pendulum ensemble "$DATA/pendulum_default.ini" $(one 1.5) --set transient.t_end=3000 \
    --set ensemble.attractor_window_revs=20 -o circ.h5
grep -q "circulating: a pendulum at nu = " out.txt && ok "summary: circulating with its frequency" || { bad "summary"; cat out.txt; }
chk circulating circ.h5
run "$AUTOBAL" pendulum ensemble "$DATA/pendulum_default.ini" $(one 3) -o bal.h5
chk balanced bal.h5
run "$AUTOBAL" pendulum ensemble "$DATA/pendulum_default.ini" $(one 0.4) --set transient.t_end=300
grep -q "0 periodic, 1 irregular" out.txt && ok "a window longer than the run: irregular" || { bad "short run"; cat out.txt; }
expect_err 3 "attractor_rest_tol" "$AUTOBAL" pendulum ensemble "$DATA/pendulum_default.ini" --set ensemble.attractor_rest_tol=0 -o x.h5
[ -e x.h5 ] && bad "archive written for bad input" || ok "nothing written for bad input"
finish
