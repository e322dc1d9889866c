#!/usr/bin/env python3
"""Figures of one run's result file, for `condyn plot RESULT` (docs/plots.md).

    /usr/bin/python3 validation/plot_result.py RESULT [--out-dir DIR] [--dofs a,b*] [--format png,pdf]

RESULT is the CSV or HDF5 that `condyn run` writes (docs/cli.md). Draws into DIR (default:
beside RESULT), each figure named STEM_<what>.<format>:
  displacement  the chosen DOFs against t (default: the four with the largest peak |u|)
  drift         running max of the position and velocity constraint residuals (if written; none when it is 0 throughout)
  energy        the energy balance's terms, and its error (if written: docs/energy.md)
  shape         with --nodes (the scene's node map): the deformed shape at the time of the
                largest nodal displacement (plot_shapes.py)
  modes         with --nodes, for the CSV of `condyn modes --shapes` or the HDF5 of `condyn modes
                --out FILE.h5`: the mode shapes (from the HDF5, each titled with its frequency
                and period)
Sized for print: 3.5 in wide (one column), 8-9 pt text.

Exit status: 0 drawn; 2 bad input (the message names the file and what is wrong); 3 matplotlib,
numpy or h5py missing.
"""
import argparse
import os
import re
import sys

import plot_shapes as shapes
from result_file import (BadInput, energy_columns, mode_shapes_file, read_csv, read_h5,
                         read_mode_shapes)

# The shared style (figure_style.py), imported with matplotlib by pyplot() once the input has been
# read: a refusal of bad input costs no matplotlib import (0.6 s of a 0.7 s refusal before).
style = None

DEFAULT_DOFS = 4
# Two DOFs whose curves stay within this fraction of the larger peak of each other throughout
# are drawn over each other: the default choice takes one of them.
DISTINCT = 0.25
# A DOF whose peak is below this fraction of the largest peak stays at 0 but for roundoff (a
# support: 1e-26 against the pendulum's 1): about 4500 machine epsilons.
STILL = 1e-12
# More curves than this are drawn without a legend (it would outgrow the figure).
MAX_LEGEND = 12
# The columns figure draws one panel per column, at most this many (a note names the rest).
MAX_PANELS = 6


def star_match(name, pattern):
    """`*` as any run of characters, every other character as itself: the globs of [output]
    dofs (a DOF named n[1] is matched by 'n[1]', not read as a character class)."""
    return re.fullmatch(".*".join(re.escape(part) for part in pattern.split("*")), name) is not None


def chosen_dofs(np, columns, dofs, patterns, path):
    """The DOFs to draw, how they were chosen (for the title), and notes: --dofs patterns, or by
    default up to DEFAULT_DOFS of the largest peaks that differ from each other (distinct). DOFs
    that stay 0 throughout (supports) are drawn only when named exactly."""
    peak = {d: float(np.abs(columns[d]).max()) for d in dofs}
    largest = max(peak.values(), default=0.0)
    still_ = {d for d in dofs if peak[d] <= STILL * largest}
    if patterns:
        chosen, still = [], []
        for p in patterns:
            hits = [d for d in dofs if star_match(d, p)]
            if not hits:
                some = ", ".join(dofs[:8]) + (", ..." if len(dofs) > 8 else "")
                raise BadInput(f"--dofs: '{p}' matches no DOF of {path} (DOFs: {some or 'none'})")
            glob = "*" in p
            still += [d for d in hits if glob and d in still_ and d not in still]
            chosen += [d for d in hits if d not in chosen and not (glob and d in still_)]
        notes = [f"{names(still)} stay at 0 but for roundoff (supports?): not drawn (name "
                 "them in --dofs to draw them)"] if still else []
        if not chosen:
            raise BadInput(f"--dofs: every DOF it matches stays at 0 but for roundoff "
                           f"({names(still)}): name one to draw it")
        return chosen, "chosen", notes
    moving = sorted((d for d in dofs if d not in still_), key=lambda d: -peak[d])
    chosen, close = [], []
    for d in moving:
        twin = next((c for c in chosen if np.abs(columns[d] - columns[c]).max()
                     <= DISTINCT * max(peak[d], peak[c])), None)
        if twin is None:
            chosen.append(d)
        elif len(chosen) < DEFAULT_DOFS:
            close.append(f"{d} (near {twin})")
        if len(chosen) == DEFAULT_DOFS:
            break
    notes = []
    if close:
        notes.append(f"not drawn, within {DISTINCT:.0%} of a larger peak's curve throughout: "
                     f"{names(close)}; --dofs draws them")
    if len(moving) < len(dofs):
        notes.append(f"{names(sorted(still_, key=dofs.index))} stay at 0 but for roundoff "
                     "(supports?): not drawn")
    how = (f"{len(chosen)} of {len(dofs)} DOFs: largest distinct peaks" if len(chosen) < len(dofs)
           else f"all {len(dofs)} DOFs")
    return chosen, how, notes


