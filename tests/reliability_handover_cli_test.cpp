// The files the later stages read (sweep, statistics and trajectory files), through the
// command line: units, finite values and ranges checked where they are read, and files
// given together checked against each other before anything is written (docs/reliability.md).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cases/debris_flows.hpp"
#include "common/netcdf.hpp"
#include "common/output_lock.hpp"
#include "common/sha256.hpp"
#include "data/gdal_support.hpp"
#include "formats/scene.hpp"
#include "fuzz/bad_files.hpp"
#include "tests/reliability_cases.hpp"

using namespace flotsam;
using namespace flotsam::test;
namespace fs = std::filesystem;

// Flows, scenes, statistics and trajectories given together must come from one scene:
// grid, bed, building mask and CRS, in every command that combines them; and what export
// writes must be a map (no all-missing depth, no arrival before the run, no NaN track).
TEST(ReliabilityCli, FilesGivenTogetherAreCheckedAgainstEachOther) {
    const SmallCase c = small_case("cli_together");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    const std::string stats = c.dir + "/stats.nc", traj = c.dir + "/traj.nc";
    ASSERT_EQ(test::run_cli("stats --sweep " + o.sweep + " --out " + stats, &out), 0) << out;
    ASSERT_EQ(test::run_cli("debris --flow " + o.flow + " --scene " + c.scene + " --start FD --quiet --out " + traj, &out), 0) << out;
    // The same bed with one more building cell (cell 0, in the flume's water).
    const std::string mask = copy_of(c.scene, c.dir + "/mask.nc");
    fuzz::copy_with_value(c.scene, mask, "building", 0, 1);
    // Another resolution, and another layout, with their flows.
    const std::string coarse = c.dir + "/coarse.nc", other = c.dir + "/other.nc";
    ASSERT_EQ(test::run_cli("scene generate --resolution 0.32 --out " + coarse, &out), 0) << out;
    ASSERT_EQ(test::run_cli("scene generate --resolution 0.16 --seed 7 --out " + other, &out), 0) << out;
    const std::string hydro = " --west level --west-series " + c.series + " --duration 4 --quiet" + whole_grid + " --out ";
    ASSERT_EQ(test::run_cli("hydro --scene " + coarse + hydro + c.dir + "/coarse_flow.nc", &out), 0) << out;
    ASSERT_EQ(test::run_cli("hydro --scene " + other + hydro + c.dir + "/other_flow.nc", &out), 0) << out;
    const std::string nan_depth = copy_of(o.flow, c.dir + "/nan_depth.nc");
    fuzz::set_all(nan_depth, "max_depth", std::nan(""));
    const std::string early = copy_of(o.flow, c.dir + "/early.nc");
    fuzz::copy_with_value(o.flow, early, "arrival_time", 10, -5.0);
    const std::string nan_x = copy_of(traj, c.dir + "/nan_x.nc");
    fuzz::copy_with_value(traj, nan_x, "x", 3, std::nan(""));
    const std::string transposed = c.dir + "/transposed.nc";  // drawn as garbage lines before
    fuzz::copy_with_transposed(traj, transposed, "x");
    const std::string flow_index = c.dir + "/flow_index.nc", one_body = c.dir + "/one_body.nc";
    fuzz::copy_with_value(o.sweep, flow_index, "flow_index", 0, 99);
    fuzz::copy_with_dimension(o.sweep, one_body, "body", 1);
    const std::string gis = " --out-dir " + c.dir + "/gis";
    expect_named_errors({
        {"debris --flow " + o.flow + " --scene " + mask + " --start FD --quiet --out " + c.dir + "/d.nc",
         "was not computed on scene " + mask + ": the bed is the same, but the building mask differs"},
        {"stats --sweep " + o.sweep + " --scene " + mask + " --out " + c.dir + "/s.nc", "was run on another scene than " + mask},
        {"export --stats " + stats + " --flow " + c.dir + "/coarse_flow.nc" + gis, "coarse_flow.nc: comes from a scene of 0.32 m cells"},
        {"export --flow " + o.flow + " --flow " + c.dir + "/other_flow.nc" + gis,
         "other_flow.nc: variable 'z': the bed differs from that of " + o.flow},
        {"export --flow " + nan_depth + gis, "nan_depth.nc: variable 'max_depth': missing (NaN or a fill value) at flat index 0"},
        {"export --flow " + early + gis, "early.nc: variable 'arrival_time': -5 at flat index 10 is outside [-1e-06, 4]"},
        {"export --trajectories " + nan_x + gis, "nan_x.nc: variable 'x': trajectory 0, time index 3: nan is not a position"},
        {"export --trajectories " + transposed + gis, "transposed.nc: variable 'x': must have dimensions (trajectory, time)"},
        {"export --trajectories " + flow_index + gis, "flow_index.nc: trajectory 0: body, variant, flow or parameter set not in"},
        {"export --trajectories " + one_body + gis, "one_body.nc: trajectory "},
        {"export --trajectories " + traj + " --flow " + c.dir + "/other_flow.nc" + gis, "comes from another scene than"},
    });
    EXPECT_FALSE(fs::exists(c.dir + "/gis"));  // refused before anything was written
}

