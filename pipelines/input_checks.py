"""The checks flotsam's C++ readers make, for the Python pipelines that read the same files
(docs/reliability.md, "Bad input and what it gets"): an input is a regular file of the
kind asked for, its units convert (or are refused by name), its values are finite and in
range, files given together share a CRS, and no output lands on an input. A problem is an
InputError whose message names the file, the variable and what is wrong; a pipeline's
main turns it into one line and exit status 1 (`run`).
"""
import math
import os
import stat
import sys

import numpy as np

# The bounds of a stored track (formats/trajectory_file.hpp).
MAX_TRACK_COORDINATE = 1e8  # [m]
MAX_TRACK_SPEED = 1000.0    # [m s-1]
MAX_DEPTH = 11000.0         # [m] no ocean is deeper (hydro's own state check)

KINDS = {"scene": "a scene (written by `flotsam scene generate` or `scene import`)",
         "flow": "a flow file (written by `flotsam hydro`)",
         "trajectories": "a trajectory file (written by `flotsam debris`)",
         "sweep": "a sweep file (written by `flotsam sweep`)",
         "stats": "a statistics file (written by `flotsam stats`)",
         "boundary": "boundary values (written by `flotsam hydro --boundary-output`)"}


class InputError(Exception):
    """A named problem with an input: '<file>: <what>: <problem>'."""


def fail(path, what, problem):
    raise InputError(": ".join(p for p in (path, what, problem) if p))


def run(name, main, argv=None):
    """main(argv) with an InputError (or a file that cannot be read) as one line and exit 1."""
    try:
        return main(argv)
    except InputError as e:
        sys.exit(f"{name}: error: {e}")
    except OSError as e:  # netCDF4's and the file system's own, named
        sys.exit(f"{name}: error: {e.filename or ''}: {e.strerror or e}".replace(": : ", ": "))


