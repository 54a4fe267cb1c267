#!/usr/bin/python3
"""Hydro cost against error on the real layout: grid × scheme × nesting.

    accuracy_hydro.py --dem DEM.nc --runs DIR --csv OUT.csv [--duration 420]
                      [--configs 0.08:fv:1,0.04:fv:1,...] [--reference 0.02:fv:1]
                      [--flotsam build/flotsam] [--threads 1]

Each configuration is RES:SCHEME:NEST_RATIO (nest ratio 1 = one uniform grid). Every run
is the benchmark forcing (--west pump) for --duration seconds; a run whose flow and
timing file already exist is not repeated (delete them to redo). The CSV has one row per
run: its CPU time (user + system, on one thread by default, so that other work on a
shared machine inflates it far less than wall time), wall time, steps, file size, and
the errors of pipelines/flow_error.py against the reference run (the finest one
affordable). Times are comparable within one CSV only.
"""
import argparse
import csv
import os
import re
import subprocess

import xarray as xr

from pipelines import flow_error
from pipelines.cached_run import run_once

NEST_X = -1.2  # the interface: on the flume's slope, about 15 cm deep at rest


def tag(cfg):
    res, scheme, nest = cfg
    return f"{scheme}-{round(float(res) * 100):d}cm-nest{nest}"


def run(args, cfg):
    res, scheme, nest = cfg
    scene = os.path.join(args.runs, f"real-{res}.nc")
    if not os.path.exists(scene):
        subprocess.run([args.flotsam, "scene", "import", "--dem", args.dem, "--resolution", res, "--out", scene], check=True)
    flow = os.path.join(args.runs, tag(cfg) + ".nc")
    cmd = [args.flotsam, "hydro", "--scene", scene, "--west", "pump", "--duration", str(args.duration),
           "--output-interval", "5", "--threads", str(args.threads), "--label", tag(cfg), "--out", flow]
    if scheme != "fv":
        cmd += ["--scheme", scheme]
    if int(nest) > 1:
        cmd += ["--nest-ratio", nest, "--nest-x", str(NEST_X)]

    def parse(stderr, cpu):
        m = re.search(r"after (\d+) steps in ([0-9.]+) s wall", stderr)
        return [m.group(1), m.group(2), f"{cpu:.1f}"] if m else None

    steps, wall, cpu = run_once("accuracy_hydro", flow, flow + ".timing", cmd, parse, announce=True)
    return scene, flow, int(steps), float(wall), float(cpu)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dem", required=True)
    ap.add_argument("--runs", required=True)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--duration", type=float, default=420.0)
    ap.add_argument("--configs", default="0.08:fv:1,0.08:fv:2,0.04:fv:1,0.04:fv:2,0.04:fv:4,0.02:fv:2,0.02:fv:4,"
                                         "0.08:leapfrog:1,0.04:leapfrog:1,0.02:leapfrog:1")
    ap.add_argument("--reference", default="0.02:fv:1")
    ap.add_argument("--flotsam", default="build/flotsam")
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()
    os.makedirs(a.runs, exist_ok=True)
    ref_cfg = tuple(a.reference.split(":"))
    ref_scene, ref_flow, _, _, _ = run(a, ref_cfg)
    scene = xr.open_dataset(ref_scene)
    ref = xr.open_dataset(ref_flow, decode_timedelta=False)
    rows = []
    for c in [ref_cfg] + [tuple(s.split(":")) for s in a.configs.split(",") if s]:
        _, flow, steps, wall, cpu = run(a, c)
        err = flow_error.errors(scene, ref_flow, ref, flow)
        rows.append({"config": tag(c), "resolution_m": c[0], "scheme": c[1], "nest_ratio": c[2], "cpu_s": f"{cpu:.1f}", "wall_s": f"{wall:.1f}", "threads": a.threads,
                     "steps": steps, "file_bytes": os.path.getsize(flow), **{k: f"{v:.4g}" for k, v in err.items()}})
    with open(a.csv + ".part", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    os.replace(a.csv + ".part", a.csv)
    print(f"accuracy_hydro: wrote {a.csv} ({len(rows)} runs)")


if __name__ == "__main__":
    main()
