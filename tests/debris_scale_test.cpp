// The collision, blocking and load geometry at both scales the tool is used at: the
// flume's box on 1 cm cells and a car on a port's 10 m cells (a body narrower than a
// quarter of a cell), set where the rules could fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "cases/debris_flows.hpp"
#include "debris/catalogue.hpp"
#include "debris/collision.hpp"
#include "debris/ground_contact.hpp"
#include "debris/dynamics.hpp"
#include "debris/world.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

constexpr double deg = M_PI / 180.0;

// Deepest overlap of body b with a building cell right now [m].
double overlap_with_buildings(const World& w, std::size_t b) {
    const BodyState& s = w.states()[b];
    const BodyParams& p = w.params()[b];
    std::vector<ObstacleCollision> cs;
    w.obstacles().find_contacts(Box::make({s.x, s.y}, s.theta, p.def.length, p.def.width), 1e9, p.step_height, cs, 0.0);
    double d = 0.0;
    for (const auto& c : cs) d = std::max(d, c.depth);
    return d;
}

// A floating body thrown at a building face along x at `speed` and `angle` to it, its long
// axis along its velocity and turning at `omega`, and kept pressed against it: the water, deep and uniform,
// accelerates toward the wall at 0.1 m/s² (v = a t), and the inertia force ρ V_s Cm Du/Dt
// at the centre gives the body that acceleration (no drag: cd = 0; no friction afloat).
// Nothing acts along the wall (walls are frictionless, e acts on the normal component,
// the inertia force is normal to the wall), so the centre's velocity along the wall stays
// speed cos(angle) through every impact and the sliding: by hand.
void slides_along_wall(const BodyDef& body, const Grid& g, double wall_y, double speed, double angle, double omega, double seconds,
                       const char* label) {
    const auto dir = test::scratch_dir(std::string("scale_wall_") + label);
    const double depth = 20.0 * body.height, a = 0.1;  // afloat everywhere [m], [m/s²]
    std::vector<double> times;
    for (double t = 0.0; t <= seconds + 1.0; t += 1.0) times.push_back(t);
    const auto path = test::write_flow(
        dir + "/pushing.nc", g, times, [&](double, double) { return -depth; },
        [&](double, double, double t) {
            return test::FlowState{float(depth), 0.0f, float(a * t)};
        });
    std::vector<std::uint8_t> wall(g.size(), 0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) wall[g.index(i, j)] = g.y(j) > wall_y ? 1 : 0;
    const WorldDef def = scaled_to_bodies(default_world_def(), {body}, false);
    World w(path, wall, def);
    w.add_body(body);
    BodyState& s0 = w.states()[0];
    s0.flags |= flag_released;
    s0.vx = speed * std::cos(angle);
    s0.vy = speed * std::sin(angle);
    s0.omega = omega;
    const double along = speed * std::cos(angle);
    const double tolerance = unresolved_overlap_cells * std::min(g.dx, g.dy);
    double worst = 0.0, slowest = along, fastest = along;
    for (int k = 1; k <= 100; ++k) {
        w.advance_to(seconds * k / 100.0);
        worst = std::max(worst, overlap_with_buildings(w, 0));
        slowest = std::min(slowest, w.states()[0].vx);
        fastest = std::max(fastest, w.states()[0].vx);
    }
    const BodyStats& st = w.stats()[0];
    std::printf(
        "%s: %ld collision steps, %ld jammed, %ld unresolved; speed along the wall %.6f to %.6f m/s (by hand %.6f); "
        "deepest overlap %.3g m (tolerance %.3g m)\n",
        label, st.collisions, st.jams, st.unresolved, slowest, fastest, along, worst, tolerance);
    EXPECT_GT(st.collisions, 50) << label;  // it met the wall and was held against it
    EXPECT_EQ(st.jams, 0) << label;
    EXPECT_EQ(st.unresolved, 0) << label;
    EXPECT_NEAR(slowest, along, 0.01 * along) << label;
    EXPECT_NEAR(fastest, along, 0.01 * along) << label;
    EXPECT_LE(worst, tolerance) << label;
    EXPECT_LE(st.max_residual_overlap, tolerance) << label;
    EXPECT_LE(w.states()[0].y, wall_y) << label;  // on its side of the wall
}

