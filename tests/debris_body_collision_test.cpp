// Bodies that meet each other (debris/body_collision.hpp): the box-box contact by hand, a
// head-on impact by hand, momentum kept in a pile, and a yard of containers pressed on a
// wall by a current with no overlap left at any step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cases/debris_flows.hpp"
#include "debris/body_collision.hpp"
#include "debris/catalogue.hpp"
#include "debris/loads.hpp"
#include "debris/world.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

// A body with no drag (cd = 0): in still water only the contacts change its motion.
BodyDef frictionless_box(double x, double y, double heading) {
    BodyDef b = test::body_at(x, y, heading);
    b.cd1 = b.cd2 = 0.0;
    return b;
}

}  // namespace

// Two 0.25 x 0.10 m boxes side by side along x, B 24 cm right of A and 2 cm up: their
// ends overlap by 1 cm along x; across, they share y from -3 to 5 cm. Normal: -x (from B
// into A), depth 1 cm, the point in the middle of B's end that lies in A's: x = 0.115 m
// (B's end face), y = (-3 + 5)/2 = 1 cm. Turned by 30 degrees together, the same in their
// frame.
TEST(BodyCollision, BoxOverlapByHand) {
    for (const double turn : {0.0, 30.0}) {
        const double c = std::cos(turn * M_PI / 180), s = std::sin(turn * M_PI / 180);
        const auto rot = [&](Vec2 p) { return Vec2{c * p.x - s * p.y, s * p.x + c * p.y}; };
        const Box a = Box::make({0.0, 0.0}, turn * M_PI / 180, 0.25, 0.10);
        const Box b = Box::make(rot({0.24, 0.02}), turn * M_PI / 180, 0.25, 0.10);
        BodyCollision k;
        ASSERT_TRUE(box_overlap(a, b, 0.0, k));
        EXPECT_NEAR(k.depth, 0.01, 1e-12);
        const Vec2 n = rot({-1.0, 0.0}), p = rot({0.115, 0.01});
        EXPECT_NEAR(k.normal.x, n.x, 1e-12);
        EXPECT_NEAR(k.normal.y, n.y, 1e-12);
        EXPECT_NEAR(k.point.x, p.x, 1e-12);
        EXPECT_NEAR(k.point.y, p.y, 1e-12);
        const Box far = Box::make(rot({0.26, 0.02}), turn * M_PI / 180, 0.25, 0.10);
        EXPECT_FALSE(box_overlap(a, far, 0.0, k));
    }
}

// Two equal boxes afloat in still water, aligned along x, meet head-on at 0.1 m/s each
// (no drag, no friction). Equal masses, restitution e = 0.5: by hand they leave at
// -e u and +e u (v_a' = ((1 - e) v_a + (1 + e) v_b) / 2), without turning, and no overlap
// is left.
TEST(BodyCollision, HeadOnImpactOfEqualBoxesByHand) {
    const auto dir = test::scratch_dir("body_head_on");
    const Grid g{200, 60, -0.995, -0.295, 0.01, 0.01};
    const auto path = test::uniform_flow(dir + "/still.nc", g, 3, 0.1, 0.0, 0.0);
    World w(path, {});
    w.add_body(frictionless_box(-0.2, 0.0, 0.0), 0);
    w.add_body(frictionless_box(0.2, 0.0, 0.0), 0);
    for (BodyState& s : w.states()) s.flags |= flag_released;
    w.states()[0].vx = 0.1;
    w.states()[1].vx = -0.1;
    w.advance_to(2.0);  // they meet at 0.75 s (15 cm apart at 0.2 m/s closing)
    const BodyState &a = w.states()[0], &b = w.states()[1];
    std::printf("after: %.6f and %.6f m/s, turning %.3g and %.3g rad/s; %ld contact steps\n", a.vx, b.vx, a.omega, b.omega,
                w.stats()[0].body_contacts);
    EXPECT_NEAR(a.vx, -0.05, 0.0005);
    EXPECT_NEAR(b.vx, 0.05, 0.0005);
    EXPECT_NEAR(a.vy, 0.0, 1e-12);
    EXPECT_NEAR(a.omega, 0.0, 1e-9);
    EXPECT_NEAR(b.omega, 0.0, 1e-9);
    EXPECT_GE(w.stats()[0].body_contacts, 1);
    EXPECT_LE(w.stats()[0].max_body_overlap, unresolved_overlap_cells * 0.01);
    EXPECT_GT(b.x - a.x, 0.25);  // apart again
    // The same bodies in groups of their own pass through each other.
    World apart(path, {});
    apart.add_body(frictionless_box(-0.2, 0.0, 0.0));
    apart.add_body(frictionless_box(0.2, 0.0, 0.0));
    for (BodyState& s : apart.states()) s.flags |= flag_released;
    apart.states()[0].vx = 0.1;
    apart.states()[1].vx = -0.1;
    apart.advance_to(2.0);
    EXPECT_EQ(apart.states()[0].vx, 0.1);
    EXPECT_EQ(apart.stats()[0].body_contacts, 0);
}

