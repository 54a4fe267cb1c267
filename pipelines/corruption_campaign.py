"""Byte mutations of every kind of file flotsam reads, each copy run through the command
that reads it, counted by outcome (docs/reliability.md, "Bad input and what it gets").

    /usr/bin/python3 -m pipelines.corruption_campaign --flotsam build/flotsam --out runs/corrupt \
        [--kinds scene flow sweep stats trajectory forcing checkpoint sources] [--count 120] [--seed 7] [--mode values]

It first makes one small file of each kind (a 0.16 m scene, its 4 s flow, a sweep of two
bodies and two variants, its statistics, a trajectory file, the run's boundary outline
along the scene's edges (which forces its west side), a checkpoint of an interrupted run, a GeoPackage of debris sources),
runs each command on it for the reference result, then on --count copies with 1 to 4
random bytes changed, or (--mode values) one number set to NaN, infinity, a fill value,
an absurd or a negative number where another program could have written it (seeded: a
campaign repeats exactly):

    scene       hydro --scene COPY (0.2 s)          stats       export --stats COPY --scene S
    flow        debris --flow COPY --at ...          trajectory  export --trajectories COPY
    sweep       stats --sweep COPY --scene S         forcing     hydro --scene S --west-forcing COPY
    checkpoint  hydro ... --restart (COPY as the checkpoint)
    sources     debris --flow F --scene S --sources COPY

Outcomes: "named error" (exit 1 naming the file), "same result" (exit 0, the reference's
values), "other valid result" (exit 0, other values, every changed input value finite and
in range), "silent acceptance" (exit 0 with a changed input value that is not finite or
out of range, or an output value that is not: NaN, a negative depth, an arrival outside
the run), "crash" (a signal or another exit status), "hang" (--timeout). Copies of the last three are kept under OUT/kept/.
"""
import argparse
import hashlib
import json
import os
import random
import shutil
import subprocess
import sys

KINDS = ["scene", "flow", "sweep", "stats", "trajectory", "forcing", "checkpoint", "sources"]
WHOLE = " --nest-ratio 1 --output-window -100,100,-100,100"

# Physical ranges of the values an input holds (what a reader must refuse outside them);
# any other number must be finite and below 1e30 in magnitude.
RANGES = {"h": (0, 11000), "max_depth": (0, 11000), "depth": (0, 11000), "u": (-1000, 1000), "v": (-1000, 1000),
          "max_speed": (0, 1000), "z": (-11000, 9000), "eta": (-11000, 11000), "manning_n": (0, 1),
          "pass_probability": (0, 1), "pass_probability_all": (0, 1), "building_hit_probability": (0, 1),
          "building_hit_probability_all": (0, 1), "max_debris_speed": (0, 1000), "max_debris_speed_all": (0, 1000),
          "heading": (-360, 360), "bearing": (-360, 360), "count": (1, 1e6), "mass": (0, 1e9), "length": (0, 1e4),
          "width": (0, 1e4)}
COORDINATE = 1e8  # [m] x, y and positions


def run(cmd, timeout, cwd=None):
    try:
        r = subprocess.run(cmd, capture_output=True, timeout=timeout, cwd=cwd)
        return r.returncode, (r.stdout + r.stderr).decode(errors="replace")
    except subprocess.TimeoutExpired:
        return None, ""


def must(cmd):
    rc, out = run(cmd, 600)
    if rc != 0:
        sys.exit(f"corruption_campaign: setting up: {' '.join(cmd)} failed ({rc}):\n{out}")


