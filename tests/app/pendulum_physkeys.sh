#!/usr/bin/env bash
# App test: `autobal pendulum sweep|map` over the physical keys of [pendulum] (M, e, m, l, c, H1, H2,
# omega; docs/pendulum.md "Physical keys on an axis"), run as a user would from
# data/pendulum_physical.ini with ranges in the keys' units (rpm, g, cm); the archives are checked by
# pendulum_physkeys_check.py against an independent conversion (2)-(3) and:
#   - omega at k = 0, undamped: the critical speeds (13) and the roots of (12) (SymPy, exact);
#   - c and m, undamped: the verdict of (10) from 30-digit roots, changes bisected;
#   - H1, damped, and omega for every unbalance (data/pendulum_physical_speed.ini): NumPy eigenvalues
#     of (5), changes bisected;
#   - maps over (m, l) and (e, R_w), damped: NumPy eigenvalues of (5) at every point.
# Then: a rerun reproduces a physical sweep bit for bit; bad input (unknown key, a key mixed with a
# dimensionless parameter it determines, a physical key of a dimensionless configuration, a range
# leaving the model's domain, a unit of the wrong kind, every unbalance with e) exits 3 with the key
# and the allowed range named, nothing written.
set -u
: "${AUTOBAL:?}" "${DATA:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"
A=$AUTOBAL
C="$DATA/pendulum_physical.ini"
U="--set pendulum.H1=0 --set pendulum.H2=0"
chk() { "$PY" "$here/pendulum_physkeys_check.py" "$@" && ok "checked: $*" || bad "check: $*"; }

expect 0 "critical values of omega" $A pendulum sweep "$C" $U --set pendulum.e=0 --set "pendulum.m=1 kg" \
  --set sweep.param=omega --set "sweep.min=500 rpm" --set "sweep.max=3000 rpm" --set sweep.n=400 -o omega.h5
grep -q "rpm)   unstable -> stable" out.txt && ok "critical speeds also in rpm" || bad "no rpm in the summary"
chk omega_k0 omega.h5 500
expect 0 "critical values of c" $A pendulum sweep "$C" $U --set pendulum.e=0.01 --set pendulum.m=1 \
  --set sweep.param=c --set sweep.min=2e4 --set "sweep.max=1 MN/m" --set sweep.n=300 -o c.h5
chk undamped c.h5
expect 0 "critical values of m" $A pendulum sweep "$C" $U --set pendulum.omega=150 --set sweep.param=m \
  --set "sweep.min=70 g" --set "sweep.max=2 kg" --set sweep.n=300 -o m.h5
chk undamped m.h5
expect 0 "critical values of H1" $A pendulum sweep "$C" --set sweep.param=H1 --set sweep.n=200 -o H1.h5
chk damped H1.h5
expect 0 "critical values of omega" $A pendulum sweep "$DATA/pendulum_physical_speed.ini" -o speed.h5
chk damped speed.h5
expect 0 "map 12 x 10 over m in [0.12, 0.5] kg (log), l in [0.15, 0.45] m (log)" $A pendulum map "$C" \
  --set pendulum.H2=300 --set map.param1=m --set "map.min1=120 g" --set "map.max1=500 g" --set map.n1=12 \
  --set map.param2=l --set "map.min2=15 cm" --set "map.max2=45 cm" --set map.n2=10 -o ml.h5
chk map ml.h5
expect 0 "physical axis" $A pendulum map "$C" --set pendulum.H1=0.05 --set map.param1=e --set "map.max1=2.9 mm" \
  --set map.n1=8 --set map.param2=R_w --set map.min2=0.5 --set map.max2=4 --set map.n2=15 -o eRw.h5
chk map eRw.h5
expect 0 '"param":"H1"' $A pendulum sweep "$C" --set sweep.param=H1 --set sweep.n=50 --json
grep -qF '"critical":"N m s"' out.txt && ok "JSON critical values with their unit" || { bad "JSON unit"; cat out.txt; }

# every point's own dimensionless set (/.../point), from the physical set and the axis values by the formulas of
# docs/pendulum.md in NumPy; none for dimensionless axes
"$PY" - <<'PY' && ok "point/: each point's R_w, R_m, H, h, psi0, k from the physical set" || bad "point/ datasets"
import h5py, numpy as np
def conv(P):
    Ms = P["M"] + 2 * P["m"]; w0 = np.sqrt(P["c"] / Ms); s = P["M"] * P["e"] / (2 * P["m"] * P["l"])
    psi0 = np.arcsin(s)
    return dict(R_w=P["omega"] / w0, R_m=P["m"] / Ms, H=P["H2"] / (w0 * Ms), h=P["H1"] / (P["m"] * P["l"]**2 * w0),
                psi0=psi0, k=np.sin(2 * psi0)**2)
