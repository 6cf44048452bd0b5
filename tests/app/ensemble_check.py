#!/usr/bin/env python3
"""Checks of `autobal rotor|pendulum ensemble` archives (tests/app/ensemble.sh).

usage: ensemble_check.py MODE ARGS...
  equal A.h5 B.h5            same data: every dataset and attribute equal bit for bit (NaN == NaN), except
                             the root provenance (created, command_line, input_config, effective_config) and the
                             .../ensemble/execution group (threads, ranks, wall time)
  grid A.h5 MODEL            a complete grid: coordinates by the linspace formula, every member done,
                             counts and probability recomputed from the per-member data, consistency of
                             balanced / time_to_balance / status / residuals
  symmetric A.h5             rotor with two identical balls, axes psi_1 = psi_2: swapping the initial
                             angles relabels the balls, so the map is symmetric and the final angles swap
  member A.h5 T.h5 MODEL I J a member (grid indices I, J) agrees with the single transient archive T.h5
  random A.h5 SEED           random mode: samples recomputed with an independent splitmix64
  failures A.h5              omega grid with a step limit: low speeds succeed, high speeds fail with
                             AUTOBAL_EMAXSTEPS, failures counted
  main_motion A.h5           pendulum grid over psi x phi whose centre is the main motion (4): that member
                             starts balanced (time to balance 0, residual 0, no vibration)
  incomplete A.h5 NDONE      archive marked incomplete with exactly NDONE members done (-1: 0 < done < all)
  series A.h5 MEMBER         the kept series of MEMBER ends at its t_reached with its final residual
  drive_grid A.h5            rotor grid with a ramp drive (docs: include/autobal/ensemble.h): the drive recorded,
                             each member's ramp end t_b rebuilt from its ramp_rate / ramp_time / omega_b,
                             time_to_balance >= t_b (the dwell counts after the ramp), the probability along
                             each axis (attribute probability_balanced of its coordinate) recomputed
  drive_member A.h5 T.h5 I J member (I, J) of a 2-axis grid with a drive (stop_at_balance off) has the final state
                             of the single `rotor transient` run T.h5: residual, final ball angles, max
                             amplitude, t_reached and the accepted steps
  same_members A.h5 B.h5     two ensembles of different parameter names with the same members: equal results
"""
import math
import sys

import h5py
import numpy as np

AUTOBAL_EVENT = 2
AUTOBAL_EMAXSTEPS = -5
SKIP_ROOT = {"created", "command_line", "history", "input_config", "effective_config"}  # the configurations hold threads etc.


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def ok(msg):
    print("ok:", msg)


def ens(f):
    for m in ("rotor", "pendulum"):
        if m in f and "ensemble" in f[m]:
            return m, f[m]["ensemble"]
    fail("no ensemble group")


def same(a, b):
    a = np.asarray(a)
    b = np.asarray(b)
    if a.shape != b.shape or a.dtype.kind != b.dtype.kind:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a, b, equal_nan=True)
    if a.dtype.kind == "O":
        return all(x == y for x, y in zip(a.ravel(), b.ravel()))
    return np.array_equal(a, b)


def equal(pa, pb):
    fa, fb = h5py.File(pa, "r"), h5py.File(pb, "r")
    items = {}

    def collect(f, store):
        def visit(name, obj):
            if "/ensemble/execution" in "/" + name:
                return
            store[name] = obj

        f.visititems(visit)

    ia, ib = {}, {}
    collect(fa, ia)
    collect(fb, ib)
    if set(ia) != set(ib):
        fail(f"{pa} and {pb} hold different objects: {sorted(set(ia) ^ set(ib))[:10]}")
    n = 0
    for name in sorted(ia):
        oa, ob = ia[name], ib[name]
        if isinstance(oa, h5py.Dataset):
            if not same(oa[()], ob[()]):
                fail(f"dataset {name} differs between {pa} and {pb}")
            n += 1
        if set(oa.attrs) != set(ob.attrs):
            fail(f"attributes of {name} differ: {sorted(set(oa.attrs) ^ set(ob.attrs))}")
        for k in oa.attrs:
            # settings_hash: the hash of the configuration text (what a resume must match), which
            # differs between a run and its rerun like effective_config
            if k in ("DIMENSION_LIST", "REFERENCE_LIST", "settings_hash"):
                continue
            if not same(oa.attrs[k], ob.attrs[k]):
                fail(f"attribute {name}@{k} differs: {oa.attrs[k]!r} vs {ob.attrs[k]!r}")
    for k in set(fa.attrs) | set(fb.attrs):
        if k in SKIP_ROOT:
            continue
        if k not in fa.attrs or k not in fb.attrs or not same(fa.attrs[k], fb.attrs[k]):
            fail(f"root attribute {k} differs")
    items["datasets"] = n
    ok(f"{pa} == {pb}: {n} datasets and all attributes identical (exact, NaN == NaN)")


