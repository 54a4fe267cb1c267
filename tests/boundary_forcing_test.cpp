// Another model's boundary values read from CF NetCDF and placed along a scene's side
// (data/boundary_forcing.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <functional>
#include <sstream>

#include "common/error.hpp"
#include "data/boundary_forcing.hpp"
#include "data/gdal_support.hpp"
#include "test_support.hpp"

using namespace flotsam;

namespace {

struct Stations {
    std::vector<double> x, y;                // in the file's coordinates
    std::vector<double> time;                // [s]
    std::function<double(double, std::size_t)> level;  // of time and station
    std::function<double(double, std::size_t)> east;   // velocity components; empty: none
    std::function<double(double, std::size_t)> north;
    bool geographic = false;
    cf::GridMapping crs;  // projected stations' CRS; empty: none
    double level_fill_at = -1.0;  // a time whose first station's level is the fill value
};

std::string write_stations(const std::string& path, const Stations& s) {
    nc::File f = nc::File::create(path);
    const int dt = f.def_dim("time", s.time.size()), ds = f.def_dim("station", s.x.size());
    const int vt = cf::def_time(f, dt);
    const std::string gm = cf::grid_mapping_of(s.crs);
    const int vx = cf::def_var(f, {.name = s.geographic ? "lon" : "x", .dims = {ds}, .units = s.geographic ? "degrees_east" : "m",
                                   .standard_name = s.geographic ? "longitude" : "projection_x_coordinate"});
    const int vy = cf::def_var(f, {.name = s.geographic ? "lat" : "y", .dims = {ds}, .units = s.geographic ? "degrees_north" : "m",
                                   .standard_name = s.geographic ? "latitude" : "projection_y_coordinate"});
    cf::def_crs(f, s.crs);
    const std::string coords = s.geographic ? "time lat lon" : "time y x";
    const int vl = cf::def_var(f, {.name = "zeta", .dims = {dt, ds}, .units = "cm", .standard_name = "sea_surface_height",
                                   .coordinates = coords, .fill = true, .grid_mapping = gm});
    int vu = -1, vv = -1;
    if (s.east) {
        vu = cf::def_var(f, {.name = "ue", .dims = {dt, ds}, .units = "m s-1", .standard_name = "eastward_sea_water_velocity",
                             .coordinates = coords, .grid_mapping = gm});
        vv = cf::def_var(f, {.name = "vn", .dims = {dt, ds}, .units = "m s-1", .standard_name = "northward_sea_water_velocity",
                             .coordinates = coords, .grid_mapping = gm});
    }
    f.enddef();
    f.put(vt, s.time);
    f.put(vx, s.x);
    f.put(vy, s.y);
    std::vector<double> l, u, v;
    for (double t : s.time)
        for (std::size_t p = 0; p < s.x.size(); ++p) {
            l.push_back(t == s.level_fill_at && p == 0 ? cf::fill_value : 100.0 * s.level(t, p));
            if (s.east) {
                u.push_back(s.east(t, p));
                v.push_back(s.north(t, p));
            }
        }
    f.put(vl, l);
    if (s.east) {
        f.put(vu, u);
        f.put(vv, v);
    }
    f.close();
    return path;
}

OGRSpatialReference epsg(int code) {
    OGRSpatialReference s;
    s.importFromEPSG(code);
    s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return s;
}

}  // namespace

