#!/usr/bin/env bash
# App test: [transient] output = dense6 (issue 20, "output for free") with stepper = dop853, pendulum
# and rotor: DOP853's order-6 continuous extension from the step's own stages (no extra right-hand
# side).  Checked: the archive records output = dense6 (and derived_math = fastmath; libm for dense and
# rk8pd) and `autobal rerun` reproduces it bit for bit;
# output every quarter revolution costs exactly the right-hand sides of the run without an output
# grid (the steps are not cut and the extension needs none; the balance monitor is located on it);
# the error at the output points against a tight reference (rk8pd, steps cut at the output times,
# rtol 1e-13: another integrator) is within 1.5 x that of contd8 (output = dense) at rtol 1e-6,
# 1e-8, 1e-10 (bench/dense_order6.py predicts 0.99-1.08 on the bench's cases).
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

P="--set transient.t_end=200 --set transient.stepper=dop853"
R="--set transient.t_end=0.5 --set transient.stepper=dop853"
for tol in 1e-6 1e-8 1e-10; do
  atol=$tol  # rtol = atol as in bench/run.sh dense
  for mode in dense dense6; do
    run "$AUTOBAL" pendulum transient $P --set transient.rtol=$tol --set transient.atol=$atol --set transient.output=$mode -o p_${mode}_$tol.h5
    run "$AUTOBAL" rotor transient $R --set transient.rtol=$tol --set transient.atol=$tol --set transient.output=$mode -o r_${mode}_$tol.h5
  done
  run "$AUTOBAL" pendulum transient $P --set transient.rtol=$tol --set transient.atol=$atol --set transient.output=dense6 --set transient.dt_out=200 -o p_none_$tol.h5
  run "$AUTOBAL" rotor transient $R --set transient.rtol=$tol --set transient.atol=$tol --set transient.output=dense6 --set transient.dt_out=0.5 -o r_none_$tol.h5
done
# the references: rk8pd (the default until 0.2.0, pinned since dop853 dense6 became the default)
run "$AUTOBAL" pendulum transient --set transient.t_end=200 --set transient.rtol=1e-13 --set transient.atol=1e-14 --set transient.stepper=rk8pd -o pref.h5
run "$AUTOBAL" rotor transient --set transient.t_end=0.5 --set transient.rtol=1e-13 --set transient.atol=1e-13 --set transient.stepper=rk8pd -o rref.h5
run "$AUTOBAL" rerun p_dense6_1e-8.h5 -o p_rerun.h5 -q
run "$AUTOBAL" rerun r_dense6_1e-8.h5 -o r_rerun.h5 -q
"$PY" - <<'PYEOF' && ok "dense6: attribute, rerun bit for bit, rhs with output = without, error <= 1.5 x contd8's" || bad "dense6"
import h5py, numpy as np, sys
fails = 0
def attr(g, k):
    v = g.attrs[k]
    return v.decode() if isinstance(v, bytes) else str(v)
cases = (("pendulum", "p", "/pendulum/transient", ["xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate"]),
         ("rotor", "r", "/rotor/transient", ["x", "y", "x_rate", "y_rate", "state_phi_1", "state_phi_2", "p1_s_abs"]))
for kind, p, grp, names in cases:
    with h5py.File(p + "ref.h5", "r") as f:
        ref = np.array([f[grp][n][()] for n in names])
        if attr(f[grp], "derived_math") != "libm":  # rk8pd: libm, as in 0.1.0
            print(f"FAIL {kind} reference (rk8pd): derived_math {attr(f[grp], 'derived_math')!r}, want 'libm'"); fails += 1
    sc = np.max(np.abs(ref), axis=1)[:, None]
    sc[sc == 0] = 1
    if kind == "rotor":
        sc[4:6] = 1.0  # ball angles: absolute (rad)
    for tol in ("1e-6", "1e-8", "1e-10"):
        err, rhs = {}, {}
        for mode in ("dense", "dense6", "none"):
            with h5py.File(f"{p}_{mode}_{tol}.h5", "r") as f:
                g = f[grp]
                want = "dense6" if mode != "dense" else "dense"
                if attr(g, "output") != want:
                    print(f"FAIL {kind} {mode} {tol}: output attribute {attr(g, 'output')!r}, want {want!r}"); fails += 1
                # dense6's derived columns by the library's sin, cos, hypot; every other mode libm's
                want_dm = "fastmath" if want == "dense6" else "libm"
                if attr(g, "derived_math") != want_dm:
                    print(f"FAIL {kind} {mode} {tol}: derived_math {attr(g, 'derived_math')!r}, want {want_dm!r}"); fails += 1
                rhs[mode] = int(f[grp + "/solver"].attrs["rhs_evaluations"])
                if mode != "none":
                    y = np.array([g[n][()] for n in names])
                    if y.shape != ref.shape:
                        print(f"FAIL {kind} {mode} {tol}: shape {y.shape} vs {ref.shape}"); fails += 1; continue
                    err[mode] = np.max(np.abs(y - ref) / sc)
        r = err["dense6"] / err["dense"]
        print(f"{kind} rtol {tol}: error at the output points contd8 {err['dense']:.3e}, order 6 {err['dense6']:.3e} "
              f"(ratio {r:.3f}); rhs contd8 {rhs['dense']}, order 6 {rhs['dense6']}, order 6 without output grid {rhs['none']}")
        if not r <= 1.5:
            print(f"FAIL {kind} {tol}: order-6 error above 1.5 x contd8's"); fails += 1
        if rhs["dense6"] != rhs["none"]:
            print(f"FAIL {kind} {tol}: output grid cost {rhs['dense6'] - rhs['none']} right-hand sides"); fails += 1
        if not rhs["dense"] > rhs["dense6"]:
            print(f"FAIL {kind} {tol}: contd8 not dearer"); fails += 1
    # rerun: every dataset of the transient group equal, bit for bit
    with h5py.File(f"{p}_dense6_1e-8.h5", "r") as a, h5py.File(f"{p}_rerun.h5", "r") as b:
        ga, gb = a[grp], b[grp]
        if attr(gb, "output") != "dense6":
            print(f"FAIL {kind}: rerun output attribute {attr(gb, 'output')!r}"); fails += 1
        n = 0
        for k in ga:
            if isinstance(ga[k], h5py.Dataset):
                n += 1
                if k not in gb or not np.array_equal(ga[k][()], gb[k][()]):
                    print(f"FAIL {kind}: rerun dataset {k} differs"); fails += 1
        print(f"{kind}: rerun of the dense6 run: {n} datasets compared")
        if n < len(names):
            print(f"FAIL {kind}: only {n} datasets"); fails += 1
sys.exit(1 if fails else 0)
PYEOF
expect_err 3 "dense, dense6, exact" "$AUTOBAL" pendulum transient --set transient.output=dense5
expect_err 3 "dense, dense6, exact" "$AUTOBAL" rotor transient --set transient.output=dense7
finish
