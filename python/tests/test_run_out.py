"""condyn.run(scene, out=FILE) writes FILE through the command's own writers (src/output/): the
file `condyn run SCENE --out FILE` writes, CSV byte for byte and HDF5 dataset by dataset bit for
bit (the command streams its rows into an extendible, chunked file, Python writes the whole result
at once: the layouts differ, never the numbers); a failed run's rows in the same partial file; the
same names refused, with the command's message naming the path, before any work."""

import os
import subprocess

import numpy as np
import pytest

import condyn
from conftest import QUICKSTART, ROOT

SCENES = ROOT / "models" / "scenes"
CASES = [
    QUICKSTART,                                   # a truss with constraints
    SCENES / "two_storey_frame.toml",             # [[derived]] columns
    SCENES / "multibody" / "slider_crank.toml",   # a mechanism's own columns and energy
    SCENES / "pendulum.toml",                     # multipliers, energy, a nonlinear model
]
# The quickstart truss failing after its third output row: its step budget (as `--max-steps 20`)
# ends the run at t = 0.0024, its output rows every 0.001.
BUDGET = {"[solve]\n": "[solve]\nmax_steps = 20\n", "output_step = 0.5": "output_step = 0.001"}


def hdf5_content(path):
    """{name: (dtype, shape, bytes)} of every dataset (strings decoded) and the root attributes:
    what two files must share to hold the same result, bit for bit."""
    h5py = pytest.importorskip("h5py")
    with h5py.File(path, "r") as f:
        sets = {}
        for name, d in f.items():
            data = d.asstr()[()] if d.dtype.kind == "O" else d[()]
            sets[name] = (list(data) if d.dtype.kind == "O" else
                          (data.dtype.str, data.shape, data.tobytes()))
        return sets, dict(f.attrs)


def run_cli(cli, *args):
    return subprocess.run([str(cli), "run", *map(str, args)], capture_output=True, text=True)


@pytest.mark.parametrize("scene", CASES, ids=lambda p: p.stem)
def test_an_hdf5_out_holds_what_condyn_run_writes(cli, tmp_path, scene):
    result = condyn.run(scene, out=tmp_path / "py.h5")
    assert run_cli(cli, scene, "--out", tmp_path / "cli.h5").returncode == 0
    py, ran = hdf5_content(tmp_path / "py.h5"), hdf5_content(tmp_path / "cli.h5")
    assert py[1] == ran[1]  # the attributes: scheme, rtol, atol (and constraints)
    assert sorted(py[0]) == sorted(ran[0])
    for name in ran[0]:
        assert py[0][name] == ran[0][name], name
    # The Result returned is the run written.
    assert py[0]["t"][2] == np.asarray(result.t).tobytes()
    assert sorted(os.listdir(tmp_path)) == ["cli.h5", "py.h5"]  # no temporary file left


@pytest.mark.parametrize("scene", CASES, ids=lambda p: p.stem)
def test_a_csv_out_is_the_file_condyn_run_writes(cli, tmp_path, scene):
    condyn.run(scene, out=tmp_path / "py.csv")
    assert run_cli(cli, scene, "--out", tmp_path / "cli.csv").returncode == 0
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


