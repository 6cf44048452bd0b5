#!/usr/bin/env bash
# App test: the command line a new user meets (issue 13): "did you mean" for models, actions and
# commands; `autobal MODEL --help` and `autobal help ...`; --set without '=' or without a section;
# range errors naming the broken bound; clean one-line file errors (no HDF5 error stack); the
# parameter table of `rotor sweep/map --help` against what the program accepts and uses; and the
# documentation every help text points to (docs/rotor.md, docs/pendulum.md, docs/units.md,
# nothing outside the repository).
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${DATA:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
DOCS=$(cd "$DATA/../docs" 2>/dev/null && pwd)
A=$AUTOBAL
run() { timeout -s KILL 120 "$@" >out.txt 2>err.txt; }
# expect CODE "needle" ... -- command...: exit code and every needle in stdout or stderr
expect() {
  local code=$1; shift; local needles=()
  while [ "$1" != "--" ]; do needles+=("$1"); shift; done; shift
  run "$@"; local rc=$? n
  if [ "$rc" -ne "$code" ]; then bad "exit $rc (want $code): ${*#$A }"; head -c 600 err.txt; return 1; fi
  for n in "${needles[@]}"; do
    if ! grep -qF -- "$n" err.txt out.txt; then bad "no '$n' in the output of: ${*#$A }"; head -c 600 err.txt; return 1; fi
  done
  ok "exit $code$(printf " '%s'" "${needles[@]}"): ${*#$A }"
}
# the error is exactly one line on stderr, nothing on stdout
one_line() {
  if [ "$(wc -l <err.txt)" -eq 1 ] && [ ! -s out.txt ]; then ok "  ... one line on stderr, nothing on stdout"
  else bad "  ... want one line on stderr and an empty stdout, got:"; cat err.txt out.txt; fi
}

# ---- did you mean ---------------------------------------------------------------------------
expect 2 "unknown action 'transiant' for model 'rotor'; did you mean 'transient'?" -- "$A" rotor transiant
one_line
expect 2 "unknown model or command 'roter'; did you mean 'rotor'?" -- "$A" roter transient
one_line
expect 2 "did you mean 'pendulum'?" -- "$A" pendulm roots
expect 2 "did you mean 'stability'?" -- "$A" rotor stabilty
expect 2 "did you mean 'info'?" -- "$A" inof x.h5
expect 2 "did you mean 'rotor'?" -- "$A" Rotor transient                       # case
expect 2 "did you mean 'autobal rotor transient'?" -- "$A" transient rotor     # the action first
expect 2 "did you mean 'autobal rotor campbell'?" -- "$A" pendulum campbell    # another model's action
expect 2 "did you mean 'transient'?" -- "$A" rotor transiant --help            # --help does not hide it
expect 2 "did you mean 'rotor'?" -- "$A" help roter
# nothing close: the names to choose from instead of a guess
expect 2 "unknown action 'xyz' for model 'rotor' (actions: transient, stability, sweep, map, campbell, ensemble" -- "$A" rotor xyz
expect 2 "unknown model or command 'qqqq' (one of: pendulum, rotor, info, rerun, plot, help" -- "$A" qqqq
# every action of every command listed by `autobal --help`, with its first or last letter dropped
# (one edit) or, for actions of 4 letters or more, two neighbours swapped (two edits), is
# suggested back
"$A" --help > usage.txt
sed -n '/^commands:/,/^$/p' usage.txt | awk 'NF >= 2 && $1 != "commands:" {print $1, $2}' > names.txt
awk '$1 == "rotor" || $1 == "pendulum"' names.txt > actions.txt
[ "$(wc -l < actions.txt)" -ge 10 ] && ok "autobal --help lists $(wc -l < actions.txt) model actions" || bad "actions listed: $(cat actions.txt)"
nt=0; nbad=0
while read -r model action; do
  typos=("${action:1}" "${action:0:${#action}-1}")
  [ ${#action} -ge 4 ] && typos+=("${action:1:1}${action:0:1}${action:2}" "${action:0:2}${action:3:1}${action:2:1}${action:4}")
  for typo in "${typos[@]}"; do
    [ "$typo" = "$action" ] && continue
    grep -qx "$model $typo" actions.txt && continue
    nt=$((nt+1))
    run "$A" "$model" "$typo"; rc=$?
    if [ $rc -ne 2 ] || ! grep -q "did you mean .*'$action'" err.txt; then nbad=$((nbad+1)); echo "  $model $typo: exit $rc: $(cat err.txt)"; fi
  done
done < actions.txt
[ $nbad -eq 0 ] && ok "$nt typos of the actions: each suggests its action (exit 2)" || bad "$nbad of $nt typos not suggested back"

# ---- autobal MODEL --help, autobal MODEL, autobal help ... --------------------------------------
for model in rotor pendulum; do
  expect 0 "usage: autobal $model <action>" -- "$A" "$model" --help
  cp out.txt "model_$model.txt"
  # every action of the model, one line each: "  ACTION   SUMMARY" with the summary of `autobal --help`
  miss=0
  while read -r m action; do
    [ "$m" = "$model" ] || continue
    summary=$(grep -E "^  $model $action +" usage.txt | sed -E "s/^  $model $action +//")
    n=$(grep -cE "^  $action +" "model_$model.txt")
    if [ "$n" -ne 1 ] || ! grep -qF "$summary" "model_$model.txt"; then miss=$((miss+1)); echo "  $model $action: $n lines"; fi
  done < actions.txt
  [ $miss -eq 0 ] && ok "autobal $model --help lists each action of $model once, with its summary" || bad "autobal $model --help: $miss actions wrong"
  others=$(grep -cE "^  (transient|stability|sweep|map|campbell|ensemble|design|roots|critical) " "model_$model.txt")
  [ "$others" -eq "$(grep -c "^$model " actions.txt)" ] && ok "  ... and no other model's actions" || bad "autobal $model --help lists $others actions"
  run "$A" "$model"; rc=$?
  if [ $rc -eq 2 ] && cmp -s err.txt "model_$model.txt" && [ ! -s out.txt ]; then ok "autobal $model alone: the same on stderr, exit 2"
  else bad "autobal $model alone: exit $rc"; fi
  run "$A" help "$model"
  cmp -s out.txt "model_$model.txt" && ok "autobal help $model = autobal $model --help" || bad "autobal help $model differs"
done
# autobal help CMD = autobal CMD --help, for every command of `autobal --help`
nd=0; nc=0
while read -r w1 w2; do
  case "$w2" in FILE.h5*) set -- "$w1" ;; *) set -- "$w1" "$w2" ;; esac
  nc=$((nc+1))
  "$A" "$@" --help > h1.txt 2>&1; r1=$?
  "$A" help "$@" > h2.txt 2>&1; r2=$?
  if [ $r1 -ne 0 ] || [ $r2 -ne 0 ] || ! cmp -s h1.txt h2.txt || ! grep -q "^usage: autobal $*" h1.txt; then
    nd=$((nd+1)); echo "  autobal help $*: exit $r2, autobal $* --help: exit $r1"; fi
done < names.txt
[ $nc -ge 14 ] && [ $nd -eq 0 ] && ok "autobal help CMD = autobal CMD --help for all $nc commands" || bad "$nd of $nc help texts differ"
expect 0 "usage: autobal <model> <action>" -- "$A" help
cmp -s out.txt usage.txt && ok "autobal help = autobal --help" || bad "autobal help differs from autobal --help"
expect 2 "unexpected argument 'extra'" -- "$A" help rotor transient extra

# ---- --set -----------------------------------------------------------------------------------
expect 2 "--set 'rotor.omega': '=' is missing" "--set SECTION.KEY=VALUE" "here --set rotor.omega=300" -- "$A" rotor transient --set rotor.omega 300
one_line
expect 2 "'=' is missing" "--set SECTION.KEY=VALUE" -- "$A" rotor transient --set=rotor.omega
expect 2 "--set 'omega=300': the section is missing" "--set SECTION.KEY=VALUE" "SECTION.omega=300" -- "$A" rotor transient --set omega=300
one_line
expect 2 "the key is missing" -- "$A" rotor transient --set rotor.=300

# ---- range errors: the broken bound first, the value as given ------------------------------------
expect 3 "parameter R_m = 0.7 is too large: must be < 0.5 (allowed range (0, 0.5))" -- "$A" pendulum roots --set pendulum.R_m=0.7
one_line
expect 3 "parameter R_m = 0 is too small: must be > 0 (allowed range (0, 0.5))" -- "$A" pendulum roots --set pendulum.R_m=0
expect 3 "parameter k = 1.0000001 is too large: must be <= 1 (allowed range [0, 1])" -- "$A" pendulum roots --set pendulum.k=1.0000001
expect 3 "is too small: must be > 0 kg" -- "$A" rotor transient --set rotor.M_k=-6
expect 3 "is too small: must be >= 0 N/m" -- "$A" rotor transient --set supports.c_Lx=-1

# ---- file errors: one clean line, exit 4 ---------------------------------------------------------
# stderr must not carry HDF5's error stack ("HDF5-DIAG ...", "#000: ..." frames, "H5Fopen"...)
clean_file_error() {  # clean_file_error "reason or empty" -- command...
  local reason=$1; shift 2
  run "$@"; local rc=$?
  if [ $rc -ne 4 ]; then bad "exit $rc (want 4): ${*#$A }"; cat err.txt; return; fi
  if grep -qE "HDF5-DIAG|#[0-9]{3}:|H5[A-Z][a-z_]*\(|major:|minor:" err.txt; then bad "HDF5 error stack on stderr: ${*#$A }"; cat err.txt; return; fi
  if [ "$(wc -l <err.txt)" -ne 1 ] || [ -s out.txt ]; then bad "not one line: ${*#$A }"; cat err.txt out.txt; return; fi
  if [ -n "$reason" ] && ! grep -qF "$reason" err.txt; then bad "no '$reason': ${*#$A }"; cat err.txt; return; fi
  case "$reason" in "cannot create"*)  # the OS reason says it all: no HDF5 text in the message
    if grep -q "HDF5" err.txt; then bad "HDF5 text in: ${*#$A }"; cat err.txt; return; fi ;; esac
  ok "exit 4, one line$( [ -n "$reason" ] && echo ", '$reason'"): ${*#$A } -> $(cat err.txt)"
}
# the OS reason alone when there is one (the library's HDF5 text only without one)
clean_file_error "cannot create archive '/nonexistent-autobal/dir/x.h5': No such file or directory" -- \
  "$A" rotor transient -o /nonexistent-autobal/dir/x.h5
