#!/usr/bin/python3
"""Generate a planar chain of N rigid links for the projection scheme's benchmark (issue 44, item 11).

The chain of models/scenes/hanging_chain.toml at any length: N links of length 0.5 (point masses on
rigid bars, a nonlinear truss2d model), node 1 fixed, a mass of 0.1 at every other node, released
from rest along a straight line 30 degrees below the horizontal under gravity. 2(N + 1) DOFs,
N + 2 constraint rows (2 support rows, N distance rows). Output: the free end's displacements
only, so that writing the result costs nothing beside the run.

  /usr/bin/python3 bench/chain.py --links N [--t-end 0.1] --out FILE
"""
import argparse
import math
import sys


def scene(links, t_end, output_step):
    """The scene's text for `links` links."""
    dx, dy = 0.5 * math.cos(math.radians(30.0)), -0.5 * math.sin(math.radians(30.0))
    nodes = ", ".join(f"[{repr(k * dx)}, {repr(k * dy)}]" for k in range(links + 1))
    masses = ", ".join(["0.0"] + ["0.1"] * links)
    members = ", ".join(f"{{ nodes = [{k}, {k + 1}], rigid = true }}" for k in range(1, links + 1))
    return f"""# A chain of {links} rigid links hanging from node 1 (bench/chain.py; issue 44, item 11).
# Run: build/condyn run THIS_FILE --scheme projection
name = "Chain of {links} rigid links"

[model]
type = "truss2d"
nodes = [{nodes}]
masses = [{masses}]
supports = [1]
members = [{members}]
gravity = [0.0, -9.81]

[solve]
t_end = {t_end!r}
output_step = {output_step!r}
rtol = 1e-6
atol = 1e-8

[output]
quantities = ["displacement"]
dofs = ["ux{links + 1}", "uy{links + 1}"]
"""


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, required=True)
    parser.add_argument("--t-end", type=float, default=0.1)
    parser.add_argument("--output-step", type=float, default=0.01)
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    if args.links < 1:
        sys.exit("chain.py: --links must be at least 1")
    with open(args.out, "w") as fh:
        fh.write(scene(args.links, args.t_end, args.output_step))


if __name__ == "__main__":
    main()
