#!/usr/bin/env bash
# App test: `autobal rotor ensemble` with ball size and contact ([plane1] ball_diameter, [contact]
# restitution, v_rest; docs/device.md section 4), as a user runs it, checked by
# ensemble_contact_check.py: 1 and 2 threads give the same archive bit for bit; each member equals
# the single `rotor transient` run of its parameters (impacts, pairs touching at the end, final
# angles, residual): the ensemble is the same computation, with the pairs of every member ordered
# from its own initial angles (the grid has ball 1 behind ball 2 and ball 2 behind ball 1); random
# ball angles that overlap fail exactly those members, with a message naming the balls, the others
# run; bad input exits 3 with the message of `rotor transient` and writes nothing.
# The single transients run with stepper = rk8pd, the stepper of `rotor ensemble` / `pendulum ensemble`
# (the transients' default is dop853 with output = dense6 since 0.2.0): members equal them bit for bit.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${DATA:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
chk() { local what=$1; shift; if "$PY" "$here/ensemble_contact_check.py" "$@"; then ok "$what"; else bad "$what"; fi; }

# the default rotor with a large unbalance (tests/app/contact.sh): two 23 mm balls (gap angle
# 0.2305 rad) are pressed together, bounce (restitution 0.5) and come to resting contact
cat > model.ini <<'INI'
[plane1]
m0 = 0.0996 kg
ball_diameter = 23 mm
[contact]
restitution = 0.5
[transient]
t_end = 5 s
stop_at_balance = false
INI
# psi_1 = 0.5, 2, 3.5 against psi_2 = 1, 3: both cyclic orders of the two balls
{ cat model.ini; printf '[ensemble]\nparam1 = psi_1\nmin1 = 0.5\nmax1 = 3.5\nn1 = 3\nendpoint = true\nparam2 = psi_2\nmin2 = 1\nmax2 = 3\nn2 = 2\nwrite_unbalance = true\n'; } > grid.ini
run "$AUTOBAL" rotor ensemble grid.ini --set ensemble.threads=1 -o g1.h5
grep -q "contact: impacts per member" out.txt && ok "console: the contact line" || { bad "console lacks the contact line"; cat out.txt; }
run "$AUTOBAL" rotor ensemble grid.ini --set ensemble.threads=2 -o g2.h5
chk "1 and 2 threads: the same archive bit for bit" same g1.h5 g2.h5
chk "archive: ball_diameter on /rotor/plane1, contact_restitution and contact_v_rest (default 1e-3) on /rotor/ensemble" inputs g1.h5 0.023 0.5 0.001
for k in 0 1 2 3 4 5; do
  sets=$("$PY" "$here/ensemble_contact_check.py" params g1.h5 $k | awk '{print $2}' | paste -sd,)
  run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd model.ini --set "plane1.ball_psi=$sets" -q -o t$k.h5
  chk "member $k = rotor transient with ball_psi = $sets" member g1.h5 $k t$k.h5 1
done
# the rotating frame and v_rest given: a member against rotor transient
R="--set transient.frame=rotating --set contact.v_rest=2"
run "$AUTOBAL" rotor ensemble grid.ini $R -o gr.h5
chk "archive: contact_v_rest = 2 rad/s" inputs gr.h5 0.023 0.5 2
sets=$("$PY" "$here/ensemble_contact_check.py" params gr.h5 2 | awk '{print $2}' | paste -sd,)
run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd model.ini $R --set "plane1.ball_psi=$sets" -q -o tr2.h5
chk "rotating frame, v_rest = 2 rad/s: member 2 = rotor transient" member gr.h5 2 tr2.h5 1
# the regularized friction law with contact
F="--set friction.law=regularized --set friction.u_eps=0.5 --set plane1.ball_f=0.0005"
printf '[friction]\nlaw = none\n' >> grid.ini; printf '[friction]\nlaw = none\n' >> model.ini
run "$AUTOBAL" rotor ensemble grid.ini $F -o gf.h5
sets=$("$PY" "$here/ensemble_contact_check.py" params gf.h5 3 | awk '{print $2}' | paste -sd,)
run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd model.ini $F --set "plane1.ball_psi=$sets" -q -o tf3.h5
chk "regularized friction and contact: member 3 = rotor transient" member gf.h5 3 tf3.h5 1

