#!/usr/bin/env bash
# App test: the archive as a product for Python users (issue 6).  Archives of every command are
# opened with xarray (engine="h5netcdf", group by group) and h5py, and their names, units and
# values checked (postprocess_check.py); `autobal info` (text and --json) is compared with what
# h5py reads; `autobal rerun` must reproduce every dataset bit for bit; `autobal plot` and the
# tools/autobal_plot.py one-liner must write readable PNG files, also for ensemble archives, and the
# Campbell picture's mode tracking must follow known branches through a crossing.  Error paths: missing, truncated,
# foreign and non-HDF5 files, bad command lines.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${TOOLS:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
py() { "$PY" "$here/postprocess_check.py" "$@" >py.txt 2>&1 && ok "postprocess_check.py $* ($(tail -1 py.txt))" || { bad "postprocess_check.py $*"; grep -v '^ok' py.txt; }; }
# In the sanitizer build (SANITIZE=1) the checks that only read what the program wrote (layout, info,
# effective, png, tracking, ensemble_plot: h5py, xarray, matplotlib) are left to the Release pass;
# every command of the program still runs, and `same` (rerun bit for bit) is still checked.
if [ "${SANITIZE:-0}" = 1 ]; then
  py() { if [ "$1" = same ]; then "$PY" "$here/postprocess_check.py" "$@" >py.txt 2>&1 && ok "postprocess_check.py $* ($(tail -1 py.txt))" || { bad "postprocess_check.py $*"; grep -v '^ok' py.txt; }; else echo "sanitizer build: postprocess_check.py $1 left to the Release pass"; fi; }
fi

# ---- 1. archives of every command (grids and durations cut to keep the test fast) -------------
printf '[critical]\nn_Rm = 99\n' >crit_over.ini
printf '[map]\nn_Rm = 40\nn_Rw = 30\nmax_real = true\n' >map_over.ini
printf '[map]\nn_Rm = 40\nn_Rw = 50\nn_k = 9\n' >every_over.ini
printf '[transient]\nt_end = 150\n' >ptr_over.ini
printf '[transient]\nt_end = 10\n' >rot_over.ini
printf '[transient]\nt_end = 3\ndt_out = 0.002\n' >rot2_over.ini
expect 0 "" "$AUTOBAL" pendulum roots "$DATA/pendulum_default.ini" -o roots.h5
expect 0 "" "$AUTOBAL" pendulum roots "$DATA/pendulum_physical.ini" -o roots_phys.h5
expect 0 "" "$AUTOBAL" pendulum critical "$DATA/pendulum_critical_k1.ini" --set critical.n_Rm=99 -o critical.h5
expect 0 "" "$AUTOBAL" pendulum map --set map.n_Rm=40 --set map.n_Rw=30 --set map.max_real=true -o map.h5
expect 0 "" "$AUTOBAL" pendulum map "$DATA/pendulum_map_every.ini" --set map.n_Rm=40 --set map.n_Rw=50 --set map.n_k=9 -o map_every.h5
expect 0 "" "$AUTOBAL" pendulum transient "$DATA/pendulum_transient.ini" --set transient.t_end=150 -o ptrans.h5
expect 0 "" "$AUTOBAL" rotor transient --set transient.t_end=10 -o rotor.h5
expect 0 "" "$AUTOBAL" rotor transient "$DATA/rotor_two_planes.ini" --set transient.t_end=3 --set transient.dt_out=0.002 -o rotor2.h5
archives="roots roots_phys critical map map_every ptrans rotor rotor2"
# The rotor stability commands (apps/cmd_rotor_stability.c) are covered when they are registered.
stab=""
if "$AUTOBAL" rotor stability --help >/dev/null 2>&1; then
  expect 0 "" "$AUTOBAL" rotor stability -o rstab.h5
  expect 0 "" "$AUTOBAL" rotor sweep --set sweep.n=200 -o rsweep.h5
  expect 0 "" "$AUTOBAL" rotor map --set map.n1=40 --set map.n2=12 -o rmap.h5
  expect 0 "" "$AUTOBAL" rotor campbell --set campbell.n=300 -o rcampbell.h5
  # a known crossing: supports placed so that translation and tilt decouple (l_L c_L = l_R c_R,
  # l_L h_L = l_R h_R); the backward tilting mode then falls through the translational pair
  expect 0 "" "$AUTOBAL" rotor campbell --set supports.l_R=0.2 --set supports.c_Rx=100000 --set supports.c_Ry=100000 \
    --set supports.h_Rx=100 --set supports.h_Ry=100 --set campbell.n=300 -o rcampbell_x.h5
  stab="rstab rsweep rmap rcampbell"
