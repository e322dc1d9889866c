"""`condyn plot RESULT` on malformed input (issue 42, item 5): exit 2 with the file and the
problem on standard error, never a traceback; and the displacement figure's choice of DOFs and
its layout (item 19). Runs the condyn binary of CONDYN_BINARY (CMake sets it)."""
import os
import subprocess

import h5py
import matplotlib.pyplot as plt
import numpy as np
import pytest

import figure_style
import plot_result
import result_file
from layout import problems

plot_result.pyplot()  # the figure functions' shared style, which main imports after reading input
CONDYN = os.environ.get("CONDYN_BINARY", "build/condyn")
T = np.linspace(0.0, 1.0, 5)


def plot(*args, cwd):
    return subprocess.run([CONDYN, "plot", *args, "--format", "png"], cwd=cwd,
                          capture_output=True, text=True, timeout=120)


def h5(path, **datasets):
    """An HDF5 file laid out like condyn's (t, displacement, dof_names, ...), as given."""
    with h5py.File(path, "w") as f:
        for name, value in datasets.items():
            f[name] = value


def good_h5(path):
    h5(path, t=T, displacement=np.c_[np.sin(T), T], dof_names=np.array([b"a", b"b"]))


CSV_CASES = [
    ("latin1.csv", b"t,caf\xe9\n0,1\n", "latin1.csv:1: not UTF-8 text (byte 0xe9)"),
    ("binary.csv", bytes(range(256)) * 4, "binary.csv:1: binary data (a NUL byte)"),
    ("empty.csv", b"", "empty.csv: empty file"),
    ("header.csv", b"t,a\n", "header.csv: no rows"),
    ("ragged.csv", b"t,a\n0,1\n1,2,3\n", "ragged.csv:3: 3 cells for the header's 2 columns"),
    ("word.csv", b"t,a\n0,1\n1,x\n", "word.csv:3: 'x' is not a number"),
    ("nan.csv", b"t,a\n0,1\n1,nan\n", "nan.csv:3: column a: 'nan' is not a finite number"),
    ("inf.csv", b"t,a\n0,-inf\n", "inf.csv:2: column a: '-inf' is not a finite number"),
    ("back.csv", b"t,a\n0,1\n1,2\n0.5,3\n", "back.csv:4: t = 0.5 after t = 1"),
    ("twice.csv", b"t,a,a\n0,1,2\n", "twice.csv:1: column 'a' named twice"),
    ("other.csv", b"x,a\n0,1\n", "other.csv: not a condyn result (its first column is not t)"),
]

H5_CASES = [
    ("names3.h5", dict(t=T, displacement=np.zeros((5, 2)), dof_names=np.array([b"a", b"b",
                                                                              b"c"])),
     "names3.h5: dataset displacement is 5 x 2, expected 5 x 3"),
    ("times3.h5", dict(t=T[:3], displacement=np.zeros((5, 2)), dof_names=np.array([b"a", b"b"])),
     "times3.h5: dataset displacement is 5 x 2, expected 3 x 2"),
    ("no_t.h5", dict(displacement=np.zeros((5, 2))), "no_t.h5: not a condyn result (no dataset t)"),
    ("no_names.h5", dict(t=T, displacement=np.zeros((5, 2))),
     "no_names.h5: not a condyn result (no dataset dof_names)"),
    ("text_t.h5", dict(t=np.array([b"0", b"1"])), "text_t.h5: dataset t holds |S1, not numbers"),
    ("nan_u.h5", dict(t=T, displacement=np.full((5, 1), np.nan), dof_names=np.array([b"a"])),
     "nan_u.h5: dataset displacement holds values that are not finite numbers"),
    ("numbers_as_names.h5", dict(t=T, displacement=np.zeros((5, 1)), dof_names=np.array([1.0])),
     "numbers_as_names.h5: dataset dof_names is not a list of names"),
    ("drift3.h5", dict(t=T, drift=np.zeros((5, 3))),
     "drift3.h5: dataset drift is 5 x 3, expected 5 x 2"),
]


