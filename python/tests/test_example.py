"""python/examples/two_schemes.py runs and writes its figure; its printed figures hold what the
example claims (both schemes within a few rtol of the reference, GGL's drift far below it)."""

import os
import pathlib
import re
import subprocess
import sys

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "two_schemes.py"


def test_example_runs(tmp_path):
    out = tmp_path / "two.png"
    run = subprocess.run([sys.executable, str(EXAMPLE), str(out)], capture_output=True, text=True,
                         env=dict(os.environ), check=True)
    assert out.stat().st_size > 10000
    rows = {m[0]: (float(m[1]), float(m[2])) for m in re.findall(
        r"^(\w+) +\d+ steps  max drift (\S+) m  max error (\S+) m", run.stdout, re.M)}
    assert set(rows) == {"ggl", "baumgarte"}, run.stdout
    for drift, error in rows.values():
        assert error < 1e-3  # rtol 1e-6 of a motion of order 0.01-0.1 m, with margin
    assert rows["ggl"][0] < 1e-8
