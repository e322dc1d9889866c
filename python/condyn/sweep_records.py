"""The sweep file's [records] and [scale] (docs/sweep.md): a suite of accelerograms and the
intensities each is scaled to, as two axes over the scene's [ground_motion] acceleration (the
results' columns `record`, and `scale` or `pga`). Records are named relative to the sweep file;
each becomes the scene's table `{ type = "table", file, column, scale }`.
"""

import math
import os

import numpy as np

from .sweep_file import Axis, SweepError, _absolute, _fail

_RECORDS_KEYS = ("files", "folder", "column", "scale")
_INTENSITIES = ("factors", "pga", "sa")
_SCALE_KEYS = _INTENSITIES + ("period", "damping")


def records_axes(sweep, table):
    """The axes [records] and [scale] ask for, records first (none when neither is there)."""
    records, scale = table.get("records"), table.get("scale")
    if records is None and scale is None:
        return []
    if not isinstance(sweep.scene.get("ground_motion"), dict):
        _fail(sweep.file, "records" if records is not None else "scale",
              f"the scene {sweep.scene_file} has no [ground_motion] to apply records to")
    recorded = sweep.scene["ground_motion"].get("acceleration")
    if records is None and not (isinstance(recorded, dict) and "file" in recorded):
        _fail(sweep.file, "scale", "scales a recorded ground motion: the scene's "
              "[ground_motion] acceleration must be a table ({ type = \"table\", file = ... }), "
              "or give [records]")
    for axis in sweep.axes:
        if axis.key.startswith("ground_motion.acceleration"):
            _fail(sweep.file, "records" if records is not None else "scale",
                  f"the axis over {axis.key} sweeps the ground motion too: give one or the other")
    axes = [_records_axis(sweep, records)] if records is not None else []
    return axes + ([_scale_axis(sweep, scale)] if scale is not None else [])


def _records_axis(sweep, records):
    path = sweep.file
    if not isinstance(records, dict):
        _fail(path, "records", "expected a table ([records] with files or folder)")
    for k in records:
        if k not in _RECORDS_KEYS:
            _fail(path, f"records.{k}", f"unknown key ([records] has {', '.join(_RECORDS_KEYS)})")
    if ("files" in records) == ("folder" in records):
        _fail(path, "records", "give files (a list of record files) or folder (every .csv "
              "file in it), one of the two")
    here = os.path.dirname(os.path.abspath(path))
    if "folder" in records:
        folder = records["folder"]
        full = os.path.join(here, folder) if isinstance(folder, str) else None
        if full is None or not os.path.isdir(full):
            _fail(path, "records.folder", f"no such folder: {folder!r}")
        names = sorted(n for n in os.listdir(full) if n.endswith(".csv"))
        if not names:
            _fail(path, "records.folder", f"{full} holds no record (no .csv file)")
        files = [os.path.join(folder, n) for n in names]
    else:
        files = records["files"]
        if not isinstance(files, list) or not files or \
                not all(isinstance(f, str) and f for f in files):
            _fail(path, "records.files", f"expected a non-empty list of file names (got {files!r})")
        for i, f in enumerate(files):
            if f in files[:i]:
                _fail(path, "records.files", f"'{f}' is listed twice")
            if not os.path.isfile(os.path.join(here, f)):
                _fail(path, "records.files", f"no such file: {os.path.join(here, f)}")
    column = records.get("column")
    if column is not None and (not isinstance(column, str) or not column):
        _fail(path, "records.column", f"expected a column name (got {column!r})")
    unit = records.get("scale", 1.0)
    if isinstance(unit, bool) or not isinstance(unit, (int, float)) or not math.isfinite(unit) \
            or unit == 0:
        _fail(path, "records.scale", f"expected a finite nonzero number (got {unit!r})")

    def apply(sweep, scene, axis, value, where):
        record = os.path.relpath(os.path.join(here, value), os.path.dirname(sweep.scene_file))
        table = {"type": "table", "file": record, "scale": float(unit)}
        if column is not None:
            table["column"] = column
        scene["ground_motion"]["acceleration"] = table

    return Axis("record", [], files, apply, "records")


