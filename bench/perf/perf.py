#!/usr/bin/python3
"""Performance benchmarks of issue 7, measured side by side in one run.

autobal (C, through bench_perf) against the best NumPy a skilled user would
write for the same work:

  roots     roots of the pendulum's degree-8 polynomial (6): autobal_poly_roots
            (Aberth-Ehrlich, companion QR fall-back) vs NumPy batched np.linalg.eigvals on a stack of
            companion matrices (the same 20000 polynomials, read from the file
            bench_perf writes); per core (OPENBLAS_NUM_THREADS=1, one thread).
  verdict   the sign-test verdict (autobal_pendulum_verdict: (6) + Routh test
            with rounding bounds) vs a root solve (autobal_poly_roots).
  maps      the (R_m, R_w) stability map, 1000 x 1000, one k, coefficients
            included: autobal_pendulum_map (OpenMP, 2 threads) vs a
            vectorized NumPy Routh-Hurwitz map (coefficients of (6) from the
            same closed forms, vectorized over the grid by broadcasting; the
            first column of the Routh array, i.e. the ratios of consecutive
            Hurwitz determinants, vectorized; no rounding bounds); the
            "every unbalance" map (65 values of k) likewise (NumPy: the
            vectorized map for each k, minimum over k).
  scaling   map cost per point vs grid size; OpenMP speed-up 2 threads vs 1.
  hdf5      a transient writing 1e6 samples x 20 channels through the archive
            series API vs the same run computing the channels without writing;
            file size vs raw size.
  rhs       share of autobal's transient run time spent in the right-hand side.
  sundials  (if bench_sundials was built) CVODE Adams and ARKODE ERK on the
            same right-hand side at matched error.

Times are best of N runs (the machine is shared: the best run is the least
disturbed one): wall time for autobal's maps (threads) and transients,
process CPU time for the one-thread measurements (autobal's roots and
verdicts, every NumPy measurement); the load average is printed before and
after.

Run through bench/perf/run.sh (builds bench_perf first) with /usr/bin/python3.
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
import numpy as np  # noqa: E402

# ---- helpers -----------------------------------------------------------------


def run_json(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def best_of(fn, reps, clock=time.process_time):
    """Best of reps runs.  NumPy runs in one thread (OPENBLAS_NUM_THREADS=1),
    so its process CPU time is its per-core time, and time the process
    spends preempted by other processes on the shared machine does not count."""
    best = float("inf")
    res = None
    for _ in range(reps):
        t = clock()
        res = fn()
        t = clock() - t
        best = min(best, t)
    return best, res


def load():
    try:
        return " ".join(open("/proc/loadavg").read().split()[:3])
    except OSError:
        return "?"


# ---- NumPy references ----------------------------------------------------------


def companion_stack(c):
    """c: (N, 9) ascending coefficients -> (N, 8, 8) companion matrices (the
    layout of np.roots)."""
    p = c[:, ::-1]
    n = p.shape[1] - 1
    A = np.zeros((p.shape[0], n, n))
    A[:, 0, :] = -p[:, 1:] / p[:, :1]
    A[:, np.arange(1, n), np.arange(n - 1)] = 1.0
    return A


def routh_stable(desc):
    """desc: list of arrays, coefficients in DESCENDING powers, leading > 0.
    True where every entry of the first column of the Routh array is > 0
    (all roots in the open left half plane)."""
    n = len(desc) - 1
    r0 = list(desc[0::2])
    r1 = list(desc[1::2])
    ok = r1[0] > 0
    for _ in range(2, n + 1):
        q = r0[0] / r1[0]
        new = [r0[j + 1] - q * r1[j + 1] if j + 1 < len(r1) else r0[j + 1]
               for j in range(len(r0) - 1)]
        ok &= new[0] > 0
        r0, r1 = r1, new
    return ok


def char_parts_np(Rm, Rw, H, h):
    """The k-independent parts of (6) on the grid (broadcasting Rm (n, 1)
    against Rw (1, m)): A = |P1|^2 coefficients (ascending, list of 9) and
    W = Rw^2, with P1 = sum p_j lambda^j (15):
      p4 = 1 - Rm, p3 = (H + h) + 2i Rw (1 - 2Rm), p2 = 1 - W + hH + 6 Rm W
      + i Rw (H + 2h), p1 = h(1 - W) + i Rw (hH + 4 Rm W), p0 = -Rm W^2."""
    W = Rw * Rw
    x4 = 1.0 - Rm
    x3 = H + h
    y3 = 2.0 * (1.0 - 2.0 * Rm) * Rw
    x2 = (1.0 + h * H) + (6.0 * Rm - 1.0) * W
    y2 = (H + 2.0 * h) * Rw
    x1 = h * (1.0 - W)
    y1 = Rw * (h * H + 4.0 * Rm * W)
    x0 = -Rm * (W * W)
    A = [None] * 9
    A[8] = x4 * x4 + 0.0 * W
    A[7] = 2.0 * x4 * x3 + 0.0 * W
    A[6] = 2.0 * x4 * x2 + x3 * x3 + y3 * y3
    A[5] = 2.0 * (x4 * x1 + x3 * x2 + y3 * y2)
    A[4] = 2.0 * (x4 * x0 + x3 * x1 + y3 * y1) + x2 * x2 + y2 * y2
    A[3] = 2.0 * (x3 * x0 + x2 * x1 + y2 * y1)
    A[2] = 2.0 * x2 * x0 + x1 * x1 + y1 * y1
    A[1] = 2.0 * x1 * x0
    return A, W


def numpy_map(Rm, Rw, H, h, ks):
    """Vectorized Routh-Hurwitz map: +1 stable, -1 not (worst over ks).
    (6) = A - Rm^2 (1 - k) (lambda^2 + W)^4, constant term k Rm^2 W^4."""
    Rm = Rm[:, None]
    Rw = Rw[None, :]
    A, W = char_parts_np(Rm, Rw, H, h)
    Rm2 = Rm * Rm
    W2 = W * W
    B = {8: 1.0, 6: 4.0 * W, 4: 6.0 * W2, 2: 4.0 * W2 * W}
    stable = None
    for k in ks:
        f = Rm2 * (1.0 - k)
        c = [None] * 9
        for j in (1, 3, 5, 7):
            c[j] = A[j]
        for j in (2, 4, 6, 8):
            c[j] = A[j] - f * B[j]
        c[0] = (k * Rm2) * (W2 * W2)
        desc = c[::-1] if k != 0.0 else c[:0:-1]  # k = 0: lambda = 0 divided out
        s = routh_stable(desc)
        stable = s if stable is None else (stable & s)
    return np.where(stable, 1, -1).astype(np.int8)


# ---- the benchmarks ----------------------------------------------------------------


def bench_roots(exe, n, reps, tmp):
    path = os.path.join(tmp, "coef.bin")
    c_res = run_json([exe, "roots", str(n), str(reps), path])
    c = np.fromfile(path).reshape(n, 9)
    A = companion_stack(c)
    t_eig, ev = best_of(lambda: np.linalg.eigvals(A), reps)
    # the same roots? distance of every autobal root to the nearest NumPy
    # eigenvalue, relative to the largest root modulus of its polynomial
    z = np.fromfile(path + ".roots").reshape(n, 8, 2)
    za = z[:, :, 0] + 1j * z[:, :, 1]
    dist = np.abs(za[:, :, None] - ev[:, None, :]).min(axis=2).max(axis=1)
    rel = dist / np.abs(ev).max(axis=1)
    t_build, _ = best_of(lambda: companion_stack(c), reps)
    # NumPy sign test on the same polynomials (vectorized over the batch)
    desc = [c[:, j] for j in range(8, -1, -1)]
    t_routh, _ = best_of(lambda: routh_stable(desc), reps)
    return dict(c=c_res, numpy_eig_s=t_eig / n, numpy_build_s=t_build / n,
                numpy_routh_s=t_routh / n, numpy_roots_per_s=8 * n / t_eig,
                agree_median=float(np.median(rel)), agree_max=float(rel.max()))


def bench_maps(exe, n, reps_map, reps_np, reps_65, tmp, do_np65):
    H, h = 0.05, 0.1
    k1 = np.sin(1.0) ** 2
    Rm = 0.005 + 0.49 * np.arange(n) / (n - 1)
    Rw = 0.05 + 4.95 * np.arange(n) / (n - 1)
    res = {}
    vfile = os.path.join(tmp, "v.bin")
    res["one2"] = run_json([exe, "map", str(n), str(n), str(H), str(h), "1", "2", str(reps_map), vfile])
    res["one1"] = run_json([exe, "map", str(n), str(n), str(H), str(h), "1", "1", str(reps_map)])
    v_c = np.fromfile(vfile, dtype=np.int8).reshape(n, n)
    t_np, v_np = best_of(lambda: numpy_map(Rm, Rw, H, h, [k1]), reps_np)
    res["np_one"] = t_np
    decided = v_c != 0
    res["agree_one"] = float(np.mean((v_c == v_np)[decided]))
    res["marginal_one"] = int(np.sum(~decided))
    res["all2"] = run_json([exe, "map", str(n), str(n), str(H), str(h), "0", "2", str(reps_65), vfile])
    res["all1"] = run_json([exe, "map", str(n), str(n), str(H), str(h), "0", "1", str(max(1, reps_65 - 1))])
    if do_np65:
        v_c = np.fromfile(vfile, dtype=np.int8).reshape(n, n)
        ks = np.arange(65) / 64.0
        t0 = time.process_time()
        v_np = numpy_map(Rm, Rw, H, h, ks)
        res["np_all"] = time.process_time() - t0
        decided = v_c != 0
        res["agree_all"] = float(np.mean((v_c == v_np)[decided]))
    res["und_one2"] = run_json([exe, "map", str(n), str(n), "0", "0", "1", "2", str(reps_map)])
    res["und_one1"] = run_json([exe, "map", str(n), str(n), "0", "0", "1", "1", str(reps_map)])
    res["und_all2"] = run_json([exe, "map", str(n), str(n), "0", "0", "0", "2", str(reps_65)])
    res["und_all1"] = run_json([exe, "map", str(n), str(n), "0", "0", "0", "1", str(max(1, reps_65 - 1))])
    return res


def callgrind_irefs(cmd):
    """Instructions executed by cmd (valgrind --tool=callgrind)."""
    r = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"] + cmd,
                       capture_output=True, text=True, check=True)
    for line in r.stderr.splitlines():
        if "refs:" in line:
            return int(line.split("refs:")[1].strip().replace(",", ""))
    raise RuntimeError("no instruction count from valgrind")


def bench_callgrind(exe):
    """Instruction counts per grid point (load-independent), one thread:
    the map minus the same program on a 1 x 1 grid."""
    out = []
    for what, n, H, h, nk in (("damped, one k", 400, "0.05", "0.1", "1"),
                              ("damped, 65 k", 160, "0.05", "0.1", "0"),
                              ("undamped, one k", 400, "0", "0", "1"),
                              ("undamped, 65 k", 160, "0", "0", "0")):
        base = callgrind_irefs([exe, "map", "1", "1", H, h, nk, "1", "1"])
        full = callgrind_irefs([exe, "map", str(n), str(n), H, h, nk, "1", "1"])
        out.append((what, n, (full - base) / float(n * n)))
    return out


def bench_scaling(exe, sizes, reps):
    out = []
    for m in sizes:
        r = max(3, int(reps * (1000 / m) ** 2 / 4))
        a = run_json([exe, "map", str(m), str(m), "0.05", "0.1", "1", "1", str(r)])
        b = run_json([exe, "map", str(m), str(m), "0.05", "0.1", "1", "2", str(r)])
        out.append((m, a, b))
    return out


# ---- main ------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bench", required=True, help="path of the bench_perf executable")
    ap.add_argument("--sundials", default="", help="path of bench_sundials (optional)")
    ap.add_argument("--quick", action="store_true", help="fewer repetitions, no 65-k NumPy map")
    ap.add_argument("--only", default="roots,maps,scaling,hdf5,rhs,sundials",
                    help="comma-separated subset (also: callgrind, not in the default set)")
    args = ap.parse_args()
    only = set(args.only.split(","))
    q = args.quick
    print("machine: %s, %d cores; %s; Python %s, NumPy %s" % (
        platform.processor() or platform.machine(), os.cpu_count(), platform.platform(),
        platform.python_version(), np.__version__))
    try:
        cpu = [l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")][0]
        print("cpu: %s" % cpu)
    except (OSError, IndexError):
        pass
    print("date: %s; load average at start: %s" % (time.strftime("%Y-%m-%d %H:%M"), load()))
    rows = []  # (what, autobal, reference, ratio text, target, met)

    with tempfile.TemporaryDirectory() as tmp:
        if "roots" in only:
            r = bench_roots(args.bench, 20000, 3 if q else 7, tmp)
            c = r["c"]
            print("\n[roots] %d degree-8 polynomials (6), best of %d" % (c["n"], c["reps"]))
            print("  autobal_poly_roots          %8.3f us/poly  %.3g roots/s" % (1e6 * c["roots_s_per_poly"], c["roots_per_s"]))
            print("  NumPy eigvals (batched)     %8.3f us/poly  %.3g roots/s  (+ %.3f us/poly to build the companion stack)" % (
                1e6 * r["numpy_eig_s"], r["numpy_roots_per_s"], 1e6 * r["numpy_build_s"]))
            print("  same roots: autobal vs NumPy, distance / max |root| per polynomial: median %.1e, max %.1e" % (
                r["agree_median"], r["agree_max"]))
            print("  autobal_pendulum_verdict    %8.3f us       (coefficients + Routh test with rounding bounds)" % (1e6 * c["verdict_s"]))
            print("  autobal_poly_hurwitz        %8.3f us       (Routh test on given coefficients)" % (1e6 * c["hurwitz_s"]))
            print("  NumPy Routh (batched)       %8.3f us/poly" % (1e6 * r["numpy_routh_s"]))
            ratio = c["roots_per_s"] / r["numpy_roots_per_s"]
            rows.append(("roots/s per core vs NumPy eigvals", "%.3g/s" % c["roots_per_s"],
                         "%.3g/s" % r["numpy_roots_per_s"], "%.2fx" % ratio, ">= 2.5x", ratio >= 2.5))
            ratio = c["roots_s_per_poly"] / c["verdict_s"]
            rows.append(("verdict vs root solve (autobal)", "%.0f ns" % (1e9 * c["verdict_s"]),
                         "%.0f ns" % (1e9 * c["roots_s_per_poly"]), "%.0fx cheaper" % ratio, ">= 30x", ratio >= 30))
        if "maps" in only:
            m = bench_maps(args.bench, 1000, 5 if q else 31, 2 if q else 3, 2 if q else 6, tmp, not q)
            o2, o1 = m["one2"], m["one1"]
            print("\n[maps] 1000 x 1000, R_m in [0.005, 0.495], R_w in [0.05, 5], H = 0.05, h = 0.1")
            print("  one k (k = sin^2 1): autobal 2 threads %.1f ms, 1 thread %.1f ms; NumPy %.1f ms "
                  "(agreement on decided points %.5f, autobal marginal %d)" % (
                      1e3 * o2["seconds"], 1e3 * o1["seconds"], 1e3 * m["np_one"], m["agree_one"], m["marginal_one"]))
            a2, a1 = m["all2"], m["all1"]
            line = "  65 k (every unbalance): autobal 2 threads %.3f s, 1 thread %.3f s" % (a2["seconds"], a1["seconds"])
            if "np_all" in m:
                line += "; NumPy %.2f s (agreement %.5f)" % (m["np_all"], m["agree_all"])
            print(line)
            print("  undamped (H = h = 0, exact criterion of (10)): one k %.1f ms (2 threads), %.1f ms (1 thread); "
                  "65 k %.3f s (2 threads), %.3f s (1 thread)" % (
                      1e3 * m["und_one2"]["seconds"], 1e3 * m["und_one1"]["seconds"],
                      m["und_all2"]["seconds"], m["und_all1"]["seconds"]))
            rows.append(("one-k map 1000^2, 2 threads", "%.1f ms" % (1e3 * o2["seconds"]), "", "", "<= 50 ms",
                         o2["seconds"] <= 0.05))
            ratio = m["np_one"] / o2["seconds"]
            rows.append(("one-k map vs NumPy Routh map", "%.1f ms" % (1e3 * o2["seconds"]),
                         "%.1f ms" % (1e3 * m["np_one"]), "%.1fx faster" % ratio, ">= 4x", ratio >= 4))
            rows.append(("65-k map 1000^2, 2 threads", "%.3f s" % a2["seconds"],
                         "%.2f s" % m["np_all"] if "np_all" in m else "",
                         "%.0fx faster" % (m["np_all"] / a2["seconds"]) if "np_all" in m else "",
                         "<= 2 s", a2["seconds"] <= 2.0))
            rows.append(("65-k undamped map, 2 threads", "%.3f s" % m["und_all2"]["seconds"], "", "", "<= 2 s",
                         m["und_all2"]["seconds"] <= 2.0))
            sp1 = o1["seconds"] / o2["seconds"]
            sp2 = a1["seconds"] / a2["seconds"]
            rows.append(("OpenMP speed-up one-k map", "%.2fx" % sp1, "", "", ">= 1.8x", sp1 >= 1.8))
            rows.append(("OpenMP speed-up 65-k map", "%.2fx" % sp2, "", "", ">= 1.8x", sp2 >= 1.8))
            sp3 = m["und_one1"]["seconds"] / m["und_one2"]["seconds"]
            sp4 = m["und_all1"]["seconds"] / m["und_all2"]["seconds"]
            rows.append(("OpenMP speed-up undamped one-k map", "%.2fx" % sp3, "", "", ">= 1.8x", sp3 >= 1.8))
            rows.append(("OpenMP speed-up undamped 65-k map", "%.2fx" % sp4, "", "", ">= 1.8x", sp4 >= 1.8))
        if "scaling" in only:
            sc = bench_scaling(args.bench, [250, 500, 1000, 2000], 6 if q else 12)
            print("\n[scaling] one-k damped map, ns per grid point (best of N)")
            print("  %6s %12s %12s %10s" % ("N x N", "1 thread", "2 threads", "speed-up"))
            for mm, a, b in sc:
                print("  %6d %12.2f %12.2f %10.2f" % (mm, a["ns_per_point"], b["ns_per_point"], a["seconds"] / b["seconds"]))
            per = [a["ns_per_point"] for _, a, _ in sc]
            spread = max(per) / min(per)
            rows.append(("map cost linear in grid size", "%.1f-%.1f ns/pt" % (min(per), max(per)), "", "max/min %.2f" % spread,
                         "const ns/pt", spread < 1.3))
        if "callgrind" in only:
            print("\n[callgrind] instructions per grid point, 1 thread (same ranges, smaller grids)")
            for what, n, ipp in bench_callgrind(args.bench):
                print("  %-18s %4d x %-4d %10.0f instructions/point" % (what, n, n, ipp))
        if "hdf5" in only:
            path = os.path.join(tmp, "series.h5")
            r = run_json([args.bench, "hdf5", "1000000", "20", "2" if q else "3", path])
            print("\n[hdf5] pendulum transient, %d samples x %d channels (+ time), rk8pd rtol 1e-10, dt_out 0.1" % (
                r["samples"], r["channels"]))
            print("  without writing %.3f s, writing %.3f s: overhead %.1f%%; file %.1f MB for %.1f MB raw (ratio %.2f)" % (
                r["seconds_no_write"], r["seconds_write"], 100 * r["overhead"], r["file_bytes"] / 1e6,
                r["raw_bytes"] / 1e6, r["ratio"]))
            rows.append(("HDF5 writing overhead (1e6 x 20)", "%.1f%%" % (100 * r["overhead"]), "", "", "<= 10%",
                         r["overhead"] <= 0.10))
            rows.append(("HDF5 compression ratio", "%.2f" % r["ratio"], "", "", "compressed", r["ratio"] > 1.0))
        if "rhs" in only:
            print("\n[rhs] share of the transient run time in the right-hand side (rk8pd, tau in [0, 100])")
            shares = []
            for tol in ("1e-6", "1e-8", "1e-10"):
                r = run_json([args.bench, "rhs", "100", tol, "51" if q else "201"])
                shares.append(r["rhs_share"])
                print("  tol %-6s run %.3f ms, %d rhs evals, %.1f ns/eval; rhs alone %.1f ns/eval: share %.0f%%" % (
                    tol, 1e3 * r["seconds_run"], r["rhs_evals"], r["ns_per_eval_run"], r["ns_per_rhs"], 100 * r["rhs_share"]))
            rows.append(("share of run time in the rhs", "%.0f-%.0f%%" % (100 * min(shares), 100 * max(shares)), "", "",
                         ">= 50%", min(shares) >= 0.5))
        if "sundials" in only and args.sundials and os.path.exists(args.sundials):
            r = run_json([args.sundials, "all"])
            print("\n[sundials] pendulum transient, tau in [0, 100], error vs a tight reference (max over components)")
            print("  %-22s %8s %10s %10s %12s" % ("solver", "tol", "time [ms]", "rhs evals", "max |err|"))
            for e in r["runs"]:
                print("  %-22s %8.0e %10.3f %10d %12.3g" % (e["solver"], e["tol"], 1e3 * e["seconds"], e["rhs_evals"], e["err"]))
            for what, ratio in r.get("ratios", []):
                rows.append(("autobal vs %s (matched error)" % what, "", "", "%.2fx faster" % ratio, "> 1x", ratio > 1.0))

    print("\nload average at end: %s" % load())
    print("\n%-36s %14s %14s %16s %12s %5s" % ("measure", "autobal", "reference", "ratio", "target", "met"))
    print("-" * 104)
    for what, a, b, ratio, target, met in rows:
        print("%-36s %14s %14s %16s %12s %5s" % (what, a, b, ratio, target, "yes" if met else "NO"))


if __name__ == "__main__":
    main()