for f, g, axes in (("ml.h5", "pendulum/map", ("m", "l")), ("speed.h5", "pendulum/sweep", ("omega",))):
    with h5py.File(f) as h:
        P = {k: float(v) for k, v in h["pendulum/physical"].attrs.items() if not k.endswith("_units")}
        grids = np.meshgrid(*[h[g][a][:] for a in axes], indexing="ij")
        for a, v in zip(axes, grids): P[a] = v
        want = conv(P)
        names = ("R_w", "R_m", "H", "h") if h[g].attrs["every_unbalance"] else tuple(want)
        for n in names:
            got = h[g]["point"][n][:]
            assert got.shape == grids[0].shape, (f, n, got.shape)
            assert np.allclose(got, want[n], rtol=1e-13, atol=1e-15), (f, n, np.max(np.abs(got - want[n])))
            for i, a in enumerate(axes):  # the axes' coordinates attached as dimension scales
                assert h[g]["point"][n].dims[i][0].name == "/%s/%s" % (g, a), (f, n, i)
with h5py.File("eRw.h5") as h: assert "point" in h["pendulum/map"]
PY
expect 0 "" $A pendulum map --set map.n1=3 --set map.n2=3 -o dimless.h5
"$PY" -c "import h5py; assert 'point' not in h5py.File('dimless.h5')['pendulum/map']" && ok "no point/ for dimensionless axes" \
  || bad "point/ written for dimensionless axes"

# the plotting tool's titles and axes for physical axes: a parameter an axis moves (docs/pendulum.md: m and l move
# h, H and k) is not printed with the configuration's value; a speed axis also in rev/min
"$PY" - "$TOOLS" <<'PY' && ok "autobal_plot.py: titles name what varies over physical axes" || bad "autobal_plot.py titles"
import sys, importlib.util, h5py
spec = importlib.util.spec_from_file_location("ap", sys.argv[1] + "/autobal_plot.py"); ap = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ap)
figs = {}
ap.save = lambda fig, outdir, stem, name, written: figs.__setitem__(stem, fig)
with h5py.File("ml.h5") as h: ap.plot_pendulum_map(h, ".", "ml", [])
with h5py.File("speed.h5") as h: ap.plot_pendulum_sweep(h, ".", "speed", [])
with h5py.File("eRw.h5") as h: ap.plot_pendulum_map(h, ".", "eRw", [])
t = figs["ml"].axes[0].get_title()
assert "k = sin²(2ψ0) varies over the map" in t and "H and h vary over the map" in t and "k = 0" not in t, t
ax = figs["speed"].axes[0]
t = ax.get_title()
assert "R_w =" not in t and "R_m =" in t, t  # omega moves R_w only
assert any("rev/min" in a.get_xlabel() for a in ax.child_axes), [a.get_xlabel() for a in ax.child_axes]
t = figs["eRw"].axes[0].get_title()
assert "varies over the map" in t and "h = " in t and "H = " in t, t  # e moves k only
PY

# a rerun of a physical sweep: the same archive data
run $A rerun m.h5 -o m2.h5 -q
h5diff m.h5 m2.h5 /pendulum/sweep /pendulum/sweep >/dev/null && ok "rerun: /pendulum/sweep bit for bit" || bad "rerun differs"

# bad input
expect_err 3 "allowed R_w, R_m, H, h, k, psi0, H/h (dimensionless) and, with a [pendulum] given by its physical keys, M, e, m, l, c, H1, H2, omega" \
  $A pendulum sweep "$C" --set sweep.param=mass -o bad1.h5
expect_err 3 "axes pendulum.omega and pendulum.R_w cannot be combined: R_w is a function of omega" \
  $A pendulum map "$C" --set map.param1=omega --set map.param2=R_w -o bad2.h5
expect_err 3 "axes pendulum.m and pendulum.k cannot be combined" $A pendulum map "$C" --set map.param1=m --set map.param2=k -o bad3.h5
expect_err 3 "pendulum.omega is a physical key: it needs the physical set" $A pendulum sweep --set sweep.param=omega -o bad4.h5
expect_err 3 "pendulum.e = 0.05 m leaves the model's domain" $A pendulum sweep "$C" --set sweep.param=e --set "sweep.max=5 cm" -o bad5.h5
grep -qF "pendulum.e must lie in [0, 0.003) m" err.txt && ok "... and names the allowed range (2 m l / M = 3 mm)" || bad "no range: $(cat err.txt)"
expect_err 3 "pendulum.m = 0.01 kg leaves the model's domain" $A pendulum sweep "$C" --set sweep.param=m --set "sweep.min=10 g" -o bad6.h5
grep -qF "pendulum.m must lie in (0.0666667," err.txt && ok "... m > M e / (2 l) = 0.0666667 kg" || bad "no range: $(cat err.txt)"
expect_err 3 "cannot be converted to rad/s" $A pendulum sweep "$C" --set sweep.param=omega --set "sweep.max=3 kg" -o bad7.h5
expect_err 3 "pendulum.M = -1 kg is too small: must be > 0 kg" $A pendulum sweep "$C" --set sweep.param=M --set sweep.min=-1 -o bad8.h5
expect_err 3 "cannot be combined with an e axis" $A pendulum sweep "$C" --set sweep.param=e --set sweep.every_unbalance=true -o bad9.h5
expect_err 3 "axes pendulum.H1 and pendulum.H/h cannot be combined" $A pendulum map "$C" --set map.param1=H1 --set map.param2=H/h -o bad10.h5
n=$(ls bad*.h5 2>/dev/null | wc -l)
[ "$n" -eq 0 ] && ok "no archive written on bad input" || bad "$n archives written on bad input"
finish
