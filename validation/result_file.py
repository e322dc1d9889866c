"""A run's result file as `condyn plot` reads it: the CSV or HDF5 of `condyn run` (docs/cli.md),
and the mode shapes of `condyn modes`, checked cell by cell.

Every refusal is a BadInput whose message names the file, the line or dataset, and what is
wrong; plot_result.py prints it and exits 2. Which columns to draw is plot_result.py's.
"""
import plot_shapes as shapes

# The energy terms in the order drawn, with their labels.
ENERGY_TERMS = (("energy_kinetic", "kinetic T"), ("energy_potential", "potential V"),
                ("energy_dissipated", "dissipated D"), ("work_loads", "work of loads"),
                ("work_constraints", "work of constraints"),
                ("energy", "total T + V"))

# Every energy column condyn writes (kEnergyColumns in models/scene/scene_spec.hpp): matched by name,
# not by prefix, since a DOF may be named energy_top or work_1 (it is then a displacement).
ENERGY_NAMES = {c for c, _ in ENERGY_TERMS} | {"energy_error"}
DRIFT_NAMES = {"drift_position", "drift_velocity"}
# 1 on the rows inside a passage near a singular configuration, else 0 (docs/cli.md): not a DOF.
NEAR_SINGULAR = "near_singular"
# A mechanism's CSV (docs/cli.md, "Mechanisms") names its columns per body and joint without a
# prefix: its pose columns (`crank.angle` in 2D, `crank.qw` in 3D) mark it, and the columns
# ending in a rate or a joint's force or torque are its velocities, accelerations and reactions,
# not displacements. Named points (`crank.B.x`) are positions, drawn as displacements.
MECHANISM_POSES = (".angle", ".qw")
MECHANISM_RATES = {"vx", "vy", "vz", "omega", "wx", "wy", "wz", "ax", "ay", "az", "alpha",
                   "alphax", "alphay", "alphaz", "fx", "fy", "fz", "m", "mx", "my", "mz"}
PER_DOF = ("vel_", "acc_", "reaction_")  # the prefixes of a DOF's other quantities in a CSV


def energy_columns(columns):
    """The energy terms present, with their labels (energy_error has its own panel)."""
    return [(c, label) for c, label in ENERGY_TERMS if c in columns]


class BadInput(Exception):
    pass


def finite_table(np, path, header, rows):
    """Checks a result's columns: names unique and not empty, t first, every cell a finite
    number, t not decreasing. `rows` holds the data lines (line number, cells)."""
    if header and header[0] == "dof":
        raise BadInput(f"{path}: not a condyn result (its first column is not t): mode shapes "
                       "(condyn modes --shapes) are drawn with --scene SCENE")
    if not header or header[0] != "t":
        raise BadInput(f"{path}: not a condyn result (its first column is not t)")
    seen = set()
    for name in header:
        if not name or name in seen:
            raise BadInput(f"{path}:1: " + (f"column '{name}' named twice" if name else
                                            "a column without a name"))
        seen.add(name)
    if not rows:
        raise BadInput(f"{path}: no rows")
    for number, cells in rows:
        if len(cells) != len(header):
            raise BadInput(f"{path}:{number}: {len(cells)} cells for the header's "
                           f"{len(header)} columns")
    try:
        data = np.array([cells for _, cells in rows], dtype=float)
    except ValueError:  # find the cell, row by row (the fast path above fails only here)
        for number, cells in rows:
            for cell in cells:
                try:
                    float(cell)
                except ValueError:
                    raise BadInput(f"{path}:{number}: '{cell[:40]}' is not a number") from None
        raise
    bad = np.argwhere(~np.isfinite(data))
    if bad.size:
        k, j = bad[0]
        raise BadInput(f"{path}:{rows[k][0]}: column {header[j]}: '{rows[k][1][j].strip()}' is "
                       "not a finite number (condyn writes none)")
    back = np.flatnonzero(np.diff(data[:, 0]) < 0)
    if back.size:
        k = back[0] + 1
        raise BadInput(f"{path}:{rows[k][0]}: t = {data[k, 0]:g} after t = {data[k - 1, 0]:g} "
                       "(times must not decrease)")
    return data


