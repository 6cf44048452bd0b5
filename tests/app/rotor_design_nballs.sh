#!/usr/bin/env bash
# rotor design with the number of balls as a design bound (docs/rotor.md "Design", "Number of balls"),
# on two constructed cases, each verified by direct `rotor stability` runs (not by the design's code):
#  (A) 3 balls feasible, 2 not: 50 g on 100 mm, 1 kg/s, every m0 r0 in 500..11000 g mm: two balls
#      cannot balance 11000 g mm (2 m r = 10000 g mm, closed form; `rotor stability` with two balls
#      refuses that unbalance), three can (3 m r = 15000 g mm) and `rotor stability` finds the three
#      balls stable for every unbalance of the range at every grid speed (its every-unbalance
#      analysis, symmetric members) with every sampled single-unbalance margin below -margin; the
#      written best config runs with `rotor stability`/`rotor sweep` and reproduces the reported robust margin
#      (the smallest -margin over the grid speeds and 401 unbalances, within 1e-3 (1 + rho) + 2%);
#      its transients run with three balls;
#  (B) the reverse, by stability: 0.3 kg/s, 500..5500 g mm: two balls feasible, three not; a
#      single-unbalance `rotor stability` run of three balls at a grid speed has a root with
#      Re lambda >= -margin (a counterexample), and every sampled two-ball margin is below -margin;
#  (C) the archive: n_balls coordinate (units 1), one group per n with its map, the ranked n_balls,
#      the member rule said; bad input names its key (exit 3).
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

cat > a.ini <<'INI'
[design]
speed_min = 4500 rpm
speed_max = 9000 rpm
n_speed = 9
unbalance_min = 500 g mm
unbalance_max = 11000 g mm
margin = 0.2
ball_mass_min = 50 g
ball_mass_max = 50 g
track_radius_min = 100 mm
track_radius_max = 100 mm
ball_damping_min = 1
ball_damping_max = 1
n_best = 3
n_transient = 1
n_start_angles = 2
n_transient_unbalances = 1
n_transient_speeds = 1
transient_t_end = 4 s
n_balls_min = 2
n_balls_max = 3
unbalance_member = symmetric
INI
expect 0 "symmetric members only" "$AUTOBAL" rotor design a.ini -o a.h5 --set design.config_out=bestA.ini
[ -s bestA.ini ] && ok "bestA.ini written" || bad "bestA.ini missing"
grep -q "symmetric members of the family only" bestA.ini && ok "best config names the member rule" || bad "no member rule in bestA.ini"

# (B): [stability] unbalance_member is the default of [design] unbalance_member
sed -e 's/^unbalance_max = .*/unbalance_max = 5500 g mm/' -e 's/^ball_damping_m\(in\|ax\) = 1$/ball_damping_m\1 = 0.3/' \
    -e 's/^n_transient = 1/n_transient = 0/' -e '/^unbalance_member/d' a.ini > b.ini
printf '\n[stability]\nunbalance_member = symmetric\n' >> b.ini
expect 0 "ranked designs" "$AUTOBAL" rotor design b.ini -o b.h5

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
def stab(n, h, w, s, extra=(), member=True):
    args = [A, "rotor", "stability", "--json", "--set", "rotor.omega=%r" % w, "--set", "plane1.m0=%r" % (s / 0.1),
            "--set", "plane1.ball_mass=" + ",".join(["0.05"] * n), "--set", "plane1.ball_radius=" + ",".join(["0.1"] * n),
            "--set", "plane1.ball_damping=" + ",".join([repr(h)] * n),
            "--set", "plane1.ball_psi=" + ",".join(str(2 * i) for i in range(n)),
            "--set", "plane1.ball_rate=" + ",".join(["0"] * n)]
    if member and n >= 3: args += ["--set", "stability.unbalance_member=symmetric"]
    r = subprocess.run(args + list(extra), capture_output=True, text=True)
    return r.returncode, (json.loads(r.stdout) if r.returncode == 0 and r.stdout.strip() else None), r.stderr