def check_grid(path, model):
    f = h5py.File(path, "r")
    m, g = ens(f)
    if m != model:
        fail(f"model {m}, expected {model}")
    names = [s.strip() for s in g.attrs["parameters"].split(",")]
    endpoint = int(g.attrs["endpoint"])
    shape = []
    for nm in names:
        v = g[nm][()]
        n = len(v)
        lo = float(v[0])
        d = n - 1 if endpoint else n
        # recover max from the stored lo and the spacing of the first step, then compare all points
        # with the linspace formula (exact: the same sequence of IEEE operations)
        if n > 1:
            step = v[1] - v[0]
            hi = lo + step * d
            want = np.array([lo + (hi - lo) * i / d for i in range(n)])
            if not np.allclose(v, want, rtol=0, atol=1e-12 * max(1.0, abs(hi))):
                fail(f"coordinate {nm} is not uniform: {v}")
        shape.append(n)
    shape = tuple(shape)
    done = g["done"][()]
    if done.shape != shape or not done.all():
        fail(f"done has shape {done.shape} (want {shape}) or members missing")
    status = g["status"][()]
    bal = g["balanced"][()]
    ttb = g["time_to_balance"][()]
    tr = g["t_reached"][()]
    r1 = g["residual_unbalance_final"][()]
    tol = float(g.attrs["balance_tol"])
    stop = int(g.attrs["stop_at_balance"])
    good = status >= 0
    if int(g.attrs["n_members"]) != done.size or int(g.attrs["n_done"]) != done.sum():
        fail("n_members / n_done attributes disagree with the data")
    if int(g.attrs["n_failed"]) != int((~good).sum()):
        fail("n_failed disagrees with status")
    nb = int((bal[good] == 1).sum())
    if int(g.attrs["n_balanced"]) != nb:
        fail(f"n_balanced {g.attrs['n_balanced']} != {nb}")
    p = nb / good.sum()
    if abs(g.attrs["probability_balanced"] - p) > 1e-15:
        fail(f"probability_balanced {g.attrs['probability_balanced']} != {p}")
    se = math.sqrt(p * (1 - p) / good.sum())
    if abs(g.attrs["probability_balanced_stderr"] - se) > 1e-15:
        fail("probability stderr")
    if not np.array_equal(np.isfinite(ttb), bal == 1):
        fail("time_to_balance is finite exactly for the balanced members")
    if np.any(ttb[bal == 1] > tr[bal == 1]) or np.any(ttb[bal == 1] < 0):
        fail("time_to_balance outside [0, t_reached]")
    if stop:
        if np.any(status[bal == 1] != AUTOBAL_EVENT):
            fail("balanced members with stop_at_balance must stop with AUTOBAL_EVENT")
        if np.any(r1[bal == 1] >= tol):
            fail("balanced members end below balance_tol")
    t_end = float(g.attrs["t_end"])
    if np.any(tr[(bal == 0) & good] != t_end):
        fail("members that did not balance run to t_end")
    if np.any(g["amplitude_max"][()] < g["amplitude_final"][()]):
        fail("amplitude_max >= amplitude_final")
    if nb > 0:
        if abs(g.attrs["time_to_balance_mean"] - ttb[bal == 1].mean()) > 1e-12 * t_end:
            fail("time_to_balance_mean")
        if abs(g.attrs["time_to_balance_median"] - np.median(ttb[bal == 1])) > 1e-12 * t_end:
            fail("time_to_balance_median")
    ok(f"{path}: grid {names} {shape}, {done.sum()} done, P(balance) = {p:.4f} recomputed, flags consistent")
    return g, bal


