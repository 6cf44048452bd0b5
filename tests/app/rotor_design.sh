#!/usr/bin/env bash
# rotor design (docs/rotor.md "Design"): a small search on the default machine, in the units users
# think in (rpm, g mm, g, mm), then rotor_design_check.py re-checks it independently (NumPy roots of
# Delta built from the hardware values; transients of the best design and of an infeasible one):
#  (a) the run: exit 0, the ranked table, the best design printed and written (config_out), the
#      written .ini runs as it is (`rotor stability` finds it stable at speed_max);
#  (b) the archive and the independent checks (rotor_design_check.py); data/design_default.ini as
#      shipped: its best design feasible, re-checked, and its config stable;
#  (c) bad input: each range error names its key and exits 3 with nothing written; two planes and
#      three balls are refused naming the key; SIGINT: exit 6, the archive incomplete with the map rows
#      done.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

cat > d.ini <<'INI'
[design]
speed_min = 4500 rpm
speed_max = 8500 rpm
n_speed = 9
unbalance_min = 500 g mm
unbalance_max = 4000 g mm
margin = 0.2
ball_mass_min = 25 g
ball_mass_max = 80 g
n_ball_mass = 4
track_radius_min = 60 mm
track_radius_max = 140 mm
n_track_radius = 5
ball_damping_min = 0.02
ball_damping_max = 1
n_ball_damping = 4
n_best = 3
n_starts = 1
max_iter = 25
INI
expect 0 "best design as a config" "$AUTOBAL" rotor design d.ini -o d.h5 --set design.config_out=best.ini
grep -q "ranked designs" out.txt && ok "ranked table printed" || bad "no ranked table"
grep -q "stability analyses (" out.txt && ok "count of stability analyses printed: $(grep -o "[0-9]* stability analyses ([0-9]* per second[^)]*)" out.txt)" || bad "no analysis count"
[ -s best.ini ] && ok "best.ini written" || bad "best.ini missing"
grep -q "^ball_mass = " out.txt && ok "the config is printed" || bad "config not printed"
expect 0 "BALANCED MOTION: stable" "$AUTOBAL" rotor stability best.ini --set stability.critical_speeds=false

"$PY" "$here/rotor_design_check.py" d.h5 best.ini "$AUTOBAL" > check.txt 2>&1 && ok "rotor_design_check.py: $(grep -c '^ok' check.txt) checks" || { bad "rotor_design_check.py"; cat check.txt; }
grep '^ok\|^FAIL' check.txt | head -40

# data/design_default.ini as shipped (the 3-parameter search of docs/rotor.md "Design"): the best design
# feasible and re-checked, at least one feasible map point, the archive's best_config runs
expect 0 "best design as a config" "$AUTOBAL" rotor design "$DATA/design_default.ini" -o full.h5
"$PY" - <<'PY' && ok "data/design_default.ini: best design feasible and re-checked, ranked by robust margin" || bad "data/design_default.ini archive"
import h5py
g = h5py.File("full.h5", "r")["/rotor/design"]
r = g["ranked"]
assert r["feasible"][0] == 1 and r["recheck"][0] == 1, (r["feasible"][:], r["recheck"][:])
assert r["robust_margin"][0] > g.attrs["margin_required"]
assert g.attrs["n_feasible"] == (g["feasible"][:] == 1).sum() > 0
open("full_best.ini", "w").write(g.attrs["best_config"])
PY
expect 0 "BALANCED MOTION: stable" "$AUTOBAL" rotor stability full_best.ini --set stability.critical_speeds=false

