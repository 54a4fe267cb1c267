// Ground finer than the flow (debris::Ground, FlowReader::set_ground): the bodies stand
// on a finer scene's ground while the water comes from a coarser flow. The depth is the
// flow's level over that ground; a pit the flow's cell average hides floats a body, and
// a pit inland of the flow's shoreline stays dry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "cases/debris_flows.hpp"
#include "debris/footprint.hpp"
#include "debris/world.hpp"
#include "formats/scene.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

// The flow: 4 cm cells over [0, 0.24] x [0, 0.16] m. Water 3 cm deep (level 0.03 m) on a
// flat bed at 0 west of x = 0.12 m; a quay at z = 0.05 m from there on, dry.
const Grid coarse{6, 4, 0.02, 0.02, 0.04, 0.04};
constexpr double level = 0.03, quay = 0.05, speed = 0.2;

double coarse_bed(double x, double) { return x < 0.12 ? 0.0 : quay; }

std::string quay_flow(const std::string& path) {
    return test::write_flow(path, coarse, {0.0, 10.0}, coarse_bed, [](double x, double y, double) {
        const double h = std::max(level - coarse_bed(x, y), 0.0);
        return test::FlowState{float(h), h > 0 ? float(speed) : 0.0f, 0.0f};
    });
}

// The ground: 1 cm cells over the same area. Flat at 0 in the water but for a pit
// (−0.01 m) and a bump (0.02 m); the quay at 0.06 m but for a street at 0 one cell
// wide (x in [0.13, 0.14] m) and an inland pit (−0.1 m) at x in [0.19, 0.20] m.
const Grid fine{24, 16, 0.005, 0.005, 0.01, 0.01};
double fine_bed(double x, double y) {
    if (x < 0.12) {
        if (std::fabs(x - 0.055) < 0.004 && std::fabs(y - 0.075) < 0.004) return -0.01;  // the pit
        if (std::fabs(x - 0.085) < 0.004 && std::fabs(y - 0.075) < 0.004) return 0.02;   // the bump
        return 0.0;
    }
    if (std::fabs(x - 0.135) < 0.004) return 0.0;   // the street
    if (std::fabs(x - 0.195) < 0.004) return -0.1;  // the inland pit
    return 0.06;
}
std::vector<float> on_grid(const Grid& g, double (*bed)(double, double)) {
    std::vector<float> z(g.size());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) z[g.index(i, j)] = float(bed(g.x(i), g.y(j)));
    return z;
}

}  // namespace

// Each number by hand: depth = level over the ground cell holding the point, where the
// point's bilinear stencil has a wet node.
TEST(FineGround, DepthIsTheFlowsLevelOverTheFinerGround) {
    const auto dir = test::scratch_dir("fine_ground_depth");
    FlowReader r(quay_flow(dir + "/flow.nc"));
    r.prepare(0.0);
    // The flow's own depth, for comparison: 3 cm everywhere in the water.
    EXPECT_NEAR(r.depth(0.055, 0.075, 0.0), level, 1e-7);
    r.set_ground(fine, on_grid(fine, fine_bed));
    r.prepare(5.0);
    EXPECT_NEAR(r.depth(0.055, 0.075, 5.0), 0.04, 1e-7);  // the pit: 0.03 − (−0.01)
    EXPECT_NEAR(r.depth(0.085, 0.075, 5.0), 0.01, 1e-7);  // the bump: 0.03 − 0.02
    EXPECT_NEAR(r.depth(0.035, 0.035, 5.0), level, 1e-7);
    // The street through the quay: its stencil has the wet nodes at x = 0.10 m, so the
    // level reaches it (the flow's own depth there is the bilinear 3 cm x 1/8 = 3.75 mm).
    EXPECT_NEAR(r.depth(0.135, 0.075, 5.0), level, 1e-7);
    EXPECT_NEAR(r.sample(0.135, 0.075, 5.0).u, speed, 1e-6);  // the flow's velocity
    EXPECT_EQ(r.depth(0.125, 0.075, 5.0), 0.0);               // quay ground above the level
    // Inland of the flow's shoreline (every node of the stencil dry) a pit stays dry.
    EXPECT_EQ(r.depth(0.195, 0.075, 5.0), 0.0);
    EXPECT_EQ(r.sample(0.195, 0.075, 5.0).depth, 0.0);
    EXPECT_EQ(r.sample_accel(0.195, 0.075, 5.0).depth, 0.0);
    EXPECT_NEAR(r.sample_accel(0.055, 0.075, 5.0).depth, 0.04, 1e-7);
}

