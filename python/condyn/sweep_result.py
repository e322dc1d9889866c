"""A run's whole result as HDF5, for a sweep's `[keep] results = true` (docs/sweep.md): written by
the worker into its temporary folder and sent back as bytes (no shared file system), then saved
as DIR/runs/KEY.h5. The layout is that of `condyn run --out FILE.h5` (docs/cli.md), with every
quantity the run holds, so that `condyn plot` and h5py read it as a run's file.
"""


def result_bytes(result, path):
    """The bytes of `result` (a condyn.Result) written as HDF5 at `path`, a scratch file."""
    write_result(result, path)
    with open(path, "rb") as f:
        return f.read()


def write_result(result, path):
    """Writes `result` at `path`: the dataset `t`, one per quantity the result holds
    (displacement, velocity, reaction, drift; acceleration, absolute_acceleration and energy
    when the scene's [output] asked for them; multiplier with constraints; points with [output]
    points; derived with [[derived]] columns; near_singular where a row is in a singular
    passage), the names as UTF-8 string
    datasets and the root attributes scheme, rtol, atol (and constraints, as condyn run)."""
    import h5py  # Debian's python3-h5py; imported here, where it is needed
    import numpy as np

    summary = result.summary
    mechanism = result.velocity_names != result.dof_names
    datasets = {"t": result.t, "displacement": result.u, "velocity": result.v,
                "acceleration": result.a, "absolute_acceleration": result.a_abs,
                "reaction": result.reaction,
                "multiplier": result.multiplier if result.constraint_names else None,
                "drift": result.drift, "energy": result.energy_balance, "points": result.points,
                "derived": result.derived if result.derived_names else None,
                "near_singular": (np.asarray(result.near_singular, dtype=np.float64)
                                  if np.any(result.near_singular) else None)}
    names = {"dof_names": result.dof_names, "constraint_names": result.constraint_names,
             "energy_columns": result.energy_columns if result.energy_balance is not None
             else None,
             "point_names": result.point_names if result.points is not None else None,
             "derived_names": result.derived_names or None}
    if mechanism:  # a mechanism's quantities have columns of their own (docs/cli.md)
        names.update(velocity_names=result.velocity_names,
                     acceleration_names=result.acceleration_names,
                     reaction_names=result.reaction_names)
    with h5py.File(path, "w") as f:
        for key in ("scheme", "rtol", "atol", "constraints"):
            if summary.get(key) is not None:
                f.attrs[key] = summary[key]
        for name, data in datasets.items():
            if data is not None:
                f.create_dataset(name, data=np.asarray(data))
        for name, items in names.items():
            if items is not None:
                f.create_dataset(name, data=np.array(list(items), dtype=h5py.string_dtype()))