# random ball angles with 100 mm balls (gap angle 2 asin(0.5) = 1.047 rad): about a third overlap
{ cat model.ini; printf '[ensemble]\nmode = random\nsamples = 12\nseed = 3\nparam1 = psi_1\nparam2 = psi_2\nwrite_unbalance = true\n'; } > rnd.ini
run "$AUTOBAL" rotor ensemble rnd.ini --set plane1.ball_diameter=100mm --set transient.t_end=0.5 --set ensemble.threads=2 -o rnd.h5
if "$PY" "$here/ensemble_contact_check.py" overlap rnd.h5 0.1 0.1 > chk.txt; then
  cat chk.txt; ok "random angles: exactly the overlapping members failed, the others ran"
  first=$(tail -n 1 chk.txt)
  grep -q "member(s) failed" err.txt && grep -q "the first, member $first (psi_1 = .*), status -[0-9]*: balls [12] and [12] of plane 1 (p1_b[12], p1_b[12]) overlap at the initial position" err.txt \
    && ok "warning: member $first failed, naming the balls" || { bad "no warning naming member $first and the balls"; cat err.txt; }
else cat chk.txt; bad "random angles: failures"; fi

# bad input: exit 3 with the message of rotor transient (which names the key and range), nothing written
for case in "plane1.ball_diameter=-20mm|plane1.ball_diameter (ball 1) = -0.02 m is too small" \
            "plane1.ball_diameter=0.3|the balls of plane 1 on the track of radius 0.1 m do not fit" \
            "contact.restitution=1.5|contact.restitution = 1.5 is too large"; do
  set=${case%%|*}; needle=${case#*|}
  "$AUTOBAL" rotor transient --set transient.stepper=rk8pd model.ini --set "$set" -o bt.h5 >/dev/null 2>errt.txt; rct=$?
  msg=$(sed -n 's/^autobal: error: //p' errt.txt | head -n 1)
  case "$msg" in *"$needle"*) [ $rct -eq 3 ] && ok "rotor transient: exit 3, '$needle'" || bad "rotor transient exit $rct for $set";;
    *) bad "rotor transient: no '$needle' for $set"; cat errt.txt; msg=$needle;; esac
  expect 3 "$msg" "$AUTOBAL" rotor ensemble grid.ini --set "$set" -o bad_${set%%=*}.h5
done
grep -v '^ball_diameter' model.ini > nodia.ini
expect_err 3 "[contact]: restitution is given but no ball has a size: set [plane1] ball_diameter" "$AUTOBAL" rotor ensemble nodia.ini -o bad_nodia.h5
ls bad_*.h5 bt.h5 >/dev/null 2>&1 && bad "a file written for bad input: $(ls bad_*.h5 bt.h5 2>/dev/null)" || ok "nothing written for bad input"

# the guide's example (docs/guide.md) (data/washer_contact.ini: stiction and contact), 4 members of 6 s: 1 and 2
# threads give the same archive
W="--set ensemble.samples=4 --set transient.t_end=6"
"$AUTOBAL" rotor ensemble "$DATA/washer_contact.ini" $W --set ensemble.threads=1 -o wc1.h5 >out.txt 2>err.txt && grep -qF "contact: impacts per member" out.txt \
  && ok "data/washer_contact.ini runs (4 members, 6 s), the contact line printed" || { bad "data/washer_contact.ini"; cat out.txt err.txt; }
"$AUTOBAL" rotor ensemble "$DATA/washer_contact.ini" $W --set ensemble.threads=2 -o wc2.h5 >out.txt 2>err.txt || bad "washer_contact, 2 threads"
if "$PY" "$here/ensemble_contact_check.py" same wc1.h5 wc2.h5 >/dev/null; then ok "washer_contact: 1 and 2 threads bit for bit"; else bad "washer_contact: threads differ"; fi

finish
