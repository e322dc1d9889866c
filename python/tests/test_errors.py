"""Every bad input raises condyn.SceneError (a ValueError) with the CLI's message; a failed
integration raises condyn.IntegrationError (a RuntimeError) with the partial result."""

import copy
import decimal
import fractions
import os
import pathlib
import pickle
import re
import subprocess
import sys

import numpy as np
import pytest
import scipy.sparse as sp

import condyn
from conftest import QUICKSTART


def test_scene_error_is_a_value_error():
    assert issubclass(condyn.SceneError, ValueError)
    assert issubclass(condyn.IntegrationError, RuntimeError)
    # Shown where users catch it, not as condyn._condyn.SceneError.
    assert f"{condyn.SceneError.__module__}.{condyn.SceneError.__name__}" == "condyn.SceneError"


def test_overrides_take_what_scene_values_take(quickstart_dict):
    # A 0-d array or a Decimal is a number in a scene; as an override it was refused.
    assert condyn.run(quickstart_dict, rtol=np.array(1e-6)).summary["rtol"] == 1e-6
    assert condyn.run(quickstart_dict, rtol=decimal.Decimal("1e-6")).summary["rtol"] == 1e-6
    with pytest.raises(condyn.SceneError, match=r"^<dict>: rtol: expected a number"):
        condyn.run(quickstart_dict, rtol=np.array([1e-6]))


def test_dict_message_is_the_cli_message(cli, tmp_path, quickstart_dict):
    # The same asymmetric stiffness in a file (through the CLI) and in a dict: the messages differ
    # only in FILE:LINE, which is "<dict>" for a dict.
    text = QUICKSTART.read_text().replace("[0.0, -100.0, 100.0]]", "[0.0, -99.0, 100.0]]")
    (tmp_path / "bad.toml").write_text(text)
    cli_run = subprocess.run([str(cli), "run", str(tmp_path / "bad.toml")], capture_output=True,
                             text=True)
    assert cli_run.returncode == 2
    cli_message = cli_run.stderr.strip().removeprefix("error: ")
    scene = copy.deepcopy(quickstart_dict)
    scene["model"]["stiffness"][2][1] = -99.0
    with pytest.raises(condyn.SceneError) as e:
        condyn.run(scene)
    assert str(e.value).startswith("<dict>: model.stiffness: is not symmetric")
    assert str(e.value).removeprefix("<dict>") == re.sub(r"^[^:]*:\d+", "", cli_message)
    # A file scene through Python: exactly the CLI's message.
    with pytest.raises(condyn.SceneError) as e:
        condyn.run(tmp_path / "bad.toml")
    assert str(e.value) == cli_message


