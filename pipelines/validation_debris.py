#!/usr/bin/python3
"""The debris numbers of docs/validation.md from a statistics CSV folder.

Usage: python3 -m pipelines.validation_debris runs/stats-real-0.04 [--set control]
           [--sweep runs/sweep-real-0.04.nc]

Reads the tables `flotsam stats --csv DIR` writes (members.csv, regions.csv,
sections.csv, distance.csv) and prints, per body and model variant, for one parameter
set (the control by default: the paper's ten debris runs, one per flow):
  - the largest rotation from the initial heading in the first 30 s of the run (the
    paper's Fig. 16a, b): count, median, range; the direction of movement at 30 s
    (Fig. 16c, degrees from east, north-east positive) and Pearson's r of the two;
  - when the body starts to move (5 mm from its start; median and range), and the
    same rotation, direction and r counted from motion start instead (labelled: a
    variant, not the paper's definition);
  - where the bodies are at 300 s (region counts, Figs. 7 and 9; with --sweep also the
    positions, linear between samples);
  - passage position and speed at each section (Figs. 14 and 15);
  - R(t) of each other parameter set against the control (Fig. 17): the mean and the
    largest |R| over the times where it is defined;
  - with --sweep, the steps whose collisions were left unresolved (an overlap deeper than
    the tolerance after the pass bound), in this set and in all sets.
"""
import argparse
import csv
import math
import os
import statistics
import sys


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    """A CSV value as a float; empty or fill values as NaN."""
    try:
        v = float(text)
    except (TypeError, ValueError):
        return math.nan
    return v if math.isfinite(v) and abs(v) < 1e30 else math.nan


def pearson(a, b):
    pairs = [(x, y) for x, y in zip(a, b) if not (math.isnan(x) or math.isnan(y))]
    if len(pairs) < 2:
        return math.nan
    xs, ys = zip(*pairs)
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    sxy = sum((x - mx) * (y - my) for x, y in pairs)
    sxx = sum((x - mx) ** 2 for x in xs)
    syy = sum((y - my) ** 2 for y in ys)
    return sxy / math.sqrt(sxx * syy) if sxx > 0 and syy > 0 else math.nan


