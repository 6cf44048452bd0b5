#!/usr/bin/env bash
# Build the benchmarks (Release, standalone CMake project in bench/) and run
# the autobal-vs-SciPy comparisons; prints the tables.  Not part of CTest.
#
#   bench/run.sh                     pendulum, then rotor (default options)
#   bench/run.sh pendulum [ARGS...]  only the pendulum; ARGS go to pendulum_scipy.py
#                                    (e.g. --t1 50 --tols 1e-8)
#   bench/run.sh rotor [ARGS...]     only the rotor; ARGS go to rotor_scipy.py
#                                    (e.g. --balls 8 --tols 1e-8, --only rhs)
#   bench/run.sh runup [ARGS...]     run-up 0 -> 500 rad/s in 20 s (issue 15) and the constant-speed
#                                    rotor in the same run; ARGS go to runup_scipy.py (e.g. --quick,
#                                    --only runup); --before-commit REV also builds bench_rotor on the
#                                    library of git revision REV and times its constant-speed runs beside
#   bench/run.sh friction [ARGS...]  stiction (issue 16): friction vs frictionless per member and as a
#                                    256-member ensemble on 2 threads, SciPy with events at matched error,
#                                    and the constant-speed / run-up benches of the library before the
#                                    friction merge (found with git log; --before-commit REV to choose,
#                                    --no-before to skip); ARGS go to friction_scipy.py (e.g. --quick)
#   bench/run.sh contact [ARGS...]   stiction AND ball contact (issue 16): 20 mm balls, restitution 0.5 and 1;
#                                    per member and 256-member ensembles on 2 threads against the
#                                    frictionless ensemble, SciPy with gap events at matched error (one
#                                    member, e = 1); ARGS go to friction_scipy.py --contact (e.g. --quick,
#                                    --only member, --restitutions 0.5,1, --scipy-seed 5)
#   bench/run.sh design [N_POSITION [N_BALLS_MAX]] the design search (`autobal rotor design`) over 4
#                                    balancer parameters for the default machine: time, exact tests and
#                                    stability verdicts per second (N_POSITION = 1: 3 parameters, the position
#                                    fixed); N_BALLS_MAX >= 3: also 2..N_BALLS_MAX balls, against two balls;
#   bench/run.sh design two          the two-plane design (planes = 2) against the one-plane search
#   bench/run.sh dense [ARGS...]     output every quarter revolution (issue 20): dop853 on its continuous
#                                    extension vs exact hits (rk8pd, dop853) vs SciPy DOP853/LSODA/Radau
#                                    with t_eval, pendulum and rotor (2, 8 balls), at matched error of the
#                                    output points; archive (JSON) and work-precision plot; ARGS go to
#                                    dense_scipy.py (e.g. --cases pendulum --tols 1e-8, --from A.json)
#   bench/run.sh dense-default [ARGS...]  the evidence for the default output (dop853 dense6): error at
#                                    the output points against rk8pd at 1e-14 and the CLI's time, dense6 vs
#                                    dense (contd8) vs rk8pd exact vs dop853 exact, rtol 1e-6 .. 1e-12;
#                                    ARGS go to dense_default.py (e.g. --cases pendulum, --from A.json)
#   bench/run.sh dense-ratio REV [ARGS...]  the time of output every quarter revolution, out/none of the
#                                    CLI's transient, this library against bench_dense of git revision REV
#                                    (e.g. main), interleaved; ARGS go to dense_ratio.py (e.g. --rounds 7)
#   bench/run.sh issue20 REV [ARGS...] every target of issue 20 in one run: out/none (dense6, dense; this
#                                    library and REV interleaved, and instructions), the CLI vs SciPy DOP853
#                                    at matched error, the right-hand side's share of the bare integration
#                                    (callgrind and time); ARGS go to issue20.py (e.g. --out FILE.json)
#
# Build directory: $AUTOBAL_BENCH_BUILD (default: build-bench next to bench/).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${AUTOBAL_BENCH_BUILD:-$here/../build-bench}
what=all
if [ $# -gt 0 ]; then
  case "$1" in
    all|pendulum|rotor|runup|friction|contact|design|dense|dense-default|dense-ratio|issue20) what=$1; shift ;;
    -h|--help) sed -n '2,45p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run.sh: unknown benchmark '$1' (expected all, pendulum, rotor, runup, friction, contact, design, dense, dense-default, dense-ratio or issue20; see --help)" >&2
       exit 2 ;;
  esac
fi
if [ "$what" = all ] && [ $# -gt 0 ]; then
  echo "run.sh: options need a benchmark name first (run.sh pendulum ... or run.sh rotor ...)" >&2
  exit 2
fi
"$here/../scripts/deps.sh" --bench   # Debian packages (SciPy, SUNDIALS, ...), if missing
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
case "$what" in
  pendulum) targets=(bench_pendulum) ;;
  rotor|runup) targets=(bench_rotor) ;;
  friction) targets=(bench_rotor bench_friction) ;;
  contact) targets=(bench_rotor bench_friction) ;;
  design) targets=(bench_design) ;;
  dense|dense-default|dense-ratio|issue20) targets=(bench_dense) ;;
  all) targets=(bench_pendulum bench_rotor) ;;