@pytest.mark.parametrize("edit, message", [
    (lambda s: s.pop("solve"), "<dict>: solve: missing required key"),
    (lambda s: s["solve"].update(t_end=-1.0), "<dict>: solve.t_end: "),
    (lambda s: s["solve"].update(rtol="tight"), "<dict>: solve.rtol: "),
    (lambda s: s.update(extra=1), "<dict>: extra: "),
    (lambda s: s["model"].update(mass=np.diag([2.0, 1.0])),
     "<dict>: model.mass: the array is 2 x 2 for 3 DOFs"),
    (lambda s: s["model"].update(stiffness=sp.csr_matrix(np.triu(np.ones((3, 3))))),
     "<dict>: model.stiffness: the array is not symmetric: entry (1,2)"),
    (lambda s: s["model"].update(mass=np.diag([1.0, np.nan, 1.0])),
     "<dict>: model.mass: entry (2,2) is nan: entries must be finite"),
    (lambda s: s.update(constraint_block=[{"file": sp.coo_matrix(
        ([1.0], ([0], [0])), shape=(2000000, 3))}]),
     "<dict>: constraint_block[1]: has 2000000 rows but 1 stored entries, so some row has none"),
    # A block given transposed: its size is the problem named, as a file's size line is.
    (lambda s: s.update(constraint_block=[{"file": np.ones((3, 2))}]),
     "<dict>: constraint_block[1]: is 3 x 2 but a constraint block needs one column per DOF (3)"),
    (lambda s: s["model"].update(mass=np.eye(3, dtype=complex)),
     "<dict>: model.mass: entries must be real numbers"),
    # A boolean array (a mask by mistake) is no matrix of ones, dense or sparse.
    (lambda s: s["model"].update(mass=np.eye(3, dtype=bool)),
     "<dict>: model.mass: entries must be real numbers (the array's dtype is bool)"),
    (lambda s: s["model"].update(stiffness=sp.csr_matrix(np.eye(3, dtype=bool))),
     "<dict>: model.stiffness: entries must be real numbers (the array's dtype is bool)"),
    (lambda s: s["model"].update(dofs={"u1"}), "<dict>: model.dofs: a set is not a scene value"),
    (lambda s: s["solve"].update(t_end=None), "<dict>: solve.t_end: a NoneType is not"),
    (lambda s: s["solve"].update({1: 2}), "<dict>: solve: keys must be strings"),
    (lambda s: s["initial"].update(velocity=sp.eye(3)),
     "<dict>: initial.velocity: a scipy.sparse matrix is taken only by"),
    # numpy's bool is a bool, not the coefficient 1.0 its __float__ gives.
    (lambda s: s["constraint"][0]["terms"].update(u1=np.bool_(True)),
     "<dict>: constraint[1].terms.u1: expected a number"),
    (lambda s: s["solve"].update(t_end=np.bool_(False)), "<dict>: solve.t_end: "),
    # numpy's complex scalar is no load of its real part (its __float__ dropped the imaginary
    # one with a warning only), nor a duration or a date a number.
    (lambda s: s["load"][0].update(value=np.complex128(1 + 5j)),
     "<dict>: load[1].value: a numpy complex128 is not a scene value"),
    (lambda s: s["load"][0].update(value=1 + 5j),
     "<dict>: load[1].value: a complex number is not a scene value"),
    (lambda s: s["solve"].update(t_end=np.timedelta64(1, "s")),
     "<dict>: solve.t_end: a numpy timedelta64[s] is not a scene value"),
    # A Decimal or Fraction below the double range is no 0, as 1e-400 in a TOML file is none.
    (lambda s: s["solve"].update(t_end=decimal.Decimal("1e-400")),
     "<dict>: solve.t_end: 1E-400 is nonzero but below the smallest double"),
    (lambda s: s["load"][0].update(value=fractions.Fraction(1, 10**400)),
     "<dict>: load[1].value: 1/1" + "0" * 400 + " is nonzero but below the smallest double"),
    # A masked entry has no value: named as such, not as the None tolist() gives for it.
    # A matrix's masked entry was read as the data stored under the mask.
    (lambda s: s["model"].update(mass=np.ma.masked_array(np.eye(3), mask=np.eye(3) > 0.5)),
     "<dict>: model.mass: a masked numpy value is not a scene value"),
    (lambda s: s["load"][0].update(value=np.ma.masked_array([1.0, 2.0], mask=[0, 1])),
     "<dict>: load[1].value: a masked numpy value is not a scene value"),
    (lambda s: s["solve"].update(t_end=np.ma.masked),
     "<dict>: solve.t_end: a masked numpy value is not a scene value"),
    (lambda s: s["solve"].update(t_end=np.datetime64("2020-01-01")),
     "<dict>: solve.t_end: a numpy datetime64[D] is not a scene value"),
    (lambda s: s["model"].update(mass={"file": pathlib.PurePosixPath("no/such.mtx")}),
     "<dict>: model.mass.file: no/such.mtx: cannot open the file"),
    # A lone surrogate has no UTF-8 form: refused by key, never pybind11's cast RuntimeError.
    (lambda s: s.update(name="a\udcffb"), "<dict>: name: is not valid text: it holds a lone"),
    (lambda s: s["solve"].update({"rt\ud800ol": 1e-6}), "<dict>: solve: a key is not valid text"),
    (lambda s: s["model"].update(mass={"file": "m\ud800.mtx"}),
     "<dict>: model.mass.file: is not a file name this system can encode"),
    # A file name with a byte that is not UTF-8 (surrogateescape) is the system's name, and the
    # message gives it back as the same str.
    (lambda s: s["model"].update(mass={"file": "m\udcff.mtx"}),
     "<dict>: model.mass.file: m\udcff.mtx: cannot open the file"),
])
def test_bad_dicts(quickstart_dict, edit, message):
    edit(quickstart_dict)
    with pytest.raises(condyn.SceneError) as e:
        condyn.run(quickstart_dict)
    assert str(e.value).startswith(message), str(e.value)


