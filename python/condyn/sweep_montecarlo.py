"""The sweep file's [monte_carlo] (docs/sweep.md): scene keys drawn from distributions, `samples`
draws from numpy's generator seeded by `seed`, as one axis `sample` (1 ... samples) whose columns
are the sample's number and each parameter's value. Each parameter's draws are made in the order
the parameters are listed, so a parameter added at the end leaves the others' draws as they were.
"""

import math

import numpy as np

from .sweep_file import Axis, _fail, _set, parse_key

_KEYS = ("samples", "seed", "parameter")
# Each distribution's keys, and how `n` draws are made from a generator.
_DISTRIBUTIONS = {
    "normal": (("mean", "std"), lambda rng, p, n: rng.normal(p["mean"], p["std"], n)),
    "lognormal": (("median", "beta"),
                  lambda rng, p, n: p["median"] * np.exp(p["beta"] * rng.standard_normal(n))),
    "uniform": (("low", "high"), lambda rng, p, n: rng.uniform(p["low"], p["high"], n)),
}


def monte_carlo_axes(sweep, table, axes):
    """[the axis `sample`], or [] without [monte_carlo]. `axes`: the [[axis]] tables (a key may
    not be both swept and drawn)."""
    mc = table.get("monte_carlo")
    if mc is None:
        return []
    path = sweep.file
    if not isinstance(mc, dict):
        _fail(path, "monte_carlo", "expected a table ([monte_carlo] with samples, seed and "
              "[[monte_carlo.parameter]])")
    for k in mc:
        if k not in _KEYS:
            _fail(path, f"monte_carlo.{k}", f"unknown key ([monte_carlo] has {', '.join(_KEYS)})")
    samples, seed = mc.get("samples"), mc.get("seed")
    for key, value in (("samples", samples), ("seed", seed)):
        if isinstance(value, bool) or not isinstance(value, int) or value < (key == "samples"):
            _fail(path, f"monte_carlo.{key}", f"required: a whole number >= "
                  f"{int(key == 'samples')} (got {value!r})")
    params = mc.get("parameter")
    if not isinstance(params, list) or not params or not all(isinstance(p, dict) for p in params):
        _fail(path, "monte_carlo.parameter", "required: [[monte_carlo.parameter]] tables, each "
              "with key, distribution and its values")
    rng = np.random.default_rng(seed)
    keys, draws = [], []
    for i, p in enumerate(params, start=1):
        where = f"monte_carlo.parameter[{i}]"
        key, draw = _read_parameter(path, where, p, [a.key for a in axes] + [k.key for k in keys])
        keys.append(Axis(key, parse_key(key), [], name=where))
        draws.append([float(x) for x in draw(rng, samples)])

    def apply(sweep, scene, axis, value, where):
        for parameter, values in zip(keys, draws):
            _set(sweep, scene, parameter, values[value - 1], parameter.name)

    def cells(value):
        return [value] + [values[value - 1] for values in draws]

    return [Axis("sample", [], list(range(1, samples + 1)), apply, "monte_carlo",
                 ["sample"] + [k.key for k in keys], cells)]


def _read_parameter(path, where, p, taken):
    """(key, draw) of one [[monte_carlo.parameter]]: draw(rng, n) gives n values."""
    name = p.get("distribution")
    if name not in _DISTRIBUTIONS:
        _fail(path, f"{where}.distribution", f"expected one of {', '.join(_DISTRIBUTIONS)} "
              f"(got {name!r})")
    needed, draw = _DISTRIBUTIONS[name]
    for k in p:
        if k not in ("key", "distribution") + needed:
            _fail(path, f"{where}.{k}", f"unknown key (a {name} parameter has key, distribution, "
                  f"{', '.join(needed)})")
    key = p.get("key")
    if not isinstance(key, str) or parse_key(key) is None:
        _fail(path, f"{where}.key", f"expected a dotted scene path (got {key!r})")
    if key in taken:
        _fail(path, f"{where}.key", f"'{key}' is swept or drawn already")
    for k in needed:
        v = p.get(k)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            _fail(path, f"{where}.{k}", f"required: a finite number (got {v!r})")
    spread = {"normal": ("std", p.get("std", 0) >= 0), "lognormal": ("beta", p.get("beta", 0) >= 0),
              "uniform": ("high", p.get("high", 0) >= p.get("low", 0))}[name]
    if not spread[1]:
        _fail(path, f"{where}.{spread[0]}", "must not be negative" if name != "uniform"
              else "must not be below low")
    if name == "lognormal" and p["median"] <= 0:
        _fail(path, f"{where}.median", "must be positive")
    return key, lambda rng, n: draw(rng, p, n)
