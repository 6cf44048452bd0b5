#!/bin/bash
# Alternating ensembles (frictionless, stiction+contact e = 0.5, e = 1; 256 members, 2 threads, 20 s each),
# three rounds: prints case, law, e, CPU s, wall s, rhs evals, load.  Build first: bench/run.sh contact --quick
B=${AUTOBAL_BENCH_BUILD:-$(cd "$(dirname "$0")/.." && pwd)/build-bench}/bench_friction
for i in 1 2 3; do
  for c in "--psi-gap 0.02 ensemble none" "--contact 0.02 0.5 ensemble exact" "--contact 0.02 1 ensemble exact"; do
    $B $c 0.01 0.02 1e-10 1e-10 20 256 2 50 500 20 2>/dev/null | /usr/bin/python3 -c "
import sys,json
txt=sys.stdin.read(); i=txt.index('{'); j=txt.rindex('}')
d=json.loads(txt[i:j+1]); print('$c'.split()[1], d['law'], d['restitution'], d['cpu_seconds'], d['wall_seconds'], d['rhs_evals'], open('/proc/loadavg').read().split()[0])"
  done
done
