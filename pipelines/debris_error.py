#!/usr/bin/python3
"""How far debris replayed through a flow ends from the same bodies replayed through a reference flow.

Usage: python3 -m pipelines.debris_error REFERENCE.traj.nc RUN.traj.nc [RUN.traj.nc ...] [--times 30,60,150]
           [--length 0.25]

The files are `flotsam debris` trajectory files with the same bodies in the same order
(typically the scene's start points, `--start FD --start LD`, over two flows). For each run
and body: the distance of the body centre from the reference's at each time, in body
lengths, and the difference of its largest heading change within the first time [deg];
with more than one body, a row `all` gives the median of those over the bodies and the
distance between the two ensembles' centroids (`centroid_*`), which single bodies'
chaotic paths move far less. Prints CSV.
"""
import argparse
import sys

import numpy as np
import xarray as xr


def at(ds, name, k, t):
    times = (ds.time.values - ds.time.values[0]) / np.timedelta64(1, "s") if ds.time.dtype.kind == "M" else ds.time.values
    return float(np.interp(t, times, ds[name].values[k])), times


def largest_turn(ds, k, t_end):
    _, times = at(ds, "yaw", k, 0.0)
    yaw = ds.yaw.values[k][times <= t_end]
    if not str(ds.yaw.attrs.get("units", "")).startswith("degree"):
        yaw = np.degrees(yaw)
    return float(np.max(np.abs(yaw - yaw[0])))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("reference")
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--times", default="30,60,150", help="times [s] at which to compare positions")
    ap.add_argument("--length", type=float, default=0.25, help="body length [m] the distances are given in")
    a = ap.parse_args(argv[1:])
    times = [float(t) for t in a.times.split(",")]
    ref = xr.open_dataset(a.reference, decode_times=False)
    print("run,body," + ",".join(f"distance_{t:g}s_lengths" for t in times) + f",largest_turn_0_{times[0]:g}s_err_deg,"
          + ",".join(f"centroid_{t:g}s_lengths" for t in times))
    for path in a.runs:
        run = xr.open_dataset(path, decode_times=False)
        n = ref.sizes["trajectory"]
        if run.sizes["trajectory"] != n:
            sys.exit(f"debris_error.py: {path}: {run.sizes['trajectory']} bodies, the reference has {n}")
        rows, shift = [], []
        for t in times:
            xy = [[at(ds, c, k, t)[0] for k in range(n)] for ds in (run, ref) for c in ("x", "y")]
            shift.append(np.hypot(np.mean(xy[0]) - np.mean(xy[2]), np.mean(xy[1]) - np.mean(xy[3])) / a.length)
        for k in range(n):
            d = [np.hypot(at(run, "x", k, t)[0] - at(ref, "x", k, t)[0], at(run, "y", k, t)[0] - at(ref, "y", k, t)[0]) / a.length
                 for t in times]
            rows.append(d + [largest_turn(run, k, times[0]) - largest_turn(ref, k, times[0])])
            if n <= 4:
                print(f"{path},{k}," + ",".join(f"{v:.2f}" for v in rows[-1][:-1]) + f",{rows[-1][-1]:.1f}," + "," * (len(times) - 1))
        if n > 1:
            med = np.median(np.abs(np.array(rows)), axis=0)
            print(f"{path},all," + ",".join(f"{v:.2f}" for v in med[:-1]) + f",{med[-1]:.1f}," + ",".join(f"{v:.2f}" for v in shift))

if __name__ == "__main__":
    main(sys.argv)
