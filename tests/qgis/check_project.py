#!/usr/bin/python3
"""Opens a flotsam export's QGIS project in a real QGIS (headless) and checks what a
planner would see.

    QT_QPA_PLATFORM=offscreen python3 tests/qgis/check_project.py gis/project.qgz \\
        --crs EPSG:32653 --png-dir DIR [--prefix NAME]

Checks, for every layer of the project: it loads (valid), it is in the project's CRS
(which must be --crs), and it carries its style (a colour ramp with units, a graduated,
categorised or labelled renderer, a mesh with depth colours and velocity arrows on the
temporal controller, never QGIS's default grey or single random colour). Each file also
opened on its own (as a planner drags it in) gets the same style: a GeoTIFF its .qml,
a GeoPackage layer its default style in layer_styles.

Then renders PNGs (DIR/NAME_*.png: the project as it opens, the inundation, the debris,
the flow at mid-run, and close-ups) and checks pixels at known cells, read from the data
with GDAL: the deepest onshore flooded cell is drawn in the inundation ramp's blue, a
never-flooded cell is left clear, the most-hit building in its hit-probability class's
colour and a building never hit in grey, the cell most tracks pass in the probability
classes' colour, and the flow mesh at the wave's peak blue where the water is.
Prints the layer table (layer, loads, CRS, style) and exits 1 if any check failed.
Needs Debian's qgis and python3-qgis (make -f Makefile.pipeline test-qgis installs them).
"""
import argparse
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import numpy as np  # noqa: E402
from osgeo import gdal, ogr  # noqa: E402
from qgis.core import (QgsApplication, QgsCoordinateReferenceSystem, QgsDateTimeRange, QgsMapRendererSequentialJob,  # noqa: E402
                       QgsMapSettings, QgsMeshDatasetIndex, QgsMeshLayer, QgsPointXY, QgsProject, QgsRasterLayer, QgsRectangle,
                       QgsRenderContext, QgsVectorLayer)
from qgis.PyQt.QtCore import QSize  # noqa: E402
from qgis.PyQt.QtGui import QColor  # noqa: E402

FAILURES = []


def check(ok, what):
    if not ok:
        FAILURES.append(what)
    return ok


def style_of(layer):
    """A short description of the layer's style and whether it is one flotsam wrote."""
    if isinstance(layer, QgsRasterLayer):
        r = layer.renderer()
        if r is None or r.type() != "singlebandpseudocolor":
            return f"{r.type() if r else 'none'} (default)", False
        items = r.shader().rasterShaderFunction().colorRampItemList()
        kind = "classes" if r.shader().rasterShaderFunction().colorRampType() == 1 else "ramp"
        units = any(any(u in i.label for u in (" m", "%", " s", "m/s")) for i in items)
        return f"{kind} {items[0].label} .. {items[-1].label}", len(items) >= 2 and units
    if isinstance(layer, QgsVectorLayer):
        r = layer.renderer()
        kind = r.type() if r else "none"
        detail = {"categorizedSymbol": lambda: f"{len(r.categories())} categories by {r.classAttribute()}",
                  "graduatedSymbol": lambda: f"{len(r.ranges())} classes by {r.classAttribute()}",
                  "singleSymbol": lambda: "one symbol"}.get(kind, lambda: kind)()
        labels = layer.labelsEnabled()
        ok = kind in ("categorizedSymbol", "graduatedSymbol") or (kind == "singleSymbol" and labels)
        return detail + (", labelled" if labels else ""), ok
    if isinstance(layer, QgsMeshLayer):
        s = layer.rendererSettings()
        scalar, vector = s.activeScalarDatasetGroup(), s.activeVectorDatasetGroup()
        meta = lambda g: layer.datasetGroupMetadata(QgsMeshDatasetIndex(g))  # noqa: E731
        ok = scalar >= 0 and vector >= 0 and meta(scalar).name().startswith("water depth") and meta(vector).isVector()
        steps = layer.datasetCount(QgsMeshDatasetIndex(scalar)) if scalar >= 0 else 0
        temporal = layer.temporalProperties().isActive()
        ok = ok and temporal and steps > 1
        name = lambda g: meta(g).name() if g >= 0 else "none"  # noqa: E731
        return f"{name(scalar)} + arrows of {name(vector)}, {steps} times{', temporal' if temporal else ''}", ok
    return "?", False


def same_style_alone(layer):
    """The file opened on its own gets the same renderer (its .qml or layer_styles default)."""
    src = layer.source()
    if isinstance(layer, QgsRasterLayer):
        alone = QgsRasterLayer(src, "alone")
        return alone.isValid() and alone.renderer() is not None and alone.renderer().type() == layer.renderer().type()
    if isinstance(layer, QgsVectorLayer):
        alone = QgsVectorLayer(src, "alone", "ogr")
        return alone.isValid() and alone.renderer() is not None and alone.renderer().type() == layer.renderer().type()
    return True  # a mesh: its style lives in the project


