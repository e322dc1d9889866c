#!/usr/bin/python3
"""Writes models/scenes/iftomm/A02_n_four_bar.toml: IFToMM A02 for N windows (default the
specification's 40), 2N+1 bodies and 3N+1 revolute joints, named as reference_A02.py names them.
The [[check]] tables against A02_reference.csv are written for N = 40 only, the N that reference
computes (the crank's motion depends on N: reference_A02.py's m_eff and V).
Run: /usr/bin/python3 validation/references/iftomm/write_A02_scene.py [N]
"""
import os
import sys

import iftomm_common as ic

HEADER = """\
# IFToMM benchmark A02, the N-four-bar mechanism, as its specification states it
# (http://lim.ii.udc.es/mbsbenchmark/dist/A02/A02_specification.xml): 2N+1 links of 1 m with a
# uniformly distributed mass of 1 kg (inertia m L^2 / 12 = 1/12), N = {n}, gravity 9.81 N/kg along
# -y, 20 s in 400 output steps; initially the N+1 cranks stand upright on the ground pivots
# A_i = (i, 0) and the couplers lie at y = 1 (as the OpenSim reproduction builds the figure's
# position: github.com/RehabEngGroup/MBSbenchmarksInOpenSim), B0 (crank0's tip) moving at +1 m/s
# along x. The reference is B0's position and velocity; the accuracy measure the largest error
# (1e-3 "high precision", 1e-1 "low"). The mechanism turns for good: each time the links lie on
# the ground line (20 times in 20 s) it passes a singular position where the Jacobian loses
# rank and N more DOF appear; the specification's reference stays on the branch where the
# couplers keep translating, as validation/references/iftomm/A02_reference.csv does.
# Written by validation/references/iftomm/write_A02_scene.py.
# Run: build/condyn check models/scenes/iftomm/A02_n_four_bar.toml
name = "IFToMM A02: N-four-bar mechanism, N = {n}"

[model]
type = "multibody"
dimension = 2
gravity = [0.0, -9.81]
ground = {{ {ground} }}
"""

CRANK = """
[[body]]
name = "crank{i}"
mass = 1.0
inertia = 0.08333333333333333
position = [{x}, 0.5]
angle = 1.5707963267948966     # body x along the crank, upright
velocity = [0.5, 0.0]
angular_velocity = -1.0
points = {{ A = [-0.5, 0.0], B = [0.5, 0.0] }}
"""

COUPLER = """
[[body]]
name = "coupler{i}"
mass = 1.0
inertia = 0.08333333333333333
position = [{x}, 1.0]
angle = 0.0
velocity = [1.0, 0.0]
points = {{ L = [-0.5, 0.0], R = [0.5, 0.0] }}
"""

JOINT = """
[[joint]]
name = "{name}"
type = "revolute"
bodies = ["{a}", "{b}"]
points = ["{pa}", "{pb}"]
"""

FOOTER = """
[solve]
t_end = 20.0
output_step = 0.05            # the specification's 400 output steps
scheme = "ggl"
rtol = 1e-10
atol = 1e-12

[output]
quantities = ["displacement", "velocity", "reaction", "drift", "energy"]
points = ["crank0.B"]
"""

CHECKS = """
[[check]]                     # B0's path to the specification's high precision, 1e-3
quantity = "crank0.B.x"
reference = {{ file = "{ref}" }}
tolerance = 1e-3

[[check]]
quantity = "crank0.B.y"
reference = {{ file = "{ref}" }}
tolerance = 1e-3

[[check]]                     # B0's velocity is coupler1's (it translates with B0)
quantity = "coupler1.vx"
reference = {{ file = "{ref}" }}
tolerance = 1e-3

[[check]]                     # the far end stays on the branch too
quantity = "coupler{n}.angle"
reference = {{ file = "{ref}" }}
tolerance = 1e-3
"""


def scene(n):
    ground = ", ".join(f"A{i} = [{float(i)}, 0.0]" for i in range(n + 1))
    parts = [HEADER.format(n=n, ground=ground)]
    parts += [CRANK.format(i=i, x=float(i)) for i in range(n + 1)]
    parts += [COUPLER.format(i=i, x=i - 0.5) for i in range(1, n + 1)]
    parts += [JOINT.format(name=f"A{i}", a="ground", b=f"crank{i}", pa=f"A{i}", pb="A")
              for i in range(n + 1)]
    for i in range(1, n + 1):
        parts.append(JOINT.format(name=f"B{i - 1}_L", a=f"crank{i - 1}", b=f"coupler{i}",
                                  pa="B", pb="L"))
        parts.append(JOINT.format(name=f"B{i}_R", a=f"crank{i}", b=f"coupler{i}", pa="B", pb="R"))
    parts.append(FOOTER)
    if n == 40:  # the reference's N
        parts.append(CHECKS.format(n=n, ref="../../../validation/references/iftomm/A02_reference.csv"))
    return "".join(parts)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    path = os.path.join(ic.HERE, "..", "..", "..", "models", "scenes", "iftomm",
                        "A02_n_four_bar.toml")
    with open(path, "w") as f:
        f.write(scene(n))
    print(os.path.normpath(path))


if __name__ == "__main__":
    main()
