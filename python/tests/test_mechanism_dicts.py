"""Mechanisms as Python dicts (issue 44 item 13, docs/python.md): `"body"`, `"joint"` and
`"force"` lists of dicts, vectors as lists, tuples or numpy arrays, give the command's results
bit for bit, under every scheme; a refusal names the same key path as the file's."""

import subprocess
import tomllib

import numpy as np
import pytest

import condyn
from conftest import ROOT

SLIDER_CRANK = ROOT / "models" / "scenes" / "multibody" / "slider_crank.toml"
SPATIAL_FOUR_BAR = ROOT / "models" / "scenes" / "multibody" / "spatial_four_bar.toml"


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: table[:, i] for i, name in enumerate(header)}


def load(path):
    with open(path, "rb") as f:
        return tomllib.load(f)


def as_numpy(scene):
    """The scene's body vectors as numpy arrays and its point markers as tuples: the forms a
    user builds a mechanism from in Python (same values, so the same doubles)."""
    for body in scene["body"]:
        for key in ("position", "velocity", "inertia"):
            if isinstance(body.get(key), list):
                body[key] = np.array(body[key])
        body["points"] = {name: tuple(p) for name, p in body.get("points", {}).items()}
    return scene


def result_columns(r):
    """The Python result's columns by the CSV's names (docs/python.md)."""
    cols = {"t": r.t, "drift_position": r.drift[:, 0], "drift_velocity": r.drift[:, 1]}
    groups = [(r.u, r.dof_names), (r.v, r.velocity_names), (r.a, r.acceleration_names),
              (r.reaction, r.reaction_names), (r.points, r.point_names),
              (r.multiplier, ["lambda_" + c for c in r.constraint_names]),
              (r.energy_balance, r.energy_columns)]
    for array, names in groups:
        if array is not None:
            cols.update({name: array[:, j] for j, name in enumerate(names)})
    if r.near_singular is not None:  # the CSV's flag column: 1 inside a singular passage
        cols["near_singular"] = r.near_singular.astype(float)
    return cols


def assert_same_as_cli(result, csv_path):
    """Every column of the command's CSV is the Python result's, bit for bit."""
    mine = result_columns(result)
    for name, values in read_csv(csv_path).items():
        assert name in mine, f"{name}: a CSV column the result does not have"
        np.testing.assert_array_equal(mine[name], values, err_msg=name)


def cli_run(cli, scene, scheme, out, *flags):
    return subprocess.run([str(cli), "run", str(scene), "--scheme", scheme, "--out", str(out),
                           *flags], capture_output=True, text=True)


@pytest.mark.parametrize("scheme", ["index1", "baumgarte", "ggl", "index2", "index3",
                                    "projection", "elimination", "newmark", "hht",
                                    "generalized_alpha"])
def test_slider_crank_from_a_dict_is_the_cli_run_bit_for_bit(cli, tmp_path, scheme):
    out = tmp_path / "slider_crank.csv"
    proc = cli_run(cli, SLIDER_CRANK, scheme, out)
    assert proc.returncode == 0, proc.stderr
    r = condyn.run(as_numpy(load(SLIDER_CRANK)), scheme=scheme)
    assert r.dof_names[:3] == ["crank.x", "crank.y", "crank.angle"]
    assert r.point_names == ["crank.B.x", "crank.B.y"]
    assert_same_as_cli(r, out)


@pytest.mark.parametrize("scheme", ["newmark", "hht", "generalized_alpha"])
def test_the_newmark_family_with_a_step_from_a_dict_is_the_cli_run_bit_for_bit(cli, tmp_path,
                                                                              scheme):
    # step= is the command's --step: the same fixed-step run, its summary's counts the command's
    # (t_end / h steps; one factorization per Newton iteration on a mechanism).
    out = tmp_path / "slider_crank.csv"
    proc = cli_run(cli, SLIDER_CRANK, scheme, out, "--step", "0.01")
    assert proc.returncode == 0, proc.stderr
    r = condyn.run(as_numpy(load(SLIDER_CRANK)), scheme=scheme, step=0.01)
    assert_same_as_cli(r, out)
    assert r.summary["scheme"] == scheme
    assert r.summary["steps"] == round(load(SLIDER_CRANK)["solve"]["t_end"] / 0.01)
    assert f"{r.summary['steps']} steps" in proc.stdout + proc.stderr
    assert r.summary["newton_iterations"] >= r.summary["steps"]
    assert r.summary["jacobian_evals"] == r.summary["newton_iterations"]


@pytest.mark.parametrize("step,message", [(-0.01, "solve.step"), (10.0, "solve.step"),
                                          (True, "step: expected a number")])
def test_a_bad_step_is_refused_naming_it(step, message):
    with pytest.raises(condyn.SceneError, match=message):
        condyn.run(load(SLIDER_CRANK), scheme="hht", step=step)


def test_a_setting_the_cli_refuses_is_refused_from_a_dict_with_its_reason(cli, tmp_path):
    # Newmark's beta below gamma/2: conditionally stable, refused naming the key.
    text = SLIDER_CRANK.read_text().replace("[solve]\n", "[solve]\nnewmark = { beta = 0.2 }\n")
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    proc = cli_run(cli, bad, "newmark", tmp_path / "x.csv")
    assert proc.returncode == 2
    scene = load(SLIDER_CRANK)
    scene["solve"]["newmark"] = {"beta": 0.2}
    with pytest.raises(condyn.SceneError) as refusal:
        condyn.run(scene, scheme="newmark")
    reason = str(refusal.value).split(": ", 1)[1]
    assert reason.startswith("solve.newmark.beta: must be >= gamma/2")
    assert reason in proc.stderr


