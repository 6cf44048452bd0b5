#!/usr/bin/env bash
# App test: `autobal pendulum map` over any two parameters and `autobal pendulum sweep`, run as a
# user would; archives checked by pendulum_axes_check.py (SymPy exact undamped verdicts, NumPy
# eigenvalues, the exact critical speeds); bad input: exit 3, a message naming the key and the
# allowed range, nothing written.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
A=$AUTOBAL
U="--set pendulum.H=0 --set pendulum.h=0 --set pendulum.R_m=0.125"
# undamped (k, R_w) maps, both conventions; the default axes at k = 0 through R_w = 0 and 1
expect 0 "map 2 x 7 over k in [0, 1], R_w in [0, 3]" $A pendulum map $U --set map.param1=k --set map.min1=0 --set map.max1=1 --set map.n1=2 --set map.Rw_min=0 --set map.Rw_max=3 --set map.n_Rw=7 -o exact_k_rw.h5
expect 0 "" $A pendulum map $U --set map.param1=k --set map.min1=0 --set map.max1=1 --set map.n1=2 --set map.min2=0 --set map.max2=3 --set map.n2=7 --set map.convention=paper -o paper_k_rw.h5
expect 0 "" $A pendulum map $U --set pendulum.k=0 --set map.Rm_min=0.125 --set map.Rm_max=0.125 --set map.n_Rm=1 --set map.Rw_min=0 --set map.Rw_max=3 --set map.n_Rw=7 -o exact_rm_rw_k0.h5
: >roots.jsonl
for k in 0 1; do for r in 0 0.5 1 1.5 2 2.5 3; do
  $A pendulum roots $U --set pendulum.k=$k --set pendulum.R_w=$r --json >>roots.jsonl || bad "pendulum roots k=$k R_w=$r"
done; done
# damped maps over other pairs (R_m = 0.1, R_w = 3, k = 0.5 unless on an axis)
D="--set pendulum.R_m=0.1 --set pendulum.R_w=3 --set pendulum.k=0.5"
expect 0 "map 6 x 5 over H in [0.001, 10] (log), h in [0.001, 10] (log)" $A pendulum map $D --set map.param1=H --set map.param2=h --set map.min1=1e-3 --set map.max1=10 --set map.n1=6 --set map.min2=1e-3 --set map.max2=10 --set map.n2=5 -o damped_H_h.h5
expect 0 "axis H/h: H = (H/h) h, h from its axis" $A pendulum map $D --set pendulum.R_w=20 --set pendulum.k=1 --set map.param1=H/h --set map.param2=h --set map.min1=0.5 --set map.max1=8 --set map.n1=5 --set map.min2=0.1 --set map.max2=1 --set map.n2=4 -o damped_ratio_h.h5
expect 0 "" $A pendulum map $D --set pendulum.H=0.05 --set pendulum.h=0.05 --set map.param1=k --set map.n1=5 --set map.param2=R_w --set map.min2=0.5 --set map.max2=4 --set map.n2=15 -o damped_k_rw.h5
expect 0 "axis H/h: H = (H/h) h, h held at pendulum.h" $A pendulum map $D --set pendulum.h=0.3 --set map.param1=R_w --set map.min1=1 --set map.max1=30 --set map.n1=8 --set map.param2=H/h --set map.min2=0.1 --set map.max2=10 --set map.n2=7 -o damped_rw_ratio.h5
# sweeps: undamped over R_w (vs pendulum critical), damped over h (vs NumPy)
expect 0 "critical values of R_w" $A pendulum sweep --set pendulum.H=0 --set pendulum.h=0 --set pendulum.R_m=0.1 --set pendulum.k=0.5 --set sweep.n=500 -o sweep_rw.h5
$A pendulum critical --set pendulum.H=0 --set pendulum.h=0 --set pendulum.R_m=0.1 --set pendulum.k=0.5 --set critical.n_Rm=3 --json >critical.json || bad "pendulum critical"
expect 0 "unstable -> stable" $A pendulum sweep --set pendulum.R_m=0.1 --set pendulum.R_w=20 --set pendulum.H=1 --set pendulum.k=1 --set sweep.param=h --set sweep.min=0.1 --set sweep.max=1 --set sweep.n=40 -o sweep_h.h5
"$PY" "$here/pendulum_axes_check.py" "$SCRATCH" && ok "archives vs SymPy / NumPy / pendulum critical" || bad "archive checks"
# JSON of a map over two other parameters
expect 0 '"axis1":"H"' $A pendulum map $D --set map.param1=H --set map.param2=h --set map.n1=3 --set map.n2=3 --json
# bad input: exit 3, the key and the allowed range named, no archive
expect 3 "not a pendulum parameter: allowed R_w, R_m, H, h, k, psi0, H/h" $A pendulum map --set map.param1=foo -o bad1.h5
expect 3 "pendulum.H = -1 is too small: must be >= 0" $A pendulum map --set map.param1=H --set map.min1=-1 --set map.max1=1 --set map.n1=3 --set map.log1=linear -o bad2.h5
expect 3 "pendulum.R_m = 0.6 is too large: must be < 0.5 (allowed range (0, 0.5))" $A pendulum map --set map.param2=R_m --set map.param1=R_w --set map.min2=0.1 --set map.max2=0.6 --set map.n2=3 -o bad3.h5
expect 3 "axis H/h needs pendulum.h > 0" $A pendulum map --set pendulum.h=0 --set map.param1=H/h -o bad4.h5
expect 3 "cannot be combined with a k or psi0 axis" $A pendulum map --set map.param1=k --set map.every_unbalance=true -o bad5.h5
expect 3 "a logarithmic axis needs min1 > 0" $A pendulum map --set map.param1=h --set map.min1=0 --set map.log1=log -o bad6.h5
expect 3 "param1 and param2 are both 'R_w'" $A pendulum map --set map.param1=R_w -o bad7.h5
expect 3 "pendulum.psi0 = 2 rad is too large: must be < 1.5707963267948966 rad" $A pendulum sweep --set sweep.param=psi0 --set sweep.max=2 -o bad8.h5
expect 3 "log = 'sideways': allowed auto, log, linear" $A pendulum sweep --set sweep.log=sideways -o bad9.h5
expect 3 "convention = 'none': allowed exact, paper" $A pendulum map --set map.convention=none -o bad10.h5
expect 3 "unknown key 'map.Rm_min'" $A pendulum map --set map.param1=H --set map.Rm_min=0.1 -o bad11.h5
n=$(ls bad*.h5 2>/dev/null | wc -l)
[ "$n" -eq 0 ] && ok "no archive written on bad input" || bad "$n archives written on bad input"
finish
