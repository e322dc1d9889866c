"""condyn from Python: run scenes (files or dicts, models from numpy and scipy.sparse arrays) and
compare schemes, over the same C++ library as the `condyn` command (docs/python.md).

    import condyn
    r = condyn.run("models/scenes/quickstart.toml", scheme="ggl")
    r.t, r.u, r.drift, r.summary["steps"]
"""

import collections.abc
import decimal
import numbers
import os
import warnings

from ._condyn import OutputError, SceneError, scheme_names
from . import _condyn
from .sweep_file import SweepError

SceneError.__module__ = __name__  # shown as condyn.SceneError, where users catch it
OutputError.__module__ = __name__

__all__ = ["run", "compare", "check", "modes", "sweep", "Result", "SceneError", "OutputError",
           "SweepError", "IntegrationError", "scheme_names"]


class Result:
    """One run: numpy arrays over the output times and what the integrator did.

    t (nt); u, v, reaction (nt x n); multiplier (nt x m); drift (nt x 2: position, velocity
    residual, max-norm); a (nt x n, u'', relative to the ground under [ground_motion]) when the
    scene's [output] asks for acceleration or absolute_acceleration (or a [[derived]] column
    reads an acceleration), else None; a_abs (nt x n,
    u'' + r a_g(t)) when it asks for absolute_acceleration, else None;
    energy and kinetic (nt) for a conservative model, else None; energy_balance (nt x 7, columns
    named by energy_columns: energy, energy_error, energy_kinetic, energy_potential,
    energy_dissipated, work_loads, work_constraints) when [output] asks for "energy", else None
    (docs/energy.md); near_singular (nt booleans: the rows inside a passage near a singular
    configuration, whose reactions are not to be trusted; docs/schemes.md); dof_names,
    velocity_names, acceleration_names, reaction_names (the columns of u, v, a and reaction:
    each the DOFs, except for a mechanism), constraint_names; points (nt x k, the [output]
    points' positions, columns point_names) or None; derived (nt x k, the scene's [[derived]]
    columns, named by derived_names; nt x 0 without any: docs/scenes.md); summary (dict: scheme, steps, wall_s, rtol,
    atol, residual_evals, jacobian_evals, ..., singular_passages, worst_drift_joint); checks
    (run(..., checks=True) on a scene with [[check]] tables: condyn.check's dict for this run's
    rows, else None).
    A mechanism ([model] type = "multibody") shows its own columns, as the CSV does: u holds
    the poses (crank.x, crank.y, crank.angle; in 3D a quaternion crank.qw..qz, 7 columns a body),
    v the velocities (crank.vx, ..., crank.omega; in 3D wx, wy, wz, 6 a body), a the
    accelerations, reaction the joints' forces and torques (hinge.fx, hinge.m), each named by
    its own list.
    The arrays are read-only: views of the run's memory, except drift, a_abs and energy_balance
    (copies gathered from the rows).
    """

    __slots__ = ("t", "u", "v", "reaction", "multiplier", "drift", "a", "a_abs", "energy",
                 "kinetic", "energy_balance", "energy_columns", "near_singular", "dof_names",
                 "velocity_names", "acceleration_names", "reaction_names", "points",
                 "point_names", "constraint_names", "derived", "derived_names", "summary",
                 "checks")

    def __init__(self, fields, checks=None):
        self.checks = checks  # not one of the run's fields: run(checks=True)'s verdict
        for key in self.__slots__:
            if key == "checks":
                continue
            value = fields[key]
            if hasattr(value, "flags"):  # a numpy array: read-only, as documented
                value.flags.writeable = False
            setattr(self, key, value)

    def dof(self, name):
        """The column of u named `name`: a DOF, or a mechanism's pose column (KeyError naming
        them otherwise)."""
        try:
            return self.dof_names.index(name)
        except ValueError:
            raise KeyError(f"no DOF {name!r}; DOFs: {', '.join(self.dof_names)}") from None

    def __repr__(self):
        s = self.summary
        return (f"<condyn.Result {s['scheme']}: {len(self.t)} rows, {len(self.dof_names)} DOFs, "
                f"{len(self.constraint_names)} constraints, {s['steps']} steps, "
                f"{s['wall_s']:.3g} s>")


class IntegrationError(RuntimeError):
    """The integrator stopped before t_end. `result` holds the rows computed before the failure
    (a Result, possibly with no rows); the message is the CLI's (scheme, kind, where, what to
    try); `kind` names the failure's kind ("step_budget", "convergence", ...: docs/python.md),
    None when no run failed (compare's missing reference)."""

    def __init__(self, message, result=None, kind=None):
        super().__init__(message)
        self.result = result
        self.kind = kind

    def __reduce__(self):  # pickled with its result (a failed run in a process pool)
        return (type(self), (str(self), self.result, self.kind))


