"""condyn.modes: the natural modes from Python, as `condyn modes` gives them, against the closed
form of a uniform shear building (tests/shear_building.hpp has the derivation); and its refusals."""

import math
import subprocess

import numpy as np
import pytest

import condyn

# The dense eigensolver's roundoff: a few eps of ω²_max = 4 k/m, 64 eps relative to the
# frequencies here (the lowest is 0.17 of the highest).
ROUNDOFF = 64 * np.finfo(float).eps * 36


def building(n, m=2.0, k=50.0, ground=True):
    """n storeys of mass m and storey stiffness k on a fixed ground, as a dict scene."""
    K = np.zeros((n, n))
    for i in range(n):
        K[i, i] = 2 * k if i + 1 < n else k
        if i + 1 < n:
            K[i, i + 1] = K[i + 1, i] = -k
    dofs = [f"u{i + 1}" for i in range(n)]
    scene = {"model": {"type": "matrix", "dofs": dofs, "mass": m * np.eye(n), "stiffness": K},
             "solve": {"t_end": 1.0, "output_step": 0.5}}
    if ground:
        scene["ground_motion"] = {"acceleration": 1.0, "influence": {d: 1.0 for d in dofs}}
    return scene


def closed_form(n, m, k, j):
    return 2 * math.sqrt(k / m) * math.sin((2 * j - 1) * math.pi / (2 * (2 * n + 1)))


def test_modes_of_a_shear_building(tmp_path):
    n, m, k = 5, 2.0, 50.0
    r = condyn.modes(building(n, m, k))
    assert r["available"] == n and r["solver"] == "dense"
    exact = np.array([closed_form(n, m, k, j) for j in range(1, n + 1)])
    assert np.allclose(r["omega"], exact, rtol=ROUNDOFF, atol=0)
    assert np.allclose(r["period"], 2 * np.pi / exact, rtol=ROUNDOFF, atol=0)
    assert np.allclose(r["frequency"], exact / (2 * np.pi), rtol=ROUNDOFF, atol=0)
    # Every mode: the ratios sum to 1, the total is the storeys' mass.
    assert r["mass_ratio_cumulative"][-1] == pytest.approx(1.0, abs=ROUNDOFF)
    assert r["total_mass"] == pytest.approx(n * m, rel=ROUNDOFF)
    # Shapes: n x count over dof_names, mass-normalized.
    phi = r["shapes"]
    assert phi.shape == (n, n) and r["dof_names"] == [f"u{i + 1}" for i in range(n)]
    assert np.allclose(phi.T @ (m * np.eye(n)) @ phi, np.eye(n), atol=ROUNDOFF)
    # Fewer, and no ratios without [ground_motion].
    two = condyn.modes(building(n, m, k, ground=False), count=2)
    assert len(two["omega"]) == 2 and two["mass_ratio"] is None and two["total_mass"] is None


def test_modes_agrees_with_the_cli(cli, tmp_path):
    path = tmp_path / "b.toml"
    path.write_text('[model]\ntype = "matrix"\ndofs = ["a", "b"]\nmass = [[1.0, 0.0], [0.0, 2.0]]\n'
                    'stiffness = [[3.0, -1.0], [-1.0, 1.0]]\n[solve]\nt_end = 1.0\noutput_step = 0.5\n')
    r = condyn.modes(str(path))
    out = subprocess.run([str(cli), "modes", str(path)], capture_output=True, text=True, check=True)
    table = np.loadtxt(out.stdout.splitlines(), delimiter=",", skiprows=1, ndmin=2)
    assert np.array_equal(table[:, 1], r["omega"])  # the same doubles, shortest round trip


