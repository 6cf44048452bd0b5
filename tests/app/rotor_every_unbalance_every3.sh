#!/usr/bin/env bash
# rotor stability for EVERY member and every unbalance with three identical balls ([stability]
# unbalance_min, unbalance_max, unbalance_member = every, the default):
#  (a) u_min, u_max against NumPy: 400000 random triples of ball angles (uniform, no constraint) whose
#      |sum e^{i psi}| falls in the range, and 200000 members with the constraint solved (random
#      unbalance in the range, random angle of ball 1, balls 2, 3 from z2 + z3 = t - z1);
#  (b) the verdict of each u sub-interval against ordinary `rotor stability` runs (member1 = given,
#      method poly) of NumPy-built members whose u lies in it, and the pieces of unbalances of each
#      critical u against NumPy members; stable_for_all against the ordinary runs (both ways);
#  (c) console and archive (critical_u, its pieces with units and dimensions, u sub-intervals);
#      the symmetric rule and two balls write no critical_u;
#  (d) the map with every member runs and names the rule.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

balls3='[plane1]\nball_mass = 0.05, 0.05, 0.05\nball_radius = 0.1, 0.1, 0.1\nball_damping = 0.1, 0.1, 0.1\nball_psi = 1, 2.5, 3\nball_rate = 0, 0, 0\n'
run_every() { # omega lo hi (g mm) file
  printf "[rotor]\nomega = %s\n${balls3}[stability]\nunbalance_min = %s g mm\nunbalance_max = %s g mm\ncritical_speeds = false\n" "$1" "$2" "$3" > "$4.ini"
  "$AUTOBAL" rotor stability "$4.ini" --json > "$4.json" 2>"$4.err" || bad "run $4"
}
run_every 500 100 14000 a
run_every 300 2500 7500 b
run_every 1200 13000 14500 c

# (a) the range of u against NumPy
for f in a b c; do
if "$PY" - $f.json <<'PY'
import json, sys
import numpy as np
e = json.load(open(sys.argv[1]))["every_unbalance"]
m, a = 0.05, 0.05 * 0.1
ta, tb = e["unbalance_min"] / a, e["unbalance_max"] / a
rng = np.random.default_rng(3)
# unconstrained random triples
z = np.exp(1j * rng.uniform(-np.pi, np.pi, (400000, 3)))
t = np.abs(z.sum(1)); sel = (t >= ta) & (t <= tb)
u1 = m * m * np.abs((z[sel] ** 2).sum(1)) ** 2 / 4
# constrained: ball 1 at phi, balls 2, 3 solved
t = rng.uniform(ta, tb, 200000); phi = rng.uniform(-np.pi, np.pi, 200000)
z1 = np.exp(1j * phi); v = t - z1; av = np.abs(v); ok = av <= 2
z1, v, av = z1[ok], v[ok], av[ok]
d = 1j * v / av * np.sqrt(1 - av ** 2 / 4)
z2, z3 = v / 2 + d, v / 2 - d
u2 = m * m * np.abs(z1 ** 2 + z2 ** 2 + z3 ** 2) ** 2 / 4
lo, hi = min(u1.min(), u2.min()), max(u1.max(), u2.max())
scale = 9 * m * m / 4
good = lo >= e["u_min"] - 1e-12 * scale and hi <= e["u_max"] + 1e-12 * scale
good = good and lo - e["u_min"] < 2e-3 * scale and e["u_max"] - hi < 2e-3 * scale
print("t in [%.4f, %.4f]: NumPy u in [%.9g, %.9g] (%d + %d members), program [%.9g, %.9g]" % (ta, tb, lo, hi, len(u1), len(u2), e["u_min"], e["u_max"]))
sys.exit(0 if good and e["unbalance_member"] == "every" and e["n_balls"] == 3 else 1)
PY
then ok "$f: u range inside and approached by NumPy random members"; else bad "$f: u range vs NumPy"; fi
done

