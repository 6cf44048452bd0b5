#!/usr/bin/python3
"""The cost of output every quarter revolution in time (issue 20): out/none of the CLI's transient
(bench_dense: the study without archive with the output grid, "out", and without it, "none"),
for this library and a reference build (e.g. main), interleaved in one run.

    dense_ratio.py --bench NEW/bench_dense --before REF/bench_dense [--rounds 7] [--repeats 21]
                   [--cases pendulum,rotor2,rotor8] [--tols 1e-6,1e-8,1e-10] [--outputs dense,dense6]
                   [--out FILE.json]

For every case, tolerance and output mode: ROUNDS rounds, each one bench_dense call of the new
build then one of the reference (REPEATS interleaved out/none/bare runs each, thread CPU time).
Reported per build: the median over the rounds of each call's own best out / best none (the two
measured side by side in one process, so the load of that moment cancels), and the best out over
all rounds / the best none over all rounds.  Counts of right-hand sides are exact and equal in
both builds when the results are the same bit for bit (checked: printed as 'same rhs').
"""
import argparse
import json
import os
import statistics
import subprocess
import time

CASES = {"pendulum": ("pendulum", 0, 500), "rotor2": ("rotor", 2, 100), "rotor8": ("rotor", 8, 100)}


def bench(exe, model, n, output, tol, revs, repeats):
    out = subprocess.run([exe, model, str(n), "dop853", output, str(tol), str(tol), str(revs), "0.25",
                          str(repeats), "-"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", required=True)
    ap.add_argument("--before", required=True)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--repeats", type=int, default=21)
    ap.add_argument("--cases", default="pendulum,rotor2,rotor8")
    ap.add_argument("--tols", default="1e-6,1e-8,1e-10")
    ap.add_argument("--outputs", default="dense,dense6")
    ap.add_argument("--out", default="dense_ratio.json")
    a = ap.parse_args()
    arch = dict(started=time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()), load=os.getloadavg()[0],
                rounds=a.rounds, repeats=a.repeats, rows=[])
    print(f"out/none of the CLI's transient (thread CPU time), {a.rounds} rounds x {a.repeats} repeats, "
          f"load {arch['load']:.1f}, {arch['started']}")
    print(f"{'case':<10}{'output':<8}{'tol':>7} | {'new: median':>12}{'best/best':>10} | {'ref: median':>12}"
          f"{'best/best':>10} | {'new out ms':>10}{'ref out ms':>11} | rhs")
    for c in a.cases.split(","):
        model, n, revs = CASES[c]
        for output in a.outputs.split(","):
            for tol in map(float, a.tols.split(",")):
                runs = {"new": [], "ref": []}
                for _ in range(a.rounds):
                    runs["new"].append(bench(a.bench, model, n, output, tol, revs, a.repeats))
                    runs["ref"].append(bench(a.before, model, n, output, tol, revs, a.repeats))
                row = dict(case=c, output=output, tol=tol)
                for k, rs in runs.items():
                    row[k] = dict(median_ratio=statistics.median(r["out_seconds"] / r["none_seconds"] for r in rs),
                                  best_ratio=min(r["out_seconds"] for r in rs) / min(r["none_seconds"] for r in rs),
                                  best_out=min(r["out_seconds"] for r in rs), best_none=min(r["none_seconds"] for r in rs),
                                  out_rhs=rs[0]["out_rhs"], none_rhs=rs[0]["none_rhs"])
                same = all((r["out_rhs"], r["none_rhs"]) == (row["new"]["out_rhs"], row["new"]["none_rhs"])
                           for r in runs["new"] + runs["ref"])
                row["same_rhs"] = same
                arch["rows"].append(row)
                nw, rf = row["new"], row["ref"]
                print(f"{c:<10}{output:<8}{tol:>7.0e} | {nw['median_ratio']:>12.3f}{nw['best_ratio']:>10.3f} | "
                      f"{rf['median_ratio']:>12.3f}{rf['best_ratio']:>10.3f} | {1e3 * nw['best_out']:>10.3f}"
                      f"{1e3 * rf['best_out']:>11.3f} | {'same rhs' if same else 'RHS DIFFER'} "
                      f"{nw['out_rhs']}/{nw['none_rhs']}", flush=True)
    arch["load_after"] = os.getloadavg()[0]
    with open(a.out, "w") as f:
        json.dump(arch, f, indent=1)
    print(f"archive: {a.out}")


if __name__ == "__main__":
    main()
