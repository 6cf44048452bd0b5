#!/usr/bin/python3
"""The evidence for the default output of the transients (issue 20): the error at the output points
against a tight reference and the cost, for dop853 dense6 (order-6 extension, 0 extra right-hand
sides), dop853 dense (Hairer's contd8, order 7, +3 right-hand sides per step holding an output time),
rk8pd exact (steps cut at the output times, the default until 0.2.0) and dop853 exact (the step-end
accuracy of the same integration as dense/dense6: what the interpolation adds is measured against it).

    bench/run.sh dense-default [--tols 1e-6,...,1e-12] [--cases pendulum,rotor2,rotor8] [--out F.json]
    dense_default.py --from F.json     (print the tables of an archive again)

Cases of dense_scipy.py (bench_dense): the pendulum (500 revolutions), the default rotor with 2 and
8 balls (100 revolutions), output every quarter revolution, rtol = atol = tol, and a row "CLI" at the
command line's default tolerances (pendulum rtol 1e-10, atol 1e-12; rotor rtol 1e-10, atol 1e-9).  Reference: autobal
rk8pd exact at rtol 1e-14, atol 1e-14 (pendulum) or 1e-16 (rotor); its own error is estimated by its
distance to dop853 exact at the same tolerances (another pair, another step sequence) and printed:
it must be well below the errors it measures (else a row says "ref").  Error: the largest over the
output times and components of |y - y_ref| / scale (dense_scipy.err_of; rotor: per-group scales).
Cost: the CLI's transient without archive with the output grid (bench_dense "out", thread CPU time,
best of --repeats), and its right-hand sides.
"""
import argparse
import json
import os
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dense_scipy import bench, case_setup, err_of, read_samples  # noqa: E402
import rotor_scipy  # noqa: E402

CONFIGS = (("dop853", "dense6"), ("dop853", "dense"), ("rk8pd", "exact"), ("dop853", "exact"))


def run_case(exe, key, tols, repeats, tmp):
    model, n = ("pendulum", 0) if key == "pendulum" else ("rotor", int(key[5:]))
    _, y0, revs, t_end, grid, _ = case_setup(model, n)
    dim = len(y0)
    ref_atol = 1e-14 if model == "pendulum" else 1e-16
    f = os.path.join(tmp, "s.bin")
    bench(exe, model, n, "rk8pd", "exact", 1e-14, ref_atol, revs, 0.25, 1, f)
    _, ref = read_samples(f, dim)
    scale = np.ones(dim) if model == "pendulum" else rotor_scipy.group_scales(n, ref)
    bench(exe, model, n, "dop853", "exact", 1e-14, ref_atol, revs, 0.25, 1, f)
    _, ref2 = read_samples(f, dim)
    res = dict(case=key, revs=revs, outputs=len(grid), ref_err=err_of(ref2, ref, scale), rows=[])
    for tol in tols + ["cli"]:
        # "cli": the command line's default tolerances (pendulum rtol 1e-10, atol 1e-12; rotor rtol
        # 1e-10, atol 1e-9)
        rtol, atol = (tol, tol) if tol != "cli" else (1e-10, 1e-12 if model == "pendulum" else 1e-9)
        for stepper, output in CONFIGS:
            w = bench(exe, model, n, stepper, output, rtol, atol, revs, 0.25, repeats, f)
            t, Y = read_samples(f, dim)
            if len(t) != len(grid) or np.max(np.abs(t - grid)) > 1e-9 * t_end:
                raise RuntimeError("output times differ from the grid")
            res["rows"].append(dict(stepper=stepper, output=output, tol=tol, rtol=rtol, atol=atol, err=err_of(Y, ref, scale),
                                    out_seconds=w["out_seconds"], none_seconds=w["none_seconds"],
                                    out_rhs=w["out_rhs"], none_rhs=w["none_rhs"]))
    return res


def print_tables(arch):
    print(arch["header"])
    for res in arch["cases"]:
        print(f"\n== {res['case']}: {res['revs']} revolutions, {res['outputs']} output times; reference rk8pd exact "
              f"1e-14 (dop853 exact 1e-14 differs by {res['ref_err']:.1e}) ==")
        print(f"{'tol':>7} | {'err at the output points (max scaled)':^47} | {'dense6 / dense':>14}"
              f"{'dense6 / exact':>15} | {'CLI time out (ms)':^31} | rhs out: dense6 dense rk8pd")
        print(f"{'':>7} | {'dense6':>11}{'dense':>12}{'rk8pd ex':>12}{'dop ex':>12} | {'':>14}{'(dop853)':>15} | "
              f"{'dense6':>8}{'dense':>8}{'rk8pd':>8}{'  d6/rk':>7} |")
        by = {}
        for r in res["rows"]:
            by[(r["tol"], r["stepper"], r["output"])] = r
        for tol in sorted({r["tol"] for r in res["rows"] if r["tol"] != "cli"}, reverse=True) + ["cli"]:
            d6, d7 = by[(tol, "dop853", "dense6")], by[(tol, "dop853", "dense")]
            rk, dx = by[(tol, "rk8pd", "exact")], by[(tol, "dop853", "exact")]
            flag = "  ref" if res["ref_err"] > 0.1 * min(d6["err"], d7["err"], rk["err"]) else ""
            print(f"{(f'{tol:.0e}' if tol != 'cli' else 'CLI'):>7} | {d6['err']:>11.2e}{d7['err']:>12.2e}{rk['err']:>12.2e}{dx['err']:>12.2e} | "
                  f"{d6['err'] / d7['err']:>14.2f}{d6['err'] / dx['err']:>15.2f} | "
                  f"{1e3 * d6['out_seconds']:>8.3f}{1e3 * d7['out_seconds']:>8.3f}{1e3 * rk['out_seconds']:>8.3f}"
                  f"{d6['out_seconds'] / rk['out_seconds']:>7.2f} | {d6['out_rhs']:>8}{d7['out_rhs']:>8}{rk['out_rhs']:>8}"
                  + flag)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", help="path of the bench_dense binary")
    ap.add_argument("--cases", default="pendulum,rotor2,rotor8")
    ap.add_argument("--tols", default="1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--out", default="dense_default.json")
    ap.add_argument("--from", dest="from_")
    a = ap.parse_args()
    if a.from_:
        print_tables(json.load(open(a.from_)))
        return
    arch = dict(header=f"bench/dense_default.py, {time.strftime('%Y-%m-%d %H:%M:%S UTC', time.gmtime())}, "
                       f"load {os.getloadavg()[0]:.1f}", cases=[])
    tols = [float(s) for s in a.tols.split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        for key in a.cases.split(","):
            arch["cases"].append(run_case(a.bench, key, tols, a.repeats, tmp))
    arch["load_after"] = os.getloadavg()[0]
    with open(a.out, "w") as fo:
        json.dump(arch, fo, indent=1)
    print(f"archive: {a.out}")
    print_tables(arch)


if __name__ == "__main__":
    main()