def chosen_columns(columns, derived, patterns, path):
    """The columns of the columns figure: those --columns names (names or globs, any column read
    but t), or by default the result's [[derived]] columns; and notes."""
    chosen = []
    for p in patterns:
        hits = [c for c in columns if c != "t" and star_match(c, p)]
        if not hits:
            some = names([c for c in columns if c != "t"], 8)
            raise BadInput(f"--columns: '{p}' matches no column of {path} (columns: "
                           f"{some or 'none'})")
        chosen += [c for c in hits if c not in chosen]
    if not patterns:
        chosen = list(derived)
    notes = []
    if len(chosen) > MAX_PANELS:
        notes.append(f"{names(chosen[MAX_PANELS:])} not drawn (at most {MAX_PANELS} panels); "
                     "--columns chooses")
        chosen = chosen[:MAX_PANELS]
    return chosen, notes


def names(items, most=6):
    return ", ".join(items[:most]) + (f" and {len(items) - most} more" if len(items) > most else "")


def draw_displacement(plt, t, columns, chosen, how, title_stem, relative):
    fig, ax = plt.subplots(figsize=(style.COLUMN_WIDTH, 2.8))
    for d in chosen:
        ax.plot(t, columns[d], label=style.literal(d))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("displacement [m in SI]")
    # condyn writes displacements relative to the ground under [ground_motion]; a result says so
    # only through its absolute accelerations (acc_abs_), so without them the title covers both
    ground = "relative to the ground" if relative else "relative to any ground motion"
    style.title(fig, f"{title_stem}: displacements {ground}\n({how}; --dofs chooses)")
    ax.grid(True, alpha=0.3)
    legend = None
    if len(chosen) <= MAX_LEGEND:
        legend = style.legend_below(fig, ax.get_lines(), ncol=min(4, len(chosen)))
    style.fit(fig, legend)
    return fig


def draw_columns(plt, t, columns, chosen, title_stem):
    """One panel per column, stacked over a shared time axis (each column its own units: a
    drift ratio beside a base shear)."""
    fig, axes = plt.subplots(len(chosen), 1, figsize=(style.COLUMN_WIDTH, 0.9 + 1.1 * len(chosen)),
                             sharex=True, squeeze=False)
    for ax, c in zip(axes[:, 0], chosen):
        ax.plot(t, columns[c], color="black")
        ax.set_title(style.literal(c), loc="left", fontsize=8)  # a name too long for a y label
        ax.grid(True, alpha=0.3)
    axes[-1][0].set_xlabel("time [s]")
    style.title(fig, f"{title_stem}: result columns")
    style.fit(fig)
    return fig


