#!/usr/bin/env python3
"""Plots for the output folder of `condyn compare`.

Draws into DIR, each as PNG and PDF, sized for print (validation/compare-output.md, docs/plots.md):
  work_precision   error of u, u' and f_con against median wall time, one panel each (log-log);
                   against a published reference: correct digits (mescd) of u and u'
  error_steps      the same against integrator steps (no timing noise)
  drift            running max of the position and velocity residuals; failed runs marked
  multipliers      max |lambda - lambda_ref| / max |lambda_ref| against t per scheme
  baumgarte_study  error, drift and steps over the (alpha, beta) grid (log colour)

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
# Dashes too, so that curves which coincide (index1 and baumgarte on a linear scene) both show.
SCHEME_DASHES = dict(zip(SCHEME_COLOURS, ["-", "-", "--", "-", "-.", "-", ":", "--"]))
EXTRA_COLOURS = ["#7f7f7f", "#bcbd22", "#17becf"]
_extra = {}
ERROR_COLUMNS = ("error_u", "error_v", "error_reaction")
# Drift of an exactly satisfied constraint is 0, which a log axis cannot show.
FLOOR = 1e-18
# PNG for screens, PDF (vector) for papers.
FORMATS = ("png", "pdf")


def note(msg):
    print(f"plot_compare: {msg}")


def colour(scheme):
    if scheme in SCHEME_COLOURS:
        return SCHEME_COLOURS[scheme]
    return _extra.setdefault(scheme, EXTRA_COLOURS[len(_extra) % len(EXTRA_COLOURS)])


def line_style(scheme):
    """Colour and dash pattern of a scheme's curve over time (drift, multipliers)."""
    return dict(color=colour(scheme), ls=SCHEME_DASHES.get(scheme, "-"))


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
    named.pop("reference", None)  # history_reference.csv: the reference's, not a scheme's
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
    for ext in FORMATS:
        fig.savefig(os.path.join(d, f"{name}.{ext}"), dpi=300 if ext == "png" else None)
    plt.close(fig)
    note("wrote " + ", ".join(f"{name}.{ext}" for ext in FORMATS))


def paper_style(plt):
    """8-9 pt text, thin lines: legible when the figure is printed at its own size (3.5 in for a
    single column, 7.2 in across a page)."""
    plt.rcParams.update({
        "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "xtick.labelsize": 8,
        "ytick.labelsize": 8, "legend.fontsize": 8, "legend.title_fontsize": 8,
        "lines.linewidth": 1.0, "lines.markersize": 3.5, "axes.linewidth": 0.6,
        "grid.linewidth": 0.4, "savefig.bbox": "tight", "savefig.pad_inches": 0.02,
    })


def scheme_legend(fig, handles, ncol=4):
    fig.legend(handles=handles, loc="lower center", ncol=ncol, frameon=False,
               bbox_to_anchor=(0.5, -0.01))


def short_reference(meta):
    """The reference in a few words (the description's first clause)."""
    ref = meta.get("reference") or {}
    return (ref.get("description") or "an unknown reference").split(" (")[0]


def runs_by_scheme(d, meta):
    runs = read_csv(os.path.join(d, "runs.csv")) or meta.get("runs") or []
    by_scheme = {}
    for r in runs:
        by_scheme.setdefault(str(r.get("scheme") or "?"), []).append(r)
    return {s: by_scheme[s] for s in sorted(by_scheme, key=scheme_key)}


