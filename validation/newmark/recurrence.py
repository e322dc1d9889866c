"""Newmark's method written out in numpy, independently of condyn, for the El Centro shear frame
(models/scenes/shear_frame_el_centro.toml): what a structural engineer would write to check that
`condyn run --scheme newmark --step h` reproduces another program's Newmark run (issue 45, "Done
when"; docs/validation.md "Newmark against a numpy recurrence").

The scene's linear model M ü + C u̇ + K u + Aᵀλ = f(t), A u = 0, is read from its TOML (matrix
model, Rayleigh damping from two (frequency, ratio) pairs, a tabulated ground acceleration with
its influence vector, homogeneous constraint rows), and stepped in the acceleration form of
Newmark (1959) found in the textbooks (Chopra, Dynamics of Structures, §5.4; Hughes, The Finite
Element Method, §9.1), the constraints held at every step:

    predictors  ũ = u_n + h v_n + h² (½ − β) a_n,   ṽ = v_n + h (1 − γ) a_n
    solve       [M + γ h C + β h² K   Aᵀ] [a_{n+1}]   [f_{n+1} − C ṽ − K ũ]
                [A                     0] [λ_{n+1}] = [−A ũ / (β h²)       ]
    correctors  u_{n+1} = ũ + β h² a_{n+1},   v_{n+1} = ṽ + γ h a_{n+1}

started at rest with a_0, λ_0 from [M Aᵀ; A 0] [a_0; λ_0] = [f(0); 0]. The reactions are
f_con = −Aᵀλ with λ at each output row from the constraints at acceleration level at the row's u
and v, as condyn reports them (the step's own λ carries the undamped step-to-step oscillation of
index 3's constraint modes under average acceleration: docs/validation.md). condyn solves the
same step in displacement form with a scaled Newton matrix (docs/schemes.md), so the two agree to
roundoff, not bit for bit.

    /usr/bin/python3 validation/newmark/recurrence.py --condyn build/condyn --step 0.01

runs both and prints the largest differences. Debian's /usr/bin/python3 (numpy).
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import tomllib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCENE = os.path.join(ROOT, "models", "scenes", "shear_frame_el_centro.toml")


class ShearFrame:
    """The scene's matrices and load: M, C, K (n x n), A (m x n), the ground acceleration's
    samples (times, values already scaled) and the influence vector ι, so that
    f(t) = −M ι a_g(t), a_g linear between samples."""

    def __init__(self, path=SCENE):
        with open(path, "rb") as f:
            scene = tomllib.load(f)
        model = scene["model"]
        if model.get("type") != "matrix":
            raise ValueError(f"{path}: only a matrix model is written out here")
        self.dofs = list(model["dofs"])
        self.M = np.array(model["mass"], dtype=float)
        self.K = np.array(model["stiffness"], dtype=float)
        self.C = rayleigh(self.M, self.K, model["damping"]["rayleigh"])
        index = {name: i for i, name in enumerate(self.dofs)}
        rows = scene.get("constraint", [])
        self.A = np.zeros((len(rows), len(self.dofs)))
        for r, row in enumerate(rows):
            if row.get("value", 0.0) != 0.0:
                raise ValueError(f"{path}: constraint {r}: only homogeneous rows A u = 0")
            for name, coefficient in row["terms"].items():
                self.A[r, index[name]] = coefficient
        self.constraint_names = [row.get("name", f"c{r}") for r, row in enumerate(rows)]
        ground = scene["ground_motion"]
        table = ground["acceleration"]
        if table.get("type") != "table":
            raise ValueError(f"{path}: only a tabulated ground acceleration")
        data = read_record(os.path.join(os.path.dirname(path), table["file"]))
        self.record_t = data[:, 0]
        self.record_a = table.get("scale", 1.0) * data[:, 1]
        self.iota = np.zeros(len(self.dofs))
        for name, value in ground["influence"].items():
            if name not in index:  # a pattern or a file: this second program reads names only
                raise ValueError(f"{path}: ground_motion.influence: only DOF by DOF (got {name!r})")
            self.iota[index[name]] = value
        self.solve = scene["solve"]

    def force(self, t):
        """f(t) = −M ι a_g(t), a_g interpolated linearly between the record's samples."""
        return -self.M @ self.iota * np.interp(t, self.record_t, self.record_a)


def read_record(path):
    """The record's (t, value) rows: comment lines (#) and the header line skipped."""
    with open(path) as f:
        lines = [l for l in f if l.strip() and not l.startswith("#")]
    return np.array([[float(x) for x in l.split(",")] for l in lines[1:]])


def rayleigh(M, K, pairs):
    """C = a0 M + a1 K with damping ratio z_i at frequency f_i (cycles per second), the textbook
    formulas (Chopra §11.4): a0 = 2 ω1 ω2 (z1 ω2 − z2 ω1)/(ω2² − ω1²),
    a1 = 2 (z2 ω2 − z1 ω1)/(ω2² − ω1²)."""
    (f1, f2), (z1, z2) = pairs["frequencies"], pairs["ratios"]
    w1, w2 = 2.0 * math.pi * f1, 2.0 * math.pi * f2
    a0 = 2.0 * w1 * w2 * (z1 * w2 - z2 * w1) / (w2 ** 2 - w1 ** 2)
    a1 = 2.0 * (z2 * w2 - z1 * w1) / (w2 ** 2 - w1 ** 2)
    return a0 * M + a1 * K


