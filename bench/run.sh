#!/usr/bin/env bash
# Build bench_pendulum (Release, standalone CMake project in bench/) and run
# the autobal-vs-SciPy comparison; prints a table.  Extra arguments go to
# pendulum_scipy.py (e.g. --t1 100 --tols 1e-8).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${AUTOBAL_BENCH_BUILD:-$here/../build-bench}
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" --target bench_pendulum > /dev/null
exec /usr/bin/python3 "$here/pendulum_scipy.py" --bench "$build/bench_pendulum" "$@"
