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

# The shared style (figure_style.py), imported with matplotlib by pyplot() once the input has been
# read: a refusal of bad input costs no matplotlib import (0.6 s of a 0.7 s refusal before).
style = None

ENERGY_TERMS = (("energy_kinetic", "kinetic T"), ("energy_potential", "potential V"),
                ("energy_dissipated", "dissipated D"), ("work_loads", "work of loads"),
                ("work_constraints", "work of constraints"),
                ("energy", "total T + V"))
DEFAULT_DOFS = 4
# Two DOFs whose curves stay within this fraction of the larger peak of each other throughout
# are drawn over each other: the default choice takes one of them.
DISTINCT = 0.25
# A DOF whose peak is below this fraction of the largest peak stays at 0 but for roundoff (a
# support: 1e-26 against the pendulum's 1): about 4500 machine epsilons.
STILL = 1e-12


# Every energy column condyn writes (kEnergyColumns in models/scene/scene_spec.hpp): matched by name,
# not by prefix, since a DOF may be named energy_top or work_1 (it is then a displacement).
ENERGY_NAMES = {c for c, _ in ENERGY_TERMS} | {"energy_error"}
DRIFT_NAMES = {"drift_position", "drift_velocity"}
# 1 on the rows inside a passage near a singular configuration, else 0 (docs/cli.md): not a DOF.
NEAR_SINGULAR = "near_singular"
# A mechanism's CSV (docs/cli.md, "Mechanisms") names its columns per body and joint without a
# prefix: its pose columns (`crank.angle` in 2D, `crank.qw` in 3D) mark it, and the columns
# ending in a rate or a joint's force or torque are its velocities, accelerations and reactions,
# not displacements. Named points (`crank.B.x`) are positions, drawn as displacements.
MECHANISM_POSES = (".angle", ".qw")
MECHANISM_RATES = {"vx", "vy", "vz", "omega", "wx", "wy", "wz", "ax", "ay", "az", "alpha",
                   "alphax", "alphay", "alphaz", "fx", "fy", "fz", "m", "mx", "my", "mz"}
# More curves than this are drawn without a legend (it would outgrow the figure).
MAX_LEGEND = 12
# The columns figure draws one panel per column, at most this many (a note names the rest).
MAX_PANELS = 6
PER_DOF = ("vel_", "acc_", "reaction_")  # the prefixes of a DOF's other quantities in a CSV


def energy_columns(columns):
    """The energy terms present, with their labels (energy_error has its own panel)."""
    return [(c, label) for c, label in ENERGY_TERMS if c in columns]


class BadInput(Exception):
    pass


def finite_table(np, path, header, rows):
    """Checks a result's columns: names unique and not empty, t first, every cell a finite
    number, t not decreasing. `rows` holds the data lines (line number, cells)."""
    if header and header[0] == "dof":
        raise BadInput(f"{path}: not a condyn result (its first column is not t): mode shapes "
                       "(condyn modes --shapes) are drawn with --scene SCENE")
    if not header or header[0] != "t":
        raise BadInput(f"{path}: not a condyn result (its first column is not t)")
    seen = set()
    for name in header:
        if not name or name in seen:
            raise BadInput(f"{path}:1: " + (f"column '{name}' named twice" if name else
                                            "a column without a name"))
        seen.add(name)
    if not rows:
        raise BadInput(f"{path}: no rows")
    for number, cells in rows:
        if len(cells) != len(header):
            raise BadInput(f"{path}:{number}: {len(cells)} cells for the header's "
                           f"{len(header)} columns")
    try:
        data = np.array([cells for _, cells in rows], dtype=float)
    except ValueError:  # find the cell, row by row (the fast path above fails only here)
        for number, cells in rows:
            for cell in cells:
                try:
                    float(cell)
                except ValueError:
                    raise BadInput(f"{path}:{number}: '{cell[:40]}' is not a number") from None
        raise
    bad = np.argwhere(~np.isfinite(data))
    if bad.size:
        k, j = bad[0]
        raise BadInput(f"{path}:{rows[k][0]}: column {header[j]}: '{rows[k][1][j].strip()}' is "
                       "not a finite number (condyn writes none)")
    back = np.flatnonzero(np.diff(data[:, 0]) < 0)
    if back.size:
        k = back[0] + 1
        raise BadInput(f"{path}:{rows[k][0]}: t = {data[k, 0]:g} after t = {data[k - 1, 0]:g} "
                       "(times must not decrease)")
    return data


