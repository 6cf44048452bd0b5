#!/usr/bin/env bash
# Install test: install the build tree into a temporary prefix, move the prefix (everything
# installed must be relocatable), then, with LD_LIBRARY_PATH unset:
#   - the installed `autobal --version` runs, and the installed program and library carry a
#     RUNPATH that resolves to the prefix's lib directory;
#   - consumer.c and the embedding example of docs/embedding.md are built and run every documented way:
#     CMake find_package (autobal::autobal and autobal::autobal_static), pkg-config with the
#     shared library (-Wl,-rpath from `pkg-config --variable=libdir`), pkg-config --static with
#     libautobal.a inside a dynamic program, and pkg-config --static fully static (-static);
#     the static ones must not need libautobal.so;
#   - the archive written by each consumer reads back in h5py;
#   - only autobal_* symbols are exported; docs/embedding.md shows the example and the link lines.
# Usage: smoke.sh BUILD_DIR SCRATCH
set -euo pipefail
build=$1; scratch=$2; here=$(cd "$(dirname "$0")" && pwd)
readme="$here/../../docs/embedding.md"
unset LD_LIBRARY_PATH
fail() { echo "FAIL $*"; exit 1; }
# run a build step quietly; on failure show its output
quiet() {
  local log="$scratch/step.log"
  if ! "$@" > "$log" 2>&1; then cat "$log"; fail "command failed: $*"; fi
}
# the DT_NEEDED entries of an ELF file, one a line ("" for a static executable)
needed() { local d; d=$(readelf -d "$1"); sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' <<< "$d"; }
# consumer.c's archive, read back with h5py (a reader independent of the library)
check_archive() {
  /usr/bin/python3 - "$1" <<'EOF' || fail "archive $1 does not read back in h5py as written"
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r") as f:
    assert f.attrs["Conventions"] == "CF-1.8 autobal-1" and f.attrs["status"] == "complete", dict(f.attrs)
    assert np.array_equal(f["consumer/R_w"][...], [2.0, 3.0, 4.0]), f["consumer/R_w"][...]
    assert f["consumer/R_w"].attrs["units"] == "1"
    v = f["consumer/verdict"][...]
    assert v.shape == (3,) and v[1] == 1, v  # AUTOBAL_VERDICT_STABLE = 1 (stability.h) at R_w = 3
EOF
}

rm -rf "$scratch"; mkdir -p "$scratch"
quiet cmake --install "$build" --prefix "$scratch/stage"
mv "$scratch/stage" "$scratch/prefix"   # installed under one name, used under another
prefix="$scratch/prefix"
lib=$(dirname "$(find "$prefix" -name libautobal.so)")
export PKG_CONFIG_PATH="$lib/pkgconfig"
echo "installed into $scratch/stage, moved to $prefix (library in $lib)"

# ---- the installed program and library: RUNPATH to the prefix's lib directory ------------
for f in "$prefix/bin/autobal" "$lib/libautobal.so"; do
  rp=$(readelf -d "$f" | sed -n 's/.*(RUNPATH).*\[\(.*\)\]/\1/p')
  [ -n "$rp" ] || fail "$f has no RUNPATH"
  case "$rp" in '$ORIGIN'*) ;; *) fail "$f: RUNPATH '$rp' is not relative to \$ORIGIN";; esac
  resolved=$(realpath -m "$(dirname "$f")/${rp#\$ORIGIN}")
  [ "$resolved" = "$(realpath "$lib")" ] || fail "$f: RUNPATH '$rp' resolves to $resolved, not $lib"
  echo "ok   RUNPATH of ${f#$prefix/} is '$rp' -> the prefix's lib directory"
done
version=$(pkg-config --modversion autobal)
out=$("$prefix/bin/autobal" --version) || fail "installed autobal --version exits non-zero"
case "$out" in "autobal $version "*) ;; *) fail "installed autobal --version prints '$out'";; esac
echo "ok   installed autobal --version runs without LD_LIBRARY_PATH: $out"
libdir=$(pkg-config --variable=libdir autobal)
[ "$(realpath "$libdir")" = "$(realpath "$lib")" ] || fail "autobal.pc libdir $libdir is not $lib (not relocatable)"
echo "ok   autobal.pc follows the moved prefix (libdir $libdir)"

# ---- CMake find_package ---------------------------------------------------------------------
quiet cmake -S "$here" -B "$scratch/cmake-build" -DCMAKE_PREFIX_PATH="$prefix"
quiet cmake --build "$scratch/cmake-build"
needed "$scratch/cmake-build/consumer" | grep -qx 'libautobal\.so\.[0-9]*' ||
  fail "find_package consumer does not link libautobal.so"
"$scratch/cmake-build/consumer" "$scratch/cmake.h5"
check_archive "$scratch/cmake.h5"
echo "ok   find_package(autobal), autobal::autobal: consumer built, ran, archive read back"
if needed "$scratch/cmake-build/consumer_static" | grep -q '^libautobal\.so'; then
  fail "consumer_static (autobal::autobal_static) needs libautobal.so"
fi
"$scratch/cmake-build/consumer_static" "$scratch/cmake-static.h5"
check_archive "$scratch/cmake-static.h5"
echo "ok   find_package(autobal), autobal::autobal_static: built without libautobal.so, ran"
# the embedding example (docs/embedding.md): a verdict, a rejected parameter, a rotor transient with a
# "time to balance" event; it exits non-zero if any step failed
"$scratch/cmake-build/embed_example" | tee "$scratch/embed.txt"
grep -q "pendulum at R_w = 3: stable" "$scratch/embed.txt" || fail "embed_example: no stable verdict"
grep -q "rejected: parameter R_m = 0.7 is too large: must be < 0.5 (allowed range (0, 0.5))" "$scratch/embed.txt" ||
  fail "embed_example: R_m not rejected with the expected message"
