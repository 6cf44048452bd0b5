#!/usr/bin/env bash
# rotor design, n >= 3 balls certified for every member (docs/rotor.md "Design", "Number of balls";
# [design] unbalance_member = every, the default), checked by direct `rotor stability` runs of members
# built in NumPy (member1 = given: every ball angle), not by the design's code:
#  (A) the constructed case: the default rotor with 4 balls of 50 g on 100 mm, 0.3 kg/s, every m0 r0 in
#      7000..9500 g mm, 700..1100 rad/s, margin 0.1 1/s.  The symmetric fan is stable (the symmetric run
#      calls the design feasible; `rotor stability` of the fan at 5 unbalances x the grid speeds: margin
#      < -0.1), but the member of two right-angled pairs (z, iz, w, iw: sum e^{2 i psi} = 0 exactly,
#      closed form) has a root with Re lambda > 0 at the reported speed, so the certification must say
#      NOT FEASIBLE: console, JSON (members_certified -1, verdict_covers) and archive (ranked/
#      members_certified, member_found_speed with units, on the rank dimension);
#  (B) a certified design (the default machine's search with 3 and 4 balls, a coarse grid): the best is
#      certified for every member; 40 random members (NumPy: n - 2 random angles, two by the closed
#      form) of random unbalances of the range, each run by `rotor stability` (member given) at 3 of the
#      re-check speeds: every margin < -margin, and u = m^2 |sum e^{2 i psi}|^2 / 4 inside the enclosure;
#  (C) bad input names its key: member_boxes, n_balls_max = 11 with every.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

cat > m.ini <<'INI'
[plane1]
ball_mass = 50 g, 50 g, 50 g, 50 g
ball_radius = 100 mm, 100 mm, 100 mm, 100 mm
ball_damping = 0.3, 0.3, 0.3, 0.3
ball_psi = 0, 1, 2, 3
ball_rate = 0, 0, 0, 0
INI
cp m.ini a.ini
cat >> a.ini <<'INI'

[design]
speed_min = 700
speed_max = 1100
n_speed = 5
n_verify = 9
unbalance_min = 7000 g mm
unbalance_max = 9500 g mm
margin = 0.1
ball_mass_min = 50 g
ball_mass_max = 50 g
track_radius_min = 100 mm
track_radius_max = 100 mm
ball_damping_min = 0.3
ball_damping_max = 0.3
n_best = 1
n_starts = 0
n_transient = 0
n_balls_min = 4
n_balls_max = 4
INI
expect 0 "NOT FEASIBLE" "$AUTOBAL" rotor design a.ini -o a.h5
"$AUTOBAL" rotor design a.ini --json > a.json 2>/dev/null && ok "json run" || bad "json run"
expect 0 "feasible" "$AUTOBAL" rotor design a.ini -o s.h5 --set design.unbalance_member=symmetric

cat > b.ini <<'INI'
[plane1]
ball_mass = 50 g, 50 g, 50 g
ball_radius = 100 mm, 100 mm, 100 mm
ball_damping = 0.1, 0.1, 0.1
ball_psi = 0, 1, 2
ball_rate = 0, 0, 0

[design]
speed_min = 4500 rpm
speed_max = 9000 rpm
n_speed = 5
n_verify = 9
unbalance_min = 500 g mm
unbalance_max = 4000 g mm
margin = 0.2
ball_mass_min = 25 g
ball_mass_max = 100 g
n_ball_mass = 3
track_radius_min = 50 mm
track_radius_max = 150 mm
n_track_radius = 6
ball_damping_min = 0.1
ball_damping_max = 1
n_ball_damping = 3
n_best = 6
n_starts = 1
max_iter = 15
n_transient = 0
n_balls_min = 3
n_balls_max = 4
INI
expect 0 "every member certified" "$AUTOBAL" rotor design b.ini -o b.h5 --set design.config_out=bestB.ini
grep -q "the verdict covers EVERY member" bestB.ini && ok "best config says every member" || bad "best config comment"

"$PY" - "$AUTOBAL" <<'PY'
import json, subprocess, sys, math
import h5py, numpy as np
A = sys.argv[1]
npass = nfail = 0
def ok(c, what):
    global npass, nfail
    print(("ok   " if c else "FAIL ") + what)
    if c: npass += 1
    else: nfail += 1
def stab(cfg, m, r, h, w, s, angles):
    n = len(angles)
    args = [A, "rotor", "stability", cfg, "--json", "--set", "rotor.omega=%r" % w, "--set", "plane1.m0=%r" % (s / 0.1),
            "--set", "plane1.ball_mass=" + ",".join([repr(m)] * n), "--set", "plane1.ball_radius=" + ",".join([repr(r)] * n),
            "--set", "plane1.ball_damping=" + ",".join([repr(h)] * n),
            "--set", "plane1.ball_psi=" + ",".join("0" for i in range(n)),
            "--set", "plane1.ball_rate=" + ",".join(["0"] * n),
            "--set", "stability.member1=given", "--set", "stability.member1_angles=" + ",".join(repr(a) for a in angles),
            "--set", "stability.critical_speeds=false"]
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0: print(r.stderr)
    return json.loads(r.stdout) if r.returncode == 0 and r.stdout.strip() else None
def pairs_member(t):
    # two right-angled pairs a, a + pi/2, b, b + pi/2: Q = 0; |S| = 2 sqrt2 cos(g/2) = t; S opposite the unbalance (psi0 = 0)
    g = 2 * math.acos(t / (2 * math.sqrt(2)))
    a, b = 0.0, -g
    S = (1 + 1j) * (np.exp(1j * a) + np.exp(1j * b))
    turn = math.pi - np.angle(S)
    ang = np.array([a, a + math.pi / 2, b, b + math.pi / 2]) + turn
    return ang
