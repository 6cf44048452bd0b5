"""Checks of `autobal pendulum transient` archives with independent reasons.

- the residual unbalance is recomputed from the geometry of the model section of
  docs/pendulum.md (rotor M e along +U, pendulum 1 at l(-sin psi, cos psi), pendulum 2 at
  l(-sin phi, -cos phi)), in units of 2 m l;
- balanced runs end at the main motion (4): psi = phi = psi0, xi = eta = 0;
- with H = h = 0 the Jacobi integral of the rotating frame is conserved;
- an unstable speed (between the damped critical speeds) does not balance.
Usage: pendulum_transient_check.py balanced|conserved|unstable FILE.h5
"""
import sys

import h5py
import numpy as np
import xarray as xr

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    failures += 0 if ok else 1


def main():
    what, path = sys.argv[1], sys.argv[2]
    with h5py.File(path, "r") as f:
        check("status complete", f.attrs["status"] == "complete")
        psi0 = float(f["pendulum"].attrs["psi0"])
        tr = f["pendulum/transient"].attrs
        balanced = int(tr["balanced"])
    ds = xr.open_dataset(path, engine="h5netcdf", group="pendulum/transient")
    check("series over 'tau' with units", ds["psi"].dims == ("tau",) and ds["tau"].attrs["units"] == "1")
    psi, phi = ds["psi"].values, ds["phi"].values
    du = np.sin(psi0) - (np.sin(psi) + np.sin(phi)) / 2
    dv = (np.cos(psi) - np.cos(phi)) / 2
    d = np.hypot(du, dv)
    err = np.max(abs(d - ds["unbalance"].values))
    check("residual unbalance matches the model geometry", err < 1e-12, "%.2e" % err)
    if what == "balanced":
        check("balanced flag", balanced == 1)
        check("pendulums at psi0 (4)", abs(psi[-1] - psi0) < 1e-5 and abs(phi[-1] - psi0) < 1e-5,
              "psi-psi0 %.2e phi-psi0 %.2e" % (psi[-1] - psi0, phi[-1] - psi0))
        check("shaft at rest on the axis", np.hypot(ds["xi"].values[-1], ds["eta"].values[-1]) < 1e-5)
    elif what == "conserved":
        J = ds["jacobi"].values
        drift = np.max(abs(J - J[0])) / max(1.0, abs(J[0]))
        check("Jacobi integral conserved without damping", drift < 1e-8, "relative drift %.2e" % drift)
    elif what == "unstable":
        check("not balanced at an unstable speed", balanced == 0)
        check("residual unbalance does not vanish", d[-1] > 1e-2, "%.3e" % d[-1])
    print("%s: %d failed" % (what, failures))
    sys.exit(1 if failures else 0)


main()