clean_file_error "cannot create archive '/proc/autobal-x.h5': " -- "$A" pendulum roots -o /proc/autobal-x.h5  # not creatable, root too
echo plain > afile
clean_file_error "cannot create archive 'afile/x.h5': Not a directory" -- "$A" pendulum roots -o afile/x.h5   # a file as a directory
mkdir ro && chmod 555 ro
if [ "$(id -u)" -ne 0 ]; then
  clean_file_error "cannot create archive 'ro/x.h5': Permission denied" -- "$A" pendulum roots -o ro/x.h5
else
  echo "skip a read-only directory (root writes into it; /proc stands for it above)"
fi
clean_file_error "No such file or directory" -- "$A" info missing.h5
clean_file_error "is not an HDF5 file" -- "$A" info afile
"$PY" -c "import sys,random; r=random.Random(3); sys.stdout.buffer.write(b'\x89HDF\r\n\x1a\n' + bytes(r.randrange(256) for _ in range(4000)))" > fake.h5
clean_file_error "fake.h5" -- "$A" info fake.h5                                  # an HDF5 signature, then garbage
clean_file_error "No such file or directory" -- "$A" rerun missing.h5 -o new.h5
ls | grep -q partial && bad "temporary files left: $(ls | grep partial)" || ok "no temporary files left"

