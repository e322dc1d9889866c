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

  /usr/bin/python3 bench/factorization_bench.py [--topologies 2d 3d] [--sizes 1e4 1e5] [--repeat 3]
"""
import argparse
import datetime
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from run_bench import median_row, run_condyn  # noqa: E402


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
            for solver in ("klu", "cholmod"):
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
                         if solver == "cholmod" and per["klu"] and per["cholmod"] else "")
                print(f"| {topology} | {size:g} | {solver} | {r['steps']:g} | {r['jacobian_evals']:g} "
                      f"| {per[solver]:.3g} | {r['process_cpu_s']:.2f} | {r['peak_mb']:.0f} | {ratio} |")
    print()
    for n in notes:
        print("- " + n)
    return 0


if __name__ == "__main__":
    sys.exit(main())