def make_sources(path):
    """Two points and a yard, in the flume's water (local metres, no CRS)."""
    from osgeo import ogr
    drv = ogr.GetDriverByName("GPKG")
    if os.path.exists(path):
        drv.DeleteDataSource(path)
    ds = drv.CreateDataSource(path)
    layer = ds.CreateLayer("sources", None, ogr.wkbUnknown)
    for name, kind in (("type", ogr.OFTString), ("heading", ogr.OFTReal), ("count", ogr.OFTInteger), ("length", ogr.OFTReal),
                       ("width", ogr.OFTReal), ("height", ogr.OFTReal), ("mass", ogr.OFTReal)):
        layer.CreateField(ogr.FieldDefn(name, kind))
    for wkt, heading, count in (("POINT (0.5 -1.0)", 10.0, None), ("POINT (0.8 -1.3)", 80.0, None),
                                ("POLYGON ((-0.6 -1.6,0.0 -1.6,0.0 -1.2,-0.6 -1.2,-0.6 -1.6))", 0.0, 3)):
        f = ogr.Feature(layer.GetLayerDefn())
        f.SetField("type", "paper_box")
        f.SetField("heading", heading)
        f.SetField("length", 0.12)
        f.SetField("width", 0.05)
        f.SetField("height", 0.04)
        f.SetField("mass", 0.06)
        if count:
            f.SetField("count", count)
        f.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        layer.CreateFeature(f)
    ds = None


def setup(flotsam, base):
    """The small valid files of every kind, and the command of each (COPY and OUT filled in)."""
    os.makedirs(base, exist_ok=True)
    b = lambda n: os.path.join(base, n)
    scene, series, flow = b("scene.nc"), b("bc/wg1_r00.csv"), b("flow.nc")
    must([flotsam, "scene", "generate", "--resolution", "0.16", "--out", scene])
    must([flotsam, "boundary", "generate", "--count", "1", "--duration", "30", "--out-dir", b("bc")])
    hydro = [flotsam, "hydro", "--scene", scene, "--west", "level", "--west-series", series, "--quiet"] + WHOLE.split()
    must(hydro + ["--duration", "4", "--out", flow])
    with open(b("spec.toml"), "w") as f:
        f.write(f'[sweep]\nscene = "{scene}"\n[flows]\npaths = ["{flow}"]\n[[body]]\nstart = "FD"\n[[body]]\nstart = "LD"\n'
                '[variants]\nnames = ["CC+SC", "LC+MC"]\n')
    must([flotsam, "sweep", "--spec", b("spec.toml"), "--quiet", "--out", b("sweep.nc")])
    must([flotsam, "stats", "--sweep", b("sweep.nc"), "--scene", scene, "--out", b("stats.nc")])
    must([flotsam, "debris", "--flow", flow, "--scene", scene, "--start", "FD", "--quiet", "--out", b("traj.nc")])
    # The run's outline along the scene's own edges, which then forces the scene's west side.
    must(hydro + ["--duration", "2", "--boundary-output", b("outline.nc"), "--boundary-box", "-12.36,8.1,-4,-0.01",
                  "--boundary-interval", "0.1", "--out", b("regional.nc")])
    # An interrupted run and its checkpoint.
    ck = hydro + ["--duration", "3", "--output-interval", "0.5", "--checkpoint-interval", "1", "--threads", "1"]
    must(ck + ["--stop-after", "1.5", "--out", b("ck.nc")])
    make_sources(b("sources.gpkg"))
    at = ["--at", "0.5,-1,0"]
    return {
        "scene": (scene, lambda c, o: [flotsam, "hydro", "--scene", c, "--west", "wall", "--duration", "0.2", "--quiet",
                                       "--out", o + ".nc"]),
        "flow": (flow, lambda c, o: [flotsam, "debris", "--flow", c] + at + ["--quiet", "--out", o + ".nc"]),
        "sweep": (b("sweep.nc"), lambda c, o: [flotsam, "stats", "--sweep", c, "--scene", scene, "--out", o + ".nc"]),
        "stats": (b("stats.nc"), lambda c, o: [flotsam, "export", "--stats", c, "--scene", scene, "--out-dir", o]),
        "trajectory": (b("traj.nc"), lambda c, o: [flotsam, "export", "--trajectories", c, "--out-dir", o]),
        "forcing": (b("outline.nc"), lambda c, o: [flotsam, "hydro", "--scene", scene, "--west-forcing", c, "--nest-ratio", "1",
                                                   "--duration", "2", "--quiet", "--out", o + ".nc"]),
        "checkpoint": (b("ck.nc.checkpoint.nc"), lambda c, o: ck + ["--restart", "--out", o + ".nc"]),
        "sources": (b("sources.gpkg"), lambda c, o: [flotsam, "debris", "--flow", flow, "--scene", scene, "--sources", c,
                                                    "--quiet", "--out", o + ".nc"]),
    }, b("ck.nc.part")


