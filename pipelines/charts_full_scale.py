#!/usr/bin/python3
"""The real-scale demo's chart: Kainan at the prototype scale, in its projected CRS.

    python3 -m pipelines.charts_full_scale --scene SCENE.nc --stats STATS.nc --sweep SWEEP.nc
                                          [--flows FLOW.nc ...] --out PNG

Two panels over the port and city, axes in the scene's projected coordinates (UTM zone
53N eastings and northings, from the files' CF grid mapping): (a) the probability that a
body's centre passes each cell, one colour per source (a body, or a yard's bodies), with every track drawn thin;
(b) the largest debris speed per cell over all trajectories, with the flows' largest
depth (envelope) as contours. Uses only Debian's python3-matplotlib, -xarray, -netcdf4.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.colors import LinearSegmentedColormap  # noqa: E402

from pipelines import stats_file as S  # noqa: E402

BODY_COLOURS = ["tab:red", "tab:purple", "tab:orange", "tab:green", "tab:brown", "tab:pink"]


def crs_label(ds):
    """'WGS 84 / UTM zone 53N (EPSG:32653)' from the grid mapping's crs_wkt."""
    if "crs" not in ds.variables:
        return "local metres (no CRS)"
    wkt = ds["crs"].attrs.get("crs_wkt", "")
    name = wkt.split('"')[1] if wkt.count('"') >= 2 else "projected CRS"
    code = ""
    if 'AUTHORITY["EPSG","' in wkt:
        code = wkt.rsplit('AUTHORITY["EPSG","', 1)[1].split('"')[0]
    return f"{name} (EPSG:{code})" if code else name


