#!/usr/bin/python3
"""archive_same.py A.h5 B.h5 [--provenance]: the two autobal archives hold the same groups and
datasets, every dataset identical bit for bit (dtype, shape, bytes) with the same dimension scales,
and the same attributes with identical values and types, except those that say when, where and
how a file was made: the root's created, command_line, history, git_revision and source (the build) and every wall_time; with
--provenance also the rest of what autobal_archive_provenance and the `autobal` program record
at the root (title, versions, git_revision, source, command, input_config, effective_config).
Prints what it compared; exit status 0 when identical, 1 otherwise."""
import sys

import h5py
import numpy as np

VOLATILE = {"created", "command_line", "history", "git_revision", "source"}
PROVENANCE = VOLATILE | {"title", "autobal_version", "git_revision", "gsl_version", "hdf5_version", "source",
                         "command", "input_config", "effective_config"}


def dim_names(ds):
    out = []
    for d in ds.dims:
        out.append(tuple(sorted(s.name for s in d.values())))
    return out


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    root_skip = PROVENANCE if "--provenance" in argv else VOLATILE
    a, b = args
    ha, hb = h5py.File(a, "r"), h5py.File(b, "r")
    oa, ob = {"/": ha}, {"/": hb}
    ha.visititems(lambda n, o: oa.__setitem__("/" + n, o))
    hb.visititems(lambda n, o: ob.__setitem__("/" + n, o))
    diffs = []
    if sorted(oa) != sorted(ob):
        diffs.append("objects only in one file: %s" % sorted(set(oa) ^ set(ob)))
    nd = na = 0
    for p in sorted(set(oa) & set(ob)):
        x, y = oa[p], ob[p]
        if isinstance(x, h5py.Dataset) != isinstance(y, h5py.Dataset):
            diffs.append("%s: dataset in one file, group in the other" % p)
            continue
        if isinstance(x, h5py.Dataset):
            nd += 1
            dx, dy = x[()], y[()]
            if not (x.dtype == y.dtype and x.shape == y.shape and np.asarray(dx).tobytes() == np.asarray(dy).tobytes()):
                diffs.append("dataset %s differs" % p)
            if dim_names(x) != dim_names(y):
                diffs.append("dimension scales of %s differ" % p)
        keys = set(x.attrs) | set(y.attrs)
        for k in sorted(keys):
            if k in ("DIMENSION_LIST", "REFERENCE_LIST") or k == "wall_time":
                continue
            if p == "/" and k in root_skip:
                continue
            if k not in x.attrs or k not in y.attrs:
                diffs.append("attribute %s@%s only in one file" % (p, k))
                continue
            na += 1
            vx, vy = x.attrs[k], y.attrs[k]
            if np.asarray(vx).tobytes() != np.asarray(vy).tobytes() or type(vx) != type(vy):
                diffs.append("attribute %s@%s: %r vs %r" % (p, k, vx, vy))
    ok = not diffs and nd > 0
    print("%s: %s vs %s: %d datasets bit for bit, %d attributes compared (root attributes skipped: %s)%s"
          % ("ok" if ok else "FAIL", a, b, nd, na, ", ".join(sorted(root_skip)),
             "" if ok else "\n  " + "\n  ".join(diffs[:20] or ["no datasets"])))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