else
  echo "note: 'autobal rotor stability|sweep|map|campbell' are not registered: not covered"
fi
archives="$archives $stab"

# ---- 2. xarray (h5netcdf) and h5py: names, units, values ----------------------------------------
# (one Python process for all archives: "+" separates the checks)
py layout roots roots.h5 "$DATA/pendulum_default.ini" \
 + layout roots roots_phys.h5 "$DATA/pendulum_physical.ini" \
 + layout critical critical.h5 "$DATA/pendulum_critical_k1.ini,crit_over.ini" \
 + layout map map.h5 map_over.ini \
 + layout map map_every.h5 "$DATA/pendulum_map_every.ini,every_over.ini" critical.h5 \
 + layout pendulum_transient ptrans.h5 "$DATA/pendulum_transient.ini,ptr_over.ini" \
 + layout rotor_transient rotor.h5 rot_over.ini \
 + layout rotor_transient rotor2.h5 "$DATA/rotor_two_planes.ini,rot2_over.ini" \
 $(for a in $stab; do printf '+ layout rotor_stability %s.h5 - ' "$a"; done)

# ---- 3. autobal info ---------------------------------------------------------------------------
triples=""
for a in $archives; do
  "$AUTOBAL" info "$a.h5" >"$a.info.txt" 2>err.txt && "$AUTOBAL" info --json "$a.h5" >"$a.info.json" 2>>err.txt \
    && ok "info and info --json on $a.h5" || { bad "info on $a.h5"; cat err.txt; }
  triples="$triples $a.h5 $a.info.txt $a.info.json"
done
py info $triples
expect 4 "No such file" "$AUTOBAL" info missing.h5
head -c 4000 rotor.h5 >truncated.h5
expect 4 "truncated" "$AUTOBAL" info truncated.h5
"$PY" -c "import h5py; h = h5py.File('foreign.h5', 'w'); h['x'] = [1.0, 2.0]" && ok "made a foreign HDF5 file"
expect 4 "not an autobal archive" "$AUTOBAL" info foreign.h5
"$PY" -c "import h5py; h = h5py.File('wrongconv.h5', 'w'); h.attrs['Conventions'] = 'CF-1.8'"
expect 4 "CF-1.8" "$AUTOBAL" info wrongconv.h5
echo "not hdf5" >text.h5
expect 4 "not an HDF5 file" "$AUTOBAL" info text.h5
mkdir -p adir
expect 4 "directory" "$AUTOBAL" info adir
expect 4 "not an autobal archive" "$AUTOBAL" info --json foreign.h5
[ ! -s out.txt ] && ok "info --json on a foreign file prints nothing on stdout" || bad "info --json printed on failure"
expect 2 "give an archive" "$AUTOBAL" info
expect 2 "takes one archive" "$AUTOBAL" info roots.h5 map.h5
expect 2 "no --set" "$AUTOBAL" info roots.h5 --set pendulum.R_w=2
expect 0 "usage: autobal info FILE.h5" "$AUTOBAL" info --help
"$AUTOBAL" --help >help.txt 2>&1
grep -q "^  info " help.txt && grep -q "^  rerun " help.txt && grep -q "^  plot " help.txt \
  && ok "autobal --help lists info, rerun, plot" || bad "autobal --help does not list info/rerun/plot"