# (b) verdicts against ordinary runs of NumPy-built members; pieces of each critical u
cat > mk.py <<'PY'
import json, sys
import numpy as np
# members for the checks: for each u sub-interval, 3 members whose u lies inside it (away from its ends);
# for each piece of a critical u, whether NumPy members at its middle reach u* and 1e-4 outside do not
e = json.load(open(sys.argv[1]))["every_unbalance"]
m, a, r0 = 0.05, 0.05 * 0.1, 0.1
ta, tb = e["unbalance_min"] / a, e["unbalance_max"] / a
rng = np.random.default_rng(5)
def members(t, n):
    phi = np.linspace(-np.pi, np.pi, n)
    z1 = np.exp(1j * phi); v = t - z1; av = np.abs(v); ok = (av <= 2) & (av > 0)
    z1, v, av = z1[ok], v[ok], av[ok]
    d = 1j * v / av * np.sqrt(1 - av ** 2 / 4)
    z = np.stack([z1, v / 2 + d, v / 2 - d], 1)
    return z, m * m * np.abs((z ** 2).sum(1)) ** 2 / 4
out = []
for lo, hi, v in zip(e["u_sub_lo"], e["u_sub_hi"], e["u_sub_verdict"]):
    w = hi - lo; found = 0
    for it in range(4000):
        t = rng.uniform(ta, tb)
        z, u = members(t, 721)
        k = np.nonzero((u > lo + 0.05 * w) & (u < hi - 0.05 * w))[0]
        if len(k):
            j = rng.choice(k); ang = np.angle(z[j]) + np.pi  # psi0 = 0: S points at pi
            out.append("%r %s %s %r" % (t * a / r0, v, ",".join(repr(x) for x in ang), u[j]))
            found += 1
            if found == 3: break
bad = 0
for i, uc in enumerate(e["critical_u"]):
    for k, lo, hi in zip(e["critical_u_piece_index"], e["critical_u_piece_lo"], e["critical_u_piece_hi"]):
        if int(k) != i: continue
        tl, th = lo / a, hi / a
        _, u = members(0.5 * (tl + th), 200001)
        bad += not (u.min() <= uc <= u.max())
        for tt in ([tl - 1e-4] if tl > ta + 1e-3 else []) + ([th + 1e-4] if th < tb - 1e-3 else []):
            _, u = members(tt, 200001)
            bad += (u.min() <= uc <= u.max())
