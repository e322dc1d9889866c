#!/usr/bin/python3
"""Generate a mesh lattice truss for the factorization benchmark (issue 47, item 2): a 2D square
lattice (a wall) or a 3D cubic lattice (a block), beside bench/lattice.py's five-node strip.

The strip is banded: any ordering factors it with little fill. A mesh is not: its factor grows as
N log N (2D) or N^(4/3) (3D) under nested dissection, and the ordering and the factorization
decide the time of a step. The lattices:
  2d  nx x ny nodes (nx = ny, rounded to the target DOF count), unit cells, every cell with its
      two edges and both diagonals (the strip's cell); DOFs ux, uy per node.
  3d  nx x ny x nz nodes (a cube), every cell with its edges, both diagonals of each face and its
      four body diagonals (13 bar directions per node); DOFs ux, uy, uz per node.
Lumped mass `mass` per DOF; bars of axial stiffness EA; the bottom layer (y = 0 in 2D, z = 0 in 3D)
clamped (single-freedom rows); in every tenth layer above it a rigid floor: the horizontal
displacements of each of its nodes tied to those of its first node (two-DOF rows, as the issue's
braced wall's floor ties); a step load -load on the vertical DOF of every free node. Node k
(1-based, first coordinate fastest) has DOFs numbered dim (k - 1) + 1 ... dim k (u1, u2, ... in
the scene).

Writes into OUT the Matrix Market files M.mtx, K.mtx, A.mtx, f.mtx (as bench/lattice.py), and
  klu.toml      scheme elimination, [solve] newton = "condensed", linear_solver = "klu"
  cholmod.toml  the same with linear_solver = "cholmod"
  mesh.json     sizes for bench/factorization_bench.py

  /usr/bin/python3 bench/mesh_lattice.py --dim 2 --dofs 1e4 --out bench/out/mesh2d-1e4
"""
import argparse
import itertools
import json
import os
import sys

import numpy as np
import scipy.io
import scipy.sparse as sp


def grid_shape(n_target, dim):
    """Nodes per side of a square (cube) with about n_target DOFs (at least 3 per side)."""
    side = max(3, int(round((n_target / dim) ** (1.0 / dim))))
    return (side,) * dim


def directions(dim):
    """Bar directions: one of each pair ±d of the offsets in {-1, 0, 1}^dim."""
    out = []
    for d in itertools.product((-1, 0, 1), repeat=dim):
        d = np.array(d)
        nonzero = d[d != 0]
        if nonzero.size and nonzero[-1] > 0:  # the last nonzero component positive: one of ±d
            out.append(d)
    return out


def members(shape):
    """Bars as (i, j) node index pairs, 0-based, first coordinate fastest."""
    dim = len(shape)
    index = np.arange(int(np.prod(shape))).reshape(shape[::-1]).transpose()  # index[x, y(, z)]
    mi, mj = [], []
    for d in directions(dim):
        src = tuple(slice(max(0, -c), s - max(0, c)) for c, s in zip(d, shape))
        dst = tuple(slice(max(0, c), s - max(0, -c)) for c, s in zip(d, shape))
        mi.append(index[src].ravel())
        mj.append(index[dst].ravel())
    return np.concatenate(mi), np.concatenate(mj), index


def coordinates(shape):
    grids = np.meshgrid(*[np.arange(s, dtype=float) for s in shape], indexing="ij")
    # Node order: first coordinate fastest (index[x, y(, z)] = x + nx (y + ny z)).
    return np.column_stack([g.transpose().ravel() for g in grids])


def stiffness(xy, mi, mj, ea, n):
    """Linear bar stiffness EA/L (e, -e)(e, -e)^T assembled over all members."""
    dim = xy.shape[1]
    d = xy[mj] - xy[mi]
    length = np.linalg.norm(d, axis=1)
    e = d / length[:, None]
    g = np.hstack([e, -e])
    dofs = np.hstack([dim * mi[:, None] + np.arange(dim), dim * mj[:, None] + np.arange(dim)])
    vals = (ea / length)[:, None, None] * g[:, :, None] * g[:, None, :]
    r = np.repeat(dofs, 2 * dim, axis=1).ravel()
    c = np.tile(dofs, (1, 2 * dim)).ravel()
    return sp.coo_matrix((vals.ravel(), (r, c)), shape=(n, n)).tocsr()


