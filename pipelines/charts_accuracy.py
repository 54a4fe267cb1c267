#!/usr/bin/python3
"""Error against cost for the hydro options, from pipelines/accuracy_hydro.py's CSV.

    charts_accuracy.py HYDRO_ACCURACY.csv OUT.png

One line per scheme × nesting, one point per grid spacing (labelled), three panels: the
WG2 level, the depth at the FD start and the depth at the LD start, each as RMS error
against the reference run, against CPU time. The reference itself is left out (its
error is zero).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = [("wg2_rms_m", "WG2 level, RMS error [mm]"), ("FD_depth_rms_m", "depth at FD start, RMS error [mm]"),
          ("LD_depth_rms_m", "depth at LD start, RMS error [mm]")]


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    rows = list(csv.DictReader(open(argv[1])))
    if not rows:
        sys.exit(f"charts_accuracy.py: {argv[1]}: no rows")
    ref = rows[0]
    lines = {}
    for r in rows[1:]:
        key = f"{r['scheme']}" + (f", nested ×{r['nest_ratio']}" if int(r["nest_ratio"]) > 1 else ", uniform")
        lines.setdefault(key, []).append(r)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    for ax, (col, label) in zip(axes, PANELS):
        for key, rs in sorted(lines.items()):
            rs = sorted(rs, key=lambda r: float(r["cpu_s"]))
            x = [float(r["cpu_s"]) for r in rs]
            y = [max(float(r[col]) * 1000, 1e-4) for r in rs]
            ax.plot(x, y, "o-", label=key)
            for xi, yi, r in zip(x, y, rs):
                ax.annotate(f"{float(r['resolution_m']) * 100:g} cm", (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("CPU time, one thread [s]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8, title=f"reference: {ref['config']}", title_fontsize=8)
    fig.suptitle("Hydro cost against error on the real layout (benchmark forcing)")
    fig.tight_layout()
    fig.savefig(argv[2] + ".part.png", dpi=120)
    os.replace(argv[2] + ".part.png", argv[2])
    print(f"charts_accuracy.py: wrote {argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
