"""Runs of the IFToMM benchmark scenes under a chosen scheme through the condyn command, and the
benchmark's measures of each run (validation/iftomm/README.md): the reference point's
trajectory error against the independent reference, the energy drift, the constraint drift, the
CPU time, the steps and how the run ended (finished, failed with its message, refused).

Shared by scheme_table.py (the per-scheme table of docs/validation.md), andrews_agreement.py and
test_scheme_table.py. Debian's /usr/bin/python3 (numpy); no condyn module needed.
"""
import dataclasses
import math
import os
import re
import resource
import subprocess
import tomllib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
REFERENCES = os.path.join(ROOT, "validation", "references", "iftomm")

# Every scheme condyn offers, in docs/schemes.md's order; elimination is coordinate partitioning
# on a mechanism.
SCHEMES = ["elimination", "index1", "baumgarte", "ggl", "index2", "index3", "penalty",
           "projection"]


@dataclasses.dataclass(frozen=True)
class Benchmark:
    """A scene and what its run is measured against: the reference point's columns in a reference
    CSV of validation/references/iftomm/ (one tuple per point: its x, y (, z)), or, where no CSV
    exists (A03), the scene's own `[[check]]` values at a time."""
    key: str
    scene: str
    reference: str | None
    points: tuple
    what: str


BENCHMARKS = [
    Benchmark("A01", "models/scenes/iftomm/A01_simple_pendulum.toml", "A01_reference.csv",
              (("bob.x", "bob.y"),), "P1 (m)"),
    Benchmark("A02", "models/scenes/iftomm/A02_n_four_bar.toml", "A02_reference.csv",
              (("crank0.B.x", "crank0.B.y"),), "B0 (m)"),
    Benchmark("A03", "models/scenes/iftomm/A03_andrews.toml", None, (),
              "body angles at 0.03 s (rad)"),
    Benchmark("A04", "models/scenes/iftomm/A04_bricard.toml", "A04_reference.csv",
              (("link3.J4.x", "link3.J4.y", "link3.J4.z"),), "J4 (m)"),
    Benchmark("A05", "models/scenes/iftomm/A05_flyball_governor.toml", "A05_reference.csv",
              (("slider.z",),), "s, slider height (m)"),
    Benchmark("heavy_top", "models/scenes/heavy_top.toml", "heavy_top_reference.csv",
              (("top.tip.x", "top.tip.y", "top.tip.z"),), "tip (m)"),
    Benchmark("inclined_revolute", "models/scenes/inclined_revolute.toml",
              "inclined_revolute_reference.csv", (("bar.tip.x", "bar.tip.y", "bar.tip.z"),),
              "tip (m)"),
]


def benchmark(key):
    return next(b for b in BENCHMARKS if b.key == key)


def load_scene(bench):
    with open(os.path.join(ROOT, bench.scene), "rb") as f:
        return tomllib.load(f)


def read_csv(path):
    """A CSV's columns as a dict of float arrays, in the file's order."""
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, j] for j, name in enumerate(header)}


# --- TOML -----------------------------------------------------------------------------------


def _toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)  # the shortest text that reads back as the same double
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_toml_value(v)}" for k, v in value.items()) + " }"
    raise TypeError(f"no TOML form for {type(value).__name__}")


def _key(key):
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else _toml_value(key)