# ---- what a run produced, and what a copy changed (read in a child: a corrupted file can
# crash libhdf5 in this process too) ----

def nc_values(path):
    """{variable: list of values} of a NetCDF file (strings as text), masked values as None."""
    import netCDF4
    import numpy as np
    out = {}
    with netCDF4.Dataset(path) as ds:
        for name, v in ds.variables.items():
            v.set_auto_mask(False)
            if v.dtype == "S1":  # character arrays as bytes: a changed byte need not be UTF-8
                v.set_auto_chartostring(False)
                chars = np.atleast_2d(v[:])
                out[name] = [b"".join(row).decode("utf-8", "replace") for row in chars.reshape(-1, chars.shape[-1])]
                continue
            if v.dtype == str or v.dtype.kind in "SU":
                out[name] = [str(s) for s in np.atleast_1d(v[:]).ravel()]
                continue
            a = np.asarray(v[:], dtype=float).ravel()
            fill = getattr(v, "_FillValue", None)
            out[name] = [None if (fill is not None and x == float(fill)) or (abs(x) >= 9.96e36) else x for x in a.tolist()]
    return out


def gis_values(path):
    from osgeo import gdal, ogr
    gdal.UseExceptions()
    if path.endswith(".tif"):
        d = gdal.Open(path)
        return {"band": [float(x) for x in d.GetRasterBand(1).ReadAsArray().ravel()]}
    ds = ogr.Open(path)
    out = {}
    for layer in ds:
        for f in layer:
            g = f.GetGeometryRef()
            out[f"{layer.GetName()}/{f.GetFID()}"] = [g.ExportToWkt() if g else ""] + [f.GetField(k) for k in range(f.GetFieldCount())]
    return out


def values_of(path):
    if path.endswith((".tif", ".gpkg")):
        return gis_values(path)
    if path.endswith(".nc"):
        return nc_values(path)
    return {"bytes": [hashlib.sha256(open(path, "rb").read()).hexdigest()]}  # a style, a project


def bad_value(name, x):
    """Why a number is not one an input may hold ("" when it may)."""
    if isinstance(x, str) or x is None:
        return ""
    if x != x or x in (float("inf"), float("-inf")):
        return f"{name} = {x}"
    lo, hi = RANGES.get(name, (-1e30, 1e30))
    if name in ("x", "y", "x0", "y0") or name.startswith(("point_", "section_")):
        lo, hi = -COORDINATE, COORDINATE
    return "" if lo <= x <= hi else f"{name} = {x:g} outside [{lo:g}, {hi:g}]"


def changed_bad_values(original, copy):
    """The changed values of `copy` that are not finite or out of range (their variables named)."""
    a, b = values_of(original), values_of(copy)
    bad = []
    for name, vb in b.items():
        va = a.get(name)
        field = name.split("/")[0]
        for k, x in enumerate(vb):
            if va is not None and k < len(va) and va[k] == x:
                continue
            if isinstance(x, list):
                continue
            why = bad_value(field if "/" not in name else "value", x)
            if why:
                bad.append(why)
    return bad


def output_digest(out):
    """A hash of the values a run wrote (its .nc, or every file of its folder), and what among
    them is not finite outside a fill, or out of range (depths, speeds, an arrival time
    outside the run)."""
    files = [out + ".nc"] if os.path.exists(out + ".nc") else sorted(
        os.path.join(out, f) for f in os.listdir(out)) if os.path.isdir(out) else []
    h, bad = hashlib.sha256(), []
    for p in files:
        if p.endswith((".part", ".lock", ".aux.xml")):
            continue
        values = values_of(p)
        times = [t for t in values.get("time", []) if isinstance(t, float)]
        for name, vals in sorted(values.items()):
            h.update(json.dumps([os.path.basename(p), name, vals], default=str).encode())
            if p.endswith(".tif"):  # a map's nodata is NaN
                continue
            for x in vals:
                why = bad_value(name, x) if name in RANGES or x != x else ""
                if name == "arrival_time" and isinstance(x, float) and times and not min(times) - 1e-6 <= x <= max(times) + 1e-6:
                    why = f"arrival_time = {x:g} outside the run"
                if why:
                    bad.append(f"{os.path.basename(p)}: {why}")
                    break
    return h.hexdigest(), bad


