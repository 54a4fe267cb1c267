#!/usr/bin/python3
"""The design standard's debris hazard region beside the simulated ensemble, per source.

    python3 -m pipelines.hazard_region --sweep SWEEP.nc [--scene SCENE.nc] --out DIR
                                      [--half-angle 22.5] [--sources NAME,...] [--no-charts]

ASCE 7-16 Section 6.11 (after Naito et al. 2014's survey of the 2011 Tohoku debris)
marks as exposed to debris from a source the region within +-22.5 degrees of the flow
direction from the debris' origin, out to the inundation limit. Here, per source (a GIS
feature of `flotsam debris --sources`, else a named body such as FD), docs/debris.md
"The design standard's hazard region":

- origins: the start positions of the source's bodies (a yard's every body);
- flow direction: at the source's centroid in each flow of the sweep, the direction of
  the velocity at the frame of the largest momentum flux h|u|^2 up to the time of the
  deepest water there (inflow), and among the later frames whose velocity points
  against the inflow (outflow, the return flow); the flows' unit vectors averaged;
- region: cells whose centre lies within the half-angle of the inflow (or outflow)
  direction seen from some origin, and flooded (depth above the flow's flood_depth) in
  some flow of the sweep;
- passages: the cells a member's centre passes (segments between output samples,
  stepped at a quarter cell), counted once per member; the share of those passages that
  lie in the region, and the share of members that end inside it;
- buildings: hit by the source's members (the sweep's impacts) outside the region, and
  in the region (a cell of it beside a flooded cell) but never hit.

Writes DIR/hazard_regions.csv (one row per source), DIR/hazard_buildings.csv (source,
building, in region, hit probability), DIR/hazard_regions.nc (the regions and passage
shares on the scene grid) and, unless --no-charts, DIR/hazard_<source>.png.
The standard's further limit on how far the region reaches was not checked against its
text and is not applied (docs/debris.md says so). Uses numpy, netCDF4, matplotlib.
"""
import argparse
import csv
import math
import os
import sys

import netCDF4
import numpy as np

from pipelines import input_checks as checks

EPS = 1e-9


def strings(ds, name):
    v = ds.variables[name]
    v.set_auto_chartostring(True)
    return [str(s) for s in np.atleast_1d(v[:])]


def read_sweep(path):
    with checks.open_nc("--sweep", path, ["sweep"]) as ds:
        x, y, _ = checks.tracks(ds)  # finite, in range, in metres (pipelines/input_checks.py)
        out = {
            "body": strings(ds, "body"),
            "flow": strings(ds, "flow"),
            "x": x,
            "y": y,
            "bodies": strings(ds, "body_name"),
            "flows": strings(ds, "flow_path"),
            "scene_file": getattr(ds, "scene_file", ""),
            "crs": checks.crs_of(ds, "yaw"),
        }
        out["body_source"] = strings(ds, "body_source") if "body_source" in ds.variables else [""] * len(out["bodies"])
        if "impact_trajectory" in ds.variables:
            out["impact_trajectory"] = np.asarray(ds["impact_trajectory"][:], dtype=int)
            out["impact_building"] = np.asarray(ds["impact_building"][:], dtype=int)
        else:
            out["impact_trajectory"] = out["impact_building"] = np.zeros(0, dtype=int)
    return out


def read_scene(path):
    with checks.open_nc("--scene", path, ["scene"]) as ds:
        s = {"x": checks.finite_values(ds, "x", "length"), "y": checks.finite_values(ds, "y", "length"),
             "z": checks.finite_values(ds, "z", "length", checks.MAX_DEPTH), "crs": grid_mapping(ds)}
        if getattr(ds["z"], "positive", "up") == "down":
            s["z"] = -s["z"]
        s["crs_name"] = checks.crs_of(ds, "z")
        if "building_id" in ds.variables:
            s["building_id"] = np.asarray(ds["building_id"][:], dtype=int)
        elif "building" in ds.variables:
            s["building_id"] = components(np.asarray(ds["building"][:]) != 0)
        else:
            s["building_id"] = np.zeros(s["z"].shape, dtype=int)
    return s