def spread(values, unit, digits=1):
    v = sorted(x for x in values if not math.isnan(x))
    if not v:
        return "none"
    f = f"{{:+.{digits}f}}" if unit == "°" else f"{{:.{digits}f}}"
    return f"{f.format(statistics.median(v))}{unit} median ({f.format(v[0])} to {f.format(v[-1])}{unit}, n = {len(v)})"


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv_dir", help="the folder of `flotsam stats --csv`")
    ap.add_argument("--set", default="control", help="parameter set label (default: control)")
    ap.add_argument("--sweep", help="the sweep file, for the positions at --at seconds")
    ap.add_argument("--at", type=float, default=300.0, help="time of the positions, from the first sample [s]")
    ap.add_argument("--reach-x", type=float, default=3.6,
                    help="with --sweep: when a body first reaches this x (default 3.6 m, the basin's east shore on the "
                         "real layout; the paper's FD bodies reach it at about 80 s) [m]")
    args = ap.parse_args(argv)

    members = read(os.path.join(args.csv_dir, "members.csv"))
    regions = read(os.path.join(args.csv_dir, "regions.csv"))
    sections = read(os.path.join(args.csv_dir, "sections.csv"))
    distance = read(os.path.join(args.csv_dir, "distance.csv"))
    groups = list(dict.fromkeys((m["body"], m["variant"]) for m in members))
    positions = {}
    unresolved = {}  # member -> steps left unresolved
    if args.sweep:
        import numpy as np
        import xarray as xr
        with xr.open_dataset(args.sweep, decode_times=False) as d:
            t = d["time"].values - d["time"].values[0]
            if "unresolved_collisions" in d:
                unresolved = {str(int(m)): int(n) for m, n in zip(d["member_id"].values, d["unresolved_collisions"].values)}
            for k, member in enumerate(d["member_id"].values):
                x = d["x"].values[k]
                reached = np.nonzero(x >= args.reach_x)[0]
                positions[str(int(member))] = (float(np.interp(args.at, t, x)), float(np.interp(args.at, t, d["y"].values[k])),
                                               float(t[reached[0]]) if reached.size else math.nan)

    for body, variant in groups:
        rows = [m for m in members if (m["body"], m["variant"]) == (body, variant) and m["param_label"] == args.set]
        if not rows:
            continue
        rot = [number(m["max_rotation_from_start_deg"]) for m in rows]
        direction = [number(m["movement_direction_deg"]) for m in rows]
        start = [number(m["motion_start_s"]) for m in rows]
        print(f"== {body} {variant} ({args.set}, {len(rows)} runs)")
        print(f"  largest rotation, first 30 s of the run: {spread(rot, '°')}")
        print(f"  direction of movement at 30 s (from east, NE +): {spread(direction, '°')}")
        print(f"  correlation rotation/direction: r = {pearson(rot, direction):.2f}")
        print(f"  motion start (5 mm): {spread(start, ' s')}")
        after = [number(m["max_rotation_deg"]) for m in rows]
        after_direction = [number(m["motion_direction_deg"]) for m in rows]
        print(f"  variant, counted from motion start: largest rotation in 30 s {spread(after, '°')}; direction "
              f"{spread(after_direction, '°')}; r = {pearson(after, after_direction):.2f}")
        print("  per flow (rotation, direction, motion start, region at 300 s, position at --at):")
        for m in rows:
            where = positions.get(m["member"])
            print(f"    r{int(m['flow']):02d}: {number(m['max_rotation_from_start_deg']):+7.1f}°  "
                  f"{number(m['movement_direction_deg']):+7.1f}°  {number(m['motion_start_s']):6.1f} s  "
                  f"{m['region_at_arrival'] or '-':12s}" +
                  (f"  ({where[0]:.2f}, {where[1]:.2f}) m, x >= {args.reach_x:g} m at {where[2]:.0f} s" if where else ""))
        if positions:
            print(f"  first time at x >= {args.reach_x:g} m: {spread([positions[m['member']][2] for m in rows], ' s', 0)}")
        if unresolved:
            def tally(members_):
                n = [unresolved.get(m["member"], 0) for m in members_]
                return f"{sum(1 for k in n if k)} of {len(n)} runs, {sum(n)} steps (most {max(n) if n else 0})"
            every = [m for m in members if (m["body"], m["variant"]) == (body, variant)]
            print(f"  unresolved collision steps: {tally(rows)}; all sets: {tally(every)}")
        counts = [r for r in regions if (r["body"], r["variant"], r["param_label"]) == (body, variant, args.set)]
        print("  at 300 s: " + ", ".join(f"{r['region']} {r['count']}/{r['members']}" for r in counts))
        for s in sections:
            if (s["body"], s["variant"], s["param_label"]) != (body, variant, args.set) or s["count"] == "0":
                continue
            print(f"  section {s['section']}: n = {s['count']}, y mean {number(s['y_mean_m']):.3f} m, median "
                  f"{number(s['y_median_m']):.3f} m, std {number(s['y_std_m']):.3f} m; speed mean "
                  f"{number(s['speed_mean_m_s']):.3f} m/s, median {number(s['speed_median_m_s']):.3f}, std "
                  f"{number(s['speed_std_m_s']):.3f}")
        labels = list(dict.fromkeys(d["param_label"] for d in distance
                                    if (d["body"], d["variant"]) == (body, variant) and d["param_label"] != args.set))
        for label in labels:
            r = [number(d["relative_error"]) for d in distance
                 if (d["body"], d["variant"], d["param_label"]) == (body, variant, label)]
            r = [abs(x) for x in r if not math.isnan(x)]
            if r:
                print(f"  R(t) {label}: mean |R| {statistics.fmean(r):.2f}, largest {max(r):.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
