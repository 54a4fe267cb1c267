#!/usr/bin/python3
"""Error of flows against a reference flow, at the points debris cares about.

Usage: python3 -m pipelines.flow_error [--box X0,X1,Y0,Y1] SCENE.nc REFERENCE.nc FLOW.nc [FLOW.nc ...]

For each flow, against the reference (typically the finest run), over their common time:
  wg2_rms_m          RMS difference of the WG2 level (gauge series)
  wg2_max_err_m      difference of the WG2 maximum
  FD_depth_rms_m     RMS difference of the depth at the FD start (stored frames)
  LD_depth_rms_m     the same at the LD start
  FD_draft_err_s     difference of the time the depth first exceeds the draft at FD
  LD_draft_err_s     the same at LD
  arrival_mae_s      mean |difference| of the arrival-time map (depth above the draft) over the
                     cells both reach, each flow cell against the reference cell holding its centre
  arrival_only       share of the cells reached by one of the two only (of those either reaches)
  max_depth_mae_m    mean |difference| of the maximum depth over the cells either wets
Grids may differ: values are taken at the cell holding each point. With --box the maps
are compared over the reference's cells inside the box only (a flow run over the box
alone). Prints CSV.
"""
import sys

import numpy as np
import xarray as xr


def seconds(t, t0):
    return (t - t0) / np.timedelta64(1, "s")


def by_standard_name(ds, name, path):
    for v in ds.data_vars:
        if ds[v].attrs.get("standard_name") == name:
            return ds[v]
    sys.exit(f"flow_error.py: {path}: no variable with standard_name '{name}'")


def gauge(ds, name, path):
    names = [str(n) for n in ds.gauge_name.values]
    if name not in names:
        sys.exit(f"flow_error.py: {path}: no gauge '{name}'")
    return seconds(ds.gauge_time.values, ds.time.values[0]), ds.gauge_eta.isel(gauge=names.index(name)).values


def point_series(ds, path, x, y):
    h = by_standard_name(ds, "sea_floor_depth_below_sea_surface", path)
    return seconds(ds.time.values, ds.time.values[0]), h.sel(x=x, y=y, method="nearest").values


def arrival(ds, x, y):
    a = ds.arrival_time
    v = a.sel(x=x, y=y, method="nearest").values
    if np.issubdtype(np.asarray(v).dtype, np.timedelta64):
        v = v / np.timedelta64(1, "s")
    return float(v)


def scene_point(scene, name):
    """(x, y) [m] of the scene's named point (WG1, WG2, FD, LD ...)."""
    names = [str(n) for n in scene.point_name.values]
    if name not in names:
        path = scene.encoding.get("source", "the scene")
        sys.exit(f"{path}: variable point_name: no point '{name}' (the scene has {', '.join(names)})")
    k = names.index(name)
    return float(scene.point_x[k]), float(scene.point_y[k])


def print_csv(rows):
    """rows: [(flow path, {column: value})], all with the same columns."""
    keys = list(rows[0][1].keys())
    print("flow," + ",".join(keys))
    for p, r in rows:
        print(p + "," + ",".join(f"{r[k]:.4g}" for k in keys))
    return keys


def seconds_of(a):
    v = a.values
    if np.issubdtype(v.dtype, np.timedelta64):
        v = v / np.timedelta64(1, "s")
    return np.asarray(v, dtype=float)


def on_reference_grid(field, ref):
    """A (y, x) field of one flow at the reference's cell centres (nearest cell)."""
    return field.sel(x=ref.x, y=ref.y, method="nearest")


def map_errors(ref, ds):
    out = {}
    a_f = seconds_of(on_reference_grid(ds.arrival_time, ref))
    a_r = seconds_of(ref.arrival_time)
    reached_f, reached_r = np.isfinite(a_f), np.isfinite(a_r)
    both, either = reached_f & reached_r, reached_f | reached_r
    out["arrival_mae_s"] = float(np.mean(np.abs(a_f[both] - a_r[both]))) if both.any() else float("nan")
    out["arrival_only"] = float((either & ~both).sum() / max(either.sum(), 1))
    d_f = np.nan_to_num(on_reference_grid(ds.max_depth, ref).values.astype(float))
    d_r = np.nan_to_num(ref.max_depth.values.astype(float))
    wet = (d_f > 0) | (d_r > 0)
    out["max_depth_mae_m"] = float(np.mean(np.abs(d_f[wet] - d_r[wet]))) if wet.any() else float("nan")
    return out


def errors(scene, ref_path, ref, path, box=None):
    ds = xr.open_dataset(path)
    out = {}
    tr, er = gauge(ref, "WG2", ref_path)
    tf, ef = gauge(ds, "WG2", path)
    t_end = min(tr[-1], tf[-1])
    t = tf[tf <= t_end + 1e-9]
    ri = np.interp(t, tr, er)
    out["wg2_rms_m"] = float(np.sqrt(np.mean((ef[: len(t)] - ri) ** 2)))
    out["wg2_max_err_m"] = float(ef[: len(t)].max() - ri.max())
    for p in ("FD", "LD"):
        x, y = scene_point(scene, p)
        t_f, h_f = point_series(ds, path, x, y)
        t_r, h_r = point_series(ref, ref_path, x, y)
        keep = t_f <= min(t_f[-1], t_r[-1]) + 1e-9
        out[f"{p}_depth_rms_m"] = float(np.sqrt(np.mean((h_f[keep] - np.interp(t_f[keep], t_r, h_r)) ** 2)))
        out[f"{p}_draft_err_s"] = arrival(ds, x, y) - arrival(ref, x, y)
    if box is not None:
        x0, x1, y0, y1 = box
        ref = ref.where((ref.x >= x0) & (ref.x <= x1) & (ref.y >= y0) & (ref.y <= y1), drop=True)
    out.update(map_errors(ref, ds))
    return out


def main(argv):
    box = None
    if len(argv) > 2 and argv[1] == "--box":
        box = [float(v) for v in argv[2].split(",")]
        argv = argv[:1] + argv[3:]
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    scene = xr.open_dataset(argv[1])
    ref = xr.open_dataset(argv[2], decode_timedelta=False)
    rows = [(p, errors(scene, argv[2], ref, p, box)) for p in argv[3:]]
    print_csv(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
