"""Helpers shared by the ensemble checks of tests/app (ensemble_friction_check.py,
ensemble_contact_check.py): open /rotor/ensemble, fail, compare two archives bit for bit, print a
member's parameter values."""
import sys

import h5py
import numpy as np


def fail(msg):
    print("FAIL", msg)
    sys.exit(1)


def ens(path):
    return h5py.File(path, "r")["rotor/ensemble"]


def same(a, b, need_datasets=(), need_attr=None):
    """Every dataset of /rotor/ensemble of a and b equal bit for bit (NaN = NaN); the datasets
    need_datasets present; the attribute need_attr on both groups."""
    ga, gb = ens(a), ens(b)
    names = sorted(k for k in ga if isinstance(ga[k], h5py.Dataset))
    if names != sorted(k for k in gb if isinstance(gb[k], h5py.Dataset)):
        fail("different datasets")
    for k in need_datasets:
        if k not in names:
            fail("no dataset %s" % k)
    for k in names:
        x, y = ga[k][()], gb[k][()]
        if x.shape != y.shape or not np.array_equal(x, y, equal_nan=x.dtype.kind == "f"):
            fail("dataset %s differs" % k)
    if need_attr:
        for g in (ga, gb):
            if g.attrs.get(need_attr) is None:
                fail("no %s attribute on /rotor/ensemble" % need_attr)
    print("%d datasets equal bit for bit (%s)" % (len(names), ", ".join(names)))


def params(path, k, names):
    """Print the parameter values of member k (flat index) as exact decimals: for a random
    ensemble the per-member variables among names, for a grid the axes' coordinates."""
    g = ens(path)
    shape = g["status"].shape
    mode = g.attrs.get("mode")
    mode = mode.decode() if isinstance(mode, bytes) else mode
    if mode == "random":
        out = [(n, g[n][k]) for n in names if n in g and g[n].shape == shape]
    else:
        idx = np.unravel_index(k, shape)
        out = [(dim[0].name.split("/")[-1], dim[0][idx[ax]]) for ax, dim in enumerate(g["status"].dims)]
    if not out:
        fail("no parameters found")
    for n, v in out:
        print("%s %r" % (n, float(v)))
