#!/usr/bin/python3
"""Time per step of KLU against CHOLMOD on mesh lattices (issue 47, item 2; docs/benchmarks.md).

For each topology (2d, 3d) and target DOF count: bench/mesh_lattice.py writes the lattice and its
two scenes, both elimination with the condensed Newton systems K + cj C + cj^2 M (so the runs
differ in the factorization alone), `linear_solver = "klu"` and `"cholmod"`; `condyn run` runs
each --repeat times under /usr/bin/time -v (bench/run_bench.py's runner). Prints a Markdown table
of medians: steps, Newton setups (the summary's Jacobian evaluations: one factorization each),
the solver's wall time per step, the whole process's CPU seconds (reading the files and the
analyses included: on a shared machine the wall time per step follows the share of the CPU the
run got, its CPU time much less), peak RSS, and CHOLMOD's time per step over KLU's; and `condyn
info`'s factorization line (each candidate's predicted factor) for the first repeat.

With --bare, each size also gets the bare drivers' floor (issue 47, item 3: condyn's solver time
per step within 1.2 times the best bare driver's on the same matrices, peak memory within 1.5
times), each against condyn on the same formulation and factorization:
  klu      condyn_bare_driver (IDA + KLU, index 1, multipliers out of the error test) against
           `condyn run klu.toml --scheme index1` with the full Newton matrix (the scene's
           `newton = "condensed"` left out), as the bare driver factors it
  cholmod  condyn_bare_cholmod_driver (IDA + CHOLMOD on the penalty form K + w Aᵀ D A, the
           condensed Newton matrix refactored at each change of cj) against the same scene under
           `scheme = "penalty"`, `penalty = { weight = W }` (--weight, default 1e8)
both with the velocities' absolute tolerance equal to the displacements' (the bare drivers' one
scalar atol). Rows: condyn's and the bare driver's medians, the ratios per step and of the peaks.
--bare-solvers picks the pairs (KLU's index 1 on a 2D mesh of 10^5 DOFs takes minutes a step).

  /usr/bin/python3 bench/factorization_bench.py [--topologies 2d 3d] [--sizes 1e4 1e5] [--repeat 3]
      [--solvers klu cholmod] [--bare [--bare-solvers klu cholmod] [--weight W]]
"""
import argparse
import datetime
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from run_bench import median_row, run_bare, run_condyn  # noqa: E402


def factorization_line(condyn, scene):
    out = subprocess.run([condyn, "info", scene], capture_output=True, text=True).stdout
    lines = out.splitlines()
    for k, line in enumerate(lines):
        if line.startswith("factorization: "):
            text = [line]
            for more in lines[k + 1:]:
                if not more.startswith(" "):
                    break
                text.append(more.strip())
            return " ".join(text)
    return "(no factorization line)"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--topologies", nargs="+", default=["2d"], choices=["2d", "3d"])
    p.add_argument("--sizes", type=float, nargs="+", default=[1e4, 1e5])
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--t-end", type=float, default=0.2)
    p.add_argument("--condyn", default=os.path.join(ROOT, "build", "condyn"))
    p.add_argument("--work", default=os.path.join(HERE, "out"))
    p.add_argument("--timeout", type=float, default=3600.0)
    p.add_argument("--solvers", nargs="+", default=["klu", "cholmod"], choices=["klu", "cholmod"],
                   help="the factorizations of the first table (KLU on a mesh of 1e5 DOFs takes minutes)")
    p.add_argument("--bare", action="store_true", help="also the bare drivers' floor (below)")
    p.add_argument("--bare-solvers", nargs="+", default=["klu", "cholmod"], choices=["klu", "cholmod"])
    p.add_argument("--weight", type=float, default=1e8, help="penalty weight of the CHOLMOD pair")
    args = p.parse_args(argv)

    print(f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, "
          f"`bench/factorization_bench.py {' '.join(argv if argv is not None else sys.argv[1:])}`")
    print("\n| topology | DOFs | solver | steps | setups | ms/step | process CPU s | peak MB "
          "| CHOLMOD/KLU per step |")
    print("|---|---|---|---|---|---|---|---|---|")
    notes = []
    for topology in args.topologies:
        for size in args.sizes:
            folder = os.path.join(args.work, f"mesh{topology}-{size:g}")
            subprocess.run(["/usr/bin/python3", os.path.join(HERE, "mesh_lattice.py"),
                            "--dim", topology[0], "--dofs", repr(size), "--out", folder,
                            "--t-end", repr(args.t_end)], check=True, capture_output=True)
            rows = {}
            for solver in args.solvers:
                scene = os.path.join(folder, f"{solver}.toml")
                rows[solver] = median_row([run_condyn(args.condyn, scene, "elimination", args.timeout)
                                           for _ in range(args.repeat)])
            notes.append(f"{topology} {size:g}: " +
                         factorization_line(args.condyn, os.path.join(folder, "cholmod.toml")))
            per = {s: r["solver_s"] / r["steps"] * 1e3 if r["status"] == "ok" else None
                   for s, r in rows.items()}
            for solver, r in rows.items():
                if r["status"] != "ok":
                    print(f"| {topology} | {size:g} | {solver} | {r['status']} ||||||")
                    continue
                ratio = (f"{per['cholmod'] / per['klu']:.2f}"
                         if solver == "cholmod" and per.get("klu") and per["cholmod"] else "")
                print(f"| {topology} | {size:g} | {solver} | {r['steps']:g} | {r['jacobian_evals']:g} "
                      f"| {per[solver]:.3g} | {r['process_cpu_s']:.2f} | {r['peak_mb']:.0f} | {ratio} |")
    if args.bare:
        bare_table(args)
    print()
    for n in notes:
        print("- " + n)
    return 0