def random_member(n, mr, s, rng):
    while True:
        ang = rng.uniform(0, 2 * math.pi, n)
        W = -s - mr * np.exp(1j * ang[2:]).sum()
        if abs(W) <= 2 * mr and abs(W) > 1e-9 * mr:
            c = math.acos(abs(W) / (2 * mr))
            ang[0], ang[1] = np.angle(W) - c, np.angle(W) + c
            return ang
# (A)
j = json.load(open("a.json"))
d = j["designs"][0]
ok(d["members_certified"] == -1 and not d["feasible"], "A: JSON: members_certified -1, not feasible")
ok(d["verdict_covers"] == "symmetric members only", "A: JSON verdict_covers")
wf = d["member_found_speed"]
ok(700 <= wf <= 1100, "A: found speed %.6g in the range" % wf)
ang = pairs_member(8000e-6 / (0.05 * 0.1))
z = np.exp(1j * ang)
ok(abs(0.05 * 0.1 * z.sum() + 8000e-6) < 1e-15 and abs((z ** 2).sum()) < 1e-12, "A: the pairs member balances 8000 g mm with Q = 0")
r = stab("m.ini", 0.05, 0.1, 0.3, wf, 8000e-6, ang)
ok(r is not None and r["margin"] > 0, "A: rotor stability of the Q = 0 member at %.6g rad/s: margin %s > 0" % (wf, r and r["margin"]))
wfan = -1e9
for s in np.linspace(7000e-6, 9500e-6, 5):
    for w in np.linspace(700, 1100, 3):
        r = subprocess.run([A, "rotor", "stability", "m.ini", "--json", "--set", "rotor.omega=%r" % w, "--set", "plane1.m0=%r" % (s / 0.1),
                            "--set", "stability.member1=symmetric", "--set", "stability.critical_speeds=false"], capture_output=True, text=True)
        wfan = max(wfan, json.loads(r.stdout)["margin"])
ok(wfan < -0.1, "A: the symmetric fan's margins below -0.1 (largest %.6g): the symmetric search's premise" % wfan)
with h5py.File("a.h5", "r") as f:
    g = f["/rotor/design/ranked"]
    ok(int(g["members_certified"][0]) == -1 and int(g["feasible"][0]) == 0, "A: archive members_certified -1, feasible 0")
    ok(g["member_found_speed"].attrs["units"] in (b"rad/s", "rad/s"), "A: member_found_speed units rad/s")
    ok(g["member_found_u"].attrs["units"] in (b"kg^2", "kg^2"), "A: member_found_u units kg^2")
    ok("DIMENSION_LIST" in g["members_certified"].attrs, "A: members_certified on a named dimension")
    vc = f["/rotor/design"].attrs["verdict_covers"]
    ok("certified" in str(vc), "A: verdict_covers says what is certified")
with h5py.File("s.h5", "r") as f:
    g = f["/rotor/design/ranked"]
    ok(int(g["feasible"][0]) == 1 and "members_certified" not in g, "A: symmetric run: feasible, no certification written")
# (B)
with h5py.File("b.h5", "r") as f:
    g = f["/rotor/design/ranked"]
    mc = g["members_certified"][:]; fe = g["feasible"][:]
    ok(all((fe == 0) | (mc == 1)), "B: feasible only when certified")
    ok(mc[0] == 1 and fe[0] == 1, "B: the best design is certified")
    m, r_, h, n = float(g["ball_mass"][0]), float(g["track_radius"][0]), float(g["ball_damping"][0]), int(g["n_balls"][0])
    ulo, uhi = float(g["member_u_min"][0]), float(g["member_u_max"][0])
    mcert = float(g["member_margin_certified"][0])
    ok(g["member_margin_certified"].attrs["units"] in (b"1/s", "1/s") and 0.2 <= mcert, "B: member_margin_certified %.6g >= 0.2 1/s, units 1/s" % mcert)
rng = np.random.default_rng(7)
ws = np.array([4500, 6750, 9000]) * math.pi / 30
worst = -1e9; uout = 0; nrun = 0
for k in range(40):
    s = rng.uniform(500e-6, 4000e-6)
    ang = random_member(n, m * r_, s, rng)
    u = m * m * abs(np.exp(2j * ang).sum()) ** 2 / 4
    if not (ulo - 1e-12 <= u <= uhi + 1e-12): uout += 1
    rr = stab("bestB.ini", m, r_, h, ws[k % 3], s, ang)
    if rr is None: worst = 1e9; continue
    nrun += 1
    worst = max(worst, rr["margin"])
ok(nrun == 40 and worst < -mcert, "B: 40 random members by rotor stability: largest margin %.6g < -member_margin_certified" % worst)
ok(uout == 0, "B: every random member's u inside the enclosure [%.6g, %.6g] kg^2" % (ulo, uhi))
print("%d passed, %d failed" % (npass, nfail))
sys.exit(1 if nfail else 0)
PY
[ $? -eq 0 ] && ok "independent checks (rotor stability runs)" || bad "independent checks"

# bad input
expect_err 3 "member_boxes" "$AUTOBAL" rotor design a.ini --set design.member_boxes=5
expect_err 3 "unbalance_member" "$AUTOBAL" rotor design a.ini --set design.n_balls_max=11
finish
