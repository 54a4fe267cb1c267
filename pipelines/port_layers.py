#!/usr/bin/python3
"""The full-scale demo's debris sources: a container yard and a car park on Kainan's north
quay, as a port would hand them over (a GeoPackage in its own CRS).

    python3 -m pipelines.port_layers --out runs/kainan-full/port_layers.gpkg [--crs EPSG:6674]

Two polygon layers, drawn on the open quay east of the FD start (the x250 scene's 10 m
grid: land clear of buildings over x 518290..518600, y 3779525..3779580 in UTM 53N):

- container_yard: 210 x 52 m, 24 empty 40 ft containers (type container_40ft) stacked
  along the quay (heading 0, east), spread at the widest gap that holds them;
- car_park: 80 x 47 m, 24 cars (type car) parked north-south (bearing 0).

They are written in JGD2011 / Japan Plane Rectangular CS VI (EPSG:6674, Wakayama's
survey grid) unless --crs says otherwise, so `flotsam debris --sources` and sweep
[[sources]] carry them into the scene's UTM. Attributes as docs/gis.md, "Debris sources".
"""
import argparse
import os

from osgeo import ogr, osr

UTM = 32653
LAYERS = [
    # name, (x0, y0, x1, y1) in UTM 53N [m], attributes
    ("container_yard", (518380.0, 3779528.0, 518590.0, 3779580.0), {"type": "container_40ft", "count": 24, "heading": 0.0}),
    ("car_park", (518290.0, 3779528.0, 518370.0, 3779575.0), {"type": "car", "count": 24, "bearing": 0.0}),
]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--crs", default="EPSG:6674", help="CRS of the written layers")
    a = ap.parse_args(argv)
    ogr.UseExceptions()
    src, dst = osr.SpatialReference(), osr.SpatialReference()
    src.ImportFromEPSG(UTM)
    dst.SetFromUserInput(a.crs)
    for s in (src, dst):
        s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    to_dst = osr.CoordinateTransformation(src, dst)
    tmp = a.out + ".part.gpkg"  # GDAL picks the driver by the extension
    if os.path.exists(tmp):
        os.remove(tmp)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(tmp)
    for name, (x0, y0, x1, y1), attributes in LAYERS:
        layer = ds.CreateLayer(name, dst, ogr.wkbPolygon)
        for key, value in attributes.items():
            kind = ogr.OFTString if isinstance(value, str) else ogr.OFTInteger if isinstance(value, int) else ogr.OFTReal
            layer.CreateField(ogr.FieldDefn(key, kind))
        ring = ogr.Geometry(ogr.wkbLinearRing)
        for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)):
            ring.AddPoint_2D(*to_dst.TransformPoint(x, y)[:2])
        polygon = ogr.Geometry(ogr.wkbPolygon)
        polygon.AddGeometry(ring)
        feature = ogr.Feature(layer.GetLayerDefn())
        for key, value in attributes.items():
            feature.SetField(key, value)
        feature.SetGeometry(polygon)
        layer.CreateFeature(feature)
    ds = None
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
