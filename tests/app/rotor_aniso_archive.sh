#!/usr/bin/env bash
# What the archive and the map record of an every-unbalance analysis on ANISOTROPIC supports (Hill's
# method, data/rotor_anisotropic.ini; docs/rotor.md "Anisotropic supports: Hill's method"):
#  (a) `rotor stability` -o: /rotor/stability/every_unbalance carries method = "hill", hill_order,
#      hill_tail, hill_boxes, hill_open, unstable_unbalance, the same values as the --json summary of
#      the same run, and sub_verdict 1 (proven), -2 (undecided: budget) or -1 (a member unstable);
#  (b) `rotor map` for every unbalance: a point whose budget ([map] hill_boxes) runs out is -3
#      "undecided", not -2 "no balanced configuration" (the old code's label) and not stable; with the
#      default budget (at 500 rad/s, ball damping 0.05 and 0.1 kg/s) each point says what `rotor
#      stability` says there: one undecided, one stable;
#      `autobal plot` draws the two cells of that one-row map in their colours;
#  (c) [map] hill_boxes out of range: exit 3 naming the key and the range.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

ini="$DATA/rotor_anisotropic.ini"
stab() { # lo hi (g mm) out.h5 [--set ...]: JSON into out.json
  local lo=$1 hi=$2 out=$3; shift 3
  "$AUTOBAL" rotor stability "$ini" --set stability.unbalance_min="$lo g mm" --set stability.unbalance_max="$hi g mm" \
    --set stability.critical_speeds=false "$@" -o "$out" --force --json > "${out%.h5}.json" 2>err.txt ||
    { bad "rotor stability $lo..$hi g mm $*: exit $?"; cat err.txt; }
}
# archive vs JSON of the same run; $2: the expected sub_verdict
check() {
  "$PY" - "$1" "$2" <<'PYEOF' && ok "$1: archive = JSON (method hill, sub_verdict $2)" || bad "$1: archive and JSON differ"
import json, math, sys, h5py
f, want = sys.argv[1], int(sys.argv[2])
j = json.load(open(f[:-3] + ".json"))["every_unbalance"]
g = h5py.File(f, "r")["rotor/stability/every_unbalance"]
a = g.attrs
def s(x): return x.decode() if isinstance(x, bytes) else str(x)
assert s(a["method"]) == "hill", a["method"]
assert "Hill" in s(a["description"])
for k in ("hill_order", "hill_boxes", "hill_open"):
    assert int(a[k]) == int(j[k]), (k, a[k], j[k])
u = float(a["unstable_unbalance"])
ju = j["unstable_unbalance"]
assert (math.isnan(u) and ju is None) or abs(u - ju) <= 1e-12 * abs(ju), (u, ju)
assert int(a["stable_for_all"]) == (1 if j["stable_for_all"] else 0)
v = g["sub_verdict"][...].tolist()
assert v == [want], v
assert (want == 1) == (int(a["hill_open"]) == 0 and bool(j["stable_for_all"]))
assert (want == -1) == (not math.isnan(u))
PYEOF
}

# (a)
stab 1500 3000 proven.h5 && check proven.h5 1
stab 1500 3000 budget.h5 --set stability.hill_boxes=200 && check budget.h5 -2
stab 6000 7000 unstable.h5 && check unstable.h5 -1

# (b)
map() { # hill_boxes out.h5 [--set ...]
  local hb=$1 out=$2; shift 2
  "$AUTOBAL" rotor map "$ini" --set map.param1=omega --set map.min1=490 --set map.max1=510 --set map.n1=2 \
    --set map.param2=ball_damping --set map.min2=0.05 --set map.max2=0.1 --set map.n2=2 \
    --set map.unbalance_min="1500 g mm" --set map.unbalance_max="3000 g mm" --set map.hill_boxes="$hb" \
    -o "$out" --force "$@"
}
map 200 small.h5 > small.txt 2>err.txt || { bad "map, budget 200: exit $?"; cat err.txt; }
grep -q "undecided points: 4" small.txt && ok "map, budget 200: 4 undecided points (console)" || { bad "map console"; cat small.txt; }
"$PY" -c "
import h5py, numpy as np
v = h5py.File('small.h5', 'r')['rotor/map/verdict'][...]
assert (v == -3).all(), v
" && ok "map, budget 200: every point -3 (undecided) in the archive" || bad "map, budget 200: verdicts not -3"
map 0 full.h5 --set map.min1=500 --set map.max1=500 --set map.n1=1 --json > full.json 2>err.txt ||
  { bad "map, default budget: exit $?"; cat err.txt; }
"$PY" -c "
import json, h5py
d = json.load(open('full.json'))
assert d['n_undecided'] == 1 and d['n_stable'] == 1, d
v = h5py.File('full.h5', 'r')['rotor/map/verdict'][...].tolist()
assert v == [[-3, 1]], v
" && ok "map, default budget: ball damping 0.05 kg/s undecided (-3), 0.1 kg/s stable (1)" || bad "map, default budget: $(cat full.json)"
# the picture of that one-row map: both cells drawn, in the colours of undecided and stable (a map with
# one row used to come out blank: cells of zero width)
"$AUTOBAL" plot full.h5 -o pics > plot.txt 2>&1 || { bad "autobal plot full.h5: exit $?"; cat plot.txt; }
"$PY" -c "
import numpy as np, matplotlib.image as mi
im = mi.imread('pics/full_stability_map.png')[..., :3]
left = im[:, : im.shape[1] // 2]
def n(hexc):
    c = np.array([int(hexc[i:i + 2], 16) for i in (1, 3, 5)]) / 255.0
    return int((np.abs(left - c).max(axis=2) < 0.02).sum())
u, s = n('#9ec5e8'), n('#8fd18f')
print('undecided pixels', u, 'stable pixels', s)
assert u > 20000 and s > 20000, (u, s)
" && ok "plot of the one-row map: undecided and stable cells drawn" || bad "plot of the one-row map"
for hv in "0.05 UNDECIDED" "0.1 STABLE for all"; do
  h=${hv%% *}
  expect 0 "${hv#* }" "$AUTOBAL" rotor stability "$ini" --set plane1.ball_damping="$h, $h" \
    --set stability.unbalance_min="1500 g mm" --set stability.unbalance_max="3000 g mm" --set stability.critical_speeds=false
done

# (c)
expect 3 "[map]: hill_boxes = 50 is out of range: allowed 0 (the default budget, 20000) or [100, 1e8]" map 50 bad.h5
[ -e bad.h5 ] && bad "bad.h5 written" || ok "nothing written on bad input"
finish
