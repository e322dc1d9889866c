"""Issue 42: what a run says beyond its numbers, from Python as from the command line: a drift far
beyond the tolerance (in the summary, and failing check), the budget of steps between two
outputs as a dict key, and a ground motion record's unit warnings."""

import pytest

import condyn
from conftest import ROOT


def pendulum(scheme, **solve):
    """The pendulum over 100 s at rtol 1e-6, a check that holds under every scheme."""
    return {
        "model": {
            "type": "truss2d",
            "nodes": [[0.0, 0.0], [1.0, 0.0]],
            "masses": [0.0, 1.0],
            "supports": [1],
            "members": [{"nodes": [1, 2], "rigid": True}],
            "gravity": [0.0, -9.81],
        },
        "solve": {"t_end": 100.0, "output_step": 1.0, "rtol": 1e-6, "scheme": scheme, **solve},
        "check": [{"quantity": "ux2", "max_abs": 2.5}],
    }


def test_a_drift_beyond_the_tolerance_is_in_the_summary_and_fails_check():
    # index1 drifts to 0.0437 against 100 (rtol max|u| + atol) = 2.0e-4; GGL holds 1.9e-6.
    drifting = condyn.run(pendulum("index1")).summary
    assert "warning: the constraints drifted by" in drifting["notes"]
    assert "constraints drifted" in drifting["brief"]
    assert "drifted" not in condyn.run(pendulum("ggl")).summary["notes"]
    result = condyn.check(pendulum("index1"))
    assert not result["passed"]
    assert all(c["passed"] for c in result["checks"])  # the checks hold: the drift fails it
    assert result["drift"].startswith("the constraints drifted by")
    held = condyn.check(pendulum("ggl"))
    assert held["passed"] and held["drift"] is None


def test_max_steps_per_output_is_a_solve_key_of_the_dict():
    with pytest.raises(condyn.IntegrationError, match=r"max_steps_per_output"):
        condyn.run(pendulum("ggl", t_end=5.0, output_step=5.0, max_steps_per_output=40))
    with pytest.raises(condyn.SceneError, match=r"solve\.max_steps_per_output"):
        condyn.run(pendulum("ggl", max_steps_per_output=0))


def test_a_record_in_g_without_its_scale_is_warned_of():
    record = str(ROOT / "models" / "scenes" / "data" / "el_centro_1940_ns.csv")
    scene = {
        "units": "SI",
        "model": {"type": "matrix", "dofs": ["u"], "mass": [[2e5]], "stiffness": [[3e8]]},
        "ground_motion": {
            "influence": {"u": 1.0},
            "acceleration": {"type": "table", "file": record},
        },
        "solve": {"t_end": 1.0, "output_step": 0.1},
    }
    warnings = condyn.run(scene).summary["warnings"]
    assert any("says the record" in w and "is in g, but its scale 1 is not g" in w
               for w in warnings)
