// Runs of the hydro driver: the stored file, restart, determinism, errors.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cases/hydro_cases.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/sha256.hpp"
#include "formats/flow_file.hpp"
#include "hydro/run.hpp"
#include "hydro/state_checks.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using test::error_of;
using test::write_file;
using namespace flotsam::hydro;

namespace {

// A 1 m x 0.4 m channel: a slope up to a shore with two 5 cm buildings, driven by a
// level series on the west.
std::string make_scene(const std::string& dir) {
    Scene s;
    s.grid = Grid{50, 20, 0.01, 0.01, 0.02, 0.02};
    s.z.resize(s.grid.size());
    s.building.assign(s.grid.size(), 0);
    for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 50; ++i) {
            double z = -0.05 + 0.07 * s.grid.x(i);
            const bool bldg = (i >= 35 && i < 40 && j >= 4 && j < 8) || (i >= 42 && i < 46 && j >= 12 && j < 16);
            if (bldg) z += 0.05;
            s.z[s.grid.index(i, j)] = z;
            s.building[s.grid.index(i, j)] = bldg ? 1 : 0;
        }
    s.points.push_back({"G1", "gauge", 0.3, 0.2, 0.0});
    s.title = "test channel";
    const std::string path = dir + "/scene.nc";
    write_scene(path, s, "test");
    return path;
}

std::string make_series(const std::string& dir) {
    const std::string path = dir + "/level.csv";
    std::ofstream f(path);
    f << "time,eta\n";
    for (int k = 0; k <= 200; ++k) f << k * 0.1 << "," << 0.03 * std::sin(0.1 * k * 0.1) << "\n";
    return path;
}

RunDef base_run(const std::string& scene, const std::string& out) {
    RunDef r;
    r.scene_file = scene;
    r.out_file = out;
    r.duration = 6.0;
    r.output_interval = 0.5;
    r.gauge_interval = 0.1;
    r.quiet = true;
    r.config_text = "test";
    r.command_line = "test";
    return r;
}

PhysicsDef level_def(const std::string& series) {
    PhysicsDef d = default_physics_def();
    d.west.series_file = series;
    return d;
}

// Runs `r` to a checkpoint at 1 s intervals, stops it after 2.7 s as if interrupted,
// and continues it with --restart; returns whether the continued run completed.
bool interrupted_and_restarted(RunDef r, const PhysicsDef& d) {
    r.checkpoint_interval = 1.0;
    r.stop_after = 2.7;
    EXPECT_FALSE(run_hydro(r, d).completed);
    EXPECT_FALSE(std::filesystem::exists(r.out_file));  // nothing that looks finished
    EXPECT_TRUE(std::filesystem::exists(r.out_file + ".part"));
    r.stop_after = -1.0;
    r.restart = true;
    return run_hydro(r, d).completed;
}

}  // namespace

TEST(HydroRun, WritesAReadableCfFlowFile) {
    const auto dir = test::scratch_dir("hydro_cf");
    const auto scene = make_scene(dir);
    const auto series = make_series(dir);
    RunDef r = base_run(scene, dir + "/flow.nc");
    r.window = std::array<double, 4>{0.2, 0.8, 0.0, 0.4};
    const RunResult res = run_hydro(r, level_def(series));
    ASSERT_TRUE(res.completed);
    EXPECT_FALSE(std::filesystem::exists(dir + "/flow.nc.part"));
    EXPECT_FALSE(std::filesystem::exists(checkpoint_path(dir + "/flow.nc")));

    const nc::File f = nc::File::open_read(dir + "/flow.nc");
    EXPECT_EQ(f.att_text(NC_GLOBAL, "Conventions").value_or(""), "CF-1.11");
    EXPECT_EQ(f.att_text(f.var("time"), "units").value_or(""), "seconds since 2000-01-01 00:00:00");
    EXPECT_EQ(f.dim_length("time"), 13u);
    EXPECT_EQ(f.dim_length("x"), 31u);  // cells 10..40 of the window
    const auto h_var = f.find_by_standard_name("sea_floor_depth_below_sea_surface");
    ASSERT_TRUE(h_var.has_value());
    EXPECT_EQ(f.var_name(*h_var), "h");
    EXPECT_EQ(f.att_text(*h_var, "units").value_or(""), "m");
    EXPECT_TRUE(f.find_by_standard_name("sea_water_x_velocity").has_value());
    EXPECT_NE(f.att_text(NC_GLOBAL, "boundary_checksum").value_or("").find("sha256:" + sha256_file(series)), std::string::npos);
    const auto h = f.get_float(*h_var);
    const auto u = f.get_float(f.var("u"));
    const auto z = f.get_float(f.var("z"));
    for (std::size_t k = 0; k < h.size(); ++k) {
        ASSERT_TRUE(std::isfinite(h[k]) && std::isfinite(u[k]));
        ASSERT_GE(h[k], 0.0f);
        if (h[k] == 0.0f) {
            ASSERT_EQ(u[k], 0.0f);
        }
    }
    // Frame 0 is still water: h = max(0, -z).
    for (std::size_t k = 0; k < z.size(); ++k) EXPECT_NEAR(h[k], std::max(0.0f, -z[k]), 1e-6f);
    // The roofs (5 cm above the shore) stay dry all run; the wave wets the lower shore.
    const auto maxd = f.get_float(f.var("max_depth"));
    EXPECT_EQ(maxd[std::size_t(5 * 31 + (36 - 10))], 0.0f);
    const auto eta = f.get_float(f.var("gauge_eta"));
    EXPECT_EQ(f.dim_length("gauge_time"), 61u);
    EXPECT_GT(*std::max_element(eta.begin(), eta.end()), 0.01f);
}

