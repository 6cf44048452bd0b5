#!/usr/bin/env bash
# Install smoke test: install the build tree into a temporary prefix, then build and run
# consumer.c against it once with find_package (CMake) and once with pkg-config, as a legacy
# code would.  Usage: smoke.sh BUILD_DIR SCRATCH
set -eu
build=$1; scratch=$2; here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$scratch"; mkdir -p "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
echo "installed into $scratch/prefix"
cmake -S "$here" -B "$scratch/cmake-build" -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/cmake-build" >/dev/null
"$scratch/cmake-build/consumer"
echo "ok   find_package(autobal) consumer built and ran"
pcdir=$(dirname "$(find "$scratch/prefix" -name autobal.pc | head -1)")
cflags=$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags autobal)
libs=$(PKG_CONFIG_PATH="$pcdir" pkg-config --libs autobal)
cc $cflags "$here/consumer.c" -o "$scratch/consumer-pc" $libs -lgsl -lgslcblas -lm -Wl,-rpath,"$pcdir/.."
"$scratch/consumer-pc"
echo "ok   pkg-config consumer built and ran"
# only the public API is exported from the shared library
if nm -D --defined-only "$pcdir/../libautobal.so" | awk '{print $3}' | grep -v '^autobal_' | grep -v '^_' | grep -v '^\.gomp_critical_user_' | grep -q .; then
  echo "FAIL non-API symbols exported:"; nm -D --defined-only "$pcdir/../libautobal.so" | awk '{print $3}' | grep -v '^autobal_' | grep -v '^_'
  exit 1
fi
echo "ok   only autobal_* symbols exported"
echo "3 passed, 0 failed"