def cost_panels(plt, d, meta, scene, cost, cost_label, name):
    """Error (or correct digits) of each quantity against a cost, one panel per quantity, one line
    per scheme from the loosest to the tightest rtol (the two ends labelled)."""
    from matplotlib.lines import Line2D
    by_scheme = runs_by_scheme(d, meta)
    if not by_scheme:
        return note(f"{name} skipped: runs.csv absent or empty")
    ref = meta.get("reference") or {}
    digits = ref.get("kind") == "published"
    panels = ([("mescd_u", "positions"), ("mescd_v", "velocities")] if digits else
              [("error_u", "displacements u"), ("error_v", "velocities u'"),
               ("error_reaction", "reactions f_con")])
    fig, axes = plt.subplots(1, len(panels), figsize=(7.2, 2.5), sharey=not digits,
                             squeeze=False)
    handles, drawn = [], 0
    for scheme, rows in by_scheme.items():
        style = dict(color=colour(scheme), marker=SCHEME_MARKERS.get(scheme, "o"))
        failed = sum(1 for r in rows if r.get("status") != "ok")
        label = scheme + (f" ({failed}/{len(rows)} failed)" if failed else "")
        any_point = False
        for ax, (col, _) in zip(axes[0], panels):
            pts = []
            for r in rows:
                x, y, rtol = num(r.get(cost)), num(r.get(col)), num(r.get("rtol"))
                if r.get("status") == "ok" and None not in (x, y, rtol) and x > 0 and (
                        digits or y > 0):
                    pts.append((rtol, x, y))
            if not pts:
                continue
            pts.sort(reverse=True)  # loose to tight
            ax.plot([p[1] for p in pts], [p[2] for p in pts], **style)
            any_point = True
        drawn += any_point
        handles.append(Line2D([], [], label=label if any_point else f"{scheme} (all failed)",
                              **style))
    if not drawn:
        plt.close(fig)
        return note(f"{name} skipped: no successful run")
    for ax, (col, what) in zip(axes[0], panels):
        ax.set_xscale("log")
        ax.set_xlabel(cost_label)
        ax.grid(True, which="major", alpha=0.3)
        if digits:
            ax.set_title(f"{what}: correct digits at t_end")
            trusted = num(ref.get("trusted_digits_u" if col == "mescd_u" else "trusted_digits_v"))
            if trusted is not None:
                top = max(trusted + 1, ax.get_ylim()[1])
                ax.axhspan(trusted, top, color="lightgray", alpha=0.5, lw=0)
        else:
            ax.set_yscale("log")
            ax.set_title(f"{what}")
    axes[0][0].set_ylabel("significant correct digits (mescd)" if digits else
                          "relative max-norm error")
    reference = short_reference(meta)
    tolerances = [num(x) for x in meta.get("tolerances") or [] if num(x)]
    sweep = (f"rtol {fmt_tol(max(tolerances))} (first point) to {fmt_tol(min(tolerances))} "
             "(last)" if tolerances else "one point per rtol")
    fig.suptitle(f"{scene}\nerror against {reference}; each line: {sweep}", y=1.04)
    scheme_legend(fig, handles)
    fig.tight_layout(rect=(0, 0.12, 1, 1))
    save(plt, fig, d, name)


def plot_work_precision(plt, np, d, meta, scene):
    cost_panels(plt, d, meta, scene, "wall_median_s", "wall time, median of runs [s]",
                "work_precision")


def plot_error_steps(plt, np, d, meta, scene):
    cost_panels(plt, d, meta, scene, "steps", "integrator steps (no timing noise)",
                "error_steps")


def running_max(np, y):
    return np.maximum.accumulate(np.where(np.isfinite(y), y, 0.0))


def plot_drift(plt, np, d, meta, scene, at_rtol):
    """Running maximum of the position and velocity residuals over the internal steps; a failed
    run ends in a cross where it stopped."""
    from matplotlib.lines import Line2D
    histories = meta.get("histories") or {}
    fig, axes = plt.subplots(1, 2, figsize=(7.2, 2.5), sharex=True)
    handles, drawn, floor_used = [], 0, False
    for scheme, path in per_scheme_files(d, "drift"):
        rows = read_csv(path) or []
        t = column(np, rows, "t")
        if not t.size:
            continue
        h = histories.get(scheme) or {}
        failed = h.get("status") == "failed"
        for ax, col in zip(axes, ("drift_position", "drift_velocity")):
            y = running_max(np, column(np, rows, col))
            floor_used |= bool((y < FLOOR).any())
            ax.plot(t, np.maximum(y, FLOOR), lw=1.0, **line_style(scheme))
            if failed:
                ax.plot(t[-1], max(y[-1], FLOOR), marker="x", ms=6, mew=1.5, color=colour(scheme))
        label = scheme
        if failed:
            label += f" (failed at t = {num(h.get('t_reached')) or t[-1]:.3g} s)"
        elif all((running_max(np, column(np, rows, c)) < FLOOR).all()
                 for c in ("drift_position", "drift_velocity")):
            label += " (exact: 0)"
        handles.append(Line2D([], [], marker="x" if failed else None, label=label,
                              **line_style(scheme)))
        drawn += 1
    if not drawn:
        plt.close(fig)
        return note("drift skipped: no drift_<scheme>.csv with data")
    axes[0].set_title("position level: max |Φ(u, t)|, running max")
    axes[1].set_title("velocity level: max |Ψ(u, u', t)|, running max")
    axes[0].set_ylabel("residual (row units)")
    for ax in axes:
        ax.set_yscale("log")
        ax.set_xlabel("time [s]")
        ax.grid(True, which="major", alpha=0.3)
        if floor_used:
            ax.axhline(FLOOR, color="gray", ls=":", lw=0.6)
    note_floor = f"; values below {FLOOR:g} drawn at {FLOOR:g}" if floor_used else ""
    fig.suptitle(f"{scene}\nconstraint drift at every internal step, rtol = {at_rtol}"
                 f"{note_floor}", y=1.04)
    scheme_legend(fig, handles)
    fig.tight_layout(rect=(0, 0.12, 1, 1))
    save(plt, fig, d, "drift")


