#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "common/scene.hpp"
#include "debris/flow_reader.hpp"
#include "tests/debris_flows.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using test::error_of;
using test::write_file;
using namespace flotsam::debris;

namespace {
const Grid grid{20, 12, -1.0, 2.0, 0.1, 0.05};
}  // namespace

// Fields linear in x, y and t are reproduced exactly (to float storage) by linear-in-
// time, bilinear-in-space interpolation, and so is the depth-then-divide velocity when
// the depth is uniform.
TEST(FlowReader, LinearFieldsAreExact) {
    const auto dir = test::scratch_dir("fr_linear");
    auto h = [](double x, double y, double t) { return 0.2 + 0.05 * x - 0.03 * y + 0.01 * t; };
    auto u = [](double x, double y, double t) { return 0.3 + 0.2 * x + 0.1 * y - 0.02 * t; };
    const auto path = test::write_flow(dir + "/f.nc", grid, {0.0, 2.0, 4.0}, [](double, double) { return -0.5; },
                                       [&](double x, double y, double t) { return test::FlowState{float(h(x, y, t)), float(u(x, y, t)), 0.0f}; });
    FlowReader r(path);
    r.prepare(2.5);
    const double x = -0.437, y = 2.213, t = 2.7;
    EXPECT_NEAR(r.depth(x, y, t), h(x, y, t), 2e-7);
    // A uniform-depth file for the velocity.
    const auto path2 = test::write_flow(dir + "/g.nc", grid, {0.0, 2.0, 4.0}, [](double, double) { return -0.5; },
                                        [&](double x2, double y2, double t2) { return test::FlowState{0.3f, float(u(x2, y2, t2)), 0.0f}; });
    FlowReader r2(path2);
    r2.prepare(2.5);
    const FlowPoint p = r2.sample(x, y, t);
    EXPECT_NEAR(p.u, u(x, y, t), 1e-6);
    EXPECT_NEAR(p.v, 0.0, 1e-12);
}

// Du/Dt = ∂u/∂t + u ∂u/∂x + v ∂u/∂y for u = a + b x + c t, v = e + f y at uniform depth.
TEST(FlowReader, MaterialAccelerationOfAnalyticField) {
    const auto dir = test::scratch_dir("fr_accel");
    const double a = 0.2, b = 0.3, c = 0.05, e = -0.1, f = 0.4;
    const auto path = test::write_flow(dir + "/f.nc", grid, {0.0, 1.0, 2.0}, [](double, double) { return -0.5; },
                                       [&](double x, double y, double t) {
                                           return test::FlowState{0.25f, float(a + b * x + c * t), float(e + f * y)};
                                       });
    FlowReader r(path);
    r.prepare(1.2);
    const double x = -0.33, y = 2.31, t = 1.4;
    const FlowPointAccel p = r.sample_accel(x, y, t);
    const double u = a + b * x + c * t, v = e + f * y;
    EXPECT_NEAR(p.du_dt, c + u * b, 1e-5);
    EXPECT_NEAR(p.dv_dt, v * f, 1e-5);
}

// At a wetting front (one wet corner, the others dry) the velocity from interpolated
// discharge over interpolated depth is a depth-weighted mean of the corner velocities,
// so it never exceeds the fastest corner, however thin the water.
TEST(FlowReader, WettingFrontGivesBoundedSpeed) {
    const auto dir = test::scratch_dir("fr_front");
    const auto path = test::write_flow(dir + "/f.nc", grid, {0.0, 1.0}, [](double, double) { return 0.0; },
                                       [&](double x, double y, double t) {
                                           const bool wet = x < -0.55 && (t > 0.5 || y < 2.2);
                                           return wet ? test::FlowState{0.004f, 1.5f, -0.7f} : test::FlowState{};
                                       });
    FlowReader r(path);
    r.prepare(0.0);
    double max_speed = 0.0;
    for (int k = 0; k <= 100; ++k)
        for (int m = 0; m <= 40; ++m) {
            const FlowPoint p = r.sample(-0.7 + 0.004 * k, 2.0 + 0.01 * m, 0.01 * (k % 100));
            max_speed = std::max(max_speed, std::hypot(p.u, p.v));
        }
    EXPECT_LE(max_speed, std::hypot(1.5, 0.7) * (1 + 1e-6));
    EXPECT_GT(max_speed, 1.0);  // the wet side does carry the speed
}

TEST(FlowReader, HoldsLastFrameAndLoadsFramesOnce) {
    const auto dir = test::scratch_dir("fr_hold");
    const auto path = test::write_flow(dir + "/f.nc", grid, {0.0, 1.0, 2.0, 3.0}, [](double, double) { return -0.5; },
                                       [](double, double, double t) { return test::FlowState{0.2f, float(0.1 * t), 0.0f}; });
    FlowReader r(path);
    for (double t = 0.0; t < 3.0; t += 0.25) r.prepare(t);
    EXPECT_EQ(r.frames_loaded(), 4u);  // each frame read once while time advances
    r.prepare(7.0);
    const FlowPointAccel p = r.sample_accel(0.0, 2.2, 7.0);
    EXPECT_NEAR(p.u, 0.3, 1e-6);   // held
    EXPECT_EQ(p.du_dt, 0.0);       // steady past the end
    EXPECT_EQ(r.next_frame_time(7.0), 3.0);
}

TEST(FlowReader, SubWindowGivesTheSameValues) {
    const auto dir = test::scratch_dir("fr_window");
    const auto path = test::write_flow(dir + "/f.nc", grid, {0.0, 1.0}, [](double, double) { return -0.5; },
                                       [](double x, double y, double t) {
                                           return test::FlowState{float(0.2 + 0.1 * std::sin(7 * x) * std::cos(5 * y)), float(x * y + t), float(x - y)};
                                       });
    FlowReader full(path), part(path);
    part.set_window(part.cells_for(-0.5, -0.2, 2.1, 2.3));
    full.prepare(0.3);
    part.prepare(0.3);
    const FlowPointAccel a = full.sample_accel(-0.31, 2.17, 0.3), b = part.sample_accel(-0.31, 2.17, 0.3);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.u, b.u);
    EXPECT_EQ(a.du_dt, b.du_dt);
}

TEST(FlowReader, RejectsAFileThatIsNotAFlow) {
    const auto dir = test::scratch_dir("fr_bad");
    Scene s;
    s.grid = Grid{4, 3, 0.0, 0.0, 1.0, 1.0};
    s.z.assign(12, 0.0);
    write_scene(dir + "/scene.nc", s, "test");
    const std::string msg = error_of([&] { FlowReader r(dir + "/scene.nc"); });
    EXPECT_NE(msg.find("scene.nc"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not a flow file"), std::string::npos) << msg;
    EXPECT_NE(msg.find("sea_floor_depth_below_sea_surface"), std::string::npos) << msg;
}
