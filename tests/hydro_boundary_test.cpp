// The level boundary: which reading of a measured record gives the measured level.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "hydro/solver.hpp"
#include "test_support.hpp"

using namespace flotsam;
using namespace flotsam::hydro;

namespace {

// A 20 m closed flume, 0.8 m deep, driven on the west by a level that rises smoothly by
// 1 cm over 100 s and then holds: a wave fifteen times longer than the flume, which
// therefore fills almost uniformly, as the paper's flume does under its 300 s leading
// wave. Returns the level at the east wall averaged over 120-150 s (about one period
// of the flume's quarter-wave seiche, 4 L / sqrt(g h) = 28.5 s, which the rise excites).
double east_wall_level(LevelMode mode, const std::string& dir) {
    std::ostringstream csv;
    csv << "time,eta\n";
    for (int k = 0; k <= 160; ++k) {
        const double s = std::min(1.0, k / 100.0);
        csv << k << "," << 0.01 * s * s * (3.0 - 2.0 * s) << "\n";
    }
    Scene scene;
    scene.grid = Grid{40, 2, 0.25, 0.25, 0.5, 0.5};
    scene.z.assign(scene.grid.size(), -0.8);
    PhysicsDef d = default_physics_def();
    d.default_manning_n = 0.0;
    d.east.kind = BoundaryKind::wall;
    d.west.kind = BoundaryKind::level;
    d.west.level_mode = mode;
    d.west.series_file = test::write_file(dir, "rise.csv", csv.str());
    Solver solver(scene, d);
    double sum = 0.0, weight = 0.0;
    while (solver.time() < 150.0 - 1e-9) {
        const double dt = std::min(solver.stable_dt(), 150.0 - solver.time());
        solver.step(dt);
        if (solver.time() > 120.0) {
            sum += dt * solver.level(39, 0);
            weight += dt;
        }
    }
    return sum / weight;
}

}  // namespace

// A record measured near the wave maker is the total level, reflection included. Imposed
// as `total` (the default) the flume fills to the record's level; read as the incident
// wave, the wall's reflection is added on top and the level doubles: the error that put
// WG2 at 0.117 m instead of the paper's 0.063 m (docs/hydro.md).
TEST(LevelBoundary, TotalRecordFillsTheFlumeToItsLevelIncidentDoublesIt) {
    const std::string dir = test::scratch_dir("LevelBoundary");
    EXPECT_EQ(default_physics_def().west.level_mode, LevelMode::total);
    const double total = east_wall_level(LevelMode::total, dir);
    const double incident = east_wall_level(LevelMode::incident, dir);
    std::printf("east-wall level over 120-150 s: total %.5f m, incident %.5f m (record 0.01 m)\n", total, incident);
    EXPECT_NEAR(total, 0.010, 0.0003);
    EXPECT_NEAR(incident, 0.020, 0.001);
}

namespace {

// A 10 m channel, 0.1 m deep (c = 0.99 m/s), wall on the east; the west side imposes
// the total level of a 1 cm hump over 0-2 s, then either holds it at 0 until `hold`
// (a level side: it reflects what comes back) or, with a series that ends at 2 s, hands
// over to a transmissive side. Returns the largest |level| in the channel at 30 s, after
// the hump has run to the east wall and back to the west side (about 20 s).
double level_left_at_30s(const std::string& dir, SeriesEnd end, double hold) {
    std::ostringstream csv;
    csv << "time,eta\n";
    for (int k = 0; k * 0.1 <= std::max(2.0, hold) + 1e-9; ++k) {
        const double t = k * 0.1, s = std::sin(std::acos(-1.0) * std::min(t, 2.0) / 2.0);
        csv << t << "," << 0.01 * s * s << "\n";
    }
    Scene scene;
    scene.grid = Grid{200, 2, 0.025, 0.025, 0.05, 0.05};
    scene.z.assign(scene.grid.size(), -0.1);
    PhysicsDef d = default_physics_def();
    d.default_manning_n = 0.0;
    d.east.kind = BoundaryKind::wall;
    d.west.series_file = test::write_file(dir, end == SeriesEnd::error ? "held.csv" : "ends.csv", csv.str());
    d.west.series_end = end;
    Solver solver(scene, d);
    while (solver.time() < 30.0 - 1e-9) solver.step(std::min(solver.stable_dt(), 30.0 - solver.time()));
    double worst = 0.0;
    for (int i = 0; i < 200; ++i) worst = std::max(worst, std::abs(solver.level(i, 0)));
    return worst;
}

}  // namespace

