// Shortcuts in the body step that skip work which cannot change the answer: the whole
// cells of a footprint found without their four corner tests, the contact and ground
// scans that rule out a whole range of cells at once (ObstacleMap's block maxima) or test
// only the cells beside the body's part of a row, and the contact patches without the
// depth bound. Each is checked here against a plain reference written from the
// definitions, or against the path it replaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "cases/debris_flows.hpp"
#include "debris/ground_contact.hpp"
#include "debris/flow_reader.hpp"
#include "debris/footprint.hpp"
#include "debris/obstacles.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

std::array<Vec2, 4> cell_corners(Vec2 c, double hx, double hy) {
    return {Vec2{c.x + hx, c.y + hy}, Vec2{c.x - hx, c.y + hy}, Vec2{c.x - hx, c.y - hy}, Vec2{c.x + hx, c.y - hy}};
}

// How deep the box and the cell overlap: the smallest overlap of their projections on
// the four axes that can separate them (x, y and the body's two axes); ≤ 0: apart.
double overlap_depth(const Box& box, Vec2 cell, double hx, double hy) {
    const auto a = box.corners();
    const auto b = cell_corners(cell, hx, hy);
    double depth = std::numeric_limits<double>::infinity();
    for (const Vec2 axis : {Vec2{1, 0}, Vec2{0, 1}, box.axis_long, box.axis_wide}) {
        double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
        for (int k = 0; k < 4; ++k) {
            a0 = std::min(a0, dot(a[k], axis));
            a1 = std::max(a1, dot(a[k], axis));
            b0 = std::min(b0, dot(b[k], axis));
            b1 = std::max(b1, dot(b[k], axis));
        }
        depth = std::min(depth, std::min(a1, b1) - std::max(a0, b0));
    }
    return depth;
}

}  // namespace

// Every cell whose four corners lie inside the footprint is one patch of the whole cell,
// its centre and area to the bit (what the corner tests give), whether the shortcut or the
// tests found it; the areas still sum to L B. Headings along the grid, at 45 degrees, a
// hair off the axes, and random; square and oblong cells.
TEST(StepShortcuts, WholeFootprintCellsAreTheCornerTestsAnswer) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const Grid& g : {Grid{300, 300, 0.005, -2.995, 0.01, 0.01}, Grid{80, 80, 0.02, -3.18, 0.04, 0.04},
                          Grid{300, 150, 0.005, -2.99, 0.01, 0.02}}) {
        std::vector<double> headings = {0.0, M_PI / 2, M_PI / 4, 1e-12, M_PI / 2 - 1e-13, -M_PI};
        for (int k = 0; k < 200; ++k) headings.push_back(2.0 * M_PI * unit(rng));
        for (std::size_t k = 0; k < headings.size(); ++k) {
            // The first poses with edges on cell edges (1.37 m: as the sliver test), then anywhere.
            const Vec2 centre = k < 6 ? Vec2{1.37, -2.15} : Vec2{1.0 + unit(rng), -2.0 + unit(rng)};
            const Box box = Box::make(centre, headings[k], 0.25, 0.1);
            std::vector<FootprintPatch> patches;
            footprint_patches(box, g, patches);
            double area = 0.0;
            for (const auto& p : patches) area += p.area;
            EXPECT_NEAR(area, 0.025, 1e-12) << k;
            const double hx = 0.5 * g.dx, hy = 0.5 * g.dy;
            int whole = 0;
            for (int j = 0; j < g.ny; ++j)
                for (int i = 0; i < g.nx; ++i) {
                    const Vec2 c{g.x(i), g.y(j)};
                    if (std::fabs(c.x - centre.x) > 0.2 || std::fabs(c.y - centre.y) > 0.2) continue;
                    const auto corners = cell_corners(c, hx, hy);
                    if (!std::all_of(corners.begin(), corners.end(), [&](Vec2 p) { return box.contains(p); })) continue;
                    ++whole;
                    const int found = int(std::count_if(patches.begin(), patches.end(), [&](const FootprintPatch& p) {
                        return p.centroid.x == c.x && p.centroid.y == c.y && p.area == g.dx * g.dy;
                    }));
                    EXPECT_EQ(found, 1) << "heading " << headings[k] << " cell " << i << ", " << j;
                }
            if (g.dx == 0.01 && g.dy == 0.01 && k >= 6) {
                EXPECT_GT(whole, 150) << k;  // most of the 250 cells
            }
        }
    }
}

