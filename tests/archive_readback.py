#!/usr/bin/python3
"""Read the sample archive written by `test_archive --write FILE` with h5py and xarray.

Usage: /usr/bin/python3 archive_readback.py FILE

Checks what a user of the archive relies on: named dimensions, coordinate values,
units/long_name attributes read as str, parameters as NAME / NAME_units attributes,
the streamed series (unlimited dimension), root provenance attributes, attributes listed in
the order they were written (creation order tracked).
Expected values are recomputed from the formulas that test_archive.c uses
(sample_omega, sample_re, sample_flag and the series rows), not copied from output.
Also opened through netCDF-C (engine="netcdf4") when the netCDF4 module exists.
Exit status 0 on success; every check prints one line.
"""
import re
import sys

import h5py
import numpy as np
import xarray as xr

NOMEGA, NROOT, NROWS = 5, 3, 10000
failures = 0


def check(what, cond):
    global failures
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures += 1


def omega(i):
    return 10.0 * (i + 1)


def expected_re():
    return np.array([[omega(i) + 0.25 * j for j in range(NROOT)] for i in range(NOMEGA)])


def expected_flag():
    return np.array([[i * 10 + j - 7 for j in range(NROOT)] for i in range(NOMEGA)], dtype=np.int32)


def check_xarray(path, engine):
    tag = f"[{engine}] "
    ds = xr.open_dataset(path, engine=engine, group="/")
    check(tag + "root Conventions", ds.attrs.get("Conventions") == "CF-1.8 autobal-1")
    check(tag + "root status complete", ds.attrs.get("status") == "complete")
    check(tag + "root title is str", isinstance(ds.attrs.get("title"), str) and ds.attrs["title"] == "archive sample")
    ds.close()

    ds = xr.open_dataset(path, engine=engine, group="/pendulum")
    check(tag + "parameter mass = 0.5", float(ds.attrs["mass"]) == 0.5)
    check(tag + "mass_units = kg (str)", ds.attrs["mass_units"] == "kg")
    check(tag + "n_pendulums = 2", int(ds.attrs["n_pendulums"]) == 2)
    check(tag + "model string", ds.attrs["model"] == "two pendulums")
    check(tag + "pair array", np.array_equal(np.asarray(ds.attrs["pair"]), [1.5, -2.0]))
    ds.close()

    ds = xr.open_dataset(path, engine=engine, group="/pendulum/map")
    check(tag + "dims of re are (omega, root)", ds["re"].dims == ("omega", "root"))
    check(tag + "dims of flag are (omega, root)", ds["flag"].dims == ("omega", "root"))
    check(tag + "sizes omega=5 root=3", dict(ds.sizes) == {"omega": NOMEGA, "root": NROOT})
    check(tag + "omega is a coordinate", "omega" in ds.coords and ds["omega"].dims == ("omega",))
    check(tag + "omega values", np.array_equal(ds["omega"].values, [omega(i) for i in range(NOMEGA)]))
    check(tag + "root coordinate 0..2", np.array_equal(ds["root"].values, np.arange(NROOT)))
    check(tag + "omega units rad/s", ds["omega"].attrs.get("units") == "rad/s")
    check(tag + "omega long_name", ds["omega"].attrs.get("long_name") == "rotor speed")
    check(tag + "root units 1", ds["root"].attrs.get("units") == "1")
    check(tag + "re units 1/s", ds["re"].attrs.get("units") == "1/s")
    check(tag + "re long_name", ds["re"].attrs.get("long_name") == "real part")
    check(tag + "re values (C order)", np.array_equal(ds["re"].values, expected_re()))
    check(tag + "re selected by label", float(ds["re"].sel(omega=30.0, root=2)) == 30.5)
    check(tag + "flag int32 values", ds["flag"].dtype == np.int32 and np.array_equal(ds["flag"].values, expected_flag()))
    check(tag + "scalar omega_crit", ds["omega_crit"].dims == () and float(ds["omega_crit"]) == omega(0))
    for v in ds.variables:
        check(tag + f"{v}: units and long_name are str",
              isinstance(ds[v].attrs.get("units"), str) and isinstance(ds[v].attrs.get("long_name"), str))
    ds.close()

    ds = xr.open_dataset(path, engine=engine, group="/pendulum/map/sub")
    check(tag + "subgroup variable uses the parent's omega dimension", ds["lam"].dims == ("omega",))
    check(tag + "lam values", np.array_equal(ds["lam"].values, [-0.5 * omega(i) for i in range(NOMEGA)]))
    ds.close()

    ds = xr.open_dataset(path, engine=engine, group="/rotor/transient")
    i = np.arange(NROWS)
    check(tag + "series dims (time,)", ds["x"].dims == ("time",) and ds["y"].dims == ("time",))
    check(tag + "series length 10000", ds.sizes["time"] == NROWS)
    check(tag + "time is unlimited", "time" in ds.encoding.get("unlimited_dims", set()))
    check(tag + "time values", np.array_equal(ds["time"].values, 1e-3 * i))
    check(tag + "time units s (not decoded to timedelta)",
          ds["time"].attrs.get("units") == "s" and ds["time"].dtype == np.float64)
    check(tag + "x values", np.array_equal(ds["x"].values, i.astype(float)))
    check(tag + "y values", np.array_equal(ds["y"].values, -0.5 * i))
    check(tag + "x long_name", ds["x"].attrs.get("long_name") == "displacement x")
    check(tag + "y long_name defaults to name", ds["y"].attrs.get("long_name") == "y")
    check(tag + "y units m", ds["y"].attrs.get("units") == "m")
    ds.close()


