#!/usr/bin/env bash
# App test: the verdict of `autobal pendulum roots` without damping (H = h = 0) comes from the exact
# criterion (10) (issue 18 item 4): the listed case, the exact double roots R_w = 0 and (k = 0) R_w = 1,
# and points down to 1e-15 relative around every critical speed of nine (R_m, k) cases, each against
# the eigenvalues of (5) and their semisimplicity in 50-digit mpmath (undamped_verdict_check.py).
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

"$PY" "$here/undamped_verdict_check.py" "$AUTOBAL" > check.txt 2>&1 && ok "undamped verdicts == 50-digit reference" \
  || { bad "undamped verdicts == 50-digit reference"; cat check.txt; }
grep -E "^R_m|points near|checks" check.txt

# the text summary names the criterion; the archive records it
expect 0 "unstable (exact undamped criterion (10))" "$AUTOBAL" pendulum roots --set pendulum.R_m=0.1 --set pendulum.k=0 \
  --set pendulum.R_w=2 --set pendulum.H=0 --set pendulum.h=0 -o undamped.h5
"$PY" -c "
import h5py, sys
g = h5py.File('undamped.h5', 'r')['/pendulum/roots']
a = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in g.attrs.items()}
ok = a['verdict'] == 'unstable' and a['criterion'] == 'exact undamped criterion (10)' and int(a['n_right_half_plane']) == 2
sys.exit(0 if ok else 1)" && ok "archive: verdict unstable, criterion (10), n_right_half_plane 2" || bad "archive attributes"
expect 0 "stable (Routh-Hurwitz on (6))" "$AUTOBAL" pendulum roots --set pendulum.R_m=0.1 --set pendulum.k=0 \
  --set pendulum.R_w=3.5 --set pendulum.H=0.1 --set pendulum.h=0.1
# the transient's linear verdict is the same function
expect 0 "" "$AUTOBAL" pendulum transient --set pendulum.R_m=0.1 --set pendulum.k=0 --set pendulum.R_w=2 \
  --set pendulum.H=0 --set pendulum.h=0 --set transient.t_end=1 --json
"$PY" -c "import json,sys; sys.exit(0 if json.load(open('out.txt'))['linear_verdict'] == 'unstable' else 1)" \
  && ok "pendulum transient --json: linear_verdict unstable" || bad "pendulum transient linear_verdict"
finish
