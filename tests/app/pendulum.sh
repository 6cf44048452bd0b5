#!/usr/bin/env bash
# App test: `autobal pendulum roots|critical|map` run as a user would, archives read back and
# checked against NumPy/SciPy recomputations (pendulum_check.py), and bad input provoked.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
# expect CODE "needle" -- command...

expect 0 "main motion (4)" "$AUTOBAL" pendulum roots
expect 0 "" "$AUTOBAL" pendulum roots "$DATA/pendulum_default.ini" -o roots.h5
"$PY" "$here/pendulum_check.py" roots roots.h5 && ok "roots archive checks" || bad "roots archive checks"
expect 0 "" "$AUTOBAL" pendulum roots "$DATA/pendulum_physical.ini" -o phys.h5
"$PY" "$here/pendulum_check.py" roots phys.h5 && ok "physical roots archive checks" || bad "physical roots archive checks"
expect 0 "" "$AUTOBAL" pendulum critical "$DATA/pendulum_critical_k1.ini" -o crit.h5
"$PY" "$here/pendulum_check.py" critical crit.h5 && ok "critical archive checks (k = 1)" || bad "critical archive checks"
expect 0 "" "$AUTOBAL" pendulum critical --set pendulum.k=0.7 --set pendulum.R_m=0.05 --set critical.n_Rm=99 -o crit2.h5
"$PY" "$here/pendulum_check.py" critical crit2.h5 && ok "critical archive checks (k = 0.7)" || bad "critical archive checks (k = 0.7)"
# damped critical speeds (the regime of (9): H >> 1): every list carries its truncation flag (0 here)
expect 0 "damped critical speeds" "$AUTOBAL" pendulum critical --set pendulum.R_m=0.1 --set pendulum.k=1 --set pendulum.H=100 --set pendulum.h=1 --set critical.Rw_min=0.05 --set critical.Rw_max=5 --set critical.n_sweep=400 --set critical.n_Rm=49 -o critd.h5
grep -q "TRUNCATED" out.txt err.txt && bad "damped critical speeds reported as truncated" || ok "no truncation reported (few changes)"
"$PY" "$here/pendulum_check.py" critical critd.h5 && ok "damped critical archive checks (flags, sign changes of (6))" || bad "damped critical archive checks"
expect 0 "" "$AUTOBAL" pendulum critical --set pendulum.R_m=0.1 --set pendulum.k=1 --set pendulum.H=100 --set pendulum.h=1 --set critical.Rw_min=0.05 --set critical.Rw_max=5 --set critical.n_sweep=400 --set critical.n_Rm=49 --json
"$PY" -c "import json,sys; d=json.load(open('out.txt')); sys.exit(0 if d['damped_truncated'] is False and len(d['damped_critical_R_w']) == 2 else 1)" \
  && ok "--json: damped_truncated = false, two damped critical speeds" || bad "--json damped_truncated"
expect 0 "" "$AUTOBAL" pendulum map "$DATA/pendulum_map_every.ini" -o map.h5
"$PY" "$here/pendulum_check.py" map map.h5 && ok "every-unbalance map checks" || bad "every-unbalance map checks"
expect 0 "" "$AUTOBAL" pendulum map --set map.n_Rm=40 --set map.n_Rw=50 -o mapd.h5
"$PY" "$here/pendulum_check.py" map mapd.h5 && ok "damped map checks" || bad "damped map checks"
expect 0 "" "$AUTOBAL" pendulum roots --json
"$PY" -c "import json,sys; d=json.load(open('out.txt')); sys.exit(0 if d['verdict'] in ('stable','unstable','marginal') and len(d['root_real'])==8 else 1)" \
  && ok "--json is valid JSON with 8 roots" || bad "--json output"

# bad input: each names the parameter and exits with the documented code
expect 3 "'pendulum.R_m'" "$AUTOBAL" pendulum roots --set pendulum.Rm=0.2
expect 3 "R_m" "$AUTOBAL" pendulum roots --set pendulum.R_m=0.5
expect 3 "(0, 0.5)" "$AUTOBAL" pendulum roots --set pendulum.R_m=-1
expect 3 "not a finite number" "$AUTOBAL" pendulum roots --set pendulum.H=nan
expect 3 "not a number" "$AUTOBAL" pendulum roots --set pendulum.h=abc
expect 3 "k" "$AUTOBAL" pendulum roots --set pendulum.k=1.5
expect 3 "unknown section" "$AUTOBAL" pendulum roots --set rotorr.x=1
printf '[pendulum]\nR_m = 0.1\nthis line is broken\n' > broken.ini
expect 3 "line 3" "$AUTOBAL" pendulum roots broken.ini
printf '[pendulum]\nR_m = 0.1\nR_m = 0.2\n' > dup.ini
expect 3 "more than once" "$AUTOBAL" pendulum roots dup.ini
expect 3 "cannot read config" "$AUTOBAL" pendulum roots does-not-exist.ini
sed 's/^e = .*/e = 0.01/' "$DATA/pendulum_physical.ini" > unbal.ini   # M e = 0.1 >= 2 m l = 0.03
expect 3 "M*e" "$AUTOBAL" pendulum roots unbal.ini
expect 4 "no-such-dir" "$AUTOBAL" pendulum roots -o no-such-dir/x.h5
before=$(md5sum roots.h5)
expect 4 "--force" "$AUTOBAL" pendulum roots -o roots.h5
[ "$before" = "$(md5sum roots.h5)" ] && ok "existing archive untouched" || bad "existing archive was modified"
expect 0 "" "$AUTOBAL" pendulum roots -o roots.h5 --force
ls | grep -q partial && bad "temporary files left behind: $(ls | grep partial)" || ok "no temporary files left"
expect 2 "unknown option" "$AUTOBAL" pendulum roots --frobnicate
expect 2 "did you mean 'roots'" "$AUTOBAL" pendulum rootz
expect 0 "" "$AUTOBAL" --help
expect 0 "R_m" "$AUTOBAL" pendulum map --help

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
