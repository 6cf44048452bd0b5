#!/usr/bin/python3
"""Output every quarter revolution (issue 20): dense output (dop853 on its continuous extension)
against exact hits (steps cut at the output times) and against SciPy solve_ivp, at matched error
of the output points.  Run through bench/run.sh dense (builds bench_dense first).

Cases: the pendulum of bench_pendulum.c (500 revolutions, tau in [0, 1047.2]) and the default
rotor of bench_rotor.c with 2 and 8 balls (100 revolutions, t in [0, 1.2566] s), output every
quarter revolution.  autobal: bench_dense (see its header) at rtol = atol = tol, for rk8pd
(exact hits), dop853 exact and dop853 dense; each with the output grid and without (only t0 and
t_end), the whole transient of the command line without the archive ("study": driver, balance
monitor, derived quantities at the output points) and the bare integration.  SciPy: solve_ivp
DOP853, LSODA, Radau with t_eval = the output grid (DOP853 interpolates on its own 7th-order
extension), rtol = atol = tol on a grid of tolerances; CPU time (time.process_time), best of N.

Error of the output points: the largest over the output times and components of
|y - y_ref| / scale, scale = 1 for the pendulum (dimensionless, O(1)), the largest |component| of
each group over the trajectory for the rotor (rotor_scipy.group_scales); y_ref: SciPy DOP853 at
rtol = 1e-13, atol = 1e-13 (pendulum) or 1e-15 (rotor) on the same grid, cross-checked against
autobal rk8pd exact hits at 1e-13.  Matched error: SciPy's time interpolated (log-log, over its
tolerances, sorted by error) at autobal's error.

Writes every number to an archive (JSON, --out) and prints the tables from it; --plot draws the
work-precision diagrams (error vs time) from that archive.
"""
import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pendulum_scipy  # noqa: E402
import rotor_scipy  # noqa: E402


def case_setup(model, n):
    if model == "pendulum":
        rhs = pendulum_scipy.make_rhs(**pendulum_scipy.P)
        period = 2 * math.pi / pendulum_scipy.P["Rw"]
        revs = 500
        y0 = np.zeros(8)
        ref_atol = 1e-13
    else:
        rhs = rotor_scipy.RHS["numpy"](n)
        period = 2 * math.pi / rotor_scipy.OMEGA
        revs = 100
        y0 = rotor_scipy.initial_state(n)
        ref_atol = 1e-15
    t_end = revs * period
    k = int(round(revs / 0.25))
    grid = np.array([min(i * 0.25 * period, t_end) for i in range(k + 1)])
    grid[-1] = t_end
    return rhs, y0, revs, t_end, grid, ref_atol


def scipy_run(rhs, y0, t_end, grid, method, rtol, atol, repeats):
    best, sol = math.inf, None
    for _ in range(repeats):
        c0 = time.process_time()
        sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, t_eval=grid)
        best = min(best, time.process_time() - c0)
        if not sol.success:
            raise RuntimeError(f"{method}: {sol.message}")
    return best, sol


