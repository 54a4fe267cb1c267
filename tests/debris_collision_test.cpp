// Obstacles: walls, corners and thin walls against the two collision models.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "cases/debris_flows.hpp"
#include "debris/world.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

const Grid grid{120, 120, -0.595, -0.595, 0.01, 0.01};  // 1.2 m square, 1 cm cells

// Building mask of cells whose centre satisfies `inside`.
std::vector<std::uint8_t> mask(const std::function<bool(double, double)>& inside) {
    std::vector<std::uint8_t> m(grid.size(), 0);
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) m[grid.index(i, j)] = inside(grid.x(i), grid.y(j)) ? 1 : 0;
    return m;
}

// Deepest overlap of the body with a blocked cell right now [m].
double overlap(const World& w, std::size_t b) {
    const BodyState& s = w.states()[b];
    const BodyParams& p = w.params()[b];
    std::vector<ObstacleCollision> cs;
    const double bottom = 1e9;  // so that only the building mask blocks
    w.obstacles().find_contacts(Box::make({s.x, s.y}, s.theta, p.def.length, p.def.width), bottom, p.step_height, cs, 0.0);
    double d = 0.0;
    for (const auto& c : cs) d = std::max(d, c.depth);
    return d;
}

BodyDef body(double x, double y, double heading_deg, CollisionModel model) {
    BodyDef b = default_body_def();
    b.x = x;
    b.y = y;
    b.heading = heading_deg * M_PI / 180.0;
    b.collision = model;
    return b;
}

}  // namespace

// Thrown at a straight wall on frictionless dry ground (no drag, no friction): the body
// never overlaps the wall after a step, and its kinetic energy ½ m V² + ½ I ω² never
// grows (e ≤ 1); with e = 1 and one contact at a time it is kept, with e = 0.5 it drops.
TEST(DebrisCollision, StraightWallNoPenetrationNoEnergyGain) {
    const auto dir = test::scratch_dir("coll_wall");
    const auto path = test::uniform_flow(dir + "/dry.nc", grid, 5, 0.0, 0.0, 0.0);
    for (double e : {1.0, 0.5}) {
        World w(path, mask([](double x, double) { return x > 0.3; }));
        BodyDef b = body(0.0, 0.0, 30.0, CollisionModel::multi);
        b.mu = 0.0;
        b.restitution = e;
        w.add_body(b);
        BodyState& s = w.states()[0];
        s.flags |= flag_released;
        s.vx = 0.8;
        s.vy = 0.1;
        s.omega = 0.5;
        const BodyParams& p = w.params()[0];
        auto energy = [&] {
            const BodyState& q = w.states()[0];
            return 0.5 * p.mass * (q.vx * q.vx + q.vy * q.vy) + 0.5 * p.inertia * q.omega * q.omega;
        };
        const double e0 = energy();
        double previous = e0, worst_overlap = 0.0, min_vx = 1.0;
        for (int k = 1; k <= 200; ++k) {
            w.advance_to(0.01 * k);
            min_vx = std::min(min_vx, w.states()[0].vx);
            worst_overlap = std::max(worst_overlap, overlap(w, 0));
            EXPECT_LE(energy(), previous * (1 + 1e-12)) << "step " << k;
            previous = energy();
        }
        EXPECT_GT(w.stats()[0].collisions, 0);
        EXPECT_LT(min_vx, 0.0);  // bounced
        EXPECT_LT(worst_overlap, 1e-8);
        if (e < 1.0) {
            EXPECT_LT(previous, 0.9 * e0);
        }
    }
}

// Driven diagonally into a corner by a strong current: each step pushes the body into
// both walls. Multi-collision clears both every step; single collision clears only the
// deepest and leaves the other overlapping.
TEST(DebrisCollision, MultiKeepsBodyOutOfCornerWhereSingleDoesNot) {
    const auto dir = test::scratch_dir("coll_corner");
    const auto path = test::uniform_flow(dir + "/f.nc", grid, 4, 0.1, 0.6, 0.6);
    auto corner = mask([](double x, double y) { return x > 0.25 || y > 0.2; });
    World mc(path, corner), sc(path, corner);
    mc.add_body(body(0.0, 0.0, 0.0, CollisionModel::multi));
    sc.add_body(body(0.0, 0.0, 0.0, CollisionModel::single));
    double mc_worst = 0.0, sc_worst = 0.0;
    for (int k = 1; k <= 300; ++k) {
        mc.advance_to(0.01 * k);
        sc.advance_to(0.01 * k);
        mc_worst = std::max(mc_worst, overlap(mc, 0));
        sc_worst = std::max(sc_worst, overlap(sc, 0));
    }
    EXPECT_GT(mc.stats()[0].collisions, 10);
    EXPECT_EQ(mc.stats()[0].unresolved, 0);
    EXPECT_LT(mc_worst, 1e-8);
    EXPECT_LT(mc.stats()[0].max_residual_overlap, 1e-8);
    EXPECT_GT(sc_worst, 1e-4) << "single collision should leave an overlap in a corner";
    EXPECT_GT(sc.stats()[0].max_residual_overlap, 1e-4);
}

