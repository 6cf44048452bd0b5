#!/usr/bin/python3
"""Every target of issue 20 in one run, as ratios measured side by side (bench/run.sh issue20 REV).

    issue20.py --bench NEW/bench_dense --before REF/bench_dense [--rounds 7] [--repeats 21]
               [--scipy-tols 1e-5,...,1e-11] [--c-repeats 15] [--out FILE.json]

1. Output every quarter revolution costs <= 10% over no output: out/none of the CLI's transient
   (bench_dense: the study without archive with and without the output grid, thread CPU time),
   pendulum, rotor 2 and 8 balls, rtol = atol = 1e-6, 1e-8, 1e-10, output = dense6 and dense
   (dop853); this library and the reference build REV interleaved (dense_ratio.py; the median over
   the rounds of each call's best out / best none).
2. The CLI's whole transient >= 100x SciPy DOP853 (pendulum, 2 balls), >= 50x (8 balls): "CLI out"
   of this library (dense6, dense and rk8pd exact hits, the default before 0.2.0; dense6 is the default now) against SciPy solve_ivp
   DOP853 with t_eval = the output grid, SciPy's time interpolated (log-log) at autobal's error of
   the output points (dense_scipy.py: errors against SciPy DOP853 at 1e-13); also the accuracy of
   the output points of dense6 against dense (contd8) at the same tolerances.
3. >= 80% of the bare integration's time inside the right-hand side: (a) by instructions,
   callgrind (load-independent): inclusive Ir of the model's right-hand side / of
   autobal_transient_run in a bare run (bench_dense ... REVS 0 0 -: no observer, no events, no
   output grid), dop853 and rk8pd at rtol 1e-8; (b) by time: bench_dense's "rhs share" (the right-
   hand side alone replayed on every (t, y) the bare run evaluated it at, divided by the bare run's
   time; two separate timings, so noisy under load); (c) by sampled time, perf (a sampling
   profiler, Debian's linux-perf): `perf record -e cpu-clock --call-graph dwarf` of K bare runs in
   one process (bench_dense ... REPEATS = -K), the samples whose call stack holds the model's
   right-hand side / those whose stack holds autobal_transient_run (perf report --children):
   the time of the right-hand side and of everything it calls (libm's sine and cosine) within
   the integration, in the same run, without a second timing.
Writes every number to one archive (JSON) and prints the status of each target from it.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
CASES = {"pendulum": ("pendulum", 0, 500), "rotor2": ("rotor", 2, 100), "rotor8": ("rotor", 8, 100)}
TARGET_X = {"pendulum": 100.0, "rotor2": 100.0, "rotor8": 50.0}


def run(cmd):
    print("+", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def inclusive(txt, pattern, model):
    """the first value (group 1) of the model's right-hand side and of autobal_transient_run (group 2:
    the function's name, an .avx2 clone's suffix dropped) in a profiler's inclusive listing"""
    rhs_name = "autobal_pendulum_motion_rhs" if model == "pendulum" else "autobal_rotor_rhs"
    v = {}
    for line in txt.splitlines():
        m = re.match(pattern, line)
        if m and m.group(2) in (rhs_name, "autobal_transient_run") and m.group(2) not in v:
            v[m.group(2)] = float(m.group(1).replace(",", ""))
    return v[rhs_name], v["autobal_transient_run"]


def callgrind_share(exe, model, n, revs, stepper, tmp):
    """inclusive Ir of the right-hand side / of autobal_transient_run in a bare run (rtol 1e-8)"""
    f = os.path.join(tmp, f"cg.{model}{n}.{stepper}")
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={f}", exe, model, str(n), stepper,
                    "dense6", "1e-8", "1e-8", str(revs), "0", "0", "-"], check=True, capture_output=True)
    txt = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", f], check=True,
                         capture_output=True, text=True).stdout
    rhs, run = inclusive(txt, r"\s*([\d,]+)\s+\([^)]*\)\s+\S*?:(\S+?)(?:\.avx2)?\s", model)
    return dict(rhs_ir=int(rhs), run_ir=int(run), share=rhs / run)


