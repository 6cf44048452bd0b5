#!/usr/bin/env bash
# App test: values with units in configuration files (apps/units.c, docs/units.md).
# 1. Conversions: a config written in engineering units (rpm, Hz, g, mm, N/mm, g mm, deg, ms)
#    gives archives whose SI attributes equal the values converted with exact factors written
#    here by hand (independent of UDUNITS: 1 rpm = 2 pi/60 rad/s, 1 Hz = 2 pi rad/s for a shaft,
#    1 g mm = 1e-6 kg m, ...), and the same run written in SI gives identical datasets.
# 2. The bad-input catalogue: unknown unit, wrong dimension, ambiguous speed unit, negative,
#    NaN, m0 and unbalance together: exit 3 and a message naming the key.
# 3. rerun of an archive whose configuration has units reproduces it bit for bit.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
fail=0
ok()  { echo "ok   $*"; }
bad() { echo "FAIL $*"; fail=1; }

cat > eng.ini <<'INI'
; the default rotor, written as an engineer would
[rotor]
omega = 3000 rpm
M_k = 6000 g
A_k = 12 kg dm2
[supports]
l_L = 200 mm
l_R = 15 cm
c_Lx = 100 N/mm
c_Rx = 150 kN/m
h_Lx = 0.1 N s/mm
[plane1]
d = 100 mm
r0 = 100 mm
unbalance = 2000 g mm
psi0 = 0 deg
ball_mass = 50 g, 50 g
ball_radius = 100 mm
ball_damping = 100 g/s
ball_psi = 57.29577951308232 deg, 2.5 rad
[transient]
t_end = 200 ms
INI
cat > si.ini <<'INI'
[rotor]
omega = 314.15926535897932
M_k = 6
A_k = 0.12
[supports]
l_L = 0.2
l_R = 0.15
c_Lx = 100000
c_Rx = 150000
h_Lx = 100
[plane1]
d = 0.1
r0 = 0.1
m0 = 0.02
psi0 = 0
ball_mass = 0.05, 0.05
ball_radius = 0.1
ball_damping = 0.1
ball_psi = 1.0, 2.5
[transient]
t_end = 0.2
INI
"$AUTOBAL" rotor transient eng.ini -o eng.h5 -q || bad "engineering-unit run failed"
"$AUTOBAL" rotor transient si.ini -o si.h5 -q || bad "SI run failed"
"$AUTOBAL" rerun eng.h5 -o eng_rerun.h5 -q || bad "rerun of the engineering-unit archive failed"
"$AUTOBAL" rotor transient --set "rotor.omega=50 Hz" --set "transient.t_end=0.05" -o hz.h5 -q || bad "50 Hz run failed"
"$AUTOBAL" rotor transient --set "rotor.omega=50 rev/s" --set "transient.t_end=0.05" -o rev.h5 -q || bad "50 rev/s run failed"
"$AUTOBAL" pendulum roots --set "pendulum.M=10 kg" --set "pendulum.e=1 mm" --set "pendulum.m=500 g" \
  --set "pendulum.l=50 mm" --set "pendulum.c=1 kN/mm" --set "pendulum.H1=0.01 N m s" --set "pendulum.H2=10 N s/m" \
  --set "pendulum.omega=6000 rpm" -o pend.h5 -q || bad "pendulum physical run failed"
"$AUTOBAL" pendulum map "$DATA/pendulum_physical.ini" --set map.n_Rm=5 --set map.n_Rw=7 -o pmap.h5 -q || bad "pendulum map (physical) failed"
"$AUTOBAL" plot pmap.h5 -o pmap_png >/dev/null || bad "plot of the physical pendulum map failed"
"$PY" - <<'PY' || fail=1
import h5py, numpy as np, math, sys
bad = 0
def check(name, got, want, rel=1e-15):
    global bad
    ok = abs(got - want) <= rel * abs(want)
    print(("ok  " if ok else "FAIL") + f" {name}: {got!r} vs {want!r} (rel {rel:g})")
    bad += not ok
