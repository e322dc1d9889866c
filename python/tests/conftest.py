"""Shared paths and scenes of the Python module's tests (run by ctest, label python)."""

import os
import pathlib
import tomllib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
QUICKSTART = ROOT / "models" / "scenes" / "quickstart.toml"


@pytest.fixture
def cli():
    """The condyn executable ctest points to (CONDYN_BINARY), else build/condyn."""
    path = pathlib.Path(os.environ.get("CONDYN_BINARY", ROOT / "build" / "condyn"))
    if not path.exists():
        pytest.fail(f"no condyn executable at {path} (build target condyn)")
    return path


@pytest.fixture
def quickstart_dict():
    """models/scenes/quickstart.toml as a dict (the TOML's structure, read by tomllib)."""
    with open(QUICKSTART, "rb") as f:
        return tomllib.load(f)
