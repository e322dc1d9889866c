#!/usr/bin/python3
"""Generate the benchmark's 2D lattice truss (issue 12, item 5) for a target DOF count.

The lattice: `rows` nodes per column (default 5), columns spaced `spacing` apart, every square cell
with its vertical, horizontal and both diagonal bars; lumped mass `mass` per node in x and y; the
first column clamped (ux = uy = 0 at each of its nodes: single-freedom constraints); in every tenth
column (10, 20, ...) a tie, one multi-freedom constraint uy(top) - uy(bottom) = 0; a step load
-load on uy of every free node. Node k (1-based, column-major: node = col * rows + row + 1) has DOFs
ux_k, uy_k, numbered 2k-1 and 2k as condyn's truss2d model numbers them, so the matrix scene and the
inline truss2d scene describe the same system. For rows = 5 and N = 4,000 this is the lattice of
issue 12's table (400 columns, 10 supports + 39 ties, 1,995 loaded DOFs).

Writes into OUT:
  M.mtx, K.mtx  mass and stiffness (Matrix Market, coordinate real symmetric, scipy.io.mmwrite)
  A.mtx         constraint rows (m x n, coordinate real general): supports first, then the ties
  f.mtx         load pattern (n x 1, coordinate real general)
  lattice.toml  the scene with the contract keys of scene-format.md "Matrices and vectors from files"
  condensed.toml  the same with [solve] newton = "condensed"
  inline.toml   (only when N <= --inline-max) the same system as a truss2d scene today's condyn reads
  lattice.json  sizes (n, m, supports, ties, loaded DOFs, nnz) for the benchmark runner
"""
import argparse
import json
import os
import sys

import numpy as np
import scipy.io
import scipy.sparse as sp


def layout(n_target, rows):
    """Columns so that 2 * rows * columns is the nearest achievable DOF count (at least 2 columns)."""
    cols = max(2, int(round(n_target / (2.0 * rows))))
    return cols


def members(cols, rows):
    """Bars as (i, j) node index pairs, 0-based, node = col * rows + row."""
    node = np.arange(cols * rows).reshape(cols, rows)
    pairs = [
        (node[:, :-1].ravel(), node[:, 1:].ravel()),  # verticals within a column
        (node[:-1, :].ravel(), node[1:, :].ravel()),  # horizontals between columns
        (node[:-1, :-1].ravel(), node[1:, 1:].ravel()),  # diagonals /
        (node[:-1, 1:].ravel(), node[1:, :-1].ravel()),  # diagonals \
    ]
    i = np.concatenate([p[0] for p in pairs])
    j = np.concatenate([p[1] for p in pairs])
    return i, j


def coordinates(cols, rows, spacing):
    col, row = np.divmod(np.arange(cols * rows), rows)
    return np.column_stack([col * spacing, row * spacing]).astype(float)


def stiffness(xy, mi, mj, ea, n):
    """Linear bar stiffness k = EA/L e e^T (e the unit axis) assembled over all members."""
    d = xy[mj] - xy[mi]
    length = np.hypot(d[:, 0], d[:, 1])
    e = d / length[:, None]
    k = ea / length
    dofs = np.column_stack([2 * mi, 2 * mi + 1, 2 * mj, 2 * mj + 1])
    sign = np.array([1.0, 1.0, -1.0, -1.0])
    g = np.column_stack([e[:, 0], e[:, 1], e[:, 0], e[:, 1]]) * sign  # the bar's B row
    vals = k[:, None, None] * g[:, :, None] * g[:, None, :]
    r = np.repeat(dofs, 4, axis=1).ravel()
    c = np.tile(dofs, (1, 4)).ravel()
    return sp.coo_matrix((vals.ravel(), (r, c)), shape=(n, n)).tocsr()


def constraints(cols, rows, n):
    """Rows of A: the clamped first column (ux, uy of each node), then one tie per tenth column."""
    r, c, v = [], [], []
    m = 0
    for row in range(rows):
        for comp in (0, 1):
            r.append(m)
            c.append(2 * row + comp)
            v.append(1.0)
            m += 1
    supports = m
    for col in range(10, cols, 10):
        top, bottom = col * rows + rows - 1, col * rows
        r += [m, m]
        c += [2 * top + 1, 2 * bottom + 1]
        v += [1.0, -1.0]
        m += 1
    a = sp.coo_matrix((v, (r, c)), shape=(m, n)).tocsr()
    return a, supports, m - supports


def load_pattern(cols, rows, load):
    """-load on uy of every node outside the clamped column."""
    free = np.arange(rows, cols * rows)
    return 2 * free + 1, np.full(free.size, -load)


def solve_section(args):
    return (
        "[solve]\n"
        f"t_end = {args.t_end!r}\n"
        f"output_step = {args.output_step!r}\n"
        'scheme = "index1"\n'
        f"rtol = {args.rtol!r}\n"
        f"atol = {args.atol!r}\n"
    )


def matrix_scene(args, n, watch):
    dofs = ", ".join(f'"u{d + 1}"' for d in watch)
    return (
        f'name = "Lattice truss, {n} DOFs, from Matrix Market files (bench/lattice.py)"\n\n'
        "[model]\n"
        'type = "matrix"\n'
        'mass = { file = "M.mtx" }\n'
        'stiffness = { file = "K.mtx" }\n\n'
        "[[constraint_block]]\n"
        'file = "A.mtx"\n'
        'name = "c"\n\n'
        "[[load]]\n"
        'pattern = { file = "f.mtx" }\n'
        'value = { type = "step", amplitude = 1.0 }\n\n'
        + solve_section(args)
        + "\n[output]\n"
        'quantities = ["displacement"]\n'
        f"dofs = [{dofs}]\n"
    )


