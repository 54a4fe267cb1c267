"""The paper's statistics of several sweeps side by side (issue 17.4): region counts at
the arrival time (Channel A and B) and the passage at each cross-section (how many cross,
median position, median speed), per body and model, over all parameter sets, as
`flotsam stats --csv DIR` writes them.

    python3 -m pipelines.resolution_stats 1cm=ST_1CM 2cm=ST_2CM 4cm=ST_4CM [--regions channel_a,channel_b]

Each argument is LABEL=DIR, DIR holding regions.csv and sections.csv. Prints one markdown
table of region counts and one of section passages, the columns in the order given.
"""
import argparse
import csv
import os


def read(folder, name):
    with open(os.path.join(folder, name), newline="") as f:
        return [r for r in csv.DictReader(f) if r["param_label"] == "all"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="LABEL=DIR of a stats --csv folder")
    ap.add_argument("--regions", default="channel_a,channel_b", help="regions to count (comma-separated)")
    args = ap.parse_args()
    runs = []
    for spec in args.runs:
        if "=" not in spec:
            ap.error(f"'{spec}': expected LABEL=DIR")
        label, folder = spec.split("=", 1)
        for name in ("regions.csv", "sections.csv"):
            if not os.path.isfile(os.path.join(folder, name)):
                ap.error(f"{folder}: no {name} (write it with flotsam stats --csv {folder})")
        runs.append((label, read(folder, "regions.csv"), read(folder, "sections.csv")))
    labels = [r[0] for r in runs]
    wanted = args.regions.split(",")

    print("| body, model | region | " + " | ".join(labels) + " |")
    print("| --- | --- |" + " --- |" * len(labels))
    keys = [(r["body"], r["variant"], r["region"]) for r in runs[0][1] if r["region"] in wanted]
    for body, variant, region in keys:
        cells = []
        for _, regions, _ in runs:
            row = next((r for r in regions if (r["body"], r["variant"], r["region"]) == (body, variant, region)), None)
            cells.append(f"{row['count']}/{row['members']}" if row else "–")
        print(f"| {body} {variant} | {region} | " + " | ".join(cells) + " |")

    print()
    print("| body, model | section | " + " | ".join(f"{l}: crossed, y median, speed median" for l in labels) + " |")
    print("| --- | --- |" + " --- |" * len(labels))
    keys = [(r["body"], r["variant"], r["section"]) for r in runs[0][2] if r["section"].startswith(r["body"].lower())]
    for body, variant, section in keys:
        cells = []
        for _, _, sections in runs:
            row = next((r for r in sections if (r["body"], r["variant"], r["section"]) == (body, variant, section)), None)
            if not row or int(row["count"]) == 0:
                cells.append("0")
                continue
            cells.append(f"{row['count']}, {float(row['y_median_m']):+.2f} m, {float(row['speed_median_m_s']) * 100:.1f} cm/s")
        print(f"| {body} {variant} | {section} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
