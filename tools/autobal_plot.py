#!/usr/bin/python3
"""autobal_plot.py: pictures of an autobal HDF5 archive, drawn with matplotlib.

Reads ONLY the archive (h5py + numpy); every number, label unit and title comes from it.
Use Debian's interpreter, which has h5py, numpy and matplotlib:

    /usr/bin/python3 tools/autobal_plot.py run.h5 -o pictures/      # or: autobal plot run.h5 -o pictures/

For each group it knows it writes DIR/<stem>_<kind>.png (stem = archive name without .h5):

    /pendulum/critical/curves   <stem>_critical_speeds.png  R_wj(R_m) for k = 0 and k = 1 (the
                                paper's figure 2) with regions A and B shaded;
                                beside it the stable R_w intervals of /pendulum/critical at the run's R_m
    /pendulum/map               <stem>_stability_map.png    verdict over its two axes (default (R_m, R_w)) [+ max_real]
    /pendulum/sweep             <stem>_sweep.png            verdict along one parameter, critical values marked
    /pendulum/roots             <stem>_roots.png            roots of (6) and eigenvalues of (5)
    /pendulum/transient         <stem>_transient.png        shaft amplitude and residual unbalance
                                (log scales), pendulum angles; time to balance marked
    /rotor/transient            <stem>_transient.png        displacement and residual unbalance (log
                                scales), ball angles relative to the rotor; time to balance marked
    /rotor/runup                <stem>_runup.png            run-up (a transient with a speed profile):
                                amplitude envelope and |s|/(m0 r0) over the spin speed Omega with a
                                rev/min axis, the resonance speeds (Campbell crossings) marked,
                                captures shaded
    /rotor/stability            <stem>_stability.png        characteristic roots of the balanced motion
                                and its stable speed intervals (autobal rotor stability)
    /rotor/sweep                <stem>_stability_sweep.png  margin along the swept parameter, stable
                                intervals and critical values (autobal rotor sweep)
    /rotor/map                  <stem>_stability_map.png    verdict and margin over two parameters
    /rotor/campbell             <stem>_campbell.png         Campbell diagram (natural frequencies vs
                                spin speed, each mode followed through crossings by
                                track_modes, whirl, 1X and 2X, critical speeds, rev/min and Hz
                                axes) and unbalance response
    /rotor/ensemble,            <stem>_ensemble.png         basin map (outcome, with the attractor class of the
                                                            members that did not balance, over the grid or the
    /pendulum/ensemble                                      random samples), time to balance over it,
                                P(balance) along the first parameter, time-to-balance distribution
    /rotor/ensemble/residual_   <stem>_unbalance.png        (with ensemble.write_unbalance = true) the
      unbalance_abs_final                                   distribution of the residual unbalance at the
                                end: empirical CDF in g mm (log axis) with the ISO 21940-11 grade
                                lines, histogram of the grade with the target and P(G <= target)
                                with its Wilson interval; --compare B.h5 draws a second ensemble's
                                distribution beside it (e.g. the same ensemble without friction)

Stable intervals are drawn from the archive's stable_lo/stable_hi (not from the sampled curves); one
narrower than NARROW of the axis is drawn that wide, outlined and labelled with its ends.  Speeds
in rad/s get a secondary axis in rev/min.

The functions below can be imported (plot_archive(path, outdir) returns the written files).
Exit codes: 0 done, 2 bad command line, 3 nothing this script can draw in the archive,
4 the file is missing, not HDF5, damaged, or not an autobal archive.
"""
import argparse
import os
import sys
import textwrap
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

try:
    import h5py
except ImportError:  # pragma: no cover
    sys.stderr.write("autobal_plot.py: needs h5py: use /usr/bin/python3 (Debian's python3-h5py)\n")
    sys.exit(7)

DPI = 110


# ---- small helpers -------------------------------------------------------------------
def s(v):
    """An attribute as str (h5py returns str for variable-length UTF-8, bytes otherwise)."""
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    return str(v)


def units(obj):
    """The units attribute of a dataset, '?' if missing."""
    return s(obj.attrs.get("units", "?"))


def ubr(u):
    """Units for an axis label: [-] for dimensionless."""
    return "[–]" if u == "1" else "[%s]" % u


def param(g, name, default=None):
    """Parameter attribute `name` of group g as float (or default)."""
    if name in g.attrs:
        try:
            return float(np.asarray(g.attrs[name]).ravel()[0])
        except (TypeError, ValueError):
            return default
    return default


def punit(g, name):
    return s(g.attrs.get(name + "_units", "1"))


def fmt(v, digits=4):
    return ("%%.%dg" % digits) % v


def status_note(h):
    st = s(h.attrs.get("status", "?"))
    return "" if st == "complete" else "  [run %s]" % st


def save(fig, outdir, stem, kind, written):
    path = os.path.join(outdir, "%s_%s.png" % (stem, kind))
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    written.append(path)


def mark_time(axes, t, label, color="k"):
    """A vertical line at t on every axis; labelled on the first."""
    if t is None or not np.isfinite(t):
        return
    for i, ax in enumerate(axes):
        ax.axvline(t, color=color, ls="--", lw=1.0, label=label if i == 0 else None)


def positive(a):
    """Values for a log axis: zeros and negatives (an exactly balanced or resting start) become NaN
    (a gap in the line) instead of a 1e-300 spike that stretches the axis."""
    a = np.array(a, dtype=float)
    a[~(a > 0)] = np.nan
    return a


def break_wraps(t, a):
    """NaN where a wrapped angle jumps by more than pi, so that lines do not cross the plot."""
    a = np.array(a, dtype=float)
    t = np.array(t, dtype=float)
    jump = np.abs(np.diff(a)) > np.pi
    if not jump.any():
        return t, a
    idx = np.nonzero(jump)[0] + 1
    return np.insert(t, idx, np.nan), np.insert(a, idx, np.nan)


def pendulum_params_text(h, skip=()):
    p = h["pendulum"]
    parts = []
    for name, sym in (("R_w", "R_w"), ("R_m", "R_m"), ("H", "H"), ("h", "h"), ("k", "k")):
        if name in skip:
            continue
        v = param(p, name)
        if v is not None:
            parts.append("%s = %s" % (sym, fmt(v, 3)))
    return ", ".join(parts)


# ---- pendulum ---------------------------------------------------------------------------
def plot_pendulum_critical(h, outdir, stem, written):
    """Figure 2: critical speeds R_wj(R_m) for k = 0 and k = 1, regions A and B shaded."""
    g = h["pendulum/critical/curves"]
    rm = g["R_m"][:]
    c0 = g["R_w_k0"][:]
    c1 = g["R_w_k1"][:]
    u = units(g["R_w_k0"])
    pc = h["pendulum/critical"] if "pendulum/critical" in h else None
    cases = pendulum_interval_cases(h, pc)
    if cases:
        fig, (ax, axs) = plt.subplots(1, 2, figsize=(13, 7.8), constrained_layout=True, sharey=True,
                                      gridspec_kw={"width_ratios": [3, 1.25]})
    else:
        fig, ax = plt.subplots(figsize=(9, 7.5), constrained_layout=True)
    finite1 = c1[np.isfinite(c1)]
    top = max(4.0, 1.3 * float(finite1.max())) if finite1.size else 4.0

    w1k1 = c1[:, 0]
    w2k0, w3k0 = c0[:, 1], c0[:, 2]
    # region A: above R_w3(R_m, 0) (and, for R_m >= 0.25 where that branch is gone, above
    # R_w1(R_m, 1)); region B: R_w1(R_m, 1) < R_w < R_w2(R_m, 0) where that is non-empty
    lowA = np.where(np.isfinite(w3k0), np.fmax(w3k0, w1k1), w1k1)
    okA = np.isfinite(lowA) & (lowA < top)
    ax.fill_between(rm, np.where(okA, lowA, np.nan), top, where=okA, color="tab:green", alpha=0.22, lw=0,
                    label="region A: R_w > R_w3(R_m, 0); for R_m ≥ 0.25: R_w > R_w1(R_m, 1)")
    okB = np.isfinite(w1k1) & np.isfinite(w2k0) & (w2k0 > w1k1)
    ax.fill_between(rm, w1k1, np.fmin(w2k0, top), where=okB, color="tab:orange", alpha=0.30, lw=0,
                    label="region B: R_w1(R_m, 1) < R_w < R_w2(R_m, 0)")

    for j in range(c0.shape[1]):
        ax.plot(rm, c0[:, j], color="tab:blue", lw=1.8, label="k = 0: R_w1, R_w2, R_w3" if j == 0 else None)
    # names of the k = 0 branches, written beside the curves
    for j, target in ((0, None), (1, 0.45 * top), (2, 0.8 * top)):
        if j >= c0.shape[1]:
            break
        col = c0[:, j]
        if target is None:
            i = int(0.75 * (len(rm) - 1))
        else:
            hit = np.nonzero(np.isfinite(col) & (col >= target))[0]
            if not hit.size:
                continue
            i = int(hit[0])
        if np.isfinite(col[i]):
            ax.annotate("R_w%d(R_m, 0)" % (j + 1), (rm[i], col[i]), textcoords="offset points",
                        xytext=(6, 4 if target is None else -4), color="tab:blue", fontsize=9)
    for j in range(c1.shape[1]):
        if np.isfinite(c1[:, j]).any():
            ax.plot(rm, c1[:, j], color="tab:red", lw=1.8, ls="--",
                    label="k = 1: R_w1 (16)" if j == 0 else "k = 1: critical speed %d" % (j + 1))
    if "eq18_R_w23_k1" in g:
        e18 = g["eq18_R_w23_k1"][:]
        if np.isfinite(e18).any():
            ax.plot(rm, e18, color="tab:red", lw=1.2, ls=":",
                    label="k = 1: R_w2 = R_w3 (18), touch without a change of stability")
    if "pendulum/critical" in h:
        pc = h["pendulum/critical"]
        r1, w1 = param(pc, "R_m1"), param(pc, "R_w_at_R_m1")
        if r1 is not None and w1 is not None and np.isfinite(r1):
            ax.plot([r1], [w1], "kD", ms=5, label="R_m^(1) = %s: (16) and (18) touch" % fmt(r1, 5))
        rm_run = param(h["pendulum"], "R_m")
        for key, col, mk, lab in (("undamped_k0_R_w", "tab:blue", "o", "k = 0"),
                                  ("undamped_k1_R_w", "tab:red", "s", "k = 1")):
            if key in pc and rm_run is not None and pc[key].size:
                v = pc[key][:]
                v = v[np.isfinite(v) & (v < top)]
                ax.plot(np.full(v.shape, rm_run), v, mk, color=col, mfc="none", ms=7,
                        label="critical speeds at R_m = %s, %s (this run)" % (fmt(rm_run, 3), lab))
    # the letters A and B in the middle of their regions
    if okA.any():
        i = int(np.nonzero(okA)[0][max(0, int(0.04 * okA.sum()))])
        ax.text(rm[i] + 0.01 * (rm.max() - rm.min()), 0.5 * (lowA[i] + top) + 0.15 * (top - lowA[i]), "A",
                fontsize=18, fontweight="bold", color="darkgreen")
        iA2 = np.nonzero(okA & (rm >= 0.25))[0]
        if iA2.size:
            i = int(iA2[int(0.5 * (iA2.size - 1))])
            ax.text(rm[i], 0.5 * (lowA[i] + top), "A", fontsize=18, fontweight="bold", color="darkgreen")
    if okB.any():
        iB = np.nonzero(okB)[0]
        i = int(iB[int(0.6 * (iB.size - 1))])
        ax.text(rm[i], 0.5 * (w1k1[i] + min(w2k0[i], top)), "B", fontsize=18, fontweight="bold",
                color="saddlebrown", ha="center", va="center")
    ax.set_xlim(float(rm.min()), float(rm.max()))
    ax.set_ylim(0.0, top)
    ax.set_xlabel("mass ratio R_m = m/(M + 2m) %s" % ubr(units(g["R_m"])))
    ax.set_ylabel("rotor speed R_w = ω/ω0 %s" % ubr(u))
    ax.set_title("Two-pendulum autobalancer, undamped: critical speeds and the regions A, B\nstable for every unbalance (figure 2)%s" % status_note(h))
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.09), ncol=2, fontsize=8, frameon=False)
    if cases:
        pendulum_interval_strips(h, axs, cases, top)
    save(fig, outdir, stem, "critical_speeds", written)


