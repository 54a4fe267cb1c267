// The footprint overlaid on the grid (local contact): for each cell the body covers,
// the overlap area S_ij and the centroid of the overlap, where the depth is sampled.
#pragma once
#include <vector>

#include "common/grid.hpp"
#include "debris/box.hpp"

namespace flotsam::debris {

struct FootprintPatch {
    Vec2 centroid;      // centre of the overlap of the footprint with one cell [m]
    double area = 0.0;  // S_ij [m²]
};

// Appends one patch per grid cell that overlaps `box` (cells outside the grid are
// skipped). The areas sum to L B when the box lies inside the grid.
void footprint_patches(const Box& box, const Grid& grid, std::vector<FootprintPatch>& out);

// The patches of the last box asked for, kept for the next ask: a body that has not moved
// (the same pose, bit for bit: resting on the ground, held by friction, or waiting against a
// quay) reuses them instead of clipping its cells again. The patches depend on the box and
// the grid only, so the answer is the same bits either way.
class FootprintCache {
public:
    const std::vector<FootprintPatch>& patches(const Box& box, const Grid& grid);

private:
    std::vector<FootprintPatch> patches_;
    Box box_;
    Grid grid_;
    bool valid_ = false;
};

}  // namespace flotsam::debris
