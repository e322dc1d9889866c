"""`condyn plot RESULT --scene SCENE` (issue 47, items 6 and 9): the deformed shape of a run and the
mode shapes of `condyn modes --shapes` (CSV) or `condyn modes --out FILE.h5` (HDF5, each panel
titled with its mode's frequency and period) drawn on the scene's nodes (a matrix model's
coordinates file, a truss's nodes), where they should be, inside their figure; and the refusals
(exit 2)."""
import glob
import math
import os
import subprocess
import tempfile

import h5py
import matplotlib.pyplot as plt
import numpy as np
import pytest

import figure_style
import plot_result
import plot_shapes
from layout import problems

CONDYN = os.environ.get("CONDYN_BINARY", "build/condyn")

# Three floors of a shear building, DOFs u1..u3 named from the node ids; node 0 the ground.
SCENE = """[model]
type = "matrix"
dofs = ["u1", "u2", "u3"]
mass = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
stiffness = [[200.0, -100.0, 0.0], [-100.0, 200.0, -100.0], [0.0, -100.0, 100.0]]
coordinates = { file = "nodes.csv", dofs = { x = "u{node}" } }
[ground_motion]
influence = { "u*" = 1.0 }
acceleration = { type = "harmonic", amplitude = 1.0, omega = 5.0 }
[solve]
t_end = 2.0
output_step = 0.05
"""
NODES = "node,x,y\n0,0,0\n1,0,3\n2,0,6\n3,0,9\n"


def condyn(*args, cwd):
    return subprocess.run([CONDYN, *args], cwd=cwd, capture_output=True, text=True, timeout=120)


@pytest.fixture
def building(tmp_path):
    (tmp_path / "b.toml").write_text(SCENE)
    (tmp_path / "nodes.csv").write_text(NODES)
    return tmp_path


def nodes_map():
    return plot_shapes.NodeMap({"dimension": 2, "nodes": ["0", "1", "2", "3"],
                                "position": [[0, 3 * k, 0] for k in range(4)],
                                "dofs": [["", "", ""]] + [[f"u{k}", "", ""] for k in (1, 2, 3)],
                                "edges": []})


def test_deformed_shape_drawn_at_the_peak_row_scaled_to_its_fraction():
    figure_style.paper_style(plt)
    t = np.linspace(0.0, 1.0, 11)
    columns = {"t": t, "u1": np.sin(3 * t), "u2": 2 * np.sin(3 * t), "u3": 3 * np.sin(3 * t)}
    fig, note = plot_shapes.draw_deformed(plt, np, figure_style, nodes_map(), columns, "run")
    assert note is None
    row = int(np.argmax(3 * np.abs(np.sin(3 * t))))  # node 3 moves most
    peak = 3 * abs(np.sin(3 * t[row]))
    factor = plot_shapes.SHAPE_FRACTION * 9.0 / peak  # the extent: 9 high
    deformed = [ln for ln in fig.axes[0].get_lines() if ln.get_label() == "deformed"][0]
    x = deformed.get_xdata()
    # x0 + factor u at the peak row, to the roundoff of the factor (a norm, a division) and of
    # the product: 4 eps.
    expected = factor * np.array([0.0, 1.0, 2.0, 3.0]) * np.sin(3 * t[row])
    assert np.allclose(x, expected, rtol=4 * np.finfo(float).eps, atol=0)
    assert abs(x[-1]) == pytest.approx(plot_shapes.SHAPE_FRACTION * 9.0, rel=1e-15)
    assert f"t = {t[row]:.4g}" in fig._suptitle.get_text().replace("\n", " ")
    assert fig.get_figwidth() == pytest.approx(figure_style.COLUMN_WIDTH)
    assert problems(fig) == []
    plt.close(fig)


def test_a_result_without_the_map_dofs_or_at_rest_draws_nothing_and_says_why():
    t = np.linspace(0.0, 1.0, 3)
    fig, why = plot_shapes.draw_deformed(plt, np, figure_style, nodes_map(), {"t": t, "v": t},
                                         "run")
    assert fig is None and "none of the node map's DOFs" in why
    still = {"t": t, "u1": 0 * t, "u2": 0 * t, "u3": 0 * t}
    fig, why = plot_shapes.draw_deformed(plt, np, figure_style, nodes_map(), still, "run")
    assert fig is None and "every node stays at rest" in why
    fig, note = plot_shapes.draw_deformed(plt, np, figure_style, nodes_map(),
                                          {"t": t, "u1": t, "u3": t}, "run")
    assert fig is not None and note.startswith("1 DOFs of the node map are not in the result")
    plt.close(fig)


