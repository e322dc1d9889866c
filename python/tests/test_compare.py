"""condyn.compare: the sweep of `condyn compare` as a list of dicts."""

import numpy as np
import pytest

import condyn
from conftest import QUICKSTART


def test_compare_two_schemes():
    runs = condyn.compare(QUICKSTART, tolerances=[1e-6, 1e-8], schemes=["ggl", "index1"])
    assert [(r["scheme"], r["rtol"]) for r in runs] == [
        ("ggl", 1e-6), ("ggl", 1e-8), ("index1", 1e-6), ("index1", 1e-8)]
    for r in runs:
        assert r["ok"] and not r["skipped"], r["message"]
        assert r["reference"] == "exact"  # a linear model: the exact modal solution
        # Errors against the reference shrink with the tolerance (max-norm, metres).
        assert 0.0 < r["error_u"] < 1e3 * r["rtol"]
        assert r["steps"] > 0 and r["repeats"] == 1
    assert runs[1]["error_u"] < runs[0]["error_u"]


def test_compare_refuses_bad_arguments():
    with pytest.raises(condyn.SceneError, match="schemes: name schemes, not 'auto'"):
        condyn.compare(QUICKSTART, schemes=["auto"])
    with pytest.raises(condyn.SceneError, match=r"tolerances: each lies in \[1e-15, 1\) \(got 2\)"):
        condyn.compare(QUICKSTART, tolerances=[2.0])


@pytest.mark.parametrize("kwargs, message", [
    # The command line's ranges (docs/cli.md): these ran, or failed as runs, before.
    ({"tolerances": [1e-20]}, r"tolerances: each lies in \[1e-15, 1\) \(got 1e-20\)"),
    ({"drift_rtol": 1e-20}, r"drift_rtol: lies in \[1e-14, 0.5\] \(got 1e-20\)"),
    ({"drift_rtol": 0.9}, r"drift_rtol: lies in \[1e-14, 0.5\] \(got 0.9\)"),
    ({"repeats": 1000}, r"repeats: lies in \[1, 100\] \(got 1000\)"),
    ({"max_wall_time": 1e-12}, r"max_wall_time: 0 for no budget, else in \[1e-09, 1e\+12\]"),
])
def test_compare_holds_the_command_lines_ranges(kwargs, message):
    with pytest.raises(condyn.SceneError, match=message):
        condyn.compare(QUICKSTART, schemes=["ggl"], **kwargs)


@pytest.mark.parametrize("kwargs, message", [
    ({"schemes": "ggl"}, r"schemes: expected a list \(got str 'ggl'\); give \['ggl'\] for one"),
    ({"tolerances": 1e-4}, r"tolerances: expected a list \(got float 0.0001\)"),
    ({"tolerances": ["1e-4"]}, r"tolerances\[0\]: expected a number \(got str '1e-4'\)"),
    ({"tolerances": [1e-4, None]}, r"tolerances\[1\]: None is not a value"),
    ({"tolerances": [1e-4, 1e-4]}, r"tolerances: 0.0001 is listed twice"),
    ({"schemes": ["ggl", "ggl"]}, r"schemes: 'ggl' is listed twice"),
    ({"repeats": 2.0}, r"repeats: expected an integer \(got float 2.0\)"),
    ({"repeats": True}, r"repeats: expected an integer \(got bool True\)"),
    ({"drift_rtol": "1e-6"}, r"drift_rtol: expected a number \(got str '1e-6'\)"),
    ({"max_steps": 10**20}, r"max_steps: 100000000000000000000 is out of range"),
])
def test_compare_names_a_badly_typed_argument(kwargs, message):
    # Each would reach pybind11 as an argument of the wrong type: its TypeError lists the
    # signature and every argument given, the whole scene for a dict.
    with pytest.raises(condyn.SceneError, match=message):
        condyn.compare(QUICKSTART, **kwargs)


def test_compare_accepts_tuples_arrays_and_numpy_integers():
    runs = condyn.compare(QUICKSTART, tolerances=np.array([1e-4]), schemes=("ggl",),
                          repeats=np.int64(1), max_steps=None, max_wall_time=None)
    assert [(r["scheme"], r["rtol"], r["ok"]) for r in runs] == [("ggl", 1e-4, True)]