def grid_mapping(ds):
    """The attributes of the scene's CF grid-mapping variable (empty: local metres)."""
    name = getattr(ds["z"], "grid_mapping", "")
    return {a: ds[name].getncattr(a) for a in ds[name].ncattrs()} if name in ds.variables else {}


def components(mask):
    """4-connected components numbered in row-major order from the south-west (formats/scene.hpp)."""
    ids = np.zeros(mask.shape, dtype=int)
    n = 0
    ny, nx = mask.shape
    for j in range(ny):
        for i in range(nx):
            if mask[j, i] and ids[j, i] == 0:
                n += 1
                stack = [(j, i)]
                ids[j, i] = n
                while stack:
                    a, b = stack.pop()
                    for c, d in ((a + 1, b), (a - 1, b), (a, b + 1), (a, b - 1)):
                        if 0 <= c < ny and 0 <= d < nx and mask[c, d] and ids[c, d] == 0:
                            ids[c, d] = n
                            stack.append((c, d))
    return ids


def nearest(axis, value):
    k = int(round((value - axis[0]) / (axis[1] - axis[0])))
    return k if 0 <= k < len(axis) else None


def flow_directions(flow_paths, x, y):
    """Inflow and outflow directions [rad] at (x, y), averaged over the flows; None where none."""
    inflow, outflow = np.zeros(2), np.zeros(2)
    for path in flow_paths:
        with checks.open_nc("flow of the sweep", path, ["flow"]) as ds:
            i, j = nearest(checks.finite_values(ds, "x", "length"), x), nearest(checks.finite_values(ds, "y", "length"), y)
            if i is None or j is None:
                continue
            h, u, v = flow_series(ds, j, i)
        flux = h * (u * u + v * v)
        peak = int(np.argmax(h))
        k = int(np.argmax(flux[:peak + 1]))
        if not flux[k] > 0:
            continue
        into = np.array([u[k], v[k]]) / math.hypot(u[k], v[k])
        inflow += into
        # The return flow: after the deepest water, moving against the inflow.
        back = [f for f in range(peak + 1, len(h)) if u[f] * into[0] + v[f] * into[1] < 0 and flux[f] > 0]
        if back:
            f = back[int(np.argmax(flux[back]))]
            outflow += np.array([u[f], v[f]]) / math.hypot(u[f], v[f])
    return tuple(math.atan2(p[1], p[0]) if np.hypot(*p) > EPS else None for p in (inflow, outflow))


def flow_series(ds, j, i):
    """Depth and velocity at cell (j, i) over the frames, in m and m/s: finite, the depth not
    negative (a NaN or negative depth would move the directions silently)."""
    out = []
    for name, kind in (("h", "length"), ("u", "speed"), ("v", "speed")):
        var = checks.variable(ds, name)
        var.set_auto_mask(False)
        values = np.asarray(var[:, j, i], dtype=float)
        bad = ~np.isfinite(values) | (np.abs(values) >= 9.96e36) | (values < 0 if name == "h" else np.abs(values) > 1000.0)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            checks.fail(ds.filepath(), f"variable '{name}'", f"frame {k}, cell (i {i}, j {j}): {values[k]!r} is not "
                        + ("a depth (NaN, a fill value or negative)" if name == "h" else "a speed in m/s"))
        out.append(values * checks.unit_factor(ds, name, kind))
    return out