def symmetric(path):
    f = h5py.File(path, "r")
    _, g = ens(f)
    a, b = g["psi_1"][()], g["psi_2"][()]
    if not np.array_equal(a, b):
        fail("axes differ")
    bal = g["balanced"][()]
    ttb = g["time_to_balance"][()]
    ang = g["final_angle"][()]
    if not np.array_equal(bal, bal.T):
        fail(f"balanced map not symmetric:\n{bal}")
    both = bal == 1
    if not np.allclose(ttb[both], ttb.T[both], rtol=1e-6, atol=0):
        fail("time_to_balance not symmetric (rtol 1e-6)")
    d = ang[..., 0] - np.swapaxes(ang, 0, 1)[..., 1]
    d = (d + np.pi) % (2 * np.pi) - np.pi
    if np.abs(d[both]).max() > 1e-5:
        fail(f"final angles of balanced members do not swap (max diff {np.abs(d[both]).max()})")
    if both.sum() == 0 or both.sum() == both.size:
        fail("the test map should hold balanced and unbalanced members")
    ok(f"{path}: map symmetric under psi_1 <-> psi_2 ({both.sum()} of {both.size} balanced); "
       "time to balance rtol 1e-6, final angles swap to 1e-5 rad")


def member(path, tpath, model, i, j):
    f, t = h5py.File(path, "r"), h5py.File(tpath, "r")
    _, g = ens(f)
    tg = t[model]["transient"]
    got = {k: g[k][i, j] for k in ("balanced", "time_to_balance", "residual_unbalance_final", "amplitude_max")}
    res_name = "residual_unbalance_final" if model == "rotor" else "unbalance_final"
    want = {"balanced": tg.attrs["balanced"], "time_to_balance": tg.attrs["time_to_balance"],
            "residual_unbalance_final": tg.attrs[res_name], "amplitude_max": tg.attrs["amplitude_max"]}
    for k in want:
        a, b = float(got[k]), float(want[k])
        if not (a == b or (math.isnan(a) and math.isnan(b)) or abs(a - b) <= 1e-12 * abs(b)):
            fail(f"member ({i}, {j}) {k} = {a!r}, single transient {b!r}")
    ok(f"member ({i}, {j}) equals the single `{model} transient` run (balanced, time to balance, "
       "residual, max amplitude; rtol 1e-12)")


def splitmix64_u(seed, k):
    mask = (1 << 64) - 1
    z = (seed + (k + 1) * 0x9E3779B97F4A7C15) & mask
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & mask
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
    z ^= z >> 31
    return (z >> 11) * 2.0 ** -53


def random(path, seed):
    f = h5py.File(path, "r")
    _, g = ens(f)
    names = [s.strip() for s in g.attrs["parameters"].split(",")]
    n = int(g.attrs["n_members"])
    if g.attrs["seed"] != str(seed):
        fail("seed attribute")
    for j, nm in enumerate(names):
        lo, hi = g.attrs[nm + "_min"], g.attrs[nm + "_max"]
        want = np.array([lo + (hi - lo) * splitmix64_u(seed, m * len(names) + j) for m in range(n)])
        got = g[nm][()]
        if not np.array_equal(got, want):
            fail(f"{nm} samples differ from splitmix64: {got} vs {want}")
        if np.any(got < lo) or np.any(got >= hi) or len(set(got)) != n:
            fail(f"{nm} samples outside [{lo}, {hi}) or repeated")
    # known first output of splitmix64 with seed 0 (the reference implementation's value)
    if splitmix64_u(0, 0) != (0xE220A8397B1DCDAF >> 11) * 2.0 ** -53:
        fail("the checker's splitmix64 is wrong")
    ok(f"{path}: {n} random members x {names}: samples equal an independent splitmix64 (seed {seed})")


def failures(path):
    f = h5py.File(path, "r")
    _, g = ens(f)
    om = g["omega"][()]
    st = g["status"][()]
    failed = st < 0
    if not failed.any() or failed.all():
        fail(f"want some failed and some good members, status {st}")
    if np.any(st[failed] != AUTOBAL_EMAXSTEPS):
        fail(f"failures should be AUTOBAL_EMAXSTEPS: {st}")
    if om[failed].min() <= om[~failed].max():
        fail("steps grow with omega: failures must be the fastest members")
    if int(g.attrs["n_failed"]) != failed.sum() or not g["done"][()].all():
        fail("failed members are done and counted")
    if np.any(g["steps"][()][failed] != float(g.attrs["max_steps"])):
        fail("failed members stopped at max_steps")
    if f.attrs["status"] != "complete":
        fail("failures are results: the archive is complete")
    ok(f"{path}: {failed.sum()} of {len(st)} members failed with AUTOBAL_EMAXSTEPS (the fastest), recorded per member")