TEST(HydroRun, RestartContinuesToTheSameResultAndSameInputsGiveSameBytes) {
    const auto dir = test::scratch_dir("hydro_restart");
    const auto scene = make_scene(dir);
    const auto series = make_series(dir);
    const PhysicsDef d = level_def(series);
    for (Precision precision : {Precision::float32, Precision::float64}) {
        RunDef a = base_run(scene, dir + "/a.nc"), b = base_run(scene, dir + "/b.nc"), c = base_run(scene, dir + "/c.nc");
        for (RunDef* r : {&a, &b, &c}) r->finite_volume.precision = precision;
        for (const RunDef* r : {&a, &b, &c}) std::filesystem::remove(r->out_file);
        run_hydro(a, d);
        run_hydro(b, d);
        EXPECT_EQ(sha256_file(a.out_file), sha256_file(b.out_file));
        ASSERT_TRUE(interrupted_and_restarted(c, d));
        EXPECT_EQ(sha256_file(a.out_file), sha256_file(c.out_file)) << enum_name(precision);
    }

    RunDef r = base_run(scene, dir + "/c.nc");
    std::filesystem::remove(r.out_file);

    // A restart with other settings is refused.
    r.restart = false;
    r.checkpoint_interval = 1.0;
    r.stop_after = 1.5;
    run_hydro(r, d);
    r.restart = true;
    r.stop_after = -1.0;
    r.config_text = "cfl=0.4";  // a setting that changes the result
    EXPECT_NE(error_of([&] { run_hydro(r, d); }).find("other settings"), std::string::npos);
}

// Rows are split over threads, and the rows beside a thread's strip are computed by
// both threads: the same bytes whatever the thread count, uniform and nested.
TEST(HydroRun, SameBytesOnOneAndTwoThreads) {
    const auto dir = test::scratch_dir("hydro_threads");
    const auto scene = make_scene(dir);
    const PhysicsDef d = level_def(make_series(dir));
    for (Precision precision : {Precision::float32, Precision::float64})
        for (int ratio : {1, 2}) {
            std::string sha[2];
            for (int threads : {1, 2}) {
                omp_set_num_threads(threads);
                RunDef r = base_run(scene, dir + "/t" + std::to_string(threads) + std::string(enum_name(precision)) +
                                               std::to_string(ratio) + ".nc");
                r.nest = NestDef{0.3, ratio};
                r.finite_volume.precision = precision;
                ASSERT_TRUE(run_hydro(r, d).completed);
                sha[threads - 1] = sha256_file(r.out_file);
            }
            EXPECT_EQ(sha[0], sha[1]) << "nest ratio " << ratio << ", " << enum_name(precision);
        }
    omp_set_num_threads(omp_get_num_procs());
}