def test_bad_arguments(quickstart_dict):
    with pytest.raises(condyn.SceneError, match=r"^<dict>: scheme: unknown scheme 'fast'"):
        condyn.run(quickstart_dict, scheme="fast")
    with pytest.raises(condyn.SceneError, match=r"^<dict>: rtol: must lie in \[1e-15, 1\)"):
        condyn.run(quickstart_dict, rtol=2.0)
    with pytest.raises(condyn.SceneError, match=r"^<dict>: atol: must be a finite number"):
        condyn.run(quickstart_dict, atol=float("nan"))
    # Out of range values are printed as numbers, the tiny ones too.
    with pytest.raises(condyn.SceneError, match=r"^<dict>: rtol: .*\(got 1e-20\)$"):
        condyn.run(quickstart_dict, rtol=1e-20)
    # Wrong types are bad input too, named like the others (not pybind11's TypeError).
    with pytest.raises(condyn.SceneError, match=r"^<dict>: rtol: expected a number \(got str"):
        condyn.run(quickstart_dict, rtol="1e-6")
    with pytest.raises(condyn.SceneError, match=r"^<dict>: atol: expected a number \(got bool"):
        condyn.run(quickstart_dict, atol=True)
    with pytest.raises(condyn.SceneError, match=r"^<dict>: rtol: an integer of 2001 bits is out"):
        condyn.run(quickstart_dict, rtol=2**2000)
    with pytest.raises(condyn.SceneError, match=r"^<dict>: scheme: expected a string \(got int"):
        condyn.run(quickstart_dict, scheme=3)
    with pytest.raises(condyn.SceneError, match=r"no_such\.toml: cannot open the scene file"):
        condyn.run("no_such.toml")
    with pytest.raises(TypeError, match="a scene is a path"):
        condyn.run(42)


def test_scheme_that_cannot_treat_the_scene():
    # Elimination cannot treat a nonholonomic row (the CLI answers exit 2: bad input).
    with pytest.raises(condyn.SceneError,
                       match="chaplygin_sleigh.toml: .*elimination cannot treat a nonholonomic"):
        condyn.run(QUICKSTART.parent / "chaplygin_sleigh.toml", scheme="elimination")


def test_integration_error_carries_the_partial_result(quickstart_dict):
    # A budget the run exhausts: 250 steps reach t = 0.81 of 2 s (output every 0.5 s).
    quickstart_dict["solve"]["max_steps"] = 250
    with pytest.raises(condyn.IntegrationError) as e:
        condyn.run(quickstart_dict, scheme="ggl")
    assert str(e.value).startswith("<dict>: integration failed: under ggl")
    partial = e.value.result
    np.testing.assert_array_equal(partial.t, [0.0, 0.5])
    assert partial.u.shape == (len(partial.t), 3)
    # The summary describes the run that stopped: where, its system, its drift (at least the
    # rows' own).
    s = partial.summary
    assert s["termination"].startswith("stopped at t = 0.8") and s["steps"] == 251
    assert s["unknowns"] > 0 and s["jacobian_nonzeros"] > 0
    assert s["max_drift_position"] >= partial.drift[:, 0].max()
    assert s["max_drift_velocity"] >= partial.drift[:, 1].max()
    # Its kind, as an identifier (a sweep's status column, docs/sweep.md).
    assert e.value.kind == "step_budget"
    # It pickles (a failed run in a process pool): message, kind and partial result survive.
    back = pickle.loads(pickle.dumps(e.value))
    assert str(back) == str(e.value) and back.kind == "step_budget"
    np.testing.assert_array_equal(back.result.u, partial.u)