def test_a_dict_scene_and_a_bytes_name_write_the_same_file(cli, tmp_path, quickstart_dict):
    condyn.run(quickstart_dict, out=os.fsencode(tmp_path / "dict.csv"))
    assert run_cli(cli, QUICKSTART, "--out", tmp_path / "cli.csv").returncode == 0
    assert (tmp_path / "dict.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


def test_standard_output_gets_the_csv_as_from_the_command(cli, capfd):
    condyn.run(QUICKSTART, out="-")
    written = capfd.readouterr().out
    ran = run_cli(cli, QUICKSTART, "--out", "-")
    assert ran.returncode == 0 and written == ran.stdout and written.startswith("t,")


def test_a_failed_run_keeps_its_rows_in_the_partial_file_as_the_command(cli, tmp_path):
    scene = tmp_path / "budget.toml"
    text = QUICKSTART.read_text()
    for old, new in BUDGET.items():
        text = text.replace(old, new)
    scene.write_text(text)
    for name in ("py.h5", "cli.h5"):  # the file named keeps what it had
        (tmp_path / name).write_bytes(b"earlier")
    with pytest.raises(condyn.IntegrationError) as e:
        condyn.run(scene, out=tmp_path / "py.h5")
    ran = run_cli(cli, scene, "--out", tmp_path / "cli.h5")
    assert ran.returncode == 1
    # The message says where the rows went, in the command's words.
    partial = str(tmp_path / "py.partial.h5")
    assert str(e.value).endswith(f"partial result: the 3 output rows up to t = 0.002 are in "
                                 f"{partial} (the run did not reach t_end; {tmp_path / 'py.h5'} "
                                 "was not written)")
    assert str(e.value).split("integration failed: ")[1] == \
        ran.stderr.split("integration failed: ")[1].strip().replace("cli.", "py.")
    assert (tmp_path / "py.h5").read_bytes() == b"earlier"
    assert (tmp_path / "cli.h5").read_bytes() == b"earlier"
    assert len(e.value.result.t) == 3  # rows before the failure, all of them in the file
    assert hdf5_content(partial) == hdf5_content(tmp_path / "cli.partial.h5")
    # A run that finishes then replaces the file and removes the stale partial file.
    condyn.run(QUICKSTART, out=tmp_path / "py.h5")
    assert not os.path.exists(partial)
    assert hdf5_content(tmp_path / "py.h5")[0]["t"][1] == (5,)  # t_end 2 every 0.5 s


def test_a_failed_run_to_standard_output_asks_for_out_in_python_words(cli, tmp_path, capfd):
    # A stream gets complete results only; the message names the argument Python takes, where
    # the command's names its option.
    scene = tmp_path / "budget.toml"
    text = QUICKSTART.read_text()
    for old, new in BUDGET.items():
        text = text.replace(old, new)
    scene.write_text(text)
    with pytest.raises(condyn.IntegrationError) as e:
        condyn.run(scene, out="-")
    assert str(e.value).endswith("gets complete results only; give out=FILE to keep them)")
    ran = run_cli(cli, scene, "--out", "-")
    assert ran.returncode == 1
    assert "gets complete results only; give --out FILE to keep them)" in ran.stderr
    assert capfd.readouterr().out == ""  # nothing of the failed run on standard output


def test_a_scene_the_builder_refuses_leaves_no_file(tmp_path, quickstart_dict):
    # The output is checked first (its temporary file created), the model built after: the
    # builder's refusal (a third constraint incompatible with `base`) removes the temporary file.
    quickstart_dict["constraint"].append({"name": "c3", "terms": {"u1": 1.0}, "value": 1.0})
    with pytest.raises(condyn.SceneError, match="linearly dependent"):
        condyn.run(quickstart_dict, out=tmp_path / "r.csv")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("name, why", [
    ("r.txt", "the extension .txt names no format condyn writes: out writes CSV (.csv, or a name "
              "without an extension) or HDF5 (.h5, .hdf5, .hdf)"),
    ("r.xml", "the extension .xml asks for a format out does not write: out writes CSV (.csv, "
              "or a name without an extension) or HDF5 (.h5, .hdf5, .hdf)"),
    ("missing/r.h5", "the folder {tmp}/missing does not exist"),
    (".", "is a folder (name a file)"),
    ("folder/", "names a folder (name a file)"),
    ("scene.toml", "is {tmp}/scene.toml, an input of this command: choose another name"),
    ("rest.csv", "is {tmp}/rest.csv, an input of this command: choose another name"),
])
def test_a_name_the_command_refuses_raises_output_error_naming_it(cli, tmp_path, monkeypatch,
                                                                   name, why):
    # A scene that reads a record file, rest.csv: no output may replace it either.
    (tmp_path / "rest.csv").write_text("t,a\n0,0\n10,0\n")
    (tmp_path / "folder").mkdir()
    text = (ROOT / "models" / "scenes" / "two_storey_frame.toml").read_text()
    scene = tmp_path / "scene.toml"
    scene.write_text(text)
    if "rest.csv" in name:
        at = text.index("[output]")
        scene.write_text(text[:at] + '[ground_motion]\ninfluence = { u1 = 1.0, u2 = 1.0 }\n'
                         'acceleration = { type = "table", file = "rest.csv" }\n' + text[at:])
    monkeypatch.chdir(tmp_path)
    path = str(tmp_path / name) if "input" in why else name
    before = sorted(os.listdir(tmp_path))
    with pytest.raises(condyn.OutputError) as e:
        condyn.run(scene, out=path)
    message = f"out {path}: " + why.format(tmp=os.path.realpath(tmp_path))
    assert str(e.value) == message
    assert isinstance(e.value, ValueError)
    ran = run_cli(cli, scene, "--out", path)  # the command's refusal, flag for argument
    assert ran.returncode == 2
    assert ran.stderr == "error: " + message.replace("out ", "--out ", 1).replace(
        ": out writes", ": --out writes").replace("format out does", "format --out does") + "\n"
    assert sorted(os.listdir(tmp_path)) == before  # nothing written, no temporary file


@pytest.mark.parametrize("name", ["", "  ", b"\t"])
def test_a_blank_name_is_refused(name):
    with pytest.raises(condyn.OutputError, match="an empty name: name a file"):
        condyn.run(QUICKSTART, out=name)


def test_a_name_that_is_no_path_raises_type_error():
    with pytest.raises(TypeError):
        condyn.run(QUICKSTART, out=3)


def test_threads_write_their_files_side_by_side(tmp_path):
    # Each run integrates without the GIL and writes with it (HDF5 serves one thread at a time):
    # the files equal those of the same runs one after the other.
    from concurrent.futures import ThreadPoolExecutor
    names = [(scene, tmp_path / f"{scene.stem}.h5") for scene in CASES]
    with ThreadPoolExecutor(len(CASES)) as pool:
        list(pool.map(lambda case: condyn.run(case[0], out=case[1]), names))
    for scene, path in names:
        condyn.run(scene, out=tmp_path / "alone.h5")
        assert hdf5_content(path) == hdf5_content(tmp_path / "alone.h5"), scene.stem
