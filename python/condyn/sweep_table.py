"""The results of a sweep (docs/sweep.md): DIR/results.csv, one row per run, appended and flushed
as each run ends (a sweep stopped any way keeps every row written), and read back on restart so
that the runs done are skipped; at the end the rows are put in the order of the product of the
axes and DIR/results.h5 is written beside (one dataset per column, through h5py).
"""

import csv
import io
import json
import math
import os

from .sweep_file import SweepError


def header(sweep):
    """The columns: run, one per axis (its key), status, steps, wall_s, then per kept column
    peak_<column> and peak_time_<column>, then with [[check]] tables in the scene checks_passed
    and per check check<k>_passed and check<k>_computed (k as check[k], 1-based)."""
    peaks = [f"{kind}_{p}" for p in sweep.peaks for kind in ("peak", "peak_time")]
    axes = [c for a in sweep.axes for c in a.columns_of()]
    return ["run"] + axes + ["status", "steps", "wall_s"] + peaks + check_columns(sweep.checks)


def check_columns(count):
    """The columns of `count` [[check]] tables' verdicts (none without checks)."""
    each = [f"check{k}_{what}" for k in range(1, count + 1) for what in ("passed", "computed")]
    return ["checks_passed"] + each if count else []


def cell(value):
    """A value as the table writes it: numbers as Python writes them (they read back exactly),
    booleans as TOML does, None as an empty cell, arrays and tables as JSON."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float, str)):
        return str(value) if not isinstance(value, float) else repr(value)
    return json.dumps(value, sort_keys=True, default=str)


class ResultsTable:
    """DIR/results.csv of one sweep: `done` maps each run key in it to its row (a list of cells)."""

    def __init__(self, folder, columns):
        self.folder, self.columns = folder, columns
        self.csv_path = os.path.join(folder, "results.csv")
        try:
            os.makedirs(folder, exist_ok=True)
        except OSError as e:
            raise SweepError(f"{folder}: cannot create the results folder: {e.strerror}") from None
        self.done = self._read() if os.path.exists(self.csv_path) else {}
        try:
            self._file = open(self.csv_path, "a", newline="", encoding="utf-8")
        except OSError as e:
            raise SweepError(f"{self.csv_path}: cannot write: {e.strerror}") from None
        if not self.done and self._file.tell() == 0:
            self._write(columns)

    def append(self, run, values, row, peaks, checks=0):
        """Writes the row of `run` (its cells of the axes, and the worker's row) and flushes it
        to disk; a run's HDF5 file (the worker's bytes) goes to runs/KEY.h5 first."""
        cells = [run] + [cell(v) for v in values]
        cells += [row["status"], cell(row["steps"]), cell(row["wall_s"])]
        for p in peaks:
            cells += [cell(x) for x in row["peaks"].get(p, (None, None))]
        if checks:  # a run that failed evaluated no check: empty cells
            verdicts = row.get("checks") or {"passed": None, "each": [(None, None)] * checks}
            cells.append(cell(verdicts["passed"]))
            cells += [cell(x) for each in verdicts["each"] for x in each]
        if row.get("result") is not None:
            self.write_result(run, row["result"])
        self._write(cells)
        self.done[run] = cells

    def write_result(self, run, data):
        """DIR/runs/RUN.h5, written whole through a temporary name (never half a file)."""
        folder = os.path.join(self.folder, "runs")
        os.makedirs(folder, exist_ok=True)
        _replace(os.path.join(folder, f"{run}.h5"), lambda f: f.write(data))

    def finish(self, order):
        """Rewrites results.csv with the rows of the keys in `order` first, in that order, then
        any others (runs of an earlier version of the sweep) as they were; writes results.h5."""
        self._file.close()
        rows = [self.done[k] for k in order if k in self.done]
        rows += [r for k, r in self.done.items() if k not in set(order)]
        text = io.StringIO()
        writer = csv.writer(text, lineterminator="\n")
        writer.writerow(self.columns)
        writer.writerows(rows)
        _replace(self.csv_path, lambda f: f.write(text.getvalue().encode("utf-8")))
        _write_hdf5(os.path.join(self.folder, "results.h5"), self.columns, rows)

    def _write(self, cells):
        csv.writer(self._file, lineterminator="\n").writerow(cells)
        self._file.flush()
        os.fsync(self._file.fileno())

    def _read(self):
        """The rows already in results.csv, by run key. A last line cut short (a sweep killed
        while writing it) is dropped; columns other than this sweep's are refused."""
        with open(self.csv_path, "r+b") as f:
            data = f.read()
            if data and not data.endswith(b"\n"):
                f.truncate(data.rfind(b"\n") + 1)
                data = data[:data.rfind(b"\n") + 1]
        lines = list(csv.reader(io.StringIO(data.decode("utf-8", errors="replace"))))
        if not lines:
            return {}
        if lines[0] != self.columns:
            raise SweepError(
                f"{self.csv_path}: written by another sweep (its columns: {', '.join(lines[0])}; "
                f"this sweep's: {', '.join(self.columns)}): give another --out, or remove it")
        done = {}
        for n, line in enumerate(lines[1:], start=2):
            if len(line) != len(self.columns):
                raise SweepError(f"{self.csv_path}:{n}: {len(line)} cells where the header has "
                                 f"{len(self.columns)}: remove the line to run it again")
            done[line[0]] = line
        return done


def _replace(path, write):
    """Writes `path` through a temporary file beside it, renamed over it when complete."""
    partial = path + ".partial"
    with open(partial, "wb") as f:
        write(f)
        f.flush()
        os.fsync(f.fileno())
    os.replace(partial, path)


def _write_hdf5(path, columns, rows):
    """results.h5: one dataset per column, named by it (a '/' in a name written as '|'), float64
    where every cell is a number or empty (NaN), or true or false (1, 0), else UTF-8 strings;
    the root's attribute `columns` lists them in the CSV's order."""
    import h5py  # Debian's python3-h5py; imported here, where it is needed
    import numpy as np

    partial = path + ".partial"
    with h5py.File(partial, "w") as f:
        f.attrs["columns"] = columns
        for j, name in enumerate(columns):
            cells = [r[j] for r in rows]
            numbers = _numbers(cells) if name != "run" else None
            data = (np.array(numbers, dtype=np.float64) if numbers is not None
                    else np.array(cells, dtype=h5py.string_dtype()))
            f.create_dataset(name.replace("/", "|"), data=data)
    os.replace(partial, path)


_BOOLEANS = {"true": 1.0, "false": 0.0, "": math.nan}


def _numbers(cells):
    """The cells as floats (empty: NaN), or None when one is not a number; a column of true and
    false (and empty cells) as 1 and 0."""
    if all(c in _BOOLEANS for c in cells):
        return [_BOOLEANS[c] for c in cells]
    try:
        return [float(c) if c != "" else math.nan for c in cells]
    except ValueError:
        return None
