#!/usr/bin/env bash
# Every public header on its own: each of include/autobal.h, include/autobal/*.h and the
# generated autobal/version.h is included ALONE (so it must include what it needs) and TWICE
# (include guards) into a translation unit compiled as
#   C99     cc  -std=c99   -pedantic-errors -Wall -Wextra -Werror
#   C11     cc  -std=c11   -pedantic-errors -Wall -Wextra -Werror
#   C++11   c++ -std=c++11 -pedantic-errors -Wall -Wextra -Werror
# Then every function declared AUTOBAL_API in the headers is referenced from a C++ program that
# is linked against the shared library: a declaration outside extern "C" (looked up under its
# mangled name), a declared function that was never defined, or one that is not exported
# (hidden visibility) makes the link fail and names the function.
# Usage: test_headers.sh CC CXX SRC_INCLUDE_DIR BUILD_INCLUDE_DIR LIBAUTOBAL_SO SCRATCH [EXTRA_FLAGS]
set -u
cc=$1; cxx=$2; inc=$3; binc=$4; lib=$5; scratch=$6; extra=${7:-}
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail=0; pass=0
ok()  { echo "ok   $*"; pass=$((pass+1)); }
bad() { echo "FAIL $*"; fail=$((fail+1)); }

headers=$(cd "$inc" && ls autobal.h autobal/*.h)
headers="$headers autobal/version.h"
for h in $headers; do
  printf '#include <%s>\n#include <%s>\nint main(void) { return 0; }\n' "$h" "$h" > one.c
  cp one.c one.cpp
  sed -i 's/(void)/()/' one.cpp
  for std in c99 c11; do
    if $cc -std=$std -pedantic-errors -Wall -Wextra -Werror $extra -I"$inc" -I"$binc" -c one.c -o one.o 2>err.txt
    then ok "$h alone as $std"; else bad "$h alone as $std"; cat err.txt; fi
  done
  if [ -n "$cxx" ]; then
    if $cxx -std=c++11 -pedantic-errors -Wall -Wextra -Werror $extra -I"$inc" -I"$binc" -c one.cpp -o one.o 2>err.txt
    then ok "$h alone as c++11"; else bad "$h alone as c++11"; cat err.txt; fi
  fi
done

# every AUTOBAL_API function: declared in extern "C", defined, exported
funcs=$(cd "$inc" && cat autobal.h autobal/*.h "$binc/autobal/version.h" |
  tr '\n' ' ' | grep -o 'AUTOBAL_API[^;(]*(' | sed 's/($//; s/.*[^A-Za-z0-9_]\([A-Za-z_][A-Za-z0-9_]*\)$/\1/' | grep '^autobal_' | sort -u)
nf=$(echo "$funcs" | grep -c .)
if [ "$nf" -lt 50 ]; then bad "found only $nf AUTOBAL_API functions in the headers (parser broken?)"; fi
{
  for h in $headers; do echo "#include <$h>"; done
  echo "#include <cstdio>"
  echo "int main() {"
  echo "  const void *f[] = {"
  for f in $funcs; do echo "    reinterpret_cast<const void *>(&$f),"; done
  echo "  };"
  echo "  std::printf(\"%u functions\\n\", static_cast<unsigned>(sizeof f / sizeof f[0]));"
  echo "  return f[0] == 0;"
  echo "}"
} > all.cpp
compiler=${cxx:-$cc}
if [ -z "$cxx" ]; then sed -e 's/reinterpret_cast<const void \*>(&\(.*\))/(const void *)\&\1/' -e 's/static_cast<unsigned>(\(.*\))/(unsigned)(\1)/' \
     -e 's/<cstdio>/<stdio.h>/' -e 's/std::printf/printf/' -e 's/main()/main(void)/' all.cpp > all.c; src=all.c; else src=all.cpp; fi
if $compiler -Wall -Wextra -Werror $extra -I"$inc" -I"$binc" $src -o all "$lib" -Wl,-rpath,"$(dirname "$lib")" 2>err.txt; then
  ok "$nf AUTOBAL_API functions declared with C linkage, defined and exported by $(basename "$lib") (linked from ${cxx:+C++}${cxx:-C})"
  if [ -z "$extra" ]; then
    ./all >out.txt 2>&1 && ok "the program runs: $(cat out.txt)" || { bad "the program did not run"; cat out.txt; }
  fi
else
  bad "linking every AUTOBAL_API function failed:"; grep -o "undefined reference to .*" err.txt | sort -u | head -40
  grep -v "undefined reference" err.txt | head -20
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