e = h5py.File("eng.h5", "r"); s = h5py.File("si.h5", "r")
r, p = e["rotor"].attrs, e["rotor/plane1"].attrs
check("omega 3000 rpm", r["omega"], 3000 * 2 * math.pi / 60)
check("M_k 6000 g", r["M_k"], 6.0)
check("A_k 12 kg dm2", r["A_k"], 0.12)
check("l_L 200 mm", r["l_L"], 0.2)
check("l_R 15 cm", r["l_R"], 0.15)
check("c_Lx 100 N/mm", r["c_Lx"], 1e5)
check("c_Rx 150 kN/m", r["c_Rx"], 1.5e5)
check("h_Lx 0.1 N s/mm", r["h_Lx"], 100.0)
check("m0 from unbalance 2000 g mm / r0 100 mm", p["m0"], 2000e-6 / 0.1)
check("ball_mass 50 g", p["ball_mass"][0], 0.05)
check("ball_damping 100 g/s", p["ball_damping"][1], 0.1)
check("ball_psi 57.29577951308232 deg", p["ball_psi_initial"][0], 1.0, 1e-15)
check("t_end 200 ms", e["rotor/transient/time"][-1], 0.2, 1e-12)
check("omega 50 Hz (revolutions per second)", h5py.File("hz.h5")["rotor"].attrs["omega"], 100 * math.pi)
check("omega 50 rev/s", h5py.File("rev.h5")["rotor"].attrs["omega"], 100 * math.pi)
q = h5py.File("pend.h5")["pendulum/physical"].attrs
for k, want in [("M", 10), ("e", 1e-3), ("m", 0.5), ("l", 0.05), ("c", 1e6), ("H1", 0.01), ("H2", 10), ("omega", 200 * math.pi)]:
    check(f"pendulum {k}", q[k], want)
# pendulum map with the physical set: the design point and the speed axis in rad/s (eq. (2))
g = h5py.File("pmap.h5")["pendulum/map"]; q = h5py.File("pmap.h5")["pendulum/physical"].attrs
w0 = math.sqrt(q["c"] / (q["M"] + 2 * q["m"]))
check("map design_R_w = omega/omega0", g.attrs["design_R_w"], q["omega"] / w0, 1e-14)
check("map design_R_m = m/(M + 2m)", g.attrs["design_R_m"], q["m"] / (q["M"] + 2 * q["m"]), 1e-14)
d = np.max(np.abs(g["omega"][()] - g["R_w"][()] * w0) / (g["R_w"][()] * w0))
print(("ok  " if d < 1e-14 else "FAIL") + f" map omega(R_w) = R_w omega0: {d:.1e}"); bad += not d < 1e-14
check("omega0 in /pendulum/physical", q["omega0"], w0, 1e-15)
# the same model in SI: the time series agree to rounding (the unit conversions differ from
# the SI literals by at most an ulp or two, e.g. 3000 rpm vs 314.15926535897932)
for name in ("x", "y", "p1_s_rel"):
    a, b = e["rotor/transient/" + name][()], s["rotor/transient/" + name][()]
    scale = np.max(np.abs(b))
    d = np.max(np.abs(a - b)) / scale
    ok = a.shape == b.shape and d < 1e-8
    print(("ok  " if ok else "FAIL") + f" {name}: engineering vs SI input, max diff / max = {d:.2e} (< 1e-8)")
    bad += not ok
# rerun: bit for bit
def walk(g, out):
    for k, v in g.items():
        if isinstance(v, h5py.Dataset): out[v.name] = v[()]
        else: walk(v, out)
A = {}; B = {}; walk(e, A); walk(h5py.File("eng_rerun.h5"), B)
same = A.keys() == B.keys() and all(np.array_equal(A[k], B[k]) for k in A)
print(("ok  " if same else "FAIL") + f" rerun of the engineering-unit archive: {len(A)} datasets identical")
bad += not same
sys.exit(1 if bad else 0)
PY

# 4. Engineering quantities of the transient summary against the closed-form steady unbalance
#    response of the linear rotor (3.2) (balls of negligible mass): complex amplitudes from
#    (K - w^2 M + i w H) Q = F solved here with NumPy; then the peak-to-peak displacement, the RMS
#    velocity at the supports and the ISO 21940-11 grade G = (m0 r0 / m_p) w follow in closed form.
"$AUTOBAL" rotor transient --set "rotor.omega=3000 rpm" --set "plane1.ball_mass=1e-9 g, 1e-9 g" \
  --set "plane1.ball_damping=1e-9 kg/s" --set "plane1.ball_psi=0, 180 deg" \
  --set "plane1.unbalance=200 g mm" --set "transient.t_end=5 s" --set "transient.balance_tol=1e-12" \
  --set "balance.grade=G6.3" -o steady.h5 --json > steady.json || bad "steady-response run failed"
