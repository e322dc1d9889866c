#!/usr/bin/env python3
"""Plots for the output folder of `condyn compare`.

Draws four figures into DIR, each as PNG and SVG:
  work_precision   error against median wall time per scheme (log-log), points labelled by rtol;
                   against a published reference (runs.json reference.kind "published"): the
                   significant correct digits of the positions (mescd_u) against wall time
  drift            position-constraint drift against time per scheme (log y)
  multipliers      Lagrange multiplier histories, one panel per scheme
  baumgarte_study  max position drift over the Baumgarte (alpha, beta) grid, and step counts

Run:   /usr/bin/python3 validation/plot_compare.py DIR
Needs: matplotlib and numpy (Debian: apt-get install python3-matplotlib python3-numpy).

Input contract: the files written by `condyn compare SCENE --out-dir DIR` (runs.csv, runs.json,
drift_<scheme>.csv, history_<scheme>.csv, baumgarte_study.csv) as defined in
validation/compare-output.md. A plot whose inputs are absent or empty is skipped with a note on
stdout; failed runs (status != ok or empty numbers) are left out of the plots.

Exit status: 0 done (some plots may be skipped), 1 a plot raised an error (the others are still
written), 2 bad usage, 3 matplotlib not importable.
"""
import csv
import glob
import json
import math
import os
import sys

# Fixed, so that a scheme keeps its colour across figures and across runs of the script.
SCHEME_COLOURS = {
    "elimination": "#000000", "index1": "#1f77b4", "baumgarte": "#ff7f0e", "ggl": "#2ca02c",
    "index2": "#d62728", "index3": "#9467bd", "penalty": "#8c564b", "projection": "#e377c2",
}
SCHEME_MARKERS = dict(zip(SCHEME_COLOURS, "osD^v<>P"))
EXTRA_COLOURS = ["#7f7f7f", "#bcbd22", "#17becf"]
_extra = {}
ERROR_COLUMNS = ("error_u", "error_v", "error_reaction")
# Drift of an exactly satisfied constraint is 0, which a log axis cannot show.
FLOOR = 1e-18


def note(msg):
    print(f"plot_compare: {msg}")


def colour(scheme):
    if scheme in SCHEME_COLOURS:
        return SCHEME_COLOURS[scheme]
    return _extra.setdefault(scheme, EXTRA_COLOURS[len(_extra) % len(EXTRA_COLOURS)])


def scheme_key(scheme):
    order = list(SCHEME_COLOURS)
    return (order.index(scheme) if scheme in order else len(order), scheme)


def num(value):
    """Float of a CSV or JSON field; None for empty, null, unparsable or non-finite."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def fmt_tol(x):
    """1e-06 or 0.0001 -> 1e-6, 1e-4: the form tolerances are written in."""
    mantissa, exponent = f"{x:.2e}".split("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"


def read_csv(path):
    """Rows as dicts, or None when the file is absent or has no data rows."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f)) or None


def column(np, rows, name):
    """One CSV column as floats, NaN where a value is missing, so plots show gaps."""
    return np.array([np.nan if num(r.get(name)) is None else num(r.get(name)) for r in rows])


def per_scheme_files(d, prefix):
    paths = glob.glob(os.path.join(d, f"{prefix}_*.csv"))
    named = {os.path.basename(p)[len(prefix) + 1:-4]: p for p in paths}
    return [(s, named[s]) for s in sorted(named, key=scheme_key)]


def load_meta(d):
    path = os.path.join(d, "runs.json")
    if not os.path.isfile(path):
        return {}
    try:
        with open(path) as f:
            meta = json.load(f)
    except (OSError, ValueError) as e:
        note(f"runs.json unreadable ({e}); titles lack the scene name")
        return {}
    return meta if isinstance(meta, dict) else {}


def save(plt, fig, d, name):
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(d, f"{name}.{ext}"), dpi=150)
    plt.close(fig)
    note(f"wrote {name}.png, {name}.svg")


