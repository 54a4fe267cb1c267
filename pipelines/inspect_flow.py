#!/usr/bin/python3
"""Summarise a flotsam flow file through xarray (Debian's python3-xarray).

Usage: python3 -m pipelines.inspect_flow FLOW.nc [--check]

Prints the decoded time axis, the variables found by CF standard_name, the gauges and
the largest depth and speed. With --check, exits non-zero unless the time axis decodes
to datetimes and h, u, v are found by their standard names (used by the tests).
"""
import sys

import numpy as np
import xarray as xr

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
    for label, sn in STANDARD_NAMES.items():
        found = [name for name, v in ds.data_vars.items() if v.attrs.get("standard_name") == sn]
        ok &= len(found) == 1
        print(f"{label:11s} standard_name={sn}: {found[0] if found else 'MISSING'}")
    if "max_depth" in ds:
        print(f"largest depth {float(ds.max_depth.max()):.4f} m, largest speed {float(ds.max_speed.max()):.3f} m/s")
    if "gauge_name" in ds:
        for k, name in enumerate(ds.gauge_name.values):
            eta = ds.gauge_eta.isel(gauge=k)
            print(f"gauge {name}: max level {float(eta.max()):.4f} m at "
                  f"{float((eta.gauge_time[int(eta.argmax())] - ds.gauge_time[0]) / np.timedelta64(1, 's')):.1f} s")
    for key in ("title", "source", "realisation", "boundary_file", "boundary_checksum"):
        if key in ds.attrs:
            print(f"{key}: {ds.attrs[key]}")
    if check and not ok:
        print("CHECK FAILED: time not decoded or standard names missing", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
