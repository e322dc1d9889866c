"""[[derived]] columns from Python (docs/scenes.md, "Derived columns"): Result.derived holds the
CSV's values, computed from the result's own rows; a sweep keeps a derived column's peak; bad
tables raise SceneError naming the entry."""

import subprocess
import tomllib

import numpy as np
import pytest

import condyn
from condyn.sweep_worker import result_columns, run_one
from conftest import ROOT

FRAME = ROOT / "models" / "scenes" / "two_storey_frame.toml"
EPS = np.finfo(float).eps


def frame():
    with open(FRAME, "rb") as f:
        return tomllib.load(f)


def test_derived_columns_in_the_result_equal_the_cli_csv(cli, tmp_path):
    out = tmp_path / "frame.csv"
    subprocess.run([str(cli), "run", str(FRAME), "--out", str(out)], check=True,
                   capture_output=True)
    with open(out) as f:
        header = f.readline().strip().split(",")
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    col = {name: table[:, i] for i, name in enumerate(header)}
    r = condyn.run(str(FRAME))
    assert r.derived_names == ["drift1", "drift2", "drift_ratio2", "base_shear", "storey_shear2"]
    assert r.derived.shape == (201, 5) and r.derived.dtype == np.float64
    assert not r.derived.flags.writeable  # read-only, as every array of a Result
    for j, name in enumerate(r.derived_names):
        np.testing.assert_array_equal(r.derived[:, j], col[name])  # the same doubles
    # drift2 = u2 − u1 from the result's own columns: roundoff of one difference.
    u1, u2 = r.u[:, r.dof("u1")], r.u[:, r.dof("u2")]
    scale = np.abs(r.u).max()
    assert scale > 1e-4  # the roof moves: not a comparison of zeros
    assert np.abs(r.derived[:, 1] - (u2 - u1)).max() <= 4 * EPS * scale
    # base_shear = −(sum of the support reactions): roundoff of one sum.
    reactions = r.reaction[:, r.dof("base_l")] + r.reaction[:, r.dof("base_r")]
    assert np.abs(r.derived[:, 3] + reactions).max() <= 4 * EPS * np.abs(reactions).max()


def test_a_scene_without_derived_columns_has_an_empty_table():
    scene = frame()
    del scene["derived"], scene["check"]
    r = condyn.run(scene)
    assert r.derived_names == [] and r.derived.shape == (len(r.t), 0)


def test_a_derived_column_is_a_column_a_sweep_keeps():
    r = condyn.run(str(FRAME))
    columns = result_columns(r)
    np.testing.assert_array_equal(columns["base_shear"], r.derived[:, 3])
    # One run of a sweep as a worker does it ([keep] peaks = ["base_shear", "drift_ratio2"]).
    row = run_one(frame(), {}, ["base_shear", "drift_ratio2"])
    assert row["status"] == "ok", row["message"]
    for j, name in ((3, "base_shear"), (2, "drift_ratio2")):
        k = int(np.argmax(np.abs(r.derived[:, j])))
        assert row["peaks"][name] == (abs(r.derived[k, j]), r.t[k])


def test_check_bounds_a_derived_column():
    result = condyn.check(str(FRAME))
    assert result["passed"], [c["text"] for c in result["checks"]]
    scene = frame()
    scene["check"] = [{"quantity": "base_shear", "max_abs": 1000.0}]  # the shear is about 1e5 N
    result = condyn.check(scene)
    assert not result["passed"]
    assert result["checks"][0]["text"].startswith("max |base_shear| = ")


@pytest.mark.parametrize("terms, message", [
    ({"u9": 1.0}, "derived[1].terms.u9: derived column 'drift1': no output column is named 'u9'"),
    ({}, "derived[1].terms: derived column 'drift1': has no terms"),
    ({"u1": float("nan")}, "derived[1].terms.u1: derived column 'drift1': the coefficient nan"),
    ({"lambda_support_l": 1.0}, "'lambda_support_l' is a multiplier column"),
])
def test_bad_derived_tables_raise_scene_error_naming_the_entry(terms, message):
    scene = frame()
    scene["derived"][0]["terms"] = terms
    with pytest.raises(condyn.SceneError) as e:
        condyn.run(scene)
    assert message in str(e.value)


