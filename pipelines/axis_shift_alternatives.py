#!/usr/bin/python3
"""FD's early turn under the alternatives of the axis shift and the blocking ground.

Usage: python3 -m pipelines.axis_shift_alternatives --scene runs/real-0.04.nc
           --flows 'runs/flows-real-0.04/flow_r*.nc' [--ground runs/real-0.01.nc]
           [--cases carried:land:0.02 restarted:land:0.02 ...] [--out-dir runs/axis-shift]

For each case PIVOT:GROUND:DT (the body settings `pivot-rate` and `blocking-ground`, and
the sweep's `dt-max`), sweeps FD with CC+SC and LC+MC, the control set, over the flows
(`flotsam sweep`, then `flotsam stats`), and prints one Markdown table row per case for
LC+MC: the largest rotation from the initial heading in the first 30 s of the run (the
paper's Fig. 16a; median and range over the flows), the direction of movement at 30 s
(from east, north-east positive), the motion start (5 mm), and the steps whose collisions
were left unresolved; and one row for CC+SC under the first case. The default cases are
those of docs/debris.md, "Axis shift" and "Ground and obstacles".
"""
import argparse
import csv
import glob
import math
import os
import statistics
import subprocess
import sys

from pipelines.validation_debris import number

DEFAULT_CASES = ["carried:land:0.02", "carried:land:0.01", "restarted:land:0.02", "restarted:land:0.01",
                 "braked:land:0.02", "carried:any:0.02", "carried:none:0.02"]


def spec_text(scene, pivot, ground, dt):
    return f"""[sweep]
scene = "{scene}"
output-interval = 1.0
end-time = 420
dt-max = {dt}
pivot-rate = "{pivot}"
blocking-ground = "{ground}"
[[body]]
start = "FD"
[variants]
names = ["CC+SC", "LC+MC"]
"""


def spread(values, fmt, unit):
    v = sorted(x for x in values if not math.isnan(x))
    if not v:
        return "none"
    return f"{fmt.format(statistics.median(v))}{unit} ({fmt.format(v[0])} to {fmt.format(v[-1])}{unit}, n = {len(v)})"


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--flows", required=True, help="glob of the flow files")
    ap.add_argument("--ground", default="", help="a finer scene for the bodies' ground (optional)")
    ap.add_argument("--cases", nargs="*", default=DEFAULT_CASES, help="PIVOT:GROUND:DT")
    ap.add_argument("--flotsam", default="build/flotsam")
    ap.add_argument("--threads", default="1")
    ap.add_argument("--out-dir", default="runs/axis-shift")
    args = ap.parse_args(argv)
    flows = sorted(glob.glob(args.flows))
    if not flows:
        sys.exit(f"axis_shift_alternatives: no flow matches {args.flows}")
    os.makedirs(args.out_dir, exist_ok=True)
    env = dict(os.environ, OMP_WAIT_POLICY=os.environ.get("OMP_WAIT_POLICY", "passive"))
    rows = []
    for k, case in enumerate(args.cases):
        pivot, ground, dt = case.split(":")
        tag = f"{pivot}-{ground}-dt{dt}" + ("-on-" + os.path.splitext(os.path.basename(args.ground))[0] if args.ground else "")
        spec = os.path.join(args.out_dir, tag + ".toml")
        sweep = os.path.join(args.out_dir, tag + ".nc")
        stats = os.path.join(args.out_dir, tag + "-stats")
        with open(spec, "w") as f:
            f.write(spec_text(args.scene, pivot, ground, dt))
        cmd = [args.flotsam, "sweep", "--spec", spec, "--threads", args.threads, "--quiet", "--out", sweep]
        cmd += ["--ground", args.ground] if args.ground else []
        for fl in flows:
            cmd += ["--flow", fl]
        subprocess.run(cmd, check=True, env=env)
        subprocess.run([args.flotsam, "stats", "--sweep", sweep, "--scene", args.scene, "--out", stats + ".nc", "--csv", stats],
                       check=True, env=env, stdout=subprocess.DEVNULL)
        with open(os.path.join(stats, "members.csv"), newline="") as f:
            members = [m for m in csv.DictReader(f) if m["param_label"] == "control"]
        unresolved = {}
        with open(os.path.splitext(sweep)[0] + ".csv", newline="") as f:
            for m in csv.DictReader(f):
                unresolved[m["member"]] = int(m["unresolved_collisions"])
        for variant in (["CC+SC", "LC+MC"] if k == 0 else ["LC+MC"]):
            rs = [m for m in members if m["variant"] == variant]
            rot = [number(m["max_rotation_from_start_deg"]) for m in rs]
            direction = [number(m["movement_direction_deg"]) for m in rs]
            start = [number(m["motion_start_s"]) for m in rs]
            left = sum(unresolved.get(m["member"], 0) for m in rs)
            label = variant if variant == "CC+SC" else f"{pivot} | {ground} | {dt}"
            rows.append(f"| {label} | {spread(rot, '{:+.1f}', '°')} | {spread(direction, '{:+.1f}', '°')} | "
                        f"{spread(start, '{:.0f}', ' s')} | {left} |")
        print(rows[-1], flush=True)
    print()
    print("| pivot rate | blocking ground | dt-max [s] | FD rotation, 0–30 s | direction at 30 s | motion start | unresolved steps |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        print(r if not r.startswith("| CC+SC") else r.replace("| CC+SC |", "| CC+SC (reference) | | |", 1))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
