# tests/app/common.bash: the helpers of the app tests (not *.sh: not a test itself), sourced after the script has checked its
# environment (AUTOBAL, SCRATCH, ...):  . "$(dirname "$0")/common.bash"
# Sets here (this folder), empties SCRATCH and changes into it; counts pass and fail.
#   ok WHAT / bad WHAT        count and print a check
#   run CMD...                CMD must exit 0 (its output in out.txt, err.txt)
#   expect CODE NEEDLE CMD... CMD must exit CODE and print NEEDLE (stdout or stderr; "" for none)
#   expect_err CODE NEEDLE CMD...  the same, NEEDLE on stderr
#   finish                    print "N passed, M failed", exit status 0 only without failures
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH" && cd "$SCRATCH" || exit 1
fail=0; pass=0
ok()  { echo "ok   $*"; pass=$((pass+1)); }
bad() { echo "FAIL $*"; fail=$((fail+1)); }
run() { "$@" >out.txt 2>err.txt && ok "ran: $*" || { bad "exit $?: $*"; cat err.txt; }; }
expect() {
  local code=$1 needle=$2; shift 2
  "$@" >out.txt 2>err.txt; local rc=$?
  if [ "$rc" -ne "$code" ]; then bad "exit $rc (want $code): $*"; cat err.txt; return; fi
  if [ -n "$needle" ] && ! grep -qF -- "$needle" err.txt out.txt; then bad "no '$needle' in output of: $*"; cat out.txt err.txt; return; fi
  ok "exit $code${needle:+ and '$needle'}: $*"
}
expect_err() {
  local code=$1 needle=$2; shift 2
  "$@" >out.txt 2>err.txt; local rc=$?
  [ $rc -eq "$code" ] && grep -qF -- "$needle" err.txt && ok "exit $code '$needle': $*" || { bad "exit $rc (want $code '$needle'): $*"; cat err.txt; }
}
finish() { echo "$pass passed, $fail failed"; [ "$fail" -eq 0 ]; exit $?; }
