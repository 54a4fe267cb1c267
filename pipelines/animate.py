#!/usr/bin/python3
"""A debris run as a moving picture: the stored flow and the bodies moving through it.

    python3 -m pipelines.animate --flow FLOW.nc --trajectories TRACKS.nc [--scene SCENE.nc]
                                 --out RUN.mp4 [--gif RUN.gif] [--fps 24] [--tail 60]
                                 [--box x0,x1,y0,y1 | --whole] [--width 1280]

Each frame is one stored frame of the flow file (no fluid is re-run): the water depth over
the ground (land in greys, buildings dark, from --scene or else the flow's bed), and the
bodies of the trajectory file (flotsam debris, or the members of a sweep that replayed
this flow) as boxes of their length and width turned to their heading, each trailing its
track over the last --tail seconds, fading. Bodies are coloured by source (the GIS
feature they came from, else the body). The view is the tracks' extent with a margin
(--box: given; --whole: the flow's window).

Writes an H.264 MP4 (Debian's ffmpeg) and, with --gif, a GIF of it (--gif-fps frames a
second, --gif-width pixels wide, its own palette). Files appear only when complete
(<name>.part first). A progress bar goes to stderr; the last line gives the cost: seconds
of wall (and of processor, ffmpeg included) per second of video. Uses numpy, netCDF4,
matplotlib and ffmpeg.
"""
import argparse
import math
import os
import resource
import shutil
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import netCDF4  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
from matplotlib.colors import ListedColormap, PowerNorm, to_rgba  # noqa: E402

SOURCE_COLOURS = ["#d62728", "#ff7f0e", "#9467bd", "#2ca02c", "#8c564b", "#e377c2", "#17becf", "#bcbd22"]


def strings(ds, name):
    v = ds.variables[name]
    v.set_auto_chartostring(True)
    return [str(s) for s in np.atleast_1d(v[:])]


def crs_label(ds):
    """'WGS 84 / UTM zone 53N' from the grid mapping, or local metres."""
    if "crs" not in ds.variables:
        return "local metres"
    wkt = getattr(ds["crs"], "crs_wkt", "")
    return wkt.split('"')[1] if wkt.count('"') >= 2 else "projected CRS"


def round_up(v):
    """The smallest of 1, 2, 5 x 10^k at or above v."""
    if not v > 0:
        return 1.0
    d = 10 ** math.floor(math.log10(v))
    return next(m * d for m in (1, 2, 5, 10) if m * d >= v * (1 - 1e-12))


class Flow:
    def __init__(self, path):
        self.path = path
        self.ds = netCDF4.Dataset(path)
        self.ds.set_auto_mask(False)
        self.x = np.asarray(self.ds["x"][:], dtype=float)
        self.y = np.asarray(self.ds["y"][:], dtype=float)
        self.z = np.asarray(self.ds["z"][:], dtype=float)
        self.time = np.asarray(self.ds["time"][:], dtype=float)
        self.flood_depth = float(getattr(self.ds["flooded"], "flood_depth", 0.0)) if "flooded" in self.ds.variables else 0.0
        self.max_depth = np.asarray(self.ds["max_depth"][:], dtype=float)
        self.crs = crs_label(self.ds)
        d = self.x[1] - self.x[0]
        self.extent = [self.x[0] - d / 2, self.x[-1] + d / 2, self.y[0] - d / 2, self.y[-1] + d / 2]

    def depth(self, k):
        return np.asarray(self.ds["h"][k], dtype=float)


def read_bodies(path, flow_path):
    """Tracks of the bodies that went through `flow_path`: x, y, yaw [rad] over time, sizes, sources."""
    with netCDF4.Dataset(path) as ds:
        ds.set_auto_mask(False)
        n = len(ds.dimensions["trajectory"])
        keep = np.ones(n, dtype=bool)
        if "flow" in ds.variables:  # a sweep: its members that replayed this flow
            flows = strings(ds, "flow")
            name = os.path.basename(flow_path)
            keep = np.array([os.path.basename(f) == name for f in flows])
            if not keep.any():
                sys.exit(f"animate: {path}: no member replayed a flow named {name} (flows: {', '.join(sorted(set(flows)))})")
        if "body_name" in ds.variables:  # a sweep's body table
            table = dict(zip(strings(ds, "body_name"), strings(ds, "body_source") if "body_source" in ds.variables
                             else strings(ds, "body_name")))
            bodies = strings(ds, "body")
            source = [table.get(b) or b for b in bodies]
        else:
            ids = strings(ds, "trajectory_id")
            source = strings(ds, "source") if "source" in ds.variables else ids
            source = [s or i for s, i in zip(source, ids)]
        t = np.asarray(ds["time"][:], dtype=float)
        take = lambda v: np.asarray(ds[v][:], dtype=float)[keep]  # noqa: E731
        out = {"time": t, "x": take("x"), "y": take("y"), "yaw": np.radians(take("yaw")),
               "length": take("length"), "width": take("width"),
               "source": [s for s, k in zip(source, keep) if k]}
    bad = ~np.isfinite(out["x"]) | (np.abs(out["x"]) > 1e30)
    for v in ("x", "y", "yaw"):
        out[v][bad] = np.nan
    return out