// Between ground cell centres the depth is bilinear, as a flow stored on the ground's
// grid is sampled: halfway from the pit's centre to its east neighbour's, (0.04 + 0.03) / 2.
TEST(FineGround, DepthIsBilinearBetweenGroundCellCentres) {
    const auto dir = test::scratch_dir("fine_ground_bilinear");
    FlowReader r(quay_flow(dir + "/flow.nc"));
    r.set_ground(fine, on_grid(fine, fine_bed));
    r.prepare(5.0);
    EXPECT_NEAR(r.depth(0.060, 0.075, 5.0), 0.035, 1e-7);
    EXPECT_NEAR(r.depth(0.0575, 0.0775, 5.0), 0.75 * 0.75 * 0.04 + (1 - 0.75 * 0.75) * 0.03, 1e-7);
    // Half a cell from the street's centre onto the quay (0.06 m, above the level): half
    // the street's depth.
    EXPECT_NEAR(r.depth(0.140, 0.075, 5.0), 0.5 * level, 1e-7);
}

// The depth over the ground is interpolated in time frame by frame, as a flow stored on
// the ground's grid would be: the bump (z = 0.02 m) is dry at t = 0 (level 0.01 m) and
// under 1 cm at t = 10 s (level 0.03 m), so at t = 5 s it has half of that, 5 mm, though
// the level interpolated to 5 s (0.02 m) only reaches its top. min_depth bounds it.
TEST(FineGround, DepthOverTheGroundIsInterpolatedBetweenFramesLikeAStoredFlow) {
    const auto dir = test::scratch_dir("fine_ground_time");
    const std::string path = test::write_flow(
        dir + "/flow.nc", coarse, {0.0, 10.0}, [](double, double) { return 0.0; },
        [](double, double, double t) {
            return test::FlowState{float(0.01 + 0.002 * t), 0.0f, 0.0f};
        });
    FlowReader r(path);
    r.set_ground(fine, on_grid(fine, fine_bed));
    r.prepare(5.0);
    EXPECT_NEAR(r.depth(0.085, 0.075, 0.0), 0.0, 1e-7);
    EXPECT_NEAR(r.depth(0.085, 0.075, 10.0), 0.01, 1e-7);
    EXPECT_NEAR(r.depth(0.085, 0.075, 5.0), 0.005, 1e-7);  // the bump
    EXPECT_NEAR(r.depth(0.035, 0.035, 5.0), 0.02, 1e-7);   // flat ground
    EXPECT_NEAR(r.depth(0.055, 0.075, 5.0), 0.03, 1e-7);   // the pit
    // Halfway between the bump's centre and its flat neighbour's: at 2.5 s (0.0025 + 0.015) / 2,
    // at 7.5 s (0.0075 + 0.025) / 2.
    EXPECT_NEAR(r.depth(0.09, 0.075, 2.5), 0.00875, 1e-7);
    EXPECT_NEAR(r.depth(0.09, 0.075, 7.5), 0.01625, 1e-7);
    const CellWindow all{0, coarse.nx, 0, coarse.ny};
    EXPECT_NEAR(r.min_depth(all), 0.0, 1e-12);  // the bump at t = 0
    const CellWindow west{0, 2, 0, 3};          // x < 0.08: flat and the pit
    EXPECT_NEAR(r.min_depth(west), 0.01, 1e-7);
}