// The float32 state follows the float64 one on the test channel (a level wave up a slope
// onto a shore between buildings, 6 s, nested): the gauge within 0.1 micrometre and every
// stored depth within 0.2 micrometre (float32 rounds a 0.05 m depth to 4e-9 m; the runs
// differ by 8e-9 and 1.7e-8 m), the volume within a millionth; and the float32 run is
// not the float64 one (the option does change the arithmetic).
TEST(HydroRun, Float32StateFollowsFloat64WithinItsRoundOff) {
    const auto dir = test::scratch_dir("hydro_float32");
    const auto scene = make_scene(dir);
    const PhysicsDef d = level_def(make_series(dir));
    RunResult result[2];
    for (Precision precision : {Precision::float32, Precision::float64}) {
        RunDef r = base_run(scene, dir + "/" + std::string(enum_name(precision)) + ".nc");
        r.nest = NestDef{0.3, 2};
        r.finite_volume.precision = precision;
        result[int(precision)] = run_hydro(r, d);
        ASSERT_TRUE(result[int(precision)].completed);
    }
    const nc::File f = nc::File::open_read(dir + "/float32.nc"), g = nc::File::open_read(dir + "/float64.nc");
    auto worst = [&](const char* name) {
        const auto a = f.get_float(f.var(name)), b = g.get_float(g.var(name));
        double w = 0.0;
        for (std::size_t k = 0; k < a.size(); ++k) w = std::max(w, double(std::abs(a[k] - b[k])));
        return w;
    };
    EXPECT_GT(worst("h"), 0.0);
    EXPECT_LT(worst("gauge_eta"), 1e-7);
    EXPECT_LT(worst("h"), 2e-7);
    const double v32 = result[0].volume_end, v64 = result[1].volume_end;
    EXPECT_LT(std::abs(v32 / v64 - 1.0), 1e-6);
    EXPECT_NE(f.att_text(NC_GLOBAL, "source")->find("float32 state"), std::string::npos);
}

TEST(HydroRun, NestedRunRestartsToTheSameResult) {
    const auto dir = test::scratch_dir("hydro_nested_restart");
    const auto scene = make_scene(dir);
    const PhysicsDef d = level_def(make_series(dir));
    RunDef a = base_run(scene, dir + "/a.nc");
    a.nest = NestDef{0.3, 2};
    const RunResult full = run_hydro(a, d);
    ASSERT_TRUE(full.completed);
    EXPECT_LT(std::abs(full.volume_end - full.volume_start), 1.0);  // sanity: it ran and stayed finite
    RunDef c = a;
    c.out_file = dir + "/c.nc";
    ASSERT_TRUE(interrupted_and_restarted(c, d));
    const nc::File fa = nc::File::open_read(dir + "/a.nc"), fc = nc::File::open_read(dir + "/c.nc");
    for (const char* name : {"h", "u", "v", "gauge_eta"}) EXPECT_EQ(fa.get_float(fa.var(name)), fc.get_float(fc.var(name))) << name;
    // The uniform run differs (it is another model), but not by much at the gauge.
    RunDef u = base_run(scene, dir + "/u.nc");
    run_hydro(u, d);
    const nc::File fu = nc::File::open_read(dir + "/u.nc");
    const auto ga = fa.get_float(fa.var("gauge_eta")), gu = fu.get_float(fu.var("gauge_eta"));
    double worst = 0.0;
    for (std::size_t k = 0; k < ga.size(); ++k) worst = std::max(worst, double(std::abs(ga[k] - gu[k])));
    EXPECT_GT(worst, 0.0);
    EXPECT_LT(worst, 2e-3);
}

