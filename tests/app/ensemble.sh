#!/usr/bin/env bash
# App test: `autobal rotor ensemble` and `autobal pendulum ensemble` (apps/cmd_ensemble.c), archives
# checked by ensemble_check.py.  Serial vs OpenMP threads, a member vs the single transient command,
# the rotor map's psi_1 <-> psi_2 symmetry, random samples vs an independent splitmix64, failures
# recorded per member, interrupted runs resumed from the journals (also with a torn last record),
# error paths; and, when the program was built with -DAUTOBAL_MPI=ON and mpirun exists, the same
# ensembles under `mpirun -np 1` and `-np 2` (and a resume across rank counts) give equal archives.
# The single transients run with stepper = rk8pd, the stepper of `rotor ensemble` / `pendulum ensemble`
# (the transients' default is dop853 with output = dense6 since 0.2.0): members equal them bit for bit.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
chk() { "$PY" "$here/ensemble_check.py" "$@" && ok "check $1" || bad "check $*"; }
# expect CODE NEEDLE CMD...: exit code CODE and NEEDLE in the message

# a small rotor basin map: initial angles of the two (identical) balls, 5 x 5 over [-pi, pi)
cat > rotor.ini <<'EOF'
[transient]
t_end = 10
[ensemble]
param1 = psi_1
param2 = psi_2
n1 = 5
n2 = 5
series = 3, 7
EOF
run "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.threads=1 -o r1.h5
run "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.threads=2 -o r2.h5
chk equal r1.h5 r2.h5
chk grid r1.h5 rotor
chk symmetric r1.h5
chk series r1.h5 7
# a balanced and an unbalanced member against `rotor transient` with the same initial angles
for ij in "1 0" "2 2"; do
  set -- $ij
  angles=$("$PY" -c "import h5py; g=h5py.File('r1.h5')['rotor/ensemble']; print(repr(float(g['psi_1'][$1]))+','+repr(float(g['psi_2'][$2])))")
  run "$AUTOBAL" rotor transient --set transient.stepper=rk8pd --set transient.t_end=10 --set transient.stop_at_balance=true --set plane1.ball_psi="$angles" -o t$1$2.h5
  chk member r1.h5 t$1$2.h5 rotor "$1" "$2"
done

# random samples, reproducible from the seed
run "$AUTOBAL" rotor ensemble --set ensemble.mode=random --set ensemble.samples=5 --set ensemble.seed=12345 --set transient.t_end=2 --set ensemble.series=4 -o rnd.h5
chk random rnd.h5 12345
chk series rnd.h5 4

# failures are results: members above some speed exceed max_steps
run "$AUTOBAL" rotor ensemble --set ensemble.param1=omega --set ensemble.min1=200 --set ensemble.max1=800 --set ensemble.n1=4 --set ensemble.param2=none --set transient.t_end=1 --set transient.max_steps=1100 -o fail.h5
chk failures fail.h5
grep -q "2 member(s) failed" err.txt && ok "failures reported on stderr" || bad "no failure warning"

# interrupted run (max_members), resumed twice, the journal's last record torn as by a kill
run "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.max_members=7 -o part.h5
chk incomplete part.h5 7
[ -f part.h5.journal-0 ] && ok "journal kept" || bad "no journal"
expect_err 4 "ensemble.resume=true" "$AUTOBAL" rotor ensemble rotor.ini -o part.h5
expect_err 3 "different configuration" "$AUTOBAL" rotor ensemble rotor.ini --set transient.t_end=9 --set ensemble.resume=true -o part.h5
run "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.resume=true --set ensemble.max_members=5 -o part.h5
chk incomplete part.h5 12
truncate -s -100 part.h5.journal-0
run "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.resume=true --set ensemble.threads=2 --json -o part.h5
grep -q '"n_computed_now":14' out.txt && ok "resume recomputed the 13 missing members and the torn one" || { bad "resume count"; cat out.txt; }
chk equal r1.h5 part.h5
[ ! -e part.h5.journal-0 ] && ok "journals removed when complete" || bad "journal left behind"
expect_err 4 "nothing to resume" "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.resume=true -o part.h5

# SIGINT in the middle of a run: members being computed are cancelled (not recorded), the archive is
# incomplete (exit 6), and a resume completes it to the same data
"$AUTOBAL" rotor ensemble rotor.ini --set ensemble.threads=1 -o int.h5 >out.txt 2>err.txt & pid=$!
for i in $(seq 1 400); do
  sz=$(stat -c %s int.h5.journal-0 2>/dev/null || echo 0)
  [ "$sz" -gt 48 ] && break
  sleep 0.05
done
kill -INT $pid 2>/dev/null; wait $pid; rc=$?
if [ $rc -eq 6 ]; then
  ok "SIGINT -> exit 6"
  chk incomplete int.h5 -1
  run "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.resume=true -o int.h5
  chk equal r1.h5 int.h5
