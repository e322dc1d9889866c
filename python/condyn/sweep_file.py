"""The sweep file of `condyn sweep` (docs/sweep.md): its reader, the product of its axes and each
run's key (a hash of the run's inputs). Nothing here runs a scene; every scene a sweep will run is
checked here, before any run, and bad input raises SweepError naming the file and the key.

    sweep = read_sweep("study.toml")
    for run in expand(sweep): run.key, run.values, run.scene, run.files
"""

import copy
import dataclasses
import hashlib
import itertools
import json
import os
import re
import tomllib

from . import _condyn

_TOP_KEYS = ("scene", "axis", "schemes", "tolerances", "keep", "records", "scale", "monte_carlo",
             "ida")
# Shorthands for the axes over the run settings compared most: schemes = [...] is an axis over
# solve.scheme, tolerances = [...] over solve.rtol.
_SHORTHANDS = {"schemes": "solve.scheme", "tolerances": "solve.rtol"}
_KEEP_KEYS = ("peaks", "results")
_AXIS_KEYS = ("key", "values")
# One component of a dotted scene path: a name, then 1-based indices into arrays (load[1]).
_COMPONENT = re.compile(r"^([A-Za-z0-9_-]+)((?:\[[0-9]+\])*)$")


class SweepError(ValueError):
    """A bad sweep file (or a scene it names): the message is "FILE: key: what is wrong"."""


@dataclasses.dataclass
class Axis:
    key: str     # the dotted scene path, as written (the results' column name)
    path: list   # its components: names (str) and 1-based indices (int)
    values: list
    # How a value goes into the scene, apply(sweep, scene, axis, value, where); None: set at
    # `path`
    # ([records] and [scale] have their own: sweep_records.py).
    apply: object = None
    name: str = ""  # the axis in messages: axis[2], records, scale
    # The results' columns of the axis and a value's cells in them; None: one, named by the key
    # ([monte_carlo] has a sample number and each parameter's value: sweep_montecarlo.py).
    columns: list = None
    cells: object = None

    def columns_of(self):
        return self.columns or [self.key]

    def cells_of(self, value):
        return self.cells(value) if self.cells else [value]


@dataclasses.dataclass
class Sweep:
    file: str        # the sweep file
    scene_file: str  # the scene, an absolute path
    scene: dict      # the scene as tomllib reads it
    axes: list       # of Axis
    peaks: list      # the kept columns (names of the run's CSV columns)
    ida: tuple = None  # [ida]: (the kept column, the limit state or None, axis labels), sweep_ida.py
    keep_result: bool = False  # [keep] results: each run's HDF5 file as DIR/runs/KEY.h5

    @property
    def checks(self):
        """The scene's [[check]] tables: each run's verdicts are columns of the results."""
        return len(self.scene.get("check", []))

    @property
    def default_out(self):
        """The results folder when none is given: the sweep file's name without extension."""
        return os.path.splitext(self.file)[0]


@dataclasses.dataclass
class Run:
    index: int     # the run's place in the product of the axes (the last axis varies fastest)
    values: tuple  # one value per axis
    scene: dict    # the scene with the axis values applied; its file names as written
    files: dict    # each file name the scene holds -> its absolute path
    key: str = ""  # a hash of the scene and the files' contents (run_key)


def read_sweep(path):
    """Reads and checks the sweep file at `path` and the scene it names: a Sweep, or SweepError."""
    path = os.fspath(path)
    table = _read_toml(path, "the sweep file")
    for key in table:
        if key not in _TOP_KEYS:
            _fail(path, key, f"unknown key (a sweep file has {', '.join(_TOP_KEYS)})")
    scene_name = table.get("scene")
    if not isinstance(scene_name, str) or not scene_name:
        _fail(path, "scene", "required: the scene file's name, relative to the sweep file"
              if scene_name is None else f"expected a file name (got {scene_name!r})")
    scene_file = os.path.join(os.path.dirname(os.path.abspath(path)), scene_name)
    if not os.path.isfile(scene_file):
        _fail(path, "scene", f"no such file: {scene_file}")
    try:
        _condyn.parse_scene(scene_file)
    except ValueError as e:  # SceneError: "FILE:LINE: key: problem"
        _fail(path, "scene", f"the scene is refused: {e}")
    scene = _read_toml(scene_file, "the scene")
    # A sweep keeps what [keep] says, no run's file; the rest of [output] stays: it decides what
    # the run computes (energy, accelerations, points) and what a kept result holds.
    scene.get("output", {}).pop("file", None)
    from .sweep_records import records_axes  # it builds on this file's Axis and SweepError
    axes = _read_axes(path, table.get("axis", [])) + _read_shorthands(path, table)
    keep = table.get("keep", {})
    sweep = Sweep(path, scene_file, scene, axes, _read_peaks(path, keep),
                  keep_result=_read_keep_result(path, keep))
    from .sweep_montecarlo import monte_carlo_axes
    sweep.axes = records_axes(sweep, table) + axes + monte_carlo_axes(sweep, table, axes)
    from .sweep_ida import read_ida
    sweep.ida = read_ida(path, table, sweep)
    return sweep


