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
# The MPI variant (-DAUTOBAL_MPI=ON): only the program differs, so build it and run the ensemble
# test, which then also runs the ensembles under `mpirun -np 1` and `-np 2` and compares archives.
cmake -S . -B build-mpi -G Ninja -DCMAKE_BUILD_TYPE=Release -DAUTOBAL_WERROR=ON -DAUTOBAL_MPI=ON
cmake --build build-mpi -j "$jobs" --target autobal_cli
ctest --test-dir build-mpi --output-on-failure -R '^app_ensemble$'
if [ "${1:-}" != "--quick" ]; then
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DAUTOBAL_WERROR=ON -DAUTOBAL_SANITIZE=ON -DAUTOBAL_OPENMP=OFF
  cmake --build build-asan -j "$jobs"
  # test_derive* are SymPy/NumPy only (no compiled code to sanitize; about two and a half minutes):
  # the Release pass above runs them
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE slow -E '^test_derive'
fi
