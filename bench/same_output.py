#!/usr/bin/python3
"""Two builds of condyn give the same output: every scene under every scheme, validate, compare.

Shows that a refactor changes no output. For each scene of models/scenes and validation/scenes
it runs, with BASELINE and with CANDIDATE (each in a folder of its own):
  - `condyn info SCENE`, whose table of the system each scheme integrates names the schemes the
    scene accepts (a multiplier scheme also under the mixed treatment);
  - `condyn run SCENE --scheme S [--constraints multipliers|mixed] --out out.csv --steps-out
    steps.csv` for each of them, comparing the exit code, standard output and error (masked, see
    below) and every file written, byte for byte;
  - one `condyn run SCENE --out out.h5` (the scene's own scheme), comparing with h5py the
    datasets (names, dtypes, shapes, values bit for bit) and the attributes of file and datasets;
then `condyn validate`, and `condyn compare [SCENE] --no-plots --repeats 1` for a few scenes
(runs.csv and runs.json without their wall_* columns and keys; the other files byte for byte).

Masked in the text (what varies from run to run of one binary, nothing else):
  - `wall 12.3 ms` in a run's summary becomes `wall <ms>`;
  - the progress lines of long runs (`progress: ...`, compare's `...: running, t = ...`), whose
    count depends on the wall time, are dropped;
  - validate's `time ms` cell (the 2-decimal number before a row's verdict word) and compare's
    `wall ms (min-max)` cell (`1.96 (1.91-2.03)`) become `<ms>`, and in that output runs of
    two or more spaces become two (the columns' widths follow the timings);
  - `24.8 GB available` (the machine's free memory in info and run) becomes `<mem> available`.
Numeric columns are never masked: a difference in any result is reported.

    /usr/bin/python3 bench/same_output.py BASELINE CANDIDATE [--jobs 2] [--keep DIR] [--only RE]

Exit 0 when every case is the same, 1 listing the differences, 2 on bad arguments.
"""

import argparse
import concurrent.futures
import csv
import io
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENE_DIRS = ("models/scenes", "validation/scenes")
COMPARE_SCENES = (None, "models/scenes/pendulum.toml", "models/scenes/truss_inclined_roller.toml",
                  "validation/scenes/chapter_5_6_1.toml")
TIMEOUT_S = 1800

WALL_MS = re.compile(r"\bwall [0-9.eE+-]+ ms\b")
MEMORY_AVAILABLE = re.compile(r"\b[0-9.]+ [KMGT]?B available\b")
PROGRESS = re.compile(r"^progress: |: running, t = ")
VALIDATE_TIME = re.compile(r"(?<![\w.])\d+\.\d\d(?=\s+[A-Za-z]+\s*$)")
COMPARE_WALL = re.compile(r"(?<![\w.])\d+(\.\d+)? \(\d+(\.\d+)?-\d+(\.\d+)?\)")
SPACES = re.compile(r" {2,}")
# The info table of the systems each scheme integrates: "  ggl mixed  6  24  7.0 MB".
SCHEME_ROW = re.compile(r"^  ([a-z0-9]+)( mixed)? +(\d+|not applicable)")


def mask(text, table=False):
    """The text with what varies between two runs of one binary masked (the module's doc)."""
    lines = []
    for line in text.splitlines():
        if PROGRESS.search(line):
            continue
        line = MEMORY_AVAILABLE.sub("<mem> available", WALL_MS.sub("wall <ms>", line))
        if table:
            line = SPACES.sub("  ", COMPARE_WALL.sub("<ms>", VALIDATE_TIME.sub("<ms>", line)))
        lines.append(line)
    return "\n".join(lines)


def invoke(binary, args, cwd):
    """(exit code, stdout, stderr) of one run of the binary in the folder cwd."""
    try:
        p = subprocess.run([binary, *args], cwd=cwd, capture_output=True, text=True,
                           errors="replace", timeout=TIMEOUT_S)
        return p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        return "timeout", "", f"no exit after {TIMEOUT_S} s"


