#!/usr/bin/python3
"""Checks of `autobal pendulum critical --json` and the undamped `autobal pendulum map` against
an independent reference (pendulum_crit_ref.py: SymPy's exact real-root isolation of the
discriminant of (10) in W, verdicts from 80-digit roots), issue 18 items 1, 2 and 5:

  item 1: R_m from 0.249 to 0.2499999 (critical speeds R_w up to ~1e4) for k = 0, 0.5, 0.9999, 1;
  item 2: the stable island (R_w1, R_w2) of relative width ~1e-7 at k = 0.9999 on a dense R_m
          grid 0.04478 ... 0.04490 across the R_m where the extra pair appears;
  item 5: the kinds (gained, lost, touch) and the closed forms in the JSON;
  map:    rows of the undamped map near R_m = 1/4 against the reference's stable intervals.

Every case: the same number of critical speeds and kinds as the reference, each R_w to
RTOL relative, the stable intervals, *_unresolved false.  The reference takes R_m and k as the
exact doubles the program used (k read back from the JSON: the program stores psi0).
In the sanitizer build (environment SANITIZE=1) autobal still runs for every case (the C code under
ASan/UBSan), but the SymPy/mpmath reference, pure Python and the same in both builds, is computed for
every 4th case only (and the island's count check is left out); the Release pass compares all of them.
Usage: pendulum_exact_check.py AUTOBAL SCRATCH"""
import json
import os
import subprocess
import sys

import h5py
import mpmath
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pendulum_crit_ref as ref  # noqa: E402

RTOL = 1e-13
AUTOBAL, SCRATCH = sys.argv[1], sys.argv[2]
THIN = 4 if os.environ.get("SANITIZE", "0") == "1" else 1
fails = 0
checks = 0
cases = 0  # compare() calls so far (THIN: which get the reference)


def check(what, ok):
    global fails, checks
    checks += 1
    if not ok:
        fails += 1
    print(("ok   " if ok else "FAIL ") + what, flush=True)


def run_critical(rm, k):
    p = subprocess.run([AUTOBAL, "pendulum", "critical", "--set", f"pendulum.R_m={rm}", "--set", f"pendulum.k={k}",
                        "--set", "pendulum.H=0", "--set", "pendulum.h=0", "--set", "critical.n_Rm=2", "--json"],
                       capture_output=True, text=True)
    if p.returncode != 0:
        return None, p.stderr
    return json.loads(p.stdout), p.stderr


def compare(rm, k, extra=""):
    global cases
    cases += 1
    d, err = run_critical(rm, k)
    if d is None:
        check(f"R_m = {rm}, k = {k}: exit 0 ({err.strip()})", False)
        return None, None
    if (cases - 1) % THIN:
        check(f"R_m = {rm}, k = {k}{extra}: {len(d['undamped_critical_R_w'])} critical speeds, resolved "
              "(sanitizer build: reference at every 4th case)", d["undamped_unresolved"] is False and not err.strip())
        return None, None
    r = ref.critical(repr(d["R_m"]), repr(d["k"]))
    got, kinds = d["undamped_critical_R_w"], d["undamped_kind"]
    want = [mpmath.mpf(v) for v in r["R_w"]]
    same = len(got) == len(want) and kinds == r["kind"]
    err_max = max([abs(g - w) / w for g, w in zip(got, want)] + [mpmath.mpf(0)]) if same else None
    lo_ok = same and len(d["undamped_stable_lo"]) == len(r["stable_lo"]) and all(
        abs(g - mpmath.mpf(w)) <= RTOL * mpmath.mpf(w) for g, w in zip(d["undamped_stable_lo"], r["stable_lo"]))
    ok = same and err_max <= RTOL and lo_ok and d["undamped_unresolved"] is False and not err.strip()
    check(f"R_m = {rm}, k = {k}{extra}: {len(got)} critical speeds {d['undamped_kind_name']}"
          + (f", max rel err {float(err_max):.1e} (tol {RTOL:g})" if same else
             f" -- reference {[float(w) for w in want]} {r['kind']}, got {got} {kinds}"), ok)
    return d, r


# ---- item 1: R_m -> 1/4 -------------------------------------------------------------------
for rm in ["0.249", "0.2492", "0.2494", "0.2495", "0.2496", "0.2497", "0.2498", "0.2499", "0.24995", "0.24999",
           "0.249999", "0.2499999"]:
    for k in ["0", "0.5", "0.9999", "1"]:
        d, r = compare(rm, k)
        if d is not None and k == "1":
            # item 5: the touch at (18) is named, and the closed form agrees with the reference
            f18 = d["closed_forms"]["eq18_R_w23_k1"]
            t = [mpmath.mpf(v) for v, kk in zip(r["R_w"], r["kind"]) if kk == 0]
            check(f"  k = 1, R_m = {rm}: kind names {d['k1_kind_name']} == ['gained', 'touch'], "
                  f"(18) = {f18} vs reference touch to 1e-14",
                  d["k1_kind_name"] == ["gained", "touch"] and len(t) == 1 and abs(f18 - t[0]) <= 1e-14 * t[0]
                  and d["closed_form_errors"]["eq18_R_w23_k1"] <= 1e-14)
        if d is not None and k == "0":
            # (14): the JSON's series value and its error against the numerical R_w2, R_w3
            q = mpmath.sqrt((mpmath.mpf(0.25) - mpmath.mpf(d["R_m"])) / 2)
            e2, e3 = d["closed_form_errors"]["eq14_R_w2_k0"], d["closed_form_errors"]["eq14_R_w3_k0"]
            check(f"  k = 0, R_m = {rm}: JSON errors of (14) {e2:.2e}, {e3:.2e} below 60 q^5 = {float(60 * q**5):.2e}",
                  e2 <= 60 * q**5 + 1e-15 and e3 <= 60 * q**5 + 1e-15 and d["closed_forms"]["eq13_R_w1_k0"] == 1.0
                  and d["closed_form_errors"]["eq13_R_w1_k0"] == 0.0 and d["k0_kind_name"] == ["gained", "lost", "gained"])

