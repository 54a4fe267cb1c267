#!/usr/bin/python3
"""Flows of the same records at several grids against the finest (the flows' table of
docs/studies/resolution_by_debris.md): the error at the points debris cares about (pipelines.flow_error: WG2, the depth
and the draft time at the FD and LD starts) against what a flow of each grid costs.

    python3 -m pipelines.resolution_cost SCENE "1 cm=DIR[:LOG]" "2 cm=DIR[:LOG]" ... [--csv OUT.csv] [--png OUT.png]

The first grid is the reference. DIR holds its flows (flow_rNN.nc); only records whose
reference flow is complete are compared. LOG, where given, is the output of the make
command that ran the flows: a flow's cost is the processor time of its run summaries
("hydro-rNN: complete after N steps (t = T0 to T1 s) in … (P s processor)"), summed over
the parts of a flow continued with --restart where their spans chain from t = 0 to the
end. A flow with a part that left no summary (killed outright) is left out, as is a
continued flow in a log from before the summaries gave spans. Prints a Markdown table
per grid: processor s a flow (median, and how many flows it is from), and per measure
the median over the records with its range (a draft time counts only the records where
the point floods in both flows; "–" where it floods in none).
"""
import argparse
import csv
import os
import re
import sys

import numpy as np
import xarray as xr

from pipelines.flow_error import errors

MEASURES = [("wg2_rms_m", "WG2 RMS", 1e3, "mm"), ("wg2_max_err_m", "WG2 max", 1e3, "mm"),
            ("FD_depth_rms_m", "FD depth RMS", 1e3, "mm"), ("FD_draft_err_s", "FD draft time", 1.0, "s"),
            ("LD_depth_rms_m", "LD depth RMS", 1e3, "mm"), ("LD_draft_err_s", "LD draft time", 1.0, "s")]


def parse_grid(text):
    if "=" not in text:
        sys.exit(f"resolution_cost.py: '{text}': give LABEL=DIR[:LOG]")
    label, rest = text.split("=", 1)
    directory, _, log = rest.partition(":")
    if not os.path.isdir(directory):
        sys.exit(f"resolution_cost.py: {directory}: no such directory (grid '{label}')")
    if log and not os.path.isfile(log):
        sys.exit(f"resolution_cost.py: {log}: no such file (grid '{label}')")
    return label, directory, log


def records(directory):
    """Record numbers of the complete flows (flow_rNN.nc; not .part) in directory."""
    out = []
    for name in sorted(os.listdir(directory)):
        m = re.fullmatch(r"flow_r(\d+)\.nc", name)
        if m:
            out.append(int(m.group(1)))
    return out


SUMMARY = re.compile(r"hydro-r(\d+): (.*?) after \d+ steps(?: \(t = (\S+) to (\S+) s\))? in [\d.]+ s wall "
                     r"\(([\d.]+) s processor\)")


