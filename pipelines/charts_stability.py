#!/usr/bin/python3
"""Stability map of the hydro schemes, from bench/hydro_stability's CSV.

    charts_stability.py HYDRO_STABILITY.csv OUT.png

One panel per case; in each, one row of markers per scheme (and friction treatment),
placed at the run's first step as dt sqrt(g h_max) / dx (so both schemes share the
axis), coloured by what happened: stable, negative depth (clamped), reverses (a draining
film flows back), blow-up. Hollow markers: outside the study the scheme's guard refuses
the setting or stops the run.
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pipelines.charts import save  # noqa: E402

COLOURS = {"stable": "tab:green", "negative depth": "tab:orange", "reverses": "tab:purple", "blow-up": "tab:red"}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("png")
    a = ap.parse_args()
    rows = list(csv.DictReader(open(a.csv)))
    if not rows:
        sys.exit(f"charts_stability.py: {a.csv}: no rows")
    cases = list(dict.fromkeys(r["case"] for r in rows))
    fig, axes = plt.subplots(len(cases), 1, figsize=(9, 1.3 + 1.25 * len(cases)), sharex=True)
    for ax, case in zip(axes, cases):
        rs = [r for r in rows if r["case"] == case]
        lines = list(dict.fromkeys(f"{r['scheme']} ({r['friction']} friction)" for r in rs))
        for y, line in enumerate(lines):
            for r in rs:
                if f"{r['scheme']} ({r['friction']} friction)" != line:
                    continue
                colour = COLOURS[r["outcome"]]
                hollow = r["guard"] != "runs"
                ax.scatter(float(r["c_dt_over_dx"]), y, s=46, marker="o", edgecolors=colour, facecolors="none" if hollow else colour,
                           linewidths=1.5)
        ax.set_yticks(range(len(lines)))
        ax.set_yticklabels(lines, fontsize=8)
        ax.set_ylim(-0.7, len(lines) - 0.3)
        ax.set_title(case, fontsize=9, loc="left")
        ax.grid(axis="x", alpha=0.3)
    axes[-1].set_xlabel("first step, dt √(g h_max) / dx")
    handles = [plt.Line2D([], [], marker="o", linestyle="", color=c, label=k) for k, c in COLOURS.items()]
    handles.append(plt.Line2D([], [], marker="o", linestyle="", markerfacecolor="none", markeredgecolor="grey",
                              label="refused or stopped by the guard"))
    axes[0].legend(handles=handles, fontsize=7, ncol=5, loc="lower left", bbox_to_anchor=(0.0, 1.15))
    fig.suptitle("Hydro stability map: step size against outcome", y=0.995)
    fig.tight_layout()
    save(fig, os.path.dirname(a.png) or ".", os.path.basename(a.png))


if __name__ == "__main__":
    main()