def test_modes_shapes_are_the_cli_hdf5_file_s(cli, tmp_path):
    """condyn.modes returns the shapes and names that `condyn modes --out FILE.h5` writes, the
    same doubles, with the same table, solver and total mass."""
    path = tmp_path / "b.toml"
    scene = building(4)
    lines = ['[model]', 'type = "matrix"', 'dofs = ["u1", "u2", "u3", "u4"]',
             f'mass = {scene["model"]["mass"].tolist()}',
             f'stiffness = {scene["model"]["stiffness"].tolist()}',
             '[ground_motion]', 'acceleration = 1.0', 'influence = { "u*" = 1.0 }',
             '[solve]', 't_end = 1.0', 'output_step = 0.5']
    path.write_text("\n".join(lines) + "\n")
    r = condyn.modes(str(path), count=3)
    subprocess.run([str(cli), "modes", str(path), "--count", "3", "--out", str(tmp_path / "m.h5")],
                   capture_output=True, text=True, check=True)
    h5py = pytest.importorskip("h5py")
    with h5py.File(tmp_path / "m.h5", "r") as f:
        assert r["shapes"].shape == (4, 3) and f["shapes"].shape == (4, 3)
        assert np.array_equal(f["shapes"][()], r["shapes"])
        assert list(f["dof_names"].asstr()[()]) == r["dof_names"] == ["u1", "u2", "u3", "u4"]
        for key in ("omega", "frequency", "period", "mass_ratio", "mass_ratio_cumulative"):
            assert np.array_equal(f[key][()], r[key]), key
        assert list(f["mode"][()]) == [1, 2, 3] and f["mode"].dtype.kind == "i"
        assert f.attrs["solver"] == r["solver"] and f.attrs["available"] == r["available"] == 4
        assert f.attrs["total_mass"] == r["total_mass"]


@pytest.mark.parametrize("count, says", [
    (0, "count: must be from 1 to the number of modes of the constrained model, 3"),
    (4, "count: must be from 1"),
    (2.0, "count: expected an integer"),
    (True, "count: expected an integer"),
])
def test_modes_refuses_a_bad_count(count, says):
    with pytest.raises(condyn.SceneError, match=says):
        condyn.modes(building(3), count=count)


def test_modes_refuses_a_model_without_mass():
    scene = building(3, ground=False)  # with it, the builder refuses M r = 0 first
    scene["model"]["mass"] = np.zeros((3, 3))
    with pytest.raises(condyn.SceneError, match="model.mass: the model has no mass"):
        condyn.modes(scene)


def test_influence_as_an_array_or_a_pattern(tmp_path):
    """The influence vector as a numpy array (as load.pattern takes one) or as a pattern over DOF
    names: the same run and the same participating masses as the dict of DOFs, bit for bit."""
    n = 4
    by_name = building(n)
    by_name["ground_motion"]["influence"] = {"u1": 1.0, "u2": 1.0, "u3": 0.5, "u4": 1.0}
    array = building(n)
    array["ground_motion"]["influence"] = np.array([1.0, 1.0, 0.5, 1.0])
    pattern = building(n)
    pattern["ground_motion"]["influence"] = {"u*": 1.0, "u3": 0.5}
    reference, reference_run = condyn.modes(by_name), condyn.run(by_name)
    for scene in (array, pattern):
        r = condyn.modes(scene)
        assert np.array_equal(r["mass_ratio"], reference["mass_ratio"])
        assert r["total_mass"] == reference["total_mass"]
        assert np.array_equal(condyn.run(scene).u, reference_run.u)
    wrong = building(n)
    wrong["ground_motion"]["influence"] = np.ones(3)
    with pytest.raises(condyn.SceneError, match=r"ground_motion.influence: is 3 x 1 but an "
                                                r"influence vector is n x 1 \(n = 4 DOFs\)"):
        condyn.run(wrong)
    nothing = building(n)
    nothing["ground_motion"]["influence"] = {"x*": 1.0}
    with pytest.raises(condyn.SceneError, match=r"ground_motion.influence.x\*: 'x\*' matches no DOF"):
        condyn.modes(nothing)