def pendulum_interval_cases(h, pc):
    """The stable-interval sets of /pendulum/critical at this run's R_m: (prefix, label) pairs."""
    if pc is None:
        return []
    p = h["pendulum"]
    kk = param(p, "k", np.nan)
    out = []
    for pre, lab in (("undamped_k0", "k = 0\nundamped"), ("undamped", "k = %s\nundamped" % fmt(kk, 3)),
                     ("undamped_k1", "k = 1\nundamped"),
                     ("damped", "k = %s, damped\nH = %s\nh = %s" % (fmt(kk, 3), fmt(param(p, "H", np.nan), 3),
                                                           fmt(param(p, "h", np.nan), 3)))):
        if pre + "_stable_lo" in pc and pre + "_stable_hi" in pc:
            out.append((pre, lab))
    return out


def pendulum_interval_strips(h, ax, cases, top):
    """At this run's R_m: one column per case, unstable background, the archive's stable R_w intervals
    (narrow ones widened to NARROW of the axis and outlined), critical speeds as numbered ticks; a
    secondary axis in rev/min when the archive has the physical form (omega0 = omega / R_w)."""
    pc = h["pendulum/critical"]
    p = h["pendulum"]
    narrow, crit = [], []
    for i, (pre, lab) in enumerate(cases):
        lo, hi = pc[pre + "_stable_lo"][:], pc[pre + "_stable_hi"][:]
        ax.bar([i], [top], bottom=[0.0], width=0.6, color=VERDICT_COLORS[-1], label="unstable" if i == 0 else None)
        for j, (a, b) in enumerate(zip(lo, hi)):
            b = min(b, top) if np.isfinite(b) else top
            if b - a < NARROW * top:
                c = 0.5 * (a + b)
                ax.bar([i], [NARROW * top], bottom=[c - 0.5 * NARROW * top], width=0.6, color=VERDICT_COLORS[1],
                       edgecolor="darkgreen", lw=0.8)
                narrow.append((i + 0.3, c, "%s–%s" % (fmt(a, 4), fmt(b, 4))))
            else:
                ax.bar([i], [b - a], bottom=[a], width=0.6, color=VERDICT_COLORS[1])
        if pre + "_R_w" in pc:
            cv = pc[pre + "_R_w"][:]
            cv = cv[np.isfinite(cv) & (cv <= top)]
            ax.plot(np.full(cv.shape, i), cv, "_", color="k", ms=26, mew=1.6)
            crit.extend((i - 0.3, v, fmt(v, 4)) for v in cv)
    ax.set_ylim(0.0, top)
    rw = param(p, "R_w")
    if rw is not None and np.isfinite(rw):
        ax.axhline(rw, color="tab:purple", lw=1.2, ls="--", label="R_w of this run = %s" % fmt(rw, 4))
    ax.set_xticks(range(len(cases)))
    ax.set_xticklabels([lab for _, lab in cases], fontsize=7.5)
    ax.set_xlim(-0.8, len(cases) - 0.2)
    for i in range(len(cases)):  # labels of one column pushed apart
        for lst, dx, ha, col in ((crit, -3, "right", "k"), (narrow, 3, "left", "darkgreen")):
            sel = [e for e in lst if abs(e[0] - i) < 0.5]
            if sel:
                spread_labels(ax, np.array([e[0] for e in sel]), np.array([e[1] for e in sel]),
                              [e[2] for e in sel], color=col, dx=abs(dx), ha=ha, fontsize=7, min_gap=9.0)
    handles, _ = ax.get_legend_handles_labels()
    from matplotlib.lines import Line2D
    handles += [Patch(facecolor=VERDICT_COLORS[1], label="stable R_w (archive intervals; narrow ones widened)"),
                Line2D([], [], color="k", lw=1.6, label="critical speeds")]
    ax.set_title("stable speeds at R_m = %s (this run)" % fmt(param(p, "R_m", np.nan), 3), fontsize=10)
    ax.legend(handles=handles, fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.13), frameon=False)
    if "pendulum/physical" in h and rw:
        om = param(h["pendulum/physical"], "omega")
        if om is not None and punit(h["pendulum/physical"], "omega") == "rad/s" and rw > 0:
            w0 = om / rw
            sec = ax.secondary_yaxis("right", functions=(lambda r: r * w0 * RPM_PER_RAD_S,
                                                         lambda n: n / (w0 * RPM_PER_RAD_S)))
            sec.set_ylabel("rotor speed ω = R_w ω0 [rev/min] (ω0 = %s rad/s)" % fmt(w0, 4), fontsize=9)


VERDICT_COLORS = {-3: "#9ec5e8", -2: "#bbbbbb", -1: "#f4a6a6", 0: "#ffe680", 1: "#8fd18f"}
VERDICT_NAMES = {-3: "undecided (Hill budget)", -2: "no balanced motion", -1: "unstable", 0: "marginal",
                 1: "stable"}


def cells(a):
    """Cell edges around grid values a (what shading="nearest" does), also for a single value, where
    matplotlib draws a cell of zero width: a map with one row or column would come out blank."""
    a = np.asarray(a, dtype=float)
    if a.size == 1:
        d = 0.05 * abs(a[0]) if a[0] != 0 else 0.5
        return np.array([a[0] - d, a[0] + d])
    mid = 0.5 * (a[1:] + a[:-1])
    return np.concatenate([[a[0] - (mid[0] - a[0])], mid, [a[-1] + (a[-1] - mid[-1])]])


def mesh(ax, x, y, z, **kw):
    """pcolormesh of z[x, y] with the cells of cells(): correct for one row or column too."""
    return ax.pcolormesh(cells(x), cells(y), np.asarray(z).T, shading="flat", **kw)


def verdict_image(ax, x, y, v):
    """Draw an int verdict grid v[x, y] (values -3..1) with a fixed colour per verdict."""
    codes = [-3, -2, -1, 0, 1]
    cmap = ListedColormap([VERDICT_COLORS[c] for c in codes])
    norm = BoundaryNorm([-3.5, -2.5, -1.5, -0.5, 0.5, 1.5], cmap.N)
    mesh(ax, x, y, v, cmap=cmap, norm=norm)
    present = sorted(set(np.unique(v).astype(int).tolist()) & set(codes))
    return [Patch(facecolor=VERDICT_COLORS[c], edgecolor="k", lw=0.5, label=VERDICT_NAMES[c]) for c in present]


AXIS_LABELS = {"R_m": "mass ratio R_m = m/(M + 2m)", "R_w": "rotor speed R_w = ω/ω0",
               "H": "external damping H", "h": "pendulum damping h", "k": "unbalance k = sin²(2ψ0)",
               "psi0": "main-motion angle ψ0", "H_over_h": "damping ratio H/h",
               # physical keys (pendulum.M ... pendulum.omega): each point converted to the dimensionless set
               "M": "rotor mass M", "e": "rotor eccentricity e", "m": "pendulum mass m", "l": "pendulum length l",
               "c": "support stiffness c", "H1": "pendulum damping H1", "H2": "support damping H2",
               "omega": "rotor speed ω"}
# the dimensionless parameters an axis moves (docs/pendulum.md: R_w on omega, c, M, m; R_m on M, m;
# H on H2, c, M, m; h on H1, m, l, c, M; k on M, e, m, l): the archive's value of a moved parameter
# (k_values, the /pendulum attributes) is the configuration's own, not that of the map's points
MOVES = {"R_w": {"R_w"}, "R_m": {"R_m"}, "H": {"H"}, "h": {"h"}, "H_over_h": {"H", "h"}, "k": {"k"},
         "psi0": {"k"}, "omega": {"R_w"}, "c": {"R_w", "H", "h"}, "M": {"R_w", "R_m", "H", "h", "k"},
         "m": {"R_w", "R_m", "H", "h", "k"}, "l": {"h", "k"}, "e": {"k"}, "H1": {"h"}, "H2": {"H"}}


def plot_pendulum_map(h, outdir, stem, written):
    g = h["pendulum/map"]
    # the axes (archives before 0.3: R_m and R_w)
    d1, d2 = s(g.attrs.get("axis1_dim", "R_m")), s(g.attrs.get("axis2_dim", "R_w"))
    rm, rw = g[d1][:], g[d2][:]
    v = g["verdict"][:]
    has_mr = "max_real" in g
    fig, axes = plt.subplots(1, 2 if has_mr else 1, figsize=(13 if has_mr else 8, 6), constrained_layout=True,
                             squeeze=False)
    ax = axes[0, 0]
    handles = verdict_image(ax, rm, rw, v)
    every = int(param(g, "every_unbalance", 0) or 0)
    ks = np.atleast_1d(g.attrs.get("k_values", []))
    p = h["pendulum"]
    moved = (MOVES.get(d1, set()) | MOVES.get(d2, set())) & {"H", "h"}
    damp = ", ".join("%s = %s" % (n, fmt(param(p, n, np.nan), 3)) for n in ("H", "h") if n not in moved)
    if moved:  # a damping that varies over the map is not the configuration's
        damp = (damp + "; " if damp else "") + "%s var%s over the map" % (" and ".join(sorted(moved)),
                                                                         "y" if len(moved) > 1 else "ies")
    if every:
        what = "stable for every unbalance k in %d values from %s to %s" % (len(ks), fmt(ks.min(), 3),
                                                                              fmt(ks.max(), 3))
    elif "k" in MOVES.get(d1, set()) | MOVES.get(d2, set()):
        what = "the unbalance k = sin²(2ψ0) varies over the map"
    else:
        what = "k = %s" % ", ".join(fmt(k, 3) for k in ks)
    ax.set_title("Stability of the main motion (4): %s\n%s%s" % (what, damp, status_note(h)), fontsize=11)
    ax.set_xlabel("%s %s" % (AXIS_LABELS.get(d1, d1), ubr(units(g[d1]))))
    ax.set_ylabel("%s %s" % (AXIS_LABELS.get(d2, d2), ubr(units(g[d2]))))
    if s(g.attrs.get("axis1_scale", "linear")) == "log":
        ax.set_xscale("log")
    if s(g.attrs.get("axis2_scale", "linear")) == "log":
        ax.set_yscale("log")
    if "note" in g.attrs:  # the undamped map's note on the small-damping limit
        fig.supxlabel(textwrap.fill("Note: " + s(g.attrs["note"]), 170), fontsize=6.5, x=0.01, ha="left")
    # the design point of the configuration (archives of earlier versions do not record it)
    if "design_" + d1 in g.attrs and "design_" + d2 in g.attrs:
        dm, dw = float(g.attrs["design_" + d1]), float(g.attrs["design_" + d2])
        if rm.min() <= dm <= rm.max() and rw.min() <= dw <= rw.max():
            for a_ in axes[0]:
                a_.plot([dm], [dw], marker="*", ms=16, mfc="gold", mec="k", ls="none", zorder=5)
            handles = handles + [Line2D([], [], marker="*", ms=12, mfc="gold", mec="k", ls="none",
                                        label="design point (%s %s, %s %s)" % (d1, fmt(dm, 3), d2, fmt(dw, 3)))]
    # physical speed on a secondary axis when the configuration gave the physical set
    if "omega" in g and d2 == "R_w" and len(rw) > 1 and rw[-1] != rw[0]:
        w0 = float(g["omega"][-1] / rw[-1]) if rw[-1] else float(g["omega"][0] / rw[0])
        if np.isfinite(w0) and w0 > 0:
            sec = ax.secondary_yaxis("right", functions=(lambda r: r * w0 * RPM_PER_RAD_S,
                                                         lambda n: n / (w0 * RPM_PER_RAD_S)))
            sec.set_ylabel("rotor speed [rev/min] (ω0 = %s rad/s)" % fmt(w0, 4), fontsize=9)
    # a physical speed axis (pendulum.omega, rad/s) also in rev/min
    for dim, make in ((d1, ax.secondary_xaxis), (d2, ax.secondary_yaxis)):
        if dim == "omega" and units(g[dim]) == "rad/s":
            sec = make("top" if make == ax.secondary_xaxis else "right",
                       functions=(lambda w: w * RPM_PER_RAD_S, lambda n: n / RPM_PER_RAD_S))
            (sec.set_xlabel if make == ax.secondary_xaxis else sec.set_ylabel)("rotor speed [rev/min]", fontsize=9)
    ax.legend(handles=handles, loc="upper right", fontsize=9, framealpha=0.9)
    if has_mr:
        ax2 = axes[0, 1]
        mr = g["max_real"][:]
        lim = np.nanmax(np.abs(mr)) if np.isfinite(mr).any() else 1.0
        im = mesh(ax2, rm, rw, mr, cmap="RdBu_r", vmin=-lim, vmax=lim)
        if len(rm) > 1 and len(rw) > 1:
            ax2.contour(rm, rw, mr.T, levels=[0.0], colors="k", linewidths=1.0)
        fig.colorbar(im, ax=ax2, label="largest real part of the roots of (6) %s" % ubr(units(g["max_real"])))
        ax2.set_title("stability margin (black line: max Re λ = 0)", fontsize=11)
        ax2.set_xlabel(ax.get_xlabel())
        ax2.set_ylabel(ax.get_ylabel())
    save(fig, outdir, stem, "stability_map", written)


