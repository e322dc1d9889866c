#!/usr/bin/python3
"""The cost of a run under `condyn sweep` against the same scene run alone by `condyn run`
(issue 46 item 7; the figures are in docs/benchmarks.md, "condyn sweep: per-run overhead").

The study: the first RECORDS records of models/scenes/ida/frame_ida.toml (El Centro, then the
synthetic ones) times its first LEVELS peak ground accelerations, on the five-storey frame
(models/scenes/shear_frame_el_centro.toml): N = RECORDS x LEVELS runs. Each repeat times, in this
order, so that the machine's load falls on all alike, wall time and the CPU time of the child
processes (condyn run; the sweep with its cluster's scheduler and workers):
  - `condyn run` of each run's scene, one process after the other (--out a CSV per run);
  - `condyn sweep` of the study with --workers 1, then of its first run alone (the fixed cost:
    the local cluster's start and close), then the same with --workers 2, each into a new folder.
Each repeat gives its own figures (per run: condyn run's time, the sweep's marginal time
(T(N) - T(1)) / (N - 1), each beside the runs' integration time, the `wall` of their summaries;
the ratio of the two; runs per second), and the medians over the repeats are printed: a loaded
machine slows a whole repeat, and the ratios within one stay comparable. Then one run of a
lattice truss of --frame-dofs DOFs (bench/lattice.py, clamped at one end) under the synthetic
record syn01 across it (every uy DOF), through a one-run sweep: the projection of a 44-record x
20-level IDA (880 runs) on such a model from its integration time and the measured overhead.

    PYTHONPATH=build/python /usr/bin/python3 bench/sweep_overhead.py [--records 4] [--levels 5]
        [--repeat 5] [--condyn build/condyn] [--frame-dofs 1e4] [--frame-t-end 20]
"""

import argparse
import csv
import os
import re
import resource
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
IDA = os.path.join(ROOT, "models", "scenes", "ida")
FRAME = os.path.join(ROOT, "models", "scenes", "shear_frame_el_centro.toml")
EL_CENTRO = os.path.join(ROOT, "models", "scenes", "data", "el_centro_1940_ns.csv")
LEVELS = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0]  # frame_ida.toml's pga, m/s^2


def records(count):
    synthetic = [os.path.join(IDA, "records", f"syn{k:02d}.csv") for k in range(1, 11)]
    return ([EL_CENTRO] + synthetic)[:count]


def study_text(scene, files, levels, peaks):
    return (f"scene = {scene!r}\n[records]\nfiles = {files!r}\ncolumn = \"acceleration_g\"\n"
            f"scale = 9.81\n[scale]\npga = {levels!r}\n[keep]\npeaks = {peaks!r}\n")


def scene_texts(sweep_file):
    """Each run's scene as a file `condyn run` reads: the frame's text with its [ground_motion]
    acceleration replaced by the run's (the sweep's own scaling, read back from its expansion)."""
    from condyn.sweep_file import expand, read_sweep
    with open(FRAME) as f:
        frame = f.read()
    line = re.compile(r"^acceleration = .*$", re.M)
    assert len(line.findall(frame)) == 1
    texts = []
    for run in expand(read_sweep(sweep_file)):
        a = run.scene["ground_motion"]["acceleration"]
        table = (f'acceleration = {{ type = "table", file = "{run.files[a["file"]]}", column = '
                 f'"{a["column"]}", scale = {a["scale"]!r} }}')
        texts.append(line.sub(table, frame))
    return texts


def wall_of(brief):
    """The integration wall time (s) in `condyn run`'s summary line: `wall 13.3 ms`."""
    m = re.search(r"wall ([0-9.]+) (ms|s)\b", brief)
    return float(m.group(1)) / (1000.0 if m.group(2) == "ms" else 1.0)


def timed(work):
    """(work's result, wall s, CPU s of the child processes it waited for: condyn run, or the
    sweep with its cluster's worker processes)."""
    cpu = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    result = work()
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return result, wall, after.ru_utime + after.ru_stime - cpu.ru_utime - cpu.ru_stime


def run_one_by_one(condyn, scenes, folder):
    """([integration wall], [steps]) of `condyn run` on each scene in turn."""
    walls, steps = [], []
    for i, scene in enumerate(scenes):
        done = subprocess.run([condyn, "run", scene, "--out", os.path.join(folder, f"{i}.csv")],
                              capture_output=True, text=True, check=True)
        walls.append(wall_of(done.stderr + done.stdout))
        steps.append(int(re.search(r"(\d+) steps", done.stderr + done.stdout).group(1)))
    return walls, steps