def shaken_frame(tmp_path):
    """models/scenes/shear_frame_el_centro.toml over 1 s, its record by absolute path, with a base
    shear of the inertia forces −m (u'' + r a_g) of its ten DOFs of 1e5 kg and the roof's
    absolute acceleration as [[derived]] columns on acc_abs_ terms."""
    text = (ROOT / "models" / "scenes" / "shear_frame_el_centro.toml").read_text()
    record = ROOT / "models" / "scenes" / "data" / "el_centro_1940_ns.csv"
    text = text.replace('file = "data/el_centro_1940_ns.csv"', f'file = "{record}"')
    text = text.replace("t_end = 31.16", "t_end = 1.0")
    text = text.replace('quantities = ["displacement", "reaction", "drift"]',
                        'quantities = ["displacement", "absolute_acceleration"]')
    text = text.replace('dofs = ["ul*"]', "")
    dofs = [f"{side}{k}" for k in range(1, 6) for side in ("ul", "ur")]
    shear = ", ".join(f"acc_abs_{d} = -1e5" for d in dofs)
    text += (f'[[derived]]\nname = "base_shear"\nterms = {{ {shear} }}\n'
             '[[derived]]\nname = "roof_abs"\nterms = { acc_abs_ul5 = 0.5, acc_abs_ur5 = 0.5 }\n')
    path = tmp_path / "shaken.toml"
    path.write_text(text)
    return path, dofs


def test_derived_columns_on_absolute_accelerations(cli, tmp_path):
    path, dofs = shaken_frame(tmp_path)
    out = tmp_path / "shaken.csv"
    subprocess.run([str(cli), "run", str(path), "--out", str(out)], check=True,
                   capture_output=True)
    with open(out) as f:
        header = f.readline().strip().split(",")
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    col = {name: table[:, i] for i, name in enumerate(header)}
    r = condyn.run(str(path))
    assert r.derived_names == ["base_shear", "roof_abs"]
    for j, name in enumerate(r.derived_names):
        np.testing.assert_array_equal(r.derived[:, j], col[name])  # the same doubles
    # From the result's own a_abs (u'' + r a_g(t)): roundoff of a sum of ten products,
    # 11 eps of the sum of their magnitudes at the row.
    terms = -1e5 * r.a_abs[:, [r.dof(d) for d in dofs]]
    assert np.abs(terms).max() > 1e5  # the record shakes the frame: not a comparison of zeros
    bound = 11 * EPS * np.abs(terms).sum(axis=1)
    assert (np.abs(r.derived[:, 0] - terms.sum(axis=1)) <= bound).all()
    # A sweep keeps the column's peak, and a check bounds it.
    columns = result_columns(r)
    np.testing.assert_array_equal(columns["roof_abs"], r.derived[:, 1])
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    record = scene["ground_motion"]["acceleration"]["file"]  # a worker gets the files' bytes
    with open(record, "rb") as f:
        row = run_one(scene, {record: f.read()}, ["base_shear"])
    assert row["status"] == "ok", row["message"]
    k = int(np.argmax(np.abs(r.derived[:, 0])))
    assert row["peaks"]["base_shear"] == (abs(r.derived[k, 0]), r.t[k])
    scene["check"] = [{"quantity": "roof_abs", "max_abs": 0.01}]  # the roof moves by m/s²
    result = condyn.check(scene)
    assert not result["passed"]
    assert result["checks"][0]["text"].startswith("max |roof_abs| = ")


def test_an_absolute_acceleration_term_needs_ground_motion():
    scene = frame()
    scene["derived"][0]["terms"] = {"acc_abs_u1": 1.0}
    with pytest.raises(condyn.SceneError) as e:
        condyn.run(scene)
    assert ("derived[1].terms.acc_abs_u1: derived column 'drift1': 'acc_abs_u1' needs "
            "[ground_motion]") in str(e.value)
