#!/usr/bin/python3
"""A heavy symmetric top on a spherical joint (issue 44 item 10), in Euler angles.

The top: mass 1 kg, centre of mass on its symmetry axis 0.3 m from the fixed point O (the
spherical joint at the origin), inertia about the centre of mass diag(0.02, 0.02, 0.03) kg m^2
(body frame, z the symmetry axis), gravity 9.81 along -z; at t = 0 its axis is tilted by
theta0 = pi/6 about global x (orientation {axis = [1, 0, 0], angle = pi/6}) and it spins about
its own axis at 60 rad/s, with no precession and no nutation rate. 4 s in 400 output steps.
Euler angles z-x-z: R = Rz(psi) Rx(theta) Rz(phi); with A = A_c + m l^2 and C about O,
  L = A/2 (theta'^2 + psi'^2 sin^2 theta) + C/2 (phi' + psi' cos theta)^2 - m g l cos theta.
The right-hand side is the Euler-Lagrange equations (M(q) q'' = f); the conserved energy, p_psi
and p_phi are checks, not inputs. The nutation period is exact: with u = cos theta the motion
obeys u'^2 = (2 m g l / A)(u - u1)(u - u2)(u - u3), and the time from u2 to u1 and back is
T = 4 K(k) / sqrt((2 m g l / A)(u3 - u1)), k = (u2 - u1)/(u3 - u1) (complete elliptic integral).

Body "top" (points O at the joint, tip 0.3 m beyond the centre of mass on the axis), as in
models/scenes/heavy_top.toml. Columns: top.x/y/z (centre of mass), top.qw/qx/qy/qz, top.wx/wy/wz
(global), top.tip.x/y/z.
Run: /usr/bin/python3 validation/references/iftomm/reference_heavy_top.py  (writes heavy_top_reference.csv)
"""
import sys

import numpy as np
from scipy.special import ellipk

import iftomm_common as ic

MASS, L_CM, L_TIP, G = 1.0, 0.3, 0.3, 9.81
A = 0.02 + MASS * L_CM**2   # about O, perpendicular to the axis
C = 0.03                    # about the axis
THETA0, SPIN = np.pi / 6.0, 60.0
T_END, STEPS = 4.0, 400


def rhs(_t, y):
    """Euler-Lagrange in (psi, theta, phi): p_psi' = 0, p_phi' = 0 differentiated, and theta's."""
    _psi, th, _phi, dpsi, dth, dphi = y
    s, c = np.sin(th), np.cos(th)
    m = np.array([[A * s * s + C * c * c, C * c], [C * c, C]])
    rhs2 = np.array([-2.0 * (A - C) * s * c * dth * dpsi + C * s * dth * dphi,
                     C * s * dth * dpsi])
    ddpsi, ddphi = np.linalg.solve(m, rhs2)
    ddth = (A * dpsi**2 * s * c - C * (dphi + dpsi * c) * dpsi * s + MASS * G * L_CM * s) / A
    return [dpsi, dth, dphi, ddpsi, ddth, ddphi]


def invariants(y):
    psi, th, phi, dpsi, dth, dphi = y.T
    c, s = np.cos(th), np.sin(th)
    p_phi = C * (dphi + dpsi * c)
    p_psi = A * dpsi * s * s + p_phi * c
    e = 0.5 * A * (dth**2 + dpsi**2 * s * s) + 0.5 * p_phi**2 / C + MASS * G * L_CM * c
    return e, p_psi, p_phi


def nutation_period(y0):
    e, p_psi, p_phi = (float(v) for v in invariants(np.array([y0])))
    a = 2.0 * MASS * G * L_CM / A
    # u'^2 = (1 - u^2)(2/A)(e - p_phi^2/(2C) - m g l u) - (p_psi - p_phi u)^2 / A^2
    e1 = e - 0.5 * p_phi**2 / C
    poly = np.polysub(np.polymul([-1.0, 0.0, 1.0], [-a, 2.0 * e1 / A]),
                      np.polymul([-p_phi / A, p_psi / A], [-p_phi / A, p_psi / A]))
    u1, u2, u3 = np.sort(np.roots(poly).real)
    return 4.0 * ellipk((u2 - u1) / (u3 - u1)) / np.sqrt(a * (u3 - u1)), (u1, u2, u3)