// The flow's own bed as the ground gives the flow's own depth everywhere, shorelines
// included (the stencil of a ground node is that node alone), to float rounding.
TEST(FineGround, TheFlowsOwnBedAsGroundChangesNothing) {
    const auto dir = test::scratch_dir("fine_ground_own");
    const std::string path = quay_flow(dir + "/flow.nc");
    FlowReader plain(path), own(path);
    own.set_ground(coarse, on_grid(coarse, coarse_bed));
    plain.prepare(3.0);
    own.prepare(3.0);
    for (double x = 0.02; x <= 0.22; x += 0.0037)
        for (double y = 0.02; y <= 0.14; y += 0.0111) {
            EXPECT_NEAR(own.depth(x, y, 3.0), plain.depth(x, y, 3.0), 1e-9) << x << ", " << y;
            const FlowPoint a = own.sample(x, y, 3.0), b = plain.sample(x, y, 3.0);
            EXPECT_EQ(a.u, b.u);
            EXPECT_EQ(a.v, b.v);
        }
}

// A body whose draft (2.5 cm) the flow's 4 cm cell average does not reach floats where
// the finer ground shows the water deeper. Still water: it starts (its centre is deeper
// than its draft) and stays where it is.
TEST(FineGround, APitTheCellAverageHidesFloatsABody) {
    const auto dir = test::scratch_dir("fine_ground_body");
    const Grid flow_grid{10, 10, 0.02, 0.02, 0.04, 0.04};
    const std::string flow = test::write_flow(
        dir + "/still.nc", flow_grid, {0.0, 10.0}, [](double, double) { return -0.02; },
        [](double, double, double) {
            return test::FlowState{0.02f, 0.0f, 0.0f};
        });
    Scene ground;
    ground.grid = Grid{40, 40, 0.005, 0.005, 0.01, 0.01};
    ground.z.assign(ground.grid.size(), -0.02);
    for (int j = 0; j < ground.grid.ny; ++j)
        for (int i = 0; i < ground.grid.nx; ++i)
            if (std::fabs(ground.grid.x(i) - 0.2) < 0.2 && std::fabs(ground.grid.y(j) - 0.2) < 0.1)
                ground.z[ground.grid.index(i, j)] = -0.04;  // a 40 x 20 cm pit 4 cm deep
    ground.path = dir + "/ground.nc";
    const std::vector<BodyDef> bodies = {test::body_at(0.2, 0.2, 0.0)};
    World coarse_only = make_world(flow, nullptr, bodies, default_world_def());
    World on_fine = make_world(flow, nullptr, bodies, default_world_def(), &ground);
    coarse_only.advance_to(2.0);
    on_fine.advance_to(2.0);
    EXPECT_NEAR(on_fine.flow().depth(0.2, 0.2, 2.0), 0.04, 1e-7);
    EXPECT_NEAR(coarse_only.flow().depth(0.2, 0.2, 2.0), 0.02, 1e-7);
    EXPECT_FALSE(coarse_only.states()[0].flags & flag_released);  // 2 cm < its draft
    EXPECT_TRUE(on_fine.states()[0].flags & flag_released);       // 4 cm > its draft
    const BodyState& s = on_fine.states()[0];
    EXPECT_LT(std::hypot(s.x - 0.2, s.y - 0.2), 1e-9);
    EXPECT_LT(std::fabs(s.theta), 1e-9);
    EXPECT_EQ(on_fine.obstacles().grid().dx, 0.01);
}