# The coupler's inertia tensor about its centre with products of inertia (body frame, rows).
COUPLER_INERTIA = [[0.004, -0.0005, 0.0], [-0.0005, 0.004, 0.0002], [0.0, 0.0002, 0.003]]


def with_forces(scene, samples):
    """The spatial four-bar with one force element of each kind: a spring-damper from the
    ground to the coupler, a rotational spring-damper at the crank's hinge, a point force on the
    coupler whose x component is a table (`samples`: an array in the dict, a CSV file for the
    command), and a torque on the rocker; the coupler's inertia a full tensor (a 3 x 3 array)."""
    scene["body"][1]["inertia"] = np.array(COUPLER_INERTIA)
    scene["force"] = [
        {"type": "spring_damper", "bodies": ["ground", "coupler"], "points": ["Q", "B"],
         "k": 50.0, "c": 0.5, "rest_length": 0.05},
        {"type": "rotational_spring_damper", "joint": "O", "k": 0.2, "c": 0.01},
        {"type": "point_force", "body": "coupler", "point": "A",
         "force": [{"type": "table", "file": samples}, 0.0, 0.0]},
        {"type": "torque", "body": "rocker",
         "torque": [{"type": "harmonic", "amplitude": 0.05, "omega": 6.0}, 0.0, 0.0]},
    ]
    scene["solve"]["t_end"] = 0.5
    return scene


def toml_of_forces(samples_file):
    return f"""
[[force]]
type = "spring_damper"
bodies = ["ground", "coupler"]
points = ["Q", "B"]
k = 50.0
c = 0.5
rest_length = 0.05

[[force]]
type = "rotational_spring_damper"
joint = "O"
k = 0.2
c = 0.01

[[force]]
type = "point_force"
body = "coupler"
point = "A"
force = [{{ type = "table", file = "{samples_file}" }}, 0.0, 0.0]

[[force]]
type = "torque"
body = "rocker"
torque = [{{ type = "harmonic", amplitude = 0.05, omega = 6.0 }}, 0.0, 0.0]
"""


def test_spatial_mechanism_with_every_force_element_from_a_dict_is_the_cli_run(cli, tmp_path):
    # The force table's samples: 1/3 and the like have no short decimal form, so the CSV holds
    # 17 digits (what reads back as the same double) and the dict the array itself.
    samples = np.column_stack([np.linspace(0.0, 1.0, 7), np.linspace(0.0, 1.0, 7) ** 2 / 3.0])
    np.savetxt(tmp_path / "push.csv", samples, delimiter=",", header="t,value", comments="",
               fmt="%.17g")
    text = SPATIAL_FOUR_BAR.read_text().replace("t_end = 1.0", "t_end = 0.5")
    text = text.replace("inertia = [0.004, 0.004, 0.004]", f"inertia = {COUPLER_INERTIA}")
    assert str(COUPLER_INERTIA) in text
    scene = tmp_path / "spatial_four_bar_forces.toml"
    scene.write_text(text + toml_of_forces("push.csv"))
    out = tmp_path / "forces.csv"
    proc = cli_run(cli, scene, "ggl", out)
    assert proc.returncode == 0, proc.stderr
    r = condyn.run(with_forces(as_numpy(load(SPATIAL_FOUR_BAR)), samples), scheme="ggl")
    assert r.dof_names[3:7] == ["crank.qw", "crank.qx", "crank.qy", "crank.qz"]
    assert_same_as_cli(r, out)
    # The forces act: without them the coupler's pose differs by far more than the run's
    # accuracy (observed 1.25 in its coordinates; 1e-3 is 1e5 times the run's rtol of 1e-8).
    free = load(SPATIAL_FOUR_BAR)
    free["solve"]["t_end"] = 0.5
    moved = np.max(np.abs(condyn.run(free, scheme="ggl").u - r.u))
    assert moved > 1e-3, f"the forces changed the motion by {moved:.3g} only"


def test_a_bad_mechanism_dict_is_refused_by_key_path_as_its_file_is(cli, tmp_path):
    scene = load(SLIDER_CRANK)
    scene["joint"][1]["bodies"] = ["crank", "rood"]
    with pytest.raises(condyn.SceneError) as refusal:
        condyn.run(scene)
    assert str(refusal.value).startswith("<dict>: joint[2].bodies[2]: unknown body 'rood'")
    assert "did you mean rod?" in str(refusal.value)
    bad = tmp_path / "bad.toml"
    bad.write_text(SLIDER_CRANK.read_text().replace('bodies = ["crank", "rod"]',
                                                    'bodies = ["crank", "rood"]'))
    proc = cli_run(cli, bad, "ggl", tmp_path / "bad.csv")
    assert proc.returncode == 2
    assert "joint[2].bodies[2]: unknown body 'rood'" in proc.stderr


def test_the_slider_crank_of_docs_python_md_runs_as_its_file_does():
    # The example of docs/python.md "Mechanisms as dicts", run as written. Its inputs are
    # computed (math.pi, atan2) where the file has decimal literals, so the two runs differ in
    # their last digits and in their step sequences: each within its global error of the same
    # motion, 1000 times the rtol of 1e-8 on coordinates of order 1 (m, rad; observed 5.5e-11).
    text = (ROOT / "docs" / "python.md").read_text()
    section = text.split("## Mechanisms as dicts", 1)[1]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    namespace = {}
    exec(code, namespace)
    r, from_file = namespace["r"], condyn.run(load(SLIDER_CRANK))
    assert r.dof_names == from_file.dof_names
    np.testing.assert_allclose(namespace["x"], from_file.u[:, from_file.dof("slider.x")],
                               rtol=0, atol=1000 * 1e-8)
    np.testing.assert_allclose(r.u, from_file.u, rtol=0, atol=1000 * 1e-8)
