#!/usr/bin/env bash
# App test: `autobal rotor transient` with the exact stick-slip law and ball contact together
# (docs/device.md, "Stiction and contact"), as a user runs it:
#  (a) data/washer_contact.ini without its [ensemble] (ten 25 mm balls side by side at the bottom of a
#      horizontal drum, stiction, run-up 100 -> 1200 rpm, e = 0.5): the run
#      ends without failure; at every output sample no two neighbours on the track are closer than their
#      gap angle 2 asin(25 mm / (2 x 0.27 m)) (to 1e-9 rad); a ball flagged stuck at two consecutive
#      samples has not moved relative to the drum; every normal force is positive; impacts, sticks and
#      slips were counted; `autobal rerun` reproduces it bit for bit; with the default stepper (dop853,
#      output = dense6: samples on the continuous extension), dop853 with output = dense, and rk8pd;
#  (b) two balls of the default rotor, one thrown at 40 rad/s against the other (an impact on a stuck
#      ball sets it free), in the fixed and the rotating frame: the same counts, the same final angles
#      (1e-8 rad).
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
data=$(cd "$here/../../data" && pwd)

# (a) the washer with contact: its file without [ensemble]
sed '/^\[ensemble\]/,$d' "$data/washer_contact.ini" > washer.ini
expect 0 "contact:" "$AUTOBAL" rotor transient washer.ini -o washer.h5
grep -qF "friction (exact):" out.txt && ok "summary: the friction line" || bad "no friction line in the summary"
# dop853's outputs on the continuous extension showed balls overlapping by 1.8e-5 rad before 0.2.0's fix
# (impacts the step's ends missed, now also looked for at the output times,
# autobal_transient_set_event_output_probes); dop853 dense and rk8pd (the default before) too
expect 0 "contact:" "$AUTOBAL" rotor transient washer.ini --set transient.output=dense -o washer_dense.h5
expect 0 "contact:" "$AUTOBAL" rotor transient washer.ini --set transient.stepper=rk8pd -o washer_rk8pd.h5

for w in washer.h5 washer_dense.h5 washer_rk8pd.h5; do
echo "-- $w"
if "$PY" - $w <<'PY'
import sys, math
import h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
g = f["/rotor/transient"]
a = g.attrs
bad = 0
def chk(what, cond):
    global bad
    print(("ok   " if cond else "FAIL ") + what)
    bad += 0 if cond else 1
gam = 2 * math.asin(0.025 / (2 * 0.27))
psi = np.array([g["p1_b%d_psi" % (i + 1)][:] for i in range(10)])        # relative to the drum
stuck = np.array([g["p1_b%d_stuck" % (i + 1)][:] for i in range(10)])
N = np.array([g["p1_b%d_N" % (i + 1)][:] for i in range(10)])
w = np.sort(np.mod(psi, 2 * math.pi), axis=0)
gaps = np.diff(np.vstack([w, w[:1] + 2 * math.pi]), axis=0) - gam
chk("no overlap at %d samples: smallest gap beyond the gap angle %.3e rad (>= -1e-9)" % (psi.shape[1], gaps.min()), gaps.min() >= -1e-9)
both = (stuck[:, 1:] == 1) & (stuck[:, :-1] == 1)
moved = np.abs(np.diff(psi, axis=1))[both]
chk("a ball stuck at two consecutive samples has not moved relative to the drum (largest change %.2e rad, %d pairs of samples)" % (moved.max(), moved.size), moved.size > 0 and moved.max() < 1e-9)
chk("every normal force positive (smallest %.4g N)" % N.min(), N.min() > 0)
chk("impacts %d, sticks %d, slips %d all > 0" % (a["contact_impacts"], a["friction_sticks"], a["friction_slips"]),
    a["contact_impacts"] > 0 and a["friction_sticks"] > 0 and a["friction_slips"] > 0)
chk("friction = exact, contact_restitution = 0.5", a["friction"] in (b"exact", "exact") and float(a["contact_restitution"]) == 0.5)
sys.exit(1 if bad else 0)
PY
then ok "washer archive read back ($w)"; else bad "washer archive checks ($w)"; fi
done

expect 0 "" "$AUTOBAL" rerun washer.h5 -o washer_rerun.h5 -q
if "$PY" "$here/drive_check.py" same washer.h5 washer_rerun.h5; then ok "rerun of the washer run, bit for bit"; else bad "rerun differs"; fi

# (b) an impact on a stuck ball, both frames
for frame in fixed rotating; do
cat > throw_$frame.ini <<INI
[plane1]
ball_psi = 1.0, 1.3
ball_rate = 40, 0
ball_diameter = 20 mm
ball_f = 0.01
ball_mu = 0.02
[friction]
law = exact
[contact]
restitution = 0.5
[transient]
t_end = 2 s
frame = $frame
INI
expect 0 "1 impact(s)" "$AUTOBAL" rotor transient throw_$frame.ini -o throw_$frame.h5
done
if "$PY" - throw_fixed.h5 throw_rotating.h5 <<'PY'
import sys, math
import h5py, numpy as np
A = [h5py.File(p, "r")["/rotor/transient"] for p in sys.argv[1:]]
bad = 0
keys = ["contact_impacts", "friction_sticks", "friction_slips", "friction_reversals"]
same = all(int(A[0].attrs[k]) == int(A[1].attrs[k]) for k in keys)
print(("ok   " if same else "FAIL ") + "the same counts in both frames: " + ", ".join("%s %d/%d" % (k, A[0].attrs[k], A[1].attrs[k]) for k in keys))
bad += 0 if same else 1
d = max(abs(math.remainder(A[0]["p1_b%d_psi" % i][-1] - A[1]["p1_b%d_psi" % i][-1], 2 * math.pi)) for i in (1, 2))
print(("ok   " if d < 1e-8 else "FAIL ") + "the same final angles in both frames (difference %.2e rad, 1e-8)" % d)
bad += 0 if d < 1e-8 else 1
sys.exit(1 if bad else 0)
PY
then ok "both frames agree"; else bad "frames differ"; fi

finish