# ---- rotor sweep/map --help: the parameter table against the program ------------------------------
"$A" rotor sweep --help > sweep_help.txt
"$A" rotor map --help > map_help.txt
sed -n '/^parameters (unit/,/^$/p' sweep_help.txt | awk '/^  [A-Za-z_]+ +[^ ]+ +/ && $1 != "any" {print $1, $2}' > table.txt
sed -n '/^parameters (unit/,/^$/p' map_help.txt | awk '/^  [A-Za-z_]+ +[^ ]+ +/ && $1 != "any" {print $1, $2}' > table_map.txt
[ "$(wc -l < table.txt)" -ge 6 ] && cmp -s table.txt table_map.txt && ok "rotor sweep and rotor map --help list the same $(wc -l < table.txt) parameters with units" \
  || { bad "parameter tables"; cat table.txt table_map.txt; }
# the named parameters the program accepts (its message for a bad name) are the names of the table
"$A" rotor sweep --set sweep.param=bogus > /dev/null 2> err.txt
accepted=$(sed -n "s/.*is not a parameter: one of \(.*\), a key of .*/\1/p" err.txt | tr -d ' ' | tr ',' '\n' | sort | tr '\n' ' ')
listed=$(awk '{print $1}' table.txt | sort | tr '\n' ' ')
[ -n "$accepted" ] && [ "$accepted" = "$listed" ] && ok "the table lists exactly the accepted parameters: $listed" \
  || bad "accepted '$accepted' vs listed '$listed'"