def _scale_axis(sweep, scale):
    path = sweep.file
    if not isinstance(scale, dict):
        _fail(path, "scale", "expected a table ([scale] with factors, pga or sa)")
    for k in scale:
        if k not in _SCALE_KEYS:
            _fail(path, f"scale.{k}", f"unknown key ([scale] has {', '.join(_SCALE_KEYS)})")
    kinds = [k for k in _INTENSITIES if k in scale]
    if len(kinds) != 1:
        _fail(path, "scale", "give factors (multiples of each record), pga (target peak ground "
              "accelerations) or sa (target spectral accelerations at period), one of the three")
    kind, values = kinds[0], scale[kinds[0]]
    if not isinstance(values, list) or not values or not all(_positive(v) for v in values):
        _fail(path, f"scale.{kind}", f"expected a non-empty list of positive numbers "
              f"(got {values!r})")
    for i, v in enumerate(values):
        if v in values[:i]:
            _fail(path, f"scale.{kind}", f"{v} is listed twice")
    measure = _measure(path, kind, scale)
    measured = {}  # each record's intensity at scale 1, read once

    def apply(sweep, scene, axis, value, where):
        table = scene["ground_motion"]["acceleration"]
        old = table.get("scale", 1.0)
        if kind == "factors":
            table["scale"] = old * value
            return
        record = _absolute(sweep, table["file"])
        if record not in measured:
            measured[record] = measure(*_read_record(record, table.get("column")))
        if measured[record] == 0.0:
            _fail(path, f"scale.{kind}", f"the record {record} is zero throughout: it cannot be "
                  "scaled to an intensity")
        table["scale"] = math.copysign(value / measured[record], old)

    return Axis("scale" if kind == "factors" else kind, [], values, apply, "scale")


def _measure(path, kind, scale):
    """The intensity measure of `kind` as a function of a record's (t, a): None for factors."""
    spectral = [k for k in ("period", "damping") if k in scale]
    if kind != "sa" and spectral:
        _fail(path, f"scale.{spectral[0]}", "belongs to sa (the spectral acceleration's period "
              "and damping ratio)")
    if kind == "pga":
        return lambda t, a: float(np.max(np.abs(a)))
    if kind != "sa":
        return None
    period, damping = scale.get("period"), scale.get("damping", 0.05)
    if not _positive(period):
        _fail(path, "scale.period", f"required with sa: the period, a positive number "
              f"(got {period!r})")
    if isinstance(damping, bool) or not isinstance(damping, (int, float)) or \
            not 0.0 <= damping < 1.0:
        _fail(path, "scale.damping", f"expected a damping ratio in [0, 1) (got {damping!r})")
    return lambda t, a: spectral_acceleration(t, a, period, damping)


def spectral_acceleration(t, a, period, damping):
    """Sa(T, zeta) = omega^2 max |u| of the oscillator u'' + 2 zeta omega u' + omega^2 u = -a(t),
    from rest, a(t) linear between samples (the scene's tables are): integrated exactly at the
    samples (scipy's lsim, a first-order hold), over the record and one period after it (the
    record held at its last value, as a table is), the maximum taken at the samples."""
    from scipy import signal

    omega = 2.0 * math.pi / period
    dt = float(np.min(np.diff(t))) if len(t) > 1 else period / 20.0
    tail = np.arange(t[-1] + dt, t[-1] + period + dt, dt)
    times = np.concatenate([t, tail])
    ground = np.concatenate([a, np.full(len(tail), a[-1])])
    oscillator = signal.lti([-1.0], [1.0, 2.0 * damping * omega, omega ** 2])
    _, u, _ = signal.lsim(oscillator, ground, times - times[0])
    return float(omega ** 2 * np.max(np.abs(u)))


def _positive(v):
    return not isinstance(v, bool) and isinstance(v, (int, float)) and math.isfinite(v) and v > 0


def _read_record(path, column):
    """(t, values) of a record's column, read as the scene's tables are (docs/scenes.md): `#`
    and blank lines skipped, a header when the first cell is not a number, the second column by
    default. The scene parser has checked the file (its refusals name the problem)."""
    rows = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.strip() and not line.lstrip().startswith("#"):
                rows.append([c.strip() for c in line.split(",")])
    j = 1
    if rows and not _is_number(rows[0][0]):
        header, rows = rows[0], rows[1:]
        if column is not None:
            if column not in header:
                raise SweepError(f"{path}: no column '{column}' (columns: {', '.join(header)})")
            j = header.index(column)
    if not rows:
        raise SweepError(f"{path}: the record has no samples")
    return (np.array([float(r[0]) for r in rows]), np.array([float(r[j]) for r in rows]))


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False