# an interrupted run: info says so
"$AUTOBAL" pendulum transient --set transient.max_steps=10 -o partial.h5 >/dev/null 2>&1
expect 0 "WARNING: the run did not complete" "$AUTOBAL" info partial.h5

# ---- 4. autobal rerun: bit for bit ------------------------------------------------------------
pairs=""
for a in $archives; do
  expect 0 "" "$AUTOBAL" rerun "$a.h5" -o "re_$a.h5" --quiet
  pairs="$pairs $a.h5 re_$a.h5"
done
expect 0 "" "$AUTOBAL" rerun re_ptrans.h5 -o re_re_ptrans.h5 --json
py same $pairs ptrans.h5 re_re_ptrans.h5
"$PY" -c "import json; json.load(open('out.txt'))" && ok "rerun --json prints the command's JSON summary" || bad "rerun --json output"
# a changed input must change the data: the comparison can fail
expect 0 "" "$AUTOBAL" pendulum transient "$DATA/pendulum_transient.ini" --set transient.t_end=150 --set pendulum.R_w=3.01 -o ptrans_other.h5
"$PY" "$here/postprocess_check.py" same ptrans.h5 ptrans_other.h5 >py.txt 2>&1 && bad "comparison did not see R_w = 3.01" || ok "bit-for-bit comparison detects a changed R_w"
expect 4 "exists" "$AUTOBAL" rerun roots.h5 -o re_roots.h5
expect 0 "" "$AUTOBAL" rerun roots.h5 -o re_roots.h5 --force
expect 2 "-o NEW.h5" "$AUTOBAL" rerun roots.h5
expect 2 "is the archive being re-run" "$AUTOBAL" rerun roots.h5 -o roots.h5 --force
expect 2 "no --set" "$AUTOBAL" rerun roots.h5 -o x.h5 --set pendulum.R_w=2
# the damaged copies of roots.h5 for the reruns below, made by one Python process (h5py once)
for f in noconfig badcmd badcfg baddef twice defnan garbled; do cp roots.h5 $f.h5; done
"$PY" - <<'PYEOF' || bad "could not make the damaged copies of roots.h5"
import h5py
def edit(name, **attrs):
    with h5py.File(name, 'r+') as h:
        for k, v in attrs.items():
            if v is None:
                del h.attrs[k]
            else:
                h.attrs[k] = v
edit('noconfig.h5', input_config=None, effective_config=None)
edit('badcmd.h5', command='rotor levitate')
edit('badcfg.h5', effective_config='[pendulum]\nR_w = 2\n[pendulum]\nR_q = 1\n')
edit('baddef.h5', effective_config='[pendulum]\n;default R_q = 1\n')
edit('twice.h5', effective_config='[pendulum]\nR_w = 2\n;default R_w = 3\n')
edit('defnan.h5', effective_config='[pendulum]\n;default R_w = zz\n')
edit('garbled.h5', effective_config='R_w: 2\n')
PYEOF
expect 4 "not an autobal archive" "$AUTOBAL" rerun foreign.h5 -o x.h5
expect 4 "No such file" "$AUTOBAL" rerun missing.h5 -o x.h5
expect 4 "no root attribute 'effective_config' (nor 'input_config')" "$AUTOBAL" rerun noconfig.h5 -o x.h5
expect 4 "rotor levitate" "$AUTOBAL" rerun badcmd.h5 -o x.h5
expect 3 "R_q" "$AUTOBAL" rerun badcfg.h5 -o x.h5
expect 3 "R_q" "$AUTOBAL" rerun baddef.h5 -o x.h5
expect 4 "recorded more than once" "$AUTOBAL" rerun twice.h5 -o x.h5
expect 3 "R_w = 'zz'" "$AUTOBAL" rerun defnan.h5 -o x.h5
[ ! -e x.h5 ] && ok "no x.h5 left by the failed reruns" || bad "a failed rerun left x.h5"
expect 4 "neither" "$AUTOBAL" rerun garbled.h5 -o x.h5