# units and default ranges: what the sweep reports (--json) against the table and the defaults of
# `rotor sweep --help` (ball_damping 0.1, ball_mass 0.05, m0 0.02, omega 500; natural frequencies
# at rest from `rotor campbell`)
"$A" rotor campbell --json > campbell.json
for p in $(awk '{print $1}' table.txt); do
  "$A" rotor sweep --json --set sweep.param="$p" --set sweep.n=2 > "sweep_$p.json" 2> err.txt || bad "rotor sweep param=$p: $(cat err.txt)"
done
"$PY" - table.txt <<'EOF' && ok "units and default ranges of the table = what the sweeps use" || bad "units or default ranges"
import json, sys
table = dict(line.split() for line in open(sys.argv[1]))
f = json.load(open("campbell.json"))["natural_frequency_undamped"]
want = {  # the defaults stated in the help, with the default model of `rotor sweep --help`
    "omega": (0.05 * f[0], 4 * max(f[3], 500.0)),
    "ball_damping": (0.0, 10 * 0.1 + 0.001),
    "ball_mass": (0.1 * 0.05, 4 * 0.05),
    "stiffness_scale": (0.25, 4.0),
    "damping_scale": (0.0, 4.0),
    "unbalance_mass": (0.0, 4 * 0.02 + 0.001),
    "anisotropy": (0.25, 4.0),  # isotropic default: c_Ly/c_Lx = 1
    "C_over_A": (0.25 * 0.03 / 0.16, 4 * 0.03 / 0.16),  # C_p / (A_k + A_p) of data/rotor_default.ini
}
bad = 0
for p, unit in table.items():
    d = json.load(open("sweep_%s.json" % p))
    lo, hi = want[p]
    good = d["param"] == p and d["unit"] == unit and abs(d["min"] - lo) <= 1e-12 * max(1, abs(lo)) \
        and abs(d["max"] - hi) <= 1e-12 * max(1, abs(hi))
    print("%-4s %-16s unit %-6s (table %-6s) min %.10g (want %.10g) max %.10g (want %.10g)"
          % ("ok" if good else "FAIL", p, d["unit"], unit, d["min"], lo, d["max"], hi))
    bad += not good