def ground(ax, scene, extent):
    """Sea in blues by depth, land in greys by height, buildings dark."""
    z = scene["z"].values
    x, y = scene["x"].values, scene["y"].values
    dx = x[1] - x[0]
    ext = [x[0] - dx / 2, x[-1] + dx / 2, y[0] - dx / 2, y[-1] + dx / 2]
    ax.imshow(np.ma.masked_where(z >= 0, z), origin="lower", extent=ext, cmap="Blues_r", vmin=-40, vmax=5, aspect="equal")
    ax.imshow(np.ma.masked_where(z < 0, z), origin="lower", extent=ext, cmap="Greys", vmin=-4, vmax=30, aspect="equal")
    if "building" in scene:
        b = scene["building"].values
        ax.imshow(np.ma.masked_where(b == 0, b), origin="lower", extent=ext, cmap=LinearSegmentedColormap.from_list(
            "roof", ["#555555", "#555555"]), aspect="equal", alpha=0.85)
    ax.set_xlim(extent[0], extent[1])
    ax.set_ylim(extent[2], extent[3])
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.set_xlabel(f"easting [m], {crs_label(scene)}")
    ax.set_ylabel("northing [m]")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", required=True)
    p.add_argument("--stats", required=True)
    p.add_argument("--sweep", required=True)
    p.add_argument("--flows", nargs="*", default=[])
    p.add_argument("--out", required=True)
    a = p.parse_args()
    scene = xr.open_dataset(a.scene)
    stats = xr.open_dataset(a.stats)
    sweep = xr.open_dataset(a.sweep, decode_times=False)
    x, y = stats[S.X].values, stats[S.Y].values
    dx = x[1] - x[0]
    ext_map = [x[0] - dx / 2, x[-1] + dx / 2, y[0] - dx / 2, y[-1] + dx / 2]
    # The port and city: east of the flume's x = -0.5 m (E 517875) in the demo's frame.
    extent = [517875.0, scene["x"].values[-1], scene["y"].values[0], scene["y"].values[-1]]

    fig, axes = plt.subplots(2, 1, figsize=(13, 10.5), constrained_layout=True)
    ax = axes[0]
    ground(ax, scene, extent)
    bodies = list(dict.fromkeys(str(b) for b in stats[S.GROUP_BODY].values))
    handles = []
    for g, body in enumerate(stats[S.GROUP_BODY].values):
        colour = BODY_COLOURS[bodies.index(str(body)) % len(BODY_COLOURS)]
        pp = stats[S.PASS_PROBABILITY].values[g]
        cmap = LinearSegmentedColormap.from_list("p", [(0, 0, 0, 0), colour])
        ax.imshow(np.ma.masked_where(pp <= 0, pp), origin="lower", extent=ext_map, cmap=cmap, vmin=0, vmax=1, alpha=0.75,
                  aspect="equal")
    # Each trajectory's group: the GIS source its body came from (a yard), else the body.
    names = [str(n) for n in sweep["body_name"].values]
    sources = [str(v) for v in sweep["body_source"].values] if "body_source" in sweep else [""] * len(names)
    group_of = {n: (src if src else n) for n, src in zip(names, sources)}
    track_group = [group_of[str(b)] for b in sweep["body"].values]
    for k, group in enumerate(track_group):
        colour = BODY_COLOURS[bodies.index(group) % len(BODY_COLOURS)] if group in bodies else "k"
        ax.plot(sweep["x"].values[k], sweep["y"].values[k], color=colour, lw=0.6, alpha=0.8)
    for b in bodies:
        k = track_group.index(b)
        colour = BODY_COLOURS[bodies.index(b) % len(BODY_COLOURS)]
        length = float(sweep["length"].values[k])
        count = len({str(sweep["body"].values[j]) for j, g in enumerate(track_group) if g == b})
        label = f"{b} ({length:g} m long)" if count == 1 else f"{b} ({count} bodies, {length:g} m long)"
        handles.append(plt.Line2D([], [], color=colour, lw=3, label=label))
        for j, g in enumerate(track_group):
            if g == b and int(sweep["perturbation"].values[j]) == 0:
                ax.plot(sweep["x0"].values[j], sweep["y0"].values[j], "o", mfc="white", mec=colour, ms=4)
    ax.legend(handles=handles, loc="lower right", fontsize=9, framealpha=0.9)
    members = sweep.sizes["trajectory"]
    flows = int(stats[S.MEMBER_FLOW].max()) + 1 if S.MEMBER_FLOW in stats else 0
    ax.set_title(f"(a) probability that the body's centre passes each cell ({members} tracks over {flows} flows; "
                 f"colour strength = probability)", fontsize=11, loc="left")

    ax = axes[1]
    ground(ax, scene, extent)
    speed = stats[S.MAX_DEBRIS_SPEED_ALL].values
    im = ax.imshow(np.ma.masked_invalid(speed), origin="lower", extent=ext_map, cmap="inferno_r", aspect="equal",
                   vmin=0, vmax=np.nanpercentile(speed, 99) if np.isfinite(speed).any() else 1)
    fig.colorbar(im, ax=list(axes), shrink=0.45, anchor=(0.0, 0.05), label="largest debris speed [m/s], panel (b)")
    if a.flows:
        depth = None
        for f in a.flows:
            with xr.open_dataset(f) as flow:
                d = flow["max_depth"].values
                depth = d if depth is None else np.fmax(depth, d)
                fx, fy = flow["x"].values, flow["y"].values
        cs = ax.contour(fx, fy, depth, levels=[0.5, 2, 5], colors=["#4d9de0", "#1f5fa8", "#0b2e59"], linewidths=0.7)
        ax.clabel(cs, fmt="%g m", fontsize=7)
    ax.set_title("(b) largest debris speed per cell; contours: largest water depth over the flows [m]", fontsize=11,
                 loc="left")
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    fig.suptitle("Kainan port at the prototype scale (the 1/250 flume x250): debris from the paper's box, a container "
                 "yard and a car park", fontsize=12)
    fig.savefig(a.out + ".part.png", dpi=150)
    os.replace(a.out + ".part.png", a.out)
    print(f"chart: {a.out}")


if __name__ == "__main__":
    main()