"$PY" - <<'PY' || fail=1
import h5py, json, numpy as np, math, sys
bad = 0
def check(name, got, want, rel):
    global bad
    ok = abs(got - want) <= rel * abs(want)
    print(("ok  " if ok else "FAIL") + f" {name}: {got!r} vs closed form {want!r} (rel {rel:g})")
    bad += not ok
h = h5py.File("steady.h5", "r")
L = h["rotor/lumped"].attrs; R = h["rotor"].attrs; P = h["rotor/plane1"].attrs; T = h["rotor/transient"].attrs
w = R["omega"]; U = P["m0"] * P["r0"]; d = P["d"]
M, A, C = L["M"], L["A"], L["C"]
Mm = np.diag([M, M, A, A])
K = np.array([[L["c_x"], 0, 0, -L["c_xbeta"]], [0, L["c_y"], L["c_yalpha"], 0],
              [0, L["c_yalpha"], L["c_alpha"], 0], [-L["c_xbeta"], 0, 0, L["c_beta"]]])
H = np.array([[L["h_x"], 0, 0, -L["h_xbeta"]], [0, L["h_y"], L["h_yalpha"], 0],
              [0, L["h_yalpha"], L["h_alpha"], C * w], [-L["h_xbeta"], 0, -C * w, L["h_beta"]]])
# s_u = U cos wt = Re(U e^{iwt}), s_v = U sin wt = Re(-i U e^{iwt}); forcing -s'' terms of (3.2)
F = U * w**2 * np.array([1, -1j, d * 1j, d])
Q = np.linalg.solve(K - w**2 * Mm + 1j * w * H, F)
X, Y, Al, Be = Q
def rms(z): return abs(1j * w * z) / math.sqrt(2)          # RMS of Re(i w z e^{iwt})
vs = []
for p in (-R["l_L"], R["l_R"]):
    vs += [rms(X + p * Be), rms(Y - p * Al)]
check("displacement peak-to-peak at G", T["displacement_pk_pk_G_last_10pct"], 2 * max(abs(X), abs(Y)), 1e-6)
check("velocity RMS at G", T["velocity_rms_G_last_10pct"], max(rms(X), rms(Y)), 1e-6)
check("velocity RMS at the left support", T["velocity_rms_left_support_last_10pct"], max(vs[0], vs[1]), 1e-6)
check("velocity RMS at the right support", T["velocity_rms_right_support_last_10pct"], max(vs[2], vs[3]), 1e-6)
check("residual unbalance |s| (g mm)", T["residual_unbalance_abs_final"][0] * 1e6, 200.0, 1e-9)
check("balance grade G = U/m_p w (mm/s)", T["balance_grade_final"], U / R["m_p"] * w * 1e3, 1e-9)
check("permissible unbalance of G6.3 (kg m)", T["permissible_unbalance"], 6.3e-3 / w * R["m_p"], 1e-12)
met = T["permissible_unbalance_met"] == (U <= 6.3e-3 / w * R["m_p"])
print(("ok  " if met else "FAIL") + " G6.3 met or not as the closed form says"); bad += not met
j = json.load(open("steady.json"))
ok = j["units"]["balance_grade_final"] == "mm/s" and j["units"]["velocity_rms_supports_last_10pct"] == "m/s" \
     and abs(j["velocity_rms_supports_last_10pct"] - max(vs)) <= 1e-6 * max(vs)
print(("ok  " if ok else "FAIL") + " --json carries the values and their units"); bad += not ok
sys.exit(1 if bad else 0)
PY

# 5. Two planes: the text and --json summaries report every plane; the balanced configuration
#    of each plane against the closed form psi = psi0 + pi -/+ arccos(m0 r0 / (2 m r)) (two equal
#    balls), the final ball angles against it, and |s_j| against the archive's last p<j>_s_abs.
"$AUTOBAL" rotor transient "$DATA/rotor_two_planes.ini" --set transient.t_end=5 -o two.h5 --json > two.json ||
  bad "two-plane run failed"