# ---- 4b. the effective configuration: every key read, defaults included ---------------------------
# Each archive's effective_config holds the keys given and the defaults used; the model parameters
# stored in the archive's groups equal its values bit for bit.
py effective $(for a in $archives; do printf '%s.h5 ' "$a"; done)
# A re-run takes the values from effective_config, not from the built-in defaults: change a
# recorded default (as a later version with other defaults would), re-run, and the new archive
# must hold the recorded value.  ";default" keys (the command tells given from absent) stay absent.
expect 0 "" "$AUTOBAL" pendulum roots -o d_roots.h5 -q
cp d_roots.h5 d_roots_edit.h5
"$PY" - <<'PYEOF' && ok "edited ;default R_w = 3 -> 2.75 in a copy of d_roots.h5" || bad "edit d_roots_edit.h5"
import h5py
h = h5py.File("d_roots_edit.h5", "r+")
e = h.attrs["effective_config"]
assert ";default R_w = 3\n" in e and h.attrs["input_config"] == "", e
h.attrs["effective_config"] = e.replace(";default R_w = 3\n", ";default R_w = 2.75\n")
PYEOF
expect 0 "" "$AUTOBAL" rerun d_roots_edit.h5 -o d_roots_re.h5 -q
"$PY" - <<'PYEOF' && ok "re-run used the recorded default R_w = 2.75 (built-in 3), kept it absent, kept input_config" || bad "re-run of an edited ;default"
import h5py
a, b = h5py.File("d_roots_edit.h5", "r"), h5py.File("d_roots_re.h5", "r")
assert float(b["pendulum"].attrs["R_w"]) == 2.75 and float(h5py.File("d_roots.h5")["pendulum"].attrs["R_w"]) == 3.0
assert b.attrs["effective_config"] == a.attrs["effective_config"], (b.attrs["effective_config"], a.attrs["effective_config"])
assert b.attrs["input_config"] == a.attrs["input_config"] == ""
assert (b["pendulum/roots/root_real"][:] != a["pendulum/roots/root_real"][:]).any()
PYEOF
# the rotor's ball lists (not given) are recorded as the lists used: change ball_psi and the
# number of balls in a copy, re-run, and the new archive has the recorded balls
expect 0 "" "$AUTOBAL" rotor transient --set transient.t_end=0.05 -o d_rotor.h5 -q
cp d_rotor.h5 d_rotor_edit.h5
"$PY" - <<'PYEOF' && ok "edited the recorded ball lists of d_rotor.h5 (2 balls -> 3)" || bad "edit d_rotor_edit.h5"
import h5py
h = h5py.File("d_rotor_edit.h5", "r+")
e = h.attrs["effective_config"]
old = [";default ball_mass = 0.05, 0.05\n", ";default ball_radius = 0.1, 0.1\n",
       ";default ball_damping = 0.1, 0.1\n", ";default ball_psi = 1, 2.5\n", ";default ball_rate = 0, 0\n"]
new = [";default ball_mass = 0.05, 0.04, 0.03\n", ";default ball_radius = 0.1, 0.1, 0.1\n",
       ";default ball_damping = 0.1, 0.1, 0.1\n", ";default ball_psi = 1, 2, 3\n", ";default ball_rate = 0, 0, 0\n"]
for o, n in zip(old, new):
    assert o in e, (o, e)
    e = e.replace(o, n)