# transients of the best designs (default n_transient = 5, here the 3 ranked): P(balance), median and
# worst time to balance per design with units; rank_by = time orders the designs by their own numbers
"$PY" - <<'PY' && ok "d.h5: transients of the ranked designs archived with units, P in [0, 1], median <= worst" || bad "d.h5 transients"
import h5py, numpy as np
g = h5py.File("d.h5", "r")["/rotor/design"]
r = g["ranked"]
assert g.attrs["rank_by"] == "margin" and g.attrs["n_transient"] == 5, dict(g.attrs)
assert r["p_balance"].attrs["units"] == "1" and r["time_to_balance_worst"].attrs["units"] == "s"
assert r["time_to_balance_median"].attrs["units"] == "s"
n = r["transient_members"][:]
assert (n == 3 * 3 * 2 * 2).all(), n                  # 3 x 3 starts x 2 unbalances x 2 speeds
assert g.attrs["transients"] == n.sum()
p = r["p_balance"][:]
assert np.allclose(p, r["transient_balanced"][:] / n)
med, worst = r["time_to_balance_median"][:], r["time_to_balance_worst"][:]
assert (med <= worst).all() and (np.isinf(worst) == (p < 1)).all(), (med, worst, p)
assert (np.diff(r["robust_margin"][:]) <= 0).all() or r["feasible"][0] == 1  # margin order (best feasible first)
PY
expect 0 "ranked by time" "$AUTOBAL" rotor design d.ini -o dt.h5 --set design.rank_by=time
"$PY" - <<'PY' && ok "rank_by = time: ordered by (feasible, worst, median time to balance) as archived" || bad "dt.h5 order"
import h5py, numpy as np
r = h5py.File("dt.h5", "r")["/rotor/design/ranked"]
key = list(zip(-r["feasible"][:], r["time_to_balance_worst"][:], r["time_to_balance_median"][:], -r["p_balance"][:]))
assert key == sorted(key), key
PY

# a run-up profile ([drive] ramp 0 -> 8500 rpm in 4 s): the operating range is [balance_from, top speed],
# the transients run the profile from rest (time to balance not before its end), the best config carries it
{ printf '[drive]\nmode = ramp\nomega_a = 0\nomega_b = 8500 rpm\nt_a = 0 s\nt_b = 4 s\n'; grep -v '^speed_m' d.ini; printf 'balance_from = 4500 rpm\nn_transient = 2\n'; } > ru.ini
expect 0 "run-up profile from rest" "$AUTOBAL" rotor design ru.ini -o ru.h5 --set design.config_out=rubest.ini
"$PY" - <<'PY' && ok "run-up: speed range [balance_from, top speed], 18 members per design, time to balance after the ramp" || bad "ru.h5"
import h5py, numpy as np
g = h5py.File("ru.h5", "r")["/rotor/design"]
r = g["ranked"]
rpm = 2 * np.pi / 60
assert abs(g.attrs["omega_min"] - 4500 * rpm) < 1e-9 and abs(g.attrs["omega_max"] - 8500 * rpm) < 1e-9, dict(g.attrs)
assert g.attrs["transient_n_speeds"] == 0 and g.attrs["transient_t_end"] == 14.0
n = r["transient_members"][:]
assert (n[:2] == 3 * 3 * 2).all() and (n[2:] == 0).all(), n   # no speed axis: the profile
t = r["time_to_balance_median"][:2]
assert (t[np.isfinite(t)] >= 4.0).all(), t
PY
grep -q '^mode = ramp' rubest.ini && ok "the best config carries the run-up profile" || bad "no [drive] in rubest.ini"
expect_err 3 "disagrees with the run-up profile" "$AUTOBAL" rotor design ru.ini --set design.speed_max=9000rpm
expect_err 3 "balance_from" "$AUTOBAL" rotor design ru.ini --set design.speed_min=4000rpm
expect_err 3 "balance_from needs a run-up profile" "$AUTOBAL" rotor design d.ini --set design.balance_from=4000rpm
expect_err 3 "transient_t_end" "$AUTOBAL" rotor design ru.ini --set design.transient_t_end=3
{ printf '[drive]\nmode = motor\nomega_0 = 1000\nJ = 0.05\nL_0 = 5\n'; cat d.ini; } > mo.ini
expect_err 3 "mode = motor is not supported" "$AUTOBAL" rotor design mo.ini

