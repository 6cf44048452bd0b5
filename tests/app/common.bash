# tests/app/common.bash: the helpers of the app tests (not *.sh: not a test itself), sourced after the script has checked its
# environment (AUTOBAL, SCRATCH, ...):  . "$(dirname "$0")/common.bash"
# Sets here (this folder), empties SCRATCH and changes into it; counts pass and fail.
#   ok WHAT / bad WHAT        count and print a check
#   run CMD...                CMD must exit 0 (its output in out.txt, err.txt)
#   expect CODE NEEDLE CMD... CMD must exit CODE and print NEEDLE (stdout or stderr; "" for none)
#   expect_err CODE NEEDLE CMD...  the same, NEEDLE on stderr
#   finish                    print "N passed, M failed", exit status 0 only without failures
#   caught PID SIG            wait (at most 20 s) until PID (or, for a `timeout` wrapper, its child)
#                             catches SIG, before a test sends it
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
# caught PID SIG: wait (at most 20 s) until the process PID catches SIG (its handler is installed: bit
# SIG - 1 of SigCgt in /proc/PID/status); when PID is a `timeout` wrapper, until its child does.  On a
# loaded machine a signal sent after a fixed delay can arrive while the program is still loading; it
# would then die of the default action (exit 128 + SIG) instead of stopping cleanly.  Returns at once
# where /proc is not there or the process has ended.
caught() {
  local pid=$1 num mask k c
  num=$(kill -l "$2")
  for k in $(seq 1 400); do
    case $(awk '/^State:/ {print $2}' "/proc/$pid/status" 2>/dev/null) in '' | Z) return 0 ;; esac
    if [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = timeout ]; then
      c=$(cat "/proc/$pid/task/$pid/children" 2>/dev/null)
      c=${c%% *}
      [ -n "$c" ] || { sleep 0.05; continue; }
    else
      c=$pid
    fi
    mask=$(awk '/^SigCgt:/ {print $2}' "/proc/$c/status" 2>/dev/null)
    [ -n "$mask" ] || return 0
    (( (16#$mask >> (num - 1)) & 1 )) && return 0
    sleep 0.05
  done
}