def read_csv(np, path):
    with open(path, "rb") as f:
        raw = f.read()
    if not raw.strip():
        raise BadInput(f"{path}: empty file (condyn plot reads the CSV or HDF5 of condyn run)")
    if b"\0" in raw:
        line = raw[:raw.index(b"\0")].count(b"\n") + 1
        raise BadInput(f"{path}:{line}: binary data (a NUL byte), not a CSV")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        line = raw[:e.start].count(b"\n") + 1
        raise BadInput(f"{path}:{line}: not UTF-8 text (byte 0x{raw[e.start]:02x}): "
                       "not a condyn result") from None
    lines = text.splitlines()
    header = lines[0].strip().split(",")
    rows = [(n, line.strip().split(",")) for n, line in enumerate(lines[1:], start=2)
            if line.strip()]
    data = finite_table(np, path, header, rows)
    columns = {name: data[:, k] for k, name in enumerate(header)}
    prefixed = ("vel_", "acc_", "reaction_", "lambda_")
    # The flag of rows near a singular configuration, when written, is the last column.
    values = header[1:-1] if header[-1] == NEAR_SINGULAR else header[1:]
    dofs = [n for n in values
            if not n.startswith(prefixed) and n not in ENERGY_NAMES and n not in DRIFT_NAMES]
    others = []
    if any(n.endswith(MECHANISM_POSES) for n in dofs):
        dofs = [n for n in dofs if "." not in n or n.rsplit(".", 1)[1] not in MECHANISM_RATES]
    else:
        # A CSV with a DOF's velocity, acceleration or reaction columns names its DOFs through
        # them ([output] dofs selects the same DOFs for every quantity): the other unprefixed
        # columns are [[derived]] columns. Without such columns they cannot be told apart.
        named = {n[len(p):] for n in values for p in PER_DOF
                 if n.startswith(p) and not n.startswith("acc_abs_")}
        if named:
            others = [n for n in dofs if n not in named]
            dofs = [n for n in dofs if n in named]
    # acc_abs_ columns exist only under [ground_motion]: the displacements are relative to it
    return columns, dofs, any(n.startswith("acc_abs_") for n in header), others


def h5_names(h5py, f, path, name):
    """A dataset of names, fixed-length bytes or variable-length strings, as a list of str."""
    ds = h5_dataset(h5py, f, path, name)
    if ds.ndim != 1 or not (ds.dtype.kind == "S" or h5py.check_string_dtype(ds.dtype)):
        raise BadInput(f"{path}: dataset {name} is not a list of names "
                       f"(shape {ds.shape}, type {ds.dtype})")
    names = []
    for s in h5_read(path, name, ds):
        try:
            names.append(s.decode("utf-8") if isinstance(s, bytes) else str(s))
        except UnicodeDecodeError:
            raise BadInput(f"{path}: dataset {name}: a name that is not UTF-8") from None
    return names


def h5_dataset(h5py, f, path, name):
    item = f.get(name)
    if not isinstance(item, h5py.Dataset):
        raise BadInput(f"{path}: not a condyn result (no dataset {name})" if item is None else
                       f"{path}: {name} is a group, not a dataset")
    return item


def h5_read(path, name, ds):
    try:
        return ds[()]
    except (OSError, ValueError, TypeError) as e:
        raise BadInput(f"{path}: dataset {name} cannot be read (a truncated or damaged file?: "
                       f"{e})") from None


def h5_numbers(np, h5py, f, path, name, shape):
    """A numeric dataset of the given shape (None: any length), every entry finite."""
    ds = h5_dataset(h5py, f, path, name)
    if ds.dtype.kind not in "fiu":
        raise BadInput(f"{path}: dataset {name} holds {ds.dtype}, not numbers")
    if len(ds.shape) != len(shape) or any(
            want is not None and have != want for have, want in zip(ds.shape, shape)):
        want = " x ".join("n" if w is None else str(w) for w in shape)
        raise BadInput(f"{path}: dataset {name} is {' x '.join(map(str, ds.shape)) or 'a scalar'}"
                       f", expected {want} (the rows of t, the columns its names give)")
    values = np.asarray(h5_read(path, name, ds), dtype=float)
    if not np.isfinite(values).all():
        raise BadInput(f"{path}: dataset {name} holds values that are not finite numbers "
                       "(condyn writes none)")
    return values


