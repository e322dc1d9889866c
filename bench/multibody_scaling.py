#!/usr/bin/python3
"""Time per step against size on chains of rigid bodies (issue 44, item 11).

For each chain (bench/multibody_chain.py: planar bars on revolute joints, spatial bars on
spherical or revolute joints) and each scheme, `condyn run --scheme S` runs the chain to two end
times, t_short and t_long, each under /usr/bin/time -v (helpers of bench/run_bench.py), --repeat
times. The cost of a step is the marginal one, (CPU(t_long) - CPU(t_short)) / (steps(t_long) -
steps(t_short)): the process's CPU time (user + system; on a shared machine the wall clock also
counts the other processes' turns), less what both runs share (reading the scene, building the
model, the consistent start, writing the output). Also: the setup (CPU of the short run less its
steps at the marginal cost), the cost per residual evaluation (Newton iteration) the same way
(the iterations a step takes vary with N and with the run), steps, peak RSS of the long run
against `condyn info --scheme S`'s memory estimate, and the exponents of the cost per step and
per iteration over N fitted per chain and scheme. With --instructions, valgrind's callgrind
counts the instructions of both runs instead of timing them (noise-free, about 50 times slower).

  /usr/bin/python3 bench/multibody_scaling.py [--planar 100 1000 10000] [--spatial 100 1000]
      [--joint spherical] [--schemes auto ggl ...] [--repeat 3] [--large-repeat 1]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import multibody_chain  # noqa: E402
import run_bench  # noqa: E402

SCHEMES = ["auto", "ggl", "index1", "baumgarte", "index2", "index3", "projection"]
SELECTED = re.compile(r"^  (\S+(?: mixed)?)\s+\d+\s+\d+\s+([0-9.]+) (B|kB|MB|GB|TB)\s+<- selected",
                      re.M)
COLLECTED = re.compile(r"Collected : (\d+)")


def info_estimate(condyn, scene, scheme, timeout):
    """The memory estimate (MB of 2^20 bytes, as peak_mb) of `condyn info --scheme S`'s selected
    system, or None."""
    try:
        out = subprocess.run([condyn, "info", scene, "--scheme", scheme], capture_output=True,
                             text=True, timeout=timeout).stdout
    except subprocess.TimeoutExpired:
        return None
    m = SELECTED.search(out)
    return float(m[2]) * run_bench.UNITS[m[3]] / 2.0**20 if m else None


def instructions(condyn, scene, scheme, timeout):
    """Instructions the run executes (callgrind's total) and its steps, as a row."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", condyn, "run",
               scene, "--scheme", scheme, "--out", os.path.join(tmp, "out.csv")]
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return {"status": f"timed out after {timeout} s"}
    out = proc.stdout + proc.stderr
    summary, collected = run_bench.SUMMARY.search(out), COLLECTED.search(out)
    if proc.returncode != 0 or summary is None or collected is None:
        return {"status": "failed: " + run_bench.first_error(out)}
    return {"status": "ok", "steps": int(summary["steps"]), "residual_evals": int(summary["res"]),
            "instructions": int(collected[1])}


def measure(args, scene_of, scheme, repeat):
    """Median rows of the short and the long run of one chain under one scheme."""
    rows = []
    for t_end in (args.t_short, args.t_long):
        scene = scene_of(t_end)
        runs = []
        for _ in range(repeat):
            if args.instructions:
                runs.append(instructions(args.condyn, scene, scheme, args.timeout))
            else:
                runs.append(run_bench.run_condyn(args.condyn, scene, scheme, args.timeout))
            if runs[-1]["status"] != "ok":
                break  # a failure repeats identically: one is enough to report
        rows.append(run_bench.median_row(runs))
    return rows


def marginal(short, long, key):
    """Per step of the long run beyond the short one, the short run's setup, and per residual
    evaluation (Newton iteration) beyond the short run's."""
    steps = long["steps"] - short["steps"]
    residuals = long["residual_evals"] - short["residual_evals"]
    if steps <= 0 or residuals <= 0:
        return None, None, None
    per_step = (long[key] - short[key]) / steps
    return per_step, short[key] - per_step * short["steps"], (long[key] - short[key]) / residuals