w = np.linspace(4500, 9000, 9) * math.pi / 30
delta = 0.2
# (A)
with h5py.File("a.h5", "r") as f:
    g = f["/rotor/design"]
    ok(list(g["n_balls"][:]) == [2, 3] and g["n_balls"].attrs["units"] in (b"1", "1"), "A: n_balls coordinate [2, 3], units 1")
    f2 = g["n_balls_2/feasible"][:].ravel(); f3 = g["n_balls_3/feasible"][:].ravel()
    ok(list(f2) == [-1], "A: two balls: -1 (cannot balance 11000 g mm)")
    ok(list(f3) == [1], "A: three balls feasible")
    dims = [d[0].name.split("/")[-1] for d in [g["n_balls_3/feasible"].dims[i] for i in range(4)]]
    ok(dims == ["ball_mass", "ball_damping", "plane_position", "track_radius"], "A: map dimensions named %s" % dims)
    ra = g["ranked"]
    nb = list(ra["n_balls"][:]); rho = float(ra["robust_margin"][0])
    ok(nb[0] == 3 and ra["feasible"][0] == 1 and ra["recheck"][0] == 1, "A: best design has 3 balls, feasible, re-checked")
    ok(all(n == 3 for n in nb), "A: no two-ball design ranked (%s)" % nb)
    ok("symmetric" in str(g.attrs["verdict_covers"]) and str(g.attrs["unbalance_member"]).strip("b'") == "symmetric",
       "A: the archive says which members the verdict covers")
    ok(int(ra["transient_members"][0]) == 4, "A: transients of the best design run (4 members)")
rc, j, err = stab(2, 1.0, w[0], 0.011)
ok(j is None and "cannot" in err, "A: rotor stability, two balls at 11000 g mm: no balanced configuration")
allstable = True; worst = -np.inf
us = np.linspace(0.0005, 0.011, 7)
for wk in w:
    rc, j, err = stab(3, 1.0, wk, 0.002, ["--set", "stability.unbalance_min=0.0005", "--set", "stability.unbalance_max=0.011"])
    allstable &= bool(j and j["every_unbalance"]["stable_for_all"])
for wk in w:
    for s in us:
        rc, j, err = stab(3, 1.0, wk, s)
        worst = max(worst, j["margin"] if j else np.inf)
ok(allstable, "A: rotor stability (every unbalance, symmetric) stable for all of 500..11000 g mm at the 9 grid speeds")
ok(worst < -delta, "A: every sampled margin of three balls below -0.2 (largest %.6g)" % worst)
# the best config reproduces the reported margin: rotor sweep of unbalance_mass (401 values) at every grid speed
worst_cfg = -np.inf
for k, wk in enumerate(w):
    r = subprocess.run([A, "rotor", "sweep", "bestA.ini", "-q", "--force", "-o", "sw.h5", "--set", "rotor.omega=%r" % wk,
                        "--set", "sweep.param=unbalance_mass", "--set", "sweep.min=0.005", "--set", "sweep.max=0.11",
                        "--set", "sweep.n=401"], capture_output=True, text=True)
    if r.returncode != 0:
        worst_cfg = np.inf; print(r.stderr); break
    with h5py.File("sw.h5", "r") as f:
        worst_cfg = max(worst_cfg, float(np.max(f["/rotor/sweep/margin"][:])))
acc = 1e-3 * (1 + abs(rho))
ok(rho <= -worst_cfg + acc and rho >= -worst_cfg - 0.02 * abs(worst_cfg) - acc,
   "A: rotor sweep on bestA.ini reproduces the robust margin: reported %.6g, sampled %.6g" % (rho, -worst_cfg))
# (B)
with h5py.File("b.h5", "r") as f:
    g = f["/rotor/design"]
    ok(list(g["n_balls_2/feasible"][:].ravel()) == [1] and list(g["n_balls_3/feasible"][:].ravel()) == [0],
       "B: two balls feasible, three not")
    ok(list(g["ranked/n_balls"][:]) == [2], "B: the one ranked design has two balls")
cex = None; w2 = -np.inf
for wk in w:
    for s in np.linspace(0.0005, 0.0055, 11):
        rc, j, err = stab(3, 0.3, wk, s)
        if j and j["margin"] >= -delta and cex is None: cex = (wk, s, j["margin"])
        rc, j2, err = stab(2, 0.3, wk, s)
        w2 = max(w2, j2["margin"] if j2 else np.inf)
ok(cex is not None, "B: three balls: a direct run with margin >= -0.2: %s" % (cex,))
ok(w2 < -delta, "B: every sampled two-ball margin below -0.2 (largest %.6g)" % w2)
print("%d passed, %d failed" % (npass, nfail))
sys.exit(1 if nfail else 0)
PY
[ $? -eq 0 ] && ok "independent checks (rotor stability runs)" || bad "independent checks"

# bad input
expect_err 3 "unbalance_member" "$AUTOBAL" rotor design a.ini --set design.unbalance_member=every --set design.n_balls_max=11
expect_err 3 "n_balls_min" "$AUTOBAL" rotor design a.ini --set design.n_balls_min=1
expect_err 3 "n_balls_max" "$AUTOBAL" rotor design a.ini --set design.n_balls_max=17
expect_err 3 "total_ball_mass_max" "$AUTOBAL" rotor design a.ini --set "design.total_ball_mass_max=-1 g"
finish