@pytest.mark.parametrize("name, content, expected", CSV_CASES)
def test_malformed_csv_exit_2_naming_file_and_problem(tmp_path, name, content, expected):
    (tmp_path / name).write_bytes(content)
    r = plot(name, cwd=tmp_path)
    assert (r.returncode, "Traceback" in r.stderr) == (2, False), r.stderr
    assert expected in r.stderr
    assert not list(tmp_path.glob("*.png"))


@pytest.mark.parametrize("name, datasets, expected", H5_CASES)
def test_malformed_hdf5_exit_2_naming_file_and_problem(tmp_path, name, datasets, expected):
    h5(tmp_path / name, **datasets)
    r = plot(name, cwd=tmp_path)
    assert (r.returncode, "Traceback" in r.stderr) == (2, False), r.stderr
    assert expected in r.stderr


def test_truncated_or_foreign_hdf5_exit_2(tmp_path):
    good_h5(tmp_path / "whole.h5")
    data = (tmp_path / "whole.h5").read_bytes()
    for cut in (len(data) // 2, 600, 8):
        (tmp_path / "cut.h5").write_bytes(data[:cut])
        r = plot("cut.h5", cwd=tmp_path)
        assert (r.returncode, "Traceback" in r.stderr) == (2, False), (cut, r.stderr)
        assert "cut.h5: " in r.stderr
    with h5py.File(tmp_path / "group.h5", "w") as f:
        f.create_group("t")
    r = plot("group.h5", cwd=tmp_path)
    assert r.returncode == 2 and "group.h5: t is a group, not a dataset" in r.stderr


def test_names_as_fixed_length_bytes_or_variable_length_strings(tmp_path):
    good_h5(tmp_path / "bytes.h5")
    with h5py.File(tmp_path / "text.h5", "w") as f:
        f["t"], f["displacement"] = T, np.c_[np.sin(T), T]
        f.create_dataset("dof_names", data=["a", "b"], dtype=h5py.string_dtype("utf-8"))
    for name in ("bytes.h5", "text.h5"):
        r = plot(name, "--dofs", "b", cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        assert (tmp_path / (name[:-3] + "_displacement.png")).stat().st_size > 5000


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads files without read permission")
def test_unreadable_file_exit_2(tmp_path):
    (tmp_path / "r.csv").write_text("t,a\n0,1\n")
    (tmp_path / "r.csv").chmod(0)
    r = plot("r.csv", cwd=tmp_path)
    assert r.returncode == 2 and "r.csv: Permission denied" in r.stderr


def run_lines(dofs):
    """A result's columns: each DOF name with its curve."""
    columns = {"t": np.linspace(0.0, 10.0, 501)}
    columns.update({name: f(columns["t"]) for name, f in dofs.items()})
    return columns


def test_default_dofs_distinct_and_moving(capsys):
    # a frame's floors: the top two within 10 % of each other, a support at roundoff
    columns = run_lines({"u1": lambda t: 0.3 * np.sin(t), "u2": lambda t: 0.6 * np.sin(t),
                         "u3": lambda t: 0.95 * np.sin(t), "u4": lambda t: np.sin(t),
                         "s": lambda t: 1e-20 * np.sin(t), "r": lambda t: 0.5 * np.cos(3 * t)})
    dofs = [d for d in columns if d != "t"]
    chosen, how, notes = plot_result.chosen_dofs(np, columns, dofs, [], "r.csv")
    assert chosen == ["u4", "u2", "r", "u1"]  # u3 runs within 25 % of u4: drawn over it
    assert "u3 (near u4)" in notes[0]
    assert "s stay at 0 but for roundoff" in notes[1]
    assert how == "4 of 6 DOFs: largest distinct peaks"
    # a glob leaves the support out, an exact name draws it
    chosen, _, notes = plot_result.chosen_dofs(np, columns, dofs, ["*"], "r.csv")
    assert "s" not in chosen and "s stay at 0" in notes[0]
    assert plot_result.chosen_dofs(np, columns, dofs, ["s"], "r.csv")[0] == ["s"]


@pytest.mark.parametrize("relative", [False, True])
def test_displacement_figure_inside_its_column_width(relative):
    figure_style.paper_style(plt)
    columns = run_lines({f"floor_{k}_left_column": (lambda k: lambda t: k * np.sin(t))(k)
                         for k in range(1, 5)})
    fig = plot_result.draw_displacement(plt, columns["t"], columns, list(columns)[1:],
                                        "4 of 4 DOFs", "a_result_file_with_a_long_name",
                                        relative)
    assert fig.get_figwidth() == pytest.approx(figure_style.COLUMN_WIDTH)
    assert problems(fig) == []
    assert fig.axes[0].get_ylabel() == "displacement [m in SI]"  # was "(model units)"
    heading = fig._suptitle.get_text().replace("\n", " ")
    assert ("relative to the ground" if relative else "relative to any ground motion") in heading
    plt.close(fig)


def test_drift_and_energy_figures_inside_their_column_width():
    figure_style.paper_style(plt)
    t = np.linspace(0.0, 10.0, 501)
    columns = {"t": t, "drift_position": 1e-9 * t ** 2, "drift_velocity": 1e-7 * t,
               "energy_kinetic": np.sin(t) ** 2, "energy_potential": -np.sin(t) ** 2,
               "energy_dissipated": 0 * t, "work_loads": 0 * t, "work_constraints": 0 * t,
               "energy": 1e-6 * t, "energy_error": 1e-6 * t}
    drift, _ = plot_result.draw_drift(plt, np, t, columns, "pendulum_run")
    energy = plot_result.draw_energy(plt, t, columns, result_file.energy_columns(columns),
                                     "pendulum_run")
    for fig in (drift, energy):
        assert fig.get_figwidth() == pytest.approx(figure_style.COLUMN_WIDTH)
        assert problems(fig) == []
        plt.close(fig)


def test_derived_columns_told_from_dofs_and_drawn_by_default(tmp_path):
    # A CSV with reactions names its DOFs through them: the other unprefixed columns are
    # [[derived]] columns (docs/plots.md), drawn one panel each; an HDF5 file names them.
    t = np.linspace(0.0, 1.0, 11)
    rows = np.c_[t, np.sin(t), 2 * np.sin(t), -np.sin(t), -2 * np.sin(t), np.sin(t), 1e5 * t]
    header = "t,u1,u2,reaction_u1,reaction_u2,drift2,base_shear"
    np.savetxt(tmp_path / "r.csv", rows, delimiter=",", header=header, comments="")
    columns, dofs, _, others = result_file.read_csv(np, tmp_path / "r.csv")
    assert dofs == ["u1", "u2"] and others == ["drift2", "base_shear"]
    r = plot("r.csv", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "r_columns.png").stat().st_size > 5000
    # --columns draws any column, and one named leaves the displacement figure.
    np.savetxt(tmp_path / "u.csv", rows[:, :3], delimiter=",", header="t,u1,u2", comments="")
    _, chosen, _, _, _, drawn = plot_result.read_result(np, str(tmp_path / "u.csv"), "", "u2")
    assert drawn == ["u2"] and chosen == ["u1"]
    r = plot("u.csv", "--columns", "nothing*", cwd=tmp_path)
    assert r.returncode == 2
    assert "--columns: 'nothing*' matches no column of u.csv (columns: u1, u2)" in r.stderr
    h5(tmp_path / "d.h5", t=t, displacement=np.c_[np.sin(t)], dof_names=np.array([b"u1"]),
       derived=np.c_[np.cos(t), t], derived_names=np.array([b"drift1", b"base_shear"]))
    columns, dofs, _, derived = result_file.read_h5(np, str(tmp_path / "d.h5"))
    assert dofs == ["u1"] and derived == ["drift1", "base_shear"]
    np.testing.assert_array_equal(columns["base_shear"], t)


def test_columns_figure_inside_its_column_width():
    figure_style.paper_style(plt)
    columns = run_lines({"drift_ratio_of_the_second_storey": lambda t: 4e-3 * np.sin(t),
                         "base_shear": lambda t: 2.3e5 * np.sin(t),
                         "storey_shear2": lambda t: 1.9e5 * np.cos(t)})
    fig = plot_result.draw_columns(plt, columns["t"], columns, list(columns)[1:],
                                   "a_result_file_with_a_long_name")
    assert fig.get_figwidth() == pytest.approx(figure_style.COLUMN_WIDTH)
    assert problems(fig) == []
    assert [ax.get_title(loc="left") for ax in fig.axes] == list(columns)[1:]
    plt.close(fig)
