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
written), 2 bad usage or a file compare would not have written (named with the problem; the
figures that do not need it are still drawn), 3 matplotlib not importable.
"""
import math
import os
import sys

import baumgarte_figure
from compare_files import (SCHEME_ORDER, BadData, column, load_meta, num, per_scheme_files,
                           read_csv, runs_by_scheme)

try:  # the shared style imports matplotlib: without it, main exits 3
    import figure_style as style
except ImportError:
    style = None

# Fixed, so that a scheme keeps its colour across figures and across runs of the script.
SCHEME_COLOURS = dict(zip(SCHEME_ORDER, ("#000000", "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                         "#9467bd", "#8c564b", "#e377c2")))
SCHEME_MARKERS = dict(zip(SCHEME_COLOURS, "osD^v<>P"))
# Dashes too, so that curves which coincide (index1 and baumgarte on a linear scene) both show.
SCHEME_DASHES = dict(zip(SCHEME_COLOURS, ["-", "-", "--", "-", "-.", "-", ":", "--"]))
EXTRA_COLOURS = ["#7f7f7f", "#bcbd22", "#17becf"]
_extra = {}
# Drift of an exactly satisfied constraint is 0, which a log axis cannot show.
FLOOR = 1e-18
# PNG for screens, PDF (vector) for papers.
FORMATS = ("png", "pdf")
# A relative error from here up leaves no correct digit: such a run followed another solution (a
# wrong branch, a lost phase) and is ringed in the cost figures.
NO_DIGIT = 0.5
# The marks of the cost figures: a ring around a run without a correct digit, a red square
# around a run compare marked OVER (its error far beyond its target).
RING = dict(mec="black", mew=0.8)
OVER = dict(marker="s", ms=7, mfc="none", mec="#d62728", mew=0.8)
# A curve denser than this many points is drawn as its upper envelope over as many bins of t (a
# 3.5 in axis is about 200 points wide): 100 periods of multipliers were a solid band.
ENVELOPE_BINS = 200
# A failed run's last residuals (up to 1e50 before the integrator gave up) are clipped this
# factor above the largest drift of the runs that succeeded, so that theirs stay readable.
CLIP_ABOVE_OK = 1e3
# The drift figure's time axis starts this fraction of t_end in (four decades of time): the
# first internal steps (1e-13 s) would take most of a log axis.
EARLIEST = 1e-4


def note(msg):
    print(f"plot_compare: {msg}")


def colour(scheme):
    if scheme in SCHEME_COLOURS:
        return SCHEME_COLOURS[scheme]
    return _extra.setdefault(scheme, EXTRA_COLOURS[len(_extra) % len(EXTRA_COLOURS)])


def line_style(scheme):
    """Colour and dash pattern of a scheme's curve over time (drift, multipliers)."""
    return dict(color=colour(scheme), ls=SCHEME_DASHES.get(scheme, "-"))