# (c) bad input
expect_err 3 "rank_by" "$AUTOBAL" rotor design d.ini --set design.rank_by=speed
expect_err 3 "n_transient" "$AUTOBAL" rotor design d.ini --set design.rank_by=p_balance --set design.n_transient=0
expect_err 3 "n_start_angles" "$AUTOBAL" rotor design d.ini --set design.n_start_angles=0
expect_err 3 "speed_max" "$AUTOBAL" rotor design d.ini --set design.speed_max=4000rpm -o bad1.h5
[ ! -e bad1.h5 ] && ok "nothing written" || bad "bad1.h5 written"
expect_err 3 "unbalance_max" "$AUTOBAL" rotor design d.ini --set "design.unbalance_max=100 g mm" -o bad2.h5
expect_err 3 "n_speed" "$AUTOBAL" rotor design d.ini --set design.n_speed=1
expect_err 3 "ball_mass_max" "$AUTOBAL" rotor design d.ini --set "design.ball_mass_max=10 g"
grep -v '^ball_mass_max' d.ini > onlymin.ini
expect_err 3 "ball_mass_min and ball_mass_max go together" "$AUTOBAL" rotor design onlymin.ini
printf '[design]\nspeed_min = 400\nspeed_max = 800\n' > nou.ini
expect_err 3 "unbalance_min and unbalance_max are required" "$AUTOBAL" rotor design nou.ini
printf '[plane1]\nball_mass = 0.05, 0.05, 0.05\nball_radius = 0.1, 0.1, 0.1\nball_damping = 0.1, 0.1, 0.1\nball_psi = 0, 2, 4\nball_rate = 0, 0, 0\n' > three.ini
cat d.ini >> three.ini
expect_err 3 "ball_mass" "$AUTOBAL" rotor design three.ini
grep -q "n_balls_max" err.txt && ok "three balls outside n_balls 2..2: names n_balls_max" || bad "three balls message: $(cat err.txt)"
printf '[plane2]\nd = -0.12\nm0 = 0.015\nr0 = 0.09\nball_mass = 0.04, 0.04\nball_radius = 0.09, 0.09\nball_damping = 0.5, 0.5\nball_psi = 1, 2\n' > two.ini
cat d.ini >> two.ini
expect_err 3 "plane2" "$AUTOBAL" rotor design two.ini

# SIGINT during a long search: exit 6, the archive incomplete, the map rows done
"$AUTOBAL" rotor design d.ini --set design.n_ball_mass=200 --set design.n_ball_damping=40 --set design.n_speed=400 -o int.h5 > int.out 2> int.err &
pid=$!
caught $pid INT
sleep "$([ "${SANITIZE:-0}" = 1 ] && echo 8 || echo 3)"   # the first map row takes longer under ASan
kill -INT $pid
wait $pid; rc=$?
[ $rc -eq 6 ] && ok "SIGINT: exit 6" || { bad "SIGINT: exit $rc"; cat int.err; }
if [ -e int.h5 ]; then
  "$PY" - <<'PY' && ok "int.h5: status incomplete, the map rows done (if any) marked partial" || bad "int.h5"
import h5py
f = h5py.File("int.h5", "r")
assert f.attrs["status"] == "incomplete", f.attrs["status"]
assert f.attrs["status_reason"] == "interrupted by SIGINT", f.attrs["status_reason"]
if "/rotor/design" in f:  # rows done: they are there, marked partial
    g = f["/rotor/design"]
    assert g.attrs["partial"] == 1 and 0 < g.attrs["done"] < g.attrs["requested"] == 200, dict(g.attrs)
    assert g["feasible"].shape[0] == g.attrs["done"]
else:  # interrupted inside the first row: the model and provenance only
    assert "/rotor" in f, list(f)
    print("interrupted before the first map row: no /rotor/design")
PY
else
  grep -q "nothing written\|interrupted\|SIGINT" int.err && ok "SIGINT before the first row: nothing written, said so" || bad "no int.h5 and no message"
fi
finish