def draw_drift(plt, np, t, columns, title_stem):
    """The drift figure, or None and the note that says why there is none."""
    not_a_number = [c for c in ("drift_position", "drift_velocity") if c in columns and np.isnan(columns[c]).any()]
    curves = []
    for col, label in (("drift_position", "position |Φ(u, t)|"),
                       ("drift_velocity", "velocity |Ψ(u, u', t)|")):
        y = np.maximum.accumulate(np.nan_to_num(columns[col], nan=0.0))
        if (y > 0).any():
            curves.append((np.where(y > 0, y, np.nan), label))
    if not curves:
        if not_a_number:
            return None, (f"{', '.join(not_a_number)} not a number at some output times, and "
                          "nowhere above 0: no drift figure")
        # eliminated constraints hold exactly: an empty log axis would say nothing
        return None, ("drift exactly 0 at every output time (constraints eliminated, or none): "
                      "no drift figure")
    fig, ax = plt.subplots(figsize=(style.COLUMN_WIDTH, 2.8))
    for y, label in curves:
        ax.plot(t, y, label=label)
    style.log_axis(ax, "y")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("residual, running max\n(constraint row units)")
    style.title(fig, f"{title_stem}: constraint drift at the output times")
    ax.grid(True, which="major", alpha=0.3)
    style.fit(fig, style.legend_below(fig, ax.get_lines(), ncol=2))
    return fig, None


def draw_energy(plt, t, columns, terms, title_stem):
    error = "energy_error" in columns
    fig, axes = plt.subplots(2 if error else 1, 1,
                             figsize=(style.COLUMN_WIDTH, 3.8 if error else 2.8),
                             sharex=True, squeeze=False,
                             gridspec_kw={"height_ratios": [2, 1] if error else [1]})
    top = axes[0][0]
    for col, label in terms:
        top.plot(t, columns[col], label=style.literal(label))
    top.set_ylabel("energy [J in SI]")
    top.grid(True, alpha=0.3)
    if error:
        bottom = axes[1][0]
        bottom.plot(t, columns["energy_error"], color="black")
        bottom.set_ylabel("balance\nerror [J]")
        bottom.grid(True, alpha=0.3)
    axes[-1][0].set_xlabel("time [s]")
    fig.align_ylabels(axes[:, 0])
    style.title(fig, f"{title_stem}: energy balance" if error else f"{title_stem}: energy")
    style.fit(fig, style.legend_below(fig, top.get_lines(), ncol=3, handlelength=1.5,
                                      columnspacing=1.0))
    return fig


def too_large(np, columns, chosen):
    """The refusal of a column whose values come near the double range (they break matplotlib's
    ticks: a traceback), or None. 1e300 leaves the headroom it needs."""
    for names_ in (["t"], list(chosen), [c for c, _ in energy_columns(columns)]):
        if not names_:
            continue
        worst = max(names_, key=lambda c: np.abs(columns[c]).max())
        top = np.abs(columns[worst]).max()
        if top > 1e300:
            return (f"column {worst}: values up to {top:g} are too near the double range to draw "
                    "(beyond 1e300)")
    return None


def read_result(np, path, dofs_flag, columns_flag=""):
    """Everything plot needs from the result, or BadInput naming the file and the problem."""
    try:
        # HDF5 under the names run writes it (src/output/output_format.hpp), else CSV.
        hdf5 = path.lower().endswith((".h5", ".hdf5", ".hdf"))
        columns, dofs, relative, derived = read_h5(np, path) if hdf5 else read_csv(np, path)
    except OSError as e:  # a folder, no permission, a read error
        raise BadInput(f"{path}: {e.strerror or e}") from None
    drawn, drawn_notes = chosen_columns(columns, derived,
                                        [p for p in columns_flag.split(",") if p], path)
    dofs = [d for d in dofs if d not in drawn]  # a column named for its own panel
    patterns = [p for p in dofs_flag.split(",") if p]
    if patterns and not dofs:
        raise BadInput(f"{path}: has no displacement columns to choose from")
    chosen, how, notes = chosen_dofs(np, columns, dofs, patterns, path) if dofs else ([], "", [])
    problem = too_large(np, columns, chosen + drawn)
    if problem:
        raise BadInput(f"{path}: {problem}")
    return columns, chosen, how, notes + drawn_notes, relative, drawn


def pyplot():
    """matplotlib's pyplot on the Agg backend, and the shared style in the global `style`; None
    when matplotlib is missing (main exits 3)."""
    global style
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import figure_style
    except ImportError:
        return None
    style = figure_style
    return plt


