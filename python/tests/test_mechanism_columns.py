"""The columns of a result: per DOF, or a mechanism's per body and joint (docs/python.md), and
bit for bit those of the command's CSV."""

import subprocess

import numpy as np

import condyn
from conftest import QUICKSTART

# A bar of length 1 hinged at its end A to the ground's point O, released horizontal under
# gravity; its far end B is a named point written by [output] points.
BAR = {
    "model": {"type": "multibody", "dimension": 2, "gravity": [0.0, -9.81],
              "ground": {"O": [0.0, 0.0]}},
    "body": [{"name": "bar", "mass": 1.0, "inertia": 1.0 / 12.0, "position": [0.5, 0.0],
              "angle": 0.0, "points": {"A": [-0.5, 0.0], "B": [0.5, 0.0]}}],
    "joint": [{"name": "hinge", "type": "revolute", "bodies": ["ground", "bar"],
               "points": ["O", "A"]}],
    "solve": {"t_end": 1.0, "output_step": 0.1, "scheme": "ggl", "rtol": 1e-8, "atol": 1e-10},
    "output": {"quantities": ["displacement", "velocity", "acceleration", "reaction",
                              "multiplier", "drift"], "points": ["bar.B"]},
}

BAR_TOML = """[model]
type = "multibody"
dimension = 2
gravity = [0.0, -9.81]
ground = { O = [0.0, 0.0] }
[[body]]
name = "bar"
mass = 1.0
inertia = 0.08333333333333333
position = [0.5, 0.0]
angle = 0.0
points = { A = [-0.5, 0.0], B = [0.5, 0.0] }
[[joint]]
name = "hinge"
type = "revolute"
bodies = ["ground", "bar"]
points = ["O", "A"]
[solve]
t_end = 1.0
output_step = 0.1
scheme = "ggl"
rtol = 1e-8
atol = 1e-10
[output]
quantities = ["displacement", "velocity", "acceleration", "reaction", "multiplier", "drift"]
points = ["bar.B"]
"""


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: table[:, i] for i, name in enumerate(header)}, header


def test_a_model_of_dofs_names_every_quantity_by_its_dofs():
    r = condyn.run(str(QUICKSTART), scheme="ggl")
    assert r.velocity_names == r.dof_names
    assert r.acceleration_names == r.dof_names
    assert r.reaction_names == r.dof_names
    assert r.points is None and r.point_names == []
    assert r.summary["worst_drift_joint"] is None
    assert r.summary["worst_drift_body"] is None


def test_a_mechanism_shows_its_bodies_and_joints_as_the_cli_csv(cli, tmp_path):
    scene = tmp_path / "bar.toml"
    scene.write_text(BAR_TOML)
    out = tmp_path / "bar.csv"
    subprocess.run([str(cli), "run", str(scene), "--out", str(out)], check=True,
                   capture_output=True)
    col, header = read_csv(out)
    r = condyn.run(BAR)
    assert r.dof_names == ["bar.x", "bar.y", "bar.angle"]
    assert r.velocity_names == ["bar.vx", "bar.vy", "bar.omega"]
    assert r.acceleration_names == ["bar.ax", "bar.ay", "bar.alpha"]
    assert r.reaction_names == ["hinge.fx", "hinge.fy", "hinge.m"]
    assert r.point_names == ["bar.B.x", "bar.B.y"]
    nt = len(r.t)
    assert r.u.shape == (nt, 3) and r.v.shape == (nt, 3) and r.reaction.shape == (nt, 3)
    assert r.points.shape == (nt, 2)
    # The CSV's columns are the same names, no prefix, and the same doubles.
    assert header == (["t"] + r.dof_names + r.velocity_names + r.acceleration_names
                      + r.reaction_names + ["lambda_" + c for c in r.constraint_names]
                      + ["drift_position", "drift_velocity"] + r.point_names + ["near_singular"])
    np.testing.assert_array_equal(r.t, col["t"])
    # The flag of rows near a singular configuration (none on a hinged bar): Python's too.
    np.testing.assert_array_equal(r.near_singular, col["near_singular"] == 1)
    for array, names in ((r.u, r.dof_names), (r.v, r.velocity_names),
                         (r.a, r.acceleration_names), (r.reaction, r.reaction_names),
                         (r.points, r.point_names)):
        for j, name in enumerate(names):
            np.testing.assert_array_equal(array[:, j], col[name])
    # The far end B is the centre plus half the bar along its angle, to the drift GGL leaves in
    # the bar's unit vector: within 100 times the run's atol (1e-10).
    drift_bound = 100 * BAR["solve"]["atol"]
    x, y, angle = r.u[:, 0], r.u[:, 1], r.u[:, 2]
    np.testing.assert_allclose(r.points[:, 0], x + 0.5 * np.cos(angle), rtol=0, atol=drift_bound)
    np.testing.assert_allclose(r.points[:, 1], y + 0.5 * np.sin(angle), rtol=0, atol=drift_bound)
