#!/usr/bin/env bash
# examples/embed_study.c against the command line: the program's archives equal, dataset for
# dataset bit for bit and attribute for attribute (provenance left out), those of
# `autobal rotor transient|stability` with the same inputs given as --set overrides of the
# built-in default rotor; `autobal info` and `autobal rerun` read them; a negative control shows
# that the comparison sees a difference of one input.
set -u
: "${EMBED:?}" "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH" && cd "$SCRATCH" || exit 1
fail=0; pass=0
ok()  { echo "ok   $*"; pass=$((pass+1)); }
bad() { echo "FAIL $*"; fail=$((fail+1)); }

"$EMBED" . >embed.txt 2>embed.err && ok "embed_study ran (exit 0)" || { bad "embed_study failed"; cat embed.txt embed.err; }
cat embed.txt
grep -q "cancelled transient: AUTOBAL_ECANCELLED" embed.txt && ok "cancellation from the progress callback" \
  || bad "no cancellation line"
# the same inputs on the command line: the values embed_study.c fills in that differ from the
# built-in default rotor (docs/rotor.md), and its transient options
same_inputs=(--set rotor.omega=400 --set plane1.m0=0.03)
"$AUTOBAL" rotor transient "${same_inputs[@]}" --set transient.t_end=1 --set transient.dt_out=0.002 \
  --set balance.grade=G6.3 -o cli_transient.h5 --quiet --no-progress && ok "autobal rotor transient" || bad "autobal rotor transient"
"$AUTOBAL" rotor stability "${same_inputs[@]}" -o cli_stability.h5 --quiet --no-progress \
  && ok "autobal rotor stability" || bad "autobal rotor stability"
"$PY" "$here/archive_same.py" --provenance embed_transient.h5 cli_transient.h5 \
  && ok "transient archive = the CLI's" || bad "transient archive differs from the CLI's"
"$PY" "$here/archive_same.py" --provenance embed_stability.h5 cli_stability.h5 \
  && ok "stability archive = the CLI's" || bad "stability archive differs from the CLI's"
# negative control: one input different (the unbalance 31 g instead of 30 g)
"$AUTOBAL" rotor stability --set rotor.omega=400 --set plane1.m0=0.031 -o cli_other.h5 --quiet --no-progress
if "$PY" "$here/archive_same.py" --provenance embed_stability.h5 cli_other.h5 >other.txt; then
  bad "the comparison did not see plane1.m0 = 0.031 vs 0.03"
else
  grep -q "m0" other.txt && ok "the comparison sees a different m0" || { bad "difference not named"; cat other.txt; }
fi
# the programs that read archives work on the embedded ones
"$AUTOBAL" info embed_transient.h5 >info_t.txt 2>&1 && ok "autobal info reads the transient archive" \
  || { bad "autobal info on the transient archive"; cat info_t.txt; }
"$AUTOBAL" info embed_stability.h5 >info_s.txt 2>&1 && ok "autobal info reads the stability archive" \
  || { bad "autobal info on the stability archive"; cat info_s.txt; }
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