def plot_mode_shapes(np, path, nodes, out_dir, stem, formats):
    """STEM_modes.<format> from a mode shapes CSV or modes HDF5; the exit status."""
    try:
        table, modes, omega = read_mode_shapes(np, path)
    except BadInput as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001 -- any other malformed input: named, never a traceback
        print(f"error: {path}: cannot be read as mode shapes ({type(e).__name__}: {e})",
              file=sys.stderr)
        return 2
    plt = pyplot()
    if plt is None:
        return 3
    style.paper_style(plt)
    fig, notes = shapes.draw_modes(plt, np, style, nodes, table, modes, style.literal(stem),
                                   omega)
    for line in notes:
        print(f"note: {stem}: {line}")
    for ext in formats:
        name = os.path.join(out_dir, f"{stem}_modes.{ext}")
        fig.savefig(name, dpi=300 if ext == "png" else None)
        print(f"wrote {name}")
    plt.close(fig)
    return 0


def main(argv):
    parser = argparse.ArgumentParser(prog="plot_result.py")
    parser.add_argument("result")
    parser.add_argument("--out-dir", default=None)
    parser.add_argument("--dofs", default="")
    parser.add_argument("--columns", default="")
    parser.add_argument("--format", default="png,pdf")
    # the scene's node map as JSON (condyn plot --scene writes it): shapes are drawn
    parser.add_argument("--nodes", default=None)
    args = parser.parse_args(argv[1:])
    try:
        import numpy as np
    except ImportError:
        return 3
    path = args.result
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(path))
    stem = os.path.splitext(os.path.basename(path))[0]
    formats = [f for f in args.format.split(",") if f]
    nodes = shapes.read_nodes(args.nodes) if args.nodes else None
    if nodes and mode_shapes_file(path):
        return plot_mode_shapes(np, path, nodes, out_dir, stem, formats)
    try:
        columns, chosen, how, notes, relative, drawn = read_result(np, path, args.dofs,
                                                                  args.columns)
    except BadInput as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001 -- any other malformed input: named, never a traceback
        print(f"error: {path}: cannot be read as a condyn result ({type(e).__name__}: {e})",
              file=sys.stderr)
        return 2
    notes = [f"{stem}: {n}" for n in notes]
    plt = pyplot()
    if plt is None:
        return 3
    style.paper_style(plt)
    t, title_stem, written = columns["t"], style.literal(stem), []

    def save(fig, what):
        for ext in formats:
            name = os.path.join(out_dir, f"{stem}_{what}.{ext}")
            fig.savefig(name, dpi=300 if ext == "png" else None)
            written.append(name)
        plt.close(fig)

    try:
        if chosen:
            save(draw_displacement(plt, t, columns, chosen, how, title_stem, relative),
                 "displacement")
            if len(chosen) > MAX_LEGEND:  # a legend of hundreds of names would be the figure
                notes.append(f"{stem}: {len(chosen)} DOFs drawn without a legend (more than "
                             f"{MAX_LEGEND}); --dofs chooses fewer")
        if drawn:
            save(draw_columns(plt, t, columns, drawn, title_stem), "columns")
        if "drift_position" in columns:
            fig, why = draw_drift(plt, np, t, columns, title_stem)
            if fig:
                save(fig, "drift")
            else:
                notes.append(f"{stem}: {why}")
        terms = energy_columns(columns)
        if terms:
            save(draw_energy(plt, t, columns, terms, title_stem), "energy")
        if nodes:
            fig, note = shapes.draw_deformed(plt, np, style, nodes, columns, title_stem)
            if fig:
                save(fig, "shape")
            if note:
                notes.append(f"{stem}: {note}")
    except Exception as e:  # noqa: BLE001 -- a drawing error is a bug: said in one line
        print(f"error: {path}: drawing failed ({type(e).__name__}: {e})", file=sys.stderr)
        return 1
    for line in notes:
        print(f"note: {line}")
    if not written:
        why = ("the notes above say why" if notes
               else "no displacement, drift, energy or derived columns")
        print(f"error: {path}: nothing to draw ({why})", file=sys.stderr)
        return 2
    for name in written:
        print(f"wrote {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