def test_compare_issues_the_scenes_warnings(quickstart_dict):
    # As the command prints them: a displacement beyond 1e15 is warned of (units).
    quickstart_dict.setdefault("initial", {})["displacement"] = {"u2": 2e15, "u3": 2e15}
    with pytest.warns(UserWarning, match=r"<dict>: \[initial\] displacements up to magnitude"):
        condyn.compare(quickstart_dict, tolerances=[1e-4], schemes=["ggl"])


def test_compare_without_a_reference_raises_integration_error():
    # A nonlinear scene (no exact solution) whose tight reference runs all fail (a load of
    # 1e300 strikes at t = 0.5): no run can be scored. It was a bare RuntimeError, documented
    # nowhere. (A scene's step budget no longer bounds the reference.)
    scene = {"model": {"type": "truss2d", "nodes": [[0.0, 0.0], [1.0, 0.0]],
                       "masses": [0.0, 1.0], "supports": [1],
                       "members": [{"nodes": [1, 2], "rigid": True}]},
             "load": [{"dof": "uy2",
                       "value": {"type": "step", "amplitude": 1e300, "start": 0.5}}],
             "solve": {"t_end": 1.0, "output_step": 0.1}}
    with pytest.raises(condyn.IntegrationError, match=r"^<dict>: no reference solution") as e:
        condyn.compare(scene, tolerances=[1e-4], schemes=["ggl"])
    assert e.value.result is None


def test_a_skipped_scheme_has_every_key_of_a_run():
    # elimination does not treat a nonholonomic row: its record is skipped, with the same keys as
    # a run's (None), so a table of the records needs no special case.
    runs = condyn.compare(QUICKSTART.parent / "chaplygin_sleigh.toml", tolerances=[1e-3],
                          schemes=["ggl", "elimination"], max_steps=20000)
    ran = [r for r in runs if not r["skipped"]]
    skipped = [r for r in runs if r["skipped"]]
    assert [r["scheme"] for r in skipped] == ["elimination"]
    assert set(skipped[0]) == set(ran[0])
    assert skipped[0]["rtol"] is None and skipped[0]["steps"] is None
    # Every key but scheme, skipped and message, as docs/python.md says: ok too (it was False,
    # a verdict on a run that never ran; reference was the sweep's).
    assert {k for k, v in skipped[0].items() if v is not None} == {"scheme", "skipped", "message"}
    assert skipped[0]["ok"] is None and skipped[0]["skipped"] is True
    assert "nonholonomic" in skipped[0]["message"]


def test_compare_marks_runs_far_beyond_their_target():
    # Every run carries its target, its worst error over it and the mark (docs/python.md);
    # GGL's errors on the quickstart stay within 1e3 times rtol (test above), far below the
    # default mark 1e4.
    runs = condyn.compare(QUICKSTART, tolerances=[1e-6], schemes=["ggl"])
    r = runs[0]
    assert r["ok"], r["message"]
    assert r["error_target"] == 1e-6
    worst = max(r["error_u"], r["error_v"], r["error_reaction"])
    assert r["error_ratio"] == pytest.approx(worst / r["error_target"], rel=1e-15)
    assert r["over_tolerance"] is False


def test_compare_sets_the_newmark_family_under_a_fixed_step_no_target(quickstart_dict):
    # Under a fixed step rtol is only the Newton tolerance of newmark, hht and generalized_alpha:
    # no target, no ratio, never marked (docs/schemes.md), whatever its error against rtol.
    runs = condyn.compare(quickstart_dict, tolerances=[1e-6], schemes=["ggl", "hht"], step=0.01)
    ggl, hht = runs
    assert ggl["error_target"] == 1e-6
    assert hht["ok"], hht["message"]
    assert hht["error_target"] is None and hht["error_ratio"] is None
    assert hht["over_tolerance"] is False
    assert hht["error_u"] > 0.0
    # The same as [solve] step in the scene; a step beyond t_end is refused naming solve.step.
    quickstart_dict["solve"]["step"] = 0.01
    assert condyn.compare(quickstart_dict, tolerances=[1e-6], schemes=["hht"])[0]["error_u"] == \
        hht["error_u"]
    with pytest.raises(condyn.SceneError, match="solve.step"):
        condyn.compare(quickstart_dict, tolerances=[1e-6], schemes=["hht"], step=1e9)