// What a ground must be, with errors that name the files.
TEST(FineGround, GroundMustCoverTheFlowWithFinerCellsAndKeepBodiesOffItsBuildings) {
    const auto dir = test::scratch_dir("fine_ground_errors");
    const std::string flow = quay_flow(dir + "/flow.nc");
    const std::vector<BodyDef> bodies = {test::body_at(0.06, 0.08, 0.0)};
    auto scene = [&](const Grid& g) {
        Scene s;
        s.grid = g;
        s.z.assign(g.size(), 0.0);
        s.path = dir + "/ground.nc";
        return s;
    };
    const Scene coarser = scene(Grid{3, 2, 0.04, 0.04, 0.08, 0.08});
    std::string msg = test::error_of([&] { make_world(flow, nullptr, bodies, default_world_def(), &coarser); });
    EXPECT_NE(msg.find("ground.nc"), std::string::npos) << msg;
    EXPECT_NE(msg.find("coarser than"), std::string::npos) << msg;
    const Scene half = scene(Grid{12, 16, 0.005, 0.005, 0.01, 0.01});
    msg = test::error_of([&] { make_world(flow, nullptr, bodies, default_world_def(), &half); });
    EXPECT_NE(msg.find("does not cover the grid of flow"), std::string::npos) << msg;
    EXPECT_NE(msg.find("flow.nc"), std::string::npos) << msg;
    Scene built = scene(fine);
    built.building.assign(fine.size(), 0);
    built.building[fine.index(fine.cell_i(0.06), fine.cell_j(0.08))] = 1;  // one 1 cm building cell under its centre
    msg = test::error_of([&] { make_world(flow, nullptr, bodies, default_world_def(), &built); });
    EXPECT_NE(msg.find("inside a building of scene"), std::string::npos) << msg;
    EXPECT_NE(msg.find("ground.nc"), std::string::npos) << msg;
}

// A body whose edges lie on cell edges (the paper's box at x = 1.37 m, heading 0, on a
// 1 cm grid from 0.005 m: edges at 1.245 and 1.495 m) clips to slivers of round-off area
// along them. Their centroids are noise (found 0.3 m outside the body, sampling dry
// ground there and holding it); none may remain, every centroid lies in the body, and
// the areas still sum to L B.
TEST(FineGround, NoSliverPatchesWhereBodyEdgesLieOnCellEdges) {
    const Grid g{300, 300, 0.005, -2.995, 0.01, 0.01};
    for (double heading : {0.0, M_PI / 2, M_PI, -M_PI / 2}) {
        const Box box = Box::make({1.37, -2.15}, heading, 0.25, 0.1);
        std::vector<FootprintPatch> patches;
        footprint_patches(box, g, patches);
        double area = 0.0;
        for (const auto& p : patches) {
            area += p.area;
            EXPECT_GT(p.area, 1e-9 * g.dx * g.dy) << heading;
            EXPECT_LE(std::fabs(p.centroid.x - 1.37), 0.125 + 1e-9) << heading;
            EXPECT_LE(std::fabs(p.centroid.y + 2.15), 0.125 + 1e-9) << heading;
        }
        EXPECT_NEAR(area, 0.025, 1e-12) << heading;
    }
}

// A corner a fraction of a micrometre past a cell edge cuts a triangle of legs ~1e-7 m
// from that cell: above the sliver threshold (1e-9 of a cell) from legs of about 5e-7 m.
// Its centroid, by the shoelace sums in map coordinates (x ≈ 4.3 m here), was found up
// to 1.5 cm away: a cell and a half, outside the body, where the depth was then sampled.
// Every patch centroid must lie in the body (to 1e-9 m).
// The poses: random headings, each moved so that its westmost corner lies 0–1e-6 m past
// a cell edge, at map coordinates of the real layout's port.
TEST(FineGround, EveryPatchCentroidLiesInTheBody) {
    const Grid g{900, 400, -0.995, -3.995, 0.01, 0.01};
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> heading(-M_PI, M_PI), past(0.0, 1e-6), at(0.0, 1.0);
    int slivers = 0;
    for (int k = 0; k < 4000; ++k) {
        Box box = Box::make({4.3 + 0.3 * at(rng), -1.86 + 0.3 * at(rng)}, heading(rng), 0.25, 0.1);
        double west = 1e300;
        for (const Vec2& c : box.corners()) west = std::min(west, c.x);
        const double edge = g.x0 - 0.5 * g.dx + std::ceil((west - (g.x0 - 0.5 * g.dx)) / g.dx) * g.dx;  // the cell edge east of it
        box = Box::make({box.centre.x + (edge - west) - past(rng), box.centre.y}, std::atan2(box.axis_long.y, box.axis_long.x),
                        0.25, 0.1);
        std::vector<FootprintPatch> patches;
        footprint_patches(box, g, patches);
        for (const auto& p : patches) {
            slivers += p.area < 1e-6 * g.dx * g.dy;
            const Vec2 r = p.centroid - box.centre;
            ASSERT_LE(std::fabs(dot(r, box.axis_long)), box.half_length + 1e-9) << k << " area " << p.area;
            ASSERT_LE(std::fabs(dot(r, box.axis_wide)), box.half_width + 1e-9) << k << " area " << p.area;
        }
    }
    EXPECT_GT(slivers, 100);  // the poses do make such triangles
}