def pose_at(b, t):
    """Positions and headings of every body at time t (linear between samples; NaN before its first)."""
    tt = b["time"]
    k = int(np.clip(np.searchsorted(tt, t, side="right") - 1, 0, len(tt) - 1))
    if k + 1 < len(tt) and tt[k] <= t:
        f = (t - tt[k]) / (tt[k + 1] - tt[k])
        lerp = lambda v: v[:, k] + f * (v[:, k + 1] - v[:, k])  # noqa: E731
        return lerp(b["x"]), lerp(b["y"]), lerp(b["yaw"])
    return b["x"][:, k], b["y"][:, k], b["yaw"][:, k]


def box_corners(x, y, yaw, length, width):
    """(n, 4, 2) corners of boxes centred at (x, y), long axis at yaw."""
    c, s = np.cos(yaw), np.sin(yaw)
    half = np.stack([np.array([1, 1, -1, -1]) * 0.5, np.array([1, -1, -1, 1]) * 0.5], axis=1)  # (4, 2)
    dx = half[None, :, 0] * length[:, None]
    dy = half[None, :, 1] * width[:, None]
    return np.stack([x[:, None] + c[:, None] * dx - s[:, None] * dy, y[:, None] + s[:, None] * dx + c[:, None] * dy], axis=2)


def view_box(flow, b, margin=0.25):
    xs, ys = b["x"][np.isfinite(b["x"])], b["y"][np.isfinite(b["y"])]
    if len(xs) == 0:
        return flow.extent
    x0, x1, y0, y1 = xs.min(), xs.max(), ys.min(), ys.max()
    size = max(x1 - x0, y1 - y0, 20 * float(np.nanmax(b["length"])))
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    half_w = max(x1 - x0, 0.6 * size) * (0.5 + margin)
    half_h = max(y1 - y0, 0.35 * size) * (0.5 + margin)
    e = flow.extent
    return [max(e[0], cx - half_w), min(e[1], cx + half_w), max(e[2], cy - half_h), min(e[3], cy + half_h)]