def perf_share(exe, model, n, revs, stepper, tmp, runs=200):
    """perf's sampled share: inclusive samples of the right-hand side / of autobal_transient_run"""
    f = os.path.join(tmp, f"perf.{model}{n}.{stepper}")
    subprocess.run(["perf", "record", "-q", "-e", "cpu-clock", "-F", "20000", "--call-graph", "dwarf", "-o", f,
                    exe, model, str(n), stepper, "dense6", "1e-8", "1e-8", str(revs), "0", str(-runs), "-"],
                   check=True, capture_output=True)
    txt = subprocess.run(["perf", "report", "-i", f, "--stdio", "--children", "--sort", "symbol"], check=True,
                         capture_output=True, text=True).stdout
    os.remove(f)
    rhs, run = inclusive(txt, r"\s*([\d.]+)%\s+[\d.]+%\s+\[\.\]\s+(\S+?)(?:\.avx2)?\s", model)
    return rhs / run


def summary(arch):
    print(f"\n==== issue 20: the targets, {arch['started']} (load {arch['load_before']:.1f} -> {arch['load_after']:.1f}) ====")
    print("\n1. output every quarter revolution: out/none of the CLI's transient (time; target <= 1.10)")
    print(f"{'case':<10}{'output':<8}{'rtol':>7} | {'this':>7}{'ref':>7} | {'instr.':>7} | rhs out/none   | status")
    for r in arch["ratio"]["rows"]:
        ins = arch.get("instructions", {}).get(f"{r['case']}:{r['output']}:{r['tol']:.0e}")
        nw = r["new"]
        ok = nw["median_ratio"] <= 1.10
        print(f"{r['case']:<10}{r['output']:<8}{r['tol']:>7.0e} | {nw['median_ratio']:>7.3f}{r['ref']['median_ratio']:>7.3f} | "
              f"{(f'{ins:7.3f}' if ins else '      -')} | {nw['out_rhs']:>6}/{nw['none_rhs']:<6}  | "
              f"{'met' if ok else 'NOT met'}")
    print("\n2. the CLI's whole transient (with output) vs SciPy DOP853 at matched error of the output points")
    sys.path.insert(0, here)
    from dense_scipy import matched  # noqa: E402
    for res in arch["scipy"]["cases"]:
        key = "pendulum" if res["model"] == "pendulum" else f"rotor{res['nballs']}"
        dop = [(s["err"], s["seconds"]) for s in res["scipy"] if s["method"] == "DOP853"]
        for a in res["autobal"]:
            m = matched(dop, a["err"])
            x = m / a["run"]["out_seconds"] if m else None
            st = ("met" if x >= TARGET_X[key] else "NOT met") if x else "out of SciPy's range"
            print(f"  {key:<9}{a['stepper'] + ' ' + a['output']:<14}{a['tol']:>7.0e}  err {a['err']:.2e}  "
                  f"CLI {1e3 * a['run']['out_seconds']:.3f} ms  SciPy @err "
                  f"{(f'{1e3 * m:.1f} ms  {x:.0f}x' if m else '-'):<22} (>= {TARGET_X[key]:.0f}x: {st})")
    print("\n   accuracy of the output points, dense6 / dense (contd8), same rtol:")
    for res in arch["scipy"]["cases"]:
        key = "pendulum" if res["model"] == "pendulum" else f"rotor{res['nballs']}"
        e = {(a["output"], a["tol"]): a["err"] for a in res["autobal"] if a["stepper"] == "dop853"}
        tols = sorted({t for (_, t) in e}, reverse=True)
        print(f"  {key:<9}" + "  ".join(f"{t:.0e}: {e[('dense6', t)]:.2e} / {e[('dense', t)]:.2e} = "
                                      f"{e[('dense6', t)] / e[('dense', t)]:.2f}" for t in tols
                                      if ("dense6", t) in e and ("dense", t) in e))
    print("\n3. share of the bare integration inside the right-hand side (target >= 0.80)")
    for k, v in arch["share"].items():
        st = "met" if v["share"] >= 0.80 else "NOT met"
        t = v.get("time_share")
        p = v.get("perf_share")
        print(f"  {k:<18} instructions {v['share']:.3f} ({v['rhs_ir'] / 1e6:.2f}M of {v['run_ir'] / 1e6:.2f}M)"
              + (f", time by perf's samples {p:.3f}" if p else "")
              + (f", time by the replay {t:.2f}" if t else "") + f": {st} by instructions"
              + (f", {'met' if p >= 0.80 else 'NOT met'} by perf's samples" if p else ""))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", required=True)
    ap.add_argument("--before", required=True)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--repeats", type=int, default=21)
    ap.add_argument("--scipy-tols", default="1e-5,3e-6,1e-6,3e-7,1e-7,3e-8,1e-8,3e-9,1e-9,3e-10,1e-10,3e-11,1e-11")
    ap.add_argument("--c-repeats", type=int, default=15)
    ap.add_argument("--out", default="issue20.json")
    ap.add_argument("--from", dest="from_", help="print the targets of an existing archive")
    a = ap.parse_args()
    if a.from_:
        summary(json.load(open(a.from_)))
        return
    arch = dict(started=time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()), load_before=os.getloadavg()[0])
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp:
        # 3. callgrind first (load-independent), then the instruction ratios out/none of 1.
        arch["share"] = {}
        arch["instructions"] = {}
        if shutil.which("valgrind") and shutil.which("callgrind_annotate"):
            for c, (model, n, revs) in CASES.items():
                for stepper in ("dop853", "rk8pd"):
                    arch["share"][f"{c} {stepper}"] = callgrind_share(a.bench, model, n, revs, stepper, tmp)
                for output in ("dense6", "dense"):
                    for tol in (1e-6, 1e-8, 1e-10):
                        f = os.path.join(tmp, "cg.ratio")
                        subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={f}",
                                        "--dump-before=run_study", "--dump-after=run_study", a.bench, model, str(n),
                                        "dop853", output, str(tol), str(tol), str(revs), "0.25", "1", "-"],
                                       check=True, capture_output=True)
                        tot = {}
                        for part in (2, 4):
                            for line in open(f"{f}.{part}"):
                                if line.startswith("totals:"):
                                    tot[part] = int(line.split()[1])
                        arch["instructions"][f"{c}:{output}:{tol:.0e}"] = tot[2] / tot[4]
                        for p in os.listdir(tmp):
                            if p.startswith("cg.ratio"):
                                os.remove(os.path.join(tmp, p))
        # 3 (c). perf's sampled time share, where perf is installed and may sample (scripts/deps.sh --bench)
        if shutil.which("perf"):
            for c, (model, n, revs) in CASES.items():
                for stepper in ("dop853", "rk8pd"):
                    try:
                        arch["share"].setdefault(f"{c} {stepper}", {})["perf_share"] = perf_share(
                            a.bench, model, n, revs, stepper, tmp)
                    except (subprocess.CalledProcessError, KeyError) as ex:
                        print(f"perf: no sampled share for {c} {stepper} ({ex})", file=sys.stderr)
        # 1. time out/none, this library and the reference interleaved
        fr = os.path.join(tmp, "ratio.json")
        run([py, os.path.join(here, "dense_ratio.py"), "--bench", a.bench, "--before", a.before, "--rounds",
             str(a.rounds), "--repeats", str(a.repeats), "--outputs", "dense6,dense", "--out", fr])
        arch["ratio"] = json.load(open(fr))
        # 2. SciPy DOP853 at matched error, the accuracy of the output points; bench_dense's time share
        fs = os.path.join(tmp, "scipy.json")
        run([py, os.path.join(here, "dense_scipy.py"), "--bench", a.bench, "--configs",
             "dop853:dense6,dop853:dense,rk8pd:exact", "--methods", "DOP853", "--scipy-tols", a.scipy_tols,
             "--c-repeats", str(a.c_repeats), "--scipy-repeats", "1", "--out", fs])
        arch["scipy"] = json.load(open(fs))
        for res in arch["scipy"]["cases"]:
            key = "pendulum" if res["model"] == "pendulum" else f"rotor{res['nballs']}"
            for e in res["autobal"]:
                k = f"{key} {e['stepper']}"
                if e["tol"] == 1e-8 and e["output"] in ("dense6", "exact") and k in arch["share"]:
                    arch["share"][k]["time_share"] = e["run"]["rhs_share"]
    arch["load_after"] = os.getloadavg()[0]
    with open(a.out, "w") as f:
        json.dump(arch, f, indent=1)
    print(f"archive: {a.out}")
    summary(arch)


if __name__ == "__main__":
    main()
