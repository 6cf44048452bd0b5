#!/usr/bin/env bash
# rotor stability for EVERY member and every unbalance with four to six identical balls ([stability]
# unbalance_min, unbalance_max, unbalance_member = every, the default; docs/rotor.md "Four or more
# balls, every member"):
#  (a) the enclosure [u_min, u_max] and the members found [u_min_inner, u_max_inner] against NumPy and
#      SciPy, which use no branch-and-bound: 300000 random configurations (angles uniform, kept when
#      |sum e^{i psi}| lies in the range), 300000 random members (the last two balls solved) and SLSQP from 40 random starts each for the largest and the
#      least q subject to ta^2 <= |S|^2 <= tb^2: every value inside the enclosure, and the optima equal
#      the members found (to 2e-6 n^2 m^2/4), for n = 4, 5, 6 at single unbalances and ranges;
#  (b) the verdict of each u sub-interval against ordinary `rotor stability` runs (member1 = given,
#      method poly) of NumPy-built members with u inside it and just either side of each critical u;
#      stable_for_all against the runs;
#  (c) console and archive (the enclosure's attributes with units, u sub-intervals with dimensions);
#      a map with every member of four balls runs.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

balls() { # n
  "$PY" -c 'import sys; n = int(sys.argv[1]); L = lambda v: ", ".join([v] * n)
print("[plane1]\nball_mass = %s\nball_radius = %s\nball_damping = %s\nball_psi = %s\nball_rate = %s" % (L("0.05"), L("0.1"), L("0.1"), ", ".join(str(0.5 * k) for k in range(n)), L("0")))' "$1"
}
run_every() { # n omega lo hi (g mm) file
  { printf "[rotor]\nomega = %s\n" "$2"; balls "$1"; printf "[stability]\nunbalance_min = %s g mm\nunbalance_max = %s g mm\ncritical_speeds = false\n" "$3" "$4"; } > "$5.ini"
  "$AUTOBAL" rotor stability "$5.ini" --json > "$5.json" 2>"$5.err" || { bad "run $5"; cat "$5.err"; }
}
# single unbalances at the t of the non-symmetric maxima (t = 1.7889, 0.63333, 3.32222), ranges with
# Q = 0 inside and beyond it
run_every 4 500 8944.5 8944.5 s4
run_every 5 500 3166.65 3166.65 s5
run_every 6 500 16611.1 16611.1 s6
run_every 4 500 100 19000 a4
run_every 4 500 15000 17500 b4
run_every 5 500 100 24000 a5
run_every 5 500 18750 21500 b5
run_every 6 500 100 29000 a6
run_every 4 1200 18000 19500 c4

# (a) the enclosure against NumPy and SciPy
cat > rng.py <<'PY'
import json, sys
import numpy as np
from scipy.optimize import minimize
e = json.load(open(sys.argv[1]))["every_unbalance"]
n = e["n_balls"]; m, a = 0.05, 0.05 * 0.1; um = m * m / 4
ta, tb = e["unbalance_min"] / a, e["unbalance_max"] / a
rng = np.random.default_rng(11)
z = np.exp(1j * rng.uniform(-np.pi, np.pi, (300000, n)))
t = np.abs(z.sum(1)); sel = (t >= ta) & (t <= tb)
us = um * np.abs((z[sel] ** 2).sum(1)) ** 2
# and 300000 members with the constraint solved (t uniform, n - 2 random angles, the last two closed)
tc = rng.uniform(ta, tb, 300000); zc = np.exp(1j * rng.uniform(-np.pi, np.pi, (300000, n - 2)))
v = tc - zc.sum(1); av = np.abs(v); okc = (av < 2) & (av > 0); v, av, zc = v[okc], av[okc], zc[okc]
d = 1j * v / av * np.sqrt(1 - av ** 2 / 4)
zc = np.concatenate([zc, (v / 2 + d)[:, None], (v / 2 - d)[:, None]], 1)
us = np.concatenate([us, um * np.abs((zc ** 2).sum(1)) ** 2])
def q(x): return np.abs(np.exp(2j * x).sum()) ** 2
def dq(x):
    Q = np.exp(2j * x).sum(); return -4 * np.imag(np.exp(2j * x) * np.conj(Q))
def f(x): return np.abs(np.exp(1j * x).sum()) ** 2
def df(x):
    S = np.exp(1j * x).sum(); return -2 * np.imag(np.exp(1j * x) * np.conj(S))