def fmt_tol(x):
    """1e-06 or 0.0001 -> 1e-6, 1e-4: the form tolerances are written in."""
    mantissa, exponent = f"{x:.2e}".split("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"


def save(plt, fig, d, name):
    for ext in FORMATS:
        fig.savefig(os.path.join(d, f"{name}.{ext}"), dpi=300 if ext == "png" else None)
    plt.close(fig)
    note("wrote " + ", ".join(f"{name}.{ext}" for ext in FORMATS))


def short_reference(meta):
    """The reference in a few words (the description's first clause)."""
    ref = meta.get("reference") or {}
    return (ref.get("description") or "an unknown reference").split(" (")[0]


def cost_points(rows, cost, col, digits):
    """(cost, value, rtol) of a scheme's successful runs with both numbers, in order of cost."""
    pts = []
    for r in rows:
        x, y, rtol = num(r.get(cost)), num(r.get(col)), num(r.get("rtol"))
        if r.get("status") == "ok" and None not in (x, y, rtol) and x > 0 and (digits or y > 0):
            pts.append((x, y, rtol))
    return sorted(pts)


def over_points(rows, cost, col, digits):
    """The points of runs compare marked OVER (runs.csv over_tolerance = 1, an optional column):
    errors far beyond what their rtol asks for."""
    return [p for p in cost_points([r for r in rows if num(r.get("over_tolerance")) == 1],
                                   cost, col, digits)]


def no_digit(y, digits):
    """A value that leaves no correct digit (error NO_DIGIT or more, or as few digits)."""
    return y <= -math.log10(NO_DIGIT) if digits else y >= NO_DIGIT


def cost_panels(plt, d, meta, scene, cost, cost_label, name):
    """Error (or correct digits) of each quantity against a cost, one panel per quantity, one line
    per scheme joined in order of cost (a slow loose run does not zig-zag the line), the loosest
    rtol hollow, runs without a correct digit ringed."""
    from matplotlib.lines import Line2D
    by_scheme = runs_by_scheme(d, meta)
    if not by_scheme:
        return note(f"{name} skipped: runs.csv absent or empty")
    ref = meta.get("reference") or {}
    digits = ref.get("kind") == "published"
    panels = ([("mescd_u", "positions"), ("mescd_v", "velocities")] if digits else
              [("error_u", "displacements u"), ("error_v", "velocities u'"),
               ("error_reaction", "reactions f_con")])
    fig, axes = plt.subplots(1, len(panels), figsize=(style.PAGE_WIDTH, 3.1),
                             sharey=not digits, squeeze=False)
    handles, drawn, ringed, marked = [], 0, False, False
    for scheme, rows in by_scheme.items():
        style_ = dict(color=colour(scheme), marker=SCHEME_MARKERS.get(scheme, "o"))
        failed = sum(1 for r in rows if r.get("status") != "ok")
        loosest = max((num(r.get("rtol")) or 0.0 for r in rows), default=0.0)
        any_point = False
        for ax, (col, _) in zip(axes[0], panels):
            pts = cost_points(rows, cost, col, digits)
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], **style_)
            ax.plot([p[0] for p in pts if p[2] == loosest], [p[1] for p in pts if p[2] == loosest],
                    ls="none", mfc="white", **style_)
            bad = [p for p in pts if no_digit(p[1], digits)]
            if bad:
                ax.plot([p[0] for p in bad], [p[1] for p in bad], ls="none", marker="o", ms=9,
                        mfc="none", **RING)
                ringed = True
            over = over_points(rows, cost, col, digits)
            if over:
                ax.plot([p[0] for p in over], [p[1] for p in over], ls="none", **OVER)
                marked = True
            any_point = True
        drawn += any_point
        label = scheme + (f" ({failed}/{len(rows)} failed)" if failed else "")
        handles.append(Line2D([], [], label=label if any_point else f"{scheme} (all failed)",
                              **style_))
    if not drawn:
        plt.close(fig)
        return note(f"{name} skipped: no successful run")
    if ringed:
        handles.append(Line2D([], [], ls="none", marker="o", ms=9, mfc="none", **RING,
                              label=f"error ≥ {NO_DIGIT:g}: no correct digit "
                                    "(another branch or phase)"))
    if marked:
        factor = num(meta.get("mark_factor"))
        handles.append(Line2D([], [], ls="none", **OVER, label="OVER: error " + (
            f"over {factor:g} × its target" if factor else "far beyond its target")))
    for k, (ax, (col, what)) in enumerate(zip(axes[0], panels)):
        style.log_axis(ax, "x")
        if len(panels) % 2 == 0 or k == len(panels) // 2:  # one label under the row
            ax.set_xlabel(cost_label)
        ax.grid(True, which="major", alpha=0.3)
        if digits:
            ax.set_title(f"{what}: correct digits at t_end")
            trusted = num(ref.get("trusted_digits_u" if col == "mescd_u" else "trusted_digits_v"))
            if trusted is not None:
                top = max(trusted + 1, ax.get_ylim()[1])
                ax.axhspan(trusted, top, color="lightgray", alpha=0.5, lw=0)
        else:
            style.log_axis(ax, "y")
            ax.set_title(f"{what}")
    axes[0][0].set_ylabel("significant correct digits (mescd)" if digits else
                          "relative max-norm error")
    reference = short_reference(meta)
    tolerances = [num(x) for x in meta.get("tolerances") or [] if num(x)]
    sweep = (f"rtol {fmt_tol(max(tolerances))} (hollow) to {fmt_tol(min(tolerances))}"
             if tolerances else "one point per rtol")
    style.title(fig, f"{scene}\nerror against {reference}; each line: {sweep}, "
                     "joined in order of cost")
    style.fit(fig, style.legend_below(fig, handles, ncol=4))
    save(plt, fig, d, name)


def plot_work_precision(plt, np, d, meta, scene):
    cost_panels(plt, d, meta, scene, "wall_median_s", "wall time, median of runs [s]",
                "work_precision")


def plot_error_steps(plt, np, d, meta, scene):
    cost_panels(plt, d, meta, scene, "steps", "integrator steps (no timing noise)",
                "error_steps")


def running_max(np, y):
    return np.maximum.accumulate(np.where(np.isfinite(y), y, 0.0))


