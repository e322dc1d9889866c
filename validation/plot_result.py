#!/usr/bin/env python3
"""Figures of one run's result file, for `condyn plot RESULT` (docs/plots.md).

    /usr/bin/python3 validation/plot_result.py RESULT [--out-dir DIR] [--dofs a,b*] [--format png,pdf]

RESULT is the CSV or HDF5 that `condyn run` writes (docs/cli.md). Draws into DIR (default:
beside RESULT), each figure named STEM_<what>.<format>:
  displacement  the chosen DOFs against t (default: the four with the largest peak |u|)
  drift         running max of the position and velocity constraint residuals (if written; none when it is 0 throughout)
  energy        the energy balance's terms, and its error (if written: docs/energy.md)
Sized for print: 3.5 in wide (one column), 8-9 pt text.

Exit status: 0 drawn; 2 bad input (the message names the file and what is wrong); 3 matplotlib,
numpy or h5py missing.
"""
import argparse
import os
import re
import sys

ENERGY_TERMS = (("energy_kinetic", "kinetic T"), ("energy_potential", "potential V"),
                ("energy_dissipated", "dissipated D"), ("work_loads", "work of loads"),
                ("work_constraints", "work of constraints"),
                ("energy", "total T + V"))
DEFAULT_DOFS = 4


# Every energy column condyn writes (kEnergyColumns in models/scene_spec.hpp): matched by name,
# not by prefix, since a DOF may be named energy_top or work_1 (it is then a displacement).
ENERGY_NAMES = {c for c, _ in ENERGY_TERMS} | {"energy_error"}
DRIFT_NAMES = {"drift_position", "drift_velocity"}
# More curves than this are drawn without a legend (it would outgrow the figure).
MAX_LEGEND = 12


def literal(text):
    """Text matplotlib draws as written: a DOF named y$_1$ (a legal name) is not math."""
    return text.replace("$", r"\$")


def energy_columns(columns):
    """The energy terms present, with their labels (energy_error has its own panel)."""
    return [(c, label) for c, label in ENERGY_TERMS if c in columns]


class BadInput(Exception):
    pass


def read_csv(np, path):
    with open(path, newline="") as f:
        header = f.readline().strip().split(",")
    if not header or header[0] != "t":
        raise BadInput(f"{path}: not a condyn result (its first column is not t)")
    import warnings
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # an empty file's warning: "no rows" below says it
            data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    except ValueError:
        raise BadInput(first_bad_line(path, len(header))) from None
    if data.shape[0] == 0:
        raise BadInput(f"{path}: no rows")
    if data.shape[1] != len(header):
        raise BadInput(first_bad_line(path, len(header)))
    columns = {name: data[:, k] for k, name in enumerate(header)}
    prefixed = ("vel_", "acc_", "reaction_", "lambda_")
    dofs = [n for n in header[1:]
            if not n.startswith(prefixed) and n not in ENERGY_NAMES and n not in DRIFT_NAMES]
    return columns, dofs


def first_bad_line(path, width):
    """FILE:LINE: what is wrong with the first row that is not `width` numbers."""
    with open(path, newline="") as f:
        for number, line in enumerate(f, start=1):
            if number == 1 or not line.strip():
                continue
            cells = line.rstrip("\r\n").split(",")
            if len(cells) != width:
                return f"{path}:{number}: {len(cells)} cells for the header's {width} columns"
            for cell in cells:
                try:
                    float(cell)
                except ValueError:
                    return f"{path}:{number}: '{cell[:40]}' is not a number"
    return f"{path}: rows of different lengths"


