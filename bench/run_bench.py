#!/usr/bin/python3
"""Benchmark condyn against a bare IDA + KLU driver on lattice trusses (issue 12, item 5).

For each N: bench/lattice.py writes the lattice (Matrix Market files, lattice.toml, condensed.toml
and, up to 5,000 DOFs, inline.toml); build/condyn_bare_driver solves it; `condyn run lattice.toml
--scheme S` runs for each scheme S, and `condyn run condensed.toml --scheme S` ([solve] newton =
"condensed", variant "condensed"); where inline.toml exists, `condyn run inline.toml --scheme S`
runs too; `condyn info lattice.toml` is timed too. Every run is wrapped in /usr/bin/time -v (peak
RSS; wall and CPU time from this runner's clock and resource usage) and repeated --repeat times
(--large-repeat times from 1e6 DOFs, default once: such a run takes minutes); the table gives
medians, time per step, and ratios per step to the bare driver measured in this run.
A run that fails (for instance because this condyn cannot read the Matrix Market scene yet) is a
row that says why, with no figures. Writes bench/results.csv and bench/scaling.png.

  /usr/bin/python3 bench/run_bench.py [--sizes 1e3 1e4 1e5] [--large] [--repeat 3] [--large-repeat 1]
"""
import argparse
import csv
import math
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SCHEMES = ["index1", "ggl", "elimination"]
INLINE_MAX = 5000

SUMMARY = re.compile(
    r"^(?P<scheme>[a-z0-9_]+): [^\n]*?(?P<steps>\d+) steps, (?P<res>\d+) residual and (?P<jac>\d+) "
    r"Jacobian evaluations,[^\n]*? wall (?P<wall>[0-9.eE+-]+) ms", re.M)


def time_v(path):
    """Peak RSS (MB), wall and CPU seconds of the process from a /usr/bin/time -v report."""
    text = open(path).read()
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", text)
    user = re.search(r"User time \(seconds\): ([0-9.]+)", text)
    system = re.search(r"System time \(seconds\): ([0-9.]+)", text)
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([0-9:.]+)", text)
    if not (rss and user and system and wall):
        return None
    parts = [float(p) for p in wall.group(1).split(":")]
    seconds = 0.0
    for p in parts:
        seconds = 60.0 * seconds + p
    return {"peak_mb": int(rss.group(1)) / 1024.0, "process_s": seconds,
            "process_cpu_s": float(user.group(1)) + float(system.group(1))}


def timed(cmd, timeout):
    """Runs cmd under /usr/bin/time -v; returns (exit code, stdout + stderr, time figures).

    The peak comes from /usr/bin/time; wall and CPU time from this process's clock and its
    children's resource usage, because /usr/bin/time prints them in hundredths of a second and a
    run of 1,000 DOFs takes a few of those (`condyn info` less than one)."""
    with tempfile.NamedTemporaryFile("r", suffix=".time", delete=False) as fh:
        report = fh.name
    try:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        proc = subprocess.run(["/usr/bin/time", "-v", "-o", report] + cmd, capture_output=True,
                              text=True, timeout=timeout)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        figures = time_v(report)
        if figures is not None:
            figures["process_s"] = wall
            figures["process_cpu_s"] = (after.ru_utime - before.ru_utime +
                                        after.ru_stime - before.ru_stime)
        return proc.returncode, proc.stdout + proc.stderr, figures
    except subprocess.TimeoutExpired:
        return None, f"timed out after {timeout} s", None
    finally:
        os.unlink(report)


def first_error(text):
    for line in text.splitlines():
        if "error" in line.lower():
            return line.strip()
    lines = [ln for ln in text.splitlines() if ln.strip()]
    return lines[-1].strip() if lines else "no output"


