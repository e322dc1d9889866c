#!/usr/bin/python3
"""IFToMM A01, the planar simple pendulum, in its one minimal coordinate.

Specification (http://lim.ii.udc.es/mbsbenchmark/dist/A01/A01_specification.xml): a lumped mass
of 1 kg on a massless link of 1 m, gravity 9.81 N/kg along -y, released at rest with P1 at
x = +1 m (link horizontal), 2000 s sampled in 4000 output steps. theta is the link's angle from
the downward vertical: P1 = (L sin theta, -L cos theta), theta(0) = pi/2, and
theta'' = -(g/L) sin theta. The scene (models/scenes/iftomm/A01_simple_pendulum.toml) models the
lumped mass as a body "bob" centred at P1 held by a distance joint of 1 m to the ground point O:
the massless link carries only a force along itself, through the bob's centre, so the bob's own
rotation is never excited (its angle stays 0, whatever inertia it is given) and its centre moves
as the point mass does. Columns: bob.x, bob.y (= P1), bob.vx, bob.vy, bob.angle (0).

The CSV holds the closed form (exact); the SciPy integration at rtol 1e-12 checks it:
energy conserved, the motion against the closed form
sin(theta/2) = k sn(K - w t | k^2), k = sin(theta0/2), w = sqrt(g/L); the period between
successive turning points against 4 K(k^2) / w.
Run: /usr/bin/python3 validation/references/iftomm/reference_A01.py  (writes A01_reference.csv)
"""
import sys

import numpy as np

import iftomm_common as ic

MASS, LENGTH, G = 1.0, 1.0, 9.81
THETA0 = np.pi / 2.0
T_END, STEPS = 2000.0, 4000


def rhs(_t, y):
    theta, theta_dot = y
    return [theta_dot, -(G / LENGTH) * np.sin(theta)]


def energy(theta, theta_dot):
    return 0.5 * MASS * LENGTH**2 * theta_dot**2 - MASS * G * LENGTH * np.cos(theta)


def turning_point(_t, y):
    return y[1]


def compute(t_end=T_END):
    """The reference columns at the benchmark's output times up to t_end (the closed form, which
    is exact) and the self-checks (the SciPy integration against it among them)."""
    t = np.linspace(0.0, t_end, int(round(t_end / T_END * STEPS)) + 1)
    y, sol = ic.integrate(rhs, [THETA0, 0.0], t, events=turning_point)
    w = np.sqrt(G / LENGTH)
    theta, theta_dot = ic.pendulum_closed_form(t, THETA0, w)
    x, yy = LENGTH * np.sin(theta), -LENGTH * np.cos(theta)
    columns = {"bob.x": x, "bob.y": yy, "bob.vx": LENGTH * np.cos(theta) * theta_dot,
               "bob.vy": LENGTH * np.sin(theta) * theta_dot, "bob.angle": np.zeros_like(t)}
    period = ic.pendulum_period(THETA0, w)
    turns = sol.t_events[0]
    turns = turns[turns > 1e-9]  # the release at t = 0 is a turning point too
    checks = [
        ("energy drift of the integration / m g L",
         ic.relative_drift(energy(y[:, 0], y[:, 1]), MASS * G * LENGTH), 1e-10,
         "conserved; 100 rtol"),
        ("energy drift of the closed form / m g L",
         ic.relative_drift(energy(theta, theta_dot), MASS * G * LENGTH), 1e-12,
         "exact up to ellipj's roundoff"),
        ("max |theta (SciPy, rtol 1e-12) - closed form| (rad)", np.max(np.abs(y[:, 0] - theta)),
         1e-7, "global error over 845 periods grows linearly: 1e5 rtol"),
        ("max |2 (t_turn,i+1 - t_turn,i) - 4K/w| / period",
         np.max(np.abs(2.0 * np.diff(turns) - period)) / period, 1e-10, "100 rtol"),
    ]
    return t, columns, checks, f"A01 simple pendulum: {len(t)} rows to {t_end} s, period 4K/w = {period:.15f} s"


def main(out_dir=ic.HERE):
    t, columns, checks, title = compute()
    ic.write_csv("A01_reference.csv", t, columns, out_dir)
    return ic.report(title, checks)


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