// A body's corner in the inside corner of an L-shaped building of three cells (the cells
// north and east of the body's cell and the one between them, north-east), its long axis
// north, reaching 2.3e-4 of a cell past the east face and 1.6e-4 past the north one. By
// hand: two contacts, out through each face by what the body reaches past it; the
// north-east cell, which the body reaches only through its faces shared with the other
// two, is no contact. (It was: a cell and a body's width deep out through its far face,
// into the building; on 10 m cells the move out of that and the east face together threw
// a car 416 km and turned it 30 000 revolutions.)
void corner_contacts_by_hand(const BodyDef& body, double cell, const char* label) {
    const int c = 4 + int(std::ceil(body.length / cell));  // the grid's edges well away from the body
    const Grid g{2 * c, 2 * c, 0.5 * cell, 0.5 * cell, cell, cell};  // cell edges at k × cell
    std::vector<std::uint8_t> mask(g.size(), 0);
    mask[g.index(c, c)] = mask[g.index(c - 1, c)] = mask[g.index(c, c - 1)] = 1;  // the corner at (c, c) × cell
    const ObstacleMap walls(g, std::vector<float>(g.size(), -1.0f), mask);
    const double ex = 2.3e-4 * cell, ey = 1.6e-4 * cell, corner = c * cell;
    const Box box = Box::make({corner + ex - 0.5 * body.width, corner + ey - 0.5 * body.length}, 90.0 * deg, body.length,
                              body.width);
    std::vector<ObstacleCollision> cs;
    walls.find_contacts(box, 1e9, 0.0, cs);
    std::printf("%s: %zu contacts:", label, cs.size());
    for (const auto& k : cs) std::printf(" depth %.6g m along (%g, %g);", k.depth, k.normal.x, k.normal.y);
    std::printf("\n");
    ASSERT_EQ(cs.size(), 2u) << label;
    std::sort(cs.begin(), cs.end(), [](const auto& a, const auto& b) { return a.depth > b.depth; });
    EXPECT_NEAR(cs[0].depth, ex, 1e-9 * cell) << label;
    EXPECT_NEAR(cs[0].normal.x, -1.0, 1e-12) << label;
    EXPECT_NEAR(cs[1].depth, ey, 1e-9 * cell) << label;
    EXPECT_NEAR(cs[1].normal.y, -1.0, 1e-12) << label;
}

}  // namespace

TEST(DebrisScale, ACornerInABuildingsInsideCornerTouchesOnlyItsTwoFaces) {
    corner_contacts_by_hand(catalogue_body_def("car", "test"), 10.0, "car on 10 m cells");
    corner_contacts_by_hand(default_body_def(), 0.01, "flume box on 1 cm cells");
}

// A 40 ft container resting on a quay's edge before the water lifts it: 2.2 m of its width
// over the cells north of the edge, whose ground is 0.1 m higher and dry, its centre among
// them (no water there, under its 0.13 m draft). A light box (draft 2 cm) afloat beside it
// is carried into its end at 1 m/s. The container rests on the highest ground under it, so
// the quay under its own footprint never walls it in: the two meet and part with no overlap
// deeper than the tolerance, none jammed, and the centred blow along its axis leaves it
// within 0.1 m of its line and 1 degree of its heading. (From the level less the draft, the
// quay under it was a wall from both sides: the moves out put it 2.2 m south, off the quay;
// in the full-scale demo they turned a container by 35 degrees in one step.)
TEST(DebrisScale, ABodyAtRestIsNotWalledInByTheGroundUnderIt) {
    const auto dir = test::scratch_dir("scale_resting");
    const Grid g{30, 12, 5.0, 5.0, 10.0, 10.0};  // 300 m x 120 m; the quay's edge at y = 60 m
    const auto bed = [](double, double y) { return y > 60.0 ? 0.1 : 0.0; };
    const auto path = test::write_flow(dir + "/quay.nc", g, {0.0, 30.0}, bed, [&](double, double y, double) {
        return test::FlowState{float(y > 60.0 ? 0.0 : 0.1), 0.0f, 0.0f};
    });
    BodyDef container = catalogue_body_def("container_40ft", "test");
    container.x = 150.0;
    container.y = 60.0 + 2.2 - 0.5 * container.width;
    BodyDef light = container;
    light.specific_gravity = 0.02 / container.height;  // draft 2 cm
    light.cd1 = light.cd2 = 0.0;
    light.x = 150.0 - container.length - 2.0;
    light.y = container.y;
    WorldDef def = scaled_to_bodies(default_world_def(), {container, light}, false);
    World w(path, {}, def);
    w.add_body(container, 0);
    w.add_body(light, 0);
    BodyState& thrown = w.states()[1];
    thrown.flags |= flag_released;
    thrown.vx = 1.0;
    w.advance_to(20.0);
    const double tolerance = unresolved_overlap_cells * 10.0;
    for (std::size_t k = 0; k < 2; ++k) {
        const BodyStats& st = w.stats()[k];
        std::printf("body %zu: %ld body contact steps, %ld jammed, %ld unresolved, overlap left %.3g m (bodies) %.3g m (walls); "
                    "at (%.3f, %.3f) m, heading %.3f degrees\n",
                    k, st.body_contacts, st.jams, st.unresolved, st.max_body_overlap, st.max_residual_overlap, w.states()[k].x,
                    w.states()[k].y, w.states()[k].theta / deg);
        EXPECT_GT(st.body_contacts, 0);
        EXPECT_EQ(st.jams, 0);
        EXPECT_EQ(st.unresolved, 0);
        EXPECT_LE(st.max_body_overlap, tolerance);
        EXPECT_LE(st.max_residual_overlap, tolerance);
    }
    EXPECT_LT(std::fabs(w.states()[0].theta), 1.0 * deg);
    EXPECT_NEAR(w.states()[0].y, container.y, 0.1);
}