def toml_text(scene):
    """A scene dict (as tomllib reads it) as TOML text: top-level values, then each table and each
    array of tables, their own values inline."""
    lines = [f"{_key(k)} = {_toml_value(v)}" for k, v in scene.items()
             if not isinstance(v, dict) and not _is_table_array(v)]
    for name, value in scene.items():
        tables = [value] if isinstance(value, dict) else value if _is_table_array(value) else []
        header = f"[{_key(name)}]" if isinstance(value, dict) else f"[[{_key(name)}]]"
        for table in tables:
            lines += ["", header] + [f"{_key(k)} = {_toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def _is_table_array(value):
    return isinstance(value, list) and value != [] and all(isinstance(v, dict) for v in value)


def study_scene(bench, t_end=None):
    """The benchmark's scene for a study run: its `[[check]]` tables removed (the study measures
    the run itself; a check's reference would also have to reach t_end), t_end shortened when
    asked (to a multiple of output_step, so the output times stay the reference's rows)."""
    scene = load_scene(bench)
    scene.pop("check", None)
    if t_end is not None:
        step = scene["solve"]["output_step"]
        if abs(t_end / step - round(t_end / step)) > 1e-9:
            raise ValueError(f"{bench.key}: t_end {t_end} is not a multiple of {step}")
        scene["solve"]["t_end"] = float(t_end)
    return scene


# --- runs -----------------------------------------------------------------------------------


@dataclasses.dataclass
class Run:
    """One run of a benchmark under a scheme. status: finished, failed (the integrator gave up or
    its budget ran out: `message`, `t_reached`) or refused (bad input for this scheme, exit 2).
    error: the reference point's largest distance from the reference over the output rows (over
    the rows written before a failure, for a failed run); energy_drift: max |energy_error| over
    max(|E(0)|, the largest kinetic energy); drift_position, drift_velocity: the summary's max
    constraint residuals over every step (a failed run's: over its output rows); cpu_s: user +
    system CPU seconds of the process; variant: the flags that set this run apart from the
    scene's own settings (--atol 1e-10)."""
    key: str
    scheme: str
    status: str
    variant: tuple = ()
    message: str = ""
    t_end: float = math.nan
    t_reached: float = math.nan
    cpu_s: float = math.nan
    steps: int | None = None
    drift_position: float = math.nan
    drift_velocity: float = math.nan
    error: float = math.nan
    energy_drift: float = math.nan
    columns: dict | None = dataclasses.field(default=None, repr=False)


def run_scheme(condyn, bench, scheme, work_dir, t_end=None, flags=(), variant=()):
    """Runs `bench`'s study scene (study_scene) under `scheme` with `condyn run` in work_dir;
    `flags` are more command-line flags (a budget: --max-steps N, --max-wall-time S), `variant`
    flags that change the run itself (--atol 1e-10), kept in its name and its Run.
    Returns the Run with its measures."""
    scene = study_scene(bench, t_end)
    name = "_".join([bench.key, scheme] + [re.sub(r"[^A-Za-z0-9.+-]", "", f) for f in variant])
    stem = os.path.join(work_dir, name)
    with open(stem + ".toml", "w") as f:
        f.write(toml_text(scene))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run([str(condyn), "run", stem + ".toml", "--scheme", scheme, "--out",
                           stem + ".csv", *variant, *flags], capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    run = Run(bench.key, scheme, "finished", tuple(variant), t_end=scene["solve"]["t_end"],
              cpu_s=(after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime))
    text = proc.stdout + proc.stderr
    if proc.returncode != 0:
        run.status = "refused" if proc.returncode == 2 else "failed"
        run.message = failure_message(proc.stderr)
        reached = re.search(r"reached t = (\S+) of t_end", proc.stderr)
        run.t_reached = float(reached.group(1)) if reached else math.nan
    else:
        summary = re.search(r"^\w+: reached t = (\S+), (\d+) steps", text, re.M)
        run.t_reached, run.steps = float(summary.group(1).rstrip(",")), int(summary.group(2))
        drift = re.search(r"max drift position (\S+) velocity (\S+?)[ ,;\n]", text)
        run.drift_position, run.drift_velocity = float(drift.group(1)), float(drift.group(2))
    out = stem + (".csv" if run.status == "finished" else ".partial.csv")
    if run.status != "refused" and os.path.exists(out):
        run.columns = read_csv(out)
        measure(run, bench)
    return run


def failure_message(stderr):
    """The error line without its `error: FILE: ` prefix and the solver's long tail."""
    line = next((l for l in stderr.splitlines() if l.startswith("error:")), stderr.strip())
    line = re.sub(r"^error: [^:]*\.toml: ", "", line)
    return line.split(": IDASolve:")[0].split(": CVode:")[0]


def measure(run, bench):
    """The run's trajectory error, energy drift and, for a failed run (whose summary is not
    printed), its constraint drift over the output rows. Nothing from a run that wrote no row
    after t = 0."""
    cols = run.columns
    if len(cols["t"]) < 2:
        return
    if bench.reference is not None:
        run.error = point_error(cols, read_csv(os.path.join(REFERENCES, bench.reference)),
                                bench.points)
    else:
        run.error = check_value_error(cols, load_scene(bench))
    if "energy_error" in cols:
        scale = max(abs(cols["energy"][0]), float(np.max(cols["energy_kinetic"])))
        run.energy_drift = float(np.max(np.abs(cols["energy_error"]))) / scale
    if math.isnan(run.drift_position) and "drift_position" in cols:
        run.drift_position = float(np.max(cols["drift_position"]))
        run.drift_velocity = float(np.max(cols["drift_velocity"]))


def point_error(cols, ref, points):
    """max over the run's rows and the points of |p(t) - p_ref(t)|, the rows matched to the
    reference's by time (the scenes' output times are the reference's rows)."""
    n = len(cols["t"])
    if n == 0:
        return math.nan
    if n > len(ref["t"]) or not np.allclose(cols["t"], ref["t"][:n], rtol=0, atol=1e-9):
        raise ValueError("the run's output times are not the reference's rows")
    worst = 0.0
    for point in points:
        diff = np.stack([cols[c] - ref[c][:n] for c in point])
        worst = max(worst, float(np.max(np.sqrt(np.sum(diff ** 2, axis=0)))))
    return worst


def check_value_error(cols, scene):
    """max over the scene's `[[check]]` values at a time of |computed - value| (the published
    reference of A03 at t = 0.03); NaN when the run did not reach them."""
    worst = math.nan
    for check in scene.get("check", []):
        rows = np.flatnonzero(np.isclose(cols["t"], check["at"], rtol=0, atol=1e-12))
        if len(rows) == 0:
            return math.nan
        err = abs(cols[check["quantity"]][rows[0]] - check["value"])
        worst = err if math.isnan(worst) else max(worst, err)
    return worst