def flooded_on(scene, flow_paths):
    """Cells of the scene grid flooded in some flow (nearest flow cell; outside every window: dry)."""
    wet = np.zeros(scene["z"].shape, dtype=bool)
    for path in flow_paths:
        with checks.open_nc("flow of the sweep", path, ["flow"]) as ds:
            fx, fy = checks.finite_values(ds, "x", "length"), checks.finite_values(ds, "y", "length")
            checks.same_crs(path, checks.crs_of(ds, "h"), scene["path"], scene["crs_name"])
            flooded = checks.flags(ds, "flooded")
            if flooded is None:  # never written: where some frame's depth passed the flood depth
                depth = float(getattr(ds["flooded"], "flood_depth", 0.0))
                flooded = (checks.finite_values(ds, "h", "length", checks.MAX_DEPTH, lo=0) > depth).any(axis=0)
            flooded = flooded != 0
        i0 = nearest(scene["x"], fx[0])
        j0 = nearest(scene["y"], fy[0])
        wet[j0:j0 + len(fy), i0:i0 + len(fx)] |= flooded
    return wet


def wedge(scene, origins, direction, half_angle):
    """Cells whose centre lies within half_angle of `direction` from some origin."""
    if direction is None:
        return np.zeros(scene["z"].shape, dtype=bool)
    X, Y = np.meshgrid(scene["x"], scene["y"])
    inside = np.zeros(X.shape, dtype=bool)
    c, s, cos_half = math.cos(direction), math.sin(direction), math.cos(half_angle)
    for ox, oy in origins:
        dx, dy = X - ox, Y - oy
        r = np.hypot(dx, dy)
        inside |= (dx * c + dy * s) >= cos_half * r - EPS
    return inside


def passed_cells(scene, xs, ys):
    """Flat indices of the scene cells a track passes (quarter-cell steps along each segment)."""
    x0, y0 = scene["x"][0], scene["y"][0]
    d = scene["x"][1] - scene["x"][0]
    nx, ny = len(scene["x"]), len(scene["y"])
    ok = np.isfinite(xs) & np.isfinite(ys)
    xs, ys = xs[ok], ys[ok]
    if len(xs) == 0:
        return np.zeros(0, dtype=int)
    pts_x, pts_y = [xs[:1]], [ys[:1]]
    for k in range(1, len(xs)):
        n = max(1, int(math.ceil(math.hypot(xs[k] - xs[k - 1], ys[k] - ys[k - 1]) / (0.25 * d))))
        f = np.arange(1, n + 1) / n
        pts_x.append(xs[k - 1] + f * (xs[k] - xs[k - 1]))
        pts_y.append(ys[k - 1] + f * (ys[k] - ys[k - 1]))
    px, py = np.concatenate(pts_x), np.concatenate(pts_y)
    i = np.clip(np.rint((px - x0) / d).astype(int), 0, nx - 1)
    j = np.clip(np.rint((py - y0) / d).astype(int), 0, ny - 1)
    return np.unique(j * nx + i)


def source_of(sweep):
    """Per body index: its source (the GIS feature, else the body's own name)."""
    return [src if src else name for name, src in zip(sweep["bodies"], sweep["body_source"])]