// A car (1.8 m wide) on 10 m cells, where a quarter cell is wider than half the car:
// driven at 2 m/s into a grid-aligned building face at 20 degrees, turning at 0.3 rad/s
// (so that its corners hit and its passes must move it out of an arc), it bounces and
// slides along the face, never held there.
TEST(DebrisScale, CarSlidesAlongABuildingFaceOnTenMetreCells) {
    BodyDef car = catalogue_body_def("car", "test");
    car.x = 100.0;
    car.y = 85.0;
    car.heading = 20.0 * deg;
    car.cd1 = car.cd2 = 0.0;
    const Grid g{60, 30, 5.0, 5.0, 10.0, 10.0};  // 600 m x 300 m, face at y = 100 m (cells from 105 m blocked)
    slides_along_wall(car, g, 100.0, 2.0, 20.0 * deg, 0.3, 40.0, "car");
}

// The flume's box on 1 cm cells, at the car's speed scaled by Froude (2 m/s / sqrt(250)),
// turning at 0.1 rad/s x sqrt(250).
TEST(DebrisScale, FlumeBoxSlidesAlongAOneCentimetreWall) {
    BodyDef box = default_body_def();
    box.x = 0.2;
    box.y = 0.1;
    box.heading = 20.0 * deg;
    box.cd1 = box.cd2 = 0.0;
    const Grid g{160, 40, 0.005, 0.005, 0.01, 0.01};  // 1.6 m x 0.4 m, face at y = 0.2 m
    slides_along_wall(box, g, 0.2, 2.0 / std::sqrt(250.0), 20.0 * deg, 0.1 * std::sqrt(250.0), 6.0, "flume box");
}