def run(scene, scheme=None, rtol=None, atol=None, step=None, checks=False, out=None):
    """Runs `scene` (a path to a scene file, or a dict with the TOML's structure) and returns a
    Result. `scheme`, `rtol`, `atol` and `step` (the fixed step of the Newmark family: newmark,
    hht, generalized_alpha) override the scene's [solve] keys. With `checks`, the scene's
    [[check]] tables are evaluated on this run's rows (Result.checks: the dict condyn.check
    returns, without a second run; the quantities the checks read are computed too; None for a
    scene without [[check]]; on a failed run, on IntegrationError's result). With `out` (a str,
    bytes or os.PathLike), the result is also written there, the file `condyn run --out OUT`
    writes (CSV, or HDF5 for .h5, .hdf5, .hdf; a failed run's rows in OUT's partial file, named
    in IntegrationError's message); a name the command refuses raises OutputError (a
    ValueError) naming it, before any work. Bad input raises SceneError (a ValueError) with the
    CLI's "FILE:LINE: key.path: problem" message ("<dict>" and no line for a dict); a failed
    integration raises IntegrationError. The GIL is released while the model is built and
    integrated (not while `out` is written)."""
    _refuse_text(scene)
    fields, failure, kind, verdict = _condyn.run(scene, _text(scene, "scheme", scheme),
                                                 _number(scene, "rtol", rtol),
                                                 _number(scene, "atol", atol),
                                                 _number(scene, "step", step), bool(checks),
                                                 _out(out))
    result = Result(fields, verdict)
    if failure is not None:
        raise IntegrationError(f"{_name(scene)}: integration failed: {failure}", result, kind)
    return result


def compare(scene, tolerances=None, schemes=None, repeats=1, drift_rtol=None, max_steps=0,
            max_wall_time=0.0, step=None):
    """`condyn compare`'s sweep without its files: every scheme (or `schemes`, a list of names)
    at every rtol of `tolerances` (default 1e-3 ... 1e-10), each run `repeats` times for its wall
    time. Returns one dict per run (scheme, rtol, atol, ok, message, error_u, error_v,
    error_reaction against `reference`, drifts, steps, evaluations, wall times); a scheme that
    cannot treat the scene gives one dict with skipped=True and the reason. `max_steps` and
    `max_wall_time` (seconds) budget each run as the command's --max-steps and --max-wall-time
    (0 or None: none); a run over budget has ok=False and says so in its message. `step` is the
    Newmark family's fixed step, as the command's --step. An argument
    of another type raises SceneError naming it. The scene's warnings are issued as
    UserWarning. When no run can be scored (no exact solution, and the tight reference runs
    failed) it raises IntegrationError, whose result is None."""
    _refuse_text(scene)
    records, scene_warnings, no_reference = _condyn.compare(
        scene, _list(scene, "tolerances", tolerances, _number),
        _list(scene, "schemes", schemes, _text), _integer(scene, "repeats", repeats),
        _number(scene, "drift_rtol", drift_rtol), _integer(scene, "max_steps", max_steps) or 0,
        _number(scene, "max_wall_time", max_wall_time) or 0.0, _number(scene, "step", step))
    if no_reference is not None:
        raise IntegrationError(f"{_name(scene)}: {no_reference}", None)
    for w in scene_warnings:
        warnings.warn(f"{_name(scene)}: {w}", UserWarning, stacklevel=2)
    return records


def check(scene, scheme=None, step=None):
    """Runs `scene` and evaluates its [[check]] tables as `condyn check` does (docs/checks.md);
    `step` is the Newmark family's fixed step, as the command's --step.
    Returns a dict: scene, scheme, steps, wall_s, failure (the integration failure's message or
    None), passed (every check held and the run reached t_end) and checks, one dict per check
    (quantity, computed, bound, passed, text). A scene without [[check]] raises SceneError."""
    _refuse_text(scene)
    return _condyn.check(scene, _text(scene, "scheme", scheme), _number(scene, "step", step))


def modes(scene, count=None):
    """The natural modes of the scene's constrained model at t = 0, lowest first, as `condyn
    modes` gives them (docs/cli.md): `count` of them (default the lowest 10, or all when the model
    has fewer). Returns a dict of numpy arrays and names: omega (rad per time unit), frequency
    (cycles per time unit), period (inf for a zero-frequency mode), mass_ratio and
    mass_ratio_cumulative (under [ground_motion], else None), total_mass (the mass along the
    influence vector, or None), shapes (n x count, columns mass-normalized, phi' M phi = 1, over
    dof_names), available (the modes the constrained model has) and solver ("dense" or
    "lanczos"): the doubles `condyn modes --out FILE.h5` writes, under the same names. Bad input
    (a count out of range, a model without mass, a nonlinear model) raises SceneError naming the
    argument or key."""
    _refuse_text(scene)
    return _condyn.modes(scene, _integer(scene, "count", count))