def analyse(sweep, scene, wet, source, half_angle):
    sources = source_of(sweep)
    body_index = {name: k for k, name in enumerate(sweep["bodies"])}
    members = [m for m, b in enumerate(sweep["body"]) if sources[body_index[b]] == source]
    origins = sorted({(sweep["x"][m, 0], sweep["y"][m, 0]) for m in members})
    cx, cy = np.mean([o[0] for o in origins]), np.mean([o[1] for o in origins])
    flows = sorted({sweep["flow"][m] for m in members})
    inflow, outflow = flow_directions(flows, cx, cy)
    region_in = wedge(scene, origins, inflow, half_angle) & wet
    region_out = wedge(scene, origins, outflow, half_angle) & wet
    region = region_in | region_out
    passes = np.zeros(region.size, dtype=int)
    final_inside = 0
    for m in members:
        cells = passed_cells(scene, sweep["x"][m], sweep["y"][m])
        passes[cells] += 1
        xs, ys = sweep["x"][m], sweep["y"][m]
        last = np.flatnonzero(np.isfinite(xs))
        if len(last):
            k = passed_cells(scene, xs[last[-1]:last[-1] + 1], ys[last[-1]:last[-1] + 1])
            final_inside += int(region.ravel()[k[0]])
    total = max(1, passes.sum())
    share = {name: passes[r.ravel()].sum() / total for name, r in
             (("inflow", region_in), ("outflow", region_out), ("region", region))}
    # Buildings: in the region where a region cell touches a flooded cell; hit by the source's members.
    bid = scene["building_id"]
    beside_wet = np.zeros_like(wet)
    beside_wet[1:, :] |= wet[:-1, :]
    beside_wet[:-1, :] |= wet[1:, :]
    beside_wet[:, 1:] |= wet[:, :-1]
    beside_wet[:, :-1] |= wet[:, 1:]
    wedges = wedge(scene, origins, inflow, half_angle) | wedge(scene, origins, outflow, half_angle)
    in_region_cells = wedges & beside_wet & (bid > 0)
    buildings_in_region = set(np.unique(bid[in_region_cells]).tolist()) - {0}
    member_set = set(members)
    hits = {}
    for t, b in zip(sweep["impact_trajectory"], sweep["impact_building"]):
        if int(t) in member_set:
            hits.setdefault(int(b), set()).add(int(t))
    hit_probability = {b: len(ms) / len(members) for b, ms in hits.items()}
    return {
        "source": source, "origins": len(origins), "members": len(members), "origin": (cx, cy),
        "inflow": inflow, "outflow": outflow, "share": share,
        "final_inside": final_inside / max(1, len(members)),
        "region_in": region_in, "region_out": region_out, "passes": passes.reshape(region.shape) / max(1, len(members)),
        "buildings_in_region": buildings_in_region, "hit_probability": hit_probability,
        "hit_outside": sorted(set(hit_probability) - buildings_in_region),
        "never_reached": sorted(buildings_in_region - set(hit_probability)),
    }


def degrees(a):
    return "" if a is None else f"{math.degrees(a):.2f}"