cons = [{"type": "ineq", "fun": lambda x: f(x) - ta * ta, "jac": df}, {"type": "ineq", "fun": lambda x: tb * tb - f(x), "jac": lambda x: -df(x)}]
def reclose(x):
    # SLSQP meets the constraint to about 1e-9: an exact member from its angles (S turned real, t clamped
    # into [ta, tb], the two balls farthest from parallel solved again)
    zz = np.exp(1j * x); zz = zz * np.exp(-1j * np.angle(zz.sum())); tt = min(max(abs(zz.sum()), ta), tb)
    i, j = max(((i, j) for i in range(n) for j in range(i + 1, n)), key=lambda p: abs(np.sin(np.angle(zz[p[0]] / zz[p[1]]))))
    rest = [k for k in range(n) if k not in (i, j)]
    v = tt - zz[rest].sum(); av = abs(v)
    if not (0 < av < 2): return None
    d = 1j * v / av * np.sqrt(1 - av * av / 4)
    zz[i], zz[j] = v / 2 + d, v / 2 - d
    return np.angle(zz)
best = {1: -1.0, -1: 1e9}
for sg in (1, -1):
    for k in range(40):
        r = minimize(lambda x: -sg * q(x), rng.uniform(-np.pi, np.pi, n), jac=lambda x: -sg * dq(x), constraints=cons,
                     method="SLSQP", options={"maxiter": 500, "ftol": 1e-15})
        x = reclose(r.x)
        if x is not None:
            v = q(x)
            best[sg] = max(best[sg], v) if sg > 0 else min(best[sg], v)
umax, umin = um * best[1], um * best[-1]
tol = 1e-12 * n * n * um
close = 2e-6 * n * n * um
inside = us.min() >= e["u_min"] - tol and us.max() <= e["u_max"] + tol and umin >= e["u_min"] - tol and umax <= e["u_max"] + tol
found = abs(umax - e["u_max_inner"]) <= close and abs(umin - e["u_min_inner"]) <= close
print("n %d t in [%.5f, %.5f]: random u in [%.9g, %.9g] (%d), SciPy [%.12g, %.12g]; program outer [%.12g, %.12g] found [%.12g, %.12g] gap %.3g"
      % (n, ta, tb, us.min() if len(us) else np.nan, us.max() if len(us) else np.nan, len(us), umin, umax, e["u_min"], e["u_max"], e["u_min_inner"], e["u_max_inner"], e["u_gap"]))
sys.exit(0 if inside and found and e["unbalance_member"] == "every" else 1)
PY
for f in s4 s5 s6 a4 b4 a5 b5 a6 c4; do
  if "$PY" rng.py $f.json; then ok "$f: enclosure holds every random and SciPy member; SciPy's optima = the members found"
  else bad "$f: enclosure vs NumPy/SciPy"; fi
done

# (b) verdicts against ordinary runs of NumPy-built members
cat > mk.py <<'PY'
import json, sys
import numpy as np
e = json.load(open(sys.argv[1]))["every_unbalance"]
n = e["n_balls"]; m, a, r0 = 0.05, 0.05 * 0.1, 0.1; um = m * m / 4
ta, tb = e["unbalance_min"] / a, e["unbalance_max"] / a
rng = np.random.default_rng(5)
def members(k):
    t = rng.uniform(ta, tb, k)
    z = np.exp(1j * rng.uniform(-np.pi, np.pi, (k, n - 2)))
    v = t - z.sum(1); av = np.abs(v); ok = (av < 2) & (av > 0)
    t, z, v, av = t[ok], z[ok], v[ok], av[ok]
    d = 1j * v / av * np.sqrt(1 - av ** 2 / 4)
    z = np.concatenate([z, (v / 2 + d)[:, None], (v / 2 - d)[:, None]], 1)
    return t, z, um * np.abs((z ** 2).sum(1)) ** 2
t, z, u = members(400000)
def emit(j, v):
    ang = np.angle(z[j]) + np.pi  # psi0 = 0: S points at pi
    print("%r %s %s %r" % (t[j] * a / r0, v, ",".join(repr(x) for x in ang), u[j]))
for lo, hi, v in zip(e["u_sub_lo"], e["u_sub_hi"], e["u_sub_verdict"]):
    w = hi - lo
    k = np.nonzero((u > lo + 0.05 * w) & (u < hi - 0.05 * w) & (u < 0.999 * n * n * um))[0]
    for j in k[:3]: emit(j, v)