elif [ $rc -eq 0 ]; then
  echo "skip SIGINT check: the run finished before the signal"
else
  bad "SIGINT gave exit $rc"; cat err.txt
fi

# pendulum: a grid around the main motion (4) psi = phi = psi0
cat > pend.ini <<'EOF'
[pendulum]
psi0 = 0.4
[transient]
t_end = 150
[ensemble]
param1 = psi
min1 = 0.1
max1 = 0.7
n1 = 5
param2 = phi
min2 = 0.1
max2 = 0.7
n2 = 5
endpoint = true
series = 12
EOF
run "$AUTOBAL" pendulum ensemble pend.ini --set ensemble.threads=1 -o p1.h5
run "$AUTOBAL" pendulum ensemble pend.ini --set ensemble.threads=2 -o p2.h5
chk equal p1.h5 p2.h5
chk grid p1.h5 pendulum
chk main_motion p1.h5
chk series p1.h5 12
angles=$("$PY" -c "import h5py; g=h5py.File('p1.h5')['pendulum/ensemble']; print(repr(float(g['psi'][1])), repr(float(g['phi'][3])))")
set -- $angles x x
run "$AUTOBAL" pendulum transient --set transient.stepper=rk8pd --set pendulum.psi0=0.4 --set transient.t_end=150 --set transient.stop_at_balance=true --set initial.psi="$1" --set initial.phi="$2" -o pt.h5
chk member p1.h5 pt.h5 pendulum 1 3

# error paths
expect_err 3 "param1" "$AUTOBAL" rotor ensemble --set ensemble.param1=bogus
expect_err 3 "ball 3 does not exist" "$AUTOBAL" rotor ensemble --set ensemble.param1=psi_3
expect_err 3 "min1 and max1" "$AUTOBAL" rotor ensemble --set ensemble.param1=omega
expect_err 3 "samples" "$AUTOBAL" pendulum ensemble --set ensemble.mode=random --set ensemble.n1=4
expect_err 3 "already" "$AUTOBAL" pendulum ensemble --set ensemble.param2=psi
expect_err 3 "series" "$AUTOBAL" pendulum ensemble --set ensemble.series=256
expect_err 2 "needs -o" "$AUTOBAL" pendulum ensemble --set ensemble.resume=true
expect_err 4 "" "$AUTOBAL" pendulum ensemble --set ensemble.n1=2 --set ensemble.n2=2 -o /nonexistent-dir/x.h5

# MPI: only when the program was built with -DAUTOBAL_MPI=ON and mpirun is there
mpi_build=$("$PY" -c "import h5py; print(h5py.File('r1.h5')['rotor/ensemble/execution'].attrs['mpi_build'])")
if [ "$mpi_build" = 1 ] && command -v mpirun >/dev/null; then
  MPI="mpirun --allow-run-as-root --oversubscribe"
  run $MPI -np 1 "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.threads=1 -o m1.h5
  run $MPI -np 2 "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.threads=1 -o m2.h5
  chk equal r1.h5 m1.h5 m2.h5
  run $MPI -np 2 "$AUTOBAL" pendulum ensemble pend.ini --set ensemble.threads=1 -o pm2.h5
  chk equal p1.h5 pm2.h5
  run $MPI -np 2 "$AUTOBAL" rotor ensemble --set ensemble.mode=random --set ensemble.samples=5 --set ensemble.seed=12345 --set transient.t_end=2 --set ensemble.series=4 --set ensemble.threads=1 -o rndm.h5
  chk equal rnd.h5 rndm.h5
  # a run on 2 ranks stopped early, resumed on 1 rank, finished on 2 ranks
  run $MPI -np 2 "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.threads=1 --set ensemble.max_members=9 -o mp.h5
  chk incomplete mp.h5 9
  [ -f mp.h5.journal-1 ] && ok "one journal per rank" || bad "no journal of rank 1"
  run $MPI -np 1 "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.threads=1 --set ensemble.resume=true --set ensemble.max_members=4 -o mp.h5
  chk incomplete mp.h5 13
  run $MPI -np 2 "$AUTOBAL" rotor ensemble rotor.ini --set ensemble.threads=1 --set ensemble.resume=true -o mp.h5
  chk equal r1.h5 mp.h5
  expect_err 3 "param1" $MPI -np 2 "$AUTOBAL" rotor ensemble --set ensemble.param1=bogus
elif [ "$mpi_build" = 1 ]; then
  bad "the program was built with MPI but mpirun is missing"
else
  echo "skip MPI checks (mpi_build=$mpi_build; this is not the -DAUTOBAL_MPI=ON build or mpirun is missing)"
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