def read_csv(np, path):
    with open(path, "rb") as f:
        raw = f.read()
    if not raw.strip():
        raise BadInput(f"{path}: empty file (condyn plot reads the CSV or HDF5 of condyn run)")
    if b"\0" in raw:
        line = raw[:raw.index(b"\0")].count(b"\n") + 1
        raise BadInput(f"{path}:{line}: binary data (a NUL byte), not a CSV")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        line = raw[:e.start].count(b"\n") + 1
        raise BadInput(f"{path}:{line}: not UTF-8 text (byte 0x{raw[e.start]:02x}): "
                       "not a condyn result") from None
    lines = text.splitlines()
    header = lines[0].strip().split(",")
    rows = [(n, line.strip().split(",")) for n, line in enumerate(lines[1:], start=2)
            if line.strip()]
    data = finite_table(np, path, header, rows)
    columns = {name: data[:, k] for k, name in enumerate(header)}
    prefixed = ("vel_", "acc_", "reaction_", "lambda_")
    # The flag of rows near a singular configuration, when written, is the last column.
    values = header[1:-1] if header[-1] == NEAR_SINGULAR else header[1:]
    dofs = [n for n in values
            if not n.startswith(prefixed) and n not in ENERGY_NAMES and n not in DRIFT_NAMES]
    others = []
    if any(n.endswith(MECHANISM_POSES) for n in dofs):
        dofs = [n for n in dofs if "." not in n or n.rsplit(".", 1)[1] not in MECHANISM_RATES]
    else:
        # A CSV with a DOF's velocity, acceleration or reaction columns names its DOFs through
        # them ([output] dofs selects the same DOFs for every quantity): the other unprefixed
        # columns are [[derived]] columns. Without such columns they cannot be told apart.
        named = {n[len(p):] for n in values for p in PER_DOF
                 if n.startswith(p) and not n.startswith("acc_abs_")}
        if named:
            others = [n for n in dofs if n not in named]
            dofs = [n for n in dofs if n in named]
    # acc_abs_ columns exist only under [ground_motion]: the displacements are relative to it
    return columns, dofs, any(n.startswith("acc_abs_") for n in header), others


def h5_names(h5py, f, path, name):
    """A dataset of names, fixed-length bytes or variable-length strings, as a list of str."""
    ds = h5_dataset(h5py, f, path, name)
    if ds.ndim != 1 or not (ds.dtype.kind == "S" or h5py.check_string_dtype(ds.dtype)):
        raise BadInput(f"{path}: dataset {name} is not a list of names "
                       f"(shape {ds.shape}, type {ds.dtype})")
    names = []
    for s in h5_read(path, name, ds):
        try:
            names.append(s.decode("utf-8") if isinstance(s, bytes) else str(s))
        except UnicodeDecodeError:
            raise BadInput(f"{path}: dataset {name}: a name that is not UTF-8") from None
    return names


def h5_dataset(h5py, f, path, name):
    item = f.get(name)
    if not isinstance(item, h5py.Dataset):
        raise BadInput(f"{path}: not a condyn result (no dataset {name})" if item is None else
                       f"{path}: {name} is a group, not a dataset")
    return item


def h5_read(path, name, ds):
    try:
        return ds[()]
    except (OSError, ValueError, TypeError) as e:
        raise BadInput(f"{path}: dataset {name} cannot be read (a truncated or damaged file?: "
                       f"{e})") from None


def h5_numbers(np, h5py, f, path, name, shape):
    """A numeric dataset of the given shape (None: any length), every entry finite."""
    ds = h5_dataset(h5py, f, path, name)
    if ds.dtype.kind not in "fiu":
        raise BadInput(f"{path}: dataset {name} holds {ds.dtype}, not numbers")
    if len(ds.shape) != len(shape) or any(
            want is not None and have != want for have, want in zip(ds.shape, shape)):
        want = " x ".join("n" if w is None else str(w) for w in shape)
        raise BadInput(f"{path}: dataset {name} is {' x '.join(map(str, ds.shape)) or 'a scalar'}"
                       f", expected {want} (the rows of t, the columns its names give)")
    values = np.asarray(h5_read(path, name, ds), dtype=float)
    if not np.isfinite(values).all():
        raise BadInput(f"{path}: dataset {name} holds values that are not finite numbers "
                       "(condyn writes none)")
    return values


