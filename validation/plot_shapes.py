"""Deformed and mode shapes for `condyn plot RESULT --scene SCENE` (docs/plots.md).

The scene's node map (a truss's nodes and members, a matrix model's `[model] coordinates`) comes
from condyn as JSON: node ids, positions, the DOF moving each node along x, y, z ("" for none) and
the node pairs drawn as lines. plot_result.py calls read_nodes, then draw_deformed for a run's
result or draw_modes for the CSV of `condyn modes --shapes` or the HDF5 of `condyn modes --out`.
"""
import json
import math

# The largest drawn displacement, as a fraction of the model's extent: visible, and small
# enough that the shape reads as a deformation of the grey undeformed model.
SHAPE_FRACTION = 0.1
# Mode shapes drawn side by side, at most this many (a note names the rest).
MAX_MODES = 6


class NodeMap:
    def __init__(self, data):
        self.dimension = int(data["dimension"])
        self.nodes = list(data["nodes"])
        self.position = [list(map(float, p)) for p in data["position"]]
        self.dofs = [list(d) for d in data["dofs"]]
        self.edges = [tuple(e) for e in data["edges"]]

    def plane(self, np):
        """The two axes drawn: x and y in 2D; in 3D the two of largest extent, in order."""
        if self.dimension == 2:
            return (0, 1)
        extent = np.ptp(np.array(self.position), axis=0)
        return tuple(sorted(np.argsort(-extent, kind="stable")[:2]))

    def history(self, np, columns):
        """rows x nodes x 3 displacements from the result's columns (a DOF missing there: 0),
        and the DOFs of the map that were missing."""
        rows = len(next(iter(columns.values())))
        u = np.zeros((rows, len(self.nodes), 3))
        missing = []
        for k, dofs in enumerate(self.dofs):
            for a, dof in enumerate(dofs):
                if dof and dof in columns:
                    u[:, k, a] = columns[dof]
                elif dof:
                    missing.append(dof)
        return u, missing

    def mapped(self):
        return sum(1 for dofs in self.dofs for dof in dofs if dof)


def read_nodes(path):
    with open(path, encoding="utf-8") as f:
        return NodeMap(json.load(f))


def scale_for(np, nodes, peak):
    """The factor drawing the largest displacement `peak` at SHAPE_FRACTION of the extent."""
    extent = float(np.max(np.ptp(np.array(nodes.position), axis=0)))
    return SHAPE_FRACTION * (extent if extent > 0 else 1.0) / peak


def draw_on(ax, np, nodes, u, factor):
    """The undeformed model in grey and the deformed one in black, in the map's plane."""
    i, j = nodes.plane(np)
    x = np.array(nodes.position)
    d = x + factor * u
    for a, b in nodes.edges:
        ax.plot(x[[a, b], i], x[[a, b], j], color="0.75", lw=0.6)
        ax.plot(d[[a, b], i], d[[a, b], j], color="black", lw=0.9)
    ax.plot(x[:, i], x[:, j], "o", color="0.75", ms=2.5, label="undeformed")
    ax.plot(d[:, i], d[:, j], "o", color="black", ms=2.5, label="deformed")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("xyz"[i])
    ax.set_ylabel("xyz"[j])
    ax.grid(True, alpha=0.3)


def missing_note(missing, where):
    if not missing:
        return None
    more = " ..." if len(missing) > 6 else ""
    return (f"{len(missing)} DOFs of the node map are not in {where} (drawn at 0): "
            f"{', '.join(missing[:6])}{more}")


def draw_deformed(plt, np, style, nodes, columns, title_stem):
    """The shape at the output time of the largest nodal displacement: (figure, note), or
    (None, why not)."""
    t = columns["t"]
    u, missing = nodes.history(np, columns)
    if len(missing) == nodes.mapped():
        return None, "the result has none of the node map's DOFs: no deformed shape drawn"
    magnitude = np.linalg.norm(u, axis=2).max(axis=1)  # per row: the largest nodal |u|
    row = int(np.argmax(magnitude))
    peak = float(magnitude[row])
    if peak == 0.0:
        return None, "every node stays at rest: no deformed shape drawn"
    factor = scale_for(np, nodes, peak)
    fig, ax = plt.subplots(figsize=(style.COLUMN_WIDTH, 3.2))
    draw_on(ax, np, nodes, u[row], factor)
    style.title(fig, f"{title_stem}: deformed shape at t = {t[row]:.4g}, largest nodal "
                     f"displacement {peak:.3g}, drawn x {factor:.3g}")
    legend = style.legend_below(fig, ax.get_lines()[-2:], ncol=2)
    style.fit(fig, legend)
    return fig, missing_note(missing, "the result")


def read_shapes(np, path, header, lines):
    """The CSV of `condyn modes --shapes` (header dof, mode_1, ...): {dof: row of values} and the
    mode numbers. Raises ValueError naming the line of a malformed row."""
    modes = header[1:]
    if not modes or any(not m.startswith("mode_") for m in modes):
        raise ValueError(f"{path}:1: a mode shapes file has the columns dof, mode_1, mode_2, ...")
    shapes = {}
    for n, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        cells = line.strip().split(",")
        if len(cells) != len(header):
            raise ValueError(f"{path}:{n}: {len(cells)} cells, the header {len(header)}")
        values = np.array([float(c) for c in cells[1:]])
        if not np.all(np.isfinite(values)):
            raise ValueError(f"{path}:{n}: a value that is not finite")
        shapes[cells[0]] = values
    return shapes, modes


def mode_title(label, omega):
    """A mode panel's title: `mode 3`, and with its ω (rad/s) its frequency and period."""
    name = label.replace("_", " ")
    if omega is None:
        return name
    if omega == 0.0:  # a rigid motion: its period is infinite (condyn modes writes inf)
        return f"{name}\nf = 0 Hz\nT = ∞"
    return f"{name}\nf = {omega / (2 * math.pi):.4g} Hz\nT = {2 * math.pi / omega:.4g} s"


def draw_modes(plt, np, style, nodes, shapes, modes, title_stem, omega=None):
    """Up to MAX_MODES mode shapes side by side, each scaled to SHAPE_FRACTION of the extent and
    titled with its frequency and period when `omega` (per mode, rad/s) is given: (figure,
    notes)."""
    count = min(len(modes), MAX_MODES)
    columns = {dof: values for dof, values in shapes.items()}
    u, missing = nodes.history(np, columns)
    fig, axes = plt.subplots(1, count, figsize=(style.PAGE_WIDTH, 3.4), squeeze=False)
    for j, ax in enumerate(axes[0]):
        peak = float(np.linalg.norm(u[j], axis=1).max())
        draw_on(ax, np, nodes, u[j], scale_for(np, nodes, peak) if peak > 0 else 0.0)
        ax.set_title(mode_title(modes[j], None if omega is None else float(omega[j])),
                     fontsize=8)
        if j:
            ax.set_ylabel("")
    style.title(fig, f"{title_stem}: mode shapes, each drawn with its largest nodal "
                     f"displacement at {SHAPE_FRACTION:g} of the model's extent")
    legend = style.legend_below(fig, axes[0][0].get_lines()[-2:], ncol=2)
    style.fit(fig, legend)
    notes = [missing_note(missing, "the shapes file")] if missing else []
    if omega is None:
        notes.append("the shapes CSV holds no frequencies: the HDF5 of condyn modes --out "
                     "FILE.h5 holds them with the shapes, and each panel then gives its mode's "
                     "frequency and period")
    if len(modes) > count:
        notes.append(f"modes {count + 1} to {len(modes)} not drawn (at most {MAX_MODES})")
    return fig, notes
