#!/usr/bin/env bash
# App test: the run-up outputs of `autobal rotor transient` with a prescribed speed (/rotor/runup,
# docs/device.md "Run-up outputs"), as a user runs it: a ramp through the default rotor's
# resonances and a table with a dwell near the first one; runup_check.py compares the archive with
# the Campbell crossings computed by NumPy from the lumped equations, the closed-form crossing times
# of the prescribed profile, a brute-force envelope and the psi and s_rel columns; `autobal plot`
# draws the run-up picture; the constant drive writes no /rotor/runup; bad options exit 3.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
check() { local what=$1; shift; if "$PY" "$here/runup_check.py" "$@"; then ok "$what"; else bad "$what"; fi; }

# (a) a run-up 0 -> 500 rad/s over 20 s, 10 s at speed (unequal ball damping: the balls balance)
cat > ramp.ini <<'INI'
[plane1]
ball_damping = 1.0, 1.3
[drive]
mode = ramp
omega_a = 0
omega_b = 500
t_a = 0
t_b = 20
[transient]
t_end = 30
INI
expect 0 "run-up: 4 passage(s)" "$AUTOBAL" rotor transient ramp.ini -o ramp.h5
grep -F "run-up:" out.txt
check "(a) ramp: resonances, passages, envelope, lag, time to balance" ramp.h5 capture 0
# the --json summary carries the same passages as the archive
expect 0 "" "$AUTOBAL" rotor transient ramp.ini --json -o ramp_json.h5
if "$PY" -c "
import json, h5py, numpy as np
d = json.load(open('out.txt'))['runup']
g = h5py.File('ramp_json.h5', 'r')['rotor/runup']
assert np.array_equal(d['passage_time'], g['passage_time'][:]) and len(d['resonance_speed']) == 4
assert d['units']['passage_time'] == 's'"; then ok "--json: runup.passage_time = the archive's"; else bad "--json runup"; fi
# (b) a table with a dwell at 160 rad/s (within 5% of the first two resonances) for 5 s, then up
# to 300 rad/s and a fast coast-down to 120 rad/s: passages up and down, two captures
cat > dwell.ini <<'INI'
[drive]
mode = table
table_t = 0, 4, 9, 12, 14
table_omega = 0, 160, 160, 300, 120
[transient]
t_end = 16
INI
expect 0 "CAPTURED" "$AUTOBAL" rotor transient dwell.ini -o dwell.h5
check "(b) table with a dwell: passages up and down, captures" dwell.h5 capture 2
# the same with a longer capture_time than the dwell: no capture (a check that can fail)
expect 0 "no capture" "$AUTOBAL" rotor transient dwell.ini --set transient.capture_time=6 -o dwell6.h5
check "(b) capture_time 6 s > the dwell: no capture" dwell6.h5 capture 0
# (c) the run-up picture
expect 0 "ramp_runup.png" "$AUTOBAL" plot ramp.h5 -o pics
if [ -s pics/ramp_runup.png ] && [ "$(head -c 8 pics/ramp_runup.png | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] &&
   [ "$(stat -c %s pics/ramp_runup.png)" -gt 20000 ]; then ok "(c) pics/ramp_runup.png is a PNG ($(stat -c %s pics/ramp_runup.png) bytes)"
else bad "(c) pics/ramp_runup.png missing or not a PNG"; fi
# (d) the constant drive keeps its layout: no /rotor/runup
expect 0 "" "$AUTOBAL" rotor transient --set transient.t_end=0.2 -o const.h5
if "$PY" -c "import h5py,sys; sys.exit('rotor/runup' in h5py.File('const.h5','r'))"; then ok "(d) constant drive: no /rotor/runup"
else bad "(d) constant drive wrote /rotor/runup"; fi
if grep -q "run-up" out.txt; then bad "(d) constant drive printed run-up lines"; else ok "(d) no run-up lines for the constant drive"; fi
# (e) bad options: exit 3 naming the key, no archive
expect 3 "capture_band" "$AUTOBAL" rotor transient ramp.ini --set transient.capture_band=0 -o x.h5
expect 3 "capture_band" "$AUTOBAL" rotor transient ramp.ini --set transient.capture_band=1.5 -o x.h5
expect 3 "capture_time" "$AUTOBAL" rotor transient ramp.ini --set transient.capture_time=0 -o x.h5
expect 3 "capture_time" "$AUTOBAL" rotor transient ramp.ini --set "transient.capture_time=3 m" -o x.h5
[ -e x.h5 ] && bad "bad input left an archive x.h5" || ok "bad input left no archive"

echo "$pass passed, $fail failed"
exit $((fail > 0))