def bench(exe, *args):
    out = subprocess.run([exe, *map(str, args)], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def read_samples(path, dim):
    a = np.fromfile(path, dtype=np.float64)
    a = a.reshape(-1, dim + 1)
    return a[:, 0], a[:, 1:].T


def err_of(Y, ref, scale):
    return float(np.max(np.abs(Y - ref) / scale[:, None]))


def matched(points, err):
    """SciPy time at autobal's error: log-log interpolation over (err, time) sorted by error."""
    pts = sorted((e, t) for e, t in points if e > 0)
    if not pts:
        return None
    es = np.log([p[0] for p in pts])
    ts = np.log([p[1] for p in pts])
    le = math.log(err)
    if le < es[0] or le > es[-1]:
        return None
    return float(math.exp(np.interp(le, es, ts)))


def best_of(runs):
    """One bench_dense record from several runs of the same configuration: every time the best."""
    m = dict(runs[0])
    for r in runs[1:]:
        for k in ("out_seconds", "none_seconds", "bare_seconds", "rhs_only_seconds"):
            m[k] = min(m[k], r[k])
    m["rhs_share"] = m["rhs_only_seconds"] / m["bare_seconds"]
    m["rounds"] = len(runs)
    return m


def run_case(args, model, n, tmp):
    rhs, y0, revs, t_end, grid, ref_atol = case_setup(model, n)
    dim = len(y0)
    res = dict(model=model, nballs=n, dim=dim, revs=revs, t_end=t_end, outputs=len(grid))
    _, rs = scipy_run(rhs, y0, t_end, grid, "DOP853", 1e-13, ref_atol, 1)
    ref = rs.y
    scale = np.ones(dim) if model == "pendulum" else rotor_scipy.group_scales(n, ref)
    # cross-check of the reference against autobal rk8pd exact hits at 1e-13
    f = os.path.join(tmp, "ref.bin")
    bench(args.bench, model, n, "rk8pd", "exact", 1e-13, ref_atol, revs, 0.25, 1, f)
    tc, Yc = read_samples(f, dim)
    res["ref_rhs"] = int(rs.nfev)
    res["ref_vs_autobal"] = err_of(Yc, ref, scale)
    res["autobal"] = []
    for stepper, output in args.configs:
        for tol in args.tols:
            atol = tol if model == "pendulum" else tol * args.rotor_atol_factor
            f = os.path.join(tmp, "s.bin")
            w = bench(args.bench, model, n, stepper, output, tol, atol, revs, 0.25, args.c_repeats, f)
            t, Y = read_samples(f, dim)
            if len(t) != len(grid) or np.max(np.abs(t - grid)) > 1e-9 * t_end:
                raise RuntimeError("output times differ from the grid")
            entry = dict(stepper=stepper, output=output, tol=tol, atol=atol, err=err_of(Y, ref, scale), run=w)
            if args.before:
                # the same configuration with an older bench_dense (library), right after: before/after
                # in one run; --rounds > 1: after and before alternate that many times (best of all)
                wb = bench(args.before, model, n, stepper, output, tol, atol, revs, 0.25, args.c_repeats, f)
                tb, Yb = read_samples(f, dim)
                runs, runs_b = [w], [wb]
                for _ in range(args.rounds - 1):
                    runs.append(bench(args.bench, model, n, stepper, output, tol, atol, revs, 0.25, args.c_repeats, "-"))
                    runs_b.append(bench(args.before, model, n, stepper, output, tol, atol, revs, 0.25, args.c_repeats, "-"))
                entry["run"] = best_of(runs)
                entry["before"] = dict(err=err_of(Yb, ref, scale), run=best_of(runs_b))
            res["autobal"].append(entry)
    res["scipy"] = []
    for method in args.methods:
        for tol in args.scipy_tols:
            atol = tol if model == "pendulum" else tol * args.rotor_atol_factor
            if method != "DOP853" and tol < 1e-11:
                continue
            reps = args.scipy_repeats
            ts, sol = scipy_run(rhs, y0, t_end, grid, method, tol, atol, reps)
            res["scipy"].append(dict(method=method, tol=tol, atol=atol, seconds=ts, nfev=int(sol.nfev),
                                     err=err_of(sol.y, ref, scale)))
    return res


def print_tables(arch):
    print(arch["header"])
    for res in arch["cases"]:
        name = res["model"] + ("" if res["model"] == "pendulum" else f", {res['nballs']} balls")
        print(f"\n== {name}: {res['revs']} revolutions, {res['outputs']} output times (every quarter "
              f"revolution); reference SciPy DOP853 1e-13 ({res['ref_rhs']} rhs), autobal rk8pd exact "
              f"1e-13 differs from it by {res['ref_vs_autobal']:.1e} ==")
        hdr = (f"{'autobal':<16}{'tol':>7}{'err out':>10}{'rhs out':>9}{'rhs none':>9}{'rhs +%':>7}"
               f"{'CLI out':>11}{'CLI none':>11}{'time +%':>8}{'bare':>9}{'rhs share':>10}"
               f"{'DOP853 @err':>12}{'ratio':>7}")
        print(hdr)
        print("-" * len(hdr))
        dop = [(s["err"], s["seconds"]) for s in res["scipy"] if s["method"] == "DOP853"]
        rows = []
        for a in res["autobal"]:
            rows.append((a["stepper"] + " " + a["output"], a))
            if "before" in a:
                rows.append(("  before", dict(a["before"], tol=a["tol"])))
        for label, a in rows:
            o = a["run"]
            m = matched(dop, a["err"])
            print(f"{label:<16}{a['tol']:>7.0e}{a['err']:>10.2e}"
                  f"{o['out_rhs']:>9d}{o['none_rhs']:>9d}"
                  f"{100 * (o['out_rhs'] / o['none_rhs'] - 1):>7.1f}"
                  f"{o['out_seconds'] * 1e3:>9.3f}ms{o['none_seconds'] * 1e3:>9.3f}ms"
                  f"{100 * (o['out_seconds'] / o['none_seconds'] - 1):>8.1f}"
                  f"{o['bare_seconds'] * 1e3:>7.3f}ms{o['rhs_share']:>10.2f}"
                  + (f"{m * 1e3:>10.1f}ms{m / o['out_seconds']:>6.0f}x" if m else f"{'(out of range)':>19}"))
        print(f"\n{'SciPy':<10}{'tol':>8}{'err out':>10}{'rhs':>9}{'time':>11}")
        for s in res["scipy"]:
            print(f"{s['method']:<10}{s['tol']:>8.1e}{s['err']:>10.2e}{s['nfev']:>9d}{s['seconds'] * 1e3:>9.2f}ms")


def plot(arch, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cases = arch["cases"]
    fig, axs = plt.subplots(1, len(cases), figsize=(5 * len(cases), 4.2))
    for ax, res in zip(np.atleast_1d(axs), cases):
        for key, mk in ((("rk8pd", "exact"), "s-"), (("dop853", "exact"), "^-"), (("dop853", "dense"), "o-"),
                        (("dop853", "dense6"), "v-")):
            pts = sorted((a["err"], a["run"]["out_seconds"]) for a in res["autobal"]
                         if (a["stepper"], a["output"]) == key)
            ax.loglog([p[1] for p in pts], [p[0] for p in pts], mk, label="autobal " + " ".join(key))
        for method, mk in (("DOP853", "x--"), ("LSODA", "+--"), ("Radau", "d--")):
            pts = sorted((s["err"], s["seconds"]) for s in res["scipy"] if s["method"] == method)
            if pts:
                ax.loglog([p[1] for p in pts], [p[0] for p in pts], mk, label="SciPy " + method)
        name = res["model"] + ("" if res["model"] == "pendulum" else f", {res['nballs']} balls")
        ax.set_title(f"{name}, {res['revs']} rev, output every 1/4 rev")
        ax.set_xlabel("CPU time [s] (autobal: the CLI's transient without archive)")
        ax.set_ylabel("max error at the output points")
        ax.grid(True, which="both", alpha=0.3)
    np.atleast_1d(axs)[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"plot: {path}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", help="path of the bench_dense binary")
    ap.add_argument("--cases", default="pendulum,rotor2,rotor8")
    ap.add_argument("--tols", default="1e-6,1e-8,1e-10")
    ap.add_argument("--scipy-tols", default="1e-4,3e-5,1e-5,3e-6,1e-6,3e-7,1e-7,3e-8,1e-8,3e-9,1e-9,3e-10,1e-10,3e-11,1e-11,3e-12,1e-12")
    ap.add_argument("--methods", default="DOP853,LSODA,Radau")
    ap.add_argument("--configs", default="rk8pd:exact,dop853:exact,dop853:dense,dop853:dense6",
                    help="autobal's stepper:output pairs (output dense: contd8, dense6: the order-6 extension)")
    ap.add_argument("--rotor-atol-factor", type=float, default=1.0,
                    help="rotor: atol = tol x this (default 1: rtol = atol = tol, as bench/rotor_scipy.py)")
    ap.add_argument("--c-repeats", type=int, default=51)
    ap.add_argument("--before", help="an older bench_dense binary, run right after each autobal configuration "
                    "(before/after in one run; printed as rows 'before')")
    ap.add_argument("--rounds", type=int, default=1,
                    help="with --before: after and before alternate this many times per configuration, best of all")
    ap.add_argument("--scipy-repeats", type=int, default=3)
    ap.add_argument("--out", default="dense_bench.json", help="the archive (JSON) of this run")
    ap.add_argument("--from", dest="from_", help="print (and plot) an existing archive instead of running")
    ap.add_argument("--plot", help="PNG of the work-precision diagrams, drawn from the archive")
    args = ap.parse_args()
    if args.from_:
        arch = json.load(open(args.from_))
    else:
        args.tols = [float(s) for s in args.tols.split(",")]
        args.scipy_tols = [float(s) for s in args.scipy_tols.split(",")]
        args.methods = [m for m in args.methods.split(",") if m]  # "": no SciPy runs (the reference only)
        args.configs = [tuple(c.split(":")) for c in args.configs.split(",")]
        arch = dict(header=(f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}; "
                            f"{platform.processor() or platform.machine()}; load {os.getloadavg()[0]:.1f}; "
                            f"{time.strftime('%Y-%m-%d %H:%M:%S UTC', time.gmtime())}"), cases=[])
        with tempfile.TemporaryDirectory() as tmp:
            for c in args.cases.split(","):
                model, n = ("pendulum", 0) if c == "pendulum" else ("rotor", int(c[5:]))
                arch["cases"].append(run_case(args, model, n, tmp))
        arch["load_after"] = os.getloadavg()[0]
        with open(args.out, "w") as fo:
            json.dump(arch, fo, indent=1)
        print(f"archive: {args.out}")
    print_tables(arch)
    if args.plot:
        plot(arch, args.plot)


if __name__ == "__main__":
    main()
