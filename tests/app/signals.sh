#!/usr/bin/env bash
# App test: SIGINT, SIGTERM and SIGHUP stop every long-running command (README and docs/guide.md, "Exit codes"):
# rotor stability|sweep|map|campbell, pendulum map|critical, info, rerun and plot get each signal (pendulum
# sweep: SIGTERM) after a short delay while they run a job far longer than the test (grids of millions of points); each
# must exit 6 within a few seconds, and the archive (-o) must be readable, status "incomplete",
# status_reason "interrupted by SIG...", with the partial data present and consistent
# (signals_check.py: lengths = the recorded count done, the grid = the first points of the requested
# one, values in range, spot checks against an independent command).  The transients and the
# ensemble (interrupted by SIGINT/SIGTERM in rotor.sh, badinput.sh, ensemble.sh) get SIGHUP here.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
A=$AUTOBAL
# The signal goes out once the command (with its threads and child processes) has used BUSY seconds of
# CPU after installing its handler: the same progress on a quiet and on a loaded machine (a fixed
# sleep of 0.7 s gave ~0.6 s of CPU when quiet, less under load).  The least any command needs for the
# partial data checked below: 0.03 s (Release), 0.1 s (ASan, rotor map: 1 row done), measured 2026-11-29.
BUSY=${SIGNALS_BUSY:-0.25}
LIMIT=10                     # seconds a command may take to stop after the signal
BUSY_WAIT=30                 # seconds (wall) at most to wait for BUSY s of CPU (then the signal goes anyway)

# busy PID: wait until PID and its descendants have used BUSY s of CPU (utime + stime, all threads),
# at most BUSY_WAIT s; returns at once when PID has ended
busy() {
  local pid=$1 want k ticks kids all
  want=$(awk -v b="$BUSY" -v h="$(getconf CLK_TCK)" 'BEGIN { printf "%d", b * h + 0.5 }')
  for k in $(seq 1 $((BUSY_WAIT * 50))); do
    all=$pid; kids=$(cat /proc/$pid/task/*/children 2>/dev/null)
    while [ -n "${kids// /}" ]; do
      all="$all $kids"; kids=$(for c in $kids; do cat /proc/$c/task/*/children 2>/dev/null; done)
    done
    ticks=$(for c in $all; do cat /proc/$c/stat 2>/dev/null; done | awk '{ s += $14 + $15 } END { print s + 0 }')
    kill -0 $pid 2>/dev/null || return 0
    [ "$ticks" -ge "$want" ] && return 0
    sleep 0.02
  done
}

# interrupt SIG NAME CMD...: run CMD in the background, send SIG once it has installed its handler
# for SIG and used BUSY s of CPU, wait at most LIMIT s (then SIGKILL: a failure).  Sets rc (exit code) and dt
# (seconds from the signal to the exit).
interrupt() {
  local sig=$1 name=$2; shift 2
  "$@" >"$name.out" 2>"$name.err" &
  local pid=$! t0 k
  caught $pid "$sig"
  busy $pid
  if ! kill -0 $pid 2>/dev/null; then
    wait $pid; rc=$?; dt=0
    bad "$name: finished (exit $rc) before the signal: the job is not long enough"; return
  fi
  kill -"$sig" $pid; t0=${EPOCHREALTIME/./}
  for k in $(seq 1 $((LIMIT * 20))); do kill -0 $pid 2>/dev/null || break; sleep 0.05; done
  if kill -0 $pid 2>/dev/null; then
    kill -KILL $pid; wait $pid; rc=$?; dt=$LIMIT
    bad "$name: SIG$sig ignored: still running $LIMIT s after it (killed)"; return
  fi
  wait $pid; rc=$?
  k=$(( (${EPOCHREALTIME/./} - t0 + 5000) / 10000 )); dt=$((k / 100)).$(printf %02d $((k % 100)))
  if [ $rc -eq 6 ] && { [ "${NOMSG:-0}" = 1 ] || grep -q "interrupted by SIG$sig" "$name.err"; }; then
    ok "$name: SIG$sig -> exit 6 after $dt s: $(head -c 160 "$name.err")"
  else
    bad "$name: SIG$sig -> exit $rc after $dt s (want 6 and 'interrupted by SIG$sig')"; cat "$name.err"
  fi
}
# chk WHAT KIND FILE SIG ARGS...: a check of signals_check.py, queued; all of them run at the end in one
# Python process (h5py and NumPy imported once: 0.4 s of CPU each time otherwise), each as before
: >checks.txt
chk() { local a q=""; for a in "$@"; do q="$q$(printf '%q' "$a") "; done; echo "$q" >>checks.txt; }
R=$DATA/rotor_default.ini P=$DATA/pendulum_default.ini

# the complete analysis at omega (no critical speeds): what an interrupted `rotor stability` keeps
"$A" rotor stability "$R" --set stability.critical_speeds=false -q -o stab_ref.h5 || bad "rotor stability reference"

