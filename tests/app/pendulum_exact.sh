#!/usr/bin/env bash
# App test (issue 18 items 1, 2, 5): `autobal pendulum critical --json` and the undamped `autobal pendulum map`
# near R_m -> 1/4 (critical speeds up to ~1e4) and at the narrow stable island of k = 0.9999 near R_m = 0.0448,
# against an independent reference computed here (pendulum_crit_ref.py: SymPy's exact root isolation of the
# discriminant of (10), 80-digit verdicts); the JSON's kinds and closed forms; the archive's flags.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
"$PY" "$here/pendulum_exact_check.py" "$AUTOBAL" "$SCRATCH" > check.txt 2>&1; rc=$?
cat check.txt
[ $rc -eq 0 ] && ok "critical speeds and map rows agree with the exact reference" || bad "pendulum_exact_check.py (exit $rc)"
# the reference script itself, on a case with a known closed form: k = 1, R_m = 0.3 has the touch (18) at sqrt(20)
"$PY" "$here/pendulum_crit_ref.py" 0.3 1 > ref.txt
"$PY" -c "import json,sys; d=json.loads(open('ref.txt').read()); sys.exit(0 if d['kind']==[1,0] and abs(float(d['R_w'][1])-20**0.5)<1e-15 else 1)" \
  && ok "reference: k = 1, R_m = 0.3 touch at sqrt(20) = (18)" || bad "reference self-check"
finish