def sweep(sweep_file, workers=None, scheduler=None, out=None, progress=True):
    """`condyn sweep` (docs/sweep.md): runs the product of the sweep file's axes on a local Dask
    cluster of `workers` processes (default: one per core) or on the cluster of the scheduler at
    `scheduler` ("tcp://host:8786"), and writes `out`/results.csv and results.h5 (default `out`:
    the sweep file's name without extension). Runs already in the table are skipped. Progress
    and the summary go to standard error unless `progress` is False. Returns the summary: runs,
    ok, failed ({status: count}), skipped, missing, table, with [[check]] tables checks
    ({passed, failed, failed_by_check}) and with [ida] fragility. A bad sweep file raises
    SweepError (a ValueError) naming the file and key, before any run."""
    import sys
    from .sweep_run import sweep as run_sweep  # Dask is imported only by a sweep
    return run_sweep(sweep_file, workers=workers, scheduler=scheduler, out=out,
                     progress=sys.stderr if progress else None)


def _refuse_text(scene):
    """A scene's TOML text given where its path belongs: SceneError saying what to pass, not the
    whole text followed by 'cannot open the scene file (File name too long)'."""
    if isinstance(scene, (str, bytes)):
        text = scene.decode(errors="replace") if isinstance(scene, bytes) else scene
        if ("\n" in text or text.lstrip().startswith("[")) and not os.path.exists(scene):
            raise SceneError(
                f"the scene given is text ({text.count(chr(10)) + 1} lines), not a path: pass the "
                "path of a scene file, or the scene as a dict (tomllib.loads(text))")


def _name(scene):
    """The scene as messages name it: a path's text (bytes decoded as open() would), or <dict>."""
    if isinstance(scene, dict):
        return "<dict>"
    try:
        return os.fsdecode(scene)
    except TypeError:  # not a path at all: run() refuses it by its type
        return str(scene)


def _out(out):
    """run()'s `out` as the file system's bytes (None: not given); a blank name raises
    OutputError, as the command refuses `--out ""`."""
    if out is None:
        return None
    path = os.fsencode(out)  # TypeError for what is no path
    if not path.strip():
        raise OutputError(f"out {os.fsdecode(path)!r}: an empty name: name a file (or - for "
                          "standard output)")
    return path


def _number(scene, argument, value):
    """An override that must be a real number (None: not given), else SceneError naming it."""
    if value is None:
        return None
    # What a scene value takes takes here too: a 0-d numeric array, a Decimal.
    if getattr(value, "ndim", None) == 0 and getattr(value, "dtype", None) is not None and \
            value.dtype.kind in "iuf":
        value = value.item()
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, decimal.Decimal)):
        raise SceneError(f"{_name(scene)}: {argument}: expected a number "
                         f"(got {type(value).__name__} {value!r})")
    try:
        return float(value)
    except OverflowError:
        raise SceneError(f"{_name(scene)}: {argument}: an integer of {int(value).bit_length()} "
                         "bits is out of the double range") from None


def _integer(scene, argument, value):
    """An argument that must be an integer of 64 bits (None: not given), else SceneError."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise SceneError(f"{_name(scene)}: {argument}: expected an integer "
                         f"(got {type(value).__name__} {value!r})")
    if not -2**31 <= int(value) < 2**31:
        raise SceneError(f"{_name(scene)}: {argument}: {int(value)} is out of range")
    return int(value)


def _list(scene, argument, value, item):
    """An argument that must be a list (or tuple, or 1-d array) of values `item` accepts, none
    twice (None: not given), else SceneError naming it, as the command refuses its flags."""
    if value is None:
        return None
    if isinstance(value, (str, bytes, collections.abc.Mapping, collections.abc.Set)) or \
            not isinstance(value, collections.abc.Iterable):
        raise SceneError(f"{_name(scene)}: {argument}: expected a list "
                         f"(got {type(value).__name__} {value!r}); give [{value!r}] for one")
    try:
        values = list(value)
    except TypeError:  # a 0-d array
        raise SceneError(f"{_name(scene)}: {argument}: expected a list "
                         f"(got {type(value).__name__} {value!r})") from None
    items = []
    for k, v in enumerate(values):
        checked = item(scene, f"{argument}[{k}]", v)
        if checked is None:
            raise SceneError(f"{_name(scene)}: {argument}[{k}]: None is not a value")
        if checked in items:
            raise SceneError(f"{_name(scene)}: {argument}: {checked!r} is listed twice")
        items.append(checked)
    return items


def _text(scene, argument, value):
    """An override that must be a string (None: not given), else SceneError naming it."""
    if value is None or isinstance(value, str):
        return value
    raise SceneError(f"{_name(scene)}: {argument}: expected a string "
                     f"(got {type(value).__name__} {value!r})")
