"""Resolution judged by the debris answer: two sweeps of the same spec over
flows of the same records at two grid resolutions, compared by what a user reads off them.

    python3 -m pipelines.resolution_debris --ref runs/sweep-real-0.02.nc --test runs/sweep-real-0.04.nc

Each sweep's CSV (same name, .csv) gives body, variant and parameter set per member. For
each body and variant, the control set only (--set LABEL for another, --set all to pair
every set's members by record and set: with few records, more pairs), it prints:

  - pass probability: the fraction of trajectories whose centre passes each cell of a
    common grid (--cell, default 4 cm; paths densified to a tenth of a cell), and the L1
    difference between the two sweeps as a fraction of the reference's L1 norm. Beside it
    the same difference between the reference's even and odd records (half the flows
    each): the scatter that the choice of records alone makes;
  - the largest rotation from the initial heading in the first --window seconds (Fig. 16),
    median over the records, and the same counted from each member's motion start;
  - the motion start (the CSV's, 5 mm from the start), median;
  - the distance between the two sweeps' positions at --at seconds, member by member
    (same record), median and largest; beside it the median distance between the
    reference's members of different records at that time.
"""
import argparse
import csv
import itertools

import numpy as np
import xarray as xr


def load(path):
    with xr.open_dataset(path, decode_times=False) as d:
        t = d["time"].values
        x, y, yaw = d["x"].values, d["y"].values, d["yaw"].values
    rows = list(csv.DictReader(open(path[:-3] + ".csv")))
    return t, x, y, yaw, rows


def visits(x, y, cell, x0, y0, nx, ny):
    """Cells the densified path of one trajectory visits (a boolean grid)."""
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    grid = np.zeros((ny, nx), bool)
    if len(x) == 0:
        return grid
    seg = np.hypot(np.diff(x), np.diff(y))
    n = np.maximum(1, np.ceil(seg / (0.1 * cell)).astype(int))
    px = np.concatenate([np.linspace(a, b, k, endpoint=False) for a, b, k in zip(x[:-1], x[1:], n)] + [x[-1:]])
    py = np.concatenate([np.linspace(a, b, k, endpoint=False) for a, b, k in zip(y[:-1], y[1:], n)] + [y[-1:]])
    i = np.clip(((px - x0) / cell).astype(int), 0, nx - 1)
    j = np.clip(((py - y0) / cell).astype(int), 0, ny - 1)
    grid[j, i] = True
    return grid


def probability(tracks, cell, box):
    x0, y0, nx, ny = box
    if not tracks:
        return np.zeros((ny, nx))
    return np.mean([visits(x, y, cell, x0, y0, nx, ny) for x, y in tracks], axis=0)


def rel_l1(a, b):
    ref = np.abs(a).sum()
    return np.abs(a - b).sum() / ref if ref > 0 else float("nan")