# ---- item 5: the closed forms at small R_m (the first form of (14), (16), (17)) -----------------
for rm in ["0.001", "0.01", "0.03"]:
    d, r = compare(rm, "0")
    if d is None:
        continue
    x = float(d["R_m"])
    eps, s3 = (x / 2) ** (1 / 3), x ** (1 / 3)
    cf, ce = d["closed_forms"], d["closed_form_errors"]
    w2, w3 = [mpmath.mpf(v) for v in r["R_w"][1:3]]
    check(f"  R_m = {rm}: (14) first form, errors {ce['eq14_R_w2_k0']:.2e} < 60 R_m^3, {ce['eq14_R_w3_k0']:.2e} < 10 eps^4, "
          f"consistent with the reference",
          cf["eq14_form"] == "R_m < 0.05" and ce["eq14_R_w2_k0"] < 60 * x**3 and ce["eq14_R_w3_k0"] < 10 * eps**4
          and abs(abs(cf["eq14_R_w2_k0"] - w2) / w2 - ce["eq14_R_w2_k0"]) < 1e-14
          and abs(abs(cf["eq14_R_w3_k0"] - w3) / w3 - ce["eq14_R_w3_k0"]) < 1e-14)
    # (16) exact; (17) truncated after s^3: next term -407 s^4/3456 (docs/pendulum.md)
    check(f"  R_m = {rm}: (16) error {ce['eq16_R_w1_k1']:.1e} < 1e-14, (17) error {ce['eq17_R_w1_k1']:.2e} < 0.2 s^4",
          ce["eq16_R_w1_k1"] < 1e-14 and ce["eq17_R_w1_k1"] < 0.2 * s3**4 and d["k1_kind_name"][0] == "gained")

# ---- item 2: the island near R_m = 0.0448, k = 0.9999 ----------------------------------------
counts = []
for i in range(13):
    rm = f"{0.04478 + 1e-5 * i:.5f}"
    d, r = compare(rm, "0.9999", " (island)")
    if r is not None:
        counts.append(len(r["R_w"]))
if THIN == 1:
    check(f"the island appears inside the grid (reference counts {counts})", 1 in counts and 3 in counts)
for rm in ["0.0448", "0.0449", "0.05"]:
    for k in ["0.99", "0.999999"]:
        compare(rm, k)

# ---- the archive: the flags as attributes ----------------------------------------------------
h5 = os.path.join(SCRATCH, "crit.h5")
subprocess.run([AUTOBAL, "pendulum", "critical", "--set", "pendulum.R_m=0.04482", "--set", "pendulum.k=0.9999",
                "--set", "pendulum.H=0", "--set", "pendulum.h=0", "--set", "critical.n_Rm=3", "-o", h5, "--force"],
               check=True, capture_output=True)
with h5py.File(h5, "r") as f:
    g = f["/pendulum/critical"]
    check("archive: undamped_unresolved = 0, undamped_resolution_W = DBL_EPSILON, undamped_R_w has 3 entries",
          int(g.attrs["undamped_unresolved"]) == 0 and int(g.attrs["undamped_k1_unresolved"]) == 0
          and float(g.attrs["undamped_resolution_W"]) == float(np.finfo(float).eps) and len(g["undamped_R_w"]) == 3)

# ---- the undamped map near R_m = 1/4 ---------------------------------------------------------
for im, (rm, k, lo, hi) in enumerate([(0.246, 0, 50, 80), (0.2494, 0, 300, 450), (0.2495, 0, 450, 560),
                                      (0.2497, 0, 780, 880), (0.2495, 0.5, 450, 560), (0.2499, 0.9, 2400, 2600),
                                      (0.24995, 0, 4800, 5300)]):
    h5 = os.path.join(SCRATCH, "map.h5")
    subprocess.run([AUTOBAL, "pendulum", "map", "--set", "pendulum.H=0", "--set", "pendulum.h=0", "--set",
                    f"pendulum.k={k}", "--set", f"map.Rm_min={rm}", "--set", f"map.Rm_max={rm}", "--set", "map.n_Rm=1",
                    "--set", f"map.Rw_min={lo}", "--set", f"map.Rw_max={hi}", "--set", "map.n_Rw=1001", "-o", h5,
                    "--force"], check=True, capture_output=True)
    if im % THIN:
        print(f"     map R_m = {rm}, k = {k}: ran (sanitizer build: reference at every 4th row)", flush=True)
        continue
    d, _ = run_critical(rm, k)  # only for the k the program used
    r = ref.critical(repr(rm), repr(d["k"]))
    los = [mpmath.mpf(v) for v in r["stable_lo"]]
    his = [mpmath.mpf(v) if v != "inf" else mpmath.inf for v in r["stable_hi"]]
    with h5py.File(h5, "r") as f:
        v = f["/pendulum/map/verdict"][0]
        rw = f["/pendulum/map/R_w"][:]
    want = np.array([1 if any(a < x < b for a, b in zip(los, his)) else -1 for x in rw])
    bad = int(np.sum((v >= 0) != (want > 0)))
    nun = int(np.sum(want < 0))
    check(f"map R_m = {rm}, k = {k}, R_w in [{lo}, {hi}]: {bad} of {len(rw)} verdicts differ from the reference "
          f"({nun} unstable)", bad == 0 and nun > 0)

print(f"{checks} checks, {fails} failed")
sys.exit(1 if fails else 0)
