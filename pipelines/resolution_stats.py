"""The paper's statistics of several sweeps side by side: region counts at
the arrival time (Channel A and B) and the passage at each cross-section (how many cross,
median position, median speed), per body and model, over all parameter sets, as
`flotsam stats --csv DIR` writes them.

    python3 -m pipelines.resolution_stats 1cm=ST_1CM 2cm=ST_2CM 4cm=ST_4CM [--regions channel_a,channel_b]
        [--bootstrap N]

Each argument is LABEL=DIR, DIR holding regions.csv and sections.csv. Prints one markdown
table of region counts and one of section passages, the columns in the order given.

Is a difference from the first column (the reference) more than the choice of boundary
records makes? The records are the ensemble's independent draws (a record's parameter
sets share its flow), so where every folder has members.csv, each later column also
gives, in brackets, the 90 % interval of its difference from the reference over the
records resampled with replacement (N resamples, paired: the same records drawn for both,
a fixed seed, so the same output every time). An interval that excludes 0 is a
difference the records' own spread does not explain.

That interval does not hold the tracks' chaos: the same records with the flow barely
changed can move a count or a median beyond it (docs/studies/resolution_by_debris.md, "How much of that is
chaos?"). --floor LABEL=DIR (repeatable) names stats of such perturbed copies of the
reference (`python3 -m pipelines.subsample_flow IN.nc 1 OUT.nc --keep-bits N` on its
flows, then the same sweep and stats). A "chaos floor" column then gives, per statistic,
the largest difference from the reference that any of them shows, and a later column's
value is bold where its difference is beyond that floor and its interval excludes 0:
beyond both the records and the chaos.
"""
import argparse
import csv
import os

import numpy as np


def read(folder, name):
    with open(os.path.join(folder, name), newline="") as f:
        return [r for r in csv.DictReader(f) if r["param_label"] == "all"]


def members(folder):
    """{(body, variant): {flow: [member rows]}} from members.csv, or None without it."""
    path = os.path.join(folder, "members.csv")
    if not os.path.isfile(path):
        return None
    out = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            out.setdefault((r["body"], r["variant"]), {}).setdefault(int(r["flow"]), []).append(r)
    return out


class Bootstrap:
    """Paired resamples of the records shared by the reference and a test."""

    def __init__(self, count, seed=1):
        self.count, self.seed = count, seed

    def draws(self, records):
        rng = np.random.default_rng(self.seed)
        return rng.integers(0, len(records), size=(self.count, len(records)))

    def interval(self, values):
        lo, hi = np.quantile(np.asarray(values, dtype=float), [0.05, 0.95], method="inverted_cdf")
        return lo, hi

    def count_difference(self, ref, test, key, predicate):
        """Interval of (test − ref) members satisfying predicate, records resampled."""
        r_by, t_by = ref.get(key, {}), test.get(key, {})
        records = sorted(set(r_by) & set(t_by))
        if not records:
            return None
        diff = np.array([sum(predicate(m) for m in t_by[f]) - sum(predicate(m) for m in r_by[f]) for f in records])
        return self.interval(diff[self.draws(records)].sum(axis=1))

    def median_difference(self, ref, test, key, column, section):
        """Interval of (test − ref) median of `column` over the members that cross `section`."""
        r_by, t_by = ref.get(key, {}), test.get(key, {})
        records = sorted(set(r_by) & set(t_by))

        def values(by, f):
            return [float(m[column]) for m in by[f] if m.get(section + "_time_s", "") not in ("", "nan")]

        r_vals, t_vals = [values(r_by, f) for f in records], [values(t_by, f) for f in records]
        out = []
        for draw in self.draws(records) if records else []:
            a = [v for k in draw for v in r_vals[k]]
            b = [v for k in draw for v in t_vals[k]]
            if a and b:
                out.append(np.median(b) - np.median(a))
        return self.interval(out) if out else None


def beyond(diff, floor, interval):
    """A difference beyond the chaos floor whose interval over the records excludes 0."""
    return floor is not None and interval is not None and abs(diff) > floor + 1e-12 and (interval[0] > 0 or interval[1] < 0)


def value(row, column):
    return float(row[column])


def bold_if(text, flag):
    return f"**{text}**" if flag else text