def plot_pendulum_sweep(h, outdir, stem, written):
    g = h["pendulum/sweep"]
    d = s(g.attrs.get("axis1_dim", "R_w"))
    x, v = g[d][:], g["verdict"][:]
    fig, ax = plt.subplots(figsize=(9, 3.6), constrained_layout=True)
    ax.step(x, v, where="mid", color="k", lw=1.2)
    for c in ("critical",):
        if c in g:
            for xc in g[c][:]:
                ax.axvline(xc, color="tab:red", lw=0.8, ls="--")
    ax.set_yticks([-1, 0, 1])
    ax.set_yticklabels(["unstable", "marginal", "stable"])
    if s(g.attrs.get("axis1_scale", "linear")) == "log":
        ax.set_xscale("log")
    ax.set_xlabel("%s %s" % (AXIS_LABELS.get(d, d), ubr(units(g[d]))))
    if d == "omega" and units(g[d]) == "rad/s":
        sec = ax.secondary_xaxis("top", functions=(lambda w: w * RPM_PER_RAD_S, lambda n: n / RPM_PER_RAD_S))
        sec.set_xlabel("rotor speed [rev/min]", fontsize=9)
    every = int(param(g, "every_unbalance", 0) or 0)
    ax.set_title("Stability of the main motion (4) along %s%s (red: critical values)\n%s%s"
                 % (d, " for every unbalance" if every else "",
                    pendulum_params_text(h, skip=MOVES.get(d, {d}) | ({"k"} if every else set())), status_note(h)),
                 fontsize=10)
    if "note" in g.attrs:
        fig.supxlabel(textwrap.fill("Note: " + s(g.attrs["note"]), 150), fontsize=6, x=0.01, ha="left")
    save(fig, outdir, stem, "sweep", written)


def plot_pendulum_roots(h, outdir, stem, written):
    g = h["pendulum/roots"]
    fig, ax = plt.subplots(figsize=(7, 6), constrained_layout=True)
    ax.plot(g["root_real"][:], g["root_imag"][:], "o", ms=9, mfc="none", label="roots of (6)")
    ax.plot(g["eig_real"][:], g["eig_imag"][:], "x", ms=7, label="eigenvalues of the matrix of (5)")
    ax.axvline(0.0, color="k", lw=0.8)
    ax.axhline(0.0, color="k", lw=0.5, alpha=0.5)
    ax.set_xlabel("Re λ %s (per unit of τ = ω0 t)" % ubr(units(g["root_real"])))
    ax.set_ylabel("Im λ %s" % ubr(units(g["root_imag"])))
    ax.set_title("Characteristic roots of the two-pendulum balancer\n%s; verdict %s, max Re λ = %s%s"
                 % (pendulum_params_text(h), s(g.attrs.get("verdict", "?")), fmt(param(g, "max_real", np.nan)),
                    status_note(h)), fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=9)
    save(fig, outdir, stem, "roots", written)


def plot_pendulum_transient(h, outdir, stem, written):
    g = h["pendulum/transient"]
    t = g["tau"][:]
    tu = units(g["tau"])
    ttb = param(g, "time_to_balance")
    tol = param(g, "balance_tol")
    fig, ax = plt.subplots(3, 1, figsize=(10, 9), sharex=True, constrained_layout=True)
    ax[0].semilogy(t, positive(g["amplitude"][:]), lw=1.0, color="tab:blue")
    ax[0].set_ylabel("shaft amplitude / l %s (log scale)" % ubr(units(g["amplitude"])))
    ax[1].semilogy(t, positive(g["unbalance"][:]), lw=1.0, color="tab:purple",
                   label="|d| of rotor plus pendulums")
    if tol is not None:
        ax[1].axhline(tol, color="tab:gray", ls=":", label="balance tolerance %s" % fmt(tol, 3))
    ax[1].set_ylabel("residual unbalance / (2 m l) %s (log scale)" % ubr(units(g["unbalance"])))
    for name, lab, col in (("alpha", "pendulum 1: α = ψ - ψ0", "tab:green"),
                           ("beta", "pendulum 2: β = φ - ψ0", "tab:orange")):
        tt, a = break_wraps(t, g[name][:])
        ax[2].plot(tt, a, lw=1.0, color=col, label=lab)
    ax[2].axhline(0.0, color="k", lw=0.6)
    ax[2].set_ylabel("angle from the balancing position %s" % ubr(units(g["alpha"])))
    ax[2].set_xlabel("dimensionless time τ = ω0 t %s" % ubr(tu))
    mark_time(ax, ttb, "time to balance τ = %s" % fmt(ttb) if ttb is not None and np.isfinite(ttb) else None)
    for a in ax:
        a.grid(True, alpha=0.3)
    ax[1].legend(fontsize=8, loc="upper right")
    ax[2].legend(fontsize=8, loc="upper right")
    if ttb is not None and np.isfinite(ttb):
        ax[0].legend(fontsize=8, loc="upper right")
    bal = "balanced at τ = %s" % fmt(ttb) if int(param(g, "balanced", 0) or 0) else "not balanced"
    fig.suptitle("Two-pendulum autobalancer transient: %s; %s%s" % (pendulum_params_text(h), bal, status_note(h)),
                 fontsize=11)
    save(fig, outdir, stem, "transient", written)


# ---- rotor ----------------------------------------------------------------------------------
def rotor_planes(h):
    planes = []
    j = 1
    while "rotor/plane%d" % j in h:
        planes.append(j)
        j += 1
    return planes


def plot_rotor_transient(h, outdir, stem, written):
    g = h["rotor/transient"]
    t = g["time"][:]
    tu = units(g["time"])
    ttb = param(g, "time_to_balance")
    tol = param(g, "balance_tol")
    planes = rotor_planes(h)
    omega = param(h["rotor"], "omega", np.nan)
    nballs = sum(int(param(h["rotor/plane%d" % j], "n_balls", 0) or 0) for j in planes)
    fig, ax = plt.subplots(3, 1, figsize=(10, 10), sharex=True, constrained_layout=True)
    # (a) displacement amplitudes, in micrometres (the archive stores m)
    scale, ulab = (1e6, "µm") if units(g["amp_G"]) == "m" else (1.0, units(g["amp_G"]))
    ax[0].semilogy(t, positive(scale * g["amp_G"][:]), lw=0.9, color="tab:blue", label="centre of mass |(x, y)|")
    for j in planes:
        name = "p%d_amp_D" % j
        if name in g:
            ax[0].semilogy(t, positive(scale * g[name][:]), lw=0.9, color=("tab:orange", "tab:green", "tab:red")[(j - 1) % 3],
                       alpha=0.8, label="at balancer plane %d" % j)
    ax[0].set_ylabel("displacement amplitude [%s] (log scale)" % ulab)
    ax[0].legend(fontsize=8, loc="upper right")
    # (b) residual unbalance |s_j| / (m0 r0), log scale
    for j in planes:
        name = "p%d_s_rel" % j
        if name in g:
            ax[1].semilogy(t, positive(g[name][:]), lw=0.9, color=("tab:purple", "tab:brown")[(j - 1) % 2],
                           label="plane %d: |s| / (m0 r0)" % j)
    if tol is not None:
        ax[1].axhline(tol, color="tab:gray", ls=":", label="balance tolerance %s" % fmt(tol, 3))
    ax[1].set_ylabel("relative residual unbalance %s (log scale)"
                     % ubr(units(g["p1_s_rel"]) if "p1_s_rel" in g else "1"))
    ax[1].legend(fontsize=8, loc="upper right")
    # (c) ball angles relative to the rotor (wrapped), with the balanced angles (3.14)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    k = 0
    for j in planes:
        pg = h["rotor/plane%d" % j]
        nb = int(param(pg, "n_balls", 0) or 0)
        bal = np.atleast_1d(pg.attrs["ball_psi_balanced"]) if "ball_psi_balanced" in pg.attrs else []
        for i in range(1, nb + 1):
            name = "p%d_b%d_psi_w" % (j, i)
            if name not in g:
                continue
            col = colors[k % len(colors)]
            k += 1
            tt, a = break_wraps(t, g[name][:])
            ax[2].plot(tt, a, lw=0.9, color=col, label="plane %d, ball %d" % (j, i))
        for b in bal:  # the balanced set; the balls may take its angles in either order
            if np.isfinite(b):
                ax[2].axhline(b, color="k", ls=":", lw=1.0)
    ax[2].set_ylim(-np.pi - 0.2, np.pi + 0.2)
    ax[2].set_yticks([-np.pi, -np.pi / 2, 0, np.pi / 2, np.pi])
    ax[2].set_yticklabels(["-π", "-π/2", "0", "π/2", "π"])
    ax[2].set_ylabel("ball angle ψ relative to the rotor [rad]")
    ax[2].set_xlabel("time t %s" % ubr(tu))
    ax[2].legend(fontsize=8, loc="upper right", ncol=2, title="dotted: the balanced angles (3.14), in either order", title_fontsize=8)
    mark_time(ax, ttb, "time to balance %s %s" % (fmt(ttb), tu) if ttb is not None and np.isfinite(ttb) else None)
    if ttb is not None and np.isfinite(ttb):
        ax[0].legend(fontsize=8, loc="upper right")
    for a in ax:
        a.grid(True, alpha=0.3)
    baltxt = ("balanced after %s %s" % (fmt(ttb), tu)) if int(param(g, "balanced", 0) or 0) else "not balanced"
    if "Omega" in g:  # a speed profile: the rotor's constant omega is not used by the run
        wtxt = "Ω %s → %s %s (%s drive)" % (fmt(g["Omega"][0]), fmt(g["Omega"][-1]), units(g["Omega"]),
                                             s(g.attrs.get("drive_mode", "speed")))
    else:
        wtxt = "ω = %s %s" % (fmt(omega), punit(h["rotor"], "omega"))
    fig.suptitle("Rotor with ball autobalancer: %s, %d plane(s), %d ball(s); %s%s"
                 % (wtxt, len(planes), nballs, baltxt, status_note(h)), fontsize=11)
    save(fig, outdir, stem, "transient", written)


# ---- rotor stability (autobal rotor stability|sweep|map|campbell) --------------------------
RPM_PER_RAD_S = 60.0 / (2.0 * np.pi)


