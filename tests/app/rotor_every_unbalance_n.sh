#!/usr/bin/env bash
# rotor stability for EVERY unbalance with three and four identical balls ([stability] unbalance_min,
# unbalance_max, unbalance_member = symmetric):
#  (a) 3 balls at 500 rad/s over 100..14000 g mm: every sub-interval's verdict is that of an ordinary
#      `rotor stability` run (member1 = symmetric) at its midpoint, and the ordinary verdicts differ at
#      1e-6 on either side of each critical unbalance;
#  (b) u_min, u_max against NumPy: the symmetric fan solved by SciPy's brentq on a dense grid of
#      unbalances, |sum m e^{2 i psi}|^2 / 4 (not the Chebyshev forms);
#  (c) the archive attributes; the map with 4 balls; two balls print no member rule;
#  (d) refusals, exit 3, nothing written: unbalance_member = every with 11 balls (3 to 10 only), unequal balls
#      (naming the keys), an unknown rule.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

balls3='[plane1]\nball_mass = 0.05, 0.05, 0.05\nball_radius = 0.1, 0.1, 0.1\nball_damping = 0.1, 0.1, 0.1\nball_psi = 1, 2.5, 3\nball_rate = 0, 0, 0\n'
verdict_at() { # omega m0 -> the verdict of an ordinary analysis of the symmetric member
  printf "[rotor]\nomega = %s\n${balls3}m0 = %s\n[stability]\ncritical_speeds = false\nmember1 = symmetric\n" "$1" "$2" > one.ini
  "$AUTOBAL" rotor stability one.ini --json 2>/dev/null | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["verdict"])'
}

