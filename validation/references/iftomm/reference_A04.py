#!/usr/bin/python3
"""IFToMM A04, Bricard's mechanism, in one minimal coordinate with a Newton-solved closure.

Specification (http://lim.ii.udc.es/mbsbenchmark/dist/A04/A04_specification.xml, and as the
OpenSim reproduction builds it: github.com/RehabEngGroup/MBSbenchmarksInOpenSim,
src/A04-BricardsMechanism/): five links of 1 m and 1 kg closing a loop through the ground with
six revolute joints; gravity 9.81 along -y; released at rest; Gruebler's count gives 0 DOF, the
axes' arrangement gives 1 (the loop's six joint twists have rank 5). The start is the cube
corner: joints J1..J6 at (0,0,0), (1,0,0), (1,-1,0), (1,-1,1), (0,-1,1), (0,0,1) with axes y, z,
x, y, z, x; link k joins J_k to J_{k+1}, the ground closes J6 to J1. The links are homogeneous
bars 1 x 0.1 x 0.1 m (the OpenSim reproduction's square section of 0.1 m, which also keeps
every inertia tensor positive definite). 10 s in 400 output steps (an assumption: the OpenSim
reproduction reports 10 s; the specification's own figure is not in the sources found).

Coordinates: the six joint angles theta (0 at the cube corner) of the serial chain ground -> J1
-> link1 -> ... -> J6 -> ground; the closure g1 g2 ... g6 = I (product of exponentials) leaves
one DOF. q = theta1 is integrated; theta2..theta6 follow by Gauss-Newton on the closure at every
evaluation; theta' = u q', theta'' = u q'' + w q'^2 with S u = 0 and S w = -sum_k
[V_{k-1}, xi_k] u_k (S the current joint twists, u1 = 1, w1 = 0: the closure at velocity and
acceleration level). q'' follows from Kane's equation: the sum over the links of the partial
velocities (for q) dotted into m (a_c - g) and I alpha + omega x I omega is zero, with every
acceleration from the recursive spatial kinematics: exact, no difference quotient.
Self-checks: energy conserved; the closure residual; the velocity closure.

Body names (models/scenes/iftomm/A04_bricard.toml): link1..link5, each with points at its
joints (link1: J1, J2; link2: J2, J3; ...; link5: J5, J6), body frame = global at t = 0.
Columns: <link>.x/y/z, <link>.qw/qx/qy/qz, and the joint points J2..J5 on the links
(link2.J3.x... as the scene's [output] points lists them).
Run: /usr/bin/python3 validation/references/iftomm/reference_A04.py  (writes A04_reference.csv)
"""
import sys

import numpy as np

import iftomm_common as ic

MASS, LENGTH, SECTION, G = 1.0, 1.0, 0.1, 9.81
GRAVITY = np.array([0.0, -G, 0.0])
JOINTS = np.array([[0, 0, 0], [1, 0, 0], [1, -1, 0], [1, -1, 1], [0, -1, 1], [0, 0, 1]], float)
AXES = np.array([[0, 1, 0], [0, 0, 1], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 0, 0]], float)
T_END, STEPS = 10.0, 400


def link_inertia(k):
    """Principal inertia of link k (0-based, from J_k to J_{k+1}) in the global frame at t = 0."""
    along = np.argmax(np.abs(JOINTS[k + 1] - JOINTS[k]))
    dims = [SECTION] * 3
    dims[along] = LENGTH
    return np.diag(ic.box_inertia(MASS, *dims))


CENTRES = 0.5 * (JOINTS[:5] + JOINTS[1:])
INERTIAS = [link_inertia(k) for k in range(5)]


def rodrigues(axis, angle):
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


def poses(theta):
    """(R_k, t_k) of the chain's links 1..6 (link 6 = ground again): x = R_k x0 + t_k."""
    r, t = np.eye(3), np.zeros(3)
    out = []
    for p, a, th in zip(JOINTS, AXES, theta):
        rj = rodrigues(a, th)
        tj = p - rj @ p
        r, t = r @ rj, r @ tj + t
        out.append((r, t))
    return out


def twists(theta, pose=None):
    """The current joint twists xi_k = (omega, v) as the columns of S (6 x 6): joint k's axis
    is carried by link k-1."""
    pose = pose or poses(theta)
    s = np.zeros((6, 6))
    for k in range(6):
        r, t = (np.eye(3), np.zeros(3)) if k == 0 else pose[k - 1]
        w, p = r @ AXES[k], r @ JOINTS[k] + t
        s[:3, k], s[3:, k] = w, np.cross(p, w)
    return s


def bracket(a, b):
    return np.concatenate([np.cross(a[:3], b[:3]), np.cross(a[:3], b[3:]) - np.cross(b[:3], a[3:])])


def link_motion(s, theta_dot, theta_ddot):
    """Spatial twists V_k and their rates A_k of links 1..6 (recursive)."""
    v, a = np.zeros(6), np.zeros(6)
    vs, acc = [], []
    for k in range(6):
        a = a + s[:, k] * theta_ddot[k] + bracket(v, s[:, k]) * theta_dot[k]
        v = v + s[:, k] * theta_dot[k]
        vs.append(v)
        acc.append(a)
    return vs, acc


def close(theta1, guess):
    """theta2..theta6 closing the loop (Gauss-Newton from guess), to roundoff."""
    theta = np.array(guess, dtype=float)
    theta[0] = theta1
    for _ in range(50):
        r, t = poses(theta)[5]
        err = np.concatenate([0.5 * np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0],
                                              r[1, 0] - r[0, 1]]), t])
        if np.max(np.abs(err)) < 1e-15:
            return theta
        delta = np.linalg.lstsq(twists(theta)[:, 1:], -err, rcond=None)[0]
        theta[1:] += delta
    raise RuntimeError(f"closure did not converge at theta1 = {theta1}: {err}")