def drift_curves(np, d, meta):
    """Per scheme: t > 0, the running max of both residuals, whether the run failed, the fitted
    growth exponent (runs.json drift_growth) or None."""
    histories = meta.get("histories") or {}
    growth = meta.get("drift_growth") or {}
    curves = []
    for scheme, path in per_scheme_files(d, "drift"):
        rows = read_csv(path) or []
        t = column(np, rows, "t")
        later = t > 0  # a log time axis starts after t = 0
        if not later.any():
            continue
        ys = [running_max(np, column(np, rows, c))[later]
              for c in ("drift_position", "drift_velocity")]
        h = histories.get(scheme) or {}
        exponent = num((growth.get(scheme) or {}).get("exponent"))
        curves.append(dict(scheme=scheme, t=t[later], ys=ys, failed=h.get("status") == "failed",
                           t_failed=num(h.get("t_reached")) or t[-1], exponent=exponent,
                           predicted=(growth.get(scheme) or {}).get("predicted")))
    return curves


def drift_top(np, curves):
    """The top of the drift axes: CLIP_ABOVE_OK times the largest drift of the runs that
    succeeded (a failed run's last residual, up to 1e50, would flatten theirs), or None."""
    ok = [y.max() for c in curves if not c["failed"] for y in c["ys"] if y.size]
    return max(ok) * CLIP_ABOVE_OK if ok and max(ok) > FLOOR else None


def plot_drift(plt, np, d, meta, scene, at_rtol):
    """Running maximum of the position and velocity residuals over the internal steps, on log-log
    axes (a growth t^p is a line of slope p; the fitted p drawn through the run's end); a failed
    run ends in a cross where it stopped, clipped at the axis top."""
    from matplotlib.lines import Line2D
    curves = drift_curves(np, d, meta)
    if not curves:
        return note("drift skipped: no drift_<scheme>.csv with data")
    fig, axes = plt.subplots(1, 2, figsize=(style.PAGE_WIDTH, 3.1), sharex=True)
    top = drift_top(np, curves)
    handles, floor_used, clipped, fitted = [], False, [], False
    for c in curves:
        for ax, y in zip(axes, c["ys"]):
            floor_used |= bool((y < FLOOR).any())
            shown = np.maximum(y, FLOOR) if top is None else np.clip(y, FLOOR, top)
            ax.plot(c["t"], shown, lw=1.0, **line_style(c["scheme"]))
            if c["failed"]:
                ax.plot(c["t"][-1], shown[-1], marker="x", ms=6, mew=1.5,
                        color=colour(c["scheme"]))
            if top is not None and y[-1] > top:
                clipped.append(f"{c['scheme']} {y[-1]:.0e}")
        label = c["scheme"]
        if c["exponent"] is not None and c["ys"][0][-1] > FLOOR:
            t_end, y_end = c["t"][-1], c["ys"][0][-1]
            span = np.array([t_end / 100, t_end])
            axes[0].plot(span, y_end * (span / t_end) ** c["exponent"], color="black", lw=0.6,
                         ls=(0, (1, 2)))
            label += f": t^{c['exponent']:.2f}"
            fitted = True
        if c["failed"]:
            label += f" (failed at t = {c['t_failed']:.3g} s)"
        elif all((y < FLOOR).all() for y in c["ys"]):
            label += " (exact: 0)"
        handles.append(Line2D([], [], marker="x" if c["failed"] else None, label=label,
                              **line_style(c["scheme"])))
    if fitted:
        handles.append(Line2D([], [], color="black", lw=0.6, ls=(0, (1, 2)),
                              label="fitted t^p through the end"))
    axes[0].set_title("position level: max |Φ(u, t)|, running max")
    axes[1].set_title("velocity level: max |Ψ(u, u', t)|, running max")
    axes[0].set_ylabel("residual (row units)")
    t_end = max(c["t"][-1] for c in curves)
    for ax in axes:
        style.log_axis(ax, "y")
        style.log_axis(ax, "x")
        # the last decades of time, where a growth law shows (the first steps are tiny)
        ax.set_xlim(max(min(c["t"][0] for c in curves), t_end * EARLIEST), t_end * 1.2)
        ax.set_xlabel("time [s]")
        ax.grid(True, which="major", alpha=0.3)
        if floor_used:
            ax.axhline(FLOOR, color="gray", ls=":", lw=0.6)
    notes = []
    if floor_used:
        notes.append(f"below {FLOOR:g} drawn at {FLOOR:g}")
    if clipped:
        notes.append("clipped at the top: " + ", ".join(dict.fromkeys(clipped)))
    style.title(fig, f"{scene}\nconstraint drift at every internal step, rtol = {at_rtol}"
                + "".join(f"; {n}" for n in notes))
    style.fit(fig, style.legend_below(fig, handles, ncol=3))
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
    fig, ax = plt.subplots(figsize=(style.COLUMN_WIDTH, 3.4))
    handles, top, enveloped = [], 0.0, False
    for scheme, path in histories.items():
        rows = read_csv(path) or []
        if not rows or not all(c in rows[0] for c in ref_cols):
            continue
        t = column(np, rows, "t")
        diff = np.zeros_like(t)
        for k, c in enumerate(ref_cols):
            diff = np.maximum(diff, np.abs(column(np, rows, c) - np.interp(t, t_ref, lam_ref[k])))
        y = np.where(diff > 0, diff / scale, np.nan)  # exact agreement (t = 0): not drawn
        if t.size > 2 * ENVELOPE_BINS:
            t, y = upper_envelope(np, t, y)
            enveloped = True
        ax.plot(t, y, lw=1.0, **line_style(scheme))
        handles.append(Line2D([], [], label=scheme, **line_style(scheme)))
        top = max(top, float(np.nanmax(y)) if np.isfinite(y).any() else 0.0)
    if not handles:
        plt.close(fig)
        return note("multipliers skipped: no history_<scheme>.csv with the reference's columns")
    style.log_axis(ax, "y")
    if top > 0:  # seven decades below the largest difference; a roundoff dip at t = 0 is clipped
        ax.set_ylim(bottom=max(ax.get_ylim()[0], top * 1e-7))
    ax.set_xlabel("time [s]" + (f"; upper envelope over {ENVELOPE_BINS} bins" if enveloped
                                else ""))
    ax.set_ylabel("max over the constraints\n|λ − λ_ref| / max |λ_ref|")
    ax.grid(True, which="major", alpha=0.3)
    style.title(fig, f"{scene}\nmultipliers at rtol = {at_rtol} against {ref_name}", fontsize=8)
    style.fit(fig, style.legend_below(fig, handles, ncol=3, handlelength=2.5))
    save(plt, fig, d, "multipliers")