h.attrs["effective_config"] = e
PYEOF
expect 0 "" "$AUTOBAL" rerun d_rotor_edit.h5 -o d_rotor_re.h5 -q
"$PY" - <<'PYEOF' && ok "re-run used the recorded ball lists (3 balls, masses 0.05/0.04/0.03, psi 1/2/3)" || bad "re-run of edited ball lists"
import h5py, numpy as np
b = h5py.File("d_rotor_re.h5", "r")
p = b["rotor/plane1"]
names = {k: p[k][()] if k in p else p.attrs[k] for k in list(p.keys()) + list(p.attrs.keys())}
m = np.asarray(p.attrs["ball_mass"], dtype=float).ravel()
psi = np.asarray(p.attrs["ball_psi_initial"], dtype=float).ravel()
assert list(m) == [0.05, 0.04, 0.03], (m, sorted(names))
assert list(psi) == [1.0, 2.0, 3.0], (psi, sorted(names))
assert b.attrs["input_config"] == h5py.File("d_rotor.h5", "r").attrs["input_config"]
PYEOF
# a default the command does not ask about is recorded as a key: n_Rw = 200 -> 7
expect 0 "" "$AUTOBAL" pendulum map --set map.n_Rm=5 -o d_map.h5 -q
cp d_map.h5 d_map_edit.h5
"$PY" - <<'PYEOF' && ok "edited n_Rw = 200 -> 7 in a copy of d_map.h5" || bad "edit d_map_edit.h5"
import h5py
h = h5py.File("d_map_edit.h5", "r+")
e = h.attrs["effective_config"]
assert "\nn_Rw = 200\n" in e and "n_Rw" not in h.attrs["input_config"], e
h.attrs["effective_config"] = e.replace("\nn_Rw = 200\n", "\nn_Rw = 7\n")
PYEOF
expect 0 "" "$AUTOBAL" rerun d_map_edit.h5 -o d_map_re.h5 -q
"$PY" -c "
import h5py; b = h5py.File('d_map_re.h5', 'r')
assert b['pendulum/map/verdict'].shape == (5, 7), b['pendulum/map/verdict'].shape
assert 'n_Rw = 7' in b.attrs['effective_config'] and 'n_Rw' not in b.attrs['input_config']" \
  && ok "re-run used the recorded n_Rw = 7 (built-in 200): verdict 5 x 7" || bad "re-run of an edited default key"
# an archive of an earlier version (input_config only) is re-run with this version's defaults
cp d_map.h5 d_map_old.h5 && "$PY" -c "import h5py; h = h5py.File('d_map_old.h5', 'r+'); del h.attrs['effective_config']"
expect 0 "" "$AUTOBAL" rerun d_map_old.h5 -o d_map_old_re.h5 -q
"$PY" -c "
import h5py; a, b = h5py.File('d_map.h5', 'r'), h5py.File('d_map_old_re.h5', 'r')
assert b.attrs['effective_config'] == a.attrs['effective_config']
assert (b['pendulum/map/verdict'][:] == a['pendulum/map/verdict'][:]).all()" \
  && ok "an archive without effective_config re-runs from input_config (same data, same effective_config)" \
  || bad "re-run from input_config only"
# the effective configuration is plain INI: as a configuration file it gives the same run
"$PY" -c "import h5py; open('d_map_eff.ini', 'w').write(h5py.File('d_map.h5', 'r').attrs['effective_config'])"
expect 0 "" "$AUTOBAL" pendulum map d_map_eff.ini -o d_map_file.h5 -q
"$PY" -c "
import h5py; a, b = h5py.File('d_map.h5', 'r'), h5py.File('d_map_file.h5', 'r')
assert (b['pendulum/map/verdict'][:] == a['pendulum/map/verdict'][:]).all() and b['pendulum/map/verdict'].shape == (5, 200)
assert b.attrs['effective_config'] == a.attrs['effective_config']" \
  && ok "effective_config used as a CONFIG.ini file: same data, same effective_config" || bad "effective_config as a file"

# ---- 5. autobal plot and the one-liner -----------------------------------------------------------
declare -A kinds=([roots]=roots [roots_phys]=roots [critical]=critical_speeds [map]=stability_map
                  [map_every]=stability_map [ptrans]=transient [rotor]=transient [rotor2]=transient
                  [rstab]=stability [rsweep]=stability_sweep [rmap]=stability_map [rcampbell]=campbell)
