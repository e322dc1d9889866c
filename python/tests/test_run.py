"""condyn.run: arrays against the CLI's CSV, dict scenes against file scenes, scipy.sparse and
numpy matrices against lists and Matrix Market files. Runs are deterministic, so equal inputs
must give bit-equal arrays; the CSV holds each double's shortest round-trip form, so it reads back
exactly."""

import math
import os
import subprocess
import tomllib

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

import condyn
from conftest import QUICKSTART, ROOT


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    return header, np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def test_arrays_equal_the_cli_csv(cli, tmp_path):
    out = tmp_path / "q.csv"
    subprocess.run([str(cli), "run", str(QUICKSTART), "--scheme", "ggl", "--out", str(out)],
                   check=True, capture_output=True)
    header, table = read_csv(out)
    r = condyn.run(str(QUICKSTART), scheme="ggl")
    assert r.dof_names == ["u1", "u2", "u3"]
    assert r.constraint_names == ["base", "link"]
    assert r.u.shape == (5, 3) and r.reaction.shape == (5, 3)
    assert r.multiplier.shape == (5, 2) and r.drift.shape == (5, 2)
    col = {name: table[:, i] for i, name in enumerate(header)}
    np.testing.assert_array_equal(r.t, col["t"])
    for j, name in enumerate(r.dof_names):
        np.testing.assert_array_equal(r.u[:, j], col[name])
        np.testing.assert_array_equal(r.reaction[:, j], col["reaction_" + name])
    np.testing.assert_array_equal(r.drift[:, 0], col["drift_position"])
    np.testing.assert_array_equal(r.drift[:, 1], col["drift_velocity"])
    # The link u2 = u3 holds to GGL's tolerance (rtol 1e-8 of a 0.2 m motion).
    assert np.max(np.abs(r.u[:, 1] - r.u[:, 2])) < 1e-8


def test_hdf5_of_the_cli_equals_the_module_and_reads_as_text(cli, tmp_path):
    h5py = pytest.importorskip("h5py")
    out = tmp_path / "q.h5"
    subprocess.run([str(cli), "run", str(QUICKSTART), "--scheme", "ggl", "--out", str(out)],
                   check=True, capture_output=True)
    r = condyn.run(str(QUICKSTART), scheme="ggl")
    with h5py.File(out, "r") as f:
        # Attributes and names are strings, not bytes: a script compares them with 'ggl'.
        assert f.attrs["scheme"] == "ggl"
        # The names as docs/cli.md says to read them: h5py 3 gives a string dataset's entries as
        # bytes whatever its encoding (issue 42 found b'u1'), .asstr() as str.
        assert list(f["dof_names"].asstr()[()]) == r.dof_names
        assert list(f["constraint_names"].asstr()[()]) == r.constraint_names
        np.testing.assert_array_equal(f["t"][...], r.t)
        np.testing.assert_array_equal(f["displacement"][...], r.u)
        np.testing.assert_array_equal(f["reaction"][...], r.reaction)
        np.testing.assert_array_equal(f["drift"][...], r.drift)