// A level series that ends can hand over to a transmissive side: the hump
// that comes back from the east wall leaves through the west side, where a level held
// at 0 sends it back into the channel at full height.
TEST(LevelBoundary, SeriesThatEndsHandsOverToATransmissiveSide) {
    const std::string dir = test::scratch_dir("SeriesEnd");
    const double held = level_left_at_30s(dir, SeriesEnd::error, 30.0);
    const double handed_over = level_left_at_30s(dir, SeriesEnd::transmissive, 2.0);
    std::printf("largest |level| at 30 s: level held at 0 %.5f m, handed over to transmissive %.5f m (hump 0.01 m)\n", held,
                handed_over);
    EXPECT_GT(held, 0.005);
    EXPECT_LT(handed_over, 0.1 * held);
    EXPECT_EQ(parse_enum<SeriesEnd>("transmissive", "--west-series-end"), SeriesEnd::transmissive);
}

namespace {

// A 10 m channel, 1 m deep (c0 = 3.13 m/s), west wall, open east side; the water starts
// flowing west at 0.5 m/s, so the east side begins as an inflow. Runs 60 s (19 crossings)
// without friction; returns the level at the middle of the channel [m], and the largest
// |u| in the channel [m/s] through `speed`.
double channel_level_after_inflow(BoundaryKind east, double& speed) {
    Scene scene;
    scene.grid = Grid{100, 2, 0.1, 0.1, 0.05, 0.05};
    scene.z.assign(scene.grid.size(), -1.0);
    scene.u0.assign(scene.grid.size(), -0.5);
    scene.v0.assign(scene.grid.size(), 0.0);
    PhysicsDef d = default_physics_def();
    d.default_manning_n = 0.0;
    d.west.kind = BoundaryKind::wall;
    d.east.kind = east;
    Solver solver(scene, d);
    while (solver.time() < 60.0 - 1e-9) solver.step(std::min(solver.stable_dt(), 60.0 - solver.time()));
    speed = 0.0;
    for (int i = 0; i < 100; ++i) speed = std::max(speed, std::abs(solver.x_velocity(i, 0)));
    return solver.level(50, 0);
}

}  // namespace

// A transmissive side lets waves leave into still water of the side's initial depth: an
// inflow through it dies out, and the channel comes to rest at that water's level, 0 m
// (the incoming Riemann invariant at the side is the still water's, u - 2c = -2 c0, so
// the only state at rest is h = 1 m). A zero-gradient side (the study option, and
// transmissive before this test) copies the edge cell, so the inflow keeps its own
// incoming invariant: here the channel keeps what came in and rests 0.163 m high (in
// 2-D, the full-scale Kainan flows' east basin kept filling, to 100 m in 300 s:
// docs/hydro.md, "Boundaries").
TEST(TransmissiveBoundary, InflowDiesOutAndTheLevelReturnsToStillWater) {
    double speed_char = 0.0, speed_zero = 0.0;
    const double level_char = channel_level_after_inflow(BoundaryKind::transmissive, speed_char);
    const double level_zero = channel_level_after_inflow(BoundaryKind::zero_gradient, speed_zero);
    std::printf("level at 60 s: transmissive %.6f m (largest |u| %.2e m/s), zero-gradient %.6f m (%.2e m/s)\n", level_char,
                speed_char, level_zero, speed_zero);
    EXPECT_NEAR(level_char, 0.0, 1e-3);
    EXPECT_LT(speed_char, 1e-3);
    EXPECT_GT(level_zero, 0.1);
}
