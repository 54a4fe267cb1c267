#!/usr/bin/python3
"""Debris speed against accuracy on one stored flow of the real layout.

    accuracy_debris.py --scene S.nc --flow F.nc --runs DIR --csv-frames A.csv --csv-steps B.csv
                       [--flotsam build/flotsam] [--jobs 2] [--launch PREFIX]

F is a flow stored every 0.1 s. The coarser stored intervals (0.2, 0.5, 1, 2, 5 s) are
made from it by keeping every k-th frame (pipelines/subsample_flow.py), so every
interval sees the same flow. Bodies: nine starts on a 3 cm grid centred on each of the
scene's FD and LD, so that one start that happens to sit on a fork in the flow does not
decide a chart.

Frames chart (A.csv): stored interval × time interpolant (linear, cubic) × model
(CC+SC, LC+MC), errors against the 0.1 s linear run of the same model.
Steps chart (B.csv): debris step (dt_max at vertex_step_fraction 0.25, and the fraction
at dt_max 0.01 s) × integrator (euler, heun) on the 1 s flow, errors against the finest
step (heun, dt_max 1.25 ms, fraction 1/16).

Error of a body: its distance from the reference body, sampled every 0.5 s: 10, 30 and
60 s after the reference body's release ("after_10s" ...), averaged over 0–420 s
("mean"), over the leading wave 0–300 s ("mean_300"), and at 420 s ("final"); each row
gives the median over the nine bodies of a start. The trajectories fork at obstacles, so
a long-horizon distance soon measures which side of a building a body went rather than
how accurate a step was; the "floor" rows (the reference run with every start moved
1 mm east) give the spread that any change at all produces. CPU: `flotsam debris
--threads 1`'s own count (its "debris cost" line), stepping only, per body-run. A run
whose trajectory file exists is not repeated (delete DIR's files to redo). --launch
puts a launcher in front of every debris run (srun …, docs/cluster.md); --jobs runs that
many at once.
"""
import argparse
import concurrent.futures
import csv
import os
import re
import shlex
import subprocess
import sys

import numpy as np
import xarray as xr

from pipelines.cached_run import run_once

# The repository root: subsample_flow runs as a module of the pipelines package.
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

STARTS = ["FD", "LD"]
OFFSETS = [(dx, dy) for dy in (-0.03, 0.0, 0.03) for dx in (-0.03, 0.0, 0.03)]  # [m]
HORIZONS = [10, 30, 60]  # [s] after the reference body's release
MODELS = {"CC+SC": ("center", "single"), "LC+MC": ("local", "multi")}
FRAME_STEPS = [1, 2, 5, 10, 20, 50]  # frames kept: every k-th of the 0.1 s flow
BASE_INTERVAL = 0.1                  # [s]
STEP_FLOW = 10                       # the steps chart runs on the 1 s flow
STEP_CONFIGS = ([("dt_max", dt, 0.25) for dt in (0.04, 0.02, 0.01, 0.005, 0.0025)] +
                [("fraction", 0.01, f) for f in (1.0, 0.5, 0.125, 0.0625)])  # (0.01, 0.25) is in the first series
STEP_REFERENCE = ("reference", 0.00125, 0.0625)


def scene_starts(scene_path):
    s = xr.open_dataset(scene_path)
    names = [str(n) for n in s.point_name.values]
    out = {}
    for name in STARTS:
        if name not in names:
            sys.exit(f"accuracy_debris: {scene_path}: no start point '{name}'")
        i = names.index(name)
        out[name] = (float(s.point_x[i]), float(s.point_y[i]), float(s.point_heading[i]))
    return out


def body_args(starts, shift=0.0):
    """--at arguments of the ensemble; body k belongs to STARTS[k // len(OFFSETS)]."""
    args = []
    for name in STARTS:
        x, y, heading = starts[name]
        for dx, dy in OFFSETS:
            args += ["--at", f"{x + dx + shift:.6f},{y + dy:.6f},{heading:g}"]
    return args


def flow_path(runs, k):
    return os.path.join(runs, f"flow-{k * BASE_INTERVAL:g}s.nc")


def run_debris(a, out, flow, bodies, extra):
    """Runs flotsam debris unless `out` exists; returns its step count and CPU seconds."""
    cmd = [a.flotsam, "debris", "--flow", flow, "--scene", a.scene, "--threads", "1", "--output-interval", "0.5",
           "--out", out] + bodies + extra

    def parse(stderr, _cpu):
        m = re.search(r"debris cost: (\d+) bodies, (\d+) steps, ([0-9.]+) s CPU stepping, ([0-9.]+) s CPU reading",
                      stderr)
        return list(m.groups()) if m else None

    n, steps, cpu, reading = run_once("accuracy_debris", out, out + ".cost", cmd, parse, launch=shlex.split(a.launch))
    return {"bodies": int(n), "steps": int(steps), "stepping_cpu_s": float(cpu), "reading_cpu_s": float(reading)}


