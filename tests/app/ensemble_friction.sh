#!/usr/bin/env bash
# App test: `autobal rotor ensemble` with rolling resistance and stiction ([friction] law = exact |
# regularized, [plane1] ball_f, ball_mu; the ensemble parameters ball_f, ball_mu), as a user runs
# it, checked by ensemble_friction_check.py: 1 and 2 threads give the same archive bit for bit;
# each member equals the single `rotor transient` run of its parameters (final residual, angles,
# stuck balls, time stuck, switch count); with gravity (data/washer_friction.ini, shortened) the
# threads agree and f = mu = 0 reproduces the ensemble without friction; bad input exits 3 naming
# the key and writes nothing; tools/autobal_plot.py draws the residual-unbalance distribution.
# The single transients run with stepper = rk8pd, the stepper of `rotor ensemble` / `pendulum ensemble`
# (the transients' default is dop853 with output = dense6 since 0.2.0): members equal them bit for bit.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${DATA:?}" "${TOOLS:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
chk() { local what=$1; shift; if "$PY" "$here/ensemble_friction_check.py" "$@"; then ok "$what"; else bad "$what"; fi; }

# the default rotor, balls lagging the rotor: they stick, slip, stick (tests/app/friction.sh)
cat > model.ini <<'INI'
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
INI
{ cat model.ini; printf '[ensemble]\nparam1 = psi_1\nn1 = 3\nparam2 = psi_2\nn2 = 2\nwrite_unbalance = true\n'; } > grid.ini
run "$AUTOBAL" rotor ensemble grid.ini --set ensemble.threads=1 -o g1.h5
grep -q "friction (exact): balls stuck at the end (of 2)" out.txt && ok "console: the stuck balls" || { bad "console lacks the friction line"; cat out.txt; }
run "$AUTOBAL" rotor ensemble grid.ini --set ensemble.threads=2 -o g2.h5
chk "exact law: 1 and 2 threads, the same archive bit for bit" same g1.h5 g2.h5
for k in 0 1 2 3 4 5; do
  sets=$("$PY" "$here/ensemble_friction_check.py" params g1.h5 $k | awk '{print $2}' | paste -sd,)
  run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd model.ini --set "plane1.ball_psi=$sets" -q -o t$k.h5
  chk "exact law: member $k = rotor transient with ball_psi = $sets" member g1.h5 $k t$k.h5
done
"$PY" -c "import h5py,sys; f=h5py.File('g1.h5'); sys.exit(0 if f['rotor/ensemble'].attrs['friction']=='exact' and list(f['rotor/plane1'].attrs['ball_mu'])==[0.02,0.02] else 1)" \
  && ok "archive: friction = exact on /rotor/ensemble, ball_mu on /rotor/plane1" || bad "friction attributes"

# ball_f as an ensemble parameter (random draws), fixed frame; a member against rotor transient
{ cat model.ini; printf '[ensemble]\nmode = random\nsamples = 4\nseed = 5\nparam1 = ball_f\nmin1 = 0.004\nmax1 = 0.016\nparam2 = none\nwrite_unbalance = true\n'; } > rf.ini
run "$AUTOBAL" rotor ensemble rf.ini --set transient.frame=fixed --set ensemble.threads=2 -o rf.h5
run "$AUTOBAL" rotor ensemble rf.ini --set transient.frame=fixed --set ensemble.threads=1 -o rf1.h5
chk "ball_f varied: 1 and 2 threads bit for bit" same rf.h5 rf1.h5
for k in 0 3; do
  v=$("$PY" "$here/ensemble_friction_check.py" params rf.h5 $k | awk '{print $2}')
  run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd model.ini --set transient.frame=fixed --set "plane1.ball_f=$v" -q -o tf$k.h5
  chk "ball_f varied: member $k = rotor transient with ball_f = $v" member rf.h5 $k tf$k.h5
done

# rolling inertia (ball_rho): the members are rolling balls (a member against rotor transient; the
# point-mass ensemble differs), ball_rho recorded on /rotor/plane1
{ awk '{print} /^ball_mu/ {print "ball_rho = 11.5 mm"}' model.ini
  printf '[ensemble]\nparam1 = psi_1\nn1 = 2\nparam2 = psi_2\nn2 = 2\nwrite_unbalance = true\n'; } > rollgrid.ini