namespace {

// The values of band 1 of a GeoTIFF.
std::vector<float> raster_values(const std::string& path) {
    gdal::init();
    gdal::Dataset d = gdal::open_raster(path);
    const int nx = d->GetRasterXSize(), ny = d->GetRasterYSize();
    std::vector<float> v(std::size_t(nx) * std::size_t(ny));
    EXPECT_EQ(d->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, nx, ny, v.data(), nx, ny, GDT_Float32, 0, 0, nullptr), CE_None);
    return v;
}

}  // namespace

// Statistics are checked as they are read, whole, before export writes anything: a NaN
// cell, a hit probability of 2, a unit that is no speed, maps moved 1 km off their scene,
// another scene; a speed in km/h is converted (the same map).
TEST(ReliabilityCli, StatisticsAreCheckedWhereTheyAreRead) {
    const SmallCase c = small_case("cli_stats_checks");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    const std::string stats = c.dir + "/stats.nc", other = c.dir + "/other.nc";
    ASSERT_EQ(test::run_cli("stats --sweep " + o.sweep + " --out " + stats, &out), 0) << out;
    ASSERT_EQ(test::run_cli("scene generate --resolution 0.16 --seed 7 --out " + other, &out), 0) << out;
    const std::string nan_cell = copy_of(stats, c.dir + "/nan_cell.nc"), hit2 = copy_of(stats, c.dir + "/hit2.nc"),
                      furlongs = copy_of(stats, c.dir + "/furlongs.nc"), moved = copy_of(stats, c.dir + "/moved.nc"),
                      kmh = copy_of(stats, c.dir + "/kmh.nc");
    fuzz::set_value(nan_cell, "pass_probability", 5, std::nan(""));
    fuzz::set_all(hit2, "building_hit_probability_all", 2.0);
    fuzz::set_text_attribute(furlongs, "max_debris_speed", "units", "furlongs per fortnight");
    fuzz::shift_values(moved, "x", 1000.0);
    for (const char* v : {"max_debris_speed", "max_debris_speed_all"}) {
        fuzz::scale_values(kmh, v, 3.6);
        fuzz::set_text_attribute(kmh, v, "units", "km h-1");
    }
    const std::string gis = " --out-dir " + c.dir + "/gis";
    expect_named_errors({
        {"export --stats " + nan_cell + gis,
         "nan_cell.nc: variable 'pass_probability': value at flat index 5: nan is not a finite number (allowed: [0, 1] 1)"},
        {"export --stats " + hit2 + gis,
         "hit2.nc: variable 'building_hit_probability_all': value at flat index 0: 2 is outside the allowed range [0, 1] 1"},
        {"export --stats " + furlongs + gis, "furlongs.nc: variable 'max_debris_speed' attribute 'units': 'furlongs per fortnight' is not a unit of speed"},
        {"export --stats " + moved + " --scene " + c.scene + gis, "moved.nc: variables 'x', 'y': the maps' grid ("},
        {"export --stats " + stats + " --scene " + other + gis, "stats.nc: scene_buildings_sha256: comes from another scene than " + other},
        {"export --stats " + moved + " --flow " + o.flow + gis, "neither lies within the other"},
    });
    EXPECT_FALSE(fs::exists(c.dir + "/gis"));  // refused before the first GeoTIFF
    ASSERT_EQ(test::run_cli("export --stats " + stats + " --out-dir " + c.dir + "/a", &out), 0) << out;
    ASSERT_EQ(test::run_cli("export --stats " + kmh + " --out-dir " + c.dir + "/b", &out), 0) << out;
    const std::vector<float> a = raster_values(c.dir + "/a/max_debris_speed_all.tif"), b = raster_values(c.dir + "/b/max_debris_speed_all.tif");
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k)
        if (!std::isnan(a[k])) {
            EXPECT_NEAR(b[k], a[k], 1e-5) << k;
        }
}