# `autobal plot` runs its C code (archive checks, then Python) for three of the archives: the same
# path for each.  In the Release pass the other archives' pictures are drawn by the same Python code
# (autobal_plot.main) in one process (postprocess_check.py draw: one matplotlib import instead of one
# per archive), then every picture is checked; the sanitizer build (SANITIZE=1) leaves the pictures,
# Python and unchanged by the build, to the Release pass.
set -- $archives; plotted="$1 ${4:-} ${!#}"; set --
drawn=""
for a in $archives; do case " $plotted " in *" $a "*) ;; *) drawn="$drawn $a";; esac; done
pngs=""
for a in $plotted; do
  expect 0 "png/${a}_${kinds[$a]}.png" "$AUTOBAL" plot "$a.h5" -o png
done
for a in $archives; do pngs="$pngs png/${a}_${kinds[$a]}.png"; done
# the Campbell pictures follow each mode through crossings (track_modes in autobal_plot.py)
track=""
[ -n "$stab" ] && track="+ tracking $TOOLS rcampbell.h5 + tracking $TOOLS rcampbell_x.h5 decoupled"
py draw "$TOOLS" png $(for a in $drawn; do printf '%s.h5:png/%s_%s.png ' "$a" "$a" "${kinds[$a]}"; done) + png $pngs $track
[ -n "$stab" ] && expect 0 "png/rcampbell_x_campbell.png" "$AUTOBAL" plot rcampbell_x.h5 -o png
# ensemble archives: a basin map, P(balance) and the time to balance, for grids and random samples
if "$AUTOBAL" rotor ensemble --help >/dev/null 2>&1; then
  expect 0 "" "$AUTOBAL" rotor ensemble --set ensemble.n1=6 --set ensemble.n2=6 --set transient.t_end=3 -o rens.h5 -q
  expect 0 "" "$AUTOBAL" rotor ensemble --set ensemble.mode=random --set ensemble.samples=30 --set transient.t_end=3 -o rensr.h5 -q
  expect 0 "" "$AUTOBAL" pendulum ensemble --set ensemble.param1=R_w --set ensemble.min1=1 --set ensemble.max1=4 \
    --set ensemble.n1=12 --set ensemble.n2=6 -o pens.h5 -q
  expect 0 "" "$AUTOBAL" pendulum ensemble --set ensemble.n1=4 --set ensemble.n2=4 --set ensemble.max_members=9 -o pens_part.h5 -q
  # as above: the C path of plot twice, the other pictures drawn in the checks' process (Release)
  for a in rens pens_part; do
    expect 0 "png/${a}_ensemble.png" "$AUTOBAL" plot "$a.h5" -o png
  done
  py draw "$TOOLS" png rensr.h5:png/rensr_ensemble.png pens.h5:png/pens_ensemble.png \
    + ensemble_plot "$TOOLS" png rens.h5 rensr.h5 pens.h5 pens_part.h5
else
  echo "note: 'autobal rotor ensemble' is not registered: ensemble pictures not covered"
fi
expect 0 "one/x_critical_speeds.png" "$PY" "$TOOLS/autobal_plot.py" critical.h5 -o one --stem x
[ -f one/x_critical_speeds.png ] && ok "one-liner wrote one/x_critical_speeds.png" || bad "one-liner"
expect 4 "not an autobal archive" "$AUTOBAL" plot foreign.h5 -o png
expect 4 "No such file" "$AUTOBAL" plot missing.h5
"$PY" -c "import h5py; h = h5py.File('empty.h5', 'w'); h.attrs['Conventions'] = 'autobal-1'"
expect 3 "nothing to draw" "$AUTOBAL" plot empty.h5 -o png
AUTOBAL_PYTHON=/nonexistent/python3 "$AUTOBAL" plot roots.h5 -o png >out.txt 2>err.txt; rc=$?
[ $rc -eq 7 ] && grep -q "/nonexistent/python3" err.txt && ok "plot with a missing interpreter: exit 7 naming it" || { bad "missing interpreter gave $rc"; cat err.txt; }
(cd png && "$AUTOBAL" plot ../ptrans.h5 -q) && [ -f png/ptrans_transient.png ] && ok "plot without -o writes to the current directory" || bad "plot without -o"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