def file_type(path):
    try:
        m = os.stat(path).st_mode
    except OSError:
        return ""
    for test, name in ((stat.S_ISREG, "a regular file"), (stat.S_ISDIR, "a directory"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket")):
        if test(m):
            return name
    return "not a regular file"


def input_file(option, path):
    """An input must exist and be a regular file: a FIFO or a device may never end."""
    kind = file_type(path)
    if not kind:
        fail(option, path, "does not exist")
    if kind != "a regular file":
        fail(option, path, f"is {kind}, not a regular file: flotsam reads its inputs from files (a device or a pipe may never end)")


def outputs_not_inputs(outputs, inputs):
    """No output (nor its .part) is one of the inputs: compared by device and inode."""
    def ident(p):
        try:
            s = os.stat(p)
            return (s.st_dev, s.st_ino)
        except OSError:
            return None
    seen = {ident(p): (opt, p) for opt, p in inputs if ident(p)}
    for opt, p in outputs:
        for q in (p, p + ".part"):
            i = ident(q)
            if i and i in seen:
                fail(opt, p, f"{'its temporary file ' + q + ' ' if q != p else ''}is the input given as {seen[i][0]} "
                             f"({seen[i][1]}): an output never overwrites an input; choose another {opt}")
            kind = file_type(q)
            if kind and kind != "a regular file":
                fail(opt, q, f"is {kind}, not a regular file")


def open_nc(option, path, kinds):
    """The file opened with netCDF4, after the checks of input_file, and of one of `kinds`."""
    import netCDF4
    input_file(option, path)
    try:
        ds = netCDF4.Dataset(path)
    except OSError as e:
        fail(option, path, f"cannot open as NetCDF: {e.strerror or e}")
    kind = getattr(ds, "flotsam_file_kind", "")
    if kind and kind not in kinds:
        ds.close()
        fail(option, path, f"is {KINDS.get(kind, repr(kind))}, not " + " or ".join(KINDS[k] for k in kinds))
    return ds


def variable(ds, name):
    if name not in ds.variables:
        fail(ds.filepath(), f"variable '{name}'", "missing")
    return ds.variables[name]


LENGTHS = {"m": 1.0, "metre": 1.0, "metres": 1.0, "meter": 1.0, "meters": 1.0, "cm": 0.01, "mm": 0.001, "km": 1000.0,
           "ft": 0.3048, "foot": 0.3048, "feet": 0.3048, "in": 0.0254, "inch": 0.0254, "mi": 1609.344, "mile": 1609.344,
           "miles": 1609.344, "nmile": 1852.0}
TIMES = {"s": 1.0, "sec": 1.0, "second": 1.0, "seconds": 1.0, "min": 60.0, "minute": 60.0, "minutes": 60.0, "h": 3600.0,
         "hr": 3600.0, "hour": 3600.0, "hours": 3600.0, "d": 86400.0, "day": 86400.0, "days": 86400.0}


def _speed(u):
    if u in ("knot", "knots", "kt", "kn"):
        return 1852.0 / 3600.0
    if "/" in u:
        a, b = (p.strip() for p in u.split("/", 1))
    else:
        parts = u.replace(".", " ").split()
        if len(parts) != 2:
            return None
        a, b = parts
        for sfx in ("**-1", "^-1", "-1"):
            if b.endswith(sfx):
                b = b[:-len(sfx)]
                break
        else:
            return None
    return LENGTHS[a] / TIMES[b] if a in LENGTHS and b in TIMES else None


def unit_factor(ds, name, kind):
    """The factor from variable `name`'s units to m ("length"), s ("time") or m s-1 ("speed");
    1 without units; an InputError naming the unit otherwise (common/units.hpp)."""
    u = str(getattr(variable(ds, name), "units", "")).strip().lower()
    if not u:
        return 1.0
    if kind == "time":
        u = u.split(" since ")[0].strip()
    factor = {"length": LENGTHS.get, "time": TIMES.get, "speed": _speed}[kind](u)
    if factor is None:
        fail(ds.filepath(), f"variable '{name}' attribute 'units'", f"'{u}' is not a unit of {kind} flotsam can convert")
    return factor


def finite_values(ds, name, kind, bound=None, lo=None):
    """A variable's values as floats in flotsam's units, every one finite (no fill value) and,
    when given, |value| <= bound and value >= lo."""
    v = variable(ds, name)
    v.set_auto_mask(False)
    raw = np.asarray(v[:], dtype=float)
    fill = getattr(v, "_FillValue", None)
    bad = ~np.isfinite(raw) | (np.abs(raw) >= 9.96e36)
    if fill is not None:
        bad |= raw == float(fill)
    if bad.any():
        k = int(np.flatnonzero(bad.ravel())[0])
        fail(ds.filepath(), f"variable '{name}'", f"value at flat index {k} is {raw.ravel()[k]!r}: NaN, infinite or a fill value")
    values = raw * unit_factor(ds, name, kind)
    if bound is not None and (np.abs(values) > bound).any():
        k = int(np.flatnonzero((np.abs(values) > bound).ravel())[0])
        fail(ds.filepath(), f"variable '{name}'", f"{values.ravel()[k]:g} at flat index {k} is beyond +-{bound:g}")
    if lo is not None and (values < lo).any():
        k = int(np.flatnonzero((values < lo).ravel())[0])
        fail(ds.filepath(), f"variable '{name}'", f"{values.ravel()[k]:g} at flat index {k} is below {lo:g}")
    return values


def flags(ds, name):
    """A variable of 0 and 1 (a mask such as a flow's `flooded`); None when it was never
    written (every value its fill value), a named error for any other value."""
    v = variable(ds, name)
    v.set_auto_mask(False)
    values = np.asarray(v[:], dtype=float)
    fill = getattr(v, "_FillValue", None)
    if fill is None:
        fill = {"i1": -127, "b": -127, "i2": -32767, "i4": -2147483647}.get(v.dtype.str[1:], None)
    if fill is not None and values.size and (values == float(fill)).all():
        return None
    bad = ~((values == 0) | (values == 1))
    if bad.any():
        k = int(np.flatnonzero(bad.ravel())[0])
        fail(ds.filepath(), f"variable '{name}'", f"value at flat index {k} is {values.ravel()[k]!r}, not 0 or 1")
    return values


def time_axis(ds, name="time"):
    t = finite_values(ds, name, "time")
    steps = np.diff(t)
    if len(steps) and not (steps > 0).all():
        k = int(np.flatnonzero(~(steps > 0))[0]) + 1
        fail(ds.filepath(), f"variable '{name}'", f"must increase (at index {k})")
    return t


def tracks(ds):
    """x, y (trajectory, time) [m] and the times [s] of a trajectory or sweep file, checked as
    formats/trajectory_file.hpp's TrackReader checks them."""
    t = time_axis(ds)
    xy = [finite_values(ds, n, "length", MAX_TRACK_COORDINATE) for n in ("x", "y")]
    for n in ("u", "v"):
        if n in ds.variables:
            finite_values(ds, n, "speed", MAX_TRACK_SPEED)
    x, y = xy
    if x.ndim != 2 or x.shape != y.shape or x.shape[1] != len(t):
        fail(ds.filepath(), "variables 'x', 'y'", f"must have dimensions (trajectory, time) = (n, {len(t)})")
    if len(t) > 1:
        speed = np.hypot(np.diff(x, axis=1), np.diff(y, axis=1)) / np.diff(t)
        if (speed > MAX_TRACK_SPEED).any():
            b, k = np.unravel_index(int(np.argmax(speed > MAX_TRACK_SPEED)), speed.shape)
            fail(ds.filepath(), "variables 'x', 'y'",
                 f"trajectory {b}, time index {k + 1}: the body moves at {speed[b, k]:g} m/s, more than the "
                 f"{MAX_TRACK_SPEED:g} m/s of any debris")
    return x, y, t


def within(path, x, y, grid_x, grid_y, what):
    """Every position within the cells of axes grid_x, grid_y [m] (a body never leaves them)."""
    dx, dy = grid_x[1] - grid_x[0], grid_y[1] - grid_y[0]
    lo_x, hi_x = grid_x[0] - 0.5 * dx * (1 + 1e-6), grid_x[-1] + 0.5 * dx * (1 + 1e-6)
    lo_y, hi_y = grid_y[0] - 0.5 * dy * (1 + 1e-6), grid_y[-1] + 0.5 * dy * (1 + 1e-6)
    out = (x < lo_x) | (x > hi_x) | (y < lo_y) | (y > hi_y)
    if out.any():
        b, k = np.unravel_index(int(np.argmax(out)), out.shape)
        fail(path, "variables 'x', 'y'", f"trajectory {b}, time index {k}: ({x[b, k]:g}, {y[b, k]:g}) m lies outside "
                                         f"{what} (x {lo_x:g} to {hi_x:g}, y {lo_y:g} to {hi_y:g} m)")


def crs_of(ds, var):
    """The name of `var`'s grid mapping's WKT ('' for local metres)."""
    name = getattr(ds.variables[var], "grid_mapping", "") if var in ds.variables else ""
    if not name:
        return ""
    if name not in ds.variables:
        fail(ds.filepath(), f"variable '{var}' attribute 'grid_mapping'", f"names '{name}', which is not in the file")
    return str(getattr(ds.variables[name], "crs_wkt", "")) or str(getattr(ds.variables[name], "grid_mapping_name", "custom"))


def same_crs(a_path, a, b_path, b):
    if a != b:
        label = lambda c: "none (local metres)" if not c else ("a map projection" if len(c) > 60 else c)
        fail(a_path, "crs", f"is {label(a)}, that of {b_path} is {label(b)}: files in different coordinate reference "
                            "systems do not combine (positions would mean other places)")