def errors(path, ref_path):
    """Per start, medians over its bodies of the distance from the reference body [m]:
    HORIZONS seconds after the reference body's release, averaged over the run, over
    0-300 s, and at the end."""
    d, r = xr.open_dataset(path, decode_times=False), xr.open_dataset(ref_path, decode_times=False)
    dist = np.hypot(d.x.values - r.x.values, d.y.values - r.y.values)  # (trajectory, time)
    t = d.time.values - d.time.values[0]
    released = (r.status.values & 1) > 0
    lead = t <= 300.0 + 1e-9
    out = {}
    for s, name in enumerate(STARTS):
        rows = range(s * len(OFFSETS), (s + 1) * len(OFFSETS))
        e = {}
        for h in HORIZONS:
            at = []
            for b in rows:
                t_release = t[np.argmax(released[b])] if released[b].any() else t[-1]
                at.append(dist[b, min(np.searchsorted(t, t_release + h - 1e-9), len(t) - 1)])
            e[f"after_{h}s_m"] = float(np.median(at))
        e["mean_m"] = float(np.median(dist[rows].mean(axis=1)))
        e["mean_300_m"] = float(np.median(dist[rows][:, lead].mean(axis=1)))
        e["final_m"] = float(np.median(dist[rows, -1]))
        out[name] = e
    return out


def write_csv(path, rows):
    with open(path + ".part", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".part", path)
    print(f"accuracy_debris: wrote {path} ({len(rows)} rows)")


def fmt(v):
    return f"{v:.4g}" if isinstance(v, float) else v


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--flow", required=True, help="the flow stored every 0.1 s")
    ap.add_argument("--runs", required=True)
    ap.add_argument("--csv-frames", required=True)
    ap.add_argument("--csv-steps", required=True)
    ap.add_argument("--flotsam", default="build/flotsam")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--launch", default="", help="launcher prefix for every debris run (docs/cluster.md)")
    a = ap.parse_args()
    os.makedirs(a.runs, exist_ok=True)
    starts = scene_starts(a.scene)
    bodies, shifted = body_args(starts), body_args(starts, shift=0.001)
    per_body = len(OFFSETS) * len(STARTS)

    flows = {1: a.flow}
    for k in FRAME_STEPS[1:]:
        flows[k] = flow_path(a.runs, k)
        if not os.path.exists(flows[k]):
            subprocess.run([sys.executable, "-m", "pipelines.subsample_flow", a.flow, str(k), flows[k]], check=True,
                           env={**os.environ, "PYTHONPATH": ROOT})

    # ---- every run, in parallel (each single-threaded) ----
    jobs = {}
    for model, (contact, collision) in MODELS.items():
        tag = model.replace("+", "")
        for interp in ("linear", "cubic"):
            for k in FRAME_STEPS:
                jobs[("frames", model, interp, k)] = (os.path.join(a.runs, f"frames-{tag}-{interp}-{k}.nc"), flows[k], bodies,
                                                      ["--contact", contact, "--collision", collision, "--time-interpolation", interp])
        jobs[("frames", model, "floor", 1)] = (os.path.join(a.runs, f"frames-{tag}-floor.nc"), flows[1], shifted,
                                               ["--contact", contact, "--collision", collision])
        for series, dt, frac in STEP_CONFIGS + [STEP_REFERENCE]:
            for integ in ("euler", "heun"):
                if series == "reference" and integ == "euler":
                    continue
                jobs[("steps", model, series, dt, frac, integ)] = (
                    os.path.join(a.runs, f"steps-{tag}-{integ}-{dt:g}-{frac:g}.nc"), flows[STEP_FLOW], bodies,
                    ["--contact", contact, "--collision", collision, "--integrator", integ, "--dt-max", f"{dt:g}",
                     "--vertex-step-fraction", f"{frac:g}"])
        jobs[("steps", model, "floor", *STEP_REFERENCE[1:], "heun")] = (
            os.path.join(a.runs, f"steps-{tag}-floor.nc"), flows[STEP_FLOW], shifted,
            ["--contact", contact, "--collision", collision, "--integrator", "heun", "--dt-max", f"{STEP_REFERENCE[1]:g}",
             "--vertex-step-fraction", f"{STEP_REFERENCE[2]:g}"])
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        futures = {key: pool.submit(run_debris, a, *job) for key, job in jobs.items()}
        cost = {key: f.result() for key, f in futures.items()}

    # ---- frames chart ----
    rows = []
    for key, (out, flow, _, _) in jobs.items():
        if key[0] != "frames":
            continue
        _, model, interp, k = key
        ref = jobs[("frames", model, "linear", 1)][0]
        c = cost[key]
        for name, e in errors(out, ref).items():
            rows.append({"model": model, "interpolant": interp, "frame_interval_s": f"{k * BASE_INTERVAL:g}", "start": name,
                         "file_bytes": os.path.getsize(flow), **{n: fmt(v) for n, v in e.items()},
                         "stepping_cpu_per_body_run_s": fmt(c["stepping_cpu_s"] / per_body),
                         "reading_cpu_s": fmt(c["reading_cpu_s"])})
    write_csv(a.csv_frames, rows)

    # ---- steps chart ----
    rows = []
    for key, (out, _, _, _) in jobs.items():
        if key[0] != "steps":
            continue
        _, model, series, dt, frac, integ = key
        ref = jobs[("steps", model, *STEP_REFERENCE, "heun")][0]
        c = cost[key]
        for name, e in errors(out, ref).items():
            rows.append({"model": model, "series": series, "integrator": integ, "dt_max_s": f"{dt:g}", "vertex_step_fraction": f"{frac:g}",
                         "start": name, **{n: fmt(v) for n, v in e.items()}, "steps_per_body_run": c["steps"] // per_body,
                         "stepping_cpu_per_body_run_s": fmt(c["stepping_cpu_s"] / per_body)})
    write_csv(a.csv_steps, rows)


if __name__ == "__main__":
    main()
