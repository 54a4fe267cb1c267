#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include "cases/debris_flows.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "debris/flow_reader.hpp"
#include "formats/scene.hpp"
#include "formats/tile_decoder.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using test::error_of;
using test::write_file;
using namespace flotsam::debris;

namespace {
const Grid grid{20, 12, -1.0, 2.0, 0.1, 0.05};

// A flow that varies in x, y and t on unevenly spaced frames, wet everywhere.
std::string uneven_flow(const std::string& path) {
    return test::write_flow(
        path, grid, {0.0, 1.0, 2.0, 3.0, 4.5, 6.0}, [](double, double) { return -0.5; },
        [](double x, double y, double t) {
            const double h = 0.05 + 0.04 * std::sin(3 * x + t) * std::cos(4 * y - 0.7 * t) + 0.03 * t;
            return test::FlowState{float(std::max(0.0, h)), float(x * y + 0.2 * t), float(std::cos(x - t) - y)};
        });
}
}  // namespace

// Fields linear in x, y and t are reproduced exactly (to float storage) by linear-in-
// time, bilinear-in-space interpolation, and so is the depth-then-divide velocity when
// the depth is uniform.
TEST(FlowReader, LinearFieldsAreExact) {
    const auto dir = test::scratch_dir("fr_linear");
    auto h = [](double x, double y, double t) { return 0.2 + 0.05 * x - 0.03 * y + 0.01 * t; };
    auto u = [](double x, double y, double t) { return 0.3 + 0.2 * x + 0.1 * y - 0.02 * t; };
    const auto path = test::write_flow(
        dir + "/f.nc", grid, {0.0, 2.0, 4.0}, [](double, double) { return -0.5; },
        [&](double x, double y, double t) {
            return test::FlowState{float(h(x, y, t)), float(u(x, y, t)), 0.0f};
        });
    FlowReader r(path);
    r.prepare(2.5);
    const double x = -0.437, y = 2.213, t = 2.7;
    EXPECT_NEAR(r.depth(x, y, t), h(x, y, t), 2e-7);
    // A uniform-depth file for the velocity.
    const auto path2 = test::write_flow(
        dir + "/g.nc", grid, {0.0, 2.0, 4.0}, [](double, double) { return -0.5; },
        [&](double x2, double y2, double t2) {
            return test::FlowState{0.3f, float(u(x2, y2, t2)), 0.0f};
        });
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
    const auto path = test::write_flow(
        dir + "/f.nc", grid, {0.0, 1.0, 2.0}, [](double, double) { return -0.5; },
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
// A thin, fast film at one corner of a cell (a wetting front racing ahead, as shallow-
// water solvers write it: 0.1 mm at 5 m/s) beside deep, slow water (10 cm at 0.5 m/s).
// Depth-then-divide weighs each corner's velocity by its depth, so the film barely moves
// the velocity at the cell centre: (½·0.1·0.5 + ½·1e-4·5)/(½·0.1 + ½·1e-4) = 0.5045 m/s.
// Interpolating the velocity itself would give the plain mean, 2.75 m/s. And in a cell
// half wet with equal velocities, the wet side's speed is kept exactly (u interpolation
// would average it with the dry corners' zeros).
TEST(FlowReader, ThinFastFilmBarelyMovesTheVelocity) {
    const auto dir = test::scratch_dir("fr_film");
    const Grid g{8, 4, 0.05, 0.05, 0.1, 0.1};  // nodes at x = 0.05, 0.15, ...
    const auto path = test::write_flow(
        dir + "/f.nc", g, {0.0, 1.0}, [](double, double) { return 0.0; },
        [&](double x, double y, double) {
            if (y > 0.2) return x < 0.3 ? test::FlowState{0.02f, 1.5f, -0.7f} : test::FlowState{};
            return x < 0.2 ? test::FlowState{0.1f, 0.5f, 0.0f} : test::FlowState{1e-4f, 5.0f, 0.0f};
        });
    for (TimeInterpolation interp : {TimeInterpolation::linear, TimeInterpolation::cubic}) {
        FlowReaderDef def;
        def.time_interpolation = interp;
        FlowReader r(path, def);
        r.prepare(0.5);
        const FlowPoint film = r.sample(0.2, 0.1, 0.5);  // between nodes x = 0.15 (deep) and 0.25 (film)
        EXPECT_NEAR(film.u, (0.5 * 0.1 * 0.5 + 0.5 * 1e-4 * 5.0) / (0.5 * 0.1 + 0.5 * 1e-4), 1e-5) << enum_name(interp);
        const FlowPoint front = r.sample(0.3, 0.3, 0.5);  // between x = 0.25 (wet) and 0.35 (dry)
        EXPECT_NEAR(front.u, 1.5, 1e-5) << enum_name(interp);
        EXPECT_NEAR(front.v, -0.7, 1e-5) << enum_name(interp);
    }
}

TEST(FlowReader, WettingFrontGivesBoundedSpeed) {
    const auto dir = test::scratch_dir("fr_front");
    const auto path = test::write_flow(
        dir + "/f.nc", grid, {0.0, 1.0}, [](double, double) { return 0.0; },
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
    const auto path = test::write_flow(
        dir + "/f.nc", grid, {0.0, 1.0, 2.0, 3.0, 4.0, 5.0}, [](double, double) { return -0.5; },
        [](double, double, double t) {
            return test::FlowState{0.2f, float(0.1 * t), 0.0f};
        });
    for (TimeInterpolation interp : {TimeInterpolation::linear, TimeInterpolation::cubic}) {
        FlowReaderDef def;
        def.time_interpolation = interp;
        FlowReader r(path, def);
        for (double t = 0.0; t < 5.0; t += 0.25) r.prepare(t);
        EXPECT_EQ(r.read_stats().frames_loaded, 6u) << enum_name(interp);  // each frame read once while time advances
        r.prepare(7.0);
        const FlowPointAccel p = r.sample_accel(0.0, 2.2, 7.0);
        EXPECT_NEAR(p.u, 0.5, 1e-6);  // held
        EXPECT_EQ(p.du_dt, 0.0);      // steady past the end
        EXPECT_EQ(r.next_frame_time(7.0), 5.0);
    }
}

// The cubic (Catmull-Rom) is exact for a field quadratic in time at even frame spacing,
// and its Du/Dt is the derivative of that same interpolant; the linear one is not.
TEST(FlowReader, CubicIsExactForQuadraticInTime) {
    const auto dir = test::scratch_dir("fr_cubic");
    const double a = 0.2, c = 0.03;  // u = a + c t² at uniform depth
    const auto path = test::write_flow(
        dir + "/f.nc", grid, {0.0, 1.0, 2.0, 3.0, 4.0}, [](double, double) { return -0.5; },
        [&](double, double, double t) {
            return test::FlowState{0.25f, float(a + c * t * t), 0.0f};
        });
    FlowReaderDef def;
    def.time_interpolation = TimeInterpolation::cubic;
    FlowReader cubic(path, def), linear(path);
    const double t = 2.3;
    cubic.prepare(t);
    linear.prepare(t);
    const FlowPointAccel pc = cubic.sample_accel(-0.4, 2.2, t), pl = linear.sample_accel(-0.4, 2.2, t);
    EXPECT_NEAR(pc.u, a + c * t * t, 1e-6);
    EXPECT_NEAR(pc.du_dt, 2 * c * t, 1e-5);
    EXPECT_GT(std::fabs(pl.u - (a + c * t * t)), 5e-3);  // the linear interpolant cuts the corner: c Δ² s(1 − s) = 6.3 mm/s
    EXPECT_NEAR(pl.du_dt, c * (2 * 2 + 1), 1e-5);        // the secant slope of [2, 3]
}

// Stability map of the time interpolants: a cubic in time undershoots where the depth
// at a node has a trough or a wetting front between frames. Without a guard its depth
// is negative (shown with the same weights); the guard falls back to the linear
// interpolant there, so the depth stays ≥ 0 and never below the shallower of the two
// frames around t; a peak between frames (overshoot upwards) keeps the cubic's value.
TEST(FlowReader, CubicGuardKeepsDepthPositiveWhereTheCubicUndershoots) {
    const auto dir = test::scratch_dir("fr_guard");
    const std::vector<double> times = {0.0, 1.0, 2.0, 3.0};
    FlowReaderDef def;
    def.time_interpolation = TimeInterpolation::cubic;
    struct Case {
        const char* name;
        double h[4];    // the depth at frames 0..3 [m]
        double linear;  // the linear value at t = 1.5 [m]
    };
    const Case cases[] = {{"trough", {0.1, 0.001, 0.001, 0.1}, 0.001},
                          {"wetting front", {0.0, 0.0, 0.0, 0.05}, 0.0},
                          {"peak", {0.01, 0.05, 0.05, 0.01}, 0.05}};
    const TimeWeights w = catmull_rom_time_weights(0.5, 1.0, 0.5, 0.5);  // t = 1.5, frames k−1 … k+2 = 0 … 3
    for (const Case& c : cases) {
        const auto path = test::write_flow(
            dir + "/f.nc", grid, times, [](double, double) { return -0.5; },
            [&](double, double, double t) {
                const float h = float(c.h[int(t)]);
                return test::FlowState{h, h > 0 ? 0.4f : 0.0f, 0.0f};
            });
        FlowReader r(path, def);
        r.prepare(1.5);
        const double unguarded = apply_time_weights(w.w, c.h[0], c.h[1], c.h[2], c.h[3]);
        const FlowPoint p = r.sample(-0.37, 2.21, 1.5);
        if (std::string(c.name) == "peak") {
            EXPECT_NEAR(unguarded, 0.055, 1e-9);
            EXPECT_NEAR(p.depth, unguarded, 1e-7) << c.name;  // the cubic's peak is kept
            EXPECT_NEAR(p.u, 0.4, 1e-6);
        } else {
            EXPECT_LT(unguarded, -1e-3) << c.name;  // the cubic alone goes negative
            EXPECT_GE(p.depth, 0.0) << c.name;
            EXPECT_NEAR(p.depth, c.linear, 1e-9) << c.name;
        }
        EXPECT_GE(r.depth(-0.37, 2.21, 1.5), r.min_depth(r.cells_for(-0.37, -0.37, 2.21, 2.21)) - 1e-9) << c.name;
    }
}

TEST(FlowReader, SubWindowGivesTheSameValues) {
    const auto dir = test::scratch_dir("fr_window");
    const auto path = test::write_flow(
        dir + "/f.nc", grid, {0.0, 1.0}, [](double, double) { return -0.5; },
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

// The replay as a sweep drives it: time advances frame by frame, frames read anew reuse
// the arrays of frames no longer needed, and every third sample the window moves to
// follow a point that crosses the grid: it starts at the window's south-west edge (its
// own stencil cells are the window's first ones), moves across it and out of it. Every sample, at the point and at its
// neighbours inside the window, equals to the bit what a fresh reader of the whole grid
// gives, for both interpolants, through the per-time stencil (TimeStencil) too, and
// sampled all together.
TEST(FlowReader, MovingWindowAndReusedFramesGiveTheSameBits) {
    const auto dir = test::scratch_dir("fr_moving");
    const auto path = uneven_flow(dir + "/f.nc");
    for (TimeInterpolation interp : {TimeInterpolation::linear, TimeInterpolation::cubic}) {
        FlowReaderDef def;
        def.time_interpolation = interp;
        FlowReader moving(path, def);
        int compared = 0;
        for (int k = 0; k <= 120; ++k) {
            const double t = 0.05 * k;
            // From the south-west corner to the north-east one and beyond the grid's edge.
            const double x = -1.02 + 0.0175 * k, y = 1.99 + 0.0052 * k;
            if (k % 3 == 0) moving.set_window(moving.cells_for(x, x + 0.1, y, y + 0.06));
            moving.prepare(t);
            FlowReader fresh(path, def);
            fresh.prepare(t);
            const FlowReader::TimeStencil ts = moving.at_time(t);
            const CellWindow w = moving.window();
            std::vector<Vec2> served;  // sampled together below
            for (const double dx : {0.0, 0.03, -0.04})
                for (const double dy : {0.0, 0.02, -0.01}) {
                    const double px = x + dx, py = y + dy;
                    const CellWindow need = moving.cells_for(px, px, py, py);
                    if (!w.contains(need)) continue;  // only points the window serves
                    served.push_back({px, py});
                    const FlowPointAccel a = moving.sample_accel(px, py, t), b = fresh.sample_accel(px, py, t);
                    EXPECT_EQ(a.depth, b.depth) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(a.u, b.u) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(a.v, b.v) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(a.du_dt, b.du_dt) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(a.dv_dt, b.dv_dt) << enum_name(interp) << " t " << t;
                    const FlowPoint c = moving.sample(px, py, ts), d = fresh.sample(px, py, t);
                    EXPECT_EQ(c.depth, d.depth);
                    EXPECT_EQ(c.u, d.u);
                    EXPECT_EQ(c.v, d.v);
                    EXPECT_EQ(moving.depth(px, py, ts), fresh.depth(px, py, t));
                    EXPECT_EQ(moving.min_depth(need), fresh.min_depth(need));
                    ++compared;
                }
            // Many points at once (sample(p, n, ...), depth(p, n, ...)) give the same bits.
            const int n = int(served.size());
            std::vector<FlowPoint> at(served.size());
            std::vector<double> depth(served.size());
            moving.sample(served.data(), n, ts, at.data());
            moving.depth(served.data(), n, ts, depth.data());
            for (int q = 0; q < n; ++q) {
                const FlowPoint one = fresh.sample(served[q].x, served[q].y, t);
                EXPECT_EQ(at[q].depth, one.depth);
                EXPECT_EQ(at[q].u, one.u);
                EXPECT_EQ(at[q].v, one.v);
                EXPECT_EQ(depth[q], one.depth);
            }
        }
        EXPECT_GT(compared, 300) << enum_name(interp);
        // A window's move reads the frames held (2 linear, 4 cubic) again; otherwise each
        // frame is read once: 41 moves and 6 frames.
        EXPECT_LE(moving.read_stats().frames_loaded, 41u * (interp == TimeInterpolation::cubic ? 4u : 2u) + 6u) << enum_name(interp);
    }
}

// Read-ahead, as a World runs it: after each prepare(t) the next frame is read on the
// other thread while samples are taken; now and then the window moves (dropping a frame
// read on the old window), at times just as a new frame is needed. Every sample equals
// to the bit what a reader that reads each frame itself gives, for both interpolants,
// and the frames read ahead are the ones used.
TEST(FlowReader, ReadAheadGivesTheSameBitsAsReadingInTurn) {
    const auto dir = test::scratch_dir("fr_ahead");
    const auto path = uneven_flow(dir + "/f.nc");
    for (TimeInterpolation interp : {TimeInterpolation::linear, TimeInterpolation::cubic}) {
        FlowReaderDef def;
        def.time_interpolation = interp;
        FlowReader in_turn(path, def), ahead(path, def);
        int compared = 0;
        for (int k = 0; k <= 120; ++k) {
            const double t = 0.05 * k;
            const double x = -1.02 + 0.0175 * k, y = 1.99 + 0.0052 * k;
            if (k % 30 == 0) {  // frames are first needed at k = 20, 40, 60, 90, 120
                const CellWindow w = ahead.cells_for(x - 0.6, x + 0.6, y - 0.2, y + 0.2);
                in_turn.set_window(w);
                ahead.set_window(w);
            }
            in_turn.prepare(t);
            ahead.prepare(t);
            ahead.read_ahead(ahead.next_frame_time(t));
            for (const double dx : {0.0, 0.03, -0.04})
                for (const double dy : {0.0, 0.02, -0.01}) {
                    const double px = x + dx, py = y + dy;
                    const CellWindow need = ahead.cells_for(px, px, py, py);
                    if (!ahead.window().contains(need)) continue;
                    const FlowPointAccel a = ahead.sample_accel(px, py, t), b = in_turn.sample_accel(px, py, t);
                    EXPECT_EQ(a.depth, b.depth) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(a.u, b.u) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(a.v, b.v) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(a.du_dt, b.du_dt) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(a.dv_dt, b.dv_dt) << enum_name(interp) << " t " << t;
                    EXPECT_EQ(ahead.min_depth(need), in_turn.min_depth(need));
                    ++compared;
                }
            if (k % 2) ahead.finish_read_ahead();  // else prepare() takes a read maybe still under way
        }
        EXPECT_GT(compared, 500) << enum_name(interp);
        // Each frame first needed without a window move at the same step came from the
        // other thread (k = 20 and 40; the cubic needs frames 3 and 4 there: both), and
        // only reads dropped by a move are extra.
        EXPECT_GE(ahead.read_stats().frames_read_ahead, 2u) << enum_name(interp);
        EXPECT_LE(ahead.read_stats().frames_loaded, in_turn.read_stats().frames_loaded + 4u) << enum_name(interp);
    }
}

// A frame that fails the reader's checks is reported when it is needed, as without
// read-ahead: not while it is read ahead, and never if the window moves first.
TEST(FlowReader, ABadFrameReadAheadIsReportedWhereItIsNeeded) {
    const auto dir = test::scratch_dir("fr_ahead_bad");
    const auto path = test::write_flow(
        dir + "/f.nc", grid, {0.0, 1.0, 2.0}, [](double, double) { return -0.5; },
        [](double x, double, double t) {
            const bool bad = t == 2.0 && x > 0.5;
            return test::FlowState{bad ? std::nanf("") : 0.3f, 0.1f, 0.0f};
        });
    FlowReader r(path);
    r.prepare(0.5);
    r.read_ahead(1.0);  // frame 2
    r.finish_read_ahead();
    EXPECT_EQ(r.sample(0.0, 2.2, 0.5).depth, 0.3f);
    const std::string msg = error_of([&] { r.prepare(1.0); });
    EXPECT_NE(msg.find("f.nc"), std::string::npos) << msg;
    EXPECT_NE(msg.find("frame 2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("h = nan"), std::string::npos) << msg;

    FlowReader moved(path);
    moved.prepare(0.5);
    moved.read_ahead(1.0);
    moved.set_window(moved.cells_for(-0.9, -0.2, 2.1, 2.4));  // west of the bad cells
    EXPECT_NO_THROW(moved.prepare(1.0));
    EXPECT_EQ(moved.sample(-0.5, 2.2, 1.5).depth, 0.3f);
    // Moved east over them, the frame held is refit: its new tiles are read and checked.
    const std::string refit = error_of([&] { moved.set_window(moved.cells_for(-0.9, 0.8, 2.1, 2.4)); });
    EXPECT_NE(refit.find("frame 2"), std::string::npos) << refit;
    EXPECT_NE(refit.find("h = nan"), std::string::npos) << refit;
}

TEST(FlowReader, RejectsAFileThatIsNotAFlow) {
    const auto dir = test::scratch_dir("fr_bad");
    Scene s;
    s.grid = Grid{4, 3, 0.0, 0.0, 1.0, 1.0};
    s.z.assign(12, 0.0);
    write_scene(dir + "/scene.nc", s, "test");
    const std::string msg = error_of([&] { FlowReader r(dir + "/scene.nc"); });
    EXPECT_NE(msg.find("scene.nc: is a scene"), std::string::npos) << msg;  // its flotsam_file_kind
    EXPECT_NE(msg.find("not a flow file"), std::string::npos) << msg;
    // A file of no known kind (another program's) is read, and refused for what it lacks.
    nc::File other = nc::File::create(dir + "/other.nc");
    const int d = other.def_dim("n", 2);
    other.def_var("q", NC_DOUBLE, {d});
    other.close();
    const std::string lacking = error_of([&] { FlowReader r(dir + "/other.nc"); });
    EXPECT_NE(lacking.find("not a flow file"), std::string::npos) << lacking;
    EXPECT_NE(lacking.find("sea_floor_depth_below_sea_surface"), std::string::npos) << lacking;
}

// The dry tolerance is the run's: the file's dry_depth_m (as hydro writes it, text), or
// 1e-5 m where the file has none. Below it the velocity is zero.
TEST(FlowReader, DryToleranceComesFromTheFlowFile) {
    const auto dir = test::scratch_dir("fr_dry");
    auto write = [&](const std::string& name, const std::map<std::string, std::string>& attributes) {
        return test::write_flow(
            dir + "/" + name, grid, {0.0, 1.0}, [](double, double) { return 0.0; },
            [](double, double, double) {
                return test::FlowState{5e-4f, 0.2f, 0.0f};
            },
            attributes);
    };
    FlowReader with(write("with.nc", {{"dry_depth_m", "0.001000"}}));
    with.prepare(0.5);
    EXPECT_EQ(with.description().dry_depth, 1e-3);
    EXPECT_EQ(with.sample(0.0, 2.3, 0.5).u, 0.0);  // 0.5 mm is dry for this run

    FlowReader without(write("without.nc", {}));
    without.prepare(0.5);
    EXPECT_EQ(without.description().dry_depth, 1e-5);
    EXPECT_NEAR(without.sample(0.0, 2.3, 0.5).u, 0.2, 1e-6);

    for (const char* bad : {"wet", "0.000000", "-1"}) {
        const std::string path = write("bad.nc", {{"dry_depth_m", bad}});
        const std::string msg = error_of([&] { FlowReader r(path); });
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        EXPECT_NE(msg.find("dry_depth_m"), std::string::npos) << msg;
    }
}

namespace {
// A flow on 8 × 8 tiles (40 × 24 cells: 5 × 3 tiles) that varies in x, y and t and is
// dry in places, and a ground twice as fine under it with bumps of its own: for the
// tests of reading only some tiles.
struct TiledFlow {
    Grid grid{40, 24, 0.025, 0.025, 0.05, 0.05};
    Grid fine{80, 48, 0.0125, 0.0125, 0.025, 0.025};
    std::string path;
    std::vector<float> ground;  // [m] on `fine`
};
TiledFlow tiled_flow(const std::string& dir) {
    TiledFlow f;
    const auto bed = [](double x, double y) { return -0.01 + 0.01 * x - 0.005 * y; };
    f.path = test::write_flow(
        dir + "/f.nc", f.grid, {0.0, 1.0, 2.0, 3.5, 5.0}, bed,
        [](double x, double y, double t) {
            const double h = 0.01 + 0.03 * std::sin(3 * x + t) * std::cos(4 * y - 0.7 * t);  // dry in places
            return test::FlowState{float(std::max(0.0, h)), float(0.3 * x - 0.1 * t), float(0.2 * y + 0.05 * t)};
        },
        {}, 8);
    f.ground.resize(f.fine.size());
    for (int j = 0; j < f.fine.ny; ++j)
        for (int i = 0; i < f.fine.nx; ++i)
            f.ground[f.fine.index(i, j)] =
                float(bed(f.fine.x(i), f.fine.y(j)) + 0.004 * std::sin(40 * f.fine.x(i) + 30 * f.fine.y(j)));
    return f;
}
}  // namespace

// Two bodies far apart (set_regions): only the tiles (the file's 8 × 8 chunks here) under
// each region widened by region_margin are read. Region A, cells i 4..7, j 4..7, widens
// to i 1..10, j 1..10: tiles (0..1, 0..1); region B, i 30..33, j 14..17, to i 27..36,
// j 11..20: tiles (3..4, 1..2). The window is their bounding box widened to whole tiles,
// 5 × 3 tiles, of which 8 are read. Every sample the regions serve, over a finer ground too, equals to the bit
// what a reader of the whole grid gives, for both interpolants, as time advances.
TEST(FlowReader, RegionsReadOnlyTheirTilesAndGiveTheSameBits) {
    const TiledFlow flow = tiled_flow(test::scratch_dir("fr_regions"));
    const Grid& g = flow.grid;
    const std::string& path = flow.path;
    const CellWindow a{4, 8, 4, 8}, b{30, 34, 14, 18}, between{18, 22, 8, 12};
    for (TimeInterpolation interp : {TimeInterpolation::linear, TimeInterpolation::cubic})
        for (const bool on_ground : {false, true}) {
            FlowReaderDef def;
            def.time_interpolation = interp;
            FlowReader sparse(path, def), whole(path, def);
            if (on_ground) {
                sparse.set_ground(flow.fine, flow.ground);
                whole.set_ground(flow.fine, flow.ground);
            }
            sparse.set_regions({a, b});
            EXPECT_EQ(sparse.window(), (CellWindow{0, 40, 0, 24}));
            EXPECT_EQ(sparse.read_stats().tiles_loaded, 8u);
            EXPECT_TRUE(sparse.covers(a));
            EXPECT_TRUE(sparse.covers(b));
            EXPECT_FALSE(sparse.covers(between));
            EXPECT_TRUE(sparse.covers(CellWindow{4, 13, 4, 8}));   // widened: cells 1..15, tiles 0..1
            EXPECT_FALSE(sparse.covers(CellWindow{4, 14, 4, 8}));  // widened: cell 16, in tile 2
            int compared = 0;
            for (double t = 0.0; t <= 5.0; t += 0.45) {
                sparse.prepare(t);
                whole.prepare(t);
                for (const CellWindow& r : {a, b}) {
                    EXPECT_EQ(sparse.min_depth(r), whole.min_depth(r)) << t;
                    for (double fx = 0.0; fx <= 1.0; fx += 0.23)
                        for (double fy = 0.0; fy <= 1.0; fy += 0.31) {
                            const double x = g.x(r.i0) + fx * (g.x(r.i1 - 1) - g.x(r.i0));
                            const double y = g.y(r.j0) + fy * (g.y(r.j1 - 1) - g.y(r.j0));
                            const FlowPointAccel p = sparse.sample_accel(x, y, t), q = whole.sample_accel(x, y, t);
                            EXPECT_EQ(p.depth, q.depth) << x << ", " << y << ", " << t;
                            EXPECT_EQ(p.u, q.u);
                            EXPECT_EQ(p.du_dt, q.du_dt);
                            EXPECT_EQ(sparse.depth(x, y, t), whole.depth(x, y, t));
                            compared += p.depth > 0.0;
                        }
                }
            }
            EXPECT_GT(compared, 100) << "the regions' points must be wet, mostly";
        }
}

// A body's region moving across the tiles (set_regions, 8 × 8 tiles): the frames held,
// and one read ahead before the move, are refit to the new window by reading only the
// tiles the old one did not hold, and every sample equals to the bit what a reader of
// the whole grid gives (both interpolants, with and without a finer ground). Counted
// by hand for the linear one (cells of 64-cell tiles):
//   region A (i 4..7, j 4..7; tiles 0..1 × 0..1), prepare(0.5): frames 0, 1 read, 2 × 4 tiles;
//   read_ahead(1.0): frame 2 on A's 4 tiles;
//   region B (i 10..13, j 4..7; tiles 0..2 × 0..1): frames 0, 1 refit, 2 × 2 new tiles;
//   prepare(1.0): frame 2 taken from the read-ahead and refit, 2 new tiles;
//   region C (i 20..23, j 12..15; tiles 2..3 × 1..2): frames 1, 2 refit, 2 × 3 new tiles
//   (tile (2, 1) is kept).
// So 3 frames read (12 tiles) and 5 refits (12 tiles): 24 tiles, 1 536 cells. Reading
// every frame anew on each window, as before the refits, reads 38 tiles.
TEST(FlowReader, AMovedWindowReadsOnlyItsNewTiles) {
    const TiledFlow flow = tiled_flow(test::scratch_dir("fr_refit"));
    const Grid& g = flow.grid;
    const std::string& path = flow.path;
    const CellWindow a{4, 8, 4, 8}, b{10, 14, 4, 8}, c{20, 24, 12, 16};
    for (TimeInterpolation interp : {TimeInterpolation::linear, TimeInterpolation::cubic})
        for (const bool on_ground : {false, true}) {
            FlowReaderDef def;
            def.time_interpolation = interp;
            FlowReader moving(path, def), whole(path, def);
            if (on_ground) {
                moving.set_ground(flow.fine, flow.ground);
                whole.set_ground(flow.fine, flow.ground);
            }
            int compared = 0;
            const auto same_bits = [&](const CellWindow& r, double t) {
                ASSERT_TRUE(moving.covers(r));
                whole.prepare(t);
                EXPECT_EQ(moving.min_depth(r), whole.min_depth(r)) << t;
                for (double fx = 0.0; fx <= 1.0; fx += 0.23)
                    for (double fy = 0.0; fy <= 1.0; fy += 0.31) {
                        const double x = g.x(r.i0) + fx * (g.x(r.i1 - 1) - g.x(r.i0));
                        const double y = g.y(r.j0) + fy * (g.y(r.j1 - 1) - g.y(r.j0));
                        const FlowPointAccel p = moving.sample_accel(x, y, t), q = whole.sample_accel(x, y, t);
                        EXPECT_EQ(p.depth, q.depth) << x << ", " << y << ", " << t;
                        EXPECT_EQ(p.u, q.u);
                        EXPECT_EQ(p.v, q.v);
                        EXPECT_EQ(p.du_dt, q.du_dt);
                        EXPECT_EQ(p.dv_dt, q.dv_dt);
                        EXPECT_EQ(moving.depth(x, y, t), whole.depth(x, y, t));
                        compared += p.depth > 0.0;
                    }
            };
            moving.set_regions({a});
            moving.prepare(0.5);
            same_bits(a, 0.5);
            moving.read_ahead(1.0);
            moving.set_regions({b});
            EXPECT_FALSE(moving.covers(c));
            same_bits(b, 0.7);
            moving.prepare(1.0);
            same_bits(b, 1.0);
            moving.set_regions({c});
            EXPECT_FALSE(moving.covers(a));
            same_bits(c, 1.2);
            if (interp == TimeInterpolation::linear) {
                EXPECT_EQ(moving.read_stats().frames_loaded, 3u);
                EXPECT_EQ(moving.read_stats().frames_refit, 5u);
                EXPECT_EQ(moving.read_stats().cells_read, 24u * 64u);
            }
            for (double t = 1.3; t <= 5.0; t += 0.45) {  // on to new frames, read on C's 4 tiles
                moving.prepare(t);
                same_bits(c, t);
            }
            EXPECT_GT(compared, 150) << "the regions' points must be wet, mostly";
        }
}

// formats/tile_decoder reads the chunks of h, u, v without netCDF's data path. Its tiles
// hold netCDF's values to the bit (the east and north tiles cut by the grid's edge
// included; with and without compression), and a reader that uses it samples the same
// bits as one that reads through netCDF, on a whole window and on regions (there with
// three threads decoding).
TEST(FlowReader, DecodedTilesHoldTheValuesNetcdfReads) {
    const auto dir = test::scratch_dir("fr_decode");
    const Grid g{21, 13, 0.025, 0.025, 0.05, 0.05};  // 3 x 2 tiles of 8 x 8 cells, the last ones cut
    const auto field = [](double x, double y, double t) {
        const double h = 0.02 + 0.03 * std::sin(5 * x + t) * std::cos(7 * y - 0.7 * t);  // dry in places
        return test::FlowState{float(std::max(0.0, h)), float(0.3 * std::cos(9 * x) - 0.1 * t), float(-0.2 * y * t)};
    };
    for (const int deflate : {1, 0}) {
        SCOPED_TRACE(deflate);
        const auto path = test::write_flow(
            dir + "/f" + std::to_string(deflate) + ".nc", g, {0.0, 1.0, 2.0, 3.0}, [](double x, double) { return -0.01 * x; },
            field, {}, 8, deflate);
        const nc::File file = nc::File::open_read(path);  // the process holds the file through netCDF too
        const std::unique_ptr<TileDecoder> decoder = TileDecoder::open(path, {"h", "u", "v"});
        ASSERT_TRUE(decoder);
        EXPECT_EQ(decoder->tile_x(), 8);
        EXPECT_EQ(decoder->tile_y(), 8);
        std::vector<float> tile(64), slab;
        int differ = 0, cells = 0;
        for (std::size_t frame = 0; frame < 4; ++frame)
            for (std::size_t var = 0; var < 3; ++var)
                for (int tj = 0; tj < 2; ++tj)
                    for (int ti = 0; ti < 3; ++ti) {
                        ASSERT_TRUE(decoder->read(var, frame, ti, tj, tile.data()));
                        const int i0 = 8 * ti, j0 = 8 * tj, ni = std::min(8, g.nx - i0), nj = std::min(8, g.ny - j0);
                        slab.assign(std::size_t(ni * nj), -1.0f);
                        file.get_slab(file.var(std::string(1, "huv"[var])), {frame, std::size_t(j0), std::size_t(i0)},
                                      {1, std::size_t(nj), std::size_t(ni)}, slab.data());
                        for (int j = 0; j < nj; ++j)
                            for (int i = 0; i < ni; ++i) {
                                differ += std::memcmp(&tile[std::size_t(8 * j + i)], &slab[std::size_t(ni * j + i)], 4) != 0;
                                ++cells;
                            }
                    }
        EXPECT_EQ(differ, 0);
        EXPECT_EQ(cells, 4 * 3 * 21 * 13);

        FlowReaderDef through_netcdf, on_three_threads;
        through_netcdf.decode_tiles = false;
        on_three_threads.decode_threads = 3;
        for (const bool regions : {false, true}) {
            FlowReader a(path, regions ? on_three_threads : FlowReaderDef{}), b(path, through_netcdf);
            if (regions) {
                a.set_regions({CellWindow{2, 5, 2, 5}, CellWindow{15, 19, 9, 12}});
                b.set_regions({CellWindow{2, 5, 2, 5}, CellWindow{15, 19, 9, 12}});
            }
            int wet = 0;
            for (double t = 0.0; t <= 3.0; t += 0.4) {
                a.prepare(t);
                b.prepare(t);
                for (double x = 0.16; x < 1.0; x += 0.13)
                    for (double y = 0.12; y < 0.6; y += 0.09) {
                        if (regions && !a.covers(a.cells_for(x, x, y, y))) continue;
                        const FlowPointAccel p = a.sample_accel(x, y, t), q = b.sample_accel(x, y, t);
                        EXPECT_EQ(p.depth, q.depth) << x << ", " << y << ", " << t;
                        EXPECT_EQ(p.u, q.u);
                        EXPECT_EQ(p.v, q.v);
                        EXPECT_EQ(p.du_dt, q.du_dt);
                        wet += p.depth > 0.0;
                    }
            }
            EXPECT_GT(wet, regions ? 20 : 150);
        }
    }
}

// The decoder takes only the layout it decodes; the reader then reads through netCDF.
TEST(TileDecoder, OpensOnlyTheLayoutItDecodes) {
    const auto dir = test::scratch_dir("tile_layouts");
    const std::string path = dir + "/layouts.nc";
    {
        nc::File f = nc::File::create(path);
        const int t = f.def_dim("time", 2), y = f.def_dim("y", 5), x = f.def_dim("x", 6);
        const auto field = [&](const std::string& name, nc_type type, std::vector<std::size_t> chunks, int deflate) {
            const int v = f.def_var(name, type, {t, y, x});
            if (!chunks.empty()) f.def_chunking(v, chunks);
            if (deflate >= 0) f.def_deflate(v, deflate, true);
            return v;
        };
        const int good = field("good", NC_FLOAT, {1, 4, 4}, 1);
        field("unwritten", NC_FLOAT, {1, 4, 4}, 1);
        const int dbl = field("double", NC_DOUBLE, {1, 4, 4}, 1);
        const int contiguous = field("contiguous", NC_FLOAT, {}, -1);
        const int deep = field("two_frames_a_chunk", NC_FLOAT, {2, 4, 4}, 1);
        const int summed = field("fletcher32", NC_FLOAT, {1, 4, 4}, 1);
        f.check(nc_def_var_fletcher32(f.id(), summed, NC_FLETCHER32), "fletcher32");
        f.enddef();
        std::vector<float> values(60);
        for (std::size_t k = 0; k < values.size(); ++k) values[k] = float(k) * 0.25f - 3.0f;
        for (int v : {good, contiguous, deep, summed}) f.put(v, values);
        f.put(dbl, std::vector<double>(60, 1.5));
        f.close();
    }
    EXPECT_TRUE(TileDecoder::open(path, {"good"}));
    EXPECT_TRUE(TileDecoder::open(path, {"good", "unwritten"}));
    for (const char* other : {"double", "contiguous", "two_frames_a_chunk", "fletcher32", "no_such_variable"})
        EXPECT_FALSE(TileDecoder::open(path, {"good", other})) << other;
    EXPECT_FALSE(TileDecoder::open(dir + "/missing.nc", {"good"}));
    const std::unique_ptr<TileDecoder> d = TileDecoder::open(path, {"good", "unwritten"});
    std::vector<float> tile(16);
    ASSERT_TRUE(d->read(0, 1, 1, 1, tile.data()));  // frame 1, cells x 4..5, y 4: values 30 + 6 y + x
    EXPECT_EQ(tile[0], (30 + 6 * 4 + 4) * 0.25f - 3.0f);
    EXPECT_EQ(tile[1], (30 + 6 * 4 + 5) * 0.25f - 3.0f);
    EXPECT_FALSE(d->read(1, 0, 0, 0, tile.data()));         // never written: netCDF gives its fill
    EXPECT_THROW(d->read(0, 2, 0, 0, tile.data()), Error);  // no frame 2
}

// A tile whose stored bytes were damaged (the file's structure intact) is an error that
// names the file, the variable, the frame and the tile, raised where that frame is
// needed (decoded on one thread or two); read through netCDF it fails too.
TEST(FlowReader, ADamagedTileIsANamedError) {
    const auto dir = test::scratch_dir("fr_damaged");
    const std::string path = uneven_flow(dir + "/f.nc");
    test::damage_chunk(path, "u", 3);
    for (const int threads : {1, 2, 0}) {  // 0: read through netCDF
        const bool decode = threads > 0;
        FlowReaderDef def;
        def.decode_tiles = decode;
        def.decode_threads = threads;
        FlowReader r(path, def);
        r.prepare(1.5);  // frames 1 and 2: intact
        EXPECT_GT(r.sample(0.0, 2.3, 1.5).depth, 0.0);
        const std::string msg = error_of([&] { r.prepare(3.2); });
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        if (decode) {
            EXPECT_NE(msg.find("variable 'u', frame 3, tile (0, 0) of 20 x 12 cells: the stored chunk does not inflate"),
                      std::string::npos)
                << msg;
        }
    }
}

// pipelines/subsample_flow.py --keep-bits N (docs/studies/resolution_by_debris.md, "How much of that is chaos?")
// perturbs a flow by a known amount: each stored h, u, v keeps N significant bits, so it
// moves by at most 2^-(N+1) of itself; dry stays dry and wet stays wet. Read back through
// the replay's own reader (its tile decoder). By hand, for N = 12: u = 1 + 2^-13 + 2^-20
// lies above the midpoint 1 + 2^-13 of 1 and 1 + 2^-12, so it becomes 1 + 2^-12 (a change
// of 1.2e-4, not a round-off); v = 5/32 needs three bits and stays exact.
TEST(FlowReader, FieldsKeptToFewerBitsMoveByAtMostHalfTheirLastBit) {
    const auto dir = test::scratch_dir("fr_keep_bits");
    const float u_in = 1.0f + std::ldexp(1.0f, -13) + std::ldexp(1.0f, -20);
    auto depth = [](double x, double y, double t) { return x < -0.45 ? 0.0 : 0.1 + 0.013 * x + 0.003 * y + 0.001 * t; };
    const auto in = test::write_flow(
        dir + "/in.nc", grid, {0.0, 1.0}, [](double, double) { return -0.5; },
        [&](double x, double y, double t) {
            return test::FlowState{float(depth(x, y, t)), u_in, 0.15625f};
        });
    const std::string out = dir + "/out.nc";
    auto run = [&](const std::string& args) {
        const std::string cmd =
            "cd " FLOTSAM_SOURCE_DIR " && /usr/bin/python3 -m pipelines.subsample_flow " + args + " > " + dir + "/log.txt 2>&1";
        const int rc = std::system(cmd.c_str());
        std::ifstream f(dir + "/log.txt");
        return std::make_pair(rc, std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>()));
    };
    const auto [rc, log] = run(in + " 1 " + out + " --keep-bits 12");
    ASSERT_EQ(rc, 0) << log;
    FlowReader original(in), kept(out);
    // Sampling before prepare() is refused, not a read of unloaded memory.
    EXPECT_NE(error_of([&] { original.sample(0.0, 2.2, 0.5); }).find("before prepare()"), std::string::npos);
    original.prepare(0.0);  // frames 0 and 1
    kept.prepare(0.0);
    int wet = 0, changed = 0;
    for (double t : {0.0, 1.0})
        for (int j = 0; j < grid.ny; ++j)
            for (int i = 0; i < grid.nx; ++i) {
                const double x = grid.x(i), y = grid.y(j);
                const FlowPoint a = original.sample(x, y, t), b = kept.sample(x, y, t);
                if (a.depth == 0.0) {
                    EXPECT_EQ(b.depth, 0.0) << "dry cell " << i << ", " << j << " got water";
                    continue;
                }
                ++wet;
                EXPECT_GT(b.depth, 0.0);
                EXPECT_LE(std::abs(b.depth - a.depth), std::ldexp(a.depth, -13)) << i << ", " << j;
                changed += b.depth != a.depth;
                EXPECT_NEAR(b.u, 1.0 + std::ldexp(1.0, -12), 1e-6) << i << ", " << j;
                EXPECT_NEAR(b.v, 0.15625, 1e-7) << i << ", " << j;
            }
    EXPECT_GT(wet, grid.nx * grid.ny);  // both frames mostly wet
    EXPECT_GT(changed, wet / 2);        // most depths need more than 12 bits: the perturbation happened
    // A bad bit count is refused with the option named, and leaves no output.
    const auto [bad_rc, bad_log] = run(in + " 1 " + dir + "/bad.nc --keep-bits 30");
    EXPECT_NE(bad_rc, 0);
    EXPECT_NE(bad_log.find("--keep-bits must be 1 to 23"), std::string::npos) << bad_log;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.nc"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.nc.part"));
}
