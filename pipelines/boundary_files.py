#!/usr/bin/python3
"""Boundary values from other models, in the CF layout `flotsam hydro --<side>-forcing` reads.

Usage:
  python3 -m pipelines.boundary_files geoclaw-gauges --out OUT.nc (--geographic | --crs EPSG:n) gauge00001.txt ...
  python3 -m pipelines.boundary_files to-lonlat IN.nc OUT.nc

geoclaw-gauges: GeoClaw's ASCII gauge output (`_output/gauge*.txt`, GeoClaw 5.x): a header
  line `# gauge_id= N location=( X Y ) ...`, comment lines, then rows of
  `level t h hu hv eta`. Each gauge becomes a station: eta is the level, hu/h and hv/h the
  velocity (0 where h <= 1e-6 m), on the times of the first gauge (every gauge must have
  them). With --geographic the locations are longitude and latitude (GeoClaw's
  coordinate_system = 2) and the velocity is eastward and northward; with --crs they are
  projected coordinates of that CRS and the velocity is along its x and y.
to-lonlat: a flotsam --boundary-output file (projected) rewritten in longitude and
  latitude (WGS 84) with eastward and northward velocities, as a regional model in
  geographic coordinates would give it; used to check that path (docs/gis.md).

Both write a CF-1.11 NetCDF-4 timeSeries file: time(time) [s], station coordinates,
eta(time, station) [m] (standard_name sea_surface_height_above_mean_sea_level), the two
velocity components [m s-1] and the depth [m] (0 where the source is dry).
"""
import argparse
import math
import re
import sys

import netCDF4
import numpy as np
from osgeo import osr


def write_stations(path, time, x, y, eta, u, v, depth, geographic, crs_wkt=None, history=""):
    """time [s] (n), x, y (stations), eta, u, v, depth (n, stations)."""
    with netCDF4.Dataset(path, "w") as f:
        f.Conventions = "CF-1.11"
        f.featureType = "timeSeries"
        f.history = history
        f.createDimension("time", len(time))
        f.createDimension("station", len(x))
        t = f.createVariable("time", "f8", ("time",))
        t.standard_name, t.units, t.axis = "time", "seconds since 2000-01-01 00:00:00", "T"
        t[:] = time
        names = ("lon", "lat") if geographic else ("x", "y")
        std = ("longitude", "latitude") if geographic else ("projection_x_coordinate", "projection_y_coordinate")
        unit = ("degrees_east", "degrees_north") if geographic else ("m", "m")
        for name, s, un, values in zip(names, std, unit, (x, y)):
            c = f.createVariable(name, "f8", ("station",))
            c.standard_name, c.units = s, un
            c[:] = values
        if crs_wkt:
            crs = f.createVariable("crs", "i4")
            crs.crs_wkt = crs_wkt
        coords = f"time {names[1]} {names[0]}"
        vel = ("eastward_sea_water_velocity", "northward_sea_water_velocity") if geographic else (
            "sea_water_x_velocity", "sea_water_y_velocity")
        for name, s, un, values in (("eta", "sea_surface_height_above_mean_sea_level", "m", eta),
                                    ("u", vel[0], "m s-1", u), ("v", vel[1], "m s-1", v),
                                    ("depth", "sea_floor_depth_below_sea_surface", "m", depth)):
            var = f.createVariable(name, "f8", ("time", "station"))
            var.standard_name, var.units, var.coordinates = s, un, coords
            if crs_wkt:
                var.grid_mapping = "crs"
            var[:] = values