def render(project, layers, extent, path, width=1400, temporal=None):
    s = QgsMapSettings()
    s.setDestinationCrs(project.crs())
    s.setLayers(layers)
    s.setBackgroundColor(QColor(255, 255, 255))
    height = max(200, int(round(width * extent.height() / extent.width())))
    s.setOutputSize(QSize(width, height))
    s.setExtent(extent)
    s.setOutputDpi(96)
    if temporal is not None:
        s.setIsTemporal(True)
        s.setTemporalRange(temporal)
    job = QgsMapRendererSequentialJob(s)
    job.start()
    job.waitForFinished()
    image = job.renderedImage()
    image.save(path, "PNG")
    return image, s


def pixel(image, settings, x, y):
    p = settings.mapToPixel().transform(QgsPointXY(x, y))
    c = image.pixelColor(int(p.x()), int(p.y()))
    return c.red(), c.green(), c.blue()


def over_white(layer, rgb):
    """The colour a raster layer draws over a white background, with its opacity."""
    o = layer.renderer().opacity()
    return tuple(int(round(o * c + (1 - o) * 255)) for c in rgb)


def near(a, b, tol=12):
    return all(abs(int(u) - int(v)) <= tol for u, v in zip(a, b))


def raster_values(path):
    d = gdal.Open(path)
    gt = d.GetGeoTransform()
    v = d.GetRasterBand(1).ReadAsArray().astype(float)
    return v, gt


def cell_centre(gt, row, col):
    return gt[0] + (col + 0.5) * gt[1], gt[3] + (row + 0.5) * gt[5]