def sweep(command, sweep_file, workers, out):
    """The results' rows (dicts) of one sweep into the new folder `out`."""
    done = subprocess.run(command + [sweep_file, "--workers", str(workers), "--out", out],
                          capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(done.args)}: exit {done.returncode}\n{done.stderr}")
    with open(os.path.join(out, "results.csv"), newline="") as f:
        return list(csv.DictReader(f))


def measure(args, folder):
    """Per repeat: {what: (wall, CPU, the runs' integration walls)} for run (condyn run one by
    one), sweepW (the study, W workers) and oneW (its first run alone)."""
    runs = os.path.join(folder, "runs")
    os.makedirs(runs)
    full, one = os.path.join(folder, "study.toml"), os.path.join(folder, "one.toml")
    files, levels = records(args.records), LEVELS[:args.levels]
    with open(full, "w") as f:
        f.write(study_text(FRAME, files, levels, ["ul5"]))
    with open(one, "w") as f:
        f.write(study_text(FRAME, files[:1], levels[:1], ["ul5"]))
    scenes = []
    for i, text in enumerate(scene_texts(full)):
        scenes.append(os.path.join(folder, f"scene{i}.toml"))
        with open(scenes[-1], "w") as f:
            f.write(text)
    command = shlex.split(args.sweep) if args.sweep else [args.condyn, "sweep"]
    repeats = []
    for r in range(args.repeat):
        (walls, steps), wall, cpu = timed(lambda: run_one_by_one(args.condyn, scenes, runs))
        t = {"run": (wall, cpu, walls)}
        for w in (1, 2):
            for name, study in ((f"sweep{w}", full), (f"one{w}", one)):
                out = os.path.join(folder, f"{name}_{r}")
                rows, wall, cpu = timed(lambda: sweep(command, study, w, out))
                t[name] = (wall, cpu, [float(row["wall_s"]) for row in rows])
                if study == full:  # the same runs: the sweep's steps are condyn run's
                    assert [int(row["steps"]) for row in rows] == steps, "other runs"
        print(f"repeat {r + 1}: " + ", ".join(f"{k} {v[0]:.2f} s" for k, v in t.items()),
              file=sys.stderr)
        repeats.append(t)
    return len(scenes), repeats


def frame_run(args, command, folder):
    """(DOFs, integration wall, steps, the one-run sweep's wall and CPU) of the lattice under
    syn01."""
    lattice = os.path.join(folder, "lattice")
    subprocess.run([sys.executable, os.path.join(ROOT, "bench", "lattice.py"), "--dofs",
                    str(args.frame_dofs), "--out", lattice, "--t-end", str(args.frame_t_end),
                    "--output-step", "0.02"], check=True, capture_output=True)
    scene = os.path.join(lattice, "lattice.toml")
    with open(scene) as f:
        text = f.read()
    n = int(re.search(r"Lattice truss, (\d+) DOFs", text).group(1))
    uy = ", ".join(f"u{d} = 1.0" for d in range(2, n + 1, 2))
    ground = (f"[ground_motion]\nacceleration = {{ type = \"table\", file = "
              f"\"{records(2)[1]}\", column = \"acceleration_g\", scale = 9.81 }}\n"
              f"influence = {{ {uy} }}\n\n")
    text = re.sub(r"\[\[load\]\]\n.*?\n\n", ground, text, flags=re.S)
    with open(scene, "w") as f:
        f.write(text)
    study = os.path.join(folder, "lattice_study.toml")
    with open(study, "w") as f:
        f.write(f"scene = {scene!r}\n[keep]\npeaks = [\"drift_position\"]\n")
    rows, total, cpu = timed(lambda: sweep(command, study, 1, os.path.join(folder, "lattice_out")))
    assert rows[0]["status"] == "ok", rows[0]
    return n, float(rows[0]["wall_s"]), int(rows[0]["steps"]), total, cpu