def plot_rotor_runup(h, outdir, stem, written):
    """The run-up picture: envelope and residual unbalance over Omega (docs/device.md, "Run-up outputs")."""
    g = h["rotor/runup"]
    tr = h["rotor/transient"]
    if "Omega" not in tr or "envelope" not in g:
        raise NotImplementedError("rotor/runup: no Omega column or no envelope (a series shorter than the run?): "
                                  "no run-up picture")
    w = tr["Omega"][:]
    wu = units(tr["Omega"])
    t = tr["time"][:]
    tu = units(tr["time"])
    env = g["envelope"][:]
    scale, ulab = (1e6, "µm") if units(g["envelope"]) == "m" else (1.0, units(g["envelope"]))
    planes = rotor_planes(h)
    tol = param(tr, "balance_tol")
    res = g["resonance"][:] if "resonance" in g else np.zeros(0)
    whirl = g["resonance_whirl"][:] if "resonance_whirl" in g else np.zeros(len(res), dtype=int)
    fig, ax = plt.subplots(2, 1, figsize=(10, 7.5), sharex=True, constrained_layout=True)
    ax[0].semilogy(w, positive(scale * tr["amp_G"][:]), lw=0.5, color="tab:blue", alpha=0.35,
                   label="|(x, y)| of the centre of mass, sampled")
    ax[0].semilogy(w, positive(scale * env), lw=1.2, color="tab:blue",
                   label="envelope: largest over the last revolution")
    for j in planes:
        name = "p%d_s_rel" % j
        if name in tr:
            ax[1].semilogy(w, positive(tr[name][:]), lw=0.9, color=("tab:purple", "tab:brown")[(j - 1) % 2],
                           label="plane %d: |s| / (m0 r0)" % j)
    if tol is not None:
        ax[1].axhline(tol, color="tab:gray", ls=":", label="balance tolerance %s" % fmt(tol, 3))
    # the resonance speeds: forward whirl solid, backward dashed; labelled once on the top axis
    for k, x in enumerate(res):
        fw = whirl[k] > 0 if k < len(whirl) else True
        for a in ax:
            a.axvline(x, color="tab:red" if fw else "tab:gray", ls="-" if fw else "--", lw=0.9, alpha=0.8)
    # the balanced end at the final speed would stretch the log axes over many decades: floors at
    # 1e-4 of the largest amplitude and a tenth of the balance tolerance (values below sit on them)
    emax = np.nanmax(positive(scale * env)) if np.any(env > 0) else np.nan
    if np.isfinite(emax) and ax[0].get_ylim()[0] < 1e-4 * emax:
        ax[0].set_ylim(1e-4 * emax, None)
    if tol is not None and np.isfinite(tol) and ax[1].get_ylim()[0] < 0.1 * tol:
        ax[1].set_ylim(0.1 * tol, None)
    # one label per cluster of resonances closer than 3% of the axis (e.g. a forward-backward pair)
    top = ax[0].get_ylim()[1]
    span = max(np.nanmax(np.abs(w)), 1e-300)
    clusters = []
    for k, x in enumerate(res):
        if clusters and x - clusters[-1][-1][0] < 0.03 * span:
            clusters[-1].append((x, k))
        else:
            clusters.append([(x, k)])
    for cl in clusters:
        txt = ", ".join("%s%s" % (fmt(x), "" if whirl[k] > 0 else " (bw)") for x, k in cl)
        ax[0].text(cl[-1][0], top, " %s %s" % (txt, wu), fontsize=7, va="top", ha="left", rotation=90,
                   color="tab:red" if any(whirl[k] > 0 for _, k in cl) else "tab:gray")
    # captures: the band of the resonance shaded
    band = param(g, "capture_band")
    if "capture_resonance" in g and band is not None:
        for r in np.atleast_1d(g["capture_resonance"][:]):
            for a in ax:
                a.axvspan((1 - band) * res[r], (1 + band) * res[r], color="tab:orange", alpha=0.2)
    handles, labels = ax[0].get_legend_handles_labels()
    handles += [Line2D([], [], color="tab:red", lw=0.9), Line2D([], [], color="tab:gray", ls="--", lw=0.9)]
    labels += ["resonance speed (Campbell crossing), forward whirl", "resonance speed, backward whirl"]
    if "capture_resonance" in g:
        handles.append(Patch(color="tab:orange", alpha=0.2))
        labels.append("capture band (stayed %s %s or longer)" % (fmt(param(g, "capture_time")), punit(g, "capture_time")))
    ax[0].legend(handles, labels, fontsize=8, loc="lower right")
    ax[0].set_ylabel("displacement amplitude [%s] (log scale)" % ulab)
    ax[1].set_ylabel("relative residual unbalance (log scale)")
    ax[1].legend(fontsize=8, loc="lower left")
    ax[1].set_xlabel("spin speed Ω %s" % ubr(wu))
    rpm_axis(ax[0], wu)
    for a in ax:
        a.grid(True, alpha=0.3)
    ttb = param(g, "time_to_balance_after_last_passage")
    tlp = param(g, "t_last_passage")
    if ttb is not None and np.isfinite(ttb):
        baltxt = "balanced %s %s after the last passage" % (fmt(param(g, "balance_delay"), 3), tu)
    elif tlp is not None and np.isfinite(tlp):
        baltxt = "not balanced after the last passage"
    else:
        baltxt = "no resonance passed"
    mode = s(tr.attrs.get("drive_mode", "drive"))
    fig.suptitle("Run-up (%s drive, Ω %s → %s %s, a run of %s %s): %s%s"
                 % (mode, fmt(w[0]), fmt(w[-1]), wu, fmt(t[-1] - t[0]), tu, baltxt, status_note(h)), fontsize=11)
    save(fig, outdir, stem, "runup", written)


def rpm_axis(ax, unit, where="top"):
    """A secondary x axis in rev/min when the axis is a speed in rad/s (nothing otherwise)."""
    if unit != "rad/s":
        return None
    sec = ax.secondary_xaxis(where, functions=(lambda w: w * RPM_PER_RAD_S, lambda n: n / RPM_PER_RAD_S))
    sec.set_xlabel("spin speed [rev/min]", fontsize=9)
    sec.tick_params(labelsize=8)
    return sec


def hz_axis(ax, unit):
    """A secondary y axis in Hz when the axis is a frequency in rad/s."""
    if unit != "rad/s":
        return None
    sec = ax.secondary_yaxis("right", functions=(lambda w: w / (2.0 * np.pi), lambda f: f * 2.0 * np.pi))
    sec.set_ylabel("natural frequency [Hz]", fontsize=9)
    sec.tick_params(labelsize=8)
    return sec


def spread_labels(ax, xs, ys, texts, color="k", dx=6, min_gap=11.0, fontsize=8, colors=None, ha="left"):
    """Write texts beside the points (xs, ys), pushed apart vertically (display units) so that no two
    overlap; a thin leader line joins a label moved from its point."""
    if not len(xs):
        return
    tr = ax.transData
    pts = tr.transform(np.column_stack([xs, ys])) * 72.0 / ax.figure.dpi  # in points
    order = np.argsort(pts[:, 1])
    y = pts[order, 1].copy()
    for i in range(1, len(y)):  # push up
        y[i] = max(y[i], y[i - 1] + min_gap)
    top = ax.bbox.y1 * 72.0 / ax.figure.dpi - 4
    if len(y) and y[-1] > top:  # and back down if the top ran out of room
        y[-1] = top
        for i in range(len(y) - 2, -1, -1):
            y[i] = min(y[i], y[i + 1] - min_gap)
    for j, i in enumerate(order):
        px, py = pts[i]
        col = colors[i] if colors is not None else color
        ax.annotate(texts[i], xy=(xs[i], ys[i]), xycoords="data",
                    xytext=(dx if ha == "left" else -dx, y[j] - py), textcoords="offset points",
                    fontsize=fontsize, color=col, ha=ha, va="center",
                    bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none", alpha=0.75),
                    arrowprops=dict(arrowstyle="-", color=col, lw=0.5, alpha=0.7) if abs(y[j] - py) > 2 else None)


def track_modes(omega, freq, whirl=None):
    """Follow each mode of a Campbell diagram through crossings.

    freq[k, j] is the j-th natural frequency at spin speed omega[k], sorted by frequency at each
    speed (as the archive stores it), so at a crossing two curves swap columns.  A mode is followed
    from one speed to the next by predicting its frequency from its last two points (value and
    slope) and choosing the assignment of the new points to the modes with the smallest total
    prediction error; a change of whirl direction (whirl[k, j]: 1 forward, -1 backward, 0
    undecided) costs as much as two typical frequency steps, so the whirl decides only between
    nearly equal predictions.  Returns perm (n_omega x n_modes, int): mode m is column perm[k, m]
    at speed k; freq[k, perm[k]] (np.take_along_axis(freq, perm, 1)) are the tracked curves."""
    om = np.asarray(omega, dtype=float)
    fr = np.asarray(freq, dtype=float)
    nk, nm = fr.shape
    wh = np.zeros(fr.shape, dtype=int) if whirl is None else np.asarray(whirl, dtype=int)
    perm = np.zeros((nk, nm), dtype=int)
    perm[0] = np.arange(nm)
    if nk == 0 or nm == 0:
        return perm
    steps = np.abs(np.diff(fr, axis=0))
    steps = steps[np.isfinite(steps) & (steps > 0)]
    fin = fr[np.isfinite(fr)]
    span = float(fin.max() - fin.min()) if fin.size else 1.0
    typ = float(np.median(steps)) if steps.size else (span if span > 0 else 1.0)
    w_whirl = 2.0 * typ
    w_nan = 10.0 * max(span, typ)
    last_w = np.where(np.abs(om[0]) > 0, wh[0], 0).astype(int)  # whirl is meaningless at rest
    try:
        from scipy.optimize import linear_sum_assignment
    except ImportError:  # pragma: no cover
        linear_sum_assignment = None
    import itertools
    for k in range(1, nk):
        prev = fr[k - 1, perm[k - 1]]
        pred = prev.copy()
        if k >= 2 and om[k - 1] != om[k - 2]:
            prev2 = fr[k - 2, perm[k - 2]]
            slope = (prev - prev2) / (om[k - 1] - om[k - 2])
            ok = np.isfinite(slope)
            pred[ok] = prev[ok] + slope[ok] * (om[k] - om[k - 1])
        new = fr[k]
        cost = np.abs(pred[:, None] - new[None, :])
        nan_p, nan_n = ~np.isfinite(pred)[:, None], ~np.isfinite(new)[None, :]
        cost = np.where(nan_p & nan_n, 0.0, np.where(nan_p | nan_n, w_nan, cost))
        wn = wh[k][None, :]
        cost = cost + w_whirl * ((last_w[:, None] != 0) & (wn != 0) & (last_w[:, None] != wn))
        if linear_sum_assignment is not None:
            rows, cols = linear_sum_assignment(cost)
            p = np.empty(nm, dtype=int)
            p[rows] = cols
        else:
            best = min(itertools.permutations(range(nm)), key=lambda q: sum(cost[i, q[i]] for i in range(nm)))
            p = np.array(best, dtype=int)
        perm[k] = p
        w_now = wh[k, p]
        last_w = np.where((w_now != 0) & (om[k] != 0), w_now, last_w)
    return perm


WHIRL_NAMES = {1: "forward", -1: "backward", 0: "undecided"}


def whirl_summary(w):
    """'forward', 'backward', 'undecided' or 'forward → backward' for a tracked whirl series."""
    seq = []
    for v in np.asarray(w, dtype=int):
        if v != 0 and (not seq or seq[-1] != v):
            seq.append(int(v))
    if not seq:
        return "whirl undecided"
    return " → ".join(WHIRL_NAMES[v] for v in seq) + " whirl"


def order_crossings(om, f, order):
    """Speeds where the curve f(om) meets the order line order * om (linear interpolation)."""
    d = f - order * om
    out = []
    for k in range(len(om) - 1):
        a, b = d[k], d[k + 1]
        if np.isfinite(a) and np.isfinite(b) and ((a > 0 >= b) or (a < 0 <= b)) and b != a:
            out.append(om[k] + (om[k + 1] - om[k]) * a / (a - b))
    return out