"$AUTOBAL" rotor transient "$DATA/rotor_two_planes.ini" --set transient.t_end=5 > two.txt || bad "two-plane text run failed"
for j in 1 2; do
  for needle in "plane $j: residual unbalance" "plane $j ball angles relative to the rotor" "balanced configuration (3.14) of plane $j"; do
    grep -qF "$needle" two.txt && ok "text summary: '$needle'" || bad "text summary lacks '$needle'"
  done
done
"$PY" - <<'PY' || fail=1
import h5py, json, math, sys
bad = 0
j = json.load(open("two.json")); h = h5py.File("two.h5", "r")
def wrap(a): return math.remainder(a, 2 * math.pi)
for pl in j["planes"]:
    k = pl["plane"]; P = h[f"rotor/plane{k}"].attrs
    m, r = P["ball_mass"][0], P["ball_radius"][0]
    c = math.acos(P["m0"] * P["r0"] / (2 * m * r))
    want = sorted(wrap(P["psi0"] + math.pi + sgn * c) for sgn in (-1, 1))
    got_bal = sorted(pl["ball_psi_balanced"]); got_fin = sorted(pl["ball_psi_final"])
    e1 = max(abs(wrap(a - b)) for a, b in zip(got_bal, want))
    e2 = max(abs(wrap(a - b)) for a, b in zip(got_fin, want))
    s_last = h[f"rotor/transient/p{k}_s_abs"][-1]
    e3 = abs(pl["residual_unbalance_abs"] - s_last)
    for name, e, tol in (("balanced configuration vs closed form", e1, 1e-12), ("final angles vs closed form", e2, 1e-6),
                         ("|s_j| vs the archive's last p<j>_s_abs", e3, 1e-15)):
        ok = e <= tol
        print(("ok  " if ok else "FAIL") + f" plane {k}: {name}: {e:.2e} (<= {tol:g})"); bad += not ok
    ok = pl["units"]["residual_unbalance_abs"] == "kg m" and pl["units"]["ball_psi_final"] == "rad"
    print(("ok  " if ok else "FAIL") + f" plane {k}: units in the JSON plane object"); bad += not ok
ok = len(j["planes"]) == 2 and len(j["residual_unbalance_abs_final"]) == 2
print(("ok  " if ok else "FAIL") + " --json reports both planes"); bad += not ok
sys.exit(1 if bad else 0)
PY

# bad-input catalogue: exit 3 and the key named
expect3() {
  local needle=$1; shift
  "$AUTOBAL" "$@" -q >out.txt 2>err.txt; local rc=$?
  if [ "$rc" -eq 3 ] && grep -qF -- "$needle" err.txt; then ok "exit 3 '$needle': $*"
  else bad "exit $rc (want 3, '$needle'): $*"; cat err.txt; fi
}
expect3 "rotor.omega = '3 kg'" rotor transient --set "rotor.omega=3 kg"
expect3 "cannot be converted to rad/s" rotor transient --set "rotor.omega=3 kg"
expect3 "unknown unit 'furlongz'" rotor transient --set "rotor.omega=3 furlongz"
expect3 "ambiguous" rotor transient --set "rotor.omega=3000 1/min"
expect3 "ambiguous" rotor stability --set "rotor.omega=50 1/s"
expect3 "plane1.m0" rotor transient --set "plane1.m0=-5 g"
expect3 "not a finite number" rotor transient --set "plane1.m0=nan g"
expect3 "plane1.unbalance" rotor transient --set "plane1.unbalance=200 g"
expect3 "give either m0 or unbalance" rotor transient --set "plane1.unbalance=200 g mm" --set "plane1.m0=1 g"
expect3 "plane1.ball_mass: item 2" rotor transient --set "plane1.ball_mass=50 g, 5 s"
expect3 "supports.c_Lx" rotor transient --set "supports.c_Lx=100 N"
expect3 "pendulum.omega" pendulum roots --set "pendulum.M=10 kg" --set "pendulum.e=1 mm" --set "pendulum.m=500 g" \
  --set "pendulum.l=50 mm" --set "pendulum.c=1 kN/mm" --set "pendulum.H1=0" --set "pendulum.H2=0" --set "pendulum.omega=100 m"
expect3 "balance quality grade" rotor transient --set "balance.grade=X2.5"
expect3 "balance quality grade" rotor transient --set "balance.grade=G-1"
expect3 "pendulum.R_m = '0.1 kg' is dimensionless" pendulum roots --set "pendulum.R_m=0.1 kg"
exit $fail