def test_scene_paths_are_the_systems_bytes(tmp_path, quickstart_dict):
    # A scene file whose name holds the byte 0xff (not UTF-8): Python names it with
    # surrogateescape, and condyn opens that file.
    name = os.fsdecode(b"q\xff.toml")
    (tmp_path / name).write_bytes(QUICKSTART.read_bytes())
    assert condyn.run(tmp_path / name).t[-1] == quickstart_dict["solve"]["t_end"]
    # The same file named by its bytes, as open() takes it.
    assert condyn.run(os.fsencode(tmp_path) + b"/q\xff.toml").t[-1] == \
        quickstart_dict["solve"]["t_end"]
    with pytest.raises(condyn.SceneError, match="cannot open the scene file"):
        condyn.run(tmp_path / os.fsdecode(b"missing\xff.toml"))
    with pytest.raises(condyn.SceneError, match="the scene path is not a file name"):
        condyn.run("q\ud800.toml")
    # Messages name a path given as bytes by its text, as the CLI would (not b'...').
    (tmp_path / "q.toml").write_bytes(QUICKSTART.read_bytes())
    with pytest.raises(condyn.SceneError) as e:
        condyn.run(os.fsencode(tmp_path / "q.toml"), rtol="x")
    assert str(e.value).startswith(f"{tmp_path / 'q.toml'}: rtol: expected a number")


@pytest.mark.parametrize("call", [condyn.run, condyn.check, condyn.compare])
def test_scene_text_instead_of_a_path(call):
    # The TOML text itself, where a path belongs: the message said 'cannot open the scene file
    # (File name too long)' after the whole text. It now says what to pass, and stays short.
    text = QUICKSTART.read_text()
    with pytest.raises(condyn.SceneError, match=r"^the scene given is text \(\d+ lines\), not a "
                                                r"path: .*tomllib\.loads\(text\)") as caught:
        call(text)
    assert len(str(caught.value)) < 200
    with pytest.raises(condyn.SceneError, match="not a path"):
        call(text.encode())


def test_an_all_zero_pattern_is_warned_about_by_its_key():
    scene = {"model": {"type": "matrix", "dofs": ["a", "b"], "mass": np.eye(2),
                       "stiffness": np.eye(2)},
             "load": [{"pattern": np.zeros((2, 1)), "value": 1.0}],
             "solve": {"t_end": 1.0, "output_step": 0.5}}
    result = condyn.run(scene)
    assert result.summary["warnings"] == [
        "load[1].pattern: the array has no nonzero entry: this load applies no force"]


def test_a_dict_scenes_inconsistent_start_is_blamed_on_initial():
    # Dict nodes have no line: the error went to model.members[1] instead of initial.
    scene = {"model": {"type": "truss2d", "nodes": [[0.0, 0.0], [1.0, 0.0]],
                       "masses": [0.0, 1.0], "supports": [1],
                       "members": [{"nodes": [1, 2], "rigid": True}], "gravity": [0.0, -9.81]},
             "initial": {"velocity": {"ux2": 0.3, "uy2": -1.0}},
             "solve": {"t_end": 1.0, "output_step": 0.1}}
    with pytest.raises(condyn.SceneError,
                       match=r"^<dict>: initial: initial velocities violate constraint 'rigid_1_2'"):
        condyn.run(scene)


# A model of this many DOFs cannot be integrated in 24 GB or any machine's memory near it: IDA's
# vectors alone are 30 of 2n doubles, 48 GB (models/core/memory_estimate.hpp's lower bound).
HUGE = 10**8