def read_h5(np, path):
    try:
        import h5py
    except ImportError:
        raise SystemExit(3)
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise BadInput(f"{path}: not an HDF5 file, or a damaged one ({e})") from None
    with f:
        if "t" not in f and "shapes" in f:
            raise BadInput(f"{path}: the modes of condyn modes, not a run's result: mode shapes "
                           "are drawn with --scene SCENE")
        if "t" not in f:
            raise BadInput(f"{path}: not a condyn result (no dataset t), nor the modes of "
                           "condyn modes (no dataset shapes)")
        t = h5_numbers(np, h5py, f, path, "t", (None,))
        if not t.size:
            raise BadInput(f"{path}: no rows")
        if (np.diff(t) < 0).any():
            raise BadInput(f"{path}: dataset t decreases (times must not decrease)")
        nt = t.size
        columns, dofs = {"t": t}, []
        if "displacement" in f:
            dofs = h5_names(h5py, f, path, "dof_names")
            u = h5_numbers(np, h5py, f, path, "displacement", (nt, len(dofs)))
            if len(set(dofs)) != len(dofs):
                raise BadInput(f"{path}: dataset dof_names names a DOF twice")
            columns.update({name: u[:, k] for k, name in enumerate(dofs)})
        if "drift" in f:
            d = h5_numbers(np, h5py, f, path, "drift", (nt, 2))
            columns["drift_position"], columns["drift_velocity"] = d[:, 0], d[:, 1]
        if "energy" in f:
            names = h5_names(h5py, f, path, "energy_columns")
            e = h5_numbers(np, h5py, f, path, "energy", (nt, len(names)))
            columns.update({name: e[:, k] for k, name in enumerate(names)})
        derived = []
        if "derived" in f:  # [[derived]] columns, named by derived_names
            derived = h5_names(h5py, f, path, "derived_names")
            d = h5_numbers(np, h5py, f, path, "derived", (nt, len(derived)))
            columns.update({name: d[:, k] for k, name in enumerate(derived)})
        return columns, dofs, "absolute_acceleration" in f, derived


def mode_shapes_file(path):
    """Whether `path` holds mode shapes: the CSV of `condyn modes --shapes` (its first column
    `dof`) or the HDF5 of `condyn modes --out` (a dataset shapes, no t)."""
    if path.lower().endswith((".h5", ".hdf5", ".hdf")):
        try:
            import h5py
        except ImportError:
            raise SystemExit(3)
        try:
            with h5py.File(path, "r") as f:
                return "shapes" in f and "t" not in f
        except OSError:
            return False  # read_result names the problem
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return f.readline().split(",", 1)[0].strip() == "dof"
    except OSError:
        return False  # read_result names the problem


def read_modes_h5(np, path):
    """The HDF5 of `condyn modes --out` (docs/cli.md): {dof: row of shapes}, the mode labels
    (mode_1, ...) and omega per mode; BadInput naming the file and the dataset at fault."""
    import h5py
    with h5py.File(path, "r") as f:
        dofs = h5_names(h5py, f, path, "dof_names")
        if len(set(dofs)) != len(dofs):
            raise BadInput(f"{path}: dataset dof_names names a DOF twice")
        mode = h5_numbers(np, h5py, f, path, "mode", (None,))
        count = mode.size
        if count == 0 or (mode != np.arange(1, count + 1)).any():
            raise BadInput(f"{path}: dataset mode is not the mode numbers 1 to K")
        omega = h5_numbers(np, h5py, f, path, "omega", (count,))
        if (omega < 0).any():
            raise BadInput(f"{path}: dataset omega holds a negative frequency")
        phi = h5_numbers(np, h5py, f, path, "shapes", (len(dofs), count))
    return ({d: phi[k] for k, d in enumerate(dofs)}, [f"mode_{j}" for j in range(1, count + 1)],
            omega)


def read_mode_shapes(np, path):
    """Mode shapes from the CSV of `condyn modes --shapes` (no frequencies: omega None) or the
    HDF5 of `condyn modes --out`: (shapes, modes, omega). BadInput names the file and problem."""
    if path.lower().endswith((".h5", ".hdf5", ".hdf")):
        return read_modes_h5(np, path)
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
        table, modes = shapes.read_shapes(np, path, lines[0].strip().split(","), lines)
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise BadInput(str(e) if isinstance(e, ValueError) and str(e).startswith(path)
                       else f"{path}: cannot be read as mode shapes ({e})") from None
    return table, modes, None
