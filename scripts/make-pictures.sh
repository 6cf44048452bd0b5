#!/usr/bin/env bash
# Regenerate the pictures committed in docs/ from fresh runs: every PNG is drawn by
# `autobal plot` (tools/autobal_plot.py, matplotlib, Debian's /usr/bin/python3) from an archive
# written a moment before by `autobal`, with the configurations in data/.
#
#   scripts/make-pictures.sh [BUILD_DIR]     (default: build; configured and built if needed)
#
# The archives are written to a temporary directory and deleted afterwards; set KEEP=DIR to
# keep them in DIR instead.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
case $build in /*) ;; *) build=$PWD/$build ;; esac
if [ ! -x "$build/apps/autobal" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" >/dev/null
fi
A=$build/apps/autobal
D=$root/data
out=$root/docs
mkdir -p "$out"
if [ -n "${KEEP:-}" ]; then work=$KEEP; mkdir -p "$work"; else work=$(mktemp -d); trap 'rm -rf "$work"' EXIT; fi
cd "$work"

# name of the picture in docs/  <-  command that writes the archive
pic() {
  local name=$1 kind=$2; shift 2
  "$@" -o "$name.h5" --force --quiet
  "$A" plot "$name.h5" -o png --quiet
  cp "png/${name}_${kind}.png" "$out/$name.png"
  echo "docs/$name.png  <-  autobal ${*:2}"
}

pic pendulum_critical_speeds critical_speeds "$A" pendulum critical
pic pendulum_map_k05         stability_map   "$A" pendulum map "$D/pendulum_default.ini" --set map.max_real=true --set map.n_Rm=150 --set map.n_Rw=150
pic pendulum_map_every_k     stability_map   "$A" pendulum map "$D/pendulum_map_every.ini"
pic pendulum_roots           roots           "$A" pendulum roots "$D/pendulum_default.ini"
pic pendulum_transient       transient       "$A" pendulum transient "$D/pendulum_transient.ini"
pic rotor_transient          transient       "$A" rotor transient "$D/rotor_default.ini"
pic rotor_transient_two_planes transient     "$A" rotor transient "$D/rotor_two_planes.ini"
# The rotor stability commands (apps/cmd_rotor_stability.c), when this autobal has them:
if "$A" rotor campbell --help >/dev/null 2>&1; then
  pic rotor_campbell         campbell        "$A" rotor campbell "$D/rotor_default.ini"
  # supports with l_L c_L = l_R c_R (and the same for h): translation and tilt decouple, and the
  # backward tilting mode crosses the translational pair (the picture follows it through)
  pic rotor_campbell_crossing campbell       "$A" rotor campbell "$D/rotor_default.ini" --set supports.l_R=0.2 \
      --set supports.c_Rx=1e5 --set supports.c_Ry=1e5 --set supports.h_Rx=100 --set supports.h_Ry=100
  pic rotor_stable_speeds    stability_sweep "$A" rotor sweep "$D/rotor_default.ini"
  pic rotor_stability        stability       "$A" rotor stability "$D/rotor_default.ini"
  pic rotor_stability_map    stability_map   "$A" rotor map "$D/rotor_default.ini"
else
  echo "note: this autobal has no 'rotor campbell|sweep|stability|map': those pictures are not made" >&2
fi
# Ensembles (apps/cmd_ensemble.c), when this autobal has them:
if "$A" rotor ensemble --help >/dev/null 2>&1; then
  pic rotor_ensemble         ensemble        "$A" rotor ensemble "$D/rotor_default.ini" --set ensemble.n1=32 \
      --set ensemble.n2=32 --set transient.t_end=30
  pic pendulum_ensemble      ensemble        "$A" pendulum ensemble "$D/pendulum_default.ini" --set ensemble.param1=R_w \
      --set ensemble.min1=1 --set ensemble.max1=4 --set ensemble.n1=61 --set ensemble.param2=psi --set ensemble.n2=24
else
  echo "note: this autobal has no 'rotor ensemble|pendulum ensemble': those pictures are not made" >&2
fi
