"""The output folder of `condyn compare` as plot_compare.py reads it (validation/compare-output.md):
runs.csv, runs.json, drift_<scheme>.csv, history_<scheme>.csv and baumgarte_study.csv.

A file compare would not have written (not UTF-8, torn rows, a word where a number goes) is a
BadData naming the file, the line and the column; an absent or empty one reads as None.
"""
import csv
import glob
import json
import math
import os

# The schemes in compare's order: files and runs are listed in it, other names after them.
SCHEME_ORDER = ("elimination", "index1", "baumgarte", "ggl", "index2", "index3", "penalty",
                "projection")
# Columns of compare's CSV files that hold text; every other cell is a number or empty.
TEXT_COLUMNS = {"scheme", "status", "message"}
# What runs.json holds (validation/compare-output.md), by key: a key of another type is left
# out with a note, as if absent.
META_TYPES = {"scene": str, "reference": dict, "tolerances": list, "drift_rtol": (int, float),
              "mark_factor": (int, float), "histories": dict, "drift_growth": dict, "runs": list, "skipped": list}


class BadData(Exception):
    """A file of the folder that compare would not have written: named with the problem."""



def scheme_key(scheme):
    return (SCHEME_ORDER.index(scheme) if scheme in SCHEME_ORDER else len(SCHEME_ORDER),
            scheme)


def num(value):
    """Float of a CSV or JSON field; None for empty, null, unparsable or non-finite."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def read_csv(path):
    """Rows as dicts, or None when the file is absent or has no data rows; BadData for a file
    compare would not have written (not UTF-8 text, torn rows, a word where a number goes)."""
    if not os.path.isfile(path):
        return None
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.reader(f)
            header = next(reader, None)
            rows = [(reader.line_num, cells) for cells in reader if cells]
    except UnicodeDecodeError as e:
        raise BadData(f"{path}: not UTF-8 text (byte 0x{e.object[e.start]:02x}): not written by "
                      "condyn compare") from None
    except (csv.Error, OSError) as e:
        raise BadData(f"{path}: {e}") from None
    if not header:
        return None
    for line, cells in rows:
        if len(cells) != len(header):
            raise BadData(f"{path}:{line}: {len(cells)} cells for the header's {len(header)} "
                          "columns")
        for name, cell in zip(header, cells):
            if name not in TEXT_COLUMNS and cell.strip():
                try:
                    float(cell)
                except ValueError:
                    raise BadData(f"{path}:{line}: column {name}: '{cell[:40]}' is not a "
                                  "number") from None
    return [dict(zip(header, cells)) for _, cells in rows] or None


def column(np, rows, name):
    """One CSV column as floats, NaN where a value is missing, so plots show gaps."""
    return np.array([np.nan if num(r.get(name)) is None else num(r.get(name)) for r in rows])


def per_scheme_files(d, prefix):
    paths = glob.glob(os.path.join(d, f"{prefix}_*.csv"))
    named = {os.path.basename(p)[len(prefix) + 1:-4]: p for p in paths}
    named.pop("reference", None)  # history_reference.csv: the reference's, not a scheme's
    return [(s, named[s]) for s in sorted(named, key=scheme_key)]




def load_meta(d):
    """runs.json as a dict, and the problems found in it (each key of the wrong type dropped)."""
    path = os.path.join(d, "runs.json")
    if not os.path.isfile(path):
        return {}, []
    try:
        with open(path, encoding="utf-8") as f:
            meta = json.load(f)
    except (OSError, ValueError) as e:  # UnicodeDecodeError is a ValueError
        return {}, [f"{path}: unreadable ({e}); titles lack the scene name"]
    if not isinstance(meta, dict):
        return {}, [f"{path}: not a JSON object"]
    problems = []
    for key, kind in META_TYPES.items():
        if key in meta and not isinstance(meta[key], kind):
            problems.append(f"{path}: '{key}' is a {type(meta[key]).__name__}, not a "
                            f"{getattr(kind, '__name__', 'number')}: left out")
            del meta[key]
    for key in ("histories", "drift_growth"):
        if key in meta and not all(isinstance(v, dict) for v in meta[key].values()):
            problems.append(f"{path}: '{key}' holds entries that are not objects: left out")
            del meta[key]
    if "runs" in meta and not all(isinstance(r, dict) for r in meta["runs"]):
        problems.append(f"{path}: 'runs' holds entries that are not objects: left out")
        del meta["runs"]
    return meta, problems


def runs_by_scheme(d, meta):
    runs = read_csv(os.path.join(d, "runs.csv")) or meta.get("runs") or []
    by_scheme = {}
    for r in runs:
        by_scheme.setdefault(str(r.get("scheme") or "?"), []).append(r)
    return {s: by_scheme[s] for s in sorted(by_scheme, key=scheme_key)}