# just either side of each critical u (within 1e-3 of the range of u): the verdicts of the two neighbours
for i, uc in enumerate(e["critical_u"]):
    d = 1e-3 * (e["u_max"] - e["u_min"])
    for sd, (lo, hi) in enumerate(((uc - d, uc), (uc, uc + d))):
        k = np.nonzero((u > lo) & (u < hi))[0]
        if len(k): emit(k[0], e["u_sub_verdict"][i + sd])
PY
for f in a4 b4 a5 a6 c4; do
  "$PY" mk.py $f.json > $f.members || bad "$f: NumPy members"
  n=0; nbad=0; allst=1
  nb=$("$PY" -c 'import json; print(json.load(open("'$f.json'"))["every_unbalance"]["n_balls"])')
  while read -r m0 v angs u; do
    { printf "[rotor]\nomega = %s\n" "$(grep -m1 '^omega' $f.ini | cut -d= -f2)"; balls "$nb"
      printf "m0 = %s\n[stability]\ncritical_speeds = false\nmethod = poly\nmember1 = given\nmember1_angles = %s\n" "$m0" "$angs"; } > one.ini
    got=$("$AUTOBAL" rotor stability one.ini --json 2>one.err | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["verdict"])')
    n=$((n + 1)); [ "$got" = "$v" ] || { nbad=$((nbad + 1)); echo "  member u = $u: ordinary $got, sub-interval $v ($(head -c 300 one.err))"; }
    [ "$got" = stable ] || allst=0
  done < $f.members
  [ "$n" -ge 3 ] && [ "$nbad" = 0 ] && ok "$f: $n ordinary runs of members (inside each u sub-interval, either side of each critical u) have its verdict" || bad "$f: $nbad of $n ordinary runs disagree"
  sfa=$("$PY" -c 'import json; e = json.load(open("'$f.json'"))["every_unbalance"]; print(int(e["stable_for_all"]), len(e["critical_u"]))')
  [ "${sfa% *}" = "$([ $allst = 1 ] && [ "${sfa#* }" = 0 ] && echo 1 || echo 0)" ] && ok "$f: stable_for_all = ${sfa% *} agrees with the ordinary runs" || bad "$f: stable_for_all ${sfa% *} vs runs all stable $allst"
done
"$PY" -c 'import json,sys; sys.exit(0 if json.load(open("c4.json"))["every_unbalance"]["stable_for_all"] else 1)' \
  && ok "c4 (1200 rad/s, 18000..19500 g mm): stable for all" || bad "c4 not stable for all"

# (c) console, archive, map
expect 0 "an enclosure: members found have u from" "$AUTOBAL" rotor stability a4.ini -o a4.h5
if "$PY" - a4.h5 a4.json <<'PY'
import sys, json, h5py
import numpy as np
g = h5py.File(sys.argv[1], "r")["/rotor/stability/every_unbalance"]
e = json.load(open(sys.argv[2]))["every_unbalance"]
def units(x):
    x = x.attrs["units"] if hasattr(x, "attrs") else x; return x.decode() if isinstance(x, bytes) else x
ok = g.attrs["n_balls"] == 4 and g.attrs["u_min_inner"] == e["u_min_inner"] and g.attrs["u_max_inner"] == e["u_max_inner"]
ok = ok and g.attrs["u_enclosure_complete"] == 1 and g.attrs["u_boxes"] == e["u_boxes"] and g.attrs["u_sub_undecided"] == 0
ok = ok and np.allclose(g["critical_u"][()], e["critical_u"], rtol=0, atol=0) and units(g["u_sub_lo"]) == "kg^2"
ok = ok and "DIMENSION_LIST" in g["u_sub_margin"].attrs and g["u_sub_verdict"].shape == (len(e["u_sub_lo"]),)
sys.exit(0 if ok else 1)
PY
then ok "archive: the enclosure's attributes, critical_u, u sub-intervals (units, dimensions)"; else bad "archive"; fi
{ printf "[rotor]\nomega = 500\n"; balls 4; printf "[map]\nparam1 = omega\nmin1 = 500\nmax1 = 1200\nn1 = 2\nparam2 = ball_damping\nmin2 = 0.05\nmax2 = 0.1\nn2 = 2\nunbalance_min = 18000 g mm\nunbalance_max = 19500 g mm\n"; } > m.ini
expect 0 "" "$AUTOBAL" rotor map m.ini -o m.h5
finish