def plot_rotor_campbell(h, outdir, stem, written):
    """Campbell diagram (modes tracked through crossings, whirl, order lines 1X and 2X, critical speeds)
    and steady unbalance response."""
    g = h["rotor/campbell"]
    om = g["omega"][:]
    fr = g["frequency"][:]
    wh = g["whirl"][:] if "whirl" in g else np.zeros(fr.shape, int)
    ou, fu = units(g["omega"]), units(g["frequency"])
    perm = track_modes(om, fr, wh)
    tf = np.take_along_axis(fr, perm, 1)
    tw = np.take_along_axis(wh, perm, 1)
    nm = tf.shape[1]
    fig, ax = plt.subplots(2, 1, figsize=(14, 10), sharex=True, constrained_layout=True,
                           gridspec_kw={"height_ratios": [3, 1.6]})
    a0 = ax[0]
    fin = tf[np.isfinite(tf)]
    top = float(fin.max()) * 1.12 if fin.size else float(om.max())
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    styles = {1: "-", -1: (0, (6, 2)), 0: (0, (1.5, 1.5))}
    ends_x, ends_y, ends_t, ends_c = [], [], [], []
    for m in range(nm):
        col = colors[m % len(colors)]
        rest = tf[0, m]
        wsum = whirl_summary(tw[1:, m] if len(om) > 1 else tw[:, m])
        lab = "mode %d: %s, %s %s at ω = %s" % (m + 1, wsum, fmt(rest), fu, fmt(om[0], 3))
        # the line style follows the whirl at each speed: solid forward, dashed backward, dotted undecided
        code = tw[:, m].copy()
        if len(code) > 1:
            code[0] = code[1]
        start = 0
        for k in range(1, len(om) + 1):
            if k == len(om) or code[k] != code[start]:
                seg = slice(start, min(k + 1, len(om)))
                a0.plot(om[seg], tf[seg, m], color=col, lw=1.8, ls=styles.get(int(code[start]), "-"),
                        label=lab if start == 0 else None)
                start = k
        last = np.nonzero(np.isfinite(tf[:, m]))[0]
        if last.size:
            i = int(last[-1])
            ends_x.append(om[i]), ends_y.append(tf[i, m]), ends_c.append(col)
            ends_t.append("%d %s" % (m + 1, {1: "fw", -1: "bw"}.get(int(tw[i, m]), "")))
    handles, _ = a0.get_legend_handles_labels()
    from matplotlib.lines import Line2D
    omax = float(om.max())
    handles.append(a0.plot(om, om, color="k", lw=1.0, label="1X: frequency = ω (unbalance excitation)")[0])
    cx2 = []
    if 2.0 * om.min() < top:
        handles.append(a0.plot(om, 2.0 * om, color="0.45", lw=0.9, ls=(0, (4, 3)),
                               label="2X: frequency = 2ω")[0])
        for m in range(nm):
            for c in order_crossings(om, tf[:, m], 2.0):
                cx2.append((c, 2.0 * c))
        if cx2:
            cx = np.array(cx2)
            handles.append(a0.plot(cx[:, 0], cx[:, 1], "s", mfc="none", mec="0.35", ms=6,
                                   label="2X crossings (from the curves): ω = %s %s"
                                   % (", ".join(fmt(c, 4) for c in sorted(set(np.round(cx[:, 0], 9)))), ou))[0])
    mx = []  # where two tracked modes cross each other
    for m in range(nm):
        for n in range(m + 1, nm):
            d = tf[:, m] - tf[:, n]
            for k in range(len(om) - 1):
                a, b = d[k], d[k + 1]
                scl = 1e-6 * max(abs(tf[k, m]), 1e-300)
                if np.isfinite(a) and np.isfinite(b) and a * b < 0 and max(abs(a), abs(b)) > scl:
                    c = om[k] + (om[k + 1] - om[k]) * a / (a - b)
                    mx.append((c, np.interp(c, om[k:k + 2], tf[k:k + 2, m]), m + 1, n + 1))
    if mx:
        handles.append(a0.plot([c[0] for c in mx], [c[1] for c in mx], "X", color="k", ms=8, mfc="yellow",
                               label="modes crossing each other: " + ", ".join(
                                   "%d and %d at ω = %s %s" % (c[2], c[3], fmt(c[0]), ou) for c in mx))[0])
    handles.append(Line2D([], [], color="0.3", lw=1.5, ls="-", label="line style: solid forward, dashed backward, "
                          "dotted undecided whirl"))
    if "crossing_omega" in g and g["crossing_omega"].size:
        co = g["crossing_omega"][:]
        cw = g["crossing_whirl"][:] if "crossing_whirl" in g else np.zeros(co.shape, int)
        handles.append(a0.plot(co, co, "o", mfc="none", mec="tab:red", mew=1.6, ms=10,
                               label="critical speeds (1X crossings, from the archive)")[0])
    a0.set_xlim(float(om.min()), omax * 1.06)
    a0.set_ylim(0, top)
    if "crossing_omega" in g and g["crossing_omega"].size:
        # one label per speed: a degenerate pair crosses the 1X line at the same speed twice
        lx, lw = [], []
        for c, w in zip(co, cw):
            wt = {1: "fw", -1: "bw"}.get(int(w), "whirl ?")
            if lx and abs(c - lx[-1]) <= 1e-9 * max(abs(c), 1.0):
                lw[-1].append(wt)
                continue
            lx.append(c)
            lw.append([wt])
        lt = ["%s %s (%s)" % (fmt(c), ou, w[0] if len(w) == 1 else
                              ("%d modes, %s" % (len(w), w[0]) if len(set(w)) == 1 else ", ".join(w)))
              for c, w in zip(lx, lw)]
        spread_labels(a0, np.array(lx), np.array(lx), lt, color="tab:red", dx=14)
    spread_labels(a0, np.array(ends_x), np.array(ends_y), ends_t, colors=ends_c, dx=4)
    a0.set_ylabel("natural frequency %s" % ubr(fu))
    a0.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.07, 1.0), frameon=False)
    a0.grid(True, alpha=0.3)
    rpm_axis(a0, ou)
    hz_axis(a0, fu)
    scale, ulab = (1e6, "µm") if units(g["amp_G"]) == "m" else (1.0, units(g["amp_G"]))
    ag = np.where(np.isfinite(g["amp_G"][:]), g["amp_G"][:], np.nan)
    ax[1].semilogy(om, scale * ag, color="tab:blue", lw=1.2, label="centre of mass")
    if "amp_D" in g:
        ad = g["amp_D"][:]
        for j in range(ad.shape[1]):
            ax[1].semilogy(om, scale * np.where(np.isfinite(ad[:, j]), ad[:, j], np.nan), lw=1.0,
                           color=("tab:orange", "tab:green")[j % 2], label="at balancer plane %d" % (j + 1))
    if np.isfinite(ag).any():
        ax[1].set_ylim(bottom=1e-3 * scale * float(np.nanmax(ag)))
    if "peak_omega" in g:
        for i, pk in enumerate(g["peak_omega"][:]):
            ax[1].axvline(pk, color="tab:red", ls=":", lw=1.0,
                          label="response peaks: ω = %s %s" % (", ".join(fmt(p) for p in g["peak_omega"][:]), ou)
                          if i == 0 else None)
    ax[1].set_ylabel("unbalance response amplitude [%s]" % ulab)
    ax[1].set_xlabel("spin speed ω %s" % ubr(ou))
    ax[1].legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.07, 1.0), frameon=False)
    ax[1].grid(True, which="both", alpha=0.3)
    fig.suptitle("Rotor-housing without balls: Campbell diagram (modes followed through crossings) and steady "
                 "unbalance response%s" % status_note(h), fontsize=11)
    save(fig, outdir, stem, "campbell", written)


def param_label(name, ds):
    """Axis label for a swept rotor parameter from its coordinate dataset."""
    sym = {"omega": "spin speed ω"}.get(name, name)
    return "%s %s" % (sym, ubr(units(ds)))


NARROW = 0.02  # a stable interval narrower than this fraction of the axis is drawn widened and pointed at


def shade_intervals(ax, lo, hi, label, xmin, xmax, color="tab:green", alpha=0.18, narrow_note=True):
    """Shade the stable intervals [lo_i, hi_i] (archive values, not the sampled curve).  An interval
    narrower than NARROW of the axis is drawn at least that wide in a stronger colour, outlined at its
    true ends, and named in a note, so that a window of a few rad/s stays visible."""
    span = float(xmax - xmin) if xmax > xmin else 1.0
    narrow = []
    for i, (a, b) in enumerate(zip(lo, hi)):
        b = min(b, xmax) if np.isfinite(b) else xmax
        ax.axvspan(a, b, color=color, alpha=alpha, lw=0, label=label if i == 0 else None)
        if b - a < NARROW * span:
            c, w = 0.5 * (a + b), 0.5 * NARROW * span
            ax.axvspan(c - w, c + w, color=color, alpha=0.35, lw=0,
                       label="narrow stable window (drawn %g%% of the axis wide)" % (100 * NARROW)
                       if not narrow else None)
            for e in (a, b):
                ax.axvline(e, color="darkgreen", lw=0.8)
            narrow.append((a, b))
    if narrow_note and narrow:
        for k, (a, b) in enumerate(narrow):
            ax.annotate("stable window\n[%s, %s]\n(width %s)" % (fmt(a, 5), fmt(b, 5), fmt(b - a, 3)),
                        xy=(0.5 * (a + b), 0.0), xycoords=("data", "axes fraction"),
                        xytext=(28, 40 + 34 * k), textcoords="offset points", fontsize=8, color="darkgreen",
                        arrowprops=dict(arrowstyle="->", color="darkgreen", lw=1.0),
                        bbox=dict(boxstyle="round,pad=0.25", fc="white", ec="darkgreen", lw=0.6, alpha=0.9))
    return narrow


def interval_strip(ax, lo, hi, xmin, xmax, y, height, label_stable=None, label_unstable=None):
    """One horizontal strip: unstable over [xmin, xmax], stable on the archive's intervals (narrow ones
    widened to NARROW of the axis, as in shade_intervals)."""
    span = float(xmax - xmin) if xmax > xmin else 1.0
    ax.barh([y], [xmax - xmin], left=[xmin], color=VERDICT_COLORS[-1], height=height, label=label_unstable)
    for i, (a, b) in enumerate(zip(lo, hi)):
        b = min(b, xmax) if np.isfinite(b) else xmax
        if b - a < NARROW * span:
            c = 0.5 * (a + b)
            a, b = c - 0.5 * NARROW * span, c + 0.5 * NARROW * span
        ax.barh([y], [b - a], left=[a], color=VERDICT_COLORS[1], height=height,
                label=label_stable if i == 0 else None)


def mark_critical(ax, cvs, kinds=None, color="tab:red"):
    """Dashed lines at the critical values, each numbered at the top (labels staggered)."""
    for i, cv in enumerate(cvs):
        ax.axvline(cv, color=color, ls="--", lw=1.0)
    order = np.argsort(cvs)
    ax.figure.canvas.draw()
    last, lev = -1e300, 0
    for j in order:
        px = ax.transData.transform((cvs[j], 0))[0]
        lev = lev + 1 if px - last < 40 else 0
        last = px
        ax.annotate(fmt(cvs[j], 5), xy=(cvs[j], 1.0), xycoords=("data", "axes fraction"),
                    xytext=(2, -10 - 11 * lev), textcoords="offset points", fontsize=7.5, color=color,
                    bbox=dict(boxstyle="square,pad=0.05", fc="white", ec="none", alpha=0.8))


def intervals_text(lo, hi, unit):
    parts = ["[%s, %s]" % (fmt(a), fmt(b) if np.isfinite(b) else "∞") for a, b in zip(lo, hi)]
    return ("stable for %s %s" % (" ∪ ".join(parts), unit)) if parts else "no stable interval"


