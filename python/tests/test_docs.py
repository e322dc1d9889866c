"""docs/python.md's promises about what run, compare and check return, statement by statement,
where no other test of this folder holds them: types, shapes, keys and values."""

import math
import re

import numpy as np
import pytest

import condyn
from conftest import QUICKSTART, ROOT

PENDULUM = ROOT / "models" / "scenes" / "pendulum.toml"
OSCILLATOR = ROOT / "models" / "scenes" / "checks" / "oscillator_closed_form.toml"

# The energy balance's columns, in the CSV's order (docs/energy.md).
ENERGY_COLUMNS = ["energy", "energy_error", "energy_kinetic", "energy_potential",
                  "energy_dissipated", "work_loads", "work_constraints"]


def every_quantity(quickstart_dict):
    quickstart_dict["output"]["quantities"] = [
        "displacement", "velocity", "acceleration", "reaction", "multiplier", "drift"]
    return condyn.run(quickstart_dict)


def test_run_arrays_have_the_documented_shapes(quickstart_dict):
    # "r.t (nt,); r.u, r.v (nt, n); r.reaction (nt, n); r.multiplier (nt, m); r.drift (nt, 2);
    # r.a (nt, n) when [output] asks for acceleration", all float64.
    r = every_quantity(quickstart_dict)
    nt, n, m = len(r.t), len(r.dof_names), len(r.constraint_names)
    assert (nt, n, m) == (5, 3, 2)  # t_end 2 every 0.5 s; u1..u3; base and link
    assert r.t.shape == (nt,)
    for name in ("u", "v", "reaction", "a"):
        assert getattr(r, name).shape == (nt, n), name
    assert r.multiplier.shape == (nt, m) and r.drift.shape == (nt, 2)
    for name in ("t", "u", "v", "reaction", "a", "multiplier", "drift"):
        assert getattr(r, name).dtype == np.float64, name
    assert r.a_abs is None  # only under [ground_motion] with absolute_acceleration
    # "r.dof_names, r.constraint_names": lists of str.
    assert all(isinstance(x, str) for x in r.dof_names + r.constraint_names)


def test_views_and_copies_are_as_documented(quickstart_dict):
    # "read-only views of the run's own memory (nothing is copied), except drift, a_abs and
    # energy_balance, small read-only copies".
    r = every_quantity(quickstart_dict)
    for name in ("t", "u", "v", "reaction", "multiplier", "a"):
        array = getattr(r, name)
        assert array.base is not None and not array.flags.owndata, name  # a view
        assert not array.flags.writeable, name
    assert r.drift.flags.owndata and not r.drift.flags.writeable
    p = condyn.run(PENDULUM)
    assert p.energy_balance.flags.owndata and not p.energy_balance.flags.writeable
    for name in ("energy", "kinetic"):
        assert not getattr(p, name).flags.owndata and not getattr(p, name).flags.writeable


def test_energy_of_a_conservative_model_and_none_otherwise(quickstart_dict):
    # "r.energy, r.kinetic (nt,) total and kinetic energy of a conservative model, else None;
    # r.energy_balance (nt, 7) when [output] asks for "energy" (columns named by
    # r.energy_columns), else None".
    p = condyn.run(PENDULUM)  # a rigid pendulum under gravity: conservative, asks for energy
    nt = len(p.t)
    assert p.energy.shape == (nt,) and p.kinetic.shape == (nt,)
    assert p.energy_balance.shape == (nt, 7)
    assert p.energy_columns == ENERGY_COLUMNS
    # The balance's own columns are the same figures: energy and kinetic, bit for bit.
    np.testing.assert_array_equal(p.energy_balance[:, 0], p.energy)
    np.testing.assert_array_equal(p.energy_balance[:, 2], p.kinetic)
    # quickstart: a driven support and damping, no conservative energy, no "energy" asked for.
    q = condyn.run(quickstart_dict)
    assert q.energy is None and q.kinetic is None and q.energy_balance is None
    assert q.energy_columns == ENERGY_COLUMNS  # the names are there whatever the run