def plot_multipliers(plt, np, d, meta, scene, at_rtol):
    """Each scheme's multipliers against the reference's: max over the constraints of
    |λ − λ_ref|, relative to the reference's largest |λ|, at the output times."""
    from matplotlib.lines import Line2D
    ref_rows = read_csv(os.path.join(d, "history_reference.csv"))
    histories = dict(per_scheme_files(d, "history"))
    if ref_rows:
        ref_name = short_reference(meta)
    else:
        base = next((s for s in ("elimination", "ggl") if s in histories), None)
        if base is None:
            return note("multipliers skipped: no reference multipliers and no elimination or "
                        "ggl history")
        ref_rows = read_csv(histories.pop(base)) or []
        ref_name = f"{base} at the same rtol"
    ref_cols = [c for c in (ref_rows[0] if ref_rows else {}) if c and c.startswith("lambda_")]
    if not ref_cols:
        return note("multipliers skipped: the reference has no multipliers")
    t_ref = column(np, ref_rows, "t")
    lam_ref = np.array([column(np, ref_rows, c) for c in ref_cols])
    scale = np.nanmax(np.abs(lam_ref)) if np.isfinite(lam_ref).any() else 0.0
    if not scale > 0:
        return note("multipliers skipped: the reference multipliers are all zero")
    fig, ax = plt.subplots(figsize=(3.5, 2.9))
    handles, top = [], 0.0
    for scheme, path in histories.items():
        rows = read_csv(path) or []
        if not rows or not all(c in rows[0] for c in ref_cols):
            continue
        t = column(np, rows, "t")
        diff = np.zeros_like(t)
        for k, c in enumerate(ref_cols):
            diff = np.maximum(diff, np.abs(column(np, rows, c) - np.interp(t, t_ref, lam_ref[k])))
        y = np.where(diff > 0, diff / scale, np.nan)  # exact agreement (t = 0): not drawn
        ax.plot(t, y, lw=1.0, **line_style(scheme))
        handles.append(Line2D([], [], label=scheme, **line_style(scheme)))
        top = max(top, float(np.nanmax(y)) if np.isfinite(y).any() else 0.0)
    if not handles:
        plt.close(fig)
        return note("multipliers skipped: no history_<scheme>.csv with the reference's columns")
    ax.set_yscale("log")
    if top > 0:  # seven decades below the largest difference; a roundoff dip at t = 0 is clipped
        ax.set_ylim(bottom=max(ax.get_ylim()[0], top * 1e-7))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("relative multiplier error [–]")
    ax.grid(True, which="major", alpha=0.3)
    ax.set_title(f"{scene}\nmultipliers at rtol = {at_rtol} against {ref_name}\n"
                 "error: max over the constraints |λ − λ_ref| / max |λ_ref|", fontsize=8)
    fig.legend(handles=handles, loc="lower center", ncol=4, frameon=False,
               bbox_to_anchor=(0.5, 0.0), handlelength=2.5)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
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
            ax.text(j, i, labels[i][j], ha="center",
                    va="center", fontsize=6, color="white" if dark else "black")
    if default is not None:  # a frame around the cell keeps its value legible
        from matplotlib.patches import Rectangle
        for colour_, width in (("black", 2.2), ("white", 1.0)):
            ax.add_patch(Rectangle((default[0] - 0.46, default[1] - 0.46), 0.92, 0.92,
                                   fill=False, ec=colour_, lw=width))
    alphas, betas = axes_values
    tick = lambda x: f"{x:.2g}" if x < 100 else f"{x:.0f}"  # noqa: E731
    ax.set_xticks(range(len(alphas)), [tick(a) for a in alphas], fontsize=8)
    ax.set_yticks(range(len(betas)), [tick(b) for b in betas], fontsize=8)
    ax.set_xlabel("α [1/s]")
    ax.set_ylabel("β [1/s]")


