#!/usr/bin/env bash
# Build the fuzz targets with clang's libFuzzer + AddressSanitizer + UndefinedBehaviorSanitizer
# and run them.  See tests/fuzz/README.md.
#
#   tests/fuzz/run.sh [SECONDS] [config|cli|numeric|all]   fuzz each target for SECONDS (default 60)
#   tests/fuzz/run.sh build                        only build
#   tests/fuzz/run.sh coverage                     line coverage of the corpus (llvm-cov)
#
# Needs clang and libclang-rt-14-dev (apt-get install clang libclang-rt-14-dev) and the
# library's dependencies (scripts/deps.sh).  Build directory: $AUTOBAL_FUZZ_BUILD, default
# build-fuzz/ in the source tree.  The growing corpus lives in the build directory (seeded from
# tests/fuzz/corpus/<target>/); findings are written there as crash-*/leak-*/timeout-* files.
# Extra libFuzzer flags can be given in $FUZZ_FLAGS (e.g. FUZZ_FLAGS=-jobs=2).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
build=${AUTOBAL_FUZZ_BUILD:-$src/build-fuzz}
mode=${1:-60}
which=${2:-all}
CC=${CC_FUZZ:-clang}
command -v "$CC" >/dev/null || { echo "run.sh: $CC not found (apt-get install clang libclang-rt-14-dev)"; exit 1; }

version=$(sed -n 's/^ *VERSION \([0-9][0-9.]*\)$/\1/p' "$src/CMakeLists.txt" | head -1)
IFS=. read -r vmaj vmin vpat <<<"$version"
mkdir -p "$build/include/autobal"
sed -e "s/@PROJECT_VERSION_MAJOR@/$vmaj/" -e "s/@PROJECT_VERSION_MINOR@/$vmin/" \
    -e "s/@PROJECT_VERSION_PATCH@/$vpat/" -e "s/@PROJECT_VERSION@/$version/" \
    "$src/include/autobal/version.h.in" > "$build/include/autobal/version.h"

hdf5_inc=$(pkg-config --cflags-only-I hdf5 2>/dev/null || echo -I/usr/include/hdf5/serial)
hdf5_libs=$(pkg-config --libs hdf5 2>/dev/null || echo "-L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5")
inc="-I$src/include -I$build/include -I$src/src -I$src/apps -I$here $hdf5_inc"
libs="$(echo "$hdf5_libs" | sed "s/-lhdf5/-lhdf5_hl -lhdf5/") -lgsl -lgslcblas -linih -ludunits2 -lm"
defs="-DAUTOBAL_BUILDING -DH5_USE_110_API -DAUTOBAL_GIT_REVISION=\"fuzz\""