def test_every_string_hdf5_writes_is_variable_length_utf8(cli, tmp_path):
    # Datasets and attributes alike, from both writers (the whole result after a run to
    # standard output is written at once; a file is streamed row by row): variable-length UTF-8
    # strings, which h5py reads as str (attributes) or, by .asstr(), str (datasets).
    h5py = pytest.importorskip("h5py")
    scene = tmp_path / "s.toml"
    scene.write_text(QUICKSTART.read_text().replace(
        '["displacement", "reaction", "drift"]', '["displacement", "drift", "energy"]').replace(
        'name = "link"', 'name = "lien_é"'))
    streamed = tmp_path / "streamed.h5"
    subprocess.run([str(cli), "run", str(scene), "--scheme", "ggl", "--out", str(streamed)],
                   check=True, capture_output=True)
    # Into a FIFO the result is written whole once the run ends (src/output/hdf5_output.cpp).
    fifo = tmp_path / "whole.h5"
    os.mkfifo(fifo)
    writer = subprocess.Popen([str(cli), "run", str(scene), "--scheme", "ggl", "--out",
                               str(fifo)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    image = fifo.read_bytes()  # until the writer closes it
    assert writer.wait(timeout=60) == 0, writer.stderr.read()
    writer.stderr.close()
    (tmp_path / "whole_copy.h5").write_bytes(image)
    files = [streamed, tmp_path / "whole_copy.h5"]
    for path in files:
        with h5py.File(path, "r") as f:
            strings = {name: f[name].dtype for name in f if f[name].dtype.kind in "OSU"}
            strings.update({"@" + name: f.attrs.get_id(name).dtype for name in f.attrs
                            if f.attrs.get_id(name).dtype.kind in "OSU"})
            assert set(strings) == {"dof_names", "constraint_names", "energy_columns",
                                    "@scheme", "@constraints"}, path
            for name, dtype in strings.items():
                info = h5py.check_string_dtype(dtype)
                assert info is not None and info.encoding == "utf-8" and info.length is None, \
                    (path, name)
            assert list(f["constraint_names"].asstr()[()]) == ["base", "lien_é"]
            assert isinstance(f.attrs["scheme"], str) and isinstance(f.attrs["constraints"], str)


@pytest.mark.parametrize("scheme, constraints, expected", [
    ("ggl", "mixed", "mixed"), ("ggl", "multipliers", "multipliers"),
    ("index1", None, "multipliers"), ("elimination", None, None),
    ("generalized_alpha", "mixed", "mixed"), ("hht", None, "multipliers")])
def test_the_constraint_treatment_is_recorded(cli, tmp_path, scheme, constraints, expected):
    # The HDF5 root attribute `constraints` and summary["constraints"]: how a multiplier scheme
    # or the Newmark family treated the rows ([solve] constraints); absent (None) for the others.
    h5py = pytest.importorskip("h5py")
    out = tmp_path / "q.h5"
    flags = ["--constraints", constraints] if constraints else []
    subprocess.run([str(cli), "run", str(QUICKSTART), "--scheme", scheme, *flags, "--out",
                    str(out)], check=True, capture_output=True)
    with h5py.File(out, "r") as f:
        assert f.attrs.get("constraints") == expected
    with open(QUICKSTART, "rb") as f:
        scene = tomllib.load(f)
    scene["solve"]["scheme"] = scheme
    if constraints:
        scene["solve"]["constraints"] = constraints
    assert condyn.run(scene).summary["constraints"] == expected


def test_a_scheme_override_sets_the_constraints_key_aside(quickstart_dict):
    # As the command's --scheme: [solve] constraints applies to the multiplier schemes, so an
    # override to another scheme sets it aside and says so in the warnings.
    quickstart_dict["solve"]["scheme"] = "ggl"
    quickstart_dict["solve"]["constraints"] = "mixed"
    r = condyn.run(quickstart_dict, scheme="penalty")
    assert r.summary["constraints"] is None
    assert any(w.startswith('[solve] constraints = "mixed" is set aside') and
               w.endswith("not to penalty") for w in r.summary["warnings"])
    kept = condyn.run(quickstart_dict, scheme="index1")
    assert kept.summary["constraints"] == "mixed"
    assert not any("set aside" in w for w in kept.summary["warnings"])


def test_summary_and_overrides():
    r = condyn.run(QUICKSTART, scheme="index1", rtol=1e-6, atol=1e-9)
    s = r.summary
    assert s["scheme"] == "index1"
    assert s["rtol"] == 1e-6 and s["atol"] == 1e-9
    assert s["steps"] > 10 and s["residual_evals"] >= s["steps"]
    assert s["jacobian_evals"] >= 1 and s["wall_s"] > 0.0
    assert s["termination"] != "not run"
    assert r.a is None  # the scene does not ask for accelerations
    # Every array is read-only (docs/python.md), t and drift included.
    for name in ("t", "u", "v", "reaction", "multiplier", "drift"):
        assert not getattr(r, name).flags.writeable, name


def test_a_loose_rtol_is_warned_of_as_the_cli_warns():
    assert not any("correct digits" in w for w in condyn.run(QUICKSTART).summary["warnings"])
    loose = condyn.run(QUICKSTART, rtol=0.5).summary["warnings"]
    assert "rtol 0.5 asks for fewer than 2 correct digits" in loose


def test_dict_scene_equals_file_scene(quickstart_dict):
    from_file = condyn.run(QUICKSTART, scheme="ggl")
    from_dict = condyn.run(quickstart_dict, scheme="ggl")
    for key in ("t", "u", "v", "reaction", "multiplier", "drift"):
        np.testing.assert_array_equal(getattr(from_dict, key), getattr(from_file, key))
    assert from_dict.summary["steps"] == from_file.summary["steps"]
    # numpy's strings are strings (np.str_ subclasses str): a scheme read from an array of names.
    quickstart_dict["solve"]["scheme"] = np.array(["index1", "ggl"])[1]
    assert condyn.run(quickstart_dict).summary["scheme"] == "ggl"


def test_sparse_and_numpy_matrices_equal_lists(quickstart_dict):
    lists = condyn.run(quickstart_dict, scheme="baumgarte")
    model = quickstart_dict["model"]
    for make in (sp.csr_matrix, sp.coo_matrix, np.array):
        scene = dict(quickstart_dict)
        scene["model"] = dict(model, mass=make(np.array(model["mass"])),
                              stiffness=make(np.array(model["stiffness"])))
        r = condyn.run(scene, scheme="baumgarte")
        np.testing.assert_array_equal(r.u, lists.u)
        np.testing.assert_array_equal(r.reaction, lists.reaction)


def chain(n=6):
    """A chain of n unit masses and springs of 100 N/m, fixed at its left end."""
    k = sp.diags([np.full(n - 1, -100.0), np.full(n, 200.0), np.full(n - 1, -100.0)], [-1, 0, 1],
                 format="lil")
    k[n - 1, n - 1] = 100.0
    a = sp.csr_matrix(([1.0, -1.0, 1.0, 1.0, -2.0], ([0, 0, 1, 1, 1], [1, 4, 0, 2, 3])),
                      shape=(2, n))
    f = np.zeros(n)
    f[-1] = 1.0
    return sp.identity(n, format="csr"), k.tocsr(), a, f


def chain_scene(mass, stiffness, block, pattern):
    return {"model": {"type": "matrix", "mass": mass, "stiffness": stiffness},
            "constraint_block": [{"file": block, "name": "mfc"}],
            "load": [{"pattern": pattern,
                      "value": {"type": "harmonic", "amplitude": 5.0, "omega": 3.0}}],
            "solve": {"t_end": 2.0, "output_step": 0.25, "scheme": "ggl"}}


def test_arrays_equal_matrix_market_files(tmp_path):
    m, k, a, f = chain()
    for name, x in (("M", m), ("K", k), ("A", a), ("f", sp.csr_matrix(f).T)):
        scipy.io.mmwrite(tmp_path / f"{name}.mtx", x, precision=17)
    (tmp_path / "chain.toml").write_text(
        'model = { type = "matrix", mass = { file = "M.mtx" }, stiffness = { file = "K.mtx" } }\n'
        '[[constraint_block]]\nfile = "A.mtx"\nname = "mfc"\n'
        '[[load]]\npattern = { file = "f.mtx" }\n'
        'value = { type = "harmonic", amplitude = 5.0, omega = 3.0 }\n'
        '[solve]\nt_end = 2.0\noutput_step = 0.25\nscheme = "ggl"\n')
    from_files = condyn.run(tmp_path / "chain.toml")
    from_arrays = condyn.run(chain_scene(m, k, a, f))
    assert from_arrays.dof_names == [f"u{i}" for i in range(1, 7)]
    assert from_arrays.constraint_names == ["mfc1", "mfc2"]
    np.testing.assert_array_equal(from_arrays.u, from_files.u)
    np.testing.assert_array_equal(from_arrays.multiplier, from_files.multiplier)
    # The constraints hold: u2 = u5 and u1 + u3 = 2 u4, to GGL's tolerance (rtol 1e-8).
    u = from_arrays.u
    assert np.max(np.abs(u[:, 1] - u[:, 4])) < 1e-9
    assert np.max(np.abs(u[:, 0] + u[:, 2] - 2 * u[:, 3])) < 1e-9
    assert np.max(np.abs(u)) > 1e-3  # and the chain moves
    # File keys take a pathlib.Path (any os.PathLike), as the scene argument does.
    paths = {"model": {"type": "matrix", "mass": {"file": tmp_path / "M.mtx"},
                       "stiffness": {"file": tmp_path / "K.mtx"}},
             "constraint_block": [{"file": tmp_path / "A.mtx", "name": "mfc"}],
             "load": [{"pattern": {"file": tmp_path / "f.mtx"},
                       "value": {"type": "harmonic", "amplitude": 5.0, "omega": 3.0}}],
             "solve": {"t_end": 2.0, "output_step": 0.25, "scheme": "ggl"}}
    np.testing.assert_array_equal(condyn.run(paths).u, from_files.u)


def oscillator_with_table(file, column=None):
    value = {"type": "table", "file": file, "scale": 2.0}
    if column:
        value["column"] = column
    return {"model": {"type": "matrix", "dofs": ["x"], "mass": [[1.0]], "stiffness": [[4.0]]},
            "load": [{"dof": "x", "value": value}],
            "solve": {"t_end": 1.0, "output_step": 0.1, "rtol": 1e-10, "atol": 1e-12}}


def test_recorded_time_function_from_an_array_equals_its_csv_file(tmp_path):
    # A record sampled every 0.05 s (as an accelerogram would be), once as an n x 2 array and
    # once as the CSV file a scene names: the same samples, the same run, bit for bit.
    t = np.arange(0.0, 1.0001, 0.05)
    samples = np.column_stack([t, np.sin(7.0 * t) * np.exp(-t)])
    np.savetxt(tmp_path / "rec.csv", samples, delimiter=",", header="t,ag", comments="",
               fmt="%.17g")
    from_file = condyn.run(oscillator_with_table(str(tmp_path / "rec.csv"), "ag"))
    from_array = condyn.run(oscillator_with_table(samples))
    np.testing.assert_array_equal(from_array.u, from_file.u)
    assert np.max(np.abs(from_array.u)) > 1e-3


def test_a_bad_recorded_array_names_its_key_and_row():
    t = np.array([0.0, 0.1, 0.1, 0.2])
    bad = np.column_stack([t, np.zeros(4)])
    with pytest.raises(condyn.SceneError,
                       match=r"^<dict>: load\[1\]\.value\.file: <array load\[1\]\.value\.file>: "
                             r"row 3: the time 0\.1 is not after"):
        condyn.run(oscillator_with_table(bad))
    with pytest.raises(condyn.SceneError, match=r"must be n x 2 \(time, value\); this one is 4 x 3"):
        condyn.run(oscillator_with_table(np.zeros((4, 3))))


GROUND_SCENE = """
[model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
[[constraint]]
terms = { a = 1.0 }
[ground_motion]
acceleration = { type = "harmonic", omega = 3.0 }
influence = { a = 1.0, b = 1.0 }
[solve]
t_end = 0.3
output_step = 0.1
[output]
quantities = ["QUANTITIES"]
"""


def test_absolute_accelerations_are_their_own_array(cli, tmp_path):
    # Asked for alone, absolute accelerations were returned in `a`, which holds the relative
    # ones: a_abs = a + r a_g(t) is its own array, the CLI's acc_abs_ columns bit for bit.
    scene = tmp_path / "g.toml"
    scene.write_text(GROUND_SCENE.replace('"QUANTITIES"', '"absolute_acceleration"'))
    r = condyn.run(scene)
    np.testing.assert_allclose(r.a_abs, r.a + np.sin(3.0 * r.t)[:, None], rtol=0, atol=1e-15)
    assert r.a[1, 0] == 0.0 and r.a_abs[1, 0] == math.sin(3.0 * r.t[1])  # the support moves
    out = tmp_path / "g.csv"
    subprocess.run([str(cli), "run", str(scene), "--out", str(out)], check=True,
                   capture_output=True)
    col = np.genfromtxt(out, delimiter=",", names=True)
    for j, name in enumerate(r.dof_names):
        np.testing.assert_array_equal(r.a_abs[:, j], col["acc_abs_" + name])
    scene.write_text(GROUND_SCENE.replace('"QUANTITIES"', '"acceleration"'))
    assert condyn.run(scene).a_abs is None


def test_times_are_a_read_only_view():
    r = condyn.run(QUICKSTART)
    assert r.t.base is not None  # the run's own memory
    with pytest.raises(ValueError):
        r.t.flags.writeable = True


def test_singular_passages_and_rows():
    """The parallelogram four-bar under index1 by its own steps (bridge_singular = false): both
    collinear passages (t = 1 and 3) in the summary, the change of branch at t = 3 among the
    warnings, and exactly those two rows marked (docs/schemes.md, "Singular configurations").
    Bridged (the default), no change of branch."""
    path = ROOT / "models" / "scenes" / "parallelogram_four_bar.toml"
    bridged = condyn.run(str(path), scheme="index1")
    assert [p["left_branch"] for p in bridged.summary["singular_passages"]] == [False, False]
    assert "bridged 2 near-singular configurations" in bridged.summary["notes"]
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    scene["solve"]["bridge_singular"] = False
    r = condyn.run(scene, scheme="index1")
    passages = r.summary["singular_passages"]
    assert [round(p["t_closest"]) for p in passages] == [1, 3]
    assert [p["left_branch"] for p in passages] == [False, True]
    assert all(p["closest"] < 0.05 and p["t_leave"] is not None for p in passages)
    assert any("left its branch" in w for w in r.summary["warnings"])
    assert r.near_singular.dtype == bool
    assert list(r.t[r.near_singular]) == [1.0, 3.0]
    # A linear scene: nothing marked, nothing listed.
    q = condyn.run(str(QUICKSTART))
    assert q.summary["singular_passages"] == [] and not q.near_singular.any()
