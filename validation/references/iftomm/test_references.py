"""The IFToMM and 3D references (validation/references/iftomm/README.md), ctest label validation:
each script's self-checks pass on a short run, the stored CSV agrees with that run where they
overlap, and every scene that checks against a CSV names columns the CSV holds at the scene's
own output times."""
import glob
import importlib
import math
import os
import re
import sys
import tomllib

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, HERE)
import iftomm_common as ic  # noqa: E402

# script, stored CSV, the short run's end (the self-checks hold on any interval; a short one keeps
# the tier fast: A04 solves its closure at every evaluation, A05 is stiff and derived by SymPy)
CASES = [
    ("reference_A01", "A01_reference.csv", 20.0),
    ("reference_A02", "A02_reference.csv", 20.0),
    ("reference_A04", "A04_reference.csv", 0.5),
    ("reference_A05", "A05_reference.csv", 0.25),
    ("reference_heavy_top", "heavy_top_reference.csv", 4.0),
    ("reference_inclined_revolute", "inclined_revolute_reference.csv", 4.0),
]
# The stored CSVs were written by the same scripts at the same settings: a shorter run takes the
# same steps up to its end, so the rows agree to roundoff, but solve_ivp's last step before a
# shorter end may differ; 1e-10 is 100 rtol, far below any scheme's error the checks admit.
AGREEMENT = 1e-10


@pytest.mark.parametrize("module,csv_name,t_end", CASES)
def test_self_checks_and_stored_rows(module, csv_name, t_end):
    mod = importlib.import_module(module)
    t, columns, checks, title = mod.compute(t_end)
    assert ic.report(title, checks), f"{module}: a self-check failed (printed above)"
    stored = ic.read_csv(os.path.join(HERE, csv_name))
    assert list(stored)[1:] == list(columns), f"{csv_name}: columns differ from {module}'s"
    rows = stored["t"] <= t_end + 1e-12
    assert np.array_equal(stored["t"][rows], t), f"{csv_name}: output times differ"
    for name, values in columns.items():
        worst = np.max(np.abs(stored[name][rows] - values))
        assert worst <= AGREEMENT, f"{csv_name}: {name} off by {worst:.3e} from a rerun"


def scenes_with_references():
    found = []
    for path in sorted(glob.glob(os.path.join(ROOT, "models", "scenes", "**", "*.toml"),
                                 recursive=True)):
        with open(path, "rb") as f:
            scene = tomllib.load(f)
        for check in scene.get("check", []):
            ref = check.get("reference", {}).get("file", "")
            if "references/iftomm/" in ref:
                found.append((path, scene, check["quantity"], ref))
    return found


@pytest.mark.parametrize("path,scene,quantity,ref", scenes_with_references(),
                         ids=lambda v: os.path.basename(v) if isinstance(v, str) else "")
def test_scene_checks_name_reference_columns(path, scene, quantity, ref):
    stored = ic.read_csv(os.path.normpath(os.path.join(os.path.dirname(path), ref)))
    assert quantity in stored, f"{path}: {quantity} is not a column of {ref}"
    solve = scene["solve"]
    assert stored["t"][-1] == pytest.approx(solve["t_end"], abs=1e-12), f"{path}: t_end"
    steps = np.diff(stored["t"])
    # the reference sampled at the scene's output times: no interpolation error in the check
    assert np.allclose(steps, solve["output_step"], rtol=1e-9, atol=0.0), f"{path}: output_step"


def test_every_benchmark_scene_is_checked():
    checked = {os.path.basename(p) for p, *_ in scenes_with_references()}
    expected = {"A01_simple_pendulum.toml", "A02_n_four_bar.toml", "A04_bricard.toml",
                "A05_flyball_governor.toml", "heavy_top.toml", "inclined_revolute.toml"}
    assert expected <= checked, f"unchecked: {sorted(expected - checked)}"


@pytest.mark.parametrize("module,scene_name", [("write_A02_scene", "A02_n_four_bar.toml"),
                                               ("write_A03_scene", "A03_andrews.toml")])
def test_written_scenes_are_current(module, scene_name):
    """The generated scenes are what their writers write (edit the writer, not the scene): the
    same text but for the last digits of computed numbers. The writers' trigonometry (libm's and
    numpy's) rounds differently on different processors: A03's body positions came out a few
    ulps apart on two CI machines (0.050337813329684546 against 0.05033781332968454), so numbers
    are compared to 1e-13 relative (beside 1e-15 absolute, for a computed zero)."""
    mod = importlib.import_module(module)
    text = mod.scene(40) if module == "write_A02_scene" else mod.scene()
    with open(os.path.join(ROOT, "models", "scenes", "iftomm", scene_name)) as f:
        stored = f.read()
    number = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
    assert number.split(stored) == number.split(text), \
        f"{scene_name} differs from {module}.py's output beyond its numbers: rerun it"
    differ = [(a, b) for a, b in zip(map(float, number.findall(stored)),
                                     map(float, number.findall(text)))
              if not math.isclose(a, b, rel_tol=1e-13, abs_tol=1e-15)]
    assert not differ, f"{scene_name}: numbers differ from {module}.py's, e.g. {differ[:3]}: rerun it"


def test_andrews_bodies_carry_the_test_sets_mass_matrix():
    """A03 as rigid bodies has the test set's mass matrix at its start (see write_A03_scene.py)."""
    import write_A03_scene
    assert write_A03_scene.check_mass_matrix() < 1e-8