def write_tables(results, out):
    with open(os.path.join(out, "hazard_regions.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["source", "origins", "members", "origin_x_m", "origin_y_m", "inflow_direction_deg",
                    "outflow_direction_deg", "passage_share_inflow_wedge", "passage_share_outflow_wedge",
                    "passage_share_region", "members_ending_inside", "buildings_in_region", "buildings_hit",
                    "buildings_hit_outside_region", "buildings_in_region_never_hit"])
        for r in results:
            w.writerow([r["source"], r["origins"], r["members"], f"{r['origin'][0]:.3f}", f"{r['origin'][1]:.3f}",
                        degrees(r["inflow"]), degrees(r["outflow"]), f"{r['share']['inflow']:.4f}",
                        f"{r['share']['outflow']:.4f}", f"{r['share']['region']:.4f}", f"{r['final_inside']:.4f}",
                        len(r["buildings_in_region"]), len(r["hit_probability"]),
                        " ".join(map(str, r["hit_outside"])), " ".join(map(str, r["never_reached"]))])
    with open(os.path.join(out, "hazard_buildings.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["source", "building_id", "in_region", "hit_probability"])
        for r in results:
            for b in sorted(r["buildings_in_region"] | set(r["hit_probability"])):
                w.writerow([r["source"], b, int(b in r["buildings_in_region"]), f"{r['hit_probability'].get(b, 0.0):.4f}"])


def write_masks(results, scene, path):
    """The regions and passage shares on the scene grid, per source (for GIS tools and tests)."""
    with netCDF4.Dataset(path + ".part", "w") as ds:
        ds.Conventions = "CF-1.11"
        ds.title = "flotsam: the design standard's debris hazard regions beside the simulated passages"
        ds.createDimension("source", len(results))
        ds.createDimension("y", len(scene["y"]))
        ds.createDimension("x", len(scene["x"]))
        # Georeferenced as the scene: projection coordinates and its grid mapping (GDAL, QGIS).
        for axis, direction in (("x", "east"), ("y", "north")):
            v = ds.createVariable(axis, "f8", (axis,))
            v[:] = scene[axis]
            v.units = "m"
            v.standard_name = f"projection_{axis}_coordinate"
            v.axis = axis.upper()
            v.long_name = f"{axis} of cell centre ({direction})"
        if scene["crs"]:
            crs = ds.createVariable("crs", "i4")
            crs.setncatts(scene["crs"])
        name = ds.createVariable("source", str, ("source",))
        name.long_name = "debris source (GIS feature or body) of each region"
        for k, r in enumerate(results):
            name[k] = r["source"]

        def gridded(var, kind, long_name):
            v = ds.createVariable(var, kind, ("source", "y", "x"), zlib=True)
            v.long_name = long_name
            v.coordinates = "source"
            if scene["crs"]:
                v.grid_mapping = "crs"
            return v
        for var, key, long_name in (("region_inflow", "region_in", "within the half-angle of the inflow, flooded"),
                                    ("region_outflow", "region_out", "within the half-angle of the outflow, flooded")):
            v = gridded(var, "i1", long_name)
            v.flag_values = np.array([0, 1], dtype=np.int8)
            v.flag_meanings = "outside inside"
            for k, r in enumerate(results):
                v[k] = r[key].astype(np.int8)
        v = gridded("pass_share", "f4", "share of the source's members whose centre passes the cell")
        v.units = "1"
        for k, r in enumerate(results):
            v[k] = r["passes"].astype(np.float32)
    os.replace(path + ".part", path)


def chart(r, scene, path):
    """The source's passage shares over the ground, the regions' outlines, the buildings that differ."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    x, y, z = scene["x"], scene["y"], scene["z"]
    d = x[1] - x[0]
    ext = [x[0] - d / 2, x[-1] + d / 2, y[0] - d / 2, y[-1] + d / 2]
    shown = (r["passes"] > 0) | r["region_in"] | r["region_out"]
    jj, ii = np.nonzero(shown)
    margin = 10 * d
    box = [x[ii.min()] - margin, x[ii.max()] + margin, y[jj.min()] - margin, y[jj.max()] + margin]
    aspect = (box[3] - box[2]) / max(box[1] - box[0], d)
    fig, ax = plt.subplots(figsize=(10, min(9, max(4.5, 10 * aspect + 1.5))))
    from matplotlib.colors import ListedColormap
    ax.imshow((z >= 0).astype(int), origin="lower", extent=ext, cmap=ListedColormap(["#d6e6f2", "#e4e1da"]), vmin=0, vmax=1,
              aspect="equal")
    bid = scene["building_id"]
    ax.imshow(np.ma.masked_where(bid == 0, bid > 0), origin="lower", extent=ext, cmap=ListedColormap(["#6b6b6b"]),
              aspect="equal")
    p = np.ma.masked_where(r["passes"] <= 0, r["passes"])
    im = ax.imshow(p, origin="lower", extent=ext, cmap="viridis", vmin=0, vmax=max(0.05, float(p.max())), aspect="equal")
    fig.colorbar(im, ax=ax, orientation="horizontal", fraction=0.05, pad=0.12,
                 label="share of the source's members whose centre passes the cell")
    for region, colour, label in ((r["region_in"], "tab:red", "inflow"), (r["region_out"], "tab:orange", "return flow")):
        if region.any():
            ax.contour(x, y, region.astype(float), levels=[0.5], colors=colour, linewidths=1.4)
            ax.plot([], [], color=colour, label=f"±22.5° of the {label}, flooded")
    for ids, marker, colour, label in ((r["hit_outside"], "x", "tab:red", "building hit outside the region"),
                                       (r["never_reached"], "o", "tab:orange", "building in the region, never hit")):
        for b in ids:
            bj, bi = np.nonzero(bid == b)
            ax.plot(x[bi].mean(), y[bj].mean(), marker, mfc="none", color=colour, ms=5)
        ax.plot([], [], marker, mfc="none", color=colour, label=f"{label} ({len(ids)})")
    ax.plot(*r["origin"], "*", color="white", mec="black", ms=13, label="source")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    ax.set_xlim(box[0], box[1])
    ax.set_ylim(box[2], box[3])
    s = r["share"]
    ax.set_title(f"{r['source']}: {r['members']} members; passages in the region {100 * s['region']:.1f} % "
                 f"(inflow {100 * s['inflow']:.1f} %, return flow {100 * s['outflow']:.1f} %)", fontsize=10)
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sweep", required=True)
    ap.add_argument("--scene", help="the sweep's scene (default: the one it names)")
    ap.add_argument("--out", required=True, help="folder for the tables and charts")
    ap.add_argument("--half-angle", type=float, default=22.5, help="[degree] (ASCE 7-16, Naito et al. 2014)")
    ap.add_argument("--sources", help="comma-separated sources (default: all)")
    ap.add_argument("--no-charts", action="store_true")
    a = ap.parse_args(argv)
    if not 0 < a.half_angle < 90:
        sys.exit(f"hazard_region: --half-angle {a.half_angle}: must lie in (0, 90) degrees")
    sweep = read_sweep(a.sweep)
    scene_path = a.scene or sweep["scene_file"]
    if not scene_path:
        sys.exit(f"hazard_region: {a.sweep}: names no scene; give --scene")
    scene = read_scene(scene_path)
    scene["path"] = scene_path
    # Files given together: one CRS, the tracks on the scene's grid, each flow there to read.
    checks.same_crs(a.sweep, sweep["crs"], scene_path, scene["crs_name"])
    checks.within(a.sweep, sweep["x"], sweep["y"], scene["x"], scene["y"], f"the grid of the scene {scene_path}")
    for f in sweep["flows"]:
        checks.input_file(f"{a.sweep}: flow", f)
    names = sorted(set(source_of(sweep)), key=source_of(sweep).index)
    if a.sources:
        wanted = a.sources.split(",")
        for w in wanted:
            if w not in names:
                sys.exit(f"hazard_region: --sources {w}: not a source of {a.sweep} ({', '.join(names)})")
        names = wanted
    # No output over an input (compared by inode), before anything is written.
    written = ["hazard_regions.csv", "hazard_buildings.csv", "hazard_regions.nc"]
    if not a.no_charts:
        written += ["hazard_" + n.replace("/", "_") + ".png" for n in names]
    checks.outputs_not_inputs([("--out", os.path.join(a.out, w)) for w in written],
                              [("--sweep", a.sweep), ("--scene", scene_path)] + [("flow", f) for f in sweep["flows"]])
    os.makedirs(a.out, exist_ok=True)
    wet = flooded_on(scene, sweep["flows"])
    results = [analyse(sweep, scene, wet, s, math.radians(a.half_angle)) for s in names]
    write_tables(results, a.out)
    write_masks(results, scene, os.path.join(a.out, "hazard_regions.nc"))
    if not a.no_charts:
        for r in results:
            chart(r, scene, os.path.join(a.out, "hazard_" + r["source"].replace("/", "_") + ".png"))
    for r in results:
        print(f"{r['source']}: inflow {degrees(r['inflow'])} deg, outflow {degrees(r['outflow'])} deg; passages in the "
              f"region {100 * r['share']['region']:.1f} %, members ending inside {100 * r['final_inside']:.1f} %; "
              f"{len(r['hit_outside'])} buildings hit outside it, {len(r['never_reached'])} in it never hit")


if __name__ == "__main__":
    checks.run("hazard_region", main)
