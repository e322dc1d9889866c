"""The IFToMM benchmark table of docs/validation.md: every scheme condyn offers on every benchmark
scene (A01 to A05, the heavy top, the inclined revolute axis), each run measured as the
benchmark reports results: the reference point's trajectory error against the independent
reference (validation/references/iftomm/), energy drift, constraint drift, CPU time, steps, and
how the run ended (finished, failed with its message, refused with its reason).

    /usr/bin/python3 validation/iftomm/scheme_table.py --condyn build/condyn --out-dir iftomm-table

writes table.md (the Markdown table) and runs.csv (every figure) in --out-dir and prints the
table. Every run has a budget (--max-steps, --max-wall-time), so the study never hangs: a run
beyond it is reported as failed with the budget named (--scene-budget A02=20000,120 gives a
scene its own: 20000 steps, 120 s). --scenes and --schemes select; --t-end
KEY=T shortens a scene (T a multiple of its output_step); --also "KEY SCHEME FLAGS..." adds a run
with other settings (--also "A01 ggl --atol 1e-10"), after the others.
"""
import argparse
import csv
import datetime
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runs as ir  # noqa: E402

FIELDS = ["scene", "scheme", "variant", "status", "t_end", "t_reached", "error", "energy_drift",
          "drift_position", "drift_velocity", "cpu_s", "steps", "message"]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--condyn", default=os.path.join(ir.ROOT, "build", "condyn"))
    p.add_argument("--out-dir", default="iftomm-table")
    p.add_argument("--scenes", default=",".join(b.key for b in ir.BENCHMARKS))
    p.add_argument("--schemes", default=",".join(ir.SCHEMES))
    p.add_argument("--max-steps", type=int, default=10_000_000,
                   help="step budget of every run (default 1e7)")
    p.add_argument("--max-wall-time", type=float, default=300.0,
                   help="wall-time budget of every run in seconds (default 300)")
    p.add_argument("--t-end", action="append", default=[], metavar="KEY=T",
                   help="shorten a scene's run to T seconds (repeatable)")
    p.add_argument("--scene-budget", action="append", default=[], metavar="KEY=STEPS,SECONDS",
                   help="a scene's own budget, instead of --max-steps and --max-wall-time "
                        "(repeatable)")
    p.add_argument("--also", action="append", default=[], metavar="'KEY SCHEME FLAGS'",
                   help="one more run, with flags of condyn run (repeatable)")
    return p.parse_args(argv)


def figure(x, digits=2):
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}g}"


def short_reason(message):
    """A refusal's reason without the flag it names and the advice after it."""
    reason = message.removeprefix("--scheme: ")
    return reason.split(" (")[0].split("; ")[0]


def short_failure(message):
    """A failure as its kind and the solver's flag (`Newton convergence failures
    (IDA_CONV_FAIL)`), or the budget it ran out of; runs.csv keeps the whole message."""
    kind = re.search(r"under \w+ \(([^)]*)\)", message)
    if kind is None:
        return message
    budget = re.search(r"(ran longer than [^(]*|took more than [^(]*?) \(", message)
    flag = re.search(r"\b(IDA_[A-Z_]+|CV_[A-Z_]+)\b", message)
    detail = budget.group(1).strip() if budget else flag.group(1) if flag else ""
    return f"{kind.group(1)} ({detail})" if detail else kind.group(1)


def table_row(run, bench):
    if run.status == "finished":
        status = "finished"
    elif run.status == "failed":
        reached = f" at t = {run.t_reached:.4g}" if not math.isnan(run.t_reached) else ""
        status = f"**failed**{reached}: {short_failure(run.message)}"
    else:
        status = f"refused: {short_reason(run.message)}"
    error = figure(run.error)
    if run.status == "failed" and error != "—":
        error += " (rows to the failure)"
    cpu = figure(run.cpu_s, 3) if run.status != "refused" else "—"
    scheme = " ".join((run.scheme,) + run.variant)
    return (f"| {bench.key} | {scheme} | {error} | {figure(run.energy_drift)} | "
            f"{figure(run.drift_position)} | {cpu} | {run.steps or '—'} | {status} |")


def markdown(runs, version, when):
    lines = [f"{version}, {when}; CPU seconds of each `condyn run` process.", "",
             "| scene | scheme | reference point's error | energy drift | position drift | "
             "CPU s | steps | status |", "|---|---|---|---|---|---|---|---|"]
    lines += [table_row(r, ir.benchmark(r.key)) for r in runs]
    lines += ["", "Reference points: " + "; ".join(
        f"{b.key} {b.what}" for b in ir.BENCHMARKS if any(r.key == b.key for r in runs)) + ". "
        "Error: the largest distance from the reference over the output rows (of a failed run, "
        "over the rows before its failure). Energy drift: max |energy_error| / max(|E(0)|, max "
        "kinetic energy). Position drift: the largest constraint residual over every step (of a "
        "failed run, over its output rows)."]
    return "\n".join(lines) + "\n"


def csv_row(r):
    return [r.key, r.scheme, " ".join(r.variant), r.status, r.t_end, r.t_reached, r.error,
            r.energy_drift, r.drift_position, r.drift_velocity, r.cpu_s,
            "" if r.steps is None else r.steps, r.message]


def append_csv(path, rows):
    with open(path, "a", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(rows)


def main(argv=None):
    args = parse_args(argv)
    t_ends = dict(item.split("=") for item in args.t_end)
    os.makedirs(os.path.join(args.out_dir, "runs"), exist_ok=True)
    default_budget = [str(args.max_steps), str(args.max_wall_time)]
    budgets = {key: value.split(",") for key, value in
               (item.split("=") for item in args.scene_budget)}
    version = subprocess.run([args.condyn, "--version"], capture_output=True, text=True,
                             check=True).stdout.strip()
    runs_csv = os.path.join(args.out_dir, "runs.csv")
    open(runs_csv, "w").close()
    append_csv(runs_csv, [FIELDS])  # each run's row follows as soon as it ends
    plan = [(key, scheme, ()) for key in args.scenes.split(",")
            for scheme in args.schemes.split(",")]
    plan += [(words[0], words[1], tuple(words[2:])) for words in map(str.split, args.also)]
    runs = []
    for key, scheme, variant in plan:
        t_end = float(t_ends[key]) if key in t_ends else None
        steps, seconds = budgets.get(key, default_budget)
        flags = ["--max-steps", steps, "--max-wall-time", seconds]
        run = ir.run_scheme(args.condyn, ir.benchmark(key), scheme,
                            os.path.join(args.out_dir, "runs"), t_end, flags, variant)
        print(f"{key} {scheme} {' '.join(variant)}: {run.status}, error {figure(run.error)}, "
              f"CPU {figure(run.cpu_s, 3)} s {run.message}", file=sys.stderr, flush=True)
        runs.append(run)
        append_csv(runs_csv, [csv_row(run)])
    when = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    text = markdown(runs, version, when)
    with open(os.path.join(args.out_dir, "table.md"), "w") as f:
        f.write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
