"""The paper's statistics of several sweeps side by side (issue 17.4): region counts at
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
    args = ap.parse_args()
    runs = []
    for spec in args.runs:
        if "=" not in spec:
            ap.error(f"'{spec}': expected LABEL=DIR")
        label, folder = spec.split("=", 1)
        for name in ("regions.csv", "sections.csv"):
            if not os.path.isfile(os.path.join(folder, name)):
                ap.error(f"{folder}: no {name} (write it with flotsam stats --csv {folder})")
        runs.append((label, read(folder, "regions.csv"), read(folder, "sections.csv"), members(folder)))
    labels = [r[0] for r in runs]
    wanted = args.regions.split(",")
    boot = Bootstrap(args.bootstrap) if args.bootstrap > 0 and all(r[3] is not None for r in runs) else None
    ref_members = runs[0][3]
    if boot:
        print(f"In brackets: the 90 % interval of the difference from {labels[0]} over the records resampled "
              f"({args.bootstrap} paired resamples).")
        print()

    print("| body, model | region | " + " | ".join(labels) + " |")
    print("| --- | --- |" + " --- |" * len(labels))
    keys = [(r["body"], r["variant"], r["region"]) for r in runs[0][1] if r["region"] in wanted]
    for body, variant, region in keys:
        cells = []
        for k, (_, regions, _, mem) in enumerate(runs):
            row = next((r for r in regions if (r["body"], r["variant"], r["region"]) == (body, variant, region)), None)
            cell = f"{row['count']}/{row['members']}" if row else "–"
            if boot and k > 0 and row:
                cell += bracket(boot.count_difference(ref_members, mem, (body, variant), lambda m: m["region_at_arrival"] == region))
            cells.append(cell)
        print(f"| {body} {variant} | {region} | " + " | ".join(cells) + " |")

    print()
    print("| body, model | section | " + " | ".join(f"{l}: crossed, y median, speed median" for l in labels) + " |")
    print("| --- | --- |" + " --- |" * len(labels))
    keys = [(r["body"], r["variant"], r["section"]) for r in runs[0][2] if r["section"].startswith(r["body"].lower())]
    for body, variant, section in keys:
        cells = []
        for k, (_, _, sections, mem) in enumerate(runs):
            row = next((r for r in sections if (r["body"], r["variant"], r["section"]) == (body, variant, section)), None)
            if not row or int(row["count"]) == 0:
                cells.append("0")
                continue
            y, speed = f"{float(row['y_median_m']):+.2f} m", f"{float(row['speed_median_m_s']) * 100:.1f} cm/s"
            if boot and k > 0:
                y += bracket(boot.median_difference(ref_members, mem, (body, variant), section + "_y_m", section), 1.0, 2)
                speed += bracket(boot.median_difference(ref_members, mem, (body, variant), section + "_speed_m_s", section),
                                 100.0, 1)
            cells.append(f"{row['count']}, {y}, {speed}")
        print(f"| {body} {variant} | {section} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
