"""The README's Python example is the program's: its code block runs as written and prints what
the README shows (step counts and the displacement exactly as printed; drifts, which sit at
round-off level for Baumgarte, within a factor of 10 and below 1e-10 m)."""

import os
import re
import subprocess
import sys

from conftest import ROOT


def readme_blocks():
    text = (ROOT / "README.md").read_text()
    section = text[text.index("## Python"):]
    section = section[:section.index("\n## ", 1)]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    shown = re.search(r"it prints\n\(and draws `drift.png`\):\n\n```\n(.*?)```", section,
                      re.S).group(1)
    return code, shown


LINE = re.compile(r"^(\w+) +(\d+) steps, max drift (\S+) m, u10\(5 s\) = (\S+) m$", re.M)


def test_readme_python_example_prints_what_the_readme_shows(tmp_path):
    code, shown = readme_blocks()
    (tmp_path / "chain.py").write_text(code)
    # Run where the README's reader would, with the module's path made absolute.
    path = os.pathsep.join(os.path.abspath(p) for p in sys.path if p)
    run = subprocess.run([sys.executable, "chain.py"], cwd=tmp_path, capture_output=True,
                         text=True, env=dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=path),
                         check=True)
    printed = {m[0]: m[1:] for m in LINE.findall(run.stdout)}
    expected = {m[0]: m[1:] for m in LINE.findall(shown)}
    assert set(printed) == set(expected) == {"ggl", "baumgarte"}, run.stdout
    for scheme, (steps, drift, u10) in expected.items():
        got_steps, got_drift, got_u10 = printed[scheme]
        assert got_steps == steps and got_u10 == u10, (scheme, printed[scheme])
        assert float(got_drift) < 1e-10
        assert float(drift) / 10 <= float(got_drift) <= float(drift) * 10, (scheme, got_drift)
    assert (tmp_path / "drift.png").stat().st_size > 10000