def bracket(interval, scale=1.0, digits=0):
    if interval is None:
        return ""
    lo, hi = interval
    return f" [{lo * scale:+.{digits}f}, {hi * scale:+.{digits}f}]"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="LABEL=DIR of a stats --csv folder")
    ap.add_argument("--regions", default="channel_a,channel_b", help="regions to count (comma-separated)")
    ap.add_argument("--bootstrap", type=int, default=2000, help="resamples of the records (0: no intervals)")
    ap.add_argument("--floor", action="append", default=[],
                    help="LABEL=DIR of stats of a perturbed copy of the reference (repeatable): the chaos floor")
    args = ap.parse_args()

    def load(spec):
        if "=" not in spec:
            ap.error(f"'{spec}': expected LABEL=DIR")
        label, folder = spec.split("=", 1)
        for name in ("regions.csv", "sections.csv"):
            if not os.path.isfile(os.path.join(folder, name)):
                ap.error(f"{folder}: no {name} (write it with flotsam stats --csv {folder})")
        return (label, read(folder, "regions.csv"), read(folder, "sections.csv"), members(folder))

    runs = [load(spec) for spec in args.runs]
    floors = [load(spec) for spec in args.floor]
    labels = [r[0] for r in runs]
    wanted = args.regions.split(",")
    boot = Bootstrap(args.bootstrap) if args.bootstrap > 0 and all(r[3] is not None for r in runs) else None
    ref_members = runs[0][3]
    if boot:
        print(f"In brackets: the 90 % interval of the difference from {labels[0]} over the records resampled "
              f"({args.bootstrap} paired resamples).")
    if floors:
        print(f"Chaos floor: the largest difference from {labels[0]} of its perturbed copies "
              f"({', '.join(f[0] for f in floors)}); bold: beyond the floor, with an interval that excludes 0.")
    if boot or floors:
        print()
    floor_head = " | chaos floor" if floors else ""

    def region_row(regions, key):
        return next((r for r in regions if (r["body"], r["variant"], r["region"]) == key), None)

    def section_row(sections, key):
        row = next((r for r in sections if (r["body"], r["variant"], r["section"]) == key), None)
        return row if row and int(row["count"]) > 0 else None

    def largest(diffs):
        return max(diffs) if diffs else None

    print("| body, model | region | " + " | ".join(labels) + floor_head + " |")
    print("| --- | --- |" + " --- |" * (len(labels) + bool(floors)))
    keys = [(r["body"], r["variant"], r["region"]) for r in runs[0][1] if r["region"] in wanted]
    for key in keys:
        body, variant, region = key
        ref = region_row(runs[0][1], key)
        floor = largest([abs(int(f_row["count"]) - int(ref["count"])) for f in floors if (f_row := region_row(f[1], key))])
        cells = []
        for k, (_, regions, _, mem) in enumerate(runs):
            row = region_row(regions, key)
            cell = f"{row['count']}/{row['members']}" if row else "–"
            if boot and k > 0 and row:
                interval = boot.count_difference(ref_members, mem, (body, variant), lambda m: m["region_at_arrival"] == region)
                cell = bold_if(cell + bracket(interval), beyond(int(row["count"]) - int(ref["count"]), floor, interval))
            cells.append(cell)
        if floors:
            cells.append("–" if floor is None else f"±{floor}")
        print(f"| {body} {variant} | {region} | " + " | ".join(cells) + " |")

    print()
    print("| body, model | section | " + " | ".join(f"{l}: crossed, y median, speed median" for l in labels) + floor_head +
          " |")
    print("| --- | --- |" + " --- |" * (len(labels) + bool(floors)))
    keys = [(r["body"], r["variant"], r["section"]) for r in runs[0][2] if r["section"].startswith(r["body"].lower())]
    for key in keys:
        body, variant, section = key
        ref = section_row(runs[0][2], key)
        floor_y = largest([abs(value(f_row, "y_median_m") - value(ref, "y_median_m")) for f in floors
                           if ref and (f_row := section_row(f[2], key))])
        floor_s = largest([abs(value(f_row, "speed_median_m_s") - value(ref, "speed_median_m_s")) for f in floors
                           if ref and (f_row := section_row(f[2], key))])
        cells = []
        for k, (_, _, sections, mem) in enumerate(runs):
            row = section_row(sections, key)
            if not row:
                cells.append("0")
                continue
            y, speed = f"{float(row['y_median_m']):+.2f} m", f"{float(row['speed_median_m_s']) * 100:.1f} cm/s"
            if boot and k > 0 and ref:
                iy = boot.median_difference(ref_members, mem, (body, variant), section + "_y_m", section)
                i_s = boot.median_difference(ref_members, mem, (body, variant), section + "_speed_m_s", section)
                y = bold_if(y + bracket(iy, 1.0, 2), beyond(value(row, "y_median_m") - value(ref, "y_median_m"), floor_y, iy))
                speed = bold_if(speed + bracket(i_s, 100.0, 1),
                                beyond(value(row, "speed_median_m_s") - value(ref, "speed_median_m_s"), floor_s, i_s))
            cells.append(f"{row['count']}, {y}, {speed}")
        if floors:
            cells.append("–" if floor_y is None else f"±{floor_y:.2f} m, ±{floor_s * 100:.1f} cm/s")
        print(f"| {body} {variant} | {section} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
