// Froude similarity: the real layout at the prototype scale, x250 (lengths
// x250, times x sqrt(250), Manning n x 250^(1/6), the paper's box x250 at the same
// specific gravity), placed in UTM zone 53N near Kainan, gives the flume's WG2 level,
// arrival times and debris path scaled by the same factors. The shallow-water equations
// with Manning friction are invariant under that scaling, and so is every numerical
// choice that is a pure number (CFL, limiter, Courant) or follows the scene or the body
// (the scene's recommended max-dt and arrival depth; the debris step, window and motion
// thresholds). What can break it is a constant in metres or seconds hidden in the code:
// such a constant acts 250 times more weakly (or strongly) at full scale, and the scaled
// run departs from the flume's. Coarse (8 cm) grid, 90 s of flume time: the FD box
// floats from about 40 s and moves some body lengths before the end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "common/netcdf.hpp"
#include "data/boundary_generator.hpp"
#include "data/dem_import.hpp"
#include "data/gdal_support.hpp"
#include "debris/catalogue.hpp"
#include "debris/world.hpp"
#include "hydro/run.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;

namespace {

constexpr double lambda = 250.0;                        // length scale
const double time_scale = std::sqrt(lambda);            // Froude: times and speeds scale as sqrt(lambda)
constexpr double east0 = 518000.0, north0 = 3780000.0;  // the flume's origin in UTM 53N

double to_east(double x) { return east0 + lambda * x; }
double to_north(double y) { return north0 + lambda * y; }

Scene full_scale(const Scene& a) {
    Scene b = a;
    b.grid.x0 = to_east(a.grid.x0);
    b.grid.y0 = to_north(a.grid.y0);
    b.grid.dx = lambda * a.grid.dx;
    b.grid.dy = lambda * a.grid.dy;
    for (double& z : b.z) z *= lambda;
    const double n_scale = std::pow(lambda, 1.0 / 6.0);
    for (double& n : b.manning_n) n *= n_scale;
    for (auto& p : b.points) p.x = to_east(p.x), p.y = to_north(p.y);
    for (auto& s : b.sections) s.x = to_east(s.x), s.y_min = to_north(s.y_min), s.y_max = to_north(s.y_max);
    for (auto& r : b.regions)
        for (auto& v : r.polygon) v = {to_east(v[0]), to_north(v[1])};
    gdal::init();
    OGRSpatialReference utm;
    utm.importFromEPSG(32653);
    b.crs = gdal::grid_mapping(utm);
    return b;
}

void write_series(const std::string& path, const TimeSeries& s, double t_scale, double v_scale) {
    std::ofstream f(path);
    f << "time,eta\n";
    char buf[80];
    for (std::size_t k = 0; k < s.time.size(); ++k) {
        std::snprintf(buf, sizeof buf, "%.17g,%.17g\n", s.time[k] * t_scale, s.value[k] * v_scale);
        f << buf;
    }
}

struct FlowFigures {
    std::vector<double> wg2;     // gauge level at WG2 [m]
    std::vector<float> arrival;  // arrival-time map [s], NaN where never
};

FlowFigures read_flow(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    FlowFigures out;
    const auto names = f.get_strings(f.var("gauge_name"));
    const std::size_t g = std::size_t(std::find(names.begin(), names.end(), "WG2") - names.begin());
    EXPECT_LT(g, names.size());
    const auto eta = f.get_double(f.var("gauge_eta"));
    for (std::size_t k = g; k < eta.size(); k += names.size()) out.wg2.push_back(eta[k]);
    const auto at = f.get_double(f.var("arrival_time"));
    for (double v : at) out.arrival.push_back(v > 1e30 ? std::nanf("") : float(v));
    return out;
}

// The FD box through a flow: centre positions at `steps` + 1 output times.
std::vector<std::array<double, 2>> fd_path(const std::string& flow, const Scene& scene, const debris::BodyDef& body,
                                           double interval, int steps) {
    debris::WorldDef wdef = debris::scaled_to_bodies(debris::default_world_def(), {body}, false);  // as flotsam debris sets it up
    wdef.threads = 1;
    std::vector<std::uint8_t> building;
    {
        const debris::FlowReader probe(flow, wdef.flow);
        building = debris::buildings_on_grid(scene, probe.grid());
    }
    debris::World world(flow, std::move(building), wdef);
    world.add_body(body);
    auto at = [&] { return std::array<double, 2>{world.states()[0].x + world.origin_x(), world.states()[0].y + world.origin_y()}; };
    std::vector<std::array<double, 2>> path{at()};
    for (int k = 1; k <= steps; ++k) {
        world.advance_to(world.flow().description().start_time() + k * interval);
        path.push_back(at());
    }
    return path;
}

}  // namespace