def expand(sweep):
    """Every run of the sweep, in the order of the product of its axes (the last axis varying
    fastest), each with its key. The scene of each axis value is checked by condyn's scene parser
    first (an unknown key, a value of the wrong type, a missing file: SweepError naming the axis);
    a combination of values the parser would refuse fails at its run ("scene_error")."""
    for axis in sweep.axes:
        for value in axis.values:
            scene = _applied(sweep, [axis], (value,), axis.name)
            _check_scene(sweep, scene, f"{axis.name} ({axis.key} = {_shown(value)})")
    digests = {}
    runs = []
    for index, values in enumerate(itertools.product(*(a.values for a in sweep.axes))):
        scene = _applied(sweep, sweep.axes, values, "axis")
        _check_count(sweep, scene, values)
        files = {name: _absolute(sweep, name) for name in file_names(scene)}
        run = Run(index, values, scene, files)
        run.key = run_key(scene, {n: _digest(p, digests) for n, p in files.items()})
        runs.append(run)
    return runs


def run_key(scene, file_digests):
    """The run's key: the first 16 hex digits of SHA-256 over the scene (canonical JSON: keys
    sorted, numbers as Python writes them) and the SHA-256 of each data file's bytes, by the name
    the scene gives it. Equal inputs give equal keys on any machine; an edited record a new one."""
    text = json.dumps({"scene": scene, "files": file_digests}, sort_keys=True,
                      separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def file_names(scene):
    """The data files a scene names: every string under a key `file` (tables, records, matrices,
    references), in the order met."""
    names = []
    map_files(scene, lambda name: names.append(name) or name)
    return list(dict.fromkeys(names))


def map_files(node, rename):
    """A copy of `node` with each string under a key `file` replaced by rename(string)."""
    if isinstance(node, dict):
        return {k: (rename(v) if k == "file" and isinstance(v, str) else map_files(v, rename))
                for k, v in node.items()}
    if isinstance(node, list):
        return [map_files(v, rename) for v in node]
    return node


def parse_key(text):
    """A dotted scene path ("load[1].value.amplitude") as components, or None when malformed."""
    path = []
    for part in text.split("."):
        m = _COMPONENT.match(part)
        if m is None:
            return None
        path.append(m.group(1))
        indices = [int(i) for i in re.findall(r"\[([0-9]+)\]", m.group(2))]
        if any(i < 1 for i in indices):
            return None
        path.extend(indices)
    return path


def _read_toml(path, what):
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except OSError as e:
        raise SweepError(f"{path}: cannot read {what}: {e.strerror}") from None
    except UnicodeDecodeError as e:
        raise SweepError(f"{path}: {what} is not UTF-8 text ({e.reason})") from None
    except tomllib.TOMLDecodeError as e:  # its message names the line and column
        raise SweepError(f"{path}: {what} is not valid TOML: {e}") from None


def _read_axes(path, axes):
    if not isinstance(axes, list) or not all(isinstance(a, dict) for a in axes):
        _fail(path, "axis", "expected [[axis]] tables, each with key and values")
    read = []
    for a, table in enumerate(axes, start=1):
        where = f"axis[{a}]"
        for k in table:
            if k not in _AXIS_KEYS:
                _fail(path, f"{where}.{k}", "unknown key (an axis has key and values)")
        key = table.get("key")
        if not isinstance(key, str):
            _fail(path, f"{where}.key", "required: a scene key by its dotted path "
                  "(solve.rtol, load[1].value.amplitude)" if key is None
                  else f"expected a dotted scene path (got {key!r})")
        components = parse_key(key)
        if components is None:
            _fail(path, f"{where}.key", f"'{key}' is not a dotted scene path (names of letters, "
                  "digits, _ and -, joined by dots; array entries as name[1], 1-based)")
        if any(key == other.key for other in read):
            _fail(path, f"{where}.key", f"'{key}' is swept by an earlier axis too")
        values = table.get("values")
        if not isinstance(values, list) or not values:
            _fail(path, f"{where}.values", "required: a non-empty list of the key's values"
                  if values is None else f"expected a non-empty list (got {values!r})")
        for i, v in enumerate(values):
            if v in values[:i]:
                _fail(path, f"{where}.values", f"{_shown(v)} is listed twice")
        read.append(Axis(key, components, values, name=where))
    return read


def _read_shorthands(path, table):
    """The axes of `schemes` and `tolerances`; refused beside an [[axis]] over the same key."""
    swept = [a.get("key") for a in table.get("axis", [])]
    axes = []
    for name, key in _SHORTHANDS.items():
        values = table.get(name)
        if values is None:
            continue
        if key in swept:
            _fail(path, name, f"an [[axis]] sweeps {key} too: give one or the other")
        if not isinstance(values, list) or not values:
            _fail(path, name, f"expected a non-empty list (got {values!r})")
        for i, v in enumerate(values):
            if v in values[:i]:
                _fail(path, name, f"{_shown(v)} is listed twice")
        axes.append(Axis(key, parse_key(key), values, name=name))
    return axes


def _read_peaks(path, keep):
    if not isinstance(keep, dict):
        _fail(path, "keep", "expected a table ([keep] with peaks = [...])")
    for k in keep:
        if k not in _KEEP_KEYS:
            _fail(path, f"keep.{k}", f"unknown key ([keep] has {', '.join(_KEEP_KEYS)})")
    peaks = keep.get("peaks", [])
    if not isinstance(peaks, list) or not all(isinstance(p, str) and p for p in peaks):
        _fail(path, "keep.peaks", f"expected a list of column names (got {peaks!r})")
    for i, p in enumerate(peaks):
        if p in peaks[:i]:
            _fail(path, "keep.peaks", f"'{p}' is listed twice")
    return peaks


def _read_keep_result(path, keep):
    value = keep.get("results", False)
    if not isinstance(value, bool):
        _fail(path, "keep.results", f"expected true or false (got {_shown(value)})")
    return value


def _applied(sweep, axes, values, where):
    """A copy of the sweep's scene with each axis' value set at its key."""
    scene = copy.deepcopy(sweep.scene)
    for axis, value in zip(axes, values):
        (axis.apply or _set)(sweep, scene, axis, copy.deepcopy(value), where)
    return scene


def _set(sweep, scene, axis, value, where):
    """Sets `value` at the axis' key: the tables and array entries on the way must be in the
    scene (SweepError naming what is missing); the last key may be new (the parser judges it)."""
    node, walked = scene, ""
    for i, step in enumerate(axis.path):
        last = i == len(axis.path) - 1
        if isinstance(step, int):
            if not isinstance(node, list):
                _missing(sweep, where, axis, f"'{walked}' is not an array")
            if step > len(node):
                _missing(sweep, where, axis, f"'{walked}' has {len(node)} entries")
            shown = f"{walked}[{step}]"
            step -= 1
        else:
            if not isinstance(node, dict):
                _missing(sweep, where, axis, f"'{walked}' is not a table")
            shown = f"{walked}.{step}" if walked else step
            if not last and step not in node:
                _missing(sweep, where, axis, f"it has no '{shown}'")
        if last:
            node[step] = value
        else:
            node, walked = node[step], shown


def _missing(sweep, where, axis, problem):
    _fail(sweep.file, f"{where}.key", f"'{axis.key}' is not a key of the scene "
          f"{sweep.scene_file}: {problem}")


def _check_count(sweep, scene, values):
    """Every run has the scene's [[check]] tables (their verdicts are columns of the results)."""
    checks = scene.get("check", [])
    if len(checks) != sweep.checks:
        _fail(sweep.file, "axis", f"the run of {_shown(list(values))} has {len(checks)} [[check]] "
              f"tables where the scene has {sweep.checks}: the results have a column per check "
              "of the scene, so an axis may change a check's keys, not their number")


def _check_scene(sweep, scene, where):
    """condyn's parser on the scene, its files named by absolute paths."""
    try:
        _condyn.parse_scene(map_files(scene, lambda name: _absolute(sweep, name)))
    except ValueError as e:
        _fail(sweep.file, where, f"the scene refuses it: {e}")


def _absolute(sweep, name):
    """A file name of the scene: relative names are taken from the scene file's folder."""
    return os.path.join(os.path.dirname(sweep.scene_file), os.path.expanduser(name))


def _digest(path, digests):
    """SHA-256 of the file's bytes, each file read once."""
    if path not in digests:
        h = hashlib.sha256()
        try:
            with open(path, "rb") as f:
                for block in iter(lambda: f.read(1 << 20), b""):
                    h.update(block)
        except OSError as e:  # checked by the parser already, but it may have gone since
            raise SweepError(f"{path}: cannot read the data file: {e.strerror}") from None
        digests[path] = h.hexdigest()
    return digests[path]


def _shown(value):
    """A value as the sweep file writes it (strings quoted)."""
    return json.dumps(value, default=str)


def _fail(path, key, problem):
    raise SweepError(f"{path}: {key}: {problem}")
