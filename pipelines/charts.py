#!/usr/bin/python3
"""The pictures people look at, from flows, trajectories and statistics.

    charts.py --scene SCENE.nc --flows FLOW.nc ... [--trajectories TRAJ.nc ...]
              [--stats STATS.nc] --out DIR

Writes PNGs into DIR (each skipped, with a line saying why, when its input is missing):

  trajectories.png      debris paths over the scene with a vorticity snapshot
  wg2.png               WG2 level, ensemble mean ± std against time
  time_to_draft.png     time at which the depth first exceeds the 2.5 cm draft (Fig. 8)
  sections.png          passage position per cross-section (mean, median, std)
  speed_density.png     passage speed kernel densities per section
  yaw.png               largest rotation in the first 30 s of the run and its relation to the
                        direction of movement (Fig. 16), and the same after motion starts
  relative_error.png    R(t) per parameter against the control
  probability.png       probability that debris passes each cell
  max_speed.png         largest debris speed per cell
  buildings.png         building footprints coloured by the share of trajectories that hit them,
                        the 90th-percentile impact force written on the most loaded ones

Uses only Debian's python3-matplotlib, python3-xarray and python3-netcdf4.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from pipelines import stats_file as S  # noqa: E402

VARIANT_STYLE = {"center+single": ("tab:orange", "CC+SC"), "local+multi": ("tab:blue", "LC+MC")}


def by_standard_name(ds, name):
    for v in ds.data_vars:
        if ds[v].attrs.get("standard_name") == name:
            return ds[v]
    raise SystemExit(f"charts.py: {ds.encoding.get('source', '?')}: no variable with standard_name '{name}'")


def scene_background(ax, scene, extent=None):
    """Ground (grey, buildings dark) with still water in light blue."""
    z = scene["z"].values
    x, y = scene["x"].values, scene["y"].values
    land = np.ma.masked_where(z < 0, z)
    water = np.ma.masked_where(z >= 0, z)
    ext = [x[0], x[-1], y[0], y[-1]]
    deep, high = -0.3, 0.08  # the flume's [m]; a map (wider than 100 m) takes its own from the ground
    if x[-1] - x[0] > 100.0 and (z < 0).any() and (z >= 0).any():
        deep, high = np.percentile(z[z < 0], 2), np.percentile(z[z >= 0], 90)
    ax.imshow(water, origin="lower", extent=ext, cmap="Blues_r", vmin=deep, vmax=-deep / 6, aspect="equal")
    ax.imshow(land, origin="lower", extent=ext, cmap="Greys", vmin=-high / 4, vmax=high, aspect="equal")
    if extent:
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.set_xlabel("x [m] (east)")
    ax.set_ylabel("y [m] (north)")


def save(fig, out, name):
    path = os.path.join(out, name)
    fig.savefig(path + ".part.png", dpi=130, bbox_inches="tight")
    os.replace(path + ".part.png", path)
    plt.close(fig)
    print(f"charts.py: wrote {path}")


def city_extent(scene):
    x = scene["x"].values
    return [max(x[0], -0.8), x[-1], scene["y"].values[0], scene["y"].values[-1]]


def chart_trajectories(scene, flows, trajs, out, snapshot_time):
    if not trajs:
        print("charts.py: trajectories.png skipped (no --trajectories)")
        return
    fig, ax = plt.subplots(figsize=(12, 5.6))
    scene_background(ax, scene, city_extent(scene))
    if flows:
        f = xr.open_dataset(flows[0])
        h = by_standard_name(f, "sea_floor_depth_below_sea_surface")
        u = by_standard_name(f, "sea_water_x_velocity")
        v = by_standard_name(f, "sea_water_y_velocity")
        t = (f["time"] - f["time"][0]) / np.timedelta64(1, "s")
        k = int(np.argmin(np.abs(t.values - snapshot_time)))
        dx = float(f["x"][1] - f["x"][0])
        dy = float(f["y"][1] - f["y"][0])
        uu, vv, hh = u[k].values, v[k].values, h[k].values
        vort = np.gradient(vv, dx, axis=1) - np.gradient(uu, dy, axis=0)
        vort = np.ma.masked_where(hh < 0.005, vort)
        xs, ys = f["x"].values, f["y"].values
        im = ax.imshow(vort, origin="lower", extent=[xs[0], xs[-1], ys[0], ys[-1]], cmap="RdBu_r", vmin=-5, vmax=5,
                       alpha=0.75, aspect="equal")
        fig.colorbar(im, ax=ax, shrink=0.8, label=f"vorticity at t = {t.values[k]:.0f} s [1/s] (depth > 5 mm)")
    seen = set()
    for path in trajs:
        d = xr.open_dataset(path, decode_times=False)
        members = range(d.sizes["trajectory"])
        if "param_set" in d and "param_set_is_control" in d:  # a sweep: the control set only
            ctrl = d["param_set_is_control"].values
            members = [n for n in members if ctrl[int(d["param_set"].values[n])]]
        for n in members:
            key = f"{str(d['contact_model'].values[n])}+{str(d['collision_model'].values[n])}"
            color, label = VARIANT_STYLE.get(key, ("k", key))
            x, y = d["x"].values[n], d["y"].values[n]
            ax.plot(x, y, color=color, lw=1.4 if len(members) <= 8 else 0.8, alpha=1.0 if len(members) <= 8 else 0.6,
                    label=label if label not in seen else None)
            seen.add(label)
            ax.plot(x[0], y[0], "o", color="k", ms=4)
            ax.plot(x[-1], y[-1], "s", color=color, ms=4)
            name = str(d["start_name"].values[n]) if "start_name" in d else ""
            if name:
                ax.annotate(name, (x[0], y[0]), textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title("Debris paths (circle: start, square: end) over the ground")
    save(fig, out, "trajectories.png")


def chart_wg2(flows, out):
    series = []
    for path in flows:
        f = xr.open_dataset(path)
        if "gauge_eta" not in f or "gauge_name" not in f:
            continue
        names = [str(s) for s in f["gauge_name"].values]
        if "WG2" not in names:
            continue
        g = names.index("WG2")
        t = (f["gauge_time"] - f["time"][0]) / np.timedelta64(1, "s") if np.issubdtype(f["gauge_time"].dtype, np.datetime64) else f["gauge_time"]
        series.append((np.asarray(t), f["gauge_eta"].values[:, g]))
    if not series:
        print("charts.py: wg2.png skipped (no flow with a WG2 gauge)")
        return
    n = min(len(s[0]) for s in series)
    t = series[0][0][:n]
    eta = np.stack([s[1][:n] for s in series])
    mean, std = eta.mean(axis=0), eta.std(axis=0)
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.fill_between(t, (mean - std) * 100, (mean + std) * 100, color="tab:blue", alpha=0.3, label="± 1 std")
    ax.plot(t, mean * 100, color="tab:blue", label=f"mean of {len(series)} flows")
    ax.axhline(6.3, color="k", ls=":", lw=1, label="paper's maximum ≈ 6.3 cm")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("water level at WG2 [cm]")
    ax.set_title("WG2 (port entrance)")
    ax.legend()
    ax.grid(alpha=0.3)
    save(fig, out, "wg2.png")


def chart_time_to_draft(scene, flows, out):
    if not flows:
        print("charts.py: time_to_draft.png skipped (no --flows)")
        return
    f = xr.open_dataset(flows[0], decode_timedelta=False)
    if "arrival_time" not in f:
        print("charts.py: time_to_draft.png skipped (no arrival_time in the flow)")
        return
    a = f["arrival_time"]
    vals = a.values.astype(float)
    if np.issubdtype(a.dtype, np.timedelta64):
        vals = a.values / np.timedelta64(1, "s")
    vals = np.ma.masked_invalid(np.where(vals < 0, np.nan, vals))
    xs, ys = f["x"].values, f["y"].values
    fig, ax = plt.subplots(figsize=(12, 5.6))
    scene_background(ax, scene, city_extent(scene))
    im = ax.imshow(vals, origin="lower", extent=[xs[0], xs[-1], ys[0], ys[-1]], cmap="viridis_r", vmin=0, vmax=300,
                   aspect="equal", alpha=0.9)
    fig.colorbar(im, ax=ax, shrink=0.8, label="time the depth first exceeds 2.5 cm [s]")
    if "flooded" in f:  # the inundation line: the 0.5 contour of the flooded flag (docs/hydro.md)
        depth = float(f["flooded"].attrs.get("flood_depth", float("nan")))
        ax.contour(xs, ys, f["flooded"].values.astype(float), levels=[0.5], colors="k", linewidths=0.8)
        ax.plot([], [], "k-", lw=0.8, label=f"inundation line (depth > {1000 * depth:g} mm at some time)")
        if "runup_x" in f and np.isfinite(float(f["runup_x"])):
            ax.plot(float(f["runup_x"]), float(f["runup_y"]), "k^", ms=7,
                    label=f"highest flooded ground {1000 * float(f['runup_elevation']):.1f} mm")
        ax.legend(loc="lower right", fontsize=8)
    for p in ("FD", "LD"):
        pts = point_positions(scene)
        if p in pts:
            ax.plot(*pts[p], "r*", ms=10)
            ax.annotate(p, pts[p], textcoords="offset points", xytext=(5, 5), color="r")
    ax.set_title("Time to the debris draft (paper's Fig. 8)")
    save(fig, out, "time_to_draft.png")


def group_labels(st):
    return [f"{b} {v}" for b, v in zip(st[S.GROUP_BODY].values, st[S.GROUP_VARIANT].values)]


def group_color(label):
    return "tab:blue" if "LC+MC" in label else ("tab:orange" if "CC+SC" in label else "tab:gray")


def chart_sections(st, out):
    groups, names = group_labels(st), [str(n) for n in st[S.SECTION_NAME].values]
    count = st[S.PASSAGE_COUNT].values
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.6))
    width = 0.8 / max(1, len(groups))
    for g, label in enumerate(groups):
        xs = np.arange(len(names)) + (g - (len(groups) - 1) / 2) * width
        for ax, (v_mean, v_std, v_median), scale in (
                (axes[0], (S.PASSAGE_Y_MEAN, S.PASSAGE_Y_STD, S.PASSAGE_Y_MEDIAN), 1.0),
                (axes[1], (S.PASSAGE_SPEED_MEAN, S.PASSAGE_SPEED_STD, S.PASSAGE_SPEED_MEDIAN), 100.0)):
            mean = st[v_mean].values[g] * scale
            std = st[v_std].values[g] * scale
            med = st[v_median].values[g] * scale
            ok = count[g] > 0
            ax.errorbar(xs[ok], mean[ok], yerr=np.nan_to_num(std[ok]), fmt="o", color=group_color(label),
                        mfc="white" if label.startswith("LD") else group_color(label), capsize=3,
                        label=f"{label} (mean ± std, x = median)")
            ax.plot(xs[ok], med[ok], "x", color=group_color(label))
            for xi, c, m in zip(xs[ok], count[g][ok], mean[ok]):
                ax.annotate(f"n={c}", (xi, m), textcoords="offset points", xytext=(3, -10), fontsize=6)
    for ax, lab in ((axes[0], "passage position y [m]"), (axes[1], "passage speed [cm/s]")):
        ax.set_xticks(np.arange(len(names)))
        ax.set_xticklabels(names, rotation=20)
        ax.set_xlabel("cross-section")
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Where and how fast debris crosses each north-south section (all flows and parameter sets)")
    fig.tight_layout()
    save(fig, out, "sections.png")


def chart_speed_density(st, out):
    groups, names = group_labels(st), [str(n) for n in st[S.SECTION_NAME].values]
    count = st[S.PASSAGE_COUNT].values
    used = [k for k in range(len(names)) if count[:, k].sum() > 0]
    if not used:
        print("charts.py: speed_density.png skipped (no passages)")
        return
    ncol = min(3, len(used))
    nrow = (len(used) + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.4 * ncol, 3.4 * nrow), squeeze=False)
    for ax in axes.flat[len(used):]:
        ax.set_visible(False)
    speed = st[S.SPEED].values * 100
    for ax, k in zip(axes.flat, used):
        for g, label in enumerate(groups):
            if count[g, k] < 2:
                continue
            ax.plot(speed, st[S.PASSAGE_SPEED_KDE].values[g, k] / 100, color=group_color(label),
                    ls="--" if label.startswith("LD") else "-", label=f"{label} (n={count[g, k]})")
        ax.set_title(names[k])
        ax.set_xlabel("passage speed [cm/s]")
        ax.set_ylabel("density [1/(cm/s)]")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    fig.suptitle("Passage speed, Gaussian kernel density (Silverman bandwidth)")
    fig.tight_layout()
    save(fig, out, "speed_density.png")


# The paper's experiment (FD, Fig. 16a): largest rotation in the first 30 s, median and range.
PAPER_FD_ROTATION = {"median": 46.0, "min": 14.0, "max": 64.0}


def finite(a):
    a = np.asarray(a, dtype=float)
    return np.where(np.abs(a) > 1e30, np.nan, a)


def chart_yaw(st, out):
    """Top: the paper's Fig. 16 (from the run's start): the largest rotation and its relation
    to the direction of movement. Bottom: the same window counted from motion start."""
    groups = group_labels(st)
    centres = st[S.YAW_BIN].values
    width = float(centres[1] - centres[0]) if len(centres) > 1 else 10.0
    window = float(st.attrs.get(S.YAW_WINDOW, 30.0))
    fig, axes = plt.subplots(2, 2, figsize=(13, 8.4))
    style = {g: dict(color=group_color(g), ls="--" if g.startswith("LD") else "-") for g in groups}

    ax = axes[0][0]
    med, lo, hi = (finite(st[v].values) for v in (S.MAX_ROTATION_FROM_START_MEDIAN, S.MAX_ROTATION_FROM_START_MIN,
                                                  S.MAX_ROTATION_FROM_START_MAX))
    for g, label in enumerate(groups):
        ax.step(centres, st[S.MAX_ROTATION_FROM_START_HISTOGRAM].values[g], where="mid", **style[label],
                label=f"{label}: median {med[g]:.0f}°, {lo[g]:.0f} to {hi[g]:.0f}°")
    p = PAPER_FD_ROTATION
    ax.axvspan(p["min"], p["max"], color="tab:red", alpha=0.12, label=f"experiment FD: {p['min']:.0f} to {p['max']:.0f}°")
    ax.axvline(p["median"], color="tab:red", lw=1.2, label=f"experiment FD median {p['median']:.0f}°")
    ax.set_xlabel(f"largest rotation from the initial heading, 0 to {window:g} s of the run [degree, ccw +]")
    ax.set_ylabel(f"trajectories per {width:g}° bin")
    ax.set_title("largest rotation in the first seconds of the run (paper Fig. 16a, b)", fontsize=10)
    ax.legend(fontsize=7)

    ax = axes[0][1]
    rotation = finite(st[S.MEMBER_MAX_ROTATION_FROM_START].values)
    direction = finite(st[S.MEMBER_MOVEMENT_DIRECTION].values)
    member_group = st[S.MEMBER_GROUP].values
    r = finite(st[S.ROTATION_DIRECTION_CORRELATION].values)
    for g, label in enumerate(groups):
        sel = member_group == g
        ax.scatter(rotation[sel], direction[sel], s=14, color=style[label]["color"], marker="^" if label.startswith("LD") else "o",
                   alpha=0.7, label=f"{label} (r = {r[g]:.2f})")
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xlabel(f"largest rotation from the initial heading, 0 to {window:g} s [degree]")
    ax.set_ylabel(f"direction of movement at {window:g} s [° from east, NE +]")
    ax.set_title("rotation against direction of movement (paper Fig. 16c)", fontsize=10)
    ax.legend(fontsize=7)

    for ax, var, title in ((axes[1][0], S.MAX_ROTATION_HISTOGRAM, "largest rotation from the heading at motion start"),
                           (axes[1][1], S.MAX_YAW_TO_MOTION_HISTOGRAM,
                            "largest angle of the long axis to the direction of motion")):
        for g, label in enumerate(groups):
            ax.step(centres, st[var].values[g], where="mid", **style[label], label=label)
        ax.set_xlabel(f"angle in the first {window:g} s after motion starts [degree]")
        ax.set_ylabel(f"trajectories per {width:g}° bin")
        ax.set_title(f"after motion start: {title}", fontsize=10)
    axes[1][0].legend(fontsize=8)
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out, "yaw.png")


def chart_relative_error(st, out):
    groups = group_labels(st)
    labels = [str(v) for v in st[S.PARAM_SET_LABEL].values]
    control = [bool(v) for v in st[S.PARAM_SET_IS_CONTROL].values]
    t = st[S.TIME].values - st[S.TIME].values[0]
    fig, axes = plt.subplots(1, len(groups), figsize=(4.2 * len(groups), 3.8), squeeze=False, sharey=True)
    cmap = plt.get_cmap("tab10")
    for ax, (g, label) in zip(axes[0], enumerate(groups)):
        for p, pl in enumerate(labels):
            if control[p]:
                continue
            r = st[S.RELATIVE_ERROR].values[g, p]
            r = np.where(np.abs(r) > 1e30, np.nan, r)
            ax.plot(t, r, color=cmap(p % 10), ls="-" if "x" in pl else "--", lw=1.2, label=pl)
        ax.axhline(0, color="k", lw=0.8)
        ax.set_title(label)
        ax.set_xlabel("time [s]")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("R(t) = (D - D_control) / D_control [-]")
    axes[0][-1].legend(fontsize=7, ncol=2)
    fig.suptitle("Relative change of the distance from the start per parameter (mean over flows)")
    fig.tight_layout()
    save(fig, out, "relative_error.png")


def chart_map(scene, st, out, var, name, label, cmap, scale=1.0, vmax=None):
    groups = group_labels(st)
    xs, ys = st[S.X].values, st[S.Y].values
    fig, axes = plt.subplots(len(groups), 1, figsize=(11, 3.3 * len(groups)), squeeze=False)
    for ax, (g, glabel) in zip(axes[:, 0], enumerate(groups)):
        scene_background(ax, scene, city_extent(scene))
        v = st[var].values[g].astype(float) * scale
        v = np.ma.masked_where(~np.isfinite(v) | (v <= 0) | (v > 1e30), v)
        im = ax.imshow(v, origin="lower", extent=[xs[0], xs[-1], ys[0], ys[-1]], cmap=cmap, vmin=0, vmax=vmax, aspect="equal")
        fig.colorbar(im, ax=ax, shrink=0.85, label=label)
        ax.set_title(f"{glabel}: {int(st[S.GROUP_MEMBERS].values[g])} trajectories", fontsize=10)
    fig.tight_layout()
    save(fig, out, name)


def building_ids(scene):
    """The scene's building_id (y, x), or the mask's 4-connected components numbered as flotsam numbers them."""
    if "building_id" in scene:
        return scene["building_id"].values.astype(int)
    if "building" not in scene:
        return None
    try:
        from scipy import ndimage
    except ImportError:
        return None
    ids, _ = ndimage.label(scene["building"].values != 0)  # 4-connected, numbered in row-major scan order
    return ids


def chart_buildings(scene, st, out, annotate=15):
    if S.BUILDING_ID not in st:
        print("charts.py: buildings.png skipped (statistics written before impacts were recorded)")
        return
    ids = building_ids(scene)
    if ids is None:
        print("charts.py: buildings.png skipped (the scene has no buildings, or no building_id and no scipy)")
        return
    stat_ids = st[S.BUILDING_ID].values.astype(int)
    prob = st[S.BUILDING_HIT_PROBABILITY + S.ALL].values.astype(float)
    p90 = st[S.BUILDING_IMPACT_FORCE_P90 + S.ALL].values.astype(float)
    p90[~np.isfinite(p90) | (p90 > 1e30)] = np.nan
    lookup = np.full(ids.max() + 1, np.nan)
    lookup[stat_ids] = prob
    field = np.where(ids > 0, lookup[np.clip(ids, 0, None)], np.nan)
    x, y = scene["x"].values, scene["y"].values
    extent = city_extent(scene)
    if np.any(field > 0):  # the buildings hit, with a margin of a tenth of their spread
        jj, ii = np.nonzero(field > 0)
        mx, my = 0.1 * (x[ii].max() - x[ii].min()), 0.1 * (y[jj].max() - y[jj].min())
        extent = [max(extent[0], x[ii].min() - mx), min(extent[1], x[ii].max() + mx),
                  max(extent[2], y[jj].min() - my), min(extent[3], y[jj].max() + my)]
    fig, ax = plt.subplots(figsize=(12, 4.2))
    scene_background(ax, scene, extent)
    hit = np.ma.masked_where(~(field > 0), field)
    never = np.ma.masked_where(~(field == 0), np.ones_like(field))
    ext = [x[0], x[-1], y[0], y[-1]]
    ax.imshow(never, origin="lower", extent=ext, cmap="Greys", vmin=0, vmax=3, aspect="equal")
    im = ax.imshow(hit, origin="lower", extent=ext, cmap="YlOrRd", vmin=0, vmax=1, aspect="equal")
    fig.colorbar(im, ax=ax, shrink=0.85, label="share of trajectories that hit the building [-]")
    order = [k for k in np.argsort(-np.nan_to_num(p90, nan=-1.0)) if np.isfinite(p90[k])][:annotate]
    for k in order:
        jj, ii = np.nonzero(ids == stat_ids[k])
        ax.annotate(f"{p90[k]:.3g} N", (x[ii].mean(), y[jj].mean()), fontsize=7, ha="center", va="center",
                    bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.75))
    members = int(st.sizes.get(S.MEMBER_ID, st[S.MEMBER_ID].size)) if S.MEMBER_ID in st else 0
    ax.set_title(f"impacts on buildings over {members} trajectories: hit probability (colour), 90th-percentile impact force "
                 f"(labels, the {len(order)} largest; ASCE 7-16 Sec. 6.11 estimate)", fontsize=9)
    fig.tight_layout()
    save(fig, out, "buildings.png")


def charts_from_stats(scene, stats_path, out):
    if not stats_path:
        print("charts.py: sections, speed_density, yaw, relative_error, probability, max_speed, buildings skipped (no --stats)")
        return
    st = xr.open_dataset(stats_path, decode_times=False)
    chart_sections(st, out)
    chart_speed_density(st, out)
    chart_yaw(st, out)
    chart_relative_error(st, out)
    chart_map(scene, st, out, S.PASS_PROBABILITY, "probability.png", "probability that debris passes the cell [-]", "magma_r",
              vmax=1.0)
    chart_map(scene, st, out, S.MAX_DEBRIS_SPEED, "max_speed.png", "largest debris speed in the cell [cm/s]", "viridis", scale=100.0)
    chart_buildings(scene, st, out)


def point_positions(scene):
    out = {}
    if "point_name" in scene and "point_x" in scene:
        for n, x, y in zip(scene["point_name"].values, scene["point_x"].values, scene["point_y"].values):
            out[str(n)] = (float(x), float(y))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--flows", nargs="*", default=[])
    ap.add_argument("--trajectories", nargs="*", default=[])
    ap.add_argument("--stats")
    ap.add_argument("--snapshot-time", type=float, default=250.0, help="time of the vorticity snapshot [s]")
    ap.add_argument("--out", required=True)
    ap.add_argument("--only-buildings", action="store_true", help="only buildings.png (any scene, any scale)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    for p in [a.scene] + a.flows + a.trajectories + ([a.stats] if a.stats else []):
        if not os.path.exists(p):
            sys.exit(f"charts.py: {p}: no such file")
    scene = xr.open_dataset(a.scene)
    if a.only_buildings:
        if not a.stats:
            sys.exit("charts.py: --only-buildings needs --stats")
        return chart_buildings(scene, xr.open_dataset(a.stats), a.out)
    chart_trajectories(scene, a.flows, a.trajectories, a.out, a.snapshot_time)
    chart_wg2(a.flows, a.out)
    chart_time_to_draft(scene, a.flows, a.out)
    charts_from_stats(scene, a.stats, a.out)


if __name__ == "__main__":
    main()
