#!/usr/bin/env bash
# Install dependencies, build with warnings as errors, run the test suite, build the MPI
# variant and run its ensemble test, then build again with AddressSanitizer + UndefinedBehaviorSanitizer and run
# the same tests.  Usage: scripts/test.sh [--quick]   (--quick: no sanitizer pass)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DAUTOBAL_WERROR=ON
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs" -LE slow
# The MPI variant (-DAUTOBAL_MPI=ON): only the program differs (the library stays serial), so the
# Release build above is switched to it, only apps/cmd_ensemble.c is recompiled and the program
# relinked (the library's and the program's other objects are kept), and the ensemble test runs, which then also runs the ensembles under `mpirun -np 1` and
# `-np 2` and compares archives; then the build is switched back (also when the test fails).
cmake -S . -B build -DAUTOBAL_MPI=ON
cmake --build build -j "$jobs" --target autobal_cli
mpi_rc=0
ctest --test-dir build --output-on-failure -R '^app_ensemble$' || mpi_rc=$?
cmake -S . -B build -DAUTOBAL_MPI=OFF
cmake --build build -j "$jobs" --target autobal_cli
[ "$mpi_rc" -eq 0 ] || exit "$mpi_rc"
if [ "${1:-}" != "--quick" ]; then
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DAUTOBAL_WERROR=ON -DAUTOBAL_SANITIZE=ON -DAUTOBAL_OPENMP=OFF
  cmake --build build-asan -j "$jobs"
  # test_derive* are SymPy/NumPy only and test_layers reads the source and the object files' symbols
  # (no compiled code of the project runs in them; about three minutes): the Release pass above runs them
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE slow -E '^(test_derive|test_layers$)'
fi
