#!/usr/bin/python3
"""Time the projection scheme against GGL on planar chains of rigid links (issue 44, item 11).

For each N, bench/chain.py writes the chain of N links; `condyn run --scheme projection` and
`condyn run --scheme ggl` run it, each under /usr/bin/time -v, --repeat times (helpers of
bench/run_bench.py). The table gives medians of the solver's wall time (the summary's), the
process's CPU time (user + system: on a shared machine the wall clock also counts the other
processes' turns), steps, Newton matrix setups, peak RSS, CPU time per step, and the ratio of
projection's CPU time per step to GGL's in the same run; then the exponent of CPU time per step
over N fitted per scheme.

  /usr/bin/python3 bench/projection_chain.py [--links 100 1000 10000] [--repeat 3]
"""
import argparse
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import chain  # noqa: E402
import run_bench  # noqa: E402

SCHEMES = ["projection", "ggl"]
CLOCK = "process_cpu_s"  # the process's CPU time, robust to other processes on the machine


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, nargs="+", default=[100, 1000, 10000])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--t-end", type=float, default=0.1)
    parser.add_argument("--timeout", type=float, default=1800.0)
    parser.add_argument("--condyn", default=os.path.join(run_bench.ROOT, "build", "condyn"))
    args = parser.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for links in args.links:
            path = os.path.join(tmp, f"chain_{links}.toml")
            with open(path, "w") as fh:
                fh.write(chain.scene(links, args.t_end, args.t_end / 10.0))
            for scheme in SCHEMES:
                runs = [run_bench.run_condyn(args.condyn, path, scheme, args.timeout)
                        for _ in range(args.repeat)]
                row = run_bench.median_row(runs)
                row.update(links=links, scheme=scheme)
                rows.append(row)
                print(f"  {links} links, {scheme}: {row}", file=sys.stderr, flush=True)
    print(f"{'links':>6} {'scheme':>10} {'steps':>6} {'setups':>6} {'solver s':>9} {'CPU s':>8} "
          f"{'CPU ms/step':>11} {'peak MB':>8} {'x GGL/step':>10}")
    for row in rows:
        if row["status"] != "ok":
            print(f"{row['links']:>6} {row['scheme']:>10} {row['status']}")
            continue
        ggl = next(r for r in rows if r["links"] == row["links"] and r["scheme"] == "ggl")
        ratio = (run_bench.per_step(row, CLOCK) / run_bench.per_step(ggl, CLOCK)
                 if ggl["status"] == "ok" else None)
        print(f"{row['links']:>6} {row['scheme']:>10} {row['steps']:>6.0f} "
              f"{row['jacobian_evals']:>6.0f} {row['solver_s']:>9.3f} {row[CLOCK]:>8.3f} "
              f"{1e3 * run_bench.per_step(row, CLOCK):>11.3f} {row['peak_mb']:>8.1f} "
              f"{run_bench.fmt(ratio, '.2f'):>10}")
    for scheme in SCHEMES:
        points = [(r["links"], run_bench.per_step(r, CLOCK)) for r in rows
                  if r["scheme"] == scheme and r["status"] == "ok"]
        if len(points) >= 2:
            print(f"{scheme}: time per step ~ N^{run_bench.fit_exponent(points):.2f}")


if __name__ == "__main__":
    main()