// The contact scan with the block maxima against every blocked cell checked one by one:
// a contact for each blocked cell on a wall's edge (a side open) that the body reaches into
// (by more than 1 nm; a cell inside a wall has no side to push out through and gives
// none, nor one the body reaches only from a blocked neighbour's side, as at a wall's
// inside corner), none for a cell it stays clear of (by 1 nm); the ground test against a plain scan of the cells
// within a cell of the body's bounding box. The poses: a corner of the body 2 mm into a
// building's corner cell, 0.5 mm short of it, a body across the grid's edge and one just
// inside it, one whose cells reach a block that holds a wall but not the wall itself,
// and many at random over the grid (most of them far from anything: the shortcut).
TEST(StepShortcuts, ContactAndGroundScansGiveTheCellByCellAnswer) {
    const Grid g{120, 120, -0.595, -0.595, 0.01, 0.01};
    const double hx = 0.5 * g.dx, hy = 0.5 * g.dy;
    std::vector<float> bed(g.size(), 0.0f);
    std::vector<std::uint8_t> building(g.size(), 0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double x = g.x(i), y = g.y(j);
            if (x > 0.1 && x < 0.3 && y > 0.1 && y < 0.3) building[g.index(i, j)] = 1;       // a building, corner near (0.1, 0.1)
            if (x > -0.4 && x < -0.35 && y > -0.2 && y < 0.4) bed[g.index(i, j)] = 0.03f;  // a quay wall 3 cm high
            if (x > -0.2 && x < 0.0 && y < -0.3) bed[g.index(i, j)] = 0.002f;              // a low step, 2 mm
            if (x > 0.35 && y > 0.2) bed[g.index(i, j)] = float(0.004 * std::sin(40.0 * x + 70.0 * y));  // rough ground
        }
    const ObstacleMap map(g, bed, building);
    const double bottom = 0.0, step = 0.005;  // the quay blocks, the low step does not
    const auto blocked = [&](int i, int j) {
        if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) return true;
        return building[g.index(i, j)] != 0 || double(bed[g.index(i, j)]) > bottom + step;
    };
    const auto check = [&](const Box& box, const std::string& what) {
        int deep = 0, touching = 0;
        for (int j = -20; j < g.ny + 20; ++j)  // outside the grid too: the flume walls
            for (int i = -20; i < g.nx + 20; ++i) {
                if (!blocked(i, j)) continue;
                const Vec2 c{g.x0 + i * g.dx, g.y0 + j * g.dy};
                const double d = overlap_depth(box, c, hx, hy);
                const bool edge = !blocked(i + 1, j) || !blocked(i - 1, j) || !blocked(i, j + 1) || !blocked(i, j - 1);
                // How far the body reaches past each face (out through it: +x, −x, +y, −y),
                // the least through a face it shares with another blocked cell and through an
                // open one: a cell the body reaches less than half a cell through a shared face
                // and more than half a cell from every open face is held by its neighbour.
                double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
                for (const Vec2& p : box.corners()) {
                    lo_x = std::min(lo_x, p.x), hi_x = std::max(hi_x, p.x);
                    lo_y = std::min(lo_y, p.y), hi_y = std::max(hi_y, p.y);
                }
                const double past[4] = {c.x + hx - lo_x, hi_x - (c.x - hx), c.y + hy - lo_y, hi_y - (c.y - hy)};
                const bool shut[4] = {blocked(i + 1, j), blocked(i - 1, j), blocked(i, j + 1), blocked(i, j - 1)};
                double via_wall = 1e300, via_open = 1e300;
                for (int f = 0; f < 4; ++f) {
                    double& least = shut[f] ? via_wall : via_open;
                    least = std::min(least, past[f]);
                }
                const bool held_by_neighbour = via_wall < hx && via_open > hx;
                deep += d > 1e-9 && edge && !held_by_neighbour ? 1 : 0;
                touching += d > -1e-9 ? 1 : 0;
            }
        // The highest open ground under the body: cells it reaches into by more than 1 µm.
        double highest = -std::numeric_limits<double>::infinity();
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i)
                if (!building[g.index(i, j)] && overlap_depth(box, Vec2{g.x0 + i * g.dx, g.y0 + j * g.dy}, hx, hy) > 1e-6)
                    highest = std::max(highest, double(bed[g.index(i, j)]));
        EXPECT_EQ(map.highest_ground(box, 1e-6), highest) << what;
        std::vector<ObstacleCollision> contacts;
        map.find_contacts(box, bottom, step, contacts);
        EXPECT_GE(int(contacts.size()), deep) << what;
        EXPECT_LE(int(contacts.size()), touching) << what;
        // Ground above a level within a cell of the bounding box, buildings left out.
        for (const double level : {0.001, 0.01, 0.05}) {
            const int i0 = int(std::floor((box.centre.x - box.extent_x() - g.x0) / g.dx + 0.5)) - 1;
            const int i1 = int(std::floor((box.centre.x + box.extent_x() - g.x0) / g.dx + 0.5)) + 1;
            const int j0 = int(std::floor((box.centre.y - box.extent_y() - g.y0) / g.dy + 0.5)) - 1;
            const int j1 = int(std::floor((box.centre.y + box.extent_y() - g.y0) / g.dy + 0.5)) + 1;
            bool above = false;
            for (int j = std::max(j0, 0); j <= std::min(j1, g.ny - 1); ++j)
                for (int i = std::max(i0, 0); i <= std::min(i1, g.nx - 1); ++i)
                    above = above || (!building[g.index(i, j)] && double(bed[g.index(i, j)]) > level);
            EXPECT_EQ(map.ground_above(box, level), above) << what << " level " << level;
        }
        return int(contacts.size());
    };
    // The body's (+long, +wide) corner at a point, heading 30 degrees.
    const double heading = M_PI / 6;
    const auto corner_at = [&](Vec2 p) {
        const Box at_origin = Box::make({0.0, 0.0}, heading, 0.25, 0.1);
        return Box::make(p - at_origin.corners()[0], heading, 0.25, 0.1);
    };
    // Cell edges lie on whole centimetres: the building's south-west corner is (0.1, 0.1)
    // and the grid's east edge x = 0.6 m.
    EXPECT_EQ(check(corner_at({0.102, 0.102}), "corner 2 mm into the building's corner cell"), 1);
    EXPECT_EQ(check(corner_at({0.0995, 0.0995}), "corner 0.5 mm short of the building"), 0);
    EXPECT_GE(check(Box::make({0.49, -0.4}, 0.0, 0.25, 0.1), "across the grid's edge"), 1);
    EXPECT_EQ(check(Box::make({0.474, -0.4}, 0.0, 0.25, 0.1), "just inside the grid's edge"), 0);
    // Blocks of 4 cells from the grid's west edge: cells 68..71 share one, and the
    // building begins at cell 70 (x = 0.105 m). A body ending in cell 69 reaches that
    // block, not the building.
    EXPECT_EQ(check(Box::make({-0.03, 0.2}, 0.0, 0.25, 0.1), "in the building's block, clear of it"), 0);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> x(-0.6, 0.6), turn(-M_PI, M_PI);
    int with_contact = 0;
    for (int k = 0; k < 2000; ++k)
        with_contact += check(Box::make({x(rng), x(rng)}, turn(rng), 0.25, 0.1), "random pose " + std::to_string(k)) > 0;
    EXPECT_GT(with_contact, 200);   // the walls and the edges are met often enough
    EXPECT_LT(with_contact, 1800);  // and the open ground as often
}

