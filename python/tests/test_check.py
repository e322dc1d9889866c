"""condyn.check: a scene's [[check]] tables from Python, as `condyn check` evaluates them; and
compare's per-run budget."""

import copy
import math
import os
import tomllib

import pytest

import condyn
from conftest import QUICKSTART, ROOT

OSCILLATOR = ROOT / "models" / "scenes" / "checks" / "oscillator_closed_form.toml"


def test_check_passes_and_agrees_with_the_cli(cli):
    import subprocess

    result = condyn.check(OSCILLATOR)
    assert result["passed"] and result["failure"] is None
    assert result["steps"] > 0 and len(result["checks"]) >= 1
    cli_run = subprocess.run([str(cli), "check", str(OSCILLATOR)], capture_output=True, text=True)
    assert cli_run.returncode == 0
    for c in result["checks"]:
        assert c["passed"] and c["computed"] <= c["bound"], c["text"]
        assert c["text"] in cli_run.stdout  # the same line as the command prints


def test_check_fails_when_a_bound_is_too_tight():
    with open(OSCILLATOR, "rb") as f:
        scene = tomllib.load(f)
    for c in scene["check"]:
        if "reference" in c:  # a dict's relative paths are taken from the working directory
            c["reference"]["file"] = str(OSCILLATOR.parent / c["reference"]["file"])
        for key in ("tolerance", "max_abs"):
            if key in c:
                c[key] = 1e-15 if key == "tolerance" else 1e-9
    result = condyn.check(scene)
    assert not result["passed"]
    assert any(not c["passed"] for c in result["checks"])


def test_a_run_that_fails_reports_its_failure_and_the_time_it_took():
    with open(OSCILLATOR, "rb") as f:
        scene = tomllib.load(f)
    scene["check"] = [{"quantity": "x", "max_abs": 2.0},
                      {"quantity": "vel_x", "at": 1.0, "value": 0.5, "tolerance": 1e-3}]
    scene["solve"]["max_steps"] = 50  # the budget ends the run: a failure, as the CLI's
    result = condyn.check(scene)
    assert not result["passed"]
    assert result["failure"] and "budget" in result["failure"]
    assert result["wall_s"] > 0.0  # it was 0 for a failed run
    # One dict per check, NaN where the run gave no figure (docs/python.md): the list was empty.
    assert [c["quantity"] for c in result["checks"]] == ["x", "vel_x"]
    assert [c["bound"] for c in result["checks"]] == [2.0, 1e-3]  # max_abs; the tolerance
    for c in result["checks"]:
        assert set(c) == {"quantity", "computed", "bound", "passed", "text"}
        assert math.isnan(c["computed"]) and c["passed"] is False
        assert "not evaluated" in c["text"] and "nan" not in c["text"].lower()


def test_check_lists_the_scenes_warnings_as_run_does():
    with open(OSCILLATOR, "rb") as f:
        scene = tomllib.load(f)
    scene["check"] = [{"quantity": "x", "max_abs": 2.0}]
    assert condyn.check(scene)["warnings"] == []
    scene["solve"]["rtol"] = 0.5
    warned = condyn.check(scene)["warnings"]
    assert warned == condyn.run(scene).summary["warnings"]
    assert warned == ["rtol 0.5 asks for fewer than 2 correct digits"]


def test_run_refuses_a_bad_check_as_the_cli_run_does(quickstart_dict):
    # docs/checks.md: `condyn run` refuses the checks `condyn check` would (exit 2).
    quickstart_dict["check"] = [{"quantity": "u9", "max_abs": 1.0}]
    with pytest.raises(condyn.SceneError, match=r"<dict>: check\[1\]\.quantity: no output column"):
        condyn.run(quickstart_dict)


def test_check_quotes_a_reference_path_that_is_not_utf8(tmp_path, quickstart_dict):
    # A folder named with the byte 0xff (surrogateescape): the check's text quotes the path as
    # the same str; it raised UnicodeDecodeError after the run, and the result was lost.
    folder = tmp_path / os.fsdecode(b"ref\xff")
    folder.mkdir()
    ref = folder / "ref.csv"
    ref.write_text("t,u3\n0,0\n2,0\n")
    quickstart_dict["check"] = [{"quantity": "u3", "reference": {"file": str(ref)},
                                 "tolerance": 10.0}]
    result = condyn.check(quickstart_dict)
    assert str(ref) in result["checks"][0]["text"]


