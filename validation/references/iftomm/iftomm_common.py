"""Shared helpers of the IFToMM reference scripts (validation/references/iftomm/README.md).

Each reference_*.py integrates a mechanism in minimal coordinates with SciPy at RTOL, samples it
at the benchmark's output times and writes a CSV whose columns are named as condyn's mechanism
outputs (`<body>.x`, `<body>.angle`, `<body>.<point>.x`, ...), then prints its self-checks.
A self-check is a figure, its bound and the reason for the bound; `report` prints them and
returns whether all hold, so that `main()` can exit non-zero and the pytest can assert it.
"""
import csv
import os

import numpy as np
from scipy.integrate import solve_ivp

RTOL = 1e-12   # the accuracy for every reference
ATOL = 1e-12   # absolute floor: coordinates are O(1) in every benchmark
HERE = os.path.dirname(os.path.abspath(__file__))


def integrate(rhs, y0, t_out, method="DOP853", rtol=RTOL, atol=ATOL, **kwargs):
    """solve_ivp from t_out[0] to t_out[-1], returning the solution at t_out (rows) and the
    solver's result; raises when the integration fails."""
    sol = solve_ivp(rhs, (t_out[0], t_out[-1]), y0, method=method, t_eval=t_out, rtol=rtol,
                    atol=atol, **kwargs)
    if not sol.success:
        raise RuntimeError(f"integration failed: {sol.message}")
    return sol.y.T, sol


def write_csv(name, t, columns, out_dir=HERE):
    """Writes `name` (in out_dir) with the column t first, then `columns` (an ordered dict of
    name -> array of len(t)), each number in its shortest exact form (repr)."""
    path = os.path.join(out_dir, name)
    names = list(columns)
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["t"] + names)
        for i, ti in enumerate(t):
            w.writerow([repr(float(ti))] + [repr(float(columns[n][i])) for n in names])
    return path


def read_csv(path):
    """The columns of a reference CSV as a dict of arrays (t included)."""
    with open(path) as f:
        rows = list(csv.reader(f))
    data = np.array(rows[1:], dtype=float)
    return {name: data[:, j] for j, name in enumerate(rows[0])}


def report(title, checks):
    """Prints `title` and each check (label, figure, bound, reason); True when every figure is
    within its bound."""
    print(title)
    ok = True
    for label, figure, bound, reason in checks:
        passed = bool(np.isfinite(figure) and abs(figure) <= bound)
        ok &= passed
        print(f"  {'PASS' if passed else 'FAIL'} {label}: {figure:.3e} (bound {bound:.0e}: {reason})")
    return ok


def relative_drift(values, scale):
    """max |values - values[0]| / scale: the drift of a conserved quantity."""
    values = np.asarray(values)
    return float(np.max(np.abs(values - values[0])) / scale)


def quaternion_from_matrix(r):
    """Hamilton's unit quaternion [w, x, y, z] of a rotation matrix (Shepperd's method)."""
    tr = np.trace(r)
    cand = [tr, r[0, 0], r[1, 1], r[2, 2]]
    k = int(np.argmax(cand))
    if k == 0:
        s = 2.0 * np.sqrt(1.0 + tr)
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    elif k == 1:
        s = 2.0 * np.sqrt(1.0 + 2.0 * r[0, 0] - tr)
        q = [(r[2, 1] - r[1, 2]) / s, 0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s]
    elif k == 2:
        s = 2.0 * np.sqrt(1.0 + 2.0 * r[1, 1] - tr)
        q = [(r[0, 2] - r[2, 0]) / s, (r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s]
    else:
        s = 2.0 * np.sqrt(1.0 + 2.0 * r[2, 2] - tr)
        q = [(r[1, 0] - r[0, 1]) / s, (r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s]
    return np.array(q)


def continuous_quaternions(matrices):
    """Unit quaternions of a sequence of rotation matrices, the sign chosen so that qw > 0 at the
    first and each is continuous with the previous (the contract's convention for 3D output)."""
    qs = [quaternion_from_matrix(r) for r in matrices]
    if qs[0][0] < 0:
        qs[0] = -qs[0]
    for i in range(1, len(qs)):
        if np.dot(qs[i], qs[i - 1]) < 0:
            qs[i] = -qs[i]
    return np.array(qs)


def rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def box_inertia(mass, a, b, c):
    """Principal inertia [Ixx, Iyy, Izz] about the centre of a homogeneous box a x b x c."""
    return np.array([b * b + c * c, a * a + c * c, a * a + b * b]) * mass / 12.0


def pendulum_closed_form(t, theta0, w):
    """The pendulum theta'' = -w^2 sin theta released at rest from theta0 (|theta0| < pi),
    theta from the stable equilibrium: sin(theta/2) = k sn(K - w t | k^2), k = sin(theta0/2),
    and (1/2) cos(theta/2) theta' = -k w cn dn; Jacobi's argument reduced modulo the period 4K.
    Returns (theta, theta') at the times t."""
    from scipy.special import ellipj, ellipk
    k = np.sin(theta0 / 2.0)
    m = k * k
    quarter = ellipk(m)
    u = np.mod(quarter - w * np.asarray(t), 4.0 * quarter)
    sn, cn, dn, _ = ellipj(u, m)
    theta = 2.0 * np.arcsin(k * sn)
    return theta, -2.0 * k * w * cn * dn / np.cos(theta / 2.0)


def pendulum_period(theta0, w):
    """4 K(k^2) / w, k = sin(theta0/2): the period of pendulum_closed_form."""
    from scipy.special import ellipk
    return 4.0 * ellipk(np.sin(theta0 / 2.0) ** 2) / w
