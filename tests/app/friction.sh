#!/usr/bin/env bash
# App test: `autobal rotor transient` with rolling resistance and stiction of the balls ([friction]
# law = exact | regularized, [plane1] ball_f, ball_mu), as a user runs it: the friction attributes,
# the output columns p<j>_b<i>_stuck and p<j>_b<i>_N and the summary's switch counts and stuck times
# read back and checked for consistency (friction_check.py); without friction the archive has no
# friction column; `autobal rerun` reproduces an exact-law run bit for bit; bad input exits 3 naming
# the key and the allowed range, leaving no file.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
check() { local what=$1; shift; if "$PY" "$here/friction_check.py" "$@"; then ok "$what"; else bad "$what"; fi; }

# the balls start lagging the rotor, slow down by rolling resistance, stick, break free, stick again
cat > exact.ini <<'INI'
[rotor]
omega = 300 rad/s
[plane1]
ball_rate = -20, -10
ball_f = 0.01
ball_mu = 0.02
[friction]
law = exact
[transient]
t_end = 2 s
frame = rotating
dt_out = 1 ms
INI
expect 0 "friction (exact): 4 stick(s), 2 slip(s)" "$AUTOBAL" rotor transient exact.ini -o exact.h5
check "exact law: attributes, stuck/N columns, stuck samples do not move, stuck times = sampled times" exact exact.h5
expect 0 '"friction_sticks":4' "$AUTOBAL" rotor transient exact.ini --json -q -o exact_json.h5
expect 0 "" "$AUTOBAL" rerun exact.h5 -o exact_rerun.h5 -q
if "$PY" "$here/drive_check.py" same exact.h5 exact_rerun.h5; then ok "rerun of the exact-law run, bit for bit"; else bad "rerun differs"; fi

# two planes (data/rotor_two_planes.ini), per-ball mu: fixed and rotating frames switch alike
cat "$DATA/rotor_two_planes.ini" > two.ini
printf '\n[friction]\nlaw = exact\n[plane1]\nball_f = 0.005\nball_mu = 0.01, 0.02\n[plane2]\nball_f = 0.003\n' >> two.ini
expect 0 "friction (exact): 3 stick(s), 1 slip(s)" "$AUTOBAL" rotor transient two.ini --set transient.t_end=1 -o two.h5
expect 0 "" "$AUTOBAL" rotor transient two.ini --set transient.t_end=1 --set transient.frame=rotating -o two_rot.h5
check "two planes: fixed frame == rotating frame (switches, motion, N, stuck times)" frames two.h5 two_rot.h5

# the regularized law: no modes (stuck columns 0), its attributes
cat > reg.ini <<'INI'
[rotor]
omega = 300 rad/s
[plane1]
ball_rate = -20, -10
ball_f = 0.01
[friction]
law = regularized
u_eps = 0.01 rad/s
[transient]
t_end = 0.5 s
INI
expect 0 "" "$AUTOBAL" rotor transient reg.ini -o reg.h5
check "regularized law: attributes, columns, no stuck flag" regularized reg.h5

# without friction: the layout of before (no friction column or attribute)
printf '[transient]\nt_end = 0.2\n' > none.ini
expect 0 "" "$AUTOBAL" rotor transient none.ini -o none.h5
check "no friction: no friction column, no friction attribute" none none.h5

# bad input: exit 3, the key and the allowed range named, no file left
f() { printf "$1" > "$2"; }
f '[plane1]\nball_f = 0.03\nball_mu = 0.02\n[friction]\nlaw = exact\n' b1.ini
expect 3 "plane1.ball_mu (ball 1) = 0.02 is too small: the static coefficient must be >= the rolling-resistance coefficient plane1.ball_f (ball 1) = 0.03 (allowed range [0.03, inf))" "$AUTOBAL" rotor transient b1.ini -o x.h5
f '[plane1]\nball_f = -0.01, 0\n[friction]\nlaw = exact\n' b2.ini
expect 3 "plane1.ball_f (ball 1) = -0.01 is too small: must be >= 0 (allowed range [0, inf))" "$AUTOBAL" rotor transient b2.ini -o x.h5
f '[plane1]\nball_mu = 0.1, -1\n[friction]\nlaw = exact\n' b3.ini
expect 3 "plane1.ball_mu (ball 2) = -1 is too small" "$AUTOBAL" rotor transient b3.ini -o x.h5
f '[plane1]\nball_f = 0.01\n[friction]\nlaw = regularized\nu_eps = 0\n' b4.ini
expect 3 "friction.u_eps = 0 rad/s is too small: must be > 0 rad/s (allowed range (0, inf))" "$AUTOBAL" rotor transient b4.ini -o x.h5
f '[plane1]\nball_f = 0.01\n[friction]\nlaw = regularized\nu_eps = -1 rad/s\n' b5.ini
expect 3 "friction.u_eps = -1 rad/s is too small" "$AUTOBAL" rotor transient b5.ini -o x.h5
f '[plane1]\nball_f = 0.01\n[friction]\nlaw = regularized\n' b6.ini
expect 3 "law = regularized needs u_eps" "$AUTOBAL" rotor transient b6.ini -o x.h5
f '[plane1]\nball_f = 0.01\n[friction]\nlaw = exact\nu_eps = 1\n' b7.ini
expect 3 "u_eps is a key of law = regularized" "$AUTOBAL" rotor transient b7.ini -o x.h5
f '[plane1]\nball_f = 0.01\n' b8.ini
expect 3 "ball_f is given but there is no friction law" "$AUTOBAL" rotor transient b8.ini -o x.h5
f '[friction]\nlaw = sticky\n' b9.ini
expect 3 "law = 'sticky' is not one of: none, exact, regularized" "$AUTOBAL" rotor transient b9.ini -o x.h5
f '[plane1]\nball_f = 0.01, 0.02, 0.03\n[friction]\nlaw = exact\n' b10.ini
expect 3 "ball_f has 3 values but there are 2 balls" "$AUTOBAL" rotor transient b10.ini -o x.h5
f '[plane1]\nball_mu = nan\n[friction]\nlaw = exact\n' b11.ini
expect 3 "plane1.ball_mu: item 1 'nan' is not a finite number" "$AUTOBAL" rotor transient b11.ini -o x.h5
[ -e x.h5 ] && bad "bad input left an archive x.h5" || ok "bad input left no archive"

# a ball that would leave its track (N <= 0, here at rest: Omega = 0) is an error naming the ball and the time
printf "[drive]\nmode = ramp\nomega_a = 0\nomega_b = 100\nt_a = 0\nt_b = 1\n[friction]\nlaw = exact\n[transient]\nt_end = 0.5\n" > off.ini
expect 5 "ball 1 of plane 1 (p1_b1) would leave its track at t = 0 s" "$AUTOBAL" rotor transient off.ini -o off.h5

echo "$pass passed, $fail failed"
exit $((fail > 0))