def costs(log):
    """{record: processor s of the whole flow} from a make log (see the module's notes)."""
    if not log:
        return {}
    cost = {}
    chain = {}  # record: (simulated time its parts so far reached, as printed; their processor s), or None
    unreported = set()  # records whose last part started and has printed no summary yet
    restarted = set()  # records continued with --restart anywhere in the log (the older summaries)
    for line in open(log, errors="replace"):
        m = re.search(r"--label hydro-r(\d+)\b", line)
        if m:
            r = int(m.group(1))
            if r in unreported:
                chain[r] = None  # the part before this one was killed before it could report
            unreported.add(r)
            if "--restart" in line:
                restarted.add(r)
            continue
        m = SUMMARY.match(line)
        if not m:
            continue
        r, status, start, end, cpu = int(m.group(1)), m.group(2), m.group(3), m.group(4), float(m.group(5))
        unreported.discard(r)
        if start is None:  # a summary without its span: counted only for a flow never continued
            if status == "complete" and r not in restarted:
                cost[r] = cpu
            continue
        if float(start) == 0.0:
            chain[r] = (end, cpu)
        elif chain.get(r) is not None and chain[r][0] == start:
            chain[r] = (end, chain[r][1] + cpu)
        else:
            chain[r] = None
        if status == "complete" and chain[r] is not None:
            cost[r] = chain[r][1]
    return cost


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", help="the scene the flows ran on (its named points FD, LD)")
    ap.add_argument("grids", nargs="+", help="LABEL=DIR[:LOG], the reference first")
    ap.add_argument("--csv", help="write every record's errors here")
    ap.add_argument("--png", help="draw the chart here (error against processor s a flow)")
    a = ap.parse_args(argv[1:])
    grids = [parse_grid(g) for g in a.grids]
    if len(grids) < 2:
        sys.exit("resolution_cost.py: give the reference grid and at least one other")
    scene = xr.open_dataset(a.scene)
    ref_label, ref_dir, ref_log = grids[0]
    ref_records = records(ref_dir)
    if not ref_records:
        sys.exit(f"resolution_cost.py: {ref_dir}: no complete flow_rNN.nc")
    rows, summary = [], []
    ref_cost = costs(ref_log)
    summary.append((ref_label, ref_cost, {}, ref_records))
    for label, directory, log in grids[1:]:
        found = [r for r in ref_records if os.path.exists(os.path.join(directory, f"flow_r{r:02d}.nc"))]
        per_record = {}
        for r in found:
            ref_path = os.path.join(ref_dir, f"flow_r{r:02d}.nc")
            path = os.path.join(directory, f"flow_r{r:02d}.nc")
            with xr.open_dataset(ref_path, decode_timedelta=False) as ref:
                per_record[r] = errors(scene, ref_path, ref, path)
            rows.append({"grid": label, "record": r, **per_record[r]})
        summary.append((label, costs(log), per_record, found))

    print(f"| grid | processor s a flow | records | " + " | ".join(f"{m[1]} [{m[3]}]" for m in MEASURES) + " |")
    print("| --- | --- | --- | " + " | ".join("---" for _ in MEASURES) + " |")
    for label, cost, per_record, found in summary:
        c = f"{np.median(list(cost.values())):.0f} ({len(cost)} flows)" if cost else "–"
        cells = []
        for key, _, scale, _ in MEASURES:
            if not per_record:
                cells.append("reference")
                continue
            v = np.array([per_record[r][key] for r in found]) * scale
            finite = v[np.isfinite(v)]  # a draft time is NaN where the point never floods in a run
            if finite.size == 0:
                cells.append("–")
                continue
            sign = "+" if "err" in key else ""
            text = f"{np.median(finite):{sign}.2f} ({finite.min():{sign}.2f} … {finite.max():{sign}.2f})"
            cells.append(text + (f", {v.size - finite.size} of {v.size} never" if finite.size < v.size else ""))
        records_text = ", ".join(f"r{r:02d}" for r in found)
        print(f"| {label} | {c} | {records_text} | " + " | ".join(cells) + " |")

    if a.csv:
        with open(a.csv + ".part", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=["grid", "record"] + [m[0] for m in MEASURES])
            w.writeheader()
            w.writerows(rows)
        os.replace(a.csv + ".part", a.csv)
    if a.png:
        draw(summary, a.png)
    return 0


def draw(summary, png):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = [m for m in MEASURES if m[0] in ("wg2_rms_m", "FD_depth_rms_m", "LD_depth_rms_m", "LD_draft_err_s")]
    fig, axes = plt.subplots(1, len(panels), figsize=(4 * len(panels), 3.6))
    for ax, (key, title, scale, unit) in zip(axes, panels):
        for label, cost, per_record, found in summary[1:]:
            if not cost or not per_record:
                continue
            v = np.abs(np.array([per_record[r][key] for r in found])) * scale
            v = v[np.isfinite(v)]
            if v.size == 0:
                continue
            x = np.median(list(cost.values()))
            ax.errorbar([x], [np.median(v)], yerr=[[np.median(v) - v.min()], [v.max() - np.median(v)]], fmt="o", capsize=3)
            ax.annotate(label, (x, np.median(v)), textcoords="offset points", xytext=(6, 4))
        ref_label, ref_cost = summary[0][0], summary[0][1]
        if ref_cost:
            ax.axvline(np.median(list(ref_cost.values())), color="grey", ls=":", label=f"{ref_label} (the reference)")
            ax.legend(fontsize=7, loc="upper right")
        ax.set_xscale("log")
        ax.set_ylim(bottom=0.0)
        ax.set_xlabel("processor s a flow")
        ax.set_title(f"{title}, |error| [{unit}]", fontsize=9)
        ax.grid(alpha=0.3)
    fig.suptitle(f"flows against the {summary[0][0]} flows of the same records (median, range over the records)", fontsize=9)
    fig.tight_layout()
    fig.savefig(png + ".part.png", dpi=110)
    os.replace(png + ".part.png", png)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