def main_motion(path):
    f = h5py.File(path, "r")
    _, g = ens(f)
    psi0 = f["pendulum"].attrs["psi0"]
    a, b = g["psi"][()], g["phi"][()]
    i, j = len(a) // 2, len(b) // 2
    if abs(a[i] - psi0) > 1e-14 or abs(b[j] - psi0) > 1e-14:
        fail(f"the grid centre ({a[i]}, {b[j]}) is not the main motion psi0 = {psi0}")
    if g["balanced"][i, j] != 1 or g["time_to_balance"][i, j] != 0.0:
        fail("the main motion is balanced from tau = 0")
    if g["residual_unbalance_initial"][i, j] > 1e-15 or g["amplitude_max"][i, j] > 1e-12:
        fail("the main motion has no residual unbalance and no vibration")
    ok(f"{path}: the member at psi = phi = psi0 (main motion (4)) is balanced at tau = 0 with residual "
       f"{g['residual_unbalance_initial'][i, j]:.1e}")


def incomplete(path, ndone):
    f = h5py.File(path, "r")
    _, g = ens(f)
    reason = f.attrs["status_reason"]
    if f.attrs["status"] != "incomplete" or not ("resume" in reason or "interrupted by SIG" in reason):
        fail(f"archive should be incomplete with a resume hint or the signal: {reason!r}")
    d = g["done"][()]
    if ndone < 0:  # any proper part
        ndone = int(d.sum())
        if not 0 < ndone < d.size:
            fail(f"{ndone} of {d.size} members done: want a proper part")
    if d.sum() != ndone or int(g.attrs["n_done"]) != ndone:
        fail(f"{d.sum()} members done, want {ndone}")
    if np.any(np.isfinite(g["t_reached"][()][d == 0])):
        fail("members not done have no results")
    ok(f"{path}: incomplete archive with {ndone} members done, the others NaN")


def series(path, m):
    f = h5py.File(path, "r")
    model, g = ens(f)
    s = g["series"][f"member_{m}"]
    shape = g["done"].shape
    idx = np.unravel_index(m, shape) if len(shape) > 1 else (m,)
    tr = g["t_reached"][idx]
    tname = "time" if model == "rotor" else "tau"
    t = s[tname][()]
    if t[0] != 0.0 or not (t[-1] <= tr) or np.any(np.diff(t) <= 0):
        fail(f"series time from 0 increasing up to t_reached {tr}: {t[:3]} ... {t[-1]}")
    amp = s["amp_G"][()] if model == "rotor" else s["amplitude"][()]
    amax, afin = g["amplitude_max"][idx], g["amplitude_final"][idx]
    # amplitude_max = max(sampled amplitudes, final amplitude): the series maximum equals it unless the
    # largest value is the final state of a run stopped between samples
    if amp.max() > amax or (amp.max() != amax and amax != afin):
        fail(f"series max amplitude {amp.max()} vs amplitude_max {amax} (final {afin})")
    ok(f"{path}: series of member {m}: {len(t)} samples from 0 to {t[-1]:.6g} (t_reached {tr:.6g}), "
       "its largest amplitude is amplitude_max")


def member_t_b(g, values):
    """The member's ramp end, by the definition in include/autobal/ensemble.h."""
    wa, wb, ta, tb = (float(g.attrs[k]) for k in ("drive_omega_a", "drive_omega_b", "drive_t_a", "drive_t_b"))
    wb = values.get("omega_b", wb)
    if "ramp_time" in values:
        tb = ta + values["ramp_time"]
    if "ramp_rate" in values:
        tb = ta + abs(wb - wa) / values["ramp_rate"]
    return tb


def drive_grid(path):
    g, bal = check_grid(path, "rotor")
    if g.attrs["drive_mode"] != "ramp":
        fail("the ensemble group does not record the ramp drive")
    for k, u in (("drive_omega_a", "rad/s"), ("drive_omega_b", "rad/s"), ("drive_t_a", "s"), ("drive_t_b", "s")):
        if g.attrs[k + "_units"] != u:
            fail(f"{k}_units = {g.attrs[k + '_units']!r}, want {u}")
    names = [s.strip() for s in g.attrs["parameters"].split(",")]
    units = {"ramp_rate": "rad/s^2", "ramp_time": "s", "omega_b": "rad/s"}
    for nm in names:
        if nm in units and g[nm].attrs["units"] != units[nm]:
            fail(f"{nm} has units {g[nm].attrs['units']!r}, want {units[nm]}")
    axes = [g[nm][()] for nm in names]
    ttb = g["time_to_balance"][()]
    status = g["status"][()]
    n_checked = 0
    for idx in np.ndindex(bal.shape):
        values = {nm: float(axes[j][idx[j]]) for j, nm in enumerate(names)}
        tb = member_t_b(g, values)
        if bal[idx] == 1:
            if not ttb[idx] >= tb:
                fail(f"member {idx}: time_to_balance {ttb[idx]!r} s before the end of its ramp t_b = {tb!r} s")
            n_checked += 1
    # the probability along each axis, over the others
    good = status >= 0
    for j, nm in enumerate(names):
        other = tuple(k for k in range(len(names)) if k != j)
        want = (bal == 1).sum(axis=other) / good.sum(axis=other)
        got = np.asarray(g[nm].attrs["probability_balanced"])
        if got.shape != want.shape or np.max(np.abs(got - want)) > 1e-15:
            fail(f"{nm}@probability_balanced = {got}, recomputed {want}")
        if g[nm].attrs["probability_balanced_units"] != "1":
            fail("probability units")
    ok(f"{path}: ramp drive recorded; {n_checked} balanced members all balanced after their ramp end t_b; "
       f"probability along {names} recomputed")