TEST(FroudeSimilarity, RealLayoutAtPrototypeScaleMatchesTheFlume) {
    const std::string dem = test::shared_data("city-topography-from-figure.nc");
    if (dem.empty()) GTEST_SKIP() << "../shared/data/city-topography-from-figure.nc not found";
    const std::string dir = test::scratch_dir("froude");

    // The flume: the real layout at 8 cm with the Kainan features, a generated WG1 record.
    ImportDef idef;
    idef.dem_path = dem;
    idef.resolution = 0.08;
    const Scene flume = import_scene(idef);
    const Scene proto = full_scale(flume);
    write_scene(dir + "/flume.nc", flume, "test");
    write_scene(dir + "/proto.nc", proto, "test");
    BoundaryGenDef bdef;
    bdef.count = 1;
    bdef.duration = 100.0;
    const TimeSeries wg1 = generate_boundary_records(bdef).front();
    write_series(dir + "/wg1_flume.csv", wg1, 1.0, 1.0);
    write_series(dir + "/wg1_proto.csv", wg1, time_scale, lambda);

    const double duration = 90.0, frame = 1.0;
    // One run. The prototype scales every setting that is a length or a time, as its
    // scene recommends (docs/gis.md, "Any scale"): the output and gauge intervals, the
    // window, the nesting interface, the arrival depth, max-dt and, unless
    // `keep_dry_depth`, the dry tolerance.
    auto run = [&](const std::string& scene, const std::string& series, const std::string& out, bool prototype,
                   bool keep_dry_depth) {
        const double ts = prototype ? time_scale : 1.0, ls = prototype ? lambda : 1.0;
        auto x = [&](double v) { return prototype ? to_east(v) : v; };
        auto y = [&](double v) { return prototype ? to_north(v) : v; };
        hydro::RunDef r;
        // float64: the test looks for constants that do not scale, down to rounding, and
        // float32's rounding (1e-7 of the state), which a floating box's path amplifies,
        // would hide them (0.09 body lengths in 90 s, more than the control's 0.03).
        r.finite_volume.precision = hydro::Precision::float64;
        r.scene_file = scene;
        r.out_file = out;
        r.duration = duration * ts;
        r.output_interval = frame * ts;
        r.gauge_interval = 0.5 * ts;
        r.window = std::array<double, 4>{x(0.0), x(8.0), y(-4.0), y(0.0)};
        r.nest = {x(-1.2), 2};
        // Near the draft, but not a level the DEM's quantised channel beds sit at exactly
        // (there float rounding of z x 250 decides whether a still cell counts as reached).
        r.arrival_depth = 0.0237 * ls;
        r.quiet = true;
        r.command_line = r.config_text = "froude test";
        r.flood_depth *= ls;
        hydro::PhysicsDef s = hydro::default_physics_def();
        s.west.kind = hydro::BoundaryKind::level;
        s.west.series_file = series;
        s.max_dt *= ts;
        if (!keep_dry_depth) s.dry_depth *= ls;
        hydro::run_hydro(r, s);
    };
    run(dir + "/flume.nc", dir + "/wg1_flume.csv", dir + "/flow_flume.nc", false, false);
    run(dir + "/proto.nc", dir + "/wg1_proto.csv", dir + "/flow_proto.nc", true, false);
    // The control: the prototype with the flume's 1e-5 m dry tolerance, a length left
    // unscaled, as a hidden constant in metres would be. The test must see it.
    run(dir + "/proto.nc", dir + "/wg1_proto.csv", dir + "/flow_proto_dry.nc", true, true);

    const ScenePoint* fd = flume.find_point("FD");
    ASSERT_NE(fd, nullptr);
    debris::BodyDef box = debris::catalogue_body_def("paper_box", "test");
    box.name = "FD";
    box.x = fd->x;
    box.y = fd->y;
    debris::BodyDef big = debris::catalogue_body_def("paper_box_full_scale", "test");
    big.name = "FD";
    big.x = to_east(fd->x);
    big.y = to_north(fd->y);
    const int steps = int(duration / frame);
    const FlowFigures a = read_flow(dir + "/flow_flume.nc");
    const auto pa = fd_path(dir + "/flow_flume.nc", flume, box, frame, steps);

    struct Comparison {
        double peak = 0, wg2 = 0, arrival = 0, travel = 0, path = 0;
        std::size_t reached = 0, disagree = 0;
    };
    auto compare = [&](const std::string& flow, const char* label) {
        Comparison c;
        const FlowFigures b = read_flow(flow);
        EXPECT_EQ(a.wg2.size(), b.wg2.size());
        // WG2: the prototype's level over 250 against the flume's, sample by sample.
        for (std::size_t k = 0; k < std::min(a.wg2.size(), b.wg2.size()); ++k) {
            c.peak = std::max(c.peak, std::abs(a.wg2[k]));
            c.wg2 = std::max(c.wg2, std::abs(b.wg2[k] / lambda - a.wg2[k]));
        }
        // Arrival times over sqrt(250), cell by cell.
        EXPECT_EQ(a.arrival.size(), b.arrival.size());
        for (std::size_t k = 0; k < std::min(a.arrival.size(), b.arrival.size()); ++k) {
            const bool ra = !std::isnan(a.arrival[k]), rb = !std::isnan(b.arrival[k]);
            c.reached += ra;
            if (ra != rb)
                ++c.disagree;
            else if (ra)
                c.arrival = std::max(c.arrival, std::abs(double(b.arrival[k]) / time_scale - double(a.arrival[k])));
        }
        // The FD box and its x250 twin (the debris settings follow the body: its step, its
        // window, the reader's depth thresholds).
        const auto pb = fd_path(flow, proto, big, frame * time_scale, steps);
        for (int k = 0; k <= steps; ++k) {
            c.travel = std::max(c.travel, std::hypot(pa[k][0] - pa[0][0], pa[k][1] - pa[0][1]));
            c.path = std::max(c.path, std::hypot((pb[k][0] - east0) / lambda - pa[k][0], (pb[k][1] - north0) / lambda - pa[k][1]));
        }
        std::printf("froude (%s): WG2 peak %.5f m (flume), largest |eta/250 - eta_flume| %.3g m (%.3g of the peak)\n", label,
                    c.peak, c.wg2, c.wg2 / c.peak);
        std::printf("froude (%s): arrival: %zu cells reached, %zu in one scale only, largest |t/sqrt(250) - t_flume| %.3g s\n",
                    label, c.reached, c.disagree, c.arrival);
        std::printf("froude (%s): FD box: moved up to %.4f m (flume), largest path difference %.3g m (%.3g body lengths)\n", label,
                    c.travel, c.path, c.path / 0.25);
        return c;
    };
    const Comparison scaled = compare(dir + "/flow_proto.nc", "all scaled");
    const Comparison control = compare(dir + "/flow_proto_dry.nc", "dry tolerance unscaled");

    // Nothing in the code knows the scale: the scaled runs agree to rounding (z x 250 in
    // float32, coordinates 250 times larger), amplified at wet/dry switches. Measured:
    // 6.5e-8 of the peak, 5.5e-6 s, 1.3e-6 body lengths. The control, whose dry tolerance
    // was left at the flume's 1e-6 m (a 250th of what the scaled run has), moves them by
    // 7.2e-4 of the peak, 0.087 s and 0.020 body lengths. The tolerances sit 150-1800 times
    // above the first and 9-70 times below the second.
    EXPECT_GT(scaled.peak, 0.01);
    EXPECT_LT(scaled.wg2, 1e-5 * scaled.peak);
    EXPECT_GT(scaled.reached, 500u);
    EXPECT_EQ(scaled.disagree, 0u);
    EXPECT_LT(scaled.arrival, 0.01);
    EXPECT_GT(scaled.travel, 4 * 0.25);  // the box travels several body lengths: the comparison can fail
    EXPECT_LT(scaled.path, 1e-3 * 0.25);
    // The control fails each of them: the test sees a length left at flume scale.
    EXPECT_GT(control.wg2, 1e-5 * control.peak);
    EXPECT_GT(control.arrival, 0.01);
    EXPECT_GT(control.path, 1e-3 * 0.25);
}