def run_bare(bare, folder, info, timeout, extra=(), prefix="bare: "):
    """A bare driver's run (condyn_bare_driver; condyn_bare_cholmod_driver with its prefix
    "bare_cholmod: " and extra ["--weight", W]): its key=value line as a row."""
    cmd = [bare, folder, "--t-end", repr(info["t_end"]), "--output-step", repr(info["output_step"]),
           "--rtol", repr(info["rtol"]), "--atol", repr(info["atol"])] + list(extra)
    code, out, tv = timed(cmd, timeout)
    line = next((ln for ln in out.splitlines() if ln.startswith(prefix)), None)
    if code != 0 or line is None or tv is None:
        return {"status": "failed: " + first_error(out)}
    kv = dict(item.split("=", 1) for item in line[len(prefix):].split())
    row = {"status": "ok", "steps": int(kv["steps"]), "jacobian_evals": int(kv["jacobian_evals"]),
           "residual_evals": int(kv["residual_evals"]), "solver_s": float(kv["solver_s"]),
           "solver_cpu_s": float(kv["solver_cpu_s"]), "u_last": float(kv["u_last"])}
    row.update(tv)
    return row


def run_condyn(condyn, scene, scheme, timeout):
    """`scheme` is a name, or NAME:H for a fixed step H (the Newmark family, rattle: --step H)."""
    name, _, step = scheme.partition(":")
    with tempfile.TemporaryDirectory() as tmp:
        code, out, tv = timed([condyn, "run", scene, "--scheme", name,
                               "--out", os.path.join(tmp, "out.csv")]
                              + (["--step", step] if step else []), timeout)
    match = SUMMARY.search(out)
    if code != 0 or match is None or tv is None:
        return {"status": "failed: " + first_error(out)}
    row = {"status": "ok", "steps": int(match["steps"]), "jacobian_evals": int(match["jac"]),
           "residual_evals": int(match["res"]), "solver_s": float(match["wall"]) / 1e3}
    row.update(tv)
    return row


def run_info(condyn, scene, timeout):
    """`condyn info` on the scene: the whole process, which the issue asks to be near-linear."""
    code, out, tv = timed([condyn, "info", scene], timeout)
    if code != 0 or tv is None:
        return {"status": "failed: " + first_error(out)}
    return dict({"status": "ok"}, **tv)


def median_row(rows):
    """The median of every figure over repeats; a failure in any repeat makes the row a failure."""
    for r in rows:
        if r["status"] != "ok":
            return r
    out = {"status": "ok"}
    for key in rows[0]:
        if key != "status":
            out[key] = statistics.median(r[key] for r in rows)
    return out


def per_step(row, key):
    return row[key] / row["steps"] if row.get("status") == "ok" and row.get("steps") else None


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


COLUMNS = ["n", "m", "variant", "scheme", "status", "steps", "jacobian_evals", "residual_evals",
           "solver_s", "solver_cpu_s", "process_s", "process_cpu_s", "peak_mb", "solver_ms_per_step",
           "process_ms_per_step", "ratio_solver", "ratio_process", "ratio_process_cpu", "ratio_peak",
           "estimate_mb", "ratio_estimate"]

ESTIMATE_ROW = re.compile(r"^  (\S+)\s+\d+\s+\d+\s+([0-9.]+) (B|kB|MB|GB|TB)", re.M)
UNITS = {"B": 1.0, "kB": 1e3, "MB": 1e6, "GB": 1e9, "TB": 1e12}


def memory_estimates(condyn, scene, timeout):
    """Each pure scheme's memory estimate in MB of 2^20 bytes (as peak_mb), from `condyn info`'s
    table of the systems each scheme integrates; {} when info fails."""
    try:
        out = subprocess.run([condyn, "info", scene], capture_output=True, text=True,
                             timeout=timeout).stdout
    except subprocess.TimeoutExpired:
        return {}
    return {m[1]: float(m[2]) * UNITS[m[3]] / 2.0**20 for m in ESTIMATE_ROW.finditer(out)}


def with_ratios(row, bare):
    """Per-step times and the ratios to the bare driver's row of the same N (per step; memory)."""
    ms = lambda key: None if per_step(row, key) is None else 1e3 * per_step(row, key)  # noqa: E731
    row["solver_ms_per_step"] = fmt(ms("solver_s"), ".4g")
    row["process_ms_per_step"] = fmt(ms("process_s"), ".4g")
    ok = row["status"] == "ok" and bare["status"] == "ok"
    ratio = lambda key: fmt(per_step(row, key) / per_step(bare, key), ".3g") if ok else "-"  # noqa: E731
    row["ratio_solver"] = ratio("solver_s")
    row["ratio_process"] = ratio("process_s")
    row["ratio_process_cpu"] = ratio("process_cpu_s")
    row["ratio_peak"] = fmt(row["peak_mb"] / bare["peak_mb"], ".3g") if ok else "-"
    return row


