#!/usr/bin/env bash
# The two-plane speed set for every unbalance (docs/rotor.md "Plane 2's unbalance: a certified box
# search"): data/rotor_two_planes.ini, both planes' m0 r0 in 1000..6000 g mm, every phase, the default
# speed scan (400 grid speeds up to 2000 rad/s, each change bisected), timed as CPU seconds with the
# box search off (unbalance2_boxes = -1, plane 2 on its 9-value grid: the reference) and on (the
# default: plane 2's whole range certified at each speed), alternating, ROUNDS rounds; prints each
# run and the ratio on/off per round (the load of the machine cancels in the ratio).
#   bench/every2_speeds.sh [ROUNDS] [--before BIN]   BIN: an autobal of an older revision, timed beside
#                                                    with its default (e.g. main before issue 17's fixes)
# AUTOBAL: the binary (default build/apps/autobal next to bench/).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${AUTOBAL:-$here/../build/apps/autobal}
rounds=1
before=
while [ $# -gt 0 ]; do
  case "$1" in
    --before) before=$2; shift 2 ;;
    *) rounds=$1; shift ;;
  esac
done
ini=$here/../data/rotor_two_planes.ini
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() { # binary, boxes -> "cpu_seconds undecided_speeds evaluated_speeds"
  /usr/bin/time -f "%U %S" -o "$tmp/t" "$1" rotor stability "$ini" --set "stability.unbalance_min=1000 g mm" \
    --set "stability.unbalance_max=6000 g mm" --set "stability.unbalance2_boxes=$2" --json > "$tmp/j"
  /usr/bin/python3 - "$tmp/t" "$tmp/j" <<'PY'
import json, sys
u, s = open(sys.argv[1]).read().split()[-2:]
d = json.load(open(sys.argv[2]))['every_unbalance']['speeds']
print(f"{float(u) + float(s):.2f} {d.get('n_speeds_undecided_in_unbalance2', 'NA')} {d.get('n_speeds_evaluated', 'NA')} "
      f"{d['stable_lo'][0] if d['stable_lo'] else float('nan'):.10g}")
PY
}
printf "%-5s %-22s %8s %10s %10s %14s %6s\n" round case cpu_s undecided evaluated stable_from ratio
for r in $(seq 1 "$rounds"); do
  read -r c0 u0 e0 w0 < <(run "$bin" -1)
  printf "%-5s %-22s %8s %10s %10s %14s %6s\n" "$r" "search off (reference)" "$c0" "$u0" "$e0" "$w0" 1
  read -r c1 u1 e1 w1 < <(run "$bin" 0)
  printf "%-5s %-22s %8s %10s %10s %14s %6.2f\n" "$r" "search on (default)" "$c1" "$u1" "$e1" "$w1" \
    "$(echo "$c1 / $c0" | bc -l)"
  if [ -n "$before" ]; then
    read -r c2 u2 e2 w2 < <(run "$before" 0)
    printf "%-5s %-22s %8s %10s %10s %14s %6.2f\n" "$r" "before, default" "$c2" "$u2" "$e2" "$w2" \
      "$(echo "$c2 / $c0" | bc -l)"
  fi
done
