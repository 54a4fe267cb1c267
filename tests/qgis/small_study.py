#!/usr/bin/python3
"""A small full study in UTM for the QGIS test, made in seconds: every kind of layer the
GIS export writes, on a beach whose flooded and hit cells are known.

    python3 tests/qgis/small_study.py --flotsam build/flotsam --out runs/qgis-test

A 900 m x 300 m beach at E 518000, N 3779700 in UTM zone 53N (EPSG:32653), 5 m DEM
pixels, the bed rising from -8 m in the west at 3 cm per metre (still water reaches it at
x = 267 m), four building blocks on the land (one beyond the wave's reach); a container
yard and a car as debris sources in the port's survey CRS (EPSG:6674); a 6 m wave from the west for 420 s; a sweep
of the sources (five starts each) through the flow; statistics, the design standard's
hazard regions, and `flotsam export` of all of it with the QGIS project.
Uses python3-gdal and the flotsam tool; writes under --out only.
"""
import argparse
import os
import subprocess
import sys

import numpy as np
from osgeo import gdal, ogr, osr

E0, N0 = 518000.0, 3779700.0  # the south-west corner
WIDTH, HEIGHT, PIXEL = 900.0, 300.0, 5.0
BLOCKS = [  # building footprints (x0, y0, x1, y1) relative to the corner [m], 10 m high
    (330.0, 40.0, 370.0, 110.0),
    (330.0, 170.0, 380.0, 250.0),
    (450.0, 100.0, 500.0, 190.0),
    (760.0, 120.0, 800.0, 180.0),  # on high ground the wave never reaches: never hit
]
YARD = (285.0, 120.0, 315.0, 165.0)  # container yard on the quay, below the wave's reach
CAR = (300.0, 70.0)


def utm():
    s = osr.SpatialReference()
    s.ImportFromEPSG(32653)
    s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    return s


def write_inputs(out):
    gdal.UseExceptions()
    ogr.UseExceptions()
    nx, ny = int(WIDTH / PIXEL), int(HEIGHT / PIXEL)
    x = (np.arange(nx) + 0.5) * PIXEL
    z = np.tile(-8.0 + 0.03 * x, (ny, 1)).astype(np.float32)
    d = gdal.GetDriverByName("GTiff").Create(os.path.join(out, "dem.tif"), nx, ny, 1, gdal.GDT_Float32)
    d.SetGeoTransform([E0, PIXEL, 0, N0 + HEIGHT, 0, -PIXEL])
    d.SetProjection(utm().ExportToWkt())
    d.GetRasterBand(1).WriteArray(z)
    d = None

    def rectangle(x0, y0, x1, y1, to=None):
        ring = ogr.Geometry(ogr.wkbLinearRing)
        for px, py in ((x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)):
            p = (E0 + px, N0 + py)
            if to:
                p = to.TransformPoint(*p)[:2]
            ring.AddPoint_2D(*p)
        poly = ogr.Geometry(ogr.wkbPolygon)
        poly.AddGeometry(ring)
        return poly

    ds = ogr.GetDriverByName("GPKG").CreateDataSource(os.path.join(out, "footprints.gpkg"))
    layer = ds.CreateLayer("footprints", utm(), ogr.wkbPolygon)
    layer.CreateField(ogr.FieldDefn("height", ogr.OFTReal))
    for b in BLOCKS:
        f = ogr.Feature(layer.GetLayerDefn())
        f.SetField("height", 10.0)
        f.SetGeometry(rectangle(*b))
        layer.CreateFeature(f)
    ds = None

    survey = osr.SpatialReference()
    survey.ImportFromEPSG(6674)
    survey.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    to_survey = osr.CoordinateTransformation(utm(), survey)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(os.path.join(out, "port_layers.gpkg"))
    yard = ds.CreateLayer("container_yard", survey, ogr.wkbPolygon)
    for name, kind in (("type", ogr.OFTString), ("count", ogr.OFTInteger), ("heading", ogr.OFTReal)):
        yard.CreateField(ogr.FieldDefn(name, kind))
    f = ogr.Feature(yard.GetLayerDefn())
    f.SetField("type", "container_20ft")
    f.SetField("count", 4)
    f.SetField("heading", 90.0)
    f.SetGeometry(rectangle(*YARD, to=to_survey))
    yard.CreateFeature(f)
    car = ds.CreateLayer("cars", survey, ogr.wkbPoint)
    car.CreateField(ogr.FieldDefn("type", ogr.OFTString))
    f = ogr.Feature(car.GetLayerDefn())
    f.SetField("type", "car")
    p = ogr.Geometry(ogr.wkbPoint)
    p.AddPoint_2D(*to_survey.TransformPoint(E0 + CAR[0], N0 + CAR[1])[:2])
    f.SetGeometry(p)
    car.CreateFeature(f)
    ds = None

    with open(os.path.join(out, "features.toml"), "w") as f:
        f.write("[[manning]]\nn = 0.025\n\n[hydro]\nmax-dt = 0.5\ndry-depth = 1e-4\narrival-depth = 0.3\n"
                "output-interval = 10\ngauge-interval = 1\n")
    with open(os.path.join(out, "wave.csv"), "w") as f:
        f.write("time,eta\n0,0\n60,6.0\n240,6.0\n420,0\n")
    with open(os.path.join(out, "sweep.toml"), "w") as f:
        f.write(f'[sweep]\nscene = "{out}/scene.nc"\noutput-interval = 10\n\n[flows]\npaths = ["{out}/flow_r00.nc"]\n\n'
                f'[[sources]]\nfile = "{out}/port_layers.gpkg"\n\n[variants]\nnames = ["LC+MC"]\n\n'
                "[perturbation]\ncount = 4\nposition-std = 2.0\nheading-std = 10.0\nseed = 1\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--flotsam", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    out = a.out
    os.makedirs(out, exist_ok=True)
    write_inputs(out)

    def run(*cmd):
        print("+ " + " ".join(cmd), flush=True)
        r = subprocess.run(cmd)
        if r.returncode != 0:
            sys.exit(f"small_study: failed ({r.returncode}): {' '.join(cmd)}")

    f = a.flotsam
    run(f, "scene", "import", "--dem", f"{out}/dem.tif", "--buildings", f"{out}/footprints.gpkg", "--building-height-field",
        "height", "--features", f"{out}/features.toml", "--resolution", "10", "--out", f"{out}/scene.nc")
    run(f, "hydro", "--scene", f"{out}/scene.nc", "--west", "level", "--west-series", f"{out}/wave.csv", "--duration", "420",
        "--label", "qgis test", "--out", f"{out}/flow_r00.nc")
    run(f, "sweep", "--spec", f"{out}/sweep.toml", "--quiet", "--out", f"{out}/sweep.nc")
    run(f, "stats", "--sweep", f"{out}/sweep.nc", "--scene", f"{out}/scene.nc", "--out", f"{out}/stats.nc")
    run(sys.executable, "-m", "pipelines.hazard_region", "--sweep", f"{out}/sweep.nc", "--scene", f"{out}/scene.nc",
        "--out", f"{out}/hazard", "--no-charts")
    run(f, "export", "--stats", f"{out}/stats.nc", "--scene", f"{out}/scene.nc", "--flow", f"{out}/flow_r00.nc",
        "--trajectories", f"{out}/sweep.nc", "--sources", f"{out}/port_layers.gpkg", "--hazard-regions",
        f"{out}/hazard/hazard_regions.nc", "--out-dir", f"{out}/gis")


if __name__ == "__main__":
    main()