// A body that has not moved reuses its patches (FootprintCache); any change of pose, even
// the last bit of the heading, or of the grid, clips again. Every answer is the patches a
// fresh clip gives, bit for bit.
TEST(FineGround, FootprintCacheGivesTheFreshClipForEveryPose) {
    const Grid fine{300, 300, 0.005, -2.995, 0.01, 0.01}, coarse{75, 75, 0.02, -2.98, 0.04, 0.04};
    const auto fresh = [](const Box& box, const Grid& g) {
        std::vector<FootprintPatch> p;
        footprint_patches(box, g, p);
        return p;
    };
    const auto same = [](const std::vector<FootprintPatch>& a, const std::vector<FootprintPatch>& b) {
        if (a.size() != b.size()) return false;
        for (std::size_t k = 0; k < a.size(); ++k)
            if (a[k].area != b[k].area || a[k].centroid.x != b[k].centroid.x || a[k].centroid.y != b[k].centroid.y) return false;
        return true;
    };
    const double theta = 0.3;
    const Box boxes[] = {Box::make({1.37, -2.15}, theta, 0.25, 0.1), Box::make({1.37, -2.15}, theta, 0.25, 0.1),
                         Box::make({1.37, -2.15}, std::nextafter(theta, 1.0), 0.25, 0.1),
                         Box::make({1.3712, -2.15}, theta, 0.25, 0.1), Box::make({1.3712, -2.15}, theta, 0.25, 0.1)};
    FootprintCache cache;
    for (const Box& box : boxes) EXPECT_TRUE(same(cache.patches(box, fine), fresh(box, fine)));
    EXPECT_TRUE(same(cache.patches(boxes[0], coarse), fresh(boxes[0], coarse)));
    EXPECT_TRUE(same(cache.patches(boxes[0], fine), fresh(boxes[0], fine)));
    EXPECT_FALSE(same(fresh(boxes[0], fine), fresh(boxes[3], fine)));  // the moves above do change the patches
}

