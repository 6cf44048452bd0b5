#!/usr/bin/env bash
# App test: archives written by autobal 0.1.0 (tests/data/archives-0.1.0/, one per command,
# written by the program as it was before the library took over the analyses, issue 14) are
# re-run by today's `autobal rerun`: every dataset must be reproduced bit for bit (dtype, shape,
# bytes), and the new archive must be one that today's readers accept (Conventions, status).
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
here=$(cd "$(dirname "$0")" && pwd)
old="$here/../data/archives-0.1.0"
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH" && cd "$SCRATCH" || exit 1
fail=0 n=0
for f in "$old"/*.h5; do
  name=$(basename "$f" .h5)
  n=$((n + 1))
  if ! "$AUTOBAL" rerun "$f" -o "$name.h5" -q 2>err.txt; then
    echo "FAIL rerun $name: $(cat err.txt)"; fail=1; continue
  fi
  "$PY" - "$f" "$name.h5" <<'PY' || fail=1
import h5py, numpy as np, sys
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
def walk(g, out):
    for k, v in g.items():
        if isinstance(v, h5py.Dataset): out[v.name] = v
        else: walk(v, out)
A, B = {}, {}; walk(a, A); walk(b, B)
bad = [k for k in A if k not in B or A[k].dtype != B[k].dtype or A[k].shape != B[k].shape
       or A[k][()].tobytes() != B[k][()].tobytes()]
extra = [k for k in B if k not in A]
ok = not bad and not extra and b.attrs["status"] == "complete" and "autobal-1" in b.attrs["Conventions"].split()
print(("ok  " if ok else "FAIL") + f" {sys.argv[1].split('/')[-1]}: {len(A)} datasets reproduced bit for bit"
      + (f"; differ: {bad[:5]}" if bad else "") + (f"; new: {extra[:5]}" if extra else ""))
sys.exit(0 if ok else 1)
PY
done
[ "$n" -ge 12 ] || { echo "FAIL only $n archives found in $old"; fail=1; }
exit $fail