def read_geoclaw_gauge(path):
    """(x, y, time, eta, u, v, h) of one GeoClaw ASCII gauge file."""
    with open(path) as f:
        head = f.readline()
    m = re.search(r"location=\(\s*(\S+)\s+(\S+)\s*\)", head)
    if not m:
        sys.exit(f"{path}: line 1: no 'location=( X Y )' (a GeoClaw gauge file starts '# gauge_id= N location=( X Y ) ...')")
    rows = np.loadtxt(path, comments="#", ndmin=2)
    if rows.shape[1] < 6:
        sys.exit(f"{path}: {rows.shape[1]} columns; a GeoClaw gauge row is 'level t h hu hv eta'")
    t, h, hu, hv, eta = rows[:, 1], rows[:, 2], rows[:, 3], rows[:, 4], rows[:, 5]
    wet = h > 1e-6
    u = np.where(wet, hu / np.where(wet, h, 1.0), 0.0)
    v = np.where(wet, hv / np.where(wet, h, 1.0), 0.0)
    return float(m.group(1)), float(m.group(2)), t, eta, u, v, h


def geoclaw_gauges(args):
    gauges = [read_geoclaw_gauge(p) for p in args.gauges]
    time = gauges[0][2]
    for p, g in zip(args.gauges, gauges):
        if len(g[2]) != len(time) or np.any(np.abs(g[2] - time) > 1e-9 * max(1.0, abs(time[-1]))):
            sys.exit(f"{p}: its times differ from {args.gauges[0]}'s: write every gauge at the same times "
                     "(GeoClaw's gauge output interval)")
    wkt = None
    if args.crs:
        s = osr.SpatialReference()
        if s.SetFromUserInput(args.crs) != 0:
            sys.exit(f"--crs {args.crs}: not a CRS GDAL knows")
        wkt = s.ExportToWkt()
    stack = lambda k: np.stack([g[k] for g in gauges], axis=1)
    write_stations(args.out, time, [g[0] for g in gauges], [g[1] for g in gauges], stack(3), stack(4), stack(5), stack(6),
                   args.geographic, wkt, "pipelines.boundary_files geoclaw-gauges " + " ".join(args.gauges))


def to_lonlat(args):
    with netCDF4.Dataset(args.input) as f:
        if "crs" not in f.variables or not getattr(f.variables["crs"], "crs_wkt", ""):
            sys.exit(f"{args.input}: no crs variable with crs_wkt: the file is in local metres, with no place on Earth")
        src = osr.SpatialReference()
        src.ImportFromWkt(f.variables["crs"].crs_wkt)
        time = f.variables["time"][:].filled()
        x, y = f.variables["x"][:].filled(), f.variables["y"][:].filled()
        eta, u, v, depth = (f.variables[n][:].filled() for n in ("eta", "u", "v", "depth"))
    wgs = osr.SpatialReference()
    wgs.ImportFromEPSG(4326)
    for s in (src, wgs):
        s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    to_geo = osr.CoordinateTransformation(src, wgs)
    to_map = osr.CoordinateTransformation(wgs, src)
    lon, lat = np.empty(len(x)), np.empty(len(x))
    east, north = np.empty((len(x), 2)), np.empty((len(x), 2))
    for k in range(len(x)):
        lon[k], lat[k], _ = to_geo.TransformPoint(float(x[k]), float(y[k]))
        # True east and north at the station as unit vectors on the map grid.
        for out, (dlon, dlat) in ((east, (1e-6, 0.0)), (north, (0.0, 1e-6))):
            px, py, _ = to_map.TransformPoint(lon[k] + dlon, lat[k] + dlat)
            d = np.array([px - x[k], py - y[k]])
            out[k] = d / math.hypot(*d)
    ue = u * east[:, 0] + v * east[:, 1]
    vn = u * north[:, 0] + v * north[:, 1]
    write_stations(args.output, time, lon, lat, eta, ue, vn, depth, True, None, "pipelines.boundary_files to-lonlat " + args.input)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    g = sub.add_parser("geoclaw-gauges")
    g.add_argument("--out", required=True)
    where = g.add_mutually_exclusive_group(required=True)
    where.add_argument("--geographic", action="store_true")
    where.add_argument("--crs")
    g.add_argument("gauges", nargs="+")
    t = sub.add_parser("to-lonlat")
    t.add_argument("input")
    t.add_argument("output")
    args = p.parse_args(argv[1:])
    (geoclaw_gauges if args.command == "geoclaw-gauges" else to_lonlat)(args)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