run "$AUTOBAL" rotor ensemble rollgrid.ini -o roll.h5
sets=$("$PY" "$here/ensemble_friction_check.py" params roll.h5 2 | awk '{print $2}' | paste -sd,)
run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd model.ini --set "plane1.ball_psi=$sets" --set plane1.ball_rho=0.0115 -q -o troll.h5
chk "rolling inertia: member 2 = rotor transient with ball_rho = 11.5 mm" member roll.h5 2 troll.h5
run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd model.ini --set "plane1.ball_psi=$sets" -q -o tpoint.h5
if "$PY" "$here/ensemble_friction_check.py" member roll.h5 2 tpoint.h5 >/dev/null; then bad "rolling inertia: the member equals the point-mass run (ball_rho ignored)"; else ok "rolling inertia: the member differs from the point-mass run"; fi
"$PY" -c "import h5py,sys; f=h5py.File('roll.h5'); sys.exit(0 if list(f['rotor/plane1'].attrs['ball_rho'])==[0.0115,0.0115] else 1)" \
  && ok "archive: ball_rho on /rotor/plane1" || bad "no ball_rho on /rotor/plane1"

# the regularized law (no events): a member against rotor transient
sed 's/^law = exact/law = regularized\nu_eps = 0.5 rad\/s/' model.ini > reg.ini
{ cat reg.ini; printf '[ensemble]\nparam1 = psi_1\nn1 = 2\nparam2 = psi_2\nn2 = 2\nwrite_unbalance = true\n'; } > reggrid.ini
run "$AUTOBAL" rotor ensemble reggrid.ini -o reg.h5
sets=$("$PY" "$here/ensemble_friction_check.py" params reg.h5 1 | awk '{print $2}' | paste -sd,)
run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd reg.ini --set "plane1.ball_psi=$sets" -q -o treg.h5
chk "regularized law: member 1 = rotor transient" member reg.h5 1 treg.h5

# gravity and friction: the washing machine of docs/guide.md, 4 members of 6 s
W="--set ensemble.samples=4 --set transient.t_end=6"
run "$AUTOBAL" rotor ensemble "$DATA/washer_friction.ini" $W --set ensemble.threads=1 -o w1.h5
run "$AUTOBAL" rotor ensemble "$DATA/washer_friction.ini" $W --set ensemble.threads=2 -o w2.h5
chk "washer (gravity, exact law): 1 and 2 threads bit for bit" same w1.h5 w2.h5
# f = mu = 0: the balls never stay stuck, the frictionless ensemble (same steps up to the events)
grep -v '^ball_f\|^ball_mu\|^\[friction\]\|^law = ' "$DATA/washer_friction.ini" > washer_nofric.ini
run "$AUTOBAL" rotor ensemble washer_nofric.ini $W -o w_none.h5
run "$AUTOBAL" rotor ensemble "$DATA/washer_friction.ini" $W --set plane1.ball_f=0 --set plane1.ball_mu=0 -o w_zero.h5
chk "washer: f = mu = 0 reproduces the frictionless ensemble (residual in kg m within 1e-6)" close w_zero.h5 w_none.h5 1e-6

# the picture of the distribution
if "$PY" "$TOOLS/autobal_plot.py" w1.h5 -o pics --compare w_none.h5 >out.txt 2>err.txt && [ -s pics/w1_unbalance.png ] \
   && "$PY" -c "import matplotlib.image as m,sys; a=m.imread('pics/w1_unbalance.png'); sys.exit(0 if a.shape[0] > 300 and a.std() > 0.05 else 1)"; then
  ok "autobal_plot.py draws pics/w1_unbalance.png (with and without friction)"
else bad "no unbalance plot"; cat err.txt; fi

# bad input: exit 3 naming the key, nothing written
grep -v '^\[friction\]\|^law = ' grid.ini > nolaw.ini
expect_err 3 "ball_f is given but there is no friction law" "$AUTOBAL" rotor ensemble nolaw.ini -o bad1.h5
{ printf '[ensemble]\nparam1 = ball_f\nn1 = 2\nmin1 = 0\nmax1 = 0.01\n'; } > nolaw2.ini
expect_err 3 "ball_f varies the friction of the balls, but there is no friction law" "$AUTOBAL" rotor ensemble nolaw2.ini -o bad2.h5
expect_err 3 "ball_mu" "$AUTOBAL" rotor ensemble grid.ini --set plane1.ball_mu=0.001 -o bad3.h5
[ ! -e bad1.h5 ] && [ ! -e bad2.h5 ] && [ ! -e bad3.h5 ] && ok "nothing written for bad input" || bad "a file written for bad input"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