for sig in INT TERM HUP; do
  # rotor stability: the analysis at omega, then 1e7 grid points of the critical-speed search (minutes)
  interrupt $sig stab_$sig "$A" rotor stability "$R" --set stability.n_omega=10000000 -q -o stab_$sig.h5
  chk "stab_$sig.h5: analysis at omega kept, no critical speeds" stability stab_$sig.h5 SIG$sig stab_ref.h5

  # rotor sweep: 1e7 points of omega in [10, 2000] rad/s
  interrupt $sig sweep_$sig "$A" rotor sweep "$R" --set sweep.n=10000000 --set sweep.min=10 --set sweep.max=2000 -q -o sweep_$sig.h5
  if [ $sig = INT ]; then # an independent margin at one point of the partial sweep: `rotor stability` there
    read -r k om < <("$PY" -c "
import h5py; o = h5py.File('sweep_INT.h5')['rotor/sweep/omega'][:]; k = len(o) // 2; print(k, repr(float(o[k])))")
    "$A" rotor stability "$R" --set rotor.omega="$om" --set stability.critical_speeds=false -q -o spot.h5 &&
      ref=$("$PY" -c "import h5py; print(repr(float(h5py.File('spot.h5')['rotor/stability'].attrs['margin'])))")
    chk "sweep_INT.h5: partial sweep, margin at omega[$k] as rotor stability" sweep sweep_INT.h5 SIGINT 10 2000 10000000 "$k" "${ref:-nan}"
  else
    chk "sweep_$sig.h5: partial sweep" sweep sweep_$sig.h5 SIG$sig 10 2000 10000000
  fi

  # rotor map: 4000 x 2000 points
  interrupt $sig map_$sig "$A" rotor map "$R" --set map.n1=4000 --set map.n2=2000 --set map.min1=10 --set map.max1=2000 \
    --set map.min2=0 --set map.max2=1 -q -o map_$sig.h5
  chk "map_$sig.h5: partial map" map map_$sig.h5 SIG$sig 10 2000 4000 0 1 2000

  # rotor campbell: 1e6 speeds
  interrupt $sig camp_$sig "$A" rotor campbell "$R" --set campbell.n=1000000 --set campbell.omega_min=0 \
    --set campbell.omega_max=3000 -q -o camp_$sig.h5
  chk "camp_$sig.h5: partial Campbell diagram" campbell camp_$sig.h5 SIG$sig 0 3000 1000000

  # pendulum map: 3000 x 2000 points with the largest real part (a root solve per point)
  interrupt $sig pmap_$sig "$A" pendulum map "$P" --set map.n_Rm=3000 --set map.n_Rw=2000 --set map.max_real=true -q -o pmap_$sig.h5
  if [ $sig = INT ]; then # a point of the partial map checked by `pendulum roots` (the roots of (6) there)
    read -r i j rm rw < <("$PY" -c "
import h5py; g = h5py.File('pmap_INT.h5')['pendulum/map']; i = len(g['R_m']) // 2; j = 1234
print(i, j, repr(float(g['R_m'][i])), repr(float(g['R_w'][j])))")
    "$A" pendulum roots "$P" --set pendulum.R_m="$rm" --set pendulum.R_w="$rw" -q -o roots.h5 &&
      read -r v mr < <("$PY" -c "
import h5py; a = h5py.File('roots.h5')['pendulum/roots'].attrs
print({'stable': 1, 'marginal': 0, 'unstable': -1}[a['verdict']], repr(float(a['max_real'])))")
    chk "pmap_INT.h5: partial pendulum map, point ($i, $j) as pendulum roots" pmap pmap_INT.h5 SIGINT 3000 2000 "$i" "$j" "${v:-9}" "${mr:-nan}"
  else
    chk "pmap_$sig.h5: partial pendulum map" pmap pmap_$sig.h5 SIG$sig 3000 2000
  fi

  # pendulum critical: interrupted in the damped search (1e8 grid points)
  interrupt $sig pcrit_$sig "$A" pendulum critical "$P" --set critical.n_sweep=100000000 -q -o pcrit_$sig.h5
  chk "pcrit_$sig.h5: critical speeds at R_m, no damped search, no curves" pcrit pcrit_$sig.h5 SIG$sig 499 damped
done

# pendulum sweep over R_w (1e7 points), interrupted: the points done, one checked by `pendulum roots`
interrupt TERM psweep "$A" pendulum sweep "$P" --set sweep.param=R_w --set sweep.min=0.5 --set sweep.max=4 \
  --set sweep.n=10000000 -q -o psweep.h5
read -r k rw < <("$PY" -c "
import h5py; r = h5py.File('psweep.h5')['pendulum/sweep/R_w'][:]; k = len(r) // 2; print(k, repr(float(r[k])))")
vk=$("$A" pendulum roots "$P" --set pendulum.R_w="$rw" --json | "$PY" -c "
import json, sys; print({'stable': 1, 'marginal': 0, 'unstable': -1}[json.load(sys.stdin)['verdict']])")
chk "psweep.h5: partial pendulum sweep, verdict at R_w[$k] as pendulum roots" psweep psweep.h5 SIGTERM 0.5 4 10000000 "$k" "${vk:-9}"

# pendulum critical interrupted in the curves (1e6 points of R_m)
interrupt INT pcurve "$A" pendulum critical "$P" --set critical.n_Rm=1000000 -q -o pcurve.h5
chk "pcurve.h5: partial curves, R_w1(k=1) = (16) on them" pcrit pcurve.h5 SIGINT 1000000 curves
# rotor campbell interrupted in the resonance search (the diagram done)
interrupt TERM campres "$A" rotor campbell "$R" --set campbell.n=401 --set campbell.n_resonance=10000000 \
  --set campbell.omega_min=0 --set campbell.omega_max=3000 -q -o campres.h5
chk "campres.h5: complete diagram, no resonances" campbell campres.h5 SIGTERM 0 3000 401

# info: an archive with 10000 groups more (listing takes seconds)
"$A" pendulum roots "$P" -q -o big.h5 && "$PY" -c "
import h5py
with h5py.File('big.h5', 'a') as f:
    for i in range(10000):
        g = f.create_group('extra/g%05d' % i); g.attrs['x'] = float(i); g.create_dataset('d', data=[1.0, 2.0])
" || bad "making big.h5"
for sig in INT TERM HUP; do
  interrupt $sig info_$sig "$A" info big.h5
  grep -q "the listing stopped" info_$sig.err && ok "info_$sig: the message says the listing stopped" || bad "info_$sig: message"
done

# rerun of an interrupted pendulum map re-runs it in full (3000 x 2000): interrupted again
for sig in INT TERM HUP; do
  interrupt $sig rerun_$sig "$A" rerun pmap_INT.h5 -q -o rerun_$sig.h5
  chk "rerun_$sig.h5: partial pendulum map" pmap rerun_$sig.h5 SIG$sig 3000 2000
done

# SIGHUP ignored by the parent (nohup) stays ignored: the run goes on, SIGTERM then stops it
( trap '' HUP; exec "$A" rotor map "$R" --set map.n1=4000 --set map.n2=2000 -q -o nohup.h5 ) >nohup.out 2>nohup.err &
pid=$!; caught $pid TERM; busy $pid; kill -HUP $pid; sleep 0.5
if kill -0 $pid 2>/dev/null; then
  ok "nohup: an ignored SIGHUP does not stop the run"
  kill -TERM $pid; wait $pid; rc=$?
  [ $rc -eq 6 ] && grep -q "interrupted by SIGTERM" nohup.err && ok "nohup: SIGTERM stops it (exit 6)" || { bad "nohup: SIGTERM gave exit $rc"; cat nohup.err; }
else
  wait $pid; bad "nohup: an ignored SIGHUP stopped the run (exit $?)"; cat nohup.err
fi

# plot (a Python child, seconds for a map): the signal is passed on to it
for sig in INT TERM HUP; do
  interrupt $sig plot_$sig "$A" plot map_INT.h5 -q -o plots_$sig
done

# SIGHUP to the transients and an ensemble (SIGINT/SIGTERM: rotor.sh, badinput.sh, ensemble.sh)
# (their messages are the transients' own: only the exit code and the archive are checked)
NOMSG=1 interrupt HUP rtr "$A" rotor transient "$R" --set transient.t_end=100000 -q -o rtr.h5
NOMSG=1 interrupt HUP ptr "$A" pendulum transient "$P" --set transient.t_end=1e8 --set transient.revs_out=50 -q -o ptr.h5
NOMSG=1 interrupt HUP ens "$A" pendulum ensemble "$P" --set ensemble.n1=400 --set transient.t_end=3000 -q -o ens.h5
"$PY" - <<'EOF' && ok "rtr.h5, ptr.h5, ens.h5: incomplete, interrupted by SIGHUP, data up to the stop" || bad "transients after SIGHUP"
import h5py, numpy as np
for fn, t in (("rtr.h5", "rotor/transient/time"), ("ptr.h5", "pendulum/transient/tau")):
    f = h5py.File(fn, "r")
    assert f.attrs["status"] == "incomplete" and f.attrs["status_reason"] == "interrupted by SIGHUP", (fn, dict(f.attrs))
    x = f[t][:]
    assert x.size >= 2 and x[0] == 0 and np.all(np.diff(x) > 0), fn
f = h5py.File("ens.h5", "r")
assert f.attrs["status"] == "incomplete" and f.attrs["status_reason"] == "interrupted by SIGHUP", dict(f.attrs)
EOF
# the queued checks of the archives (chk above), each reported as ok/FAIL with its description
"$PY" "$here/signals_check.py" --batch checks.txt >batch.txt 2>&1
cat batch.txt
n_ok=$(grep -c '^ok   ' batch.txt); n_bad=$(grep -c '^FAIL ' batch.txt)
pass=$((pass + n_ok)); fail=$((fail + n_bad))
[ $((n_ok + n_bad)) -eq "$(wc -l <checks.txt)" ] && [ "$n_ok" -gt 0 ] && ok "signals_check.py --batch: $n_ok of $(wc -l <checks.txt) checks ran and passed or failed above" \
  || bad "signals_check.py --batch: $n_ok ok + $n_bad failed != $(wc -l <checks.txt) queued"
ls | grep -q '\.partial' && bad "temporary files left: $(ls | grep '\.partial')" || ok "no temporary files left"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