# build VARIANT CFLAGS LINKFLAGS: objects of the library, the apps' config code, the readers and
# the targets in $build/VARIANT
build_variant() {
  local variant=$1 cflags=$2 lflags=$3 out="$build/$1" f
  mkdir -p "$out/obj"
  local objs=()
  # every .c under src/ (the layer folders, docs/architecture.md); the object is named after the
  # path below src/ (models/rotor/rotor.c -> lib_models_rotor_rotor.o)
  local rel obj
  while IFS= read -r f; do
    rel=${f#"$src"/src/}
    obj="$out/obj/lib_$(echo "${rel%.c}" | tr / _).o"
    $CC -std=c11 $cflags $defs $inc -c "$f" -o "$obj"
    objs+=("$obj")
  done < <(find "$src/src" -name '*.c' | LC_ALL=C sort)
  for f in cli.c units.c cli_archive.c cmd_pendulum.c; do
    $CC -std=c11 $cflags $inc -c "$src/apps/$f" -o "$out/obj/app_${f%.c}.o"
    objs+=("$out/obj/app_${f%.c}.o")
  done
  for f in reader_rotor.c reader_pendulum_transient.c; do
    $CC -std=c11 $cflags $inc -c "$here/$f" -o "$out/obj/${f%.c}.o"
    objs+=("$out/obj/${f%.c}.o")
  done
  $CC -std=c11 $cflags $inc -c "$here/main_renamed.c" -o "$out/obj/app_main.o"
  for f in fuzz_config fuzz_cli fuzz_numeric; do
    $CC -std=c11 $cflags $inc -c "$here/$f.c" -o "$out/obj/$f.o"
  done
  $CC $lflags "$out/obj/fuzz_config.o" "${objs[@]}" $libs -o "$out/fuzz_config"
  $CC $lflags "$out/obj/fuzz_cli.o" "$out/obj/app_main.o" "${objs[@]}" $libs -o "$out/fuzz_cli"
  $CC $lflags "$out/obj/fuzz_numeric.o" "${objs[@]}" $libs -o "$out/fuzz_numeric"
}

san="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
if [ "$mode" = coverage ]; then
  mkdir -p "$build/coverage/obj"
  $CC -std=c11 -O0 -g -c "$here/replay_main.c" -o "$build/coverage/obj/replay_main.o"
  # the targets with replay_main.c instead of libFuzzer, instrumented for source coverage
  build_variant coverage "-O0 -g -fprofile-instr-generate -fcoverage-mapping" \
    "-fprofile-instr-generate $build/coverage/obj/replay_main.o"
  for t in config cli; do
    corpus=("$here/corpus/$t")
    [ -d "$build/corpus-$t" ] && corpus+=("$build/corpus-$t")
    LLVM_PROFILE_FILE="$build/coverage/$t.profraw" "$build/coverage/fuzz_$t" "${corpus[@]}" >/dev/null 2>&1 || true
  done
  llvm-profdata merge -sparse "$build/coverage/config.profraw" "$build/coverage/cli.profraw" -o "$build/coverage/all.profdata"
  llvm-cov report "$build/coverage/fuzz_config" -object "$build/coverage/fuzz_cli" \
    -instr-profile="$build/coverage/all.profdata" \
    "$src/apps/cli.c" "$src/apps/main.c" "$src/apps/cmd_rotor.c" "$src/apps/cmd_pendulum_transient.c" "$src/apps/cmd_pendulum.c"
  exit 0
fi

build_variant fuzz "-g -O1 -fsanitize=fuzzer-no-link $san" "-fsanitize=fuzzer $san"
echo "built $build/fuzz/fuzz_config, $build/fuzz/fuzz_cli and $build/fuzz/fuzz_numeric"
[ "$mode" = build ] && exit 0

run_target() {
  local t=$1 secs=$2 extra=""
  mkdir -p "$build/corpus-$t" "$build/findings-$t" "$build/tmp"
  [ "$t" = cli ] && extra="-close_fd_mask=3"
  [ -f "$here/$t.dict" ] && extra="$extra -dict=$here/$t.dict"
  echo "fuzzing $t for $secs s (log: $build/fuzz_$t.log)"
  ( cd "$build/findings-$t" &&
    TMPDIR="$build/tmp" ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/fuzz/fuzz_$t" -max_total_time="$secs" -max_len=4096 -timeout=20 -rss_limit_mb=2048 \
      -print_final_stats=1 $extra ${FUZZ_FLAGS:-} \
      "$build/corpus-$t" "$here/corpus/$t" ) 2>&1 | tee "$build/fuzz_$t.log" | grep -E "^#[0-9]+ +(INITED|DONE|pulse)|stat::|ERROR|SUMMARY|==[0-9]+==|Test unit written|fuzz_(config|cli|numeric):" || true
  if ls "$build/findings-$t" | grep -q .; then echo "FINDINGS in $build/findings-$t:"; ls "$build/findings-$t"; return 1; fi
}
status=0
case "$which" in
  config) run_target config "$mode" || status=1 ;;
  cli) run_target cli "$mode" || status=1 ;;
  numeric) run_target numeric "$mode" || status=1 ;;
  all) run_target config "$mode" || status=1; run_target cli "$mode" || status=1; run_target numeric "$mode" || status=1 ;;
  *) echo "unknown target '$which' (config, cli, numeric, all)"; exit 2 ;;
esac
exit $status