def plot_work_precision(plt, np, d, meta, scene):
    runs = read_csv(os.path.join(d, "runs.csv")) or meta.get("runs")
    if not runs:
        return note("work_precision skipped: runs.csv absent or empty")
    ref = meta.get("reference") or {}
    # Against a published reference state (a test-set benchmark) the figure of merit is the test
    # set's own: significant correct digits (mescd) of the positions, higher is better.
    digits = ref.get("kind") == "published"
    by_scheme = {}
    for r in runs:
        by_scheme.setdefault(str(r.get("scheme") or "?"), []).append(r)
    fig, ax = plt.subplots(figsize=(10, 6))
    drawn = dropped = 0
    for scheme in sorted(by_scheme, key=scheme_key):
        points, failed = [], 0
        for r in by_scheme[scheme]:
            if digits:
                y = num(r.get("mescd_u"))
                measures = [] if y is None else [y]
            else:
                measures = [e for e in (num(r.get(c)) for c in ERROR_COLUMNS) if e is not None]
            wall, rtol = num(r.get("wall_median_s")), num(r.get("rtol"))
            if r.get("status") != "ok" or not measures or wall is None or rtol is None:
                failed += 1
            elif wall <= 0 or (not digits and max(measures) <= 0):
                dropped += 1
            else:
                points.append((rtol, wall, max(measures)))
        style = dict(color=colour(scheme), marker=SCHEME_MARKERS.get(scheme, "o"))
        if not points:
            note(f"work_precision: no usable run of {scheme}")
            ax.plot([], [], ls="none", label=f"{scheme} (all failed)", **style)
            continue
        points.sort(reverse=True)  # loose to tight tolerance
        label = scheme + (f" ({failed} of {len(by_scheme[scheme])} failed)" if failed else "")
        ax.plot([p[1] for p in points], [p[2] for p in points], label=label, **style)
        for rtol, wall, err in points:
            ax.annotate(fmt_tol(rtol), (wall, err), xytext=(5, 4), textcoords="offset points",
                        fontsize=7, color=style["color"])
        drawn += 1
    if dropped:
        note(f"work_precision: {dropped} run(s) with zero error or wall time dropped (log axes)")
    if not drawn:
        plt.close(fig)
        return note("work_precision skipped: no successful run")
    ax.set_xscale("log")
    ax.set_xlabel("wall time per run, median [s]")
    reference = ref.get("description") or "unknown reference"
    if digits:
        trusted = num(ref.get("trusted_digits_u"))
        if trusted is not None:
            # Beyond the reference's own accuracy, more digits only mean agreement with its error.
            ax.axhspan(trusted, max(trusted + 1, ax.get_ylim()[1]), color="lightgray", alpha=0.5,
                       label=f"beyond the reference's trust ({trusted:g} digits)")
        ax.set_ylabel("significant correct digits in positions (mescd) [-]")
        ax.set_title(f"Work-precision: {scene}\ndigits against {reference}", fontsize=11)
        footer = ("mescd = min_i -log10(|y_i - ref_i| / (atol/rtol + |ref_i|)) at t_end "
                  "(Test Set for IVP Solvers); point labels = rtol; failed runs omitted")
    else:
        ax.set_yscale("log")
        ax.set_ylabel("error (relative max-norm) [-]")
        ax.set_title(f"Work-precision: {scene}\nerror against {reference}", fontsize=11)
        footer = ("error = max(error_u, error_v, error_reaction); point labels = rtol; "
                  "failed runs omitted")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(title="scheme", fontsize=9, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.text(0.01, 0.01, footer, fontsize=7, color="dimgray")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    save(plt, fig, d, "work_precision")


def plot_drift(plt, np, d, scene, at_rtol):
    fig, ax = plt.subplots(figsize=(10.5, 5.5))
    drawn, clipped_any = 0, False
    for scheme, path in per_scheme_files(d, "drift"):
        rows = read_csv(path) or []
        pairs = [(num(r.get("t")), num(r.get("drift_position"))) for r in rows]
        pairs = [p for p in pairs if None not in p]
        if not pairs:
            note(f"drift: {os.path.basename(path)} empty, {scheme} left out")
            continue
        t, y = np.array(pairs).T
        clipped = y < FLOOR
        clipped_any |= bool(clipped.any())
        label = scheme + (" (all below floor)" if clipped.all() else "")
        ax.plot(t, np.maximum(y, FLOOR), color=colour(scheme), lw=1.2, label=label)
        drawn += 1
    if not drawn:
        plt.close(fig)
        return note("drift skipped: no drift_<scheme>.csv with data")
    if clipped_any:
        ax.axhline(FLOOR, color="gray", ls=":", lw=0.8)
    ax.set_yscale("log")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("position drift max |A u - g| [length]\n"
                  f"(values below {FLOOR:g}, e.g. exact 0, drawn at {FLOOR:g})")
    ax.set_title(f"Position-constraint drift at every internal step: {scene}\n"
                 f"(runs at rtol = {at_rtol})", fontsize=11)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(title="scheme", fontsize=9, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    save(plt, fig, d, "drift")


def plot_multipliers(plt, np, d, scene, at_rtol):
    panels = []
    for scheme, path in per_scheme_files(d, "history"):
        rows = read_csv(path) or []
        columns = [c for c in (rows[0] if rows else {}) if c and c.startswith("lambda_")]
        series = {c: column(np, rows, c) for c in columns}
        series = {c: y for c, y in series.items() if np.isfinite(y).any()}
        t = column(np, rows, "t")
        if series:
            panels.append((scheme, t, series))
        else:
            note(f"multipliers: no values in {os.path.basename(path)}, {scheme} left out")
    if not panels:
        return note("multipliers skipped: no history_<scheme>.csv with lambda_ columns")
    names = list(dict.fromkeys(c for _, _, s in panels for c in s))
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    line_colour = {c: cycle[i % len(cycle)] for i, c in enumerate(names)}
    fig, axes = plt.subplots(len(panels), 1, sharex=True, squeeze=False,
                             figsize=(9, 1.2 + 2.3 * len(panels)))
    for ax, (scheme, t, series) in zip(axes[:, 0], panels):
        for c, y in series.items():
            ax.plot(t, y, color=line_colour[c], lw=1.2, label=c[len("lambda_"):])
        ax.set_title(f"scheme: {scheme}", color=colour(scheme), loc="left", fontsize=10)
        ax.set_ylabel("multiplier lambda [force]", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(title="constraint", fontsize=8, title_fontsize=8, loc="upper left",
                  bbox_to_anchor=(1.01, 1.0), ncol=1 + len(series) // 12)
    axes[-1, 0].set_xlabel("time [s]")
    fig.suptitle(f"Constraint multipliers (reaction forces) at the output times: {scene}\n"
                 f"(runs at rtol = {at_rtol})", fontsize=11)
    fig.tight_layout()
    save(plt, fig, d, "multipliers")


def heat_map(plt, np, fig, ax, grid, labels, norm, cmap, bar_label, axes_values, default):
    cmap = plt.get_cmap(cmap).copy()
    cmap.set_bad("lightgray")  # failed or absent grid points
    cmap.set_under("white")  # exactly zero drift: below any log scale
    image = ax.imshow(np.ma.masked_invalid(grid), origin="lower", aspect="auto", cmap=cmap,
                      norm=norm)
    fig.colorbar(image, ax=ax, label=bar_label)
    if grid.size <= 100:  # cell labels stay legible only on small grids
        for (i, j), v in np.ndenumerate(grid):
            dark = np.isfinite(v) and np.dot(image.to_rgba(v)[:3], (0.299, 0.587, 0.114)) < 0.5
            ax.text(j, i - 0.12 if (j, i) == default else i, labels[i][j], ha="center",
                    va="center", fontsize=8, color="white" if dark else "black")
    if default is not None:
        ax.plot(*default, marker="*", ms=16, mfc="white", mec="black", mew=1.2, ls="none")
        ax.annotate("default", default, xytext=(0, 10), textcoords="offset points",
                    ha="center", fontsize=8, fontweight="bold",
                    bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8))
    alphas, betas = axes_values
    ax.set_xticks(range(len(alphas)), [f"{a:.3g}" for a in alphas])
    ax.set_yticks(range(len(betas)), [f"{b:.3g}" for b in betas])
    ax.set_xlabel("alpha (damping gain) [1/s]")
    ax.set_ylabel("beta (stiffness gain) [1/s]")


def plot_baumgarte(plt, np, d, scene):
    from matplotlib.colors import LogNorm, Normalize
    rows = read_csv(os.path.join(d, "baumgarte_study.csv")) or []
    rows = [r for r in rows if num(r.get("alpha")) is not None and num(r.get("beta")) is not None]
    if not rows:
        return note("baumgarte_study skipped: baumgarte_study.csv absent or without grid points")
    alphas = sorted({num(r["alpha"]) for r in rows})
    betas = sorted({num(r["beta"]) for r in rows})
    drift = np.full((len(betas), len(alphas)), np.nan)
    steps = drift.copy()
    drift_text = [["no run"] * len(alphas) for _ in betas]
    steps_text = [row[:] for row in drift_text]
    default = None
    for r in rows:
        i, j = betas.index(num(r["beta"])), alphas.index(num(r["alpha"]))
        if num(r.get("default")) == 1:
            default = (j, i)
        dp, n = num(r.get("max_drift_position")), num(r.get("steps"))
        if r.get("status") != "ok":
            drift_text[i][j] = steps_text[i][j] = "failed"
            continue
        drift_text[i][j] = steps_text[i][j] = "n/a"  # ok run, value missing unless set below
        if dp is not None:
            drift[i, j], drift_text[i][j] = dp, f"{dp:.1e}" if dp else "0"
        if n is not None:
            steps[i, j], steps_text[i][j] = n, f"{n:.0f}"
    positive = drift[np.isfinite(drift) & (drift > 0)]
    if not positive.size:
        return note("baumgarte_study skipped: no successful grid point with positive drift")
    lo, hi = positive.min(), positive.max()
    if (drift <= 0).any():
        note("baumgarte_study: zero drift drawn white (below the log colour scale)")
        drift[drift <= 0] = lo / 10
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5.5))
    heat_map(plt, np, fig, left, drift, drift_text, LogNorm(lo / 2, hi * 2) if lo == hi else
             LogNorm(lo, hi), "viridis", "max over the run of |A u - g| [length]",
             (alphas, betas), default)
    left.set_title("max position drift over the run (log colour)", fontsize=10)
    finite = steps[np.isfinite(steps)]
    heat_map(plt, np, fig, right, steps, steps_text,
             Normalize(finite.min(), finite.max()) if finite.size else None, "cividis",
             "integrator steps [-]", (alphas, betas), default)
    right.set_title("integrator steps", fontsize=10)
    fig.suptitle(f"Baumgarte gain study: {scene}\n"
                 r"constraint error obeys $e'' + 2\alpha e' + \beta^2 e = 0$;"
                 " grey = failed run or missing value; star = default gains", fontsize=11)
    fig.tight_layout()
    save(plt, fig, d, "baumgarte_study")


def main(argv):
    if len(argv) != 2 or not os.path.isdir(argv[1]):
        print("usage: plot_compare.py DIR   (DIR: output folder of `condyn compare`)"
              + (f"\nplot_compare: not a directory: {argv[1]}" if len(argv) == 2 else ""),
              file=sys.stderr)
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np
    except ImportError:
        print("plot_compare: matplotlib not available, plots skipped")
        return 3
    d = argv[1]
    meta = load_meta(d)
    scene = meta.get("scene") or "unknown scene"
    at_rtol = fmt_tol(num(meta["drift_rtol"])) if num(meta.get("drift_rtol")) else "drift_rtol"
    status = 0
    for name, draw in (
            ("work_precision", lambda: plot_work_precision(plt, np, d, meta, scene)),
            ("drift", lambda: plot_drift(plt, np, d, scene, at_rtol)),
            ("multipliers", lambda: plot_multipliers(plt, np, d, scene, at_rtol)),
            ("baumgarte_study", lambda: plot_baumgarte(plt, np, d, scene))):
        try:
            draw()
        except Exception as e:  # one malformed file must not cost the other plots
            note(f"{name} failed: {type(e).__name__}: {e}")
            plt.close("all")
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