class Progress:
    def __init__(self, total, what):
        self.total, self.what, self.start, self.shown = total, what, time.monotonic(), -1
        self.tty = sys.stderr.isatty()

    def update(self, k):
        pct = int(100 * k / max(1, self.total))
        if not self.tty and pct // 10 == self.shown // 10 and k != self.total:
            return
        if self.tty and pct == self.shown and k != self.total:
            return
        self.shown = pct
        bar = "#" * (pct * 30 // 100) + "." * (30 - pct * 30 // 100)
        elapsed = time.monotonic() - self.start
        line = f"{self.what}: [{bar}] {pct:3d} % frame {k}/{self.total} {elapsed:6.1f} s"
        sys.stderr.write(("\r" + line) if self.tty else line + "\n")
        if self.tty and k == self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def processor_seconds():
    """Processor time of this process and its finished children (ffmpeg) [s]."""
    me, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + children.ru_utime + children.ru_stime


def render(flow, bodies, scene_path, out, gif, fps, tail, box, width_px, gif_width, gif_fps):
    if not shutil.which("ffmpeg"):
        sys.exit("animate: ffmpeg is missing (Debian: apt-get install ffmpeg; make -f Makefile.pipeline setup)")
    dx = flow.x[1] - flow.x[0]
    aspect = (box[3] - box[2]) / (box[1] - box[0])
    dpi = 100
    fig_w = width_px / dpi
    # Margins [inch]: left for the y labels, right for the colour bar, below for the x label.
    left, right, bottom, top = 1.0, 1.2, 0.65, 0.35
    ax_w = fig_w - left - right
    ax_h = min(ax_w * aspect, 9.0)
    fig_h = round((ax_h + bottom + top) * dpi / 2) * 2 / dpi  # an even number of pixels (H.264's 4:2:0)
    fig = plt.figure(figsize=(fig_w, fig_h), dpi=dpi)
    ax = fig.add_axes([left / fig_w, bottom / fig_h, ax_w / fig_w, ax_h / fig_h])
    cax = fig.add_axes([(left + ax_w + 0.2) / fig_w, bottom / fig_h, 0.15 / fig_w, ax_h / fig_h])

    # The ground: sea floor and land in greys by height, buildings dark.
    z = flow.z
    relief = max(1e-9, float(np.nanpercentile(np.abs(z), 95)))
    ax.imshow(z, origin="lower", extent=flow.extent, cmap="Greys", vmin=-1.5 * relief, vmax=2.5 * relief,
              aspect="equal", interpolation="nearest")
    building = None
    if scene_path:
        with netCDF4.Dataset(scene_path) as s:
            if "building" in s.variables:
                sx, sy = np.asarray(s["x"][:]), np.asarray(s["y"][:])
                i0 = int(round((flow.x[0] - sx[0]) / (sx[1] - sx[0])))
                j0 = int(round((flow.y[0] - sy[0]) / (sy[1] - sy[0])))
                if abs(sx[1] - sx[0] - dx) < 1e-9 * dx and i0 >= 0 and j0 >= 0:
                    building = np.asarray(s["building"][j0:j0 + len(flow.y), i0:i0 + len(flow.x)]) != 0
    if building is not None:
        ax.imshow(np.ma.masked_where(~building, building), origin="lower", extent=flow.extent,
                  cmap=ListedColormap(["#4d4d4d"]), aspect="equal", interpolation="nearest")

    # The water: depth in blues, dry cells clear; one scale for the whole run.
    wet_max = flow.max_depth[(flow.max_depth > flow.flood_depth) & (z > 0)]
    top = round_up(float(np.percentile(wet_max, 99)) if len(wet_max) else float(flow.max_depth.max()))
    water = ax.imshow(np.ma.masked_all(z.shape), origin="lower", extent=flow.extent, cmap="Blues",
                      norm=PowerNorm(0.5, vmin=0, vmax=top), aspect="equal", interpolation="nearest", alpha=0.85)
    fig.colorbar(water, cax=cax, label="water depth [m]")

    sources = list(dict.fromkeys(bodies["source"]))
    colour_of = {s: SOURCE_COLOURS[k % len(SOURCE_COLOURS)] for k, s in enumerate(sources)}
    face = np.array([to_rgba(colour_of[s]) for s in bodies["source"]])
    boxes = PolyCollection([], facecolors=face, edgecolors="black", linewidths=0.4, zorder=4)
    ax.add_collection(boxes)
    trails = LineCollection([], linewidths=0.9, zorder=3)
    ax.add_collection(trails)
    for s in sources[:8]:
        ax.plot([], [], "s", color=colour_of[s], mec="black", mew=0.4, label=s)
    if sources:
        ax.legend(loc="upper left", fontsize=7, framealpha=0.8, ncol=min(4, len(sources)))
    label = ax.text(0.99, 0.02, "", transform=ax.transAxes, ha="right", va="bottom", fontsize=10,
                    bbox=dict(facecolor="white", alpha=0.8, edgecolor="none"))
    ax.set_xlim(box[0], box[1])
    ax.set_ylim(box[2], box[3])
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.set_xlabel(f"x [m], {flow.crs}")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{os.path.basename(flow.path)}: water depth and {len(bodies['source'])} bodies", fontsize=10)

    fig.canvas.draw()
    w, h = fig.canvas.get_width_height()
    part = out + ".part.mp4"
    cmd = ["ffmpeg", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgba", "-s", f"{w}x{h}", "-r", str(fps),
           "-i", "-", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2:color=white", "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "23",
           "-preset", "medium", "-movflags", "+faststart", "-fflags", "+bitexact", "-flags:v", "+bitexact",
           "-map_metadata", "-1", part]
    enc = subprocess.Popen(cmd, stdin=subprocess.PIPE)
    start, cpu_start = time.monotonic(), processor_seconds()
    frames = range(len(flow.time))
    bar = Progress(len(frames), "animate " + os.path.basename(out))
    lengths, widths = bodies["length"], bodies["width"]
    tt = bodies["time"]
    try:
        for n, k in enumerate(frames):
            t = flow.time[k]
            h = flow.depth(k)
            water.set_data(np.ma.masked_where(h <= flow.flood_depth, h))
            x, y, yaw = pose_at(bodies, t)
            ok = np.isfinite(x)
            boxes.set_verts(box_corners(x[ok], y[ok], yaw[ok], lengths[ok], widths[ok]))
            boxes.set_facecolor(face[ok])
            # Trails: each body's samples in (t - tail, t], older segments fainter.
            sel = np.flatnonzero((tt > t - tail) & (tt <= t))
            segs, cols = np.zeros((0, 2, 2)), np.zeros((0, 4))
            if len(sel) >= 2:
                px, py = bodies["x"][:, sel], bodies["y"][:, sel]
                head = np.stack([px[:, :-1], py[:, :-1]], axis=-1)
                tip = np.stack([px[:, 1:], py[:, 1:]], axis=-1)
                keep_seg = np.isfinite(head).all(-1) & np.isfinite(tip).all(-1)
                segs = np.stack([head, tip], axis=2)[keep_seg]
                fade = np.clip(1.0 - (t - tt[sel[:-1]]) / tail, 0.0, 1.0) * 0.9
                cols = np.repeat(face[:, None, :], len(sel) - 1, axis=1).copy()
                cols[..., 3] = fade[None, :]
                cols = cols[keep_seg]
            trails.set_segments(segs)
            trails.set_color(cols if len(cols) else "none")
            label.set_text(f"t = {t:.0f} s")
            fig.canvas.draw()
            enc.stdin.write(fig.canvas.buffer_rgba())
            bar.update(n + 1)
        enc.stdin.close()
        if enc.wait() != 0:
            raise RuntimeError("ffmpeg failed writing " + part)
    except BaseException:
        enc.kill()
        if os.path.exists(part):
            os.remove(part)
        raise
    plt.close(fig)
    wall = time.monotonic() - start
    os.replace(part, out)
    seconds = len(frames) / fps
    if gif:
        gpart = gif + ".part.gif"
        gif_start = time.monotonic()
        vf = (f"fps={gif_fps:g},scale={gif_width}:-2:flags=lanczos,split[a][b];[a]palettegen=max_colors=128:stats_mode=diff[p];"
              f"[b][p]paletteuse=dither=bayer:bayer_scale=4:diff_mode=rectangle")
        r = subprocess.run(["ffmpeg", "-y", "-loglevel", "error", "-i", out, "-vf", vf, "-fflags", "+bitexact", gpart])
        if r.returncode != 0:
            if os.path.exists(gpart):
                os.remove(gpart)
            sys.exit(f"animate: ffmpeg could not write {gif}")
        os.replace(gpart, gif)
        wall += time.monotonic() - gif_start
    cpu = processor_seconds() - cpu_start
    print(f"animate: {out}{' and ' + gif if gif else ''}: {len(frames)} frames, {seconds:.1f} s of video at {fps} fps, "
          f"{len(bodies['source'])} bodies; {wall:.1f} s of wall ({cpu:.1f} s of processor): {wall / seconds:.2f} s of wall "
          f"({cpu / seconds:.2f} s of processor) per second of video")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--flow", required=True, help="the flow file (flotsam hydro)")
    ap.add_argument("--trajectories", required=True, help="a debris or sweep file whose bodies went through --flow")
    ap.add_argument("--scene", help="the scene, for the buildings")
    ap.add_argument("--out", required=True, help="the MP4")
    ap.add_argument("--gif", help="also a GIF")
    ap.add_argument("--fps", type=int, default=24)
    ap.add_argument("--tail", type=float, help="[s] track shown behind each body (default: 60 frames)")
    ap.add_argument("--box", help="x0,x1,y0,y1 [m]: the view")
    ap.add_argument("--whole", action="store_true", help="the view: the flow's whole window")
    ap.add_argument("--width", type=int, default=1280, help="[pixel] of the video")
    ap.add_argument("--gif-width", type=int, default=480, help="[pixel] of the GIF")
    ap.add_argument("--gif-fps", type=float, default=6, help="frames per second of the GIF (every fourth frame at 24)")
    a = ap.parse_args(argv)
    if a.fps < 1:
        sys.exit(f"animate: --fps {a.fps}: must be at least 1")
    for p in (a.flow, a.trajectories, a.scene):
        if p and not os.path.exists(p):
            sys.exit(f"animate: {p}: no such file")
    flow = Flow(a.flow)
    bodies = read_bodies(a.trajectories, a.flow)
    if a.box:
        try:
            box = [float(v) for v in a.box.split(",")]
        except ValueError:
            box = []
        if len(box) != 4 or not (box[0] < box[1] and box[2] < box[3]):
            sys.exit(f"animate: --box {a.box}: give x0,x1,y0,y1 with x0 < x1 and y0 < y1")
    else:
        box = flow.extent if a.whole else view_box(flow, bodies)
    tail = a.tail if a.tail else 60 * (flow.time[1] - flow.time[0] if len(flow.time) > 1 else 1.0)
    for path in (a.out, a.gif):
        if path and os.path.dirname(path):
            os.makedirs(os.path.dirname(path), exist_ok=True)
    render(flow, bodies, a.scene, a.out, a.gif, a.fps, tail, box, a.width, a.gif_width, a.gif_fps)


if __name__ == "__main__":
    main()
