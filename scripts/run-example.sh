#!/usr/bin/env bash
# Install dependencies, build autobal, and run the main job on the built-in
# default example.  Extra arguments go to `autobal`, e.g. --json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc 2>/dev/null || echo 2)" >/dev/null
exec build/apps/autobal rotor transient -o example.h5 --force "$@"
