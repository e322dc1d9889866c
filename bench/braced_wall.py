#!/usr/bin/python3
"""Generate the braced wall of issue 47 under El Centro: the start of a stiff run (item 4).

A 2D lattice of nx x ny nodes (bench/mesh_lattice.py's cell: edges and both diagonals, unit
cells, ny layers high), its bottom layer clamped and a rigid floor in every tenth layer above
it (horizontal DOFs of each node tied to the floor's first node), lumped mass `mass` per DOF,
bars of axial stiffness EA, Rayleigh damping of `ratio` at the lowest natural frequency and at
`spread` times it, and the El Centro record (models/scenes/data/el_centro_1940_ns.csv) as the
load pattern -M r a_g(t), r = 1 on the horizontal DOFs (ground motion along x).

Writes into OUT the Matrix Market files M.mtx, K.mtx, A.mtx, f.mtx, the record (el_centro.csv),
  klu.toml      scheme elimination, [solve] newton = "full" (KLU on IDA's Jacobian)
  cholmod.toml  scheme elimination, newton = "condensed", linear_solver = "cholmod"
  ggl.toml      scheme GGL (multipliers for every row), KLU
  wall.json     sizes and the frequencies the damping was fitted to

  /usr/bin/python3 bench/braced_wall.py --nx 100 --ny 100 --t-end 0.1 --out bench/out/wall-100
  build/condyn run bench/out/wall-100/cholmod.toml --out /tmp/wall.csv
"""
import argparse
import json
import os
import shutil
import sys

import numpy as np
import scipy.io
import scipy.sparse as sp
import scipy.sparse.linalg as sla

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import mesh_lattice  # noqa: E402

RECORD = os.path.join(os.path.dirname(HERE), "models", "scenes", "data", "el_centro_1940_ns.csv")


def lowest_frequency(M, K, A, supports):
    """The lowest natural frequency (rad/s) of the wall with its bottom clamped (ties left out:
    they stiffen the floors, not the wall's sway)."""
    clamped = A[:supports].indices
    free = np.setdiff1d(np.arange(K.shape[0]), clamped)
    Kf = K[free][:, free].tocsc()
    Mf = M[free][:, free].tocsc()
    w2 = sla.eigsh(Kf, k=1, M=Mf, sigma=0.0, which="LM", return_eigenvectors=False)
    return float(np.sqrt(w2.min()))


def scene(args, solver_lines, watch):
    dofs = ", ".join(f'"u{d + 1}"' for d in watch)
    velocity = "" if args.atol_velocity is None else f"atol_velocity = {args.atol_velocity!r}\n"
    return (
        f'name = "Braced wall {args.nx} x {args.ny} nodes under El Centro (bench/braced_wall.py)"\n\n'
        '[model]\ntype = "matrix"\nmass = { file = "M.mtx" }\nstiffness = { file = "K.mtx" }\n'
        f"damping = {{ rayleigh = [{args.a0!r}, {args.a1!r}] }}\n\n"
        '[[constraint_block]]\nfile = "A.mtx"\nname = "c"\n\n'
        '[[load]]\npattern = { file = "f.mtx" }\n'
        'value = { type = "table", file = "el_centro.csv", column = "acceleration_g", '
        "scale = 9.81 }\n\n"
        f"[solve]\nt_end = {args.t_end!r}\noutput_step = {args.output_step!r}\n{solver_lines}"
        f"rtol = {args.rtol!r}\natol = {args.atol!r}\n{velocity}\n"
        f'[output]\nquantities = ["displacement"]\ndofs = [{dofs}]\n'
    )


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--nx", type=int, default=100, help="nodes per layer (default 100)")
    p.add_argument("--ny", type=int, default=100, help="layers (default 100)")
    p.add_argument("--out", default="bench/out/wall", help="output folder")
    p.add_argument("--ea", type=float, default=1.0e9, help="axial stiffness EA of every bar (N)")
    p.add_argument("--mass", type=float, default=100.0, help="lumped mass per DOF (kg)")
    p.add_argument("--ratio", type=float, default=0.05, help="damping ratio (default 0.05)")
    p.add_argument("--spread", type=float, default=10.0,
                   help="second damped frequency over the lowest (default 10)")
    p.add_argument("--t-end", type=float, default=5.0)
    p.add_argument("--output-step", type=float, default=0.01)
    p.add_argument("--rtol", type=float, default=1e-6)
    p.add_argument("--atol", type=float, default=1e-8)
    p.add_argument("--atol-velocity", type=float, default=None,
                   help="[solve] atol_velocity (default: derived); the derived one depends on "
                        "t_end, so a short run measuring a long run's start sets the long run's")
    args = p.parse_args(argv)

    shape = (args.nx, args.ny)
    mi, mj, index = mesh_lattice.members(shape)
    xy = mesh_lattice.coordinates(shape)
    n = 2 * xy.shape[0]
    K = mesh_lattice.stiffness(xy, mi, mj, args.ea, n)
    M = sp.identity(n, format="csr") * args.mass
    A, supports, ties = mesh_lattice.constraints(index, n)
    w1 = lowest_frequency(M, K, A.tocsr(), supports)
    w2 = args.spread * w1
    # C = a0 M + a1 K with ratio z at w1 and w2: z = a0 / (2 w) + a1 w / 2 at both.
    args.a1 = 2.0 * args.ratio / (w1 + w2)
    args.a0 = args.a1 * w1 * w2
    ux = 2 * np.arange(xy.shape[0])
    f = sp.coo_matrix((np.full(ux.size, -args.mass), (ux, np.zeros_like(ux))), shape=(n, 1))

    os.makedirs(args.out, exist_ok=True)
    path = lambda name: os.path.join(args.out, name)  # noqa: E731
    scipy.io.mmwrite(path("M.mtx"), M, symmetry="symmetric")
    scipy.io.mmwrite(path("K.mtx"), K, symmetry="symmetric")
    scipy.io.mmwrite(path("A.mtx"), A)
    scipy.io.mmwrite(path("f.mtx"), f)
    shutil.copyfile(RECORD, path("el_centro.csv"))
    top = index[..., -1].ravel()
    watch = [2 * top[0], 2 * top[-1], 2 * top[-1] + 1]
    variants = {
        "klu": 'scheme = "elimination"\nnewton = "full"\n',
        "cholmod": 'scheme = "elimination"\nnewton = "condensed"\nlinear_solver = "cholmod"\n',
        "ggl": 'scheme = "ggl"\nconstraints = "multipliers"\n',
    }
    for name, lines in variants.items():
        with open(path(f"{name}.toml"), "w") as fh:
            fh.write(scene(args, lines, watch))
    info = {"shape": list(shape), "n": n, "m": int(A.shape[0]), "supports": supports,
            "ties": ties, "members": int(mi.size), "omega_1": w1, "rayleigh": [args.a0, args.a1],
            "t_end": args.t_end, "rtol": args.rtol, "atol": args.atol}
    with open(path("wall.json"), "w") as fh:
        json.dump(info, fh, indent=1)
    print(json.dumps(info))
    return 0


if __name__ == "__main__":
    sys.exit(main())