def read_h5(np, path):
    try:
        import h5py
    except ImportError:
        raise SystemExit(3)
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise BadInput(f"{path}: not an HDF5 file, or a damaged one ({e})") from None
    with f:
        if "t" not in f and "shapes" in f:
            raise BadInput(f"{path}: the modes of condyn modes, not a run's result: mode shapes "
                           "are drawn with --scene SCENE")
        if "t" not in f:
            raise BadInput(f"{path}: not a condyn result (no dataset t), nor the modes of "
                           "condyn modes (no dataset shapes)")
        t = h5_numbers(np, h5py, f, path, "t", (None,))
        if not t.size:
            raise BadInput(f"{path}: no rows")
        if (np.diff(t) < 0).any():
            raise BadInput(f"{path}: dataset t decreases (times must not decrease)")
        nt = t.size
        columns, dofs = {"t": t}, []
        if "displacement" in f:
            dofs = h5_names(h5py, f, path, "dof_names")
            u = h5_numbers(np, h5py, f, path, "displacement", (nt, len(dofs)))
            if len(set(dofs)) != len(dofs):
                raise BadInput(f"{path}: dataset dof_names names a DOF twice")
            columns.update({name: u[:, k] for k, name in enumerate(dofs)})
        if "drift" in f:
            d = h5_numbers(np, h5py, f, path, "drift", (nt, 2))
            columns["drift_position"], columns["drift_velocity"] = d[:, 0], d[:, 1]
        if "energy" in f:
            names = h5_names(h5py, f, path, "energy_columns")
            e = h5_numbers(np, h5py, f, path, "energy", (nt, len(names)))
            columns.update({name: e[:, k] for k, name in enumerate(names)})
        derived = []
        if "derived" in f:  # [[derived]] columns, named by derived_names
            derived = h5_names(h5py, f, path, "derived_names")
            d = h5_numbers(np, h5py, f, path, "derived", (nt, len(derived)))
            columns.update({name: d[:, k] for k, name in enumerate(derived)})
        return columns, dofs, "absolute_acceleration" in f, derived


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


def mode_shapes_file(path):
    """Whether `path` holds mode shapes: the CSV of `condyn modes --shapes` (its first column
    `dof`) or the HDF5 of `condyn modes --out` (a dataset shapes, no t)."""
    if path.lower().endswith((".h5", ".hdf5", ".hdf")):
        try:
            import h5py
        except ImportError:
            raise SystemExit(3)
        try:
            with h5py.File(path, "r") as f:
                return "shapes" in f and "t" not in f
        except OSError:
            return False  # read_result names the problem
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return f.readline().split(",", 1)[0].strip() == "dof"
    except OSError:
        return False  # read_result names the problem


def read_modes_h5(np, path):
    """The HDF5 of `condyn modes --out` (docs/cli.md): {dof: row of shapes}, the mode labels
    (mode_1, ...) and omega per mode; BadInput naming the file and the dataset at fault."""
    import h5py
    with h5py.File(path, "r") as f:
        dofs = h5_names(h5py, f, path, "dof_names")
        if len(set(dofs)) != len(dofs):
            raise BadInput(f"{path}: dataset dof_names names a DOF twice")
        mode = h5_numbers(np, h5py, f, path, "mode", (None,))
        count = mode.size
        if count == 0 or (mode != np.arange(1, count + 1)).any():
            raise BadInput(f"{path}: dataset mode is not the mode numbers 1 to K")
        omega = h5_numbers(np, h5py, f, path, "omega", (count,))
        if (omega < 0).any():
            raise BadInput(f"{path}: dataset omega holds a negative frequency")
        phi = h5_numbers(np, h5py, f, path, "shapes", (len(dofs), count))
    return ({d: phi[k] for k, d in enumerate(dofs)}, [f"mode_{j}" for j in range(1, count + 1)],
            omega)


def read_mode_shapes(np, path):
    """Mode shapes from the CSV of `condyn modes --shapes` (no frequencies: omega None) or the
    HDF5 of `condyn modes --out`: (shapes, modes, omega). BadInput names the file and problem."""
    if path.lower().endswith((".h5", ".hdf5", ".hdf")):
        return read_modes_h5(np, path)
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
        table, modes = shapes.read_shapes(np, path, lines[0].strip().split(","), lines)
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise BadInput(str(e) if isinstance(e, ValueError) and str(e).startswith(path)
                       else f"{path}: cannot be read as mode shapes ({e})") from None
    return table, modes, None


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