def read_h5(np, path):
    try:
        import h5py
    except ImportError:
        raise SystemExit(3)
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise BadInput(f"{path}: not an HDF5 file ({e})") from None
    with f:
        if "t" not in f:
            raise BadInput(f"{path}: not a condyn result (no dataset t)")
        columns = {"t": np.asarray(f["t"])}
        dofs = [s.decode() if isinstance(s, bytes) else str(s) for s in f.get("dof_names", [])]
        if "displacement" in f:
            u = np.asarray(f["displacement"])
            for k, name in enumerate(dofs):
                columns[name] = u[:, k]
        else:
            dofs = []
        if "drift" in f:
            d = np.asarray(f["drift"])
            columns["drift_position"], columns["drift_velocity"] = d[:, 0], d[:, 1]
        if "energy" in f:
            e = np.asarray(f["energy"])
            names = [s.decode() if isinstance(s, bytes) else str(s)
                     for s in f.get("energy_columns", [])]
            for k, name in enumerate(names):
                columns[name] = e[:, k]
    return columns, dofs


def star_match(name, pattern):
    """`*` as any run of characters, every other character as itself: the globs of [output]
    dofs (a DOF named n[1] is matched by 'n[1]', not read as a character class)."""
    return re.fullmatch(".*".join(re.escape(part) for part in pattern.split("*")), name) is not None


def chosen_dofs(np, columns, dofs, patterns, path):
    if patterns:
        chosen = []
        for p in patterns:
            hits = [d for d in dofs if star_match(d, p)]
            if not hits:
                some = ", ".join(dofs[:8]) + (", ..." if len(dofs) > 8 else "")
                raise BadInput(f"--dofs: '{p}' matches no DOF of {path} (DOFs: {some or 'none'})")
            chosen += [d for d in hits if d not in chosen]
        return chosen, "chosen"
    peaks = sorted(dofs, key=lambda d: -np.nanmax(np.abs(columns[d])))
    return peaks[:DEFAULT_DOFS], f"the {min(DEFAULT_DOFS, len(dofs))} largest peaks of {len(dofs)}"