esac
cmake --build "$build" --target "${targets[@]}" > /dev/null
py=/usr/bin/python3
if [ "$what" = dense-default ]; then
  exec "$py" "$here/dense_default.py" --bench "$build/bench_dense" "$@"
fi
if [ "$what" = dense ]; then
  exec "$py" "$here/dense_scipy.py" --bench "$build/bench_dense" "$@"
fi
if [ "$what" = dense-ratio ] || [ "$what" = issue20 ]; then
  [ $# -ge 1 ] || { echo "run.sh: $what needs a git revision (the reference, e.g. main)" >&2; exit 2; }
  rev=$(git -C "$here/.." rev-parse --short "$1^{commit}")
  shift
  old="$build-before-$rev"
  if [ ! -x "$old/build/bench_dense" ]; then
    rm -rf "$old"; mkdir -p "$old/src"
    git -C "$here/.." archive "$rev" | tar -x -C "$old/src"
    cmake -S "$old/src/bench" -B "$old/build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
    cmake --build "$old/build" --target bench_dense > /dev/null
  fi
  [ "$what" = issue20 ] && exec "$py" "$here/issue20.py" --bench "$build/bench_dense" --before "$old/build/bench_dense" "$@"
  exec "$py" "$here/dense_ratio.py" --bench "$build/bench_dense" --before "$old/build/bench_dense" "$@"
fi
# bench_rotor of the library at git revision $1 (built once, in $build-before-REV); prints its path
build_before() {
  local rev old
  rev=$(git -C "$here/.." rev-parse --short "$1^{commit}")
  old="$build-before-$rev"
  if [ ! -x "$old/build/bench_rotor" ]; then
    rm -rf "$old"; mkdir -p "$old/src"
    git -C "$here/.." archive "$rev" | tar -x -C "$old/src"
    cmake -S "$old/src/bench" -B "$old/build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
    cmake --build "$old/build" --target bench_rotor > /dev/null
  fi
  echo "$old/build/bench_rotor"
}
if [ "$what" = friction ]; then
  # the library before friction: the first parent of the merge of branch 'friction'
  merge=$(git -C "$here/.." log --merges --first-parent --format=%H --grep="^Merge branch 'friction'" -1)
  rev=${merge:+$merge^1}
  args=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --before-commit) [ $# -ge 2 ] || { echo "run.sh: --before-commit needs a git revision" >&2; exit 2; }
                       rev=$2; shift 2 ;;
      --no-before) rev=; shift ;;
      *) args+=("$1"); shift ;;
    esac
  done
  if [ -n "$rev" ]; then
    echo "library before friction: $(git -C "$here/.." log -1 --format='%h %s' "$rev^{commit}" | cut -c1-100)"
    args+=(--before "$(build_before "$rev")")
  fi
  cd "$here"
  exec "$py" "$here/friction_scipy.py" --bench-friction "$build/bench_friction" \
    --bench-rotor "$build/bench_rotor" ${args[@]+"${args[@]}"}
fi
if [ "$what" = contact ]; then
  cd "$here"
  exec "$py" "$here/friction_scipy.py" --contact --bench-friction "$build/bench_friction" \
    --bench-rotor "$build/bench_rotor" "$@"
fi
if [ "$what" = design ]; then
  exec "$build/bench_design" "$@"
fi
if [ "$what" = runup ]; then
  args=()
  while [ $# -gt 0 ]; do
    if [ "$1" = --before-commit ]; then
      [ $# -ge 2 ] || { echo "run.sh: --before-commit needs a git revision" >&2; exit 2; }
      rev=$(git -C "$here/.." rev-parse --short "$2^{commit}")
      old="$build-before-$rev"
      if [ ! -x "$old/build/bench_rotor" ]; then
        rm -rf "$old"; mkdir -p "$old/src"
        git -C "$here/.." archive "$rev" | tar -x -C "$old/src"
        cmake -S "$old/src/bench" -B "$old/build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
        cmake --build "$old/build" --target bench_rotor > /dev/null
      fi
      args+=(--before "$old/build/bench_rotor")
      shift 2
    else
      args+=("$1"); shift
    fi
  done
  exec "$py" "$here/runup_scipy.py" --bench "$build/bench_rotor" ${args[@]+"${args[@]}"}
fi
if [ "$what" = pendulum ] || [ "$what" = all ]; then
  "$py" "$here/pendulum_scipy.py" --bench "$build/bench_pendulum" "$@"
fi
if [ "$what" = all ]; then echo; fi
if [ "$what" = rotor ] || [ "$what" = all ]; then
  "$py" "$here/rotor_scipy.py" --bench "$build/bench_rotor" "$@"
fi