def test_mode_shapes_figure_inside_the_page_width():
    figure_style.paper_style(plt)
    shapes = {f"u{k}": np.array([k, -k, (-1) ** k, 1.0, 2.0, 3.0, 4.0]) for k in (1, 2, 3)}
    modes = [f"mode_{j}" for j in range(1, 8)]
    # A rigid motion first (ω = 0, T infinite), then periods from 0.5 s down, with long figures.
    omega = np.array([0.0, 4 * math.pi, 123.456789, 1e4, 2e5, 3.3e6, 4e7])
    fig, notes = plot_shapes.draw_modes(plt, np, figure_style, nodes_map(), shapes, modes, "b",
                                        omega)
    assert len(fig.axes) == plot_shapes.MAX_MODES
    assert notes == ["modes 7 to 7 not drawn (at most 6)"]
    titles = [ax.get_title() for ax in fig.axes]
    assert titles[0] == "mode 1\nf = 0 Hz\nT = ∞"
    assert titles[1] == "mode 2\nf = 2 Hz\nT = 0.5 s"  # 4π rad/s
    assert fig.get_figwidth() == pytest.approx(figure_style.PAGE_WIDTH)
    assert problems(fig) == []
    plt.close(fig)
    # The CSV holds no frequencies: the panels are named alone, and a note says where they are.
    fig, notes = plot_shapes.draw_modes(plt, np, figure_style, nodes_map(), shapes, modes[:2],
                                        "b")
    assert [ax.get_title() for ax in fig.axes] == ["mode 1", "mode 2"]
    assert notes == ["the shapes CSV holds no frequencies: the HDF5 of condyn modes --out "
                     "FILE.h5 holds them with the shapes, and each panel then gives its mode's "
                     "frequency and period"]
    assert problems(fig) == []
    plt.close(fig)


def node_map_files():
    return set(glob.glob(os.path.join(tempfile.gettempdir(), "condyn-plot-nodes-*.json")))


def test_plot_scene_draws_the_shape_and_the_modes(building):
    before = node_map_files()
    assert condyn("run", "b.toml", "--out", "b.csv", cwd=building).returncode == 0
    r = condyn("plot", "b.csv", "--scene", "b.toml", "--format", "png", cwd=building)
    assert r.returncode == 0, r.stderr
    assert (building / "b_shape.png").exists() and (building / "b_displacement.png").exists()
    assert condyn("modes", "b.toml", "--shapes", "s.csv", cwd=building).returncode == 0
    r = condyn("plot", "s.csv", "--scene", "b.toml", "--format", "png", cwd=building)
    assert r.returncode == 0, r.stderr
    assert (building / "s_modes.png").exists()
    assert "the shapes CSV holds no frequencies" in r.stdout
    assert node_map_files() <= before  # the node map handed to the script is removed


def test_plot_scene_draws_the_modes_of_the_hdf5_titled_with_the_table_s_frequencies(building):
    assert condyn("modes", "b.toml", "--out", "m.csv", "--shapes", "s.csv",
                  cwd=building).returncode == 0
    r = condyn("modes", "b.toml", "--out", "m.h5", cwd=building)
    assert r.returncode == 0, r.stderr
    r = condyn("plot", "m.h5", "--scene", "b.toml", "--format", "png", cwd=building)
    assert r.returncode == 0, r.stderr
    assert (building / "m_modes.png").stat().st_size > 5000
    assert "no frequencies" not in r.stdout
    # What the script draws: the shapes CSV's values and the table's frequencies and periods,
    # the same doubles (each file's numbers round-trip).
    shapes, modes, omega = plot_result.read_mode_shapes(np, str(building / "m.h5"))
    csv_shapes, csv_modes, none = plot_result.read_mode_shapes(np, str(building / "s.csv"))
    assert none is None
    assert modes == csv_modes == ["mode_1", "mode_2", "mode_3"]
    assert shapes.keys() == csv_shapes.keys()
    assert all(np.array_equal(shapes[d], csv_shapes[d]) for d in shapes)
    table = np.loadtxt(building / "m.csv", delimiter=",", skiprows=1)
    assert np.array_equal(omega, table[:, 1])
    figure_style.paper_style(plt)
    fig, _ = plot_shapes.draw_modes(plt, np, figure_style, nodes_map(), shapes, modes, "m",
                                    omega)
    for ax, (j, _, f, period) in zip(fig.axes, table[:, :4]):
        assert ax.get_title() == f"mode {j:.0f}\nf = {f:.4g} Hz\nT = {period:.4g} s"
    plt.close(fig)


