// Whole runs: determinism across thread counts, the CLI and its output. (The stability
// of the added-mass treatment: debris_stability_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>

#include "cases/debris_flows.hpp"
#include "common/netcdf.hpp"
#include "common/sha256.hpp"
#include "debris/world.hpp"
#include "formats/scene.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

const Grid grid{100, 60, -0.495, -0.295, 0.01, 0.01};

// A time-varying sheared current with a wetting front and a block of raised ground.
std::string varied_flow(const std::string& path) {
    std::vector<double> times;
    for (int k = 0; k <= 20; ++k) times.push_back(0.5 * k);
    auto bed = [](double x, double y) { return (x > 0.25 && y > -0.05 && y < 0.1) ? 0.05 : -0.03 + 0.02 * x; };
    return test::write_flow(path, grid, times, bed, [&](double x, double y, double t) {
        const double level = 0.002 * t;
        const double h = std::max(0.0, level - bed(x, y));
        const float u = float(0.3 + 0.5 * y + 0.05 * std::sin(t)), v = float(0.1 * std::cos(3 * x + 0.4 * t));
        return h > 0 ? test::FlowState{float(h), u, v} : test::FlowState{};
    });
}

std::string hash_positions(const World& w) {
    std::string bytes;
    for (const auto& s : w.states()) {
        for (double v : {s.x, s.y, s.theta, s.vx, s.vy, s.omega}) bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    return sha256_hex(bytes);
}

}  // namespace

// The read-ahead thread (on by default) changes nothing either.
TEST(DebrisRun, SameTrajectoriesOnOneAndTwoThreadsWithAndWithoutReadAhead) {
    const auto dir = test::scratch_dir("run_threads");
    const auto path = varied_flow(dir + "/f.nc");
    std::vector<std::string> hashes;
    for (const auto& [threads, read_ahead] : {std::pair{1, true}, {2, true}, {1, false}, {2, false}}) {
        WorldDef def = default_world_def();
        def.threads = threads;
        def.read_ahead = read_ahead;
        World w(path, {}, def);
        for (int k = 0; k < 8; ++k) {
            BodyDef b = default_body_def();
            b.x = -0.3 + 0.07 * k;
            b.y = -0.1 + 0.02 * k;
            b.heading = 0.3 * k;
            b.contact = k % 2 ? ContactModel::local : ContactModel::center;
            b.collision = k % 3 ? CollisionModel::multi : CollisionModel::single;
            w.add_body(b);
        }
        std::string trail;
        for (int k = 1; k <= 20; ++k) {
            w.advance_to(0.5 * k);
            trail += hash_positions(w);
        }
        long steps = 0;
        for (const auto& s : w.stats()) steps += s.steps;
        EXPECT_GT(steps, 8 * 500);
        hashes.push_back(sha256_hex(trail));
    }
    EXPECT_EQ(hashes[0], hashes[1]);
    EXPECT_EQ(hashes[0], hashes[2]);
    EXPECT_EQ(hashes[0], hashes[3]);
}

TEST(DebrisRun, CliWritesTheSameTrajectoryFileTwice) {
    const auto dir = test::scratch_dir("run_cli");
    const auto flow = varied_flow(dir + "/f.nc");
    Scene scene;
    scene.grid = grid;
    const auto bed = debris::FlowReader(flow).description().bed;  // the scene the flow was computed on (a replay checks it)
    scene.z.assign(bed.begin(), bed.end());
    scene.building.assign(grid.size(), 0);
    for (int j = 0; j < grid.ny; ++j) scene.building[grid.index(80, j)] = 1;
    scene.points.push_back({"FD", "start", -0.2, 0.0, 15.0});
    scene.points.push_back({"WG", "gauge", 0.0, 0.0, 0.0});
    write_scene(dir + "/scene.nc", scene, "test");
    const std::string args =
        "debris --flow " + flow + " --scene " + dir + "/scene.nc --start FD --at 0.1,0.05,90 --output-interval 0.25 --quiet";
    std::string out;
    ASSERT_EQ(test::run_cli(args + " --out " + dir + "/a.nc", &out), 0) << out;
    ASSERT_EQ(test::run_cli(args + " --out " + dir + "/b.nc", &out), 0) << out;
    // The history attribute holds the command line, so compare files written with the same one.
    ASSERT_EQ(test::run_cli(args + " --out " + dir + "/a.nc", &out), 0) << out;
    const std::string first = sha256_file(dir + "/a.nc");
    ASSERT_EQ(test::run_cli(args + " --out " + dir + "/a.nc", &out), 0) << out;
    EXPECT_EQ(sha256_file(dir + "/a.nc"), first);

    const nc::File f = nc::File::open_read(dir + "/b.nc");
    EXPECT_EQ(f.att_text(NC_GLOBAL, "featureType").value_or(""), "trajectory");
    EXPECT_EQ(f.att_text(f.var("trajectory_id"), "cf_role").value_or(""), "trajectory_id");
    EXPECT_EQ(f.dim_length("trajectory"), 2u);
    EXPECT_EQ(f.dim_length("time"), 41u);  // 0 .. 10 s every 0.25 s
    EXPECT_EQ(f.get_strings(f.var("start_name"))[0], "FD");
    EXPECT_EQ(f.get_strings(f.var("contact_model"))[1], "local");
    const auto yaw = f.get_double(f.var("yaw"));
    EXPECT_NEAR(yaw[0], 15.0, 1e-9);
    EXPECT_NEAR(yaw[41], 90.0, 1e-9);

    EXPECT_NE(test::run_cli("debris --flow " + dir + "/scene.nc --at 0,0,0 --out " + dir + "/c.nc", &out), 0);
    EXPECT_NE(out.find("not a flow file"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("debris --flow " + flow + " --scene " + dir + "/scene.nc --start WG --out " + dir + "/c.nc", &out), 0);
    EXPECT_NE(out.find("no start point"), std::string::npos) << out;
    for (const char* bad : {"--time-interpolation spline", "--integrator rk4", "--vertex-step-fraction 0"}) {
        EXPECT_NE(test::run_cli("debris --flow " + flow + " --at 0,0,0 " + bad + " --out " + dir + "/c.nc", &out), 0) << bad;
        EXPECT_NE(out.find(std::string(bad).substr(0, std::string(bad).find(' '))), std::string::npos) << out;
    }
    // The choices are recorded in the file.
    ASSERT_EQ(test::run_cli(args + " --time-interpolation cubic --integrator heun --out " + dir + "/d.nc", &out), 0) << out;
    const nc::File d = nc::File::open_read(dir + "/d.nc");
    EXPECT_EQ(d.att_text(NC_GLOBAL, "time_interpolation").value_or(""), "cubic");
    EXPECT_EQ(d.att_text(NC_GLOBAL, "integrator").value_or(""), "heun");
}