def largest_rotation(t, yaw, window, start=None):
    """Largest turn from the heading at `start` (the run's start if None) within `window` s."""
    t0 = t[0] if start is None else start
    k = (t >= t0) & (t <= t0 + window)
    if not k.any():
        return float("nan")
    d = yaw[k] - yaw[k][0]
    return float(d[np.argmax(np.abs(d))]) if np.isfinite(d).all() else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ref", required=True, help="reference sweep (the finer grid)")
    ap.add_argument("--test", required=True, help="sweep to judge (the coarser grid)")
    ap.add_argument("--set", default="control",
                    help="parameter set label, or 'all' to pair the members of every set (record and set alike)")
    ap.add_argument("--cell", type=float, default=0.04, help="pass-probability cell [m]")
    ap.add_argument("--window", type=float, default=30.0, help="rotation window from the run start [s]")
    ap.add_argument("--at", type=float, default=300.0, help="time of the position comparison [s]")
    a = ap.parse_args()
    ref, test = load(a.ref), load(a.test)
    xs = np.concatenate([ref[1].ravel(), test[1].ravel()])
    ys = np.concatenate([ref[2].ravel(), test[2].ravel()])
    x0, y0 = np.nanmin(xs) - a.cell, np.nanmin(ys) - a.cell
    box = (x0, y0, int((np.nanmax(xs) - x0) / a.cell) + 2, int((np.nanmax(ys) - y0) / a.cell) + 2)
    groups = list(dict.fromkeys((r["body"], r["variant"]) for r in ref[4]))
    print("| body, variant | pass probability L1 (test vs ref) | same, ref's even vs odd records | rotation in "
          f"{a.window:g} s, ref / test | the same from motion start | motion start, ref / test | position at {a.at:g} s: ref-test distance median, "
          "largest | ref, between records, median |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for body, variant in groups:
        def members(s):
            # Keyed by (record, set); rows are indexed by their member number.
            t, x, y, yaw, rows = s
            sel = [int(r["member"]) for r in rows
                   if (r["body"], r["variant"]) == (body, variant) and a.set in ("all", r["param_label"])]
            return {(int(rows[m]["flow"]), rows[m]["param_label"]): m for m in sel}
        mr, mt = members(ref), members(test)
        flows = sorted(set(mr) & set(mt))  # (record, set) pairs in both
        pr = probability([(ref[1][mr[f]], ref[2][mr[f]]) for f in flows], a.cell, box)
        pt = probability([(test[1][mt[f]], test[2][mt[f]]) for f in flows], a.cell, box)
        even = probability([(ref[1][mr[f]], ref[2][mr[f]]) for f in flows if f[0] % 2 == 0], a.cell, box)
        odd = probability([(ref[1][mr[f]], ref[2][mr[f]]) for f in flows if f[0] % 2 == 1], a.cell, box)
        rot_r = np.median([largest_rotation(ref[0], ref[3][mr[f]], a.window) for f in flows])
        rot_t = np.median([largest_rotation(test[0], test[3][mt[f]], a.window) for f in flows])
        def after_start(s, m):
            return largest_rotation(s[0], s[3][m], a.window, float(s[4][m]["motion_start_s"]))
        rot_sr = np.nanmedian([after_start(ref, mr[f]) for f in flows])
        rot_st = np.nanmedian([after_start(test, mt[f]) for f in flows])
        start_r = np.median([float(ref[4][mr[f]]["motion_start_s"]) for f in flows])
        start_t = np.median([float(test[4][mt[f]]["motion_start_s"]) for f in flows])
        kr, kt = np.argmin(np.abs(ref[0] - a.at)), np.argmin(np.abs(test[0] - a.at))
        pos_r = {f: (ref[1][mr[f]][kr], ref[2][mr[f]][kr]) for f in flows}
        pos_t = {f: (test[1][mt[f]][kt], test[2][mt[f]][kt]) for f in flows}
        dist = [np.hypot(pos_r[f][0] - pos_t[f][0], pos_r[f][1] - pos_t[f][1]) for f in flows]
        spread = [np.hypot(pos_r[f][0] - pos_r[g][0], pos_r[f][1] - pos_r[g][1])
                  for f, g in itertools.combinations(flows, 2) if f[0] != g[0] and f[1] == g[1]]
        spread_txt = f"{np.median(spread):.2f} m" if spread else "–"
        n_records = len({f[0] for f in flows})
        label = f"{n_records} records" + (f", {len(flows)} members" if a.set == "all" else "")
        print(f"| {body} {variant} ({label}) | {rel_l1(pr, pt):.2f} | {rel_l1(even, odd):.2f} | "
              f"{rot_r:+.1f}° / {rot_t:+.1f}° | {rot_sr:+.1f}° / {rot_st:+.1f}° | {start_r:.1f} / {start_t:.1f} s | {np.median(dist):.2f}, {np.max(dist):.2f} m | "
              f"{spread_txt} |")


if __name__ == "__main__":
    main()
