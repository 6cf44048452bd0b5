#!/usr/bin/env bash
# rotor design on ANISOTROPIC supports (data/design_anisotropic.ini, grids made smaller here; docs/rotor.md
# "Design", "Anisotropic supports"):
#  (a) the JSON summary says anisotropic; the best design is feasible and certified by Hill's method at
#      every re-check speed; its config (config_out), run by ordinary `rotor stability` (Floquet, no Hill
#      matrix) at 3 speeds x 7 unbalances across the range, is stable with margin < -[design] margin;
#      the console names the verdict ("CERTIFIED") and says the screen is sampled;
#  (b) a speed range below the critical speeds (100..200 rad/s): no design passes, and the output says so;
#  (c) bad input: three balls (n_balls_max = 3) on anisotropic supports, exit 3 naming n_balls_max;
#      hill_boxes out of range (exit 3); a budget too small (hill_boxes = 100): UNDECIDED, not feasible.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

ini="$DATA/design_anisotropic.ini"
small=(--set design.n_speed=3 --set design.n_ball_mass=2 --set design.n_track_radius=2 --set design.n_ball_damping=2
       --set design.n_best=2)

# (a)
"$AUTOBAL" rotor design "$ini" "${small[@]}" --set design.config_out=best.ini --json > d.json 2>err.txt \
  || { bad "design: exit $?"; cat err.txt; }
"$PY" - <<'PYEOF' > chk.txt 2>&1 && ok "JSON: anisotropic, best design certified ($(cat chk.txt))" || { bad "JSON: $(cat chk.txt)"; }
import json
d = json.load(open("d.json"))
assert d["anisotropic"] is True, "anisotropic flag"
b = d["designs"][0]
assert b["feasible"] is True and b["verdict"] == "certified" and b["hill_certified"] == 1, b
assert b["hill_speeds"] == d["n_verify"] and b["hill_speeds_undecided"] == 0, b
for x in d["designs"]:
    assert x["feasible"] == (x["hill_certified"] == 1), x
print("rho_s %.4g 1/s, %d speeds, %d boxes" % (b["robust_margin"], b["hill_speeds"], b["hill_boxes"]))
PYEOF
margin=$(grep -E '^margin *=' "$ini" | sed 's/^margin *= *\([0-9.]*\).*/\1/')
[ -s best.ini ] && ok "config_out written" || bad "no best.ini"
n_ok=0
for w in 471.24 700 942.48; do
  for k in 0 1 2 3 4 5 6; do
    m0=$("$PY" -c "print((1.5e-3 + 2.5e-3 * $k / 6) / 0.1)") # r0 = 0.1 m
    r=$("$AUTOBAL" rotor stability best.ini --set rotor.omega="$w" --set plane1.m0="$m0" \
        --set stability.critical_speeds=false --json 2>/dev/null |
        "$PY" -c "import json,sys; d = json.load(sys.stdin); print('ok' if d['method'] == 'floquet' and d['verdict'] == 'stable' and d['margin'] < -$margin else d['verdict'] + ' ' + str(d['margin']))")
    [ "$r" = ok ] && n_ok=$((n_ok + 1)) || bad "best design at $w rad/s, m0 $m0 kg: $r"
  done
done
[ "$n_ok" -eq 21 ] && ok "best design: 21 ordinary Floquet runs stable with margin < -$margin"
expect 0 "CERTIFIED" "$AUTOBAL" rotor design "$ini" "${small[@]}"
grep -q "SAMPLED" out.txt && ok "the console says the screen is sampled" || bad "no 'SAMPLED' in the console output"
grep -q "anisotropic supports" err.txt && ok "a note on the cost before the run" || bad "no note on stderr"

# (b)
expect 0 "none: no design in the bounds passes the screen" "$AUTOBAL" rotor design "$ini" "${small[@]}" \
  --set design.speed_min="100 rad/s" --set design.speed_max="200 rad/s"

# (c)
expect 3 "n_balls_max" "$AUTOBAL" rotor design "$ini" "${small[@]}" --set design.n_balls_max=3
expect 3 "hill_boxes" "$AUTOBAL" rotor design "$ini" "${small[@]}" --set design.hill_boxes=10
expect 0 "UNDECIDED" "$AUTOBAL" rotor design "$ini" "${small[@]}" --set design.hill_boxes=100
finish
