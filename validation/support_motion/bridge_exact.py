"""The two-support bridge of models/scenes/two_support_bridge.toml: its support records and its
exact response, computed independently of condyn (numpy and scipy only).

The bridge is a chain of three masses (1, 1.5, 1) on four springs of 100 between two massless
support DOFs sL and sR, with Rayleigh damping C = 0.2 M + 0.001 K. The supports follow

    g_L(t) = 0.02 (1 - cos 3t),    g_R(t) = 0.015 sin 2t - 0.0075 sin 4t,

both at rest at t = 0 (g = g' = 0), so the masses start at rest. With q the masses' displacements,
M q'' + C_qq q' + K_qq q = -K_qs g - C_qs g' (C_qs = 0.001 K_qs, the supports being massless): a
sum of a constant and harmonics, solved mode by mode in closed form (the particular solution of
each term plus the damped free response that starts the mode at rest). The reactions at the
supports are the forces they apply, f_s = K_sq q + K_ss g + C_sq q' + C_ss g'.

Writes models/scenes/data/bridge_left.csv and bridge_right.csv (t, d, v, a: the records sampled
every 0.01 s to 17 digits) and bridge_exact.csv (t, every DOF and the support reactions, at the
scene's output times). Run from the repository's root:
    /usr/bin/python3 validation/support_motion/bridge_exact.py
"""

import pathlib

import numpy as np
import scipy.linalg

T_END, OUTPUT_STEP, SAMPLE = 5.0, 0.05, 0.01
A0, A1 = 0.2, 0.001
DOFS = ["sL", "u1", "u2", "u3", "sR"]
MASS = np.diag([0.0, 1.0, 1.5, 1.0, 0.0])
K = 100.0 * (np.diag([1.0, 2.0, 2.0, 2.0, 1.0]) - np.eye(5, k=1) - np.eye(5, k=-1))
C = A0 * MASS + A1 * K
FREE, SUPPORTS = [1, 2, 3], [0, 4]

# Each support's motion as terms (kind, amplitude, omega): "const" c, "cos" a cos(wt), "sin"
# a sin(wt).
LEFT = [("const", 0.02, 0.0), ("cos", -0.02, 3.0)]
RIGHT = [("sin", 0.015, 2.0), ("sin", -0.0075, 4.0)]


def motion(terms, t, order):
    """d^order/dt^order of a support's motion at the times t."""
    out = np.zeros_like(t)
    for kind, a, w in terms:
        if kind == "const":
            out += a if order == 0 else 0.0
        else:
            phase = 0.0 if kind == "sin" else np.pi / 2  # cos x = sin(x + pi/2)
            out += a * w**order * np.sin(w * t + phase + order * np.pi / 2)
    return out


def complex_terms(terms):
    """The motion as sum Re(c e^{i w t}) over (c, w): a sin wt = Re(-i a e^{iwt})."""
    return [(complex(a) if kind in ("const", "cos") else -1j * a, w) for kind, a, w in terms]


def response(t):
    """The masses' q, q', q'' (3 x nt) in closed form, mode by mode."""
    m, k, c = MASS[np.ix_(FREE, FREE)], K[np.ix_(FREE, FREE)], C[np.ix_(FREE, FREE)]
    w2, phi = scipy.linalg.eigh(k, m)  # phi^T m phi = I
    omega = np.sqrt(w2)
    zeta = np.array([phi[:, j] @ c @ phi[:, j] for j in range(3)]) / (2 * omega)
    q, qd, qdd = np.zeros((3, t.size)), np.zeros((3, t.size)), np.zeros((3, t.size))
    for s, terms in zip(SUPPORTS, (LEFT, RIGHT)):
        k_qs, c_qs = K[FREE, s], C[FREE, s]
        for amp, w in complex_terms(terms):
            # force -(k_qs + i w c_qs) amp e^{iwt} on the masses
            force = -(k_qs + 1j * w * c_qs) * amp
            for j in range(3):
                f = phi[:, j] @ force
                h = f / (omega[j] ** 2 - w**2 + 2j * zeta[j] * omega[j] * w)
                eta_p = np.real(h * np.exp(1j * w * t))
                etad_p = np.real(1j * w * h * np.exp(1j * w * t))
                # the free response that cancels the particular one's start
                a_, wd = -np.real(h), omega[j] * np.sqrt(1 - zeta[j] ** 2)
                b_ = (-np.real(1j * w * h) + zeta[j] * omega[j] * a_) / wd
                decay = np.exp(-zeta[j] * omega[j] * t)
                eta_h = decay * (a_ * np.cos(wd * t) + b_ * np.sin(wd * t))
                etad_h = -zeta[j] * omega[j] * eta_h + decay * wd * (
                    -a_ * np.sin(wd * t) + b_ * np.cos(wd * t))
                # the free response solves its homogeneous equation
                etadd_h = -2 * zeta[j] * omega[j] * etad_h - omega[j] ** 2 * eta_h
                etadd_p = np.real(-(w**2) * h * np.exp(1j * w * t))
                q += np.outer(phi[:, j], eta_p + eta_h)
                qd += np.outer(phi[:, j], etad_p + etad_h)
                qdd += np.outer(phi[:, j], etadd_p + etadd_h)
    return q, qd, qdd


def write_csv(path, header, columns):
    with open(path, "w", encoding="utf-8") as f:
        f.write(",".join(header) + "\n")
        for row in np.column_stack(columns):
            f.write(",".join(repr(float(x)) for x in row) + "\n")


def main():
    data = pathlib.Path(__file__).resolve().parents[2] / "models" / "scenes" / "data"
    ts = np.linspace(0.0, T_END, int(round(T_END / SAMPLE)) + 1)
    for name, terms in (("bridge_left.csv", LEFT), ("bridge_right.csv", RIGHT)):
        write_csv(data / name, ["t", "d", "v", "a"], [ts] + [motion(terms, ts, o) for o in range(3)])
    t = np.linspace(0.0, T_END, int(round(T_END / OUTPUT_STEP)) + 1)
    q, qd, qdd = response(t)
    u, v = np.zeros((5, t.size)), np.zeros((5, t.size))
    u[FREE], v[FREE] = q, qd
    for s, terms in zip(SUPPORTS, (LEFT, RIGHT)):
        u[s], v[s] = motion(terms, t, 0), motion(terms, t, 1)
    reactions = [K[s] @ u + C[s] @ v for s in SUPPORTS]  # M u'' = 0 at the supports
    # Self-checks: the masses start at rest, and their equations of motion hold at every output
    # time to roundoff of the forces' size (K u of order 100 x 0.04).
    assert np.abs(q[:, 0]).max() < 1e-15 and np.abs(qd[:, 0]).max() < 1e-15
    residual = MASS[FREE] @ np.vstack([np.zeros(t.size), qdd, np.zeros(t.size)]) + C[FREE] @ v + K[FREE] @ u
    assert np.abs(residual).max() < 1e-12, np.abs(residual).max()
    write_csv(data / "bridge_exact.csv",
              ["t"] + DOFS + ["reaction_sL", "reaction_sR"], [t] + list(u) + reactions)


if __name__ == "__main__":
    main()