def test_check_refuses_a_scene_without_checks(quickstart_dict):
    scene = copy.deepcopy(quickstart_dict)
    scene.pop("check", None)
    with pytest.raises(condyn.SceneError, match=r"^<dict>: has no \[\[check\]\] table"):
        condyn.check(scene)


def test_check_refuses_before_reading_the_scenes_files(tmp_path):
    # The matrix files are absent: the refusal is about the checks, not about them.
    scene = tmp_path / "matrix.toml"
    scene.write_text('[model]\ntype = "matrix"\nmass = { file = "absent_M.mtx" }\n'
                     'stiffness = { file = "absent_K.mtx" }\n[solve]\nt_end = 1.0\n')
    with pytest.raises(condyn.SceneError, match=r"matrix.toml: has no \[\[check\]\] table"):
        condyn.check(scene)


def test_compare_budget_marks_runs_over_it():
    runs = condyn.compare(QUICKSTART, tolerances=[1e-8], schemes=["ggl"], max_steps=5)
    assert len(runs) == 1 and not runs[0]["ok"]
    assert "5" in runs[0]["message"]
    # No figures for a failed run: 0 read as a perfect one.
    assert runs[0]["error_u"] is None and runs[0]["steps"] is None
    # Nor wall times (they were 0.0, and repeats 0).
    assert runs[0]["wall_median"] is None and runs[0]["wall_min"] is None
    assert runs[0]["wall_max"] is None and runs[0]["repeats"] is None


def test_check_runs_the_newmark_family_with_a_step_as_the_cli_does(cli):
    import subprocess

    # step= is the command's --step: the same run and the same lines; a step beyond t_end is bad
    # input (SceneError naming solve.step, exit 2). Without a step the scheme controls its steps.
    result = condyn.check(OSCILLATOR, scheme="generalized_alpha", step=1e-3)
    assert result["scheme"] == "generalized_alpha"
    cli_run = subprocess.run([str(cli), "check", str(OSCILLATOR), "--scheme", "generalized_alpha",
                              "--step", "1e-3"], capture_output=True, text=True)
    assert f"generalized_alpha, {result['steps']} steps" in cli_run.stdout
    for c in result["checks"]:
        assert c["text"] in cli_run.stdout
    with pytest.raises(condyn.SceneError, match="solve.step"):
        condyn.check(OSCILLATOR, scheme="generalized_alpha", step=1e9)
    bad = subprocess.run([str(cli), "check", str(OSCILLATOR), "--scheme", "generalized_alpha",
                          "--step", "1e9"], capture_output=True, text=True)
    assert bad.returncode == 2


@pytest.mark.parametrize("scene_file", [OSCILLATOR, QUICKSTART.parent / "checks" / "quickstart_checked.toml"])
def test_run_with_checks_gives_checks_verdict_on_its_own_rows(scene_file):
    # condyn sweep evaluated a scene's checks with condyn.check, a second run of the same scene;
    # run(checks=True) evaluates them on the run's own rows: the same verdict, figure for figure
    # (the same integration, rows assembled alike: equal to the last bit).
    alone = condyn.check(scene_file)
    r = condyn.run(scene_file, checks=True)
    assert r.checks is not None
    for key in ("passed", "failure", "drift", "scheme", "steps", "warnings"):
        assert r.checks[key] == alone[key], key
    assert [c["computed"] for c in r.checks["checks"]] == [c["computed"] for c in alone["checks"]]
    assert [c["text"] for c in r.checks["checks"]] == [c["text"] for c in alone["checks"]]
    assert condyn.run(scene_file).checks is None  # only when asked


def test_run_with_checks_on_a_failed_run_lists_each_check_unevaluated():
    with open(OSCILLATOR, "rb") as f:
        scene = tomllib.load(f)
    scene["check"] = [{"quantity": "x", "max_abs": 2.0}]
    scene["solve"]["max_steps"] = 50
    with pytest.raises(condyn.IntegrationError) as failed:
        condyn.run(scene, checks=True)
    verdict = failed.value.result.checks
    assert not verdict["passed"] and "budget" in verdict["failure"]
    assert len(verdict["checks"]) == 1 and math.isnan(verdict["checks"][0]["computed"])