def main(argv):
    parser = argparse.ArgumentParser(prog="plot_result.py")
    parser.add_argument("result")
    parser.add_argument("--out-dir", default=None)
    parser.add_argument("--dofs", default="")
    parser.add_argument("--format", default="png,pdf")
    args = parser.parse_args(argv[1:])
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np
    except ImportError:
        return 3
    path = args.result
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(path))
    stem = os.path.splitext(os.path.basename(path))[0]
    formats = [f for f in args.format.split(",") if f]
    try:
        # HDF5 under the names run writes it (src/output_format.hpp), else CSV.
        hdf5 = path.lower().endswith((".h5", ".hdf5", ".hdf"))
        columns, dofs = read_h5(np, path) if hdf5 else read_csv(np, path)
        patterns = [p for p in args.dofs.split(",") if p]
        if patterns and not dofs:
            raise BadInput(f"{path}: has no displacement columns to choose from")
        chosen, how = chosen_dofs(np, columns, dofs, patterns, path) if dofs else ([], "")
    except BadInput as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"error: {path}: {e.strerror}", file=sys.stderr)
        return 2

    plt.rcParams.update({
        "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "xtick.labelsize": 8,
        "ytick.labelsize": 8, "legend.fontsize": 8, "lines.linewidth": 1.0,
        "axes.linewidth": 0.6, "grid.linewidth": 0.4, "savefig.bbox": "tight"})
    t = columns["t"]
    written, notes = [], []
    title_stem = literal(stem)
    # An axis whose values (or their span, with its margins) come near the double range breaks
    # matplotlib's ticks (a traceback): refused by name. 1e300 leaves the headroom it needs.
    for names in (["t"], list(chosen), [c for c, _ in energy_columns(columns)]):
        if not names:
            continue
        values = np.concatenate([columns[c][np.isfinite(columns[c])] for c in names])
        if values.size and np.abs(values).max() > 1e300:
            worst = max(names, key=lambda c: np.nanmax(np.abs(np.where(
                np.isfinite(columns[c]), columns[c], 0.0))))
            print(f"error: {path}: column {worst}: values up to {np.abs(values).max():g} are too "
                  "near the double range to draw (beyond 1e300)", file=sys.stderr)
            return 2

    def save(fig, what):
        for ext in formats:
            name = os.path.join(out_dir, f"{stem}_{what}.{ext}")
            fig.savefig(name, dpi=300 if ext == "png" else None)
            written.append(name)
        plt.close(fig)

    if chosen:
        fig, ax = plt.subplots(figsize=(3.5, 2.4))
        for d in chosen:
            ax.plot(t, columns[d], label=literal(d))
        ax.set_xlabel("time [s]")
        ax.set_ylabel("displacement (model units)")
        ax.set_title(f"{title_stem}: displacements ({how})")
        ax.grid(True, alpha=0.3)
        if len(chosen) <= MAX_LEGEND:
            ax.legend(ncol=2 if len(chosen) > 3 else 1, frameon=False)
        else:  # a legend of hundreds of names would be the whole (metres-tall) figure
            notes.append(f"{stem}: {len(chosen)} DOFs drawn without a legend (more than "
                         f"{MAX_LEGEND}); --dofs chooses fewer")
        fig.tight_layout()
        save(fig, "displacement")
    if "drift_position" in columns:
        fig, ax = plt.subplots(figsize=(3.5, 2.4))
        drawn = 0
        not_a_number = [c for c in ("drift_position", "drift_velocity")
                        if c in columns and np.isnan(columns[c]).any()]
        for col, label in (("drift_position", "position |Φ(u, t)|"),
                           ("drift_velocity", "velocity |Ψ(u, u', t)|")):
            y = np.maximum.accumulate(np.nan_to_num(columns[col], nan=0.0))
            if (y > 0).any():
                ax.plot(t, np.where(y > 0, y, np.nan), label=label)
                drawn += 1
        if drawn:
            ax.set_yscale("log")
            ax.set_xlabel("time [s]")
            ax.set_ylabel("max residual, running max\n(units of the constraint rows)")
            ax.set_title(f"{title_stem}: constraint drift at the output times")
            ax.grid(True, which="major", alpha=0.3)
            ax.legend(frameon=False)
            fig.tight_layout()
            save(fig, "drift")
        elif not_a_number:
            plt.close(fig)
            notes.append(f"{stem}: {', '.join(not_a_number)} not a number at some output times, "
                         "and nowhere above 0: no drift figure")
        else:  # eliminated constraints hold exactly: an empty log axis would say nothing
            plt.close(fig)
            notes.append(f"{stem}: drift exactly 0 at every output time (constraints "
                         "eliminated, or none): no drift figure")
    terms = energy_columns(columns)
    if terms:
        error = "energy_error" in columns
        fig, axes = plt.subplots(2 if error else 1, 1, figsize=(3.5, 3.6 if error else 2.4),
                                 sharex=True, squeeze=False,
                                 gridspec_kw={"height_ratios": [2, 1] if error else [1]})
        top = axes[0][0]
        for col, label in terms:
            top.plot(t, columns[col], label=literal(label))
        top.set_ylabel("energy [J in SI]")
        top.grid(True, alpha=0.3)
        # above the axes, under the title: curves fill the whole panel
        top.legend(frameon=False, ncol=3, loc="lower center", bbox_to_anchor=(0.5, 1.0),
                   fontsize=7,
                   title=f"{title_stem}: energy balance" if error else f"{title_stem}: energy",
                   title_fontsize=9, handlelength=1.5, columnspacing=1.0)
        if error:
            bottom = axes[1][0]
            bottom.plot(t, columns["energy_error"], color="black")
            bottom.set_ylabel("balance\nerror [J]")
            bottom.grid(True, alpha=0.3)
        axes[-1][0].set_xlabel("time [s]")
        fig.align_ylabels(axes[:, 0])
        fig.tight_layout()
        save(fig, "energy")
    for line in notes:
        print(f"note: {line}")
    if not written:
        why = ("the notes above say why" if notes
               else "no displacement, drift or energy columns")
        print(f"error: {path}: nothing to draw ({why})", file=sys.stderr)
        return 2
    for name in written:
        print(f"wrote {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
