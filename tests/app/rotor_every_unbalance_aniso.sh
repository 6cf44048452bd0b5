#!/usr/bin/env bash
# rotor stability for EVERY unbalance with ANISOTROPIC supports (data/rotor_anisotropic.ini; one plane,
# two balls; Hill's method, docs/rotor.md "Anisotropic supports: Hill's method"):
#  (a) 1500..3000 g mm at 500 rad/s: "STABLE for all", proven (no box left open); ordinary `rotor
#      stability` runs (Floquet, no Hill matrix) at 13 unbalances across the range are all stable;
#  (b) 6000..7000 g mm: not stable, with the unstable member named; an ordinary run there is unstable,
#      and some of 13 ordinary runs across the range are unstable;
#  (c) a small budget ([stability] hill_boxes) on the stable range: undecided, never "stable";
#  (d) bad input: hill_boxes out of range (exit 3); three balls on anisotropic supports refused with a
#      message naming what is supported.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

ini="$DATA/rotor_anisotropic.ini"
verdict_at() { # unbalance (kg m) -> the verdict of an ordinary analysis (m0 = s / r0, r0 = 0.1 m)
  "$AUTOBAL" rotor stability "$ini" --set plane1.m0="$("$PY" -c "print($1 / 0.1)")" \
    --set stability.critical_speeds=false --json 2>/dev/null |
    "$PY" -c 'import json,sys; d = json.load(sys.stdin); print(d["verdict"] + ":" + d["method"])'
}
every() { # lo hi (g mm) [extra --set ...] -> JSON of the every_unbalance object into e.json
  local lo=$1 hi=$2; shift 2
  "$AUTOBAL" rotor stability "$ini" --set stability.unbalance_min="$lo g mm" --set stability.unbalance_max="$hi g mm" \
    --set stability.critical_speeds=false "$@" --json > e.json 2>err.txt || { bad "every unbalance $lo..$hi: exit $?"; cat err.txt; }
}
field() { "$PY" -c "import json; print(json.load(open('e.json'))['every_unbalance']['$1'])"; }

# (a)
expect 0 "STABLE for all" "$AUTOBAL" rotor stability "$ini" --set stability.unbalance_min="1500 g mm" \
  --set stability.unbalance_max="3000 g mm" --set stability.critical_speeds=false
every 1500 3000
[ "$(field method)" = hill ] && ok "method hill" || bad "method $(field method)"
[ "$(field stable_for_all)" = True ] && [ "$(field hill_open)" = 0 ] && ok "1500..3000 g mm stable for all, $(field hill_boxes) boxes, none open" \
  || bad "1500..3000 g mm: stable_for_all $(field stable_for_all), open $(field hill_open)"
n_st=0
for k in $(seq 0 12); do
  s=$("$PY" -c "print(1.5e-3 + 1.5e-3 * $k / 12)")
  v=$(verdict_at "$s")
  [ "$v" = "stable:floquet" ] && n_st=$((n_st + 1)) || bad "ordinary run at $s kg m: $v"
done
[ $n_st -eq 13 ] && ok "13 ordinary Floquet runs across 1500..3000 g mm: all stable"

# (b)
every 6000 7000
su=$(field unstable_unbalance)
[ "$(field stable_for_all)" = False ] && [ "$su" != None ] && ok "6000..7000 g mm not stable: unstable member at $su kg m" || bad "6000..7000: $(cat e.json)"
[ "$(verdict_at "$su")" = "unstable:floquet" ] && ok "an ordinary run at $su kg m: unstable" || bad "ordinary run at $su kg m: $(verdict_at "$su")"
n_un=0
for k in $(seq 0 12); do
  s=$("$PY" -c "print(6e-3 + 1e-3 * $k / 12)")
  [ "$(verdict_at "$s")" = "unstable:floquet" ] && n_un=$((n_un + 1))
done
[ $n_un -ge 1 ] && ok "$n_un of 13 ordinary runs across 6000..7000 g mm unstable" || bad "no ordinary run unstable in 6000..7000 g mm"

# (c)
every 1500 3000 --set stability.hill_boxes=200
[ "$(field stable_for_all)" = False ] && [ "$(field hill_open)" != 0 ] && ok "budget 200 boxes: undecided ($(field hill_open) open), not 'stable'" \
  || bad "budget 200: stable_for_all $(field stable_for_all), open $(field hill_open)"
expect 0 "UNDECIDED" "$AUTOBAL" rotor stability "$ini" --set stability.unbalance_min="1500 g mm" \
  --set stability.unbalance_max="3000 g mm" --set stability.critical_speeds=false --set stability.hill_boxes=200

# (d)
expect 3 "hill_boxes" "$AUTOBAL" rotor stability "$ini" --set stability.unbalance_min="1500 g mm" \
  --set stability.unbalance_max="3000 g mm" --set stability.hill_boxes=10
sed -e 's/^ball_mass = .*/ball_mass = 0.05, 0.05, 0.05/' -e 's/^ball_radius = .*/ball_radius = 0.1, 0.1, 0.1/' \
  -e 's/^ball_damping = .*/ball_damping = 0.1, 0.1, 0.1/' -e 's/^ball_psi = .*/ball_psi = 0, 2, 4/' \
  -e 's/^ball_rate = .*/ball_rate = 0, 0, 0/' "$ini" > three.ini
"$AUTOBAL" rotor stability three.ini --set stability.unbalance_min="1500 g mm" --set stability.unbalance_max="3000 g mm" \
  --set stability.critical_speeds=false > three.txt 2>&1
rc=$?
[ $rc -ne 0 ] && grep -q "two balls" three.txt && ok "three balls, anisotropic: refused (exit $rc), naming what is supported" \
  || bad "three balls, anisotropic: exit $rc: $(cat three.txt)"
finish