def same_atol_scene(folder, solver, weight):
    """The lattice's scene for `solver` with the velocities' atol the displacements' (and, for
    CHOLMOD, the penalty weight): the formulation the bare driver integrates."""
    text = open(os.path.join(folder, f"{solver}.toml")).read()
    atol = next(ln for ln in text.splitlines() if ln.startswith("atol = "))
    extra = f"atol_velocity = {atol.split('=', 1)[1].strip()}\n"
    if solver == "cholmod":
        extra += f"penalty = {{ weight = {weight!r} }}\n"
    else:  # the full Newton matrix, as the bare driver factors it
        text = "".join(ln for ln in text.splitlines(keepends=True) if not ln.startswith("newton = "))
    path = os.path.join(folder, f"bare_pair_{solver}.toml")
    with open(path, "w") as out:
        out.write(text.replace(atol + "\n", atol + "\n" + extra))
    return path


def bare_table(args):
    build = os.path.dirname(args.condyn)
    drivers = {"klu": (os.path.join(build, "condyn_bare_driver"), "index1", "bare: ", []),
               "cholmod": (os.path.join(build, "condyn_bare_cholmod_driver"), "penalty",
                           "bare_cholmod: ", ["--weight", repr(args.weight)])}
    print("\n| topology | DOFs | pair | run | steps | setups | ms/step | peak MB "
          "| condyn/bare per step | condyn/bare peak |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for topology in args.topologies:
        for size in args.sizes:
            folder = os.path.join(args.work, f"mesh{topology}-{size:g}")
            info = json.load(open(os.path.join(folder, "mesh.json")))
            info["output_step"] = output_step(os.path.join(folder, "klu.toml"))
            for solver in args.bare_solvers:
                bare, scheme, prefix, extra = drivers[solver]
                scene = same_atol_scene(folder, solver, args.weight)
                rows = {
                    "condyn": median_row([run_condyn(args.condyn, scene, scheme, args.timeout)
                                          for _ in range(args.repeat)]),
                    "bare": median_row([run_bare(bare, folder, info, args.timeout, extra, prefix)
                                        for _ in range(args.repeat)])}
                ok = all(r["status"] == "ok" for r in rows.values())
                per = {k: r["solver_s"] / r["steps"] * 1e3 for k, r in rows.items() if r["status"] == "ok"}
                for who, r in rows.items():
                    if r["status"] != "ok":
                        print(f"| {topology} | {size:g} | {solver} | {who} | {r['status']} |||||")
                        continue
                    ratios = (f"{per['condyn'] / per['bare']:.2f} | "
                              f"{rows['condyn']['peak_mb'] / rows['bare']['peak_mb']:.2f}"
                              if ok and who == "condyn" else " | ")
                    print(f"| {topology} | {size:g} | {solver} ({scheme}) | {who} | {r['steps']:g} "
                          f"| {r['jacobian_evals']:g} | {per[who]:.3g} | {r['peak_mb']:.0f} | {ratios} |")


def output_step(scene):
    for line in open(scene):
        if line.startswith("output_step = "):
            return float(line.split("=", 1)[1])
    raise ValueError(f"{scene}: no output_step")


if __name__ == "__main__":
    sys.exit(main())