// A wall one cell thick and a fast current (3 m/s, 3 cm per 0.01 s step): the vertex
// speed limit keeps each corner within a quarter cell per step (so more steps than
// dt_max alone would take), the wall is always seen and the body stays on the near side.
TEST(DebrisCollision, NoTunnellingThroughOneCellWall) {
    const auto dir = test::scratch_dir("coll_tunnel");
    const auto path = test::uniform_flow(dir + "/f.nc", grid, 2, 0.1, 3.0, 0.0);
    auto wall = mask([](double x, double) { return std::fabs(x - 0.305) < 0.004; });  // the one column at x = 0.305
    World w(path, wall);
    w.add_body(body(0.0, 0.0, 20.0, CollisionModel::multi));
    w.states()[0].vx = 3.0;  // already at the current's speed
    double max_x = -1.0, worst = 0.0;
    for (int k = 1; k <= 100; ++k) {
        w.advance_to(0.02 * k);
        max_x = std::max(max_x, w.states()[0].x);
        worst = std::max(worst, overlap(w, 0));
    }
    EXPECT_LT(max_x, 0.3);
    EXPECT_LT(worst, 1e-8);
    EXPECT_GT(w.stats()[0].steps, 300);  // dt_max = 0.01 s alone would take 200 steps: the vertex limit set them
}

// A body at 9° (projected width across the gap L sin 9° + B cos 9° = 0.1379 m) driven by
// a 0.3 m/s current into a gap between two buildings one cell narrower than that width
// rounded up to whole cells: 13 cells of 1 cm (0.13 m), and 3 cells of 4 cm (0.12 m, the
// gap a land body was wedged in on the real layout at 4 cm). The body cannot pass at 9°;
// pushed back out along each contact's normal by translation alone it was pressed from
// one wall into the other, step after step. Advanced again from the start of the step
// with the corrected velocity and rotation rate (the paper's step 3), every step ends
// with no overlap deeper than the tolerance (1e-3 of a cell) within the 10 passes.
TEST(DebrisCollision, WedgedAcrossAGapNarrowerThanItsWidthEndsEachStepWithoutOverlap) {
    const auto dir = test::scratch_dir("coll_gap");
    const double heading = 9.0, width = 0.25 * std::sin(heading * M_PI / 180.0) + 0.10 * std::cos(heading * M_PI / 180.0);
    EXPECT_NEAR(width, 0.1379, 1e-4);
    ASSERT_EQ(default_world_def().step.max_collision_passes, 10);  // the paper's 5-10 passes: at most 10 per step
    for (const double cell : {0.01, 0.04}) {
        const int n = int(std::ceil(width / cell)) - 1;  // cells across the gap
        const double gap = n * cell;
        const Grid g{int(std::lround(1.2 / cell)), int(std::lround(1.2 / cell)), -0.6 + 0.5 * cell, -0.6 + 0.5 * cell, cell, cell};
        // Buildings at 0.2 ≤ x ≤ 0.6 beside the gap, which spans the cells' edges 0 … gap in y.
        std::vector<std::uint8_t> walls(g.size(), 0);
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i)
                walls[g.index(i, j)] = g.x(i) > 0.2 && g.x(i) < 0.6 && (g.y(j) < 0.0 || g.y(j) > gap);
        const auto path = test::uniform_flow(dir + "/f" + std::to_string(n) + ".nc", g, 5, 0.1, 0.3, 0.0);
        World w(path, walls);
        w.add_body(body(0.0, 0.5 * gap, heading, CollisionModel::multi));
        double worst = 0.0, furthest = -1.0;
        for (int k = 1; k <= 250; ++k) {
            w.advance_to(0.02 * k);
            worst = std::max(worst, overlap(w, 0));
            furthest = std::max(furthest, w.states()[0].x);
        }
        const BodyStats& st = w.stats()[0];
        std::printf("gap of %d cells of %.0f cm: %ld collision steps, %ld unresolved, deepest overlap left %.2e m, "
                    "heading %.1f deg at 5 s, x at most %.3f m\n",
                    n, 100 * cell, st.collisions, st.unresolved, st.max_residual_overlap,
                    w.states()[0].theta * 180.0 / M_PI, furthest);
        EXPECT_GT(st.collisions, 20) << n;  // pressed against the gap throughout
        EXPECT_EQ(st.unresolved, 0) << n;
        EXPECT_LE(st.max_residual_overlap, 1e-3 * cell) << n;
        EXPECT_LE(worst, 1e-3 * cell) << n;
    }
}

