#!/usr/bin/env bash
# App test: `autobal rotor transient` with ball size and contact ([plane1] ball_diameter, [contact]
# restitution), as a user runs it: two 23 mm balls whose balanced separation (0.1795 rad for the
# unbalance 0.00996 kg m) is below their gap angle (0.2305 rad) are pressed together, bounce and come
# to resting contact.  Read back: the contact attributes, no overlap at any sample (both gaps >= 0 to
# 1e-9 rad), the final separation = the gap angle, the capacity 2 m r cos(gamma/2) and "out of reach";
# the rotating frame ends at the same angles; `autobal rerun` reproduces the run bit for bit.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

for frame in fixed rotating; do
cat > rest_$frame.ini <<INI
[plane1]
m0 = 0.0996 kg
ball_psi = 2.5, 3.5
ball_diameter = 23 mm
[contact]
restitution = 0.5
[transient]
t_end = 5 s
frame = $frame
dt_out = 1 ms
INI
expect 0 "1 touching at the end" "$AUTOBAL" rotor transient rest_$frame.ini -o rest_$frame.h5
done
grep -qF "out of reach" out.txt && ok "summary: the balanced angles are out of reach" || bad "no 'out of reach' line"

if "$PY" - rest_fixed.h5 rest_rotating.h5 <<'PY'
import sys, math
import h5py, numpy as np
gam = 2 * math.asin(0.046 / 0.4)
fin = []
bad = 0
for path in sys.argv[1:]:
    f = h5py.File(path, "r")
    g = f["/rotor/transient"]
    a = g.attrs
    def chk(what, cond):
        global bad
        print(("ok   " if cond else "FAIL ") + path + ": " + what)
        bad += 0 if cond else 1
    chk("contact_impacts %d > 0, contact_joins %d > 0" % (a["contact_impacts"], a["contact_joins"]),
        a["contact_impacts"] > 0 and a["contact_joins"] > 0)
    chk("contacts_final = 1", a["contacts_final"] == 1)
    chk("contact_reachable = [0]", list(np.atleast_1d(a["contact_reachable"])) == [0])
    cap = float(np.atleast_1d(a["contact_capacity"])[0])
    chk("contact_capacity %.12g = 2 m r cos(gamma/2)" % cap, abs(cap - 0.01 * math.cos(gam / 2)) < 1e-15)
    chk("contact_restitution = 0.5", float(a["contact_restitution"]) == 0.5)
    chk("ball_diameter of /rotor/plane1 = 0.023 m", list(np.atleast_1d(f["/rotor/plane1"].attrs["ball_diameter"])) == [0.023, 0.023])
    p1, p2 = g["p1_b1_psi"][:], g["p1_b2_psi"][:]
    g12 = p2 - p1 - gam                  # ball 1 behind ball 2 (initially 1 rad apart)
    g21 = p1 + 2 * math.pi - p2 - gam    # ball 2 behind ball 1, round the track
    chk("no overlap at %d samples: min gaps %.3e, %.3e rad >= -1e-9" % (len(p1), g12.min(), g21.min()),
        g12.min() >= -1e-9 and g21.min() >= -1e-9)
    sep = min(g12[-1], g21[-1]) + gam
    chk("final separation %.12f = gap angle %.12f (1e-8)" % (sep, gam), abs(sep - gam) < 1e-8)
    fin.append((math.remainder(p1[-1], 2 * math.pi), math.remainder(p2[-1], 2 * math.pi)))
d = max(abs(fin[0][0] - fin[1][0]), abs(fin[0][1] - fin[1][1]))
# the frames take different bounce sequences (other rounding at the events) to the same resting
# position, still approached at 5 s: the same angles to 1e-5 rad
print(("ok   " if d < 1e-5 else "FAIL ") + "both frames end at the same angles (difference %.2e rad, 1e-5)" % d)
bad += 0 if d < 1e-5 else 1
sys.exit(1 if bad else 0)
PY
then ok "archives read back"; else bad "archive checks"; fi

expect 0 "" "$AUTOBAL" rerun rest_fixed.h5 -o rest_rerun.h5 -q
if "$PY" "$here/drive_check.py" same rest_fixed.h5 rest_rerun.h5; then ok "rerun of the contact run, bit for bit"; else bad "rerun differs"; fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
