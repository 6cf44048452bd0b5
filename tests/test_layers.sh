#!/usr/bin/env bash
# test_layers.sh: the layers of src/ (docs/architecture.md) are kept.
#
#   tests/test_layers.sh ROOT [OBJECTS]
#
# ROOT is the source tree; OBJECTS (optional) the library's object files, one argument or one
# ';'-separated list (CTest passes $<TARGET_OBJECTS:autobal_objects>).  Checks, each failure
# printed with the file and the line:
#  1. every #include of src/**/*.{c,h,inc} and include/autobal/*.h goes down or sideways only:
#     core (src/core/, src/internal.h) <- numerics, transient <- models <- analysis <- studies,
#     the archive (src/archive/) beside: it includes core only, and only studies include it;
#     a model includes no other model's headers; numerics and transient not each other;
#  2. HDF5 headers (hdf5.h, hdf5_hl.h, H5*.h) only in src/archive/;
#  3. no printing in the library (printf, fprintf, puts, fputs, putchar, perror, vprintf,
#     vfprintf): it returns statuses and messages;
#  4. no circle of private includes between files of src/ (X.c and X.h count as one file);
#  5. with OBJECTS: every call (undefined symbol of one object defined in another) goes down or
#     sideways by the rules of 1, and the calls between objects have no circle.
# A folder of src/ that is none of these layers fails (add it to docs/architecture.md and here).
set -u
root=${1:?usage: test_layers.sh ROOT [OBJECTS]}
shift
src=$root/src
fail=0
bad() { echo "FAIL: $*"; fail=1; }

