#!/usr/bin/env bash
# Install dependencies, build with warnings as errors, run the test suite,
# then build again with AddressSanitizer + UndefinedBehaviorSanitizer and run
# the same tests.  Usage: scripts/test.sh [--quick]   (--quick: no sanitizer pass)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DAUTOBAL_WERROR=ON
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs" -LE slow
if [ "${1:-}" != "--quick" ]; then
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DAUTOBAL_WERROR=ON -DAUTOBAL_SANITIZE=ON -DAUTOBAL_OPENMP=OFF
  cmake --build build-asan -j "$jobs"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE slow
fi