def one_row(args, kind, n, scheme, tmp):
    """Measures one chain of n bodies under one scheme; returns the table's row."""
    dimension, joint = (2, "revolute") if kind == "planar" else (3, args.joint)

    def scene_of(t_end):
        path = os.path.join(tmp, f"{kind}_{n}_{t_end!r}.toml")
        if not os.path.exists(path):
            with open(path, "w") as fh:
                fh.write(multibody_chain.scene(n, dimension, joint, t_end))
        return path

    repeat = args.repeat if n < 10000 else args.large_repeat
    short, long = measure(args, scene_of, scheme, repeat)
    row = {"kind": kind, "n": n, "scheme": scheme, "status": long["status"]}
    if short["status"] != "ok" or long["status"] != "ok":
        row["status"] = short["status"] if short["status"] != "ok" else long["status"]
        return row
    key = "instructions" if args.instructions else "process_cpu_s"
    row.update(steps_short=short["steps"], steps=long["steps"],
               iterations=(long["residual_evals"] - short["residual_evals"]) /
               max(long["steps"] - short["steps"], 1))
    row["per_step"], row["setup"], row["per_residual"] = marginal(short, long, key)
    if not args.instructions:
        row.update(cpu_s=long["process_cpu_s"], peak_mb=long["peak_mb"],
                   estimate_mb=info_estimate(args.condyn, scene_of(args.t_long), scheme,
                                             args.timeout))
    return row


def print_table(rows, instructions_counted):
    unit = "instructions / step" if instructions_counted else "CPU ms / step"
    setup = "setup instructions" if instructions_counted else "setup CPU s"
    print(f"\n| chain | bodies | scheme | steps | iterations / step | {unit} | per iteration | "
          f"{setup} | CPU s | peak MB | estimate MB | estimate / peak |\n|" + "---|" * 12)
    for r in rows:
        if r["status"] != "ok":
            status = r["status"] if len(r["status"]) <= 110 else r["status"][:107] + "..."
            print(f'| {r["kind"]} | {r["n"]} | {r["scheme"]} | {status} |' + " |" * 8)
            continue
        scale = 1.0 if instructions_counted else 1e3
        per_step = run_bench.fmt(None if r["per_step"] is None else scale * r["per_step"], ".4g")
        per_residual = run_bench.fmt(None if r["per_residual"] is None
                                     else scale * r["per_residual"], ".4g")
        estimate = r.get("estimate_mb")
        ratio = estimate / r["peak_mb"] if estimate and r.get("peak_mb") else None
        print(f'| {r["kind"]} | {r["n"]} | {r["scheme"]} | '
              f'{r["steps_short"]:.0f} / {r["steps"]:.0f} | {r["iterations"]:.2f} | '
              f'{per_step} | {per_residual} | '
              f'{run_bench.fmt(r["setup"], ".3g")} | '
              f'{run_bench.fmt(r.get("cpu_s"), ".3g")} | '
              f'{run_bench.fmt(r.get("peak_mb"), ".1f")} | '
              f'{run_bench.fmt(estimate, ".1f")} | {run_bench.fmt(ratio, ".2f")} |')
    print("\nFitted exponent of the cost per step and per iteration over N (least squares):")
    series = {}
    for r in rows:
        if r["status"] == "ok" and r["per_step"]:
            series.setdefault((r["kind"], r["scheme"]), []).append(
                (r["n"], r["per_step"], r["per_residual"]))
    for (kind, scheme), pts in sorted(series.items()):
        k = run_bench.fit_exponent([(p[0], p[1]) for p in pts])
        k_it = run_bench.fit_exponent([(p[0], p[2]) for p in pts])
        print(f"  {kind:7s} {scheme:11s} k = {run_bench.fmt(k, '.3f')} per step, "
              f"{run_bench.fmt(k_it, '.3f')} per iteration, over N = {[p[0] for p in pts]}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--planar", type=int, nargs="*", default=[100, 1000, 10000])
    p.add_argument("--spatial", type=int, nargs="*", default=[100, 1000])
    p.add_argument("--joint", choices=["spherical", "revolute"], default="spherical")
    p.add_argument("--schemes", nargs="+", default=SCHEMES)
    p.add_argument("--repeat", type=int, default=3, help="runs per row below 10^4 bodies (medians)")
    p.add_argument("--large-repeat", type=int, default=1, help="runs per row from 10^4 bodies")
    p.add_argument("--t-short", type=float, default=0.01)
    p.add_argument("--t-long", type=float, default=0.03)
    p.add_argument("--instructions", action="store_true", help="count instructions (callgrind)")
    p.add_argument("--timeout", type=float, default=1800.0, help="seconds per run")
    p.add_argument("--condyn", default=os.path.join(run_bench.ROOT, "build", "condyn"))
    args = p.parse_args(argv)
    if args.repeat < 1 or args.large_repeat < 1 or not 0.0 < args.t_short < args.t_long:
        p.error("--repeat and --large-repeat take at least 1; 0 < --t-short < --t-long")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for kind, sizes in (("planar", args.planar), ("spatial", args.spatial)):
            for n in sizes:
                for scheme in args.schemes:
                    rows.append(one_row(args, kind, n, scheme, tmp))
                    print(f"  {rows[-1]}", file=sys.stderr, flush=True)
    print_table(rows, args.instructions)
    return 0


if __name__ == "__main__":
    sys.exit(main())