// Land that blocks only where the body would ground: a current of 0.2 m/s (+x) carries the
// paper's box (draft 2.5 cm, floating at level 0) toward a strip of land (ground +1 cm,
// 0.3 m ≤ x ≤ 0.5 m) over which the water stands higher, as at a wave's front: its ground
// rises 3.5 cm above the body's bottom (far past the 5 mm step), so the level at the body's
// centre would call it a wall. Over the land the water is 1.2 d deep in one run (the box
// floats over it: it passes, no collision, in 8 s) and 0.5 d in the other (it would
// ground: it stops against the strip's edge, held there by the current; end-on against
// the edge it is unstable and turns broadside, as a floating box pressed on a wall does).
TEST(DebrisScale, LandBlocksOnlyWhereItsWaterIsShallowerThanTheDraft) {
    const auto dir = test::scratch_dir("scale_land");
    const Grid g{160, 40, -0.295, -0.195, 0.01, 0.01};
    const BodyDef body = test::body_at(0.1, 0.0, 0.0);
    const double d = make_body_params(body, 1000.0).draft;
    for (const double over_land : {1.2, 0.5}) {
        const auto on_land = [](double x) { return x > 0.3 && x < 0.5; };
        const auto bed = [&](double x, double) { return on_land(x) ? 0.01 : -0.06; };
        const auto path = test::write_flow(dir + "/land.nc", g, {0.0, 10.0}, bed, [&](double x, double, double) {
            return test::FlowState{float(on_land(x) ? over_land * d : 0.06), 0.2f, 0.0f};
        });
        World w(path, {});
        w.add_body(body);
        // The body's easternmost point past the strip's edge (x = 0.3 m), most over the run [m].
        double worst = -1.0;
        for (int k = 1; k <= 160; ++k) {
            w.advance_to(0.05 * k);
            const BodyState& s = w.states()[0];
            for (const Vec2& c : Box::make({s.x, s.y}, s.theta, body.length, body.width).corners())
                worst = std::max(worst, c.x - 0.3);
        }
        const BodyState& s = w.states()[0];
        const BodyStats& st = w.stats()[0];
        std::printf(
            "water over the land %.1f d: centre at x = %.4f m, heading %.1f degrees after 8 s, %ld collision steps, %ld "
            "jammed; easternmost point %.3g m past the edge\n",
            over_land, s.x, s.theta / deg, st.collisions, st.jams, worst);
        if (over_land > 1.0) {
            EXPECT_GT(s.x, 0.5 + 0.125) << "floats over the land and past it";
            EXPECT_EQ(st.collisions, 0);
        } else {
            EXPECT_LE(worst, unresolved_overlap_cells * 0.01) << "stops against the land's edge";
            EXPECT_GT(worst, -1e-3);
            EXPECT_GT(st.collisions, 0);
            EXPECT_EQ(st.jams, 0);
        }
    }
}

// A body grounded on a 5 mm ridge under its middle (cells |x| < 2 cm at −1.5 cm, the bed
// elsewhere at −2 cm, level 0: 2 cm of water, under the 2.5 cm draft) in a uniform current
// of 0.1 m/s along its long axis. It rests on the ridge, so its bottom is 5 mm above the
// bed at its ends: each end face is wetted from there to the level, 1.5 cm. By hand:
// ½ ρ (Cd1 + Cd2) U² B × 1.5 cm = 600 × 0.01 × 0.1 × 0.015 = 9.0e-3 N along +x, no torque
// (the wetted height to the local ground would give 2 cm and 1.2e-2 N).
TEST(DebrisScale, GroundedBodyFacesAreWettedFromItsBottom) {
    const auto dir = test::scratch_dir("scale_wetted");
    const Grid g{80, 40, -0.395, -0.195, 0.01, 0.01};
    const auto bed = [](double x, double) { return std::fabs(x) < 0.02 ? -0.015 : -0.02; };
    const auto path = test::write_flow(dir + "/ridge.nc", g, {0.0, 5.0}, bed, [&](double x, double y, double) {
        return test::FlowState{float(-bed(x, y)), 0.1f, 0.0f};
    });
    FlowReader flow(path);
    flow.prepare(0.0);
    const ObstacleMap ground(flow.grid(), flow.description().bed, {});
    const StepDef step = default_step_def();
    const StepContext ctx{flow, ground, step};
    const BodyDef def = test::body_at(0.0, 0.0, 0.0);
    const BodyParams p = make_body_params(def, 1000.0);
    const Box box = Box::make({0.0, 0.0}, 0.0, def.length, def.width);
    const FlowPointAccel centre = flow.sample_accel(0.0, 0.0, 0.0);
    FootprintCache footprint;
    std::vector<GroundPatch> patches;
    ground_patches(flow, flow.grid(), p, box, centre.depth, 0.0, 1000.0, 9.81, footprint, patches);
    const Resting rest = resting_place(ctx, p, box, centre.depth, patches);
    ASSERT_TRUE(rest.on_ground);
    EXPECT_NEAR(rest.bottom, -0.015, 1e-9);
    const Motion at_rest{{0.0, 0.0}, 0.0, {0.0, 0.0}, 0.0, 0.0, {0.0, 0.0}};
    const FluidLoad load =
        fluid_load(flow, p, at_rest, box, centre, p.plan_area * std::min(p.draft, centre.depth), 0.0, 1000.0, rest);
    EXPECT_NEAR(load.force.x, 9.0e-3, 9.0e-5);
    EXPECT_NEAR(load.force.y, 0.0, 1e-12);
    EXPECT_NEAR(load.torque, 0.0, 1e-12);
}