def plot_baumgarte(plt, np, d, scene):
    """Error, drift and steps over the (alpha, beta) grid, each on a log colour scale."""
    from matplotlib.colors import LogNorm
    rows = read_csv(os.path.join(d, "baumgarte_study.csv")) or []
    rows = [r for r in rows if num(r.get("alpha")) is not None and num(r.get("beta")) is not None]
    if not rows:
        return note("baumgarte_study skipped: baumgarte_study.csv absent or without grid points")
    alphas = sorted({num(r["alpha"]) for r in rows})
    betas = sorted({num(r["beta"]) for r in rows})
    shape = (len(betas), len(alphas))
    grids = {k: np.full(shape, np.nan) for k in ("error_u", "max_drift_position", "steps")}
    texts = {k: [["no run"] * len(alphas) for _ in betas] for k in grids}
    default = None
    for r in rows:
        i, j = betas.index(num(r["beta"])), alphas.index(num(r["alpha"]))
        if num(r.get("default")) == 1:
            default = (j, i)
        for k in grids:
            if r.get("status") != "ok":
                texts[k][i][j] = "failed"
                continue
            v = num(r.get(k))
            texts[k][i][j] = "n/a" if v is None else (f"{v:.0f}" if k == "steps" else
                                                      f"{v:.0e}".replace("e-0", "e-") if v else "0")
            if v is not None:
                grids[k][i, j] = v
    panels = [(k, title, bar) for k, title, bar in (
        ("error_u", "displacement error", "relative max-norm error"),
        ("max_drift_position", "max position drift", "max |Φ| (units of the rows)"),
        ("steps", "integrator steps", "steps")) if np.isfinite(grids[k]).any()]
    if not panels:
        return note("baumgarte_study skipped: no successful grid point")
    fig, axes = plt.subplots(1, len(panels), figsize=(7.2, 2.6), squeeze=False)
    for ax, (k, title, bar) in zip(axes[0], panels):
        grid = grids[k]
        positive = grid[np.isfinite(grid) & (grid > 0)]
        if not positive.size:
            ax.set_axis_off()
            ax.set_title(f"{title}: all zero")
            continue
        lo, hi = positive.min(), positive.max()
        grid = np.where(grid <= 0, lo / 10, grid)  # exact zeros: white, below the scale
        heat_map(plt, np, fig, ax, grid, texts[k], LogNorm(lo / 2, hi * 2) if lo == hi else
                 LogNorm(lo, hi), "viridis", bar, (alphas, betas), default)
        ax.set_title(title)
    fig.suptitle(f"{scene}\nBaumgarte gains (e'' + 2α e' + β² e = 0 on the constraint error); "
                 "framed: default; grey: failed", y=1.04)
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
    paper_style(plt)
    d = argv[1]
    meta = load_meta(d)
    # drawn as written: a scene named "cost in $" is not math
    scene = (meta.get("scene") or "unknown scene").replace("$", r"\$")
    at_rtol = fmt_tol(num(meta["drift_rtol"])) if num(meta.get("drift_rtol")) else "drift_rtol"
    status = 0
    for name, draw in (
            ("work_precision", lambda: plot_work_precision(plt, np, d, meta, scene)),
            ("error_steps", lambda: plot_error_steps(plt, np, d, meta, scene)),
            ("drift", lambda: plot_drift(plt, np, d, meta, scene, at_rtol)),
            ("multipliers", lambda: plot_multipliers(plt, np, d, meta, scene, at_rtol)),
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
