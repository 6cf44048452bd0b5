#!/usr/bin/env bash
# rotor stability for EVERY unbalance in a range ([stability] unbalance_min, unbalance_max):
#  (a) at 500 rad/s over 100..9500 g mm: every sub-interval's verdict is the verdict of a separate,
#      ordinary `rotor stability` run at the sub-interval's midpoint m0 (no crossing polynomial there),
#      and at 1e-6 on either side of each critical unbalance the two runs differ (a root crosses);
#  (b) the speeds stable for every unbalance in 10..4000 g mm: ordinary runs at m0 = 0.1, 20, 40 g
#      (r0 = 0.1 m) just inside and just outside the reported lower end agree with it;
#  (c) the archive: /rotor/stability/every_unbalance with units; the map for every unbalance; bad input:
#      one key alone, a range the balls cannot balance, exit 3 and nothing written.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

verdict_at() { # omega m0 -> the verdict of an ordinary analysis
  printf '[rotor]\nomega = %s\n[plane1]\nm0 = %s\n[stability]\ncritical_speeds = false\n' "$1" "$2" > one.ini
  "$AUTOBAL" rotor stability one.ini --json 2>/dev/null | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["verdict"])'
}

printf '[rotor]\nomega = 500\n[stability]\nunbalance_min = 100 g mm\nunbalance_max = 9500 g mm\ncritical_speeds = false\n' > a.ini
expect 0 "EVERY UNBALANCE" "$AUTOBAL" rotor stability a.ini
"$AUTOBAL" rotor stability a.ini --json > a.json 2>err.txt || bad "json run"
read -r -a subs < <("$PY" -c '
import json; e = json.load(open("a.json"))["every_unbalance"]
print(" ".join("%r:%s" % (0.5 * (lo + hi), v) for lo, hi, v in zip(e["sub_lo"], e["sub_hi"], e["sub_verdict"])))')
read -r -a crit < <("$PY" -c 'import json; print(" ".join(repr(x) for x in json.load(open("a.json"))["every_unbalance"]["critical_unbalance"]))')
[ "${#crit[@]}" -ge 1 ] && ok "500 rad/s: ${#crit[@]} critical unbalance(s): ${crit[*]} kg m" || bad "no critical unbalance at 500 rad/s (the unstable window m0 0.056-0.083 kg expected)"
for sv in "${subs[@]}"; do
  s=${sv%%:*}; v=${sv##*:}
  m0=$("$PY" -c "print($s / 0.1)")
  got=$(verdict_at 500 "$m0")
  [ "$got" = "$v" ] && ok "sub-interval around m0 r0 = $s kg m: $v (ordinary run: $got)" || bad "sub-interval around $s kg m: every-unbalance $v, ordinary run $got"
done
for s in "${crit[@]}"; do
  lo=$(verdict_at 500 "$("$PY" -c "print($s * (1 - 1e-6) / 0.1)")")
  hi=$(verdict_at 500 "$("$PY" -c "print($s * (1 + 1e-6) / 0.1)")")
  [ "$lo" != "$hi" ] && ok "across $s kg m: $lo -> $hi" || bad "across $s kg m the ordinary verdicts agree ($lo, $hi)"
done

# (b) the speeds stable for every unbalance in 10..4000 g mm
printf '[stability]\nunbalance_min = 10 g mm\nunbalance_max = 4000 g mm\nn_omega = 200\n' > b.ini
expect 0 "for every unbalance" "$AUTOBAL" rotor stability b.ini -o b.h5
read -r w_lo < <("$PY" - b.h5 <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r")["/rotor/stability/every_unbalance/speeds"]
print(repr(float(g["stable_lo"][0])))
PY
)
ok "lowest speed stable for every unbalance: $w_lo rad/s"
below=$("$PY" -c "print($w_lo * (1 - 1e-4))"); above=$("$PY" -c "print($w_lo * (1 + 1e-4))")
n_unstable_below=0
for m0 in 0.0001 0.02 0.04; do
  [ "$(verdict_at "$above" $m0)" = stable ] && ok "just above ($above rad/s) m0 = $m0 kg: stable" || bad "just above $above rad/s m0 = $m0 kg is not stable"
  [ "$(verdict_at "$below" $m0)" = stable ] || n_unstable_below=$((n_unstable_below + 1))
done
# just below, some unbalance in the range is unstable: the sampled ones or the range's ends
if [ $n_unstable_below -ge 1 ]; then ok "just below ($below rad/s) $n_unstable_below of m0 = 0.0001, 0.02, 0.04 kg unstable"
else
  [ "$(verdict_at "$below" 0.0001)$(verdict_at "$below" 0.04)" != stablestable ] && ok "just below: an end of the range is unstable" || bad "just below $below rad/s all sampled unbalances are stable"
fi
if "$PY" - b.h5 <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
g = f["/rotor/stability/every_unbalance"]
ok = abs(g.attrs["unbalance_min"] - 1e-5) < 1e-18 and abs(g.attrs["unbalance_max"] - 4e-3) < 1e-15 and g.attrs["stable_for_all"] == 1
ok = ok and g["sub_lo"].attrs["units"] in (b"kg m", "kg m") and "description" in g.attrs
sys.exit(0 if ok else 1)
PY
then ok "archive: every_unbalance group with its range, verdict and units"; else bad "archive: every_unbalance group"; fi

# the map for every unbalance (omega x ball damping): its archive and the pairing of its keys
printf '[map]\nparam1 = omega\nmin1 = 400\nmax1 = 1000\nn1 = 4\nparam2 = ball_damping\nmin2 = 0.05\nmax2 = 0.2\nn2 = 2\nunbalance_min = 10 g mm\nunbalance_max = 4000 g mm\n' > m.ini
expect 0 "for EVERY unbalance" "$AUTOBAL" rotor map m.ini -o m.h5
if "$PY" - m.h5 <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r")["/rotor/map"]
sys.exit(0 if g.attrs["every_unbalance"] == 1 and abs(g.attrs["unbalance_max"] - 4e-3) < 1e-15 and g["verdict"].shape == (4, 2) else 1)
PY
then ok "map archive: every_unbalance, its range, verdict[4][2]"; else bad "map archive"; fi
printf '[map]\nunbalance_max = 4000 g mm\n' > m2.ini
expect 3 "unbalance_min" "$AUTOBAL" rotor map m2.ini -o m2.h5
[ ! -e m2.h5 ] && ok "map, one key alone: nothing written" || bad "m2.h5 written"

# (c) bad input: exit 3, nothing written
printf '[stability]\nunbalance_min = 100 g mm\n' > c1.ini
expect 3 "unbalance_max" "$AUTOBAL" rotor stability c1.ini -o c1.h5
[ ! -e c1.h5 ] && ok "one key alone: nothing written" || bad "c1.h5 written"
printf '[stability]\nunbalance_min = 100 g mm\nunbalance_max = 12000 g mm\n' > c2.ini
expect 3 "m0 r0" "$AUTOBAL" rotor stability c2.ini -o c2.h5
[ ! -e c2.h5 ] && ok "a range the balls cannot balance: nothing written" || bad "c2.h5 written"
printf '[stability]\nunbalance_min = nan\nunbalance_max = 100 g mm\n' > c3.ini
expect 3 "unbalance_min" "$AUTOBAL" rotor stability c3.ini -o c3.h5
finish