def plot_rotor_sweep(h, outdir, stem, written):
    """Stability margin along a swept parameter; the archive's stable intervals shaded (narrow ones
    widened and named), critical values marked; a strip of the intervals and of the sampled verdicts."""
    g = h["rotor/sweep"]
    pname = s(g.attrs.get("param", "omega"))
    x = g[pname][:]
    xu = units(g[pname])
    mg = g["margin"][:]
    v = g["verdict"][:]
    xmin, xmax = float(np.nanmin(x)), float(np.nanmax(x))
    fig, ax = plt.subplots(2, 1, figsize=(11, 7.5), sharex=True, constrained_layout=True,
                           gridspec_kw={"height_ratios": [4, 1.1]})
    lo = g["stable_lo"][:] if "stable_lo" in g else np.array([])
    hi = g["stable_hi"][:] if "stable_hi" in g else np.array([])
    narrow = shade_intervals(ax[0], lo, hi, "stable intervals (refined ends from the archive)", xmin, xmax)
    ax[0].plot(x, mg, color="tab:blue", lw=1.4, label="stability margin (largest Re λ), sampled")
    ax[0].axhline(0.0, color="k", lw=0.8)
    ax[0].set_xlim(xmin, xmax)
    cvs = g["critical_value"][:] if "critical_value" in g else np.array([])
    if cvs.size:
        kds = g["critical_kind"][:]
        kindtxt = {1: "stable above", -1: "unstable above"}
        ax[0].plot([], [], color="tab:red", ls="--", lw=1.0,
                   label="critical values (%s)" % ", ".join("%s %s" % (fmt(cv), kindtxt.get(int(kd), "edge"))
                                                            for cv, kd in zip(cvs, kds)))
        mark_critical(ax[0], cvs)
    ax[0].set_ylabel("margin %s" % ubr(units(g["margin"])))
    ax[0].legend(fontsize=8, loc="lower right", framealpha=0.92)
    ax[0].grid(True, alpha=0.3)
    rpm_axis(ax[0], xu)
    if narrow:  # a zoom on the first narrow window: the sampled curve there and the true interval
        a, b = narrow[0]
        w = max(b - a, 1e-12)
        ins = ax[0].inset_axes([0.30, 0.55, 0.28, 0.38])
        sel = (x >= a - 4 * w) & (x <= b + 4 * w)
        ins.axvspan(a, b, color="tab:green", alpha=0.25, lw=0)
        ins.plot(x[sel], mg[sel], ".-", color="tab:blue", lw=1.0, ms=4)
        ins.axhline(0.0, color="k", lw=0.6)
        for cv in cvs:
            if a - 4 * w <= cv <= b + 4 * w:
                ins.axvline(cv, color="tab:red", ls="--", lw=0.8)
        ins.set_xlim(a - 4 * w, b + 4 * w)
        if sel.any():
            fin = mg[sel][np.isfinite(mg[sel])]
            if fin.size:
                pad = 0.1 * (fin.max() - fin.min() + 1e-12)
                ins.set_ylim(fin.min() - pad, fin.max() + pad)
        ins.tick_params(labelsize=7)
        ins.set_title("zoom: stable window, %d sampled points in it" % int(np.sum((x >= a) & (x <= b))), fontsize=8)
        ins.grid(True, alpha=0.3)
    interval_strip(ax[1], lo, hi, xmin, xmax, 1.0, 0.8, "stable (archive intervals)", "unstable")
    verdict_image(ax[1], x, np.array([-0.2, 0.2]), np.vstack([v, v]).T)
    ax[1].set_ylim(-0.5, 1.5)
    ax[1].set_yticks([0.0, 1.0])
    ax[1].set_yticklabels(["sampled verdict", "archive intervals\n(narrow: widened)"], fontsize=8)
    handles = [Patch(facecolor=VERDICT_COLORS[c], edgecolor="k", lw=0.5, label=VERDICT_NAMES[c])
               for c in sorted(set(np.unique(v).astype(int).tolist()) & set(VERDICT_COLORS))]
    ax[1].legend(handles=handles, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.6), ncol=4,
                 frameon=False)
    ax[1].set_xlabel(param_label(pname, g[pname]))
    ax[1].set_xlim(xmin, xmax)
    fig.suptitle("Rotor with ball autobalancer: stability of the balanced motion (3.14) along %s\n%s%s"
                 % ("the spin speed ω" if pname == "omega" else pname, intervals_text(lo, hi, xu), status_note(h)),
                 fontsize=11)
    save(fig, outdir, stem, "stability_sweep", written)


def plot_rotor_map(h, outdir, stem, written):
    g = h["rotor/map"]
    p1, p2 = s(g.attrs["param1"]), s(g.attrs["param2"])
    x, y = g[p1][:], g[p2][:]
    v = g["verdict"][:]
    has_m = "margin" in g
    fig, axes = plt.subplots(1, 2 if has_m else 1, figsize=(13 if has_m else 8, 6), constrained_layout=True,
                             squeeze=False)
    ax = axes[0, 0]
    handles = verdict_image(ax, x, y, v)
    ax.set_xlabel(param_label(p1, g[p1]))
    ax.set_ylabel(param_label(p2, g[p2]))
    ax.legend(handles=handles, fontsize=9, loc="upper right", framealpha=0.9)
    ax.set_title("Rotor with ball autobalancer: stability of the balanced motion (3.14)%s" % status_note(h),
                 fontsize=11)
    rpm_axis(ax, units(g[p1]))
    if has_m:
        ax2 = axes[0, 1]
        mg = g["margin"][:]
        fin = mg[np.isfinite(mg)]
        lim = float(np.percentile(np.abs(fin), 98)) if fin.size else 1.0
        im = mesh(ax2, x, y, mg, cmap="RdBu_r", vmin=-lim, vmax=lim)
        if fin.size and fin.min() < 0 < fin.max() and len(x) > 1 and len(y) > 1:
            ax2.contour(x, y, mg.T, levels=[0.0], colors="k", linewidths=1.0)
        fig.colorbar(im, ax=ax2, label="stability margin (largest Re λ) %s" % ubr(units(g["margin"])))
        ax2.set_xlabel(ax.get_xlabel())
        ax2.set_ylabel(ax.get_ylabel())
        ax2.set_title("stability margin (black line: margin = 0)", fontsize=11)
        rpm_axis(ax2, units(g[p1]))
    save(fig, outdir, stem, "stability_map", written)


def plot_rotor_stability(h, outdir, stem, written):
    """Characteristic roots of the balanced motion and the stable speed intervals."""
    g = h["rotor/stability"]
    crit = "rotor/stability/critical" in h and "stable_lo" in h["rotor/stability/critical"]
    fig, axes = plt.subplots(1, 2 if crit else 1, figsize=(13 if crit else 7, 6), constrained_layout=True,
                             squeeze=False, gridspec_kw={"width_ratios": [3, 2]} if crit else None)
    ax = axes[0, 0]
    sets = (("root_real", "root_imag", "o", "roots of the closed system"),
            ("full_real", "full_imag", "x", "eigenvalues of the full linearization"))
    u = "1/s"
    for re_, im_, mk, lab in sets:
        if re_ in g:
            u = units(g[re_])
            ax.plot(g[re_][:], g[im_][:], mk, ms=8 if mk == "o" else 6, mfc="none" if mk == "o" else None, label=lab)
    ax.axvline(0.0, color="k", lw=0.8)
    ax.set_xlabel("Re λ %s" % ubr(u))
    ax.set_ylabel("Im λ %s (rotating frame)" % ubr(u))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    om = param(h["rotor"], "omega", np.nan)
    ax.set_title("balanced motion at ω = %s %s: %s, margin %s %s (%s)"
                 % (fmt(om), punit(h["rotor"], "omega"), s(g.attrs.get("verdict", "?")),
                    fmt(param(g, "margin", np.nan)), punit(g, "margin"), s(g.attrs.get("method", "?"))), fontsize=10)
    if crit:
        c = h["rotor/stability/critical"]
        ax2 = axes[0, 1]
        lo, hi = c["stable_lo"][:], c["stable_hi"][:]
        wmin, wmax = param(c, "omega_min", 0.0), param(c, "omega_max", float(np.nanmax(hi)))
        cu = units(c["stable_lo"])
        interval_strip(ax2, lo, hi, wmin, wmax, 0.0, 0.5, "stable (narrow windows widened to %g%% of the axis)"
                       % (100 * NARROW), "unstable")
        span = wmax - wmin
        for k, (a, b) in enumerate(zip(lo, hi)):
            if np.isfinite(b) and b - a < NARROW * span:
                ax2.annotate("[%s, %s]\nwidth %s %s" % (fmt(a, 5), fmt(b, 5), fmt(b - a, 3), cu),
                             xy=(0.5 * (a + b), -0.25), xytext=(0.5 * (a + b), -0.75 + 0.0 * k), fontsize=8,
                             color="darkgreen", ha="left", va="center",
                             arrowprops=dict(arrowstyle="->", color="darkgreen", lw=1.0))
        if "critical_value" in c:
            cvs = c["critical_value"][:]
            ax2.plot(cvs, np.full(cvs.shape, 0.32), "v", color="tab:red", ms=7,
                     label="critical speeds: " + ", ".join(fmt(cv) for cv in cvs))
        ax2.axvline(om, color="k", lw=1.5, label="ω of this run")
        ax2.set_xlim(wmin, wmax)
        ax2.set_ylim(-1, 1)
        ax2.set_yticks([])
        ax2.set_xlabel("spin speed ω %s" % ubr(cu))
        ax2.legend(fontsize=8, loc="upper right")
        rpm_axis(ax2, cu)
        ax2.set_title("stable speed intervals: %s" % intervals_text(lo, hi, units(c["stable_lo"])), fontsize=10)
    fig.suptitle("Rotor with ball autobalancer: stability of the balanced motion (3.14)%s" % status_note(h),
                 fontsize=11)
    save(fig, outdir, stem, "stability", written)


# ---- ensembles (autobal rotor ensemble | pendulum ensemble) ----------------------------------
# 1 balanced, 0 not balanced (archives without attractor classes), 10 + class for the members
# that did not balance when the archive has the classes (rotor: /rotor/ensemble/attractor, legend
# "0 unclassified, 1 balanced, 2 heavy_side, 3 fixed, 4 circulating, 5 periodic, 6 irregular"),
# -1 failed, -2 not run
OUTCOME_CODES = [1, 11, 12, 13, 14, 15, 16, 0, -1, -2]
OUTCOME_COLORS = {1: "#5cb85c", 11: "#a9dfa9", 12: "#f0ad4e", 13: "#9b59b6", 14: "#d9534f", 15: "#5bc0de",
                  16: "#8c564b", 0: "#e8787a", -1: "#444444", -2: "#ffffff"}
OUTCOME_NAMES = {1: "balanced", 11: "below balance_tol at the end (dwell unfinished)", 12: "heavy side",
                 13: "balls at rest elsewhere (fixed)", 14: "a ball circulating", 15: "periodic", 16: "irregular",
                 0: "not balanced by t_end", -1: "failed (solver status < 0)", -2: "not run yet"}


def ensemble_outcome(g):
    """Outcome per member from the archive's balanced, status and done: 1 balanced, 0 ran to its end
    without balancing, -1 failed, -2 not computed (an interrupted or time-limited run)."""
    bal = g["balanced"][()]
    st = g["status"][()] if "status" in g else np.zeros(np.shape(bal), int)
    done = g["done"][()] if "done" in g else np.ones(np.shape(bal), int)
    out = np.where(bal == 1, 1, 0)
    if "attractor" in g:  # what the members that did not balance settled to
        cls = np.asarray(g["attractor"][()], dtype=int)
        out = np.where((bal != 1) & (cls >= 1) & (cls <= 6), 10 + cls, out)
    out = np.where(st < 0, -1, out)
    return np.where(done == 0, -2, out).astype(int)


def outcome_image(ax, x, y, code):
    """Draw an outcome grid code[x, y] with a fixed colour per outcome; returns legend handles."""
    codes = sorted(OUTCOME_CODES)
    cmap = ListedColormap([OUTCOME_COLORS[c] for c in codes])
    norm = BoundaryNorm(np.arange(len(codes) + 1) - 0.5, cmap.N)
    index = np.searchsorted(codes, np.asarray(code))
    mesh(ax, x, y, index, cmap=cmap, norm=norm, edgecolors="face")
    return outcome_handles(code)


def outcome_handles(code):
    present = set(np.unique(code).astype(int).tolist())
    return [Patch(facecolor=OUTCOME_COLORS[c], edgecolor="k", lw=0.5, label=OUTCOME_NAMES[c])
            for c in OUTCOME_CODES if c in present]