print("PIECES_BAD %d" % bad)
for o in out: print(o)
PY
for f in a b c; do
  "$PY" mk.py $f.json > $f.members || bad "$f: NumPy members"
  read -r _ pb < <(head -1 $f.members)
  [ "$pb" = 0 ] && ok "$f: NumPy members reach each critical u in its pieces and not 1e-4 outside" || bad "$f: pieces ($pb wrong)"
  n=0; nbad=0; allst=1
  while read -r m0 v angs u; do
    printf "[rotor]\nomega = %s\n${balls3}m0 = %s\n[stability]\ncritical_speeds = false\nmethod = poly\nmember1 = given\nmember1_angles = %s\n" \
      "$(grep -m1 '^omega' $f.ini | cut -d= -f2)" "$m0" "$angs" > one.ini
    got=$("$AUTOBAL" rotor stability one.ini --json 2>one.err | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["verdict"])')
    n=$((n + 1)); [ "$got" = "$v" ] || { nbad=$((nbad + 1)); echo "  member u = $u: ordinary $got, sub-interval $v ($(head -c 300 one.err))"; }
    [ "$got" = stable ] || allst=0
  done < <(tail -n +2 $f.members)
  [ "$n" -ge 3 ] && [ "$nbad" = 0 ] && ok "$f: $n ordinary runs of members have their u sub-interval's verdict" || bad "$f: $nbad of $n ordinary runs disagree"
  sfa=$("$PY" -c 'import json; e = json.load(open("'$f.json'"))["every_unbalance"]; print(int(e["stable_for_all"]), len(e["critical_u"]))')
  [ "${sfa% *}" = "$([ $allst = 1 ] && [ "${sfa#* }" = 0 ] && echo 1 || echo 0)" ] && ok "$f: stable_for_all = ${sfa% *} agrees with the ordinary runs" || bad "$f: stable_for_all ${sfa% *} vs runs all stable $allst"
done
"$PY" -c 'import json,sys; sys.exit(0 if json.load(open("c.json"))["every_unbalance"]["stable_for_all"] else 1)' \
  && ok "c (1200 rad/s, 13000..14500 g mm): stable for all" || bad "c not stable for all"
"$PY" -c 'import json,sys; sys.exit(0 if not json.load(open("a.json"))["every_unbalance"]["stable_for_all"] else 1)' \
  && ok "a (500 rad/s, 100..14000 g mm): not stable for all" || bad "a stable for all"

# (c) console and archive
expect 0 "critical values of u" "$AUTOBAL" rotor stability a.ini
expect 0 "met by some member for m0 r0 in" "$AUTOBAL" rotor stability a.ini -o a.h5
if "$PY" - a.h5 a.json <<'PY'
import sys, json, h5py
import numpy as np
g = h5py.File(sys.argv[1], "r")["/rotor/stability/every_unbalance"]
e = json.load(open(sys.argv[2]))["every_unbalance"]
m = g.attrs["unbalance_member"]; m = m.decode() if isinstance(m, bytes) else m
def units(d):
    x = d.attrs["units"]; return x.decode() if isinstance(x, bytes) else x
ok = m == "every" and g.attrs["n_balls"] == 3
ok = ok and np.allclose(g["critical_u"][()], e["critical_u"], rtol=0, atol=0) and units(g["critical_u"]) == "kg^2"
ok = ok and units(g["critical_u_piece_lo"]) == "kg m" and np.array_equal(g["critical_u_piece_index"][()], np.array(e["critical_u_piece_index"], int))
ok = ok and g["u_sub_verdict"].shape == (len(e["u_sub_lo"]),) and units(g["u_sub_lo"]) == "kg^2"
ok = ok and "DIMENSION_LIST" in g["critical_u_piece_hi"].attrs and "DIMENSION_LIST" in g["u_sub_margin"].attrs
sys.exit(0 if ok else 1)
PY
then ok "archive: critical_u, its pieces, u sub-intervals (units, dimensions)"; else bad "archive datasets"; fi
printf "[rotor]\nomega = 500\n${balls3}[stability]\nunbalance_min = 100 g mm\nunbalance_max = 14000 g mm\nunbalance_member = symmetric\ncritical_speeds = false\n" > s.ini
"$AUTOBAL" rotor stability s.ini --json > s.json && "$AUTOBAL" rotor stability s.ini -o s.h5 >/dev/null || bad "symmetric run"
"$PY" -c '
import json, sys, h5py
e = json.load(open("s.json"))["every_unbalance"]; g = h5py.File("s.h5", "r")["/rotor/stability/every_unbalance"]
sys.exit(0 if "critical_u" not in e and "critical_u" not in g and len(e["critical_unbalance"]) >= 1 else 1)' \
  && ok "symmetric rule: no critical_u, critical unbalances as before" || bad "symmetric output changed"

# (d) the map with every member
printf "${balls3}[map]\nparam1 = omega\nmin1 = 400\nmax1 = 1200\nn1 = 3\nparam2 = ball_damping\nmin2 = 0.05\nmax2 = 0.2\nn2 = 2\nunbalance_min = 13000 g mm\nunbalance_max = 14500 g mm\n" > m.ini
expect 0 "unbalance_member = every" "$AUTOBAL" rotor map m.ini -o m.h5
if "$PY" - m.h5 <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r")["/rotor/map"]
m = g.attrs["unbalance_member"]; m = m.decode() if isinstance(m, bytes) else m
v = g["verdict"][()]
sys.exit(0 if m == "every" and v.shape == (3, 2) and (v == 1).any() and (v < 1).any() else 1)
PY
then ok "map with every member: archive names the rule, stable and not stable points"; else bad "map (every member)"; fi
finish