def fit_exponent(points):
    """Least-squares slope of log(time per step) over log N; None with fewer than two sizes."""
    pts = [(math.log(n), math.log(t)) for n, t in points if t and t > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx > 0 else None


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    series = {}
    for r in rows:
        if r["status"] == "ok":
            series.setdefault(f'{r["variant"]} {r["scheme"]}'.strip(), []).append(
                (r["n"], float(r["solver_ms_per_step"])))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for label, pts in sorted(series.items()):
        pts.sort()
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=label)
    ax.set_xlabel("DOFs N")
    ax.set_ylabel("solver wall time per step [ms]")
    ax.set_title("Lattice truss: cost per step (bench/run_bench.py)")
    ax.grid(True, which="both", alpha=0.3)
    if series:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", type=float, nargs="+", default=[1e3, 1e4, 1e5], help="target DOF counts")
    p.add_argument("--large", action="store_true", help="add N = 1e6")
    p.add_argument("--repeat", type=int, default=3, help="runs per row; the table gives medians")
    p.add_argument("--large-repeat", type=int, default=1,
                   help="runs per row from 1e6 DOFs (a 1e6 run takes minutes)")
    p.add_argument("--schemes", nargs="+", default=SCHEMES,
                   help="schemes to run; NAME:H runs NAME with the fixed step H (--step H), e.g. "
                        "generalized_alpha:0.005")
    p.add_argument("--variants", nargs="+", default=["mtx", "condensed", "inline"],
                   choices=["mtx", "condensed", "inline"], help="which scenes of each lattice run")
    p.add_argument("--condyn", default=os.path.join(ROOT, "build", "condyn"))
    p.add_argument("--bare", default=os.path.join(ROOT, "build", "condyn_bare_driver"))
    p.add_argument("--work", default=os.path.join(HERE, "out"), help="where the lattices are written")
    p.add_argument("--csv", default=os.path.join(HERE, "results.csv"))
    p.add_argument("--plot", default=os.path.join(HERE, "scaling.png"))
    p.add_argument("--no-bare", action="store_true", help="skip the bare driver")
    p.add_argument("--timeout", type=float, default=3600.0, help="seconds per run")
    args = p.parse_args(argv)
    if args.repeat < 1 or args.large_repeat < 1:
        p.error("--repeat and --large-repeat take a whole number of runs, at least 1")
    sizes = sorted(set(int(s) for s in args.sizes) | ({1000000} if args.large else set()))
    for exe in ([args.condyn] + ([] if args.no_bare else [args.bare])):
        if not os.access(exe, os.X_OK):
            p.error(f"{exe} not found: build it (cmake --build build --target condyn condyn_bare_driver)")
    sys.path.insert(0, HERE)
    import lattice

    rows = []
    info_rows = []
    for n_target in sizes:
        repeat = args.repeat if n_target < 1000000 else args.large_repeat
        folder = os.path.join(args.work, f"N{n_target}")
        print(f"== N = {n_target}: generating {folder}", flush=True)
        lattice.main(["--dofs", str(n_target), "--out", folder])
        import json
        info = json.load(open(os.path.join(folder, "lattice.json")))
        base = {"n": info["n"], "m": info["m"]}
        bare = {"status": "skipped"}
        if not args.no_bare:
            bare = median_row([run_bare(args.bare, folder, info, args.timeout) for _ in range(repeat)])
            print(f"   bare: {bare}", flush=True)
        rows.append(with_ratios(dict(base, variant="bare", scheme="index1", **bare), bare))
        r = median_row([run_info(args.condyn, os.path.join(folder, "lattice.toml"), args.timeout)
                        for _ in range(repeat)])
        print(f"   info: {r}", flush=True)
        info_rows.append(dict(base, **r))
        variants = [("mtx", os.path.join(folder, "lattice.toml"))]
        variants.append(("condensed", os.path.join(folder, "condensed.toml")))
        if info["inline"] and info["n"] <= INLINE_MAX:
            variants.append(("inline", os.path.join(folder, "inline.toml")))
        variants = [v for v in variants if v[0] in args.variants]
        for variant, scene in variants:
            estimate = memory_estimates(args.condyn, scene, args.timeout)
            for scheme in args.schemes:
                runs = []
                for _ in range(repeat):
                    runs.append(run_condyn(args.condyn, scene, scheme, args.timeout))
                    if runs[-1]["status"] != "ok":
                        break  # a failure repeats identically: one is enough to report
                r = median_row(runs)
                if variant == "mtx" and r["status"] != "ok":
                    r["status"] = "failed: " + r["status"][8:]
                name = scheme.partition(":")[0]
                if r["status"] == "ok" and name in estimate:
                    r["estimate_mb"] = estimate[name]
                    r["ratio_estimate"] = round(estimate[name] / r["peak_mb"], 2)
                print(f"   {variant} {scheme}: {r}", flush=True)
                rows.append(with_ratios(dict(base, variant=variant, scheme=scheme, **r), bare))

    with open(args.csv, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (format(v, ".6g") if isinstance(v, float) else v) for k, v in r.items()})

    head = ("| N | m | run | scheme | steps | Jacobian evals | solver ms/step | process ms/step | "
            "peak MB | solver ratio | process ratio | process CPU ratio | memory ratio |")
    print("\n" + head + "\n|" + "---|" * 13)
    for r in rows:
        if r["status"] != "ok":
            status = re.sub(r"error: \S+?:\d+: ", "", r["status"])  # the scene's path: in the CSV
            status = status if len(status) <= 110 else status[:107] + "..."
            print(f'| {r["n"]} | {r["m"]} | {r["variant"]} | {r["scheme"]} | {status} |' + " |" * 8)
            continue
        print(f'| {r["n"]} | {r["m"]} | {r["variant"]} | {r["scheme"]} | {r["steps"]:.0f} | '
              f'{r["jacobian_evals"]:.0f} | {r["solver_ms_per_step"]} | {r["process_ms_per_step"]} | '
              f'{r["peak_mb"]:.1f} | {r["ratio_solver"]} | {r["ratio_process"]} | '
              f'{r["ratio_process_cpu"]} | {r["ratio_peak"]} |')
    print("\nMemory estimate (`condyn info`, the scheme's row) against the run's peak:\n\n"
          "| N | run | scheme | estimate MB | peak MB | estimate / peak |\n|---|---|---|---|---|---|")
    for r in rows:
        if r["status"] == "ok" and "estimate_mb" in r:
            print(f'| {r["n"]} | {r["variant"]} | {r["scheme"]} | {r["estimate_mb"]:.1f} | '
                  f'{r["peak_mb"]:.1f} | {r["ratio_estimate"]} |')
    print("\nFitted cost exponent (solver time per step ~ N^k, least squares over the sizes run):")
    series = {}
    for r in rows:
        if r["status"] == "ok":
            series.setdefault((r["variant"], r["scheme"]), []).append((r["n"], per_step(r, "solver_s")))
    for (variant, scheme), pts in sorted(series.items()):
        k = fit_exponent(pts)
        print(f"  {variant:6s} {scheme:12s} k = {fmt(k, '.3f')} over N = {[p[0] for p in pts]}")
    print("\n`condyn info lattice.toml` (whole process, medians):\n\n| N | m | process s | peak MB |\n|---|---|---|---|")
    for r in info_rows:
        if r["status"] == "ok":
            print(f'| {r["n"]} | {r["m"]} | {r["process_s"]:.3g} | {r["peak_mb"]:.1f} |')
        else:
            print(f'| {r["n"]} | {r["m"]} | {r["status"][:100]} | |')
    k = fit_exponent([(r["n"], r["process_s"]) for r in info_rows if r["status"] == "ok"])
    print(f"  info k = {fmt(k, '.3f')} (process time ~ N^k)")
    try:
        plot(rows, args.plot)
        print(f"wrote {args.csv} and {args.plot}")
    except ImportError as e:  # matplotlib is optional for the table
        print(f"wrote {args.csv}; no plot ({e})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