// Sweep and trajectory files are checked where they are read, so stats, export and
// hazard_region.py refuse alike: a position 1e6 m off at one sample (the body would move
// at 1e7 m/s), a speed of 1e4 m/s, a unit that is no length, tracks moved 1 km off the
// scene or flow they moved on, a body 1e30 m wide. Positions in km and times in hours, labelled so, are
// converted.
TEST(ReliabilityCli, SweepAndTrajectoryFilesAreCheckedWhereTheyAreRead) {
    const SmallCase c = small_case("cli_track_checks");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    const std::string traj = c.dir + "/traj.nc";
    ASSERT_EQ(test::run_cli("debris --flow " + o.flow + " --scene " + c.scene + " --start FD --quiet --out " + traj, &out), 0) << out;
    const std::string far = c.dir + "/far.nc", fast = c.dir + "/fast.nc";
    fuzz::copy_with_value(o.sweep, far, "x", 3, 1e6);
    fuzz::copy_with_value(o.sweep, fast, "u", 2, 1e4);
    const std::string furlongs = copy_of(o.sweep, c.dir + "/furlongs.nc"), moved = copy_of(o.sweep, c.dir + "/moved.nc"),
                      km = copy_of(o.sweep, c.dir + "/km.nc"), hours = copy_of(traj, c.dir + "/hours.nc"),
                      off_flow = copy_of(traj, c.dir + "/off_flow.nc");
    fuzz::set_text_attribute(furlongs, "x", "units", "furlongs");
    fuzz::shift_values(moved, "x", 1000.0);
    for (const char* v : {"x", "y", "x0", "y0"}) {
        fuzz::scale_values(km, v, 1e-3);
        fuzz::set_text_attribute(km, v, "units", "km");
    }
    fuzz::scale_values(hours, "time", 1.0 / 3600.0);
    fuzz::set_text_attribute(hours, "time", "units", "hours since 2000-01-01 00:00:00");
    fuzz::shift_values(off_flow, "x", 1000.0);
    const std::string wide = c.dir + "/wide.nc";  // became a GIS attribute
    fuzz::copy_with_value(traj, wide, "width", 0, 1e30);
    const std::string gis = " --out-dir " + c.dir + "/gis";
    const auto stats = [&](const std::string& sweep) { return "stats --sweep " + sweep + " --out " + c.dir + "/s.nc"; };
    expect_named_errors({
        {stats(far), "far.nc: variables 'x', 'y': trajectory 0, time index 3: the body moves "},
        {"export --trajectories " + far + gis, "far.nc: variables 'x', 'y': trajectory 0, time index 3: the body moves "},
        {stats(fast), "fast.nc: variable 'u': trajectory 0, time index 2: 10000 is not a speed (beyond +-1000)"},
        {stats(furlongs), "furlongs.nc: variable 'x' attribute 'units': 'furlongs' is not a unit of length"},
        {stats(moved), "moved.nc: variables 'x', 'y': trajectory 0, time index 0: ("},
        {"export --trajectories " + off_flow + " --flow " + o.flow + gis, "off_flow.nc: variables 'x', 'y': trajectory 0, time index 0: ("},
        {"export --trajectories " + wide + gis, "wide.nc: variable 'width': 1e+30 is outside the allowed range (0, 10000] m"},
    });
    EXPECT_NE(test::run_cli(stats(moved), &out), 0);
    EXPECT_NE(out.find("lies outside the grid of the scene " + c.scene), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(c.dir + "/gis"));
    EXPECT_EQ(run_pipeline("hazard_region --sweep " + far + " --scene " + c.scene + " --out " + c.dir + "/h --no-charts", &out), 1);
    EXPECT_NE(out.find("far.nc: variables 'x', 'y': trajectory 0, time index 3: the body moves"), std::string::npos) << out;
    // Labelled units are converted: the same statistics from metres and kilometres.
    ASSERT_EQ(test::run_cli("stats --sweep " + o.sweep + " --out " + c.dir + "/m.nc", &out), 0) << out;
    ASSERT_EQ(test::run_cli("stats --sweep " + km + " --out " + c.dir + "/k.nc", &out), 0) << out;
    for (const char* v : {"pass_probability_all", "member_passage_y", "distance_mean"}) {
        const std::vector<double> m = all_values(c.dir + "/m.nc", v), k = all_values(c.dir + "/k.nc", v);
        ASSERT_EQ(m.size(), k.size()) << v;
        for (std::size_t i = 0; i < m.size(); ++i) EXPECT_NEAR(k[i], m[i], 1e-6 * (1.0 + std::fabs(m[i]))) << v << " " << i;
    }
    ASSERT_EQ(test::run_cli("export --trajectories " + hours + " --out-dir " + c.dir + "/hours_gis", &out), 0) << out;
}