def newmark(frame, h, steps, beta=0.25, gamma=0.5):
    """`steps` steps of h from rest at t = 0. Returns t (steps + 1) and u, v, a (steps + 1, n),
    λ (steps + 1, m)."""
    M, C, K, A = frame.M, frame.C, frame.K, frame.A
    n, m = M.shape[0], A.shape[0]
    t = h * np.arange(steps + 1)
    u, v, a = (np.zeros((steps + 1, n)) for _ in range(3))
    lam = np.zeros((steps + 1, m))

    def kkt(block):
        return np.block([[block, A.T], [A, np.zeros((m, m))]])

    start = np.linalg.solve(kkt(M), np.concatenate([frame.force(0.0), np.zeros(m)]))
    a[0], lam[0] = start[:n], start[n:]
    step_matrix = kkt(M + gamma * h * C + beta * h * h * K)
    for k in range(steps):
        u_pred = u[k] + h * v[k] + h * h * (0.5 - beta) * a[k]
        v_pred = v[k] + h * (1.0 - gamma) * a[k]
        rhs = np.concatenate([frame.force(t[k + 1]) - C @ v_pred - K @ u_pred,
                              -A @ u_pred / (beta * h * h)])
        x = np.linalg.solve(step_matrix, rhs)
        a[k + 1], lam[k + 1] = x[:n], x[n:]
        u[k + 1] = u_pred + beta * h * h * a[k + 1]
        v[k + 1] = v_pred + gamma * h * a[k + 1]
    return t, u, v, a, lam


def reactions(frame, lam):
    """f_con = −Aᵀλ at every row of λ (rows x n)."""
    return -lam @ frame.A


def row_multipliers(frame, t, u, v):
    """λ at each row (t_k, u_k, v_k) from the constraints at acceleration level, what condyn
    reports at its output rows under every scheme: [M Aᵀ; A 0] [ü; λ] = [f(t) − C v − K u; 0]
    (the rows A u = 0 are constant, so A ü = 0). Returns rows x m."""
    n, m = frame.M.shape[0], frame.A.shape[0]
    kkt = np.block([[frame.M, frame.A.T], [frame.A, np.zeros((m, m))]])
    lam = np.zeros((len(t), m))
    for k in range(len(t)):
        rhs = np.concatenate([frame.force(t[k]) - frame.C @ v[k] - frame.K @ u[k], np.zeros(m)])
        lam[k] = np.linalg.solve(kkt, rhs)[n:]
    return lam


def condyn_run(condyn, frame, h, work_dir):
    """The scene under `condyn run --scheme newmark --step h`, an output at every step, every
    DOF's displacement, velocity and reaction. Returns the CSV's columns (name -> array)."""
    with open(SCENE) as f:
        text = f.read()
    record = os.path.join(ROOT, "models", "scenes", "data", "el_centro_1940_ns.csv")
    text = text.replace('file = "data/el_centro_1940_ns.csv"', f'file = "{record}"')
    head, _, _ = text.partition("[output]")
    head = head.replace("output_step = 0.02", f"output_step = {h!r}")
    scene = os.path.join(work_dir, "frame.toml")
    with open(scene, "w") as f:
        f.write(head + '[output]\nquantities = ["displacement", "velocity", "reaction"]\n')
    out = os.path.join(work_dir, "frame.csv")
    subprocess.run([condyn, "run", scene, "--scheme", "newmark", "--step", repr(h), "--out", out],
                   check=True, capture_output=True, text=True)
    with open(out) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(out, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, j] for j, name in enumerate(header)}


def differences(frame, columns, h):
    """The recurrence against condyn's columns at the same times: the largest |difference| of u,
    v and f_con, each with its peak, and the step count."""
    steps = len(columns["t"]) - 1
    t, u, v, _, _ = newmark(frame, h, steps)
    if not np.allclose(columns["t"], t, rtol=0, atol=1e-9):
        raise ValueError("condyn's output times are not the step grid")
    f_con = reactions(frame, row_multipliers(frame, t, u, v))
    out = {"steps": steps}
    for what, ours, prefix in (("u", u, ""), ("v", v, "vel_"), ("f_con", f_con, "reaction_")):
        theirs = np.stack([columns[prefix + name] for name in frame.dofs], axis=1)
        out[what] = (float(np.max(np.abs(theirs - ours))), float(np.max(np.abs(ours))))
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--condyn", default=os.path.join(ROOT, "build", "condyn"))
    parser.add_argument("--step", type=float, default=0.01)
    args = parser.parse_args(argv)
    frame = ShearFrame()
    with tempfile.TemporaryDirectory() as work_dir:
        d = differences(frame, condyn_run(args.condyn, frame, args.step, work_dir), args.step)
    print(f"{d['steps']} steps of h = {args.step}")
    for what in ("u", "v", "f_con"):
        diff, peak = d[what]
        print(f"{what}: max |condyn - numpy| = {diff:.3e}, peak {peak:.3e}, "
              f"ratio {diff / peak:.3e} = {diff / peak / np.finfo(float).eps:.1f} eps")
    return 0


if __name__ == "__main__":
    sys.exit(main())