// Stations in longitude and latitude (WGS 84) along the west side of a scene in UTM zone
// 53N, 20 m apart, levels in cm: placed at their UTM northings (to 1 mm), the level in
// metres, and the eastward current turned by the meridian convergence at the stations,
// gamma = atan(tan(lambda - 135 deg) sin(phi)) (spherical; the ellipsoid changes it by
// less than 1e-5 rad here): true east is (cos gamma, sin gamma) on the grid east of the
// central meridian.
TEST(BoundaryForcing, StationsInLongitudeLatitudeArePlacedAlongAUtmSide) {
    gdal::init();
    const std::string dir = test::scratch_dir("BoundaryForcingGeo");
    const Grid g{50, 40, 518005.0, 3780005.0, 10.0, 10.0};
    const OGRSpatialReference utm = epsg(32653), wgs = epsg(4326);
    std::unique_ptr<OGRCoordinateTransformation> to_geo(OGRCreateCoordinateTransformation(&utm, &wgs));
    Stations s;
    s.geographic = true;
    for (int k = 0; k <= 20; ++k) {
        double x = 518000.0, y = 3780000.0 + 20.0 * k;
        ASSERT_TRUE(to_geo->Transform(1, &x, &y));
        s.x.push_back(x);
        s.y.push_back(y);
    }
    s.time = {0.0, 10.0, 20.0};
    s.level = [](double t, std::size_t p) { return 0.5 + 0.01 * t + 0.001 * double(p); };
    s.east = [](double, std::size_t) { return 1.0; };
    s.north = [](double, std::size_t) { return 0.0; };
    const std::string path = write_stations(dir + "/geo.nc", s);
    const SideRecord r = data::read_side_forcing(path, "west", g, gdal::grid_mapping(utm));
    ASSERT_EQ(r.along.size(), 21u);
    ASSERT_TRUE(r.has_velocity());
    const double pi = std::acos(-1.0);
    for (std::size_t p = 0; p < 21; ++p) {
        EXPECT_NEAR(r.along[p], 3780000.0 + 20.0 * double(p), 1e-3);
        EXPECT_NEAR(r.level[1 * 21 + p], 0.6 + 0.001 * double(p), 1e-12);
        const double gamma = std::atan(std::tan((s.x[p] - 135.0) * pi / 180.0) * std::sin(s.y[p] * pi / 180.0));
        EXPECT_NEAR(std::atan2(r.v[p], r.u[p]), gamma, 1e-5) << p;
        EXPECT_NEAR(std::hypot(r.u[p], r.v[p]), 1.0, 1e-9);
    }
    EXPECT_GT(std::atan2(r.v[0], r.u[0]), 0.0015);  // the test can see a turn: 0.11 deg here
}

// A gridded level linear in x, y and t, in local metres like the scene, on a grid five
// times coarser than the scene's: read at the side's edge points exactly (bilinear).
TEST(BoundaryForcing, GriddedFieldsAreReadAtTheSideBilinearly) {
    const std::string dir = test::scratch_dir("BoundaryForcingGrid");
    const std::string path = dir + "/grid.nc";
    {
        nc::File f = nc::File::create(path);
        const int dt = f.def_dim("time", 3), dy = f.def_dim("y", 12), dx = f.def_dim("x", 12);
        const int vt = cf::def_time(f, dt);
        const cf::XYAxes axes = cf::def_xy(f, dx, dy, "cell centre");
        const int vl = cf::def_var(f, {.name = "eta", .dims = {dt, dy, dx}, .units = "m",
                                       .standard_name = "sea_surface_height_above_mean_sea_level"});
        f.enddef();
        f.put(vt, std::vector<double>{0.0, 1.0, 3.0});
        std::vector<double> xs, ys, l;
        for (int i = 0; i < 12; ++i) xs.push_back(-1.0 + 0.5 * i);
        for (int j = 0; j < 12; ++j) ys.push_back(-1.0 + 0.5 * j);
        for (double t : {0.0, 1.0, 3.0})
            for (double y : ys)
                for (double x : xs) l.push_back(0.1 + 0.01 * x - 0.02 * y + 0.003 * t);
        f.put(axes.x, xs);
        f.put(axes.y, ys);
        f.put(vl, l);
    }
    const Grid g{40, 30, 0.05, 0.05, 0.1, 0.1};  // edges x in [0, 4], y in [0, 3]
    const SideRecord south = data::read_side_forcing(path, "south", g, {});
    ASSERT_EQ(south.along.size(), 40u);
    EXPECT_FALSE(south.has_velocity());
    for (std::size_t p = 0; p < 40; ++p) EXPECT_NEAR(south.level[2 * 40 + p], 0.1 + 0.01 * g.x(int(p)) + 0.009, 1e-14);
    const SideRecord east = data::read_side_forcing(path, "east", g, {});
    for (std::size_t p = 0; p < 30; ++p) EXPECT_NEAR(east.level[p], 0.1 + 0.04 - 0.02 * g.y(int(p)), 1e-14);
}