// hazard_region.py checks its inputs as flotsam does and ends with one named line (no
// traceback): a FIFO, a file of another kind, a flow the sweep names gone, a scene in
// another CRS, NaN depths in a flow (which moved its directions by a degree).
TEST(ReliabilityCli, HazardRegionChecksItsInputsAsFlotsamDoes) {
    const SmallCase c = small_case("cli_hazard_checks");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    const std::string fifo = c.dir + "/fifo.nc";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    const std::string gone = copy_of(o.sweep, c.dir + "/gone.nc"), nan = copy_of(o.sweep, c.dir + "/nan_sweep.nc");
    fuzz::set_string(gone, "flow_path", 0, c.dir + "/no.nc");
    const std::string nan_flow = copy_of(o.flow, c.dir + "/nan.nc");
    fuzz::set_all(nan_flow, "h", std::nan(""));
    fuzz::set_string(nan, "flow_path", 0, nan_flow);
    for (std::size_t m = 0; m < all_values(o.sweep, "member_id").size(); ++m) fuzz::set_string(nan, "flow", m, nan_flow);
    const std::string utm = c.dir + "/utm.nc";
    ASSERT_EQ(test::run_cli("scene import --dem " + c.scene + " --crs EPSG:32653 --resolution 0.16 --out " + utm, &out), 0) << out;
    const auto hazard = [&](const std::string& sweep, const std::string& scene) {
        return "hazard_region --sweep " + sweep + " --scene " + scene + " --out " + c.dir + "/h --no-charts";
    };
    for (const Case& k : std::vector<Case>{
             {hazard(fifo, c.scene), "hazard_region: error: --sweep: " + fifo + ": is a FIFO (named pipe), not a regular file"},
             {hazard(o.flow, c.scene), "hazard_region: error: --sweep: " + o.flow + ": is a flow file (written by `flotsam hydro`), not a sweep file"},
             {hazard(gone, c.scene), "hazard_region: error: " + gone + ": flow: " + c.dir + "/no.nc: does not exist"},
             {hazard(o.sweep, utm), "hazard_region: error: " + o.sweep + ": crs: is none (local metres), that of " + utm + " is "},
             {hazard(nan, c.scene), "hazard_region: error: " + nan_flow + ": variable 'h': frame 0, cell (i "},
         }) {
        const int rc = test::finish_cli(::popen(("cd " FLOTSAM_SOURCE_DIR " && timeout 60 /usr/bin/python3 -m pipelines." + k.args + " 2>&1").c_str(), "r"), &out);
        EXPECT_EQ(rc, 1) << k.args << "\n" << out;
        EXPECT_NE(out.find(k.expect), std::string::npos) << k.args << "\n" << out;
        EXPECT_EQ(out.find("Traceback"), std::string::npos) << out;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;  // one line
    }
}
