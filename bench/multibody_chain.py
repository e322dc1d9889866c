#!/usr/bin/python3
"""Write a chain of N rigid bodies as a multibody scene (issue 44, item 11: the chain benchmarks).

Planar (--dimension 2): N bars of length 0.5 and mass 0.1 (inertia m L^2/12 about the centre),
joined end to end by revolute joints, the first hinged to the ground at O, released from rest
along a straight line 30 degrees below the horizontal under gravity -9.81 along y. 4N natural
coordinates, N rigid rows and 2N joint rows.

Spatial (--dimension 3): N bars of the same length and mass, thin cylinders of radius 0.02 along
their body x axis (inertia [m r^2/2, m(3r^2 + L^2)/12, m(3r^2 + L^2)/12]), laid along a straight
line 30 degrees below the horizontal in the x-z plane, gravity -9.81 along z. With --joint
spherical (the default) every joint is spherical and the whole chain starts turning as one rigid
body about the vertical through O at 1 rad/s (a consistent start with spatial motion); with
--joint revolute the joints' axes alternate between the bodies' y axis (horizontal, normal to the
line) and their z axis (normal to the bar in the x-z plane), starting from rest. 12N natural
coordinates, 6N rigid rows, 3N (spherical) or 5N (revolute) joint rows.

Output: the last body's pose only, so that writing the result costs nothing beside the run.

  /usr/bin/python3 bench/multibody_chain.py --bodies N [--dimension 2|3]
      [--joint spherical|revolute] [--t-end 0.02] [--scheme S] --out FILE
"""
import argparse
import math
import sys

LENGTH = 0.5
MASS = 0.1
RADIUS = 0.02
SLOPE = math.radians(30.0)  # the line's angle below the horizontal
SPIN = 1.0                  # rad/s about the vertical through O (spatial, spherical joints)


def planar_bodies(n):
    """[[body]] and [[joint]] tables of the planar chain."""
    inertia = MASS * LENGTH**2 / 12.0
    c, s = math.cos(SLOPE), -math.sin(SLOPE)
    out = []
    for k in range(1, n + 1):
        x, y = (k - 0.5) * LENGTH * c, (k - 0.5) * LENGTH * s
        out.append(f"""[[body]]
name = "b{k}"
mass = {MASS!r}
inertia = {inertia!r}
position = [{x!r}, {y!r}]
angle = {-SLOPE!r}
points = {{ A = [{-LENGTH / 2!r}, 0.0], B = [{LENGTH / 2!r}, 0.0] }}
""")
    for k in range(1, n + 1):
        first, point = ("ground", "O") if k == 1 else (f"b{k - 1}", "B")
        out.append(f"""[[joint]]
name = "j{k}"
type = "revolute"
bodies = ["{first}", "b{k}"]
points = ["{point}", "A"]
""")
    return "\n".join(out)


def spatial_body(k, joint):
    """The [[body]] table of the spatial chain's k-th bar (1-based)."""
    axial = MASS * RADIUS**2 / 2.0
    transverse = MASS * (3.0 * RADIUS**2 + LENGTH**2) / 12.0
    x, z = (k - 0.5) * LENGTH * math.cos(SLOPE), -(k - 0.5) * LENGTH * math.sin(SLOPE)
    # Rigid rotation about the global z axis: v = w ez x r, with r_y = 0.
    spin = SPIN if joint == "spherical" else 0.0
    return f"""[[body]]
name = "b{k}"
mass = {MASS!r}
inertia = [{axial!r}, {transverse!r}, {transverse!r}]
position = [{x!r}, 0.0, {z!r}]
orientation = {{ axis = [0.0, 1.0, 0.0], angle = {SLOPE!r} }}
velocity = [0.0, {spin * x!r}, 0.0]
angular_velocity = [0.0, 0.0, {spin!r}]
points = {{ A = [{-LENGTH / 2!r}, 0.0, 0.0], B = [{LENGTH / 2!r}, 0.0, 0.0] }}
axes = {{ y = [0.0, 1.0, 0.0], z = [0.0, 0.0, 1.0] }}
"""


def spatial_joint(k, joint):
    """The [[joint]] table joining bar k - 1 (or the ground) to bar k."""
    first, point = ("ground", "O") if k == 1 else (f"b{k - 1}", "B")
    text = f"""[[joint]]
name = "j{k}"
type = "{joint}"
bodies = ["{first}", "b{k}"]
points = ["{point}", "A"]
"""
    if joint == "revolute":
        axis = "y" if k % 2 == 1 else "z"
        text += f'axes = ["{axis}", "{axis}"]\n'
    return text


def spatial_bodies(n, joint):
    return "\n".join([spatial_body(k, joint) for k in range(1, n + 1)] +
                     [spatial_joint(k, joint) for k in range(1, n + 1)])


def scene(n, dimension, joint, t_end, scheme=None):
    """The scene's text."""
    if dimension == 2:
        model = ('dimension = 2\ngravity = [0.0, -9.81]\nground = { O = [0.0, 0.0] }\n')
        tables = planar_bodies(n)
        columns = ["x", "y", "angle"]
        what = f"planar chain of {n} bars on revolute joints"
    else:
        model = ('dimension = 3\ngravity = [0.0, 0.0, -9.81]\nground = { O = [0.0, 0.0, 0.0] }\n'
                 'ground_axes = { y = [0.0, 1.0, 0.0] }\n')
        tables = spatial_bodies(n, joint)
        columns = ["x", "y", "z"]
        what = f"spatial chain of {n} bars on {joint} joints"
    dofs = ", ".join(f'"b{n}.{c}"' for c in columns)
    solve = f"t_end = {t_end!r}\noutput_step = {t_end!r}\nrtol = 1e-6\natol = 1e-8\n"
    if scheme:
        solve += f'scheme = "{scheme}"\n'
    return f"""# A {what} (bench/multibody_chain.py; issue 44, item 11).
# Run: build/condyn run THIS_FILE --scheme ggl
name = "{what}"

[model]
type = "multibody"
{model}
{tables}
[solve]
{solve}
[output]
quantities = ["displacement"]
dofs = [{dofs}]
"""


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bodies", type=int, required=True)
    parser.add_argument("--dimension", type=int, choices=[2, 3], default=2)
    parser.add_argument("--joint", choices=["spherical", "revolute"], default="spherical",
                        help="the spatial chain's joints (the planar one's are revolute)")
    parser.add_argument("--t-end", type=float, default=0.02)
    parser.add_argument("--scheme")
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    if args.bodies < 1:
        sys.exit("multibody_chain.py: --bodies must be at least 1")
    if not args.t_end > 0.0:
        sys.exit("multibody_chain.py: --t-end must be positive")
    with open(args.out, "w") as fh:
        fh.write(scene(args.bodies, args.dimension, args.joint, args.t_end, args.scheme))


if __name__ == "__main__":
    main()