def test_plot_scene_refusals_exit_2(building):
    assert condyn("run", "b.toml", "--out", "b.csv", cwd=building).returncode == 0
    (building / "bare.toml").write_text(SCENE.replace(
        'coordinates = { file = "nodes.csv", dofs = { x = "u{node}" } }\n', ""))
    r = condyn("plot", "b.csv", "--scene", "bare.toml", cwd=building)
    assert r.returncode == 2
    assert "--scene bare.toml: no nodes to draw shapes on" in r.stderr
    (building / "nodes.csv").write_text("node,x,y\n1,0,0\n1,0,3\n")
    r = condyn("plot", "b.csv", "--scene", "b.toml", cwd=building)
    assert r.returncode == 2
    assert "model.coordinates.file: " in r.stderr and "nodes.csv:3: node '1' is listed twice" \
        in r.stderr
    assert not (building / "b_shape.png").exists()
    # A mode shapes file without --scene is no run result.
    (building / "nodes.csv").write_text(NODES)
    assert condyn("modes", "b.toml", "--shapes", "s.csv", cwd=building).returncode == 0
    r = condyn("plot", "s.csv", cwd=building)
    assert r.returncode == 2 and "mode shapes (condyn modes --shapes) are drawn with --scene" \
        in r.stderr


def modes_h5(path, **changes):
    """A modes file laid out as condyn modes --out writes it, with `changes` (None: dropped)."""
    data = dict(mode=np.arange(1, 3), omega=np.array([1.0, 2.0]), shapes=np.eye(3)[:, :2],
                dof_names=np.array([b"u1", b"u2", b"u3"]))
    data.update(changes)
    with h5py.File(path, "w") as f:
        for name, value in data.items():
            if value is not None:
                f[name] = value


@pytest.mark.parametrize("changes, says", [
    (dict(shapes=np.eye(3)), "dataset shapes is 3 x 3, expected 3 x 2"),
    (dict(shapes=np.full((3, 2), np.nan)), "dataset shapes holds values that are not finite"),
    (dict(dof_names=None), "not a condyn result (no dataset dof_names)"),
    (dict(dof_names=np.array([b"u1", b"u1", b"u3"])), "dataset dof_names names a DOF twice"),
    (dict(omega=np.array([1.0])), "dataset omega is 1, expected 2"),
    (dict(omega=np.array([-1.0, 2.0])), "dataset omega holds a negative frequency"),
    (dict(mode=np.array([2, 1])), "dataset mode is not the mode numbers 1 to K"),
    (dict(mode=None), "not a condyn result (no dataset mode)"),
])
def test_plot_scene_refuses_a_malformed_modes_file_exit_2(building, changes, says):
    modes_h5(building / "bad.h5", **changes)
    r = condyn("plot", "bad.h5", "--scene", "b.toml", "--format", "png", cwd=building)
    assert (r.returncode, "Traceback" in r.stderr) == (2, False), r.stderr
    assert f"bad.h5: {says}" in r.stderr
    assert not list(building.glob("*.png"))


def test_plot_refuses_a_modes_file_without_scene_and_a_foreign_hdf5_exit_2(building):
    assert condyn("modes", "b.toml", "--out", "m.h5", cwd=building).returncode == 0
    r = condyn("plot", "m.h5", "--format", "png", cwd=building)
    assert r.returncode == 2
    assert "m.h5: the modes of condyn modes, not a run's result: mode shapes are drawn with " \
           "--scene SCENE" in r.stderr
    with h5py.File(building / "other.h5", "w") as f:
        f["x"] = np.zeros(3)
    r = condyn("plot", "other.h5", "--scene", "b.toml", "--format", "png", cwd=building)
    assert r.returncode == 2
    assert "other.h5: not a condyn result (no dataset t), nor the modes of condyn modes (no " \
           "dataset shapes)" in r.stderr
    assert not list(building.glob("*.png"))