def check_h5py(path):
    with h5py.File(path, "r") as f:
        a = f.attrs
        for k in ("title", "autobal_version", "git_revision", "gsl_version", "hdf5_version", "command_line",
                  "created", "status", "Conventions"):
            check(f"[h5py] root attribute {k} is str", isinstance(a.get(k), str))
        check("[h5py] created is ISO 8601 UTC", re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", a["created"]) is not None)
        check("[h5py] hdf5_version matches h5py's HDF5",
              a["hdf5_version"] == ".".join(str(v) for v in h5py.version.hdf5_version_tuple))
        check("[h5py] command_line", a["command_line"].startswith("test_archive --write "))
        om = f["/pendulum/map/omega"]
        check("[h5py] omega is a dimension scale", h5py.h5ds.is_scale(om.id))
        check("[h5py] omega NAME attribute = dimension name", om.attrs["NAME"] in (b"omega", "omega"))
        re_ = f["/pendulum/map/re"]
        check("[h5py] re dims labelled",
              [d[0].name for d in re_.dims] == ["/pendulum/map/omega", "/pendulum/map/root"])
        check("[h5py] re units str", re_.attrs["units"] == "1/s")
        x = f["/rotor/transient/x"]
        check("[h5py] series x unlimited", x.maxshape == (None,))
        check("[h5py] series x chunked + deflate + shuffle",
              x.chunks is not None and x.compression == "gzip" and x.shuffle)
        check("[h5py] series x attached to time", x.dims[0][0].name == "/rotor/transient/time")
        check("[h5py] small re contiguous", re_.chunks is None)
        check("[h5py] parameter mass", f["/pendulum"].attrs["mass"] == 0.5
              and f["/pendulum"].attrs["mass_units"] == "kg")
        # attribute creation order is tracked: h5py lists them in the order test_archive.c's
        # write_sample wrote them (not alphabetical: "model" after "n_pendulums")
        check("[h5py] /pendulum attributes in creation order",
              list(f["/pendulum"].attrs) == ["mass", "mass_units", "n_pendulums", "model", "pair", "pair_units"])
        check("[h5py] /pendulum/map/re attributes: units before long_name (creation order)",
              [k for k in f["/pendulum/map/re"].attrs if k in ("units", "long_name")] == ["units", "long_name"])


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    path = sys.argv[1]
    check_h5py(path)
    check_xarray(path, "h5netcdf")
    try:
        import netCDF4  # noqa: F401
    except ImportError:
        print("skip [netcdf4]: the netCDF4 module is not installed")
    else:
        check_xarray(path, "netcdf4")
    print(f"{failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
