#!/usr/bin/env bash
# bench/every4.sh: the cost of `rotor stability` with [stability] unbalance_member = every for 4..6
# identical balls (the branch-and-bound enclosure of u, docs/rotor.md "Four to six balls, every
# member"), as a ratio against the same run with unbalance_member = symmetric (the fan, closed form)
# in the same invocation.  Usage: bench/every4.sh [path/to/autobal] (default build/apps/autobal).
set -eu
A=${1:-build/apps/autobal}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ini() { # n omega lo hi rule
  /usr/bin/python3 -c 'import sys
n, om, lo, hi, rule = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5]
L = lambda v: ", ".join([v] * n)
print("[rotor]\nomega = %s\n[plane1]\nball_mass = %s\nball_radius = %s\nball_damping = %s\nball_psi = %s\nball_rate = %s\n[stability]\nunbalance_min = %s g mm\nunbalance_max = %s g mm\nunbalance_member = %s\ncritical_speeds = false" % (om, L("0.05"), L("0.1"), L("0.1"), ", ".join(str(0.5 * k) for k in range(n)), L("0"), lo, hi, rule))' "$@"
}
secs() { local t0 t1; t0=$(date +%s.%N); "$A" rotor stability "$1" --json > "$1.json"; t1=$(date +%s.%N); echo "$t1 - $t0" | bc -l; }
printf "%-4s %-22s %10s %10s %8s %10s\n" n "m0 r0 (g mm)" "every s" "symm s" ratio boxes
for c in "4 100 19000" "5 100 24000" "6 100 29000" "4 15000 17500" "5 18750 21500" "6 16611.1 16611.1" "6 22500 27000"; do
  set -- $c
  ini "$1" 500 "$2" "$3" every > "$tmp/e.ini"; ini "$1" 500 "$2" "$3" symmetric > "$tmp/s.ini"
  te=$(secs "$tmp/e.ini"); ts=$(secs "$tmp/s.ini")
  b=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["every_unbalance"]["u_boxes"])' "$tmp/e.ini.json")
  printf "%-4s %-22s %10.3f %10.3f %8.1f %10s\n" "$1" "$2..$3" "$te" "$ts" "$(echo "$te / $ts" | bc -l)" "$b"
done
