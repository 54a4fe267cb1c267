// Shortcuts in the body step that skip work which cannot change the answer: the whole
// cells of a footprint found without their four corner tests. Each is checked here
// against a plain, cell-by-cell reference written from the definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "debris/footprint.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

std::array<Vec2, 4> cell_corners(Vec2 c, double hx, double hy) {
    return {Vec2{c.x + hx, c.y + hy}, Vec2{c.x - hx, c.y + hy}, Vec2{c.x - hx, c.y - hy}, Vec2{c.x + hx, c.y - hy}};
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
