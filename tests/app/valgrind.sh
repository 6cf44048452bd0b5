#!/usr/bin/env bash
# App test: valgrind memcheck finds no leak and no error in the apps on the default examples
# (and on an error path).  Skipped in the sanitizer build (ASan and valgrind do not mix).
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}"
if [ "${SANITIZE:-0}" = "1" ]; then echo "sanitizer build: valgrind test skipped"; echo "0 passed, 0 failed"; exit 0; fi
if ! command -v valgrind >/dev/null; then echo "FAIL valgrind not installed (scripts/deps.sh installs it)"; exit 1; fi
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH" && cd "$SCRATCH" || exit 1
fail=0; pass=0
vg() {
  local want=$1; shift
  valgrind --quiet --suppressions="$here/valgrind.supp" --leak-check=full --show-leak-kinds=definite,indirect,possible --errors-for-leak-kinds=definite,indirect,possible \
    --error-exitcode=99 "$@" >out.txt 2>vg.txt
  local rc=$?
  if [ $rc -eq "$want" ]; then echo "ok   valgrind clean (exit $rc): ${*#$AUTOBAL }"; pass=$((pass+1));
  else echo "FAIL valgrind exit $rc (want $want): $*"; cat vg.txt | head -40; fail=$((fail+1)); fi
}
vg 0 "$AUTOBAL" rotor transient --set transient.t_end=2 -o r.h5
vg 0 "$AUTOBAL" rotor transient --set transient.t_end=0.5 --set transient.frame=rotating --json
vg 0 "$AUTOBAL" pendulum roots -o p.h5
vg 0 "$AUTOBAL" pendulum critical --set critical.n_Rm=50 -o c.h5
vg 0 "$AUTOBAL" pendulum map --set map.n_Rm=30 --set map.n_Rw=30 --set map.threads=1 -o m.h5
vg 0 "$AUTOBAL" info p.h5
vg 0 "$AUTOBAL" info r.h5 --json
vg 0 "$AUTOBAL" rerun p.h5 -o p2.h5
# values with units (UDUNITS-2), configuration comments, the engineering summary, a re-run of it
printf '; a comment\n[rotor]\nomega = 3000 rpm ; running speed\n[plane1]\nunbalance = 2000 g mm\n[balance]\ngrade = G2.5\n[transient]\nt_end = 100 ms\n' > u.ini
vg 0 "$AUTOBAL" rotor transient u.ini -o u.h5 --json
vg 0 "$AUTOBAL" rerun u.h5 -o u2.h5
vg 3 "$AUTOBAL" rotor transient --set "rotor.omega=3 kg"
printf "not an archive\n" > junk.h5
vg 4 "$AUTOBAL" info junk.h5
vg 3 "$AUTOBAL" rotor transient --set plane1.ball_radius=-1,1
vg 4 "$AUTOBAL" pendulum roots -o p.h5
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
