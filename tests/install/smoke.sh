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
# the README's embedding example: a verdict, a rejected parameter, a rotor transient with a
# "time to balance" event; it exits non-zero if any step failed
"$scratch/cmake-build/embed_example" | tee "$scratch/embed.txt"
grep -q "pendulum at R_w = 3: stable" "$scratch/embed.txt"
grep -q "rejected: parameter R_m = 0.7 is too large: must be < 0.5 (allowed range (0, 0.5))" "$scratch/embed.txt"
echo "ok   find_package(autobal) embedding example built and ran"
# its time to balance agrees with the installed command line's (same library, separate wiring)
tb_example=$(sed -n 's/^rotor balanced after \([0-9.]*\) s.*/\1/p' "$scratch/embed.txt")
tb_cli=$("$scratch/prefix/bin/autobal" rotor transient --json --set transient.t_end=12 |
  /usr/bin/python3 -c "import json,sys; print(json.load(sys.stdin)['time_to_balance'])")
/usr/bin/python3 -c "import sys; sys.exit(0 if abs($tb_example - $tb_cli) <= 0.006 else 1)" ||
  { echo "FAIL time to balance: example $tb_example s, autobal rotor transient $tb_cli s"; exit 1; }
echo "ok   time to balance of the example ($tb_example s) = the command line's ($tb_cli s) within 0.006 s"
# the README shows this program verbatim (checked once the section is in README.md)
readme="$here/../../README.md"
if grep -q "^## Embedding in an existing C code" "$readme"; then
  awk '/^## Embedding in an existing C code/{s=1} s&&/^```c$/{c=1; next} c&&/^```$/{exit} c' "$readme" > "$scratch/readme_embed.c"
  if diff -u "$here/embed_example.c" "$scratch/readme_embed.c"; then echo "ok   README embedding example = tests/install/embed_example.c"
  else echo "FAIL the README's embedding example differs from tests/install/embed_example.c"; exit 1; fi
else
  echo "skip README has no 'Embedding in an existing C code' section yet"
fi
pcdir=$(dirname "$(find "$scratch/prefix" -name autobal.pc | head -1)")
cflags=$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags autobal)
libs=$(PKG_CONFIG_PATH="$pcdir" pkg-config --libs autobal)
cc $cflags "$here/consumer.c" -o "$scratch/consumer-pc" $libs -lgsl -lgslcblas -lm -Wl,-rpath,"$pcdir/.."
"$scratch/consumer-pc"
echo "ok   pkg-config consumer built and ran"
cc $cflags "$here/embed_example.c" -o "$scratch/embed-pc" $libs -lgsl -lgslcblas -lm -Wl,-rpath,"$pcdir/.."
"$scratch/embed-pc" > "$scratch/embed-pc.txt"
cmp -s "$scratch/embed.txt" "$scratch/embed-pc.txt" || { echo "FAIL pkg-config build of the example prints something else"; exit 1; }
echo "ok   pkg-config embedding example built and ran (same output)"
# only the public API is exported from the shared library
if nm -D --defined-only "$pcdir/../libautobal.so" | awk '{print $3}' | grep -v '^autobal_' | grep -v '^_' | grep -v '^\.gomp_critical_user_' | grep -q .; then
  echo "FAIL non-API symbols exported:"; nm -D --defined-only "$pcdir/../libautobal.so" | awk '{print $3}' | grep -v '^autobal_' | grep -v '^_'
  exit 1
fi
echo "ok   only autobal_* symbols exported"
echo "all passed"