def per_repeat(n, t):
    """The figures of one repeat, each from its own timings (the load alike for all)."""
    run_wall, run_cpu, run_walls = t["run"]
    f = {"run": run_wall / n, "run_cpu": run_cpu / n, "integration_run": sum(run_walls) / n,
         "run_overhead": (run_wall - sum(run_walls)) / n}
    for w in (1, 2):
        (wall, cpu, walls), (wall1, cpu1, walls1) = t[f"sweep{w}"], t[f"one{w}"]
        f[f"rate{w}"] = n / wall
        f[f"marginal{w}"] = (wall - wall1) / (n - 1)
        f[f"fixed{w}"] = wall1 - f[f"marginal{w}"]
        f[f"cpu{w}"] = (cpu - cpu1) / (n - 1)
    (wall, _, walls), (wall1, _, walls1) = t["sweep1"], t["one1"]
    # One worker runs one run at a time: what is not integration is the sweep's.
    f["integration_sweep"] = sum(walls) / n
    f["sweep_overhead"] = ((wall - sum(walls)) - (wall1 - sum(walls1))) / (n - 1)
    f["ratio"] = f["marginal1"] / f["run"]
    f["cpu_ratio"] = f["cpu1"] / f["run_cpu"]
    return f


def report(n, repeats, frame):
    figures = [per_repeat(n, t) for t in repeats]
    m = {k: statistics.median(f[k] for f in figures) for k in figures[0]}
    ms = lambda x: f"{x * 1e3:.1f} ms"  # noqa: E731
    print(f"{n} runs of the five-storey frame; medians over {len(repeats)} repeats of the "
          "figures each repeat gives")
    print(f"condyn run, one by one: {ms(m['run'])} a run, CPU {ms(m['run_cpu'])}; integration "
          f"{ms(m['integration_run'])}, beyond it {ms(m['run_overhead'])}")
    print(f"condyn sweep --workers 1, marginal: {ms(m['marginal1'])} a run, CPU "
          f"{ms(m['cpu1'])}; integration {ms(m['integration_sweep'])}, beyond it "
          f"{ms(m['sweep_overhead'])}; fixed {m['fixed1']:.2f} s")
    print(f"a run under the sweep against condyn run: {m['ratio']:.2f} x the wall time, "
          f"{m['cpu_ratio']:.2f} x the CPU")
    for w in (1, 2):
        print(f"--workers {w}: {m[f'rate{w}']:.2f} runs/s over the {n} runs, marginal "
              f"{1 / m[f'marginal{w}']:.2f} runs/s, CPU {ms(m[f'cpu{w}'])} a run, fixed "
              f"{m[f'fixed{w}']:.2f} s")
    if frame:
        dofs, wall, steps, total, cpu = frame
        per_run = wall + max(m["sweep_overhead"], 0.0)
        print(f"lattice of {dofs} DOFs under syn01: {steps} steps, {wall:.2f} s of integration "
              f"(a one-run sweep: {total:.2f} s, CPU {cpu:.2f} s)")
        for w in (1, 2):
            hours = (880 * per_run / w + m[f"fixed{w}"]) / 3600
            print(f"projection, 44 records x 20 levels = 880 runs on {w} worker(s) with a core "
                  f"each: {hours:.1f} h")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--records", type=int, default=4, help="records of frame_ida.toml (1-11)")
    p.add_argument("--levels", type=int, default=5, help="its PGA levels (1-10)")
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--condyn", default=os.path.join(ROOT, "build", "condyn"))
    p.add_argument("--sweep", help="the sweep command (default: CONDYN sweep), e.g. "
                   "'/usr/bin/python3 -m condyn.sweep_cli'")
    p.add_argument("--frame-dofs", type=float, default=1e4,
                   help="the projection's model size (0: no projection)")
    p.add_argument("--frame-t-end", type=float, default=20.0, help="its run's duration, s")
    args = p.parse_args(argv)
    if not (1 <= args.records <= 11 and 1 <= args.levels <= 10 and
            args.records * args.levels >= 2):
        p.error("--records 1-11, --levels 1-10, at least two runs")
    with tempfile.TemporaryDirectory(prefix="condyn-sweep-bench-") as folder:
        n, repeats = measure(args, folder)
        command = shlex.split(args.sweep) if args.sweep else [args.condyn, "sweep"]
        frame = frame_run(args, command, folder) if args.frame_dofs > 0 else None
    report(n, repeats, frame)
    return 0


if __name__ == "__main__":
    sys.exit(main())
