#!/usr/bin/python3
"""A body on an inclined revolute axis (issue 44 item 10): its one-DOF equation.

The body: a homogeneous bar 0.04 x 0.5 x 0.04 m (long along body y) of 2 kg, hinged at one end
O (the origin) on the axis n = (sin b, 0, cos b), b = pi/3 from the vertical; gravity 9.81 along
-z; released at rest with the bar along +y (horizontal, its centre of mass c0 = (0, 0.25, 0)
perpendicular to n). Turned by theta about n, c = R_n(theta) c0 has the height
r sin b sin theta (r = 0.25), so with J = n.I_c.n + m r^2 (inertia about the axis)
  J theta'' = -m g r sin b cos theta,
a pendulum of w^2 = m g r sin b / J about theta = -pi/2 released pi/2 from it: the closed form
of iftomm_common.pendulum_closed_form is exact, and the CSV holds it; the SciPy integration of
the one-DOF equation at rtol 1e-12 checks it, with energy and the period 4 K / w.
4 s in 400 output steps.

Body "bar" (points O at the hinge, tip at the free end; body frame = global at t = 0; axis n
in both frames), as in models/scenes/inclined_revolute.toml. Columns: bar.x/y/z, bar.qw/qx/qy/qz
(the rotation about n by theta: [cos(theta/2), n sin(theta/2)]), bar.wx/wy/wz = theta' n,
bar.tip.x/y/z.
Run: /usr/bin/python3 validation/references/iftomm/reference_inclined_revolute.py
"""
import sys

import numpy as np

import iftomm_common as ic

MASS, G, BETA = 2.0, 9.81, np.pi / 3.0
SIZE = (0.04, 0.5, 0.04)
R_CM = SIZE[1] / 2.0
AXIS = np.array([np.sin(BETA), 0.0, np.cos(BETA)])
I_CM = ic.box_inertia(MASS, *SIZE)
J = AXIS @ np.diag(I_CM) @ AXIS + MASS * R_CM**2
W = np.sqrt(MASS * G * R_CM * np.sin(BETA) / J)
T_END, STEPS = 4.0, 400


def rhs(_t, y):
    return [y[1], -MASS * G * R_CM * np.sin(BETA) * np.cos(y[0]) / J]


def rotation(theta):
    """Rodrigues: rotation by theta about AXIS."""
    k = np.array([[0.0, -AXIS[2], AXIS[1]], [AXIS[2], 0.0, -AXIS[0]], [-AXIS[1], AXIS[0], 0.0]])
    return np.eye(3) + np.sin(theta) * k + (1.0 - np.cos(theta)) * (k @ k)


def energy(theta, theta_dot):
    return 0.5 * J * theta_dot**2 + MASS * G * R_CM * np.sin(BETA) * np.sin(theta)


def columns(theta, theta_dot):
    cm = np.array([rotation(a) @ [0.0, R_CM, 0.0] for a in theta])
    tip = np.array([rotation(a) @ [0.0, 2.0 * R_CM, 0.0] for a in theta])
    q = np.column_stack([np.cos(theta / 2.0)] + [AXIS[k] * np.sin(theta / 2.0) for k in range(3)])
    cols = {}
    for k, ax in enumerate("xyz"):
        cols[f"bar.{ax}"] = cm[:, k]
    for k, name in enumerate(("qw", "qx", "qy", "qz")):
        cols[f"bar.{name}"] = q[:, k]
    for k, ax in enumerate("xyz"):
        cols[f"bar.w{ax}"] = AXIS[k] * theta_dot
    for k, ax in enumerate("xyz"):
        cols[f"bar.tip.{ax}"] = tip[:, k]
    return cols


def turning_point(_t, y):
    return y[1]


def compute(t_end=T_END):
    t = np.linspace(0.0, t_end, int(round(t_end / T_END * STEPS)) + 1)
    y, sol = ic.integrate(rhs, [0.0, 0.0], t, events=turning_point)
    vartheta, rate = ic.pendulum_closed_form(t, np.pi / 2.0, W)
    theta = vartheta - np.pi / 2.0
    period = ic.pendulum_period(np.pi / 2.0, W)
    turns = sol.t_events[0][sol.t_events[0] > 1e-9]
    scale = MASS * G * R_CM * np.sin(BETA)
    checks = [
        ("energy drift of the integration / (m g r sin b)",
         ic.relative_drift(energy(y[:, 0], y[:, 1]), scale), 1e-10, "conserved; 100 rtol"),
        ("energy drift of the closed form / (m g r sin b)",
         ic.relative_drift(energy(theta, rate), scale), 1e-12, "exact up to ellipj's roundoff"),
        ("max |theta (SciPy, rtol 1e-12) - closed form| (rad)", np.max(np.abs(y[:, 0] - theta)),
         1e-10, "global error over 2 periods: 100 rtol"),
        ("max |2 (t_turn,i+1 - t_turn,i) - 4K/w| / period",
         np.max(np.abs(2.0 * np.diff(turns) - period)) / period, 1e-10, "100 rtol"),
    ]
    title = (f"inclined revolute: {len(t)} rows to {t_end} s, J = {J:.15f} kg m^2, "
             f"period 4K/w = {period:.12f} s")
    return t, columns(theta, rate), checks, title


def main(out_dir=ic.HERE):
    t, cols, checks, title = compute()
    ic.write_csv("inclined_revolute_reference.csv", t, cols, out_dir)
    return ic.report(title, checks)


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
