#!/usr/bin/env bash
# App test: [transient] output = dense|exact (issue 20) with stepper = dop853, pendulum and rotor:
# the archive records the mode; dense and exact runs give the same series within the tolerance
# (two independent ways to the output points: the continuous extension and steps cut there) and
# both agree with a tight exact-hit run; dense output needs fewer right-hand sides; bad values
# are refused with exit 3.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}"
. "$(dirname "$0")/common.bash"

P="--set transient.t_end=200 --set transient.rtol=1e-9 --set transient.atol=1e-11"
# output = dense (contd8) given: dop853's default output is dense6 since 0.2.0 (tests/app/dense6.sh);
# the references rk8pd, given since dop853 is the default stepper
run "$AUTOBAL" pendulum transient $P --set transient.stepper=dop853 --set transient.output=dense -o pd.h5
run "$AUTOBAL" pendulum transient $P --set transient.stepper=dop853 --set transient.output=exact -o px.h5
run "$AUTOBAL" pendulum transient --set transient.t_end=200 --set transient.rtol=1e-13 --set transient.atol=1e-14 --set transient.stepper=rk8pd -o pref.h5
R="--set transient.t_end=0.5 --set transient.rtol=1e-10 --set transient.atol=1e-9"
run "$AUTOBAL" rotor transient $R --set transient.stepper=dop853 --set transient.output=dense -o rd.h5
run "$AUTOBAL" rotor transient $R --set transient.stepper=dop853 --set transient.output=exact -o rx.h5
run "$AUTOBAL" rotor transient --set transient.t_end=0.5 --set transient.rtol=1e-13 --set transient.atol=1e-13 --set transient.stepper=rk8pd -o rref.h5
"$PY" - <<'PYEOF' && ok "dense vs exact vs tight reference, archive attribute 'output', rhs counts" || bad "dense vs exact"
import h5py, numpy as np, sys
def series(path, grp, names):
    f = h5py.File(path, "r")
    g = f[grp]
    return f, g, np.array([g[n][()] for n in names])
fails = 0
for kind, grp, names, tol in (("pendulum", "/pendulum/transient", ["xi", "eta", "psi", "phi", "xi_rate", "eta_rate", "psi_rate", "phi_rate"], 1e-6),
                              ("rotor", "/rotor/transient", ["x", "y", "x_rate", "y_rate", "state_phi_1", "state_phi_2", "p1_s_abs"], None)):
    p = "p" if kind == "pendulum" else "r"
    fd, gd, d = series(p + "d.h5", grp, names)
    fx, gx, x = series(p + "x.h5", grp, names)
    fr, gr, r = series(p + "ref.h5", grp, names)
    mode_d = gd.attrs["output"].decode() if isinstance(gd.attrs["output"], bytes) else str(gd.attrs["output"])
    mode_x = gx.attrs["output"].decode() if isinstance(gx.attrs["output"], bytes) else str(gx.attrs["output"])
    if mode_d != "dense" or mode_x != "exact" or "output" in gr.attrs:
        print(f"FAIL {kind}: output attributes {mode_d!r}, {mode_x!r}, reference has one: {'output' in gr.attrs}"); fails += 1
    if d.shape != x.shape or d.shape != r.shape:
        print(f"FAIL {kind}: shapes {d.shape} {x.shape} {r.shape}"); fails += 1; continue
    sc = np.max(np.abs(r), axis=1)[:, None]
    sc[sc == 0] = 1
    if kind == "rotor":  # ball angles: absolute error (rad); displacements relative to their scale
        sc[4:6] = 1.0
    ed = np.max(np.abs(d - r) / sc); ex = np.max(np.abs(x - r) / sc); edx = np.max(np.abs(d - x) / sc)
    lim = 1e-7
    print(f"{kind}: max error at the output points (scaled): dense {ed:.2e}, exact {ex:.2e}, dense vs exact {edx:.2e}, limit {lim:g}")
    if not (ed < lim and ex < lim):
        print(f"FAIL {kind}: errors above {lim}"); fails += 1
    nd = int(fd[grp + "/solver"].attrs["rhs_evaluations"]); nx = int(fx[grp + "/solver"].attrs["rhs_evaluations"])
    print(f"{kind}: rhs evaluations dense {nd}, exact {nx}")
    if not nd < nx:
        print(f"FAIL {kind}: dense output took no fewer right-hand sides"); fails += 1
sys.exit(1 if fails else 0)
PYEOF
"$AUTOBAL" pendulum transient --set transient.output=sometimes >out.txt 2>err.txt; rc=$?
[ $rc -eq 3 ] && grep -q "output" err.txt && ok "output = sometimes -> exit 3 naming output" || bad "output = sometimes gave $rc"
"$AUTOBAL" rotor transient --set transient.output=interp >out.txt 2>err.txt; rc=$?
[ $rc -eq 3 ] && grep -q "dense, dense6, exact" err.txt && ok "rotor output = interp -> exit 3 listing dense, dense6, exact" || bad "rotor output = interp gave $rc"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