def inline_scene(args, xy, mi, mj, a, supports, load_dofs, load_vals):
    n = 2 * xy.shape[0]
    out = [f'name = "Lattice truss, {n} DOFs, inline (bench/lattice.py)"\n\n[model]\ntype = "truss2d"\n']
    out.append("nodes = [" + ", ".join(f"[{x!r}, {y!r}]" for x, y in xy) + "]\n")
    out.append("masses = [" + ", ".join([repr(args.mass)] * xy.shape[0]) + "]\n")
    out.append("members = [\n")
    for i, j in zip(mi, mj):
        out.append(f"  {{ nodes = [{i + 1}, {j + 1}], EA = {args.ea!r} }},\n")
    out.append("]\n")
    for d, val in zip(load_dofs, load_vals):
        name = ("ux" if d % 2 == 0 else "uy") + str(d // 2 + 1)
        out.append(f'\n[[load]]\ndof = "{name}"\nvalue = {{ type = "step", amplitude = {val!r} }}\n')
    a = a.tocsr()
    for k in range(a.shape[0]):
        cols = a.indices[a.indptr[k]:a.indptr[k + 1]]
        vals = a.data[a.indptr[k]:a.indptr[k + 1]]
        terms = ", ".join(
            ("ux" if d % 2 == 0 else "uy") + f"{d // 2 + 1} = {v!r}" for d, v in zip(cols, vals))
        label = f"c{k + 1}"
        out.append(f'\n[[constraint]]\nname = "{label}"\nterms = {{ {terms} }}\n')
    out.append("\n" + solve_section(args))
    out.append('\n[output]\nquantities = ["displacement"]\n')
    return "".join(out)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--dofs", type=float, default=1e3, help="target DOF count N (default 1e3)")
    p.add_argument("--out", default="bench/out/lattice", help="output folder")
    p.add_argument("--rows", type=int, default=5, help="nodes per column (default 5)")
    p.add_argument("--spacing", type=float, default=1.0, help="cell size (default 1)")
    p.add_argument("--ea", type=float, default=1.0e4, help="axial stiffness EA of every bar (default 1e4)")
    p.add_argument("--mass", type=float, default=1.0, help="lumped mass per node (default 1)")
    p.add_argument("--load", type=float, default=1.0, help="step load on uy of each free node (default 1)")
    p.add_argument("--t-end", type=float, default=1.0)
    p.add_argument("--output-step", type=float, default=0.01)
    p.add_argument("--rtol", type=float, default=1e-6)
    p.add_argument("--atol", type=float, default=1e-8)
    p.add_argument("--inline-max", type=int, default=5000,
                   help="write inline.toml only up to this many DOFs (condyn's current cap is 5,000)")
    args = p.parse_args(argv)
    if args.rows < 2 or args.dofs < 4 * args.rows:
        p.error("need --rows >= 2 and --dofs >= 4 * rows")

    cols = layout(args.dofs, args.rows)
    n = 2 * cols * args.rows
    xy = coordinates(cols, args.rows, args.spacing)
    mi, mj = members(cols, args.rows)
    K = stiffness(xy, mi, mj, args.ea, n)
    M = sp.identity(n, format="csr") * args.mass
    A, supports, ties = constraints(cols, args.rows, n)
    load_dofs, load_vals = load_pattern(cols, args.rows, args.load)
    f = sp.coo_matrix((load_vals, (load_dofs, np.zeros_like(load_dofs))), shape=(n, 1))

    os.makedirs(args.out, exist_ok=True)
    path = lambda name: os.path.join(args.out, name)  # noqa: E731
    scipy.io.mmwrite(path("M.mtx"), M, symmetry="symmetric")
    scipy.io.mmwrite(path("K.mtx"), K, symmetry="symmetric")
    scipy.io.mmwrite(path("A.mtx"), A)
    scipy.io.mmwrite(path("f.mtx"), f)
    # Watched DOFs: the free end's top and bottom nodes (a handful of columns in the output).
    last = (cols - 1) * args.rows
    watch = [2 * last, 2 * last + 1, 2 * (last + args.rows - 1), 2 * (last + args.rows - 1) + 1]
    scene = matrix_scene(args, n, watch)
    with open(path("lattice.toml"), "w") as fh:
        fh.write(scene)
    # The same scene with IDA's Newton systems condensed (dae/linsolve/condensed_newton.hpp).
    with open(path("condensed.toml"), "w") as fh:
        fh.write(scene.replace("[solve]\n", '[solve]\nnewton = "condensed"\n', 1))
    inline = n <= args.inline_max and A.shape[0] <= args.inline_max
    if inline:
        with open(path("inline.toml"), "w") as fh:
            fh.write(inline_scene(args, xy, mi, mj, A, supports, load_dofs, load_vals))
    elif os.path.exists(path("inline.toml")):
        os.remove(path("inline.toml"))
    info = {
        "n": n, "m": int(A.shape[0]), "supports": supports, "ties": ties, "columns": cols,
        "rows": args.rows, "members": int(mi.size), "loaded_dofs": int(load_dofs.size),
        "nnz_K": int(K.nnz), "nnz_A": int(A.nnz), "inline": inline,
        "t_end": args.t_end, "output_step": args.output_step, "rtol": args.rtol, "atol": args.atol,
    }
    with open(path("lattice.json"), "w") as fh:
        json.dump(info, fh, indent=1)
    print(json.dumps(info))
    return 0


if __name__ == "__main__":
    sys.exit(main())
