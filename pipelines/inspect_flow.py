#!/usr/bin/python3
"""Summarise a flotsam flow file through xarray (Debian's python3-xarray).

Usage: python3 -m pipelines.inspect_flow FLOW.nc [--check] [--stranded-seconds S]

Prints the decoded time axis, the variables found by CF standard_name, the gauges and
the largest depth and speed, and any stranded fast water (below). With --check, exits
non-zero unless the time axis decodes to datetimes, h, u, v are found by their standard
names and no water is stranded (used by the tests).

Stranded fast water: a cell holding at least 1 mm that moves at 0.3 m/s or more with no
outlet (no velocity component of 0.1 m/s or more toward a neighbour, in x or in y, holding
a twentieth of its depth or more), in every frame for 30 s or more (--stranded-seconds).
A front does that for a frame or two and moves on; water that does it frame after frame
is running into faces the scheme keeps shut, with nowhere for its discharge to go: the
signature of the defect of docs/hydro.md, "A puddle in a pit" (9 mm at 1.4 m/s, the same
in every frame for minutes).
"""
import sys

import numpy as np
import xarray as xr

STRANDED_DEPTH = 1e-3  # [m]
STRANDED_SPEED = 0.3  # [m/s]
STRANDED_RATIO = 0.05  # a neighbour with less than this times the cell's depth is no outlet
STRANDED_OUTLET = 0.1  # [m/s] the least velocity component toward an outlet
STRANDED_SECONDS = 30.0  # [s], and at least three frames


def stranded_water(ds, depth="h", x_velocity="u", y_velocity="v", seconds=STRANDED_SECONDS):
    """Cells with stranded fast water (module docstring), as (frames in the run, t_end [s],
    x, y, h [m], u, v [m/s]) of each cell's longest run, longest first; the variables by
    name (main finds them by standard_name)."""
    h_all, u_all, v_all = ds[depth], ds[x_velocity], ds[y_velocity]
    t = (ds["time"] - ds["time"][0]) / np.timedelta64(1, "s") if np.issubdtype(ds["time"].dtype, np.datetime64) else ds["time"]
    run = np.zeros(h_all.shape[1:], dtype=np.int32)
    best = np.zeros_like(run)
    best_at = np.full(run.shape, -1, dtype=np.int32)
    for k in range(ds.sizes["time"]):
        h = np.nan_to_num(h_all[k].values.astype(np.float64))
        u = np.nan_to_num(u_all[k].values.astype(np.float64))
        v = np.nan_to_num(v_all[k].values.astype(np.float64))
        # The neighbours the flow points at in x and in y (edges: the cell itself); a
        # component of STRANDED_OUTLET or more toward one that holds water is an outlet.
        hp = np.pad(h, 1, mode="edge")
        x_down = np.where(u > 0, hp[1:-1, 2:], hp[1:-1, :-2])
        y_down = np.where(v > 0, hp[2:, 1:-1], hp[:-2, 1:-1])
        outlet = ((np.abs(u) >= STRANDED_OUTLET) & (x_down >= STRANDED_RATIO * h)) | \
                 ((np.abs(v) >= STRANDED_OUTLET) & (y_down >= STRANDED_RATIO * h))
        flagged = (h >= STRANDED_DEPTH) & (np.hypot(u, v) >= STRANDED_SPEED) & ~outlet
        run = np.where(flagged, run + 1, 0)
        longer = run > best
        best = np.where(longer, run, best)
        best_at = np.where(longer, k, best_at)
    found = []
    t = np.asarray(t, dtype=np.float64)
    ends = np.maximum(best_at, 0)
    span = t[ends] - t[np.maximum(ends - best + 1, 0)]  # [s] from the run's first frame to its last
    for j, i in zip(*np.nonzero((best >= 3) & (span >= seconds))):
        k = int(best_at[j, i])
        found.append((int(best[j, i]), float(t[k]), float(ds.x[i]), float(ds.y[j]), float(h_all[k, j, i]),
                      float(u_all[k, j, i]), float(v_all[k, j, i])))
    return sorted(found, reverse=True)


STANDARD_NAMES = {
    "depth": "sea_floor_depth_below_sea_surface",
    "x velocity": "sea_water_x_velocity",
    "y velocity": "sea_water_y_velocity",
}


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    path, check = argv[1], "--check" in argv[2:]
    seconds = STRANDED_SECONDS
    if "--stranded-seconds" in argv[2:]:
        k = argv.index("--stranded-seconds") + 1
        try:
            seconds = float(argv[k])
        except (IndexError, ValueError):
            print(f"inspect_flow: --stranded-seconds needs a number of seconds, got {argv[k] if k < len(argv) else 'nothing'}",
                  file=sys.stderr)
            return 2
    ds = xr.open_dataset(path)
    ok = True
    time = ds["time"]
    decoded = np.issubdtype(time.dtype, np.datetime64)
    ok &= decoded
    elapsed = (time - time[0]) / np.timedelta64(1, "s") if decoded else time
    print(f"{path}: {ds.sizes['time']} frames, t = {float(elapsed[0]):g} .. {float(elapsed[-1]):g} s "
          f"(time decoded as {'datetime64' if decoded else 'raw numbers: NOT decoded'})")
    print(f"grid: {ds.sizes['x']} x {ds.sizes['y']} cells, x {float(ds.x[0]):.3f} .. {float(ds.x[-1]):.3f} m, "
          f"y {float(ds.y[0]):.3f} .. {float(ds.y[-1]):.3f} m")
    names = {}
    for label, sn in STANDARD_NAMES.items():
        found = [name for name, v in ds.data_vars.items() if v.attrs.get("standard_name") == sn]
        ok &= len(found) == 1
        if len(found) == 1:
            names[label] = found[0]
        print(f"{label:11s} standard_name={sn}: {found[0] if found else 'MISSING'}")
    if "max_depth" in ds:
        print(f"largest depth {float(ds.max_depth.max()):.4f} m, largest speed {float(ds.max_speed.max()):.3f} m/s")
    if "gauge_name" in ds:
        for k, name in enumerate(ds.gauge_name.values):
            eta = ds.gauge_eta.isel(gauge=k)
            print(f"gauge {name}: max level {float(eta.max()):.4f} m at "
                  f"{float((eta.gauge_time[int(eta.argmax())] - ds.gauge_time[0]) / np.timedelta64(1, 's')):.1f} s")
    stranded = stranded_water(ds, *(names[k] for k in STANDARD_NAMES), seconds=seconds) if len(names) == 3 else []
    ok &= not stranded
    if stranded:
        print(f"STRANDED FAST WATER in {len(stranded)} cell(s) (>= {STRANDED_DEPTH * 1e3:g} mm at >= {STRANDED_SPEED:g} m/s "
              f"with no outlet, every frame for {seconds:g} s or more); the longest:")
        for n, t_end, x, y, h, u, v in stranded[:5]:
            print(f"  ({x:.3f}, {y:.3f}) m: {n} frames to t = {t_end:g} s, h {h * 1e3:.2f} mm, u {u:+.2f}, v {v:+.2f} m/s")
    else:
        print("stranded fast water: none")
    for key in ("title", "source", "realisation", "boundary_file", "boundary_checksum"):
        if key in ds.attrs:
            print(f"{key}: {ds.attrs[key]}")
    if check and not ok:
        print("CHECK FAILED: time not decoded, standard names missing, or stranded fast water", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