TEST(HydroRun, LeapfrogRunRestartsToTheSameResultAndRecordsItsScheme) {
    const auto dir = test::scratch_dir("hydro_leapfrog_restart");
    const auto scene = make_scene(dir);
    const PhysicsDef d = level_def(make_series(dir));
    RunDef a = base_run(scene, dir + "/a.nc");
    a.scheme = Scheme::leapfrog;
    const RunResult full = run_hydro(a, d);
    ASSERT_TRUE(full.completed);
    RunDef b = a;
    b.out_file = dir + "/b.nc";
    run_hydro(b, d);
    EXPECT_EQ(sha256_file(dir + "/a.nc"), sha256_file(dir + "/b.nc"));
    RunDef c = a;
    c.out_file = dir + "/c.nc";
    ASSERT_TRUE(interrupted_and_restarted(c, d));
    const nc::File fa = nc::File::open_read(dir + "/a.nc"), fc = nc::File::open_read(dir + "/c.nc");
    for (const char* name : {"h", "u", "v", "max_depth", "max_speed", "arrival_time", "gauge_eta"})
        EXPECT_EQ(fa.get_float(fa.var(name)), fc.get_float(fc.var(name))) << name;
    EXPECT_NE(fa.att_text(NC_GLOBAL, "source").value_or("").find("leap-frog"), std::string::npos);
    // Frames on the stored times exactly (the fixed step divides the interval), the wave
    // arrives at the gauge, the roofs stay dry.
    const auto t = fa.get_double(fa.var("time"));
    ASSERT_EQ(t.size(), 13u);
    EXPECT_EQ(t[7], 3.5);
    const auto eta = fa.get_float(fa.var("gauge_eta"));
    EXPECT_GT(*std::max_element(eta.begin(), eta.end()), 0.01f);
    EXPECT_EQ(fa.get_float(fa.var("max_depth"))[std::size_t(5 * 50 + 36)], 0.0f);
    // Against the finite-volume run of the same case: another scheme, the same wave.
    run_hydro(base_run(scene, dir + "/fv.nc"), d);
    const nc::File ff = nc::File::open_read(dir + "/fv.nc");
    const auto eta_fv = ff.get_float(ff.var("gauge_eta"));
    double worst = 0.0;
    for (std::size_t k = 0; k < eta.size(); ++k) worst = std::max(worst, double(std::abs(eta[k] - eta_fv[k])));
    std::printf("leap-frog vs finite volumes at G1: largest level difference %.2e m\n", worst);
    EXPECT_LT(worst, 1e-3);  // 9.5e-5 m measured
    // Nesting is for the finite-volume scheme only; the error names both ways out.
    a.nest = NestDef{0.3, 2};
    const std::string msg = error_of([&] { run_hydro(a, d); });
    EXPECT_NE(msg.find("--scheme fv with --nest-ratio 2, or --scheme leapfrog with --nest-ratio 1"), std::string::npos) << msg;
}