def null_rates(theta):
    """u (S u = 0, u1 = 1) and w (S w = -b(u), w1 = 0)."""
    s = twists(theta)
    u = np.concatenate([[1.0], np.linalg.lstsq(s[:, 1:], -s[:, 0], rcond=None)[0]])
    _, acc = link_motion(s, u, np.zeros(6))
    w = np.concatenate([[0.0], np.linalg.lstsq(s[:, 1:], -acc[5], rcond=None)[0]])
    return s, u, w


def kane_residual(theta, s, u, w, q_dot, q_ddot):
    """Sum over links 1..5 of the partial velocities dotted into the inertia and gravity forces."""
    pose = poses(theta)
    vel, acc = link_motion(s, u * q_dot, u * q_ddot + w * q_dot**2)
    part, _ = link_motion(s, u, np.zeros(6))
    total = 0.0
    for k in range(5):
        r, t = pose[k]
        x = r @ CENTRES[k] + t
        i_w = r @ INERTIAS[k] @ r.T
        om, v = vel[k][:3], vel[k][3:]
        x_dot = v + np.cross(om, x)
        x_ddot = acc[k][3:] + np.cross(acc[k][:3], x) + np.cross(om, x_dot)
        om_u = part[k][:3]
        x_u = part[k][3:] + np.cross(om_u, x)
        total += MASS * x_u @ (x_ddot - GRAVITY)
        total += om_u @ (i_w @ acc[k][:3] + np.cross(om, i_w @ om))
    return total


class Bricard:
    """The one-DOF ODE in (q, q'), keeping the last closed configuration as Newton's guess."""

    def __init__(self):
        self.theta = np.zeros(6)

    def rhs(self, _t, y):
        self.theta = close(y[0], self.theta)
        s, u, w = null_rates(self.theta)
        f0 = kane_residual(self.theta, s, u, w, y[1], 0.0)
        f1 = kane_residual(self.theta, s, u, w, y[1], 1.0)
        return [y[1], -f0 / (f1 - f0)]

    def energy(self, theta, q_dot):
        s, u, _ = null_rates(theta)
        vel, _ = link_motion(s, u * q_dot, np.zeros(6))
        e = 0.0
        for k, (r, t) in enumerate(poses(theta)[:5]):
            x = r @ CENTRES[k] + t
            om = vel[k][:3]
            x_dot = vel[k][3:] + np.cross(om, x)
            e += 0.5 * MASS * x_dot @ x_dot + 0.5 * om @ (r @ INERTIAS[k] @ r.T) @ om
            e -= MASS * GRAVITY @ x
        return e


POINTS = {"link1": ("J1", "J2"), "link2": ("J2", "J3"), "link3": ("J3", "J4"),
          "link4": ("J4", "J5"), "link5": ("J5", "J6")}


def columns(thetas):
    pose = [poses(th)[:5] for th in thetas]
    cols = {}
    for k, name in enumerate(POINTS):
        rs = [p[k][0] for p in pose]
        xs = np.array([r @ CENTRES[k] + t for r, t in (p[k] for p in pose)])
        q = ic.continuous_quaternions(rs)
        for j, ax in enumerate("xyz"):
            cols[f"{name}.{ax}"] = xs[:, j]
        for j, qn in enumerate(("qw", "qx", "qy", "qz")):
            cols[f"{name}.{qn}"] = q[:, j]
        for jp in (k, k + 1):
            pts = np.array([r @ JOINTS[jp] + t for r, t in (p[k] for p in pose)])
            for j, ax in enumerate("xyz"):
                cols[f"{name}.J{jp + 1}.{ax}"] = pts[:, j]
    return cols


def compute(t_end=T_END):
    t = np.linspace(0.0, t_end, int(round(t_end / T_END * STEPS)) + 1)
    model = Bricard()
    y, _ = ic.integrate(model.rhs, [0.0, 0.0], t)
    thetas, guess = [], np.zeros(6)
    for q in y[:, 0]:
        guess = close(q, guess)
        thetas.append(guess.copy())
    e = np.array([model.energy(th, qd) for th, qd in zip(thetas, y[:, 1])])
    closure = max(np.max(np.abs(poses(th)[5][1])) + np.max(np.abs(poses(th)[5][0] - np.eye(3)))
                  for th in thetas)
    max_u = max(np.max(np.abs(null_rates(th)[1])) for th in thetas)
    ke_scale = 5.0 * MASS * G * LENGTH
    s0 = np.linalg.svd(twists(np.zeros(6)), compute_uv=False)
    checks = [
        ("energy drift / (5 m g L)", ic.relative_drift(e, ke_scale), 1e-10, "conserved; 100 rtol"),
        ("closure residual |g_6 - I| at the output times", closure, 1e-13, "Newton to roundoff"),
        ("6th singular value of S at t = 0 / the 5th", s0[5] / s0[4], 1e-14,
         "rank 5: one DOF (roundoff)"),
    ]
    title = (f"A04 Bricard: {len(t)} rows to {t_end} s, theta1 in [{y[:, 0].min():.6f}, "
             f"{y[:, 0].max():.6f}] rad, max |theta1'| {np.max(np.abs(y[:, 1])):.6f} rad/s, "
             f"max |u_i| {max_u:.4f}")
    return t, columns(thetas), checks, title


def main(out_dir=ic.HERE):
    t, cols, checks, title = compute()
    ic.write_csv("A04_reference.csv", t, cols, out_dir)
    return ic.report(title, checks)


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