sys.exit(bad != 0)
EOF
expect 0 "" -- "$A" rotor map --set map.param1=stiffness_scale --set map.param2=unbalance_mass --set map.n1=2 --set map.n2=2 --json
grep -q '"param1":"stiffness_scale"' out.txt && ok "rotor map takes table parameters as axes" || bad "rotor map axes: $(cat out.txt)"

# ---- the documentation the help texts point to -----------------------------------------------------
"$A" pendulum --help > help_pendulum.txt; "$A" rotor --help > help_rotor.txt
while read -r w1 w2; do
  case "$w2" in FILE.h5*) "$A" "$w1" --help > "help_${w1}.txt" ;; *) "$A" "$w1" "$w2" --help > "help_${w1}_${w2}.txt" ;; esac
done < names.txt
cp usage.txt help_top.txt
"$PY" - "$DOCS" help_*.txt <<'EOF' && ok "every help text names its docs/*.md and docs/units.md; equation numbers come with their document" || bad "help texts and documentation"
import os, re, sys
docs, files = sys.argv[1], sys.argv[2:]
bad = 0
eq = re.compile(r"eqs?\. (\(\d+(?:\.\d+)?\)(?:(?:-| and )\(\d+(?:\.\d+)?\))*) in (docs/\w+\.md)")
for fn in files:
    text = open(fn).read()
    name = fn[5:-4]
    need = ["docs/units.md"]
    if name == "top": need += ["docs/rotor.md", "docs/pendulum.md"]
    elif name.startswith("rotor"): need += ["docs/rotor.md"]
    elif name.startswith("pendulum"): need += ["docs/pendulum.md"]
    else: need += ["docs/rotor.md", "docs/pendulum.md"]
    flat = " ".join(text.split())
    problems = ["no " + n for n in need if n not in flat]
    if name.startswith("rotor") and "docs/pendulum.md" in flat: problems.append("a rotor text points to docs/pendulum.md")
    if name.startswith("pendulum") and "docs/rotor.md" in flat: problems.append("a pendulum text points to docs/rotor.md")
    for bad_ref in ("http", "www.", "spec ", "/spec", "the paper", "figure "):
        if bad_ref in flat: problems.append("points outside the repository: %r" % bad_ref)
    # every equation number "(3.14)", "(2)-(3)" is part of "eq(s). (...) in docs/X.md"
    covered = set()
    for m in eq.finditer(flat):
        covered.update(range(m.start(1), m.end(1)))
        if docs and os.path.isdir(docs):
            path = os.path.join(docs, os.path.basename(m.group(2)))
            if os.path.exists(path):
                body = open(path).read()
                for num in re.findall(r"\((\d+(?:\.\d+)?)\)", m.group(1)):
                    # "(3.14)", "\tag{3.14}" or "eq. 3.14" / "equation 3.14" in the document
                    n = re.escape(num)
                    if not re.search(r"\(%s\)|\{%s\}|(?i:eqs?\.|equations?)\s+%s(?![\d.]\d)" % (n, n, n), body):
                        problems.append("(%s) not in %s" % (num, m.group(2)))
    for m in re.finditer(r"(?<!\^)\(\d+(?:\.\d+)?\)", flat):  # not R_m^(1)
        if m.start() not in covered: problems.append("bare equation number %s: ...%s..." % (m.group(0), flat[max(0, m.start() - 40):m.end() + 10]))
    print("%-4s %-24s %s" % ("ok" if not problems else "FAIL", name, "; ".join(problems)))
    bad += bool(problems)
for d in ("rotor.md", "pendulum.md", "units.md"):
    print("     docs/%s %s" % (d, "present: equation numbers checked against it" if docs and os.path.exists(os.path.join(docs, d)) else "not in this tree: equation numbers not checked against it"))
sys.exit(bad != 0)
EOF

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