// The contact patches without the depth bound (the step's choice for a body grounded at
// its last step) are those with it, bit for bit: where the bound skips, every patch is
// as deep as the draft anyway. Water 3 cm deep over a bed that rises 10 cm per metre
// east: afloat in the west, grounded in the east, partly grounded between.
TEST(StepShortcuts, ContactPatchesWithoutTheDepthBoundAreTheSame) {
    const auto dir = test::scratch_dir("shortcuts_depth_bound");
    const Grid g{160, 80, -0.795, -0.395, 0.01, 0.01};
    const auto bed = [](double x, double) { return 0.1 * x; };
    const auto path = test::write_flow(dir + "/slope.nc", g, {0.0, 1.0}, bed, [&](double x, double y, double t) {
        const double h = std::max(0.03 + 0.01 * t - bed(x, y), 0.0);
        return test::FlowState{float(h), 0.1f, 0.0f};
    });
    FlowReader flow(path);
    flow.prepare(0.5);
    BodyDef def = default_body_def();
    def.contact = ContactModel::local;
    const BodyParams p = make_body_params(def, 1000.0);
    int skipped = 0, grounded = 0;
    std::size_t rows_left_out = 0;
    for (double x = -0.5; x <= 0.5; x += 0.0137)
        for (const double heading : {0.0, 0.4, 1.3}) {
            const Box box = Box::make({x, 0.01}, heading, def.length, def.width);
            FootprintCache cache_with, cache_without;
            std::vector<GroundPatch> with, without;
            const double centre_depth = flow.depth(x, 0.01, 0.5);
            ground_patches(flow, g, p, box, centre_depth, 0.5, 1000.0, 9.81, cache_with, with, true);
            ground_patches(flow, g, p, box, centre_depth, 0.5, 1000.0, 9.81, cache_without, without, false);
            ASSERT_EQ(with.size(), without.size()) << x << " " << heading;
            for (std::size_t k = 0; k < with.size(); ++k) {
                EXPECT_EQ(with[k].r.x, without[k].r.x);
                EXPECT_EQ(with[k].r.y, without[k].r.y);
                EXPECT_EQ(with[k].area, without[k].area);
                EXPECT_EQ(with[k].capacity, without[k].capacity);
            }
            skipped += with.empty() && flow.min_depth(flow.cells_for(x - 0.14, x + 0.14, -0.13, 0.15)) >= p.draft;
            grounded += !with.empty();
            rows_left_out += with.empty() ? 0 : cache_with.rows_left_out();
            EXPECT_EQ(cache_without.rows_left_out(), 0u);
        }
    EXPECT_GT(skipped, 10);   // the bound does skip in the west
    EXPECT_GT(grounded, 10);  // and there are contacts in the east
    // Turned, a partly grounded body's rows of cells reach different depths: those that
    // cannot touch are neither clipped nor sampled, and the patches are the same.
    EXPECT_GT(rows_left_out, 30u);
}