def drive_member(path, tpath, i, j):
    f, t = h5py.File(path, "r"), h5py.File(tpath, "r")
    _, g = ens(f)
    tg = t["rotor"]["transient"]
    if int(g.attrs["stop_at_balance"]) != 0:
        fail("drive_member compares full runs: stop_at_balance must be off")
    nb = g["final_angle"].shape[-1]
    last = -1
    if float(tg["time"][last]) != float(g["t_reached"][i, j]):
        fail(f"t_reached {g['t_reached'][i, j]!r} vs the transient's last sample {tg['time'][last]!r}")
    pairs = [("residual_unbalance_final", float(tg.attrs["residual_unbalance_final"])),
             ("amplitude_max", float(tg.attrs["amplitude_max"])),
             ("steps", float(tg["solver"].attrs["steps"]))]
    # rhs_evaluations are not compared: locating the crossings of balance_tol costs evaluations outside
    # the steps, and the ensemble's dwell does not look before the end of the ramp (settle_time)
    for k, want in pairs:
        got = float(g[k][i, j])
        if not (got == want or abs(got - want) <= 1e-12 * abs(want)):
            fail(f"member ({i}, {j}) {k} = {got!r}, single transient {want!r}")
    for b in range(nb):
        want = float(tg[f"p1_b{b + 1}_psi_w"][last])
        got = float(g["final_angle"][i, j, b])
        d = math.remainder(got - want, 2 * math.pi)
        if abs(d) > 1e-9:
            fail(f"member ({i}, {j}) ball {b + 1} final angle {got!r} vs the transient's {want!r}")
    ok(f"member ({i}, {j}) with a ramp drive has the final state of the single `rotor transient` run "
       f"(residual, {nb} ball angles to 1e-9 rad, max amplitude, t_reached, accepted steps)")


def same_members(pa, pb):
    _, ga = ens(h5py.File(pa, "r"))
    _, gb = ens(h5py.File(pb, "r"))
    for k in ("status", "balanced", "time_to_balance", "residual_unbalance_final", "amplitude_max", "t_reached",
              "steps", "rhs_evaluations", "final_angle"):
        a, b = np.asarray(ga[k][()]), np.asarray(gb[k][()])
        if a.size != b.size or not np.array_equal(a.ravel(), b.ravel(), equal_nan=True):
            fail(f"{k} differs between {pa} and {pb}: {a.ravel()} vs {b.ravel()}")
    ok(f"{pa} and {pb}: the same members give the same results (exact)")


if __name__ == "__main__":
    mode, args = sys.argv[1], sys.argv[2:]
    if mode == "equal":
        for other in args[1:]:
            equal(args[0], other)
    elif mode == "grid":
        check_grid(args[0], args[1])
    elif mode == "symmetric":
        symmetric(args[0])
    elif mode == "member":
        member(args[0], args[1], args[2], int(args[3]), int(args[4]))
    elif mode == "random":
        random(args[0], int(args[1]))
    elif mode == "failures":
        failures(args[0])
    elif mode == "main_motion":
        main_motion(args[0])
    elif mode == "incomplete":
        incomplete(args[0], int(args[1]))
    elif mode == "series":
        series(args[0], int(args[1]))
    elif mode == "drive_grid":
        drive_grid(args[0])
    elif mode == "drive_member":
        drive_member(args[0], args[1], int(args[2]), int(args[3]))
    elif mode == "same_members":
        same_members(args[0], args[1])
    else:
        fail("unknown mode " + mode)