def text_differences(a, b, table=False):
    """Differences of two (code, stdout, stderr) triples: [] or the lines saying which."""
    out = []
    if a[0] != b[0]:
        out.append(f"exit code {a[0]} vs {b[0]}")
    for name, x, y in (("stdout", a[1], b[1]), ("stderr", a[2], b[2])):
        x, y = mask(x, table), mask(y, table)
        if x != y:
            out.append(f"{name}: {first_difference(x.splitlines(), y.splitlines())}")
    return out


def first_difference(xs, ys):
    """Where two lists of lines first differ, both lines quoted."""
    for i, (x, y) in enumerate(zip(xs, ys)):
        if x != y:
            return f"line {i + 1}: {x!r} vs {y!r}"
    return f"{len(xs)} vs {len(ys)} lines"


def without_wall_columns(data):
    """runs.csv with its wall_* columns dropped, as a list of rows."""
    rows = list(csv.reader(io.StringIO(data.decode())))
    if not rows:
        return rows
    keep = [i for i, name in enumerate(rows[0]) if not name.startswith("wall")]
    return [[r[i] for i in keep if i < len(r)] for r in rows]


def without_wall_keys(value):
    """runs.json with every key wall_* dropped, at any depth."""
    if isinstance(value, dict):
        return {k: without_wall_keys(v) for k, v in value.items() if not k.startswith("wall")}
    if isinstance(value, list):
        return [without_wall_keys(v) for v in value]
    return value


def same_file(path_a, path_b):
    """True when two output files agree: byte for byte, but for compare's timing columns."""
    a, b = path_a.read_bytes(), path_b.read_bytes()
    if a == b:
        return True
    if path_a.name == "runs.csv":
        return without_wall_columns(a) == without_wall_columns(b)
    if path_a.name == "runs.json":
        return without_wall_keys(json.loads(a)) == without_wall_keys(json.loads(b))
    if path_a.name == "summary.txt":
        return mask(a.decode(errors="replace"), True) == mask(b.decode(errors="replace"), True)
    return False


def hdf5_differences(path_a, path_b):
    """Differences of two HDF5 results: datasets, values and attributes (wall* ones excluded)."""
    import h5py  # only this comparison needs it
    import numpy as np

    def contents(path):
        items = {}

        def visit(name, obj):
            attrs = {k: v for k, v in obj.attrs.items() if "wall" not in k}
            items[name] = (obj[()] if isinstance(obj, h5py.Dataset) else None, attrs)

        with h5py.File(path, "r") as f:
            visit("/", f)
            f.visititems(visit)
        return items

    def equal(x, y):
        x, y = np.asarray(x), np.asarray(y)
        if x.dtype != y.dtype or x.shape != y.shape:
            return False
        if x.dtype.kind in "fc":  # bit for bit, NaN equal to itself
            return x.tobytes() == y.tobytes()
        return bool(np.all(x == y))

    a, b = contents(path_a), contents(path_b)
    out = [f"{path_a.name}: only in one: {sorted(set(a) ^ set(b))}"] if set(a) != set(b) else []
    for name in sorted(set(a) & set(b)):
        (va, aa), (vb, ab) = a[name], b[name]
        if (va is None) != (vb is None) or (va is not None and not equal(va, vb)):
            out.append(f"{path_a.name}: dataset {name} differs")
        if set(aa) != set(ab) or any(not equal(aa[k], ab[k]) for k in aa):
            out.append(f"{path_a.name}: attributes of {name} differ: {aa} vs {ab}")
    return out


def folder_differences(dir_a, dir_b):
    """Differences of the files two runs wrote into their folders."""
    files_a = {p.relative_to(dir_a) for p in dir_a.rglob("*") if p.is_file()}
    files_b = {p.relative_to(dir_b) for p in dir_b.rglob("*") if p.is_file()}
    out = [f"files only in one: {sorted(map(str, files_a ^ files_b))}"] if files_a != files_b else []
    for rel in sorted(files_a & files_b):
        if rel.suffix in (".h5", ".hdf5", ".hdf"):
            out += hdf5_differences(dir_a / rel, dir_b / rel)
        elif not same_file(dir_a / rel, dir_b / rel):
            out.append(f"{rel} differs")
    return out


