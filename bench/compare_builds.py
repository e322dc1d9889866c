#!/usr/bin/python3
"""Two builds of condyn on the scenes of models/scenes and validation/scenes under one scheme.

For each scene and rtol (1e-4, 1e-6, 1e-8; atol = rtol/100) it runs the baseline binary and the
candidate and prints steps, Newton iterations per step (residual evaluations / steps), Jacobian
evaluations, Newton and error-test failures, and the error: the largest difference of the output
columns from a reference run (elimination at rtol 1e-11, else GGL at 1e-11, by the baseline),
relative to the reference's largest value. Then geometric means of the candidate's ratios to the
baseline over the cases both finished, linear and nonlinear scenes apart.

    /usr/bin/python3 bench/compare_builds.py BASELINE CANDIDATE --scheme ggl

What it measured is in docs/benchmarks.md (GGL's Newton corrections from a stale matrix).
"""

import argparse
import math
import os
import re
import subprocess
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
COUNTS = re.compile(r"(\d+) steps, (\d+) residual and (\d+) Jacobian evaluations, "
                    r"(\d+) Newton and (\d+) error-test")


def run(binary, scene, scheme, rtol, out):
    """(steps, residuals, jacobians, newton failures, error-test failures), columns; or None."""
    p = subprocess.run([binary, "run", str(scene), "--scheme", scheme, "--rtol", str(rtol),
                        "--atol", str(rtol * 1e-2), "--out", out], capture_output=True, text=True,
                       cwd=scene.parent, timeout=900)
    m = COUNTS.search(p.stdout + p.stderr)
    if p.returncode != 0 or not m:
        return None
    return tuple(int(x) for x in m.groups()), np.genfromtxt(out, delimiter=",", names=True)


def geometric_mean(xs):
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else float("nan")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("baseline")
    p.add_argument("candidate")
    p.add_argument("--scheme", default="ggl")
    args = p.parse_args()
    scenes = sorted((ROOT / "models/scenes").glob("*.toml")) + sorted(
        (ROOT / "validation/scenes").glob("*.toml"))
    ratios = {}  # linear or not -> list of (steps, iterations, jacobians, error) ratios
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            ref = (run(args.baseline, scene, "elimination", 1e-11, f"{tmp}/ref.csv"), True)
            if ref[0] is None:
                ref = (run(args.baseline, scene, "ggl", 1e-11, f"{tmp}/ref.csv"), False)
            (reference, linear) = ref
            if reference is None:
                print(f"{scene.stem}: no reference run")
                continue
            cols = [c for c in reference[1].dtype.names if c != "t"]
            R = np.column_stack([reference[1][c] for c in cols])
            scale = max(float(np.max(np.abs(R))), 1e-300)
            for rtol in (1e-4, 1e-6, 1e-8):
                line, got = f"{scene.stem:28s} {rtol:.0e}", []
                for binary in (args.baseline, args.candidate):
                    r = run(binary, scene, args.scheme, rtol, f"{tmp}/run.csv")
                    if r is None:
                        line += " | failed" + " " * 62
                        got.append(None)
                        continue
                    (st, res, jac, nf, etf), d = r
                    X = np.column_stack([d[c] for c in cols])
                    n = min(len(X), len(R))
                    err = float(np.max(np.abs(X[:n] - R[:n]))) / scale
                    line += (f" | st {st:7d} it/st {res / st:4.2f} jac {jac:6d} nf {nf:6d} "
                             f"etf {etf:6d} err {err:8.2e}")
                    got.append((st, res, jac, err))
                print(line, flush=True)
                if None not in got and got[0][3] > 0 and got[1][3] > 0:
                    a, b = got
                    ratios.setdefault(linear, []).append(
                        (b[0] / a[0], b[1] / a[1], b[2] / a[2], b[3] / a[3]))
    for linear, rs in sorted(ratios.items()):
        means = [geometric_mean([r[k] for r in rs]) for k in range(4)]
        print(f"{'linear' if linear else 'nonlinear'} scenes, {len(rs)} cases, candidate / "
              f"baseline (geometric means): steps {means[0]:.3f}, Newton iterations "
              f"{means[1]:.3f}, Jacobian evaluations {means[2]:.3f}, error {means[3]:.3f}")


if __name__ == "__main__":
    main()
