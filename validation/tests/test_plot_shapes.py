"""`condyn plot RESULT --scene SCENE` (issue 47, item 9): the deformed shape of a run and the mode
shapes of `condyn modes --shapes` drawn on the scene's nodes (a matrix model's coordinates file,
a truss's nodes), where they should be, inside their figure; and the refusals (exit 2)."""
import glob
import os
import subprocess
import tempfile

import matplotlib.pyplot as plt
import numpy as np
import pytest

import figure_style
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
    fig, notes = plot_shapes.draw_modes(plt, np, figure_style, nodes_map(), shapes, modes, "b")
    assert len(fig.axes) == plot_shapes.MAX_MODES
    assert notes == ["modes 7 to 7 not drawn (at most 6)"]
    assert fig.get_figwidth() == pytest.approx(figure_style.PAGE_WIDTH)
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
    assert node_map_files() <= before  # the node map handed to the script is removed


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