def angle_ticks(axis_obj, vals, unit):
    """Ticks at multiples of pi/2 on an axis of angles in rad spanning about a full turn."""
    if unit != "rad" or not np.size(vals):
        return
    lo, hi = float(np.nanmin(vals)), float(np.nanmax(vals))
    if hi - lo < 2.0:
        return
    names = {-4: "-2π", -3: "-3π/2", -2: "-π", -1: "-π/2", 0: "0", 1: "π/2", 2: "π", 3: "3π/2", 4: "2π"}
    ks = [k for k in names if lo - 0.3 <= k * np.pi / 2 <= hi + 0.3]
    axis_obj.set_ticks([k * np.pi / 2 for k in ks])
    axis_obj.set_ticklabels([names[k] for k in ks])


def uword(u):
    """' UNIT' for a value in running text; nothing for a dimensionless one."""
    return "" if u in ("1", "") else " " + u


def ens_label(g, name):
    ds = g[name]
    ln = s(ds.attrs.get("long_name", ""))
    return "%s%s %s" % (name, (" (%s)" % ln) if ln and len(ln) <= 40 else "", ubr(units(ds)))


def binomial_fraction(ok, n):
    """Fraction and its binomial standard error sqrt(p (1 - p) / n) (NaN where n = 0)."""
    n = np.asarray(n, dtype=float)
    p = np.where(n > 0, np.asarray(ok, dtype=float) / np.maximum(n, 1), np.nan)
    return p, np.where(n > 0, np.sqrt(p * (1 - p) / np.maximum(n, 1)), np.nan)


def plot_ensemble(h, outdir, stem, written, model):
    """Basin map (outcome over the grid or the random samples), time to balance over the same plane,
    P(balance) along the first parameter with the archive's overall value and standard error, and the
    distribution of the time to balance."""
    g = h["%s/ensemble" % model]
    params = [p.strip() for p in s(g.attrs.get("parameters", "")).split(",") if p.strip()]
    random = s(g.attrs.get("mode", "grid")) == "random"
    code = ensemble_outcome(g)
    ttb = np.asarray(g["time_to_balance"][()], dtype=float) if "time_to_balance" in g else None
    tu = units(g["time_to_balance"]) if ttb is not None else "?"
    tname = "time to balance τ" if model == "pendulum" else "time to balance"
    fig, ax = plt.subplots(2, 2, figsize=(13, 10.5), constrained_layout=True)
    (a_map, a_ttb), (a_p, a_hist) = ax
    # (a) outcome and (b) time to balance over the parameter plane
    if not random and len(params) >= 2:
        x, y = g[params[0]][:], g[params[1]][:]
        c2, t2 = code, ttb
        note = ""
        if len(params) == 3:  # a third axis: the fraction balanced across it, and the mean time
            frac, _ = binomial_fraction(np.sum(code == 1, axis=2), np.sum(code >= 0, axis=2))
            im = mesh(a_map, x, y, frac, cmap="RdYlGn", vmin=0, vmax=1)
            a_map.set_facecolor("0.85")
            fig.colorbar(im, ax=a_map, label="fraction balanced over %s (grey: none ran)" % params[2])
            handles = []
            with warnings.catch_warnings():  # a column with no balanced member has no mean: NaN
                warnings.simplefilter("ignore", RuntimeWarning)
                t2 = np.nanmean(ttb, axis=2) if ttb is not None else None
            note = " (mean over %s)" % params[2]
        else:
            handles = outcome_image(a_map, x, y, c2)
        for a in (a_map, a_ttb):
            a.set_xlabel(ens_label(g, params[0]))
            a.set_ylabel(ens_label(g, params[1]))
            angle_ticks(a.xaxis, x, units(g[params[0]]))
            angle_ticks(a.yaxis, y, units(g[params[1]]))
        if t2 is not None and np.isfinite(t2).any():
            im = mesh(a_ttb, x, y, t2, cmap="viridis")
            fig.colorbar(im, ax=a_ttb, label="%s %s%s" % (tname, ubr(tu), note))
        a_ttb.set_facecolor("0.85")
        a_ttb.set_title("%s of the balanced members (grey: not balanced)" % tname, fontsize=10)
        a_map.set_title("basin map: outcome over the %d x %d grid%s" % (len(x), len(y), note), fontsize=10)
    elif random and len(params) >= 2:
        x, y = g[params[0]][()], g[params[1]][()]
        for c in OUTCOME_CODES:
            sel = code == c
            if sel.any():
                a_map.scatter(x[sel], y[sel], s=10, color=OUTCOME_COLORS[c], edgecolors="k", linewidths=0.2)
        handles = outcome_handles(code)
        bal = np.isfinite(ttb) if ttb is not None else np.zeros(code.shape, bool)
        if bal.any():
            sc = a_ttb.scatter(x[bal], y[bal], c=ttb[bal], s=10, cmap="viridis")
            fig.colorbar(sc, ax=a_ttb, label="%s %s" % (tname, ubr(tu)))
        a_ttb.scatter(x[~bal], y[~bal], s=6, color="0.7", label="not balanced")
        for a in (a_map, a_ttb):
            a.set_xlabel(ens_label(g, params[0]))
            a.set_ylabel(ens_label(g, params[1]))
            angle_ticks(a.xaxis, x, units(g[params[0]]))
            angle_ticks(a.yaxis, y, units(g[params[1]]))
        a_map.set_title("outcome of %d random members (seed %s)" % (code.size, s(g.attrs.get("seed", "?"))),
                        fontsize=10)
        a_ttb.set_title("%s of the balanced members (grey: not balanced)" % tname, fontsize=10)
    else:  # one parameter: outcome strip and time to balance along it
        x = g[params[0]][()]
        if random:
            for c in OUTCOME_CODES:
                sel = code == c
                if sel.any():
                    a_map.plot(x[sel], np.full(sel.sum(), 0.0) + 0.3 * (np.arange(sel.sum()) % 5) / 5, "|",
                               color=OUTCOME_COLORS[c] if c != -2 else "0.6", ms=14)
            handles = outcome_handles(code)
        else:
            handles = outcome_image(a_map, x, np.array([0.0, 1.0]), np.column_stack([code, code]))
        a_map.set_yticks([])
        a_map.set_xlabel(ens_label(g, params[0]))
        angle_ticks(a_map.xaxis, x, units(g[params[0]]))
        a_map.set_title("outcome along %s (%d members)" % (params[0], code.size), fontsize=10)
        if ttb is not None:
            a_ttb.plot(x, ttb, ".", color="tab:blue", ms=5)
        a_ttb.set_xlabel(ens_label(g, params[0]))
        a_ttb.set_ylabel("%s %s" % (tname, ubr(tu)))
        angle_ticks(a_ttb.xaxis, x, units(g[params[0]]))
        a_ttb.grid(True, alpha=0.3)
        a_ttb.set_xlim(a_map.get_xlim())
        a_ttb.set_title("%s of the balanced members" % tname, fontsize=10)
    if handles:
        a_map.legend(handles=handles, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=4,
                     frameon=False)
    # (c) P(balance) along the first parameter, with the archive's overall value
    ran = code >= 0  # members that ran without failure
    p_all = param(g, "probability_balanced", np.nan)
    p_se = param(g, "probability_balanced_stderr", np.nan)
    if not random:
        x1 = g[params[0]][:]
        axes_other = tuple(range(1, code.ndim))
        nb = np.sum(code == 1, axis=axes_other)
        nr = np.sum(ran, axis=axes_other)
        pp, se = binomial_fraction(nb, nr)
        a_p.errorbar(x1, pp, yerr=se, fmt="o-", ms=3.5, lw=1.0, capsize=2, color="tab:green",
                     label="fraction balanced at each %s%s ± binomial s.e." % (
                         params[0], (" (over %s)" % ", ".join(params[1:])) if len(params) > 1 else ""))
    else:
        x1 = g[params[0]][()]
        lo1, hi1 = param(g, "%s_min" % params[0], float(np.min(x1))), param(g, "%s_max" % params[0], float(np.max(x1)))
        nbins = int(np.clip(np.sqrt(max(code.size, 1)) / 2, 4, 24))
        edges = np.linspace(lo1, hi1, nbins + 1)
        idx = np.clip(np.digitize(x1, edges) - 1, 0, nbins - 1)
        nb = np.bincount(idx[code == 1], minlength=nbins)
        nr = np.bincount(idx[ran], minlength=nbins)
        pp, se = binomial_fraction(nb, nr)
        cen = 0.5 * (edges[1:] + edges[:-1])
        a_p.errorbar(cen, pp, yerr=se, xerr=0.5 * (edges[1] - edges[0]), fmt="o", ms=3.5, capsize=2,
                     color="tab:green", label="fraction balanced in %d bins of %s ± binomial s.e." % (nbins, params[0]))
        x1 = edges
        a_p.set_xlim(edges[0], edges[-1])
    if np.isfinite(p_all):
        a_p.axhspan(p_all - (p_se if np.isfinite(p_se) else 0), p_all + (p_se if np.isfinite(p_se) else 0),
                    color="k", alpha=0.12, lw=0)
        a_p.axhline(p_all, color="k", lw=1.2, ls="--",
                    label="P(balance) = %s ± %s (archive: %d of the %d members that ran without failure)"
                    % (fmt(p_all, 4), fmt(p_se, 2), int(param(g, "n_balanced", 0) or 0),
                       int((param(g, "n_done", 0) or 0) - (param(g, "n_failed", 0) or 0))))
    a_p.set_ylim(-0.03, 1.12)
    a_p.set_xlabel(ens_label(g, params[0]))
    a_p.set_ylabel("P(balance) [–]")
    angle_ticks(a_p.xaxis, x1, units(g[params[0]]))
    a_p.grid(True, alpha=0.3)
    a_p.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12), frameon=False)
    short = dict(OUTCOME_NAMES)
    short.update({11: "below tol", 12: "heavy side", 13: "fixed", 14: "circulating"})
    counts = ", ".join("%s %d" % (short[c].split(" (")[0], int(np.sum(code == c)))
                       for c in OUTCOME_CODES if np.any(code == c))
    a_p.set_title("probability of balancing along %s; %s" % (params[0], counts), fontsize=10)
    # (d) distribution of the time to balance
    if ttb is not None and np.isfinite(ttb).any():
        tt = ttb[np.isfinite(ttb)]
        a_hist.hist(tt, bins=int(np.clip(np.sqrt(tt.size) * 1.5, 8, 60)), color="tab:blue", alpha=0.8,
                    edgecolor="white", lw=0.4)
        for key, ls, lab in (("time_to_balance_mean", "--", "mean"), ("time_to_balance_median", ":", "median"),
                             ("time_to_balance_max", "-.", "max")):
            v = param(g, key)
            if v is not None and np.isfinite(v):
                a_hist.axvline(v, color="k", ls=ls, lw=1.2, label="%s %s%s" % (lab, fmt(v), uword(tu)))
        t_end = param(g, "t_end")
        a_hist.set_xlabel("%s %s" % (tname, ubr(tu)))
        a_hist.set_ylabel("members")
        a_hist.legend(fontsize=8, loc="best", framealpha=0.92)
        a_hist.set_title("distribution of the %s (%d balanced members; run length t_end = %s%s)"
                         % (tname, tt.size, fmt(t_end) if t_end is not None else "?", uword(tu)), fontsize=10)
        a_hist.grid(True, alpha=0.3)
    else:
        a_hist.text(0.5, 0.5, "no member balanced: no time to balance", ha="center", va="center",
                    transform=a_hist.transAxes)
        a_hist.set_axis_off()
    if model == "rotor":
        om = param(h["rotor"], "omega", np.nan)
        what = "Rotor with ball autobalancer" + ("" if "omega" in params else
                                                 ", ω = %s %s" % (fmt(om), punit(h["rotor"], "omega")))
    else:
        fixed = pendulum_params_text(h, skip=params)
        what = "Two-pendulum autobalancer" + (", " + fixed if fixed else "")
    grid = "random, %d members" % code.size if random else " x ".join(
        "%s[%d]" % (p, n) for p, n in zip(params, np.shape(code)))
    fig.suptitle("%s: ensemble of transients over %s (%s)\nP(balance) = %s ± %s, tolerance %s%s"
                 % (what, ", ".join(params), grid, fmt(p_all, 4), fmt(p_se, 2),
                    fmt(param(g, "balance_tol", np.nan), 3), status_note(h)), fontsize=11)
    save(fig, outdir, stem, "ensemble", written)