def schemes_of(info_stdout):
    """[(scheme, constraints flag or None)] the info table says the scene accepts."""
    rows = [m for m in map(SCHEME_ROW.match, info_stdout.splitlines()) if m]
    mixed = {m.group(1) for m in rows if m.group(2)}
    cases = []
    for m in rows:
        if m.group(3) == "not applicable":
            continue
        if m.group(2):
            cases.append((m.group(1), "mixed"))
        else:
            cases.append((m.group(1), "multipliers" if m.group(1) in mixed else None))
    return cases


class Case:
    """One command run with both binaries, each in a folder of its own, and its differences."""

    def __init__(self, name, args, table=False):
        self.name, self.args, self.table = name, args, table

    def run(self, binaries, work):
        results, dirs = [], []
        for which, binary in zip(("baseline", "candidate"), binaries):
            d = work / re.sub(r"[^\w.-]+", "_", self.name) / which
            d.mkdir(parents=True)
            results.append(invoke(binary, self.args, d))
            dirs.append(d)
        return (results[0],
                text_differences(results[0], results[1], self.table) + folder_differences(*dirs))


def run_all(cases, binaries, work, jobs):
    """{case name: (baseline's (code, stdout, stderr), differences)}, at most `jobs` at a time."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {c.name: pool.submit(c.run, binaries, work) for c in cases}
        return {name: f.result() for name, f in futures.items()}


def scene_cases(scene, info_stdout):
    """The runs of one scene: each scheme it accepts to CSV, its own scheme once to HDF5."""
    rel = scene.relative_to(ROOT)
    cases = [Case(f"{rel} hdf5", ["run", str(scene), "--out", "out.h5"])]
    for scheme, constraints in schemes_of(info_stdout):
        args = ["run", str(scene), "--scheme", scheme, "--out", "out.csv", "--steps-out",
                "steps.csv"]
        if constraints:
            args += ["--constraints", constraints]
        cases.append(Case(f"{rel} {scheme} {constraints or ''}".strip(), args))
    return cases


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("baseline", help="the condyn binary of the reference build")
    p.add_argument("candidate", help="the condyn binary to check against it")
    p.add_argument("--jobs", type=int, default=2, choices=(1, 2),
                   help="binaries running at once (at most 2)")
    p.add_argument("--keep", help="keep every run's folder under this (new) folder")
    p.add_argument("--only", type=re.compile, default=re.compile(""), metavar="REGEX",
                   help="only the cases whose name (e.g. 'models/scenes/pendulum.toml ggl "
                        "mixed', 'validate', 'compare ...') it finds")
    args = p.parse_args()
    binaries = [str(Path(b).resolve()) for b in (args.baseline, args.candidate)]
    for b in binaries:
        if not Path(b).is_file():
            p.error(f"{b}: no such binary")
    scenes = [s for d in SCENE_DIRS for s in sorted((ROOT / d).glob("*.toml"))]
    scenes = [s for s in scenes if args.only.search(str(s.relative_to(ROOT)))]

    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="same_output-"))
    work.mkdir(parents=True, exist_ok=bool(not args.keep))
    try:
        infos = run_all([Case(f"{s.relative_to(ROOT)} info", ["info", str(s)]) for s in scenes],
                        binaries, work, args.jobs)
        cases = [Case("validate", ["validate"], table=True)]
        for c in COMPARE_SCENES:
            scene = [str(ROOT / c)] if c else []
            cases.append(Case(f"compare {c or '(built-in chapter truss)'}",
                              ["compare", *scene, "--no-plots", "--repeats", "1", "--out-dir",
                               "cmp"], table=True))
        for s in scenes:
            (code, stdout, _), _ = infos[f"{s.relative_to(ROOT)} info"]
            if code != 0:
                print(f"{s.relative_to(ROOT)}: info exits {code}; its runs are skipped",
                      file=sys.stderr)
                continue
            cases += scene_cases(s, stdout)
        cases = [c for c in cases if args.only.search(c.name)]
        results = {**infos, **run_all(cases, binaries, work, args.jobs)}
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)

    differing = {name: diffs for name, (_, diffs) in results.items() if diffs}
    for name, diffs in differing.items():
        print(f"DIFFERENT {name}")
        for d in diffs:
            print(f"    {d}")
    print(f"{len(results)} cases compared ({len(scenes)} scenes), {len(differing)} differ")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