def rotation(psi, th, phi):
    return ic.rot_z(psi) @ ic.rot_x(th) @ ic.rot_z(phi)


def columns(y):
    mats = [rotation(*row[:3]) for row in y]
    q = ic.continuous_quaternions(mats)
    cm = np.array([r @ [0.0, 0.0, L_CM] for r in mats])
    tip = np.array([r @ [0.0, 0.0, L_CM + L_TIP] for r in mats])
    w = np.array([row[3] * np.array([0.0, 0.0, 1.0])
                  + row[4] * (ic.rot_z(row[0]) @ [1.0, 0.0, 0.0]) + row[5] * (r @ [0.0, 0.0, 1.0])
                  for row, r in zip(y, mats)])
    cols = {}
    for k, ax in enumerate("xyz"):
        cols[f"top.{ax}"] = cm[:, k]
    for k, name in enumerate(("qw", "qx", "qy", "qz")):
        cols[f"top.{name}"] = q[:, k]
    for k, ax in enumerate("xyz"):
        cols[f"top.w{ax}"] = w[:, k]
    for k, ax in enumerate("xyz"):
        cols[f"top.tip.{ax}"] = tip[:, k]
    return cols


def lowest_point(_t, y):
    return y[4]


def compute(t_end=T_END):
    t = np.linspace(0.0, t_end, int(round(t_end / T_END * STEPS)) + 1)
    y0 = [0.0, THETA0, 0.0, 0.0, 0.0, SPIN]
    y, sol = ic.integrate(rhs, y0, t, events=lowest_point)
    e, p_psi, p_phi = invariants(y)
    period, roots = nutation_period(y0)
    # theta' = 0 at theta0 (u2, the top's highest) and at the lowest point (u1): every second
    # event after t = 0 closes one nutation period.
    ev = sol.t_events[0][sol.t_events[0] > 1e-9]
    periods = np.diff(np.concatenate([[0.0], ev[1::2]]))
    scale_p = C * SPIN
    checks = [
        ("energy drift / (C spin^2 / 2)", ic.relative_drift(e, 0.5 * C * SPIN**2), 1e-10,
         "conserved; 100 rtol"),
        ("p_psi drift / (C spin)", ic.relative_drift(p_psi, scale_p), 1e-10, "conserved; 100 rtol"),
        ("p_phi drift / (C spin)", ic.relative_drift(p_phi, scale_p), 1e-10, "conserved; 100 rtol"),
        ("max |nutation period - 4K/sqrt(...)| / period", np.max(np.abs(periods - period)) / period,
         1e-9, "event location on a flat extremum of theta: 1000 rtol"),
        ("max |theta at the turning points - arccos(u1 or u2)| (rad)",
         np.max(np.abs(np.cos(sol.y_events[0][sol.t_events[0] > 1e-9][:, 1])
                       - np.where(np.arange(len(ev)) % 2 == 0, roots[0], roots[1]))), 1e-10,
         "cos theta at theta' = 0 against the cubic's roots: 100 rtol"),
    ]
    title = (f"heavy top: {len(t)} rows to {t_end} s, nutation period {period:.12f} s, "
             f"theta in [{np.arccos(roots[1]):.6f}, {np.arccos(roots[0]):.6f}], "
             f"{len(periods)} periods timed")
    return t, columns(y), checks, title


def main(out_dir=ic.HERE):
    t, cols, checks, title = compute()
    ic.write_csv("heavy_top_reference.csv", t, cols, out_dir)
    return ic.report(title, checks)


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