def plot_rotor_ensemble(h, outdir, stem, written):
    plot_ensemble(h, outdir, stem, written, "rotor")


def plot_pendulum_ensemble(h, outdir, stem, written):
    plot_ensemble(h, outdir, stem, written, "pendulum")


GRADES = (0.4, 1.0, 2.5, 6.3, 16.0, 40.0, 100.0, 250.0, 630.0, 1600.0)


def ensemble_unbalance(h):
    """Per-member residual unbalance (g mm) and grade (mm/s) of the members that ran without failure,
    the grade statistics' attributes and a label of the run."""
    g = h["rotor/ensemble"]
    u = np.asarray(g["residual_unbalance_abs_final"][()], dtype=float).ravel()
    gr = np.asarray(g["balance_grade_final"][()], dtype=float).ravel()
    st = np.asarray(g["status"][()]).ravel()
    done = np.asarray(g["done"][()]).ravel() if "done" in g else np.ones_like(st)
    ok = (st >= 0) & (done == 1) & np.isfinite(u) & np.isfinite(gr)
    if unit_factor_ok(g["residual_unbalance_abs_final"]) is None:
        raise NotImplementedError("residual_unbalance_abs_final: units '%s', not kg m"
                                  % units(g["residual_unbalance_abs_final"]))
    stats = dict(g["statistics/balance_grade_final"].attrs) if "statistics/balance_grade_final" in g else {}
    law = s(g.attrs.get("friction", "none"))
    if law == "exact" and "ball_f" in h["rotor/plane1"].attrs:
        pa = h["rotor/plane1"].attrs
        label = "stiction: f = %s, μ = %s" % (fmt(np.max(pa["ball_f"]), 3), fmt(np.max(pa["ball_mu"]), 3))
    elif law != "none":
        label = "friction: %s law" % law
    else:
        label = "no friction"
    if "ball_diameter" in h["rotor/plane1"].attrs:  # ball size and contact
        dia = np.atleast_1d(h["rotor/plane1"].attrs["ball_diameter"])
        e = g.attrs.get("contact_restitution")
        label += " + contact (%s mm%s)" % (fmt(np.max(dia) * 1e3, 3), ", e = %s" % fmt(float(e), 3) if e is not None else "")
    return u[ok] * 1e6, gr[ok], stats, label, int(np.sum(~ok))


def unit_factor_ok(ds):
    return 1.0 if units(ds) == "kg m" else None


def plot_rotor_unbalance(h, outdir, stem, written, compare=None):
    """Distribution of the residual unbalance at the end over the ensemble's members: empirical CDF
    in g mm on a log axis with the permissible unbalance of the ISO 21940-11 grades (U = G m / Omega,
    from the members' own U/G ratio), and the grades' histogram with the target and P(G <= target)."""
    runs = [(h, ensemble_unbalance(h))]
    if compare is not None:
        runs.append((compare, ensemble_unbalance(compare)))
        if runs[0][1][3] == runs[1][1][3]:  # the same friction (e.g. two drives): name the files
            runs = [(hh, r[:3] + ("%s, %s" % (os.path.splitext(os.path.basename(hh.filename))[0], r[3]),) + r[4:])
                    for hh, r in runs]
    fig, (a_cdf, a_hist) = plt.subplots(1, 2, figsize=(13, 5.8), constrained_layout=True)
    colors = ["tab:red", "tab:blue"]
    allu = np.concatenate([r[1][0] for r in runs])
    if allu.size == 0 or not np.all(allu > 0):
        raise NotImplementedError("no positive residual unbalance to draw on a log axis")
    ratio = None
    for (hh, (u, gr, stats, label, nbad)), c in zip(runs, colors):
        if u.size == 0:
            continue
        x = np.sort(u)
        a_cdf.step(x, np.arange(1, x.size + 1) / x.size, where="post", color=c, lw=1.8,
                   label="%s\n(%d members%s): median %s g mm, G %s"
                   % (label, u.size, ", %d failed" % nbad if nbad else "", fmt(np.median(u), 3),
                      fmt(np.median(gr), 3)))
        r = u / gr  # g mm per mm/s: m / (n_planes Omega), the same for all members at one final speed
        if ratio is None and np.all(gr > 0):
            ratio = np.median(r)
            spread = np.max(np.abs(r / ratio - 1))
        lg = np.log10(gr[gr > 0])
        bins = np.linspace(np.floor(np.log10(np.min(allu / np.median(r)))), np.ceil(np.max(lg)) + 0.01, 41) \
            if lg.size else 10
        a_hist.hist(gr[gr > 0], bins=10 ** np.asarray(bins), color=c, alpha=0.55, label=label)
        if "target" in stats and stats.get("n_evaluated", 0):
            a_hist.axvline(stats["target"], color="k", lw=1.2, ls="--")
            a_hist.text(0.02, 0.96 - 0.11 * colors.index(c), "%s:\nP(G ≤ %s mm/s) = %s (%d of %d), Wilson 95%% [%s, %s]"
                        % (label, fmt(stats["target"], 3), fmt(stats["probability_within_target"], 3),
                           stats["n_within_target"], stats["n_evaluated"],
                           fmt(stats["probability_within_target_wilson_low"], 3),
                           fmt(stats["probability_within_target_wilson_high"], 3)),
                        transform=a_hist.transAxes, fontsize=8, color=c, va="top")
    a_cdf.set_xscale("log")
    lo, hi = np.min(allu) / 2, np.max(allu) * 2
    if ratio is not None:
        for G in GRADES:
            U = G * ratio
            if lo <= U <= hi:
                a_cdf.axvline(U, color="0.5", lw=0.8, ls=":")
                a_cdf.text(U, 0.02, " G%s" % fmt(G, 3), rotation=90, fontsize=8, color="0.3", va="bottom")
        note = "" if spread < 1e-6 else " (U/G varies by %s between members: lines at the median)" % fmt(spread, 2)
        a_cdf.set_title("residual unbalance at the end: empirical CDF; dotted: permissible U of the grades%s" % note,
                        fontsize=9)
    a_cdf.set_xlim(lo, hi)
    a_cdf.set_ylim(0, 1.02)
    a_cdf.set_xlabel("residual unbalance U at the end (g mm, the worst plane)")
    a_cdf.set_ylabel("fraction of members with U below")
    a_cdf.grid(True, which="both", alpha=0.3)
    a_cdf.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1)
    a_hist.set_xscale("log")
    a_hist.set_xlabel("balance quality grade G at the end (mm/s, ISO 21940-11); dashed: the target")
    a_hist.set_ylabel("members")
    a_hist.grid(True, which="both", alpha=0.3)
    a_hist.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1)
    a_hist.set_title("grade distribution", fontsize=9)
    g = h["rotor/ensemble"]
    params = s(g.attrs.get("parameters", ""))
    fig.suptitle("Rotor ensemble: residual unbalance over %s (%s, %d members)%s"
                 % (params, s(g.attrs.get("mode", "?")), int(param(g, "n_members", 0)), status_note(h)), fontsize=11)
    save(fig, outdir, stem, "unbalance", written)


PLOTTERS = [
    ("pendulum/critical/curves", plot_pendulum_critical),
    ("pendulum/map", plot_pendulum_map),
    ("pendulum/sweep", plot_pendulum_sweep),
    ("pendulum/roots", plot_pendulum_roots),
    ("pendulum/transient", plot_pendulum_transient),
    ("rotor/transient", plot_rotor_transient),
    ("rotor/runup", plot_rotor_runup),
    ("rotor/stability", plot_rotor_stability),
    ("rotor/sweep", plot_rotor_sweep),
    ("rotor/map", plot_rotor_map),
    ("rotor/campbell", plot_rotor_campbell),
    ("rotor/ensemble", plot_rotor_ensemble),
    ("rotor/ensemble/residual_unbalance_abs_final", plot_rotor_unbalance),
    ("pendulum/ensemble", plot_pendulum_ensemble),
]


class ArchiveError(Exception):
    pass


def open_archive(path):
    if not os.path.exists(path):
        raise ArchiveError("cannot open archive '%s': no such file" % path)
    if os.path.isdir(path):
        raise ArchiveError("cannot open archive '%s': is a directory" % path)
    try:
        h = h5py.File(path, "r")
    except OSError as e:
        raise ArchiveError("'%s' is not a readable HDF5 file (%s)" % (path, e))
    if "autobal-1" not in s(h.attrs.get("Conventions", "")).replace(",", " ").split():
        h.close()
        raise ArchiveError("'%s' is an HDF5 file but not an autobal archive (no Conventions = autobal-1)" % path)
    return h


def plot_archive(path, outdir=".", stem=None, notes=None, compare=None):
    """Draw every picture this script knows for the archive; returns the list of PNG paths.  compare: a
    second rotor ensemble archive whose residual unbalance is drawn beside this one's."""
    if stem is None:
        stem = os.path.splitext(os.path.basename(path))[0]
    os.makedirs(outdir, exist_ok=True)
    written = []
    with open_archive(path) as h:
        for group, fn in PLOTTERS:
            if group in h:
                try:
                    if fn is plot_rotor_unbalance and compare is not None:
                        with open_archive(compare) as hc:
                            if "rotor/ensemble/residual_unbalance_abs_final" not in hc:
                                raise ArchiveError("--compare '%s': no /rotor/ensemble/residual_unbalance_abs_final "
                                                   "(run it with ensemble.write_unbalance = true)" % compare)
                            fn(h, outdir, stem, written, compare=hc)
                    else:
                        fn(h, outdir, stem, written)
                except NotImplementedError as e:
                    if notes is not None:
                        notes.append(str(e))
    return written


def main(argv=None):
    ap = argparse.ArgumentParser(description="PNG pictures of an autobal HDF5 archive (reads only the archive).")
    ap.add_argument("archive", help="FILE.h5 written by autobal")
    ap.add_argument("-o", "--outdir", default=".", help="directory for the PNG files (created; default: .)")
    ap.add_argument("--stem", default=None, help="file name prefix (default: archive name without .h5)")
    ap.add_argument("-q", "--quiet", action="store_true", help="do not list the files written")
    ap.add_argument("--compare", default=None, metavar="B.h5",
                    help="a second rotor ensemble (write_unbalance = true) drawn beside the first in <stem>_unbalance.png")
    args = ap.parse_args(argv)
    notes = []
    if args.outdir == "":
        sys.stderr.write("autobal_plot.py: error: -o needs a directory name (it is empty)\n")
        return 2
    if os.path.exists(args.outdir) and not os.path.isdir(args.outdir):
        sys.stderr.write("autobal_plot.py: error: -o '%s' exists and is not a directory (the pictures go into a "
                         "directory)\n" % args.outdir)
        return 4
    try:
        written = plot_archive(args.archive, args.outdir, args.stem, notes, args.compare)
    except ArchiveError as e:
        sys.stderr.write("autobal_plot.py: error: %s\n" % e)
        return 4
    except OSError as e:  # the output directory cannot be created or written
        sys.stderr.write("autobal_plot.py: error: cannot write the pictures into '%s': %s\n"
                         % (args.outdir, e.strerror or e))
        return 4
    for n in notes:
        sys.stderr.write("autobal_plot.py: note: %s\n" % n)
    if not written:
        with h5py.File(args.archive, "r") as h:
            groups = []
            h.visit(lambda n: groups.append("/" + n) if isinstance(h[n], h5py.Group) else None)
        sys.stderr.write("autobal_plot.py: nothing to draw in '%s' (groups: %s)\n"
                         % (args.archive, ", ".join(groups) or "none"))
        return 3
    if not args.quiet:
        for w in written:
            print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main())