def child(args):
    """--child digest OUT | --child changed ORIGINAL COPY: prints JSON."""
    if args[0] == "digest":
        print(json.dumps(output_digest(args[1])))
    else:
        print(json.dumps(changed_bad_values(args[1], args[2])))


def in_child(args, timeout=120):
    """The child's answer (its last line of stdout, JSON); None when it failed or crashed."""
    try:
        r = subprocess.run([sys.executable, "-m", "pipelines.corruption_campaign", "--child"] + args, capture_output=True,
                           timeout=timeout, cwd=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    except subprocess.TimeoutExpired:
        return None
    lines = r.stdout.decode(errors="replace").strip().splitlines()
    return json.loads(lines[-1]) if r.returncode == 0 and lines else None


# ---- the campaign ----

def clean(out):
    for p in (out + ".nc", out + ".nc.part", out + ".nc.checkpoint.nc"):
        if os.path.exists(p):
            os.remove(p)
    if os.path.isdir(out):
        shutil.rmtree(out)


SPECIAL = [float("nan"), float("inf"), float("-inf"), 1e30, -1e30, 9.969209968386869e36, -1.0, 1e6, -1e6, 1e12, 0.0]


def edit_values(original, copy, rng):
    """A copy of `original` with one number set to a special value (NaN, infinity, a fill
    value, an absurd or negative number), in a random variable (GeoPackage: a random
    attribute or coordinate of a random feature), as another program could write it."""
    shutil.copy(original, copy)
    value = rng.choice(SPECIAL)
    if copy.endswith(".gpkg"):
        from osgeo import ogr
        ds = ogr.Open(copy, 1)
        layer = ds.GetLayer(0)
        fid = rng.randrange(layer.GetFeatureCount()) + 1
        f = layer.GetFeature(fid)
        fields = [k for k in range(f.GetFieldCount()) if f.GetFieldDefnRef(k).GetType() in (ogr.OFTReal, ogr.OFTInteger)]
        k = rng.randrange(len(fields) + 1)
        if k < len(fields):
            f.SetField(fields[k], value if f.GetFieldDefnRef(fields[k]).GetType() == ogr.OFTReal or value != value
                       else int(max(-2e9, min(2e9, value))) if abs(value) != float("inf") else 2**31 - 1)
        else:
            g = f.GetGeometryRef().Clone()
            ring = g.GetGeometryRef(0) if g.GetGeometryCount() else g
            p = rng.randrange(ring.GetPointCount())
            ring.SetPoint_2D(p, value, ring.GetY(p)) if rng.random() < 0.5 else ring.SetPoint_2D(p, ring.GetX(p), value)
            f.SetGeometry(g)
        layer.SetFeature(f)
        ds = None
        return
    import netCDF4
    import numpy as np
    with netCDF4.Dataset(copy, "a") as ds:
        names = [n for n, v in ds.variables.items() if v.dtype.kind == "f" and v.size > 0]
        v = ds.variables[rng.choice(names)]
        v.set_auto_mask(False)
        index = np.unravel_index(rng.randrange(v.size), v.shape)
        v[index] = value


def campaign(kind, original, command, a, work, ck_part):
    data = open(original, "rb").read()
    rng = random.Random(f"{a.seed}/{kind}" if a.mode == "bytes" else f"{a.seed}/{kind}/values")
    ext = os.path.splitext(original)[1]
    copy, out = os.path.join(work, "copy" + ext), os.path.join(work, "out")

    def one(content):
        clean(out)
        open(copy, "wb").write(content)
        c = copy
        if kind == "checkpoint":  # the interrupted run's .part beside the copy as its checkpoint
            shutil.copy(ck_part, out + ".nc.part")
            shutil.copy(copy, out + ".nc.checkpoint.nc")
        return run(command(c, out), a.timeout, cwd=work)

    rc, text = one(data)
    if rc != 0:
        sys.exit(f"corruption_campaign: {kind}: the unchanged file fails ({rc}):\n{text}")
    reference = in_child(["digest", out])[0]
    counts = dict.fromkeys(["named error", "same result", "other valid result", "silent acceptance", "crash", "hang"], 0)
    notes = []
    for k in range(a.count):
        if a.mode == "values":
            edit_values(original, os.path.join(work, "edited" + ext), rng)
            b = bytearray(open(os.path.join(work, "edited" + ext), "rb").read())
        else:
            b = bytearray(data)
            for _ in range(rng.randint(1, 4)):
                b[rng.randrange(min(len(b), a.bytes))] = rng.randrange(256)
        rc, text = one(bytes(b))
        outcome = None
        if rc is None:
            outcome = "hang"
        elif rc == 1 and "error" in text:
            outcome = "named error"
        elif rc != 0:
            outcome = "crash"
        else:
            got = in_child(["digest", out])
            if got is None or got[1]:
                outcome, why = "silent acceptance", f"output {got[1] if got else '(unreadable)'}"
            elif got[0] == reference:
                outcome = "same result"
            else:
                bad = in_child(["changed", original, copy])
                outcome = "silent acceptance" if bad is None or bad else "other valid result"
                why = "; ".join(bad[:3]) if bad else "the copy cannot be read to compare"
            if outcome == "silent acceptance":
                notes.append(f"{kind} copy {k}: {why}")
        counts[outcome] += 1
        if outcome in ("silent acceptance", "crash", "hang"):
            os.makedirs(os.path.join(a.out, "kept"), exist_ok=True)
            open(os.path.join(a.out, "kept", f"{kind}_{k}{ext}"), "wb").write(b)
            if outcome == "crash":
                notes.append(f"{kind} copy {k}: exit {rc}: {text.strip().splitlines()[-1] if text.strip() else ''}")
    clean(out)
    return counts, notes


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "--child":
        return child(argv[1:])
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--flotsam", default="build/flotsam")
    p.add_argument("--out", default="runs/corrupt")
    p.add_argument("--kinds", nargs="+", choices=KINDS, default=KINDS)
    p.add_argument("--count", type=int, default=120, help="copies of each kind")
    p.add_argument("--seed", type=int, default=7)
    p.add_argument("--bytes", type=int, default=65536, help="change bytes within the first this many")
    p.add_argument("--timeout", type=float, default=60, help="seconds before a run counts as a hang")
    p.add_argument("--mode", choices=["bytes", "values"], default="bytes",
                   help="bytes: 1 to 4 random bytes changed; values: one number set to NaN, infinity, a fill value, "
                        "an absurd or a negative number, as another program could write it")
    a = p.parse_args(argv)
    a.flotsam, a.out = os.path.abspath(a.flotsam), os.path.abspath(a.out)
    files, ck_part = setup(a.flotsam, os.path.join(a.out, "base"))
    rows = []
    for kind in a.kinds:
        work = os.path.join(a.out, "work", kind)
        os.makedirs(work, exist_ok=True)
        original, command = files[kind]
        counts, notes = campaign(kind, original, command, a, work, ck_part)
        rows.append((kind, counts))
        print(f"{kind}: " + ", ".join(f"{v} {k}" for k, v in counts.items()), flush=True)
        for n in notes:
            print("  " + n, flush=True)
    keys = list(rows[0][1]) if rows else []
    what = "1-4 bytes" if a.mode == "bytes" else "one value"
    print(f"\n| kind ({a.count} copies, {what}) | " + " | ".join(keys) + " |")
    print("| --- " * (len(keys) + 1) + "|")
    for kind, counts in rows:
        print(f"| {kind} | " + " | ".join(str(counts[k]) for k in keys) + " |")
    print("| all | " + " | ".join(str(sum(c[k] for _, c in rows)) for k in keys) + " |")


if __name__ == "__main__":
    main()
