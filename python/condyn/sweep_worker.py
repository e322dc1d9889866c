"""One run of a sweep, on a Dask worker (docs/sweep.md): the scene and its data files arrive with
the task (no shared file system), are written into a temporary folder and run through condyn.run;
what returns is the run's row: its status, steps, wall time, the peaks of the kept columns, and
when asked the scene's [[check]] verdicts and the bytes of its HDF5 file (condyn run --out).
"""

import os
import tempfile

import numpy as np

import condyn
from .sweep_file import map_files

# Statuses besides "ok" and the integrator's failure kinds (IntegrationError.kind).
SCENE_ERROR = "scene_error"    # the parser or builder refused this run's combination of values
ERROR = "error"                # anything else the run raised (its message in the row's message)
NO_COLUMN = "no_column"        # a kept column the result does not have: the sweep stops (exit 2)
NOT_RUN = ("interrupted",)     # stopped from outside: no row, the run is done again on restart


def run_one(scene, files, peaks, checks=False, keep_result=False):
    """Runs `scene` (a dict; its `file` keys name entries of `files`, name -> bytes) and returns
    {status, steps, wall_s, peaks: {column: (peak, time)}, message}, with `checks` (the scene's
    [[check]] verdicts, verdict_of) when asked and the run succeeded, and `result` (the bytes
    of the HDF5 file `condyn run --out RESULT.h5` writes, or of its partial file for a failed
    run) when `keep_result` and the run wrote one. Never raises for a run's failure: the
    failure is the row's status."""
    with tempfile.TemporaryDirectory(prefix="condyn-sweep-") as folder:
        local = {}
        for i, name in enumerate(sorted(files)):
            local[name] = os.path.join(folder, f"{i}_{os.path.basename(name)}")
            with open(local[name], "wb") as f:
                f.write(files[name])
        scene = map_files(scene, local.__getitem__)
        # Named apart from the scene's files (which start with their index): the result, or the
        # partial file beside it where a failed run keeps its rows (docs/cli.md).
        out = os.path.join(folder, "result.h5") if keep_result else None
        row, result = _run(scene, peaks, checks, out)
        if checks and row["status"] == "ok":
            row["checks"] = verdict_of(result.checks)
        for written in ([out, os.path.join(folder, "result.partial.h5")] if out else []):
            if os.path.exists(written):
                with open(written, "rb") as f:
                    row["result"] = f.read()
    return row


def _run(scene, peaks, checks, out=None):
    """(the run's row, its Result or None); with `checks`, the Result's checks are evaluated on
    its own rows (condyn.run(checks=True): one run, not a second one for condyn.check); with
    `out`, the result is written there (condyn.run(out=...))."""
    try:
        result = condyn.run(scene, checks=checks, out=out)
    except condyn.IntegrationError as e:
        return _row(e.kind or "unknown", e.result, {}, str(e)), e.result
    except condyn.SceneError as e:
        return _row(SCENE_ERROR, None, {}, str(e)), None
    except Exception as e:  # the row says what it was; the sweep goes on
        return _row(ERROR, None, {}, f"{type(e).__name__}: {e}"), None
    columns = result_columns(result)
    missing = [p for p in peaks if p not in columns]
    if missing:
        return _row(NO_COLUMN, result, {}, f"no column {', '.join(map(repr, missing))} in the "
                    f"run's result (its columns: {', '.join(columns)})"), None
    return _row("ok", result, {p: peak(result.t, columns[p]) for p in peaks}, ""), result


def verdict_of(verdict):
    """The row's part of condyn.check's dict for the run (Result.checks): {passed: every check
    held and the constraints did not drift, each: [(passed, computed)] per check, in the scene's
    order}."""
    return {"passed": bool(verdict["passed"]),
            "each": [(bool(c["passed"]), float(c["computed"])) for c in verdict["checks"]]}


def peak(t, column):
    """(max |column| over the output rows, the first time it is reached); (nan, nan) for none."""
    if len(column) == 0:
        return (float("nan"), float("nan"))
    i = int(np.argmax(np.abs(column)))
    return (float(abs(column[i])), float(t[i]))


def result_columns(r):
    """The columns `condyn run` would write for the result, by their CSV names (docs/cli.md):
    every quantity the result holds, whatever the scene's [output] selects."""
    columns = {"t": r.t}
    mechanism = r.velocity_names != r.dof_names  # a mechanism names its own columns

    def add(names, rows, prefix):
        if rows is not None:
            for j, name in enumerate(names):
                columns[name if mechanism else prefix + name] = rows[:, j]

    add(r.dof_names, r.u, "")
    add(r.velocity_names, r.v, "vel_")
    add(r.acceleration_names, r.a, "acc_")
    if not mechanism:
        add(r.acceleration_names, r.a_abs, "acc_abs_")
    add(r.reaction_names, r.reaction, "reaction_")
    for j, name in enumerate(r.constraint_names):
        columns["lambda_" + name] = r.multiplier[:, j]
    columns["drift_position"], columns["drift_velocity"] = r.drift[:, 0], r.drift[:, 1]
    if r.energy_balance is not None:
        for j, name in enumerate(r.energy_columns):
            columns[name] = r.energy_balance[:, j]
    if r.points is not None:
        for j, name in enumerate(r.point_names):
            columns[name] = r.points[:, j]
    for j, name in enumerate(r.derived_names):  # [[derived]]: after the points, as in the CSV
        columns[name] = r.derived[:, j]
    return columns


def _row(status, result, peaks, message):
    summary = result.summary if result is not None else {}
    return {"status": status, "steps": summary.get("steps"), "wall_s": summary.get("wall_s"),
            "peaks": peaks, "message": message}