# layer of a path below src/ ("" for not a layer); models carry their model: models:rotor
layer_of_src() {
  case $1 in
    internal.h | core/*) echo core ;;
    numerics/*) echo numerics ;;
    transient/*) echo transient ;;
    models/*/*) local m=${1#models/}; echo "models:${m%%/*}" ;;
    analysis/*) echo analysis ;;
    studies/*) echo studies ;;
    archive/*) echo archive ;;
    *) echo "" ;;
  esac
}
# layer of a public header by name (autobal/NAME.h); "?" for a header not in this table
layer_of_public() {
  case $1 in
    autobal/status.h | autobal/version.h | autobal/export.h) echo core ;;
    autobal/stability.h) echo numerics ;;
    autobal/transient.h) echo transient ;;
    autobal/rotor.h) echo models:rotor ;;
    autobal/pendulum.h) echo models:pendulum ;;
    autobal/rotor_stability.h | autobal/rotor_asymptotic.h | autobal/runup.h | autobal/attractor.h) echo analysis ;;
    autobal/archive.h) echo archive ;;
    autobal/study*.h | autobal/studies*.h | autobal/ensemble.h | autobal/design.h) echo studies ;;
    autobal.h) echo umbrella ;;
    *) echo "?" ;;
  esac
}
rank() {
  case $1 in
    core) echo 0 ;; numerics | transient) echo 1 ;; models:*) echo 2 ;; analysis) echo 3 ;;
    studies) echo 4 ;; archive) echo 9 ;; umbrella) echo 10 ;; *) echo 99 ;;
  esac
}
# may a file of layer $1 use (include, call) layer $2?
allowed() {
  local x=$1 y=$2
  [ "$y" = core ] && return 0
  [ "$x" = "$y" ] && return 0
  [ "$x" = archive ] && return 1
  [ "$y" = archive ] && { [ "$x" = studies ]; return; }
  [ "$x" = core ] && return 1
  [ "$(rank "$y")" -lt "$(rank "$x")" ]
}

files=$(cd "$src" && find . -type f \( -name '*.c' -o -name '*.h' -o -name '*.inc' \) | sed 's|^\./||' | LC_ALL=C sort)
[ -n "$files" ] || { echo "FAIL: no sources under $src"; exit 1; }
edges=$(mktemp)
trap 'rm -f "$edges"' EXIT
nchk=0
for f in $files; do
  lx=$(layer_of_src "$f")
  if [ -z "$lx" ]; then
    bad "src/$f: folder is not a layer of docs/architecture.md (core, numerics, transient, models/<model>, analysis, studies, archive)"
    continue
  fi
  # 2, 3
  grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"](hdf5|hdf5_hl|H5[A-Za-z]*)\.h[>"]' "$src/$f" |
    while IFS= read -r l; do [ "$lx" = archive ] || echo "FAIL: src/$f:${l%%:*}: HDF5 outside src/archive/: ${l#*:}"; done | grep . && fail=1
  grep -nE '(^|[^_[:alnum:]])(printf|fprintf|puts|fputs|putchar|perror|vprintf|vfprintf)[[:space:]]*\(' "$src/$f" |
    grep -vE '^[0-9]+:[[:space:]]*(/?\*|//)' |
    while IFS= read -r l; do echo "FAIL: src/$f:${l%%:*}: the library prints: ${l#*:}"; done | grep . && fail=1
  # 1, 4
  while IFS= read -r l; do
    n=${l%%:*}
    inc=$(echo "${l#*:}" | sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"].*/\1/')
    ly=""
    target=""
    if [ -f "$src/$(dirname "$f")/$inc" ]; then
      target=$(realpath -m --relative-to="$src" "$src/$(dirname "$f")/$inc")
    elif [ -f "$src/$inc" ]; then
      target=$(realpath -m --relative-to="$src" "$src/$inc")
    fi
    if [ -n "$target" ]; then
      ly=$(layer_of_src "$target")
      echo "${f%.*} ${target%.*}" >>"$edges"
    else
      case $inc in autobal/* | autobal.h) ly=$(layer_of_public "$inc") ;; *) continue ;; esac
      if [ "$ly" = "?" ]; then echo "note: src/$f:$n: public header $inc has no layer in tests/test_layers.sh"; continue; fi
    fi
    nchk=$((nchk + 1))
    allowed "$lx" "$ly" || bad "src/$f:$n: $lx includes $inc ($ly): a lower layer includes a higher one"
  done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]' "$src/$f")
done
# public headers: the same rules
for h in "$root"/include/autobal/*.h; do
  lx=$(layer_of_public "autobal/$(basename "$h")")
  [ "$lx" = "?" ] && { echo "note: include/autobal/$(basename "$h") has no layer in tests/test_layers.sh"; continue; }
  while IFS= read -r l; do
    inc=$(echo "${l#*:}" | sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"].*/\1/')
    case $inc in autobal/* | autobal.h) ;; *) continue ;; esac
    ly=$(layer_of_public "$inc")
    [ "$ly" = "?" ] && continue
    nchk=$((nchk + 1))
    allowed "$lx" "$ly" || bad "include/autobal/$(basename "$h"):${l%%:*}: $lx includes $inc ($ly)"
  done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]' "$h")
done
echo "checked $nchk #include lines of $(echo "$files" | wc -l) files of src/ and the public headers"
# 4: circles of private includes (tsort names the files of a loop on stderr)
if ! out=$(awk '$1 != $2' "$edges" | tsort 2>&1 >/dev/null); then
  bad "a circle of private includes:"
  echo "$out" | sed 's/^tsort: /  /' | awk '!seen[$0]++'
elif [ -n "$out" ]; then
  bad "a circle of private includes:"; echo "$out"
else
  echo "private includes: $(awk '$1 != $2' "$edges" | sort -u | wc -l) edges between files, no circle"
fi

# 5: calls between objects
objs=$(printf '%s\n' "$@" | tr ';' '\n' | grep -v '^$' || true)
if [ -n "$objs" ]; then
  defs=$(mktemp)
  calls=$(mktemp)
  trap 'rm -f "$edges" "$defs" "$calls"' EXIT
  for o in $objs; do
    rel=${o##*.dir/}
    rel=${rel#./}
    rel=${rel%.o}
    echo "$rel" | grep -q '\.c$' || { bad "object $o: not below a *.dir/ folder"; continue; }
    [ -n "$(layer_of_src "$rel")" ] || { bad "object $o: src/$rel is in no layer"; continue; }
    nm -P --defined-only "$o" | awk -v r="$rel" '$2 ~ /^[TDBRiWV]$/ && $1 !~ /\.resolver$/ {print $1, r}' >>"$defs"
    nm -P --undefined-only "$o" | awk -v r="$rel" '{print $1, r}' >>"$calls"
  done
  ncall=0
  pairs=$(awk 'NR == FNR {def[$1] = $2; next} ($1 in def) && def[$1] != $2 {print $2, def[$1], $1}' "$defs" "$calls" | sort -u)
  while read -r from to sym; do
    [ -n "$from" ] || continue
    ncall=$((ncall + 1))
    lx=$(layer_of_src "$from")
    ly=$(layer_of_src "$to")
    allowed "$lx" "$ly" || bad "src/$from ($lx) calls $sym of src/$to ($ly): a lower layer calls a higher one"
  done <<<"$pairs"
  if ! out=$(echo "$pairs" | awk 'NF == 3 {print $1, $2}' | sort -u | tsort 2>&1 >/dev/null); then
    bad "a circle of calls between files:"
    echo "$out" | sed 's/^tsort: /  /' | awk '!seen[$0]++'
  fi
  echo "checked $ncall calls between $(echo "$objs" | wc -l) objects"
fi
[ $fail = 0 ] && echo "layers: OK"
exit $fail
