#!/usr/bin/python3
"""The paper's timing numbers from one or more flow files.

Usage: python3 -m pipelines.flow_timing SCENE.nc FLOW.nc [FLOW.nc ...]

For each flow: the largest level at WG2 and when, the first time the WG2 level exceeds
1 cm, and the time the depth first exceeds the arrival depth (the 2.5 cm draft) at the
scene's FD and LD start points. Paper (Chida & Mori): WG2 max ~0.063 m; water in the
channel above 1 cm at ~30 s; FD start under the draft until ~40 s; LD moves at 180-200 s.
With several flows, also the ensemble mean and standard deviation.
"""
import sys

import numpy as np
import xarray as xr

from pipelines.flow_error import arrival, print_csv, scene_point, seconds


def timing(scene, path):
    ds = xr.open_dataset(path)
    t0 = ds.time.values[0]
    names = [str(n) for n in ds.gauge_name.values]
    out = {}
    if "WG2" in names:
        eta = ds.gauge_eta.isel(gauge=names.index("WG2"))
        gt = seconds(ds.gauge_time.values, t0)
        k = int(eta.argmax())
        out["wg2_max_m"] = float(eta[k])
        out["wg2_max_time_s"] = float(gt[k])
        above = np.nonzero(eta.values > 0.01)[0]
        out["wg2_1cm_time_s"] = float(gt[above[0]]) if above.size else float("nan")
    for name in ("FD", "LD"):
        out[f"{name}_draft_time_s"] = arrival(ds, *scene_point(scene, name))
    return out


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    scene = xr.open_dataset(argv[1])
    rows = [(p, timing(scene, p)) for p in argv[2:]]
    keys = print_csv(rows)
    if len(rows) > 1:
        for label, f in (("mean", np.nanmean), ("std", np.nanstd)):
            print(label + "," + ",".join(f"{f([r[k] for _, r in rows]):.4g}" for k in keys))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