printf "[rotor]\nomega = 500\n${balls3}[stability]\nunbalance_min = 100 g mm\nunbalance_max = 14000 g mm\nunbalance_member = symmetric\ncritical_speeds = false\n" > a.ini
expect 0 "unbalance_member = symmetric" "$AUTOBAL" rotor stability a.ini
"$AUTOBAL" rotor stability a.ini --json > a.json 2>err.txt || bad "json run"
read -r -a subs < <("$PY" -c '
import json; e = json.load(open("a.json"))["every_unbalance"]
print(" ".join("%r:%s" % (0.5 * (lo + hi), v) for lo, hi, v in zip(e["sub_lo"], e["sub_hi"], e["sub_verdict"])))')
read -r -a crit < <("$PY" -c 'import json; print(" ".join(repr(x) for x in json.load(open("a.json"))["every_unbalance"]["critical_unbalance"]))')
[ "${#crit[@]}" -ge 1 ] && ok "3 balls, 500 rad/s: ${#crit[@]} critical unbalance(s): ${crit[*]} kg m" || bad "no critical unbalance"
for sv in "${subs[@]}"; do
  s=${sv%%:*}; v=${sv##*:}
  got=$(verdict_at 500 "$("$PY" -c "print($s / 0.1)")")
  [ "$got" = "$v" ] && ok "sub-interval around $s kg m: $v (ordinary run: $got)" || bad "sub-interval around $s kg m: every-unbalance $v, ordinary run $got"
done
for s in "${crit[@]}"; do
  lo=$(verdict_at 500 "$("$PY" -c "print($s * (1 - 1e-6) / 0.1)")")
  hi=$(verdict_at 500 "$("$PY" -c "print($s * (1 + 1e-6) / 0.1)")")
  [ "$lo" != "$hi" ] && ok "across $s kg m: $lo -> $hi" || bad "across $s kg m the ordinary verdicts agree ($lo, $hi)"
done

# (b) the range of u against NumPy/SciPy
if "$PY" - a.json <<'PY'
import json, sys
import numpy as np
from scipy.optimize import brentq
e = json.load(open(sys.argv[1]))["every_unbalance"]
n, m, a = 3, 0.05, 0.05 * 0.1
us = []
for s in np.linspace(100e-6, 14000e-6, 20001):
    th = brentq(lambda x: np.sin(n * x) / np.sin(x) - s / a, 1e-12, np.pi / n)
    psi = np.pi + (np.arange(n) - (n - 1) / 2) * 2 * th
    q = m * np.exp(2j * psi).sum()
    us.append(abs(q) ** 2 / 4)
us = np.array(us)
ok = us.min() >= e["u_min"] - 1e-12 and us.max() <= e["u_max"] * (1 + 1e-10)
ok = ok and us.min() - e["u_min"] < 1e-7 and e["u_max"] - us.max() < 1e-7 * e["u_max"] + 1e-12
print("NumPy u range", us.min(), us.max(), "program", e["u_min"], e["u_max"])
sys.exit(0 if ok and e["n_balls"] == 3 and e["unbalance_member"] == "symmetric" else 1)
PY
then ok "u = |Q|^2/4 range agrees with a NumPy/SciPy fan on 20001 unbalances"; else bad "u range vs NumPy"; fi

# (c) archive, map with 4 balls, two balls
expect 0 "EVERY UNBALANCE" "$AUTOBAL" rotor stability a.ini -o a.h5
if "$PY" - a.h5 <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r")["/rotor/stability/every_unbalance"]
m = g.attrs["unbalance_member"]; m = m.decode() if isinstance(m, bytes) else m
u = g.attrs["u_max"]
sys.exit(0 if m == "symmetric" and g.attrs["n_balls"] == 3 and u > 0 and "u_min" in g.attrs else 1)
PY
then ok "archive: unbalance_member, n_balls, u_min, u_max"; else bad "archive attributes"; fi
balls4='[plane1]\nball_mass = 0.05, 0.05, 0.05, 0.05\nball_radius = 0.1, 0.1, 0.1, 0.1\nball_damping = 0.1, 0.1, 0.1, 0.1\nball_psi = 1, 2, 3, 4\nball_rate = 0, 0, 0, 0\n'
printf "${balls4}[map]\nparam1 = omega\nmin1 = 400\nmax1 = 1200\nn1 = 3\nparam2 = ball_damping\nmin2 = 0.05\nmax2 = 0.2\nn2 = 2\nunbalance_min = 100 g mm\nunbalance_max = 4000 g mm\nunbalance_member = symmetric\n" > m.ini
expect 0 "unbalance_member = symmetric" "$AUTOBAL" rotor map m.ini -o m.h5
if "$PY" - m.h5 <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r")["/rotor/map"]
m = g.attrs["unbalance_member"]; m = m.decode() if isinstance(m, bytes) else m
sys.exit(0 if m == "symmetric" and g["verdict"].shape == (3, 2) else 1)
PY
then ok "map with 4 balls: archive names the member rule"; else bad "map archive (4 balls)"; fi
printf '[stability]\nunbalance_min = 100 g mm\nunbalance_max = 4000 g mm\ncritical_speeds = false\n' > two.ini
"$AUTOBAL" rotor stability two.ini --json > two.json || bad "two balls run"
"$PY" -c 'import json,sys; e = json.load(open("two.json"))["every_unbalance"]; sys.exit(0 if "unbalance_member" not in e and "u_min" not in e else 1)' \
  && ok "two balls: no member rule, no u range in the output" || bad "two balls output changed"

# (d) refusals
balls7='[plane1]\nball_mass = 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05\nball_radius = 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1\nball_damping = 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1\nball_psi = 1, 2, 3, 4, 5, 6, 0, 0.5, 1.5, 2.5, 3.5\nball_rate = 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0\n'
printf "${balls7}[stability]\nunbalance_min = 100 g mm\nunbalance_max = 4000 g mm\n" > d1.ini
expect 3 "unbalance_member = symmetric" "$AUTOBAL" rotor stability d1.ini -o d1.h5
[ ! -e d1.h5 ] && ok "rule every with 11 balls: refused, nothing written" || bad "d1.h5 written"
printf '[plane1]\nball_mass = 0.05, 0.05, 0.06\nball_radius = 0.1, 0.1, 0.1\nball_damping = 0.1, 0.1, 0.1\nball_psi = 1, 2.5, 3\nball_rate = 0, 0, 0\n[stability]\nunbalance_min = 100 g mm\nunbalance_max = 4000 g mm\nunbalance_member = symmetric\n' > d2.ini
expect 3 "plane1.ball_mass" "$AUTOBAL" rotor stability d2.ini -o d2.h5
[ ! -e d2.h5 ] && ok "unequal balls: refused, nothing written" || bad "d2.h5 written"
printf "${balls3}[stability]\nunbalance_min = 100 g mm\nunbalance_max = 4000 g mm\nunbalance_member = fan\n" > d3.ini
expect 3 "unbalance_member" "$AUTOBAL" rotor stability d3.ini
finish