// The depth over the ground, worked out here from its definition (at each ground centre:
// the flow's level h + z bilinear over the wet nodes of the flow stencil, weights
// renormalised, less the ground; then linear in time and bilinear between the ground's
// centres), against the reader on the whole grid and on two windows: one touching the
// grid's west, south and north edges, one in the east with its west edge inside the
// grid. Points run up to the windows' edges, over the wetting front and the dry quay.
TEST(FineGround, DepthOverTheGroundFollowsItsDefinitionOnEveryWindow) {
    const auto dir = test::scratch_dir("fine_ground_definition");
    const std::string path = test::write_flow(dir + "/flow.nc", coarse, {0.0, 10.0}, coarse_bed, [](double x, double y, double t) {
        // The level rises in time and toward the north; the quay (z = 0.05 m) wets late.
        const double h = std::max(level + 0.002 * t + 0.05 * y - coarse_bed(x, y), 0.0);
        return test::FlowState{float(h), float(speed), 0.0f};
    });
    const std::vector<float> ground_z = on_grid(fine, fine_bed);
    const double t = 6.5, a = t / 10.0;
    // The ground centre's depth in frame `frame` by the definition.
    const auto depth_at_centre = [&](const FlowReader& r, int frame, int gi, int gj) {
        const double frame_t = frame == 0 ? 0.0 : 10.0;
        const double fx = (fine.x(gi) - coarse.x0) / coarse.dx, fy = (fine.y(gj) - coarse.y0) / coarse.dy;
        const int i = std::clamp(int(std::floor(fx)), 0, coarse.nx - 2), j = std::clamp(int(std::floor(fy)), 0, coarse.ny - 2);
        const double wx = std::clamp(fx - i, 0.0, 1.0), wy = std::clamp(fy - j, 0.0, 1.0);
        double wet = 0.0, level_sum = 0.0;
        for (int c = 0; c < 4; ++c) {
            const int ni = i + (c & 1), nj = j + (c >> 1);
            const double x = coarse.x(ni), y = coarse.y(nj);
            const double h = double(float(std::max(level + 0.002 * frame_t + 0.05 * y - coarse_bed(x, y), 0.0)));
            if (!(h > r.description().dry_depth)) continue;
            const double w = ((c & 1) ? wx : 1.0 - wx) * ((c >> 1) ? wy : 1.0 - wy);
            wet += w;
            level_sum += w * (h + double(float(coarse_bed(x, y))));
        }
        return wet > 0.0 ? double(float(std::max(0.0, level_sum / wet - double(ground_z[fine.index(gi, gj)])))) : 0.0;
    };
    const CellWindow whole{0, coarse.nx, 0, coarse.ny}, west{0, 3, 0, 4}, east{2, 6, 1, 4};
    int wet_points = 0, dry_points = 0;
    for (const CellWindow& w : {whole, west, east}) {
        FlowReader r(path);
        r.set_ground(fine, ground_z);
        r.set_window(w);
        r.prepare(t);
        std::vector<Vec2> points;
        // From the window's first node to its last, both included where the window ends
        // at the grid's edge; one ground cell in from a node inside the grid (a point
        // nearer takes a ground centre whose flow stencil lies outside the window; the
        // world keeps region_margin flow cells from there).
        const auto inner = [](int edge, int grid_edge) { return edge == grid_edge ? 0.0 : fine.dx; };
        const double x0 = coarse.x(w.i0) + inner(w.i0, 0), x1 = coarse.x(w.i1 - 1) - inner(w.i1, coarse.nx);
        const double y0 = coarse.y(w.j0) + inner(w.j0, 0), y1 = coarse.y(w.j1 - 1) - inner(w.j1, coarse.ny);
        for (double x = x0; x <= x1 + 1e-12; x += 0.0031)
            for (double y = y0; y <= y1 + 1e-12; y += 0.0047) points.push_back({x, y});
        for (const Vec2& p : points) {
            const double fx = std::clamp((p.x - fine.x0) / fine.dx, 0.0, double(fine.nx - 1)),
                         fy = std::clamp((p.y - fine.y0) / fine.dy, 0.0, double(fine.ny - 1));
            const int gi = std::min(int(std::floor(fx)), fine.nx - 2), gj = std::min(int(std::floor(fy)), fine.ny - 2);
            const double wx = fx - gi, wy = fy - gj;
            double expected = 0.0;
            for (int c = 0; c < 4; ++c) {
                const int ci = gi + (c & 1), cj = gj + (c >> 1);
                const double in_time = (1.0 - a) * depth_at_centre(r, 0, ci, cj) + a * depth_at_centre(r, 1, ci, cj);
                expected += ((c & 1) ? wx : 1.0 - wx) * ((c >> 1) ? wy : 1.0 - wy) * in_time;
            }
            const double got = r.depth(p.x, p.y, t);
            EXPECT_NEAR(got, expected, 1e-12) << p.x << ", " << p.y << " on window " << w.i0 << ".." << w.i1;
            (expected > 0.0 ? wet_points : dry_points) += 1;
        }
        // Many points at once (more than one block of the batched sampler) give the bits
        // of one at a time.
        std::vector<double> together(points.size());
        r.depth(points.data(), int(points.size()), r.at_time(t), together.data());
        for (std::size_t k = 0; k < points.size(); ++k) EXPECT_EQ(together[k], r.depth(points[k].x, points[k].y, t)) << k;
        EXPECT_GT(points.size(), 64u * 2);
    }
    EXPECT_GT(wet_points, 100);
    EXPECT_GT(dry_points, 100);
}