TEST(HydroRun, BadInputsNameFileAndProblem) {
    const auto dir = test::scratch_dir("hydro_bad");
    const auto scene = make_scene(dir);
    std::ofstream(dir + "/short.csv") << "time,eta\n0,0\n1,0.01\n";
    auto msg = error_of([&] { run_hydro(base_run(scene, dir + "/x.nc"), level_def(dir + "/short.csv")); });
    EXPECT_NE(msg.find("short.csv: covers [0"), std::string::npos) << msg;
    // A scene with NaN in z.
    Scene s = read_scene(scene);
    s.z[7] = std::nan("");
    {
        nc::File f = nc::File::create(dir + "/nan.nc");
        const int dx = f.def_dim("x", 50), dy = f.def_dim("y", 20);
        const int vx = f.def_var("x", NC_DOUBLE, {dx}), vy = f.def_var("y", NC_DOUBLE, {dy}),
                  vz = f.def_var("z", NC_DOUBLE, {dy, dx});
        f.enddef();
        f.put(vx, s.grid.xs());
        f.put(vy, s.grid.ys());
        f.put(vz, s.z);
    }
    msg = error_of([&] { run_hydro(base_run(dir + "/nan.nc", dir + "/y.nc"), level_def(make_series(dir))); });
    EXPECT_NE(msg.find("nan.nc: variable 'z': value at flat index 7"), std::string::npos) << msg;
    std::string out;
    EXPECT_NE(test::run_cli("hydro --scene " + scene + " --out " + dir + "/z.nc --west bogus", &out), 0);
    EXPECT_NE(out.find("--west: unknown boundary 'bogus'"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("hydro --scene " + scene + " --out " + dir + "/z.nc --scheme upwind", &out), 0);
    EXPECT_NE(out.find("--scheme"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("hydro --scene " + scene + " --out " + dir + "/z.nc --west wall --scheme leapfrog --courant 1.5", &out),
              0);
    EXPECT_NE(out.find("--courant: must be at most 1"), std::string::npos) << out;
}

TEST(HydroRun, XarrayDecodesTimeAndFindsStandardNames) {
    const auto dir = test::scratch_dir("hydro_xr");
    const auto scene = make_scene(dir);
    run_hydro(base_run(scene, dir + "/flow.nc"), level_def(make_series(dir)));
    const std::string cmd = "cd " FLOTSAM_SOURCE_DIR " && /usr/bin/python3 -m pipelines.inspect_flow " + dir +
                            "/flow.nc --check > " + dir + "/out.txt 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream f(dir + "/out.txt");
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_EQ(rc, 0) << text;
    EXPECT_NE(text.find("time decoded as datetime64"), std::string::npos) << text;
    EXPECT_NE(text.find("stranded fast water: none"), std::string::npos) << text;

    // The same flow with a puddle planted on the dry roof of the building at cells 35..39,
    // 4..7: 5 mm running north at 1 m/s between dry neighbours in every frame, as the
    // defect of docs/hydro.md ("A puddle in a pit") did. The check names it and fails.
    const std::string plant = "cd " + dir + " && cp flow.nc planted.nc && /usr/bin/python3 -c \"import netCDF4 as nc; "
                              "d = nc.Dataset('planted.nc', 'a'); i = 37; d['h'][:, 5, i] = 0.005; d['v'][:, 5, i] = 1.0; "
                              "d['u'][:, 5, i] = 0.0; d.close()\"";
    ASSERT_EQ(std::system(plant.c_str()), 0);
    const std::string check = "cd " FLOTSAM_SOURCE_DIR " && /usr/bin/python3 -m pipelines.inspect_flow " + dir +
                              "/planted.nc --check --stranded-seconds 5 > " + dir + "/planted.txt 2>&1";
    EXPECT_NE(std::system(check.c_str()), 0);
    std::ifstream p(dir + "/planted.txt");
    const std::string planted((std::istreambuf_iterator<char>(p)), std::istreambuf_iterator<char>());
    EXPECT_NE(planted.find("STRANDED FAST WATER in 1 cell(s)"), std::string::npos) << planted;
    EXPECT_NE(planted.find("(0.750, 0.110) m: 13 frames to t = 6 s, h 5.00 mm, u +0.00, v +1.00 m/s"), std::string::npos)
        << planted;
}

// Gauges interpolate bilinearly between the four cell centres around them: on a plane
// level (still water tilted at t = 0 over a flat bed), the gauge reads the plane's value
// at its own point, which the nearest cell (up to half a 2 cm cell away, 1e-4 m off on
// this slope) does not. A gauge beside a dry roof takes its level from the wet cells.
TEST(HydroRun, GaugesReadThePlaneLevelWhereTheyStand) {
    const auto dir = test::scratch_dir("hydro_gauge_bilinear");
    Scene s;
    s.grid = Grid{30, 20, 0.01, 0.01, 0.02, 0.02};
    s.z.assign(s.grid.size(), -0.1);
    s.eta0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 30; ++i) s.eta0[s.grid.index(i, j)] = 0.01 * s.grid.x(i) - 0.003 * s.grid.y(j);
    s.z[s.grid.index(20, 10)] = 0.05;  // a roof, dry
    s.eta0[s.grid.index(20, 10)] = 0.05;
    write_scene(dir + "/plane.nc", s, "test");
    RunDef r = base_run(dir + "/plane.nc", dir + "/flow.nc");
    r.duration = 0.1;
    r.output_interval = 0.1;
    r.gauges = {{"A", 0.137, 0.291}, {"B", 0.414, 0.207}};  // B: beside the roof at (0.41, 0.21)
    PhysicsDef d = default_physics_def();
    d.west.kind = BoundaryKind::wall;
    d.east.kind = BoundaryKind::wall;
    ASSERT_TRUE(run_hydro(r, d).completed);
    const nc::File f = nc::File::open_read(dir + "/flow.nc");
    const auto eta = f.get_float(f.var("gauge_eta"));  // (gauge_time, gauge): sample 0 first
    EXPECT_NEAR(eta[0], 0.01 * 0.137 - 0.003 * 0.291, 1e-7);
    // B sits at 20.2 and 9.85 cell spacings from the first centres: the roof's cell
    // (20, 10) weighs 0.8 x 0.85 = 0.68 and is dry; the level comes from the three wet
    // cells (20, 9), (21, 9), (21, 10) with weights 0.12, 0.03, 0.17.
    const double w[3] = {0.8 * 0.15, 0.2 * 0.15, 0.2 * 0.85};
    const double lv[3] = {0.01 * 0.41 - 0.003 * 0.19, 0.01 * 0.43 - 0.003 * 0.19, 0.01 * 0.43 - 0.003 * 0.21};
    EXPECT_NEAR(eta[1], (w[0] * lv[0] + w[1] * lv[1] + w[2] * lv[2]) / (w[0] + w[1] + w[2]), 1e-7);
    const auto h = f.get_float(f.var("gauge_h"));  // the roof's cell counts with depth 0
    EXPECT_NEAR(h[1], w[0] * (lv[0] + 0.1) + w[1] * (lv[1] + 0.1) + w[2] * (lv[2] + 0.1), 1e-7);
}

// The runup outputs by hand on a 4 x 2 beach: ground -0.1, 0, 0.02, 0.05 m along x (the
// same in both rows), largest depths 0.1, 0.01, 0.0005 and 0 m in the south row and
// 0.1, 0.0015, 0, 0 m in the north row, flood depth 1 mm. Flooded: the first two cells of
// each row (0.5 mm is below the threshold); the highest flooded ground is 0 m, first
// reached at (i 1, j 0); max_level z + max_depth where the cell was ever wet, else NaN.
TEST(HydroRun, RunupOutputsByHand) {
    const Grid g{4, 2, 0.5, 0.25, 1.0, 0.5};
    const std::vector<float> z = {-0.1f, 0.0f, 0.02f, 0.05f, -0.1f, 0.0f, 0.02f, 0.05f};
    const std::vector<float> max_depth = {0.1f, 0.01f, 0.0005f, 0.0f, 0.1f, 0.0015f, 0.0f, 0.0f};
    const RunupSummary r = runup_summary(g, z, max_depth, 0.001);
    EXPECT_EQ(r.flooded, (std::vector<std::int8_t>{1, 1, 0, 0, 1, 1, 0, 0}));
    EXPECT_EQ(r.elevation, 0.0);
    EXPECT_EQ(r.x, 1.5);
    EXPECT_EQ(r.y, 0.25);
    EXPECT_FLOAT_EQ(r.max_level[1], 0.01f);
    EXPECT_FLOAT_EQ(r.max_level[2], 0.0205f);
    EXPECT_TRUE(std::isnan(r.max_level[3]));
    EXPECT_TRUE(std::isnan(r.max_level[6]));
    // Nothing flooded: NaN position and elevation.
    const RunupSummary dry = runup_summary(g, z, std::vector<float>(8, 0.0f), 0.001);
    EXPECT_TRUE(std::isnan(dry.elevation));
    EXPECT_TRUE(std::isnan(dry.x));
}

// A scene's recommended nesting (the Kainan layout recommends nest-ratio 4) is for finite
// volumes: with --scheme leapfrog the run takes the scene's other recommendations and
// one grid, instead of refusing to start.
TEST(HydroCli, LeapfrogOnASceneThatRecommendsNesting) {
    const std::string real = test::shared_data("city-topography-from-figure.nc");
    if (real.empty()) GTEST_SKIP() << "../shared/data/city-topography-from-figure.nc not found";
    const std::string dir = test::scratch_dir("leapfrog_scene_nesting");
    std::string out;
    ASSERT_EQ(test::run_cli("scene import --dem " + real + " --resolution 0.16 --out " + dir + "/real.nc", &out), 0) << out;
    ASSERT_EQ(test::run_cli("hydro --scene " + dir +
                                "/real.nc --west pump --scheme leapfrog --duration 2 --output-interval 1 --out " + dir + "/lf.nc",
                            &out),
              0)
        << out;
    EXPECT_NE(out.find("recommended settings"), std::string::npos) << out;
    EXPECT_EQ(out.find("nest-ratio"), std::string::npos) << out;
    ASSERT_EQ(test::run_cli(
                  "hydro --scene " + dir + "/real.nc --west pump --duration 2 --output-interval 1 --out " + dir + "/fv.nc", &out),
              0)
        << out;
    EXPECT_NE(out.find("nest-ratio = 4"), std::string::npos) << out;
}

// pipelines.resolution_cost (the hydro cost chart): two records, the second grid a
// copy of the reference with WG2 raised by 1 mm in record r01 only; every other measure
// is zero (LD does not flood in 8 s: no draft time). The costs come from the make log's
// run summaries: a continued flow's parts summed, a flow with a part that left no summary
// left out.
TEST(HydroRun, ResolutionCostTableComparesRecordsAndTakesCostsFromTheLog) {
    const auto dir = test::scratch_dir("resolution_cost");
    std::string out;
    ASSERT_EQ(test::run_cli("scene generate --resolution 0.32 --out " + dir + "/scene.nc", &out), 0) << out;
    ASSERT_EQ(test::run_cli("boundary generate --count 2 --duration 8 --out-dir " + dir + "/bc", &out), 0) << out;
    std::filesystem::create_directories(dir + "/ref");
    for (const char* r : {"00", "01"})
        ASSERT_EQ(test::run_cli("hydro --scene " + dir + "/scene.nc --west level --west-series " + dir + "/bc/wg1_r" + r +
                                    ".csv --duration 8 --output-interval 1 --quiet --out " + dir + "/ref/flow_r" + r + ".nc",
                                &out),
                  0)
            << out;
    const std::string setup = "cd " + dir + " && cp -r ref test && /usr/bin/python3 -c \"import netCDF4 as nc; "
                              "d = nc.Dataset('test/flow_r01.nc', 'a'); names = [str(n) for n in d['gauge_name'][:]]; "
                              "k = names.index('WG2'); d['gauge_eta'][:, k] = d['gauge_eta'][:, k] + 0.001; d.close()\"";
    ASSERT_EQ(std::system(setup.c_str()), 0);
    // r00 was interrupted and continued: its two parts chain from t = 0 and add up to 12 s.
    // r01's first part was killed without a summary, so its cost is unknown: left out.
    test::write_file(dir, "ref.log",
                     "  --label hydro-r00 --out ref/flow_r00.nc\n"
                     "  --label hydro-r01 --out ref/flow_r01.nc\n"
                     "hydro-r00: interrupted (SIGTERM) after 60 steps (t = 0 to 4 s) in 11.0 s wall (7.0 s processor), "
                     "1e+06 cell-updates/s\n"
                     "  --label hydro-r00 --out ref/flow_r00.nc --restart\n"
                     "  --label hydro-r01 --out ref/flow_r01.nc --restart\n"
                     "hydro-r00: complete after 40 steps (t = 4 to 8 s) in 9.0 s wall (5.0 s processor), 1e+06 cell-updates/s\n"
                     "hydro-r01: complete after 50 steps (t = 3 to 8 s) in 9.0 s wall (5.0 s processor), 1e+06 cell-updates/s\n");
    const std::string cmd = "cd " FLOTSAM_SOURCE_DIR " && /usr/bin/python3 -m pipelines.resolution_cost " + dir +
                            "/scene.nc 'fine=" + dir + "/ref:" + dir + "/ref.log' 'coarse=" + dir + "/test' > " + dir +
                            "/table.md 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream f(dir + "/table.md");
    const std::string table((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    ASSERT_EQ(rc, 0) << table;
    EXPECT_NE(table.find("| fine | 12 (1 flows) | r00, r01 | reference |"), std::string::npos) << table;
    EXPECT_NE(table.find("| coarse | – | r00, r01 | 0.50 (0.00 … 1.00) | +0.50 (+0.00 … +1.00) | 0.00 (0.00 … 0.00) | "
                         "+0.00 (+0.00 … +0.00) | 0.00 (0.00 … 0.00) | – |"),
              std::string::npos)
        << table;
}

// The stall watch: a step 1000 times below the run's median for more than 20 steps in a
// row stops the run; a step that changes tenfold, or dips for a few steps, does not.
TEST(StepWatch, ACollapsedStepStopsTheRunAndOrdinaryChangesDoNot) {
    StepWatch ordinary;
    for (int n = 0; n < 500; ++n) EXPECT_FALSE(ordinary.stalled(n < 250 ? 1e-3 : 1e-4));  // a wave arrives: 10x
    for (int n = 0; n < collapse_steps; ++n) EXPECT_FALSE(ordinary.stalled(1e-9));        // a dip of 20 steps
    EXPECT_FALSE(ordinary.stalled(1e-3));
    EXPECT_NEAR(ordinary.median(), 1e-4, 0.03e-4);  // 270 of 521 steps at most 1e-4 s; bins of 2.3 %

    StepWatch sudden;
    for (int n = 0; n < 100; ++n) EXPECT_FALSE(sudden.stalled(1e-3));
    for (int n = 0; n < collapse_steps; ++n) EXPECT_FALSE(sudden.stalled(0.9e-6));
    EXPECT_TRUE(sudden.stalled(0.9e-6));  // the 21st step in a row below 1e-6

    // A slow decline, 2 % a step (the tracked fronts on Thacker's bowl): the median of the
    // whole run lags it. After 100 level steps and k > 100 declining ones the median is the
    // decline's ((k - 100)/2)-th step, so 0.98^k < 1e-3 · 0.98^((k - 100)/2) once
    // k > 2 ln(1e-3)/ln(0.98) - 100 = 584; then 20 steps more: stopped near n = 705.
    StepWatch slow;
    int n = 0;
    for (; n < 100; ++n) ASSERT_FALSE(slow.stalled(1e-3));
    double dt = 1e-3;
    while (!slow.stalled(dt) && n < 5000) dt *= 0.98, ++n;
    EXPECT_NEAR(n, 705, 5);
    EXPECT_LT(dt, 1e-3 * slow.median());
}

// A run whose step collapses stops with a named error: the time, the cell setting the
// step and what is there, and no flow file. Here a level record whose units went wrong
// floods a 0.1 mm sheet of water with 50 m at t = 1050 s: the step, 25.8 s in the sheet
// (cfl dx / sqrt(g h), 1 m cells), falls more than a thousandfold in the bore that runs
// in (measured: to 8e-4 s, the bore 1.4 km deep at 900 m/s by then), and the run stops
// 21 steps later instead of creeping on.
TEST(HydroCli, AStalledRunStopsWithTheCellThatSetTheStep) {
    const std::string dir = test::scratch_dir("hydro_stall");
    Scene s = test::flat_scene(100, 4, 1.0, 0.0, -1e-4);
    s.title = "a sheet of water";
    write_scene(dir + "/sheet.nc", s, "test");
    write_file(dir, "level.csv", "time,level\n0,0\n1050,0\n1060,50\n2000,50\n");
    std::string out;
    const int rc = test::run_cli("hydro --scene " + dir + "/sheet.nc --west level --west-series " + dir +
                                     "/level.csv --max-dt 100 --duration 1100 --output-interval 1100 --nest-ratio 1 --quiet --out " +
                                     dir + "/flow.nc",
                                 &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("the time step collapsed to"), std::string::npos) << out;
    EXPECT_NE(out.find("The fastest water sets it: cell (i "), std::string::npos) << out;
    EXPECT_NE(out.find(" m/s, bed -0.0001 m"), std::string::npos) << out;
    EXPECT_NE(out.find("no flow file was written"), std::string::npos) << out;
    EXPECT_FALSE(std::filesystem::exists(dir + "/flow.nc"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/flow.nc.part"));
}

// The settings a flow records (its flotsam_config, written from the option table),
// given back with --config, reproduce the flow: the same fields and the same attributes
// but the command line (history). Settings of each kind go through: numbers, a list, a
// choice given by name, a study option, a series path and a gauge.
TEST(HydroCli, TheRecordedSettingsGivenBackWithConfigReproduceTheFlow) {
    const std::string dir = test::scratch_dir("hydro_config_reproduces");
    const std::string scene = make_scene(dir), series = make_series(dir);
    std::string out;
    ASSERT_EQ(test::run_cli("hydro --scene " + scene + " --west level --west-series " + series +
                                " --east wall --level-mode incident --duration 2 --output-interval 0.5 --cfl 0.6 --order 1"
                                " --time-stepping heun --output-window 0.1,0.9,0,0.4 --gauge X,0.5,0.2 --quiet --out " +
                                dir + "/a.nc",
                            &out),
              0)
        << out;
    const std::string recorded = *nc::File::open_read(dir + "/a.nc").att_text(NC_GLOBAL, "flotsam_config");
    EXPECT_NE(recorded.find("time-stepping=\"heun\""), std::string::npos) << recorded;
    EXPECT_NE(recorded.find("output-window=[0.1, 0.9, 0, 0.4]"), std::string::npos) << recorded;
    const std::string config = write_file(dir, "a.toml", recorded);
    ASSERT_EQ(test::run_cli("hydro --config " + config + " --quiet --out " + dir + "/b.nc", &out), 0) << out;

    const nc::File a = nc::File::open_read(dir + "/a.nc"), b = nc::File::open_read(dir + "/b.nc");
    ASSERT_EQ(a.att_names(NC_GLOBAL), b.att_names(NC_GLOBAL));
    for (const auto& name : a.att_names(NC_GLOBAL)) {
        if (name == "history") continue;
        EXPECT_EQ(a.att_text(NC_GLOBAL, name), b.att_text(NC_GLOBAL, name)) << name;
    }
    int vars_a = 0, vars_b = 0;
    nc_inq_nvars(a.id(), &vars_a);
    nc_inq_nvars(b.id(), &vars_b);
    ASSERT_EQ(vars_a, vars_b);
    ASSERT_GT(vars_a, 10);
    for (int v = 0; v < vars_a; ++v) {
        ASSERT_EQ(a.var_name(v), b.var_name(v));
        nc_type type = NC_NAT;
        nc_inq_vartype(a.id(), v, &type);
        if (type == NC_CHAR || type == NC_STRING) continue;
        const std::vector<double> va = a.get_double(v), vb = b.get_double(v);
        ASSERT_EQ(va.size(), vb.size()) << a.var_name(v);
        for (std::size_t k = 0; k < va.size(); ++k)
            ASSERT_TRUE(va[k] == vb[k] || (std::isnan(va[k]) && std::isnan(vb[k]))) << a.var_name(v) << "[" << k << "]";
    }
}