def constraints(index, n):
    """The clamped bottom layer, then the rigid floors of every tenth layer above it."""
    dim = index.ndim
    layers = index.shape[-1]
    layer = lambda k: index[..., k].ravel()  # noqa: E731  (nodes of layer k, first node first)
    r, c, v = [], [], []
    m = 0
    for node in layer(0):
        for comp in range(dim):
            r.append(m)
            c.append(dim * node + comp)
            v.append(1.0)
            m += 1
    supports = m
    for k in range(10, layers, 10):
        nodes = layer(k)
        for node in nodes[1:]:
            for comp in range(dim - 1):  # the horizontal components
                r += [m, m]
                c += [dim * node + comp, dim * nodes[0] + comp]
                v += [1.0, -1.0]
                m += 1
    return sp.coo_matrix((v, (r, c)), shape=(m, n)).tocsr(), supports, m - supports


def scene(args, n, solver, watch):
    dofs = ", ".join(f'"u{d + 1}"' for d in watch)
    return (
        f'name = "{args.dim}D mesh lattice, {n} DOFs (bench/mesh_lattice.py)"\n\n'
        '[model]\ntype = "matrix"\nmass = { file = "M.mtx" }\nstiffness = { file = "K.mtx" }\n\n'
        '[[constraint_block]]\nfile = "A.mtx"\nname = "c"\n\n'
        '[[load]]\npattern = { file = "f.mtx" }\nvalue = { type = "step", amplitude = 1.0 }\n\n'
        f"[solve]\nt_end = {args.t_end!r}\noutput_step = {args.output_step!r}\n"
        f'scheme = "elimination"\nnewton = "condensed"\nlinear_solver = "{solver}"\n'
        f"rtol = {args.rtol!r}\natol = {args.atol!r}\n\n"
        f'[output]\nquantities = ["displacement"]\ndofs = [{dofs}]\n'
    )


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--dim", type=int, choices=(2, 3), default=2)
    p.add_argument("--dofs", type=float, default=1e4, help="target DOF count (default 1e4)")
    p.add_argument("--out", default="bench/out/mesh", help="output folder")
    p.add_argument("--ea", type=float, default=1.0e4, help="axial stiffness EA of every bar")
    p.add_argument("--mass", type=float, default=1.0, help="lumped mass per DOF")
    p.add_argument("--load", type=float, default=1.0, help="step load on the vertical DOF")
    p.add_argument("--t-end", type=float, default=0.2)
    p.add_argument("--output-step", type=float, default=0.01)
    p.add_argument("--rtol", type=float, default=1e-6)
    p.add_argument("--atol", type=float, default=1e-8)
    args = p.parse_args(argv)

    shape = grid_shape(args.dofs, args.dim)
    mi, mj, index = members(shape)
    xy = coordinates(shape)
    n = args.dim * xy.shape[0]
    K = stiffness(xy, mi, mj, args.ea, n)
    M = sp.identity(n, format="csr") * args.mass
    A, supports, ties = constraints(index, n)
    free = np.setdiff1d(np.arange(xy.shape[0]), index[..., 0].ravel())
    load_dofs = args.dim * free + args.dim - 1
    f = sp.coo_matrix((np.full(free.size, -args.load), (load_dofs, np.zeros_like(load_dofs))),
                      shape=(n, 1))

    os.makedirs(args.out, exist_ok=True)
    path = lambda name: os.path.join(args.out, name)  # noqa: E731
    scipy.io.mmwrite(path("M.mtx"), M, symmetry="symmetric")
    scipy.io.mmwrite(path("K.mtx"), K, symmetry="symmetric")
    scipy.io.mmwrite(path("A.mtx"), A)
    scipy.io.mmwrite(path("f.mtx"), f)
    top = index[..., -1].ravel()
    watch = [args.dim * top[0] + c for c in range(args.dim)] + [args.dim * top[-1] + args.dim - 1]
    for solver in ("klu", "cholmod"):
        with open(path(f"{solver}.toml"), "w") as fh:
            fh.write(scene(args, n, solver, watch))
    info = {"dim": args.dim, "shape": list(shape), "n": n, "m": int(A.shape[0]),
            "supports": supports, "ties": ties, "members": int(mi.size), "nnz_K": int(K.nnz),
            "t_end": args.t_end, "rtol": args.rtol, "atol": args.atol}
    with open(path("mesh.json"), "w") as fh:
        json.dump(info, fh, indent=1)
    print(json.dumps(info))
    return 0


if __name__ == "__main__":
    sys.exit(main())
