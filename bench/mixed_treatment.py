#!/usr/bin/python3
"""What the mixed constraint treatment saves (issue 12, item 7): each scene under index1 and GGL,
with a multiplier for every row ([solve] constraints = "multipliers") and mixed (the cheap linear
rows eliminated, dae/formulations/constraint_treatment.hpp), and the lattice of bench/lattice.py under the same
four runs and elimination.

For every run: unknowns, steps, Jacobian evaluations, median wall time in the solver over --repeat
runs, and the largest displacement error against a reference run of the same scene (pure GGL at
rtol 1e-11, atol 1e-13, or the first of REFERENCES that succeeds), so that a saving is never bought with accuracy unseen. Lattice runs have no
reference (their error is not the point: the scheme's cost at size is).

  /usr/bin/python3 bench/mixed_treatment.py [--repeat 5] [--lattice 1e4 1e5]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SCENES = ["slider_crank", "four_bar", "double_pendulum", "hanging_chain", "truss_inclined_roller",
          "von_mises_truss", "chain_driven_base", "spherical_pendulum"]
# The reference of a scene: the first of these that reaches t_end at rtol 1e-11 (GGL at such
# tolerances fails on some mechanisms near singular configurations: docs/schemes.md).
REFERENCES = [("ggl", "multipliers"), ("ggl", "mixed"), ("index1", "multipliers")]
SUMMARY = re.compile(
    r"^(?P<scheme>[a-z0-9_]+): reached[^\n]*? (?P<steps>\d+) steps, (?P<res>\d+) residual and "
    r"(?P<jac>\d+) Jacobian evaluations,[^\n]*? (?P<unknowns>\d+) unknowns, wall "
    r"(?P<wall>[0-9.eE+-]+) ms", re.M)


def run(condyn, scene, args, out):
    proc = subprocess.run([condyn, "run", scene, "--out", out] + args, capture_output=True,
                          text=True, timeout=3600)
    m = SUMMARY.search(proc.stdout + proc.stderr)
    if proc.returncode != 0 or not m:
        return None
    return {k: float(m.group(k)) for k in ("steps", "jac", "unknowns", "wall")}


def displacement_columns(path):
    data = np.genfromtxt(path, delimiter=",", names=True)
    names = [n for n in data.dtype.names if n != "t" and not n.startswith(("vel_", "reaction_",
                                                                           "drift", "energy",
                                                                           "lambda_"))]
    return np.column_stack([data[n] for n in names])


def measure(condyn, scene, args, repeat, tmp):
    out = os.path.join(tmp, "run.csv")
    rows = [run(condyn, scene, args, out) for _ in range(repeat)]
    if any(r is None for r in rows):
        return None, out
    row = dict(rows[0])
    row["wall"] = statistics.median(r["wall"] for r in rows)
    return row, out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--lattice", nargs="*", default=["1e4"], help="lattice sizes (DOFs)")
    p.add_argument("--condyn", default=os.path.join(ROOT, "build", "condyn"))
    a = p.parse_args(argv)
    print(f"{'scene':24} {'run':22} {'unknowns':>8} {'steps':>6} {'Jac':>5} {'wall ms':>9} "
          f"{'max |u - ref|':>13}")
    with tempfile.TemporaryDirectory() as tmp:
        for name in SCENES:
            scene = os.path.join(ROOT, "models", "scenes", name + ".toml")
            ref_csv = os.path.join(tmp, "ref.csv")
            u_ref = None
            for scheme, treatment in REFERENCES:
                if run(a.condyn, scene, ["--scheme", scheme, "--constraints", treatment, "--rtol",
                                         "1e-11", "--atol", "1e-13"], ref_csv):
                    u_ref = displacement_columns(ref_csv)
                    print(f"{name:24} reference: {scheme} {treatment}, rtol 1e-11, atol 1e-13")
                    break
            for scheme in ("index1", "ggl"):
                for treatment in ("multipliers", "mixed"):
                    row, out = measure(a.condyn, scene, ["--scheme", scheme, "--constraints",
                                                         treatment], a.repeat, tmp)
                    label = f"{scheme} {treatment}"
                    if row is None:
                        print(f"{name:24} {label:22} failed")
                        continue
                    err = (np.max(np.abs(displacement_columns(out) - u_ref))
                           if u_ref is not None else float("nan"))
                    print(f"{name:24} {label:22} {row['unknowns']:8.0f} {row['steps']:6.0f} "
                          f"{row['jac']:5.0f} {row['wall']:9.1f} {err:13.2e}")
        for size in a.lattice:
            n = int(float(size))
            folder = os.path.join(tmp, f"lattice{n}")
            subprocess.run([sys.executable, os.path.join(HERE, "lattice.py"), "--dofs", str(n),
                            "--out", folder], check=True, capture_output=True)
            scene = os.path.join(folder, "lattice.toml")
            runs = [("elimination", ["--scheme", "elimination"])]
            for scheme in ("index1", "ggl"):
                for treatment in ("multipliers", "mixed"):
                    runs.append((f"{scheme} {treatment}",
                                 ["--scheme", scheme, "--constraints", treatment]))
            for label, args in runs:
                row, _ = measure(a.condyn, scene, args, a.repeat, tmp)
                if row is None:
                    print(f"{'lattice ' + size:24} {label:22} failed")
                    continue
                print(f"{'lattice ' + size:24} {label:22} {row['unknowns']:8.0f} "
                      f"{row['steps']:6.0f} {row['jac']:5.0f} {row['wall']:9.1f} {'-':>13}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
