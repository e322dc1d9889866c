#!/usr/bin/python3
"""Writes models/scenes/iftomm/A03_andrews.toml: Andrews' squeezing mechanism (IFToMM A03) as
seven rigid bodies and ten revolute joints, from the Test Set for IVP Solvers' data (release
2.4, problem "andrews", the same as condyn's built-in model type = "andrews": the parameters
below are its models/systems/andrews.cpp's). Each body's frame is chosen so that its output
angle is the test set's absolute link angle: body1 beta, body2 beta + Theta, body3 gamma,
body4 Phi + delta, body5 delta, body6 Omega + epsilon, body7 epsilon. The test set's equations
fix each centre of mass's distance from the body's pivot (bodies 1, 3, 5, 7 turn about ground
pivots, with no gravity, so only that distance enters) and its place on the coupler links 2, 4,
6; the positions follow from the published initial angles.
Run: /usr/bin/python3 validation/references/iftomm/write_A03_scene.py
"""
import os

import numpy as np

import iftomm_common as ic

M = [.04325, .00365, .02373, .00706, .07050, .00706, .05498]
INERTIA = [2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7, 1.169e-5, 5.667e-7, 1.912e-5]
XA, YA, XB, YB, XC, YC, C0 = -.06934, -.00227, -.03635, .03273, .014, .072, 4530.0
D, DA, E, EA, RR, RA, L0 = 28e-3, 115e-4, 2e-2, 1421e-5, 7e-3, 92e-5, 7785e-5
SS, SA, SB, SC, SD = 35e-3, 1874e-5, 1043e-5, 18e-3, 2e-2
TA, TB, U, UA, UB, ZF, ZT, FA, MOM = 2308e-5, 916e-5, 4e-2, 1228e-5, 449e-5, 2e-2, 4e-2, 1421e-5, 33e-3
# beta, Theta, gamma, Phi, delta, Omega, epsilon at t = 0 (the test set's consistent start)
Q0 = [-0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449,
      0.222668390165885884674473185609, 0.487364979543842550225598953530,
      -0.222668390165885884674473185609, 1.23054744454982119249735015568]
# the test set's reference at t = 0.03 (PSIDE, rtol = atol = 1e-14), as condyn builds it in
Q_REF = [0.1581077119629904e+2, -0.1575637105984298e+2, 0.4082224013073101e-1,
         -0.5347301163226948e+0, 0.5244099658805304e+0, 0.5347301163226948e+0,
         0.1048080741042263e+1]


def angles(q):
    beta, theta, gamma, phi, delta, omega, eps = q
    return [beta, beta + theta, gamma, phi + delta, delta, omega + eps, eps]


def bodies(q=Q0):
    """Per body: name, index, centre of mass (global) and named points (body frame, relative to
    the centre of mass), at the angles q."""
    a = angles(q)

    def rot(k, v):
        c, s = np.cos(a[k]), np.sin(a[k])
        return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])

    o, b, pa = np.zeros(2), np.array([XB, YB]), np.array([XA, YA])
    f = o + rot(0, [RR, 0.0])
    g = pa + rot(4, [ZT, 0.0])
    h = pa + rot(6, [0.0, -U])
    # body: reference point (global), centre of mass (body frame, from it), named points (body
    # frame, from the reference point)
    spec = [
        ("body1", o, [RA, 0.0], {"O": [0.0, 0.0], "F": [RR, 0.0]}),
        ("body2", f, [-DA, 0.0], {"F": [0.0, 0.0], "E": [-D, 0.0]}),
        ("body3", b, [SA, SB], {"B": [0.0, 0.0], "E": [0.0, -SS], "D": [SD, -SC]}),
        ("body4", g, [0.0, -(E - EA)], {"G": [0.0, 0.0], "E": [0.0, -E]}),
        ("body5", pa, [TA, TB], {"A": [0.0, 0.0], "G": [ZT, 0.0]}),
        ("body6", h, [ZF - FA, 0.0], {"H": [0.0, 0.0], "E": [ZF, 0.0]}),
        ("body7", pa, [UA, UB], {"A": [0.0, 0.0], "H": [0.0, -U]}),
    ]
    out = []
    for k, (name, ref, com, pts) in enumerate(spec):
        com = np.array(com)
        position = ref + rot(k, com)
        rel = {p: np.array(v) - com for p, v in pts.items()}
        out.append((name, k, position, rel))
    e_points = [pos + rot(k, rel["E"]) for name, k, pos, rel in out if "E" in rel]
    spread = max(np.max(np.abs(p - e_points[0])) for p in e_points)
    if q is Q0:
        assert spread < 1e-15, f"the initial angles do not close the loops at E: {spread}"
    return out, a


def test_set_mass_matrix(q):
    """M(q) of the test set (models/systems/andrews.cpp's formulas)."""
    _, th, _, ph, _, om, _ = q
    ee, ff = (E - EA) ** 2, (ZF - FA) ** 2
    m = np.zeros((7, 7))
    m[0, 0] = M[0] * RA**2 + M[1] * (RR**2 - 2 * DA * RR * np.cos(th) + DA**2) + INERTIA[0] + INERTIA[1]
    m[1, 0] = m[0, 1] = M[1] * (DA**2 - DA * RR * np.cos(th)) + INERTIA[1]
    m[1, 1] = M[1] * DA**2 + INERTIA[1]
    m[2, 2] = M[2] * (SA**2 + SB**2) + INERTIA[2]
    m[3, 3] = M[3] * ee + INERTIA[3]
    m[4, 3] = m[3, 4] = M[3] * (ee + ZT * (E - EA) * np.sin(ph)) + INERTIA[3]
    m[4, 4] = (M[3] * (ZT**2 + 2 * ZT * (E - EA) * np.sin(ph) + ee) + M[4] * (TA**2 + TB**2)
               + INERTIA[3] + INERTIA[4])
    m[5, 5] = M[5] * ff + INERTIA[5]
    m[6, 5] = m[5, 6] = M[5] * (ff - U * (ZF - FA) * np.sin(om)) + INERTIA[5]
    m[6, 6] = (M[5] * (ff - 2 * U * (ZF - FA) * np.sin(om) + U**2) + M[6] * (UA**2 + UB**2)
               + INERTIA[5] + INERTIA[6])
    return m


