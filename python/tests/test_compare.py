"""condyn.compare: the sweep of `condyn compare` as a list of dicts."""

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
    with pytest.raises(condyn.SceneError, match="tolerances must lie in"):
        condyn.compare(QUICKSTART, tolerances=[2.0])