// Fifty boxes on a loose lattice in still water (no drag, no friction, far from any wall),
// thrown at each other with seeded velocities of up to 0.3 m/s and turns of up to 2 rad/s:
// hundreds of contacts, and the total momentum Σ M V (M the effective mass, added mass
// included) is what it was, to 1e-12 of Σ M |V|.
TEST(BodyCollision, MomentumOfAPileIsKept) {
    const auto dir = test::scratch_dir("body_pile");
    const Grid g{300, 300, -1.495, -1.495, 0.01, 0.01};
    const auto path = test::uniform_flow(dir + "/still.nc", g, 4, 0.2, 0.0, 0.0);
    World w(path, {});
    std::uint64_t seed = 12345;
    const auto uniform = [&seed] {  // [-1, 1)
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(seed >> 11) / double(1ULL << 52) - 1.0;
    };
    for (int k = 0; k < 50; ++k)
        w.add_body(frictionless_box(-0.45 + 0.3 * (k % 7) + 0.01 * uniform(), -0.6 + 0.17 * (k / 7), 0.0), 7);
    for (BodyState& s : w.states()) {
        s.flags |= flag_released;
        s.vx = 0.3 * uniform() - 0.3 * s.x;  // inward on the whole
        s.vy = 0.3 * uniform() - 0.3 * s.y;
        s.omega = 2.0 * uniform();
    }
    const BodyParams& p = w.params()[0];
    const double M = effective_inertia(p, p.plan_area * p.draft, 1000.0).mass;  // the same for all, afloat
    const auto momentum = [&] {
        Vec2 sum;
        double scale = 0.0;
        for (const BodyState& s : w.states()) {
            sum += M * Vec2{s.vx, s.vy};
            scale += M * std::hypot(s.vx, s.vy);
        }
        return std::pair{sum, scale};
    };
    const auto [p0, scale] = momentum();
    w.advance_to(2.0);
    const auto [p1, unused] = momentum();
    long contacts = 0;
    double deepest = 0.0;
    for (const BodyStats& s : w.stats()) {
        contacts += s.body_contacts;
        deepest = std::max(deepest, s.max_body_overlap);
    }
    std::printf(
        "pile: %ld body contact steps; momentum (%.17g, %.17g) -> (%.17g, %.17g) kg m/s, scale %.4g; deepest overlap left %.3g m\n",
        contacts, p0.x, p0.y, p1.x, p1.y, scale, deepest);
    EXPECT_GT(contacts, 100);
    EXPECT_NEAR(p1.x, p0.x, 1e-12 * scale);
    EXPECT_NEAR(p1.y, p0.y, 1e-12 * scale);
    EXPECT_LE(deepest, unresolved_overlap_cells * 0.01);
}

// A yard of 480 empty 40 ft containers (12.19 x 2.44 m, draft 0.13 m) packed at 1 m gaps,
// 24 along x by 20 across, afloat in 3 m of water on 10 m cells, carried north by a 1 m/s
// current onto a building's face: they pile up against it. No two overlap deeper than the
// tolerance (1e-3 of a cell, 1 cm) after any step, nor any of them a wall, and none jams.
TEST(BodyCollision, YardPressedOnAWallKeepsEveryBodyApart) {
    const auto dir = test::scratch_dir("body_yard");
    const Grid g{40, 16, 5.0, 5.0, 10.0, 10.0};  // 400 x 160 m, a building face at y = 150 m
    const auto path = test::uniform_flow(dir + "/current.nc", g, 130, 3.0, 0.0, 1.0, -3.0);
    std::vector<std::uint8_t> wall(g.size(), 0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) wall[g.index(i, j)] = g.y(j) > 150.0 ? 1 : 0;
    BodyDef c = catalogue_body_def("container_40ft", "test");
    std::vector<BodyDef> yard;
    for (int row = 0; row < 20; ++row)
        for (int col = 0; col < 24; ++col) {
            BodyDef b = c;
            b.x = 45.0 + col * (c.length + 1.0);
            b.y = 20.0 + row * (c.width + 1.0);
            yard.push_back(b);
        }
    WorldDef def = scaled_to_bodies(default_world_def(), yard, false);
    def.threads = 2;
    World w(path, wall, def);
    for (const BodyDef& b : yard) w.add_body(b, 0);
    w.advance_to(120.0);
    long contacts = 0, jams = 0, unresolved = 0;
    double body_overlap = 0.0, wall_overlap = 0.0, north = 0.0;
    for (std::size_t k = 0; k < w.size(); ++k) {
        const BodyStats& s = w.stats()[k];
        contacts += s.body_contacts;
        jams += s.jams;
        unresolved += s.unresolved;
        body_overlap = std::max(body_overlap, s.max_body_overlap);
        wall_overlap = std::max(wall_overlap, s.max_residual_overlap);
        north = std::max(north, w.states()[k].y);
    }
    std::printf(
        "yard: %ld body contact steps, %ld jammed, %ld unresolved; deepest overlap left: %.3g m between bodies, %.3g m "
        "with the wall; northernmost centre at y = %.2f m\n",
        contacts, jams, unresolved, body_overlap, wall_overlap, north);
    const double tolerance = unresolved_overlap_cells * 10.0;
    EXPECT_GT(contacts, 1000);
    EXPECT_GT(north, 140.0);  // at the wall
    EXPECT_LE(body_overlap, tolerance);
    EXPECT_LE(wall_overlap, tolerance);
    EXPECT_EQ(unresolved, 0);
    EXPECT_EQ(jams, 0);
}