// A floating body at rest (heading 0) between two single blocked cells that touch its
// long faces at two corners near its nose: (0.09, 0.05) on its north face and (0.12,
// −0.05) on its south face. The water turns clockwise as a solid body (Ω = −1 rad/s)
// and drifts north at 5 cm/s, which drives the body into both corners at once. For
// such a pair the impulses (and the moves out) of one contact are nearly all undone by
// the other's: the north contact's effective inverse mass is 2.95 kg⁻¹, the south one's
// 4.61, and each moves the other by −3.66 (n · n'/M + (r × n)(r' × n')/I with M = 1.25
// kg, I = 3.776e-3 kg m²), so taken one at a time they leave 3.66² / (2.95 × 4.61) = 0.99
// of the overlap pass after pass, and 50 of the 300 steps end with 10-50 µm of overlap.
// Every step ends with no overlap deeper
// than the tolerance (1e-3 of a cell): the move out clears both at once.
TEST(DebrisCollision, PinchedBetweenTwoCornersEndsEachStepWithoutOverlap) {
    const auto dir = test::scratch_dir("coll_pinch");
    const double Omega = -1.0, drift = 0.05;
    const auto path = test::write_flow(
        dir + "/vortex.nc", grid, {0.0, 1.0, 2.0, 3.0}, [](double, double) { return -0.1; },
        [&](double x, double y, double) {
            return test::FlowState{0.1f, float(-Omega * y), float(Omega * x + drift)};
        });
    World w(path, mask([](double x, double y) {
                return (std::fabs(x - 0.095) < 0.004 && std::fabs(y - 0.055) < 0.004) ||
                       (std::fabs(x - 0.125) < 0.004 && std::fabs(y + 0.055) < 0.004);
            }));
    w.add_body(body(0.0, 0.0, 0.0, CollisionModel::multi));
    double worst = 0.0;
    for (int k = 1; k <= 150; ++k) {
        w.advance_to(0.02 * k);
        worst = std::max(worst, overlap(w, 0));
    }
    const BodyStats& st = w.stats()[0];
    const BodyState& s = w.states()[0];
    std::printf("pinched between two corners: %ld collision steps, %ld unresolved, deepest overlap left %.2e m, at (%.4f, "
                "%.4f), heading %.3f deg\n",
                st.collisions, st.unresolved, st.max_residual_overlap, s.x, s.y, s.theta * 180.0 / M_PI);
    EXPECT_GT(st.collisions, 100);
    EXPECT_EQ(st.unresolved, 0);
    EXPECT_LE(st.max_residual_overlap, 1e-5);
    EXPECT_LE(worst, 1e-5);
}

// Jammed: where the passes leave an overlap deeper than the tolerance, the body stays
// where the step began, at rest (held by its contacts), if that pose is clearer. With no
// passes at all every contact is left unresolved: a body 0.5 mm from a wall at 1 m/s (a
// 2.5 mm step, a quarter cell, overlapping by 2 mm) is put back at x = 0.1745 m, at rest,
// one jam, no unresolved step, no overlap.
TEST(DebrisCollision, AJammedStepLeavesTheBodyWhereTheStepBegan) {
    const auto dir = test::scratch_dir("coll_jam");
    const auto path = test::uniform_flow(dir + "/dry.nc", grid, 2, 0.0, 0.0, 0.0);
    WorldDef def = default_world_def();
    def.step.max_collision_passes = 0;
    World w(path, mask([](double x, double) { return x > 0.3; }), def);
    BodyDef b = body(0.30 - 0.125 - 0.0005, 0.0, 0.0, CollisionModel::multi);
    b.mu = 0.0;
    w.add_body(b);
    BodyState& s = w.states()[0];
    s.flags |= flag_released;
    s.vx = 1.0;
    w.advance_to(0.1);
    const BodyStats& st = w.stats()[0];
    EXPECT_EQ(w.states()[0].x, 0.1745);
    EXPECT_EQ(w.states()[0].vx, 0.0);
    EXPECT_EQ(st.jams, 1);
    EXPECT_EQ(st.unresolved, 0);
    EXPECT_EQ(st.max_residual_overlap, 0.0);
    EXPECT_EQ(overlap(w, 0), 0.0);
}