def test_dof_gives_a_column_and_names_the_dofs_otherwise():
    # "r.dof("u3")  # a DOF's column"
    r = condyn.run(QUICKSTART)
    assert [r.dof(name) for name in r.dof_names] == [0, 1, 2]
    np.testing.assert_array_equal(r.u[:, r.dof("u3")], r.u[:, 2])
    with pytest.raises(KeyError, match="no DOF 'u9'; DOFs: u1, u2, u3"):
        r.dof("u9")


def test_summary_holds_the_documented_keys_and_types():
    # "r.summary  # dict: scheme, steps, wall_s, rtol, atol, residual_evals, jacobian_evals".
    s = condyn.run(QUICKSTART, scheme="ggl").summary
    assert isinstance(s["scheme"], str) and s["scheme"] == "ggl"
    for key in ("steps", "residual_evals", "jacobian_evals"):
        assert isinstance(s[key], int) and s[key] > 0, key
    for key in ("wall_s", "rtol", "atol"):
        assert isinstance(s[key], float), key
    assert isinstance(s["warnings"], list)


def test_compare_returns_the_documented_keys_and_default_tolerances():
    # "returns one dict per run: scheme, rtol, atol, ok, message, reference (exact, published,
    # or the scheme of a tight run), error_u, error_v, error_reaction, the drifts, steps,
    # evaluations and wall times"; default tolerances 1e-3 ... 1e-10.
    runs = condyn.compare(QUICKSTART, schemes=["ggl"])
    assert [r["rtol"] for r in runs] == [10.0 ** -k for k in range(3, 11)]
    for r in runs:
        assert r["scheme"] == "ggl" and r["ok"] is True and r["skipped"] is False
        assert isinstance(r["message"], str)
        assert r["reference"] in ("exact", "published", "elimination", "ggl", "projection",
                                  "index1")
        for key in ("atol", "error_u", "error_v", "error_reaction", "max_drift_position",
                    "max_drift_velocity", "final_drift_position", "final_drift_velocity",
                    "wall_median", "wall_min", "wall_max"):
            assert isinstance(r[key], float), key
        for key in ("steps", "residual_evals", "jacobian_evals", "newton_failures",
                    "error_test_failures", "repeats"):
            assert isinstance(r[key], int), key


def test_check_returns_the_documented_keys_and_figures():
    # "returns passed, failure, scheme, steps, wall_s, warnings and checks: one dict per check
    # with quantity, computed, bound, passed and text"; "for a value check the deviation
    # |x(at) - value| (x(at) itself is in text), for max_abs the largest |quantity|".
    result = condyn.check(OSCILLATOR)
    assert {"passed", "failure", "scheme", "steps", "wall_s", "warnings", "checks"} <= set(result)
    assert result["passed"] is True and result["failure"] is None
    assert isinstance(result["scheme"], str) and isinstance(result["steps"], int)
    assert isinstance(result["wall_s"], float) and isinstance(result["warnings"], list)
    r = condyn.run(OSCILLATOR)
    checks = result["checks"]
    value = next(c for c in checks if c["text"].startswith("x at t = 3: "))
    # "x at t = 3: -0.9899924953251423, expected -0.9899924966004454 +- 1e-08 (off by ...)"
    x_at, expected = (float(v) for v in re.match(
        r"x at t = 3: (\S+), expected (\S+) \+- ", value["text"]).groups())
    assert x_at == r.u[np.argmin(np.abs(r.t - 3.0)), 0]  # the row at t = 3, bit for bit
    assert value["computed"] == abs(x_at - expected)  # the same subtraction, bit for bit
    assert value["passed"] == (value["computed"] <= value["bound"])
    largest = next(c for c in checks if c["text"].startswith("max |vel_x| = "))
    # The run's own velocities (the check asks for them, so the run's v is the same).
    assert largest["computed"] == np.max(np.abs(r.v[:, 0]))
    for c in checks:
        assert isinstance(c["quantity"], str) and isinstance(c["computed"], float)
        assert isinstance(c["bound"], float) and isinstance(c["passed"], bool)
        assert c["passed"] == (c["computed"] <= c["bound"]) and not math.isnan(c["computed"])