# Each call runs in a child limited to 4 GB of address space: were the check lost, the model's
# 10⁸ DOFs (gigabytes before this check) would fail there, not take the machine's memory.
SIZED_CALL = """
import resource, sys
import numpy as np, scipy.sparse as sp
import condyn
resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
n = int(sys.argv[1])
diagonal = sp.coo_matrix((np.ones(3), ([0, 1, 2], [0, 1, 2])), shape=(n, n))
routes = {
    "sparse": lambda: {"mass": diagonal, "stiffness": diagonal},
    # A strided view declares n x n in a few bytes (its entries: ones).
    "dense": lambda: dict.fromkeys(("mass", "stiffness"), np.broadcast_to(np.float64(1.0), (n, n))),
    "block": lambda: {"mass": np.eye(3), "stiffness": np.eye(3)},
}
scene = {"model": {"type": "matrix", **routes[sys.argv[2]]()},
         "solve": {"t_end": 1.0, "output_step": 0.5}}
if sys.argv[2] == "block":  # constraint rows: held, not integrated as DOFs
    scene["constraint_block"] = [{"file": diagonal}]
try:
    condyn.run(scene)
except condyn.SceneError as e:
    print(e)
"""


def sized_call(n, route):
    done = subprocess.run([sys.executable, "-c", SIZED_CALL, str(n), route], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def without_available(message):
    """The message without the figure of available memory, which changes from call to call."""
    return re.sub(r"more than the [0-9.]+ [kMGTP]?B", "more than the X", message)


@pytest.mark.parametrize("route", ["sparse", "dense"])
def test_a_model_matrix_too_large_to_integrate_is_refused_as_the_cli_refuses(cli, tmp_path,
                                                                             route):
    # A scipy.sparse matrix of 10⁸ x 10⁸ with 3 entries was held in full before a refusal for
    # another reason, where the CLI refuses the same .mtx at its size line: the same check, the
    # same words, before anything of the matrix is held.
    mtx = tmp_path / "K.mtx"
    mtx.write_text(f"%%MatrixMarket matrix coordinate real general\n{HUGE} {HUGE} 3\n"
                   "1 1 1.0\n2 2 1.0\n3 3 1.0\n")
    scene = tmp_path / "huge.toml"
    scene.write_text('[model]\ntype = "matrix"\nmass = { file = "K.mtx" }\n'
                     'stiffness = { file = "K.mtx" }\n[solve]\nt_end = 1.0\noutput_step = 0.5\n')
    cli_run = subprocess.run([str(cli), "run", str(scene)], capture_output=True, text=True,
                             timeout=60)
    assert cli_run.returncode == 2
    cli_says = re.search(r"holding it and integrating .*\(MemAvailable in /proc/meminfo\)",
                         cli_run.stderr)
    assert cli_says, cli_run.stderr
    message = sized_call(HUGE, route)
    size = f"{HUGE} x {HUGE}"
    if route == "sparse":  # its 3 entries, as the file's: the same figure of bytes needed
        assert message.startswith(f"<dict>: model.mass: the array is {size} with 3 stored "
                                  "entries: "), message
        assert without_available(cli_says.group(0)) in without_available(message)
    else:  # refused before its entries are counted (or copied): as if all were zero
        assert message.startswith(f"<dict>: model.mass: the array is {size} with 0 stored "
                                  f"entries: holding it and integrating a model of {HUGE} DOFs "
                                  "needs at least "), message


def test_constraint_rows_too_large_to_hold_and_sizes_beyond_32_bit_indices_are_refused():
    # 2^31 rows: past the 32-bit indices of Eigen's and KLU's matrices, as a file's size line.
    assert sized_call(2**31, "sparse") == (f"<dict>: model.mass: the size {2**31} x {2**31} is "
                                           "not between 1 and 2^31 - 1")
    # Not a model matrix: only holding it is counted, 8 bytes a row and a column (34 GB here),
    # as the file reader counts a constraint block's.
    top = 2**31 - 1
    available = available_bytes()
    if available is None or available > 3.4e10:
        pytest.skip("this machine has the 34 GB available: the refusal cannot be shown")
    message = sized_call(top, "block")
    assert message.startswith(f"<dict>: constraint_block[1].file: the array is {top} x {top} "
                              "with 3 stored entries: holding it needs 34.4 GB, more than the "), \
        message


def available_bytes():
    """MemAvailable of /proc/meminfo in bytes, None where it cannot be read."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None