def check_mass_matrix():
    """The bodies' kinetic energy in the test set's coordinates equals 1/2 v.M(q).v: the centres
    of mass sit where the test set's equations put them. Central differences of the positions
    (h = 1e-6): agreement to 1e-8 relative is their truncation error, not a tolerance on data."""
    h = 1e-6
    jac = np.zeros((7, 3, 7))   # body, (x, y, angle), coordinate
    for j in range(7):
        dq = np.zeros(7)
        dq[j] = h
        plus, ap = bodies(np.array(Q0) + dq)
        minus, am = bodies(np.array(Q0) - dq)
        for k in range(7):
            jac[k, :2, j] = (plus[k][2] - minus[k][2]) / (2 * h)
            jac[k, 2, j] = (ap[k] - am[k]) / (2 * h)
    mm = sum(M[k] * jac[k, :2].T @ jac[k, :2] + INERTIA[k] * np.outer(jac[k, 2], jac[k, 2])
             for k in range(7))
    ref = test_set_mass_matrix(Q0)
    err = np.max(np.abs(mm - ref)) / np.max(np.abs(ref))
    assert err < 1e-8, f"the bodies' mass matrix differs from the test set's by {err:.2e}"
    return err


def fmt(v):
    return "[" + ", ".join(repr(float(x)) for x in v) + "]"


def scene():
    out, a = bodies()
    lines = [HEADER]
    for name, k, position, rel in out:
        pts = ", ".join(f"{p} = {fmt(v)}" for p, v in rel.items())
        lines.append(f'\n[[body]]\nname = "{name}"\nmass = {M[k]!r}\ninertia = {INERTIA[k]!r}\n'
                     f"position = {fmt(position)}\nangle = {a[k]!r}\npoints = {{ {pts} }}\n")
    joints = [("O", "ground", "body1", "O", "O"), ("F", "body1", "body2", "F", "F"),
              ("B", "ground", "body3", "B", "B"), ("A5", "ground", "body5", "A", "A"),
              ("A7", "ground", "body7", "A", "A"), ("G", "body5", "body4", "G", "G"),
              ("H", "body7", "body6", "H", "H"), ("E3", "body2", "body3", "E", "E"),
              ("E4", "body2", "body4", "E", "E"), ("E6", "body2", "body6", "E", "E")]
    for name, b1, b2, p1, p2 in joints:
        lines.append(f'\n[[joint]]\nname = "{name}"\ntype = "revolute"\nbodies = ["{b1}", "{b2}"]\n'
                     f'points = ["{p1}", "{p2}"]\n')
    lines.append(FORCES)
    ref = angles(Q_REF)
    for k, value in enumerate(ref):
        lines.append(f'\n[[check]]\nquantity = "body{k + 1}.angle"\nat = 0.03\nvalue = {value!r}\n'
                     f"tolerance = {TOLERANCE!r}\n")
    return "".join(lines)


# 1e-6 rad: the published values' 10 digits hold; a run at rtol 1e-10 reaches about 1e-8 on the
# built-in model (condyn compare), and a wrong inertia or joint moves the angles by far more
TOLERANCE = 1e-6

HEADER = """\
# IFToMM benchmark A03, Andrews' squeezing mechanism, as seven rigid bodies and ten revolute
# joints: the data of the Test Set for IVP Solvers (release 2.4, problem "andrews"), the same
# as the built-in model (models/scenes/andrews.toml, [model] type = "andrews"), whose published
# reference at t = 0.03 (PSIDE, rtol = atol = 1e-14) the checks below compare the body angles
# with: body1 beta, body2 beta + Theta, body3 gamma, body4 Phi + delta, body5 delta, body6
# Omega + epsilon, body7 epsilon. No gravity; a constant driving moment of 0.033 N m on body1;
# a spring (c0 = 4530 N/m, rest length 0.07785 m) from D on body3 to the ground point C.
# Released at rest from the test set's consistent angles, 0.03 s.
# Written by validation/references/iftomm/write_A03_scene.py.
# Run: build/condyn check models/scenes/iftomm/A03_andrews.toml
name = "IFToMM A03: Andrews' squeezing mechanism, as rigid bodies"

[model]
type = "multibody"
dimension = 2
ground = { O = [0.0, 0.0], A = [-0.06934, -0.00227], B = [-0.03635, 0.03273], C = [0.014, 0.072] }
"""

FORCES = """
[[force]]
type = "torque"
body = "body1"
torque = 0.033

[[force]]
type = "spring_damper"
bodies = ["body3", "ground"]
points = ["D", "C"]
k = 4530.0
rest_length = 0.07785

[solve]
t_end = 0.03
output_step = 0.001
scheme = "ggl"
rtol = 1e-10
atol = 1e-12

[output]
quantities = ["displacement", "velocity", "reaction", "drift", "energy"]
"""


def main():
    print(f"mass matrix against the test set's: {check_mass_matrix():.2e} (relative)")
    path = os.path.join(ic.HERE, "..", "..", "..", "models", "scenes", "iftomm", "A03_andrews.toml")
    with open(path, "w") as f:
        f.write(scene())
    print(os.path.normpath(path))


if __name__ == "__main__":
    main()
