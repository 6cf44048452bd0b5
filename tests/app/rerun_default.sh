#!/usr/bin/env bash
# App test: the default stepper of the transients changed in 0.2.0 (rk8pd with steps cut at the output
# times -> dop853 with output = dense6).  An archive written with the old default must still be re-run
# with rk8pd, bit for bit, not with today's default.  autobal before the change records the stepper and
# output it used as given keys ("stepper = rk8pd", "output = dense" in effective_config, checked against
# archives of main 0dd64b7 written with no configuration: their effective_config is byte for byte the one
# of a run given `--set transient.stepper=rk8pd --set transient.output=dense`), so such a run stands for
# an old-default archive here.  Checked: the new default is dop853/dense6 (and its numbers differ from
# rk8pd's, else the test could not fail); the re-run of the rk8pd archive reproduces every dataset bit for
# bit and records stepper rk8pd; the same for a dop853/dense (contd8) archive, the 0.2.0 option before
# dense6 became the default.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

same() { # same A.h5 B.h5 GROUP STEPPER: every dataset of A equal (bytes) in B; GROUP's stepper attribute
  "$PY" - "$@" <<'PY'
import h5py, sys
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
def walk(g, out):
    for k, v in g.items():
        if isinstance(v, h5py.Dataset): out[v.name] = v
        else: walk(v, out)
A, B = {}, {}; walk(a, A); walk(b, B)
bad = [k for k in A if k not in B or A[k].dtype != B[k].dtype or A[k][()].tobytes() != B[k][()].tobytes()]
st = b[sys.argv[3]].attrs["stepper"]
st = st.decode() if isinstance(st, bytes) else st
print(f"{len(A)} datasets, differ: {bad[:5]}, stepper {st}")
sys.exit(0 if not bad and set(A) == set(B) and st == sys.argv[4] and len(A) > 10 else 1)
PY
}
differs() { # differs A.h5 B.h5 DATASET: the two runs' DATASET differ (so a wrong stepper would be seen)
  "$PY" -c "import h5py,sys; a,b=(h5py.File(f,'r')[sys.argv[3]][()] for f in sys.argv[1:3]); sys.exit(0 if a.tobytes()!=b.tobytes() else 1)" "$@"
}
attr() { "$PY" -c "import h5py,sys; v=h5py.File(sys.argv[1],'r')[sys.argv[2]].attrs[sys.argv[3]]; print(v.decode() if isinstance(v,bytes) else v)" "$@"; }

# MODEL T_END DATASET: the default is dop853/dense6, its numbers differ from rk8pd's (DATASET), and an
# rk8pd archive (the old default) re-runs with rk8pd bit for bit
old_default() {
  local m=$1 tend=$2 ds=$3 p=${1:0:1}
  run "$AUTOBAL" "$m" transient --set transient.t_end="$tend" -o "${p}new.h5" -q
  [ "$(attr "${p}new.h5" "/$m/transient" stepper)/$(attr "${p}new.h5" "/$m/transient" output)" = dop853/dense6 ] \
    && ok "$m: the default is dop853, output dense6" || bad "$m: the default is not dop853/dense6"
  run "$AUTOBAL" "$m" transient --set transient.t_end="$tend" --set transient.stepper=rk8pd --set transient.output=dense \
    -o "${p}old.h5" -q
  differs "${p}new.h5" "${p}old.h5" "/$m/transient/$ds" && ok "$m: rk8pd and the default differ" \
    || bad "$m: rk8pd = the default"
  run "$AUTOBAL" rerun "${p}old.h5" -o "${p}re.h5" -q
  same "${p}old.h5" "${p}re.h5" "/$m/transient" rk8pd && ok "$m: the rk8pd archive re-run with rk8pd, bit for bit" \
    || bad "$m: the rk8pd archive was not reproduced by rerun"
}

# rotor: 4 revolutions of the default machine; pendulum: tau in [0, 10]
old_default rotor 0.05 state_phi_1
run "$AUTOBAL" rotor transient --set transient.t_end=0.05 --set transient.stepper=dop853 --set transient.output=dense -o r7.h5 -q
run "$AUTOBAL" rerun r7.h5 -o r7re.h5 -q
same r7.h5 r7re.h5 /rotor/transient dop853 && [ "$(attr r7re.h5 /rotor/transient output)" = dense ] \
  && ok "rotor: a dop853/dense archive re-run with contd8, bit for bit" || bad "rotor: dop853/dense archive not reproduced"
old_default pendulum 10 xi
finish