// What a user gets wrong, each named with the file.
TEST(BoundaryForcing, BadFilesAreNamedErrors) {
    gdal::init();
    const std::string dir = test::scratch_dir("BoundaryForcingBad");
    const Grid g{10, 10, 5.0, 5.0, 10.0, 10.0};  // edges [0, 100] both ways
    const OGRSpatialReference utm = epsg(32653);
    Stations s;
    for (int k = 0; k <= 10; ++k) {
        s.x.push_back(0.0);
        s.y.push_back(10.0 * k);
    }
    s.time = {0.0, 5.0, 10.0};
    s.level = [](double, std::size_t) { return 0.1; };
    auto err = [&](const Stations& st, const std::string& name, const cf::GridMapping& crs) {
        const std::string path = write_stations(dir + "/" + name, st);
        return test::error_of([&] { data::read_side_forcing(path, "west", g, crs); });
    };
    EXPECT_EQ(err(s, "good.nc", {}), "(no error)");
    const std::string no_crs = err(s, "no_crs.nc", gdal::grid_mapping(utm));
    EXPECT_NE(no_crs.find("no_crs.nc: coordinate reference system: none"), std::string::npos) << no_crs;
    Stations backwards = s;
    backwards.time = {0.0, 5.0, 4.0};
    const std::string time = err(backwards, "backwards.nc", {});
    EXPECT_NE(time.find("backwards.nc: variable 'time': time is not increasing at index 2"), std::string::npos) << time;
    Stations gap = s;
    gap.time = {0.0, 1.0, 2.0, 60.0};
    const std::string gaps = err(gap, "gap.nc", {});
    EXPECT_NE(gaps.find("gap.nc: variable 'time': a gap of 58 s after 2 s"), std::string::npos) << gaps;
    Stations holes = s;
    holes.level_fill_at = 5.0;
    const std::string fill = err(holes, "fill.nc", {});
    EXPECT_NE(fill.find("fill.nc: variable 'zeta': no value"), std::string::npos) << fill;
    EXPECT_NE(fill.find("time index 1, station 0"), std::string::npos) << fill;
    Stations half = s;
    half.x.resize(6);
    half.y.resize(6);
    const std::string cover = err(half, "half.nc", {});
    EXPECT_NE(cover.find("half.nc: stations: do not cover the side"), std::string::npos) << cover;
    Stations far = s;
    for (double& x : far.x) x = 500.0;
    const std::string reach = err(far, "far.nc", {});
    EXPECT_NE(reach.find("far.nc: stations: none within"), std::string::npos) << reach;
}

