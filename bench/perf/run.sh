#!/usr/bin/env bash
# Build the performance benchmarks (Release, standalone CMake project in
# bench/perf/) and run them with the NumPy references side by side; prints
# the measurements and a table of ratios against the targets of issue 7.
# Not part of CTest.
#
#   bench/perf/run.sh                 everything (about a minute)
#   bench/perf/run.sh --quick         fewer repetitions, no 65-k NumPy map
#   bench/perf/run.sh --only maps,roots   a subset of roots,maps,scaling,hdf5,rhs,sundials
#   bench/perf/run.sh --only callgrind    instruction counts per map point (valgrind)
#
# Build directory: $AUTOBAL_PERF_BUILD (default: build-perf-bench next to bench/).
# SUNDIALS (Debian libsundials-dev) is used when CMake finds it.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${AUTOBAL_PERF_BUILD:-$here/../../build-perf-bench}
case "${1:-}" in
  -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
esac
"$here/../../scripts/deps.sh" --bench   # Debian packages (SciPy, SUNDIALS, ...), if missing
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" > /dev/null
sund=()
if [ -x "$build/bench_sundials" ]; then sund=(--sundials "$build/bench_sundials"); fi
OPENBLAS_NUM_THREADS=1 /usr/bin/python3 "$here/perf.py" --bench "$build/bench_perf" "${sund[@]}" "$@"