def away_from_edges(mask, margin=2):
    """Cells of mask whose neighbours within `margin` cells are in mask too (no edge blending)."""
    m = mask.copy()
    for _ in range(margin):
        inner = m.copy()
        inner[1:, :] &= m[:-1, :]
        inner[:-1, :] &= m[1:, :]
        inner[:, 1:] &= m[:, :-1]
        inner[:, :-1] &= m[:, 1:]
        m = inner
    return m


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("project")
    ap.add_argument("--crs", required=True, help="the scene's CRS, e.g. EPSG:32653")
    ap.add_argument("--png-dir", required=True)
    ap.add_argument("--prefix", default="qgis")
    a = ap.parse_args(argv)
    gdal.UseExceptions()
    app = QgsApplication([], False)
    app.initQgis()
    project = QgsProject.instance()
    if not project.read(a.project):
        sys.exit(f"check_project: {a.project}: QGIS cannot read it: {project.error()}")
    check(project.crs().authid() == a.crs, f"project CRS {project.crs().authid()} is not {a.crs}")
    crs = QgsCoordinateReferenceSystem(a.crs)
    os.makedirs(a.png_dir, exist_ok=True)

    root = project.layerTreeRoot()
    rows, by_file = [], {}
    for node in root.findLayers():
        layer = node.layer()
        group = node.parent().name()
        if layer is None:
            rows.append((node.name(), group, "no", "-", "-"))
            check(False, f"{node.name()}: not loaded")
            continue
        valid = layer.isValid()
        style, styled = style_of(layer) if valid else ("-", False)
        alone = same_style_alone(layer) if valid else False
        layer_crs = layer.crs().authid()
        rows.append((layer.name(), group, "yes" if valid else "NO", layer_crs or "none",
                     style + ("" if alone else " [file alone: other style]")))
        check(valid, f"{layer.name()}: not valid")
        check(layer.crs() == crs, f"{layer.name()}: CRS {layer_crs} is not {a.crs}")
        check(styled, f"{layer.name()}: not styled ({style})")
        check(alone, f"{layer.name()}: opened on its own, the file does not carry the project's style")
        key = os.path.basename(layer.source().split("|")[0])
        by_file.setdefault(key, []).append(layer)

    widths = [max(len(r[k]) for r in rows + [("layer", "group", "loads", "CRS", "style")]) for k in range(5)]
    line = lambda r: "| " + " | ".join(v.ljust(w) for v, w in zip(r, widths)) + " |"  # noqa: E731
    print(line(("layer", "group", "loads", "CRS", "style")))
    print("|" + "|".join("-" * (w + 2) for w in widths) + "|")
    for r in rows:
        print(line(r))

    folder = os.path.dirname(os.path.abspath(a.project))
    view = project.viewSettings().defaultViewExtent()
    extent = QgsRectangle(view) if not view.isEmpty() else root.layerOrder()[0].extent()
    visible = [n.layer() for n in root.findLayers() if n.isVisible() and n.layer() is not None]
    render(project, visible, extent, os.path.join(a.png_dir, f"{a.prefix}_overview.png"))
    print(f"check_project: {a.prefix}_overview.png: the project as it opens ({len(visible)} layers shown)")

    def one(name):
        return by_file.get(name, [None])[0]

    # Flooding: the deepest onshore cell (clear of every edge) is blue, in the inundation ramp's colour.
    onshore, sea = one("inundation_depth.tif"), one("max_depth.tif")
    if onshore and sea:
        depth, gt = raster_values(os.path.join(folder, "inundation_depth.tif"))
        allwet, _ = raster_values(os.path.join(folder, "max_depth.tif"))
        inner = away_from_edges(np.isfinite(depth))
        check(inner.any(), "inundation_depth.tif: no flooded onshore cell away from the edges")
        if inner.any():
            r, c = np.unravel_index(np.nanargmax(np.where(inner, depth, -np.inf)), depth.shape)
            x, y = cell_centre(gt, r, c)
            span = 40 * abs(gt[1])
            box = QgsRectangle(x - span, y - span / 2, x + span, y + span / 2)
            image, s = render(project, [onshore, sea], box, os.path.join(a.png_dir, f"{a.prefix}_flood.png"), width=800)
            got = pixel(image, s, x, y)
            colour = onshore.renderer().shader().rasterShaderFunction().shade(float(depth[r, c]))
            expected = over_white(onshore, colour[1:4]) if colour[0] else None
            blue = got[2] > got[0] + 30 and got[2] >= got[1]
            check(blue and expected is not None and near(got, expected),
                  f"flood: the deepest onshore cell ({x:.1f}, {y:.1f}, {depth[r, c]:.2f} m) is {got}, not the ramp's {expected}")
            print(f"check_project: {a.prefix}_flood.png: the deepest onshore cell ({x:.1f}, {y:.1f}), {depth[r, c]:.2f} m, "
                  f"drawn {got} (ramp {expected}){'' if blue else ' NOT BLUE'}")
        render(project, [onshore, sea], extent, os.path.join(a.png_dir, f"{a.prefix}_inundation.png"))
        print(f"check_project: {a.prefix}_inundation.png: the inundation depth onshore over the sea's largest depth")
        dry = away_from_edges(~np.isfinite(allwet), 3)
        if dry.any():
            rr, cc = np.argwhere(dry)[len(np.argwhere(dry)) // 2]
            x, y = cell_centre(gt, rr, cc)
            span = 40 * abs(gt[1])
            image, s = render(project, [onshore, sea], QgsRectangle(x - span, y - span / 2, x + span, y + span / 2),
                              os.path.join(a.png_dir, f"{a.prefix}_dry.png"), width=400)
            got = pixel(image, s, x, y)
            check(got == (255, 255, 255), f"dry: a never-flooded cell ({x:.1f}, {y:.1f}) is drawn {got}, not left clear")
            print(f"check_project: a never-flooded cell ({x:.1f}, {y:.1f}) is left clear: {got}")
            os.remove(os.path.join(a.png_dir, f"{a.prefix}_dry.png"))

    # Buildings: the most-hit one in its class colour (warm), one never hit in grey.
    buildings = one("buildings.gpkg")
    if buildings:
        feats = list(buildings.getFeatures())
        hit = max(feats, key=lambda f: f["hit_probability"])
        never = [f for f in feats if not f["hit_probability"]]
        check(hit["hit_probability"] > 0, "buildings: none is hit")
        g = ogr.CreateGeometryFromWkt(hit.geometry().asWkt())
        inside = g.PointOnSurface()
        bb = g.GetEnvelope()
        span = max(bb[1] - bb[0], bb[3] - bb[2]) * 1.5 + 20
        cx, cy = inside.GetX(), inside.GetY()
        labels = buildings.labelsEnabled()
        buildings.setLabelsEnabled(False)  # the label sits where the pixel is read
        image, s = render(project, [buildings], QgsRectangle(cx - span, cy - span, cx + span, cy + span),
                          os.path.join(a.png_dir, f"{a.prefix}_buildings.png"), width=600)
        ctx = QgsRenderContext.fromMapSettings(s)
        buildings.renderer().startRender(ctx, buildings.fields())
        want = buildings.renderer().symbolForFeature(hit, ctx).color()
        grey = buildings.renderer().symbolForFeature(never[0], ctx).color() if never else None
        buildings.renderer().stopRender(ctx)
        got = pixel(image, s, cx, cy)
        expected = (want.red(), want.green(), want.blue())
        check(near(got, expected) and got[0] > got[2], f"buildings: the most-hit building is drawn {got}, not its class colour {expected}")
        print(f"check_project: {a.prefix}_buildings.png: building {hit['building_id']} (hit by "
              f"{100 * hit['hit_probability']:.0f} % of the tracks) drawn {got}, its class colour {expected}")
        if never and grey is not None:
            g = ogr.CreateGeometryFromWkt(never[0].geometry().asWkt())
            p = g.PointOnSurface()
            image, s = render(project, [buildings], QgsRectangle(p.GetX() - span, p.GetY() - span, p.GetX() + span, p.GetY() + span),
                              os.path.join(a.png_dir, f"{a.prefix}_never.png"), width=600)
            got = pixel(image, s, p.GetX(), p.GetY())
            check(near(got, (grey.red(), grey.green(), grey.blue())) and max(got) - min(got) < 12,
                  f"buildings: building {never[0]['building_id']}, never hit, is drawn {got}, not grey")
            print(f"check_project: building {never[0]['building_id']}, never hit, drawn grey {got}")
            os.remove(os.path.join(a.png_dir, f"{a.prefix}_never.png"))
        buildings.setLabelsEnabled(labels)

    # Debris: the cell most tracks pass, in the probability classes; with the tracks and sources.
    passing = one("pass_probability_all.tif")
    if passing:
        prob, gt = raster_values(os.path.join(folder, "pass_probability_all.tif"))
        r, c = np.unravel_index(np.nanargmax(np.where(np.isfinite(prob), prob, -1)), prob.shape)
        x, y = cell_centre(gt, r, c)
        layers = [l for l in (one("sources.gpkg"), passing) if l is not None]
        span = 30 * abs(gt[1])
        image, s = render(project, [passing], QgsRectangle(x - span, y - span / 2, x + span, y + span / 2),
                          os.path.join(a.png_dir, f"{a.prefix}_pass.png"), width=600)
        colour = passing.renderer().shader().rasterShaderFunction().shade(float(prob[r, c]))
        expected = over_white(passing, colour[1:4]) if colour[0] else None
        got = pixel(image, s, x, y)
        check(expected is not None and near(got, expected), f"debris: the most-passed cell is drawn {got}, not its class {expected}")
        print(f"check_project: the cell passed by {100 * prob[r, c]:.0f} % of the tracks drawn {got} (class {expected})")
        os.remove(os.path.join(a.png_dir, f"{a.prefix}_pass.png"))
        tracks = [l for k, ls in by_file.items() if k.endswith("_tracks.gpkg") for l in ls]
        render(project, tracks + layers + ([sea] if sea else []), extent, os.path.join(a.png_dir, f"{a.prefix}_debris.png"))
        print(f"check_project: {a.prefix}_debris.png: tracks, sources and pass probability")

    # The flow in time: at the frame of the deepest water somewhere, wet cells are blue.
    meshes = [l for ls in by_file.values() for l in ls if isinstance(l, QgsMeshLayer)]
    for mesh in meshes[:1]:
        tp = mesh.temporalProperties()
        check(tp.isActive(), f"{mesh.name()}: not time-aware")
        rng = tp.timeExtent()
        group = mesh.rendererSettings().activeScalarDatasetGroup()
        steps = mesh.datasetCount(QgsMeshDatasetIndex(group))
        mid = rng.begin().addSecs(int(rng.begin().secsTo(rng.end()) * 0.5))
        image, s = render(project, [mesh], extent, os.path.join(a.png_dir, f"{a.prefix}_flow_mid.png"),
                          temporal=QgsDateTimeRange(mid, mid.addSecs(1)))
        arr = np.array([[image.pixelColor(i, j).getRgb()[:3] for i in range(0, image.width(), 7)]
                        for j in range(0, image.height(), 7)])
        bluish = ((arr[..., 2] > arr[..., 0] + 30) & (arr[..., 2] > 100)).mean()
        check(bluish > 0.05, f"{mesh.name()}: at {mid.toString('hh:mm:ss')} hardly any water drawn ({100 * bluish:.1f} %)")
        print(f"check_project: {a.prefix}_flow_mid.png: the mesh at {mid.toString('hh:mm:ss')} after the start "
              f"({steps} stored times, {rng.begin().toString('yyyy-MM-dd hh:mm:ss')} to {rng.end().toString('hh:mm:ss')}): "
              f"{100 * bluish:.0f} % of the view water")

    for f in FAILURES:
        print("check_project: FAILED: " + f)
    print(f"check_project: {len(rows)} layers, {len(FAILURES)} failed checks")
    app.exitQgis()
    sys.exit(1 if FAILURES else 0)


if __name__ == "__main__":
    main()