// GeoClaw's ASCII gauges, converted by pipelines/boundary_files.py, are read through the
// same path: three gauges on the west edge of a UTM scene, h = 2 m, hu = 1 m^2/s, so
// u = 0.5 m/s, and eta = 0.1 + 0.01 t.
TEST(BoundaryForcing, GeoclawGaugesConvertedByThePipelineDriveASide) {
    const std::string dir = test::scratch_dir("BoundaryForcingGeoclaw");
    const Grid g{10, 10, 518005.0, 3780005.0, 10.0, 10.0};
    std::string files;
    for (int k = 0; k < 3; ++k) {
        std::ostringstream text;
        text << "# gauge_id=     " << k + 1 << " location=(   0.518000E+06   " << 3780000.0 + 50.0 * k << " ) num_var=  4\n"
             << "# Stationary gauge\n# level, time, q[  1  2  3], eta, aux[]\n# file format ascii\n";
        for (int n = 0; n <= 4; ++n) text << "1 " << 5.0 * n << " 2.0 1.0 0.0 " << 0.1 + 0.05 * n << "\n";
        files += " " + test::write_file(dir, "gauge0000" + std::to_string(k + 1) + ".txt", text.str());
    }
    const std::string out = dir + "/geoclaw.nc";
    const std::string cmd = "cd " FLOTSAM_SOURCE_DIR " && /usr/bin/python3 -m pipelines.boundary_files geoclaw-gauges --crs "
                            "EPSG:32653 --out " + out + files + " > " + dir + "/log.txt 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    gdal::init();
    const SideRecord r = data::read_side_forcing(out, "west", g, gdal::grid_mapping(epsg(32653)));
    ASSERT_EQ(r.along.size(), 3u);
    EXPECT_DOUBLE_EQ(r.along[2], 3780100.0);
    EXPECT_DOUBLE_EQ(r.time[4], 20.0);
    EXPECT_NEAR(r.level[3 * 3 + 1], 0.25, 1e-12);
    EXPECT_NEAR(r.u[2], 0.5, 1e-12);
    EXPECT_NEAR(r.v[2], 0.0, 1e-12);
}

// A regional model's gridded output in longitude and latitude (a 0.001 deg grid with its
// level linear in both) read along the south side of a UTM scene: each edge cell takes
// the level at its own longitude and latitude, which bilinear interpolation of a field
// linear in both gives exactly.
TEST(BoundaryForcing, AGriddedFieldInLongitudeLatitudeIsReadAtTheUtmSide) {
    gdal::init();
    const std::string dir = test::scratch_dir("BoundaryForcingGeoGrid");
    const std::string path = dir + "/regional.nc";
    auto level = [](double lon, double lat) { return 1.0 + 50.0 * (lon - 135.0) - 20.0 * (lat - 34.0); };
    {
        nc::File f = nc::File::create(path);
        const int dt = f.def_dim("time", 2), dy = f.def_dim("lat", 40), dx = f.def_dim("lon", 40);
        const int vt = cf::def_time(f, dt);
        const int vx = cf::def_var(f, {.name = "lon", .dims = {dx}, .units = "degrees_east", .standard_name = "longitude"});
        const int vy = cf::def_var(f, {.name = "lat", .dims = {dy}, .units = "degrees_north", .standard_name = "latitude"});
        const int vl = cf::def_var(f, {.name = "eta", .dims = {dt, dy, dx}, .units = "m", .standard_name = "sea_surface_height"});
        f.enddef();
        f.put(vt, std::vector<double>{0.0, 60.0});
        std::vector<double> lon, lat, l;
        for (int i = 0; i < 40; ++i) lon.push_back(135.18 + 0.001 * i);
        for (int j = 0; j < 40; ++j) lat.push_back(34.14 + 0.001 * j);
        for (int k = 0; k < 2; ++k)
            for (double b : lat)
                for (double a : lon) l.push_back(level(a, b) + 0.1 * k);
        f.put(vx, lon);
        f.put(vy, lat);
        f.put(vl, l);
    }
    const Grid g{20, 20, 518005.0, 3780005.0, 10.0, 10.0};
    const OGRSpatialReference utm = epsg(32653), wgs = epsg(4326);
    const SideRecord r = data::read_side_forcing(path, "south", g, gdal::grid_mapping(utm));
    std::unique_ptr<OGRCoordinateTransformation> to_geo(OGRCreateCoordinateTransformation(&utm, &wgs));
    ASSERT_EQ(r.along.size(), 20u);
    for (std::size_t p = 0; p < 20; ++p) {
        double x = g.x(int(p)), y = g.y_min_edge();
        ASSERT_TRUE(to_geo->Transform(1, &x, &y));
        EXPECT_NEAR(r.level[20 + p], level(x, y) + 0.1, 1e-9) << p;
    }
}