echo "ok   find_package(autobal) embedding example built and ran"
# its time to balance agrees with the installed command line's (same library, separate wiring)
tb_example=$(sed -n 's/^rotor balanced after \([0-9.]*\) s.*/\1/p' "$scratch/embed.txt")
[ -n "$tb_example" ] || fail "embed_example printed no time to balance"
tb_cli=$("$prefix/bin/autobal" rotor transient --json --set transient.t_end=12 |
  /usr/bin/python3 -c "import json,sys; print(json.load(sys.stdin)['time_to_balance'])")
/usr/bin/python3 -c "import sys; sys.exit(0 if abs($tb_example - $tb_cli) <= 0.006 else 1)" ||
  fail "time to balance: example $tb_example s, autobal rotor transient $tb_cli s"
echo "ok   time to balance of the example ($tb_example s) = the command line's ($tb_cli s) within 0.006 s"

# ---- pkg-config: the link lines docs/embedding.md gives ----------------------------------------
# shared: the executable finds libautobal.so through its own RUNPATH
cflags=$(pkg-config --cflags autobal gsl)
shared_libs="$(pkg-config --libs autobal gsl) -Wl,-rpath,$libdir"
quiet cc $cflags "$here/consumer.c" -o "$scratch/consumer-pc" $shared_libs
deps=$(ldd "$scratch/consumer-pc")
grep -q "libautobal\.so\.[0-9]* => $libdir/libautobal\.so" <<< "$deps" ||
  { echo "$deps"; fail "consumer-pc does not load libautobal.so from $libdir"; }
"$scratch/consumer-pc" "$scratch/pc.h5"
check_archive "$scratch/pc.h5"
echo "ok   pkg-config shared: consumer built, ran without LD_LIBRARY_PATH (libautobal.so from $libdir)"
quiet cc $cflags "$here/embed_example.c" -o "$scratch/embed-pc" $shared_libs
"$scratch/embed-pc" > "$scratch/embed-pc.txt"
cmp -s "$scratch/embed.txt" "$scratch/embed-pc.txt" || fail "pkg-config build of the example prints something else"
echo "ok   pkg-config shared: embedding example built and ran (same output)"
# libautobal.a inside an otherwise dynamic program
static_libs="-Wl,--as-needed -Wl,-Bstatic -lautobal -Wl,-Bdynamic $(pkg-config --static --libs autobal gsl)"
quiet cc $cflags "$here/consumer.c" -o "$scratch/consumer-pc-static" $static_libs
if needed "$scratch/consumer-pc-static" | grep -q '^libautobal\.so'; then
  fail "consumer-pc-static needs libautobal.so"
fi
needed "$scratch/consumer-pc-static" | grep -q '^libhdf5' || fail "consumer-pc-static links no HDF5 (not the test meant)"
"$scratch/consumer-pc-static" "$scratch/pc-static.h5"
check_archive "$scratch/pc-static.h5"
echo "ok   pkg-config --static, libautobal.a in a dynamic program: built, needs no libautobal.so, ran"
# fully static: every library of the link line comes from its .a (a test of Libs.private)
quiet cc -static $cflags "$here/consumer.c" -o "$scratch/consumer-pc-allstatic" $(pkg-config --static --libs autobal gsl)
[ -z "$(needed "$scratch/consumer-pc-allstatic")" ] || fail "consumer-pc-allstatic is not static"
"$scratch/consumer-pc-allstatic" "$scratch/pc-allstatic.h5"
check_archive "$scratch/pc-allstatic.h5"
echo "ok   pkg-config --static with -static: fully static consumer built and ran"

# ---- docs/embedding.md ----------------------------------------------------------------------
# it shows the example verbatim and the link lines used above
awk '/^# Embedding autobal in a C program/{s=1} s&&/^```c$/{c=1; next} c&&/^```$/{exit} c' "$readme" > "$scratch/readme_embed.c"
diff -u "$here/embed_example.c" "$scratch/readme_embed.c" ||
  fail "the embedding example of docs/embedding.md differs from tests/install/embed_example.c"
echo "ok   docs/embedding.md example = tests/install/embed_example.c"
for line in \
  'cc host.c $(pkg-config --cflags --libs autobal gsl) -Wl,-rpath,$(pkg-config --variable=libdir autobal)' \
  'cc host.c $(pkg-config --cflags autobal gsl) -Wl,--as-needed -Wl,-Bstatic -lautobal -Wl,-Bdynamic $(pkg-config --static --libs autobal gsl)' \
  'cc -static host.c $(pkg-config --cflags --static --libs autobal gsl)' \
  'target_link_libraries(host PRIVATE autobal::autobal GSL::gsl)' \
  'target_link_libraries(host PRIVATE autobal::autobal_static GSL::gsl)'; do
  grep -qF -- "$line" "$readme" || fail "docs/embedding.md does not show the link line: $line"
done
echo "ok   docs/embedding.md shows the five link lines tested here"

# ---- only the public API is exported from the shared library ----------------------------------
bad=$(nm -D --defined-only "$lib/libautobal.so" | awk '{print $3}' |
  grep -v -e '^autobal_' -e '^_' -e '^\.gomp_critical_user_' || true)
[ -z "$bad" ] || fail "non-API symbols exported: $bad"
[ "$(nm -D --defined-only "$lib/libautobal.so" | grep -c ' T autobal_')" -gt 50 ] ||
  fail "libautobal.so exports almost no autobal_* functions"
echo "ok   only autobal_* symbols exported"
echo "all passed"
