#!/usr/bin/python3
"""Debris speed-against-accuracy and stability charts from the CSVs of
pipelines/accuracy_debris.py and build/debris_stability.

    charts_accuracy_debris.py DATA_DIR IMG_DIR

Reads DATA_DIR/debris_frames_accuracy.csv, debris_step_accuracy.csv and
debris_stability.csv; writes IMG_DIR/debris_frames_error.png (trajectory error against
flow file size, one line per model × time interpolant, one point per stored frame
interval), debris_step_error.png (trajectory error against stepping CPU per body-run,
one line per model × integrator × step series) and debris_stability.png (the explicit
added mass's growth per step against Cm; the share of runs that go through a one-cell
wall against the step length). Errors are medians over the nine bodies of a start; the
dotted lines are the floors (the reference with its starts moved 1 mm). See
docs/debris.md.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METRICS = [(f"after_{h}s_m", f"distance {h} s after release [m]") for h in (10, 30, 60)]
STARTS = ["FD", "LD"]
COLOURS = {"CC+SC": "tab:blue", "LC+MC": "tab:red"}
FLOOR_VALUE = 1e-5  # plotted in place of a smaller error on the log axis [m]


def read(path):
    rows = list(csv.DictReader(open(path)))
    if not rows:
        sys.exit(f"charts_accuracy_debris.py: {path}: no rows")
    return rows


def save(fig, path, legend_rows=0):
    fig.tight_layout(rect=(0, 0.04 * legend_rows, 1, 1))
    fig.savefig(path + ".part.png", dpi=110)
    os.replace(path + ".part.png", path)
    plt.close(fig)
    print(f"charts_accuracy_debris.py: wrote {path}")


def error_grid(rows, is_floor, xlabel, draw, title, legend_title, legend_rows, out):
    """Starts (rows) × METRICS (columns) on log-log axes: the floor lines, then
    draw(ax, rows of the start, metric column), then one legend below."""
    fig, axes = plt.subplots(2, 3, figsize=(16, 8.5))
    for i, start in enumerate(STARTS):
        for j, (col, label) in enumerate(METRICS):
            ax = axes[i][j]
            mine = [r for r in rows if r["start"] == start]
            for r in mine:
                if is_floor(r):
                    ax.axhline(max(float(r[col]), FLOOR_VALUE), color=COLOURS[r["model"]], ls=":", lw=1)
            draw(ax, mine, col)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(xlabel)
            ax.set_ylabel(label)
            ax.set_title(f"{start} starts", fontsize=10)
            ax.grid(alpha=0.3, which="both")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8, title=legend_title, title_fontsize=8)
    fig.suptitle(title)
    save(fig, out, legend_rows)


def frames_chart(rows, out):
    def draw(ax, mine, col):
        for model in COLOURS:
            for interp, style in (("linear", "o-"), ("cubic", "s--")):
                rs = sorted((r for r in mine if r["model"] == model and r["interpolant"] == interp), key=lambda r: float(r["file_bytes"]))
                rs = [r for r in rs if not (interp == "linear" and float(r["frame_interval_s"]) == 0.1)]  # the reference
                x = [float(r["file_bytes"]) / 1e6 for r in rs]
                y = [max(float(r[col]), FLOOR_VALUE) for r in rs]
                ax.plot(x, y, style, color=COLOURS[model], label=f"{model}, {interp}")
                if interp == "linear":
                    for xi, yi, r in zip(x, y, rs):
                        ax.annotate(f"{r['frame_interval_s']} s", (xi, yi), textcoords="offset points", xytext=(3, 3), fontsize=7)

    error_grid(rows, lambda r: r["interpolant"] == "floor", "flow file size [MB]", draw,
               "Debris trajectory error against stored frame interval and time interpolant (real layout, 4 cm flow)",
               "reference: 0.1 s frames, linear; dotted: the reference with starts moved 1 mm", 2, out)


def steps_chart(rows, out):
    def draw(ax, mine, col):
        for model in COLOURS:
            for integ, style in (("euler", "o-"), ("heun", "s--")):
                rs = sorted((r for r in mine if r["model"] == model and r["integrator"] == integ and r["series"] == "dt_max"),
                            key=lambda r: float(r["stepping_cpu_per_body_run_s"]))
                x = [float(r["stepping_cpu_per_body_run_s"]) for r in rs]
                y = [max(float(r[col]), FLOOR_VALUE) for r in rs]
                ax.plot(x, y, style, color=COLOURS[model], mfc="none" if integ == "heun" else None, label=f"{model}, {integ}")
                for xi, yi, r in zip(x, y, rs):
                    ax.annotate(f"{float(r['dt_max_s']) * 1000:g} ms", (xi, yi), textcoords="offset points", xytext=(3, 3), fontsize=6)
                fr = [r for r in mine if r["model"] == model and r["integrator"] == integ and r["series"] == "fraction"]
                ax.plot([float(r["stepping_cpu_per_body_run_s"]) for r in fr], [max(float(r[col]), FLOOR_VALUE) for r in fr], "x",
                        color=COLOURS[model], ms=5)

    error_grid(rows, lambda r: r["series"] == "floor", "stepping CPU per body-run [s]", draw,
               "Debris trajectory error against step and integrator (real layout, 4 cm flow, 1 s frames)",
               "lines: dt_max at f = 0.25; x: f = 1 … 1/16 at dt_max 10 ms; reference: heun, 1.25 ms, f 1/16; "
               "dotted: the reference with starts moved 1 mm", 3, out)


def stability_chart(rows, out):
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.6))
    am = [r for r in rows if r["map"] == "added_mass" and r["method"] == "explicit"]
    cm = [float(r["cm"]) for r in am]
    a1.plot(cm, [float(r["growth_per_step"]) for r in am], "o", color="tab:red", label="explicit: measured growth per step")
    a1.plot([1.0, 4.0], [0.0, 3.0], "-", color="grey", lw=1, label="theory: C_a = Cm − 1")
    a1.axhline(1.0, color="k", ls=":", lw=1)
    a1.axvspan(2.0, 4.0, color="tab:red", alpha=0.08, label="explicit unstable (Cm > 2)")
    a1.axvline(3.0, color="tab:purple", ls="--", lw=1, label="paper's Cm 1.5 × 2 = 3")
    blown = [float(r["cm"]) for r in am if r["speed_ratio_2s"] in ("nan", "inf") or float(r["speed_ratio_2s"]) > 100]
    a1.plot(blown, [0.05] * len(blown), "x", color="tab:red", label="explicit blown up within 2 s")
    a1.set_xlabel("Cm")
    a1.set_ylabel("growth of the step-to-step oscillation per step")
    a1.set_title("added mass: the implicit form follows the relaxation at every Cm", fontsize=9)
    a1.legend(fontsize=7)
    a1.grid(alpha=0.3)
    tn = [r for r in rows if r["map"] == "tunnelling"]
    for cell, colour in (("0.01", "tab:blue"), ("0.04", "tab:orange")):
        for heading, marker in (("0", "o"), ("20", "s"), ("90", "^")):
            rs = sorted((r for r in tn if r["cell_m"] == cell and r["heading_deg"] == heading), key=lambda r: float(r["step_travel_m"]))
            a2.plot([float(r["step_travel_m"]) * 100 for r in rs], [int(r["tunnelled_of_8"]) / 8 for r in rs], marker + "-", color=colour,
                    ms=4, lw=1, label=f"{float(cell) * 100:g} cm cells, heading {heading}°")
    for cell, colour in ((0.01, "tab:blue"), (0.04, "tab:orange")):
        a2.axvline(0.25 * cell * 100, color=colour, ls=":", lw=1)
    a2.axvline(5.0, color="grey", ls="--", lw=1, label="half the body width (5 cm)")
    a2.set_xscale("log")
    a2.set_xlabel("step travel at 3 m/s [cm] (dotted: default f = 0.25)")
    a2.set_ylabel("share of 8 start phases through a one-cell wall")
    a2.set_title("tunnelling against the debris step", fontsize=9)
    a2.legend(fontsize=7)
    a2.grid(alpha=0.3, which="both")
    save(fig, out)


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    data, img = argv[1], argv[2]
    os.makedirs(img, exist_ok=True)
    frames_chart(read(os.path.join(data, "debris_frames_accuracy.csv")), os.path.join(img, "debris_frames_error.png"))
    steps_chart(read(os.path.join(data, "debris_step_accuracy.csv")), os.path.join(img, "debris_step_error.png"))
    stability_chart(read(os.path.join(data, "debris_stability.csv")), os.path.join(img, "debris_stability.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
