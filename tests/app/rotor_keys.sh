#!/usr/bin/env bash
# `autobal rotor sweep|map` over any configuration key (docs/rotor.md "Sweeps and maps over any key"):
#  (a) sweeps over the balancer's axial position plane1.d, a support position supports.l_R and the
#      track radius plane1.ball_radius (given in mm): margins and critical values against NumPy roots of
#      the rotor rebuilt in rotor_keys_check.py from the recorded hardware with the key changed;
#  (b) a map over (plane1.ball_radius, C_over_A), checked the same way at random points;
#  (c) bad input: an unknown key, a lumped key of a hardware rotor, plane2 of a one-plane rotor, a range
#      end the model refuses: exit 3 naming the key, nothing written.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}"

expect 0 "critical values of plane1.d" "$AUTOBAL" rotor sweep --set sweep.param=plane1.d --set sweep.min=-0.2 \
  --set sweep.max=0.15 --set sweep.n=120 -o d.h5
"$PY" "$here/rotor_keys_check.py" sweep d.h5 && ok "plane1.d sweep checked" || bad "plane1.d sweep check"
expect 0 "supports.l_R" "$AUTOBAL" rotor sweep --set sweep.param=supports.l_R --set sweep.min=0.02 \
  --set sweep.max=0.6 --set sweep.n=120 -o l.h5
"$PY" - l.h5 <<'PY' && ok "the l_R sweep has a critical value" || bad "no critical value over l_R in [0.02, 0.6] m"
import sys, h5py
sys.exit(0 if int(h5py.File(sys.argv[1], "r")["rotor/sweep"].attrs["n_critical"]) >= 1 else 1)
PY
"$PY" "$here/rotor_keys_check.py" sweep l.h5 && ok "supports.l_R sweep checked" || bad "supports.l_R sweep check"
expect 0 "plane1.ball_radius" "$AUTOBAL" rotor sweep --set sweep.param=plane1.ball_radius --set "sweep.min=25 mm" \
  --set "sweep.max=200 mm" --set sweep.n=100 -o r.h5
"$PY" "$here/rotor_keys_check.py" sweep r.h5 && ok "plane1.ball_radius sweep checked" || bad "plane1.ball_radius sweep check"

expect 0 "C_over_A" "$AUTOBAL" rotor map --set map.param1=plane1.ball_radius --set "map.min1=25 mm" \
  --set "map.max1=200 mm" --set map.n1=12 --set map.param2=C_over_A --set map.min2=0.05 --set map.max2=2 \
  --set map.n2=9 -o m.h5
"$PY" "$here/rotor_keys_check.py" map m.h5 && ok "map checked" || bad "map check"

expect_err 3 "is not a parameter" "$AUTOBAL" rotor sweep --set sweep.param=c_Lxx -o bad1.h5
expect_err 3 "lumped.c_x: the rotor is given by its hardware" "$AUTOBAL" rotor sweep --set sweep.param=lumped.c_x -o bad2.h5
expect_err 3 "plane2.d: the rotor has 1 balancing plane" "$AUTOBAL" rotor map --set map.param1=plane2.d -o bad3.h5
expect_err 3 "parameter plane1.ball_mass = -0.01 kg is too small" "$AUTOBAL" rotor sweep \
  --set sweep.param=plane1.ball_mass --set sweep.min=-0.01 -o bad4.h5
expect_err 3 "supports.l_L" "$AUTOBAL" rotor sweep --set sweep.param=supports.l_L --set sweep.min=-0.3 -o bad5.h5
ls bad*.h5* >/dev/null 2>&1 && bad "an archive was written for bad input" || ok "nothing written for bad input"
finish
