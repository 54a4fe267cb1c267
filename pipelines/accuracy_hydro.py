#!/usr/bin/python3
"""Hydro cost against error on the real layout: grid × scheme × nesting.

    accuracy_hydro.py --dem DEM.nc --runs DIR --csv OUT.csv [--duration 420]
                      [--configs 0.08:fv:1,0.04:fv:1,...] [--reference 0.01:fv:4]
                      [--flotsam build/flotsam] [--threads 1]
                      [--launch [RES=]PREFIX ... --jobs N]

Each configuration is RES:SCHEME:NEST_RATIO (nest ratio 1 = one uniform grid). Every run
is the benchmark forcing (--west pump) for --duration seconds; a run whose flow and
timing file already exist is not repeated (delete them to redo). The CSV has one row per
run: its CPU time (user + system, on one thread by default, so that other work on a
shared machine inflates it far less than wall time), wall time, steps, file size, and
the errors of pipelines/flow_error.py against the reference run (the finest one
affordable). Times are comparable within one CSV only.

On a cluster (docs/cluster.md), --launch puts a launcher in front of every flow
("RES=srun ..." for the runs at RES, a plain prefix for the rest) and --jobs N runs N at
once; the CPU column is then flotsam's own count of its stepping time (the processor time
of the machine it ran on), since this process cannot see it.
"""
import argparse
import concurrent.futures
import csv
import os
import re
import shlex
import subprocess
import sys

import xarray as xr

from pipelines import flow_error
from pipelines.cached_run import run_once

NEST_X = -1.2  # the interface: on the flume's slope, about 15 cm deep at rest


def tag(cfg):
    res, scheme, nest = cfg
    return f"{scheme}-{round(float(res) * 100):d}cm-nest{nest}"


def scene_path(args, res):
    return os.path.join(args.runs, f"real-{res}.nc")


def import_scene(args, res):
    scene = scene_path(args, res)
    if not os.path.exists(scene):
        subprocess.run([args.flotsam, "scene", "import", "--dem", args.dem, "--resolution", res, "--out", scene], check=True)


def launcher(args, res):
    """The words put in front of a run at `res`: its --launch RES=PREFIX, else the plain --launch PREFIX."""
    plain, per_res = None, {}
    for entry in args.launch:
        key, sep, prefix = entry.partition("=")
        if sep and re.fullmatch(r"[0-9.]+", key):
            per_res[float(key)] = prefix
        else:
            plain = entry
    prefix = per_res.get(float(res), plain)
    if prefix is None and args.launch:
        sys.exit(f"accuracy_hydro: --launch: no launcher for the runs at {res} m (give --launch {res}=PREFIX)")
    return shlex.split(prefix) if prefix else []


def run(args, cfg):
    res, scheme, nest = cfg
    scene = scene_path(args, res)
    flow = os.path.join(args.runs, tag(cfg) + ".nc")
    cmd = [args.flotsam, "hydro", "--scene", scene, "--west", "pump", "--duration", str(args.duration),
           "--output-interval", "5", "--threads", str(args.threads), "--label", tag(cfg), "--out", flow]
    if scheme != "fv":
        cmd += ["--scheme", scheme]
    if int(nest) > 1:
        cmd += ["--nest-ratio", nest, "--nest-x", str(NEST_X)]
    elif scheme == "fv":
        cmd += ["--nest-ratio", "1"]  # one uniform grid: a Kainan scene recommends nesting, which hydro applies unasked

    def parse(stderr, cpu):
        m = re.search(r"after (\d+) steps in ([0-9.]+) s wall \(([0-9.]+) s processor\)", stderr)
        return [m.group(1), m.group(2), f"{cpu if cpu is not None else float(m.group(3)):.1f}"] if m else None

    steps, wall, cpu = run_once("accuracy_hydro", flow, flow + ".timing", cmd, parse, announce=True,
                                launch=launcher(args, res))
    return scene, flow, int(steps), float(wall), float(cpu)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dem", required=True)
    ap.add_argument("--runs", required=True)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--duration", type=float, default=420.0)
    ap.add_argument("--configs", default="0.02:fv:1,0.08:fv:1,0.08:fv:2,0.04:fv:1,0.04:fv:2,0.04:fv:4,0.02:fv:2,0.02:fv:4,"
                                         "0.08:leapfrog:1,0.04:leapfrog:1,0.02:leapfrog:1")
    # The paper's grid on the flows' nesting (a uniform 1 cm run would take about 4 processor hours).
    ap.add_argument("--reference", default="0.01:fv:4")
    ap.add_argument("--flotsam", default="build/flotsam")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--launch", action="append", default=[],
                    help="launcher prefix for the flows (RES=PREFIX: for those at RES); repeatable")
    ap.add_argument("--jobs", type=int, default=1, help="flows at once (more than one needs --launch)")
    a = ap.parse_args()
    if a.jobs > 1 and not a.launch:
        sys.exit("accuracy_hydro: --jobs above 1 needs --launch (here, parallel runs would spoil each other's CPU times)")
    os.makedirs(a.runs, exist_ok=True)
    ref_cfg = tuple(a.reference.split(":"))
    cfgs = list(dict.fromkeys([ref_cfg] + [tuple(s.split(":")) for s in a.configs.split(",") if s]))
    for res in dict.fromkeys(c[0] for c in cfgs):
        import_scene(a, res)
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        results = list(pool.map(lambda c: run(a, c), cfgs))
    ref_scene, ref_flow = results[0][0], results[0][1]
    scene = xr.open_dataset(ref_scene)
    ref = xr.open_dataset(ref_flow, decode_timedelta=False)
    rows = []
    for c, (_, flow, steps, wall, cpu) in zip(cfgs, results):
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