def upper_envelope(np, t, y):
    """The largest y in each of ENVELOPE_BINS equal bins of t, at the bin's centre: what a curve
    of more points than the axis has pixels shows of an error (its peaks), without the band."""
    edges = np.linspace(t[0], t[-1], ENVELOPE_BINS + 1)
    which = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, ENVELOPE_BINS - 1)
    peak = np.full(ENVELOPE_BINS, np.nan)
    finite = np.isfinite(y)
    np.fmax.at(peak, which[finite], y[finite])
    return (edges[:-1] + edges[1:]) / 2, peak


def plot_baumgarte(plt, np, d, scene):
    rows = read_csv(os.path.join(d, "baumgarte_study.csv")) or []
    fig, why = baumgarte_figure.draw(plt, np, style, rows, scene)
    if fig is None:
        return note(f"baumgarte_study skipped: {why}")
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
        if style is None:
            raise ImportError("figure_style")
    except ImportError:
        print("plot_compare: matplotlib not available, plots skipped")
        return 3
    style.paper_style(plt)
    d = argv[1]
    meta, problems = load_meta(d)
    for problem in problems:
        note(problem)
    # drawn as written: a scene named "cost in $" is not math
    scene = (meta.get("scene") or "unknown scene").replace("$", r"\$")
    at_rtol = fmt_tol(num(meta["drift_rtol"])) if num(meta.get("drift_rtol")) else "drift_rtol"
    status = 2 if problems else 0
    for name, draw in (
            ("work_precision", lambda: plot_work_precision(plt, np, d, meta, scene)),
            ("error_steps", lambda: plot_error_steps(plt, np, d, meta, scene)),
            ("drift", lambda: plot_drift(plt, np, d, meta, scene, at_rtol)),
            ("multipliers", lambda: plot_multipliers(plt, np, d, meta, scene, at_rtol)),
            ("baumgarte_study", lambda: plot_baumgarte(plt, np, d, scene))):
        try:
            draw()
        except BadData as e:  # a file compare would not have written: named, the others drawn
            note(f"{name} skipped: {e}")
            plt.close("all")
            status = max(status, 2)
        except Exception as e:  # noqa: BLE001 -- a bug: said in one line, the others drawn
            note(f"{name} failed: {type(e).__name__}: {e}")
            plt.close("all")
            status = max(status, 1)
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
